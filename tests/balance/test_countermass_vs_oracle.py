"""Counter-mass balancing of a sliding link: every reported number recomputed from its definition.

``balance.devices.countermass.verify_counter_mass`` designs the two counter-mass laws and reports
how far the centre of mass and the moment of inertia drift, for the laws and for the
two-crank ±120° construction.  Here the same numbers come from the balance conditions
themselves (m·q + M·z1 + M·z2 = 0 and I + m·q² + M·(z1² + z2²) = C, solved as a sum
and a product of roots), sampled on grids of our own.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import counter_mass_laws, verify_counter_mass

# (m, I, M, q_max, stroke, C offset over C_min)
CASES = [
    (2.0, 0.1, 2.0, 0.5, None, 0.0),
    (1.0, 0.0, 3.0, 0.2, None, 0.4),
    (5.0, 1.3, 0.7, 1.1, None, 2.0),
    (2.0, 0.1, 1.5, 0.5, 0.6, 0.0),     # stroke beyond what C allows
    (3.0, 0.2, 3.0, 0.4, 0.3, 0.0),     # equal masses, short stroke: the cranks are not exact
    (2.0, 0.1, 1.5, 0.5, 0.505, 0.0),   # one per cent beyond: a small negative discriminant is reported
    (0.5, 0.05, 4.0, 0.8, None, 0.0),
]


def smallest_constant(m, inertia, M, q_max):
    """Least C for real laws on |q| ≤ q_max: z1, z2 real needs (z1 + z2)² ≤ 2(z1² + z2²)."""
    # z1 + z2 = −m·q/M, z1² + z2² = (C − I − m·q²)/M; real roots iff (m q / M)² ≤ 2 (C − I − m q²)/M
    return inertia + m * q_max ** 2 + m * m * q_max ** 2 / (2 * M)


def laws(q, m, inertia, M, C):
    s = -m * q / M                                     # z1 + z2
    sq = (C - inertia - m * q * q) / M                 # z1² + z2²
    half_gap = np.sqrt(np.maximum(2 * sq - s * s, 0.0)) / 2
    return s / 2 + half_gap, s / 2 - half_gap, 2 * sq - s * s


@pytest.mark.parametrize("m, inertia, M, q_max, stroke, extra", CASES)
def test_reported_numbers_recomputed(m, inertia, M, q_max, stroke, extra):
    C = smallest_constant(m, inertia, M, q_max) + extra
    res = verify_counter_mass(m, inertia, M, q_max, stroke=stroke, C=C)
    s = q_max if stroke is None else stroke
    assert res.C_min == pytest.approx(smallest_constant(m, inertia, M, q_max), rel=1e-14)
    assert (res.C, res.stroke, res.m, res.M, res.inertia, res.q_max) == pytest.approx((C, s, m, M, inertia, q_max))
    # the largest stroke the constant allows
    valid = math.sqrt((C - inertia) / (m + m * m / (2 * M)))
    assert res.law_valid_stroke == pytest.approx(valid, rel=1e-12)
    # the laws' drift on the stroke actually travelled
    q = np.linspace(-s, s, 200001)
    z1, z2, disc = laws(q, m, inertia, M, C)
    com = np.max(np.abs(m * q + M * (z1 + z2))) / (m + 2 * M)
    inert = np.max(np.abs(inertia + m * q * q + M * (z1 * z1 + z2 * z2) - C))
    assert res.max_com_error <= 1e-12 * max(1.0, s) and com <= 1e-12 * max(1.0, s)
    assert res.max_inertia_error == pytest.approx(inert, rel=1e-3, abs=1e-12 * C)
    beyond = s > valid * (1 + 1e-12)
    assert (res.max_inertia_error > 1e-9 * C) == beyond
    assert any("exceeds" in msg for msg in res.messages) == beyond
    # the two cranks at ±120°: q = s·cos η, z1,2 = q_max·cos(η ± 120°)
    eta = np.linspace(0, 2 * math.pi, 200001)
    cq = s * np.cos(eta)
    c1, c2 = q_max * np.cos(eta + 2 * math.pi / 3), q_max * np.cos(eta - 2 * math.pi / 3)
    ccom = np.max(np.abs(m * cq + M * (c1 + c2))) / (m + 2 * M)
    cin = m * cq * cq + M * (c1 * c1 + c2 * c2)
    assert res.crank_max_com_error == pytest.approx(ccom, rel=1e-6, abs=1e-15)
    assert res.crank_max_inertia_error == pytest.approx(np.ptp(cin), rel=1e-6, abs=1e-14)
    exact = m == M and s == q_max
    assert res.crank_exact == exact
    assert any("exact only for M = m" in msg for msg in res.messages) == (not exact)


@pytest.mark.parametrize("m, inertia, M, q_max, stroke, extra", CASES)
def test_laws_solve_the_balance_conditions(m, inertia, M, q_max, stroke, extra):
    C = smallest_constant(m, inertia, M, q_max) + extra
    q = np.linspace(-q_max, q_max, 1001)
    z1, z2, disc = counter_mass_laws(q, m, inertia, M, C)
    w1, w2, _ = laws(q, m, inertia, M, C)
    np.testing.assert_allclose(np.sort([z1, z2], axis=0), np.sort([w1, w2], axis=0), atol=1e-7 * max(1.0, q_max))
    np.testing.assert_allclose(m * q + M * (z1 + z2), 0.0, atol=1e-13 * max(1.0, m * q_max))
    np.testing.assert_allclose(inertia + m * q * q + M * (z1 * z1 + z2 * z2), C, rtol=1e-12)
    assert np.all(disc >= -1e-12 * C)


@pytest.mark.parametrize("args, kwargs, sentence", [
    ((-1, 0.1, 1, 0.5), {}, "the link mass m must be a finite number > 0, not -1.0."),
    ((0, 0.1, 1, 0.5), {}, "the link mass m must be a finite number > 0, not 0.0."),
    ((1, -0.1, 1, 0.5), {}, "the moment of inertia I must be a finite number ≥ 0, not -0.1."),
    ((1, 0.1, 0, 0.5), {}, "the counter-mass M must be a finite number > 0, not 0.0."),
    ((1, 0.1, 1, math.inf), {}, "the stroke q_max must be a finite number > 0, not inf."),
    ((1, 0.1, 1, 0.5), {"stroke": -0.2}, "the stroke must be a finite number > 0, not -0.2."),
    ((1, 0.1, 1, 0.5), {"C": 0.05}, "the inertia constant C must be finite and at least I = 0.1, not 0.05."),
    ((1, 0.1, 1, 0.5), {"C": math.nan}, "the inertia constant C must be finite and at least I = 0.1, not nan."),
    ((1, 0.1, 1, 0.5), {"samples": 2}, "the verification needs at least 3 samples, not 2."),
])
def test_refusals_say_why(args, kwargs, sentence):
    from balance import InvalidInput

    with pytest.raises(InvalidInput) as info:
        verify_counter_mass(*args, **kwargs)
    assert str(info.value) == sentence


def test_inertia_may_be_zero_and_reported_dictionary():
    res = verify_counter_mass(1.0, 0.0, 1.0, 0.5, samples=3)
    assert res.C_min == pytest.approx(0.375) and res.samples == 3
    d = res.to_dict()
    assert (d["m"], d["I"], d["M"], d["q_max"], d["stroke"], d["C"], d["C_min"]) == (
        1.0, 0.0, 1.0, 0.5, 0.5, res.C, res.C_min)
    assert d["crank"]["exact"] is True and d["crank"]["max_com_error"] == res.crank_max_com_error
    assert d["crank"]["max_inertia_error"] == res.crank_max_inertia_error
    assert d["crank"]["laws"] == "q = s·cos η, z1 = q_max·cos(η + 120°), z2 = q_max·cos(η − 120°)"
    assert verify_counter_mass(1.0, 0.0, 1.0, 0.5).samples == 2001  # the documented default
    # C = I is allowed: no stroke at all keeps the inertia, and the message says so
    assert any("exceeds ±0 m" in msg for msg in verify_counter_mass(1.0, 0.1, 1.0, 0.5, C=0.1).messages)
    assert (d["law_valid_stroke"], d["max_com_error"], d["max_inertia_error"], d["samples"], d["messages"]) == (
        res.law_valid_stroke, res.max_com_error, res.max_inertia_error, 3, [])


def test_crank_construction_stroke():
    from balance import crank_construction

    eta = np.linspace(0, 2 * math.pi, 7)
    q, z1, z2 = crank_construction(eta, 0.4)
    np.testing.assert_allclose(q, 0.4 * np.cos(eta), atol=1e-15)
    q, z1, z2 = crank_construction(eta, 0.4, stroke=0.3)
    np.testing.assert_allclose(q, 0.3 * np.cos(eta), atol=1e-15)
    np.testing.assert_allclose(z1, 0.4 * np.cos(eta + 2 * math.pi / 3), atol=1e-15)
    np.testing.assert_allclose(z2, 0.4 * np.cos(eta - 2 * math.pi / 3), atol=1e-15)
