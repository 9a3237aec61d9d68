"""The fit's methods SLSQP (balance/devices/fit/slsqp.py) and trf (trf.py) called alone, without the driver's
confirming restarts, on small grids: the corner optimum against a linear programme (max norm) and a least-squares
solve (RMS) of the scale, a constrained optimum against Nelder–Mead's on the projected problem, every limit kept
(checked from the device's own lengths and forces), Lawson's reweighting near the minimax error, and how each
method says it ended."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize

from balance import SpringBounds
from balance.devices.fit.problem import _Problem
from balance.devices.fit.slider_problem import _SliderProblem
from balance.devices.fit.slsqp import _fit_slsqp
from balance.devices.fit.trf import _fit_trf
from tests.balance.test_fit_vs_oracle import free_length, moment_from_positions

ISSUE = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))
MID = (math.radians(20), math.radians(160))
#: two limits binding, two directions left free (r and the split of l0 into r0 and a)
INTERIOR = ("compression", 100.0, (math.radians(8), math.radians(188)),
            SpringBounds(r=(0.03, 0.32), r0=(0.03, 0.88), a=(0.0, 0.58), max_force=2400.0, max_free_length=0.97))
SINE = SpringBounds(r=(0.02, 0.12), r0=None, a=(0.0, 0.3), max_force=1500.0, max_free_length=0.5)


def corner_scale_problem(norm):
    """At the corner r = 0.01, r0 = 1, a = 1 of ISSUE only κ is left: M/Φ0 = κ·h with h the moment per unit c
    (from positions) over r·d, since c = κ·|Φ0|/(r·d); the target is sin φ."""
    p = _Problem("compression", 100.0, *MID, ISSUE, 21, norm)
    r, r0, a = 0.01, 1.0, 1.0
    m, _ = moment_from_positions("compression", 1.0, r, r0, a, p.phi)
    return p, m / (r * (r + r0)), np.sin(p.phi)


def test_slsqp_on_the_max_norm_reaches_the_linear_programmes_minimax():
    p, h, s = corner_scale_problem("max")
    z, msg, ok = _fit_slsqp(p, "max")
    n = len(h)
    lp = optimize.linprog([0, 1], A_ub=np.block([[h[:, None], -np.ones((n, 1))], [-h[:, None], -np.ones((n, 1))]]),
                          b_ub=np.concatenate([s, -s]), bounds=[(0, None), (0, None)], method="highs")
    assert p.objective(z, "max") == pytest.approx(lp.fun, rel=1e-8)
    assert p.best_kappa(*p.decode(z)[:3], "max") == pytest.approx(lp.x[0], rel=1e-6)
    assert p.decode(z)[:3] == pytest.approx((0.02, 2.0, 2.0), rel=1e-7)
    assert (msg, ok) == ("SLSQP: Optimization terminated successfully", True)


@pytest.mark.parametrize("fit", [_fit_slsqp, _fit_trf])
def test_the_rms_norm_reaches_the_least_squares_scale(fit):
    p, h, s = corner_scale_problem("rms")
    z, msg, ok = fit(p, "rms")
    k = float(np.linalg.lstsq(h[:, None], s, rcond=None)[0][0])
    assert p.objective(z, "rms") == pytest.approx(np.sqrt(np.mean((k * h - s) ** 2)), rel=1e-7)
    assert ok


def limits_kept(p, z, b):
    """Every limit of ``b`` kept by the device of ``z`` (its force and lengths from positions)."""
    rho, rho0, al, viol = p.decode(z)
    kappa = p.best_kappa(rho, rho0, al, "max")
    r, r0, a = rho * p.ell, rho0 * p.ell, al * p.ell
    c = kappa * abs(p.moment) / (r * (r + r0))
    _, L = moment_from_positions(p.kind, c, r, r0, a, np.linspace(p.lo, p.hi, 4001))
    l0 = free_length(p.kind, r, r0, a)
    return (viol == 0.0 and c * np.max(np.abs(L - l0)) <= b.max_force * (1 + 1e-6)
            and l0 <= b.max_free_length * (1 + 1e-9))


@pytest.mark.parametrize("norm", ["max", "rms"])
def test_slsqp_reaches_nelder_meads_constrained_optimum_within_its_limits(norm):
    kind, moment, rng, b = INTERIOR
    p = _Problem(kind, moment, *rng, b, 21, norm)
    z, msg, ok = _fit_slsqp(p, norm)
    lb, ub = p.z_bounds
    nm = optimize.minimize(p.objective, p.start(norm), args=(norm,), method="Nelder-Mead", bounds=list(zip(lb, ub)),
                           options={"xatol": 1e-12, "fatol": 1e-15, "maxfev": 20000, "adaptive": True})
    assert p.objective(z, norm) <= nm.fun * (1 + 1e-6) and limits_kept(p, z, b)
    assert ok and msg == "SLSQP: Optimization terminated successfully"
    # from another start (the driver's restarts give one) the same optimum
    z2, _, _ = _fit_slsqp(p, norm, z0=np.array([0.5, 0.5, 0.5]))
    assert p.objective(z2, norm) == pytest.approx(p.objective(z, norm), rel=1e-6)


def test_slsqp_keeps_a_slider_devices_limits():
    """The sine device with a force and a free-length limit: both bind, both kept (force and stroke from r·cos φ)."""
    p = _SliderProblem("sine", -30.0, math.radians(-80), math.radians(250), SINE, 21, "max")
    z, msg, ok = _fit_slsqp(p, "max")
    rho, eps, lam, al, viol = p.decode(z)
    kappa = p.best_kappa(rho, eps, lam, al, "max")
    x = rho * np.cos(np.linspace(p.lo, p.hi, 20001))
    stroke = x.max() - x.min()
    force = kappa * 30.0 / 0.12 ** 2 * 0.12 * (al + stroke)       # c·(a + stroke), c = κ·|Φ0|/ℓ²
    assert viol == 0.0 and force <= 1500.0 * (1 + 1e-6) and 0.12 * (al + stroke) <= 0.5 * 0.5 * (1 + 1e-9)
    assert force == pytest.approx(1500.0, rel=1e-6) and 0.12 * (al + stroke) == pytest.approx(0.25, rel=1e-6)
    lb, ub = p.z_bounds
    nm = optimize.minimize(p.objective, p.start("max"), args=("max",), method="Nelder-Mead", bounds=list(zip(lb, ub)),
                           options={"xatol": 1e-12, "fatol": 1e-15, "maxfev": 20000, "adaptive": True})
    assert p.objective(z, "max") <= nm.fun * (1 + 1e-6) and ok


@pytest.mark.parametrize("grid", [21, 61])
def test_trf_lawson_reweighting_nears_the_minimax_error(grid):
    """trf alone on the max norm: within 0.5 % of SLSQP's minimax error (plain least squares is several % off)."""
    kind, moment, rng, b = INTERIOR
    p = _Problem(kind, moment, *rng, b, grid, "max")
    minimax = p.objective(_fit_slsqp(p, "max")[0], "max")
    z, msg, ok = _fit_trf(p, "max")
    assert minimax <= p.objective(z, "max") <= minimax * 1.005
    assert msg == "least_squares (trf) with Lawson reweighting for the max norm"
    plain = _fit_trf(_Problem(kind, moment, *rng, b, grid, "rms"), "rms")[0]
    assert p.objective(plain, "max") > minimax * 1.02


