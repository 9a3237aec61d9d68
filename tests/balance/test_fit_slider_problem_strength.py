"""balance/devices/fit/slider_problem.py against values found without it, fast enough to judge its mutants:
the relative errors against the moment −d(½c(x − x_n)²)/dφ with the slider's position found by bisection
(finite differences), the rod's angle, the stroke, the free length and the force sampled over the range,
SLSQP's constraints at chosen points, a finished result's numbers from its device, its active bounds at
their tolerance, and every refusal in full."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import SpringBounds
from balance.devices.fit.slider_problem import (MAX_ROD_ANGLE, _active_slider, _finish_slider, _SIDE_TEXT,
                                                _SliderProblem)
from balance.errors import InfeasibleBounds
from tests.balance.test_slider_devices import _slider_x_from_positions

CRANK = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), rod=(0.2, 0.5), offset=(-0.05, 0.05))
SINE = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3))
H = 1e-6


def problem(family="slider-crank", moment=20.0, lo=0.3, hi=2.6, b=CRANK, grid=31, norm="rms"):
    return _SliderProblem(family, moment, lo, hi, b, grid, norm)


def position(phi, r, rod, e):
    """The slider's position from the linkage: bisection for the slider-crank, r·cos φ for the sine device."""
    return _slider_x_from_positions(phi, r, rod, e) if rod is not None else r * np.cos(np.asarray(phi, float))


def stroke_and_ends(p, rho, eps, lam):
    rod = lam if p.rod else None
    x = position(np.linspace(p.lo, p.hi, 20001), rho, rod, eps)
    return x.max() - x.min(), x.min(), x.max()


@pytest.mark.parametrize("family, moment, point", [
    ("slider-crank", 20.0, (0.8, 0.3, 3.0, 0.5, 0.9)),
    ("slider-crank", -20.0, (0.6, -0.4, 2.5, 0.2, 1.2)),
    ("sine", 20.0, (0.7, 0.0, math.inf, 0.4, 1.1)),
    ("sine", -20.0, (1.0, 0.0, math.inf, 0.1, 0.8)),
])
def test_the_errors_are_the_devices_relative_errors(family, moment, point):
    """κ·m − σ·sin φ = (M − Φ0·sin φ)/|Φ0| with M = −d(½c(x − x_n)²)/dφ by central differences of positions,
    c = κ·|Φ0|/ℓ² and x_n the least position less α (σ > 0) or the largest plus α (σ < 0)."""
    b = CRANK if family == "slider-crank" else SINE
    p = problem(family, moment, -0.5, 2.8, b, grid=23)
    rho, eps, lam, al, kappa = point
    rod = lam if family == "slider-crank" else None
    _, xmin, xmax = stroke_and_ends(p, rho, eps, lam)
    xn = xmin - al if moment > 0 else xmax + al
    assert p.neutral(rho, eps, lam, al) == pytest.approx(xn, abs=1e-8)
    c = kappa * abs(moment)             # (ℓ = 0.1 m: lengths in units of ℓ, c·ℓ² = κ·|Φ0|)
    energy = lambda phi: 0.5 * c * (position(phi, rho, rod, eps) - xn) ** 2  # noqa: E731
    m = -(energy(p.phi + H) - energy(p.phi - H)) / (2 * H)
    np.testing.assert_allclose(p.errors(*point), (m - moment * np.sin(p.phi)) / abs(moment), atol=1e-6)
    np.testing.assert_array_equal(p.target, np.sign(moment) * np.sin(p.phi))
    assert p.nfev == 1 and p.ell == 0.1 and len(p.phi) == 23


def test_the_stroke_and_ends_from_positions():
    p = problem(lo=-0.5, hi=2.8)
    for rho, eps, lam in ((0.8, 0.3, 3.0), (1.0, -0.5, 2.0)):
        stroke, xmin, xmax = stroke_and_ends(p, rho, eps, lam)
        assert p.stroke(rho, eps, lam) == pytest.approx(stroke, abs=1e-8)
        assert p.extremes(rho, eps, lam) == pytest.approx((xmin, xmax), abs=1e-8)
    s = problem("sine", b=SINE, lo=-0.5, hi=2.8)
    assert s.stroke(0.7, 0.0, math.inf) == pytest.approx(0.7 * (1 - math.cos(2.8)), rel=1e-12)
    assert s.rod_length(3.0) is None and p.rod_length(3.0) == 3.0


