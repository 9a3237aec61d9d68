"""Stage B of a count with multiple joints in the programme's two orders of the strings, unit by unit: maximum
adjacency with the multiple joints first (before, ``_NARROW_MOST`` = −1) and the order that keeps the fewest
vertices open (``stage_b._narrow_rank``); the chains must agree unit by unit (exit 1 otherwise, 2 for bad input).

Every ``--every``-th unit of each code given, in the order a count's stage A hands them on
(``contracted_stream``), is counted both ways in this one process (``count_unit``, the first count or
``--method tight-reverse``), each timed in CPU seconds (``time.process_time``).  Prints one row per code and
the totals.  Run from the project root::

    MECHSYNTH_CACHE=off nice -n 5 python benchmarks/programme_order.py 16 --v 0..14 --every 100 \\
        --codes 11.3.2.0.0.0.0/5 12.3.0.1.0.0.0/4-1
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path.cwd()))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks._out import refusals  # noqa: E402

fail, _Parser = refusals("programme_order")


def compare(job, every: int, method: str) -> dict:
    """The sampled units of one (code, conventions) job counted in both orders: units, chains, CPU s of stage A
    (the whole stream), of the old order and of the new, and the units whose counts differ."""
    from synth.synthesis import stage_b
    from synth.synthesis.stage_a import contracted_stream
    from synth.synthesis.type_synthesis import Unit, count_unit

    row = {"units": 0, "chains": 0, "stage A": 0.0, "before": 0.0, "after": 0.0, "differ": 0}
    narrow_most = stage_b._NARROW_MOST
    stream = contracted_stream(*job)
    seen = 0
    while True:
        t0 = time.process_time()
        graph = next(stream, None)
        row["stage A"] += time.process_time() - t0
        if graph is None:
            return row
        seen += 1
        if (seen - 1) % every:
            continue
        unit = Unit(job[0], graph, job[1])
        counts = []
        for key, most in (("before", -1), ("after", narrow_most)):
            stage_b._NARROW_MOST = most
            t0 = time.process_time()
            try:
                counts.append(count_unit(unit, method, {}))
            finally:
                stage_b._NARROW_MOST = narrow_most
            row[key] += time.process_time() - t0
        row["units"] += 1
        row["chains"] += sum(counts[1].values())
        row["differ"] += counts[0] != counts[1]


def main(argv=None) -> int:
    parser = _Parser(description=__doc__.split("\n\n")[0])
    parser.add_argument("links", type=int, help="links of the chains")
    parser.add_argument("--dof", type=int, default=1, help="their degree of freedom W (default: %(default)s)")
    parser.add_argument("--v", default="0..14", help="range A..B of multiple joints (default: %(default)s)")
    parser.add_argument("--codes", nargs="+", required=True, help="codes of the query to sample")
    parser.add_argument("--every", type=int, default=1, help="count every N-th unit of each code (default: 1)")
    parser.add_argument("--method", choices=("count", "tight-reverse"), default="count",
                        help="the first count or the second (default: %(default)s)")
    args = parser.parse_args(argv)
    if args.every < 1:
        fail(f"--every must be 1 or more, not {args.every}")
    from synth.errors import InvalidOption
    from synth.synthesis import stage_b
    from synth.synthesis.type_synthesis import ChainQuery, plan_jobs

    try:
        query = ChainQuery(args.dof, args.links, v=args.v)
    except (InvalidOption, ValueError) as exc:
        fail(f"no such query: {exc}")
    jobs = {str(job[0]): job for job in plan_jobs(query)}
    missing = [code for code in args.codes if code not in jobs]
    if missing:
        fail(f"{', '.join(missing)} {'is' if len(missing) == 1 else 'are'} not a code of that query")
    stage_b.load_kernel()
    method = "listing" if args.method == "count" else args.method
    columns = ("units", "chains", "stage A", "before", "after", "differ")
    print(f"{'code':>24} " + " ".join(f"{c:>9}" for c in columns))
    total = dict.fromkeys(columns, 0)
    for code in args.codes:
        row = compare(jobs[code], args.every, method)
        total = {c: total[c] + row[c] for c in columns}
        for name, values in ((code, row), *((("total", total),) if code == args.codes[-1] else ())):
            print(f"{name:>24} " + " ".join(f"{values[c]:>9}" if isinstance(values[c], int) else f"{values[c]:>9.2f}"
                                            for c in columns), flush=True)
    ratio = total["before"] / max(total["after"], 1e-9)
    print(f"stage B {total['before']:.2f} → {total['after']:.2f} CPU s ({ratio:.2f}×); {total['differ']} units differ")
    return 1 if total["differ"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
