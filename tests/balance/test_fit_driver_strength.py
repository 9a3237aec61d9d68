"""balance/devices/fit/driver.py: every refusal of fit_spring in full, each limit on both sides
(the grid's 5 and MAX_GRID points, one turn of φ, 1e-9 rad, a deflection ratio in (0, 1)), and the
bounds a device takes passed on unchanged."""

from __future__ import annotations

import math

import pytest

from balance import SpringBounds, fit_spring
from balance.devices.fit import DEVICES, MAX_GRID
from balance.devices.fit.driver import _checked_bounds, _phi_range
from balance.errors import InvalidInput, InvalidRange, WrongSense

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
