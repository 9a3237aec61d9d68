"""The global stage judges a path's candidate where the best similarity places it: a mechanism that
traces the target, turned, scaled and shifted anywhere, is judged as the mechanism itself, and the
placed mechanism it returns traces the target (checked by the motion layer's own assembly)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, PathTarget
from synth.dimension._search import _Evaluate, _problem, similarity
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


def test_the_similarity_of_two_point_sets_is_found_in_closed_form():
    rng = np.random.default_rng(0)
    z = rng.normal(size=7) + 1j * rng.normal(size=7)
    lam, shift = 1.3 * np.exp(2.1j), -0.7 + 0.2j
    found = similarity(z, lam * z + shift)
    assert abs(found[0] - lam) < 1e-12 and abs(found[1] - shift) < 1e-12
    assert similarity(np.full(3, 1 + 1j), z[:3]) is None  # one point: no turn or scale


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
    original = random_crank_rocker(0)
    target = PathTarget(sweep(original, steps=11).tracers["P"][:10])
    problem, _ = _problem(FOUR_BAR, target, None, Constraints(reach=8))
    evaluate = _Evaluate(problem)
    truth = problem.unknowns_of(original)
    assert evaluate(truth) < 1e-24  # the points lie on the sampled curve: matched exactly where it stands
    cost, _, offsets, placed = evaluate.untimed(problem.unknowns_of(
        _moved(original, PLACEMENTS[which], SHIFTS[which], problem.scale)))
    # the iterated closest-point fit is as close as the curve's sampling lets it (points between samples)
    assert cost < 1e-5 and np.abs(placed - truth).max() < 0.02
    lk = problem.linkage(placed)
    traced = np.array([assemble(lk, float(lk.pose_inputs[0] + v)).tracers["P"][1]
                       for v in offsets])
    assert np.abs(traced - target.points[1:]).max() < 0.03 * target.size
