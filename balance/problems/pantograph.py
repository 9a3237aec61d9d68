"""The pantograph balanced manipulator: its spring, and its cylinder's force over the workspace.

:class:`PantographProblem` (the mechanism of :mod:`balance.model.pantograph`, the spring's
size, the check's samples) is solved into a :class:`PantographBalance`. Every range it reports
(cylinder and hand forces, cylinder length and lever arm, the residual) is a true extreme over
the workspace: the random ``(θ2, θ3)`` start a bounded local search
(:func:`balance.extremes.box_extremes`). The force is linear in the payload, so its extremes
over payloads 0 … max are those at 0 and at the maximum.

Examples
--------
>>> from balance.model.pantograph import Pantograph
>>> res = PantographProblem(Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0, tool=20.0), samples=50).solve()
>>> res.relative_residual < 1e-12, res.force[0.5][0].value < res.force[0.5][1].value
(True, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from mechbase import Row

from ..budget import WORK_LIMIT, ensure_affordable
from ..errors import InvalidArm
from ..extremes import EXTREMES_NOTE, Extreme, box_extremes
from ..model.arm import DescribedTerm
from ..model.pantograph import PAYLOADS, Pantograph, stroke_gradients
from ..schema import PantographTable, parse
from .arm import SineSizes, TensionSizes

__all__ = ["PantographProblem", "PantographBalance", "pantograph_problem"]


def _forces(p: Pantograph, th: np.ndarray) -> np.ndarray:
    """Per configuration: F and R at payloads 0, ½, 1 (m, 6)."""
    return np.stack([p.cylinder_force(th, f) for f in PAYLOADS] + [p.hand_force(th, f) for f in PAYLOADS], axis=1)


def _cylinder(p: Pantograph, th: np.ndarray) -> np.ndarray:
    """Per configuration: the cylinder's length and lever arm about A (m, 2)."""
    length, _, lever = p.cylinder(th)
    return np.stack([length, lever], axis=1)


def _gravity(p: Pantograph, th: np.ndarray) -> np.ndarray:
    """Per configuration: the gravity forces on (θ2, θ3) at payloads 0, ½, 1 (m, 6)."""
    return np.concatenate([p.gravity_forces(th, frac) for frac in PAYLOADS], axis=1)


def _residuals(p: Pantograph, th: np.ndarray) -> np.ndarray:
    """Per configuration: the virtual-work residual on (θ2, θ3) at payloads 0, ½, 1 (m, 6)."""
    ds, drho = stroke_gradients(p, th)
    t = p.term()
    res = []
    for frac in PAYLOADS:
        q = p.gravity_forces(th, frac)
        q[:, 0] += t.moment(th[:, 0])
        res.append(q + p.cylinder_force(th, frac)[:, None] * ds + p.hand_force(th, frac)[:, None] * drho)
    return np.concatenate(res, axis=1)


def _magnitude(pair: tuple[Extreme, Extreme]) -> float:
    return max(-pair[0].value, pair[1].value)


@dataclass(frozen=True)
class Span(Row):
    """The smallest and largest value of a quantity."""

    min: float
    max: float


@dataclass(frozen=True)
class ExtremesAt(Row):
    """The smallest and largest value of a quantity and the arm's angles (degrees) where they are reached."""

    min: float
    max: float
    at_min_deg: tuple[float, ...]
    at_max_deg: tuple[float, ...]

    @classmethod
    def of(cls, low: Extreme, high: Extreme) -> "ExtremesAt":
        return cls(low.value, high.value, _degrees(low), _degrees(high))


@dataclass(frozen=True)
class CylinderForce(Row):
    """The cylinder's force over the workspace and the payload range, at half the payload, by payload
    fraction, and the best of the random samples alone."""

    min: float
    max: float
    at_min_deg: tuple[float, ...]
    at_max_deg: tuple[float, ...]
    half_payload: ExtremesAt
    by_payload: dict[str, Span]
    sampled: Span


@dataclass(frozen=True)
class CylinderSizes(Row):
    """The cylinder's base point, its shortest and longest length and its shortest and longest lever about A."""

    base: tuple[float, ...]
    length_min: float
    length_max: float
    lever_min: float
    lever_max: float


