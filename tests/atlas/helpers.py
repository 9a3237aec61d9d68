"""What several atlas tests do to an atlas file: build one from a grid file's text, read its rows (SQLite),
and take it back to an older schema."""

from __future__ import annotations

import sqlite3
from pathlib import Path


def grid_atlas(db: Path, grid: str) -> Path:
    """The atlas ``db`` of the grid file ``grid`` (its text), run in this process."""
    from synth.atlas import parse_grid, run_grid

    run_grid(parse_grid(grid), db, workers=1)
    return db


def sql(db: Path, statement: str, *args) -> list[tuple]:
    """The rows of one statement on the atlas ``db`` (the connection closed after it)."""
    with sqlite3.connect(db) as conn:
        rows = list(conn.execute(statement, args))
    conn.close()
    return rows


def as_version_3(db: Path) -> None:
    """Make ``db`` what an atlas of schema version 3 holds: no mesh counts, no gear-train tables."""
    with sqlite3.connect(db) as conn:
        conn.execute("DROP TABLE trains")
        conn.execute("DROP TABLE rotations")
        conn.execute("ALTER TABLE chains DROP COLUMN meshes")
        conn.execute("UPDATE meta SET value = '3' WHERE key = 'schema_version'")
    conn.close()


def units_in_reverse(monkeypatch) -> None:
    """Make every atlas run hand its gear units to the pool last tree first (the order units finish in
    on a real pool is not fixed; a rotation cell's result must not depend on it)."""
    from synth.atlas import runs

    class LastTreeFirst(runs.Executor):
        def map(self, fn, items, **options):
            items = list(items)
            return super().map(fn, items[::-1] if fn is runs.compute_unit else items, **options)

    monkeypatch.setattr(runs, "Executor", LastTreeFirst)
