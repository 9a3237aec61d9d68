"""Time and memory of the gear-train atlas per size, by the engine and by the independent second method.

Run from the repository root (about 15 minutes on 2 cores for everything up to 10 links):

    nice -n 10 python benchmarks/bench_gears.py [--links 4..10] [--dof 1] [--workers 2] [--second]

Each size runs in a fresh process, so the peak memory (resident set, parent and workers) is that
size's own.  One JSON line per (method, F, n) goes to stdout and is appended to
``benchmarks/gears.jsonl``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _measure(method: str, dof: int, links: int, workers: int) -> dict:
    """Run one count in this process (called in a child) and return its record."""
    start = time.perf_counter()
    if method == "engine":
        from synth.gears.enumeration import census

        found = census(dof, links, workers=workers)
    else:
        from tests.oracles.gear_trains_fast import census

        found = census(dof, links, workers=workers)
    seconds = time.perf_counter() - start
    usage = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024
    return {"method": method, "dof": dof, "links": links, "workers": workers,
            "displacement": found["displacement"], "rotation": found["rotation"],
            "seconds": round(seconds, 1), "peak_mib_parent": usage, "peak_mib_worker": children}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", default="4..9")
    parser.add_argument("--dof", type=int, default=1)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--second", action="store_true", help="also run the independent second method")
    parser.add_argument("--one", nargs=3, metavar=("METHOD", "DOF", "LINKS"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        method, dof, links = args.one[0], int(args.one[1]), int(args.one[2])
        print(json.dumps(_measure(method, dof, links, args.workers)))
        return 0
    lo, _, hi = args.links.partition("..")
    methods = ["engine"] + (["second"] if args.second else [])
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    with open(ROOT / "benchmarks" / "gears.jsonl", "a") as log:
        for links in range(int(lo), int(hi or lo) + 1):
            for method in methods:
                run = subprocess.run([sys.executable, __file__, "--one", method, str(args.dof), str(links),
                                      "--workers", str(args.workers)], env=env, capture_output=True, text=True)
                if run.returncode != 0:
                    print(run.stderr, file=sys.stderr)
                    return run.returncode
                out = run.stdout.strip().splitlines()[-1]
                print(out, flush=True)
                log.write(out + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
