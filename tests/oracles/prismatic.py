"""Independent answers for prismatic pairs (test helpers, nothing imported from ``synth``).

* ``generic_mobility``: the planar constraint Jacobian at a random configuration, its rank
  giving the generic mobility (what the wedge rule must equal);
* ``count_rule``: the wedge count 3(n − 1) − 2p + c_P, c_P by breadth-first search;
* ``brute_variant_count``: assignments of k prismatic pairs up to the chain's symmetry, by
  trying every permutation of the links (itertools, not nauty), without idle joints and
  without a hidden redundancy (count ≠ Jacobian rank).
"""

from __future__ import annotations

from itertools import combinations, permutations

import numpy as np

__all__ = ["generic_mobility", "brute_variant_count", "has_idle_joint", "count_rule"]


def generic_mobility(links: int, joints, kinds, rng: np.random.Generator, *, trials: int = 2) -> int:
    """3(n − 1) − rank of the velocity constraints at random joint points and slide directions.

    A link's velocity state is (ω, vx, vy) of the point at the origin.  A revolute pair at r
    equates the two links' velocities of r (2 rows); a prismatic pair of direction u equates
    their ω and their velocities across u (2 rows).  The largest rank over a few random
    configurations is the generic rank.
    """
    best = 0
    for _ in range(trials):
        rows = []
        for j, kind in zip(joints, kinds):
            a, b = j
            if kind == "revolute":
                rx, ry = rng.normal(size=2)
                for coeffs in ((-ry, 1.0, 0.0), (rx, 0.0, 1.0)):
                    row = np.zeros(3 * links)
                    row[3 * a: 3 * a + 3] = coeffs
                    row[3 * b: 3 * b + 3] = [-c for c in coeffs]
                    rows.append(row)
            else:
                t = rng.uniform(0, np.pi)
                nx, ny = -np.sin(t), np.cos(t)
                for coeffs in ((1.0, 0.0, 0.0), (0.0, nx, ny)):
                    row = np.zeros(3 * links)
                    row[3 * a: 3 * a + 3] = coeffs
                    row[3 * b: 3 * b + 3] = [-c for c in coeffs]
                    rows.append(row)
        frame = np.zeros((3, 3 * links))
        frame[:, :3] = np.eye(3)
        best = max(best, np.linalg.matrix_rank(np.vstack(rows + [frame])) if rows else 3)
    return 3 * links - best


def has_idle_joint(links: int, joints, kinds) -> bool:
    """A revolute pair whose links are also joined through prismatic pairs (breadth-first search)."""
    adj = {x: set() for x in range(links)}
    for (a, b), k in zip(joints, kinds):
        if k == "prismatic":
            adj[a].add(b)
            adj[b].add(a)
    for (a, b), k in zip(joints, kinds):
        if k != "revolute":
            continue
        seen, todo = {a}, [a]
        while todo:
            x = todo.pop()
            for y in adj[x] - seen:
                seen.add(y)
                todo.append(y)
        if b in seen:
            return True
    return False


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
