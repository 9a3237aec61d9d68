"""Graphs from other tools: a multiple joint by its edges' shared ``joint``, the refusals naming the
node or edge at fault, the names of the graphs of a document."""

from __future__ import annotations

import io

import networkx as nx
import pytest

from synth import Chain, MalformedChain
from synth.exchange import read_text, write


def _graphml(g) -> str:
    out = io.BytesIO()
    nx.write_graphml(g, out)
    return out.getvalue().decode()


def test_edges_sharing_a_joint_are_one_multiple_joint():
    """The Watt chain's ternary links 0 and 1 as one double joint 0-1-2: edges 0-1 and 1-2 both
    ``joint=j``; with a slider there, the refusal names the joint and the kind."""
    g = nx.Graph()
    g.add_edges_from([(0, 1, {"joint": "j"}), (1, 2, {"joint": "j"}), (2, 3, {}), (3, 0, {})])
    (entry,) = read_text(_graphml(g), "graphml")
    assert entry.chain.joints == Chain.parse("0-1-2 2-3 3-0").joints and entry.chain.v == 1
    g.edges[1, 2]["kind"] = "prismatic"
    with pytest.raises(MalformedChain) as info:
        read_text(_graphml(g), "graphml")
    assert str(info.value).endswith("joint j joins three links or more and is a pin (revolute), not a prismatic pair")


def test_an_incidence_graph_at_fault_is_named():
    g = nx.MultiGraph()
    g.add_nodes_from(["a", "b"], kind="link")
    g.add_node("j", kind="joint")
    g.add_node("w", kind="wheel")
    g.add_edges_from([("j", "a"), ("j", "b"), ("w", "a")])
    with pytest.raises(MalformedChain) as info:
        read_text(_graphml(nx.Graph(g)), "graphml")
    assert "node w is neither a link nor a joint (its 'kind' is 'wheel')" in str(info.value)
    h = nx.MultiGraph()
    h.add_nodes_from(["a", "b"], kind="link")
    h.add_node("j", kind="joint")
    h.add_edges_from([("j", "a"), ("j", "a"), ("j", "b")])
    text = "\n".join(nx.generate_gml(h))
    with pytest.raises(MalformedChain) as info:
        read_text(text, "gml")
    assert str(info.value) == "the input: joint j holds link a twice: a link is joined to itself"


def test_every_graph_of_a_document_is_named_and_counted():
    out = io.StringIO()
    chains = [Chain.parse("0-1 1-2 2-0"), Chain.parse("0-1 1-2 2-3 3-0")]
    assert write(chains, "graphml", out) == 2
    entries = read_text(out.getvalue(), "graphml")
    assert [e.source for e in entries] == ["the input graph 1", "the input graph 2"]
    assert [e.chain.certificate for e in entries] == [c.certificate for c in chains]
    (one,) = read_text(_graphml(nx.cycle_graph(4)), "graphml")
    assert one.source == "the input"
