"""A second, independent count of planetary gear trains, a tree at a time (test oracle).

:func:`tree_trains` / :func:`tree_census` count the trains on one link–axis tree given by its axes
(any numbering), holding only that tree's trains: the unit of the tree-by-tree comparison with the
engine (benchmarks/gears_two_methods_by_tree.py), which reaches 11 links.  :func:`census` adds the
trees of the brute force's list up, keeping one graph per rotation-graph class.

It shares no code with ``synth`` (nor with nauty): trees come from :mod:`gear_trains` (the brute
force's string canonical forms); the symmetries of a tree are listed by networkx's VF2 matcher
(the first ``_CAP`` of them; the star, whose symmetries are all permutations of its n − 1 gears,
has its trains counted as the unlabelled forests on those gears, see :func:`_star_trains`); mesh sets are grown in *another order* than the engine's (candidates
sorted by carrier first, then by their gears, from the last to the first; a numba loop with a
stack of slack tables) and kept when no listed symmetry maps them to a smaller set (a test that passes to every prefix, and that the least set
of each class passes, for any list of symmetries); where the list is not the whole group the
sets kept on a tree are told apart by VF2 within classes of a Weisfeiler–Lehman hash.  Rigid
sub-chains are found by counting, for every link set S, the meshes inside it against
3(|S| − 1) − 2·p(S) − 1.  Rotation graphs are told apart by their canonical form under bliss
(Junttila & Kaski's canonical labelling, through igraph — another program than nauty):
:func:`rotation_key`, checked in the tests against the pure-Python individualisation–refinement
form :func:`rotation_form` and under random renumberings of the links.

Example
-------
>>> census(1, 6)["displacement"], census(1, 6)["rotation"]
(81, 27)
"""

from __future__ import annotations

import itertools
from multiprocessing import Pool

import igraph
import networkx as nx
import numpy as np
from numba import njit
from networkx.algorithms.isomorphism import GraphMatcher

try:
    from . import gear_trains as brute
except ImportError:  # run as a top-level module
    import gear_trains as brute

__all__ = ["census", "tree_census", "tree_trains", "rotation_key", "rotation_form"]


# ------------------------------------------------------------------------ one tree
_CAP = 50_000  # symmetries of a tree listed for the pruning test


def _symmetries(links: int, axes) -> tuple[list[tuple[int, ...]], bool]:
    """Permutations of the links that map the tree onto itself (VF2 on the typed tree), at most
    ``_CAP``, and whether that is all of them."""
    g = nx.Graph()
    g.add_nodes_from(((("L", x), {"t": "L"}) for x in range(links)))
    for k, axis in enumerate(axes):
        g.add_node(("A", k), t="A")
        g.add_edges_from((("A", k), ("L", x)) for x in axis)
    matcher = GraphMatcher(g, g, node_match=lambda u, v: u["t"] == v["t"])
    out = []
    for m in matcher.isomorphisms_iter():
        if len(out) == _CAP:
            return out + _twin_swaps(links, axes), False
        out.append(tuple(m[("L", x)][1] for x in range(links)))
    return out, True


def _twin_swaps(links: int, axes) -> list[tuple[int, ...]]:
    """The exchanges of two links that each turn about the same single axis and nothing else."""
    axes_of = [[k for k, axis in enumerate(axes) if x in axis] for x in range(links)]
    out = []
    for x in range(links):
        for y in range(x + 1, links):
            if len(axes_of[x]) == 1 and axes_of[x] == axes_of[y]:
                perm = list(range(links))
                perm[x], perm[y] = y, x
                out.append(tuple(perm))
    return out


def _typed(graph: nx.Graph) -> tuple[str, nx.Graph]:
    """(Weisfeiler–Lehman hash, graph) of a graph whose nodes carry a type ``t`` and edges a kind ``k``."""
    return nx.weisfeiler_lehman_graph_hash(graph, node_attr="t", edge_attr="k", iterations=4), graph


def _same(g: nx.Graph, h: nx.Graph) -> bool:
    return nx.is_isomorphic(g, h, node_match=lambda u, v: u["t"] == v["t"], edge_match=lambda u, v: u["k"] == v["k"])


def _train_graph(links: int, axes, meshes) -> nx.Graph:
    g = nx.Graph()
    g.add_nodes_from(((("L", x), {"t": "L"}) for x in range(links)))
    for k, axis in enumerate(axes):
        g.add_node(("A", k), t="A")
        g.add_edges_from(((("A", k), ("L", x)) for x in axis), k="r")
    for k, (a, b) in enumerate(meshes):
        g.add_node(("M", k), t="M")
        g.add_edges_from(((("M", k), ("L", x)) for x in (a, b)), k="g")
    return g


