"""Start linkages for motion generation from the target's own dyads: Burmester's RR dyads (circle and centre points)
and the RP dyads of a slider on the frame (the points whose positions are collinear).

A body passing poses i (its point P at Pᵢ, turned by φᵢ from the first pose) carries each of its points m
(body coordinates from P in the first pose) through Xᵢ(m) = Pᵢ + R(φᵢ) m.  A crank or rocker jointed to it at m and
pivoted on the frame at f keeps |Xᵢ(m) − f| = r at every pose (an **RR dyad**); a slider block jointed to it at m and
sliding on a guide of the frame keeps Xᵢ(m) on the guide's line (an **RP dyad**).  For a given m the best f and r are
the circle through the Xᵢ (linear least squares in f and |f|² − r²) and the best line the Xᵢ's principal axis (its
normal the eigenvector of their scatter's least eigenvalue), so a dyad of either kind is a zero of a function of m
alone — two unknowns, searched on a grid and polished by least squares in m and the circle or line.  Counting
(unknowns m, f, r or m and the line's two): five poses leave finitely many RR dyads (the Burmester points) and four
finitely many RP dyads (Ball's point: for four poses the positions of one point of the body, besides the poles', are
collinear), three poses a circle of them; more poses leave only those of a mechanism that passes them exactly, and
least squares beyond.  Two dyads, each jointed to the body at its own m, are a four-bar (RR + RR) or a slider-crank
(RR + RP) posed at the first pose.

The global stage of :func:`synthesize` searches all joint coordinates together and left two of five random
four-bars' six coupler poses 0.3–0.4 % of their size off after 60 CPU s (benchmarks/DIMENSION.md, *Motion
generation from no guess*); each dyad alone is a search in two unknowns, its exact zeros found in a tenth of a CPU
second.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.optimize import least_squares

from ..errors import MotionError
from ..structure.joints import PRISMATIC, REVOLUTE
from ._problem import input_joint_of
from ._target import MotionTarget

__all__ = ["dyads", "slider_dyads", "dyad_starts"]

#: grid points per side of the body's square where the moving pivot m is sought (its reach: REACH sizes)
GRID = 61
#: the square's half side and the frame pivots' box, in target sizes about the first point and the centre
REACH = 4.0
#: the least residual minima of the grid polished, and the distinct dyads kept of them
POLISHED, KEPT = 12, 6


def _carried(target: MotionTarget, m: np.ndarray) -> np.ndarray:
    """The places Xᵢ(m) (…, N, 2) of body points m (…, 2) at each pose."""
    p = target.poses[:, :2]
    phi = target.poses[:, 2] - target.poses[0, 2]
    c, s = np.cos(phi), np.sin(phi)
    mx, my = m[..., None, 0], m[..., None, 1]
    return p + np.stack((c * mx - s * my, s * mx + c * my), axis=-1)


def _circle_fit(x: np.ndarray, w: np.ndarray, size: float) -> np.ndarray:
    """The best circle (f, r) through each row of places x (G, N, 2), weighted: |X|² = 2 X·f + k, k = |f|² − r²,
    linear least squares per row.  Returns (G, 3): fx, fy, r."""
    root = np.sqrt(w)
    a = np.concatenate((2 * x, np.ones(x.shape[:2] + (1,))), axis=-1) * root[:, None]
    b = (x ** 2).sum(axis=-1) * root
    normal = np.einsum("gni,gnj->gij", a, a) + 1e-12 * size ** 2 * np.eye(3)
    fk = np.linalg.solve(normal, np.einsum("gni,gn->gi", a, b)[..., None])[..., 0]
    r = np.sqrt(np.maximum(fk[:, 2] + (fk[:, :2] ** 2).sum(axis=1), 0.0))
    return np.column_stack((fk[:, :2], r))


def _line_fit(x: np.ndarray, w: np.ndarray, size: float) -> np.ndarray:
    """The best line through each row of places x (G, N, 2), weighted (total least squares: the principal axis of
    their scatter about its weighted centroid).  Returns (G, 2): the line's direction angle θ and its offset
    c = n·X along its normal n = (−sin θ, cos θ)."""
    centroid = np.einsum("n,gni->gi", w, x) / w.sum()
    d = x - centroid[:, None]
    sxx, syy, sxy = (np.einsum("n,gn->g", w, d[..., i] * d[..., j]) for i, j in ((0, 0), (1, 1), (0, 1)))
    theta = 0.5 * np.arctan2(2 * sxy, sxx - syy)  # the scatter's greatest axis
    return np.column_stack((theta, -np.sin(theta) * centroid[:, 0] + np.cos(theta) * centroid[:, 1]))


@dataclass(frozen=True)
class _Kind:
    """One kind of dyad: its frame part fitted to a body point's places, its residual at each pose, which grid
    points are searched further, whether a polished dyad is one, and what it gives the frame."""

    fit: Callable  # (places (G, N, 2), weights (N,), size) -> frame parts z (G, k)
    residuals: Callable  # (places (..., N, 2), frame parts (..., k)) -> distances (..., N)
    searched: Callable  # (frame parts (G, k), centre (2,), size) -> (G,) bool
    proper: Callable  # (frame part (k,), size) -> bool
    frame: Callable  # frame part (k,) -> the fixed pivot f, or the guide's unit direction


def _circle_residuals(x, z):
    return np.linalg.norm(x - z[..., None, :2], axis=-1) - z[..., None, 2]


def _line_residuals(x, z):
    theta = z[..., None, 0]
    return -np.sin(theta) * x[..., 0] + np.cos(theta) * x[..., 1] - z[..., None, 1]


#: the dyads by the kind of their joint with the frame (their joint with the body is revolute)
KINDS = {
    REVOLUTE: _Kind(_circle_fit, _circle_residuals,
                    lambda z, centre, size: (np.abs(z[:, :2] - centre) <= REACH * size).all(axis=1),
                    lambda z, size: z[2] > 1e-9 * size,
                    lambda z: z[:2]),
    PRISMATIC: _Kind(_line_fit, _line_residuals,
                     lambda z, centre, size: np.ones(len(z), dtype=bool),
                     lambda z, size: True,
                     lambda z: np.array([np.cos(z[0]), np.sin(z[0])])),
}


def _dyads_of(target: MotionTarget, kind: _Kind) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The dyads of one kind that best guide the body through the poses (see :func:`dyads`)."""
    size = target.size
    w = np.ones(len(target)) if target.weights is None else target.weights / target.weights.mean()
    root = np.sqrt(w)
    centre = (target.points.min(axis=0) + target.points.max(axis=0)) / 2
    side = np.linspace(-REACH, REACH, GRID) * size
    m = np.stack(np.meshgrid(side, side), axis=-1).reshape(-1, 2)
    x = _carried(target, m)  # (G, N, 2)
    z = kind.fit(x, w, size)
    error = np.sqrt((w * kind.residuals(x, z) ** 2).mean(axis=1)) / size
    error = np.where(kind.searched(z, centre, size), error, np.inf).reshape(GRID, GRID)
    padded = np.pad(error, 1, constant_values=np.inf)
    neighbours = np.min([padded[1 + dy:GRID + 1 + dy, 1 + dx:GRID + 1 + dx]
                         for dy in (-1, 0, 1) for dx in (-1, 0, 1) if dy or dx], axis=0)
    minima = np.argwhere((error <= neighbours) & np.isfinite(error))
    minima = sorted(minima, key=lambda ij: error[ij[0], ij[1]])[:POLISHED]

    def residuals(v):
        return root * kind.residuals(_carried(target, v[:2]), v[2:]) / size

    found = []
    for i, j in minima:
        g = i * GRID + j
        v = least_squares(residuals, np.concatenate((m[g], z[g])), xtol=1e-15, ftol=1e-15, gtol=1e-15).x
        e = float(np.sqrt((residuals(v) ** 2).mean()))
        if kind.proper(v[2:], size) and not any(np.hypot(*(v[:2] - mm)) < 1e-6 * size for _, mm, _ in found):
            found.append((e, v[:2], kind.frame(v[2:])))
    found.sort(key=lambda d: d[0])
    return found[:KEPT]


