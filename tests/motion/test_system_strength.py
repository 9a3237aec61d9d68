"""The loop-closure equations against finite differences of themselves: the Jacobian, the convective
terms (the second derivative along a straight path of the unknowns) and the inputs' column, for
pins, sliders on turning guides, gear meshes and both kinds of input; Newton's method and the
conditioning that says a pose is locked."""


import numpy as np
import pytest

from synth.motion import Linkage
from synth.motion._system import LOCKED, System, check_movable
from synth.structure.chain import Chain, Mechanism

from .helpers import inverted_slider_crank, scotch_yoke, slider_crank


def planetary():
    chain = Chain.parse("0-1-2-3 2-4 1~4 3~4")  # joints 0-1-2-3, 1~4, 2-4, 3~4
    return Linkage(Mechanism(chain, 0), (0, 0), [[0, 0], [1, 0], [1.5, 0], [2, 0]], driven=(1, 2))


def piston():
    lk = slider_crank(1.0, 3.0, 0.5)
    return Linkage(lk.mechanism, (1,), lk.points, lk.slides)  # the slider 0=3 drives


CASES = {"inverted slider-crank": lambda: inverted_slider_crank(1.0, 2.0), "Scotch yoke": lambda: scotch_yoke(1.3),
         "planetary": planetary, "piston": piston}


@pytest.mark.parametrize("name", CASES)
def test_the_jacobian_convective_terms_and_input_column_are_the_equations_derivatives(name):
    lk = CASES[name]()
    system = System(lk)
    rng = np.random.default_rng(5)
    q = rng.uniform(-0.5, 0.5, system.size)
    qd = rng.uniform(-1, 1, system.size)
    values = lk.pose_inputs + rng.uniform(-0.3, 0.3, lk.dof)

    def r(x, v=values):
        theta, t = system.poses(x[None])
        return system.residual(theta, t, v[None])[0]

    h = 1e-6
    theta, t = system.poses(q[None])
    jac = system.jacobian(theta, t)[0]
    numeric = np.stack([(r(q + h * e) - r(q - h * e)) / (2 * h) for e in np.eye(system.size)], axis=1)
    assert jac.shape == (system.rows, system.size)
    assert np.abs(jac - numeric).max() < 1e-7
    dtheta, dt = system.poses(qd[None])
    gamma = system.convective(theta, t, dtheta, dt)[0]
    h2 = 1e-4
    second = (r(q + h2 * qd) - 2 * r(q) + r(q - h2 * qd)) / h2 ** 2
    assert np.abs(gamma - second).max() < 1e-5
    column = np.stack([-(r(q, values + h * e) - r(q, values - h * e)) / (2 * h) for e in np.eye(lk.dof)], axis=1)
    assert np.abs(system.rate_column() - column).max() < 1e-8


def test_the_poses_of_the_unknowns_leave_the_frame_still():
    lk = inverted_slider_crank(1.0, 2.0)  # links 0 (frame) … 3
    system = System(lk)
    assert system.moving == [1, 2, 3] and system.size == 9 and system.rows == 9
    q = np.arange(1.0, 10.0)[None]
    theta, t = system.poses(q)
    assert theta.tolist() == [[0, 3, 6, 9]] and t.tolist() == [[[0, 0], [1, 2], [4, 5], [7, 8]]]
    assert system.input_offsets(np.array([[1.5]])).tolist() == [[1.5 - lk.pose_inputs[0]]]


