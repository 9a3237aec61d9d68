"""Method ``"nelder-mead"``: bounded (adaptive) Nelder–Mead on the projected norm."""

from __future__ import annotations

from scipy import optimize

from .problem import _Problem


def _fit_nelder_mead(p: _Problem, norm: str):
    lb, ub = p.z_bounds
    sol = optimize.minimize(
        p.objective, p.start(norm), args=(norm,), method="Nelder-Mead", bounds=list(zip(lb, ub)),
        options={"xatol": 1e-10, "fatol": 1e-14, "maxfev": 3000, "adaptive": True},
    )
    return sol.x, sol.message, bool(sol.success)
