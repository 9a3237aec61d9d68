"""Resumable counts: a count's finished codes and units, committed to SQLite as they finish.

A checkpoint file belongs to one query (its *fingerprint*: what is counted, W, n, v, code,
conventions, requirements, the plan format).  While a count runs, every finished unit's
count is committed at least once a second and whenever a code is complete; a complete
code replaces its units by one row.  A run killed at any instant (``kill -9``, power
loss) leaves committed rows that are all exact, so the next run with the same file skips
them and the total is identical to an uninterrupted run.  A count on this machine also keeps each
code's stage A beside the file (``FILE.units/``, see :func:`synth.execution.spill.write_kept` and
``kept_units_folder`` in :mod:`synth.synthesis.type_synthesis`) until the code is complete, so a
resumed run does not redo it.

Example
-------
>>> import os, tempfile
>>> path = os.path.join(tempfile.mkdtemp(), "c.sqlite")
>>> with Checkpoint(path, "plan-a", "chains W=1 n=8") as ck:
...     ck.add_unit("440/0|ab", "440/0", 9)
...     ck.finish_code("440/0", 9, units=1)
>>> Checkpoint(path, "plan-a", "chains W=1 n=8").codes
{'440/0': 9}
>>> Checkpoint(path, "plan-b", "chains W=1 n=10")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
synth.execution.checkpoint.CheckpointMismatch: the checkpoint ... belongs to another query (chains W=1 n=8), not to chains W=1 n=10; ...
"""

from __future__ import annotations

import sqlite3
import time
from dataclasses import dataclass
from pathlib import Path

from ..errors import SynthesisError, option
from .sqlite_files import read_only_uri

__all__ = ["Checkpoint", "CheckpointError", "CheckpointMismatch", "CheckpointState", "PLAN_FORMAT", "read_checkpoint"]

