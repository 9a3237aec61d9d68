"""Chains with revolute and prismatic pairs against an oracle that shares no code with the engine
(tests/oracles/rp_chains.py: every simple graph of up to 7 links, every R/P assignment, classified
by the exact generic mobility of the velocity constraints, idle joints on its null space and
isomorphism with joint-kind colours).

``chains --dof W --links n --prismatic A..B`` must list exactly the chains of generic mobility W,
wedge loops included; the sub-chain side of the wedge rule is checked on every subset of links."""

from __future__ import annotations

import itertools
import random

import networkx as nx
import pytest

from synth import Chain, count_chains, type_synthesis
from synth.analysis.chains import analyze_chain
from synth.structure.kinds import generic_mobility, idle_joints, redundant_constraints, structural_mobility
from synth.structure.subchains import check_subchains
from tests.oracles import rp_chains as oracle

CASES = [(W, n) for W in (0, 1, 2) for n in range(3, 8) if (W, n) != (2, 3)]
SLOW = {(0, 7), (1, 7), (2, 7)}


def _by_prismatic(by_code: dict) -> dict:
    out: dict[int, int] = {}
    for name, count in by_code.items():
        p = int(name.split(" P")[1].split()[0]) if " P" in name else 0
        out[p] = out.get(p, 0) + count
    return dict(sorted(out.items()))


@pytest.mark.parametrize("W,n", [pytest.param(*c, marks=pytest.mark.slow) if c in SLOW else c for c in CASES],
                         ids=lambda x: str(x))
def test_counts_by_prismatic_pairs(W, n):
    """`chains --dof W --links n --prismatic 0.. --count` by number of P pairs equals the oracle."""
    assert _by_prismatic(count_chains(W, n, prismatic="0..", workers=1)["by_code"]) == oracle.rp_counts(W, n)


def _canonical(chain: Chain):
    kinds = "".join("P" if k == "prismatic" else "R" for k in chain.kinds)
    return oracle.canonical(chain.links, chain.joints, kinds)


@pytest.mark.parametrize("W,n,idle", [(1, 4, False), (1, 5, False), (1, 6, False), (2, 5, False), (2, 6, False),
                                      (0, 5, False), (1, 5, True), (1, 6, True), (2, 6, True)])
def test_the_same_chains(W, n, idle):
    """Chain by chain (canonical forms), with and without the chains whose joints never move."""
    engine = [_canonical(c) for c in type_synthesis(W, n, prismatic="0..", idle_joints=idle, workers=1)]
    assert len(engine) == len(set(engine))  # no chain twice
    assert sorted(engine) == sorted(oracle.rp_chains(W, n, idle=idle))


def _graphs(sizes):
    for g in nx.graph_atlas_g():
        if g.number_of_nodes() in sizes and nx.is_connected(g) and min(d for _, d in g.degree()) >= 2:
            yield Chain(g.number_of_nodes(), list(g.edges()))


def _sample_assignments(chain: Chain, rng: random.Random, most: int):
    every = list(itertools.product("RP", repeat=len(chain.joints)))
    for kinds in (every if len(every) <= most else rng.sample(every, most)):
        yield Chain(chain.links, chain.joints, ["prismatic" if k == "P" else "revolute" for k in kinds]), "".join(kinds)


# R/P assignments tried per simple graph, by its number of links: every one of 4 links, a sample of
# 5 and 6 (the sample grows in the slow set: every assignment of 5 links, four of 6)
SUBSET_SAMPLES = [pytest.param({4: 64, 5: 12, 6: 1}, 8000, id="sampled"),
                  pytest.param({4: 64, 5: 64, 6: 4}, 20000, id="every-5", marks=pytest.mark.slow)]


@pytest.mark.parametrize("most, least_checked", SUBSET_SAMPLES)
def test_every_subset_of_every_assignment(most, least_checked):
    """Every simple graph of 4, 5 and 6 links, R/P assignments, every subset S of its links: the
    engine's generic mobility of S equals the oracle's; its count W(S), with S's own wedge loops, is
    never above it and equal exactly where S carries no redundant constraint.  And `analyze`'s W and
    sub-chain verdict are the oracle's: no proper S below the threshold or with a redundant
    constraint, and none hidden in the whole (whose own negative count is its W's to say)."""
    rng = random.Random(28)
    checked = differ = 0
    for base in _graphs(set(most)):
        for chain, kinds in _sample_assignments(base, rng, most[base.links]):
            n = chain.links
            whole = oracle.generic_mobility(n, chain.joints, kinds)
            assert analyze_chain(chain).dof == whole == generic_mobility(chain)
            threshold = 0 if whole == 0 else 1
            # no redundant constraint hidden from the count (a negative count shows its own)
            admissible = whole == max(oracle.count_rule(n, chain.joints, kinds), 0)
            for size in range(2, n + 1):
                for s in itertools.combinations(range(n), size):
                    truth = oracle.generic_mobility(n, chain.joints, kinds, links=s)
                    count = structural_mobility(chain, s)
                    assert generic_mobility(chain, s) == truth, (chain.compact(), s)
                    assert count == oracle.count_rule(n, chain.joints, kinds, links=s) and count <= truth
                    assert (count == truth) == (redundant_constraints(chain, s) == 0)
                    differ += count != truth
                    if size < n and (truth < threshold or count != truth):
                        admissible = False  # a rigid proper sub-chain, or constraints that repeat others
                    checked += 1
            assert check_subchains(chain, rigid_subchains=threshold == 0).ok == admissible, chain.compact()
    assert checked > least_checked and differ > 0


def test_idle_joints_equal_the_oracle():
    """Idle joints on the null space, on every assignment of the 5-link graphs and the six-link
    chain whose prismatic path locks a four-bar."""
    for base in _graphs({5}):
        for chain, kinds in _sample_assignments(base, random.Random(5), 64):
            if oracle.generic_mobility(chain.links, chain.joints, kinds) == 0:
                continue  # nothing moves: every joint would be idle
            assert set(idle_joints(chain)) == set(oracle.idle_joints(chain.links, chain.joints, kinds))
    locked = Chain.parse("0-2 0-3 0=4 1-2 1-3 1=5 4=5")
    assert set(idle_joints(locked)) == set(oracle.idle_joints(6, locked.joints, "RRPRRPP"))
