"""What the benchmarks share: their tables under ``benchmarks/out``, the ``--quick`` command line and a
script's refusals (one sentence, exit status 2).

>>> import tempfile, pathlib; folder = pathlib.Path(tempfile.mkdtemp())
>>> write_csv(folder / "demo.csv", [{"links": 8, "chains": 16}]).read_text().splitlines()
['links,chains', '8,16']
"""

from __future__ import annotations

import argparse
import csv
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

__all__ = ["OUT", "write_csv", "print_rows", "emit", "refusals"]

#: where every benchmark writes its tables and figures
OUT = Path(__file__).resolve().parent / "out"


def write_csv(path: Path, rows: Sequence[dict], columns: Sequence[str] | None = None) -> Path:
    """Write ``rows`` to ``path`` (its folder made if need be) under ``columns`` (default: the first row's
    keys); a key of a row that is no column is left out."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(columns or rows[0]), extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    return path


def print_rows(run: Callable[[bool], list[dict]], description: str) -> None:
    """A benchmark's command line: ``--quick`` (a smaller run) passed to ``run``, each row printed."""
    parser = argparse.ArgumentParser(description=description.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a smaller run of a few seconds")
    for row in run(parser.parse_args().quick):
        print(row)


def emit(text: str) -> None:
    """Print a result on stdout; a reader that stops early (``| head``) changes no exit status and
    sees no traceback."""
    try:
        print(text, flush=True)
    except BrokenPipeError:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


def refusals(script: str):
    """``fail`` (one sentence on stderr after ``script:``, exit status 2) and an ``argparse.ArgumentParser``
    class whose errors go through it: how a benchmark script refuses bad input.

    >>> fail, Parser = refusals("demo")
    >>> Parser(prog="demo").parse_args(["--nope"])
    Traceback (most recent call last):
    SystemExit: 2
    """
    def fail(sentence: str) -> None:
        print(f"{script}: {sentence}", file=sys.stderr)
        raise SystemExit(2)

    class Parser(argparse.ArgumentParser):
        def error(self, message):
            fail(message)

    return fail, Parser
