"""Dimensional synthesis on classical four-bar path problems: error and CPU time per problem.

Usage: ``python benchmarks/bench_dimension.py [--budget SECONDS] [--seed N]`` — one row per problem
(JSON lines on stdout): the error (max and RMS, in the target's units), the relative error, CPU
seconds and candidates evaluated.  The problems and their sources are in benchmarks/DIMENSION.md.
"""

from __future__ import annotations

import argparse
import json
import math

import numpy as np

from synth import Chain, Mechanism
from synth.dimension import PathTarget, synthesize

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)

#: the problems as later papers restate Cabrera, Simon and Prado (2002): name -> (points, inputs or None)
PROBLEMS = {
    "five points on a line, timed": (
        [(20, 20), (20, 25), (20, 30), (20, 35), (20, 40)],
        [math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2]),
    "six points on a line, untimed": (
        [(20, 20), (20, 25), (20, 30), (20, 35), (20, 40), (20, 45)], None),
    "ten points of a closed path, untimed": (
        [(20, 10), (17.66, 15.142), (11.736, 17.878), (5, 16.928), (0.60307, 12.736), (0, 6.9519),
         (3.5396, 2.5171), (10, 0.2679), (16.736, 2.1216), (20, 6.5798)], None),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=60.0, help="CPU seconds per problem (default 60)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    for name, (points, inputs) in PROBLEMS.items():
        target = PathTarget(np.array(points, dtype=float), None if inputs is None else np.array(inputs))
        result = synthesize(FOUR_BAR, target, budget=args.budget, seed=args.seed, underdetermined=True)
        squared = float(np.sum(result.errors ** 2))
        print(json.dumps({"problem": name, "points": len(points), "sum_squared_error": squared,
                          "error_max": result.error_max, "error_rms": result.error_rms,
                          "relative_max": result.relative_max, "cpu_seconds": round(result.seconds, 1),
                          "evaluations": result.evaluations, "met": result.met,
                          "linkage": result.linkage.to_dict()}), flush=True)


if __name__ == "__main__":
    main()
