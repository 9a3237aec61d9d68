"""Grid runs into an atlas: every unit of every cell computed once (a process pool or Dask) and
committed in one transaction, so a run killed at any instant resumes where it stopped; and the
sizing of a grid before it runs.

Guarantees
----------
* One transaction per finished unit: its chains (gear trains with their ``trains`` rows),
  memberships, mechanisms and its ``done`` status commit together, so a run killed at any instant (Ctrl-C, ``kill -9``,
  power loss) leaves every unit either fully stored or still pending.
* A rerun of the same grid skips ``done`` units; ``INSERT OR IGNORE`` on certificates
  means no chain or mechanism is ever stored twice.
* A gear cell's units are its link–axis trees (:mod:`synth.atlas.trains`), run and committed
  the same way.
* A second run on the same atlas while the first is alive is refused (``run_lock``
  row checked inside ``BEGIN IMMEDIATE``; a lock left by a killed run is taken over).

Example
-------
>>> import tempfile, os
>>> from synth.atlas import parse_grid, summary
>>> grid = parse_grid('dof = 1\\nlinks = "4..8"')
>>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
>>> run_grid(grid, db, workers=1).chains_new
19
>>> summary(db)["by_code"]["440/0"]
9
"""

from __future__ import annotations

import json
import os
import sqlite3
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from mechbase import Row

from ..errors import ImpossibleParameters, InvalidOption, QueryTooLarge, option
from ..execution.scheduler import SchedulerUnreachable, connect as _connect
from ..structure.chain import Chain
from ..structure.code import Code
from ..execution.executor import Executor
from ..structure.joints import MESH, PRISMATIC
from ..synthesis.type_synthesis import Unit, mechanisms_of, plan_jobs, plan_many, run_unit
from ..gears.train import GearTrain
from .database import acquire_run, open_atlas, refuse_unwritable, release_run, transaction
from .grid import Cell, GearCell, Grid
from .trains import TrainUnit, keep_representatives, plan_gear_cell, store_trains, train_row, unit_trains

__all__ = ["GridRunResult", "SchedulerUnreachable", "UnitTask", "UnitRows", "compute_unit", "run_grid", "size_grid"]


# ------------------------------------------------------------------- worker
@dataclass(frozen=True)
class UnitTask:
    """One unit of a grid cell as a worker receives it: chains of a unit of the engine, or gear
    trains of a link–axis tree (``input_link``: store input-link mechanisms of chains too)."""

    cell: str
    unit: Unit | TrainUnit
    input_link: bool


@dataclass
class UnitRows:
    """The atlas rows one unit produced: chains, link counts, mechanisms and gear trains, and its
    seconds (``rotation``: a cell of rotation graphs, one train each)."""

    cell: str
    unit: str
    chains: list[tuple]
    link_counts: list[tuple]
    mechanisms: list[tuple]
    seconds: float
    trains: list[tuple] = field(default_factory=list)
    rotation: bool = False


def _chain_rows(chain: Chain, fractionated: bool, input_link: bool, out: UnitRows) -> None:
    """Add a chain (in its canonical labelling) to a unit's rows: its chain row, link counts and mechanisms."""
    cert, code, degrees = chain.certificate, chain.code, chain.degrees
    kinds = chain.kinds
    out.chains.append((cert, str(code), str(Code(code.assortment, code.v, None, code.n1)), chain.dof, chain.h,
                       chain.links, chain.loops, chain.v, kinds.count(PRISMATIC), max(degrees),
                       " ".join(map(str, sorted(degrees, reverse=True))), int(fractionated),
                       json.dumps(chain.to_dict(), separators=(",", ":")), kinds.count(MESH)))
    out.link_counts += [(cert, i + 2, n) for i, n in enumerate(code.assortment) if n]
    mechanisms = mechanisms_of(chain)
    if input_link and chain.dof != 0:  # a truss on a frame (W = 0) has no input link: nothing moves
        mechanisms += mechanisms_of(chain, input_link=True)
    out.mechanisms += [(cert, m.frame, -1 if m.input_link is None else m.input_link) for m in mechanisms]


