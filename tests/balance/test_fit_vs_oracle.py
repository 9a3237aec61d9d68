"""Every number a spring fit reports, recomputed from the returned device alone.

``balance.devices.fit.fit_spring`` reports its errors, force, deflection, normalised
parameters and active bounds.  Here they are recomputed from ``(kind, c, r, r0, a)``
only, with the device's mechanics written out from positions (crank pin B, base point
C, spring force along BC, moment = B × F) — no code of ``balance`` is used for the
check — on dense grids of the working range.
"""

from __future__ import annotations

import functools
import math
import re

import numpy as np
import pytest

from balance import SpringBounds, fit_spring
from balance.errors import InfeasibleBounds

# a solver option misspelt or unknown is ignored by scipy with only a warning: here it fails
pytestmark = pytest.mark.filterwarnings("error::scipy.optimize.OptimizeWarning")

ISSUE = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))
FORCED = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0), max_force=2000.0,
                      max_free_length=1.5, max_deflection=0.4)
TENSION = SpringBounds(r=(0.05, 0.2), r0=(0.3, 0.5), a=(0.0, 0.1))
TENSION_FORCED = SpringBounds(r=(0.05, 0.5), r0=(0.1, 1.0), a=(0.0, 0.05), max_force=300.0, max_free_length=0.95)
#: r0 − a ≤ 0.06 with a ≤ 0.05: r0 ≤ 0.11, where the force limit binds as well
TENSION_SHORT = SpringBounds(r=(0.05, 0.5), r0=(0.1, 1.0), a=(0.0, 0.05), max_force=300.0, max_free_length=0.06)
STEEP = SpringBounds(r=(0.05, 0.5), r0=(1e-4, 1e-2), a=(0.0, 1.0))
#: one device, κ the only freedom: its error peaks within 0.1° of φ = 0, where the moment turns over
#: on the scale r0/r = 2e-4 rad — a uniform grid of the range misses the peak by 1e-5 of its height
STEEP_FIXED = SpringBounds(r=(0.5, 0.5), r0=(1e-4, 1e-4), a=(0.0, 0.0))


def deg(lo, hi):
    return math.radians(lo), math.radians(hi)


# (kind, moment, range, bounds, method, norm)
CASES = {
    "compression-20..160-max": ("compression", 100.0, deg(20, 160), ISSUE, None, "max"),
    "compression-20..160-rms": ("compression", 100.0, deg(20, 160), ISSUE, None, "rms"),
    "compression-0..180-max": ("compression", 100.0, deg(0, 180), ISSUE, None, "max"),
    "compression--90..90-rms": ("compression", 250.0, deg(-90, 90), ISSUE, None, "rms"),
    "compression-forced-max": ("compression", 100.0, deg(20, 160), FORCED, None, "max"),
    "compression-forced-rms-trf": ("compression", 100.0, deg(0, 180), FORCED, "trf", "rms"),
    "compression-nelder-mead": ("compression", 3.0, deg(30, 150), ISSUE, "nelder-mead", "max"),
    "compression-steep-near-0": ("compression", 100.0, deg(-30, 120), STEEP, None, "max"),
    "compression-steep-fixed": ("compression", 100.0, deg(-30, 30), STEEP_FIXED, None, "max"),
    "compression-steep-fixed-at-360": ("compression", 100.0, deg(330, 390), STEEP_FIXED, None, "max"),
    "compression-steep-fixed-at--360": ("compression", 100.0, deg(-390, -330), STEEP_FIXED, None, "max"),
    "tension-exact": ("tension", -100.0, deg(0, 180), ISSUE, None, "max"),
    "tension-fitted-max": ("tension", -100.0, deg(20, 160), TENSION, None, "max"),
    "tension-fitted-rms": ("tension", -40.0, deg(-60, 100), TENSION, None, "rms"),
    "tension-forced-max": ("tension", -100.0, deg(20, 160), TENSION_FORCED, None, "max"),
    "tension-forced-rms-nelder-mead": ("tension", -100.0, deg(20, 160), TENSION_FORCED, "nelder-mead", "rms"),
    "tension-short-rms-trf": ("tension", -100.0, deg(20, 160), TENSION_SHORT, "trf", "rms"),
}


@functools.lru_cache(maxsize=None)
def fitted(name):
    kind, moment, rng, bounds, method, norm = CASES[name]
    return fit_spring(kind, moment, rng, bounds, method=method, norm=norm)


