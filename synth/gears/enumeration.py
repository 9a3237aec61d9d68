"""Every planetary gear train of n links and F degrees of freedom, up to isomorphism.

The trains are those of the atlases (docs/gears.md): the axes join the links as a tree, each of
the g = n − 1 − F meshes joins two links at distance 4 in it (a – X – t – Y – b, t the carrier),
no set of two links or more is rigid, and for F ≥ 2 no link splits the Willis equations
(non-fractionated).  Two classes are counted: *displacement graphs* (trains up to renumbering)
and *rotation graphs* (their mesh–carrier triples up to renumbering).

Method
------
1. Link–axis trees with n links, grown link by link from those with n − 1 (a new link on a new
   axis with one old link, or on an old axis) and told apart by nauty certificates (links and
   axes in two colours).
2. On each tree, the mesh sets by *orderly generation*: the candidate meshes (link pairs at
   tree distance 4) are numbered, a set grows by meshes of higher number only, and a set is kept
   only when it is the lexicographically least image of itself under the tree's automorphisms.
   That property passes to every prefix, so each class is reached exactly once, with memory
   bounded by the depth.  A tree with more than 5 000 symmetries (a frame carrying many gears
   alike) is grown by McKay's canonical augmentation instead, which needs no list of them.  A set that has a rigid sub-chain is cut with all its supersets
   (adding a mesh only lowers sub-chain mobilities): a table of 3(|S| − 1) − 2p(S) − g(S) − 1 over
   every link set S, lowered by one on the sets holding both gears of each mesh added.
3. Each complete set is decided by the engine's exact sub-chain test on its lever analogue
   (:meth:`GearTrain.is_rigid_free`), which must agree with the table.
4. Rotation graphs: the nauty certificate of the triples, first train of each kept.

Trees are independent units: ``workers`` processes share them (results merged in tree order).

Example
-------
>>> [count_trains(1, n)["count"] for n in (3, 4, 5, 6)]
[1, 3, 13, 81]
>>> count_trains(2, 6, graphs="rotation")["count"]
2
"""

from __future__ import annotations

from collections import Counter, deque
from collections.abc import Iterator
from functools import lru_cache

import numpy as np
import pynauty

from ..errors import InvalidOption
from .train import GearTrain, axis_paths

__all__ = ["GRAPHS", "MAX_LINKS", "link_axis_trees", "tree_trains", "trains", "count_trains", "census", "check_query"]

GRAPHS = ("displacement", "rotation")
MAX_LINKS = 12  # 2^n link sets in the pruning table; 12 links: 4096 a tree
_ORDERLY_GROUP = 5_000  # trees with more symmetries are grown by canonical augmentation instead


