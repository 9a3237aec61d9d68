"""Chains as lines of text: joint lists, JSON rows, edge lists.

* ``text``: one chain per line in the joint-list notation (``0-1 1=2 2~3``; ``0-1-2`` a
  double joint); ``#`` starts a comment.
* ``json``: a chain or mechanism row as the commands print it (``{"joints": …, "kinds": …,
  "frame": …}``), an array of rows (``--format json``), one row per line (``jsonl``), or a bare
  array of joints.
* ``edgelist``: one joint per line, its links as numbers or names separated by spaces or commas
  (three or more: a multiple joint), then optionally its kind (``revolute``, ``prismatic``,
  ``mesh``, ``-``, ``=``, ``~``, or a networkx data dictionary such as ``{'kind': 'prismatic'}``);
  a line ``# frame F`` fixes a frame; a blank line ends a chain.

Example
-------
>>> [e.chain.compact() for e in read_text_lists("0-1 1-2 2-0\\n0=1 1-2 2-3 3-0 # a slider-crank\\n", "t")]
['0-1 0-2 1-2', '0=1 0-3 1-2 2-3']
>>> read_edgelist("a b\\nb c prismatic\\nc a\\n", "e")[0].chain.compact()
'0-1 0-2 1=2'
"""

from __future__ import annotations

import ast
import json
import re

from ..errors import MalformedChain
from ..structure.chain import Chain
from ._entry import Entry, check_distinct, entry_of, kind_of

__all__ = ["read_text_lists", "read_json", "read_edgelist", "write_edgelist", "write_lines", "looks_like_joint_list",
           "edge_words"]

_JOINT_TOKEN = re.compile(r"^\d+(?:[-=~]\d+)+$")
_FRAME_LINE = re.compile(r"^#\s*frame\s*[:=]?\s*(\S+)\s*$", re.IGNORECASE)


def looks_like_joint_list(line: str) -> bool:
    """Whether a line is written in the joint-list notation (every word like ``0-1`` or ``2=3``;
    a heterogeneous chain's loop classes may follow a ``|``).

    >>> looks_like_joint_list("0-1 1=2"), looks_like_joint_list("0 1"), looks_like_joint_list("0-1 1-2 2-0 | h5: 0 1 2")
    (True, False, True)
    """
    words = line.split("#", 1)[0].split("|", 1)[0].replace(",", " ").split()
    return bool(words) and all(_JOINT_TOKEN.match(w) for w in words)


def read_text_lists(text: str, source: str) -> list[Entry]:
    """One chain per non-empty line, in the joint-list notation; a comment ``# frame F`` on the
    line fixes link F (a mechanism)."""
    out = []
    lines = text.splitlines()
    single = sum(1 for line in lines if line.split("#", 1)[0].strip()) == 1
    for number, line in enumerate(lines, start=1):
        body, _, comment = line.partition("#")
        body = body.strip()
        if not body:
            continue
        frame = _FRAME_LINE.match("#" + comment.strip()) if comment else None
        where = source if single else f"{source} line {number}"
        joints = body.split("|", 1)[0]  # (a heterogeneous chain's loop classes follow a '|')
        check_distinct([re.split(r"[-=~]", w) for w in joints.replace(",", " ").split()], where)
        try:
            chain = Chain.parse(body)
        except MalformedChain as exc:
            raise MalformedChain(f"{where}: {exc}") from None
        out.append(_with_frame(Entry(chain, None, None, where), frame.group(1) if frame else None))
    return out


def _with_frame(entry: Entry, frame) -> Entry:
    if frame is None:
        return entry
    if not re.fullmatch(r"\d+", str(frame)) or int(frame) >= entry.chain.links:
        raise MalformedChain(f"{entry.source}: the frame {frame} is not a link of the chain (0 … {entry.chain.links - 1})")
    return Entry(entry.chain, int(frame), entry.names, entry.source)


def write_lines(items, fmt: str, out) -> int:
    """One chain a line: its joint list (``text``; a mechanism adds ``# frame F``) or its JSON row
    (``json``, with its ``id``)."""
    from ._graphs import describe

    count = 0
    for item in items:
        chain = getattr(item, "chain", item)
        if fmt == "text":
            frame = getattr(item, "frame", None)
            out.write(chain.compact() + ("" if frame is None else f"  # frame {frame}") + "\n")
        else:
            row = item.to_dict()
            row["id" if chain is item else "chain_id"] = describe(item)["id"]
            out.write(json.dumps(row) + "\n")
        count += 1
    return count