def _forests(vertices: int, trees: int) -> list[list[tuple[int, int]]]:
    """Every forest of ``trees`` trees on ``vertices`` vertices up to isomorphism, as its edges on
    0 … vertices − 1: a multiset of unlabelled trees (networkx's list of non-isomorphic trees) for
    every partition of the vertices into ``trees`` sizes.

    >>> [len(_forests(6, k)) for k in (1, 2, 3)]
    [6, 6, 4]
    """
    def of_size(size):
        return [[]] if size == 1 else [sorted(tuple(sorted(e)) for e in t.edges()) for t in nx.nonisomorphic_trees(size)]

    def partitions(total, parts, largest):
        if parts == 0:
            yield from [()] if total == 0 else []
            return
        for size in range(min(largest, total - parts + 1), 0, -1):
            yield from (((size,) + rest) for rest in partitions(total - size, parts - 1, size))

    out = []
    for sizes in partitions(vertices, trees, vertices):
        groups = [(size, sum(1 for s in sizes if s == size)) for size in sorted(set(sizes), reverse=True)]
        for choice in itertools.product(*(itertools.combinations_with_replacement(of_size(size), count)
                                          for size, count in groups)):
            edges, first = [], 0
            for (size, _), chosen in zip(groups, choice):
                for tree in chosen:
                    edges += [(first + a, first + b) for a, b in tree]
                    first += size
            out.append(edges)
    return out


def _star_trains(links: int, hub: int = 0, dof: int = 1) -> list[tuple]:
    """Trains on the star (every other link on an axis of its own with the hub): every mesh has the
    hub as carrier and every permutation of the gears is a symmetry.  A cycle of meshes C locks
    (S = C + hub has W = 3|C| − 2|C| − |C| = 0) and a forest leaves every S a freedom, so the
    trains are the forests of n − 1 − F meshes on the n − 1 gears (F trees), one per unlabelled
    forest; for F ≥ 2 those that are not fractionated (the brute force's test) — the hub joins
    the trees only through itself, so none is.  For F = 1: the unlabelled spanning trees."""
    gears = [x for x in range(links) if x != hub]
    carriers = {(min(a, b), max(a, b)): hub for a, b in itertools.combinations(gears, 2)}
    trains = []
    for forest in _forests(links - 1, dof):
        meshes = [(gears[a], gears[b]) for a, b in forest]
        if dof == 1 or brute.non_fractionated(links, (), meshes, carriers):
            trains.append(tuple((a, b, hub) for a, b in meshes))
    return trains


def _slack_table(links: int, axes) -> np.ndarray:
    """slack(S) = 3(|S| − 1) − 2·p(S) − 1 for every link set S (a bit mask) of two links or more:
    the meshes S can still take without a rigid sub-chain; a large number for smaller sets."""
    subsets = np.arange(1 << links)
    member = (subsets[:, None] >> np.arange(links)) & 1
    size = member.sum(axis=1)
    p = sum(np.maximum(member[:, list(axis)].sum(axis=1) - 1, 0) for axis in axes)
    return np.where(size >= 2, 3 * (size - 1) - 2 * p - 1, 10**6).astype(np.int32)


@njit(cache=True)
def _is_least(chosen, depth, images) -> bool:
    """No listed symmetry maps the first ``depth`` chosen candidates to a lexicographically
    smaller sorted set."""
    moved = np.empty(depth, np.int64)
    for r in range(images.shape[0]):
        for j in range(depth):  # insertion sort of the image
            v = images[r, chosen[j]]
            k = j
            while k > 0 and moved[k - 1] > v:
                moved[k] = moved[k - 1]
                k -= 1
            moved[k] = v
        for j in range(depth):
            if moved[j] != chosen[j]:
                if moved[j] < chosen[j]:
                    return False
                break
    return True


