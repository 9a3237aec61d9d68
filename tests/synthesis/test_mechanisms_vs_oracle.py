"""Mechanisms (frame, and frame + input link) against a brute force over labelled choices.

The engine picks one frame per nauty orbit of links and one input link per orbit of
the frame's stabiliser, and names mechanisms by nauty certificates with the frame
and input link in colour cells of their own.  Here every labelled choice on every
chain is listed and grouped by isomorphism decided without nauty
(``tests/oracles/mechanisms.py``: VF2 with node colours; brute-force canonical forms
on small chains), and compared per chain, in total, and certificate by certificate.
The chains themselves come from the engine and, for the totals, from the
brute-force chain enumerator ``tests/oracles/chains.py``.
"""

from __future__ import annotations

import functools
import random
from collections import defaultdict

import pytest

import synth
from synth import Chain, Mechanism
from synth.synthesis.type_synthesis import mechanisms_of

from tests.oracles.mechanisms import canonical_form, choices, mechanism_classes  # noqa: E402
from tests.oracles.chains import brute_force_chains  # noqa: E402

# (W, n, v): small queries with simple and multiple joints, every W the engine builds
QUERIES = [(1, 4, 0), (1, 6, (0, 2)), (1, 8, (0, 4)), (2, 5, 0), (2, 7, (0, 1)), (3, 6, (0, 3)), (3, 8, 0),
           (0, 5, 0), (0, 7, (0, 1))]
SAMPLE_10 = 30  # chains of 10 links checked by default (fixed seed); all 230 under -m slow


@functools.lru_cache(maxsize=None)
def engine_chains(W, n, v) -> tuple[Chain, ...]:
    return tuple(synth.type_synthesis(W, n, v=v, workers=1))


@functools.lru_cache(maxsize=None)
def brute_classes(chain: Chain, input_link: bool):
    return mechanism_classes(chain.links, chain.joints, input_link)


def _check_chain(chain: Chain, input_link: bool) -> int:
    """Engine mechanisms of one chain: one per brute-force class, and certificates = classes."""
    classes = brute_classes(chain, input_link)
    where = chain.compact()
    class_of = {choice: k for k, members in enumerate(classes) for choice in members}
    got = mechanisms_of(chain, input_link=input_link)
    hit = [class_of[m.marked] for m in got]
    assert len(set(hit)) == len(hit), f"{where}: the engine lists isomorphic mechanisms {hit}"
    assert len(got) == len(classes), f"{where}: engine {len(got)} mechanisms, brute force {len(classes)}"
    # certificates split the labelled choices exactly as the isomorphism classes do
    by_cert = defaultdict(set)
    for choice in choices(chain.links, chain.joints, input_link):
        by_cert[Mechanism(chain, *choice).certificate].add(class_of[choice])
    assert all(len(ks) == 1 for ks in by_cert.values()), f"{where}: one certificate for different mechanisms"
    assert len(by_cert) == len(classes), f"{where}: one mechanism with different certificates"
    return len(classes)


#: every query on its frames, and with input links but trusses (W = 0: refused, tests/structure/test_trusses.py)
PER_CHAIN = [(q, i) for q in QUERIES for i in (False, True) if not (i and q[0] == 0)]


@pytest.mark.parametrize("query, input_link", PER_CHAIN, ids=[f"{q}-{'frame+input' if i else 'frame'}"
                                                              for q, i in PER_CHAIN])
def test_mechanisms_per_chain(query, input_link):
    total = sum(_check_chain(c, input_link) for c in engine_chains(*query))
    assert synth.count_mechanisms(*query[:2], v=query[2], input_link=input_link, workers=1)["count"] == total


def _ten_link_sample(k):
    chains = engine_chains(1, 10, 0)
    return chains if k is None else random.Random(10).sample(chains, k)


@pytest.mark.parametrize("input_link", [False, True], ids=["frame", "frame+input"])
def test_ten_link_chains_sample(input_link):
    for chain in _ten_link_sample(SAMPLE_10):
        _check_chain(chain, input_link)