def dyads(target: MotionTarget) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The RR dyads that best guide the body through the poses: (RMS of |Xᵢ − f| − r over the target's
    size, moving pivot m in body coordinates, fixed pivot f), least residual first, distinct.

    Examples
    --------
    >>> import math
    >>> turns = np.radians([0, 20, 45, 70, 100, 130])    # a body on a crank 2 long about (1, 1), P 0.5 along it
    >>> poses = [[1 + 2.5 * math.cos(a), 1 + 2.5 * math.sin(a), a] for a in turns]
    >>> e, m, f = dyads(MotionTarget(poses))[0]
    >>> e < 1e-12, np.round(f, 9).tolist()
    (True, [1.0, 1.0])
    """
    return _dyads_of(target, KINDS[REVOLUTE])


def slider_dyads(target: MotionTarget) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The RP dyads (a slider block pinned to the body, sliding on a guide of the frame) that best guide the body
    through the poses: (RMS distance of the places Xᵢ from the guide's line over the target's size, the pin m in
    body coordinates, the guide's unit direction), least residual first, distinct.  The guide's line passes
    through the pin's first place, P₁ + m.

    Examples
    --------
    >>> import math
    >>> turns, along = [0, 0.3, 0.5, 0.9, 1.2], [0, 0.4, 1.1, 1.5, 2.6]   # the body's point (2, 1) from P …
    >>> poses = [[s - 2 * math.cos(a) + math.sin(a), 0.5 - 2 * math.sin(a) - math.cos(a), a]   # … on y = 0.5
    ...          for a, s in zip(turns, along)]
    >>> e, m, u = slider_dyads(MotionTarget(poses))[0]
    >>> e < 1e-12, np.round(m, 9).tolist(), np.round(np.abs(u), 9).tolist()
    (True, [2.0, 1.0], [1.0, 0.0])
    """
    return _dyads_of(target, KINDS[PRISMATIC])