def compute_unit(task: UnitTask) -> UnitRows:
    """Run one unit and turn its chains (or gear trains) and mechanisms into atlas rows (runs on a worker)."""
    start = time.perf_counter()
    out = UnitRows(task.cell, task.unit.key, [], [], [], 0.0)
    if isinstance(task.unit, TrainUnit):
        out.rotation = task.unit.graphs == "rotation"
        for train, rank in unit_trains(task.unit):
            chain = train.to_chain().canonical()
            _chain_rows(chain, train.is_fractionated(), False, out)
            out.trains.append(train_row(GearTrain.from_chain(chain), chain.certificate, rank))
    else:
        # a non-degenerate 1-DOF chain is never fractionated (each part would need W >= 1)
        conv = task.unit.conventions
        fractionable = conv.rigid_subchains or task.unit.code.dof(conv.h) + conv.slack != 1 or task.unit.code.n1
        for chain in run_unit(task.unit):  # canonical; with prismatic pairs the chains of the cell's W
            _chain_rows(chain, bool(fractionable and chain.is_fractionated()), task.input_link, out)
    out.seconds = time.perf_counter() - start
    return out


def _commit(conn: sqlite3.Connection, result: UnitRows, run: int) -> int:
    """Store one finished unit in one transaction; returns the number of new chains."""
    with transaction(conn):
        found, displaced = len(result.chains), []
        if result.rotation:
            result, displaced = keep_representatives(conn, result.cell, result)
        before = conn.total_changes
        conn.executemany("INSERT OR IGNORE INTO chains (certificate, code, base_code, dof, h, links, loops, v, "
                         "prismatic, max_degree, degrees, fractionated, chain, meshes) "
                         "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
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
        store_trains(conn, result, ids, displaced)
        conn.execute(
            "UPDATE units SET status = 'done', chains = ?, mechanisms = ?, seconds = ?, finished = ?, run = ? "
            "WHERE cell = ? AND unit = ?",
            (found, len(result.mechanisms), result.seconds, time.time(), run, result.cell, result.unit))
    return new


# ------------------------------------------------------------------ running
@dataclass
class GridRunResult(Row):
    """What a grid run did: units (total, already done, run now), chains and mechanisms, time (its row
    gives the seconds to the millisecond and the rate to a tenth)."""

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

    row_keys = ("status", "units_total", "units_skipped", "units_run", "chains_found", "chains_new",
                "mechanisms_found", "seconds=seconds_shown", "executor", "cells", "chains_per_second=rate_shown")

    @property
    def chains_per_second(self) -> float:
        return self.chains_found / self.seconds if self.seconds > 0 else 0.0

    @property
    def seconds_shown(self) -> float:
        return round(self.seconds, 3)

    @property
    def rate_shown(self) -> float:
        return round(self.chains_per_second, 1)


def _cell_row(cell: Cell | GearCell, units: int) -> tuple:
    """The ``cells`` row of a cell (a gear cell: h = 3, any v, non-fractionated trains only for F ≥ 2)."""
    if isinstance(cell, GearCell):
        return cell.key, cell.dof, 3, cell.links, 0, None, 0, int(cell.dof == 1), 0, "[]", units
    return (cell.key, cell.dof, cell.h, cell.links, cell.v[0], cell.v[1], int(cell.rigid_subchains),
            int(cell.fractionated), int(cell.planar_only), json.dumps(cell.require), units)


def _register(conn: sqlite3.Connection, plans: Sequence[tuple[Cell | GearCell, list[Unit | TrainUnit]]]) -> None:
    with transaction(conn):
        for cell, units in plans:
            conn.execute("INSERT OR IGNORE INTO cells VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)", _cell_row(cell, len(units)))
            conn.executemany("INSERT OR IGNORE INTO units (cell, unit, code) VALUES (?, ?, ?)",
                             [(cell.key, u.key, str(u.code)) for u in units])


def _refuse_impossible(grid: Grid, plans) -> None:
    """A grid none of whose cells can hold a chain (every one ruled out by the counting equations: a v, a
    requirement or a link count no chain meets) is refused with the first cell's reason, as ``chains``
    refuses that query; a grid with one possible cell runs, its impossible cells left empty.

    >>> from synth.atlas.grid import parse_grid
    >>> _refuse_impossible(parse_grid('dof = 1\\nlinks = 8\\nv = "50..60"'), [])
    Traceback (most recent call last):
    synth.errors.ImpossibleParameters: no cell of grid 'grid' can hold a chain: W=1 n=8 v=50..60 rigid=0 frac=1 planar=0: v = 50 is too large: a chain with K = 3 loops and 8 links has v ≤ 2(K − 1) + n1 = 4
    """
    if grid.gear_cells or any(units for _, units in plans):
        return
    reasons = []
    for cell in grid.cells:
        try:
            plan_jobs(cell.query())
        except ImpossibleParameters as exc:
            reasons.append(f"{cell.key}: {exc}")
        else:
            return
    if reasons:
        raise ImpossibleParameters(f"no cell of grid {grid.name!r} can hold a chain: {reasons[0]}")


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
    where = f"dask {scheduler}" if scheduler else f"local {workers}"  # the run's record says where it ran
    path = Path(db)
    refuse_unwritable(path)  # refuse a read-only atlas before connecting anywhere
    if path.exists() and path.stat().st_size:
        open_atlas(path).close()  # not an atlas, or another version: refused before any planning
    client = _connect(scheduler, connect_timeout) if scheduler else None
    start = time.perf_counter()
    executor = Executor(workers, client)  # the units' executor; its pool (if any) plans too
    try:
        # planned on this machine, before the atlas is created: a grid the engine refuses leaves no file behind
        plans = list(zip(grid.cells, plan_many([cell.query() for cell in grid.cells], skip_impossible=True,
                                               executor=executor if client is None else None)))
        plans += [(cell, plan_gear_cell(cell)) for cell in grid.gear_cells]
        _refuse_impossible(grid, plans)
        conn = open_atlas(path, write=True)
    except BaseException:
        if client is not None:
            client.close()
        executor.close()
        raise
    try:
        run = acquire_run(conn, path, grid, where)
        # WAL + synchronous=NORMAL: a commit survives kill -9 without an fsync per unit (a power
        # cut may lose the last units, never consistency); back to a plain journal at the end
        conn.execute("PRAGMA journal_mode = WAL")
        conn.execute("PRAGMA synchronous = NORMAL")
        conn.execute("PRAGMA cache_size = -65536")  # 64 MiB of pages: the certificate index stays in memory
        conn.execute("PRAGMA wal_autocheckpoint = 10000")  # checkpoint rarely during a run (and at its end)
        status, done_now = "failed", 0
        result = GridRunResult("running", 0, 0, 0, executor=where, cells=len(plans))
        try:
            _register(conn, plans)
            done = {(c, u) for c, u in conn.execute("SELECT cell, unit FROM units WHERE status = 'done'")}
            tasks = [UnitTask(cell.key, u, grid.input_link) for cell, units in plans
                     for u in units
                     if (cell.key, u.key) not in done]
            result.units_total = sum(len(units) for _, units in plans)
            result.units_skipped = result.units_total - len(tasks)
            if tasks:
                with transaction(conn):
                    conn.executemany("UPDATE units SET attempts = attempts + 1 WHERE cell = ? AND unit = ?",
                                     [(t.cell, t.unit.key) for t in tasks])
            bar = None
            if progress:
                from tqdm import tqdm

                bar = tqdm(total=len(tasks), unit="unit", file=sys.stderr, disable=None, desc=grid.name,
                           dynamic_ncols=True)
            try:
                for res in executor.map(compute_unit, tasks, ordered=False):
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
            executor.close()  # before the atlas is released: no worker outlives the run
            result.units_run = done_now
            result.status = status
            result.seconds = time.perf_counter() - start
            release_run(conn, run, status, done_now)
    finally:
        if conn.execute("PRAGMA journal_mode").fetchone()[0] == "wal":
            try:
                conn.execute("PRAGMA journal_mode = DELETE")
            except sqlite3.DatabaseError:
                pass  # a reader keeps the WAL open: the file stays in WAL mode, still consistent
        conn.close()
        if client is not None:
            client.close()
        executor.close()  # no-op after the run; the atlas was locked by another run
    return result


# -------------------------------------------------------------------- sizing
_GRID_LIMIT_SECONDS = 86400.0  # refused without --force when estimated to take longer (on the workers)
_GRID_NOTE_SECONDS = 600.0  # said on stderr before the run starts
_BYTES_PER_MECHANISM = 210  # atlas bytes per stored mechanism, its chain's row included (W = 1, n ≤ 12: 204 and 210)


def size_grid(grid: Grid, *, processes: int, db, scheduler: bool = False) -> str | None:
    """Estimate the large cells of a grid (as a chain query is: from exact runs at smaller sizes,
    timing chains and their mechanisms) and refuse a grid of more than a day, or one whose atlas
    would not fit on the disk of ``db``'s folder, with :class:`QueryTooLarge`; a grid of more than
    ten minutes passes with a sentence to show before it starts (returned).

    >>> from synth.atlas import parse_grid
    >>> size_grid(parse_grid('dof = 1\\nlinks = 8'), processes=2, db="a.sqlite") is None
    True
    """
    import math
    import shutil

    from ..execution.sizes import describe_seconds, magnitude
    from ..synthesis.estimate import FLOOR_SECONDS, PLAIN_MARGIN, estimate, needs_compiled, sized_loops

    large = [c for c in grid.cells if c.loops >= sized_loops(c.h, multiple=c.v != (0, 0))]
    if not large:
        return None
    # first on the plain path, which compiles nothing (its time a floor, its counts with a margin: the query's
    # sizing, estimate.FLOOR_SECONDS), then, if that refuses nothing, timed on the compiled path as the cells run
    for plain in (True, False) if any(needs_compiled(c.query()) for c in large) else (False,):
        log_seconds, log_chains, worst = -math.inf, -math.inf, None
        for cell in sorted(large, key=lambda c: -c.links):
            found = estimate(cell.query(), work="mechanisms", budget=1.2 / len(large), plain=plain)
            if found is None:
                if plain:  # (the compiled path's sizing says so)
                    break
                raise QueryTooLarge(f"the grid's cell {cell.key} is large and its size cannot be estimated; give "
                                    f"{option('force')} to run it anyway")
            log_seconds = _log_sum(log_seconds, found.log10_seconds)
            log_chains = _log_sum(log_chains, found.log10_chains)
            worst = worst or (cell, found)
        else:
            wall = log_seconds - math.log10(processes)
            log_bytes = log_chains + math.log10(_BYTES_PER_MECHANISM)
            where = ("on the scheduler's workers (one core shown)" if scheduler
                     else f"on {processes} worker{'s' if processes != 1 else ''}")
            cells = f"its cell {worst[0].key} holds" if len(large) == 1 else f"its {len(large)} large cells hold"
            floor = f"at least (at {FLOOR_SECONDS * 1e6:g} µs a mechanism) " if plain else ""
            size = (f"{cells} about {magnitude(_power(log_chains), log_chains)} mechanisms, "
                    f"{floor}{describe_seconds(_power(wall), wall)} {where} and "
                    f"{magnitude(_power(log_bytes - 9), log_bytes - 9)} GB in the atlas (extrapolated from exact runs at "
                    "smaller sizes)")
            if wall > math.log10(_GRID_LIMIT_SECONDS):
                raise QueryTooLarge(f"this grid is too large to run unasked: {size}; give {option('force')} to run it "
                                    "anyway (it can be stopped and resumed)")
            folder = os.path.dirname(os.path.abspath(db))
            free = shutil.disk_usage(folder).free if os.path.isdir(folder) else math.inf
            if log_bytes > math.log10(max(free, 1)) + (math.log10(PLAIN_MARGIN) if plain else 0.0):
                raise QueryTooLarge(f"this grid does not fit on the disk: {size}, and {folder} has "
                                    f"{free / 1e9:.1f} GB free; give {option('force')} to run it anyway")
    if wall > math.log10(_GRID_NOTE_SECONDS):
        return f"a long grid: {size}"
    return None


def _log_sum(a: float, b: float) -> float:
    """log10(10^a + 10^b) without overflow."""
    import math

    top = max(a, b)
    return top if math.isinf(top) else top + math.log10(10 ** (a - top) + 10 ** (b - top))


def _power(log10: float) -> float:
    return 10.0 ** log10 if log10 < 308 else float("inf")