@dataclass(frozen=True)
class PantographDevices(Row):
    """The spring devices that cancel the pantograph's one term."""

    sine: SineSizes
    tension: TensionSizes


def _degrees(e: Extreme) -> tuple[float, ...]:
    return tuple(math.degrees(v) for v in e.at)


@dataclass(frozen=True)
class PantographBalance(Row):
    """What :class:`PantographProblem` finds (its row, :meth:`to_dict`, is the JSON).

    ``force`` and ``hand`` map each payload fraction (0, ½, 1) to the (min, max)
    :class:`~balance.extremes.Extreme` of the cylinder's force and of the operator's force along
    ``A→C`` over the workspace; ``length`` and ``lever`` those of the cylinder's length and of its
    lever arm about ``A``; ``residual`` the largest virtual-work residual per payload.
    """

    pantograph: Pantograph
    force: dict[float, tuple[Extreme, Extreme]]
    hand: dict[float, tuple[Extreme, Extreme]]
    length: tuple[Extreme, Extreme]
    lever: tuple[Extreme, Extreme]
    residual: dict[float, float]
    max_gravity_force: float
    samples: int
    seed: int
    r: float | None = None
    r0: float | None = None

    @property
    def force_range(self) -> tuple[Extreme, Extreme]:
        """The cylinder force's extremes over the workspace and payloads 0 … max."""
        ends = (self.force[0.0], self.force[1.0])
        return min((e[0] for e in ends), key=lambda e: e.value), max((e[1] for e in ends), key=lambda e: e.value)

    @property
    def hand_range(self) -> tuple[Extreme, Extreme]:
        ends = (self.hand[0.0], self.hand[1.0])
        return min((e[0] for e in ends), key=lambda e: e.value), max((e[1] for e in ends), key=lambda e: e.value)

    @property
    def max_residual(self) -> float:
        return max(self.residual.values())

    @property
    def relative_residual(self) -> float:
        return self.max_residual / self.max_gravity_force if self.max_gravity_force > 0 else 0.0

    @property
    def notes(self) -> list[str]:
        """What a designer must know of the forces: a pulling cylinder, a large hand force."""
        p = self.pantograph
        lo, hi = self.hand_range
        hand_peak = max(-lo.value, hi.value)
        load = p.vertical_load(1.0)
        out = []
        if self.force_range[0].value < 0:
            out.append("the cylinder pulls somewhere in the workspace (negative force): it must be double-acting")
        if hand_peak > 0.05 * load:
            out.append(f"the operator holds up to {hand_peak:.3g} N along A→C ({100 * hand_peak / load:.3g} % of the "
                       f"full load {load:.4g} N reduced to B): a base P further below B keeps the cylinder nearer "
                       "vertical")
        return out

    row_keys = ("point_weights", "point_weights_without_payload", "term", "device", "spring_moment", "drive_force",
                "drive_force_range", "cylinder_force", "hand_force", "cylinder", "max_residual",
                "residual_by_payload", "max_gravity_force", "relative_residual", "samples", "seed", "extremes",
                "notes", "note")
    extremes = EXTREMES_NOTE
    note = "the payload sits at C: it changes the cylinder and hand forces, never the spring"

    @property
    def point_weights(self) -> dict[str, float]:
        return self.pantograph.point_weights(0.5)

    @property
    def point_weights_without_payload(self) -> dict[str, float]:
        return self.pantograph.point_weights(0.0)

    @property
    def term(self) -> DescribedTerm:
        """The one harmonic term, ``A·cos θ2``."""
        t = self.pantograph.term()
        return DescribedTerm(t.amplitude, t.phase, t.form, "θ2")

    @property
    def device(self) -> PantographDevices:
        a = self.pantograph.term().amplitude
        return PantographDevices(SineSizes(a), TensionSizes.of(a, 90.0, self.r, self.r0))

    @property
    def spring_moment(self) -> str:
        return f"{self.pantograph.term().amplitude:.6g}·cos θ2 on the upper arm (base point C above A)"

    @property
    def drive_force(self) -> float:
        return self.pantograph.vertical_load(0.5)

    @property
    def drive_force_range(self) -> tuple[float, float]:
        return self.pantograph.vertical_load(0.0), self.pantograph.vertical_load(1.0)

    @property
    def cylinder_force(self) -> CylinderForce:
        f_lo, f_hi = self.force_range
        return CylinderForce(f_lo.value, f_hi.value, _degrees(f_lo), _degrees(f_hi),
                             ExtremesAt.of(*self.force[0.5]),
                             {str(f): Span(lo.value, hi.value) for f, (lo, hi) in self.force.items()},
                             Span(f_lo.sampled, f_hi.sampled))

    @property
    def hand_force(self) -> Span:
        lo, hi = self.hand_range
        return Span(lo.value, hi.value)

    @property
    def cylinder(self) -> CylinderSizes:
        levers = abs(self.lever[0].value), abs(self.lever[1].value)
        return CylinderSizes(tuple(float(v) for v in self.pantograph.cylinder_base), self.length[0].value,
                             self.length[1].value, min(levers), max(levers))

    @property
    def residual_by_payload(self) -> dict[str, float]:
        return {str(f): v for f, v in self.residual.items()}


