"""Validate the brute-force oracle (tests/oracles/chains.py) against published counts.

These tests do not touch the engine: they establish that the independent
checker is right, so that tests/synthesis/test_chains_vs_oracle.py can trust it.
Reference numbers: docs/theory.md, "Reference counts".
"""

from __future__ import annotations

import itertools
import random
from collections import Counter

import pytest


from tests.oracles.chains import (  # noqa: E402
    ChainIndex,
    _SubsetChecker,
    brute_force_chains_once,
    code_key,
    count_by_code,
    is_connected,
    is_fractionated,
    mobility,
    subchain_ok,
)


def chains(links, dof, v_max=0, rigid=False, frac=True):
    return brute_force_chains_once(links, dof, v_max=v_max, rigid_subchains=rigid, fractionated=frac)


def _by_v(cs):
    return dict(sorted(Counter(c.v for c in cs).items()))


# ---------------------------------------------------------------- 1-DOF, simple joints

@pytest.mark.parametrize("links, expected", [(4, 1), (6, 2), (8, 16)])
def test_one_dof_simple_counts(links, expected):
    assert len(chains(links, 1)) == expected


def test_one_dof_eight_links_by_assortment():
    got = count_by_code(chains(8, 1))
    assert got == {((4, 4), ()): 9, ((5, 2, 1), ()): 5, ((6, 0, 2), ()): 2}


@pytest.mark.parametrize("links, expected", [(4, 1), (6, 5), (8, 71)])
def test_one_dof_mechanisms(links, expected):
    assert sum(c.fixed_link_orbits for c in chains(links, 1)) == expected


def test_one_dof_never_fractionated():
    for links in (4, 6, 8):
        assert chains(links, 1, frac=False) == chains(links, 1, frac=True)
        assert not any(c.fractionated for c in chains(links, 1))


@pytest.mark.slow
def test_one_dof_ten_links():
    cs = chains(10, 1)
    assert len(cs) == 230
    assert sum(not c.planar for c in cs) == 11
    assert count_by_code(cs) == {
        ((4, 6), ()): 50, ((5, 4, 1), ()): 95, ((6, 2, 2), ()): 57,
        ((6, 3, 0, 1), ()): 15, ((7, 0, 3), ()): 3, ((7, 1, 1, 1), ()): 8,
        ((8, 0, 0, 2), ()): 2,
    }


# ---------------------------------------------------------------- 2-DOF and 3-DOF

@pytest.mark.parametrize("dof, links, with_frac, without_frac", [
    (2, 5, 1, 1),
    (2, 7, 4, 3),
    (2, 9, 40, 35),
    (3, 6, 1, 1),
    (3, 8, 7, 5),
    pytest.param(3, 10, 98, 74, marks=pytest.mark.slow),
])
def test_multi_dof_counts(dof, links, with_frac, without_frac):
    kept = chains(links, dof, frac=True)
    dropped = chains(links, dof, frac=False)
    assert len(kept) == with_frac
    assert len(dropped) == without_frac
    # dropping fractionated chains is exactly filtering them
    assert dropped == tuple(c for c in kept if not c.fractionated)


# ---------------------------------------------------------------- multiple joints

def test_multiple_joints_six_links():
    cs = chains(6, 1, v_max=2)
    assert len(cs) == 4
    assert _by_v(cs) == {0: 2, 1: 1, 2: 1}


def test_multiple_joints_eight_links():
    # about 8 s on one core
    cs = chains(8, 1, v_max=4)
    assert len(cs) == 60
    assert _by_v(cs) == {0: 16, 1: 20, 2: 18, 3: 4, 4: 2}


def test_v_max_is_cumulative():
    """v_max = k returns the chains of v_max = k - 1 plus those with v = k."""
    small = chains(6, 1, v_max=1)
    big = chains(6, 1, v_max=2)
    assert small == tuple(c for c in big if c.v <= 1)
    assert chains(6, 1, v_max=0) == tuple(c for c in big if c.v == 0)


# ---------------------------------------------------------------- W = 0 trusses

def test_triangle_is_the_only_three_link_truss():
    cs = chains(3, 0, rigid=True)
    assert [c.joints for c in cs] == [((0, 1), (0, 2), (1, 2))]
    # non-degenerate convention: the triangle's proper sub-chains are fine too
    assert len(chains(3, 0, rigid=False)) == 1


@pytest.mark.parametrize("links, with_frac, without_frac", [
    (5, 3, 2),
    (7, 24, 17),
])
def test_truss_counts_consistency(links, with_frac, without_frac):
    """No published number: counts found by this oracle (regression) plus
    structural consistency of every truss."""
    kept = chains(links, 0, rigid=True, frac=True)
    dropped = chains(links, 0, rigid=True, frac=False)
    assert (len(kept), len(dropped)) == (with_frac, without_frac)
    for c in kept:
        assert mobility(c.joints, links) == 0
        assert subchain_ok(c.joints, links, rigid_subchains=True)
    # the non-degenerate convention is stricter
    strict = chains(links, 0, rigid=False)
    idx = ChainIndex(kept)
    assert all(idx.find(c.joints, links) is not None for c in strict)
    assert len(strict) < len(kept)


