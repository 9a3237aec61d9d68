"""entry_of and its helpers by hand: link names and their order, every refusal's sentence (the source,
the link or joint at fault), settings comments, motion spaces stated and given."""

from __future__ import annotations

import pytest

from synth import Chain, MalformedChain
from synth.exchange._entry import (check_distinct, entry_of, in_motion_space, is_kind_word, kind_of,
                                   motion_space_of, settings_of)

TRIANGLE = [(0, 1), (1, 2), (2, 0)]
FOUR_BAR = [(0, 1), (1, 2), (2, 3), (3, 0)]


def _refused(call) -> str:
    with pytest.raises(MalformedChain) as info:
        call()
    return str(info.value)


def test_names_are_ordered_by_number_where_all_are_numbers_else_as_text():
    numbers = entry_of([(10, 2), (2, -1), (-1, 10)], None, "s")
    assert numbers.names == ("-1", "2", "10") and numbers.chain == Chain.parse("0-1 0-2 1-2")
    words = entry_of([("b10", "b2"), ("b2", "a"), ("a", "b10")], None, "s")
    assert words.names == ("a", "b10", "b2")
    plain = entry_of([(2, 0), (1, 2), (0, 1)], None, "s", frame=2)
    assert (plain.names, plain.frame, plain.name(2), plain.source) == (None, 2, 2, "s")
    named = entry_of([("base", "crank"), ("crank", "rod"), ("rod", "base")], None, "s", frame="rod")
    assert (named.frame, named.name(named.frame), named.item.frame) == (2, "rod", 2)
    assert entry_of(TRIANGLE, None, "s").item == Chain.parse("0-1 1-2 2-0")


def test_kinds_and_motion_space_travel_with_the_joints():
    e = entry_of([("a", "b"), ("b", "c"), ("c", "d"), ("d", "a")], ["revolute", "prismatic", "revolute", "prismatic"],
                 "s", h="3")
    assert e.chain == Chain.parse("0-1 1=2 2-3 3=0") and (e.h, e.chain.h) == (3, 3)
    five = entry_of(TRIANGLE, None, "s", h="5")
    assert (five.h, five.chain.h) == (5, 5)
    assert entry_of(TRIANGLE, None, "s").h is None and entry_of(TRIANGLE, None, "s").chain.h == 3


@pytest.mark.parametrize("joints, kw, said", [
    ([], {}, "s: no joint: an empty joint list is not a chain"),
    ([(0,)], {}, "s: a joint on link 0 alone joins nothing: a joint joins two links or more"),
    ([(0, 1), (1, 1)], {}, "s: link 1 is joined to itself (joint 1-1): a joint joins different links"),
    (TRIANGLE, {"links": [0, 1, 2, 7]}, "s: link 7 is in no joint: a chain's links are all jointed"),
    (TRIANGLE, {"links": [0, 1, 2, 7, 8]}, "s: links 7, 8 are in no joint: a chain's links are all jointed"),
    (TRIANGLE, {"links": list(range(9))},
     "s: links 3, 4, 5, 6, 7, … are in no joint: a chain's links are all jointed"),
    (TRIANGLE, {"links": list(range(8))}, "s: links 3, 4, 5, 6, 7 are in no joint: a chain's links are all jointed"),
    (TRIANGLE, {"frame": 5}, "s: the frame 5 is not a link of the chain"),
    (TRIANGLE, {"frame": 0, "input_link": 9}, "s: the input link 9 is not a link of the mechanism"),
    (TRIANGLE, {"input_link": 1}, "s: the input link 1 is not a link of the mechanism (an input link needs a frame)"),
    (FOUR_BAR, {"frame": 0, "input_link": 2}, "s: input link 2 is not jointed to the fixed link 0"),
    (TRIANGLE, {"h": 7}, "s: the motion space h is a whole number 2 … 6 (3 planar and spherical), not 7"),
    ([("a", "b"), ("b", "c"), ("c", "a"), ("a", "b")], {},
     "s: joints 0-1 and 0-1 join the same links: two joints never join the same set of links (links numbered in "
     "the order a, b, c)"),
    ([(f"n{i}", f"n{i + 1}") for i in range(9)] + [("n9", "n0"), ("n0", "n1")], {},
     "s: joints 0-1 and 0-1 join the same links: two joints never join the same set of links (links numbered in "
     "the order n0, n1, n2, n3, n4, n5, n6, n7, …)"),
    ([(0, 1), (1, 2), (2, 0), (0, 1)], {}, "s: joints 0-1 and 0-1 join the same links: two joints never join the "
                                           "same set of links"),
])
def test_every_refusal_names_the_source_and_what_is_wrong(joints, kw, said):
    assert _refused(lambda: entry_of(joints, None, "s", **kw)) == said


