"""``mechsynth balance …`` commands (also ``python -m mechsynth balance …``).

Results go to stdout (a readable table, or ``--format json``); a mistake prints one
sentence to stderr and returns 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any, Sequence

from balance.errors import BalanceError, InvalidRange

from .._argtypes import positive

__all__ = ["main", "build_parser"]

PROG = "mechsynth balance"
_RANGE_OPTS = {"--range", "--r", "--r0", "--a"}


class _UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # noqa: D401 - argparse hook
        raise _UsageError(message)


def parse_range(text: str, name: str = "range") -> tuple[float, float]:
    """``"A..B"`` → ``(A, B)``; ``inf`` allowed as B.

    Examples
    --------
    >>> parse_range("-90..90")
    (-90.0, 90.0)
    """
    if ".." not in text:
        raise InvalidRange(f"{name} must be written low..high (e.g. 20..160), not {text!r}.")
    a, b = text.split("..", 1)
    try:
        lo, hi = float(a), float(b)
    except ValueError:
        raise InvalidRange(f"{name} must be written low..high with numbers, not {text!r}.") from None
    if math.isnan(lo) or math.isnan(hi):
        raise InvalidRange(f"{name} {text!r} is not a range of numbers.")
    return lo, hi


PLOT_FORMATS = (".png", ".pdf", ".svg")


def plot_file(text: str) -> str:
    """A figure path ending in .png, .pdf or .svg (checked before any work is done)."""
    import os

    ext = os.path.splitext(text)[1].lower()
    if ext not in PLOT_FORMATS:
        raise argparse.ArgumentTypeError(
            f"a plot is written as PNG, PDF or SVG: end the file name in {', '.join(PLOT_FORMATS)}, not {text!r}")
    return text


def _materials():
    from balance.helical import MATERIALS

    return MATERIALS


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog=PROG, description="Static and dynamic balancing of robot arms.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    def common(sp):
        sp.add_argument("--format", choices=("table", "json"), default="table")
        sp.add_argument("--plot", metavar="FILE", type=plot_file, help="write a figure (.png, .pdf or .svg)")

    a = sub.add_parser("arm", help="balance an arm ([arm] TOML, or a URDF file)")
    a.add_argument("file", help="a TOML file with an [arm] table, or a .urdf file")
    a.add_argument("--samples", type=positive, help="random configurations of the check (default from file or 1000)")
    a.add_argument("--seed", type=int)
    a.add_argument("--transmission", action="store_true",
                   help="the gear trains (differentials, reducers, spur stages) forming each device shaft")
    common(a)

    s = sub.add_parser("spring", help="fit a crank-and-rocker spring device to Φ0·sin φ (and design its spring)")
    s.add_argument("--kind", required=True, choices=("tension", "compression", "compression-lever"),
                   help="compression-lever: compression spring on the lever beyond the pin, exact at a = r0")
    s.add_argument("--moment", required=True, type=float, metavar="PHI0",
                   help="Φ0 in N·m; + turns the crank away from the base point (compression), − towards it (tension)")
    s.add_argument("--range", required=True, metavar="A..B", help="working range of φ in degrees")
    s.add_argument("--r", required=True, metavar="A..B", help="crank length range (m)")
    s.add_argument("--r0", required=True, metavar="A..B", help="spring length at φ = 0 (m); d = r + r0")
    s.add_argument("--a", required=True, metavar="A..B", help="pre-extension/pre-load range (m), 'inf' allowed")
    s.add_argument("--max-force", type=float, metavar="F")
    s.add_argument("--max-free-length", type=float, metavar="L")
    s.add_argument("--max-deflection", type=float, metavar="X", help="compression: largest (l0 − L_min)/l0")
    s.add_argument("--method", choices=("trf", "slsqp", "nelder-mead", "de"))
    s.add_argument("--norm", choices=("max", "rms"), default="max")
    s.add_argument("--grid", type=int, default=None, help="fit grid points (default 61)")
    s.add_argument("--target-error", type=float, metavar="E",
                   help="requested relative error (e.g. 0.01); missed: a warning and exit status 1")
    s.add_argument("--pareto", action="store_true",
                   help="compression: the front of error against free length and peak force (a few seconds)")
    g = s.add_argument_group("helical spring design (EN 13906-1 formulas)")
    g.add_argument("--design-spring", action="store_true", help="design a helical spring a maker can wind")
    g.add_argument("--material", choices=tuple(_materials()), help="spring wire (default music-wire)")
    g.add_argument("--max-outer-diameter", type=float, metavar="D", help="bore the coils must fit in (m)")
    g.add_argument("--min-inner-diameter", type=float, metavar="D", help="rod the coils must fit over (m)")
    g.add_argument("--spring-ends", choices=("pinned", "fixed-free", "fixed-pinned", "fixed"),
                   help="end condition for buckling of a compression spring (default pinned)")
    g.add_argument("--guided", action="store_true", help="the compression spring runs on a rod or in a sleeve")
    common(s)

    pr = sub.add_parser("prismatic", help="counter-masses for a sliding last link")
    pr.add_argument("--mass", required=True, type=float, metavar="m")
    pr.add_argument("--inertia", required=True, type=float, metavar="I")
    pr.add_argument("--counter-mass", required=True, type=float, metavar="M")
    pr.add_argument("--stroke", required=True, type=float, metavar="q_max", help="designed stroke half-amplitude (m)")
    pr.add_argument("--travel", type=float, metavar="S", help="stroke actually travelled (default q_max)")
    pr.add_argument("--C", type=float, dest="C", help="inertia constant (default C_min)")
    pr.add_argument("--dynamics", choices=("spatial", "planar"),
                    help="mass matrix of a three-joint arm carrying the slide (Pinocchio): ∂M/∂q with and "
                         "without the counter-masses")
    common(pr)

    pa = sub.add_parser("pantograph", help="pantograph balanced manipulator ([pantograph] TOML)")
    pa.add_argument("file")
    common(pa)

    so = sub.add_parser("solve", help="any balance scene: [arm], [spring], [slider] or [pantograph]")
    so.add_argument("file")
    so.add_argument("--format", choices=("table", "json"), default="table")
    return p


def _fix_negative_ranges(argv: Sequence[str]) -> list[str]:
    """Let ``--range -90..90`` through argparse (it would take ``-90..90`` for an option)."""
    out: list[str] = []
    argv = list(argv)
    i = 0
    while i < len(argv):
        tok = argv[i]
        if tok in _RANGE_OPTS and i + 1 < len(argv) and argv[i + 1].startswith("-") and ".." in argv[i + 1]:
            out.append(f"{tok}={argv[i + 1]}")
            i += 2
            continue
        out.append(tok)
        i += 1
    return out


def _clean(obj: Any) -> Any:
    """JSON-safe: non-finite floats become null, tuples lists."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    return obj


