"""A linkage from any pose: the inputs and slides it guesses, each checked by hand, the refusals'
sentences, and the nudge off a locked pose (how far it moved the joints, said in its note)."""

import math

import numpy as np
import pytest

from synth.errors import BadPose, LockedMechanism
from synth.motion import linkage_from_pose, sweep
from synth.structure.chain import Chain, Mechanism

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1 0-3 1-2 2-3
#: a rigid triangle 0-1-2 and a four-bar 0-3-4-5 on one frame: W = 3·5 − 2·7 = 1, but the triangle cannot move
TRIANGLE_AND_FOUR_BAR = Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-0")  # joints 0-1 0-2 0-3 0-5 1-2 3-4 4-5
TRIANGLE_POINTS = [[0, 0], [2, 0], [3, 0], [6, 0], [1, 1], [3.5, 1.5], [5, 1.8]]


def test_positions_that_are_not_numbers_are_one_sentence_even_with_a_slider_to_guess():
    slider_crank = Mechanism(Chain.parse("0-1 1-2 2-3 0=3"), 0)  # joints 0-1 0=3 1-2 2-3
    for positions in ([["a", "b"], ["c", "d"], ["e", "f"], ["g", "h"]], [[0, 0], [1], [2, 2], [3, 3]]):
        with pytest.raises(BadPose) as exc:
            linkage_from_pose(slider_crank, positions)
        assert str(exc.value) == "the joint positions must be numbers, one [x, y] per joint"
    with pytest.raises(BadPose) as exc:
        linkage_from_pose(slider_crank, np.zeros((3, 2)))
    assert str(exc.value) == "the pose needs one [x, y] per joint (4), not an array of shape (3, 2)"


def test_the_inputs_guessed_are_the_frames_revolute_joints_first_one_per_link():
    assert linkage_from_pose(FOUR_BAR, [[0, 0], [4, 0], [1, 0], [3.5, 3]]).inputs == (0,)
    # the mechanism's input link chooses the joint of the frame that holds it
    assert linkage_from_pose(Mechanism(FOUR_BAR.chain, 0, 3), [[0, 0], [4, 0], [1, 0], [3.5, 3]]).inputs == (1,)
    # a slider on the frame numbered first: the revolute joint of the frame is still the input
    chain = Chain.parse("0=1 1-2 2-3 3-0")  # joints 0=1 0-3 1-2 2-3
    lk = linkage_from_pose(Mechanism(chain, 0), [[3, 0.5], [0, 0], [3, 0.5], [0.6, 0.8]])
    assert lk.inputs == (1,)
    # with the slider's link asked for, the slider is the input
    assert linkage_from_pose(Mechanism(chain, 0, 1), [[3, 0.5], [0, 0], [3, 0.5], [0.6, 0.8]]).inputs == (0,)
    # W = 2: the five-bar's two joints of the frame
    five_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0)  # joints 0-1 0-4 1-2 2-3 3-4
    assert linkage_from_pose(five_bar, [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]]).inputs == (0, 1)


