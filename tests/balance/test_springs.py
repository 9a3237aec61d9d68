"""Spring device formulas against direct vector mechanics and high-precision arithmetic."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from balance import CrankRockerDevice, SineDevice, crank_moment, spring_length
from balance.devices.springs import free_length, spring_length_textbook


def vector_moment(phi, kind, c, r, r0, a):
    """Spring force × lever arm, from positions: A = 0, C = (d, 0), B = r·(cos φ, sin φ)."""
    d = r + r0
    B = np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1)
    C = np.array([d, 0.0])
    BC = C - B
    L = np.linalg.norm(BC, axis=-1)
    tension = c * (L - free_length(kind, r, r0, a))  # > 0 pulls B towards C
    F = tension[:, None] * BC / L[:, None]
    return B[:, 0] * F[:, 1] - B[:, 1] * F[:, 0]  # z-moment about A, + = increasing φ


@pytest.mark.parametrize("kind", ["tension", "compression"])
@pytest.mark.parametrize("seed", range(4))
def test_moment_equals_force_times_lever(kind, seed):
    rng = np.random.default_rng(seed)
    c, r, r0 = rng.uniform(100, 1e4), rng.uniform(0.02, 0.5), rng.uniform(0.05, 1.0)
    a = rng.uniform(0, r0) if kind == "tension" else rng.uniform(0, 0.5)
    phi = np.linspace(-math.pi, math.pi, 721)
    got = crank_moment(phi, kind, c, r, r0, a)
    want = vector_moment(phi, kind, c, r, r0, a)
    np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-12 * c * r * (r + r0))
    # docs/theory.md writes each kind in its own sense: M_T = c·r·d·sin φ·(1 − l0/L) (towards C),
    # M_C = c·r·d·sin φ·(l0/L − 1) (away from C)
    d = r + r0
    L = np.sqrt(r * r + d * d - 2 * r * d * np.cos(phi))
    l0 = free_length(kind, r, r0, a)
    theory = c * r * d * np.sin(phi) * ((1 - l0 / L) if kind == "tension" else (l0 / L - 1))
    sign = -1 if kind == "tension" else 1
    np.testing.assert_allclose(got, sign * theory, rtol=1e-9, atol=1e-9 * c * r * d)


def test_zero_free_length_tension_is_exactly_harmonic():
    dev = CrankRockerDevice("tension", 1234.5, 0.12, 0.34, 0.34)
    phi = np.linspace(-2 * math.pi, 2 * math.pi, 1001)
    np.testing.assert_allclose(dev.moment(phi), -dev.amplitude * np.sin(phi), rtol=0, atol=1e-13 * dev.amplitude)
    assert dev.free_length == 0.0 and dev.sense == -1


@pytest.mark.parametrize("kind", ["tension", "compression"])
def test_moment_is_zero_where_the_crank_tip_meets_the_pivot(kind):
    """r = r0 puts the crank tip on the spring's far pivot at φ = 0: length 0, direction undefined,
    moment 0 (and no division warning) whatever the free length."""
    phi = np.tile([0.0, math.pi / 2, 2 * math.pi], 200)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m = crank_moment(phi, kind, 500.0, 0.1, 0.1, 0.05)
    assert np.all(m[0::3] == 0.0) and np.all(m[2::3] == pytest.approx(0.0, abs=1e-12))
    np.testing.assert_allclose(m[1::3], vector_moment(np.array([math.pi / 2]), kind, 500.0, 0.1, 0.1, 0.05)[0])


def test_sine_device():
    dev = SineDevice(0.05, 200.0)
    assert dev.amplitude == 10.0
    assert float(dev.moment(math.pi / 6)) == pytest.approx(-5.0)


def test_stable_length_keeps_accuracy_when_r0_tiny():
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 50
    r, r0 = 0.3, 1e-9
    phis = [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.5, math.pi]
    worst_stable = worst_text = 0.0
    for p in phis:
        d = mpmath.mpf(r) + mpmath.mpf(r0)
        exact = mpmath.sqrt(mpmath.mpf(r) ** 2 + d ** 2 - 2 * mpmath.mpf(r) * d * mpmath.cos(mpmath.mpf(p)))
        s = float(spring_length(p, r, r0))
        t = float(spring_length_textbook(p, r, r0))
        worst_stable = max(worst_stable, abs(s - float(exact)) / float(exact))
        worst_text = max(worst_text, abs(t - float(exact)) / float(exact))
    assert worst_stable < 1e-14
    assert worst_text > 1e-3  # the textbook form loses (nearly) all digits here


def test_device_force_and_free_length():
    dev = CrankRockerDevice("compression", 1000.0, 0.1, 0.3, 0.05)
    assert dev.free_length == pytest.approx(0.55)
    assert float(dev.force(0.0)) == pytest.approx(1000.0 * 0.25)
