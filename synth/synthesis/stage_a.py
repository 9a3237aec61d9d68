"""Stage A of type synthesis: the branch multigraphs H of a code, once each.

Every chain contracts to a multigraph H on its *branch vertices* — links with 3+ joints and
joints with 3+ links — whose edges are the strings of binary links and simple joints between
them; the weight of an edge is its number of binary links.  H is a subdivision-equivalent of
the incidence graph, so chains are isomorphic exactly when their H's are isomorphic by a map
that keeps the weights: stage A lists the H of a code, stage B (:mod:`synth.synthesis.stage_b`)
the weights on each.

Stage A enumerates labelled multigraphs with the degree equations, the least weights of
parallel strings and loops, stage B's sub-chain conditions written on H and the sb*ℓ
lexicographic row constraints of Codish et al. between branch vertices of one kind and degree;
connectivity is checked on each solution and nauty removes the labelled copies that are left.
A large query (:func:`uses_kernel`) runs the compiled search of :mod:`synth.synthesis._stage_a_kernel`,
where the sub-chain conditions on sets of links are a pebble game and those with multiple joints are
checked on each complete multigraph; the others the plain search or one CP-SAT model per code.
Planarity and fractionation are properties of H (a subdivision keeps both), so they are decided once
per H.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property, lru_cache
from itertools import combinations
from operator import itemgetter
from typing import NamedTuple

import pynauty

from ..execution.memo import is_remembered, remembered
from ..structure.nauty_graph import NautyGraph
from ..structure.code import Code
from ..structure.disjoint import DisjointSets

__all__ = ["Conventions", "Contracted", "Vertex", "LINK", "JOINT", "contracted_graphs", "contracted_stream",
           "needs_solver", "uses_kernel", "kernel_loops"]

_GROUP_LIMIT = 4096  # enumerate the automorphism group of H up to this order
_LEX_BITS = 52  # keep lex-leader coefficients exact in CP-SAT's linear constraints
# Stage A writes the sub-chain conditions for sets T of at most this many links (default: all).
# h = 2 (wedge systems): H is nearly the chain itself (few binary links), and the 2^m conditions
# on its 9-10 branch links cost CP-SAT more than the units they save.  1-DOF, 10 links, one
# process: stage A 16.9 s -> 11.1 s, the whole query 27.6 s -> 23.6 s (33 765 units, not 25 384).
_STAGE_A_SET_LINKS = {2: 2}
# From _SPLIT_LINKS inner links on, stage A's model writes the sub-chain conditions of sets of at most
# _MODEL_SET_LINKS links and of the largest sets only, and the others are checked on its solutions.
_SPLIT_LINKS = 9
_MODEL_SET_LINKS = 3
_CONDITION_BLOCK = 512  # conditions checked at once on stage A's solutions
_CONDITION_BATCH = 4096  # labelled multigraphs stage A's kernel returns at once
# Stages A and B use the compiled kernels for codes of at least this many loops K (by motion space h; None: others)
_KERNEL_LOOPS = {2: 8, 3: 6, None: 5}
# Stage A of a code with at most this many branch vertices runs the plain search, not the CP-SAT model
_SEARCH_VERTICES = 8


@dataclass(frozen=True)
class Conventions:
    """Which chains count: sub-chain rule, fractionated chains, planar graphs only,
    required sub-structures ``cranks``: pairs (I, C) asking for a link with I joints that
    carries at least C cranks (binary links jointed to it), and the motion space ``h`` of
    the loops (W(S) = h(|S| − 1) − (h − 1)·p(S)).

    With ``prismatic`` (a range of prismatic pairs per chain) the revolute chains built are
    skeletons that ``slack`` wedge loops will raise: each sub-chain may lack up to ``slack``
    freedoms (its own wedge loops give them back), ``idle_joints`` keeps the assignments
    with joints that never move, and ``cylinders_only`` puts prismatic pairs between two binary
    links only (where every one of them must be a cylinder).  ``kernel_loops`` moves the size from
    which the compiled searches run (None: the engine's own, by motion space; the size estimator
    times small queries on the path the large one will take).
    """

    rigid_subchains: bool = False
    fractionated: bool = True
    planar_only: bool = False
    cranks: tuple[tuple[int, int], ...] = ()
    h: int = 3
    slack: int = 0
    prismatic: tuple[int, int | None] | None = None
    idle_joints: bool = False
    cylinders_only: bool = False
    kernel_loops: int | None = None

    @property
    def threshold(self) -> int:
        """Least W(S) allowed for a proper sub-chain S of a skeleton (every chain without slack)."""
        return (0 if self.rigid_subchains else 1) - self.slack


LINK, JOINT = "link", "joint"  # the two kinds of branch vertex


class Vertex(NamedTuple):
    """A branch vertex of H: a ``LINK`` with ``degree`` joints (3 or more; 1 for a single-joint
    link of an open chain), or a multiple ``JOINT`` of ``degree`` links (3 or more).

    Vertices sort joints first, then links, each by degree: the colour classes of H for nauty
    in that order, on which the certificates of H (and the unit keys of checkpoints) depend.

    >>> sorted([Vertex(LINK, 3), Vertex(JOINT, 4), Vertex(LINK, 1)])
    [Vertex(kind='joint', degree=4), Vertex(kind='link', degree=1), Vertex(kind='link', degree=3)]
    """

    kind: str
    degree: int

    @property
    def is_link(self) -> bool:
        return self.kind == LINK

    @property
    def is_joint(self) -> bool:
        return self.kind == JOINT


@dataclass(frozen=True)
class Contracted:
    """Branch-vertex multigraph H of a chain: ``vertices[u]`` is a :class:`Vertex` (a link and
    its joints, or a multiple joint and its links), ``edges`` its strings as vertex pairs."""

    vertices: tuple[Vertex, ...]
    edges: tuple[tuple[int, int], ...]
    certificate: str

    def _subdivided(self) -> pynauty.Graph:
        m = len(self.vertices)
        adjacency = {m + k: [u] if u == v else [u, v] for k, (u, v) in enumerate(self.edges)}
        return NautyGraph(m + len(self.edges), adjacency, _colour_cells(self.vertices, len(self.edges)))

    def edge_group(self) -> tuple[list[tuple[int, ...]], bool]:
        """Automorphisms of H acting on its edge list, and whether that is the whole group.

        The whole group (identity left out) if its order is at most 4096, else generators and
        their inverses.

        >>> Contracted((Vertex(LINK, 3), Vertex(LINK, 3)), ((0, 1), (0, 1), (0, 1)), "").edge_group()[1]
        True
        """
        m, e = len(self.vertices), len(self.edges)
        if e == 0:
            return [], True
        return _listed_group(self._subdivided(), m, e)

    def bundle_group(self) -> tuple[list[tuple[int, ...]], bool]:
        """The permutations of the bundles of parallel strings of H (numbered in the order of
        :attr:`edges`, which lists parallel strings next to each other) that its automorphisms
        make, each once, and whether that is all of them, as :meth:`edge_group` (identity left out).

        The automorphisms of H modulo the swaps of parallel strings among themselves: nauty on H
        with one vertex per bundle, coloured by its number of strings (every permutation of the
        bundles that keeps their ends and sizes is made by an automorphism of H, which takes the
        strings of a bundle in order).  Far smaller than :meth:`edge_group` where strings are
        parallel, and it is what stage B's lex-least test needs.

        >>> H = Contracted((Vertex(LINK, 4), Vertex(LINK, 4)), ((0, 1), (0, 1), (0, 1), (0, 1)), "")
        >>> H.bundle_group(), len(H.edge_group()[0])
        (([], True), 23)
        >>> Contracted((Vertex(LINK, 3),) * 2, ((0, 0), (0, 1), (1, 1)), "").bundle_group()
        ([(2, 1, 0)], True)
        """
        ends, sizes = [], []  # of each bundle: its two vertices, its strings
        for k, uv in enumerate(self.edges):
            if k and uv == self.edges[k - 1]:
                sizes[-1] += 1
            else:
                ends.append(uv)
                sizes.append(1)
        m, b = len(self.vertices), len(ends)
        if b < 2:
            return [], True
        cells: dict[int, set[int]] = {}
        for q, size in enumerate(sizes):
            cells.setdefault(size, set()).add(m + q)
        adjacency = {m + q: [u] if u == v else [u, v] for q, (u, v) in enumerate(ends)}
        colours = _colour_cells(self.vertices, 0)[:-1] + [cells[size] for size in sorted(cells)]
        return _listed_group(NautyGraph(m + b, adjacency, colours), m, b)


def _listed_group(graph: pynauty.Graph, m: int, e: int) -> tuple[list[tuple[int, ...]], bool]:
    """The automorphisms of ``graph`` (m vertices, then e more on which they are read), as
    permutations of those e, each once, identity left out: the whole group if its order is at most
    ``_GROUP_LIMIT``, else generators and their inverses (False)."""
    gens, size1, size2, _, _ = pynauty.autgrp(graph)
    identity, to_edge = tuple(range(e)), (-m).__add__  # vertex m + k is edge k
    gens = [g for g in (tuple(map(to_edge, g[m:])) for g in gens) if g != identity]
    if size1 * 10.0**size2 > _GROUP_LIMIT:
        return gens + [tuple(sorted(range(e), key=g.__getitem__)) for g in gens], False  # and inverses
    # closure under a -> a after g (b[k] = a[g[k]]); an itemgetter builds the tuple in C
    # (every g moves an edge, so e >= 2 and itemgetter returns a tuple)
    apply = [itemgetter(*g) for g in gens]
    group, frontier = {identity}, [identity]
    while frontier:
        nxt = []
        for a in frontier:
            for after in apply:
                b = after(a)
                if b not in group:
                    group.add(b)
                    nxt.append(b)
        frontier = nxt
    group.discard(identity)
    return sorted(group), True


@lru_cache(maxsize=256)
def _colour_cells(vertices: tuple[Vertex, ...], strings: int) -> list[set[int]]:
    """nauty's colour cells of the subdivided H: its vertices by kind and degree (:class:`Vertex`
    order), then the ``strings`` subdivision vertices; shared by every H of a code (read only)."""
    m = len(vertices)
    cells: dict[Vertex, set[int]] = {}
    for u, vertex in enumerate(vertices):
        cells.setdefault(vertex, set()).add(u)
    return [cells[k] for k in sorted(cells)] + [set(range(m, m + strings))]


def _branch_vertices(code: Code) -> tuple[Vertex, ...]:
    """Links with 3+ joints (most first), the single-joint links of an open chain (leaves of H),
    then the multiple joints (most links first)."""
    links = [Vertex(LINK, i) for i in range(len(code.assortment) + 1, 2, -1) for _ in range(code.count(i))]
    links += [Vertex(LINK, 1)] * code.n1
    comp = code.composition or ()
    joints = [Vertex(JOINT, k + 3) for k in range(len(comp) - 1, -1, -1) for _ in range(comp[k])]
    return tuple(links + joints)


def _inner_links(vertices) -> list[int]:
    """Branch links that can lower a sub-chain's W: a single-joint link (a leaf of H) with its
    string adds w + 1 ≥ 1, so the sets T of the sub-chain conditions leave leaves out."""
    return [u for u, vertex in enumerate(vertices) if vertex.is_link and vertex.degree > 1]


def _loop_lb(vertex: Vertex, conv: Conventions) -> int:
    """Fewest binary links on a closed string through one branch vertex."""
    # through a link: w links, w+1 joints, W = w − (h − 1); through a joint: W = w − h; and at least
    # 2: one binary link would be two joints between the same two links (or a link twice on a joint)
    return max(2, conv.h - 1 + conv.threshold) if vertex.is_link else max(2, conv.h + conv.threshold)


def uses_kernel(code: Code, conv: Conventions) -> bool:
    """Whether stage B places the binary links of ``code``'s units with the compiled kernel
    (:mod:`synth.synthesis._stage_b_kernel`, where it applies): loading it costs about a second per
    process, which the queries of at least ``_KERNEL_LOOPS`` loops (by motion space; one fewer with
    multiple joints) earn back many times (planar 14 links: stage B 10.5 → 1.5 CPU s), and smaller
    ones do not.

    >>> uses_kernel(Code.parse("4.10.0/0"), Conventions()), uses_kernel(Code.parse("48/0"), Conventions())
    (True, False)
    """
    return code.loops >= kernel_loops(conv, multiple=bool(code.v))


def kernel_loops(conv: Conventions, multiple: bool = False) -> int:
    """The least number of loops K from which :func:`uses_kernel` says yes (one fewer with
    multiple joints: more placements per chain).

    >>> kernel_loops(Conventions()), kernel_loops(Conventions(h=2)), kernel_loops(Conventions(), multiple=True)
    (6, 8, 5)
    """
    return (conv.kernel_loops or _KERNEL_LOOPS.get(conv.h, _KERNEL_LOOPS[None])) - (1 if multiple else 0)


def contracted_graphs(code: Code, conv: Conventions) -> list[Contracted]:
    """Stage A: every branch multigraph H of ``code`` (with composition), once each.

    >>> [c.edges for c in contracted_graphs(Code((4, 2), 0, ()), Conventions())]
    [((0, 1), (0, 1), (0, 1))]
    """
    if not _branch_vertices(code):
        return []
    if uses_kernel(code, conv) and _stage_a_kernel_applies(code, conv):
        return _contracted_by_kernel(code, conv)
    if _searched(code, conv):
        return _contracted_by_search(code, conv)
    return remembered("stage-a", _stored_as(code, conv), lambda: _contracted_by_model(code, conv),
                      encode=lambda graphs: [[[list(u) for u in g.vertices], [list(e) for e in g.edges], g.certificate]
                                             for g in graphs],
                      decode=lambda rows: [Contracted(tuple(Vertex(*u) for u in vs), tuple(map(tuple, es)), cert)
                                           for vs, es, cert in rows])


def _stored_as(code: Code, conv: Conventions) -> str:
    return repr((code.assortment, code.v, code.composition, code.n1, conv))


def needs_solver(code: Code, conv: Conventions) -> bool:
    """Whether stage A of ``code`` will build its CP-SAT model in this run (neither the kernel's
    search nor a result stored by an earlier run).

    >>> needs_solver(Code.parse("4/0"), Conventions())   # a single loop has no branch multigraph
    False
    """
    return (bool(_branch_vertices(code)) and not (uses_kernel(code, conv) and _stage_a_kernel_applies(code, conv))
            and not _searched(code, conv) and not is_remembered("stage-a", _stored_as(code, conv)))


def _contracted_by_model(code: Code, conv: Conventions) -> list[Contracted]:
    """Stage A's CP-SAT model of a code (the kernel's searches take the large ones)."""
    from ._cpsat import cp_model, each_solution  # loaded by the first query that needs a solver

    vertices = _branch_vertices(code)
    n2 = code.count(2)
    m = len(vertices)
    deg = [vertex.degree for vertex in vertices]
    model = cp_model.CpModel()
    pairs = list(combinations(range(m), 2))
    x = {(u, v): model.new_int_var(0, min(deg[u], deg[v]), f"x{u}_{v}") for u, v in pairs}
    # a loop at a link makes it a cut link of a closed chain; with single-joint links the closed part decides
    y = [model.new_int_var(0, deg[u] // 2 if conv.fractionated or code.n1 else 0, f"y{u}") for u in range(m)]
    for u in range(m):
        model.add(cp_model.LinearExpr.sum([x[min(u, v), max(u, v)] for v in range(m) if v != u]) + 2 * y[u] == deg[u])
    # weight lower bounds: parallel strings need binary links (the same rules as stage B)
    bounds = _StringBounds(vertices, pairs, code, conv)
    lbs = []
    for (u, v), var, a, b in zip(pairs, x.values(), bounds.slope, bounds.offset):
        lb = model.new_int_var(0, (conv.h - 1) * min(deg[u], deg[v]), f"lb{u}_{v}")
        model.add_max_equality(lb, [0, int(a) * var + int(b)])
        lbs.append(lb)
    loops_lb = sum(int(k) * y[u] for u, k in enumerate(bounds.loop))
    model.add(sum(lbs) + loops_lb <= n2)
    strong, later = _split_conditions(_subset_conditions(vertices, code.dof(conv.h), conv), vertices)
    _write_conditions(model, vertices, x, dict(zip(x, lbs)), loops_lb, n2, conv.h, strong)
    # connectivity is checked on each solution: a cut constraint for each of the 2^(m−1) sets holding
    # vertex 0 made every search step of CP-SAT slower than the few disconnected solutions it removed
    # sb*ℓ: rows of vertices of one colour (kind and degree) in lexicographic order (loops at their diagonal place)
    base = max(deg) + 1
    for u, v in pairs:
        if vertices[u] != vertices[v]:
            continue

        def row(a):
            out = []
            for k in range(m):
                if k == v:
                    continue
                out.append(y[a] if k == u else x[min(a, k), max(a, k)])
            return out

        # a prefix of the rows (exact coefficients); a lexicographic order implies it on any prefix
        L = min(m - 1, max(1, _LEX_BITS // base.bit_length()))
        ru, rv = row(u)[:L], row(v)[:L]
        weights = [base ** (L - 1 - i) for i in range(L)]
        model.add(cp_model.LinearExpr.weighted_sum(ru, weights) <= cp_model.LinearExpr.weighted_sum(rv, weights))
    distinct = _Distinct(vertices, pairs, bounds, later, conv)
    # branching on the rows in order, least value first, follows the lexicographic row constraints
    each_solution(model, [x[p] for p in pairs] + y, distinct.add, fixed_search=True)
    return distinct.graphs()


class _Distinct:
    """The labelled multigraphs a search finds (rows x_p …, y_u …), told apart by nauty: those that
    meet the sub-chain ``conditions`` left to them, are connected and kept by the conventions; of
    each class the first found, in the order of the certificates."""

    def __init__(self, vertices, pairs, bounds: "_StringBounds", conditions, conv: Conventions):
        self.vertices, self.pairs, self.bounds, self.conditions, self.conv = vertices, pairs, bounds, conditions, conv
        self.seen: dict[str, Contracted] = {}

    def add(self, batch: list[tuple[int, ...]]) -> None:
        import numpy as np

        pairs, m = self.pairs, len(self.vertices)
        sol = np.asarray(batch, dtype=np.int64)
        for row in sol[self.bounds.meet(sol[:, :len(pairs)], sol[:, len(pairs):], self.conditions)]:
            edges = []
            for (u, v), k in zip(pairs, row[:len(pairs)]):
                edges += [(u, v)] * int(k)
            for u, k in enumerate(row[len(pairs):]):
                edges += [(u, u)] * int(k)
            if not _connected(m, edges) or not _keep_multigraph(m, edges, self.conv):
                continue
            graph = Contracted(self.vertices, tuple(sorted(edges)), "")
            cert = pynauty.certificate(graph._subdivided()).hex()
            if cert not in self.seen:
                self.seen[cert] = Contracted(self.vertices, graph.edges, cert)

    def graphs(self) -> list[Contracted]:
        return [self.seen[c] for c in sorted(self.seen)]


def _searched(code: Code, conv: Conventions) -> bool:
    """Whether stage A of ``code`` runs the plain search (:func:`_contracted_by_search`) rather than
    the CP-SAT model: a code of few branch vertices, where the search costs about what the model
    does and a query of them then never loads OR-Tools (≈ 0.3 s with the pandas it imports)."""
    return len(_branch_vertices(code)) <= _SEARCH_VERTICES


def _contracted_by_search(code: Code, conv: Conventions) -> list[Contracted]:
    """Stage A without a solver: the model's labelled multigraphs listed depth first in its own
    order (the pairs' multiplicities row by row, least first), so the same classes with the same
    first representatives.

    The search keeps the degrees, the loops a vertex may carry, the binary links the strings need
    and the sb*ℓ rows of vertices of one colour in lexicographic order (a row is compared as soon
    as its first values are known); the sub-chain conditions, connectivity and the conventions
    are checked on each multigraph found.

    >>> code = Code.parse("4400/0")
    >>> _contracted_by_search(code, Conventions()) == _contracted_by_model(code, Conventions())
    True
    """
    vertices = _branch_vertices(code)
    m, n2 = len(vertices), code.count(2)
    deg = [vertex.degree for vertex in vertices]
    pairs = list(combinations(range(m), 2))
    bounds = _StringBounds(vertices, pairs, code, conv)
    slope, offset, loop_lb = bounds.slope.tolist(), bounds.offset.tolist(), bounds.loop.tolist()
    loops_most = [d // 2 if conv.fractionated or code.n1 else 0 for d in deg]
    last = {}  # the last pair of each vertex: its loops are fixed by its degree once that pair is chosen
    for k, (u, v) in enumerate(pairs):
        last[u] = last[v] = k
    closes: list[list[int]] = [[] for _ in range(len(pairs) + 1)]
    for u in range(m):
        closes[last.get(u, len(pairs))].append(u)  # a lone vertex (no pair) at the end
    # the values x_p (pair p) then y_u (at len(pairs) + u), as the model's variables; the rows the
    # model's sb*ℓ constraints compare, each value with the step after which it is known: after a step,
    # each comparison whose leading values are then known (a run from the first) is made on them
    P = len(pairs)
    at = {p: k for k, p in enumerate(pairs)}
    known = [k for k in range(P)] + [last.get(u, P) for u in range(m)]
    width = min(m - 1, max(1, _LEX_BITS // (max(deg) + 1).bit_length()))
    compare_after: list[list[tuple]] = [[] for _ in range(P + 1)]
    for u, v in pairs:
        if vertices[u] != vertices[v]:
            continue
        lower, upper = ([P + a if k == u else at[min(a, k), max(a, k)] for k in range(m) if k != v][:width]
                        for a in (u, v))
        ready = [max(known[i], known[j]) for i, j in zip(lower, upper)]
        for step in sorted(set(ready)):
            leading = next((n for n, when in enumerate(ready) if when > step), len(ready))
            compare_after[step].append(tuple(zip(lower, upper))[:leading])
    value, left = [0] * (P + m), list(deg)
    found: list[tuple[int, ...]] = []

    def close(step: int) -> bool:
        """The loops of the vertices whose last pair this was, and the rows' order so far."""
        for w in closes[step]:
            if left[w] % 2 or left[w] // 2 > loops_most[w]:
                return False
            value[P + w] = left[w] // 2
        for leading in compare_after[step]:
            for i, j in leading:
                if value[i] != value[j]:
                    if value[i] > value[j]:
                        return False
                    break
        return True

    def search(k: int, least: int) -> None:
        if k == P:
            if close(k) and least + sum(a * b for a, b in zip(loop_lb, value[P:])) <= n2:
                found.append(tuple(value))
            return
        u, v = pairs[k]
        for c in range(min(left[u], left[v]) + 1):
            lb = max(0, slope[k] * c + offset[k])
            if least + lb > n2:
                break  # the least weight grows with the multiplicity
            value[k] = c
            left[u] -= c
            left[v] -= c
            if close(k):
                search(k + 1, least + lb)
            left[u] += c
            left[v] += c
        value[k] = 0

    search(0, 0)
    distinct = _Distinct(vertices, pairs, bounds, _subset_conditions(vertices, code.dof(conv.h), conv), conv)
    if found:
        distinct.add(found)
    return distinct.graphs()


def _stage_a_kernel_applies(code: Code, conv: Conventions) -> bool:
    """Whether stage A's compiled kernel writes this code's conditions: two branch vertices or more
    and no exemption of the whole chain (then the sub-chain conditions of stage A on sets of links are
    the sparsity that its pebble game checks; those with multiple joints it checks on each complete
    multigraph, its vertex sets as bit masks: a query has at most 18 branch vertices)."""
    return len(_branch_vertices(code)) >= 2 and code.dof(conv.h) >= conv.threshold


def _mask(vertices) -> int:
    """A set of branch vertices as a bit mask.

    >>> _mask((0, 3))
    9
    """
    return sum(1 << u for u in vertices)


def _contracted_by_kernel(code: Code, conv: Conventions) -> list[Contracted]:
    """Stage A by the compiled kernel (:mod:`synth.synthesis._stage_a_kernel`): the same branch
    multigraphs as the CP-SAT model, from labelled ones found batch by batch and told apart by nauty,
    in the order of their certificates.  As a count's stream, the kernel hands on the least labelling of
    each class where its test shows it (:data:`_LEAST_BUDGET`), not the model's first: a listing's chains
    do not depend on which labelling of H they are placed on (each is renumbered canonically and sorted by
    certificate, :func:`~synth.synthesis.type_synthesis.run_unit`; docs/theory.md, "The least labelling of H")."""
    return sorted(_kernel_stream(code, conv, _LEAST_BUDGET), key=lambda graph: graph.certificate)


def contracted_stream(code: Code, conv: Conventions) -> Iterator[Contracted]:
    """Stage A for a count: every branch multigraph H of ``code`` once, the classes of
    :func:`contracted_graphs` in the order found, not sorted; where the compiled kernel runs, each is
    handed on as soon as nauty has told it apart, in its least labelling where the kernel's test shows
    it (one labelling a class reaches nauty, not tens to hundreds: :data:`_LEAST_BUDGET`), so what stays
    held is the set of certificates met (as bytes, the rows of the strings' vertices only: under 300 B an
    H at 20 links, against some 3 kB for the H themselves), never the code's H.

    >>> code, conv = Code.parse("662000/0"), Conventions()   # 14 links: the kernel's search
    >>> found = [g.certificate for g in contracted_stream(code, conv)]
    >>> len(found), sorted(found) == [g.certificate for g in contracted_graphs(code, conv)]
    (215, True)
    """
    if _branch_vertices(code) and uses_kernel(code, conv) and _stage_a_kernel_applies(code, conv):
        return _kernel_stream(code, conv, _LEAST_BUDGET)
    return iter(contracted_graphs(code, conv))


# nodes the kernel's test of a least labelling may take on one labelled H before keeping it (a count's stream and a
# listing's stage A alike)
_LEAST_BUDGET = 2000


def _kernel_stream(code: Code, conv: Conventions, least_budget: int = 0) -> Iterator[Contracted]:
    """The branch multigraphs of the compiled kernel's search, each once, in the order found (a class
    is represented by its first labelled multigraph, as in the CP-SAT model's order).  With
    ``least_budget`` the kernel drops labellings it shows are not the least of their class (a count's
    stream and a listing: the same classes, fewer labellings to certify, but a class may come with another
    labelling than the model's)."""
    import numpy as np

    from ._stage_a_kernel import multigraphs, new_state

    vertices = _branch_vertices(code)
    m, n2, h = len(vertices), code.count(2), conv.h
    deg = np.array([vertex.degree for vertex in vertices], dtype=np.int64)
    pairs = list(combinations(range(m), 2))
    bounds = _StringBounds(vertices, pairs, code, conv)
    most = int(deg.max())
    strings = np.arange(most + 1, dtype=np.int64)
    lb_of = np.maximum(0, bounds.slope[:, None] * strings[None, :] + bounds.offset[:, None])
    cost_of = (h - 1) * strings[None, :] - lb_of
    inner = np.full(m, -1, dtype=np.int64)
    for i, u in enumerate(_inner_links(vertices)):
        inner[u] = i
    loops_most = deg // 2 if conv.fractionated or code.n1 else np.zeros(m, dtype=np.int64)
    same = np.array([(u, v) for u, v in pairs if vertices[u] == vertices[v]], dtype=np.int64).reshape(-1, 2)
    conditions = _subset_conditions(vertices, code.dof(h), conv)
    # the pebble game is the conditions on sets of links (every set of 3+ inner links, or none at h = 2, where
    # the sets stop at 2 links; a pair is within its least weights); those with multiple joints (whose joints
    # must be on a string from a link of T) are checked on each complete multigraph, in the kernel
    of_links = [c for c in conditions if not c[1]]
    joint_sets = np.array([(_mask(TL + TJ), _mask(TL), _mask(TJ), bound) for TL, TJ, bound in conditions if TJ],
                          dtype=np.int64).reshape(-1, 4)
    pu, pv = np.array(pairs, dtype=np.int64).reshape(-1, 2).T.copy()
    state = new_state(len(pairs), m)
    out_x = np.zeros((_CONDITION_BATCH, len(pairs)), dtype=np.int64)
    out_y = np.zeros((_CONDITION_BATCH, m), dtype=np.int64)
    flags = np.zeros(_CONDITION_BATCH, dtype=np.int64)
    # nauty's certificates met, as bytes, and of them only the rows of the strings' vertices: the canonical
    # labelling keeps the colour cells in place (the m branch vertices first) and every edge of the
    # subdivided H has a string's vertex at one end, so those rows are the whole graph (20 links: 168 of
    # 272 bytes) — exact, no object per H
    seen: set[bytes] = set()
    while True:
        found = multigraphs(m, deg, loops_most, bounds.loop, pu, pv, lb_of, cost_of, inner, same, n2, h,
                            h + conv.threshold, bool(of_links), joint_sets, state, out_x, out_y, flags,
                            least_budget)
        X, Y = out_x[:found], out_y[:found]
        keep = np.ones(found, dtype=bool)
        marked = np.flatnonzero(flags[:found])
        if len(marked):  # the slack is too large for a pebble game: the conditions on sets of links by the numbers
            keep[marked] = bounds.meet(X[marked], Y[marked], of_links)
        for row_x, row_y in zip(X[keep].tolist(), Y[keep].tolist()):
            edges = [p for p, k in zip(pairs, row_x) if k for _ in range(k)]
            edges += [(u, u) for u, k in enumerate(row_y) if k for _ in range(k)]
            if not _keep_multigraph(m, edges, conv):
                continue
            edges.sort()
            graph = Contracted(vertices, tuple(edges), "")
            cert = pynauty.certificate(graph._subdivided())
            rows = cert[m * (len(cert) // (m + len(edges))):]
            if rows not in seen:
                seen.add(rows)
                yield Contracted(vertices, graph.edges, cert.hex())
        if found < _CONDITION_BATCH:
            return


class _StringBounds:
    """Least binary links on the strings of H, as numbers (for solutions) and coefficients (for the
    model): k parallel strings between u and v need max(0, slope·k + offset), a loop at u needs
    ``loop[u]`` per loop.

    All strings between two links, all taken: W = h + Σ w − k(h − 1), so Σ w ≥ (h − 1)k − h + threshold
    (the whole chain's W instead where it is below the threshold: the whole chain is exempt); between
    two joints W = Σ w − h − (h − 1)(k − 2) ≥ min(threshold, 0, W); from a link to a joint one binary
    link per string after the first (two joints never join the same links).
    """

    def __init__(self, vertices, pairs, code: Code, conv: Conventions):
        import numpy as np

        h = conv.h
        least = min(conv.threshold, code.dof(h))  # what the strings between two links keep, whole chain or not
        slope, offset = [], []
        for u, v in pairs:
            same = vertices[u].kind == vertices[v].kind
            slope.append(h - 1 if same else 1)
            offset.append((-h + least if vertices[u].is_link else -h + 2 + min(least, 0)) if same else -1)
        self.slope, self.offset = np.array(slope, dtype=np.int64), np.array(offset, dtype=np.int64)
        self.loop = np.array([_loop_lb(vertex, conv) for vertex in vertices], dtype=np.int64)
        self.pairs, self.n2, self.h = pairs, code.count(2), h

    def meet(self, X, Y, conditions) -> "np.ndarray":
        """Which solutions (pair multiplicities X, loops Y) meet every sub-chain condition of
        ``conditions`` (:func:`_subset_conditions`), as the model would have written them."""
        import numpy as np

        ok = np.ones(len(X), dtype=bool)
        if not conditions or not len(X):
            return ok
        lb = np.maximum(0, X * self.slope + self.offset)
        cost = ((self.h - 1) * X - lb).astype(np.float32)
        slack = self.n2 - lb.sum(axis=1) - Y @ self.loop
        index = {p: k for k, p in enumerate(self.pairs)}
        u, v = np.array(self.pairs, dtype=np.int64).reshape(-1, 2).T
        for start in range(0, len(conditions), _CONDITION_BLOCK):
            block = conditions[start:start + _CONDITION_BLOCK]
            masks = np.array([sum(1 << w for w in TL + TJ) for TL, TJ, _ in block], dtype=np.int64)
            inside = ((masks[:, None] >> u) & (masks[:, None] >> v) & 1).astype(np.float32)
            limit = np.array([bound for *_, bound in block], dtype=np.float32)
            violated = cost @ inside.T > slack[:, None] + limit[None, :]
            for c, (TL, TJ, _) in enumerate(block):
                for J in TJ:  # the condition holds where every joint of T is on a string from a link of T
                    violated[:, c] &= X[:, [index[min(J, L), max(J, L)] for L in TL]].sum(axis=1) >= 1
            ok &= ~violated.any(axis=1)
        return ok


def _subset_conditions(vertices, dof: int, conv: Conventions) -> list[tuple[tuple, tuple, int]]:
    """Stage B's sub-chain conditions as stage A writes them on H: ``(T_L, T_J, bound)`` for sets of
    inner links T_L with multiple joints T_J: the strings inside T may cost the rule at most
    bound + slack (see :func:`_write_conditions`).

    One link or two need a multiple joint to have a condition (simple joints: the pairwise
    bounds); a set of every link is left out where the whole chain is exempt (W below the threshold).
    """
    h = conv.h
    all_links = sum(1 for vertex in vertices if vertex.is_link)
    links = _inner_links(vertices)
    joints = [u for u, vertex in enumerate(vertices) if vertex.is_joint]
    out = []
    for size in range(1, min(len(links), _STAGE_A_SET_LINKS.get(h, len(links))) + 1):
        if size == all_links and dof < conv.threshold:
            break  # T would hold every link: maybe the whole chain, which is exempt
        for TL in combinations(links, size):
            for jsize in range(0 if size >= 3 else 1, len(joints) + 1):
                for TJ in combinations(joints, jsize):
                    # one link: S has two links or more only with a one-link string (W = 0 otherwise)
                    least = conv.threshold if size >= 2 else min(conv.threshold, 0)
                    out.append((TL, TJ, h * (size - 1) + (h - 1) * jsize - least))
    return out


def _split_conditions(conditions, vertices) -> tuple[list, list]:
    """The conditions stage A's model writes, and those checked on its solutions: the model has
    every condition of a code with fewer than _SPLIT_LINKS inner links, else the sets of at most
    _MODEL_SET_LINKS links and of every inner link but one or none (the strongest). The 2^m
    conditions of a code with 12–14 branch links slowed each CP-SAT step more than the labelled
    solutions the middle ones remove (16 links, 4.12.0.0.0.0.0/0: stage A 25 s against 7.7 s)."""
    inner = len(_inner_links(vertices))
    strong, later = [], []
    for condition in conditions:
        size = len(condition[0])
        in_model = inner < _SPLIT_LINKS or size <= _MODEL_SET_LINKS or size >= inner - 1
        (strong if in_model else later).append(condition)
    return strong, later


def _write_conditions(model, vertices, x, lbs, loops_lb, n2: int, h: int, conditions) -> None:
    """Stage B's sub-chain conditions (``_subset_constraint``) written on H, for sets T of branch
    vertices with 3+ links or a multiple joint: drops the H whose binary links are too few for every
    distribution (most of them, and the costliest: they are whole units of stage B).

    A string inside T with w < h − 1 binary links costs its condition h − 1 − w (planar: 2 for
    none, 1 for one), so the E_T strings inside T hold at least (h − 1)·E_T − bound(T) binary
    links; the other strings at least their pairwise bounds ``lbs``. The condition holds where
    stage B writes it: every joint of T on a string from a link of T (a bool per joint and set
    of links, ``touched``).
    """
    if not conditions:
        return  # (no slack or cost variables: free ones would only slow the search)
    touched: dict = {}

    def touches(J, TL):
        if (J, TL) not in touched:
            ends = [x[min(J, L), max(J, L)] for L in TL]
            t = touched[J, TL] = model.new_bool_var("")
            model.add(sum(ends) >= 1).only_enforce_if(t)
            model.add(sum(ends) == 0).only_enforce_if(t.negated())
        return touched[J, TL]

    # need + rest = Σ_inside ((h − 1)·x − lb) − bound + Σ_all lb: with a cost variable per pair and
    # the slack n2 − Σ_all lb − loops_lb, each condition holds only the pairs inside T
    slack = model.new_int_var(0, n2, "slack")
    model.add(slack == n2 - sum(lbs.values()) - loops_lb)
    cost = {}
    for p, lb in lbs.items():
        cost[p] = model.new_int_var(0, (h - 1) * min(vertices[p[0]].degree, vertices[p[1]].degree), f"c{p}")
        model.add(cost[p] == (h - 1) * x[p] - lb)
    for TL, TJ, bound in conditions:
        T = set(TL + TJ)
        inside = [p for p in x if p[0] in T and p[1] in T]
        model.add(sum(cost[p] for p in inside) <= slack + bound).only_enforce_if([touches(J, TL) for J in TJ])


def _connected(m: int, edges) -> bool:
    """Whether the multigraph on vertices 0 … m − 1 with ``edges`` is connected.

    >>> _connected(3, [(0, 1), (1, 1), (1, 2)]), _connected(3, [(0, 1), (2, 2)])
    (True, False)
    """
    joined = DisjointSets(range(m))
    return m - sum(joined.union(u, v) for u, v in edges) == 1


def _closed_core(edges) -> list[tuple[int, int]]:
    """The edges of H's closed part: vertices of degree 1 (single-joint links and what only
    they hold) pruned again and again; all of H for a closed chain.

    >>> _closed_core([(0, 1), (0, 1), (0, 1), (1, 2), (2, 3)])
    [(0, 1), (0, 1), (0, 1)]
    """
    edges = list(edges)
    while True:
        degree: dict[int, int] = {}
        for u, v in edges:
            degree[u] = degree.get(u, 0) + 1
            degree[v] = degree.get(v, 0) + 1
        kept = [(u, v) for u, v in edges if degree[u] > 1 and degree[v] > 1]
        if len(kept) == len(edges):
            return kept
        edges = kept


def _keep_multigraph(m: int, edges, conv: Conventions) -> bool:
    """Fractionation (of the closed part) and planarity of the chain, decided on H."""
    if conv.fractionated and not conv.planar_only:
        return True  # without importing networkx (0.1 s of a small query's start-up)
    if not conv.fractionated and is_fractionated_multigraph(edges):
        return False
    return not conv.planar_only or is_planar_multigraph(edges)


def is_fractionated_multigraph(edges) -> bool:
    """Whether every chain on the branch multigraph with ``edges`` is fractionated: its closed part's
    incidence graph (H with a vertex on every edge, two on a loop, is a subdivision of it) has a cut vertex.

    >>> is_fractionated_multigraph([(0, 1), (0, 1), (0, 1)]), is_fractionated_multigraph([(0, 0), (0, 1), (1, 1)])
    (False, True)
    """
    import networkx as nx

    core = nx.Graph()
    for k, (u, v) in enumerate(_closed_core(edges)):
        core.add_edges_from([(u, ("e", k)), (("e", k), ("f", k)), (("f", k), v)] if u == v
                            else [(u, ("e", k)), (("e", k), v)])
    return core.number_of_nodes() > 2 and not nx.is_biconnected(core)


def is_planar_multigraph(edges) -> bool:
    """Whether every chain on the branch multigraph with ``edges`` is planar (its incidence graph is a
    subdivision of H; loops and parallel strings do not change planarity).

    >>> is_planar_multigraph([(u, v) for u in range(3) for v in range(3, 6)])   # K3,3: the smallest non-planar H
    False
    """
    import networkx as nx

    return nx.check_planarity(nx.Graph([(u, v) for u, v in edges if u != v]))[0]


class BranchFacts:
    """Planarity and fractionation of the chains on one branch multigraph H, decided on H once, when first
    asked, for all of them (a listing shares one among a unit's chains: :meth:`Chain.is_planar` reads it).

    >>> facts = BranchFacts([(0, 1), (0, 1), (0, 1)]); facts.planar, facts.fractionated   # a theta: the six-bars' H
    (True, False)
    """

    def __init__(self, edges) -> None:
        self.edges = tuple(edges)

    @cached_property
    def planar(self) -> bool:
        return is_planar_multigraph(self.edges)

    @cached_property
    def fractionated(self) -> bool:
        return is_fractionated_multigraph(self.edges)
