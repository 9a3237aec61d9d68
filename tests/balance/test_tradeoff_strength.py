"""balance/devices/tradeoff.py piece by piece: each bound moved by 25 % and said in words, the
largest |sin| over a range, the non-dominated devices of a hand-made set, the advice's sentences,
and the sensitivities against fits made here with the moved bounds."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from balance.devices.fit import SpringBounds, fit_spring
from balance.devices.tradeoff import (RELAX, ParetoPoint, Sensitivity, _nondominated, _peak_sin, _relaxed, advice,
                                      bound_sensitivity, pareto_front)

RAD = (math.radians(20), math.radians(160))
B = SpringBounds(r=(0.02, 0.5), r0=(0.04, 1.0), a=(0.1, 0.8), max_force=2000.0, max_free_length=1.6,
                 max_deflection=0.6, rod=(0.3, 0.9))


@pytest.fixture(scope="module")
def fit():
    return fit_spring("compression", 100.0, RAD, SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0)))


@pytest.mark.parametrize("name, field, value, words", [
    ("r=min", "r", (0.015, 0.5), "lower bound on r to 0.015 m"),
    ("r=max", "r", (0.02, 0.625), "upper bound on r to 0.625 m"),
    ("r0=min", "r0", (0.03, 1.0), "lower bound on r0 to 0.03 m"),
    ("r0=max", "r0", (0.04, 1.25), "upper bound on r0 to 1.25 m"),
    ("rod=min", "rod", (0.225, 0.9), "lower bound on the rod to 0.225 m"),
    ("rod=max", "rod", (0.3, 1.125), "upper bound on the rod to 1.125 m"),
    ("a=min", "a", (0.075, 0.8), "lower bound on a to 0.075 m"),
    ("a=max", "a", (0.1, 1.0), "upper bound on a to 1 m"),
    ("max_free_length", "max_free_length", 2.0, "maximum free length to 2 m"),
    ("max_force", "max_force", 2500.0, "force limit to 2500 N"),
    ("max_deflection", "max_deflection", 0.75, "maximum deflection to 0.75"),
])
def test_each_bound_moves_a_quarter_outwards(fit, name, field, value, words):
    assert RELAX == 0.25
    moved, said = _relaxed(name, B, fit)
    assert said == words
    assert getattr(moved, field) == pytest.approx(value, rel=1e-12)
    assert replace(moved, **{field: getattr(B, field)}) == B  # nothing else moved


def test_bounds_that_cannot_move_a_quarter(fit):
    zero = SpringBounds(r=(0.0, 0.5), r0=(0.0, 1.0), a=(0.0, math.inf))
    for name in ("r=min", "r0=min", "a=min", "a=max", "max_force", "max_free_length", "max_deflection", "nonsense"):
        assert _relaxed(name, zero, fit) is None
    # a deflection ratio stops at 0.95, and one at 0.95 or more is not moved
    assert _relaxed("max_deflection", replace(B, max_deflection=0.9), fit)[0].max_deflection == 0.95
    assert _relaxed("max_deflection", replace(B, max_deflection=0.95), fit) is None
    # an upper bound of zero on a becomes a quarter of the reference length (the largest crank)
    moved, said = _relaxed("a=max", replace(B, a=(0.0, 0.0)), fit)
    assert moved.a == (0.0, 0.25 * fit.reference_length) and said == "upper bound on a to 0.125 m"


@pytest.mark.parametrize("lo, hi, peak", [
    (0.1, 0.5, math.sin(0.5)), (2.0, 3.0, math.sin(2.0)), (0.2, 3.0, 1.0), (-0.5, 0.2, math.sin(0.5)),
    (4.0, 5.0, 1.0), (3.3, 4.0, abs(math.sin(4.0))), (-2.0, -1.0, 1.0), (math.pi / 2, math.pi / 2, 1.0),
    (1.6, 1.7, math.sin(1.6)),
])
def test_the_largest_sine_over_a_range(lo, hi, peak):
    import numpy as np

    assert _peak_sin((lo, hi)) == pytest.approx(peak, rel=1e-12)
    assert _peak_sin((lo, hi)) == pytest.approx(np.abs(np.sin(np.linspace(lo, hi, 100001))).max(), abs=1e-9)


def point(error, size, force):
    return ParetoPoint(error, size, force, 1.0, 0.1, 0.2, 0.0, ())


def test_the_devices_no_other_beats_in_all_three():
    a, b, c = point(0.01, 1.0, 500.0), point(0.02, 0.5, 500.0), point(0.03, 0.4, 300.0)
    worse = point(0.02, 1.1, 600.0)       # a beats it in all three
    tie = point(0.01, 1.0, 500.0)         # a again: kept once
    near = point(0.01 * (1 + 1e-7), 1.0, 500.0)  # within 1e-6 of a everywhere: neither beats the other
    front = _nondominated([a, worse, b, c, tie, near])
    assert set(map(id, front)) >= {id(b), id(c)} and worse not in front
    assert sum(p.error == 0.01 and p.size == 1.0 for p in front) == 1
    assert near in front
    # sorted by size, then by force
    assert [p.size for p in front] == sorted(p.size for p in front)
    assert [p.force for p in _nondominated([point(0.02, 1.0, 400.0), point(0.01, 1.0, 500.0)])] == [400.0, 500.0]
    # equal in two coordinates and smaller in the third: beaten
    assert _nondominated([point(0.01, 1.0, 500.0), point(0.01, 0.9, 500.0)]) == [point(0.01, 0.9, 500.0)]
    # beaten in one coordinate by a hair, equal in the others: not beaten
    assert len(_nondominated([point(0.01, 1.0, 500.0), point(0.01 * (1 + 1e-8), 1.0, 500.0 * (1 - 1e-8))])) == 2


def test_the_sensitivities_are_refits_with_each_bound_moved(fit):
    b = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))
    rows = bound_sensitivity(fit, b)
    assert [s.bound for s in rows] == sorted((s.bound for s in rows), key=lambda n: -next(
        r.gain for r in rows if r.bound == n))
    for s in rows:
        moved, said = _relaxed(s.bound, b, fit)
        new = fit_spring("compression", 100.0, RAD, moved)
        assert s.move == said
        assert s.error == pytest.approx(new.max_rel_error, rel=1e-6)
        assert s.gain == pytest.approx((fit.max_rel_error - new.max_rel_error) / fit.max_rel_error, rel=1e-6)
        assert s.to_dict() == {"bound": s.bound, "move": s.move, "error": s.error, "gain": s.gain}


def test_a_tension_fit_has_no_front():
    res = fit_spring("tension", -100.0, RAD, SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0)))
    assert pareto_front(res, SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))) == []


def test_the_advice_in_words(fit):
    sens = [Sensitivity("r0=max", "upper bound on r0 to 1.25 m", 0.004, 0.6),
            Sensitivity("a=max", "upper bound on a to 1.25 m", 0.008, 0.2)]
    on, missed = advice(fit, sens, target_error=0.001)
    err = fit.max_rel_error
    assert on == (f"the optimum sits on the bound(s) r0=max, a=max: it is a trade-off, not a free optimum; "
                  f"moving the upper bound on r0 to 1.25 m lowers the max error from {100 * err:.3g} % to 0.4 %")
    assert missed == (f"the max error {100 * err:.3g} % misses the requested 0.1 %; move the upper bound on r0 "
                      f"to 1.25 m first (the largest gain)")
    assert advice(fit, sens, target_error=0.5) == [on]  # met: no second warning
    assert advice(fit, [], target_error=None) == []
    rms = replace(fit, norm="rms")
    (line,) = advice(rms, [], target_error=0.001)
    assert line == f"the RMS error {100 * fit.rms_rel_error:.3g} % misses the requested 0.1 %"
    front = [point(0.0005, 1.2, 900.0), point(0.0008, 0.9, 1500.0), point(0.0009, 2.0, 700.0), point(0.2, 0.1, 10.0)]
    (line,) = advice(fit, [], target_error=0.001, front=front)
    assert line == (f"the max error {100 * err:.3g} % misses the requested 0.1 %; the Pareto front reaches it with "
                    "a free length of 0.9 m (peak force 1500 N) or a peak force of 700 N (free length 2 m): raise the "
                    "maximum free length or the force limit to there")
    line = advice(fit, sens, target_error=0.001, front=[point(0.2, 0.1, 10.0)])[1]
    assert line == (f"the max error {100 * err:.3g} % misses the requested 0.1 %; no device within the bounds "
                    "on r, r0 and a reaches it: widen them")


# (a long crank: the free device's peak force is 1.36× the least any crank can work with)
@pytest.mark.parametrize("r", [(0.01, 0.5), (0.45, 0.5)])
def test_the_front_sweeps_the_free_length_and_force_limits_it_documents(r, monkeypatch):
    """steps × steps fits: free-length limits from 1.02 × the shortest device of the box (2·r_min + r0_min +
    a_min) to the free length of the best device without limits, force limits from 1.05 × the least a crank
    of r_max can work with (|Φ0|·max|sin φ|/r_max) to that device's peak force, both geometric."""
    import numpy as np

    from balance.devices import tradeoff

    b = SpringBounds(r=r, r0=(0.01, 1.0), a=(0.0, 1.0), max_force=2000.0, max_free_length=1.5)
    fit = fit_spring("compression", 100.0, RAD, b)
    calls = []
    real = tradeoff._refit

    def recorded(res, bounds):
        calls.append(bounds)
        return real(res, bounds)

    monkeypatch.setattr(tradeoff, "_refit", recorded)
    front = pareto_front(fit, b, steps=3)
    free = fit_spring("compression", 100.0, RAD, SpringBounds(r=r, r0=(0.01, 1.0), a=(0.0, 1.0)))
    assert calls[0] == SpringBounds(r=r, r0=(0.01, 1.0), a=(0.0, 1.0))
    sizes = np.geomspace(1.02 * (2 * r[0] + 0.01 + 0.0), free.free_length, 3)
    forces = np.geomspace(1.05 * 100.0 / 0.5, free.max_force, 3)
    swept = [(c.max_free_length, c.max_force) for c in calls[1:]]
    assert swept == pytest.approx([(s, f) for s in sizes for f in forces], rel=1e-12)
    assert all((c.r, c.r0, c.a) == (b.r, b.r0, b.a) for c in calls)
    # the device without those limits has the least error of all: it is on the front
    best = min(front, key=lambda p: p.error)
    assert (best.error, best.size, best.force) == pytest.approx((free.max_rel_error, free.free_length,
                                                                 free.max_force), rel=1e-9)
    assert all(p.to_dict()["active_bounds"] == list(p.active_bounds) for p in front)


def test_a_slider_device_is_refitted_as_itself():
    b = SpringBounds((0.02, 0.12), None, (0.0, 0.3), max_force=1500.0, max_free_length=0.5)
    res = fit_spring("compression", -30.0, (math.radians(-80), math.radians(250)), b, device="sine")
    rows = bound_sensitivity(res, b)
    assert rows
    for s in rows:
        moved, _ = _relaxed(s.bound, b, res)
        again = fit_spring("compression", -30.0, (math.radians(-80), math.radians(250)), moved, device="sine")
        assert s.error == pytest.approx(again.max_rel_error, rel=1e-6)
