"""Pantograph balanced manipulator: geometry, substitution weights, spring, cylinder force by virtual work."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import InvalidArm, Pantograph, SchemaError, solve_pantograph
from balance.model.pantograph import virtual_work_forces
from balance.problems.pantograph import pantograph_problem


def cross(a, b):
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def test_geometry_collinear_similar_and_parallelograms():
    p = Pantograph(l2=0.8, l3=1.0, k=4.0)
    th = np.random.default_rng(0).uniform(-2, 2, (100, 2))
    P = p.points(th)
    np.testing.assert_allclose(P["C"] - P["A"], p.k * (P["B"] - P["A"]), atol=1e-14)
    np.testing.assert_allclose(cross(P["B"] - P["F"], P["D"] - P["A"]), 0, atol=1e-14)  # 8 ∥ 2
    np.testing.assert_allclose(cross(P["B"] - P["E"], P["C"] - P["D"]), 0, atol=1e-14)  # 9 ∥ 3
    # plates 16 (D→D1) and 4 (C→C1) keep the frame's direction: they translate
    np.testing.assert_allclose(P["D1"] - P["D"], P["A1"] - P["A"], atol=1e-15)
    np.testing.assert_allclose(P["C1"] - P["C"], P["A1"] - P["A"], atol=1e-15)
    # similarity ratio = length of link 3 over link 9
    assert np.hypot(*(P["B"] - P["E"]).T) == pytest.approx(np.full(100, p.l3 / p.k))


def test_substitution_weights_reproduce_potential(model):
    p = pantograph_problem(model("pantograph")).pantograph
    w = p.point_weights()
    th = np.random.default_rng(1).uniform(-2, 2, (200, 2))
    P = p.points(th)
    subst = sum(w[k] * P[k][:, 1] for k in "ADBC")
    direct = p.potential(th)
    assert np.ptp(subst - direct) < 1e-12  # equal up to a constant (the bars' fixed offsets)
    total = sum(wt for _, wt, _, _ in p.height_coefficients())
    assert sum(w.values()) == pytest.approx(total) == pytest.approx(60 + 40 + 8 + 6 + 5 + 5 + 4 + 10 + 20 + 50)


def test_model_matches_expect(model):
    doc = model("pantograph")
    exp = doc["expect"]
    out = solve_pantograph(doc, "pantograph.toml").to_dict()
    for k, v in exp["point_weights"].items():
        assert out["point_weights"][k] == pytest.approx(v, rel=1e-12)
    assert out["term"]["amplitude"] == pytest.approx(exp["spring_amplitude"], rel=1e-12)
    assert out["drive_force"] == pytest.approx(exp["drive_force"], rel=1e-12)
    assert out["drive_force_range"] == pytest.approx(exp["drive_force_range"], rel=1e-12)
    assert out["relative_residual"] < exp["relative_residual_below"]
    assert out["device"]["tension"]["c"] * 0.1 * 0.4 == pytest.approx(exp["spring_amplitude"])


def test_cylinder_force_equals_virtual_work_and_varies(model):
    """The moment formula (substitution weights, lever arm about A) against an independent
    virtual-work solve on the links' own centres of mass, at 1000 random configurations."""
    p = pantograph_problem(model("pantograph")).pantograph
    th = p.sample(1000, seed=7)
    for frac in (0.0, 0.5, 1.0):
        vw = virtual_work_forces(p, th, frac)
        F = p.cylinder_force(th, frac)
        np.testing.assert_allclose(F, vw[:, 0], rtol=1e-12)
        np.testing.assert_allclose(p.hand_force(th, frac), vw[:, 1], atol=1e-10 * np.max(np.abs(F)))
    F = p.cylinder_force(th)
    assert np.ptp(F) > 0.1 * np.mean(F)  # configuration-dependent, not a constant
    out = solve_pantograph(model("pantograph")).to_dict()
    assert out["cylinder_force"]["min"] < out["drive_force_range"][0] < out["cylinder_force"]["max"]


def test_virtual_work_by_finite_differences(model):
    """Generalised gravity forces by central differences of the potential, the cylinder's
    by differences of its length: the residual of F, R stays at the differencing error."""
    p = pantograph_problem(model("pantograph")).pantograph
    th = p.sample(50, seed=3)
    h = 1e-6
    F, R = p.cylinder_force(th), p.hand_force(th)
    for j in range(2):
        d = np.zeros(2)
        d[j] = h
        dU = (p.potential(th + d) - p.potential(th - d)) / (2 * h)
        ds = (p.cylinder(th + d)[0] - p.cylinder(th - d)[0]) / (2 * h)
        rho = lambda t: np.hypot(*p.points(t)["C"].T)  # noqa: E731
        drho = (rho(th + d) - rho(th - d)) / (2 * h)
        spring = p.term().moment(th[:, 0]) if j == 0 else 0.0
        np.testing.assert_allclose(-dU + spring + F * ds + R * drho, 0, atol=1e-6 * np.max(F))


