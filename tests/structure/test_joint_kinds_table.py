"""The table of joint kinds (synth/structure/joints.py): what it says, checked against the engine's
independent generic mobility, and what the stored ids depend on.

The ids below were computed on main before the table existed (commit 0f04a8d, when the kinds were
string literals and a plain chain's kinds were None).  They are *stored* ids: every atlas, listing
and site addresses chains by them, so a change here would orphan every atlas ever written.
"""

from __future__ import annotations

import json
import pickle

import pytest

import synth.structure.chain as chain_module
from synth.errors import MalformedChain
from synth.structure.chain import Chain, chain_id
from synth.structure.joints import JOINT_KINDS, MESH, PRISMATIC, REVOLUTE, JointKind
from synth.structure.kinds import generic_mobility, structural_mobility

# (joint list, id of its certificate) — computed on main at 0f04a8d; never recompute these
STORED_IDS = [
    ("0-1 1-2 2-3 3-0", "404959cfebdd"),
    ("0-1 1-2 2=3 3-0", "0977a2089905"),
    ("0=1 1=2 2=3 3=0", "3b28b62d9289"),
    ("0-1 1=2 2-0", "9b37e62334d3"),
    ("0~1 1-2 2-0", "3841e661d108"),
    ("0-1 1=2 2~3 3-0", "8110c37a8caa"),
    ("0-1-2 2-3 3-0 0-4 4-5 5-1", "57ab6e9e865f"),
    ("0-2 0-3 0=4 1-2 1-3 1=5 4=5", "f63e40f63d9e"),
    ("0-1-2 2-3 0~3 1~3", "6a992412943b"),
    ("0~1 1~2 2~0", "f90a97ffa61f"),
    ("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5", "22f2a75bf2e9"),
]
# the jsonl rows of two chains as main wrote them (the row format is a contract)
STORED_ROWS = {
    "0-1 1=2 2~3 3-0": '{"code": "4/0 P1 G1", "links": 4, "joints": [[0, 1], [0, 3], [1, 2], [2, 3]], "certificate": '
                       '"0404p01g01000000000000000300000000000000060000000000000009000000000000000c0000000000000030000'
                       '000000000005000000000000000c000000000000000a0", "dof": 2, "loops": 1, "v": 0, "kinds": '
                       '["revolute", "revolute", "prismatic", "mesh"], "prismatic": 1, "meshes": 1, "loops_2": 0, '
                       '"loops_3": 1}',
    "0-1 1-2 2-3 3-0": '{"code": "4/0", "links": 4, "joints": [[0, 1], [0, 3], [1, 2], [2, 3]], "certificate": '
                       '"0404000000000000000c000000000000000a0000000000000005000000000000000300000000000000c00000000000'
                       '0000a000000000000000500000000000000030", "dof": 1, "loops": 1, "v": 0}',
}


def _ids() -> dict[str, str]:
    return {text: chain_id(Chain.parse(text).certificate) for text, _ in STORED_IDS}


def test_stored_ids_are_unchanged():
    assert _ids() == dict(STORED_IDS)


def test_ids_survive_relabelling_and_kinds_given_as_names():
    for text, stored in STORED_IDS:
        c = Chain.parse(text)
        if c.classes is not None:
            continue
        shuffled = c.relabel(list(reversed(range(c.links))))
        by_name = Chain(c.links, c.joints, [str(k.value) for k in c.kinds], c.h)
        assert chain_id(shuffled.certificate) == chain_id(by_name.certificate) == stored, text


def test_reordering_the_table_changes_the_ids_of_chains_with_sliders_or_meshes(monkeypatch):
    """Swap the prismatic and mesh cells: every chain with either kind gets another id, plain chains keep theirs."""
    monkeypatch.setattr(chain_module, "JOINT_KINDS", (REVOLUTE, MESH, PRISMATIC))
    monkeypatch.setattr(MESH, "cell", 1)
    monkeypatch.setattr(PRISMATIC, "cell", 2)
    after = _ids()
    for text, stored in STORED_IDS:
        if Chain.parse(text).all_revolute:
            assert after[text] == stored, text
        else:
            assert after[text] != stored, text


def test_changing_a_tag_changes_the_ids(monkeypatch):
    monkeypatch.setattr(PRISMATIC, "tag", "s")
    after = _ids()
    assert all((after[t] == s) == Chain.parse(t).all_revolute for t, s in STORED_IDS)


def test_appending_a_kind_keeps_every_id(monkeypatch):
    """A kind at the end of the table is shown only by chains that have it: no stored id moves."""
    class Extra(str):
        cell, tag = 3, "x"

    monkeypatch.setattr(chain_module, "JOINT_KINDS", JOINT_KINDS + (Extra("extra"),))
    assert _ids() == dict(STORED_IDS)


def test_rows_are_byte_for_byte_as_stored():
    for text, row in STORED_ROWS.items():
        assert Chain.parse(text).to_json() == row
        assert Chain.from_json(row).to_json() == row


