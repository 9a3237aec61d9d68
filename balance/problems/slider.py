"""Counter-masses for a sliding last link, and (on request) the mass matrix of an arm carrying it.

Examples
--------
>>> res = SliderProblem(2.0, 0.1, 2.0, 0.5).solve()
>>> res.counter_mass.C_min, res.dynamics is None
(0.85, True)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from mechbase import Row

from ..budget import WORK_LIMIT, ensure_affordable
from ..devices.countermass import CounterMass, verify_counter_mass
from ..devices.dynamics import SlideDynamics, slide_dynamics
from ..schema import parse

__all__ = ["SliderProblem", "SliderBalance", "DynamicsCheck", "slider_problem"]


@dataclass(frozen=True)
class DynamicsCheck:
    """The three-joint arm that carries the slide in the mass-matrix check (see :mod:`balance.devices.dynamics`)."""

    arm: str = "spatial"
    length: float = 0.5
    mass: float = 10.0
    samples: int = 200
    seed: int = 0


@dataclass(frozen=True)
class SliderBalance(Row):
    """The counter-mass design and, when asked, the mass-matrix check."""

    counter_mass: CounterMass
    dynamics: SlideDynamics | None = None

    row_keys = ("*counter_mass", "dynamics?")


@dataclass(frozen=True)
class SliderProblem:
    """A sliding link (mass ``m`` kg, transverse central inertia ``inertia`` kg·m²), two counter-masses
    ``M`` (kg) and the designed stroke ``±q_max`` (m); ``stroke`` the stroke travelled, ``C`` the
    inertia to keep (default ``C_min``), ``samples`` the points along the stroke that start the
    searches for the largest errors."""

    m: float
    inertia: float
    M: float
    q_max: float
    stroke: float | None = None
    C: float | None = None
    samples: int = 2001
    dynamics: DynamicsCheck | None = None
    work_limit: float | None = WORK_LIMIT

    def solve(self) -> SliderBalance:
        ensure_affordable(f"checking the laws at {self.samples} points", self.samples,
                          lambda: verify_counter_mass(self.m, self.inertia, self.M, self.q_max, self.stroke,
                                                      self.C, 64), self.work_limit, per=64)
        res = verify_counter_mass(self.m, self.inertia, self.M, self.q_max, stroke=self.stroke, C=self.C,
                                  samples=self.samples)
        dyn = None
        if self.dynamics is not None:
            d = self.dynamics
            ensure_affordable(f"the mass-matrix check at {d.samples} configurations", d.samples,
                              lambda: slide_dynamics(self.m, self.inertia, self.M, self.q_max, d.arm, d.length,
                                                     d.mass, 1, d.seed), self.work_limit)
            dyn = slide_dynamics(self.m, self.inertia, self.M, self.q_max, d.arm, d.length, d.mass, d.samples, d.seed)
        return SliderBalance(res, dyn)


def slider_problem(doc: Mapping[str, Any], source: str = "<slider>") -> SliderProblem:
    """The :class:`SliderProblem` of a parsed TOML document with a ``[slider]`` table.

    Examples
    --------
    >>> slider_problem({"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 2, "q_max": 0.5}}).solve().counter_mass.C_min
    0.85
    """
    t = parse(doc, "slider", source)
    dyn = None
    if t.dynamics is not None:
        d = t.dynamics
        dyn = DynamicsCheck(d.arm, d.length, d.mass, d.samples, d.seed)
    return SliderProblem(t.mass, t.inertia, t.counter_mass, t.q_max, t.stroke, t.C, t.samples, dyn)
