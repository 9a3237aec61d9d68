"""CLI command ``move``: a dimensioned mechanism moved through its input range.

The mechanism is a linkage file (.toml or .json: chain, frame, inputs, the position of every joint
in one assembled pose, sliding directions, gear ratios, tracer points) or any atlas mechanism
(``--chain … --frame F`` or ``--db … --id … --frame F``), dimensioned by its drawing.  The command
prints a row per step (input, every joint and tracer point, velocities and accelerations on
request), or with ``--range`` what a designer checks: crank or rocker and its limits, Grashof's
class, dead and toggle positions, transmission angles, the coupler curves' extent; ``--out`` draws
the coupler curves over the mechanism, ``--animate`` writes a GIF or an animated SVG.

Example
-------
>>> import os, tempfile
>>> from mechsynth.cli import main
>>> saved = os.path.join(tempfile.mkdtemp(), "four_bar.json")
>>> main(["move", "--chain", "0-1 1-2 2-3 3-0", "--frame", "0", "--save", saved])
0
>>> main(["move", saved, "--steps", "3", "--format", "jsonl"]) == 0 and len(open(saved).read()) > 0  # doctest: +ELLIPSIS
{"step": 0, ...}
...
True
"""

from __future__ import annotations

import argparse
import io
import json
import math
import os
import sys

from .._argtypes import add_row, chain_text, finite, mechanism_of, output_file, whole
from .._output import pairs, save_linkage, write_document, write_rows

__all__ = ["add_commands"]

#: the longest sweep (or largest grid) a command runs (rows are written as they come; the solver allows
#: more from Python)
MAX_STEPS = 1_000_000
#: a grid's default values per input
GRID_STEPS = 37


def _picture(text: str) -> str:
    return output_file(text, (".png", ".svg"), "the picture")


def _animation(text: str) -> str:
    return output_file(text, (".gif", ".svg"), "the animation")


def _saved(text: str) -> str:
    return output_file(text, (".toml", ".json"), "the linkage")


def _numbers(text: str) -> tuple[float, ...]:
    """One finite number, or one per input separated by commas (``80,100``)."""
    try:
        return tuple(finite(part) for part in text.split(","))
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"expected a finite number, or one per input separated by commas, not "
                                         f"{text!r}") from None


def _counts(text: str) -> tuple[int, ...]:
    """A number of steps, or one per input of a grid separated by x (``36x24``)."""
    try:
        out = tuple(int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of steps, or one per input like 36x24, not "
                                         f"{text!r}") from None
    return out


