"""Prismatic pairs in planar chains: R/P assignments up to symmetry and the wedge rule.

A prismatic (P) pair lets two links slide and fixes their relative rotation, so a loop
made only of P pairs is a wedge loop (motion space h = 2).  For a sub-chain S of a chain
with simple joints (docs/theory.md, "Prismatic pairs and wedge loops"):

    W(S) = 3(|S| − 1) − 2·p(S) + c_P(S)

with c_P(S) the cycle rank of the P pairs inside S (K_2 = c_P, K_3 = K − c_P).  A revolute
pair whose two links are also joined by a path of P pairs cannot turn (an *idle* joint);
such assignments are left out unless asked for.

Example
-------
>>> from synth.structure.chain import Chain
>>> four_bar = Chain.parse("0-1 1-2 2-3 3-0")
>>> [len(prismatic_variants(four_bar, k)) for k in range(5)]     # slider-crank, ..., wedge loop
[1, 1, 2, 0, 1]
>>> v = prismatic_variants(four_bar, 4)[0]
>>> wedge_mobility(v), wedge_loops(v)
(2, 1)
"""

from __future__ import annotations

import random
from itertools import combinations

from ..structure.chain import Chain
from ..errors import InvalidOption
from ..structure.subchains import check_subchains

__all__ = ["prismatic_count", "wedge_loops", "wedge_mobility", "idle_joints", "wedge_subchain_minimum",
           "generic_mobility", "cylinders", "prismatic_variants", "variants_of", "variant_summary", "variant_rows"]

_MAX_BRUTE_LINKS = 16
_PRIME = 2_147_483_647  # 2^31 − 1: products of two residues fit in 64-bit integers


def prismatic_count(chain: Chain) -> int:
    """Number of prismatic pairs of the chain."""
    return 0 if chain.kinds is None else chain.kinds.count("prismatic")


def _prismatic_pairs(chain: Chain) -> list[tuple[int, int]]:
    if chain.kinds is None:
        return []
    return [j for j, k in zip(chain.joints, chain.kinds) if k == "prismatic"]


def _components(nodes, edges) -> dict[int, int]:
    """Union-find root of every node over ``edges``."""
    root = {x: x for x in nodes}

    def find(x):
        while root[x] != x:
            root[x] = root[root[x]]
            x = root[x]
        return x

    for a, b in edges:
        root[find(a)] = find(b)
    return {x: find(x) for x in nodes}


def wedge_loops(chain: Chain, links=None) -> int:
    """c_P(S): independent loops made only of prismatic pairs inside the links ``links`` (all by default).

    >>> wedge_loops(Chain(3, [(0, 1), (1, 2), (2, 0)], ["prismatic"] * 3))
    1
    """
    s = set(range(chain.links) if links is None else links)
    edges = [(a, b) for a, b in _prismatic_pairs(chain) if a in s and b in s]
    roots = set(_components(s, edges).values())
    return len(edges) - len(s) + len(roots)


def wedge_mobility(chain: Chain, links=None) -> int:
    """W(S) = 3(|S| − 1) − 2·p(S) + c_P(S) of the sub-chain ``links`` (the whole chain by default).

    >>> wedge_mobility(Chain.parse("0-1 1-2 2-3 3-0"))
    1
    """
    s = set(range(chain.links) if links is None else links)
    p = sum(max(sum(1 for x in j if x in s) - 1, 0) for j in chain.joints)
    return 3 * (len(s) - 1) - 2 * p + wedge_loops(chain, s)


def idle_joints(chain: Chain) -> list[tuple[int, ...]]:
    """Revolute joints two of whose links are also joined by a path of prismatic pairs (they cannot turn).

    A multiple joint is idle when any two of its links are so joined.

    >>> idle_joints(Chain(4, [(0, 1), (1, 2), (2, 3), (3, 0)], ["prismatic", "prismatic", "prismatic", "revolute"]))
    [(0, 3)]
    """
    roots = _components(range(chain.links), _prismatic_pairs(chain))
    kinds = chain.kinds or ("revolute",) * len(chain.joints)
    return [j for j, k in zip(chain.joints, kinds)
            if k == "revolute" and len({roots[x] for x in j}) < len(j)]


