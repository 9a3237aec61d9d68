"""Every 1-DOF mechanism the engine lists, with each choice of input link on the frame, moved from
its drawing's pose: the loop-closure equations hold to 1e-12 at every step (4 and 6 links in the
default suite; 8 links, 153 mechanisms with their inputs, with ``-m slow``)."""

import numpy as np
import pytest

import synth
from synth.draw import layout
from synth.motion._sweep import _solver
from synth.motion import linkage_from_pose, sweep
from synth.motion._system import System


def _closure(lk, motion):
    """The largest closure residual over the sweep, from the link poses the sweep reached."""
    theta, t, _ = _solver(lk).poses_along(motion.inputs[:, 0] - lk.pose_inputs[0])
    return float(np.abs(System(lk).residual(theta, t, motion.inputs)).max())


def _check(links):
    count = nudged = newton = 0
    for mechanism in synth.mechanisms(1, links, input_link=True, workers=1):
        lk = linkage_from_pose(mechanism, layout(mechanism.chain).joints, nudge=True)
        motion = sweep(lk, steps=60)
        assert motion.stopped is None  # the default range: a turn, or limit to limit
        assert _closure(lk, motion) <= 1e-12, mechanism.to_dict()
        # joints shared by links are where each link puts them
        count += 1
        nudged += lk.note is not None
        newton += _solver(lk).plan is None
    return count, nudged, newton


def test_every_mechanism_of_four_and_six_links_moves_with_closed_loops():
    assert _check(4) == (1, 0, 0)
    count, _, _ = _check(6)
    assert count == 9  # the five Watt and Stephenson inversions with their choices of input link


@pytest.mark.slow
def test_every_mechanism_of_eight_links_moves_with_closed_loops():
    count, nudged, newton = _check(8)
    assert count == 153 and nudged <= 10 and newton > 0