def free_length(kind, r, r0, a):
    """The device's free length: tension r0 − a (pre-extension a), compression 2r + r0 + a."""
    return r0 - a if kind == "tension" else 2 * r + r0 + a


def moment_from_positions(kind, c, r, r0, a, phi):
    """Crank AB (A at the origin) of length r at angle φ from A→C, |AC| = r + r0; spring B–C."""
    phi = np.asarray(phi, dtype=float)
    bx, by = r * np.cos(phi), r * np.sin(phi)
    ux, uy = (r + r0) - bx, -by                       # B → C
    L = np.hypot(ux, uy)
    pull = c * (L - free_length(kind, r, r0, a))       # > 0 pulls B towards C
    fx, fy = pull * ux / L, pull * uy / L
    return bx * fy - by * fx, L


def dense_phi(lo, hi, r, r0):
    """Uniform points, plus points clustered on the multiples of 2π (where L → r0)."""
    phi = [np.linspace(lo, hi, 200001)]
    for k in range(math.ceil(lo / (2 * math.pi)), math.floor(hi / (2 * math.pi)) + 1):
        offs = np.geomspace(1e-4 * r0 / r, 1.0, 4000)
        phi += [2 * math.pi * k + offs, 2 * math.pi * k - offs, [2 * math.pi * k]]
    phi = np.concatenate(phi)
    return np.unique(phi[(phi >= lo) & (phi <= hi)])


@pytest.mark.parametrize("name", CASES)
def test_reported_errors_recomputed(name):
    kind, moment, (lo, hi), bounds, method, norm = CASES[name]
    res = fitted(name)
    m, _ = moment_from_positions(kind, res.c, res.r, res.r0, res.a, dense_phi(lo, hi, res.r, res.r0))
    phi = dense_phi(lo, hi, res.r, res.r0)
    e = (m - moment * np.sin(phi)) / abs(moment)
    # the largest error over the continuum, not over a grid that can step over a narrow peak
    assert res.max_rel_error == pytest.approx(np.max(np.abs(e)), rel=2e-6, abs=1e-12)
    # the RMS over the range: a uniform sample, as documented (4001 points) and in the continuum limit
    u = np.linspace(lo, hi, 4001)
    mu, _ = moment_from_positions(kind, res.c, res.r, res.r0, res.a, u)
    eu = (mu - moment * np.sin(u)) / abs(moment)
    assert res.rms_rel_error == pytest.approx(np.sqrt(np.mean(eu ** 2)), rel=1e-9, abs=1e-14)
    u = np.linspace(lo, hi, 200001)
    mu, _ = moment_from_positions(kind, res.c, res.r, res.r0, res.a, u)
    assert res.rms_rel_error == pytest.approx(np.sqrt(np.mean(((mu - moment * np.sin(u)) / abs(moment)) ** 2)),
                                              rel=2e-3, abs=1e-12)
    assert res.rms_rel_error <= res.max_rel_error * (1 + 1e-12)


def _plain_grid(case) -> bool:
    """Whether the fit grid is just equally spaced (the max norm adds points near φ = 0 when
    0 is in range and r0 may be short against r; those cases are judged on the fine grid)."""
    kind, moment, (lo, hi), bounds, method, norm = case
    near_zero = math.floor(hi / (2 * math.pi)) >= math.ceil(lo / (2 * math.pi))
    return not (norm == "max" and near_zero and bounds.r0[0] / bounds.r[1] <= 0.05)


@pytest.mark.parametrize("name", [k for k, case in CASES.items() if _plain_grid(case)])
def test_reported_fit_grid_errors_recomputed(name):
    """The errors on the fit's own grid of equally spaced points."""
    kind, moment, (lo, hi), bounds, method, norm = CASES[name]
    res = fitted(name)
    phi = np.linspace(lo, hi, res.grid)
    m, _ = moment_from_positions(kind, res.c, res.r, res.r0, res.a, phi)
    e = (m - moment * np.sin(phi)) / abs(moment)
    assert res.grid_max_rel_error == pytest.approx(np.max(np.abs(e)), rel=1e-7, abs=1e-13)
    assert res.grid_rms_rel_error == pytest.approx(np.sqrt(np.mean(e ** 2)), rel=1e-7, abs=1e-13)


