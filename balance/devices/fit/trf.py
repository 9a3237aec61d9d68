"""Method ``"trf"``: :func:`scipy.optimize.least_squares` (trust-region reflective) on the
projected residuals; for the max norm Lawson's iteratively reweighted least squares."""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from .problem import _Problem


def _fit_trf(p: _Problem, norm: str):
    z0 = p.start(norm)
    lb, ub = (np.asarray(v) for v in p.z_bounds)
    free = lb < ub  # least_squares takes no variable whose range is one value (a length fixed): it is held there
    sq = math.sqrt(len(p.phi))

    def run(z_start, weights):
        """The least-squares point from ``z_start`` (its fixed variables kept) and scipy's result."""
        def at(x):
            z = np.array(z_start)
            z[free] = x
            return z

        def fun(x):
            e, _, viol = p.projected(at(x), "rms", weights)
            r = e if weights is None else np.sqrt(weights) * e
            return np.append(r / sq, 10.0 * viol)

        sol = optimize.least_squares(
            fun, np.asarray(z_start)[free], bounds=(lb[free], ub[free]), method="trf", x_scale="jac",
            ftol=1e-12, xtol=1e-12, gtol=1e-12,
        )
        return at(sol.x), sol

    z, sol = run(z0, None)
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
            z, _ = run(z, v)
            val = p.objective(z, "max")
            if val < best:
                best, bz = val, z
        z, msg = bz, "least_squares (trf) with Lawson reweighting for the max norm"
    return z, msg, ok
