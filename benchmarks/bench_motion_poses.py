"""Motion generation from no guess (issue 40): a random four-bar's coupler poses recovered by ``synthesize``.

Usage: ``python benchmarks/bench_motion_poses.py --seeds 0..4 [--poses N] [--span DEG] [--budget SECONDS]`` — one
JSON row per seed: the four-bar of :func:`random_four_bar` (seeded), N poses of its coupler (its point P and the
angle of its pins' line) as its crank turns through DEG (default 6 poses over 200°), dimensioned from no guess by
``synthesize`` with that seed and budget (CPU seconds, default 60): the largest position error over the target's
size, the largest angle error (rad), the CPU seconds (``time.process_time``), the candidates evaluated and the
method.  The results are in benchmarks/DIMENSION.md (*Motion generation from no guess*).

>>> lk = random_four_bar(0)
>>> len(poses(lk, 6, 200.0))
6
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from synth.dimension import MotionTarget, synthesize
from synth.motion import Linkage, sweep
from synth.structure.chain import Chain, Mechanism

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1 0-3 1-2 2-3


def random_four_bar(seed: int) -> Linkage:
    """A four-bar drawn at random (frame 2–4 along x, crank 0.5–1.2, rocker 1.5–3.5, P about the coupler's
    middle) whose crank turns a full turn with every transmission angle above 17°."""
    rng = np.random.default_rng(seed)
    for _ in range(10000):
        a, b = np.array([0.0, 0.0]), np.array([rng.uniform(2, 4), 0.0])
        crank, th = rng.uniform(0.5, 1.2), rng.uniform(0, 2 * math.pi)
        c = a + crank * np.array([math.cos(th), math.sin(th)])
        rocker, t = rng.uniform(1.5, 3.5), rng.uniform(0, math.pi)
        d = b + rocker * np.array([math.cos(t), math.sin(t)])
        p = (c + d) / 2 + rng.normal(size=2)
        try:
            lk = Linkage(FOUR_BAR, (0,), [a, b, c, d], tracers={"P": (2, tuple(p))})
            m = sweep(lk, steps=73)
        except Exception:  # (no assembly, or the crank stops: draw again)
            continue
        if m.stopped is None and all(min(v["min"], math.pi - v["max"]) > 0.3 for v in m.transmission.values()):
            return lk
    raise RuntimeError(f"no four-bar drawn for seed {seed}")


def poses(lk: Linkage, count: int, span_deg: float) -> MotionTarget:
    """``count`` poses of the coupler (P and its pins' line 1-2 → 2-3) over ``span_deg`` of crank turn."""
    m = sweep(lk, steps=count, stop=float(lk.pose_inputs[0]) + math.radians(span_deg))
    j = np.asarray(m.joints)
    d = j[:, 3] - j[:, 2]
    return MotionTarget(np.column_stack((m.tracers["P"], np.arctan2(d[:, 1], d[:, 0]))))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", default="0..4", help="A..B: the four-bars and search seeds")
    parser.add_argument("--poses", type=int, default=6)
    parser.add_argument("--span", type=float, default=200.0, help="degrees of crank turn the poses span")
    parser.add_argument("--budget", type=float, default=60.0)
    args = parser.parse_args()
    lo, hi = (int(v) for v in args.seeds.split(".."))
    for seed in range(lo, hi + 1):
        target = poses(random_four_bar(seed), args.poses, args.span)
        start = time.process_time()
        r = synthesize(FOUR_BAR, target, budget=args.budget, seed=seed)
        print(json.dumps({"seed": seed, "poses": args.poses, "span_deg": args.span, "relative_max": r.relative_max,
                          "angle_max_rad": float(np.abs(r.angle_errors).max()),
                          "cpu_s": round(time.process_time() - start, 2), "evaluations": r.evaluations, "met": r.met,
                          "method": r.method}), flush=True)


if __name__ == "__main__":
    main()
