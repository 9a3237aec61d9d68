"""Arms from URDF via Pinocchio: exact harmonic decomposition, Pinocchio's gravity as the check."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from balance import BalanceError, arm_from_dict, solve_arm
from balance.model.potential import terms_forces, terms_potential
from balance.model.urdf import UrdfArm, arm_to_urdf, load_urdf, pinocchio_check, pinocchio_model


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
        assert chk.relative_residual < 50 * eps
    assert chk.relative_residual > 1e-12  # an approximation, honestly not exact


@pytest.mark.parametrize("name", ["arm_base_drives", "arm_prismatic"])
def test_toml_arms_agree_with_pinocchio(model, name):
    arm = arm_from_dict(model(name))
    chk = pinocchio_check(arm, arm.harmonic_terms(), 1000, 3)
    assert chk.gravity_agreement < 1e-9  # the project's gravity forces = Pinocchio's, relative
    out = solve_arm(model(name)).to_dict()
    assert out["pinocchio"]["relative_residual"] == pytest.approx(out["relative_residual"], rel=1e-6, abs=1e-13)


def test_example1_as_urdf_gives_the_textbook_amplitudes(model):
    from pathlib import Path

    doc = model("arm_urdf_example1")
    out = solve_arm(doc, str(Path(__file__).resolve().parents[2] / "models" / "arm_urdf_example1.toml")).to_dict()
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


def _one(kind: str, extra: str, mass: str = "1", ixx: str = "0.01", ixy: str = "0", child: str = "b",
         axis: str = "0 1 0", limit: str = '<limit lower="-1" upper="1" effort="1" velocity="1"/>') -> str:
    """Links a (base) and b, one joint j of ``kind`` from a to ``child``, and ``extra`` elements."""
    return (f'<robot name="x"><link name="a"/><link name="b"><inertial><mass value="{mass}"/><inertia ixx="{ixx}" '
            f'ixy="{ixy}" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>'
            f'<joint name="j" type="{kind}"><parent link="a"/><child link="{child}"/><axis xyz="{axis}"/>{limit}'
            f'</joint>{extra}</robot>')


@pytest.mark.parametrize("text, words", [
    ("<robot", "not a URDF"),
    ('<robot name="x"><link name="a"/></robot>', "no movable joint"),
    ('<robot name="x"><link name="a"/><link name="b"/><joint name="j" type="floating"><parent link="a"/>'
     '<child link="b"/></joint></robot>', "^[^:]*: joint 'j' is of type 'floating', which an arm cannot have here; use "
     "revolute, continuous, prismatic or fixed joints.$"),
    (_one("planar", ""), "joint 'j' is of type 'planar'"),  # Pinocchio's JointModelPlanar once passed as a slide
    (_one("continuous", "", mass="nan"), "the mass of link 'b' must be a finite number, not 'nan'"),
    (_one("continuous", "", mass="-2"), "link 'b' has the negative mass -2 kg"),
    (_one("continuous", "", ixx="-0.5"), "link 'b' has an inertia with a negative principal moment"),
    (_one("continuous", "", ixy="0.5"), "negative principal moment"),  # symmetric but indefinite
    (_one("continuous", "", child="a"), "joint 'j' has the link 'a' as both its parent and its child"),
    (_one("continuous", "", child="c"), "joint 'j' has the child link 'c', which the URDF does not define"),
    (_one("continuous", '<joint name="k" type="continuous"><parent link="b"/><child link="a"/></joint>'),
     "every URDF link is the child of a joint: the joints close a loop"),
    (_one("continuous", '<link name="c"/><link name="d"/><joint name="k" type="continuous"><parent link="c"/>'
                        '<child link="d"/></joint>'), "the URDF has 2 root links (a, c)"),
    (_one("continuous", '<link name="c"/><joint name="k" type="continuous"><parent link="c"/><child link="b"/>'
                        '</joint>'), "link 'b' is the child of two joints ('j' and 'k')"),
    (_one("continuous", "", axis="0 0 0"), "joint 'j' has the zero axis"),
    (_one("revolute", "", limit='<limit lower="nan" upper="1" effort="1" velocity="1"/>'),
     "the lower limit of joint 'j' must be a finite number, not 'nan'"),
    (_one("revolute", "", limit=""), "joint 'j' is revolute and needs a <limit lower=… upper=…>"),
    ('<html/>', "its root element is <html>, not <robot>"),
    ('<robot name="x"><link name="a"/><link name="b"/><joint name="j" type="prismatic"><parent link="a"/>'
     '<child link="b"/><axis xyz="0 0 1"/><limit lower="1" upper="0" effort="1" velocity="1"/></joint></robot>',
     "joint 'j' has the limits lower 1 ≥ upper 0; give lower < upper."),
])
def test_bad_urdf_one_sentence(tmp_path, capfd, text, words):
    f = tmp_path / "bad.urdf"
    f.write_text(text)
    with pytest.raises(BalanceError, match=words if words.startswith("^") else re.escape(words)) as ei:
        load_urdf(str(f))
    assert "bad.urdf" in str(ei.value) and "\n" not in str(ei.value)
    assert capfd.readouterr().err == ""  # the C++ parser's own diagnostics are silenced


def test_urdf_arm_with_a_slide_is_balanced_within_its_bound(tmp_path):
    """A URDF with a prismatic joint (once a KeyError): the γ = q/k substitution's residual bound per
    joint holds for the true largest residual, and Pinocchio's gravity agrees at the worst configurations."""
    f = tmp_path / "slide.urdf"
    f.write_text(random_urdf(np.random.default_rng(5), 4, prismatic=2))
    out = solve_arm({"arm": {"urdf": str(f), "accuracy": 1e-4}}).to_dict()
    (pr,) = out["prismatic"]
    assert pr["coordinate"] == "q2" and pr["rel_error_bound"] <= 1e-4
    bound = np.array(pr["residual_bound_per_joint"])
    per = np.array(out["check"]["per_joint"])
    assert np.all(per <= bound * (1 + 1e-9) + 1e-12)
    assert bound[2:].tolist() == [0.0, 0.0]  # joints beyond the slide do not see it
    assert out["pinocchio"]["max_residual_at_worst"] == pytest.approx(out["max_residual"], rel=1e-9)
