"""The prismatic variants of one given chain (synth/synthesis/variants.py) against the independent
R/P oracle (tests/oracles/rp_chains.py): every admissible chain of that graph, of any mobility, with
and without joints that never move; cylinders only between two binary links; ``variants_of`` as
the variants of its counts one after the other."""

from __future__ import annotations

import itertools

import pytest

from synth import Chain
from synth.synthesis.stage_a import Conventions
from synth.synthesis.variants import assignments, prismatic_variants, variants_of
from tests.oracles import rp_chains as oracle

WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")


def _canonical(chain: Chain):
    kinds = "".join("P" if k == "prismatic" else "R" for k in chain.kinds)
    return oracle.canonical(chain.links, chain.joints, kinds)


def _oracle_variants(chain: Chain, idle: bool) -> list:
    """The oracle's admissible chains (every mobility a wedge loop can reach) on ``chain``'s graph."""
    graph = oracle.canonical(chain.links, chain.joints, "R" * len(chain.joints))[0]
    return [(joints, kinds) for W in range(chain.dof + chain.loops + 1)
            for joints, kinds in oracle.rp_chains(W, chain.links, idle=idle)
            if oracle.canonical(chain.links, joints, "R" * len(joints))[0] == graph]


@pytest.mark.parametrize("text", [
    "0-1 1-2 2-3 3-0",                    # four-bar: slider-cranks, ..., the wedge loop (W = 2)
    WATT.compact(),
    "0-1 1-2 2-0 1-3 3-4 4-2",            # a truss (W = 0) with a rigid triangle in it
    "0-1 1-2 2-0 0-3 3-4 4-5 5-2",        # W = 1 on a rigid triangle: only its wedge loop moves it
])
def test_variants_of_one_chain_are_the_oracles(text):
    """Every count of prismatic pairs, the defaults (no idle joints; rigid sub-chains only in a
    truss) and with idle joints: the same chains as the oracle's, class by class."""
    chain = Chain.parse(text)
    for idle in (False, True):
        expected = _oracle_variants(chain, idle)
        for k in range(len(chain.joints) + 1):
            found = prismatic_variants(chain, k, idle=True) if idle else prismatic_variants(chain, k)
            assert sorted(map(_canonical, found)) == sorted(x for x in expected if x[1].count("prismatic") == k), (k, idle)


def test_rigid_subchains_as_asked():
    """The truss with a rigid triangle, rigid sub-chains refused although its W is 0: only the
    oracle's chains of that graph in which every proper set of links moves are left (the triangle
    a wedge loop)."""
    truss = Chain.parse("0-1 1-2 2-0 1-3 3-4 4-2")
    n = truss.links

    def every_part_moves(joints, kinds):
        letters = "".join("P" if k == "prismatic" else "R" for k in kinds)
        return all(oracle.generic_mobility(n, joints, letters, links=s) >= 1
                   for size in range(2, n) for s in itertools.combinations(range(n), size))

    expected = [x for x in _oracle_variants(truss, False) if every_part_moves(*x)]
    assert expected
    for k in range(len(truss.joints) + 1):
        found = prismatic_variants(truss, k, rigid_subchains=False)
        assert sorted(map(_canonical, found)) == sorted(x for x in expected if x[1].count("prismatic") == k), k


def test_cylinders_only_between_binary_links():
    """With every prismatic pair a cylinder, a unit tries only the joints between two binary links:
    on Watt's chain 2-3 and 4-5, one or both — the oracle's chains of that graph with such pairs."""
    def binary(joints, a):
        return sum(a in j for j in joints) == 2

    expected = [(j, k) for j, k in _oracle_variants(WATT, False)
                if 1 <= k.count("prismatic") <= 2
                and all(binary(j, a) and binary(j, b) for (a, b), kind in zip(j, k) if kind == "prismatic")]
    found = assignments(WATT, Conventions(prismatic=(1, 2), cylinders_only=True))
    assert len(found) == 2 and sorted(map(_canonical, found)) == sorted(expected)


def test_variants_of_runs_through_the_counts():
    """A chain with a double joint (1-3-5; five simple joints): the counts A..B, B open or beyond the
    simple joints, with and without idle joints, are the variants of each count in turn."""
    chain = Chain.parse("0-1 0-2 0-4 1-3-5 2-3 4-5")
    for counts, ks in (((0, None), range(6)), ((1, 2), (1, 2)), ((2, 9), range(2, 6))):
        for idle in (False, True):
            expected = [v for k in ks for v in prismatic_variants(chain, k, idle=idle)]
            assert list(variants_of([chain], counts, idle=idle)) == expected, (counts, idle)
    assert list(variants_of([chain], (0, None))) != list(variants_of([chain], (0, None), idle=True))
