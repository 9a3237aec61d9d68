"""Exhaustive sub-chain oracle and random chain generators (test helpers, no engine code).

This module imports nothing from ``synth``: it states the sub-chain rule by its
definition and checks it on *every* subset of links, so it can judge the engine's
fast test (``synth.structure.subchains.check_subchains``), which never looks at most subsets.

Definitions (planar, h = 3)
---------------------------
For a set S of links, ``W(S) = 3(|S| − 1) − 2·Σ_j max(m_j(S) − 1, 0)`` where
``m_j(S)`` is the number of links of S on joint j.  The engine's verdict is about
*proper* sub-chains (``2 ≤ |S| < n``; the whole chain is judged by its own W):
non-degenerate chains need ``W(S) ≥ 1`` for each, chains that allow rigid
sub-chains need ``W(S) ≥ 0``.

Generators
----------
``random_chain(rng, kind)`` builds connected chains of a named family — rigid
triangles, over-constrained sub-chains, multiple joints, closed strings of binary
links through one link, parallel joints between two links, free (single-joint)
links — with W = 0 … 3 where the family allows it, so that both verdicts occur.
"""

from __future__ import annotations

import functools
import random

__all__ = ["SubsetVerdict", "subset_mobility", "exhaustive_subchains", "random_chain", "FAMILIES", "connected"]


def subset_mobility(joints, subset) -> int:
    """W(S) from the definition (plain set arithmetic)."""
    s = set(subset)
    p = 0
    for j in joints:
        on = sum(1 for x in j if x in s)
        if on > 1:
            p += on - 1
    return 3 * (len(s) - 1) - 2 * p


class SubsetVerdict:
    """Least W(S) over proper sub-chains, every smallest set that reaches it, and the verdicts."""

    def __init__(self, links: int, joints):
        self.links = links
        self.joints = [tuple(j) for j in joints]
        masks = [sum(1 << x for x in set(j)) for j in self.joints]
        best, sets, full = None, [], (1 << links) - 1
        for s in range(1, full):  # every proper subset, as a bit mask of links
            size = s.bit_count()
            if size < 2:
                continue
            p = 0
            for m in masks:
                on = (s & m).bit_count()
                if on > 1:
                    p += on - 1
            w = 3 * (size - 1) - 2 * p
            if best is None or w < best or (w == best and size < sets[0].bit_count()):
                best, sets = w, [s]
            elif w == best and size == sets[0].bit_count():
                sets.append(s)
        self.least = best            # None when the chain has no proper sub-chain (n ≤ 2)
        # the smallest sets of least mobility, as sorted tuples of links
        self.smallest_worst = [tuple(x for x in range(links) if s >> x & 1) for s in sets]

    def ok(self, rigid_subchains: bool) -> bool:
        need = 0 if rigid_subchains else 1
        return self.least is None or self.least >= need

    def kind(self, rigid_subchains: bool) -> str:
        if self.ok(rigid_subchains):
            return "none"
        return "rigid sub-chain" if self.least == 0 else "over-constrained sub-chain"


@functools.lru_cache(maxsize=4096)
def _verdict(links: int, joints: tuple) -> SubsetVerdict:
    return SubsetVerdict(links, joints)


def exhaustive_subchains(links: int, joints) -> SubsetVerdict:
    """The verdict of every subset (cached: the same chain is judged under both conventions)."""
    return _verdict(links, tuple(tuple(j) for j in joints))


def connected(links: int, joints) -> bool:
    """Every link reachable from link 0 (own breadth-first search)."""
    adj = {i: set() for i in range(links)}
    for j in joints:
        for a in j:
            adj[a].update(x for x in j if x != a)
    seen, todo = {0}, [0]
    while todo:
        for y in adj[todo.pop()]:
            if y not in seen:
                seen.add(y)
                todo.append(y)
    return len(seen) == links


# ----------------------------------------------------------------------------- generators
def _relabel(links: int, joints, rng: random.Random):
    perm = list(range(links))
    rng.shuffle(perm)
    out = [tuple(perm[x] for x in j) for j in joints]
    rng.shuffle(out)
    return out


def _loop(start: int, body: list[int]) -> list[tuple[int, int]]:
    """Closed string start – body… – start (simple joints)."""
    seq = [start, *body, start]
    return list(zip(seq, seq[1:]))


def _random_graph(rng: random.Random, links: int, p: int, multiple: bool) -> list[tuple[int, ...]]:
    """A connected chain with p simple-joint equivalents, built on a random spanning tree."""
    while True:
        order = list(range(links))
        rng.shuffle(order)
        joints = [tuple(sorted((order[i], order[rng.randrange(i)]))) for i in range(1, links)]
        used = links - 1
        while used < p:
            if multiple and rng.random() < 0.3 and p - used >= 2:
                j = tuple(sorted(rng.sample(range(links), 3)))
            else:
                j = tuple(sorted(rng.sample(range(links), 2)))
            joints.append(j)
            used += len(j) - 1
        if used == p:
            return joints


