"""Chains as lines of text: joint lists, JSON rows, edge lists.

* ``text``: one chain per line in the joint-list notation (``0-1 1=2 2~3``; ``0-1-2`` a
  double joint); ``#`` starts a comment, and a comment ``# frame F``, ``# h H`` (or both,
  ``# frame F, input I, h H``) fixes a frame and states the motion space.
* ``json``: a chain or mechanism row as the commands print it (``{"joints": …, "kinds": …,
  "frame": …}``), an array of rows (``--format json``), one row per line (``jsonl``), or a bare
  array of joints; the motion space is the row's ``h``, else the one its certificate carries.
* ``edgelist``: one joint per line, its links as numbers or names separated by spaces or commas
  (three or more: a multiple joint), then optionally its kind (``revolute``, ``prismatic``,
  ``mesh``, ``-``, ``=``, ``~``, or a networkx data dictionary such as ``{'kind': 'prismatic'}``);
  a line ``# frame F`` fixes a frame (``# frame F, input I`` with its input link), ``# h H`` states
  the motion space; a blank line ends a chain.

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
from dataclasses import replace

from ..errors import MalformedChain
from ..structure.chain import Chain
from ..structure.joints import REVOLUTE
from ._entry import Entry, check_distinct, entry_of, is_kind_word, kind_of, settings_of

__all__ = ["read_text_lists", "read_json", "read_edgelist", "write_edgelist", "write_lines", "looks_like_joint_list",
           "edge_words", "with_settings", "settings_text", "stated_space", "read_listing", "looks_like_listing",
           "read_table", "looks_like_table"]

_JOINT_TOKEN = re.compile(r"^\d+(?:[-=~]\d+)+$")


def looks_like_joint_list(line: str) -> bool:
    """Whether a line is written in the joint-list notation (every word like ``0-1`` or ``2=3``;
    a heterogeneous chain's loop classes may follow a ``|``).

    >>> looks_like_joint_list("0-1 1=2"), looks_like_joint_list("0 1"), looks_like_joint_list("0-1 1-2 2-0 | h5: 0 1 2")
    (True, False, True)
    """
    words = line.split("#", 1)[0].split("|", 1)[0].replace(",", " ").split()
    return bool(words) and all(_JOINT_TOKEN.match(w) for w in words)


def read_text_lists(text: str, source: str) -> list[Entry]:
    """One chain per non-empty line, in the joint-list notation; a comment of settings on the
    line (``# frame F``, ``# frame F, input I``, ``# h H``) fixes link F (a mechanism, with its
    input link I) or states the motion space; any other comment is a comment.  Settings on a
    line of their own belong to no chain and are refused (an edge list's belong to its block)."""
    out = []
    lines = text.splitlines()
    single = sum(1 for line in lines if line.split("#", 1)[0].strip()) == 1
    for number, line in enumerate(lines, start=1):
        body, _, comment = line.partition("#")
        body = body.strip()
        if not body:
            if settings_of(comment):
                raise MalformedChain(f"{source} line {number}: '# {comment.strip()}' stands on a line of its own: in a "
                                     "joint list the settings follow their chain on its line, e.g. "
                                     "'0-1 1-2 2-3 3-0  # frame 0'")
            continue
        where = source if single else f"{source} line {number}"
        joints = body.split("|", 1)[0]  # (a heterogeneous chain's loop classes follow a '|')
        check_distinct([re.split(r"[-=~]", w) for w in joints.replace(",", " ").split()], where)
        try:
            chain = Chain.parse(body)
        except MalformedChain as exc:
            raise MalformedChain(f"{where}: {exc}") from None
        out.append(with_settings(chain, where, settings_of(comment) or {}))
    return out


def with_settings(chain: Chain, where: str, settings: dict) -> Entry:
    """The entry of a chain read with its links numbered 0 … n − 1 and the settings its source
    states (``frame``, ``input``, ``h``: see :func:`~synth.exchange._entry.settings_of`)."""
    joints = [list(j) for j in chain.joints]
    entry = entry_of(joints, chain.kinds, where, frame=settings.get("frame"), input_link=settings.get("input"),
                     h=settings.get("h"), links=range(chain.links))
    if chain.classes is not None:  # a heterogeneous chain keeps the loop classes it was written with
        if entry.h not in (None, chain.h):
            raise MalformedChain(f"{where} names its loop classes (its other links are of class {chain.h}): "
                                 f"h = {entry.h} contradicts them")
        entry = replace(entry, chain=chain)
    return entry


def write_lines(items, fmt: str, out) -> int:
    """One chain a line: its joint list (``text``; a mechanism adds ``# frame F``) or its JSON row
    (``json``, with its ``id``)."""
    from ._graphs import describe

    count = 0
    for item in items:
        chain = getattr(item, "chain", item)
        if fmt == "text":
            said = settings_text(item)
            out.write(chain.compact() + (f"  # {said}" if said else "") + "\n")
        else:
            row = item.to_dict()
            row["id" if chain is item else "chain_id"] = describe(item)["id"]
            out.write(json.dumps(row) + "\n")
        count += 1
    return count


def settings_text(item, every: bool = False) -> str:
    """The settings comment of a chain or mechanism (without ``#``): ``frame F, input I, h H``;
    h where it is not 3 unless ``every``.

    >>> from synth.structure.chain import Mechanism
    >>> settings_text(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1)), settings_text(Chain.parse("0-1 1-2 2-0"), every=True)
    ('frame 0, input 1', 'h 3')
    """
    chain = getattr(item, "chain", item)
    said = []
    if getattr(item, "frame", None) is not None:
        said.append(f"frame {item.frame}")
        if item.input_link is not None:
            said.append(f"input {item.input_link}")
    if every or chain.h != 3:
        said.append(f"h {chain.h}")
    return ", ".join(said)


_CERTIFICATE_SPACE = re.compile(r"^(?:m\d+)?h(\d)")


def stated_space(row: dict):
    """The motion space a row states: its ``h``, else the one its certificate carries (the
    engine's rows leave out h = 3, their certificates say h ≠ 3 in front), else None.

    >>> stated_space({"h": 4}), stated_space({"certificate": "h50606…"}), stated_space({"certificate": "0606…"})
    (4, 5, 3)
    >>> stated_space({"joints": [[0, 1]]}) is None
    True
    """
    if row.get("h") is not None:
        return row["h"]
    certificate = row.get("chain_certificate", row.get("certificate"))
    if not isinstance(certificate, str) or not certificate:
        return None
    found = _CERTIFICATE_SPACE.match(certificate)
    return int(found.group(1)) if found else 3


def _link_of_row(row: dict, key: str, chain: Chain, where: str):
    """A row's frame or input link: a link number, or a name of the row's ``names``."""
    value = row.get(key)
    names = row.get("names")
    if value is None:
        return None
    if isinstance(names, list) and len(names) == chain.links and value in names and not isinstance(value, int):
        return names.index(value)
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < chain.links:
        what = "frame" if key == "frame" else "input link"
        raise MalformedChain(f"{where}: the {what} {value!r} is not a link of the chain (0 … {chain.links - 1})")
    return value


def _entry_of_row(row, where: str) -> Entry:
    if isinstance(row, list):
        row = {"joints": row}
    if isinstance(row, dict) and "joints" not in row:
        row = _linkage_row(row, where)
    if isinstance(row, dict) and isinstance(row.get("joints"), list):
        check_distinct([j for j in row["joints"] if isinstance(j, list)], where)
    try:
        chain = Chain.from_dict(row)
    except MalformedChain as exc:
        raise MalformedChain(f"{where}: {exc}") from None
    frame, moved = _link_of_row(row, "frame", chain, where), _link_of_row(row, "input_link", chain, where)
    names = row.get("names")
    names = tuple(map(str, names)) if isinstance(names, list) and len(names) == chain.links else None
    entry = with_settings(chain, where, {"frame": frame, "input": moved, "h": stated_space(row)})
    return Entry(entry.chain, entry.frame, names, where, entry.h, entry.input_link)


def _linkage_row(row: dict, where: str) -> dict:
    """A linkage as a chain row: its joint list and frame (its dimensions are not part of the chain).  A
    linkage is what ``move --save`` writes, a scene's ``[linkage]`` table and the ``linkage`` of
    ``dimension --format json``; any other row is returned as it is.

    >>> _linkage_row({"linkage": {"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"],
    ...               "points": {"0-1": [0, 0], "1-2": [1, 0], "2-3": [3, 2], "0-3": [4, 0]}}}, "x")["joints"]
    [[0, 1], [0, 3], [1, 2], [2, 3]]
    """
    from ..errors import MotionError
    from ..motion import Linkage

    linkage = row["linkage"] if isinstance(row.get("linkage"), dict) else row
    if not isinstance(linkage.get("chain"), str):
        return row
    try:  # read whole, as 'move' reads it: a NaN point or a misspelt entry is refused, not passed over
        read = Linkage.from_dict(linkage)
    except MotionError as exc:
        raise MalformedChain(f"{where}: {exc.args[0]}") from None
    return {**read.chain.to_dict(), "frame": read.frame}


def read_linkage_file(text: str, source: str) -> list[Entry]:
    """The chain and frame of a TOML scene or linkage file: its ``[linkage]`` table's (a file without one
    is refused in one sentence)."""
    from mechbase.toml import read_toml_text

    data = read_toml_text(text, error=MalformedChain, source=source)
    row = _linkage_row(data, source)
    table = data.get("linkage")
    if "joints" not in row and isinstance(table, dict):  # it said "holds no chain: … this one holds scene, linkage"
        raise MalformedChain(f"{source}: its [linkage] table has no chain (a joint list, chain = \"0-1 1-2 2-3 3-0\"); "
                             f"it has {', '.join(table) or 'nothing'}")
    if "joints" not in row:
        raise MalformedChain(f"{source} holds no chain: a TOML file is read for the chain of its [linkage] table (a "
                             f"linkage or a scene that moves one); this one holds {', '.join(data) or 'nothing'}")
    return [_entry_of_row(row, source)]


def read_json(text: str, source: str) -> list[Entry]:
    """Chain rows: one JSON document (a row, an array of rows or an array of joints) or one row a line."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        _refuse_comment(exc, f"{source} line {exc.lineno}")
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
            _refuse_comment(exc, where)
            raise MalformedChain(f"{where}: not valid JSON ({exc.msg} at column {exc.colno})") from None
        out.append(_entry_of_row(row, where))
    return out


def _refuse_comment(exc: json.JSONDecodeError, where: str) -> None:
    """Refuse a ``#`` comment in JSON (which has none) in a sentence that says where its settings go."""
    if exc.doc[exc.pos:].lstrip().startswith("#"):
        raise MalformedChain(f"{where}: JSON takes no '#' comment: give a frame, an input link or a motion space as "
                             'keys of the row, e.g. {"joints": [[0, 1], [1, 2], [2, 0]], "frame": 0, "h": 3}') from None


def _header_of(text: str) -> list[str]:
    """The cells of a CSV text's first line that is not a comment."""
    first = next((ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")), "")
    return [c.strip().strip('"').lower() for c in first.split(",")]


def looks_like_listing(text: str) -> bool:
    """Whether a CSV text is the listing ``chains``/``mechanisms --format csv`` print (a ``joints`` column).

    >>> looks_like_listing("index,id,code,links,joints\\n1,x,4/0,4,0-1 1-2 2-3 3-0\\n"), looks_like_listing("0,1\\n1,0")
    (True, False)
    """
    return "joints" in _header_of(text)


def read_listing(text: str, source: str) -> list[Entry]:
    """The rows of a listing in CSV: the ``joints`` column in the joint-list notation, the motion
    space from the ``h`` column (else the certificate's), a mechanism's ``frame`` and ``input_link``."""
    import csv

    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.DictReader(lines)
    fields = {(f or "").strip().lower(): f for f in reader.fieldnames or []}
    if "joints" not in fields:
        raise MalformedChain(f"{source}: a listing in CSV has a 'joints' column (as chains --format csv prints)")
    out = []
    for number, row in enumerate(reader, start=1):
        where = f"{source} row {number}"
        cell = {key: (row.get(name) or "").strip() for key, name in fields.items()}
        try:
            chain = Chain.parse(cell["joints"])
        except MalformedChain as exc:
            raise MalformedChain(f"{where}: {exc}") from None
        space = cell.get("h") or stated_space({"certificate": cell.get("certificate")})
        out.append(with_settings(chain, where, {"frame": cell.get("frame") or None,
                                                "input": cell.get("input_link") or None, "h": space}))
    if not out:
        raise MalformedChain(f"{source}: the listing has a header and no row")
    return out


_RULE = re.compile(r"^-+(?: +-+)*$")
_FOOTER = re.compile(r"^\d+ (chains?|mechanisms?)$")  # "1 chain", "2 chains"


def looks_like_table(text: str) -> bool:
    """Whether a text is a listing as a table (``chains``/``mechanisms``' default output): a header
    with a ``joints`` column over a rule of dashes.

    >>> looks_like_table("index  joints\\n-----  -------\\n1      0-1 1-2 2-0\\n"), looks_like_table("0 1\\n1 2\\n")
    (True, False)
    """
    lines = [ln for ln in text.splitlines() if ln.strip()][:2]
    return len(lines) == 2 and "joints" in lines[0].split() and bool(_RULE.match(lines[1].strip()))


def read_table(text: str, source: str) -> list[Entry]:
    """The rows of a listing as a table: its columns lie under the rule's dashes; the ``joints``
    column in the joint-list notation, ``h`` (absent: the plane, as the table leaves it out for
    h = 3), a mechanism's ``frame`` and ``input_link``; the count line ends it."""
    lines = [ln.rstrip() for ln in text.splitlines() if ln.strip()]
    if not looks_like_table(text):
        raise MalformedChain(f"{source}: a listing as a table has a header with a 'joints' column over a rule of "
                             "dashes (as chains prints)")
    starts = [m.start() for m in re.finditer(r"-+", lines[1])] + [None]

    def cells(line: str) -> list[str]:
        return [line[a:b].strip() for a, b in zip(starts, starts[1:])]

    names = cells(lines[0])
    out = []
    for number, line in enumerate(lines[2:], start=1):
        if _FOOTER.match(line.strip()):
            break
        where = f"{source} row {number}"
        cell = dict(zip(names, cells(line)))
        try:
            chain = Chain.parse(cell["joints"])
        except MalformedChain as exc:
            raise MalformedChain(f"{where}: {exc}") from None
        out.append(with_settings(chain, where, {"frame": cell.get("frame") or None,
                                                "input": cell.get("input_link") or None, "h": cell.get("h") or 3}))
    if not out:
        raise MalformedChain(f"{source}: the table has a header and no row")
    return out


_NAME = re.compile(r"^[A-Za-z0-9_.:]+$")


def edge_words(body: str) -> tuple[list[str], str | None] | None:
    """The link names and kind word of an edge-list line (data dictionary split off), or None
    when the line is not one: two or more names (letters, digits, ``_ . :``), then a kind.

    The last of three or more words is the joint's kind when it is a kind word (``revolute``,
    ``R``, ``pin``, ``-``; ``prismatic``, ``P``, ``slider``, ``=``; ``mesh``, ``G``, ``gear``,
    ``~``), and when it is any other word after link numbers (``0 1 X``: a kind to refuse, not a
    link ``X``); otherwise every word names a link (``a b c``: a double joint).

    >>> edge_words("0 1 prismatic"), edge_words("0 1 P"), edge_words("crank, rod"), edge_words('dof = 1')
    ((['0', '1'], 'prismatic'), (['0', '1'], 'P'), (['crank', 'rod'], None), None)
    >>> edge_words("0 1 X"), edge_words("a b c")
    ((['0', '1'], 'X'), (['a', 'b', 'c'], None))
    """
    words = body.replace(",", " ").split()
    last = words[-1] if words else ""
    numbered = all(w.isdigit() for w in words[:-1]) and not last.isdigit()
    kind = words.pop() if len(words) >= 3 and (is_kind_word(last) or numbered) else None
    if len(words) < 2 or not all(_NAME.match(w) for w in words):
        return None
    return words, kind


def read_edgelist(text: str, source: str) -> list[Entry]:
    """Chains written one joint per line; a blank line ends a chain."""
    out, joints, kinds, settings, start = [], [], [], {}, None

    def close():
        nonlocal joints, kinds, settings, start
        if joints:
            out.append(entry_of(joints, kinds, f"{source} line {start}", frame=settings.get("frame"),
                                input_link=settings.get("input"), h=settings.get("h")))
        elif settings:
            said = ", ".join(f"{k} {v}" for k, v in settings.items())
            raise MalformedChain(f"{source}: '# {said}' is followed by no joint")
        joints, kinds, settings, start = [], [], {}, None

    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped:
            close()
            continue
        found = settings_of(stripped) if stripped.startswith("#") else None
        if found:
            settings.update(found)
            start = start or number
            continue
        body, _, comment = stripped.partition("#")
        body = body.strip()
        if not body:
            continue
        settings.update(settings_of(comment) or {})  # settings after a joint, as on a line of their own
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
        kind = REVOLUTE if word is None else kind_of(word, where)
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
    out.write(f"# {info['code']} id {info['id']}\n# {settings_text(item, every=True)}\n")
    kinds = chain.kinds
    for joint, kind in zip(chain.joints, kinds):
        out.write(" ".join(map(str, joint)) + ("" if kind == REVOLUTE else f" {kind}") + "\n")
