"""analyze_chain by hand: the counts of each field, every kind of advice and its sentence, the
refusals.  W by count is 3(n − 1) − 2·(pins and sliders) − (meshes) in the plane, a loop of sliders
only giving one freedom back; the true W of each chain below is argued in its comment."""

from __future__ import annotations

import pytest

from synth import Chain
from synth.analysis.chains import analyze_chain, mobility_of
from synth.analysis.codes import LOWER_W, RAISE_W
from synth.errors import InvalidOption, MalformedChain, QueryTooLarge
from synth.gears.planetary import planetary_train
from synth.structure.query import MAX_CODE_LINKS

NO_DEFECT = "no defect: no rigid or over-constrained sub-chain, no idle joint"


def test_the_four_bar_field_by_field():
    a = analyze_chain("0-1 1-2 2-3 3-0")
    assert (a.code, a.h, a.links, a.joints, a.dof, a.dof_count, a.redundant) == ("4/0", 3, 4, 4, 1, 1, 0)
    assert (a.loops, a.loops_2, a.loops_3, a.complexity, a.v, a.prismatic, a.meshes) == (1, 0, 1, 0, 0, 0, 0)
    assert (a.lever_analogue, a.standard_code, a.connected, a.fractionated, a.planar) == (None, True, True, False, True)
    # its smallest proper sub-chains are two jointed links: 3·1 − 2·1 = 1
    assert (a.subchain_defect, a.worst_subchain, a.worst_subchain_mobility, a.idle_joints) == ("none", [0, 1], 1, [])
    assert (a.advice, a.required_dof, a.defect, a.redundant_joints, a.loop_classes) == (NO_DEFECT, None, None, None,
                                                                                         None)
    assert a.certificate == Chain.parse("3-2 2-1 1-0 0-3").certificate


@pytest.mark.parametrize("dof, defect, advice", [
    (2, -1, "the chain has W = 1, not 2: " + RAISE_W.format(k=1)),
    (3, -2, "the chain has W = 1, not 3: " + RAISE_W.format(k=2)),
    (0, 1, "the chain has W = 1, not 0: " + LOWER_W.format(k=1)),
    (1, 0, NO_DEFECT),
])
def test_a_required_mobility_gives_the_defect_and_the_edit(dof, defect, advice):
    a = analyze_chain("0-1 1-2 2-3 3-0", dof=dof)
    assert (a.required_dof, a.defect, a.advice) == (dof, defect, advice)


def test_wedge_loops_and_sliders_that_lock_a_pin():
    # three sliders in a triangle: a wedge loop (h = 2): W = (3 − 1) − 1
    wedge = analyze_chain("0=1 1=2 2=0")
    assert (wedge.dof, wedge.dof_count, wedge.loops_2, wedge.loops_3, wedge.prismatic, wedge.code) == (
        1, 1, 1, 0, 3, "3/0 P3")
    four = analyze_chain("0=1 1=2 2=3 3=0")  # four sliders: W = 3 − 1
    assert (four.dof, four.loops_2, four.loops_3) == (2, 1, 0)
    # three sliders and a pin in one loop: the sliders keep every link's angle, so the pin never turns
    locked = analyze_chain("0-1 1=2 2=3 3=0", dof=1)
    assert (locked.dof, locked.loops_2, locked.loops_3, locked.idle_joints) == (1, 0, 1, [[0, 1]])
    assert locked.advice == ("joint(s) 0-1 never move: prismatic pairs lock the rotation of their links; make one of "
                             "those pairs revolute")


