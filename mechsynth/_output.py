"""Writing results for people (table) or programs (jsonl, csv, json), and the exit-status rule.

Every command follows one rule, as grep does: exit status 0 when something matched, 1 when a
valid query matched nothing — in every output form, ``--count`` included — and 2 for an error.
"""

from __future__ import annotations

import csv
import json
import math
import os
import sys
from collections.abc import Iterable, Sequence
from typing import Any

__all__ = ["FORMATS", "COUNT_FORMATS", "write_rows", "write_count", "nothing_found", "write_document", "pairs",
           "number", "save_linkage"]

FORMATS = ("table", "jsonl", "csv", "json")
COUNT_FORMATS = ("json", "table", "jsonl", "csv")  # --count: one JSON object by default (DESIGN contract)


def _cell(value) -> str:
    """One cell of a table or csv row: a list as its items, a missing value (None) empty."""
    if value is None:
        return ""
    if isinstance(value, (list, tuple)):
        return " ".join(map(str, value)) if all(not isinstance(x, (list, tuple)) for x in value) else json.dumps(value)
    return str(value)


def write_rows(rows: Iterable[dict], columns: Sequence[str], fmt: str, out=None) -> int:
    """Write ``rows`` (dicts) in ``fmt``; tables and csv show ``columns``, jsonl and json the whole dict.

    ``json`` is one array, written as the rows come (no row is held back); a table shows a float to six
    significant digits (:func:`number`), csv and JSON every digit. Returns the number of rows.
    A table holds its rows to align its columns: beyond ``synth.TABLE_ROWS`` it writes nothing and
    raises :class:`synth.QueryTooLarge` (the listings size themselves first; this bounds any other).

    >>> write_rows([{"code": "44/0", "v": 0}, {"code": "53/1", "v": None}], ["code", "v"], "csv")
    code,v
    44/0,0
    53/1,
    2
    >>> write_rows([{"x": 4.499999999999999}], ["x"], "table")
    x
    ---
    4.5
    1
    >>> write_rows([{"code": "44/0"}, {"code": "53/1"}], ["code"], "json")
    [{"code": "44/0"},
     {"code": "53/1"}]
    2
    """
    out = out or sys.stdout
    count = 0
    if fmt == "jsonl":
        for row in rows:
            out.write(json.dumps(row) + "\n")
            count += 1
    elif fmt == "json":
        for row in rows:
            out.write(("[" if count == 0 else ",\n ") + json.dumps(row))
            count += 1
        out.write("]\n" if count else "[]\n")
    elif fmt == "csv":
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(columns)
        for row in rows:
            writer.writerow([_cell(row.get(c, "")) for c in columns])
            count += 1
    else:
        from synth import TABLE_ROWS, QueryTooLarge

        cells = []  # only the shown cells of each row are held, not the rows
        for r in rows:
            if len(cells) == TABLE_ROWS:
                raise QueryTooLarge(f"a table is held in memory to align it and this one has more than "
                                    f"{TABLE_ROWS:,} rows".replace(",", " ")
                                    + "; use --format jsonl or csv (streamed), or --count")
            cells.append(tuple(number(v) if isinstance(v := r.get(c, ""), float) else _cell(v) for c in columns))
        widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(columns)]
        out.write("  ".join(c.ljust(w) for c, w in zip(columns, widths)).rstrip() + "\n")
        out.write("  ".join("-" * w for w in widths) + "\n")
        for row in cells:
            out.write("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip() + "\n")
        count = len(cells)
    return count


def write_count(result: dict, fmt: str, out=None) -> int:
    """Write a ``{"count": N, "by_code": {...}}`` result in ``fmt``; returns N.

    ``json`` is the object itself; ``jsonl`` and ``csv`` give one row per code; ``table``
    adds the total.

    >>> write_count({"count": 3, "by_code": {"42/0": 2, "51/1": 1}}, "csv")
    code,count
    42/0,2
    51/1,1
    3
    """
    out = out or sys.stdout
    if fmt == "json":
        out.write(json.dumps(result) + "\n")
    else:
        rows = [{"code": code, "count": n} for code, n in result["by_code"].items()]
        write_rows(rows, ["code", "count"], fmt, out)
        if fmt == "table":
            out.write(f"{result['count']} in all\n")
    return result["count"]


def nothing_found(what: str, err=None) -> int:
    """Say on stderr that a valid query matched nothing; return exit status 1.

    >>> import io; nothing_found("chains satisfy these parameters", io.StringIO())
    1
    """
    (err or sys.stderr).write(f"mechsynth: no {what}\n")
    return 1


def _finite(obj: Any) -> Any:
    """JSON-safe: non-finite numbers become null, tuples lists, keys strings."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {str(k): _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    return obj


def write_document(document: dict, fmt: str, table: str, out=None) -> None:
    """One result: ``json`` writes the document (indented, non-finite numbers as null), ``table`` the
    text ``table`` already laid out for people.

    >>> write_document({"c": 1.5, "e": float("inf")}, "json", "")
    {
      "c": 1.5,
      "e": null
    }
    """
    out = out or sys.stdout
    if fmt == "json":
        out.write(json.dumps(_finite(document), indent=2, ensure_ascii=False, allow_nan=False) + "\n")
    else:
        out.write(table.rstrip("\n") + "\n")


def number(value: Any) -> str:
    """A value for a table: floats to six significant digits.

    >>> number(1 / 3), number(7), number("x")
    ('0.333333', '7', 'x')
    """
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def pairs(rows: Sequence[tuple[str, Any]]) -> str:
    """A two-column table of names and values (:func:`number`), the names padded to one width.

    >>> print(pairs([("c (N/m)", 9900.54321), ("r (m)", 0.01)]))
    c (N/m)  9900.54
    r (m)    0.01
    """
    width = max(len(k) for k, _ in rows)
    return "\n".join(f"{k:<{width}}  {number(v)}" for k, v in rows)


def save_linkage(linkage, path: str, *, source: str, description: str, comment: str | None = None,
                 tables: dict | None = None, compute: tuple = ("motion",)) -> None:
    """Write ``linkage`` to ``path``: as JSON (``.json``), or as a TOML scene (``.toml``) whose ``[linkage]``
    table ``move`` and ``draw`` read and ``scene`` runs (``compute``), under a ``comment`` line.  ``tables``:
    more tables beside it (name → dict; in JSON the linkage is then under ``"linkage"``).

    >>> import os, tempfile
    >>> from synth.motion import Linkage, read_linkage
    >>> lk = Linkage.from_dict({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"],
    ...                         "points": {"0-1": [0, 0], "1-2": [1, 0], "2-3": [3, 2], "0-3": [4, 0]}})
    >>> path = os.path.join(tempfile.mkdtemp(), "four_bar.toml")
    >>> save_linkage(lk, path, source="a doctest", description="a four-bar")
    >>> print(open(path).read().split("[linkage]")[1].strip().splitlines()[:2])
    ['chain = "0-1 0-3 1-2 2-3"', 'frame = 0']
    >>> read_linkage(path).to_dict() == lk.to_dict()
    True
    """
    from mechbase import toml_value

    d = linkage.to_dict()
    with open(path, "w", encoding="utf-8") as fh:
        if path.lower().endswith(".json"):
            json.dump({"linkage": d} | tables if tables else d, fh, indent=2)
            fh.write("\n")
            return
        name = os.path.splitext(os.path.basename(path))[0]
        if comment:
            fh.write(f"# {comment}\n\n")
        fh.write(f"[scene]\nname = {toml_value(name)}\ndescription = {toml_value(description)}\n"
                 f"source = {toml_value(source)}\ncompute = {toml_value(list(compute))}\n")
        for table, content in {"linkage": d, **(tables or {})}.items():
            fh.write(f"\n[{table}]\n")
            for key, value in content.items():
                fh.write(f"{key} = {toml_value(value)}\n")
