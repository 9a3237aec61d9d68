"""Method ``"de"``: :func:`scipy.optimize.differential_evolution` (fixed seed) on the
projected norm, polished by SLSQP."""

from __future__ import annotations

from scipy import optimize

from .problem import _Problem
from .slsqp import _fit_slsqp


def _fit_de(p: _Problem, norm: str):
    lb, ub = p.z_bounds
    sol = optimize.differential_evolution(
        p.objective, list(zip(lb, ub)), args=(norm,), seed=12345, tol=1e-6, atol=0,
        maxiter=80, popsize=8, polish=False, init="sobol",
    )
    # polish locally from the global candidate
    z, (z2, _, ok) = sol.x, _fit_slsqp(p, norm, z0=sol.x)
    if p.objective(z2, norm) <= p.objective(z, norm):
        z = z2
    return z, "differential_evolution (seed 12345) polished by SLSQP", ok
