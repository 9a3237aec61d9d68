"""Stage B's compiled kernel: the placements of the binary links on the strings of one branch
multigraph H with simple joints, enumerated depth first and checked by a pebble game (numba).

A placement gives each string e of H its number w_e of binary links (Σ w = n2, w_e ≥ its least
weight, parallel strings non-decreasing).  With simple joints a string with w < h − 1 binary
links is *short*: it costs the sub-chain rule d_e = h − 1 − w freedoms, and the rule (stage B's
model, docs/theory.md) says that for every set T of two or more inner branch links the short
strings inside T cost at most h(|T| − 1) − threshold, i.e. the multigraph D that holds each short
string d_e times is (k, l)-sparse with k = h and l = h + threshold.  The (k, l) pebble game of
Lee and Streinu (2008) decides that edge by edge (exact for 0 ≤ l < 2k): each vertex holds k
pebbles, an edge is accepted when l + 1 pebbles can be gathered on its ends by reversing
directed paths, and it then takes a pebble and points away from the vertex that gave it;
taking an edge back returns that pebble, so the search backtracks without copies.

The search assigns the strings in order with w ascending, so placements come out in
lexicographic order; a complete one is kept where it is the lex-least of its images under the
given edge permutations (the automorphisms of H: one placement per orbit when the whole group
is given).  Prunes that cut no solution:

* a partial placement that an image already beats on the strings placed so far (an image w[g]
  that differs from w first at a string i, reading only strings up to the current one, and is
  smaller there) is beaten whatever the later strings hold: the search backs up at once instead of
  visiting every completion to reject it (14 links: half the search's steps; issue 41); tested
  before the string's units go into the game, which a beaten prefix then never pays for;

* the set of all inner links is sparse too, so the excess X above h − 1 on long strings (and
  above the least weight on strings that are never short) is at most B0 + Σ k − l, where
  B0 = n2 − (h − 1)·(short-able strings) − (least weights of the others);
* X − D = B0 at the end, so the strings still to come must be able to carry the deficit D
  still missing: at most what they hold in the game on their own (the rank of their units in the
  (k, l)-sparsity matroid, the game run once over the strings from the last back before the
  search), and at most h − 1 a string and k_a + k_b − l a bundle of parallel strings (the pair of
  its ends is sparse), less what the bundle's placed strings already hold (14 links: 0.92 M of
  the 1.28 M descents that found nothing; issue 41); with multiple joints, at most what they hold
  in either game (14 links, v ≤ 12, a sample: the kernel's steps 25.2 M → 21.9 M);
* the set of every vertex but one, x, is sparse: the strings at x carry at least
  −B0 − (Σ k − k_x − l) of the deficit (``vertex_need``).

With multiple joints two games run side by side, each a weaker rule that no valid placement
breaks, and the exact test decides among what both keep: in one a multiple joint J is a vertex of
h − 1 pebbles (its freedoms, as in the exact test: each of its links then costs h − 1) and l is
h + min(threshold, 0) — exact for the sets of two links or more up to the threshold, and never
wrong for the sets of fewer, which the rule leaves out (a link with joints on it alone, two joints
with one binary link between them); in the other J has h pebbles and l = h + threshold — exact
for the sets without multiple joints, one freedom weaker for each joint in a set.
A count with W ≥ 1 also checks the exact rule itself on the sets T with a multiple joint that can
refuse a placement (W_T below the threshold with two links or more; not the set of every link,
whose rule depends on every string), each as soon as its last string is placed, so that a refused
prefix is not completed (12 links: 10.9 placements written per chain → 1.4; benchmarks/PROFILE.md
section 28).  The listing's search runs without it and stays a check of the count.  Most such units are
not searched at all: :func:`tight_count` with ``links`` counts them under the exact rule
(docs/theory.md, "Counting tight placements without visiting them", *With multiple joints*).

Numba compiles the kernel once (cached beside this file, or in numba's user cache); loading it
takes about a second per process, so type synthesis uses it for large queries only
(:func:`synth.synthesis.stage_a.uses_kernel`).
"""

from __future__ import annotations

import tempfile

import numpy as np
from numba import njit

from ..structure.subchain_kernel import by_last_path, verdict

__all__ = ["fixed_placements", "fixed_total", "narrow_ranks", "place", "tight_count"]


@njit(cache=True)
def _take_back(a, b, pebbles, arcs):
    """Remove one unit of the edge a–b from the pebble game: its tail gets its pebble back."""
    if arcs[a, b] > 0:
        arcs[a, b] -= 1
        pebbles[a] += 1
    else:
        arcs[b, a] -= 1
        pebbles[b] += 1


@njit(cache=True)
def _fetch(source, other, pebbles, arcs, seen, parent, stack):
    """Bring one pebble to ``source`` from a vertex it reaches along directed edges (never from
    ``other`` or itself), reversing the path; False if there is none."""
    M = len(pebbles)
    for i in range(M):
        seen[i] = False
    seen[source] = True
    seen[other] = True
    stack[0] = source
    top = 1
    while top > 0:
        top -= 1
        x = stack[top]
        for y in range(M):
            if arcs[x, y] > 0 and not seen[y]:
                seen[y] = True
                parent[y] = x
                if pebbles[y] > 0:
                    z = y
                    while z != source:
                        p = parent[z]
                        arcs[p, z] -= 1
                        arcs[z, p] += 1
                        z = p
                    pebbles[y] -= 1
                    pebbles[source] += 1
                    return True
                stack[top] = y
                top += 1
    return False


@njit(cache=True)
def _accept(a, b, l, pebbles, arcs, seen, parent, stack):
    """Add one unit of the edge a–b if the multigraph stays (k, l)-sparse."""
    while pebbles[a] + pebbles[b] < l + 1:
        if not _fetch(a, b, pebbles, arcs, seen, parent, stack):
            if not _fetch(b, a, pebbles, arcs, seen, parent, stack):
                return False
    if pebbles[a] > 0:
        pebbles[a] -= 1
        arcs[a, b] += 1
    else:
        pebbles[b] -= 1
        arcs[b, a] += 1
    return True


@njit(cache=True)
def _not_beaten(w, group, e):
    """Whether no image w[g] under a row g of ``group`` is already lexicographically smaller than
    w, judged on the strings 0 … e placed so far (e = len(w) − 1: w is the lex-least of its images).

    Each row is compared up to the first string where w and its image differ, or where the image
    reads a string not yet placed: there the row cannot decide yet, whatever comes later.
    """
    for g in range(group.shape[0]):
        for i in range(e + 1):
            j = group[g, i]
            if j > e:
                break
            if w[j] != w[i]:
                if w[j] < w[i]:
                    return False
                break
    return True


@njit(cache=True)
def _sets_hold(w, e, C, threshold, sets, order):
    """Whether the placement w of strings 0 … e passes the exact rule on the sets T whose strings
    are all placed once string e is (``sets``: see :func:`place`): W_T = base − Σ (C − w) and
    X_T = size + Σ w over the strings of T with w ≤ C, refused where X_T ≥ 2 and W_T < threshold, the
    exact test's own arithmetic (:mod:`synth.structure.subchain_kernel`).  A set that refuses moves
    to the front of its group in ``order``: the next placement tried is usually refused by it too."""
    bucket, base, size, start, inside = sets
    for r in range(bucket[e], bucket[e + 1]):
        t = order[r]
        W, X = base[t], size[t]
        for q in range(start[t], start[t + 1]):
            L = w[inside[q]]
            if L <= C:
                W -= C - L
                X += L
        if X >= 2 and W < threshold:
            order[r], order[bucket[e]] = order[bucket[e]], t
            return False
    return True


