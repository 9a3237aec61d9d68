"""Method ``"trf"``: :func:`scipy.optimize.least_squares` (trust-region reflective) on the
projected residuals; for the max norm Lawson's iteratively reweighted least squares."""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from .problem import _Problem


def _fit_trf(p: _Problem, norm: str):
    z0 = p.start(norm)
    lb, ub = p.z_bounds
    sq = math.sqrt(len(p.phi))

    def run(z_start, weights):
        def fun(z):
            e, _, viol = p.projected(z, "rms", weights)
            r = e if weights is None else np.sqrt(weights) * e
            return np.append(r / sq, 10.0 * viol)

        return optimize.least_squares(
            fun, z_start, bounds=(lb, ub), method="trf", x_scale="jac",
            ftol=1e-12, xtol=1e-12, gtol=1e-12,
        )

    sol = run(z0, None)
    z = sol.x
    msg, ok = sol.message, sol.status > 0
    if norm == "max":
        # Lawson's algorithm: reweight by the error magnitude, refit, keep the best max-norm point
        v = np.full(len(p.phi), 1.0 / len(p.phi))
        best, bz = p.objective(z, "max"), z
        for _ in range(40):
            e, _, _ = p.projected(z, "rms", v)
            v = v * np.abs(e)
            tot = v.sum()
            if not tot > 0:
                break
            v = v / tot + 1e-300
            z = run(z, v).x
            val = p.objective(z, "max")
            if val < best:
                best, bz = val, z
        z, msg = bz, "least_squares (trf) with Lawson reweighting for the max norm"
    return z, msg, ok