@dataclass(frozen=True)
class PantographProblem:
    """A pantograph manipulator to balance: the mechanism, the spring's crank ``r`` and ``r0`` (m,
    optional: then its rate is given too) and the random configurations (seeded) of the checks."""

    pantograph: Pantograph
    r: float | None = None
    r0: float | None = None
    samples: int = 1000
    seed: int = 0
    work_limit: float | None = WORK_LIMIT

    def solve(self) -> PantographBalance:
        p = self.pantograph
        probe = p.sample(64, self.seed)

        def unit():
            with np.errstate(all="ignore"):  # a cylinder through A is refused below, not here
                return _forces(p, probe), _cylinder(p, probe), _gravity(p, probe), _residuals(p, probe)

        ensure_affordable(f"checking {self.samples} configurations", self.samples, unit, self.work_limit,
                          per=len(probe))
        th = p.sample(self.samples, self.seed)
        lo, hi = [p.range2[0], p.range3[0]], [p.range2[1], p.range3[1]]
        length, lever = box_extremes(lambda x: _cylinder(p, x), lo, hi, th)
        if lever[0].value <= 1e-9 * p.l2 and lever[1].value >= -1e-9 * p.l2:
            raise InvalidArm("the cylinder's line of action passes through A in the workspace, so it cannot hold "
                             "the pantograph there; move its base (cylinder.base).")
        ext = box_extremes(lambda x: _forces(p, x), lo, hi, th)
        mg = max(_magnitude(e) for e in box_extremes(lambda x: _gravity(p, x), lo, hi, th))
        # the residual of an exact balance is rounding noise: searched only where it is more (as an arm's check)
        res = box_extremes(lambda x: _residuals(p, x), lo, hi, th, floor=1e-11 * mg)
        residual = {f: max(_magnitude(res[2 * i]), _magnitude(res[2 * i + 1])) for i, f in enumerate(PAYLOADS)}
        return PantographBalance(p, dict(zip(PAYLOADS, ext[:3])), dict(zip(PAYLOADS, ext[3:6])), length, lever,
                                 residual, mg, self.samples, self.seed, self.r, self.r0)


def pantograph_problem(doc: Mapping[str, Any], source: str = "<pantograph>") -> PantographProblem:
    """The :class:`PantographProblem` of a parsed TOML document with a ``[pantograph]`` table."""
    t: PantographTable = parse(doc, "pantograph", source)
    try:
        p = Pantograph(
            l2=t.l2, l3=t.l3, k=t.ratio,
            w2=t.upper.weight, w3=t.forearm.weight, w9=t.bar_eb.weight, w8=t.bar_fb.weight,
            w14=t.parallelogram_bars.weight, w15=t.parallelogram_bars.weight,
            w16=t.elbow_plate.weight, w4=t.wrist_plate.weight,
            s2=t.upper.com, s3=t.forearm.com, tool=t.tool, payload=t.payload, offset=t.parallelogram_offset,
            base=None if t.cylinder.base is None else tuple(t.cylinder.base),
            range2=tuple(math.radians(v) for v in t.range_upper_deg),
            range3=tuple(math.radians(v) for v in t.range_forearm_deg),
        )
    except InvalidArm as exc:
        raise InvalidArm(f"{source}: {exc}") from None
    return PantographProblem(p, t.spring.r, t.spring.r0, t.check.samples, t.check.seed)
