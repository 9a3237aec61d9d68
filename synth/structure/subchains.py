"""Exact sub-chain mobility test: no rigid or over-constrained sub-chain anywhere.

For a set S of links in motion space h (3 planar, see :class:`~synth.structure.chain.Chain`),
W(S) = h(|S| − 1) − (h − 1)·Σ_j max(m_j(S) − 1, 0).  The test is exact over *every*
subset of links, computed without enumerating all 2^n sets:

* a *core* link carries 1 or 3+ joints or lies on a multiple joint; the other links
  are binary links on two simple joints and form paths between core links (a path may
  close on one core link);
* for a fixed set T of core links, adding a path of w binary links whose ends are
  both in T changes W by w − (h − 1), adding part of a path by +1 or more; so the
  smallest W(S) with core part T takes exactly the paths with w < h − 1 (planar: the
  single-link paths);
* so min over S is a vectorised scan over the 2^c subsets T of the c core links,
  with a separate look at one closed path alone on its core link (planar: w = 2 is a
  rigid triangle).  Complexity O(2^c · J) with c ≤ n − n2.

Example
-------
>>> from synth.structure.chain import Chain
>>> check_subchains(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")).ok       # Watt chain
True
>>> r = check_subchains(Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-2 4-1"))  # triangle 0-1-2 inside
>>> r.ok, r.worst
(False, (0, 1, 2))
"""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ._blas import single_threaded
from .chain import Chain
from .joints import JOINT_KINDS, PRISMATIC
from .kinds import cycle_rank, generic_mobility, lever_analogue, restricted_pairs, structural_mobility
from ..errors import MalformedChain

__all__ = ["MAX_CORE", "SubchainReport", "check_subchains", "subchain_mobility", "least_base_mobilities", "passing",
           "sets_to_check"]

MAX_CORE = 24  # non-binary links the exact test handles (2^24 subsets of the core)
_MAX_SCANNED = 22  # links of a chain with prismatic pairs: every subset is scanned (4 M sets)
_BLOCK = 1 << 16  # subsets T of the core links scanned at once (a block of W is candidates × _BLOCK)
_BIG = 1 << 20  # stands for "no proper sub-chain of two links or more"
_CANDIDATE_SUBSETS = 1 << 22  # candidates × subsets in one block of the batched test (16 MiB an array)
# OpenBLAS threads a matrix-vector product from 2304·4 = 9216 multiply-adds on and a matrix product
# from 65536·4 = 262144: the exact test's products below those run on the calling thread, with no
# limit to set
_THREADED_GEMV, _THREADED_GEMM = 9216, 262144


def _subset_bits(c: int, start: int) -> tuple[np.ndarray, np.ndarray]:
    """Subsets start … start + _BLOCK − 1 of c core links (bit masks): row t, column i is 1 if
    subset start + t holds core link i (float32: exact, and a BLAS product), and the sizes.

    >>> bits, size = _subset_bits(2, 0); bits.tolist(), size.tolist()
    ([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [0, 1, 1, 2])
    """
    T = np.arange(start, min(1 << c, start + _BLOCK), dtype=np.int64)
    bits = ((T[:, None] >> np.arange(c)) & 1).astype(np.float32)
    return bits, bits.sum(axis=1).astype(np.int64)