@njit(cache=True)
def place(M, a_end, b_end, least, parallel, n2, k, C, l, k2, l2, x_most, vertex_need, group, out,
          threshold, sets):
    """Count the placements (and write the first ``len(out)`` into ``out``); see the module.

    M: pebble-game vertices (inner branch links, multiple joints); ``a_end[e]``, ``b_end[e]``: the
    ends of string e among them, −1 for a string that is never short (a loop, a string to a
    single-joint link); ``least[e]``: its least weight; ``parallel[e]``: −1, or the least weight of a
    string parallel to string e − 1 (then w_e ≥ w_{e−1} too); n2 binary links; ``k[v]`` the pebbles
    of vertex v and l the sparsity (and a second game ``k2``, ``l2`` where l2 ≥ 0); C the weight
    from which a string is long; ``x_most``,
    ``vertex_need[v]``: the bounds of the module's prunes; ``group``: edge permutations (rows).
    With multiple joints, ``sets`` = (bucket, base, size, start, inside) are sets T of the exact
    test checked as soon as their strings are placed (:func:`_sets_hold`; none with simple joints,
    in the listing's search, or where ``threshold`` ≤ 0).
    """
    E = len(a_end)
    if E == 0:
        return 0
    pebbles = k.copy()
    arcs = np.zeros((M, M), dtype=np.int64)
    pebbles2 = k2.copy()
    arcs2 = np.zeros((M, M), dtype=np.int64)
    seen = np.zeros(M, dtype=np.bool_)
    parent = np.zeros(M, dtype=np.int64)
    stack = np.zeros(M, dtype=np.int64)
    least_after = np.zeros(E + 1, dtype=np.int64)  # Σ least weights of strings e …
    first = np.zeros(E, dtype=np.int64)  # the first string of string e's bundle
    end = np.zeros(E, dtype=np.int64)  # … and one past its last
    for e in range(E):
        first[e] = first[e - 1] if e > 0 and parallel[e] >= 0 else e
    for e in range(E - 1, -1, -1):
        end[e] = end[e + 1] if e + 1 < E and parallel[e + 1] >= 0 else e + 1
    room_after = np.zeros(E + 1, dtype=np.int64)  # the most deficit the bundles from string e on take
    rank_after = np.zeros(E + 1, dtype=np.int64)  # … and the strings e … take in the game on their own
    for e in range(E - 1, -1, -1):
        room_after[e], rank_after[e] = room_after[e + 1], rank_after[e + 1]
        if a_end[e] >= 0:
            if e == first[e]:
                room_after[e] += min(C * (end[e] - e), k[a_end[e]] + k[b_end[e]] - l)
            for _ in range(C):  # greedy is exact in a matroid: strings e … hold rank_after[e] units
                if not _accept(a_end[e], b_end[e], l, pebbles, arcs, seen, parent, stack):
                    break
                rank_after[e] += 1
    if l2 >= 0:  # the second game bounds them too (with multiple joints, often tighter)
        rank2 = 0
        for e in range(E - 1, -1, -1):
            if a_end[e] >= 0:
                for _ in range(C):
                    if not _accept(a_end[e], b_end[e], l2, pebbles2, arcs2, seen, parent, stack):
                        break
                    rank2 += 1
            rank_after[e] = min(rank_after[e], rank2)
        pebbles2[:] = k2
        arcs2[:, :] = 0
    pebbles[:] = k
    arcs[:, :] = 0
    B0 = n2
    for e in range(E - 1, -1, -1):
        least_after[e] = least_after[e + 1] + least[e]
        B0 -= C if a_end[e] >= 0 else least[e]
    at = np.zeros(M, dtype=np.int64)  # deficit on the strings of each vertex so far
    open_ = np.zeros(M, dtype=np.int64)  # short-able strings of each vertex not yet placed
    for e in range(E):
        if a_end[e] >= 0:
            open_[a_end[e]] += 1
            open_[b_end[e]] += 1
    w = np.zeros(E, dtype=np.int64)
    set_order = np.arange(len(sets[1]))  # the sets of the exact test in the order they are tried
    top = np.zeros(E, dtype=np.int64)  # largest weight left to try
    units = np.zeros(E, dtype=np.int64)  # deficit units of string e in the pebble game
    units2 = np.zeros(E, dtype=np.int64)  # … in the second game
    placed = np.zeros(E, dtype=np.bool_)
    left = np.zeros(E + 1, dtype=np.int64)  # binary links not yet placed, before string e
    excess = np.zeros(E + 1, dtype=np.int64)
    deficit = np.zeros(E + 1, dtype=np.int64)
    left[0] = n2
    found = 0
    e = 0
    w[0] = least[0] - 1
    top[0] = n2 - least_after[1]
    if E == 1:
        w[0] = n2 - 1 if n2 >= least[0] else n2
        top[0] = n2
    while e >= 0:
        a, b = a_end[e], b_end[e]
        if placed[e]:  # take string e back
            placed[e] = False
            for _ in range(units[e]):
                _take_back(a, b, pebbles, arcs)
            for _ in range(units2[e]):
                _take_back(a, b, pebbles2, arcs2)
            if a >= 0:
                at[a] -= units[e]
                at[b] -= units[e]
                open_[a] += 1
                open_[b] += 1
        units[e] = 0
        units2[e] = 0
        w[e] += 1
        if w[e] > top[e]:
            e -= 1
            continue
        we = w[e]
        if a >= 0:
            dx, dd = max(we - C, 0), max(C - we, 0)
        else:
            dx, dd = we - least[e], 0
        x, d = excess[e] + dx, deficit[e] + dd
        room = room_after[end[e]]  # the bundles after e's, and the strings after e in it
        if a >= 0:
            room += min(C * (end[e] - 1 - e), k[a] + k[b] - l - (d - deficit[first[e]]))
        if x > x_most or x - B0 - d > min(room, rank_after[e + 1]):
            top[e] = we  # a larger weight raises the deficit missing at least as much as the room
            continue
        if a >= 0 and (at[a] + dd + C * (open_[a] - 1) < vertex_need[a]
                       or at[b] + dd + C * (open_[b] - 1) < vertex_need[b]):
            continue
        if not _not_beaten(w, group, e):  # this placement, and every one below it, is beaten by an image
            continue
        ok = True
        for _ in range(dd):
            if not _accept(a, b, l, pebbles, arcs, seen, parent, stack):
                ok = False
                break
            units[e] += 1
        if ok and l2 >= 0:
            for _ in range(dd):
                if not _accept(a, b, l2, pebbles2, arcs2, seen, parent, stack):
                    ok = False
                    break
                units2[e] += 1
        placed[e] = True
        if a >= 0:
            at[a] += units[e]
            at[b] += units[e]
            open_[a] -= 1
            open_[b] -= 1
        if not ok or not _sets_hold(w, e, C, threshold, sets, set_order):
            continue
        if e == E - 1:
            if found < out.shape[0]:
                out[found, :] = w
            found += 1
            continue
        left[e + 1], excess[e + 1], deficit[e + 1] = left[e] - we, x, d
        e += 1
        lo = least[e]
        if parallel[e] >= 0:
            lo = max(lo, w[e - 1], parallel[e])
        if e == E - 1:  # the last string takes what is left
            w[e] = left[e] - 1 if left[e] >= lo else left[e]
            top[e] = left[e]
        else:
            w[e] = lo - 1
            top[e] = left[e] - least_after[e + 1]
    return found


@njit(cache=True)
def _ways(sizes, count, total, ways):
    """Solutions y ≥ 0 of Σ sizes[c]·y[c] = total over the first ``count`` cycles: a coin change
    count, one pass over ``ways`` (an array of at least total + 1 entries) per cycle."""
    if total <= 0 or count == 0:
        return 1 if total == 0 else 0
    ways[:total + 1] = 0
    ways[0] = 1
    for c in range(count):
        s = sizes[c]
        for t in range(s, total + 1):
            ways[t] += ways[t - s]
    return ways[total]


