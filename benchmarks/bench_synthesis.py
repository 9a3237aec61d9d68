"""Synthesis time against link count, with counts checked against the published references.

For every case: per-stage time in one process (stage A = branch multigraphs, CP-SAT of
stage B, exact sub-chain test, nauty), the same units counted as ``--count`` counts them
(chains built only where stage B's vectors are not already one per chain: ``count_one_core_s``),
candidates per unique chain (and by v for multiple joints), and the wall time of the real command ``mechsynth chains --count`` on 2 workers
(start-up included; the minimum of ``reps`` runs, with the CPU time of the fastest).

With the environment variable ``GENSPARSEG`` pointing at a gensparseg binary (built by
nauty's ``geng`` with M. Larsson's nauty-laman-plugin; never a dependency), every 1-DOF simple-joint
case also times ``gensparseg N -K3/2L2 -u`` on 2 processes (geng's res/mod split 0/2 and
1/2 at once) *alternately* with mechsynth in the same loop, checks its count, and gives the
ratio mechsynth / gensparseg of the two minima.

Writes ``benchmarks/out/synthesis.csv`` and ``benchmarks/out/synthesis.png``.
Run: ``python benchmarks/bench_synthesis.py [--quick | --full] [--reps N]`` (``--full`` adds
14 links and multiple joints at 12 links, v = 0…10).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from benchmarks._out import OUT, write_csv  # noqa: E402
from mechbase import save_figure  # noqa: E402

# (series, W, links) -> published count (OEIS A233288 for W = 1; docs/theory.md's reference counts otherwise)
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
    out += [("W=1 multiple joints", 1, n, f"0..{2 * ((n - 2) // 2 - 1)}") for n in (6, 8, 10) + ((12,) if full else ())]
    if quick:
        out = [c for c in out if c[2] <= 10]
    return out


def _timed(cmd: list[str]) -> tuple[float, float, subprocess.CompletedProcess]:
    """Wall and CPU (this child and its own children) seconds of one command."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, check=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime, proc


