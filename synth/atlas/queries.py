"""What an atlas holds: the ``--where`` language, exports of chains and mechanisms, the summary.

Example
-------
>>> import tempfile, os
>>> from synth.atlas import parse_grid, run_grid
>>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
>>> _ = run_grid(parse_grid('dof = 1\\nlinks = "4..8"'), db, workers=1)
>>> sum(1 for _ in export(db, "mechanisms", where=["n=8"]))
71
"""

from __future__ import annotations

import json
import re
import sqlite3
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

from mechbase import Row, parse_range

from ..errors import InvalidOption, MalformedCode
from ..structure.chain import Chain, Mechanism
from ..structure.code import Code
from ..gears.train import GearTrain
from .database import SCHEMA_VERSION, _reading, chain_id, open_atlas

__all__ = ["parse_where", "export", "summary", "AtlasChain", "AtlasMechanism", "TrainColumns"]


# ------------------------------------------------------------------ queries
_FIELDS = {
    "code": "code", "dof": "dof", "w": "dof", "h": "h", "links": "links", "n": "links", "loops": "loops", "k": "loops",
    "v": "v", "max_degree": "max_degree", "maxdeg": "max_degree", "fractionated": "fractionated", "cell": "cell",
    "p": "prismatic", "prismatic": "prismatic", "meshes": "meshes", "g": "meshes",
}
_TRAIN = "(SELECT t.{} FROM trains t WHERE t.chain = c.id)"  # NULL for a chain that is no gear train
_KINDS = {"gears": "EXISTS", "chains": "NOT EXISTS"}
_WHERE_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*(<=|>=|!=|==|=|<|>)\s*(\S.*?)\s*$")
_OPS = {"=": "=", "==": "=", "!=": "!=", "<": "<", "<=": "<=", ">": ">", ">=": ">="}


