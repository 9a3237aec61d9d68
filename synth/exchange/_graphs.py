"""Chains as graphs: networkx graphs, GraphML and GML (written and read by networkx).

A chain is written as its *link–joint incidence graph*: a node ``L<i>`` for each link (``kind``
``link``, ``number`` i) and a node ``J<k>`` for each joint (``kind`` ``joint``, ``number`` k,
``joint_kind`` revolute/prismatic/mesh, ``multiplicity``), an edge where a joint holds a link;
the graph carries the code, ``chain_id``, the certificate, W, K and h (a mechanism also its
``frame``).  This graph holds multiple joints and joint kinds exactly.

Graphs from other tools are read either way: as an incidence graph when its nodes say which
are links and joints (``kind`` = ``link``/``joint``), otherwise as a *link graph* whose nodes are
the links and whose edges are the joints (edge attribute ``kind``, ``joint_kind`` or ``type``:
revolute, prismatic, mesh; edges sharing a ``joint`` attribute form one multiple joint).  The
graph attributes ``h``, ``frame`` and ``input_link`` are read back where a graph has them.

Example
-------
>>> from synth.structure.chain import Chain
>>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
>>> from_graph(to_graph(watt), "g").chain == watt
True
>>> import networkx as nx
>>> from_graph(nx.cycle_graph(4), "c4").chain.compact()
'0-1 0-3 1-2 2-3'
"""

from __future__ import annotations

import re

from ..errors import MalformedChain
from ..structure.chain import Chain, Mechanism, chain_id
from ..structure.joints import REVOLUTE
from ._entry import Entry, entry_of, kind_of

__all__ = ["describe", "to_graph", "from_graph", "read_graphml", "write_graphml", "read_gml", "write_gml"]


def describe(item: Chain | Mechanism) -> dict:
    """The chain's (or mechanism's) identity as graph attributes: code, chain_id, certificate(s),
    W, K, h, and the frame (and input link) of a mechanism."""
    chain = item.chain if isinstance(item, Mechanism) else item
    info = {"code": str(chain.code) + chain.kind_suffix, "id": chain_id(chain.certificate),
            "certificate": chain.certificate, "dof": chain.dof, "loops": chain.loops, "h": chain.h}
    if isinstance(item, Mechanism):
        info.update(frame=item.frame, mechanism_certificate=item.certificate)
        if item.input_link is not None:
            info["input_link"] = item.input_link
    return info


def to_graph(item: Chain | Mechanism):
    """The incidence graph of a chain or mechanism with string node names and every attribute
    (see the module docstring): what GraphML, GML and DOT files hold."""
    import networkx as nx

    chain = item.chain if isinstance(item, Mechanism) else item
    info = describe(item)
    info["chain_id"] = info.pop("id")  # GraphML takes a graph's 'id' for its element id
    g = nx.Graph(**info)
    for i in range(chain.links):
        g.add_node(f"L{i}", kind="link", number=i)
    for k, (joint, kind) in enumerate(zip(chain.joints, chain.kinds)):
        g.add_node(f"J{k}", kind="joint", number=k, joint_kind=kind.value, multiplicity=len(joint))
        g.add_edges_from((f"J{k}", f"L{x}") for x in joint)
    return g


def _link_name(g, node):
    number = g.nodes[node].get("number")
    if isinstance(number, int) and not isinstance(number, bool):
        return number
    if isinstance(node, tuple) and len(node) == 2 and isinstance(node[1], int):  # Chain.to_networkx
        return node[1]
    return node


