"""Pantograph balanced manipulator: geometry, substitution weights, spring and drive force."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import InvalidArm, Pantograph, SchemaError, solve_pantograph
from balance.pantograph import pantograph_from_dict


def points(p: Pantograph, t2, t3):
    u2 = np.array([math.cos(t2), math.sin(t2)])
    u3 = np.array([math.cos(t3), math.sin(t3)])
    A = np.zeros(2)
    D = A + p.l2 * u2
    C = D + p.l3 * u3
    E = A + p.e * u2
    B = E + p.g * u3
    F = D + p.g * u3
    return A, B, C, D, E, F


def test_geometry_collinear_and_similar():
    p = Pantograph(l2=0.8, l3=1.0, k=4.0)
    rng = np.random.default_rng(0)
    for t2, t3 in rng.uniform(-2, 2, (100, 2)):
        A, B, C, D, E, F = points(p, t2, t3)
        np.testing.assert_allclose(C - A, p.k * (B - A), atol=1e-14)
        np.testing.assert_allclose(B - F, -(p.l2 - p.e) * (D - A) / p.l2, atol=1e-14)  # F→B ∥ upper arm


def test_substitution_weights_reproduce_potential(model):
    p, _ = pantograph_from_dict(model("pantograph"))
    w = p.point_weights()
    rng = np.random.default_rng(1)
    for t2, t3 in rng.uniform(-2, 2, (200, 2)):
        A, B, C, D, E, F = points(p, t2, t3)
        direct = sum(wt * (a * math.sin(t2) + b * math.sin(t3)) for wt, a, b in p.height_coefficients())
        subst = w["A"] * A[1] + w["D"] * D[1] + w["B"] * B[1] + w["C"] * C[1]
        assert subst == pytest.approx(direct, abs=1e-12)
    assert sum(w.values()) == pytest.approx(60 + 40 + 8 + 6 + 20 + 50)


def test_model_matches_expect(model):
    doc = model("pantograph")
    exp = doc["expect"]
    out = solve_pantograph(doc, "pantograph.toml")
    for k, v in exp["point_weights"].items():
        assert out["point_weights"][k] == pytest.approx(v, rel=1e-12)
    assert out["term"]["amplitude"] == pytest.approx(exp["spring_amplitude"], rel=1e-12)
    assert out["drive_force"] == pytest.approx(exp["drive_force"], rel=1e-12)
    assert out["drive_force_range"] == pytest.approx(exp["drive_force_range"], rel=1e-12)
    assert out["relative_residual"] < exp["relative_residual_below"]
    assert out["device"]["tension"]["c"] * 0.1 * 0.4 == pytest.approx(exp["spring_amplitude"])


def test_without_spring_the_drive_alone_does_not_balance(model):
    p, _ = pantograph_from_dict(model("pantograph"))
    th = np.array([[0.1, 0.2], [1.0, -0.5]])
    jb = np.stack([p.e * np.cos(th[:, 0]), p.g * np.cos(th[:, 1])], axis=1)
    res = p.gravity_forces(th) + p.drive_force() * jb
    assert np.max(np.abs(res)) > 1.0  # the spring term is needed


def test_bad_pantograph():
    with pytest.raises(InvalidArm, match="ratio"):
        Pantograph(l2=0.8, l3=1.0, k=0.5)
    with pytest.raises(InvalidArm, match="weight"):
        Pantograph(l2=0.8, l3=1.0, k=3, w2=-1)
    with pytest.raises(SchemaError, match="'lenght'"):
        solve_pantograph({"pantograph": {"l2": 1, "l3": 1, "ratio": 3, "lenght": 2}}, "p.toml")
