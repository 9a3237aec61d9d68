"""The source's planetary layout by hand: the trains and their lever analogues, Assur groups split link by link,
the rows of a determinate, an under- and an over-constrained train, every refusal's sentence."""

from __future__ import annotations

import pytest

from synth.errors import InvalidOption
from synth.gears.planetary import assur_groups, lever_analogue, planetary_row, planetary_rows, planetary_train
from synth.structure.chain import Chain


@pytest.mark.parametrize("call,sentence", [
    (lambda: planetary_train(0), "a planetary train needs a whole number of satellites ≥ 1, not 0"),
    (lambda: planetary_train(True), "a planetary train needs a whole number of satellites ≥ 1, not True"),
    (lambda: planetary_train(1.5), "a planetary train needs a whole number of satellites ≥ 1, not 1.5"),
    (lambda: planetary_train(2, "stuck"), "the sun is floating or fixed, not 'stuck'"),
    (lambda: next(planetary_rows((0, 2))), "a planetary train needs at least one satellite, not 0"),
    (lambda: next(planetary_rows((3, 22), "fixed")),
     "3..22 satellites: at most 21, whose lever analogue has 24 non-binary links (the exact sub-chain test handles up to 24)"),
])
def test_refusals_in_full(call, sentence):
    with pytest.raises(InvalidOption) as refused:
        call()
    assert str(refused.value) == sentence


def test_the_trains_and_their_lever_analogues():
    """A fixed sun turns on the ring's axis, so its meshes' carrier cannot be read from the axes and is written;
    the lever analogue numbers a binary link per mesh after the train's links, in mesh order."""
    assert planetary_train(2, "fixed").compact() == "0-1 0-2 1-3 1-4 0~3i 0~4i 2~3@1 2~4@1"
    assert planetary_train(2).frame == 0 and planetary_train(2).internal == (True, True, False, False)
    assert lever_analogue(2).compact() == "0-1 0-5 0-6 1-3 1-4 2-7 2-8 3-5 3-7 4-6 4-8"
    assert lever_analogue(2, "fixed").compact() == "0-1 0-2 0-5 0-6 1-3 1-4 2-7 2-8 3-5 3-7 4-6 4-8"


def test_assur_groups_by_hand():
    """Four-bar, frame 0, crank 1: links 2 and 3 form a dyad, joined to the placed links by 0-3 and 1-2.  Watt's
    six-bar adds the dyad 4, 5 on links 2 and 0.  A five-bar driven by one crank has no group (W = 2); the
    triad of the 3-satellite train needs four links, more than ``largest = 2``."""
    four = assur_groups(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1)
    assert [(g.name, g.links, g.outer_joints) for g in four] == [("dyad", (2, 3), ((0, 3), (1, 2)))]
    six = assur_groups(Chain.parse("0-1 1-2 2-3 3-0 2-4 4-5 5-0"), 0, 1)
    assert [(g.name, g.links, g.outer_joints) for g in six] == [
        ("dyad", (2, 3), ((0, 3), (1, 2))), ("dyad", (4, 5), ((0, 5), (2, 4)))]
    assert assur_groups(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0, 1) == []
    assert assur_groups(lever_analogue(3), 0, 1, largest=2) == []
    assert assur_groups(lever_analogue(3), 0, 1, largest=3) == []  # groups have an even number of links
    triad = assur_groups(lever_analogue(3), 0, 1)[-1]
    assert (triad.name, triad.links, triad.outer_joints) == ("triad", (2, 9, 10, 11), ((3, 9), (4, 10), (5, 11)))


def test_a_group_of_another_shape_is_named_by_its_size():
    """Frame 0, crank 1 pinned to link 2 of a loop 2-3-4-5, whose link 4 is pinned to the frame: the four links
    and their six pins (four inside, two to placed links) leave 3·4 − 2·6 = 0 and no pair of them does (each
    pair holds at most two pins: 3·2 − 2·2 = 2), so they are one group of four links with two outer joints."""
    chain = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-2 4-0")
    assert chain.dof == 1
    assert [(g.name, g.links, g.outer_joints) for g in assur_groups(chain, 0, 1)] == [
        ("4-link group", (2, 3, 4, 5), ((0, 4), (1, 2)))]


def test_rows_of_three_trains():
    """One fixed-sun satellite: lever analogue 42/0, W = 1, two dyads (planet with its ring lever, then sun with
    its lever).  Two floating-sun satellites: W = 2, D = +1, not determinate.  Four: W = 0, D = −1, any of its
    eight meshes redundant."""
    one = planetary_row(1, "fixed")
    assert (one.code, one.links, one.dof, one.loops, one.defect, one.determinate) == ("42/0", 6, 1, 2, 0, True)
    assert [(g.name, g.links, g.outer_joints) for g in one.assur_groups] == [
        ("dyad", (3, 4), ((0, 4), (1, 3))), ("dyad", (2, 5), ((0, 2), (3, 5)))]
    assert one.train == "0-1 0-2 0~3 1-3 2~3" and one.sun == "fixed" and one.satellites == 1
    two = planetary_row(2)
    assert (two.code, two.dof, two.defect, two.determinate, two.assur_groups, two.redundant_joints) == (
        "540/0", 2, 1, False, (), None)
    four = planetary_row(4)
    assert (four.dof, four.defect, four.determinate, four.subchains) == (0, -1, False, "none")
    assert four.redundant_joints == ([0, 3], [0, 4], [0, 5], [0, 6], [2, 3], [2, 4], [2, 5], [2, 6])
    assert [r.satellites for r in planetary_rows((2, 4))] == [2, 3, 4]
