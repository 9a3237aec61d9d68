"""CLI command ``dimension``: the dimensions with which a given mechanism meets a target — a path
(with or without timing), a function (input–output angles, or a slider's displacement against an
angle) or poses of a body.

The target is a CSV or JSON file (columns ``x,y`` / ``x,y,input`` / ``input,output`` / ``x,y,angle``,
``input_deg,output_displacement`` or ``input_displacement,output_deg`` for a slider's side, a ``*_deg``
column in degrees, and last an optional ``weight`` column); the topology is a linkage file
(its pose is a first guess) or a joint list with ``--frame`` and ``--input``.  The result is printed as a table or JSON, saved as a
linkage file that ``move`` and ``scene`` read, and drawn over the target.

Example
-------
>>> import os, tempfile
>>> from mechsynth.cli import main
>>> folder = tempfile.mkdtemp()
>>> target = os.path.join(folder, "function.csv")
>>> _ = open(target, "w").write("input_deg,output_deg\\n40,70\\n60,85\\n80,105\\n")
>>> main(["dimension", target, "--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0", "--budget", "5",
...       "--format", "jsonl"])  # doctest: +ELLIPSIS
{"kind": "function", ...}
0
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys

from mechbase import finite_pair

from .._argtypes import add_row, finite, mechanism_of, number_range, output_file, positive, seconds, whole, workers
from .._output import pairs, save_linkage, write_document

__all__ = ["add_commands"]


def _picture(text: str) -> str:
    return output_file(text, (".png", ".svg"), "the picture")


def _saved(text: str) -> str:
    return output_file(text, (".toml", ".json"), "the linkage")


def _limits(text: str) -> tuple[float, float]:
    """``A..B``: two finite numbers, A < B (read as every range of numbers is: ``number_range``)."""
    lo, hi = number_range(text)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise argparse.ArgumentTypeError(f"expected finite numbers, not {text!r}")
    if not lo < hi:
        raise argparse.ArgumentTypeError(f"expected A..B with A < B, not {text!r}")
    return lo, hi


def _box(text: str) -> tuple[float, float, float, float]:
    """``x0..x1,y0..y1``."""
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected x0..x1,y0..y1, not {text!r}")
    (x0, x1), (y0, y1) = (_limits(p) for p in parts)
    return x0, x1, y0, y1


def _held(text: str) -> tuple[str, tuple[float, float]]:
    """``J=x,y``: a joint held at a point."""
    joint, _, at = text.rpartition("=")
    expected = f"expected JOINT=x,y with finite x and y, e.g. 0-1=0,0, not {text!r}"
    if not joint:
        raise argparse.ArgumentTypeError(expected)
    return joint, finite_pair(at.split(","), error=argparse.ArgumentTypeError, malformed=expected)


def add_commands(sub) -> None:
    """Mount ``dimension`` on the ``mechsynth`` parser."""
    p = sub.add_parser("dimension", help="dimensional synthesis: the dimensions with which a mechanism traces a path, "
                                         "generates a function or guides a body")
    p.add_argument("target", metavar="TARGET", help="a .csv or .json target: columns x,y (a path), x,y,input (timed "
                   "path), input,output (a function; input_displacement or output_displacement for a slider on the "
                   "frame) or x,y,angle (a motion); a *_deg column is in degrees; a last column weight: how much each "
                   "row counts")
    p.add_argument("--linkage", metavar="FILE", help="the mechanism as a linkage file (.toml or .json); its pose is a "
                   "first guess")
    p.add_argument("--mechanism", metavar="CHAIN", help="the mechanism as a joint list, e.g. '0-1 1-2 2-3 3-0'")
    p.add_argument("--frame", type=whole, help="with --mechanism: the fixed link")
    p.add_argument("--input", metavar="JOINT", help="with --mechanism: the input joint of the frame, e.g. 0-1 "
                   "(default: the frame's first revolute joint)")
    p.add_argument("--tracer-link", type=whole, metavar="L", help="the link carrying the tracer point P (path, "
                   "motion; default the coupler)")
    p.add_argument("--output-link", type=whole, metavar="L", help="a function's output link, pivoted or sliding on "
                   "the frame (default: the only other one)")
    p.add_argument("--displacement-origin", choices=("pivot", "free"), help="where a slider's displacements are "
                   "measured from: the foot of the other pivot on the slider's line (default), or a point the "
                   "synthesis chooses (the target's own zero)")
    p.add_argument("--crank", action="store_true", help="the input must turn fully")
    p.add_argument("--rocker", type=_limits, metavar="A..B", help="the input must stay within A..B (degrees; "
                   "length for a slide) over the target")
    p.add_argument("--min-transmission", type=finite, metavar="DEG", help="least transmission angle of every "
                   "dyad over the target (over the turn for a crank), degrees (default: none)")
    p.add_argument("--max-ratio", type=finite, metavar="R", help="bound on the longest over the shortest "
                   "distance between two joints of one link (default: none)")
    p.add_argument("--max-length", type=finite, metavar="L", help="bound on every distance between two joints of "
                   "one link, the frame's pivots included (target units; default: none)")
    p.add_argument("--pivots", type=_box, metavar="x0..x1,y0..y1", help="a box the frame's joints must lie in, in "
                   "target units (the target's x, y)")
    p.add_argument("--pivot-at", type=_held, action="append", metavar="J=x,y", help="hold the frame's revolute "
                   "joint J at the point (x, y) in target units, e.g. 0-1=0,0 (repeatable)")
    p.add_argument("--frame-angle", type=finite, metavar="DEG", help="the frame line's direction (degrees from the x "
                   "axis): from the input pivot to --frame-line (default: free)")
    p.add_argument("--frame-line", metavar="JOINT", help="the frame line's far joint (default: the frame's only "
                   "other joint), for --frame-angle or --timing absolute")
    p.add_argument("--timing", choices=("relative", "absolute"), default="relative", help="a timed path's inputs "
                   "counted from the first point's (relative, default) or the crank's angles from the frame line "
                   "(absolute; the frame's direction free unless --frame-angle)")
    p.add_argument("--order", action="append", metavar="ORDER", help="a link-length order, e.g. 'r2<=r3<=r4<=r1' "
                   "(a four-bar's frame, input, coupler, output) or '1<=2<=3<=0' in link numbers (repeatable)")
    p.add_argument("--reach", type=finite, help="the search box: joints within this many target "
                   "sizes of its centre (default 4; a function: frame lengths, default 2)")
    p.add_argument("--underdetermined", action="store_true", help="allow fewer target equations than unknowns "
                   "(one of infinitely many exact solutions is returned); refused for a target that gives enough "
                   "(with --db: for the topologies that need it, refused when none of those searched does)")
    p.add_argument("--budget", type=seconds, default=60.0, help="CPU seconds of the search (default 60; with --db "
                   "shared by the topologies; of one mechanism with --workers N > 1 or --scheduler, wall-clock seconds)")
    p.add_argument("--seed", type=whole, default=0, help="seed of the search (default 0)")
    p.add_argument("--workers", type=workers, default=None, help="local processes evaluating the global search's "
                   "generations, or (with --db) polishing the topologies (default 1)")
    p.add_argument("--format", choices=("table", "json", "jsonl"), default="table", help="table (default), json "
                   "(the result with its linkage) or jsonl (one row with its linkage; with --db a row per topology, "
                   "each with its linkage)")
    p.add_argument("--save", type=_saved, metavar="FILE", help="write the linkage found (.toml: a scene that move "
                   "and scene read; or .json); with --db the best row's, or row K's with --row K")
    p.add_argument("-o", "--out", type=_picture, metavar="FILE", help="draw the mechanism over the target and its "
                   "curve (.png or .svg); with --db a sheet, a panel per row")
    p.add_argument("--db", metavar="ATLAS", help="search every topology of this atlas (its curve index: 'mechsynth "
                   "atlas --db ATLAS --index-curves') instead of one mechanism; a closed path's target only")
    p.add_argument("--links", metavar="A..B", help="with --db: only mechanisms with this many links, e.g. 4..6")
    p.add_argument("--top", type=positive, default=5, metavar="K", help="with --db: topologies polished (default 5; "
                   "the best of every link count is always among them)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="run the global search's generations (with --db: the "
                   "topologies' polish) on a Dask scheduler, tcp://HOST:PORT")
    add_row(p, "; with --db and --save, the row saved (default 1)")
    p.set_defaults(run=_run)


def _check(args) -> None:
    """Every contradiction refused before any work."""
    from synth import InvalidOption

    if args.db is None:
        alone = [name for name, value in (("--links", args.links), ("--top", args.top != 5)) if value]
        if alone:
            raise InvalidOption(f"{', '.join(alone)} go{'es' * (len(alone) == 1)} with --db (the search over an atlas)")
    else:
        from .dimension_atlas import check

        check(args)
        named = [flag for flag, value in (("--pivot-at", args.pivot_at), ("--frame-angle", args.frame_angle is not None),
                                          ("--frame-line", args.frame_line), ("--timing absolute",
                                                                              args.timing == "absolute"),
                                          ("--order", args.order)) if value]
        if named:
            raise InvalidOption(f"{', '.join(named)} name joints, links or the frame of one mechanism: they do not go "
                                "with --db (every topology of the atlas)")
    if args.scheduler is not None and args.workers is not None:
        raise InvalidOption("--workers and --scheduler contradict each other: the scheduler's workers do the work")
    args.workers = args.workers or 1
    if args.db is None and bool(args.linkage) == bool(args.mechanism):
        raise InvalidOption("give one mechanism: --linkage FILE, or --mechanism CHAIN --frame F"
                            + (" (not both)" if args.linkage else ""))
    if args.linkage and (args.frame is not None or args.input is not None):
        raise InvalidOption("--frame and --input go with --mechanism; a linkage file names its frame and input")
    if args.row is not None and not args.linkage and not (args.db and args.save):
        raise InvalidOption("--row picks the start of the search from a file of an atlas search's rows: it goes with "
                            "--linkage ROWS.json" + (" (with --db, it picks the row --save writes: give --save FILE)"
                                                     if args.db else ""))
    if args.mechanism and args.frame is None:
        raise InvalidOption("--mechanism needs --frame F: the fixed link")
    if args.crank and args.rocker:
        raise InvalidOption("--crank and --rocker contradict each other: the input turns fully or rocks within limits")
    if args.min_transmission is not None and not 0 < args.min_transmission < 90:
        raise InvalidOption(f"--min-transmission must be between 0 and 90 degrees, not {args.min_transmission:g}")
    if args.max_ratio is not None and not args.max_ratio > 1:
        raise InvalidOption(f"--max-ratio must be above 1 (the longest over the shortest), not {args.max_ratio:g}")
    if args.max_length is not None and not args.max_length > 0:
        raise InvalidOption(f"--max-length must be a positive length (target units), not {args.max_length:g}")
    if args.reach is not None and not args.reach > 0:
        raise InvalidOption(f"--reach must be a positive number of target sizes, not {args.reach:g}")
    if args.seed < 0:
        raise InvalidOption(f"--seed must be a whole number ≥ 0, not {args.seed}")
    outputs = [os.path.realpath(p) for p in (args.out, args.save) if p]
    if len(set(outputs)) != len(outputs):
        raise InvalidOption("--out and --save name the same file: give them different files")
    for given in (args.target, args.linkage):
        if given and os.path.realpath(given) in outputs:
            raise InvalidOption(f"{given} is read by this command: an output would overwrite it")


def _mechanism(args):
    """The linkage or mechanism to dimension."""
    from synth import Chain
    from synth.motion import read_linkage

    if args.linkage:
        return read_linkage(args.linkage, row=args.row)
    chain = Chain.parse(args.mechanism)
    return mechanism_of(chain, args.frame, args.input)


def _run(args) -> int:
    from tqdm import tqdm

    from synth.atlas import sampled_starts
    from synth.dimension import Constraints, read_target, synthesize

    _check(args)
    target = read_target(args.target, output_link=args.output_link, origin=args.displacement_origin or "pivot")
    if args.displacement_origin is not None and not (target.kind == "function" and "displacement" in
                                                     (target.input_is, target.output_is)):
        from synth import InvalidOption

        raise InvalidOption("--displacement-origin is where a slider's displacements are measured from; this target "
                            "gives none (no input_displacement or output_displacement column)")
    if args.output_link is not None and target.kind != "function":
        from synth import InvalidOption

        raise InvalidOption("--output-link names a function's output; this target is a " + target.kind)
    if args.tracer_link is not None and target.kind == "function":
        from synth import InvalidOption

        raise InvalidOption("--tracer-link names the link of a path's or motion's tracer; this target is a function")
    if args.db is not None:
        from .dimension_atlas import run

        constraints = Constraints(crank=args.crank, rocker=args.rocker and tuple(math.radians(v) for v in args.rocker),
                                  min_transmission=math.radians(args.min_transmission or 0.0),
                                  max_ratio=args.max_ratio, max_length=args.max_length, pivots=args.pivots,
                                  reach=args.reach, **_placing(args))
        return run(args, target, constraints, save=_save, draw=_draw_rows)
    mechanism = _mechanism(args)
    constraints = Constraints(crank=args.crank, rocker=args.rocker and _rocker(mechanism, args.rocker),
                              min_transmission=math.radians(args.min_transmission or 0.0), max_ratio=args.max_ratio,
                              max_length=args.max_length, pivots=args.pivots, reach=args.reach, **_placing(args))
    if args.underdetermined:
        _check_underdetermined(mechanism, target, args.tracer_link, constraints)
    with tqdm(total=round(args.budget, 1), unit="s", file=sys.stderr, desc="dimension", leave=False,
              bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.1f}/{total:.1f} s{postfix}",
              disable=not sys.stderr.isatty()) as bar:
        def progress(used: float, cost: float) -> None:
            bar.n = round(used, 1)
            bar.set_postfix_str(f"best {math.sqrt(cost):.3g}" if cost < 1e3 else "")

        result = synthesize(mechanism, target, tracer_link=args.tracer_link, constraints=constraints,
                            budget=args.budget, seed=args.seed, workers=args.workers, scheduler=args.scheduler,
                            underdetermined=args.underdetermined, progress=progress, starts=sampled_starts)
    _write(result, args.format, wall=args.workers > 1 or bool(args.scheduler))
    if result.on_reach and result.relative_max > 1e-9:
        print(f"mechsynth: {' and '.join(result.on_reach)} lie{'s' * (len(result.on_reach) == 1)} on the edge of the "
              f"search's reach (--reach, in target sizes): a larger reach may lower the error", file=sys.stderr)
    if not result.met:
        print(f"mechsynth: no mechanism met the constraints within the budget; the best found fails: "
              f"{'; '.join(result.failed())} (nothing saved or drawn)", file=sys.stderr)
        return 1
    if args.save:
        _save(result, args.save)
        print(f"linkage -> {args.save}", file=sys.stderr)
    if args.out:
        _draw(result, args.out)
        print(f"picture -> {args.out}", file=sys.stderr)
    return 0


def _check_underdetermined(mechanism, target, tracer_link, constraints) -> None:
    """Refuse --underdetermined where the target gives as many equations as the synthesis has unknowns."""
    from synth import InvalidOption
    from synth.dimension import equations_and_unknowns

    equations, unknowns = equations_and_unknowns(mechanism, target, tracer_link=tracer_link, constraints=constraints)
    if equations >= unknowns:
        raise InvalidOption(f"--underdetermined allows fewer target equations than unknowns, and this target gives "
                            f"{equations} equations for the {unknowns} unknowns of this {target.kind} synthesis: "
                            "drop it")


def _placing(args) -> dict:
    """The fixed pivots, the frame's direction, the timing and the link-length orders as Constraints' keywords."""
    held = dict(args.pivot_at or ())
    if len(held) != len(args.pivot_at or ()):
        from synth import InvalidOption

        raise InvalidOption("--pivot-at names one joint twice: hold each pivot at one point")
    return {"pivot_at": held, "frame_angle": None if args.frame_angle is None else math.radians(args.frame_angle),
            "frame_line": args.frame_line, "timing": args.timing, "order": tuple(args.order or ())}


def _rocker(mechanism, limits: tuple[float, float]) -> tuple[float, float]:
    """The rocker's limits in the input's unit: degrees to radians for a revolute input."""
    from synth import JointKind
    from synth.motion import Linkage

    chain = mechanism.chain
    if isinstance(mechanism, Linkage):
        k = mechanism.inputs[0]
    else:
        k = next(k for k, j in enumerate(chain.joints) if mechanism.frame in j and len(j) == 2
                 and (mechanism.input_link is None or mechanism.input_link in j))
    return tuple(math.radians(v) for v in limits) if chain.kinds[k] == JointKind.REVOLUTE else limits


def _write(result, fmt: str, wall: bool = False) -> None:
    """The result as a table, json or a jsonl row; ``wall``: its seconds are the clock's (generations on workers)."""
    from synth import JointKind
    from synth.motion import joint_name

    if fmt == "jsonl":  # with its linkage, as the atlas search's rows: move, draw and balance linkage read it
        sys.stdout.write(json.dumps({**result.row(), "linkage": result.linkage.to_dict()}) + "\n")
        return
    if fmt == "json":
        write_document(result.to_dict(), "json", "")
        return
    lk = result.linkage
    unit = "rad" if result.kind == "function" and result.target.output_is == "angle" else "target units"
    lines = [("mechanism", f"{lk.chain.compact()}, frame {lk.frame}, input {joint_name(lk.chain, lk.inputs[0])}"),
             ("target", f"{result.kind}, {len(result.errors)} points, size {result.size:.6g}"),
             (f"error max ({unit})", result.error_max), (f"error rms ({unit})", result.error_rms),
             ("relative max", result.relative_max), ("relative rms", result.relative_rms)]
    if result.weights is not None:
        lines[3] = (f"error rms ({unit}, each point once)", result.error_rms)
        lines.append((f"weighted sum of squares ({unit}², Σ weight × error²)", result.weighted_sum_squares))
    if result.angle_errors is not None:
        lines.append(("angle error max (deg)", math.degrees(float(result.angle_errors.max()))))
    revolute = lk.chain.kinds[lk.inputs[0]] == JointKind.REVOLUTE
    for name, c in result.constraints.items():
        unit, value, limit = _UNITS.get(name, ""), c["value"], c["limit"]
        if name == "rocker":  # the library's radians (or lengths), in the option's degrees
            unit = "°" if revolute else _UNITS["length"]
            if revolute:
                value, limit = [math.degrees(v) for v in value], [math.degrees(v) for v in limit]
        lines.append((f"constraint {name}", f"{'met' if c['met'] else 'NOT met'}: {_value(value)}{unit}"
                      + (f" (limit {_value(limit)}{unit})" if limit is not None else "")))
    for k in range(len(lk.chain.joints)):
        lines.append((f"joint {joint_name(lk.chain, k)}", f"{lk.points[k][0]:.10g}, {lk.points[k][1]:.10g}"))
    for name, (link, at) in lk.tracers.items():
        lines.append((f"tracer {name} (link {link})", f"{at[0]:.10g}, {at[1]:.10g}"))
    for link, length in sorted(lk.lengths().items()):
        lines.append((f"link {link} length", length))
    lines += [("seconds (wall clock: the search ran on workers)" if wall else "CPU seconds", result.seconds), ("evaluations", result.evaluations), ("method", result.method)]
    write_document({}, "table", pairs(lines))