@njit(cache=True)
def _grow(need, slack0, holding, images, out) -> int:
    """Every set of ``need`` candidates (ascending) that leaves every link set a freedom and that
    no listed symmetry maps to a smaller set; the first ``len(out)`` go to ``out``.  Returns how
    many there are (depth-first, a stack of slack tables instead of recursion)."""
    m = holding.shape[0]
    slack = np.empty((need + 1, slack0.shape[0]), np.int32)
    slack[0] = slack0
    chosen = np.empty(need, np.int64)
    start = np.zeros(need + 1, np.int64)  # the next candidate to try at each depth
    depth, found = 0, 0
    while depth >= 0:
        i = start[depth]
        if i > m - (need - depth):
            depth -= 1
            continue
        start[depth] = i + 1
        free = True
        for s in holding[i]:
            if slack[depth, s] < 1:
                free = False
                break
        if not free:
            continue
        chosen[depth] = i
        if not _is_least(chosen, depth + 1, images):
            continue
        if depth + 1 == need:
            if found < out.shape[0]:
                out[found] = chosen
            found += 1
            continue
        slack[depth + 1] = slack[depth]
        for s in holding[i]:
            slack[depth + 1, s] -= 1
        depth += 1
        start[depth] = i + 1
    return found


def tree_trains(dof: int, links: int, axes) -> list[tuple[tuple[int, int, int], ...]]:
    """The trains of mobility ``dof`` on one link–axis tree (its axes: any tree, numbered as the
    caller likes), one per displacement graph, each as its meshes (a, b, carrier).  Only this
    tree is held in memory: the unit of a tree-by-tree comparison.

    Example
    -------
    >>> len(tree_trains(1, 5, ((0, 1, 2), (0, 3), (1, 4))))
    2
    """
    hubs = set.intersection(*(set(a) for a in axes)) if axes else set()
    if links >= 4 and hubs and all(len(a) == 2 for a in axes):
        return _star_trains(links, hubs.pop(), dof)
    return _searched_trains(dof, links, axes)


def _searched_trains(dof: int, links: int, axes) -> list[tuple[tuple[int, int, int], ...]]:
    """:func:`tree_trains` by the search of mesh sets against the listed symmetries (any tree)."""
    pairs = brute.mesh_pairs(links, axes)  # {(a, b): carrier}
    order = sorted(pairs, key=lambda ab: (pairs[ab], ab), reverse=True)
    need = links - 1 - dof
    if len(order) < need:
        return []
    where = {ab: i for i, ab in enumerate(order)}
    perms, complete = _symmetries(links, axes)
    images = np.array([[where[tuple(sorted((perm[a], perm[b])))] for a, b in order] for perm in perms], dtype=np.int64)
    images = images[(images != np.arange(len(order))).any(axis=1)]
    subsets = np.arange(1 << links)
    holding = np.array([subsets[subsets & m == m] for m in ((1 << a) | (1 << b) for a, b in order)], dtype=np.int64)
    slack = _slack_table(links, axes)
    out = np.empty((1024, need), np.int64)
    found = _grow(need, slack, holding, images, out) if need else 1  # no mesh to place: the empty set
    if found > len(out):  # room for all of them, and again
        out = np.empty((found, need), np.int64)
        _grow(need, slack, holding, images, out)
    trains, kept = [], {}
    for chosen in out[:found]:
        meshes = [order[i] for i in chosen]
        if dof >= 2 and not brute.non_fractionated(links, axes, meshes, pairs):
            continue
        if not complete:  # some symmetries were not listed: tell the kept sets apart
            key, g = _typed(_train_graph(links, axes, meshes))
            if any(_same(g, h) for h in kept.get(key, ())):
                continue
            kept.setdefault(key, []).append(g)
        trains.append(tuple((a, b, pairs[(a, b)]) for a, b in meshes))
    return trains


def tree_census(dof: int, links: int, axes, rotation: bool = False, keys: bool = False) -> dict:
    """Numbers of displacement graphs on one tree and (``rotation``) of the rotation graphs among
    them — the rotation graphs met on this tree, not the first met here; with ``keys`` also the
    set of their :func:`rotation_key` (to count the rotation graphs of many trees as a union).

    Example
    -------
    >>> tree_census(1, 5, ((0, 1, 2), (0, 3), (1, 4)), rotation=True)
    {'displacement': 2, 'rotation': 2}
    """
    trains = tree_trains(dof, links, axes)
    out = {"displacement": len(trains)}
    if rotation or keys:
        found = {rotation_key(links, triples) for triples in trains}
        out["rotation"] = len(found)
        if keys:
            out["keys"] = found
    return out


