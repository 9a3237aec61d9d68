"""analyze by hand: n, p, K and W of codes counted from their assortment, every formula of the
counting theory against the hand value, the defect's advice, the criterion, the refusals."""

from __future__ import annotations

import pytest

from synth.analysis.codes import LOWER_W, RAISE_W, analyze, mobility
from synth.errors import ImpossibleParameters, InvalidOption


def _by_hand(n1, assortment, v, h=3, f=0):
    """n, p, K, W.  A joint of m links holds m link ends and counts as m − 1 simple joints, and
    v = Σ (m − 2): with J joints, ends = 2J + v, so p = ends − J = (ends + v) / 2."""
    n = n1 + sum(assortment)
    ends = n1 + sum(i * c for i, c in enumerate(assortment, start=2))
    assert (ends + v) % 2 == 0
    p = (ends + v) // 2
    K = p - n + 1
    return n, p, K, (n - 1) - (h - 1) * K + f


@pytest.mark.parametrize("code, n1, assortment, v", [
    ("64200/0", 0, (6, 4, 2), 0), ("6301/0", 0, (6, 3, 0, 1), 0), ("7201/1", 0, (7, 2, 0, 1), 1),
    ("4/0", 0, (4,), 0), ("42/0", 0, (4, 2), 0), ("2|5/2", 2, (5,), 2), ("8101/2", 0, (8, 1, 0, 1), 2),
])
def test_every_formula_gives_the_hand_count(code, n1, assortment, v):
    n, p, K, W = _by_hand(n1, assortment, v)
    a = analyze(code)
    assert (a.links, a.simple_joint_equivalents, a.loops, a.complexity, a.dof, a.v, a.h, a.f) == (
        n, p, K, K - 1, W, v, 3, 0)
    assert a.joints == p - v  # a double joint is one joint that counts twice
    expected = {"general (2a/2b)": W, "Grübler 3(n−1)−2p+f": 3 * (n - 1) - 2 * p, "VIP assortment (2c)": W}
    if K == 1 and n1 == 0 and v == 0:
        expected["single loop n2−h+f"] = assortment[0] - 3
    assert a.formulas == expected
    assert (a.required_dof, a.defect, a.criterion_holds, a.advice) == (None, None, None, "")


@pytest.mark.parametrize("counts, n, p, W", [({1: 2}, 2, 1, 1), ({1: 2, 2: 1}, 3, 2, 2), ({1: 3, 3: 1}, 4, 3, 3)])
def test_open_chains_without_a_loop(counts, n, p, W):
    """A pin (two links), a two-pin arm, a three-armed star: K = 0 and W = 3(n − 1) − 2p."""
    a = analyze(counts=counts)
    assert (a.links, a.simple_joint_equivalents, a.loops, a.complexity, a.dof) == (n, p, 0, -1, W)
    assert a.formulas == {"general (2a/2b)": W, "Grübler 3(n−1)−2p+f": W, "VIP assortment (2c)": W}
    assert W == 3 * (n - 1) - 2 * p


def test_the_vip_formula_weighs_links_of_four_joints_and_more():
    """2·n1 + n2 − Σ (i − 3)·n_i − v − 3 + f: a 6-joint link counts 3, a 5-joint link 2."""
    a = analyze(counts={1: 1, 2: 9, 4: 1, 6: 1}, v=1, f=1)
    n, p, K, W = _by_hand(1, (9, 0, 1, 0, 1), 1, f=1)
    assert (a.links, a.loops, a.dof) == (n, K, W)
    assert a.formulas["VIP assortment (2c)"] == 2 * 1 + 9 - 1 - 3 - 1 - 3 + 1 == W
    assert a.formulas["Grübler 3(n−1)−2p+f"] == 3 * (n - 1) - 2 * p + 1 == W


