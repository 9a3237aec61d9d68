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

import sys
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np
import pynauty

from mechbase import Row

from ..errors import InvalidOption
from ..execution.executor import Executor
from ..structure.disjoint import DisjointSets
from .train import GearTrain, axis_paths, fractionated, rotation_graph

if TYPE_CHECKING:
    from ..synthesis.type_synthesis import Counts

__all__ = ["GRAPHS", "MAX_LINKS", "SIZED_LINKS", "link_axis_trees", "tree_trains", "tree_census", "trains", "count_trains", "census", "Census",
           "check_query", "estimate_trains", "size_check_trains"]

GRAPHS = ("displacement", "rotation")
MAX_LINKS = 12  # 2^n link sets in the pruning table; 12 links: 4096 a tree
SIZED_LINKS = 9  # from this size on a query is sized before it runs (1-DOF: 9 links take 3 CPU seconds, 11 ten minutes)
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
    """A tree with what the enumeration needs: candidate meshes, their carriers, the pruning
    table and the automorphisms acting on the candidates."""

    def __init__(self, links: int, axes):
        self.links, self.axes = links, axes
        paths = axis_paths(links, axes)
        self.pairs = [(a, b) for a in range(links) for b in range(a + 1, links) if len(paths[a].get(b, ())) == 5]
        self.carriers = [paths[a][b][2] for a, b in self.pairs]
        self.triples = [(a, b, t) for (a, b), t in zip(self.pairs, self.carriers)]
        index = {p: i for i, p in enumerate(self.pairs)}
        gens, size1, size2, _, _ = pynauty.autgrp(_tree_graph(links, axes))
        self.order = size1 * 10.0**size2  # on links: at least the order of the group on the pairs
        self.moves = [tuple(index[tuple(sorted((g[a], g[b])))] for a, b in self.pairs) for g in gens]
        self.group = _closure(self.moves, len(self.pairs)) if self.order <= _ORDERLY_GROUP else None

    def table(self, meshes: int) -> tuple[list[int], list[int]]:
        """The pruning table for sets of ``meshes`` meshes, as bit masks over the link sets S that
        can refuse a mesh: ``levels[k]`` the sets of slack 3(|S| − 1) − 2p(S) − 1 = k, for
        k < ``meshes`` (a set of larger slack never refuses one), and ``holds[i]`` the sets
        holding both gears of candidate i.  A mesh may join while no set holding it has slack 0
        (:func:`_lowered` takes it in)."""
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
        slack = np.where(size >= 2, 3 * (size - 1) - 2 * p - 1, meshes)
        held = [((sets >> a) & 1 & (sets >> b)).astype(bool) for a, b in self.pairs]
        refusing = (slack < meshes) & np.logical_or.reduce(held) if held else np.zeros(len(sets), dtype=bool)

        def bits(on: np.ndarray) -> int:
            return int.from_bytes(np.packbits(on[refusing], bitorder="little").tobytes(), "little")

        return [bits(slack == k) for k in range(meshes)], [bits(h) for h in held]

    def mesh_sets(self, meshes: int, method: str = "auto") -> Iterator[tuple[int, ...]]:
        """One set of ``meshes`` candidates without a rigid sub-chain per class (indices into
        :attr:`pairs`, increasing): by orderly generation, or by canonical augmentation where the
        tree has many symmetries (``method``: "auto", "orderly", "augmentation")."""
        if meshes > len(self.pairs):
            return
        levels, holds = self.table(meshes)
        if method == "augmentation" or (method == "auto" and self.group is None):
            yield from _augmented(self, meshes, levels, holds)
            return
        group = self.group if self.group is not None else _closure(self.moves, len(self.pairs))
        yield from _orderly(_Images(group, len(self.pairs)), meshes, levels, holds)


def _lowered(levels: list[int], held: int) -> list[int]:
    """The slack levels after a mesh joins the sets ``held``: each of them one level down; the top
    level is dropped (one mesh fewer to come, a set of that slack can no longer refuse one)."""
    return [(levels[k] & ~held) | (levels[k + 1] & held) for k in range(len(levels) - 1)]


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


