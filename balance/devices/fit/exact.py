"""Exact devices: the zero-free-length tension spring (``a = r0``) and the compression-lever
device, with the least peak spring force the bounds allow."""

from __future__ import annotations

import math
from dataclasses import replace

from ...errors import InfeasibleBounds
from .problem import _check_feasible, _Problem
from .result import FitResult, LeverGeometry, SpringBounds, _finish


def _tension_exact(p: _Problem, max_lmax: float = math.inf):
    """The zero-free-length device (``a = r0``, exact) with the least peak spring force within the
    bounds, its longest spring length at most ``max_lmax`` (units of ℓ); None if there is none.

    Exact means κ = 1, so the peak force is ``|Φ0|/ℓ · L_max/(ρ(ρ + ρ0))`` with
    ``L_max² = ρ0² + 4ρ(ρ + ρ0)·S``, S the largest ``sin²(φ/2)``. It falls as ρ grows; at fixed ρ
    it is least at ``ρ0 = 2Sρ/(1 − 2S)`` (it falls all the way where S ≥ 1/2). Where the length
    limit binds, ``ρ(ρ + ρ0) = (Λ² − ρ0²)/(4S)`` and the force grows with ρ0. So ρ is the largest
    crank for every ρ0 up to ``cap`` (where the limit starts to bind at that crank), ρ0 the point of
    that interval nearest the unconstrained best; else the least ρ0 with the crank the limit allows.
    """
    lo0, hi0 = max(p.rho0_b[0], p.al_b[0]), min(p.rho0_b[1], p.al_b[1])  # a = r0 within both ranges
    if lo0 > hi0:
        return None
    S, rho = p.s2max, p.rho_b[1]
    max_lmax *= 1 - 1e-12  # (a device on the limit stays within it after round-off)
    cap = math.inf
    if math.isfinite(max_lmax):
        disc = max_lmax * max_lmax - 4 * S * (1 - S) * rho * rho
        cap = -2 * S * rho + math.sqrt(disc) if disc >= 0 else -math.inf
    if cap >= lo0:
        rho0 = min(max(2 * S * rho / (1 - 2 * S) if S < 0.5 else math.inf, lo0), hi0, cap)
    else:
        rho0 = lo0
        if rho0 >= max_lmax:
            return None  # L_max > r0 for every crank
        rho = (math.sqrt(rho0 * rho0 + (max_lmax * max_lmax - rho0 * rho0) / S) - rho0) / 2
        if rho < p.rho_b[0]:
            return None
    if p.kappa_max(rho, rho0, rho0) < 1.0:
        return None  # the least force is above the limit: so is every other
    return rho, rho0, rho0, 1.0


#: deflection ratio (compression over free length) of the lever device's spring when none is given
LEVER_DEFLECTION = 0.5


def _lever_device(moment: float, lo: float, hi: float, b: SpringBounds, grid: int, norm: str,
                  t_start: float) -> FitResult:
    """The compression-lever device at ``a = r0``: exact, with the lever it needs.

    The crank geometry with the least spring force among ``a = r0`` devices (as for a
    zero-free-length tension spring); the spring's own free length ``s`` (= the stop's
    distance from ``C``) follows from the largest compression ``L_max`` it must take:
    ``s = L_max/δ`` with ``δ`` = ``max_deflection`` (default 0.5).
    """
    delta = LEVER_DEFLECTION if b.max_deflection is None else b.max_deflection
    p = _Problem("compression-lever", moment, lo, hi, SpringBounds(b.r, b.r0, b.a, b.max_force), grid, norm)
    if not (b.a[0] <= b.r0[1] and b.a[1] >= b.r0[0]):
        raise InfeasibleBounds(
            f"the compression-lever device is exact only at a = r0, but a ∈ [{b.a[0]:g}, {b.a[1]:g}] m and "
            f"r0 ∈ [{b.r0[0]:g}, {b.r0[1]:g}] m never meet; widen the range of a or of r0."
        )
    _check_feasible(p)
    longest = math.inf if b.max_free_length is None else delta * b.max_free_length / p.ell
    exact = _tension_exact(p, longest)
    if exact is None:
        limits = []
        if b.max_force is not None:
            limits.append(f"keeps the spring force below {b.max_force:g} N")
        if b.max_free_length is not None:
            limits.append(f"fits a spring of at most {b.max_free_length:g} m at a deflection ratio of {delta:g}")
        raise InfeasibleBounds(
            f"no compression-lever device with a = r0 {' and '.join(limits)}; raise the force limit, "
            "the maximum free length or the maximum deflection."
        )
    res = _finish(p, exact, "exact", norm, t_start, "compression spring on the lever beyond B, a = r0: exact", [])
    lmax = math.sqrt(res.r0 ** 2 + 4 * res.r * res.d * p.s2max)
    lmin = math.sqrt(res.r0 ** 2 + 4 * res.r * res.d * p.s2min)
    lever = LeverGeometry.for_spring(lmax / delta, lmin, lmax)
    return replace(res, deflection=delta, lever=lever, notes=res.notes + (lever.note(),))
