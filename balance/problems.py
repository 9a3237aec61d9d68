"""One pure function per problem kind: parsed TOML document in, JSON-able dict out.

A scene runner calls these; the CLI calls them too. ``[scene]`` and ``[expect]`` tables
are ignored here; any other unknown key is a :class:`~balance.errors.SchemaError`
naming the source and the key.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

from ._schema import check_keys, check_top_level, get_number, get_range
from .arm import arm_from_dict
from .counterweights import counterweights
from .countermass import verify_counter_mass
from .errors import SchemaError
from .fit import DEFAULT_GRID, SpringBounds, fit_spring
from .pantograph import balance_pantograph, pantograph_from_dict
from .static import balance_arm

__all__ = ["solve_arm", "solve_spring", "solve_prismatic", "solve_pantograph", "load_toml"]


def load_toml(path: str) -> dict:
    """Read a TOML file; a syntax error becomes one :class:`SchemaError` sentence."""
    import tomllib

    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise SchemaError(f"{path}: no such file.") from None
    except tomllib.TOMLDecodeError as exc:
        raise SchemaError(f"{path}: not valid TOML ({exc}).") from None


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
    arm = arm_from_dict(doc, source)
    a = doc["arm"]
    ck = a.get("check", {})
    check_keys(ck, {"samples", "seed"}, "[arm.check]", source)
    samples = int(get_number(ck, "samples", "[arm.check]", source, default=1000))
    seed = int(get_number(ck, "seed", "[arm.check]", source, default=0))
    dv = a.get("devices", {})
    check_keys(dv, {"eccentricity", "r", "r0"}, "[arm.devices]", source)
    opts = {k: get_number(dv, k, "[arm.devices]", source) for k in ("eccentricity", "r", "r0")}
    res = balance_arm(arm, samples=samples, seed=seed, device_options=opts)
    out = res.to_dict()
    cw = a.get("counterweights", {})
    check_keys(cw, {"arm"}, "[arm.counterweights]", source)
    default_b = get_number(cw, "arm", "[arm.counterweights]", source)
    arms = {}
    for i, ln in enumerate(a["links"]):
        b = get_number(ln, "counterweight_arm", f"link '{arm.links[i].name}'", source, default=default_b)
        if b is not None:
            arms[i] = b
    out["counterweights"] = counterweights(res.arm, arms, samples=samples, seed=seed)
    out["kind"] = "arm"
    return out


_SPRING_KEYS = {"kind", "moment", "range_deg", "r", "r0", "a", "max_force", "max_free_length",
                "max_deflection", "method", "norm", "grid"}


def spring_from_dict(doc: Mapping[str, Any], source: str = "<spring>") -> dict:
    """Arguments of :func:`~balance.fit.fit_spring` from a ``[spring]`` document."""
    t = check_top_level(doc, "spring", source)
    check_keys(t, _SPRING_KEYS, "[spring]", source)
    w = "[spring]"
    rng = get_range(t, "range_deg", w, source)
    if rng is None:
        raise SchemaError(f"{source}: [spring] needs 'range_deg' = [low, high].")
    ranges = {}
    for key in ("r", "r0", "a"):
        v = get_range(t, key, w, source)
        if v is None:
            raise SchemaError(f"{source}: [spring] needs '{key}' = [low, high] (m).")
        ranges[key] = v
    return {
        "kind": t.get("kind", "compression"),
        "moment": get_number(t, "moment", w, source, required=True),
        "phi_range": (math.radians(rng[0]), math.radians(rng[1])),
        "bounds": SpringBounds(ranges["r"], ranges["r0"], ranges["a"],
                               get_number(t, "max_force", w, source),
                               get_number(t, "max_free_length", w, source),
                               get_number(t, "max_deflection", w, source)),
        "method": t.get("method"),
        "norm": t.get("norm", "max"),
        "grid": int(get_number(t, "grid", w, source, default=DEFAULT_GRID)),
    }


def solve_spring(doc: Mapping[str, Any], source: str = "<spring>") -> dict:
    """Fit the crank-and-rocker device of a ``[spring]`` document (see :func:`fit_spring`).

    Examples
    --------
    >>> doc = {"spring": {"kind": "tension", "moment": -50.0, "range_deg": [0, 180],
    ...                   "r": [0.05, 0.1], "r0": [0.1, 0.2], "a": [0, 0.3]}}
    >>> solve_spring(doc)["max_rel_error"] < 1e-12
    True
    """
    res = fit_spring(**spring_from_dict(doc, source))
    out = res.to_dict()
    out["kind_of_problem"] = "spring"
    return out


_SLIDER_KEYS = {"mass", "inertia", "counter_mass", "q_max", "stroke", "C", "samples"}


def solve_prismatic(doc: Mapping[str, Any], source: str = "<slider>") -> dict:
    """Counter-mass design of a ``[slider]`` document (see :func:`verify_counter_mass`).

    Examples
    --------
    >>> solve_prismatic({"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 2, "q_max": 0.5}})["C_min"]
    0.85
    """
    t = check_top_level(doc, "slider", source)
    check_keys(t, _SLIDER_KEYS, "[slider]", source)
    w = "[slider]"
    res = verify_counter_mass(
        get_number(t, "mass", w, source, required=True),
        get_number(t, "inertia", w, source, default=0.0),
        get_number(t, "counter_mass", w, source, required=True),
        get_number(t, "q_max", w, source, required=True),
        stroke=get_number(t, "stroke", w, source),
        C=get_number(t, "C", w, source),
        samples=int(get_number(t, "samples", w, source, default=2001)),
    )
    return res.to_dict()


def solve_pantograph(doc: Mapping[str, Any], source: str = "<pantograph>") -> dict:
    """Spring device and drive force of a ``[pantograph]`` document (see :mod:`balance.pantograph`)."""
    p, opts = pantograph_from_dict(doc, source)
    return balance_pantograph(p, samples=opts["samples"], seed=opts["seed"], r=opts["r"], r0=opts["r0"])
