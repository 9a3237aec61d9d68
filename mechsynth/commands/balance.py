"""CLI commands ``mechsynth balance arm|spring|prismatic|pantograph|compare|linkage|solve``: balancing of arms and
of dimensioned linkages.

Each command builds the problem of :mod:`balance.problems` from its file or options, solves it
and writes the result (a readable table, or ``--format json``) and, with ``--plot FILE``, its
figure. A problem whose estimated work exceeds the limit is refused with the estimate
(``--force`` runs it anyway). Nothing here imports ``balance`` until a balance command runs.

Example
-------
>>> from mechsynth.cli import main
>>> main(["balance", "prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2",
...       "--stroke", "0.5"])  # doctest: +ELLIPSIS
C_min (kg·m²)                 0.85
...
0
"""

from __future__ import annotations

import math
import os
import re
import sys

from .._argtypes import add_row, finite, number_range, output_file, picture_file, positive
from .._output import number, pairs, save_linkage, write_document

#: ``--range -90..90``: a negative range is a value, not an option
_NEGATIVE_VALUE = re.compile(r"^-\d+$|^-\d*\.\d+$|^-[\d.]+\.\.")


def add_commands(sub) -> None:
    """Mount ``balance`` and its subcommands on the ``mechsynth`` parser."""
    top = sub.add_parser("balance", help="balancing of arms and linkages: arm, spring, prismatic, pantograph, compare, "
                                         "linkage, solve",
                         description="Static and dynamic balancing of robot arms and of dimensioned linkages "
                                     "(docs/balance.md).")
    bsub = top.add_subparsers(dest="balance_command", metavar="COMMAND", required=True)

    def command(name: str, help: str, problem, table, plot: str | None):
        p = bsub.add_parser(name, help=help, description=help)
        p._negative_number_matcher = _NEGATIVE_VALUE  # argparse's own test for "is this a value?"
        p.set_defaults(run=_run, problem=problem, table=table, plot_with=plot)
        return p

    def common(p, plot: bool = True):
        p.add_argument("--format", choices=("table", "json"), default="table", help="table (default) or json")
        if plot:
            p.add_argument("--plot", metavar="FILE", type=picture_file, help="write a figure (.png, .pdf or .svg)")
        p.add_argument("--force", action="store_true",
                       help="run a problem whose estimated work exceeds the limit (30 s) instead of refusing it")

    a = command("arm", "balance an arm ([arm] TOML, or a URDF file)", _arm_problem, _table_arm, "plot_arm")
    a.add_argument("file", help="a TOML file with an [arm] table, or a .urdf file")
    a.add_argument("--samples", type=positive,
                   help="random configurations that start the searches for the largest residuals (default 1000)")
    a.add_argument("--seed", type=int, help="seed of the random configurations (default: the file's, else 0)")
    a.add_argument("--transmission", action="store_true",
                   help="the gear trains (differentials, reducers, spur stages) forming each device shaft")
    common(a)

    s = command("spring", "fit a spring device to Φ0·sin φ: the crank with a slotted lever, the offset slider-crank "
                          "or the sine device (and design its spring)",
                _spring_problem, _table_spring, "plot_spring")
    s.add_argument("--device", choices=("slotted-lever", "slider-crank", "sine"), default="slotted-lever",
                   help="slotted-lever (default): the spring along the lever from the crank pin to the base point; "
                        "slider-crank / sine: a compression spring on the slider in a fixed guide, on the side the "
                        "sign of Φ0 asks for")
    s.add_argument("--kind", choices=("tension", "compression", "compression-lever"),
                   help="the slotted lever's spring (required there); compression-lever: compression spring on the "
                        "lever beyond the pin, exact at a = r0")
    s.add_argument("--moment", required=True, type=float, metavar="PHI0",
                   help="Φ0 in N·m; + turns the crank away from the base point (compression), − towards it (tension)")
    s.add_argument("--range", required=True, type=number_range, metavar="A..B", help="working range of φ in degrees")
    s.add_argument("--r", required=True, type=number_range, metavar="A..B", help="crank length range (m)")
    s.add_argument("--r0", type=number_range, metavar="A..B",
                   help="slotted lever: spring length at φ = 0 (m); d = r + r0")
    s.add_argument("--a", required=True, type=number_range, metavar="A..B",
                   help="pre-extension/pre-load range (m), 'inf' allowed; on a slider the spring's least "
                        "deflection over the range")
    s.add_argument("--rod", type=number_range, metavar="A..B", help="slider-crank: rod length range (m)")
    s.add_argument("--offset", type=number_range, metavar="A..B",
                   help="slider-crank: offset of the guide from the crank pivot (m, signed; default 0..0)")
    s.add_argument("--max-force", type=float, metavar="F", help="largest spring force over the range (N)")
    s.add_argument("--max-free-length", type=float, metavar="L", help="longest free length of the spring (m)")
    s.add_argument("--max-deflection", type=float, metavar="X", help="compression: largest (l0 − L_min)/l0")
    s.add_argument("--method", choices=("trf", "slsqp", "nelder-mead", "de"),
                   help="the fit's optimiser (default: one per --norm; a tension spring exact where a = r0 is allowed)")
    s.add_argument("--norm", choices=("max", "rms"), default="max",
                   help="minimise the largest (default) or the RMS deviation over the range")
    s.add_argument("--grid", type=int, default=None, help="fit grid points (default 61, at most 100001)")
    s.add_argument("--target-error", type=float, metavar="E",
                   help="requested relative error (e.g. 0.01); missed: a warning and exit status 1")
    s.add_argument("--pareto", action="store_true",
                   help="compression: the front of error against free length and peak force (a few seconds)")
    g = s.add_argument_group("helical spring design (EN 13906-1 formulas)")
    g.add_argument("--design-spring", action="store_true", help="design a helical spring a maker can wind")
    g.add_argument("--material", help="spring wire: music-wire (default), oil-tempered, chrome-vanadium, "
                                      "chrome-silicon, stainless")
    g.add_argument("--max-outer-diameter", type=float, metavar="D", help="bore the coils must fit in (m)")
    g.add_argument("--min-inner-diameter", type=float, metavar="D", help="rod the coils must fit over (m)")
    g.add_argument("--spring-ends", choices=("pinned", "fixed-free", "fixed-pinned", "fixed"),
                   help="end condition for buckling of a compression spring (default pinned)")
    g.add_argument("--guided", action="store_true", help="the compression spring runs on a rod or in a sleeve")
    common(s)

    pr = command("prismatic", "counter-masses for a sliding last link", _prismatic_problem, _table_prismatic,
                 "plot_prismatic")
    pr.add_argument("--mass", required=True, type=float, metavar="m", help="mass of the sliding link (kg)")
    pr.add_argument("--inertia", required=True, type=float, metavar="I",
                    help="the sliding link's transverse central moment of inertia (kg·m²)")
    pr.add_argument("--counter-mass", required=True, type=float, metavar="M", help="each of the two counter-masses (kg)")
    pr.add_argument("--stroke", required=True, type=float, metavar="q_max", help="designed stroke half-amplitude (m)")
    pr.add_argument("--travel", type=float, metavar="S", help="stroke actually travelled (default q_max)")
    pr.add_argument("--C", type=float, dest="C", help="inertia constant (default C_min)")
    pr.add_argument("--dynamics", choices=("spatial", "planar"),
                    help="mass matrix of a three-joint arm carrying the slide (Pinocchio): ∂M/∂q with and "
                         "without the counter-masses")
    common(pr)

    pa = command("pantograph", "pantograph balanced manipulator ([pantograph] TOML)", _file_problem,
                 _table_pantograph, "plot_pantograph")
    pa.add_argument("file", help="a TOML file with a [pantograph] table")
    common(pa)

    c = command("compare", "balancing hardware side by side: counterweights, a spring per joint, the harmonic "
                           "decomposition pruned, exact springs — residual torque, devices, added mass",
                _compare_problem, _table_compare, "plot_compare")
    c.add_argument("file", help="a TOML file with a [compare] table (its arm = FILE), an [arm] table, or a .urdf file")
    c.add_argument("--payload", type=number_range, metavar="A..B", help="payload range (kg); default the file's")
    c.add_argument("--range", action="append", type=_joint_range, metavar="qJ=A..B", dest="ranges",
                   help="the workspace of joint J (degrees, or m on a slide); repeat for each joint to narrow "
                        "(default: the joint limits)")
    c.add_argument("--target", type=_share, metavar="E",
                   help="the pruned decomposition keeps the residual under E × the baseline torque (default 0.05)")
    c.add_argument("--acceleration", type=float, metavar="A",
                   help="joint acceleration (rad/s²) at which the counterweights' motor torque is given (default 1)")
    c.add_argument("--samples", type=positive, help="random configurations (default 1000)")
    c.add_argument("--seed", type=int, help="seed of the random configurations (default: the file's, else 0)")
    common(c)

    lb = command("linkage", "counterweights that balance a dimensioned 1-DOF linkage's shaking force and its gravity "
                            "potential: a linkage file (move/dimension --save) with --density, or a TOML file with a "
                            "[linkage_balance] table", _linkage_problem, _table_linkage, "plot_linkage")
    lb.add_argument("file", help="a linkage file (.json or .toml; an atlas search's rows with --row K), or a TOML "
                                 "file with a [linkage_balance] table "
                                 "(its linkage: 'file' or the file's [linkage]; per-link masses or a density)")
    lb.add_argument("--density", type=finite, metavar="KG_PER_M",
                    help="the links as bars of this many kg per metre between every two of their joints")
    lb.add_argument("--on", type=_link_list, metavar="L,L",
                    help="the links that carry counterweights (default: those pivoted on the frame)")
    lb.add_argument("--counter-mass", type=finite, metavar="KG", help="every counterweight's mass")
    lb.add_argument("--counter-radius", type=finite, metavar="M",
                    help="every counterweight's distance from its frame pivot (default: the link's reach)")
    lb.add_argument("--gravity", type=_vector, metavar="GX,GY", help="gravity in m/s² (default 0,-9.81)")
    lb.add_argument("--range", type=number_range, metavar="A..B",
                    help="the input's range (degrees, or m for a prismatic input; default a crank's turn or the "
                         "limits of a rocker)")
    lb.add_argument("--samples", type=positive, help="input values sampled for the fit and the searches (default 361)")
    lb.add_argument("--save", type=_saved, metavar="OUT.json|OUT.toml",
                    help="write the balanced linkage: its counterweights as tracers CW<link> (draw and move show them) "
                         "and the masses in [linkage_balance] (balance linkage OUT finds none needed); .toml: a scene")
    add_row(lb)
    common(lb)

    so = command("solve", "any balance problem: a TOML file with [arm], [spring], [slider], [pantograph], "
                          "[compare] or [linkage_balance]", _file_problem, None, None)
    so.add_argument("file", help="a TOML file with [arm], [spring], [slider], [pantograph], [compare] or "
                                 "[linkage_balance]")
    common(so, plot=False)