_UNITS = {"transmission": "°", "frame_angle": "°", "length": " target units"}  # a constraint's value and limit


def _value(v) -> str:
    """A constraint's value as the table shows it.

    >>> _value({"0-1": [0.0, 1.5]}), _value([[2.08576123, 2.2753]])
    ('0-1 at [0, 1.5]', '[[2.08576, 2.2753]]')
    """
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):  # pivots held at points
        return ", ".join(f"{k} at {_value(x)}" for k, x in v.items())
    return str(v)


def _save(result, path: str) -> None:
    """The linkage found, as JSON or as a TOML scene that says how it was found."""
    save_linkage(result.linkage, path, source="mechsynth dimension", description="a linkage found by dimensional "
                 "synthesis", comment=f"Found by 'mechsynth dimension': {result.kind} target of {len(result.errors)} "
                 f"points, error max {result.error_max:.6g} (relative {result.relative_max:.3g}).")


def _swept(result):
    """The found mechanism swept over its range (721 steps), and the target's points to mark (none for a function)."""
    from synth.motion import motion_range, sweep

    lk = result.linkage
    reach = motion_range(lk)
    if reach.full_rotation:
        motion = sweep(lk, steps=721)
    else:
        motion = sweep(lk, steps=721, start=reach.limits[0], stop=reach.limits[1])
    return motion, None if result.kind == "function" else result.target.points


