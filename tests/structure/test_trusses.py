"""A chain of W = 0 by the count fixed by a link is a truss only when it is one: ``truss_defect`` against
brute force (every subset of links by the definition, ``tests/oracles/chains.py``; the true mobility as the
exact rank of the pins' velocity equations at a random rational geometry, ``tests/oracles/gear_mobility.py``),
neither sharing code with the engine."""

from __future__ import annotations

import random
from collections import Counter

import pytest

import synth
from synth import Chain, InvalidOption, mechanisms_of, truss_defect

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
        defect, truss = truss_defect(chain), _is_truss(chain)
        assert (defect is None) == truss, (chain.compact(), defect)
        moving = _true_mobility(chain)
        assert (f"the links move with W = {moving}" in (defect or "")) == (moving > 0), (chain.compact(), defect)
        seen[truss] += 1
    assert seen[True] >= 2 and seen[False] >= 100  # both verdicts put to the test (engine trusses: below)


def test_every_truss_type_synthesis_lists_is_one():
    """The listings name W = 0 chains trusses by their count alone: the exact sub-chain test they pass makes the
    count true (brute force agrees, chain by chain, at 5 and 7 links with multiple joints)."""
    chains = [c for n in (5, 7) for c in synth.type_synthesis(0, n, v=(0, 1), workers=1)]
    assert len(chains) > 20 and all(_is_truss(c) and truss_defect(c) is None for c in chains)


def test_a_braced_four_bar_beside_a_five_bar_loop_is_no_truss():
    chain = Chain.parse(MOVING)
    assert (chain.dof, _true_mobility(chain)) == (0, 1)
    assert truss_defect(chain) == "a sub-chain is over-constrained (W(S) = -1) and the links move with W = 1"
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