def add_commands(sub) -> None:
    """Mount ``move`` on the ``mechsynth`` parser."""
    p = sub.add_parser("move", help="move a dimensioned mechanism: positions, velocities, range, coupler curves, "
                                    "animations")
    p.add_argument("linkage", nargs="?", metavar="LINKAGE_FILE",
                   help="a linkage file (.toml or .json: chain, frame, inputs, points, slides, meshes, tracers), or "
                        "the rows of an atlas search (.json or .jsonl) with --row K")
    p.add_argument("--chain", type=chain_text("move"), help="any planar mechanism, as a joint list '0-1 1-2 2-3 3-0', dimensioned by its drawing")
    p.add_argument("--db", help="an atlas: the chain with --id, dimensioned by its drawing")
    p.add_argument("--id", help="with --db: the chain's id (12 hex digits, as listings and the site show it)")
    p.add_argument("--frame", type=whole, help="with --chain or --db: the fixed link")
    p.add_argument("--input", metavar="JOINT",
                   help="with --chain or --db: the input joint of the frame, e.g. 0-1 (default: a crank if one turns fully)")
    p.add_argument("--steps", type=_counts, help=f"input values, ends included (2 … {MAX_STEPS:,}; default 360); "
                   f"with W > 1 inputs a grid: one count for every input or one each, like 36x24 (default "
                   f"{GRID_STEPS} each)")
    p.add_argument("--start", type=_numbers, help="first input value: degrees for a revolute input, length for a "
                   "prismatic one (default: the pose's for a crank, the lower limit for a rocker); with W > 1 one "
                   "per input, like 80,100")
    p.add_argument("--stop", type=_numbers, help="last input value, as --start (default: one turn, or the upper "
                   "limit; a grid: half a turn (or the mechanism's size) each side of the pose)")
    p.add_argument("--velocities", action="store_true", help="add each joint's and tracer's velocity per unit input rate")
    p.add_argument("--accelerations", action="store_true", help="add each joint's and tracer's acceleration per unit input rate "
                   "squared (input turning steadily)")
    p.add_argument("--format", choices=("table", "jsonl", "csv", "json"),
                   help="rows per step (default table), or with --range: table or json")
    p.add_argument("--range", action="store_true", help="what a designer checks instead of rows: crank or rocker, "
                   "limits, Grashof, dead and toggle positions (of the whole branch), transmission angles and "
                   "curve extent (over --start … --stop where given), a crank-driven slider's stroke and quick-return "
                   "ratio; the table's angles in degrees, the JSON's in radians, a crank's within one turn "
                   "(0 … 360°, 0 … 2π) in both")
    p.add_argument("-o", "--out", type=_picture,
                   help="draw the coupler curves over the mechanism in its pose (.png or .svg)")
    p.add_argument("--animate", type=_animation, metavar="FILE", help="write an animation (.gif, or .svg that plays "
                   "in a browser)")
    p.add_argument("--frames", type=whole, help="with --animate: frames of the animation (2 … 1000, default 60)")
    p.add_argument("--save", type=_saved, metavar="FILE",
                   help="write the linkage (as dimensioned, e.g. from a drawing) to edit and reuse: .toml (a scene "
                        "that move, draw and scene read) or .json")
    add_row(p)
    p.set_defaults(run=_run)


def _check(args) -> None:
    """Every contradiction refused before any work."""
    from synth import InvalidOption

    sources = [name for name, given in (("a linkage file", args.linkage), ("--chain", args.chain), ("--db", args.db))
               if given]
    if len(sources) != 1:
        raise InvalidOption("give one mechanism: a linkage file, --chain TEXT --frame F, or --db FILE --id ID --frame F"
                            + (f" (not {' and '.join(sources)})" if sources else ""))
    if args.linkage and (args.frame is not None or args.input is not None):
        raise InvalidOption("--frame and --input go with --chain or --db; a linkage file names its frame and inputs")
    if args.row is not None and not args.linkage:
        raise InvalidOption("--row picks a row of a file of an atlas search's rows: give that file, not "
                            + ("--chain" if args.chain else "--db"))
    if args.id is not None and not args.db:
        raise InvalidOption("--id names a chain of an atlas: give --db too")
    if args.db and args.id is None:
        raise InvalidOption("--db needs --id ID: the chain of the atlas to move")
    if (args.chain or args.db) and args.frame is None:
        raise InvalidOption("--chain and --db need --frame F: the fixed link of the mechanism to move")
    if args.steps is not None and not (all(2 <= n <= MAX_STEPS for n in args.steps)
                                       and math.prod(args.steps) <= MAX_STEPS):
        raise InvalidOption(f"--steps must be 2 … {MAX_STEPS:,} in all (each input's count at least 2), not "
                            + "x".join(map(str, args.steps)))
    if args.frames is not None and not args.animate:
        raise InvalidOption("--frames goes with --animate (the animation's frames)")
    if args.frames is not None and not 2 <= args.frames <= 1000:
        raise InvalidOption(f"--frames must be 2 … 1000, not {args.frames}")
    if args.range and args.format in ("csv", "jsonl"):
        raise InvalidOption("--range prints one document: --format table or json, not " + args.format)
    if args.range and (args.velocities or args.accelerations):
        raise InvalidOption("--velocities and --accelerations add columns to the rows; --range prints no rows")
    pictures = [name for name, value in (("--out", args.out), ("--animate", args.animate), ("--save", args.save))
                if value]
    if (args.velocities or args.accelerations) and pictures and not (args.format or args.range):
        raise InvalidOption(f"--velocities and --accelerations add columns to the rows, and with {' and '.join(pictures)} "
                            "no rows are printed unless asked: add --format table, csv, jsonl or json")
    swept = [name for name, value in (("--steps", args.steps), ("--start", args.start), ("--stop", args.stop))
             if value is not None]
    if pictures == ["--save"] and swept and not (args.format or args.range):
        raise InvalidOption(f"--save alone writes the linkage and moves nothing, so {swept[0]} has no use: the sweep's "
                            "options go with rows (--format), --out, --animate or --range")
    if args.start is not None and args.stop is not None:
        if len(args.start) != len(args.stop):
            raise InvalidOption(f"--start gives {len(args.start)} value(s) and --stop {len(args.stop)}: one each per "
                                "input")
        if any(a == b for a, b in zip(args.start, args.stop)):
            raise InvalidOption(f"--start and --stop are both {next(a for a, b in zip(args.start, args.stop) if a == b):g}"
                                " for an input: a sweep needs two different ends")
    outputs = [os.path.realpath(p) for p in (args.out, args.animate, args.save) if p]
    if len(set(outputs)) != len(outputs):
        raise InvalidOption("two outputs name the same file: give --out, --animate and --save different files")
    if args.linkage and os.path.realpath(args.linkage) in outputs:
        raise InvalidOption(f"{args.linkage} is the linkage read: an output would overwrite it")


