"""balance/devices/fit/result.py by hand: the lever of a compression-lever device and its sentence,
the largest value on a range (ends, a floor, a peak between grid points, a grid of two points),
the dead-centre notes' sentences and a result's JSON; every number of a finished result from its device
alone (moments from positions on dense samples), the verification grid and each active bound at its
tolerance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import SpringBounds, fit_spring
from balance.devices.fit.problem import _Problem
from balance.devices.fit.result import (VERIFY_GRID, LeverGeometry, _active, _finish, _verify_grid, dead_centre_notes,
                                        largest_on_range, measured_errors, relative_errors)
from tests.balance.test_fit_vs_oracle import free_length, moment_from_positions


def test_the_lever_of_a_spring_by_hand():
    """A spring of free length 0.5 m compressed to 0.2 … 0.4 m: the stop 0.5 m from C, the spring
    0.3 … 0.1 m long, the lever 0.1 m beyond the farthest crank pin, 1.25× a spring between C and B."""
    g = LeverGeometry.for_spring(0.5, 0.2, 0.4)
    assert (g.stop_distance_from_C, g.spring_free_length) == (0.5, 0.5)
    assert (g.spring_length_min, g.spring_length_max) == pytest.approx((0.1, 0.3), rel=1e-15)
    assert (g.compression_min, g.compression_max, g.deflection_ratio) == (0.2, 0.4, 0.8)
    assert (g.reach_from_C, g.reach_from_C_fig_a) == (0.5, 0.4)
    assert g.extra_length == pytest.approx(0.1, rel=1e-15) and g.size_ratio == pytest.approx(1.25, rel=1e-15)
    assert not g.designed_from_spring and LeverGeometry.for_spring(0.5, 0.2, 0.4, designed=True).designed_from_spring
    assert g.note() == ("the lever reaches 0.5 m from C, 0.1 m beyond the farthest crank-pin position (1.25× the "
                        "0.4 m of a spring between C and B): the price of an exact compression spring")
    d = g.to_dict()
    assert d["reach_from_C"] == 0.5 and d["reach_from_C_fig_a"] == 0.4
    assert d["extra_length"] == pytest.approx(0.1) and d["size_ratio"] == pytest.approx(1.25)
    assert d["stop_distance_from_C"] == 0.5 and d["designed_from_spring"] is False


def test_the_largest_value_on_a_range():
    grid = np.linspace(0.0, 1.0, 11)
    peak = lambda x: 1.0 - (x - 0.537) ** 2  # noqa: E731  (between grid points)
    assert largest_on_range(peak, 0.0, 1.0, grid) == pytest.approx(1.0, abs=1e-15)
    assert largest_on_range(peak, 0.0, 0.3, grid) == pytest.approx(1 - 0.237 ** 2, rel=1e-15)  # the end 0.3
    assert largest_on_range(peak, 0.7, 1.0, grid) == pytest.approx(1 - 0.163 ** 2, rel=1e-15)  # the end 0.7
    assert largest_on_range(lambda x: -x, 0.2, 0.9, grid) == -0.2
    # at most the floor: the grid's largest, not refined
    small = lambda x: 1e-14 * peak(x)  # noqa: E731
    assert largest_on_range(small, 0.0, 1.0, grid) == small(np.array([0.5]))[0]
    assert largest_on_range(small, 0.0, 1.0, grid, floor=1e-16) == pytest.approx(1e-14, rel=1e-12)
    # two points, one of them the larger: nothing to bracket
    assert largest_on_range(peak, 0.5, 0.6, np.array([])) == pytest.approx(1 - 0.037 ** 2, rel=1e-15)
    # 50 peaks rising towards x = 1, none on a grid point: the highest is refined (the first 24 by height)
    many = lambda x: (1 + x) * np.cos(2 * math.pi * 50 * (x - 0.013))  # noqa: E731
    dense = np.linspace(0.9, 1.0, 2_000_001)
    assert largest_on_range(many, 0.0, 1.0, np.linspace(0.0, 1.0, 173)) == pytest.approx(many(dense).max(), rel=1e-9)
    # two peaks: the higher one, wherever the grid's best sample lies
    two = lambda x: np.maximum(1.0 - 400 * (x - 0.12) ** 2, 1.001 - 400 * (x - 0.75) ** 2)  # noqa: E731
    assert largest_on_range(two, 0.0, 1.0, np.linspace(0, 1, 5)) == pytest.approx(1.001, rel=1e-12)


@pytest.mark.parametrize("lo, hi, notes", [
    (10, 170, []),
    (-30, 30, ["the range crosses the dead centre φ = 0°, where crank AB and spring BC are in line: the device's "
               "moment and the target both pass through zero and change sign there, so the crank is held in both "
               "directions; at 0° the spring is shortest (0.2 m)"]),
    (90, 270, ["the range crosses the dead centre φ = 180°, where crank AB and spring BC are in line: the "
               "device's moment and the target both pass through zero and change sign there, so the crank is "
               "held in both directions; at 180° longest (2r + r0 = 0.4 m)"]),
    (-10, 190, ["the range crosses the dead centres φ = 0° and 180°, where crank AB and spring BC are in line: the "
                "device's moment and the target both pass through zero and change sign there, so the crank is "
                "held in both directions; at 0° the spring is shortest (0.2 m) and at 180° longest "
                "(2r + r0 = 0.4 m)"]),
    (0, 180, []),        # a dead centre at an end of the range is not crossed
    # half a degree past a dead centre (a division by 181 instead of 180 would miss it)
    (100, 180.5, ["the range crosses the dead centre φ = 180°, where crank AB and spring BC are in line: the "
                  "device's moment and the target both pass through zero and change sign there, so the crank is "
                  "held in both directions; at 180° longest (2r + r0 = 0.4 m)"]),
    (170, 370, ["the range crosses the dead centres φ = 180° and 360°, where crank AB and spring BC are in line: "
                "the device's moment and the target both pass through zero and change sign there, so the crank "
                "is held in both directions; at 0° the spring is shortest (0.2 m) and at 180° longest "
                "(2r + r0 = 0.4 m)"]),
])
def test_dead_centre_notes_in_words(lo, hi, notes):
    assert dead_centre_notes(math.radians(lo), math.radians(hi), 0.1, 0.2) == notes


def test_a_result_as_json():
    res = fit_spring("tension", -50.0, (0.2, 2.9), SpringBounds((0.05, 0.1), (0.1, 0.2), (0.0, 0.3)))
    d = res.to_dict()
    assert d["phi_range"] == [0.2, 2.9] and d["phi_range_deg"] == pytest.approx([math.degrees(0.2),
                                                                                   math.degrees(2.9)])
    assert d["x"] == list(res.x) and d["active_bounds"] == list(res.active_bounds) and d["notes"] == list(res.notes)
    assert d["lever"] is None and d["family"] == "slotted-lever" and d["method"] == "exact"
    assert d["sense"] == -1 and d["sense_text"] == "towards the base point C (decreasing φ)"
    # the exact device: its error is round-off, measured from the physical device
    phi = np.linspace(0.2, 2.9, 1001)
    assert np.abs(relative_errors(res.device, -50.0, phi)).max() < 1e-12 and res.max_rel_error < 1e-12
    lever = fit_spring("compression-lever", -50.0, (0.2, 2.9), SpringBounds((0.05, 0.1), (0.1, 0.2), (0.0, 0.3)))
    assert lever.to_dict()["lever"] == lever.lever.to_dict() and lever.to_dict()["deflection"] == 0.5


# ---------------------------------------------------------------- a result's numbers from its device alone
B = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3))


@pytest.mark.parametrize("kind, moment, lo, hi, y", [
    ("compression", 80.0, 0.3, 2.6, (0.6, 1.2, 0.4, 1.1)),
    ("compression", 80.0, -0.5, 3.5, (0.9, 0.3, 0.1, 0.8)),      # both dead centres inside
    ("tension", -60.0, -2.0, 1.0, (0.5, 1.5, 0.3, 0.9)),
])
def test_a_finished_result_by_hand(kind, moment, lo, hi, y):
    """Every number of _finish from the device (κ·|Φ0|/(r·d), lengths times ℓ) and its moment from positions:
    the errors on a dense sample and on the fit grid, the largest force, the deflection, the free length."""
    p = _Problem(kind, moment, lo, hi, B, 31, "rms")
    res = _finish(p, y, "slsqp", "rms", 0.0, "done", [], 2)
    rho, rho0, al, kappa = y
    r, r0, a = 0.4 * rho, 0.4 * rho0, 0.4 * al
    c = kappa * abs(moment) / (r * (r + r0))
    assert (res.r, res.r0, res.a) == pytest.approx((r, r0, a), rel=1e-15) and res.c == pytest.approx(c, rel=1e-14)
    assert res.d == pytest.approx(r + r0, rel=1e-15) and res.free_length == pytest.approx(free_length(kind, r, r0, a))
    assert res.x == y and (res.kind, res.method, res.norm, res.moment) == (kind, "slsqp", "rms", moment)
    assert (res.phi_range, res.grid, res.message, res.restarts, res.reference_length) == ((lo, hi), 31, "done", 2, 0.4)
    assert res.nfev == 1 and res.seconds > 0
    phi = np.linspace(lo, hi, 40001)
    m, L = moment_from_positions(kind, c, r, r0, a, phi)
    e = (m - moment * np.sin(phi)) / abs(moment)
    assert res.max_rel_error == pytest.approx(np.max(np.abs(e)), rel=1e-6)
    u = np.linspace(lo, hi, 4001)
    eu = (moment_from_positions(kind, c, r, r0, a, u)[0] - moment * np.sin(u)) / abs(moment)
    assert res.rms_rel_error == pytest.approx(np.sqrt(np.mean(eu ** 2)), rel=1e-9)
    g = p.phi
    eg = (moment_from_positions(kind, c, r, r0, a, g)[0] - moment * np.sin(g)) / abs(moment)
    assert res.grid_max_rel_error == pytest.approx(np.max(np.abs(eg)), rel=1e-9)
    assert res.grid_rms_rel_error == pytest.approx(np.sqrt(np.mean(eg ** 2)), rel=1e-9)
    l0 = free_length(kind, r, r0, a)
    assert res.max_force == pytest.approx(c * np.max(np.abs(L - l0)), rel=1e-6)
    if kind == "compression":
        assert res.deflection == pytest.approx((l0 - L.min()) / l0, rel=1e-6)
    else:
        assert res.deflection is None
    assert res.sense == (1 if kind == "compression" else -1)
    assert res.sense_text == ("away from the base point C (increasing φ)" if kind == "compression"
                              else "towards the base point C (decreasing φ)")
    assert list(res.notes) == dead_centre_notes(lo, hi, r, r0) and res.active_bounds == ()
    assert res.device.moment(1.0) == pytest.approx(moment_from_positions(kind, c, r, r0, a, 1.0)[0], rel=1e-12)


def test_a_short_spring_at_a_dead_centre_is_noted():
    """r0/r below 0.05 with φ = 0 inside the range: a note on the steep part, with its width in degrees."""
    b = SpringBounds(r=(0.05, 0.5), r0=(1e-3, 0.1), a=(0.0, 0.3))
    p = _Problem("compression", 80.0, -0.5, 1.0, b, 31, "max")
    res = _finish(p, (1.0, 0.02, 0.1, 1.0), "slsqp", "max", 0.0, "done", [])
    assert res.notes[0] == ("r0/r = 0.02 with φ = 0 in the range: the moment changes steeply within |φ| ≲ 1.15° of 0 "
                            "(resolved by the verification grid)")
    assert len(res.notes) == 2 and "dead centre φ = 0°" in res.notes[1]
    assert all("steeply" not in n for n in _finish(p, (1.0, 0.05, 0.1, 1.0), "slsqp", "max", 0.0, "", []).notes)
    away = _Problem("compression", 80.0, 0.3, 1.0, b, 31, "max")
    assert _finish(away, (1.0, 0.02, 0.1, 1.0), "slsqp", "max", 0.0, "", []).notes == ()


def test_the_verification_grid_resolves_the_dead_centres():
    phi = _verify_grid(-1.0, 7.0, 0.5, 0.01)
    np.testing.assert_array_equal(phi[:VERIFY_GRID], np.linspace(-1.0, 7.0, VERIFY_GRID))
    extra = phi[VERIFY_GRID:]
    offs = np.geomspace(0.02 * 1e-2, 0.02 * 1e2, 200)
    want = np.concatenate([offs, -offs, 2 * math.pi + offs, 2 * math.pi - offs])
    np.testing.assert_allclose(np.sort(extra), np.sort(want[(want >= -1.0) & (want <= 7.0)]), rtol=1e-15)
    assert len(extra) == 762                                     # (the offsets past −1 and 7 left out)
    assert len(_verify_grid(0.5, 6.0, 0.5, 0.01)) == VERIFY_GRID                 # no multiple of 2π inside
    below = _verify_grid(-7.0, -5.0, 0.5, 0.01)[VERIFY_GRID:]                    # −2π inside a negative range
    assert len(below) == 200 + 167 and np.all(np.abs(below + 2 * math.pi) <= 2.0 * (1 + 1e-12))  # (167 above −7)
    near_zero = _verify_grid(-1.0, 5.0, 0.5, 0.01)[VERIFY_GRID:]                 # 2π − 2 = 4.28 < 5: not a centre
    assert np.all(np.abs(near_zero) <= 2.0 * (1 + 1e-12)) and len(near_zero) == 200 + 185   # (185 of the 200 below 0 within −1)
    wide = _verify_grid(-4.0, 2.0, 0.01, 1.0)                                    # r0/r = 100: offsets up to π
    assert np.max(np.abs(wide[VERIFY_GRID:])) == pytest.approx(math.pi, rel=1e-14)
    assert np.min(np.abs(_verify_grid(-1.0, 1.0, 1.0, 0.0)[VERIFY_GRID:])) == pytest.approx(1e-14, rel=1e-9)


def test_the_measured_errors_are_the_largest_and_the_uniform_rms():
    from balance.devices.springs import CrankRockerDevice

    dev = CrankRockerDevice("compression", 9000.0, 0.02, 0.9, 1.0)
    fine = np.linspace(0.35, 2.8, 200001)
    e = np.abs(moment_from_positions("compression", 9000.0, 0.02, 0.9, 1.0, fine)[0] - 100.0 * np.sin(fine)) / 100.0
    phi = np.concatenate([np.linspace(0.35, 2.8, VERIFY_GRID), [0.351, 0.352]])   # points past the uniform part
    worst, rms = measured_errors(dev, 100.0, 0.35, 2.8, phi)
    assert worst == pytest.approx(e.max(), rel=1e-9)
    u = np.linspace(0.35, 2.8, VERIFY_GRID)
    eu = (moment_from_positions("compression", 9000.0, 0.02, 0.9, 1.0, u)[0] - 100.0 * np.sin(u)) / 100.0
    assert rms == pytest.approx(np.sqrt(np.mean(eu ** 2)), rel=1e-12)


FORCED = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3), max_force=500.0, max_free_length=1.0,
                      max_deflection=0.3)


@pytest.mark.parametrize("shift, named", [(1e-7, True), (1e-5, False)])
def test_each_active_bound_named_within_its_tolerance(shift, named):
    """A bound is active within 1e-6 (relative, or absolute below 1): each one named, at its own edge."""
    p = _Problem("compression", 80.0, 0.3, 2.6, FORCED, 31, "max")
    s = 1 + shift
    cases = [("r=min", (0.125 * s, 1.0, 0.2)), ("r=max", (1.0 / s, 1.0, 0.2)), ("r0=min", (0.3, 0.25 * s, 0.2)),
             ("r0=max", (0.3, 2.0 / s, 0.2)), ("a=min", (0.3, 1.0, shift)), ("a=max", (0.3, 1.0, 0.75 - shift)),
             ("max_free_length", (0.3, 1.0, 2.5 - 1.6 - shift))]
    for name, (rho, rho0, al) in cases:
        k = 0.5 * p.kappa_max(rho, rho0, al)
        assert (name in _active(p, rho, rho0, al, k)) == named, name
    rho, rho0 = 0.3, 1.0
    lmin = math.sqrt(rho0 ** 2 + 4 * rho * (rho + rho0) * p.s2min)
    al = lmin / (1 - 0.3 * s) - 2 * rho - rho0 if named else lmin / (1 - 0.3 * (1 + 1e-3)) - 2 * rho - rho0
    assert ("max_deflection" in _active(p, rho, rho0, al, 1.0)) == named
    km = p.kappa_max(rho, rho0, 0.2)
    assert ("max_force" in _active(p, rho, rho0, 0.2, km / s)) == named
    assert _active(p, 0.3, 1.0, 0.2, 0.5 * km) == []


def test_the_tolerance_of_a_long_bound_is_relative():
    """Past 1 (in units of the longest crank) the tolerance grows with the bound: r0 ≤ 8 m is 20 ℓ, so a value
    2e-6 below it (1e-7 relative) is on it."""
    p = _Problem("compression", 80.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, 8.0), (0.0, 0.3)), 31, "max")
    assert _active(p, 0.3, 20.0 / (1 + 1e-7), 0.2, 1.0) == ["r0=max"]
    assert _active(p, 0.3, 20.0 / (1 + 2e-6), 0.2, 1.0) == []


def test_the_tension_springs_own_active_bounds():
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.5))
    p = _Problem("tension", -60.0, 0.3, 2.6, b, 31, "max")
    assert _active(p, 0.5, 1.0, 1.0, 1.0) == ["a=r0 (zero free length)"]
    assert _active(p, 0.5, 1.0, 0.99, 1.0) == []
    assert _active(p, 0.5, 1.0, 1.0 - 1e-7, 1.0) == ["a=r0 (zero free length)"]
    # (a deflection limit is a compression spring's: never named for a tension one)
    d = _Problem("tension", -60.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, 0.5), max_deflection=0.3),
                 31, "max")
    assert "max_deflection" not in _active(d, 0.5, 1.0, 0.2, 1.0)
