"""Fitting crank-and-rocker spring devices to a target moment ``Φ0·sin φ``.

The device moment is ``M(φ) = ±c·r·d·sin φ·g(φ)`` with a *shape* ``g`` that depends
on length ratios only (``g = l0/L − 1`` for compression, ``1 − l0/L`` for tension).
Everything is therefore solved in non-dimensional variables

    ρ = r/ℓ,  ρ0 = r0/ℓ,  α = a/ℓ   (ℓ = upper bound of r),   κ = c·r·d/|Φ0|,

and the relative error ``e(φ) = |sin φ|·(κ·g(φ) − 1)`` never divides by ``sin φ``.
For fixed geometry ``e`` is linear in ``κ``: the optimal ``κ`` is closed-form for the
RMS norm and a one-dimensional convex problem for the max norm (variable projection).
The constraints that involve ``a`` (free length, deflection ratio, ``a ≤ r0`` for
tension) are upper/lower limits of ``α`` given ``(ρ, ρ0)``, so ``α`` is mapped from a
unit variable ``t``; the force limit is a limit on ``κ``. The projected problems
therefore have box bounds only.

Methods (``method=``): ``"trf"`` — :func:`scipy.optimize.least_squares` (trust-region
reflective) on the projected residuals (for the max norm: Lawson's iteratively
reweighted least squares); ``"slsqp"`` — :func:`scipy.optimize.minimize` SLSQP on the
full variables with explicit constraints (epigraph form for the max norm);
``"nelder-mead"`` — bounded Nelder–Mead on the projected norm; ``"de"`` —
:func:`scipy.optimize.differential_evolution` (fixed seed) on the projected norm,
polished by SLSQP.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import asdict, dataclass, replace
from typing import Callable

import numpy as np
from scipy import optimize

from ..errors import FitFailed, InfeasibleBounds, InvalidInput, InvalidRange, WrongSense
from ..extremes import box_extremes
from .springs import KIND_SENSE, SPRING_KINDS, CrankRockerDevice

__all__ = [
    "SpringBounds",
    "FitResult",
    "fit_spring",
    "METHODS",
    "NORMS",
    "DEFAULT_METHOD",
    "DEFAULT_GRID",
    "MAX_GRID",
    "LeverGeometry",
    "relative_errors",
]

NORMS = ("max", "rms")
DEFAULT_GRID = 61
#: the finest fit grid: finer ones only cost memory and time (one evaluation holds a few arrays of it)
MAX_GRID = 100_001
VERIFY_GRID = 4001
_SENSE_TEXT = {
    +1: "away from the base point C (increasing φ)",
    -1: "towards the base point C (decreasing φ)",
}


@dataclass(frozen=True)
class SpringBounds:
    """Physical bounds a designer states (SI units; ``math.inf`` for none).

    Attributes
    ----------
    r, r0, a : (float, float)
        Ranges of the crank length, the spring length at ``φ = 0`` (``d = r + r0``)
        and the pre-extension (tension) / pre-load (compression).
    max_force : float or None
        Largest spring force over the working range (N).
    max_free_length : float or None
        Largest free length ``l0`` of the spring (m).
    max_deflection : float or None
        Compression only: largest ``(l0 − L_min)/l0`` (fraction of the free length).
    """

    r: tuple[float, float]
    r0: tuple[float, float]
    a: tuple[float, float]
    max_force: float | None = None
    max_free_length: float | None = None
    max_deflection: float | None = None


@dataclass(frozen=True)
class LeverGeometry:
    """The slotted lever of a compression-lever device (lengths in m, from the base point ``C``).

    The spring is compressed by ``L`` (``compression_min`` … ``compression_max``); its free length
    ``spring_free_length`` is the stop's distance from ``C``, so the lever reaches that far
    (``reach_from_C``), ``extra_length`` beyond the farthest crank-pin position, which a spring
    between ``C`` and ``B`` (``reach_from_C_fig_a``) would not need.
    """

    stop_distance_from_C: float
    spring_free_length: float
    spring_length_min: float
    spring_length_max: float
    compression_min: float
    compression_max: float
    deflection_ratio: float
    designed_from_spring: bool = False

    @property
    def reach_from_C(self) -> float:
        return self.stop_distance_from_C

    @property
    def reach_from_C_fig_a(self) -> float:
        return self.compression_max

    @property
    def extra_length(self) -> float:
        return self.stop_distance_from_C - self.compression_max

    @property
    def size_ratio(self) -> float:
        return self.stop_distance_from_C / self.compression_max

    @classmethod
    def for_spring(cls, free_length: float, lmin: float, lmax: float, designed: bool = False) -> "LeverGeometry":
        """The lever that carries a spring of ``free_length`` compressed by ``lmin`` … ``lmax``."""
        s = free_length
        return cls(s, s, s - lmax, s - lmin, lmin, lmax, lmax / s, designed)

    def note(self) -> str:
        """The device's size against a spring between C and B, in one sentence."""
        s, lmax = self.reach_from_C, self.reach_from_C_fig_a
        return (f"the lever reaches {s:.4g} m from C, {s - lmax:.4g} m beyond the farthest crank-pin position "
                f"({s / lmax:.3g}× the {lmax:.4g} m of a spring between C and B): the price of an exact compression "
                "spring")

    def to_dict(self) -> dict:
        return asdict(self) | {"reach_from_C": self.reach_from_C, "reach_from_C_fig_a": self.reach_from_C_fig_a,
                               "extra_length": self.extra_length, "size_ratio": self.size_ratio}