def rotation_key(links: int, triples) -> bytes:
    """Canonical form of a rotation graph — a set of triples (a, b, t), meshing links a, b and
    their carrier t — under renumbering of the links, by bliss: the graph with a vertex per link,
    per mesh (joined to a and b) and per carrier mark (joined to the mesh and to t), in three
    colours.  The triples read back from the canonical graph (links numbered in their order
    there), sorted, three bytes a mesh, are the key: equal keys ⇔ the same rotation graph.

    >>> rotation_key(4, [(1, 3, 2), (0, 3, 2)]) == rotation_key(4, [(0, 1, 3), (0, 2, 3)])
    True
    >>> rotation_key(4, [(1, 3, 2), (0, 3, 2)]) == rotation_key(4, [(0, 1, 3), (0, 2, 1)])
    False
    """
    meshes = len(triples)
    edges = []
    for k, (a, b, t) in enumerate(triples):
        mesh, mark = links + k, links + meshes + k
        edges += [(mesh, a), (mesh, b), (mesh, mark), (mark, t)]
    graph = igraph.Graph(n=links + 2 * meshes, edges=edges)
    graph.vs["colour"] = [0] * links + [1] * meshes + [2] * meshes
    canonical = graph.permute_vertices(graph.canonical_permutation(color=graph.vs["colour"]))
    colour = canonical.vs["colour"]  # read the triples back from the canonical graph itself
    rank = {x: r for r, x in enumerate(v for v in range(len(colour)) if colour[v] == 0)}
    gears: dict = {}
    mark_of, carrier_at = {}, {}
    for u, v in canonical.get_edgelist():
        if colour[u] > colour[v]:
            u, v = v, u
        if colour[v] == 1:  # link u is a gear of mesh v
            gears.setdefault(v, []).append(rank[u])
        elif colour[u] == 1:  # mesh u has the carrier mark v
            mark_of[u] = v
        else:  # mark v stands on link u, the carrier
            carrier_at[v] = rank[u]
    renumbered = sorted((*sorted(pair), carrier_at[mark_of[mesh]]) for mesh, pair in gears.items())
    return bytes(x for triple in renumbered for x in triple)


# ------------------------------------------------------------------ rotation forms
def _refine(links: int, triples, colour: list) -> list:
    """Colour refinement of the links by their roles in the triples; colours are canonical ranks."""
    while True:
        signature = []
        for x in range(links):
            roles = []
            for a, b, t in triples:
                if x in (a, b):
                    other = b if x == a else a
                    roles.append(("gear", colour[other], colour[t]))
                if x == t:
                    roles.append(("carrier", *sorted((colour[a], colour[b]))))
            signature.append((colour[x], tuple(sorted(roles))))
        ranks = {sig: r for r, sig in enumerate(sorted(set(signature)))}
        new = [ranks[sig] for sig in signature]
        if len(set(new)) == len(set(colour)):
            return new
        colour = new


def rotation_form(links: int, triples) -> tuple:
    """Canonical form of a set of triples (a, b, t) under renumbering of links: the least relabelled
    triple list over the leaves of an individualisation–refinement search.

    >>> rotation_form(4, [(1, 3, 2), (0, 3, 2)]) == rotation_form(4, [(0, 1, 3), (0, 2, 3)])
    True
    """
    best = None

    def search(colour):
        nonlocal best
        colour = _refine(links, triples, colour)
        if len(set(colour)) == links:
            relabelled = tuple(sorted((tuple(sorted((colour[a], colour[b]))), colour[t]) for a, b, t in triples))
            if best is None or relabelled < best:
                best = relabelled
            return
        sizes = {}
        for c in colour:
            sizes[c] = sizes.get(c, 0) + 1
        cell = min(c for c, k in sizes.items() if k > 1)
        for x in range(links):
            if colour[x] == cell:  # individualise x: it goes first in its cell
                search([2 * c + (0 if y == x else 1) if c == cell else 2 * c for y, c in enumerate(colour)])

    search([0] * links)
    return best


# ---------------------------------------------------------------------------- census
def census(dof: int, links: int, workers: int = 1) -> dict:
    """Numbers of displacement graphs and rotation graphs, a tree at a time: the parent holds one
    key (:func:`rotation_key`) per rotation graph found so far, never the trains of more than the
    trees in flight."""
    jobs = [(dof, links, axes) for axes in brute.link_axis_trees(links)]
    classes: set = set()
    displacement = 0
    pool = Pool(workers) if workers > 1 else None
    try:
        for found in (pool.imap(_keyed_trains, jobs) if pool else map(_keyed_trains, jobs)):
            displacement += found["displacement"]
            classes |= found["keys"]
    finally:
        if pool:
            pool.terminate()
    return {"displacement": displacement, "rotation": len(classes)}


def _keyed_trains(job) -> dict:
    """:func:`tree_census` of one tree with the keys of its rotation graphs."""
    dof, links, axes = job
    return tree_census(dof, links, axes, keys=True)
