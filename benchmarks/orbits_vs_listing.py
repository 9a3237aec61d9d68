"""The two counting methods of ``chains --count`` side by side, code by code: the listing
(``count_realised``: one lex-least placement per chain) and the orbits (``count_orbits``:
Burnside's lemma over the bundle permutations of each branch multigraph).

Stage A runs once per code; each unit is then counted by both methods in this process, with the
CPU seconds of each (``time.process_time``: other work on a shared machine hardly changes them).
Prints one row per code (units, chains by each method, CPU seconds of stage A and of each
method, µs per chain) and the totals; exit 1 if any code's counts differ.

Run from the project root::

    nice -n 19 python benchmarks/orbits_vs_listing.py 16 [--dof 1] [--h 3] > benchmarks/logs/orbits_vs_listing_16.txt
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path.cwd()
sys.path.insert(0, str(ROOT))


def compare(dof: int, links: int, h: int) -> int:
    from synth import ChainQuery
    from synth.synthesis.stage_b import count_orbits, count_realised, load_kernel
    from synth.synthesis.type_synthesis import job_units, plan_jobs

    load_kernel()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    print(f"W = {dof}, {links} links, h = {h}; engine {commit}; CPU seconds of one process")
    print(f"{'code':>20} {'units':>6} {'listing':>11} {'orbits':>11} {'stage A':>8} {'listing s':>9} "
          f"{'orbits s':>9} {'µs/chain L':>10} {'µs/chain O':>10}")
    totals = [0, 0, 0, 0.0, 0.0, 0.0]
    bad = 0
    for code, conv in plan_jobs(ChainQuery(dof, links, h=h)):
        t0 = time.process_time()
        units = [u for u in job_units((code, conv)) if u.contracted is not None]
        stage_a = time.process_time() - t0
        found = [0, 0]
        seconds = [0.0, 0.0]
        for unit in units:
            for i, count in enumerate((count_realised, count_orbits)):
                t0 = time.process_time()
                found[i] += count(unit.code, unit.contracted, unit.conventions)
                seconds[i] += time.process_time() - t0
        bad += found[0] != found[1]
        rate = [f"{1e6 * s / found[0]:.2f}" if found[0] else "-" for s in seconds]
        print(f"{str(code):>20} {len(units):>6} {found[0]:>11} {found[1]:>11} {stage_a:>8.2f} {seconds[0]:>9.2f} "
              f"{seconds[1]:>9.2f} {rate[0]:>10} {rate[1]:>10}" + ("" if found[0] == found[1] else "  DIFFERENT"),
              flush=True)
        for i, x in enumerate((len(units), *found, stage_a, *seconds)):
            totals[i] += x
    print(f"{'total':>20} {totals[0]:>6} {totals[1]:>11} {totals[2]:>11} {totals[3]:>8.2f} {totals[4]:>9.2f} "
          f"{totals[5]:>9.2f} {1e6 * totals[4] / max(1, totals[1]):>10.2f} {1e6 * totals[5] / max(1, totals[1]):>10.2f}")
    print("codes whose counts differ:", bad)
    return 1 if bad else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("links", type=int)
    parser.add_argument("--dof", type=int, default=1)
    parser.add_argument("--h", type=int, default=3)
    args = parser.parse_args()
    return compare(args.dof, args.links, args.h)


if __name__ == "__main__":
    raise SystemExit(main())