def parse_where(items: Iterable[str]) -> tuple[str, list]:
    """Turn ``--where`` conditions into an SQL condition on ``chains c`` and its parameters.

    A condition is ``FIELD OP VALUE``; OP is one of ``= != < <= > >=``; conditions are
    joined by AND.  Fields: ``code`` (= or !=, the code as the atlas shows it, e.g.
    ``620/2`` or ``620/0-1``), ``basecode`` (= or !=, any joint composition), ``W``/``dof``, ``h`` (motion space), ``n``/``links``, ``K``/``loops``, ``v``, ``maxdeg``,
    ``fractionated`` (0/1), ``P``/``prismatic`` (number of prismatic pairs), ``nI`` (number of links with I joints, e.g. ``n3>=2``), ``cell``
    (= only, a cell key as shown by ``mechsynth atlas``), ``id`` and ``certificate`` (= or !=: the chain's
    id, 12 hex digits as listings print it, or its nauty certificate).  Gear trains: ``kind`` (= or
    !=: ``gears`` or ``chains``), ``meshes``/``G`` (gear meshes), ``carriers`` (carrier links),
    ``lever`` (= or !=: the lever analogue's code), ``rotation`` (= or !=: the rotation graph's id).  With ``=`` a number may be a
    range ``A..B``.  Values always travel as SQL parameters, never as SQL text.

    >>> parse_where(["code=6301/0", "n=8..10", "n3>=2"])[1]
    ['6301/0', 8, 10, 3, 2]
    >>> parse_where(["kind=gears", "meshes=3"])
    ('EXISTS (SELECT 1 FROM trains t WHERE t.chain = c.id) AND c.meshes = ?', [3])
    """
    clauses, params = [], []
    for item in items:
        m = _WHERE_RE.match(item) if isinstance(item, str) else None
        if not m:
            raise InvalidOption(f"cannot read the condition {item!r}: write FIELD OP VALUE, e.g. n=10, v<=1, code=6301/0")
        name, op, value = m.group(1), _OPS[m.group(2)], m.group(3)
        key = name.lower()
        degree = re.fullmatch(r"n(\d+)", key)
        if key in ("code", "basecode", "lever"):
            if op not in ("=", "!="):
                raise InvalidOption(f"a code is compared with = or != only, not {m.group(2)!r}")
            try:
                code = Code.parse(value)
            except MalformedCode as exc:
                raise InvalidOption(f"in the condition {item!r}: {exc}") from None
            column = {"code": "c.code", "basecode": "c.base_code", "lever": _TRAIN.format("lever_code")}[key]
            clauses.append(f"{column} {op} ?")
            params.append(str(Code(code.assortment, code.v)) if key == "basecode" else str(code))
            continue
        if key == "kind":
            if op not in ("=", "!=") or value.lower() not in _KINDS:
                raise InvalidOption(f"in the condition {item!r}: kind is gears or chains (with = or !=)")
            chosen = value.lower() if op == "=" else next(k for k in _KINDS if k != value.lower())
            clauses.append(f"{_KINDS[chosen]} (SELECT 1 FROM trains t WHERE t.chain = c.id)")
            continue
        if key in ("id", "certificate", "rotation"):
            if op not in ("=", "!="):
                raise InvalidOption(f"a chain's {key} is compared with = or != only, not {m.group(2)!r}")
            value = value.strip().lower()
            if key in ("id", "rotation") and not re.fullmatch(r"[0-9a-f]{12}", value):
                raise InvalidOption(f"in the condition {item!r}: {'a chain' if key == 'id' else 'a rotation graph'} id "
                                    f"is 12 hex digits (the '{key if key == 'id' else 'rotation_id'}' column of a "
                                    f"listing), not {m.group(3)!r}")
            column = {"id": "chain_id(c.certificate)", "certificate": "c.certificate",
                      "rotation": f"chain_id({_TRAIN.format('rotation')})"}[key]
            clauses.append(f"{column} {op} ?")
            params.append(value)
            continue
        if key == "cell":
            if op != "=":
                raise InvalidOption("a cell is selected with = only")
            clauses.append("EXISTS (SELECT 1 FROM members m WHERE m.chain = c.id AND m.cell = ?)")
            params.append(value)
            continue
        if degree:
            column = "COALESCE((SELECT l.count FROM link_counts l WHERE l.chain = c.id AND l.degree = ?), 0)"
            col_params = [int(degree.group(1))]
        elif key in _FIELDS:
            column, col_params = f"c.{_FIELDS[key]}", []
        elif key == "carriers":
            column, col_params = _TRAIN.format("carriers"), []
        else:
            raise InvalidOption(f"unknown field {name!r} in the condition {item!r} (fields: code, W, h, n, K, v, P, maxdeg, "
                                "fractionated, nI such as n3, basecode, cell, id, certificate; gear trains: kind, "
                                "meshes, carriers, lever, rotation)")
        if key == "fractionated" and value.lower() in ("true", "false"):
            value = "1" if value.lower() == "true" else "0"
        try:
            if ".." in value:
                if op != "=":
                    raise InvalidOption(f"a range A..B goes with '=' only, not {m.group(2)!r} (in {item!r})")
                bounds = list(parse_range(value, open_low=True))
                if any(b is not None and abs(b) >= 2**63 for b in bounds):
                    raise InvalidOption(f"in the condition {item!r}: {value} is beyond any count an atlas holds (|x| < 2^63)")
                if None not in bounds and bounds[0] > bounds[1]:
                    raise InvalidOption(f"in the condition {item!r}: the range {value} is empty (write the smaller end "
                                        "first)")
                if bounds[0] is not None:
                    clauses.append(f"{column} >= ?")
                    params += col_params + [bounds[0]]
                if bounds[1] is not None:
                    clauses.append(f"{column} <= ?")
                    params += col_params + [bounds[1]]
                continue
            number = int(value)
        except ValueError:
            raise InvalidOption(f"in the condition {item!r}: {value!r} is not a whole number or a range A..B") from None
        if abs(number) >= 2**63:
            raise InvalidOption(f"in the condition {item!r}: {value} is beyond any count an atlas holds (|x| < 2^63)")
        clauses.append(f"{column} {op} ?")
        params += col_params + [number]
    return (" AND ".join(clauses) or "1"), params


_ORDER = "ORDER BY c.dof, c.h, c.links, c.v, c.code, c.certificate"


