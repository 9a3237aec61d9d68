"""Chains in Graphviz DOT, written and read here (no pydot or pygraphviz needed).

The writer gives the incidence graph of :func:`~synth.exchange._graphs.to_graph` with drawing
hints (links as boxes, joints as small circles; a prismatic pair as a box, a gear mesh as a
double circle), so ``dot -Tsvg`` shows it.  The reader takes the DOT language of Graphviz:
``graph``/``digraph`` (``strict`` too), several graphs a file, node and edge statements with
attribute lists, edge chains ``a -- b -- c``, subgraphs and ``{ … }`` groups as edge ends,
``graph``/``node``/``edge`` defaults, ``ID = ID`` graph attributes, quoted, HTML and numeral
IDs, ``+`` concatenation, ports, and ``//``, ``/* */`` and ``#`` comments.  Each graph becomes a
networkx multigraph read by :func:`~synth.exchange._graphs.from_graph`.

Example
-------
>>> [e.chain.compact() for e in read_dot('graph { a -- b -- c; c -- a [kind=prismatic] }', "d")]
['0-1 0=2 1-2']
"""

from __future__ import annotations

import re

from ..errors import MalformedChain
from ..structure.chain import Mechanism
from ..structure.joints import JointKind
from ._entry import Entry

__all__ = ["read_dot", "write_dot"]

_TOKEN = re.compile(r"""
    (?P<space>\s+|//[^\n]*|/\*.*?\*/|^\#[^\n]*)
  | (?P<string>"(?:[^"\\]|\\.)*")
  | (?P<html><)
  | (?P<edge>--|->)
  | (?P<punct>[{}\[\];,=:+])
  | (?P<id>[A-Za-z_\x80-\uffff][A-Za-z_0-9\x80-\uffff]*|-?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?))
""", re.VERBOSE | re.DOTALL | re.MULTILINE)
_KEYWORDS = {"graph", "digraph", "strict", "node", "edge", "subgraph"}
_PLAIN = re.compile(r"^[A-Za-z_][A-Za-z_0-9]*$|^-?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)$")


def _tokens(text: str, source: str) -> list[tuple[str, str]]:
    out, i = [], 0
    while i < len(text):
        m = _TOKEN.match(text, i)
        if not m:
            line = text.count("\n", 0, i) + 1
            raise MalformedChain(f"{source}: not DOT: cannot read {text[i:i + 12]!r} on line {line}")
        kind = m.lastgroup
        if kind == "html":  # <...> with nested angle brackets, as one ID
            depth, j = 0, i
            while j < len(text):
                depth += {"<": 1, ">": -1}.get(text[j], 0)
                j += 1
                if depth == 0:
                    break
            if depth:
                raise MalformedChain(f"{source}: not DOT: an HTML label '<…' is never closed")
            out.append(("id", text[i + 1:j - 1]))
            i = j
            continue
        if kind == "string":
            out.append(("id", re.sub(r'\\(["\\])', r"\1", m.group()[1:-1]).replace("\\\n", "")))
        elif kind == "id":
            word = m.group()
            out.append(("kw", word.lower()) if word.lower() in _KEYWORDS else ("id", word))
        elif kind != "space":
            out.append((kind, m.group()))
        i = m.end()
    return out


