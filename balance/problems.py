"""One pure function per problem kind: parsed TOML document in, JSON-able dict out.

A scene runner calls these; the CLI calls them too. ``[scene]`` and ``[expect]`` tables
are ignored here; any other unknown key is a :class:`~balance.errors.SchemaError`
naming the source and the key.
"""

from __future__ import annotations

import math
import os
from typing import Any, Mapping

import numpy as np

from .arm import arm_from_table
from .counterweights import counterweights
from .countermass import verify_counter_mass
from .errors import InvalidInput, SchemaError
from .helical import design_for_device
from .urdf import pinocchio_check
from .tradeoff import advice, bound_sensitivity, pareto_front
from .transmission import transmissions
from .schema import load_toml, parse
from .fit import FitResult, SpringBounds, fit_spring, lever_note
from .pantograph import balance_pantograph, pantograph_from_dict
from .static import balance_arm

__all__ = ["solve_arm", "solve_spring", "spring_problem", "solve_prismatic", "solve_pantograph", "load_toml"]


def solve_arm(doc: Mapping[str, Any], source: str = "<arm>") -> dict:
    """Balance the arm of an ``[arm]`` document.

    Returns ``terms`` (``amplitude``, ``phase``, ``form`` over joint coordinates and
    ``drive_form`` over drive shafts), ``devices``, ``max_residual`` (N·m or N, at
    ``[arm.check] samples`` random configurations, default 1000, seed 0),
    ``relative_residual``, ``prismatic``, ``payload`` and ``counterweights``.

    Examples
    --------
    >>> doc = {"arm": {"links": [{"joint": "revolute", "length": 1.0, "weight": 10.0}]}}
    >>> out = solve_arm(doc)
    >>> out["terms"][0]["amplitude"], out["max_residual"] < 1e-12
    (5.0, True)
    """
    t = parse(doc, "arm", source)
    if t.urdf is not None:
        out = _solve_urdf_arm(t, source)
    else:
        arm = arm_from_table(t, source)
        d = t.devices
        opts = {"eccentricity": d.eccentricity, "r": d.r, "r0": d.r0}
        res = balance_arm(arm, samples=t.check.samples, seed=t.check.seed, device_options=opts)
        out = res.to_dict()
        arms = {}
        for i, ln in enumerate(t.links):
            b = ln.counterweight_arm if ln.counterweight_arm is not None else t.counterweights.arm
            if b is not None:
                arms[i] = b
        out["counterweights"] = counterweights(res.arm, arms, samples=t.check.samples, seed=t.check.seed)
        out["pinocchio"] = pinocchio_check(res.arm, res.terms, t.check.samples, t.check.seed, t.g,
                                           worst=res.check.worst, scale=res.check.max_gravity_force)
    if t.transmission:
        out["transmission"] = transmissions([term["drive_form"] for term in out["terms"]],
                                            [f"ψ{i + 1}" for i in range(len(out["joints"]))])
    out["kind"] = "arm"
    return out


def _solve_urdf_arm(t, source: str) -> dict:
    """Balance an arm read from URDF (path relative to the scene file); Pinocchio is the check."""
    from .arm import _drive_matrix
    from .static import ArmBalance, check_terms, device_table, prismatic_rows
    from .urdf import load_urdf, pinocchio_check

    if t.links or t.loads:
        raise SchemaError(f"{source}: [arm] takes its links from 'urdf'; remove [[arm.links]] and [[arm.loads]].")
    base = os.path.dirname(source) if os.path.exists(source) else ""
    path = t.urdf if os.path.isabs(t.urdf) else os.path.join(base, t.urdf)
    arm = load_urdf(path, accuracy=t.accuracy, g=t.g, name=t.name if t.name != "arm" else None)
    if t.drives != "joint":
        try:
            arm.drive_matrix = np.asarray(_drive_matrix(t.drives, arm.n))
        except (TypeError, ValueError):
            raise SchemaError(f"{source}: 'drives' must be a {arm.n}×{arm.n} matrix for this URDF arm.") from None
        if arm.drive_matrix.shape != (arm.n, arm.n) or abs(np.linalg.det(arm.drive_matrix)) < 1e-12:
            raise SchemaError(f"{source}: 'drives' must be a non-singular {arm.n}×{arm.n} matrix for this URDF arm.")
    terms = arm.harmonic_terms()
    q = arm.sample(t.check.samples, t.check.seed)
    check = check_terms(arm, terms, q=q, seed=t.check.seed)
    d = t.devices
    devices = device_table(arm, terms, {"eccentricity": d.eccentricity, "r": d.r, "r0": d.r0})
    out = ArmBalance(arm, terms, devices, check, prismatic_rows(arm), None).to_dict()
    out["urdf"] = path
    out["pinocchio"] = pinocchio_check(arm, terms, t.check.samples, t.check.seed, t.g, worst=check.worst,
                                       scale=check.max_gravity_force)
    out["counterweights"] = {"available": False, "reason": "not computed for URDF arms"}
    return out


def _spring_table(doc: Mapping[str, Any], source: str):
    t = parse(doc, "spring", source)
    if t.a is None:
        raise SchemaError(f"{source}: [spring] needs 'a' = [low, high] (m).")
    return t