def test_trf_on_the_rms_norm_reaches_slsqps_optimum_and_says_how_it_ended():
    kind, moment, rng, b = INTERIOR
    p = _Problem(kind, moment, *rng, b, 21, "rms")
    z, msg, ok = _fit_trf(p, "rms")
    ref = p.objective(_fit_slsqp(p, "rms")[0], "rms")
    assert p.objective(z, "rms") == pytest.approx(ref, rel=1e-6) and limits_kept(p, z, b)
    assert ok and msg.endswith("termination condition is satisfied.")


def test_trf_keeps_a_tension_springs_free_length_in_its_box():
    """r0 − a ≤ 0.06 m with a ≤ 0.05 m: r0 ≤ 0.11 m is in trf's box, so it ends at the limit, not past it."""
    b = SpringBounds(r=(0.05, 0.5), r0=(0.1, 1.0), a=(0.0, 0.05), max_force=300.0, max_free_length=0.06)
    for norm in ("rms", "max"):
        p = _Problem("tension", -100.0, *MID, b, 21, norm)
        z, _, _ = _fit_trf(p, norm)
        rho, rho0, al, viol = p.decode(z)
        assert viol == 0.0 and (rho * 0.5, rho0 * 0.5, al * 0.5) == pytest.approx((0.5, 0.11, 0.05), rel=1e-6)


