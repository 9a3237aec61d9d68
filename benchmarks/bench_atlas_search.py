"""The atlas search at a given size of index: what the index holds and cost, retrieval time, and exact
recovery of a random mechanism's timed curve with its topology withheld.

Run (after ``mechsynth grid`` and ``mechsynth atlas --index-curves`` on the atlas)::

    python benchmarks/bench_atlas_search.py --db ATLAS [--mechanism CHAIN --frame F --input-link L
        --tracer-link T] [--seed S] [--points N] [--budget SECONDS] [--workers N]

Prints JSON lines: the index (mechanisms sampled and skipped, curves, the CPU seconds its units took,
the file's size), retrieval (CPU seconds to align the target to every indexed curve, timed and without
timing), and the search (each topology's error over the curve's size, CPU seconds of this process and
wall seconds, and the withheld chain's rank, by certificate).  The default
mechanism is an eight-bar whose tracer link's motion depends on all eight links; its random dimensions
come from the seeded generator of tests/atlas/test_curve_search.py.
"""

from __future__ import annotations

import argparse
import json
import os
import sqlite3
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth import Chain, Mechanism  # noqa: E402
from synth.atlas import index_info, retrieve, search_atlas  # noqa: E402
from synth.dimension import PathTarget  # noqa: E402
from tests.atlas.test_curve_search import _random_crank, _target  # noqa: E402

#: the default withheld mechanism: chain, frame, input link, tracer link (a link whose motion depends on all
#: eight: no smaller mechanism inside the chain traces its curve)
EIGHT_BAR = ("0-1 0-2 0-4 1-3 1-5 2-5 2-6 3-4 3-7 6-7", 2, 5, 7)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--db", required=True, help="an atlas with a curve index")
    parser.add_argument("--mechanism", default=EIGHT_BAR[0], help="the withheld mechanism's chain")
    parser.add_argument("--frame", type=int, default=EIGHT_BAR[1])
    parser.add_argument("--input-link", type=int, default=EIGHT_BAR[2])
    parser.add_argument("--tracer-link", type=int, default=EIGHT_BAR[3])
    parser.add_argument("--seed", type=int, default=8)
    parser.add_argument("--points", type=int, default=72)
    parser.add_argument("--budget", type=float, default=600.0, help="CPU seconds of polish (default 600)")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()

    info = index_info(args.db)
    conn = sqlite3.connect(f"file:{args.db}?mode=ro", uri=True)
    by_links = conn.execute("SELECT c.links, u.status, COUNT(*), SUM(u.seconds), SUM(u.tries) FROM curve_units u "
                            "JOIN chains c ON c.id = u.chain GROUP BY c.links, u.status ORDER BY c.links, u.status"
                            ).fetchall()
    curves = dict(conn.execute("SELECT c.links, COUNT(*) FROM curve_samples s JOIN chains c ON c.id = s.chain "
                               "GROUP BY c.links").fetchall())
    conn.close()
    print(json.dumps({"index": info, "bytes": os.path.getsize(args.db), "curves_by_links": curves,
                      "units": [{"links": n, "status": s, "mechanisms": k, "cpu_seconds": round(cpu, 1),
                                 "tries": tries} for n, s, k, cpu, tries in by_links]}), flush=True)

    mechanism = Mechanism(Chain.parse(args.mechanism), args.frame, args.input_link)
    linkage = _random_crank(mechanism, args.tracer_link, seed=args.seed)
    target = _target(linkage, args.points, True)
    untimed = PathTarget(target.points)
    for name, t in (("timed", target), ("untimed", untimed)):
        clock = time.process_time()
        found, size = retrieve(args.db, t, per_topology=3, topologies=5)
        print(json.dumps({"retrieval": name, "curves": size, "cpu_seconds": round(time.process_time() - clock, 3),
                          "nearest_misfit": min(c.misfit for c in found)}), flush=True)

    clock, wall = time.process_time(), time.perf_counter()
    result = search_atlas(args.db, target, budget=args.budget, workers=args.workers)
    rows = [{"rank": rank, **m.row()} for rank, m in enumerate(result.matches, 1)]
    withheld = next((r["rank"] for r, m in zip(rows, result.matches)
                     if m.mechanism.chain.certificate == mechanism.chain.certificate), None)
    print(json.dumps({"search": args.mechanism, "frame": args.frame, "input_link": args.input_link,
                      "tracer_link": args.tracer_link, "seed": args.seed, "points": args.points,
                      "withheld_chain_rank": withheld, "best_relative_max": rows[0]["relative_max"] if rows else None,
                      "cpu_seconds_parent": round(time.process_time() - clock, 1),
                      "wall_seconds": round(time.perf_counter() - wall, 1), "notes": result.notes,
                      "linkage": linkage.to_dict()}), flush=True)
    for row in rows:
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
