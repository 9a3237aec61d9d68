"""Directed repair (docs/theory.md, "Directed repair"): the nearest valid structures, fewest edits first.

Elementary edits of a chain: add a binary link with its two joints, remove a binary link with
its joints, move one end of a joint to another link, merge two simple joints on a common link
into a double joint, or split a multiple joint.  A repair is kept when the rebuilt chain is
connected, has the intended W and passes the exact sub-chain test.  A code is repaired by the
same edits on its counts, and each proposed code is verified by building one of its chains.

Example
-------
>>> from synth.structure.chain import Chain
>>> r = chain_repairs(Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-1"), limit=1)[0]
>>> len(r.edits), r.code, list(r.to_dict())
(1, '42/0', ['edits', 'code', 'chain', 'dof'])
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations
from math import comb

from mechbase import Row

from ..structure.chain import Chain
from ..structure.joints import MESH, REVOLUTE, JointKind
from ..structure.code import Code
from ..errors import InvalidOption, MalformedChain
from ..structure.subchains import check_subchains

__all__ = ["Repair", "ChainRepair", "chain_edits", "chain_repairs", "code_repairs", "redundant_joints"]

_DEPTH = 3
_WORK = 1 << 28  # sets of links the search for redundant joints may scan


def _valid(chain: Chain, dof: int) -> bool:
    return (chain.is_connected() and chain.dof == dof
            and check_subchains(chain, rigid_subchains=dof == 0).ok)


def _text(joint, kind: JointKind = REVOLUTE) -> str:
    return kind.symbol.join(map(str, joint))


def chain_edits(chain: Chain):
    """Every chain one elementary edit away, with the edit said in words.

    Joints keep their kinds (a gear mesh or a prismatic pair moved is still one); the joints an
    edit adds are revolute, and only revolute joints merge into a multiple joint.  A chain with
    gear meshes has two more edits: remove a mesh (W + 1) and mesh two links (W − 1).

    >>> sum(1 for _ in chain_edits(Chain.parse("0-1 1-2 2-0")))
    6
    >>> [w for w, c in chain_edits(Chain.parse("0-1 1-2 2-0 0~3 1-3")) if "mesh" in w][:2]
    ['move mesh 0~3 from link 0 to link 2', 'remove the gear mesh 0~3']
    """
    for words, edited in _edits(chain):
        if edited is not None:
            yield words, edited


def _edits(chain: Chain):
    """:func:`chain_edits`, with None for an edit whose result is no chain."""
    n = chain.links
    pairs = list(zip(chain.joints, chain.kinds))

    def build(links, items):
        try:
            return Chain(links, [j for j, _ in items], [k for _, k in items])
        except MalformedChain:  # a mesh would join two links a joint already joins
            return None

    for a, b in combinations(range(n), 2):
        yield (f"add a binary link {n} jointed to links {a} and {b}",
               build(n + 1, pairs + [((a, n), REVOLUTE), ((b, n), REVOLUTE)]))
    for x in range(n):
        on = [(j, k) for j, k in pairs if x in j]
        if len(on) == 2 and all(len(j) == 2 for j, _ in on) and n > 3:
            keep = [y for y in range(n) if y != x]
            rename = {y: i for i, y in enumerate(keep)}
            rest = [(tuple(rename[y] for y in j), k) for j, k in pairs if x not in j]
            yield (f"remove the binary link {x} with its joints {_text(*on[0])} and {_text(*on[1])}",
                   build(n - 1, rest))
    present = {frozenset(j) for j, _ in pairs}
    for i, (j, kind) in enumerate(pairs):
        for end in j:
            for c in range(n):
                if c in j:
                    continue
                moved = tuple(sorted([y for y in j if y != end] + [c]))
                if frozenset(moved) in present:
                    continue
                yield (f"move {kind.noun} {_text(j, kind)} from link {end} to link {c}",
                       build(n, pairs[:i] + [(moved, kind)] + pairs[i + 1:]))
        if kind == MESH:
            yield f"remove the gear mesh {_text(j, kind)}", build(n, pairs[:i] + pairs[i + 1:])
    if any(k == MESH for _, k in pairs):
        joined = {frozenset(q) for j, _ in pairs for q in combinations(j, 2)}
        for a, b in combinations(range(n), 2):
            if frozenset((a, b)) not in joined:
                yield f"mesh links {a} and {b} (gear mesh {a}~{b})", build(n, pairs + [((a, b), MESH)])
    for (i, (p, kp)), (m, (q, kq)) in combinations(enumerate(pairs), 2):
        if kp == kq == REVOLUTE and len(p) == 2 and len(q) == 2 and len(set(p) & set(q)) == 1:
            merged = tuple(sorted(set(p) | set(q)))
            rest = [jk for k, jk in enumerate(pairs) if k not in (i, m)]
            yield (f"merge joints {_text(p)} and {_text(q)} into the double joint {_text(merged)}",
                   build(n, rest + [(merged, REVOLUTE)]))
    for i, (j, kind) in enumerate(pairs):
        if len(j) > 2:
            for x in j:
                rest = [y for y in j if y != x]
                split = [(tuple(rest), REVOLUTE), ((x, rest[0]), REVOLUTE)]
                yield (f"split joint {_text(j)} into {_text(split[0][0])} and {_text(split[1][0])}",
                       build(n, pairs[:i] + split + pairs[i + 1:]))


@dataclass(frozen=True)
class Repair(Row):
    """A repair of a code: the ``edits`` (words), the ``code`` they lead to and one ``chain`` of it
    (the compact joint list ``analyze`` reads)."""

    edits: tuple[str, ...]
    code: str
    chain: str


@dataclass(frozen=True)
class ChainRepair(Repair):
    """A repair of a chain: the rebuilt chain and its ``dof``."""

    dof: int


def chain_repairs(chain: Chain, *, dof: int | None = None, limit: int = 5, depth: int = _DEPTH) -> list[ChainRepair]:
    """The nearest valid chains (intended W: ``dof`` or the chain's own), fewest edits first.

    A chain that is valid already needs no repair: the list is empty.
    """
    if limit < 1:
        raise InvalidOption(f"the number of repairs must be ≥ 1, not {limit}")
    target = chain.dof if dof is None else dof
    if _valid(chain, target):
        return []
    found: list[ChainRepair] = []
    seen = {chain.certificate}
    level = [(chain, [])]
    for _ in range(depth):
        nxt = []
        for current, edits in level:
            for words, candidate in chain_edits(current):
                if candidate.certificate in seen:
                    continue
                seen.add(candidate.certificate)
                path = edits + [words]
                if _valid(candidate, target):
                    found.append(ChainRepair(tuple(path), str(candidate.code) + candidate.kind_suffix,
                                             candidate.compact(), candidate.dof))
                else:
                    nxt.append((candidate, path))
        if found:
            return found[:limit]
        level = nxt
    return found[:limit]


def redundant_joints(chain: Chain, dof: int, *, most: int = 3) -> list[tuple[int, ...]] | None:
    """The joints that carry the chain's redundant constraints: those in some set of joints whose
    removal leaves a connected chain with W = ``dof`` by the count and no rigid or over-constrained
    sub-chain.  Sets of up to D joints are tried (D = ``dof`` − W, at most ``most``); None when the
    chain has no redundant constraint by the count (W ≥ ``dof``), D is larger, or the tries would
    scan more than 2^28 sets of links (a try counted as 2^min(n, 22): the sub-chain test of a
    larger chain scans the sets of its core, whose binary links it contracts).

    A planetary train with four planets and a floating sun has W = 0: each planet beyond the
    third is redundant, and any one of its meshes can go.

    >>> four = Chain.parse("0-1 1-3 1-4 1-5 1-6 0~3 0~4 0~5 0~6 2~3 2~4 2~5 2~6")
    >>> [Chain(7, [j], ["mesh"]).compact() for j in redundant_joints(four, 1)][:4]
    ['0~3', '0~4', '0~5', '0~6']
    """
    missing = dof - chain.dof
    if missing <= 0 or missing > most:
        return None
    pairs = list(zip(chain.joints, chain.kinds))
    tries = sum(comb(len(pairs), size) for size in range(1, missing + 1))
    if tries << min(chain.links, 22) > _WORK:  # each try scans every set of links
        return None
    found: set[int] = set()
    for size in range(1, missing + 1):
        for removed in combinations(range(len(pairs)), size):
            kept = [jk for k, jk in enumerate(pairs) if k not in removed]
            candidate = Chain(chain.links, [j for j, _ in kept], [k for _, k in kept])
            if candidate.dof == dof and _valid(candidate, dof):
                found.update(removed)
        if found:
            break
    return [pairs[k][0] for k in sorted(found)]


def _code_edits(code: Code):
    """Codes one edit away: a binary link added or removed, a joint end moved, joints merged or split
    (an open chain's single-joint links stay as they are).

    Each edit changes the degrees of the links it touches: a link with i joints that gains one
    becomes a link with i + 1 joints (at most one more than the code's largest degree, which
    ``counts`` already holds, as it holds every degree a lost joint leaves).
    """
    counts = {i: code.count(i) for i in range(2, code.max_degree + 2)}
    degrees = [i for i in counts if counts[i]]

    def make(changes, dv=0):
        c = dict(counts)
        for i, d in changes:
            c[i] += d
        if any(x < 0 for x in c.values()) or code.v + dv < 0:
            return None
        top = max(i for i, k in c.items() if k)  # (an edit leaves at least one link)
        return Code(tuple(c[i] for i in range(2, top + 1)), code.v + dv, n1=code.n1)  # free ends kept

    def gain(i):
        return [(i, -1), (i + 1, +1)]

    def lose(i):
        return [(i, -1), (i - 1, +1)]

    pairs = [(i, k) for i in degrees for k in degrees if i <= k]
    for i, k in pairs:
        yield f"add a binary link jointed to links with {i} and {k} joints", make([(2, 1)] + gain(i) + gain(k))
        if i > 2:
            yield (f"remove a binary link jointed to links with {i} and {k} joints",
                   make([(2, -1)] + lose(i) + lose(k)))
    for i in degrees:
        for k in degrees:
            if i > 2:
                yield f"move a joint from a link with {i} joints to one with {k}", make(lose(i) + gain(k))
        if i > 2:
            yield f"merge two joints of a link with {i} joints into a double joint", make(lose(i), +1)
        yield f"split a multiple joint on a link with {i} joints", make(gain(i), -1)  # (None without one)


def code_repairs(code: Code, dof: int, *, limit: int = 5, depth: int = _DEPTH) -> list[Repair]:
    """The nearest standard codes with W = ``dof``, fewest edits first, each verified by one chain
    (empty when ``code`` itself has W = ``dof`` and a valid chain)."""
    from ..synthesis.type_synthesis import type_synthesis

    if limit < 1:
        raise InvalidOption(f"the number of repairs must be ≥ 1, not {limit}")
    if code.dof() == dof and next(iter(type_synthesis(dof, code=str(code), workers=1)), None) is not None:
        return []

    found, seen, level = [], {str(code)}, [(code, [])]
    for _ in range(depth):
        nxt = []
        for current, edits in level:
            for words, candidate in _code_edits(current):
                if candidate is None:
                    continue
                text = str(candidate)
                if text in seen:
                    continue
                seen.add(text)
                path = edits + [words]
                if candidate.dof() == dof:
                    chain = next(iter(type_synthesis(dof, code=text, workers=1)), None)
                    if chain is not None:
                        found.append(Repair(tuple(path), text, chain.compact()))
                        continue
                nxt.append((candidate, path))
        if found:
            return found[:limit]
        level = nxt
    return found[:limit]
