"""CLI command ``gears``: planetary gear trains — the atlas, mechanisms with speed ratios, tooth design.

Example
-------
>>> from mechsynth.cli import main
>>> main(["gears", "--dof", "1", "--links", "5", "--count"])
{"count": 13, "by_code": {"521/0": 3, "530/1": 4, "602/0": 2, "611/1": 2, "620/2": 1, "701/0-1": 1}}
0
"""

from __future__ import annotations

import sys

from .._argtypes import picture_file, positive, whole, workers
from .._output import COUNT_FORMATS, FORMATS, nothing_found, write_count, write_rows

_RATIO_LINKS = 7  # --ratio over every train of a size: up to this many links
_SHEET = 48  # schematics on one sheet unless --limit says otherwise


def add_commands(sub) -> None:
    """Mount ``gears`` on the ``mechsynth`` parser."""
    p = sub.add_parser("gears", help="planetary gear trains: atlas, mechanisms and speed ratios, tooth design")
    p.add_argument("--dof", type=whole, help="degrees of freedom F (default 1)")
    p.add_argument("--links", type=whole, help="number of links n, frame included")
    p.add_argument("--train", help="one given train instead of the atlas: axes '0-1-2', meshes '1~3', "
                   "'0~3i' (internal, ring first), '2~3@1' (carrier 1)")
    p.add_argument("--graphs", choices=("displacement", "rotation"), default="displacement",
                   help="one row per displacement graph (default) or per rotation graph")
    p.add_argument("--count", action="store_true", help='print {"count": N, "by_code": {...}} only')
    p.add_argument("--input-output", action="store_true",
                   help="list mechanisms: frame, input and output shafts up to symmetry, with the speed ratio")
    p.add_argument("--frame", type=whole, help="with --train: the fixed link")
    p.add_argument("--input", type=whole, help="with --train and --frame: the input link")
    p.add_argument("--output", type=whole, help="with --train and --frame: the output link")
    p.add_argument("--compound", default="", metavar="L,L", help="links that carry a wheel per mesh (stepped planets)")
    p.add_argument("--ratio", help="design tooth numbers for this speed ratio ω_in/ω_out, e.g. 4.25 or 17/4")
    p.add_argument("--tolerance", help="with --ratio: relative error allowed, below 100%%, e.g. 1%% (default) or 0.002")
    p.add_argument("--teeth", metavar="A..B", help="with --ratio: tooth numbers allowed (default 17..150)")
    p.add_argument("--min-teeth", type=whole, help="with --ratio: fewest teeth without undercut (default 17)")
    p.add_argument("--planets", type=whole, help="with --ratio: k equally spaced planets that assemble "
                   "((z_sun + z_ring)/k whole) and clear each other")
    p.add_argument("--best", type=whole, default=5, help="with --ratio: designs listed (default 5)")
    p.add_argument("--mesh-kinds", choices=("given", "free"),
                   help="with --ratio: 'free' lets each mesh be external or internal (either gear the ring), "
                        "'given' keeps the train's (default: free for the atlas, given for --train)")
    p.add_argument("-o", "--out", metavar="FILE", type=picture_file,
                   help="draw the functional schematics (.svg, .png, .pdf), checked before any work")
    p.add_argument("--limit", type=positive,
                   help=f"with --out: most schematics on one sheet (default {_SHEET}); a larger selection is refused")
    p.add_argument("--force", action="store_true", help="run a count or listing estimated to take more than a day")
    p.add_argument("--workers", type=workers, help="processes, at most the number of cores (default 1)")
    p.add_argument("--format", choices=FORMATS,
                   help="table (default), jsonl, csv or json; with --count json (default), table, jsonl or csv")
    p.set_defaults(run=_run)


