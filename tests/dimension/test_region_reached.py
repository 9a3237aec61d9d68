"""A region of the fixed pivots no link within the length bound can join to the search box is refused at once
(it used to spend the whole budget, then say that no mechanism was found), and a region a function's gauge
ignores is refused too."""

from __future__ import annotations

import math

import pytest

from synth.dimension import Constraints, FunctionTarget, PathTarget, synthesize
from synth.dimension._problem import Problem
from synth.errors import DimensionError
from synth.structure.chain import Chain, Mechanism
from tests.refusals import refused

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)
SLIDER_CRANK = Mechanism(Chain.parse("0-1 1-2 2-3 0=3"), 0)
# centre (2.5, 3), size 5: with the default reach of 4 sizes every moving joint is sought within x −17.5 … 22.5,
# y −17 … 23
PATH = PathTarget([[1, 1], [4, 1], [4, 5]])


@pytest.mark.parametrize("region, gap", [((25.5, 30, 0, 1), 3.0),        # 3 beyond the box's right side
                                         ((25.5, 30, 27, 30), 5.0),      # beyond its corner (22.5, 23): 3, 4, 5
                                         ((-30, -20.5, -40, -21), 5.0)])  # beyond (−17.5, −17) the other way
def test_a_region_farther_from_the_box_than_the_length_bound_is_refused_and_nearer_is_kept(region, gap):
    for mechanism in (FOUR_BAR, SLIDER_CRANK):
        message = refused(DimensionError, Problem, mechanism, 0, PATH, None,
                          Constraints(pivots=region, max_length=gap * 0.999))
        assert message.startswith(f"the pivots' region x {region[0]:g}..{region[1]:g}, y {region[2]:g}..{region[3]:g} "
                                  f"lies {gap:.4g} from every place a moving joint is sought (within 4 target sizes, 20")
        assert "beyond the link-length bound" in message and "nearer the target" in message
        # a link of the bound's length reaches from the region's nearest corner to the box: not refused
        Problem(mechanism, 0, PATH, None, Constraints(pivots=region, max_length=gap * 1.001))
    # without a length bound any region may be joined to the box (the links as long as they must be)
    Problem(FOUR_BAR, 0, PATH, None, Constraints(pivots=region))
    # a larger reach brings the box to the region
    Problem(FOUR_BAR, 0, PATH, None, Constraints(pivots=region, max_length=gap * 0.999, reach=5))


def test_the_refusal_comes_before_any_search():
    """synthesize refuses it as it refuses a contradiction: before any candidate (a budget of a day is not spent)."""
    far = Constraints(pivots=(1000, 1010, 1000, 1010), max_length=50)
    with pytest.raises(DimensionError, match="beyond the link-length bound 50"):
        synthesize(FOUR_BAR, PATH, constraints=far, budget=86400)


def test_a_function_takes_no_region_of_pivots():
    target = FunctionTarget([math.radians(a) for a in (35, 55, 75)], [math.radians(a) for a in (60, 72, 85)])
    message = refused(DimensionError, Problem, FOUR_BAR, 0, target, None, Constraints(pivots=(5, 6, 5, 6)))
    assert "a pivots' region" in message and "do not apply" in message
