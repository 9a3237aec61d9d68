"""Counting chains with multiple joints without visiting their placements (issue 41 item 2): the programme of
``tight_count`` with each set's values kept by the links it holds (0, 1, ≥ 2), the exact sub-chain rule checked on
the sets of two links or more (``stage_b._programme_fault`` says where it applies), against the kernel's search and
the exact test (``count_realised(programme=False)``), unit by unit; Fix(identity) against every weight vector the
exact test passes; the second count (``count_reversed``, the same programme in reverse with the bundles' ways listed).

Faults put into the compiled programme by hand (numba: not patchable from a test), each run on this file and the
second count's tests with multiple joints (``pytest tests/synthesis/test_count_exact_programme.py
tests/synthesis/test_count_reversed.py -k "exact_programme or multiple_joints or bundles_ways"``: 25 tests):

* the ≥ 2-links clause dropped (every set holding both ends checked: ``most[max(Q − 1 − z, 0)]`` and
  ``most[Q − 1]`` → ``most[0]``): 9 of the 25 fail;
* a bundle's links not brought to the sets (``max(c − z, 0)`` → ``c`` in the row built for a bundle): 16 fail;
* an opened link not counted in its sets' links (``max(c − open_link[x], 0)`` → ``c``): 17 fail.
"""

from __future__ import annotations

import pytest

import synth
from synth.synthesis import stage_a, stage_b

# multiple joints: W = 0 … 3, h = 3 and 4, non-degenerate and rigid sub-chains allowed
QUERIES = [dict(dof=1, links=10, v=(0, 8)), dict(dof=0, links=9, v=(0, 7)), dict(dof=2, links=11, v=(0, 9)),
           dict(dof=3, links=10, v=(0, 8)), dict(dof=1, links=11, h=4, v=(0, 9)),
           dict(dof=1, links=10, rigid_subchains=True, v=(0, 8))]


def _ids(query):
    return ",".join(f"{k}={v}" for k, v in query.items())


@pytest.fixture
def kernel_everywhere(monkeypatch):
    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})


def _joint_units(query):
    for u in synth.plan_units(**query, workers=1):
        graph = u.contracted
        if graph is not None and any(vertex.is_joint for vertex in graph.vertices):
            yield u, (u.code, graph, u.conventions)


@pytest.mark.parametrize("query", QUERIES, ids=_ids)
def test_the_programme_counts_what_the_search_and_the_exact_test_keep(query, kernel_everywhere):
    """Unit by unit with a multiple joint: the count by the programme (Burnside over the bundles' permutations)
    equals the kernel's search with the exact test; the programme counts some of the units, some with
    automorphisms, and says why it left the others."""
    stats: dict = {}
    counted = with_group = chains = 0
    for u, args in _joint_units(query):
        before = stats.get("tight", 0)
        found = stage_b.count_realised(*args, stats)
        assert found == stage_b.count_realised(*args, {}, programme=False), u.key
        if stats.get("tight", 0) > before:
            counted += 1
            with_group += len(args[1].bundle_group()[0]) > 0
            chains += found
    assert counted and with_group and chains
    assert set(key for key in stats if key.startswith("visited_")) <= {"visited_" + key for key in stage_b.VISITED}


@pytest.mark.parametrize("query", QUERIES[:4], ids=_ids)
def test_the_identitys_count_is_every_placement_the_exact_test_passes(query, kernel_everywhere):
    """Fix(identity): the programme with no permutation counts every weight vector with ordered bundles that the
    exact test passes (listed directly: no kernel, no pebble game), on every unit of at most 12 strings it takes."""
    import numpy as np

    from synth.synthesis import _stage_b_kernel

    compared = 0
    for u, (code, graph, conv) in _joint_units(query):
        lows, parallel = stage_b._string_limits(graph, conv)
        spare = code.count(2) - sum(lows)
        if spare < 0 or len(graph.edges) > 12 or stage_b._programme_fault(code, graph, conv) is not None:
            continue
        w = stage_b._compositions(spare, len(lows)) + np.array(lows)
        for k, least in parallel:
            w = w[(w[:, k] >= w[:, k - 1]) & (w[:, k] >= least)]
        valid = int(stage_b._exact_test(graph.vertices, graph.edges, w, conv).sum()) if len(w) else 0
        inner, _, k2, _ = stage_b._pebble_vertices(graph.vertices, conv.h, conv.threshold)
        a_list, b_list = stage_b._game_ends(graph, inner)
        after = np.full(len(lows), -1, dtype=np.int64)
        for e, least in parallel:
            after[e] = least
        C, l = conv.h - 1, conv.h + conv.threshold
        x_most = code.count(2) - sum(C if a >= 0 else low for a, low in zip(a_list, lows)) + int(k2.sum()) - l
        got = 0 if x_most < 0 else _stage_b_kernel.tight_count(
            len(inner), np.array(a_list), np.array(b_list), np.array(lows), after, k2, C, l, x_most,
            np.zeros(0, dtype=np.int64), np.zeros((0, 0, 0, 0), dtype=np.int64), None,
            stage_b._game_links(graph, inner))
        assert got == valid, u.key
        compared += 1
    assert compared > 10