def test_a_mechanism_read_with_its_input():
    e = entry_of([("base", "crank"), ("crank", "rod"), ("rod", "rocker"), ("rocker", "base")], None, "s",
                 frame="base", input_link="crank")
    assert (e.frame, e.input_link, e.names) == (0, 1, ("base", "crank", "rocker", "rod"))
    assert (e.item.frame, e.item.input_link) == (0, 1)


def test_settings_of_a_comment():
    assert settings_of("# frame 2; input 3 ,h=4") == {"frame": "2", "input": "3", "h": "4"}
    assert settings_of("# FRAME: base") == {"frame": "base"}
    assert settings_of("#h 5") == {"h": "5"}
    assert settings_of("# frame 2,h 4") == {"frame": "2", "h": "4"}  # one separator, then the next setting
    for other in ("# frame 2 frame 3", "#", "# framework 2", "# frame 2 and more", "# a slider-crank"):
        assert settings_of(other) is None, other


def test_kinds_motion_spaces_and_distinct_links():
    assert [kind_of(w, "x") for w in ("R", "pin", "-", "P", "slider", "=", "G", "gear", "~")] == (
        ["revolute"] * 3 + ["prismatic"] * 3 + ["mesh"] * 3)
    assert _refused(lambda: kind_of("wheel", "w")) == ("w: joint kind 'wheel' is not one of revolute, prismatic, mesh "
                                                       "(or R, P, G; -, =, ~)")
    assert is_kind_word("slider") and not is_kind_word("base")
    assert [motion_space_of(x, "x") for x in ("2", "6.00", " 3 ", 4)] == [2, 6, 3, 4]
    for bad in ("1", "7", True, "4.5", "h4", -3):
        assert _refused(lambda: motion_space_of(bad, "x")) == (
            f"x: the motion space h is a whole number 2 … 6 (3 planar and spherical), not {bad!r}")
    check_distinct([(0, 1), ("a", "b", "c")], "x")  # no error
    assert _refused(lambda: check_distinct([(0, 1), (2, "2")], "x")) == (
        "x: link 2 is joined to itself (joint 2-2): a joint joins different links")
    assert _refused(lambda: check_distinct([("a", "b", "a")], "x")) == (
        "x: link a is joined to itself (joint a-b-a): a joint joins different links")
    assert _refused(lambda: check_distinct([("a", "b", "b")], "x")) == (
        "x: link b is joined to itself (joint a-b-b): a joint joins different links")


def test_a_motion_space_given_against_the_one_stated():
    e = entry_of(TRIANGLE, None, "y")
    assert in_motion_space(e, None) is e and in_motion_space(e, 3) is e
    moved = in_motion_space(e, 5)
    assert (moved.chain.h, moved.h, moved.chain.joints) == (5, 5, e.chain.joints)
    four = entry_of(TRIANGLE, None, "y", h=4)
    assert in_motion_space(four, 4) is four
    assert _refused(lambda: in_motion_space(four, 5, "--space")) == (
        "y states motion space h = 4, and --space 5 was given: leave out --space (the chain's own h is used) or "
        "give --space 4")
    assert _refused(lambda: in_motion_space(entry_of(FOUR_BAR, ["prismatic"] * 4, "y"), 2)) == (
        "y: prismatic pairs and gear meshes are planar (h = 3), not in motion space h = 2")
    from synth.exchange import read

    (het,) = read("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5")
    assert _refused(lambda: in_motion_space(het, 4)) == (
        f"{het.source} names its loop classes (its other links are of class 3): --h 4 contradicts them")
