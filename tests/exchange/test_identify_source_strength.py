"""identify of a source: one chain or each of several, the frame named as the source names links
(an input link that came with the source's own frame goes with it), the motion space given."""

from __future__ import annotations

import pytest

from synth import Chain, InvalidOption
from synth.exchange import text_of
from synth.exchange.identify import identify, identify_all

TWO = text_of([Chain.parse("0-1 1-2 2-0"), Chain.parse("0-1 1-2 2-3 3-0")], "json")


def test_a_source_of_two_chains_is_identified_chain_by_chain():
    found = identify_all(TWO)
    assert [(f.code, f.loops, f.dof) for f in found] == [("3/0", 1, 0), ("4/0", 1, 1)]
    with pytest.raises(InvalidOption) as info:
        identify(TWO)
    assert str(info.value) == "the source holds 2 chains: identify_all identifies each"
    with pytest.raises(InvalidOption) as info:
        identify_all(TWO, frame=0)
    assert str(info.value) == "a frame names one link of one chain, and the source holds 2 chains"


def test_the_frame_is_a_link_as_the_source_names_it():
    four_bar = "base crank\ncrank rod\nrod rocker\nrocker base\n"
    found = identify(four_bar, frame="rod")
    assert (found.frame, found.names, found.inversion) == ("rod", ["base", "crank", "rocker", "rod"],
                                                           ["four-bar linkage"])
    with pytest.raises(InvalidOption) as info:
        identify(four_bar, frame="slider")
    assert str(info.value) == "the frame slider is not a link of the chain (base … rod)"
    with pytest.raises(InvalidOption) as info:
        identify("0-1 1-2 2-3 3-0", frame=7)
    assert str(info.value) == "the frame 7 is not a link of the chain (0 … 3)"
    assert identify("0-1 1-2 2-3 3-0", frame=3).frame == 3  # numbered links: the number is the name


def test_a_frame_given_replaces_the_sources_frame_and_its_input():
    text = "# frame 0, input 1\n0 1\n1 2\n2 3\n3 0\n"
    own = identify(text)
    assert (own.frame, own.input_link, own.mechanism_listing) == (0, 1, "mechsynth mechanisms --code 4/0 --input-link")
    moved = identify(text, frame=2)
    assert (moved.frame, moved.input_link, moved.mechanism_listing) == (2, None, "mechsynth mechanisms --code 4/0")
    assert "input_link" not in moved.to_dict()


def test_the_motion_space_given_is_the_chains():
    """A ring of four in h = 4: W = 4·3 − 3·4 = 0; the plane's W = 1."""
    found = identify("0-1 1-2 2-3 3-0", h=4)
    assert (found.h, found.dof) == (4, 0)
    assert identify("0-1 1-2 2-3 3-0").dof == 1


def test_the_format_given_is_the_one_read():
    """A joint list read as GraphML is no GraphML; an adjacency matrix written with spaces is the matrix it is,
    asked or not (its rows repeat a number, which no edge-list line can)."""
    from synth import MalformedChain

    for call in (identify, identify_all):
        with pytest.raises(MalformedChain) as info:
            call("0-1 1-2 2-3 3-0", fmt="graphml")
        assert str(info.value).startswith("the chain given: not a GraphML document networkx can read (")
    matrix = "0 1 0 1\n1 0 1 0\n0 1 0 1\n1 0 1 0\n"  # the four-bar's adjacency
    assert identify(matrix).code == "4/0"
    assert identify(matrix, fmt="adjacency").code == "4/0"
    assert [f.code for f in identify_all(matrix, fmt="adjacency")] == ["4/0"]
