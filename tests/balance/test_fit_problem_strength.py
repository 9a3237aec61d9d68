"""balance/devices/fit/problem.py against values found without it, fast enough to judge its mutants
(each case well under a second): the weighted errors against the moment of the device built from
positions, the potential of the balanced crank constant for the exact device, the scale κ against a
dense search and a weighted least-squares solve, the limits of α and κ against the spring's length and
force sampled densely, the extremes of sin²(φ/2) and |sin φ| against dense samples, the start scan
against the corners of its box, SLSQP's constraints at chosen points, and every refusal in full."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import SpringBounds
from balance.devices.fit.problem import (_check_feasible, _cluster, _max_abs_sin, _Problem, _sin2_half_extremes,
                                         _span, best_scale)
from balance.errors import InfeasibleBounds, InvalidRange
from tests.balance.test_fit_vs_oracle import free_length, moment_from_positions

LEVER = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3))


def problem(kind="compression", moment=80.0, lo=0.3, hi=2.6, b=LEVER, grid=41, norm="rms"):
    return _Problem(kind, moment, lo, hi, b, grid, norm)


def dense(lo, hi, n=20001):
    return np.linspace(lo, hi, n)


def device(p, rho, rho0, al, kappa):
    """The physical device of the non-dimensional point: lengths times ℓ, c = κ·|Φ0|/(r·d)."""
    r, r0, a = rho * p.ell, rho0 * p.ell, al * p.ell
    return p.kind, kappa * abs(p.moment) / (r * (r + r0)), r, r0, a


# ---------------------------------------------------------------- the errors and the objective
@pytest.mark.parametrize("kind, moment, point", [
    ("compression", 80.0, (0.4, 0.9, 0.2, 1.3)),
    ("compression", 80.0, (1.0, 0.25, 0.0, 0.7)),
    ("tension", -60.0, (0.5, 1.5, 0.3, 0.9)),
    ("tension", -60.0, (0.3, 1.0, 1.0, 1.0)),     # a = r0: the exact device
])
def test_the_errors_are_the_devices_relative_errors(kind, moment, point):
    """|errors| = |M(φ) − Φ0·sin φ|/|Φ0| with M from positions; each error's sign that of κg − 1."""
    p = problem(kind, moment, lo=-0.7, hi=2.9, grid=37)
    assert p.ell == 0.4 and p.grid == 37
    np.testing.assert_array_equal(p.phi, np.linspace(-0.7, 2.9, 37))
    e = p.errors(*point)
    m, _ = moment_from_positions(*device(p, *point), p.phi)
    np.testing.assert_allclose(np.abs(e), np.abs(m - moment * np.sin(p.phi)) / abs(moment), atol=1e-12)
    # the sign: that of the moment's excess over the target, times the signs of sin φ and of Φ0
    np.testing.assert_allclose(e * np.sign(np.sin(p.phi)) * np.sign(moment), (m - moment * np.sin(p.phi)) / abs(moment), atol=1e-12)
    assert p.nfev == 1 and p.errors(*point) is not None and p.nfev == 2


def test_the_free_length_of_each_spring():
    for kind in ("compression", "tension"):
        p = problem(kind, 80.0 if kind == "compression" else -80.0)
        assert p.l0(0.3, 0.7, 0.2) == pytest.approx(free_length(kind, 0.3, 0.7, 0.2), rel=1e-15)


def test_the_exact_tension_device_keeps_the_crank_in_balance():
    """a = r0, κ = 1: the spring supplies M = Φ0·sin φ = −dE/dφ against a load of potential −Φ0·cos φ,
    so its energy c/2·(L − l0)² plus the load's is the same at random angles, and the errors vanish."""
    p = problem("tension", -60.0, lo=-3.0, hi=3.0)
    _, c, r, r0, a = device(p, 0.6, 1.4, 1.4, 1.0)
    phi = np.random.default_rng(3).uniform(-3.0, 3.0, 50)
    _, L = moment_from_positions("tension", c, r, r0, a, phi)
    total = 0.5 * c * (L - (r0 - a)) ** 2 - (-60.0) * np.cos(phi)
    assert np.ptp(total) < 1e-9 * 60.0 and np.ptp(L) > 0.1
    assert np.max(np.abs(p.errors(0.6, 1.4, 1.4, 1.0))) < 1e-12


