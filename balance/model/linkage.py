"""The masses of a dimensioned linkage's links and their total first moment over the input.

Each moving link l has a mass m_l and a centre of mass c_l, both as placed in the linkage's pose;
at input q the link is turned by θ_l(q) about the origin and moved by t_l(q), so its centre is at
R(θ_l) c_l + t_l.  The linkage's total first moment of mass is

    M(q) = Σ_l  R(θ_l) a_l + m_l t_l,     a_l = m_l c_l,

linear in (m_l, a_l).  Its centre of mass is M / Σ m_l, its gravity potential −g·M, and the
shaking force it sends into the frame −d²M/dt² = −(M'' ω² + M' α): per ω² at a constant input
speed, −M''.  M constant over the input's range ⇔ no shaking force at any speed ⇔ the gravity
potential is constant whatever the direction of gravity.

The link poses come from outside (a callable, :data:`Motion`): this package never moves a linkage.

Examples
--------
>>> import numpy as np
>>> crank = LinkBody(1, (("0-1", (0.0, 0.0)), ("1-2", (1.0, 0.0))), 2.0, (0.5, 0.0), "0-1")
>>> q = np.array([0.0, np.pi / 2])                  # a lone crank turned by q about the origin
>>> motion = (np.c_[0 * q, q], np.zeros((2, 2, 2)), np.c_[0 * q, 1 + 0 * q], np.zeros((2, 2, 2)),
...           np.zeros((2, 2)), np.zeros((2, 2, 2)))
>>> mass, moment = body_arrays([crank], 2)
>>> first_moment(mass, moment, motion).round(12).tolist()          # 2 kg at 0.5 m: 1 kg·m, turning
[[1.0, 0.0], [0.0, 1.0]]
>>> (first_moment(mass, moment, motion, order=2).round(12) + 0).tolist()  # −ω² r: the centripetal term
[[-1.0, 0.0], [0.0, -1.0]]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from mechbase import Row

from ..errors import InvalidInput

__all__ = ["LinkBody", "Motion", "body_arrays", "first_moment", "bar_bodies", "moment_rate"]

#: the link poses at given input values q (S,): (θ, t, θ', t', θ'', t''), shapes (S, n), (S, n, 2) × 3,
#: derivatives with respect to the input
Motion = Callable[[np.ndarray], tuple]


@dataclass(frozen=True)
class LinkBody(Row):
    """A moving link as balancing sees it: its joints (named, as placed in the pose), its mass and centre.

    Attributes
    ----------
    link : int
        The link's number in the chain.
    joints : tuple of (str, (float, float))
        The link's joints by name and position in the pose (m).
    mass : float
        kg (≥ 0).
    centre : (float, float)
        Its centre of mass in the pose (m).
    pivot : str or None
        The joint pivoting it on the frame (a revolute joint to the frame), else None: it floats.
    inertia : float or None
        Its moment of inertia about its centre (kg·m²; 0 for a point mass), None where not known.
    """

    link: int
    joints: tuple[tuple[str, tuple[float, float]], ...]
    mass: float
    centre: tuple[float, float]
    pivot: str | None = None
    inertia: float | None = None
    row_keys = ("link", "mass", "centre", "pivot", "inertia")

    def __post_init__(self):
        if not (math.isfinite(self.mass) and self.mass >= 0):
            raise InvalidInput(f"link {self.link} has mass {self.mass:g} kg: a mass is a finite number ≥ 0.")
        if self.inertia is not None and not (math.isfinite(self.inertia) and self.inertia >= 0):
            raise InvalidInput(f"link {self.link} has inertia {self.inertia:g} kg·m²: an inertia is a finite number "
                               "≥ 0.")
        if not all(math.isfinite(v) for v in self.centre):
            raise InvalidInput(f"link {self.link} has a centre of mass that is not finite: {list(self.centre)}.")

    def joint(self, name: str) -> np.ndarray:
        """The position of the link's joint ``name`` in the pose."""
        return np.array(dict(self.joints)[name], dtype=float)

    @property
    def reach(self) -> float:
        """The largest distance from the link's first named joint (its pivot, if pivoted) to another of its joints."""
        origin = self.joint(self.anchor)
        return max((float(np.hypot(*(np.array(p) - origin))) for _, p in self.joints), default=0.0)

    @property
    def anchor(self) -> str:
        """The joint a counterweight on this link is placed from: its pivot, else its first joint."""
        return self.pivot or self.joints[0][0]