def _linkage(args):
    """The linkage the command moves, and where it came from (for the messages)."""
    from synth import Chain, InvalidOption
    from synth.motion import read_linkage
    from synth import linkage_from_layout

    if args.linkage:
        return read_linkage(args.linkage, row=args.row)
    if args.chain:
        chain = Chain.parse(args.chain)
    else:
        from synth.atlas import export

        rows = list(export(args.db, "chains", where=[f"id={args.id}"]))
        if not rows:
            raise InvalidOption(f"the atlas {args.db} has no chain with id {args.id}")
        chain = Chain.from_dict(rows[0])
    return linkage_from_layout(mechanism_of(chain, args.frame, args.input))


def _run(args) -> int:
    from synth.motion import motion_range, sweep
    from synth import JointKind

    _check(args)
    linkage = _linkage(args)
    _check_inputs(args, linkage)
    if linkage.note and not args.linkage:  # a file's note tells what was done when it was saved, not now
        print(f"mechsynth: note: {linkage.note}", file=sys.stderr)
    if args.save:
        save_linkage(linkage, args.save, source="mechsynth move", description=f"{linkage.chain.compact()}, frame "
                     f"{linkage.frame}, saved by 'mechsynth move'")
    if linkage.dof != 1:
        return _grid(linkage, args)
    revolute = linkage.kind(linkage.inputs[0]) == JointKind.REVOLUTE
    start, stop = (None if v is None else (math.radians(v[0]) if revolute else v[0]) for v in (args.start, args.stop))
    steps = args.steps[0] if args.steps else 360
    rows_only = not (args.out or args.animate or args.range or args.save)
    if rows_only and steps > _CHUNK:
        return _write_long_sweep(linkage, args, steps, start, stop)
    motion = sweep(linkage, steps=steps, start=start, stop=stop, velocities=args.velocities,
                   accelerations=args.accelerations)
    if motion.stopped:
        print(f"mechsynth: {motion.stopped}", file=sys.stderr)
    if args.out:
        from synth import draw_motion

        draw_motion(motion, args.out)
        print(f"coupler curves -> {args.out}", file=sys.stderr)
    if args.animate:
        from synth import animate_motion

        frames = animate_motion(motion, args.animate, frames=args.frames or 60, progress=sys.stderr.isatty())
        print(f"{frames} frames -> {args.animate}", file=sys.stderr)
    if args.range:
        _write_range(linkage, motion_range(linkage), motion, args.format or "table")
    elif args.format or not (args.out or args.animate or args.save):
        rows = motion.rows()
        first = next(rows, None)
        if first is None:
            print("mechsynth: the sweep has no step", file=sys.stderr)
            return 1
        import itertools

        write_rows(itertools.chain([first], rows), list(first), args.format or "table")
    return 0


