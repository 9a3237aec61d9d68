"""A chain query read and checked once: its ranges, requirements, cranks and cylinders, every refusal's
sentence, the values it derives (loops, wedge-loop counts, the defaults), and its plain form read back."""

from __future__ import annotations

import pytest

from synth import Code
from synth.errors import ImpossibleParameters, InvalidOption, QueryTooLarge
from synth.structure.query import (ChainQuery, parse_cranks, parse_cylinders, parse_range,
                                   parse_requirements)
from tests.refusals import refused


@pytest.mark.parametrize("text, minimum, expected", [
    ("0..4", 0, (0, 4)), (" 2 .. ", 0, (2, None)), ("..3", 1, (1, 3)), ("2..2", 0, (2, 2)), (3, 0, (3, 3)),
    ([1, 2], 0, (1, 2)), ((0, None), 0, (0, None)), (None, 0, None), ("7", 7, (7, 7)),
])
def test_ranges(text, minimum, expected):
    assert parse_range(text, "v", minimum=minimum) == expected


@pytest.mark.parametrize("text, minimum, error, words", [
    (True, 0, InvalidOption, "v must be a whole number or a range A..B, not True"),
    ("a..b", 0, InvalidOption, "v must be a whole number or a range A..B, not 'a..b'"),
    ("1.5", 0, InvalidOption, "v must be a whole number or a range A..B, not '1.5'"),
    ((1, 2, 3), 0, InvalidOption, "v must be a whole number or a range A..B, not (1, 2, 3)"),
    (1.5, 0, InvalidOption, "v must be a whole number or a range A..B, not 1.5"),
    ((1.0, 2), 0, InvalidOption, "v must be a whole number or a range A..B, not (1.0, 2)"),
    ((True, 2), 0, InvalidOption, "v must be a whole number or a range A..B, not (True, 2)"),
    ((1, False), 0, InvalidOption, "v must be a whole number or a range A..B, not (1, False)"),
    ((None, 2), 0, ImpossibleParameters, "v must not be below 0 (got (None, 2))"),
    (-1, 0, ImpossibleParameters, "v must not be below 0 (got -1)"),
    ((0, -1), 0, ImpossibleParameters, "v must not be below 0 (got (0, -1))"),
    ("0", 1, ImpossibleParameters, "v must not be below 1 (got '0')"),
    ("3..1", 0, InvalidOption, "the range for v is empty: 3..1"),
])
def test_bad_ranges(text, minimum, error, words):
    with pytest.raises(error) as caught:
        parse_range(text, "v", minimum=minimum)
    assert str(caught.value) == words


def test_requirements():
    assert parse_requirements(["5=1..", " 3 = 0..2 "]) == {3: (0, 2), 5: (1, None)}
    assert list(parse_requirements(["5=1", "3=0"])) == [3, 5]  # sorted by the number of joints
    assert parse_requirements([(5, "1..")]) == parse_requirements({5: "1.."}) == {5: (1, None)}
    assert parse_requirements(["5=1", "5=1"]) == {5: (1, 1)} and parse_requirements(["1=1"]) == {1: (1, 1)}
    assert parse_requirements(None) == {} == parse_requirements([])
    for items, error, words in [
        ({"x": 1}, InvalidOption, "a requirement names the number of joints on a link, not 'x'"),
        (["0=1"], ImpossibleParameters, "a link carries at least one joint; requirement on n0 is impossible"),
        (["5=1", "5=2"], ImpossibleParameters, "conflicting requirements on n5: (1, 1) and (2, 2)"),
        (["5"], InvalidOption, "a requirement is written I=N, I=A..B or I=A.. (e.g. 5=1..), not '5'"),
        ([5], InvalidOption, "a requirement is written I=N, I=A..B or I=A.. (e.g. 5=1..), not 5"),
        (["5=-1"], ImpossibleParameters, "n5 must not be below 0 (got '-1')"),
        (["5=1=2"], InvalidOption, "n5 must be a whole number or a range A..B, not '1=2'"),
    ]:
        with pytest.raises(error) as caught:
            parse_requirements(items)
        assert str(caught.value) == words


