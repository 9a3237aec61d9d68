"""The exact sub-chain test of many candidates compiled (numba), one candidate at a time.

:func:`synth.structure.subchains.least_mobilities` scans every subset T of the core for every
candidate of a batch with matrix products; where most candidates fail (the placements of stage B's
kernel with multiple joints: nine in ten at 12 links) a test that stops at the first set T giving a
sub-chain below the threshold does far less.  :func:`passes` first keeps the sets T that can fall
below the threshold for some candidate of the batch (W_T is at least its constant part less the
most each path inside T costs over the batch, the whole chain's correction only adds to it; X_T is
at most its links plus the most each path brings), then decides each candidate by the scan's own
arithmetic: W_T = Σ freedoms of T − h − Σ cost_p and X_T = links of T + Σ taken_p over the short
paths p inside T, with the whole chain's correction on the sets that hold every core link.  A set
that refuses a candidate moves to the front of the list: the next candidate, a neighbour in the
placements' lexicographic order, is usually refused by the same set.

Numba compiles it once (cached beside this file, or in numba's user cache); it is used only where
stage B's kernel is loaded already (:func:`synth.synthesis.stage_a.uses_kernel`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["by_last_path", "exact_sets", "partial_sets", "passes", "verdict"]


@njit(cache=True)
def _terms(h, neutral, on_core, L):
    """Freedoms a path of ``L`` binary links costs a set that holds both its ends, and the links
    it brings: short paths only (w < h − 1, or w = h − 1 where ``neutral``), on the core."""
    if on_core and (L < h - 1 or (neutral and L == h - 1)):
        return h - 1 - L, L
    return 0, 0


@njit(cache=True)
def _bounds(T, h, is_link, end_a, end_b, most_cost, most_taken):
    """Σ freedoms − h and the links of the set T (a bit mask of core vertices), the least W_T and
    the most X_T over the batch, and the number of core paths inside T."""
    free, links = -h, 0
    for v in range(len(is_link)):
        if (T >> v) & 1:
            free += h if is_link[v] else h - 1
            links += is_link[v]
    low, most, paths = free, links, 0
    for p in range(len(end_a)):
        if end_a[p] >= 0 and (T >> end_a[p]) & 1 and (T >> end_b[p]) & 1:
            low -= most_cost[p]
            most += most_taken[p]
            paths += 1
    return free, links, low, most, paths


@njit(cache=True)
def _sets(h, is_link, end_a, end_b, most_cost, most_taken, threshold):
    """The sets T that may give a sub-chain below ``threshold``: their Σ freedoms − h, links,
    whether they hold every core link, their core paths (``inside[start[t]:start[t + 1]]``) and the
    sets themselves (bit masks of core vertices)."""
    c = len(is_link)
    n_links = 0
    for v in range(c):
        n_links += is_link[v]
    n_sets, n_inside = 0, 0  # count first, then fill
    for T in range(1, 1 << c):
        _, _, low, most, paths = _bounds(T, h, is_link, end_a, end_b, most_cost, most_taken)
        if low < threshold and most >= 2:
            n_sets += 1
            n_inside += paths
    base = np.zeros(n_sets, dtype=np.int64)
    size = np.zeros(n_sets, dtype=np.int64)
    every = np.zeros(n_sets, dtype=np.bool_)
    mask = np.zeros(n_sets, dtype=np.int64)
    start = np.zeros(n_sets + 1, dtype=np.int64)
    inside = np.zeros(n_inside, dtype=np.int64)
    t, k = 0, 0
    for T in range(1, 1 << c):
        free, links, low, most, _ = _bounds(T, h, is_link, end_a, end_b, most_cost, most_taken)
        if low < threshold and most >= 2:
            base[t], size[t], every[t], mask[t] = free, links, links == n_links, T
            for p in range(len(end_a)):
                if end_a[p] >= 0 and (T >> end_a[p]) & 1 and (T >> end_b[p]) & 1:
                    inside[k] = p
                    k += 1
            t += 1
            start[t] = k
    return base, size, every, start, inside, mask


@njit(cache=True)
def exact_sets(h, is_link, end_a, end_b, least, threshold):
    """The sets T of :func:`_sets` for every candidate whose path p holds at least ``least[p]``
    binary links (a short path costs the most at its least weight and brings at most h − 1 links):
    (base, size, every, start, inside, mask) as :func:`_sets` gives them.  Arguments as :func:`passes`."""
    P = len(end_a)
    most_cost = np.zeros(P, dtype=np.int64)
    most_taken = np.zeros(P, dtype=np.int64)
    for p in range(P):
        if end_a[p] >= 0 and least[p] <= h - 1:  # a short path: its least weight costs the most
            most_cost[p], most_taken[p] = h - 1 - least[p], h - 1
    return _sets(h, is_link, end_a, end_b, most_cost, most_taken, threshold)


@njit(cache=True)
def verdict(h, is_link, end_a, end_b, row, total, threshold, sets, order, cost, taken, binary_short):
    """Whether the candidate ``row`` (binary links per path, Σ ``total``) has no proper sub-chain below
    ``threshold``, decided on ``sets`` = (base, size, every, start, inside) (:func:`_sets` or
    :func:`exact_sets`: every set that can refuse it).  A set that refuses moves to the front of
    ``order``; ``cost``, ``taken``, ``binary_short`` are work arrays of one entry a path.  It reads a
    path of the core only through min(L, h) (:func:`_terms`, and L ≥ 1 or not), a path with a free end
    not at all, and the rest only through ``total``.  Arguments as :func:`passes`."""
    base, size, every, start, inside = sets
    neutral = False
    n_links = 0
    for v in range(len(is_link)):
        neutral |= not is_link[v]
        n_links += is_link[v]
    n_binary, longest, ok = 0, 0, True
    for p in range(len(end_a)):
        L = row[p]
        cost[p], taken[p] = _terms(h, neutral, end_a[p] >= 0, L)
        binary_short[p] = taken[p] > 0  # a short path with binary links
        n_binary += L >= 1
        if binary_short[p]:
            longest = max(longest, L)
        if end_a[p] >= 0 and end_a[p] == end_b[p]:  # a path closed on one core vertex, alone
            on_link = 1 if is_link[end_a[p]] else 0
            if L + on_link >= 2 and L - (h - 1) - (1 - on_link) < threshold:
                ok = False
    if n_links + total >= 3 and 1 < threshold:  # two links on one joint: W = 1
        ok = False
    for r in range(len(base)):
        if not ok:
            break
        t = order[r]
        W, X, whole = base[t], size[t], 0
        for q in range(start[t], start[t + 1]):
            p = inside[q]
            W -= cost[p]
            X += taken[p]
            whole += binary_short[p]
        if every[t] and whole == n_binary:  # S_T is the whole chain: leave the longest short path out
            if longest >= 1:
                W += h - 1 - longest
                X -= longest
            else:
                X = 0
        if X >= 2 and W < threshold:
            ok = False
            order[r], order[0] = order[0], t  # the set that refused it first next time
    return ok


@njit(cache=True)
def passes(h, is_link, end_a, end_b, lengths, threshold, out):
    """Write into ``out[i]`` whether candidate i (row i of ``lengths``: binary links per path) has
    no proper sub-chain below ``threshold``: ``least_mobilities(...)[i] >= threshold`` with no joint
    groups.  ``is_link``: the core vertices (links, or multiple joints with h − 1 freedoms); path p
    runs from core vertex ``end_a[p]`` to ``end_b[p]`` (−1, −1: a path with a free end)."""
    N, P = lengths.shape
    neutral = False
    for v in range(len(is_link)):
        neutral |= not is_link[v]
    most_cost = np.zeros(P, dtype=np.int64)
    most_taken = np.zeros(P, dtype=np.int64)
    for i in range(N):
        for p in range(P):
            d, x = _terms(h, neutral, end_a[p] >= 0, lengths[i, p])
            most_cost[p] = max(most_cost[p], d)
            most_taken[p] = max(most_taken[p], x)
    base, size, every, start, inside, _ = _sets(h, is_link, end_a, end_b, most_cost, most_taken, threshold)
    sets = (base, size, every, start, inside)
    order = np.arange(len(base))
    cost = np.zeros(P, dtype=np.int64)
    taken = np.zeros(P, dtype=np.int64)
    binary_short = np.zeros(P, dtype=np.int64)
    for i in range(N):
        out[i] = verdict(h, is_link, end_a, end_b, lengths[i], lengths[i].sum(), threshold, sets, order, cost, taken,
                         binary_short)
    return out


@njit(cache=True)
def partial_sets(h, is_link, end_a, end_b, least, threshold, position):
    """The sets T of the core that hold a multiple joint but not every core link and can give a
    sub-chain below ``threshold`` for some weights of at least ``least`` (binary links per path):
    (bucket, base, size, start, inside) with ``base[t]`` (Σ freedoms − h), ``size[t]`` (links) and their paths ``inside[start[t]:start[t + 1]]``
    written as the positions ``position[p]`` of a search order, the sets ordered by the position of
    their last path: ``bucket[e]`` … ``bucket[e + 1] − 1`` are the sets whose paths are all placed
    once the path at position e is.  Arguments as :func:`passes`, ``least`` per path."""
    return by_last_path(is_link, exact_sets(h, is_link, end_a, end_b, least, threshold), position, len(end_a))


@njit(cache=True)
def by_last_path(is_link, sets, position, n_positions):
    """:func:`partial_sets` of the sets ``sets`` (as :func:`exact_sets` gives them), for a search whose
    ``n_positions`` positions ``position[p]`` may each place several paths."""
    base, size, every, start, inside, mask = sets
    P = n_positions
    joints = 0
    for v in range(len(is_link)):
        if not is_link[v]:
            joints |= 1 << v
    last = np.full(len(base), -1, dtype=np.int64)
    bucket = np.zeros(P + 1, dtype=np.int64)
    n_inside = 0
    for t in range(len(base)):
        if every[t] or not mask[t] & joints:  # (the whole chain's correction needs every path)
            continue
        last[t] = 0  # (a set without paths refuses every placement, from the first string on)
        for q in range(start[t], start[t + 1]):
            last[t] = max(last[t], position[inside[q]])
        bucket[last[t] + 1] += 1
        n_inside += start[t + 1] - start[t]
    for e in range(P):
        bucket[e + 1] += bucket[e]
    order = np.zeros(bucket[P], dtype=np.int64)  # the kept sets by the position of their last path
    fill = bucket[:P].copy()
    for t in range(len(base)):
        if last[t] >= 0:
            order[fill[last[t]]] = t
            fill[last[t]] += 1
    start2, inside2 = np.zeros(len(order) + 1, dtype=np.int64), np.zeros(n_inside, dtype=np.int64)
    for i in range(len(order)):
        t = order[i]
        start2[i + 1] = start2[i] + start[t + 1] - start[t]
        for q in range(start[t], start[t + 1]):
            inside2[start2[i] + q - start[t]] = position[inside[q]]
    return bucket, base[order], size[order], start2, inside2