def test_the_objective_by_hand():
    p = problem(grid=21)
    z = np.array([0.5, 0.8, 0.4])
    rho, rho0, al, viol = p.decode(z)
    assert viol == 0.0
    for norm in ("rms", "max"):
        k = p.best_kappa(rho, rho0, al, norm)
        e = p.errors(rho, rho0, al, k)
        want = np.sqrt(np.mean(e ** 2)) if norm == "rms" else np.max(np.abs(e))
        assert p.objective(z, norm) == pytest.approx(want, rel=1e-14)
        got, kk, v = p.projected(z, norm)
        assert kk == k and v == 0.0 and np.array_equal(got, e)


def test_a_violation_costs_ten_times_its_size():
    """With a free length of at most 0.2 ℓ·… no α fits a long crank: the objective is the error plus 10× the gap."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3), max_free_length=0.5)
    p = problem(b=b, grid=21)
    z = np.array([1.0, 2.0, 0.5])                   # 2ρ + ρ0 = 4 > Lf = 1.25
    rho, rho0, al, viol = p.decode(z)
    assert (rho, rho0) == (1.0, 2.0) and al == 0.0 and viol == pytest.approx(0.0 - (1.25 - 4.0), rel=1e-14)
    for norm in ("rms", "max"):
        e = p.errors(rho, rho0, al, p.best_kappa(rho, rho0, al, norm))
        plain = np.sqrt(np.mean(e ** 2)) if norm == "rms" else np.max(np.abs(e))
        assert p.objective(z, norm) == pytest.approx(plain + 10 * 2.75, rel=1e-14)


def test_the_max_norm_sees_the_steep_part_near_a_dead_centre():
    """Where φ = 0 is in range and r0/r is small, the max norm's grid gains points clustered at 0."""
    b = SpringBounds(r=(0.05, 0.5), r0=(1e-3, 0.1), a=(0.0, 0.3))
    rms, mx = problem(b=b, lo=-0.5, hi=1.0, norm="rms"), problem(b=b, lo=-0.5, hi=1.0, norm="max")
    assert len(rms.phi) == 41 and len(mx.phi) == 41 + 47    # 24 on each side of 0, −0.5 the range's end
    assert np.all(np.diff(mx.phi) > 0) and set(rms.phi) <= set(mx.phi)
    assert np.min(np.abs(mx.phi)) == pytest.approx(1e-3 / 0.5 * 0.1, rel=1e-12)
    np.testing.assert_allclose(mx.w, np.abs(np.sin(mx.phi)), rtol=1e-15)
    np.testing.assert_allclose(mx.S, np.sin(mx.phi / 2) ** 2, rtol=1e-15)
    assert len(problem(b=b, lo=0.5, hi=2.0, norm="max").phi) == 41       # 0 out of range: nothing added


# ---------------------------------------------------------------- the scale κ
def test_the_rms_scale_is_the_least_squares_one():
    rng = np.random.default_rng(5)
    h, v = rng.uniform(0.2, 1.0, 30), rng.uniform(0.1, 1.0, 30)
    s = 2.0 * h + rng.normal(scale=0.5, size=30)
    k = float(np.linalg.lstsq(h[:, None], s, rcond=None)[0][0])
    kw = float(np.linalg.lstsq((np.sqrt(v) * h)[:, None], np.sqrt(v) * s, rcond=None)[0][0])
    assert k > 0 and kw > 0 and abs(k - kw) > 1e-3
    assert best_scale(h, s, 1e9, "rms") == pytest.approx(k, rel=1e-12)
    assert best_scale(h, s, 1e9, "rms", v) == pytest.approx(kw, rel=1e-12)
    assert best_scale(h, s, 0.5 * k, "rms") == 0.5 * k          # at most κmax
    assert best_scale(-h, s, 1e9, "rms") == 0.0                 # at least 0
    assert best_scale(np.zeros(4), np.ones(4), 3.0, "rms") == 0.0


def test_the_max_scale_against_a_dense_search():
    rng = np.random.default_rng(8)
    h, s = rng.uniform(0.2, 1.0, 25), rng.uniform(0.5, 2.0, 25)
    grid = np.linspace(0.0, 10.0, 100001)
    worst = np.max(np.abs(grid[:, None] * h - s), axis=1)
    k = best_scale(h, s, 10.0, "max")
    assert np.max(np.abs(k * h - s)) <= worst.min() + 1e-12
    assert k == pytest.approx(grid[np.argmin(worst)], abs=2e-4)
    assert best_scale(h, s, 0.5, "max") == 0.5
    # terms of either sign (|κh − s| = |κ(−h) − (−s)|), against the same dense search
    hm, sm = np.concatenate([h, -h[:5]]), np.concatenate([s, -s[:5] + 0.3])
    k = best_scale(hm, sm, 10.0, "max")
    assert np.max(np.abs(k * hm - sm)) <= np.min(np.max(np.abs(grid[:, None] * hm - sm), axis=1)) + 1e-12


