"""The count's search of stage B (issue 41): the compiled kernel run over the strings of H in
maximum-adjacency order, with the prefix prune and one automorphism per coset of the parallel-string
swaps, against the listing's search (the strings' own order, every lex-least placement written out),
against counting by orbits (Burnside's lemma, no lex-least test), and against the brute-force oracle.

The kernel is forced on every code here (small queries do not load it otherwise); the 14-link
comparison is ``slow`` (the 16-link one is benchmarks/logs/count_search_16.txt).
"""

from __future__ import annotations

import numpy as np
import pytest

import synth
from synth.synthesis import stage_a, stage_b
from tests.oracles.chains import brute_force_chains_once, count_by_code, engine_counts_by_key

from .kernel_units import kernel_units

# simple joints (the count's kernel), every motion space and convention the kernel takes
QUERIES = [dict(dof=1, links=10), dict(dof=1, links=12), dict(dof=0, links=9), dict(dof=2, links=11),
           dict(dof=2, links=11, fractionated=False), dict(dof=3, links=12), dict(dof=3, links=10, n1=(0, 3)),
           dict(dof=1, links=7, h=2), dict(dof=1, links=11, h=4), dict(dof=1, links=14, h=5),
           dict(dof=1, links=12, h=6), dict(dof=2, links=9, rigid_subchains=True), dict(dof=1, links=12, planar_only=True)]


def _ids(query):
    return ",".join(f"{k}={v}" for k, v in query.items())


@pytest.fixture
def kernel_everywhere(monkeypatch):
    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})


def _compare_units(query) -> int:
    """Per unit: the count's search, the listing's rows and (where it applies) the orbits agree."""
    compared = 0
    for u, args in kernel_units(query):
        counted, _, whole = stage_b._kernel_placements(*args, None, listing=False)
        listed, rows, _ = stage_b._kernel_placements(*args, None, listing=True)
        assert counted == listed == len(rows), u.key
        if whole and stage_b.orbits_apply(*args):
            assert counted == stage_b.count_orbits(*args), u.key
        compared += 1
    return compared


@pytest.mark.parametrize("query", QUERIES, ids=_ids)
def test_the_count_search_finds_as_many_placements_as_the_listing(query, kernel_everywhere):
    """Unit by unit: as many placements in the search order as the listing writes out in the
    strings' own order (one per orbit either way), and as many orbits as Burnside's lemma counts."""
    assert _compare_units(query)


@pytest.mark.parametrize("query", QUERIES, ids=_ids)
def test_the_count_search_prunes_no_valid_placement(query, kernel_everywhere):
    """Unit by unit, as many placements as the direct listing of every weight vector (no kernel, no
    pebble game) keeps after the exact test on every subset: the kernel's bounds on the deficit the
    strings still to come can take (their rank in the game, their bundles' pairs) cut nothing valid."""
    compared = 0
    for u, (code, graph, conv) in kernel_units(query):
        lows, parallel = stage_b._string_limits(graph, conv)
        spare = code.count(2) - sum(lows)
        counted, _, whole = stage_b._kernel_placements(code, graph, conv, None, listing=False)
        if not whole or spare < 0 or len(graph.edges) > 12:
            continue
        listed = stage_b._few_distributions(lows, spare, parallel, graph, None)[0]
        assert counted == len(stage_b._passing(graph, conv, listed, None)), u.key
        compared += 1
    assert compared


@pytest.mark.slow
def test_the_count_search_at_14_links(kernel_everywhere):
    """The same on every one of the 1 040 units of the 14-link 1-DOF chains."""
    assert _compare_units(dict(dof=1, links=14)) == 1040