class _Images:
    """The least-image test of orderly generation, one candidate at a time.

    A set of candidates is the bit mask with candidate i at bit ``count − 1 − i``, so that of
    two sets of one size the lexicographically smaller (as increasing tuples) has the larger mask.
    A set is kept when no symmetry maps it onto a larger mask; the masks of its images under every
    symmetry but the identity are carried along (``extend``: one OR per symmetry), in a numpy
    array of int64 for large groups (a tree of 12 links has at most 55 candidates).

    >>> images = _Images([(0, 1, 2), (2, 1, 0)], 3)  # the reflection of three candidates
    >>> images.extend(images.start(), 0) is not None, images.extend(images.start(), 2) is None
    (True, True)
    """

    def __init__(self, group, count: int):
        top, others = count - 1, group[1:]
        if len(others) > 16:
            self.columns = np.array([[1 << (top - g[i]) for g in others] for i in range(count)], dtype=np.int64)
        else:
            self.columns = [tuple(1 << (top - g[i]) for g in others) for i in range(count)]
        self.top, self.wide, self.trivial = top, len(others) > 16, not others

    def start(self):
        """The state of the empty set: its mask and its images' masks."""
        return 0, (np.zeros(self.columns.shape[1], dtype=np.int64) if self.wide else (0,) * len(self.columns[0]))

    def extend(self, state, i: int):
        """The state of the set with candidate i added (larger than any in it), or None when an
        image of that set is smaller."""
        mask, images = state
        mask |= 1 << (self.top - i)
        if self.trivial:
            return mask, images
        if self.wide:
            images = images | self.columns[i]
            return None if (images > mask).any() else (mask, images)
        images = tuple(a | b for a, b in zip(images, self.columns[i]))
        return None if max(images) > mask else (mask, images)


def _orderly(images: _Images, meshes: int, levels: list[int], holds: list[int]) -> Iterator[tuple[int, ...]]:
    """Orderly generation: a set grows by candidates of higher number only and is kept when it is
    the least of its images; the candidates still open to a set (no rigid sub-chain, higher
    number) are carried along, and a set with fewer of them than meshes missing is dropped."""

    def grow(chosen: tuple[int, ...], levels: list[int], options: list[int], state):
        wanted = len(levels)
        for position in range(len(options) - wanted + 1):
            i = options[position]
            child = images.extend(state, i)
            if child is None:
                continue
            if wanted == 1:
                yield chosen + (i,)
                continue
            lowered = _lowered(levels, holds[i])
            full = lowered[0]
            rest = [j for j in options[position + 1:] if not holds[j] & full]
            if len(rest) >= wanted - 1:
                yield from grow(chosen + (i,), lowered, rest, child)

    if meshes == 0:
        yield ()
        return
    options = [i for i, held in enumerate(holds) if not held & levels[0]]
    yield from grow((), levels, options, images.start())


def _augmented(tree: _Tree, meshes: int, levels: list[int], holds: list[int]) -> Iterator[tuple[int, ...]]:
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
        orbits = DisjointSets(free)  # each orbit named by its smallest pair
        for g in gens:
            for i in free:
                a, b = pairs[i]
                orbits.union(i, index[tuple(sorted((g[a], g[b])))])
        return sorted(orbits.roots())

    def grow(chosen: tuple[int, ...], levels: list[int]):
        if len(chosen) == meshes:
            yield tuple(sorted(chosen))
            return
        free = [i for i in range(len(pairs)) if i not in chosen and not holds[i] & levels[0]]
        for i in pair_orbits(chosen, free):
            child = chosen + (i,)
            g = graph(child)
            lab = pynauty.canon_label(g)
            orbits = pynauty.autgrp(g)[3]
            last = min((pos, v) for pos, v in enumerate(lab) if v >= base)[1]
            if orbits[last] != orbits[base + len(chosen)]:
                continue
            yield from grow(child, _lowered(levels, holds[i]))

    yield from grow((), levels)


_METHODS = ("auto", "orderly", "augmentation")


def tree_trains(dof: int, links: int, axes, method: str = "auto") -> list[GearTrain]:
    """The trains on one link–axis tree (one of :func:`link_axis_trees`), in generation order: the
    independent unit of the enumeration (an atlas's grid runs a tree a unit).

    >>> [len(tree_trains(1, 4, axes)) for axes in link_axis_trees(4)]
    [1, 1, 0, 1]
    """
    tree = _Tree(links, axes)
    out = []
    for chosen in tree.mesh_sets(links - 1 - dof, method):
        triples = [tree.triples[i] for i in chosen]
        if dof >= 2 and fractionated(links, triples):
            continue
        out.append(GearTrain(links, axes, tuple(tree.pairs[i] for i in chosen), tuple(t for _, _, t in triples)))
    return out