def _check(args) -> None:
    from synth import InvalidOption

    ratio_only = [name for name in ("tolerance", "teeth", "min_teeth", "planets", "mesh_kinds")
                  if getattr(args, name) is not None]
    if ratio_only and args.ratio is None:
        raise InvalidOption(f"--{ratio_only[0].replace('_', '-')} goes with --ratio")
    if args.ratio is not None:  # (before the trains are enumerated)
        from synth.gears import ratio_and_tolerance

        ratio_and_tolerance(args.ratio, args.tolerance or "1%")
    if args.count and (args.ratio is not None or args.input_output or args.out):
        what = "--ratio" if args.ratio is not None else ("--input-output" if args.input_output else "--out")
        raise InvalidOption(f"--count and {what} contradict each other: --count prints one number per code")
    if args.count and args.format not in (None, *COUNT_FORMATS):
        raise InvalidOption(f"--count prints json, table, jsonl or csv, not {args.format}")
    if args.ratio is not None and args.graphs == "rotation":
        raise InvalidOption("--ratio designs displacement graphs (their mesh kinds and axes): drop --graphs rotation")
    if args.train is not None:
        for name in ("links", "dof"):
            if getattr(args, name) is not None:
                raise InvalidOption(f"--{name} selects trains of the atlas and contradicts --train")
        if args.graphs == "rotation" or args.count:
            raise InvalidOption("--train is one train: --count and --graphs rotation select from the atlas")
    else:
        for name in ("frame", "input", "output"):
            if getattr(args, name) is not None:
                raise InvalidOption(f"--{name} goes with --train (the atlas lists every choice with --input-output)")
        if args.links is None:
            raise InvalidOption("give --links N (and --dof F), or --train")
    if (args.input is None) != (args.output is None) or (args.input is not None and args.frame is None):
        raise InvalidOption("--input and --output go together, with --frame")
    if args.limit is not None and not args.out:
        raise InvalidOption("--limit goes with --out (it is the most schematics drawn on one sheet)")
    if args.force and (args.train is not None or args.ratio is not None):
        raise InvalidOption("--force goes with a count or listing of the atlas (one train or a ratio design is not sized)")
    if args.best < 1:
        raise InvalidOption(f"--best must be a whole number ≥ 1, not {args.best}")


def _compound(text: str) -> tuple[int, ...]:
    from synth import InvalidOption

    try:
        return tuple(int(x) for x in text.replace(",", " ").split())
    except ValueError:
        raise InvalidOption(f"--compound lists link numbers, e.g. 3,4, not {text!r}") from None


def _train_row(train, fmt: str) -> dict:
    """A train's listing row: ``code`` is its lever analogue's (as ``--count`` counts them), ``train_code``
    the train's own, with its meshes, as an atlas stores and captions it (530/1 and 230/1 G3)."""
    row = train.to_dict()
    chain = train.to_chain()
    row["train_code"] = str(chain.code) + chain.kind_suffix
    if fmt == "table":
        row["certificate"] = "…" + row["certificate"][-12:]
    return row


def _run(args) -> int:
    from synth import InvalidOption
    from synth.gears import check_query, count_trains, trains

    _check(args)
    dof = 1 if args.dof is None else args.dof
    compound = _compound(args.compound)
    if args.train is None:
        check_query(dof, args.links, args.graphs)
        if args.links < dof + 2:
            raise InvalidOption(f"a gear train with F = {dof} needs at least {dof + 2} links (one mesh), not {args.links}")
    if args.train is None and args.ratio is None:
        _size_note(args, dof)
    if args.count:
        result = count_trains(dof, args.links, args.graphs, workers=args.workers, progress=True)
        if write_count(result.to_dict(), args.format or "json") == 0:
            return nothing_found("gear trains satisfy these parameters")
        return 0
    if args.train is not None:
        from synth.gears import GearTrain

        items = [GearTrain.parse(args.train, args.frame)]
        for x in (args.frame, args.input, args.output):
            if x is not None and not 0 <= x < items[0].links:
                raise InvalidOption(f"link {x} is not a link of the train (0…{items[0].links - 1})")
    else:
        items = trains(dof, args.links, args.graphs, workers=args.workers, progress=args.ratio is None)
    if args.ratio is not None:
        return _run_ratio(args, items, compound)
    if args.input_output or args.input is not None:
        return _run_mechanisms(args, items, compound)
    fmt = args.format or "table"
    if args.out:
        items = list(items)
        _check_sheet(args, len(items), "gear trains")
    columns = ["index", "train", "code", "train_code", "dof", "carriers", "certificate"]
    n = write_rows(_indexed(_train_row(t, fmt) for t in items), columns, fmt)
    if fmt == "table":
        print((f"{n} gear trains ({args.graphs} graphs)" if args.train is None else f"{n} gear train")
              + "; code: the lever analogue's, train_code: the train's own, as an atlas lists and draws it")
    if args.out and n:
        _draw(items, args.out, compound)
    return 0 if n else nothing_found("gear trains satisfy these parameters")