def test_cylinders_and_cranks():
    assert parse_cylinders("guide=0,, slider=1..2") == (("guide", (0, 0)), ("slider", (1, 2)))
    assert parse_cylinders([("floating", 1)]) == (("floating", (1, 1)),)
    assert parse_cylinders({"floating": 1, "swinging": "2.."}) == (("swinging", (2, None)), ("floating", (1, 1)))
    assert parse_cylinders(None) == () == parse_cylinders("")
    with pytest.raises(InvalidOption) as caught:
        parse_cylinders(["piston=1"])
    assert str(caught.value) == "a prismatic pair of a mechanism is a guide, swinging, floating or slider, not 'piston'"
    with pytest.raises(InvalidOption) as caught:
        parse_cylinders(["guide"])
    assert str(caught.value) == ("a cylinder requirement is written KIND=N or KIND=A..B with KIND guide, swinging or "
                                 "floating, not 'guide'")
    for items, words in [("guide=1=2", "guide cylinders must be a whole number or a range A..B, not '1=2'"),
                         (["ab"], "a cylinder requirement is written KIND=N or KIND=A..B with KIND guide, swinging "
                                  "or floating, not 'ab'")]:
        with pytest.raises(InvalidOption) as caught:
            parse_cylinders(items)
        assert str(caught.value) == words
    with pytest.raises(ImpossibleParameters, match="^guide cylinders must not be below 0"):
        parse_cylinders("guide=-1")
    assert parse_cranks([(5, 5)]) == ((5, 5),) and parse_cranks(None) == ()
    with pytest.raises(InvalidOption, match="not '5=5=1'$"):
        parse_cranks(["5=5=1"])