@pytest.mark.parametrize("name", CASES)
def test_reported_device_numbers_recomputed(name):
    kind, moment, (lo, hi), bounds, method, norm = CASES[name]
    res = fitted(name)
    r, r0, a, c = res.r, res.r0, res.a, res.c
    assert c > 0 and r > 0 and r0 > 0 and a >= 0
    assert res.d == pytest.approx(r + r0, rel=1e-15)
    assert res.free_length == pytest.approx(free_length(kind, r, r0, a), rel=1e-12, abs=1e-15)
    # the largest spring force over the range, c·|L − l0|, from a dense sample and the range's ends
    phi = np.concatenate([dense_phi(lo, hi, r, r0), [lo, hi]])
    _, L = moment_from_positions(kind, c, r, r0, a, phi)
    force = c * np.max(np.abs(L - free_length(kind, r, r0, a)))
    assert res.max_force == pytest.approx(force, rel=1e-6)
    if kind == "compression":
        l0 = free_length(kind, r, r0, a)
        assert res.deflection == pytest.approx((l0 - np.min(L)) / l0, rel=1e-6, abs=1e-12)
    else:
        assert res.deflection is None
    # non-dimensional parameters: lengths over the longest crank allowed, κ = c·r·d / |Φ0|
    ell = bounds.r[1]
    assert res.reference_length == ell
    assert res.x == pytest.approx((r / ell, r0 / ell, a / ell, c * r * (r + r0) / abs(moment)), rel=1e-12)
    assert (res.sense, res.kind, res.norm, res.moment) == ((1 if kind == "compression" else -1), kind, norm, moment)
    # the sense in words, from the device's geometry: a compression spring pushes the crank away from C
    assert res.sense_text == ("away from the base point C (increasing φ)" if kind == "compression"
                              else "towards the base point C (decreasing φ)")
    # how the fit ended: exactly, or by a method, with the reason for not being exact
    if res.method == "exact":
        assert res.message == "zero free length (a = r0): exact" and res.max_rel_error < 1e-12
    elif kind == "tension" and method is None:
        assert "a zero free length (a = r0) is outside the bounds; fitted instead" in res.notes
    assert res.phi_range == (lo, hi)


@pytest.mark.parametrize("name", CASES)
def test_bounds_kept_and_active_bounds_true(name):
    kind, moment, (lo, hi), b, method, norm = CASES[name]
    res = fitted(name)
    tol = 1e-9
    for value, (low, high), label in ((res.r, b.r, "r"), (res.r0, b.r0, "r0"), (res.a, b.a, "a")):
        assert low * (1 - tol) - tol <= value <= high * (1 + tol) + tol, label
        at_low = abs(value - low) <= 1e-6 * max(1.0, abs(low))
        at_high = abs(value - high) <= 1e-6 * max(1.0, abs(high))
        assert (f"{label}=min" in res.active_bounds) == at_low, (label, value, res.active_bounds)
        assert (f"{label}=max" in res.active_bounds) == at_high, (label, value, res.active_bounds)
    if b.max_force is not None:
        assert res.max_force <= b.max_force * (1 + 1e-6)
        assert ("max_force" in res.active_bounds) == (abs(res.max_force - b.max_force) <= 1e-6 * b.max_force)
    if b.max_free_length is not None:
        assert res.free_length <= b.max_free_length * (1 + 1e-9)
        assert ("max_free_length" in res.active_bounds) == (
            abs(res.free_length - b.max_free_length) <= 1e-6 * max(1.0, b.max_free_length))
    if b.max_deflection is not None:
        assert res.deflection <= b.max_deflection * (1 + 1e-6)
    if kind == "tension":
        assert ("a=r0 (zero free length)" in res.active_bounds) == (abs(res.a - res.r0) <= 1e-6 * max(1.0, res.r0))


def test_exact_tension_device_is_exact():
    """The zero-free-length tension device reproduces −c·r·d·sin φ = Φ0·sin φ at every angle."""
    res = fitted("tension-exact")
    phi = np.linspace(-math.pi, math.pi, 10001)
    m, _ = moment_from_positions("tension", res.c, res.r, res.r0, res.a, phi)
    np.testing.assert_allclose(m, -100.0 * np.sin(phi), atol=1e-9 * 100.0)
    assert res.max_rel_error < 1e-12 and res.method == "exact"


# ------------------------------------------------------------------ the devices themselves
@pytest.mark.parametrize("kind, c, r, r0, a", [("tension", 800.0, 0.1, 0.25, 0.05), ("tension", 500.0, 0.2, 0.3, 0.3),
                                               ("compression", 1200.0, 0.15, 0.4, 0.02),
                                               ("compression", 900.0, 0.25, 0.5, 0.0)])  # free length exactly 1
