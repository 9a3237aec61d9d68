"""Stage A's compiled kernel: the labelled branch multigraphs H of one code, enumerated depth first
pair by pair (numba), in batches.

The variables are those of stage A's CP-SAT model (synth/synthesis/stage_a.py): the number
x_uv of strings between each pair of branch vertices, row by row, and the loops y_u, which the
degree equation fixes once row u is complete.  The search keeps the model's conditions:

* degrees, the loops a vertex may carry, and the binary links the strings need (pairwise least
  weights and loops: at most n2);
* the sb*ℓ rows of vertices of one kind and degree in lexicographic order (Codish et al.), checked on every
  prefix of columns known for both rows, and whole when the later row is complete;
* the sub-chain conditions of stage B written on H: on sets of links they say that the
  multigraph holding ``cost_p`` units on each pair p of inner links is (h, h + threshold − slack)-
  sparse, where cost_p = (h − 1)·x_p − lb_p and slack = n2 − Σ lb (docs/theory.md).  While the
  search runs the slack can only shrink, so a (k, l)-pebble game with the current upper bound of
  the slack rejects only what the final rule rejects (a pebble-game rejection exhibits a set T
  over its bound); a complete multigraph is then checked exactly by a fresh game.  Where the final
  l is negative the game does not apply, and the row is marked for the caller's exact check.  The
  conditions on sets with multiple joints (with their touched-joint clause, not a sparsity) are
  checked on each complete multigraph (:func:`_joint_conditions_hold`);
* with ``least_budget`` (a count's stream and a listing's stage A), the least labelling of each
  class: every completed row prefix that a relabelling of equal vertices puts lexicographically
  first is dropped (:func:`_least_labelling`, docs/theory.md "The least labelling of H");
* connectivity (union–find) on each complete multigraph.

What is left to the caller: the isomorphism classes (nauty), fractionation and planarity.
:func:`multigraphs` returns after each batch of ``len(out)`` multigraphs with its state in
``state``, so a long enumeration is resumed batch by batch (bounded memory, Ctrl-C between
batches).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._stage_b_kernel import _accept, _take_back

__all__ = ["multigraphs", "new_state"]

# state slots (int64): depth, started, then per-depth arrays laid out by new_state
_DEPTH, _STARTED, _FIXED = 0, 1, 2


def new_state(pairs: int, vertices: int) -> np.ndarray:
    """A fresh search state for :func:`multigraphs`."""
    return np.zeros(_FIXED + 5 * pairs + 3 * vertices + vertices * vertices + 1, dtype=np.int64)


@njit(cache=True)
def _sparse(M, inner, pu, pv, x, cost_of, k, l, pebbles, arcs, seen, parent, stack):
    """Whether the cost units of x on the pairs of inner vertices are (k, l)-sparse (a fresh game)."""
    for i in range(M):
        pebbles[i] = k
        for j in range(M):
            arcs[i, j] = 0
    for p in range(len(pu)):
        a, b = inner[pu[p]], inner[pv[p]]
        if a < 0 or b < 0:
            continue
        for _ in range(cost_of[p, x[p]]):
            if not _accept(a, b, l, pebbles, arcs, seen, parent, stack):
                return False
    return True


@njit(cache=True)
def _joint_conditions_hold(m, pu, pv, x, cost_of, slack, within, links, joints, bound, reach, cost, ends):
    """Whether the complete multigraph x meets every sub-chain condition with multiple joints: condition c
    (vertex sets as bit masks: ``within`` all of T, ``links`` its links, ``joints`` its joints) fails where the
    strings inside T cost more than ``slack`` + ``bound[c]`` and every joint of T is on a string from a link of
    T (:meth:`synth.synthesis.stage_a._StringBounds.meet`, compiled).  ``reach`` (m), ``cost`` and ``ends``
    (pairs) are work arrays."""
    for u in range(m):
        reach[u] = 0
    n = 0
    for p in range(len(pu)):
        if x[p] > 0:
            reach[pu[p]] |= 1 << pv[p]
            reach[pv[p]] |= 1 << pu[p]
            if cost_of[p, x[p]] != 0:
                cost[n] = cost_of[p, x[p]]
                ends[n] = (1 << pu[p]) | (1 << pv[p])
                n += 1
    for c in range(len(within)):
        total = 0
        for i in range(n):
            if (ends[i] & within[c]) == ends[i]:
                total += cost[i]
        if total <= slack + bound[c]:
            continue
        touched = True
        for J in range(m):
            if (joints[c] >> J) & 1 and (reach[J] & links[c]) == 0:
                touched = False
                break
        if touched:
            return False
    return True


@njit(cache=True)
def _connected(m, pu, pv, x, root):
    """Whether the pairs with x > 0 join the m vertices into one part: union–find on an array, the
    compiled form of :class:`synth.structure.disjoint.DisjointSets` (numba compiles no dict-based class)."""
    for i in range(m):
        root[i] = i
    parts = m
    for p in range(len(pu)):
        if x[p] > 0:
            a = pu[p]
            while root[a] != a:
                a = root[a]
            b = pv[p]
            while root[b] != b:
                b = root[b]
            if a != b:
                root[a] = b
                parts -= 1
    return parts == 1


@njit(cache=True)
def _rows_ordered(A, u, w, last):
    """sb*ℓ: row u ≤ row w lexicographically (column w left out, the loops at column u), on the
    columns 0 … last; False only where row u is already greater."""
    for k in range(last + 1):
        if k == w:
            continue
        a = A[u, u] if k == u else A[u, k]
        b = A[w, w] if k == u else A[w, k]
        if a != b:
            return a < b
    return True


@njit(cache=True)
def _least_labelling(A, m, known, first, budget, img, start, choice):
    """Whether no relabelling of equal vertices puts the multigraph A (loops on the diagonal) lexicographically
    before itself, A read row by row along the upper triangle, each row from its diagonal: the order in
    which sb*ℓ is the least-labelling rule for each transposition of two equal vertices, so this rule
    and sb*ℓ together keep the least labelling of every class.  ``first[u]``: u starts a class of equal
    vertices (classes are runs of vertices).  Partition backtracking: position i is given each vertex
    its cell allows, row i of the relabelled A is the least the cells allow (each cell sorted) and is
    compared with row i of A — less: a smaller labelling exists (False); greater: that branch is left;
    equal: the cells are split by value and position i + 1 is next.  After ``budget`` nodes the answer
    is True (kept: the caller's nauty still tells classes apart), so only a labelling shown not least is
    dropped.  Only rows 0 … ``known`` − 1 need be complete (a prefix of the search): positions are then
    given only vertices of complete rows and rows from ``known`` on are not compared, so False still
    means that every completion has a smaller labelling.  ``img``, ``start`` (m × m) and ``choice`` (m)
    are work arrays."""
    for j in range(m):
        img[0, j] = j
        start[0, j] = first[j]
    i = 0
    choice[0] = -1
    nodes = 0
    while i >= 0:
        end = i + 1
        while end < m and start[i, end] == 0:
            end += 1
        choice[i] = i if choice[i] < i else choice[i] + 1
        while choice[i] < end and img[i, choice[i]] >= known:
            choice[i] += 1
        if choice[i] >= end:
            i -= 1
            continue
        nodes += 1
        if nodes > budget:
            return True
        if i == m - 1:  # the last position: one vertex left, only its loops to compare
            a = img[i, choice[i]]
            if A[a, a] < A[i, i]:
                return False
            i -= 1
            continue
        for j in range(m):
            img[i + 1, j] = img[i, j]
            start[i + 1, j] = start[i, j]
        im = img[i + 1]
        st = start[i + 1]
        c = choice[i]
        t = im[i]
        im[i] = im[c]
        im[c] = t
        st[i + 1] = 1
        a = im[i]
        order = A[a, a] - A[i, i]
        s = i + 1
        while order == 0 and s < m:
            e = s + 1
            while e < m and st[e] == 0:
                e += 1
            for q in range(s + 1, e):  # insertion sort of the cell by A[a, ·]
                b = im[q]
                r = q
                while r > s and A[a, im[r - 1]] > A[a, b]:
                    im[r] = im[r - 1]
                    r -= 1
                im[r] = b
            for q in range(s, e):
                order = A[a, im[q]] - A[i, q]
                if order != 0:
                    break
            s = e
        if order < 0:
            return False
        if order > 0:
            continue
        if i + 1 >= known:  # equal as far as rows are known
            continue
        for q in range(i + 2, m):  # split the cells by value (the cell of i + 1 starts there already)
            if st[q] == 0 and A[a, im[q]] != A[a, im[q - 1]]:
                st[q] = 1
        i += 1
        choice[i] = -1
    return True


@njit(cache=True)
def multigraphs(m, deg, loops_most, loop_lb, pu, pv, lb_of, cost_of, inner, same, n2, k, l0, check, joint_sets,
                state, out_x, out_y, out_flag, least_budget=0):
    """Fill ``out_x``/``out_y`` with the next labelled multigraphs (pair multiplicities, loops) and
    ``out_flag`` with 1 where the caller must check the sub-chain conditions itself; returns how
    many were written (fewer than ``len(out_x)``: the enumeration is complete).

    ``lb_of[p, x]``/``cost_of[p, x]``: least binary links and sub-chain cost of x strings on pair p;
    ``inner[u]``: u's index among the inner links (−1 for others); ``same``: (u, w) pairs of
    vertices of one kind and degree (u < w) whose rows are ordered; ``l0`` = h + threshold (the game's l is l0 − slack);
    ``check``: whether the sub-chain conditions on sets of links apply (as pebble games); ``joint_sets``: the
    conditions on sets with multiple joints (rows: bit masks of T, of its links and of its joints, then its
    bound; none with simple joints), checked on each complete multigraph; ``least_budget`` > 0: each
    completed row prefix is kept only if :func:`_least_labelling` does not show it smaller within that
    many nodes (one labelling a class where the budget suffices, the least; the classes are the same).
    """
    P = len(pu)
    M = 0
    for u in range(m):
        if inner[u] >= 0:
            M += 1
    # the state: depth, started, x[P], top[P], added lb[P], units[P], loops lb[P] (added at depth), rem[m],
    # y[m], arcs (M × M, inner vertices), pebbles
    o = _FIXED
    x = state[o:o + P]
    top = state[o + P:o + 2 * P]
    added = state[o + 2 * P:o + 3 * P]
    units = state[o + 3 * P:o + 4 * P]
    loops_added = state[o + 4 * P:o + 5 * P]
    rem = state[o + 5 * P:o + 5 * P + m]
    y = state[o + 5 * P + m:o + 5 * P + 2 * m]
    arcs = state[o + 5 * P + 2 * m:o + 5 * P + 2 * m + m * m].reshape(m, m)
    pebbles = state[o + 5 * P + 2 * m + m * m:o + 5 * P + 2 * m + m * m + m]
    used = state[o + 5 * P + 2 * m + m * m + m:o + 5 * P + 2 * m + m * m + m + 1]  # binary links so far
    A = np.zeros((m, m), dtype=np.int64)
    seen = np.zeros(m, dtype=np.bool_)
    parent = np.zeros(m, dtype=np.int64)
    stack = np.zeros(m, dtype=np.int64)
    root = np.zeros(m, dtype=np.int64)
    fresh_pebbles = np.zeros(m, dtype=np.int64)
    fresh_arcs = np.zeros((m, m), dtype=np.int64)
    first = np.ones(m, dtype=np.int64)  # the classes of equal vertices, as runs (pairs of ``same``)
    for s in range(len(same)):
        if same[s, 1] == same[s, 0] + 1:
            first[same[s, 1]] = 0
    img = np.zeros((m, m), dtype=np.int64)
    start = np.zeros((m, m), dtype=np.int64)
    choice = np.zeros(m, dtype=np.int64)
    reach = np.zeros(m, dtype=np.int64)
    string_cost = np.zeros(P, dtype=np.int64)
    string_ends = np.zeros(P, dtype=np.int64)
    written = 0
    if state[_STARTED] == 0:
        state[_STARTED] = 1
        for u in range(m):
            rem[u] = deg[u]
            pebbles[u] = k
        used[0] = 0
        state[_DEPTH] = 0
        if P == 0:
            return 0
        x[0] = -1
        top[0] = min(rem[pu[0]], rem[pv[0]])
    depth = state[_DEPTH]
    # rebuild the adjacency of the current prefix
    for p in range(P):
        if p < depth or (p == depth and x[p] >= 0):
            A[pu[p], pv[p]] = x[p]
            A[pv[p], pu[p]] = x[p]
    for u in range(m):
        A[u, u] = y[u]
    while depth >= 0:
        p = depth
        u, v = pu[p], pv[p]
        a, b = inner[u], inner[v]
        if x[p] >= 0:  # take pair p back (and the rows it completed)
            for _ in range(units[p]):
                _take_back(a, b, pebbles, arcs)
            units[p] = 0
            rem[u] += x[p]
            rem[v] += x[p]
            used[0] -= added[p] + loops_added[p]
            added[p] = 0
            loops_added[p] = 0
            A[u, v] = 0
            A[v, u] = 0
        x[p] += 1
        if x[p] > top[p]:
            x[p] = -1
            depth -= 1
            continue
        xp = x[p]
        lb = lb_of[p, xp]
        rem[u] -= xp
        rem[v] -= xp
        used[0] += lb
        added[p] = lb
        A[u, v] = xp
        A[v, u] = xp
        if used[0] > n2:
            top[p] = xp  # more strings need more binary links
            continue
        ok = True
        # row u must still be completable: its last pairs and its loops take what is left
        if v < m - 1:
            room = 2 * loops_most[u]
            for w in range(v + 1, m):
                room += rem[w]
            if rem[u] > room:
                ok = False
        if ok and check and a >= 0 and b >= 0:
            l = l0 - (n2 - used[0])
            if l >= 0:
                for _ in range(cost_of[p, xp]):
                    if not _accept(a, b, l, pebbles, arcs, seen, parent, stack):
                        ok = False
                        break
                    units[p] += 1
        if ok and v == m - 1:  # row u is complete (and row m − 1 with the last pair)
            looped = 0
            for r in range(u, m if u == m - 2 else u + 1):
                if rem[r] % 2 != 0 or rem[r] // 2 > loops_most[r]:
                    ok = False
                    break
                y[r] = rem[r] // 2
                A[r, r] = y[r]
                looped += y[r] * loop_lb[r]
            if ok:
                used[0] += looped
                loops_added[p] = looped
                if used[0] > n2:
                    ok = False
            if ok:
                done = m - 1 if u == m - 2 else u  # rows 0 … done are complete
                for s in range(len(same)):
                    r1, r2 = same[s, 0], same[s, 1]
                    if r2 <= done:
                        if (r2 == u or r2 == done) and not _rows_ordered(A, r1, r2, m - 1):
                            ok = False
                            break
                    elif not _rows_ordered(A, r1, r2, min(done, r1 - 1)):
                        ok = False
                        break
                if ok and least_budget > 0:  # rows 0 … done already put a relabelling first: no completion is least
                    ok = _least_labelling(A, m, done + 1, first, least_budget, img, start, choice)
        if not ok:
            continue
        if p == P - 1:  # a complete multigraph
            if not _connected(m, pu, pv, x, root):
                continue
            flag = 0
            if check:
                l = l0 - (n2 - used[0])
                if l < 0:
                    flag = 1
                elif not _sparse(m, inner, pu, pv, x, cost_of, k, l, fresh_pebbles, fresh_arcs, seen, parent,
                                 stack):
                    continue
            if len(joint_sets) and not _joint_conditions_hold(
                    m, pu, pv, x, cost_of, n2 - used[0], joint_sets[:, 0], joint_sets[:, 1], joint_sets[:, 2],
                    joint_sets[:, 3], reach, string_cost, string_ends):
                continue
            out_x[written, :] = x
            out_y[written, :] = y
            out_flag[written] = flag
            written += 1
            if written == len(out_x):
                state[_DEPTH] = depth
                return written
            continue
        depth += 1
        x[depth] = -1
        top[depth] = min(rem[pu[depth]], rem[pv[depth]])
    state[_DEPTH] = -1
    return written
