"""``mechsynth scene``: run one scene file, or every scene of a directory with ``--all``.

Mount with ``add_commands(sub)`` on the sub-parsers of ``mechsynth``.
Exit status: 0 when every expectation is met, 1 when one fails, 2 when a scene is
malformed or its problem impossible (one sentence naming the file and the key).

Example
-------
>>> import argparse
>>> parser = argparse.ArgumentParser(prog="mechsynth")
>>> add_commands(parser.add_subparsers(dest="command"))
>>> args = parser.parse_args(["scene", "--all", "models", "--format", "json"])
>>> args.all, args.format
('models', 'json')
"""

from __future__ import annotations

import json
import sys
from typing import TextIO

from .._argtypes import output_folder, workers

__all__ = ["add_commands", "run_scene_command", "format_result"]

_STATUS = {"met": "ok  ", "failed": "FAIL", "skipped": "skip"}


def add_commands(sub) -> None:
    """Add ``scene FILE`` / ``scene --all DIR`` to the sub-parsers ``sub``."""
    p = sub.add_parser("scene", help="run a scene file (models/NAME.toml) and check its [expect] table",
                       description="Run one scene, or every scene of a directory with --all; "
                                   "each expectation is reported as met or not.")
    p.add_argument("file", nargs="?", help="the scene file (TOML)")
    p.add_argument("--all", metavar="DIR", help="run every scene *.toml of DIR (files without [scene] are skipped)")
    p.add_argument("--format", choices=("table", "json"), default="table", help="table (default) or json")
    p.add_argument("-o", "--out", metavar="DIR", type=output_folder,
                   help="write drawings and plots to DIR (default: none is written, and their expectations are "
                   "skipped)")
    p.add_argument("--workers", type=workers, default=1, help="processes for type synthesis (default 1)")
    p.set_defaults(run=run_scene_command)


def run_scene_command(args, out: TextIO | None = None, err: TextIO | None = None) -> int:
    """Run the command parsed into ``args``; return the exit status."""
    from synth import InvalidOption
    from ..scene import run_directory, run_scene

    out = out or sys.stdout
    err = err or sys.stderr
    if (args.file is None) == (args.all is None):
        raise InvalidOption("give a scene file or --all DIR, not both or neither")
    if args.all is not None:
        result = run_directory(args.all, out_dir=args.out, workers=args.workers)
        if args.format == "json":
            out.write(json.dumps(result.to_dict(), ensure_ascii=False) + "\n")
        else:
            _print_directory(result, out)
        for _, message in result.errors:  # a malformed scene is an error: stderr, and the others still run
            err.write(f"mechsynth: {message}\n")
        return 2 if result.errors else (0 if result.ok else 1)
    result = run_scene(args.file, out_dir=args.out, workers=args.workers)
    if args.format == "json":
        out.write(json.dumps(result.to_dict(), ensure_ascii=False) + "\n")
    else:
        out.write(format_result(result))
    return 0 if result.ok else 1


# --------------------------------------------------------------------------- table output
def format_result(result) -> str:
    """A readable summary of a :class:`~mechsynth.scene.SceneResult`.

    >>> from mechsynth.scene import SceneResult
    >>> print(format_result(SceneResult("s.toml", "s", "demo", ("codes",), {"codes": {
    ...     "codes": ["44/0"], "count": 1, "by_loops": {"2": 1}, "links": [6], "i_max": 3}}, ())), end="")
    scene  s — demo (s.toml)
    codes  1 codes: 44/0
           per K: 2: 1; i_max = 3
    no expectations (0.00 s)
    """
    from ..scene import KINDS

    width = max([5, *(len(k) for k in result.compute)])
    lines = [f"{'scene':<{width}}  {result.name} — {result.description} ({result.path})"]
    for kind in result.compute:
        for i, line in enumerate(KINDS[kind].report(result.rows[kind])):
            lines.append(f"{kind if i == 0 else '':<{width}}  {line}")
    for c in result.checks:
        lines.append(f"  {_STATUS[c.status]}  {c.message}")
    met = sum(c.status == "met" for c in result.checks)
    if result.checks:
        lines.append(f"{met} of {len(result.checks)} expectations met ({result.seconds:.2f} s)")
    else:
        lines.append(f"no expectations ({result.seconds:.2f} s)")
    return "\n".join(lines) + "\n"


def _print_directory(result, out: TextIO) -> None:
    for r in result.results:
        met = sum(c.status == "met" for c in r.checks)
        skipped = sum(c.status == "skipped" for c in r.checks)
        extra = f", {skipped} skipped" if skipped else ""
        out.write(f"{'PASS' if r.ok else 'FAIL'}  {r.name:<32} {met}/{len(r.checks)} expectations met{extra} "
                  f"({r.seconds:.2f} s)\n")
        for c in r.checks:
            if c.status != "met":
                out.write(f"      {_STATUS[c.status]}  {c.message}\n")
        for note in r.notes:
            out.write(f"      note  {note}\n")
        for f in r.files:
            out.write(f"      file  {f}\n")
    for path, reason in result.skipped:
        out.write(f"skip  {path}: {reason}\n")
    passed = sum(r.ok for r in result.results)
    out.write(f"{passed} of {len(result.results)} scenes passed"
              f"{f', {len(result.errors)} malformed' if result.errors else ''}"
              f"{f', {len(result.skipped)} files skipped' if result.skipped else ''}\n")