def test_the_search_order_keeps_bundles_whole_and_relabels_the_automorphisms():
    """On every unit of 12 links: a permutation of the strings with parallel strings adjacent and
    in their order, and the automorphisms relabelled as the count does (``back[g[order]]``) move a
    placement read in the search order as the automorphisms move it in the strings' own order."""
    rng = np.random.default_rng(41)
    checked = 0
    for u in synth.plan_units(dof=1, links=12, workers=1):
        graph = u.contracted
        inner, *_ = stage_b._pebble_vertices(graph.vertices, u.conventions.h, u.conventions.threshold)
        a_list, b_list = stage_b._game_ends(graph, inner)
        order = stage_b._search_order(graph.edges, a_list, b_list, stage_b._adjacency_rank(a_list, b_list, len(inner)))
        assert sorted(order.tolist()) == list(range(len(graph.edges)))
        edges = [graph.edges[e] for e in order]
        runs = [e for i, e in enumerate(edges) if not i or e != edges[i - 1]]
        assert len(runs) == len(set(runs)), u.key  # each bundle in one piece
        assert all(order[i] < order[i + 1] for i in range(len(edges) - 1) if edges[i] == edges[i + 1])
        group, _ = graph.edge_group()
        if not group:
            continue
        group = np.asarray(group, dtype=np.int64)
        relabelled = np.argsort(order)[group[:, order]]
        w = rng.integers(0, 5, size=(8, len(edges)))
        for g, g2 in zip(group, relabelled):
            assert (w[:, order][:, g2] == w[:, g][:, order]).all(), u.key
        checked += 1
    assert checked


def test_one_automorphism_per_coset_decides_as_the_whole_group():
    """For every placement with ordered bundles of every unit of 10 links, lex-least under the
    whole group of H exactly when lex-least under the rows ``_coset_rows`` makes of the
    permutations of the bundles (nauty on H with each bundle one vertex)."""
    checked = 0
    for u in synth.plan_units(dof=1, links=10, workers=1):
        graph = u.contracted
        group, whole = graph.edge_group()
        if not group:
            continue
        assert whole
        lows, parallel = stage_b._string_limits(graph, u.conventions)
        vectors = np.asarray(stage_b._compositions(u.code.count(2) - sum(lows), len(lows)), dtype=np.int64) + lows
        for k, _ in parallel:
            vectors = vectors[vectors[:, k] >= vectors[:, k - 1]]
        full = {tuple(w) for w in stage_b._lex_least(vectors, group).tolist()}
        perms, whole = graph.bundle_group()
        assert whole
        rows = stage_b._coset_rows(graph.edges, np.asarray(perms, dtype=np.int64).reshape(len(perms), -1)) \
            if perms else np.zeros((0, len(graph.edges)), dtype=np.int64)
        assert len(rows) <= len(group)
        assert {tuple(w) for w in stage_b._lex_least(vectors, rows).tolist()} == full, u.key
        checked += len(vectors)
    assert checked


@pytest.mark.parametrize("dof, links, v", [(1, 12, 0), (2, 11, 0), (1, 10, 2)])
def test_the_bundle_group_is_the_edge_group_read_on_bundles(dof, links, v):
    """On every unit (12 links W = 1, 11 links W = 2, 10 links W = 1 with two multiple joints):
    the permutations of the bundles of parallel strings that the automorphisms of H make, from
    nauty on H itself (every automorphism), are those ``bundle_group`` lists from H with each
    bundle one vertex — each once, the identity left out."""
    checked = 0
    for u in synth.plan_units(dof=dof, links=links, v=v, workers=1):
        graph = u.contracted
        group, whole = graph.edge_group()
        perms, whole_bundles = graph.bundle_group()
        assert whole and whole_bundles
        starts = stage_b._bundle_starts(graph.edges)
        first, bundle = np.flatnonzero(starts), np.cumsum(starts) - 1
        read = {tuple(bundle[np.asarray(g)[first]].tolist()) for g in group} - {tuple(range(len(first)))}
        assert sorted(read) == perms, u.key
        checked += bool(perms)
    assert checked


@pytest.mark.parametrize("dof, links, rigid", [(1, 6, False), (1, 8, False), (2, 7, False), (3, 8, False),
                                               (1, 8, True), (0, 7, True)])
def test_counts_with_the_count_search_equal_the_brute_force(dof, links, rigid, kernel_everywhere):
    """Counts by code, the kernel's count search on every code, against the oracle (which shares no
    code with the engine)."""
    got = synth.count_chains(dof, links, rigid_subchains=rigid, workers=1)
    expected = count_by_code(brute_force_chains_once(links, dof, rigid_subchains=rigid))

    assert engine_counts_by_key(got.by_code) == expected


