"""A spring device for ``Φ0·sin φ``: the fit, its trade-offs and a spring to order.

The device is the crank with a slotted lever (crank-and-rocker, the default), the offset slider-crank
or the sine device (:data:`~balance.devices.fit.DEVICES`).

:class:`SpringProblem` (read from a ``[spring]`` table or built by the caller) is solved into a
:class:`SpringDesign`: the fit (:class:`~balance.devices.fit.FitResult`), for a fitted
device the sensitivity to each bound it sits on and, on request, the Pareto front, the
warnings these give, the requested error met or not, and a helical spring
(:class:`~balance.devices.helical.HelicalSpring`) with, for the compression-lever device,
the lever it fixes.

Examples
--------
>>> import math
>>> from balance.devices.fit import SpringBounds
>>> res = SpringProblem("tension", -50.0, (0.0, math.pi), SpringBounds((0.05, 0.1), (0.1, 0.2), (0.0, 0.3))).solve()
>>> res.fit.method, res.fit.max_rel_error < 1e-12
('exact', True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Mapping

from mechbase import Row

from ..devices.fit import DEFAULT_GRID, FitResult, LeverGeometry, SpringBounds, fit_spring
from ..devices.helical import HelicalSpring, design_for_device
from ..devices.tradeoff import ParetoPoint, Sensitivity, advice, bound_sensitivity, pareto_front
from ..errors import InvalidInput, SchemaError
from ..schema import parse

__all__ = ["SpringProblem", "SpringDesign", "SpringOptions", "spring_problem"]


@dataclass(frozen=True)
class SpringOptions:
    """How to design the helical spring (see :func:`~balance.devices.helical.design_spring`)."""

    material: str = "music-wire"
    max_outer_diameter: float | None = None
    min_inner_diameter: float = 0.0
    ends: str = "pinned"
    guided: bool | None = None

    def kwargs(self) -> dict:
        out = {"material": self.material, "max_outer_diameter": self.max_outer_diameter,
               "min_inner_diameter": self.min_inner_diameter, "ends": self.ends}
        if self.guided is not None:
            out["guided"] = self.guided
        return out


@dataclass(frozen=True)
class SpringDesign(Row):
    """What :class:`SpringProblem` finds (its row, :meth:`to_dict`, is the JSON): the fit's row, its
    lever and notes as the designed spring fixes them, then the sensitivity, trade-off and spring."""

    fit: FitResult
    sensitivity: tuple[Sensitivity, ...]
    pareto: tuple[ParetoPoint, ...] | None
    warnings: tuple[str, ...]
    target_error: float | None
    spring: HelicalSpring | None = None

    row_keys = ("*designed_fit", "sensitivity", "pareto?", "warnings", "target_error", "target_met", "spring?",
                "kind_of_problem")
    kind_of_problem = "spring"

    @property
    def error(self) -> float:
        """The fit's error in its own norm."""
        return self.fit.max_rel_error if self.fit.norm == "max" else self.fit.rms_rel_error

    @property
    def target_met(self) -> bool | None:
        return None if self.target_error is None else self.error <= self.target_error

    @property
    def lever(self) -> LeverGeometry | None:
        """The compression-lever device's lever: fixed by the designed spring when there is one."""
        lv = self.fit.lever
        if lv is None or self.spring is None:
            return lv
        return LeverGeometry.for_spring(self.spring.free_length_m, lv.compression_min, lv.compression_max, True)

    @property
    def designed_fit(self) -> FitResult:
        """The fit, its lever, deflection and lever note replaced by those of the designed spring's lever."""
        lever = self.lever
        if self.spring is None or lever is None or not lever.designed_from_spring:
            return self.fit
        notes = tuple(n for n in self.fit.notes if not n.startswith("the lever reaches")) + (lever.note(),)
        return replace(self.fit, lever=lever, deflection=lever.deflection_ratio, notes=notes)