def test_device_moment_length_force_from_positions(kind, c, r, r0, a):
    from balance import CrankRockerDevice, crank_moment, spring_length

    dev = CrankRockerDevice(kind, c, r, r0, a)
    phi = np.linspace(-2 * math.pi, 2 * math.pi, 2001)
    m, L = moment_from_positions(kind, c, r, r0, a, phi)
    np.testing.assert_allclose(dev.moment(phi), m, atol=1e-9 * c * r * (r + r0))
    np.testing.assert_allclose(crank_moment(phi, kind, c, r, r0, a), m, atol=1e-9 * c * r * (r + r0))
    np.testing.assert_allclose(dev.length(phi), L, rtol=1e-12)
    np.testing.assert_allclose(spring_length(phi, r, r0), L, rtol=1e-12)
    np.testing.assert_allclose(dev.force(phi), c * np.abs(L - free_length(kind, r, r0, a)), rtol=1e-9, atol=1e-9 * c)
    d = dev.to_dict()
    assert (d["kind"], d["c"], d["r"], d["r0"], d["a"]) == (kind, c, r, r0, a)
    assert d["d"] == pytest.approx(r + r0) and d["free_length"] == pytest.approx(free_length(kind, r, r0, a))
    assert (dev.d, dev.amplitude, dev.sense) == (pytest.approx(r + r0), pytest.approx(c * r * (r + r0)),
                                                 -1 if kind == "tension" else 1)


def test_spring_kind_refused_with_a_sentence():
    from balance import InvalidInput, crank_moment
    from balance.devices.springs import free_length as engine_free_length

    with pytest.raises(InvalidInput) as info:
        engine_free_length("torsion", 0.1, 0.2, 0.0)
    assert str(info.value) == "spring kind must be one of tension, compression, compression-lever, not 'torsion'."
    with pytest.raises(InvalidInput):
        crank_moment(0.3, "torsion", 1.0, 0.1, 0.2, 0.0)


def test_sine_device_from_its_definition():
    from balance import SineDevice

    dev = SineDevice(0.04, 250.0)
    phi = np.linspace(-math.pi, math.pi, 101)
    np.testing.assert_allclose(dev.moment(phi), -0.04 * 250.0 * np.sin(phi), atol=1e-12)
    assert dev.amplitude == pytest.approx(10.0)


def test_textbook_length_is_the_law_of_cosines():
    from balance.devices.springs import spring_length_textbook

    phi = np.linspace(-math.pi, math.pi, 721)
    for r, r0 in ((0.1, 0.25), (0.3, 0.05), (0.02, 1.0)):
        _, L = moment_from_positions("tension", 1.0, r, r0, 0.0, phi)
        np.testing.assert_allclose(spring_length_textbook(phi, r, r0), L, rtol=1e-9)


def test_crank_pin_on_the_base_point():
    """r0 = 0: at φ = 0 the pin sits on C, the spring has no direction and the moment is 0 (finite)."""
    from balance import crank_moment

    phi = np.array([0.0, 1e-3, 0.5, -0.5])
    got = crank_moment(phi, "compression", 1000.0, 0.2, 0.0, 0.05)
    assert np.all(np.isfinite(got)) and got[0] == 0.0
    m, _ = moment_from_positions("compression", 1000.0, 0.2, 0.0, 0.05, phi[1:])
    np.testing.assert_allclose(got[1:], m, rtol=1e-9)


# ------------------------------------------------------------------ the solver's inner pieces
@pytest.mark.parametrize("seed", range(6))
def test_minimax_scale_against_a_dense_search(seed):
    """``_minimax_scale`` minimises max|κ·h − s| over 0 ≤ κ ≤ κmax: no κ of a dense grid does better,
    also where the optimum lies far above 1 (small h) or on κmax."""
    from balance.devices.fit import _minimax_scale

    from scipy.optimize import linprog

    rng = np.random.default_rng(seed)
    h = rng.uniform(0.0, 1.0, 40) * 10.0 ** rng.uniform(-3, 1)
    s = rng.uniform(0.0, 1.0, 40) * 10.0 ** rng.uniform(-2, 3)
    crossing_scale = float(np.max(s) / np.max(h))
    for kmax in (0.3 * crossing_scale, 50.0 * crossing_scale + 1.0):
        k = _minimax_scale(h, s, kmax)
        assert 0.0 <= k <= kmax
        err = float(np.max(np.abs(k * h - s)))
        grid = np.linspace(0.0, kmax, 20001)
        best = np.min(np.max(np.abs(grid[:, None] * h[None, :] - s[None, :]), axis=1))
        assert err <= best + 1e-9 * max(1.0, float(np.max(s)))
        # the exact optimum, as a linear programme in (κ, t): min t, −t ≤ κ·h_i − s_i ≤ t, 0 ≤ κ ≤ κmax
        lp = linprog([0.0, 1.0], A_ub=np.block([[h[:, None], -np.ones((40, 1))], [-h[:, None], -np.ones((40, 1))]]),
                     b_ub=np.concatenate([s, -s]), bounds=[(0.0, kmax), (0.0, None)], method="highs")
        assert lp.status == 0 and err <= lp.fun * (1 + 1e-9) + 1e-12 * float(np.max(s))
        if k < kmax:  # inside: where the largest overshoot meets the largest undershoot, to round-off
            up = k * h - s
            i, j = int(np.argmax(up)), int(np.argmin(up))
            assert k == pytest.approx((s[i] + s[j]) / (h[i] + h[j]), rel=1e-14)


