"""Validate the R/P chain oracle (tests/oracles/rp_chains.py) without the engine.

Against published counts (all-revolute rows), against the other independent oracles (the count-based
brute force of tests/oracles/chains.py, the floating-point Jacobian of tests/oracles/prismatic.py),
against a labelled brute force that uses the plain definitions (every subset, no pruning), and
against chains checked by hand.
"""

from __future__ import annotations

import itertools
import random

import networkx as nx
import numpy as np
import pytest

from tests.oracles import prismatic
from tests.oracles.chains import brute_force_chains
from tests.oracles.rp_chains import (
    canonical,
    count_misses,
    count_rule,
    generic_mobility,
    idle_joints,
    is_fractionated,
    rp_chains,
    rp_counts,
    rp_survey,
)


def _parse(text: str):
    """'0-1 1=2' -> links, joints, kinds ('-' revolute, '=' prismatic)."""
    joints, kinds = [], []
    for tok in text.split():
        sep = "=" if "=" in tok else "-"
        a, b = map(int, tok.split(sep))
        joints.append((a, b))
        kinds.append("prismatic" if sep == "=" else "revolute")
    return max(max(j) for j in joints) + 1, joints, kinds


# ---------------------------------------------------------------- published, all-revolute

@pytest.mark.parametrize("W, n, fractionated, expected", [
    (1, 4, True, 1), (1, 6, True, 2), (1, 6, False, 2),
    (2, 5, True, 1), (2, 7, True, 4), (2, 7, False, 3),
    (1, 5, True, 0), (1, 7, True, 0), (2, 6, True, 0),          # parity: 3(n - 1) - W is even
])
def test_published_revolute_counts(W, n, fractionated, expected):
    assert len(rp_chains(W, n, p_range=(0, 0), fractionated=fractionated)) == expected


@pytest.mark.parametrize("W, n", [(1, 4), (1, 6), (2, 5), (2, 7), (0, 5), (0, 7)])
def test_revolute_chains_equal_count_oracle(W, n):
    """With no P pair generic mobility is the count and W(S) >= 1 (trusses: >= 0 and no redundant
    constraint) is the count convention (Tay's theorem for pinned bodies): the same classes as the
    count-based brute force, which shares nothing with this oracle."""
    brute = {canonical(n, c.joints, ["revolute"] * len(c.joints))
             for c in brute_force_chains(n, W, rigid_subchains=(W == 0))}
    assert set(rp_chains(W, n, p_range=(0, 0))) == brute


# ---------------------------------------------------------------- chains checked by hand

def test_wedges():
    # all-P four-bar: rotations locked, 2·3 translations − 4 normals = 2 (a wedge loop, h = 2)
    assert generic_mobility(4, [(0, 1), (1, 2), (2, 3), (3, 0)], ["prismatic"] * 4) == 2
    # all-P triangle: 2·2 − 3 = 1
    assert generic_mobility(3, [(0, 1), (1, 2), (0, 2)], ["prismatic"] * 3) == 1
    assert rp_chains(1, 3) == [(((0, 1), (0, 2), (1, 2)), ("prismatic",) * 3)]
    # any R pair in a triangle makes it rigid
    for kinds in itertools.product(("revolute", "prismatic"), repeat=3):
        if "revolute" in kinds:
            assert generic_mobility(3, [(0, 1), (1, 2), (0, 2)], kinds) == 0


def test_task3_wedge_lever_system():
    """Task 3: 5 links, n2 = 3, n3 = 2, one all-P loop (K_2 = 1) and one planar loop (K_3 = 1), W = 1.
    Built from the brief: ternary links 0 and 1 and binary link 2 close the wedge triangle
    0=1=2; binary links 3, 4 close the lever loop 0-3-4-1 with revolute pairs."""
    n, joints, kinds = _parse("0=1 0=2 1=2 0-3 3-4 1-4")
    assert count_rule(n, joints, kinds) == 1
    assert generic_mobility(n, joints, kinds) == 1
    assert idle_joints(n, joints, kinds) == ()
    form = canonical(n, joints, kinds)
    assert form in rp_chains(1, 5, p_range=(3, 3))
    # its revolute skeleton is the truss 32/0 (W_R = 0) and the wedge loop adds one freedom
    assert generic_mobility(n, joints, ["revolute"] * 6) == 0


