"""The crank-and-rocker fitting problem in non-dimensional variables, and its feasibility.

:class:`_Problem` evaluates the weighted errors ``|sin φ|·(κ·g − 1)`` on the fit grid, solves
for the scale ``κ`` exactly (closed form for RMS, :func:`_minimax_scale` for the max norm) and
maps the box-bounded variables ``z = (ρ, ρ0, t)`` to ``(ρ, ρ0, α)``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from ...errors import InfeasibleBounds, InvalidRange
from .result import SpringBounds


# --------------------------------------------------------------------------- problem
class _Problem:
    """The non-dimensional fitting problem on a grid."""

    def __init__(self, kind: str, moment: float, lo: float, hi: float, b: SpringBounds, grid: int, norm: str):
        self.kind, self.moment, self.lo, self.hi, self.bounds = kind, moment, lo, hi, b
        self.ell = b.r[1]
        e = self.ell
        self.grid = grid
        self.phi = np.linspace(lo, hi, grid)
        if norm == "max":
            # where φ = 0 (mod 2π) is in range the moment varies on the scale r0/r: let the
            # max-norm fit see it (the RMS norm rightly gives that sliver little weight)
            self.phi = np.union1d(self.phi, _cluster(lo, hi, b.r0[0] / b.r[1], 24))
        self.w = np.abs(np.sin(self.phi))
        self.S = np.sin(self.phi / 2) ** 2
        self.s2min, self.s2max = _sin2_half_extremes(lo, hi)
        self.rho_b = (b.r[0] / e, 1.0)
        self.rho0_b = (b.r0[0] / e, b.r0[1] / e)
        self.al_b = (b.a[0] / e, b.a[1] / e)
        self.Fhat = math.inf if b.max_force is None else b.max_force * e / abs(moment)
        self.Lf = math.inf if b.max_free_length is None else b.max_free_length / e
        self.delta = b.max_deflection
        self.nfev = 0

    # -- geometry ---------------------------------------------------------------
    def l0(self, rho, rho0, al):
        return 2 * rho + rho0 + al if self.kind == "compression" else rho0 - al

    def alpha_limits(self, rho, rho0) -> tuple[float, float]:
        lo, hi = self.al_b
        if self.kind == "compression":
            hi = min(hi, self.Lf - 2 * rho - rho0)
            if self.delta is not None:
                lmin = math.sqrt(rho0 * rho0 + 4 * rho * (rho + rho0) * self.s2min)
                hi = min(hi, lmin / (1 - self.delta) - 2 * rho - rho0)
        else:
            hi = min(hi, rho0)  # free length r0 − a ≥ 0
            lo = max(lo, rho0 - self.Lf)
        if hi < lo <= hi + 1e-12 * max(1.0, abs(hi)):
            hi = lo  # a device exactly on a limit, not to be lost to the round-off of normalising
        return lo, hi

    def kappa_max(self, rho, rho0, al) -> float:
        if not math.isfinite(self.Fhat):
            return math.inf
        l0 = self.l0(rho, rho0, al)
        if self.kind == "compression":
            stretch = l0 - math.sqrt(rho0 * rho0 + 4 * rho * (rho + rho0) * self.s2min)
        else:
            stretch = math.sqrt(rho0 * rho0 + 4 * rho * (rho + rho0) * self.s2max) - l0
        if stretch <= 0:
            return math.inf
        return self.Fhat * rho * (rho + rho0) / stretch

    def shape(self, rho, rho0, al):
        L = np.sqrt(rho0 * rho0 + 4.0 * rho * (rho + rho0) * self.S)
        l0 = self.l0(rho, rho0, al)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = np.where(L > 0, l0 / L, 0.0)
        return q - 1.0 if self.kind == "compression" else 1.0 - q

    def decode(self, z) -> tuple[float, float, float, float]:
        """``z = (ρ, ρ0, t)`` → ``(ρ, ρ0, α, violation)``."""
        rho, rho0, t = float(z[0]), float(z[1]), float(z[2])
        lo, hi = self.alpha_limits(rho, rho0)
        if hi < lo:
            return rho, rho0, lo, lo - hi
        return rho, rho0, lo + min(max(t, 0.0), 1.0) * (hi - lo), 0.0

    def encode(self, rho, rho0, al) -> np.ndarray:
        lo, hi = self.alpha_limits(rho, rho0)
        t = 0.0 if hi <= lo else (al - lo) / (hi - lo)
        return np.array([rho, rho0, min(max(t, 0.0), 1.0)])

    @property
    def z_bounds(self):
        """Box of ``z``.  A tension spring's free length r0 − a ≤ limit with a ≤ a_max needs
        r0 ≤ a_max + limit: in the box, not left to the penalty (whose optimum would lie past it)."""
        top = self.rho0_b[1]
        if self.kind == "tension":
            top = max(min(top, self.al_b[1] + self.Lf), self.rho0_b[0])
        return ([self.rho_b[0], self.rho0_b[0], 0.0], [self.rho_b[1], top, 1.0])

    # -- projected residuals ----------------------------------------------------------
    def errors(self, rho, rho0, al, kappa):
        """Weighted errors ``|sin φ|·(κ·g − 1)`` on the grid: one evaluation (counted in ``nfev``)."""
        self.nfev += 1
        return self.w * (kappa * self.shape(rho, rho0, al) - 1.0)

    def best_kappa(self, rho, rho0, al, norm: str, weights=None) -> float:
        g = self.shape(rho, rho0, al)
        h, s = self.w * g, self.w
        kmax = self.kappa_max(rho, rho0, al)
        if norm == "rms":
            v = 1.0 if weights is None else weights
            den = float(np.sum(v * h * h))
            k = float(np.sum(v * h * s)) / den if den > 0 else 0.0
            return min(max(k, 0.0), kmax)
        return _minimax_scale(h, s, kmax)

    def projected(self, z, norm: str, weights=None):
        rho, rho0, al, viol = self.decode(z)
        k = self.best_kappa(rho, rho0, al, norm, weights)
        return self.errors(rho, rho0, al, k), k, viol

    def objective(self, z, norm: str) -> float:
        e, _, viol = self.projected(z, norm)
        val = float(np.max(np.abs(e))) if norm == "max" else float(np.sqrt(np.mean(e * e)))
        return val + 10.0 * viol

    def full_problem(self, z0, norm: str):
        """SLSQP's view: the start ``y0 = (ρ, ρ0, α, κ)`` from ``z0``, the bounds of ``y``, the
        constraints (dicts for :func:`scipy.optimize.minimize`) and the errors as a function of ``y``."""
        rho, rho0, al, _ = self.decode(z0)
        k = self.best_kappa(rho, rho0, al, norm)
        y0 = [rho, rho0, al, k]
        al_hi = self.al_b[1] if math.isfinite(self.al_b[1]) else None
        bounds = [self.rho_b, self.rho0_b, (self.al_b[0], al_hi), (0.0, None)]
        cons: list[dict] = []

        def l_at(y, s2):
            return math.sqrt(y[1] ** 2 + 4 * y[0] * (y[0] + y[1]) * s2)

        if self.kind == "compression":
            if math.isfinite(self.Lf):
                cons.append({"type": "ineq", "fun": lambda y: self.Lf - (2 * y[0] + y[1] + y[2])})
            if self.delta is not None:
                cons.append({"type": "ineq",
                             "fun": lambda y: l_at(y, self.s2min) - (1 - self.delta) * (2 * y[0] + y[1] + y[2])})
            if math.isfinite(self.Fhat):
                cons.append({"type": "ineq", "fun": lambda y: self.Fhat * y[0] * (y[0] + y[1])
                             - y[3] * (2 * y[0] + y[1] + y[2] - l_at(y, self.s2min))})
        else:
            cons.append({"type": "ineq", "fun": lambda y: y[1] - y[2]})
            if math.isfinite(self.Lf):
                cons.append({"type": "ineq", "fun": lambda y: self.Lf - (y[1] - y[2])})
            if math.isfinite(self.Fhat):
                cons.append({"type": "ineq", "fun": lambda y: self.Fhat * y[0] * (y[0] + y[1])
                             - y[3] * (l_at(y, self.s2max) - (y[1] - y[2]))})

        def err(y):
            return self.errors(y[0], y[1], y[2], y[3])

        return y0, bounds, cons, err

    def encode_full(self, y) -> np.ndarray:
        """``z`` of SLSQP's full variables ``y``."""
        return self.encode(y[0], y[1], y[2])

    def start(self, norm: str) -> np.ndarray:
        """Best point of a small deterministic scan of the box (log-spaced lengths)."""
        best, bz = math.inf, None
        (_, rho0_lo, _), (_, rho0_hi, _) = self.z_bounds
        for rho in _span(*self.rho_b, 4):
            for rho0 in _span(rho0_lo, rho0_hi, 4):
                for t in (0.0, 0.5, 1.0):
                    z = np.array([rho, rho0, t])
                    v = self.objective(z, norm)
                    if v < best:
                        best, bz = v, z
        return bz


