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
import sys

from .._argtypes import seconds, whole, workers
from .._output import FORMATS, nothing_found, write_count, write_rows

# Queries at least this large (loops K; multiple joints grow faster) are sized before they run.
_SIZED_LOOPS, _SIZED_LOOPS_MULTIPLE = 7, 6
_LIMIT_SECONDS = 86400.0  # refused without --force when estimated to take longer (wall, on the workers)
_TABLE_ROWS = 1_000_000  # a table is held in memory to align its columns: refused above this
_NOTE_SECONDS = 600.0  # a query estimated to take longer says so on stderr before it starts
_MAX_CODE_LINKS = 1000  # --code: larger chains are beyond what certificates and drawings are used for


def _add_selection(p) -> None:
    p.add_argument("--dof", type=whole, help="mobility W (0 = trusses); default: the code's W")
    p.add_argument("--links", type=whole, help="number of links n (frame included)")
    p.add_argument("--v", help="multiple-joint count or range A..B (default 0: simple joints; with --code its own)")
    p.add_argument("--code", help="only this code, e.g. 6301/0, 620/0-1 or the open 2|5/2")
    p.add_argument("--h", type=whole, default=3,
                   help="motion space of the loops, 2 … 6 (default 3: planar and spherical; 5 Bricard; 6 spatial)")
    p.add_argument("--n1", help="single-joint links (open chains: arms, grippers), N or A..B (default 0; "
                   "with --code its own)")
    p.add_argument("--max-multiplicity", type=whole,
                   help="most links on one joint (default: the limit theorem's K + 1 closed, K + W + 1 open)")
    p.add_argument("--require", action="append", default=[], metavar="I=N|I=A..B|I=A..",
                   help="design constraint on n_I, the links with I joints (repeatable)")
    p.add_argument("--cranks", action="append", default=[], metavar="I=C",
                   help="required sub-structure: a link with I joints carrying ≥ C cranks (repeatable)")
    p.add_argument("--rigid-subchains", action="store_true", default=None,
                   help="allow rigid sub-chains, W(S) ≥ 0 (default only for W = 0)")
    p.add_argument("--fractionated", action=argparse.BooleanOptionalAction, default=True,
                   help="keep chains split by one link or joint (default: keep)")
    p.add_argument("--planar-only", action="store_true", help="keep only chains with planar graphs")
    p.add_argument("--prismatic", metavar="A..B",
                   help="also list every assignment of A…B prismatic pairs to the simple joints, up to symmetry")
    p.add_argument("--chain", help="with --prismatic: one given chain (joint list '0-1 1-2 …' or JSON) instead of a query")
    p.add_argument("--idle-joints", action="store_true",
                   help="with --prismatic: keep revolute pairs whose links are also joined by prismatic pairs")
    p.add_argument("--count", action="store_true", help='print {"count": N, "by_code": {...}} only')
    p.add_argument("--workers", type=workers, help="processes, at most the number of cores (default: all cores)")
    p.add_argument("--checkpoint", metavar="FILE",
                   help="with --count: commit unit counts to this SQLite file as they finish; rerun to resume")
    p.add_argument("--scheduler", metavar="ADDRESS", help="with --count: run the units on a Dask scheduler, "
                   "e.g. tcp://host:8786")
    p.add_argument("--timeout", type=seconds, help="with --scheduler: seconds to wait for it (default 5)")
    p.add_argument("--force", action="store_true",
                   help="run a query estimated to take more than a day (see README, 'Large queries')")
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


def checked_code(text: str, h: int, dof: int | None = None):
    """The code of ``--code`` and its W (``dof`` or the code's own in motion space ``h``), refused
    when its chains would be too large to build or it has no chain with W ≥ 0."""
    from synth.errors import ImpossibleParameters, QueryTooLarge
    from synth.structure.code import Code

    code = Code.parse(text)
    if code.links > _MAX_CODE_LINKS:
        raise QueryTooLarge(f"the code given has {code.links} links; chains are built here up to "
                            f"{_MAX_CODE_LINKS} links")
    if dof is None:
        dof = code.dof(h)
        if dof < 0:
            raise ImpossibleParameters(f"code {text.strip()} gives W = {dof} in motion space h = {h}: its links are "
                                       "over-constrained, and a chain has W ≥ 0")
    return code, dof


def _selection(args) -> tuple[int, dict]:
    from synth.errors import InvalidOption

    from synth.structure._params import check_motion_space

    check_motion_space(args.h, lowest=2)
    if args.code is not None:
        _, args.dof = checked_code(args.code, args.h, args.dof)
    if args.dof is None:
        raise InvalidOption("give --dof (and --links), or --code")
    if args.links is None and args.code is None:
        raise InvalidOption("give --links N (or --code C)")
    return args.dof, dict(
        v=args.v, code=args.code, rigid_subchains=args.rigid_subchains, fractionated=args.fractionated,
        planar_only=args.planar_only, require=args.require, cranks=args.cranks, workers=args.workers,
        progress=True, h=args.h, n1=args.n1 if args.n1 is not None else (None if args.code else 0),
        max_multiplicity=args.max_multiplicity,
    )


