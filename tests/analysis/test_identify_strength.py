"""identify's fields by hand: orbits, conventions, idle joints, a chain in pieces, a link in no joint,
an over-constrained chain, and the note of a chain its listing misses."""

from __future__ import annotations

import pytest

import synth
from synth import MalformedChain
from synth.exchange.identify import identify

WATT = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"


def test_the_watt_chain_by_hand():
    """Ternary links 0 and 1 joined, two binary paths 1-2-3-0 and 0-4-5-1 between them: swapping the
    paths and reversing them are its symmetries (order 4), orbits {0, 1} and {2, 3, 4, 5}."""
    found = identify(WATT)
    assert (found.symmetry, found.link_orbits) == (4, [[0, 1], [2, 3, 4, 5]])
    assert (found.fractionated, found.planar, found.idle_joints, found.subchains) == (False, True, [], "none")
    assert found.conventions == {"non_degenerate": True, "rigid_subchains": True, "not_fractionated": True,
                                 "planar": True, "no_idle_joint": True}


def test_a_rigid_sub_chain_breaks_one_convention_and_an_over_constrained_one_both():
    rigid = identify("0-1 1-2 2-0 0-3 3-4 4-5 5-1")  # the triangle 0, 1, 2: W(S) = 0
    assert rigid.conventions["non_degenerate"] is False and rigid.conventions["rigid_subchains"] is True
    # links 0, 1, 2, 3 with five pins: W(S) = 3·3 − 2·5 = −1
    over = identify("0-1 1-2 2-0 0-3 3-1 2-4 4-5 5-6 6-3")
    assert over.worst_mobility == -1 and over.conventions["rigid_subchains"] is False
    assert (over.listing, over.index) == (None, None)
    assert over.note == ("an over-constrained chain (a sub-chain with W(S) < 0, or redundant constraints) is in "
                         "no listing")


def test_a_chain_in_pieces_and_a_link_in_no_joint():
    pieces = identify("0-1 1-2 2-0 3-4 4-5 5-3")
    assert (pieces.connected, pieces.fractionated, pieces.idle_joints, pieces.listing) == (False, None, [], None)
    assert pieces.note == "a chain in pieces is in no listing" and pieces.conventions["no_idle_joint"] is False
    with pytest.raises(MalformedChain) as info:
        identify('{"links": 5, "joints": [[0, 1], [1, 2], [2, 3], [3, 0]]}')
    assert str(info.value).endswith("link 4 is in no joint: a chain's links are all jointed")


def test_a_chain_with_an_idle_joint_is_in_the_idle_joints_listing():
    """Three sliders on a four-bar's pair of ternary links: the chains only --idle-joints lists are
    found there, at their rows."""
    query = synth.ChainQuery(1, 6, prismatic=(3, 3), idle_joints=True)
    plain = {c.certificate for c in synth.type_synthesis(synth.ChainQuery(1, 6, prismatic=(3, 3)), workers=1)}
    rows = {}
    for c in synth.type_synthesis(query, workers=1):
        rows.setdefault(str(c.code), []).append(c)
    idle = [c for c in (c for cs in rows.values() for c in cs) if c.certificate not in plain]
    assert idle
    for chain in idle:
        found = identify(chain.compact())
        listed = list(synth.type_synthesis(synth.ChainQuery(1, code=str(chain.code), prismatic=3, idle_joints=True),
                                           workers=1))
        assert found.listing == f"mechsynth chains --code {chain.code} --dof 1 --prismatic 3 --idle-joints"
        assert found.idle_joints and found.conventions["no_idle_joint"] is False
        assert listed[found.index - 1].certificate == chain.certificate and found.listed == len(listed)


def test_a_chain_its_listing_misses_is_reported(monkeypatch):
    from synth.analysis import identify as module

    monkeypatch.setattr(module, "_chain_rows", lambda query: {})
    found = identify(WATT, index=True)
    assert (found.index, found.listed) == (None, 0)
    assert found.note == "not found in its listing: the engine misses this chain (please report it)"
