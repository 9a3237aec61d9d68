"""W > 1: a grid of inputs, solved by the dyads' closed forms and, independently, by continuation
from cell to cell (Newton's method on the same linkage with its dyads ignored)."""

import numpy as np

from synth.motion import Linkage, sweep_grid
from synth.motion._sweep import _solver
from synth.structure.chain import Chain, Mechanism


def five_bar():
    return Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
                   [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])  # joints 0-1 0-4 1-2 2-3 3-4


def test_five_bar_grid_by_closed_form_and_by_continuation_agree():
    ranges = [(0.6, 2.6), (0.4, 2.4)]
    closed = sweep_grid(five_bar(), ranges, steps=9, velocities=True)
    by_newton = five_bar()
    _solver(by_newton).plan = None
    newton = sweep_grid(by_newton, ranges, steps=9, velocities=True)
    reached = np.isfinite(closed.joints).all(axis=(1, 2))
    assert reached.sum() > 40 and (~reached).sum() > 0  # some cells are beyond the branch
    assert np.array_equal(reached, np.isfinite(newton.joints).all(axis=(1, 2)))
    assert np.abs(closed.joints[reached] - newton.joints[reached]).max() < 1e-10
    assert np.abs(closed.velocities[reached] - newton.velocities[reached]).max() < 1e-8
    # the coupler pin keeps its lengths to both cranks' pins
    pin, a, b = closed.joints[reached, 3], closed.joints[reached, 2], closed.joints[reached, 4]
    assert np.allclose(np.hypot(*(pin - a).T), np.hypot(1.5, 1.5), atol=1e-12)
    assert np.allclose(np.hypot(*(pin - b).T), np.hypot(1.5, 1.5), atol=1e-12)


def test_a_grid_a_whole_turn_from_the_pose_starts_at_the_pose():
    """The cell the grid starts from was the nearest to the pose's inputs in raw angle: for the five-bar posed at
    90°, 90° over ranges a turn back and a turn on (-5.68 … -3.68 rad and 6.68 … 8.68: the same angles) it started
    at the corner ≡ 149°, 23°, which does not assemble, and refused the grid ("cannot be assembled at the grid's
    input nearest to its pose").  Compared within a turn, the start is the pose's cell and the grid is the plain
    one's, cell by cell, by the closed forms and by continuation alike."""
    turn = 2 * np.pi
    plain, shifted = [(0.6, 2.6), (0.4, 2.4)], [(0.6 - turn, 2.6 - turn), (0.4 + turn, 2.4 + turn)]
    for newton in (False, True):
        grids = []
        for ranges in (plain, shifted):
            lk = five_bar()
            if newton:
                _solver(lk).plan = None
            grids.append(sweep_grid(lk, ranges, steps=9))
        reached = [np.isfinite(g.joints).all(axis=(1, 2)) for g in grids]
        assert np.array_equal(*reached) and 40 < reached[0].sum() < 81
        assert np.abs(grids[0].joints[reached[0]] - grids[1].joints[reached[0]]).max() < 1e-12
        assert np.allclose(grids[1].inputs - grids[0].inputs, [-turn, turn], atol=1e-12, rtol=0)  # as asked
