"""A linkage decomposed into its inputs and Assur dyads, each closed in closed form, vectorised over
every step of a sweep.

A dyad is two moving links i, j joined by a middle joint, each with an outer joint to a link whose
pose is already known.  Its kind is written by its joints outer–middle–outer (R revolute, P
prismatic): RRR (two circles), PRR and RRP (a circle and a line), RPR (a line at a fixed distance
from a point), PRP (two lines).  A gear on a known axis meshing with a known gear is a group of one
link.  Each dyad has two assembly modes (PRP one); the pose's mode is its sign σ, kept for the
whole sweep, so a sweep never jumps branch.  Each dyad also has a normalised discriminant g: the
dyad closes where g ≥ 0, and g = 0 is a dead position (its two links aligned).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._linkage import Linkage

__all__ = ["Dyad", "decompose", "close", "locked_groups"]


@dataclass(frozen=True)
class Dyad:
    """One group of the decomposition, in solving order.

    kind : "RRR", "PRR", "RPR", "PRP" or "gear" (one link: a gear on a known axis)
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
    return {"revolute": "R", "prismatic": "P", "mesh": "G"}[linkage.kind(k)]


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
    joints = chain.joints
    plan: list[Dyad] = []

    def attachments(link):
        """(joint, known link) pairs: joints of ``link`` that hold a known link."""
        out = []
        for k in linkage.joints_of(link):
            kind = linkage.kind(k)
            if kind == "mesh":
                continue
            held = [x for x in joints[k] if x in known]
            if held:
                out.append((k, held[0]))
        return out

    while len(known) < chain.links:
        found = None
        unknown = [x for x in range(chain.links) if x not in known]
        for g in unknown:  # a gear turning on a known axis, meshing with a known gear, both on a known carrier
            for k, held in attachments(g):
                if linkage.kind(k) != "revolute":
                    continue
                for m in linkage.joints_of(g):
                    if linkage.kind(m) == "mesh":
                        other = sum(joints[m]) - g
                        c = linkage.carrier(m)
                        if other in known and c in known:
                            found = Dyad("gear", (g, g), (k, m), -1, (held, c))
                            break
                if found:
                    break
            if found:
                break
        if found is None:
            for i in unknown:
                for k3 in linkage.joints_of(i):
                    if linkage.kind(k3) == "mesh" or any(x in known for x in joints[k3]):
                        continue
                    for j in joints[k3]:
                        if j == i or (linkage.kind(k3) == "prismatic" and len(joints[k3]) != 2):
                            continue
                        for k1, h1 in attachments(i):
                            if k1 == k3 or j in joints[k1]:
                                continue
                            for k2, h2 in attachments(j):
                                if k2 in (k1, k3) or i in joints[k2]:
                                    continue
                                kind = _letter(linkage, k1) + _letter(linkage, k3) + _letter(linkage, k2)
                                if kind == "RRP":  # the same group seen from its other end
                                    found = Dyad("PRR", (j, i), (k2, k1), k3, (h2, h1))
                                elif kind in ("RRR", "PRR", "RPR", "PRP"):
                                    found = Dyad(kind, (i, j), (k1, k2), k3, (h1, h2))
                                else:
                                    continue
                                break
                            if found:
                                break
                        if found:
                            break
                    if found:
                        break
                if found:
                    break
        if found is None:
            return None
        plan.append(found)
        known.update(found.links)
    return _with_signs(linkage, plan)


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


def _rot(theta, p):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack((c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]), axis=-1)


def _angle(v):
    return np.arctan2(v[..., 1], v[..., 0])


def _between(v, w):
    """The angle between vectors v and w, in [0, π]."""
    return np.arctan2(np.abs(_cross2(v, w)), (v * w).sum(axis=-1))


