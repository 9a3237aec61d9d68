"""Heterogeneous queries' sizing and options, on estimates given by hand: every sentence of
:func:`size_note` in full, the day's limit at its exact value, and what reaches type synthesis.
"""

from __future__ import annotations

import math

import pytest

from synth.errors import QueryTooLarge, flag
from synth.synthesis import estimate as sizing
from synth.synthesis.classes import heterogeneous_synthesis, size_note, skeleton_query


def _found(chains, seconds, log10_chains=None):
    return sizing.Estimate(chains=chains, units=10, seconds=seconds, basis="exact counts at 8, 10, 12 links",
                           log10_chains=math.log10(chains) if log10_chains is None else log10_chains, log10_units=1,
                           log10_seconds=math.log10(seconds) if math.isfinite(seconds) else 2000.0)


@pytest.fixture
def given(monkeypatch):
    asked = []

    def give(found):
        monkeypatch.setattr(sizing, "estimate", lambda q, **kw: asked.append((q, kw)) or found)
        return asked

    return give


QUERY = skeleton_query(1, {3: 6, 5: 1})  # 18 links, seven loops: skeletons of W = 3 in h = 3


def test_a_query_of_more_than_a_day_is_refused_in_full(given):
    asked = given(_found(2.0e8, 1.0e5))
    with pytest.raises(QueryTooLarge) as refused:
        size_note(QUERY, processes=2)
    # 1e5 s / 2 + 2e8 · 0.006 s = 1 250 000 s = 14.5 days
    assert refused.value.text(flag) == (
        "this heterogeneous query (18 links) is too large to run unasked: about 2e+08 skeletons of W = 3 in class "
        "h = 3, each given its bases, 14.5 days on 2 workers (extrapolated from the exact counts at 8, 10, 12 links); "
        "give --force to run it anyway, or narrow it (--code C, --v N)")
    assert asked == [(QUERY, {"work": "list", "budget": 5.0})]


def test_a_day_exactly_runs_with_a_note(given):
    given(_found(1000, 86394.0))  # 86 394 s + 1 000 · 0.006 s = 86 400 s: not more than a day
    assert size_note(QUERY, processes=1) == (
        "a long query: about 1 000 skeletons of W = 3 in class h = 3, each given its bases, 24.0 h on 1 worker "
        "(extrapolated from the exact counts at 8, 10, 12 links)")


def test_a_query_beyond_floating_point_is_written_from_its_logarithm(given):
    given(_found(math.inf, math.inf, log10_chains=2100.3))
    with pytest.raises(QueryTooLarge, match=r"about 2e\+2100 skeletons of W = 3"):
        size_note(QUERY, processes=2)


def test_a_forced_query_and_a_short_one(given):
    given(_found(2.0e8, 1.0e5))
    assert size_note(QUERY, processes=2, force=True).startswith("a long query: about 2e+08 skeletons")
    given(_found(1.0e3, 1194.0))  # 597 s + 6 s = 603 s: more than ten minutes
    assert size_note(QUERY, processes=2).startswith("a long query: about 1 000 skeletons")
    given(_found(1.0e3, 1188.0))  # 594 s + 6 s = 600 s: not more
    assert size_note(QUERY, processes=2) is None
    given(None)  # no estimate (too few smaller sizes)
    assert size_note(QUERY, processes=2) is None


def test_queries_of_fewer_than_five_loops_are_not_estimated(given):
    asked = given(_found(2.0e8, 1.0e5))
    assert size_note(skeleton_query(1, {3: 3, 5: 1}), processes=2) is None  # 4 loops
    assert asked == []
    with pytest.raises(QueryTooLarge):
        size_note(skeleton_query(1, {3: 4, 5: 1}), processes=2)  # 5 loops


def test_the_skeletons_are_listed_with_the_caller_s_workers_and_progress(monkeypatch):
    from synth.synthesis import type_synthesis as ts

    calls = []
    monkeypatch.setattr(ts, "type_synthesis", lambda q, **kw: calls.append((q, kw)) or iter(()))
    assert list(heterogeneous_synthesis(1, {3: 1, 5: 1})) == []
    assert list(heterogeneous_synthesis(1, {3: 1, 5: 1}, workers=3, progress=True)) == []
    query = skeleton_query(1, {3: 1, 5: 1})
    assert calls == [(query, {"workers": None, "progress": False}), (query, {"workers": 3, "progress": True})]


WATT = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"  # h = 3, W = 1, two loops


@pytest.mark.parametrize("base_class, loops, words", [
    (3, 1, "above the chain's own class h = 3 (and at most 6), not 3"),  # the chain's own class
    (7, 1, "above the chain's own class h = 3 (and at most 6), not 7"),
    (True, 1, "not True"),
    (4.0, 1, "not 4.0"),
    (4, 0, "a base holds 1 … 2 of the chain's loops, not 0"),
    (4, 3, "a base holds 1 … 2 of the chain's loops, not 3"),  # more loops than the chain has
    (4, True, "not True"),
    (4, 1.0, "not 1.0"),
])
def test_class_variants_refuses_a_class_or_loop_count_out_of_range(base_class, loops, words):
    from synth import Chain, InvalidOption
    from synth.synthesis.classes import class_variants

    with pytest.raises(InvalidOption) as refused:
        class_variants(Chain.parse(WATT), base_class, loops)
    assert words in str(refused.value)


