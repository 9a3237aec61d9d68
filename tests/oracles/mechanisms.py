"""Mechanisms by brute force over labelled choices (test helper, no engine code, no nauty).

A mechanism is a chain with a fixed link (the frame) and, optionally, an input link
that shares a joint with the frame.  Two choices on one chain give the same
mechanism when an isomorphism of the chain maps one choice onto the other.  Here
every labelled choice is listed and the choices are grouped by isomorphism decided
in two ways that share nothing with ``synth`` (which uses nauty orbits):

* networkx VF2 on the link–joint incidence graph with node colours
  (link / joint kind, and the marks frame = 1, input = 2), bucketed by a
  Weisfeiler–Lehman hash of the same colours;
* for small chains, a canonical form by brute force over every permutation of the
  links (joints follow the links), compared as plain tuples.
"""

from __future__ import annotations

import itertools

import networkx as nx

__all__ = ["choices", "marked_graph", "mechanism_classes", "canonical_form"]

_MATCH = nx.algorithms.isomorphism.categorical_node_match("colour", None)


def neighbours(joints, link: int) -> list[int]:
    """Links that share a joint with ``link``."""
    return sorted({x for j in joints if link in j for x in j if x != link})


def choices(links: int, joints, input_link: bool) -> list[tuple[int, ...]]:
    """Every labelled choice: (frame,) or (frame, input link jointed to it)."""
    if not input_link:
        return [(f,) for f in range(links)]
    return [(f, i) for f in range(links) for i in neighbours(joints, f)]


def marked_graph(links: int, joints, choice, kinds=None) -> nx.Graph:
    """Incidence graph with a ``colour`` per node: link mark, or joint kind."""
    g = nx.Graph()
    for x in range(links):
        mark = choice.index(x) + 1 if x in choice else 0
        g.add_node(("L", x), colour=f"link{mark}")
    for k, j in enumerate(joints):
        g.add_node(("J", k), colour=f"joint-{kinds[k] if kinds else 'revolute'}")
        g.add_edges_from((("J", k), ("L", x)) for x in j)
    return g


def mechanism_classes(links: int, joints, input_link: bool, kinds=None) -> list[list[tuple[int, ...]]]:
    """The labelled choices grouped into isomorphism classes (VF2 with colours)."""
    buckets: dict[str, list[tuple[nx.Graph, list]]] = {}
    classes = []
    for choice in choices(links, joints, input_link):
        g = marked_graph(links, joints, choice, kinds)
        key = nx.weisfeiler_lehman_graph_hash(g, node_attr="colour", iterations=3)
        for rep, members in buckets.setdefault(key, []):
            if nx.is_isomorphic(g, rep, node_match=_MATCH):
                members.append(choice)
                break
        else:
            members = [choice]
            buckets[key].append((g, members))
            classes.append(members)
    return classes


def canonical_form(links: int, joints, choice) -> tuple:
    """Least image of (marks, sorted joints) over all link permutations: equal iff isomorphic."""
    best = None
    for perm in itertools.permutations(range(links)):
        image = (tuple(perm[x] for x in choice),
                 tuple(sorted(tuple(sorted(perm[x] for x in j)) for j in joints)))
        if best is None or image < best:
            best = image
    return best
