"""CLI command ``atlas``: what an atlas holds, its chains and mechanisms exported, its web site.

Example
-------
>>> import tempfile, pathlib
>>> from mechsynth.cli import main
>>> from synth.atlas import parse_grid, run_grid
>>> db = str(pathlib.Path(tempfile.mkdtemp()) / "a.sqlite")
>>> run_grid(parse_grid('dof = 1\\nlinks = "8"\\n'), db, workers=1).status
'done'
>>> main(["atlas", "--db", db, "--export", "mechanisms", "--where", "n=8", "--count"])
{"count": 71, "by_code": {"440/0": 35, "521/0": 31, "602/0": 5}}
0
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from .._argtypes import positive, whole, where_conditions, workers
from .._output import nothing_found, write_count, write_rows
from .chains import WRITTEN

__all__ = ["add_commands"]


def add_commands(sub) -> None:
    """Mount ``atlas`` on the ``mechsynth`` parser."""
    p = sub.add_parser("atlas", help="summarise an atlas, or export its chains / mechanisms")
    p.add_argument("--db", required=True, help="SQLite atlas written by 'mechsynth grid'")
    p.add_argument("--export", choices=("chains", "mechanisms"), help="print rows instead of the summary")
    p.add_argument("--where", action="append", nargs="+", default=[], metavar="FIELD OP VALUE",
                   help="filter, repeatable (AND): code=6301/0, W=1, 'n = 8..10', v<=1, K=3, n3>=2, maxdeg<=4, "
                        "fractionated=0, cell=KEY, id=ID (12 hex digits), certificate=CERT; gear trains: kind=gears, "
                        "meshes=4, carriers=2, lever=530/1, rotation=ID")
    p.add_argument("--count", action="store_true", help='print {"count": N, "by_code": {...}} of the selection')
    p.add_argument("--prismatic", metavar="A..B",
                   help="export the variants with A…B prismatic pairs of the selected revolute chains, up to symmetry; "
                        "with --index-curves: also index the atlas's chains with A…B prismatic pairs (slider-cranks, "
                        "six-bars with sliders; the atlas holds them when its grid has 'prismatic')")
    p.add_argument("--idle-joints", action="store_true", help="with --prismatic: keep variants with idle joints")
    p.add_argument("--format", choices=("table", "json", "jsonl", "csv", *WRITTEN), default=None,
                   help="summary: table or json; export: jsonl, csv, table, or graphml, gml, dot, edgelist, adjacency, "
                        "incidence (docs/exchange.md)")
    p.add_argument("--html", metavar="DIR", help="write the atlas as a static web site into DIR (open DIR/index.html)")
    p.add_argument("--page-size", type=positive, help="with --html: chains per page (default 60)")
    p.add_argument("--draw-limit", type=whole,
                   help="with --html: draw at most this many chains, in code order (default 20000; ~50 ms each at 12 links)")
    p.add_argument("--move-limit", type=whole,
                   help="with --html: give the mechanisms of this many planar 1-DOF chains (the first drawn) a page "
                        "where they move (default 0; about a second a mechanism)")
    p.add_argument("--force", action="store_true", help="with --html: write into a non-empty DIR")
    p.add_argument("--workers", type=workers,
                   help="with --html: processes building the pages (default: all cores beyond 200 chains); with "
                        "--index-curves: processes sampling the mechanisms (default: all cores)")
    p.add_argument("--index-curves", action="store_true",
                   help="build (or resume) the curve index the atlas search of 'mechsynth dimension --db' needs: "
                        "coupler curves of random crank poses of every planar 1-DOF mechanism, as Fourier descriptors")
    p.add_argument("--samples", type=positive, help="with --index-curves: crank poses per mechanism and drawing "
                   "(default 200)")
    p.add_argument("--drawings", type=positive, metavar="K", help="with --index-curves: drawings of each mechanism its poses are "
                   "sampled around: the atlas's and K − 1 of its chain numbered at random (default 1; see "
                   "docs/dimension.md)")
    p.add_argument("--links", metavar="A..B", help="with --index-curves: only the mechanisms with this many links")
    p.add_argument("--triads", action="store_true", help="with --index-curves: also the mechanisms moved by Newton's "
                   "method (triads and higher groups; about a second a sample)")
    p.add_argument("--seed", type=whole, help="with --index-curves: seed of the random poses (default 0)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="with --index-curves: sample on a Dask scheduler")
    p.set_defaults(run=_run_atlas)


_CHAIN_COLUMNS = ["id", "code", "links", "dof", "v", "degrees", "fractionated", "joints", "certificate"]
_MECH_COLUMNS = ["chain_id", "code", "links", "dof", "v", "frame", "input_link", "joints", "certificate"]
_TRAIN_COLUMNS = ["id", "code", "lever_code", "links", "dof", "meshes", "carriers", "rotation_id", "train", "certificate"]
_TRAIN_MECH_COLUMNS = ["chain_id", "code", "lever_code", "links", "dof", "frame", "train", "certificate"]


def _run_atlas(args) -> int:
    from synth.atlas import export, summary
    from synth import InvalidOption

    args.where = where_conditions(args.where)
    if args.index_curves:
        return _index_curves(args)
    extra = [name for name, given in (("--samples", args.samples), ("--drawings", args.drawings),
                                      ("--links", args.links), ("--triads", args.triads),
                                      ("--seed", args.seed is not None), ("--scheduler", args.scheduler)) if given]
    if extra:
        raise InvalidOption(f"{', '.join(extra)} go{'es' * (len(extra) == 1)} with --index-curves")
    if args.html is not None:
        return _write_site(args)
    if args.force or any(given is not None for given in (args.page_size, args.draw_limit, args.move_limit,
                                                          args.workers)):
        raise InvalidOption("--force, --page-size, --draw-limit, --move-limit and --workers go with --html")
    if args.idle_joints and args.prismatic is None:
        raise InvalidOption("--idle-joints goes with --prismatic (an all-revolute chain has no idle joint)")
    if args.count and args.format in WRITTEN:
        raise InvalidOption(f"--count prints a count as json, table, jsonl or csv, not {args.format} (a format of "
                            "chains)")
    what = args.export or ("chains" if args.where or args.count or args.prismatic is not None else None)
    if what is None:
        fmt = args.format or "table"
        if fmt not in ("table", "json"):
            raise InvalidOption(f"the summary is printed as table or json, not {fmt} (use --export for {fmt})")
        info = summary(args.db)
        if fmt == "json":
            print(json.dumps(info))
        else:
            _print_summary(info)
        return 0
    if args.prismatic is not None:
        return _export_variants(args, what)
    rows = export(args.db, what, where=args.where)
    if args.format in WRITTEN:
        from synth.exchange import write

        found = write(_items(rows, what), args.format)
    elif args.count:
        by_code: dict[str, int] = {}
        for row in rows:
            by_code[row["code"]] = by_code.get(row["code"], 0) + 1
        found = write_count({"count": sum(by_code.values()), "by_code": by_code}, args.format or "json")
    else:
        fmt = args.format or "jsonl"
        rows, columns = _columns(rows, what)
        found = write_rows(_written(rows, fmt), columns, fmt)
    return 0 if found else nothing_found(f"{what} of the atlas match the selection")


def _index_curves(args) -> int:
    """``--index-curves``: sample every mechanism's coupler curves into the atlas (resumable)."""
    from synth import InvalidOption
    from synth.atlas import IndexSettings, index_curves

    other = [name for name, given in (("--export", args.export), ("--where", args.where), ("--count", args.count),
                                      ("--html", args.html is not None),
                                      ("--format", args.format not in (None, "table", "json"))) if given]
    if other:
        raise InvalidOption(f"--index-curves builds the curve index; it does not go with {', '.join(other)}")
    if args.idle_joints:
        raise InvalidOption("--idle-joints goes with --prismatic when exporting variants; the index takes the "
                            "atlas's own chains")
    if args.workers is not None and args.scheduler is not None:
        raise InvalidOption("--workers and --scheduler contradict each other: the scheduler's workers sample")
    if args.seed is not None and args.seed < 0:
        raise InvalidOption(f"--seed must be a whole number ≥ 0, not {args.seed}")
    from .dimension_atlas import links_range

    settings = IndexSettings(samples=args.samples or 200, seed=args.seed or 0, triads=args.triads,
                             prismatic=_pairs(args.prismatic), drawings=args.drawings or 1)
    result = index_curves(args.db, settings=settings, links=links_range(args.links), workers=args.workers,
                          scheduler=args.scheduler, progress=True)
    if result.units_total == 0:
        return nothing_found("mechanism of the atlas is planar, 1-DOF and without gears with the links and "
                             "prismatic pairs asked for: the index has nothing to sample")
    if args.format == "json":
        print(json.dumps(result.to_dict()))
    else:
        print(f"curve index of {args.db}: {result.units_total} mechanisms ({result.units_run} sampled now, "
              f"{result.units_skipped} of them without curves), {result.curves} curves in all; "
              f"{result.seconds:.1f} s on {result.executor}")
    return 0


