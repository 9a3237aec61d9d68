"""identify's fields by hand: orbits, conventions, idle joints, a chain in pieces, a link in no joint,
an over-constrained chain, and the note of a chain its listing misses."""

from __future__ import annotations

import math

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
    # in h = 4 a triangle is over-constrained (W(S) = 2 − 3 = −1), and W is the count: 7 − 3·2 = 1
    h4 = identify('{"links": 8, "h": 4, "joints": [[0, 1], [1, 2], [2, 0], [0, 3], [3, 4], [4, 5], [5, 6], [6, 7], '
                  '[7, 1]]}')
    assert (h4.dof, h4.dof_count, h4.worst_mobility, h4.worst_subchain) == (1, 1, -1, [0, 1, 2])
    assert (h4.listing, h4.index) == (None, None) and h4.note == over.note


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


def test_links_are_named_as_the_source_names_them():
    """A Watt chain written with words: names sort as text (b1 … b4 are links 0 … 3, t1 and t2 the
    ternary links 4 and 5); the frame, its orbit (the four binary links), the worst sub-chain and the
    idle joints are reported in the source's words, and the chain itself is kept."""
    text = "# frame b1\nt1 t2\nt2 b1\nb1 b2\nb2 t1\nt1 b3\nb3 b4\nb4 t2\n"
    found = identify(text)
    assert found.names == ["b1", "b2", "b3", "b4", "t1", "t2"]
    assert (found.frame, found.frame_orbit, found.inversion) == ("b1", ["b1", "b2", "b3", "b4"], ["Watt I"])
    assert found.link_orbits == [["b1", "b2", "b3", "b4"], ["t1", "t2"]]
    assert found.chain == synth.Chain.parse("4-5 5-0 0-1 1-4 4-2 2-3 3-5") and found.chain.links == 6
    assert found.id == identify(WATT).id
    # a crank and a second slider on the frame of a slider-crank: which joints do nothing, by name
    idle = identify("base crank R\ncrank rod R\nrod slider R\nslider base P\nbase guide P\nguide crank R\n")
    assert idle.names == ["base", "crank", "guide", "rod", "slider"]
    assert all(isinstance(x, str) for j in idle.idle_joints for x in j) and idle.idle_joints
    assert ["base", "slider"] in idle.idle_joints


def test_a_chain_object_with_links_in_no_joint_is_refused_by_the_first():
    """A Chain made in Python is not checked by a reader: identify refuses it itself, a lone link too."""
    with pytest.raises(MalformedChain) as info:
        identify(synth.Chain(6, [(0, 1), (1, 2), (2, 3), (3, 0)]))
    assert str(info.value) == "the chain: link 4 is in no joint: a chain's links are all jointed"
    with pytest.raises(MalformedChain) as info:
        identify(synth.Chain(1, []))
    assert str(info.value) == "the chain: link 0 is in no joint: a chain's links are all jointed"


def test_a_heterogeneous_chain_keeps_the_class_of_each_link():
    found = identify("0-2 0-4 0-5 1-2 1-6 1-9 2-3 3-4 3-5 6-7 7-8 8-9 | h5: 1 6 7 8 9")
    assert found.classes == [3, 5, 3, 3, 3, 3, 5, 5, 5, 5]
    assert found.to_dict()["classes"] == found.classes
    assert identify(WATT).classes is None and "classes" not in identify(WATT).to_dict()


def _estimate(chains, log10_chains, seconds, log10_seconds):
    from synth.synthesis.estimate import Estimate

    return Estimate(chains=chains, units=1.0, seconds=seconds, basis="8 to 10 links",
                    log10_chains=log10_chains, log10_seconds=log10_seconds)


def test_a_listing_too_long_to_run_unasked_is_said_in_numbers(monkeypatch):
    """Beyond floating point the listing's size is said from its logarithm: 2e+400 chains, 3.2e+387 years."""
    from synth.analysis import identify as module

    monkeypatch.setattr(module, "index_size", lambda chain, query, mechanisms=False: _estimate(
        math.inf, 400.3, math.inf, 395.0))
    monkeypatch.setattr(module, "_chain_rows", lambda query: pytest.fail("the listing was run"))
    found = identify(WATT)
    assert (found.index, found.listed) == (None, None)
    assert found.note == ("its place in the listing was not computed: it is found by listing the code, and listing "
                          "every 6-link chain like it is about 2e+400 chains, 3.2e+387 years on one core (8 to 10 "
                          "links); ask for its index to have it computed")
    found = identify(WATT, frame=2)
    assert "every 6-link chain like it is about 2e+400 mechanisms, 3.2e+387 years" in found.note
    monkeypatch.setattr(module, "index_size", lambda chain, query, mechanisms=False: _estimate(
        1.5e6, math.log10(1.5e6), 61.0, math.log10(61.0)))
    assert identify(WATT).note.endswith("about 1 500 000 chains, 61 s on one core (8 to 10 links); ask for its "
                                        "index to have it computed")
    monkeypatch.setattr(module, "index_size", lambda chain, query, mechanisms=False: _estimate(
        1.5e6, math.log10(1.5e6), 59.0, math.log10(59.0)))
    monkeypatch.setattr(module, "_chain_rows", lambda query: {})
    assert identify(WATT).note == "not found in its listing: the engine misses this chain (please report it)"


