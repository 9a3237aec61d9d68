"""The SQLite atlas: chains and mechanisms of grid runs, resumable unit by unit.

Schema (version 3, ``meta.schema_version``)
-------------------------------------------
``chains``      one row per chain: integer ``id``, ``certificate`` (nauty, canonical) UNIQUE; code
                (with joint composition), base code (without), W, h, n, K, v, number of prismatic
                pairs (grid key ``prismatic``; W then follows the wedge rule), largest link degree,
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
``cells``       the grid cells (key, W, n, v range, conventions, constraints, unit count).
``units``       (cell, unit key) PRIMARY KEY, status pending/done, chains, mechanisms,
                attempts (runs that scheduled it), seconds, finished time, run id.
``runs``        every grid run: pid, host, start/end, status, workers or scheduler.
``run_lock``    at most one row: the run writing the atlas now (pid, host).

Guarantees
----------
* One transaction per finished unit: its chains, memberships, mechanisms and its
  ``done`` status commit together, so a run killed at any instant (Ctrl-C, ``kill -9``,
  power loss) leaves every unit either fully stored or still pending.
* A rerun of the same grid skips ``done`` units; ``INSERT OR IGNORE`` on certificates
  means no chain or mechanism is ever stored twice.
* A second run on the same atlas while the first is alive is refused (``run_lock``
  row checked inside ``BEGIN IMMEDIATE``; a lock left by a killed run is taken over).

Example
-------
>>> import tempfile, os
>>> from synth.atlas.grid import parse_grid
>>> grid = parse_grid('dof = 1\\nlinks = "4..8"')
>>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
>>> run_grid(grid, db, workers=1).chains_new
19
>>> summary(db)["by_code"]["440/0"]
9
>>> sum(1 for _ in export(db, "mechanisms", where=["n=8"]))
71
"""

from __future__ import annotations

import json
import os
import re
import socket
import sqlite3
import sys
import time
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import pynauty

from ..execution.scheduler import SchedulerUnreachable, connect as _connect
from ..synthesis.type_synthesis import Unit, mechanisms_of, plan_many, process_pool, run_unit
from ..structure.chain import Chain, Mechanism
from ..structure.code import Code
from ..analysis.identify import chain_id  # a chain's id: the site's address and every listing's 'id'
from ..errors import InvalidOption, MalformedChain, MalformedCode, SynthesisError
from .grid import Cell, Grid

__all__ = [
    "SCHEMA_VERSION", "AtlasError", "AtlasLocked", "SchedulerUnreachable", "GridRunResult",
    "run_grid", "summary", "export", "parse_where", "open_atlas", "chain_id",
]

