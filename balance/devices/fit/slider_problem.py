"""The slider devices' fitting problem (offset slider-crank, sine device) in non-dimensional variables.

With ``ℓ`` the longest crank allowed, ``ρ = r/ℓ``, ``ε = e/ℓ``, ``λ = l/ℓ``, ``α = a/ℓ`` and
``κ = c·ℓ²/|Φ0|``, the relative error is ``κ·m(φ) − σ·sin φ`` with ``σ = sign Φ0`` and
``m = −(x̂ − x̂_n)·dx̂/dφ`` (:mod:`balance.devices.sliders` in units of ``ℓ``). The spring's side
follows ``σ``: for ``σ = +1`` it pushes the slider towards ``A`` and ``x_n = x_min − a``, for
``σ = −1`` away from ``A`` and ``x_n = x_max + a`` — so ``a ≥ 0`` is the spring's least deflection
over the working range and the spring never unloads there. As for the slotted lever, ``κ`` is solved
exactly for each geometry (the same :func:`~.problem.best_scale`), the rod is mapped from a unit
variable between its limits (the rod's angle to the guide at most :data:`MAX_ROD_ANGLE` over a turn:
``l·sin θ ≥ r + |e|``) and so is ``α`` (free length: ``a + stroke ≤ δ·l0_max``), so the projected
problem has box bounds only.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ...errors import InfeasibleBounds
from ..sliders import SliderSpringDevice, slider_extremes, slider_position, slider_rate
from .exact import LEVER_DEFLECTION
from .problem import _max_abs_sin, _span, best_scale
from .result import VERIFY_GRID, FitResult, SpringBounds, measured_errors

#: the largest angle between the rod and the guide over a turn (a common limit of the pressure angle)
MAX_ROD_ANGLE = math.radians(60.0)


class _SliderProblem:
    """The non-dimensional slider problem on a grid (``family`` "slider-crank" or "sine")."""

    def __init__(self, family: str, moment: float, lo: float, hi: float, b: SpringBounds, grid: int, norm: str):
        self.family, self.kind, self.moment, self.lo, self.hi, self.bounds = family, "compression", moment, lo, hi, b
        self.rod = family == "slider-crank"
        self.sign = 1 if moment > 0 else -1
        self.ell = e = b.r[1]
        self.grid = grid
        self.phi = np.linspace(lo, hi, grid)
        self.target = self.sign * np.sin(self.phi)
        self.rho_b = (b.r[0] / e, 1.0)
        self.al_b = (b.a[0] / e, b.a[1] / e)
        self.lam_b = (b.rod[0] / e, b.rod[1] / e) if self.rod else (math.inf, math.inf)
        self.eps_b = (b.offset[0] / e, b.offset[1] / e) if self.rod else (0.0, 0.0)
        #: the offset nearest an in-line guide: it leaves the shortest rod, so every scan of the box holds it
        self.eps_in_line = min(max(0.0, self.eps_b[0]), self.eps_b[1])
        self.Fhat = math.inf if b.max_force is None else b.max_force * e / abs(moment)
        self.Lf = math.inf if b.max_free_length is None else b.max_free_length / e
        self.delta = LEVER_DEFLECTION if b.max_deflection is None else b.max_deflection  # as the lever's spring
        self.nfev = 0

    # -- geometry ---------------------------------------------------------------------
    def rod_length(self, lam):
        """The rod as :mod:`balance.devices.sliders` takes it: None for the sine device."""
        return lam if self.rod else None

    def extremes(self, rho, eps, lam) -> tuple[float, float]:
        return slider_extremes(self.lo, self.hi, rho, self.rod_length(lam), eps)

    def neutral(self, rho, eps, lam, al) -> float:
        xmin, xmax = self.extremes(rho, eps, lam)
        return xmin - al if self.sign > 0 else xmax + al

    def stroke(self, rho, eps, lam) -> float:
        xmin, xmax = self.extremes(rho, eps, lam)
        return xmax - xmin

    def rod_limits(self, rho, eps) -> tuple[float, float]:
        lo, hi = max(self.lam_b[0], (rho + abs(eps)) / math.sin(MAX_ROD_ANGLE)), self.lam_b[1]
        if hi < lo <= hi + 1e-12 * max(1.0, hi):
            lo = hi  # a rod exactly on the angle's limit, not to be lost to the round-off of normalising
        return lo, hi

    def alpha_limits(self, rho, eps, lam) -> tuple[float, float]:
        lo, hi = self.al_b
        if math.isfinite(self.Lf):
            hi = min(hi, self.delta * self.Lf - self.stroke(rho, eps, lam))
        return lo, hi

    def kappa_max(self, rho, eps, lam, al) -> float:
        return self.Fhat / (al + self.stroke(rho, eps, lam)) if math.isfinite(self.Fhat) else math.inf

    def shape(self, rho, eps, lam, al) -> np.ndarray:
        """``m(φ)`` on the grid: the moment per unit ``κ`` (relative to ``|Φ0|``)."""
        x = slider_position(self.phi, rho, self.rod_length(lam), eps)
        return -(x - self.neutral(rho, eps, lam, al)) * slider_rate(self.phi, rho, self.rod_length(lam), eps)

    # -- variables ---------------------------------------------------------------------
    def decode(self, z) -> tuple[float, float, float, float, float]:
        """``z = (ρ, ε, t_λ, t_α)`` (sine: ``(ρ, t_α)``) → ``(ρ, ε, λ, α, violation)``."""
        if self.rod:
            rho, eps, tl, ta = (float(v) for v in z)
            lo, hi = self.rod_limits(rho, eps)
            if hi < lo:
                return rho, eps, lo, self.al_b[0], lo - hi
            lam = lo + min(max(tl, 0.0), 1.0) * (hi - lo)
        else:
            (rho, ta), eps, lam = (float(v) for v in z), 0.0, math.inf
        lo, hi = self.alpha_limits(rho, eps, lam)
        if hi < lo:
            return rho, eps, lam, lo, lo - hi
        return rho, eps, lam, lo + min(max(ta, 0.0), 1.0) * (hi - lo), 0.0

    def encode(self, rho, eps, lam, al) -> np.ndarray:
        def unit(v, lo, hi):
            return 0.0 if hi <= lo else min(max((v - lo) / (hi - lo), 0.0), 1.0)

        ta = unit(al, *self.alpha_limits(rho, eps, lam))
        if not self.rod:
            return np.array([rho, ta])
        return np.array([rho, eps, unit(lam, *self.rod_limits(rho, eps)), ta])

    @property
    def z_bounds(self):
        if self.rod:
            return ([self.rho_b[0], self.eps_b[0], 0.0, 0.0], [self.rho_b[1], self.eps_b[1], 1.0, 1.0])
        return ([self.rho_b[0], 0.0], [self.rho_b[1], 1.0])

    # -- projected residuals -------------------------------------------------------------
    def errors(self, rho, eps, lam, al, kappa):
        """Relative errors ``κ·m − σ·sin φ`` on the grid: one evaluation (counted in ``nfev``)."""
        self.nfev += 1
        return kappa * self.shape(rho, eps, lam, al) - self.target

    def best_kappa(self, rho, eps, lam, al, norm: str, weights=None) -> float:
        return best_scale(self.shape(rho, eps, lam, al), self.target, self.kappa_max(rho, eps, lam, al), norm, weights)

    def projected(self, z, norm: str, weights=None):
        rho, eps, lam, al, viol = self.decode(z)
        k = self.best_kappa(rho, eps, lam, al, norm, weights)
        return self.errors(rho, eps, lam, al, k), k, viol

    def objective(self, z, norm: str) -> float:
        e, _, viol = self.projected(z, norm)
        val = float(np.max(np.abs(e))) if norm == "max" else float(np.sqrt(np.mean(e * e)))
        return val + 10.0 * viol

    def start(self, norm: str) -> np.ndarray:
        """Best point of a small deterministic scan of the box."""
        lb, ub = self.z_bounds
        axes = self._with_in_line([_span(lb[0], ub[0], 4)] + [np.linspace(a, b, 3) for a, b in zip(lb[1:], ub[1:])])
        grids = np.meshgrid(*axes, indexing="ij")
        best, bz = math.inf, None
        for z in np.stack([g.ravel() for g in grids], axis=1):
            v = self.objective(z, norm)
            if v < best:
                best, bz = v, z
        return bz

    def _with_in_line(self, axes: list) -> list:
        """The axes of a scan of the box, the in-line offset among the offsets (the slider-crank's)."""
        if self.rod:
            axes[1] = np.union1d(axes[1], [self.eps_in_line])
        return axes

    # -- SLSQP's full variables -----------------------------------------------------------------
    def full_problem(self, z0, norm: str):
        """``y = (ρ, ε, λ, α, κ)`` (sine: ``(ρ, α, κ)``), its bounds, constraints and errors."""
        rho, eps, lam, al, _ = self.decode(z0)
        k = self.best_kappa(rho, eps, lam, al, norm)
        al_hi = self.al_b[1] if math.isfinite(self.al_b[1]) else None
        if self.rod:
            y0 = [rho, eps, lam, al, k]
            lam_hi = self.lam_b[1] if math.isfinite(self.lam_b[1]) else None
            bounds = [self.rho_b, self.eps_b, (self.lam_b[0], lam_hi), (self.al_b[0], al_hi), (0.0, None)]
            s = math.sin(MAX_ROD_ANGLE)
            cons = [{"type": "ineq", "fun": lambda y: y[2] * s - y[0] - y[1]},
                    {"type": "ineq", "fun": lambda y: y[2] * s - y[0] + y[1]}]
        else:
            y0 = [rho, al, k]
            bounds = [self.rho_b, (self.al_b[0], al_hi), (0.0, None)]
            cons = []
        unpack = self.unpack
        if math.isfinite(self.Lf):
            cons.append({"type": "ineq", "fun": lambda y: self.delta * self.Lf - unpack(y)[3]
                         - self.stroke(*unpack(y)[:3])})
        if math.isfinite(self.Fhat):
            cons.append({"type": "ineq", "fun": lambda y: self.Fhat - unpack(y)[4]
                         * (unpack(y)[3] + self.stroke(*unpack(y)[:3]))})

        def err(y):
            return self.errors(*unpack(y))

        return y0, bounds, cons, err

    def unpack(self, y) -> tuple[float, float, float, float, float]:
        """``(ρ, ε, λ, α, κ)`` of SLSQP's ``y``.  SLSQP may step past the rod's angle limit (a linear constraint)
        in a line search, where a rod shorter than ``r + |e|`` cannot reach the guide: the rod is then taken at the
        shortest length that limit allows there."""
        if self.rod:
            rho, eps, lam, al, kappa = (float(v) for v in y[:5])
            return rho, eps, max(lam, (rho + abs(eps)) / math.sin(MAX_ROD_ANGLE)), al, kappa
        return float(y[0]), 0.0, math.inf, float(y[1]), float(y[2])

    def encode_full(self, y) -> np.ndarray:
        rho, eps, lam, al, _ = self.unpack(y)
        return self.encode(rho, eps, lam, al)

    # -- feasibility --------------------------------------------------------------------------
    def check_feasible(self) -> None:
        """One sentence for bounds that leave no device, or a fit without a bound to stop at."""
        b = self.bounds
        if not math.isfinite(self.al_b[1]) and not math.isfinite(self.Lf):
            raise InfeasibleBounds(
                "with no upper bound on the pre-load a (nor a maximum free length), the error keeps falling as "
                "a grows without limit (the spring's force tends to a constant); give a finite upper bound on a "
                "or a maximum free length.")
        least_eps = abs(self.eps_in_line)
        if self.rod and self.lam_b[1] * math.sin(MAX_ROD_ANGLE) < self.rho_b[0] + least_eps:
            raise InfeasibleBounds(
                f"a rod of at most {b.rod[1]:g} m is too short for a crank of at least {b.r[0]:g} m and an offset of "
                f"at least {least_eps * self.ell:g} m: the rod must be (r + |e|)/sin {math.degrees(MAX_ROD_ANGLE):g}° "
                "long or more so that its angle to the guide stays within that; allow a longer rod or a shorter crank.")
        # a force F on the slider gives at most F·max|dx/dφ| ≤ F·r·(1 + tan θ) (θ the rod's largest angle)
        rate = b.r[1] * (1 + math.tan(MAX_ROD_ANGLE) if self.rod else 1.0)
        peak = _max_abs_sin(self.lo, self.hi)
        if b.max_force is not None and b.max_force * rate < abs(self.moment) * peak:
            raise InfeasibleBounds(
                f"the force limit {b.max_force:g} N on a slider driven by a crank of at most {b.r[1]:g} m gives at "
                f"most {b.max_force * rate:g} N·m, less than the {abs(self.moment) * peak:g} N·m the target needs in "
                "this range; raise the force limit or the longest crank.")
        lb, ub = self.z_bounds
        axes = self._with_in_line([_span(a, c, 7) for a, c in zip(lb, ub)])
        for z in np.stack([g.ravel() for g in np.meshgrid(*axes, indexing="ij")], axis=1):
            rho, eps, lam, al, viol = self.decode(z)
            if viol == 0.0:
                break
        else:
            raise InfeasibleBounds(
                f"no {self.family} device within the bounds keeps the spring's deflection a + stroke within "
                f"{self.delta:g} × the maximum free length {b.max_free_length:g} m; allow a longer spring, a larger "
                "deflection ratio or a shorter crank.")


_SIDE_TEXT = {
    +1: "spring beyond the slider, pushing it towards the crank (increasing φ where sin φ > 0)",
    -1: "spring between the crank's side and the slider, pushing it away (decreasing φ where sin φ > 0)",
}


def _finish_slider(p: _SliderProblem, y, method: str, norm: str, t_start: float, msg: str, notes,
                   restarts: int = 0) -> FitResult:
    """The :class:`FitResult` of a slider device ``y = (ρ, ε, λ, α, κ)``, its errors measured afresh."""
    rho, eps, lam, al, kappa = (float(v) for v in y)
    e_grid = p.errors(rho, eps, lam, al, kappa)
    ell, M = p.ell, p.moment
    r, a = rho * ell, al * ell
    rod, offset = (lam * ell, eps * ell) if p.rod else (None, None)
    c = kappa * abs(M) / ell ** 2
    neutral = p.neutral(rho, eps, lam, al) * ell
    dev = SliderSpringDevice(c, r, neutral, rod, offset or 0.0)
    phi = np.linspace(p.lo, p.hi, VERIFY_GRID)
    max_err, rms_err = measured_errors(dev, M, p.lo, p.hi, phi)
    stroke = p.stroke(rho, eps, lam) * ell
    free_length = (a + stroke) / p.delta
    x = (rho, eps, lam, al, kappa) if p.rod else (rho, al, kappa)
    return FitResult(
        kind=p.kind, method=method, norm=norm, moment=M, phi_range=(p.lo, p.hi), x=x, c=c, r=r, r0=None, a=a,
        d=None, free_length=free_length, max_force=c * (a + stroke), deflection=p.delta,
        max_rel_error=max_err, rms_rel_error=rms_err,
        grid_max_rel_error=float(np.max(np.abs(e_grid))), grid_rms_rel_error=float(np.sqrt(np.mean(e_grid ** 2))),
        grid=p.grid, seconds=time.perf_counter() - t_start, nfev=p.nfev,
        active_bounds=tuple(_active_slider(p, rho, eps, lam, al, kappa)), sense=p.sign,
        sense_text=_SIDE_TEXT[p.sign], message=msg, reference_length=ell,
        notes=tuple(notes) + (f"stroke {stroke:.4g} m; the spring's free length is the shortest that keeps its "
                              f"deflection within {p.delta:g} of it",),
        restarts=restarts, family=p.family, rod=rod, offset=offset, neutral=neutral,
    )


def _active_slider(p: _SliderProblem, rho, eps, lam, al, kappa) -> list[str]:
    tol = 1e-6

    def near(v, b):
        return math.isfinite(b) and abs(v - b) <= tol * max(1.0, abs(b))

    out = []
    named = [("r", rho, p.rho_b), ("a", al, p.al_b)]
    if p.rod:
        named[1:1] = [("offset", eps, p.eps_b), ("rod", lam, p.lam_b)]
    for name, v, (lo, hi) in named:
        if near(v, lo):
            out.append(f"{name}=min")
        if near(v, hi):
            out.append(f"{name}=max")
    if p.rod and near(lam * math.sin(MAX_ROD_ANGLE), rho + abs(eps)):
        out.append("rod angle")
    if math.isfinite(p.Lf) and near(al + p.stroke(rho, eps, lam), p.delta * p.Lf):
        out.append("max_free_length")
    km = p.kappa_max(rho, eps, lam, al)
    if math.isfinite(km) and near(kappa, km):
        out.append("max_force")
    return out
