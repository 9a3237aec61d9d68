"""Chains as matrices in CSV: a link adjacency matrix or a link–joint incidence matrix.

* ``adjacency``: n × n, entry (i, j) the joint between links i and j — ``0`` or empty for none,
  ``1`` (or ``R``, ``-``) revolute, ``P`` (``=``) prismatic, ``G`` (``~``) a gear mesh; symmetric,
  zero diagonal.  Simple joints only: a multiple joint needs the incidence matrix.
* ``incidence``: a row per link, a column per joint, ``1`` where the joint holds the link (or the
  joint's kind letter, as above).  A header row naming the joints in the joint-list notation
  (``0-1``, ``1=2``, ``2~3``) gives their kinds too; a corner cell ``joint`` says the rows are
  joints instead.

The matrices written here have a header row (corner ``link``, then link numbers or joints) and
the link number first on every row; a bare matrix without them is read too (a square, symmetric
one with a zero diagonal as an adjacency matrix, any other as an incidence matrix, unless the
format is named).  Cells may be separated by commas, semicolons, tabs or spaces; a line
``# frame F`` fixes a frame (``# frame F, input I`` with its input link), ``# h H`` states the
motion space (the matrices written here always state it); a blank line ends a chain.

Example
-------
>>> read_matrices("0,1,0,1\\n1,0,1,0\\n0,1,0,P\\n1,0,P,0\\n", "m")[0].chain.compact()
'0-1 0-3 1-2 2=3'
"""

from __future__ import annotations

import re

from ..errors import InvalidOption, MalformedChain
from ..structure.chain import Chain, Mechanism
from ..structure.joints import REVOLUTE, JointKind
from ._entry import Entry, entry_of, kind_of, settings_of

__all__ = ["read_matrices", "write_adjacency", "write_incidence"]

_EMPTY = {"", "0", "0.0"}
_LETTER = {kind: kind.letter for kind in JointKind} | {REVOLUTE: "1"}  # a pin is the plain 1
_NOTATION = re.compile(r"^\d+(?:[-=~]\d+)+$")


def _cells(line: str) -> list[str]:
    for sep in (",", ";", "\t"):
        if sep in line:
            return [c.strip().strip('"') for c in line.split(sep)]
    return line.split()


def _kind(cell: str, where: str) -> str | None:
    """None for no joint, else the joint kind a matrix entry stands for."""
    if cell in _EMPTY:
        return None
    if re.fullmatch(r"\d+(\.0*)?", cell):
        if int(float(cell)) == 1:
            return REVOLUTE
        raise MalformedChain(f"{where}: entry {cell} is not 0 or 1 (or a joint kind R, P, G): two joints between "
                             "the same links, or a link held twice by a joint, are not a chain")
    return kind_of(cell, where)


def _blocks(text: str, source: str):
    """Blocks of non-empty lines: (rows of cells, first line number, settings: frame, input, h)."""
    rows, start, settings = [], None, {}
    for number, line in enumerate(text.splitlines() + [""], start=1):
        body, hashed, comment = line.partition("#")  # a comment: a line of its own or after a row
        body = body.strip()
        found = settings_of(comment) if hashed else None
        if found:
            settings.update(found)
            start = start or number
        if body:
            rows.append(_cells(body))
            start = start or number
        elif hashed:
            continue
        elif rows:
            yield rows, start, settings
            rows, start, settings = [], None, {}
        elif settings:
            said = ", ".join(f"{k} {v}" for k, v in settings.items())
            raise MalformedChain(f"{source}: '# {said}' is followed by no matrix")


def _split_header(rows):
    """(header or None, row labels or None, body)."""
    first = rows[0]
    corner = first[0].lower()
    names = first[1:]
    # a corner word, or an empty corner over distinct column names (pandas writes that); a bare
    # matrix may have empty cells, but never two equal column names nor an empty one
    named = corner == "" and names and all(names) and len(set(names)) == len(names)
    if len(rows) > 1 and (corner in ("link", "links", "joint", "joints") or named):
        return names, [r[0] for r in rows[1:]], [r[1:] for r in rows[1:]]
    return None, None, rows


def _read_block(rows, where: str, fmt: str | None, settings: dict) -> Entry:
    header, labels, body = _split_header(rows)
    width = len(body[0])
    if any(len(r) != width for r in body):
        raise MalformedChain(f"{where}: the rows of the matrix have different lengths")
    if header is not None and len(header) != width:
        raise MalformedChain(f"{where}: the header names {len(header)} columns but the rows have {width}")
    transposed = rows[0][0].lower() in ("joint", "joints")
    if fmt is None:
        square = len(body) == width and not transposed
        symmetric = square and all(body[i][j] == body[j][i] for i in range(width) for j in range(width))
        notation = header is not None and any(_NOTATION.match(h) for h in header)
        zero = square and all(body[i][i] in _EMPTY for i in range(width))
        fmt = "adjacency" if symmetric and zero and not notation else "incidence"
    if fmt == "adjacency":
        return _adjacency(body, labels or header, where, settings)
    return _incidence(body, labels, header, transposed, where, settings)


