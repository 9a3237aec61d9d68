"""Heterogeneous chains (synth/synthesis/classes.py): loops of two classes, a base of the higher
class on a chain of the lower one, against the independent brute force of
tests/oracles/hetero_chains.py (every graph of up to 7 links, every base, every subset tested);
the chain as a value (certificate, JSON, joint list); the batched test against the one-chain test;
the linear translator of the source."""

from __future__ import annotations

import json
import math
import random

import networkx as nx
import pytest

from synth import Chain, MalformedChain, SynthesisError, analyze_chain, check_subchains, identify
from synth.structure.subchains import least_base_mobilities
from synth.synthesis.classes import _bases, class_variants, heterogeneous_synthesis
from tests.oracles.hetero_chains import hetero_chains

TRANSLATOR = "0-1-6 1-2-7 2-3-8 3-4-9 4-5-10 5-0-11 6-12 8-12 10-12 7-13 9-13 11-13 | h5: 0 1 2 3 4 5"


def _as_graph(chain: Chain) -> nx.Graph:
    """A chain of simple joints as the oracle's labelled graph, the base as node attribute."""
    g = nx.Graph()
    g.add_nodes_from(range(chain.links))
    g.add_edges_from(chain.joints)
    nx.set_node_attributes(g, {i: chain.classes[i] != chain.h for i in range(chain.links)}, "base")
    return g


@pytest.mark.parametrize("dof, classes, expected", [
    (1, {2: 1, 3: 1}, 2),
    (0, {2: 1, 3: 1}, 1),
    (2, {2: 1, 3: 1}, 5),
    (1, {2: 2, 3: 1}, 12),
    (1, {2: 1, 4: 1}, 2),
    (0, {3: 1, 4: 1}, 5),
    (1, {3: 1, 4: 1}, 4),
    (1, {2: 1, 3: 2}, 13),      # a base of two loops
    (0, {3: 1, 5: 1}, 6),
    (1, {2: 1, 5: 1}, 3),
])
def test_counts_equal_the_brute_force(dof, classes, expected):
    """The engine's chains are the oracle's, class by class of isomorphism (base included)."""
    engine = list(heterogeneous_synthesis(dof, classes, workers=1))
    oracle = hetero_chains(dof, classes)
    assert len(engine) == len(oracle) == expected
    match = nx.algorithms.isomorphism.categorical_node_match("base", False)
    for chain in engine:
        assert chain.dof == dof and chain.loop_classes == dict(sorted(classes.items()))
        assert sum(nx.is_isomorphic(_as_graph(chain), g, node_match=match) for g, _ in oracle) == 1


@pytest.mark.slow
def test_many_lower_loops_equal_the_brute_force():
    """Seven links, three loops of class 2 and one of class 3: 99 chains."""
    assert sum(1 for _ in heterogeneous_synthesis(1, {2: 3, 3: 1}, workers=1)) == len(hetero_chains(1, {2: 3, 3: 1})) == 99


def test_the_class_assignment_is_part_of_the_chain():
    """Two bases on one graph are two chains; a renumbering is the same chain; the JSON row and the
    joint list read back; the code names the loops of each class."""
    ring = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3")
    six = Chain.parse(ring.compact() + " | h5: 0 1 2 3 4 5")
    five = Chain.parse(ring.compact() + " | h5: 0 1 2 3 6")
    assert len({ring.certificate, six.certificate, five.certificate}) == 3
    assert (ring.dof, six.dof, five.dof) == (2, 0, 0)
    rng = random.Random(42)
    for _ in range(10):
        perm = list(range(7))
        rng.shuffle(perm)
        moved = six.relabel(perm)
        assert moved.certificate == six.certificate != five.relabel(perm).certificate
        assert Chain.parse(moved.compact()) == moved
        assert Chain.from_json(json.dumps(moved.to_dict())) == moved
    row = six.to_dict()
    assert row["code"] == "52/0 K3=1 K5=1" and row["loop_classes"] == {"3": 1, "5": 1} and row["dof"] == 0


def test_mechanisms_are_the_orbits_of_class_keeping_symmetries():
    """A frame per orbit of the links under the renumberings that keep joints and classes (networkx
    VF2 with the class as a node colour, not nauty): 22 mechanisms for K3 = 1, K5 = 1."""
    from synth import mechanisms_of

    match = nx.algorithms.isomorphism.categorical_node_match("base", False)
    total = 0
    for chain in heterogeneous_synthesis(1, {3: 1, 5: 1}, workers=1):
        g = _as_graph(chain)
        orbit = {v: {m[v] for m in nx.algorithms.isomorphism.GraphMatcher(g, g, node_match=match).isomorphisms_iter()}
                 for v in g}
        orbits = {frozenset(o) for o in orbit.values()}
        assert len(mechanisms_of(chain)) == len(orbits)
        total += len(orbits)
    assert total == 22


def test_lower_ambient_class_reads_back():
    """A chain whose other links are of class 2 writes that class too ('| h2; h3: …')."""
    chain = next(iter(heterogeneous_synthesis(1, {2: 1, 3: 1}, workers=1)))
    assert chain.h == 2 and chain.compact().split("|")[1].startswith(" h2;")
    assert Chain.parse(chain.compact()) == chain


