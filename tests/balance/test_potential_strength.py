"""Harmonic terms (balance.model.potential) against independent computations: merged phasors against the
summed cosines they stand for, forces against finite differences of the potential, forms as text."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance.model.potential import HarmonicTerm, format_form, merge_terms, terms_forces, terms_potential

RNG = np.random.default_rng(7)
Q = RNG.uniform(-4, 4, (50, 3))


def summed(phasors, q):
    """Σ Re(z·e^{iφ}) of the phasors at configurations q: what the merged terms must equal."""
    return sum((z * np.exp(1j * (q @ np.asarray(f, dtype=float)))).real for z, f in phasors)


@pytest.mark.parametrize("phasors", [
    [(1 + 0j, (1, 0, 0)), (1j, (1, 0, 0)), (2 + 0j, (-1, 0, 0))],           # the docstring's, in 3 joints
    [(2 - 1j, (0, -1, 2)), (0.5j, (0, 1, -2)), (-3 + 0j, (1, 1, 0))],      # a flipped form, conjugated
    [(-1 + 0j, (0, 0, 1)), (4 + 0j, (0, 0, 0)), (1e-3 - 2j, (0, 0, -1))],  # a constant: no term
    [(-2 - 1e-17j, (0, 1, 0))],                                          # phase π, not −π
])
def test_merged_terms_are_the_sum_of_the_phasors(phasors):
    terms = merge_terms(phasors)
    np.testing.assert_allclose(terms_potential(terms, Q), summed([p for p in phasors if any(p[1])], Q),
                               atol=1e-12)
    keys = [tuple(f) for f in dict.fromkeys(tuple(-v if next(x for x in p[1] if x) < 0 else v for v in p[1])
                                             for p in phasors if any(p[1]))]
    assert [t.form for t in terms] == [tuple(float(v) for v in k) for k in keys]  # first appearance order
    for t in terms:
        assert t.amplitude > 0 and -math.pi < t.phase <= math.pi
        assert next(v for v in t.form if v) > 0 and all(isinstance(v, float) for v in t.form)
        assert math.copysign(1.0, t.phase) > 0 or t.phase < 0  # never −0.0


def test_a_phase_of_pi_is_written_pi_and_a_zero_phase_is_positive_zero():
    (t,) = merge_terms([(complex(-2.0, -0.0), (0, 1, 0))])
    assert t.phase == math.pi and t.amplitude == 2.0 and t.form == (0.0, 1.0, 0.0)
    (t,) = merge_terms([(complex(3.0, -0.0), (-1.0, 0, 0))])  # conjugated: +0.0j, phase +0.0
    assert t.phase == 0.0 and math.copysign(1.0, t.phase) == 1.0 and t.form == (1.0, -0.0 + 0.0, 0.0)
    assert str(t.phase) == "0.0"
    (t,) = merge_terms([(complex(3.0, -0.0), (1.0, 0, 0))])  # phase(3 − 0j) is −0.0: written 0.0
    assert str(t.phase) == "0.0" and str(t.to_dict()["phase_deg"]) == "0.0"


def test_small_terms_are_dropped_relative_to_the_largest():
    phasors = [(10 + 0j, (1, 0, 0)), (1e-10 + 0j, (0, 1, 0)), (1e-12 + 0j, (0, 0, 1))]
    assert [t.form for t in merge_terms(phasors)] == [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    assert [t.form for t in merge_terms(phasors, rel_tol=1e-10)] == [(1.0, 0.0, 0.0)]
    assert len(merge_terms(phasors, rel_tol=1e-14)) == 3
    # exactly the tolerance: dropped; cancelling phasors: nothing left; no phasors: no terms
    assert [t.form for t in merge_terms([(1 + 0j, (1, 0)), (0.5 + 0j, (0, 1))], rel_tol=0.5)] == [(1.0, 0.0)]
    assert merge_terms([(1 + 0j, (1, 0)), (-1 + 0j, (1, 0))]) == []
    assert merge_terms([]) == [] and merge_terms([(5 + 0j, (0, 0))]) == []
    # a dropped term or a constant before the others leaves the others
    assert [t.form for t in merge_terms([(1e-13 + 0j, (0, 1)), (1 + 0j, (1, 0))])] == [(1.0, 0.0)]
    assert [t.form for t in merge_terms([(5 + 0j, (0, 0)), (1 + 0j, (0, 1))])] == [(0.0, 1.0)]


def test_a_form_starting_below_one_keeps_its_sign():
    (t,) = merge_terms([(2j, (0.0, 0.25, -1.0))])
    assert t.form == (0.0, 0.25, -1.0) and t.phase == pytest.approx(math.pi / 2)
    (t,) = merge_terms([(2j, (0.0, -0.25, 1.0))])  # flipped: the phasor conjugated
    assert t.form == (0.0, 0.25, -1.0) and t.phase == pytest.approx(-math.pi / 2)


def test_forms_equal_to_twelve_digits_are_merged():
    (t,) = merge_terms([(1 + 0j, (1.0, 0.5)), (1 + 0j, (1.0 + 1e-14, 0.5 - 1e-14))])
    assert t.amplitude == pytest.approx(2.0, rel=1e-15) and t.form == (1.0, 0.5)
    assert len(merge_terms([(1 + 0j, (1.0, 0.5)), (1 + 0j, (1.0 + 1e-9, 0.5))])) == 2


def test_forces_are_minus_the_gradient_of_the_potential():
    terms = [HarmonicTerm(3.0, 0.4, (1.0, 0.0, 0.0)), HarmonicTerm(1.5, -2.0, (1.0, 1.0, 0.0)),
             HarmonicTerm(0.7, math.pi, (0.0, 2.0, -0.5))]
    h = 1e-6
    fd = np.stack([-(terms_potential(terms, Q + h * e) - terms_potential(terms, Q - h * e)) / (2 * h)
                   for e in np.eye(3)], axis=1)
    f = terms_forces(terms, Q)
    assert f.shape == Q.shape
    np.testing.assert_allclose(f, fd, atol=1e-8)
    np.testing.assert_allclose(terms_forces(terms, Q[0]), fd[0], atol=1e-8)  # one configuration (n,)
    assert terms_potential(terms, Q[0]).shape == () and terms_forces([], Q).shape == Q.shape
    assert not terms_forces([], Q).any() and not terms_potential([], Q).any()
    assert terms_potential([], Q).shape == (50,) and terms_forces([], Q).shape == (50, 3)
    # whole-number configurations give float forces and potentials
    assert terms_forces([], np.array([[0, 1, 2]])).dtype == float
    np.testing.assert_allclose(terms_forces(terms, np.array([[0, 1, 2]])), terms_forces(terms, np.array([[0.0, 1.0, 2.0]])))


def test_a_terms_value_angle_moment_and_dict():
    t = HarmonicTerm(2.0, 0.3, (1.0, -2.0))
    q = np.array([[0.5, 0.1], [-1.0, 2.0]])
    np.testing.assert_allclose(t.angle(q), [0.3, -5.0], atol=1e-15)
    np.testing.assert_allclose(t.value(q), 2.0 * np.cos(np.array([0.3, -5.0]) + 0.3), atol=1e-15)
    phi = np.linspace(-3, 3, 7)
    h = 1e-6  # the moment is ∂U/∂φ
    np.testing.assert_allclose(t.moment(phi), (2 * np.cos(phi + h + 0.3) - 2 * np.cos(phi - h + 0.3)) / (2 * h),
                               atol=1e-8)
    assert t.moment(0.0) == pytest.approx(-2.0 * math.sin(0.3), rel=1e-15)
    assert t.to_dict() == {"amplitude": 2.0, "phase": 0.3, "phase_deg": pytest.approx(17.188733853924695),
                           "form": [1.0, -2.0]}


@pytest.mark.parametrize("coeffs, text", [
    ([0, 1, -1], "b − c"),
    ([-1, 1, 0], "b − a"),                    # positive shafts first
    ([1, 0.25, 0], "a + 0.25·b"),
    ([-1, 0, 0], "−a"),
    ([-2.5, 0, -1], "−2.5·a − c"),
    ([0, 0, 0], "0"),
    ([1e-9, 0, 1], "c"),                      # below the digits: left out
    ([1.0000001, 0, 0], "a"),                  # rounded to 6 digits: 1
    ([0.123456789, 0, 0], "0.123457·a"),
    ([-0.4, 0, 0], "−0.4·a"),
    ([1, -0.25, 0], "a − 0.25·b"),
    ([0, -0.4, 0.3], "0.3·c − 0.4·b"),
])
def test_forms_as_text(coeffs, text):
    assert format_form(coeffs, ["a", "b", "c"]) == text


def test_forms_as_text_to_more_digits():
    assert format_form([1.0000001, 0, 0], ["a", "b", "c"], digits=9) == "1.0000001·a"
    assert format_form([1e-9, 0, 1], ["a", "b", "c"], digits=10) == "1e-09·a + c"
