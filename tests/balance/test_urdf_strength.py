"""Arms from URDF (balance.model.urdf) against second opinions: Pinocchio's own centre of mass of the URDF
written for a TOML arm against the arm's weights placed by hand, the joints' ranges and kinds as read, the
payload point, the slide's error bound worked out for one slide, and the check's fields."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from balance.model.arm import Arm, Link, Load
from balance.model.potential import terms_forces, terms_potential
from balance.model.urdf import UrdfArm, arm_to_urdf, pinocchio_check, pinocchio_model

G = 9.80665


def toml_arm(zero: str) -> Arm:
    """A turntable column, an upper arm with an off-axis centre, a tilted slide and a forearm with a tool."""
    return Arm((Link("column", "vertical", 0.4, 30.0, 0.2, com_lateral=0.05),
                Link("upper", "revolute", 0.7, 20.0, 0.3, 0.04, 0.3),
                Link("slide", "prismatic", 0.5, 15.0, 0.2, -0.03, -0.4, stroke=0.2, gear_ratio=0.5),
                Link("fore", "revolute", 0.4, 10.0, 0.2, 0.0, 0.2)),
               (Load(3, 5.0, 0.4, 0.01, name="tool"), Load(1, 2.0, 0.1, -0.02)), zero)


@pytest.mark.parametrize("zero", ["vertical", "horizontal"])
def test_pinocchios_centre_of_mass_of_the_written_urdf_is_the_arms_weights_placed_by_hand(zero):
    arm = toml_arm(zero)
    model = pinocchio_model(arm_to_urdf(arm))
    data = model.createData()
    weights = np.array([w for _, w, _, _ in arm.masses()])
    assert sum(model.inertias[j].mass for j in range(model.njoints)) == pytest.approx(weights.sum() / G, rel=1e-14)
    ua = UrdfArm(model, "written")
    for q in arm.sample(20, 4):
        com = pin.centerOfMass(model, data, ua.config(q))
        # the arm's plane is URDF's x–z (x forward, z up), turned by the turntable's q1 about z
        _, _, points = arm.positions(q)
        x, z = weights @ points[0] / weights.sum()
        np.testing.assert_allclose(com, [x * math.cos(q[0]), x * math.sin(q[0]), z], atol=1e-12)


def test_a_urdf_arms_joints_are_read_with_their_kinds_and_ranges():
    text = ('<robot name="r"><link name="a"/>'
            '<link name="b"><inertial><mass value="2"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
            '</inertial></link><link name="c"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>'
            '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>'
            '<link name="d"><inertial><mass value="1"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
            '</inertial></link><link name="e"/>'
            '<joint name="wide" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
            '<limit lower="-5" upper="4" effort="1" velocity="1"/></joint>'
            '<joint name="narrow" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 1 0"/>'
            '<limit lower="-1" upper="2" effort="1" velocity="1"/></joint>'
            '<joint name="free" type="continuous"><parent link="c"/><child link="d"/><origin xyz="1 0 0"/>'
            '<axis xyz="0 1 0"/></joint>'
            '<joint name="slide" type="prismatic"><parent link="d"/><child link="e"/><axis xyz="1 0 0"/>'
            '<limit lower="-0.1" upper="0.3" effort="1" velocity="1"/></joint></robot>')
    arm = UrdfArm(pinocchio_model(text), "r", accuracy=1e-4)
    assert [(c.name, c.joint) for c in arm.coordinates] == [("wide", "revolute"), ("narrow", "revolute"),
                                                           ("free", "revolute"), ("slide", "prismatic")]
    assert [c.limits for c in arm.coordinates] == [(-math.pi, math.pi), (-1.0, 2.0), (-math.pi, math.pi), (-0.1, 0.3)]
    c = arm.coordinates[3]
    assert c.stroke == pytest.approx(0.4) and c.gear_ratio == pytest.approx(0.2 / math.sqrt(6e-4), rel=1e-14)
    assert arm.kinds == ["revolute", "revolute", "revolute", "prismatic"]
    assert [arm.link_name(j) for j in range(4)] == ["b", "c", "d", "e"]
    assert arm.g == pytest.approx(G, rel=1e-15)
    # the continuous joint takes (cos q, sin q) in Pinocchio's configuration
    np.testing.assert_allclose(arm.config(np.array([0.1, 0.2, 0.3, 0.05])),
                               [0.1, 0.2, math.cos(0.3), math.sin(0.3), 0.05], rtol=1e-15)


def test_a_payload_point_moves_the_centre_of_mass_by_its_share():
    # a 1 m link of 2 kg about z-horizontal axis with its centre at 0.5 m; 1 kg at 0.8 m on it
    text = ('<robot name="r"><link name="a"/><link name="b"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>'
            '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>'
            '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/></joint></robot>')
    arm = UrdfArm(pinocchio_model(text), "r").with_payload_at("b", (0.8, 0.0, 0.0))
    assert arm.payload_point == (1, (0.8, 0.0, 0.0))
    loaded = arm.with_payload(1.0)
    # horizontal: Pinocchio's gravity moment (2·0.5 + 1·0.8)·g about the axis, at q = 0
    assert abs(loaded.gravity_forces(np.zeros(1))[0]) == pytest.approx(1.8 * G, rel=1e-12)
    assert abs(arm.gravity_forces(np.zeros(1))[0]) == pytest.approx(1.0 * G, rel=1e-12)
    assert arm.with_payload(0.0) is arm
    # the mass matrix of the loaded link about its axis: 2·0.5² + 1·0.8²
    assert loaded.mass_matrix(np.zeros(1))[0, 0] == pytest.approx(2 * 0.25 + 0.64, rel=1e-12)


def test_the_slides_bound_is_its_weight_times_the_substitutions_error():
    # a horizontal turntable-free arm: revolute joint about y, then a slide along the link; 3 kg beyond the slide
    text = ('<robot name="r"><link name="a"/><link name="b"/><link name="c"><inertial><mass value="3"/>'
            '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>'
            '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/></joint>'
            '<joint name="s" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.5 0 0"/>'
            '<axis xyz="1 0 0"/><limit lower="-0.2" upper="0.2" effort="1" velocity="1"/></joint></robot>')
    arm = UrdfArm(pinocchio_model(text), "r", accuracy=1e-3)
    k = arm.coordinates[1].gear_ratio
    gm = 0.2 / k
    w = 3 * G
    np.testing.assert_allclose(arm.approx_potential_error_bounds(),
                               [w * 0.2 * (1 - math.sin(gm) / gm), w * (1 - math.cos(gm))], rtol=1e-12)


def test_the_check_of_a_toml_arm_reports_its_samples_worst_configurations_and_agreement():
    arm = toml_arm("vertical")
    terms = arm.harmonic_terms()
    worst = arm.sample(3, 9)
    chk = pinocchio_check(arm, terms, samples=40, seed=2, worst=worst)
    assert (chk.samples, chk.seed, chk.worst_configurations, chk.pinocchio) == (40, 2, 3, pin.__version__)
    q = np.concatenate([arm.sample(40, 2), worst])
    grav = arm.gravity_forces(q)  # the arm's own, which Pinocchio must agree with
    res = np.abs(grav - terms_forces(terms, q))
    scale = float(np.max(np.abs(grav)))
    assert chk.max_gravity_force == pytest.approx(scale, rel=1e-9)
    assert chk.max_residual == pytest.approx(float(np.max(res)), rel=1e-6)
    assert chk.relative_residual == pytest.approx(chk.max_residual / scale, rel=1e-12)
    assert chk.max_residual_at_worst == pytest.approx(float(np.max(res[40:])), rel=1e-6)
    assert chk.gravity_agreement < 1e-12
    # a larger scale given is kept; no worst configurations: none reported
    big = pinocchio_check(arm, terms, samples=40, seed=2, scale=10 * scale)
    assert big.max_gravity_force == 10 * scale and big.max_residual_at_worst is None
    assert big.worst_configurations == 0


def test_a_revolute_joint_built_without_a_range_turns_a_full_turn():
    # a model built in code (not from URDF, whose reader refuses lower ≥ upper) with the limits 0 … 0
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "j", np.array([1.0]), np.array([1.0]),
                       np.array([0.0]), np.array([0.0]))
    model.appendBodyToJoint(j, pin.Inertia(2.0, np.array([0.5, 0.0, 0.0]), np.zeros((3, 3))), pin.SE3.Identity())
    assert UrdfArm(model, "r").coordinates[0].limits == (-math.pi, math.pi)


def test_without_pinocchio_reading_urdf_says_how_to_install_it(monkeypatch):
    import sys

    from balance.errors import InvalidArm
    from balance.model.urdf import _pin

    monkeypatch.setitem(sys.modules, "pinocchio", None)  # import pinocchio now raises ImportError
    with pytest.raises(InvalidArm) as err:
        _pin()
    assert str(err.value) == "reading URDF needs Pinocchio: python -m pip install pin."


SLIDE_ARM = ('<robot name="r"><link name="a"/><link name="b"><inertial><origin xyz="0.3 0 0"/><mass value="1"/>'
             '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>'
             '<link name="c"><inertial><mass value="2"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
             '</inertial></link>'
             '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/></joint>'
             '<joint name="s" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.5 0 0"/>'
             '<axis xyz="1 0 0"/><limit lower="-0.2" upper="0.2" effort="1" velocity="1"/></joint></robot>')


def test_an_arm_with_a_payload_keeps_its_name_accuracy_and_slides():
    arm = UrdfArm(pinocchio_model(SLIDE_ARM), "slider", accuracy=1e-4)
    moved = arm.with_payload_at(None, (0.1, 0.0, 0.0))
    assert (moved.name, moved.accuracy, moved.payload_point) == ("slider", 1e-4, (2, (0.1, 0.0, 0.0)))
    loaded = moved.with_payload(3.0)
    assert (loaded.name, loaded.accuracy, loaded.coordinates) == ("slider", 1e-4, arm.coordinates)
    # horizontal at q = 0, the slide at mid-stroke: moment 1·0.3 + 2·0.5 + 3·0.6 (kg·m) times g about j
    assert abs(loaded.gravity_forces(np.zeros(2))[0]) == pytest.approx((0.3 + 1.0 + 1.8) * G, rel=1e-12)


def test_an_arm_of_eight_joints_is_decomposed_over_its_whole_grid():
    # 3⁸ = 6561 configurations: more than one chunk of 4096
    rng = np.random.default_rng(8)
    out = ['<robot name="r">', '<link name="l0"/>']
    for i in range(1, 9):
        c = rng.uniform(-0.2, 0.2, 3)
        axis = rng.normal(size=3)
        out.append(f'<link name="l{i}"><inertial><origin xyz="{c[0]} {c[1]} {c[2]}"/><mass value="{rng.uniform(0.5, 3)}"/>'
                   '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>')
        xyz = rng.uniform(-0.3, 0.3, 3)
        out.append(f'<joint name="j{i}" type="continuous"><parent link="l{i - 1}"/><child link="l{i}"/>'
                   f'<origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}"/><axis xyz="{axis[0]} {axis[1]} {axis[2]}"/></joint>')
    out.append("</robot>")
    arm = UrdfArm(pinocchio_model("\n".join(out)), "eight")
    terms = arm.harmonic_terms()
    q = arm.sample(200, 1)
    u = arm.potential(q)
    assert np.ptp(u - terms_potential(terms, q)) <= 1e-9 * np.max(np.abs(u))


def _robot(links: str, joints: str) -> str:
    return f'<robot name="r">{links}{joints}</robot>'


_B = '<link name="a"/><link name="b"><inertial><mass value="1"/></inertial></link>'
_J = '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/></joint>'


@pytest.mark.parametrize("text, words", [
    (_robot('<link name="a"/><link name="b"><inertial><origin xyz="nan 0 0"/><mass value="1"/></inertial></link>', _J),
     "the centre of mass of link 'b' must be 3 finite numbers, not 'nan 0 0'."),
    (_robot('<link name="a"/><link name="b"><inertial><origin rpy="0 inf 0"/><mass value="1"/></inertial></link>', _J),
     "the inertia frame of link 'b' must be 3 finite numbers, not '0 inf 0'."),
    # a tiny link whose inertia is indefinite: refused at its own scale, not at 1 kg·m²'s
    (_robot('<link name="a"/><link name="b"><inertial><mass value="1e-6"/><inertia ixx="1e-12" ixy="1e-11" ixz="0" '
            'iyy="1e-12" iyz="0" izz="1e-12"/></inertial></link>', _J),
     "link 'b' has an inertia with a negative principal moment (-9e-12, 1e-12, 1.1e-11 kg·m²): it must be positive "
     "semi-definite."),
    (_robot('<link name="a"/><link/>', ""), "a URDF link has no name."),
    (_robot(_B, '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><origin rpy="nan 0 0"/>'
                '<axis xyz="0 1 0"/></joint>'),
     "the orientation of joint 'j' must be 3 finite numbers, not 'nan 0 0'."),
    (_robot(_B + "".join(f'<link name="{c}"/>' for c in "cdefg"),
            _J + "".join(f'<joint name="k{p}" type="continuous"><parent link="{p}"/><child link="{c}"/></joint>'
                         for p, c in zip("cdefg", "defgc"))),
     "the links c, d, e, f hang in a loop of joints, not from the base 'a': an arm is a tree."),
])
def test_a_urdf_no_arm_can_be_read_from_is_refused_in_one_sentence(text, words):
    from balance.errors import InvalidArm
    from balance.model.urdf import validate_urdf

    with pytest.raises(InvalidArm) as err:
        validate_urdf(text)
    assert str(err.value) == words


@pytest.mark.parametrize("text, words", [
    (_robot('<link name="a"/><link name="b"/><link name="b"/>', _J), "two URDF links are named 'b'."),
    (_robot(_B, '<joint type="continuous"><parent link="a"/><child link="b"/></joint>'), "a URDF joint has no name."),
    (_robot(_B, '<joint name="j" type="continuous"><child link="b"/></joint>'), "joint 'j' names no parent link."),
    (_robot(_B, '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><origin xyz="nan 0 0"/>'
                '<axis xyz="0 1 0"/></joint>'), "the origin of joint 'j' must be 3 finite numbers, not 'nan 0 0'."),
])
def test_a_urdf_with_a_repeated_or_missing_name_or_place_is_refused(text, words):
    from balance.errors import InvalidArm
    from balance.model.urdf import validate_urdf

    with pytest.raises(InvalidArm) as err:
        validate_urdf(text)
    assert str(err.value) == words


def test_a_fixed_joints_axis_is_ignored_and_a_missing_lower_limit_is_zero():
    from balance.errors import InvalidArm

    text = _robot(_B + '<link name="c"><inertial><mass value="1"/></inertial></link>',
                  '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>'
                  '<limit upper="1" effort="1" velocity="1"/></joint>'
                  '<joint name="f" type="fixed"><parent link="b"/><child link="c"/><axis xyz="0 0 0"/></joint>')
    arm = UrdfArm(pinocchio_model(text), "r")
    assert [c.limits for c in arm.coordinates] == [(0.0, 1.0)]
    with pytest.raises(InvalidArm) as err:
        UrdfArm(pinocchio_model(_robot(_B, '<joint name="f" type="fixed"><parent link="a"/><child link="b"/>'
                                           '</joint>')), "r")
    assert str(err.value) == "the URDF has no movable joint."


def test_the_decomposition_is_refused_past_sixteen_revolute_joints_or_the_work_limit():
    from balance.budget import TooMuchWork
    from balance.errors import InvalidArm

    def chain(n):
        links = '<link name="l0"/>' + "".join(f'<link name="l{i}"><inertial><origin xyz="0.1 0 0"/><mass value="1"/>'
                                              '</inertial></link>' for i in range(1, n + 1))
        joints = "".join(f'<joint name="j{i}" type="continuous"><parent link="l{i - 1}"/><child link="l{i}"/>'
                         '<origin xyz="0.1 0 0"/><axis xyz="0 1 0"/></joint>' for i in range(1, n + 1))
        return _robot(links, joints)

    with pytest.raises(InvalidArm) as err:
        UrdfArm(pinocchio_model(chain(17)), "r").ensure_decomposable(None)
    assert str(err.value) == ("the URDF arm has 17 revolute joints; the exact decomposition samples 3ⁿ configurations "
                              "and stops at 16 (its grid would fill memory).")
    with pytest.raises(TooMuchWork) as err:
        UrdfArm(pinocchio_model(chain(4)), "r").ensure_decomposable(1e-9)
    assert str(err.value).startswith("decomposing the potential of 4 revolute joints and 0 slides (81 evaluations) "
                                     "would take about ")
    assert UrdfArm(pinocchio_model(chain(4)), "r").ensure_decomposable(None) > 0


def test_the_urdf_written_for_a_toml_arm_names_its_joints_and_links_from_one():
    arm = toml_arm("vertical")
    ua = UrdfArm(pinocchio_model(arm_to_urdf(arm)), "written")
    assert [c.name for c in ua.coordinates] == ["joint1", "joint2", "joint3", "joint4"]
    assert [ua.link_name(j) for j in range(4)] == ["link1", "link2", "link3", "link4"]


def test_a_dh_arm_carries_its_source_in_a_comment_only_when_given():
    from balance.model.urdf import DHLink, urdf_from_dh

    links = [DHLink("l1", 0.5, 0.0, 0.0, 2.0, (-0.25, 0.0, 0.0))]
    assert "<!--" not in urdf_from_dh("one", links)
    assert "<!-- published DH table -->" in urdf_from_dh("one", links, "published DH table")