# ----------------------------------------------------------------- running
def _run(args) -> int:
    from balance import BalanceError, TooMuchWork
    from synth import InvalidOption

    if getattr(args, "file", None) and args.balance_command != "linkage":
        _refuse_linkage(args.file)
    try:
        problem = args.problem(args)
        if args.force:
            from dataclasses import replace

            problem = replace(problem, work_limit=None)
        result = problem.solve()
        out = result.to_dict()
        table = args.table or _TABLES[type(result).__name__]
        write_document(out, args.format, "" if args.format == "json" else table(out))
        if getattr(args, "plot", None):
            import balance

            getattr(balance, args.plot_with)(result, args.plot)
            print(f"plot -> {args.plot}", file=sys.stderr)  # as move, dimension and draw say where they wrote
        if getattr(args, "save", None):
            _save_balanced(args, result)
            print(f"linkage -> {args.save}", file=sys.stderr)
    except TooMuchWork as exc:
        raise InvalidOption(f"{str(exc).rstrip('.')}; give --force to run it anyway.") from None
    except BalanceError as exc:
        raise InvalidOption(str(exc)) from None
    except OSError as exc:  # e.g. the plot file cannot be written
        if exc.filename is None:  # stdout itself (a full disk): the command's own sentence
            raise
        raise InvalidOption(f"cannot write or read {exc.filename}: {exc.strerror}.") from None
    return 1 if out.get("target_met") is False else 0  # a valid query whose requested error is not reached


