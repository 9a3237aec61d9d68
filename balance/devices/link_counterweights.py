"""Counterweights that make a linkage's total first moment of mass constant over its input's range
(shaking-force and gravity balancing; Berkof & Lowen 1969, the linearly independent vectors).

A counterweight of mass μ on link l, placed d/μ from the link's joint J (``LinkBody.anchor``: its
frame pivot, else its first joint), adds R(θ_l) d + μ P_J(q) to the first moment, P_J = R(θ_l) J + t_l
the joint's path: linear in (d, μ).  On a link pivoted on the frame P_J is the fixed pivot, so only the
moment d about the pivot matters (its mass or radius is then the designer's: ``counter_mass``,
``counter_radius``, else the link's reach from the pivot).  The best (d, μ ≥ 0) over sampled inputs is a
bounded linear least-squares problem (BVLS) on the first moment's deviation from its mean.

Examples
--------
>>> import numpy as np
>>> from balance.model.linkage import LinkBody
>>> crank = LinkBody(1, (("0-1", (0.0, 0.0)), ("1-2", (1.0, 0.0))), 2.0, (0.5, 0.0), "0-1")
>>> q = np.linspace(0, 2 * np.pi, 9)
>>> z = np.zeros((9, 2, 2))
>>> motion = (np.c_[0 * q, q], z, np.c_[0 * q, 1 + 0 * q], z, np.zeros((9, 2)), z)
>>> cw, = fit_counterweights([crank], [crank], motion, 2)
>>> round(cw.mass, 12), round(cw.distance, 12), round(cw.angle_deg, 9), cw.towards   # 1 kg·m opposite
(1.0, 1.0, 180.0, '1-2')
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from scipy.optimize import lsq_linear

from mechbase import Row

from ..errors import InvalidInput
from ..model.linkage import LinkBody, body_arrays, first_moment

__all__ = ["LinkCounterweight", "fit_counterweights"]

#: a counterweight's moment (a floating one's mass, where it has no moment) below this share of the largest
#: link moment (or mass) is none at all
NONE_NEEDED = 1e-12


@dataclass(frozen=True)
class LinkCounterweight(Row):
    """A point mass fixed to a link: ``mass`` kg at ``distance`` m from the link's ``joint``, at
    ``angle_deg`` counterclockwise from the line from that joint towards the joint ``towards``;
    ``at`` is the same point in the pose (m); ``moment`` = mass × (at − joint) (kg·m)."""

    link: int
    mass: float
    joint: str
    distance: float
    angle_deg: float
    towards: str | None
    at: tuple[float, float]
    moment: tuple[float, float]

    @property
    def first_moment(self) -> np.ndarray:
        """μ·p: the counterweight's first moment about the origin of the pose (kg·m)."""
        return self.mass * np.asarray(self.at, dtype=float)