def _size_note(args, dof: int) -> None:
    """Refuse an atlas query too large to run unasked, and say how long a long one takes (stderr)."""
    from synth.gears import size_check_trains

    note = size_check_trains(dof, args.links, args.graphs, processes=args.workers or 1, force=args.force,
                             table=not args.count and (args.format or "table") == "table")
    if note:
        print(f"mechsynth: {note}", file=sys.stderr)


def _check_sheet(args, n: int, what: str) -> None:
    """A sheet of more schematics than --limit is refused before anything is printed."""
    from synth import InvalidOption

    limit = args.limit or _SHEET
    if n > limit:
        count = f"{n:,}".replace(",", " ")
        raise InvalidOption(f"{count} {what} to draw, more than --limit {limit} on one sheet: draw fewer (one --train, "
                            "fewer --links, --graphs rotation) or raise --limit")


def _draw(items, out: str, compound, teeth=None, titles=None) -> None:
    from synth.draw import draw_train, draw_train_sheet

    if len(items) == 1:
        draw_train(items[0], out, teeth=teeth, compound=compound, title=titles[0] if titles else None)
    else:
        draw_train_sheet(items, out, limit=len(items), titles=titles)
    print(f"{len(items)} schematic{'s' * (len(items) != 1)} -> {out}", file=sys.stderr)  # as draw says


def _mechanisms_of(args, items, compound):
    from synth.gears import GearMechanism, mechanisms, speed_ratio

    for train in items:
        if args.input is not None:
            yield GearMechanism(train, args.frame, args.input, args.output,
                                speed_ratio(train, args.frame, args.input, args.output, compound))
        else:
            yield from mechanisms(train, input_output=True, compound=compound)


def _run_mechanisms(args, items, compound) -> int:
    fmt = args.format or "table"
    found = _mechanisms_of(args, items, compound)
    drawn = []
    if args.out:
        found = list(found)
        _check_sheet(args, len(found), "mechanisms")

    def rows():
        for m in found:
            drawn.append(m)
            row = m.to_dict()
            if fmt == "table":
                row["certificate"] = "…" + row["certificate"][-12:]
            yield row

    columns = ["index", "train", "frame", "input_link", "output_link", "ratio"]
    n = write_rows(_indexed(rows()), columns, fmt)
    if fmt == "table":
        print(f"{n} mechanism{'s' * (n != 1)} (ratio i = ω_input/ω_output, frame at rest; z<link> teeth of its wheel)")
    if args.out and drawn:
        from dataclasses import replace

        titles = [f"{k}: {m.train.compact()}: frame {m.frame}, input {m.input_link}, output {m.output_link}, "
                  f"i = {m.ratio.text}" for k, m in enumerate(drawn, start=1)]
        _draw([replace(m.train, frame=m.frame) for m in drawn], args.out, compound, titles=titles)
    return 0 if n else nothing_found("mechanisms with an input and an output on the frame")


