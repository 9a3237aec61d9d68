"""A linkage decomposed into its inputs and Assur dyads, each closed in closed form, vectorised over
every step of a sweep.

A dyad is two moving links i, j joined by a middle joint, each with an outer joint to a link whose
pose is already known.  Its kind is written by its joints outer–middle–outer (R revolute, P
prismatic): RRR (two circles), PRR and RRP (a circle and a line), RPR (a line at a fixed distance
from a point), PRP (two lines), RPP and PPR (both links turn with the known link of the outer
slider: two lines again, a Scotch yoke).  A gear on a known axis meshing with a known gear is a
group of one link.  Each dyad has two assembly modes (PRP and RPP one); the pose's mode is its sign
σ, kept for the whole sweep, so a sweep never jumps branch.  Each dyad also has a normalised discriminant g: the
dyad closes where g ≥ 0, and g = 0 is a dead position (its two links aligned).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..structure.joints import MESH, PRISMATIC, REVOLUTE
from ._kernel import GEAR, PRP, PRR, RPP, RPR, RRR, close_kernel
from ._linkage import Linkage

__all__ = ["Dyad", "Closure", "decompose", "close", "locked_groups"]


@dataclass(frozen=True)
class Dyad:
    """One group of the decomposition, in solving order.

    kind : "RRR", "PRR", "RPR", "PRP", "RPP" or "gear" (one link: a gear on a known axis)
    links : (i, j) — for a gear (g, g)
    outer : (J1, J2) — the outer joints (of i, of j); for a gear (axis joint, mesh joint)
    middle : J3 (−1 for a gear)
    known : (K1, K2) — the known links at J1, J2; for a gear (axis link, carrier)
    sign : σ, the assembly mode of the pose (+1 or −1; 0 where the pose is a dead position)
    """

    kind: str
    links: tuple[int, int]
    outer: tuple[int, int]
    middle: int
    known: tuple[int, int]
    sign: float = 1.0


def _letter(linkage: Linkage, k: int) -> str:
    return linkage.kind(k).letter


def decompose(linkage: Linkage) -> list[Dyad] | None:
    """The dyads (and gears on known axes) that close the linkage after its inputs, in solving
    order, each with the sign of the pose's assembly mode; None if some group is not one of these
    (a triad or higher: the linkage is then solved by Newton's method).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> [(d.kind, d.links, d.sign) for d in decompose(lk)]
    [('RRR', (2, 3), 1.0)]
    """
    chain = linkage.chain
    known = {linkage.frame} | {linkage.input_link(i) for i in range(linkage.dof)}
    plan: list[Dyad] = []
    while len(known) < chain.links:
        unknown = [x for x in range(chain.links) if x not in known]
        found = next(_groups(linkage, known, unknown), None)
        if found is None:
            return None
        plan.append(found)
        known.update(found.links)
    return _with_signs(linkage, plan)


def _attachments(linkage: Linkage, known: set[int], link: int) -> list[tuple[int, int]]:
    """(joint, known link) pairs: the joints (not meshes) of ``link`` that hold a known link."""
    out = []
    for k in linkage.joints_of(link):
        held = [x for x in linkage.chain.joints[k] if x in known]
        if held and linkage.kind(k) != MESH:
            out.append((k, held[0]))
    return out


def _groups(linkage: Linkage, known: set[int], unknown: list[int]) -> Iterator[Dyad]:
    """Every group that can be placed once the ``known`` links are: first gears turning on a known
    axis and meshing with a known gear (both axes on a known carrier), then dyads, each seen from the
    end its kind is written from (RRP is PRR reversed, PPR is RPP reversed)."""
    joints = linkage.chain.joints
    for g in unknown:
        for k, held in _attachments(linkage, known, g):
            if linkage.kind(k) != REVOLUTE:
                continue
            for m in linkage.joints_of(g):
                if linkage.kind(m) == MESH and sum(joints[m]) - g in known and linkage.carrier(m) in known:
                    yield Dyad("gear", (g, g), (k, m), -1, (held, linkage.carrier(m)))
    for i in unknown:
        for k3 in linkage.joints_of(i):
            if linkage.kind(k3) == MESH or any(x in known for x in joints[k3]):
                continue
            if linkage.kind(k3) == PRISMATIC and len(joints[k3]) != 2:
                continue
            for j in joints[k3]:
                if j == i:
                    continue
                for k1, h1 in _attachments(linkage, known, i):
                    if k1 == k3 or j in joints[k1]:
                        continue
                    for k2, h2 in _attachments(linkage, known, j):
                        if k2 in (k1, k3) or i in joints[k2]:
                            continue
                        kind = _letter(linkage, k1) + _letter(linkage, k3) + _letter(linkage, k2)
                        if kind in _REVERSED:  # the same group seen from its other end
                            yield Dyad(_REVERSED[kind], (j, i), (k2, k1), k3, (h2, h1))
                        elif kind in _KINDS:
                            yield Dyad(kind, (i, j), (k1, k2), k3, (h1, h2))


#: dyads written from their other end
_REVERSED = {"RRP": "PRR", "PPR": "RPP"}


def _with_signs(linkage: Linkage, plan: list[Dyad]) -> list[Dyad]:
    """Each dyad with the sign of the pose's assembly mode."""
    p, out = linkage.points, []
    for d in plan:
        if d.kind == "RRR":
            a, c, b = p[d.outer[0]], p[d.outer[1]], p[d.middle]
            sign = np.sign(_cross2(c - a, b - a))
        elif d.kind == "PRR":
            sign = np.sign(np.dot(linkage.slides[d.outer[0]], p[d.middle] - p[d.outer[1]]))
        elif d.kind == "RPR":
            sign = np.sign(np.dot(linkage.slides[d.middle], p[d.outer[1]] - p[d.outer[0]]))
        else:
            sign = 1.0
        out.append(Dyad(d.kind, d.links, d.outer, d.middle, d.known, float(sign)))
    return out


def _cross2(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


_KINDS = {"RRR": RRR, "PRR": PRR, "RPR": RPR, "PRP": PRP, "RPP": RPP, "gear": GEAR}


class Closure:
    """A linkage's dyads packed once for the compiled kernel, closed at any input offsets (S, W)
    from the pose's inputs.  Calling it gives θ (S, n), t (S, n, 2), g (S, G) the dyads'
    normalised discriminants (the dyad closes where g ≥ 0), μ (S, G) their transmission angles (rad
    in [0, π]; NaN for a gear) and every joint's position (S, J, 2); :meth:`points` gives only the
    joints and the tracer points (what a sweep keeps), :meth:`angles` only θ.  Where a dyad does not close, its links'
    poses are NaN.

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> joints, tracers = Closure(lk, decompose(lk)).points(np.array([[0.0], [np.pi]]))
    >>> joints[1, 2].round(12).tolist()
    [-1.0, 0.0]
    """

    def __init__(self, linkage: Linkage, plan: list[Dyad]):
        lk = self.linkage = linkage
        chain = lk.chain
        count = len(chain.joints)
        slides = np.zeros((count, 2))
        for k, u in lk.slides.items():
            slides[k] = u
        in_link = np.array([lk.input_link(i) for i in range(lk.dof)], dtype=np.int64)
        in_prismatic = np.array([lk.kind(k) == PRISMATIC for k in lk.inputs])
        in_point = np.array([lk.points[k] for k in lk.inputs], dtype=float).reshape(-1, 2)
        in_slide = np.array([slides[k] for k in lk.inputs], dtype=float).reshape(-1, 2)
        groups = np.array([_KINDS[d.kind] for d in plan], dtype=np.int64)
        ints = np.zeros((len(plan), 9), dtype=np.int64)
        floats = np.zeros((len(plan), 2))
        for m, d in enumerate(plan):
            mesh = chain.joints[d.outer[1]] if d.kind == "gear" else (0, 0)
            ints[m] = (*d.links, *d.outer, max(d.middle, 0), *d.known, *mesh)
            floats[m] = (d.sign, lk.meshes.get(d.outer[1], 1.0) if d.kind == "gear" else 0.0)
        points = np.array(lk.points, dtype=float)  # a writable copy, as the tracers' below: one compiled signature
        self._dyads = (in_link, in_prismatic, in_point, in_slide, groups, ints, floats, points, slides)
        first = np.array([j[0] for j in chain.joints], dtype=np.int64)
        self._joints = (first, points)
        traced = list(lk.tracers.values())
        self._carried = (np.concatenate((first, np.array([link for link, _ in traced], dtype=np.int64))),
                         np.concatenate((points, np.array([at for _, at in traced], dtype=float).reshape(-1, 2))))
        self._scale2 = float(lk.scale) ** 2

    def _run(self, offsets, carried, every: bool, angles: bool = True, recurrence: bool = False):
        offsets = np.ascontiguousarray(offsets, dtype=float)
        steps, n, groups = offsets.shape[0], self.linkage.chain.links, len(self._dyads[4])
        rows = steps if every else 0
        theta = np.empty((steps if angles else 0, n))
        t_x, t_y = np.empty((rows, n)), np.empty((rows, n))
        g, mu = np.empty((rows, groups)), np.empty((rows, groups))
        out = np.empty((steps, len(carried[0]), 2))
        close_kernel(offsets, recurrence, *self._dyads, *carried, self._scale2, theta, t_x, t_y, g, mu, out)
        return theta, t_x, t_y, g, mu, out

    def __call__(self, offsets: np.ndarray):
        theta, t_x, t_y, g, mu, joints = self._run(offsets, self._joints, True)
        return theta, np.stack((t_x, t_y), axis=-1), g, mu, joints

    def points(self, offsets: np.ndarray):
        """The joints (S, J, 2) and each tracer's points (S, 2) by name (the kernel computes no angle; a
        revolute input's cosine and sine by the rotation recurrence: for a sweep's many steps)."""
        out = self._run(offsets, self._carried, False, False, True)[-1]
        count = len(self.linkage.chain.joints)
        return out[:, :count], {name: out[:, count + i] for i, name in enumerate(self.linkage.tracers)}

    def angles(self, offsets: np.ndarray) -> np.ndarray:
        """θ (S, n): each link's rotation from the pose (rad, modulo a turn; a gear's as its ratio turns it)."""
        return self._run(offsets, (np.empty(0, dtype=np.int64), np.empty((0, 2))), False, True, True)[0]


def close(linkage: Linkage, plan: list[Dyad], offsets: np.ndarray):
    """Every link's pose at S input offsets (S, W) from the pose's inputs, by the compiled kernel:
    θ, t, g, μ and the joints, as :class:`Closure` gives them."""
    return Closure(linkage, plan)(offsets)


def locked_groups(linkage: Linkage) -> list[tuple[int, int]]:
    """The dyads aligned in the pose (a dead position), by their links; empty if the linkage does
    not decompose or no dyad is aligned."""
    plan = decompose(linkage)
    if plan is None:
        return []
    g = close(linkage, plan, np.zeros((1, linkage.dof)))[2]
    return [d.links for m, d in enumerate(plan) if d.kind != "gear" and g[0, m] < 1e-12]