@njit(cache=True)
def fixed_placements(M, a_end, b_end, least, later, width, n2, k, C, l, x_most, vertex_need, g, k2, l2, exact):
    """Fix(g): the placements that pass the pebble game of :func:`place` (and, with multiple joints,
    its second game and the exact test), taken up to the order of parallel strings, that the
    permutation ``g`` of the bundles of parallel strings leaves unchanged.

    Bundle q is ``width[q]`` parallel strings between the game's vertices ``a_end[q]`` and
    ``b_end[q]`` (−1 for strings that are never short: loops, strings to single-joint links), the
    first of at least ``least[q]`` binary links, the others of at least ``later[q]``; Σ w = n2.
    A placement up to the order of parallel strings is a non-decreasing vector per bundle, and g
    leaves it unchanged when every bundle of a cycle of g holds the same vector.  The rule sees a
    string only through its *pattern* min(w, P): with simple joints P = C = h − 1, a string of C
    binary links or more costs nothing; with multiple joints P = h, since the exact test also tells
    a string of exactly h − 1 (which brings its links to a set at no cost) from a longer one
    (:func:`synth.structure.subchain_kernel.verdict` reads a string of the core only through
    min(w, h), loops included).  So the search gives each cycle's vector a non-decreasing pattern,
    slot by slot (every string of the slot, one per bundle of the cycle, takes C − w units in each
    game), the long slots (pattern P) last; for a complete pattern the exact test, where given,
    decides on one placement of it (each long slot at its least), and the long slots' weights are
    counted, not listed: r long slots of a cycle of s bundles are a partition into at most r parts,
    coins s·1 … s·r of a coin change count (``_ways``).
    Prunes: the binary links taken so far (long slots at their least, the slots to come at theirs)
    at most n2; the excess X the long strings will carry (above C, and above their least on strings
    the game never sees) at most ``x_most`` (the slots to come taken at their most without excess);
    ``vertex_need`` as in :func:`place`.  ``exact`` = (is_link, core_a, core_b, sets, total,
    threshold, first): the exact test's core (its ends per string of H, loops on the core), its sets
    (:func:`synth.structure.subchain_kernel.exact_sets`), Σ of a placement's path lengths, and the
    first string of each bundle; an empty ``core_a`` for simple joints, where the game is the rule.
    Other arguments as :func:`place`.
    """
    Q = len(a_end)
    if Q == 0:
        return 0
    is_link, core_a, core_b, sets, total, threshold, first = exact
    tested = len(core_a) > 0
    P = C + 1 if tested else C  # the pattern of a long string
    # the cycles of g on the bundles; their slots, cycle after cycle (slot_cycle), first bundle first
    cycle_of = np.full(Q, -1, dtype=np.int64)
    size = np.zeros(Q, dtype=np.int64)
    members = np.zeros(Q, dtype=np.int64)  # bundles of cycle c: members[start[c]:start[c + 1]]
    start = np.zeros(Q + 1, dtype=np.int64)
    nc = 0
    for q in range(Q):
        x = q
        while cycle_of[x] < 0:
            cycle_of[x] = nc
            members[start[nc] + size[nc]] = x
            size[nc] += 1
            x = g[x]
        if cycle_of[q] == nc:
            start[nc + 1] = start[nc] + size[nc]
            nc += 1
    S = 0
    for c in range(nc):
        S += width[members[start[c]]]
    slot_cycle = np.zeros(S, dtype=np.int64)
    slot_index = np.zeros(S, dtype=np.int64)  # the slot's place in its bundles
    i = 0
    for c in range(nc):
        for j in range(width[members[start[c]]]):
            slot_cycle[i] = c
            slot_index[i] = j
            i += 1
    lowest = np.zeros(S + 1, dtype=np.int64)  # binary links the slots i … take at least
    most = np.zeros(S + 1, dtype=np.int64)  # … and at most without excess (every one long at its least)
    for i in range(S - 1, -1, -1):
        c = slot_cycle[i]
        q = members[start[c]]
        lowest[i] = lowest[i + 1] + (size[c] * least[q] if a_end[q] < 0 else 0)
        most[i] = most[i + 1] + size[c] * (least[q] if a_end[q] < 0 else max(C, least[q]))
    pebbles = k.copy()
    arcs = np.zeros((M, M), dtype=np.int64)
    pebbles2 = k2.copy()
    arcs2 = np.zeros((M, M), dtype=np.int64)
    seen = np.zeros(M, dtype=np.bool_)
    parent = np.zeros(M, dtype=np.int64)
    stack = np.zeros(M, dtype=np.int64)
    # the deficit the slots i … can hold in the games on their own (the rank of their units, as in place)
    rank = np.zeros(S + 1, dtype=np.int64)
    rank2 = np.zeros(S + 1, dtype=np.int64)
    for i in range(S - 1, -1, -1):
        rank[i], rank2[i] = rank[i + 1], rank2[i + 1]
        c = slot_cycle[i]
        for m in range(start[c], start[c + 1] if a_end[members[start[c]]] >= 0 else start[c]):
            q = members[m]
            for _ in range(C):
                if not _accept(a_end[q], b_end[q], l, pebbles, arcs, seen, parent, stack):
                    break
                rank[i] += 1
            for _ in range(C if l2 >= 0 else 0):
                if not _accept(a_end[q], b_end[q], l2, pebbles2, arcs2, seen, parent, stack):
                    break
                rank2[i] += 1
        if l2 < 0:
            rank2[i] = rank[i]
    pebbles[:] = k
    arcs[:, :] = 0
    pebbles2[:] = k2
    arcs2[:, :] = 0
    B0 = n2  # X − D = B0 for every placement: X the excess, D the deficit (as in place)
    for q in range(Q):
        B0 -= width[q] * (C if a_end[q] >= 0 else least[q])
    at = np.zeros(M, dtype=np.int64)  # deficit on the strings of each vertex so far
    open_ = np.zeros(M, dtype=np.int64)  # short-able strings of each vertex not yet given a pattern
    for q in range(Q):
        if a_end[q] >= 0:
            open_[a_end[q]] += width[q]
            open_[b_end[q]] += width[q]
    deficit = np.zeros(S + 1, dtype=np.int64)  # deficit of the slots before slot i
    choice = np.full(S, -1, dtype=np.int64)  # pattern of slot i: 0 … P − 1 exact, P long
    placed = np.zeros(S, dtype=np.bool_)  # slot i's pattern is counted in ``at`` and ``open_``
    units = np.zeros(S, dtype=np.int64)  # units slot i holds in the game (over its bundles)
    units2 = np.zeros(S, dtype=np.int64)  # … in the second game
    weight = np.zeros(S, dtype=np.int64)  # the binary links of each string of slot i (long: its least)
    used = np.zeros(S + 1, dtype=np.int64)  # binary links taken before slot i (long slots: their least)
    excess = np.zeros(S + 1, dtype=np.int64)  # excess those carry at least
    coins = np.zeros(S, dtype=np.int64)
    n_coins = np.zeros(S + 1, dtype=np.int64)  # coins before slot i
    run = np.zeros(S + 1, dtype=np.int64)  # long slots of slot i's cycle before it
    ways = np.zeros(n2 + 1, dtype=np.int64)
    row = np.zeros(len(core_a), dtype=np.int64)  # one placement of a complete pattern, per string of H
    base, size_t, every, start_t, inside, _ = sets
    whole = (base, size_t, every, start_t, inside)  # every set that may refuse a pattern, for the end
    order = np.arange(len(base))
    position = np.zeros(len(core_a), dtype=np.int64)  # the slot that gives each string of H its pattern
    for j in range(S if tested else 0):
        cj = slot_cycle[j]
        for m in range(start[cj], start[cj + 1]):
            position[first[members[m]] + slot_index[j]] = j
    # the sets with a multiple joint, checked as soon as their strings have patterns (as place does)
    early = by_last_path(is_link, sets, position, S if tested else 0)
    early_order = np.arange(len(early[1]))
    cost = np.zeros(len(core_a), dtype=np.int64)
    taken = np.zeros(len(core_a), dtype=np.int64)
    binary_short = np.zeros(len(core_a), dtype=np.int64)
    fixed = 0
    i = 0
    while i >= 0:
        c = slot_cycle[i]
        q0 = members[start[c]]
        short_able = a_end[q0] >= 0
        # a pattern below P for: the game's strings, and the exact test's loops (on its core)
        patterned = short_able or (tested and core_a[first[q0]] >= 0)
        d = C - choice[i] if 0 <= choice[i] < C else 0
        if placed[i]:  # take slot i back, bundle by bundle
            left, left2 = units[i], units2[i]
            for m in range(start[c], start[c + 1]):
                q = members[m]
                for _ in range(min(left, d)):
                    _take_back(a_end[q], b_end[q], pebbles, arcs)
                for _ in range(min(left2, d)):
                    _take_back(a_end[q], b_end[q], pebbles2, arcs2)
                left -= min(left, d)
                left2 -= min(left2, d)
                at[a_end[q]] -= d
                at[b_end[q]] -= d
                open_[a_end[q]] += 1
                open_[b_end[q]] += 1
            placed[i] = False
            units[i] = 0
            units2[i] = 0
        if choice[i] < 0 and slot_index[i]:
            choice[i] = choice[i - 1] - 1  # non-decreasing in a bundle
        choice[i] += 1
        if not patterned and choice[i] < P:
            choice[i] = P  # never short: long at once
        if choice[i] > P:
            choice[i] = -1
            i -= 1
            continue
        p = choice[i]
        if p < P and p < (later[q0] if slot_index[i] else least[q0]):
            continue
        if p < P:
            w = p
        elif slot_index[i] and choice[i - 1] == P:
            w = weight[i - 1]  # (non-decreasing: at least the long slot before it)
        else:
            w = max(P, least[q0]) if patterned else least[q0]
        weight[i] = w
        if used[i] + size[c] * w + lowest[i + 1] > n2:
            choice[i] = P  # every later choice costs more: nothing left to try
            continue
        x = excess[i] + size[c] * (max(w - C, 0) if short_able else w - least[q0])
        x_least = x + max(n2 - used[i] - size[c] * w - most[i + 1], 0)  # the excess X will be at least
        if x_least > x_most:
            continue  # the long strings would carry more excess than the rule allows
        dd = size[c] * (C - p) if short_able and p < C else 0
        if x_least - B0 - deficit[i] - dd > min(rank[i + 1], rank2[i + 1]):
            # the slots to come cannot hold the deficit still missing, nor with any later choice (each
            # unit more on the slot takes a unit of deficit off it and a unit of excess at most)
            choice[i] = P
            continue
        if short_able:
            d = C - p if p < C else 0
            for m in range(start[c], start[c + 1]):
                q = members[m]
                at[a_end[q]] += d
                at[b_end[q]] += d
                open_[a_end[q]] -= 1
                open_[b_end[q]] -= 1
            placed[i] = True
            ok = True
            for m in range(start[c], start[c + 1]):  # the strings still open at its ends can carry the rest
                q = members[m]
                if (at[a_end[q]] + C * open_[a_end[q]] < vertex_need[a_end[q]]
                        or at[b_end[q]] + C * open_[b_end[q]] < vertex_need[b_end[q]]):
                    ok = False
            for m in range(start[c], start[c + 1]):
                q = members[m]
                for _ in range(d):
                    if not ok or not _accept(a_end[q], b_end[q], l, pebbles, arcs, seen, parent, stack):
                        ok = False
                        break
                    units[i] += 1
                for _ in range(d if l2 >= 0 else 0):
                    if not ok or not _accept(a_end[q], b_end[q], l2, pebbles2, arcs2, seen, parent, stack):
                        ok = False
                        break
                    units2[i] += 1
            if not ok:
                continue
        if tested and not _sets_hold(weight, i, C, threshold, early, early_order):
            continue
        used[i + 1] = used[i] + size[c] * w
        excess[i + 1] = x
        deficit[i + 1] = deficit[i] + dd
        n_coins[i + 1] = n_coins[i]
        run[i + 1] = 0
        if p == P:  # the r-th long slot of its cycle: a coin of r·s
            run[i + 1] = (run[i] if slot_index[i] else 0) + 1
            coins[n_coins[i]] = run[i + 1] * size[c]
            n_coins[i + 1] += 1
        if i < S - 1:
            i += 1
            continue
        if tested:  # the exact test on one placement of the pattern (a string to a single-joint link holds it too)
            for e in range(len(core_a)):
                row[e] = weight[position[e]] + (core_a[e] < 0)
            if not verdict(C + 1, is_link, core_a, core_b, row, total, threshold, whole, order, cost, taken,
                           binary_short):
                continue
        fixed += _ways(coins, n_coins[i + 1], n2 - used[i + 1], ways)
    return fixed


