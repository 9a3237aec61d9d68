"""Chains as matrices by hand: every refusal's sentence, adjacency and incidence matrices read with and without
headers (commas, semicolons, tabs, spaces; rows of joints; pandas' empty corner), their settings, and the
matrices written."""

from __future__ import annotations

import io

import pytest

from synth.errors import InvalidOption, MalformedChain
from synth.exchange._matrices import read_matrices, write_adjacency, write_incidence
from synth.structure.chain import Chain, Mechanism


@pytest.mark.parametrize("text,fmt,sentence", [
    ("0,1,1\n1,0,1\n1,1,0\n0,0,0\n", None, "m: link 3 is in no joint: a chain's links are all jointed"),
    ("0,1,1,0\n1,0,1,0\n1,1,0,0\n0,0,0,0\n", None, "m: link 3 is in no joint: a chain's links are all jointed"),
    ("link,0-1,1-2\n0,1,0\n1,X,1\n2,0,1\n", None,
     "m, joint 0-1: joint kind 'X' is not one of revolute, prismatic, mesh (or R, P, G; -, =, ~)"),
    ("0,2\n2,0\n", None, "m: entry 2 is not 0 or 1 (or a joint kind R, P, G): two joints between the same links, or a "
                         "link held twice by a joint, are not a chain"),
    ("0,1,1\n1,0,1\n0,1,0\n", "adjacency", "m: the adjacency matrix is not symmetric at links 0 and 2 (1 and 0)"),
    ("0,1,1\n1,0,1\n,1,0\n", "adjacency", "m: the adjacency matrix is not symmetric at links 0 and 2 (1 and empty)"),
    ("0,1,\n1,0,1\n1,1,0\n", "adjacency", "m: the adjacency matrix is not symmetric at links 0 and 2 (empty and 1)"),
    ("1,1\n1,0\n", "adjacency", "m: link 0 is joined to itself (entry 1 on the diagonal)"),
    ("0,1\n1,0,1\n", None, "m: the rows of the matrix have different lengths"),
    ("link,a,b,c\n0,1,1\n1,1,0\n", None, "m: the header names 3 columns but the rows have 2"),
    ("0,1,1\n1,0,1\n", "adjacency", "m: an adjacency matrix is square, not 2 × 3"),
    ("1,1,0\n1,0,1\n0,0,1\n", "incidence", "m: joint 1 holds 1 link: a joint joins two links or more"),
    ("0,0\n0,0\n", "incidence", "m: joint 0 holds 0 links: a joint joins two links or more"),
    ("link,0-1,x\n0,1,1\n1,1,0\n", "incidence", "m: joint x holds 1 link: a joint joins two links or more"),
    ("# frame 0\n\n", None, "m: '# frame 0' is followed by no matrix"),
    ("# comment\n", None, "m: no matrix: write a link adjacency or link–joint incidence matrix in CSV"),
    ("0,X\nX,0\n", None, "m: joint kind 'X' is not one of revolute, prismatic, mesh (or R, P, G; -, =, ~)"),
    ("0,1,1\n1,0,1\n1,1,0\n\n0,1\n1,0,1\n", None, "m line 5: the rows of the matrix have different lengths"),
])
def test_every_refusal_in_full(text, fmt, sentence):
    with pytest.raises(MalformedChain) as refused:
        read_matrices(text, "m", fmt)
    assert str(refused.value) == sentence


def _read(text, fmt=None):
    return [(e.chain.compact(), e.frame, e.input_link, e.h, e.names, e.source) for e in read_matrices(text, "m", fmt)]


def test_adjacency_matrices():
    """Empty cells and zeros are no joint, 1.0 is a pin; P and G name the kinds; the labels of rows and columns
    name the links (in their order)."""
    assert _read("0,1,\n1,0,1\n,1,0\n") == [("0-1 1-2", None, None, None, None, "m")]
    assert _read("0,1.0,1\n1.0,0.0,1\n1,1,0\n") == [("0-1 0-2 1-2", None, None, None, None, "m")]
    assert _read("link;a;b;c\na;0;1;1\nb;1;0;P\nc;1;P;0\n") == [("0-1 0-2 1=2", None, None, None, ("a", "b", "c"), "m")]
    assert _read(",a,b,c\na,0,1,1\nb,1,0,G\nc,1,G,0\n") == [("0-1 0-2 1~2", None, None, None, ("a", "b", "c"), "m")]
    assert _read("links,a,b,c\na,0,1,1\nb,1,0,1\nc,1,1,0\n") == [("0-1 0-2 1-2", None, None, None, ("a", "b", "c"), "m")]


