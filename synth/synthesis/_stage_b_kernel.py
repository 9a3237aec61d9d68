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

* the set of all inner links is sparse too, so the excess X above h − 1 on long strings (and
  above the least weight on strings that are never short) is at most B0 + Σ k − l, where
  B0 = n2 − (h − 1)·(short-able strings) − (least weights of the others);
* X − D = B0 at the end, so the strings still to come must be able to carry the deficit D
  still missing (at most h − 1 each);
* the set of every vertex but one, x, is sparse: the strings at x carry at least
  −B0 − (Σ k − k_x − l) of the deficit (``vertex_need``).

With multiple joints two games run side by side, each a weaker rule that no valid placement
breaks, and the exact test decides among what both keep: in one a multiple joint J is a vertex of
h − 1 pebbles (its freedoms, as in the exact test: each of its links then costs h − 1) and l is
h + min(threshold, 0) — exact for the sets of two links or more up to the threshold, and never
wrong for the sets of fewer, which the rule leaves out (a link with joints on it alone, two joints
with one binary link between them); in the other J has h pebbles and l = h + threshold — exact
for the sets without multiple joints, one freedom weaker for each joint in a set.

Numba compiles the kernel once (cached beside this file, or in numba's user cache); loading it
takes about a second per process, so type synthesis uses it for large queries only
(:func:`synth.synthesis.stage_a.uses_kernel`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["place"]


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
def _lex_least(w, group):
    """Whether w is lexicographically least among its images w[g] under the rows of ``group``."""
    E = len(w)
    for g in range(group.shape[0]):
        for i in range(E):
            image = w[group[g, i]]
            if image != w[i]:
                if image < w[i]:
                    return False
                break
    return True


@njit(cache=True)
def place(M, a_end, b_end, least, parallel, n2, k, C, l, k2, l2, x_most, vertex_need, group, out):
    """Count the placements (and write the first ``len(out)`` into ``out``); see the module.

    M: pebble-game vertices (inner branch links, multiple joints); ``a_end[e]``, ``b_end[e]``: the
    ends of string e among them, −1 for a string that is never short (a loop, a string to a
    single-joint link); ``least[e]``: its least weight; ``parallel[e]``: −1, or the least weight of a
    string parallel to string e − 1 (then w_e ≥ w_{e−1} too); n2 binary links; ``k[v]`` the pebbles
    of vertex v and l the sparsity (and a second game ``k2``, ``l2`` where l2 ≥ 0); C the weight
    from which a string is long; ``x_most``,
    ``vertex_need[v]``: the bounds of the module's prunes; ``group``: edge permutations (rows).
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
    short_after = np.zeros(E + 1, dtype=np.int64)  # short-able strings e …
    B0 = n2
    for e in range(E - 1, -1, -1):
        least_after[e] = least_after[e + 1] + least[e]
        short_after[e] = short_after[e + 1] + (1 if a_end[e] >= 0 else 0)
        B0 -= C if a_end[e] >= 0 else least[e]
    at = np.zeros(M, dtype=np.int64)  # deficit on the strings of each vertex so far
    open_ = np.zeros(M, dtype=np.int64)  # short-able strings of each vertex not yet placed
    for e in range(E):
        if a_end[e] >= 0:
            open_[a_end[e]] += 1
            open_[b_end[e]] += 1
    w = np.zeros(E, dtype=np.int64)
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
        if x > x_most or x - B0 - d > C * short_after[e + 1]:
            top[e] = we  # a larger weight only raises both
            continue
        if a >= 0 and (at[a] + dd + C * (open_[a] - 1) < vertex_need[a]
                       or at[b] + dd + C * (open_[b] - 1) < vertex_need[b]):
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
        if not ok:
            continue
        if e == E - 1:
            if _lex_least(w, group):
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