def test_minimax_scale_without_any_lever():
    """h = 0 everywhere (or no points): every κ is as good, and the answer is κ = 0, inside the bounds."""
    from balance.devices.fit import _minimax_scale

    assert _minimax_scale(np.zeros(5), np.ones(5), 0.5) == 0.0
    assert _minimax_scale(np.zeros(0), np.zeros(0), 0.5) == 0.0


def test_exact_tension_device_has_the_least_force_of_the_corner_devices():
    """Among zero-free-length tension devices (a = r0) the fit reports the least peak force: no device
    at a corner of the bounds needs less (each corner fitted alone, its force from positions)."""
    rng = deg(10, 170)
    b = SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.6), a=(0.0, 1.0))
    best = fit_spring("tension", -50.0, rng, b)
    assert best.method == "exact"
    phi = np.linspace(*rng, 4001)

    def peak_force(res):
        _, L = moment_from_positions("tension", res.c, res.r, res.r0, res.a, phi)
        return float(np.max(np.abs(res.c * (L - free_length("tension", res.r, res.r0, res.a)))))

    assert best.max_force == pytest.approx(peak_force(best), rel=1e-6)
    corners = []
    for r in b.r:
        for r0 in b.r0:
            one = fit_spring("tension", -50.0, rng, SpringBounds(r=(r, r), r0=(r0, r0), a=(r0, r0)))
            assert one.method == "exact"
            corners.append(peak_force(one))
    assert peak_force(best) <= min(corners) * (1 + 1e-9)


def test_fit_result_as_a_dictionary():
    """``FitResult.to_dict`` (the JSON of ``balance spring``): every field, the range also in degrees."""
    res = fitted("tension-exact")
    d = res.to_dict()
    assert d["phi_range_deg"] == pytest.approx([0.0, 180.0])
    assert d["phi_range"] == list(res.phi_range) and d["x"] == list(res.x)
    assert isinstance(d["x"], list) and isinstance(d["phi_range"], list)
    assert {"c", "r", "r0", "a", "max_force", "max_rel_error", "method"} <= d.keys()
    assert d["c"] == res.c and d["max_force"] == res.max_force


# -------------------------------------------------------------- the search's own helpers
def test_exact_tension_device_under_a_force_limit():
    """With r ≤ 0.5, r0 ≤ 1 and a free up to 1, the least-force zero-free-length device over 0…180°
    is the corner r = 0.5, r0 = 1 (force |M|·(2r + r0)/(r(r + r0)) falls as either grows): 266.7 N
    for 100 N·m.  A 300 N limit keeps it, and it is reported exact; a 250 N limit leaves no exact
    device at all, so the spring is fitted."""
    rng = deg(0, 180)
    corner = 100.0 * (2 * 0.5 + 1.0) / (0.5 * 1.5)
    kept = fit_spring("tension", -100.0, rng, SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0),
                                                              max_force=300.0))
    assert kept.method == "exact" and (kept.r, kept.r0, kept.a) == pytest.approx((0.5, 1.0, 1.0))
    phi = np.linspace(*rng, 4001)
    _, L = moment_from_positions("tension", kept.c, kept.r, kept.r0, kept.a, phi)
    assert float(np.max(kept.c * L)) == pytest.approx(corner, rel=1e-9) and corner < 300.0
    refused = fit_spring("tension", -100.0, rng, SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0),
                                                                 max_force=250.0))
    assert refused.method != "exact" and refused.max_force <= 250.0 * (1 + 1e-6)


