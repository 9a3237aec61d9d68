"""The sampled starts' polishes that end with two target points on one input (issue 40, the reliability
runs' seed 13): such a polish sits in a corner of the in-order matching, not at a fit of the curve, and is
not counted among the starts polished before differential evolution — the next start is polished instead."""

from __future__ import annotations

import numpy as np

from synth.dimension import Constraints, PathTarget
from synth.dimension._search import SAMPLED_STARTS, _Evaluate, _problem, _Search, _Watch
from synth.motion import sweep

from .test_synthesize import FOUR_BAR, random_crank_rocker


def search_and_starts():
    original = random_crank_rocker(13)
    target = PathTarget(sweep(original, steps=11).tracers["P"][:10])
    problem, _ = _problem(FOUR_BAR, target, None, Constraints())
    starts = [random_crank_rocker(seed) for seed in range(20, 32)]  # twelve other crank-rockers
    return _Search(_Evaluate(problem), problem, _Watch(1e9, None)), starts


def canned_polishes(search, folding: int) -> list:
    """Replace the search's polish by one that records its starts and answers the first ``folding`` with the
    first two points on one input (error 1e-4), the rest with every step 0.3 rad (error 1e-5)."""
    polished = []
    dims, steps = search.problem.dims, search.problem.points - 1

    def polish(x, grace=False, until=None):
        polished.append(np.array(x))
        z = np.concatenate((x[:dims], np.full(steps, 0.3)))
        if len(polished) <= folding:
            z[dims] = 0.0
        cost = 1e-4 if len(polished) <= folding else 1e-5
        if search.best is None or cost < search.best[0]:
            search.best = (cost, z, 1)
        return cost, z

    search.polish = polish
    return polished


def test_a_polish_that_folds_two_points_onto_one_input_is_told_apart():
    search, _ = search_and_starts()
    dims, steps = search.problem.dims, search.problem.points - 1
    spread = np.concatenate((np.zeros(dims), np.full(steps, 0.3)))
    folded = spread.copy()
    folded[dims + 4] = 0.0
    assert not search.folded((1e-4, spread)) and search.folded((1e-4, folded))
    assert not search.folded((1e-30, folded))  # an exact answer is an answer, wherever its points lie
    timed, _ = _problem(FOUR_BAR, PathTarget(search.problem.target.points, np.linspace(0, 3, 10)), None, Constraints())
    assert not _Search(_Evaluate(timed), timed, _Watch(1e9, None)).folded((1e-4, np.zeros(timed.dims)))


def test_the_sampled_starts_go_on_past_the_folded_polishes():
    """Six folded polishes do not count: the five counted are the next five starts, eleven polished in all
    (the best then going on, a twelfth); none folded, five are polished and the best goes on."""
    for folding, want in ((6, 6 + SAMPLED_STARTS), (0, SAMPLED_STARTS)):
        search, starts = search_and_starts()
        polished = canned_polishes(search, folding)
        search.from_samples(lambda *_: starts, 0)
        assert len(polished) == want + 1, folding
        assert len({tuple(np.round(x[:search.problem.searched], 12)) for x in polished[:-1]}) == want  # all distinct
        assert search.best[0] == (1e-5 if want > folding else 1e-4)
