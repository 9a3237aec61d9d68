"""Readers of the formats other tools write, and their refusals (one sentence naming the place)."""

from __future__ import annotations

import io

import networkx as nx
import pytest

from synth import Chain, MalformedChain
from synth.exchange import detect, read, read_file, read_text, text_of

WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")


def _one(text: str, fmt=None):
    (entry,) = read_text(text, fmt)
    return entry


def test_link_graphs_from_networkx_in_graphml_and_gml():
    g = nx.relabel_nodes(WATT.link_graph(), {i: f"part {i}" for i in range(6)})
    g.edges["part 0", "part 1"]["kind"] = "prismatic"
    for writer in (nx.write_graphml, nx.write_gml):
        out = io.BytesIO()
        writer(g, out)
        entry = _one(out.getvalue().decode())
        assert entry.chain.kinds.count("prismatic") == 1 and entry.names[0] == "part 0"
        assert entry.chain.certificate == Chain(6, WATT.joints, ["prismatic"] + ["revolute"] * 6).certificate


def test_dot_as_graphviz_users_write_it():
    text = """
    /* a Stephenson chain */
    strict graph "stephenson" {
      graph [rankdir=LR];  // a comment
      node [shape=box];
      T1 -- {a b} -- T2;      // a group as an edge end
      T1 -- c -- d -- T2 [color="red"];
      "T1":n -- e [kind="="];  e -- f -- T2;
    }
    """
    entry = _one(text)
    assert entry.chain.links == 8 and entry.chain.kinds.count("prismatic") == 1
    assert sorted(entry.chain.degrees) == [2, 2, 2, 2, 2, 2, 4, 4]


def test_edge_lists_with_names_kinds_data_and_several_chains():
    text = "# two chains\ncrank rod\nrod slider prismatic\nslider frame {'kind': 'revolute'}\nframe crank\n\n0 1\n1 2\n2 0\n"
    first, second = read_text(text)
    assert first.chain.compact() == "0-1 0-2 1-3 2=3" and first.names == ("crank", "frame", "rod", "slider")
    assert second.chain.compact() == "0-1 0-2 1-2" and second.source.endswith("line 7")


def test_matrices_bare_with_headers_and_transposed():
    bare = _one("0 1 0 1\n1 0 1 0\n0 1 0 1\n1 0 1 0\n", "adjacency")
    assert bare.chain.compact() == "0-1 0-3 1-2 2-3"
    headed = _one(",a,b,c\na,0,1,P\nb,1,0,1\nc,P,1,0\n")
    assert headed.chain.kinds.count("prismatic") == 1 and headed.names == ("a", "b", "c")
    incidence = _one("link,0-1-2,2=3,3-0\n0,1,0,1\n1,1,0,0\n2,1,1,0\n3,0,1,1\n")
    assert incidence.chain.compact() == "0-1-2 0-3 2=3"
    transposed = _one("joint,0,1,2,3\n0-1-2,1,1,1,0\n2=3,0,0,1,1\n3-0,1,0,0,1\n")
    assert transposed.chain == incidence.chain
    square_incidence = _one("1,0,0,1\n1,1,0,0\n0,1,1,0\n0,0,1,1\n")  # not symmetric: an incidence matrix
    assert square_incidence.chain.compact() == "0-1 0-3 1-2 2-3"


def test_formats_told_apart():
    assert detect("0-1 1-2\n2=3 3-0\n") == "text"
    assert detect('{"joints": [[0, 1]]}') == "json"
    assert detect("<?xml version='1.0'?><graphml/>") == "graphml"
    assert detect("graph [\n node [ id 0 ]\n]") == "gml"
    assert detect("digraph { a -> b }") == "dot"
    assert detect("a b\nb c\n") == "edgelist"
    assert detect("0,1\n1,0\n") == "matrix"
    # a matrix written with spaces (as numpy.savetxt or a hand writes it) is a matrix, not an edge list:
    # its rows repeat a number, which no joint's line can
    spaced = "0 1 0 1\n1 0 1 0\n0 1 0 1\n1 0 1 0\n"
    assert detect(spaced) == "matrix" and read_text(spaced)[0].chain.compact() == "0-1 0-3 1-2 2-3"
    assert detect("0 1 2\n2 3 4\n") == "edgelist"  # two double joints: no number repeats within a line
    assert detect("anything", ".gv") == "dot"
    assert detect("dof = 1\nname = 'x'\n") == "unknown"


