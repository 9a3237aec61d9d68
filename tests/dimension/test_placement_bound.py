"""The global stage places a path's candidate by its best similarity; under a length bound the placement's
scale is at most what the bound allows (``placement(..., most=)``), and the bound is measured where the
candidate is placed.  Before, a timed candidate's bound was measured where differential evolution drew it
(any size), so the search chased shapes that fit only beyond the bound (benchmarks/DIMENSION.md, *The half
circle at the default budget*)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from synth.dimension import Constraints, PathTarget
from synth.dimension._problem import longest_link, placement
from synth.dimension._search import _Evaluate, _problem
from synth.motion import Linkage

from .test_synthesize import FOUR_BAR

ROOT = Path(__file__).resolve().parents[2]


def _scanned(turn, moves, w, most, pivot, turns):
    """The least squared misfit over λ on the bound, by a scan of its angle (or, λ real, its one value) with q and s
    fitted by numpy's least squares at each: an independent check of the closed form."""
    lams = most * np.exp(1j * np.linspace(0, 2 * math.pi, 20_001)) if turns else [most + 0j]
    best = math.inf
    for lam in lams:
        if pivot is None:
            a, b = np.column_stack((turn, np.ones(len(w)))), w - lam * moves
        else:
            a, b = turn[:, None], w - pivot - lam * (moves - pivot)
        coef, *_ = np.linalg.lstsq(a, b, rcond=None)
        best = min(best, float(np.sum(np.abs(a @ coef - b) ** 2)))
    return best


@pytest.mark.parametrize("pivot, turns", [(None, True), (0.3 - 0.4j, True), (0.3 - 0.4j, False)])
def test_a_bounded_placement_is_the_best_at_the_largest_scale(pivot, turns):
    rng = np.random.default_rng(3)
    theta, moves = rng.uniform(0, 6, 8), rng.normal(size=8) + 1j * rng.normal(size=8)
    lam = 2.0 * (np.exp(0.9j) if turns else 1.0)
    w = np.exp(1j * theta) * (0.5 + 0.2j) + lam * moves + (0.1 + 0.7j) + 0.05 * rng.normal(size=8)
    if pivot is not None:
        w = w - (0.1 + 0.7j) + pivot * (1 - lam)
    free = placement(np.exp(1j * theta), moves, w, pivot=pivot, turns=turns)
    assert abs(free[1]) > 1.5  # the free fit is larger than the bound below
    q, found, shift = placement(np.exp(1j * theta), moves, w, pivot=pivot, turns=turns, most=1.5)
    assert abs(found) == pytest.approx(1.5, rel=1e-12) and (turns or found.imag == 0)
    misfit = float(np.sum(np.abs(np.exp(1j * theta) * q + found * moves + shift - w) ** 2))
    assert misfit <= _scanned(np.exp(1j * theta), moves, w, 1.5, pivot, turns) * (1 + 1e-9)
    if pivot is not None:
        assert shift == pytest.approx(pivot * (1 - found), abs=1e-12)
    # a bound the free fit keeps changes nothing
    assert placement(np.exp(1j * theta), moves, w, pivot=pivot, turns=turns, most=abs(free[1]) * 1.01) == free


def test_the_half_circles_record_is_judged_at_its_error_within_the_bound():
    """The record's answer of dim11a (the bound of 50 on its frame and rocker), shrunk to half its size as
    differential evolution may draw it: placed, it stands on the bound (1e-4 inside) and is judged at its own error; before,
    its best fit placed it at a longest link of 52.8 and judged it there (a sum of 1.206, below what the bound
    allows)."""
    log = ROOT / "benchmarks" / "logs" / "dimension_half_circle_dim11a_seeds_0_4_120s.jsonl"
    row = json.loads(log.read_text().splitlines()[0])
    assert row["sum_squared_error"] < 1.2163
    answer = Linkage.from_dict(row["linkage"])
    points = [(0, 0), (1.9098, 5.8779), (6.9098, 9.5106), (13.09, 9.5106), (18.09, 5.8779), (20, 0)]
    target = PathTarget(np.array(points, dtype=float), np.radians([30.0, 60, 90, 120, 150, 180]))
    constraints = Constraints(crank=True, max_length=50.0, timing="absolute", order=("r2<=r1", "r2<=r3", "r2<=r4"))
    problem, _ = _problem(FOUR_BAR, target, None, constraints)
    evaluate = _Evaluate(problem)
    shrunk = 0.5 * problem.unknowns_of(answer)[:problem.searched]  # (about the target's centre)
    placed = problem.linkage(evaluate.complete(shrunk))
    assert longest_link(placed) == pytest.approx(50.0 * (1 - 1e-4), rel=1e-9)
    residuals, _, _ = evaluate.timed(shrunk)  # (its cost adds the orders' penalty: they aim 1e-4 inside)
    assert float(residuals @ residuals) * problem.scale ** 2 == pytest.approx(row["sum_squared_error"], rel=1e-4)