def test_differential_evolution_is_repeatable():
    """The global method is seeded: the same call gives the same device, digit for digit."""
    one, two = (fit_spring("compression", 3.0, deg(30, 150), ISSUE, method="de", norm="rms") for _ in range(2))
    assert (one.c, one.r, one.r0, one.a) == (two.c, two.r, two.r0, two.a)


@pytest.mark.parametrize("lo, hi", [(-0.5, 0.5), (-7.0, -5.0), (10.0, 14.0), (-1.0, 2 * math.pi + 1.0), (-0.2, 1.0)])
def test_cluster_points_hug_every_multiple_of_two_pi_in_range(lo, hi):
    """Where φ = 0 (mod 2π) lies in the range, the max-norm fit adds points on both sides of it,
    geometrically spaced from a tenth of the width to 0.5 rad, 24 on a side, never outside the range."""
    from balance.devices.fit import _cluster

    width = 0.01
    pts = _cluster(lo, hi, width, 24)
    assert len(pts) and np.all((pts >= lo) & (pts <= hi))
    centres = [2 * math.pi * k for k in range(-5, 5) if lo <= 2 * math.pi * k <= hi]
    assert centres
    near = [pts[np.abs(pts - c) <= 0.5 + 1e-12] - c for c in centres]
    assert sum(len(d) for d in near) == len(pts)  # every point belongs to a multiple of 2π in range
    for c, d in zip(centres, near):
        for side, room in ((d[d > 0], hi - c), (-d[d < 0], c - lo)):
            offsets = np.sort(side)
            assert offsets[0] == pytest.approx(width / 10)
            if room >= 0.5:
                assert len(offsets) == 24 and offsets[-1] == pytest.approx(0.5)
                assert np.allclose(offsets[1:] / offsets[:-1], (0.5 / (width / 10)) ** (1 / 23))


def test_cluster_ends_width_and_empty_cases():
    """The range ends are kept when points fall on them; a width of 0.05 still clusters, a wider
    one does not (the grid resolves it); no multiple of 2π in range, no points."""
    from balance.devices.fit import _cluster

    pts = _cluster(-0.5, 0.5, 0.01, 24)
    assert -0.5 in pts and 0.5 in pts
    assert len(_cluster(-0.5, 0.5, 0.05, 24)) == 48
    assert len(_cluster(-0.5, 0.5, 0.06, 24)) == 0 and len(_cluster(-0.5, 0.5, 0.5, 24)) == 0
    assert len(_cluster(0.1, 2 * math.pi - 0.2, 0.01, 24)) == 0



def test_exact_tension_device_when_short_springs_are_out_of_bounds():
    """A pre-extension of at least 0.2 m rules out every zero-free-length device with r0 < 0.2 m (a = r0):
    the search passes over them to the longer ones, and the device is still exact."""
    res = fit_spring("tension", -100.0, deg(0, 180), SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.2, 1.0)))
    assert res.method == "exact" and res.a == res.r0 and res.r0 >= 0.2 and res.max_rel_error < 1e-12


@pytest.mark.parametrize("method", ["trf", "slsqp", "nelder-mead", "de"])
def test_a_fixed_preload_is_kept_by_every_method(method):
    """A range of one value fixes a: every method keeps it to the last digit and reaches the
    same optimum over r and r0."""
    b = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.25, 0.25))
    res = fit_spring("compression", 100.0, deg(20, 160), b, method=method, norm="rms")
    ref = fit_spring("compression", 100.0, deg(20, 160), b, method="slsqp", norm="rms")
    assert res.a == 0.25
    assert res.grid_rms_rel_error == pytest.approx(ref.grid_rms_rel_error, rel=1e-7)