@pytest.mark.parametrize("make, error, words", [
    (lambda: ChainQuery(-1, 8), ImpossibleParameters, "the degree of freedom W must be 0 or more, not -1"),
    (lambda: ChainQuery(1.0, 8), InvalidOption, "the degree of freedom W must be a whole number, not 1.0"),
    (lambda: ChainQuery(True, 8), InvalidOption, "the degree of freedom W must be a whole number, not True"),
    (lambda: ChainQuery(1, 8, h=7), ImpossibleParameters,
     "the motion space h of a loop is 2 … 6 (6: general spatial loop), not 7"),
    (lambda: ChainQuery(1, 8, h=1), ImpossibleParameters,
     "the motion space h of a loop is 2 … 6 (6: general spatial loop), not 1"),
    (lambda: ChainQuery(1, 8, h=True), ImpossibleParameters,
     "the motion space h of a loop is 2 … 6 (6: general spatial loop), not True"),
    (lambda: ChainQuery(1, 8, h=3.0), ImpossibleParameters,
     "the motion space h of a loop is 2 … 6 (6: general spatial loop), not 3.0"),
    (lambda: ChainQuery(1, code=5), InvalidOption, "a code is a Code or its text, e.g. '6301/0', not 5"),
    (lambda: ChainQuery(1, code=Code((1001,), 0)), QueryTooLarge,
     "the code given has 1001 links; chains are built here up to 1000 links"),
    (lambda: ChainQuery(1), InvalidOption, "give the number of links (or a code)"),
    (lambda: ChainQuery(1, 0), ImpossibleParameters, "the number of links must be 1 or more, not 0"),
    (lambda: ChainQuery(1, 8, code="7201/1"), ImpossibleParameters, "code 7201/1 has 10 links, not 8"),
    (lambda: ChainQuery(1, 8, fractionated=1), InvalidOption, "fractionated is true or false, not 1"),
    (lambda: ChainQuery(1, 8, planar_only=None), InvalidOption, "planar_only is true or false, not None"),
    (lambda: ChainQuery(1, 8, idle_joints="no"), InvalidOption, "idle_joints is true or false, not 'no'"),
    (lambda: ChainQuery(1, 8, rigid_subchains=0), InvalidOption, "rigid_subchains is true, false or None, not 0"),
    (lambda: ChainQuery(1, 8, max_multiplicity=1), ImpossibleParameters,
     "the largest multiplicity (links on one joint) must be 2 or more, not 1"),
    (lambda: ChainQuery(1, 11, h=4, prismatic=1), InvalidOption,
     "prismatic pairs are assigned in planar chains (h = 3), not in motion space h = 4"),
    (lambda: ChainQuery(1, 8, idle_joints=True), InvalidOption,
     "idle joints go with prismatic pairs (an all-revolute chain has no idle joint)"),
    (lambda: ChainQuery(1, 8, cylinders="guide=1"), InvalidOption,
     "cylinders go with prismatic pairs: give the number of prismatic pairs too"),
    # W = 1, 8 links: at most (8 − 1 − 1 + k)/2 + 7 joints over the wedge-loop counts k = 0, 2, 4, 6
    (lambda: ChainQuery(1, 8, prismatic=14), ImpossibleParameters,
     "14 prismatic pairs do not fit: a chain with W = 1 and 8 links has at most 13 joints"),
    # a tree of 2 links moves with W = 1 at most, and no loop (wedge loops included) adds mobility
    (lambda: ChainQuery(4, 2, prismatic=0), ImpossibleParameters,
     "no chain of 2 links has W = 4: an open chain of n links moves with W = n − 1 = 1, and every loop, "
     "wedge loops of prismatic pairs included, takes mobility away"),
    (lambda: ChainQuery(3, 3, prismatic="0.."), ImpossibleParameters,
     "no chain of 3 links has W = 3: an open chain of n links moves with W = n − 1 = 2, and every loop, "
     "wedge loops of prismatic pairs included, takes mobility away"),
    # 7201/1: 12 joints, one of them double
    (lambda: ChainQuery(1, code="7201/1", prismatic=12), ImpossibleParameters,
     "code 7201/1 has 11 simple joint(s) and prismatic pairs go on simple joints: 12 do not fit"),
    # 620/2 with v = 2 of unknown composition: 8 joints, at least one multiple
    (lambda: ChainQuery(1, code="620/2", prismatic=8), ImpossibleParameters,
     "code 620/2 has 7 simple joint(s) and prismatic pairs go on simple joints: 8 do not fit"),
    # 620/0-1: one triple joint of 8 joints
    (lambda: ChainQuery(1, code="620/0-1", prismatic=8), ImpossibleParameters,
     "code 620/0-1 has 7 simple joint(s) and prismatic pairs go on simple joints: 8 do not fit"),
    # two double joints given: 8 joints, 6 simple
    (lambda: ChainQuery(1, code=Code((6, 2), 2, (2,)), prismatic=7), ImpossibleParameters,
     "code 620/2 has 6 simple joint(s) and prismatic pairs go on simple joints: 7 do not fit"),
    # three binary links on two triple joints
    (lambda: ChainQuery(0, code=Code((3,), 2, (2,)), prismatic=1), ImpossibleParameters,
     "code 30/2 has no simple joint: prismatic pairs go on simple joints (a multiple joint is a pin)"),
    (lambda: ChainQuery(1, 8, prismatic="x"), InvalidOption,
     "the number of prismatic pairs must be a whole number or a range A..B, not 'x'"),
    (lambda: ChainQuery(2, code="7201/1"), ImpossibleParameters,
     "code 7201/1 gives W = 1 with h = 3, not the requested W = 2"),
    (lambda: ChainQuery(6, code="7201/1", prismatic=0), ImpossibleParameters,
     "code 7201/1 gives W = 1 with revolute pairs; its wedge loops can raise that to at most 5, not to the "
     "requested W = 6"),
    (lambda: ChainQuery(0, code="7201/1", prismatic=0), ImpossibleParameters,
     "code 7201/1 gives W = 1 with revolute pairs; its wedge loops can raise that to at most 5, not to the "
     "requested W = 0"),
    (lambda: ChainQuery(1, code="7201/1", v="2.."), ImpossibleParameters,
     "code 7201/1 has v = 1, outside the requested v = 2.."),
    (lambda: ChainQuery(1, code="7201/1", v="0..0"), ImpossibleParameters,
     "code 7201/1 has v = 1, outside the requested v = 0"),
    (lambda: ChainQuery(4, code="2|5/2", n1="3.."), ImpossibleParameters,
     "code 2|5/2 has n1 = 2, not the requested n1 = 3.."),
    (lambda: ChainQuery(4, code="2|5/2", n1="0..1"), ImpossibleParameters,
     "code 2|5/2 has n1 = 2, not the requested n1 = 0..1"),
    (lambda: ChainQuery(1, code="7201/1", require=["5=2.."]), ImpossibleParameters,
     "code 7201/1 has 1 link(s) with 5 joints, but the requirement asks for n5 = 2.."),
    (lambda: ChainQuery(1, code="7201/1", require=["3=0..1"]), ImpossibleParameters,
     "code 7201/1 has 2 link(s) with 3 joints, but the requirement asks for n3 = 0..1"),
    (lambda: ChainQuery(1, 3), ImpossibleParameters,
     "no whole number of loops fits: n = W + 1 + (h − 1)·K needs n − W − 1 = 1 to be a non-negative multiple of "
     "h − 1 = 2 (W=1, n=3, h=3)"),
    (lambda: ChainQuery(2, 2), ImpossibleParameters,
     "no whole number of loops fits: n = W + 1 + (h − 1)·K needs n − W − 1 = -1 to be a non-negative multiple of "
     "h − 1 = 2 (W=2, n=2, h=3)"),
])
def test_refusals(make, error, words):
    assert refused(error, make) == words


