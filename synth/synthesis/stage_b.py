"""Stage B of type synthesis: the chains of one branch multigraph H, placing the binary links.

The n2 binary links are distributed on the strings (edges) of H, keeping the lex-least weight
vector of each orbit of the automorphisms of H (from nauty), so no chain comes out twice where
the whole group of H is listed.  Three ways find the placements, all under the same conditions:

* the compiled kernel of :mod:`synth.synthesis._stage_b_kernel` for large queries (a pebble game:
  exact for simple joints, a weaker rule with multiple joints, where the exact test decides);
* where the placements are few, a direct listing (numpy) that the exact sub-chain test, batched
  on H for every joint kind, filters;
* otherwise a CP-SAT model with the exact sub-chain conditions of docs/theory.md written on the
  strings (necessary conditions with multiple joints) and lex-leader constraints.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import combinations
from math import comb
from time import perf_counter

from ..structure.chain import Chain
from ..structure.code import Code
from .stage_a import Contracted, Conventions, _contracted_by_kernel, _inner_links, _loop_lb, uses_kernel

__all__ = ["BY_SEARCH", "count_listed", "count_orbits", "count_realised", "count_reversed", "load_kernel", "orbits_apply", "realise"]

_LEX_BITS = 52  # keep lex-leader coefficients exact in CP-SAT's linear constraints
# stage B lists the weight vectors directly up to this many (no model to build); 4096 -> 16384:
# planar 12 links count 0.44 -> 0.27 CPU s, 14 links 12.3 -> 11.4 s (PROFILE.md section 13)
_FEW_VECTORS = 16384
_LEX_BLOCK = 1 << 20  # entries of one numpy block of (vectors × automorphisms × edges) in that enumeration
_KERNEL_ROWS = 4096  # placements a listing reads from the kernel's first pass (more: a second pass)
# entries (placements × strings, 16 MiB) a count with multiple joints reads from the kernel's first pass: a
# second pass repeats the whole search (14 links, v = 0..12: 40 % of the kernel's time with 4096 rows)
_COUNT_ENTRIES = 1 << 21


def realise(code: Code, graph: Contracted, conv: Conventions, stats: dict | None = None) -> list[Chain]:
    """Stage B: all chains of ``code`` whose branch multigraph is ``graph``, once each, by certificate."""
    solutions, _, checked = _distributions(code, graph, conv, stats)
    return _distinct(graph, conv, _passing(graph, conv, solutions, stats, checked), stats)


def count_realised(code: Code, graph: Contracted, conv: Conventions, stats: dict | None = None, *,
                   programme: bool = True) -> int:
    """``len(realise(code, graph, conv))``, without chains or certificates where they are not needed.

    Chains with the branch multigraph H are isomorphic exactly when an automorphism of H maps
    one weight vector onto the other; when the whole group of H is listed, stage B keeps the
    lex-least vector of each orbit, so the chains are the vectors that pass the sub-chain test
    (docs/theory.md). Otherwise the chains are built and compared.

    >>> from synth.synthesis.stage_a import contracted_graphs
    >>> graph = contracted_graphs(Code((4, 2), 0, ()), Conventions())[0]
    >>> code = Code((4, 2), 0, ())
    >>> count_realised(code, graph, Conventions()), len(realise(code, graph, Conventions()))
    (2, 2)

    With multiple joints a unit is counted without visiting its placements where :func:`_programme_fault` finds
    nothing (``programme`` off: always by the search and the exact test, the check of the programme).
    """
    if uses_kernel(code, conv) and _kernel_applies(code, graph, conv):
        simple = not any(_vertex_terms(graph.vertices, conv)[1])
        if simple or 2 - conv.h < conv.threshold:  # (else two joints on the same links need the chains)
            found, placements, whole_group = _kernel_placements(code, graph, conv, stats, listing=False,
                                                                rows=not simple, programme=programme)
            if whole_group and (simple or placements is None):  # (None: counted by the programme)
                return found
            if whole_group:  # multiple joints: the exact test keeps the valid ones among the kernel's
                t0 = perf_counter()
                valid = int(_exact_test(graph.vertices, graph.edges, placements, conv, compiled=True).sum()) if found else 0
                _add(stats, subchain_s=perf_counter() - t0)
                return valid
    solutions, one_per_orbit, checked = _distributions(code, graph, conv, stats)
    kept = _passing(graph, conv, solutions, stats, checked)
    return len(kept) if one_per_orbit else len(_distinct(graph, conv, kept, stats))


def count_listed(code: Code, graph: Contracted, conv: Conventions) -> int:
    """The chains the listing path finds for one unit: the weight vectors it lists that pass the
    sub-chain test, one per orbit where the whole group of H is listed (else the chains, by
    certificate) — the listing's own count, against which :func:`count_realised`'s search is checked.

    >>> from synth.synthesis.stage_a import contracted_graphs
    >>> code = Code((4, 2), 0, ())
    >>> graph = contracted_graphs(code, Conventions())[0]
    >>> count_listed(code, graph, Conventions()) == count_realised(code, graph, Conventions()) == 2
    True
    """
    solutions, one_per_orbit, checked = _distributions(code, graph, conv, None)
    if one_per_orbit and checked:
        return len(_passing(graph, conv, solutions, None, checked))
    return len(realise(code, graph, conv))


def _distinct(graph: Contracted, conv: Conventions, kept: list, stats: dict | None) -> list[Chain]:
    """The chains of the passing vectors ``kept``, once each by certificate."""
    t0 = perf_counter()
    found: dict[str, Chain] = {}
    for chain in (_expand(graph.vertices, graph.edges, s, conv.h) for s in kept):
        found.setdefault(chain.certificate, chain)
    _add(stats, nauty_s=perf_counter() - t0)
    return [found[c] for c in sorted(found)]


def _string_limits(graph: Contracted, conv: Conventions) -> tuple[list[int], list[tuple[int, int]]]:
    """Least binary links of each string of H, and the strings parallel to the one before them
    with their own least weight: (string, least) pairs."""
    edges = graph.edges
    loop_least, joint = _vertex_terms(graph.vertices, conv)
    lows = [loop_least[u] if u == v else int(joint[u] and joint[v]) for u, v in edges]
    # parallel strings: non-decreasing (a symmetry of H); two joints never join the same links
    # (a direct joint or incidence at most once), and two one-link strings between two multiple
    # joints (W = 2 − h) only where the convention allows it
    parallel = [(k, 0 if u == v else 2 if joint[u] and joint[v] and 2 - conv.h < conv.threshold else 1)
                for k, (u, v) in enumerate(edges) if k and edges[k] == edges[k - 1]]
    return lows, parallel


@lru_cache(maxsize=256)
def _vertex_terms(vertices: tuple, conv: Conventions) -> tuple[tuple[int, ...], tuple[bool, ...]]:
    """Per branch vertex of H: the least binary links of a loop through it, and whether it is a
    multiple joint (shared by every H of a code)."""
    return tuple(_loop_lb(vertex, conv) for vertex in vertices), tuple(vertex.is_joint for vertex in vertices)


def _distributions(code: Code, graph: Contracted, conv: Conventions, stats: dict | None) -> tuple[list, bool, bool]:
    """Stage B's CP-SAT model: candidate weight vectors of ``graph`` (binary links per string),
    whether they are one per orbit of Aut(H) (lex-least under the whole group), and whether
    they meet the sub-chain rule already (the model's conditions, exact for simple joints)."""
    vertices, edges = graph.vertices, graph.edges
    n2 = code.count(2)
    space = conv.h
    lows, parallel = _string_limits(graph, conv)
    spare = n2 - sum(lows)
    if spare < 0:
        return [], True, True
    # simple joints: the model's conditions are the exact test, unless the whole chain is exempt
    # (W below the threshold), where the model skips every set of all branch links
    simple = all(vertex.is_link for vertex in vertices) and code.dof(space) >= conv.threshold
    if uses_kernel(code, conv) and _kernel_applies(code, graph, conv):
        _, placements, whole_group = _kernel_placements(code, graph, conv, stats, listing=True)
        return list(map(tuple, placements.tolist())), whole_group, all(vertex.is_link for vertex in vertices)
    if not conv.cranks and comb(spare + len(edges) - 1, len(edges) - 1) <= _FEW_VECTORS:
        return _few_distributions(lows, spare, parallel, graph, stats)
    from ._cpsat import all_solutions, cp_model

    model = cp_model.CpModel()
    w = [model.new_int_var(lb, n2, f"w{k}") for k, lb in enumerate(lows)]
    model.add(sum(w) == n2)
    for k, least in parallel:
        model.add(w[k] >= w[k - 1])
        model.add(w[k] >= least)
    # sub-chain conditions on sets T of branch vertices (links T_L and multiple joints T_J):
    # S = T_L + the binary links of every string inside T with w < h − 1 binary links has
    # W(S) ≤ h(|T_L| − 1) + (h − 1)·|T_J| − Σ_{strings inside T} (h − 1 − w)⁺  (an empty string
    # is a joint of two links of T or a link of T on a joint of T), with equality when every J
    # of T_J is touched: exact for simple joints, necessary otherwise.  short[k][t] ⇔ w_k = t.
    short: dict[int, dict[int, object]] = {}
    for k, (u, v) in enumerate(edges):
        if u == v:
            continue
        first = 1 if vertices[u].is_joint and vertices[v].is_joint else 0
        short[k] = {t: model.new_bool_var(f"s{k}_{t}") for t in range(first, space - 1)}
        for t, flag in short[k].items():
            model.add(w[k] == t).only_enforce_if(flag)
        model.add(w[k] >= space - 1).only_enforce_if([flag.negated() for flag in short[k].values()])
        if len(short[k]) > 1:
            model.add_at_most_one(short[k].values())
    link_vertices = _inner_links(vertices)
    n_links = sum(1 for vertex in vertices if vertex.is_link)
    joint_vertices = [u for u, vertex in enumerate(vertices) if vertex.is_joint]
    dof = code.dof(space)
    for size in range(1, len(link_vertices) + 1):
        for TL in combinations(link_vertices, size):
            for jsize in range(len(joint_vertices) + 1):
                for TJ in combinations(joint_vertices, jsize):
                    _subset_constraint(model, vertices, edges, short, set(TL), set(TJ), n_links, dof, conv)
    # required sub-structure: a link with I joints carrying C cranks (invariant under Aut(H))
    z = {k: flags[0] for k, flags in short.items() if 0 in flags}  # z[k] ⇔ string k is empty
    for joints_on_link, count in conv.cranks:
        chosen = []
        for u in link_vertices:
            if vertices[u].degree != joints_on_link:
                continue
            ends = [1 - z[k] if k in z else 1 for k, e in enumerate(edges) if u in e and e[0] != e[1]]
            ends += [2 for e in edges if e == (u, u)]
            sel = model.new_bool_var(f"cranks{u}")
            model.add(sum(ends) >= count).only_enforce_if(sel)
            model.add(sum(ends) <= count - 1).only_enforce_if(sel.negated())
            chosen.append(sel)
        if not chosen:
            return [], True, True
        model.add_bool_or(chosen)
    # lex-leader for the automorphisms of H (a prefix short enough for exact coefficients)
    base = n2 + 1
    prefix = max(1, min(len(edges), int(_LEX_BITS // max(1.0, base.bit_length()))))
    group, whole_group = graph.edge_group()
    weights = [base ** (prefix - 1 - i) for i in range(prefix)]
    lhs = cp_model.LinearExpr.weighted_sum(w[:prefix], weights)
    for g in group:
        model.add(lhs <= cp_model.LinearExpr.weighted_sum([w[g[i]] for i in range(prefix)], weights))
    t0 = perf_counter()
    solutions = all_solutions(model, w)
    if whole_group and prefix < len(edges) and group and solutions:
        # the model's lex-leader covers a prefix of the edges only: keep the lex-least of each orbit
        import numpy as np

        solutions = list(map(tuple, _lex_least(np.asarray(solutions, dtype=np.int64), group).tolist()))
    _add(stats, candidates=len(solutions), cpsat_s=perf_counter() - t0)
    return solutions, whole_group, simple


def load_kernel() -> None:
    """Load (or compile, the first time) the kernels of stages A and B in this process, before
    workers are forked: small codes through each (6020/0's one H has no automorphism: ``tight_count``).
    Their counts take Burnside's way (``tight_count``), so each is listed too: the listing runs
    ``place``, the search of a count with a multiple joint or a partial group (left out, a cold cache had
    each process that met such a unit compile it in the middle of the count: about 3 CPU s); and the
    programme's order of a unit with multiple joints (``narrow_ranks``)."""
    conv = Conventions()
    for code in (Code.parse("440/0"), Code.parse("6020/0")):
        for graph in _contracted_by_kernel(code, conv):
            for listing in (False, True):
                _kernel_placements(code, graph, conv, None, listing=listing)
            count_orbits(code, graph, conv)
    _narrow_rank([0], [1], [0, 1])  # (the programme's order with multiple joints)
    _freeze_compiled()


@lru_cache(maxsize=1)
def _freeze_compiled() -> None:
    """Once a process: the objects numba's compiling leaves alive for good (about 240 000 on a cold cache) out of the
    garbage collector's full scans, which every later allocation otherwise pays for (a sizing's 8-link calibration
    of h = 2 took 0.27-0.33 CPU s cold against 0.06 warm, and its sizes stopped one short: PROFILE.md section 42)."""
    import gc

    gc.collect()
    gc.freeze()


#: why a unit is counted by the search where Burnside's count was asked for (:func:`count_orbits`): the key
#: ``stats`` gets 1 under (``"by_search_" + key``) and the reason in words (docs/theory.md, "Counting by orbits")
BY_SEARCH = {
    "group": "the permutations of their branch multigraph's bundles of parallel strings are more than 4 096, too "
             "many to list",
    "empty_strings": "h + threshold ≤ 2, where two strings between the same links may both be empty",
    "joint_pairs": "they have a multiple joint and h + threshold ≤ 2, where two joints on the same links pass the "
                   "sub-chain rule on the branch multigraph and only the built chain tells them from one joint",
    "crank": "a crank requirement is checked on each chain",
    "exempt": "the chain's W is below the least mobility its proper sub-chains must keep and it has no free end, "
              "where the pebble game's rule, which would ask it of the whole chain too, is not the exact test",
    "short_loop": "a loop through one link may hold fewer than h − 1 binary links",
}


def _kernel_fault(code: Code, graph: Contracted, conv: Conventions) -> str | None:
    """Why the kernel cannot find this unit's placements (a key of :data:`BY_SEARCH`), or None where it
    can: no crank requirement, a (k, l) pebble game (0 ≤ l = h + threshold), the set of all branch
    vertices not exempt, and loops never short (their least weight at least h − 1).  With simple joints
    its conditions are stage B's; with multiple joints they are weaker by one freedom
    (:mod:`synth.synthesis._stage_b_kernel`), so there the exact test keeps the valid placements among
    the kernel's."""
    if conv.cranks:
        return "crank"
    if conv.h + conv.threshold < 0:
        return "empty_strings"
    if code.dof(conv.h) < conv.threshold and code.n1 == 0:
        return "exempt"
    loop_least, _ = _vertex_terms(graph.vertices, conv)
    if any(loop_least[u] < conv.h - 1 for u, v in graph.edges if u == v):
        return "short_loop"
    return None


def _kernel_applies(code: Code, graph: Contracted, conv: Conventions) -> bool:
    """Whether the kernel can find this unit's placements (:func:`_kernel_fault` finds no fault)."""
    return _kernel_fault(code, graph, conv) is None


def _kernel_placements(code: Code, graph: Contracted, conv: Conventions, stats: dict | None,
                       listing: bool, rows: bool = False, check_sets: bool = True,
                       programme: bool = True) -> tuple[int, "np.ndarray | None", bool]:
    """Stage B by the compiled kernel: how many placements pass its rule and are lex-least under
    Aut(H) (one per orbit where the whole group is listed), those placements (rows) if ``listing``,
    and whether the group was whole.  With ``rows`` (a count that tests each placement: multiple
    joints) the search runs in a count's order of the strings and still returns the placements,
    one per orbit but not the lex-least in H's own order, with their columns in H's order; there
    the search also checks the exact test's sets with a multiple joint as soon as their strings are
    placed, unless ``check_sets`` is off (the tests compare both: the check drops only placements
    the exact test refuses).  The listing's search stays without it, a check of the count's.  Such a
    count (``rows``, ``programme`` on) counts a unit :func:`_programme_fault` passes by the programme
    with the exact rule instead, and gives None for its placements (the count already exact)."""
    import numpy as np

    from ..structure.subchains import sets_to_check
    from ._stage_b_kernel import place

    t0 = perf_counter()
    lows, parallel = _string_limits(graph, conv)
    inner, k, k2, l2 = _pebble_vertices(graph.vertices, conv.h, conv.threshold)
    M, E = len(inner), len(graph.edges)
    n2 = code.count(2)
    if sum(lows) > n2:  # no placement: nothing else is needed
        return 0, np.zeros((0, E), dtype=np.int64), True
    a_list, b_list = _game_ends(graph, inner)
    least = np.array(lows, dtype=np.int64)
    after = np.full(E, -1, dtype=np.int64)
    for e, least_e in parallel:
        after[e] = least_e
    C, l = conv.h - 1, conv.h + conv.threshold
    b0 = n2 - sum(C if a >= 0 else low for a, low in zip(a_list, lows))
    x_most, vertex_need = _game_bounds(k, l, k2, l2, b0, n2, conv.h)
    perms, whole_group = graph.bundle_group()
    a_end, b_end = np.array(a_list, dtype=np.int64), np.array(b_list, dtype=np.int64)
    edges = graph.edges
    by_programme = rows and not listing and programme and whole_group  # (multiple joints: perhaps the programme)
    fault = _programme_fault(code, graph, conv) if by_programme else None
    if not listing:  # a count: any order of the strings keeps one placement per orbit
        order, _, perms = _count_order(graph, inner, a_list, b_list, perms, narrow=by_programme and fault is None)
        a_end, b_end, least, after = a_end[order], b_end[order], least[order], after[order]
        back = np.argsort(order)  # string order[i] is string i of the search: the rows' columns back in H's order
        edges = tuple(edges[e] for e in order)
    group = _coset_rows(edges, np.array(perms, dtype=np.int64)) if len(perms) else np.zeros((0, E), dtype=np.int64)
    if by_programme:
        if fault is None:  # multiple joints, counted without visiting: the programme holds the exact rule
            found = _burnside(code, M, a_end, b_end, least, after, k2, C, conv.h + conv.threshold,
                              b0 + int(k2.sum()) - conv.h - conv.threshold, group, _game_links(graph, inner))
            _add(stats, tight=1, candidates=found, cpsat_s=perf_counter() - t0)
            return found, None, whole_group
        _add(stats, **{"visited_" + fault: 1})
    if rows and not listing and check_sets and conv.threshold > 0:  # (else the first game is the exact rule)
        is_link, ends = _core(graph.vertices, graph.edges)
        sets = sets_to_check(conv.h, is_link, ends, lows, conv.threshold, back)
    else:
        empty = np.zeros(0, dtype=np.int64)
        sets = (np.zeros(E + 1, dtype=np.int64), empty, empty, np.zeros(1, dtype=np.int64), empty)
    if rows and not listing:  # (the kernel writes whole rows, and only rows up to what it found are read)
        out = np.empty((max(_KERNEL_ROWS, _COUNT_ENTRIES // E), E), dtype=np.int64)
    else:
        out = np.zeros((_KERNEL_ROWS if listing else 0, E), dtype=np.int64)
    if not (listing or rows) and (whole_group or not len(group)) and _counted_without_visiting(M, l2, x_most, l, conv.h):
        found = _burnside(code, M, a_end, b_end, least, after, k, C, l, x_most, group)
        _add(stats, tight=1)  # (the sizing times these units per unit, the others per placement visited)
    else:
        found = place(M, a_end, b_end, least, after, n2, k, C, l, k2, l2, x_most, vertex_need, group, out,
                      conv.threshold, sets)
    if (listing or rows) and found > len(out):
        out = np.zeros((found, E), dtype=np.int64)
        place(M, a_end, b_end, least, after, n2, k, C, l, k2, l2, x_most, vertex_need, group, out,
              conv.threshold, sets)
    _add(stats, candidates=found, cpsat_s=perf_counter() - t0)
    return found, out[:found] if listing or not rows else out[:found, back], whole_group


def _burnside(code: Code, M: int, a_end, b_end, least, after, k, C: int, l: int, x_most: int, group,
              links=None) -> int:
    """A unit's chains without visiting its placements: Burnside's lemma, Σ Fix(g) over the permutations of the
    bundles ``group`` (rows, the identity left out) by the programme (:func:`_stage_b_kernel.tight_count`; ``links``
    with multiple joints), over |G/P|; no valid placement where the excess bound ``x_most`` is negative."""
    import numpy as np

    from . import _stage_b_kernel as kernel

    if x_most < 0:
        return 0
    computed = np.zeros((0, 0, 0, 0), dtype=np.int64)  # (the bundles' ways found by the programme itself)
    found = sum(kernel.tight_count(M, a_end, b_end, least, after, k, C, l, x_most, g, computed, kernel.LAYER_BYTES,
                                   links) for g in (np.zeros(0, dtype=np.int64), *group))
    found, rest = divmod(found, len(group) + 1)
    if rest:  # a fault of this engine
        raise RuntimeError(f"Burnside's sum over the {len(group) + 1} permutations of the bundles of a branch "
                           f"multigraph of {code} is not a multiple of their number")
    return found


#: why a count with multiple joints visits a unit's placements (the kernel's search, then the exact test) instead of
#: counting them by the programme with the exact rule (:func:`_programme_fault`): ``stats`` gets 1 under
#: ``"visited_" + key``
VISITED = {
    "threshold": "the least mobility of a proper sub-chain is above 1, or h is below it + 2, or two joints on the "
                 "same links may pass the rule",
    "exempt": "the chain's W is below the least mobility of its proper sub-chains (the whole chain's own rule)",
    "short_loop": "a loop may hold h − 1 binary links or fewer, and so bring links to a set",
    "few_links": "the exact test's core holds fewer than two links",
}


def _programme_fault(code: Code, graph: Contracted, conv: Conventions) -> str | None:
    """Why a unit with a multiple joint cannot be counted by the programme with the exact rule (a key of
    :data:`VISITED`), or None.  The programme (``tight_count`` with ``links``: k = h on a link, h − 1 on a joint,
    l = h + threshold, every set's values kept by the links it holds, 0, 1 or ≥ 2) checks every set T of the
    exact test's core with X_T ≥ 2 against W_T ≥ threshold, and nothing else; it is the exact test
    (:func:`synth.structure.subchain_kernel.verdict`) where

    * threshold ≤ 1, 2 − h < threshold and h ≥ threshold + 2: the test's clause for two links on one joint
      never refuses; the parallel strings between two joints keep their least 2 (:func:`_string_limits`); and a
      vertex with no string inside a set T (its first string placed after T's last) cannot make T refuse
      where T without it does not (T without it holds 1 link at most only with W ≥ 0, docs/theory.md);
    * the chain's W ≥ threshold: a set whose sub-chain is the whole chain then has W_T ≥ W, so the test's
      correction there (the longest short string left out) never decides;
    * every loop's least weight above h − 1: loops are long, bring no link to a set and cost none, and their
      own clause holds from their least weight on (:func:`synth.synthesis.stage_a._loop_lb`);
    * the core holds two links or more: the set of every core vertex is checked, so the deficit is at most
      Σ k − l, as the programme takes it.

    >>> from synth.synthesis.stage_a import contracted_graphs
    >>> code = Code.parse("53/1")  # 8 links, a ternary joint
    >>> [_programme_fault(code, g, Conventions()) for g in contracted_graphs(code, Conventions())]
    [None, None]
    """
    from .stage_a import _loop_lb

    h, threshold = conv.h, conv.threshold
    if threshold > 1 or 2 - h >= threshold or h < threshold + 2:
        return "threshold"
    if code.dof(h) < threshold:
        return "exempt"
    if any(_loop_lb(graph.vertices[u], conv) <= h - 1 for u, v in graph.edges if u == v):
        return "short_loop"
    if sum(_core(graph.vertices, graph.edges)[0]) < 2:
        return "few_links"
    return None


def _game_links(graph: Contracted, inner: dict[int, int]) -> "np.ndarray":
    """Whether each of the games' vertices (``inner``) is a link (1) or a multiple joint (0)."""
    import numpy as np

    links = np.zeros(len(inner), dtype=np.int64)
    for u, i in inner.items():
        links[i] = graph.vertices[u].is_link
    return links


def _count_order(graph: Contracted, inner: dict[int, int], a_list: list[int], b_list: list[int], perms,
                 narrow: bool = False):
    """The count's order of the strings of H (:func:`_search_order` by :func:`_adjacency_rank`, the multiple
    joints first; with ``narrow``, a unit the programme counts, :func:`_narrow_rank` of that), the bundles of
    parallel strings in that order (bundle ``q_order[i]`` of H is bundle i of the search), and the permutations of
    the bundles ``perms`` (rows) relabelled to it."""
    import numpy as np

    joints = frozenset(i for u, i in inner.items() if graph.vertices[u].is_joint)
    rank = _adjacency_rank(a_list, b_list, len(inner), joints)
    order = _search_order(graph.edges, a_list, b_list, _narrow_rank(a_list, b_list, rank) if narrow else rank)
    q_order = (np.cumsum(_bundle_starts(graph.edges)) - 1)[order][_bundle_starts(tuple(graph.edges[e] for e in order))]
    perms = np.array(perms, dtype=np.int64).reshape(len(perms), len(q_order))
    return order, q_order, np.argsort(q_order)[perms[:, q_order]]


def _counted_without_visiting(M: int, l2: int, x_most: int, l: int, h: int) -> bool:
    """Whether a count of one unit can count its placements instead of visiting them, the orbits by
    Burnside's lemma over the permutations of its bundles (:func:`synth.synthesis._stage_b_kernel.tight_count`):
    simple joints (one pebble game, ``l2`` < 0), two game vertices or more, the game exact (l < 2h), and an
    excess bound ``x_most`` ≥ 0 on the long strings (0 in the rule's equality case, where every valid
    placement's deficit multigraph is tight, e.g. every 1-DOF chain; W − threshold above it).

    >>> _counted_without_visiting(6, -1, 0, 4, 3), _counted_without_visiting(6, -1, 1, 4, 3)
    (True, True)
    >>> _counted_without_visiting(6, 4, 0, 4, 3), _counted_without_visiting(6, -1, -1, 4, 3)
    (False, False)
    """
    return l2 < 0 and M >= 2 and x_most >= 0 and l < 2 * h


#: the most game vertices :func:`_narrow_rank` orders by its search over their sets (2^M × M steps: 0.03 ms at 10,
#: 0.2 ms at 12, 1 ms at 14; benchmarks/PROFILE.md section 47); above it the rank given is kept
_NARROW_MOST = 14


def _narrow_rank(a_list: list[int], b_list: list[int], rank: list[int]) -> list[int]:
    """For the programme (``tight_count``, whose states hold 2^(open vertices) values a class): the order of the
    game's vertices that keeps the fewest open (:func:`synth.synthesis._stage_b_kernel.narrow_ranks`) where it
    keeps at least two fewer open than ``rank`` does, else ``rank`` (also above :data:`_NARROW_MOST` vertices).
    Any order of the bundles counts the same placements.

    >>> _narrow_rank([0, 0, 0, 0, 0], [1, 2, 3, 4, 5], [5, 4, 3, 2, 1, 0])  # a star's centre first, not last
    [0, 1, 2, 3, 4, 5]
    """
    import numpy as np

    from ._stage_b_kernel import narrow_ranks

    if len(rank) > _NARROW_MOST:
        return rank
    ends = np.array(a_list, dtype=np.int64), np.array(b_list, dtype=np.int64)
    return narrow_ranks(len(rank), *ends, np.array(rank, dtype=np.int64)).tolist()


def _adjacency_rank(a_list: list[int], b_list: list[int], M: int, first: frozenset = frozenset()) -> list[int]:
    """The game's ``M`` vertices by maximum adjacency (next the vertex with the most strings to those taken, then
    the most strings), those in ``first`` (the multiple joints) before the others, by maximum adjacency among
    themselves: each vertex's rank.  Rigid groups of links then close early, so a placement that cannot be
    completed fails near the root of the search (14 links: 0.47 → 0.29 CPU s of the kernel against the strings'
    own order; issue 41); every set the kernel checks for the exact rule holds a multiple joint, and closes sooner
    (14 links, v ≤ 12, a sample: the kernel's steps 21.9 M → 19.3 M; benchmarks/PROFILE.md, section 32).

    >>> _adjacency_rank([0, 1, 1, 2], [1, 2, 3, 3], 4), _adjacency_rank([0, 1, 1, 2], [1, 2, 3, 3], 4, frozenset({0}))
    ([3, 0, 1, 2], [0, 1, 2, 3])
    """
    neighbours: list[list[int]] = [[] for _ in range(M)]
    for a, b in zip(a_list, b_list):
        if a >= 0:
            neighbours[a].append(b)
            neighbours[b].append(a)
    score = [len(n) for n in neighbours]  # strings to the vertices taken × 1024 + strings; −1 once taken
    rank = [0] * M
    for r in range(M):
        v = max(range(M), key=lambda u: (score[u] >= 0 and u in first, score[u]))  # (the first of the best)
        rank[v], score[v] = r, -1
        for u in neighbours[v]:
            if score[u] >= 0:
                score[u] += 1024
    return rank


def _search_order(edges, a_list: list[int], b_list: list[int], rank: list[int]) -> "np.ndarray":
    """An order of the strings of H for counting its placements, bundles of parallel strings kept
    together and in their order: the strings the pebble game never sees first, then the game's
    vertices by ``rank`` (:func:`_adjacency_rank`, :func:`_narrow_rank`), each vertex bringing the strings
    between it and those before it, the latest first.

    >>> _search_order(((0, 1), (0, 2), (1, 2), (1, 2)), [0, 0, 1, 1], [1, 2, 2, 2], [2, 0, 1]).tolist()
    [2, 3, 1, 0]
    >>> _search_order(((0, 1), (1, 2), (1, 3), (2, 3)), [0, 1, 1, 2], [1, 2, 3, 3], [3, 0, 1, 2]).tolist()
    [1, 3, 2, 0]
    """
    import numpy as np

    firsts = np.flatnonzero(_bundle_starts(edges)).tolist() + [len(edges)]

    def key(q):  # bundles the game never sees first, then by the later end's rank, the earlier's last
        a, b = a_list[firsts[q]], b_list[firsts[q]]
        return (-1, 0) if a < 0 else (max(rank[a], rank[b]), -min(rank[a], rank[b]))

    return np.array([e for q in sorted(range(len(firsts) - 1), key=key) for e in range(firsts[q], firsts[q + 1])],
                    dtype=np.int64)


def _bundle_starts(edges) -> "np.ndarray":
    """Whether each string of H begins a bundle of parallel strings (H lists parallel strings
    next to each other); read-only (stage B asks it of the same strings a few times per unit)."""
    import numpy as np

    starts = np.array([not e or edges[e] != edges[e - 1] for e in range(len(edges))], dtype=np.bool_)
    starts.flags.writeable = False
    return starts


def _coset_rows(edges, perms: "np.ndarray") -> "np.ndarray":
    """The automorphisms of H that make the permutations of its bundles ``perms`` (rows over the
    bundles of parallel strings in the order of ``edges``, as :meth:`Contracted.bundle_group`
    gives them) and take the strings of each bundle in order: as edge permutations (rows).

    Stage B keeps the weights of a bundle non-decreasing, so among the images of a vector under a
    coset of the swaps of parallel strings the one that reads each bundle in order is the least:
    a vector is the lex-least of its images under the whole group of H exactly when it is under
    one such row per coset, the identity's left out (fewer rows and, in the kernel, ones that
    decide on shorter prefixes than the swaps of equal parallel strings).

    >>> import numpy as np
    >>> _coset_rows(((0, 1), (0, 1), (1, 2), (1, 2)), np.array([[1, 0]])).tolist()
    [[2, 3, 0, 1]]
    """
    import numpy as np

    starts = _bundle_starts(edges)
    first = np.flatnonzero(starts)
    bundle = np.cumsum(starts) - 1  # string p of bundle B goes to place p of the bundle B is sent to
    return np.ascontiguousarray(first[perms[:, bundle]] + (np.arange(len(edges)) - first[bundle]))


def _deficit_bounds(k, l: int, b0: int, n2: int, h: int) -> tuple[int, "np.ndarray"]:
    """The kernel's prunes for a game of ``k`` pebbles a vertex and sparsity ``l``, ``b0`` the
    binary links left when every short-able string holds h − 1 and every other its least: the most
    excess the long strings can carry (the set of every vertex is sparse), and the least deficit
    the strings at each vertex carry (the set of every vertex but that one is sparse)."""
    import numpy as np

    M, slack = len(k), b0 + int(k.sum()) - l
    return (slack if M >= 2 else n2), (k - slack if M >= 3 else np.full(M, -n2 * h, dtype=np.int64))


def _game_bounds(k, l: int, k2, l2: int, b0: int, n2: int, h: int) -> tuple[int, "np.ndarray"]:
    """:func:`_deficit_bounds` of the first game, or with multiple joints (a second game, ``l2`` ≥ 0) the
    tighter of the two games' bounds."""
    import numpy as np

    x_most, vertex_need = _deficit_bounds(k, l, b0, n2, h)
    if l2 >= 0:
        x_most2, vertex_need2 = _deficit_bounds(k2, l2, b0, n2, h)
        x_most, vertex_need = min(x_most, x_most2), np.maximum(vertex_need, vertex_need2)
    return x_most, vertex_need


def _game_ends(graph: Contracted, inner: dict[int, int]) -> tuple[list[int], list[int]]:
    """The ends of each string of H among the pebble game's vertices ``inner``; −1 for a string
    that is never short (a loop, a string to a single-joint link)."""
    a_list = [inner.get(u, -1) if u != v and v in inner else -1 for u, v in graph.edges]
    return a_list, [inner[v] if a >= 0 else -1 for a, (_, v) in zip(a_list, graph.edges)]


def orbits_apply(code: Code, graph: Contracted, conv: Conventions) -> bool:
    """Whether :func:`count_orbits` counts this unit's chains by Burnside's lemma: where the
    kernel applies (:func:`_kernel_applies`) and two strings between the same two links never both
    hold no binary link (h + threshold > 2: the rule already refuses it, so the search need not
    order parallel strings).  With multiple joints the pebble games prune and the exact test decides
    each pattern."""
    return _orbits_fault(code, graph, conv) is None


def _orbits_fault(code: Code, graph: Contracted, conv: Conventions) -> str | None:
    """Why :func:`orbits_apply` says no (a key of :data:`BY_SEARCH`), or None.  With a multiple joint,
    h + threshold ≤ 2 is also where two joints on the same links pass the sub-chain rule (W = 2 − h) and
    only the built chain tells them from one joint: the case :func:`count_realised` leaves to the chains."""
    if conv.h + conv.threshold <= 2 and any(vertex.is_joint for vertex in graph.vertices):
        return "joint_pairs"
    if conv.h + conv.threshold <= 2:
        return "empty_strings"
    return _kernel_fault(code, graph, conv)


def count_orbits(code: Code, graph: Contracted, conv: Conventions, stats: dict | None = None) -> int:
    """``count_realised``, counted by orbits: Burnside's lemma over the automorphisms of H.

    The chains of H are the orbits of the valid placements under the group G of H acting on its
    strings.  The permutations of parallel strings among themselves are a normal subgroup P of G,
    so the chains are also the orbits of G/P (permutations of the bundles of parallel strings) on
    the placements up to the order of parallel strings: (1/|G/P|) Σ Fix(g) over G/P
    (:func:`synth.synthesis._stage_b_kernel.fixed_placements`: a search over the patterns
    min(w, h − 1), the long strings' weights by a coin change count).  No placement is listed and
    no lex-least test is made.  With multiple joints the patterns are min(w, h): the exact sub-chain
    test reads a string of its core only through that (a string of exactly h − 1 brings its links to a
    set at no cost, a longer one nothing), so validity is a property of the pattern; the two pebble
    games and the exact test's sets with a multiple joint prune the search, and the exact test decides
    each complete pattern on one of its placements (docs/theory.md, "Counting by orbits").  Where it does not apply (:func:`orbits_apply`) or G/P is too
    large to list (more than 4096 elements, :meth:`Contracted.bundle_group`), the unit is counted
    as :func:`count_realised` counts it (docs/theory.md), and ``stats`` gets 1 under
    ``"by_search_" + key``, the key of :data:`BY_SEARCH` that says why.

    >>> from synth.synthesis.stage_a import contracted_graphs
    >>> code = Code.parse("64200/0")
    >>> [count_orbits(code, g, Conventions()) for g in contracted_graphs(code, Conventions())][:6]
    [15, 104, 13, 6, 15, 681]
    """
    fault = _orbits_fault(code, graph, conv)
    if fault is None:
        perms, whole_group = graph.bundle_group()
        fault = None if whole_group else "group"
    if fault is not None:
        _add(stats, **{"by_search_" + fault: 1})
        return count_realised(code, graph, conv, stats)
    import numpy as np

    from ._stage_b_kernel import fixed_total

    edges = graph.edges
    t0 = perf_counter()
    picked = np.flatnonzero(_bundle_starts(edges))
    width = np.diff(np.append(picked, len(edges)))
    lows, parallel = _string_limits(graph, conv)
    later = np.array(lows, dtype=np.int64)  # the least weight of the second string of a bundle on
    for e, least in parallel:
        later[e - 1] = least
    inner, k, k2, l2 = _pebble_vertices(graph.vertices, conv.h, conv.threshold)
    a_list, b_list = _game_ends(graph, inner)
    perms = np.array(perms, dtype=np.int64).reshape(len(perms), len(picked))
    if l2 >= 0:  # multiple joints: the bundles in the count's order, so that the exact test's sets close early
        _, q_order, perms = _count_order(graph, inner, a_list, b_list, perms)
        picked, width = picked[q_order], width[q_order]
    # the permutations of the bundles the automorphisms make (the identity among them), each once
    bundles = np.vstack([np.arange(len(picked)), perms])
    C, l, n2 = conv.h - 1, conv.h + conv.threshold, code.count(2)
    b0 = n2 - sum(C if a >= 0 else low for a, low in zip(a_list, lows))
    x_most, vertex_need = _game_bounds(k, l, k2, l2, b0, n2, conv.h)
    total = fixed_total(len(inner), np.array(a_list, dtype=np.int64)[picked], np.array(b_list, dtype=np.int64)[picked],
                        np.array(lows, dtype=np.int64)[picked], later[picked], width, n2, k, C, l, x_most, vertex_need,
                        bundles, k2, l2, _exact_arguments(graph, conv, lows, picked, n2) if l2 >= 0 else _no_exact_test())
    orbits, rest = divmod(int(total), len(bundles))
    if rest:  # Burnside's sum is a multiple of |G/P|; anything else is a fault of this engine
        raise RuntimeError(f"Burnside's sum {total} over the {len(bundles)} permutations of bundles of a branch "
                           f"multigraph of {code} is not a multiple of their number")
    _add(stats, cpsat_s=perf_counter() - t0)
    return orbits


def _exact_arguments(graph: Contracted, conv: Conventions, lows: list[int], firsts, n2: int) -> tuple:
    """The exact sub-chain test as :func:`~synth.synthesis._stage_b_kernel.fixed_placements` runs it on a
    pattern with multiple joints: the test's core (:func:`_core`), its sets for weights from ``lows``
    (:func:`synth.structure.subchain_kernel.exact_sets`), Σ of a placement's path lengths (the binary
    links and one per string to a single-joint link), the threshold, and the first string of each bundle."""
    import numpy as np

    from ..structure.subchain_kernel import exact_sets

    is_link, ends = _core(graph.vertices, graph.edges)
    is_link = np.array(is_link, dtype=np.bool_)
    core_a, core_b = np.ascontiguousarray(ends[:, 0]), np.ascontiguousarray(ends[:, 1])
    least = np.array(lows, dtype=np.int64) + (core_a < 0)
    sets = exact_sets(conv.h, is_link, core_a, core_b, least, conv.threshold)
    return is_link, core_a, core_b, sets, n2 + int((core_a < 0).sum()), conv.threshold, np.asarray(firsts, dtype=np.int64)


@lru_cache(maxsize=1)
def _no_exact_test() -> tuple:
    """:func:`_exact_arguments` for simple joints, where the pebble game is the exact rule: no core."""
    import numpy as np

    empty, no = np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.bool_)
    return no, empty, empty, (empty, empty, no, np.zeros(1, dtype=np.int64), empty, empty), 0, 0, empty


def count_reversed(code: Code, graph: Contracted, conv: Conventions, stats: dict | None = None) -> int:
    """``count_realised`` by a second route that shares as little of the first count's arithmetic as
    can be arranged, so that an error in one is unlikely to be repeated by the other (issue 41).

    Where the first count counts a unit's placements by the programme of
    :func:`~synth.synthesis._stage_b_kernel.tight_count` (:func:`_counted_without_visiting`), this one runs that programme

    * over the bundles of parallel strings in the reverse of an order of the first count's kind (maximum
      adjacency; with multiple joints without the joints first, and :func:`_narrow_rank`'s where that is
      narrower): reversed, the cuts between bundles are the same, so the layers are as narrow, but each layer
      sums up the other side of every cut, so no state of one run is a state of the other;
    * with Burnside's lemma over the permutations of the bundles read off nauty's group of H acting
      on its strings (:meth:`Contracted.edge_group`, the subdivided multigraph) and closed under
      composition here (:func:`_bundle_closure`), where the first asks nauty of H with one vertex
      per bundle (:meth:`Contracted.bundle_group`);
    * with each bundle's ways to hold t units of deficit listed from its weights
      (:func:`_bundle_ways`), not by the kernel's own programme.

    Above the rule's equality case (the long strings may carry excess) the bundles' ways are listed
    over the pairs (deficit, excess); with multiple joints (where :func:`_programme_fault` finds nothing) the
    programme holds the exact rule, as the first count runs it, and the ways are listed over (deficit, excess,
    links brought).  A unit the programme does not take is counted by orbits
    (:func:`count_orbits`: the search over patterns and a coin-change count); one that neither
    covers (the group of the bundles above 4096, or two empty parallel strings to exclude) as the
    first count does; ``stats`` counts the units of each kind (``reversed``,
    ``by_orbits``, ``shared``).

    >>> from synth.synthesis.stage_a import contracted_graphs
    >>> code = Code.parse("64200/0")
    >>> [count_reversed(code, g, Conventions()) for g in contracted_graphs(code, Conventions())][:6]
    [15, 104, 13, 6, 15, 681]
    """
    import numpy as np

    from . import _stage_b_kernel as kernel

    lows, parallel = _string_limits(graph, conv)
    inner, k, k2, l2 = _pebble_vertices(graph.vertices, conv.h, conv.threshold)
    M, E, n2 = len(inner), len(graph.edges), code.count(2)
    a_list, b_list = _game_ends(graph, inner)
    C, l = conv.h - 1, conv.h + conv.threshold
    b0 = n2 - sum(C if a >= 0 else low for a, low in zip(a_list, lows))
    x_most, _ = _deficit_bounds(k, l, b0, n2, conv.h)
    simple = all(vertex.is_link for vertex in graph.vertices)
    applies = _kernel_applies(code, graph, conv)
    exact = not simple and applies and _programme_fault(code, graph, conv) is None  # multiple joints: the exact rule
    links, classes = None, 1
    if exact:  # the programme with the exact rule, as the first count runs it
        k, links, classes, x_most = k2, _game_links(graph, inner), 3, b0 + int(k2.sum()) - l
    bundles = _bundle_closure(graph) if (simple or exact) and E else None
    if bundles is None or not (applies and (exact or _counted_without_visiting(M, l2, x_most, l, conv.h))):
        if orbits_apply(code, graph, conv) and graph.bundle_group()[1]:
            _add(stats, by_orbits=1)
            return count_orbits(code, graph, conv, stats)
        _add(stats, shared=1)
        return count_realised(code, graph, conv, stats)
    if sum(lows) > n2 or x_most < 0:
        return 0
    t0 = perf_counter()
    rank = _adjacency_rank(a_list, b_list, M)
    order = _search_order(graph.edges, a_list, b_list, _narrow_rank(a_list, b_list, rank) if exact else rank)
    searched = tuple(graph.edges[e] for e in order)
    # the first count's bundles, each still read in order, taken last first
    order = np.concatenate(np.split(order, np.flatnonzero(_bundle_starts(searched))[1:])[::-1])
    edges = tuple(graph.edges[e] for e in order)
    bundle_of = np.cumsum(_bundle_starts(graph.edges)) - 1  # H's bundle of each string
    held = bundle_of[order[np.flatnonzero(_bundle_starts(edges))]]  # H's bundle at each place of the new order
    place_of = np.argsort(held)
    perms = place_of[bundles[1:][:, held]] if len(bundles) > 1 else np.zeros((0, len(held)), dtype=np.int64)
    rows = _coset_rows(edges, perms) if len(perms) else np.zeros((0, E), dtype=np.int64)
    a_end, b_end = np.array(a_list, dtype=np.int64)[order], np.array(b_list, dtype=np.int64)[order]
    least, after = np.array(lows, dtype=np.int64)[order], np.full(E, -1, dtype=np.int64)
    for e, least_e in parallel:
        after[e] = least_e
    after = after[order]
    given = np.zeros((E, C * E + 1, x_most + 1, classes), dtype=np.int64)
    for f in np.flatnonzero(_bundle_starts(edges)).tolist():
        r = 1
        while f + r < E and after[f + r] >= 0:
            r += 1
        lows = tuple([int(least[f])] + [max(int(least[f + x]), int(after[f + x])) for x in range(1, r)])
        ways = _bundle_ways(C, lows, x_most, bool(a_end[f] >= 0), classes)
        given[f, :len(ways)] = ways
    total = sum(kernel.tight_count(M, a_end, b_end, least, after, k, C, l, x_most, g, given, kernel.LAYER_BYTES,
                                   links) for g in (np.zeros(0, dtype=np.int64), *rows))
    orbits, rest = divmod(total, len(bundles))
    if rest:  # a fault of this engine
        raise RuntimeError(f"Burnside's sum over the {len(bundles)} permutations of the bundles of a branch "
                           f"multigraph of {code}, counted in reverse, is not a multiple of their number")
    _add(stats, reversed=1, tight=1, cpsat_s=perf_counter() - t0)  # (counted, not visited: as the sizing reads it)
    return int(orbits)


def _bundle_closure(graph: Contracted) -> "np.ndarray | None":
    """The permutations of the bundles of parallel strings of H (rows, the identity first) that
    nauty's automorphisms of H on its strings make, closed under composition; None where there are
    more than 4096 (the group is then not listed whole).

    >>> from synth.synthesis.stage_a import LINK, Vertex
    >>> _bundle_closure(Contracted((Vertex(LINK, 3),) * 2, ((0, 0), (0, 1), (1, 1)), "")).tolist()
    [[0, 1, 2], [2, 1, 0]]
    """
    import numpy as np

    from .stage_a import _GROUP_LIMIT

    first = _bundle_starts(graph.edges)
    bundle_of, firsts = np.cumsum(first) - 1, np.flatnonzero(first)
    found = {tuple(range(len(firsts)))}
    steps = {tuple(bundle_of[np.asarray(g)[firsts]].tolist()) for g in graph.edge_group()[0]} - found
    layer = list(found)
    while layer:
        layer = [p for p in {tuple(s[i] for i in q) for q in layer for s in steps} if p not in found]
        found.update(layer)
        if len(found) > _GROUP_LIMIT:
            return None
    return np.array(sorted(found), dtype=np.int64)


@lru_cache(maxsize=1024)
def _bundle_ways(C: int, lows: tuple[int, ...], x_most: int = 0, game: bool = True,
                 classes: int = 1) -> tuple[tuple[tuple[int, ...], ...], ...]:
    """How many ways a bundle of parallel strings holds t = 0 … C·r units of deficit and y = 0 …
    ``x_most`` of excess and brings z of ``classes`` classes of links: its weights w_1 ≤ … ≤ w_r with
    w_x ≥ ``lows[x]``, t = Σ max(C − w_x, 0), y = Σ max(w_x − C, 0), z = min(Σ of the weights ≤ C,
    classes − 1) (a bundle the game never sees, ``game`` false: t = z = 0, y = Σ (w_x − lows[x])) — found by
    listing every such tuple (the second count's check of the kernel's programme); rows t, then y, then z.

    >>> _bundle_ways(2, (0, 1))  # (0, 1) (0, 2) (1, 1) (1, 2) (2, 2)
    (((1,),), ((1,),), ((2,),), ((1,),), ((0,),))
    >>> _bundle_ways(2, (0, 1), 1)  # and (2, 3) (1, 3) (0, 3), one unit of excess each
    (((1,), (1,)), ((1,), (1,)), ((2,), (1,)), ((1,), (0,)), ((0,), (0,)))
    >>> _bundle_ways(2, (0, 1), 0, True, 3)[1]  # t = 1: (1, 2) brings three links (two or more), (0, 3) none
    ((0, 0, 1),)
    >>> _bundle_ways(2, (0, 1), 1, True, 3)[2]  # t = 2: (1, 1) and (0, 2) bring two links, (0, 3) none
    ((0, 0, 2), (1, 0, 0))
    """
    from itertools import combinations_with_replacement

    ways = [[[0] * classes for _ in range(x_most + 1)] for _ in range(C * len(lows) + 1)]
    top = (max(C, lows[-1]) if game else lows[-1]) + x_most
    for weights in combinations_with_replacement(range(top + 1), len(lows)):
        if all(w >= low for w, low in zip(weights, lows)):
            t = sum(max(C - w, 0) for w in weights) if game else 0
            y = sum(max(w - C, 0) for w in weights) if game else sum(w - low for w, low in zip(weights, lows))
            z = min(sum(w for w in weights if w <= C), classes - 1) if game else 0
            if y <= x_most:
                ways[t][y][z] += 1
    return tuple(tuple(map(tuple, row)) for row in ways)


@lru_cache(maxsize=256)
def _pebble_vertices(vertices: tuple, h: int, threshold: int) -> tuple[dict[int, int], "np.ndarray", "np.ndarray", int]:
    """The pebble games' vertices among H's branch vertices (inner links, multiple joints), as
    {vertex of H: vertex of the game}; the pebbles of each in the first game (h) and the second
    (h − 1 on a multiple joint), and the second game's l (−1: no second game, simple joints).
    Shared by every H of a code: the kernel copies the pebbles, never writes these."""
    import numpy as np

    links = set(_inner_links(vertices))
    inner = {u: i for i, u in enumerate(u for u, vertex in enumerate(vertices) if u in links or vertex.is_joint)}
    k = np.full(len(inner), h, dtype=np.int64)
    k2 = np.array([h if vertices[u].is_link else h - 1 for u in inner], dtype=np.int64)
    l2 = -1 if len(inner) == len(links) else h + min(threshold, 0)
    return inner, k, k2, l2


def _few_distributions(lows: list[int], spare: int, parallel: list, graph: Contracted,
                       stats: dict | None) -> tuple[list, bool, bool]:
    """Stage B without a model, where the weight vectors are few: every way to put ``spare``
    binary links on the edges above their least weights, kept where the parallel strings are
    ordered and the vector is the lex-least of its images under Aut(H) (as the model's
    constraints; the sub-chain conditions are left to the exact test)."""
    import numpy as np

    t0 = perf_counter()
    w = _compositions(spare, len(lows)) + np.array(lows)
    keep = np.ones(len(w), dtype=bool)
    for k, least in parallel:
        keep &= (w[:, k] >= w[:, k - 1]) & (w[:, k] >= least)
    w, whole_group = w[keep], True
    if len(w) > 1:  # (the lex-least vector of an orbit has ordered parallel strings: one alone is its orbit's)
        group, whole_group = graph.edge_group()
        w = _lex_least(w, group)
    solutions = list(map(tuple, w.tolist()))  # (tolist gives Python ints in one C call)
    _add(stats, candidates=len(solutions), cpsat_s=perf_counter() - t0)
    return solutions, whole_group, False


def _lex_least(w, group):
    """The rows of ``w`` (weight vectors) that are lexicographically least among their images
    under the edge permutations ``group`` (the image of w under g is w[g]).

    >>> import numpy as np
    >>> _lex_least(np.array([[0, 1], [1, 0], [1, 1]]), [(1, 0)]).tolist()
    [[0, 1], [1, 1]]
    """
    import numpy as np

    if not len(group) or not len(w):
        return w
    images = np.asarray(group, dtype=np.int64)
    base, edges = int(w.max()) + 1, w.shape[1]
    if base ** edges < 1 << 62:
        # each vector as one number of ``edges`` digits in ``base`` (the first edge the highest): lex order
        # is the order of the numbers, and the image under g has the digit of edge g[e] at place e, so
        # all the images' numbers are one integer product w @ places (exact in int64)
        place = base ** np.arange(edges - 1, -1, -1, dtype=np.int64)
        places = np.zeros((edges, len(images)), dtype=np.int64)
        places[images.T, np.arange(len(images))] = place[:, None]
        w = np.asarray(w, dtype=np.int64)
        return w[w @ place <= (w @ places).min(axis=1)]
    step = max(1, _LEX_BLOCK // max(1, len(w) * w.shape[1]))
    for start in range(0, len(images), step):  # where w and an image first differ, w is smaller
        if not len(w):
            break
        differ = w[:, images[start:start + step]] - w[:, None, :]  # vectors × automorphisms × edges
        first = (differ != 0).argmax(axis=2)
        w = w[(np.take_along_axis(differ, first[..., None], axis=2)[..., 0] >= 0).all(axis=1)]
    return w


@lru_cache(maxsize=64)
def _compositions(total: int, parts: int):
    """Every way to write ``total`` as an ordered sum of ``parts`` numbers ≥ 0 (stars and bars),
    one per row, read-only: stage B asks for the same few shapes again and again (int16 and at
    most 64 shapes kept: a shape has up to ``_FEW_VECTORS`` rows).

    >>> _compositions(2, 2).tolist()
    [[0, 2], [1, 1], [2, 0]]
    """
    import numpy as np

    bars = list(combinations(range(total + parts - 1), parts - 1))
    bars = np.array(bars, dtype=np.int64).reshape(len(bars), parts - 1)
    ends = np.full((len(bars), 1), -1), np.full((len(bars), 1), total + parts - 1)
    out = (np.diff(np.hstack([ends[0], bars, ends[1]]), axis=1) - 1).astype(np.int16)
    out.flags.writeable = False
    return out


def _add(stats: dict | None, **values) -> None:
    if stats is not None:
        for key, value in values.items():
            stats[key] = stats.get(key, 0) + value


def _passing(graph: Contracted, conv: Conventions, solutions, stats: dict | None,
             checked: bool = False) -> list:
    """The candidates that pass the exact sub-chain test (all of them if ``checked``: stage B's
    model wrote the exact conditions)."""
    t0 = perf_counter()
    if checked or not solutions:
        kept = list(solutions)
    else:
        kept = [s for s, ok in zip(solutions, _exact_test(graph.vertices, graph.edges, solutions, conv)) if ok]
        if 2 - conv.h >= conv.threshold and any(vertex.is_joint for vertex in graph.vertices):
            # two joints on the same links are one joint; the rule refuses them (W = 2 − h per pair)
            # except for h = 2 with rigid sub-chains allowed
            kept = [s for s in kept for c in [_expand(graph.vertices, graph.edges, s, conv.h)]
                    if len(set(c.joints)) == len(c.joints)]
    _add(stats, subchain_s=perf_counter() - t0)
    return kept


def _subset_constraint(model, vertices, edges, short, TL: set, TJ: set, n_links: int, dof: int, conv) -> None:
    """Add W(S_T) ≥ threshold for the set T = TL ∪ TJ of branch vertices (see realise)."""
    h = conv.h
    T = TL | TJ
    inside = [k for k, (u, v) in enumerate(edges) if u != v and u in T and v in T]
    on_joint = {J: [k for k in inside if J in edges[k] and any(vertices[x].is_link for x in edges[k])] for J in TJ}
    if any(not ks for ks in on_joint.values()):
        return  # a joint no link of T touches directly: a smaller T gives a stronger condition
    if len(TL) == n_links and dof < conv.threshold:
        return  # S may be the whole chain, which is exempt
    if not any(short[k] for k in inside) and not TJ:
        return
    bound = h * (len(TL) - 1) + (h - 1) * len(TJ) - conv.threshold
    most = sum(h - 1 - min(short[k], default=h - 1) for k in inside)
    if most <= bound:
        return  # cannot be violated
    expr = sum((h - 1 - t) * flag for k in inside for t, flag in short[k].items())
    if len(TL) >= 2:
        model.add(expr <= bound)
    else:  # one link: S has two links or more only when a string with binary links is taken
        takes = [flag for k in inside for t, flag in short[k].items() if t >= 1]
        if not takes:
            return  # (no variable is made: a free one would repeat every solution)
        some = model.new_bool_var("")
        model.add_max_equality(some, takes)
        model.add(expr <= bound + conv.threshold - conv.threshold * some)


def _exact_test(vertices, edges, solutions, conv: Conventions, compiled: bool = False):
    """Exact sub-chain test of the chains of H with the weight vectors ``solutions``, all at once:
    a bool per vector (:func:`synth.structure.subchains.least_mobilities` over the sets of H's vertices;
    with ``compiled``, :func:`synth.structure.subchains.passing`, the same verdicts where the kernels
    are loaded and most vectors fail: the kernel's placements with multiple joints).

    A multiple joint J counts as a vertex of its own with h − 1 freedoms, joined to each of its
    links by a simple joint: W(S) is then the same for every S that takes J with its links, and
    larger where J is taken without them, so the least W over the vertex sets is the least
    over the sub-chains (docs/theory.md).  Every string is then a path of w binary links between
    two vertices, as with simple joints.  Single-joint links never lower W (a string to one adds
    w + 1 links and w + 1 joints): they are left out, their strings are paths with a free end.
    """
    import numpy as np

    from ..structure.subchains import least_mobilities, passing

    is_link, ends = _core(vertices, edges)
    sol = np.asarray(solutions, dtype=np.int64).reshape(len(solutions), len(edges))
    lengths = sol + (ends[:, 0] < 0)  # a string to a single-joint link holds that link too
    if compiled:
        return passing(conv.h, is_link, ends, lengths, conv.threshold)
    return least_mobilities(conv.h, is_link, [], ends, lengths) >= conv.threshold


@lru_cache(maxsize=256)
def _core(vertices, edges) -> tuple[tuple[bool, ...], "np.ndarray"]:
    """The exact test's core of H (:func:`_exact_test`): whether each core vertex is a link (else a
    multiple joint), and each string's ends among them, (−1, −1) for a string to a single-joint
    link; read-only (the same for every vector of a unit)."""
    import numpy as np

    inner = set(_inner_links(vertices))
    kept = [u for u, vertex in enumerate(vertices) if u in inner or vertex.is_joint]
    index = {u: i for i, u in enumerate(kept)}
    ends = np.array([(index[u], index[v]) if u in index and v in index else (-1, -1) for u, v in edges],
                    dtype=np.int64).reshape(-1, 2)
    ends.flags.writeable = False
    return tuple(vertices[u].is_link for u in kept), ends


@lru_cache(maxsize=256)
def _string_ends(vertices, edges) -> tuple[int, tuple]:
    """The number of branch links of H, and for each string the chain link at each end (its
    number) or None where the end is a multiple joint; the same for every vector of a unit."""
    link_id = {u: i for i, u in enumerate(u for u, vertex in enumerate(vertices) if vertex.is_link)}
    return len(link_id), tuple((link_id.get(u), link_id.get(v)) for u, v in edges)


def _expand(vertices, edges, weights, space: int = 3) -> Chain:
    """The chain of H with ``weights`` binary links on its strings (branch links numbered first).

    >>> from synth.synthesis.stage_a import LINK, Vertex
    >>> _expand((Vertex(LINK, 3), Vertex(LINK, 3)), ((0, 1), (0, 1), (0, 1)), (0, 2, 2)).joints
    ((0, 1), (0, 2), (0, 4), (1, 3), (1, 5), (2, 3), (4, 5))
    """
    nxt, ends = _string_ends(vertices, edges)
    multiple: dict[int, list[int]] = {u: [] for u, vertex in enumerate(vertices) if vertex.is_joint}
    joints: list[tuple[int, ...]] = []
    for (u, v), (a, b), wk in zip(edges, ends, weights):
        if wk:  # a string of binary links nxt … nxt + wk − 1
            first, last = nxt, nxt + wk - 1
            joints.extend(zip(range(first, last), range(first + 1, last + 1)))
            if a is None:
                multiple[u].append(first)
            else:
                joints.append((a, first))
            if b is None:
                multiple[v].append(last)
            else:
                joints.append((last, b))
            nxt += wk
        elif a is None:  # a link of H on a multiple joint of H
            multiple[u].append(b)
        elif b is None:
            multiple[v].append(a)
        else:
            joints.append((a, b))
    joints.extend(tuple(links) for links in multiple.values())
    return Chain.trusted(nxt, joints, space)