def test_vertical_cylinder_carries_the_constant_vertical_load():
    """With the base far below B the cylinder is vertical: F → W_B + k·W_C and R → 0."""
    p0 = Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0, tool=20.0)
    th = p0.sample(20, 1)
    errs = []
    for depth in (1e2, 1e4):  # the tilt, and with it the deviation, falls as 1/depth
        far = Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0, tool=20.0, base=(0.25, -depth))
        errs.append((np.max(np.abs(far.cylinder_force(th) / far.vertical_load() - 1)),
                     np.max(np.abs(far.hand_force(th))) / far.vertical_load()))
    assert errs[1][0] < 2e-2 * errs[0][0] and errs[1][1] < 2e-2 * errs[0][1]
    assert errs[1][0] < 1e-4 and errs[1][1] < 1e-4


def test_without_spring_the_cylinder_alone_does_not_balance(model):
    p = pantograph_problem(model("pantograph")).pantograph
    th = p.sample(50, 2)
    vw = virtual_work_forces(p, th)
    q = p.gravity_forces(th)  # no spring term: the cylinder and hand cannot hold W_D
    from balance.model.pantograph import stroke_gradients as _gradients

    ds, drho = _gradients(p, th)
    res = q + vw[:, :1] * ds + vw[:, 1:] * drho
    assert np.max(np.abs(res)) > 1.0


def test_bad_pantograph():
    with pytest.raises(InvalidArm, match="ratio"):
        Pantograph(l2=0.8, l3=1.0, k=0.5)
    with pytest.raises(InvalidArm, match="weight"):
        Pantograph(l2=0.8, l3=1.0, k=3, w2=-1)
    with pytest.raises(SchemaError, match="'lenght'"):
        solve_pantograph({"pantograph": {"l2": 1, "l3": 1, "ratio": 3, "lenght": 2}}, "p.toml")
    with pytest.raises(InvalidArm, match="through A"):  # the cylinder's line through A
        solve_pantograph({"pantograph": {"l2": 1, "l3": 1, "ratio": 3, "cylinder": {"base": [0.0, 0.0]}}})
    with pytest.raises(InvalidArm, match="p.toml"):
        solve_pantograph({"pantograph": {"l2": -1, "l3": 1, "ratio": 3}}, "p.toml")


def test_points_by_hand():
    """θ2 = 30°, θ3 = −45°, l2 = 0.8, l3 = 1.2, k = 3, offset 0.15: every joint from its definition."""
    p = Pantograph(l2=0.8, l3=1.2, k=3.0)
    r2, r3 = math.radians(30), math.radians(-45)
    u2, u3 = np.array([math.cos(r2), math.sin(r2)]), np.array([math.cos(r3), math.sin(r3)])
    P = {k: v[0] for k, v in p.points(np.array([r2, r3])).items()}
    expect = {"A": np.zeros(2), "D": 0.8 * u2, "C": 0.8 * u2 + 1.2 * u3, "E": 0.8 / 3 * u2,
              "B": 0.8 / 3 * u2 + 0.4 * u3, "F": 0.8 * u2 + 0.4 * u3}
    expect.update({k + "1": expect[k] + np.array([0.0, -0.15]) for k in "ADC"})
    assert set(P) == set(expect)
    for k, v in expect.items():
        np.testing.assert_allclose(P[k], v, atol=1e-15, err_msg=k)


def test_substitution_weights_with_centres_off_the_middle():
    """Forearm 1.25 m with its centre of mass 0.5 m from D: 60 % of w3 at D, 40 % at C; upper arm
    0.8 m with its centre 0.2 m from A: 75 % of w2 at A."""
    p = Pantograph(l2=0.8, l3=1.25, k=4.0, w2=100.0, w3=50.0, s2=0.2, s3=0.5)
    w = p.point_weights()
    assert w["A"] == pytest.approx(75.0) and w["D"] == pytest.approx(25.0 + 30.0)
    assert w["C"] == pytest.approx(20.0) and w["B"] == 0.0
    half = Pantograph(l2=0.8, l3=1.25, k=4.0, w3=50.0).point_weights()  # centres at the middle
    assert half["D"] == pytest.approx(25.0) and half["C"] == pytest.approx(25.0)
    # the bars and plates: w9 (E→B) splits 1 − 1/k : 1/k between A and D and half to B, and so on
    bars = Pantograph(l2=0.8, l3=1.25, k=4.0, w9=8.0, w8=16.0, w14=2.0, w15=4.0, w16=1.0, w4=3.0, tool=5.0,
                      payload=10.0).point_weights(payload_fraction=1.0)
    assert bars["A"] == pytest.approx(4.0 * 0.75 + 1.0)
    assert bars["D"] == pytest.approx(4.0 / 4 + 8.0 * 0.75 + 1.0 + 2.0 + 1.0)
    assert bars["B"] == pytest.approx(4.0 + 8.0)
    assert bars["C"] == pytest.approx(8.0 / 4 + 2.0 + 3.0 + 5.0 + 10.0)