def fit_counterweights(bodies: Sequence[LinkBody], on: Sequence[LinkBody], motion: tuple, links: int,
                       counter_mass: float | None = None, counter_radius: float | None = None
                       ) -> tuple[LinkCounterweight, ...]:
    """The counterweights on the links ``on`` that keep the first moment of ``bodies`` (with theirs)
    closest to constant over the sampled ``motion`` (θ, t, θ', t', θ'', t'') of an ``links``-link chain.

    ``counter_mass`` fixes every counterweight's mass; ``counter_radius`` the distance from a frame
    pivot (pivoted links only). One counterweight per link of ``on`` (mass 0 where none is needed).
    """
    if counter_mass is not None and counter_radius is not None:
        raise InvalidInput("give a counterweight's mass or its radius, not both: the moment fixes the other.")
    for name, v in (("mass", counter_mass), ("radius", counter_radius)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise InvalidInput(f"a counterweight's {name} must be a positive number, not {v:g}.")
    floating = [b.link for b in on if b.pivot is None]
    if counter_radius is not None and floating:
        raise InvalidInput(f"a counterweight's radius is fixed about a frame pivot, and link {floating[0]} floats: "
                           "give its mass instead (--counter-mass), or neither.")
    fixed = {b.link: counter_mass for b in on if b.pivot is None and counter_mass is not None}
    d, mu = _fit(bodies, on, motion, links, fixed)
    reach = {b.link: b.reach for b in on}
    far = {k: float(np.hypot(*d[k])) / reach[k] for k in mu if k not in fixed and reach[k] > 0
           and float(np.hypot(*d[k])) > reach[k] * mu[k]}
    if far:  # a floating counterweight placed beyond its link's reach (or of no mass): its mass set by the reach
        d, mu = _fit(bodies, on, motion, links, fixed | far)
    mass, moment = body_arrays(bodies, links)
    scale = max(float(np.abs(moment).max(initial=0.0)), float(np.abs(mass).max(initial=0.0)), 1e-300)
    out = []
    for b in on:
        if b.pivot is None:
            m = mu[b.link]
        else:
            size, radius = float(np.hypot(*d[b.link])), counter_radius or b.reach
            if counter_mass is None and size > 0 and radius == 0:
                raise InvalidInput(f"link {b.link} reaches nowhere from its pivot {b.pivot}: give the counterweight's "
                                   "radius or mass (--counter-radius, --counter-mass).")
            m = counter_mass if counter_mass is not None else (size / radius if size > 0 else 0.0)
        out.append(_placed(b, d[b.link], m, scale))
    return tuple(out)


def _fit(bodies, on, motion, links, fixed: dict) -> tuple[dict, dict]:
    """The least-squares moments d (about each link's anchor) and the floating links' masses μ ≥ 0
    (those in ``fixed`` held at their value)."""
    theta, t = motion[0], motion[1]
    mass, moment = body_arrays(bodies, links)
    target = first_moment(mass, moment, motion)  # (S, 2)
    columns, bounds, unknowns = [], [], []
    for b in on:
        c, s = np.cos(theta[:, b.link]), np.sin(theta[:, b.link])
        columns += [np.stack((c, s), axis=1), np.stack((-s, c), axis=1)]  # R(θ) d, per component of d
        bounds += [(-np.inf, np.inf)] * 2
        unknowns += [(b.link, 0), (b.link, 1)]
        if b.pivot is None:
            path = _joint_path(b, theta, t)
            if b.link in fixed:
                target = target + fixed[b.link] * path
            else:
                columns.append(path)
                bounds.append((0.0, np.inf))
                unknowns.append((b.link, "mass"))
    if 2 * (len(theta) - 1) < len(columns):
        raise InvalidInput(f"{len(theta)} samples of the input cannot fix {len(columns)} unknowns of the counterweights: "
                           "sample more inputs.")
    a = np.stack([col - col.mean(axis=0) for col in columns], axis=-1).reshape(-1, len(columns))
    rhs = -(target - target.mean(axis=0)).reshape(-1)
    lo, hi = np.array(bounds).T
    x = lsq_linear(a, rhs, bounds=(lo, hi), method="bvls", tol=1e-15).x
    d = {b.link: np.zeros(2) for b in on}
    mu = {b.link: fixed[b.link] for b in on if b.link in fixed}
    for (link, which), value in zip(unknowns, x):
        if which == "mass":
            mu[link] = float(value)
        else:
            d[link][which] = value
    return d, mu


def _joint_path(b: LinkBody, theta: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Where the link's anchor joint is at each sample (S, 2)."""
    x, y = b.joint(b.anchor)
    c, s = np.cos(theta[:, b.link]), np.sin(theta[:, b.link])
    return np.stack((c * x - s * y, s * x + c * y), axis=1) + t[:, b.link]


def _placed(b: LinkBody, d: np.ndarray, mu: float, scale: float) -> LinkCounterweight:
    """The counterweight of moment ``d`` about the link's anchor and mass ``mu``, placed and described."""
    origin = b.joint(b.anchor)
    size = float(np.hypot(*d))
    if size <= NONE_NEEDED * scale:
        d, size = np.zeros(2), 0.0
    if size == 0 and (mu <= NONE_NEEDED * scale or b.pivot is not None):
        mu = 0.0  # none needed: on a pivot a mass changes nothing; a floating one's mass of rounding is none
    elif mu <= 0:
        raise InvalidInput(f"the counterweight of link {b.link} would need a moment of {size:.6g} kg·m with no mass "
                           "(a mass at infinity): give its mass (--counter-mass) or leave the link out of --on.")
    offset = d / mu if mu > 0 else np.zeros(2)
    towards = next((n for n, p in b.joints if n != b.anchor and np.hypot(*(np.array(p) - origin)) > 0), None)
    line = (b.joint(towards) - origin) if towards else np.array([1.0, 0.0])
    angle = math.degrees(math.atan2(line[0] * offset[1] - line[1] * offset[0], line @ offset)) if size else 0.0
    if angle <= -180 + 1e-9:  # opposite the line: 180°, whichever side rounding put it
        angle += 360
    at = origin + offset
    return LinkCounterweight(b.link, float(mu), b.anchor, size / mu if mu > 0 else 0.0, angle, towards,
                             (float(at[0]), float(at[1])), (float(d[0]), float(d[1])))
