"""Independent answers for prismatic pairs (test helpers, nothing imported from ``synth``).

* ``generic_mobility``: the planar constraint Jacobian at a random configuration, its rank
  giving the generic mobility (what the wedge rule must equal);
* ``idle_joints``: the joints whose links never move relative to each other, on the null space
  of the same constraints (SVD);
* ``count_rule``: the wedge count 3(n − 1) − 2p + c_P, c_P by breadth-first search;
* ``brute_variant_count``: assignments of k prismatic pairs up to the chain's symmetry, by
  trying every permutation of the links (itertools, not nauty), without idle joints and
  without a hidden redundancy (count ≠ Jacobian rank).
"""

from __future__ import annotations

from itertools import combinations, permutations

import numpy as np

__all__ = ["generic_mobility", "idle_joints", "brute_variant_count", "has_idle_joint", "count_rule"]


def _constraints(links: int, joints, kinds, rng: np.random.Generator) -> np.ndarray:
    """Velocity constraints at a random configuration: a link's state is (ω, vx, vy) of the point
    at the origin.  A revolute joint at r (a multiple joint: one pin for all its links) equates the
    links' velocities of r (2 rows per link after the first); a prismatic pair of direction u
    equates their ω and their velocities across u (2 rows)."""
    rows = []
    for j, kind in zip(joints, kinds):
        a = j[0]
        if kind == "revolute":
            rx, ry = rng.normal(size=2)
            for b in j[1:]:
                for coeffs in ((-ry, 1.0, 0.0), (rx, 0.0, 1.0)):
                    row = np.zeros(3 * links)
                    row[3 * a: 3 * a + 3] = coeffs
                    row[3 * b: 3 * b + 3] = [-c for c in coeffs]
                    rows.append(row)
        else:
            b = j[1]
            t = rng.uniform(0, np.pi)
            nx, ny = -np.sin(t), np.cos(t)
            for coeffs in ((1.0, 0.0, 0.0), (0.0, nx, ny)):
                row = np.zeros(3 * links)
                row[3 * a: 3 * a + 3] = coeffs
                row[3 * b: 3 * b + 3] = [-c for c in coeffs]
                rows.append(row)
    frame = np.zeros((3, 3 * links))
    frame[:, :3] = np.eye(3)
    return np.vstack(rows + [frame])


def generic_mobility(links: int, joints, kinds, rng: np.random.Generator, *, trials: int = 2) -> int:
    """3(n − 1) − rank of the velocity constraints at random joint points and slide directions
    (floating point, numpy's SVD rank); the largest rank over a few random configurations is the
    generic rank."""
    return 3 * links - max(np.linalg.matrix_rank(_constraints(links, joints, kinds, rng)) for _ in range(trials))


def idle_joints(links: int, joints, kinds, rng: np.random.Generator) -> list[tuple[int, ...]]:
    """Joints whose links never move relative to each other: the null space of the constraints
    (SVD) gives every motion; a revolute joint is idle when two of its links turn equally in all
    of them, a prismatic pair when its links never move apart."""
    m = _constraints(links, joints, kinds, rng)
    _, s, vt = np.linalg.svd(m)
    rank = int((s > 1e-9 * s[0]).sum())
    null = vt[rank:]  # rows: a basis of the motions (the frame held)
    out = []
    for j, kind in zip(joints, kinds):
        pairs = [(a, b) for i, a in enumerate(j) for b in j[i + 1:]]
        if kind == "revolute":
            idle = any(np.allclose(null[:, 3 * a] - null[:, 3 * b], 0, atol=1e-8) for a, b in pairs)
        else:
            (a, b), = pairs
            idle = np.allclose(null[:, 3 * a + 1: 3 * a + 3] - null[:, 3 * b + 1: 3 * b + 3], 0, atol=1e-8)
        if idle:
            out.append(tuple(j))
    return out


def has_idle_joint(links: int, joints, kinds) -> bool:
    """Whether any joint never moves (:func:`idle_joints` at a fixed random configuration)."""
    return bool(idle_joints(links, joints, kinds, np.random.default_rng(99)))


def count_rule(links: int, joints, kinds) -> int:
    """3(n − 1) − 2p + c_P for simple joints, c_P = |P| − n + (components of the P pairs' graph)."""
    adj = {x: set() for x in range(links)}
    for (a, b), k in zip(joints, kinds):
        if k == "prismatic":
            adj[a].add(b)
            adj[b].add(a)
    seen, components = set(), 0
    for start in range(links):
        if start in seen:
            continue
        components += 1
        seen.add(start)
        todo = [start]
        while todo:
            x = todo.pop()
            for y in adj[x] - seen:
                seen.add(y)
                todo.append(y)
    c_p = sum(1 for k in kinds if k == "prismatic") - links + components
    return 3 * (links - 1) - 2 * len(joints) + c_p


def brute_variant_count(links: int, joints, count: int, *, idle: bool = False, frames: bool = False) -> int:
    """Classes of ``count``-subsets of the (simple) joints under every link permutation keeping the joints
    (with ``frames``: of the subsets together with a fixed link, i.e. the mechanisms)."""
    edges = [tuple(sorted(j)) for j in joints]
    edge_set = sorted(edges)
    autos = [p for p in permutations(range(links))
             if sorted(tuple(sorted((p[a], p[b]))) for a, b in edges) == edge_set]
    rng = np.random.default_rng(0)
    classes = set()
    for chosen in combinations(range(len(edges)), count):
        kinds = ["prismatic" if k in chosen else "revolute" for k in range(len(edges))]
        if not idle and has_idle_joint(links, edges, kinds):
            continue
        if count_rule(links, edges, kinds) != generic_mobility(links, edges, kinds, rng):
            continue
        picked = [edges[k] for k in chosen]
        for frame in range(links) if frames else (None,):
            classes.add(min((tuple(sorted(tuple(sorted((p[a], p[b]))) for a, b in picked)),
                             None if frame is None else p[frame]) for p in autos))
    return len(classes)
