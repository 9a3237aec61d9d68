"""Spring devices whose spring acts on a slider: the offset slider-crank and the sine (Scotch-yoke) device.

Geometry: the crank ``AB`` of length ``r`` turns about ``A`` by ``φ``, measured from the direction
of the fixed guide. The slider's pin ``P`` runs on a line parallel to the guide at the offset ``e``
(positive on the side ``φ = +90°`` points to); a rod ``BP`` of length ``l`` joins them, so the
slider's position along the guide, measured from ``A``, is

    x(φ) = r·cos φ + √(l² − (r·sin φ − e)²),

and its rate ``dx/dφ = −r·sin φ − r·cos φ·(r·sin φ − e)/√(l² − (r·sin φ − e)²)``. The sine device
is the limit of an infinitely long rod: its yoke moves by ``x = r·cos φ`` (``dx/dφ = −r·sin φ``).

A spring of rate ``c`` lies along the guide between the slider and a stop; it is unloaded when the
slider is at ``x_n``, so its potential is ``E = ½·c·(x − x_n)²`` and its moment on the crank, the
virtual work of the guide force ``−c·(x − x_n)`` through ``dx``, is

    M(φ) = −dE/dφ = −c·(x − x_n)·dx/dφ        (positive towards increasing φ).

With ``x_n`` short of the slider's range (a spring beyond the slider, pushing it towards ``A``)
the moment has the sign of ``sin φ``; with ``x_n`` beyond it (spring between ``A``'s side and
the slider, pushing it away) the opposite sign. Neither device is exact: ``(x − x_n)²`` holds
``cos²φ`` (sine device) or worse, which no choice of the parameters cancels; only a spring whose
deflection is large against the stroke (a nearly constant force) comes close.

Examples
--------
>>> dev = SliderSpringDevice(c=1000.0, r=0.1, neutral=-0.5)          # sine device
>>> round(float(dev.moment(math.pi / 2)), 9)                         # c·(0 + 0.5)·0.1
50.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechbase import Row

__all__ = ["slider_position", "slider_rate", "slider_dead_centres", "slider_extremes", "SliderSpringDevice"]


def slider_position(phi, r: float, rod: float | None, offset: float = 0.0) -> np.ndarray:
    """Slider position ``x(φ)`` along the guide from ``A`` (``rod=None``: the sine device, ``r·cos φ``).

    Examples
    --------
    >>> float(slider_position(0.0, 0.1, 0.3))   # crank and rod in line: r + l
    0.4
    """
    phi = np.asarray(phi, dtype=float)
    if rod is None:
        return r * np.cos(phi)
    return r * np.cos(phi) + np.sqrt(rod * rod - (r * np.sin(phi) - offset) ** 2)


def slider_rate(phi, r: float, rod: float | None, offset: float = 0.0) -> np.ndarray:
    """``dx/dφ``: the slider's velocity per unit crank speed (the device's Jacobian).

    Examples
    --------
    >>> float(slider_rate(math.pi / 2, 0.1, 0.3))
    -0.1
    """
    phi = np.asarray(phi, dtype=float)
    if rod is None:
        return -r * np.sin(phi)
    y = r * np.sin(phi) - offset
    return -r * np.sin(phi) - r * np.cos(phi) * y / np.sqrt(rod * rod - y * y)


def slider_dead_centres(r: float, rod: float | None, offset: float = 0.0) -> tuple[float, float]:
    """Crank angles of the outer and inner dead centre (``x`` largest and least over a turn).

    Outer: crank and rod in line, ``sin φ = e/(l + r)``; inner: folded, ``φ = π + asin(e/(l − r))``.

    Examples
    --------
    >>> [round(math.degrees(v), 6) for v in slider_dead_centres(0.1, 0.3, 0.0)]
    [0.0, 180.0]
    """
    if rod is None:
        return 0.0, math.pi
    return math.asin(offset / (rod + r)), math.pi + math.asin(offset / (rod - r))


def slider_extremes(lo: float, hi: float, r: float, rod: float | None, offset: float = 0.0) -> tuple[float, float]:
    """Least and largest slider position over ``lo ≤ φ ≤ hi`` (closed form: range ends and dead centres).

    Examples
    --------
    >>> [round(v, 12) for v in slider_extremes(0.0, math.pi / 2, 0.1, None)]
    [0.0, 0.1]
    """
    angles = [lo, hi]
    for c0 in slider_dead_centres(r, rod, offset):
        k = math.ceil((lo - c0) / (2 * math.pi))
        angles += [c0 + 2 * math.pi * j for j in range(k, k + 2) if lo <= c0 + 2 * math.pi * j <= hi]
    x = slider_position(np.array(angles), r, rod, offset)
    return float(np.min(x)), float(np.max(x))


@dataclass(frozen=True)
class SliderSpringDevice(Row):
    """A spring on a slider driven by a crank (SI units): ``rod=None`` is the sine (Scotch-yoke) device.

    Attributes
    ----------
    c : float
        Spring rate (N/m).
    r : float
        Crank length (m).
    neutral : float
        Slider position ``x_n`` (m from ``A`` along the guide) at which the spring is unloaded.
    rod, offset : float
        Rod length ``l`` and guide offset ``e`` (m) of the slider-crank; ``rod=None`` for the sine device.

    Examples
    --------
    >>> dev = SliderSpringDevice(c=2000.0, r=0.1, neutral=0.2, rod=0.4, offset=0.02)
    >>> phi = 1.0
    >>> num = -float(dev.potential(phi + 1e-6) - dev.potential(phi - 1e-6)) / 2e-6
    >>> bool(abs(num - float(dev.moment(phi))) < 1e-6)
    True
    """

    c: float
    r: float
    neutral: float
    rod: float | None = None
    offset: float = 0.0

    row_keys = ("family", "c", "r", "neutral", "rod", "offset")

    @property
    def family(self) -> str:
        return "sine" if self.rod is None else "slider-crank"

    def position(self, phi) -> np.ndarray:
        return slider_position(phi, self.r, self.rod, self.offset)

    def rate(self, phi) -> np.ndarray:
        return slider_rate(phi, self.r, self.rod, self.offset)

    def potential(self, phi) -> np.ndarray:
        """``E = ½·c·(x − x_n)²`` (J)."""
        return 0.5 * self.c * (self.position(phi) - self.neutral) ** 2

    def moment(self, phi) -> np.ndarray:
        """``M = −c·(x − x_n)·dx/dφ`` (N·m, positive towards increasing φ)."""
        return -self.c * (self.position(phi) - self.neutral) * self.rate(phi)

    def force(self, phi) -> np.ndarray:
        """Spring force magnitude ``c·|x − x_n|`` (N)."""
        return self.c * np.abs(self.position(phi) - self.neutral)
