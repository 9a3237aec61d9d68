"""Fitting spring devices to a target moment ``Φ0·sin φ``: the slotted lever, the slider-crank, the sine device.

The slotted lever (crank-and-rocker, the spring along the lever from the crank pin ``B`` to the base
point ``C``) is described here; the slider devices in :mod:`.slider_problem`. Its moment is
``M(φ) = ±c·r·d·sin φ·g(φ)`` with a *shape* ``g`` that depends on length ratios only
(``g = l0/L − 1`` for compression, ``1 − l0/L`` for tension).
Everything is therefore solved in non-dimensional variables

    ρ = r/ℓ,  ρ0 = r0/ℓ,  α = a/ℓ   (ℓ = upper bound of r),   κ = c·r·d/|Φ0|,

and the relative error ``e(φ) = |sin φ|·(κ·g(φ) − 1)`` never divides by ``sin φ``.
For fixed geometry ``e`` is linear in ``κ``: the optimal ``κ`` is closed-form for the
RMS norm and a one-dimensional convex problem for the max norm (variable projection).
The constraints that involve ``a`` (free length, deflection ratio, ``a ≤ r0`` for
tension) are upper/lower limits of ``α`` given ``(ρ, ρ0)``, so ``α`` is mapped from a
unit variable ``t``; the force limit is a limit on ``κ``. The projected problems
therefore have box bounds only.

Methods (``method=``): ``"trf"`` — :func:`scipy.optimize.least_squares` (trust-region
reflective) on the projected residuals (for the max norm: Lawson's iteratively
reweighted least squares); ``"slsqp"`` — :func:`scipy.optimize.minimize` SLSQP on the
full variables with explicit constraints (epigraph form for the max norm);
``"nelder-mead"`` — bounded Nelder–Mead on the projected norm; ``"de"`` —
:func:`scipy.optimize.differential_evolution` (fixed seed) on the projected norm,
polished by SLSQP.

The package follows the seams of the problem: :mod:`.result` (the shared :class:`FitResult`),
:mod:`.problem` (the non-dimensional problem), one module per method (:mod:`.trf`,
:mod:`.slsqp`, :mod:`.nelder_mead`, :mod:`.de`), :mod:`.exact` (the exact devices) the slider
devices' problem (:mod:`.slider_problem`), the table of devices (:mod:`.kinds`) and :mod:`.driver`
(:func:`fit_spring`).

Besides the slotted lever (``device="slotted-lever"``, the crank with an oscillating slotted lever
above), :data:`DEVICES` holds the offset slider-crank and the sine (Scotch-yoke) device with a real
spring on the slider (:mod:`balance.devices.sliders`), fitted by the same methods into the same
:class:`FitResult`.
"""

from __future__ import annotations

from .driver import DEFAULT_METHOD, METHODS, fit_spring
from .kinds import DEFAULT_DEVICE, DEVICES, DeviceKind
# the helpers the tests check directly
from .problem import _cluster, _max_abs_sin, _minimax_scale, _Problem, _sin2_half_extremes
from .result import (
    DEFAULT_GRID, MAX_GRID, NORMS, FitResult, LeverGeometry, SpringBounds, dead_centre_notes, relative_errors,
)

__all__ = [
    "SpringBounds",
    "FitResult",
    "fit_spring",
    "METHODS",
    "NORMS",
    "DEFAULT_METHOD",
    "DEFAULT_GRID",
    "MAX_GRID",
    "LeverGeometry",
    "relative_errors",
    "DEVICES",
    "DEFAULT_DEVICE",
    "DeviceKind",
]
