"""Chains as lines of text by hand: every refusal's sentence with the line or row it names, and what each
reader takes from a line, a row, a CSV listing, a table and an edge list (frame, input link, motion space,
names), and what the writers put on a line."""

from __future__ import annotations

import io
import json
from dataclasses import replace

import pytest

from synth.errors import MalformedChain
from synth.exchange._graphs import describe
from synth.exchange._lists import (edge_words, looks_like_joint_list, looks_like_listing, looks_like_table,
                                   read_edgelist, read_json, read_listing, read_table, read_text_lists,
                                   settings_text, stated_space, write_edgelist, write_lines)
from synth.structure.chain import Chain, Mechanism

_JOINTS = ("cannot read joint '1-x': write joints as link numbers joined by '-' (revolute, '0-1-2' joins three links), "
           "'=' (prismatic) or '~' (gear mesh), e.g. '0-1 1=2 2~3'")
_FOUR = '"joints": [[0, 1], [1, 2], [2, 3], [3, 0]]'
_NO_COMMENT = ("JSON takes no '#' comment: give a frame, an input link or a motion space as keys of the row, e.g. "
               '{"joints": [[0, 1], [1, 2], [2, 0]], "frame": 0, "h": 3}')


@pytest.mark.parametrize("call,sentence", [
    (lambda: read_text_lists("0-1 1-x", "src"), f"src: {_JOINTS}"),
    (lambda: read_text_lists("0-1 1-2 2-0\n\n0-1 1-x\n", "src"), f"src line 3: {_JOINTS}"),
    (lambda: read_text_lists("# only a comment\n0-1 1-x # and one here\n", "src"), f"src: {_JOINTS}"),
    (lambda: read_json("{" + _FOUR + ', "frame": 9}', "src"), "src: the frame 9 is not a link of the chain (0 … 3)"),
    (lambda: read_json("{" + _FOUR + ', "frame": -1}', "src"), "src: the frame -1 is not a link of the chain (0 … 3)"),
    (lambda: read_json("{" + _FOUR + ', "frame": 4}', "src"), "src: the frame 4 is not a link of the chain (0 … 3)"),
    (lambda: read_json("{" + _FOUR + ', "frame": true}', "src"), "src: the frame True is not a link of the chain (0 … 3)"),
    (lambda: read_json("{" + _FOUR + ', "frame": 0, "input_link": "x"}', "src"),
     "src: the input link 'x' is not a link of the chain (0 … 3)"),
    (lambda: read_json('[{"joints": [[0, 1]]}, {"joints": 5}]', "src"),
     "src row 2: 'joints' must be a list of lists of link numbers"),
    (lambda: read_json('{"joints": [[0, 1], [1, 2], [2, 0]]}\n{bad\n', "src"),
     "src line 2: not valid JSON (Expecting property name enclosed in double quotes at column 2)"),
    (lambda: read_text_lists("0-1 1-2 2-3 3-0\n# frame 0\n", "src"),  # the old reader dropped it without a word
     "src line 2: '# frame 0' stands on a line of its own: in a joint list the settings follow their chain on its "
     "line, e.g. '0-1 1-2 2-3 3-0  # frame 0'"),
    (lambda: read_json("[[0, 1], [1, 2], [2, 0]]  # frame 0", "src"), f"src line 1: {_NO_COMMENT}"),
    (lambda: read_json('{"joints": [[0, 1], [1, 2], [2, 0]]}\n# a note\n', "src"), f"src line 2: {_NO_COMMENT}"),
    (lambda: read_json('[\n  {"joints": [[0, 1], [1, 2], [2, 0]]}  # the triangle\n]', "src"),
     f"src line 2: {_NO_COMMENT}"),
    (lambda: read_listing("a,b\n1,2\n", "src"), "src: a listing in CSV has a 'joints' column (as chains --format csv prints)"),
    (lambda: read_listing("index,joints\n", "src"), "src: the listing has a header and no row"),
    (lambda: read_listing("index,joints\n1,0-1 1-2 2-0\n2,0-1 1-x\n", "src"), f"src row 2: {_JOINTS}"),
    (lambda: read_table("a b\n1 2\n", "src"),
     "src: a listing as a table has a header with a 'joints' column over a rule of dashes (as chains prints)"),
    (lambda: read_table("index  joints\n-----  ------\n3 chains\n", "src"), "src: the table has a header and no row"),
    (lambda: read_table("index  joints\n-----  -----------\n1      0-1 1-2 2-0\n2      0-1 1-x\n", "src"),
     f"src row 2: {_JOINTS}"),
    (lambda: read_edgelist("# frame 0\n\n0 1\n1 2\n2 0\n", "src"), "src: '# frame 0' is followed by no joint"),
    (lambda: read_edgelist("# frame 0, input 1\n\n0 1\n1 2\n2 0\n", "src"),
     "src: '# frame 0, input 1' is followed by no joint"),
    (lambda: read_text_lists("0-1 1-2 2-0 | h5: 0-0", "src"),  # the loop classes are no joints
     "src: cannot read the loop classes 'h5: 0-0': after '|' write each base's class and links, e.g. "
     "'| h5: 0 1 2 3 4 5' ('| h2; h3: 0 1 2 3' where the other links are not of class 3)"),
    (lambda: read_text_lists("0-1 1-2 2-3 3-0 2-4 4-5 5-3 | h5: 0 1 2 3  # h 4", "src"),
     "src names its loop classes (its other links are of class 3): h = 4 contradicts them"),
    (lambda: read_edgelist("0 1 {bad\n", "src"),
     "src line 1: cannot read the data '{bad' (a dictionary such as {'kind': 'prismatic'})"),
    (lambda: read_edgelist("0 1 {1, 2}\n", "src"), "src line 1: the joint's data must be a dictionary, not {1, 2}"),
    (lambda: read_edgelist("0 1\n1\n", "src"),
     "src line 2: cannot read '1' as a joint: an edge-list line names the two (or more) links of a joint, then "
     "optionally its kind, e.g. '0 1' or '1 2 prismatic'"),
    (lambda: read_edgelist("# just a comment\n", "src"),
     "src: no joint: an edge list names the links of one joint a line, e.g. '0 1'"),
])
def test_every_refusal_names_its_place(call, sentence):
    with pytest.raises(MalformedChain) as refused:
        call()
    assert str(refused.value) == sentence