def test_a_slide_guessed_points_from_the_slider_to_the_first_other_joint_away_from_it():
    # the slider 0=3 of a slider-crank: its links' other joints are 0-1 (link 0) and 2-3 (link 3);
    # 2-3 is at the slider's own point, so the slide points at the crank's pivot
    slider_crank = Mechanism(Chain.parse("0-1 1-2 2-3 0=3"), 0)  # joints 0-1 0=3 1-2 2-3
    lk = linkage_from_pose(slider_crank, [[0, 0], [3, 0.5], [0.6, 0.8], [3, 0.5]])
    assert lk.slides[1] == pytest.approx((-3 / math.hypot(3, 0.5), -0.5 / math.hypot(3, 0.5)), abs=1e-15)
    # the slider's point on the crank's pivot: the slide points at the other joint, 2-3
    u = (3 / math.hypot(3, 0.5), 0.5 / math.hypot(3, 0.5))
    assert linkage_from_pose(slider_crank, [[0, 0], [0, 0], [0.6, 0.8], [3, 0.5]]).slides[1] == \
        pytest.approx(u, abs=1e-15)
    # 1e-5 from the pivot in a mechanism of size 3 is away from it (more than 1e-6 of the size) ...
    assert linkage_from_pose(slider_crank, [[0, 0], [0, 1e-5], [0.6, 0.8], [3, 0.5]]).slides[1] == \
        pytest.approx((0.0, -1.0), abs=1e-12)
    # ... 1e-6 from it is at it
    assert linkage_from_pose(slider_crank, [[0, 0], [0, 1e-6], [0.6, 0.8], [3, 0.5]]).slides[1] == \
        pytest.approx(u, abs=1e-6)
    # away along x only: the slide points along x
    assert linkage_from_pose(slider_crank, [[1e-5, 0], [0, 0], [0.6, 0.8], [3, 0.5]]).slides[1] == \
        pytest.approx((1.0, 0.0), abs=1e-12)
    # exactly 1e-6 of the size (1) away is still at the point: the slide points at 2-3
    exact = linkage_from_pose(slider_crank, [[1e-6, 0], [0, 0], [0.6, 0.8], [1, 0.5]])
    assert exact.slides[1] == pytest.approx((1 / math.hypot(1, 0.5), 0.5 / math.hypot(1, 0.5)), abs=1e-12)
    # every other joint at the slider's point: no line to guess, the slide is along x
    alone = linkage_from_pose(slider_crank, [[0, 0], [0, 0], [0.6, 0.8], [0, 0]])
    assert alone.slides[1] == (1.0, 0.0)
    # given slides are kept
    assert linkage_from_pose(slider_crank, [[0, 0], [3, 0.5], [0.6, 0.8], [3, 0.5]], slides={1: (1, 0)}).slides == \
        {1: (1.0, 0.0)}


def test_a_locked_pose_is_refused_or_nudged_by_a_stated_distance():
    flat = [[0, 0], [4, 0], [1, 0], [2, 0]]  # coupler 2 and rocker 3 in line
    with pytest.raises(LockedMechanism) as exc:
        linkage_from_pose(FOUR_BAR, flat)
    assert str(exc.value) == "its loop-closure equations are singular there: links 2, 3 are aligned in a dead position"
    lk = linkage_from_pose(FOUR_BAR, flat, nudge=True, tracers={"P": (2, (1.5, 1))})
    shift = float(np.hypot(*(lk.points - np.array(flat, dtype=float)).T).max())
    assert 0 < shift <= 0.02 * 4 * math.sqrt(2) * 2  # up to 2 % of the size per coordinate, doubled after ten tries
    assert lk.note == ("the given pose is locked (its loop-closure equations are singular there: links 2, 3 are "
                       f"aligned in a dead position); the joints were moved by up to {shift:.3g} "
                       f"({shift / 4:.1%} of the mechanism's size) to a nearby pose that moves")
    assert lk.tracers == {"P": (2, (1.5, 1.0))} and lk.inputs == (0,)
    assert sweep(lk, steps=3).stopped is None or sweep(lk, steps=3).joints.shape == (3, 4, 2)
    # the nudge is drawn with a fixed seed: the same pose twice gives the same linkage
    assert np.array_equal(linkage_from_pose(FOUR_BAR, flat, nudge=True).points, lk.points)
    # a pose that moves is not nudged
    assert linkage_from_pose(FOUR_BAR, [[0, 0], [4, 0], [1, 0], [3.5, 3]], nudge=True).note is None


def test_a_chain_locked_everywhere_is_refused_after_the_nudges():
    mechanism = Mechanism(TRIANGLE_AND_FOUR_BAR, 0)
    why = ("its loop-closure equations are singular there (a group of links aligned in a dead position, or a "
           "locked sub-chain); input 0-1")
    with pytest.raises(LockedMechanism) as exc:
        linkage_from_pose(mechanism, TRIANGLE_POINTS)
    assert str(exc.value) == why
    with pytest.raises(LockedMechanism) as exc:
        linkage_from_pose(mechanism, TRIANGLE_POINTS, nudge=True)
    assert str(exc.value) == f"the pose is locked ({why}) and no nearby pose moves"
    # driven by the four-bar's crank it moves
    assert linkage_from_pose(Mechanism(TRIANGLE_AND_FOUR_BAR, 0, 3), TRIANGLE_POINTS).inputs == (2,)