def _triangle_family(rng):
    # a rigid triangle 0-1-2 inside a larger chain, W = 0 … 3
    links = rng.randint(5, 9)
    tri = [(0, 1), (1, 2), (0, 2)]
    rest = list(range(3, links))
    joints = list(tri)
    prev = rng.choice([0, 1, 2])
    for x in rest:
        joints.append((prev, x))
        prev = x
    joints.append((prev, rng.choice([0, 1, 2])))
    for _ in range(rng.randint(0, 2)):
        a, b = rng.sample(range(links), 2)
        joints.append((a, b))
    return links, joints


def _closed_string_family(rng):
    # closed strings of w binary links through one link: W = w − 2 (w = 2 is a rigid triangle)
    hub = 0
    joints, nxt = [], 1
    for _ in range(rng.randint(1, 3)):
        w = rng.randint(2, 4)
        body = list(range(nxt, nxt + w))
        nxt += w
        joints += _loop(hub, body)
    if rng.random() < 0.5:  # and something else hanging on the hub
        a, b = nxt, nxt + 1
        joints += [(hub, a), (a, b), (b, hub), (a, rng.randrange(1, nxt))]
        nxt += 2
    return nxt, joints


def _parallel_family(rng):
    # two joints between the same two links (W({a, b}) = −1), or a link pair inside a loop
    links = rng.randint(4, 8)
    joints = _loop(0, list(range(1, links)))
    a, b = rng.sample(range(links), 2)
    joints.append((a, b))
    return links, joints


def _counted(rng, lo: int, hi: int, multiple: bool):
    """Random links in lo..hi and W in 0..3 by Grübler's count (an odd count rounded to a whole p)."""
    links = rng.randint(lo, hi)
    twice_p = 3 * (links - 1) - rng.randint(0, 3)
    twice_p += (-1 if multiple else 1) * (twice_p % 2)
    return links, _random_graph(rng, links, twice_p // 2, multiple=multiple)


def _multiple_family(rng):
    # multiple joints (m = 3 or 4) on a random connected base
    links, joints = _counted(rng, 5, 9, multiple=True)
    if rng.random() < 0.3:
        quad = tuple(sorted(rng.sample(range(links), min(4, links))))
        joints[rng.randrange(len(joints))] = quad
    return links, joints


def _counted_family(rng):
    # random chains with W = 0 … 3 by Grübler's count, simple joints
    return _counted(rng, 4, 10, multiple=False)


def _free_links_family(rng):
    # a loop with single-joint links hanging from it (open chains)
    links, joints = _counted_family(rng)
    for _ in range(rng.randint(1, 2)):
        joints.append((rng.randrange(links), links))
        links += 1
    return links, joints


def _overconstrained_family(rng):
    # a dense cluster (W(S) < 0) in a chain: K4 on 4 links, or a triangle with a double joint
    links = rng.randint(6, 10)
    cluster = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] if rng.random() < 0.5 else [(0, 1), (1, 2), (0, 2), (0, 1, 3)]
    joints = list(cluster)
    prev = 3
    for x in range(4, links):
        joints.append((prev, x))
        prev = x
    joints.append((prev, rng.randrange(3)))
    return links, joints


def _two_defects_family(rng):
    # a rigid triangle and a rigid five-link truss (two links joined by three one-link strings)
    # in one chain: equal W(S) = 0, sizes 3 and 5, so only the smallest may be named
    tri = [(0, 1), (1, 2), (0, 2)]
    truss = [(3, 5), (5, 4), (3, 6), (6, 4), (3, 7), (7, 4)]
    joints, nxt = tri + truss, 8
    for a, b in ((0, 3), (1, 4), (2, rng.choice([3, 4]))):
        body = [nxt]
        nxt += len(body)
        seq = [a, *body, b]
        joints += list(zip(seq, seq[1:]))
    return nxt, joints


def _dense_family(rng):
    # links of three or more joints only, then a few strings of one binary link between them:
    # the worst sub-chain is often all of the chain but one binary link
    links = rng.randint(4, 8)
    pairs = [(a, b) for a in range(links) for b in range(a + 1, links)]
    joints = rng.sample(pairs, rng.randint(links, min(len(pairs), 2 * links)))
    nxt = links
    for _ in range(rng.randint(0, 4)):
        a, b = rng.sample(range(links), 2)
        joints += [(a, nxt), (nxt, b)]
        nxt += 1
    return nxt, joints


FAMILIES = {
    "dense": _dense_family,
    "two-defects": _two_defects_family,
    "triangle": _triangle_family,
    "closed-string": _closed_string_family,
    "parallel-joints": _parallel_family,
    "multiple-joints": _multiple_family,
    "counted": _counted_family,
    "free-links": _free_links_family,
    "over-constrained": _overconstrained_family,
}


def random_chain(rng: random.Random, family: str) -> tuple[int, list[tuple[int, ...]]]:
    """(links, joints) of a random connected chain of ``family``, randomly relabelled."""
    while True:
        links, joints = FAMILIES[family](rng)
        joints = [tuple(sorted(set(j))) for j in joints]
        joints = [j for j in joints if len(j) >= 2]
        if connected(links, joints):
            return links, _relabel(links, joints, rng)
