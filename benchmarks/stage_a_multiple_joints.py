"""Stage A of the codes with multiple joints, the compiled kernel against the path it replaced (the plain
search of a code of few branch vertices, else the CP-SAT model): the set of branch multigraphs (nauty's
certificates) of each code must be the same from the kernel's listing (sorted), from a count's stream (both
the least labellings, since PROFILE.md section 46) and from the old path, and each once; CPU seconds of each (``time.process_time`` of this one
process).  Exit 1 where a code differs, 2 for bad input.

Run from the project root::

    python benchmarks/stage_a_multiple_joints.py 10 --v 0..8
    python benchmarks/stage_a_multiple_joints.py 8 --dof 0 --v 0..6 --h 4
    python benchmarks/stage_a_multiple_joints.py 16 --v 0..14 --code 8800000/2-1 --kernel-only
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path.cwd()))


def _timed(function, *args):
    t0 = time.process_time()
    out = function(*args)
    return out, time.process_time() - t0


def _seconds(value: float, args) -> str:
    return f"{'-':>9}" if args.kernel_only else f"{value:>9.2f}"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("links", type=int, help="links of the chains")
    parser.add_argument("--dof", type=int, default=1, help="their degree of freedom W (default: %(default)s)")
    parser.add_argument("--v", required=True, help="range A..B of multiple joints")
    parser.add_argument("--h", type=int, default=3, help="motion space h (default: %(default)s)")
    parser.add_argument("--code", help="this code of the query only")
    parser.add_argument("--kernel-only", action="store_true", help="time the kernel's stream only (no old path)")
    args = parser.parse_args(argv)
    from synth import ChainQuery
    from synth.errors import SynthesisError
    from synth.synthesis import stage_a
    from synth.synthesis.type_synthesis import plan_jobs

    try:
        jobs = [(c, conv) for c, conv in plan_jobs(ChainQuery(args.dof, args.links, v=args.v, h=args.h))
                if c.v and stage_a._branch_vertices(c) and (args.code is None or str(c) == args.code)]
    except SynthesisError as error:
        print(f"stage_a_multiple_joints: {error}", file=sys.stderr)
        return 2
    if not jobs:
        print("stage_a_multiple_joints: no code with multiple joints (and branch vertices) in this query",
              file=sys.stderr)
        return 2
    if any(not stage_a._stage_a_kernel_applies(c, conv) for c, conv in jobs):
        print("note: the kernel does not apply to "
              + ", ".join(str(c) for c, conv in jobs if not stage_a._stage_a_kernel_applies(c, conv)), file=sys.stderr)
        jobs = [(c, conv) for c, conv in jobs if stage_a._stage_a_kernel_applies(c, conv)]
    print(f"{'code':>24} {'H':>7} {'kernel s':>9} {'stream s':>9} {'old s':>9}  old path")
    bad, totals = 0, [0, 0.0, 0.0, 0.0]
    for code, conv in jobs:
        stream, stream_s = _timed(lambda: [g.certificate
                                           for g in stage_a._kernel_stream(code, conv, stage_a._LEAST_BUDGET)])
        row = [len(stream), 0.0, stream_s, 0.0]
        path = "-"
        if not args.kernel_only:
            listed, row[1] = _timed(lambda: [g.certificate for g in stage_a._contracted_by_kernel(code, conv)])
            path = "search" if stage_a._searched(code, conv) else "model"
            old_path = stage_a._contracted_by_search if path == "search" else stage_a._contracted_by_model
            old, row[3] = _timed(lambda: [g.certificate for g in old_path(code, conv)])
            same = len(set(stream)) == len(stream) and len(set(listed)) == len(listed) and \
                sorted(stream) == listed == sorted(old)
            if not same:
                bad += 1
                path += f"  DIFFERENT: kernel {len(listed)}, stream {len(stream)}, old {len(old)}"
        elif len(set(stream)) != len(stream):
            bad += 1
            path += "  DOUBLED"
        totals = [t + r for t, r in zip(totals, row)]
        print(f"{str(code):>24} {row[0]:>7} {_seconds(row[1], args)} {row[2]:>9.2f} {_seconds(row[3], args)}  {path}")
    print(f"{'total (' + str(len(jobs)) + ' codes)':>24} {totals[0]:>7} {_seconds(totals[1], args)} {totals[2]:>9.2f} "
          f"{_seconds(totals[3], args)}  {bad} codes differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
