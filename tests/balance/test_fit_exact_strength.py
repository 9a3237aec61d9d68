"""balance/devices/fit/exact.py, fast: the exact devices (a = r0, κ = 1) against a vectorised search of every
a = r0 device of a 160 × 160 grid over the bounds (for the lever, those whose spring L_max/δ fits the free-length
limit; peak force and spring length from positions), the balanced crank's potential constant at random angles,
the compression-lever's lever by hand, and every refusal in full."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import SpringBounds, fit_spring
from balance.devices.fit.exact import LEVER_DEFLECTION, _tension_exact
from balance.devices.fit.problem import _Problem
from balance.errors import InfeasibleBounds
from tests.balance.test_devices import lever_moment
from tests.balance.test_fit_vs_oracle import deg, moment_from_positions

LEAST_FORCE = {  # kind, range, bounds: the zero-free-length device with the least peak force
    "tension-S<1/2": ("tension", deg(10, 70), SpringBounds(r=(0.05, 0.2), r0=(0.01, 0.6), a=(0.0, 1.0))),
    "tension-S>1/2": ("tension", deg(10, 170), SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.6), a=(0.0, 1.0))),
    "tension-a-range": ("tension", deg(-40, 60), SpringBounds(r=(0.02, 0.3), r0=(0.01, 0.5), a=(0.05, 0.3))),
    "lever-S<1/2-capped": ("compression-lever", deg(0, 40),  # S = 0.12: the limit binds at the longest crank
                           SpringBounds(r=(0.05, 0.3), r0=(0.01, 0.6), a=(0.0, 1.0), max_free_length=0.5)),
    "lever-capped": ("compression-lever", deg(20, 160),  # the limit shortens the crank
                     SpringBounds(r=(0.01, 0.2), r0=(0.05, 0.4), a=(0.0, 1.0), max_deflection=0.25, max_free_length=1.2)),
    "lever-cap-within": ("compression-lever", deg(20, 160),  # the limit binds at the longest crank
                         SpringBounds(r=(0.01, 0.2), r0=(0.05, 0.4), a=(0.0, 1.0), max_free_length=1.2)),
    "lever-cap-above": ("compression-lever", deg(10, 70),  # the limit shortens the crank
                        SpringBounds(r=(0.05, 0.3), r0=(0.01, 0.6), a=(0.0, 1.0), max_free_length=0.5)),
}


def exact_devices(rng, b, n=160, lmax_limit=math.inf, moment=50.0):
    """Every a = r0 device of an n × n grid over the bounds (c·r·d = |Φ0|): its peak force c·L_max and its
    longest spring L_max, the spring's length from the crank pin's position over 401 angles."""
    phi = np.linspace(*rng, 401)
    r = np.linspace(*b.r, n)[:, None, None]
    r0 = np.linspace(max(b.r0[0], b.a[0]), min(b.r0[1], b.a[1]), n)[None, :, None]
    lmax = np.hypot(r * np.cos(phi) - (r + r0), r * np.sin(phi)).max(axis=2)
    force = moment / (r[:, :, 0] * (r[:, :, 0] + r0[:, :, 0])) * lmax
    return np.where(lmax <= lmax_limit, force, np.inf)


@pytest.mark.parametrize("name", LEAST_FORCE)
def test_the_exact_device_needs_the_least_peak_force(name):
    kind, rng, b = LEAST_FORCE[name]
    res = fit_spring(kind, -50.0, rng, b)
    assert res.method == "exact" and res.a == res.r0 and res.max_rel_error < 1e-12
    delta = 0.5 if b.max_deflection is None else b.max_deflection
    limit = math.inf if b.max_free_length is None else b.max_free_length * delta
    best = exact_devices(rng, b, lmax_limit=limit).min()
    _, L = moment_from_positions("tension", res.c, res.r, res.r0, res.r0, np.linspace(*rng, 4001))
    assert res.c * L.max() <= best * (1 + 1e-9) and res.c * L.max() >= best * (1 - 5e-3)  # (the grid's reach)
    assert L.max() <= limit * (1 + 1e-9)
    if kind == "compression-lever" and b.max_free_length is not None:
        # on the limit, and within it to the last bit
        assert res.lever.spring_free_length == pytest.approx(b.max_free_length, rel=1e-9)
        assert res.lever.spring_free_length <= b.max_free_length


def test_the_exact_device_balances_the_crank():
    """Spring energy c/2·L² (l0 = 0) plus the load's −Φ0·cos φ: the same at random angles."""
    kind, rng, b = LEAST_FORCE["tension-S>1/2"]
    res = fit_spring(kind, -50.0, rng, b)
    phi = np.random.default_rng(7).uniform(*rng, 40)
    _, L = moment_from_positions("tension", res.c, res.r, res.r0, res.a, phi)
    total = 0.5 * res.c * L ** 2 + 50.0 * np.cos(phi)
    assert np.ptp(total) <= 1e-9 * 50.0 and res.x[3] == 1.0


