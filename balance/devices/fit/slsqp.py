"""Method ``"slsqp"``: :func:`scipy.optimize.minimize` SLSQP on the full variables
``(ρ, ρ0, α, κ)`` with explicit constraints (epigraph form ``τ`` for the max norm)."""

from __future__ import annotations

import warnings

import numpy as np
from scipy import optimize

from .problem import _Problem


def _fit_slsqp(p: _Problem, norm: str, z0=None):
    """SLSQP on the problem's full variables (``y = (ρ, ρ0, α, κ)`` for the slotted lever) with its
    explicit constraints; for the max norm in epigraph form (one more variable ``τ``)."""
    z0 = p.start(norm) if z0 is None else z0
    y0, bounds, cons, err = p.full_problem(z0, norm)
    if norm == "rms":
        fun = lambda y: float(np.mean(err(y) ** 2))  # noqa: E731
        x0 = np.array(y0)
    else:
        e0 = err(y0)
        tau = len(y0)
        x0 = np.array(y0 + [float(np.max(np.abs(e0)))])
        bounds = bounds + [(0.0, None)]
        fun = lambda y: y[tau]  # noqa: E731
        cons.append({"type": "ineq", "fun": lambda y: y[tau] - err(y)})
        cons.append({"type": "ineq", "fun": lambda y: y[tau] + err(y)})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        sol = optimize.minimize(
            fun, x0, method="SLSQP", bounds=bounds, constraints=cons,
            options={"ftol": 1e-15, "maxiter": 500},
        )
    return p.encode_full(sol.x), f"SLSQP: {sol.message}", bool(sol.success)