def test_the_max_scale_where_nothing_lifts():
    """No points, no lever (h = 0), or the largest overshoot already beyond the undershoot at κ = 0: κ = 0."""
    assert best_scale(np.zeros(0), np.zeros(0), 5.0, "max") == 0.0
    assert best_scale(np.zeros(4), np.ones(4), 5.0, "max") == 0.0
    assert best_scale(np.ones(3), -np.ones(3), 5.0, "max") == 0.0
    # max(|κ − 1|, |κ + 3|) over κ ≥ 0 is least at 0 (3), where it is 3 + κ beyond
    assert best_scale(np.array([1.0, 1.0]), np.array([1.0, -3.0]), 5.0, "max") == 0.0


def test_the_problems_scale_minimises_its_norm():
    """best_kappa: no κ of a dense grid gives a smaller weighted error, and the force limit caps it."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3), max_force=900.0)
    p = problem(b=b, grid=31)
    point = (0.5, 0.9, 0.25)
    cap = p.kappa_max(*point)
    ks = np.linspace(0.0, cap, 4001)
    for norm, f in (("rms", lambda e: np.sqrt(np.mean(e ** 2))), ("max", lambda e: np.max(np.abs(e)))):
        k = p.best_kappa(*point, norm)
        assert 0.0 <= k <= cap
        assert f(p.errors(*point, k)) <= min(f(p.errors(*point, kk)) for kk in ks) + 1e-12
    v = np.linspace(1.0, 3.0, len(p.phi))
    kw = p.best_kappa(*point, "rms", v)
    h, t = p.w * p.shape(*point), p.w
    assert kw == pytest.approx(np.sum(v * h * t) / np.sum(v * h * h), rel=1e-12)


# ---------------------------------------------------------------- the limits of α and κ
@pytest.mark.parametrize("lo, hi", [(0.3, 2.6), (-0.4, 1.0), (2.0, 4.0), (-3.5, -2.0), (8.0, 10.0), (-10.0, -8.0),
                                    (11.0, 14.0)])
def test_the_extremes_of_the_spring_length(lo, hi):
    s = np.sin(dense(lo, hi, 200001) / 2) ** 2
    assert _sin2_half_extremes(lo, hi) == pytest.approx((s.min(), s.max()), abs=1e-9)
    a = np.abs(np.sin(dense(lo, hi, 200001)))
    assert _max_abs_sin(lo, hi) == pytest.approx(a.max(), abs=1e-9)


def test_the_extremes_at_their_edges():
    """A multiple of π/2 exactly at an end counts; the ends alone where none lies inside."""
    assert _max_abs_sin(0.0, math.pi / 2) == 1.0 and _max_abs_sin(math.pi / 2, 3.0) == 1.0
    assert _max_abs_sin(-math.pi / 2, -1.0) == 1.0
    assert _max_abs_sin(0.2, 0.5) == math.sin(0.5) and _max_abs_sin(2.0, 3.0) == math.sin(2.0)
    assert _sin2_half_extremes(0.0, 1.0) == (0.0, math.sin(0.5) ** 2)
    assert _sin2_half_extremes(1.0, math.pi) == (math.sin(0.5) ** 2, 1.0)
    assert _sin2_half_extremes(-1.0, -0.5) == (math.sin(0.25) ** 2, math.sin(0.5) ** 2)
    assert _sin2_half_extremes(2 * math.pi, 7.0) == (0.0, math.sin(3.5) ** 2)


def spring_lengths(p, rho, rho0):
    """The spring's length over the range sampled densely (units of ℓ), from positions."""
    _, L = moment_from_positions("tension", 1.0, rho, rho0, 0.0, dense(p.lo, p.hi))
    return L