def close(linkage: Linkage, plan: list[Dyad], offsets: np.ndarray):
    """Every link's pose at S input offsets (S, W) from the pose's inputs.

    Returns θ (S, n), t (S, n, 2), g (S, G) the dyads' normalised discriminants (the dyad closes
    where g ≥ 0) and μ (S, G) their transmission angles (rad in [0, π]; NaN for a gear).  Where a
    dyad does not close, its links' poses are NaN.
    """
    lk = linkage
    p = lk.points
    s = offsets.shape[0]
    n = lk.chain.links
    theta = np.zeros((s, n))
    t = np.zeros((s, n, 2))
    for i, k in enumerate(lk.inputs):
        link = lk.input_link(i)
        if lk.kind(k) == "revolute":
            theta[:, link] = offsets[:, i]
            t[:, link] = p[k] - _rot(offsets[:, i], p[k])
        else:
            t[:, link] = offsets[:, i, None] * np.array(lk.slides[k])
    g = np.empty((s, len(plan)))
    mu = np.full((s, len(plan)), np.nan)
    scale2 = lk.scale ** 2

    def at(k, link):  # joint k's reference point carried by known link
        return _rot(theta[:, link], p[k]) + t[:, link]

    def place(link, angle, point, ref):  # a link turned by ``angle`` with its point ``ref`` at ``point``
        theta[:, link] = angle
        t[:, link] = point - _rot(angle, ref)

    for m, d in enumerate(plan):
        i, j = d.links
        k1, k2 = d.outer
        if d.kind == "RRR":
            a0, b0, c0 = p[k1], p[d.middle], p[k2]
            a, c = at(k1, d.known[0]), at(k2, d.known[1])
            li2, lj2 = ((b0 - a0) ** 2).sum(), ((b0 - c0) ** 2).sum()
            dv = c - a
            dd = (dv ** 2).sum(axis=1)
            with np.errstate(divide="ignore", invalid="ignore"):
                along = (li2 - lj2 + dd) / (2 * dd)
                h2 = li2 / dd - along ** 2
                g[:, m] = np.where(dd > 0, h2 * dd / li2, -1.0)
                b = a + along[:, None] * dv + (d.sign * np.sqrt(h2))[:, None] * np.stack((-dv[:, 1], dv[:, 0]), 1)
            place(i, _angle(b - a) - _angle(b0 - a0), a, a0)
            place(j, _angle(b - c) - _angle(b0 - c0), c, c0)
            mu[:, m] = _between(a - b, c - b)
        elif d.kind == "PRR":
            k_1, k_2 = d.known
            u = _rot(theta[:, k_1], np.array(lk.slides[k1]))
            base = at(d.middle, k_1)
            c0, b0 = p[k2], p[d.middle]
            c = at(k2, k_2)
            w = base - c
            bb = (u * w).sum(axis=1)
            disc = bb ** 2 - (w ** 2).sum(axis=1) + ((b0 - c0) ** 2).sum()
            g[:, m] = disc / ((b0 - c0) ** 2).sum()
            with np.errstate(invalid="ignore"):
                slide = -bb + d.sign * np.sqrt(disc)
            b = base + slide[:, None] * u
            theta[:, i] = theta[:, k_1]
            t[:, i] = t[:, k_1] + slide[:, None] * u
            place(j, _angle(b - c) - _angle(b0 - c0), c, c0)
            mu[:, m] = _between(b - c, np.stack((-u[:, 1], u[:, 0]), 1))
        elif d.kind == "RPR":
            a0, c0 = p[k1], p[k2]
            u0 = np.array(lk.slides[d.middle])
            a, c = at(k1, d.known[0]), at(k2, d.known[1])
            dv = c - a
            h = _cross2(u0, c0 - a0)
            disc = (dv ** 2).sum(axis=1) - h ** 2
            g[:, m] = disc / scale2
            with np.errstate(invalid="ignore"):
                psi = np.arctan2(np.full(s, h), d.sign * np.sqrt(disc))
            angle = _angle(dv) - _angle(u0) - psi
            place(i, angle, a, a0)
            place(j, angle, c, c0)
            uw = _rot(angle, u0)
            mu[:, m] = _between(dv, np.stack((-uw[:, 1], uw[:, 0]), 1))
        elif d.kind == "PRP":
            k_1, k_2 = d.known
            u1 = _rot(theta[:, k_1], np.array(lk.slides[k1]))
            u2 = _rot(theta[:, k_2], np.array(lk.slides[k2]))
            delta = at(d.middle, k_2) - at(d.middle, k_1)
            det = _cross2(u2, u1)  # of the columns [u1, −u2]
            g[:, m] = det ** 2
            with np.errstate(divide="ignore", invalid="ignore"):
                s1 = _cross2(delta, -u2) / det
                s2 = _cross2(u1, delta) / det
            theta[:, i], theta[:, j] = theta[:, k_1], theta[:, k_2]
            t[:, i] = t[:, k_1] + s1[:, None] * u1
            t[:, j] = t[:, k_2] + s2[:, None] * u2
            mu[:, m] = _between(u1, u2)
        else:  # a gear on a known axis
            axis, mesh = k1, k2
            a, b = lk.chain.joints[mesh]
            c = d.known[1]
            ratio = lk.meshes[mesh]
            angle = (theta[:, c] + (theta[:, a] - theta[:, c]) / ratio if i == b
                     else theta[:, c] + ratio * (theta[:, b] - theta[:, c]))
            place(i, angle, at(axis, d.known[0]), p[axis])
            g[:, m] = 1.0
    return theta, t, g, mu


def locked_groups(linkage: Linkage) -> list[tuple[int, int]]:
    """The dyads aligned in the pose (a dead position), by their links; empty if the linkage does
    not decompose or no dyad is aligned."""
    plan = decompose(linkage)
    if plan is None:
        return []
    _, _, g, _ = close(linkage, plan, np.zeros((1, linkage.dof)))
    return [d.links for m, d in enumerate(plan) if d.kind != "gear" and g[0, m] < 1e-12]
