"""balance/devices/fit/result.py by hand: the lever of a compression-lever device and its sentence,
the largest value on a range (ends, a floor, a peak between grid points, a grid of two points),
the dead-centre notes' sentences and a result's JSON."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import SpringBounds, fit_spring
from balance.devices.fit.result import LeverGeometry, dead_centre_notes, largest_on_range, relative_errors


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
