"""How near an atlas index's samples of one mechanism come to a random mechanism's curve, as the index
samples it around one or several drawings (``--drawings``), and whether the polish from the nearest
samples recovers the curve exactly.

Run (after ``mechsynth grid`` on an atlas that holds the chain)::

    python benchmarks/bench_index_drawings.py --db ATLAS [--drawings 1 10 30] [--samples 20] [--seeds 8]
        [--polish 8]

The withheld mechanism (default: the eight-bar of bench_atlas_search.py) gets random dimensions from the
seeded generator of tests/atlas/test_curve_search.py, near the drawing of the chain *as it is written
there*; the samples are taken as the index takes them, of the atlas's own numbering of the chain (found
by certificate, frame, input and tracer link carried over by an isomorphism), around the atlas's drawing
and K − 1 others.  Prints one JSON line per (seed, K): CPU seconds of the sampling, samples of the
tracer link, the nearest descriptor misfits, and the polish of the ``--polish`` nearest (relative
largest error, CPU seconds) — the starts and the polish of the atlas search's (:func:`start_linkage`,
``synthesize(..., polish_only=True)``), without the retrieval's ranking against the other mechanisms.
"""

from __future__ import annotations

import argparse
import json
import sqlite3
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth import Chain, Mechanism  # noqa: E402
from synth.atlas.search import descriptor_of, sampled_starts  # noqa: E402
from synth.dimension import Constraints, synthesize  # noqa: E402
from tests.atlas.test_curve_search import _random_crank, _target  # noqa: E402
from bench_atlas_search import EIGHT_BAR  # noqa: E402


def in_atlas(db: str, mechanism: Mechanism, tracer_link: int) -> tuple[Mechanism, int]:
    """The mechanism in the atlas's numbering of its chain, and its tracer link there."""
    import networkx as nx

    from synth.synthesis.type_synthesis import mechanisms_of

    conn = sqlite3.connect(f"file:{db}?mode=ro", uri=True)
    try:
        chain = next(c for (text,) in conn.execute("SELECT chain FROM chains")
                     for c in [Chain.from_dict(json.loads(text))] if c.certificate == mechanism.chain.certificate)
    finally:
        conn.close()
    units = {(m.frame, m.input_link) for m in mechanisms_of(chain, input_link=True)}  # the index's, up to symmetry
    matcher = nx.algorithms.isomorphism.GraphMatcher(mechanism.chain.link_graph(), chain.link_graph())
    to = next(iso for iso in matcher.isomorphisms_iter() if (iso[mechanism.frame], iso[mechanism.input_link]) in units)
    return Mechanism(chain, to[mechanism.frame], to[mechanism.input_link]), to[tracer_link]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--db", required=True, help="an atlas holding the mechanism's chain")
    parser.add_argument("--drawings", type=int, nargs="+", default=[1, 10, 30])
    parser.add_argument("--samples", type=int, default=20, help="poses per drawing (default 20)")
    parser.add_argument("--seeds", type=int, nargs="+", default=[8])
    parser.add_argument("--polish", type=int, default=8, help="nearest samples polished (default 8)")
    parser.add_argument("--points", type=int, default=72)
    args = parser.parse_args()

    chain, frame, input_link, tracer_link = EIGHT_BAR
    withheld = Mechanism(Chain.parse(chain), frame, input_link)
    mechanism, tracer = in_atlas(args.db, withheld, tracer_link)
    for seed in args.seeds:
        target = _target(_random_crank(withheld, tracer_link, seed=seed), args.points, True)
        for drawings in args.drawings:
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
