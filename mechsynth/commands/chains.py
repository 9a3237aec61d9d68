"""CLI commands ``chains`` and ``mechanisms`` (type synthesis).

Example
-------
>>> from mechsynth.cli import main
>>> main(["chains", "--dof", "1", "--links", "8", "--count", "--workers", "1"])
{"count": 16, "by_code": {"440/0": 9, "521/0": 5, "602/0": 2}}
0
"""

from __future__ import annotations

import argparse

from .._argtypes import whole, workers
from .._output import FORMATS, nothing_found, write_count, write_rows


def _add_selection(p) -> None:
    p.add_argument("--dof", type=whole, help="mobility W (0 = trusses); default: the code's W")
    p.add_argument("--links", type=whole, help="number of links n (frame included)")
    p.add_argument("--v", help="multiple-joint count or range A..B (default 0: simple joints; with --code its own)")
    p.add_argument("--code", help="only this code, e.g. 6301/0 or 620/0-1")
    p.add_argument("--require", action="append", default=[], metavar="I=N|I=A..B|I=A..",
                   help="design constraint on n_I, the links with I joints (repeatable)")
    p.add_argument("--cranks", action="append", default=[], metavar="I=C",
                   help="required sub-structure: a link with I joints carrying ≥ C cranks (repeatable)")
    p.add_argument("--rigid-subchains", action="store_true", default=None,
                   help="allow rigid sub-chains, W(S) ≥ 0 (default only for W = 0)")
    p.add_argument("--fractionated", action=argparse.BooleanOptionalAction, default=True,
                   help="keep chains split by one link or joint (default: keep)")
    p.add_argument("--planar-only", action="store_true", help="keep only chains with planar graphs")
    p.add_argument("--count", action="store_true", help='print {"count": N, "by_code": {...}} only')
    p.add_argument("--workers", type=workers, help="processes, at most the number of cores (default: all cores)")
    p.add_argument("--format", choices=FORMATS,
                   help="table (default), jsonl, csv or json; with --count json (default), table, jsonl or csv")


def add_commands(sub) -> None:
    """Mount ``chains`` and ``mechanisms`` on the ``mechsynth`` parser."""
    p = sub.add_parser("chains", help="type synthesis: every non-isomorphic chain")
    _add_selection(p)
    p.set_defaults(run=_run, what="chains")
    p = sub.add_parser("mechanisms", help="chains with a fixed link (and input link) up to symmetry")
    _add_selection(p)
    p.add_argument("--input-link", action="store_true", help="also choose the input link, jointed to the frame")
    p.set_defaults(run=_run, what="mechanisms")


def _selection(args) -> tuple[int, dict]:
    from synth.code import Code
    from synth.errors import InvalidOption

    if args.dof is None:
        if args.code is None:
            raise InvalidOption("give --dof (and --links), or --code")
        args.dof = Code.parse(args.code).dof()
    if args.links is None and args.code is None:
        raise InvalidOption("give --links N (or --code C)")
    return args.dof, dict(
        v=args.v, code=args.code, rigid_subchains=args.rigid_subchains, fractionated=args.fractionated,
        planar_only=args.planar_only, require=args.require, cranks=args.cranks, workers=args.workers,
        progress=True,
    )


def _run(args) -> int:
    from synth._type_synthesis import count_chains, count_mechanisms, mechanisms, type_synthesis

    dof, kwargs = _selection(args)
    if args.count:  # counted in the worker processes: flat memory at any size
        if args.what == "chains":
            result = count_chains(dof, args.links, **kwargs)
        else:
            result = count_mechanisms(dof, args.links, input_link=args.input_link, **kwargs)
        if write_count(result, args.format or "json") == 0:
            return nothing_found(f"{args.what} satisfy these parameters and conventions")
        return 0
    if args.what == "chains":
        items = type_synthesis(dof, args.links, **kwargs)
    else:
        items = mechanisms(dof, args.links, input_link=args.input_link, **kwargs)
    rows = (_row(item, args.what, args.format or "table") for item in items)
    columns = ["index", "code", "links", "joints", "certificate"]
    if args.what == "mechanisms":
        columns[3:3] = ["frame", "input_link"]
    fmt = args.format or "table"
    n = write_rows(_indexed(rows), columns, fmt)
    if fmt == "table":
        print(f"{n} {args.what}")
    if n == 0:
        return nothing_found(f"{args.what} satisfy these parameters and conventions")
    return 0


def _indexed(rows):
    for i, row in enumerate(rows, start=1):
        row["index"] = i
        yield row


def _row(item, what: str, fmt: str) -> dict:
    row = item.to_dict()
    if fmt == "table":  # for people: the compact joint list and a short certificate
        chain = item if what == "chains" else item.chain
        row["joints"] = chain.compact()
        row["certificate"] = "…" + row["certificate"][-16:]
    return row