def test_each_body_centre_of_mass_by_hand():
    """(a, b) of every body's centre, height a·sin θ2 + b·sin θ3, from the figure's geometry."""
    l2, l3, k = 0.8, 1.25, 4.0
    p = Pantograph(l2=l2, l3=l3, k=k, w2=1, w3=2, w9=3, w8=4, w14=5, w15=6, w16=7, w4=8, tool=9, payload=10,
                   s2=0.3, s3=0.5)
    e, g = l2 / k, l3 / k
    expect = {"2": (1, 0.3, 0.0), "3": (2, l2, 0.5), "9": (3, e, g / 2), "8": (4, (l2 + e) / 2, g),
              "14": (5, l2 / 2, 0.0), "15": (6, l2, l3 / 2), "16": (7, l2, 0.0), "4": (8, l2, l3),
              "tool": (9, l2, l3), "payload": (2.5, l2, l3)}
    got = {name: (w, a, b) for name, w, a, b in p.height_coefficients(payload_fraction=0.25)}
    assert list(got) == list(expect)
    for name, v in expect.items():
        assert got[name] == pytest.approx(v, abs=1e-15), name
    # the default payload is half of it, in the forces as in the load reduced to B
    th = np.array([[0.4, -0.3]])
    only = Pantograph(l2=l2, l3=l3, k=k, payload=10.0)
    np.testing.assert_allclose(only.gravity_forces(th), [[-5.0 * l2 * math.cos(0.4), -5.0 * l3 * math.cos(-0.3)]])
    assert only.vertical_load() == pytest.approx(k * 5.0)
    with_tool = Pantograph(l2=l2, l3=l3, k=k, w2=60.0, tool=20.0, payload=10.0)
    np.testing.assert_allclose(virtual_work_forces(with_tool, th)[:, 0], with_tool.cylinder_force(th, 0.5), rtol=1e-12)


def test_spring_term_is_the_weight_at_d_on_the_upper_arm():
    """W_D·l2·sin θ2 as the potential (cos(θ2 − 90°)) and W_D·l2·cos θ2 as the moment, whatever θ3."""
    p = Pantograph(l2=0.8, l3=1.25, k=4.0, w2=60.0, w3=40.0)
    wd = p.point_weights()["D"]
    th = np.array([[0.3, 1.1], [-0.7, -0.2], [1.2, 0.0]])
    term = p.term()
    np.testing.assert_allclose(term.value(th), wd * 0.8 * np.sin(th[:, 0]), atol=1e-12)
    np.testing.assert_allclose(term.moment(th[:, 0]), wd * 0.8 * np.cos(th[:, 0]), atol=1e-12)


def test_sample_fills_the_ranges():
    p = Pantograph(l2=0.8, l3=1.0, k=4.0, range2=(-0.5, 1.0), range3=(0.2, 0.9))
    th = p.sample(2000, seed=5)
    for j, (lo, hi) in enumerate((p.range2, p.range3)):
        assert lo <= th[:, j].min() < lo + 0.01 * (hi - lo) and hi - 0.01 * (hi - lo) < th[:, j].max() <= hi
    np.testing.assert_array_equal(p.sample(3, seed=5), th[:3])  # seeded: the same draws again


@pytest.mark.parametrize("bad, match", [
    (dict(l2=0.0), "length l2 must be positive, not 0.0"), (dict(offset=-0.1), "length offset must be positive"),
    (dict(k=1.0), "ratio k = AC/AB must exceed 1, not 1.0"),
    (dict(range2=(0.5, 0.5)), "angle range must be finite with low < high"),
    (dict(range3=(math.nan, 1.0)), "angle range"), (dict(range3=(0.0, math.inf)), "angle range"),
    (dict(range2=(-math.inf, 1.0)), "angle range"),
    (dict(range2=(1.0, 0.0)), "angle range"),
    # in degrees and named, as the TOML file gives them (it printed the radians as a tuple)
    (dict(range2=(math.radians(80), math.radians(-30))), "the pantograph's upper arm's (θ2) angle range must be finite "
                                                         "with low < high, not 80° .. -30°."),
    (dict(range3=(0.5, 0.5)), "the pantograph's forearm's (θ3) angle range")])
def test_bad_pantograph_geometry(bad, match):
    with pytest.raises(InvalidArm, match=match.replace("(", r"\(").replace(")", r"\)")):
        Pantograph(**{"l2": 0.8, "l3": 1.0, "k": 3.0, **bad})


def test_ratio_just_above_one_is_a_pantograph():
    p = Pantograph(l2=0.8, l3=1.0, k=1.5)
    assert p.g == pytest.approx(1.0 / 1.5)
