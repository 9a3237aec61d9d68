"""The elementary edits of a chain and of a code by hand: a binary link removed with its joints, a multiple joint
split, the counts of a code with double joints, a truss's rigid triangle, the redundant meshes of a large chain."""

from __future__ import annotations

import pytest

from synth import Chain
from synth.analysis.repair import _code_edits, chain_edits, chain_repairs, code_repairs
from synth.structure.code import Code


def test_a_binary_link_of_a_four_bar_is_removed_with_its_joints():
    """Link 0 of the four-bar goes with its pins 0-1 and 0-3: links 1, 2, 3 (renumbered 0, 1, 2) joined 1-2, 2-3."""
    edits = dict(chain_edits(Chain.parse("0-1 1-2 2-3 3-0")))
    assert edits["remove the binary link 0 with its joints 0-1 and 0-3"] == Chain.parse("0-1 1-2")


def test_a_double_joint_is_split_into_two_pins():
    """0-1-2 joins three links: split, it leaves 1-2 and a pin from the link taken out to link 1."""
    chain = Chain.parse("0-1-2 2-3 3-4 4-0 1-5 5-4")
    edits = dict(chain_edits(chain))
    split = edits["split joint 0-1-2 into 1-2 and 0-1"]
    assert split == Chain.parse("0-1 1-2 2-3 3-4 4-0 1-5 5-4") and (split.v, split.links) == (0, 6)
    assert sum(w.startswith("split joint 0-1-2") for w in edits) == 3


def test_a_truss_may_hold_a_rigid_triangle():
    """W = 0: a triangle 0-1-2 with a dyad 3-4 from link 0 to link 1 is a statically determinate truss
    (5 links, 6 pins: 3·4 − 2·6 = 0) whose triangle is rigid, which a truss allows: it needs no repair,
    while as a mechanism (W = 1 asked, the triangle forbidden) it does."""
    from tests.oracles.subchains import exhaustive_subchains

    truss = Chain.parse("0-1 1-2 2-0 0-3 3-4 4-1")
    oracle = exhaustive_subchains(truss.links, truss.joints)
    assert truss.dof == 0 and oracle.ok(rigid_subchains=True) and not oracle.ok(rigid_subchains=False)
    assert chain_repairs(truss, dof=0) == []
    assert chain_repairs(truss, dof=1)


def test_code_edits_with_double_joints_by_hand():
    """42/2 (n2 = 4, n3 = 2, two double joints): each edit moves link counts by hand, e.g. a binary link
    added between the two ternary links turns both into quaternary ones (n2 = 5, n3 = 0, n4 = 2) and
    splitting a double joint on a ternary link makes it quaternary with one double joint fewer."""
    edits = {words: str(code) for words, code in _code_edits(Code.parse("42/2"))}
    by_hand = {
        "add a binary link jointed to links with 2 and 2 joints": "34/2",
        "add a binary link jointed to links with 2 and 3 joints": "421/2",
        "add a binary link jointed to links with 3 and 3 joints": "502/2",
        "remove a binary link jointed to links with 3 and 3 joints": "5/2",
        "move a joint from a link with 3 joints to one with 2": "42/2",
        "move a joint from a link with 3 joints to one with 3": "501/2",
        "merge two joints of a link with 3 joints into a double joint": "51/3",
        "split a multiple joint on a link with 2 joints": "33/1",
        "split a multiple joint on a link with 3 joints": "411/1",
    }
    assert edits == {words: str(Code.parse(text)) for words, text in by_hand.items()}


def test_code_repairs_name_each_code_once():
    """6301/0 (W = 1) asked for W = 3 needs two binary links fewer: removing one between a ternary and the
    quinary link and then one between two ternary links gives 701/0, in either order; then one between the
    ternary and the quaternary link left gives 62/0.  Each code is proposed once, by its first path."""
    repairs = code_repairs(Code.parse("6301/0"), 3, limit=50)
    assert sorted(r.code for r in repairs) == ["62/0", "701/0"]
    for r in repairs:
        assert len(r.edits) == 2 and str(Chain.parse(r.chain).code) == r.code and Chain.parse(r.chain).dof == 3


