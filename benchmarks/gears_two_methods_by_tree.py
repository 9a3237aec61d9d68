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
forms (nauty for the engine, bliss for the second method) — once every tree of the size has
been compared (``null`` after a sample).  The forms are kept on disk, in the SQLite file
``LOG.forms.sqlite`` beside the log (each tree's forms and the tree's number in one transaction,
before its line is written to the log), so a run killed and started again loses no tree and still
gives both unions; a tree in the log but not in that file (its forms lost) is run again.  A run
holds a lock on its log: a second run on the same log, while the first is alive, is refused.
Each line also says the commit and the niceness the run had.

Run from the project root (one process; a progress bar on stderr, or a line a minute when it is a file)::

    nice -n 19 python benchmarks/gears_two_methods_by_tree.py benchmarks/logs/gears_two_methods_F1_n11.jsonl --dof 1 --links 11
    python benchmarks/gears_two_methods_by_tree.py /tmp/t.jsonl --dof 2 --links 8 --rotation --sample 20 --seed 1

A sample is compared in the order it was drawn, so a run stopped by Ctrl-C has compared a
random part of it; the summary then says how many trees that was.  A sample of more trees than the
size has is refused (``--sample`` equal to their number compares every tree in a random order).

The progress reckons the time to go by the trees' sizes, not by trees alike: a tree's size is its
pairs of links on a common axis (:func:`tree_size`), which a tree's CPU follows (benchmarks/GEARS.md).

``--record CSV`` runs nothing: it reads the log's latest summary of the size that covers every
tree of it with both methods agreeing (and with ``--rotation``, the two totals equal), and writes the
engine's counts so checked to the records table (``benchmarks/records.csv``, the other lines kept)::

    python benchmarks/gears_two_methods_by_tree.py benchmarks/logs/gears_two_methods_rotation_F1_n10.jsonl --dof 1 --links 10 --rotation --record benchmarks/records.csv

Exit status: 0 when every tree compared agrees, 1 when one does not, 2 for bad options, 130 on Ctrl-C (after the summary).
"""

from __future__ import annotations

import argparse
import fcntl
import json
import os
import random
import resource
import signal
import sqlite3
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


def tree_size(axes) -> int:
    """The pairs of links on a common axis of a link–axis tree: the measure of its size by which the
    progress reckons the time to go (a tree with few, crowded axes holds more trains and takes longer).

    >>> tree_size([[0, 1, 2], [0, 3]]), tree_size([[0, 1], [1, 2], [2, 3]])
    (4, 3)
    """
    return sum(len(axis) * (len(axis) - 1) // 2 for axis in axes)


def compare_tree(dof: int, links: int, pair, rotation: bool, forms: dict | None = None) -> dict:
    """Both counts of one tree, and the CPU seconds of each; with ``forms`` (two sets, ``engine``
    and ``second``) each method's canonical forms of the tree's rotation graphs are added to it."""
    from synth.gears import tree_census
    from tests.oracles import gear_trains_fast

    k, axes, other = pair
    start = time.process_time()
    n, _, rotations = tree_census(dof, links, axes, rotation=rotation)
    middle = time.process_time()
    second = gear_trains_fast.tree_census(dof, links, other, rotation=rotation, keys=forms is not None)
    end = time.process_time()
    if forms is not None:
        forms["engine"].update(rotations)
        forms["second"].update(second["keys"])
    row = {"dof": dof, "links": links, "tree": k, "axes": [list(a) for a in axes], "engine": n,
           "second": second["displacement"], "engine_cpu": round(middle - start, 3), "second_cpu": round(end - middle, 3)}
    if rotation:
        row.update(engine_rotation=len(rotations), second_rotation=second["rotation"])
    return row


class FormStore:
    """Each method's canonical forms of the rotation graphs met so far on the trees of one size,
    and the trees whose forms are all in: an SQLite file, so that the unions survive a killed run.

    A tree's forms and its number go in together (one transaction), so the file never holds half a
    tree.  Opening a file of another size or mobility is an error (:class:`ValueError`).

    Example
    -------
    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "forms.sqlite"
    >>> with FormStore(path, 2, 7) as store:
    ...     store.add(3, {"engine": {b"ab", b"cd"}, "second": {b"xy"}})
    ...     store.add(5, {"engine": {b"ab"}, "second": {b"zz"}})
    >>> with FormStore(path, 2, 7) as store:
    ...     sorted(store.trees()), store.totals()
    ([3, 5], {'engine': 2, 'second': 2})
    """

    METHODS = ("engine", "second")

    def __init__(self, path: Path, dof: int, links: int):
        self.path = path
        try:
            self.db = sqlite3.connect(path)
        except sqlite3.Error:  # a folder, or a folder that is gone
            raise ValueError(f"cannot open {path} as the store of rotation-graph forms (a folder, or not writable)") from None
        try:
            self.db.executescript(
                "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;"
                "CREATE TABLE IF NOT EXISTS size (dof INTEGER, links INTEGER);"
                "CREATE TABLE IF NOT EXISTS forms (method INTEGER, form BLOB, PRIMARY KEY (method, form)) WITHOUT ROWID;"
                "CREATE TABLE IF NOT EXISTS trees (tree INTEGER PRIMARY KEY);")
            size = self.db.execute("SELECT dof, links FROM size").fetchall()
        except sqlite3.DatabaseError:
            self.db.close()
            raise ValueError(f"{path} is not a store of rotation-graph forms (not an SQLite file of this script)") from None
        if not size:
            with self.db:
                self.db.execute("INSERT INTO size VALUES (?, ?)", (dof, links))
        elif size[0] != (dof, links):
            self.db.close()
            raise ValueError(f"{path} holds the forms of F = {size[0][0]}, {size[0][1]} links, not of F = {dof}, "
                             f"{links} links: give the log of that size or a new log")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.db.close()

    def add(self, tree: int, forms: dict) -> None:
        """Put one tree's forms (a set of bytes a method) and its number in, at once."""
        with self.db:
            for m, method in enumerate(self.METHODS):
                self.db.executemany("INSERT OR IGNORE INTO forms VALUES (?, ?)", ((m, f) for f in forms[method]))
            self.db.execute("INSERT OR IGNORE INTO trees VALUES (?)", (tree,))

    def trees(self) -> set[int]:
        """The trees whose forms are in."""
        return {t for (t,) in self.db.execute("SELECT tree FROM trees")}

    def totals(self) -> dict:
        """The size of each method's union of forms."""
        return {method: self.db.execute("SELECT COUNT(*) FROM forms WHERE method = ?", (m,)).fetchone()[0]
                for m, method in enumerate(self.METHODS)}


