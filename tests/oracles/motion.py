"""An independent reference solver for planar linkages of revolute and prismatic joints (test helper,
no code shared with synth.motion).

Each moving link has an absolute pose (x, y, φ): the position of its *anchor* (its first joint in
the pose) and its absolute angle.  A joint's point is stored per link in that link's own
coordinates (relative to the anchor, unrotated).  Equations: for a revolute joint the points of its
links coincide (2 per extra link); for a prismatic pair a, b with direction u the angles are equal
and b's point lies on a's line; a revolute input fixes the driven link's angle.  The input is moved
in small steps (0.25°), Newton's method (least squares, numpy) started from the previous solution.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["OracleLinkage", "follow", "oracle_of", "traced_by_the_oracle"]


class OracleLinkage:
    """links: number of links; joints: list of (kind, links tuple, point, direction or None);
    frame: the fixed link; driven: (joint index of the input, driven link)."""

    def __init__(self, links, joints, frame, driven):
        self.links, self.joints, self.frame = links, joints, frame
        self.input_joint, self.driven = driven
        self.anchor = {}
        for kind, members, point, _ in joints:
            for x in members:
                self.anchor.setdefault(x, np.array(point, dtype=float))
        self.moving = [x for x in range(links) if x != frame]
        self.phi0 = {x: 0.0 for x in range(links)}

    def local(self, link, point):
        return np.array(point, dtype=float) - self.anchor[link]

    def start(self):
        z = []
        for x in self.moving:
            z += [*self.anchor[x], 0.0]
        return np.array(z)

    def pose(self, z, link):
        if link == self.frame:
            return self.anchor[link], 0.0
        i = self.moving.index(link)
        return z[3 * i:3 * i + 2], z[3 * i + 2]

    def world(self, z, link, point):
        origin, phi = self.pose(z, link)
        c, s = math.cos(phi), math.sin(phi)
        v = self.local(link, point)
        return origin + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])

    def equations(self, z, turn):
        out = []
        for kind, members, point, direction in self.joints:
            if kind == "revolute":
                first = self.world(z, members[0], point)
                for x in members[1:]:
                    out += list(first - self.world(z, x, point))
            else:
                a, b = members
                _, pa = self.pose(z, a)
                _, pb = self.pose(z, b)
                c, s = math.cos(pa), math.sin(pa)
                u = np.array([c * direction[0] - s * direction[1], s * direction[0] + c * direction[1]])
                d = self.world(z, b, point) - self.world(z, a, point)
                out += [pa - pb, u[0] * d[1] - u[1] * d[0]]
        out.append(self.pose(z, self.driven)[1] - turn)
        return np.array(out)

    def solve(self, z, turn):
        for _ in range(50):
            r = self.equations(z, turn)
            if np.abs(r).max() < 1e-13:
                return z
            jac = np.empty((len(r), len(z)))
            for k in range(len(z)):
                dz = np.zeros(len(z))
                dz[k] = 1e-7
                jac[:, k] = (self.equations(z + dz, turn) - self.equations(z - dz, turn)) / 2e-7
            z = z - np.linalg.lstsq(jac, r, rcond=None)[0]
        raise ArithmeticError(f"no solution at input turn {turn}")


def follow(oracle: OracleLinkage, turns, step=math.radians(0.25)):
    """The oracle's link poses at each input rotation in ``turns`` (from the pose, ascending
    or descending from 0), each reached by small steps from the previous one; returns the world
    position of every joint (as listed) at each."""
    z, here, out = oracle.start(), 0.0, []
    for target in turns:
        count = max(1, math.ceil(abs(target - here) / step))
        for k in range(1, count + 1):
            z = oracle.solve(z, here + (target - here) * k / count)
        here = target
        out.append([oracle.world(z, members[0], point) for _, members, point, _ in oracle.joints])
    return np.array(out)


def oracle_of(lk, tracers: bool = False) -> OracleLinkage:
    """The oracle of an engine's linkage ``lk`` (a revolute input), read from its data only: joints,
    kinds, pose and slides; with ``tracers``, each tracer point is a last joint of its link alone (no
    equation: :func:`follow` gives its world position beside the joints')."""
    kinds = [lk.kind(k) for k in range(len(lk.chain.joints))]
    joints = [(kinds[k], lk.chain.joints[k], lk.points[k], lk.slides.get(k)) for k in range(len(kinds))]
    if tracers:
        joints += [("revolute", (link,), np.asarray(at, dtype=float), None) for link, at in lk.tracers.values()]
    return OracleLinkage(lk.chain.links, joints, lk.frame, (lk.inputs[0], lk.input_link(0)))


def traced_by_the_oracle(lk, inputs, tracer: str = "P", step=math.radians(1)) -> np.ndarray:
    """The points the tracer ``tracer`` of ``lk`` passes at the input values ``inputs`` (absolute, as a
    dimensional synthesis reports them), the linkage moved by the oracle from its pose, input after input
    (steps of ``step``: each Newton solve still to 1e-13)."""
    names = list(lk.tracers)
    moved = follow(oracle_of(lk, tracers=True), np.asarray(inputs, dtype=float) - float(lk.pose_inputs[0]), step)
    return moved[:, len(lk.chain.joints) + names.index(tracer)]
