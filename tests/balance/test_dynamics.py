"""Sliding last link: Pinocchio's mass matrix without and with counter-masses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import solve_prismatic
from balance.devices.dynamics import _Arm, _crank_laws, slide_dynamics
from balance.errors import InvalidInput


def test_scene_counter_masses_make_the_crank_angle_cyclic(model):
    out = solve_prismatic(model("slider_dynamics")).to_dict()
    cases = out["dynamics"]["cases"]
    bare = cases["without counter-masses"]
    both = cases["two counter-masses, crank angle η"]
    one = cases["one counter-mass keeping the centre of mass"]
    assert bare["max_dM_relative"] > 0.1 and bare["max_change_relative"] > 0.1  # clearly non-zero
    assert both["max_change_relative"] < 1e-14  # constant to rounding over the whole crank turn
    assert both["max_dM_relative"] < 1e-10  # central differences: rounding / h
    assert one["max_change_relative"] > 0.1


@pytest.mark.parametrize("M", [0.7, 2.0, 5.0])
def test_crank_laws_are_the_c_min_laws_for_any_counter_mass(M):
    m, inertia, q_max = 2.0, 0.1, 0.5
    z, _ = _crank_laws(m, M, q_max)
    eta = np.linspace(0, 2 * math.pi, 721)
    q = q_max * np.cos(eta)
    z1, z2 = np.array([z(e) for e in eta]).T
    np.testing.assert_allclose(m * q + M * (z1 + z2), 0, atol=1e-14)
    C = inertia + (m * m + 2 * m * M) * q_max ** 2 / (2 * M)
    np.testing.assert_allclose(inertia + m * q * q + M * (z1 * z1 + z2 * z2), C, rtol=1e-14)
    if M == m:  # the ±120° cranks of the textbook
        np.testing.assert_allclose(np.sort([z1, z2], 0), np.sort([q_max * np.cos(eta + 2 * math.pi / 3),
                                                                q_max * np.cos(eta - 2 * math.pi / 3)], 0), atol=1e-14)
    out = slide_dynamics(m, inertia, M, q_max, samples=20, seed=3).to_dict()
    assert out["cases"]["two counter-masses, crank angle η"]["max_change_relative"] < 1e-14


def test_planar_frame_needs_no_counter_mass():
    out = slide_dynamics(2.0, 0.1, 2.0, 0.5, kind="planar", samples=50, seed=1).to_dict()
    assert out["cases"]["without counter-masses"]["max_change_relative"] == 0.0


def test_point_jacobian_by_finite_differences():
    """The counter-masses' Jacobian (used to add them to Pinocchio's M) against positions."""
    import pinocchio as pin

    arm = _Arm("spatial", 2.0, 0.1, 0.5, 0.5, 10.0)
    rng = np.random.default_rng(0)
    for _ in range(10):
        q = np.array([*rng.uniform(-3, 3, 2), rng.uniform(-0.5, 0.5)])
        z = rng.uniform(-0.5, 0.5)

        def point(qq):
            pin.forwardKinematics(arm.model, arm.data, qq)
            o2 = arm.data.oMi[2]
            return o2.act(arm.model.jointPlacements[3].translation) + o2.rotation @ (z * arm.axis)

        J = arm.point_jacobian(q, z)
        for j in range(2):
            dq = np.zeros(3)
            dq[j] = 1e-6
            np.testing.assert_allclose(J[:, j], (point(q + dq) - point(q - dq)) / 2e-6, atol=1e-8)


def test_one_mass_keeping_inertia_is_bounded():
    out = slide_dynamics(2.0, 0.1, 2.0, 0.5, samples=5).to_dict()
    C = out["C_min"]
    assert out["one_mass"]["valid_interval"] == pytest.approx(math.sqrt((C - 0.1) / 2.0))


@pytest.mark.parametrize("args, options, words", [
    ((0, 0.1, 1, 0.5), {}, "the link mass m must be a positive number, not 0"),
    ((1, 0.1, -1, 0.5), {}, "the counter-mass M must be a positive number, not -1"),
    ((1, 0.1, 1, 0.0), {}, "the stroke q_max must be a positive number, not 0.0"),
    ((1, 0.1, 1, 0.5), {"length": 0.0}, "the length must be a positive number, not 0.0"),
    ((1, 0.1, 1, 0.5), {"parent_mass": math.nan}, "the parent mass must be a positive number, not nan"),
    ((1, 0.1, 1, 0.5), {"samples": 0}, "the dynamics check needs at least one sample, not 0"),
    ((1, 0.1, 1, 0.5, "curved"), {}, "the sliding-link arm is 'spatial' or 'planar', not 'curved'")])
def test_bad_dynamics_input(args, options, words):
    with pytest.raises(InvalidInput) as info:
        slide_dynamics(*args, **{"samples": 2, **options})
    assert str(info.value) == words + "."