def test_truss_standard_codes_present():
    """docs/theory.md lists 32/0 (5 links) and 430/1, 520/2 (7 links) among the trusses."""
    assert ((3, 2), ()) in count_by_code(chains(5, 0, rigid=True))
    codes7 = count_by_code(chains(7, 0, v_max=2, rigid=True))
    assert any(k[0] == (4, 3) and sum(i * x for i, x in enumerate(k[1], 1)) == 1
               for k in codes7)
    assert any(k[0] == (5, 2) and sum(i * x for i, x in enumerate(k[1], 1)) == 2
               for k in codes7)


# ---------------------------------------------------------------- structural invariants

INVARIANT_CASES = [
    (6, 1, 2, False, True), (8, 1, 0, False, True), (7, 2, 0, False, True),
    (8, 3, 0, False, False), (5, 0, 0, True, True), (7, 0, 1, True, True),
]


@pytest.mark.parametrize("links, dof, v_max, rigid, frac", INVARIANT_CASES)
def test_every_result_satisfies_the_definitions(links, dof, v_max, rigid, frac):
    cs = chains(links, dof, v_max, rigid, frac)
    for c in cs:
        assert c.links == links
        assert c.joints == tuple(sorted(c.joints))
        assert all(len(j) >= 2 and list(j) == sorted(set(j)) for j in c.joints)
        assert mobility(c.joints, links) == dof
        assert 0 <= c.v == sum(len(j) - 2 for j in c.joints) <= v_max
        degrees = Counter(i for j in c.joints for i in j)
        assert min(degrees[i] for i in range(links)) >= 2
        assert is_connected(c.joints, links)
        assert subchain_ok(c.joints, links, rigid)
        assert c.fractionated == is_fractionated(c.joints, links)
        if not frac:
            assert not c.fractionated
        assert c.code_key == code_key(c.joints, links)
        assortment, composition = c.code_key
        # counting equation W = sum (3 - i) n_i - 3 - v
        assert sum((3 - i) * x for i, x in enumerate(assortment, 2)) - 3 - c.v == dof
        assert sum(k * x for k, x in enumerate(composition, 1)) == c.v
        assert 1 <= c.fixed_link_orbits <= links


# ---------------------------------------------------------------- relabelling

def _shuffle(joints, links, rng):
    perm = list(range(links))
    rng.shuffle(perm)
    out = [tuple(perm[i] for i in j) for j in joints]
    rng.shuffle(out)
    return out


@pytest.mark.parametrize("links, dof, v_max, rigid, frac", INVARIANT_CASES)
def test_relabelling_is_identified(links, dof, v_max, rigid, frac):
    rng = random.Random(42)
    cs = chains(links, dof, v_max, rigid, frac)
    idx = ChainIndex(cs)
    for k, c in enumerate(cs):
        for _ in range(3):
            assert idx.find(_shuffle(c.joints, links, rng), links) == k


def test_index_rejects_duplicates_and_unknowns():
    cs = chains(8, 1)
    idx = ChainIndex(cs[:-1])
    assert idx.find(cs[-1].joints, 8) is None
    with pytest.raises(ValueError):
        idx.add(_shuffle(cs[0].joints, 8, random.Random(1)), 8)


# ---------------------------------------------------------------- checker internals

def test_packed_subset_check_matches_plain_check():
    rng = random.Random(7)
    for links in (4, 5, 6, 7):
        pairs = list(itertools.combinations(range(links), 2))
        triples = list(itertools.combinations(range(links), 3))
        for rigid in (False, True):
            for _ in range(300):
                joints = rng.sample(pairs, rng.randint(1, min(len(pairs), 2 * links)))
                joints += rng.sample(triples, rng.randint(0, 2))
                p = sum(len(j) - 1 for j in joints)
                chk = _SubsetChecker(links, max(p, 1), rigid)
                load = chk.load_of(joints)
                # the packed checker ignores the whole set in the
                # non-degenerate convention; compare like with like
                assert chk.ok(load) == subchain_ok(joints, links, rigid)


def _naive(links, dof, rigid, frac):
    """Zero-pruning enumeration: every set of p distinct pairs, filtered by the
    definitions, deduplicated with ChainIndex."""
    twice_p = 3 * (links - 1) - dof
    p = twice_p // 2
    pairs = list(itertools.combinations(range(links), 2))
    idx = ChainIndex()
    for joints in itertools.combinations(pairs, p):
        deg = Counter(i for j in joints for i in j)
        if len(deg) < links or min(deg.values()) < 2:
            continue
        if not is_connected(joints, links):
            continue
        if not subchain_ok(joints, links, rigid):
            continue
        if not frac and is_fractionated(joints, links):
            continue
        if idx.find(joints, links) is None:
            idx.add(joints, links)
    return idx


@pytest.mark.parametrize("links, dof, rigid, frac", [
    (4, 1, False, True), (6, 1, False, True), (5, 2, False, True),
    (6, 3, False, True), (6, 3, False, False), (5, 0, True, True),
    (5, 0, True, False), (3, 0, True, True),
])
def test_pruned_search_equals_unpruned_enumeration(links, dof, rigid, frac):
    idx = _naive(links, dof, rigid, frac)
    cs = chains(links, dof, 0, rigid, frac)
    assert idx.size == len(cs)
    assert sorted(idx.find(c.joints, links) for c in cs) == list(range(idx.size))


@pytest.mark.slow
@pytest.mark.parametrize("links, dof, rigid, frac", [
    (7, 2, False, True), (7, 2, False, False), (7, 0, True, True),
])
def test_pruned_search_equals_unpruned_enumeration_slow(links, dof, rigid, frac):
    test_pruned_search_equals_unpruned_enumeration(links, dof, rigid, frac)