@lru_cache(maxsize=None)
def _first_block(c: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_subset_bits` from subset 0, shared and read-only: every scan of up to 16 core links
    is this one block (at most 4 MiB)."""
    bits, size = _subset_bits(c, 0)
    bits.flags.writeable = size.flags.writeable = False
    return bits, size


def _block(c: int, start: int) -> tuple[np.ndarray, np.ndarray]:
    return _first_block(c) if start == 0 and c <= 16 else _subset_bits(c, start)


def _scan(h: int, is_link, groups: list[list[int]], ends: np.ndarray, lengths: np.ndarray, neutral: bool = False):
    """Least mobilities over the sub-chains of many chains that share their core and paths,
    block by block of the subsets T of the core.

    The core is a list of vertices, each a link (``is_link``: h freedoms) or a multiple joint
    standing as a vertex of its own (h − 1 freedoms: a joint J of S with m of its links removes
    (h − 1)(m − 1), as a vertex joined to each of them by a simple joint; taking J without its
    links only raises W, so the least W over S and T is the same); ``groups``: the joints whose
    links are all core links (core indices), each removing (h − 1)·(m − 1) freedoms from a set
    holding m of its links; ``ends`` (P × 2): the core ends of the paths of binary links (equal
    for a path closed on one vertex, −1 for a path with a free end, never inside T);
    ``lengths`` (N × P): each chain's binary links on each path (0: a simple joint between the
    ends).  For a set T the least W(S) over the sub-chains with core part T takes the paths
    inside T with w < h − 1 (each lowers W by h − 1 − w and brings w links) and no other; with
    ``neutral`` also those with w = h − 1, which bring links and leave W as it is (a set of joint
    vertices may need them to hold two links).  When T holds every link and every path with
    links is inside and taken, S_T is the whole chain and the best proper sub-chain leaves out
    the longest of them.

    Yields ``(start, W, X)``: W[i, t] that least mobility for chain i and subset start + t,
    X[i, t] its number of links (below 2 where T gives no proper sub-chain of two links or more).
    """
    c = len(is_link)
    closed = ends[:, 0] == ends[:, 1]
    short = ((lengths < h - 1) | (neutral & (lengths == h - 1))) & (ends[:, 0] >= 0)
    cost = np.where(short, h - 1 - lengths, 0).astype(np.float32)  # N × P
    taken = np.where(short, lengths, 0).astype(np.float32)
    binary = lengths >= 1
    binary_short = (binary & short).astype(np.float32)
    n_binary = binary.sum(axis=1)
    longest = np.where(binary & short, lengths, 0).max(axis=1, initial=0)
    M = np.zeros((c, len(groups) + len(ends)), dtype=np.float32)
    for k, group in enumerate(groups):
        M[group, k] = 1
    on_core = np.flatnonzero(ends[:, 0] >= 0)
    M[ends[on_core, 0], len(groups) + on_core] = 1
    M[ends[on_core, 1], len(groups) + on_core] = 1
    need = np.where(closed, 1, 2).astype(np.float32)
    links = np.asarray(is_link, dtype=np.float32)
    weight = np.where(links > 0, h, h - 1).astype(np.float32)
    for start in range(0, 1 << c, _BLOCK):
        bits, _ = _block(c, start)
        size = bits @ links
        counts = bits @ M  # links of T on each joint and at the ends of each path
        lost = (h - 1) * np.maximum(counts[:, :len(groups)] - 1, 0).sum(axis=1)
        inside = (counts[:, len(groups):] == need).astype(np.float32)
        W = (bits @ weight - h - lost)[None, :] - cost @ inside.T
        X = size[None, :] + taken @ inside.T
        every = np.flatnonzero(size == links.sum())  # T holds every link
        if len(every):
            whole = (binary_short @ inside[every].T) == n_binary[:, None]  # S_T is the whole chain
            cut = whole & (longest >= 1)[:, None]  # leave the longest short path out
            W[:, every] += np.where(cut, (h - 1 - longest)[:, None], 0)
            X[:, every] = np.where(whole, np.where(cut, X[:, every] - longest[:, None], 0), X[:, every])
        yield start, W, X


def least_mobilities(h: int, is_link, groups: list[list[int]], ends, lengths) -> np.ndarray:
    """The least W(S) over the proper sub-chains (|S| ≥ 2) of each of many chains that share
    their core (see :func:`_scan` for the arguments), a path closed on one core vertex alone
    included (W = w − (h − 1) on a link, w − h on a joint); ``_BIG`` where a chain has no such
    sub-chain.  The exact sub-chain test of a whole batch of candidates in one pass, as
    :func:`check_subchains` is of one chain.

    >>> least_mobilities(3, [True] * 2, [], [[0, 1], [0, 1], [0, 1]], [[1, 1, 1], [0, 1, 2]]).tolist()  # Watt / a triangle
    [1, 0]
    >>> least_mobilities(3, [True] * 3, [[0, 1, 2]], [], [[]]).tolist()  # three links on one joint: W(pair) = 1
    [1]
    >>> joint = [[0, 3], [1, 3], [2, 3], [0, 1]]  # links 0, 1, 2 on a multiple joint (vertex 3), a path 0–1
    >>> least_mobilities(3, [True, True, True, False], [], joint, [[0, 0, 0, 2], [0, 0, 0, 1]]).tolist()
    [1, 0]
    >>> least_mobilities(3, [False, False], [], [[0, 1], [0, 1], [0, 1]], [[1, 2, 3]]).tolist()  # 60/2: links 0+1+2 rigid
    [0]
    """
    is_link = np.asarray(is_link, dtype=bool)
    ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
    lengths = np.asarray(lengths, dtype=np.int64)  # candidates × paths
    c, paths = len(is_link), len(groups) + len(ends)
    rows = min(1 << c, _BLOCK)
    chunk = max(1, _CANDIDATE_SUBSETS // rows)
    if len(lengths) > chunk:  # a block of W and X is candidates × subsets: bounded memory
        return np.concatenate([least_mobilities(h, is_link, groups, ends, lengths[i:i + chunk])
                               for i in range(0, len(lengths), chunk)])
    low = np.full(len(lengths), _BIG, dtype=np.int64)
    # subsets × core links (@ a vector), × paths; candidates × paths × subsets (a vector if one)
    vector = rows * max(c, len(ends) if len(lengths) == 1 else 0)
    matrix = rows * max(c * paths, len(lengths) * len(ends) if len(lengths) > 1 else 0)
    with single_threaded() if vector >= _THREADED_GEMV or matrix >= _THREADED_GEMM else nullcontext():
        for _, W, X in _scan(h, is_link, groups, ends, lengths, neutral=not is_link.all()):
            low = np.minimum(low, np.where(X >= 2, W, _BIG).min(axis=1).astype(np.int64))
    loops = (ends[:, 0] == ends[:, 1]) & (ends[:, 0] >= 0)
    on_link = np.zeros(len(ends), dtype=bool)
    on_link[loops] = is_link[ends[loops, 0]]
    alone = np.where(loops & (lengths + on_link >= 2), lengths - (h - 1) - (~on_link), _BIG)
    # two links on one joint: W = h − (h − 1) = 1, a proper sub-chain of every chain of 3 links or more
    # (the scan takes whole strings only, so it does not see a link with one of its neighbours)
    pair = np.where(is_link.sum() + lengths.sum(axis=1) >= 3, 1, _BIG)
    return np.minimum(np.minimum(low, alone.min(axis=1, initial=_BIG)), pair)


def passing(h: int, is_link, ends, lengths, threshold: int) -> np.ndarray:
    """``least_mobilities(h, is_link, [], ends, lengths) >= threshold``, compiled and stopping at the
    first set that refuses a candidate: for large batches where most candidates fail (stage B's
    kernel placements with multiple joints), where the scan computes every set for every candidate.

    Only the sets T of the core that can give a sub-chain below ``threshold`` for some candidate of
    the batch are looked at (:mod:`synth.structure.subchain_kernel`).  Loads numba (about a second
    the first time in a process).

    >>> joint = [[0, 3], [1, 3], [2, 3], [0, 1]]  # links 0, 1, 2 on a multiple joint (vertex 3), a path 0–1
    >>> passing(3, [True, True, True, False], joint, [[0, 0, 0, 2], [0, 0, 0, 1]], 1).tolist()
    [True, False]
    """
    from .subchain_kernel import passes

    ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
    lengths = np.ascontiguousarray(np.asarray(lengths, dtype=np.int64).reshape(-1, len(ends)))
    return passes(h, np.asarray(is_link, dtype=np.bool_), np.ascontiguousarray(ends[:, 0]),
                  np.ascontiguousarray(ends[:, 1]), lengths, threshold, np.zeros(len(lengths), dtype=np.bool_))


def sets_to_check(h: int, is_link, ends, least, threshold: int, position) -> tuple:
    """The sets T of the core that :func:`passing` may refuse a candidate by and that hold a
    multiple joint (not every core link), for a search that places the paths one at a time in the
    order ``position`` (path p is placed ``position[p]``-th) and checks each set once its paths are
    all placed: (bucket, base, size, start, inside), the sets completed by the path placed e-th being
    ``bucket[e]`` … ``bucket[e + 1] − 1``, set t with Σ freedoms − h ``base[t]``, ``size[t]`` links
    and its paths at the positions ``inside[start[t]:start[t + 1]]``.  ``least[p]``: the fewest
    binary links path p takes (a set that no weights from those can refuse is left out).  Stage B's
    kernel checks them as it places the strings (:func:`synth.synthesis._stage_b_kernel.place`).

    >>> joint = [[0, 3], [1, 3], [2, 3], [0, 1]]  # links 0, 1, 2 on a multiple joint (vertex 3), a path 0–1
    >>> bucket, base, size, start, inside = sets_to_check(3, [True, True, True, False], joint, [0, 0, 0, 0], 1,
    ...                                                   [0, 1, 2, 3])
    >>> bucket.tolist()   # {0, J}, {1, J}, {2, J} complete with their one path, {0, 1, J} with path 0–1
    [0, 1, 2, 3, 4]
    >>> base.tolist(), size.tolist(), inside[start[3]:start[4]].tolist()   # {0, 1, 2, J} holds every link
    ([2, 2, 2, 5], [1, 1, 1, 2], [0, 1, 3])
    """
    from .subchain_kernel import partial_sets

    ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
    return partial_sets(
        h, np.asarray(is_link, dtype=np.bool_), np.ascontiguousarray(ends[:, 0]), np.ascontiguousarray(ends[:, 1]),
        np.asarray(least, dtype=np.int64), threshold, np.asarray(position, dtype=np.int64))


def subchain_mobility(chain: Chain, links) -> int:
    """W(S) of the sub-chain made of ``links`` by the count, in the chain's motion space (with
    joint kinds: its own wedge loops and meshes, :func:`~synth.structure.kinds.structural_mobility`).

    >>> subchain_mobility(Chain.parse("0-1 1-2 2-0 2-3"), [0, 1, 2])
    0
    >>> subchain_mobility(Chain.parse("0=1 1=2 2=0 2-3 3-4 4-0"), [0, 1, 2])   # Task 3's wedge
    1
    """
    return structural_mobility(chain, links)


@dataclass(frozen=True)
class SubchainReport:
    """Result of the sub-chain test.

    ``worst`` is a smallest proper sub-chain (|S| ≥ 2) of least mobility ``worst_mobility``;
    ``ok`` says whether it meets the convention (≥ 1 non-degenerate, ≥ 0 rigid allowed) and the
    chain has no ``redundant`` constraint the count cannot see (with prismatic pairs: its
    generic mobility above the count, or above 0 where the count is negative).  The whole chain
    is not a sub-chain: its W, over-constrained or not, is the count's to say.
    """

    ok: bool
    worst: tuple[int, ...]
    worst_mobility: int
    threshold: int
    redundant: int = 0

    @property
    def kind(self) -> str:
        """'none', 'rigid sub-chain' (W(S) = 0), 'over-constrained sub-chain' (W(S) < 0) or
        'redundant constraints' (every count holds, yet the pairs constrain each other)."""
        if self.ok:
            return "none"
        if self.worst_mobility >= self.threshold:
            return "redundant constraints"
        return "rigid sub-chain" if self.worst_mobility == 0 else "over-constrained sub-chain"


def _paths(chain: Chain, core: list[int]):
    """Binary-link paths between core links: (end a, end b, links on the path), for a connected
    chain with at least one core link (every walk along binary links then ends on one)."""
    is_core = set(core)
    by_link = [[] for _ in range(chain.links)]
    for k, j in enumerate(chain.joints):
        for x in j:
            by_link[x].append(k)
    seen: set[int] = set()
    paths = []
    for start in range(chain.links):
        if start in is_core or start in seen:
            continue
        # walk both ways from a binary link to the core links that end its path
        body = [start]
        seen.add(start)
        ends = []
        for k in by_link[start]:
            prev, cur_joint = start, k
            while True:
                other = next(x for x in chain.joints[cur_joint] if x != prev)
                if other in is_core:
                    ends.append(other)
                    break
                seen.add(other)
                body.append(other)
                cur_joint = next(q for q in by_link[other] if q != cur_joint)
                prev = other
        paths.append((ends[0], ends[1], tuple(sorted(body))))
    return paths


def _cycle_ranks(bits: np.ndarray, pairs: list[tuple[int, int]]) -> np.ndarray:
    """For each subset (a row of ``bits``), the cycle rank of the ``pairs`` with both links in it:
    |E| − |V| + components, by label propagation.

    >>> bits = np.array([[1, 1, 1, 0], [1, 1, 1, 1], [1, 1, 0, 1]])
    >>> _cycle_ranks(bits, [(0, 1), (1, 2), (2, 0), (2, 3)]).tolist()
    [1, 1, 0]
    """
    ends = sorted({x for pair in pairs for x in pair})
    if not ends:
        return np.zeros(len(bits), dtype=np.int64)
    label = np.where(bits[:, ends] > 0, np.arange(len(ends)), -1)
    where = {x: i for i, x in enumerate(ends)}
    inside = [(where[a], where[b], (bits[:, a] & bits[:, b]) > 0) for a, b in pairs]
    for _ in range(len(ends)):
        for a, b, on in inside:
            low = np.where(on, np.minimum(label[:, a], label[:, b]), label[:, a])
            label[:, a] = low
            label[:, b] = np.where(on, low, label[:, b])
    edges = sum(on.astype(np.int64) for _, _, on in inside)
    vertices = (label >= 0).sum(axis=1)
    components = (label == np.arange(len(ends))).sum(axis=1)
    return edges - vertices + components


def _loop_terms(chain: Chain) -> list[tuple[int, list[tuple[int, int]]]]:
    """The loops a count gives back, as (freedoms per loop, the pairs whose loops they are): the
    loops of one kind whose loops live in a smaller motion space x (h − x each: the wedge loops of
    prismatic pairs, +1 in the plane) and, in a heterogeneous chain, the loops of each base
    of class x (+(h − x) each; each joint restricted to the base's links, a pin of m of them m − 1
    pairs)."""
    terms = [(chain.h - kind.loop_space, [j for j, k in zip(chain.joints, chain.kinds) if k is kind])
             for kind in JOINT_KINDS if kind.loop_space is not None and kind in chain.kinds]
    for x in sorted(set(chain.classes or ()) - {chain.h}):
        base = {y for y in range(chain.links) if chain.classes[y] == x}
        terms.append((chain.h - x, [pair for j in chain.joints for pair in restricted_pairs(j, base)]))
    return terms


def _minimum_by_count(chain: Chain) -> tuple[int, tuple[int, ...]]:
    """Least count W(S) (prismatic pairs, meshes and loop classes included) over the proper
    sub-chains of at least two links, and a smallest such S: every subset of links, block by block.

    >>> _minimum_by_count(Chain.parse("0=1 1=2 2=0 2-3 3-4 4-0"))
    (1, (0, 1))
    >>> _minimum_by_count(Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5"))   # the toroid alone
    (1, (0, 1))
    """
    n, h = chain.links, chain.h
    terms = _loop_terms(chain)
    best, best_set = _BIG, ()
    for start in range(0, 1 << n, _BLOCK):
        T = np.arange(start, min(1 << n, start + _BLOCK), dtype=np.int64)
        bits = ((T[:, None] >> np.arange(n)) & 1).astype(np.int64)
        size = bits.sum(axis=1)
        W = h * (size - 1)
        for j, k in zip(chain.joints, chain.kinds):  # h − freedom per pair inside (a pin of m links: m − 1 pairs)
            W -= k.removes(h) * np.maximum(bits[:, list(j)].sum(axis=1) - 1, 0)
        for weight, pairs in terms:
            W += weight * _cycle_ranks(bits, pairs)
        W = np.where((size >= 2) & (size < n), W, _BIG)
        low = int(W.min())
        if low < best or (low == best and low < _BIG):
            ties = np.flatnonzero(W == low)
            t = int(ties[np.argmin(size[ties])])
            if low < best or size[t] < len(best_set):
                best, best_set = low, tuple(int(x) for x in np.flatnonzero(bits[t]))
    return best, best_set


def _check_with_kinds(chain: Chain, threshold: int) -> SubchainReport:
    """The exact test of a planar chain with prismatic pairs or gear meshes: the count over
    every subset, and the rank of the whole chain's velocity constraints for redundancy."""
    if chain.links > _MAX_SCANNED:
        if PRISMATIC not in chain.kinds:  # meshes only: the lever analogue has the same sub-chains
            analogue = check_subchains(lever_analogue(chain), rigid_subchains=threshold == 0)
            worst = tuple(x for x in analogue.worst if x < chain.links)
            return SubchainReport(analogue.ok, worst, analogue.worst_mobility, threshold)
        raise MalformedChain(f"the exact sub-chain test of a chain with prismatic pairs scans every set of links, "
                             f"up to {_MAX_SCANNED} links, not {chain.links}")
    low, worst = _minimum_by_count(chain)
    if low == _BIG:  # two links: no proper sub-chain of two links or more
        low, worst = 10**9, ()
    redundant = _hidden_redundancy(chain) if PRISMATIC in chain.kinds else 0
    return SubchainReport(low >= threshold and redundant == 0, worst, low, threshold, redundant)


def least_base_mobilities(chain: Chain, base_class: int, bases) -> list[int]:
    """The least W(S) over the proper sub-chains (|S| ≥ 2) of a homogeneous revolute chain read
    with each of ``bases`` (sets of links) of class ``base_class``: the exact heterogeneous test of
    many class assignments of one chain.

    A base that is a single loop lowers W(S) by x − h exactly on the sets S that hold all of it,
    so its least W(S) is the least of the chain's own (the homogeneous test, once) and of
    W_h(S) − (x − h) over those supersets (2^(n − |B|) of them); a base of several loops is
    scanned over every subset with its cycle rank in each.

    >>> ring = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3")
    >>> least_base_mobilities(ring, 5, [{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 6}])   # the five-link loop alone: W = 0
    [1, 0]
    """
    n, h = chain.links, chain.h
    bases = [sorted(b) for b in bases]
    if n > _MAX_SCANNED:
        raise MalformedChain(f"the exact sub-chain test of a chain with loop classes scans every set of links, "
                             f"up to {_MAX_SCANNED} links, not {n}")
    drop = base_class - h
    pairs = [[pair for j in chain.joints for pair in restricted_pairs(j, set(b))] for b in bases]
    incidence = np.zeros((n, len(chain.joints)), dtype=np.int64)
    for k, j in enumerate(chain.joints):
        incidence[list(j), k] = 1
    own = check_subchains(chain, rigid_subchains=True).worst_mobility  # the least W_h(S), every proper S
    best = []
    for base, base_pairs in zip(bases, pairs):
        if cycle_rank(base, base_pairs) == 1:  # a single loop: the proper supersets of it, block by block
            rest = [x for x in range(n) if x not in base]
            low = own
            for start in range(0, (1 << len(rest)) - 1, _BLOCK):  # every part of the rest but all of it
                R = np.arange(start, min((1 << len(rest)) - 1, start + _BLOCK), dtype=np.int64)
                bits = np.zeros((len(R), n), dtype=np.int64)
                bits[:, base] = 1
                bits[:, rest] = (R[:, None] >> np.arange(len(rest))) & 1
                size = bits.sum(axis=1)
                W = h * (size - 1) - (h - 1) * np.maximum(bits @ incidence - 1, 0).sum(axis=1) - drop
                low = min(low, int(W.min()))
            best.append(low)
            continue
        low = _BIG
        for start in range(0, 1 << n, _BLOCK):
            T = np.arange(start, min(1 << n, start + _BLOCK), dtype=np.int64)
            bits = (T[:, None] >> np.arange(n)) & 1
            size = bits.sum(axis=1)
            W = h * (size - 1) - (h - 1) * np.maximum(bits @ incidence - 1, 0).sum(axis=1)
            W = np.where((size >= 2) & (size < n), W - drop * _cycle_ranks(bits, base_pairs), _BIG)
            low = min(low, int(W.min()))
        best.append(low)
    return best


def _check_with_classes(chain: Chain, threshold: int) -> SubchainReport:
    """The exact test of a heterogeneous chain: the count with each base's loops in their own
    class, over every subset of links (up to ``_MAX_SCANNED`` links)."""
    if chain.links > _MAX_SCANNED:
        raise MalformedChain(f"the exact sub-chain test of a chain with loop classes scans every set of links, "
                             f"up to {_MAX_SCANNED} links, not {chain.links}")
    low, worst = _minimum_by_count(chain)
    if low == _BIG:  # two links: no proper sub-chain of two links or more
        low, worst = 10**9, ()
    return SubchainReport(low >= threshold, worst, low, threshold)


def _hidden_redundancy(chain: Chain) -> int:
    """Redundant constraints the count does not show, in the chain or any proper sub-chain (whose
    counts are all ≥ 0 here): the generic mobility above the count, or above 0 where the whole
    chain's count is negative (that over-constraint the count shows itself).  A sub-chain's
    redundancy is one of every larger set's, so where the whole's count hides nothing the sets
    of all links but one are looked at.

    >>> _hidden_redundancy(Chain.parse("0-1 0-2 1-2 1=3 2=4 3=4"))   # the P path holds a rigid triangle parallel
    1
    """
    whole = generic_mobility(chain) - max(chain.dof, 0)
    if whole or chain.dof >= 0:
        return whole
    return max(generic_mobility(chain, s) - structural_mobility(chain, s)
               for s in (tuple(x for x in range(chain.links) if x != left) for left in range(chain.links)))


def check_subchains(chain: Chain, *, rigid_subchains: bool = False) -> SubchainReport:
    """Exact test of every proper sub-chain against the convention.

    Parameters
    ----------
    chain : Chain
        A connected chain.
    rigid_subchains : bool
        False (non-degenerate): every proper S with |S| ≥ 2 needs W(S) ≥ 1.
        True (trusses): every S with |S| ≥ 2 needs W(S) ≥ 0.

    Returns
    -------
    SubchainReport

    Raises
    ------
    MalformedChain
        If the chain is not connected, or has more than 24 core links (the scan is exponential
        in them).
    """
    if not chain.is_connected():
        raise MalformedChain("the chain is not connected: every link must be reachable through joints")
    threshold = 0 if rigid_subchains else 1
    if not chain.all_revolute:
        return _check_with_kinds(chain, threshold)
    if chain.classes is not None:
        return _check_with_classes(chain, threshold)
    h = chain.h
    degrees = chain.degrees
    core = sorted({x for j in chain.joints if len(j) > 2 for x in j} | {i for i, d in enumerate(degrees) if d != 2})
    if len(core) > MAX_CORE:
        raise MalformedChain(f"the exact sub-chain test handles up to {MAX_CORE} non-binary links, not {len(core)}")
    # two links on one joint always give W = h − (h − 1) = 1: the least value any larger S must beat
    best = (1, chain.joints[0][:2]) if chain.joints and chain.links > 2 else (10**9, ())
    if not core:  # a single loop of binary links: its proper sub-chains are open paths, W ≥ 1
        return SubchainReport(True, best[1], best[0], threshold)
    paths = _paths(chain, core)
    index = {x: i for i, x in enumerate(core)}
    c = len(core)
    core_set = set(core)
    on_core = [[index[x] for x in j] for j in chain.joints if core_set.issuperset(j)]
    ends = np.array([(index[a], index[b]) for a, b, _ in paths],
                    dtype=np.int64).reshape(-1, 2)
    lengths = np.array([[len(body) for _, _, body in paths]], dtype=np.int64)
    pick, low, least_links = None, best[0], None
    with single_threaded():
        for start, W, X in _scan(h, np.ones(c, dtype=bool), on_core, ends, lengths):
            Wv = np.where(X[0] >= 2, W[0], _BIG)
            t = int(Wv.argmin())
            if Wv[t] < low:  # the first subset of least W, then of fewest links
                ties = np.flatnonzero(Wv == Wv[t])
                t = int(ties[np.argmin(X[0][ties])])
                pick, low, least_links = start + t, int(Wv[t]), X[0][t]
            elif pick is not None and Wv[t] == low:
                ties = np.flatnonzero(Wv == low)
                t = int(ties[np.argmin(X[0][ties])])
                if X[0][t] < least_links:
                    pick, least_links = start + t, X[0][t]
    if pick is not None:
        full = (1 << c) - 1
        short = [(a, b, body) for a, b, body in paths if len(body) < h - 1]
        left_out = max(short, key=lambda path: len(path[2])) if len(short) == len(paths) and short else None
        links = [core[i] for i in range(c) if pick >> i & 1]
        for a, b, body in short:
            if (pick >> index[a] & 1) and (pick >> index[b] & 1) and (pick != full or (a, b, body) != left_out):
                links += body
        best = (low, tuple(sorted(links)))
    for a, b, body in paths:  # one closed path alone on its core link: W = w − (h − 1)
        if a == b and (len(body) - (h - 1), len(body) + 1) < (best[0], len(best[1])):
            best = (len(body) - (h - 1), tuple(sorted((a, *body))))
    return SubchainReport(best[0] >= threshold, best[1], best[0], threshold)
