"""A dead position between the samples of a crank's turn (issue 40): the search looks into each sampled
minimum of the dyads' discriminant that may hide one, so a four-bar on the verge of Grashof's condition
whose crank in truth rocks is not taken for a crank (Kunjur and Krishnamurty's eighteen points ended with
such an answer: its dead positions 0.17° apart, between two samples 5° apart)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, PathTarget
from synth.dimension._problem import TURN_SAMPLES
from synth.dimension._search import _Evaluate, _problem
from synth.motion import Linkage, link_poses, motion_range, sweep
from synth.structure.chain import Chain, Mechanism

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)


def four_bar(frame: float, crank: float, coupler: float, rocker: float, angle: float) -> Linkage:
    """A four-bar with its crank at ``angle`` (rad) from the frame line, the coupler point at the coupler's middle
    lifted by 0.5."""
    pin = crank * np.array([math.cos(angle), math.sin(angle)])
    pivot = np.array([frame, 0.0])
    d = float(np.hypot(*(pivot - pin)))
    along = (coupler ** 2 - rocker ** 2 + d * d) / (2 * d)
    u = (pivot - pin) / d
    far = pin + along * u + math.sqrt(coupler ** 2 - along ** 2) * np.array([-u[1], u[0]])
    point = (pin + far) / 2 + 0.5 * np.array([-u[1], u[0]])
    return Linkage(FOUR_BAR, (0,), [[0, 0], pivot, pin, far], tracers={"P": (2, tuple(point))})


#: frame 3, crank 1, coupler 4.001, rocker 2: 1 + 4.001 > 3 + 2 by 0.001, so the crank cannot pass within 2.1° of
#: the frame line (where the crank pin comes nearer the rocker's pivot than 4.001 − 2); posed at 92.5°, the turn's
#: samples every 5° from the pose fall 2.5° either side of that line
NEAR_GRASHOF = four_bar(3.0, 1.0, 4.001, 2.0, math.radians(92.5))


def test_the_near_grashof_four_bar_rocks_and_its_turn_samples_all_close():
    """The premise, by the motion layer and by the samples the search took before: the crank rocks (its dead
    positions 4.2° apart), yet its dyad closes at every one of the 72 samples of a turn from the pose."""
    reach = motion_range(NEAR_GRASHOF)
    assert not reach.full_rotation
    lo, hi = reach.limits
    assert 2 * math.pi - (hi - lo) == pytest.approx(math.radians(4.2), abs=math.radians(0.1))
    g = link_poses(NEAR_GRASHOF, np.linspace(0, 2 * math.pi, TURN_SAMPLES, endpoint=False)).discriminants
    assert (g >= 0).all()


def test_a_timed_candidate_whose_crank_rocks_between_samples_is_infeasible():
    """Asked for a crank, the near-Grashof four-bar's own timed points (over 90° of its turn, away from the dead
    positions) are met exactly, but the candidate is refused: the search's cost is above INFEASIBLE, as the motion
    layer's verdict says; the same four-bar without the crank condition costs nothing."""
    motion = sweep(NEAR_GRASHOF, steps=6, start=float(NEAR_GRASHOF.pose_inputs[0]),
                   stop=float(NEAR_GRASHOF.pose_inputs[0]) + math.radians(90))
    target = PathTarget(motion.tracers["P"], motion.inputs[:, 0])
    free, _ = _problem(NEAR_GRASHOF, target, None, Constraints())
    assert _Evaluate(free)(free.unknowns_of(NEAR_GRASHOF)) == pytest.approx(0.0, abs=1e-20)
    crank, _ = _problem(NEAR_GRASHOF, target, None, Constraints(crank=True))
    evaluate = _Evaluate(crank)
    assert isinstance(evaluate.timed(crank.unknowns_of(NEAR_GRASHOF)), float)
    vector = evaluate.vector(crank.unknowns_of(NEAR_GRASHOF), 0)
    assert np.all(vector == vector[0]) and vector[0] > 0


def test_an_untimed_candidate_whose_crank_rocks_between_samples_has_no_full_turn():
    """Untimed, the global stage's curve of the near-Grashof four-bar stops at its dead positions (it is traced
    neither way over a full turn, so the crank condition skips it), and the polish's residual vector is the
    constant of a candidate that does not close."""
    points = sweep(NEAR_GRASHOF, steps=8, start=float(NEAR_GRASHOF.pose_inputs[0]),
                   stop=float(NEAR_GRASHOF.pose_inputs[0]) + math.radians(120)).tracers["P"]
    problem, _ = _problem(NEAR_GRASHOF, PathTarget(points), None, Constraints(crank=True))
    evaluate = _Evaluate(problem)
    x = problem.unknowns_of(NEAR_GRASHOF)
    _, ways = evaluate.curve(x)
    span = [float(xs[-1] - xs[0]) * d for d, (_, xs, _, _) in ways.items()]
    assert max(span) < 2 * math.pi - math.radians(4)
    assert evaluate(x[:problem.searched]) >= 1.0  # no direction left: the cost of a curve that cannot be met
    steps = np.full(len(points) - 1, math.radians(15))
    vector = evaluate.vector(np.concatenate((x, steps)), 1)
    assert np.all(vector == vector[0]) and vector[0] > 0


@pytest.mark.parametrize("margin", [1e-2, 1e-4])
def test_a_crank_just_inside_grashof_is_kept(margin):
    """Just inside Grashof's condition (coupler 4 − margin) the crank turns fully (the motion layer says so) and
    the search agrees at every sample and between them: the look between samples refuses no true crank."""
    linkage = four_bar(3.0, 1.0, 4.0 - margin, 2.0, math.radians(92.5))
    assert motion_range(linkage).full_rotation
    phi0 = float(linkage.pose_inputs[0])
    motion = sweep(linkage, steps=6, start=phi0, stop=phi0 + math.radians(90))
    problem, _ = _problem(linkage, PathTarget(motion.tracers["P"], motion.inputs[:, 0]), None, Constraints(crank=True))
    out = _Evaluate(problem).timed(problem.unknowns_of(linkage))
    assert not isinstance(out, float) and float(out[0] @ out[0]) == pytest.approx(0.0, abs=1e-20)


def test_the_least_discriminant_between_samples_is_found_to_rounding():
    """Problem.dips against a dense sweep (720 001 inputs): on a crank just inside Grashof's condition the least
    discriminant it finds between two samples is the dense sweep's least to 1e-9, and positive."""
    linkage = four_bar(3.0, 1.0, 3.999, 2.0, math.radians(92.5))
    problem, _ = _problem(linkage, PathTarget(np.eye(2)), None, Constraints(crank=True))
    xs = np.linspace(-2 * math.pi / TURN_SAMPLES, 2 * math.pi, TURN_SAMPLES + 2)
    _, _, g, _ = problem.poses(linkage, xs)
    found = problem.dips(linkage, xs, g)
    _, _, dense, _ = problem.poses(linkage, np.linspace(0, 2 * math.pi, 720_001))
    assert found.min() < g.min()
    assert found.min() == pytest.approx(dense.min(), abs=1e-9) and found.min() > 0