#: a long sweep's rows are computed this many steps at a time, so Ctrl-C is seen between pieces; a
#: table of more rows is refused (it is held in memory to align its columns)
_CHUNK = 20_000


def _check_inputs(args, linkage) -> None:
    """What depends on the linkage's number of inputs W, refused before anything is written."""
    from synth import InvalidOption

    w = linkage.dof
    if w == 1:
        if args.steps is not None and len(args.steps) != 1:
            raise InvalidOption(f"this linkage has one input: --steps is one count, not {'x'.join(map(str, args.steps))}")
        for name, given in (("--start", args.start), ("--stop", args.stop)):
            if given is not None and len(given) != 1:
                raise InvalidOption(f"this linkage has one input: {name} is one value, not {len(given)}")
        steps = args.steps[0] if args.steps else 360
    else:
        if args.range or args.animate or args.accelerations:
            option = "--range" if args.range else "--animate" if args.animate else "--accelerations"
            raise InvalidOption(f"this linkage has W = {w} inputs, moved over a grid: {option} is for one input "
                                "(a grid gives rows, velocities and a picture of the workspace, --out)")
        if args.steps is not None and len(args.steps) not in (1, w):
            raise InvalidOption(f"this linkage has W = {w} inputs: --steps is one count for each or {w} counts like "
                                + "x".join(["24"] * w) + f", not {'x'.join(map(str, args.steps))}")
        for name, given in (("--start", args.start), ("--stop", args.stop)):
            if given is not None and len(given) != w:
                raise InvalidOption(f"this linkage has W = {w} inputs: {name} takes one value per input separated by "
                                    f"commas ({w} values), not {len(given)}")
        if (args.start is None) != (args.stop is None):
            raise InvalidOption("a grid's ranges need both --start and --stop (one value per input each), or neither")
        steps = math.prod(_grid_counts(args, w))
        if steps > MAX_STEPS:
            raise InvalidOption(f"the grid has {steps:,} steps; at most {MAX_STEPS:,}")
    if steps > _CHUNK and (args.format or "table") == "table" and not (args.out or args.animate or args.range
                                                                      or args.save):
        raise InvalidOption(f"a table of {steps:,} rows is held in memory to align it: use --format jsonl or csv "
                            "(written as they come)")


def _grid_counts(args, w: int) -> tuple[int, ...]:
    """A grid's values per input: --steps given once for all, or one each, or the default."""
    return args.steps * w if args.steps and len(args.steps) == 1 else args.steps or (GRID_STEPS,) * w


def _grid(linkage, args) -> int:
    """A linkage of W > 1 inputs moved over a grid of them: rows per grid point, the workspace drawn."""
    import numpy as np
    from tqdm import tqdm

    from synth import JointKind
    from synth.motion import sweep_grid

    w = linkage.dof
    revolute = [linkage.kind(k) == JointKind.REVOLUTE for k in linkage.inputs]
    counts = _grid_counts(args, w)
    if args.start is None:  # half a turn (or the mechanism's size) each side of the pose
        half = [math.pi if r else linkage.scale for r in revolute]
        ranges = [(v - h, v + h) for v, h in zip(linkage.pose_inputs, half)]
    else:
        ranges = [(math.radians(a), math.radians(b)) if r else (a, b)
                  for a, b, r in zip(args.start, args.stop, revolute)]
    with tqdm(total=math.prod(counts), unit="cell", file=sys.stderr, desc="move",
              disable=not sys.stderr.isatty()) as bar:
        motion = sweep_grid(linkage, ranges, steps=list(counts), velocities=args.velocities, progress=bar.update)
    reached = int(np.isfinite(motion.joints).all(axis=(1, 2)).sum())
    print(f"mechsynth: {reached:,} of {motion.steps:,} grid points are on the branch of the pose (the rest are "
          "written without positions)", file=sys.stderr)
    if args.out:
        from synth.motion_draw import draw_motion

        draw_motion(motion, args.out)
        print(f"workspace -> {args.out}", file=sys.stderr)
    if args.format or not (args.out or args.save):
        rows = motion.rows()
        first = next(rows)
        import itertools

        write_rows(itertools.chain([first], rows), list(first), args.format or "table")
    return 0


