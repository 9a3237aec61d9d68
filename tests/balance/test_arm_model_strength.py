"""The planar arm model (balance.model.arm) against values worked out by hand: heights and gravity
moments of one- and two-link arms, columns on a turntable, slides along a tilted link, the payload
refusals, and the harmonic terms' total potential constant at random configurations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance.errors import InvalidArm
from balance.model.arm import Arm, Link, Load
from balance.model.potential import terms_potential

S30, C30 = 0.5, math.sqrt(3) / 2


def slide(offset: float = 0.0, **kw) -> Link:
    """A 0.5 m slide of 10 N with its centre 0.2 m from mid-stroke, stroke 0.4 m, k = 2 m/rad."""
    return Link("s", "prismatic", 0.5, 10.0, 0.2, offset=offset, stroke=0.4, gear_ratio=2.0, **kw)


def test_a_slide_along_a_tilted_link_rises_with_the_sine_of_its_tilt():
    # zero horizontal, the slide tilted 30° up: its centre at (q + 0.2)·(cos 30°, sin 30°)
    arm = Arm((slide(math.pi / 6),), zero="horizontal")
    q = np.array([0.1])
    assert arm.potential(q) == pytest.approx(10.0 * 0.3 * S30, rel=1e-14)
    _, angles, points = arm.positions(q)
    assert angles[0, 0] == pytest.approx(math.pi / 6, rel=1e-14)
    np.testing.assert_allclose(points[0, 0], [0.3 * C30, 0.3 * S30], rtol=1e-14)
    # Q = −∂U/∂q = −W·sin 30°
    assert arm.gravity_forces(q)[0] == pytest.approx(-10.0 * S30, rel=1e-14)


def test_a_slide_after_a_revolute_joint_carries_both_offsets():
    # the upper link (1 m, no weight, offset 20°) then the slide (offset 30°): its direction is q1 + 50°
    arm = Arm((Link("u", "revolute", 1.0, 0.0, 0.5, offset=math.radians(20)), slide(math.pi / 6)),
              zero="horizontal")
    q = np.array([[0.3, -0.15]])
    th = 0.3 + math.radians(50)
    y = 1.0 * math.sin(0.3 + math.radians(20)) + (-0.15 + 0.2) * math.sin(th)
    assert arm.potential(q)[0] == pytest.approx(10.0 * y, rel=1e-14)
    joints, _, _ = arm.positions(q)
    np.testing.assert_allclose(joints[0, 1], [math.cos(0.3 + math.radians(20)), math.sin(0.3 + math.radians(20))],
                               rtol=1e-14)
    # Q1 = −W·(x_c − 0), x_c the slide's centre; Q2 = −W·sin θ
    x = 1.0 * math.cos(0.3 + math.radians(20)) + 0.05 * math.cos(th)
    np.testing.assert_allclose(arm.gravity_forces(q)[0], [-10.0 * x, -10.0 * math.sin(th)], rtol=1e-13)


def test_a_column_on_a_turntable_keeps_its_weight_at_its_height_whatever_the_zero():
    # a 0.3 m column of 20 N (centre 0.15 m, 0.02 m to the left: behind the arm) then a 1 m link of 10 N
    for zero, y_link in (("vertical", 0.5), ("horizontal", 0.0)):
        arm = Arm((Link("c", "vertical", 0.3, 20.0, 0.15, com_lateral=0.02), Link("l", "revolute", 1.0, 10.0, 0.5)),
                  zero=zero)
        q = np.zeros(2)
        _, _, points = arm.positions(q)
        np.testing.assert_allclose(points[0, 0], [-0.02, 0.15], atol=1e-15)
        assert arm.potential(q) == pytest.approx(20.0 * 0.15 + 10.0 * (0.3 + y_link), rel=1e-14)


def test_integer_configurations_give_the_same_moments_as_real_ones():
    # a two-link arm hanging from zero "vertical": Q = −Σ G·(x − x_j), x = l·sin... worked out at q = (0, 1)
    arm = Arm((Link("a", "revolute", 1.0, 10.0, 0.5), Link("b", "revolute", 0.8, 6.0, 0.4)))
    q = [0, 1]
    # zero vertical: a link at angle θ points along (cos(θ + 90°), sin(θ + 90°)) = (−sin θ, cos θ)
    xb = -0.4 * math.sin(1.0)  # the second link's centre, from its joint at (0, 1)
    want = [-6.0 * xb, -6.0 * xb]  # the first link's own centre is on the vertical through its joint
    np.testing.assert_allclose(arm.gravity_forces(q), want, rtol=1e-14)
    np.testing.assert_allclose(arm.gravity_forces(np.array(q, dtype=float)), want, rtol=1e-14)


def test_an_arm_without_a_payload_load_refuses_a_payload_and_takes_none():
    arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5),))
    assert arm.with_payload(0.0) is arm
    with pytest.raises(InvalidArm, match=r"^the arm has no payload load to carry a payload; mark one with "
                                         r"payload = true\.$"):
        arm.with_payload(1.0)
    loaded = Arm(arm.links, (Load(0, 19.6133, 1.0, payload=True),))
    assert loaded.with_payload(1.0).loads[0].weight == pytest.approx(9.80665, rel=1e-15)


@pytest.mark.parametrize("seed", range(3))
def test_a_balanced_arm_with_slides_columns_and_offsets_keeps_its_total_potential(seed):
    # gravity minus the harmonic terms is constant, up to the γ = q/k substitution (k large here)
    rng = np.random.default_rng(seed)
    links = (Link("c", "vertical", 0.4, float(rng.uniform(1, 30)), 0.2, com_lateral=0.05),
             Link("u", "revolute", 0.7, float(rng.uniform(1, 30)), 0.3, 0.04, float(rng.uniform(-1, 1))),
             Link("s", "prismatic", 0.5, float(rng.uniform(1, 30)), 0.2, -0.03, float(rng.uniform(-1, 1)),
                  stroke=0.2, gear_ratio=1e3),
             Link("f", "revolute", 0.4, float(rng.uniform(1, 30)), 0.2, 0.0, float(rng.uniform(-1, 1))))
    for zero in ("vertical", "horizontal"):
        arm = Arm(links, (Load(3, 5.0, 0.4, 0.01),), zero)
        q = arm.sample(400, seed)
        total = arm.potential(q) - terms_potential(arm.harmonic_terms(), q)
        # the substitution's error: W·(q − k·sin(q/k)) ≤ W·0.1·(0.1/k)²/6
        assert np.ptp(total) < 2 * 100 * 0.1 * (0.1 / 1e3) ** 2 / 6 + 1e-12


def test_an_upright_slide_carries_its_whole_weight():
    # zero vertical: the slide points up, its centre at height q + 0.2 and Q = −W; tilted 30° from the
    # vertical (offset 30°, counter-clockwise: backwards), its height is (q + 0.2)·cos 30°
    arm = Arm((slide(),))
    assert arm.potential(np.array([0.05])) == pytest.approx(10.0 * 0.25, rel=1e-14)
    assert arm.gravity_forces(np.array([0.05]))[0] == pytest.approx(-10.0, rel=1e-14)
    tilted = Arm((slide(math.pi / 6),))
    assert tilted.potential(np.array([0.05])) == pytest.approx(10.0 * 0.25 * C30, rel=1e-14)
    assert tilted.gravity_forces(np.array([0.05]))[0] == pytest.approx(-10.0 * C30, rel=1e-14)


@pytest.mark.parametrize("link, words", [
    (slide(q_range=(-0.1, 0.25)), "link 's': the slide range [-0.1, 0.25] m leaves the stroke ±0.2 m."),
    (slide(q_range=(-0.25, 0.1)), "link 's': the slide range [-0.25, 0.1] m leaves the stroke ±0.2 m."),
    (Link("s", "prismatic", 0.5, 10.0, 0.2, stroke=0.4, gear_ratio=0.0),
     "link 's': a prismatic joint needs a positive gear ratio k (or an accuracy ε to derive it)."),
    (Link("s", "prismatic", 0.5, 10.0, 0.2, q_range=(-0.1, 0.1), stroke=0.0, gear_ratio=1.0),
     "link 's': a prismatic joint needs a positive stroke."),
])
def test_a_slide_outside_its_stroke_or_without_a_gear_ratio_is_refused_in_one_sentence(link, words):
    with pytest.raises(InvalidArm) as err:
        Arm((link,))
    assert str(err.value) == words
    # the stroke's own ends are inside it
    Arm((slide(q_range=(-0.2, 0.2)),))


@pytest.mark.parametrize("drives, words", [
    (((1.0, 0.0), (-1.0, 1.0), (0.0, 0.0)), "the drive matrix must be a finite 2×2 matrix mapping drive-shaft angles "
                                           "to joints."),
    (((1.0, None), (0.0, 1.0)), "the drive matrix must be a finite 2×2 matrix mapping drive-shaft angles to joints."),
    (((1.0, 2.0), (0.5, 1.0)), "the drive matrix is singular: some joint cannot be driven."),
])
def test_a_drive_matrix_that_cannot_drive_the_joints_is_refused_in_one_sentence(drives, words):
    links = (Link("a", "revolute", 1.0, 10.0, 0.5), Link("b", "revolute", 1.0, 10.0, 0.5))
    with pytest.raises(InvalidArm) as err:
        Arm(links, drive_matrix=drives)
    assert str(err.value) == words
    assert Arm(links, drive_matrix=((1, 0), (-1, 1))).drives.tolist() == [[1.0, 0.0], [-1.0, 1.0]]


def test_two_slides_after_a_revolute_joint_add_their_bounds_on_it():
    # each slide p: W_p·(1 − cos γp) on itself and W_p·(A_p/2)·(1 − sin γp/γp) on the revolute joint before it,
    # W_p the weight it carries (itself and beyond)
    arm = Arm((Link("u", "revolute", 0.5, 10.0, 0.25),
               Link("s1", "prismatic", 0.5, 20.0, 0.2, stroke=0.4, gear_ratio=1.0),
               Link("s2", "prismatic", 0.3, 5.0, 0.1, stroke=0.2, gear_ratio=0.5)), zero="horizontal")
    g1, g2 = 0.2 / 1.0, 0.1 / 0.5
    w1, w2 = 25.0, 5.0
    want = [w1 * 0.2 * (1 - math.sin(g1) / g1) + w2 * 0.1 * (1 - math.sin(g2) / g2),
            w1 * (1 - math.cos(g1)), w2 * (1 - math.cos(g2))]
    np.testing.assert_allclose(arm.approx_potential_error_bounds(), want, rtol=1e-14)


def test_the_drive_form_clears_the_rounding_of_its_product():
    from balance.model.arm import describe_term
    from balance.model.potential import HarmonicTerm

    # q = D·ψ with D = [[1, 0.7], [0, 1]]: the form (0.1, −0.07) over ψ is (0.1, 0.1·0.7 − 0.07) = (0.1, 0)
    arm = Arm((Link("a", "revolute", 1.0, 1.0, 0.5), Link("b", "revolute", 1.0, 1.0, 0.5)),
              drive_matrix=((1.0, 0.7), (0.0, 1.0)))
    assert 0.1 * 0.7 - 0.07 != 0.0  # (rounding)
    t = describe_term(arm, HarmonicTerm(1.0, 0.0, (0.1, -0.07)))
    assert t.drive_form == (0.1, 0.0) and t.drive_form_text == "0.1·ψ1"


def test_a_joint_of_another_kind_or_a_negative_load_is_refused_and_a_range_off_by_rounding_kept():
    with pytest.raises(InvalidArm) as err:
        Arm((Link("x", "helical", 1.0, 1.0, 0.5),))
    assert str(err.value) == "link 'x': joint must be one of vertical, revolute, prismatic, not 'helical'."
    with pytest.raises(InvalidArm) as err:
        Arm((Link("l", "revolute", 1.0, 1.0, 0.5),), (Load(0, -1.0, 0.5, name="tool"),))
    assert str(err.value) == "load 'tool': weight must be a finite number ≥ 0, not -1.0."
    # the stroke's ends give or take 1e-12 m of rounding are inside it
    edge = 0.4 / 2 + 1e-12
    assert Arm((slide(q_range=(-edge, edge)),)).links[0].limits == (-edge, edge)