def test_the_shortest_rod_keeps_its_angle_to_the_guide_within_60_degrees():
    """Over a whole turn the rod's angle θ to the guide has sin θ = (r·sin φ − e)/l: at the shortest rod
    allowed its largest |sin θ| is sin 60°, unless the rod's own lower bound is longer."""
    p = problem()
    for rho, eps in ((0.8, 0.3), (1.0, -0.5), (0.2, 0.0)):
        lo, hi = p.rod_limits(rho, eps)
        turn = np.linspace(0, 2 * math.pi, 100001)
        worst = np.max(np.abs(rho * np.sin(turn) - eps)) / lo
        assert hi == 5.0 and (worst == pytest.approx(math.sin(MAX_ROD_ANGLE), rel=1e-8) or lo == 2.0)
    assert p.rod_limits(0.2, 0.0) == (2.0, 5.0) and MAX_ROD_ANGLE == math.radians(60)


def test_the_limits_of_the_preload_and_of_the_scale():
    """α ≤ δ·Lf − stroke (the spring's deflection a + stroke within δ of its free length, δ = 0.5 unless given);
    κ ≤ F̂/(α + stroke): at κmax the largest spring force c·|x − x_n| over the range is the force limit."""
    b = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), max_force=400.0, max_free_length=0.4,
                     rod=(0.2, 0.5), offset=(-0.05, 0.05))
    p = problem(b=b)
    assert p.delta == 0.5 and problem(b=SpringBounds(**{**b.__dict__, "max_deflection": 0.3})).delta == 0.3
    rho, eps, lam = 0.8, 0.3, 3.0
    stroke, xmin, xmax = stroke_and_ends(p, rho, eps, lam)
    lo, hi = p.alpha_limits(rho, eps, lam)
    assert lo == pytest.approx(0.1) and hi == pytest.approx(0.5 * 4.0 - stroke, abs=1e-8)
    assert problem().alpha_limits(rho, eps, lam) == (pytest.approx(0.1), pytest.approx(3.0))
    al = 0.5
    km = p.kappa_max(rho, eps, lam, al)
    c = km * 20.0 / 0.01                                 # c = κ·|Φ0|/ℓ²
    x = position(np.linspace(p.lo, p.hi, 20001), 0.1 * rho, 0.1 * lam, 0.1 * eps)
    assert c * np.max(np.abs(x - 0.1 * (xmin - al))) == pytest.approx(400.0, rel=1e-6)
    assert problem().kappa_max(rho, eps, lam, al) == math.inf