@njit(cache=True)
def fixed_total(M, a_end, b_end, least, later, width, n2, k, C, l, x_most, vertex_need, group, k2, l2, exact):
    """Σ Fix(g) over the rows of ``group``, permutations of the bundles of parallel strings
    (:func:`fixed_placements`): by Burnside's lemma, the orbits of the valid placements times the
    number of rows when the rows are every permutation of the bundles that an automorphism of H
    makes (identity included)."""
    total = 0
    for r in range(group.shape[0]):
        total += fixed_placements(M, a_end, b_end, least, later, width, n2, k, C, l, x_most, vertex_need, group[r],
                                  k2, l2, exact)
    return total


@njit(cache=True)
def _bundle_deficits(C, lows, game, X, ways):
    """``ways[t, y, z]``: the weights w_0 ≤ w_1 ≤ … of a bundle of parallel strings, w_x ≥ ``lows[x]``,
    whose deficits Σ max(C − w_x, 0) add up to t and whose excess Σ max(w_x − C, 0) to y ≤ ``X``
    (t = 0 … C·len(lows): the first rows of ``ways``); a bundle the game never sees (``game`` false: loops, the string of a
    single-joint link) has no deficit, its excess is Σ (w_x − lows[x]).  With Q = ``ways.shape[2]`` above 1
    (multiple joints, :func:`tight_count`'s ``links``) z is the binary links its short strings (w ≤ C) bring to a
    set that holds both its ends, Σ w_x over them, capped at Q − 1; with Q = 1 it is 0."""
    r = len(lows)
    Q = ways.shape[2]
    ways[:C * r + 1, :, :] = 0
    top = X + (max(C, lows[r - 1]) if game else lows[r - 1])  # no weight above it keeps y ≤ X
    last = np.zeros((top + 1, C * r + 1, X + 1, Q), dtype=np.int64)  # the strings so far: last weight, Σ t, Σ y, z
    nxt = np.zeros_like(last)
    for x in range(r):
        nxt[:, :, :, :] = 0
        for v in range(lows[x], top + 1):
            dt = max(C - v, 0) if game else 0
            dy = max(v - C, 0) if game else v - lows[x]
            dz = min(v, Q - 1) if game and v <= C else 0
            if dy > X:
                break
            if x == 0:
                nxt[v, dt, dy, dz] += 1
                continue
            for u in range(v + 1):  # the string before weighs u ≤ v
                for t in range(C * x + 1):
                    for y in range(X + 1 - dy):
                        for z in range(Q):
                            if last[u, t, y, z]:
                                nxt[v, t + dt, y + dy, min(z + dz, Q - 1)] += last[u, t, y, z]
        last[:, :, :, :] = nxt
    for v in range(top + 1):
        ways[:C * r + 1] += last[v]


@njit(cache=True)
def _state_code(row, width, W, P, total):
    """The hash of a state (``row[:width]``, ``row[W:W + P]``, ``total``): its slot in a layer's table comes from
    its low bits, its bucket (:func:`_tight_split`) from bits 32 … 61."""
    code = np.int64(total) * np.int64(-7046029254386353131)
    for U in range(width):
        code = (code ^ np.int64(row[U])) * np.int64(1099511628211)
    for U in range(W, W + P):
        code = (code ^ np.int64(row[U])) * np.int64(1099511628211)
    return code


@njit(cache=True)
def _state_slot(table, states, totals, row, width, W, P, total, code):
    """Where the state (``row[:width]``, ``row[W:W + P]``, ``total``; hash ``code``) is in a layer
    (``states``, ``totals``) hashed in ``table``: its index, or −(slot + 1) for the empty slot where it goes."""
    mask = len(table) - 1
    slot = (code ^ (code >> 29)) & mask
    while True:
        j = table[slot]
        if j < 0:
            return -(slot + 1)
        if totals[j] == total:
            same = True
            for U in range(width):
                if states[j, U] != row[U]:
                    same = False
                    break
            for U in range(W, W + P):
                if states[j, U] != row[U]:
                    same = False
                    break
            if same:
                return j
        slot = (slot + 1) & mask


