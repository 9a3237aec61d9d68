"""The SQLite atlas file: its schema and version, opening it (checked, read-only first) and the lock of a run.

Schema (version 4, ``meta.schema_version``)
-------------------------------------------
``chains``      one row per chain: integer ``id``, ``certificate`` (nauty, canonical) UNIQUE; code
                (with joint composition), base code (without), W, h, n, K, v, number of prismatic
                pairs (grid key ``prismatic``; W counts their wedge loops), number of gear meshes, largest link degree,
                sorted degrees, fractionated flag, and the chain JSON (``Chain.to_dict``) in its
                *canonical labelling* (nauty's), so the same chain reads the same from any cell.
``link_counts`` (chain, degree, count): n_I of each chain, for ``--where n5>=1``.
``members``     (cell, chain) PRIMARY KEY: which grid cells produced the chain.  A chain is
                stored once however many cells contain it (the same chain is in the cell with
                and the cell without fractionated chains); a cell's own convention set is read
                through this table.
``mechanisms``  (chain, frame, input_link) PRIMARY KEY, links numbered as in the stored canonical
                chain; the frame is the smallest link of its automorphism orbit, ``input_link``
                is -1 for fixed-link-only mechanisms.  Exports add ``Mechanism.certificate``.
``trains``      one row per chain that is a planetary gear train (its axes the revolute joints,
                its meshes the ``mesh`` joints): the train's text form in the chain's labelling,
                the lever analogue's code, the number of carrier links, the rotation graph's
                certificate and the train's rank in :func:`synth.gears.trains`' order.
``rotations``   (cell, rotation) PRIMARY KEY: in a cell of rotation graphs, the train that stands
                for each rotation graph (the first in :func:`synth.gears.trains`' order) and its rank.
``cells``       the grid cells (key, W, n, v range, conventions, constraints, unit count).
``units``       (cell, unit key) PRIMARY KEY, status pending/done, chains, mechanisms,
                attempts (runs that scheduled it), seconds, finished time, run id.
``runs``        every grid run: pid, host, start/end, status, workers or scheduler.
``run_lock``    at most one row: the run writing the atlas now (pid, host).

The guarantees of a run (one transaction per finished unit, no chain stored twice, one run at a
time) are kept by :mod:`synth.atlas.runs` with this file's lock.

Example
-------
>>> import tempfile, os
>>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
>>> conn = open_atlas(db, write=True)
>>> conn.execute("SELECT value FROM meta WHERE key = 'schema_version'").fetchone()[0]
'4'
"""

from __future__ import annotations

import os
import re
import socket
import sqlite3
import time
from contextlib import contextmanager
from pathlib import Path

from ..errors import MalformedChain, SynthesisError
from ..execution.sqlite_files import read_only_uri
from ..structure.chain import chain_id
from .grid import Grid

__all__ = ["SCHEMA_VERSION", "AtlasError", "AtlasLocked", "open_atlas", "chain_id"]

SCHEMA_VERSION = 4  # 2: motion space h of chains and cells; 3: prismatic pairs of chains; 4: gear trains


class AtlasError(SynthesisError):
    """The atlas file cannot be opened, written, or is not an atlas of this version."""


class AtlasLocked(AtlasError):
    """Another run is writing the same atlas."""


