"""Motion generation from no guess: a random crank-rocker's coupler poses are met exactly from its dyads
(Burmester's circle and centre points; the global stage alone left two of five random four-bars' six poses 0.3–0.4 %
of their size off after the default 60 CPU s: benchmarks/DIMENSION.md, *Motion generation from no guess*)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import MotionTarget, PathTarget, synthesize
from synth.dimension._dyads import dyad_starts, dyads
from synth.motion import sweep
from synth.structure.chain import Chain, Mechanism

from ..oracles.motion import follow, oracle_of
from .test_synthesize import FOUR_BAR, random_crank_rocker  # joints 0-1, 0-3, 1-2, 2-3


def coupler_poses(linkage, count: int, span_deg: float = 200.0) -> MotionTarget:
    """The coupler's poses (its point P and the angle of its pins' line 1-2 → 2-3) as the crank turns."""
    motion = sweep(linkage, steps=count, stop=float(linkage.pose_inputs[0]) + math.radians(span_deg))
    pins = np.asarray(motion.joints)[:, 3] - np.asarray(motion.joints)[:, 2]
    return MotionTarget(np.column_stack((motion.tracers["P"], np.arctan2(pins[:, 1], pins[:, 0]))))


def test_the_dyads_of_a_four_bars_coupler_poses_are_its_crank_and_rocker():
    made = random_crank_rocker(11)
    target = coupler_poses(made, 6)
    found = dyads(target)
    first, turn = target.poses[0, :2], target.poses[0, 2]
    for pin, pivot in ((2, 0), (3, 1)):  # the crank's pin on its pivot (0, 0), the rocker's on (d, 0)
        errors = [e for e, m, f in found if np.allclose(first + m, made.points[pin], atol=1e-9)
                  and np.allclose(f, made.points[pivot], atol=1e-9)]
        assert errors and errors[0] < 1e-12
    # six poses: no third dyad meets them (the next best is 6e-4 of the size off)
    assert sorted(e for e, _, _ in found)[2] > 1e-6
    assert turn == pytest.approx(math.atan2(*(made.points[3] - made.points[2])[::-1]))


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("count", [5, 6, 8])
def test_a_random_four_bars_coupler_poses_are_met_exactly_from_no_guess(seed, count):
    made = random_crank_rocker(seed)
    target = coupler_poses(made, count)
    result = synthesize(FOUR_BAR, target, seed=seed)  # the default budget: met in a fraction of a CPU second
    assert result.relative_max < 1e-9 and result.angle_errors.max() < 1e-9, (result.relative_max, result.method)
    assert result.method.startswith("the target's dyads + bounded least squares") and result.met
    # re-checked by the independent reference solver: the found linkage moved to the reported inputs passes
    # every pose (P's place and the coupler's turn from the first pose)
    lk = result.linkage
    moved = follow(oracle_of(lk, tracers=True), np.asarray(result.inputs) - float(lk.pose_inputs[0]), math.radians(1))
    pins = moved[:, 3] - moved[:, 2]
    turns = np.unwrap(np.arctan2(pins[:, 1], pins[:, 0]))
    assert np.abs(moved[:, 4] - target.points).max() < 1e-9 * target.size
    want = target.poses[:, 2] - target.poses[0, 2]
    assert np.abs(np.angle(np.exp(1j * ((turns - turns[0]) - want)))).max() < 1e-9


def test_dyad_starts_are_only_for_a_motion_of_a_link_guided_by_a_four_link_loop():
    made = random_crank_rocker(0)
    target = coupler_poses(made, 6)
    assert dyad_starts(FOUR_BAR, 2, target)
    assert dyad_starts(FOUR_BAR, 2, PathTarget(target.points)) == []
    assert dyad_starts(FOUR_BAR, 1, target) == []  # the crank is pivoted on the frame: no dyad to it
    watt = Mechanism(Chain.parse("0-1 0-2 1-3 2-3 2-4 3-5 4-5"), 0, 1)
    assert dyad_starts(watt, 3, target)  # the coupler of its four-bar 0-1-3-2
    assert dyad_starts(watt, 5, target) == dyad_starts(watt, 4, target) == []  # the links of its dyad 4-5
    stephenson = Mechanism(Chain.parse("0-1 0-3 0-5 1-2 2-3 2-4 4-5"), 0, 1)  # the four-bar 0-1-2-3, the dyad 4-5
    assert dyad_starts(stephenson, 2, target) and dyad_starts(stephenson, 4, target) == []
    slider_crank = Mechanism(Chain.parse("0-1 1-2 2-3 3=0"), 0)  # its RP dyad: tests/dimension/test_motion_slider_dyads.py
    assert dyad_starts(slider_crank, 2, target)
    assert dyad_starts(Mechanism(Chain.parse("0-1 1-2 2=3 3-0"), 0), 2, target) == []  # the rod slides in a block


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("count", [6, 8])
@pytest.mark.parametrize("six_bar", ["watt", "stephenson"])
def test_a_six_bars_coupler_poses_are_met_exactly_from_its_four_bars_dyads(motion_poses, six_bar, seed, count):
    """A Watt's link 3 is the coupler of its four-bar 0-1-3-2, a Stephenson's link 2 of its four-bar 0-1-2-3, which
    alone guides it (the dyad 4-5 follows): that four-bar from the target's dyads, the dyad's joints placed at random,
    is polished to the poses."""
    mechanism, drawn = motion_poses.DRAWN[six_bar]
    made = drawn(seed)
    target = motion_poses.poses(made, count, 200.0)
    result = synthesize(mechanism, target, seed=seed, underdetermined=count < 8)  # 8 poses: 24 equations, 23 unknowns
    assert result.relative_max < 1e-9 and result.angle_errors.max() < 1e-9, (result.relative_max, result.method)
    assert result.method.startswith("the target's dyads + bounded least squares") and result.met
    lk = result.linkage  # re-checked by the reference solver: P and the turn of the line of the coupler's two pins
    moved = follow(oracle_of(lk, tracers=True), np.asarray(result.inputs) - float(lk.pose_inputs[0]), math.radians(1))
    assert np.abs(moved[:, 7] - target.points).max() < 1e-9 * target.size
    first, second = [k for k, j in enumerate(lk.chain.joints) if made.tracers["P"][0] in j][:2]
    pins = moved[:, second] - moved[:, first]
    turns = np.unwrap(np.arctan2(pins[:, 1], pins[:, 0]))
    want = target.poses[:, 2] - target.poses[0, 2]
    assert np.abs(np.angle(np.exp(1j * ((turns - turns[0]) - want)))).max() < 1e-9
