"""Fits that end on bounds are a design trade-off: sensitivities, the Pareto front, advice.

A fitted compression device almost always runs to some bound: a longer spring (``r0``,
``a``, free length) or a stronger one (peak force) lowers the error. This module says
which bounds the optimum sits on and what moving each by 25 % buys
(:func:`bound_sensitivity`), maps the whole trade-off between the error, the device's
size (its free length ``2r + r0 + a``, the length the spring and its guide need) and the
peak spring force (:func:`pareto_front`), and turns both into warnings (:func:`advice`).

Examples
--------
>>> import math
>>> from balance.devices.fit import SpringBounds, fit_spring
>>> b = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))
>>> res = fit_spring("compression", 100.0, (math.radians(20), math.radians(160)), b)
>>> [s.bound for s in bound_sensitivity(res, b)]
['r=min', 'r0=max', 'a=max']
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from mechbase import Row

from ..errors import BalanceError
from .fit import FitResult, SpringBounds, fit_spring

__all__ = ["Sensitivity", "ParetoPoint", "bound_sensitivity", "pareto_front", "advice", "RELAX"]

#: how far each active bound is moved to measure what it costs
RELAX = 0.25


@dataclass(frozen=True)
class Sensitivity(Row):
    """What moving one active bound by :data:`RELAX` buys: the fit's norm after the move."""

    bound: str
    move: str
    error: float
    gain: float


@dataclass(frozen=True)
class ParetoPoint(Row):
    """A device on the front: its error (the fit's norm), size (free length, m) and peak force (N)."""

    error: float
    size: float
    force: float
    c: float
    r: float
    r0: float
    a: float
    active_bounds: tuple[str, ...]


def _refit(res: FitResult, bounds: SpringBounds) -> FitResult | None:
    try:
        return fit_spring(res.kind, res.moment, res.phi_range, bounds, norm=res.norm, grid=res.grid,
                          device=res.family)
    except BalanceError:
        return None


def _error(res: FitResult) -> float:
    return res.max_rel_error if res.norm == "max" else res.rms_rel_error


def _relaxed(name: str, b: SpringBounds, res: FitResult) -> tuple[SpringBounds, str] | None:
    """The bounds with ``name`` moved by :data:`RELAX`, and how to say it."""
    up, down = 1 + RELAX, 1 - RELAX
    if name == "r=min" and b.r[0] > 0:
        v = b.r[0] * down
        return replace(b, r=(v, b.r[1])), f"lower bound on r to {v:.4g} m"
    if name == "r=max":
        v = b.r[1] * up
        return replace(b, r=(b.r[0], v)), f"upper bound on r to {v:.4g} m"
    if name == "r0=max":
        v = b.r0[1] * up
        return replace(b, r0=(b.r0[0], v)), f"upper bound on r0 to {v:.4g} m"
    if name == "r0=min" and b.r0[0] > 0:
        v = b.r0[0] * down
        return replace(b, r0=(v, b.r0[1])), f"lower bound on r0 to {v:.4g} m"
    if name == "rod=max":
        v = b.rod[1] * up
        return replace(b, rod=(b.rod[0], v)), f"upper bound on the rod to {v:.4g} m"
    if name == "rod=min":
        v = b.rod[0] * down
        return replace(b, rod=(v, b.rod[1])), f"lower bound on the rod to {v:.4g} m"
    if name == "a=max" and math.isfinite(b.a[1]):
        v = b.a[1] * up if b.a[1] > 0 else RELAX * res.reference_length
        return replace(b, a=(b.a[0], v)), f"upper bound on a to {v:.4g} m"
    if name == "a=min" and b.a[0] > 0:
        v = b.a[0] * down
        return replace(b, a=(v, b.a[1])), f"lower bound on a to {v:.4g} m"
    if name == "max_free_length" and b.max_free_length is not None:
        v = b.max_free_length * up
        return replace(b, max_free_length=v), f"maximum free length to {v:.4g} m"
    if name == "max_force" and b.max_force is not None:
        v = b.max_force * up
        return replace(b, max_force=v), f"force limit to {v:.4g} N"
    if name == "max_deflection" and b.max_deflection is not None and b.max_deflection < 0.95:
        v = min(0.95, b.max_deflection * up)
        return replace(b, max_deflection=v), f"maximum deflection to {v:.3g}"
    return None


