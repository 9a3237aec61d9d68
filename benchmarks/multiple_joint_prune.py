"""The count of chains with multiple joints, with and without the kernel's check of the exact
test's sets (stage B, ``_kernel_placements(check_sets=...)``), unit by unit: placements the kernel
writes out, chains that pass the exact test, and CPU seconds of the kernel and of the exact test
(``time.process_time`` of this one process: other work on a shared machine hardly changes them).

Every unit of the codes with multiple joints of ``chains --dof W --links N --v A..B`` (or every
``--every``-th code from the ``--first``-th, a sample) is counted both ways in this process, on the
kernel whatever the size (a count loads it for large queries only); the chains must agree unit by
unit (exit 1 otherwise; 1 also where the query has no code with multiple joints, 2 for bad input).  Prints one row per code and the totals.

With ``--stages`` each unit is counted once, as ``--count`` counts it (``count_unit``, the kernel as the
query's size decides), and the CPU seconds go to stage A (the code's units), the kernel's search, the
programme that counts a unit without visiting it (``tight_count``), the sets the search checks
(``sets_to_check``), the exact test and the rest of stage B; ``--records FILE`` (a
by-code file of benchmarks/records/) compares each code's count with it (exit 1 where one differs).

Run from the project root::

    nice -n 19 python benchmarks/multiple_joint_prune.py 12 --v 0..10 > benchmarks/logs/multiple_joint_prune_12.txt
    nice -n 19 python benchmarks/multiple_joint_prune.py 14 --v 0..12 --every 60 --first 8
    python benchmarks/multiple_joint_prune.py 14 --v 0..12 --every 20 --first 3 --stages \
        --records benchmarks/records/dof_1_links_14_v_0-12.json
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path.cwd()
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks._out import refusals  # noqa: E402


def count_unit(unit, check_sets: bool) -> tuple[int, int, float, float]:
    """Placements, chains, kernel and exact-test CPU seconds of one unit counted by the search and the exact test
    (as ``--count`` did before it counted most such units without visiting them)."""
    from synth.synthesis.stage_b import _exact_test, _kernel_placements

    t0 = time.process_time()
    found, rows, whole = _kernel_placements(unit.code, unit.contracted, unit.conventions, None, listing=False,
                                            rows=True, check_sets=check_sets, programme=False)
    t1 = time.process_time()
    if not whole:
        raise SystemExit(f"a unit of {unit.code} lists part of its group: not what this comparison measures")
    chains = int(_exact_test(unit.contracted.vertices, unit.contracted.edges, rows, unit.conventions,
                             compiled=True).sum()) if found else 0
    return found, chains, t1 - t0, time.process_time() - t1


def stages(jobs, records: dict | None) -> int:
    """Count every unit of ``jobs`` once as ``--count`` does, timing stage A and stage B's parts (CPU
    seconds of this process); print a row per code and the totals; 1 where a code differs from ``records``."""
    from synth.structure import subchains
    from synth.synthesis import _stage_b_kernel, stage_b
    from synth.synthesis.type_synthesis import count_unit, job_units

    spent = {"kernel": 0.0, "programme": 0.0, "sets": 0.0, "test": 0.0}

    def timed(name, function):
        def wrapper(*args, **kwargs):
            t0 = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[name] += time.process_time() - t0
        return wrapper

    _stage_b_kernel.place = timed("kernel", _stage_b_kernel.place)  # (looked up at each call by stage B)
    _stage_b_kernel.tight_count = timed("programme", _stage_b_kernel.tight_count)
    subchains.sets_to_check = timed("sets", subchains.sets_to_check)
    stage_b._exact_test = timed("test", stage_b._exact_test)
    columns = ("units", "chains", "placed", "stage A", "stage B", "kernel", "programme", "sets", "test", "rest")
    print(f"{'code':>22} " + " ".join(f"{c:>9}" for c in columns))
    total = dict.fromkeys(columns, 0)
    bad = 0
    for job in jobs:
        before = dict(spent)
        t0 = time.process_time()
        units = job_units(job)
        t1 = time.process_time()
        stats: dict = {}
        chains = sum(n for unit in units for n in count_unit(unit, "listing", stats).values())
        row = {"units": len(units), "chains": chains, "placed": stats.get("candidates", 0), "stage A": t1 - t0,
               "stage B": time.process_time() - t1, **{k: spent[k] - before[k] for k in spent}}
        row["rest"] = row["stage B"] - row["kernel"] - row["programme"] - row["sets"] - row["test"]
        total = {k: total[k] + row[k] for k in columns}
        print(f"{str(job[0]):>22} " + " ".join(f"{row[c]:>9}" if isinstance(row[c], int) else f"{row[c]:>9.2f}"
                                               for c in columns), flush=True)
        if records is not None and records.get(str(job[0]), 0) != chains:
            bad += 1
            print(f"DIFFERENT: {job[0]}: {chains} chains, {records.get(str(job[0]), 0)} recorded", file=sys.stderr)
    print(f"{'total':>22} " + " ".join(f"{total[c]:>9}" if isinstance(total[c], int) else f"{total[c]:>9.2f}"
                                        for c in columns))
    print(f"placements per chain {total['placed'] / max(total['chains'], 1):.2f}; "
          f"{'codes compared with the records: ' + str(bad) + ' differ' if records is not None else 'no records given'}")
    return 1 if bad else 0


fail, _Parser = refusals("multiple_joint_prune")


def main(argv=None) -> int:
    parser = _Parser(description=__doc__.split("\n\n")[0])
    parser.add_argument("links", type=int, help="links of the chains")
    parser.add_argument("--dof", type=int, default=1, help="their degree of freedom W (default: %(default)s)")
    parser.add_argument("--v", default="0..10", help="range A..B of multiple joints (default: %(default)s)")
    parser.add_argument("--every", type=int, default=1, help="count every N-th code with multiple joints")
    parser.add_argument("--first", type=int, default=0, help="… starting from this one (0-based)")
    parser.add_argument("--stages", action="store_true", help="count each unit once and time the stages instead")
    parser.add_argument("--records", help="with --stages: a by-code JSON file to compare each code's count with")
    args = parser.parse_args(argv)
    if args.every < 1 or args.first < 0:
        fail(f"--every must be 1 or more and --first 0 or more, not {args.every} and {args.first}")
    if args.records and not args.stages:
        fail("--records compares the counts of --stages: give both or neither")
    records = None
    if args.records:
        try:
            records = json.loads(Path(args.records).read_text())["by_code"]
        except (OSError, ValueError, KeyError, TypeError) as error:
            fail(f"cannot read the counts by code of {args.records}: {error}")
    from synth import ChainQuery
    from synth.errors import SynthesisError
    from synth.synthesis.stage_b import _kernel_applies, load_kernel
    from synth.synthesis.type_synthesis import job_units, plan_jobs

    try:
        jobs = [(code, conv if args.stages else replace(conv, kernel_loops=1))  # (the kernel on every code, as a
                for code, conv in plan_jobs(ChainQuery(args.dof, args.links, v=args.v)) if code.v]  # large query)
    except SynthesisError as error:
        fail(str(error))
    if not jobs[args.first::args.every]:
        print("multiple_joint_prune: no code with multiple joints in this query (or this sample of it)", file=sys.stderr)
        return 1
    load_kernel()
    if args.stages:
        return stages(jobs[args.first::args.every], records)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    jobs = jobs[args.first::args.every]
    print(f"W = {args.dof}, {args.links} links, v = {args.v}: {len(jobs)} codes with multiple joints; engine {commit}; "
          "CPU seconds of one process; without / with the check of the sets")
    print(f"{'code':>22} {'units':>6} {'placed':>10} {'placed':>10} {'chains':>9} {'kernel s':>9} {'kernel s':>9} "
          f"{'test s':>7} {'test s':>7}")
    total = [0] * 4 + [0.0] * 4
    bad = 0
    for code, conv in jobs:
        units = [u for u in job_units((code, conv)) if u.contracted is not None
                 and _kernel_applies(u.code, u.contracted, u.conventions)]
        row = [len(units), 0, 0, 0] + [0.0] * 4
        for unit in units:
            found0, chains0, k0, t0 = count_unit(unit, False)
            found1, chains1, k1, t1 = count_unit(unit, True)
            if chains0 != chains1 or found1 > found0:
                bad += 1
                print(f"DIFFERENT: {code} unit {unit.contracted.edges}: {chains0} chains without, {chains1} with",
                      file=sys.stderr)
            for i, x in enumerate((found0, found1, chains1, k0, k1, t0, t1)):
                row[1 + i] += x
        total = [a + b for a, b in zip(total, row)]
        print(f"{str(code):>22} {row[0]:>6} {row[1]:>10} {row[2]:>10} {row[3]:>9} {row[4]:>9.2f} {row[5]:>9.2f} "
              f"{row[6]:>7.2f} {row[7]:>7.2f}", flush=True)
    print(f"{'total':>22} {total[0]:>6} {total[1]:>10} {total[2]:>10} {total[3]:>9} {total[4]:>9.2f} {total[5]:>9.2f} "
          f"{total[6]:>7.2f} {total[7]:>7.2f}")
    print(f"placements per chain {total[1] / max(total[3], 1):.2f} -> {total[2] / max(total[3], 1):.2f}; "
          f"kernel + test {total[4] + total[6]:.2f} -> {total[5] + total[7]:.2f} CPU s; {bad} units differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
