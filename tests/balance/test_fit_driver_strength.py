"""balance/devices/fit/driver.py: every refusal of fit_spring in full, each limit on both sides
(the grid's 5 and MAX_GRID points, one turn of φ, 1e-9 rad, a deflection ratio in (0, 1)), the
bounds a device takes passed on unchanged, the restarts (from a poor point to SLSQP's optimum, none
from the optimum) and every sentence of a method that stops short or ends where no device is."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize

from balance import SpringBounds, fit_spring
from balance.devices.fit import DEVICES, MAX_GRID, driver
from balance.devices.fit.driver import CONFIRM_TOL, _checked_bounds, _confirm_optimum, _phi_range
from balance.devices.fit.problem import _Problem
from balance.devices.fit.slsqp import _fit_slsqp
from balance.errors import FitFailed, InvalidInput, InvalidRange, WrongSense

# a solver option misspelt or unknown is ignored by scipy with only a warning: here it fails
pytestmark = pytest.mark.filterwarnings("error::scipy.optimize.OptimizeWarning")

R = (0.3, 2.8)
LEVER = SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3))
SINE = SpringBounds((0.02, 0.2), None, (0.0, 0.3))
GRID = ("the fit grid takes 5 to 100001 points, not {} (the reported errors are measured afterwards on a fine "
        "grid of their own).")


def refusal(**kw):
    kw = {"kind": "compression", "moment": 10.0, "phi_range": R, "bounds": LEVER} | kw
    with pytest.raises((InvalidInput, InvalidRange, WrongSense)) as exc:
        fit_spring(**kw)
    return type(exc.value).__name__, str(exc.value)


@pytest.mark.parametrize("kw, error, sentence", [
    ({"device": "crank"}, "InvalidInput", "the device must be one of slotted-lever, slider-crank, sine, not 'crank'."),
    ({"kind": "spiral"}, "InvalidInput",
     "the spring kind must be one of tension, compression, compression-lever, not 'spiral'."),
    ({"kind": "tension", "bounds": SINE, "device": "sine"}, "InvalidInput",
     "the sine device carries a compression spring on the slider (on the side the sign of Φ0 asks for), not a "
     "'tension' one."),
    ({"norm": "L2"}, "InvalidInput", "the norm must be 'max' or 'rms', not 'L2'."),
    ({"method": "bfgs"}, "InvalidInput", "the fit method must be one of trf, slsqp, nelder-mead, de, not 'bfgs'."),
    ({"grid": 4}, "InvalidInput", GRID.format(4)),
    ({"grid": MAX_GRID + 1}, "InvalidInput", GRID.format(MAX_GRID + 1)),
    ({"grid": 7.0}, "InvalidInput", GRID.format(7.0)),
    ({"moment": 0.0}, "InvalidInput", "the moment amplitude Φ0 must be a finite non-zero number, not 0.0."),
    ({"moment": -math.inf}, "InvalidInput", "the moment amplitude Φ0 must be a finite non-zero number, not -inf."),
    ({"moment": math.nan}, "InvalidInput", "the moment amplitude Φ0 must be a finite non-zero number, not nan."),
    ({"moment": -10.0}, "WrongSense",
     "a compression device turns the crank away from the base point C (increasing φ), so it cannot give Φ0 = -10 "
     "N·m; use a tension or compression-lever device, or turn the device by 180° and fit Φ0 = 10 N·m."),
    ({"kind": "tension"}, "WrongSense",
     "a tension device turns the crank towards the base point C (decreasing φ), so it cannot give Φ0 = 10 N·m; "
     "use a compression device, or turn the device by 180° and fit Φ0 = -10 N·m."),
    ({"kind": "compression-lever"}, "WrongSense",
     "a compression-lever device turns the crank towards the base point C (decreasing φ), so it cannot give "
     "Φ0 = 10 N·m; use a compression device, or turn the device by 180° and fit Φ0 = -10 N·m."),
    ({"phi_range": (1.0,)}, "InvalidRange", "the range of φ must be low..high, not (1.0,)."),
    ({"phi_range": (1.0, math.nan)}, "InvalidRange", "the range of φ must be finite."),
    ({"phi_range": (-math.inf, 1.0)}, "InvalidRange", "the range of φ must be finite."),
    ({"phi_range": (math.pi, math.pi)}, "InvalidRange", "the range of φ 180°..180° is empty; give low < high."),
    ({"phi_range": (math.pi, math.pi / 2)}, "InvalidRange",
     "the range of φ 180°..90° is inverted; give low < high."),
    ({"phi_range": (0.0, 2 * math.pi + 1e-11)}, "InvalidRange",
     "the range of φ spans 360°, more than one turn (360°)."),
    ({"phi_range": (1.0, 2.0 + 2 * math.pi)}, "InvalidRange",
     "the range of φ spans 417.296°, more than one turn (360°)."),
    ({"phi_range": (1.0, 1.0 + 5e-10)}, "InvalidRange",
     "the range of φ is narrower than 1e-9 rad; the fit is meaningless there."),
    ({"bounds": SINE}, "InvalidInput", "the slotted-lever device needs a range of r0 (spring length at φ = 0)."),
    ({"bounds": LEVER, "device": "sine"}, "InvalidInput",
     "the sine device has no r0 (spring length at φ = 0); leave that bound out."),
    ({"bounds": SpringBounds((0.02, 0.2), None, (0, 0.3), rod=(0.3, 0.5), offset=(0, 0.1)), "device": "sine"},
     "InvalidInput", "the sine device has no rod length l nor guide offset e; leave that bound out."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0, 0.3), rod=(0.3, 0.5)), "device": "slider-crank"},
     "InvalidInput", "the slider-crank device has no r0 (spring length at φ = 0); leave that bound out."),
    ({"bounds": SINE, "device": "slider-crank"}, "InvalidInput",
     "the slider-crank device needs a range of the rod length l."),
    ({"bounds": SpringBounds((0.0, 0.2), (0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "the crank length r must be positive; its lower bound is 0.0."),
    ({"bounds": SpringBounds((0.02, 0.2), (-0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "r0 (spring length at φ = 0) must be positive; its lower bound is -0.1."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (-0.1, 0.3))}, "InvalidRange",
     "the pre-extension a cannot be negative; its lower bound is -0.1."),
    ({"bounds": SpringBounds((0.02, 0.2), None, (-0.1, 0.3)), "device": "sine"}, "InvalidRange",
     "the pre-load a cannot be negative; its lower bound is -0.1."),
    ({"bounds": SpringBounds((0.02, math.inf), (0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "the crank length r range 0.02..inf must be finite."),
    ({"bounds": SpringBounds((math.nan, 0.2), (0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "the crank length r range nan..0.2 must be finite."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (-math.inf, 0.3))}, "InvalidRange",
     "the pre-extension a range -inf..0.3 must be finite."),
    ({"bounds": SpringBounds((0.2, 0.02), (0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "the crank length r range 0.2..0.02 is inverted (low > high)."),
    ({"bounds": SpringBounds("ab", (0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "the crank length r must be a range low..high, not 'ab'."),
    ({"bounds": SpringBounds(None, (0.1, 0.3), (0.0, 0.3))}, "InvalidRange",
     "the crank length r must be a range low..high, not None."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, math.nan))}, "InvalidRange",
     "the pre-extension a range 0.0..nan must be finite."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3), max_force=0.0)}, "InvalidInput",
     "the maximum force must be a positive number, not 0.0."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3), max_force=math.nan)}, "InvalidInput",
     "the maximum force must be a positive number, not nan."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3), max_free_length=math.inf)}, "InvalidInput",
     "the maximum free length must be a positive number, not inf."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3), max_deflection=1.0)}, "InvalidInput",
     "the maximum deflection ratio must lie in (0, 1), not 1.0."),
    ({"bounds": SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3), max_deflection=0.0)}, "InvalidInput",
     "the maximum deflection ratio must lie in (0, 1), not 0.0."),
    ({"bounds": SpringBounds((0.02, 0.2), None, (0, 0.3), rod=(0.3, 0.5), offset=(-0.1, -0.2)),
      "device": "slider-crank"}, "InvalidRange", "the guide offset e range -0.1..-0.2 is inverted (low > high)."),
    ({"bounds": SpringBounds((0.02, 0.2), None, (0, 0.3), rod=(0.0, 0.5)), "device": "slider-crank"},
     "InvalidRange", "the rod length l must be positive; its lower bound is 0.0."),
])
def test_each_refusal_in_full(kw, error, sentence):
    assert refusal(**kw) == (error, sentence)


@pytest.mark.parametrize("lo, hi", [(0.0, 2 * math.pi), (-1.0, -1.0 + 2e-9), (0.5, 0.5 + 2 * math.pi + 5e-13)])
def test_the_range_of_phi_at_its_limits_is_taken(lo, hi):
    assert _phi_range((lo, hi)) == (lo, hi) and _phi_range([str(lo), hi]) == (lo, hi)


def test_the_bounds_a_device_takes_come_back_as_floats():
    b = _checked_bounds(SpringBounds(["0.02", 0.2], (1, 2), (0, "inf"), 100.0, 1.0, 0.5), DEVICES["slotted-lever"])
    assert b == SpringBounds((0.02, 0.2), (1.0, 2.0), (0.0, math.inf), 100.0, 1.0, 0.5, None, None)
    crank = _checked_bounds(SpringBounds((0.02, 0.2), None, (0, 0.3), rod=(0.3, 0.5), offset=(-0.2, -0.1)),
                            DEVICES["slider-crank"])
    assert crank.rod == (0.3, 0.5) and crank.offset == (-0.2, -0.1) and crank.r0 is None
    assert _checked_bounds(SpringBounds((0.02, 0.2), None, (0, 0.3), rod=(0.3, 0.5)),
                           DEVICES["slider-crank"]).offset == (0.0, 0.0)  # no offset given: an in-line guide
    assert _checked_bounds(SINE, DEVICES["sine"]).offset is None
    # a range of one value fixes that length
    fixed = _checked_bounds(SpringBounds((0.2, 0.2), (0.3, 0.3), (0.1, 0.1)), DEVICES["slotted-lever"])
    assert (fixed.r, fixed.r0, fixed.a) == ((0.2, 0.2), (0.3, 0.3), (0.1, 0.1))


@pytest.mark.parametrize("grid", [5, MAX_GRID])
def test_the_grid_limits_are_taken(grid):
    res = fit_spring("tension", -10.0, R, SpringBounds((0.02, 0.2), (0.1, 0.3), (0.0, 0.3)), grid=grid)
    assert res.grid == grid and res.method == "exact"


@pytest.mark.parametrize("norm", ["max", "rms"])
@pytest.mark.parametrize("method, message", [
    ("nelder-mead", "Optimization terminated successfully."),
    ("de", "differential_evolution (seed 12345) polished by SLSQP"),
    ("slsqp", "SLSQP: Optimization terminated successfully"),
])
def test_a_method_that_reports_convergence_is_not_restarted(method, message, norm):
    """The driver restarts a method only when it does not report convergence (and trf's max norm)."""
    res = fit_spring("compression", 100.0, (math.radians(20), math.radians(160)),
                     SpringBounds((0.01, 0.5), (0.01, 1.0), (0.0, 1.0)), method=method, norm=norm)
    assert (res.restarts, res.message) == (0, message)


def test_trf_on_the_max_norm_is_always_confirmed():
    res = fit_spring("compression", 100.0, (math.radians(20), math.radians(160)),
                     SpringBounds((0.01, 0.5), (0.01, 1.0), (0.0, 1.0)), method="trf", norm="rms")
    assert (res.restarts, res.message) == (0, "`gtol` termination condition is satisfied.")
    res = fit_spring("compression", 100.0, (math.radians(20), math.radians(160)),
                     SpringBounds((0.01, 0.5), (0.01, 1.0), (0.0, 1.0)), method="trf", norm="max")
    assert res.message.startswith("least_squares (trf) with Lawson reweighting for the max norm; ")


def test_differential_evolution_is_repeatable():
    """Its seed is fixed: the same input gives the same device to the last bit."""
    b = SpringBounds((0.02, 0.12), None, (0.0, 0.3), max_force=1500.0, max_free_length=0.5)
    one, two = (fit_spring("compression", -30.0, (math.radians(-80), math.radians(250)), b, device="sine",
                           method="de") for _ in range(2))
    assert one.x == two.x and (one.c, one.r, one.a) == (two.c, two.r, two.a) and one.nfev == two.nfev


# ---------------------------------------------------------------- the restarts and the driver's own sentences

ISSUE = SpringBounds((0.01, 0.5), (0.01, 1.0), (0.0, 1.0))
MID = (math.radians(20), math.radians(160))


def lever_problem(norm="max", grid=21, b=ISSUE):
    return _Problem("compression", 100.0, *MID, b, grid, norm)


@pytest.mark.parametrize("norm", ["max", "rms"])
def test_a_restart_from_a_poor_point_reaches_the_optimum_and_one_from_the_optimum_gains_nothing(norm):
    """From the middle of the box the restarts (Nelder–Mead, then SLSQP) end where SLSQP from the scan
    ends; a restart from that end point gains nothing and takes no round."""
    p = lever_problem(norm)
    best = p.objective(_fit_slsqp(p, norm)[0], norm)
    poor = np.array([0.5, 0.5, 0.5])
    assert p.objective(poor, norm) > 1.5 * best
    z, gain, rounds = _confirm_optimum(p, poor, norm)
    assert rounds >= 1 and 0.0 <= gain <= CONFIRM_TOL
    assert p.objective(z, norm) == pytest.approx(best, rel=1e-7)
    z2, gain2, rounds2 = _confirm_optimum(p, z, norm)
    assert rounds2 == 0 and gain2 <= CONFIRM_TOL and np.array_equal(z2, z)


def test_a_restart_from_an_exact_device_gains_nothing():
    """At a = r0 with κ = 1 the error is 0 to the last bit (a zero free length makes the shape 1 exactly): the
    relative gain of a restart is then 0, not 0/0."""
    p = _Problem("tension", -50.0, 0.3, 2.6, SpringBounds((0.05, 0.2), (0.1, 0.3), (0.0, 0.3)), 21, "rms")
    z = p.encode(1.0, 1.0, 1.0)
    assert p.objective(z, "rms") == 0.0
    assert _confirm_optimum(p, z, "rms")[1:] == (0.0, 0)


def test_a_restart_that_cannot_settle_is_refused(monkeypatch):
    """With no round left, a restart that still gains is reported with the method's own message."""
    monkeypatch.setattr(driver, "CONFIRM_ROUNDS", 0)
    monkeypatch.setitem(driver.METHODS, "slsqp", lambda p, norm: (np.array([0.5, 0.5, 0.5]), "stopped", False))
    with pytest.raises(FitFailed) as exc:
        fit_spring("compression", 100.0, MID, ISSUE)
    # the relative gain of the one round: from the poor point's error to the optimum's (SLSQP from the scan)
    p = lever_problem(grid=61)
    best, opt = p.objective(np.array([0.5, 0.5, 0.5]), "max"), p.objective(_fit_slsqp(p, "max")[0], "max")
    gain = f"{100 * (best - opt) / best:.3g}"
    assert float(gain) > 90
    assert str(exc.value) == (f"the slsqp fit did not settle: 0 restarts from its point (Nelder–Mead, then SLSQP) "
                              f"still lowered the max error by {gain} % in the last (stopped).")


def test_a_method_that_stops_at_the_optimum_without_saying_so(monkeypatch):
    """A method that reports no convergence at a point no restart improves: the message says it is a local
    optimum all the same, and no restart is counted."""
    honest = driver.METHODS["slsqp"]
    monkeypatch.setitem(driver.METHODS, "slsqp", lambda p, norm: (honest(p, norm)[0], "unsure", False))
    res = fit_spring("compression", 100.0, MID, ISSUE, grid=21)
    assert res.restarts == 0
    assert res.message == ("unsure — yet a restart from its point (Nelder–Mead, then SLSQP) lowers the error by less "
                           "than 1e-09: a local optimum")


#: two limits binding, two directions free: the optimum of the max norm is not that of the RMS norm
INTERIOR = SpringBounds(r=(0.03, 0.32), r0=(0.03, 0.88), a=(0.0, 0.58), max_force=2400.0, max_free_length=0.97)
WIDE = (math.radians(8), math.radians(188))


def test_a_method_that_stops_short_is_restarted_and_says_how_often(monkeypatch):
    monkeypatch.setitem(driver.METHODS, "slsqp", lambda p, norm: (np.array([0.5, 0.5, 0.5]), "stopped", False))
    res = fit_spring("compression", 100.0, MID, ISSUE, grid=21)
    ref = fit_spring("compression", 100.0, MID, ISSUE, grid=21, method="nelder-mead")
    assert res.restarts >= 1 and res.grid_max_rel_error == pytest.approx(ref.grid_max_rel_error, rel=1e-7)
    assert res.message == (f"stopped; restarted {res.restarts}× from its point (Nelder–Mead, then SLSQP): a local "
                           "optimum to 1e-09 of the error")


@pytest.mark.parametrize("norm", ["max", "rms"])
def test_the_restarts_minimise_the_norm_asked(monkeypatch, norm):
    """Where the two norms' optima differ, the restarts from a poor point end at the optimum of the norm asked
    (measured to 1e-14 of SLSQP's own; with the other norm 6 % off)."""
    honest = driver.METHODS["slsqp"]
    ref = fit_spring("compression", 100.0, WIDE, INTERIOR, norm=norm, grid=21)
    monkeypatch.setitem(driver.METHODS, "slsqp", lambda p, norm: (np.array([0.5, 0.5, 0.5]), "stopped", False))
    res = fit_spring("compression", 100.0, WIDE, INTERIOR, norm=norm, grid=21)
    key = "grid_max_rel_error" if norm == "max" else "grid_rms_rel_error"
    assert getattr(res, key) == pytest.approx(getattr(ref, key), rel=1e-9) and res.restarts >= 1
    monkeypatch.setitem(driver.METHODS, "slsqp", honest)


@pytest.mark.parametrize("point, sentence", [
    (np.array([0.5, math.nan, 0.5]), "the slsqp method returned a non-finite point (stopped)."),
    (np.array([1.0, 2.0, 0.5]), "the slsqp method ended outside the bounds (stopped): where a limit leaves no room "
                                "for a, it stops just past it; the default method, slsqp, keeps such limits exactly."),
    # 2r + r0 = 1.21 ℓ against a free length of at most 1.2 ℓ: 0.01 past it
    (np.array([0.5, 0.21, 0.5]), "the slsqp method ended outside the bounds (stopped): where a limit leaves no room "
                                 "for a, it stops just past it; the default method, slsqp, keeps such limits exactly."),
])
def test_a_method_that_ends_where_no_device_is_refused(monkeypatch, point, sentence):
    """A non-finite point, or one past a limit (here 2r + r0 = 2 m over a free length of at most 0.6 m)."""
    monkeypatch.setitem(driver.METHODS, "slsqp", lambda p, norm: (point, "stopped", True))
    b = SpringBounds((0.01, 0.5), (0.01, 1.0), (0.0, 1.0), max_free_length=0.6)
    with pytest.raises(FitFailed) as exc:
        fit_spring("compression", 100.0, MID, b)
    assert str(exc.value) == sentence


def test_trf_on_the_max_norm_says_its_restart_gained_nothing(monkeypatch):
    """trf's max-norm point is always restarted (Lawson's reweighting only nears the minimax point): ending at
    the optimum, the message says the restart gained nothing; short of it, how many restarts it took."""
    optimum = driver.METHODS["slsqp"]
    monkeypatch.setitem(driver.METHODS, "trf", lambda p, norm: (optimum(p, norm)[0], "Lawson", True))
    res = fit_spring("compression", 100.0, MID, ISSUE, method="trf", norm="max", grid=21)
    assert (res.restarts, res.message) == (0, "Lawson; a restart from its point (Nelder–Mead, then SLSQP) gains less "
                                              "than 1e-09")
    monkeypatch.setitem(driver.METHODS, "trf", lambda p, norm: (np.array([0.5, 0.5, 0.5]), "Lawson", True))
    res = fit_spring("compression", 100.0, MID, ISSUE, method="trf", norm="max", grid=21)
    assert res.restarts >= 1 and res.message.startswith("Lawson; restarted ")
    res = fit_spring("compression", 100.0, MID, ISSUE, method="trf", norm="rms", grid=21)
    assert (res.restarts, res.message) == (0, "Lawson")        # on the RMS norm trf's own point is kept


@pytest.mark.parametrize("norm", ["max", "rms"])
def test_the_scale_is_solved_for_the_final_shape(norm):
    """κ of the result is the best one for its geometry in the norm asked (a least-squares solve for the RMS norm,
    a linear programme for the max norm: the two differ by 3.5e-5 here), and c follows."""
    res = fit_spring("compression", 100.0, MID, ISSUE, norm=norm, grid=21)
    p = lever_problem(norm)
    rho, rho0, al, kappa = res.x
    h, s = p.w * p.shape(rho, rho0, al), p.w
    if norm == "rms":
        best = float(np.linalg.lstsq(h[:, None], s, rcond=None)[0][0])
    else:
        n = len(h)
        best = optimize.linprog([0, 1], A_ub=np.block([[h[:, None], -np.ones((n, 1))], [-h[:, None], -np.ones((n, 1))]]),
                                b_ub=np.concatenate([s, -s]), bounds=[(0, None), (0, None)], method="highs").x[0]
    assert kappa == pytest.approx(best, rel=1e-9)
    assert res.c == pytest.approx(kappa * 100.0 / (res.r * (res.r + res.r0)), rel=1e-12)
    assert res.method == "slsqp" and res.norm == norm and res.seconds > 0


def test_a_tension_spring_is_exact_only_when_no_method_is_asked_for():
    b = SpringBounds((0.05, 0.2), (0.1, 0.3), (0.0, 0.3))
    exact = fit_spring("tension", -10.0, R, b)
    assert exact.method == "exact" and exact.message == "zero free length (a = r0): exact" and exact.notes == ()
    fitted = fit_spring("tension", -10.0, R, b, method="slsqp", grid=21)
    assert fitted.method == "slsqp" and "zero free length" not in " ".join(fitted.notes)
    apart = fit_spring("tension", -10.0, R, SpringBounds((0.05, 0.2), (0.3, 0.5), (0.0, 0.1)), grid=21)
    assert apart.method == "slsqp" and apart.notes == ("a zero free length (a = r0) is outside the bounds; fitted "
                                                       "instead",)


def test_each_device_is_finished_by_its_own_family():
    lever = fit_spring("compression-lever", -10.0, R, LEVER)
    assert lever.method == "exact" and lever.lever is not None and lever.family == "slotted-lever"
    assert lever.norm == "max" and fit_spring("compression-lever", -10.0, R, LEVER, norm="rms").norm == "rms"
    sine = fit_spring("compression", -10.0, R, SINE, device="sine", grid=21)
    assert sine.family == "sine" and sine.r0 is None and sine.rod is None
    # the slider devices take either sign of Φ0: no refusal of the sense
    assert fit_spring("compression", 10.0, R, SINE, device="sine", grid=21).sense == 1 and sine.sense == -1


def test_a_small_moment_of_the_right_sign_is_taken():
    """Φ0 = 0.5 N·m on a compression spring: positive, the device's own sense (nothing about 1 N·m)."""
    assert fit_spring("compression", 0.5, R, LEVER, grid=21).sense == 1
    assert fit_spring("tension", -0.5, R, LEVER, grid=21).sense == -1


def test_the_max_norm_sees_a_steep_dead_centre():
    """r0/r = 2e-4 and φ = 0 in the range, κ the only freedom: the fit's grid resolves the turn of the moment at
    0 (points clustered there), so its largest error is the minimax one of a dense grid (a linear programme in
    κ over 40 001 uniform and 4 000 clustered angles, moments from positions); on the uniform grid alone 3 % more."""
    from tests.balance.test_fit_vs_oracle import moment_from_positions

    b = SpringBounds(r=(0.5, 0.5), r0=(1e-4, 1e-4), a=(0.0, 0.0))
    lo, hi = math.radians(-30), math.radians(30)
    res = fit_spring("compression", 100.0, (lo, hi), b)
    offs = np.geomspace(1e-8, 0.5, 2000)
    phi = np.unique(np.concatenate([np.linspace(lo, hi, 40001), offs, -offs]))
    m, _ = moment_from_positions("compression", 1.0, 0.5, 1e-4, 0.0, phi)
    h, s, n = m / 100.0, np.sin(phi), len(phi)
    lp = optimize.linprog([0, 1], A_ub=np.block([[h[:, None], -np.ones((n, 1))], [-h[:, None], -np.ones((n, 1))]]),
                          b_ub=np.concatenate([s, -s]), bounds=[(0, None), (0, None)], method="highs")
    assert lp.fun <= res.max_rel_error <= lp.fun * 1.001


def test_a_range_given_as_text_is_read():
    lo, hi = _phi_range(("0.5", "2.5"))
    assert (lo, hi) == (0.5, 2.5)