@dataclass(frozen=True)
class FitResult:
    """Outcome of :func:`fit_spring` (SI units; errors relative to ``|Φ0|``).

    ``x`` holds the non-dimensional optimum ``(ρ, ρ0, α, κ)``.
    """

    kind: str
    method: str
    norm: str
    moment: float
    phi_range: tuple[float, float]
    x: tuple[float, float, float, float]
    c: float
    r: float
    r0: float
    a: float
    d: float
    free_length: float
    max_force: float
    deflection: float | None
    max_rel_error: float
    rms_rel_error: float
    grid_max_rel_error: float
    grid_rms_rel_error: float
    grid: int
    seconds: float
    nfev: int
    active_bounds: tuple[str, ...]
    sense: int
    sense_text: str
    message: str
    reference_length: float = 0.0
    notes: tuple[str, ...] = ()
    restarts: int = 0
    lever: LeverGeometry | None = None

    @property
    def device(self) -> CrankRockerDevice:
        return CrankRockerDevice(self.kind, self.c, self.r, self.r0, self.a)

    def to_dict(self) -> dict:
        d = asdict(self)
        d["phi_range_deg"] = [math.degrees(v) for v in self.phi_range]
        d["x"] = list(self.x)
        d["phi_range"] = list(self.phi_range)
        d["active_bounds"] = list(self.active_bounds)
        d["notes"] = list(self.notes)
        d["lever"] = None if self.lever is None else self.lever.to_dict()
        return d


def relative_errors(device: CrankRockerDevice, moment: float, phi: np.ndarray) -> np.ndarray:
    """``(M(φ) − Φ0·sin φ)/|Φ0|`` computed from the physical device."""
    return (device.moment(phi) - moment * np.sin(phi)) / abs(moment)


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
    """``argmin_{0≤κ≤κmax} max_i |κ·h_i − s_i|`` for ``h, s ≥ 0`` (exact to round-off).

    ``F_up(κ) = max(κh − s)`` rises and ``F_dn(κ) = max(s − κh)`` falls; the optimum is where
    they cross, the root of ``F_up − F_dn`` (Brent's method: exact steps on its linear pieces),
    or κmax when they cross beyond it.
    """
    if not h.size:
        return 0.0
    hmax, smax = float(np.max(h)), float(np.max(s))
    if hmax <= 0 or smax <= 0:
        return 0.0  # κ has nothing to lift, or nothing to lift towards

    def rise(k):  # F_up − F_dn
        up = k * h - s
        return float(np.max(up) + np.min(up))

    # at 2·smax/hmax, F_up ≥ smax ≥ F_dn: the crossing is in [0, top]
    top = min(kmax, 2.0 * smax / hmax)
    if rise(top) <= 0:
        return top
    return optimize.brentq(rise, 0.0, top)