def _cluster(lo: float, hi: float, width: float, n: int) -> np.ndarray:
    """Points geometrically clustered around the multiples of 2π inside ``[lo, hi]``."""
    out = []
    width = max(width, 1e-12)
    if width > 0.05:
        return np.array([])
    offs = np.geomspace(width * 1e-1, 0.5, n)
    for kk in range(math.ceil(lo / (2 * math.pi)), math.floor(hi / (2 * math.pi)) + 1):
        c0 = 2 * math.pi * kk
        out.append(c0 + offs)
        out.append(c0 - offs)
    if not out:
        return np.array([])
    ex = np.concatenate(out)
    return ex[(ex >= lo) & (ex <= hi)]


def _span(lo: float, hi: float, n: int) -> np.ndarray:
    if lo > 0 and hi / lo > 10:
        return np.geomspace(lo, hi, n)
    return np.linspace(lo, hi, n)


def _sin2_half_extremes(lo: float, hi: float) -> tuple[float, float]:
    """min and max of ``sin²(φ/2)`` over ``[lo, hi]`` (spring length extremes)."""
    vals = [math.sin(lo / 2) ** 2, math.sin(hi / 2) ** 2]
    if math.floor(hi / (2 * math.pi)) >= math.ceil(lo / (2 * math.pi)):
        vals.append(0.0)  # a multiple of 2π lies in the range
    if math.floor((hi - math.pi) / (2 * math.pi)) >= math.ceil((lo - math.pi) / (2 * math.pi)):
        vals.append(1.0)  # an odd multiple of π lies in the range
    return min(vals), max(vals)