def tree_census(dof: int, links: int, axes, rotation: bool = True, method: str = "auto") -> tuple[int, dict, dict]:
    """The census of one link–axis tree (one of :func:`link_axis_trees`): its number of trains,
    their numbers by lever-analogue code, and (``rotation``) for each rotation graph met on the
    tree — keyed by its canonical form, the triples renumbered by nauty and sorted, three bytes a
    mesh — the code of its first train in the tree's order.  No train is built: a code is found
    from the links' degrees, a rotation graph from the triples; :func:`census` adds the trees up.

    Example
    -------
    >>> [tree_census(1, 4, axes)[:2] for axes in link_axis_trees(4)]
    [(1, {'42/0': 1}), (1, {'42/0': 1}), (0, {}), (1, {'51/1': 1})]
    """
    tree = _Tree(links, axes)
    meshes = links - 1 - dof
    on_axes = [sum(x in axis for axis in axes) for x in range(links)]
    shape = (meshes, tuple(sorted(len(axis) for axis in axes)))
    codes: Counter = Counter()
    rotations: dict = {}
    for chosen in tree.mesh_sets(meshes, method):
        triples = [tree.triples[i] for i in chosen]
        if dof >= 2 and fractionated(links, triples):
            continue
        degrees = on_axes[:]
        for a, b, _ in triples:
            degrees[a] += 1
            degrees[b] += 1
        code = _LEVER_CODES.get((shape, tuple(sorted(degrees))))
        if code is None:
            code = _lever_code(GearTrain(links, axes, [t[:2] for t in triples], [t[2] for t in triples]), shape)
        codes[code] += 1
        if rotation:
            rotations.setdefault(_rotation_key(links, triples), code)
    return sum(codes.values()), dict(codes), rotations


def _tree_summary(args) -> tuple[int, dict, dict]:
    """:func:`tree_census` of ``(dof, links, axes, rotation, method)``: a unit of the executor."""
    return tree_census(*args)


def _rotation_key(links: int, triples) -> bytes:
    """The rotation graph of ``triples`` as the triples renumbered by nauty's canonical labelling
    and sorted, three bytes a mesh: equal exactly when the rotation certificates are (the canonical
    graph is read back from them), and ten times smaller — the census holds one per rotation graph.

    >>> _rotation_key(4, [(0, 3, 2), (1, 3, 2)]) == _rotation_key(4, [(1, 0, 3), (2, 0, 3)])
    True
    """
    label = pynauty.canon_label(rotation_graph(links, triples))  # links keep positions 0 … n − 1
    position = [0] * links
    for k, vertex in enumerate(label[:links]):
        position[vertex] = k
    renumbered = sorted((*sorted((position[a], position[b])), position[t]) for a, b, t in triples)
    return bytes(x for triple in renumbered for x in triple)


_LEVER_CODES: dict = {}  # (meshes, axis sizes, sorted link degrees) -> the lever analogue's code, a process


def _lever_code(train: GearTrain, shape) -> str:
    """The code of ``train``'s lever analogue, remembered under what decides it: the number of meshes,
    the sizes of the axes and the links' degrees (axes and meshes on each)."""
    code = str(train.lever_analogue().code)
    degrees = [sum(x in axis for axis in train.axes) + sum(x in mesh for mesh in train.meshes) for x in range(train.links)]
    _LEVER_CODES[shape, tuple(sorted(degrees))] = code
    return code


def _units(dof: int, links: int, workers: int | None, work, args_of, progress: bool = False):
    """Run ``work`` on every tree, in tree order, inline or on a process pool; ``progress``: a bar
    of the trees done on stderr (on a terminal)."""
    trees = link_axis_trees(links)
    jobs = [args_of(axes) for axes in trees]
    bar = _bar(len(jobs), progress)
    try:
        for result in _run_units(jobs, workers, work):
            bar.update(1)
            yield result
    finally:
        bar.close()


def _bar(total: int, progress: bool):
    """A tqdm bar of ``total`` trees on stderr, shown on a terminal after a second; a bar that
    shows nothing when ``progress`` is false."""
    from tqdm import tqdm

    return tqdm(total=total, unit=" trees", file=sys.stderr, disable=None if progress else True, delay=1.0,
                leave=False, desc="gear trains")


def _run_units(jobs, workers: int | None, work):
    """``work`` on every job, in order: inline for one worker or fewer than 8 jobs, else on a pool
    with at most 4 trees a worker in flight (results never pile up)."""
    with Executor((workers or 1) if len(jobs) >= 8 else 1) as executor:
        yield from executor.map(work, jobs)


