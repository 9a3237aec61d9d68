"""Agreement of the fast engine (synth.type_synthesis) with the brute-force oracle.

The oracle (tests/oracles/chains.py) shares no code with the engine and is
validated against published counts in tests/oracles/test_chains_vs_published.py.
For every case the oracle finishes we compare

* the number of chains,
* the counts by code key ``(assortment, composition)``,
* the chains themselves: every engine chain is mapped through the oracle's
  isomorphism index (networkx WL buckets + VF2, no nauty); each must hit an
  oracle class and no two engine chains may hit the same class,

plus the engine's own consistency: each engine chain satisfies the
definitions (mobility, closure, connectivity, sub-chain convention,
fractionated rule, v range) and its ``code`` matches its joints.
"""

from __future__ import annotations

import functools
from collections import Counter

import pytest

import synth


from tests.oracles.chains import (  # noqa: E402
    ChainIndex,
    brute_force_chains,
    brute_force_chains_once,
    code_key,
    count_by_code,
    is_connected,
    is_fractionated,
    mobility,
    subchain_ok,
)


def _case(dof, links, v_max, rigid, frac, slow=False):
    cid = (f"W{dof}-n{links}-v{v_max}-"
           f"{'rigid' if rigid else 'nondeg'}-{'frac' if frac else 'nofrac'}")
    marks = [pytest.mark.slow] if slow else []
    return pytest.param(dof, links, v_max, rigid, frac, id=cid, marks=marks)


# (dof, links, v_max, rigid_subchains, fractionated); oracle time on one core
# in the comment where it is above a second.
CASES = [
    # W = 1, non-degenerate (never fractionated, so fractionated=False checks
    # the engine's filter does not drop anything)
    _case(1, 4, 0, False, True),
    _case(1, 4, 2, False, True),
    _case(1, 6, 0, False, True),
    _case(1, 6, 2, False, True),
    _case(1, 6, 2, False, False),
    _case(1, 8, 0, False, True),
    _case(1, 8, 0, False, False),
    _case(1, 8, 4, False, True),                   # ~8 s
    _case(1, 10, 0, False, True, slow=True),        # several minutes
    # W = 1, rigid sub-chains allowed
    _case(1, 6, 0, True, True),
    _case(1, 6, 2, True, True),
    _case(1, 6, 2, True, False),
    _case(1, 8, 0, True, True),
    _case(1, 8, 0, True, False),
    # W = 2
    _case(2, 5, 0, False, True),
    _case(2, 5, 3, False, True),
    _case(2, 7, 0, False, True),
    _case(2, 7, 0, False, False),
    _case(2, 7, 3, False, True),
    _case(2, 7, 3, False, False),
    _case(2, 9, 0, False, True),                   # ~5 s
    _case(2, 9, 0, False, False),                  # ~5 s
    # W = 3
    _case(3, 6, 0, False, True),
    _case(3, 6, 3, False, True),
    _case(3, 6, 3, False, False),
    _case(3, 8, 0, False, True),
    _case(3, 8, 0, False, False),
    _case(3, 8, 2, False, True),                   # ~3 s
    _case(3, 8, 2, False, False),                  # ~3 s
    _case(3, 10, 0, False, True, slow=True),        # ~70 s
    _case(3, 10, 0, False, False, slow=True),       # ~70 s
    # W = 0 trusses
    _case(0, 3, 0, True, True),
    _case(0, 5, 0, True, True),
    _case(0, 5, 0, True, False),
    _case(0, 5, 2, True, True),
    _case(0, 7, 0, True, True),
    _case(0, 7, 0, True, False),
    _case(0, 7, 2, True, True),                    # ~1 s
    _case(0, 7, 2, True, False),
    _case(0, 5, 0, False, True),
    _case(0, 7, 2, False, True),
]


def oracle(dof, links, v_max, rigid, frac):
    return brute_force_chains_once(links, dof, v_max=v_max, rigid_subchains=rigid, fractionated=frac)