def _refuse_linkage(path: str) -> None:
    """A linkage file (a dimensioned mechanism, as ``move`` and ``dimension --save`` write it) given to a
    command for arms refused in one sentence naming the command that balances it."""
    from synth import InvalidOption, MotionError
    from synth.motion import read_linkage

    try:
        read_linkage(path)
    except MotionError:  # not a linkage (an arm, a URDF, a file to refuse in its own words)
        return
    if path.lower().endswith(".toml"):
        from balance import load_toml

        if "linkage_balance" in load_toml(path):  # a linkage's balance problem, for solve
            return
    name = os.path.basename(path)
    raise InvalidOption(f"{name} is a linkage (a dimensioned mechanism, as move and dimension --save write it): "
                        f"balance it with 'mechsynth balance linkage {name} --density KG_PER_M' (or a TOML file with a "
                        "[linkage_balance] table giving its masses)")


def _file_problem(args):
    from balance import load_toml, read_problem

    doc = load_toml(args.file)
    if "linkage_balance" in doc and args.balance_command == "solve":
        return _linkage_problem(args)
    if args.balance_command == "pantograph":
        from balance import pantograph_problem

        return pantograph_problem(doc, args.file)
    return read_problem(doc, args.file)


def _arm_problem(args):
    from dataclasses import replace

    from balance import arm_problem, load_toml

    if args.file.lower().endswith(".urdf"):
        doc = {"arm": {"urdf": os.path.abspath(args.file), "name": os.path.basename(args.file)}}
    else:
        doc = load_toml(args.file)
    problem = arm_problem(doc, args.file)
    changes = {k: v for k, v in (("samples", args.samples), ("seed", args.seed)) if v is not None}
    if args.transmission:
        changes["transmission"] = True
    return replace(problem, **changes)


def _spring_problem(args):
    from balance import DEFAULT_GRID, InvalidInput, SpringBounds, SpringOptions, SpringProblem

    given = {"--material": args.material, "--max-outer-diameter": args.max_outer_diameter,
             "--min-inner-diameter": args.min_inner_diameter, "--spring-ends": args.spring_ends,
             "--guided": args.guided or None}
    named = [k for k, v in given.items() if v is not None]
    if named and not args.design_spring:
        raise InvalidInput(f"{' and '.join(named)} {'applies' if len(named) == 1 else 'apply'} only with --design-spring.")
    kind = _device_options(args)
    if kind == "tension" and (args.spring_ends is not None or args.guided):
        raise InvalidInput("--spring-ends and --guided concern compression springs; a tension device gets an "
                           "extension spring.")
    design = None
    if args.design_spring:
        design = SpringOptions(args.material or "music-wire", args.max_outer_diameter, args.min_inner_diameter or 0.0,
                               args.spring_ends or "pinned", True if args.guided else None)
    lo, hi = args.range
    bounds = SpringBounds(args.r, args.r0, args.a, args.max_force, args.max_free_length, args.max_deflection,
                          args.rod, args.offset)
    return SpringProblem(kind, args.moment, (math.radians(lo), math.radians(hi)), bounds, args.method, args.norm,
                         DEFAULT_GRID if args.grid is None else args.grid, args.target_error, args.pareto, design,
                         args.device)