def _guided_loop(mechanism, tracer_link: int):
    """The joints of a loop frame – A – tracer – B – frame that alone guides the tracer link: (its two pins on the
    tracer link, the frame's joint of the link at each, the other joints), or None.  The loop guides it alone when
    the other links, if any, are one RRR dyad (two links, three revolute joints of two links each: no freedom of
    its own, so it follows the loop and does not move it)."""
    chain, frame, kinds = mechanism.chain, mechanism.frame, mechanism.chain.kinds
    if frame == tracer_link or any(len(j) != 2 for j in chain.joints):
        return None

    def on_frame(link):
        return [g for g, j in enumerate(chain.joints) if frame in j and link in j]

    pins = [k for k, j in enumerate(chain.joints) if tracer_link in j and frame not in j
            and len(on_frame(next(x for x in j if x != tracer_link))) == 1]
    if len(pins) != 2 or any(kinds[k] != REVOLUTE for k in pins):
        return None
    guides = [on_frame(next(x for x in chain.joints[k] if x != tracer_link))[0] for k in pins]
    if any(kinds[g] not in KINDS for g in guides):
        return None
    rest = [k for k in range(len(chain.joints)) if k not in pins + guides]
    links = {x for k in rest for x in chain.joints[k]} - {frame, tracer_link}.union(*(chain.joints[g] for g in guides))
    if not (rest == [] or (len(rest) == 3 and len(links) == 2 and all(kinds[k] == REVOLUTE for k in rest))):
        return None
    return pins, guides, rest


#: random placements of the joints of a six-bar's RRR dyad tried with each start of its guiding loop
COMPLETIONS = 6


def dyad_starts(mechanism, tracer_link: int, target, seed: int = 0) -> list:
    """Mechanisms posed at the first pose from the target's best dyads (:func:`dyads`, :func:`slider_dyads`), one
    for each pin of the tracer link, every pair both ways round: the ``starts`` :func:`synthesize` polishes first
    for a motion.  Empty unless the target is a motion and the tracer link is guided by a loop of four links
    with the frame (:func:`_guided_loop`): jointed by revolute pins to two links, each jointed to the frame (a
    revolute pair: an RR dyad; a prismatic one: an RP dyad) — a four-bar, a slider-crank, or a six-bar whose two
    other links are an RRR dyad (its three joints placed at random within the target's size about the first pose,
    ``COMPLETIONS`` times per pair of dyads, seeded by ``seed``).

    Examples
    --------
    >>> import math
    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.motion import Linkage, sweep
    >>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)
    >>> made = Linkage(four_bar, (0,), [[0, 0], [3, 0], [0.8, 0.6], [3.4, 2.1]], tracers={"P": (2, (2.2, 1.9))})
    >>> swept = sweep(made, steps=6, stop=float(made.pose_inputs[0]) + math.radians(200))
    >>> pins = np.asarray(swept.joints)[:, 3] - np.asarray(swept.joints)[:, 2]
    >>> target = MotionTarget(np.column_stack((swept.tracers["P"], np.arctan2(pins[:, 1], pins[:, 0]))))
    >>> starts = dyad_starts(four_bar, 2, target)
    >>> any(np.allclose(s.points, made.points, atol=1e-9) for s in starts)
    True
    """
    loop = _guided_loop(mechanism, tracer_link) if isinstance(target, MotionTarget) else None
    if loop is None:
        return []
    from ..motion import Linkage

    kinds, (pins, guides, rest) = mechanism.chain.kinds, loop
    joint, _ = input_joint_of(mechanism, None)
    first, size = target.poses[0, :2], target.size
    rng = np.random.default_rng(seed)
    found = {kind: _dyads_of(target, KINDS[kind]) for kind in {kinds[g] for g in guides}}
    starts = []
    for _, ma, za in found[kinds[guides[0]]]:
        for _, mb, zb in found[kinds[guides[1]]]:
            if np.hypot(*(ma - mb)) < 1e-9 * size:
                continue  # (one dyad twice, or two at one pin)
            if kinds[guides[0]] == kinds[guides[1]] == REVOLUTE and np.hypot(*(za - zb)) < 1e-9 * size:
                continue
            points, slides = np.zeros((len(kinds), 2)), {}
            for pin, guide, m, z in ((pins[0], guides[0], ma, za), (pins[1], guides[1], mb, zb)):
                points[pin] = first + m
                if kinds[guide] == PRISMATIC:  # the guide's line through the pin's first place
                    points[guide], slides[guide] = first + m, tuple(z)
                else:
                    points[guide] = z
            for _ in range(COMPLETIONS if rest else 1):
                points[rest] = first + size * rng.uniform(-1, 1, (len(rest), 2))
                try:
                    starts.append(Linkage(mechanism, (joint,), points.copy(), slides,
                                          tracers={"P": (tracer_link, tuple(first))}))
                except MotionError:  # (two pins of one link at one point, two parallel guides: no linkage)
                    continue
    return starts
