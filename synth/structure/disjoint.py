"""Disjoint sets (union–find): which items are joined, through any chain of joins.

One structure for every such question of the engine — sub-chains joined around a link, the loops
a graph closes, whether a multigraph is connected, orbits of gear meshes under a symmetry group.

>>> sets = DisjointSets(range(5))
>>> sets.union(0, 1), sets.union(3, 4), sets.union(1, 0)
(True, True, False)
>>> sets.find(1), sets.find(4), len(sets.roots())
(0, 3, 3)
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable

__all__ = ["DisjointSets"]


class DisjointSets:
    """Union–find over ``items`` (path halving); each set is named by its smallest item, so the
    names do not depend on the order of the joins.

    Notes
    -----
    ``find`` and ``union`` take amortised O(log n); the engine's sets hold at most a few hundred items.
    """

    def __init__(self, items: Iterable[Hashable]):
        self._root = {x: x for x in items}

    def find(self, x: Hashable) -> Hashable:
        """The name (smallest item) of the set that holds ``x``."""
        root = self._root
        while root[x] != x:
            root[x] = x = root[root[x]]
        return x

    def union(self, a: Hashable, b: Hashable) -> bool:
        """Join the sets of ``a`` and ``b``; False when they were one set already."""
        ra, rb = self.find(a), self.find(b)
        if ra == rb:
            return False
        self._root[max(ra, rb)] = min(ra, rb)
        return True

    def roots(self) -> set:
        """The name of every set."""
        return {self.find(x) for x in self._root}