def bound_sensitivity(res: FitResult, bounds: SpringBounds) -> list[Sensitivity]:
    """For each bound the optimum sits on: the error when that bound alone moves by 25 %.

    Returns :class:`Sensitivity` rows (``move`` says which bound moves where), best gain first.
    """
    out = []
    for name in res.active_bounds:
        moved = _relaxed(name, bounds, res)
        if moved is None:
            continue
        new = _refit(res, moved[0])
        if new is None:
            continue
        before, after = _error(res), _error(new)
        out.append(Sensitivity(name, moved[1], after, (before - after) / before if before > 0 else 0.0))
    return sorted(out, key=lambda s: -s.gain)


def _nondominated(points: list[ParetoPoint]) -> list[ParetoPoint]:
    def key(p):
        return (p.error, p.size, p.force)

    unique = {tuple(round(v, 9) for v in key(p)): p for p in points}
    points = list(unique.values())
    front = []
    for p in points:
        dominated = any(all(a <= b * (1 + 1e-9) for a, b in zip(key(q), key(p)))
                        and any(a < b * (1 - 1e-6) for a, b in zip(key(q), key(p))) for q in points if q is not p)
        if not dominated:
            front.append(p)
    return sorted(front, key=lambda p: (round(p.size, 4), p.force))


def pareto_front(res: FitResult, bounds: SpringBounds, steps: int = 7) -> list[ParetoPoint]:
    """Non-dominated devices in (error, size, peak force) within the box bounds on r, r0, a.

    The force and free-length limits are what is traded, so they are swept: fits with every
    combination of ``steps`` free-length limits (from the shortest device the box allows to
    the free length of the best device without those limits) and ``steps`` force limits
    (from the least a crank of at most ``r_max`` can work with to that device's peak force).
    The devices no other beats in all three are kept (:class:`ParetoPoint`: ``size`` is the
    free length 2r + r0 + a); the fit itself is among the candidates.
    """
    if res.kind != "compression":
        return []
    free = _refit(res, replace(bounds, max_force=None, max_free_length=None)) or res
    smallest = 2 * bounds.r[0] + bounds.r0[0] + bounds.a[0]
    force_lo = abs(res.moment) * _peak_sin(res.phi_range) / bounds.r[1]
    sizes = np.geomspace(max(smallest * 1.02, 1e-12), max(free.free_length, smallest * 1.05), steps)
    forces = np.geomspace(force_lo * 1.05, max(free.max_force, force_lo * 1.1), steps)
    rows = [_row(res), _row(free)]
    for s in sizes:
        for f in forces:
            new = _refit(res, replace(bounds, max_free_length=float(s), max_force=float(f)))
            if new is not None:
                rows.append(_row(new))
    return _nondominated(rows)


def _row(r: FitResult) -> ParetoPoint:
    return ParetoPoint(_error(r), r.free_length, r.max_force, r.c, r.r, r.r0, r.a, tuple(r.active_bounds))


def _peak_sin(rng) -> float:
    lo, hi = rng
    k = math.ceil((lo - math.pi / 2) / math.pi)
    return 1.0 if math.pi / 2 + k * math.pi <= hi else max(abs(math.sin(lo)), abs(math.sin(hi)))


def advice(res: FitResult, sensitivity: list[Sensitivity], target_error: float | None = None,
           front: list[ParetoPoint] | None = None) -> list[str]:
    """Warnings for a fit: on a bound (and which one to move), or short of the requested error."""
    out = []
    what = "max" if res.norm == "max" else "RMS"
    if sensitivity:
        best = sensitivity[0]
        on = ", ".join(s.bound for s in sensitivity)
        out.append(
            f"the optimum sits on the bound(s) {on}: it is a trade-off, not a free optimum; moving the "
            f"{best.move} lowers the {what} error from {100 * _error(res):.3g} % to {100 * best.error:.3g} %"
        )
    if target_error is not None and _error(res) > target_error:
        msg = f"the {what} error {100 * _error(res):.3g} % misses the requested {100 * target_error:.3g} %"
        ok = [p for p in (front or []) if p.error <= target_error]
        if ok:
            small = min(ok, key=lambda p: p.size)
            weak = min(ok, key=lambda p: p.force)
            msg += (f"; the Pareto front reaches it with a free length of {small.size:.4g} m "
                    f"(peak force {small.force:.4g} N) or a peak force of {weak.force:.4g} N "
                    f"(free length {weak.size:.4g} m): raise the maximum free length or the force limit to there")
        elif front:
            msg += "; no device within the bounds on r, r0 and a reaches it: widen them"
        elif sensitivity:
            msg += f"; move the {sensitivity[0].move} first (the largest gain)"
        out.append(msg)
    return out
