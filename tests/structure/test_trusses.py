"""A chain fixed by a link is a truss (W = 0 by the count) or a mechanism of its W (W ≥ 1) only when it is one:
``count_defect`` against
brute force (every subset of links by the definition, ``tests/oracles/chains.py``; the true mobility as the
exact rank of the pins' velocity equations at a random rational geometry, ``tests/oracles/gear_mobility.py``),
neither sharing code with the engine."""

from __future__ import annotations

import random
from collections import Counter

import pytest

import synth
from synth import Chain, InvalidOption, count_defect, mechanisms_of

from tests.oracles.chains import subchain_ok  # noqa: E402
from tests.oracles.gear_mobility import generic_geometry, mobility  # noqa: E402
from tests.oracles.subchains import _random_graph  # noqa: E402

#: a braced four-bar (W(S) = −1) joined to a five-bar loop: W = 0 by the count, and it moves
MOVING = "0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-2"


def _true_mobility(chain: Chain, seed: int = 0) -> int:
    pins, contacts = generic_geometry(chain.links, chain.joints, [], random.Random(seed))
    return mobility(chain.links, pins, contacts)


def _is_truss(chain: Chain) -> bool:
    return chain.dof == 0 and subchain_ok(chain.joints, chain.links, rigid_subchains=True) and not _true_mobility(chain)


@pytest.mark.parametrize("links", [5, 7, 9])
def test_a_truss_is_what_brute_force_says(links):
    """Random chains of W = 0 by the count, simple and multiple joints: a truss exactly when no subset of links
    is over-constrained and the links do not move; where they move the defect names the true W."""
    rng = random.Random(links)
    seen = Counter()
    for k in range(120):
        chain = Chain(links, _random_graph(rng, links, 3 * (links - 1) // 2, multiple=k % 2 == 1))
        assert chain.dof == 0
        defect, truss = count_defect(chain), _is_truss(chain)
        assert (defect is None) == truss, (chain.compact(), defect)
        moving = _true_mobility(chain)
        assert (f"the links move with W = {moving}" in str(defect)) == (moving > 0), (chain.compact(), defect)
        seen[truss] += 1
    assert seen[True] >= 2 and seen[False] >= 100  # both verdicts put to the test (engine trusses: below)


@pytest.mark.parametrize("dof, links", [(1, 6), (1, 8), (1, 10), (2, 7), (2, 9)])
def test_a_mechanism_of_its_w_is_what_brute_force_says(dof, links):
    """Random chains of W = 1 and 2 by the count, simple and multiple joints: no defect exactly when every proper
    subset of links has W(S) ≥ 1 and the links move with W; the defect's true W is brute force's, and a chain
    found only degenerate (a rigid sub-chain, no over-constrained one) moves as counted (the chains with no defect:
    the engine's own, below)."""
    rng = random.Random(100 * dof + links)
    seen = Counter()
    for k in range(100):
        chain = Chain(links, _random_graph(rng, links, (3 * (links - 1) - dof) // 2, multiple=k % 2 == 1))
        assert chain.dof == dof
        defect, moving = count_defect(chain), _true_mobility(chain)
        mechanism = subchain_ok(chain.joints, links, rigid_subchains=False) and moving == dof
        assert (defect is None) == mechanism, (chain.compact(), defect)
        if defect is not None:
            no_overconstrained = subchain_ok(chain.joints, links, rigid_subchains=True)
            assert defect.moves == moving and defect.degenerate_only == (no_overconstrained and moving == dof), (
                chain.compact(), defect)
            assert (f"the links move with W = {moving}" in str(defect)) == (moving != dof), (chain.compact(), defect)
        seen["mechanism" if mechanism else "degenerate" if defect.degenerate_only else "misleads"] += 1
    assert seen["misleads"] >= 50 and seen["degenerate"] >= 3, seen  # both defects put to the test


def test_every_chain_type_synthesis_lists_is_what_its_count_says():
    """The listings name chains trusses or mechanisms of their W by their count alone: the exact sub-chain test
    they pass makes the count true (brute force agrees, chain by chain: W = 0 at 5 and 7 links, W = 1 at 6 and 8,
    W = 2 at 7, with multiple joints)."""
    for dof, sizes in ((0, (5, 7)), (1, (6, 8)), (2, (7,))):
        chains = [c for n in sizes for c in synth.type_synthesis(dof, n, v=(0, 1), workers=1)]
        assert len(chains) >= 7
        for c in chains:
            assert count_defect(c) is None, c.compact()
            assert _is_truss(c) if dof == 0 else (subchain_ok(c.joints, c.links, rigid_subchains=False)
                                                  and _true_mobility(c) == dof), c.compact()


def test_a_braced_four_bar_beside_a_five_bar_loop_is_no_truss():
    chain = Chain.parse(MOVING)
    assert (chain.dof, _true_mobility(chain)) == (0, 1)
    assert str(count_defect(chain)) == "a sub-chain is over-constrained (W(S) = -1) and the links move with W = 1"
    assert synth.analyze_chain(MOVING).dof == 1  # analyze says the same


def test_the_library_refuses_an_input_link_of_a_chain_of_w_0():
    """mechanisms_of(chain, input_link=True) gave each truss input links nothing moves; it raises the command
    line's sentence, which says what the chain is, and mechanisms and count_mechanisms refuse the query before
    any work; without input_link nothing changes."""
    with pytest.raises(InvalidOption, match="a truss is a statically determinate structure"):
        mechanisms_of(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4"), input_link=True)
    with pytest.raises(InvalidOption, match=r"not a truss: a sub-chain is over-constrained .* move with W = 1"):
        mechanisms_of(Chain.parse(MOVING), input_link=True)
    for run in (synth.count_mechanisms, lambda *a, **k: next(synth.mechanisms(*a, **k))):
        with pytest.raises(InvalidOption, match="the chains of this query have W = 0 by the count"):
            run(0, 99, input_link=True, workers=1)  # 99 links: refused before a plan could be made
    assert [m.frame for m in mechanisms_of(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4"))] == [0, 3]