def export(db: str | Path, what: str = "chains", *, where: Iterable[str] = ()) -> Iterator[dict]:
    """Rows of the atlas (chains or mechanisms) matching ``where``, in a fixed order.

    Chain rows are ``Chain.to_dict()`` plus ``id`` (:func:`chain_id`), ``degrees``, ``fractionated`` and
    ``cells``; mechanism rows add ``frame``, ``input_link``, ``chain_id`` and ``chain_certificate``.
    Rows of gear trains add ``kind`` ("gears"), ``train`` (the text form ``mechsynth gears --train``
    and ``GearTrain.parse`` read), ``carriers`` (per mesh), ``lever_code``, ``rotation_id`` and
    ``rotation_certificate``.

    >>> # export("atlas.sqlite", "chains", where=["code=6301/0", "v<=1"])
    """
    if what not in ("chains", "mechanisms"):
        raise InvalidOption(f"export 'chains' or 'mechanisms', not {what!r}")
    condition, params = parse_where(where)
    conn = open_atlas(db)  # now: a file that is not an atlas is refused before the caller writes anything
    return _export_rows(conn, db, what, condition, params)


def _export_rows(conn: sqlite3.Connection, db, what: str, condition: str, params: list) -> Iterator[dict]:
    try:
        with _reading(db):
            yield from _rows(conn, what, condition, params)
    finally:
        conn.close()


@dataclass(frozen=True)
class TrainColumns(Row):
    """What a gear train adds to its chain's row in an atlas: the train as text, the carrier of each
    mesh, the code of its lever analogue and its rotation graph's id and certificate."""

    train: str
    carriers: tuple[int, ...]
    lever_code: str | None
    rotation_id: str
    rotation_certificate: str

    row_keys = ("kind", "train", "carriers", "lever_code", "rotation_id", "rotation_certificate")
    kind = "gears"

    @classmethod
    def of(cls, train: str | None, lever_code: str | None, rotation: str | None) -> "TrainColumns | None":
        """The columns of a stored train (None: the chain is no gear train)."""
        if train is None:
            return None
        return cls(train, GearTrain.parse(train).carriers, lever_code, chain_id(rotation), rotation)


@dataclass(frozen=True)
class AtlasChain(Row):
    """A chain of an atlas as ``atlas --format`` and :func:`export` give it: the chain's own row
    (``Chain.to_dict()``, as stored), its id, its links' degrees, whether it is fractionated, the
    cells that hold it and, for a gear train, the train's columns."""

    chain: dict
    id: str
    degrees: tuple[int, ...]
    fractionated: bool
    cells: tuple[str, ...]
    gears: TrainColumns | None = None

    row_keys = ("*chain", "id", "degrees", "fractionated", "cells", "*gears?")


@dataclass(frozen=True)
class AtlasMechanism(Row):
    """A mechanism of an atlas: its chain's row (without the chain's certificate), the train's columns
    for a gear train, the chain's id and certificate, its own certificate, frame and input link."""

    chain: dict
    gears: TrainColumns | None
    chain_id: str
    chain_certificate: str
    certificate: str
    frame: int
    input_link: int | None = None

    row_keys = ("*chain", "*gears?", "chain_id", "chain_certificate", "certificate", "frame", "input_link?")


def _rows(conn: sqlite3.Connection, what: str, condition: str, params: list) -> Iterator[dict]:
    train = "t.train, t.lever_code, t.rotation"
    if what == "chains":
        sql = (f"SELECT c.chain, c.degrees, c.fractionated, "
               f"(SELECT group_concat(m.cell, ';') FROM members m WHERE m.chain = c.id), {train} "
               f"FROM chains c LEFT JOIN trains t ON t.chain = c.id WHERE {condition} {_ORDER}")
        for chain, degrees, fractionated, cells, *gears in conn.execute(sql, params):
            row = json.loads(chain)
            yield AtlasChain(row, chain_id(row["certificate"]), tuple(int(x) for x in degrees.split()),
                             bool(fractionated), tuple(sorted(cells.split(";"))) if cells else (),
                             TrainColumns.of(*gears)).to_dict()
    else:
        sql = (f"SELECT c.chain, k.frame, k.input_link, {train} FROM mechanisms k "
               f"JOIN chains c ON c.id = k.chain LEFT JOIN trains t ON t.chain = c.id WHERE {condition} "
               f"{_ORDER}, k.input_link >= 0, k.frame, k.input_link")
        for chain, frame, input_link, *gears in conn.execute(sql, params):
            row = json.loads(chain)
            driven = None if input_link < 0 else input_link
            mechanism = Mechanism(Chain.from_dict(row), frame, driven)
            certificate = row.pop("certificate")
            yield AtlasMechanism(row, TrainColumns.of(*gears), chain_id(certificate), certificate,
                                 mechanism.certificate, frame, driven).to_dict()