class _Parser:
    def __init__(self, tokens, source):
        self.tokens, self.i, self.source = tokens, 0, source

    def peek(self, ahead=0):
        j = self.i + ahead
        return self.tokens[j] if j < len(self.tokens) else ("end", "")

    def take(self, kind=None, value=None):
        token = self.peek()
        if (kind and token[0] != kind) or (value and token[1] != value):
            want = value or kind
            got = token[1] or "the end of the text"
            raise MalformedChain(f"{self.source}: not DOT: expected {want!r}, found {got!r}")
        self.i += 1
        return token

    def ident(self) -> str:
        text = self.take("id")[1]
        while self.peek() == ("punct", "+"):
            self.i += 1
            text += self.take("id")[1]
        return text

    def attrs(self) -> dict:
        found = {}
        while self.peek() == ("punct", "["):
            self.i += 1
            while self.peek() != ("punct", "]"):
                key = self.ident()
                self.take("punct", "=")
                found[key] = self.ident()
                if self.peek()[1] in (",", ";"):
                    self.i += 1
            self.take("punct", "]")
        return found

    def graphs(self) -> list:
        import networkx as nx

        out = []
        while self.peek()[0] != "end":
            if self.peek() == ("kw", "strict"):
                self.i += 1
            kind = self.take("kw")[1]
            if kind not in ("graph", "digraph"):
                raise MalformedChain(f"{self.source}: not DOT: a graph starts with 'graph' or 'digraph', not {kind!r}")
            if self.peek()[0] == "id":
                self.ident()
            g = nx.MultiGraph()
            self.block(g, {}, {})
            out.append(g)
        return out

    def block(self, g, node_defaults: dict, edge_defaults: dict) -> list:
        """``{ stmt … }``: the statements into ``g``; returns the nodes named inside."""
        node_defaults, edge_defaults = dict(node_defaults), dict(edge_defaults)
        self.take("punct", "{")
        named: list = []
        while self.peek() != ("punct", "}"):
            token = self.peek()
            if token[0] == "kw" and token[1] in ("graph", "node", "edge"):
                self.i += 1
                values = self.attrs()
                {"graph": g.graph, "node": node_defaults, "edge": edge_defaults}[token[1]].update(values)
            elif token[0] == "id" and self.peek(1) == ("punct", "="):
                key = self.ident()
                self.take("punct", "=")
                g.graph[key] = self.ident()
            else:
                ends = [self.operand(g, node_defaults, edge_defaults, named)]
                while self.peek()[0] == "edge":
                    self.i += 1
                    ends.append(self.operand(g, node_defaults, edge_defaults, named))
                values = self.attrs()
                if len(ends) == 1:
                    for node in ends[0]:
                        g.nodes[node].update(values)
                for a_side, b_side in zip(ends, ends[1:]):
                    for a in a_side:
                        for b in b_side:
                            g.add_edge(a, b, **{**edge_defaults, **values})
            if self.peek()[1] in (";", ","):
                self.i += 1
        self.take("punct", "}")
        return named

    def operand(self, g, node_defaults, edge_defaults, named) -> list:
        if self.peek() == ("kw", "subgraph") or self.peek() == ("punct", "{"):
            if self.peek() == ("kw", "subgraph"):
                self.i += 1
                if self.peek()[0] == "id":
                    self.ident()
            inner = self.block(g, node_defaults, edge_defaults)
            named += inner
            return inner
        name = self.ident()
        while self.peek() == ("punct", ":"):  # a port: name:port[:compass]
            self.i += 1
            self.ident()
        if name not in g:
            g.add_node(name, **node_defaults)
        named.append(name)
        return [name]


def read_dot(text: str, source: str) -> list[Entry]:
    """Every graph of a DOT text as a chain (see the module docstring)."""
    from ._graphs import from_graph

    graphs = _Parser(_tokens(text, source), source).graphs()
    if not graphs:
        raise MalformedChain(f"{source}: not DOT: no 'graph {{ … }}'")
    out = []
    for i, g in enumerate(graphs, start=1):
        for node, data in g.nodes(data=True):  # DOT values are text: numbers where they are numbers
            for key in ("number", "multiplicity"):
                if re.fullmatch(r"-?\d+", str(data.get(key, ""))):
                    data[key] = int(data[key])
        for key in ("frame", "input_link"):
            if re.fullmatch(r"-?\d+", str(g.graph.get(key, ""))):
                g.graph[key] = int(g.graph[key])
        out.append(from_graph(g, f"{source} graph {i}" if len(graphs) > 1 else source))
    return out


def _quoted(value) -> str:
    text = str(value)
    return text if _PLAIN.match(text) and text.lower() not in _KEYWORDS else '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _attr_list(values: dict) -> str:
    return "[" + ", ".join(f"{k}={_quoted(v)}" for k, v in values.items()) + "]"


def write_dot(items, out) -> int:
    """Write chains or mechanisms as DOT, one ``graph`` each (see the module docstring)."""
    from ._graphs import to_graph

    count = 0
    for item in items:
        g = to_graph(item)
        count += 1
        out.write(f"graph chain_{count} {{\n")
        caption = f"{g.graph['code']}  id {g.graph['chain_id']}"
        if isinstance(item, Mechanism):
            caption += f"  frame {item.frame}"
        for key, value in {"label": caption, **g.graph}.items():
            out.write(f"  {key}={_quoted(value)};\n")
        out.write('  node [fontsize=10];\n')
        for node, data in g.nodes(data=True):
            if data["kind"] == "link":
                style = {"shape": "box", "label": str(data["number"])}
                if isinstance(item, Mechanism) and data["number"] == item.frame:
                    style["style"] = "filled"
            else:
                style = {"shape": JointKind(data["joint_kind"]).graph_shape, "label": "", "width": 0.15, "height": 0.15}
            out.write(f"  {node} {_attr_list({**data, **style})};\n")
        for a, b in g.edges():
            joint, link = (a, b) if a.startswith("J") else (b, a)
            out.write(f"  {joint} -- {link};\n")
        out.write("}\n")
    return count
