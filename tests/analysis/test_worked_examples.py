"""Every worked example of structure in docs/theory.md, through the public API."""

import pytest

from synth import Code, number_synthesis
from synth.analysis.codes import analyze, mobility
from synth.synthesis.type_synthesis import type_synthesis


def test_task1_24_link_system():
    # planar, n = 24, W = 1: K from the criterion (W + 1) + 2K = n
    codes = number_synthesis(1, links=24, require={2: (4, 4)}, v=0)
    assert codes and all(c.loops == 11 for c in codes)
    a = analyze(codes[0], dof=1)
    assert (a.dof, a.loops, a.complexity, a.criterion_holds) == (1, 11, 10, True)


def test_task2_single_loop_with_prismatic_pairs():
    # a prismatic pair counts like a revolute pair: 4 links, h = 3
    assert analyze(counts={2: 4}).dof == 1
    assert mobility(4, 1, h=3) == 1


def test_task3_wedge_lever_system():
    classes = {2: 1, 3: 1}
    codes = number_synthesis(1, loop_classes=classes)
    assert Code((3, 2), 0) in codes
    assert analyze(counts={2: 3, 3: 2}, loop_classes=classes).dof == 1


def test_task4_elastic_coupling():
    assert mobility(2, 1, h=1) == 1
    assert analyze(counts={2: 2}, h=1).dof == 1


def test_task5_planetary_lever_analogue():
    a = analyze("64200/0", dof=1)
    assert (a.dof, a.loops, a.defect) == (1, 5, 0)


def test_open_robot_chain():
    a = analyze(counts={1: 2, 2: 5}, v=2)
    assert (a.links, a.loops, a.dof) == (7, 1, 4)
    assert set(a.formulas.values()) == {4}
    assert Code((5,), 2, None, 2) in number_synthesis(4, loops=1, n1="0..2")


def test_two_dof_pair_loop():
    assert analyze(counts={2: 4}, f=1).dof == 2


def test_nacl_lattice():
    a = analyze("12,000/4-1")
    assert (a.dof, a.loops, a.v) == (3, 4, 6)
    assert set(a.formulas.values()) == {3}


def test_spherical_and_bennett_four_bars():
    assert mobility(4, 1, h=3) == 1


def test_bricard_toroidal_six_bar():
    assert mobility(6, 1, h=5) == 1
    assert mobility(6, 1, h=6) == 0  # the classical formula's paradox


def test_simplest_six_space_loop():
    codes = number_synthesis(1, loops=1, h=6)
    assert [c.links for c in codes] == [7]


def test_linear_translator():
    classes = {3: 4, 5: 1}
    a = analyze(counts={2: 12, 3: 2}, v=6, loop_classes=classes)
    assert (a.links, a.loops, a.dof) == (14, 5, 1)
    assert Code((12, 2), 6) in number_synthesis(1, loop_classes=classes)


def _grubler(links: int, joints) -> int:
    return 3 * (links - 1) - 2 * sum(len(j) - 1 for j in joints)


def _edited(links: int, joints: list, edit: str):
    """The four edits the advice names, written out here on a chain's joint list (no engine code)."""
    joints = [tuple(j) for j in joints]
    binary = next(x for x in range(links)
                  if sum(x in j for j in joints) == 2 and all(len(j) == 2 for j in joints if x in j))
    if edit == "remove a binary link with both its joints":
        return links - 1, [j for j in joints if binary not in j]
    if edit == "insert a binary link into a joint":  # a–b becomes a–x–b
        a, b = joints[0]
        return links + 1, joints[1:] + [(a, links), (links, b)]
    if edit == "add a binary link jointed to two links":
        return links + 1, joints + [(0, links), (1, links)]
    if edit == "take a binary link out of its string":  # a–x–b becomes a–b
        a, b = [y for j in joints if binary in j for y in j if y != binary]
        return links - 1, [j for j in joints if binary not in j] + [(a, b)]
    raise AssertionError(edit)


@pytest.mark.parametrize("code, dof", [("6301/0", 2), ("6301/0", 0), ("440/0", 3), ("4/0", 0)])
def test_defect_advice_names_edits_that_move_w_its_way(code, dof):
    """D < 0 asks for edits that raise W, D > 0 for edits that lower it; each named edit, done by hand
    on a chain of the code, moves W by one in that direction, and the repairs go the same way."""
    from synth.analysis.repair import code_repairs

    a = analyze(code, dof=dof)
    chain = next(iter(type_synthesis(a.dof, code=code, workers=1)))
    raise_w = a.defect < 0
    named = (["remove a binary link with both its joints", "insert a binary link into a joint"] if raise_w
             else ["add a binary link jointed to two links", "take a binary link out of its string"])
    assert ("raises W" if raise_w else "lowers W") in a.advice
    for edit in named:
        links, joints = _edited(chain.links, list(chain.joints), edit)
        assert _grubler(links, joints) == a.dof + (1 if raise_w else -1), edit
    repair = code_repairs(Code.parse(code), dof, limit=1)[0]
    assert Code.parse(repair.code).dof() == dof and analyze(repair.code, dof=dof).defect == 0


def test_defect_and_advice():
    assert analyze("7201/1", dof=1).defect == 0
    assert analyze("6301/0", dof=0).defect == 1 and analyze("6301/0", dof=2).defect == -1
    assert analyze("6301/0", dof=2).advice.startswith("D = -1 < 0: the counts carry 1 redundant constraint(s); remove")
    from synth.analysis.chains import analyze_chain

    four_bar = "0-1 1-2 2-3 3-0"  # W = 1: to 2 by a removed or inserted link, to 0 by an added one
    assert "each raises W by 1" in analyze_chain(four_bar, dof=2).advice
    assert "each lowers W by 1" in analyze_chain(four_bar, dof=0).advice


def test_limit_mechanism_type_one():
    # i_max = 2K, n = 3K + 1 with W = K, v = 0
    for K in (2, 3, 4):
        codes = number_synthesis(K, loops=K, max_link_degree="K+W", v=0, require={2 * K: (1, None)})
        assert codes and all(c.links == 3 * K + 1 and c.max_degree == 2 * K for c in codes)


def test_formulas_agree_on_all_table_codes():
    for code in number_synthesis(1, loops="1..5"):
        a = analyze(code, dof=1)
        assert set(a.formulas.values()) == {1} and a.defect == 0 and a.criterion_holds
