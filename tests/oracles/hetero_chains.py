"""Independent oracle: heterogeneous chains, loops of two classes (a base of class x on a chain of class h).

Test helper; imports nothing from ``synth`` (networkx and the standard library only).  It answers:
for a mobility W and loop classes {h: K_h, x: K_x} with h < x, every non-isomorphic closed chain
with simple joints and n <= 7 links that satisfies the rule of docs/theory.md ("Heterogeneous
chains"), listed by brute force.

Definitions (the rule this module implements, read from the documentation, not from the engine)
---------------------------------------------------------------------------------------------
* **Chain**: links 0..n-1 as the vertices of a simple connected graph, joints as its edges, every
  link on >= 2 joints.  n = W + 1 + (h - 1)·K_h + (x - 1)·K_x.
* **Base**: a set B of links (the links of class x); every link of B lies on a cycle of the
  subgraph induced by B, whose cycle rank (edges - vertices + components) is K_x.  Every other
  loop is of class h.
* **Count** of a set S of links: W(S) = h(|S| - 1) - (h - 1)·e(S) - (x - h)·c(S ∩ B), e(S) the
  joints with both links in S, c(S ∩ B) the cycle rank of the base links in S.
* **Admissible**: W(all links) = W and every proper S with |S| >= 2 has W(S) >= 1 (W >= 1) or
  W(S) >= 0 (W = 0: rigid sub-chains allowed).  Every subset is tried.
* **Isomorphism**: a bijection of links mapping joints to joints and base to base (networkx VF2
  with the class as a node attribute).  Fractionated chains are included.

Generation: every unlabelled simple graph up to 7 vertices is in ``networkx.graph_atlas_g()``
exactly once; the oracle takes those with n vertices, connected, minimum degree >= 2 and the number
of edges the count of the whole chain fixes, then every subset B of the links, and keeps one
representative per isomorphism class of (graph, B).
"""

from __future__ import annotations

from itertools import combinations

import networkx as nx


def _rank(g: nx.Graph) -> int:
    return g.number_of_edges() - g.number_of_nodes() + nx.number_connected_components(g) if len(g) else 0


def _count(g: nx.Graph, s, base, h: int, x: int) -> int:
    sub = g.subgraph(s)
    return h * (len(s) - 1) - (h - 1) * sub.number_of_edges() - (x - h) * _rank(g.subgraph(set(s) & base))


def _every_link_on_a_loop(g: nx.Graph, base) -> bool:
    sub = g.subgraph(base)
    on = set()
    for cycle in nx.cycle_basis(sub):
        on |= set(cycle)
    return on == set(base)


def hetero_chains(dof: int, classes: dict[int, int], rigid_subchains: bool | None = None) -> list[tuple[nx.Graph, frozenset]]:
    """Every non-isomorphic (graph, base) of mobility ``dof`` with the loops ``classes``; proper
    sub-chains of W(S) = 0 allowed with ``rigid_subchains`` (default: where W = 0)."""
    (h, k_h), (x, k_x) = sorted(classes.items())
    n = dof + 1 + (h - 1) * k_h + (x - 1) * k_x
    if n > 7:
        raise ValueError("the oracle lists chains of up to 7 links")
    edges = n - 1 + k_h + k_x
    threshold = 0 if (dof == 0 if rigid_subchains is None else rigid_subchains) else 1
    found: list[tuple[nx.Graph, frozenset]] = []
    for g in nx.graph_atlas_g():
        if len(g) != n or g.number_of_edges() != edges or not nx.is_connected(g) or min(d for _, d in g.degree()) < 2:
            continue
        for size in range(3, n + 1):
            for base in map(frozenset, combinations(range(n), size)):
                if _rank(g.subgraph(base)) != k_x or not _every_link_on_a_loop(g, base):
                    continue
                if _count(g, range(n), base, h, x) != dof:
                    continue
                if any(_count(g, s, base, h, x) < threshold
                       for m in range(2, n) for s in combinations(range(n), m)):
                    continue
                marked = g.copy()
                nx.set_node_attributes(marked, {v: v in base for v in marked}, "base")
                same = nx.algorithms.isomorphism.categorical_node_match("base", False)
                if not any(nx.is_isomorphic(marked, other, node_match=same) for other, _ in found):
                    found.append((marked, base))
    return found
