"""CLI commands ``grid``, ``atlas`` and ``draw``: batch runs into an SQLite atlas, queries, drawings.

Example
-------
>>> import tempfile, pathlib
>>> from mechsynth.cli import main
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> grid, db = str(folder / "g.toml"), str(folder / "a.sqlite")
>>> _ = pathlib.Path(grid).write_text('dof = 1\\nlinks = "4..8"\\n')
>>> main(["grid", grid, "--db", db, "--workers", "1", "--format", "json"])  # doctest: +ELLIPSIS
{"status": "done", "units_total": 6, ...}
0
>>> main(["atlas", "--db", db, "--export", "mechanisms", "--where", "n=8", "--count"])
{"count": 71, "by_code": {"440/0": 35, "521/0": 31, "602/0": 5}}
0
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .._argtypes import inches, positive, seconds, whole, workers
from .._output import nothing_found, write_count, write_rows
from .chains import WRITTEN

__all__ = ["add_commands"]


def add_commands(sub) -> None:
    """Mount ``grid``, ``atlas`` and ``draw`` on the ``mechsynth`` parser."""
    p = sub.add_parser("grid", help="run a grid file of W, n, v ranges into an SQLite atlas (resumable)")
    p.add_argument("grid", help="grid file (TOML), e.g. models/grid_small.toml")
    p.add_argument("--db", required=True, help="SQLite atlas to create or resume")
    p.add_argument("--workers", type=workers, help="local processes (default: all cores)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="run the units on a Dask scheduler, e.g. tcp://host:8786")
    p.add_argument("--timeout", type=seconds, help="with --scheduler: seconds to wait for it (default 5)")
    p.add_argument("--force", action="store_true", help="run a grid estimated to take more than a day")
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.set_defaults(run=_run_grid)

    p = sub.add_parser("atlas", help="summarise an atlas, or export its chains / mechanisms")
    p.add_argument("--db", required=True, help="SQLite atlas written by 'mechsynth grid'")
    p.add_argument("--export", choices=("chains", "mechanisms"), help="print rows instead of the summary")
    p.add_argument("--where", action="append", nargs="+", default=[], metavar="FIELD OP VALUE",
                   help="filter, repeatable (AND): code=6301/0, W=1, 'n = 8..10', v<=1, K=3, n3>=2, maxdeg<=4, "
                        "fractionated=0, cell=KEY, id=ID (12 hex digits), certificate=CERT; gear trains: kind=gears, "
                        "meshes=4, carriers=2, lever=530/1, rotation=ID")
    p.add_argument("--count", action="store_true", help='print {"count": N, "by_code": {...}} of the selection')
    p.add_argument("--prismatic", metavar="A..B",
                   help="export the variants with A…B prismatic pairs of the selected revolute chains, up to symmetry")
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
    p.add_argument("--samples", type=positive, help="with --index-curves: crank poses per mechanism (default 200)")
    p.add_argument("--links", metavar="A..B", help="with --index-curves: only the mechanisms with this many links")
    p.add_argument("--triads", action="store_true", help="with --index-curves: also the mechanisms moved by Newton's "
                   "method (triads and higher groups; about a second a sample)")
    p.add_argument("--seed", type=whole, help="with --index-curves: seed of the random poses (default 0)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="with --index-curves: sample on a Dask scheduler")
    p.set_defaults(run=_run_atlas)

    p = sub.add_parser("draw", help="draw chains or mechanisms as a designer does (SVG/PNG)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--code", help="every chain of this code, e.g. 7201/1 (synthesised now)")
    g.add_argument("--chain", help="one chain as a joint list '0-1 1-2 2-3 3-0' or JSON")
    g.add_argument("--db", help="chains of an atlas selected with --where or --id")
    p.add_argument("--dof", type=whole, help="with --code: W (default: the code's own in motion space h); "
                   "with --repairs: the intended W")
    p.add_argument("--h", type=whole, help="with --code or --chain: motion space of the loops, 2 … 6 (default 3, or "
                   "the chain's own)")
    p.add_argument("--where", action="append", nargs="+", default=[], metavar="FIELD OP VALUE",
                   help="with --db: filter (as for 'mechsynth atlas')")
    p.add_argument("--id", help="with --db: the chain with this id (12 hex digits, as listings and the site show it)")
    p.add_argument("--frame", type=whole, help="with --chain: the fixed link (hatched)")
    p.add_argument("--loop-classes", metavar="H=K,H=K",
                   help="with --chain: every base of the higher class's loops on that chain (e.g. 3=4,5=1), "
                        "each base's links in its class's colour")
    p.add_argument("--repairs", type=positive, nargs="?", const=5, metavar="N",
                   help="with --chain: draw it beside its N (default 5) nearest valid rebuilt chains")
    p.add_argument("--mechanisms", action="store_true", help="draw every mechanism (fixed link up to symmetry)")
    p.add_argument("--prismatic", metavar="A..B",
                   help="draw every assignment of A…B prismatic pairs to the simple joints, up to symmetry "
                        "(a slider is a block on a bar, a cylinder a dark barrel)")
    p.add_argument("--idle-joints", action="store_true",
                   help="with --prismatic: keep revolute pairs whose links are also joined by prismatic pairs")
    p.add_argument("--columns", type=positive, help="drawings per row of a sheet")
    p.add_argument("--size", type=inches, help="edge of each drawing in inches (default 3.6 alone, 1.9 on a sheet)")
    p.add_argument("--dpi", type=positive, help="resolution of a .png (default 150 alone, 100 on a sheet)")
    p.add_argument("--labels", action=argparse.BooleanOptionalAction, default=None,
                   help="number the links (default: on for one drawing and for mechanisms, off on chain sheets)")
    p.add_argument("--limit", type=positive, default=400, help="refuse sheets larger than this (default 400)")
    p.add_argument("--title", help="sheet title (default: the selection)")
    p.add_argument("--out", required=True, help="output file, .svg or .png (or .pdf)")
    p.set_defaults(run=_run_draw)


# --------------------------------------------------------------------- grid
def _run_grid(args) -> int:
    import os

    from synth import InvalidOption
    from synth.atlas import load_grid, run_grid, size_grid

    if args.timeout is not None and args.scheduler is None:
        raise InvalidOption("--timeout goes with --scheduler (it is how long to wait for the scheduler)")
    if args.workers is not None and args.scheduler is not None:
        raise InvalidOption("--workers and --scheduler contradict each other: the scheduler's workers run the units")
    grid = load_grid(args.grid)
    if not args.force:
        processes = 1 if args.scheduler else (args.workers or os.cpu_count() or 1)
        note = size_grid(grid, processes=processes, db=args.db, scheduler=args.scheduler is not None)
        if note:
            print(f"mechsynth: {note}", file=sys.stderr)
    result = run_grid(grid, args.db, workers=args.workers, scheduler=args.scheduler,
                      progress=True, connect_timeout=5.0 if args.timeout is None else args.timeout)
    if args.format == "json":
        print(json.dumps(result.to_dict()))
    else:
        print(f"grid {grid.name}: {result.cells} cells, {result.units_total} units "
              f"({result.units_skipped} already done, {result.units_run} run) on {result.executor}; "
              f"{result.chains_found} chains found ({result.chains_new} new), {result.mechanisms_found} mechanisms; "
              f"{result.seconds:.1f} s, {result.chains_per_second:.0f} chains/s -> {args.db}")
    return 0


# -------------------------------------------------------------------- atlas
_CHAIN_COLUMNS = ["id", "code", "links", "dof", "v", "degrees", "fractionated", "joints", "certificate"]
_MECH_COLUMNS = ["chain_id", "code", "links", "dof", "v", "frame", "input_link", "joints", "certificate"]
_TRAIN_COLUMNS = ["id", "code", "lever_code", "links", "dof", "meshes", "carriers", "rotation_id", "train", "certificate"]
_TRAIN_MECH_COLUMNS = ["chain_id", "code", "lever_code", "links", "dof", "frame", "train", "certificate"]


def _run_atlas(args) -> int:
    from synth.atlas import export, summary
    from synth import InvalidOption

    args.where = _conditions(args.where)
    if args.index_curves:
        return _index_curves(args)
    extra = [name for name, given in (("--samples", args.samples), ("--links", args.links), ("--triads", args.triads),
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
                                      ("--prismatic", args.prismatic), ("--html", args.html is not None),
                                      ("--format", args.format not in (None, "table", "json"))) if given]
    if other:
        raise InvalidOption(f"--index-curves builds the curve index; it does not go with {', '.join(other)}")
    if args.workers is not None and args.scheduler is not None:
        raise InvalidOption("--workers and --scheduler contradict each other: the scheduler's workers sample")
    if args.seed is not None and args.seed < 0:
        raise InvalidOption(f"--seed must be a whole number ≥ 0, not {args.seed}")
    from .dimension_atlas import links_range

    settings = IndexSettings(samples=args.samples or 200, seed=args.seed or 0, triads=args.triads)
    result = index_curves(args.db, settings=settings, links=links_range(args.links), workers=args.workers,
                          scheduler=args.scheduler, progress=True)
    if args.format == "json":
        print(json.dumps(result.to_dict()))
    else:
        print(f"curve index of {args.db}: {result.units_total} mechanisms ({result.units_run} sampled now, "
              f"{result.units_skipped} of them without curves), {result.curves} curves in all; "
              f"{result.seconds:.1f} s on {result.executor}")
    return 0


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


def _conditions(groups: list[list[str]]) -> list[str]:
    """``--where n3 '>=' 2`` and ``--where n3>=2`` are the same condition."""
    return ["".join(words) for words in groups]


# --------------------------------------------------------------------- draw
def _variants(args, chains: list) -> list:
    """The chains themselves, or with ``--prismatic A..B`` every R/P variant of each."""
    if args.prismatic is None:
        return chains
    from synth import InvalidOption
    from synth import parse_range
    from synth import variants_of

    lo, hi = parse_range(args.prismatic, "--prismatic")
    chains = [c for c in chains if c.kinds is None]  # an atlas may hold variants already
    if not chains:
        return []
    simple = max(sum(1 for j in c.joints if len(j) == 2) for c in chains)
    if lo > simple:
        raise InvalidOption(f"--prismatic {args.prismatic} asks for more prismatic pairs than the {simple} "
                            "simple joints of these chains")
    return list(variants_of(chains, (lo, simple if hi is None else min(hi, simple)), idle=args.idle_joints))


def _defect(chain, dof) -> str:
    """What is wrong with a chain to repair, in a few words (the caption of its drawing)."""
    from synth import check_subchains

    report = check_subchains(chain, rigid_subchains=(chain.dof if dof is None else dof) == 0)
    wrong = f"W = {chain.dof}, not {dof}; " if dof is not None and dof != chain.dof else ""
    if report.ok:
        return f"given: {wrong or 'no defect'}".rstrip("; ")
    return (f"given: {wrong}{report.kind} of links {', '.join(map(str, report.worst))} (W(S) = "
            f"{report.worst_mobility})")


def _at_most(chains, args):
    """The selected chains, stopped once they are more than ``--limit`` drawings (each chain is
    at least one; R/P variants may be none): a large selection is refused without being built."""
    import itertools

    return chains if args.prismatic is not None else itertools.islice(chains, args.limit + 1)


def _draw_trains(rows, args) -> int:
    """Gear trains of an atlas as functional schematics (shafts, gears on their axes, carriers), as
    ``gears --out`` and the site draw them."""
    from synth import InvalidOption
    from synth.gears import GearTrain, draw_sheet, draw_train

    if len(rows) > args.limit:
        raise InvalidOption(f"the selection has more than {args.limit} drawings (--limit); narrow it with --where "
                            "or raise --limit")
    unused = [name for name, given in (("--dpi", args.dpi), ("--labels", args.labels is not None),
                                       ("--size", args.size is not None and len(rows) > 1)) if given]
    if unused:
        raise InvalidOption(f"gear trains are drawn as schematics, which take no {', '.join(unused)}"
                            + (" on a sheet" if unused == ["--size"] else ""))
    trains = [GearTrain.parse(row["train"]) for row in rows]
    if len(trains) == 1:
        draw_train(trains[0], args.out, title=args.title, size=args.size or 6.0)
    else:
        draw_sheet(trains, args.out, columns=args.columns or 4, limit=args.limit,
                   titles=[f"{k + 1}: {row['code']}  id {row['id']}" for k, row in enumerate(rows)])
    print(f"{len(trains)} schematic{'s' if len(trains) != 1 else ''} -> {args.out}", file=sys.stderr)
    return 0


def _run_draw(args) -> int:
    from synth import draw
    from synth import Chain, Mechanism
    from synth import InvalidOption

    args.where = _conditions(args.where)
    if args.id is not None:
        if not args.db:
            raise InvalidOption("--id names a chain of an atlas: give --db too (for a chain of your own, "
                                "'mechsynth identify' finds its id)")
        args.where.append(f"id={args.id}")
    if args.dpi is not None and not args.out.lower().endswith(".png"):
        raise InvalidOption("--dpi sets the resolution of a .png; .svg and .pdf drawings are vector files")
    if args.where and not args.db:
        raise InvalidOption("--where filters an atlas: give --db too")
    if args.loop_classes is not None and not args.chain:
        raise InvalidOption("--loop-classes goes with --chain (for a query: mechsynth chains --loop-classes … "
                            "--format jsonl, then draw a row with --chain)")
    if args.frame is not None and not args.chain:
        raise InvalidOption("--frame goes with --chain (for sheets use --mechanisms)")
    if args.frame is not None and args.mechanisms:
        raise InvalidOption("--frame and --mechanisms contradict each other: one fixed link, or every one up to "
                            "symmetry")
    if args.dof is not None and not (args.code or args.repairs):
        raise InvalidOption("--dof goes with --code (the W of its chains) or --repairs (the intended W); a chain "
                            "and an atlas's chains carry their own")
    if args.h is not None:
        from synth import check_motion_space

        if args.db:
            raise InvalidOption("--h goes with --code or --chain (an atlas's chains carry their own h)")
        check_motion_space(args.h, lowest=2)
        if args.repairs and args.h != 3:
            raise InvalidOption("--repairs rebuilds planar chains (h = 3), not chains in motion space h = "
                                f"{args.h}")
    given = None
    if args.chain:  # read as analyze and identify read it, in its own motion space unless --h says another
        from synth.exchange import read_chain

        given = read_chain(args.chain, args.h).chain
    h = given.h if given is not None else args.h or 3
    if args.repairs and h != 3:
        raise InvalidOption(f"--repairs rebuilds planar chains (h = 3), not chains in motion space h = {h}")
    notes = None  # the words under each drawing of a sheet: the edits of the repairs
    if args.idle_joints and args.prismatic is None:
        raise InvalidOption("--idle-joints goes with --prismatic (an all-revolute chain has no idle joint)")
    if args.prismatic is not None and (args.repairs or args.frame is not None or h != 3):
        raise InvalidOption("--prismatic draws the variants of planar chains (h = 3); it does not go with "
                            "--repairs or --frame (use --mechanisms for every fixed link)")
    if args.repairs and (not args.chain or args.frame is not None or args.mechanisms):
        raise InvalidOption("--repairs goes with --chain alone (not --frame or --mechanisms)")
    if args.chain and args.repairs:
        from synth import chain_repairs

        chain = given
        repairs = chain_repairs(chain, dof=args.dof, limit=args.repairs)
        if not repairs:
            print("mechsynth: no repair: the chain is valid already, or no valid one lies within three edits",
                  file=sys.stderr)
            return 1
        items = [chain, *(Chain.parse(r["chain"]) for r in repairs)]
        notes = [_defect(chain, args.dof)] + ["; ".join(r["edits"]) for r in repairs]
        title = args.title or f"{chain.compact()} and {len(repairs)} repairs"
    elif args.chain:
        chain = given
        if args.loop_classes is not None:
            from .chains import _class_variants_of

            if args.frame is not None or args.prismatic is not None:
                raise InvalidOption("--loop-classes draws every base on the chain: it does not go with --frame or "
                                    "--prismatic (use --mechanisms for every fixed link)")
            items = draw.expand(_class_variants_of(chain, args), mechanisms=args.mechanisms)
            if not items:
                print("mechsynth: no base of those loop classes passes the exact test on this chain", file=sys.stderr)
                return 1
        elif args.frame is not None:
            items = [Mechanism(chain, args.frame)]
        else:
            items = draw.expand(_variants(args, [chain]), mechanisms=args.mechanisms)
        title = args.title
    elif args.code:
        import synth

        query = synth.ChainQuery.of(args.dof, code=args.code, h=h)
        code, dof = query.code, query.dof
        chains = list(_at_most(synth.type_synthesis(query, workers=1), args))
        if not chains:
            print(f"mechsynth: no chain has code {args.code} with W = {dof}", file=sys.stderr)
            return 1
        items = draw.expand(_variants(args, chains), mechanisms=args.mechanisms)
        title = args.title or f"{code} (W = {dof}{'' if h == 3 else f', h = {h}'}): {len(chains)} chains"
    else:
        from synth.atlas import export

        rows = list(_at_most(export(args.db, "chains", where=args.where), args))
        if not rows:
            print("mechsynth: no chain of the atlas matches the selection", file=sys.stderr)
            return 1
        if all(row.get("kind") == "gears" for row in rows) and args.prismatic is None and not args.mechanisms:
            return _draw_trains(rows, args)
        chains = [Chain.from_dict(row) for row in rows]
        items = draw.expand(_variants(args, chains), mechanisms=args.mechanisms)
        title = args.title or (None if args.id else f"{' '.join(args.where) or 'atlas'}: {len(chains)} chains")
    if not items:  # only --prismatic can empty a selection here
        print(f"mechsynth: no variant with {args.prismatic} prismatic pairs passes the exact test", file=sys.stderr)
        return 1
    if len(items) > args.limit:
        cut = args.prismatic is None and bool(args.code or args.db) and len(chains) > args.limit  # not all built
        size = (f"more than {args.limit} drawings (--limit)" if cut
                else f"{len(items)} drawings, more than --limit {args.limit}")
        raise InvalidOption(f"the selection has {size}; narrow it with --where or raise --limit")
    if len(items) == 1 and not (args.code or (args.db and args.id is None)):
        size, dpi = draw.SINGLE
        draw.draw_one(items[0], args.out, title=title, labels=args.labels is not False,
                      size=args.size or size, dpi=args.dpi or dpi)
    else:
        size, dpi = draw.CELL
        draw.draw_sheet(items, args.out, columns=args.columns, title=title, labels=args.labels,
                        size=args.size or size, dpi=args.dpi or dpi, notes=notes)
    print(f"{len(items)} drawing{'s' if len(items) != 1 else ''} -> {args.out}", file=sys.stderr)
    return 0