def _incidence(g, source: str, role: dict) -> Entry:
    links = [n for n in g if role[n] == "link"]
    joint_nodes = [n for n in g if role[n] == "joint"]
    other = [n for n in g if role[n] not in ("link", "joint")]
    if other:
        raise MalformedChain(f"{source}: node {other[0]} is neither a link nor a joint (its 'kind' is "
                             f"{g.nodes[other[0]].get('kind')!r}) in a link–joint incidence graph")
    names = {n: _link_name(g, n) for n in links}
    if len({str(v) for v in names.values()}) < len(names):
        names = {n: n for n in links}  # 'number' attributes that repeat: the node names instead
    for a, b in g.edges():
        if role[a] == role[b]:
            raise MalformedChain(f"{source}: nodes {a} and {b} are both {role[a]}s: in an incidence graph a "
                                 "joint holds links")
    joint_nodes.sort(key=lambda n: str(_link_name(g, n)))  # (a chain sorts its joints: any fixed order)
    joints, kinds = [], []
    for node in joint_nodes:
        held = [names[x] for x in g.neighbors(node)]
        if g.is_multigraph() and len(held) != g.degree(node):
            twice = next(x for x in g.neighbors(node) if g.number_of_edges(node, x) > 1)
            raise MalformedChain(f"{source}: joint {node} holds link {names[twice]} twice: a link is joined to "
                                 "itself")
        if len(held) < 2:
            raise MalformedChain(f"{source}: joint {node} holds {len(held)} link{'s' * (len(held) != 1)}: a joint "
                                 "joins two links or more")
        data = g.nodes[node]
        kind = data.get("joint_kind", data.get("type", REVOLUTE))
        joints.append(held)
        kinds.append(kind_of(kind, f"{source}, joint {node}"))
    return entry_of(joints, kinds, source, links=list(names.values()), **_stated(g))


def _link_graph(g, source: str) -> Entry:
    loops = [a for a, b in g.edges() if a == b]
    if loops:
        raise MalformedChain(f"{source}: link {loops[0]} is joined to itself (an edge from {loops[0]} to "
                             f"{loops[0]}): a joint joins different links")
    grouped: dict = {}
    joints, kinds = [], []
    for a, b, data in g.edges(data=True):
        kind = kind_of(data.get("kind", data.get("joint_kind", data.get("type", REVOLUTE))),
                       f"{source}, edge {a}-{b}")
        group = data.get("joint")
        if group is None:
            joints.append([a, b])
            kinds.append(kind)
            continue
        if group not in grouped:
            grouped[group] = len(joints)
            joints.append([a, b])
            kinds.append(kind)
        else:
            k = grouped[group]
            joints[k] += [x for x in (a, b) if x not in joints[k]]
            if kinds[k] != kind or kind != REVOLUTE:
                raise MalformedChain(f"{source}: joint {group} joins three links or more and is a pin (revolute), "
                                     "not a " + (kind if kind != REVOLUTE else kinds[k]) + " pair")
    return entry_of(joints, kinds, source, links=list(g.nodes), **_stated(g))


def _stated(g) -> dict:
    """What a graph's attributes say of its chain beyond the joints: frame, input link, motion space."""
    return dict(frame=g.graph.get("frame"), input_link=g.graph.get("input_link"), h=g.graph.get("h"))


def from_graph(g, source: str = "graph") -> Entry:
    """Read a networkx graph as a chain: an incidence graph when its nodes carry ``kind`` =
    ``link``/``joint`` (as :meth:`Chain.to_networkx` and :func:`to_graph` write), else a link graph.

    Raises
    ------
    MalformedChain
        One sentence naming ``source``: a link joined to itself, a joint on one link, two joints
        on the same links, a link in no joint, a node that is neither link nor joint.
    """
    if g.number_of_nodes() == 0:
        raise MalformedChain(f"{source}: the graph is empty: a chain has links and joints")
    role = {n: str(g.nodes[n].get("kind", "")).lower() for n in g}
    if any(r in ("link", "joint") for r in role.values()):
        return _incidence(g, source, role)
    return _link_graph(g, source)


# -------------------------------------------------------------------- GraphML
def _graphml_header(keys) -> str:
    from xml.etree.ElementTree import tostring

    return ('<?xml version="1.0" encoding="utf-8"?>\n<graphml xmlns="http://graphml.graphdrawing.org/xmlns" '
            'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation='
            '"http://graphml.graphdrawing.org/xmlns http://graphml.graphdrawing.org/xmlns/1.0/graphml.xsd">\n'
            + "".join("  " + tostring(k, encoding="unicode").strip() + "\n" for k in keys))