# --------------------------------------------------------------------------- methods
def _fit_trf(p: _Problem, norm: str):
    z0 = p.start(norm)
    lb, ub = p.z_bounds
    sq = math.sqrt(len(p.phi))

    def run(z_start, weights):
        def fun(z):
            e, _, viol = p.projected(z, "rms", weights)
            r = e if weights is None else np.sqrt(weights) * e
            return np.append(r / sq, 10.0 * viol)

        return optimize.least_squares(
            fun, z_start, bounds=(lb, ub), method="trf", x_scale="jac",
            ftol=1e-12, xtol=1e-12, gtol=1e-12,
        )

    sol = run(z0, None)
    z = sol.x
    msg, ok = sol.message, sol.status > 0
    if norm == "max":
        # Lawson's algorithm: reweight by the error magnitude, refit, keep the best max-norm point
        v = np.full(len(p.phi), 1.0 / len(p.phi))
        best, bz = p.objective(z, "max"), z
        for _ in range(40):
            e, _, _ = p.projected(z, "rms", v)
            v = v * np.abs(e)
            tot = v.sum()
            if not tot > 0:
                break
            v = v / tot + 1e-300
            z = run(z, v).x
            val = p.objective(z, "max")
            if val < best:
                best, bz = val, z
        z, msg = bz, "least_squares (trf) with Lawson reweighting for the max norm"
    return z, msg, ok


def _fit_nelder_mead(p: _Problem, norm: str):
    lb, ub = p.z_bounds
    sol = optimize.minimize(
        p.objective, p.start(norm), args=(norm,), method="Nelder-Mead", bounds=list(zip(lb, ub)),
        options={"xatol": 1e-10, "fatol": 1e-14, "maxfev": 3000, "adaptive": True},
    )
    return sol.x, sol.message, bool(sol.success)


def _fit_slsqp(p: _Problem, norm: str, z0=None):
    """SLSQP on ``y = (ρ, ρ0, α, κ[, τ])`` with explicit constraints."""
    z0 = p.start(norm) if z0 is None else z0
    rho, rho0, al, _ = p.decode(z0)
    k = p.best_kappa(rho, rho0, al, norm)
    y0 = [rho, rho0, al, k]
    al_hi = p.al_b[1] if math.isfinite(p.al_b[1]) else None
    bounds = [p.rho_b, p.rho0_b, (p.al_b[0], al_hi), (0.0, None)]
    cons: list[dict] = []

    def l_at(y, s2):
        return math.sqrt(y[1] ** 2 + 4 * y[0] * (y[0] + y[1]) * s2)

    if p.kind == "compression":
        if math.isfinite(p.Lf):
            cons.append({"type": "ineq", "fun": lambda y: p.Lf - (2 * y[0] + y[1] + y[2])})
        if p.delta is not None:
            cons.append({"type": "ineq", "fun": lambda y: l_at(y, p.s2min) - (1 - p.delta) * (2 * y[0] + y[1] + y[2])})
        if math.isfinite(p.Fhat):
            cons.append({"type": "ineq", "fun": lambda y: p.Fhat * y[0] * (y[0] + y[1]) - y[3] * (2 * y[0] + y[1] + y[2] - l_at(y, p.s2min))})
    else:
        cons.append({"type": "ineq", "fun": lambda y: y[1] - y[2]})
        if math.isfinite(p.Lf):
            cons.append({"type": "ineq", "fun": lambda y: p.Lf - (y[1] - y[2])})
        if math.isfinite(p.Fhat):
            cons.append({"type": "ineq", "fun": lambda y: p.Fhat * y[0] * (y[0] + y[1]) - y[3] * (l_at(y, p.s2max) - (y[1] - y[2]))})

    def err(y):
        return p.errors(y[0], y[1], y[2], y[3])

    if norm == "rms":
        fun = lambda y: float(np.mean(err(y) ** 2))  # noqa: E731
        x0 = np.array(y0)
    else:
        e0 = err(y0)
        x0 = np.array(y0 + [float(np.max(np.abs(e0)))])
        bounds = bounds + [(0.0, None)]
        fun = lambda y: y[4]  # noqa: E731
        cons.append({"type": "ineq", "fun": lambda y: y[4] - err(y)})
        cons.append({"type": "ineq", "fun": lambda y: y[4] + err(y)})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        sol = optimize.minimize(
            fun, x0, method="SLSQP", bounds=bounds, constraints=cons,
            options={"ftol": 1e-15, "maxiter": 500},
        )
    y = sol.x
    return p.encode(y[0], y[1], y[2]), f"SLSQP: {sol.message}", bool(sol.success)