def _check_options(args) -> None:
    from synth.errors import InvalidOption

    for option in ("checkpoint", "scheduler"):
        if getattr(args, option) is not None and not args.count:
            raise InvalidOption(f"--{option} goes with --count (listings are not resumed or distributed)")
    if args.idle_joints and args.prismatic is None:
        raise InvalidOption("--idle-joints goes with --prismatic (an all-revolute chain has no idle joint)")
    if args.prismatic is not None and (args.checkpoint is not None or args.scheduler is not None):
        raise InvalidOption("--prismatic variants are counted on this machine: drop --checkpoint and --scheduler")
    if args.prismatic is not None and args.h != 3:
        raise InvalidOption(f"prismatic pairs are assigned in planar chains (h = 3), not in motion space h = {args.h}")
    if args.scheduler is not None and args.workers is not None:
        raise InvalidOption("--workers and --scheduler contradict each other: the scheduler's workers run the units")
    if args.timeout is not None and args.scheduler is None:
        raise InvalidOption("--timeout goes with --scheduler (it is how long to wait for the scheduler)")


def _size_guard(dof: int, args, kwargs: dict) -> None:
    """Refuse, within seconds and with an estimate, a query too large to run unasked."""
    import math
    import os

    from synth.synthesis.number_synthesis import parse_range
    from synth.errors import InvalidOption

    if args.code is not None or args.links is None or (args.force and args.count):
        return
    if args.links - dof - 1 < 0 or (args.links - dof - 1) % (args.h - 1):
        return  # no whole number of loops: the query itself says so
    loops = (args.links - dof - 1) // (args.h - 1)
    v = parse_range(args.v or 0, "v")
    if loops < (_SIZED_LOOPS_MULTIPLE if v != (0, 0) else _SIZED_LOOPS):
        return
    from synth.execution.estimate import describe_seconds, estimate, magnitude

    query = {k: val for k, val in kwargs.items() if k not in ("workers", "progress")}
    if getattr(args, "what", "chains") == "mechanisms":
        work, items = ("mechanisms with input" if args.input_link else "mechanisms"), "mechanisms"
    else:
        work, items = ("count" if args.count else "list"), "chains"
    found = estimate(dict(query, dof=dof, links=args.links), work=work)
    if found is None:
        if not args.force:
            raise InvalidOption(f"this query ({args.links} links) is large and its size cannot be estimated "
                                "(fewer than three smaller sizes have chains); give --force to run it anyway")
        return
    processes = 1 if args.scheduler else (args.workers or os.cpu_count() or 1)
    where = ("on the scheduler's workers (one core shown)" if args.scheduler
             else f"on {processes} worker{'s' * (processes > 1)}")
    log_wall = found.log10_seconds - math.log10(processes)
    size = (f"about {magnitude(found.chains, found.log10_chains)} {items} in "
            f"{magnitude(found.units, found.log10_units)} units, {describe_seconds(found.seconds / processes, log_wall)} "
            f"{where}, extrapolated from the {found.basis}")
    if not args.count and (args.format or "table") == "table" and found.chains > _TABLE_ROWS:
        raise InvalidOption(f"a table is held in memory to align it and this listing ({args.links} links) is too large "
                            f"for one ({size}); "
                            "use --format jsonl or csv (streamed), or --count")
    if not args.force and found.seconds / processes > _LIMIT_SECONDS:
        hint = " (with --checkpoint FILE it can be stopped and resumed)" if args.count else ""
        raise InvalidOption(f"this query ({args.links} links) is too large to run unasked: {size}; give --force to run "
                            f"it anyway{hint}")
    if found.seconds / processes > _NOTE_SECONDS:
        resumable = "" if not args.count or args.checkpoint else " (give --checkpoint FILE to make it resumable)"
        print(f"mechsynth: a long query: {size}{resumable}", file=sys.stderr)


def _prismatic_range(args, dof: int) -> tuple[int, int]:
    """The A..B of --prismatic, refused when it asks for more P pairs than the chains have simple joints."""
    from synth.synthesis.number_synthesis import parse_range
    from synth.structure.code import Code
    from synth.errors import InvalidOption

    lo, hi = parse_range(args.prismatic, "--prismatic")
    if args.code is not None:
        code = Code.parse(args.code)
        simple = code.joints - sum(code.composition or ())
    else:
        simple = (3 * (args.links - 1) - dof) // 2  # p: every joint simple at best
    if lo > 0 and simple == 0:
        raise InvalidOption("prismatic pairs go on simple joints and these chains have multiple joints only")
    if lo > simple:
        raise InvalidOption(f"--prismatic {args.prismatic} asks for more prismatic pairs than the {simple} "
                            "simple joints of these chains")
    return lo, simple if hi is None else min(hi, simple)


