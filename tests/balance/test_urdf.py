"""Arms from URDF via Pinocchio: exact harmonic decomposition, Pinocchio's gravity as the check."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import SchemaError, arm_from_dict, solve_arm
from balance.potential import terms_forces, terms_potential
from balance.urdf import UrdfArm, arm_to_urdf, load_urdf, pinocchio_check, pinocchio_model


def random_urdf(rng: np.random.Generator, n: int, prismatic: int | None = None) -> str:
    """A spatial serial arm: random joint axes, origins, orientations, masses, centres and inertias."""
    out = ['<robot name="r">', '<link name="l0"/>']
    for i in range(1, n + 1):
        m = rng.uniform(0.5, 5)
        c = rng.uniform(-0.2, 0.2, 3)
        a = rng.uniform(0.01, 0.1, 3)
        out.append(f'<link name="l{i}"><inertial><origin xyz="{c[0]} {c[1]} {c[2]}"/><mass value="{m}"/>'
                   f'<inertia ixx="{a[0]}" ixy="0" ixz="0" iyy="{a[1]}" iyz="0" izz="{a[2]}"/></inertial></link>')
        xyz = rng.uniform(-0.4, 0.4, 3)
        rpy = rng.uniform(-math.pi, math.pi, 3)
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        if i == prismatic:
            kind, lim = "prismatic", '<limit lower="-0.1" upper="0.3" effort="1" velocity="1"/>'
        elif i % 2:
            kind, lim = "continuous", ""
        else:
            kind, lim = "revolute", '<limit lower="-2" upper="2.5" effort="1" velocity="1"/>'
        out.append(f'<joint name="j{i}" type="{kind}"><parent link="l{i - 1}"/><child link="l{i}"/>'
                   f'<origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}" rpy="{rpy[0]} {rpy[1]} {rpy[2]}"/>'
                   f'<axis xyz="{axis[0]} {axis[1]} {axis[2]}"/>{lim}</joint>')
    out.append("</robot>")
    return "\n".join(out)


@pytest.mark.parametrize("seed", range(4))
def test_spatial_revolute_arm_decomposition_is_exact(seed):
    rng = np.random.default_rng(seed)
    arm = UrdfArm(pinocchio_model(random_urdf(rng, int(rng.integers(3, 7)))), "random")
    terms = arm.harmonic_terms()
    assert all(set(np.round(t.form, 12)) <= {-1.0, 0.0, 1.0} for t in terms)  # linear forms of ±q_j
    q = arm.sample(300, seed)
    u = arm.potential(q)
    assert np.ptp(u - terms_potential(terms, q)) <= 1e-9 * np.max(np.abs(u))
    g = arm.gravity_forces(q)  # Pinocchio's generalised gravity
    np.testing.assert_allclose(terms_forces(terms, q), g, atol=1e-9 * np.max(np.abs(g)))


def test_spatial_arm_with_a_slide_follows_the_gamma_bound():
    rng = np.random.default_rng(11)
    for eps in (1e-3, 1e-5):
        arm = UrdfArm(pinocchio_model(random_urdf(rng, 4, prismatic=3)), "slide", accuracy=eps)
        chk = pinocchio_check(arm, arm.harmonic_terms(), 500, 1)
        # error of q ≈ k·sin(q/k) over the stroke: relative γ²/6 ≤ ε of the slide's terms
        assert chk["relative_residual"] < 50 * eps
    assert chk["relative_residual"] > 1e-12  # an approximation, honestly not exact


@pytest.mark.parametrize("name", ["arm_base_drives", "arm_prismatic"])
def test_toml_arms_agree_with_pinocchio(model, name):
    arm = arm_from_dict(model(name))
    chk = pinocchio_check(arm, arm.harmonic_terms(), 1000, 3)
    assert chk["gravity_agreement"] < 1e-9  # the project's gravity forces = Pinocchio's, relative
    out = solve_arm(model(name))
    assert out["pinocchio"]["relative_residual"] == pytest.approx(out["relative_residual"], rel=1e-6, abs=1e-13)


def test_example1_as_urdf_gives_the_textbook_amplitudes(model):
    from pathlib import Path

    doc = model("arm_urdf_example1")
    out = solve_arm(doc, str(Path(__file__).resolve().parents[2] / "models" / "arm_urdf_example1.toml"))
    exp = doc["expect"]
    got = sorted(out["terms"], key=lambda t: -t["amplitude"])
    assert [t["amplitude"] for t in got] == pytest.approx(exp["amplitudes"], rel=1e-12)
    assert [t["drive_form_text"] for t in got] == ["ψ2 − ψ1", "ψ3 − ψ1", "ψ4 − ψ1"]
    assert out["pinocchio"]["relative_residual"] < 1e-12
    assert all(tr["error"] == 0 for tr in out["transmission"])


def test_urdf_written_from_toml_round_trips(model, tmp_path):
    arm = arm_from_dict(model("arm_base_drives"))
    f = tmp_path / "a.urdf"
    f.write_text(arm_to_urdf(arm))
    ua = load_urdf(str(f))
    q = arm.sample(100, 5)
    np.testing.assert_allclose(ua.gravity_forces(q), arm.gravity_forces(q), atol=1e-12 * 200)


@pytest.mark.parametrize("text, words", [
    ("<robot", "not a URDF"),
    ('<robot name="x"><link name="a"/></robot>', "no movable joint"),
    ('<robot name="x"><link name="a"/><link name="b"/><joint name="j" type="floating"><parent link="a"/>'
     '<child link="b"/></joint></robot>', "cannot take"),
    ('<robot name="x"><link name="a"/><link name="b"/><joint name="j" type="prismatic"><parent link="a"/>'
     '<child link="b"/><axis xyz="0 0 1"/><limit lower="1" upper="0" effort="1" velocity="1"/></joint></robot>',
     "finite limits"),
])
def test_bad_urdf_one_sentence(tmp_path, capfd, text, words):
    f = tmp_path / "bad.urdf"
    f.write_text(text)
    with pytest.raises((SchemaError, Exception), match=words) as ei:
        load_urdf(str(f))
    assert "bad.urdf" in str(ei.value) and "\n" not in str(ei.value)
    assert capfd.readouterr().err == ""  # the C++ parser's own diagnostics are silenced
