"""SQLite files read without changing them: the checkpoints of counts and the atlases of grids
are both opened through :func:`read_only_uri` before anything is written to them.

>>> import sqlite3, tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "a.sqlite"; sqlite3.connect(path).close()
>>> read_only_uri(path).endswith("?mode=ro&immutable=1")
True
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["read_only_uri"]


def read_only_uri(path: Path) -> str:
    """An SQLite URI that reads ``path`` and creates nothing beside it.

    A file in WAL mode read with ``mode=ro`` gets ``-wal`` and ``-shm`` files next to it; when
    no ``-wal`` file exists (no writer is at work, everything is in the file itself) it is read
    as immutable instead, which creates none.
    """
    uri = f"{path.resolve().as_uri()}?mode=ro"
    return uri if Path(f"{path}-wal").exists() else uri + "&immutable=1"
