"""The speed goals of issue 31, measured as a user runs them: the CLI, start-up included, this tree
against another (``--base DIR``: an extracted older commit), alternately in one run.

Each case is a ``mechsynth`` command; the script reports the minimum wall time of ``--reps`` runs
and the CPU time of that run (all its processes: the parent and its workers), with the load
average before and after each case, so a reading taken on a shared machine says how shared it was.
Wall times are only comparable within one run (same load); CPU times hardly depend on the load.

Run from the project root::

    python benchmarks/bench_speed.py [--base /tmp/ms_base] [--reps 3] [--only 14]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CASES = {
    "12 links count": ["chains", "--dof", "1", "--links", "12", "--count", "--workers", "2"],
    "14 links count": ["chains", "--dof", "1", "--links", "14", "--count", "--workers", "2"],
    "16 links count": ["chains", "--dof", "1", "--links", "16", "--count", "--workers", "2", "--force"],
    "12 links v = 0..10 count": ["chains", "--dof", "1", "--links", "12", "--v", "0..10", "--count", "--workers", "2"],
    "h = 2, 10 links count": ["chains", "--dof", "1", "--links", "10", "--h", "2", "--count", "--workers", "2"],
    "12 links listing (jsonl)": ["chains", "--dof", "1", "--links", "12", "--format", "jsonl", "--workers", "2"],
    "14 links listing (jsonl)": ["chains", "--dof", "1", "--links", "14", "--format", "jsonl", "--workers", "2"],
    "10 links v = 0..6 listing (jsonl)": ["chains", "--dof", "1", "--links", "10", "--v", "0..6", "--format", "jsonl",
                                           "--workers", "2"],
}


def run(tree: Path, args: list[str]) -> tuple[float, float, int]:
    """Wall seconds, CPU seconds (all processes) and output lines of one command in ``tree``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "mechsynth", *args], cwd=tree, capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(tree)})
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        raise SystemExit(f"{tree}: mechsynth {' '.join(args)} failed: {out.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, out.stdout.count("\n")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", help="another tree to time alternately (an extracted older commit)")
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--only", help="cases whose name contains this")
    args = parser.parse_args()
    trees = [("this tree", ROOT)] + ([("base", Path(args.base))] if args.base else [])
    print("| case | tree | wall s (min) | CPU s of that run | output lines | load before → after |")
    print("|---|---|---|---|---|---|")
    for name, command in CASES.items():
        if args.only and args.only not in name:
            continue
        best = {label: (float("inf"), 0.0, 0) for label, _ in trees}
        load0 = os.getloadavg()[0]
        for _ in range(args.reps):
            for label, tree in trees:
                wall, cpu, lines = run(tree, command)
                if wall < best[label][0]:
                    best[label] = (wall, cpu, lines)
        load1 = os.getloadavg()[0]
        for label, _ in trees:
            wall, cpu, lines = best[label]
            print(f"| {name} | {label} | {wall:.2f} | {cpu:.2f} | {lines} | {load0:.1f} → {load1:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
