"""The driver of the spring fit: :func:`fit_spring` checks its input, picks the method, confirms
its optimum by restarts and returns the shared :class:`~balance.devices.fit.result.FitResult`."""

from __future__ import annotations

import math
import time
import warnings
from typing import Callable

import numpy as np
from scipy import optimize

from ...errors import FitFailed, InvalidInput, InvalidRange, WrongSense
from ..springs import KIND_SENSE
from .de import _fit_de
from .exact import _lever_device, _tension_exact
from .kinds import DEFAULT_DEVICE, DEVICES
from .nelder_mead import _fit_nelder_mead
from .problem import _check_feasible, _Problem
from .slider_problem import _SliderProblem
from .result import _SENSE_TEXT, DEFAULT_GRID, MAX_GRID, NORMS, FitResult, SpringBounds, _finish
from .slsqp import _fit_slsqp
from .trf import _fit_trf


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
def _check_range(name: str, rng, positive: bool = False, allow_inf: bool = False,
                 signed: bool = False) -> tuple[float, float]:
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
    if lo < 0 and not signed:
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
    device: str = DEFAULT_DEVICE,
) -> FitResult:
    """Fit a spring device to the moment ``Φ0·sin φ`` over a range of ``φ``.

    Parameters
    ----------
    kind : {"tension", "compression", "compression-lever"}
        The spring; the slider devices take ``"compression"`` only.
    moment : float
        ``Φ0`` (N·m), signed: on the slotted lever positive turns the crank away from the base point
        ``C`` (what a compression spring does), negative towards it (a tension spring); on a slider
        device its sign picks the side of the slider the spring sits on.
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
    device : {"slotted-lever", "slider-crank", "sine"}
        The device (:data:`~balance.devices.fit.DEVICES`); the bounds it does not take must be None.

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
    >>> sine = SpringBounds(r=(0.02, 0.12), r0=None, a=(0.0, 0.3), max_force=1500.0, max_free_length=0.5)
    >>> res = fit_spring("compression", -30.0, (math.radians(-80), math.radians(250)), sine, device="sine")
    >>> round(res.max_rel_error, 4), res.active_bounds
    (0.0481, ('max_free_length', 'max_force'))
    """
    t_start = time.perf_counter()
    if device not in DEVICES:
        raise InvalidInput(f"the device must be one of {', '.join(DEVICES)}, not {device!r}.")
    family = DEVICES[device]
    if kind not in family.spring_kinds:
        if device == "slotted-lever":
            raise InvalidInput(f"the spring kind must be one of {', '.join(family.spring_kinds)}, not {kind!r}.")
        raise InvalidInput(f"the {device} device carries a {' or '.join(family.spring_kinds)} spring on the slider "
                           f"(on the side the sign of Φ0 asks for), not a {kind!r} one.")
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
    if device == "slotted-lever":
        _check_sense(kind, moment)
    lo, hi = _phi_range(phi_range)
    b = _checked_bounds(bounds, family)
    if kind == "compression-lever":
        return _lever_device(moment, lo, hi, b, grid, norm, t_start)
    if device == "slotted-lever":
        p = _Problem(kind, moment, lo, hi, b, grid, norm)
        _check_feasible(p)
    else:
        p = _SliderProblem(device, moment, lo, hi, b, grid, norm)
        p.check_feasible()

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
    *geometry, viol = p.decode(z)
    if viol > 1e-9:
        raise FitFailed(f"the {meth} method ended outside the bounds ({msg}): where a limit leaves no room for "
                        f"a, it stops just past it; the default method, slsqp, keeps such limits exactly.")
    # κ enters the error linearly: for the final shape it is solved exactly (SLSQP's own κ agrees
    # to round-off, the other methods never see it)
    kappa = p.best_kappa(*geometry, norm)
    return family.finish(p, (*geometry, kappa), meth, norm, t_start, str(msg), notes, rounds)


def _check_sense(kind: str, moment: float) -> None:
    """A slotted-lever spring turns the crank one way only: refuse a target of the other sign."""
    sense = KIND_SENSE[kind]
    if (moment > 0) != (sense > 0):
        other = "compression" if sense < 0 else "tension or compression-lever"
        raise WrongSense(
            f"a {kind} device turns the crank {_SENSE_TEXT[sense]}, so it cannot give "
            f"Φ0 = {moment:g} N·m; use a {other} device, or turn the device by 180° and fit "
            f"Φ0 = {-moment:g} N·m."
        )


_BOUND_TEXT = {"r0": "r0 (spring length at φ = 0)", "rod": "the rod length l", "offset": "the guide offset e"}


def _checked_bounds(bounds: SpringBounds, family) -> SpringBounds:
    """The bounds checked against what the device takes: its own ranges valid, the others left out."""
    extra = [name for name in ("r0", "rod", "offset")
             if getattr(bounds, name) is not None and name not in family.bounds]
    if extra:
        raise InvalidInput(f"the {family.name} device has no "
                           f"{' nor '.join(_BOUND_TEXT[n].removeprefix('the ') for n in extra)}; "
                           "leave that bound out.")
    for name in ("r0", "rod"):  # (no device takes both)
        if name in family.bounds and getattr(bounds, name) is None:
            raise InvalidInput(f"the {family.name} device needs a range of {_BOUND_TEXT[name]}.")
    r = _check_range("the crank length r", bounds.r, positive=True)
    r0 = _check_range(_BOUND_TEXT["r0"], bounds.r0, positive=True) if bounds.r0 is not None else None
    a = _check_range("the pre-extension a" if family.name == "slotted-lever" else "the pre-load a", bounds.a,
                     allow_inf=True)
    rod = _check_range(_BOUND_TEXT["rod"], bounds.rod, positive=True) if bounds.rod is not None else None
    offset = None
    if "offset" in family.bounds:
        offset = (0.0, 0.0) if bounds.offset is None else _check_range(_BOUND_TEXT["offset"], bounds.offset,
                                                                      signed=True)
    for name, v in (("maximum force", bounds.max_force), ("maximum free length", bounds.max_free_length)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise InvalidInput(f"the {name} must be a positive number, not {v}.")
    if bounds.max_deflection is not None and not 0 < bounds.max_deflection < 1:
        raise InvalidInput(f"the maximum deflection ratio must lie in (0, 1), not {bounds.max_deflection}.")
    return SpringBounds(r, r0, a, bounds.max_force, bounds.max_free_length, bounds.max_deflection, rod, offset)


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
