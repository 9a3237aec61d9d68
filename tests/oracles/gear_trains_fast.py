"""A second, independent count of planetary gear trains, fast enough for 10 links (test oracle).

It shares no code with ``synth`` (nor with nauty): trees come from :mod:`gear_trains` (the brute
force's string canonical forms); the symmetries of a tree are listed by networkx's VF2 matcher
(the first ``_CAP`` of them; the star, whose symmetries are all permutations of its n − 1 gears,
has its 1-DOF trains counted as the unlabelled trees on those gears, see :func:`_star_trains`); mesh sets are grown in *another order* than the engine's (candidates
sorted by carrier first, then by their gears, from the last to the first) and kept when no listed
symmetry maps them to a smaller set (a test that passes to every prefix, and that the least set
of each class passes, for any list of symmetries); where the list is not the whole group the
sets kept on a tree are told apart by VF2 within classes of a Weisfeiler–Lehman hash.  Rigid
sub-chains are found by counting, for every link set S, the meshes inside it against
3(|S| − 1) − 2·p(S) − 1.  Rotation graphs are told apart by VF2 within classes of a
Weisfeiler–Lehman hash (the canonical form :func:`rotation_form` serves small checks).

Example
-------
>>> census(1, 6)["displacement"], census(1, 6)["rotation"]
(81, 27)
"""

from __future__ import annotations

from multiprocessing import Pool

import networkx as nx
from networkx.algorithms.isomorphism import GraphMatcher

try:
    from . import gear_trains as brute
except ImportError:  # run as a top-level module
    import gear_trains as brute

__all__ = ["census", "rotation_form"]


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


def _rotation_graph(links: int, triples) -> nx.Graph:
    g = nx.Graph()
    g.add_nodes_from(((("L", x), {"t": "L"}) for x in range(links)))
    for k, (a, b, t) in enumerate(triples):
        g.add_node(("M", k), t="M")
        g.add_edges_from(((("M", k), ("L", x)) for x in (a, b)), k="g")
        g.add_edge(("M", k), ("L", t), k="c")
    return g


def _star_trains(links: int, hub: int = 0) -> list[tuple]:
    """F = 1 trains on the star (every other link on an axis of its own with link 0): every mesh has
    carrier 0, a cycle of meshes C locks (S = C + link 0 has W = 3|C| − 2|C| − |C| = 0) and a forest
    leaves every S a freedom, so the trains are the spanning trees of links 1 … n−1, one per
    unlabelled tree (networkx's list of non-isomorphic trees)."""
    gears = [x for x in range(links) if x != hub]
    return [tuple((gears[a], gears[b], hub) for a, b in tree.edges()) for tree in nx.nonisomorphic_trees(links - 1)]


def _tree_counts(job):
    """(displacement graphs, their rotation forms) of one tree."""
    dof, links, axes = job
    hubs = set.intersection(*(set(a) for a in axes)) if axes else set()
    if dof == 1 and links >= 4 and hubs and all(len(a) == 2 for a in axes):
        found = _star_trains(links, hubs.pop())
        return len(found), found
    pairs = brute.mesh_pairs(links, axes)  # {(a, b): carrier}
    order = sorted(pairs, key=lambda ab: (pairs[ab], ab), reverse=True)
    need = links - 1 - dof
    if len(order) < need:
        return 0, []
    where = {ab: i for i, ab in enumerate(order)}
    perms, complete = _symmetries(links, axes)
    images = [tuple(where[tuple(sorted((perm[a], perm[b])))] for a, b in order) for perm in perms]
    images = [img for img in images if img != tuple(range(len(order)))]
    full = 1 << links
    # slack(S) = 3(|S| − 1) − 2 p(S) − 1 for |S| ≥ 2
    slack = [0] * full
    for s in range(full):
        size = bin(s).count("1")
        if size < 2:
            slack[s] = 10 ** 6
            continue
        p = sum(max(bin(s & sum(1 << x for x in axis)).count("1") - 1, 0) for axis in axes)
        slack[s] = 3 * (size - 1) - 2 * p - 1
    masks = [(1 << a) | (1 << b) for a, b in order]
    holding = [[s for s in range(full) if s & m == m] for m in masks]
    found, forms, kept = 0, [], {}

    def least(chosen):
        for img in images:
            if tuple(sorted(img[i] for i in chosen)) < chosen:
                return False
        return True

    def grow(chosen, slack):
        nonlocal found
        if len(chosen) == need:
            meshes = [order[i] for i in chosen]
            if dof >= 2 and not brute.non_fractionated(links, axes, meshes):
                return
            if not complete:  # some symmetries were not listed: tell the kept sets apart
                key, g = _typed(_train_graph(links, axes, meshes))
                if any(_same(g, h) for h in kept.get(key, ())):
                    return
                kept.setdefault(key, []).append(g)
            found += 1
            forms.append(tuple((a, b, pairs[(a, b)]) for a, b in meshes))
            return
        for i in range((chosen[-1] + 1) if chosen else 0, len(order) - (need - len(chosen)) + 1):
            if min(slack[s] for s in holding[i]) < 1:
                continue
            new = chosen + (i,)
            if not least(new):
                continue
            lowered = list(slack)
            for s in holding[i]:
                lowered[s] -= 1
            grow(new, lowered)

    grow((), slack)
    return found, forms


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
    """Numbers of displacement graphs and rotation graphs."""
    jobs = [(dof, links, axes) for axes in brute.link_axis_trees(links)]
    if workers > 1:
        with Pool(workers) as pool:
            results = pool.map(_tree_counts, jobs, chunksize=1)
            hashed = pool.map(_hash_rotations, [(links, triples) for _, triples in results], chunksize=4)
    else:
        results = [_tree_counts(job) for job in jobs]
        hashed = [_hash_rotations((links, triples)) for _, triples in results]
    classes: dict = {}
    for tree_hashes, (_, triples) in zip(hashed, results):
        for key, found in zip(tree_hashes, triples):
            g = _rotation_graph(links, found)
            if not any(_same(g, h) for h in classes.get(key, ())):
                classes.setdefault(key, []).append(g)
    return {"displacement": sum(n for n, _ in results), "rotation": sum(len(v) for v in classes.values())}


def _hash_rotations(job) -> list[str]:
    links, triples = job
    return [_typed(_rotation_graph(links, t))[0] for t in triples]