def _pairs(text: str | None) -> tuple[int, int]:
    """``--prismatic A..B`` of the index: a closed range of whole numbers of prismatic pairs (default 0..0)."""
    from synth import InvalidOption, SynthesisError, parse_range

    if text is None:
        return 0, 0
    try:
        lo, hi = parse_range(text, int)
    except SynthesisError:
        lo = hi = None
    if lo is None or hi is None or not 0 <= lo <= hi:
        raise InvalidOption(f"--prismatic must be a number of prismatic pairs or a range of them, low to high "
                            f"(e.g. 0..2), not {text!r}")
    return lo, hi


def _columns(rows, what: str):
    """The rows and the columns of a CSV or table: the first row's kind decides (a selection of gear
    trains, e.g. ``--where kind=gears``, shows each train's text form, lever code and rotation graph)."""
    import itertools

    first = next(rows, None)
    rows = itertools.chain([] if first is None else [first], rows)
    train = first is not None and first.get("kind") == "gears"
    if what == "chains":
        return rows, _TRAIN_COLUMNS if train else _CHAIN_COLUMNS
    return rows, _TRAIN_MECH_COLUMNS if train else _MECH_COLUMNS


def _written(rows, fmt: str):
    """In a table or CSV the joint list as ``analyze`` reads it back (``0~3`` a gear mesh, ``0=1`` a
    prismatic pair) and, for gear trains, the number of carrier links."""
    from synth import Chain

    for row in rows:
        if fmt in ("table", "csv"):
            row["joints"] = Chain.from_dict(row).compact()
            if "train" in row:
                row["carriers"] = len(set(row["carriers"]))
        yield row