def _num(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def _kv(rows: list[tuple[str, Any]]) -> str:
    w = max(len(k) for k, _ in rows)
    return "\n".join(f"{k:<{w}}  {_num(v)}" for k, v in rows)


# ----------------------------------------------------------------- tables
def _table_arm(out: dict) -> str:
    lines = [f"arm: {out['name']}", ""]
    head = f"{'#':>2}  {'amplitude':>11}  {'phase°':>8}  {'form (joints)':<24}  {'shafts (differential)':<24}  {'sine e·T':>10}"
    lines += [head, "-" * len(head)]
    for k, (t, d) in enumerate(zip(out["terms"], out["devices"])):
        lines.append(
            f"{k + 1:>2}  {t['amplitude']:>11.6g}  {t['phase_deg']:>8.4g}  {t['form_text']:<24}  "
            f"{t['drive_form_text']:<24}  {d['sine']['eT']:>10.6g}"
        )
    ck = out["check"]
    lines += ["", _kv([
        ("check samples", ck["samples"]),
        ("max residual (N·m or N)", out["max_residual"]),
        ("largest gravity force", out["max_gravity_force"]),
        ("relative residual", out["relative_residual"]),
        ("potential spread (J)", out["potential_spread"]),
    ])]
    pc = out.get("pinocchio")
    if pc:
        rows = [(f"Pinocchio {pc['pinocchio']} check: max residual", pc["max_residual"]),
                ("  relative to the largest gravity force", pc["relative_residual"])]
        if "gravity_agreement" in pc:
            rows.append(("  arm model's gravity against Pinocchio's", pc["gravity_agreement"]))
        lines += ["", _kv(rows)]
    for p in out["prismatic"]:
        lines += ["", _kv([
            (f"prismatic {p['coordinate']} gear ratio k (m/rad)", p["gear_ratio"]),
            ("γ_max (rad)", p["gamma_max"]),
            ("relative error bound 1 − sinγ/γ", p["rel_error_bound"]),
            ("residual bound per joint", ", ".join(_num(v) for v in p["residual_bound_per_joint"])),
        ])]
    if out["payload"]:
        pl = out["payload"]
        lines += ["", _kv([
            ("payload max / tuned for (N)", f"{_num(pl['max_payload'])} / {_num(pl['tuned_for'])}"),
            ("worst residual, payload 0..max", pl["max_residual"]),
            ("effect of half the payload", pl["half_payload_effect"]),
        ])]
    for tr in out.get("transmission", []):
        lines += ["", f"gear train for {tr['shaft']} = {_form_text(tr['form'], out)} "
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
    cw = out.get("counterweights")
    if cw:
        if cw["available"]:
            lines += ["", "counterweight alternative:"]
            for r in cw["weights"]:
                lines.append(f"  {r['link']:<14} {r['weight']:>10.5g} N at {r['arm']:.4g} m behind its joint")
            lines.append(f"  added {cw['added_weight']:.5g} N ({cw['ratio']:.3g}× the arm), residual {cw['max_residual']:.3g}")
        else:
            lines += ["", f"counterweights: not available — {cw['reason']}"]
    return "\n".join(lines)


def _form_text(form, out: dict) -> str:
    from balance.potential import format_form

    return format_form(form, [f"ψ{i + 1}" for i in range(len(form))])


def _table_spring(out: dict) -> str:
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
    s = _kv(rows)
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
                          f"{_num(b['critical_deflection_m'])} m, working {_num(b['max_deflection_m'])} m)"))
        else:
            srows.append(("anchor offset beyond C (m)", sp["anchor_offset_m"]))
        s += "\n\n" + _kv(srows)
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
    s = _kv(rows) + "\nlaws: z1,2 = [−m·q ± √(2M(C − I − m·q²) − m²q²)]/(2M)"
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
        ("  payload 0 .. max (N)", " .. ".join(_num(v) for v in out["drive_force_range"])),
        ("cylinder force, half payload (N)", f"{_num(cf['half_payload']['min'])} .. {_num(cf['half_payload']['max'])}"),
        ("cylinder force, payload 0..max (N)", f"{_num(cf['min'])} .. {_num(cf['max'])}"),
        ("cylinder length (m)", f"{_num(cy['length_min'])} .. {_num(cy['length_max'])}"),
        ("operator's force along A→C (N)", f"{_num(hf['min'])} .. {_num(hf['max'])}"),
        ("max residual (virtual work)", out["max_residual"]),
        ("relative residual", out["relative_residual"]),
    ]
    if "c" in out["device"]["tension"]:
        rows.insert(3, ("tension spring c (N/m)", out["device"]["tension"]["c"]))
    s = _kv(rows) + f"\nnote: {out['note']}"
    for n in out.get("notes", []):
        s += f"\nnote: {n}"
    return s


