"""Heterogeneous chains: loops of two motion spaces, a base of one class with groups of another.

Pozhbelko's linear translator (Fig. 12б) is a toroidal six-link loop of class V (h = 5) with two
four-link, three-driver groups of class III (h = 3) attached: K_3 = 4, K_5 = 1.  A heterogeneous
chain here is a chain of the *ambient* class h (the lower one) whose *base* — a set of links, each on
a loop of base links — carries the loops of the higher class x: the loops made of base links alone
are of class x, every other loop of class h, and

    W(S) = h(|S| − 1) − (h − 1)·p(S) − (x − h)·c_x(S)

for every set S of links, c_x(S) the cycle rank of the base links in S (docs/theory.md,
"Heterogeneous chains").  Since W_h(S) ≥ W(S), every such chain is a chain of class h that passes
the homogeneous test with mobility W + (x − h)·K_x: type synthesis builds those (the *skeletons*)
and :func:`class_variants` lays every base on each, as the prismatic variants lay P pairs.

Example
-------
>>> toroid = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0")
>>> [v.compact() for v in class_variants(toroid, 5, 1)]
['0-1 0-5 1-2 2-3 3-4 4-5 | h5: 0 1 2 3 4 5']
>>> sum(1 for _ in heterogeneous_synthesis(1, {3: 1, 5: 1}, links=8, workers=1))
5
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from itertools import combinations

from ..errors import ImpossibleParameters, InvalidOption
from ..structure.chain import Chain
from ..structure.disjoint import DisjointSets
from ..structure.kinds import cycle_rank, restricted_pairs
from ..structure.query import ChainQuery
from ..structure.subchains import least_base_mobilities

__all__ = ["split_classes", "class_variants", "skeleton_query", "heterogeneous_synthesis", "size_note"]

# Laying every base on one skeleton and testing them, in the parent process: 1 785 skeletons of the
# translator's query (14 links, about 20 candidate loops each) took 9.5 CPU s of its 12 (shared machine)
SECONDS_PER_SKELETON = 0.006
_SIZED_LOOPS = 5  # skeleton queries of fewer loops end in seconds: they are not estimated


def split_classes(loop_classes: Mapping[int, int]) -> tuple[int, int, int, int]:
    """The ambient class h, its loops K_h, the base class x > h and its loops K_x of a query's
    loop classes (two classes, each with at least one loop).

    >>> split_classes({5: 1, 3: 4})
    (3, 4, 5, 1)
    >>> split_classes({3: 4})
    Traceback (most recent call last):
    ...
    synth.errors.InvalidOption: loop classes build chains of two classes, each with a loop or more (K_h ≥ 1), not {3: 4}: one class is a homogeneous chain (--h)
    """
    classes = {int(h): int(k) for h, k in dict(loop_classes).items()}
    if len(classes) != 2 or min(classes.values()) < 1:
        raise InvalidOption(f"loop classes build chains of two classes, each with a loop or more (K_h ≥ 1), not "
                            f"{classes}: one class is a homogeneous chain (--h)")
    bad = [h for h in classes if not 2 <= h <= 6]
    if bad:
        raise ImpossibleParameters(f"a chain's loop class is a motion space 2 … 6, not {bad[0]}")
    (h, k_h), (x, k_x) = sorted(classes.items())
    return h, k_h, x, k_x


def h_beside_classes(h: str, classes: str) -> InvalidOption:
    """The refusal of a motion space ``h`` (``--h``, or a scene's key so named) given beside loop classes
    ``classes``, whatever its value, 3 too: the classes give each loop's motion space, the lower one the chain's,
    so an h beside them is ignored (a code's, a count's and the chains' h come from them) or contradicts them.

    >>> print(h_beside_classes("--h", "--loop-classes"))
    --h and --loop-classes contradict each other: the classes give each loop's motion space (the lower class is the chain's h)
    """
    return InvalidOption(f"{h} and {classes} contradict each other: the classes give each loop's motion space (the "
                         "lower class is the chain's h)")


def _cycles(chain: Chain) -> list[frozenset[int]]:
    """The link sets of the simple loops of a chain: the elements of the cycle space of its
    link–joint incidence graph (sums of fundamental cycles) that are single cycles.

    >>> [sorted(c) for c in _cycles(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"))]
    [[0, 1, 2, 3], [0, 1, 2, 3, 4, 5], [0, 1, 4, 5]]
    """
    n = chain.links
    edges = [(x, n + k) for k, j in enumerate(chain.joints) for x in j]  # link x – joint k
    joined = DisjointSets(range(n + len(chain.joints)))
    tree, chords = [], []
    for e, (a, b) in enumerate(edges):
        (tree if joined.union(a, b) else chords).append(e)
    adjacent: dict[int, list[tuple[int, int]]] = {}
    for e in tree:
        a, b = edges[e]
        adjacent.setdefault(a, []).append((b, e))
        adjacent.setdefault(b, []).append((a, e))

    def tree_path(a, b) -> int:  # the tree edges from a to b, as a bit mask
        stack, seen = [(a, 0)], {a}
        while stack:
            v, mask = stack.pop()
            if v == b:
                return mask
            for w, e in adjacent[v]:  # (every vertex reached has a tree edge: a chord's end was joined before)
                if w not in seen:
                    seen.add(w)
                    stack.append((w, mask | 1 << e))
        raise AssertionError("a chord's ends are joined by the spanning tree")

    fundamental = [tree_path(*edges[e]) | 1 << e for e in chords]
    found = set()
    for pick in range(1, 1 << len(fundamental)):
        mask = 0
        for i, cycle in enumerate(fundamental):
            if pick >> i & 1:
                mask ^= cycle
        chosen = [edges[e] for e in range(len(edges)) if mask >> e & 1]
        degree: dict[int, int] = {}
        for a, b in chosen:
            degree[a] = degree.get(a, 0) + 1
            degree[b] = degree.get(b, 0) + 1
        # every vertex on two of the edges: disjoint cycles, as many as the cycle rank (one: connected)
        if any(d != 2 for d in degree.values()) or cycle_rank(degree, chosen) != 1:
            continue
        found.add(frozenset(v for v in degree if v < n))
    return sorted(found, key=sorted)


def _bases(chain: Chain, loops: int) -> Iterator[frozenset[int]]:
    """Every set of links that is a union of loops and holds exactly ``loops`` independent loops
    of its own (each joint restricted to it), once.  Every link of such a set lies on one of its
    loops, and a set whose links all do is the union of that many loops (an ear decomposition)."""
    cycles = _cycles(chain)
    seen: set[frozenset[int]] = set()
    for chosen in combinations(cycles, loops):
        base = frozenset().union(*chosen)
        if base in seen:
            continue
        seen.add(base)
        pairs = [pair for j in chain.joints for pair in restricted_pairs(j, base)]
        if cycle_rank(base, pairs) == loops:
            yield base


def class_variants(chain: Chain, base_class: int, loops: int, *, rigid_subchains: bool | None = None) -> list[Chain]:
    """Every base of ``loops`` loops of class ``base_class`` on a homogeneous chain (whose own
    class ``chain.h`` is the groups'), once up to symmetry, that passes the exact heterogeneous
    test; sorted by certificate.

    Parameters
    ----------
    chain : Chain
        A homogeneous, all-revolute chain: its ``h`` is the class of the loops outside the base.
    base_class : int
        x > h, the motion space of the base's loops.
    loops : int
        K_x ≥ 1, the independent loops of the base.
    rigid_subchains : bool, optional
        Allow sub-chains of W(S) = 0 (default: where the chain's heterogeneous W is 0).

    Returns
    -------
    list of Chain
        Heterogeneous chains, W = the chain's W − (x − h)·K_x.

    Examples
    --------
    >>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    >>> [v.compact() for v in class_variants(watt, 4, 1)]          # a four-link loop of class IV: W = 0
    ['0-1 0-3 0-4 1-2 1-5 2-3 4-5 | h4: 0 1 2 3']
    """
    if not chain.all_revolute or chain.classes is not None:
        raise InvalidOption(f"loop classes are laid on a homogeneous revolute chain, not on {chain.compact()}")
    if isinstance(base_class, bool) or not isinstance(base_class, int) or not chain.h < base_class <= 6:
        raise InvalidOption(f"the base's class must be above the chain's own class h = {chain.h} (and at most 6), "
                            f"not {base_class!r}")
    if isinstance(loops, bool) or not isinstance(loops, int) or not 1 <= loops <= chain.loops:
        raise InvalidOption(f"a base holds 1 … {chain.loops} of the chain's loops, not {loops!r}")
    dof = chain.dof - (base_class - chain.h) * loops
    rigid = dof == 0 if rigid_subchains is None else rigid_subchains
    bases = list(_bases(chain, loops))  # (never empty: a cycle and ears on it hold every count 1 … K of loops)
    least = least_base_mobilities(chain, base_class, bases)
    found: dict[str, Chain] = {}
    for base, low in zip(bases, least):
        if low >= (0 if rigid else 1):
            variant = Chain.trusted(chain.links, chain.joints, chain.h, None,
                                    tuple(base_class if i in base else chain.h for i in range(chain.links)))
            found.setdefault(variant.certificate, variant)
    return [found[c] for c in sorted(found)]


_SELECTION = ("code", "v", "require", "cranks", "fractionated", "planar_only", "max_multiplicity", "rigid_subchains")


def skeleton_query(dof: int, loop_classes: Mapping[int, int], *, links: int | None = None, **options) -> ChainQuery:
    """The homogeneous query whose chains carry the heterogeneous ones: class h (the lower),
    mobility W + (x − h)·K_x, the same links, code and selection.

    >>> q = skeleton_query(1, {3: 4, 5: 1}, code="12.2000/6-0"); q.dof, q.h, q.links
    (3, 3, 14)
    """
    h, k_h, x, k_x = split_classes(loop_classes)
    n = dof + 1 + (h - 1) * k_h + (x - 1) * k_x
    if links is not None and links != n:
        raise ImpossibleParameters(f"W = {dof} with {k_h} loop(s) of class {h} and {k_x} of class {x} needs "
                                   f"n = W + 1 + Σ (h − 1)·K_h = {n} links, not {links}")
    unknown = sorted(set(options) - set(_SELECTION))
    if unknown:
        raise InvalidOption(f"unknown option(s) for heterogeneous chains: {', '.join(unknown)}")
    rigid = options.pop("rigid_subchains", None)
    rigid = dof == 0 if rigid is None else rigid
    return ChainQuery(dof + (x - h) * k_x, n, h=h, rigid_subchains=rigid, **options)


def size_note(skeletons: ChainQuery, *, processes: int, force: bool = False) -> str | None:
    """Size a heterogeneous query before it runs, from the estimate of its skeletons (type synthesis
    on ``processes`` workers) and the bases laid on each in the parent: refuse with the estimate
    one of more than a day unless ``force``, and return a sentence for one of more than ten
    minutes (None otherwise, and for queries of fewer than five loops, which end in seconds).

    >>> size_note(skeleton_query(1, {3: 1, 5: 1}), processes=2) is None
    True
    """
    from ..errors import QueryTooLarge, option
    from ..execution.sizes import describe_seconds, magnitude
    from .estimate import LIMIT_SECONDS, NOTE_SECONDS, estimate

    if skeletons.loops < _SIZED_LOOPS:
        return None
    found = estimate(skeletons, work="list", budget=5.0)  # (a query of five loops or more takes longer itself)
    if found is None:  # too few smaller sizes to extrapolate from (a fixed code), or no time to count them
        return None
    seconds = found.seconds / processes + found.chains * SECONDS_PER_SKELETON
    size = (f"about {magnitude(found.chains, found.log10_chains)} skeletons of W = {skeletons.dof} in class "
            f"h = {skeletons.h}, each given its bases, {describe_seconds(seconds)} on {processes} worker"
            f"{'s' * (processes > 1)} (extrapolated from the {found.basis})")
    if seconds > LIMIT_SECONDS and not force:
        raise QueryTooLarge(f"this heterogeneous query ({skeletons.links} links) is too large to run unasked: {size}; "
                            f"give {option('force')} to run it anyway, or narrow it ({option('code', 'C')}, "
                            f"{option('v', 'N')})")
    return f"a long query: {size}" if seconds > NOTE_SECONDS else None


def heterogeneous_synthesis(dof: int, loop_classes: Mapping[int, int], *, links: int | None = None,
                            workers: int | None = None, progress: bool = False, **options) -> Iterator[Chain]:
    """Every non-isomorphic heterogeneous chain of mobility ``dof`` with the loops ``loop_classes``
    (two classes, K_h loops of the lower class h and K_x of the higher class x, the base).

    Parameters
    ----------
    dof : int
        W by the heterogeneous count, W = (n − 1) − Σ (h − 1)·K_h.
    loop_classes : mapping h -> K_h
        The loops of each class, e.g. ``{3: 4, 5: 1}`` (the linear translator).
    links : int, optional
        n; it follows from W and the classes, so it is only checked.
    workers, progress :
        As for :func:`~synth.synthesis.type_synthesis.type_synthesis` (the skeletons).
    **options
        The selection of :class:`~synth.structure.query.ChainQuery` (``code``, ``v``, ``require``,
        ``cranks``, ``fractionated``, ``planar_only``, ``max_multiplicity``, ``rigid_subchains``).

    Yields
    ------
    Chain
        Skeleton by skeleton in the order of type synthesis, each skeleton's bases by certificate,
        each in its canonical labelling (:meth:`~synth.structure.chain.Chain.canonical`).

    Examples
    --------
    >>> for c in heterogeneous_synthesis(1, {2: 1, 3: 1}, workers=1):   # a lever loop on a wedge system
    ...     print(c.compact(), c.dof, c.loop_classes)
    0-3 0-4 1-3 1-4 2-3 2-4 | h2; h3: 1 2 3 4 1 {2: 1, 3: 1}
    0-3 0-4 1-2 1-4 2-3 3-4 | h2; h3: 1 2 3 4 1 {2: 1, 3: 1}
    """
    from .type_synthesis import type_synthesis

    skeletons = skeleton_query(dof, loop_classes, links=links, **options)
    _, _, x, k_x = split_classes(loop_classes)
    for skeleton in type_synthesis(skeletons, workers=workers, progress=progress):
        yield from (c.canonical() for c in class_variants(skeleton, x, k_x, rigid_subchains=skeletons.rigid))
