"""What holds a count's memory: the rise of one process's peak resident memory at each stage-A code and
each stage-B unit of a 1-DOF count (issue 41, "memory ≤ 2 GiB whatever the size"; PROFILE.md section 36).

Every code of the query is expanded (stage A, its units held as a list) and every unit counted as a count's
worker counts it (``count_unit``), in this process, one after the other; the peak (``ru_maxrss``) is read
before and after each step, and the steps that raised it most are listed.  ``--every K`` counts every K-th
unit only (a sample); ``--layer-bytes`` sets the budget of stage B's counting programme
(``_stage_b_kernel.LAYER_BYTES``).

    MECHSYNTH_CACHE=off python benchmarks/memory_by_unit.py 23 --h 4
    MECHSYNTH_CACHE=off python benchmarks/memory_by_unit.py 20 --h 4 --layer-bytes 1000000

Exit status 2 with one sentence for bad options.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time


def _peak_mib() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss >> 10


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("links", type=int)
    parser.add_argument("--h", type=int, default=3)
    parser.add_argument("--every", type=int, default=1, metavar="K")
    parser.add_argument("--layer-bytes", type=int, metavar="B")
    parser.add_argument("--top", type=int, default=10, metavar="N", help="the steps listed (default 10)")
    args = parser.parse_args(argv)
    if args.every < 1 or args.top < 0 or (args.layer_bytes is not None and args.layer_bytes < 1):
        print("memory_by_unit: --every and --layer-bytes must be at least 1, --top at least 0", file=sys.stderr)
        return 2

    from synth import ChainQuery
    from synth.errors import SynthesisError
    from synth.synthesis import _stage_b_kernel
    from synth.synthesis.type_synthesis import _stage_a, count_unit, load_kernel, plan_jobs

    if args.layer_bytes is not None:
        _stage_b_kernel.LAYER_BYTES = args.layer_bytes
    try:
        jobs = plan_jobs(ChainQuery(dof=1, links=args.links, h=args.h))
    except SynthesisError as exc:
        print(f"memory_by_unit: {exc}", file=sys.stderr)
        return 2
    load_kernel()
    start, t0, counted, rises = _peak_mib(), time.process_time(), 0, []
    for code, conv in jobs:
        before = _peak_mib()
        units = [] if code.count(2) == code.links else list(_stage_a(code, conv))
        if _peak_mib() > before:
            rises.append((_peak_mib() - before, _peak_mib(), f"stage A of {code} ({len(units)} units)"))
        for i in range(0, len(units), args.every):
            before, t = _peak_mib(), time.process_time()
            count_unit(units[i])
            counted += 1
            if _peak_mib() > before:
                rises.append((_peak_mib() - before, _peak_mib(),
                              f"stage B of unit {i} of {code} ({len(units[i].contracted.edges)} strings, "
                              f"{time.process_time() - t:.2f} CPU s)"))
    print(f"{len(jobs)} codes, {counted} units counted, {time.process_time() - t0:.1f} CPU s; peak {start} MiB "
          f"before the codes, {_peak_mib()} MiB at the end")
    for rise, peak, what in sorted(rises, reverse=True)[:args.top]:
        print(f"+{rise} MiB (to {peak}): {what}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