# ----------------------------------------------------------------- commands
def _emit(out: dict, fmt: str, table) -> None:
    if fmt == "json":
        print(json.dumps(_clean(out), indent=2, ensure_ascii=False, allow_nan=False))
    else:
        print(table(out))


def _cmd_arm(ns) -> dict:
    from balance.arm import arm_from_dict
    from balance.problems import load_toml, solve_arm

    import os

    if ns.file.lower().endswith(".urdf"):
        doc = {"arm": {"urdf": os.path.abspath(ns.file), "name": os.path.basename(ns.file)}}
        if ns.plot:
            from balance.errors import InvalidInput

            raise InvalidInput("--plot draws TOML arms; for a URDF arm write a TOML file with [arm] urdf = \"…\".")
    else:
        doc = load_toml(ns.file)
    if ns.samples is not None or ns.seed is not None or ns.transmission:
        doc = dict(doc)
        arm_t = dict(doc.get("arm", {}))
        if ns.transmission:
            arm_t["transmission"] = True
        ck = dict(arm_t.get("check", {}))
        if ns.samples is not None:
            ck["samples"] = ns.samples
        if ns.seed is not None:
            ck["seed"] = ns.seed
        arm_t["check"] = ck
        doc["arm"] = arm_t
    out = solve_arm(doc, ns.file)
    if ns.plot:
        from balance.plots import plot_arm

        arm = arm_from_dict(doc, ns.file)
        plot_arm(arm, arm.with_payload_fraction(0.5).harmonic_terms(), ns.plot)
    return out


