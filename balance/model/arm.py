"""Serial arm model: exact gravity potential, its harmonic terms and generalised forces.

The arm works in a vertical plane, optionally on a turntable (joints of kind
``"vertical"`` at the base). Each link carries its joint at its proximal end:

- ``"vertical"``: rotation about the vertical axis (only before every in-plane joint);
  heights do not depend on it. The link is a vertical column of ``length``.
- ``"revolute"``: rotation in the vertical plane; the link's absolute angle is the sum
  of the in-plane joint angles before it plus its own ``q`` and ``offset``.
- ``"prismatic"``: slide of the link along the current direction by ``q`` measured from
  mid-stroke, ``|q| ≤ stroke/2``.

Angles are measured from ``zero`` ("vertical": the link points up at q = 0, height
``s·cos θ``; "horizontal": it points forward, height ``s·sin θ``), positive
counter-clockwise when seen with the forward direction to the right.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import InvalidArm
from .potential import HarmonicTerm, format_form, merge_terms

__all__ = ["Coordinate", "ArmModel", "Link", "Load", "Arm", "JOINT_KINDS", "ZERO_DIRECTIONS",
           "gear_ratio_for_accuracy", "DescribedTerm", "describe_term", "base_drives"]

JOINT_KINDS = ("vertical", "revolute", "prismatic")
ZERO_DIRECTIONS = {"vertical": math.pi / 2, "horizontal": 0.0}
DRIVE_KINDS = ("joint", "base")


def gear_ratio_for_accuracy(stroke: float, accuracy: float) -> float:
    """Smallest ``k`` (m/rad) with ``γ²/6 ≤ ε`` for ``γ = q/k``, ``|q| ≤ stroke/2``.

    ``1 − sin γ/γ ≤ γ²/6`` so the replaced bilinear term is accurate to ``ε`` relative.

    Examples
    --------
    >>> round(gear_ratio_for_accuracy(0.4, 1e-4), 6)
    8.164966
    """
    if not stroke > 0:
        raise InvalidArm(f"a prismatic stroke must be positive, not {stroke}.")
    if not 0 < accuracy < 1:
        raise InvalidArm(f"the required accuracy ε must lie in (0, 1), not {accuracy}.")
    return (stroke / 2) / math.sqrt(6 * accuracy)


@dataclass(frozen=True)
class Coordinate:
    """One joint coordinate of an arm, whatever the arm was read from.

    Attributes
    ----------
    name : str
        The joint's (or its link's) name.
    joint : {"vertical", "revolute", "prismatic"}
        ``vertical``: a turntable (gravity never loads it); ``revolute`` (rad); ``prismatic`` (m).
    limits : (float, float)
        The range the checks and searches cover.
    stroke : float
        Full stroke of a slide (m); 0 otherwise.
    gear_ratio : float
        ``k`` (m/rad) of a slide's ``γ = q/k`` substitution; 0 otherwise.
    """

    name: str
    joint: str
    limits: tuple[float, float]
    stroke: float = 0.0
    gear_ratio: float = 0.0


class ArmModel:
    """What every arm offers the balancing problems (a TOML :class:`Arm`, a URDF arm).

    Subclasses provide ``coordinates``, ``drive_matrix``, ``name``, ``potential(q)``,
    ``gravity_forces(q)``, ``harmonic_terms()`` and ``approx_potential_error_bounds()``.
    """

    coordinates: tuple[Coordinate, ...]
    drive_matrix: Any = None
    name: str = "arm"

    @property
    def n(self) -> int:
        """Number of joint coordinates."""
        return len(self.coordinates)

    @property
    def joint_names(self) -> list[str]:
        """``q1 … qn`` labels (1-based, as in the balancing textbook)."""
        return [f"q{i + 1}" for i in range(self.n)]

    @property
    def drives(self) -> np.ndarray:
        """``D`` with ``q = D·ψ`` (identity when each joint has its own local drive)."""
        if self.drive_matrix is None:
            return np.eye(self.n)
        return np.asarray(self.drive_matrix, dtype=float)

    @property
    def shaft_names(self) -> list[str]:
        """``ψ1 … ψn`` labels of the drive shafts."""
        return [f"ψ{i + 1}" for i in range(self.n)]

    @property
    def box(self) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper joint limits: the workspace the checks search."""
        lim = np.array([c.limits for c in self.coordinates], dtype=float)
        return lim[:, 0], lim[:, 1]

    def sample(self, count: int, seed: int = 0) -> np.ndarray:
        """``count`` configurations drawn uniformly from the joint ranges, fixed seed."""
        lo, hi = self.box
        return lo + (hi - lo) * np.random.default_rng(seed).random((count, self.n))