def test_a_rigid_sub_chain_a_fractionated_chain_and_idle_pins():
    # the triangle 0-1-2 (W(S) = 3·2 − 2·3 = 0) in a six-bar: one binary link into its joints mends it
    six = analyze_chain("0-1 1-2 2-0 0-3 3-4 4-5 5-1")
    assert (six.dof, six.subchain_defect, six.worst_subchain, six.worst_subchain_mobility) == (
        1, "rigid sub-chain", [0, 1, 2], 0)
    assert six.idle_joints == [[0, 1], [0, 2], [1, 2]]
    assert six.advice == ("links [0, 1, 2] form a rigid sub-chain with W(S) = 0: it acts as one link; insert 1 binary "
                          "link(s) into its joints (a–b becomes a–x–b) or move one of its joints to a link outside it")
    # link 0 (four joints) splits two loops that share no joint: fractionated
    split = analyze_chain("0-1 1-2 2-0 0-3 3-4 4-5 5-0")
    assert split.fractionated is True and split.code == "501/0"
    assert split.advice.endswith("; a link or joint splits the closed part of the chain: its mobility divides "
                                 "between the parts")
    # W = 0 allows the rigid triangle; its pins are idle, held by the rest of the chain
    truss = analyze_chain("0-1 0-2 0-3 1-2 1-5 3-4 4-5", dof=0)
    assert (truss.subchain_defect, truss.dof, truss.defect) == ("none", 1, 1)
    assert truss.advice == ("the chain has W = 1, not 0: " + LOWER_W.format(k=1) + "; joint(s) 0-1, 0-2, 1-2 never "
                            "move: the rest of the chain holds their links together")


def test_redundant_constraints_the_count_does_not_see():
    """The rigid triangle 0-1-2 closes a loop of four sliders through links 3, 4, 5: that loop is a wedge
    loop (W = 3 − 1 = 2) that the count (3·5 − 2·7 = 1) reads as an ordinary loop."""
    a = analyze_chain("0-1 0-2 0=3 1-2 1=5 3=4 4=5", dof=0)
    assert (a.dof, a.dof_count, a.redundant, a.subchain_defect) == (2, 1, 1, "redundant constraints")
    assert a.advice == ("the chain has W = 2, not 0: " + LOWER_W.format(k=2) + "; its pairs carry 1 redundant "
                        "constraint(s) the count does not see (W = 2, the count 1): turn a prismatic pair into a "
                        "revolute one or add a link")


def test_an_over_braced_four_bar():
    """Four links, six pins: the count 9 − 12 = −3, the true W 0 (a rigid body): 3 redundant constraints;
    its code 040/0 is no standard code (W < 0)."""
    a = analyze_chain("0-1 1-2 2-3 3-0 0-2 1-3", dof=1)
    assert (a.code, a.dof, a.dof_count, a.redundant, a.loops, a.defect, a.standard_code) == (
        "040/0", 0, -3, 3, 3, -4, False)
    assert a.advice.startswith("the chain has W = 0, not 1: " + RAISE_W.format(k=1) + "; links [0, 1, 2] form a "
                               "rigid sub-chain")
    assert mobility_of(Chain.parse("0-1 1-2 2-3 3-0 0-2 1-3")) == 0


def test_an_over_braced_four_bar_as_a_structure_is_over_constrained_as_a_whole():
    """W = 0 allows its rigid triangles, so no proper sub-chain is defective, but the whole chain's count
    (9 − 12 = −3) is 3 below its true W (0): the advice must say so, not 'no defect'."""
    a = analyze_chain("0-1 1-2 2-3 3-0 0-2 1-3", dof=0)
    assert (a.dof, a.dof_count, a.redundant, a.subchain_defect, a.defect) == (0, -3, 3, "none", -3)
    assert a.advice == ("the chain as a whole carries 3 redundant constraint(s): the count gives -3, its links "
                        "move with W = 0; remove joints or add links (--repairs)")


def test_gear_meshes_their_lever_analogue_and_the_redundant_meshes():
    # two meshes in a five-joint chain: each mesh read as a binary link gives six links, code 42/0
    gears = analyze_chain("0-1 1~2 2~3 3-0 1-3")
    assert (gears.meshes, gears.lever_analogue, gears.code, gears.dof_count) == (2, "42/0", "22/0 G2", 3 * 3 - 2 * 3 - 2)
    # four planets: 7 links, 5 pins, 8 meshes: 18 − 10 − 8 = 0, where one input is wanted
    a = analyze_chain(planetary_train(4).to_chain(), dof=1)
    meshes = [[0, 3], [0, 4], [0, 5], [0, 6], [2, 3], [2, 4], [2, 5], [2, 6]]
    assert (a.dof_count, a.defect, a.redundant_joints, a.meshes) == (0, -1, meshes, 8)
    assert a.advice == ("the chain has W = 0, not 1: " + RAISE_W.format(k=1) + "; D = -1: joint(s) 0~3, 0~4, 0~5, "
                        "0~6, 2~3, 2~4, 2~5, 2~6 carry the redundant constraint(s); removing 1 of them leaves W = 1 "
                        "with no rigid sub-chain")
    assert analyze_chain(planetary_train(4).to_chain()).redundant_joints is None  # no W asked: nothing to mend