def test_a_listing_that_cannot_be_sized_is_not_run_unasked_from_the_sized_loops(monkeypatch):
    """No estimate: with 7 loops a planar chain's listing is not run unasked; in h = 2 (sized from 9
    loops) a chain of 7 loops is still looked up."""
    from synth.analysis import identify as module

    monkeypatch.setattr(module, "index_size", lambda chain, query, mechanisms=False: None)
    monkeypatch.setattr(module, "_chain_rows", lambda query: {})
    # a truss of 8 links and 14 pins in h = 2: K = 14 − 8 + 1 = 7 loops
    h2 = ('{"links": 8, "h": 2, "joints": [[0, 3], [0, 5], [0, 6], [0, 7], [1, 2], [1, 3], [1, 4], [1, 7], [2, 3], '
          '[2, 4], [2, 6], [3, 4], [5, 6], [5, 7]]}')
    found = identify(h2)
    assert (found.h, found.loops, found.dof, found.listed) == (2, 7, 0, 0)
    assert found.note == "not found in its listing: the engine misses this chain (please report it)"
    # a planar chain of 7 loops (one DOF: 16 links, 22 pins, a ring with six chords)
    ring = [(i, (i + 1) % 16) for i in range(16)] + [(0, 3), (4, 7), (8, 11), (12, 15), (2, 9), (6, 13)]
    planar = identify(" ".join(f"{a}-{b}" for a, b in ring))
    assert (planar.h, planar.loops, planar.dof) == (3, 7, 1)
    assert planar.note == ("its place in the listing was not computed: the code has 7 loops and its listing cannot be "
                           "sized (ask for its index to have it computed)")


def test_a_truss_with_a_rigid_triangle_is_in_the_plain_truss_listing():
    """W = 0: 5 links, 6 pins (12 − 12); its triangle 0-1-2 is rigid, as every truss listing allows."""
    found = identify("0-1 1-2 2-0 0-3 3-4 4-1")
    listed = [c.certificate for c in synth.type_synthesis(synth.ChainQuery(0, code="32/0"), workers=1)]
    assert (found.dof, found.dof_count, found.code, found.listing) == (0, 0, "32/0", "mechsynth chains --code 32/0")
    assert (found.index, found.listed) == (listed.index(found.certificate) + 1, len(listed))


def test_kinds_count_and_pieces_are_reported_as_they_are():
    """The over-braced four-bar: W = 0 in fact, −3 by the count; kinds only where a joint is no pin."""
    braced = identify("0-1 1-2 2-3 3-0 0-2 1-3")  # (its code's listing would be asked for W = 0 and refused)
    assert (braced.dof, braced.dof_count, braced.kinds) == (0, -3, None) and "kinds" not in braced.to_dict()
    assert (braced.listing, braced.index) == (None, None)
    assert braced.note == ("an over-constrained chain (a sub-chain with W(S) < 0, or redundant constraints) is in "
                           "no listing")
    slider = identify("0-1 1=2 2-3 3-0")  # joints in order 0-1, 0-3, 1=2, 2-3
    assert slider.kinds == ["revolute", "revolute", "prismatic", "revolute"] and slider.to_dict()["kinds"] == slider.kinds
    assert identify("0-1 1-2 2-0 3-4 4-5 5-3").subchains == "not connected"


def test_an_open_chains_listing_is_sized_with_its_single_joint_links():
    """Two single-joint links on a 10-link chain of W = 3: the estimate is of the open chains (305 of them,
    counted here; 98 closed ones), from the exact counts of smaller open chains."""
    from synth.analysis.identify import index_size, listing_query

    chain = synth.Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1 2-6 6-7 7-3 0-8 1-9")
    assert (str(chain.code), chain.dof) == ("2|422/0", 3)
    size = index_size(chain, listing_query(chain, 3, None, False)[0])
    counted = synth.count_chains(3, 10, n1=(2, 2), v=(0, 0), workers=1)["count"]
    assert counted == 305 and size is not None and counted / 3 < size.chains < counted * 3
