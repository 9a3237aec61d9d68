"""Dimensional synthesis on classical four-bar path problems and on pylinkage's documented examples:
error and CPU time per problem, pylinkage 1.3.0 side by side where it has an example.

Usage: ``python benchmarks/bench_dimension.py [--budget SECONDS] [--seed N] [--only NAME] [--reach R]
[--pylinkage-python PATH]`` — one row per problem (JSON lines on stdout): the sum of squared
errors (the objective the literature reports), the largest and RMS error in the target's units,
the relative error, CPU seconds and candidates evaluated.  The problems and their sources are in
benchmarks/DIMENSION.md.

``python benchmarks/bench_dimension.py --reliability SEEDS [--budget SECONDS]`` measures how often
the search finds a mechanism's own points again from no guess: for each seed (``0..9``) a crank-rocker
with random dimensions gives ten points without timing (a whole turn), and an offset slider-crank
with random dimensions eight timed points over 300° (the search given ``synth.atlas.sampled_starts``);
a row per seed and case says the relative error
reached and the CPU seconds (the search stops early once the target is met to 1e-11 of its size).

pylinkage is not a dependency of the project: its side runs in a virtual environment of its own with
the SciPy extra its synthesis needs, made once with

    python -m venv /tmp/pylinkage-synth
    /tmp/pylinkage-synth/bin/pip install 'pylinkage[scipy]==1.3.0'

(without that interpreter its rows are left out).  Its ``path_generation`` is called exactly as its
README shows, timed in CPU seconds (the import excluded); each of its solutions is then moved through
a whole turn of its crank by its own simulation (20 000 steps) and each target point's distance to
that coupler curve is its error — the nearest point of the curve, whatever the order, which can only
flatter it.  Ours is the distance at the point's own input, in order.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth import Chain, Mechanism  # noqa: E402
from synth.atlas import sampled_starts  # noqa: E402
from synth.dimension import Constraints, PathTarget, synthesize  # noqa: E402
from synth.motion import Linkage, motion_range, sweep  # noqa: E402
from tests.dimension.test_synthesize import SLIDER_CRANK, random_crank_rocker  # noqa: E402

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
DEFAULT_PYLINKAGE = "/tmp/pylinkage-synth/bin/python"

#: name -> (points, inputs or None, pylinkage runs it too)
PROBLEMS = {
    # as later papers restate Cabrera, Simon and Prado (2002); see DIMENSION.md for what is unchecked
    "five points on a line, timed": (
        [(20, 20), (20, 25), (20, 30), (20, 35), (20, 40)],
        [math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2], False),
    "six points on a line, untimed": (
        [(20, 20), (20, 25), (20, 30), (20, 35), (20, 40), (20, 45)], None, False),
    "ten points of a closed path, untimed": (
        [(20, 10), (17.66, 15.142), (11.736, 17.878), (5, 16.928), (0.60307, 12.736), (0, 6.9519),
         (3.5396, 2.5171), (10, 0.2679), (16.736, 2.1216), (20, 6.5798)], None, False),
    # pylinkage 1.3.0: its README's example, and its path_generation docstring's
    "pylinkage README: four points, untimed": ([(0, 0), (1, 1), (2, 1), (3, 0)], None, True),
    "pylinkage docstring: four points, untimed": ([(0, 1), (1, 2), (2, 1.5), (3, 0)], None, True),
}

# The pylinkage side, run by its own interpreter: path_generation as documented, each solution moved
# through a whole turn of its crank by its own simulation, each target point's distance to that curve.
PYLINKAGE = r"""
import json, math, sys, time
import numpy as np
from pylinkage.synthesis import path_generation

job = json.loads(sys.argv[1])
start = time.process_time()
result = path_generation([tuple(p) for p in job["points"]])
seconds = time.process_time() - start
target = np.array(job["points"], dtype=float)
rows = []
for linkage in result.solutions:
    crank = next(c for c in linkage.components if type(c).__name__ == "Crank")
    names = [c.name for c in linkage.components]
    steps = job["steps"]
    curve = []
    for positions in linkage.step(iterations=steps, dt=2 * math.pi / (steps * abs(crank.angular_velocity))):
        if positions[names.index("P")][0] is None:
            break
        curve.append(positions[names.index("P")])
    c = np.array(curve, dtype=float)
    a, ab = c[:-1], c[1:] - c[:-1]
    w = target[:, None, :] - a[None]
    f = np.clip((w * ab[None]).sum(2) / np.maximum((ab ** 2).sum(1), 1e-300), 0, 1)
    rows.append({"full_turn": len(curve) == steps,
                 "errors": np.sqrt(((w - f[..., None] * ab[None]) ** 2).sum(2)).min(axis=1).tolist()})