SCHEMA_VERSION = 3  # 2: motion space h of chains and cells; 3: prismatic pairs of chains


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
    chain TEXT NOT NULL
);
CREATE INDEX chains_select ON chains (dof, h, links, v, code);
CREATE TABLE link_counts (
    chain INTEGER NOT NULL REFERENCES chains, degree INTEGER NOT NULL, count INTEGER NOT NULL,
    PRIMARY KEY (chain, degree)
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
def _writable(path: Path) -> None:
    """Refuse before touching anything when the file or its directory is read-only.

    Permission bits are checked as well as ``os.access`` so that a file made read-only
    (``chmod a-w``) is respected even by the superuser.
    """
    if path.exists():
        if path.is_dir():
            raise AtlasError(f"the atlas path {path} is a directory, not a file")
        if not os.access(path, os.W_OK) or not path.stat().st_mode & 0o222:
            raise AtlasError(f"cannot write the atlas {path}: the file is read-only")
    directory = path.parent if str(path.parent) else Path(".")
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


def _check_version(conn: sqlite3.Connection, path: Path) -> None:
    """Refuse a file that is not an atlas of this schema: its tables and columns, and its version."""
    try:
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        if "meta" not in tables:
            raise AtlasError(f"{path} is an SQLite file but not a mechsynth atlas (no 'meta' table)")
        row = conn.execute("SELECT value FROM meta WHERE key = 'schema_version'").fetchone()
        version = row[0] if row else None
        if version is None:
            raise AtlasError(f"{path} is an SQLite file but not a mechsynth atlas (its meta table names no schema "
                             "version)")
        if version != str(SCHEMA_VERSION):
            raise AtlasError(
                f"{path} is an atlas of schema version {version}, but this mechsynth reads only version "
                f"{SCHEMA_VERSION}; use a new --db file (or the mechsynth release that wrote it)")
        for table, wanted in _TABLES.items():
            have = {r[1] for r in conn.execute(f"PRAGMA table_info({table})")}
            if not wanted <= have:
                missing = sorted(wanted - have)
                raise AtlasError(f"{path} is not a complete mechsynth atlas: table '{table}' lacks "
                                 f"{', '.join(missing) if have else 'everything (it does not exist)'}")
    except sqlite3.DatabaseError as exc:
        raise AtlasError(f"{path} is not an SQLite atlas or is damaged ({exc})") from None


@contextmanager
def _reading(path):
    """Turn an error of a damaged file, met while reading it, into one sentence."""
    try:
        yield
    except (sqlite3.DatabaseError, ValueError, KeyError, MalformedChain) as exc:  # a row that no run wrote
        raise AtlasError(f"the atlas {path} is damaged ({exc}); it was only read, not changed") from None


def read_only_uri(path: Path) -> str:
    """An SQLite URI that reads ``path`` and creates nothing beside it.

    A file in WAL mode read with ``mode=ro`` gets ``-wal`` and ``-shm`` files next to it; when
    no ``-wal`` file exists (no writer is at work, everything is in the file itself) it is read
    as immutable instead, which creates none.
    """
    uri = f"{path.resolve().as_uri()}?mode=ro"
    return uri if Path(f"{path}-wal").exists() else uri + "&immutable=1"


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
        _writable(path)
        fresh = not path.exists() or path.stat().st_size == 0
        if not fresh:  # read-only first: a file that is not an atlas, or a damaged one, is never written to
            open_atlas(path, check_pages=True).close()
        try:
            conn = sqlite3.connect(path, timeout=30, isolation_level=None)
            if fresh:
                conn.execute("BEGIN IMMEDIATE")
                if not conn.execute("SELECT 1 FROM sqlite_master WHERE name = 'meta'").fetchone():
                    for statement in _SCHEMA.split(";"):
                        if statement.strip():
                            conn.execute(statement)
                    conn.execute("INSERT INTO meta VALUES ('schema_version', ?), ('created', ?)",
                                 (str(SCHEMA_VERSION), time.strftime("%Y-%m-%dT%H:%M:%S")))
                conn.execute("COMMIT")
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
        _check_version(conn, path)
        if check_pages or (check_pages is None and not write and path.stat().st_size <= _CHECKED_READ_BYTES):
            _check_pages(conn, path)
    except AtlasError:
        conn.close()
        raise
    conn.execute("PRAGMA foreign_keys = OFF")
    conn.create_function("chain_id", 1, chain_id, deterministic=True)  # for --where id=…
    return conn


# -------------------------------------------------------------------- locks
def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _acquire(conn: sqlite3.Connection, path: Path, grid: Grid, executor: str) -> int:
    host = socket.gethostname()
    conn.execute("BEGIN IMMEDIATE")
    try:
        row = conn.execute("SELECT run, pid, host, started FROM run_lock WHERE id = 1").fetchone()
        if row is not None:
            run, pid, other_host, started = row
            if other_host != host or (_alive(pid) and pid != os.getpid()):
                when = time.strftime("%H:%M:%S", time.localtime(started))
                raise AtlasLocked(
                    f"the atlas {path} is being written by another grid run (pid {pid} on {other_host}, "
                    f"started {when}); wait for it to finish or use another --db"
                )
            conn.execute("UPDATE runs SET status = 'killed', finished = ? WHERE id = ? AND status = 'running'",
                         (time.time(), run))
            conn.execute("DELETE FROM run_lock")
        now = time.time()
        run = conn.execute(
            "INSERT INTO runs (pid, host, grid, started, status, executor) VALUES (?, ?, ?, ?, 'running', ?)",
            (os.getpid(), host, grid.source, now, executor)).lastrowid
        conn.execute("INSERT INTO run_lock VALUES (1, ?, ?, ?, ?)", (run, os.getpid(), host, now))
        conn.execute("COMMIT")
    except BaseException:
        if conn.in_transaction:  # a Ctrl-C right after COMMIT finds none
            conn.execute("ROLLBACK")
        raise
    return run


def _release(conn: sqlite3.Connection, run: int, status: str, units_run: int) -> None:
    conn.execute("BEGIN IMMEDIATE")
    conn.execute("UPDATE runs SET status = ?, finished = ?, units_run = ? WHERE id = ?",
                 (status, time.time(), units_run, run))
    conn.execute("DELETE FROM run_lock WHERE run = ?", (run,))
    conn.execute("COMMIT")


# ------------------------------------------------------------------- worker
@dataclass(frozen=True)
class _Task:
    cell: str
    unit: Unit
    input_link: bool


@dataclass
class _Result:
    cell: str
    unit: str
    chains: list[tuple]
    link_counts: list[tuple]
    mechanisms: list[tuple]
    seconds: float


def _canonical(chain: Chain) -> Chain:
    """The chain relabelled by nauty's canonical labelling (same joints for isomorphic chains)."""
    labels = pynauty.canon_label(chain._nauty_graph())
    permutation = [0] * chain.links
    for position, link in enumerate(labels[: chain.links]):
        permutation[link] = position
    return chain.relabel(permutation)


def compute_unit(task: _Task) -> _Result:
    """Run one unit and turn its chains and mechanisms into atlas rows (runs on a worker)."""
    start = time.perf_counter()
    chains, counts, mechs = [], [], []
    # a non-degenerate 1-DOF chain is never fractionated (each part would need W >= 1)
    h = task.unit.conventions.h
    conv = task.unit.conventions
    fractionable = conv.rigid_subchains or task.unit.code.dof(h) + conv.slack != 1 or task.unit.code.n1
    for found in run_unit(task.unit):  # (with prismatic pairs: the chains of the cell's W, wedge loops counted)
        cert = found.certificate
        chain = _canonical(found)
        code = chain.code
        degrees = chain.degrees
        row = chain.to_dict()
        prismatic = 0 if chain.kinds is None else chain.kinds.count("prismatic")
        dof = chain.dof
        chains.append((cert, str(code), str(Code(code.assortment, code.v, None, code.n1)), dof, h,
                       chain.links, chain.loops, chain.v, prismatic, max(degrees),
                       " ".join(map(str, sorted(degrees, reverse=True))),
                       int(fractionable and chain.is_fractionated()), json.dumps(row, separators=(",", ":"))))
        counts += [(cert, i + 2, n) for i, n in enumerate(code.assortment) if n]
        mechanisms = mechanisms_of(chain)
        if task.input_link:
            mechanisms += mechanisms_of(chain, input_link=True)
        mechs += [(cert, m.frame, -1 if m.input_link is None else m.input_link) for m in mechanisms]
    return _Result(task.cell, task.unit.key, chains, counts, mechs, time.perf_counter() - start)


def _commit(conn: sqlite3.Connection, result: _Result, run: int) -> int:
    """Store one finished unit in one transaction; returns the number of new chains."""
    conn.execute("BEGIN IMMEDIATE")
    try:
        before = conn.total_changes
        conn.executemany("INSERT OR IGNORE INTO chains (certificate, code, base_code, dof, h, links, loops, v, "
                         "prismatic, max_degree, degrees, fractionated, chain) "
                         "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                         result.chains)
        new = conn.total_changes - before
        ids: dict[str, int] = {}
        certs = [c[0] for c in result.chains]
        for start in range(0, len(certs), 500):  # one lookup per batch, under SQLite's variable limit
            batch = certs[start:start + 500]
            ids.update(conn.execute(f"SELECT certificate, id FROM chains WHERE certificate IN "
                                    f"({','.join('?' * len(batch))})", batch).fetchall())
        conn.executemany("INSERT OR IGNORE INTO link_counts VALUES (?, ?, ?)",
                         [(ids[c], d, n) for c, d, n in result.link_counts])
        conn.executemany("INSERT OR IGNORE INTO members VALUES (?, ?)", [(result.cell, i) for i in ids.values()])
        conn.executemany("INSERT OR IGNORE INTO mechanisms VALUES (?, ?, ?)",
                         [(ids[c], f, i) for c, f, i in result.mechanisms])
        conn.execute(
            "UPDATE units SET status = 'done', chains = ?, mechanisms = ?, seconds = ?, finished = ?, run = ? "
            "WHERE cell = ? AND unit = ?",
            (len(result.chains), len(result.mechanisms), result.seconds, time.time(), run, result.cell, result.unit))
        conn.execute("COMMIT")
    except BaseException:
        if conn.in_transaction:  # a Ctrl-C right after COMMIT finds none
            conn.execute("ROLLBACK")
        raise
    return new


# ------------------------------------------------------------------ running
@dataclass
class GridRunResult:
    """What a grid run did: units (total, already done, run now), chains and mechanisms, time."""

    status: str
    units_total: int
    units_skipped: int
    units_run: int
    chains_found: int = 0
    chains_new: int = 0
    mechanisms_found: int = 0
    seconds: float = 0.0
    executor: str = ""
    cells: int = 0

    @property
    def chains_per_second(self) -> float:
        return self.chains_found / self.seconds if self.seconds > 0 else 0.0

    def to_dict(self) -> dict:
        d = dict(self.__dict__)
        d["chains_per_second"] = round(self.chains_per_second, 1)
        d["seconds"] = round(self.seconds, 3)
        return d


def _register(conn: sqlite3.Connection, plans: Sequence[tuple[Cell, list[Unit]]]) -> None:
    conn.execute("BEGIN IMMEDIATE")
    try:
        for cell, units in plans:
            conn.execute("INSERT OR IGNORE INTO cells VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                         (cell.key, cell.dof, cell.h, cell.links, cell.v[0], cell.v[1], int(cell.rigid_subchains),
                          int(cell.fractionated), int(cell.planar_only), json.dumps(cell.require), len(units)))
            conn.executemany("INSERT OR IGNORE INTO units (cell, unit, code) VALUES (?, ?, ?)",
                             [(cell.key, u.key, str(u.code)) for u in units])
        conn.execute("COMMIT")
    except BaseException:
        if conn.in_transaction:  # a Ctrl-C right after COMMIT finds none
            conn.execute("ROLLBACK")
        raise


def _local_pool(workers: int):
    """The process pool of a local run (planning and units share it), or None for one worker."""
    return process_pool(workers) if workers > 1 else None


def _local(tasks: list[_Task], pool) -> Iterator[_Result]:
    if pool is None or len(tasks) <= 1:
        for task in tasks:
            yield compute_unit(task)
        return
    yield from pool.imap_unordered(compute_unit, tasks, chunksize=1)


def _dask(tasks: list[_Task], client) -> Iterator[_Result]:
    from distributed import as_completed

    futures = client.map(compute_unit, tasks, pure=False) if tasks else []
    try:
        for future in as_completed(futures, loop=client.loop):
            yield future.result()
    finally:
        if futures:
            client.cancel(futures)


def run_grid(
    grid: Grid,
    db: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = False,
    connect_timeout: float = 5.0,
) -> GridRunResult:
    """Run every pending unit of ``grid`` and store the results in the atlas ``db``.

    Parameters
    ----------
    grid : Grid
        From :func:`synth.atlas.grid.load_grid`.
    db : path
        The SQLite atlas; created when missing.  Units already ``done`` are skipped.
    workers : int, optional
        Local processes (default: all cores; 1 runs inline).  Ignored with ``scheduler``.
    scheduler : str, optional
        Address of a Dask distributed scheduler (``tcp://host:8786``): units run there.
    progress : bool
        A tqdm bar on stderr (units, chains found, rate, ETA).
    connect_timeout : float
        Seconds to wait for the scheduler.

    Returns
    -------
    GridRunResult

    Raises
    ------
    AtlasError, AtlasLocked, SchedulerUnreachable
        With one sentence; the atlas is not modified by a refused run.

    Notes
    -----
    Results are committed in completion order, one transaction per unit; the atlas's
    content does not depend on that order, and every query orders its output.
    """
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InvalidOption(f"workers must be a whole number ≥ 1, not {workers!r}")
    workers = workers or os.cpu_count() or 1
    executor = f"dask {scheduler}" if scheduler else f"local {workers}"
    path = Path(db)
    _writable(path)  # refuse a read-only atlas before connecting anywhere
    if path.exists() and path.stat().st_size:
        open_atlas(path).close()  # not an atlas, or another version: refused before any planning
    client = _connect(scheduler, connect_timeout) if scheduler else None
    start = time.perf_counter()
    pool = None
    try:
        pool = _local_pool(workers) if client is None else None
        # planned before the atlas is created: a grid the engine refuses leaves no file behind
        plans = list(zip(grid.cells, plan_many([cell.query() for cell in grid.cells], pool=pool,
                                               skip_impossible=True)))
        conn = open_atlas(path, write=True)
    except BaseException:
        if client is not None:
            client.close()
        if pool is not None:
            pool.terminate()
            pool.join()
        raise
    try:
        run = _acquire(conn, path, grid, executor)
        # WAL + synchronous=NORMAL: a commit survives kill -9 without an fsync per unit (a power
        # cut may lose the last units, never consistency); back to a plain journal at the end
        conn.execute("PRAGMA journal_mode = WAL")
        conn.execute("PRAGMA synchronous = NORMAL")
        conn.execute("PRAGMA cache_size = -65536")  # 64 MiB of pages: the certificate index stays in memory
        conn.execute("PRAGMA wal_autocheckpoint = 10000")  # checkpoint rarely during a run (and at its end)
        status, done_now = "failed", 0
        result = GridRunResult("running", 0, 0, 0, executor=executor, cells=len(grid.cells))
        try:
            _register(conn, plans)
            done = {(c, u) for c, u in conn.execute("SELECT cell, unit FROM units WHERE status = 'done'")}
            tasks = [_Task(cell.key, u, grid.input_link) for cell, units in plans
                     for u in units
                     if (cell.key, u.key) not in done]
            result.units_total = sum(len(units) for _, units in plans)
            result.units_skipped = result.units_total - len(tasks)
            if tasks:
                conn.execute("BEGIN IMMEDIATE")
                conn.executemany("UPDATE units SET attempts = attempts + 1 WHERE cell = ? AND unit = ?",
                                 [(t.cell, t.unit.key) for t in tasks])
                conn.execute("COMMIT")
            bar = None
            if progress:
                from tqdm import tqdm

                bar = tqdm(total=len(tasks), unit="unit", file=sys.stderr, disable=None, desc=grid.name,
                           dynamic_ncols=True)
            try:
                results = _dask(tasks, client) if client is not None else _local(tasks, pool)
                for res in results:
                    result.chains_new += _commit(conn, res, run)
                    result.chains_found += len(res.chains)
                    result.mechanisms_found += len(res.mechanisms)
                    done_now += 1
                    if bar is not None:
                        bar.set_postfix(chains=result.chains_found, refresh=False)
                        bar.update(1)
            finally:
                if bar is not None:
                    bar.close()
            status = "done"
        except KeyboardInterrupt:
            status = "interrupted"
            raise
        finally:
            if pool is not None:
                pool.terminate()  # before the atlas is released: no worker outlives the run
                pool.join()
            result.units_run = done_now
            result.status = status
            result.seconds = time.perf_counter() - start
            _release(conn, run, status, done_now)
    finally:
        if conn.execute("PRAGMA journal_mode").fetchone()[0] == "wal":
            try:
                conn.execute("PRAGMA journal_mode = DELETE")
            except sqlite3.DatabaseError:
                pass  # a reader keeps the WAL open: the file stays in WAL mode, still consistent
        conn.close()
        if client is not None:
            client.close()
        if pool is not None:
            pool.terminate()  # no-op after the run; the atlas was locked by another run
            pool.join()
    return result


# ------------------------------------------------------------------ queries
_FIELDS = {
    "code": "code", "dof": "dof", "w": "dof", "h": "h", "links": "links", "n": "links", "loops": "loops", "k": "loops",
    "v": "v", "max_degree": "max_degree", "maxdeg": "max_degree", "fractionated": "fractionated", "cell": "cell",
    "p": "prismatic", "prismatic": "prismatic",
}
_WHERE_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*(<=|>=|!=|==|=|<|>)\s*(\S.*?)\s*$")
_OPS = {"=": "=", "==": "=", "!=": "!=", "<": "<", "<=": "<=", ">": ">", ">=": ">="}


def parse_where(items: Iterable[str]) -> tuple[str, list]:
    """Turn ``--where`` conditions into an SQL condition on ``chains c`` and its parameters.

    A condition is ``FIELD OP VALUE``; OP is one of ``= != < <= > >=``; conditions are
    joined by AND.  Fields: ``code`` (= or !=, the code as the atlas shows it, e.g.
    ``620/2`` or ``620/0-1``), ``basecode`` (= or !=, any joint composition), ``W``/``dof``, ``h`` (motion space), ``n``/``links``, ``K``/``loops``, ``v``, ``maxdeg``,
    ``fractionated`` (0/1), ``P``/``prismatic`` (number of prismatic pairs), ``nI`` (number of links with I joints, e.g. ``n3>=2``), ``cell``
    (= only, a cell key as shown by ``mechsynth atlas``), ``id`` and ``certificate`` (= or !=: the chain's
    id, 12 hex digits as listings print it, or its nauty certificate).  With ``=`` a number may be a
    range ``A..B``.  Values always travel as SQL parameters, never as SQL text.

    >>> parse_where(["code=6301/0", "n=8..10", "n3>=2"])[1]
    ['6301/0', 8, 10, 3, 2]
    """
    clauses, params = [], []
    for item in items:
        m = _WHERE_RE.match(item) if isinstance(item, str) else None
        if not m:
            raise InvalidOption(f"cannot read the condition {item!r}: write FIELD OP VALUE, e.g. n=10, v<=1, code=6301/0")
        name, op, value = m.group(1), _OPS[m.group(2)], m.group(3)
        key = name.lower()
        degree = re.fullmatch(r"n(\d+)", key)
        if key in ("code", "basecode"):
            if op not in ("=", "!="):
                raise InvalidOption(f"a code is compared with = or != only, not {m.group(2)!r}")
            try:
                code = Code.parse(value)
            except MalformedCode as exc:
                raise InvalidOption(f"in --where {item!r}: {exc}") from None
            if key == "code":
                clauses.append(f"c.code {op} ?")
                params.append(str(code))
            else:
                clauses.append(f"c.base_code {op} ?")
                params.append(str(Code(code.assortment, code.v)))
            continue
        if key in ("id", "certificate"):
            if op not in ("=", "!="):
                raise InvalidOption(f"a chain's {key} is compared with = or != only, not {m.group(2)!r}")
            value = value.strip().lower()
            if key == "id" and not re.fullmatch(r"[0-9a-f]{12}", value):
                raise InvalidOption(f"in --where {item!r}: a chain id is 12 hex digits (the 'id' column of a listing), "
                                    f"not {m.group(3)!r}")
            clauses.append("chain_id(c.certificate) " + op + " ?" if key == "id" else f"c.certificate {op} ?")
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
        else:
            raise InvalidOption(f"unknown field {name!r} in --where {item!r} (fields: code, W, h, n, K, v, P, maxdeg, "
                                "fractionated, nI such as n3, basecode, cell, id, certificate)")
        if key == "fractionated" and value.lower() in ("true", "false"):
            value = "1" if value.lower() == "true" else "0"
        try:
            if ".." in value:
                if op != "=":
                    raise InvalidOption(f"a range A..B goes with '=' only, not {m.group(2)!r} (in {item!r})")
                lo, hi = value.split("..", 1)
                bounds = [int(lo) if lo.strip() else None, int(hi) if hi.strip() else None]
                if any(b is not None and abs(b) >= 2**63 for b in bounds):
                    raise InvalidOption(f"in --where {item!r}: {value} is beyond any count an atlas holds (|x| < 2^63)")
                if None not in bounds and bounds[0] > bounds[1]:
                    raise InvalidOption(f"in --where {item!r}: the range {value} is empty (write the smaller end "
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
            raise InvalidOption(f"in --where {item!r}: {value!r} is not a whole number or a range A..B") from None
        if abs(number) >= 2**63:
            raise InvalidOption(f"in --where {item!r}: {value} is beyond any count an atlas holds (|x| < 2^63)")
        clauses.append(f"{column} {op} ?")
        params += col_params + [number]
    return (" AND ".join(clauses) or "1"), params


_ORDER = "ORDER BY c.dof, c.h, c.links, c.v, c.code, c.certificate"


def export(db: str | Path, what: str = "chains", *, where: Iterable[str] = ()) -> Iterator[dict]:
    """Rows of the atlas (chains or mechanisms) matching ``where``, in a fixed order.

    Chain rows are ``Chain.to_dict()`` plus ``id`` (:func:`chain_id`), ``degrees``, ``fractionated`` and
    ``cells``; mechanism rows add ``frame``, ``input_link``, ``chain_id`` and ``chain_certificate``.

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


def _rows(conn: sqlite3.Connection, what: str, condition: str, params: list) -> Iterator[dict]:
    if what == "chains":
        sql = (f"SELECT c.chain, c.degrees, c.fractionated, "
               f"(SELECT group_concat(m.cell, ';') FROM members m WHERE m.chain = c.id) "
               f"FROM chains c WHERE {condition} {_ORDER}")
        for chain, degrees, fractionated, cells in conn.execute(sql, params):
            row = json.loads(chain)
            row["id"] = chain_id(row["certificate"])
            row["degrees"] = [int(x) for x in degrees.split()]
            row["fractionated"] = bool(fractionated)
            row["cells"] = sorted(cells.split(";")) if cells else []
            yield row
    else:
        sql = (f"SELECT c.chain, k.frame, k.input_link FROM mechanisms k "
               f"JOIN chains c ON c.id = k.chain WHERE {condition} "
               f"{_ORDER}, k.input_link >= 0, k.frame, k.input_link")
        for chain, frame, input_link in conn.execute(sql, params):
            row = json.loads(chain)
            mechanism = Mechanism(Chain.from_dict(row), frame, None if input_link < 0 else input_link)
            row["chain_id"] = chain_id(row["certificate"])
            row["chain_certificate"] = row.pop("certificate")
            row.update(certificate=mechanism.certificate, frame=frame)
            if input_link >= 0:
                row["input_link"] = input_link
            yield row


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
    order = "ORDER BY MIN(h), MIN(links), MIN(dof), MIN(v), code, prismatic"
    shown = ("code || CASE WHEN prismatic = 0 THEN '' ELSE ' P' || prismatic END "
             "|| CASE WHEN h = 3 THEN '' ELSE ' h=' || h END")
    codes = [dict(zip(("code", "dof", "h", "links", "chains"), r)) for r in conn.execute(
        f"SELECT {shown}, MIN(dof), h, MIN(links), COUNT(*) FROM chains GROUP BY h, code, prismatic {order}")]
    by_code = {c["code"]: c["chains"] for c in codes}
    mech_by_code = {code: n for code, n in conn.execute(
        f"SELECT {shown}, COUNT(*) FROM (SELECT c.code AS code, c.h AS h, c.links AS links, c.dof AS dof, "
        f"c.v AS v, c.prismatic AS prismatic FROM mechanisms k JOIN chains c ON c.id = k.chain "
        f"WHERE k.input_link < 0) GROUP BY h, code, prismatic {order}")}
    for c in codes:
        c["mechanisms"] = mech_by_code.get(c["code"], 0)
    cells = []
    for key, dof, h, links, total in conn.execute(
            "SELECT cell, dof, h, links, units FROM cells ORDER BY dof, h, links, cell"):
        done = conn.execute("SELECT COUNT(*) FROM units WHERE cell = ? AND status = 'done'", (key,)).fetchone()[0]
        cell_codes = {code: n for code, n in conn.execute(
            f"SELECT {shown}, COUNT(*) FROM (SELECT c.* FROM members m JOIN chains c ON c.id = m.chain "
            f"WHERE m.cell = ?) GROUP BY code, prismatic {order}", (key,))}
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


