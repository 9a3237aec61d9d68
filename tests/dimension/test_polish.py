"""The polish of an untimed target and where it starts: its Jacobian, built from one evaluation per
dimension and one for all the input steps, is the full finite-difference Jacobian (one evaluation per
unknown); from no guess, the starts sampled from the mechanism's own crank curves
(``synth.atlas.sampled_starts``), each with its tracer point fitted, find a random crank-rocker's ten
untimed points exactly within seconds."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize._numdiff import approx_derivative

from synth.atlas import sampled_starts
from synth.dimension import Constraints, PathTarget, synthesize
from synth.dimension._search import _Evaluate, _problem, _Search, _Watch
from synth.motion import assemble, sweep

from .test_synthesize import FOUR_BAR, random_crank_rocker


@pytest.mark.parametrize("constraints", [Constraints(reach=8),
                                         Constraints(reach=8, min_transmission=math.radians(80), max_ratio=2.0),
                                         Constraints(reach=8, max_length=1.0)])
def test_the_untimed_jacobian_equals_the_full_finite_differences(constraints):
    original = random_crank_rocker(3)
    motion = sweep(original, steps=9, stop=float(original.pose_inputs[0]) + math.radians(300))
    target = PathTarget(motion.tracers["P"])
    problem, _ = _problem(FOUR_BAR, target, None, constraints)
    search = _Search(_Evaluate(problem), problem, _Watch(1e9, None))
    rng = np.random.default_rng(1)
    dims = problem.unknowns_of(original) + rng.normal(size=problem.dims) * 0.01  # off the answer: residuals ≠ 0
    steps = np.diff(motion.inputs[:, 0]) * rng.uniform(0.9, 1.1, size=len(target.points) - 1)
    z = np.concatenate((dims, steps))
    upper = np.concatenate((problem.upper, np.full(len(steps), problem.input_span)))

    def fun(x):
        return search.evaluate.vector(x, 1)

    if constraints.max_ratio is not None or constraints.max_length is not None:
        assert np.abs(fun(z)[2 * len(target.points):]).max() > 0  # the constraint rows are active
    fast = search.untimed_jacobian(fun, z, upper)
    full = approx_derivative(fun, z, method="3-point")  # every unknown on its own, central differences
    assert fast.shape == full.shape == (len(fun(z)), len(z))
    assert np.abs(fast - full).max() <= 1e-5 * np.abs(full).max()
    assert np.abs(full[:, problem.dims + 2]).max() > 0  # a later step moves the points after it
    calls = []

    def counted(x):
        calls.append(1)
        return fun(x)

    # the residuals at z, when the caller has them (SLSQP's gradient 2·Jᵀr), are not evaluated again, and central
    # differences, which do not use them, never evaluate them: one evaluation (two) per column built
    assert np.array_equal(search.untimed_jacobian(counted, z, upper, r0=fun(z)), fast)
    assert len(calls) == problem.dims + 1
    calls.clear()
    central = search.untimed_jacobian(counted, z, upper, central=True)
    assert len(calls) == 2 * (problem.dims + 1)
    assert np.abs(central - full).max() <= 1e-5 * np.abs(full).max()


@pytest.mark.parametrize("seed, budget", [(7, 30), (0, 30)])
def test_ten_untimed_points_of_a_random_crank_rocker_are_found_exactly_from_no_guess(seed, budget):
    # seed 7: before the sampled starts, differential evolution ended at 0.38 % of the target's size after
    # 30 CPU s; seed 0 (its coupler point farther from the coupler than the coupler is long, its points
    # unevenly spread): with the sampled starts but the tracer point searched, 3.0e-4 after 30 CPU s
    # (benchmarks/DIMENSION.md); with the tracer point fitted to each sample both within a few CPU s (seed 0's
    # budget is 30 for the share of it each sampled start's polish gets: 10 leaves it at 7e-5; seed 7's 10 CPU s
    # were once spent before its polish met the points under a load of 10, so it has 30 too: the search stops
    # as soon as the points are met, so the budget only bounds a failing run)
    original = random_crank_rocker(seed)
    target = PathTarget(sweep(original, steps=11).tracers["P"][:10])
    result = synthesize(FOUR_BAR, target, budget=budget, seed=seed, starts=sampled_starts)
    assert result.method.startswith("sampled crank curves")
    assert result.relative_max <= 1e-6 and result.met
    for value, want in zip(result.inputs, target.points):  # the motion layer's own assembly passes the points
        assert math.dist(assemble(result.linkage, float(value)).tracers["P"][1], want) <= 1e-6 * target.size
