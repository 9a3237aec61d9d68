"""An answer stalled by a link-length order on a target with fewer equations than unknowns slides along the
exact answers into the order (``_Search.slide``): CE1 as its sources state it (six points on a line, 12
equations for 15 unknowns, r2 <= r3 <= r4 <= r1), seed 5's polish with r4 = r1 binding, where the constrained
polish does not move — re-checked by the motion layer (benchmarks/DIMENSION.md, *CE1 as stated within 30 CPU s*)."""

from __future__ import annotations

import numpy as np

from synth.dimension import PathTarget
from synth.dimension._problem import MARGIN
from synth.dimension._search import EXACT, _Evaluate, _problem, _Search, _Watch
from synth.motion import Linkage, assemble

from .test_order_polish import LINE, ORDERED, lengths
from .test_synthesize import FOUR_BAR

# seed 5's second polish of CE1 as stated (30 CPU s, the code before the slide): its points' sum of squares
# 1.65e-8 (mean squared relative error) with the rocker on the frame's length (held 1e-10 inside the order)
STALLED = Linkage(FOUR_BAR, (0,), [[52.45672981350671, 2.475952838399852], [92.15359052731397, 40.92292770740325],
                                   [68.48700512613242, -4.298146776817177], [39.23548784370277, 24.99543466767009]],
                  tracers={"P": (2, (20.000075465114826, 20.0000106238019))})
STEPS = [0.8768736815480577, 0.40478938375061185, 0.33957905063526916, 0.30482554192886463, 0.2839171773748898]
DIRECTION = -1  # (the crank passes the points clockwise)


def _search():
    problem, _ = _problem(FOUR_BAR, PathTarget(np.array(LINE, dtype=float)), None, ORDERED)
    return _Search(_Evaluate(problem), problem, _Watch(60.0, None)), problem


def _points_error(search, z) -> float:
    r = search.evaluate.vector(z, DIRECTION)[:search.problem.points * 2]
    return float(r @ r)


def test_a_stalled_ordered_answer_slides_into_the_order_exactly():
    search, problem = _search()
    z = np.concatenate((problem.unknowns_of(STALLED), STEPS))
    assert 1e-8 < _points_error(search, z) < 1e-7  # where the polish stalled
    assert problem.order_gaps(STALLED)[-1] > -1e-9  # r4 = r1
    cost, slid = search.slide(z, DIRECTION)
    assert cost <= EXACT ** 2  # the search's own cost, the orders' penalty rows included: met exactly
    linkage = problem.linkage(slid[:problem.dims])
    assert (problem.order_gaps(linkage) <= -MARGIN).all()  # inside the order, beyond the search's margin
    r1, r2, r3, r4 = lengths(linkage)
    assert r2 < r3 < r4 < r1
    # the motion layer moves the slid linkage through the points, one turn at most, the crank turning
    inputs = linkage.pose_inputs[0] + DIRECTION * np.concatenate(([0.0], np.cumsum(slid[problem.dims:])))
    again = np.array([assemble(linkage, float(v)).tracers["P"][1] for v in inputs])
    assert np.abs(again - np.array(LINE)).max() <= 1e-9 * problem.scale
    assert abs(inputs[-1] - inputs[0]) < 2 * np.pi


def test_the_constrained_polish_alone_stays_where_the_order_stalled_it():
    search, problem = _search()
    z = np.concatenate((problem.unknowns_of(STALLED), STEPS))
    found = search.constrained(z, DIRECTION)
    assert found is None or _points_error(search, found[1]) > 1e-9  # not met: the slide is what meets it


# differential evolution's first candidate polished on CE1 as stated, seed 4 (the searched unknowns: the two pivots
# pinned at (0, 0) and (1, 0), then the crank pin and the coupler-rocker pin, over the target's size): its least
# squares crawled on the hinge of two binding orders, 15 100 evaluations (the polish 14 CPU s) for 1.5091e-4
CRAWLING = [0.0, 0.0, 1.0, 0.0, 0.8972490188743212, 0.09197679791177116, 1.4214973811664606, 0.876571528562458]


def test_a_least_squares_crawling_under_an_order_is_stopped():
    search, problem = _search()
    cost, _ = search.polish(np.array(CRAWLING))
    assert search.watch.count < 5_000  # the least squares' evaluations: 2 379 with the stop, 15 100 without
    assert cost < 1.6e-4  # where the crawl was going: the stop gives up 0.05 % of it
