"""The sliding arm's mass matrix against an independent one built by hand (no Pinocchio, no URDF).

Each body's kinetic energy is ½·m·v_c² + ½·ω·(R I Rᵀ)·ω with the velocity Jacobians written from the
joint axes (a revolute column is ``a × (c − p)``, a prismatic one is ``a``): the arm of the module
docstring — a turntable about the vertical, a shoulder about a horizontal axis at height ``L``, a
slide along the upper arm from ``L`` out (``spatial``), or two vertical pins ``L`` apart and a
vertical slide (``planar``); the parent links are uniform rods (mass ``mp``, transverse inertia
``mp·L²/12``, axial a thousandth of it), the slide has the transverse inertia ``I`` and an axial
tenth of it.  The counter-masses are point masses on the slide axis at ``z`` from mid-stroke.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from balance.devices.dynamics import _Arm, sliding_arm_urdf, slide_dynamics

Z = np.array([0.0, 0.0, 1.0])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def frames(kind, q1, q2, L):
    """World rotation of links 1 and 2, the shoulder/elbow pivot, its axis, the slide axis and
    the slide's mid-stroke origin."""
    R1 = rz(q1)
    if kind == "spatial":
        R2 = R1 @ ry(q2)
        p2, a2 = R1 @ np.array([0, 0, L]), R1 @ np.array([0, 1.0, 0])
        a3 = R2 @ np.array([1.0, 0, 0])
    else:
        R2 = rz(q1 + q2)
        p2, a2 = R1 @ np.array([L, 0, 0]), Z
        a3 = Z
    return R1, R2, p2, a2, a3, p2 + R2 @ np.array([L, 0, 0])


def body_matrix(mass, c, inertia_world, cols):
    """One body's share of M: ``cols`` gives, per coordinate, (axis, pivot) of a revolute column,
    (axis, None) of a prismatic one, or None where the coordinate does not move the body."""
    n = len(cols)
    Jv, Jw = np.zeros((3, n)), np.zeros((3, n))
    for j, col in enumerate(cols):
        if col is None:
            continue
        axis, pivot = col
        if pivot is None:
            Jv[:, j] = axis
        else:
            Jv[:, j] = np.cross(axis, c - pivot)
            Jw[:, j] = axis
    return mass * Jv.T @ Jv + Jw.T @ inertia_world @ Jw


def hand_mass_matrix(kind, x, m, inertia, L, mp, counter=None):
    """M at ``x``; ``counter`` = (M, z(x), dz/dx3, dq/dx3, q(x)) adds two or one point masses and
    makes the third coordinate drive the slide through q(x)."""
    q1, q2, x3 = x
    q, dq = (x3, 1.0) if counter is None else (counter[4](x3), counter[3](x3))
    R1, R2, p2, a2, a3, mid = frames(kind, q1, q2, L)
    rod = mp * L * L / 12
    if kind == "spatial":
        c1, I1 = R1 @ np.array([0, 0, L / 2]), np.diag([rod, rod, 1e-3 * rod])
        c2, I2 = p2 + R2 @ np.array([L / 2, 0, 0]), np.diag([1e-3 * rod, rod, rod])
        I3 = np.diag([0.1 * inertia, inertia, inertia])
    else:
        c1, I1 = R1 @ np.array([L / 2, 0, 0]), np.diag([1e-3 * rod, rod, rod])
        c2, I2 = p2 + R2 @ np.array([L / 2, 0, 0]), np.diag([1e-3 * rod, rod, rod])
        I3 = np.diag([inertia, inertia, 0.1 * inertia])
    c3 = mid + q * a3
    out = body_matrix(mp, c1, R1 @ I1 @ R1.T, [(Z, np.zeros(3)), None, None])
    out += body_matrix(mp, c2, R2 @ I2 @ R2.T, [(Z, np.zeros(3)), (a2, p2), None])
    out += body_matrix(m, c3, R2 @ I3 @ R2.T, [(Z, np.zeros(3)), (a2, p2), (dq * a3, None)])
    if counter is not None:
        M, zs, dzs = counter[0], counter[1](x3), counter[2](x3)
        for z, dz in zip(zs, dzs):
            out += body_matrix(M, mid + z * a3, np.zeros((3, 3)), [(Z, np.zeros(3)), (a2, p2), (dz * a3, None)])
    return out