def _minimax_scale(h: np.ndarray, s: np.ndarray, kmax: float) -> float:
    """``argmin_{0≤κ≤κmax} max_i |κ·h_i − s_i|`` (exact to round-off).

    Each term is first written with ``h_i ≥ 0`` (``|κh − s| = |κ(−h) − (−s)|``). Then
    ``F_up(κ) = max(κh − s)`` rises and ``F_dn(κ) = max(s − κh)`` falls; the optimum is where
    they cross, the root of ``F_up − F_dn`` (Brent's method: exact steps on its linear pieces),
    0 when ``F_up`` is already the larger at 0, or κmax when they cross beyond it.
    """
    if not h.size:
        return 0.0
    flip = np.where(h < 0, -1.0, 1.0)
    h, s = h * flip, s * flip
    hmax, smax = float(np.max(h)), float(np.max(s))
    if hmax <= 0 or smax <= 0:
        return 0.0  # κ has nothing to lift, or nothing to lift towards

    def rise(k):  # F_up − F_dn
        up = k * h - s
        return float(np.max(up) + np.min(up))

    if rise(0.0) >= 0:
        return 0.0
    # at 2·max|s|/hmax, F_up ≥ max|s| ≥ F_dn: the crossing is in [0, top]
    top = min(kmax, 2.0 * float(np.max(np.abs(s))) / hmax)
    if rise(top) <= 0:
        return top
    return optimize.brentq(rise, 0.0, top)


def _max_abs_sin(lo: float, hi: float) -> float:
    """Largest |sin φ| over [lo, hi] (1 when a multiple of π/2 + kπ lies inside)."""
    k = math.ceil((lo - math.pi / 2) / math.pi)
    if math.pi / 2 + k * math.pi <= hi:
        return 1.0
    return max(abs(math.sin(lo)), abs(math.sin(hi)))


def _check_feasible(p: _Problem) -> None:
    b = p.bounds
    if not math.isfinite(p.rho0_b[1]):
        raise InvalidRange("r0 needs a finite upper bound.")
    peak = _max_abs_sin(p.lo, p.hi)
    if p.Fhat < peak:  # a spring force F on a crank r gives at most F·r
        raise InfeasibleBounds(
            f"the force limit {b.max_force:g} N on a crank of at most {b.r[1]:g} m gives at most "
            f"{b.max_force * b.r[1]:g} N·m, less than the {abs(p.moment) * peak:g} N·m the target needs in this "
            f"range; raise the force limit or the longest crank."
        )
    if p.kind == "compression":
        if not math.isfinite(p.al_b[1]) and not math.isfinite(p.Lf) and p.delta is None:
            raise InfeasibleBounds(
                "with a compression spring and no upper bound on the pre-load a (nor a maximum free "
                "length or deflection), the error keeps falling as a grows without limit; give a "
                "finite upper bound on a, a maximum free length or a maximum deflection."
            )
        smallest = 2 * b.r[0] + b.r0[0] + b.a[0]
        if b.max_free_length is not None and smallest > b.max_free_length:
            raise InfeasibleBounds(
                f"the shortest compression device within the bounds has free length 2r+r0+a = "
                f"{smallest:g} m, more than the maximum free length {b.max_free_length:g} m."
            )
    else:
        if b.a[0] > b.r0[1]:
            raise InfeasibleBounds(
                f"a tension spring needs a pre-extension a ≤ r0, but a ≥ {b.a[0]:g} m and r0 ≤ {b.r0[1]:g} m."
            )
    # any (ρ, ρ0) with a non-empty α interval? (scan incl. corners)
    for rho in _span(*p.rho_b, 9):
        for rho0 in _span(*p.rho0_b, 9):
            lo, hi = p.alpha_limits(rho, rho0)
            if lo <= hi:
                return
    if p.kind == "compression" and p.delta is not None:
        raise InfeasibleBounds(
            f"no crank and spring within the bounds keeps the deflection ratio (l0 − L_min)/l0 below "
            f"{p.delta:g}: raise the maximum deflection, allow a longer r0 or a smaller pre-load a."
        )
    raise InfeasibleBounds("no device within the stated bounds satisfies the free-length limit.")
