"""Run every benchmark on this machine and write ``benchmarks/REPORT.md`` with tables and plots.

Run: ``benchmarks/run`` (or ``python benchmarks/report.py [--quick] [--reps N] [--projection N] [--no-sixteen]``).
CSVs go to ``benchmarks/out/`` (not committed); the plots the report shows go to
``benchmarks/figures/``.  Set ``GENSPARSEG`` to a gensparseg binary to add the side-by-side
column (nauty's ``geng`` built with M. Larsson's nauty-laman-plugin ``prunesparse.h``, MIT licence;
never a dependency).

The report's header names the machine (CPU, cores, memory), the commit measured, the run
(start time) and the load average before and after: every figure in it comes from that one
run.  Timings are minima of repeated runs; run it on a quiet machine.
"""

from __future__ import annotations

import argparse
import datetime as dt
import importlib.util
import os
import platform
import shutil
import subprocess
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


def _machine() -> str:
    """CPU model, cores, memory, Python and OR-Tools versions, the commit measured."""
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        memory = f"{os.sysconf('SC_PAGE_SIZE') * os.sysconf('SC_PHYS_PAGES') / 2**30:.0f} GiB"
    except (ValueError, OSError, AttributeError):
        memory = "memory unknown"
    try:
        commit = subprocess.run(["git", "describe", "--always", "--dirty"], cwd=ROOT, capture_output=True,
                                text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown commit"
    from importlib.metadata import version

    return (f"{cpu}, {os.cpu_count()} cores, {memory}; Python {platform.python_version()}, "
            f"OR-Tools {version('ortools')}; commit `{commit}`")


def _load_average() -> str:
    try:
        return " / ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "unknown"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small cases only (a minute)")
    parser.add_argument("--reps", type=int, default=3, help="timed runs of each small synthesis case (minimum kept)")
    parser.add_argument("--projection", type=int, metavar="LINKS",
                        help="also project the 1-DOF count at LINKS links from a sample of units (e.g. 18)")
    parser.add_argument("--no-sixteen", dest="sixteen", action="store_false",
                        help="skip the whole 1-DOF count at 16 links on 2 workers (about 10 minutes; never with --quick)")
    args = parser.parse_args(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")
    started = time.perf_counter()
    run_id = dt.datetime.now().strftime("%Y-%m-%d %H:%M")
    load_before = _load_average()
    gensparseg = os.environ.get("GENSPARSEG")
    parts = [
        "# Benchmark report",
        "",
        f"Run {run_id} of `benchmarks/run{' --quick' if args.quick else ''}` on {_machine()}. "
        "Every number below was measured by this one run; timings are the minimum of repeated runs "
        "where a `reps` column says so; counts carry an `error` column (engine − published reference, 0 expected).",
        "",
        f"Load average (1/5/15 min) at the start: {load_before}; at the end: LOAD_AT_END. "
        + (f"gensparseg: `{gensparseg}` (the `gensparseg_s` column: 2 processes, same run, alternating)."
           if gensparseg else "gensparseg: not measured (set GENSPARSEG to a binary to add it)."),
    ]

    codes = _load("bench_codes").run(args.quick)
    parts += ["", "## Number synthesis (CP-SAT, one model per K)", "",
              _table(codes, ["query", "codes", "reference", "error", "seconds"])]

    bench = _load("bench_synthesis")
    synthesis = bench.run(quick=args.quick, full=not args.quick, reps=args.reps)
    parts += ["", "## Type synthesis: time against link count", "",
              "One process: stage A (branch multigraphs), stage B CP-SAT, exact sub-chain test and nauty "
              "(`one_core_s`: the listing; `count_one_core_s`: the count, which builds no chain where stage B "
              "already gives one vector per chain); "
              "then the real command `mechsynth chains --count --workers 2` with start-up included "
              "(`wall_2_workers_s`: minimum of `reps` runs; `cpu_2_workers_s`: its CPU time, all processes).", "",
              _table(synthesis, ["series", "links", "v", "chains", "reference", "error", "units", "stage_a_s",
                                 "cpsat_s", "subchain_s", "nauty_s", "one_core_s", "count_one_core_s", "wall_2_workers_s",
                                 "cpu_2_workers_s", "reps", "candidates_per_chain", "chains_per_s"]),
              _figure("synthesis.png")]
    if gensparseg:
        side = [r for r in synthesis if "gensparseg_s" in r]
        parts += ["", "## Side by side with gensparseg (1-DOF chains, 2 processes each)", "",
                  "Same run, alternating mechsynth and gensparseg for each size; minimum wall times; "
                  "`ratio` = mechsynth / gensparseg (below 1: mechsynth is faster).", "",
                  _table(side, ["links", "chains", "gensparseg_chains", "gensparseg_agrees", "wall_2_workers_s",
                                "gensparseg_s", "ratio", "reps"])]
    if args.sixteen and not args.quick:
        row = bench.large(16)
        parts += ["", "## 16 links, whole count", "",
                  "`mechsynth chains --dof 1 --links 16 --count --force --workers 2`, start-up included; CPU of all "
                  "processes; `peak_rss_mib`: the largest single process (parent or worker).", "",
                  _table([row], list(row))]
    by_v = bench.by_v_rows(synthesis)
    if by_v:
        parts += ["", "## Multiple joints: candidates per chain by v", "",
                  "CP-SAT solutions of stage B (candidates) that the exact sub-chain test and nauty reduce to "
                  "the chains; one process.", "", _table(by_v, list(by_v[0]))]
    if args.projection:
        projection = _load("bench_projection")
        rows = [projection.project(1, args.projection, codes=10**6, units=30, seed=1)]
        parts += ["", f"## Projection of the 1-DOF count at {args.projection} links from a sample of units", "",
                  "Two-stage random sample (codes, then units of each; method in `benchmarks/bench_projection.py` "
                  "and PROFILE.md): every code's stage A, 30 units of each; CPU seconds of one process; `_se`: one standard error.", "",
                  _table(rows, ["links", "codes", "codes_sampled", "units_sampled", "seed", "units_projected",
                                "chains_projected", "chains_se", "published", "cpu_s_projected", "cpu_s_se",
                                "sampling_s"])]

    universal = _load("bench_universal")
    if universal is not None:
        rows = universal.run(args.quick)
        parts += ["", "## Type synthesis in every motion space h and for open chains", "",
                  "One process; `per_chain_vs_h3`: time per chain over that of the planar row with the nearest "
                  "number of chains (goal: at most 3).", "",
                  _table(rows, ["series", "h", "links", "chains", "units", "seconds", "chains_per_s",
                                "candidates_per_chain", "us_per_chain", "per_chain_vs_h3"])]

    atlas = _load("bench_atlas")
    if atlas is not None:
        rows = atlas.run(args.quick)
        parts += ["", "## Mechanisms and grid throughput", "", _table(rows, list(rows[0]))]

    balance = _load("bench_balance")
    if balance is not None:
        fit_rows = balance.run_fit(args.quick)
        arm_rows = balance.run_arm(args.quick)
        (HERE / "out").mkdir(exist_ok=True)
        balance._write_csv(HERE / "out" / "balance_fit.csv", fit_rows)  # the figure can be redrawn from the run
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
    text = "\n".join(parts).replace("LOAD_AT_END", _load_average())
    (HERE / "REPORT.md").write_text(text)
    print(f"wrote {HERE / 'REPORT.md'} in {time.perf_counter() - started:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