def test_the_variables_decoded_and_encoded():
    b = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), max_free_length=0.4, rod=(0.2, 0.5),
                     offset=(-0.05, 0.05))
    p = problem(b=b)
    rho, eps = 0.8, 0.3
    llo, lhi = p.rod_limits(rho, eps)
    lam = llo + 0.25 * (lhi - llo)
    alo, ahi = p.alpha_limits(rho, eps, lam)
    got = p.decode([rho, eps, 0.25, 0.5])
    assert got == (rho, eps, pytest.approx(lam), pytest.approx(alo + 0.5 * (ahi - alo)), 0.0)
    assert p.decode([rho, eps, -1.0, 2.0])[2:4] == (llo, pytest.approx(p.alpha_limits(rho, eps, llo)[1]))
    np.testing.assert_allclose(p.encode(rho, eps, lam, alo + 0.5 * (ahi - alo)), [rho, eps, 0.25, 0.5], rtol=1e-9)
    np.testing.assert_allclose(p.encode(rho, eps, lhi + 1.0, -5.0), [rho, eps, 1.0, 0.0])
    np.testing.assert_allclose(p.encode_full([rho, eps, lam, alo, 7.0]), [rho, eps, 0.25, 0.0], atol=1e-12)
    assert p.unpack([rho, eps, lam, 0.2, 7.0]) == (rho, eps, lam, 0.2, 7.0)
    # a rod shorter than its angle allows (SLSQP's line search may step there) is taken at that limit
    assert p.unpack([rho, eps, 1.0, 0.2, 7.0]) == (rho, eps, pytest.approx(1.1 / math.sin(MAX_ROD_ANGLE)), 0.2, 7.0)
    # a rod too long to fit: past its upper bound the gap is the violation
    tight = problem(b=SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), rod=(0.1, 0.15), offset=(-0.05, 0.05)))
    rho, eps, lam, al, viol = tight.decode([1.0, 0.5, 0.5, 0.5])
    need = 1.5 / math.sin(MAX_ROD_ANGLE)
    assert (lam, al) == (pytest.approx(need), pytest.approx(0.1)) and viol == pytest.approx(need - 1.5)
    # no room for α (the stroke alone is past δ·Lf)
    short = problem(b=SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), max_free_length=0.1, rod=(0.2, 0.5),
                                   offset=(-0.05, 0.05)))
    rho, eps, lam, al, viol = short.decode([1.0, 0.0, 0.0, 0.5])
    stroke = short.stroke(rho, eps, lam)
    assert al == pytest.approx(0.1) and viol == pytest.approx(0.1 - (0.5 - stroke))
    assert short.encode(1.0, 0.0, lam, 0.3)[3] == 0.0
    s = problem("sine", b=SINE)
    assert s.decode([0.5, 0.5]) == (0.5, 0.0, math.inf, pytest.approx(0.1 + 0.5 * 2.9), 0.0)
    np.testing.assert_allclose(s.encode(0.5, 0.0, math.inf, 0.1 + 0.5 * 2.9), [0.5, 0.5])
    assert s.unpack([0.5, 0.2, 3.0]) == (0.5, 0.0, math.inf, 0.2, 3.0)
    np.testing.assert_allclose(s.encode_full([0.5, 0.1, 3.0]), [0.5, 0.0], atol=1e-15)


def test_the_objective_and_the_scale_by_hand():
    p = problem(grid=21)
    z = np.array([0.8, 0.3, 0.5, 0.5])
    rho, eps, lam, al, viol = p.decode(z)
    for norm in ("rms", "max"):
        k = p.best_kappa(rho, eps, lam, al, norm)
        ks = np.linspace(0.0, 3.0 * k, 3001)
        f = (lambda e: np.sqrt(np.mean(e ** 2))) if norm == "rms" else (lambda e: np.max(np.abs(e)))
        assert f(p.errors(rho, eps, lam, al, k)) <= min(f(p.errors(rho, eps, lam, al, kk)) for kk in ks) + 1e-12
        assert p.objective(z, norm) == pytest.approx(f(p.errors(rho, eps, lam, al, k)), rel=1e-14)
        e, kk, v = p.projected(z, norm)
        assert kk == k and v == 0.0
    v = np.linspace(1.0, 2.0, 21)
    h = p.shape(rho, eps, lam, al)
    assert p.best_kappa(rho, eps, lam, al, "rms", v) == pytest.approx(np.sum(v * h * p.target) / np.sum(v * h * h))
    tight = problem(b=SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), rod=(0.1, 0.15), offset=(-0.05, 0.05)))
    z = np.array([1.0, 0.5, 0.5, 0.5])
    *point, viol = tight.decode(z)
    e = tight.errors(*point, tight.best_kappa(*point, "max"))
    assert tight.objective(z, "max") == pytest.approx(np.max(np.abs(e)) + 10 * viol, rel=1e-14)


def test_the_start_is_no_worse_than_any_corner():
    for family, b in (("slider-crank", CRANK), ("sine", SINE)):
        p = problem(family, b=b, grid=21)
        lb, ub = p.z_bounds
        for norm in ("rms", "max"):
            z = p.start(norm)
            corners = [p.objective(np.array(c), norm) for c in np.stack(np.meshgrid(*zip(lb, ub), indexing="ij"),
                                                                      -1).reshape(-1, len(lb))]
            assert p.objective(z, norm) <= min(corners) and np.all(z >= lb) and np.all(z <= ub)


