"""Motion generation from no guess (issue 40): a random four-bar's, slider-crank's or six-bar's coupler poses
recovered by ``synthesize``.

Usage: ``python benchmarks/bench_motion_poses.py --seeds 0..4 [--poses N] [--span DEG] [--budget SECONDS]
[--mechanism four-bar|slider-crank|watt|stephenson]`` — one JSON row per seed: the mechanism of
:func:`random_four_bar`, :func:`random_slider_crank`, :func:`random_watt` or :func:`random_stephenson` (seeded), N
poses of its coupler (its point P and the angle of the line of its first two pins) as its
crank turns through DEG (default 6 poses over 200°), dimensioned from no guess by ``synthesize`` with that seed and
budget (CPU seconds, default 60; an underdetermined problem, fewer poses than the precision-point count, allowed):
the largest position error over the target's size, the largest angle error (rad), the CPU seconds
(``time.process_time``), the candidates evaluated and the method.  The results are in benchmarks/DIMENSION.md
(*Motion generation from no guess*, *A slider-crank's and a six-bar's poses from their dyads*).

>>> lk = random_four_bar(0)
>>> len(poses(lk, 6, 200.0))
6
>>> sorted(random_slider_crank(0).slides)    # joints 0-1 0=3 1-2 2-3: the slide is joint 1
[1]
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from synth.dimension import MotionTarget, equations_and_unknowns, synthesize
from synth.motion import Linkage, motion_range, sweep
from synth.structure.chain import Chain, Mechanism

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1 0-3 1-2 2-3
SLIDER_CRANK = Mechanism(Chain.parse("0-1 1-2 2-3 3=0"), 0)  # joints 0-1 0=3 1-2 2-3: the rod 2 slides on 3
WATT = Mechanism(Chain.parse("0-1 0-2 1-3 2-3 2-4 3-5 4-5"), 0, 1)  # the four-bar 0-1-3-2 and the dyad 4-5 on 2, 3
STEPHENSON = Mechanism(Chain.parse("0-1 0-3 0-5 1-2 2-3 2-4 4-5"), 0, 1)  # the four-bar 0-1-2-3, the dyad 4-5 on 2, 0


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


def random_slider_crank(seed: int) -> Linkage:
    """An offset slider-crank drawn at random (crank pivot near the origin, crank 0.5–1.2, rod 2–3.5, the slider's
    line at any angle and offset up to ±0.5 from the pivot, P about the rod's middle) whose crank turns a full
    turn."""
    rng = np.random.default_rng(seed)
    for _ in range(10000):
        a = rng.normal(size=2)
        crank, th = rng.uniform(0.5, 1.2), rng.uniform(0, 2 * math.pi)
        c = a + crank * np.array([math.cos(th), math.sin(th)])
        turn = rng.uniform(0, 2 * math.pi)
        along, across = np.array([math.cos(turn), math.sin(turn)]), np.array([-math.sin(turn), math.cos(turn)])
        offset, rod = rng.uniform(-0.5, 0.5), rng.uniform(2, 3.5)
        foot = a + offset * across  # the line's point nearest the pivot
        reach = rod ** 2 - float((c - foot) @ across) ** 2
        if rod - crank <= abs(offset) + 0.2 or reach <= 0:
            continue  # (the crank would not turn: draw again)
        b = foot + (float((c - foot) @ along) + math.sqrt(reach)) * along
        p = (c + b) / 2 + 0.7 * rng.normal(size=2)
        lk = Linkage(SLIDER_CRANK, (0,), [a, foot, c, b], {1: tuple(along)}, tracers={"P": (2, tuple(p))})
        if motion_range(lk).full_rotation:
            return lk
    raise RuntimeError(f"no slider-crank drawn for seed {seed}")


def _six_bar(seed: int, mechanism: Mechanism, coupler: int, pose, salt: int) -> Linkage:
    """The four-bar of :func:`random_four_bar` (pivots a, b, pins c, d; P on its coupler) with a dyad jointed at
    three random points within the four-bar's size, ``pose(a, b, c, d, three points)`` giving every joint's place in
    the chain's order, P on the link ``coupler``; drawn until the crank turns a full turn."""
    base, rng = random_four_bar(seed), np.random.default_rng(salt + seed)
    a, b, c, d = base.points
    reach = np.ptp(base.points, axis=0).max()
    for _ in range(10000):
        try:
            lk = Linkage(mechanism, (0,), pose(a, b, c, d, (c + d) / 2 + reach * rng.uniform(-1, 1, (3, 2))),
                         tracers={"P": (coupler, base.tracers["P"][1])})
            if motion_range(lk).full_rotation:
                return lk
        except Exception:  # (a zero-length link: draw again)
            continue
    raise RuntimeError(f"no six-bar drawn for seed {seed}")


def random_watt(seed: int) -> Linkage:
    """A Watt six-bar: the four-bar 0-1-3-2 of :func:`random_four_bar` (its rocker 2, coupler 3 with P) and a dyad
    4-5 jointed at random to its rocker and coupler."""
    return _six_bar(seed, WATT, 3, lambda a, b, c, d, r: [a, b, c, d, (b - c) / 2 + r[0], r[1], r[2]], 10_000)


def random_stephenson(seed: int) -> Linkage:
    """A Stephenson six-bar: the four-bar 0-1-2-3 of :func:`random_four_bar` (its coupler 2 with P) and a dyad 4-5
    jointed at random to its coupler and the frame."""
    return _six_bar(seed, STEPHENSON, 2, lambda a, b, c, d, r: [a, b, r[0], c, d, r[1], r[2]], 20_000)


DRAWN = {"four-bar": (FOUR_BAR, random_four_bar), "slider-crank": (SLIDER_CRANK, random_slider_crank),
         "watt": (WATT, random_watt), "stephenson": (STEPHENSON, random_stephenson)}


def poses(lk: Linkage, count: int, span_deg: float) -> MotionTarget:
    """``count`` poses of the tracer's link (P and the line of its first two pins) over ``span_deg`` of crank turn."""
    link = lk.tracers["P"][0]
    first, second = [k for k, j in enumerate(lk.chain.joints) if link in j][:2]
    m = sweep(lk, steps=count, stop=float(lk.pose_inputs[0]) + math.radians(span_deg))
    j = np.asarray(m.joints)
    d = j[:, second] - j[:, first]
    return MotionTarget(np.column_stack((m.tracers["P"], np.arctan2(d[:, 1], d[:, 0]))))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", default="0..4", help="A..B: the four-bars and search seeds")
    parser.add_argument("--poses", type=int, default=6)
    parser.add_argument("--span", type=float, default=200.0, help="degrees of crank turn the poses span")
    parser.add_argument("--budget", type=float, default=60.0)
    parser.add_argument("--mechanism", choices=sorted(DRAWN), default="four-bar")
    args = parser.parse_args()
    lo, hi = (int(v) for v in args.seeds.split(".."))
    mechanism, drawn = DRAWN[args.mechanism]
    for seed in range(lo, hi + 1):
        target = poses(drawn(seed), args.poses, args.span)
        equations, unknowns = equations_and_unknowns(mechanism, target)
        start = time.process_time()
        r = synthesize(mechanism, target, budget=args.budget, seed=seed, underdetermined=equations < unknowns)
        print(json.dumps({"mechanism": args.mechanism, "seed": seed, "poses": args.poses, "span_deg": args.span, "relative_max": r.relative_max,
                          "angle_max_rad": float(np.abs(r.angle_errors).max()),
                          "cpu_s": round(time.process_time() - start, 2), "evaluations": r.evaluations, "met": r.met,
                          "method": r.method}), flush=True)


if __name__ == "__main__":
    main()