def _cmd_spring(ns) -> dict:
    from balance.errors import InvalidInput
    from balance.fit import DEFAULT_GRID, SpringBounds
    from balance.problems import spring_problem

    design_opts = {"material": ns.material, "max_outer_diameter": ns.max_outer_diameter,
                   "min_inner_diameter": ns.min_inner_diameter, "ends": ns.spring_ends}
    given = [f"--{k.replace('_', '-')}" for k, v in design_opts.items() if v is not None] + (["--guided"] if ns.guided else [])
    if given and not ns.design_spring:
        raise InvalidInput(f"{', '.join(given)} only apply with --design-spring.")
    if ns.kind == "tension" and (ns.spring_ends is not None or ns.guided):
        raise InvalidInput("--spring-ends and --guided concern compression springs; a tension device gets an "
                           "extension spring.")
    design = None
    if ns.design_spring:
        design = {k: v for k, v in design_opts.items() if v is not None}
        if ns.guided:
            design["guided"] = True
    lo, hi = parse_range(ns.range, "--range")
    bounds = SpringBounds(parse_range(ns.r, "--r"), parse_range(ns.r0, "--r0"), parse_range(ns.a, "--a"),
                          ns.max_force, ns.max_free_length, ns.max_deflection)
    out, res = spring_problem(ns.kind, ns.moment, (math.radians(lo), math.radians(hi)), bounds, method=ns.method,
                              norm=ns.norm, grid=ns.grid if ns.grid is not None else DEFAULT_GRID,
                              target_error=ns.target_error, pareto=ns.pareto, design=design)
    if ns.plot:
        from balance.plots import plot_spring

        plot_spring(res, ns.plot, out.get("pareto"), out.get("spring"))
    return out


def _cmd_prismatic(ns) -> dict:
    from balance.countermass import verify_counter_mass

    res = verify_counter_mass(ns.mass, ns.inertia, ns.counter_mass, ns.stroke, stroke=ns.travel, C=ns.C)
    out = res.to_dict()
    if ns.dynamics:
        from balance.dynamics import slide_dynamics

        out["dynamics"] = slide_dynamics(ns.mass, ns.inertia, ns.counter_mass, ns.stroke, ns.dynamics)
    if ns.plot:
        from balance.plots import plot_prismatic

        plot_prismatic(res.m, res.inertia, res.M, res.q_max, res.stroke, res.C, ns.plot)
    return out


def _cmd_pantograph(ns) -> dict:
    from balance.pantograph import pantograph_from_dict
    from balance.problems import load_toml, solve_pantograph

    doc = load_toml(ns.file)
    out = solve_pantograph(doc, ns.file)
    if ns.plot:
        from balance.plots import plot_pantograph

        plot_pantograph(pantograph_from_dict(doc, ns.file)[0], ns.plot)
    return out


def _cmd_solve(ns) -> tuple[dict, Any]:
    from balance import problems
    from balance.errors import SchemaError

    doc = problems.load_toml(ns.file)
    table = {"arm": (problems.solve_arm, _table_arm), "spring": (problems.solve_spring, _table_spring),
             "slider": (problems.solve_prismatic, _table_prismatic),
             "pantograph": (problems.solve_pantograph, _table_pantograph)}
    kinds = [k for k in table if k in doc]
    if len(kinds) != 1:
        raise SchemaError(f"{ns.file}: a balance scene needs exactly one of [arm], [spring], [slider] or [pantograph].")
    solve, tab = table[kinds[0]]
    return solve(doc, ns.file), tab


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``mechsynth balance`` with ``argv`` (the arguments after ``balance``); return the exit code.

    Examples
    --------
    >>> main(["prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2",
    ...       "--stroke", "0.5", "--format", "json"])  # doctest: +ELLIPSIS
    {...
    0
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        ns = build_parser().parse_args(_fix_negative_ranges(argv))
    except _UsageError as exc:
        msg = str(exc).rstrip(".")
        print(f"mechsynth: {msg} (see '{PROG} --help').", file=sys.stderr)
        return 2
    except SystemExit as exc:  # --help
        return int(exc.code or 0)
    try:
        if ns.command == "arm":
            _emit(_cmd_arm(ns), ns.format, _table_arm)
        elif ns.command == "spring":
            out = _cmd_spring(ns)
            _emit(out, ns.format, _table_spring)
            if out.get("target_met") is False:
                return 1  # a valid query whose requested error is not reached
        elif ns.command == "prismatic":
            _emit(_cmd_prismatic(ns), ns.format, _table_prismatic)
        elif ns.command == "pantograph":
            _emit(_cmd_pantograph(ns), ns.format, _table_pantograph)
        elif ns.command == "solve":
            out, tab = _cmd_solve(ns)
            _emit(out, ns.format, tab)
    except BalanceError as exc:
        print(f"mechsynth: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into `head`: not an error of ours
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as exc:  # e.g. the plot file cannot be written
        print(f"mechsynth: cannot write or read a file ({exc.strerror}: {exc.filename}).", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
