"""Exact sub-chain mobility test: no rigid or over-constrained sub-chain anywhere.

For a set S of links in motion space h (3 planar, see :class:`~synth.chain.Chain`),
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
>>> from synth.chain import Chain
>>> check_subchains(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")).ok       # Watt chain
True
>>> r = check_subchains(Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-2 4-1"))  # triangle 0-1-2 inside
>>> r.ok, r.worst
(False, (0, 1, 2))
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .chain import Chain
from .errors import MalformedChain

__all__ = ["SubchainReport", "check_subchains", "subchain_mobility"]

_MAX_CORE = 24
_POPCOUNT16 = np.array([bin(i).count("1") for i in range(1 << 16)], dtype=np.int16)


def _popcount(x: np.ndarray) -> np.ndarray:
    return _POPCOUNT16[x & 0xFFFF] + _POPCOUNT16[(x >> 16) & 0xFFFF]


_MATRIX_CORE = 16  # up to this many core links, memberships come from one matrix product (≤ 4 MiB)


@lru_cache(maxsize=None)
def _subsets(c: int) -> tuple[np.ndarray, np.ndarray]:
    """The 2^c subsets of c core links as bit masks, and their sizes (read-only, shared; cached
    up to _MATRIX_CORE links, so a 24-link core does not stay in memory)."""
    T = np.arange(1 << c, dtype=np.int64)
    size = _popcount(T).astype(np.int64)
    T.flags.writeable = size.flags.writeable = False
    return T, size


@lru_cache(maxsize=None)
def _subset_bits(c: int) -> np.ndarray:
    """Row T, column i: 1 if subset T of the c core links holds link i (float32: exact, and BLAS)."""
    T = np.arange(1 << c, dtype=np.int64)
    return ((T[:, None] >> np.arange(c)) & 1).astype(np.float32)


def _members(T: np.ndarray, c: int, groups: list[list[int]]) -> np.ndarray:
    """Row T, column k: how many core links of ``groups[k]`` (indices) the subset T holds.

    >>> _members(np.arange(4), 2, [[0, 1], [1]]).tolist()
    [[0, 0], [1, 0], [1, 1], [2, 1]]
    """
    if not groups:
        return np.zeros((len(T), 0), dtype=np.int64)
    if c <= _MATRIX_CORE:
        M = np.zeros((c, len(groups)), dtype=np.float32)
        M[[i for group in groups for i in group], [k for k, group in enumerate(groups) for _ in group]] = 1
        return (_subset_bits(c) @ M).astype(np.int64)
    return np.stack([_popcount(T & sum(1 << i for i in group)) for group in groups], axis=1)


def subchain_mobility(chain: Chain, links) -> int:
    """W(S) of the sub-chain made of ``links``, in the chain's motion space.

    >>> subchain_mobility(Chain.parse("0-1 1-2 2-0 2-3"), [0, 1, 2])
    0
    """
    s = set(links)
    p = sum(max(sum(1 for x in j if x in s) - 1, 0) for j in chain.joints)
    return chain.h * (len(s) - 1) - (chain.h - 1) * p


@dataclass(frozen=True)
class SubchainReport:
    """Result of the sub-chain test.

    ``worst`` is a smallest proper sub-chain (|S| ≥ 2) of least mobility ``worst_mobility``;
    ``ok`` says whether it meets the convention (≥ 1 non-degenerate, ≥ 0 rigid allowed).
    """

    ok: bool
    worst: tuple[int, ...]
    worst_mobility: int
    threshold: int

    @property
    def kind(self) -> str:
        """'none', 'rigid sub-chain' (W(S) = 0) or 'over-constrained sub-chain' (W(S) < 0)."""
        if self.ok:
            return "none"
        return "rigid sub-chain" if self.worst_mobility == 0 else "over-constrained sub-chain"


def _paths(chain: Chain, core: list[int]):
    """Binary-link paths between core links: (end a, end b, links on the path)."""
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
                if other in is_core or other == start:
                    ends.append(other)
                    break
                if other in seen:  # closed cycle of binary links only
                    ends.append(None)
                    break
                seen.add(other)
                body.append(other)
                cur_joint = next(q for q in by_link[other] if q != cur_joint)
                prev = other
        paths.append((ends[0], ends[1], tuple(sorted(body))))
    return paths


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
        If the chain has more than 24 core links (the scan is exponential in them).
    """
    threshold = 0 if rigid_subchains else 1
    h = chain.h
    degrees = chain.degrees
    core = sorted({x for j in chain.joints if len(j) > 2 for x in j} | {i for i, d in enumerate(degrees) if d != 2})
    if len(core) > _MAX_CORE:
        raise MalformedChain(f"the exact sub-chain test handles up to {_MAX_CORE} non-binary links, not {len(core)}")
    # two links on one joint always give W = h − (h − 1) = 1: the least value any larger S must beat
    best = (1, chain.joints[0][:2]) if chain.joints and chain.links > 2 else (10**9, ())
    paths = _paths(chain, core)
    if not core:  # a single loop of binary links: its proper sub-chains are open paths, W ≥ 1
        return SubchainReport(True, best[1], best[0], threshold)
    index = {x: i for i, x in enumerate(core)}
    c = len(core)
    T, size = _subsets(c) if c <= _MATRIX_CORE else _subsets.__wrapped__(c)
    core_set = set(core)
    on_core = [[index[x] for x in j] for j in chain.joints if core_set.issuperset(j)]
    # paths that lower W when both ends are in T (w < h − 1), closed ones (a == b) included
    short = [(a, b, body) for a, b, body in paths if len(body) < h - 1 and a is not None]
    # one membership count per joint and per short path, then (lost freedoms, path links) per T
    counts = _members(T, c, on_core + [sorted({index[a], index[b]}) for a, b, _ in short])
    J = len(on_core)
    np.maximum(counts[:, :J] - 1, 0, out=counts[:, :J])  # a joint with m links of T removes m − 1
    counts[:, J:] = counts[:, J:] == np.array([1 if a == b else 2 for a, b, _ in short], dtype=np.int64)
    weights = np.zeros((len(on_core) + len(short), 2), dtype=np.int64)
    weights[:J, 0] = h - 1
    weights[J:, 0] = [h - 1 - len(body) for _, _, body in short]
    weights[J:, 1] = [len(body) for _, _, body in short]
    lost, extra = (counts @ weights).T
    W = h * (size - 1) - lost
    full = (1 << c) - 1
    proper = np.ones(1 << c, dtype=bool)
    proper_all = len(short) < len(paths)
    left_out = None
    if not proper_all:  # S_T would be the whole chain
        if short:  # the best proper one leaves out the longest short path: W + (h − 1 − w)
            left_out = max(short, key=lambda path: len(path[2]))
            W[full] += h - 1 - len(left_out[2])
            extra[full] -= len(left_out[2])
        else:
            proper[full] = False
    valid = proper & (size + extra >= 2)
    if valid.any() and W[valid].min() < best[0]:
        Wv = np.where(valid, W, 10**9)
        low = Wv.min()
        candidates = np.flatnonzero(Wv == low)
        pick = candidates[np.argmin(size[candidates] + extra[candidates])]
        links = [core[i] for i in range(c) if pick >> i & 1]
        for a, b, body in short:
            if (pick >> index[a] & 1) and (pick >> index[b] & 1) and (pick != full or (a, b, body) != left_out):
                links += body
        best = (int(low), tuple(sorted(links)))
    for a, b, body in paths:  # one closed path alone on its core link: W = w − (h − 1)
        if a is not None and a == b and (len(body) - (h - 1), len(body) + 1) < (best[0], len(best[1])):
            best = (len(body) - (h - 1), tuple(sorted((a, *body))))
    return SubchainReport(best[0] >= threshold, best[1], best[0], threshold)
