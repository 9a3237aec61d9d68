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
from typing import Any, TextIO

from .._argtypes import workers

__all__ = ["add_commands", "run_scene_command", "format_result"]

_STATUS = {"met": "ok  ", "failed": "FAIL", "skipped": "skip"}


def add_commands(sub) -> None:
    """Add ``scene FILE`` / ``scene --all DIR`` to the sub-parsers ``sub``."""
    p = sub.add_parser("scene", help="run a scene file (models/NAME.toml) and check its [expect] table",
                       description="Run one scene, or every scene of a directory with --all; "
                                   "each expectation is reported as met or not.")
    p.add_argument("file", nargs="?", help="the scene file (TOML)")
    p.add_argument("--all", metavar="DIR", help="run every scene *.toml of DIR (files without [scene] are skipped)")
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--out", metavar="DIR", default="out", help="where drawings and plots are written (default: out/)")
    p.add_argument("--workers", type=workers, default=1, help="processes for type synthesis (default 1)")
    p.set_defaults(run=run_scene_command)


def run_scene_command(args, out: TextIO | None = None, err: TextIO | None = None) -> int:
    """Run the command parsed into ``args``; return the exit status."""
    from synth.errors import InvalidOption
    from ..scene import run_directory, run_scene

    out = out or sys.stdout
    err = err or sys.stderr
    if (args.file is None) == (args.all is None):
        raise InvalidOption("give a scene file or --all DIR, not both or neither")
    if args.all is not None:
        result = run_directory(args.all, out_dir=args.out, workers=args.workers)
        if args.format == "json":
            out.write(json.dumps(result.to_dict(), ensure_ascii=False) + "\n")
            for _, message in result.errors:
                err.write(f"mechsynth: {message}\n")
        else:
            _print_directory(result, out)
        return 2 if result.errors else (0 if result.ok else 1)
    result = run_scene(args.file, out_dir=args.out, workers=args.workers)
    if args.format == "json":
        out.write(json.dumps(result.to_dict(), ensure_ascii=False) + "\n")
    else:
        out.write(format_result(result))
    return 0 if result.ok else 1


# --------------------------------------------------------------------------- table output
def _list(items, limit: int = 12) -> str:
    items = list(items)
    text = " ".join(str(i) for i in items[:limit])
    return text + (f" … (+{len(items) - limit})" if len(items) > limit else "")


def _table(d: dict, limit: int = 12) -> str:
    items = [f"{k}: {v}" for k, v in d.items()]
    return ", ".join(items[:limit]) + (f", … (+{len(items) - limit})" if len(items) > limit else "")


def _summaries(kind: str, r: dict[str, Any]) -> list[str]:
    if kind == "codes":
        return [f"{r['count']} codes: {_list(r['codes'])}", f"per K: {_table(r['by_loops'])}; i_max = {r['i_max']}"]
    if kind in ("count", "chains"):
        lines = [f"{r['count']} chains: {_table(r['by_code'])}",
                 f"by v: {_table(r['by_v'])}; non-planar {r['nonplanar']}; fractionated {r['fractionated']}"]
        for ch in r.get("chains", [])[:10]:
            lines.append(f"  {ch['code']:<12} {ch['joints']}")
        if len(r.get("chains", [])) > 10:
            lines.append(f"  … (+{len(r['chains']) - 10} chains; --format json lists all)")
        return lines
    if kind == "mechanisms":
        return [f"{r['count']} mechanisms: {_table(r['by_code'])}"]
    if kind == "analysis":
        keys = ["code", "links", "loops", "complexity", "v", "dof", "defect", "criterion_holds", "subchain_defect"]
        head = ", ".join(f"{k} = {r[k]}" for k in keys if r.get(k) is not None)
        lines = [head]
        if r.get("formulas"):
            lines.append("W by formula: " + _table(r["formulas"]))
        if r.get("advice"):
            lines.append(r["advice"])
        return lines
    if kind == "drawing":
        return [f"wrote {r['file']} ({r['items']} of {r['of']} items)"]
    if kind == "plot":
        return [f"wrote {', '.join(r['files'])}"]
    if kind == "balance arm":
        return [f"terms: {_list(round(a, 6) for a in r['amplitudes'])} (amplitudes)",
                f"max residual {r['max_residual']:.3g}, relative {r['relative_residual']:.3g}"]
    if kind == "balance spring":
        return [f"c = {r['c']:.6g} N/m, r = {r['r']:.6g} m, r0 = {r['r0']:.6g} m, a = {r['a']:.6g} m",
                f"max relative error {r['max_rel_error']:.4g}; active bounds {', '.join(r['active_bounds']) or 'none'}"]
    if kind == "balance prismatic":
        return [f"C_min = {r['C_min']:.6g}, C = {r['C']:.6g}; max com error {r['max_com_error']:.3g}, "
                f"inertia error {r['max_inertia_error']:.3g}"]
    if kind == "balance pantograph":
        return [f"point weights {_table(r['point_weights'])}",
                f"spring amplitude {r['term']['amplitude']:.6g} N·m, drive force {r['drive_force']:.6g} N, "
                f"relative residual {r['relative_residual']:.3g}"]
    return [json.dumps(r)[:200]]


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
    width = max([5, *(len(k) for k in result.compute)])
    lines = [f"{'scene':<{width}}  {result.name} — {result.description} ({result.path})"]
    for kind in result.compute:
        key = kind
        if kind == "count" and "count" not in result.results and "chains" in result.results:
            continue
        if key not in result.results:
            continue
        for i, line in enumerate(_summaries(kind, result.results[key])):
            lines.append(f"{kind if i == 0 else '':<{width}}  {line}")
    for note in result.notes:
        lines.append(f"{'note':<{width}}  {note}")
    for f in result.files:
        lines.append(f"{'file':<{width}}  {f}")
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
    for _, message in result.errors:
        out.write(f"ERROR {message}\n")
    for path, reason in result.skipped:
        out.write(f"skip  {path}: {reason}\n")
    passed = sum(r.ok for r in result.results)
    out.write(f"{passed} of {len(result.results)} scenes passed"
              f"{f', {len(result.errors)} malformed' if result.errors else ''}"
              f"{f', {len(result.skipped)} files skipped' if result.skipped else ''}\n")
