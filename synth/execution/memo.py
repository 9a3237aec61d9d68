"""Solver results kept on disk between runs, so that a query asked again runs no solver.

Number synthesis's codes and stage A's branch multigraphs of a small code are the only CP-SAT
results the engine needs for most queries, and loading OR-Tools (with the pandas it imports)
costs about 0.3 s — most of a small query's time.  :func:`remembered` keeps each such result in
a file the first time it is computed; later runs read it instead and never load the solver.
A count on the command line keeps each finished code's count the same way (:func:`keep`,
:func:`recall`): asked again, it runs none of that code's units.

Where
    ``$MECHSYNTH_CACHE`` if set (``off`` turns the store off), else
    ``$XDG_CACHE_HOME/mechsynth``, else ``~/.cache/mechsynth``.  Deleting the folder is always safe.
What makes a result stale
    Entries live in a folder named by the engine's *fingerprint*: a hash of the source of the
    modules whose results are kept (``synth/structure``, ``synth/synthesis``) and of pynauty's
    ``__init__.py`` (which names its version and nauty's).  An edit or an upgrade of either reads none of the older entries.
What can go wrong
    Nothing a user sees: an entry is one JSON file holding its own key, written to a temporary
    file and renamed into place (two processes writing the same entry write the same bytes); an
    entry that cannot be read or holds another key is computed again and rewritten; a folder
    that cannot be written to is simply not used.

>>> import uuid; key, calls = uuid.uuid4().hex, []
>>> first = remembered("demo", key, lambda: calls.append(1) or [1, 2])
>>> again = remembered("demo", key, lambda: calls.append(1) or [1, 2])
>>> first == again == [1, 2], len(calls) == (1 if cache_folder() else 2)
(True, True)
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
import tempfile
from collections.abc import Callable
from functools import lru_cache
from pathlib import Path
from typing import TypeVar

__all__ = ["remembered", "recall", "keep", "is_remembered", "cache_folder"]

T = TypeVar("T")
_ENGINE = Path(__file__).resolve().parents[1]  # the synth package
_SOURCES = ("structure", "synthesis")  # the results kept depend on these modules only


def cache_folder() -> Path | None:
    """The folder the results of this engine go to, or None when the store is off.

    >>> cache_folder() is None or cache_folder().name.startswith("engine-")
    True
    """
    return _store()


@lru_cache(maxsize=1)
def _store() -> Path | None:
    base = os.environ.get("MECHSYNTH_CACHE")
    if base is not None and base.strip().lower() in ("off", "0", "no", "false", ""):
        return None
    if base is None:
        base = os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.join(Path.home(), ".cache"), "mechsynth")
    return Path(base) / f"engine-{_fingerprint()}"


def _fingerprint() -> str:
    # nauty's version: pynauty's __init__.py names it.  Located, not imported (a query of codes loads no
    # nauty) and not read from the package's metadata (importlib.metadata costs a query 15–20 ms).
    nauty = importlib.util.find_spec("pynauty")
    digest = hashlib.sha1(b"nauty " + (Path(nauty.origin).read_bytes() if nauty and nauty.origin else b"unknown"))
    for folder in _SOURCES:
        for path in sorted((_ENGINE / folder).glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _entry(folder: Path, kind: str, key: str) -> Path:
    return folder / kind / f"{hashlib.sha1(key.encode()).hexdigest()}.json"


def is_remembered(kind: str, key: str) -> bool:
    """Whether an earlier run stored a value under (``kind``, ``key``) (a hint: it is read, and
    checked, only by :func:`remembered`)."""
    folder = _store()
    return folder is not None and _entry(folder, kind, key).is_file()


def recall(kind: str, key: str, *, decode: Callable[[object], T] = lambda x: x) -> T | None:
    """The value an earlier run of this engine stored under (``kind``, ``key``) with :func:`keep`,
    or None (nothing stored, the store off, or an entry that cannot be read or holds another key).

    >>> import uuid; key = uuid.uuid4().hex
    >>> recall("demo", key) is None
    True
    >>> keep("demo", key, {"42/0": 2}); recall("demo", key) == ({"42/0": 2} if cache_folder() else None)
    True
    """
    folder = _store()
    if folder is None:
        return None
    try:
        entry = json.loads(_entry(folder, kind, key).read_text())
        if entry["key"] == key:
            return decode(entry["value"])
    except (OSError, ValueError, KeyError, TypeError):
        pass  # not there, or not readable
    return None


def keep(kind: str, key: str, value: T, *, encode: Callable[[T], object] = lambda x: x) -> None:
    """Store ``value`` under (``kind``, ``key``) for later runs (nothing when the store is off or
    cannot be written to); ``key`` must say everything the value depends on."""
    folder = _store()
    if folder is None:
        return
    path = _entry(folder, kind, key)
    text = json.dumps({"key": key, "value": encode(value)})
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, temporary = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    except OSError:
        return  # a folder that cannot be written to: the result is used, not kept
    try:
        with os.fdopen(fd, "w") as out:
            out.write(text)
        os.replace(temporary, path)
    except OSError:
        Path(temporary).unlink(missing_ok=True)


def remembered(kind: str, key: str, compute: Callable[[], T], *, encode: Callable[[T], object] = lambda x: x,
               decode: Callable[[object], T] = lambda x: x) -> T:
    """``compute()``, or the value an earlier run of this engine stored under (``kind``, ``key``).

    ``key`` must say everything the value depends on (a problem's ``repr``); ``encode`` turns the
    value into JSON-able data and ``decode`` back.
    """
    value = recall(kind, key, decode=decode)
    if value is None:
        value = compute()
        keep(kind, key, value, encode=encode)
    return value