def summary(db: str | Path) -> dict:
    """What an atlas holds: chains and mechanisms by code, cells and units done / total, runs.

    Returns a JSON-able dict with ``chains``, ``mechanisms``, ``by_code`` (chains; a code of
    motion space h ≠ 3 is shown as ``"6/0 h=5"``), ``mechanisms_by_code`` (fixed-link
    mechanisms), ``codes`` (code, W, h, links, chains, mechanisms), ``units`` {done, total},
    ``cells`` (key, W, h, links, units done/total, chains, by_code), ``runs`` and ``locked_by``.
    """
    conn = open_atlas(db)
    try:
        with _reading(db):
            return _summary(conn, db)
    finally:
        conn.close()


def _summary(conn: sqlite3.Connection, db) -> dict:
    order = "ORDER BY MIN(h), MIN(links), MIN(dof), MIN(v), code, prismatic, meshes"
    shown = ("code || CASE WHEN prismatic = 0 THEN '' ELSE ' P' || prismatic END "
             "|| CASE WHEN meshes = 0 THEN '' ELSE ' G' || meshes END "
             "|| CASE WHEN h = 3 THEN '' ELSE ' h=' || h END")
    codes = [dict(zip(("code", "dof", "h", "links", "chains"), r)) for r in conn.execute(
        f"SELECT {shown}, MIN(dof), h, MIN(links), COUNT(*) FROM chains GROUP BY h, code, prismatic, meshes {order}")]
    by_code = {c["code"]: c["chains"] for c in codes}
    mech_by_code = {code: n for code, n in conn.execute(
        f"SELECT {shown}, COUNT(*) FROM (SELECT c.code AS code, c.h AS h, c.links AS links, c.dof AS dof, "
        f"c.v AS v, c.prismatic AS prismatic, c.meshes AS meshes FROM mechanisms k JOIN chains c ON c.id = k.chain "
        f"WHERE k.input_link < 0) GROUP BY h, code, prismatic, meshes {order}")}
    for c in codes:
        c["mechanisms"] = mech_by_code.get(c["code"], 0)
    cells = []
    for key, dof, h, links, total in conn.execute(
            "SELECT cell, dof, h, links, units FROM cells ORDER BY dof, h, links, cell"):
        done = conn.execute("SELECT COUNT(*) FROM units WHERE cell = ? AND status = 'done'", (key,)).fetchone()[0]
        cell_codes = {code: n for code, n in conn.execute(
            f"SELECT {shown}, COUNT(*) FROM (SELECT c.* FROM members m JOIN chains c ON c.id = m.chain "
            f"WHERE m.cell = ?) GROUP BY code, prismatic, meshes {order}", (key,))}
        cells.append({"cell": key, "dof": dof, "h": h, "links": links, "units_done": done, "units_total": total,
                      "chains": sum(cell_codes.values()), "by_code": cell_codes})
    units_done, units_total = conn.execute(
        "SELECT COALESCE(SUM(status = 'done'), 0), COUNT(*) FROM units").fetchone()
    lock = conn.execute("SELECT pid, host, started FROM run_lock").fetchone()
    runs = [dict(zip(("id", "status", "executor", "units_run", "started", "finished"), r)) for r in conn.execute(
        "SELECT id, status, executor, units_run, started, finished FROM runs ORDER BY id")]
    return {
        "db": str(db),
        "schema_version": SCHEMA_VERSION,
        "chains": conn.execute("SELECT COUNT(*) FROM chains").fetchone()[0],
        "mechanisms": conn.execute("SELECT COUNT(*) FROM mechanisms WHERE input_link < 0").fetchone()[0],
        "mechanisms_with_input": conn.execute(
            "SELECT COUNT(*) FROM mechanisms WHERE input_link >= 0").fetchone()[0],
        "units": {"done": units_done, "total": units_total},
        "by_code": by_code,
        "mechanisms_by_code": mech_by_code,
        "codes": codes,
        "cells": cells,
        "runs": runs,
        "locked_by": None if lock is None else {"pid": lock[0], "host": lock[1]},
    }