def trains(dof: int, links: int, graphs: str = "displacement", workers: int | None = 1,
           progress: bool = False) -> Iterator[GearTrain]:
    """Every train, one per displacement graph, or one (the first) per rotation graph
    (``progress``: a bar of the trees done on stderr).

    >>> [t.compact() for t in trains(1, 4)]
    ['0-1 0-2 0-3 1~2 1~3', '0-1 0-2 1-3 0~3 1~2', '0-1-3 0-2 1~2 2~3']
    """
    check_query(dof, links, graphs)
    seen: set[str] = set()
    for found in _units(dof, links, workers, _tree_list, lambda axes: (dof, links, axes), progress):
        for train in found:
            if graphs == "rotation":
                if train.rotation_certificate in seen:
                    continue
                seen.add(train.rotation_certificate)
            yield train


def _tree_list(args) -> list[GearTrain]:
    return tree_trains(*args)


@dataclass(frozen=True)
class Census(Row):
    """Both counts of a gear-train query: displacement graphs D and rotation graphs R, each by
    lever-analogue code; ``census["rotation"]`` reads its JSON form.

    >>> Census(13, 6, {"521/0": 13}, {"521/0": 6}).to_dict()["rotation_by_code"]
    {'521/0': 6}
    """

    displacement: int
    rotation: int
    by_code: dict
    rotation_by_code: dict

    def __getitem__(self, key: str):
        return self.to_dict()[key]


def census(dof: int, links: int, workers: int | None = 1, method: str = "auto", progress: bool = False) -> Census:
    """Both counts in one pass (:class:`Census`) — a rotation graph counted under the code of its
    first displacement graph (the train :func:`trains` lists for it).  ``method``: "auto" (orderly generation, canonical augmentation on very symmetric trees),
    "orderly" or "augmentation" everywhere (the two must agree).

    >>> census(1, 6)["displacement"], census(1, 6)["rotation"]
    (81, 27)
    """
    check_query(dof, links)
    total, codes, rotations = 0, Counter(), {}
    if method not in _METHODS:
        raise InvalidOption(f"the method is auto, orderly or augmentation, not {method!r}")
    for n, by_code, rot in _units(dof, links, workers, _tree_summary, lambda axes: (dof, links, axes, True, method),
                                  progress=progress):
        total += n
        codes.update(by_code)
        for certificate, code in rot.items():  # trees in order: the first train of a rotation graph wins
            rotations.setdefault(certificate, code)
    return Census(total, len(rotations), dict(sorted(codes.items())),
                  dict(sorted(Counter(rotations.values()).items())))


def count_trains(dof: int, links: int, graphs: str = "displacement", workers: int | None = 1,
                 progress: bool = False) -> Counts:
    """How many trains, in all and ``by_code`` (lever-analogue code: N); for rotation graphs, ``by_code`` counts
    each rotation graph under the code of the train listed for it (its first displacement graph),
    so the codes add up to the count.  ``progress``: a bar on stderr (trees done).

    >>> count_trains(1, 5).to_dict()
    {'count': 13, 'by_code': {'521/0': 3, '530/1': 4, '602/0': 2, '611/1': 2, '620/2': 1, '701/0-1': 1}}
    >>> count_trains(1, 5, graphs="rotation").to_dict()
    {'count': 6, 'by_code': {'521/0': 1, '530/1': 3, '611/1': 2}}
    """
    from ..synthesis.type_synthesis import Counts

    check_query(dof, links, graphs)
    if graphs == "rotation":
        found = census(dof, links, workers, progress=progress)
        return Counts(found.rotation, found.rotation_by_code)
    total, codes = 0, Counter()
    for n, by_code, _ in _units(dof, links, workers, _tree_summary, lambda axes: (dof, links, axes, False, "auto"),
                                progress=progress):
        total += n
        codes.update(by_code)
    return Counts(total, dict(sorted(codes.items())))


# ------------------------------------------------------------------------------ sizing
_CALIBRATED: dict = {}  # (dof, links) -> (displacement, rotation, CPU seconds): counted once a process