def test_the_compression_alpha_limits_by_their_definitions():
    """α ≤ its bound, the free length 2ρ + ρ0 + α ≤ Lf and the deflection (l0 − Lmin)/l0 ≤ δ: the largest α is
    where the first of them binds."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.02, 0.3), max_free_length=1.0, max_deflection=0.3)
    p = problem(b=b)
    for rho, rho0 in ((0.3, 0.5), (0.8, 1.2), (0.2, 1.9)):
        lmin = spring_lengths(p, rho, rho0).min()
        lo, hi = p.alpha_limits(rho, rho0)
        want = min(0.3 / 0.4, 1.0 / 0.4 - 2 * rho - rho0, lmin / 0.7 - 2 * rho - rho0)
        assert lo == 0.02 / 0.4 and hi == pytest.approx(want, rel=1e-6)


def test_the_tension_alpha_limits_by_their_definitions():
    """α ≤ ρ0 (free length ≥ 0) and ρ0 − α ≤ Lf."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 2.0), max_free_length=0.2)
    p = problem("tension", -60.0, b=b)
    assert p.alpha_limits(0.5, 1.0) == (pytest.approx(0.5), 1.0)
    assert p.alpha_limits(0.5, 0.3) == (0.0, 0.3)
    assert problem("tension", -60.0).alpha_limits(0.5, 1.0) == (0.0, pytest.approx(0.75, rel=1e-15))


def test_a_device_exactly_on_a_limit_is_kept():
    """Round-off that puts α's upper limit a hair under the lower one gives the one α of the limit."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.1, 0.3), max_free_length=0.1 + 0.4 * 1.3 - 1e-14)
    p = problem(b=b)
    lo, hi = p.alpha_limits(0.5, 0.3)   # 2ρ + ρ0 = 1.3: room for α = 0.25 less a few 1e-14
    assert lo == hi == 0.25
    far = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.1, 0.3), max_free_length=0.1 + 0.4 * 1.3 - 1e-6)
    lo, hi = problem(b=far).alpha_limits(0.5, 0.3)
    assert hi < lo == 0.25


@pytest.mark.parametrize("kind, moment, al", [("compression", 80.0, 0.3), ("tension", -60.0, 0.1)])
def test_the_largest_scale_is_where_the_spring_force_reaches_its_limit(kind, moment, al):
    """At κmax the largest spring force over the range, c·|L − l0| sampled densely, is the force limit."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3), max_force=700.0)
    p = problem(kind, moment, b=b)
    rho, rho0 = 0.6, 1.2
    km = p.kappa_max(rho, rho0, al)
    _, c, r, r0, a = device(p, rho, rho0, al, km)
    _, L = moment_from_positions(kind, c, r, r0, a, dense(p.lo, p.hi))
    assert c * np.max(np.abs(L - free_length(kind, r, r0, a))) == pytest.approx(700.0, rel=1e-6)
    assert problem(kind, moment).kappa_max(rho, rho0, al) == math.inf


def test_no_force_limit_where_the_spring_never_works():
    """A spring whose stretch never leaves zero over the range (a tension spring shorter than its free
    length throughout) sets no limit on κ."""
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3), max_force=700.0)
    p = problem("tension", -60.0, lo=-0.2, hi=0.2, b=b)
    assert p.kappa_max(0.1, 2.0, -1.0) == math.inf   # l0 = 3 > the longest spring


# ---------------------------------------------------------------- variables
def test_decode_and_encode_are_inverse_and_clip_the_unit_variable():
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.02, 0.3), max_free_length=1.0)
    p = problem(b=b)
    lo, hi = p.alpha_limits(0.3, 0.9)
    assert p.decode([0.3, 0.9, 0.25]) == (0.3, 0.9, pytest.approx(lo + 0.25 * (hi - lo)), 0.0)
    assert p.decode([0.3, 0.9, -2.0])[2] == lo and p.decode([0.3, 0.9, 7.0])[2] == pytest.approx(hi)
    np.testing.assert_allclose(p.encode(0.3, 0.9, lo + 0.6 * (hi - lo)), [0.3, 0.9, 0.6], rtol=1e-12)
    assert p.encode(0.3, 0.9, hi + 1.0)[2] == 1.0 and p.encode(0.3, 0.9, lo - 1.0)[2] == 0.0
    assert p.encode(0.3, 2.0, 0.1)[2] == 0.0          # no room for α (hi < lo): t = 0
    np.testing.assert_allclose(p.encode_full([0.3, 0.9, lo + 0.6 * (hi - lo), 5.0]), [0.3, 0.9, 0.6], rtol=1e-12)


def test_the_box_of_the_variables():
    assert problem().z_bounds == ([0.125, 0.25, 0.0], [1.0, 2.0, 1.0])
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.1), max_free_length=0.1)
    assert problem("tension", -60.0, b=b).z_bounds == ([0.125, 0.25, 0.0], [1.0, 0.5, 1.0])