def _run_prismatic(args, dof: int, kwargs: dict) -> int:
    """``--prismatic``: the R/P variants of every chain (or their mechanisms), counted or listed."""
    from synth.synthesis.type_synthesis import type_synthesis
    from synth.synthesis.variants import variant_rows

    rows = variant_rows(type_synthesis(dof, args.links, **kwargs), _prismatic_range(args, dof),
                        idle=args.idle_joints, mechanisms=args.what == "mechanisms",
                        input_link=getattr(args, "input_link", False))
    return write_variants(rows, args.what, args.count, args.format)


def write_variants(rows, what: str, count: bool, fmt: str | None) -> int:
    """Write R/P variant rows counted by code, or listed (P pairs marked in tables); the exit status."""
    if count:
        by_code: dict[str, int] = {}
        for row in rows:
            by_code[row["code"]] = by_code.get(row["code"], 0) + 1
        found = write_count({"count": sum(by_code.values()), "by_code": dict(sorted(by_code.items()))},
                            fmt or "json")
    else:
        fmt = fmt or "table"
        columns = ["index", "code", "dof", "loops_2", "loops_3", "cylinders", "links", "joints", "kinds",
                   "certificate"]
        if what == "mechanisms":
            columns[6:6] = ["frame", "input_link"]
        found = write_rows(_indexed(_prismatic_cells(r, fmt) for r in rows), columns, fmt)
        if fmt == "table":
            print(f"{found} prismatic variants ({what})")
    return 0 if found else nothing_found("prismatic variants satisfy these parameters and conventions")


def _prismatic_cells(row: dict, fmt: str) -> dict:
    if fmt == "table":  # P pairs marked in the joint list, e.g. '0-1 1=2' (1=2 prismatic)
        kinds = row.get("kinds") or ["revolute"] * len(row["joints"])
        row["joints"] = " ".join(("=" if k == "prismatic" else "-").join(map(str, j))
                                 for j, k in zip(row["joints"], kinds))
        row["kinds"] = "".join("P" if k == "prismatic" else "R" for k in kinds)
        row["certificate"] = "…" + row["certificate"][-16:]
    return row


def _run_one_chain(args) -> int:
    """``--chain C --prismatic A..B``: the variants of one chain (Fig. 6: a drive's cylinders)."""
    from synth.synthesis.number_synthesis import parse_range
    from synth.structure.chain import Chain
    from synth.errors import InvalidOption
    from synth.synthesis.variants import prismatic_variants, variant_rows

    if args.prismatic is None:
        raise InvalidOption("--chain goes with --prismatic (it lists the variants of that chain)")
    given = [f"--{k.replace('_', '-')}" for k in ("dof", "links", "code", "v", "rigid_subchains", "planar_only")
             if getattr(args, k) not in (None, False)] + (["--require"] if args.require else [])
    if given:
        raise InvalidOption(f"{given[0]} selects chains of a query and contradicts --chain")
    chain = Chain.parse(args.chain)
    lo, hi = parse_range(args.prismatic, "--prismatic")
    prismatic_variants(chain, lo)  # refuses a count beyond the chain's simple joints, with the reason
    rows = variant_rows([chain], (lo, len(chain.joints) if hi is None else hi), idle=args.idle_joints,
                        mechanisms=args.what == "mechanisms", input_link=getattr(args, "input_link", False))
    return write_variants(rows, args.what, args.count, args.format)


def _run(args) -> int:
    from synth.synthesis.type_synthesis import count_chains, count_mechanisms, mechanisms, type_synthesis

    _check_options(args)
    if args.chain is not None:
        return _run_one_chain(args)
    dof, kwargs = _selection(args)
    _size_guard(dof, args, kwargs)
    if args.prismatic is not None:
        return _run_prismatic(args, dof, kwargs)
    if args.count:  # counted in the worker processes: flat memory at any size
        log = None
        if args.checkpoint is not None and not sys.stderr.isatty():  # batch runs log each commit
            log = lambda line: print(f"mechsynth: {line}", file=sys.stderr, flush=True)  # noqa: E731
        extra = dict(checkpoint=args.checkpoint, scheduler=args.scheduler, timeout=args.timeout or 5.0, log=log)
        if args.what == "chains":
            result = count_chains(dof, args.links, **kwargs, **extra)
        else:
            result = count_mechanisms(dof, args.links, input_link=args.input_link, **kwargs, **extra)
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
