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