def _entry_of_row(row, where: str) -> Entry:
    if isinstance(row, list):
        row = {"joints": row}
    if isinstance(row, dict) and isinstance(row.get("joints"), list):
        check_distinct([j for j in row["joints"] if isinstance(j, list)], where)
    try:
        chain = Chain.from_dict(row)
    except MalformedChain as exc:
        raise MalformedChain(f"{where}: {exc}") from None
    frame = row.get("frame") if isinstance(row, dict) else None
    if frame is not None and (isinstance(frame, bool) or not isinstance(frame, int) or not 0 <= frame < chain.links):
        raise MalformedChain(f"{where}: the frame {frame!r} is not a link of the chain (0 … {chain.links - 1})")
    return Entry(chain, frame, None, where)


def read_json(text: str, source: str) -> list[Entry]:
    """Chain rows: one JSON document (a row, an array of rows or an array of joints) or one row a line."""
    stripped = text.strip()
    try:
        data = json.loads(stripped)
    except json.JSONDecodeError:
        data = None
    if data is not None:
        if isinstance(data, list) and data and all(isinstance(r, dict) for r in data):
            return [_entry_of_row(r, f"{source} row {i}") for i, r in enumerate(data, start=1)]
        return [_entry_of_row(data, source)]
    out = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        where = f"{source} line {number}"
        try:
            row = json.loads(line)
        except json.JSONDecodeError as exc:
            raise MalformedChain(f"{where}: not valid JSON ({exc.msg} at column {exc.colno})") from None
        out.append(_entry_of_row(row, where))
    return out


_KIND_TAILS = ("revolute", "prismatic", "mesh", "gear", "-", "=", "~")  # a kind written after the links
_NAME = re.compile(r"^[A-Za-z0-9_.:]+$")


def edge_words(body: str) -> tuple[list[str], str | None] | None:
    """The link names and kind word of an edge-list line (data dictionary split off), or None
    when the line is not one: two or more names (letters, digits, ``_ . :``), then a kind.

    >>> edge_words("0 1 prismatic"), edge_words("crank, rod"), edge_words('dof = 1')
    ((['0', '1'], 'prismatic'), (['crank', 'rod'], None), None)
    """
    words = body.replace(",", " ").split()
    kind = words.pop() if len(words) >= 3 and words[-1].lower() in _KIND_TAILS else None
    if len(words) < 2 or not all(_NAME.match(w) for w in words):
        return None
    return words, kind


def read_edgelist(text: str, source: str) -> list[Entry]:
    """Chains written one joint per line; a blank line ends a chain."""
    out, joints, kinds, frame, start = [], [], [], None, None

    def close():
        nonlocal joints, kinds, frame, start
        if joints:
            out.append(entry_of(joints, kinds, f"{source} line {start}", frame=frame))
        elif frame is not None:
            raise MalformedChain(f"{source}: '# frame {frame}' is followed by no joint")
        joints, kinds, frame, start = [], [], None, None

    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped:
            close()
            continue
        found = _FRAME_LINE.match(stripped)
        if found:
            frame = found.group(1)
            start = start or number
            continue
        body = stripped.split("#", 1)[0].strip()
        if not body:
            continue
        where = f"{source} line {number}"
        data = None
        if "{" in body:
            body, _, rest = body.partition("{")
            try:
                data = ast.literal_eval("{" + rest)
            except (ValueError, SyntaxError):
                raise MalformedChain(f"{where}: cannot read the data {('{' + rest)!r} (a dictionary such as "
                                     "{'kind': 'prismatic'})") from None
            if not isinstance(data, dict):
                raise MalformedChain(f"{where}: the joint's data must be a dictionary, not {data!r}")
        found = edge_words(body)
        if found is None:
            raise MalformedChain(f"{where}: cannot read {body!r} as a joint: an edge-list line names the two (or more) "
                                 "links of a joint, then optionally its kind, e.g. '0 1' or '1 2 prismatic'")
        words, word = found
        kind = "revolute" if word is None else kind_of(word, where)
        if data:
            value = data.get("kind", data.get("joint_kind", data.get("type")))
            if value is not None:
                kind = kind_of(value, where)
        start = start or number
        joints.append(words)
        kinds.append(kind)
    close()
    if not out:
        raise MalformedChain(f"{source}: no joint: an edge list names the links of one joint a line, e.g. '0 1'")
    return out


def write_edgelist(item, out, names=None) -> None:
    """One chain (or mechanism) as an edge list: a comment with its code and id, then a joint a line."""
    from ._graphs import describe

    chain = getattr(item, "chain", item)
    info = describe(item)
    out.write(f"# {info['code']} id {info['id']}\n")
    if getattr(item, "frame", None) is not None:
        out.write(f"# frame {item.frame}\n")
    kinds = chain.kinds or ("revolute",) * len(chain.joints)
    for joint, kind in zip(chain.joints, kinds):
        out.write(" ".join(map(str, joint)) + ("" if kind == "revolute" else f" {kind}") + "\n")
