"""The spring devices a designer would consider for ``Φ0·sin φ`` on a crank, in one table.

Each :class:`DeviceKind` names its spring kinds, the bounds it takes (the others must be left out),
its device model (the moment ``M(φ)`` on the crank and the potential ``E(φ)`` with ``M = −dE/dφ``),
its non-dimensional problem and how a solution becomes a :class:`~.result.FitResult`, and its exact
solution where there is one. All are fitted by :func:`~.driver.fit_spring` with the same methods.

Examples
--------
>>> sorted(DEVICES)
['sine', 'slider-crank', 'slotted-lever']
>>> DEVICES["sine"].bounds
('r', 'a')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..sliders import SliderSpringDevice
from ..springs import SPRING_KINDS, CrankRockerDevice
from .problem import _Problem
from .result import _finish
from .slider_problem import _finish_slider, _SliderProblem

__all__ = ["DeviceKind", "DEVICES", "DEFAULT_DEVICE"]


@dataclass(frozen=True)
class DeviceKind:
    """One device of the family (see the module docstring)."""

    name: str
    title: str
    spring_kinds: tuple[str, ...]
    bounds: tuple[str, ...]
    model: type
    problem: type
    finish: Callable
    exact: str | None


DEVICES = {
    "slotted-lever": DeviceKind(
        "slotted-lever", "crank with an oscillating slotted lever, the spring along the lever (B to C)",
        SPRING_KINDS, ("r", "r0", "a"), CrankRockerDevice, _Problem, _finish,
        "a tension spring of zero free length (a = r0), and the compression spring on the lever beyond B at a = r0"),
    "slider-crank": DeviceKind(
        "slider-crank", "offset slider-crank, the spring on the slider in a fixed guide",
        ("compression",), ("r", "a", "rod", "offset"), SliderSpringDevice, _SliderProblem, _finish_slider, None),
    "sine": DeviceKind(
        "sine", "sine (Scotch-yoke) device with a real spring on the yoke",
        ("compression",), ("r", "a"), SliderSpringDevice, _SliderProblem, _finish_slider, None),
}
DEFAULT_DEVICE = "slotted-lever"