def test_kinds_are_always_a_tuple_of_members():
    plain, by_default = Chain.parse("0-1 1-2 2-0"), Chain(3, [(0, 1), (1, 2), (0, 2)])
    assert plain.kinds == by_default.kinds == (REVOLUTE,) * 3 and plain.all_revolute
    assert all(type(k) is JointKind for c in (plain, Chain.parse("0=1 1~2 2-0")) for k in c.kinds)
    given = Chain(3, [(0, 1), (1, 2), (0, 2)], ["revolute", "prismatic", "revolute"])
    assert given == Chain(3, [(0, 1), (1, 2), (0, 2)], [REVOLUTE, PRISMATIC, REVOLUTE])
    assert hash(given) == hash(Chain(3, [(0, 1), (1, 2), (0, 2)], [REVOLUTE, PRISMATIC, REVOLUTE]))
    assert Chain.trusted(3, plain.joints) == plain and Chain.trusted(3, plain.joints).kinds == plain.kinds
    for c in (plain, given, Chain.parse("0~1 1-2 2-0")):  # pool workers receive chains pickled
        back = pickle.loads(pickle.dumps(c))
        assert back == c and back.certificate == c.certificate and back.kinds[0] is c.kinds[0]


def test_a_member_is_its_name_everywhere_a_file_sees_it():
    assert json.dumps(list(JOINT_KINDS)) == '["revolute", "prismatic", "mesh"]'
    assert [f"{k}" for k in JOINT_KINDS] == [str(k) for k in JOINT_KINDS] == ["revolute", "prismatic", "mesh"]
    assert repr(Chain.parse("0=1 1-2 2-0").kinds) == "('prismatic', 'revolute', 'revolute')"
    assert {"mesh": 1}[MESH] == 1 and JointKind("prismatic") is PRISMATIC


def test_words_symbols_and_letters_name_one_kind_each():
    words = [w.lower() for k in JointKind for w in (k.value, k.letter, k.symbol, *k.words)]
    assert len(words) == len(set(words))
    for k in JointKind:
        assert JointKind.read(k.letter.lower()) is JointKind.read(f" {k.value.upper()} ") is k
        assert JointKind.by_symbol(k.symbol) is k and Chain.parse(f"0{k.symbol}1").kinds == (k,)
    assert JointKind.read("crank") is None and JointKind.symbols() == "-=~"
    with pytest.raises(KeyError):
        JointKind.by_symbol("+")


@pytest.mark.parametrize("kind", list(JointKind))
def test_freedom_is_what_the_generic_mobility_finds(kind):
    """Two links and one pair: W = 3 − removes(3) = freedom, by the count and by the rank."""
    pair = Chain.parse(f"0{kind.symbol}1")
    assert structural_mobility(pair) == generic_mobility(pair) == kind.freedom == 3 - kind.removes(3)


@pytest.mark.parametrize("kind", list(JointKind))
def test_a_loop_of_one_kind_counts_as_its_loop_space_says(kind):
    """A triangle of one kind: 3·2 − 3·removes(3), plus h − x for a kind whose loops live in space x;
    the generic mobility (velocity rank, no table) agrees."""
    triangle = Chain.parse(" ".join(f"{a}{kind.symbol}{b}" for a, b in ((0, 1), (1, 2), (2, 0))))
    back = 0 if kind.loop_space is None else 3 - kind.loop_space
    assert structural_mobility(triangle) == generic_mobility(triangle) == 6 - 3 * kind.removes(3) + back


def test_only_kinds_that_join_many_make_multiple_joints_and_planar_kinds_stay_planar():
    for kind in JointKind:
        text = f"0{kind.symbol}1{kind.symbol}2 2-3 3-0"
        if kind.joins_many:
            assert Chain.parse(text).v == 1
        else:
            with pytest.raises(MalformedChain, match="multiple joint is a pin"):
                Chain.parse(text)
        if kind.planar:
            with pytest.raises(MalformedChain, match="planar"):
                Chain(2, [(0, 1)], [kind], h=6)


def test_drawings_read_the_table(monkeypatch):
    from synth.display import svg_of

    monkeypatch.setattr(MESH, "stroke", "#123456")
    monkeypatch.setattr(PRISMATIC, "stroke", "#654321")
    svg = svg_of(Chain.parse("0-1 1=2 2~3 3-0"))
    assert "#123456" in svg and "#654321" in svg


def test_tags_cannot_be_read_as_part_of_another_field():
    """A tag follows two hex digits in the certificate's head: it must be no hex digit, not the motion
    space's ``h`` nor the loop classes' ``c``, and every kind but the revolute one has its own."""
    tags = [k.tag for k in JointKind if k is not REVOLUTE]
    assert REVOLUTE.tag == "" and len(set(tags)) == len(tags)
    assert all(len(t) == 1 and t not in "0123456789abcdefhc" for t in tags)
    assert [k.cell for k in JointKind] == list(range(len(JOINT_KINDS)))