def test_the_normalised_variables_round_trip():
    """α is carried as t ∈ [0, 1] between its limits given (ρ, ρ0): decode(encode(ρ, ρ0, α)) gives
    α back inside its limits, clips it outside them, and a range of one value maps to its value."""
    from balance.devices.fit import _Problem

    b = SpringBounds(FORCED.r, FORCED.r0, (0.1, 1.0), FORCED.max_force, FORCED.max_free_length, FORCED.max_deflection)
    p = _Problem("compression", 100.0, *deg(20, 160), b, 61, "max")  # (α's lower limit above 0)
    rng = np.random.default_rng(7)
    for _ in range(50):
        rho, rho0 = rng.uniform(*p.rho_b), rng.uniform(*p.rho0_b)
        lo, hi = p.alpha_limits(rho, rho0)
        if hi <= lo:
            continue
        al = rng.uniform(lo, hi)
        assert p.decode(p.encode(rho, rho0, al)) == pytest.approx((rho, rho0, al, 0.0), rel=1e-12)
        assert p.encode(rho, rho0, hi + 1.0)[2] == 1.0 and p.encode(rho, rho0, lo - 1.0)[2] == 0.0
    fixed = _Problem("compression", 100.0, *deg(20, 160), SpringBounds((0.01, 0.5), (0.01, 1.0), (0.25, 0.25)), 61, "max")
    z = fixed.encode(0.1, 0.5, 0.5)
    assert z[2] == 0.0 and fixed.decode(z) == (0.1, 0.5, 0.5, 0.0)


@pytest.mark.parametrize("method, norm, words", [
    ("trf", "rms", "termination condition"), ("trf", "max", "^least_squares \\(trf\\) with Lawson reweighting for the max norm(; restarted 1× from its point "
                   "\\(Nelder–Mead, then SLSQP\\): a local optimum to 1e-09 of the error)?$"),
    ("slsqp", "max", "^SLSQP: Optimization terminated successfully$"), ("nelder-mead", "max", "Optimization terminated"),
    ("de", "max", "^differential_evolution \\(seed 12345\\) polished by SLSQP$"),
])
def test_each_method_says_how_it_ended(method, norm, words):
    res = fit_spring("compression", 100.0, deg(20, 160), ISSUE, method=method, norm=norm)
    assert re.search(words, res.message) and res.method == method


@pytest.mark.parametrize("method", ["trf", "slsqp", "nelder-mead"])
def test_every_method_finds_an_exact_tension_device_within_a_force_limit(method):
    """With 400 N allowed exact zero-free-length devices exist (the exact search shows the least-force
    one): every method finds one within the limit (they stop at shorter cranks than the longest)."""
    b = SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.6), a=(0.0, 1.0), max_force=400.0)
    exact = fit_spring("tension", -50.0, deg(20, 160), b)
    assert exact.method == "exact" and exact.max_force <= 400.0
    res = fit_spring("tension", -50.0, deg(20, 160), b, method=method)
    assert res.max_rel_error < 1e-9 and res.max_force <= 400.0 * (1 + 1e-9)


def test_reported_evaluations_and_time(monkeypatch):
    """``nfev`` counts every evaluation of the errors on the fit grid (every method's, and the final
    one) and ``seconds`` is the fit's own time, within the time the call took."""
    import time

    from balance.devices import fit

    calls = {"n": 0}
    original = fit._Problem.errors

    def counted(self, *args):
        calls["n"] += 1
        return original(self, *args)

    monkeypatch.setattr(fit._Problem, "errors", counted)
    for method in ("trf", "slsqp", "nelder-mead", "de"):
        calls["n"] = 0
        start = time.perf_counter()
        res = fit_spring("compression", 100.0, deg(20, 160), FORCED, method=method)
        took = time.perf_counter() - start
        assert 0 < res.seconds <= took
        assert res.nfev > 10 and res.nfev == calls["n"], method


def test_the_steep_note_only_where_r0_is_short_and_zero_is_in_range():
    plain = fit_spring("compression", 100.0, deg(0, 180), ISSUE)  # r0/r = 100 at the optimum
    assert not any("steeply" in n for n in plain.notes)
    middling = fitted("compression-steep-near-0")  # r0/r = 0.2 with 0 in the range: not steep
    assert middling.r0 / middling.r == pytest.approx(0.2) and not any("steeply" in n for n in middling.notes)
    tiny = SpringBounds(r=(0.05, 0.5), r0=(1e-9, 1e-6), a=(0.0, 1.0))
    short = fit_spring("compression", 100.0, deg(-30, 120), tiny)
    ratio = short.r0 / short.r
    (note,) = [n for n in short.notes if "steeply" in n]
    assert note.startswith(f"r0/r = {ratio:.3g} with φ = 0 in the range: the moment changes steeply within "
                           f"|φ| ≲ {math.degrees(ratio):.3g}° of 0")
    away = fit_spring("compression", 100.0, deg(20, 120), tiny)  # r0 short, but 0 is out of range
    assert not any("steeply" in n for n in away.notes)


