"""Independent brute force over planetary gear trains (a test oracle: no code from ``synth``).

Everything here is stated from the definitions in ``docs/gears.md`` and checked the slow way,
in plain Python (networkx only for the rotation-graph isomorphism test):

* a *train* has links ``0 … n−1``, *axes* (coaxial groups: sets of two or more links that turn
  about one axis) and *meshes* (pairs of links);
* the axes alone join the links as a tree: the bipartite link–axis graph is a tree;
* a mesh (a, b) is a pair of links at distance 4 in that tree, a – X – t – Y – b: two different
  axes and the carrier t between them;
* mobility F = 3(n − 1) − 2·p − g with p = Σ (|X| − 1) = n − 1, so g = n − 1 − F meshes;
* no rigid sub-chain: every set S of two links or more has 3(|S| − 1) − 2·p(S) − g(S) ≥ 1, with
  p(S) = Σ_X max(|X ∩ S| − 1, 0) and g(S) the meshes with both gears in S — checked on every
  subset;
* F ≥ 2: non-fractionated — no link splits the Willis equations: the graph on the links in
  which each mesh and its carrier form a triangle is 2-connected (connected, every link in it,
  no cut vertex);
* *displacement graph*: the train up to renumbering of links (axes and meshes follow);
* *rotation graph*: the set of triples ({a, b}, t) — each mesh with its carrier — up to
  renumbering of links.

Trees are grown link by link (every tree with n links is one with n − 1 links plus a link on a
leaf) and told apart by a canonical string (centre rooting, sorted child strings).  Trains on a
tree are told apart by the least image of their mesh set under the tree's automorphisms (every
permutation of the links that maps the axes onto themselves).  Rotation graphs are told apart by
networkx's VF2 test within classes of an invariant.

Example
-------
>>> counts = count_trains(1, 5)
>>> counts["displacement"], counts["rotation"]
(13, 6)
"""

from __future__ import annotations

from collections import defaultdict
from itertools import combinations, permutations

import networkx as nx

__all__ = ["canonical_tree", "link_axis_trees", "mesh_pairs", "rigid_free", "non_fractionated", "trains", "count_trains",
           "rotation_triples", "rotation_classes"]


# ------------------------------------------------------------------ trees of links and axes
def canonical_tree(links: int, axes) -> str:
    """Canonical string of the link–axis tree: the least rooted form over all roots."""
    adj = defaultdict(list)
    for k, axis in enumerate(axes):
        for x in axis:
            adj[("L", x)].append(("A", k))
            adj[("A", k)].append(("L", x))
    nodes = [("L", x) for x in range(links)] + [("A", k) for k in range(len(axes))]

    def rooted(node, parent) -> str:
        return node[0] + "(" + "".join(sorted(rooted(c, node) for c in adj[node] if c != parent)) + ")"

    return min(rooted(v, None) for v in nodes)


def link_axis_trees(links: int) -> list[tuple[tuple[int, ...], ...]]:
    """One representative (its axes, each a sorted tuple of links) of every link–axis tree.

    >>> [len(link_axis_trees(n)) for n in range(2, 7)]
    [1, 2, 4, 9, 22]
    """
    level = {"": ()} if links == 1 else {}
    if links >= 2:
        level = {canonical_tree(2, [(0, 1)]): ((0, 1),)}
        for n in range(2, links):  # add link n to every tree of n links
            grown = {}
            for axes in level.values():
                options = [axes + ((x, n),) for x in range(n)]  # a new axis with link x
                options += [axes[:k] + (axis + (n,),) + axes[k + 1:] for k, axis in enumerate(axes)]  # on axis k
                for new in options:
                    grown.setdefault(canonical_tree(n + 1, new), tuple(tuple(sorted(a)) for a in new))
            level = grown
    return [level[key] for key in sorted(level)]


def _tree_distances(links: int, axes) -> dict:
    """Distances between links in the link–axis tree, and the path's middle link for distance 4."""
    g = nx.Graph()
    for k, axis in enumerate(axes):
        g.add_edges_from((("L", x), ("A", k)) for x in axis)
    g.add_nodes_from(("L", x) for x in range(links))
    paths = dict(nx.all_pairs_shortest_path(g))
    return {(a, b): paths[("L", a)][("L", b)] for a in range(links) for b in range(links)}


def mesh_pairs(links: int, axes) -> dict[tuple[int, int], int]:
    """Every pair of links that can mesh (tree distance 4) with its carrier.

    >>> mesh_pairs(4, ((0, 1, 2), (2, 3)))
    {(0, 3): 2, (1, 3): 2}
    """
    out = {}
    for (a, b), path in _tree_distances(links, axes).items():
        if a < b and len(path) == 5:  # a, X, t, Y, b
            out[(a, b)] = path[2][1]
    return out


