"""Reading and writing chains by hand (synth.exchange): the format told from a text or a suffix, every refusal of a
text, a file, a folder and a format, what each kind of source reads as, and what is written."""

from __future__ import annotations

import io
import sys

import networkx as nx
import pytest

import synth.exchange as exchange
from synth.errors import InvalidOption, MalformedChain
from synth.structure.chain import Chain, Mechanism
from tests.refusals import refused

_FORMATS = "text, json, csv, table, graphml, gml, dot, edgelist, adjacency, incidence"


@pytest.mark.parametrize("text,suffix,kind", [
    ("0-1 1-2 2-0", "", "text"), ("# a comment\n0-1 1-2", "", "text"),
    ("0 1\n1 2\n2 0\n", "", "edgelist"), ("a b\nb c", "", "edgelist"),
    ("graph { a -- b }", "", "dot"), ("digraph {}", "", "dot"), ("strict graph {}", "", "dot"),
    ("/* c */ graph {}", "", "dot"), ("// c\ngraph {}", "", "dot"), ("/* a\nb */ graph {}", "", "dot"),
    ("# c1\n# c2\ngraph [ node [ id 0 ] ]", "", "gml"),
    ("graph [ node [ id 0 ] ]", "", "gml"), ("graph\n[", "", "gml"), ('Creator "x"\ngraph [', "", "gml"),
    ("<graphml>", "", "graphml"), ("[1]", "", "json"), ('{"joints": []}', "", "json"),
    ("0,1\n1,0", "", "matrix"), ("0;1\n1;0", "", "matrix"), ("0\t1\n1\t0", "", "matrix"),
    ("index  joints\n-----  ------\n1  0-1 1-2 2-0\n", "", "table"),
    ("root:x", "", "unknown"), ("0-1\n0 1", "", "unknown"),
    ("anything", ".GML", "gml"), ("anything", ".gv", "dot"), ("anything", ".jsonl", "json"), ("x", ".tsv", "matrix"),
    ("0-1 1-2 2-0", ".txt", "text"),
])
def test_the_format_of_a_text(text, suffix, kind):
    assert exchange.detect(text, suffix) == kind


@pytest.mark.parametrize("call,kind,sentence", [
    (lambda: exchange.read_text("0-1", "xml"), InvalidOption, f"chains are read from {_FORMATS}, not 'xml'"),
    (lambda: exchange.read_text("  \n"), MalformedChain, "the input is empty: no chain to read"),
    (lambda: exchange.read_text("root:x:0", source="f.txt"), MalformedChain,
     "cannot tell what f.txt holds: it is not a joint list, JSON, GraphML, GML, DOT, an edge list or a CSV matrix "
     "(name its format)"),
    (lambda: exchange.read(5), MalformedChain, "a chain is given as a Chain, a graph, a file or text, not int"),
    (lambda: exchange.read_chain("0-1 1-2 2-0\n0-1 1-2 2-3 3-0"), MalformedChain,
     "the chain given holds 2 chains, and one is read here"),
    (lambda: exchange.read_chain('{"joints": [[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0]], "h": 5}', 4), MalformedChain,
     "the chain given states motion space h = 5, and --h 4 was given: leave out --h (the chain's own h is used) or "
     "give --h 5"),
    (lambda: exchange.write([], "csv"), InvalidOption,
     "chains are written as text, json, graphml, gml, dot, edgelist, adjacency, incidence here (a CSV listing by the "
     "commands' --format csv), not 'csv'"),
])
def test_refusals_in_full(call, kind, sentence):
    assert refused(kind, call) == sentence