@pytest.mark.parametrize("most", [1, 6, 2 ** 40], ids=["binary", "small", "beyond int64 digits"])
def test_the_lex_least_vectors_are_those_no_image_undercuts(most):
    """Against Python's own tuple order: a vector is kept when no image w[g] under the permutations is
    smaller; ``2 ** 40`` leaves the one-product path (E digits would not fit in int64) for the blocks."""
    import random

    rng = random.Random(7)
    for _ in range(200):
        edges = rng.randint(1, 7)
        w = np.array([[rng.randint(0, most) for _ in range(edges)] for _ in range(rng.randint(1, 30))], dtype=np.int64)
        group = [tuple(rng.sample(range(edges), edges)) for _ in range(rng.randint(1, 6))]
        kept = [tuple(v) for v in w.tolist() if all(tuple(v) <= tuple(v[e] for e in g) for g in group)]
        assert [tuple(v) for v in stage_b._lex_least(w, group).tolist()] == kept


def _with_and_without_the_check(query):
    """Each unit of ``query`` with a multiple joint: its args and the count's search (not the programme that
    counts most such units without it, tests/synthesis/test_count_exact_programme.py) with and without the check
    of the exact test's sets (placements, rows, whole group)."""
    for u, args in kernel_units(query):
        if all(vertex.is_link for vertex in args[1].vertices):
            continue
        yield (u, args, stage_b._kernel_placements(*args, None, listing=False, rows=True, programme=False),
               stage_b._kernel_placements(*args, None, listing=False, rows=True, check_sets=False, programme=False))


# multiple joints: the kernel's weaker rule, every placement then through the exact test
MULTIPLE_QUERIES = [dict(dof=1, links=10, v=(1, 8)), dict(dof=0, links=9, v=(1, 4)), dict(dof=1, links=7, h=2, v=(1, 3)),
                    dict(dof=1, links=11, h=4, v=(1, 4)), dict(dof=2, links=9, v=(1, 7)),
                    dict(dof=3, links=8, v=(1, 4), n1=(0, 2))]


@pytest.mark.parametrize("query, first_pass", [(q, "whole") for q in MULTIPLE_QUERIES]
                         + [(q, "one row") for q in MULTIPLE_QUERIES[1:3]], ids=lambda x: _ids(x) if isinstance(x, dict) else x)
def test_the_count_rows_with_multiple_joints_are_the_listings_orbits(query, first_pass, kernel_everywhere, monkeypatch):
    """Unit by unit with multiple joints: the count reads the placements of the search order
    (``rows``), with their columns back in H's order; as many as the listing writes out without the
    check of the exact test's sets (fewer with it), the same chains (by certificate) among those the
    exact test keeps, and the same count as the listing's, whether the first pass holds every row or
    one (then a second pass reads them)."""
    if first_pass == "one row":
        monkeypatch.setattr(stage_b, "_KERNEL_ROWS", 1)
        monkeypatch.setattr(stage_b, "_COUNT_ENTRIES", 1)
    compared = {True: 0, False: 0}
    for u, args, (found, rows, whole), (unchecked, _, _) in _with_and_without_the_check(query):
        graph, conv = args[1], args[2]
        listed, listing, _ = stage_b._kernel_placements(*args, None, listing=True)
        assert unchecked == listed == len(listing) and found == len(rows) <= listed, u.key
        if whole and found:
            certificates = []
            for placements in (rows, listing):
                valid = stage_b._exact_test(graph.vertices, graph.edges, placements, conv, compiled=True)
                certificates.append(sorted(stage_b._expand(graph.vertices, graph.edges, s, conv.h).certificate
                                           for s in placements[valid].tolist()))
            assert certificates[0] == certificates[1], u.key
        assert stage_b.count_realised(*args) == stage_b.count_listed(*args), u.key
        compared[found > 1] += 1
    assert compared[True]  # units with several placements, where the order of the strings matters


# every code with multiple joints of 10 and 11 links the kernel takes, W = 0 … 3
CHECKED_QUERIES = [dict(dof=1, links=10, v=(1, 8)), dict(dof=0, links=11, v=(1, 9)), dict(dof=2, links=11, v=(1, 9)),
                   dict(dof=3, links=10, v=(1, 8))]