def _read(entries):
    return [(e.chain.compact(), e.frame, e.input_link, e.h, e.names, e.source) for e in entries]


def test_text_lines_with_their_settings():
    entries = read_text_lists("0-1 1-2 2-3 3-0  # frame 2, input 1\n# a comment line\n"
                              "0-1 1-2 2-3 3-4 4-5 5-0 # h 5\n0-1 1-2 2-0 # any other comment\n", "src")
    assert _read(entries) == [("0-1 0-3 1-2 2-3", 2, 1, None, None, "src line 1"),
                              ("0-1 0-5 1-2 2-3 3-4 4-5", None, None, 5, None, "src line 3"),
                              ("0-1 0-2 1-2", None, None, None, None, "src line 4")]
    assert entries[1].chain.h == 5


def test_json_rows_by_name_and_by_space():
    """Rows in an array are numbered; a frame and an input link may be given by the names of the links; h comes
    from the row, else from the certificate (h ≠ 3 in front), else is not stated."""
    rows = ('[{' + _FOUR + ', "names": ["a", "b", "c", "d"], "frame": "b", "input_link": "c"}, '
            '{"joints": [[0, 1], [1, 2], [2, 0]], "h": 4}]')
    assert _read(read_json(rows, "src")) == [("0-1 0-3 1-2 2-3", 1, 2, None, ("a", "b", "c", "d"), "src row 1"),
                                             ("0-1 0-2 1-2", None, None, 4, None, "src row 2")]
    assert _read(read_json("[[0, 1], [1, 2], [2, 0]]", "src")) == [("0-1 0-2 1-2", None, None, None, None, "src")]
    lines = '{"joints": [[0, 1], [1, 2], [2, 0]]}\n\n{' + _FOUR + ', "certificate": "h5x"}\n'
    assert _read(read_json(lines, "src")) == [("0-1 0-2 1-2", None, None, None, None, "src line 1"),
                                              ("0-1 0-3 1-2 2-3", None, None, 5, None, "src line 3")]


def test_stated_space():
    assert stated_space({"h": None, "chain_certificate": "m3h4abc"}) == 4
    assert stated_space({"certificate": ""}) is None and stated_space({"certificate": 5}) is None
    assert stated_space({"h": 6, "certificate": "h4"}) == 6 and stated_space({"certificate": "m2040a"}) == 3


def test_a_csv_listing_and_a_table():
    listing = ("# a comment\nindex,Joints,h,frame,input_link,certificate\n1,0-1 1-2 2-3 3-0,,0,1,\n"
               "2,0-1 1-2 2-3 3-4 4-5 5-0,5,,,\n3,0-1 1-2 2-3 3-4 4-0,,,,h40000\n")
    assert looks_like_listing(listing) and not looks_like_listing("0,1\n1,0\n")
    assert _read(read_listing(listing, "src")) == [("0-1 0-3 1-2 2-3", 0, 1, None, None, "src row 1"),
                                                   ("0-1 0-5 1-2 2-3 3-4 4-5", None, None, 5, None, "src row 2"),
                                                   ("0-1 0-4 1-2 2-3 3-4", None, None, 4, None, "src row 3")]
    table = ("index  joints           frame  input_link  h\n-----  ---------------  -----  ----------  -\n"
             "1      0-1 1-2 2-3 3-0  0      1           \n2      0-1 1-2 2-3 3-0                     4\n"
             "2 chains\n9      junk\n")
    assert looks_like_table(table) and not looks_like_table("0 1\n1 2\n") and not looks_like_table("joints\n")
    assert _read(read_table(table, "src")) == [("0-1 0-3 1-2 2-3", 0, 1, 3, None, "src row 1"),
                                               ("0-1 0-3 1-2 2-3", None, None, 4, None, "src row 2")]


