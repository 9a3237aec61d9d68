"""Start linkages for a four-bar's motion generation from its RR dyads (Burmester's circle and centre points).

A body passing poses i (its point P at Pᵢ, turned by φᵢ from the first pose) carries each of its points m
(body coordinates from P in the first pose) through Xᵢ(m) = Pᵢ + R(φᵢ) m.  A crank or rocker jointed to it
at m and pivoted on the frame at f keeps |Xᵢ(m) − f| = r at every pose: for a given m, f and r are the best
circle through the Xᵢ (linear least squares in f and |f|² − r²), so the dyads are the zeros of a function of
m alone — two unknowns, searched on a grid and polished by least squares in (m, f, r).  Five poses leave
finitely many dyads (the Burmester points), six or more only those of a mechanism that passes them exactly;
two of them, each jointed to the body and pivoted on the frame, are a four-bar posed at the first pose.

The global stage of :func:`synthesize` searches the four-bar's eight joint coordinates together and left two of
five random four-bars' six coupler poses 0.3–0.4 % of their size off after 60 CPU s (benchmarks/DIMENSION.md,
*Motion generation from no guess*); each dyad alone is a search in two unknowns, its exact zeros found in a tenth
of a CPU second.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares

from ..errors import MotionError
from ..structure.joints import REVOLUTE
from ._problem import input_joint_of
from ._target import MotionTarget

__all__ = ["dyads", "dyad_starts"]

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
    size = target.size
    w = np.ones(len(target)) if target.weights is None else target.weights / target.weights.mean()
    root = np.sqrt(w)
    centre = (target.points.min(axis=0) + target.points.max(axis=0)) / 2
    side = np.linspace(-REACH, REACH, GRID) * size
    m = np.stack(np.meshgrid(side, side), axis=-1).reshape(-1, 2)
    x = _carried(target, m)  # (G, N, 2)
    # |X|² = 2 X·f + k, k = |f|² − r²: weighted linear least squares per grid point
    a = np.concatenate((2 * x, np.ones(x.shape[:2] + (1,))), axis=-1) * root[:, None]
    b = (x ** 2).sum(axis=-1) * root
    normal = np.einsum("gni,gnj->gij", a, a) + 1e-12 * size ** 2 * np.eye(3)
    fk = np.linalg.solve(normal, np.einsum("gni,gn->gi", a, b)[..., None])[..., 0]
    f = fk[:, :2]
    r = np.sqrt(np.maximum(fk[:, 2] + (f ** 2).sum(axis=1), 0.0))
    error = np.sqrt((w * (np.linalg.norm(x - f[:, None], axis=-1) - r[:, None]) ** 2).mean(axis=1)) / size
    error = np.where((np.abs(f - centre) <= REACH * size).all(axis=1), error, np.inf).reshape(GRID, GRID)
    padded = np.pad(error, 1, constant_values=np.inf)
    neighbours = np.min([padded[1 + dy:GRID + 1 + dy, 1 + dx:GRID + 1 + dx]
                         for dy in (-1, 0, 1) for dx in (-1, 0, 1) if dy or dx], axis=0)
    minima = np.argwhere((error <= neighbours) & np.isfinite(error))
    minima = sorted(minima, key=lambda ij: error[ij[0], ij[1]])[:POLISHED]

    def residuals(z):
        return root * (np.linalg.norm(_carried(target, z[:2]) - z[2:4], axis=1) - z[4]) / size

    found = []
    for i, j in minima:
        g = i * GRID + j
        z = least_squares(residuals, np.concatenate((m[g], f[g], [r[g]])), xtol=1e-15, ftol=1e-15, gtol=1e-15).x
        e = float(np.sqrt((residuals(z) ** 2).mean()))
        if z[4] > 1e-9 * size and not any(np.hypot(*(z[:2] - mm)) + np.hypot(*(z[2:4] - ff)) < 1e-6 * size
                                          for _, mm, ff in found):
            found.append((e, z[:2], z[2:4]))
    found.sort(key=lambda d: d[0])
    return found[:KEPT]


def dyad_starts(mechanism, tracer_link: int, target, seed: int = 0) -> list:
    """Four-bars posed at the first pose from pairs of the target's best dyads (:func:`dyads`), each pair
    both ways round (which is the input's): the ``starts`` :func:`synthesize` polishes first for a motion.
    Empty unless the target is a motion and the mechanism a four-bar of revolute pairs whose tracer link is its
    coupler.  (``seed`` is not used: the dyads are found on a grid.)

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
    if not isinstance(target, MotionTarget):
        return []
    chain, frame = mechanism.chain, mechanism.frame
    if chain.links != 4 or len(chain.joints) != 4 or any(kind != REVOLUTE for kind in chain.kinds):
        return []
    pins = [k for k, j in enumerate(chain.joints) if tracer_link in j]
    if frame == tracer_link or any(frame in chain.joints[k] for k in pins) or len(pins) != 2:
        return []
    from ..motion import Linkage

    def pivot_of(pin: int) -> int:  # the frame's joint of the link jointed to the coupler at ``pin``
        link = next(x for x in chain.joints[pin] if x != tracer_link)
        return next(g for g, j in enumerate(chain.joints) if frame in j and link in j)

    joint, _ = input_joint_of(mechanism, None)
    first = target.poses[0, :2]
    found = dyads(target)
    starts = []
    for a, (_, ma, fa) in enumerate(found):
        for b, (_, mb, fb) in enumerate(found):
            if a == b or np.hypot(*(fa - fb)) < 1e-9 * target.size:
                continue
            points = np.zeros((4, 2))
            (k1, k2) = pins
            points[k1], points[pivot_of(k1)] = first + ma, fa
            points[k2], points[pivot_of(k2)] = first + mb, fb
            try:
                starts.append(Linkage(mechanism, (joint,), points, tracers={"P": (tracer_link, tuple(first))}))
            except MotionError:  # (two pins of one link at one point: no linkage)
                continue
    return starts