def test_the_start_is_the_best_corner_or_better():
    """The scan covers the box's corners (and points between): its best is no worse than any corner."""
    for kind, moment in (("compression", 80.0), ("tension", -60.0)):
        p = problem(kind, moment, grid=21)
        (r_lo, r0_lo, _), (r_hi, r0_hi, _) = p.z_bounds
        for norm in ("rms", "max"):
            z = p.start(norm)
            corners = [p.objective(np.array([r, r0, t]), norm) for r in (r_lo, r_hi) for r0 in (r0_lo, r0_hi)
                       for t in (0.0, 0.5, 1.0)]
            assert p.objective(z, norm) <= min(corners)
            assert r_lo <= z[0] <= r_hi and r0_lo <= z[1] <= r0_hi and z[2] in (0.0, 0.5, 1.0)


def test_the_scan_spacing():
    np.testing.assert_allclose(_span(0.01, 1.0, 3), [0.01, 0.1, 1.0], rtol=1e-12)    # a ratio above 10: logarithmic
    np.testing.assert_allclose(_span(0.1, 1.0, 3), [0.1, 0.55, 1.0], rtol=1e-12)     # 10 exactly: linear
    np.testing.assert_allclose(_span(0.1, 1.05, 3), [0.1, math.sqrt(0.105), 1.05], rtol=1e-12)  # just above 10
    np.testing.assert_allclose(_span(0.0, 1.0, 3), [0.0, 0.5, 1.0], rtol=1e-12)


def test_the_points_clustered_at_the_dead_centres():
    pts = _cluster(-1.0, 7.0, 0.01, 5)
    offs = np.geomspace(1e-3, 0.5, 5)
    np.testing.assert_allclose(np.sort(pts), np.sort(np.concatenate([offs, -offs, 2 * math.pi + offs,
                                                                     2 * math.pi - offs])), rtol=1e-15)
    assert len(_cluster(0.0, 7.0, 0.01, 5)) == 15                 # 0 at the range's end: half its points
    assert _cluster(0.5, 6.0, 0.01, 5).size == 0                   # no multiple of 2π inside
    assert _cluster(-1.0, 1.0, 0.06, 5).size == 0                  # r0/r not small: nothing to resolve
    assert len(_cluster(-1.0, 1.0, 0.05, 5)) == 10
    assert np.min(np.abs(_cluster(-1.0, 1.0, 0.0, 5))) == pytest.approx(1e-13)   # a zero width is 1e-12


# ---------------------------------------------------------------- SLSQP's full problem
def test_the_full_problem_of_a_compression_spring():
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, 0.3), max_force=900.0, max_free_length=1.0,
                     max_deflection=0.3)
    p = problem(b=b, grid=21)
    z0 = np.array([0.4, 0.8, 0.5])
    y0, bounds, cons, err = p.full_problem(z0, "max")
    rho, rho0, al, _ = p.decode(z0)
    assert y0 == [rho, rho0, al, p.best_kappa(rho, rho0, al, "max")]
    assert bounds == [(0.125, 1.0), (0.25, 2.0), (0.0, pytest.approx(0.75, rel=1e-15)), (0.0, None)]
    assert [c["type"] for c in cons] == ["ineq"] * 3
    y = np.array([0.5, 0.6, 0.2, 1.1])
    l0, lmin = 2 * 0.5 + 0.6 + 0.2, spring_lengths(p, 0.5, 0.6).min()
    force = 900.0 * 0.4 / 80.0
    want = [2.5 - l0, lmin - 0.7 * l0, force * 0.5 * 1.1 - 1.1 * (l0 - lmin)]
    assert [c["fun"](y) for c in cons] == pytest.approx(want, rel=1e-6)
    np.testing.assert_array_equal(err(y), p.errors(0.5, 0.6, 0.2, 1.1))
    assert p.full_problem(z0, "rms")[0][3] == p.best_kappa(rho, rho0, al, "rms")