def _write_long_sweep(linkage, args, steps: int, start: float | None, stop: float | None) -> int:
    """Rows of a sweep of more than :data:`_CHUNK` steps, computed and written piece by piece with a
    progress bar: each piece continues the branch from the pose to its first input (the same
    inputs as one sweep: ``start + i·(stop − start)/(steps − 1)``), and the run stops at a dead
    position as one sweep does.  A piece takes well under a second, so Ctrl-C stops it within two."""
    from tqdm import tqdm

    from synth.motion import motion_range, sweep

    if start is None or stop is None:  # the default range of one sweep: a crank's turn, a rocker's limits
        reach = motion_range(linkage)
        if reach.full_rotation:
            low, high = float(linkage.pose_inputs[0]), float(linkage.pose_inputs[0]) + 2 * math.pi
        else:
            low, high = reach.limits
        start = low if start is None else start
        stop = high if stop is None else stop
    fmt = args.format or "table"
    step = (stop - start) / (steps - 1)
    written, columns = 0, None
    with tqdm(total=steps, unit="step", file=sys.stderr, desc="move", disable=not sys.stderr.isatty()) as bar:
        while written < steps:
            count = min(_CHUNK, steps - written)
            first = start + written * step
            piece = sweep(linkage, steps=max(count, 2), start=first,
                          stop=first + (count - 1) * step if count > 1 else first + step,
                          velocities=args.velocities, accelerations=args.accelerations)
            rows = list(piece.rows())[:count]
            for row in rows:
                row["step"] += written
            if columns is None:
                columns = list(rows[0]) if rows else []
                if fmt == "json":
                    sys.stdout.write("[")
            _write_piece(rows, columns, fmt, written)
            written += len(rows)
            bar.update(len(rows))
            if piece.stopped:
                print(f"mechsynth: {piece.stopped}", file=sys.stderr)
                break
    if fmt == "json":
        sys.stdout.write("]\n")
    return 0


def _write_piece(rows: list[dict], columns: list[str], fmt: str, before: int) -> None:
    """One piece of a long sweep's rows, continuing the output of the pieces before it."""
    if fmt == "json":
        sys.stdout.write("".join(("" if before == 0 and i == 0 else ",\n ") + json.dumps(row)
                                 for i, row in enumerate(rows)))
    elif fmt == "csv":
        buffer = io.StringIO()
        write_rows(rows, columns, "csv", buffer)
        text = buffer.getvalue()
        sys.stdout.write(text if before == 0 else text.split("\n", 1)[1])
    else:
        write_rows(rows, columns, fmt)


#: why a linkage moved by Newton's method reports no transmission angle
_NO_TRANSMISSION = ("not reported: the linkage does not decompose into dyads (it has a group of class III or higher, "
                    "moved by Newton's method), and a transmission angle is defined here for a dyad's two links only")


