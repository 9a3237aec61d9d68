"""The global stage judges a path's candidate where the best similarity places it, with the best tracer
point on its link: a mechanism that traces the target, turned, scaled and shifted anywhere, is judged as
the mechanism itself, and the placed mechanism it returns traces the target (checked by the motion
layer's own assembly)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, PathTarget
from synth.dimension._problem import placement
from synth.dimension._search import _Evaluate, _problem
from synth.motion import Linkage, assemble, sweep

from .test_synthesize import FOUR_BAR, SLIDER_CRANK, random_crank_rocker

#: turns, scales and shifts (over the target's size) a mechanism is carried by before it is judged
PLACEMENTS = [0.6 * np.exp(0.7j) + 0j, 1.8 * np.exp(-2.5j), 1.0 + 0j]
SHIFTS = [0.3 - 0.2j, -0.4 + 0.1j, 0.5 + 0.5j]


def _moved(linkage: Linkage, lam: complex, shift: complex, scale: float) -> Linkage:
    """The linkage carried by z ↦ λz + s·scale (positions, tracer and slide directions): an
    independent construction of what the search's placement undoes."""
    def carry(p):
        z = lam * complex(*p) + shift * scale
        return (z.real, z.imag)

    turn = math.atan2(lam.imag, lam.real)
    slides = {k: (math.cos(math.atan2(u[1], u[0]) + turn), math.sin(math.atan2(u[1], u[0]) + turn))
              for k, u in linkage.slides.items()}
    link, at = linkage.tracers["P"]
    return Linkage(linkage.mechanism, linkage.inputs, [carry(p) for p in linkage.points], slides,
                   tracers={"P": (link, carry(at))})


def test_the_placement_of_a_link_and_its_point_is_found_in_closed_form():
    """The link turned by θᵢ and moved by mᵢ carries its point q to e^{iθᵢ}q + mᵢ; the mechanism carried
    by z ↦ λz + s then passes e^{iθᵢ}q' + λmᵢ + s (q' = λq + s − s): all three found again exactly."""
    rng = np.random.default_rng(0)
    theta, moves = rng.uniform(0, 6, 7), rng.normal(size=7) + 1j * rng.normal(size=7)
    q, lam, shift = 0.4 - 1.1j, 1.3 * np.exp(2.1j), -0.7 + 0.2j
    found = placement(np.exp(1j * theta), moves, np.exp(1j * theta) * q + lam * moves + shift)
    assert np.abs(np.array(found) - [q, lam, shift]).max() < 1e-12
    # a link turning about a fixed point (no translation): the mechanism stays, only q is fitted
    assert placement(np.exp(1j * theta), 0 * moves, np.exp(1j * theta) * q) == pytest.approx((q, 1, 0), abs=1e-12)


@pytest.mark.parametrize("which", range(3))
def test_a_timed_four_bar_is_judged_exact_wherever_it_is_placed(which):
    original = random_crank_rocker(7)
    motion = sweep(original, steps=7, stop=float(original.pose_inputs[0]) + math.radians(240))
    target = PathTarget(motion.tracers["P"], motion.inputs[:, 0])
    problem, _ = _problem(FOUR_BAR, target, None, Constraints(reach=8))
    evaluate = _Evaluate(problem)
    elsewhere = _moved(original, PLACEMENTS[which], SHIFTS[which], problem.scale)
    searched = problem.unknowns_of(elsewhere)[:problem.searched]  # the tracer point is not searched
    assert evaluate(searched) < 1e-24
    placed = problem.linkage(evaluate.complete(searched))
    for value, want in zip(target.inputs - target.inputs[0] + placed.pose_inputs[0], target.points):
        assert math.dist(assemble(placed, float(value)).tracers["P"][1], want) < 1e-9 * target.size


def test_a_timed_slider_crank_is_placed_with_its_slide_turned():
    original = Linkage(SLIDER_CRANK, (0,), [[0, 0], [3.0, 0.4], [0.6, 0.8], [3.0, 0.4]], {1: (1.0, 0.0)},
                       tracers={"P": (2, (1.5, 1.6))})
    motion = sweep(original, steps=8, stop=float(original.pose_inputs[0]) + math.radians(300))
    target = PathTarget(motion.tracers["P"], motion.inputs[:, 0])
    problem, _ = _problem(SLIDER_CRANK, target, None, Constraints(reach=8))
    evaluate = _Evaluate(problem)
    searched = problem.unknowns_of(_moved(original, PLACEMENTS[0], SHIFTS[0], problem.scale))[:problem.searched]
    assert evaluate(searched) < 1e-24
    placed = problem.linkage(evaluate.complete(searched))
    assert abs(placed.slides[1][1]) < 1e-9  # the slide is horizontal again, as the original's


@pytest.mark.parametrize("which", range(3))
def test_an_untimed_four_bar_placed_anywhere_is_carried_back_onto_its_points(which):
    # seed 1: its points lie on the curve's samples (every 36° of the crank, samples every 3°), so the fit
    # of the places, the placement and the tracer point (closest points, then Gauss-Newton steps) is exact
    original = random_crank_rocker(1)
    target = PathTarget(sweep(original, steps=11).tracers["P"][:10])
    problem, _ = _problem(FOUR_BAR, target, None, Constraints(reach=8))
    evaluate = _Evaluate(problem)
    truth = problem.unknowns_of(original)
    assert evaluate(truth) < 1e-24  # the points lie on the sampled curve: matched exactly where it stands
    cost, _, offsets, placed = evaluate.untimed(problem.unknowns_of(
        _moved(original, PLACEMENTS[which], SHIFTS[which], problem.scale)))
    assert cost < 1e-24 and np.abs(placed - truth).max() < 1e-9
    assert np.abs(offsets - math.radians(36) * np.arange(1, 10)).max() < 1e-9
    lk = problem.linkage(placed)
    traced = np.array([assemble(lk, float(lk.pose_inputs[0] + v)).tracers["P"][1]
                       for v in offsets])
    assert np.abs(traced - target.points[1:]).max() < 1e-9 * target.size


def test_an_untimed_four_bar_is_found_from_its_shape_alone():
    """The searched unknowns leave the tracer point out: from the mechanism's joints alone (its tracer
    point first guessed at the middle of the coupler) the fit finds the tracer point and the placement."""
    original = random_crank_rocker(1)
    target = PathTarget(sweep(original, steps=11).tracers["P"][:10])
    problem, _ = _problem(FOUR_BAR, target, None, Constraints(reach=8))
    evaluate = _Evaluate(problem)
    truth = problem.unknowns_of(original)
    searched = problem.unknowns_of(_moved(original, PLACEMENTS[1], SHIFTS[1], problem.scale))[:problem.searched]
    assert len(searched) == problem.dims - 2
    assert evaluate(searched) < 1e-24 and np.abs(evaluate.complete(searched) - truth).max() < 1e-9
