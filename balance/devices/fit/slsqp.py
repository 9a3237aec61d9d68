"""Method ``"slsqp"``: :func:`scipy.optimize.minimize` SLSQP on the full variables
``(ρ, ρ0, α, κ)`` with explicit constraints (epigraph form ``τ`` for the max norm)."""

from __future__ import annotations

import math
import warnings

import numpy as np
from scipy import optimize

from .problem import _Problem


def _fit_slsqp(p: _Problem, norm: str, z0=None):
    """SLSQP on ``y = (ρ, ρ0, α, κ[, τ])`` with explicit constraints."""
    z0 = p.start(norm) if z0 is None else z0
    rho, rho0, al, _ = p.decode(z0)
    k = p.best_kappa(rho, rho0, al, norm)
    y0 = [rho, rho0, al, k]
    al_hi = p.al_b[1] if math.isfinite(p.al_b[1]) else None
    bounds = [p.rho_b, p.rho0_b, (p.al_b[0], al_hi), (0.0, None)]
    cons: list[dict] = []

    def l_at(y, s2):
        return math.sqrt(y[1] ** 2 + 4 * y[0] * (y[0] + y[1]) * s2)

    if p.kind == "compression":
        if math.isfinite(p.Lf):
            cons.append({"type": "ineq", "fun": lambda y: p.Lf - (2 * y[0] + y[1] + y[2])})
        if p.delta is not None:
            cons.append({"type": "ineq", "fun": lambda y: l_at(y, p.s2min) - (1 - p.delta) * (2 * y[0] + y[1] + y[2])})
        if math.isfinite(p.Fhat):
            cons.append({"type": "ineq", "fun": lambda y: p.Fhat * y[0] * (y[0] + y[1]) - y[3] * (2 * y[0] + y[1] + y[2] - l_at(y, p.s2min))})
    else:
        cons.append({"type": "ineq", "fun": lambda y: y[1] - y[2]})
        if math.isfinite(p.Lf):
            cons.append({"type": "ineq", "fun": lambda y: p.Lf - (y[1] - y[2])})
        if math.isfinite(p.Fhat):
            cons.append({"type": "ineq", "fun": lambda y: p.Fhat * y[0] * (y[0] + y[1]) - y[3] * (l_at(y, p.s2max) - (y[1] - y[2]))})

    def err(y):
        return p.errors(y[0], y[1], y[2], y[3])

    if norm == "rms":
        fun = lambda y: float(np.mean(err(y) ** 2))  # noqa: E731
        x0 = np.array(y0)
    else:
        e0 = err(y0)
        x0 = np.array(y0 + [float(np.max(np.abs(e0)))])
        bounds = bounds + [(0.0, None)]
        fun = lambda y: y[4]  # noqa: E731
        cons.append({"type": "ineq", "fun": lambda y: y[4] - err(y)})
        cons.append({"type": "ineq", "fun": lambda y: y[4] + err(y)})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        sol = optimize.minimize(
            fun, x0, method="SLSQP", bounds=bounds, constraints=cons,
            options={"ftol": 1e-15, "maxiter": 500},
        )
    y = sol.x
    return p.encode(y[0], y[1], y[2]), f"SLSQP: {sol.message}", bool(sol.success)
