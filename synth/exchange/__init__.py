"""Exchange chains with other tools: read and write the formats researchers use.

=============  ======================================================  ============
format         what it holds                                           read / write
=============  ======================================================  ============
``text``       joint lists ``0-1 1=2 2~3``, one chain a line           both
``json``       the rows the commands print (jsonl, json, a row)        both
``csv``        the rows of a listing in CSV (``--format csv``)         read
``table``      the rows of a listing as a table (``--format table``)   read
``graphml``    incidence graph, or a link graph, per ``<graph>``       both
``gml``        the same, one ``graph [ … ]`` block each                both
``dot``        the same in Graphviz DOT, one ``graph { … }`` each      both
``edgelist``   one joint a line (``0 1``, ``1 2 prismatic``)           both
``adjacency``  link adjacency matrix (CSV; simple joints)              both
``incidence``  link–joint incidence matrix (CSV)                       both
=============  ======================================================  ============

Joint kinds (revolute, prismatic, gear mesh) and multiple joints are kept by every format
except the adjacency matrix (simple joints only, a multiple joint refused); so are the motion
space h and a mechanism's frame and input link (graph attributes, ``# h 4`` and
``# frame 0, input 1`` lines, a row's fields).  A source that states no h is planar unless
:func:`in_motion_space` puts it elsewhere; one that states another h is refused there.  A file's format is told by its suffix
(``.graphml``, ``.gml``, ``.dot``/``.gv``, ``.csv``, ``.json``/``.jsonl``) or, failing that, by
its first characters; ``fmt`` names it outright.  The formats and their conventions are in
docs/exchange.md.

Example
-------
>>> import io
>>> from synth.structure.chain import Chain
>>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
>>> out = io.StringIO(); write([watt], "gml", out)
1
>>> read_text(out.getvalue())[0].chain == watt
True
"""

from __future__ import annotations

import io
import re
from pathlib import Path

from ..errors import InvalidOption, MalformedChain
from ..structure.chain import Chain, Mechanism
from ._dot import read_dot, write_dot
from ._entry import Entry, in_motion_space
from ._graphs import describe, from_graph, read_gml, read_graphml, to_graph, write_gml, write_graphml
from ._lists import (edge_words, looks_like_joint_list, looks_like_listing, looks_like_table, read_edgelist, read_json,
                     read_linkage_file, read_listing, read_table, read_text_lists, write_edgelist, write_lines)
from ._matrices import read_matrices, write_adjacency, write_incidence

__all__ = ["FORMATS", "WRITTEN", "Entry", "in_motion_space", "read_chain", "read", "read_file", "read_text", "detect",
           "write", "to_graph",
           "from_graph", "describe"]

FORMATS = ("text", "json", "csv", "table", "graphml", "gml", "dot", "edgelist", "adjacency", "incidence")
WRITTEN = ("graphml", "gml", "dot", "edgelist", "adjacency", "incidence")  # the listings write text, json, csv themselves
_SUFFIXES = {".graphml": "graphml", ".xml": "graphml", ".gml": "gml", ".dot": "dot", ".gv": "dot",
             ".json": "json", ".jsonl": "json", ".ndjson": "json", ".csv": "matrix", ".tsv": "matrix",
             ".edgelist": "edgelist", ".edges": "edgelist"}
_MAX_BYTES = 256 * 2**20  # a file of chains larger than this is refused before it is read


def detect(text: str, suffix: str = "") -> str:
    """The format of a text: from the file suffix where it says, else from the text itself
    (``matrix`` where an adjacency or incidence matrix is to be told apart by its shape).

    >>> detect("0-1 1-2 2-0"), detect("0 1\\n1 2\\n2 0\\n"), detect("graph { a -- b }"), detect("0,1\\n1,0")
    ('text', 'edgelist', 'dot', 'matrix')
    >>> detect("root:x:0:0:root:/root:/bin/bash")
    'unknown'
    """
    found = _SUFFIXES.get(suffix.lower())
    if found:
        return found
    start = re.sub(r"/\*.*?\*/|//[^\n]*|^\s*#[^\n]*", "", text[:4000], flags=re.DOTALL | re.MULTILINE)
    start = start.lstrip()[:200].lower()
    if start.startswith("<"):
        return "graphml"
    if start.startswith(("{", "[")):
        return "json"
    words = start.replace("\n", " ").split()
    if words[:1] == ["graph"] and ("[" in words[1:2] or start[5:].lstrip().startswith("[")):
        return "gml"
    if words[:1] in (["graph"], ["digraph"], ["strict"]) or start.startswith("creator"):
        return "gml" if start.startswith("creator") else "dot"
    if looks_like_table(text):
        return "table"
    lines = [ln.split("#", 1)[0].strip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln]
    if lines and all(looks_like_joint_list(ln) for ln in lines):
        return "text"
    if lines and all(("," in ln or ";" in ln or "\t" in ln) for ln in lines):
        return "matrix"
    if _spaced_matrix(lines):
        return "matrix"
    if lines and all(edge_words(ln.split("{", 1)[0]) is not None for ln in lines):
        return "edgelist"
    return "unknown"