def _draw(result, path: str) -> None:
    """The mechanism in its pose over the target's points and the traced curve."""
    from synth.motion_draw import draw_motion

    motion, marks = _swept(result)
    circles = " (circles)" if marks is not None else ""
    draw_motion(motion, path, marks=marks, title=f"{result.linkage.chain.compact()}: {result.kind} target{circles}, "
                f"error max {result.error_max:.3g}")


def _draw_rows(rows: list, path: str) -> None:
    """An atlas search's rows (``(rank, result)``, best first) on one sheet: each row's mechanism in its pose
    over the target's points and its curve, titled with its rank, links and error."""
    from synth.motion_draw import draw_motion_sheet

    panels = []
    for rank, result in rows:
        motion, marks = _swept(result)
        panels.append((motion, marks, _panel_title(rank, result, motion)))
    draw_motion_sheet(panels, path)


#: a panel of the sheet whose mechanism is more than this many times the target's size says so in its title (each
#: panel is drawn to its own scale: the target is then a speck, and a scale bar alone did not say why)
_DWARFED = 10.0


def _panel_title(rank: int, result, motion) -> str:
    """A sheet panel's title: rank, chain, frame, links, error max, and the mechanism's size over the target's
    (bounding-box diagonals; its joints and tracers over the sweep) where it is above :data:`_DWARFED`.

    >>> from types import SimpleNamespace
    >>> from synth.motion import read_linkage, sweep
    >>> lk = read_linkage("models/motion_four_bar.toml")
    >>> _panel_title(2, SimpleNamespace(linkage=lk, error_max=0.0122, size=0.05), sweep(lk, steps=90))
    '2: 0-1 0-3 1-2 2-3, frame 0\\n4 links, error max 0.0122, mechanism 149× target'
    """
    import numpy as np

    lk = result.linkage
    title = f"{rank}: {lk.chain.compact()}, frame {lk.frame}\n{lk.chain.links} links, error max {result.error_max:.3g}"
    points = np.vstack([motion.joints.reshape(-1, 2), *motion.tracers.values()])
    points = points[np.isfinite(points).all(axis=1)]
    times = float(np.hypot(*(points.max(axis=0) - points.min(axis=0)))) / result.size
    if times > _DWARFED:
        shown = f"{times:.0f}" if times < 1e4 else f"{times:.0e}".replace("e+0", "e").replace("e+", "e")  # 3e4
        title += f", mechanism {shown}× target"  # (at most about 51 characters: the width of a panel)
    return title
