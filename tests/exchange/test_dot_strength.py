"""DOT, written and read: quoting, HTML IDs, the place of a mistake, the drawing hints Graphviz reads."""

from __future__ import annotations

import io
import re

import pytest

from synth import Chain, MalformedChain, Mechanism
from synth.exchange import read_text, write
from synth.exchange._dot import _quoted, _tokens

#: Graphviz's own attributes the writer may set; the others are the chain's (ignored by Graphviz)
GRAPHVIZ = {"label", "shape", "width", "height", "style", "fontsize"}
CHAIN_DATA = {"kind", "number", "joint_kind", "multiplicity"}


@pytest.mark.parametrize("text", ['say "R"', "back\\slash", 'both \\"', "Graph", "NODE", "Subgraph", "x y", "2a"])
def test_a_quoted_value_reads_back_as_itself(text):
    """What the writer quotes is one ID to the reader, byte for byte: quotes, backslashes, keywords
    in any case (DOT's keywords are case-insensitive) and what no bare ID may hold."""
    assert _tokens(_quoted(text), "t") == [("id", text)]


def test_a_mistake_is_placed_on_its_line():
    for text, line in (("\n\ngraph { a -- b; ! }", 3), ("graph {\n a -- b;\n ! \n c -- a }\n", 3),
                       ("graph { ! }\n\n\n", 1)):
        with pytest.raises(MalformedChain, match=f"cannot read '! .*' on line {line}$"):
            read_text(text, "dot")


def test_html_ids_with_nested_brackets_are_names():
    (entry,) = read_text("graph { <<i>crank</i>> -- <b>; <b> -- c -- <<i>crank</i>> }", "dot")
    assert sorted(map(str, entry.names)) == ["<i>crank</i>", "b", "c"] and entry.chain.compact() == "0-1 0-2 1-2"
    with pytest.raises(MalformedChain, match="an HTML label '<…' is never closed"):
        read_text("graph { <<i>a</i> -- b }", "dot")


def _statements(text):
    """Each node statement of a DOT text the writer made: name -> {attribute: value}."""
    out = {}
    for name, body in re.findall(r"^  ([LJ]\d+) \[(.*)\];$", text, re.MULTILINE):
        out[name] = dict(re.findall(r'(\w+)=("[^"]*"|[^,\]]+)', body))
    return out


def test_the_drawing_hints_are_graphviz_attributes():
    """Links as boxes labelled with their numbers (the frame filled), joints as small unlabelled
    circles; every attribute either Graphviz's own (lower case, as Graphviz spells them) or the chain's."""
    mechanism = Mechanism(Chain.parse("0-1 1=2 2-3 3-0"), 3)
    out = io.StringIO()
    assert write([mechanism, Chain.parse("0-1 1-2 2-0")], "dot", out) == 2
    text = out.getvalue()
    assert re.findall(r"^graph (\w+) \{$", text, re.MULTILINE) == ["chain_1", "chain_2"]
    assert text.count("  node [fontsize=10];\n") == 2
    first = _statements(text.split("graph chain_2")[0])
    assert len(first) == 8  # four links, four joints
    for name, attrs in first.items():
        assert set(attrs) <= GRAPHVIZ | CHAIN_DATA, name
        if attrs["kind"] == "link":
            assert attrs["shape"] == "box" and attrs["label"] == attrs["number"]
            assert attrs.get("style") == ("filled" if attrs["number"] == "3" else None)
        else:
            assert attrs["label"] == '""' and attrs["width"] == attrs["height"] and float(attrs["width"]) <= 0.2
            assert attrs["shape"] == ("box" if attrs["joint_kind"] == "prismatic" else "circle")


def test_concatenated_ids_and_the_sentence_of_what_was_expected():
    (entry,) = read_text('graph { "cr" + "ank" -- b; b -- c; c -- crank }', "dot")
    assert sorted(entry.names) == ["b", "c", "crank"] and entry.chain.links == 3
    for text, words in (("graph { a -- b", "expected 'id', found 'the end of the text'"),
                        ("graph a -- b }", "expected '{', found '--'"),
                        ("graph { a -- b [color=red; }", "expected 'id', found '}'")):
        with pytest.raises(MalformedChain) as info:
            read_text(text, "dot")
        assert str(info.value) == "the input: not DOT: " + words


def test_an_attribute_without_its_equals_sign_and_the_graph_a_mistake_is_in():
    with pytest.raises(MalformedChain) as info:
        read_text("graph { a -- b [kind; P]; b -- c; c -- a }", "dot")
    assert str(info.value) == "the input: not DOT: expected '=', found ';'"
    with pytest.raises(MalformedChain) as info:
        read_text("graph { a -- b -- c -- a }\ngraph { x -- y; y -- x -- x }", "dot")
    assert str(info.value).startswith("the input graph 2: ") and "link x is joined to itself" in str(info.value)
    two = read_text("graph { a -- b -- c -- a }\ngraph { x -- y -- z -- x }", "dot")
    assert [e.source for e in two] == ["the input graph 1", "the input graph 2"]
