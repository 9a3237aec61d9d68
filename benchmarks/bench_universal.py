"""Type synthesis in every motion space h and for open chains: time, chains/s and candidates per chain.

1-DOF chains for h = 2 … 6 at growing link counts, each h up to the size that takes 10–30 s (the
next one takes many minutes), and open chains (W = 3, n1 = 0 … 3).  One process, after a warm-up
query; the best of up to 5 runs for small cases.  The time per chain of each h is compared with
h = 3 at the nearest number of chains (``per_chain_vs_h3``: the goal is at most 3), the smallest
planar queries included: below about ten chains a query is 1–4 ms of fixed costs (number
synthesis, one CP-SAT model per code and per unit), so a small query is compared with a small one.  Writes
``benchmarks/out/universal.csv``.  Run: ``python benchmarks/bench_universal.py [--quick]``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from benchmarks._out import OUT, print_rows, write_csv  # noqa: E402

#: (h, links) at 1 DOF, smallest first; --quick stops at the first two of each h
CASES_1DOF = {2: [5, 6, 7, 8, 9, 10], 3: [4, 6, 8, 10, 12, 14], 4: [5, 8, 11, 14, 17], 5: [6, 10, 14, 18],
              6: [7, 12, 17, 22]}
CASES_OPEN = [(3, 6, "0..3"), (3, 8, "0..3"), (3, 10, "0..3")]


def _timed(dof: int, links: int, stats: dict, **query) -> tuple[float, int, int]:
    """One run of the query: seconds, chains, units."""
    from synth.synthesis.stage_b import realise
    from synth.synthesis.type_synthesis import plan_units

    t0 = time.perf_counter()
    units = plan_units(dof, links, workers=1, **query)
    chains = 0
    for unit in units:
        if unit.contracted is None:
            chains += 1
        else:
            chains += len(realise(unit.code, unit.contracted, unit.conventions, stats))
    return time.perf_counter() - t0, chains, len(units)


def _one(dof: int, links: int, **query) -> dict:
    """Best of up to 5 runs (as timeit: the least disturbed), repeated while they take under 0.5 s in all."""
    stats: dict = {}
    seconds, chains, units = _timed(dof, links, stats, **query)
    spent, reps = seconds, 1
    while spent < 0.5 and reps < 5:
        again = _timed(dof, links, {}, **query)[0]
        seconds, spent, reps = min(seconds, again), spent + again, reps + 1
    return {"links": links, "chains": chains, "units": units, "seconds": round(seconds, 3), "reps": reps,
            "chains_per_s": round(chains / seconds, 1) if seconds else None,
            "candidates_per_chain": round(stats.get("candidates", chains) / chains, 2) if chains else None,
            "us_per_chain": round(1e6 * seconds / chains, 1) if chains else None}


def run(quick: bool = False, budget: float = 60.0) -> list[dict]:
    _timed(1, 6, {})  # warm-up: the first query loads the solver (about 0.2 s)
    rows = []
    for h, sizes in CASES_1DOF.items():
        for links in sizes[:2] if quick else sizes:
            row = {"series": f"1-DOF, h = {h}", "h": h, **_one(1, links, h=h)}
            rows.append(row)
            if row["seconds"] > budget / 4:
                break  # the next size would take well over the budget
    for h, links, n1 in CASES_OPEN[:2] if quick else CASES_OPEN:
        rows.append({"series": f"W = 3, n1 = {n1}", "h": h, **_one(3, links, h=h, n1=n1)})
    planar = [r for r in rows if r["series"] == "1-DOF, h = 3"]
    for row in rows:
        near = min(planar, key=lambda r: abs(r["chains"] - row["chains"]), default=None)
        if near and row["us_per_chain"]:
            row["per_chain_vs_h3"] = round(row["us_per_chain"] / near["us_per_chain"], 2)
    columns = ["series", "h", "links", "chains", "units", "seconds", "reps", "chains_per_s", "candidates_per_chain",
               "us_per_chain", "per_chain_vs_h3"]
    write_csv(OUT / "universal.csv", rows, columns)
    return rows


if __name__ == "__main__":
    print_rows(run, __doc__)