def _stated(settings: dict) -> dict:
    return dict(frame=settings.get("frame"), input_link=settings.get("input"), h=settings.get("h"))


def _adjacency(body, names, where: str, settings: dict) -> Entry:
    n = len(body)
    if any(len(r) != n for r in body):
        raise MalformedChain(f"{where}: an adjacency matrix is square, not {n} × {len(body[0])}")
    names = names or [str(i) for i in range(n)]
    joints, kinds = [], []
    for i in range(n):
        if body[i][i] not in _EMPTY:
            raise MalformedChain(f"{where}: link {names[i]} is joined to itself (entry {body[i][i]} on the diagonal)")
        for j in range(i + 1, n):
            a, b = _kind(body[i][j], where), _kind(body[j][i], where)
            if a != b:
                raise MalformedChain(f"{where}: the adjacency matrix is not symmetric at links {names[i]} and "
                                     f"{names[j]} ({body[i][j] or 'empty'} and {body[j][i] or 'empty'})")
            if a is not None:
                joints.append((names[i], names[j]))
                kinds.append(a)
    return entry_of(joints, kinds, where, links=names, **_stated(settings))


def _incidence(body, labels, header, transposed: bool, where: str, settings: dict) -> Entry:
    columns = [list(c) for c in zip(*body)] if not transposed else [list(r) for r in body]
    if transposed:
        labels, header = header, labels
    names = labels or [str(i) for i in range(len(columns[0]))]
    joints, kinds = [], []
    for k, column in enumerate(columns):
        title = header[k] if header else str(k)
        held = [(names[i], _kind(cell, f"{where}, joint {title}")) for i, cell in enumerate(column)]
        held = [(x, kind) for x, kind in held if kind is not None]
        if len(held) < 2:
            raise MalformedChain(f"{where}: joint {title} holds {len(held)} link{'s' * (len(held) != 1)}: a joint "
                                 "joins two links or more")
        kind = next((kind for _, kind in held if kind != REVOLUTE), REVOLUTE)
        if header and _NOTATION.match(header[k]):
            symbol = next(c for c in header[k] if c in "-=~")
            kind = JointKind.by_symbol(symbol)
        joints.append([x for x, _ in held])
        kinds.append(kind)
    return entry_of(joints, kinds, where, links=names, **_stated(settings))


def read_matrices(text: str, source: str, fmt: str | None = None) -> list[Entry]:
    """Every matrix of a CSV text (blocks separated by blank lines) as a chain."""
    blocks = list(_blocks(text, source))
    if not blocks:
        raise MalformedChain(f"{source}: no matrix: write a link adjacency or link–joint incidence matrix in CSV")
    return [_read_block(rows, f"{source} line {start}" if len(blocks) > 1 else source, fmt, settings)
            for rows, start, settings in blocks]


def _head(item, out) -> Chain:
    from ._graphs import describe
    from ._lists import settings_text

    info = describe(item)
    out.write(f"# {info['code']} id {info['id']}\n# {settings_text(item, every=True)}\n")
    return item.chain if isinstance(item, Mechanism) else item


def write_adjacency(items, out) -> int:
    """Link adjacency matrices (CSV), a blank line between chains; refuses multiple joints."""
    count = 0
    for item in items:
        chain = item.chain if isinstance(item, Mechanism) else item
        if any(len(j) > 2 for j in chain.joints):
            raise InvalidOption(f"an adjacency matrix holds simple joints only, and {chain.compact()} has a joint of "
                                f"{max(len(j) for j in chain.joints)} links: an incidence matrix holds it")
        if count:
            out.write("\n")
        _head(item, out)
        cells = [["0"] * chain.links for _ in range(chain.links)]
        for (a, b), kind in zip(chain.joints, chain.kinds):
            cells[a][b] = cells[b][a] = _LETTER[kind]
        out.write("link," + ",".join(map(str, range(chain.links))) + "\n")
        for i, row in enumerate(cells):
            out.write(f"{i}," + ",".join(row) + "\n")
        count += 1
    return count


def write_incidence(items, out) -> int:
    """Link–joint incidence matrices (CSV; the header names each joint with its kind), a blank line between chains."""
    count = 0
    for item in items:
        if count:
            out.write("\n")
        chain = _head(item, out)
        kinds = chain.kinds
        out.write("link," + ",".join(k.symbol.join(map(str, j)) for j, k in zip(chain.joints, kinds)) + "\n")
        for i in range(chain.links):
            out.write(f"{i}," + ",".join("1" if i in j else "0" for j in chain.joints) + "\n")
        count += 1
    return count