@functools.lru_cache(maxsize=None)
def engine(dof, links, v_max, rigid, frac):
    return tuple(synth.type_synthesis(dof=dof, links=links, v=(0, v_max),
                                      rigid_subchains=rigid, fractionated=frac))


def _strip(t):
    t = list(t or ())
    while t and t[-1] == 0:
        t.pop()
    return tuple(t)


def engine_key(chain):
    """Engine Code -> oracle code key (trailing zeros stripped, None -> ())."""
    return _strip(chain.code.assortment), _strip(chain.code.composition)


def _joints(chain):
    return tuple(sorted(tuple(sorted(j)) for j in chain.joints))


@pytest.mark.parametrize("dof, links, v_max, rigid, frac", CASES)
def test_engine_agrees_with_bruteforce(dof, links, v_max, rigid, frac):
    expected = oracle(dof, links, v_max, rigid, frac)
    got = engine(dof, links, v_max, rigid, frac)

    assert len(got) == len(expected), (
        f"engine found {len(got)} chains, brute force {len(expected)}")

    assert dict(Counter(engine_key(c) for c in got)) == count_by_code(expected)

    index = ChainIndex(expected)
    hits = Counter()
    unknown = []
    for c in got:
        k = index.find(_joints(c), c.links)
        if k is None:
            unknown.append(_joints(c))
        else:
            hits[k] += 1
    assert not unknown, f"engine chains not in the brute-force set: {unknown[:5]}"
    dup = {expected[k].joints: m for k, m in hits.items() if m > 1}
    assert not dup, f"engine returned isomorphic duplicates: {dup}"
    missing = [expected[k].joints for k in range(len(expected)) if k not in hits]
    assert not missing, f"brute-force chains the engine missed: {missing[:5]}"


@pytest.mark.parametrize("dof, links, v_max, rigid, frac", CASES)
def test_engine_chains_satisfy_definitions(dof, links, v_max, rigid, frac):
    for c in engine(dof, links, v_max, rigid, frac):
        joints = _joints(c)
        assert c.links == links
        assert all(len(j) >= 2 and len(set(j)) == len(j) for j in joints), joints
        assert all(0 <= i < links for j in joints for i in j), joints
        assert mobility(joints, links) == dof, joints
        v = sum(len(j) - 2 for j in joints)
        assert 0 <= v <= v_max, joints
        degrees = Counter(i for j in joints for i in j)
        assert all(degrees[i] >= 2 for i in range(links)), joints
        assert is_connected(joints, links), joints
        assert subchain_ok(joints, links, rigid), joints
        if not frac:
            assert not is_fractionated(joints, links), joints
        assert engine_key(c) == code_key(joints, links), joints
        if hasattr(c.code, "v"):
            assert c.code.v == v, joints


OPEN = [(dof, links, n1, v, frac) for dof, links, n1, v in [(2, 7, (0, 2), 0), (3, 8, (0, 3), 0), (2, 7, (0, 3), 1)]
        for frac in (True, False)]
# a ternary link that keeps two strings once its single-joint link is pruned and holds the closed part
# together (without it one link would cut the rest in two): ~8 s
OPEN.append((2, 9, (1, 1), 0, False))
# one loop with arms: the closed part is a single loop through one branch link, not fractionated
OPEN += [(2, 5, (1, 1), 0, False), (3, 6, (1, 2), 0, False)]


@pytest.mark.parametrize("dof, links, n1, v_max, frac", OPEN, ids=str)
def test_open_chains_agree_with_bruteforce(dof, links, n1, v_max, frac):
    """Chains with single-joint links (robot arms, grippers): without fractionated chains the rule is
    decided on the closed part left when single-joint links are pruned again and again."""
    expected = brute_force_chains(links, dof, n1=n1, v_max=v_max, fractionated=frac)
    got = list(synth.type_synthesis(dof=dof, links=links, n1=n1, v=(0, v_max), fractionated=frac))
    index = ChainIndex(expected)
    assert sorted(index.find(_joints(c), c.links) for c in got) == list(range(len(expected)))
