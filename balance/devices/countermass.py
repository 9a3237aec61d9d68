"""Dynamic balancing of a sliding last link by two counter-masses (docs/theory.md).

The link (mass ``m``, principal central moment ``I``) slides by ``q`` along ``Z``; two
equal counter-masses ``M`` at ``z1``, ``z2`` on the same axis keep the centre of mass
and the transverse moment of inertia constant when

    m·q + M·z1 + M·z2 = 0,     I + m·q² + M·z1² + M·z2² = C.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechbase import Row

from ..errors import InvalidInput
from ..extremes import box_extremes

__all__ = ["CounterMass", "c_min", "counter_mass_laws", "crank_construction", "verify_counter_mass"]


def _positive(name: str, v: float, allow_zero: bool = False) -> float:
    v = float(v)
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        need = "≥ 0" if allow_zero else "> 0"
        raise InvalidInput(f"{name} must be a finite number {need}, not {v}.")
    return v


def c_min(m: float, inertia: float, M: float, q_max: float) -> float:
    """Smallest constant ``C = I + (m² + 2mM)·q_max²/(2M)`` giving real laws on ``|q| ≤ q_max``.

    Examples
    --------
    >>> c_min(2.0, 0.1, 2.0, 0.5)  # M = m: I + 1.5·m·q_max²
    0.85
    """
    m, M = _positive("the link mass m", m), _positive("the counter-mass M", M)
    inertia, q_max = _positive("the moment of inertia I", inertia, True), _positive("the stroke q_max", q_max)
    return inertia + (m * m + 2 * m * M) * q_max * q_max / (2 * M)


def counter_mass_laws(q, m: float, inertia: float, M: float, C: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``z1(q)``, ``z2(q)`` and the discriminant ``2M(C − I − m·q²) − m²q²``.

    Where the discriminant is negative (stroke beyond what ``C`` allows) the square root
    is clipped at 0 — the caller must report it (see :func:`verify_counter_mass`).

    Examples
    --------
    >>> z1, z2, disc = counter_mass_laws(0.0, 1.0, 0.0, 1.0, 1.5)
    >>> float(z1), float(z2)
    (0.8660254037844386, -0.8660254037844386)
    """
    q = np.asarray(q, dtype=float)
    disc = 2 * M * (C - inertia - m * q * q) - m * m * q * q
    root = np.sqrt(np.maximum(disc, 0.0))
    return (-m * q + root) / (2 * M), (-m * q - root) / (2 * M), disc