ROW_FIELDS = ("engine", "second", "engine_cpu", "second_cpu")  # what every tree's line of a log holds


def read_log(log: Path) -> list[dict]:
    """The lines of a log of this script, each a JSON object; an error (:class:`ValueError`, one
    sentence) when the file is not such a log: not text, a line not a JSON object, or a tree's line
    (one with ``tree``) without its counts and times.

    Example
    -------
    >>> import tempfile
    >>> log = Path(tempfile.mkdtemp()) / "log.jsonl"
    >>> _ = log.write_text('{"dof": 2, "links": 6, "tree": 0, "engine": 1, "second": 1, "engine_cpu": 0.1, "second_cpu": 0.2}\\n')
    >>> [row["engine"] for row in read_log(log)]
    [1]
    >>> _ = log.write_text('{"dof": 2, "links": 6, "tree": 0}\\n')
    >>> read_log(log)
    Traceback (most recent call last):
    ValueError: ... is not a log of this script (the line of tree 0 lacks its counts and times)
    """
    try:
        text = log.read_text()
    except UnicodeDecodeError:
        raise ValueError(f"{log} is not a log of this script (not text)") from None
    except OSError as error:
        raise ValueError(f"cannot read the log {log}: {error.strerror}") from None
    rows = []
    for line in text.splitlines():
        try:
            row = json.loads(line)
        except ValueError:
            raise ValueError(f"{log} is not a log of this script (a line is not JSON)") from None
        if not isinstance(row, dict):
            raise ValueError(f"{log} is not a log of this script (a line is not a JSON object)")
        if "tree" in row and (not isinstance(row["tree"], int) or not all(isinstance(row.get(k), (int, float)) for k in ROW_FIELDS)):
            raise ValueError(f"{log} is not a log of this script (the line of tree {row['tree']} lacks its counts and times)")
        rows.append(row)
    return rows