@pytest.mark.parametrize("text, fmt, words", [
    ("0-1 1-1 1-2", None, "link 1 is joined to itself"),
    ('{"joints": [[0, 1], [2, 2]]}', None, "link 2 is joined to itself"),
    ("a b\nb b\n", "edgelist", "link b is joined to itself"),
    ("1,0\n0,0\n", "adjacency", "link 0 is joined to itself"),
    ("0,1,1\n1,0,0\n0,0,0\n", "adjacency", "not symmetric"),
    ("1,0\n1,1\n0,1\n0,0\n", "incidence", "link 3 is in no joint"),
    ("graph { a -- a }", None, "link a is joined to itself"),
    ("graph { a -- b; b -- c; c -- }", None, "not DOT"),
    ("graph [ node [ id 0 ] edge [ source 0 target 0 ] ]", None, "joined to itself"),
    ("<graphml><graph", None, "not a GraphML document"),
    ("0-1 1-2\n0-1 1-2 2-0 0-1\n", None, "line 2"),
    ("dof = 1\n", None, "cannot tell"),
    ("0 1\n", "graphml", "not a GraphML document"),
    ("a b\n\n# frame z\n", "edgelist", "frame z"),
    ("0-1 1-2 2-0  # frame 7", None, "frame 7"),
])
def test_bad_input_is_one_sentence_naming_the_place(text, fmt, words):
    with pytest.raises(MalformedChain) as info:
        read_text(text, fmt)
    message = str(info.value)
    assert words in message and "\n" not in message


def test_files_unreadable_missing_binary(tmp_path):
    (tmp_path / "picture.png").write_bytes(bytes(range(256)))
    with pytest.raises(MalformedChain, match="not a text file"):
        read_file(tmp_path / "picture.png")
    with pytest.raises(MalformedChain, match="no file"):
        read(str(tmp_path / "missing.graphml"))
    (tmp_path / "empty").mkdir()
    with pytest.raises(MalformedChain, match="holds no file"):
        read_file(tmp_path / "empty")


def test_a_folder_of_files_in_several_formats(tmp_path):
    (tmp_path / "a.graphml").write_text(text_of([WATT], "graphml"))
    (tmp_path / "b.dot").write_text(text_of([WATT.relabel([5, 4, 3, 2, 1, 0])], "dot"))
    (tmp_path / "c.txt").write_text("0-1 1-2 2-3 3-0\n")
    entries = read_file(tmp_path)
    assert [e.chain.links for e in entries] == [6, 6, 4] and entries[0].chain.certificate == entries[1].chain.certificate


@pytest.mark.parametrize("text, sliding", [
    ("graph { a -- b [kind=prismatic]; b -- c; c -- a }", ["a-b"]),
    ("graph { a -- b [kind=P]; b -- c [kind=R]; c -- a [type=slider] }", ["a-b", "a-c"]),
    ("graph { a -- b [color=red][kind=\"=\"]; b -- c [color=blue; joint_kind=pin]; c -- a }", ["a-b"]),
    ("graph { edge [kind=prismatic]; a -- b; edge [kind=revolute]; b -- c; c -- a }", ["a-b"]),
    ("graph { subgraph s { edge [kind=P]; a -- b } b -- c; c -- a }", ["a-b"]),  # defaults end with their block
    ("graph { a -- b -- c [kind=P]; c -- a }", ["a-b", "b-c"]),                 # an edge chain: every edge
    ("graph { edge [kind=P]; a -- b [kind=R]; b -- c; c -- a [kind=R] }", ["b-c"]),  # its own list over the default
    ("graph { node [kind=link]; a; b; c; j1 [kind=joint, joint_kind=prismatic]; j2 [kind=joint]; "
     "j3 [kind=joint, type=P]; j1 -- a; j1 -- b; j2 -- b; j2 -- c; j3 -- c; j3 -- a }", ["a-b", "a-c"]),
])
def test_a_slider_in_dot_stays_a_slider(text, sliding):
    """Each way DOT writes a joint's kind (edge attribute lists, defaults, edge chains, joint
    nodes of an incidence graph) gives exactly the prismatic pairs written, no more, no fewer."""
    entry = _one(text)
    names = entry.names
    kinds = dict(zip(("-".join(names[x] for x in j) for j in entry.chain.joints), entry.chain.kinds))
    assert sorted(k for k, kind in kinds.items() if kind == "prismatic") == sliding


