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
each method and the peak memory of this process; with ``--rotation`` also the rotation graphs
of the whole size by each method — the union over the trees of each method's own canonical
forms (nauty for the engine, bliss for the second method) — when this run compared every tree
(``null`` after a sample or a resumed run: the forms of the trees in the log are not kept).

Run from the project root (one process; a progress bar on stderr)::

    nice -n 19 python benchmarks/gears_two_methods_by_tree.py benchmarks/logs/gears_two_methods_F1_n11.jsonl --dof 1 --links 11
    python benchmarks/gears_two_methods_by_tree.py /tmp/t.jsonl --dof 2 --links 8 --rotation --sample 20 --seed 1

A sample is compared in the order it was drawn, so a run stopped by Ctrl-C has compared a
random part of it; the summary then says how many trees that was.

``--record CSV`` runs nothing: it reads the log's latest summary of the size that covers every
tree of it with both methods agreeing (and with ``--rotation``, the two totals equal), and writes the
engine's counts so checked to the records table (``benchmarks/records.csv``, the other lines kept)::

    python benchmarks/gears_two_methods_by_tree.py benchmarks/logs/gears_two_methods_rotation_F1_n10.jsonl --dof 1 --links 10 --rotation --record benchmarks/records.csv

Exit status: 0 when every tree compared agrees, 1 when one does not, 2 for bad options, 130 on Ctrl-C (after the summary).
"""

from __future__ import annotations

import argparse
import json
import random
import resource
import signal
import subprocess
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


def compare_tree(dof: int, links: int, pair, rotation: bool, union: dict | None = None) -> dict:
    """Both counts of one tree, and the CPU seconds of each; with ``union`` (two sets, ``engine``
    and ``second``) each method's canonical forms of the tree's rotation graphs are added to it."""
    from synth.gears import tree_census
    from tests.oracles import gear_trains_fast

    k, axes, other = pair
    start = time.process_time()
    n, _, rotations = tree_census(dof, links, axes, rotation=rotation)
    middle = time.process_time()
    second = gear_trains_fast.tree_census(dof, links, other, rotation=rotation, keys=union is not None)
    end = time.process_time()
    if union is not None:
        union["engine"].update(rotations)
        union["second"].update(second["keys"])
    row = {"dof": dof, "links": links, "tree": k, "axes": [list(a) for a in axes], "engine": n,
           "second": second["displacement"], "engine_cpu": round(middle - start, 3), "second_cpu": round(end - middle, 3)}
    if rotation:
        row.update(engine_rotation=len(rotations), second_rotation=second["rotation"])
    return row


def record(log: Path, dof: int, links: int, rotation: bool, table: Path) -> list[dict]:
    """The records-table lines (benchmarks/records.py's columns) of the engine's counts that the log's
    latest summary of ``dof``/``links`` showing a whole check covers, written to ``table``; an error
    (:class:`ValueError`, one sentence) when the log shows no such check."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from records import COLUMNS, read_csv, write_csv

    if table.exists() and table.read_text().partition("\n")[0] != ",".join(COLUMNS):
        raise ValueError(f"{table} is not a records table (its first line is not the header {','.join(COLUMNS)})")
    try:
        rows = [json.loads(line) for line in log.read_text().splitlines()]
    except ValueError:
        raise ValueError(f"{log} is not a log of this script (a line is not JSON)") from None
    summaries = [r["summary"] for r in rows if "summary" in r and (r["summary"]["dof"], r["summary"]["links"]) == (dof, links)]
    if not summaries:
        raise ValueError(f"{log} has no summary of F = {dof}, {links} links: run the comparison first")

    def checked(done: dict) -> bool:  # every tree compared (a sample of every tree too) and agreeing
        whole = not done["interrupted"] and done["trees_agreeing"] == done["trees_compared"] == done["trees_of_the_size"]
        totals = done.get("engine_rotation_total")
        return whole and (not rotation or totals is not None and totals == done["second_rotation_total"])

    done = next((d for d in reversed(summaries) if checked(d)), None)
    if done is None:
        raise ValueError(f"no summary of {log} shows every tree compared and agreeing"
                         + (" with two equal totals of rotation graphs (run with --rotation on every tree at once)"
                            if rotation else "") + ": nothing to record")
    if "commit" in done:  # the engine's commit when the run started
        commit = [done["commit"], done["date"]]
    else:  # a summary of before 29 Nov 2026: the commit that brought the log (the engine is the same there)
        commit = subprocess.run(["git", "log", "-1", "--format=%h %cs", "--", str(log)], cwd=ROOT, capture_output=True,
                                text=True).stdout.split() or ["uncommitted", ""]
    shown = log.resolve().relative_to(ROOT) if log.resolve().is_relative_to(ROOT) else log
    method = (f"engine synth.gears.tree_census tree by tree in one process beside the second method, nice -n 19 on the "
              f"shared machine (CPU s: the engine's, {'both graphs' if done['rotation_compared'] else 'displacement graphs only'}; "
              f"the second method's {done['second_cpu_s']}; "
              f"peak MiB: both in one process)")
    base = {"published": "", "source": "", "by_code_file": str(shown), "wall_s": "", "cpu_s": done["engine_cpu_s"],
            "peak_mib": done["peak_mib"], "method": method, "commit": commit[0], "date": commit[-1]}
    lines = [dict(base, query=f"gears --dof {dof} --links {links}", count=done["trains_on_agreeing_trees"],
                  check=f"second method (tests/oracles/gear_trains_fast.py) tree by tree: all {done['trees_compared']} "
                        "trees agree")]
    if rotation:
        lines.append(dict(base, query=f"gears --dof {dof} --links {links} --graphs rotation", count=done["engine_rotation_total"],
                          check=f"second method: its bliss forms' union {done['second_rotation_total']} equals the "
                                f"engine's nauty forms' union; per tree, all {done['trees_compared']} trees agree"))
    table_lines = read_csv(table)
    table_lines.update((line["query"], line) for line in lines)
    write_csv(table, table_lines)
    return lines


def _commit() -> dict:
    """The commit of this checkout (``+changes`` when synth/ or tests/oracles/ differ from it) and today's date."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()

    dirty = git("status", "--porcelain", "--", "synth", "tests/oracles")
    return {"commit": git("rev-parse", "--short", "HEAD") + ("+changes" if dirty else ""),
            "date": time.strftime("%Y-%m-%d", time.gmtime())}


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
    parser.add_argument("--rotation", action="store_true", help="compare the numbers of rotation graphs per tree too, and (every tree run at once) each method's total")
    parser.add_argument("--record", type=Path, metavar="CSV",
                        help="run nothing: write the counts the log shows checked to this records table")
    args = parser.parse_args(argv)
    if not 1 <= args.dof <= 3 or not 4 <= args.links <= 12:
        parser.error("--dof takes 1 … 3 and --links 4 … 12")
    if (args.sample is None) != (args.seed is None):
        parser.error("--sample and --seed go together (a sample is drawn from its seed)")
    if args.sample is not None and args.sample < 1:
        parser.error("--sample takes a positive number of trees")
    if args.record is not None:
        if args.sample is not None:
            parser.error("--record writes the count of every tree: a sample is not one (leave out --sample)")
        if not args.log.is_file():
            parser.error(f"cannot read the log {args.log}: no such file")
        if args.record.is_dir() or not args.record.parent.is_dir():
            parser.error(f"cannot write the records table {args.record}: not a file in an existing folder")
        try:
            for line in record(args.log, args.dof, args.links, args.rotation, args.record):
                print(json.dumps(line))
        except ValueError as error:
            parser.error(str(error))
        except (KeyError, TypeError):
            parser.error(f"{args.log} is not a log of this script (a summary lacks its fields)")
        return 0
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
    whole = args.rotation and len(todo) == len(pairs)  # every tree run here: each method's union is the size's count
    union = {"engine": set(), "second": set()} if whole else None
    wall, cpu = time.perf_counter(), time.process_time()
    commit = _commit()
    print(f"F={args.dof}, {args.links} links: {len(chosen)} of {len(pairs)} trees, {len(chosen) - len(todo)} in the log",
          file=sys.stderr)
    try:
        with open(args.log, "a") as out:
            for i, pair in enumerate(todo, 1):
                row = compare_tree(args.dof, args.links, pair, args.rotation, union)
                out.write(json.dumps(row) + "\n")
                out.flush()
                done[row["tree"]] = row
                if not _agrees(row):
                    print(f"\ntree {row['tree']} {row['axes']}: engine {row['engine']}, second method {row['second']}",
                          file=sys.stderr)
                print(f"\r[{'#' * (30 * i // len(todo)):<30}] {i}/{len(todo)} trees", end="", file=sys.stderr, flush=True)
    except KeyboardInterrupt:
        interrupted = True
    else:
        interrupted = False
    rows = [done[p[0]] for p in chosen if p[0] in done]
    seconds = {"this_run_cpu_s": round(time.process_time() - cpu, 1), "this_run_wall_s": round(time.perf_counter() - wall, 1),
               "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024,
               "sample": args.sample, "seed": args.seed, "interrupted": interrupted, **commit}
    if args.rotation:
        complete = union is not None and not interrupted
        seconds.update(engine_rotation_total=len(union["engine"]) if complete else None,
                       second_rotation_total=len(union["second"]) if complete else None)
    result = {"summary": {"dof": args.dof, "links": args.links, **summary(rows, len(pairs), seconds)}}
    with open(args.log, "a") as out:
        out.write(json.dumps(result) + "\n")
    print(file=sys.stderr)
    print(json.dumps(result))
    if interrupted:
        print("interrupted: the trees compared so far are in the log and in the summary above", file=sys.stderr)
        return 130
    totals_agree = result["summary"].get("engine_rotation_total") == result["summary"].get("second_rotation_total")
    return 0 if result["summary"]["trees_agreeing"] == len(rows) and totals_agree else 1


if __name__ == "__main__":
    raise SystemExit(main())