def _rank_mod_prime(rows: list[list[int]]) -> int:
    """Rank of an integer matrix over GF(2^31 − 1) (Gaussian elimination)."""
    m = [list(r) for r in rows]
    rank, cols = 0, len(m[0]) if m else 0
    for c in range(cols):
        pivot = next((i for i in range(rank, len(m)) if m[i][c] % _PRIME), None)
        if pivot is None:
            continue
        m[rank], m[pivot] = m[pivot], m[rank]
        inv = pow(m[rank][c], _PRIME - 2, _PRIME)
        m[rank] = [x * inv % _PRIME for x in m[rank]]
        for i in range(len(m)):
            if i != rank and m[i][c] % _PRIME:
                f = m[i][c]
                m[i] = [(x - f * y) % _PRIME for x, y in zip(m[i], m[rank])]
        rank += 1
    return rank


def generic_mobility(chain: Chain, *, seed: int = 0) -> int:
    """Mobility at a random configuration: 3(n − 1) − rank of the velocity constraints (exact, mod a prime).

    A link's velocity is (ω, vx, vy) at the origin; a revolute pair at (x, y) gives the two rows
    of equal point velocities, a prismatic pair of normal (a, b) equal ω and equal velocity along
    (a, b).  Multiple joints count as revolute pairs between their first link and each other link.

    >>> generic_mobility(Chain.parse("0-1 1-2 2-3 3-0"))
    1
    """
    rng = random.Random(seed)
    n = chain.links
    kinds = chain.kinds or ("revolute",) * len(chain.joints)
    rows = []
    for j, kind in zip(chain.joints, kinds):
        for b in j[1:]:
            a = j[0]
            x, y = rng.randrange(_PRIME), rng.randrange(_PRIME)
            pairs = ((-y, 1, 0), (x, 0, 1)) if kind == "revolute" else ((1, 0, 0), (0, x, y))
            for coeffs in pairs:
                row = [0] * (3 * n)
                row[3 * a: 3 * a + 3] = coeffs
                row[3 * b: 3 * b + 3] = [-c % _PRIME for c in coeffs]
                rows.append(row)
    rows += [[1 if k == i else 0 for k in range(3 * n)] for i in range(3)]  # the frame, link 0
    return 3 * n - _rank_mod_prime(rows)


def wedge_subchain_minimum(chain: Chain) -> tuple[int, tuple[int, ...]]:
    """Least W(S) over the proper sub-chains of at least two links, and a smallest such S (every subset).

    >>> wedge_subchain_minimum(Chain.parse("0-1 1-2 2-0 2-3 3-0"))
    (0, (0, 1, 2))
    """
    n = chain.links
    if n > _MAX_BRUTE_LINKS:
        raise InvalidOption(f"the wedge sub-chain test handles up to {_MAX_BRUTE_LINKS} links, not {n}")
    best = (10**9, ())
    for size in range(2, n):
        for s in combinations(range(n), size):
            w = wedge_mobility(chain, s)
            if w < best[0]:
                best = (w, s)
    return best


def _passes(chain: Chain, base_ok: bool, threshold: int) -> bool:
    """Whether every proper sub-chain has W(S) ≥ threshold.

    P pairs only add c_P(S) ≥ 0 to a sub-chain's count, so a chain whose all-revolute form
    passes needs no further look.
    """
    return base_ok or wedge_subchain_minimum(chain)[0] >= threshold