_SCHEMA = """
CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE chains (
    id INTEGER PRIMARY KEY, certificate TEXT NOT NULL UNIQUE,
    code TEXT NOT NULL, base_code TEXT NOT NULL,
    dof INTEGER NOT NULL, h INTEGER NOT NULL, links INTEGER NOT NULL, loops INTEGER NOT NULL, v INTEGER NOT NULL,
    prismatic INTEGER NOT NULL, max_degree INTEGER NOT NULL, degrees TEXT NOT NULL, fractionated INTEGER NOT NULL,
    chain TEXT NOT NULL, meshes INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX chains_select ON chains (dof, h, links, v, code);
CREATE TABLE link_counts (
    chain INTEGER NOT NULL REFERENCES chains, degree INTEGER NOT NULL, count INTEGER NOT NULL,
    PRIMARY KEY (chain, degree)
) WITHOUT ROWID;
CREATE TABLE trains (
    chain INTEGER PRIMARY KEY REFERENCES chains, train TEXT NOT NULL, lever_code TEXT NOT NULL,
    carriers INTEGER NOT NULL, rotation TEXT NOT NULL, rank INTEGER NOT NULL
);
CREATE INDEX trains_rotation ON trains (rotation);
CREATE TABLE rotations (
    cell TEXT NOT NULL REFERENCES cells, rotation TEXT NOT NULL, chain INTEGER NOT NULL REFERENCES chains,
    rank INTEGER NOT NULL, PRIMARY KEY (cell, rotation)
) WITHOUT ROWID;
CREATE TABLE cells (
    cell TEXT PRIMARY KEY, dof INTEGER NOT NULL, h INTEGER NOT NULL, links INTEGER NOT NULL,
    v_min INTEGER NOT NULL, v_max INTEGER, rigid_subchains INTEGER NOT NULL,
    fractionated INTEGER NOT NULL, planar_only INTEGER NOT NULL, require TEXT NOT NULL,
    units INTEGER NOT NULL
);
CREATE TABLE members (
    cell TEXT NOT NULL REFERENCES cells, chain INTEGER NOT NULL REFERENCES chains,
    PRIMARY KEY (cell, chain)
) WITHOUT ROWID;
CREATE INDEX members_chain ON members (chain);
CREATE TABLE mechanisms (
    chain INTEGER NOT NULL REFERENCES chains, frame INTEGER NOT NULL, input_link INTEGER NOT NULL,
    PRIMARY KEY (chain, frame, input_link)
) WITHOUT ROWID;
CREATE TABLE units (
    cell TEXT NOT NULL REFERENCES cells, unit TEXT NOT NULL, code TEXT NOT NULL,
    status TEXT NOT NULL DEFAULT 'pending' CHECK (status IN ('pending', 'done')),
    chains INTEGER, mechanisms INTEGER, attempts INTEGER NOT NULL DEFAULT 0,
    seconds REAL, finished REAL, run INTEGER,
    PRIMARY KEY (cell, unit)
);
CREATE TABLE runs (
    id INTEGER PRIMARY KEY, pid INTEGER NOT NULL, host TEXT NOT NULL, grid TEXT NOT NULL,
    started REAL NOT NULL, finished REAL, status TEXT NOT NULL, executor TEXT NOT NULL,
    units_run INTEGER NOT NULL DEFAULT 0
);
CREATE TABLE run_lock (
    id INTEGER PRIMARY KEY CHECK (id = 1), run INTEGER NOT NULL, pid INTEGER NOT NULL,
    host TEXT NOT NULL, started REAL NOT NULL
);
"""


# ------------------------------------------------------------------ opening
def refuse_unwritable(path: Path) -> None:
    """Refuse before touching anything when the file or its directory is read-only.

    Permission bits are checked as well as ``os.access`` so that a file made read-only
    (``chmod a-w``) is respected even by the superuser.
    """
    if path.exists():
        if path.is_dir():
            raise AtlasError(f"the atlas path {path} is a directory, not a file")
        if not os.access(path, os.W_OK) or not path.stat().st_mode & 0o222:
            raise AtlasError(f"cannot write the atlas {path}: the file is read-only")
    directory = path.parent  # (a bare file name's parent is ".")
    if not directory.is_dir():
        raise AtlasError(f"cannot create the atlas {path}: the directory {directory} does not exist")
    if not os.access(directory, os.W_OK) or not directory.stat().st_mode & 0o222:
        raise AtlasError(f"cannot write the atlas {path}: the directory {directory} is read-only "
                         "(SQLite needs to write its journal next to the file)")