def test_the_dot_the_engine_writes_keeps_every_slider_and_mesh():
    for chain in (Chain.parse("0-1 1=2 2-3 3-0"), Chain.parse("0=1 1=2 2=3 3=0"), Chain.parse("0-1 0-2 1~2"),
                  Chain.parse("0-1-2 2=3 3-0 0-4 4-5 5-1")):
        text = text_of([chain], "dot")
        (entry,) = read_text(text)
        assert (entry.chain.joints, entry.chain.kinds) == (chain.joints, chain.kinds)
        drawn = [line for line in text.splitlines() if line.lstrip().startswith("J") and "[" in line]
        kinds = chain.kinds
        shapes = {"revolute": "shape=circle", "prismatic": "shape=box", "mesh": "shape=doublecircle"}
        assert [shapes[k] in line for k, line in zip(kinds, drawn)] == [True] * len(kinds)  # dot draws a slider as a box


@pytest.mark.parametrize("text, compact", [
    ("0 1 R\n1 2 P\n2 3 R\n3 0 R\n", "0-1 0-3 1=2 2-3"),
    ("0 1 r\n1 2 p\n2 3 G\n3 0\n", "0-1 0-3 1=2 2~3"),
    ("0,1,revolute\n1,2,slider\n2,0,pin\n", "0-1 0-2 1=2"),
    ("0 1 2\n2 3\n3 0\n", "0-1-2 0-3 2-3"),               # three numbers: a double joint
    ("a b c\nc d\nd a\n", "0-1-2 0-3 2-3"),               # three names: a double joint
    ("a b P\nb c\nc a\n", "0=1 0-2 1-2"),                 # a kind word after names: the kind
])
def test_edge_lists_read_a_kind_column(text, compact):
    (entry,) = read_text(text, "edgelist")
    assert entry.chain.compact() == compact


@pytest.mark.parametrize("text", ["0 1 R\n1 2 X\n2 0 R\n", "0 1\n1 2 spring\n2 0\n"])
def test_an_unknown_kind_in_an_edge_list_is_one_sentence(text):
    with pytest.raises(MalformedChain) as info:
        read_text(text)
    assert "line 2: joint kind" in str(info.value) and "\n" not in str(info.value)


def test_settings_lines_of_edge_lists_and_matrices():
    (edges,) = read_text("# frame 0, input 1\n# h 3\n0 1\n1 2\n2 3\n3 0\n", "edgelist")
    assert (edges.frame, edges.input_link, edges.h) == (0, 1, 3)
    (matrix,) = read_text("# h 5\n0,1,0,0,0,1\n1,0,1,0,0,0\n0,1,0,1,0,0\n0,0,1,0,1,0\n0,0,0,1,0,1\n1,0,0,0,1,0\n")
    assert (matrix.chain.h, matrix.chain.dof) == (5, 1)
    for bad, words in [("# h 7\n0 1\n1 2\n2 0\n", "not '7'"),
                       ("# frame 0, input 2\n0 1\n1 2\n2 3\n3 0\n", "not jointed to the fixed link 0"),
                       ("# h 4\n\n0 1\n1 2\n2 0\n", "'# h 4' is followed by no joint")]:
        with pytest.raises(MalformedChain) as info:
            read_text(bad, "edgelist")
        assert words is None or words in str(info.value)