@pytest.mark.parametrize("text", ["0-1 1=2 2-3 3-0", WATT + " | h4: 0 1 2 3"])
def test_class_variants_refuses_a_chain_that_is_not_homogeneous_and_revolute(text):
    from synth import Chain, InvalidOption
    from synth.synthesis.classes import class_variants

    with pytest.raises(InvalidOption, match="loop classes are laid on a homogeneous revolute chain"):
        class_variants(Chain.parse(text), 5, 1)


def test_every_base_of_watt_s_chain_by_hand():
    """Watt's chain (loops 0-1-2-3 and 0-1-5-4) with one loop of class IV: W = 1 − 1 = 0, rigid
    sub-chains allowed.  Its bases of one loop are the two four-link loops (the ring of all six
    links holds the joint 0-1 too: two loops); each made class IV is a rigid four-bar
    (W(S) = 4·3 − 3·4 = 0) and the rest keeps W(S) ≥ 0, and the symmetry swapping 2, 3 with 5, 4
    maps one onto the other: one chain.  Both loops of class IV: W = 1 − 2 = −1, no rigid sub-chain
    allowed by default, and the four-bar of class IV has W = 0: no chain."""
    from synth import Chain
    from synth.synthesis.classes import _bases, class_variants

    watt = Chain.parse(WATT)
    assert sorted(sorted(b) for b in _bases(watt, 1)) == [[0, 1, 2, 3], [0, 1, 4, 5]]
    assert [sorted(b) for b in _bases(watt, 2)] == [[0, 1, 2, 3, 4, 5]]
    found = class_variants(watt, 4, 1)
    assert len(found) == 1 and sorted(i for i, c in enumerate(found[0].classes) if c == 4) in ([0, 1, 2, 3], [0, 1, 4, 5])
    assert found[0].dof == 0
    assert class_variants(watt, 4, 2) == []
    # with rigid sub-chains allowed the four-bars of W = 0 pass (the whole chain is not its own sub-chain)
    [both] = class_variants(watt, 4, 2, rigid_subchains=True)
    assert both.classes == (4,) * 6 and both.dof == -1


@pytest.mark.parametrize("text", [WATT, "0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3",  # Watt's, a ring with a diameter
                                  "0-1-6 1-2-7 2-3-8 3-4-9 4-5-10 5-0-11 6-12 8-12 10-12 7-13 9-13 11-13",  # the translator
                                  "0-1 1-2 2-0 0-3 3-4 4-5 5-0 1-4 2-5"])  # a truss with a rigid triangle
def test_the_loops_of_a_chain_are_the_simple_cycles_of_its_incidence_graph(text):
    """_cycles against networkx's list of simple cycles (links and joints as vertices)."""
    import networkx as nx

    from synth import Chain
    from synth.synthesis.classes import _cycles

    chain = Chain.parse(text)
    graph = nx.Graph((link, ("joint", k)) for k, joint in enumerate(chain.joints) for link in joint)
    expected = {frozenset(v for v in cycle if not isinstance(v, tuple)) for cycle in nx.simple_cycles(graph)}
    assert set(_cycles(chain)) == expected and len(_cycles(chain)) == len(expected)


@pytest.mark.parametrize("text", [WATT, "0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3", "0-1 1-2 2-0 0-3 3-4 4-5 5-0 1-4 2-5",
                                  "0-1 1-2 2-0 2-3 3-4 4-2"])  # (two triangles on one link: loops not joined)
def test_every_number_of_loops_of_a_chain_has_a_base(text):
    """A base of k loops for every k = 1 … K: brute force over the sets of links (the union of loops
    with exactly k independent loops of its own), against _bases."""
    import itertools

    import networkx as nx

    from synth import Chain
    from synth.synthesis.classes import _bases

    chain = Chain.parse(text)
    for k in range(1, chain.loops + 1):
        expected = set()
        for size in range(3, chain.links + 1):
            for links in itertools.combinations(range(chain.links), size):
                # each joint restricted to the set: its links in the set, when two or more
                sub = nx.Graph((link, ("joint", j)) for j, joint in enumerate(chain.joints)
                               for link in joint if link in links and sum(x in links for x in joint) >= 2)
                on_loop = {v for cycle in nx.cycle_basis(sub) for v in cycle}
                rank = sub.number_of_edges() - sub.number_of_nodes() + nx.number_connected_components(sub) if len(sub) else 0
                if set(links) <= on_loop and rank == k:
                    expected.add(frozenset(links))
        found = list(_bases(chain, k))
        assert expected and set(found) == expected and len(found) == len(expected), k  # each base once