def test_motion_space_extra_mobility_and_loop_classes():
    ring = analyze("6/0", h=5)  # the Bricard six-bar's count: W = 5 − 4·1
    assert (ring.dof, ring.h, ring.formulas) == (1, 5, {"general (2a/2b)": 1})
    loop = analyze("4/0", f=1)  # a loop with one 2-DOF pair
    assert loop.dof == 2 and loop.formulas == {"general (2a/2b)": 2, "Grübler 3(n−1)−2p+f": 2,
                                               "VIP assortment (2c)": 2, "single loop n2−h+f": 2}
    assert analyze("4/0", f=1, dof=2).criterion_holds is True  # (2 + 1) + 2·1 = 4 + 1
    # the linear translator: K3 = 4, K5 = 1: W = 13 − 2·4 − 4·1
    translator = analyze("12.2000/6", loop_classes={3: 4, 5: 1}, dof=1)
    assert (translator.dof, translator.defect, translator.criterion_holds) == (1, 0, None)
    assert translator.formulas == {"general (2a/2b)": 1}
    assert mobility(14, 5, loop_classes={3: 4, 5: 1}) == 1 and mobility(14, 5, loop_classes={3: 4, 5: 1}, f=2) == 3
    assert mobility(6, 1, h=6) == 0 and mobility(12, 5) == 1 and mobility(12, 5, f=1) == 2
    with pytest.raises(ImpossibleParameters) as info:
        analyze("12.2000/6", loop_classes={3: 3, 5: 1})
    assert str(info.value) == "the loop classes add up to 4 loops but code 12.2.0.0.0/6 has K = 5"


@pytest.mark.parametrize("dof, defect, advice", [
    (1, 0, "D = 0: the counts have no redundant constraints for the required W."),
    (2, -1, "D = -1 < 0: the counts carry 1 redundant constraint(s); " + RAISE_W.format(k=1) + "."),
    (4, -3, "D = -3 < 0: the counts carry 3 redundant constraint(s); " + RAISE_W.format(k=3) + "."),
    (0, 1, "D = 1 > 0: the counts give 1 degree(s) of freedom too many; " + LOWER_W.format(k=1) + "."),
])
def test_the_defect_and_its_advice(dof, defect, advice):
    a = analyze("6301/0", dof=dof)
    assert (a.required_dof, a.defect, a.advice) == (dof, defect, advice)
    assert a.criterion_holds is ((dof + 1) + 2 * 4 == 10)
    assert "3 binary link(s)" in RAISE_W.format(k=3) and "2 binary link(s)" in LOWER_W.format(k=2)


@pytest.mark.parametrize("kwargs, error, said", [
    ({}, InvalidOption, "give a code or explicit counts, not both or neither"),
    ({"code": "4/0", "counts": {2: 4}}, InvalidOption, "give a code or explicit counts, not both or neither"),
    ({"counts": {0: 1, 2: 4}}, ImpossibleParameters, "counts are n_i ≥ 0 for links with i ≥ 1 joints"),
    ({"counts": {2: -1}}, ImpossibleParameters, "counts are n_i ≥ 0 for links with i ≥ 1 joints"),
    ({"counts": {1: 4}}, ImpossibleParameters, "code 4|0/0 has fewer joints than a connected chain of 4 links needs"),
    ({"counts": {}}, ImpossibleParameters, "code 0/0 counts no link: a chain has links"),
    ({"counts": {2: 0, 3: 0}}, ImpossibleParameters, "code 0/0 counts no link: a chain has links"),
    ({"code": "0/0"}, ImpossibleParameters, "code 0/0 counts no link: a chain has links"),
])
def test_refusals(kwargs, error, said):
    with pytest.raises(error) as info:
        analyze(**kwargs)
    assert str(info.value) == said


def test_counts_read_like_codes():
    assert analyze(counts={2: 4, 5: 0}).code == "4/0" and analyze(counts={"2": "4", "3": "2"}).code == "42/0"
    assert analyze(counts={1: 2, 2: 5}, v=2).code == "2|5/2" and analyze(counts={1: 2, 2: 5}, v=2).dof == 4
    with pytest.raises(ImpossibleParameters):
        analyze("4/0", h=7)
    with pytest.raises(ImpossibleParameters):
        analyze("4/0", f=-1)
    with pytest.raises(ImpossibleParameters):
        analyze("4/0", dof=-1)
