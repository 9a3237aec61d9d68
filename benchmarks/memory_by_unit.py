"""What holds a count's memory: the rise of one process's peak resident memory at each stage-A code and
each stage-B unit of a 1-DOF count (issue 41, "memory ≤ 2 GiB whatever the size"; PROFILE.md section 36).

Every code of the query is expanded (stage A, its units held as a list) and every unit counted as a count's
worker counts it (``count_unit``), in this process, one after the other; the peak (``ru_maxrss``) is read
before and after each step, and the steps that raised it most are listed.  ``--every K`` counts every K-th
unit only (a sample); ``--code C`` the code C only, ``--unit I`` its unit I only (in stage A's order); ``--layer-bytes``
sets the budget of stage B's counting programme (``_stage_b_kernel.LAYER_BYTES``).

    MECHSYNTH_CACHE=off python benchmarks/memory_by_unit.py 23 --h 4
    MECHSYNTH_CACHE=off python benchmarks/memory_by_unit.py 20 --h 4 --layer-bytes 1000000
    MECHSYNTH_CACHE=off python benchmarks/memory_by_unit.py 32 --h 6 --code 22.10.0.0.0.0/0 --unit 82

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
    parser.add_argument("--code", metavar="C", help="this code only")
    parser.add_argument("--unit", type=int, metavar="I", help="unit I of the code only (with --code)")
    parser.add_argument("--layer-bytes", type=int, metavar="B")
    parser.add_argument("--top", type=int, default=10, metavar="N", help="the steps listed (default 10)")
    args = parser.parse_args(argv)
    if args.every < 1 or args.top < 0 or (args.layer_bytes is not None and args.layer_bytes < 1):
        print("memory_by_unit: --every and --layer-bytes must be at least 1, --top at least 0", file=sys.stderr)
        return 2
    if args.unit is not None and (args.code is None or args.unit < 0 or args.every != 1):
        print("memory_by_unit: --unit takes a --code, a unit from 0, and no --every", file=sys.stderr)
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
    if args.code is not None:
        jobs = [(code, conv) for code, conv in jobs if str(code) == args.code]
        if not jobs:
            print(f"memory_by_unit: no code {args.code} among the {args.links}-link chains of h = {args.h}", file=sys.stderr)
            return 2
    load_kernel()
    start, t0, counted, rises = _peak_mib(), time.process_time(), 0, []
    for code, conv in jobs:
        before = _peak_mib()
        units = [] if code.count(2) == code.links else list(_stage_a(code, conv))
        if _peak_mib() > before:
            rises.append((_peak_mib() - before, _peak_mib(), f"stage A of {code} ({len(units)} units)"))
        if args.unit is not None and args.unit >= len(units):
            print(f"memory_by_unit: {code} has {len(units)} units, no unit {args.unit}", file=sys.stderr)
            return 2
        for i in range(0, len(units), args.every) if args.unit is None else [args.unit]:
            before, t = _peak_mib(), time.process_time()
            chains = count_unit(units[i])
            counted += 1
            if args.unit is not None:
                print(f"unit {i} of {code}: {chains} chains, stage B {time.process_time() - t:.2f} CPU s, peak "
                      f"{_peak_mib()} MiB")
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