# Bump when unit keys or the split of a query into units change: an old checkpoint is refused.
PLAN_FORMAT = 2  # 2: units carry slack and prismatic pairs (joint kinds in the chain)

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS codes (code TEXT PRIMARY KEY, count INTEGER NOT NULL, units INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS units (unit TEXT PRIMARY KEY, code TEXT NOT NULL, count INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS shared_units (code TEXT PRIMARY KEY, units INTEGER NOT NULL);
"""
# shared_units: by code, the units a second count (tight-reverse) counted by the first count's own path, so that
# a comparison of the two can say how many were no independent check (a file of before it has none: read as 0)


class CheckpointError(SynthesisError):
    """The checkpoint file cannot be read or written."""


class CheckpointMismatch(CheckpointError):
    """The checkpoint file belongs to another query."""


def _check_file(path: Path) -> tuple[str, str]:
    """Refuse, after reading it only, a file that is not a checkpoint (an atlas, a damaged or foreign file);
    return the identity and the query in words it was written for."""
    try:
        conn = sqlite3.connect(read_only_uri(path), uri=True, timeout=30)
    except sqlite3.DatabaseError as exc:
        raise CheckpointError(f"cannot read the checkpoint {path} ({exc}); it was not changed") from None
    try:
        tables = {name: {r[1] for r in conn.execute(f"PRAGMA table_info({name})")}
                  for (name,) in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'").fetchall()}
        wanted = {"meta": {"key", "value"}, "codes": {"code", "count", "units"}, "units": {"unit", "code", "count"}}
        identity = (conn.execute("SELECT value FROM meta WHERE key = 'identity'").fetchone()
                    if "meta" in tables else None)
        optional = {"shared_units"}  # (a checkpoint written before 29 Nov 2026, 18 h, has none)
        if not set(wanted) <= set(tables) <= set(wanted) | optional or any(not wanted[t] <= tables[t] for t in wanted) \
                or identity is None:
            what = "a mechsynth atlas" if "chains" in tables else "an SQLite file of something else"
            raise CheckpointError(f"{path} is not a checkpoint of mechsynth but {what}; it was not changed "
                                  f"(give a new {option('checkpoint', 'FILE')})")
        verdict = conn.execute("PRAGMA quick_check(1)").fetchone()[0]
        if verdict != "ok":
            raise CheckpointError(f"the checkpoint {path} is damaged ({' '.join(verdict.split())}); it was not "
                                  f"changed (give a new {option('checkpoint', 'FILE')})")
        query = conn.execute("SELECT value FROM meta WHERE key = 'query'").fetchone()
        return identity[0], query[0] if query else "unknown"
    except sqlite3.DatabaseError as exc:
        raise CheckpointError(f"{path} is not a usable checkpoint ({exc}); it was not changed") from None
    finally:
        conn.close()


class Checkpoint:
    """The finished codes (``codes``: code → count) and units of one query: a unit's key is looked up
    in the file (:meth:`has_unit`), never loaded with the others (a code of 20 links may have half a
    million units committed, each key some 500 characters); ``unit_counts`` sums them by code.

    Parameters
    ----------
    path : path
        SQLite file, created when missing.
    identity : str
        What the query computes (a digest of its plan); a file written for another identity is refused.
    description : str
        The query in words, quoted when the file is refused.
    every : float
        Seconds between commits of finished units (a finished code commits at once).
    log : callable, optional
        Called with one line after every commit (the CLI prints it when stderr is not a terminal).
    """

    def __init__(self, path, identity: str, description: str, *, every: float = 1.0, log=None):
        self.path = Path(path)
        self._every = every
        self._log = log
        self._pending: list[tuple] = []
        self._last = time.monotonic()
        self.committed_units = self.committed_codes = 0
        wanted = f"{PLAN_FORMAT}:{identity}"
        if self.path.is_dir():
            raise CheckpointError(f"the checkpoint {self.path} is a directory, not a file")
        directory = self.path.parent  # ('.' for a bare file name)
        if not directory.is_dir():
            raise CheckpointError(f"cannot create the checkpoint {self.path}: the directory {directory} does not exist")
        if self.path.exists() and self.path.stat().st_size:
            identity, query = _check_file(self.path)  # read-only first: any other file is refused untouched
            if identity != wanted:
                raise CheckpointMismatch(f"the checkpoint {self.path} belongs to another query ({query}), not to "
                                         f"{description}; give a new {option('checkpoint', 'FILE')} or repeat that query")
        try:
            self._conn = sqlite3.connect(self.path, timeout=30, isolation_level=None)
            self._conn.execute("PRAGMA journal_mode = WAL")  # a commit survives kill -9 without an fsync each
            self._conn.execute("PRAGMA synchronous = NORMAL")
            self._conn.execute("BEGIN IMMEDIATE")
            for statement in _SCHEMA.split(";"):
                if statement.strip():
                    self._conn.execute(statement)
            row = self._conn.execute("SELECT value FROM meta WHERE key = 'identity'").fetchone()
            if row is None:
                self._conn.execute("INSERT INTO meta VALUES ('identity', ?), ('query', ?), ('created', ?)",
                                   (wanted, description, time.strftime("%Y-%m-%dT%H:%M:%S")))
            stored = self._conn.execute("SELECT value FROM meta WHERE key = 'query'").fetchone()
            self._conn.execute("COMMIT")
        except sqlite3.DatabaseError as exc:
            raise CheckpointError(f"{self.path} is not a usable checkpoint ({exc})") from None
        if row is not None and row[0] != wanted:
            self._conn.close()
            raise CheckpointMismatch(f"the checkpoint {self.path} belongs to another query ({stored[0]}), not to "
                                     f"{description}; give a new {option('checkpoint', 'FILE')} or repeat that query")
        self.codes = dict(self._conn.execute("SELECT code, count FROM codes"))
        # code -> (units committed, their count), for the codes not complete
        done = {code: (k, n) for code, k, n in self._conn.execute("SELECT code, COUNT(*), SUM(count) FROM units GROUP BY code")}
        self.unit_counts = {code: n for code, (_, n) in done.items()}
        self.resumed_units = sum(k for k, _ in done.values()) + sum(n for (n,) in self._conn.execute("SELECT units FROM codes"))

    @property
    def units(self) -> dict[str, tuple[str, int]]:
        """Every committed unit of the codes not complete: key → (code, count) (read from the file
        on each call: for inspection; a count asks :meth:`has_unit`)."""
        return {unit: (code, n) for unit, code, n in self._conn.execute("SELECT unit, code, count FROM units")}

    def has_unit(self, unit: str) -> bool:
        """Whether the unit of key ``unit`` (``code|…``) was committed by an earlier run (looked up only
        for the codes with units committed)."""
        if unit.split("|", 1)[0] not in self.unit_counts:
            return False
        return self._conn.execute("SELECT 1 FROM units WHERE unit = ?", (unit,)).fetchone() is not None

    def add_unit(self, unit: str, code: str, count: int, *, shared: bool = False) -> None:
        """Record a finished unit (committed within ``every`` seconds); ``shared``: a second count counted it by
        the first count's own path (:attr:`CheckpointState.shared_units`)."""
        self._pending.append(("unit", unit, code, count))
        if shared:
            self._pending.append(("shared", code))
        if time.monotonic() - self._last >= self._every:
            self.commit()

    def finish_code(self, code: str, count: int, *, units: int) -> None:
        """Record a complete code (all its ``units``, ``count`` in total) and commit now."""
        self._pending.append(("code", code, count, units))
        self.commit()

    def commit(self) -> None:
        """Write everything recorded so far in one transaction."""
        if not self._pending:
            return
        pending, self._pending = self._pending, []
        try:
            self._conn.execute("BEGIN IMMEDIATE")
            units = []  # consecutive unit rows, written in one call (h = 2, 11 links: 476 243 of them)
            for kind, *row in pending + [("end",)]:
                if kind == "unit":
                    units.append(row)
                    continue
                if kind == "shared":  # (in the transaction of its unit: a unit lost in a kill loses its mark too)
                    self._conn.execute("INSERT INTO shared_units VALUES (?, 1) "
                                       "ON CONFLICT(code) DO UPDATE SET units = units + 1", row)
                    continue
                self._conn.executemany("INSERT OR REPLACE INTO units VALUES (?, ?, ?)", units)
                units = []
                if kind == "code":
                    self._conn.execute("INSERT OR REPLACE INTO codes VALUES (?, ?, ?)", row)
                    self._conn.execute("DELETE FROM units WHERE code = ?", (row[0],))
            self._conn.execute("COMMIT")
        except sqlite3.DatabaseError as exc:
            raise CheckpointError(f"cannot write the checkpoint {self.path}: {exc}") from None
        self.committed_units += sum(1 for kind, *_ in pending if kind == "unit")
        self.committed_codes += sum(1 for kind, *_ in pending if kind == "code")
        self._last = time.monotonic()
        if self._log is not None:
            codes = f"{self.committed_codes} code{'s' * (self.committed_codes != 1)}"
            self._log(f"checkpoint {self.path}: {self.committed_units} units ({codes} complete) "
                      f"committed in this run, {self.resumed_units} units done before")

    def close(self) -> None:
        self.commit()
        try:
            self._conn.execute("PRAGMA journal_mode = DELETE")  # one file again, as an atlas after its run
        except sqlite3.DatabaseError:
            pass  # another reader keeps the WAL open: the file stays in WAL mode, still consistent
        self._conn.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if exc[0] is None or exc[0] is KeyboardInterrupt:
            self.close()  # what finished before Ctrl-C is kept
        else:
            self._conn.close()
        return False



@dataclass(frozen=True)
class CheckpointState:
    """What a checkpoint holds, read without changing it (a count may be writing it meanwhile).

    ``complete`` maps each complete code to (its count, its units); ``partial`` each code begun
    and not complete to (the count of its units done, those units).  ``identity`` is the plan
    the file belongs to (plan format and digest), ``query`` that query in words.  ``shared_units``:
    of the units done, those a second count (``tight-reverse``) counted by the first count's own
    path, no independent check of it (:func:`~synth.synthesis.stage_b.count_reversed`).
    """

    path: str
    identity: str
    query: str
    created: str
    complete: dict
    partial: dict
    shared_units: int = 0

    @property
    def units(self) -> int:
        """Units done, in complete and partial codes."""
        return sum(units for _, units in self.complete.values()) + sum(units for _, units in self.partial.values())

    @property
    def chains(self) -> int:
        """Chains (or mechanisms) counted so far."""
        return sum(n for n, _ in self.complete.values()) + sum(n for n, _ in self.partial.values())


def read_checkpoint(path) -> CheckpointState:
    """The state of the checkpoint ``path``, read only (a running count is not disturbed).

    Raises :class:`CheckpointError` for a missing file or one that is not a checkpoint.

    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "c.sqlite")
    >>> with Checkpoint(path, "plan-a", "chains W=1 n=8") as ck:
    ...     ck.add_unit("521/0|x", "521/0", 5)
    ...     ck.add_unit("440/0|a", "440/0", 6)
    ...     ck.finish_code("521/0", 5, units=1)
    >>> state = read_checkpoint(path)
    >>> state.complete, state.partial, state.units, state.chains
    ({'521/0': (5, 1)}, {'440/0': (6, 1)}, 2, 11)
    """
    path = Path(path)
    if not path.is_file():
        raise CheckpointError(f"there is no checkpoint {path}" + (" (it is a folder)" if path.is_dir() else ""))
    identity, query = _check_file(path)
    conn = sqlite3.connect(read_only_uri(path), uri=True, timeout=30)
    try:
        conn.execute("BEGIN")  # one snapshot of both tables, whatever a writer commits meanwhile
        created = conn.execute("SELECT value FROM meta WHERE key = 'created'").fetchone()
        complete = {code: (n, units) for code, n, units in conn.execute("SELECT code, count, units FROM codes")}
        partial = {code: (n, units) for code, n, units in
                   conn.execute("SELECT code, SUM(count), COUNT(*) FROM units GROUP BY code ORDER BY MIN(rowid)")}
        has_shared = conn.execute("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'shared_units'").fetchone()
        shared = conn.execute("SELECT COALESCE(SUM(units), 0) FROM shared_units").fetchone()[0] if has_shared else 0
    except sqlite3.DatabaseError as exc:
        raise CheckpointError(f"cannot read the checkpoint {path} ({exc})") from None
    finally:
        conn.close()
    return CheckpointState(str(path), identity, query, created[0] if created else "", complete, partial, shared)
