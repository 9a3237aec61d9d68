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
"""

from __future__ import annotations

import os
import pickle
import tempfile
from collections.abc import Iterable, Iterator
from itertools import islice

__all__ = ["Spilled", "spill"]


class Spilled:
    """The items a :func:`spill` wrote, in order: ``len`` and iteration (each pass reads the file
    again, one chunk at a time); :meth:`remove` deletes the file."""

    def __init__(self, path: str, length: int, chunks: int):
        self.path, self.length, self._chunks = path, length, chunks

    def __len__(self) -> int:
        return self.length

    def __iter__(self) -> Iterator:
        with open(self.path, "rb") as file:
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
    length = chunks = 0
    try:
        with os.fdopen(descriptor, "wb") as file:
            part = first
            while part:
                head, part = part[:chunk], part[chunk:]
                pickle.dump(head, file, protocol=pickle.HIGHEST_PROTOCOL)
                length, chunks = length + len(head), chunks + 1
                part += islice(items, chunk - len(part))
    except BaseException:
        os.unlink(path)
        raise
    return Spilled(path, length, chunks)
