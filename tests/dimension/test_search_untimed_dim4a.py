"""The untimed path search (issue 40, item 1 of the global search's misses): its global cost is the
mechanism's own error at its own inputs, not the sampled curve's chords; six points on a line (CE1)
and the 60-point closed path of models/ are found exactly from no guess, the latter within 10 s."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from synth.atlas import sampled_starts
from synth.dimension import Constraints, PathTarget, synthesize
from synth.dimension._search import _Evaluate, _problem, _Search, _Watch
from synth.structure.chain import Chain, Mechanism

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
LINE = PathTarget(np.array([(20, 20), (20, 25), (20, 30), (20, 35), (20, 40), (20, 45)], dtype=float))


def test_the_global_cost_of_an_untimed_path_is_the_placed_mechanisms_own_error_at_its_inputs():
    """For random candidates (the tracer point left out, as the search evaluates them) the cost is the
    mean squared distance from each target point to the returned mechanism moved to the returned input
    offsets by the motion layer: a sampled curve's chord can no longer stand in for the curve."""
    problem, _ = _problem(FOUR_BAR, LINE, None, Constraints())
    evaluate = _Evaluate(problem)
    rng = np.random.default_rng(1)
    n = problem.searched
    checked = 0
    for _ in range(400):
        x = problem.lower[:n] + rng.random(n) * (problem.upper[:n] - problem.lower[:n])
        found = evaluate.untimed(x)
        if found is None or isinstance(found, float):
            continue
        cost, direction, offsets, moved = found
        placed = problem.linkage(moved)
        values, g, _ = problem.move(placed, np.concatenate(([0.0], offsets)))
        assert g is None or (g >= 0).all()
        r = problem.residuals(values)
        outside = np.maximum(moved - problem.upper, 0.0) + np.maximum(problem.lower - moved, 0.0)
        own = float((r * r).sum()) / len(r) + 1e2 * float(outside @ outside)
        assert cost == pytest.approx(own, rel=1e-9, abs=1e-15)
        checked += 1
    assert checked > 100


def test_a_four_bar_whose_sampled_curve_has_the_line_on_one_chord_does_not_meet_it():
    """A random four-bar the chords' cost put at 3e-29 for the six points on a line (all six on one 3°
    chord of its sampled curve, 1.5° of crank turn apart): on its own motion it misses them."""
    problem, _ = _problem(FOUR_BAR, LINE, None, Constraints())
    x = np.array([2.01642544, -1.13341394, 2.0598844, -3.6268427, 3.60692944, -2.33541569, -0.17433894, 3.36708203])
    assert _Evaluate(problem)(x) > 1e-4


def test_two_pivots_pinned_keep_an_untimed_candidates_shape():
    """Differential evolution searches an untimed path's four-bar with its pivots pinned (the placement
    moves it): the pinned form of a candidate is the candidate turned, scaled and moved (its joints'
    distance ratios kept), and the mechanism's own points cost nothing in either form.  (Untimed, the
    matching also starts from where the curve stands, so other candidates may settle in other fits.)"""
    problem, _ = _problem(FOUR_BAR, LINE, None, Constraints())
    evaluate = _Evaluate(problem)
    search = _Search(evaluate, problem, _Watch(1.0, None))
    lower, upper = search.bounds()
    assert (lower[:4] == upper[:4]).all() and upper[:4].tolist() == [0.0, 0.0, 1.0, 0.0]
    rng = np.random.default_rng(3)
    n = problem.searched
    for _ in range(20):
        x = problem.lower[:n] + rng.random(n) * (problem.upper[:n] - problem.lower[:n]) / 4
        pinned = search.canonical(x)
        a, b = x.reshape(-1, 2), pinned.reshape(-1, 2)
        da = np.linalg.norm(a[:, None] - a[None], axis=2)
        db = np.linalg.norm(b[:, None] - b[None], axis=2)
        if (np.abs(pinned) >= 4).any():
            continue  # (clipped to the box: another candidate)
        assert np.allclose(db * da[0, 1], da * db[0, 1], atol=1e-12)
    timed = PathTarget(LINE.points, np.radians([0, 30, 60, 90, 120, 150]))
    problem, _ = _problem(FOUR_BAR, timed, None, Constraints())
    assert _Search(_Evaluate(problem), problem, _Watch(1.0, None)).pinned() is None  # timed: searched unpinned


def test_six_points_on_a_line_are_met_exactly_from_no_guess():
    """CE1 (the sources' six points on a line, the crank turning): the exact four-bar is found."""
    result = synthesize(FOUR_BAR, LINE, constraints=Constraints(crank=True), budget=30, seed=0, starts=sampled_starts,
                         underdetermined=True)  # (12 equations, 15 unknowns: the points' inputs among them)
    assert result.relative_rms < 1e-12 and result.met


def test_the_closed_path_of_models_is_met_within_a_10_second_budget():
    points = np.loadtxt(ROOT / "models" / "dimension_closed_path.csv", delimiter=",", skiprows=1)
    result = synthesize(FOUR_BAR, PathTarget(points), constraints=Constraints(crank=True), budget=10, seed=0,
                        starts=sampled_starts)
    assert result.relative_max < 1e-6 and result.met
