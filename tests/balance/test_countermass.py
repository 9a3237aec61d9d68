"""Counter-mass laws of a sliding last link (docs/theory.md, counter-masses) and the two-crank construction."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import InvalidInput, c_min, counter_mass_laws, crank_construction, solve_prismatic, verify_counter_mass


def smallest_c_numeric(m, inertia, M, q_max):
    """Bisection on C for a non-negative discriminant along the whole stroke."""
    q = np.linspace(-q_max, q_max, 20001)
    lo, hi = inertia, inertia + 10 * (m + m * m / M) * q_max ** 2 + 1
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if np.all(counter_mass_laws(q, m, inertia, M, mid)[2] >= 0):
            hi = mid
        else:
            lo = mid
    return hi


@pytest.mark.parametrize("m, inertia, M, q_max", [(2, 0.1, 2, 0.5), (1, 0, 3, 0.2), (5, 1.3, 0.7, 1.1)])
def test_c_min_matches_closed_form(m, inertia, M, q_max):
    assert c_min(m, inertia, M, q_max) == pytest.approx(smallest_c_numeric(m, inertia, M, q_max), rel=1e-9)
    assert c_min(m, inertia, M, q_max) == pytest.approx(inertia + (m * m + 2 * m * M) * q_max ** 2 / (2 * M))


@pytest.mark.parametrize("m, inertia, M, q_max, extra", [(2, 0.1, 2, 0.5, 0), (1, 0, 3, 0.2, 0.4), (5, 1.3, 0.7, 1.1, 2)])
def test_com_and_inertia_constant_to_round_off(m, inertia, M, q_max, extra):
    C = c_min(m, inertia, M, q_max) + extra
    r = verify_counter_mass(m, inertia, M, q_max, C=C)
    assert r.max_com_error < 1e-14 * q_max
    assert r.max_inertia_error < 1e-13 * C
    # the laws at C_min, as written in docs/theory.md
    q = np.linspace(-q_max, q_max, 101)
    z1, z2, _ = counter_mass_laws(q, m, inertia, M, c_min(m, inertia, M, q_max))
    root = np.sqrt(np.maximum((m * m + 2 * m * M) * (q_max ** 2 - q ** 2), 0))
    np.testing.assert_allclose(z1, (-m * q + root) / (2 * M), atol=1e-14)
    np.testing.assert_allclose(z2, (-m * q - root) / (2 * M), atol=1e-14)


def test_two_cranks_at_120_degrees_for_equal_masses():
    m, q_max = 3.0, 0.4
    eta = np.linspace(0, 2 * math.pi, 3601)
    q, z1, z2 = crank_construction(eta, q_max)
    np.testing.assert_allclose(m * q + m * z1 + m * z2, 0, atol=1e-14)
    np.testing.assert_allclose(m * (q * q + z1 * z1 + z2 * z2), 1.5 * m * q_max ** 2, rtol=1e-14)
    # they are the C_min laws with M = m (sorted, since the branches swap)
    a, b, _ = counter_mass_laws(q, m, 0.0, m, c_min(m, 0.0, m, q_max))
    np.testing.assert_allclose(np.sort([z1, z2], axis=0), np.sort([a, b], axis=0), atol=1e-7)
    r = verify_counter_mass(m, 0.2, m, q_max)
    assert r.crank_exact and r.crank_max_com_error < 1e-15 and r.crank_max_inertia_error < 1e-14


def test_unequal_masses_and_overlong_stroke_are_reported():
    m, M, q_max = 2.0, 1.5, 0.5
    r = verify_counter_mass(m, 0.1, M, q_max)
    assert not r.crank_exact
    # crank: COM error (m − M)·q_max/(m + 2M); inertia varies by |m − M|·q_max²
    assert r.crank_max_com_error == pytest.approx(abs(m - M) * q_max / (m + 2 * M), rel=1e-9)
    assert r.crank_max_inertia_error == pytest.approx(abs(m - M) * q_max ** 2, rel=1e-6)
    assert any("exact only for M = m" in s for s in r.messages)
    long = verify_counter_mass(m, 0.1, M, q_max, stroke=0.6)
    assert long.max_inertia_error > 0.1 and long.law_valid_stroke == pytest.approx(q_max)
    assert any("exceeds" in s for s in long.messages)


@pytest.mark.parametrize("args", [(-1, 0.1, 1, 0.5), (1, -0.1, 1, 0.5), (1, 0.1, 0, 0.5), (1, 0.1, 1, 0)])
def test_bad_input(args):
    with pytest.raises(InvalidInput):
        verify_counter_mass(*args)


def test_slider_model_matches_expect(model):
    doc = model("slider_countermass")
    exp = doc["expect"]
    out = solve_prismatic(doc, "slider_countermass.toml").to_dict()
    s = doc["slider"]
    derived = s["inertia"] + (s["mass"] ** 2 + 2 * s["mass"] * s["counter_mass"]) * s["q_max"] ** 2 / (2 * s["counter_mass"])
    assert derived == pytest.approx(exp["C_min"], rel=1e-15)
    assert out["C_min"] == pytest.approx(exp["C_min"], rel=1e-15)
    assert out["max_com_error"] < exp["max_com_error_below"]
    assert out["max_inertia_error"] < exp["max_inertia_error_below"]
    assert out["crank"]["exact"] is exp["crank_exact"]