def test_accepted_at_the_limits():
    assert ChainQuery(1, code="7201/1", prismatic=11).prismatic == (11, 11)
    assert ChainQuery(1, code="620/2", prismatic=7).prismatic == (7, 7)
    assert ChainQuery(1, code="620/0-1", prismatic=7).prismatic == (7, 7)
    assert ChainQuery(1, code=Code((6, 2), 2, (2,)), prismatic=6).prismatic == (6, 6)
    assert ChainQuery(1, 8, prismatic=13).prismatic == (13, 13)
    assert ChainQuery(5, code="7201/1", prismatic=0).dof == 5 and ChainQuery(1, code="7201/1", prismatic=0).dof == 1
    assert ChainQuery(1, code="7201/1", v="1..").v == (1, None) and ChainQuery(1, code="7201/1", v=1).v == (1, 1)
    assert ChainQuery(4, code="2|5/2", n1="2..").n1 == (2, None)
    assert ChainQuery(1, code="7201/1", require=["3=2", "5=1.."]).require == ((3, (2, 2)), (5, (1, None)))
    assert ChainQuery(1, 8, max_multiplicity=2).max_multiplicity == 2
    assert ChainQuery(1, 7, h=6).loops == 1 and ChainQuery(1, 3, h=2).loops == 1
    assert ChainQuery(997, code=Code((1000,), 0)).links == 1000  # 1000 binary links in one loop: W = 997
    assert ChainQuery.of(code=Code((1000,), 0)).links == 1000


def test_of_the_api_arguments():
    q = ChainQuery(1, 8)
    assert ChainQuery.of(q) is q and ChainQuery.of(dof=1, links=8) == q == ChainQuery.of(1, 8)
    assert ChainQuery.of(code="7201/1").dof == 1 and ChainQuery.of(code=Code.parse("7201/1")).links == 10
    assert ChainQuery.of(code="2/0", h=2).dof == 0
    assert ChainQuery.of(1, loops=3).links == 8 and ChainQuery.of(dof=2, loops=2, h=4).links == 9
    assert ChainQuery.of(1, loops=0).links == 2
    for call, error, words in [
        (lambda: ChainQuery.of(q, links=8), InvalidOption, "give a query or its options, not both"),
        (lambda: ChainQuery.of(q, v=1), InvalidOption, "give a query or its options, not both"),
        (lambda: ChainQuery.of(1, dof=1), InvalidOption, "W is given twice (as the first argument and as dof)"),
        (lambda: ChainQuery.of(1, 8, foo=1, bar=2), InvalidOption, "unknown option(s) for a chain query: bar, foo"),
        (lambda: ChainQuery.of(), InvalidOption, "give the degree of freedom W (and the links), or a code"),
        (lambda: ChainQuery.of(code=" 2/0 "), ImpossibleParameters,
         "code 2/0 gives W = -1 in motion space h = 3: its links are over-constrained, and a chain has W ≥ 0"),
        (lambda: ChainQuery.of(code="7201/1", h=4), ImpossibleParameters,
         "code 7201/1 gives W = -3 in motion space h = 4: its links are over-constrained, and a chain has W ≥ 0"),
        (lambda: ChainQuery.of(code=" 1001.0/0 "), QueryTooLarge,
         "code 1001.0/0 has 1001 links; chains are built here up to 1000 links"),
        (lambda: ChainQuery.of(code=Code((1001,), 0)), QueryTooLarge,
         "code 1001.0/0 has 1001 links; chains are built here up to 1000 links"),
        (lambda: ChainQuery.of(1, 8, loops=3), InvalidOption, "give the links or the loops, not both"),
        (lambda: ChainQuery.of(1, loops=-1), ImpossibleParameters, "the number of loops K must be 0 or more, not -1"),
        (lambda: ChainQuery.of(dof=-1, loops=2), ImpossibleParameters,
         "the degree of freedom W must be 0 or more, not -1"),
    ]:
        with pytest.raises(error) as caught:
            call()
        assert str(caught.value) == words