def _run_ratio(args, items, compound) -> int:
    from tqdm import tqdm

    from synth import InvalidOption, parse_range

    if args.train is None and args.links > _RATIO_LINKS:
        raise InvalidOption(f"--ratio over every train of a size goes up to {_RATIO_LINKS} links: choose one with --train")
    lo, hi = parse_range(args.teeth or "17..150", "--teeth", minimum=1)
    if hi is None:
        raise InvalidOption("--teeth needs an upper end: give A..B")
    kinds = args.mesh_kinds or ("given" if args.train is not None else "free")
    items = list(items)  # the bar's total
    with tqdm(items, unit=" trains", file=sys.stderr, disable=None, delay=1.0, leave=False, desc="ratio design") as bar:
        kept = _best_designs(args, bar, compound, lo, hi, kinds)
    if not kept:  # a valid question without an answer: exit 1, as any query that matches nothing
        where = "this mechanism" if args.input is not None else "these trains"
        return nothing_found(f"tooth numbers in {lo}..{hi} give the ratio {args.ratio} within {args.tolerance or '1%'} "
                             f"in {where} (coaxial, assembly and undercut conditions)")
    designs = [(d, m) for *_, d, m in kept]
    fmt = args.format or "table"
    rows = []
    for d, m in designs:
        train = d.train or m.train
        formula = m.ratio if d.train is None else _formula(train, m, compound)
        row = {"train": train.compact(), "frame": m.frame, "input_link": m.input_link,
               "output_link": m.output_link, "formula": formula.text, **d.to_dict()}
        if fmt in ("table", "csv"):
            row["teeth"] = " ".join(f"{k}={v}" for k, v in d.teeth.items())
            row["error"] = f"{float(d.error):.3%}"
        rows.append(row)
    columns = ["index", "train", "frame", "input_link", "output_link", "teeth", "ratio", "error", "formula"]
    n = write_rows(_indexed(rows), columns, fmt)
    if fmt == "table":
        print(f"{n} best designs for i = {args.ratio} (error relative to it)")
    if args.out:
        from dataclasses import replace

        best, m = designs[0]
        train = replace(best.train or m.train, frame=m.frame)
        title = (f"{train.compact()}: frame {m.frame}, input {m.input_link}, output {m.output_link}\n"
                 f"i = ω{m.input_link}/ω{m.output_link} = {best.ratio} ≈ {float(best.ratio):.5g} "
                 f"(wanted {args.ratio}, error {float(best.error):.3%})")
        _draw([train], args.out, compound, teeth=best.teeth, titles=[title])
    return 0


def _best_designs(args, items, compound, lo: int, hi: int, kinds: str) -> list:
    """The ``--best`` designs over every mechanism of ``items``: (error, teeth sum, order, design,
    mechanism), the worst kept so far bounding the next searches."""
    from synth.gears import MIN_TEETH, NoDesign, RatioUnreached, design

    kept: list = []
    for order, m in enumerate(_mechanisms_of(args, items, compound)):
        beat = kept[-1][:2] if len(kept) >= args.best else None  # nothing worse can enter
        try:
            found = design(m.train, m.frame, m.input_link, m.output_link, args.ratio, tolerance=args.tolerance or "1%",
                           teeth=(lo, hi), min_teeth=MIN_TEETH if args.min_teeth is None else args.min_teeth,
                           planets=args.planets, compound=compound, best=args.best, kinds=kinds, beat=beat)
        except RatioUnreached:
            continue  # another mechanism may reach the ratio
        except NoDesign:  # the one mechanism asked cannot be designed so: say why
            if args.train is not None and args.input is not None:
                raise
            continue
        kept = sorted(kept + [(d.error, sum(d.teeth.values()), order, d, m) for d in found],
                         key=lambda x: x[:3])[:args.best]
    return kept


def _formula(train, m, compound):
    from synth.gears import speed_ratio

    return speed_ratio(train, m.frame, m.input_link, m.output_link, compound)


def _indexed(rows):
    for i, row in enumerate(rows, start=1):
        row["index"] = i
        yield row