def _spaced_matrix(lines: list[str]) -> bool:
    """Whether lines are the rows of a matrix written with spaces: rows of equal length (three
    numbers or more), each repeating a number — which no edge-list line can (a joint names
    different links), so the reading takes nothing away from edge lists.

    >>> _spaced_matrix(["0 1 1", "1 0 1", "1 1 0"]), _spaced_matrix(["0 1 2", "2 3 4"])
    (True, False)
    """
    rows = [ln.split() for ln in lines]
    return (len(rows) >= 2 and len({len(r) for r in rows}) == 1 and len(rows[0]) >= 3
            and all(w.isdigit() for r in rows for w in r) and all(len(set(r)) < len(r) for r in rows))


def read_text(text: str, fmt: str | None = None, source: str = "the input", suffix: str = "") -> list[Entry]:
    """Every chain of a text in ``fmt`` (detected when None).

    Raises
    ------
    MalformedChain
        One sentence naming ``source`` (and the line or graph) and what is wrong.
    InvalidOption
        An unknown ``fmt``.
    """
    if fmt is not None and fmt not in FORMATS:
        raise InvalidOption(f"chains are read from {', '.join(FORMATS)}, not {fmt!r}")
    if not text.strip():
        raise MalformedChain(f"{source} is empty: no chain to read")
    kind = fmt or detect(text, suffix)
    if kind == "unknown":
        raise MalformedChain(f"cannot tell what {source} holds: it is not a joint list, JSON, GraphML, GML, DOT, an "
                             "edge list or a CSV matrix (name its format)")
    if kind == "text":
        return read_text_lists(text, source)
    if kind == "json":
        return read_json(text, source)
    if kind == "graphml":
        return read_graphml(text, source)
    if kind == "gml":
        return read_gml(text, source)
    if kind == "dot":
        return read_dot(text, source)
    if kind == "edgelist":
        return read_edgelist(text, source)
    if kind == "csv" or (kind == "matrix" and looks_like_listing(text)):
        return read_listing(text, source)
    if kind == "table":
        return read_table(text, source)
    return read_matrices(text, source, None if kind == "matrix" else kind)


def read_file(path: str | Path, fmt: str | None = None) -> list[Entry]:
    """Every chain of a file (or of every file of a directory, in name order).

    Raises
    ------
    MalformedChain
        A file that is missing, unreadable, not text, too large, or not a chain in its format.
    """
    path = Path(path)
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.is_file() and not p.name.startswith("."))
        if not files:
            raise MalformedChain(f"the folder {path} holds no file of chains")
        return [e for f in files for e in read_file(f, fmt)]
    try:
        size = path.stat().st_size
        if size > _MAX_BYTES:
            raise MalformedChain(f"{path} is {size / 2**20:.0f} MiB: files of chains are read up to "
                                 f"{_MAX_BYTES // 2**20} MiB (split it)")
        data = path.read_bytes()
    except FileNotFoundError:
        raise MalformedChain(f"no file {path}") from None
    except OSError as exc:
        raise MalformedChain(f"cannot read {path}: {exc.strerror or exc}") from None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise MalformedChain(f"{path} is not a text file (not UTF-8): chains are read from text formats "
                             f"({', '.join(FORMATS)})") from None
    if "\x00" in text:
        raise MalformedChain(f"{path} is a binary file: chains are read from text formats ({', '.join(FORMATS)})")
    if path.suffix.lower() == ".toml" and fmt is None:  # a linkage or scene file (move --save, dimension --save)
        return read_linkage_file(text, str(path))
    return read_text(text, fmt, source=str(path), suffix=path.suffix)


