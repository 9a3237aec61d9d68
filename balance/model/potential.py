"""Harmonic terms ``A·cos(φ + α)`` of linear forms ``φ = Σ a_i·q_i``.

A gravity potential of a revolute arm in a vertical plane is exactly a sum of
such terms; the balancing devices cancel them one by one.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

from mechbase import Row

__all__ = ["HarmonicTerm", "merge_terms", "terms_potential", "terms_forces", "format_form"]

_FORM_DIGITS = 12  # forms are compared after rounding their coefficients to this many digits


@dataclass(frozen=True)
class HarmonicTerm(Row):
    """One term ``amplitude·cos(form·q + phase)`` of a potential.

    Attributes
    ----------
    amplitude : float
        ``A ≥ 0`` in the potential's unit (N·m for weights in N and lengths in m).
    phase : float
        ``α`` in radians, in ``(-π, π]``.
    form : tuple of float
        Coefficients ``a_i`` of the joint coordinates; the first non-zero one is positive.

    Examples
    --------
    >>> t = HarmonicTerm(2.0, 0.0, (1.0, 0.0))
    >>> abs(float(t.value([0.5, 3.0])) - 2.0 * math.cos(0.5)) < 1e-15
    True
    """

    amplitude: float
    phase: float
    form: tuple[float, ...]

    row_keys = ("amplitude", "phase", "phase_deg", "form")

    @property
    def phase_deg(self) -> float:
        """``α`` in degrees."""
        return math.degrees(self.phase)

    def angle(self, q: np.ndarray) -> np.ndarray:
        """``φ = form·q`` for one configuration ``q`` (n,) or many (m, n)."""
        return np.asarray(q, dtype=float) @ np.asarray(self.form)

    def value(self, q: np.ndarray) -> np.ndarray:
        """The term's potential at ``q``."""
        return self.amplitude * np.cos(self.angle(q) + self.phase)

    def moment(self, phi: np.ndarray) -> np.ndarray:
        """``∂U_k/∂φ = −A·sin(φ + α)``: the moment the balancing device applies to its shaft.

        The device's potential is ``−U_k``, so its generalised force on ``φ`` is
        ``+∂U_k/∂φ``; it cancels the gravity force ``−∂U_k/∂φ``.
        """
        return -self.amplitude * np.sin(np.asarray(phi, dtype=float) + self.phase)


def _canonical(z: complex, form: Sequence[float]) -> tuple[complex, tuple[float, ...]]:
    """Flip the sign of a form so its first non-zero coefficient is positive.

    ``Re(z·e^{-iφ}) = Re(conj(z)·e^{iφ})`` so the phasor is conjugated.
    """
    f = np.asarray(form, dtype=float)
    nz = np.flatnonzero(np.abs(f) > 0)
    if nz.size and f[nz[0]] < 0:
        return z.conjugate(), tuple(float(v) for v in -f)
    return z, tuple(float(v) for v in f)


def merge_terms(
    phasors: Iterable[tuple[complex, Sequence[float]]], rel_tol: float = 1e-12
) -> list[HarmonicTerm]:
    """Merge phasors ``Re(z·e^{iφ})`` with equal forms into :class:`HarmonicTerm` s.

    Parameters
    ----------
    phasors : iterable of (complex, sequence of float)
        ``z = A·e^{iα}`` and the form of each contribution.
    rel_tol : float
        Terms whose amplitude is below ``rel_tol`` times the largest are dropped,
        as are terms with an all-zero form (constants).

    Returns
    -------
    list of HarmonicTerm
        Ordered by first appearance of each form.

    Examples
    --------
    >>> ts = merge_terms([(1 + 0j, (1, 0)), (1j, (1, 0)), (2 + 0j, (-1, 0))])
    >>> len(ts), round(ts[0].amplitude, 12)
    (1, 3.162277660168)
    """
    acc: dict[tuple[float, ...], tuple[tuple[float, ...], complex]] = {}
    for z, form in phasors:
        z, f = _canonical(complex(z), form)
        if not any(f):
            continue  # a constant: no force
        key = tuple(round(v, _FORM_DIGITS) + 0.0 for v in f)
        if key in acc:
            acc[key] = (acc[key][0], acc[key][1] + z)
        else:
            acc[key] = (f, z)
    if not acc:
        return []
    biggest = max(abs(z) for _, z in acc.values())
    out = []
    for f, z in acc.values():
        if abs(z) <= rel_tol * biggest or abs(z) == 0.0:
            continue
        phase = cmath.phase(z)
        if phase <= -math.pi:
            phase += 2 * math.pi
        out.append(HarmonicTerm(abs(z), phase + 0.0, f))  # + 0.0: no −0.0 phases
    return out


def terms_potential(terms: Sequence[HarmonicTerm], q: np.ndarray) -> np.ndarray:
    """``Σ_k A_k·cos(φ_k + α_k)`` at configurations ``q`` of shape (n,) or (m, n)."""
    q = np.asarray(q, dtype=float)
    total = np.zeros(q.shape[:-1])
    for t in terms:
        total = total + t.value(q)
    return total


def terms_forces(terms: Sequence[HarmonicTerm], q: np.ndarray) -> np.ndarray:
    """Generalised forces ``−∂U/∂q_i`` of the terms' potential, shape like ``q``."""
    q = np.asarray(q, dtype=float)
    out = np.zeros_like(q)
    for t in terms:
        s = t.amplitude * np.sin(t.angle(q) + t.phase)
        out = out + s[..., None] * np.asarray(t.form)
    return out


def format_form(coeffs: Sequence[float], names: Sequence[str], digits: int = 6) -> str:
    """Human-readable linear form, e.g. ``q2 + q3`` or ``ψ3 − ψ1`` or ``q1 + 0.25·q2``.

    Examples
    --------
    >>> format_form([0, 1, -1], ["a", "b", "c"])
    'b − c'
    """
    parts: list[str] = []
    rounded = [(round(float(c), digits), n) for c, n in zip(coeffs, names)]
    pairs = [p for p in rounded if p[0] > 0] + [p for p in rounded if p[0] < 0]  # positive shafts first: 'ψ2 − ψ1'
    for c, n in pairs:
        sign = "−" if c < 0 else "+"
        mag = abs(c)
        body = n if mag == 1 else f"{mag:.{digits}g}·{n}"
        parts.append(f"{sign} {body}")
    if not parts:
        return "0"
    s = " ".join(parts)
    return s[2:] if s.startswith("+ ") else "−" + s[2:]