def _fit_de(p: _Problem, norm: str):
    lb, ub = p.z_bounds
    sol = optimize.differential_evolution(
        p.objective, list(zip(lb, ub)), args=(norm,), seed=12345, tol=1e-6, atol=0,
        maxiter=80, popsize=8, polish=False, init="sobol",
    )
    # polish locally from the global candidate
    z, (z2, _, ok) = sol.x, _fit_slsqp(p, norm, z0=sol.x)
    if p.objective(z2, norm) <= p.objective(z, norm):
        z = z2
    return z, "differential_evolution (seed 12345) polished by SLSQP", ok


#: a fit is a local optimum when a restart from it lowers the error by at most this (relative)
CONFIRM_TOL = 1e-9
CONFIRM_ROUNDS = 4


def _confirm_optimum(p: _Problem, z, norm: str) -> tuple[np.ndarray, float, int]:
    """Restart from ``z``: Nelder–Mead on the projected norm, then SLSQP from the better point.

    A method may stop early (SLSQP's "Positive directional derivative for linesearch" or its
    iteration limit, Lawson's reweighting short of the minimax point): while a restart lowers
    the error by more than :data:`CONFIRM_TOL`, its point is taken and the restart repeated.
    A method that reports convergence (SLSQP's KKT test, Nelder–Mead's simplex size) is not
    restarted.
    Returns the point, the relative gain of the last restart and the restarts taken.
    """
    lb, ub = p.z_bounds
    best = p.objective(z, norm)
    for rounds in range(CONFIRM_ROUNDS + 1):
        nm = optimize.minimize(p.objective, z, args=(norm,), method="Nelder-Mead", bounds=list(zip(lb, ub)),
                               options={"xatol": 1e-10, "fatol": 1e-15, "maxfev": 600, "adaptive": True})
        z_nm = nm.x if nm.fun < best else z
        z_sq, _, _ = _fit_slsqp(p, norm, z0=z_nm)
        cand = min(((nm.fun, nm.x), (p.objective(z_sq, norm), z_sq)), key=lambda c: c[0])
        gain = (best - cand[0]) / best if best > 0 else 0.0
        if gain <= CONFIRM_TOL or rounds == CONFIRM_ROUNDS:
            return z, max(gain, 0.0), rounds
        best, z = cand
    raise AssertionError("unreachable")  # pragma: no cover


METHODS: dict[str, Callable] = {
    "trf": _fit_trf,
    "slsqp": _fit_slsqp,
    "nelder-mead": _fit_nelder_mead,
    "de": _fit_de,
}
#: fastest method that reaches the optimum on every case of the test-suite (see the benchmark)
DEFAULT_METHOD = {"rms": "slsqp", "max": "slsqp"}


# --------------------------------------------------------------------------- driver
def _check_range(name: str, rng, positive: bool = False, allow_inf: bool = False) -> tuple[float, float]:
    try:
        lo, hi = float(rng[0]), float(rng[1])
    except (TypeError, ValueError, IndexError):
        raise InvalidRange(f"{name} must be a range low..high, not {rng!r}.") from None
    if math.isnan(lo) or math.isnan(hi) or not math.isfinite(lo) or (not allow_inf and not math.isfinite(hi)):
        raise InvalidRange(f"{name} range {lo}..{hi} must be finite.")
    if lo > hi:
        raise InvalidRange(f"{name} range {lo}..{hi} is inverted (low > high).")
    if positive and lo <= 0:
        raise InvalidRange(f"{name} must be positive; its lower bound is {lo}.")
    if lo < 0:
        raise InvalidRange(f"{name} cannot be negative; its lower bound is {lo}.")
    return lo, hi