def test_six_link_idle_four_bar():
    """0-2 0-3 0=4 1-2 1-3 1=5 4=5: the P path 0=4=5=1 locks the rotation of 1 against 0, so the
    four-bar 0-2-1-3 is rigid and its four revolute pairs never turn; only the wedge slides."""
    n, joints, kinds = _parse("0-2 0-3 0=4 1-2 1-3 1=5 4=5")
    assert generic_mobility(n, joints, kinds) == 1
    assert set(idle_joints(n, joints, kinds)) == {(0, 2), (0, 3), (1, 2), (1, 3)}
    assert prismatic.has_idle_joint(n, joints, kinds)     # the floating-point null space sees it too
    form = canonical(n, joints, kinds)
    assert form in rp_chains(1, 6, p_range=(3, 3), idle=True)
    assert form not in rp_chains(1, 6, p_range=(3, 3))


def test_rigid_triangle_with_p_path_is_a_count_miss():
    """0-1 0-2 1-2 1=3 2=4 3=4: the revolute triangle is rigid, so the P path's rotation lock
    between 1 and 2 is redundant and links 3, 4 slide (4 translations − 3 normals): W = 1 while
    the count (and every sub-chain's count) says truss."""
    n, joints, kinds = _parse("0-1 0-2 1-2 1=3 2=4 3=4")
    assert count_rule(n, joints, kinds) == 0
    assert generic_mobility(n, joints, kinds) == 1
    assert canonical(n, joints, kinds) in {(r.joints, r.kinds) for r in count_misses(0, 5)}
    assert canonical(n, joints, kinds) not in rp_chains(0, 5)


def test_prismatic_slider_crank_four_bars():
    # four-bar: 0 P (1), 1 P (1), 2 P adjacent or opposite (2), 3 P (idle R pair), 4 P (W = 2)
    assert rp_counts(1, 4, idle=True) == {0: 1, 1: 1, 2: 2, 3: 1, 5: 1}
    assert rp_counts(1, 4) == {0: 1, 1: 1, 2: 2, 5: 1}
    # K4 minus an edge, both triangles wedges: 2·3 − 5 = 1
    assert canonical(4, [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3)], "PPPPP") in rp_chains(1, 4)
    assert rp_counts(2, 4) == {4: 1}


# ---------------------------------------------------------------- other independent methods

def test_exact_rank_equals_floating_jacobian():
    """The modular rank against the floating-point Jacobian of tests/oracles/prismatic.py on random
    labelled chains (any graph, any kinds, 3 to 7 links)."""
    rnd = random.Random(7)
    rng = np.random.default_rng(7)
    for _ in range(300):
        n = rnd.randint(3, 7)
        pairs = list(itertools.combinations(range(n), 2))
        joints = rnd.sample(pairs, rnd.randint(n - 1, len(pairs)))
        kinds = [rnd.choice(("revolute", "prismatic")) for _ in joints]
        assert generic_mobility(n, joints, kinds) == prismatic.generic_mobility(n, joints, kinds, rng, trials=3)


def _plain_classes(n):
    """Labelled brute force with the plain definitions: every labelled graph and assignment, every
    subset S (disconnected ones too) by rank, no pruning; classes by canonical form."""
    out = {0: {}, 1: {}, 2: {}}
    pairs = list(itertools.combinations(range(n), 2))
    for colours in itertools.product((None, "revolute", "prismatic"), repeat=len(pairs)):
        joints = [p for p, c in zip(pairs, colours) if c]
        kinds = [c for c in colours if c]
        g = nx.Graph(joints)
        if g.number_of_nodes() < n or not nx.is_connected(g) or min(d for _, d in g.degree()) < 2:
            continue
        W = generic_mobility(n, joints, kinds)
        if W > 2 or (W == 0 and count_rule(n, joints, kinds) != 0):
            continue
        if W >= 1 and any(generic_mobility(n, joints, kinds, links=s) < 1
                          for k in range(2, n) for s in itertools.combinations(range(n), k)):
            continue
        form = canonical(n, joints, kinds)
        idle = bool(idle_joints(n, joints, kinds)) if W else False
        if out[W].setdefault(form, idle) != idle:
            raise AssertionError(f"idle verdict differs between labellings of {form}")
    return out