def check_query(dof: int, links: int, graphs: str = "displacement") -> None:
    """Refuse a query the enumerator cannot answer, in one sentence."""
    for what, value in (("the degrees of freedom F", dof), ("the number of links", links)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise InvalidOption(f"{what} must be a whole number, not {value!r}")
    if dof < 1:
        raise InvalidOption(f"a gear train that moves has F ≥ 1 degrees of freedom, not {dof}")
    if links < 2:
        raise InvalidOption(f"a gear train has at least 2 links (a frame and a gear), not {links}")
    if links > MAX_LINKS:
        raise InvalidOption(f"gear trains are enumerated up to {MAX_LINKS} links, not {links}")
    if graphs not in GRAPHS:
        raise InvalidOption(f"a gear train is listed by its displacement or its rotation graph, not {graphs!r}")


# ------------------------------------------------------------------------------ trees
def _tree_graph(links: int, axes) -> pynauty.Graph:
    adjacency = {links + k: list(axis) for k, axis in enumerate(axes)}
    return pynauty.Graph(links + len(axes), adjacency_dict=adjacency, vertex_coloring=[set(range(links)), set(range(links, links + len(axes)))])


@lru_cache(maxsize=None)
def link_axis_trees(links: int) -> tuple[tuple[tuple[int, ...], ...], ...]:
    """One representative (its axes) of every tree of ``links`` links and their axes, in the
    order of their certificates.

    >>> [len(link_axis_trees(n)) for n in range(2, 9)]
    [1, 2, 4, 9, 22, 59, 165]
    """
    if links < 2:
        return ((),) if links == 1 else ()
    if links == 2:
        return (((0, 1),),)
    found: dict[bytes, tuple] = {}
    for axes in link_axis_trees(links - 1):
        new = links - 1
        options = [axes + ((x, new),) for x in range(new)]
        options += [axes[:k] + (axis + (new,),) + axes[k + 1:] for k, axis in enumerate(axes)]
        for option in options:
            option = tuple(sorted(tuple(sorted(a)) for a in option))
            found.setdefault(pynauty.certificate(_tree_graph(links, option)), option)
    return tuple(found[c] for c in sorted(found))


class _Tree:
    """A tree with what the orderly generation needs: candidate meshes, their carriers, the
    pruning table's index sets and the automorphisms acting on the candidates."""

    def __init__(self, links: int, axes):
        self.links, self.axes = links, axes
        paths = axis_paths(links, axes)
        self.pairs = [(a, b) for a in range(links) for b in range(a + 1, links) if len(paths[a].get(b, ())) == 5]
        self.carriers = [paths[a][b][2] for a, b in self.pairs]
        index = {p: i for i, p in enumerate(self.pairs)}
        gens, size1, size2, _, _ = pynauty.autgrp(_tree_graph(links, axes))
        self.order = size1 * 10.0**size2  # on links: at least the order of the group on the pairs
        self.moves = [tuple(index[tuple(sorted((g[a], g[b])))] for a, b in self.pairs) for g in gens]
        self.group = _closure(self.moves, len(self.pairs)) if self.order <= _ORDERLY_GROUP else None

    def table(self) -> tuple[np.ndarray, list[np.ndarray]]:
        """Slack 3(|S| − 1) − 2p(S) − 1 of every link set S (|S| ≥ 2; large below), and per
        candidate mesh the sets that hold both its gears."""
        sets = np.arange(1 << self.links, dtype=np.int64)
        size = np.zeros(len(sets), dtype=np.int64)
        for x in range(self.links):
            size += (sets >> x) & 1
        p = np.zeros(len(sets), dtype=np.int64)
        for axis in self.axes:
            on = np.zeros(len(sets), dtype=np.int64)
            for x in axis:
                on += (sets >> x) & 1
            p += np.maximum(on - 1, 0)
        slack = np.where(size >= 2, 3 * (size - 1) - 2 * p - 1, 1 << 20).astype(np.int32)
        holds = [np.flatnonzero(((sets >> a) & 1) & ((sets >> b) & 1)) for a, b in self.pairs]
        return slack, holds


def _closure(generators: list[tuple[int, ...]], size: int) -> list[tuple[int, ...]]:
    """Every element of the permutation group the generators make (on ``size`` points), identity first."""
    identity = tuple(range(size))
    group, frontier = {identity}, [identity]
    gens = [g for g in set(generators) if g != identity]
    while frontier:
        nxt = []
        for h in frontier:
            for g in gens:
                gh = tuple(g[i] for i in h)
                if gh not in group:
                    group.add(gh)
                    nxt.append(gh)
        frontier = nxt
    group.discard(identity)
    return [identity] + sorted(group)


def _least(chosen: tuple[int, ...], group) -> bool:
    """Whether ``chosen`` (increasing) is the lexicographically least of its images."""
    for g in group[1:]:
        if tuple(sorted(g[i] for i in chosen)) < chosen:
            return False
    return True


def _mesh_sets(tree: _Tree, meshes: int, augment: bool | None = None) -> Iterator[tuple[int, ...]]:
    """One candidate set of ``meshes`` meshes without a rigid sub-chain per class: by orderly
    generation, or by canonical augmentation where the tree has many symmetries (or ``augment``)."""
    slack, holds = tree.table()
    if augment or (augment is None and tree.group is None):
        yield from _augmented(tree, meshes, slack, holds)
        return
    count = len(tree.pairs)
    group = tree.group

    def grow(chosen: tuple[int, ...], slack: np.ndarray):
        if len(chosen) == meshes:
            yield chosen
            return
        start = chosen[-1] + 1 if chosen else 0
        for i in range(start, count - (meshes - len(chosen)) + 1):
            if slack[holds[i]].min() < 1:
                continue
            new = chosen + (i,)
            if len(group) > 1 and not _least(new, group):
                continue
            lowered = slack.copy()
            lowered[holds[i]] -= 1
            yield from grow(new, lowered)

    yield from grow((), slack)


def _augmented(tree: _Tree, meshes: int, slack: np.ndarray, holds) -> Iterator[tuple[int, ...]]:
    """McKay's canonical augmentation: a set grows by one mesh per orbit of its symmetries, and a
    child is kept when the mesh added is in the orbit of the mesh its canonical labelling names
    last (the mesh vertex of least canonical position)."""
    n, axes, pairs = tree.links, tree.axes, tree.pairs
    index = {p: i for i, p in enumerate(pairs)}
    base = n + len(axes)

    def graph(chosen):
        adjacency = {n + k: list(axis) for k, axis in enumerate(axes)}
        for j, i in enumerate(chosen):
            adjacency[base + j] = list(pairs[i])
        cells = [set(range(n)), set(range(n, base)), set(range(base, base + len(chosen)))]
        return pynauty.Graph(base + len(chosen), adjacency_dict=adjacency, vertex_coloring=[c for c in cells if c])

    def pair_orbits(chosen, free):
        gens = pynauty.autgrp(graph(chosen))[0]
        parent = {i: i for i in free}

        def root(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for g in gens:
            for i in free:
                a, b = pairs[i]
                j = index[tuple(sorted((g[a], g[b])))]
                ri, rj = root(i), root(j)
                if ri != rj:
                    parent[max(ri, rj)] = min(ri, rj)
        return sorted({root(i) for i in free})

    def grow(chosen: tuple[int, ...], slack: np.ndarray):
        if len(chosen) == meshes:
            yield tuple(sorted(chosen))
            return
        free = [i for i in range(len(pairs)) if i not in chosen and slack[holds[i]].min() >= 1]
        for i in pair_orbits(chosen, free):
            child = chosen + (i,)
            g = graph(child)
            lab = pynauty.canon_label(g)
            orbits = pynauty.autgrp(g)[3]
            last = min((pos, v) for pos, v in enumerate(lab) if v >= base)[1]
            if orbits[last] != orbits[base + len(chosen)]:
                continue
            lowered = slack.copy()
            lowered[holds[i]] -= 1
            yield from grow(child, lowered)

    yield from grow((), slack)


_METHODS = {"auto": None, "orderly": False, "augmentation": True}


def tree_trains(dof: int, links: int, axes, method: str = "auto") -> list[GearTrain]:
    """The trains on one link–axis tree (one of :func:`link_axis_trees`), in generation order: the
    independent unit of the enumeration (an atlas's grid runs a tree a unit).

    >>> [len(tree_trains(1, 4, axes)) for axes in link_axis_trees(4)]
    [1, 1, 0, 1]
    """
    tree = _Tree(links, axes)
    meshes = links - 1 - dof
    out = []
    if meshes > len(tree.pairs):
        return out
    if method == "orderly" and tree.group is None:
        tree.group = _closure(tree.moves, len(tree.pairs))
    for chosen in _mesh_sets(tree, meshes, _METHODS[method]):
        train = GearTrain(links, axes, tuple(tree.pairs[i] for i in chosen),
                          tuple(tree.carriers[i] for i in chosen))
        if dof >= 2 and train.is_fractionated():
            continue
        if not train.is_rigid_free():  # the table and the exact test must agree
            raise AssertionError(f"the pruning table passed {train.compact()}, which has a rigid sub-chain")
        out.append(train)
    return out


def _tree_summary(args) -> tuple[int, dict, set]:
    dof, links, axes, want_rotation, method = args
    found = tree_trains(dof, links, axes, method)
    codes = Counter(str(t.lever_analogue().code) for t in found)
    rotations = {t.rotation_certificate for t in found} if want_rotation else set()
    return len(found), dict(codes), rotations


def _units(dof: int, links: int, workers: int | None, work, args_of):
    """Run ``work`` on every tree, in tree order, inline or on a process pool."""
    trees = link_axis_trees(links)
    jobs = [args_of(axes) for axes in trees]
    workers = workers or 1
    if workers == 1 or len(trees) < 8:
        for job in jobs:
            yield work(job)
        return
    from ..execution.executor import process_pool  # workers leave Ctrl-C to this process and die with it

    pool = process_pool(workers)
    window: deque = deque()  # at most 4 trees a worker in flight: results never pile up
    try:
        for job in jobs:
            window.append(pool.apply_async(work, (job,)))
            if len(window) >= 4 * workers:
                yield window.popleft().get()
        while window:
            yield window.popleft().get()
    finally:  # Ctrl-C, an error or a reader that stops early: no worker goes on
        pool.terminate()
        pool.join()


def trains(dof: int, links: int, graphs: str = "displacement", workers: int | None = 1) -> Iterator[GearTrain]:
    """Every train, one per displacement graph, or one (the first) per rotation graph.

    >>> [t.compact() for t in trains(1, 4)]
    ['0-1 0-2 0-3 1~2 1~3', '0-1 0-2 1-3 0~3 1~2', '0-1-3 0-2 1~2 2~3']
    """
    check_query(dof, links, graphs)
    seen: set[str] = set()
    for found in _units(dof, links, workers, _tree_list, lambda axes: (dof, links, axes)):
        for train in found:
            if graphs == "rotation":
                if train.rotation_certificate in seen:
                    continue
                seen.add(train.rotation_certificate)
            yield train


def _tree_list(args) -> list[GearTrain]:
    return tree_trains(*args)


def census(dof: int, links: int, workers: int | None = 1, method: str = "auto") -> dict:
    """Both counts in one pass: ``{"displacement": D, "rotation": R, "by_code": {code: D}}``.
    ``method``: "auto" (orderly generation, canonical augmentation on very symmetric trees),
    "orderly" or "augmentation" everywhere (the two must agree).

    >>> census(1, 6)["displacement"], census(1, 6)["rotation"]
    (81, 27)
    """
    check_query(dof, links)
    total, codes, rotations = 0, Counter(), set()
    if method not in _METHODS:
        raise InvalidOption(f"the method is auto, orderly or augmentation, not {method!r}")
    for n, by_code, rot in _units(dof, links, workers, _tree_summary, lambda axes: (dof, links, axes, True, method)):
        total += n
        codes.update(by_code)
        rotations |= rot
    return {"displacement": total, "rotation": len(rotations), "by_code": dict(sorted(codes.items()))}


def count_trains(dof: int, links: int, graphs: str = "displacement", workers: int | None = 1) -> dict:
    """``{"count": N, "by_code": {lever-analogue code: N}}``; for rotation graphs, ``by_code`` counts
    the displacement graphs of each code (a rotation graph has several).

    >>> count_trains(1, 5)
    {'count': 13, 'by_code': {'521/0': 3, '530/1': 4, '602/0': 2, '611/1': 2, '620/2': 1, '701/0-1': 1}}
    """
    check_query(dof, links, graphs)
    if graphs == "rotation":
        found = census(dof, links, workers)
        return {"count": found["rotation"], "by_code": found["by_code"]}
    total, codes = 0, Counter()
    for n, by_code, _ in _units(dof, links, workers, _tree_summary, lambda axes: (dof, links, axes, False, "auto")):
        total += n
        codes.update(by_code)
    return {"count": total, "by_code": dict(sorted(codes.items()))}
