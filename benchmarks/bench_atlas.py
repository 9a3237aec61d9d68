"""Mechanisms per second and grid throughput (chains/s) on 1 and 2 workers, with the speed-up.

Run: ``python benchmarks/bench_atlas.py [--quick]``; writes ``benchmarks/out/atlas.csv``.
Importable: ``run(quick: bool) -> list[dict]`` (used by ``benchmarks/report.py``).

Cases
-----
* ``mechanisms W=1 n=10`` / ``n=12``: type synthesis then the fixed-link choices of every
  chain (nauty orbits), one process; ``per_second`` counts mechanisms.
* ``grid <name>``: ``run_grid`` into a fresh SQLite atlas with 1 and with 2 local workers
  (chains, memberships, mechanisms and unit status committed per unit); ``per_second``
  counts chains, ``speedup`` is time(1 worker) / time(2 workers).  Full mode runs the
  12-link grid (``models/grid_12.toml``) and the small grid; quick mode only the small one.
"""

from __future__ import annotations

import csv
import os
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import synth  # noqa: E402
from synth.atlas import run_grid  # noqa: E402
from synth.atlas.grid import load_grid  # noqa: E402

COLUMNS = ["case", "workers", "items", "unit", "seconds", "per_second", "speedup", "note"]


def _mechanisms(links: int) -> dict:
    start = time.perf_counter()
    chains = list(synth.type_synthesis(1, links, workers=1))
    middle = time.perf_counter()
    count = sum(len(synth.mechanisms_of(c)) for c in chains)
    end = time.perf_counter()
    return {"case": f"mechanisms W=1 n={links}", "workers": 1, "items": count, "unit": "mechanisms",
            "seconds": round(end - start, 3), "per_second": round(count / (end - start), 1), "speedup": None,
            "note": f"{len(chains)} chains; fixed-link orbits alone {count / max(end - middle, 1e-9):.0f}/s"}


def _grid(path: Path, repeat: int = 5) -> tuple[dict, dict]:
    """1 and 2 workers, interleaved, best of ``repeat`` fresh runs each (the machine is shared:
    the best run is the least disturbed, and interleaving exposes both to the same drift)."""
    grid = load_grid(path)
    results: dict[int, list] = {1: [], 2: []}
    for _ in range(repeat):
        for workers in (1, 2):
            with tempfile.TemporaryDirectory() as tmp:
                results[workers].append(run_grid(grid, Path(tmp) / "bench.sqlite", workers=workers))
    rows = []
    for workers in (1, 2):
        result = min(results[workers], key=lambda r: r.seconds)
        rows.append({"case": f"grid {grid.name}", "workers": workers, "items": result.chains_found, "unit": "chains",
                     "seconds": round(result.seconds, 3), "per_second": round(result.chains_per_second, 1),
                     "speedup": None, "note": f"{result.units_total} units, {result.mechanisms_found} mechanisms "
                                              f"stored; best of {repeat}"})
    return rows[0], rows[1]


def _compute_only(path: Path, repeat: int = 3) -> tuple[dict, dict]:
    """The same units without any database: how far the computation itself scales on this machine
    (the reference for the grid's speed-up; the pool and the atlas cannot do better than this)."""
    import multiprocessing

    from synth.atlas.runs import UnitTask, compute_unit

    grid = load_grid(path)
    tasks = [UnitTask(cell.key, u, grid.input_link) for cell in grid.cells for u in cell.plan()]
    best = {1: float("inf"), 2: float("inf")}
    for _ in range(repeat):
        start = time.perf_counter()
        for task in tasks:
            compute_unit(task)
        best[1] = min(best[1], time.perf_counter() - start)
        with multiprocessing.get_context("fork").Pool(2) as pool:
            start = time.perf_counter()
            list(pool.imap_unordered(compute_unit, tasks, chunksize=1))
            best[2] = min(best[2], time.perf_counter() - start)
    rows = [{"case": f"compute only {grid.name}", "workers": w, "items": len(tasks), "unit": "units",
             "seconds": round(best[w], 3), "per_second": round(len(tasks) / best[w], 1), "speedup": None,
             "note": f"no database; best of {repeat}"} for w in (1, 2)]
    rows[1]["speedup"] = round(best[1] / best[2], 2)
    return rows[0], rows[1]


def run(quick: bool = False) -> list[dict]:
    """Measure and write ``benchmarks/out/atlas.csv``; returns the rows."""
    rows = [_mechanisms(10)]
    if not quick:
        rows.append(_mechanisms(12))
    grids = [ROOT / "models" / "grid_small.toml"] + ([] if quick else [ROOT / "models" / "grid_12.toml"])
    for path in grids:
        one, two = _grid(path)
        two["speedup"] = round(one["seconds"] / two["seconds"], 2)
        rows += [one, two]
        if not quick and path.name == "grid_12.toml":
            rows += list(_compute_only(path))
    out = HERE / "out"
    out.mkdir(exist_ok=True)
    with open(out / "atlas.csv", "w", newline="") as fh:
        writer = csv.DictWriter(fh, COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    return rows


if __name__ == "__main__":
    os.environ.setdefault("MPLBACKEND", "Agg")
    for row in run(quick="--quick" in sys.argv):
        print(row)