def test_files_and_folders(tmp_path, monkeypatch):
    (tmp_path / "bad.bin").write_bytes(b"\xff\xfe")
    (tmp_path / "nul.txt").write_bytes(b"0-1\x00")
    (tmp_path / "empty").mkdir()
    cases = [(tmp_path / "none.txt", f"no file {tmp_path / 'none.txt'}"),
             (tmp_path / "empty", f"the folder {tmp_path / 'empty'} holds no file of chains"),
             (tmp_path / "bad.bin", f"{tmp_path / 'bad.bin'} is not a text file (not UTF-8): chains are read from text "
                                    f"formats ({_FORMATS})"),
             (tmp_path / "nul.txt", f"{tmp_path / 'nul.txt'} is a binary file: chains are read from text formats ({_FORMATS})")]
    for path, sentence in cases:
        assert refused(MalformedChain, exchange.read_file, path) == sentence
    big = tmp_path / "big.txt"
    big.write_text("0-1 1-2 2-0\n" * (3 * 2**20 // 12 + 1))
    monkeypatch.setattr(exchange, "_MAX_BYTES", 2**20)
    too_large = "is 3 MiB: files of chains are read up to 1 MiB (split it)"
    assert refused(MalformedChain, exchange.read_file, big) == f"{big} {too_large}"
    (tmp_path / "folder").mkdir()
    big.rename(tmp_path / "folder" / "big.txt")
    # a folder is read file by file, and the large one is refused
    assert refused(MalformedChain, exchange.read_file, tmp_path / "folder") == f"{tmp_path / 'folder' / 'big.txt'} {too_large}"


def test_a_linkage_file_is_read_as_its_chain_and_frame(tmp_path):
    # what 'move --save' and 'dimension --save' write, given to identify: their chain with its frame (a TOML scene
    # was once read as JSON, "JSON takes no '#' comment"; a linkage JSON as "a chain object needs 'joints'")
    from synth.motion import Linkage

    stephenson = Mechanism(Chain.parse("0-2 0-3 0-4 1-2 1-3 1-5 4-5"), 4)
    points = [[0, 0], [1, 2], [3, 0], [4, 2], [5, 1], [2, 3], [6, 3]]
    (tmp_path / "moved.json").write_text(Linkage(stephenson, (2,), points).to_json())
    (tmp_path / "found.toml").write_text('# by dimension --save\n[scene]\nname = "found"\n\n[linkage]\n'
                                         'chain = "0-1 1-2 2-3 3-0"\nframe = 2\ninputs = ["2-3"]\n'
                                         'points = { "0-1" = [0, 0], "1-2" = [1, 1], "2-3" = [3, 1], "0-3" = [4, 0] }\n')
    (tmp_path / "result.json").write_text('{"kind": "path", "chain": "0-1 0-3 1-2 2-3", "linkage": '
                                          '{"chain": "0-1 1=2 2-3 3-0", "frame": 1, "inputs": ["1-2"], "points": '
                                          '{"0-1": [0, 0], "0-3": [4, 0], "1=2": [1, 1], "2-3": [3, 2]}, '
                                          '"slides": {"1=2": [1, 0]}}}')
    read = {path: [(e.chain.compact(), e.frame) for e in exchange.read_file(tmp_path / path)]
            for path in ("moved.json", "found.toml", "result.json")}
    assert read == {"moved.json": [("0-2 0-3 0-4 1-2 1-3 1-5 4-5", 4)], "found.toml": [("0-1 0-3 1-2 2-3", 2)],
                    "result.json": [("0-1 0-3 1=2 2-3", 1)]}
    (tmp_path / "grid.toml").write_text('name = "small"\ndof = "1..3"\nlinks = "4..10"\n')
    assert refused(MalformedChain, exchange.read_file, tmp_path / "grid.toml") == (
        f"{tmp_path / 'grid.toml'} holds no chain: a TOML file is read for the chain of its [linkage] table (a linkage "
        "or a scene that moves one); this one holds name, dof, links")
    (tmp_path / "typo.toml").write_text('[scene]\nname = "t"\n[linkage]\nchian = "0-1 1-2 2-3 3-0"\nframe = 0\n')
    assert refused(MalformedChain, exchange.read_file, tmp_path / "typo.toml") == (
        f"{tmp_path / 'typo.toml'}: its [linkage] table has no chain (a joint list, chain = \"0-1 1-2 2-3 3-0\"); it has "
        "chian, frame")
    (tmp_path / "bad.toml").write_text('[linkage]\nchain = "0-1 1-1"\nframe = 0\ninputs = []\npoints = {}\n')
    assert refused(MalformedChain, exchange.read_file, tmp_path / "bad.toml").startswith(
        f"{tmp_path / 'bad.toml'}: the linkage's chain cannot be read: ")


@pytest.mark.parametrize("change, sentence", [
    # a NaN point and a misspelt entry were passed over: only the chain and frame were read
    (('"2-3" = [3, 1]', '"2-3" = [nan, 1]'), "the position of joint 2-3 is not finite: [nan, 1]"),
    (("[linkage.tracers]", "[linkage.tracer]"), "a linkage has no entry 'tracer' (it has chain, frame, inputs, "
                                                "points, slides, meshes, tracers)"),
    (("at = [2, 2]", "att = [2, 2]"), "'tracers' must map each name to {link = L, at = [x, y]}"),
])
def test_a_linkage_file_is_read_whole_as_move_reads_it(tmp_path, change, sentence):
    text = ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1"]\n'
            'points = { "0-1" = [0, 0], "1-2" = [1, 1], "2-3" = [3, 1], "0-3" = [4, 0] }\n'
            '[linkage.tracers]\nP = { link = 2, at = [2, 2] }\n')
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(text)
    bad.write_text(text.replace(*change))
    assert [e.chain.compact() for e in exchange.read_file(good)] == ["0-1 0-3 1-2 2-3"]
    assert refused(MalformedChain, exchange.read_file, bad) == f"{bad}: {sentence}"


def test_a_folder_is_read_in_name_order_without_hidden_files(tmp_path):
    (tmp_path / "b.txt").write_text("0-1 1-2 2-3 3-0\n")
    (tmp_path / "a.edges").write_text("0 1\n1 2\n2 0\n")
    (tmp_path / ".hidden").write_text("not a chain")
    (tmp_path / "sub").mkdir()
    read = [(e.chain.compact(), e.source) for e in exchange.read_file(tmp_path)]
    assert read == [("0-1 0-2 1-2", f"{tmp_path / 'a.edges'} line 1"), ("0-1 0-3 1-2 2-3", str(tmp_path / "b.txt"))]
    assert [e.chain.compact() for e in exchange.read(str(tmp_path / "b.txt"))] == ["0-1 0-3 1-2 2-3"]
    assert [e.chain.compact() for e in exchange.read(tmp_path / "b.txt")] == ["0-1 0-3 1-2 2-3"]
    # one word, no joint list: a path, said to be missing
    assert refused(MalformedChain, exchange.read, str(tmp_path / "missing.txt")) == f"no file {tmp_path / 'missing.txt'}"


def test_what_each_source_reads_as(monkeypatch):
    four = Chain.parse("0-1 1-2 2-3 3-0")
    assert [(e.chain, e.source, e.frame, e.input_link, e.h) for e in exchange.read(Mechanism(four, 0, 1))] == [
        (four, "the mechanism", 0, 1, None)]
    assert [(e.chain, e.source, e.frame, e.h) for e in exchange.read(four)] == [(four, "the chain", None, None)]
    graph = nx.Graph([(0, 1), (1, 2), (2, 0)])
    (entry,) = exchange.read(graph)
    assert entry.chain == Chain.parse("0-1 1-2 2-0") and entry.source == "the graph"
    monkeypatch.setattr(sys, "stdin", io.StringIO("0-1 1-2 2-0\n0-1 1-2 2-3 3-0\n"))
    assert [e.source for e in exchange.read("-")] == ["standard input line 1", "standard input line 2"]
    assert [e.source for e in exchange.read("0-1 1-2 2-0")] == ["the chain given"]
    assert [e.chain.compact() for e in exchange.read("0 1\n1 2\n2 0")] == ["0-1 0-2 1-2"]
    assert [e.chain.compact() for e in exchange.read('[[0, 1], [1, 2], [2, 0]]', "json")] == ["0-1 0-2 1-2"]
    (long,) = exchange.read("x" * 5000 + " y")  # a name too long for a file: text, an edge list of one joint
    assert (long.chain.compact(), long.source, long.names) == ("0-1", "the chain given line 1", ("x" * 5000, "y"))


def test_each_format_read_when_named():
    text = "0,1,1\n1,0,1\n1,1,0\n"
    assert [e.chain.compact() for e in exchange.read_text(text, "adjacency")] == ["0-1 0-2 1-2"]
    assert [e.chain.compact() for e in exchange.read_text("1,1,0\n1,0,1\n0,1,1\n", "incidence")] == ["0-1 0-2 1-2"]
    assert [e.chain.compact() for e in exchange.read_text("index,joints\n1,0-1 1-2 2-0\n", "csv")] == ["0-1 0-2 1-2"]
    assert [e.chain.compact() for e in exchange.read_text("index,joints\n1,0-1 1-2 2-0\n")] == ["0-1 0-2 1-2"]
    assert [e.chain.compact() for e in exchange.read_text("0 1\n1 2\n2 0\n", "edgelist")] == ["0-1 0-2 1-2"]
    assert [e.chain.compact() for e in exchange.read_text("graph { 0 -- 1; 1 -- 2; 2 -- 0 }", "dot")] == ["0-1 0-2 1-2"]
    one = exchange.read_chain("0-1 1-2 2-3 3-0  # frame 0")
    assert (one.chain.compact(), one.frame, one.chain.h) == ("0-1 0-3 1-2 2-3", 0, 3)


def test_what_is_written():
    chains = [Chain.parse("0-1 1-2 2-0"), Chain.parse("0-1 1=2 2-0")]
    out = io.StringIO()
    assert exchange.write(chains, "edgelist", out) == 2
    blocks = out.getvalue().split("\n\n")
    assert len(blocks) == 2 and blocks[0].endswith("0 1\n0 2\n1 2") and blocks[1].endswith("1 2 prismatic\n")
    assert exchange.write([], "edgelist", io.StringIO()) == 0
    assert exchange.text_of(chains, "text") == "0-1 0-2 1-2\n0-1 0-2 1=2\n"
    assert exchange.text_of(chains[:1], "adjacency").splitlines()[2:] == ["link,0,1,2", "0,0,1,1", "1,1,0,1", "2,1,1,0"]
    for fmt in exchange.WRITTEN:
        assert [e.chain for e in exchange.read_text(exchange.text_of(chains, fmt), fmt if fmt in
                                                    ("adjacency", "incidence") else None)] == chains


def test_a_named_format_and_a_path_with_a_space(tmp_path):
    """K4's adjacency matrix read as what it is, and as the incidence matrix it is named (four joints of three
    links each); a file whose name has a space is still a file; a JSON array of joints is a chain; a listing's
    bad row is named with its source."""
    path = tmp_path / "k4.csv"
    path.write_text("0,1,1,1\n1,0,1,1\n1,1,0,1\n1,1,1,0\n")
    assert [e.chain.compact() for e in exchange.read(str(path))] == ["0-1 0-2 0-3 1-2 1-3 2-3"]
    assert [e.chain.compact() for e in exchange.read(str(path), "incidence")] == ["0-1-2 0-1-3 0-2-3 1-2-3"]
    spaced = tmp_path / "my chains.txt"
    spaced.write_text("0-1 1-2 2-3 3-0\n")
    assert [(e.chain.compact(), e.source) for e in exchange.read(str(spaced))] == [("0-1 0-3 1-2 2-3", str(spaced))]
    assert exchange.read_chain("[[0, 1], [1, 2], [2, 0]]").chain == Chain.parse("0-1 1-2 2-0")
    framed = exchange.read_chain('[{"joints": [[0, 1], [1, 2], [2, 3], [3, 0]], "frame": 0}]')  # an array of one row
    assert (framed.chain, framed.frame, framed.source) == (Chain.parse("0-1 1-2 2-3 3-0"), 0, "the chain given row 1")
    assert refused(MalformedChain, exchange.read_text, "index,joints\n1,0-1 1-x\n", source="f.csv").startswith(
        "f.csv row 1: cannot read joint '1-x'")