def test_derived_values():
    assert [ChainQuery(1, n).loops for n in (2, 4, 6, 8)] == [0, 1, 2, 3]
    assert ChainQuery(1, 11, h=4).loops == 3 and ChainQuery(1, 18, h=5).loops == 4
    assert (ChainQuery(0, 5).rigid, ChainQuery(1, 4).rigid) == (True, False)
    assert (ChainQuery(1, 4, rigid_subchains=True).rigid, ChainQuery(0, 5, rigid_subchains=False).rigid) == (True, False)
    # wedge loops k: the skeleton (W − k, K = (n − 1 − W + k)/2) exists, k ≤ K, and k loops have ≥ k + 2 sliders
    assert [ChainQuery(1, n, prismatic="0..").skeleton_slacks() for n in (4, 5, 6, 7, 8)] == [
        [0, 2], [1, 3], [0, 2, 4], [1, 3, 5], [0, 2, 4, 6]]
    assert ChainQuery(1, 8, prismatic="0..3").skeleton_slacks() == [0]
    assert ChainQuery(1, 8, prismatic="0..4").skeleton_slacks() == [0, 2]
    assert ChainQuery(1, 8, prismatic="0..5").skeleton_slacks() == [0, 2]
    assert ChainQuery(1, code="4000/0", prismatic="0..").skeleton_slacks() == [0]
    assert ChainQuery(2, code="4000/0", prismatic="0..").skeleton_slacks() == [1]
    assert ChainQuery(1, 8).skeleton_slacks() == [0]
    assert ChainQuery(0, 3, prismatic="0..").skeleton_slacks() == [0, 2]  # k up to n − 1 − W
    assert ChainQuery(1, 2, prismatic="0..").skeleton_slacks() == [0]     # no loop: K = 0
    assert ChainQuery(3, code="4600/0", prismatic="0..").skeleton_slacks() == [2]  # not k = 0: K = 3, not 4


def test_cylinders_only_when_they_are_every_prismatic_pair():
    q = lambda p, c: ChainQuery(3, code="8310/1", prismatic=p, cylinders=c).cylinders_only  # noqa: E731
    assert q(3, "floating=1,swinging=2") and q("1..3", "floating=3") and q(3, "floating=4")
    assert not q(3, "floating=1,swinging=1") and not q("1..", "floating=3") and not q(0, "floating=0")
    assert not q(3, "guide=3") and not q(3, "slider=3") and not ChainQuery(1, 8).cylinders_only


@pytest.mark.parametrize("query", [
    ChainQuery(1, 8), ChainQuery(0, 5), ChainQuery(0, 5, rigid_subchains=False), ChainQuery(3, 10, fractionated=False),
    ChainQuery(1, code="7201/1", v="0..2", n1=0, require=["5=1..", "3=2"], cranks=["5=2"], max_multiplicity=3,
               rigid_subchains=False, fractionated=False, planar_only=True),
    ChainQuery(3, code="8310/1", prismatic="1..3", idle_joints=True, cylinders="floating=1,guide=0.."),
    ChainQuery(1, 11, h=4, rigid_subchains=True), ChainQuery(1, 8, prismatic=0), ChainQuery(3, 8, n1="0..2"),
])
def test_the_plain_form_reads_back_as_the_same_query(query):
    """to_dict names the query in logs, checkpoints and the estimate's memo of calibrations: read back it is
    the same query, so two different queries never share a plain form."""
    assert ChainQuery.of(**query.to_dict()) == query


def test_the_plain_form():
    assert ChainQuery(1, 8, v="0..2").to_dict() == {"dof": 1, "links": 8, "v": "0..2"}
    assert ChainQuery(1, code="7201/1", n1=0, require=["5=1..", "3=2"], cranks=["5=2"], max_multiplicity=3,
                      planar_only=True).to_dict() == {
        "dof": 1, "code": "7201/1", "n1": "0", "require": ["3=2", "5=1.."], "cranks": ["5=2"],
        "max_multiplicity": 3, "planar_only": True}
    assert ChainQuery(3, code="8310/1", prismatic="1..3", idle_joints=True,
                      cylinders="floating=1,guide=0..").to_dict() == {
        "dof": 3, "code": "8310/1", "prismatic": "1..3", "idle_joints": True, "cylinders": ["guide=0..", "floating=1"]}
    assert ChainQuery(1, 11, h=4).to_dict() == {"dof": 1, "links": 11, "h": 4}
    assert ChainQuery(3, 10, fractionated=False).to_dict() == {"dof": 3, "links": 10, "fractionated": False}
    assert ChainQuery(1, 8).with_options(v="0..2") == ChainQuery(1, 8, v=(0, 2))
    with pytest.raises(ImpossibleParameters, match="n − W − 1 = 7"):
        ChainQuery(1, 8).with_options(links=9)