def test_motion_spaces_and_loop_classes():
    bricard = analyze_chain("0-1 1-2 2-3 3-4 4-5 5-0", h=5)  # W = 5 − 4
    assert (bricard.h, bricard.dof, bricard.dof_count, bricard.loops_3) == (5, 1, 1, 1)
    assert analyze_chain("0-1 1-2 2-3 3-4 4-5 5-0", h=3).dof == 3
    # in h = 2 every loop of pins is a loop of class 2: W = 3 − 1
    flat = analyze_chain("0-1 1-2 2-3 3-0", h=2)
    assert (flat.h, flat.dof, flat.loops_2, flat.loops_3) == (2, 2, 1, 0)
    # one pin (W = 3 − 2): no proper sub-chain of two links or more
    pin = analyze_chain("0-1")
    assert (pin.dof, pin.loops, pin.worst_subchain, pin.worst_subchain_mobility) == (1, 0, [], None)
    het = analyze_chain("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5")
    assert het.loop_classes == {"K3": 1, "K5": 1} and (het.loops_2, het.loops_3) == (0, 1)
    with pytest.raises(InvalidOption) as info:
        analyze_chain("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5", h=4)
    assert str(info.value) == ("the chain names its loop classes after '|' (its other links are of class 3): h = 4 "
                               "contradicts them")


def test_refusals():
    with pytest.raises(MalformedChain) as info:
        analyze_chain(Chain(5, [(0, 1), (1, 2), (2, 3), (3, 0)]))
    assert str(info.value) == "link 4 of the 5 is in no joint: a chain's links are all jointed"
    with pytest.raises(MalformedChain) as info:
        analyze_chain(Chain(16, [(0, 1), (1, 2), (2, 3), (3, 0)]))
    assert str(info.value) == ("links 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, … of the 16 are in no joint: a chain's links "
                               "are all jointed")
    with pytest.raises(MalformedChain) as info:
        analyze_chain(Chain(15, [(0, 1), (1, 2), (2, 3), (3, 0)]))  # eleven: the first ten shown
    assert str(info.value) == ("links 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, … of the 15 are in no joint: a chain's links "
                               "are all jointed")
    with pytest.raises(MalformedChain) as info:
        analyze_chain(Chain(14, [(0, 1), (1, 2), (2, 3), (3, 0)]))  # ten: all shown
    assert str(info.value) == ("links 4, 5, 6, 7, 8, 9, 10, 11, 12, 13 of the 14 are in no joint: a chain's links "
                               "are all jointed")
    with pytest.raises(MalformedChain) as info:
        analyze_chain(Chain(6, [(0, 1), (1, 2), (2, 3), (3, 0)]))
    assert str(info.value) == "links 4, 5 of the 6 are in no joint: a chain's links are all jointed"
    n = MAX_CODE_LINKS + 1
    with pytest.raises(QueryTooLarge) as info:
        analyze_chain(Chain(n, [(i, (i + 1) % n) for i in range(n)]))
    assert str(info.value) == (f"the chain has {n} links; chains are analysed here up to {MAX_CODE_LINKS} links (the "
                               "generic mobility's matrix grows with the square of the links)")


@pytest.mark.parametrize("text, standard", [
    ("0=1 1=2 2=0", True),        # read with pins, W without its wedge loop: 1 − 1 = 0, the triangle truss 3/0
    ("0-1 1-2", True),            # an open chain without a loop: 2|1/0 at W = 2
    ("0-1-2 2-3 3-4 4-0 1-5 5-4", True),  # a double joint: 51/1 at W = 1
    ("0-1 1~2 2~3 3-0 1-3", True),  # meshes read as binary links: 42/0 at W = 1
    ("0-1 1-2 2-3 3-0 0-2 1-3", False),  # W = −3 by the count: no code of number synthesis
])
def test_whether_the_code_is_standard(text, standard):
    assert analyze_chain(text).standard_code is standard