def test_edge_lists_with_kinds_settings_and_two_chains():
    text = ("# frame 1, input 0\n0 1\n1 2 {'kind': 'prismatic'}\n2 3 mesh\n3 0\n\n"
            "# h 4\n0 1 2\n2 3\n3 4\n4 0 {'weight': 1}\n")
    assert _read(read_edgelist(text, "src")) == [("0-1 0-3 1=2 2~3", 1, 0, None, None, "src line 1"),
                                                 ("0-1-2 0-4 2-3 3-4", None, None, 4, None, "src line 7")]
    # settings after a joint count as on a line of their own (the old reader dropped them without a word)
    assert _read(read_edgelist("0 1  # frame 1\n1 2\n2 0  # h 4, input 0\n", "src")) == [
        ("0-1 0-2 1-2", 1, 0, 4, None, "src line 1")]
    assert edge_words("0 1 X") == (["0", "1"], "X") and edge_words("a b c") == (["a", "b", "c"], None)
    assert edge_words("a b ~") == (["a", "b"], "~") and edge_words("a") is None and edge_words("a b!") is None


def test_joint_list_lines():
    assert [looks_like_joint_list(x) for x in ("", "0-1, 1-2", "0-1 # x", "0-1-", "a-b", "0~1 1=2")] == [
        False, True, True, False, False, True]


def test_what_the_writers_put_on_a_line():
    out = io.StringIO()
    five = replace(Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0"), h=5)
    items = [Chain.parse("0-1 1=2 2-0"), Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1), five]
    assert write_lines(items, "text", out) == 3
    assert out.getvalue() == "0-1 0-2 1=2\n0-1 0-3 1-2 2-3  # frame 0, input 1\n0-1 0-5 1-2 2-3 3-4 4-5  # h 5\n"
    out = io.StringIO()
    assert write_lines(items[:2], "json", out) == 2
    chain_row, mechanism_row = map(json.loads, out.getvalue().splitlines())
    assert chain_row["id"] == describe(items[0])["id"] and "chain_id" not in chain_row
    assert mechanism_row["chain_id"] == describe(items[1].chain)["id"] and "id" not in mechanism_row
    assert (mechanism_row["frame"], mechanism_row["input_link"]) == (0, 1)
    assert settings_text(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 2)) == "frame 2"
    assert settings_text(five) == "h 5" and settings_text(items[0]) == ""
    out = io.StringIO()
    write_edgelist(Mechanism(Chain.parse("0-1 1=2 2~3 3-0"), 0), out)
    head, settings, *joints = out.getvalue().splitlines()
    assert head.startswith("# 4/0 P1 G1 id ") and settings == "# frame 0, h 3"
    assert joints == ["0 1", "0 3", "1 2 prismatic", "2 3 mesh"]


def test_a_heterogeneous_line_keeps_its_loop_classes():
    """The classes after '|' (a base of class 5, the other links of class 4 by 'h4'); a setting '# h 4' agrees
    with them, '# h 4' on a line whose other links are of class 3 does not (refused above); a base may name a
    link twice."""
    (entry,) = read_text_lists("0-1 1-2 2-3 3-0 2-4 4-5 5-3 | h4; h5: 0 1 2 3  # h 4", "src")
    assert (entry.chain.classes, entry.chain.h, entry.h) == ((5, 5, 5, 5, 4, 4), 4, 4)
    (entry,) = read_text_lists("0-1 1-2 2-3 3-0 2-4 4-5 5-3 | h5: 0 1 2 3 3  # frame 0", "src")
    assert (entry.chain.classes, entry.chain.h, entry.h, entry.frame) == ((5, 5, 5, 5, 3, 3), 3, None, 0)
    assert entry.chain.compact() == "0-1 0-3 1-2 2-3 2-4 3-5 4-5 | h5: 0 1 2 3"


def test_more_edge_list_kinds_and_a_listing_of_comments():
    """A joint's data may name its kind as 'kind', 'joint_kind' or 'type'; a text of comments only is no listing."""
    entries = read_edgelist("0 1\n1 2 {'type': 'prismatic'}\n2 0 {'joint_kind': 'mesh'}\n", "s")
    assert [e.chain.compact() for e in entries] == ["0-1 0~2 1=2"]
    assert not looks_like_listing("# only a comment\n") and not looks_like_listing("")