def fit_spring(
    kind: str,
    moment: float,
    phi_range: tuple[float, float],
    bounds: SpringBounds,
    method: str | None = None,
    norm: str = "max",
    grid: int = DEFAULT_GRID,
) -> FitResult:
    """Fit a crank-and-rocker spring device to the moment ``Φ0·sin φ`` over a range of ``φ``.

    Parameters
    ----------
    kind : {"tension", "compression", "compression-lever"}
    moment : float
        ``Φ0`` (N·m), signed: positive turns the crank away from the base point ``C``
        (what a compression spring does), negative towards it (a tension spring).
    phi_range : (float, float)
        Working range of ``φ`` in radians, ``low < high``, width at most ``2π``.
    bounds : SpringBounds
    method : {"trf", "slsqp", "nelder-mead", "de"} or None
        ``None`` picks :data:`DEFAULT_METHOD` for the norm; a tension spring whose bounds
        allow a zero free length (``a = r0``) is then solved exactly (method ``"exact"``).
    norm : {"max", "rms"}
        Minimise the largest or the root-mean-square deviation over the range.
    grid : int
        Number of equally spaced points of ``φ`` the fit uses (5 … :data:`MAX_GRID`). Reported
        errors are measured afterwards on a fine grid, so they are not flattered by a coarse one.

    Returns
    -------
    FitResult

    Raises
    ------
    InvalidInput, InvalidRange, WrongSense, InfeasibleBounds

    Notes
    -----
    One objective evaluation costs O(grid); the default methods take a few hundred.

    Examples
    --------
    >>> b = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))
    >>> res = fit_spring("compression", 100.0, (math.radians(20), math.radians(160)), b)
    >>> res.max_rel_error < 0.05, res.sense
    (True, 1)
    """
    t_start = time.perf_counter()
    if kind not in SPRING_KINDS:
        raise InvalidInput(f"the spring kind must be one of {', '.join(SPRING_KINDS)}, not {kind!r}.")
    if norm not in NORMS:
        raise InvalidInput(f"the norm must be 'max' or 'rms', not {norm!r}.")
    if method is not None and method not in METHODS:
        raise InvalidInput(f"the fit method must be one of {', '.join(METHODS)}, not {method!r}.")
    if not isinstance(grid, int) or not 5 <= grid <= MAX_GRID:
        raise InvalidInput(f"the fit grid takes 5 to {MAX_GRID} points, not {grid!r} (the reported errors are "
                           "measured afterwards on a fine grid of their own).")
    moment = float(moment)
    if not math.isfinite(moment) or moment == 0:
        raise InvalidInput(f"the moment amplitude Φ0 must be a finite non-zero number, not {moment}.")
    sense = KIND_SENSE[kind]
    if (moment > 0) != (sense > 0):
        other = "compression" if sense < 0 else "tension or compression-lever"
        raise WrongSense(
            f"a {kind} device turns the crank {_SENSE_TEXT[sense]}, so it cannot give "
            f"Φ0 = {moment:g} N·m; use a {other} device, or turn the device by 180° and fit "
            f"Φ0 = {-moment:g} N·m."
        )
    lo, hi = _phi_range(phi_range)
    r = _check_range("the crank length r", bounds.r, positive=True)
    r0 = _check_range("r0 (spring length at φ = 0)", bounds.r0, positive=True)
    a = _check_range("the pre-extension a", bounds.a, allow_inf=True)
    for name, v in (("maximum force", bounds.max_force), ("maximum free length", bounds.max_free_length)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise InvalidInput(f"the {name} must be a positive number, not {v}.")
    if bounds.max_deflection is not None and not 0 < bounds.max_deflection < 1:
        raise InvalidInput(f"the maximum deflection ratio must lie in (0, 1), not {bounds.max_deflection}.")
    b = SpringBounds(r, r0, a, bounds.max_force, bounds.max_free_length, bounds.max_deflection)
    if kind == "compression-lever":
        return _lever_device(moment, lo, hi, b, grid, norm, t_start)
    p = _Problem(kind, moment, lo, hi, b, grid, norm)
    _check_feasible(p)

    notes: list[str] = []
    if method is None and kind == "tension":
        exact = _tension_exact(p)
        if exact is not None:
            return _finish(p, exact, "exact", norm, t_start, "zero free length (a = r0): exact", notes)
        notes.append("a zero free length (a = r0) is outside the bounds; fitted instead")
    meth = method or DEFAULT_METHOD[norm]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        z, msg, ok = METHODS[meth](p, norm)
        if not np.all(np.isfinite(z)):
            raise FitFailed(f"the {meth} method returned a non-finite point ({msg}).")
        # a method that did not converge (or Lawson's reweighting, which only nears the minimax point)
        # is restarted from its point until a restart gains nothing
        gain, rounds = 0.0, 0
        if not ok or (meth == "trf" and norm == "max"):
            z, gain, rounds = _confirm_optimum(p, z, norm)
    if gain > CONFIRM_TOL:
        raise FitFailed(
            f"the {meth} fit did not settle: {rounds} restarts from its point (Nelder–Mead, then SLSQP) still "
            f"lowered the {norm} error by {100 * gain:.3g} % in the last ({msg}).")
    if rounds:
        msg = (f"{msg}; restarted {rounds}× from its point (Nelder–Mead, then SLSQP): a local optimum to "
               f"{CONFIRM_TOL:g} of the error")
    elif not ok:
        msg = (f"{msg} — yet a restart from its point (Nelder–Mead, then SLSQP) lowers the error by less than "
               f"{CONFIRM_TOL:g}: a local optimum")
    elif meth == "trf" and norm == "max":
        msg = f"{msg}; a restart from its point (Nelder–Mead, then SLSQP) gains less than {CONFIRM_TOL:g}"
    rho, rho0, al, viol = p.decode(z)
    if viol > 1e-9:
        raise FitFailed(f"the {meth} method ended outside the bounds ({msg}): where a limit leaves no room for "
                        f"a, it stops just past it; the default method, slsqp, keeps such limits exactly.")
    # κ enters the error linearly: for the final shape it is solved exactly (SLSQP's own κ agrees
    # to round-off, the other methods never see it)
    kappa = p.best_kappa(rho, rho0, al, norm)
    return _finish(p, (rho, rho0, al, kappa), meth, norm, t_start, str(msg), notes, rounds)


def _phi_range(phi_range) -> tuple[float, float]:
    try:
        lo, hi = float(phi_range[0]), float(phi_range[1])
    except (TypeError, ValueError, IndexError):
        raise InvalidRange(f"the range of φ must be low..high, not {phi_range!r}.") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise InvalidRange("the range of φ must be finite.")
    if not lo < hi:
        what = "empty" if lo == hi else "inverted"
        raise InvalidRange(
            f"the range of φ {math.degrees(lo):g}°..{math.degrees(hi):g}° is {what}; give low < high."
        )
    if hi - lo > 2 * math.pi + 1e-12:
        raise InvalidRange(f"the range of φ spans {math.degrees(hi - lo):g}°, more than one turn (360°).")
    if hi - lo < 1e-9:
        raise InvalidRange("the range of φ is narrower than 1e-9 rad; the fit is meaningless there.")
    return lo, hi


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


def _finish(p: _Problem, y, method: str, norm: str, t_start: float, msg: str, notes, restarts: int = 0) -> FitResult:
    rho, rho0, al, kappa = (float(v) for v in y)
    seconds = time.perf_counter() - t_start
    e_grid = p.errors(rho, rho0, al, kappa)
    ell, M = p.ell, p.moment
    r, r0, a = rho * ell, rho0 * ell, al * ell
    d = r + r0
    c = kappa * abs(M) / (r * d)
    dev = CrankRockerDevice(p.kind, c, r, r0, a)
    phi = _verify_grid(p.lo, p.hi, r, r0)
    e = relative_errors(dev, M, phi)
    (e_lo, e_hi), = box_extremes(lambda x: relative_errors(dev, M, x[:, 0])[:, None], [p.lo], [p.hi], phi[:, None],
                                 floor=1e-13)
    l0 = dev.free_length
    # the spring length over the range runs from lmin to lmax: the force is largest at one of them
    lmin = math.sqrt(r0 * r0 + 4 * r * d * p.s2min)
    lmax = math.sqrt(r0 * r0 + 4 * r * d * p.s2max)
    fmax = c * max(abs(lmin - l0), abs(lmax - l0))
    # deflection ratio (l0 − L_min)/l0 is a compression-spring notion; None for tension
    defl = (l0 - lmin) / l0 if p.kind == "compression" else None
    active = _active(p, rho, rho0, al, kappa)
    if rho0 < 0.05 * rho and p.s2min == 0.0:
        notes.append(
            f"r0/r = {rho0 / rho:.3g} with φ = 0 in the range: the moment changes steeply within "
            f"|φ| ≲ {math.degrees(rho0 / rho):.3g}° of 0 (resolved by the verification grid)"
        )
    notes.extend(dead_centre_notes(p.lo, p.hi, r, r0))
    return FitResult(
        kind=p.kind, method=method, norm=norm, moment=M, phi_range=(p.lo, p.hi),
        x=(rho, rho0, al, kappa), c=c, r=r, r0=r0, a=a, d=d, free_length=l0,
        max_force=fmax, deflection=defl,
        max_rel_error=max(-e_lo.value, e_hi.value),
        rms_rel_error=float(np.sqrt(np.mean(e[: VERIFY_GRID] ** 2))),
        grid_max_rel_error=float(np.max(np.abs(e_grid))),
        grid_rms_rel_error=float(np.sqrt(np.mean(e_grid ** 2))),
        grid=p.grid, seconds=seconds, nfev=p.nfev, active_bounds=tuple(active),
        sense=KIND_SENSE[p.kind], sense_text=_SENSE_TEXT[KIND_SENSE[p.kind]],
        message=msg, reference_length=ell, notes=tuple(notes), restarts=restarts,
    )


def dead_centre_notes(lo: float, hi: float, r: float, r0: float) -> list[str]:
    """What the device does where the working range crosses φ = 0 or φ = 180° (mod 360°)."""
    out = []
    zeros = [k * 180 for k in range(math.ceil(math.degrees(lo) / 180 - 1e-12),
                                     math.floor(math.degrees(hi) / 180 + 1e-12) + 1)]
    inner = [z for z in zeros if math.radians(z) > lo + 1e-12 and math.radians(z) < hi - 1e-12]
    if inner:
        where = " and ".join(f"{z}°" for z in inner)
        what = "the dead centres" if len(inner) > 1 else "the dead centre"
        ends = []
        if any(z % 360 == 0 for z in inner):
            ends.append(f"at 0° the spring is shortest ({r0:.4g} m)")
        if any(z % 360 == 180 for z in inner):
            ends.append(f"at 180° longest (2r + r0 = {2 * r + r0:.4g} m)")
        out.append(
            f"the range crosses {what} φ = {where}, where crank AB and spring BC are in line: "
            f"the device's moment and the target both pass through zero and change sign there, so the "
            f"crank is held in both directions; {' and '.join(ends)}"
        )
    return out


def _verify_grid(lo: float, hi: float, r: float, r0: float) -> np.ndarray:
    """Uniform fine grid first (its first VERIFY_GRID points give the RMS), then
    points clustered where the moment changes fastest (near multiples of 2π)."""
    phi = np.linspace(lo, hi, VERIFY_GRID)
    extra = []
    width = max(r0 / r, 1e-12)
    for kk in range(math.ceil(lo / (2 * math.pi)), math.floor(hi / (2 * math.pi)) + 1):
        c0 = 2 * math.pi * kk
        offs = np.geomspace(width * 1e-2, min(width * 1e2, math.pi), 200)
        extra.append(c0 + offs)
        extra.append(c0 - offs)
    if extra:
        ex = np.concatenate(extra)
        phi = np.concatenate([phi, ex[(ex >= lo) & (ex <= hi)]])
    return phi


def _active(p: _Problem, rho, rho0, al, kappa) -> list[str]:
    tol = 1e-6
    out = []

    def near(v, b):
        return math.isfinite(b) and abs(v - b) <= tol * max(1.0, abs(b))

    for name, v, (lo, hi) in (("r", rho, p.rho_b), ("r0", rho0, p.rho0_b), ("a", al, p.al_b)):
        if near(v, lo):
            out.append(f"{name}=min")
        if near(v, hi):
            out.append(f"{name}=max")
    l0 = p.l0(rho, rho0, al)
    if near(l0, p.Lf):
        out.append("max_free_length")
    if p.kind == "compression" and p.delta is not None:
        lmin = math.sqrt(rho0 * rho0 + 4 * rho * (rho + rho0) * p.s2min)
        if near((l0 - lmin) / l0, p.delta):
            out.append("max_deflection")
    if p.kind == "tension" and near(al, rho0):
        out.append("a=r0 (zero free length)")
    km = p.kappa_max(rho, rho0, al)
    if math.isfinite(km) and near(kappa, km):
        out.append("max_force")
    return out