@pytest.mark.parametrize("b", [SpringBounds((0.2, 0.2), (0.3, 0.3), (0.0, 0.1)), SpringBounds((0.1, 0.2), (0.3, 0.3), (0.0, 0.1))])
@pytest.mark.parametrize("norm", ["max", "rms"])
def test_trf_takes_a_length_fixed_by_a_range_of_one_value(b, norm):
    """Bug (29 Nov 2026): a range of one value (a crank or r0 fixed) ended trf in scipy's ValueError "Each lower
    bound must be strictly less than each upper bound" (a traceback of `balance spring --method trf`), where every
    other method fits; now the fixed variable is held and trf reaches SLSQP's error."""
    from balance import fit_spring

    res = fit_spring("tension", -100.0, MID, b, method="trf", norm=norm, grid=21)
    ref = fit_spring("tension", -100.0, MID, b, method="slsqp", norm=norm, grid=21)
    assert (res.r, res.r0) == pytest.approx((ref.r, 0.3), rel=1e-6) and res.method == "trf"
    key = "grid_max_rel_error" if norm == "max" else "grid_rms_rel_error"
    assert getattr(res, key) == pytest.approx(getattr(ref, key), rel=1e-8)


def test_trf_on_the_only_device_an_exact_one():
    """r, r0 and a = r0 fixed: the one device is exact, its errors 0 to the last bit, and Lawson's reweighting
    (weights |e| summing to 0) stops at once."""
    from balance import fit_spring

    b = SpringBounds((0.2, 0.2), (0.3, 0.3), (0.3, 0.3))
    p = _Problem("tension", -100.0, *MID, b, 21, "max")
    z, msg, ok = _fit_trf(p, "max")
    assert p.objective(z, "max") == 0.0 and ok
    assert fit_spring("tension", -100.0, MID, b, method="trf").max_rel_error < 1e-12


def test_trf_from_a_dead_centre():
    """A range from φ = 0, where the weight |sin φ| and so the error are 0: Lawson's weights stay positive (a
    weight of 0 plus 1e-300) and trf ends near the minimax error."""
    p = _Problem("compression", 100.0, 0.0, math.pi, ISSUE, 21, "max")
    z, _, _ = _fit_trf(p, "max")
    minimax = p.objective(_fit_slsqp(p, "max")[0], "max")
    assert minimax <= p.objective(z, "max") <= minimax * 1.005


def test_trf_on_the_rms_norm_where_the_scale_is_free():
    """No force limit: κ is the least-squares one inside trf's residuals too, and trf reaches SLSQP's RMS optimum
    (the crank at its shortest, the free length at its limit, r0 against a)."""
    b = SpringBounds(r=(0.03, 0.21), r0=(0.15, 1.2), a=(0.0, 0.6), max_free_length=0.65)
    p = _Problem("compression", 100.0, math.radians(-36), math.radians(160), b, 21, "rms")
    z, _, _ = _fit_trf(p, "rms")
    assert p.objective(z, "rms") == pytest.approx(p.objective(_fit_slsqp(p, "rms")[0], "rms"), rel=1e-9)


@pytest.mark.parametrize("norm", ["rms", "max"])
def test_trf_stops_just_past_a_coupled_limit(norm):
    """A compression spring's free length and deflection with a lower bound on a couple r and r0: trf (a penalty
    of 10× the violation against errors scaled by 1/√N) stops within 1e-4 ℓ past the limit (6e-5 and 1.5e-6
    measured), and 10 % or so above SLSQP's error; the driver's restart brings it back (test_fit.py)."""
    b = SpringBounds(r=(0.0956, 0.2378), r0=(0.1631, 1.1118), a=(0.0717, 0.6667), max_force=2920.0,
                     max_free_length=0.7321, max_deflection=0.3991)
    p = _Problem("compression", 100.0, math.radians(-25.2), math.radians(145.07), b, 61, norm)
    z, _, _ = _fit_trf(p, norm)
    assert p.decode(z)[3] <= 1e-4
    assert p.objective(z, norm) <= 1.2 * p.objective(_fit_slsqp(p, norm)[0], norm)


@pytest.mark.parametrize("device, b", [
    # no offset range: an in-line guide, the offset fixed at 0 (the default of the slider-crank)
    ("slider-crank", SpringBounds((0.02, 0.2), None, (0.0, 0.5), max_free_length=0.6, rod=(0.1, 0.6))),
    ("sine", SpringBounds((0.1, 0.1), None, (0.0, 0.3), max_free_length=0.6)),
])
def test_trf_on_a_slider_device_with_a_fixed_variable(device, b):
    """The same bug on the slider devices: a slider-crank without an offset range (its guide in line) ended trf in
    scipy's ValueError; now trf reaches SLSQP's error."""
    from balance import fit_spring

    res = fit_spring("compression", 50.0, MID, b, device=device, method="trf", grid=21)
    ref = fit_spring("compression", 50.0, MID, b, device=device, method="slsqp", grid=21)
    assert res.grid_max_rel_error == pytest.approx(ref.grid_max_rel_error, rel=1e-8)
    assert res.offset in (None, 0.0) and res.method == "trf"