@pytest.mark.parametrize("seed", range(3))
def test_range_extremes_against_a_dense_sample(seed):
    """The extremes of sin²(φ/2) (spring length) and of |sin φ| (the target's peak) over [lo, hi]
    that feasibility and force limits use: against a dense sample, for ranges anywhere on the line,
    with multiples of π/2 inside, at an end and just outside."""
    from balance.devices.fit import _max_abs_sin, _sin2_half_extremes

    rng = np.random.default_rng(seed)
    ranges = [(lo, lo + w) for lo, w in zip(rng.uniform(-4 * math.pi, 4 * math.pi, 60), rng.uniform(1e-3, 2 * math.pi, 60))]
    ranges += [(k * math.pi / 2 + e0, k * math.pi / 2 + e1) for k in range(-5, 6)
               for e0, e1 in ((0.0, 0.3), (-0.3, 0.0), (1e-9, 0.3), (-0.3, -1e-9))]
    for lo, hi in ranges:
        phi = np.concatenate([np.linspace(lo, hi, 200001), [lo, hi]])
        s2 = np.sin(phi / 2) ** 2
        got = _sin2_half_extremes(lo, hi)
        assert got[0] == pytest.approx(s2.min(), abs=1e-9) and got[1] == pytest.approx(s2.max(), abs=1e-9), (lo, hi)
        assert _max_abs_sin(lo, hi) == pytest.approx(np.abs(np.sin(phi)).max(), abs=1e-9), (lo, hi)


@pytest.mark.parametrize("a_min", [0.0, 0.05])
def test_free_length_limit_at_the_shortest_compression_device(a_min):
    """The shortest compression device has free length 2·r_min + r0_min + a_min: a limit exactly there
    leaves that one device (fitted, on the limit), a limit 1 % below leaves none (refused, saying so)."""
    b = dict(r=(0.1, 0.5), r0=(0.2, 1.0), a=(a_min, 1.0))
    shortest = 2 * 0.1 + 0.2 + a_min
    res = fit_spring("compression", 100.0, deg(20, 160), SpringBounds(**b, max_free_length=shortest))
    assert (res.r, res.r0, res.a) == pytest.approx((0.1, 0.2, a_min), abs=1e-9)
    assert res.free_length == pytest.approx(shortest, rel=1e-12)
    with pytest.raises(InfeasibleBounds, match=f"free length 2r\\+r0\\+a = {shortest:g} m, more than"):
        fit_spring("compression", 100.0, deg(20, 160), SpringBounds(**b, max_free_length=0.99 * shortest))


def _uniform_fit_grid(name):
    """The cases whose fit grid is the uniform one (RMS, or a range without a multiple of 2π, where the
    max-norm grid gets no extra points)."""
    _, _, (lo, hi), _, _, norm = CASES[name]
    return norm == "rms" or math.floor(hi / (2 * math.pi)) < math.ceil(lo / (2 * math.pi))


@pytest.mark.parametrize("name", [n for n in CASES if _uniform_fit_grid(n)])
def test_spring_rate_is_the_best_for_the_returned_geometry(name):
    """The rate c enters the moment linearly: for the returned r, r0, a the best c on the fit grid is a
    least-squares quotient (RMS) or a linear programme (max), capped where the force limit allows no
    more (c·max|L − l0| ≤ F).  The fit's c is that one."""
    from scipy.optimize import linprog

    kind, moment, (lo, hi), bounds, method, norm = CASES[name]
    res = fitted(name)
    phi = np.linspace(lo, hi, res.grid)
    unit, _ = moment_from_positions(kind, 1.0, res.r, res.r0, res.a, phi)  # moment per unit rate
    target = moment * np.sin(phi)
    limit = np.inf
    if bounds.max_force is not None:
        dense = np.concatenate([dense_phi(lo, hi, res.r, res.r0), [lo, hi]])
        lengths = moment_from_positions(kind, 1.0, res.r, res.r0, res.a, dense)[1]
        limit = bounds.max_force / np.max(np.abs(lengths - free_length(kind, res.r, res.r0, res.a)))
    if norm == "rms":
        best = min(float(np.sum(unit * target) / np.sum(unit * unit)), limit)
    else:
        rows = len(phi)
        lp = linprog([0.0, 1.0], A_ub=np.block([[unit[:, None], -np.ones((rows, 1))], [-unit[:, None], -np.ones((rows, 1))]]),
                     b_ub=np.concatenate([target, -target]), bounds=[(0.0, limit), (0.0, None)], method="highs")
        assert lp.status == 0
        best = lp.x[0]
    assert res.c == pytest.approx(best, rel=1e-7)