def _device_options(args) -> str:
    """The spring kind, with the options the chosen device does not take refused in one sentence."""
    from balance import InvalidInput

    if args.device == "slotted-lever":
        missing = [k for k, v in (("--kind", args.kind), ("--r0", args.r0)) if v is None]
        if missing:
            raise InvalidInput(f"the slotted-lever device needs {' and '.join(missing)}.")
        wrong = [k for k, v in (("--rod", args.rod), ("--offset", args.offset)) if v is not None]
        if wrong:
            raise InvalidInput(f"{' and '.join(wrong)} belong to the slider-crank; the slotted lever has no rod.")
        return args.kind
    wrong = [k for k, v in (("--r0", args.r0),) if v is not None]
    if args.device == "sine":
        wrong += [k for k, v in (("--rod", args.rod), ("--offset", args.offset)) if v is not None]
    if wrong:
        raise InvalidInput(f"the {args.device} device takes no {' nor '.join(wrong)}.")
    if args.kind not in (None, "compression"):
        raise InvalidInput(f"the {args.device} device carries a compression spring on the slider (on the side the "
                           f"sign of Φ0 asks for); --kind {args.kind} does not apply.")
    if args.device == "slider-crank" and args.rod is None:
        raise InvalidInput("the slider-crank device needs --rod A..B (the rod length range, m).")
    return "compression"


def _share(text: str) -> float:
    """A share strictly between 0 and 1."""
    import argparse

    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 < value < 1:
        raise argparse.ArgumentTypeError(f"expected a share between 0 and 1 (e.g. 0.05), not {text!r}")
    return value


def _joint_range(text: str) -> tuple[str, tuple[float, float]]:
    """``q2=-90..90`` → ``("q2", (-90.0, 90.0))``."""
    import argparse

    name, sep, rng = text.partition("=")
    if not sep or not re.fullmatch(r"q[1-9]\d*", name.strip()):
        raise argparse.ArgumentTypeError(f"expected qJ=low..high (e.g. q2=-90..90), not {text!r}")
    return name.strip(), number_range(rng)


def _compare_problem(args):
    """``balance compare FILE``: a [compare] table, an arm's TOML or a URDF file, with the options over the table's."""
    from balance import compare_problem, load_toml

    options = {k: v for k, v in (("target", args.target), ("acceleration", args.acceleration),
                                 ("samples", args.samples), ("seed", args.seed)) if v is not None}
    if args.payload is not None:
        options["payload"] = list(args.payload)
    if args.ranges:
        options["workspace"] = {name: list(rng) for name, rng in args.ranges}
    if args.file.lower().endswith(".urdf"):
        doc = {"arm": {"urdf": os.path.abspath(args.file), "name": os.path.basename(args.file)}}
    else:
        doc = load_toml(args.file)
    return compare_problem(doc, args.file, options)


def _prismatic_problem(args):
    from balance import DynamicsCheck, SliderProblem

    return SliderProblem(args.mass, args.inertia, args.counter_mass, args.stroke, args.travel, args.C,
                         dynamics=None if args.dynamics is None else DynamicsCheck(args.dynamics))


# ----------------------------------------------------------------- linkages
def _saved(text: str) -> str:
    return output_file(text, (".json", ".toml"), "the balanced linkage")