@njit(cache=True)
def _rehash(states, totals, m, width, W, P):
    """A table (a power of two, at least 128 and 4·m slots) holding the states 0 … m − 1 of a layer."""
    size = 128
    while size < 4 * m:
        size *= 2
    table = np.full(size, -1, dtype=np.int64)
    for j in range(m):
        table[-_state_slot(table, states, totals, states[j], width, W, P, totals[j],
                           _state_code(states[j], width, W, P, totals[j])) - 1] = j
    return table


@njit(cache=True)
def narrow_ranks(M, a_end, b_end, given):
    """A rank for each of the game's ``M`` vertices (strings ``a_end``–``b_end``, −1 where the game never sees
    one) that keeps few vertices open (met, with a string still to come) when the vertices are taken in that
    order, each with its strings to those before it: the order with the least, over all orders, of the most open
    while a vertex's strings are placed, then of Σ 2^that (:func:`tight_count`'s states hold 2^(open) values a
    class); or the rank ``given`` where its most open is within one of that least (a narrower order is not always
    the faster: benchmarks/PROFILE.md section 47).  A search over the sets of vertices taken first (2^M of them:
    for M ≤ 16 or so).

    >>> import numpy as np
    >>> path = np.array([0, 3, 1], dtype=np.int64), np.array([3, 1, 2], dtype=np.int64)  # 0 – 3 – 1 – 2
    >>> narrow_ranks(4, *path, np.array([0, 1, 2, 3])).tolist()  # 0, 1, 2, 3 leaves 3 open: within one, kept
    [0, 1, 2, 3]
    >>> star = np.array([0, 0, 0, 0, 0], dtype=np.int64), np.array([1, 2, 3, 4, 5], dtype=np.int64)
    >>> narrow_ranks(6, *star, np.array([5, 4, 3, 2, 1, 0])).tolist()  # the centre last: 5 open; first: 1
    [0, 1, 2, 3, 4, 5]
    """
    adjacent = np.zeros(M, dtype=np.int64)
    for e in range(len(a_end)):
        a, b = a_end[e], b_end[e]
        if a >= 0 and a != b:
            adjacent[a] |= np.int64(1) << b
            adjacent[b] |= np.int64(1) << a
    size = 1 << M
    everything = size - 1
    unreached = np.int64(1) << 62
    worst = np.full(size, unreached, dtype=np.int64)
    total = np.full(size, unreached, dtype=np.int64)
    back = np.full(size, -1, dtype=np.int64)
    opens = np.zeros(size, dtype=np.int64)  # open after the set S is taken, + 1
    worst[0], total[0] = 0, 0
    for S in range(size):  # (every subset of S comes before S)
        for u in range(M):
            if (S >> u) & 1 and adjacent[u] & ~S & everything:
                opens[S] += 1
        w = opens[S] + 1  # open while the next vertex's strings are placed
        for v in range(M):
            if (S >> v) & 1:
                continue
            T = S | (1 << v)
            most, spent = max(worst[S], w), total[S] + (np.int64(1) << w)
            if most < worst[T] or (most == worst[T] and spent < total[T]):
                worst[T], total[T], back[T] = most, spent, v
    given_most, S = 0, 0
    for v in np.argsort(given):
        given_most = max(given_most, opens[S] + 1)
        S |= 1 << v
    if given_most <= worst[everything] + 1:
        return given.copy()
    rank = np.zeros(M, dtype=np.int64)
    S = everything
    for r in range(M - 1, -1, -1):
        v = back[S]
        rank[v] = r
        S &= ~(1 << v)
    return rank


# the bytes the layers of one :func:`tight_count` may hold at once (beyond it, a layer is made in buckets; with
# copies, at most 4/3 of it): a count on 2 workers then peaks within 2 GiB (benchmarks/PROFILE.md section 40)
LAYER_BYTES = 256 * 2**20


