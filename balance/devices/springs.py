"""Spring devices: the sine (Scotch-yoke) device and the crank-and-rocker device (docs/theory.md).

Crank-and-rocker geometry: the crank ``AB`` of length ``r`` turns about ``A`` by ``φ``
measured from the direction ``A→C``; the spring runs from the pin ``B`` to the base
point ``C`` with ``|AC| = d = r + r0``, so it is ``r0`` long at ``φ = 0``.

Sign convention (used everywhere in :mod:`balance`): a moment is positive when it
turns the crank towards increasing ``φ``, i.e. pushes the pin away from ``C``. Then

    M(φ) = −c·r·d·sin φ·(1 − l0/L)

for every kind, with ``l0 = r0 − a`` (tension, pre-extension ``a ≤ r0``) and
``l0 = 2r + r0 + a`` (compression, pre-load ``a ≥ 0``). A tension spring pulls the
pin towards ``C`` (negative sense, exactly ``−c·r·d·sin φ`` for ``a = r0``); a
compression spring pushes it away (positive sense).

The compression-lever device (the textbook's second compression variant) puts a
compression spring on the slotted lever *beyond* the pin: the lever turns about ``C``
through ``B``, the spring sits between ``B`` and a stop on the lever at ``s`` from ``C``,
so it is ``s − L`` long and pushes ``B`` towards ``C`` with ``c·(l_s − s + L)`` (``l_s`` its
own free length). That is a pulling spring of effective free length ``s − l_s = r0 − a``
(``a`` the pre-compression at ``φ = 0``): the tension formula, exact for ``a = r0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechbase import Row

from ..errors import InvalidInput

__all__ = [
    "SPRING_KINDS",
    "KIND_SENSE",
    "spring_length",
    "spring_length_textbook",
    "free_length",
    "crank_moment",
    "CrankRockerDevice",
    "SineDevice",
]

SPRING_KINDS = ("tension", "compression", "compression-lever")
#: sense (+1 away from the base point C, −1 towards it) each spring kind produces
KIND_SENSE = {"tension": -1, "compression": +1, "compression-lever": -1}


def spring_length(phi, r: float, r0: float) -> np.ndarray:
    """Spring length ``L = √(r0² + 4·r·d·sin²(φ/2))``, ``d = r + r0``.

    Algebraically equal to the textbook ``√(r² + d² − 2·r·d·cos φ)`` but without its
    cancellation: that form loses all accuracy near ``φ = 0`` when ``r0 ≪ r``.

    Examples
    --------
    >>> float(spring_length(0.0, 0.1, 1e-9))
    1e-09
    """
    phi = np.asarray(phi, dtype=float)
    return np.hypot(r0, 2.0 * math.sqrt(r * (r + r0)) * np.sin(phi / 2))


def spring_length_textbook(phi, r: float, r0: float) -> np.ndarray:
    """The textbook ``√(r² + d² − 2·r·d·cos φ)`` (kept for comparison in tests only)."""
    d = r + r0
    return np.sqrt(np.maximum(r * r + d * d - 2 * r * d * np.cos(np.asarray(phi, dtype=float)), 0.0))


def free_length(kind: str, r: float, r0: float, a: float) -> float:
    """``l0 = r0 − a`` for tension (and the compression-lever device's equivalent pulling
    spring), ``2r + r0 + a`` for compression."""
    if kind in ("tension", "compression-lever"):
        return r0 - a
    if kind == "compression":
        return 2 * r + r0 + a
    raise InvalidInput(f"spring kind must be one of {', '.join(SPRING_KINDS)}, not {kind!r}.")


def crank_moment(phi, kind: str, c: float, r: float, r0: float, a: float) -> np.ndarray:
    """Moment of the spring about ``A`` (positive = away from ``C``), see the module docstring.

    Written as ``−c·r·d·sin φ + c·r·d·l0·sin φ / L`` so a zero free length needs no
    division and no ``1/sin φ`` appears anywhere.

    Examples
    --------
    >>> round(float(crank_moment(math.pi / 2, "tension", 100.0, 0.1, 0.2, 0.2)), 12)
    -3.0
    """
    phi = np.asarray(phi, dtype=float)
    d = r + r0
    l0 = free_length(kind, r, r0, a)
    s = np.sin(phi)
    m = -c * r * d * s
    if l0 != 0.0:
        L = spring_length(phi, r, r0)
        ratio = np.divide(s, L, out=np.zeros_like(s * L), where=L > 0)
        m = m + c * r * d * l0 * ratio
    return m


@dataclass(frozen=True)
class CrankRockerDevice(Row):
    """A crank-and-rocker spring device with its parameters (SI units).

    Examples
    --------
    >>> dev = CrankRockerDevice("tension", c=1000.0, r=0.1, r0=0.2, a=0.2)
    >>> round(dev.amplitude, 9), dev.sense
    (30.0, -1)
    """

    kind: str
    c: float
    r: float
    r0: float
    a: float

    row_keys = ("kind", "c", "r", "r0", "a", "d", "free_length")

    @property
    def d(self) -> float:
        """Distance between the crank pivot ``A`` and the base point ``C``."""
        return self.r + self.r0

    @property
    def free_length(self) -> float:
        return free_length(self.kind, self.r, self.r0, self.a)

    @property
    def amplitude(self) -> float:
        """``c·r·d``: the moment amplitude for a zero-free-length tension spring."""
        return self.c * self.r * self.d

    @property
    def sense(self) -> int:
        return KIND_SENSE[self.kind]

    def length(self, phi) -> np.ndarray:
        return spring_length(phi, self.r, self.r0)

    def moment(self, phi) -> np.ndarray:
        return crank_moment(phi, self.kind, self.c, self.r, self.r0, self.a)

    def potential(self, phi) -> np.ndarray:
        """``E = ½·c·(L − l0)²`` (J): its ``−dE/dφ = −c·(L − l0)·r·d·sin φ/L`` is :meth:`moment`."""
        return 0.5 * self.c * (self.length(phi) - self.free_length) ** 2

    def force(self, phi) -> np.ndarray:
        """Spring force magnitude ``c·|L − l0|`` (N)."""
        return self.c * np.abs(self.length(phi) - self.free_length)


@dataclass(frozen=True)
class SineDevice:
    """Sine (Scotch-yoke) device: crank eccentricity ``e``, mean spring force ``T``.

    Its moment is ``−e·T·sin φ`` (a soft spring keeps ``T`` nearly constant).

    Examples
    --------
    >>> round(float(SineDevice(0.05, 200.0).moment(math.pi / 2)), 12)
    -10.0
    """

    e: float
    T: float

    @property
    def amplitude(self) -> float:
        return self.e * self.T

    def moment(self, phi) -> np.ndarray:
        return -self.e * self.T * np.sin(np.asarray(phi, dtype=float))