@dataclass(frozen=True)
class Link:
    """One link and the joint at its proximal end.

    Attributes
    ----------
    name : str
    joint : {"vertical", "revolute", "prismatic"}
    length : float
        Distance from this joint to the next one (m), ``≥ 0``.
    weight : float
        Weight (N), ``≥ 0``.
    com : float
        Centre of mass along the link from its joint (m); for a prismatic link measured
        from the slide's position at mid-stroke.
    com_lateral : float
        Offset of the centre of mass to the left of the link's direction (m).
    offset : float
        Constant angle (rad) added to the link's direction.
    q_range : (float, float)
        Joint range sampled by the checks (rad, or m for prismatic).
    stroke : float
        Full stroke ``A`` of a prismatic joint (m); 0 otherwise.
    gear_ratio : float
        ``k`` (m/rad) of the ``γ = q/k`` substitution for a prismatic joint.
    """

    name: str
    joint: str
    length: float
    weight: float
    com: float
    com_lateral: float = 0.0
    offset: float = 0.0
    q_range: tuple[float, float] | None = None
    stroke: float = 0.0
    gear_ratio: float = 0.0

    @property
    def limits(self) -> tuple[float, float]:
        """``q_range``, or by default a full turn (revolute) / the whole stroke (prismatic)."""
        if self.q_range is not None:
            return self.q_range
        if self.joint == "prismatic":
            return (-self.stroke / 2, self.stroke / 2)
        return (-math.pi, math.pi)


@dataclass(frozen=True)
class Load:
    """A lumped weight on a link (wrist, tool, payload).

    ``at`` is the distance along the link from its joint (m), ``lateral`` the offset to
    the left; ``payload=True`` marks the maximum payload, tuned for at half its weight.
    """

    link: int
    weight: float
    at: float
    lateral: float = 0.0
    payload: bool = False
    name: str = ""