@pytest.mark.parametrize("text, words", [
    ("0-1 1-2 2-0 2-3 | h5: 0 1 2 3", "link 3 of class h = 5 lies on no loop"),
    ("0-1 1-2 2-0 | h9: 0 1 2", "2 … 6, not 9"),
    ("0-1 1-2 2-0 | h5: 0 1 7", "link 7 of class h = 5 is not a link"),
    ("0-1 1-2 2-0 | five: 0 1 2", "cannot read the loop classes"),
    ("0-1 1=2 2-0 | h5: 0 1 2", "revolute joints only"),
])
def test_malformed_classes_are_one_sentence(text, words):
    with pytest.raises(MalformedChain, match=words):
        Chain.parse(text)


def test_batched_test_equals_the_one_chain_test():
    """least_base_mobilities (one scan of the chain, single loops by their supersets) gives, base by
    base, the least W(S) of check_subchains on the heterogeneous chain, rejected bases included."""
    graph = Chain.parse(TRANSLATOR.split("|")[0])
    for chain in [graph, Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3"), Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")]:
        for loops in (1, 2):
            bases = list(_bases(chain, loops))
            least = least_base_mobilities(chain, 5, bases)
            for base, low in zip(bases, least):
                marked = Chain(chain.links, chain.joints, None, 3, tuple(5 if i in base else 3 for i in range(chain.links)))
                assert check_subchains(marked, rigid_subchains=True).worst_mobility == low


def test_the_translator():
    """Fig. 12б: W = 13 − 2·4 − 4·1 = 1, a standard code, no defective sub-chain; of the five loops
    of its graph that can be the class-V loop, the six-link ring is one; the heterogeneous test
    refuses the two-group ring as the base of a W = 1 chain read in h = 3 without classes."""
    t = Chain.parse(TRANSLATOR)
    a = analyze_chain(t)
    assert (a.dof, a.loops, a.v, a.loop_classes, a.standard_code, a.subchain_defect) == (
        1, 5, 6, {"K3": 4, "K5": 1}, True, "none")
    assert Chain(t.links, t.joints).dof == 3  # the same graph read in the plane
    variants = class_variants(Chain(t.links, t.joints), 5, 1)
    assert len(variants) == 5 and t.certificate in {v.certificate for v in variants}
    assert identify(TRANSLATOR, index=False).code == "12.2.0.0.0/6 K3=4 K5=1"


@pytest.mark.slow
def test_the_translator_is_found_by_the_query():
    """The whole query over the translator's code and its three-driver groups lists it."""
    found = [c.certificate for c in heterogeneous_synthesis(1, {3: 4, 5: 1}, code="12.2000/6-0", cranks=["3=3"])]
    assert len(found) == len(set(found)) == 21841
    assert Chain.parse(TRANSLATOR).certificate in found


@pytest.mark.parametrize("kwargs, words", [
    (dict(dof=1, loop_classes={3: 4}), "two classes"),
    (dict(dof=1, loop_classes={3: 4, 5: 0}), "two classes"),
    (dict(dof=1, loop_classes={3: 4, 9: 1}), "2 … 6, not 9"),
    (dict(dof=1, loop_classes={3: 4, 5: 1}, links=12), "needs n = W \\+ 1"),
    (dict(dof=1, loop_classes={3: 4, 5: 1}, h=5), "unknown option"),
])
def test_bad_queries_are_refused(kwargs, words):
    with pytest.raises(SynthesisError, match=words):
        list(heterogeneous_synthesis(workers=1, **kwargs))


def test_size_note_adds_the_bases_to_the_skeletons(monkeypatch):
    """The size of a heterogeneous query: the skeletons' estimate on the workers plus the bases laid
    on each in the parent; more than a day is refused unless forced, more than ten minutes is said."""
    from synth import QueryTooLarge
    from synth.synthesis import estimate as sizing
    from synth.synthesis.classes import SECONDS_PER_SKELETON, size_note, skeleton_query

    query = skeleton_query(1, {3: 6, 5: 1})  # 18 links, seven loops

    def fake(skeletons, chains, seconds):
        return sizing.Estimate(chains=chains, units=10, seconds=seconds, basis="exact counts at 8, 10, 12 links",
                               log10_chains=math.log10(chains), log10_units=1, log10_seconds=math.log10(seconds))

    monkeypatch.setattr(sizing, "estimate", lambda q, **kw: fake(q, 2.0e8, 1.0e5))
    with pytest.raises(QueryTooLarge, match="too large to run unasked: about 2e\\+08 skeletons"):
        size_note(query, processes=2)
    assert "a long query" in size_note(query, processes=2, force=True)
    monkeypatch.setattr(sizing, "estimate", lambda q, **kw: fake(q, 1.0e5, 100.0))  # 50 s + 600 s of bases
    assert 1.0e5 * SECONDS_PER_SKELETON > 599 and "a long query" in size_note(query, processes=2)
    monkeypatch.setattr(sizing, "estimate", lambda q, **kw: fake(q, 1.0e3, 10.0))
    assert size_note(query, processes=2) is None


@pytest.mark.parametrize("dof, classes", [(1, {2: 1, 3: 1}), (2, {2: 1, 3: 1}), (1, {3: 1, 4: 1}), (1, {2: 2, 3: 1})])
def test_rigid_sub_chains_asked_for_equal_the_brute_force(dof, classes):
    """rigid_subchains=True reaches the bases' test too: chains with a sub-chain of W(S) = 0 are kept."""
    engine = list(heterogeneous_synthesis(dof, classes, workers=1, rigid_subchains=True))
    oracle = hetero_chains(dof, classes, rigid_subchains=True)
    assert len(engine) == len(oracle) > len(hetero_chains(dof, classes))
    match = nx.algorithms.isomorphism.categorical_node_match("base", False)
    for chain in engine:
        assert sum(nx.is_isomorphic(_as_graph(chain), g, node_match=match) for g, _ in oracle) == 1