print(json.dumps({"seconds": seconds, "solutions": rows}))
"""


def _pylinkage(python: str, points) -> dict | None:
    """pylinkage's answer to the points: CPU seconds, and its first and best solution's errors."""
    done = subprocess.run([python, "-c", PYLINKAGE, json.dumps({"points": points, "steps": 20000})],
                          capture_output=True, text=True, timeout=1800)
    if done.returncode != 0:
        print(f"pylinkage failed: {done.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    answer = json.loads(done.stdout)
    errors = [np.array(s["errors"]) for s in answer["solutions"]]
    if not errors:
        return {"pylinkage_cpu_seconds": round(answer["seconds"], 2), "pylinkage_solutions": 0}
    best = min(errors, key=lambda e: float(e.max()))
    size = float(np.hypot(*np.ptp(np.array(points, dtype=float), axis=0)))
    return {"pylinkage_cpu_seconds": round(answer["seconds"], 2), "pylinkage_solutions": len(errors),
            "pylinkage_first_error_max": float(errors[0].max()),
            "pylinkage_first_sum_squared_error": float(errors[0] @ errors[0]),
            "pylinkage_best_error_max": float(best.max()), "pylinkage_best_sum_squared_error": float(best @ best),
            "pylinkage_best_relative_max": float(best.max()) / size}


def random_slider_crank(seed: int) -> Linkage:
    """An offset slider-crank whose crank turns fully, with a point P on its rod, its dimensions drawn
    at random (crank 0.4–0.8, rod 2–3, offset within ±0.3, the point near the rod)."""
    rng = np.random.default_rng(100 + seed)
    while True:
        crank, rod, offset = rng.uniform(0.4, 0.8), rng.uniform(2.0, 3.0), rng.uniform(-0.3, 0.3)
        phi = rng.uniform(0, 2 * math.pi)
        pin = crank * np.array([math.cos(phi), math.sin(phi)])
        block = np.array([pin[0] + math.sqrt(rod * rod - (offset - pin[1]) ** 2), offset])
        at = pin + (block - pin) * rng.uniform(0.2, 0.8) + rng.normal(size=2) * 0.5
        linkage = Linkage(SLIDER_CRANK, (0,), [[0, 0], block, pin, block], {1: (1.0, 0.0)},
                          tracers={"P": (2, tuple(at))})
        if motion_range(linkage).full_rotation:
            return linkage


def reliability(seeds: range, budget: float) -> None:
    """A row per seed and case: the relative error the search reaches from no guess, and its CPU time."""
    for seed in seeds:
        rocker = random_crank_rocker(seed)
        slider = random_slider_crank(seed)
        timed = sweep(slider, steps=8, stop=float(slider.pose_inputs[0]) + math.radians(300))
        cases = {"crank-rocker, 10 points, untimed": (FOUR_BAR, PathTarget(sweep(rocker, steps=11).tracers["P"][:10])),
                 "slider-crank, 8 points, timed": (SLIDER_CRANK, PathTarget(timed.tracers["P"], timed.inputs[:, 0]))}
        for case, (mechanism, target) in cases.items():
            result = synthesize(mechanism, target, budget=budget, seed=seed, starts=sampled_starts)
            print(json.dumps({"case": case, "seed": seed, "relative_max": result.relative_max,
                              "cpu_seconds": round(result.seconds, 1), "evaluations": result.evaluations,
                              "met": result.met}), flush=True)


def seed_range(text: str) -> range:
    """Seeds "A..B" (or one seed "A") for --reliability."""
    lo, _, hi = text.partition("..")
    try:
        seeds = range(int(lo), int(hi or lo) + 1)
    except ValueError:
        raise argparse.ArgumentTypeError(f"seeds are A..B or A, whole numbers, not {text!r}") from None
    if not seeds:
        raise argparse.ArgumentTypeError(f"the seed range {text!r} is empty")
    return seeds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=60.0, help="CPU seconds per problem (default 60)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--only", choices=sorted(PROBLEMS), help="run this problem alone")
    parser.add_argument("--reach", type=float, help="the search box in target sizes (default 4)")
    parser.add_argument("--pylinkage-python", default=DEFAULT_PYLINKAGE,
                        help=f"pylinkage's interpreter (default {DEFAULT_PYLINKAGE}; left out if absent)")
    parser.add_argument("--reliability", metavar="A..B", type=seed_range,
                        help="the reliability runs for these seeds instead")
    args = parser.parse_args()
    if args.reliability is not None:
        reliability(args.reliability, args.budget)
        return
    have_pylinkage = Path(args.pylinkage_python).exists()
    for name, (points, inputs, theirs) in PROBLEMS.items():
        if args.only is not None and name != args.only:
            continue
        target = PathTarget(np.array(points, dtype=float), None if inputs is None else np.array(inputs))
        result = synthesize(FOUR_BAR, target, constraints=Constraints(reach=args.reach), budget=args.budget,
                            seed=args.seed, underdetermined=True)
        row = {"problem": name, "points": len(points), "sum_squared_error": float(np.sum(result.errors ** 2)),
               "error_max": result.error_max, "error_rms": result.error_rms, "relative_max": result.relative_max,
               "cpu_seconds": round(result.seconds, 1), "evaluations": result.evaluations, "met": result.met}
        if theirs and have_pylinkage:
            row.update(_pylinkage(args.pylinkage_python, points) or {})
        row["linkage"] = result.linkage.to_dict()
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