def _link_list(text: str) -> tuple[int, ...]:
    """``1,3``: links by number."""
    import argparse

    try:
        return tuple(int(part) for part in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected link numbers separated by commas (e.g. 1,3), not {text!r}") from None


def _vector(text: str) -> tuple[float, float]:
    """``0,-9.81``: two finite numbers."""
    import argparse

    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected two numbers GX,GY (e.g. 0,-9.81), not {text!r}")
    return finite(parts[0]), finite(parts[1])


def _linkage_problem(args):
    """The balance problem of a linkage file, or of a TOML file with a [linkage_balance] table; an option given
    both on the command line and in the table is refused."""
    from balance import InvalidInput, linkage_table, load_toml
    from synth import InvalidOption
    from synth.motion import read_linkage

    from .._linkage_balance import OPTIONS, linkage_problem

    options = {key: getattr(args, key, None) for key in OPTIONS}
    table, source = None, args.file
    if args.file.lower().endswith((".toml", ".json")):
        doc = load_toml(args.file) if args.file.lower().endswith(".toml") else _load_json(args.file, args.row)
        if isinstance(doc, dict) and "linkage_balance" in doc:
            table = linkage_table(doc, args.file)
            if table.file is not None and "linkage" in doc:
                raise InvalidInput(f"{args.file} gives the linkage twice, as [linkage_balance] 'file' and as a [linkage] "
                                   "table: keep one.")
            if table.file is not None:
                source = os.path.join(os.path.dirname(args.file), table.file)
            elif "linkage" not in doc:
                raise InvalidInput(f"{args.file}: [linkage_balance] needs its linkage: 'file' = a linkage file, or a "
                                   "[linkage] table in the same file.")
    if args.save is not None:  # as move and dimension: the files read are never written over
        read = next((path for path in (args.file, source) if os.path.realpath(path) == os.path.realpath(args.save)), None)
        if read is not None:
            raise InvalidOption(f"{read} is read by this command: --save would overwrite it")
    if table is not None:
        both = [flag for key, flag in OPTIONS.items() if options[key] is not None and getattr(table, key) is not None]
        if both:
            raise InvalidOption(f"{both[0]} is also given in {args.file}'s [linkage_balance]: give it in one place")
        options = {key: getattr(table, key) if options[key] is None else options[key] for key in OPTIONS}
    args.linkage, args.options = read_linkage(source, row=args.row), options  # kept for --save
    return linkage_problem(args.linkage, options, None if table is None else table.links, os.path.basename(source),
                           args.file, None if table is None else table.counterweights)


def _load_json(path: str, row: int | None):
    """A JSON file's content (a linkage file, or one 'balance linkage --save' wrote with its masses)."""
    import json

    from synth.motion import read_linkage

    read_linkage(path, row=row)  # the file's own sentence when it is no linkage or no JSON (or --row is amiss)
    with open(path, encoding="utf-8") as fh:
        return json.load(fh)


def _save_balanced(args, result) -> None:
    """The linkage with its counterweights as tracers and its masses in [linkage_balance], as JSON or as a
    TOML scene (``move`` and ``draw`` read either; ``balance linkage`` reads the masses back)."""
    from .._linkage_balance import balanced_linkage

    balanced, table = balanced_linkage(args.linkage, result, args.options)
    save_linkage(balanced, args.save, source="mechsynth balance linkage",
                 description=f"{result.name} balanced by counterweights", tables={"linkage_balance": table},
                 compute=("motion", "balance linkage"))


def _table_linkage(out: dict) -> str:
    unit = out["shaking_force_unit"]
    to_input = (lambda v: f"{math.degrees(v):.6g}°") if out["input_kind"] == "revolute" else (lambda v: f"{v:.6g} m")
    lo, hi = out["input_range"]
    lines = [f"linkage: {out['name']}; input {out['input']} over {to_input(lo)} … {to_input(hi)}", ""]
    head = f"{'link':>4}  {'mass kg':>10}  {'from joint':>10}  {'distance m':>11}  {'angle°':>8}  {'(from line to)':<14}  " \
           f"{'at (pose) m':<24}"
    if out["carried"]:
        lines += ["counterweights carried already: " + "; ".join(
            f"link {b['link']} {b['mass']:.6g} kg at ({number(b['centre'][0])}, {number(b['centre'][1])})"
            for b in out["carried"]), ""]
    lines += ["counterweights:", head, "-" * len(head)]
    for c in out["counterweights"]:
        if c["mass"] == 0:
            lines.append(f"{c['link']:>4}  none needed")
            continue
        lines.append(f"{c['link']:>4}  {c['mass']:>10.6g}  {c['joint']:>10}  {c['distance']:>11.6g}  "
                     f"{c['angle_deg']:>8.5g}  {c['towards'] or '':<14}  "
                     f"({number(c['at'][0])}, {number(c['at'][1])})")
    rows = []
    for label, key in (("total mass (kg)", "total_mass"), ("centre of mass's largest excursion (m)", "com_excursion"),
                       ("first moment's largest excursion (kg·m)", "moment_excursion"),
                       (f"shaking force's largest amplitude ({unit})", "shaking_force"),
                       (f"shaking moment's largest, about {out['input']} ({unit.replace('N', 'N·m', 1)})",
                        "shaking_moment"),
                       ("gravity potential's variation (J)", "potential_variation")):
        b, a = out["before"][key], out["after"][key]
        rows.append((label, f"{number(b) if b is not None else '—'}  →  {number(a) if a is not None else '—'}"))
    lines += ["", "before  →  after:", pairs(rows), "",
              "full balance: " + ("yes (what is left is rounding)" if out["full_balance"] else
                                  f"no: {100 * out['residual_share']:.4g}% of the excursion is left")]
    lines += [f"note: {n}" for n in out["notes"]]
    lines.append(f"note: {out['extremes']}")
    return "\n".join(lines)


# ----------------------------------------------------------------- tables
def _table_arm(out: dict) -> str:
    lines = [f"arm: {out['name']}", ""]
    head = (f"{'#':>2}  {'amplitude':>11}  {'phase°':>8}  {'form (joints)':<24}  {'shafts (differential)':<24}  "
            f"{'sine e·T':>10}")
    lines += [head, "-" * len(head)]
    for k, (t, d) in enumerate(zip(out["terms"], out["devices"])):
        lines.append(f"{k + 1:>2}  {t['amplitude']:>11.6g}  {t['phase_deg']:>8.4g}  {t['form_text']:<24}  "
                     f"{t['drive_form_text']:<24}  {d['sine']['eT']:>10.6g}")
    ck = out["check"]
    lines += ["", pairs([
        ("check samples", ck["samples"]),
        ("max residual (N·m or N)", out["max_residual"]),
        ("largest gravity force", out["max_gravity_force"]),
        ("relative residual", out["relative_residual"]),
        ("potential spread (J)", out["potential_spread"]),
    ])]
    pc = out["pinocchio"]
    rows = [(f"Pinocchio {pc['pinocchio']} check: max residual", pc["max_residual"]),
            ("  relative to the largest gravity force", pc["relative_residual"])]
    if "gravity_agreement" in pc:
        rows.append(("  arm model's gravity against Pinocchio's", pc["gravity_agreement"]))
    lines += ["", pairs(rows)]
    for p in out["prismatic"]:
        lines += ["", pairs([
            (f"prismatic {p['coordinate']} gear ratio k (m/rad)", p["gear_ratio"]),
            ("γ_max (rad)", p["gamma_max"]),
            ("relative error bound 1 − sinγ/γ", p["rel_error_bound"]),
            ("residual bound per joint", ", ".join(number(v) for v in p["residual_bound_per_joint"])),
        ])]
    if out["payload"]:
        pl = out["payload"]
        lines += ["", pairs([
            ("payload max / tuned for (N)", f"{number(pl['max_payload'])} / {number(pl['tuned_for'])}"),
            ("worst residual, payload 0..max", pl["max_residual"]),
            ("effect of half the payload", pl["half_payload_effect"]),
        ])]
    for tr in out.get("transmission", []):
        lines += ["", f"gear train for {tr['shaft']} = {_form_text(tr['form'])} "
                      f"(composed back: error {tr['error']:.2g}):"]
        for el in tr["train"]:
            if el["element"] == "differential":
                lines.append(f"  differential: carrier {el['carrier']}, side gear {el['side']} → {el['output']}"
                             " (ω_out = 2·ω_carrier − ω_side)")
            elif el["element"] == "shaft":
                lines.append(f"  the crank sits on shaft {el['input']}")
            else:
                rev = ", reversing" if el["reverses"] else ""
                lines.append(f"  {el['element']} {el['input']} → {el['output']}, ratio {el['ratio']:.6g}{rev}")
    cw = out["counterweights"]
    if cw["available"]:
        lines += ["", "counterweight alternative:"]
        for r in cw["weights"]:
            lines.append(f"  {r['link']:<14} {r['weight']:>10.5g} N at {r['arm']:.4g} m behind its joint")
        lines.append(f"  added {cw['added_weight']:.5g} N ({cw['ratio']:.3g}× the arm), residual {cw['max_residual']:.3g}")
    else:
        lines += ["", f"counterweights: not available — {cw['reason']}"]
    return "\n".join(lines)


def _form_text(form) -> str:
    from balance import format_form

    return format_form(form, [f"ψ{i + 1}" for i in range(len(form))])


def _table_spring(out: dict) -> str:
    if out["family"] != "slotted-lever":
        return _table_slider_spring(out)
    rows = [
        ("kind / sense", f"{out['kind']} / {out['sense_text']}"),
        ("method / norm", f"{out['method']} / {out['norm']}"),
        ("c (N/m)", out["c"]), ("r (m)", out["r"]), ("r0 (m)", out["r0"]), ("a (m)", out["a"]),
        ("d = r + r0 (m)", out["d"]), ("free length l0 (m)", out["free_length"]),
        ("max spring force (N)", out["max_force"]),
        ("max relative error", out["max_rel_error"]), ("RMS relative error", out["rms_rel_error"]),
        ("seconds", out["seconds"]), ("function evaluations", out["nfev"]),
        ("active bounds", ", ".join(out["active_bounds"]) or "none"),
        ("message", out["message"]),
    ]
    if out.get("deflection") is not None:
        rows.insert(9, ("deflection (l0 − L_min)/l0", out["deflection"]))
    if out["kind"] == "compression-lever":
        lv = out["lever"]
        rows[7] = ("spring free length = stop from C (m)", lv["stop_distance_from_C"])
        rows.insert(9, ("lever reach from C (m)", lv["reach_from_C"]))
        rows.insert(10, ("  beyond the farthest pin (m)", lv["extra_length"]))
        rows.insert(11, ("  a spring between C and B reaches (m)", lv["reach_from_C_fig_a"]))
    return pairs(rows) + _spring_design_text(out)


def _table_slider_spring(out: dict) -> str:
    rows = [
        ("device / side", f"{out['family']} / {out['sense_text']}"),
        ("method / norm", f"{out['method']} / {out['norm']}"),
        ("c (N/m)", out["c"]), ("r (m)", out["r"]),
    ]
    if out["rod"] is not None:
        rows += [("rod l (m)", out["rod"]), ("guide offset e (m)", out["offset"])]
    rows += [
        ("pre-load a: least deflection (m)", out["a"]),
        ("slider position x_n with the spring unloaded (m from A)", out["neutral"]),
        ("free length l0 (m)", out["free_length"]), ("deflection ratio at most", out["deflection"]),
        ("max spring force (N)", out["max_force"]),
        ("max relative error", out["max_rel_error"]), ("RMS relative error", out["rms_rel_error"]),
        ("seconds", out["seconds"]), ("function evaluations", out["nfev"]),
        ("active bounds", ", ".join(out["active_bounds"]) or "none"),
        ("message", out["message"]),
    ]
    return pairs(rows) + _spring_design_text(out)


def _spring_design_text(out: dict) -> str:
    """The designed helical spring, the Pareto front, notes and warnings of a spring fit, as text."""
    s = ""
    sp = out.get("spring")
    if sp:
        srows = [
            ("spring", f"{sp['kind']}, {sp['material']} ({sp['material_description']})"),
            ("wire diameter d (mm)", 1e3 * sp["wire_diameter_m"]),
            ("mean coil diameter D (mm)", 1e3 * sp["mean_diameter_m"]),
            ("outer / inner diameter (mm)", f"{1e3 * sp['outer_diameter_m']:.4g} / {1e3 * sp['inner_diameter_m']:.4g}"),
            ("active / total coils", f"{sp['active_coils']:g} / {sp['total_coils']:g}"),
            ("rate G·d⁴/(8·D³·n) (N/m)", sp["stiffness_N_per_m"]),
            ("free length (m)", sp["free_length_m"]),
            ("peak shear stress, corrected (MPa)", sp["max_shear_stress_Pa"] / 1e6),
            ("allowed shear stress (MPa)", sp["allowed_shear_stress_Pa"] / 1e6),
            ("mass (kg)", sp["mass_kg"]),
        ]
        if sp["kind"] == "compression":
            b = sp["buckling"]
            srows.insert(7, ("solid length (m)", sp["solid_length_m"]))
            srows.append(("buckling", "guided: none" if b["guided"] else
                          f"{'safe' if b['safe'] else 'BUCKLES'} ({b['end_condition']} ends, critical deflection "
                          f"{number(b['critical_deflection_m'])} m, working {number(b['max_deflection_m'])} m)"))
        else:
            srows.append(("anchor offset beyond C (m)", sp["anchor_offset_m"]))
        s += "\n\n" + pairs(srows)
    if out.get("pareto"):
        s += "\n\nPareto front (error, free length, peak force):"
        for p in out["pareto"]:
            s += f"\n  {100 * p['error']:8.4g} %  {p['size']:8.4g} m  {p['force']:10.5g} N"
    for n in out.get("notes", []):
        s += f"\nnote: {n}"
    for w in out.get("warnings", []):
        s += f"\nwarning: {w}"
    return s


def _table_prismatic(out: dict) -> str:
    rows = [
        ("C_min (kg·m²)", out["C_min"]), ("C used", out["C"]),
        ("stroke valid for C (m)", out["law_valid_stroke"]),
        ("max centre-of-mass error (m)", out["max_com_error"]),
        ("max inertia error (kg·m²)", out["max_inertia_error"]),
        ("two-crank ±120° exact", out["crank"]["exact"]),
        ("two-crank COM error (m)", out["crank"]["max_com_error"]),
        ("two-crank inertia variation", out["crank"]["max_inertia_error"]),
    ]
    s = pairs(rows) + "\nlaws: z1,2 = [−m·q ± √(2M(C − I − m·q²) − m²q²)]/(2M)"
    for m in out["messages"]:
        s += f"\nwarning: {m}"
    dyn = out.get("dynamics")
    if dyn:
        s += f"\n\nmass matrix of a {dyn['arm']} arm carrying the slide (Pinocchio, {dyn['samples']} configurations):"
        for label, c in dyn["cases"].items():
            s += (f"\n  {label:<45} max |∂M/∂{c['coordinate']}| {c['max_dM_relative']:.3g}, change over the "
                  f"range {c['max_change_relative']:.3g} (relative to the largest entry)")
        s += f"\n  counter-mass cranks: {dyn['crank_laws']}"
        s += f"\n  one counter-mass: keeping the centre of mass, the {dyn['one_mass']['keeps_centre_of_mass']}"
        s += f"\n  one counter-mass keeping the inertia: only for {dyn['one_mass']['valid_interval_text']}"
    return s


def _table_pantograph(out: dict) -> str:
    w = out["point_weights"]
    cf, cy, hf = out["cylinder_force"], out["cylinder"], out["hand_force"]
    rows = [
        ("substitution weights (N)", ", ".join(f"{k} {v:.6g}" for k, v in w.items())),
        ("spring amplitude c·r·d = e·T (N·m)", out["term"]["amplitude"]),
        ("spring", out["spring_moment"]),
        ("vertical load at B, W_B + k·W_C (N)", out["drive_force"]),
        ("  payload 0 .. max (N)", " .. ".join(number(v) for v in out["drive_force_range"])),
        ("cylinder force, half payload (N)",
         f"{number(cf['half_payload']['min'])} .. {number(cf['half_payload']['max'])}"),
        ("cylinder force, payload 0..max (N)", f"{number(cf['min'])} .. {number(cf['max'])}"),
        ("cylinder length (m)", f"{number(cy['length_min'])} .. {number(cy['length_max'])}"),
        ("operator's force along A→C (N)", f"{number(hf['min'])} .. {number(hf['max'])}"),
        ("max residual (virtual work)", out["max_residual"]),
        ("relative residual", out["relative_residual"]),
    ]
    if "c" in out["device"]["tension"]:
        rows.insert(3, ("tension spring c (N/m)", out["device"]["tension"]["c"]))
    s = pairs(rows) + f"\nnote: {out['note']}"
    for n in out.get("notes", []):
        s += f"\nnote: {n}"
    return s


def _table_compare(out: dict) -> str:
    joints = out["joints"]
    loaded = [i for i, _ in enumerate(joints) if out["strategies"][0]["joints"][i]["baseline_max"] > 0]
    unit = lambda i: "N" if joints[i]["kind"] == "prismatic" else "N·m"  # noqa: E731
    ws = []
    for i, (a, b) in enumerate(out["workspace"]):
        k, u = (1.0, " m") if joints[i]["kind"] == "prismatic" else (180 / math.pi, "°")
        ws.append(f"q{i + 1} {a * k:.4g}..{b * k:.4g}{u}")
    lo, hi = out["payload"]
    lines = [f"arm: {out['name']}; payload {number(lo)} .. {number(hi)} kg", f"workspace: {', '.join(ws)}", ""]
    head = f"{'strategy':<18}  {'devices':>7}  {'added kg':>9}  {'tuned kg':>8}  {'worst residual':>20}  " \
           f"{'removed':>7}  {'RMS removed':>11}"
    lines += [head, "-" * len(head)]
    for st in out["strategies"]:
        if not st["available"]:
            lines.append(f"{st['name']:<18}  not available: {st['reason']}")
            continue
        worst = max(st["joints"], key=lambda j: j["max"])
        base_rms = sum(j["baseline_rms"] ** 2 for j in st["joints"]) ** 0.5
        rms = sum(j["rms"] ** 2 for j in st["joints"]) ** 0.5
        tuned = "—" if st["tuned_for"] is None else f"{st['tuned_for']:.3g}"
        wj = int(worst["coordinate"][1:]) - 1
        lines.append(f"{st['name']:<18}  {st['devices']:>7}  {st['added_mass']:>9.4g}  {tuned:>8}  "
                     f"{worst['max']:>11.4g} {unit(wj):<3} at {worst['coordinate']:<3}  {100 * st['removed']:>6.1f}%  "
                     f"{100 * (1 - rms / base_rms if base_rms else 0):>10.1f}%")
    lines += ["", "largest |torque| per joint over the workspace and payloads, and the share removed:"]
    head = f"{'':<18}" + "".join(f"  {joints[i]['coordinate'] + ' (' + unit(i) + ')':>16}" for i in loaded)
    lines.append(head)
    for st in out["strategies"]:
        if st["available"]:
            cells = "".join(f"  {st['joints'][i]['max']:>9.4g} ({round(100 * st['joints'][i]['removed_max']) + 0:>3.0f}%)"
                            for i in loaded)
            lines.append(f"{st['name']:<18}{cells}")
    for st in out["strategies"][1:]:
        if not st["available"]:
            continue
        lines += ["", f"{st['name']} (tuned for {st['tuned_for']:.4g} kg):"]
        lines += [f"  {h}" for h in st["hardware"]]
        d = st["details"]
        if st["name"] == "counterweights":
            lines.append("  added inertia per joint (kg·m²): "
                         + ", ".join(f"q{i + 1} {number(v)}" for i, v in enumerate(d["added_inertia"]) if v > 0)
                         + f"; motor torque at {number(out['acceleration'])} rad/s²: "
                         + ", ".join(f"q{i + 1} {number(v)} N·m" for i, v in enumerate(d["motor_torque_at_acceleration"])
                                     if v > 0))
        if st["name"] == "harmonic, pruned":
            lines.append(f"  kept {d['kept']} of {d['terms']} terms (target {number(d['target_torque'])} N·m); dropped: "
                         + (", ".join(f"{t['form_text']} ({number(max(t['largest_torque_per_joint']))} N·m alone)"
                                      for t in d["dropped"]) or "none"))
            if "note" in d:
                lines.append(f"  note: {d['note']}")
        pc = st["pinocchio"]
        lines.append(f"  Pinocchio recheck ({pc['method']}): largest difference {pc['max_difference']:.2g} at "
                     f"{pc['configurations']} configurations × {len(pc['payloads'])} payloads and the worst ones")
    lines.append(f"\nnote: every largest value is a true extreme (the best of {out['samples']} random configurations, "
                 "polished); RMS over the same configurations and the payload range")
    return "\n".join(lines)


#: the table of each result of ``balance solve``
_TABLES = {"ArmBalance": _table_arm, "SpringDesign": _table_spring, "SliderBalance": _table_prismatic,
           "PantographBalance": _table_pantograph, "Comparison": _table_compare, "LinkageBalance": _table_linkage}