def test_the_full_problem_of_a_tension_spring():
    b = SpringBounds(r=(0.05, 0.4), r0=(0.1, 0.8), a=(0.0, math.inf), max_force=900.0, max_free_length=0.3)
    p = problem("tension", -60.0, b=b, grid=21)
    y0, bounds, cons, err = p.full_problem(np.array([0.4, 0.8, 0.5]), "rms")
    assert bounds[2] == (0.0, None)
    y = np.array([0.5, 0.9, 0.2, 1.1])
    lmax = spring_lengths(p, 0.5, 0.9).max()
    force = 900.0 * 0.4 / 60.0
    assert [c["fun"](y) for c in cons] == pytest.approx([0.7, 0.75 - 0.7, force * 0.5 * 1.4 - 1.1 * (lmax - 0.7)],
                                                        rel=1e-6)
    assert [c["fun"] for c in problem("tension", -60.0).full_problem(np.array([0.4, 0.8, 0.5]), "rms")[2]][0](y) \
        == pytest.approx(0.7)
    assert len(problem("tension", -60.0).full_problem(np.array([0.4, 0.8, 0.5]), "rms")[2]) == 1
    assert len(problem().full_problem(np.array([0.4, 0.8, 0.5]), "rms")[2]) == 0


# ---------------------------------------------------------------- refusals
@pytest.mark.parametrize("kind, moment, lo, hi, b, error, sentence", [
    ("compression", 80.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, math.inf), (0.0, 0.3)), InvalidRange,
     "r0 needs a finite upper bound."),
    ("compression", 80.0, 0.3, 0.9, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, 0.3), max_force=150.0),
     InfeasibleBounds, "the force limit 150 N on a crank of at most 0.4 m gives at most 60 N·m, less than the "
     "62.6662 N·m the target needs in this range; raise the force limit or the longest crank."),
    ("compression", 80.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, math.inf)), InfeasibleBounds,
     "with a compression spring and no upper bound on the pre-load a (nor a maximum free length or deflection), "
     "the error keeps falling as a grows without limit; give a finite upper bound on a, a maximum free length or "
     "a maximum deflection."),
    ("compression", 80.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.05, 0.3), max_free_length=0.2),
     InfeasibleBounds, "the shortest compression device within the bounds has free length 2r+r0+a = 0.25 m, more "
     "than the maximum free length 0.2 m."),
    ("compression", 80.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, 0.3), max_deflection=0.05),
     InfeasibleBounds, "no crank and spring within the bounds keeps the deflection ratio (l0 − L_min)/l0 below "
     "0.05: raise the maximum deflection, allow a longer r0 or a smaller pre-load a."),
    ("tension", -60.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.1, 0.2), (0.25, 0.3)), InfeasibleBounds,
     "a tension spring needs a pre-extension a ≤ r0, but a ≥ 0.25 m and r0 ≤ 0.2 m."),
    ("tension", -60.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.5, 0.8), (0.0, 0.1), max_free_length=0.3),
     InfeasibleBounds, "no device within the stated bounds satisfies the free-length limit."),
    # (a deflection limit means nothing to a tension spring: its free length is what refuses it)
    ("tension", -60.0, 0.3, 2.6, SpringBounds((0.05, 0.4), (0.5, 0.8), (0.0, 0.1), max_free_length=0.3,
                                              max_deflection=0.3),
     InfeasibleBounds, "no device within the stated bounds satisfies the free-length limit."),
])
def test_each_refusal_of_the_bounds_in_full(kind, moment, lo, hi, b, error, sentence):
    with pytest.raises(error) as exc:
        _check_feasible(problem(kind, moment, lo, hi, b))
    assert str(exc.value) == sentence


@pytest.mark.parametrize("kind, moment, b", [
    # the force limit just reaches the peak: 200 N on 0.4 m = 80 N·m at φ = 90°
    ("compression", 80.0, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, 0.3), max_force=200.0)),
    ("compression", 80.0, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, math.inf), max_free_length=2.0)),
    ("compression", 80.0, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.0, math.inf), max_deflection=0.5)),
    # the shortest device exactly at the free-length limit: 2·0.05 + 0.1 + 0.05
    ("compression", 80.0, SpringBounds((0.05, 0.4), (0.1, 0.8), (0.05, 0.3), max_free_length=0.25)),
    ("tension", -60.0, SpringBounds((0.05, 0.4), (0.1, 0.2), (0.2, 0.3))),     # a = r0 = 0.2 exactly
    # only the last r0 of the scan (the bound itself) leaves room: r0 − a ≤ 0.25 with a ≤ 0.1 and r0 ≥ 0.35
    ("tension", -60.0, SpringBounds((0.05, 0.4), (0.35, 0.8), (0.0, 0.1), max_free_length=0.25)),
])
def test_bounds_on_the_edge_of_a_refusal_are_taken(kind, moment, b):
    assert _check_feasible(problem(kind, moment, 0.3, 2.6, b)) is None