def test_newton_closes_a_perturbed_pose_and_reports_failure():
    lk = inverted_slider_crank(1.0, 2.0)
    system = System(lk)
    values = lk.pose_inputs + 0.2
    q, ok, sign = system.newton(np.full(system.size, 0.01), values, tol=1e-13)
    theta, t = system.poses(q[None])
    assert ok and np.abs(system.residual(theta, t, values[None])).max() <= 1e-13 * lk.scale
    assert sign == int(np.sign(np.linalg.det(system.jacobian(theta, t)[0])))
    # one iteration is not enough from far away
    assert not system.newton(np.full(system.size, 0.3), values, tol=1e-13, iterations=1)[1]
    # a rocker (between ±2.518 rad) asked for an input of 3 rad: no pose closes, no sign
    from .helpers import four_bar

    rocker = four_bar(2.5, 3.2, 3.0, 4.0, phi=0.5)
    stuck = System(rocker)
    q, ok, sign = stuck.newton(np.zeros(stuck.size), np.array([3.0]), tol=1e-13)
    assert (ok, sign) == (False, 0)


def test_rates_solve_the_velocity_equations():
    lk = slider_crank(1.0, 3.0, 0.5)
    system = System(lk)
    theta, t = system.poses(np.zeros((1, system.size)))
    qd, qdd = system.rates(theta, t, accelerations=True)
    jac = system.jacobian(theta, t)[0]
    assert np.abs(jac @ qd[0, 0] - system.rate_column()[:, 0]).max() < 1e-12
    dtheta, dt = system.poses(qd[:, 0])
    gamma = system.convective(theta, t, dtheta, dt)[0]
    assert np.abs(jac @ qdd[0, 0] + gamma).max() < 1e-12
    assert system.rates(theta, t)[1] is None
    # a singular J gives NaN, not an error
    singular = np.zeros((2, system.rows, system.size))
    singular[1] = jac
    out = system.solve_linear(singular, np.ones((2, system.rows, 1)))
    assert np.isnan(out[0]).all() and np.abs(jac @ out[1, :, 0] - 1).max() < 1e-12


def test_a_wedge_loop_has_more_equations_than_unknowns_and_is_solved_by_least_squares():
    # four sliders in a loop (h = 2 in the plane: the angle equations repeat): 12 rows for 9 unknowns
    chain = Chain.parse("0=1 1=2 2=3 3=0")  # joints 0=1 0=3 1=2 2=3
    lk = Linkage(Mechanism(chain, 0), (0, 1), [[0, 0], [3, 0], [1, 1], [3, 2]],
                 slides={0: (1, 0), 1: (0, 1), 2: (1, 1), 3: (1, -1)})
    system = System(lk)
    assert (system.rows, system.size) == (10, 9)
    theta, t = system.poses(np.zeros((1, 9)))
    qd, _ = system.rates(theta, t)
    jac = system.jacobian(theta, t)[0]
    assert np.abs(jac @ qd[0].T - system.rate_column()).max() < 1e-12
    cond = system.conditioning(theta, t)[0]
    sv = np.linalg.svd(jac, compute_uv=False)
    assert cond == pytest.approx(sv[8] / sv[0], rel=1e-12) and cond > LOCKED
    q, ok, sign = system.newton(np.zeros(9), lk.pose_inputs + [0.1, 0.2], tol=1e-13)
    assert ok and sign == 1


def test_a_locked_pose_is_said_so_with_its_inputs():
    # a rigid triangle and a four-bar on one frame (W = 1 by count), driven on the triangle: locked everywhere
    chain = Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-0")  # joints 0-1 0-2 0-3 0-5 1-2 3-4 4-5
    pts = [[0, 0], [2, 0], [3, 0], [6, 0], [1, 1], [3.5, 1.5], [5, 1.8]]
    lk = Linkage(Mechanism(chain, 0), (0,), pts)
    assert check_movable(lk) == ("its loop-closure equations are singular there (a group of links aligned in a dead "
                                 "position, or a locked sub-chain); input 0-1")
    assert check_movable(Linkage(Mechanism(chain, 0), (2,), pts)) is None
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
                       [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    assert check_movable(five_bar) is None
    flat = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], [0, 1], [1, 1], [2, 1]])
    assert check_movable(flat) == ("its loop-closure equations are singular there: links 2, 3 are aligned in a dead "
                                   "position")