def cases(m, M, q_max):
    """The module's cases in its order: (hand M as a function of x, the third coordinate's range)."""
    s = math.sqrt(m * m + 2 * m * M)
    cranks = (M, lambda e: (q_max * (-m * math.cos(e) + s * math.sin(e)) / (2 * M),
                            q_max * (-m * math.cos(e) - s * math.sin(e)) / (2 * M)),
              lambda e: (q_max * (m * math.sin(e) + s * math.cos(e)) / (2 * M),
                         q_max * (m * math.sin(e) - s * math.cos(e)) / (2 * M)),
              lambda e: -q_max * math.sin(e), lambda e: q_max * math.cos(e))
    one = (M, lambda q: (-m * q / M,), lambda q: (-m / M,), lambda q: 1.0, lambda q: q)
    return {"without counter-masses": (None, (-q_max, q_max)),
            "two counter-masses, crank angle η": (cranks, (0.0, 2 * math.pi)),
            "one counter-mass keeping the centre of mass": (one, (-q_max, q_max))}


@pytest.mark.parametrize("kind", ["spatial", "planar"])
def test_pinocchio_mass_matrix_equals_the_one_by_hand(kind):
    m, inertia, q_max, L, mp = 1.7, 0.13, 0.4, 0.65, 7.0
    arm = _Arm(kind, m, inertia, q_max, L, mp)
    rng = np.random.default_rng(5)
    for _ in range(20):
        x = np.array([*rng.uniform(-math.pi, math.pi, 2), rng.uniform(-q_max, q_max)])
        hand = hand_mass_matrix(kind, x, m, inertia, L, mp)
        np.testing.assert_allclose(arm.mass_matrix(x), hand, rtol=0, atol=1e-12 * np.abs(hand).max())


def test_urdf_declares_the_stroke_and_the_joint_kinds():
    robot = ET.fromstring(sliding_arm_urdf("spatial", 2.0, 0.1, 0.35))
    joints = robot.findall("joint")
    assert [j.get("type") for j in joints] == ["revolute", "revolute", "prismatic"]
    assert [(j.find("parent").get("link"), j.find("child").get("link")) for j in joints] == \
        [("l0", "l1"), ("l1", "l2"), ("l2", "l3")]
    limit = joints[2].find("limit")
    assert (float(limit.get("lower")), float(limit.get("upper"))) == (-0.35, 0.35)
    for j in joints[:2]:  # a revolute joint turns at least a full turn
        assert float(j.find("limit").get("lower")) <= -math.pi and float(j.find("limit").get("upper")) >= math.pi
    assert [link.get("name") for link in robot.findall("link")] == ["l0", "l1", "l2", "l3"]
    slide = robot.findall("link")[3].find("inertial/mass")
    assert float(slide.get("value")) == 2.0
    for element in robot.iter():  # elements and attributes only: no stray text anywhere
        assert not (element.text or "").strip() and not (element.tail or "").strip()


def test_the_default_arm():
    """Without length and parent mass the arm has 0.5 m links of 10 kg, and the check 200 configurations
    drawn with seed 0."""
    m, inertia, q_max = 1.7, 0.13, 0.4
    x = np.array([0.4, -0.9, 0.1])
    hand = hand_mass_matrix("planar", x, m, inertia, 0.5, 10.0)
    np.testing.assert_allclose(_Arm("planar", m, inertia, q_max, 0.5, 10.0).mass_matrix(x), hand, atol=1e-12)
    assert sliding_arm_urdf("planar", m, inertia, q_max) == sliding_arm_urdf("planar", m, inertia, q_max, 0.5, 10.0)
    got = slide_dynamics(m, inertia, 2.0, q_max, "planar")
    assert (got.samples, got.seed) == (200, 0)
    rng = np.random.default_rng(0)
    largest = max(np.abs(hand_mass_matrix("planar", np.array([rng.uniform(-math.pi, math.pi),
                                                               rng.uniform(-math.pi, math.pi),
                                                               rng.uniform(-q_max, q_max)]),
                                          m, inertia, 0.5, 10.0)).max() for _ in range(200))
    assert got.cases["without counter-masses"].largest_entry == pytest.approx(largest, rel=1e-12)


