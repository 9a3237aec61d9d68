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


def test_the_incidence_graph_holds_what_the_format_documents():
    """A seven-link chain with a double joint 0-1-2: a node L<i> per link (kind link, number i) and
    J<k> per joint (kind joint, number k, its kind, its multiplicity), an edge where a joint holds a link."""
    from synth.exchange._graphs import to_graph

    chain = Chain.parse("0-1-2 2-3 3-4 4-0 1-5 5-6 6-3")
    g = to_graph(chain)
    assert {n: g.nodes[n] for n in g if n.startswith("L")} == {f"L{i}": {"kind": "link", "number": i}
                                                                for i in range(7)}
    joints = {n: g.nodes[n] for n in g if n.startswith("J")}
    assert joints == {f"J{k}": {"kind": "joint", "number": k, "joint_kind": "revolute", "multiplicity": len(j)}
                      for k, j in enumerate(chain.joints)}
    assert sorted(len(j) for j in chain.joints) == [2, 2, 2, 2, 2, 2, 3]
    assert {frozenset(g[f"J{k}"]) for k in range(len(chain.joints))} == {
        frozenset(f"L{x}" for x in j) for j in chain.joints}


def test_the_networkx_graph_of_a_chain_keeps_its_link_numbers():
    """Chain.to_networkx names its nodes ("link", i): read back, link i is link i, no names kept."""
    from synth.exchange._graphs import from_graph

    chain = Chain.parse("0=1 1-2 2-3 3-0")
    entry = from_graph(chain.to_networkx())
    assert entry.names is None and entry.chain == chain and entry.source == "graph"


def test_a_joint_holding_a_link_twice_is_named_whichever_link_it_is():
    g = nx.MultiGraph()
    g.add_nodes_from(["a", "b"], kind="link")
    g.add_node("j", kind="joint")
    g.add_edges_from([("j", "a"), ("j", "b"), ("j", "b")])
    with pytest.raises(MalformedChain) as info:
        read_text("\n".join(nx.generate_gml(g)), "gml")
    assert str(info.value) == "the input: joint j holds link b twice: a link is joined to itself"


def test_a_link_graph_at_fault_is_named():
    g = nx.Graph([(0, 1), (1, 2), (2, 0), (2, 2)])
    with pytest.raises(MalformedChain) as info:
        read_text(_graphml(g), "graphml")
    assert str(info.value) == ("the input: link 2 is joined to itself (an edge from 2 to 2): a joint joins "
                               "different links")
    g = nx.Graph([(0, 1), (1, 2), (2, 0)])
    g.add_node(7)
    with pytest.raises(MalformedChain) as info:
        read_text(_graphml(g), "graphml")
    assert str(info.value) == "the input: link 7 is in no joint: a chain's links are all jointed"
    # a slider first, then a pin, on one joint of three links: the slider is what it cannot be
    g = nx.Graph()
    g.add_edges_from([(0, 1, {"joint": "j", "kind": "prismatic"}), (1, 2, {"joint": "j"}), (2, 3, {}), (3, 0, {})])
    with pytest.raises(MalformedChain) as info:
        read_text(_graphml(g), "graphml")
    assert str(info.value).endswith("joint j joins three links or more and is a pin (revolute), not a prismatic pair")


def test_nodes_that_say_only_link_or_only_joint_make_an_incidence_graph():
    """One node role is enough to read a graph as an incidence graph: then two links (or two joints)
    on one edge are refused, where a link graph would have read them as a pin."""
    from synth.exchange._graphs import from_graph

    for role in ("link", "joint"):
        g = nx.Graph([("a", "b"), ("b", "c"), ("c", "a")])
        nx.set_node_attributes(g, role, "kind")
        with pytest.raises(MalformedChain) as info:
            from_graph(g)
        assert str(info.value) == f"graph: nodes a and b are both {role}s: in an incidence graph a joint holds links"


def test_graphml_is_written_indented_and_refuses_an_undeclared_key(monkeypatch):
    from synth.exchange import _graphs

    out = io.StringIO()
    write([Chain.parse("0-1 1-2 2-0")], "graphml", out)
    lines = out.getvalue().splitlines()
    assert [x for x in lines if "<graph " in x][0].startswith("  <graph ")
    assert all(x.startswith("  ") for x in lines[2:-1]) and lines[-1] == "</graphml>"
    plain = _graphs.to_graph

    def with_colour(item):  # a chain's graph with an attribute the mechanism's (which declares the keys) lacks
        g = plain(item)
        if isinstance(item, Chain):
            g.graph["colour"] = "red"
        return g

    monkeypatch.setattr(_graphs, "to_graph", with_colour)
    with pytest.raises(RuntimeError) as info:
        write([Chain.parse("0-1 1-2 2-0")], "graphml", io.StringIO())
    assert str(info.value) == "GraphML key(s) ['colour'] were not declared"


def test_gml_networkx_cannot_read_is_refused_with_its_reason():
    with pytest.raises(MalformedChain) as info:
        read_text("graph [ node [ id 0 label \"a\" ] node [ id 0 label \"b\" ] ]", "gml")
    assert str(info.value).startswith("the input: not GML networkx can read (")
    assert str(info.value).endswith(")") and "0" in str(info.value)
    from synth.exchange._graphs import _first_line

    assert (_first_line(ValueError("first\nsecond")), _first_line(ValueError(" ")), _first_line(KeyError())) == (
        "first", "ValueError", "KeyError")


def test_link_numbers_are_whole_numbers_else_the_nodes_are_named_by_their_ids():
    """A ``number`` that is no whole number (text, a truth value) does not name a link: its node id does."""
    from synth.exchange._graphs import from_graph

    g = nx.Graph()
    g.add_nodes_from([("a", {"kind": "link", "number": "first"}), ("b", {"kind": "link", "number": True}),
                      ("c", {"kind": "link", "number": "third"})])
    g.add_nodes_from(["j", "k", "m"], kind="joint")
    g.add_edges_from([("j", "a"), ("j", "b"), ("k", "b"), ("k", "c"), ("m", "c"), ("m", "a")])
    entry = from_graph(g)
    assert entry.names == ("a", "b", "c") and entry.chain == Chain.parse("0-1 1-2 2-0")


def test_gml_counts_what_it_writes_and_refuses_text_without_a_graph():
    out = io.StringIO()
    chains = [Chain.parse("0-1 1-2 2-0"), Chain.parse("0-1 1=2 2-3 3-0")]
    assert write(chains, "gml", out) == 2
    assert [e.chain for e in read_text(out.getvalue(), "gml")] == chains
    with pytest.raises(MalformedChain) as info:
        read_text("node [ id 0 ]", "gml")
    assert str(info.value) == "the input: not GML: no 'graph [ … ]' block"