def _survey_classes(n):
    return {W: {(r.joints, r.kinds): bool(r.idle) for r in rp_survey(W, n).records} for W in (0, 1, 2)}


def test_survey_equals_labelled_brute_force_four_links():
    assert _plain_classes(4) == _survey_classes(4)


@pytest.mark.slow
def test_survey_equals_labelled_brute_force_five_links():
    assert _plain_classes(5) == _survey_classes(5)


@pytest.mark.slow
@pytest.mark.parametrize("W", [0, 1, 2])
def test_pruning_drops_nothing_at_six_links(W):
    """The prunings (count <= W, trusses' edge bound, all-P triangles) and the sub-chain count
    shortcut drop no chain: the same records when every assignment orbit gets its ranks."""
    assert rp_survey(W, 6, prune=False).records == rp_survey(W, 6).records


def test_classes_are_pairwise_non_isomorphic_and_canonical():
    """VF2 with the kinds as edge colours, independent of the canonical form."""
    em = nx.algorithms.isomorphism.categorical_edge_match("kind", None)
    for W, n in ((1, 6), (2, 6), (0, 5)):
        graphs = []
        for r in rp_survey(W, n).records:
            g = nx.Graph()
            g.add_edges_from((a, b, {"kind": k}) for (a, b), k in zip(r.joints, r.kinds))
            graphs.append(g)
            # a random relabelling has the same canonical form
            perm = random.Random(len(graphs)).sample(range(n), n)
            assert canonical(n, [(perm[a], perm[b]) for a, b in r.joints], r.kinds) == (r.joints, r.kinds)
        for g, h in itertools.combinations(graphs, 2):
            if sorted(d for _, d in g.degree()) == sorted(d for _, d in h.degree()):
                assert not nx.is_isomorphic(g, h, edge_match=em)


# ---------------------------------------------------------------- properties of the results

@pytest.mark.parametrize("W, n", [(1, 5), (1, 6), (2, 5), (2, 6)])
def test_path_rule_idle_joints_are_idle(W, n):
    """A revolute pair whose links are joined by a P path is idle by the generic test too."""
    for r in rp_survey(W, n).records:
        for j, k in zip(r.joints, r.kinds):
            if k == "revolute":
                others = [(a, b) for (a, b), kk in zip(r.joints, r.kinds) if kk == "prismatic"]
                g = nx.Graph(others)
                if j[0] in g and j[1] in g and nx.has_path(g, *j):
                    assert j in r.idle


@pytest.mark.parametrize("W, n", [(0, 5), (0, 6), (1, 5), (1, 6), (2, 5), (2, 6)])
def test_count_agrees_up_to_six_links(W, n):
    """THEORY C3 (checked there by another program): up to 6 links the rule equals the rank except
    on idle joints and over-constrained sub-chains; here: every admissible chain has W = count."""
    survey = rp_survey(W, n)
    assert all(r.mobility == r.count == W for r in survey.records)
    assert all(r.fractionated == is_fractionated(n, r.joints) for r in survey.records)


@pytest.mark.slow
def test_seven_link_hidden_redundancies_all_idle():
    """At 7 links W = 1 has chains with W above the count (count 0): in each, P paths lock the
    rotations of a four-bar's links, so all its revolute pairs are idle."""
    flagged = [r for r in rp_survey(1, 7).records if r.redundancy]
    assert flagged and all(r.count == 0 and r.idle for r in flagged)
    for r in flagged:
        assert {j for j, k in zip(r.joints, r.kinds) if k == "revolute"} <= set(r.idle)


def test_p_range_and_counts_agree():
    everything = rp_chains(2, 5, idle=True)
    by_p = rp_counts(2, 5, idle=True)
    assert sum(by_p.values()) == len(everything)
    for k, c in by_p.items():
        assert len(rp_chains(2, 5, p_range=(k, k), idle=True)) == c
    assert rp_chains(2, 5, p_range=(0, 1), idle=True) == [x for x in everything
                                                          if x[1].count("prismatic") <= 1]