def record(log: Path, dof: int, links: int, rotation: bool, table: Path) -> list[dict]:
    """The records-table lines (benchmarks/records.py's columns) of the engine's counts that the log's
    latest summary of ``dof``/``links`` showing a whole check covers, written to ``table``; an error
    (:class:`ValueError`, one sentence) when the log shows no such check."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from records import COLUMNS, read_csv, write_csv

    if table.exists() and table.read_text().partition("\n")[0] != ",".join(COLUMNS):
        raise ValueError(f"{table} is not a records table (its first line is not the header {','.join(COLUMNS)})")
    rows = read_log(log)
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
                         + (" with two equal totals of rotation graphs (run with --rotation until every tree is compared)"
                            if rotation else "") + ": nothing to record")
    if "commit" in done:  # the engine's commits of the runs that compared the trees (a killed run leaves no summary: its rows say)
        upto = [r.get("summary", r) for r in rows[:rows.index({"summary": done}) + 1]]
        ours = [r for r in upto if (r.get("dof"), r.get("links")) == (dof, links)]  # its rows and summaries
        commit = [" ".join(dict.fromkeys(r["commit"] for r in ours if "commit" in r)), done["date"]]
        done = dict(done, peak_mib=max(r.get("peak_mib", 0) for r in ours))
        levels = sorted({r["nice"] for r in ours if "nice" in r})
        unlogged = any("tree" in r and "nice" not in r for r in ours)
        where = (f"at nice {' and '.join(map(str, levels))}{' (the first runs: not logged)' if unlogged else ''}"
                 if levels else "niced") + " on the shared machine"
    else:  # a summary of before 29 Nov 2026: the commit that brought the log (the engine is the same there)
        commit = subprocess.run(["git", "log", "-1", "--format=%h %cs", "--", str(log)], cwd=ROOT, capture_output=True,
                                text=True).stdout.split() or ["uncommitted", ""]
        where = "niced on the shared machine"
    shown = log.resolve().relative_to(ROOT) if log.resolve().is_relative_to(ROOT) else log
    method = (f"engine synth.gears.tree_census tree by tree beside the second method in one process at a time (runs resumed "
              f"from the log add up), {where} (CPU s: the engine's, "
              f"{'both graphs' if done['rotation_compared'] else 'displacement graphs only'}; "
              f"the second method's {done['second_cpu_s']}; peak MiB: both in one process, the largest of the runs)")
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
    """The commit of this checkout (``+changes`` when synth/ or tests/oracles/ differ from it), today's date and
    the niceness this process runs at."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()

    dirty = git("status", "--porcelain", "--", "synth", "tests/oracles")
    return {"commit": git("rev-parse", "--short", "HEAD") + ("+changes" if dirty else ""),
            "date": time.strftime("%Y-%m-%d", time.gmtime()), "nice": os.nice(0)}


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


