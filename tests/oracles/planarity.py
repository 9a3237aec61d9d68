"""Planarity by a second method, with checked certificates (test helper, no engine code).

The engine decides planarity with networkx's left-right test (``nx.check_planarity``).
Here the verdict comes from the Boyer–Myrvold edge-addition planarity suite (the
``planarity`` package, a separate C implementation), and each answer is then
*certified* by code written here:

* non-planar: the Kuratowski subgraph the suite returns must, after deleting
  isolated vertices and smoothing vertices of degree 2, be exactly K5 or K3,3;
* planar: a combinatorial embedding (networkx's, used only as a candidate) must be
  a rotation system whose face count satisfies Euler's formula
  V − E + F = 1 + C (C connected components), counted by our own face walk.
"""

from __future__ import annotations

import itertools

import networkx as nx
import planarity

__all__ = ["incidence_edges", "planar_verdict", "is_kuratowski_subdivision", "euler_faces_ok"]


def incidence_edges(links: int, joints) -> list[tuple[str, str]]:
    """Edges of the link–joint incidence graph, nodes named 'L<i>' and 'J<k>'."""
    return [(f"L{x}", f"J{k}") for k, j in enumerate(joints) for x in j]


def _smooth(edges) -> nx.MultiGraph:
    """Drop isolated vertices and suppress vertices of degree 2 (own loop, no nx helper)."""
    g = nx.MultiGraph()
    g.add_edges_from(edges)
    changed = True
    while changed:
        changed = False
        for v in list(g.nodes):
            if g.degree(v) == 2:
                nbrs = [u for _, u in g.edges(v)]
                if v in nbrs:  # a loop: cannot smooth
                    continue
                g.remove_node(v)
                g.add_edge(nbrs[0], nbrs[1])
                changed = True
                break
    return g


def is_kuratowski_subdivision(edges) -> bool:
    """Whether ``edges`` form a subdivision of K5 or K3,3 (checked by definition)."""
    g = _smooth(edges)
    if any(u == v for u, v in g.edges()) or g.number_of_edges() != nx.Graph(g).number_of_edges():
        return False  # loops or parallel edges: not a simple Kuratowski graph
    n, m = g.number_of_nodes(), g.number_of_edges()
    nodes = list(g.nodes)
    adj = {v: set(g.neighbors(v)) for v in nodes}
    if n == 5 and m == 10:
        return all(len(adj[v]) == 4 for v in nodes)
    if n == 6 and m == 9:
        for side in itertools.combinations(nodes, 3):
            a, b = set(side), set(nodes) - set(side)
            if all(adj[v] == b for v in a) and all(adj[v] == a for v in b):
                return True
    return False


def euler_faces_ok(rot: dict) -> bool:
    """Count faces of a rotation system ``{vertex: neighbours in cyclic order}`` by walking
    half-edges; check V − E + F = 1 + C (C components), i.e. the rotation is planar."""
    nxt = {}
    for v, order in rot.items():
        for i, u in enumerate(order):
            nxt[(v, u)] = order[(i + 1) % len(order)]
    seen, faces = set(), 0
    for v, order in rot.items():
        for u in order:
            if (v, u) in seen:
                continue
            faces += 1
            a, b = v, u
            while (a, b) not in seen:
                seen.add((a, b))
                # next half-edge of the face: at b, turn to the neighbour after a
                c = nxt[(b, a)]
                a, b = b, c
    V = len(rot)
    E = sum(len(o) for o in rot.values()) // 2
    C = nx.number_connected_components(nx.Graph([(v, u) for v, o in rot.items() for u in o]))
    isolated = sum(1 for o in rot.values() if not o)
    faces += isolated  # an isolated vertex has one (outer) face of its own in this count
    return V - E + faces == 1 + C + isolated


def planar_verdict(links: int, joints) -> bool:
    """Planarity of the incidence graph by Boyer–Myrvold, certified either way."""
    edges = incidence_edges(links, joints)
    verdict = planarity.is_planar(edges)
    if verdict:
        ok, embedding = nx.check_planarity(nx.Graph(edges))
        rotation = {v: list(embedding.neighbors_cw_order(v)) for v in embedding.nodes}
        assert ok and euler_faces_ok(rotation), "the planar verdict has no valid embedding"
    else:
        assert is_kuratowski_subdivision(planarity.kuratowski_edges(edges)), "no Kuratowski subgraph"
    return verdict
