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