def _gensparseg(binary: str, links: int) -> tuple[float, int]:
    """Wall seconds of gensparseg on 2 processes (res/mod 0/2 and 1/2 at once) and the chains it counts."""
    t0 = time.perf_counter()
    procs = [subprocess.Popen([binary, str(links), "-K3/2L2", "-u", f"{r}/2"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True) for r in (0, 1)]
    errs = [p.communicate()[1] for p in procs]
    wall = time.perf_counter() - t0
    count = sum(int(m.group(1)) for e in errs for m in [re.search(r">Z (\d+) graphs", e)] if m)
    return wall, count


def measure(series: str, dof: int, links: int, v: str, workers: int = 2, reps: int = 3) -> dict:
    import synth

    synth.count_chains(1, 8, workers=1)  # solver, nauty and both stages loaded before the clock: start-up is the CLI column's
    t0 = time.perf_counter()
    units = synth.plan_units(dof, links, v=v, workers=1)
    stage_a = time.perf_counter() - t0
    stats: dict = {}
    by_v: dict[int, list[int]] = {}
    count = 0
    for u in units:
        unit_stats: dict = {}
        found = len(synth.run_unit(u, unit_stats))
        count += found
        for key, value in unit_stats.items():
            stats[key] = stats.get(key, 0) + value
        row = by_v.setdefault(u.code.v, [0, 0, 0])
        row[0] += 1
        row[1] += found
        row[2] += unit_stats.get("candidates", 0)
    inline = time.perf_counter() - t0
    from synth.synthesis.type_synthesis import count_unit  # what `chains --count` runs on each unit

    t1 = time.perf_counter()
    counted = sum(count_unit(u)[1] for u in units)
    count_inline = stage_a + time.perf_counter() - t1
    cmd = [sys.executable, "-m", "mechsynth", "chains", "--dof", str(dof), "--links", str(links), "--v", v,
           "--count", "--workers", str(workers)]
    binary = os.environ.get("GENSPARSEG") if series == "W=1" else None
    walls, g_walls, g_count = [], [], None
    for _ in range(reps):  # alternately, so both see the same load drift
        walls.append(_timed(cmd))
        if binary:
            g_wall, g_count = _gensparseg(binary, links)
            g_walls.append(g_wall)
    wall, cpu, proc = min(walls, key=lambda w: w[0])
    cli_count = json.loads(proc.stdout)["count"]
    reference = REFERENCE.get((series, dof, links))
    row = {
        "series": series, "dof": dof, "links": links, "v": v, "chains": count, "reference": reference,
        "error": None if reference is None else count - reference, "cli_agrees": cli_count == count == counted,
        "units": len(units), "stage_a_s": round(stage_a, 4), "cpsat_s": round(stats.get("cpsat_s", 0), 4),
        "subchain_s": round(stats.get("subchain_s", 0), 4), "nauty_s": round(stats.get("nauty_s", 0), 4),
        "one_core_s": round(inline, 4), "count_one_core_s": round(count_inline, 4), "wall_2_workers_s": round(wall, 3), "cpu_2_workers_s": round(cpu, 3),
        "reps": reps, "candidates_per_chain": round(stats.get("candidates", 0) / count, 3) if count else None,
        "chains_per_s": round(count / wall, 1),
        "by_v": {k: {"units": a, "chains": b, "candidates": c} for k, (a, b, c) in sorted(by_v.items())},
    }
    if binary:
        row.update(gensparseg_s=round(min(g_walls), 3), gensparseg_chains=g_count,
                   gensparseg_agrees=g_count == count, ratio=round(wall / min(g_walls), 2))
    return row


def large(links: int = 16, workers: int = 2) -> dict:
    """One run of ``mechsynth chains --dof 1 --links N --count --workers 2`` (start-up included): wall,
    CPU of all processes, and the peak resident memory of the largest process (parent or a worker)."""
    cmd = [sys.executable, "-m", "mechsynth", "chains", "--dof", "1", "--links", str(links), "--count", "--force",
           "--workers", str(workers)]
    wall, cpu, proc = _timed(cmd)
    count = json.loads(proc.stdout)["count"]
    reference = {16: 19819281, 18: 1535380884}.get(links)
    return {"links": links, "workers": workers, "chains": count, "reference": reference,
            "error": None if reference is None else count - reference, "wall_s": round(wall, 1),
            "cpu_s": round(cpu, 1), "peak_rss_mib": round(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024)}


def by_v_rows(rows: list[dict]) -> list[dict]:
    """Candidates (CP-SAT solutions) per chain by multiple-joint count v, for the multiple-joint cases."""
    out = []
    for r in rows:
        if r["v"] == "0":
            continue
        for v, d in r["by_v"].items():
            out.append({"links": r["links"], "v": v, "units": d["units"], "chains": d["chains"],
                        "candidates": d["candidates"],
                        "candidates_per_chain": round(d["candidates"] / d["chains"], 3) if d["chains"] else None})
    return out


def run(quick: bool = False, full: bool = False, reps: int = 3) -> list[dict]:
    """Measure every case; return the rows (also written to CSV and plotted).

    Cases over a minute on one core run once (``reps`` = 1): 14 links and multiple joints at 12.
    """
    rows = []
    for series, dof, links, v in cases(quick, full):
        heavy = links >= 14 or (links >= 12 and v != "0")
        row = measure(series, dof, links, v, reps=1 if heavy else reps)
        rows.append(row)
        print(json.dumps(row), file=sys.stderr)
    columns = list(dict.fromkeys(k for r in rows for k in r if k != "by_v"))  # every row's keys, in order
    write_csv(OUT / "synthesis.csv", rows, columns)
    plot(rows, OUT / "synthesis.png")
    return rows


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from benchmarks._labels import place_labels

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    # each series labels its points on its own side first (upper left for the first: it rises most
    # steeply, its lines come from the lower left); a label that would cover another moves (_labels)
    labels = []
    for k, series in enumerate(dict.fromkeys(r["series"] for r in rows)):
        pts = [(r["links"], r["wall_2_workers_s"], r["chains"]) for r in rows if r["series"] == series]
        line, = ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=series)
        for x, y, n in pts:
            text = f"{int(n):,}".replace(",", " ")
            labels.append((k, ax.annotate(text, (x, y), xytext=(0, 0), textcoords="offset points", fontsize=7,
                                          color=line.get_color())))
    ax.set_yscale("log")
    ax.margins(y=0.12)  # room for the labels of the highest points
    ax.set_xlabel("links n")
    ax.set_ylabel("wall time, 2 workers, start-up included [s]")
    ax.set_title("Type synthesis: time against link count (labels: chains found)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    place_labels(fig, labels)
    save_figure(fig, path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="only up to 10 links")
    parser.add_argument("--full", action="store_true",
                        help="add 1-DOF 14 links and multiple joints at 12 links (about 10 minutes)")
    parser.add_argument("--reps", type=int, default=3, help="timed runs of each small case (the minimum is kept)")
    args = parser.parse_args()
    os.environ.setdefault("MPLBACKEND", "Agg")
    for row in run(args.quick, args.full, args.reps):
        print(row)
