"""How near an atlas index's samples of one mechanism come to a random mechanism's curve, as the index
samples it around one or several drawings (``--drawings``), and whether the polish from the nearest
samples recovers the curve exactly.

Run (after ``mechsynth grid`` on an atlas that holds the chain)::

    python benchmarks/bench_index_drawings.py --db ATLAS [--drawings 1 10 30] [--samples 20] [--seeds 8]
        [--polish 8] [--atlas-polish BUDGET]

The withheld mechanism (default: the eight-bar of bench_atlas_search.py) gets random dimensions from the
seeded generator of tests/atlas/test_curve_search.py, near the drawing of the chain *as it is written
there*; the samples are taken as the index takes them, of the atlas's own numbering of the chain (found
by certificate, frame, input and tracer link carried over by an isomorphism), around the atlas's drawing
and K − 1 others.  Prints one JSON line per (seed, K): CPU seconds of the sampling, samples of the
tracer link, the nearest descriptor misfits, and the polish of the ``--polish`` nearest (relative
largest error, CPU seconds) — the starts and the polish of the atlas search's (:func:`start_linkage`,
``synthesize(..., polish_only=True)``), without the retrieval's ranking against the other mechanisms.
With ``--atlas-polish BUDGET`` the nearest 3 K samples (the search's default for an index of K drawings)
go instead through the atlas search's stage for one topology, with BUDGET CPU seconds (its share of the
search's budget): the slices, the going on from the best, then the global stage.  ``same_dimensions``
is the largest difference between the sorted distances of joints on a link, withheld against found,
over the curve's size (0: the withheld mechanism itself; far from 0: another tracing the same curve).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth import Chain, Mechanism  # noqa: E402
from synth.atlas.search import PER_DRAWING, TopologyPolish, polish_topology, sampled_candidates, sampled_starts  # noqa: E402
from synth.dimension import Constraints, synthesize  # noqa: E402
from tests.atlas.test_curve_search import _in_atlas, _random_crank, _target  # noqa: E402
from bench_atlas_search import EIGHT_BAR  # noqa: E402


def link_distances(linkage) -> np.ndarray:
    """The distances between the joints (and the tracer point) of each link in the pose, sorted: equal
    for two linkages of one chain with the same dimensions, whatever their numbering or placement."""
    chain = linkage.mechanism.chain
    out = []
    for link in range(chain.links):
        at = [linkage.points[k] for k, joint in enumerate(chain.joints) if link in joint]
        if linkage.tracers["P"][0] == link:
            at.append(np.asarray(linkage.tracers["P"][1]))
        out += [float(np.hypot(*(a - b))) for i, a in enumerate(at) for b in at[i + 1:]]
    return np.sort(out)


def atlas_polish(mechanism, tracer, withheld, target, drawings: int, samples: int, budget: float) -> dict:
    """The atlas search's stage for one topology on the mechanism's nearest samples (see the module's
    docstring)."""
    clock = time.process_time()
    rows = sampled_candidates(mechanism, tracer, target, samples=samples, drawings=drawings)[:PER_DRAWING * drawings]
    sampled = time.process_time() - clock
    task = TopologyPolish(json.dumps(mechanism.chain.to_dict()), tuple(rows), target, Constraints(), budget, 0)
    result, candidate, tried, why, spent = polish_topology(task)
    gap = np.abs(link_distances(withheld) - link_distances(result.linkage)).max() / target.size
    return {"candidates": len(rows), "sampling_cpu_seconds": round(sampled, 1), "tried": tried,
            "relative_max": float(f"{result.relative_max:.3g}"), "cpu_seconds": round(spent, 1),
            "nearest_misfit_rank": rows.index(next(r for r in rows if r[0] is candidate)),
            "same_dimensions": float(f"{gap:.2g}")}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--db", required=True, help="an atlas holding the mechanism's chain")
    parser.add_argument("--drawings", type=int, nargs="+", default=[1, 10, 30])
    parser.add_argument("--samples", type=int, default=20, help="poses per drawing (default 20)")
    parser.add_argument("--seeds", type=int, nargs="+", default=[8])
    parser.add_argument("--polish", type=int, default=8, help="nearest samples polished (default 8)")
    parser.add_argument("--points", type=int, default=72)
    parser.add_argument("--atlas-polish", type=float, metavar="BUDGET",
                        help="the atlas search's stage for one topology, with this many CPU seconds, instead")
    args = parser.parse_args()

    chain, frame, input_link, tracer_link = EIGHT_BAR
    withheld = Mechanism(Chain.parse(chain), frame, input_link)
    mechanism, tracer = _in_atlas(args.db, withheld, tracer_link)
    for seed in args.seeds:
        truth = _random_crank(withheld, tracer_link, seed=seed)
        target = _target(truth, args.points, True)
        for drawings in args.drawings:
            if args.atlas_polish:
                print(json.dumps({"seed": seed, "drawings": drawings, "samples_per_drawing": args.samples,
                                  **atlas_polish(mechanism, tracer, truth, target, drawings, args.samples,
                                                 args.atlas_polish)}), flush=True)
                continue
            clock = time.process_time()
            starts = sampled_starts(mechanism, tracer, target, samples=args.samples, drawings=drawings)
            sampled = time.process_time() - clock
            polished = []
            for start in starts[:args.polish]:
                clock = time.process_time()
                centre = (np.min(target.points, axis=0) + np.max(target.points, axis=0)) / 2
                far = float(np.hypot(*(np.vstack((start.points, start.tracers["P"][1])) - centre).T).max())
                result = synthesize(start, target, tracer_link=tracer,
                                    constraints=Constraints(reach=3 * far / target.size), budget=60, polish_only=True)
                polished.append({"relative_max": float(f"{result.relative_max:.3g}"),
                                 "cpu_seconds": round(time.process_time() - clock, 1)})
            print(json.dumps({"seed": seed, "drawings": drawings, "samples_per_drawing": args.samples,
                              "atlas_mechanism": [mechanism.frame, mechanism.input_link], "tracer_link": tracer,
                              "starts": len(starts), "sampling_cpu_seconds": round(sampled, 1),
                              "polished": polished,
                              "exact": sum(p["relative_max"] <= 1e-6 for p in polished)}), flush=True)


if __name__ == "__main__":
    main()