def test_the_exact_point_in_units_of_the_longest_crank():
    """(ρ, ρ0, α, κ) with α = ρ0, κ = 1; the longest crank where nothing limits it, ρ0 = 2Sρ/(1 − 2S) for
    S < 1/2 (the least L_max/(ρ(ρ + ρ0)) at fixed ρ, found here by a dense search of ρ0)."""
    b = SpringBounds(r=(0.05, 0.2), r0=(0.01, 0.6), a=(0.0, 1.0))
    lo, hi = math.radians(10), math.radians(70)
    p = _Problem("tension", -50.0, lo, hi, b, 21, "max")
    rho, rho0, al, kappa = _tension_exact(p)
    S = math.sin(hi / 2) ** 2
    assert (rho, al, kappa) == (1.0, rho0, 1.0)
    r0s = np.linspace(0.05, 3.0, 300001)
    assert rho0 == pytest.approx(r0s[np.argmin(np.sqrt(r0s ** 2 + 4 * (1 + r0s) * S) / (1 + r0s))], abs=2e-5)
    assert rho0 == pytest.approx(2 * S / (1 - 2 * S), rel=1e-14)
    # S ≥ 1/2: the force falls all the way to the longest r0 the bounds allow (a ≤ 1 m, r0 ≤ 0.6 m)
    wide = _Problem("tension", -50.0, 0.2, 2.5, b, 21, "max")
    assert _tension_exact(wide) == (1.0, pytest.approx(3.0), pytest.approx(3.0), 1.0)
    # a narrower a-range than r0's: a = r0 within both
    narrow = _Problem("tension", -50.0, lo, hi, SpringBounds(b.r, b.r0, (0.0, 0.05)), 21, "max")
    assert _tension_exact(narrow) == (1.0, 0.25, 0.25, 1.0)
    low = _Problem("tension", -50.0, lo, hi, SpringBounds(b.r, b.r0, (0.55, 1.0)), 21, "max")
    assert _tension_exact(low) == (1.0, pytest.approx(2.75), pytest.approx(2.75), 1.0)


def test_a_force_limit_above_the_least_force_keeps_the_exact_device():
    """The least peak force of an a = r0 device here is 659.085 N: a limit of 800 N leaves it exact."""
    b = SpringBounds((0.01, 0.2), (0.05, 0.4), (0.0, 1.0))
    free = fit_spring("compression-lever", -100.0, (math.radians(20), math.radians(160)), b)
    capped = fit_spring("compression-lever", -100.0, (math.radians(20), math.radians(160)),
                        SpringBounds(b.r, b.r0, b.a, max_force=800.0))
    assert free.max_force == pytest.approx(659.0851345, rel=1e-8)
    assert (capped.r, capped.r0, capped.c) == (free.r, free.r0, free.c) and capped.method == "exact"
    p = _Problem("tension", -100.0, math.radians(20), math.radians(160), SpringBounds(b.r, b.r0, b.a, max_force=800.0),
                 21, "max")
    assert _tension_exact(p) == pytest.approx(free.x, rel=1e-12)


@pytest.mark.parametrize("b, why", [
    (SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.3), a=(0.35, 1.0)), "a and r0 never meet"),
    (SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.3), a=(0.0, 1.0), max_force=100.0), "the least force is above the limit"),
])
def test_no_exact_device(b, why):
    p = _Problem("tension", -50.0, math.radians(20), math.radians(160), b, 21, "max")
    assert _tension_exact(p) is None, why


def test_the_longest_spring_limits_the_crank():
    """With L_max ≤ Λ: where even the shortest r0 at the longest crank is too long, the crank shortens to
    the one whose L_max is Λ (checked from positions); none when r0 alone reaches Λ or the crank falls
    below its bound."""
    b = SpringBounds(r=(0.05, 0.3), r0=(0.01, 0.6), a=(0.0, 1.0))
    lo, hi = math.radians(10), math.radians(70)
    p = _Problem("tension", -50.0, lo, hi, b, 21, "max")
    rho, rho0, al, kappa = _tension_exact(p, 0.5)
    assert rho0 == pytest.approx(0.01 / 0.3) and rho < 1.0 and al == rho0
    _, L = moment_from_positions("tension", 1.0, rho, rho0, rho0, np.linspace(lo, hi, 20001))
    assert L.max() == pytest.approx(0.5, rel=1e-6)
    assert _tension_exact(p, 0.01 / 0.3) is None                       # r0 alone is the whole length
    assert _tension_exact(p, 0.01 / 0.3 + 1e-3) is None                # the crank would be shorter than 0.05 m
    # the limit binds only beyond the unconstrained best r0: that one is kept, the longest crank too
    S = math.sin(hi / 2) ** 2
    free = _tension_exact(p)
    _, L = moment_from_positions("tension", 1.0, free[0], free[1], free[1], np.linspace(lo, hi, 20001))
    assert _tension_exact(p, L.max() * 1.01)[:2] == pytest.approx(free[:2], rel=1e-12)
    assert free[1] == pytest.approx(2 * S / (1 - 2 * S), rel=1e-12)
    # between: the longest crank, and the r0 where the limit starts to bind (L_max = Λ at ρ = 1)
    rho, rho0, _, _ = _tension_exact(p, L.max() * 0.9)
    _, L2 = moment_from_positions("tension", 1.0, rho, rho0, rho0, np.linspace(lo, hi, 20001))
    assert rho == 1.0 and L2.max() == pytest.approx(L.max() * 0.9 * (1 - 1e-12), rel=1e-6)