def test_incidence_matrices():
    """A header in the joint-list notation gives the kinds; a corner 'joint' turns the rows into joints; a square
    matrix that is not symmetric, or has a nonzero diagonal, is an incidence matrix (a four-bar here)."""
    text = "# frame 0, input 1\n# h 3\nlink,0-1,1=2,2-3,3-0\n0,1,0,0,1\n1,1,1,0,0\n2,0,1,1,0\n3,0,0,1,1\n"
    assert _read(text) == [("0-1 0-3 1=2 2-3", 0, 1, 3, None, "m")]
    rows = "joint\t0\t1\t2\t3\nj0\t1\t1\t1\t0\nj1\t0\t0\t1\t1\nj2\t1\t0\t0\t1\nj3\t0\t1\t0\t1\n"
    assert _read(rows) == [("0-1-2 0-3 1-3 2-3", None, None, None, None, "m")]
    assert _read(rows.replace("joint", "joints", 1)) == _read(rows)
    four = "1 1 0 0\n0 1 1 0\n0 0 1 1\n1 0 0 1\n"
    assert _read(four) == _read(four, "incidence") == [("0-1 0-3 1-2 2-3", None, None, None, None, "m")]
    assert _read("1,1,0\n0,1,1\n1,0,P\n") == [("0-1 0-2 1=2", None, None, None, None, "m")]


def test_two_matrices_each_with_its_settings():
    text = ("0,1,1\n1,0,1\n1,1,0\n\n# h 5\n0,1,0,0,0,1\n1,0,1,0,0,0\n0,1,0,1,0,0\n0,0,1,0,1,0\n0,0,0,1,0,1\n"
            "1,0,0,0,1,0\n")
    assert _read(text) == [("0-1 0-2 1-2", None, None, None, None, "m line 1"),
                           ("0-1 0-5 1-2 2-3 3-4 4-5", None, None, 5, None, "m line 5")]


def test_a_comment_after_a_row_is_a_comment_and_its_settings_count():
    """As in a joint list and an edge list: '#' starts a comment anywhere on a line (the old reader took it for a
    cell: 'link 2 is joined to itself (entry 0  # frame 1 on the diagonal)')."""
    assert _read("0,1,1  # a triangle\n1,0,1\n1,1,0  # frame 1, h 4\n") == [("0-1 0-2 1-2", 1, None, 4, None, "m")]
    assert _read("link,0-1,1-2,2-0\n0,1,0,1 # frame 2\n1,1,1,0\n2,0,1,1\n") == [("0-1 0-2 1-2", 2, None, None,
                                                                                     None, "m")]


def test_the_matrices_written():
    out = io.StringIO()
    assert write_adjacency([Chain.parse("0-1 1=2 2~3 3-0"), Mechanism(Chain.parse("0-1 1-2 2-0"), 0, 1)], out) == 2
    lines = out.getvalue().splitlines()
    assert lines[0].startswith("# 4/0 P1 G1 id ") and lines[1] == "# h 3"
    assert lines[2:7] == ["link,0,1,2,3", "0,0,1,0,1", "1,1,0,P,0", "2,0,P,0,G", "3,1,0,G,0"]
    assert lines[7] == "" and lines[8].startswith("# 3/0 id ") and lines[9] == "# frame 0, input 1, h 3"
    assert lines[10:] == ["link,0,1,2", "0,0,1,1", "1,1,0,1", "2,1,1,0"]
    out = io.StringIO()
    assert write_incidence([Chain.parse("0-1-2 2=3 3-0"), Chain.parse("0-1 1-2 2-0")], out) == 2
    lines = out.getvalue().splitlines()
    assert lines[1:7] == ["# h 3", "link,0-1-2,0-3,2=3", "0,1,1,0", "1,1,0,0", "2,1,0,1", "3,0,1,1"]
    assert lines[7] == "" and lines[10:] == ["link,0-1,0-2,1-2", "0,1,1,0", "1,1,0,1", "2,0,1,1"]
    assert _read("\n".join(lines[:7])) == [("0-1-2 0-3 2=3", None, None, 3, None, "m")]


def test_a_multiple_joint_has_no_adjacency_matrix():
    with pytest.raises(InvalidOption) as refused:
        write_adjacency([Chain.parse("0-1 1-2 2-0"), Chain.parse("0-1-2 2-3 3-0 1-3")], io.StringIO())
    assert str(refused.value) == ("an adjacency matrix holds simple joints only, and 0-1-2 0-3 1-3 2-3 has a joint of "
                                  "3 links: an incidence matrix holds it")