@pytest.mark.parametrize("kind", ["spatial", "planar"])
def test_the_check_reports_the_hand_mass_matrix_at_its_configurations(kind):
    """Each case's largest entry, largest |∂M/∂x3| and largest change along x3 (at nine evenly spaced
    values of its range) from the hand mass matrix at the documented configurations."""
    m, inertia, M, q_max, L, mp, samples, seed = 1.7, 0.13, 2.3, 0.4, 0.65, 7.0, 4, 11
    got = slide_dynamics(m, inertia, M, q_max, kind, L, mp, samples=samples, seed=seed)
    rng = np.random.default_rng(seed)
    chosen = cases(m, M, q_max) if kind == "spatial" else dict(list(cases(m, M, q_max).items())[:1])
    assert list(got.cases) == list(chosen)
    for label, (counter, (lo, hi)) in chosen.items():
        def mass(x, counter=counter):
            return hand_mass_matrix(kind, x, m, inertia, L, mp, counter)

        scale = slope = spread = 0.0
        for _ in range(samples):
            x = np.array([rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi), rng.uniform(lo, hi)])
            scale = max(scale, np.abs(mass(x)).max())
            d = np.array([0, 0, 1e-3])  # M is quadratic in q: central differences are exact
            slope = max(slope, np.abs((mass(x + d) - mass(x - d)) / 2e-3).max())
            along = [mass(np.array([x[0], x[1], t])) for t in np.linspace(lo, hi, 9)]
            spread = max(spread, max(np.abs(a - along[0]).max() for a in along))
        case = got.cases[label]
        assert case.largest_entry == pytest.approx(scale, rel=1e-12)
        if counter is not None and len(counter[1](0.0)) == 2:  # cyclic: constant to rounding
            assert case.max_dM < 1e-9 * scale and case.max_change_relative < 1e-13
            assert slope < 1e-9 * scale and spread < 1e-13 * scale
        else:
            assert slope > 0.05 * scale or kind == "planar"
            assert case.max_dM == pytest.approx(slope, rel=1e-7, abs=1e-9 * scale)
            assert case.max_change_relative == pytest.approx(spread / scale, rel=1e-9, abs=1e-14)
            assert case.max_dM_relative == pytest.approx(case.max_dM / scale, rel=1e-12)
        assert case.coordinate == ("η" if label.startswith("two") else "q")


def test_to_dict_states_the_one_mass_cases_by_hand():
    """m = 2, I = 0.1, M = 2, q_max = 0.5: C_min = I + 1.5·m·q_max² = 0.85; keeping the centre of mass
    the inertia grows to I + m(1 + m/M)·q_max² = 1.1; keeping C, |q| ≤ √((0.85 − 0.1)/2) = 0.6124 m."""
    got = slide_dynamics(2.0, 0.1, 2.0, 0.5, samples=1, seed=4)
    out = got.to_dict()
    assert (out["arm"], out["samples"], out["seed"]) == ("spatial", 1, 4)
    assert out["C_min"] == pytest.approx(0.85, rel=1e-14)
    one = out["one_mass"]
    assert one["keeps_centre_of_mass"] == "inertia I + m(1 + m/M)·q² grows from 0.1 to 1.1 kg·m² over the stroke"
    assert one["keeps_inertia_C"] == pytest.approx(0.85, rel=1e-14)
    assert one["valid_interval"] == pytest.approx(math.sqrt(0.375), rel=1e-14)
    assert one["valid_interval_text"] == "|q| ≤ √((C − I)/m) = 0.6124 m, and its centre of mass moves"
    assert out["crank_laws"] == "z1,2 = q_max·(−m·cos η ± √(m² + 2mM)·sin η)/(2M), q = q_max·cos η"
    for label, case in got.cases.items():
        row = out["cases"][label]
        assert row == {"coordinate": case.coordinate, "max_dM": case.max_dM,
                       "max_dM_relative": case.max_dM / case.largest_entry,
                       "max_change_relative": case.max_change_relative, "largest_entry": case.largest_entry}