EPILOG = """examples (from the project root):
  python benchmarks/gears_two_methods_by_tree.py /tmp/f2n8.jsonl --dof 2 --links 8 --rotation
      every 8-link tree of F = 2 by both methods; the same command again resumes a run stopped
      by Ctrl-C or killed, comparing only the trees not in the log
  python benchmarks/gears_two_methods_by_tree.py /tmp/s.jsonl --dof 1 --links 9 --sample 20 --seed 1
      20 trees drawn at random
  python benchmarks/gears_two_methods_by_tree.py /tmp/f2n8.jsonl --dof 2 --links 8 --rotation --record /tmp/records.csv
      write the counts of a finished run to a records table (the project's: benchmarks/records.csv)

One run a log at a time (a second is refused). Exit status: 0 every tree compared agrees,
1 one does not, 2 bad options, 130 Ctrl-C (the summary written first)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        """One sentence on stderr and exit status 2 (no usage block)."""
        print(f"gears_two_methods_by_tree: {message}", file=sys.stderr)
        raise SystemExit(2)


def main(argv=None) -> int:
    parser = _Parser(description=__doc__.splitlines()[0], epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log", type=Path, help="JSON lines, appended to (a run goes on where the log stops; with "
                        "--rotation the forms are kept in LOG.forms.sqlite beside it)")
    parser.add_argument("--dof", type=int, required=True, help="mobility F (1 … 3)")
    parser.add_argument("--links", type=int, required=True, help="number of links (4 … 12)")
    parser.add_argument("--sample", type=int, help="compare this many trees drawn at random (default: every tree)")
    parser.add_argument("--seed", type=int, help="seed of the sample (required with --sample)")
    parser.add_argument("--rotation", action="store_true", help="compare the numbers of rotation graphs per tree too, and, once every tree is compared, each method's total")
    parser.add_argument("--record", type=Path, metavar="CSV",
                        help="run nothing: write the counts the log shows checked to this records table")
    args = parser.parse_args(argv)
    if not 1 <= args.dof <= 3 or not 4 <= args.links <= 12:
        parser.error("--dof takes 1 … 3 and --links 4 … 12")
    if (args.sample is None) != (args.seed is None):
        parser.error("--sample and --seed go together (a sample is drawn from its seed)")
    if args.sample is not None and args.sample < 1:
        parser.error("--sample takes a positive number of trees")
    if args.record is None and args.sample is not None:
        from synth.gears.enumeration import link_axis_trees

        if args.sample > (trees := len(link_axis_trees(args.links))):
            parser.error(f"--sample {args.sample} is more than the {trees} trees of {args.links} links: leave out --sample "
                         f"and --seed to compare every tree, or give --sample {trees} to compare them in a random order")
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
    created = not args.log.exists()
    out = open(args.log, "a")  # (a log that exists is not changed before the checks below pass)
    try:  # one run a log: a second one would compare the same trees again beside the first
        fcntl.flock(out, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        parser.error(f"another run is writing the log {args.log}: let it end (or stop it by Ctrl-C), then start this "
                     "one again, which goes on where it stopped")
    try:
        done = {row["tree"]: row for row in read_log(args.log)
                if row.get("dof") == args.dof and row.get("links") == args.links and "tree" in row
                and ("engine_rotation" in row or not args.rotation)}
    except ValueError as error:
        parser.error(f"{error}; give a new file or a log of this script")
    store = None
    if args.rotation:  # the forms of the trees done, kept for the unions
        try:
            store = FormStore(args.log.with_name(args.log.name + ".forms.sqlite"), args.dof, args.links)
        except ValueError as error:
            if created:
                args.log.unlink()
            parser.error(str(error))
        stored = store.trees()
        done = {k: row for k, row in done.items() if k in stored}  # a tree whose forms were lost is run again
    signal.signal(signal.SIGINT, signal.default_int_handler)  # Ctrl-C stops even a run started in the background
    try:
        pairs = paired_trees(args.links)
    except KeyboardInterrupt:
        print("gears_two_methods_by_tree: interrupted before any tree was compared", file=sys.stderr)
        return 130
    # a sample in its drawn order: a run stopped early has compared a random part of it
    chosen = pairs if args.sample is None else random.Random(args.seed).sample(pairs, args.sample)
    todo = [p for p in chosen if p[0] not in done]
    wall, cpu = time.perf_counter(), time.process_time()
    commit = _commit()
    print(f"F={args.dof}, {args.links} links: {len(chosen)} of {len(pairs)} trees, {len(chosen) - len(todo)} in the log"
          + (f" (rotation-graph forms in {store.path})" if store else ""), file=sys.stderr)
    from synth import Progress

    try:  # a bar on a terminal, a line a minute in a log; its steps are the trees' sizes, so is its time to go
        with Progress(sum(tree_size(p[1]) for p in todo), "size (link pairs on an axis)", desc="gears_two_methods_by_tree") as progress:
            for pair in todo:
                forms = {"engine": set(), "second": set()} if store else None
                row = compare_tree(args.dof, args.links, pair, args.rotation, forms)
                if store:
                    store.add(row["tree"], forms)  # the forms first: a tree in the log has its forms kept
                # which engine, and the memory so far: what a run killed before its summary leaves to record
                row.update(commit=commit["commit"], nice=commit["nice"], peak_mib=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024)
                out.write(json.dumps(row) + "\n")
                out.flush()
                done[row["tree"]] = row
                if not _agrees(row):
                    progress.write(f"tree {row['tree']} {row['axes']}: engine {row['engine']}, "
                                   f"second method {row['second']}")
                progress.update(tree_size(pair[1]), trees=1, disagreeing=not _agrees(row))
    except KeyboardInterrupt:
        interrupted = True
    else:
        interrupted = False
    rows = [done[p[0]] for p in chosen if p[0] in done]
    seconds = {"this_run_cpu_s": round(time.process_time() - cpu, 1), "this_run_wall_s": round(time.perf_counter() - wall, 1),
               "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024,
               "sample": args.sample, "seed": args.seed, "interrupted": interrupted, **commit}
    if store:  # each method's union is the size's count once every tree's forms are in
        complete = store.trees() >= {p[0] for p in pairs}
        totals = store.totals() if complete else {}
        store.db.close()
        seconds.update(engine_rotation_total=totals.get("engine"), second_rotation_total=totals.get("second"))
    result = {"summary": {"dof": args.dof, "links": args.links, **summary(rows, len(pairs), seconds)}}
    out.write(json.dumps(result) + "\n")
    out.close()
    print(json.dumps(result))
    if interrupted:
        print("interrupted: the trees compared so far are in the log and in the summary above", file=sys.stderr)
        return 130
    totals_agree = result["summary"].get("engine_rotation_total") == result["summary"].get("second_rotation_total")
    return 0 if result["summary"]["trees_agreeing"] == len(rows) and totals_agree else 1


if __name__ == "__main__":
    raise SystemExit(main())