@pytest.mark.parametrize("dyads,links,joints", [(8, 23, 37), (17, 41, 64)])
def test_redundant_meshes_are_named_on_a_large_chain_of_few_core_links(dyads, links, joints):
    """The planetary train with four planets (W = 0, D = −1: any one of its eight meshes can go) with dyads
    pinned between the sun and the carrier (each adds two links and three pins, no freedom and no
    redundancy); its sets of links are scanned through the 7 links of its core.  The search's bound counts
    a try as 2^min(n, 22) sets: 37 tries on 23 links are below 2^28 sets, and 64 tries on 41 links are
    exactly 2^28, still allowed; both name the same eight meshes."""
    from synth.analysis.repair import redundant_joints

    pinned = " ".join(f"0-{7 + 2 * k} {7 + 2 * k}-{8 + 2 * k} {8 + 2 * k}-1" for k in range(dyads))
    train = Chain.parse("0-1 1-3 1-4 1-5 1-6 0~3 0~4 0~5 0~6 2~3 2~4 2~5 2~6 " + pinned)
    assert (train.links, len(train.joints), train.dof) == (links, joints, 0)
    assert redundant_joints(train, 1) == [(0, 3), (0, 4), (0, 5), (0, 6), (2, 3), (2, 4), (2, 5), (2, 6)]


def test_redundant_joints_are_not_searched_beyond_the_bound():
    """One dyad more (18: 43 links, 67 joints, 67 tries of 2^22 sets, more than 2^28) and the search is not
    made: None, as for a chain whose W by the count is not below the one asked for."""
    from synth.analysis.repair import redundant_joints

    pinned = " ".join(f"0-{7 + 2 * k} {7 + 2 * k}-{8 + 2 * k} {8 + 2 * k}-1" for k in range(18))
    train = Chain.parse("0-1 1-3 1-4 1-5 1-6 0~3 0~4 0~5 0~6 2~3 2~4 2~5 2~6 " + pinned)
    assert (train.links, len(train.joints), train.dof) == (43, 67, 0)
    assert redundant_joints(train, 1) is None and redundant_joints(train, 0) is None


def test_code_edits_keep_an_open_chains_free_ends():
    """2|5/2 (two single-joint links, five binary ones, two double joints, W = 4): its edits act on the
    closed part and keep the two free ends; a binary link added between two binary links makes them
    ternary (2|42/2, W = 3), which one chain verifies."""
    edits = {words: str(code) for words, code in _code_edits(Code.parse("2|5/2"))}
    assert edits == {"add a binary link jointed to links with 2 and 2 joints": "2|42/2",
                     "split a multiple joint on a link with 2 joints": "2|41/1"}
    (repair,) = code_repairs(Code.parse("2|5/2"), 3)
    chain = Chain.parse(repair.chain)
    assert repair.code == "2|42/2" and (chain.code.n1, chain.code.assortment, chain.code.v) == (2, (4, 2), 2)
    assert chain.dof == 3 and chain.degrees.count(1) == 2


def test_code_repairs_are_five_unless_more_are_asked_for():
    """7111/0 (W = 1) asked for W = 0: one binary link more, jointed to two links of degrees 2 and 2, 2 and 3,
    2 and 4, 2 and 5, 3 and 4, 3 and 5 or 4 and 5 (one link each of 3, 4, 5 joints): seven codes one edit
    away; five by default."""
    code = Code.parse("7111/0")
    every = code_repairs(code, 0, limit=10)
    assert sorted(r.code for r in every) == sorted(
        str(Code.parse(t)) for t in ("6311/0", "7121/0", "7202/0", "72101/0", "80120/0", "80201/0", "81011/0"))
    assert [r.code for r in code_repairs(code, 0)] == [r.code for r in every][:5]


def test_a_repaired_chain_states_its_mobility():
    """The rigid triangle 0-1-2 with a three-link chain from 0 to 1 (W = 1 by the count) mended in one edit:
    each repair is a chain of W = 1 and says so."""
    for repair in chain_repairs(Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-1")):
        assert repair.dof == 1 == Chain.parse(repair.chain).dof and repair.to_dict()["dof"] == 1


def test_more_than_three_redundant_constraints_are_not_searched():
    """Seven planets on a floating sun: W = 4 − 7 = −3, D = −4 against W = 1, beyond the three searched."""
    from synth.analysis.repair import redundant_joints
    from synth.gears.planetary import planetary_train

    seven = planetary_train(7).to_chain()
    assert seven.dof == -3 and redundant_joints(seven, 1) is None
    assert redundant_joints(planetary_train(6).to_chain(), 1, most=2) is None  # D = −3 with at most 2 asked


def test_a_code_without_multiple_joints_has_none_to_split():
    """42/0: the splits name no code (None), as the other edits that cannot be made."""
    edits = dict(_code_edits(Code.parse("42/0")))
    assert edits["split a multiple joint on a link with 2 joints"] is None
    assert edits["split a multiple joint on a link with 3 joints"] is None
    assert str(edits["merge two joints of a link with 3 joints into a double joint"]) == str(Code.parse("51/1"))