def test_the_full_problem_by_hand():
    b = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), max_force=400.0, max_free_length=0.4,
                     rod=(0.2, 0.5), offset=(-0.05, 0.05))
    p = problem(b=b)
    z0 = np.array([0.8, 0.3, 0.5, 0.5])
    y0, bounds, cons, err = p.full_problem(z0, "max")
    rho, eps, lam, al, _ = p.decode(z0)
    assert y0 == [rho, eps, lam, al, p.best_kappa(rho, eps, lam, al, "max")]
    assert bounds == [(pytest.approx(0.2), 1.0), (-0.5, 0.5), (2.0, 5.0), (pytest.approx(0.1), pytest.approx(3.0)),
                      (0.0, None)]
    y = np.array([0.7, 0.2, 2.2, 0.3, 1.5])
    s = math.sin(MAX_ROD_ANGLE)
    stroke = p.stroke(0.7, 0.2, 2.2)
    want = [2.2 * s - 0.9, 2.2 * s - 0.5, 0.5 * 4.0 - 0.3 - stroke, 400.0 * 0.1 / 20.0 - 1.5 * (0.3 + stroke)]
    assert [c["fun"](y) for c in cons] == pytest.approx(want, rel=1e-12)
    assert all(c["type"] == "ineq" for c in cons)
    np.testing.assert_array_equal(err(y), p.errors(0.7, 0.2, 2.2, 0.3, 1.5))
    free = problem(b=SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, math.inf), rod=(0.2, math.inf),
                                  offset=(0.0, 0.0), max_free_length=1.0))
    _, bounds, cons, _ = free.full_problem(np.array([0.8, 0.0, 0.5, 0.5]), "rms")
    assert bounds[2] == (2.0, None) and bounds[3] == (pytest.approx(0.1), None) and len(cons) == 3
    s_y0, s_bounds, s_cons, s_err = problem("sine", b=SINE).full_problem(np.array([0.5, 0.5]), "rms")
    assert len(s_y0) == 3 and s_bounds == [(pytest.approx(0.2), 1.0), (pytest.approx(0.1), pytest.approx(3.0)), (0.0, None)] and s_cons == []
    sp = problem("sine", b=SINE)
    np.testing.assert_array_equal(s_err([0.5, 0.2, 1.0]), sp.errors(0.5, 0.0, math.inf, 0.2, 1.0))


