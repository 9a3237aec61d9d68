"""Run every benchmark on this machine and write ``benchmarks/REPORT.md`` with tables and plots.

Run: ``benchmarks/run`` (or ``python benchmarks/report.py [--quick]``).  CSVs go to
``benchmarks/out/`` (not committed); the plots the report shows go to ``benchmarks/figures/``.
"""

from __future__ import annotations

import argparse
import datetime as dt
import importlib.util
import os
import platform
import shutil
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE))
FIGURES = HERE / "figures"


def _table(rows: list[dict], columns: list[str]) -> str:
    def cell(v):
        if isinstance(v, float):
            return f"{v:.4g}"
        return "" if v is None else str(v)

    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(cell(r.get(c)) for c in columns) + " |" for r in rows]
    return "\n".join(lines)


def _figure(name: str) -> str:
    src = HERE / "out" / name
    if not src.exists():
        return ""
    FIGURES.mkdir(exist_ok=True)
    shutil.copy(src, FIGURES / name)
    return f"\n![{name}](figures/{name})\n"


def _load(name: str):
    path = HERE / f"{name}.py"
    if not path.exists():
        return None
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small cases only (a minute)")
    args = parser.parse_args(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")
    started = time.perf_counter()
    parts = [
        "# Benchmark report",
        "",
        f"Written by `benchmarks/run` on {dt.date.today()} — {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}. Every number below was measured by "
        "that run; counts carry an `error` column (engine − published reference, 0 expected).",
    ]

    codes = _load("bench_codes").run(args.quick)
    parts += ["", "## Number synthesis (CP-SAT, one model per K)", "",
              _table(codes, ["query", "codes", "reference", "error", "seconds"])]

    synthesis = _load("bench_synthesis").run(quick=args.quick, full=not args.quick)
    parts += ["", "## Type synthesis: time against link count", "",
              "One process: stage A (branch multigraphs), stage B CP-SAT, exact sub-chain test and nauty; "
              "then the real command `mechsynth chains --count --workers 2` with start-up included.", "",
              _table(synthesis, ["series", "links", "v", "chains", "reference", "error", "units", "stage_a_s",
                                 "cpsat_s", "subchain_s", "nauty_s", "one_core_s", "wall_2_workers_s",
                                 "candidates_per_chain", "chains_per_s"]),
              _figure("synthesis.png")]

    atlas = _load("bench_atlas")
    if atlas is not None:
        rows = atlas.run(args.quick)
        parts += ["", "## Mechanisms and grid throughput", "", _table(rows, list(rows[0]))]

    balance = _load("bench_balance")
    if balance is not None:
        fit_rows = balance.run_fit(args.quick)
        arm_rows = balance.run_arm(args.quick)
        (HERE / "out").mkdir(exist_ok=True)
        balance.plot_pareto(fit_rows, HERE / "out" / "balance_pareto.png")
        shown = [r for r in fit_rows if r.get("default") or r.get("grid") == getattr(balance, "DEFAULT_GRID", None)]
        parts += ["", "## Spring fits: time against error reached", "",
                  "Compression crank-and-rocker fitted to Φ0·sin φ; errors relative to Φ0 on a fine check grid. "
                  "`pareto`: on the time/error front of all runs; `default`: the method the CLI uses.", "",
                  _table(shown, ["case", "norm", "method", "grid", "seconds", "max_rel_error", "rms_rel_error",
                                 "pareto", "default"]),
                  _figure("balance_pareto.png"),
                  "", "## Arm residual check: time against sampled configurations", "",
                  _table(arm_rows, ["arm", "samples", "seconds", "max_residual", "relative_residual", "us_per_sample"])]
        hard = getattr(balance, "run_hard_cases", None)
        if hard is not None:
            rows = hard()
            parts += ["", "## Stability on the hard cases", "", _table(rows, list(rows[0]))]

    parts += ["", f"Total time of this run: {time.perf_counter() - started:.0f} s.", ""]
    (HERE / "REPORT.md").write_text("\n".join(parts))
    print(f"wrote {HERE / 'REPORT.md'} in {time.perf_counter() - started:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