def crank_construction(eta, q_max: float, stroke: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two cranks phased ±120° from the link's crank: ``q = s·cos η``, ``z1,2 = q_max·cos(η ± 120°)``.

    ``stroke`` ``s`` is the link's crank radius (default ``q_max``).
    """
    eta = np.asarray(eta, dtype=float)
    s = q_max if stroke is None else stroke
    return s * np.cos(eta), q_max * np.cos(eta + 2 * math.pi / 3), q_max * np.cos(eta - 2 * math.pi / 3)


@dataclass(frozen=True)
class CrankCheck(Row):
    """The three cranks phased 120° apart (:func:`crank_construction`): whether they are exact, and the
    drift of the centre of mass and of the inertia they leave."""

    exact: bool
    max_com_error: float
    max_inertia_error: float
    laws: str = "q = s·cos η, z1 = q_max·cos(η + 120°), z2 = q_max·cos(η − 120°)"


@dataclass(frozen=True)
class CounterMass(Row):
    """Result of :func:`verify_counter_mass` (SI units)."""

    m: float
    inertia: float
    M: float
    q_max: float
    stroke: float
    C: float
    C_min: float
    law_valid_stroke: float
    max_com_error: float
    max_inertia_error: float
    crank_max_com_error: float
    crank_max_inertia_error: float
    crank_exact: bool
    samples: int
    messages: tuple[str, ...]

    row_keys = ("m", "I=inertia", "M", "q_max", "stroke", "C", "C_min", "law_valid_stroke", "max_com_error",
                "max_inertia_error", "crank", "samples", "messages")

    @property
    def crank(self) -> CrankCheck:
        return CrankCheck(self.crank_exact, self.crank_max_com_error, self.crank_max_inertia_error)


def verify_counter_mass(m: float, inertia: float, M: float, q_max: float, stroke: float | None = None,
                        C: float | None = None, samples: int = 2001) -> CounterMass:
    """Design at ``C`` (default ``C_min``) and measure the centre of mass and inertia drift.

    Parameters
    ----------
    m, inertia, M, q_max : float
        Link mass (kg), its principal central moment (kg·m²), each counter-mass (kg) and
        the designed stroke half-amplitude (m).
    stroke : float, optional
        The stroke half-amplitude actually travelled (default ``q_max``); beyond what ``C``
        allows the laws have no real solution — the resulting errors are reported.
    C : float, optional
        The constant inertia (kg·m², ``≥ C_min`` for a full stroke).
    samples : int
        Points along the stroke / the crank turn.

    Returns
    -------
    CounterMass
        ``max_com_error`` (m, displacement of the common centre of mass) and
        ``max_inertia_error`` (kg·m², deviation from ``C``) of the laws; the same for the
        two-crank construction (exact only for ``M = m`` and ``s = q_max``).

    Examples
    --------
    >>> r = verify_counter_mass(2.0, 0.1, 2.0, 0.5)
    >>> r.C_min, r.max_com_error < 1e-15, r.max_inertia_error < 1e-14
    (0.85, True, True)
    """
    cmin = c_min(m, inertia, M, q_max)
    s = q_max if stroke is None else _positive("the stroke", stroke)
    C = cmin if C is None else float(C)
    if not math.isfinite(C) or C < inertia:
        raise InvalidInput(f"the inertia constant C must be finite and at least I = {inertia}, not {C}.")
    if samples < 3:
        raise InvalidInput(f"the verification needs at least 3 samples, not {samples}.")
    msgs: list[str] = []
    valid = math.sqrt(2 * M * (C - inertia) / (m * m + 2 * m * M))
    total = m + 2 * M

    def law_errors(x):  # centre-of-mass displacement and inertia deviation of the laws along the stroke
        q = x[:, 0]
        z1, z2, _ = counter_mass_laws(q, m, inertia, M, C)
        return np.column_stack([(m * q + M * z1 + M * z2) / total, inertia + m * q * q + M * (z1 * z1 + z2 * z2) - C])

    def crank_errors(x):  # the same for the two-crank construction over a turn of the crank
        qc, c1, c2 = crank_construction(x[:, 0], q_max, s)
        return np.column_stack([(m * qc + M * c1 + M * c2) / total, m * qc * qc + M * (c1 * c1 + c2 * c2)])

    q = np.linspace(-s, s, samples)[:, None]
    (com_lo, com_hi), (in_lo, in_hi) = box_extremes(law_errors, [-s], [s], q, floor=1e-12 * max(C, q_max))
    com_err, in_err = max(-com_lo.value, com_hi.value), max(-in_lo.value, in_hi.value)
    disc = counter_mass_laws(np.array([s]), m, inertia, M, C)[2]  # the discriminant is least at the stroke's ends
    if disc[0] < -1e-12 * max(C, 1.0):
        msgs.append(
            f"the stroke ±{s:g} m exceeds ±{valid:g} m, the largest the constant C = {C:g} kg·m² allows: "
            f"beyond it the counter-masses cannot keep the inertia constant (error {in_err:.3g} kg·m²)."
        )
    eta = np.linspace(0, 2 * math.pi, samples)[:, None]
    (ccom_lo, ccom_hi), (cin_lo, cin_hi) = box_extremes(crank_errors, [0.0], [2 * math.pi], eta,
                                                        floor=1e-12 * max(C, q_max))
    c_com_err = max(-ccom_lo.value, ccom_hi.value)
    c_in_err = cin_hi.value - cin_lo.value
    exact = M == m and s == q_max
    if not exact:
        msgs.append(
            f"the two-crank ±120° construction is exact only for M = m and stroke = q_max; here its centre "
            f"of mass moves by up to {c_com_err:.3g} m and its inertia varies by {c_in_err:.3g} kg·m²."
        )
    return CounterMass(m, inertia, M, q_max, s, C, cmin, valid, com_err, in_err, c_com_err, c_in_err,
                       exact, samples, tuple(msgs))
