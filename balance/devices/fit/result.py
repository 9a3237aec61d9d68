"""The result type every spring fit returns, and how it is measured and reported.

:class:`FitResult` holds the device found by any method of :mod:`balance.devices.fit` with its
errors measured afresh on a fine grid (the largest by a bracketed maximiser), the bounds it
sits on and notes on the dead centres; :class:`SpringBounds` the limits a designer states;
:class:`LeverGeometry` the lever of the compression-lever device.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING

import numpy as np
from scipy import optimize

from mechbase import Row

from ..sliders import SliderSpringDevice
from ..springs import KIND_SENSE, CrankRockerDevice

if TYPE_CHECKING:
    from .problem import _Problem

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
        Ranges of the crank length, the spring length at ``φ = 0`` (``d = r + r0``; the slotted
        lever only, ``None`` for the slider devices) and the pre-extension (tension) / pre-load
        (compression; on a slider: the least deflection over the working range).
    max_force : float or None
        Largest spring force over the working range (N).
    max_free_length : float or None
        Largest free length ``l0`` of the spring (m).
    max_deflection : float or None
        Compression only: largest ``(l0 − L_min)/l0`` (fraction of the free length).
    rod, offset : (float, float) or None
        Slider-crank only: ranges of the rod length ``l`` and of the guide's offset ``e`` (it may be negative).
    """

    r: tuple[float, float]
    r0: tuple[float, float] | None
    a: tuple[float, float]
    max_force: float | None = None
    max_free_length: float | None = None
    max_deflection: float | None = None
    rod: tuple[float, float] | None = None
    offset: tuple[float, float] | None = None


@dataclass(frozen=True)
class LeverGeometry(Row):
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

    row_keys = ("stop_distance_from_C", "spring_free_length", "spring_length_min", "spring_length_max",
                "compression_min", "compression_max", "deflection_ratio", "designed_from_spring", "reach_from_C",
                "reach_from_C_fig_a", "extra_length", "size_ratio")

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


@dataclass(frozen=True)
class FitResult(Row):
    """Outcome of :func:`fit_spring` (SI units; errors relative to ``|Φ0|``).

    ``x`` holds the non-dimensional optimum: ``(ρ, ρ0, α, κ)`` for the slotted lever, ``(ρ, ε, λ, α, κ)``
    for the slider-crank and ``(ρ, α, κ)`` for the sine device. ``family`` is the device
    (:data:`~balance.devices.fit.DEVICES`); the slider devices leave ``r0`` and ``d`` None and give the
    rod, the offset and the slider position ``neutral`` at which the spring is unloaded.
    """

    kind: str
    method: str
    norm: str
    moment: float
    phi_range: tuple[float, float]
    x: tuple[float, ...]
    c: float
    r: float
    r0: float | None
    a: float
    d: float | None
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
    family: str = "slotted-lever"
    rod: float | None = None
    offset: float | None = None
    neutral: float | None = None

    @property
    def device(self) -> CrankRockerDevice | SliderSpringDevice:
        if self.family == "slotted-lever":
            return CrankRockerDevice(self.kind, self.c, self.r, self.r0, self.a)
        return SliderSpringDevice(self.c, self.r, self.neutral, self.rod, self.offset or 0.0)

    @property
    def phi_range_deg(self) -> tuple[float, float]:
        return math.degrees(self.phi_range[0]), math.degrees(self.phi_range[1])

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The row: every field, then the range in degrees."""
        return (*(f.name for f in fields(self)), "phi_range_deg")


def relative_errors(device: CrankRockerDevice | SliderSpringDevice, moment: float, phi: np.ndarray) -> np.ndarray:
    """``(M(φ) − Φ0·sin φ)/|Φ0|`` computed from the physical device."""
    return (device.moment(phi) - moment * np.sin(phi)) / abs(moment)


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
    max_err, rms_err = measured_errors(dev, M, p.lo, p.hi, phi)
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
        max_rel_error=max_err, rms_rel_error=rms_err,
        grid_max_rel_error=float(np.max(np.abs(e_grid))),
        grid_rms_rel_error=float(np.sqrt(np.mean(e_grid ** 2))),
        grid=p.grid, seconds=seconds, nfev=p.nfev, active_bounds=tuple(active),
        sense=KIND_SENSE[p.kind], sense_text=_SENSE_TEXT[KIND_SENSE[p.kind]],
        message=msg, reference_length=ell, notes=tuple(notes), restarts=restarts,
    )


def measured_errors(dev, moment: float, lo: float, hi: float, phi: np.ndarray) -> tuple[float, float]:
    """The largest relative error over ``[lo, hi]`` by a bracketed maximiser (:func:`largest_on_range`
    from the grid ``phi``) and the RMS over the uniform part of ``phi`` (its first :data:`VERIFY_GRID`
    points).

    Examples
    --------
    >>> from balance.devices.springs import CrankRockerDevice
    >>> dev = CrankRockerDevice("compression", 9900.0, 0.01, 1.0, 1.0)
    >>> worst, rms = measured_errors(dev, 100.0, 0.35, 2.8, np.linspace(0.35, 2.8, 4001))
    >>> bool(worst >= rms > 0)
    True
    """
    e = relative_errors(dev, moment, phi)
    rms = float(np.sqrt(np.mean(e[: VERIFY_GRID] ** 2)))
    worst = largest_on_range(lambda x: np.abs(relative_errors(dev, moment, x)), lo, hi, phi)
    return worst, rms


#: local maxima of the sampled error refined by the bracketed search, largest first; a maximum between
#: grid points exceeds its sampled neighbours by O(h²), so further ones cannot become the largest
REFINED_PEAKS = 24


def largest_on_range(f, lo: float, hi: float, phi: np.ndarray, floor: float = 1e-13) -> float:
    """The largest value of ``f`` (vectorised, 1-D) over ``[lo, hi]``: each local maximum of ``f`` on
    the sorted grid ``phi`` (with ``lo`` and ``hi``) is bracketed by its two neighbours and refined there
    by bounded Brent (:func:`scipy.optimize.minimize_scalar`, to 1e-12 of the bracket); the range's ends
    count as they are. A function no larger than ``floor`` on the grid (rounding noise of an exact
    device) is not refined.

    Examples
    --------
    >>> round(largest_on_range(lambda x: np.sin(x), 0.0, 3.0, np.linspace(0.0, 3.0, 7)), 12)   # 1 at π/2
    1.0
    """
    x = np.unique(np.concatenate([[lo, hi], phi[(phi >= lo) & (phi <= hi)]]))
    v = f(x)
    best = float(np.max(v))
    if best <= floor or len(x) < 3:
        return best
    peaks = np.flatnonzero((v[1:-1] >= v[:-2]) & (v[1:-1] >= v[2:])) + 1
    for i in peaks[np.argsort(-v[peaks])][:REFINED_PEAKS]:
        a, b = x[i - 1], x[i + 1]
        res = optimize.minimize_scalar(lambda t: -float(f(np.array([t]))[0]), bounds=(a, b), method="bounded",
                                       options={"xatol": 1e-12 * max(b - a, 1e-300)})
        best = max(best, -float(res.fun))
    return best


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
