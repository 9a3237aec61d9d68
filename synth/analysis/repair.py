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
>>> len(r["edits"]), r["code"]
(1, '42/0')
"""

from __future__ import annotations

from itertools import combinations

from ..structure.chain import Chain
from ..structure.code import Code
from ..errors import InvalidOption
from ..structure.subchains import check_subchains

__all__ = ["chain_edits", "chain_repairs", "code_repairs"]

_DEPTH = 3


def _valid(chain: Chain, dof: int) -> bool:
    return (chain.is_connected() and chain.dof == dof
            and check_subchains(chain, rigid_subchains=dof == 0).ok)


def chain_edits(chain: Chain):
    """Every chain one elementary edit away, with the edit said in words.

    >>> sum(1 for _ in chain_edits(Chain.parse("0-1 1-2 2-0")))
    6
    """
    n, joints = chain.links, list(chain.joints)
    for a, b in combinations(range(n), 2):
        yield f"add a binary link {n} jointed to links {a} and {b}", Chain(n + 1, joints + [(a, n), (b, n)])
    for x in range(n):
        on = [j for j in joints if x in j]
        if len(on) == 2 and all(len(j) == 2 for j in on) and n > 3:
            rest = [j for j in joints if x not in j]
            keep = [y for y in range(n) if y != x]
            rename = {y: i for i, y in enumerate(keep)}
            yield (f"remove the binary link {x} with its joints {'-'.join(map(str, on[0]))} and "
                   f"{'-'.join(map(str, on[1]))}", Chain(n - 1, [tuple(rename[y] for y in j) for j in rest]))
    present = set(joints)
    for k, j in enumerate(joints):
        for end in j:
            for c in range(n):
                if c in j:
                    continue
                moved = tuple(sorted([y for y in j if y != end] + [c]))
                if moved in present:
                    continue
                yield (f"move joint {'-'.join(map(str, j))} from link {end} to link {c}",
                       Chain(n, joints[:k] + [moved] + joints[k + 1:]))
    for (k, p), (m, q) in combinations(enumerate(joints), 2):
        if len(p) == 2 and len(q) == 2 and len(set(p) & set(q)) == 1:
            merged = tuple(sorted(set(p) | set(q)))
            rest = [j for i, j in enumerate(joints) if i not in (k, m)]
            yield (f"merge joints {'-'.join(map(str, p))} and {'-'.join(map(str, q))} into the double joint "
                   f"{'-'.join(map(str, merged))}", Chain(n, rest + [merged]))
    for k, j in enumerate(joints):
        if len(j) > 2:
            for x in j:
                rest = [y for y in j if y != x]
                split = [tuple(rest), (x, rest[0])]
                yield (f"split joint {'-'.join(map(str, j))} into {'-'.join(map(str, split[0]))} and "
                       f"{'-'.join(map(str, split[1]))}", Chain(n, joints[:k] + split + joints[k + 1:]))


def chain_repairs(chain: Chain, *, dof: int | None = None, limit: int = 5, depth: int = _DEPTH) -> list[dict]:
    """The nearest valid chains (intended W: ``dof`` or the chain's own), fewest edits first.

    Each item: ``edits`` (words), ``code``, ``chain`` (the compact joint list ``analyze`` reads).
    A chain that is valid already needs no repair: the list is empty.
    """
    if limit < 1:
        raise InvalidOption(f"the number of repairs must be ≥ 1, not {limit}")
    target = chain.dof if dof is None else dof
    if _valid(chain, target):
        return []
    found: list[dict] = []
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
                    found.append({"edits": path, "code": str(candidate.code), "chain": candidate.compact(),
                                  "dof": candidate.dof})
                else:
                    nxt.append((candidate, path))
        if found:
            return found[:limit]
        level = nxt
    return found[:limit]


def _code_edits(code: Code):
    """Codes one edit away: a binary link added or removed, a joint end moved, joints merged or split.

    Each edit changes the degrees of the links it touches: a link with i joints that gains one
    becomes a link with i + 1 joints.
    """
    counts = {i: code.count(i) for i in range(2, code.max_degree + 2)}
    degrees = [i for i in counts if counts[i]]

    def make(changes, dv=0):
        c = dict(counts)
        for i, d in changes:
            c[i] = c.get(i, 0) + d
        if any(x < 0 for x in c.values()) or code.v + dv < 0:
            return None
        top = max((i for i, k in c.items() if k), default=2)
        return Code(tuple(c.get(i, 0) for i in range(2, top + 1)), code.v + dv)

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
        if code.v > 0:
            yield f"split a multiple joint on a link with {i} joints", make(gain(i), -1)


def code_repairs(code: Code, dof: int, *, limit: int = 5, depth: int = _DEPTH) -> list[dict]:
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
                        found.append({"edits": path, "code": text, "chain": chain.compact()})
                        continue
                nxt.append((candidate, path))
        if found:
            return found[:limit]
        level = nxt
    return found[:limit]