# ---------------------------------------------------------------- the finished result
@pytest.mark.parametrize("family, moment, y", [
    ("slider-crank", 20.0, (0.8, 0.3, 3.0, 0.5, 0.9)),
    ("slider-crank", -20.0, (0.6, -0.4, 2.5, 0.2, 1.2)),
    ("sine", -20.0, (0.7, 0.0, math.inf, 0.4, 1.1)),
])
def test_a_finished_slider_result_by_hand(family, moment, y):
    b = CRANK if family == "slider-crank" else SINE
    p = problem(family, moment, b=b)
    res = _finish_slider(p, y, "slsqp", "max", 0.0, "done", ["first"], 3)
    rho, eps, lam, al, kappa = y
    rod = 0.1 * lam if family == "slider-crank" else None
    c = kappa * abs(moment) / 0.01
    stroke, xmin, xmax = stroke_and_ends(p, rho, eps, lam)
    xn = 0.1 * (xmin - al if moment > 0 else xmax + al)
    assert (res.c, res.r, res.a) == pytest.approx((c, 0.1 * rho, 0.1 * al), rel=1e-14)
    assert res.neutral == pytest.approx(xn, abs=1e-9) and res.rod == (None if rod is None else pytest.approx(rod))
    assert res.offset == (None if rod is None else pytest.approx(0.1 * eps))
    assert res.x == (y if family == "slider-crank" else (rho, al, kappa))
    phi = np.linspace(p.lo, p.hi, 20001)
    x = position(phi, 0.1 * rho, rod, 0.1 * eps)
    assert res.max_force == pytest.approx(c * np.max(np.abs(x - xn)), rel=1e-6)
    assert res.free_length == pytest.approx(0.1 * (al + stroke) / 0.5, rel=1e-6) and res.deflection == 0.5
    m = -(0.5 * c * (position(phi + H, 0.1 * rho, rod, 0.1 * eps) - xn) ** 2
          - 0.5 * c * (position(phi - H, 0.1 * rho, rod, 0.1 * eps) - xn) ** 2) / (2 * H)
    assert res.max_rel_error == pytest.approx(np.max(np.abs(m - moment * np.sin(phi))) / abs(moment), rel=1e-5)
    g = p.phi
    mg = -(0.5 * c * (position(g + H, 0.1 * rho, rod, 0.1 * eps) - xn) ** 2
           - 0.5 * c * (position(g - H, 0.1 * rho, rod, 0.1 * eps) - xn) ** 2) / (2 * H)
    eg = (mg - moment * np.sin(g)) / abs(moment)
    assert res.grid_max_rel_error == pytest.approx(np.max(np.abs(eg)), rel=1e-5)
    assert res.grid_rms_rel_error == pytest.approx(np.sqrt(np.mean(eg ** 2)), rel=1e-5)
    u = np.linspace(p.lo, p.hi, 4001)
    mu = -(0.5 * c * (position(u + H, 0.1 * rho, rod, 0.1 * eps) - xn) ** 2
           - 0.5 * c * (position(u - H, 0.1 * rho, rod, 0.1 * eps) - xn) ** 2) / (2 * H)
    assert res.rms_rel_error == pytest.approx(np.sqrt(np.mean(((mu - moment * np.sin(u)) / abs(moment)) ** 2)),
                                              rel=1e-5)
    assert (res.kind, res.method, res.norm, res.moment, res.family) == ("compression", "slsqp", "max", moment, family)
    assert (res.r0, res.d, res.phi_range, res.grid, res.restarts) == (None, None, (0.3, 2.6), 31, 3)
    assert res.sense == (1 if moment > 0 else -1) and res.sense_text == _SIDE_TEXT[res.sense]
    assert res.message == "done" and res.reference_length == 0.1 and res.nfev == 1 and res.seconds > 0
    assert res.notes == ("first", f"stroke {0.1 * stroke:.4g} m; the spring's free length is the shortest that keeps "
                                  "its deflection within 0.5 of it")
    assert res.device.moment(1.0) == pytest.approx(float(np.interp(1.0, phi, m)), rel=1e-4)


def test_the_side_of_the_spring_in_words():
    assert _SIDE_TEXT == {
        +1: "spring beyond the slider, pushing it towards the crank (increasing φ where sin φ > 0)",
        -1: "spring between the crank's side and the slider, pushing it away (decreasing φ where sin φ > 0)"}


@pytest.mark.parametrize("shift, named", [(1e-7, True), (1e-5, False)])
def test_each_active_bound_named_within_its_tolerance(shift, named):
    b = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), max_force=400.0, max_free_length=0.4,
                     rod=(0.2, 0.5), offset=(-0.05, 0.05))
    p = problem(b=b)
    s = 1 + shift
    cases = [("r=min", (0.2 * s, 0.0, 3.0, 0.5)), ("r=max", (1.0 / s, 0.0, 3.0, 0.5)),
             ("offset=min", (0.5, -0.5 / s, 3.0, 0.5)), ("offset=max", (0.5, 0.5 / s, 3.0, 0.5)),
             ("rod=min", (0.5, 0.0, 2.0 * s, 0.5)), ("rod=max", (0.5, 0.0, 5.0 / s, 0.5)),
             ("a=min", (0.5, 0.0, 3.0, 0.1 * s)), ("a=max", (0.5, 0.0, 3.0, 3.0 / s)),
             ("rod angle", (0.5, 0.3, 0.8 / math.sin(MAX_ROD_ANGLE) * s, 0.5))]
    for name, (rho, eps, lam, al) in cases:
        assert (name in _active_slider(p, rho, eps, lam, al, 0.1)) == named, name
    stroke = p.stroke(0.5, 0.0, 3.0)
    assert ("max_free_length" in _active_slider(p, 0.5, 0.0, 3.0, (2.0 - stroke) / s, 0.1)) == named
    km = p.kappa_max(0.5, 0.0, 3.0, 0.5)
    assert ("max_force" in _active_slider(p, 0.5, 0.0, 3.0, 0.5, km / s)) == named
    assert _active_slider(p, 0.5, 0.0, 3.0, 0.5, 0.5 * km) == []
    sine = problem("sine", b=SINE)
    assert _active_slider(sine, 1.0, 0.0, math.inf, 0.1, 1.0) == ["r=max", "a=min"]
    # in the order of the device's variables: crank, offset, rod, pre-load
    assert _active_slider(p, 0.2, -0.5, 2.0, 0.1, 0.1) == ["r=min", "offset=min", "rod=min", "a=min"]