@dataclass(frozen=True)
class SpringProblem:
    """A crank-and-rocker device to fit to ``moment·sin φ`` over ``phi_range`` (rad) within ``bounds``.

    ``method``, ``norm`` and ``grid`` go to :func:`~balance.devices.fit.fit_spring`;
    ``target_error`` is the error asked for, ``pareto`` asks for the front (compression only),
    ``design`` for a helical spring.
    """

    kind: str
    moment: float
    phi_range: tuple[float, float]
    bounds: SpringBounds
    method: str | None = None
    norm: str = "max"
    grid: int = DEFAULT_GRID
    target_error: float | None = None
    pareto: bool = False
    design: SpringOptions | None = None
    device: str = "slotted-lever"

    def solve(self) -> SpringDesign:
        if self.target_error is not None and not (math.isfinite(self.target_error) and 0 < self.target_error < 1):
            raise InvalidInput(f"the requested error must lie in (0, 1), not {self.target_error}.")
        if self.pareto and self.device != "slotted-lever":
            raise InvalidInput(f"the Pareto front is drawn for the slotted lever's compression spring, not for the "
                               f"{self.device} device.")
        if self.pareto and self.kind != "compression":
            raise InvalidInput(f"the Pareto front is for the fitted compression device; a {self.kind} device is exact.")
        res = fit_spring(self.kind, self.moment, self.phi_range, self.bounds, method=self.method, norm=self.norm,
                         grid=self.grid, device=self.device)
        sens = tuple(bound_sensitivity(res, self.bounds)) if res.method != "exact" else ()
        front = tuple(pareto_front(res, self.bounds)) if self.pareto else None
        warnings = advice(res, list(sens), self.target_error, list(front) if front is not None else None)
        spring = None
        if self.design is not None:
            spring = design_for_device(res, **self.design.kwargs())
            b = spring.buckling
            if b is not None and not b.safe:
                warnings.append(f"the spring buckles (critical deflection {1e3 * b.critical_deflection_m:.3g} mm < "
                                f"{1e3 * b.max_deflection_m:.4g} mm): guide it on a rod or in a sleeve")
        return SpringDesign(res, sens, front, tuple(warnings), self.target_error, spring)


def spring_problem(doc: Mapping[str, Any], source: str = "<spring>") -> SpringProblem:
    """The :class:`SpringProblem` of a parsed TOML document with a ``[spring]`` table.

    Examples
    --------
    >>> p = spring_problem({"spring": {"kind": "tension", "moment": -50.0, "range_deg": [0, 180],
    ...                                "r": [0.05, 0.1], "r0": [0.1, 0.2], "a": [0, 0.3]}})
    >>> p.solve().fit.max_rel_error < 1e-12
    True
    """
    t = parse(doc, "spring", source)
    if t.a is None:
        raise SchemaError(f"{source}: [spring] needs the key 'a' = [low, high] (m).")
    if t.device == "slotted-lever" and t.r0 is None:
        raise SchemaError(f"{source}: [spring] needs the key 'r0' = [low, high] (m) for the slotted-lever device.")
    if "kind" in doc["spring"] and t.device != "slotted-lever" and t.kind != "compression":
        raise SchemaError(f"{source}: [spring] the {t.device} device carries a compression spring; "
                          f"leave out kind = {t.kind!r}.")
    design = None
    if t.design is not None:
        d = t.design
        design = SpringOptions(d.material, d.max_outer_diameter, d.min_inner_diameter, d.ends, d.guided)
    pair = lambda v: None if v is None else tuple(v)  # noqa: E731
    return SpringProblem(t.kind, t.moment, (math.radians(t.range_deg[0]), math.radians(t.range_deg[1])),
                         SpringBounds(tuple(t.r), pair(t.r0), tuple(t.a), t.max_force, t.max_free_length,
                                      t.max_deflection, pair(t.rod), pair(t.offset)),
                         t.method, t.norm, t.grid, t.target_error, t.pareto, design, t.device)
