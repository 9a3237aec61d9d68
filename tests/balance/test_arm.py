"""Arm potential, harmonic terms, devices and residual checks (docs/theory.md, Examples 1–2)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import (
    Arm, InvalidArm, Link, Load, SchemaError, arm_from_dict, balance_arm, check_terms,
    gear_ratio_for_accuracy, merge_terms, solve_arm,
)
from balance.model.potential import terms_forces, terms_potential


def random_arm(rng: np.random.Generator, n: int, zero: str = "vertical") -> Arm:
    """A revolute arm with random lengths, weights, centres (off-axis too), offsets and loads."""
    links = [
        Link(f"l{i}", "revolute", float(rng.uniform(0.1, 1.0)), float(rng.uniform(0, 100)),
             float(rng.uniform(-0.2, 1.0)), float(rng.uniform(-0.1, 0.1)), float(rng.uniform(-1, 1)))
        for i in range(n)
    ]
    loads = [Load(int(rng.integers(n)), float(rng.uniform(0, 50)), float(rng.uniform(0, 1)),
                  float(rng.uniform(-0.1, 0.1))) for _ in range(2)]
    return Arm(tuple(links), tuple(loads), zero)


# ------------------------------------------------------------------ Example 1
def _fd_forces(arm, q, h=1e-6):
    """Generalised gravity forces −∂U/∂q by central differences."""
    fd = np.zeros_like(q)
    for j in range(arm.n):
        dq = np.zeros(arm.n)
        dq[j] = h
        fd[:, j] = -(arm.potential(q + dq) - arm.potential(q - dq)) / (2 * h)
    return fd


def test_example1_matches_theory_and_expect(model):
    doc = model("arm_base_drives")
    out = solve_arm(doc, "arm_base_drives.toml").to_dict()
    exp = doc["expect"]
    # the amplitudes re-derived from U (docs/theory.md, Example 1): [G_Σ + …]·l
    G2, G3, G4, GS, l2, l3, l4 = 120, 80, 40, 30, 0.6, 0.5, 0.3
    derived = [(GS + G4 + G3 + G2 / 2) * l2, (GS + G4 + G3 / 2) * l3, (GS + G4 / 2) * l4]
    assert derived == pytest.approx(exp["amplitudes"], rel=1e-15)
    got = sorted(out["terms"], key=lambda t: -t["amplitude"])
    assert [t["amplitude"] for t in got] == pytest.approx(exp["amplitudes"], rel=1e-12)
    assert [t["phase_deg"] for t in got] == pytest.approx(exp["phases_deg"], abs=1e-12)
    assert [t["form"] for t in got] == exp["forms"]
    np.testing.assert_allclose([t["drive_form"] for t in got], exp["drive_forms"], atol=1e-15)
    assert [t["drive_form_text"] for t in got] == ["ψ2 − ψ1", "ψ3 − ψ1", "ψ4 − ψ1"]
    ets = sorted((d["sine"]["eT"] for d in out["devices"]), reverse=True)
    assert ets == pytest.approx(exp["eT"], rel=1e-12)
    assert out["check"]["samples"] == 1000
    assert out["relative_residual"] < exp["relative_residual_below"]
    assert out["potential_spread"] < 1e-9 * sum(exp["amplitudes"])


def test_example1_total_potential_constant_and_seed_forces(model):
    arm = arm_from_dict(model("arm_base_drives"))
    terms = arm.harmonic_terms()
    q = arm.sample(1000, seed=1)
    total = arm.potential(q) - terms_potential(terms, q)  # gravity + devices (−U_k each)
    assert np.ptp(total) < 1e-12 * 200
    # the textbook's generalised forces Q2, Q3, Q4 (re-derived, signs as in the textbook)
    a1, a2, a3 = 126.0, 55.0, 15.0
    q2, q3, q4 = q[:, 1], q[:, 2], q[:, 3]
    # gravity: Q = −∂U/∂q with U = Σ A cos(...)
    Q2 = a1 * np.sin(q2) + a2 * np.sin(q2 + q3) + a3 * np.sin(q2 + q3 + q4)
    Q3 = a2 * np.sin(q2 + q3) + a3 * np.sin(q2 + q3 + q4)
    Q4 = a3 * np.sin(q2 + q3 + q4)
    qg = arm.gravity_forces(q)
    assert np.max(np.abs(qg[:, 0])) == 0.0
    np.testing.assert_allclose(qg[:, 1:], np.stack([Q2, Q3, Q4], axis=1), atol=1e-12)


# ---------------------------------------------------------- generic properties
@pytest.mark.parametrize("zero", ["vertical", "horizontal"])
@pytest.mark.parametrize("seed", range(5))
def test_terms_equal_exact_potential_random_arms(seed, zero):
    rng = np.random.default_rng(seed)
    arm = random_arm(rng, int(rng.integers(1, 6)), zero)
    terms = arm.harmonic_terms()
    q = arm.sample(1000, seed)
    u = arm.potential(q)
    # equal up to a constant
    assert np.ptp(u - terms_potential(terms, q)) < 1e-12 * max(1.0, np.max(np.abs(u)))
    chk = check_terms(arm, terms, q=q)
    assert chk.relative_residual < 1e-12


@pytest.mark.parametrize("seed", range(3))
def test_gravity_forces_match_finite_differences(seed):
    rng = np.random.default_rng(100 + seed)
    arm = random_arm(rng, 4)
    q = arm.sample(50, seed)
    fd = _fd_forces(arm, q)
    np.testing.assert_allclose(arm.gravity_forces(q), fd, atol=1e-6 * 100)
    np.testing.assert_allclose(terms_forces(arm.harmonic_terms(), q), fd, atol=1e-6 * 100)


def test_prismatic_gravity_forces_match_finite_differences(model):
    arm = arm_from_dict(model("arm_prismatic"))
    q = arm.sample(200, 3)
    fd = _fd_forces(arm, q)
    np.testing.assert_allclose(arm.gravity_forces(q), fd, atol=1e-7)


def test_merge_equal_forms_and_drop_zero_terms():
    # two loads on the same link merge into one term; a weightless link gives none
    arm = Arm((Link("a", "revolute", 1.0, 0.0, 0.5), Link("b", "revolute", 1.0, 10.0, 0.5)),
              (Load(1, 5.0, 1.0), Load(1, 3.0, 0.0, 0.5)))
    terms = arm.harmonic_terms()
    forms = [t.form for t in terms]
    assert len(forms) == len(set(forms)) == 2
    by_form = {t.form: t for t in terms}
    t1 = by_form[(1.0, 1.0)]
    # 10·0.5 + 5·1 along the link, 3·0.5 sideways: |z| = hypot(10, 1.5)
    assert t1.amplitude == pytest.approx(math.hypot(10.0, 1.5), rel=1e-14)
    assert merge_terms([(0j, (1, 0)), (1 + 0j, (0, 0))]) == []
    # opposite forms merge: cos(−φ + α) = cos(φ − α)
    (t,) = merge_terms([(1 + 0j, (1, -1)), (1j, (-1, 1))])
    assert t.form == (1.0, -1.0) and t.amplitude == pytest.approx(math.sqrt(2))


# ---------------------------------------------------------------- Example 2
def test_example2_gear_ratio_terms_and_bound(model):
    doc = model("arm_prismatic")
    exp = doc["expect"]
    out = solve_arm(doc).to_dict()
    (pr,) = out["prismatic"]
    eps, A = 1e-4, 0.4
    assert gear_ratio_for_accuracy(A, eps) == pytest.approx((A / 2) / math.sqrt(6 * eps), rel=1e-15)
    assert pr["gear_ratio"] == pytest.approx(exp["gear_ratio"], rel=1e-12)
    assert pr["gamma_max"] == pytest.approx(exp["gamma_max"], rel=1e-12)
    assert pr["rel_error_bound"] <= eps
    amps = sorted(t["amplitude"] for t in out["terms"])
    assert amps == pytest.approx(sorted(exp["amplitudes"]), rel=1e-12)
    # the bilinear pair (k·G2/2)[cos(q1 − γ) − cos(q1 + γ)], γ = q2/k
    k = pr["gear_ratio"]
    pair = [t for t in out["terms"] if t["form"][1] != 0]
    assert sorted(t["form"][1] for t in pair) == pytest.approx([-1 / k, 1 / k])
    for t in pair:
        want = 0.0 if t["form"][1] < 0 else 180.0
        assert abs(t["phase_deg"]) == pytest.approx(want, abs=1e-12)
    bound = np.array(pr["residual_bound_per_joint"])
    assert bound == pytest.approx(exp["residual_bound_per_joint"], rel=1e-9)
    per = np.array(out["check"]["per_joint"])
    assert np.all(per <= bound * (1 + 1e-9))
    assert np.all(per >= 0.5 * bound)  # the bound is attained near the stroke ends: it is tight


@pytest.mark.parametrize("eps", [1e-2, 1e-3, 1e-5])
def test_prismatic_error_follows_gamma_bound(eps):
    arm = Arm((Link("l1", "revolute", 0.2, 30.0, 0.1),
               Link("s", "prismatic", 0.5, 20.0, 0.3, stroke=0.6, gear_ratio=gear_ratio_for_accuracy(0.6, eps))),
              zero="horizontal")
    terms = arm.harmonic_terms()
    q = arm.sample(2000, 7)
    q[:10, 1] = 0.3  # stroke end included
    res = np.abs(arm.gravity_forces(q) - terms_forces(terms, q))
    bound = arm.approx_potential_error_bounds()
    assert np.all(np.max(res, axis=0) <= bound * (1 + 1e-9))
    # bilinear term relative error: |q − k sin(q/k)|/|q| ≤ γ²/6 = ε at the stroke end
    k = arm.links[1].gear_ratio
    qq = np.linspace(1e-6, 0.3, 100)
    assert np.max(np.abs(qq - k * np.sin(qq / k)) / qq) <= eps * (1 + 1e-12)


# ------------------------------------------------------------------- payload
def test_payload_tuned_at_half():
    arm = Arm((Link("a", "revolute", 0.7, 50.0, 0.35), Link("b", "revolute", 0.5, 30.0, 0.25)),
              (Load(1, 40.0, 0.5, payload=True, name="payload"),))
    res = balance_arm(arm, samples=1000, seed=2)
    assert res.check.relative_residual < 1e-12  # exact at half payload
    p = res.payload
    assert p.tuned_for == 20.0 and (p.min_payload, p.max_payload) == (0.0, 40.0)
    # residual at 0 or full payload is exactly the half-payload effect
    assert p.max_residual == pytest.approx(p.half_payload_effect, rel=1e-12)
    # a true extreme: 20 N at the full reach 0.7 + 0.5 m (the sampled best was 1 % short)
    assert p.half_payload_effect == pytest.approx(20.0 * 1.2, rel=1e-12)


# ------------------------------------------------------------- counterweights
def test_counterweights_balance_example1(model):
    doc = model("arm_base_drives")
    out = solve_arm(doc).to_dict()
    cw = out["counterweights"]
    assert cw["available"]
    assert cw["max_residual"] < 1e-12 * 200
    # tip first: hand carries 30 N at 0.3 m and itself 40 N at 0.15 m → (9 + 6)/0.2 = 75 N
    by = {r["link"]: r["weight"] for r in cw["weights"]}
    assert by["hand"] == pytest.approx(15.0 / 0.2)
    assert by["forearm"] == pytest.approx(((30 + 40 + 75) * 0.5 + 80 * 0.25) / 0.2)
    assert cw["added_weight"] == pytest.approx(sum(by.values()))


def test_counterweights_refused_for_prismatic(model):
    out = solve_arm(model("arm_prismatic")).to_dict()
    assert out["counterweights"]["available"] is False
    assert "prismatic" in out["counterweights"]["reason"]


# --------------------------------------------------------------- bad input
@pytest.mark.parametrize("patch, exc, words", [
    ({"weight": -1.0}, InvalidArm, "weight"),
    ({"length": -0.5}, InvalidArm, "length"),
    ({"joint": "helical"}, SchemaError, "joint"),
    ({"colour": "red"}, SchemaError, "colour"),
    ({"range_deg": [30, 10]}, InvalidArm, "range"),
])
def test_bad_links(patch, exc, words):
    doc = {"arm": {"links": [dict({"name": "x", "joint": "revolute", "length": 1.0, "weight": 1.0}, **patch)]}}
    with pytest.raises(exc, match=words) as ei:
        solve_arm(doc, "bad.toml")
    assert "\n" not in str(ei.value)


def test_unknown_top_level_key_named_and_scene_expect_ignored():
    link = {"joint": "revolute", "length": 1.0, "weight": 1.0}
    ok = {"arm": {"links": [link]}, "scene": {"name": "x"}, "expect": {"y": 1}}
    solve_arm(ok, "ok.toml")
    with pytest.raises(SchemaError, match=r"^bad\.toml: the file has an unknown table \[robot\] \(allowed here: \[arm\], "
                                          r"\[expect\], \[plot\], \[scene\]\)\.$"):
        solve_arm({"arm": {"links": [link]}, "robot": {}}, "bad.toml")


def test_vertical_joint_after_in_plane_joint_is_refused():
    with pytest.raises(InvalidArm, match="vertical-axis"):
        Arm((Link("a", "revolute", 1.0, 1.0, 0.5), Link("b", "vertical", 1.0, 1.0, 0.5)))


@pytest.mark.parametrize("seed", [-1, 2**32])
def test_a_seed_numpy_cannot_take_is_one_sentence_in_every_table_and_in_the_api(seed):
    from balance.errors import InvalidInput
    from balance.problems.arm import balance_arm
    from balance.schema import parse

    tables = {"arm": {"links": [{"joint": "revolute", "length": 1, "weight": 2}], "check": {"seed": seed}},
              "slider": {"mass": 2, "counter_mass": 2, "q_max": 0.5, "dynamics": {"seed": seed}},
              "compare": {"arm": "a.urdf", "seed": seed},
              "pantograph": {"l2": 0.8, "l3": 1.0, "ratio": 4.0, "check": {"seed": seed}}}
    for name, table in tables.items():
        with pytest.raises(SchemaError, match=rf"s\.toml: \[{name}(\.\w+)?\] key 'seed' must be a whole number "
                                              rf"from 0 to 4294967295, not {seed}\."):
            parse({name: table}, name, "s.toml")
    with pytest.raises(InvalidInput, match=rf"^the random seed must be a whole number from 0 to 4294967295, not {seed}\.$"):
        balance_arm(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), samples=10, seed=seed)
    assert balance_arm(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), samples=10, seed=2**32 - 1).check.samples == 10
