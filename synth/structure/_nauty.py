"""nauty graphs built from the engine's own lists, without pynauty's per-vertex checks.

``pynauty.Graph(n, adjacency_dict=…, vertex_coloring=…)`` checks every vertex of every
adjacency list in Python and copies each list through a set: about 20 µs a graph, an eighth
of a listing of small chains (h = 2, 9 links: 13 693 graphs).  The incidence graphs of
chains and branch multigraphs are built here from lists that are already valid (vertices in
range, no repeated neighbour, colour cells disjoint and covering every vertex), so
:class:`TrustedGraph` stores them as given.  nauty reads the same four attributes either way;
``tests/test_doctests.py`` and the certificate tests compare the two constructions.

>>> import pynauty
>>> adjacency, cells = {2: [0, 1]}, [{0, 1}, {2}]
>>> a = pynauty.certificate(TrustedGraph(3, adjacency, cells))
>>> a == pynauty.certificate(pynauty.Graph(3, adjacency_dict=adjacency, vertex_coloring=cells))
True
"""

from __future__ import annotations

import pynauty

__all__ = ["TrustedGraph"]


class TrustedGraph(pynauty.Graph):
    """A ``pynauty.Graph`` (undirected) from a valid adjacency dict and a colour partition of
    every vertex (a single cell means no colouring, as pynauty makes it)."""

    # plain attributes in place of pynauty's read-only properties, which nauty's wrapper reads
    adjacency_dict: dict = {}
    vertex_coloring: list = []

    def __init__(self, number_of_vertices: int, adjacency: dict, coloring: list):  # noqa: D107
        self.number_of_vertices = number_of_vertices
        self.directed = False
        self.adjacency_dict = adjacency
        self.vertex_coloring = coloring if len(coloring) > 1 else []
