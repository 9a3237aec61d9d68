"""Branch keeping: a sweep never jumps to the other assembly mode, near toggles and collinear poses
(the failures reported against Pyslvs #35 and pylinkage), and stops at a dead position exactly."""

import math

import numpy as np

from synth.motion._sweep import _solver
from synth.motion import assemble, motion_range, sweep

from .helpers import four_bar, slider_crank
from .test_oracle import triad


def _side(motion):
    A, B = motion.joints[:, 2], motion.joints[:, 3]
    O4 = motion.joints[:, 1]
    return np.sign((O4[:, 0] - A[:, 0]) * (B[:, 1] - A[:, 1]) - (O4[:, 1] - A[:, 1]) * (B[:, 0] - A[:, 0]))


def test_crank_rocker_through_its_nearly_collinear_coupler_stays_on_its_branch():
    # b + c exceeds a + d by 0.001: at φ = π the coupler and rocker are 2.7° from a line
    for mode in (1, -1):
        lk = four_bar(1.0, 3.9, 1.101, 4.0, phi=3.0, mode=mode)
        motion = sweep(lk, steps=3601)
        assert motion.stopped is None
        assert (_side(motion) == mode).all()
        jumps = np.hypot(*np.diff(motion.joints[:, 3], axis=0).T)
        assert jumps.max() < 0.05  # the rocker pin moves smoothly: no flip to the mirror pose
        worst = motion.transmission["links 2, 3"]
        assert min(worst["min"], math.pi - worst["max"]) < math.radians(3)


def test_slider_crank_with_collinear_pivot_slider_and_pin_moves_through():
    # crank along the slide line: O, A and B on one line in the pose (zero offset)
    lk = slider_crank(1.0, 3.0, 0.0, phi=0.0)
    motion = sweep(lk, steps=721)
    phi = motion.inputs[:, 0]
    assert motion.stopped is None
    assert np.abs(motion.joints[:, 3, 0] - (np.cos(phi) + np.sqrt(9 - np.sin(phi) ** 2))).max() < 1e-12


def test_rocker_sweep_stops_at_the_dead_position_and_says_so():
    a, b, c, d = 2.5, 3.2, 3.0, 4.0
    lk = four_bar(a, b, c, d, phi=0.5)
    limit = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    motion = sweep(lk, steps=100, start=0.0, stop=3.0)
    assert motion.stopped is not None and "dead position" in motion.stopped
    assert abs(motion.inputs[-1, 0] - limit) < 1e-9 and motion.inputs[-2, 0] < limit
    assert np.isfinite(motion.joints).all()
    default = sweep(lk, steps=50)  # a rocker goes from limit to limit
    assert abs(default.inputs[0, 0] + limit) < 1e-9 and abs(default.inputs[-1, 0] - limit) < 1e-9


def test_newton_branch_ends_are_true_limits():
    lk = triad()
    r = motion_range(lk)
    assert not r.full_rotation
    lo, hi = r.limits
    inside = sweep(lk, steps=2, start=lo + 1e-7, stop=hi - 1e-7)
    assert inside.stopped is None
    beyond = sweep(lk, steps=3, start=lo, stop=hi + 1e-6)
    assert beyond.stopped is not None and beyond.inputs[-1, 0] == hi
    # the same limits found from another pose of the branch (traced over other paths)
    moved = assemble(lk, lo + 0.8 * (hi - lo))
    assert np.allclose(motion_range(moved).limits, (lo, hi), atol=1e-9, rtol=0)
    # and the closure Jacobian is singular there
    from synth.motion._system import System

    system = System(lk)
    theta, t, _ = _solver(lk).poses_along(np.array([hi - lk.pose_inputs[0]]))
    assert system.conditioning(theta, t)[0] < 1e-4