@njit(cache=True)
def _tight_frame(M, a_end, b_end, least, parallel, k, C, l, x_most, g, given, links):
    """What :func:`tight_count`'s programme needs of each bundle, the same for every state."""
    E = len(a_end)
    Q = 3 if len(links) else 1  # a set's values: one, or by the links it holds (0, 1, 2 or more)
    X1 = x_most + 1  # a state's total: Σ d · X1 + Σ x
    full = -l  # the most Σ d of a placement
    for v in range(M):
        full += k[v]
    starts = np.zeros(E, dtype=np.int64)  # the bundles the game sees: strings starts[i] … ends[i] − 1
    ends = np.zeros(E, dtype=np.int64)
    bundle = np.full(E, -1, dtype=np.int64)  # of the first string of each
    outside = np.zeros(X1, dtype=np.int64)  # ways[y] the bundles the game never sees hold y of excess
    outside[0] = 1
    spare = np.zeros(X1, dtype=np.int64)
    lows = np.zeros(E, dtype=np.int64)
    held = np.zeros((C * E + 1, X1, Q), dtype=np.int64)
    nb = 0
    e = 0
    while e < E:
        f = e
        e += 1
        while e < E and parallel[e] >= 0:
            e += 1
        if a_end[f] >= 0:
            starts[nb], ends[nb] = f, e
            bundle[f] = nb
            nb += 1
            continue
        s = 1  # a bundle the game never sees: its cycle under g, once (at its first string)
        lowest = f
        if len(g):
            j = g[f]
            while j != f:
                lowest = min(lowest, j)
                j = g[j]
                s += 1
        if lowest < f:
            continue
        for x in range(e - f):
            lows[x] = least[f] if x == 0 else max(least[f + x], parallel[f + x])
        if given.shape[0]:
            held[0, :, 0] = given[f, 0, :X1, 0]
        else:
            _bundle_deficits(C, lows[:e - f], False, x_most, held)
        spare[:] = 0  # outside ← outside × (the bundle's ways, each y taken s times)
        for y in range(X1):
            for z in range(0, X1 - y, s):
                spare[y + z] += outside[y] * held[0, z // s, 0]
        outside[:] = spare
    last = np.full(M, -1, dtype=np.int64)  # the last bundle at each vertex
    room_after = np.zeros(nb + 1, dtype=np.int64)  # the most deficit bundles i … can take
    for i in range(nb - 1, -1, -1):
        a, b = a_end[starts[i]], b_end[starts[i]]
        for v in (a, b):
            if last[v] < 0:
                last[v] = i
        pair = k[a] + k[b] - l if Q == 1 or (links[a] and links[b]) else C * E  # (one with a joint: < 2 links)
        room_after[i] = room_after[i + 1] + min(C * (ends[i] - starts[i]), pair)
    # with g: the slot in the state that holds the (t, y) of bundle i's cycle while the cycle is partly placed,
    # kept by its first bundle (keep), read by the others (same), freed by its last (free)
    keep = np.full(nb, -1, dtype=np.int64)
    same = np.full(nb, -1, dtype=np.int64)
    free = np.zeros(nb, dtype=np.bool_)
    P = 0
    if len(g):
        busy = np.zeros(nb, dtype=np.bool_)
        for i in range(nb):
            lo, hi, j = i, i, bundle[g[starts[i]]]
            while j != i:
                lo, hi, j = min(lo, j), max(hi, j), bundle[g[starts[j]]]
            if lo == hi:
                continue
            if i == lo:
                slot = 0
                while busy[slot]:
                    slot += 1
                busy[slot] = True
                keep[i] = slot
                P = max(P, slot + 1)
            else:
                same[i] = keep[lo]
                if i == hi:
                    free[i] = True
                    busy[keep[lo]] = False
    # the frame of each bundle, the same for every state: the positions it opens (the vertices met for the
    # first time, a then b) and their k, the sets holding both ends, the positions it closes (highest first)
    position = np.full(M, -1, dtype=np.int64)  # of an open vertex among the open ones; −1 before, −2 after
    opens = np.full((nb, 2), -1, dtype=np.int64)
    open_k = np.zeros((nb, 2), dtype=np.int64)
    open_link = np.zeros((nb, 2), dtype=np.int64)  # with Q > 1: whether the vertex opened is a link
    both = np.zeros(nb, dtype=np.int64)
    shut = np.full((nb, 2), -1, dtype=np.int64)
    n_open = np.zeros(nb + 1, dtype=np.int64)  # open after bundle i − 1's closing (n_open[0] = 0)
    widest = 0
    for i in range(nb):
        a, b = a_end[starts[i]], b_end[starts[i]]
        now = n_open[i]
        for x in range(2):
            v = a if x == 0 else b
            if position[v] == -1:
                position[v] = now
                opens[i, x], open_k[i, x] = now, k[v]
                open_link[i, x] = links[v] if Q > 1 else 0
                now += 1
        widest = max(widest, now)
        both[i] = (1 << position[a]) | (1 << position[b])
        shut0 = position[a] if last[a] == i else -1
        shut1 = position[b] if last[b] == i else -1
        if shut0 < shut1:
            shut0, shut1 = shut1, shut0
        shut[i, 0], shut[i, 1] = shut0, shut1
        n_open[i + 1] = now - (shut0 >= 0) - (shut1 >= 0)
        for p in (shut0, shut1):
            if p >= 0:
                for v in range(M):
                    if position[v] == p:
                        position[v] = -2
                    elif position[v] > p:
                        position[v] -= 1
    W = Q << widest  # a state's values: set U's class c at U·Q + c
    # the ways of each bundle's weights to give t units of deficit, y of excess and bring z links
    ways = np.zeros((nb, C * E + 1, X1, Q), dtype=np.int64)
    for i in range(nb):
        f, r = starts[i], ends[i] - starts[i]
        if given.shape[0]:
            ways[i, :C * r + 1] = given[f, :C * r + 1, :X1, :Q]
        else:
            for x in range(r):
                lows[x] = least[f] if x == 0 else max(least[f + x], parallel[f + x])
            _bundle_deficits(C, lows[:r], True, x_most, ways[i])
    # a state's values lie in [−(Σ k + 2 max k + 1), 0] and its kept (t, y, z) in [0, (C·E·X1 + x_most + 1)·Q): 16 bits
    kmax = 0
    for v in range(M):
        kmax = max(kmax, k[v])
    if full + l + 2 * kmax + 1 > 32767 or (C * E * X1 + x_most + 1) * Q > 32767:
        raise ValueError("tight_count: a state's values pass 16 bits (a game of more than 10^4 pebbles)")
    return (nb, X1, full, outside, room_after, keep, same, free, opens, open_k, open_link, both, shut, n_open, starts,
            ends, ways, W, P)


@njit(cache=True)
def _tight_total(totals, ways_in, n, outside, X1, full, x_most):
    """The placements the states 0 … n − 1 of the last layer stand for: the prefixes reaching each, times the ways
    the strings the game never sees hold the excess still missing."""
    found = 0
    for s in range(n):
        y = totals[s] // X1 - full + x_most - totals[s] % X1
        if 0 <= y <= x_most:
            found += ways_in[s] * outside[y]
    return found


@njit(cache=True)
def _row_bytes(W, P):
    """What a state costs the budget: its values, its total and ways, and the most the hash table takes a state
    (:func:`_rehash` makes at most 8 slots a state, of 8 bytes; one growth holds 2 + 4 a state while it is made)."""
    return 2 * (W + P) + 8 + 8 + 64


@njit(cache=True)
def _tight_whole(M, a_end, b_end, least, parallel, k, C, l, x_most, g, given, links, budget):
    """:func:`tight_count` with every layer whole: the count and −1; or, where a layer would pass the budget, 0,
    its index i and layer i (states, totals, ways, number), for :func:`_tight_split` to go on from (the part of
    layer i + 1 made so far let go: made again in buckets, it costs a part of one pass)."""
    (nb, X1, full, outside, room_after, keep, same, free, opens, open_k, open_link, both, shut, n_open, starts, ends,
     ways, W, P) = _tight_frame(M, a_end, b_end, least, parallel, k, C, l, x_most, g, given, links)
    Q = ways.shape[3]
    row_bytes = _row_bytes(W, P)
    states = np.zeros((1, W + P), dtype=np.int16)
    states[0, 1:Q] = -l - full - 1  # no set yet holds a link: below the floor (never matters)
    totals = np.zeros(1, dtype=np.int64)
    ways_in = np.ones(1, dtype=np.int64)
    n = 1
    row = np.zeros(W + P, dtype=np.int64)
    for i in range(nb):
        T = C * (ends[i] - starts[i])
        cap = max(2 * (T + 1) * X1 * Q, (budget - n * row_bytes) // row_bytes)
        m, stop, new_states, new_totals, new_ways, _ = _tight_layer(
            states, totals, ways_in, 0, n, np.zeros((0, W + P), dtype=np.int16), np.zeros(0, dtype=np.int64),
            np.zeros(0, dtype=np.int64), 0, np.full(128, -1, dtype=np.int64), cap, 0, 0, opens[i], open_k[i],
            open_link[i], both[i], shut[i], n_open[i + 1], ways[i], T, keep[i], same[i], free[i], room_after[i + 1],
            full, l, x_most, W, P, row)
        if stop < n:
            return 0, i, states, totals, ways_in, n
        states, totals, ways_in, n = new_states, new_totals, new_ways, m
    return _tight_total(totals, ways_in, n, outside, X1, full, x_most), -1, states, totals, ways_in, n


def tight_count(M, a_end, b_end, least, parallel, k, C, l, x_most, g, given, budget=None, links=None):
    """The placements :func:`place` counts with no edge permutation, counted without visiting them;
    or, with a permutation ``g`` of the strings (a row of :func:`place`'s ``group``: bundles to
    bundles, each read in order), those of them that ``g`` leaves unchanged: Fix(g) of Burnside's
    lemma.  ``x_most`` is :func:`place`'s excess bound: 0 in the rule's equality case (every long
    string exactly at h − 1 = C binary links, every never-short string at its least: e.g. 1-DOF
    chains), W − threshold above it.

    Such a placement is a choice of deficit d_e = C − w_e on each short string between two of the
    game's vertices such that the multigraph D holding each string d_e times is (k, l)-sparse —
    every set X of vertices holds at most Σ_X k − l (docs/theory.md) — and of the excess
    w_e − C on the long ones (and w_e − least on the strings the game never sees) such that
    Σ w = n2: the excess X and D then satisfy X − D = x_most − (Σ k − l), so D lies between
    Σ k − l − x_most and Σ k − l (tight where x_most = 0).  The bundles of parallel strings are
    taken one after the other (as :func:`place` takes them); a bundle adds t units of deficit on one
    pair a–b and y of excess, in as many ways as its non-decreasing weights give (t, y)
    (:func:`_bundle_deficits`).  A vertex is *open* from its first bundle to its last; the state
    after a bundle is, for every set U of open vertices, the most that i(U ∪ Z) − k·|U ∪ Z| reaches
    over the sets Z of closed vertices, with Σ d and Σ x so far.  A bundle on a–b adds t to the
    sets that hold both and is allowed where none of them then exceeds −l (a set that holds no new
    unit was checked before); closing a vertex keeps the larger of a set with and without it.
    Values below −l less the deficit still to come can never matter and are raised to one level,
    so placements whose prefixes differ there share a state.  The count is the sum, over the
    states of the last layer, of the placements that reach each times the ways the strings the
    game never sees hold the excess still missing.  With ``g``, the first bundle of each cycle of g
    keeps its (t, y) in the state until the last, and every other bundle of the cycle must take
    the same weights (in one way); a cycle of s bundles the game never sees takes s times one
    bundle's excess.

    With ``links`` (whether each vertex is a link, 1, or a multiple joint, 0; ``k`` then h and h − 1) the rule is
    the exact sub-chain test instead: only the sets holding two links or more are checked, a set's links being its
    link vertices and the binary links its short strings (w ≤ C) bring.  Each set's value is then kept three times,
    the most over the sets U ∪ Z with at least 0, 1 and 2 links; a bundle bringing z links moves the sets holding
    both its ends up z classes, opening a link moves its sets up one, and a bundle is refused where a set of the
    last class would pass −l (docs/theory.md; :func:`synth.synthesis.stage_b._programme_fault` says where this is
    the exact test).

    ``least``, ``parallel``, ``a_end``, ``b_end``, ``k``, ``C``, ``l``, ``M`` as :func:`place`, the
    strings in bundles whole; 0 ≤ l < 2k, M ≥ 2, x_most ≥ 0; ``g`` empty for every placement.
    ``given``: an empty array, or per string (rows) the ways[t, y, z] of the bundle it begins, found
    elsewhere, in place of :func:`_bundle_deficits` (the second count,
    :func:`synth.synthesis.stage_b.count_reversed`).  The states of a layer are a few hundred where
    :func:`place` visits 10⁴–10⁵ placements (18 links, 1-DOF: at most 5 304), but tens of thousands of
    2^(open vertices) values each at h = 4…6 beyond 20 links (a worker of the 32-link count at h = 6 grew to
    4.2 GiB).  ``budget`` bounds the bytes the layers hold at once: a layer whose states would pass it is
    made in buckets by a hash of the state, each by a pass over the whole layer before it (:func:`_tight_split`:
    every state once, merged as in a whole layer; the work the layer's times its buckets).

    >>> import numpy as np
    >>> ends = np.array([0, 0, 1], dtype=np.int64), np.array([1, 2, 2], dtype=np.int64)  # a triangle
    >>> none, k = np.full(3, -1, dtype=np.int64), np.full(3, 3, dtype=np.int64)
    >>> nothing = np.zeros((0, 0, 0, 0), dtype=np.int64)
    >>> tight_count(3, *ends, np.zeros(3, dtype=np.int64), none, k, 2, 4, 0, none[:0], nothing)  # 5 units, ≤ 2 a pair
    3
    >>> tight_count(3, *ends, np.zeros(3, dtype=np.int64), none, k, 2, 4, 0, np.array([1, 0, 2]), nothing)  # d_0 = d_1
    1
    >>> tight_count(3, *ends, np.zeros(3, dtype=np.int64), none, k, 2, 4, 1, none[:0], nothing)  # or 4 units + 1 excess
    6
    >>> joint, k2 = np.array([1, 1, 0], dtype=np.int64), np.array([3, 3, 2], dtype=np.int64)  # vertex 2 a joint
    >>> tight_count(3, *ends, np.zeros(3, dtype=np.int64), none, k2, 2, 4, 0, none[:0], nothing)  # every set: (2, 1, 1)
    1
    >>> tight_count(3, *ends, np.zeros(3, dtype=np.int64), none, k2, 2, 4, 0, none[:0], nothing, links=joint)
    6
    >>> # (a link and the joint hold one link where their string is empty: (2, 2, 0), (0, 2, 2), (1, 2, 1) … pass)
    """
    budget = LAYER_BYTES if budget is None else budget
    links = np.zeros(0, dtype=np.int64) if links is None else np.asarray(links, dtype=np.int64)
    found, i, *handed = _tight_whole(M, a_end, b_end, least, parallel, k, C, l, x_most, g, given, links, budget)
    if i < 0:
        return int(found)
    frame = _tight_frame(M, a_end, b_end, least, parallel, k, C, l, x_most, g, given, links)
    return _tight_split(frame, C, l, x_most, budget, i, handed)


def _spill_file():
    """A file for a bucket that the budget keeps out of memory: unlinked at once (O_TMPFILE where it can), so
    nothing of it is left on disk once it is closed or the process ends, however it ends."""
    return tempfile.TemporaryFile(prefix="mechsynth-layer-")


class _Buckets:
    """The buckets of the programme's layers: in memory while they hold at most ``room`` bytes, the rest each in a
    file of its own (:func:`_spill_file`)."""

    def __init__(self, room, W, P):
        self.room, self.held, self.W, self.P, self.files = room, 0, W, P, set()

    def put(self, states, totals, ways, n):
        """Keep the first n states; a handle for :meth:`get`."""
        size = n * (2 * (self.W + self.P) + 16)
        if self.held + size <= self.room:
            self.held += size
            if len(totals) == n:
                return n, (states, totals, ways)
            return n, (states[:n].copy(), totals[:n].copy(), ways[:n].copy())
        f = _spill_file()
        self.files.add(f)
        for a in (states[:n], totals[:n], ways[:n]):
            np.ascontiguousarray(a).tofile(f)
        return n, f

    def get(self, bucket):
        """The states, totals and ways of a bucket (read back from its file if it has one)."""
        n, where = bucket
        if isinstance(where, tuple):
            return where
        where.seek(0)
        states = np.fromfile(where, dtype=np.int16, count=n * (self.W + self.P)).reshape(n, self.W + self.P)
        return states, np.fromfile(where, dtype=np.int64, count=n), np.fromfile(where, dtype=np.int64, count=n)

    def drop(self, bucket):
        n, where = bucket
        if isinstance(where, tuple):
            self.held -= n * (2 * (self.W + self.P) + 16)
        else:
            self.files.discard(where)
            where.close()

    def close(self):
        for f in self.files:
            f.close()
        self.files.clear()


def _tight_split(frame, C, l, x_most, budget, i, handed):
    """:func:`tight_count` on from layer i, whose successors passed the budget: ``handed`` is :func:`_tight_whole`'s
    layer i (the list emptied, so that the layer goes as soon as it is in buckets).  Each layer from there is made
    in buckets: a bucket is the states whose hash has given low bits (bits 32 … of :func:`_state_code`), made by one
    pass over every bucket of the layer before (read one at a time), keeping only the successors that fall in it,
    merged in its own table as in a whole layer.  A bucket is first every state; where it would pass a third of the
    budget it is cut in two by its next bit: the half with the bit set is put aside (with where the pass had got to)
    and made later, the other goes on.  So every state of a layer is in one bucket once, no bucket passes a third of
    the budget (or the successors of one state), and a layer costs as many passes as it has buckets.  A third of the
    budget for the bucket being made (its hash table counted), a third for one bucket read back, a third for the
    buckets held in memory; the others wait in unlinked files.  Beside them, for a moment, one copy of the bucket
    being made (grown from the one read back, or its half cut off): the layers hold at most 4/3 of the budget."""
    (nb, X1, full, outside, room_after, keep, same, free, opens, open_k, open_link, both, shut, n_open, starts, ends,
     ways, W, P) = frame
    Q = ways.shape[3]
    row = np.zeros(W + P, dtype=np.int64)
    store = _Buckets(budget // 3, W, P)
    pending = []  # the buckets of layer i + 1 to make: bits, their value, where the pass is, the states so far

    def cut(residue, bits, b, s, states, totals, ways_in, m):
        """Cut a bucket by its next bits until it has room for the successors of a state, the halves put aside
        (each cut the same way); the bits and number of states of what is left."""
        while m + each > cap:
            if bits == 30:
                raise RuntimeError("tight_count: a bucket of states alike in 30 bits of their hash")
            m, half = _split_bucket(states, totals, ways_in, m, bits, width, W, P)
            half_bits, half_m = cut(residue | 1 << bits, bits + 1, b, s, *half)
            pending.append((residue | 1 << bits, half_bits, b, s, store.put(*half[:3], half_m)))
            half = None  # (a half gone to a file let go before the next cut)
            bits += 1
        return bits, m

    states, totals, ways_in, n = handed
    handed.clear()
    try:
        layer = [store.put(states, totals, ways_in, n)]
        states = totals = ways_in = None
        while True:
            T = C * (ends[i] - starts[i])
            each = (T + 1) * X1 * Q  # the most successors of one state
            cap = max(budget // (3 * _row_bytes(W, P)), 4 * each)
            width = Q << n_open[i + 1]
            pending.append((0, 0, 0, 0, store.put(np.zeros((0, W + P), dtype=np.int16), np.zeros(0, dtype=np.int64),
                                                  np.zeros(0, dtype=np.int64), 0)))
            made = []
            while pending:
                residue, bits, b, s, part = pending.pop()
                new_states, new_totals, new_ways = store.get(part)
                m = len(new_totals)
                store.drop(part)
                part = None  # (the arrays the bucket grows from let go once it has grown)
                table = _rehash(new_states, new_totals, m, width, W, P)
                read, bucket = -1, None
                while b < len(layer):
                    if read != b:
                        bucket = None  # (the bucket before let go first)
                        read, bucket = b, store.get(layer[b])
                    m, s, new_states, new_totals, new_ways, table = _tight_layer(
                        *bucket, s, layer[b][0], new_states, new_totals, new_ways, m,
                        table, cap, (1 << bits) - 1, residue, opens[i], open_k[i], open_link[i], both[i], shut[i],
                        n_open[i + 1], ways[i], T, keep[i], same[i], free[i], room_after[i + 1], full, l, x_most, W, P,
                        row)
                    if s == layer[b][0]:
                        b, s = b + 1, 0
                    else:  # too many: cut in two by the next bit, one half put aside
                        table = None  # (let go before the kept half's is made)
                        bits, m = cut(residue, bits, b, s, new_states, new_totals, new_ways, m)
                        table = _rehash(new_states, new_totals, m, width, W, P)
                made.append(store.put(new_states, new_totals, new_ways, m))
                bucket = new_states = new_totals = new_ways = table = None  # (let them go before the next)
            for old in layer:  # layer i is through
                store.drop(old)
            layer = made
            i += 1
            if i == nb:
                return sum(int(_tight_total(*store.get(bucket)[1:], bucket[0], outside, X1, full, x_most))
                           for bucket in layer)
    finally:
        store.close()


@njit(cache=True)
def _split_bucket(states, totals, ways_in, m, bit, width, W, P):
    """Cut the states 0 … m − 1 of a bucket by bit ``bit`` of their hash's bucket bits: those without it stay, at
    the front; the number left, and the others (states, totals, ways, number)."""
    out = np.zeros(m, dtype=np.bool_)
    for j in range(m):
        out[j] = (_state_code(states[j], width, W, P, totals[j]) >> (32 + bit)) & 1
    moved = np.flatnonzero(out)
    half = states[moved], totals[moved], ways_in[moved], len(moved)  # (copies)
    kept = 0
    for j in range(m):
        if not out[j]:
            states[kept], totals[kept], ways_in[kept] = states[j], totals[j], ways_in[j]
            kept += 1
    return kept, half


@njit(cache=True)
def _tight_layer(states, totals, ways_in, lo, hi, new_states, new_totals, new_ways, m, table, cap, key_mask, key,
                 opens, open_k, open_link, both, shut, n_after, ways, T, keep, same, free, room_after, full, l, x_most,
                 W, P, row):
    """One bundle of :func:`tight_count` on the states ``lo`` … ``hi`` − 1 of a layer, adding their successors
    whose bucket bits (:func:`_state_code`) masked by ``key_mask`` are ``key`` to the m states of the next layer
    (``new_*``, hashed in ``table``; both grown as needed, the arrays up to ``cap`` rows).  Stops before a state
    whose successors might pass ``cap``: the next layer's states so far, their number, where it stopped (``hi``
    when through) and the arrays and table, which may be new.  With Q = ``ways.shape[2]`` classes a set U's values
    are ``U·Q + c``: the most over the sets with at least c links (the last class: the sets the rule checks)."""
    Q = ways.shape[2]
    for x in range(2):  # opening a vertex: the sets with it hold no unit at it yet (the same on a second pass)
        if opens[x] >= 0:
            bit = 1 << opens[x]
            for s in range(lo, hi):
                for U in range(bit):
                    for c in range(Q):
                        states[s, (U | bit) * Q + c] = states[s, U * Q + max(c - open_link[x], 0)] - open_k[x]
    n_open = n_after + (shut[0] >= 0) + (shut[1] >= 0)
    width = Q << n_after
    X1 = x_most + 1  # a state's total: Σ d · X1 + Σ x
    most = np.zeros(Q, dtype=np.int64)  # the largest value of a set holding a and b, by class
    for s in range(lo, hi):
        if m + (T + 1) * X1 * Q > cap:
            return m, s, new_states, new_totals, new_ways, table
        most[:] = -(1 << 60)
        for U in range(1 << n_open):
            if U & both == both:
                for c in range(Q):
                    most[c] = max(most[c], states[s, U * Q + c])
        for t in range(T + 1):
            d = totals[s] // X1 + t
            if (t > 0 and most[Q - 1] + t > -l) or d > full:
                break
            if d + room_after < full - x_most:
                continue
            for z in range(Q):  # the bundle brings z links to the sets holding a and b: those then checked
                if (t > 0 or z > 0) and most[max(Q - 1 - z, 0)] + t > -l:
                    break
                built = False
                for y in range(X1):
                    x = totals[s] % X1 + y
                    if x > min(x_most, d + room_after - full + x_most):  # (X − D = x_most − full at the end)
                        break
                    if ways[t, y, z] == 0 or (same >= 0 and (t * X1 + y) * Q + z != states[s, W + same]):
                        continue
                    if not built:  # the sets' values after t units and z links on a–b (the same for every y)
                        built = True
                        for U in range(1 << n_open):
                            for c in range(Q):
                                if U & both == both:
                                    row[U * Q + c] = states[s, U * Q + max(c - z, 0)] + t
                                else:
                                    row[U * Q + c] = states[s, U * Q + c]
                        span = 1 << n_open
                        for p in shut:
                            if p >= 0:  # close the vertex at position p: the larger of each set with and without it
                                span >>= 1
                                below = (1 << p) - 1
                                for U in range(span):
                                    at = (U & below) | ((U >> p) << (p + 1))
                                    for c in range(Q):
                                        row[U * Q + c] = max(row[at * Q + c], row[(at | (1 << p)) * Q + c])
                        floor = -l - (full - d) - 1
                        for U in range(width):
                            row[U] = max(row[U], floor)
                    row[W:] = states[s, W:]
                    if keep >= 0:
                        row[W + keep] = (t * X1 + y) * Q + z
                    if free:
                        row[W + same] = 0
                    total = d * X1 + x
                    code = _state_code(row, width, W, P, total)
                    if (code >> 32) & key_mask != key:  # another bucket's
                        continue
                    weight = ways_in[s] if same >= 0 else ways_in[s] * ways[t, y, z]  # (a cycle's weights: chosen once)
                    j = _state_slot(table, new_states, new_totals, row, width, W, P, total, code)
                    if j >= 0:
                        new_ways[j] += weight
                        continue
                    if 2 * (m + 1) > len(table):  # a larger table
                        table = _rehash(new_states, new_totals, m, width, W, P)
                        j = _state_slot(table, new_states, new_totals, row, width, W, P, total, code)
                    if m == len(new_totals):  # larger arrays: twice as large, or past 4 MiB the cap at once
                        grown = max(64, min(2 * m, cap))
                        if 2 * grown * (W + P) > 1 << 22:  # (left empty: the pages are taken as rows are written)
                            grown = cap
                        more = np.empty((grown, W + P), dtype=np.int16)
                        more[:m] = new_states[:m]
                        new_states = more
                        more_totals, more_ways = np.empty(grown, dtype=np.int64), np.empty(grown, dtype=np.int64)
                        more_totals[:m], more_ways[:m] = new_totals[:m], new_ways[:m]
                        new_totals, new_ways = more_totals, more_ways
                    table[-j - 1] = m
                    for U in range(width):
                        new_states[m, U] = row[U]
                    for U in range(W, W + P):
                        new_states[m, U] = row[U]
                    new_totals[m], new_ways[m] = total, weight
                    m += 1
    return m, hi, new_states, new_totals, new_ways, table
