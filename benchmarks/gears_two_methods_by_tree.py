"""The gear-train census by two methods, compared tree by tree (issue 41: the check of 11 links).

For every link–axis tree of a size — all of them, or a seeded random sample — the engine
(``synth.gears.tree_census``) and the second method (``tests/oracles/gear_trains_fast.tree_census``,
no engine code) count the trains on the tree.  The two take their trees from their own lists
(nauty certificates; the brute force's canonical strings), paired here by that canonical string,
so each counts on its own numbering of the tree.  One JSON line per tree is appended to the log:
the tree (the engine's index and axes), both counts, both CPU times, and with ``--rotation``
the numbers of rotation graphs among the tree's trains by both.  A tree already in the log is
not run again, so a killed run goes on where it stopped.  At the end a summary line gives
what was checked: the trees, the trees agreeing, the trains they hold, the CPU seconds of
each method and the peak memory of this process.

Run from the project root (one process; a progress bar on stderr, or a line a minute when it is a file)::

    nice -n 19 python benchmarks/gears_two_methods_by_tree.py benchmarks/logs/gears_two_methods_F1_n11.jsonl --dof 1 --links 11
    python benchmarks/gears_two_methods_by_tree.py /tmp/t.jsonl --dof 2 --links 8 --rotation --sample 20 --seed 1

A sample is compared in the order it was drawn, so a run stopped by Ctrl-C has compared a
random part of it; the summary then says how many trees that was.  Exit status: 0 when every
tree compared agrees, 1 when one does not, 2 for bad options, 130 on Ctrl-C (after the summary).
"""

from __future__ import annotations

import argparse
import json
import random
import resource
import signal
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


def paired_trees(links: int) -> list[tuple[int, tuple, tuple]]:
    """(engine index, engine axes, second method's axes) for every tree, paired by the brute
    force's canonical string; an error if the two lists are not the same trees."""
    from synth.gears.enumeration import link_axis_trees
    from tests.oracles import gear_trains as brute

    second = {brute.canonical_tree(links, axes): axes for axes in brute.link_axis_trees(links)}
    engine = link_axis_trees(links)
    keys = [brute.canonical_tree(links, axes) for axes in engine]
    if len(set(keys)) != len(engine) or set(keys) != set(second):
        print(f"gears_two_methods_by_tree: the two lists of {links}-link trees differ ({len(engine)} and {len(second)} trees)",
              file=sys.stderr)
        raise SystemExit(1)
    return [(k, axes, second[key]) for k, (axes, key) in enumerate(zip(engine, keys))]


def compare_tree(dof: int, links: int, pair, rotation: bool) -> dict:
    """Both counts of one tree, and the CPU seconds of each."""
    from synth.gears import tree_census
    from tests.oracles import gear_trains_fast

    k, axes, other = pair
    start = time.process_time()
    n, _, rotations = tree_census(dof, links, axes, rotation=rotation)
    middle = time.process_time()
    second = gear_trains_fast.tree_census(dof, links, other, rotation=rotation)
    end = time.process_time()
    row = {"dof": dof, "links": links, "tree": k, "axes": [list(a) for a in axes], "engine": n,
           "second": second["displacement"], "engine_cpu": round(middle - start, 3), "second_cpu": round(end - middle, 3)}
    if rotation:
        row.update(engine_rotation=len(rotations), second_rotation=second["rotation"])
    return row


def _agrees(row: dict) -> bool:
    return row["engine"] == row["second"] and row.get("engine_rotation") == row.get("second_rotation")


def summary(rows: list[dict], trees: int, seconds: dict) -> dict:
    """What the log shows checked: never more than the rows in it."""
    agreeing = [r for r in rows if _agrees(r)]
    return {"trees_compared": len(rows), "trees_of_the_size": trees, "trees_agreeing": len(agreeing),
            "trains_on_agreeing_trees": sum(r["engine"] for r in agreeing),
            "rotation_compared": all("engine_rotation" in r for r in rows),
            "engine_cpu_s": round(sum(r["engine_cpu"] for r in rows), 1),
            "second_cpu_s": round(sum(r["second_cpu"] for r in rows), 1), **seconds}


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        """One sentence on stderr and exit status 2 (no usage block)."""
        print(f"gears_two_methods_by_tree: {message}", file=sys.stderr)
        raise SystemExit(2)


