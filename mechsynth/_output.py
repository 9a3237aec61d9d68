"""Writing result rows as a table for people, or jsonl / csv / json for programs."""

from __future__ import annotations

import csv
import json
import sys
from collections.abc import Iterable, Sequence

__all__ = ["FORMATS", "write_rows"]

FORMATS = ("table", "jsonl", "csv")


def _cell(value) -> str:
    if isinstance(value, (list, tuple)):
        return " ".join(map(str, value)) if all(not isinstance(x, (list, tuple)) for x in value) else json.dumps(value)
    return str(value)


def write_rows(rows: Iterable[dict], columns: Sequence[str], fmt: str, out=None) -> int:
    """Write ``rows`` (dicts) in ``fmt``; tables and csv show ``columns``, jsonl the whole dict.

    Returns the number of rows written.

    >>> write_rows([{"code": "44/0", "v": 0}], ["code", "v"], "csv")
    code,v
    44/0,0
    1
    """
    out = out or sys.stdout
    count = 0
    if fmt == "jsonl":
        for row in rows:
            out.write(json.dumps(row) + "\n")
            count += 1
    elif fmt == "csv":
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(columns)
        for row in rows:
            writer.writerow([_cell(row.get(c, "")) for c in columns])
            count += 1
    else:
        rows = list(rows)
        cells = [[_cell(r.get(c, "")) for c in columns] for r in rows]
        widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(columns)]
        out.write("  ".join(c.ljust(w) for c, w in zip(columns, widths)).rstrip() + "\n")
        out.write("  ".join("-" * w for w in widths) + "\n")
        for row in cells:
            out.write("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip() + "\n")
        count = len(rows)
    return count
