"""Prismatic pairs: the wedge rule against the Jacobian rank, variant counts against a brute force."""

from __future__ import annotations

from itertools import product

import networkx as nx
import numpy as np
import pytest

from brute_prismatic import brute_variant_count, generic_mobility, has_idle_joint
from synth._type_synthesis import type_synthesis
from synth.chain import Chain
from synth.errors import InvalidOption
from synth.prismatic import (idle_joints, prismatic_variants, wedge_loops, wedge_mobility,
                             wedge_subchain_minimum)

FOUR_BAR = Chain.parse("0-1 1-2 2-3 3-0")
WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
STEPHENSON = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 1-4")


def _assignments(chain: Chain):
    for bits in product(("revolute", "prismatic"), repeat=len(chain.joints)):
        yield Chain(chain.links, chain.joints, bits)


def _agree(chain: Chain, rng) -> None:
    for variant in _assignments(chain):
        kinds = variant.kinds or ("revolute",) * len(chain.joints)
        assert bool(idle_joints(variant)) == has_idle_joint(chain.links, variant.joints, kinds)
        if idle_joints(variant):
            continue
        assert wedge_mobility(variant) == generic_mobility(chain.links, variant.joints, kinds, rng), variant


@pytest.mark.parametrize("dof,links", [(1, 4), (1, 6), (1, 8), (2, 5), (2, 7), (3, 6), (0, 3), (0, 5), (0, 7)])
def test_wedge_rule_equals_jacobian_rank_on_every_assignment(dof, links):
    """Chains of the atlas (no rigid or over-constrained sub-chain): P pairs only raise each W(S)."""
    rng = np.random.default_rng(dof * 100 + links)
    chains = list(type_synthesis(dof, links, workers=1))
    assert chains
    for chain in chains:
        _agree(chain, rng)


def test_wedge_rule_equals_jacobian_rank_on_every_small_graph():
    """Every connected simple graph of 3…5 links, every R/P assignment without idle joints and
    without an over-constrained sub-chain: here all-P loops rescue chains that are over-constrained
    as revolute chains (two wedge triangles on a common pair: W = 1)."""
    rng = np.random.default_rng(5)
    checked = rescued = 0
    for g in nx.graph_atlas_g():
        if not 3 <= g.number_of_nodes() <= 5 or not nx.is_connected(g):
            continue
        base = Chain(g.number_of_nodes(), list(g.edges()))
        for variant in _assignments(base):
            if idle_joints(variant) or wedge_subchain_minimum(variant)[0] < 0 or wedge_mobility(variant) < 0:
                continue
            kinds = variant.kinds or ("revolute",) * len(base.joints)
            assert wedge_mobility(variant) == generic_mobility(base.links, variant.joints, kinds, rng), variant
            checked += 1
            rescued += base.dof < 0
    assert checked > 1000 and rescued > 0


def test_idle_joint_breaks_the_count():
    """Why idle joints are set apart: a triangle of two P pairs and an R pair is rigid by the count
    (W = 0) and rigid in fact, but a four-bar with three P pairs counts W = 1 and cannot move."""
    c = Chain(4, FOUR_BAR.joints, ["prismatic", "prismatic", "prismatic", "revolute"])
    kinds = c.kinds
    assert idle_joints(c) and wedge_mobility(c) == 1
    assert generic_mobility(4, c.joints, kinds, np.random.default_rng(1)) == 0


@pytest.mark.parametrize("chain,counts", [(FOUR_BAR, range(5)), (WATT, (1, 2)), (STEPHENSON, (1, 2))])
def test_variant_counts_match_brute_force(chain, counts):
    for k in counts:
        for idle in (False, True):
            got = len(prismatic_variants(chain, k, idle=idle))
            assert got == brute_variant_count(chain.links, chain.joints, k, idle=idle), (k, idle)


def test_four_bar_counts():
    """R-R-R-R; slider-crank; two P pairs adjacent or opposite (Scotch yoke family); three P pairs
    always make an idle joint; four P pairs: the wedge loop of W = 2."""
    assert [len(prismatic_variants(FOUR_BAR, k)) for k in range(5)] == [1, 1, 2, 0, 1]
    assert [len(prismatic_variants(FOUR_BAR, k, idle=True)) for k in range(5)] == [1, 1, 2, 1, 1]
    (wedge,) = prismatic_variants(FOUR_BAR, 4)
    assert (wedge_mobility(wedge), wedge_loops(wedge)) == (2, 1)


def test_wedge_lever_system():
    """Task 3: 5 links, n2 = 3, n3 = 2, one wedge loop and one lever loop, W = 1."""
    found = [c for base in type_synthesis(0, 5, code="32/0", workers=1)
             for k in range(7) for c in prismatic_variants(base, k) if wedge_mobility(c) == 1]
    assert len(found) == 1
    (c,) = found
    assert str(c.code) == "32/0" and wedge_loops(c) == 1 and c.loops - wedge_loops(c) == 1


@pytest.mark.parametrize("call,message", [
    (lambda: prismatic_variants(FOUR_BAR, 5), "only 4 simple joints"),
    (lambda: prismatic_variants(Chain.parse("0-1-2 0-1-2"), 1), "multiple joints only"),
    (lambda: prismatic_variants(FOUR_BAR, -1), "≥ 0"),
])
def test_refusals(call, message):
    with pytest.raises(InvalidOption, match=message):
        call()
