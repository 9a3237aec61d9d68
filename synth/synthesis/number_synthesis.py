"""Number synthesis: every standard code of the counting equations, listed directly or by CP-SAT.

The counting system (docs/theory.md, counting equations) for a chain with n links, K loops and
multiple-joint count v, in a motion space h (or loop classes K_h) with extra
pair mobility f, is

    Σ_i n_i = n = W + 1 + Σ_h (h − 1)·K_h − f
    Σ_i i·n_i + v = 2·(K + n − 1)                (p = K + n − 1 simple-joint equivalents)

over non-negative integers n_1 … n_imax and v.  For planar closed chains this is
Pozhbelko's system W = n2 − Σ_{i≥4}(i − 3)·n_i − v − 3 with Σ n_i = W + 1 + 2K.

A problem of up to some hundred thousand codes (every query of the README, the scenes and the
benchmarks) is listed directly, depth first over the counts; larger ones are enumerated by a CP-SAT
model of the same constraints.  Both give the same set (tests/synthesis/test_number_synthesis_direct.py).

Example
-------
>>> [str(c) for c in number_synthesis(1, loops=2)]
['42/0', '51/1', '60/2']
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, fields, replace

from ..errors import ImpossibleParameters, InvalidOption, QueryTooLarge, option
from ..execution.memo import remembered
from ..structure import check_dof, check_extra_mobility, check_motion_space
from ..structure.code import MAX_LOOPS, Code
from ..structure.query import Range, parse_range, parse_requirements

__all__ = ["CodeQuery", "Problem", "number_synthesis", "iter_codes", "make_problem", "parse_range",
           "parse_requirements", "MAX_CODES"]

# A query is refused unasked above this many codes (an upper bound, counted before any model is
# built): about 40 s and 300 MB of codes (W = 1 lists 140 606 codes at K = 20, 302 085 at K = 22).
MAX_CODES = 200_000
_MAX_LINKS = 1_000_000  # a model's counts are 64-bit: far below that, no chain is ever drawn or stored
_SECONDS_PER_CODE = 2e-4  # measured on the development machine, loaded: 94 551 codes (K = 19) in 19 s


@dataclass(frozen=True)
class CodeQuery:
    """What number synthesis is asked, as given: W, the size, and the options every size shares.

    :func:`make_problem` validates it (one size at a time: a range of loops or links is a
    problem per value, see :func:`iter_codes`).

    Parameters
    ----------
    dof : int
        Required mobility W (0 for statically determinate trusses).
    loops, links : int or range, optional
        K or n (one of them, or ``loop_classes``); a range ``"1..5"`` or ``(1, 5)``
        solves each value in turn.
    loop_classes : mapping h -> K_h, optional
        Heterogeneous systems whose loops live in different motion spaces.
    h : int
        Motion space of a loop (3 planar and spherical, 6 general spatial, …).
    f : int
        Extra mobility of multi-DOF pairs.
    v : int or range, optional
        Multiple-joint count; default every possible value 0 … 2(K−1) + n1.
    n1 : int or range
        Single-joint links (open chains); default 0 (closed chains).
    max_link_degree : int, 'K+1' or 'K+W', optional
        Largest number of joints on one link; default K+1 (non-fractionated closed chains).
    require : mapping or strings ``"I=N"``, ``"I=A..B"``, ``"I=A.."``
        Design constraints on n_I, constraints of the CP-SAT model.
    max_multiplicity : int, optional
        Largest number of links on one joint (2 = simple joints only); default the limit
        theorem's: a joint of order at most K (closed chains) or K + W (open chains), i.e.
        K + 1 or K + W + 1 links (docs/theory.md, "Limit theorems").
    compositions : bool
        Split each code by its joint composition (v2, v3, …).

    Example
    -------
    >>> CodeQuery.of(1, loops="1..5", require=["5=1.."]).loops
    '1..5'
    """

    dof: int
    loops: int | tuple | str | None = None
    links: int | tuple | str | None = None
    loop_classes: Mapping[int, int] | None = None
    h: int = 3
    f: int = 0
    v: int | tuple | str | None = None
    n1: int | tuple | str = 0
    max_link_degree: int | str | None = None
    require: Mapping | Iterable[str] | None = None
    max_multiplicity: int | None = None
    compositions: bool = False

    @classmethod
    def of(cls, query: "CodeQuery | int | None" = None, **options) -> "CodeQuery":
        """The query itself, or one from W and the keywords of :func:`number_synthesis`
        (``dof`` may be a keyword too).

        >>> CodeQuery.of(1, loops=2) == CodeQuery.of(dof=1, loops=2) == CodeQuery(1, loops=2)
        True
        """
        if isinstance(query, CodeQuery):
            if options:
                raise InvalidOption("give a query or its options, not both")
            return query
        if query is not None:
            if "dof" in options:
                raise InvalidOption("W is given twice (as the first argument and as dof)")
            options["dof"] = query
        unknown = sorted(set(options) - {f.name for f in fields(cls)})
        if unknown:
            raise InvalidOption(f"unknown option(s) for number synthesis: {', '.join(unknown)}")
        if "dof" not in options:
            raise InvalidOption("give the degree of freedom W")
        return cls(**options)


@dataclass(frozen=True)
class Problem:
    """One validated counting problem: fixed W, n, K, and the ranges of everything else."""

    dof: int
    links: int
    loops: int
    v: Range
    n1: Range
    max_link_degree: int
    requirements: tuple[tuple[int, Range], ...]
    max_multiplicity: int | None
    compositions: bool


def _loops_for_links(dof: int, links: int, h: int, f: int) -> int:
    if h == 1:
        raise ImpossibleParameters(f"with h = 1 the number of links does not fix the loops: give {option('loops', 'K')}")
    extra = links - dof - 1 + f
    if extra < 0 or extra % (h - 1):
        raise ImpossibleParameters(
            f"no whole number of loops fits: n = W + 1 + (h − 1)·K − f needs n − W − 1 + f = {extra} "
            f"to be a non-negative multiple of h − 1 = {h - 1} (W={dof}, n={links}, h={h}, f={f})"
        )
    return extra // (h - 1)


def make_problem(query: CodeQuery | int | None = None, /, **options) -> Problem:
    """Validate a counting problem of one size (a value of loops or links, or loop classes)
    before any model is built: a :class:`CodeQuery`, or W and its keywords.

    Raises
    ------
    ImpossibleParameters
        With a sentence naming the parameter and the relation that fails.

    Example
    -------
    >>> make_problem(1, loops=4).links
    10
    """
    query = CodeQuery.of(query, **options)
    dof, loops, links, loop_classes, h, f = query.dof, query.loops, query.links, query.loop_classes, query.h, query.f
    max_link_degree, max_multiplicity = query.max_link_degree, query.max_multiplicity
    check_dof(dof), check_motion_space(h), check_extra_mobility(f)
    given = [x is not None for x in (loops, links, loop_classes)]
    if sum(given) != 1:
        raise InvalidOption("give exactly one of loops (K), links (n) or loop classes (K_h)")
    if loop_classes is not None:
        if not loop_classes or any(int(hh) < 1 or int(k) < 0 for hh, k in loop_classes.items()):
            raise ImpossibleParameters("loop classes are pairs h=K_h with h ≥ 1 and K_h ≥ 0")
        for hh in loop_classes:
            check_motion_space(int(hh))  # as --h: 1 … 6
        K = sum(int(k) for k in loop_classes.values())
        n = dof + 1 + sum((int(hh) - 1) * int(k) for hh, k in loop_classes.items()) - f
    elif loops is not None:
        if isinstance(loops, bool) or not isinstance(loops, int) or loops < 0:
            raise ImpossibleParameters(f"the number of loops K must be 0 or more, not {loops!r}")
        K = loops
        n = dof + 1 + (h - 1) * K - f
    else:
        if isinstance(links, bool) or not isinstance(links, int) or links < 1:
            raise ImpossibleParameters(f"the number of links n must be 1 or more, not {links!r}")
        n, K = links, _loops_for_links(dof, links, h, f)
    if n < 1:
        raise ImpossibleParameters(f"W = {dof}, K = {K}, h = {h}, f = {f} leave n = {n} links: impossible")
    if n > _MAX_LINKS:
        raise QueryTooLarge(f"n = {n} links (W = {dof}, K = {K}): number synthesis lists codes of chains of up to "
                            f"{_MAX_LINKS:_} links".replace("_", " "))
    if K > MAX_LOOPS:
        raise QueryTooLarge(f"K = {K} loops (n = {n} links): a code is written with one count per loop, and codes "
                            f"are written and read up to {MAX_LOOPS} loops")
    n1_range = parse_range(query.n1, "n1")
    n1_range = (n1_range[0], n if n1_range[1] is None else min(n1_range[1], n))  # (no more free ends than links)
    if n1_range[0] > n:
        raise ImpossibleParameters(f"n1 = {n1_range[0]} single-joint links do not fit in {n} links")
    closed = n1_range[1] == 0
    if closed and K == 0:
        raise ImpossibleParameters("a closed chain has at least one loop (K ≥ 1); for open chains give n1")
    p = K + n - 1
    # Σ i·n_i ≥ n1 + 2(n − n1) bounds v from above.
    v_cap = 2 * p - 2 * n + n1_range[1]
    v_range = parse_range(query.v, "v") if query.v is not None else (0, v_cap)
    if v_range[1] is None:
        v_range = (v_range[0], v_cap)
    if v_range[0] > v_cap:
        raise ImpossibleParameters(
            f"v = {v_range[0]} is too large: a chain with K = {K} loops and {n} links has v ≤ "
            f"2(K − 1) + n1 = {v_cap}"
        )
    v_range = (v_range[0], min(v_range[1], v_cap))
    if max_link_degree is None or max_link_degree == "K+1":
        imax = K + 1
    elif max_link_degree == "K+W":
        imax = K + dof
    else:
        try:
            imax = int(max_link_degree)
        except (TypeError, ValueError):
            raise InvalidOption(
                f"the largest link degree is a whole number, 'K+1' or 'K+W', not {max_link_degree!r}"
            ) from None
        least = 2 if closed else 1
        if imax < least:
            raise ImpossibleParameters(
                f"the largest link degree must be {least} or more (a link of {'a closed' if closed else 'an open'} "
                f"chain carries at least {least} joint{'s' if least > 1 else ''}), not {imax}")
    imax = max(imax, 1 if not closed else 2)
    reqs = parse_requirements(query.require)
    for i, (lo, hi) in reqs.items():
        if i > imax and lo > 0:
            raise ImpossibleParameters(
                f"a link with {i} joints is required but the largest link allowed here carries {imax} joints "
                f"(the bound {_bound_name(max_link_degree)} with K = {K} loops)"
            )
        if i == 1 and closed and lo > 0:
            raise ImpossibleParameters("a closed chain has no single-joint links; give n1 for an open chain")
        if lo > n:
            raise ImpossibleParameters(f"n{i} ≥ {lo} links is more than the {n} links of the chain")
    if sum(lo for lo, _ in reqs.values()) > n:
        raise ImpossibleParameters(
            f"the requirements ask for {sum(lo for lo, _ in reqs.values())} links, more than n = {n}"
        )
    if max_multiplicity is not None and (isinstance(max_multiplicity, bool) or not isinstance(max_multiplicity, int)
                                         or max_multiplicity < 2):
        raise ImpossibleParameters(
            f"a joint joins at least 2 links: the largest multiplicity must be 2 or more, not {max_multiplicity!r}")
    if max_multiplicity is None:  # limit theorem: a joint of order ≤ K (closed), ≤ K + W (open) joins ≤ order + 1 links
        max_multiplicity = K + 1 if closed else K + dof + 1
    return Problem(dof, n, K, v_range, n1_range, imax, tuple(reqs.items()), max_multiplicity, query.compositions)


def _bound_name(max_link_degree) -> str:
    return "K+1" if max_link_degree is None else str(max_link_degree).replace(" ", "").upper()


def _solve(problem: Problem, tick: Callable[[int], None] | None = None) -> list[Code]:
    """The codes of one validated problem: a problem of few codes by direct enumeration (the
    same set as the CP-SAT model's, which a query of it then never loads), others by the model."""
    from ._sizing import coarse_bound

    bound = coarse_bound(problem)
    if bound is not None and bound <= _DIRECT_CODES:
        codes = list(_direct_codes(problem))
        if tick is not None and codes:
            tick(len(codes))
        return codes
    return _model_codes(problem, tick)


# Problems of at most this many codes by the coarse bound (a pair of partitions of the excess for each
# count of open links) are listed directly: 5–10 times less CPU than the model's enumeration at every
# size measured (12 links, W = 1: 0.5 ms against 5 ms and the 0.3 s of loading OR-Tools; K = 10 with
# compositions, 11 353 codes: 0.08 s against 0.63 s), and a query of them loads no solver.
_DIRECT_CODES = 200_000


def _direct_codes(problem: Problem) -> Iterator[Code]:
    """Every integer solution of the counting model of :func:`_solve_model`, listed directly:
    for each v, the counts n_K+1 … n_3 depth first (largest degree first), n_2 and n_1 then fixed
    by the two counting equations, and each v split into joints as the model splits it.

    The same constraints as the model's, each tested exactly on every solution (the bounds used to
    prune a branch only drop branches that cannot meet them), so the same set of codes.

    >>> sorted(str(c) for c in _direct_codes(make_problem(1, loops=2)))
    ['42/0', '51/1', '60/2']
    >>> [str(c) for c in _direct_codes(make_problem(1, links=4))]   # one loop: every link binary
    ['4/0']
    """
    n, imax = problem.links, problem.max_link_degree
    incidences_of_all = 2 * (problem.loops + n - 1)  # Σ i·n_i + v
    low, high = [0] * (imax + 1), [n] * (imax + 1)  # the bounds of n_i, i = 1 … imax
    for i, (lo, hi) in problem.requirements:
        if i <= imax:
            low[i], high[i] = max(low[i], lo), min(high[i], n if hi is None else hi)
    low[1], high[1] = max(low[1], problem.n1[0]), min(high[1], problem.n1[1])
    # the least links and incidences the degrees below i must take, for i = 1 … imax + 1
    least_links = [sum(low[1:i]) for i in range(imax + 2)]
    least_incidences = [sum(j * low[j] for j in range(1, i)) for i in range(imax + 2)]
    counts = [0] * (imax + 1)

    def fits_below(i: int, links: int, incidences: int) -> bool:
        """Whether ``links`` links of degrees 1 … i − 1 may carry ``incidences`` incidences."""
        if links < least_links[i] or incidences < least_incidences[i] + (links - least_links[i]):
            return False
        if incidences < links + max(0, links - high[1]):  # at most high[1] links of degree 1
            return False
        return incidences <= (i - 1) * links

    def assortments(i: int, links: int, incidences: int) -> Iterator[None]:
        if i <= 2:  # n_2 and n_1 from Σ n = links, Σ i·n = incidences
            n2, n1 = (incidences - links, 2 * links - incidences) if imax >= 2 else (0, links)
            if (imax >= 2 or incidences == links) and low[1] <= n1 <= high[1] and (
                    imax < 2 or low[2] <= n2 <= high[2]):
                counts[1] = n1
                if imax >= 2:
                    counts[2] = n2
                yield None
            return
        for c in range(low[i], min(high[i], links, incidences // i) + 1):
            if fits_below(i, links - c, incidences - i * c):
                counts[i] = c
                yield from assortments(i - 1, links - c, incidences - i * c)

    mmax = problem.max_multiplicity or n
    for v in range(problem.v[0], problem.v[1] + 1):
        incidences = incidences_of_all - v
        splits = _joint_splits(v, incidences, mmax, problem.compositions)
        if not splits or incidences < 0:
            continue
        for _ in assortments(imax, n, incidences):
            assortment = tuple(counts[2:imax + 1])
            for composition in splits:
                yield Code(assortment, v, composition, counts[1])


def _joint_splits(v: int, incidences: int, mmax: int, compositions: bool) -> list[tuple[int, ...] | None]:
    """How the model splits v into multiple joints of at most ``mmax`` links, each of m links taking
    m − 2 of v and m of the ``incidences``: every split (v_3 … v_mmax: joints of 3 … mmax links)
    with ``compositions``, else [None] when one exists (the fewest joints, ⌈v/(mmax − 2)⌉, fit) and
    [] when none does.

    >>> _joint_splits(2, 12, 4, True), _joint_splits(2, 5, 4, False), _joint_splits(1, 12, 2, False)
    ([(0, 1), (2, 0)], [None], [])
    """
    if not compositions:
        if mmax <= 2:
            return [None] if v == 0 else []
        joints = -(-v // (mmax - 2))
        return [None] if v + 2 * joints <= incidences else []
    parts = max(mmax - 2, 0)  # a joint of m links takes p = m − 2 of v: p = 1 … parts
    found: list[tuple[int, ...]] = []
    split = [0] * parts

    def place(p: int, left: int, joints: int) -> None:  # parts of size p, then smaller ones
        if left == 0:
            if v + 2 * joints <= incidences:
                found.append(tuple(split))
            return
        if p == 0:
            return
        for k in range(left // p, -1, -1):
            split[p - 1] = k
            place(p - 1, left - k * p, joints + k)
        split[p - 1] = 0

    place(parts, v, 0)
    return found


def _model_codes(problem: Problem, tick: Callable[[int], None] | None = None) -> list[Code]:
    """The codes of the CP-SAT model of one validated problem, solved once per engine (a later run
    reads them: :mod:`synth.execution.memo`)."""
    return remembered("codes", repr(problem), lambda: _solve_model(problem, tick),
                      encode=lambda codes: [[list(c.assortment), c.v, c.composition and list(c.composition), c.n1]
                                            for c in codes],
                      decode=lambda rows: [Code(tuple(a), v, comp if comp is None else tuple(comp), n1)
                                           for a, v, comp, n1 in rows])


def _solve_model(problem: Problem, tick: Callable[[int], None] | None = None) -> list[Code]:
    """Build and enumerate the CP-SAT model of one validated problem."""
    from ._cpsat import all_solutions, cp_model  # loaded by the first query that needs a solver

    n, K, imax = problem.links, problem.loops, problem.max_link_degree
    model = cp_model.CpModel()
    counts = {i: model.new_int_var(0, n, f"n{i}") for i in range(1, imax + 1)}
    model.add(counts[1] >= problem.n1[0])
    model.add(counts[1] <= problem.n1[1])
    for i, (lo, hi) in problem.requirements:
        if i > imax:
            continue  # only upper bounds remain on links that cannot exist
        model.add(counts[i] >= lo)
        if hi is not None:
            model.add(counts[i] <= hi)
    v = model.new_int_var(problem.v[0], problem.v[1], "v")
    model.add(sum(counts.values()) == n)
    model.add(sum(i * c for i, c in counts.items()) + v == 2 * (K + n - 1))
    variables = [counts[i] for i in range(1, imax + 1)] + [v]
    # v must split into joints of at most max_multiplicity links, each taking m ≥ 3 distinct
    # link incidences; without compositions the split is only required to exist
    mmax = problem.max_multiplicity or n
    incidences = sum(i * c for i, c in counts.items())
    if problem.compositions:
        comp = [model.new_int_var(0, problem.v[1], f"v{k}") for k in range(2, mmax)]
        model.add(sum((k + 1) * x for k, x in enumerate(comp)) == v)
        model.add(sum((k + 3) * x for k, x in enumerate(comp)) <= incidences)
        variables += comp
    elif mmax <= 2:
        model.add(v == 0)
    else:
        # a split exists iff the fewest joints, J = ⌈v/(mmax − 2)⌉ (each takes m − 2 ≤ mmax − 2 of v),
        # find their v + 2J link incidences; J is fixed by v, so no solution repeats (enumerating
        # the splits themselves repeated each code once per split: 11 344 solutions for 1 410 codes)
        J = model.new_int_var(0, problem.v[1], "joints")
        model.add(J * (mmax - 2) >= v)
        model.add((J - 1) * (mmax - 2) <= v - 1)
        model.add(v + 2 * J <= incidences)
    codes = []
    for sol in all_solutions(model, variables, tick=tick):
        n1, assortment, vv = sol[0], sol[1:imax], sol[imax]
        composition = tuple(sol[imax + 1 :]) if problem.compositions else None
        codes.append(Code(assortment, vv, composition, n1))
    return codes


def sort_key(code: Code):
    """Deterministic order: loops, open links, v, assortment, composition."""
    return (code.loops, code.n1, code.v, code.assortment, code.composition or ())


def number_synthesis(query: CodeQuery | int | None = None, /, *, max_codes: int | None = MAX_CODES,
                     **options) -> list[Code]:
    """Every standard code for W = ``dof`` and the given loops or links.

    Parameters
    ----------
    query : CodeQuery or int
        The query, or W (0 for trusses) with the options of :class:`CodeQuery` as keywords:
        ``loops``, ``links`` or ``loop_classes`` (the size; a range of loops or links solves each
        value in turn), ``h``, ``f``, ``v``, ``n1``, ``max_link_degree``, ``require``,
        ``max_multiplicity``, ``compositions``.
    max_codes : int or None
        Refuse (``QueryTooLarge``) a query that may have more codes than this, sized before any
        model is built (see :mod:`synth.synthesis._sizing`); None lists any number.

    Returns
    -------
    list of Code
        In deterministic order (K, n1, v, assortment).

    Raises
    ------
    ImpossibleParameters, InvalidOption, QueryTooLarge

    Examples
    --------
    >>> [str(c) for c in number_synthesis(1, loops=4, require=["5=1.."])]
    ['6301/0', '7111/0', '8002/0', '7201/1', '8011/1', '8101/2', '9001/3']
    >>> len(number_synthesis(1, loops="1..5"))
    89
    """
    return sorted(set(iter_codes(query, max_codes=max_codes, **options)), key=sort_key)


_MAX_VALUES = 1000  # a range of loops or links solves one model per value


def iter_codes(query: CodeQuery | int | None = None, /, *, max_codes: int | None = MAX_CODES,
               progress: Callable[[int], None] | None = None, **options) -> Iterator[Code]:
    """:func:`number_synthesis` one value of K (or n) at a time, in the same order: memory holds the
    codes of one value.  Every value is validated and the whole query sized before the first code.

    ``progress`` is called with the number of codes found since its last call (about every thousand).

    >>> [str(c) for c in iter_codes(1, loops="1..2")]
    ['4/0', '42/0', '51/1', '60/2']
    """
    query = CodeQuery.of(query, **options)
    dof, loops, links = query.dof, query.loops, query.links
    if query.loop_classes is not None:
        problems = [make_problem(query)]
    else:
        which = "loops" if loops is not None else "links"
        rng = parse_range(loops if loops is not None else links, "K" if loops is not None else "n")
        if rng is None:
            raise InvalidOption("give exactly one of loops (K), links (n) or loop classes (K_h)")
        if rng[1] is None:
            raise InvalidOption(f"the range of {which} needs an upper end")
        if loops is not None and links is not None:
            raise InvalidOption("give exactly one of loops (K), links (n) or loop classes (K_h)")
        if rng[1] - rng[0] >= _MAX_VALUES:
            raise QueryTooLarge(f"the range {rng[0]}..{rng[1]} of {which} has {rng[1] - rng[0] + 1} values; "
                                f"number synthesis solves one model per value and takes at most {_MAX_VALUES}")
        problems = []
        for value in range(rng[0], rng[1] + 1):
            try:
                problems.append(make_problem(replace(query, **{which: value})))
            except ImpossibleParameters:
                if rng[0] == rng[1]:
                    raise  # a single value that is impossible is an error, in a range it is skipped
        if not problems:
            raise ImpossibleParameters(f"no value of {which} in {rng[0]}..{rng[1]} is possible for W = {dof}")
    _refuse_too_many(problems, max_codes)
    for problem in problems:
        yield from sorted(set(_solve(problem, progress)), key=sort_key)


def _refuse_too_many(problems: list[Problem], max_codes: int | None) -> None:
    """Size the problems (largest first) and refuse them together above ``max_codes`` codes."""
    from ._sizing import check_excess, coarse_bound, code_bound
    from ..execution.sizes import describe_seconds, magnitude

    if max_codes is None:  # asked for any number: only a model that cannot exist is refused
        for problem in problems:
            check_excess(problem)
        return
    coarse = [coarse_bound(problem) for problem in problems]
    if None not in coarse and sum(coarse) <= max_codes:
        return  # surely few codes: the finer bound's tables are not needed
    total, exact = 0.0, True
    for problem in sorted(problems, key=lambda p: -p.loops):
        bound = code_bound(problem, stop=max_codes - total)
        total += bound.value
        exact &= bound.exact
        if total > max_codes:
            if not math.isfinite(total):
                size = "more than 1e+308 codes"
            else:
                size = (f"{'more than' if not exact else 'up to'} {magnitude(total)} codes "
                        f"({'more than ' if not exact else 'about '}{describe_seconds(total * _SECONDS_PER_CODE)})")
            where = f"K = {problems[0].loops}" if len(problems) == 1 else \
                f"K = {min(p.loops for p in problems)} … {max(p.loops for p in problems)}"
            raise QueryTooLarge(f"this query ({where} loops, n = {max(p.links for p in problems)} links) may have "
                                f"{size}, more than the {magnitude(max_codes)} codes number "
                                "synthesis lists unasked; narrow it (fewer loops, a range of v, requirements "
                                "or a lower link-degree bound)")