def spring_from_dict(doc: Mapping[str, Any], source: str = "<spring>") -> dict:
    """Arguments of :func:`~balance.fit.fit_spring` from a ``[spring]`` document."""
    t = _spring_table(doc, source)
    return {
        "kind": t.kind,
        "moment": t.moment,
        "phi_range": (math.radians(t.range_deg[0]), math.radians(t.range_deg[1])),
        "bounds": SpringBounds(tuple(t.r), tuple(t.r0), tuple(t.a), t.max_force, t.max_free_length,
                               t.max_deflection),
        "method": t.method,
        "norm": t.norm,
        "grid": t.grid,
    }


def spring_options(doc: Mapping[str, Any], source: str = "<spring>") -> dict:
    """The rest of :func:`spring_problem`'s arguments (target, Pareto front, spring design)."""
    t = _spring_table(doc, source)
    design = None
    if t.design is not None:
        d = t.design
        design = {"material": d.material, "max_outer_diameter": d.max_outer_diameter,
                  "min_inner_diameter": d.min_inner_diameter, "ends": d.ends}
        if d.guided is not None:
            design["guided"] = d.guided
    return {"target_error": t.target_error, "pareto": t.pareto, "design": design}


def spring_problem(kind: str, moment: float, phi_range, bounds: SpringBounds, method: str | None = None,
                   norm: str = "max", grid: int = 61, target_error: float | None = None,
                   pareto: bool = False, design: dict | None = None) -> tuple[dict, FitResult]:
    """Fit a device, then (compression) the trade-off advice, and a helical spring on request.

    Returns the JSON-able result (the fit's fields plus ``warnings``, ``sensitivity``,
    ``pareto`` when asked, ``spring`` when ``design`` is given, ``target_met``) and the fit.
    """
    if target_error is not None and not (math.isfinite(target_error) and 0 < target_error < 1):
        raise InvalidInput(f"the requested error must lie in (0, 1), not {target_error}.")
    res = fit_spring(kind, moment, phi_range, bounds, method=method, norm=norm, grid=grid)
    out = res.to_dict()
    sens = bound_sensitivity(res, bounds) if res.method != "exact" else []
    front = pareto_front(res, bounds) if pareto else None
    if pareto and kind != "compression":
        raise InvalidInput(f"the Pareto front is for the fitted compression device; a {kind} device is exact.")
    out["sensitivity"] = sens
    if front is not None:
        out["pareto"] = front
    out["warnings"] = advice(res, sens, target_error, front)
    out["target_error"] = target_error
    err = res.max_rel_error if norm == "max" else res.rms_rel_error
    out["target_met"] = None if target_error is None else err <= target_error
    if design is not None:
        out["spring"] = design_for_device(res, **design)
        if kind == "compression-lever":  # the designed spring fixes the lever: the shortest the checks allow
            lv = out["spring"].pop("lever")
            s = lv["stop_distance_from_C"]
            out["lever"] = dict(out["lever"], **lv, spring_free_length=s, deflection_ratio=lv["reach_from_C_fig_a"] / s,
                                spring_length_min=s - lv["reach_from_C_fig_a"], designed_from_spring=True)
            out["deflection"] = out["lever"]["deflection_ratio"]
            out["notes"] = [n for n in out["notes"] if not n.startswith("the lever reaches")] + [lever_note(out["lever"])]
        sp = out["spring"]
        if sp.get("buckling") and not sp["buckling"]["safe"]:
            out["warnings"].append(
                f"the spring buckles (critical deflection {1e3 * sp['buckling']['critical_deflection_m']:.3g} mm < "
                f"{1e3 * sp['buckling']['max_deflection_m']:.4g} mm): guide it on a rod or in a sleeve")
    return out, res


def solve_spring(doc: Mapping[str, Any], source: str = "<spring>") -> dict:
    """Fit the crank-and-rocker device of a ``[spring]`` document (see :func:`spring_problem`).

    Examples
    --------
    >>> doc = {"spring": {"kind": "tension", "moment": -50.0, "range_deg": [0, 180],
    ...                   "r": [0.05, 0.1], "r0": [0.1, 0.2], "a": [0, 0.3]}}
    >>> solve_spring(doc)["max_rel_error"] < 1e-12
    True
    """
    out, _ = spring_problem(**spring_from_dict(doc, source), **spring_options(doc, source))
    out["kind_of_problem"] = "spring"
    return out


def solve_prismatic(doc: Mapping[str, Any], source: str = "<slider>") -> dict:
    """Counter-mass design of a ``[slider]`` document (see :func:`verify_counter_mass`).

    Examples
    --------
    >>> solve_prismatic({"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 2, "q_max": 0.5}})["C_min"]
    0.85
    """
    t = parse(doc, "slider", source)
    res = verify_counter_mass(t.mass, t.inertia, t.counter_mass, t.q_max, stroke=t.stroke, C=t.C,
                              samples=t.samples)
    out = res.to_dict()
    if t.dynamics is not None:
        from .dynamics import slide_dynamics

        d = t.dynamics
        out["dynamics"] = slide_dynamics(t.mass, t.inertia, t.counter_mass, t.q_max, d.arm, d.length, d.mass,
                                         d.samples, d.seed)
    return out


def solve_pantograph(doc: Mapping[str, Any], source: str = "<pantograph>") -> dict:
    """Spring device and drive force of a ``[pantograph]`` document (see :mod:`balance.pantograph`)."""
    p, opts = pantograph_from_dict(doc, source)
    return balance_pantograph(p, samples=opts["samples"], seed=opts["seed"], r=opts["r"], r0=opts["r0"])
