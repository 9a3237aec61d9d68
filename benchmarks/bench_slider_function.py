"""Function generation with a slider (issue 40): random offset slider-cranks' functions recovered from no guess.

Usage: ``python benchmarks/bench_slider_function.py [--seeds A..B] [--budget SECONDS]`` — one JSON row per seed
and direction: ``output`` (crank angle → slider displacement, 14 pairs over 120°–330° of crank angle) and
``input`` (the slider drives: 12 displacements on one stroke → crank angle).  Each row gives the error (the
target's unit: length or rad), the error relative to the target's size, how far the found crank, rod and offset
lie from the drawn ones (over the rod), the CPU seconds of the search (``time.process_time``) and whether every
constraint was met.  ``--six-bar`` instead dimensions a Watt six-bar whose rocker drives a slider (``SIX_BAR``),
its function drawn from the pose ``SIX_BAR_POSE`` as 13 pairs over 40°–160° of crank angle: one row, its
dimensions not compared (other six-bars may give the same pairs).  ``--free-origin`` gives the displacements
from a datum 0.37 short of the first pair's place, the origin free (``origin="free"``).  The results are in benchmarks/DIMENSION.md
(*Functions with a slider*).

>>> r, l, e, _ = random_slider_crank(0)
>>> bool(r + abs(e) < l)   # the crank turns fully
True
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

#: the slider-crank: joints 0-1, 0=3, 1-2, 2-3 (crank 1, rod 2, slider 3 on the frame's line)
CHAIN = "0-1 1-2 2-3 3=0"


def displacement(theta, r, l, e):
    """The slider's pin along its line from the crank pivot's foot: an offset slider-crank's closed form.

    >>> float(displacement(0.0, 1.0, 3.0, 0.0))
    4.0
    """
    return r * np.cos(theta) + np.sqrt(l ** 2 - (r * np.sin(theta) - e) ** 2)


def random_slider_crank(seed: int):
    """(crank r, rod l, offset e, the generator for the pairs) drawn at random; r + |e| < l: the crank turns."""
    rng = np.random.default_rng(seed)
    return rng.uniform(0.5, 1.5), rng.uniform(2.5, 4.0), rng.uniform(-0.8, 0.8), rng


def pairs(seed: int, driven_by_slider: bool):
    """(crank angles, displacements, (r, l, e)) of a random slider-crank: 14 pairs over 120°–330° of a whole turn,
    or, for the slider as the input, 12 pairs over 60°–120° of crank angle from 11°–29°, on one stroke."""
    r, l, e, rng = random_slider_crank(seed)
    if driven_by_slider:
        theta = rng.uniform(0.2, 0.5) + np.linspace(0.0, math.radians(rng.uniform(60, 120)), 12)
    else:
        theta = rng.uniform(0, 2 * math.pi) + np.linspace(0.0, math.radians(rng.uniform(120, 330)), 14)
    return theta, displacement(theta, r, l, e), (r, l, e)


def recovered(linkage, dims) -> float:
    """How far the linkage's crank, rod and offset (the slider pin's height over the crank pivot) lie from ``dims``,
    over the rod."""
    lengths = linkage.lengths()
    found = lengths[1], lengths[2], linkage.points[3][1]
    return max(abs(a - b) for a, b in zip(found, dims)) / dims[1]


#: a four-bar 0-1-2-3 whose rocker 3 drives a slider 5 on the frame through the rod 4; and a pose of it (joint -> x, y)
SIX_BAR = "0-1 1-2 2-3 3-0 3-4 4-5 5=0"
SIX_BAR_POSE = {"0-1": (0, 0), "1-2": (0.6, 0.5), "0-3": (2.5, 0.2), "2-3": (2.4, 1.9), "3-4": (3.0, 1.6),
                "4-5": (4.6, 0.9), "0=5": (4.6, 0.9)}


def six_bar(budget: float) -> dict:
    """The six-bar's own slider displacements (its pin 4-5 along the x axis) at 13 crank angles, dimensioned from
    no guess (the output link 5, the slider)."""
    from synth.dimension import FunctionTarget, synthesize
    from synth.motion import Linkage, assemble, joint_name
    from synth.structure.chain import Chain, Mechanism

    chain = Chain.parse(SIX_BAR)
    names = [joint_name(chain, k) for k in range(len(chain.joints))]
    mechanism = Mechanism(chain, 0)
    drawn = Linkage(mechanism, (0,), [SIX_BAR_POSE[n] for n in names], {names.index("0=5"): (1.0, 0.0)})
    theta, pin = np.radians(np.arange(40.0, 161.0, 10.0)), names.index("4-5")
    s = np.array([assemble(drawn, angle).points[pin][0] for angle in theta])
    start = time.process_time()
    result = synthesize(mechanism, FunctionTarget(theta, s, output_link=5, output_is="displacement"), budget=budget)
    moved = np.array([assemble(result.linkage, angle).points[pin][0] for angle in theta])
    return {"mechanism": SIX_BAR, "pairs": len(theta), "error_max": result.error_max,
            "relative_max": result.relative_max, "moved_error_max": float(np.abs(moved - s).max()),
            "cpu_s": round(time.process_time() - start, 3), "met": result.met}


def run(seed: int, driven_by_slider: bool, budget: float, free: bool = False) -> dict:
    """One search; with ``free`` the displacements are given from a datum 0.37 short of the first pair's, the origin
    free (the row then says how far the found pivot lies from where the datum puts it, over the rod)."""
    from synth.dimension import FunctionTarget, synthesize
    from synth.structure.chain import Chain, Mechanism

    theta, s, dims = pairs(seed, driven_by_slider)
    datum = s[0] - 0.37 if free else 0.0
    origin = "free" if free else "pivot"
    if driven_by_slider:
        mechanism = Mechanism(Chain.parse(CHAIN), 0, 3)
        target = FunctionTarget(s - datum, theta, input_is="displacement", origin=origin)
    else:
        mechanism = Mechanism(Chain.parse(CHAIN), 0)
        target = FunctionTarget(theta, s - datum, output_is="displacement", origin=origin)
    start = time.process_time()
    result = synthesize(mechanism, target, budget=budget, seed=0)
    row = {"seed": seed, "input": "slider" if driven_by_slider else "crank", "origin": origin, "pairs": len(theta),
           "error_max": result.error_max, "relative_max": result.relative_max,
           "dimensions_off": recovered(result.linkage, dims), "cpu_s": round(time.process_time() - start, 3),
           "met": result.met}
    if free:
        row["pivot_off"] = abs(float(result.linkage.points[0][0]) + datum) / dims[1]
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0..9", help="A..B, the seeds drawn")
    parser.add_argument("--budget", type=float, default=10.0, help="CPU seconds per search")
    parser.add_argument("--six-bar", action="store_true", help="the six-bar driving a slider instead")
    parser.add_argument("--free-origin", action="store_true", help="displacements from a datum, the origin free")
    args = parser.parse_args()
    if args.six_bar:
        print(json.dumps(six_bar(args.budget)), flush=True)
        return
    a, _, b = args.seeds.partition("..")
    for seed in range(int(a), int(b or a) + 1):
        for driven_by_slider in (False, True):
            print(json.dumps(run(seed, driven_by_slider, args.budget, args.free_origin)), flush=True)


if __name__ == "__main__":
    main()