def _write_range(linkage, reach, motion, fmt: str) -> None:
    """The range document: JSON, or a two-column table."""
    from synth.motion import joint_name
    from synth import JointKind

    k = linkage.inputs[0]
    revolute = linkage.kind(k) == JointKind.REVOLUTE
    turns = revolute and reach.full_rotation  # a crank's positions are angles of one turn: 0 … 360°
    unit = (lambda v: math.degrees(v) % 360.0 if turns else math.degrees(v)) if revolute else (lambda v: v)

    def shown(v: float, digits: int = 6) -> str:
        """An input as printed; a crank's angle in one turn, so a full turn (359.9999993°) reads 0, not 360."""
        text = f"{unit(v):.{digits}g}"
        return "0" if turns and float(text) == 360.0 else text
    word = "°" if revolute else ""

    def unit_input(v: float) -> float:
        """An input as the JSON gives it: a crank's angle within one turn, 0 … 2π, as the table's."""
        return v % math.tau if turns else v
    doc = {"input": joint_name(linkage.chain, k), "kind": linkage.kind(k), "full_rotation": reach.full_rotation,
           "limits": list(reach.limits) if reach.limits else None, "grashof": reach.grashof,
           "dead_positions": [{"input": unit_input(v), "why": why} for v, why in reach.dead_positions],
           "toggles": [{"input": unit_input(v), "link": link} for v, link in reach.toggles],
           "transmission": {name: {**t, "at_min": unit_input(t["at_min"]), "at_max": unit_input(t["at_max"]),
                                   "worst": min(t["min"], math.pi - t["max"])}  # (how far from a dead position)
                            for name, t in motion.transmission.items()},
           "extent": {n: list(e) for n, e in motion.extent().items()},
           "strokes": {str(link): {"pair": joint_name(linkage.chain, pair), "stroke": s.length,
                                   "quick_return_ratio": s.quick_return_ratio,
                                   "dead_centres": [unit_input(s.far), unit_input(s.near)]}
                       for pair, link, s in _strokes(linkage, reach)},
           "stopped": motion.stopped}
    if not motion.transmission:
        doc["transmission_note"] = _NO_TRANSMISSION
    if fmt == "json":
        write_document(doc, "json", "")
        return
    if reach.full_rotation:
        motion_text = "turns fully (a crank)"
    elif reach.limits:
        motion_text = f"rocks between {shown(reach.limits[0])}{word} and {shown(reach.limits[1])}{word}"
    else:
        motion_text = "does not move"
    lines = [("input", f"{doc['input']} ({doc['kind']})"), ("motion", motion_text)]
    if reach.grashof:
        lines.append(("Grashof", reach.grashof))
    for v, why in reach.dead_positions:
        lines.append(("dead position", f"{shown(v, 10)}{word}: {why}"))
    for v, link in reach.toggles:
        lines.append(("toggle", f"{shown(v, 10)}{word}: link {link} stops and turns back"))
    if not motion.transmission:
        lines.append(("transmission", _NO_TRANSMISSION))
    for name, t in doc["transmission"].items():
        lines.append((f"transmission {name}", f"min {math.degrees(t['min']):.4g}° at input {shown(t['at_min'])}{word}, "
                                               f"max {math.degrees(t['max']):.4g}° at {shown(t['at_max'])}{word}; "
                                               f"worst {math.degrees(t['worst']):.4g}°"))
    for name, (x0, y0, x1, y1) in doc["extent"].items():
        lines.append((f"curve {name}", f"x {x0:.6g} … {x1:.6g}, y {y0:.6g} … {y1:.6g}"))
    for link, s in doc["strokes"].items():
        far, near = s["dead_centres"]
        lines.append((f"slider {link} ({s['pair']})", f"stroke {s['stroke']:.6g} between the dead centres at input "
                      f"{shown(far)}° and {shown(near)}°; quick-return ratio {s['quick_return_ratio']:.6g}"))
    write_document(doc, "table", pairs(lines))


def _strokes(linkage, reach) -> list:
    """(pair, slider link, :class:`~mechsynth._slider_stroke.Stroke`) of each slider on the frame driven by a
    crank, measured on a turn of the solver as the scene's closed form of a slider-crank measures them."""
    from synth import JointKind
    from synth.motion import sweep

    from .._slider_stroke import slider_stroke, sliders_on_frame

    if not (reach.full_rotation and linkage.kind(linkage.inputs[0]) == JointKind.REVOLUTE):
        return []
    found = sliders_on_frame(linkage)
    turn = sweep(linkage, steps=360) if found else None
    return [(pair, link, slider_stroke(linkage, turn, pin, linkage.slides[pair])) for pair, link, pin in found]