@pytest.mark.parametrize("query", QUERIES, ids=_ids)
def test_the_second_count_takes_the_same_units(query, kernel_everywhere):
    """``count_reversed`` (the programme over the bundles in reverse, the bundles' ways listed, the group from
    nauty's group on the strings) equals the first count unit by unit, and runs the programme on units with
    multiple joints."""
    stats: dict = {}
    for u, args in _joint_units(query):
        assert stage_b.count_reversed(*args, stats) == stage_b.count_realised(*args), u.key
    assert stats.get("reversed", 0) > stats.get("shared", 0)


def test_the_units_left_to_the_search_are_the_ones_the_proof_does_not_cover(kernel_everywhere):
    """Rigid sub-chains allowed (threshold 0): a loop of h − 1 binary links through a link is short and brings
    links to a set, so such units are visited (``visited_short_loop``); the count stays the search's."""
    stats: dict = {}
    for u, args in _joint_units(dict(dof=0, links=9, v=(0, 7))):
        stage_b.count_realised(*args, stats)
    assert stats.get("visited_short_loop", 0) > 0 and stats.get("tight", 0) > 0


def _widths(M, a_list, b_list, order):
    """The most vertices open while a vertex's strings are placed, taking the vertices in ``order``, and Σ 2^that."""
    most = total = 0
    for r, v in enumerate(order):
        taken = set(order[:r])
        n_open = sum(1 for u in taken if any({a, b} & {u} and {a, b} - taken for a, b in zip(a_list, b_list)))
        most, total = max(most, n_open + 1), total + 2 ** (n_open + 1)
    return most, total


def test_the_programmes_order_keeps_the_fewest_vertices_open():
    """``narrow_ranks`` against every order of the vertices (random multigraphs of 2 … 6 vertices, some strings
    the game never sees): where the order given keeps at least two more open than the least, its order reaches
    the least (most open, Σ 2^open) of all orders; else it gives back the order given."""
    import itertools
    import random

    import numpy as np

    from synth.synthesis._stage_b_kernel import narrow_ranks

    rng = random.Random(7)
    narrowed = kept = 0
    for _ in range(200):
        M = rng.randint(2, 6)
        ends = [(rng.randrange(M), rng.randrange(M)) for _ in range(rng.randint(M - 1, 2 * M))]
        ends = [(a, b) if a != b and rng.random() < 0.9 else (-1, -1) for a, b in ends]
        seen = [(a, b) for a, b in ends if a >= 0]
        if not seen:
            continue
        given = list(range(M))
        rng.shuffle(given)
        rank = narrow_ranks(M, np.array([a for a, _ in ends]), np.array([b for _, b in ends]),
                            np.array(given)).tolist()
        assert sorted(rank) == list(range(M))
        best = min(_widths(M, *zip(*seen), list(p)) for p in itertools.permutations(range(M)))
        if _widths(M, *zip(*seen), sorted(range(M), key=given.__getitem__))[0] >= best[0] + 2:
            assert _widths(M, *zip(*seen), sorted(range(M), key=rank.__getitem__)) == best, (M, ends)
            narrowed += 1
        else:
            assert rank == given
            kept += 1
    assert narrowed > 10 and kept > 10


@pytest.mark.parametrize("method", ["first", "second"])
def test_the_programme_counts_the_same_in_any_order(method, kernel_everywhere, monkeypatch):
    """Unit by unit with a multiple joint (W = 1, 11 links, h = 4 and 10 links, h = 3): the programme over the
    vertices in a random order, or in the narrowest where that keeps two fewer open (``_narrow_rank``), counts
    what it counts over maximum adjacency alone (``_NARROW_MOST`` = −1), first count and second; the narrowest
    order is taken on some units."""
    import random

    count = stage_b.count_realised if method == "first" else stage_b.count_reversed
    rng = random.Random(41)
    narrow_rank, adjacency_rank = stage_b._narrow_rank, stage_b._adjacency_rank
    narrowed = []

    def shuffled(a_list, b_list, M, first=frozenset()):
        rank = list(range(M))
        rng.shuffle(rank)
        return rank

    def watched(a_list, b_list, rank):
        narrowed.append(narrow_rank(a_list, b_list, rank) != rank)
        return narrow_rank(a_list, b_list, rank)

    compared = 0
    for query in (QUERIES[0], QUERIES[4]):
        for u, (code, graph, conv) in _joint_units(query):
            if stage_b._programme_fault(code, graph, conv) is not None:
                continue
            monkeypatch.setattr(stage_b, "_NARROW_MOST", -1)
            expected = count(code, graph, conv)
            monkeypatch.setattr(stage_b, "_NARROW_MOST", 14)
            monkeypatch.setattr(stage_b, "_adjacency_rank", shuffled)
            monkeypatch.setattr(stage_b, "_narrow_rank", watched)
            assert count(code, graph, conv) == expected, u.key
            monkeypatch.setattr(stage_b, "_adjacency_rank", adjacency_rank)
            monkeypatch.setattr(stage_b, "_narrow_rank", narrow_rank)
            compared += 1
    assert compared > 50 and sum(narrowed) > 5 and not all(narrowed)