def test_a_finished_slider_result_names_the_force_limit():
    """κ at its largest: the force limit is named among the result's active bounds (and κ is the result's)."""
    b = SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), max_force=400.0, rod=(0.2, 0.5), offset=(-0.05, 0.05))
    p = problem(b=b)
    km = p.kappa_max(0.8, 0.3, 3.0, 0.5)
    res = _finish_slider(p, (0.8, 0.3, 3.0, 0.5, km), "slsqp", "max", 0.0, "done", [])
    assert "max_force" in res.active_bounds and res.max_force == pytest.approx(400.0, rel=1e-12)


# ---------------------------------------------------------------- refusals
@pytest.mark.parametrize("family, b, sentence", [
    ("sine", SpringBounds((0.02, 0.1), None, (0.0, math.inf)),
     "with no upper bound on the pre-load a (nor a maximum free length), the error keeps falling as a grows without "
     "limit (the spring's force tends to a constant); give a finite upper bound on a or a maximum free length."),
    ("slider-crank", SpringBounds((0.02, 0.1), None, (0.0, 0.3), rod=(0.01, 0.02), offset=(0.01, 0.03)),
     "a rod of at most 0.02 m is too short for a crank of at least 0.02 m and an offset of at least 0.01 m: the rod "
     "must be (r + |e|)/sin 60° long or more so that its angle to the guide stays within that; allow a longer rod "
     "or a shorter crank."),
    ("slider-crank", SpringBounds((0.02, 0.1), None, (0.0, 0.3), rod=(0.01, 0.02), offset=(-0.03, -0.01)),
     "a rod of at most 0.02 m is too short for a crank of at least 0.02 m and an offset of at least 0.01 m: the rod "
     "must be (r + |e|)/sin 60° long or more so that its angle to the guide stays within that; allow a longer rod "
     "or a shorter crank."),
    ("sine", SpringBounds((0.02, 0.1), None, (0.0, 0.3), max_force=99.0),
     "the force limit 99 N on a slider driven by a crank of at most 0.1 m gives at most 9.9 N·m, less than the 10 "
     "N·m the target needs in this range; raise the force limit or the longest crank."),
    ("slider-crank", SpringBounds((0.02, 0.1), None, (0.0, 0.3), max_force=30.0, rod=(0.2, 0.4), offset=(0.0, 0.0)),
     "the force limit 30 N on a slider driven by a crank of at most 0.1 m gives at most 8.19615 N·m, less than the 10 "
     "N·m the target needs in this range; raise the force limit or the longest crank."),
    ("sine", SpringBounds((0.1, 0.2), None, (0.0, 0.3), max_free_length=0.1),
     "no sine device within the bounds keeps the spring's deflection a + stroke within 0.5 × the maximum free "
     "length 0.1 m; allow a longer spring, a larger deflection ratio or a shorter crank."),
])
def test_each_refusal_in_full(family, b, sentence):
    with pytest.raises(InfeasibleBounds) as exc:
        problem(family, 10.0, 0.3, math.pi / 2 + 0.5, b).check_feasible()
    assert str(exc.value) == sentence


@pytest.mark.parametrize("family, b", [
    ("sine", SpringBounds((0.02, 0.1), None, (0.0, math.inf), max_free_length=1.0)),
    ("sine", SpringBounds((0.02, 0.1), None, (0.0, 0.3), max_force=100.0)),           # 100 N · 0.1 m: exactly 10 N·m
    # the shortest rod exactly (r + |e|)/sin 60°, with an offset range holding 0
    ("slider-crank", SpringBounds((0.02, 0.1), None, (0.0, 0.3), rod=(0.01, 0.02 / math.sin(MAX_ROD_ANGLE)),
                                  offset=(-0.01, 0.01))),
])
def test_bounds_on_the_edge_of_a_refusal_are_taken(family, b):
    assert problem(family, 10.0, 0.3, math.pi / 2 + 0.5, b).check_feasible() is None


