"""Lists too long to hold: written to a temporary file in chunks, read back one chunk at a time.

A count's largest codes have hundreds of thousands of units (20 links: some 10^5–10^6 branch
multigraphs in one code).  The worker that finds them writes them here as it goes, ``chunk`` at
a time, and hands the parent a :class:`Spilled` — a path and a length, a few hundred bytes
pickled — which the parent reads chunk by chunk as it submits the units: neither process ever
holds more than a chunk of them.  The files live in a directory the parent made for the run and
removes when the run ends (even on Ctrl-C; ``kill -9`` leaves it in the system's temporary folder,
named ``mechsynth-units-…``).

Example
-------
>>> import tempfile
>>> with tempfile.TemporaryDirectory() as folder:
...     items = spill(iter(range(10)), folder, chunk=4)
...     isinstance(items, Spilled), len(items), list(items), list(items)[8:]
(True, 10, [0, 1, 2, 3, 4, 5, 6, 7, 8, 9], [8, 9])
>>> spill(iter("ab"), "/nonexistent", chunk=4)   # as short as a chunk: a list, no file
['a', 'b']

A count with a checkpoint keeps each code's units instead (:func:`write_kept`): one file a code
beside the checkpoint, in the same chunks between a header naming what they are the units of and a
trailer with their number, written under a temporary name and renamed only when complete, so that
a run resumed after a kill reads them back (:func:`read_kept`) instead of running stage A again; a
truncated or foreign file is not read.

>>> with tempfile.TemporaryDirectory() as folder:
...     path = os.path.join(folder, "440_0.units")
...     units = write_kept(iter(range(10)), path, chunk=4, label="plan-a|440/0")
...     again = read_kept(path, "plan-a|440/0")
...     len(again), list(again), read_kept(path, "plan-b|440/0"), os.listdir(folder)
(10, [0, 1, 2, 3, 4, 5, 6, 7, 8, 9], None, ['440_0.units'])
"""

from __future__ import annotations

import os
import pickle
import struct
import tempfile
from collections.abc import Iterable, Iterator
from itertools import islice

__all__ = ["Kept", "Spilled", "read_kept", "spill", "write_kept"]


class Spilled:
    """The items a :func:`spill` wrote, in order: ``len`` and iteration (each pass reads the file
    again, one chunk at a time); :meth:`remove` deletes the file."""

    def __init__(self, path: str, length: int, chunks: int, start: int = 0):
        self.path, self.length, self._chunks, self._start = path, length, chunks, start

    def __len__(self) -> int:
        return self.length

    def __iter__(self) -> Iterator:
        with open(self.path, "rb") as file:
            file.seek(self._start)
            for _ in range(self._chunks):
                yield from pickle.load(file)

    def remove(self) -> None:
        """Delete the file (once every item has been read); a file already gone is no error."""
        try:
            os.unlink(self.path)
        except FileNotFoundError:
            pass


def spill(items: Iterable, directory: str, *, chunk: int) -> list | Spilled:
    """``items`` as a list if there are at most ``chunk`` of them, else written to a new file in
    ``directory`` in pickled lists of ``chunk`` items, as they come (never more than ``chunk`` held).

    Parameters
    ----------
    items : iterable
        Picklable items, read once.
    directory : str
        An existing directory for the file (only touched when the items exceed a chunk).
    chunk : int
        Items held, written and read back at a time (at least 1).
    """
    items = iter(items)
    first = list(islice(items, chunk + 1))
    if len(first) <= chunk:
        return first
    descriptor, path = tempfile.mkstemp(prefix="units-", suffix=".pickle", dir=directory)
    try:
        with os.fdopen(descriptor, "wb") as file:
            length, chunks = _write_chunks(file, first, items, chunk)
    except BaseException:
        os.unlink(path)
        raise
    return Spilled(path, length, chunks)


def _write_chunks(file, part: list, items: Iterator, chunk: int) -> tuple[int, int]:
    """Write ``part`` then the rest of ``items`` to ``file`` in pickled lists of ``chunk`` (never more
    than ``chunk`` held); return the items and the chunks written."""
    length = chunks = 0
    while part:
        head, part = part[:chunk], part[chunk:]
        pickle.dump(head, file, protocol=pickle.HIGHEST_PROTOCOL)
        length, chunks = length + len(head), chunks + 1
        part += islice(items, chunk - len(part))
    return length, chunks


class Kept(Spilled):
    """A code's units kept beside a checkpoint (:func:`write_kept`): read like a :class:`Spilled`
    file, but :meth:`remove` leaves the file, which the count deletes once the code is complete."""

    def remove(self) -> None:
        """Nothing: the file outlives its reading until its code is committed complete."""


_MAGIC = b"mechsynth-units-1"
# after the chunks: the magic, the units, the chunks and where the chunks begin
_TRAILER = struct.Struct(f"<{len(_MAGIC)}sQQQ")
_LABEL = struct.Struct("<Q")  # the label's length in bytes, before the label (UTF-8)


def write_kept(items: Iterable, path: str, *, chunk: int, label: str) -> Kept:
    """Write ``items`` to ``path`` as :func:`spill` does (whatever their number), after a header
    holding ``label`` in UTF-8 (what they are: a plan's identity and a code) and before a trailer holding
    their number; under a temporary name in the same folder, flushed to disk and renamed to
    ``path`` only once complete (an interrupted write leaves no ``path`` and no temporary file).

    Parameters
    ----------
    items : iterable
        Picklable items, read once.
    path : str
        The file, in an existing folder; replaced if it exists.
    chunk : int
        Items held, written and read back at a time (at least 1).
    label : str
        What the items are; :func:`read_kept` reads them back only for the same label.
    """
    directory, name = os.path.split(path)
    descriptor, part = tempfile.mkstemp(prefix=name + ".", suffix=".part", dir=directory or ".")
    try:
        with os.fdopen(descriptor, "wb") as file:
            header = label.encode()
            file.write(_LABEL.pack(len(header)) + header)
            start = file.tell()
            items = iter(items)
            length, chunks = _write_chunks(file, list(islice(items, chunk)), items, chunk)
            file.write(_TRAILER.pack(_MAGIC, length, chunks, start))
            file.flush()
            os.fsync(file.fileno())
        os.replace(part, path)
    except BaseException:
        os.unlink(part)
        raise
    return Kept(path, length, chunks, start)


def read_kept(path: str, label: str) -> Kept | None:
    """The items :func:`write_kept` wrote to ``path`` with ``label``; None when there is no such
    file, or it is truncated, not one of these files, or written with another label.

    Only the header and the trailer are read (a truncated file has no trailer at its end): a file
    of a million units is checked in a moment.
    """
    wanted = label.encode()
    try:
        with open(path, "rb") as file:
            size = os.fstat(file.fileno()).st_size
            if size < _LABEL.size + len(wanted) + _TRAILER.size:
                return None
            file.seek(size - _TRAILER.size)
            magic, length, chunks, start = _TRAILER.unpack(file.read(_TRAILER.size))
            file.seek(0)
            (given,) = _LABEL.unpack(file.read(_LABEL.size))
            if magic != _MAGIC or given != len(wanted) or file.read(given) != wanted or start != file.tell():
                return None
    except OSError:
        return None
    return Kept(path, length, chunks, start)
