"""Synthesis time against link count, with counts checked against the published references.

For every case: per-stage time in one process (stage A = branch multigraphs, CP-SAT of
stage B, exact sub-chain test, nauty), candidates per unique chain, and the wall time of
the real command ``mechsynth chains --count`` on 2 workers (start-up included).
Writes ``benchmarks/out/synthesis.csv`` and ``benchmarks/out/synthesis.png``.

Run: ``python benchmarks/bench_synthesis.py [--quick | --full]`` (``--full`` adds 14 links).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
OUT = ROOT / "benchmarks" / "out"

# (series, W, links, v range, fractionated, reference count or None)
REFERENCE = {
    ("W=1", 1, 4): 1, ("W=1", 1, 6): 2, ("W=1", 1, 8): 16, ("W=1", 1, 10): 230, ("W=1", 1, 12): 6856,
    ("W=1", 1, 14): 318162,
    ("W=2", 2, 5): 1, ("W=2", 2, 7): 4, ("W=2", 2, 9): 40,
    ("W=3", 3, 6): 1, ("W=3", 3, 8): 7, ("W=3", 3, 10): 98,
    ("W=1 multiple joints", 1, 6): 4, ("W=1 multiple joints", 1, 8): 60,
}


def cases(quick: bool, full: bool):
    out = [("W=1", 1, n, "0") for n in (4, 6, 8, 10, 12)]
    if full:
        out.append(("W=1", 1, 14, "0"))
    out += [("W=2", 2, n, "0") for n in (5, 7, 9, 11)]
    out += [("W=3", 3, n, "0") for n in (6, 8, 10, 12)]
    out += [("W=1 multiple joints", 1, n, f"0..{2 * ((n - 2) // 2 - 1)}") for n in (6, 8, 10)]
    if quick:
        out = [c for c in out if c[2] <= 10]
    return out


def measure(series: str, dof: int, links: int, v: str, workers: int = 2) -> dict:
    import synth

    t0 = time.perf_counter()
    units = synth.plan_units(dof, links, v=v)
    stage_a = time.perf_counter() - t0
    stats: dict = {}
    count = sum(len(synth.run_unit(u, stats)) for u in units)
    inline = time.perf_counter() - t0
    cmd = [sys.executable, "-m", "mechsynth", "chains", "--dof", str(dof), "--links", str(links), "--v", v,
           "--count", "--workers", str(workers)]
    t1 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, check=True)
    wall = time.perf_counter() - t1
    cli_count = json.loads(proc.stdout)["count"]
    reference = REFERENCE.get((series, dof, links))
    return {
        "series": series, "dof": dof, "links": links, "v": v, "chains": count, "reference": reference,
        "error": None if reference is None else count - reference, "cli_agrees": cli_count == count,
        "units": len(units), "stage_a_s": round(stage_a, 4), "cpsat_s": round(stats.get("cpsat_s", 0), 4),
        "subchain_s": round(stats.get("subchain_s", 0), 4), "nauty_s": round(stats.get("nauty_s", 0), 4),
        "one_core_s": round(inline, 4), "wall_2_workers_s": round(wall, 3),
        "candidates_per_chain": round(stats.get("candidates", 0) / count, 3) if count else None,
        "chains_per_s": round(count / wall, 1),
    }


def run(quick: bool = False, full: bool = False) -> list[dict]:
    """Measure every case; return the rows (also written to CSV and plotted)."""
    rows = []
    for series, dof, links, v in cases(quick, full):
        row = measure(series, dof, links, v)
        rows.append(row)
        print(json.dumps(row), file=sys.stderr)
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "synthesis.csv", "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, OUT / "synthesis.png")
    return rows


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for series in dict.fromkeys(r["series"] for r in rows):
        pts = [(r["links"], r["wall_2_workers_s"], r["chains"]) for r in rows if r["series"] == series]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=series)
        for x, y, n in pts:
            ax.annotate(str(n), (x, y), textcoords="offset points", xytext=(3, 4), fontsize=7)
    ax.set_yscale("log")
    ax.set_xlabel("links n")
    ax.set_ylabel("wall time, 2 workers, start-up included [s]")
    ax.set_title("Type synthesis: time against link count (labels: chains found)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="only up to 10 links")
    parser.add_argument("--full", action="store_true", help="add 1-DOF 14 links (about 2 minutes)")
    args = parser.parse_args()
    os.environ.setdefault("MPLBACKEND", "Agg")
    for row in run(args.quick, args.full):
        print(row)