@pytest.mark.parametrize("query", CHECKED_QUERIES, ids=_ids)
def test_the_check_of_the_exact_tests_sets_drops_no_chain(query, kernel_everywhere):
    """Unit by unit with multiple joints, the count's search with and without its check of the exact
    test's sets as strings are placed: with it, the placements are some of those without it, and
    every one it leaves out is refused by the exact test, so the placements that pass are the same;
    and it leaves some out (it is not idle) where the chains' sub-chains must move (W ≥ 1; with W = 0
    the first pebble game is the exact rule on these sets already, and the search skips the check)."""
    dropped = 0
    for u, args, (found, rows, whole), (unchecked, every, _) in _with_and_without_the_check(query):
        graph, conv = args[1], args[2]
        kept, all_rows = set(map(tuple, rows.tolist())), set(map(tuple, every.tolist()))
        assert len(kept) == found and kept <= all_rows, u.key
        if unchecked:
            valid = stage_b._exact_test(graph.vertices, graph.edges, every, conv)  # (the scan of every set)
            assert {r for r, ok in zip(map(tuple, every.tolist()), valid) if ok} <= kept, u.key
        dropped += unchecked - found
    assert dropped > 0 if query["dof"] else dropped == 0


@pytest.mark.parametrize("query", MULTIPLE_QUERIES + CHECKED_QUERIES[2:]  # (W = 0 at 11 links: 20 CPU s)
                         + [pytest.param(CHECKED_QUERIES[1], marks=pytest.mark.slow)], ids=_ids)
def test_the_searches_with_multiple_joints_keep_every_valid_placement(query, kernel_everywhere):
    """Unit by unit with multiple joints: the chains the count finds (its search with the multiple joints
    first, the deficit still to come bounded by its rank in either game, the exact test's sets checked)
    and the valid placements among the listing's rows are as many as the direct listing of every weight
    vector (no kernel, no pebble game) keeps after the exact test on every subset."""
    compared = 0
    for u, (code, graph, conv) in kernel_units(query):
        lows, parallel = stage_b._string_limits(graph, conv)
        spare = code.count(2) - sum(lows)
        if all(vertex.is_link for vertex in graph.vertices) or spare < 0 or len(graph.edges) > 12:
            continue
        _, rows, whole = stage_b._kernel_placements(code, graph, conv, None, listing=True)
        if not whole:
            continue
        valid = len(stage_b._passing(graph, conv, stage_b._few_distributions(lows, spare, parallel, graph, None)[0], None))
        assert stage_b.count_realised(code, graph, conv) == valid, u.key
        assert len(stage_b._passing(graph, conv, list(map(tuple, rows.tolist())), None)) == valid, u.key
        compared += valid > 0
    assert compared


def test_the_count_order_takes_the_multiple_joints_first():
    """On every unit with multiple joints of 10 links (v ≤ 8): among the strings the game sees, those
    between two multiple joints come first in the count's order, and their bundles whole and in order;
    without the joints named, the order is the links' maximum adjacency alone (some unit differs)."""
    differ = 0
    for u in synth.plan_units(dof=1, links=10, v=(1, 8), workers=1):
        graph = u.contracted
        if graph is None or all(vertex.is_link for vertex in graph.vertices):
            continue
        inner, *_ = stage_b._pebble_vertices(graph.vertices, u.conventions.h, u.conventions.threshold)
        a_list, b_list = stage_b._game_ends(graph, inner)
        joints = frozenset(i for v, i in inner.items() if graph.vertices[v].is_joint)
        order = stage_b._search_order(graph.edges, a_list, b_list,
                                      stage_b._adjacency_rank(a_list, b_list, len(inner), joints)).tolist()
        assert sorted(order) == list(range(len(graph.edges)))
        seen = [e for e in order if a_list[e] >= 0]
        between = [a_list[e] in joints and b_list[e] in joints for e in seen]
        assert between == sorted(between, reverse=True), u.key
        differ += order != stage_b._search_order(graph.edges, a_list, b_list,
                                                 stage_b._adjacency_rank(a_list, b_list, len(inner))).tolist()
    assert differ