@dataclass(frozen=True)
class Arm(ArmModel):
    """A serial arm in a vertical plane; see the module docstring for conventions.

    Examples
    --------
    >>> arm = Arm(links=(Link("l", "revolute", 1.0, 10.0, 0.5),), zero="vertical")
    >>> [round(t.amplitude, 12) for t in arm.harmonic_terms()]
    [5.0]
    >>> float(arm.gravity_forces(np.array([math.pi / 2]))[0])  # horizontal: moment G·l/2
    5.0
    """

    links: tuple[Link, ...]
    loads: tuple[Load, ...] = ()
    zero: str = "vertical"
    drive_matrix: tuple[tuple[float, ...], ...] | None = None
    name: str = "arm"

    def __post_init__(self) -> None:
        if not self.links:
            raise InvalidArm("an arm needs at least one link.")
        if self.zero not in ZERO_DIRECTIONS:
            raise InvalidArm(
                f"'zero' must be 'vertical' or 'horizontal', not {self.zero!r}."
            )
        in_plane = False
        for ln in self.links:
            if ln.joint not in JOINT_KINDS:
                raise InvalidArm(
                    f"link '{ln.name}': joint must be one of {', '.join(JOINT_KINDS)}, not {ln.joint!r}."
                )
            for label, v in (("length", ln.length), ("weight", ln.weight)):
                if not math.isfinite(v) or v < 0:
                    raise InvalidArm(f"link '{ln.name}': {label} must be a finite number ≥ 0, not {v}.")
            for label, v in (("com", ln.com), ("com_lateral", ln.com_lateral), ("offset", ln.offset)):
                if not math.isfinite(v):
                    raise InvalidArm(f"link '{ln.name}': {label} must be finite, not {v}.")
            lo, hi = ln.limits
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise InvalidArm(
                    f"link '{ln.name}': the joint range must be finite with low < high, not [{lo}, {hi}]."
                )
            if ln.joint == "vertical" and in_plane:
                raise InvalidArm(
                    f"link '{ln.name}': a vertical-axis joint is only allowed before every in-plane "
                    "joint (its axis would tilt with the links before it)."
                )
            if ln.joint != "vertical":
                in_plane = True
            if ln.joint == "prismatic":
                if not ln.stroke > 0:
                    raise InvalidArm(f"link '{ln.name}': a prismatic joint needs a positive stroke.")
                if lo < -ln.stroke / 2 - 1e-12 or hi > ln.stroke / 2 + 1e-12:
                    raise InvalidArm(
                        f"link '{ln.name}': the slide range [{lo}, {hi}] m leaves the stroke ±{ln.stroke / 2} m."
                    )
                if not ln.gear_ratio > 0:
                    raise InvalidArm(
                        f"link '{ln.name}': a prismatic joint needs a positive gear ratio k "
                        "(or an accuracy ε to derive it)."
                    )
        for ld in self.loads:
            if not 0 <= ld.link < len(self.links):
                raise InvalidArm(f"load '{ld.name}' refers to link {ld.link}, which does not exist.")
            if not math.isfinite(ld.weight) or ld.weight < 0:
                raise InvalidArm(f"load '{ld.name}': weight must be a finite number ≥ 0, not {ld.weight}.")
            if not (math.isfinite(ld.at) and math.isfinite(ld.lateral)):
                raise InvalidArm(f"load '{ld.name}': position must be finite.")
        n = len(self.links)
        if self.drive_matrix is not None:
            d = np.asarray(self.drive_matrix, dtype=float)
            if d.shape != (n, n) or not np.all(np.isfinite(d)):
                raise InvalidArm(
                    f"the drive matrix must be a finite {n}×{n} matrix mapping drive-shaft angles to joints."
                )
            if abs(np.linalg.det(d)) < 1e-12:
                raise InvalidArm("the drive matrix is singular: some joint cannot be driven.")

    # ------------------------------------------------------------------ basics
    @property
    def coordinates(self) -> tuple[Coordinate, ...]:
        """The joint coordinates (:class:`Coordinate`), one per link."""
        return tuple(Coordinate(ln.name, ln.joint, ln.limits, ln.stroke, ln.gear_ratio) for ln in self.links)

    @property
    def theta0(self) -> float:
        return ZERO_DIRECTIONS[self.zero]

    def with_payload_fraction(self, fraction: float) -> "Arm":
        """The same arm with every payload load scaled by ``fraction``."""
        loads = tuple(
            replace(ld, weight=ld.weight * fraction) if ld.payload else ld for ld in self.loads
        )
        return replace(self, loads=loads)

    @property
    def payload_weight(self) -> float:
        """The weight of the payload loads as given (N): the largest payload."""
        return sum(ld.weight for ld in self.loads if ld.payload)

    def with_payload(self, mass: float, g: float = 9.80665) -> "Arm":
        """The same arm carrying ``mass`` kg of payload (its payload loads scaled to weigh ``mass·g``)."""
        if self.payload_weight == 0:
            if mass != 0:
                raise InvalidArm("the arm has no payload load to carry a payload; mark one with payload = true.")
            return self
        return self.with_payload_fraction(mass * g / self.payload_weight)

    def masses(self) -> list[tuple[int, float, float, float]]:
        """Point weights ``(link, weight, s, t)`` in link frames: link centres then loads."""
        out = [(i, ln.weight, ln.com, ln.com_lateral) for i, ln in enumerate(self.links)]
        out += [(ld.link, ld.weight, ld.at, ld.lateral) for ld in self.loads]
        return out

    # ------------------------------------------------------------ kinematics
    def _angle_forms(self) -> list[np.ndarray]:
        """Absolute angle of each link as coefficients over ``q`` (offsets kept apart)."""
        forms, cur = [], np.zeros(self.n)
        for i, ln in enumerate(self.links):
            if ln.joint == "revolute":
                cur = cur.copy()
                cur[i] = 1.0
            forms.append(cur.copy())
        return forms

    def _offsets(self) -> list[float]:
        out, cur = [], 0.0
        for ln in self.links:
            if ln.joint != "vertical":
                cur += ln.offset
            out.append(cur)
        return out

    def positions(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Joint points, link angles and mass points at configurations ``q`` (m, n).

        Returns
        -------
        joints : ndarray (m, n, 2)
            Proximal joint point of each link (for a prismatic link: the point it slides from).
        angles : ndarray (m, n)
            Absolute direction of each link (rad, before adding ``theta0``).
        points : ndarray (m, len(masses), 2)
            Positions of the point weights of :meth:`masses`.
        """
        q = np.atleast_2d(np.asarray(q, dtype=float))
        m = q.shape[0]
        t0 = self.theta0
        joints = np.zeros((m, self.n, 2))
        angles = np.zeros((m, self.n))
        origin = np.zeros((m, self.n, 2))  # where each link's own frame starts
        p = np.zeros((m, 2))
        theta = np.zeros(m)
        for i, ln in enumerate(self.links):
            joints[:, i] = p
            if ln.joint == "vertical":
                angles[:, i] = theta
                origin[:, i] = p
                p = p + np.array([0.0, ln.length])
                continue
            if ln.joint == "revolute":
                theta = theta + q[:, i] + ln.offset
            else:
                theta = theta + ln.offset
            angles[:, i] = theta
            u = np.stack([np.cos(theta + t0), np.sin(theta + t0)], axis=-1)
            start = p + (q[:, i, None] * u if ln.joint == "prismatic" else 0.0)
            origin[:, i] = start
            p = start + ln.length * u
        pts = []
        for link, _, s, t in self.masses():
            ln = self.links[link]
            if ln.joint == "vertical":
                pts.append(origin[:, link] + np.stack([np.full(m, -t), np.full(m, s)], axis=-1))
                continue
            th = angles[:, link] + t0
            u = np.stack([np.cos(th), np.sin(th)], axis=-1)
            nrm = np.stack([-np.sin(th), np.cos(th)], axis=-1)
            pts.append(origin[:, link] + s * u + t * nrm)
        return joints, angles, np.stack(pts, axis=1)

    def potential(self, q: np.ndarray) -> np.ndarray:
        """Exact gravity potential ``Σ G·y`` (J) at ``q`` (n,) or (m, n)."""
        q = np.asarray(q, dtype=float)
        _, _, pts = self.positions(q)
        w = np.array([m[1] for m in self.masses()])
        u = pts[..., 1] @ w
        return u[0] if q.ndim == 1 else u

    def gravity_forces(self, q: np.ndarray) -> np.ndarray:
        """Exact generalised gravity forces ``Q = −∂U/∂q`` from moments of the weights.

        For a revolute joint ``Q_j = −Σ G·(x − x_j)`` over the weights beyond it; for a
        prismatic joint ``Q_j = −W·sin(θ_j + θ0)`` with ``W`` the weight it carries.
        """
        q = np.asarray(q, dtype=float)
        qq = np.atleast_2d(q)
        joints, angles, pts = self.positions(qq)
        ms = self.masses()
        w = np.array([m[1] for m in ms])
        link_of = np.array([m[0] for m in ms])
        out = np.zeros_like(qq)
        for j, ln in enumerate(self.links):
            beyond = link_of >= j
            if ln.joint == "revolute":
                dx = pts[:, beyond, 0] - joints[:, j, None, 0]
                out[:, j] = -(dx @ w[beyond])
            elif ln.joint == "prismatic":
                out[:, j] = -w[beyond].sum() * np.sin(angles[:, j] + self.theta0)
        return out[0] if q.ndim == 1 else out

    # ------------------------------------------------------- harmonic terms
    def _phasors(self, approximate_prismatic: bool = True) -> list[tuple[complex, np.ndarray]]:
        """Height contributions ``Re(z·e^{iφ})`` weighted by the weights."""
        forms = self._angle_forms()
        offs = self._offsets()
        base = self.theta0 - math.pi / 2  # height of a unit length along θ is cos(θ + base)
        out: list[tuple[complex, np.ndarray]] = []
        for link, g, s, t in self.masses():
            if g == 0.0:
                continue
            for j in range(link + 1):
                ln = self.links[j]
                if ln.joint == "vertical":
                    continue  # constant heights
                rot = np.exp(1j * (base + offs[j]))
                if j < link:
                    out.append((g * ln.length * rot, forms[j]))
                else:
                    out.append((g * (s + 1j * t) * rot, forms[j]))
                if ln.joint == "prismatic" and approximate_prismatic:
                    # g·q·sin(θ+θ0) ≈ g·k·sin γ·sin(θ+θ0) = (g·k/2)[cos(θ+θ0−γ) − cos(θ+θ0+γ)]
                    k = ln.gear_ratio
                    e = np.zeros(self.n)
                    e[j] = 1.0 / k
                    z = 0.5 * g * k * np.exp(1j * (self.theta0 + offs[j]))
                    out.append((z, forms[j] - e))
                    out.append((-z, forms[j] + e))
        return out

    def harmonic_terms(self) -> list[HarmonicTerm]:
        """Gravity potential as merged harmonic terms (prismatic joints via ``γ = q/k``)."""
        return merge_terms(self._phasors())

    def approx_potential_error_bounds(self) -> np.ndarray:
        """Upper bounds of ``|Q_exact − Q_terms|`` per joint from the ``γ = q/k`` substitution."""
        bounds = np.zeros(self.n)
        ms = self.masses()
        forms = self._angle_forms()
        for p, ln in enumerate(self.links):
            if ln.joint != "prismatic":
                continue
            w = sum(g for link, g, _, _ in ms if link >= p)
            half = ln.stroke / 2
            gm = half / ln.gear_ratio
            rel = 1 - math.sin(gm) / gm
            bounds[p] += w * (1 - math.cos(gm))
            for i in range(self.n):
                if forms[p][i] != 0:
                    bounds[i] += abs(forms[p][i]) * w * half * rel
        return bounds


def base_drives(n: int) -> tuple[tuple[float, ...], ...]:
    """``D`` with ``q = D·ψ`` when every drive sits on the base: ``ψ_k = q_1 + … + q_k``.

    >>> base_drives(2)
    ((1.0, 0.0), (-1.0, 1.0))
    """
    d = np.eye(n) - np.eye(n, k=-1)  # bidiagonal: 1 on, −1 below the diagonal
    return tuple(tuple(float(v) for v in row) for row in d)


@dataclass(frozen=True)
class DescribedTerm(HarmonicTerm):
    """A harmonic term of an arm with its form written out over the joints and over the drive shafts (None: a
    mechanism whose shafts are not the arm's joints)."""

    form_text: str = ""
    drive_form: tuple[float, ...] | None = None
    drive_form_text: str | None = None

    row_keys = HarmonicTerm.row_keys + ("form_text", "drive_form?", "drive_form_text?")


def describe_term(arm: ArmModel, term: HarmonicTerm) -> DescribedTerm:
    """The term with its form over joints and over drive shafts, as numbers and text.

    >>> t = describe_term(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), HarmonicTerm(5.0, 0.0, (1.0,)))
    >>> t.form_text, t.drive_form
    ('q1', (1.0,))
    """
    drive = np.asarray(term.form) @ arm.drives
    drive = np.where(np.abs(drive) < 1e-14, 0.0, drive)
    return DescribedTerm(term.amplitude, term.phase, term.form, format_form(term.form, arm.joint_names),
                         tuple(float(v) for v in drive), format_form(drive, arm.shaft_names))