def _automorphisms(links: int, axes) -> list[tuple[int, ...]]:
    """Every permutation of the links that maps the set of axes onto itself (brute force)."""
    target = {frozenset(a) for a in axes}
    return [perm for perm in permutations(range(links))
            if all(frozenset(perm[x] for x in axis) in target for axis in axes)]


# ---------------------------------------------------------------------------- conditions
def rigid_free(links: int, axes, meshes) -> bool:
    """True when every set S of two links or more has 3(|S| − 1) − 2·p(S) − g(S) ≥ 1 (every subset).

    >>> rigid_free(4, ((0, 1, 2), (2, 3)), ((0, 3), (1, 3)))
    True
    >>> rigid_free(4, ((0, 1, 2), (2, 3)), ((0, 3), (1, 3), (0, 3)))
    False
    """
    for size in range(2, links + 1):
        for s in combinations(range(links), size):
            inside = set(s)
            p = sum(max(len(inside.intersection(axis)) - 1, 0) for axis in axes)
            g = sum(1 for a, b in meshes if a in inside and b in inside)
            if 3 * (size - 1) - 2 * p - g < 1:
                return False
    return True


def non_fractionated(links: int, axes, meshes, carriers: dict | None = None) -> bool:
    """True when the graph on the links with a triangle (a, b, t) per mesh and its carrier is
    2-connected.  Two gear pairs on one frame, with one gear of each on a common axis, are
    fractionated: their equations share the frame only.

    >>> non_fractionated(4, ((0, 1, 2), (2, 3)), ((0, 3), (1, 3)))
    True
    >>> non_fractionated(5, ((0, 1, 4), (0, 2), (0, 3)), ((1, 2), (3, 4)))
    False
    """
    if carriers is None:  # the caller may pass mesh_pairs(links, axes)
        carriers = mesh_pairs(links, axes)
    g = nx.Graph()
    g.add_nodes_from(range(links))
    for a, b in meshes:
        t = carriers[(a, b)]
        g.add_edges_from([(a, b), (a, t), (b, t)])
    return nx.is_biconnected(g)


# ------------------------------------------------------------------------------- trains
def trains(dof: int, links: int):
    """Every train of ``links`` links and mobility ``dof`` up to isomorphism (displacement graphs).

    Yields ``(axes, meshes, carriers)`` with meshes as sorted pairs and carriers in the same order.
    """
    g = links - 1 - dof
    if g < 0:
        return
    for axes in link_axis_trees(links):
        pairs = mesh_pairs(links, axes)
        group = None
        seen = set()
        for meshes in combinations(sorted(pairs), g):
            if not rigid_free(links, axes, meshes):
                continue
            if dof >= 2 and not non_fractionated(links, axes, meshes):
                continue
            if group is None:
                group = _automorphisms(links, axes)
            key = min(tuple(sorted(tuple(sorted((perm[a], perm[b]))) for a, b in meshes)) for perm in group)
            if key in seen:
                continue
            seen.add(key)
            yield axes, meshes, tuple(pairs[m] for m in meshes)


def rotation_triples(meshes, carriers) -> frozenset:
    """The rotation graph's triples ({a, b}, t)."""
    return frozenset((frozenset(m), t) for m, t in zip(meshes, carriers))


def _rotation_graph(links: int, triples) -> nx.Graph:
    g = nx.Graph()
    g.add_nodes_from((("L", x), {"kind": "link"}) for x in range(links))
    for k, (pair, t) in enumerate(sorted(triples, key=lambda tr: (sorted(tr[0]), tr[1]))):
        g.add_node(("M", k), kind="mesh")
        g.add_edges_from(((("M", k), ("L", x)) for x in pair), kind="gear")
        g.add_edge(("M", k), ("L", t), kind="carrier")
    return g


def rotation_classes(links: int, all_triples) -> int:
    """Number of rotation graphs among the given triple sets, up to renumbering of links."""
    buckets = defaultdict(list)
    for triples in set(all_triples):
        roles = defaultdict(lambda: [0, 0])
        for pair, t in triples:
            for x in pair:
                roles[x][0] += 1
            roles[t][1] += 1
        invariant = tuple(sorted(tuple(roles[x]) for x in range(links)))
        buckets[invariant].append(_rotation_graph(links, triples))
    same = nx.algorithms.isomorphism.categorical_node_match("kind", None)
    edge = nx.algorithms.isomorphism.categorical_edge_match("kind", None)
    total = 0
    for graphs in buckets.values():
        classes = []
        for g in graphs:
            if not any(nx.is_isomorphic(g, h, node_match=same, edge_match=edge) for h in classes):
                classes.append(g)
        total += len(classes)
    return total


def count_trains(dof: int, links: int) -> dict:
    """Numbers of displacement graphs and rotation graphs of ``links`` links and mobility ``dof``."""
    found = list(trains(dof, links))
    return {"displacement": len(found),
            "rotation": rotation_classes(links, [rotation_triples(m, c) for _, m, c in found])}