def prismatic_variants(chain: Chain, count: int, *, idle: bool = False,
                       rigid_subchains: bool | None = None) -> list[Chain]:
    """Every assignment of ``count`` prismatic pairs to the simple joints of ``chain``, up to symmetry.

    Two assignments are the same when an automorphism of the chain maps one onto the other
    (nauty certificates with the joint kinds as colours).  Assignments with idle joints are left
    out unless ``idle``; assignments with a rigid (W(S) = 0, allowed when ``rigid_subchains``,
    the default when the variant's W is 0) or over-constrained sub-chain, or whose generic
    mobility exceeds the count (a hidden redundant constraint), are always left out.

    >>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    >>> len(prismatic_variants(watt, 1)), len(prismatic_variants(watt, 2))
    (3, 8)
    """
    simple = [k for k, j in enumerate(chain.joints) if len(j) == 2]
    if count < 0:
        raise InvalidOption(f"the number of prismatic pairs must be ≥ 0, not {count}")
    if count > 0 and not simple:
        raise InvalidOption("prismatic pairs go on simple joints and this chain has multiple joints only")
    if count > len(simple):
        raise InvalidOption(f"{count} prismatic pairs asked for, but the chain has only {len(simple)} simple joints")
    base = check_subchains(chain, rigid_subchains=True).worst_mobility
    seen: dict[str, Chain | None] = {}  # certificate → variant, None if left out
    for chosen in combinations(simple, count):
        kinds = ["prismatic" if k in chosen else "revolute" for k in range(len(chain.joints))]
        variant = Chain(chain.links, chain.joints, kinds)
        if variant.certificate in seen:
            continue
        allow = wedge_mobility(variant) == 0 if rigid_subchains is None else rigid_subchains
        threshold = 0 if allow else 1
        keep = ((idle or not idle_joints(variant)) and _passes(variant, base >= threshold, threshold)
                and generic_mobility(variant) == wedge_mobility(variant))
        seen[variant.certificate] = variant if keep else None
    return [seen[c] for c in sorted(seen) if seen[c] is not None]


def variants_of(chains, counts: tuple[int, int], *, idle: bool = False,
                rigid_subchains: bool | None = None):
    """Every prismatic variant, with A ≤ P pairs ≤ B for ``counts`` = (A, B), of each chain in turn.

    A chain with fewer simple joints than a count has no variant with that many P pairs.

    >>> [prismatic_count(c) for c in variants_of([Chain.parse("0-1 1-2 2-3 3-0")], (0, 9))]
    [0, 1, 2, 2, 4]
    """
    lo, hi = counts
    for chain in chains:
        simple = sum(1 for j in chain.joints if len(j) == 2)
        for k in range(lo, min(hi, simple) + 1):
            yield from prismatic_variants(chain, k, idle=idle, rigid_subchains=rigid_subchains)


def cylinders(chain: Chain) -> int:
    """Prismatic pairs that join two binary links: each such pair with its two links is a linear
    actuator (cylinder and piston rod, a hydraulic cylinder) pinned at both ends.

    >>> cylinders(Chain(4, [(0, 1), (1, 2), (2, 3), (3, 0)], ["revolute", "prismatic", "revolute", "revolute"]))
    1
    """
    deg = chain.degrees
    return sum(1 for j in _prismatic_pairs(chain) if deg[j[0]] == 2 and deg[j[1]] == 2)


def variant_summary(chain: Chain) -> dict:
    """Row of a chain with joint kinds: code with its P count, W, K_2, K_3, cylinders and the idle joints.

    >>> variant_summary(Chain(3, [(0, 1), (1, 2), (2, 0)], ["prismatic"] * 3))["code"]
    '3/0 P3'
    """
    row = chain.to_dict()
    p = prismatic_count(chain)
    k2 = wedge_loops(chain)
    row.update(prismatic=p, dof=wedge_mobility(chain), loops_2=k2, loops_3=chain.loops - k2,
               cylinders=cylinders(chain), idle_joints=[list(j) for j in idle_joints(chain)])
    return row


def variant_rows(chains, counts: tuple[int, int], *, idle: bool = False, mechanisms: bool = False,
                 input_link: bool = False):
    """Rows (dicts) of the variants of ``chains`` (:func:`variant_summary`), or of their mechanisms.

    >>> [r["frame"] for r in variant_rows([Chain.parse("0-1 1-2 2-3 3-0")], (1, 1), mechanisms=True)]
    [0, 2]
    """
    from .type_synthesis import mechanisms_of

    for chain in variants_of(chains, counts, idle=idle):
        summary = variant_summary(chain)
        if not mechanisms:
            yield summary
            continue
        for m in mechanisms_of(chain, input_link=input_link):
            row = m.to_dict()
            row.update((k, summary[k]) for k in ("code", "dof", "prismatic", "loops_2", "loops_3", "cylinders",
                                                 "idle_joints"))
            yield row