def main(argv=None) -> int:
    parser = _Parser(description=__doc__.splitlines()[0])
    parser.add_argument("log", type=Path, help="JSON lines, appended to (a run goes on where the log stops)")
    parser.add_argument("--dof", type=int, required=True, help="mobility F (1 or 2 …)")
    parser.add_argument("--links", type=int, required=True, help="number of links (4 … 12)")
    parser.add_argument("--sample", type=int, help="compare this many trees drawn at random (default: every tree)")
    parser.add_argument("--seed", type=int, help="seed of the sample (required with --sample)")
    parser.add_argument("--rotation", action="store_true", help="compare the numbers of rotation graphs per tree too")
    args = parser.parse_args(argv)
    if not 1 <= args.dof <= 3 or not 4 <= args.links <= 12:
        parser.error("--dof takes 1 … 3 and --links 4 … 12")
    if (args.sample is None) != (args.seed is None):
        parser.error("--sample and --seed go together (a sample is drawn from its seed)")
    if args.sample is not None and args.sample < 1:
        parser.error("--sample takes a positive number of trees")
    if args.log.is_dir() or not args.log.parent.is_dir():
        parser.error(f"cannot write the log {args.log}: not a file in an existing folder")
    done = {}
    if args.log.exists():
        for line in args.log.read_text().splitlines():
            try:
                row = json.loads(line)
            except ValueError:
                parser.error(f"{args.log} is not a log of this script (a line is not JSON); give a new file or its log")
            if not isinstance(row, dict):
                parser.error(f"{args.log} is not a log of this script (a line is not a JSON object)")
            if row.get("dof") == args.dof and row.get("links") == args.links and "tree" in row:
                if "engine_rotation" in row or not args.rotation:
                    done[row["tree"]] = row
    signal.signal(signal.SIGINT, signal.default_int_handler)  # Ctrl-C stops even a run started in the background
    try:
        pairs = paired_trees(args.links)
    except KeyboardInterrupt:
        print("gears_two_methods_by_tree: interrupted before any tree was compared", file=sys.stderr)
        return 130
    # a sample in its drawn order: a run stopped early has compared a random part of it
    chosen = pairs if args.sample is None else random.Random(args.seed).sample(pairs, min(args.sample, len(pairs)))
    todo = [p for p in chosen if p[0] not in done]
    wall, cpu = time.perf_counter(), time.process_time()
    print(f"F={args.dof}, {args.links} links: {len(chosen)} of {len(pairs)} trees, {len(chosen) - len(todo)} in the log",
          file=sys.stderr)
    from synth import Progress

    try:  # a bar on a terminal, a line a minute in a log
        with open(args.log, "a") as out, Progress(len(todo), "trees", desc="gears_two_methods_by_tree") as progress:
            for pair in todo:
                row = compare_tree(args.dof, args.links, pair, args.rotation)
                out.write(json.dumps(row) + "\n")
                out.flush()
                done[row["tree"]] = row
                if not _agrees(row):
                    progress.write(f"tree {row['tree']} {row['axes']}: engine {row['engine']}, "
                                   f"second method {row['second']}")
                progress.update(1, disagreeing=not _agrees(row))
    except KeyboardInterrupt:
        interrupted = True
    else:
        interrupted = False
    rows = [done[p[0]] for p in chosen if p[0] in done]
    seconds = {"this_run_cpu_s": round(time.process_time() - cpu, 1), "this_run_wall_s": round(time.perf_counter() - wall, 1),
               "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024,
               "sample": args.sample, "seed": args.seed, "interrupted": interrupted}
    result = {"summary": {"dof": args.dof, "links": args.links, **summary(rows, len(pairs), seconds)}}
    with open(args.log, "a") as out:
        out.write(json.dumps(result) + "\n")
    print(json.dumps(result))
    if interrupted:
        print("interrupted: the trees compared so far are in the log and in the summary above", file=sys.stderr)
        return 130
    return 0 if result["summary"]["trees_agreeing"] == len(rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
