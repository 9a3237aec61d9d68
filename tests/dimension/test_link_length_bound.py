"""The bound on link lengths (``Constraints(max_length=L)``, ``--max-length``): a random crank-rocker's
ten untimed points, found exactly when the bound lies above its longest link; under a bound 20 % below
that link every link of the answer keeps to the bound and the error is above 0 (the best linkage under
that bound has its longest link well inside it, 1.71 against 2.22: a bound that excludes the exact answer
need not be met with equality)."""

from __future__ import annotations

import numpy as np

from synth.atlas import sampled_starts
from synth.dimension import Constraints, PathTarget, synthesize
from synth.dimension._problem import link_lengths, longest_link
from synth.motion import sweep

from .test_synthesize import FOUR_BAR, random_crank_rocker

ORIGINAL = random_crank_rocker(0)  # frame 2.770, crank 0.818, coupler 2.541, rocker 2.017
TARGET = PathTarget(sweep(ORIGINAL, steps=11).tracers["P"][:10])


def test_the_longest_link_is_the_longest_distance_between_two_joints_of_a_link():
    lengths = ORIGINAL.lengths()  # a four-bar's links are binary: one distance each
    assert longest_link(ORIGINAL) == max(lengths.values())
    assert sorted(link_lengths(ORIGINAL)) == sorted(lengths.values())


def test_a_bound_that_does_not_bind_leaves_the_exact_answer():
    bound = 2 * longest_link(ORIGINAL)
    result = synthesize(FOUR_BAR, TARGET, constraints=Constraints(max_length=bound), budget=10, seed=0,
                        starts=sampled_starts)
    assert result.relative_max < 1e-9
    assert result.met and result.constraints["length"]["met"]
    assert result.constraints["length"]["value"] == longest_link(result.linkage) < bound


def test_a_bound_that_excludes_the_exact_answer_is_kept_by_every_link():
    bound = 0.8 * longest_link(ORIGINAL)
    result = synthesize(FOUR_BAR, TARGET, constraints=Constraints(max_length=bound), budget=10, seed=0,
                        starts=sampled_starts)
    longest = longest_link(result.linkage)
    assert result.met and result.constraints["length"] == {"value": longest, "limit": bound, "met": True}
    assert longest <= bound
    assert result.relative_max > 1e-4  # the exact answer is out of reach
    assert np.all(np.array(link_lengths(result.linkage)) <= bound)