@pytest.mark.slow
@pytest.mark.parametrize("input_link", [False, True], ids=["frame", "frame+input"])
def test_ten_link_chains_all(input_link):
    total = sum(_check_chain(c, input_link) for c in _ten_link_sample(None))
    assert synth.count_mechanisms(1, 10, input_link=input_link, workers=1)["count"] == total


@functools.lru_cache(maxsize=None)
def oracle_total(links, dof, v_max, input_link):
    """Mechanisms of every chain the brute-force enumerator finds (no engine at all)."""
    return sum(len(mechanism_classes(c.links, c.joints, input_link))
               for c in brute_force_chains(links, dof, v_max=v_max))


@pytest.mark.parametrize("links, frame_only, with_input", [(4, 1, 1), (6, 5, 9), (8, 71, 153)])
def test_totals_equal_brute_force_over_brute_force_chains(links, frame_only, with_input):
    """1-DOF chains of 4, 6, 8 links: 1, 5, 71 mechanisms (published) and 1, 9, 153 with an input link."""
    assert oracle_total(links, 1, 0, False) == frame_only
    assert oracle_total(links, 1, 0, True) == with_input
    for input_link, want in ((False, frame_only), (True, with_input)):
        assert synth.count_mechanisms(1, links, input_link=input_link, workers=1)["count"] == want
        assert sum(1 for _ in synth.mechanisms(1, links, input_link=input_link, workers=1)) == want


def test_multiple_joint_totals_equal_brute_force():
    for input_link in (False, True):
        want = oracle_total(6, 1, 2, input_link)
        assert synth.count_mechanisms(1, 6, v=(0, 2), input_link=input_link, workers=1)["count"] == want


@pytest.mark.parametrize("query", [(1, 4, 0), (1, 6, (0, 2)), (2, 5, 0), (3, 6, (0, 3))], ids=str)
def test_vf2_classes_equal_canonical_forms(query):
    """The two brute-force isomorphism methods agree (small chains: every permutation of the links)."""
    for chain in engine_chains(*query):
        for input_link in (False, True):
            classes = brute_classes(chain, input_link)
            forms = [{canonical_form(chain.links, chain.joints, c) for c in members} for members in classes]
            assert all(len(f) == 1 for f in forms), chain.compact()
            assert len({next(iter(f)) for f in forms}) == len(forms), chain.compact()


def test_frame_and_input_swapped_are_told_apart():
    """A mechanism and its frame/input swap share a certificate exactly when they are isomorphic."""
    swaps = told_apart = 0
    for chain in engine_chains(1, 8, (0, 4)):
        class_of = {c: k for k, members in enumerate(brute_classes(chain, True)) for c in members}
        for f, i in choices(chain.links, chain.joints, True):
            same = Mechanism(chain, f, i).certificate == Mechanism(chain, i, f).certificate
            assert same == (class_of[f, i] == class_of[i, f]), (chain.compact(), f, i)
            swaps += 1
            told_apart += not same
    assert told_apart > swaps // 2  # most swaps are different mechanisms


def test_certificates_survive_random_relabelling():
    rng = random.Random(1616)
    for query in QUERIES:
        for chain in engine_chains(*query):
            perm = list(range(chain.links))
            rng.shuffle(perm)
            other = chain.relabel(perm)
            for m in mechanisms_of(chain, input_link=chain.dof != 0):  # a truss: on its frame alone
                moved = Mechanism(other, perm[m.frame], None if m.input_link is None else perm[m.input_link])
                assert moved.certificate == m.certificate, (chain.compact(), perm)
            assert other.certificate == chain.certificate


def test_mechanism_certificate_differs_from_chain_and_frame_only():
    chain = engine_chains(1, 6, 0)[0]
    frame = Mechanism(chain, 0)
    with_input = Mechanism(chain, 0, mechanisms_of(chain, input_link=True)[0].input_link)
    assert len({chain.certificate, frame.certificate, with_input.certificate}) == 3