def _graph_element(item):
    """networkx's GraphML of one graph: its key elements and its graph element."""
    from networkx.readwrite.graphml import GraphMLWriter

    writer = GraphMLWriter(named_key_ids=True)
    writer.add_graph_element(to_graph(item))
    keys = [e for e in writer.xml if e.tag == "key"]
    graph = next(e for e in writer.xml if e.tag == "graph")
    writer.indent(graph, level=1)
    return keys, graph


def write_graphml(items, out) -> int:
    """Write chains or mechanisms as one GraphML document, a ``<graph>`` each, as they come
    (networkx writes each graph; the keys are declared once, those of a mechanism with every attribute)."""
    from xml.etree.ElementTree import tostring

    count, known = 0, None
    for item in items:
        keys, graph = _graph_element(item)
        if known is None:
            every, _ = _graph_element(Mechanism(Chain.parse("0-1 1-2 2-0"), 0, 1))
            known = {k.get("id") for k in every}
            out.write(_graphml_header(sorted(every, key=lambda k: (k.get("for"), k.get("id")))))
        missing = {k.get("id") for k in keys} - known
        if missing:  # every graph has the same attributes: a new one is a bug of to_graph
            raise RuntimeError(f"GraphML key(s) {sorted(missing)} were not declared")
        out.write("  " + tostring(graph, encoding="unicode").strip() + "\n")
        count += 1
    if known is None:
        out.write(_graphml_header([]))
    out.write("</graphml>\n")
    return count


def read_graphml(text: str, source: str) -> list[Entry]:
    """Every graph of a GraphML document, read with networkx."""
    from xml.etree.ElementTree import ParseError

    import networkx as nx
    from networkx.readwrite.graphml import GraphMLReader

    try:
        graphs = list(GraphMLReader(node_type=str)(string=text))
    except (ParseError, nx.NetworkXError, ValueError, KeyError, TypeError) as exc:
        raise MalformedChain(f"{source}: not a GraphML document networkx can read ({_first_line(exc)})") from None
    if not graphs:
        raise MalformedChain(f"{source}: the GraphML document holds no graph")
    many = len(graphs) > 1
    return [from_graph(g, f"{source} graph {i}" if many else source) for i, g in enumerate(graphs, start=1)]


# ------------------------------------------------------------------------ GML
def write_gml(items, out) -> int:
    """Write chains or mechanisms as GML, one ``graph [ … ]`` block each (networkx writes each)."""
    import networkx as nx

    count = 0
    for item in items:
        for line in nx.generate_gml(to_graph(item)):
            out.write(line + "\n")
        count += 1
    return count


def _gml_blocks(text: str) -> list[str]:
    """The top-level ``graph [ … ]`` blocks of a GML text (strings and nesting respected)."""
    blocks, depth, start = [], 0, None
    for m in re.finditer(r'"[^"]*"|\[|\]|\bgraph\b', text):
        token = m.group()
        if token == "[":
            depth += 1
        elif token == "]":
            depth -= 1
            if depth == 0 and start is not None:
                blocks.append(text[start:m.end()])
                start = None
            if depth < 0:
                return []
        elif token == "graph" and depth == 0:
            start = m.start()
    return blocks


def read_gml(text: str, source: str) -> list[Entry]:
    """Every ``graph [ … ]`` block of a GML text, read with networkx (nodes named by their
    ``label`` where each has its own, else by their ``id``)."""
    import networkx as nx

    blocks = _gml_blocks(text)
    if not blocks:
        raise MalformedChain(f"{source}: not GML: no 'graph [ … ]' block")
    out = []
    for i, block in enumerate(blocks, start=1):
        where = f"{source} graph {i}" if len(blocks) > 1 else source
        try:
            try:
                g = nx.parse_gml(block)  # nodes by their labels, where every node has its own
            except nx.NetworkXError:
                g = nx.parse_gml(block, label=None)
        except (nx.NetworkXError, ValueError, KeyError, TypeError) as exc:
            raise MalformedChain(f"{where}: not GML networkx can read ({_first_line(exc)})") from None
        out.append(from_graph(g, where))
    return out


def _first_line(exc: Exception) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