def _columns(schema: str) -> dict[str, set[str]]:
    """The tables of a schema and their columns (read back from SQLite itself)."""
    with sqlite3.connect(":memory:") as conn:
        conn.executescript(schema)
        names = [r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
        return {name: {r[1] for r in conn.execute(f"PRAGMA table_info({name})")} for name in names}


_TABLES = _columns(_SCHEMA)

# Version 3 lacks only what gear trains added: it is read as it is (through the temporary views
# below) and upgraded in place by the next run that writes it.
_UPGRADE_3 = [
    "ALTER TABLE chains ADD COLUMN meshes INTEGER NOT NULL DEFAULT 0",
    *(statement for statement in _SCHEMA.split(";") if re.search(r"\b(trains|rotations)\b", statement)),
    "UPDATE meta SET value = '4' WHERE key = 'schema_version'",
]
_READ_3 = [  # temporary objects shadow the main database's of the same name
    "CREATE TEMP VIEW chains AS SELECT *, 0 AS meshes FROM main.chains",
    *(statement.replace("CREATE TABLE ", "CREATE TEMP TABLE ") for statement in _SCHEMA.split(";")
      if re.search(r"CREATE TABLE (trains|rotations)\b", statement)),
]
_TABLES_3 = {table: columns - {"meshes"} for table, columns in _TABLES.items() if table not in ("trains", "rotations")}


def _check_version(conn: sqlite3.Connection, path: Path) -> int:
    """Refuse a file that is not an atlas of this schema (or of version 3, which it reads and
    upgrades): its tables and columns, and its version, which it returns."""
    try:
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        if not tables:  # an empty file opens as an empty database
            raise AtlasError(f"{path} is empty: no atlas there (run 'mechsynth grid GRID.toml --db {path}' first)")
        if "meta" not in tables:
            raise AtlasError(f"{path} is an SQLite file but not a mechsynth atlas (no 'meta' table)")
        row = conn.execute("SELECT value FROM meta WHERE key = 'schema_version'").fetchone()
        version = row[0] if row else None
        if version is None:
            query = conn.execute("SELECT value FROM meta WHERE key = 'query'").fetchone()
            if query and {"codes", "units"} <= tables:  # a count's checkpoint (synth/execution/checkpoint.py)
                raise AtlasError(f"{path} is the checkpoint of a count ({query[0]}), not an atlas")
            raise AtlasError(f"{path} is an SQLite file but not a mechsynth atlas (its meta table names no schema "
                             "version)")
        if version not in (str(SCHEMA_VERSION), "3"):
            raise AtlasError(
                f"{path} is an atlas of schema version {version}, but this mechsynth reads only versions 3 and "
                f"{SCHEMA_VERSION}; use a new atlas file (or the mechsynth release that wrote it)")
        for table, wanted in (_TABLES if version == str(SCHEMA_VERSION) else _TABLES_3).items():
            have = {r[1] for r in conn.execute(f"PRAGMA table_info({table})")}
            if not wanted <= have:
                missing = sorted(wanted - have)
                raise AtlasError(f"{path} is not a complete mechsynth atlas: table '{table}' lacks "
                                 f"{', '.join(missing) if have else 'everything (it does not exist)'}")
        return int(version)
    except sqlite3.DatabaseError as exc:
        raise AtlasError(f"{path} is not an SQLite atlas or is damaged ({exc})") from None


@contextmanager
def _reading(path):
    """Turn an error of a damaged file, met while reading it, into one sentence."""
    try:
        yield
    except (sqlite3.DatabaseError, ValueError, KeyError, MalformedChain) as exc:  # a row that no run wrote
        raise AtlasError(f"the atlas {path} is damaged ({exc}); it was only read, not changed") from None


def _check_pages(conn: sqlite3.Connection, path: Path) -> None:
    """SQLite's own check of every page (about 3 ms a megabyte), so that damage is found before any output."""
    with _reading(path):
        verdict = conn.execute("PRAGMA quick_check(1)").fetchone()[0]
    if verdict != "ok":
        detail = " ".join(verdict.replace("*** in database main ***", "").split())
        raise AtlasError(f"the atlas {path} is damaged ({detail}); it was only read, not changed")


_CHECKED_READ_BYTES = 512 * 2**20  # larger atlases are checked page by page only before a write


def open_atlas(path: str | Path, *, write: bool = False, check_pages: bool | None = None) -> sqlite3.Connection:
    """Open an atlas (read-only by default), checking its schema version and its pages.

    With ``write=True`` an existing file is first opened read-only and checked, a missing
    file is created with the current schema; a read-only file or directory is refused before
    anything is written.  ``check_pages`` runs SQLite's page check (default: for files up to
    512 MiB; damage in a larger one is reported when a query meets it).

    Raises
    ------
    AtlasError
        One sentence: missing file, read-only path, not an atlas, other schema version.
    """
    path = Path(path)
    if write:
        refuse_unwritable(path)
        fresh = not path.exists() or path.stat().st_size == 0
        if not fresh:  # read-only first: a file that is not an atlas, or a damaged one, is never written to
            open_atlas(path, check_pages=True).close()
        try:
            conn = sqlite3.connect(path, timeout=30, isolation_level=None)
            if fresh:
                with transaction(conn):
                    if not conn.execute("SELECT 1 FROM sqlite_master WHERE name = 'meta'").fetchone():
                        for statement in _SCHEMA.split(";"):
                            if statement.strip():
                                conn.execute(statement)
                        conn.execute("INSERT INTO meta VALUES ('schema_version', ?), ('created', ?)",
                                     (str(SCHEMA_VERSION), time.strftime("%Y-%m-%dT%H:%M:%S")))
        except sqlite3.DatabaseError as exc:
            raise AtlasError(f"cannot write the atlas {path}: {exc}") from None
    else:
        if not path.is_file():
            raise AtlasError(f"no atlas at {path} (run 'mechsynth grid GRID.toml --db {path}' first)")
        try:
            conn = sqlite3.connect(read_only_uri(path), uri=True, timeout=30, isolation_level=None)
        except sqlite3.DatabaseError as exc:
            raise AtlasError(f"cannot open the atlas {path}: {exc}") from None
    try:
        version = _check_version(conn, path)
        if check_pages or (check_pages is None and not write and path.stat().st_size <= _CHECKED_READ_BYTES):
            _check_pages(conn, path)
        if version == 3 and write:
            _upgrade(conn, path)
        elif version == 3:
            for statement in _READ_3:
                conn.execute(statement)
    except AtlasError:
        conn.close()
        raise
    conn.execute("PRAGMA foreign_keys = OFF")
    # for --where id=… and rotation=… (NULL in, NULL out: a chain that is no gear train has no rotation graph)
    conn.create_function("chain_id", 1, lambda c: None if c is None else chain_id(c), deterministic=True)
    return conn


@contextmanager
def transaction(conn: sqlite3.Connection):
    """``BEGIN IMMEDIATE`` … ``COMMIT``, rolled back on any exception (a Ctrl-C included): a write
    lands whole or not at all."""
    conn.execute("BEGIN IMMEDIATE")
    try:
        yield conn
        conn.execute("COMMIT")
    except BaseException:
        if conn.in_transaction:  # a Ctrl-C right after COMMIT finds none
            conn.execute("ROLLBACK")
        raise


def _upgrade(conn: sqlite3.Connection, path: Path) -> None:
    """Version 3 to 4 in one transaction: the chains' mesh counts (0) and the gear-train tables."""
    try:
        with transaction(conn):
            for statement in _UPGRADE_3:
                conn.execute(statement)
    except sqlite3.DatabaseError as exc:
        raise AtlasError(f"cannot upgrade the atlas {path} from schema version 3 to {SCHEMA_VERSION}: {exc}") from None


# -------------------------------------------------------------------- locks
def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def acquire_run(conn: sqlite3.Connection, path: Path, grid: Grid, executor: str) -> int:
    """Record a grid run of ``grid`` on ``executor`` (``"local 2"``, ``"dask tcp://…"``) and take the
    atlas's run lock; returns the run's id.  A lock left by a killed run is taken over.

    Raises
    ------
    AtlasLocked
        Another live run holds the lock.
    """
    host = socket.gethostname()
    with transaction(conn):
        row = conn.execute("SELECT run, pid, host, started FROM run_lock WHERE id = 1").fetchone()
        if row is not None:
            run, pid, other_host, started = row
            if other_host != host or (_alive(pid) and pid != os.getpid()):
                when = time.strftime("%H:%M:%S", time.localtime(started))
                raise AtlasLocked(
                    f"the atlas {path} is being written by another grid run (pid {pid} on {other_host}, "
                    f"started {when}); wait for it to finish or use another atlas file"
                )
            conn.execute("UPDATE runs SET status = 'killed', finished = ? WHERE id = ? AND status = 'running'",
                         (time.time(), run))
            conn.execute("DELETE FROM run_lock")
        now = time.time()
        run = conn.execute(
            "INSERT INTO runs (pid, host, grid, started, status, executor) VALUES (?, ?, ?, ?, 'running', ?)",
            (os.getpid(), host, grid.source, now, executor)).lastrowid
        conn.execute("INSERT INTO run_lock VALUES (1, ?, ?, ?, ?)", (run, os.getpid(), host, now))
    return run


def release_run(conn: sqlite3.Connection, run: int, status: str, units_run: int) -> None:
    """End run ``run`` with ``status`` (done, interrupted, failed) and ``units_run``, and free the lock."""
    with transaction(conn):
        conn.execute("UPDATE runs SET status = ?, finished = ?, units_run = ? WHERE id = ?",
                     (status, time.time(), units_run, run))
        conn.execute("DELETE FROM run_lock WHERE run = ?", (run,))