def bar_bodies(joints: Sequence[tuple[int, tuple, str | None]], density: float) -> list[LinkBody]:
    """Links as bars of ``density`` kg per metre between every two of their joints, the centre at the
    bars' centroid (a binary link: one bar, centre midway; a ternary link: the triangle's three sides),
    the inertia the bars' (m L²/12 each about its middle, moved to the centre).

    ``joints``: per moving link (link, ((name, (x, y)), …), pivot or None).

    >>> bar_bodies([(1, (("0-1", (0, 0)), ("1-2", (3, 4))), "0-1")], 2.0)[0].to_dict()   # 10 kg · 25 m² / 12
    {'link': 1, 'mass': 10.0, 'centre': [1.5, 2.0], 'pivot': '0-1', 'inertia': 20.833333333333336}
    """
    if not (math.isfinite(density) and density > 0):
        raise InvalidInput(f"the density of the bars must be a positive number of kg per metre, not {density:g}.")
    out = []
    for link, named, pivot in joints:
        pts = np.unique(np.array([p for _, p in named], dtype=float).reshape(-1, 2), axis=0)
        lengths = [(float(np.hypot(*(pts[j] - pts[i]))), (pts[i] + pts[j]) / 2)
                   for i in range(len(pts)) for j in range(i + 1, len(pts))]
        bars = [(density * length, mid, length) for length, mid in lengths]
        mass = sum(m for m, _, _ in bars)
        centre = sum(m * mid for m, mid, _ in bars) / mass if mass > 0 else (pts[0] if len(pts) else np.zeros(2))
        inertia = sum(m * (length ** 2 / 12 + float(np.sum((mid - centre) ** 2))) for m, mid, length in bars)
        out.append(LinkBody(link, tuple((n, tuple(map(float, p))) for n, p in named), mass,
                            (float(centre[0]), float(centre[1])), pivot, float(inertia)))
    return out


def body_arrays(bodies: Sequence[LinkBody], links: int) -> tuple[np.ndarray, np.ndarray]:
    """Mass (n,) and first moment a = m·c (n, 2) per link of an ``links``-link chain (the frame's zero)."""
    mass, moment = np.zeros(links), np.zeros((links, 2))
    for b in bodies:
        mass[b.link] += b.mass
        moment[b.link] += b.mass * np.asarray(b.centre, dtype=float)
    return mass, moment


def first_moment(mass: np.ndarray, moment: np.ndarray, motion: tuple, order: int = 0) -> np.ndarray:
    """The total first moment M (S, 2) (kg·m) at the poses ``motion``, or its ``order``-th derivative
    with respect to the input (1 or 2), from the links' own derivatives (no finite difference).

    ``motion`` is (θ, t, θ', t', θ'', t'') as :data:`Motion` returns it; ``mass`` (n,), ``moment`` (n, 2).
    A massless link adds nothing, even where its pose is not finite.
    """
    theta, t, dtheta, dt, ddtheta, ddt = motion
    used = np.flatnonzero((mass != 0) | np.any(moment != 0, axis=1))
    m, a = mass[used], moment[used]
    c, s = np.cos(theta[:, used]), np.sin(theta[:, used])
    ra = np.stack((c * a[:, 0] - s * a[:, 1], s * a[:, 0] + c * a[:, 1]), axis=-1)  # R(θ) a   (S, k, 2)
    if order == 0:
        per = ra + m[:, None] * t[:, used]
    else:
        jra = np.stack((-ra[..., 1], ra[..., 0]), axis=-1)  # J R(θ) a: its derivative per unit θ
        if order == 1:
            per = dtheta[:, used, None] * jra + m[:, None] * dt[:, used]
        elif order == 2:
            per = ddtheta[:, used, None] * jra - dtheta[:, used, None] ** 2 * ra + m[:, None] * ddt[:, used]
        else:
            raise ValueError(f"order must be 0, 1 or 2, not {order}")
    return per.sum(axis=1)


def moment_rate(bodies: Sequence[LinkBody], motion: tuple, about) -> np.ndarray:
    """The rate of the bodies' total angular momentum about the fixed point ``about`` (S,), per ω² of the
    input at a constant input speed: Σ I θ'' + m (r − O) × r'' (N·m per (rad/s)²); the frame feels its
    opposite, the shaking moment (gravity's moment aside).  Every body's ``inertia`` must be known.

    >>> crank = LinkBody(1, (), 2.0, (0.5, 0.0), "0-1", 0.1)    # turning at constant speed about the origin
    >>> z, q = np.zeros((1, 2, 2)), np.array([0.3])
    >>> moment_rate([crank], (np.c_[0 * q, q], z, np.c_[0 * q, 1 + 0 * q], z, np.zeros((1, 2)), z), (0, 0))
    array([0.])
    """
    theta, t, dtheta, dt, ddtheta, ddt = motion
    out = np.zeros(len(theta))
    origin = np.asarray(about, dtype=float)
    for b in bodies:
        if b.mass == 0 and not b.inertia:
            continue
        c, s = np.cos(theta[:, b.link]), np.sin(theta[:, b.link])
        x, y = b.centre
        rc = np.stack((c * x - s * y, s * x + c * y), axis=1)  # R(θ) c
        r = rc + t[:, b.link] - origin
        acc = ddtheta[:, b.link, None] * np.stack((-rc[:, 1], rc[:, 0]), axis=1) \
            - dtheta[:, b.link, None] ** 2 * rc + ddt[:, b.link]
        out += b.inertia * ddtheta[:, b.link] + b.mass * (r[:, 0] * acc[:, 1] - r[:, 1] * acc[:, 0])
    return out