def _items(rows, what: str):
    """Chains (or mechanisms) of exported atlas rows."""
    from synth import Chain, Mechanism

    for row in rows:
        chain = Chain.from_dict(row)
        yield chain if what == "chains" else Mechanism(chain, row["frame"], row.get("input_link"))


def _write_site(args) -> int:
    """``--html DIR``: the whole atlas as a static web site."""
    from synth.atlas import write_site
    from synth import InvalidOption

    other = [name for name, given in (("--export", args.export), ("--where", args.where), ("--count", args.count),
                                      ("--prismatic", args.prismatic), ("--format", args.format)) if given]
    if other:
        raise InvalidOption(f"--html writes the whole atlas; it does not go with {', '.join(other)} "
                            "(the site filters in the browser)")
    if args.draw_limit is not None and args.draw_limit < 0:
        raise InvalidOption(f"--draw-limit is a number of chains, not {args.draw_limit}")
    if args.move_limit is not None and args.move_limit < 0:
        raise InvalidOption(f"--move-limit is a number of chains, not {args.move_limit}")
    import time

    from synth.atlas import EmptyAtlas

    start = time.perf_counter()
    try:
        result = write_site(args.db, args.html, page_size=args.page_size or 60,
                            draw_limit=20000 if args.draw_limit is None else args.draw_limit,
                            move_limit=args.move_limit or 0, force=args.force,
                            progress=True, workers=args.workers,
                            note=lambda text: print(f"mechsynth: {text}", file=sys.stderr))
    except EmptyAtlas as exc:
        print(f"mechsynth: {exc}", file=sys.stderr)
        return 1
    print(f"{result.chains} chains in {result.codes} codes on {result.pages} pages ({result.drawn} drawn) -> "
          f"{Path(result.folder) / 'index.html'} in {time.perf_counter() - start:.1f} s", file=sys.stderr)
    return 0


def _export_variants(args, what: str) -> int:
    """``--prismatic``: the R/P variants of the selected chains (mechanisms: of each variant)."""
    from synth.atlas import export
    from synth import Chain
    from synth import parse_range
    from synth import mechanisms_of
    from synth import variants_of

    from .chains import write_items

    lo, hi = parse_range(args.prismatic, "--prismatic")
    # variants of the revolute chains only: an atlas grown with the grid key 'prismatic' holds variants already,
    # and a gear train's meshes are not pairs to make prismatic
    chains = (Chain.from_dict(row) for row in export(args.db, "chains", where=[*args.where, "prismatic=0", "kind=chains"]))
    items = variants_of(chains, (lo, hi), idle=args.idle_joints)
    if what == "mechanisms":
        items = (m for c in items for m in mechanisms_of(c))
    return write_items(items, what, fmt=args.format or ("jsonl" if not args.count else None), count=args.count,
                       kinds=True, idle=args.idle_joints)


def _print_summary(info: dict) -> None:
    units = info["units"]
    print(f"atlas {info['db']} (schema {info['schema_version']}): {info['chains']} chains, "
          f"{info['mechanisms']} mechanisms (fixed link), units {units['done']}/{units['total']} done")
    if info["locked_by"]:
        print(f"being written by pid {info['locked_by']['pid']} on {info['locked_by']['host']}")
    if info["codes"]:
        print()
        write_rows([dict(c, W=c["dof"], n=c["links"], code=c["code"].split(" h=")[0]) for c in info["codes"]],
                   ["code", "W", "h", "n", "chains", "mechanisms"], "table")
    if info["cells"]:
        print()
        write_rows([dict(c, W=c["dof"], n=c["links"], units=f"{c['units_done']}/{c['units_total']}")
                    for c in info["cells"]], ["cell", "W", "h", "n", "units", "chains"], "table")