@pytest.mark.parametrize("rng", [(20.0, 160.0), (-150.0, 170.0)])
def test_the_compression_lever_by_hand(rng):
    """The lever device: exact (moment from positions with the spring on the lever beyond B), its stop
    at L_max/δ from C with δ = 0.5 unless given, its compressions the spring's lengths |CB|."""
    phi_rng = tuple(math.radians(v) for v in rng)
    b = SpringBounds(r=(0.01, 0.2), r0=(0.05, 0.4), a=(0.0, 1.0))
    res = fit_spring("compression-lever", -100.0, phi_rng, b)
    phi = np.linspace(*phi_rng, 4001)
    s = res.lever.stop_distance_from_C
    assert np.max(np.abs(lever_moment(phi, res.c, res.r, res.r0, s, s) + 100.0 * np.sin(phi))) <= 1e-10
    L = np.hypot(res.r + res.r0 - res.r * np.cos(phi), res.r * np.sin(phi))
    assert s == pytest.approx(L.max() / LEVER_DEFLECTION, rel=1e-6) and LEVER_DEFLECTION == 0.5
    assert (res.lever.compression_min, res.lever.compression_max) == pytest.approx((L.min(), L.max()), rel=1e-6)
    assert res.deflection == 0.5 and res.notes[-1] == res.lever.note()
    assert res.message == "compression spring on the lever beyond B, a = r0: exact" and res.kind == "compression-lever"
    assert res.norm == "max" and fit_spring("compression-lever", -100.0, phi_rng, b, norm="rms").norm == "rms"
    stiff = fit_spring("compression-lever", -100.0, phi_rng, SpringBounds(b.r, b.r0, b.a, max_deflection=0.2))
    assert stiff.lever.spring_free_length == pytest.approx(stiff.lever.compression_max / 0.2, rel=1e-12)
    assert stiff.deflection == 0.2
    # the bounds handed to the lever's problem keep the force limit (and not the free length: the lever's own)
    forced = fit_spring("compression-lever", -100.0, phi_rng, SpringBounds(b.r, b.r0, b.a, max_force=1e4))
    assert forced.max_force <= 1e4


@pytest.mark.parametrize("b, sentence", [
    (SpringBounds((0.01, 0.2), (0.05, 0.4), (0.5, 1.0)),
     "the compression-lever device is exact only at a = r0, but a ∈ [0.5, 1] m and r0 ∈ [0.05, 0.4] m never meet; "
     "widen the range of a or of r0."),
    (SpringBounds((0.01, 0.2), (0.5, 0.9), (0.0, 0.4)),
     "the compression-lever device is exact only at a = r0, but a ∈ [0, 0.4] m and r0 ∈ [0.5, 0.9] m never meet; "
     "widen the range of a or of r0."),
    # (the least peak force of an a = r0 device within these bounds is 659.085 N)
    (SpringBounds((0.01, 0.2), (0.05, 0.4), (0.0, 1.0), max_force=650.0),
     "no compression-lever device with a = r0 keeps the spring force below 650 N; raise the force limit, the maximum "
     "free length or the maximum deflection."),
    (SpringBounds((0.01, 0.2), (0.05, 0.4), (0.0, 1.0), max_free_length=0.1),
     "no compression-lever device with a = r0 fits a spring of at most 0.1 m at a deflection ratio of 0.5; raise the "
     "force limit, the maximum free length or the maximum deflection."),
    (SpringBounds((0.01, 0.2), (0.05, 0.4), (0.0, 1.0), max_force=700.0, max_free_length=0.1, max_deflection=0.4),
     "no compression-lever device with a = r0 keeps the spring force below 700 N and fits a spring of at most 0.1 m "
     "at a deflection ratio of 0.4; raise the force limit, the maximum free length or the maximum deflection."),
])
def test_each_refusal_of_the_lever_in_full(b, sentence):
    with pytest.raises(InfeasibleBounds) as exc:
        fit_spring("compression-lever", -100.0, (math.radians(20), math.radians(160)), b)
    assert str(exc.value) == sentence


def test_ranges_of_a_and_r0_that_meet_in_one_value():
    for a, r0 in (((0.4, 1.0), 0.4), ((0.0, 0.05), 0.05)):
        res = fit_spring("compression-lever", -100.0, (0.3, 2.8), SpringBounds((0.01, 0.2), (0.05, 0.4), a))
        assert res.a == res.r0 == pytest.approx(r0, rel=1e-12) and res.max_rel_error < 1e-12
