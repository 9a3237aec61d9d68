"""A second, independent count of planetary gear trains, fast enough for 10 links (test oracle).

It shares no code with ``synth`` (nor with nauty): trees come from :mod:`gear_trains` (the brute
force's string canonical forms); the symmetries of a tree are listed by networkx's VF2 matcher;
mesh sets are grown in *another order* than the engine's (candidates sorted by carrier first, then
by their gears, from the last to the first) and kept when they are the least of their images
under those symmetries; rigid sub-chains are found by counting, for every link set S, the meshes
inside it against 3(|S| − 1) − 2·p(S) − 1; rotation graphs are told apart by a canonical form of
its own (colour refinement and individualisation over the links, least relabelled triple list).

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
def _symmetries(links: int, axes) -> list[tuple[int, ...]]:
    """Every permutation of the links that maps the tree onto itself (VF2 on the typed tree)."""
    g = nx.Graph()
    g.add_nodes_from(((("L", x), {"t": "L"}) for x in range(links)))
    for k, axis in enumerate(axes):
        g.add_node(("A", k), t="A")
        g.add_edges_from((("A", k), ("L", x)) for x in axis)
    matcher = GraphMatcher(g, g, node_match=lambda u, v: u["t"] == v["t"])
    return [tuple(m[("L", x)][1] for x in range(links)) for m in matcher.isomorphisms_iter()]


def _tree_counts(job):
    """(displacement graphs, their rotation forms) of one tree."""
    dof, links, axes = job
    pairs = brute.mesh_pairs(links, axes)  # {(a, b): carrier}
    order = sorted(pairs, key=lambda ab: (pairs[ab], ab), reverse=True)
    need = links - 1 - dof
    if len(order) < need:
        return 0, []
    where = {ab: i for i, ab in enumerate(order)}
    images = [tuple(where[tuple(sorted((perm[a], perm[b])))] for a, b in order)
              for perm in _symmetries(links, axes)]
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
    found, forms = 0, []

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
            found += 1
            forms.append(rotation_form(links, [(a, b, pairs[(a, b)]) for a, b in meshes]))
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
    else:
        results = [_tree_counts(job) for job in jobs]
    return {"displacement": sum(n for n, _ in results),
            "rotation": len({form for _, forms in results for form in forms})}