@pytest.mark.parametrize("dof, links, v", [(1, 8, 6), (1, 6, 4), (2, 7, 5), (0, 7, 3)])
def test_counts_with_multiple_joints_by_the_compiled_test_equal_the_brute_force(dof, links, v, kernel_everywhere):
    """Counts by code with multiple joints, the kernel's placements and the compiled exact test on every
    code, against the oracle (which shares no code with the engine)."""
    got = engine_counts_by_key(synth.count_chains(dof, links, v=(0, v), workers=1).by_code)
    expected = count_by_code(brute_force_chains_once(links, dof, v_max=v, rigid_subchains=dof == 0))

    assert got == expected
    assert any(composition for _, composition in got)  # chains with multiple joints among them


def _counts_both_ways(query, monkeypatch):
    """Per unit of ``query``: the kernel's count with every automorphism left out (every valid
    placement with ordered bundles) by ``tight_count`` where it applies and by the search, and how
    many units ``tight_count`` counted."""
    from synth.synthesis import _stage_b_kernel

    monkeypatch.setattr(stage_b, "_coset_rows", lambda edges, perms: np.zeros((0, len(edges)), dtype=np.int64))
    calls = []
    tight = _stage_b_kernel.tight_count
    monkeypatch.setattr(_stage_b_kernel, "tight_count", lambda *args: calls.append(1) or tight(*args))
    pairs = []
    for u, args in kernel_units(query):
        with monkeypatch.context() as m:
            m.setattr(stage_b, "_counted_without_visiting", lambda *_: False)
            searched = stage_b._kernel_placements(*args, None, listing=False)[0]
        pairs.append((u.key, stage_b._kernel_placements(*args, None, listing=False)[0], searched))
    return pairs, len(calls)


@pytest.mark.parametrize("query", QUERIES, ids=_ids)
def test_the_tight_count_counts_what_the_search_visits(query, kernel_everywhere, monkeypatch):
    """Unit by unit, every automorphism left out (so every unit is counted by ``tight_count`` where
    it applies, not only those of a trivial group): as many placements as the kernel's search
    visits, on every query (W = threshold, where the deficits are tight, and above it, where the
    long strings carry up to W − threshold binary links more)."""
    pairs, tight = _counts_both_ways(query, monkeypatch)
    assert pairs
    assert [(key, counted) for key, counted, _ in pairs] == [(key, searched) for key, _, searched in pairs]
    assert tight and any(counted > 1 for key, counted, _ in pairs)


@pytest.mark.parametrize("query", [q for q in QUERIES if q["dof"] >= 2], ids=_ids)
def test_units_with_excess_are_counted_without_visiting(query, kernel_everywhere, monkeypatch):
    """Where W is above the threshold (the long strings may carry excess), the count counts the units
    by the programme, automorphisms included (Burnside's lemma), and each unit's count is the
    number of placements the listing writes out; some units carry excess bound 2 or more."""
    bounds = []
    real = stage_b._counted_without_visiting
    monkeypatch.setattr(stage_b, "_counted_without_visiting",
                        lambda M, l2, x_most, l, h: bounds.append(x_most) or real(M, l2, x_most, l, h))
    counted_units, bounds_seen = 0, set()
    for u, args in kernel_units(query):
        stats, bounds[:] = {}, []
        counted = stage_b._kernel_placements(*args, stats, listing=False)[0]
        listed, rows, _ = stage_b._kernel_placements(*args, None, listing=True)
        assert counted == listed == len(rows), u.key
        if stats.get("tight") and bounds and bounds[0] > 0:
            counted_units += 1
            bounds_seen.add(bounds[0])
    assert counted_units >= 10 and max(bounds_seen) >= (2 if query["dof"] >= 3 else 1)


@pytest.mark.slow
def test_the_tight_count_at_14_links(kernel_everywhere, monkeypatch):
    """The same on every one of the 1 040 units of the 14-link 1-DOF chains."""
    pairs, tight = _counts_both_ways(dict(dof=1, links=14), monkeypatch)
    assert tight == len(pairs) == 1040
    assert [counted for _, counted, _ in pairs] == [searched for _, _, searched in pairs]
