"""The gear-train census split as finely as it goes — tree by tree — recorded once and compared after
every change of the enumerator.

For every link–axis tree of a size (in the engine's tree order) ``record`` writes one JSON line:
the tree's axes, its number of trains (displacement graphs) by lever-analogue code, and the
rotation graphs first met on that tree (trees in order: the train listed for a rotation graph is
its first displacement graph) by code; then a line with the totals and the CPU seconds of the
workers and of this process.  ``compare`` counts again with the engine of this tree and prints
every tree whose line differs (exit 1 if any does).

Run from the project root::

    nice -n 19 python benchmarks/gears_by_tree.py record benchmarks/logs/gears_by_tree_before.jsonl --dof 1 --links 6..9
    nice -n 19 python benchmarks/gears_by_tree.py compare benchmarks/logs/gears_by_tree_before.jsonl
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path.cwd()
sys.path.insert(0, str(ROOT))


def _tree(args):
    from synth.gears import tree_census

    start = time.process_time()
    n, codes, rotations = tree_census(*args)
    return n, codes, rotations, time.process_time() - start


def by_tree(dof: int, links: int, workers: int, every: int = 1):
    """One dict per tree (in tree order) and the totals, as :func:`census` would count them; with
    ``every`` > 1 only every ``every``-th tree (a sample of a size too long to record whole)."""
    from multiprocessing import get_context

    from synth.gears.enumeration import link_axis_trees

    trees = link_axis_trees(links)
    chosen = range(0, len(trees), every)
    jobs = [(dof, links, trees[k], True, "auto") for k in chosen]
    seen: set = set()
    rows, total, rotation, cpu = [], Counter(), Counter(), 0.0
    start = time.perf_counter()
    with get_context("fork").Pool(workers) as pool:
        for k, (n, codes, rotations, seconds) in zip(chosen, pool.imap(_tree, jobs, chunksize=4)):
            first = Counter(code for cert, code in rotations.items() if cert not in seen)
            seen.update(rotations)
            rows.append({"dof": dof, "links": links, "tree": k, "axes": [list(a) for a in trees[k]], "trains": n,
                         "by_code": dict(sorted(codes.items())), "rotation_by_code": dict(sorted(first.items()))})
            total.update(codes)
            rotation.update(first)
            cpu += seconds
    summary = {"dof": dof, "links": links, "every": every, "displacement": sum(total.values()), "rotation": sum(rotation.values()),
               "by_code": dict(sorted(total.items())), "rotation_by_code": dict(sorted(rotation.items())),
               "worker_cpu_seconds": round(cpu, 1), "wall_seconds": round(time.perf_counter() - start, 1),
               "peak_mib_parent": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024}
    return rows, summary


def _sizes(text: str) -> range:
    lo, _, hi = text.partition("..")
    return range(int(lo), int(hi or lo) + 1)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("action", choices=("record", "compare"))
    parser.add_argument("file")
    parser.add_argument("--dof", default="1", help="F, or a range 1..2 (record)")
    parser.add_argument("--links", default="6..9", help="a size or a range (record)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--every", type=int, default=1, help="record every k-th tree only (record)")
    args = parser.parse_args(argv)
    if args.action == "record":
        with open(args.file, "a") as out:
            for dof in _sizes(args.dof):
                for links in _sizes(args.links):
                    rows, summary = by_tree(dof, links, args.workers, args.every)
                    for row in rows:
                        out.write(json.dumps(row) + "\n")
                    out.write(json.dumps({"summary": summary}) + "\n")
                    out.flush()
                    print(json.dumps(summary), flush=True)
        return 0
    stored: dict = {}
    for line in Path(args.file).read_text().splitlines():
        row = json.loads(line)
        if "summary" in row:
            stored.setdefault((row["summary"]["dof"], row["summary"]["links"]), {})["summary"] = row["summary"]
        else:
            stored.setdefault((row["dof"], row["links"]), {})[row["tree"]] = row
    differing = 0
    for (dof, links), before in sorted(stored.items()):
        rows, summary = by_tree(dof, links, args.workers, before["summary"]["every"])
        for row in rows:
            if before.get(row["tree"]) != row:
                differing += 1
                print(f"F={dof} n={links} tree {row['tree']}: before {before.get(row['tree'])}, now {row}")
        keys = ("displacement", "rotation", "by_code", "rotation_by_code")
        same = all(before["summary"][k] == summary[k] for k in keys)
        differing += not same
        brief = {k: v for k, v in summary.items() if not k.endswith("by_code")}
        print(json.dumps({"same": same and differing == 0, "trees": len(rows),
                          "cpu_before": before["summary"]["worker_cpu_seconds"], **brief}), flush=True)
    return 1 if differing else 0


if __name__ == "__main__":
    raise SystemExit(main())