def estimate_trains(dof: int, links: int, graphs: str = "displacement", *, budget: float = 2.0):
    """How many trains a query finds and how long it takes, before it runs.

    The same F is counted exactly (both graphs) at the sizes below ``links``, smallest first,
    while the next one is predicted to fit in what is left of ``budget`` CPU seconds.  From the
    last three sizes with trains the growth ratio r(n) = count(n)/count(n − 1) is extrapolated
    linearly, r(n + 1) = r(n) + (r(n) − r(n − 1)), and the count multiplied by it step by step.
    The time is the count times the CPU time per train of the largest size counted: that time
    falls as the trees' fixed costs spread over more trains (1-DOF on the development machine:
    64, 47, 43, 42 µs a train at 7, 8, 9, 10 links), so the estimate errs long (10 links: 46 s
    from 8 links against 38 s measured).  Returns an
    :class:`~synth.synthesis.estimate.Estimate` (``chains``: trains,
    ``units``: link–axis trees, exact), or None when fewer than three smaller sizes have trains.

    Example
    -------
    >>> e = estimate_trains(1, 10)
    >>> 8.0e5 < e.chains < 1.1e6, e.units, e.basis.startswith("exact counts at ")  # 904 156 trains
    (True, 1540, True)
    """
    import math
    import time

    from ..synthesis.estimate import Estimate

    check_query(dof, links, graphs)
    which = 1 if graphs == "rotation" else 0
    sizes, spent, per_train = [], 0.0, 0.0
    for m in range(dof + 2, links):
        if sizes:  # the next size's time: the count's last growth times the time per train, or tenfold
            (_, before), (_, last) = ([(0, None)] + sizes)[-2:]
            predicted = (last[0] ** 2 / before[0] * per_train if before and last and per_train
                         else 10 * _CALIBRATED[dof, sizes[-1][0]][2])
            wanted = sum(1 for _, c in sizes if c) < 3  # an extrapolation needs three sizes with trains
            if spent + predicted > (2 * budget if wanted else budget):
                break
        if (dof, m) not in _CALIBRATED:
            start = time.process_time()
            found = census(dof, m)
            _CALIBRATED[dof, m] = (found["displacement"], found["rotation"], time.process_time() - start)
        d, r, seconds = _CALIBRATED[dof, m]
        spent += seconds
        if d >= 50:  # below, one tree's fixed costs are most of the time
            per_train = seconds / d
        sizes.append((m, (d, r) if d else None))
    counted = [(m, c[which]) for m, c in sizes if c]
    if len(counted) < 3 or per_train == 0.0:
        return None
    (_, c1), (_, c2), (last, c3) = counted[-3:]
    ratio, step = c3 / c2, max(c3 / c2 - c2 / c1, 0.0)
    count = float(c3)
    for k in range(1, links - last + 1):
        count *= ratio + k * step
    displacement = count if which == 0 else count * sizes[-1][1][0] / sizes[-1][1][1]
    seconds = displacement * per_train
    units = len(link_axis_trees(links))
    basis = f"exact counts at {', '.join(str(m) for m, _ in counted[-3:])} links"
    return Estimate(count, units, seconds, basis, math.log10(count), math.log10(units), math.log10(max(seconds, 1e-9)))


def size_check_trains(dof: int, links: int, graphs: str = "displacement", *, processes: int = 1, table: bool = False,
                      force: bool = False) -> str | None:
    """Refuse, within seconds and with an estimate, a gear-train query too large to run unasked.

    Sizes below :data:`SIZED_LINKS` pass at once.  Others are estimated (:func:`estimate_trains`)
    and refused with :class:`~synth.errors.QueryTooLarge` when they would take more than a day on
    ``processes`` workers (unless ``force``), or when a ``table`` would hold more than a million
    rows; a query of more than ten minutes passes with a sentence to show before it starts
    (returned).

    >>> size_check_trains(1, 8) is None
    True
    """
    from ..errors import QueryTooLarge, option
    from ..execution.sizes import describe_seconds, magnitude
    from ..synthesis.estimate import LIMIT_SECONDS, NOTE_SECONDS, TABLE_ROWS

    check_query(dof, links, graphs)
    if links < SIZED_LINKS:
        return None
    found = estimate_trains(dof, links, graphs)
    if found is None:
        return None if force else _refuse_unsized(links, option)
    where = f"on {processes} worker{'s' * (processes > 1)}"
    size = (f"about {magnitude(found.chains)} {graphs} graphs from {magnitude(found.units)} link–axis trees, "
            f"about {describe_seconds(found.seconds / processes)} {where} (extrapolated from the {found.basis})")
    if table and found.chains > TABLE_ROWS:
        raise QueryTooLarge(f"a table is held in memory to align it and this listing ({links} links) is too large "
                            f"for one ({size}); use {option('format', 'jsonl')} or csv (streamed), or {option('count')}")
    if not force and found.seconds / processes > LIMIT_SECONDS:
        raise QueryTooLarge(f"this query ({links} links) is too large to run unasked: {size}; give {option('force')} "
                            "to run it anyway")
    if found.seconds / processes > NOTE_SECONDS:
        return f"a long query: {size}"
    return None


def _refuse_unsized(links: int, option):
    from ..errors import QueryTooLarge

    raise QueryTooLarge(f"this query ({links} links) is large and its size cannot be estimated (fewer than three "
                        f"smaller sizes have trains); give {option('force')} to run it anyway")