def _own_space(chain: Chain) -> int | None:
    """The motion space a Chain object states: its h where it is not the default 3 (a chain built
    without h is put in another space by ``h=``)."""
    return None if chain.h == 3 else chain.h


def read(source, fmt: str | None = None) -> list[Entry]:
    """Chains from anything :func:`synth.identify` accepts: a :class:`Chain` or :class:`Mechanism`,
    a networkx graph, a path to a file or folder, or the text itself (a joint list, JSON, …).

    >>> [e.chain.compact() for e in read("0-1 1-2 2-3 3-0")]
    ['0-1 0-3 1-2 2-3']
    """
    if isinstance(source, Chain):
        return [Entry(source, None, None, "the chain", _own_space(source))]
    if isinstance(source, Mechanism):
        return [Entry(source.chain, source.frame, None, "the mechanism", _own_space(source.chain), source.input_link)]
    if hasattr(source, "nodes") and hasattr(source, "edges"):
        return [from_graph(source, "the graph")]
    if isinstance(source, Path):
        return read_file(source, fmt)
    if not isinstance(source, str):
        raise MalformedChain(f"a chain is given as a Chain, a graph, a file or text, not {type(source).__name__}")
    text = source.strip()
    if text == "-":
        import sys

        return read_text(sys.stdin.read(), fmt, source="standard input")
    if text.startswith(("{", "[")) or "\n" in text or not text:
        return read_text(source, fmt, source="the chain given")
    if len(text.split()) == 1 and not looks_like_joint_list(text):
        return read_file(text, fmt)  # a path (a missing one is said so)
    try:
        exists = Path(text).exists()
    except OSError:  # a name too long for a file: text
        exists = False
    return read_file(text, fmt) if exists else read_text(source, fmt, source="the chain given")


def read_chain(text: str, h: int | None = None, source: str = "the chain given") -> Entry:
    """One chain as a command line writes it — a joint list (``0-1 1=2 2~3``, a comment
    ``# frame F, h H`` allowed) or a JSON row — in motion space ``h`` where it states none
    (default: its own, 3 for a joint list).  ``analyze``, ``identify``, ``draw --chain`` and
    ``chains --chain`` read a chain this way.

    >>> read_chain("0=1 1=2 2=3 3=0").chain.dof, read_chain("0-1 1-2 2-3 3-4 4-5 5-0", 5).chain.dof
    (2, 1)

    Raises
    ------
    MalformedChain
        Not one chain, or a row stating another motion space than ``h``.
    """
    body = text.strip()
    entries = read_text(text, "json" if body.startswith(("{", "[")) else "text", source=source)
    if len(entries) != 1:
        raise MalformedChain(f"{source} holds {len(entries)} chains, and one is read here")
    return in_motion_space(entries[0], h)


_WRITERS = {"graphml": write_graphml, "gml": write_gml, "dot": write_dot, "edgelist": None,
            "adjacency": write_adjacency, "incidence": write_incidence}


def write(items, fmt: str, out=None) -> int:
    """Write chains or mechanisms to ``out`` (default stdout) as ``text``, ``json`` or one of
    :data:`WRITTEN`, as they come (nothing is held back); returns how many were written."""
    import sys

    if fmt not in ("text", "json") + WRITTEN:
        raise InvalidOption(f"chains are written as {', '.join(('text', 'json') + WRITTEN)} here (a CSV listing by "
                            f"the commands' --format csv), not {fmt!r}")
    out = out or sys.stdout
    if fmt in ("text", "json"):
        return write_lines(items, fmt, out)
    if fmt == "edgelist":
        count = 0
        for item in items:
            if count:
                out.write("\n")
            write_edgelist(item, out)
            count += 1
        return count
    return _WRITERS[fmt](items, out)


def text_of(items, fmt: str) -> str:
    """:func:`write` into a string.

    >>> print(text_of([Chain.parse("0-1 1=2 2-0")], "incidence"))
    # 3/0 P1 id ...
    """
    out = io.StringIO()
    write(items, fmt, out)
    return out.getvalue()
