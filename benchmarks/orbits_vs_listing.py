"""Ways of counting the chains of ``chains --count`` side by side, code by code:

* ``count``: ``count_realised``, what ``--count`` runs (the compiled kernel's count search where
  it applies: one lex-least placement per chain in the search order, nothing written out);
* ``listing``: what the listing finds for each unit, the placements stage B writes out in the
  strings' own order (one per chain where the whole group of H is listed and the joints are
  simple; elsewhere the chains ``realise`` builds, told apart by certificate);
* ``orbits``: ``count_orbits``, Burnside's lemma over the bundle permutations of each branch
  multigraph (``--method orbits``);
* ``search``: ``count_realised`` with its programme off, the kernel's search and the exact test on every unit
  with a multiple joint (what ``--count`` ran before it counted most of them without visiting);
* ``reverse``: ``count_reversed``, the second count (``--method tight-reverse``).

Stage A runs once per code; each unit is then counted by each method asked (``--methods``, two or
more; ``count,orbits`` by default) in this process, with the CPU seconds of each
(``time.process_time``: other work on a shared machine hardly changes them). Prints one row per
code (units, chains by each method, CPU seconds of stage A and of each method, µs per chain) and
the totals; exit 1 if any unit's counts differ (a code whose units differ is marked).  ``--v A..B`` takes multiple
joints (the query's ``--v``), ``--every N`` every N-th code of the plan only, the first included (a sample of a
large query), ``--codes A,B,…`` those codes of the plan only; ``--kernel`` runs the compiled kernels on every code, as a large query does (a small query's
count otherwise takes CP-SAT and the plain searches).

Run from the project root::

    nice -n 19 python benchmarks/orbits_vs_listing.py 16 [--dof 1] [--h 3] [--methods count,listing,orbits] \
        [--v 0..14] [--every 10] > benchmarks/logs/orbits_vs_listing_16.txt
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path.cwd()
sys.path.insert(0, str(ROOT))


def compare(query, methods: list[str], every: int = 1, kernel: bool = False, codes: set | None = None) -> int:
    """Count the codes of the :class:`~synth.ChainQuery` ``query`` (every ``every``-th, or those named in ``codes``)
    by each of ``methods``, on the compiled kernels everywhere with ``kernel``."""
    from dataclasses import replace

    from synth.synthesis import stage_b
    from synth.synthesis.stage_b import count_listed, count_orbits, count_realised, count_reversed, load_kernel
    from synth.synthesis.type_synthesis import job_units, plan_jobs

    ways = {"count": count_realised, "listing": count_listed, "orbits": count_orbits, "reverse": count_reversed,
            "search": lambda code, graph, conv: stage_b.count_realised(code, graph, conv, programme=False)}
    count = [ways[m] for m in methods]
    load_kernel()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    sample = f", every {every}th code" if every > 1 else ""
    v = "0" if query.v is None else f"{query.v[0]}..{'' if query.v[1] is None else query.v[1]}"
    print(f"W = {query.dof}, {query.links} links, h = {query.h}, v {v}{sample}; engine {commit}; CPU seconds of one "
          f"process")
    print(f"{'code':>20} {'units':>6} " + " ".join(f"{m:>11}" for m in methods) + f" {'stage A':>8} "
          + " ".join(f"{m + ' s':>9}" for m in methods) + " " + " ".join(f"{'µs/ch ' + m[0].upper():>10}" for m in methods))
    n = len(methods)
    totals = [0] * (1 + n) + [0.0] * (1 + n)
    bad = units_bad = 0
    for code, conv in [job for job in plan_jobs(query) if codes is None or str(job[0]) in codes][::every]:
        conv = replace(conv, kernel_loops=1) if kernel else conv
        t0 = time.process_time()
        units = [u for u in job_units((code, conv)) if u.contracted is not None]
        stage_a = time.process_time() - t0
        found = [0] * n
        seconds = [0.0] * n
        differ = False
        for unit in units:
            each = []
            for i, way in enumerate(count):
                t0 = time.process_time()
                each.append(way(unit.code, unit.contracted, unit.conventions))
                seconds[i] += time.process_time() - t0
                found[i] += each[-1]
            units_bad += len(set(each)) > 1
            differ |= len(set(each)) > 1
        bad += differ
        rate = [f"{1e6 * s / found[0]:.2f}" if found[0] else "-" for s in seconds]
        print(f"{str(code):>20} {len(units):>6} " + " ".join(f"{x:>11}" for x in found) + f" {stage_a:>8.2f} "
              + " ".join(f"{x:>9.2f}" for x in seconds) + " " + " ".join(f"{x:>10}" for x in rate)
              + ("  DIFFERENT" if differ else ""), flush=True)
        for i, x in enumerate((len(units), *found, stage_a, *seconds)):
            totals[i] += x
    chains = max(1, totals[1])
    print(f"{'total':>20} {totals[0]:>6} " + " ".join(f"{x:>11}" for x in totals[1:1 + n]) + f" {totals[1 + n]:>8.2f} "
          + " ".join(f"{x:>9.2f}" for x in totals[2 + n:]) + " "
          + " ".join(f"{1e6 * x / chains:>10.2f}" for x in totals[2 + n:]))
    print("codes whose counts differ:", bad, "units:", units_bad)
    return 1 if bad else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("links", type=int)
    parser.add_argument("--dof", type=int, default=1)
    parser.add_argument("--h", type=int, default=3)
    parser.add_argument("--v", help="multiple joints, as the query's --v (A..B)")
    parser.add_argument("--every", type=int, default=1, help="every N-th code of the plan only (a sample)")
    parser.add_argument("--methods", default="count,orbits",
                        help="two or more of count, listing, orbits, search, reverse, comma-separated (default "
                             "count,orbits)")
    parser.add_argument("--kernel", action="store_true", help="the compiled kernels on every code")
    parser.add_argument("--codes", help="only these codes of the plan (comma-separated)")
    args = parser.parse_args()
    methods = args.methods.split(",")
    if len(methods) < 2 or len(set(methods)) < len(methods) or not set(methods) <= {"count", "listing", "orbits",
                                                                                    "search", "reverse"}:
        parser.error("--methods takes two or more different ones of count, listing, orbits, search, reverse")
    if args.every < 1:
        parser.error(f"--every takes a whole number of at least 1, not {args.every}")
    from synth import ChainQuery, SynthesisError

    try:
        query = ChainQuery.of(dof=args.dof, links=args.links, h=args.h, v=args.v)
        codes = None if args.codes is None else set(args.codes.split(","))
        status = compare(query, methods, args.every, args.kernel, codes)
    except SynthesisError as exc:  # a query the engine refuses (a --v that is no range, impossible sizes)
        parser.error(str(exc))
    return status


if __name__ == "__main__":
    raise SystemExit(main())