def test_the_force_limit_against_the_targets_peak_in_the_range():
    """Over 0.3 … 0.9 rad the target peaks at 10·sin 0.9 = 7.833 N·m: 80 N on a 0.1 m crank (8 N·m) may do,
    78 N (7.8 N·m) cannot."""
    b = SpringBounds((0.02, 0.1), None, (0.0, 0.3))
    assert problem("sine", 10.0, 0.3, 0.9, SpringBounds(**{**b.__dict__, "max_force": 80.0})).check_feasible() is None
    with pytest.raises(InfeasibleBounds) as exc:
        problem("sine", 10.0, 0.3, 0.9, SpringBounds(**{**b.__dict__, "max_force": 78.0})).check_feasible()
    assert str(exc.value) == ("the force limit 78 N on a slider driven by a crank of at most 0.1 m gives at most 7.8 "
                              "N·m, less than the 7.83327 N·m the target needs in this range; raise the force limit or "
                              "the longest crank.")


@pytest.mark.parametrize("offset, max_free_length", [((-0.1, 0.04), None), ((-0.1, 0.04), 2.0), ((0.002, 0.05), None)])
def test_a_short_rod_with_an_offset_range_about_the_in_line_guide_is_fitted(offset, max_free_length):
    """Bug (29 Nov 2026): the feasibility scan took 7 offsets of the range and missed the one nearest an
    in-line guide, the only one a rod of at most 26.558 mm allows with a 20 mm crank ((0.02 + |e|)/sin 60°
    ≤ 0.026558 m needs |e| ≤ 3 mm): `balance spring --device slider-crank … --rod 0.01..0.026558
    --offset=-0.1..0.04` ended in a TypeError (a traceback), or with a free-length limit in a refusal naming
    the free length.  Past that check SLSQP stepped beyond the rod's angle limit in a line search, where the slider
    cannot reach its guide (a math domain error).  Now the device is fitted, its rod at the 60° angle it may take
    and no more."""
    b = SpringBounds((0.02, 0.1), None, (0.0, 0.3), rod=(0.01, 0.026558), offset=offset,
                     max_free_length=max_free_length)
    from balance import fit_spring

    res = fit_spring("compression", 10.0, (math.radians(17), math.radians(115)), b, device="slider-crank")
    turn = np.linspace(0, 2 * math.pi, 100001)
    assert np.max(np.abs(res.r * np.sin(turn) - res.offset)) / res.rod <= math.sin(MAX_ROD_ANGLE) * (1 + 1e-9)
    assert abs(res.offset) <= 0.003 * (1 + 1e-6) and offset[0] <= res.offset <= offset[1]
    assert "rod=max" in res.active_bounds and np.isfinite(res.max_rel_error)


def test_the_in_line_offset_is_scanned():
    """The start and the feasibility scan hold the offset nearest 0 within its range."""
    p = problem(b=SpringBounds(r=(0.02, 0.1), r0=None, a=(0.01, 0.3), rod=(0.2, 0.5), offset=(-0.1, 0.04)))
    assert p.eps_in_line == 0.0 and problem(b=SpringBounds((0.02, 0.1), None, (0.01, 0.3), rod=(0.2, 0.5),
                                                           offset=(0.01, 0.04))).eps_in_line == pytest.approx(0.1)
    assert problem(b=SpringBounds((0.02, 0.1), None, (0.01, 0.3), rod=(0.2, 0.5),
                                  offset=(-0.04, -0.01))).eps_in_line == pytest.approx(-0.1)
    axes = p._with_in_line([np.array([1.0]), np.linspace(-1.0, 0.4, 7), np.array([0.5]), np.array([0.5])])
    assert 0.0 in axes[1] and len(axes[1]) == 8
    assert problem("sine", b=SINE)._with_in_line([np.array([1.0]), np.array([0.5])])[1].tolist() == [0.5]
