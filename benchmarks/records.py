"""Every published count of chains reproduced, and one step beyond, as data (issue 41, items 2–3).

Each row of :data:`ROWS` is one count query of the command line, ``mechsynth chains … --count
--workers 2``, run in a fresh process with the store of solver results off (``MECHSYNTH_CACHE=off``:
every count is computed, none read back).  For each the script measures the wall time, the CPU
time of the command and its workers, and the peak resident memory of all of them together
(sampled every 0.2 s), writes the counts by code to ``benchmarks/records/<query>.json`` and a row
to ``benchmarks/records.csv``, and checks the count by whatever independent means the row has:

* ``published``: the count equals the published value of the row's source;
* ``oracle``: the counts by code equal those of the brute force of ``tests/oracles/chains.py``
  (no engine code: labelled search, networkx isomorphism; small sizes only);
* ``listing``: the counts by code equal those of the listing path, which builds every chain and
  tells chains apart by their nauty certificates (queries up to ``LIST_MAX`` chains);
* ``kernels off`` (multiple joints only): the counts by code equal those of the engine with its compiled
  kernels off (:func:`kernels_off_by_code`; up to ``--second-max`` chains, or every ``--second-every``-th
  code, a sample).  The count's search with multiple joints runs the stage-B kernel with the exact test's
  sets checked inside it; this check shares neither, nor the listing's kernel;
* ``listing`` of a larger count's small codes (``--list-codes-max N``): each code of at most N chains
  listed on its own and compared, the others not checked by this means;
* ``tight-reverse`` (no multiple joints, counts the listing does not check, up to ``--reverse-max``): the
  counts by code equal those of the same command with ``--method tight-reverse``, the second count of a
  record (another programme over the strings, another reading of the automorphisms; units that are not
  tight are counted by orbits), at about the cost of the count;
* ``orbits`` (multiple joints, the same bound ``--reverse-max``): the counts by code equal those of the same
  command with ``--method orbits`` (Burnside over the bundles of parallel strings, each pattern decided once by
  the exact test; not the count's lex-least search), at about 1.2 times its cost.

A row with none of them says ``none``.  The table of the section "Published counts" of
``benchmarks/RECORDS.md`` is then written from the whole CSV (other sections of that file are left
as they are), with the rows not run and why, and the figure ``benchmarks/records_growth.png`` (chains
against links, one line per series, published values ringed) is drawn again from the whole CSV.

Run from the project root (a long row prints the command's own progress bar)::

    nice -n 19 python benchmarks/records.py                  # every row but the heavy ones
    nice -n 19 python benchmarks/records.py --only "dof 3 --links 18"   # one row, heavy or not
    nice -n 10 python benchmarks/records.py --only "links 14 --v 0..12" --recheck --list-max 0 --reverse-max 0 \
        --second-max 100000000 --second-every 10      # a recorded count checked again on a sample of codes
    python benchmarks/records.py --quick --csv /tmp/r.csv --md /tmp/R.md --by-code /tmp/r
    python benchmarks/records.py --size --only "dof 3 --links"   # the engine's sizing of rows, beside the records
    python benchmarks/records.py --only "links 32 --h 6" --recheck --reverse-from reverse.json  # a second count
        # run beside the first (`mechsynth chains --dof 1 --links 32 --h 6 --count --method tight-reverse > reverse.json`)

Rows already in the CSV are run again only when asked by ``--only`` (or ``--again``); the others
keep their line.  Exit status: 0 when every row run passed its checks, 1 when ``--only`` matched no
row or a check failed, 2 for bad options, 130 on Ctrl-C; a ``kill`` (SIGTERM, SIGHUP) stops it as Ctrl-C does
(the count running stopped, its temporary folder removed), then ends it by that signal.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import resource
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from benchmarks._out import refusals  # noqa: E402

LIST_MAX = 400_000  # the listing path checks a count up to this many chains by default (14 links: 21 CPU s)
# … and the second count (--method tight-reverse, about the cost of the count) checks larger ones up to this many
REVERSE_MAX = 10**10
COLUMNS = ["query", "count", "published", "source", "check", "by_code_file", "wall_s", "cpu_s", "peak_mib",
           "method", "commit", "date"]
SECTION = "## Published counts"
SECTIONS = [SECTION, "## 20-link chains: the counting path", "## Gear trains"]

SOURCES = {  # the keys of docs/theory.md, "Sources"
    "A233288": "OEIS A233288 (https://oeis.org/A233288): 12 and 14 links also Butcher & Hartman 2005, 16 links "
               "Sunkari & Schmidt 2006, 18 links M. Larsson (added 2025)",
    "T": "L.-W. Tsai, Mechanism Design (2001): the atlases of 2- and 3-DOF chains",
    "JMD2024": "J. Mech. Des. 146(11) 113302 (2024) counts 2- and 3-DOF chains to 7 loops as biconnected graphs "
               "(so its counts go beside the not-fractionated rows), by link partition from 6 loops on; only its "
               "abstract could be read here (benchmarks/LITERATURE.md, counts), so no value of it is quoted",
    "A227117": "OEIS A227117 (https://oeis.org/A227117): Laman graphs on n vertices, the 1-DOF chains of n links "
               "in h = 2",
    "Ding2013": "H. Ding et al., J. Mech. Des. 135(9) 091007 (2013): multiple-joint chains to 16 links, every DOF; "
                "only its abstract could be read here, so no value of it is quoted (whether its families include "
                "the chains of simple joints and sum the DOF: benchmarks/LITERATURE.md, counts)",
}


@dataclass(frozen=True)
class Row:
    """One count query: its command-line options, the published value and its source."""

    series: str
    options: tuple[str, ...]
    published: int | None = None
    source: str = ""
    quick: bool = False
    oracle: bool = False  # the brute force finishes in seconds
    heavy: str = ""  # not run unless asked by --only: why, with the engine's estimate

    @property
    def query(self) -> str:
        return "chains " + " ".join(self.options)

    @property
    def slug(self) -> str:
        return "_".join(o.lstrip("-").replace("..", "-") for o in self.options)

    def option(self, name: str, default=None):
        return self.options[self.options.index(name) + 1] if name in self.options else default


def _row(series, dof, links, published=None, source="", *, h=None, v=None, frac=True, quick=False, oracle=False,
         heavy=""):
    options = ["--dof", str(dof), "--links", str(links)]
    if h is not None:
        options += ["--h", str(h)]
    if v is not None:  # up to v (an int), or exactly as written (a str: "1" = one ternary joint)
        options += ["--v", v if isinstance(v, str) else f"0..{v}"]
    if not frac:
        options += ["--no-fractionated"]
    return Row(series, tuple(options), published, source, quick, oracle, heavy)


_A233288 = {4: 1, 6: 2, 8: 16, 10: 230, 12: 6856, 14: 318162, 16: 19819281, 18: 1535380884}
_A227117 = {3: 1, 4: 1, 5: 3, 6: 13, 7: 70, 8: 608, 9: 7222, 10: 110132, 11: 2039273, 12: 44176717}
_TSAI = {(2, True): {5: 1, 7: 4, 9: 40}, (2, False): {5: 1, 7: 3, 9: 35},
         (3, True): {6: 1, 8: 7, 10: 98}, (3, False): {6: 1, 8: 5, 10: 74}}

# h = 4 … 6 beyond 20 links, as sized on 29 Nov 2026 at a98900f (`records.py --size`, UNIT_GROWTH for h = 4, 5, 6:
# PROFILE.md section 33), each count to be checked by its second count (--method tight-reverse) at about its cost;
# their memory is bounded since a98900f (stage B's layers within a budget of 256 MiB a process: PROFILE.md section 36;
# at most 4/3 of it with the copies since bbe428f, a count on 2 workers within 2 GiB: section 40)
_SIZED_H = "the engine's sizing (`records.py --size`, a98900f, 29 Nov 2026) gives about {} chains, {} CPU s for the " \
           "count and about as much again for its second count (--method tight-reverse)"
_BEYOND = {
    (4, 23): "run on its own (--only): sized at 13 CPU s (3.6e9 chains), counted in 90 CPU s and 1.5 GiB on 29 Nov "
             "2026, and as much again for its second count (0.74 GiB since a98900f)",
    (4, 26): "run on its own (--only): sized at 1 990 CPU s (7.9e11 chains); counted on 30 Nov 2026 (64d25a8) in "
             "2 206 CPU s, 1 131 s wall and 1.6 GiB, and checked by `--recheck --reverse-from "
             "benchmarks/logs/count_h4_26_links_tight_reverse.json`, its second count (tight-reverse, 947 CPU s)",
    (5, 30): "run on its own (--only): sized at 481 CPU s (2.1e11 chains); counted on 30 Nov 2026 (bbe428f) in 818 "
             "CPU s and 1.1 GiB, past the units of cubic graphs on 12 branch links where runs at 4085be8, 1889f2d and "
             "2c5940b had been stopped (PROFILE.md sections 38, 40), and checked by `--recheck --reverse-from "
             "benchmarks/logs/count_h5_30_links_tight_reverse.json`, its second count (tight-reverse, 446 CPU s)",
    (6, 32): "run on its own (--only): sized at 36 CPU s (5.6e9 chains), counted in 137 CPU s and 879 MiB on 30 Nov "
             "2026 (bbe428f; 2 165 MiB at 892d43e, before stage B's layers were held within 4/3 of their budget: "
             "PROFILE.md section 40), checked by `--recheck --reverse-from "
             "benchmarks/logs/count_h6_32_links_tight_reverse.json`, its second count (tight-reverse, 98 CPU s)",
}

# the next size of each motion space past the last counted, sized on 30 Nov 2026 at 1cc856c (`estimate(ChainQuery.of(
# dof=1, links=N, h=H))`, 1.2-1.7 CPU s each) and not run: the sizing was 10-41 % under the CPU of the last counts at
# h = 4 and 5, and 3.8 times under at h = 6, 32 links (sized at 36 CPU s, counted in 137)
_NEXT_SIZE = "not run: the next size past the last counted, sized on 30 Nov 2026 (1cc856c) at about {} chains and {} " \
             "CPU s for the count, and as much again for its second count: {}"
_NEXT = [("h = 2 (Laman)", 2, 13, ("1.1e9", "16 700", "beyond an hour of the 2 cores")),
         ("h = 4", 4, 29, ("2.1e14", "93 500", "beyond an hour of the 2 cores")),
         ("h = 5", 5, 34, ("9.6e13", "29 300", "beyond an hour of the 2 cores")),
         ("h = 6", 6, 37, ("3.2e12", "1 790", "about 6 800 with the sizing's miss at 32 links, an hour of the 2 cores "
                                             "for the count alone, and its memory not sized"))]

# 7 and 8 loops without fractionated chains: the 2024 paper enumerates biconnected graphs, so its 7-loop counts go
# beside these rows, not beside the rows with fractionated chains (benchmarks/LITERATURE.md, the second search for
# counts); 8 loops is one beyond it
_NOT_FRACTIONATED = "run on its own (--only): {} loops without fractionated chains, with its second count " \
                    "(--method tight-reverse) by code; the row with fractionated chains took {} CPU s"

ROWS = (
    [_row("W = 1", 1, n, _A233288[n], "A233288", quick=n <= 6, oracle=n <= 8) for n in range(4, 17, 2)]
    + [_row("W = 1", 1, 18, _A233288[18], "A233288",
            heavy="not run by this script: counted by hand on 29 Nov 2026 (c280dda), the published value in "
                  "1 min 36 s wall on 2 workers of a quiet machine, 186.5 user CPU s, the same 105 codes as the "
                  "runs of 26 Nov and of the morning (benchmarks/logs/count_18_links_c280dda.txt)")]
    + [_row("W = 1", 1, 20, None, "",
            heavy="run by hand, twice, with checkpoints (section '20-link chains' below)")]
    + [_row("W = 2", 2, n, _TSAI[2, True].get(n), "T" if n <= 9 else "JMD2024", quick=n == 5, oracle=n <= 7)
       for n in range(5, 16, 2)]
    + [_row("W = 2", 2, 17, None, "JMD2024",
            heavy="run on its own (--only): 7 loops; counted without visiting (PROFILE.md section 37) on 29 Nov 2026 "
                  "(39aec68) in 14.3 CPU s, sized at 14.4 (`records.py --size`), its second count (--method "
                  "tight-reverse) 19.4 CPU s, equal by code")]
    + [_row("W = 2", 2, 19, None, "",
            heavy="run on its own (--only): 8 loops; since every unit is counted without visiting (853192f, "
                  "PROFILE.md section 37) the engine's sizing (`records.py --size`) gives about 8.4e9 chains, 394 CPU s "
                  "(it sized 17 links at 17.4 CPU s); the second count by tight-reverse costs about as much")]
    + [_row("W = 2, not fractionated", 2, n, _TSAI[2, False].get(n), "T" if n <= 9 else "JMD2024", frac=False,
            oracle=n <= 7) for n in range(5, 16, 2)]
    + [_row("W = 2, not fractionated", 2, 17, None, "JMD2024", frac=False, heavy=_NOT_FRACTIONATED.format(7, 14.3))]
    + [_row("W = 2, not fractionated", 2, 19, None, "", frac=False, heavy=_NOT_FRACTIONATED.format(8, 372))]
    + [_row("W = 3", 3, n, _TSAI[3, True].get(n), "T" if n <= 10 else "JMD2024", quick=n == 6, oracle=n <= 8)
       for n in range(6, 17, 2)]
    + [_row("W = 3", 3, 18, None, "JMD2024",
            heavy="run on its own (--only): 7 loops; counted without visiting (PROFILE.md section 37) on 29 Nov 2026 "
                  "(1b08d31) in 31.8 CPU s, sized at 20.3 (`records.py --size`), its second count (--method "
                  "tight-reverse) 32.0 CPU s, equal by code")]
    + [_row("W = 3", 3, 20, None, "",
            heavy="run on its own (--only): 8 loops; counted on 29 Nov 2026 (82b1d25) in 626 CPU s, sized at 426 "
                  "(PROFILE.md section 37), and its second count (--method tight-reverse, 468 CPU s, beside it: "
                  "`--recheck --reverse-from`) equal by code (benchmarks/logs/count_w3_20_links.txt)")]
    + [_row("W = 3, not fractionated", 3, n, _TSAI[3, False].get(n), "T" if n <= 10 else "JMD2024", frac=False,
            oracle=n <= 8) for n in range(6, 17, 2)]
    + [_row("W = 3, not fractionated", 3, 18, None, "JMD2024", frac=False, heavy=_NOT_FRACTIONATED.format(7, 31.8))]
    + [_row("W = 3, not fractionated", 3, 20, None, "", frac=False,
            heavy=_NOT_FRACTIONATED.format(8, 626).replace(" by code", " by code, run after it beside no other count and "
                                                           "compared by `--recheck --reverse-from` "
                                                           "benchmarks/logs/count_w3_20_links_no_fractionated_"
                                                           "tight_reverse.json (past --reverse-max)"))]
    + [_row("h = 2 (Laman)", 1, n, _A227117[n], "A227117", h=2, oracle=n <= 7) for n in range(3, 12)]
    + [_row("h = 2 (Laman)", 1, 12, _A227117[12], "A227117", h=2,
            heavy="run by hand with a checkpoint on 29 Nov 2026: 19.5 min wall on 2 workers beside other work, 29 CPU "
                  "min (benchmarks/logs/count_h2_12_links.txt)")]
    + [_row("h = 4", 1, n, h=4, oracle=n <= 8, heavy=_BEYOND.get((4, n), "")) for n in range(5, 27, 3)]
    + [_row("h = 5", 1, n, h=5, oracle=n <= 6, heavy=_BEYOND.get((5, n), "")) for n in range(6, 31, 4)]
    + [_row("h = 6", 1, n, h=6, oracle=n <= 7, heavy=_BEYOND.get((6, n), "")) for n in range(7, 33, 5)]
    + [_row(series, 1, n, h=h, heavy=_NEXT_SIZE.format(*sized)) for series, h, n, sized in _NEXT]
    + [_row("W = 1, multiple joints", 1, n, None, "Ding2013", v=n - 2, oracle=n <= 8) for n in range(4, 13, 2)]
    + [_row("W = 1, multiple joints", 1, 14, None, "Ding2013", v=12,
            heavy="run on its own (--only): 10 CPU min on 2 workers (PROFILE.md section 28)")]
    + [_row("W = 1, multiple joints", 1, 16, None, "Ding2013", v=14,
            heavy="run by hand with a checkpoint in five parts on 30 Nov 2026 (RECORDS.md, 'Every multiple-joint "
                  "chain of 16 links'), its second count (--method tight-reverse) by hand beside it, equal on every "
                  "code; the engine's sizing from 8, 10, 12 links said about 6.9e9 chains in "
                  "8.5e6 units (6.7e9 in 9.8e6 counted)")]
    + [_row("W = 1, multiple joints", 1, 18, None, "Ding2013", v=16,
            heavy="not run: sized on 30 Nov 2026 (f30f3a8; `estimate(ChainQuery.of(dof=1, links=18, v=(0, 16)))`, "
                  "basis 8, 10, 12 links, 5.1 CPU s) at about 1.7e12 chains in 4.2e8 units and 416 000 CPU s; at the "
                  "16-link counts' 0.92 and 1.30 CPU ms a unit (the sizing was 13 % under on units there) the count and "
                  "its second count would take about 108 and 153 CPU hours, some 5 days of both cores: out of reach "
                  "here (RECORDS.md, 'Every multiple-joint chain of 16 links')")]
    # exactly one ternary joint (--v 1): a family of multiple-joint chains that reaches 16 links on 2 cores
    + [_row("W = 1, one ternary joint", 1, n, None, "Ding2013", v="1", oracle=n <= 8) for n in range(6, 15, 2)]
    + [_row("W = 1, one ternary joint", 1, 16, None, "Ding2013", v="1",
            heavy="run on its own (--only): sized at about 1.8e8 chains and 900 CPU s (30 Nov 2026), counted in "
                  "1 033 CPU s and 831 MiB, its second count (--method orbits) 1 318 CPU s, equal by code "
                  "(benchmarks/logs/one_ternary_joint_6_16.txt)")]
    + [_row("W = 1, one ternary joint", 1, 18, None, "Ding2013", v="1",
            heavy="run by hand with a checkpoint in two parts on 30 Nov 2026 beside its second count (--method "
                  "tight-reverse), equal on all 82 codes (RECORDS.md, 'One ternary joint at 18 links'); sized at about "
                  "1.6e10 chains in 1.9e6 units (1.64e10 in 1.92e6 counted)")]
)


fail, _Parser = refusals("records")


def _commit() -> str:
    def git(*args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()

    dirty = git("status", "--porcelain", "--", "synth", "mechsynth", "mechbase")
    return git("rev-parse", "--short", "HEAD") + ("+changes" if dirty else "")


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


class _PeakMemory(threading.Thread):
    """The largest sum of resident memory of a process and its descendants, sampled every 0.2 s."""

    def __init__(self, pid: int):
        super().__init__(daemon=True)
        self.pid, self.peak, self.done = pid, 0, threading.Event()

    def run(self):
        import psutil

        try:
            root = psutil.Process(self.pid)
        except psutil.NoSuchProcess:
            return
        while not self.done.is_set():
            total = 0
            try:
                for p in [root, *root.children(recursive=True)]:
                    try:
                        total += p.memory_info().rss
                    except psutil.NoSuchProcess:
                        pass
            except psutil.NoSuchProcess:
                return
            self.peak = max(self.peak, total)
            self.done.wait(0.2)


def run_count(row: Row, method: str | None = None) -> dict:
    """Run the row's count as the command line does (by ``--method method`` if given); its counts, wall and CPU
    seconds and peak MiB."""
    command = [sys.executable, "-m", "mechsynth", *row.query.split(), "--count", "--workers", "2", "--force",
               *(["--method", method] if method else [])]
    env = dict(os.environ, MECHSYNTH_CACHE="off", PYTHONPATH=str(ROOT))
    cpu0, t0 = _children_cpu(), time.perf_counter()
    proc = subprocess.Popen(command, cwd=ROOT, env=env, stdout=subprocess.PIPE, text=True)
    memory = _PeakMemory(proc.pid)
    memory.start()
    try:
        out, _ = proc.communicate()
    except KeyboardInterrupt:  # (Ctrl-C, or a kill: main) the command stops as on Ctrl-C, its temporary folder removed
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=60)  # (its pool ended, its folder removed: a second or two, longer on a loaded machine)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        raise
    finally:
        memory.done.set()
    wall, cpu = time.perf_counter() - t0, _children_cpu() - cpu0
    if proc.returncode not in (0, 1):
        raise RuntimeError(f"`mechsynth {row.query} --count{' --method ' + method if method else ''}` failed with "
                           f"exit status {proc.returncode}")
    result = json.loads(out)
    return {"count": result["count"], "by_code": result["by_code"], "wall_s": round(wall, 2),
            "cpu_s": round(cpu, 2), "peak_mib": round(memory.peak / 2**20)}


def _oracle_key(code: str) -> tuple:
    """The brute force's code key ``(assortment, composition)`` of an engine code such as ``620/0-1``."""
    import synth

    def strip(t):
        t = list(t)
        while t and t[-1] == 0:
            t.pop()
        return tuple(t)

    return strip(synth.Code.parse(code).assortment), strip(int(x) for x in code.split("/")[1].split("-"))


def _v_range(row: Row) -> tuple[int, int] | None:
    """The row's ``--v`` as (least, most): ``0..12`` or ``1`` (exactly one ternary joint's worth).

    >>> _v_range(_row("", 1, 8, v=6)), _v_range(_row("", 1, 8, v="1")), _v_range(_row("", 1, 8))
    ((0, 6), (1, 1), None)
    """
    v = row.option("--v")
    if v is None:
        return None
    lo, _, hi = v.partition("..")
    return int(lo), int(hi or lo)


def oracle_by_code(row: Row) -> dict:
    """Counts by code key of the brute force (tests/oracles/chains.py) for the row's query (a least ``--v``
    above 0 keeps the chains whose joints' excess Σ (w − 2) reaches it)."""
    from tests.oracles.chains import brute_force_chains, count_by_code

    links, dof = int(row.option("--links")), int(row.option("--dof"))
    lo, hi = _v_range(row) or (0, 0)
    found = count_by_code(brute_force_chains(links, dof, v_max=hi, fractionated="--no-fractionated" not in row.options,
                                             h=int(row.option("--h", 3))))
    return {key: n for key, n in found.items() if sum((k + 1) * c for k, c in enumerate(key[1])) >= lo}


def _query(row: Row) -> dict:
    """The keyword arguments of ``synth`` for the row's query."""
    query = dict(dof=int(row.option("--dof")), links=int(row.option("--links")), h=int(row.option("--h", 3)),
                 fractionated="--no-fractionated" not in row.options, v=_v_range(row))
    return {k: x for k, x in query.items() if x is not None}


def listing_by_code(row: Row, code: str | None = None) -> dict:
    """Counts by code of the listing path (every chain built, nauty certificates) for the row's query, or
    for its one ``code``."""
    import synth

    out: dict[str, int] = {}
    for chain in synth.type_synthesis(**_query(row), **({"code": code} if code else {}), workers=2):
        key = str(chain.code) + chain.kind_suffix
        out[key] = out.get(key, 0) + 1
    return out


def listing_of_small_codes(row: Row, found: dict, most: int) -> tuple[str, bool]:
    """The listing path's check, code by code, of the codes of a count that hold at most ``most`` chains
    (each listed on its own), for a count too large to list whole: the check's text and whether it passed.
    Each code's count and wall seconds go to stderr."""
    codes = sorted((n, code) for code, n in found["by_code"].items() if 0 < n <= most)
    differ = []
    for k, (n, code) in enumerate(codes, 1):
        t0 = time.monotonic()
        listed = listing_by_code(row, code).get(code, 0)
        print(f"records   listing [{k}/{len(codes)}] {code}: {listed} listed, {n} counted, "
              f"{time.monotonic() - t0:.2f} s", file=sys.stderr, flush=True)
        if listed != n:
            differ.append(code)
    chains = sum(n for n, _ in codes)
    if differ:
        return f"LISTING DIFFERS on {len(differ)} of {len(codes)} codes ({', '.join(differ[:3])})", False
    return (f"listing by code on the {len(codes)} codes of at most {_number(str(most))} chains "
            f"({_number(str(chains))} chains)", True)


# kernel_loops for "never": the compiled kernels of stages A and B run from this many loops on
_NO_KERNEL = 10**6


def kernels_off_by_code(row: Row, every: int = 1) -> dict:
    """Counts by code of the row's query with the engine's compiled kernels off, for every ``every``-th code
    of its plan (the first included), in this process: stage A by its plain search or CP-SAT model, stage B
    by its direct listing of weight vectors or CP-SAT model, one vector an orbit by the lex-least test in
    numpy, and the exact sub-chain test in numpy — nothing of the kernels' searches, their pebble games, their
    check of the exact test's sets or their Burnside counts.  Each code's count and CPU seconds go to stderr.
    """
    from dataclasses import replace

    from synth import ChainQuery
    from synth.synthesis.type_synthesis import count_unit, job_units, plan_jobs

    jobs = plan_jobs(ChainQuery(**_query(row)))[::every]
    out: dict[str, int] = {}
    for k, (code, conv) in enumerate(jobs, 1):
        t0 = time.process_time()
        out.setdefault(str(code), 0)  # (a code sampled is compared even where it has no chain)
        for unit in job_units((code, replace(conv, kernel_loops=_NO_KERNEL))):
            for key, n in count_unit(unit).items():
                out[key] = out.get(key, 0) + n
        print(f"records   kernels off [{k}/{len(jobs)}] {code}: {out.get(str(code), 0)} chains, "
              f"{time.process_time() - t0:.2f} CPU s", file=sys.stderr, flush=True)
    return out


def _second_method(row: Row) -> str:
    """The second count of a record: ``tight-reverse`` for chains of simple joints, ``orbits`` (Burnside over the
    bundles of parallel strings, each pattern decided once by the exact test) with multiple joints."""
    return "orbits" if row.option("--v") else "tight-reverse"


def checks(row: Row, found: dict, list_max: int = LIST_MAX, second_max: int = LIST_MAX,
           second_every: int = 1, reverse_max: int = 0, list_codes_max: int = 0,
           reverse: dict | None = None) -> tuple[str, bool]:
    """The independent checks the row passed (``none`` if it has none) and whether all it had passed;
    the listing path checks counts of up to ``list_max`` chains, and with multiple joints the count with
    the kernels off counts of up to ``second_max`` chains (every ``second_every``-th code of the plan);
    a count the listing does not check, of up to ``reverse_max`` chains, is counted again by its second count
    (:func:`_second_method`), code by code; ``reverse`` is that second count run already (its command's JSON,
    run beside the first), compared instead of running it."""
    passed, ok = [], True
    if row.published is not None:
        ok &= found["count"] == row.published
        passed.append("published" if found["count"] == row.published else "PUBLISHED DIFFERS")
    if row.oracle:
        same = oracle_by_code(row) == {_oracle_key(c): n for c, n in found["by_code"].items()}
        ok &= same
        passed.append("oracle by code" if same else "ORACLE DIFFERS")
    if 0 < found["count"] <= list_max:
        same = listing_by_code(row) == found["by_code"]
        ok &= same
        passed.append("listing by code" if same else "LISTING DIFFERS")
    elif reverse is not None or list_max < found["count"] <= reverse_max:
        method = _second_method(row)
        second = reverse if reverse is not None else run_count(row, method)
        same = second["by_code"] == found["by_code"]
        ok &= same
        print(f"records   {method}: {second['count']} chains"
              + ("" if reverse is not None else f", {second['cpu_s']} CPU s, {second['wall_s']} s"),
              file=sys.stderr, flush=True)
        passed.append(f"{method} by code" if same else f"{method.upper()} DIFFERS")
    if found["count"] > list_max and list_codes_max > 0:
        text, same = listing_of_small_codes(row, found, list_codes_max)
        ok &= same
        passed.append(text)
    if row.option("--v") and 0 < found["count"] <= second_max:
        second = kernels_off_by_code(row, second_every)
        whole = second_every == 1  # (then every code counted is in the plan's sample)
        codes = set(second) | (set(found["by_code"]) if whole else set())
        differ = sorted(c for c in codes if found["by_code"].get(c, 0) != second.get(c, 0))
        same = not differ
        for code in differ:
            print(f"records   {code}: {found['by_code'].get(code, 0)} counted, {second.get(code, 0)} with the "
                  "kernels off", file=sys.stderr)
        ok &= same
        sample = "" if whole else (f" (1 code in {second_every}: {len(second)} codes, "
                                                f"{sum(second.values())} chains)")
        passed.append(f"kernels off by code{sample}" if same else "KERNELS OFF DIFFERS")
    return "; ".join(passed) or "none", ok


def merge_checks(before: str, now: str) -> str:
    """The checks column of a recorded count checked again: each check run now replaces the one of its kind
    (its first word) recorded before, the others recorded are kept.

    >>> merge_checks("oracle by code; listing by code", "oracle by code; kernels off by code")
    'listing by code; oracle by code; kernels off by code'
    """
    def kind(check: str) -> str:
        return check.split()[0].lower()

    new = [c for c in now.split("; ") if c != "none"]
    kept = [c for c in before.split("; ") if c != "none" and kind(c) not in {kind(n) for n in new}]
    return "; ".join(kept + new) or "none"


def read_csv(path: Path) -> dict[str, dict]:
    if not path.exists():
        return {}
    with path.open(newline="") as f:
        return {line["query"]: line for line in csv.DictReader(f)}


def write_csv(path: Path, lines: dict[str, dict]) -> None:
    order = {row.query: k for k, row in enumerate(ROWS)}
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    with tmp.open("w", newline="") as f:
        writer = csv.DictWriter(f, COLUMNS)
        writer.writeheader()
        for query in sorted(lines, key=lambda q: order.get(q, len(order))):
            writer.writerow({c: lines[query].get(c, "") for c in COLUMNS})
    tmp.replace(path)


def _number(text: str) -> str:
    return f"{int(text):,}".replace(",", " ") if text else ""


def section(lines: dict[str, dict], figure: str | None = None) -> str:
    """The text of the section "Published counts" of RECORDS.md, written from the CSV's lines, showing the growth
    figure at the path ``figure`` (relative to RECORDS.md) if given."""
    out = [SECTION, "",
           "Written by `benchmarks/records.py` from `benchmarks/records.csv` (do not edit by hand). Each count is",
           "`mechsynth chains … --count --workers 2` run in a fresh process with the store of solver results off",
           "(`MECHSYNTH_CACHE=off`), on the shared 2-core machine (times are disturbed by other work; CPU s are",
           "those of the command and its workers, peak MiB the largest sum of their resident memory). Checks:",
           "*published* = the source's value; *oracle* = the brute force of tests/oracles/chains.py, code by",
           "code; *listing* = the listing path (every chain built and told apart by nauty), code by code",
           f"(counts of up to {_number(str(LIST_MAX))} chains unless `--list-max` says otherwise; of a larger count,",
           "the codes of at most `--list-codes-max` chains where it says so, each code listed on its own);",
           "*kernels off* = with multiple joints, the engine with its compiled kernels of stages A and B turned",
           "off (plain search or CP-SAT, the exact test in numpy), code by code, in one process (`--second-max`;",
           "a sample of the codes where it says so; `--recheck` checks a recorded count again);",
           "*tight-reverse* = the same command with `--method tight-reverse` (the second count of a record: another",
           "programme over the strings, another reading of the automorphisms), code by code (`--reverse-max`); the",
           "units it counts by the first count's own path (neither its programme nor the count by orbits applies:",
           "a bundle group above 4 096 permutations, two empty parallel strings outside a tight count) are no",
           "independent check, and the count says how many (`shared_path_units` of `benchmarks/checkpoints.py",
           "status|compare`, a line on the command's stderr; not recorded by the runs before 29 Nov 2026, 18 h; at",
           "W = 1 none is: 0 of the 104, 1 040 and 14 577 units of 12, 14 and 16 links, by `MECHSYNTH_CACHE=off python -c",
           "\"import synth; c = synth.count_chains(1, 16, workers=2, method='tight-reverse'); print(c.units_run, c.shared_units)\"`);",
           "*orbits* = with multiple joints, the same command with `--method orbits` (Burnside over the bundles of",
           "parallel strings, each pattern decided once by the exact test; not the count's search), code by code",
           "(`--reverse-max`); *none* = no independent check. A row without a published value goes beyond its source;",
           "the rows of 7 loops (17 and 18 links at W = 2 and 3) are the literature's largest, run on their own.",
           "Counts by code: the JSON file of each query in `benchmarks/records/`.", ""]
    if figure:
        out += [f"![The chains of each series against their links, on a log scale; published values ringed]({figure})",
                "", f"`{figure}` is drawn from the CSV by every run of `records.py` (with every row recorded,",
                "`python benchmarks/records.py` runs nothing and only writes this section and the figure again).", ""]
    out += [
           "| series | query | chains | published | source | checks passed | wall s | CPU s | peak MiB | commit |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    keys = []
    for row in ROWS:
        line = lines.get(row.query)
        if line is None:
            continue
        keys.append(row.source)
        out.append(f"| {row.series} | `{row.query}` | {_number(line['count'])} | {_number(line['published'])} | "
                   f"{row.source or '—'} | {line['check']} | {line['wall_s']} | {line['cpu_s']} | "
                   f"{line['peak_mib']} | {line['commit']} |")
    missing = [row for row in ROWS if row.query not in lines]
    if missing:
        out += ["", "Not run:", ""]
        out += [f"- `{row.query}`" + (f" (published {_number(str(row.published))}, {row.source})"
                                      if row.published else "") + f": {row.heavy or 'not run yet'}"
                for row in missing]
    out += ["", "Sources (full references: docs/theory.md, \"Sources\"):", ""]
    out += [f"- **{key}**: {SOURCES[key]}" for key in SOURCES if key in keys + [r.source for r in missing]]
    return "\n".join(out) + "\n"


def write_md(path: Path, lines: dict[str, dict], figure: Path | None = None) -> None:
    """Replace the section "Published counts" of ``path`` (created with every section if missing), showing the
    growth figure ``figure`` if given."""
    text = path.read_text() if path.exists() else "# Records\n\n" + "\n".join(f"{s}\n" for s in SECTIONS)
    if SECTION not in text:
        text = text.rstrip("\n") + f"\n\n{SECTION}\n"
    head, rest = text.split(SECTION, 1)
    following = rest.find("\n## ")
    tail = rest[following + 1:] if following >= 0 else ""
    tmp = path.with_suffix(".tmp")
    shown = os.path.relpath(figure, path.parent) if figure else None
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp.write_text(head + section(lines, shown) + ("\n" + tail if tail else ""))
    tmp.replace(path)


def sizing(row: Row):
    """The engine's estimate of the row's count before it runs (:func:`synth.synthesis.estimate.estimate`, the
    sizing ``mechsynth chains … --count`` prints before a long count: exact counts of the same query at smaller
    sizes, extrapolated), or None where fewer than three smaller sizes have chains.  Nothing is run at the
    row's own size, so a row of hours is sized in seconds.

    >>> e = sizing(next(r for r in ROWS if r.query == "chains --dof 1 --links 14"))
    >>> 2.5e5 < e.chains < 4e5, e.basis
    (True, 'exact counts at 8, 10, 12 links')
    """
    from synth import ChainQuery
    from synth.synthesis.estimate import estimate

    return estimate(ChainQuery(**_query(row)))


def size_table(rows: list[Row], lines: dict[str, dict]) -> int:
    """Print on stdout, as a Markdown table, the engine's sizing of each row (:func:`sizing`) beside the count
    and CPU seconds recorded for it in the CSV, if any, and the estimate's error against them; the time each
    sizing took goes to stderr.  Returns 1 when no row could be sized, else 0."""
    from synth.execution.sizes import describe_seconds, magnitude

    print("| query | chains, estimated | chains, recorded | error | CPU s, estimated | CPU s, recorded | error | "
          "estimated from |\n|---|---|---|---|---|---|---|---|", flush=True)
    sized = 0
    for row in rows:
        t0 = time.process_time()
        found = sizing(row)
        print(f"records   sized `{row.query}` in {time.process_time() - t0:.1f} CPU s", file=sys.stderr, flush=True)
        line = lines.get(row.query, {})
        if found is None:
            print(f"| `{row.query}` | — | {_number(line.get('count', ''))} |  | — | {line.get('cpu_s', '')} |  | "
                  "fewer than three smaller sizes have chains |", flush=True)
            continue
        sized += 1

        def cpu(found):
            seconds = magnitude(found.seconds, found.log10_seconds) if found.seconds >= 1e7 else f"{found.seconds:.3g}"
            return seconds + (f" ({describe_seconds(found.seconds, found.log10_seconds)})" if found.seconds >= 120 else "")

        def error(estimated, recorded):
            return f"{estimated / float(recorded) - 1:+.0%}" if recorded and float(recorded) > 0 else ""

        print(f"| `{row.query}` | {magnitude(found.chains, found.log10_chains)} | {_number(line.get('count', ''))} | "
              f"{error(found.chains, line.get('count'))} | {cpu(found)} | "
              f"{line.get('cpu_s', '')} | {error(found.seconds, line.get('cpu_s'))} | {found.basis[len('exact counts at '):]} |",
              flush=True)
    return 0 if sized else 1


#: the look of each series in the growth figure: colour, marker, line style
STYLES = {"W = 1": ("tab:blue", "o", "-"), "W = 2": ("tab:orange", "s", "-"),
          "W = 2, not fractionated": ("tab:orange", "s", ":"), "W = 3": ("tab:green", "^", "-"),
          "W = 3, not fractionated": ("tab:green", "^", ":"), "h = 2 (Laman)": ("tab:red", "D", "-"),
          "h = 4": ("tab:purple", "v", "-"), "h = 5": ("tab:brown", "P", "-"), "h = 6": ("tab:gray", "X", "-"),
          "W = 1, multiple joints": ("tab:cyan", "*", "--"), "W = 1, one ternary joint": ("tab:pink", "*", ":")}


def draw_growth(lines: dict[str, dict], path: Path) -> dict[str, list[tuple[int, int, int | None]]]:
    """Draw ``path`` (PNG): the chains counted against the links, on a log scale, one line per series of
    :data:`ROWS` with the rows of the CSV's ``lines`` (rows added later are drawn as they come), each
    published value ringed.  Gear trains (not rows of :data:`ROWS`) are left out.  Returns the points
    drawn: ``(links, chains, published or None)`` by series.

    >>> import tempfile
    >>> lines = {"chains --dof 1 --links 8": {"count": "16"}, "chains --dof 1 --links 10": {"count": "230"}}
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     draw_growth(lines, Path(folder) / "g.png"), (Path(folder) / "g.png").read_bytes()[:4]
    ({'W = 1': [(8, 16, 16), (10, 230, 230)]}, b'\\x89PNG')
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    series: dict[str, list[tuple[int, int, int | None]]] = {}
    for row in ROWS:
        line = lines.get(row.query)
        if line is not None and int(line["count"]) > 0:
            series.setdefault(row.series, []).append((int(row.option("--links")), int(line["count"]), row.published))
    fig, ax = plt.subplots(figsize=(10, 6), dpi=100)
    for name, points in series.items():
        colour, marker, style = STYLES.get(name, ("black", "o", "-"))
        points.sort()
        ax.plot([n for n, _, _ in points], [c for _, c, _ in points], linestyle=style, marker=marker, color=colour,
                markersize=7, linewidth=1.6, label=name)
    published = [(n, p) for points in series.values() for n, _, p in points if p]
    if published:
        ax.plot(*zip(*published), linestyle="none", marker="o", markersize=14, markerfacecolor="none",
                markeredgecolor="black", markeredgewidth=1.2, label="published value")
    ax.set_yscale("log")
    ax.set_xlabel("links", fontsize=13)
    ax.set_ylabel("non-isomorphic chains", fontsize=13)
    ax.set_title("Chains counted by mechsynth chains … --count (benchmarks/records.csv)", fontsize=13)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.tick_params(labelsize=12)
    ax.grid(True, which="major", alpha=0.35)
    ax.legend(fontsize=11, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.png")
    fig.savefig(tmp)
    plt.close(fig)
    tmp.replace(path)
    return series


def _writable(path: Path, what: str, directory: bool = False) -> None:
    folder = path if directory else path.parent
    if not directory and path.is_dir():
        fail(f"the {what} {path} is a folder, not a file")
    if folder.exists() and not folder.is_dir():
        fail(f"the {what} {path} cannot be written: {folder} is not a folder")
    probe = folder
    while not probe.exists():
        probe = probe.parent
    if not os.access(probe, os.W_OK) or path.exists() and not os.access(path, os.W_OK):
        fail(f"the {what} {path} cannot be written (no permission)")


def _second_count(path: Path) -> dict:
    """The counts in ``path``, the JSON of a ``mechsynth chains … --count`` command (``count``, ``by_code``)."""
    try:
        found = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        fail(f"--reverse-from {path} cannot be read as the JSON of a count ({type(exc).__name__})")
    by_code = found.get("by_code") if isinstance(found, dict) else None
    if not (isinstance(by_code, dict) and all(isinstance(n, int) for n in by_code.values())
            and found.get("count") == sum(by_code.values())):
        fail(f"--reverse-from {path} is not the JSON of a count (its count and counts by code)")
    return found


def main(argv=None) -> int:
    """The script; a kill (SIGTERM, SIGHUP) stops it as Ctrl-C does (the count running stopped, its temporary
    folder removed; an in-process listing's pool ended), then ends it by that signal."""
    from synth.execution.interrupt import ending_signals_unwind

    with ending_signals_unwind():
        return _main(argv)


def _main(argv) -> int:
    parser = _Parser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="only the smallest rows (a few seconds)")
    parser.add_argument("--only", help="only the rows whose query contains this text (heavy rows included); a whole query, "
                        "such as 'chains --dof 1 --links 20', chooses its row alone")
    parser.add_argument("--again", action="store_true", help="run rows already in the CSV again")
    parser.add_argument("--list-max", type=int, metavar="N",
                        help=f"check by the listing path the counts of up to N chains (default: {LIST_MAX})")
    parser.add_argument("--list-codes-max", type=int, metavar="N",
                        help="of a count larger than --list-max, check by the listing path each code of up to N chains, "
                        "one code at a time (default: 0, none)")
    parser.add_argument("--second-max", type=int, metavar="N",
                        help="with multiple joints, check by the count with the kernels off the counts of up to N "
                        f"chains (default: {LIST_MAX})")
    parser.add_argument("--second-every", type=int, metavar="K",
                        help="… on every K-th code of the plan only, a sample (default: every code)")
    parser.add_argument("--reverse-max", type=int, metavar="N",
                        help="check the counts the listing does not check, of up to N chains, by a second count, "
                        f"--method tight-reverse (--method orbits with multiple joints) (default: {REVERSE_MAX:.0e}; "
                        "0: none)")
    parser.add_argument("--recheck", action="store_true",
                        help="with --only: check again the counts already in the CSV (their by-code files), without "
                        "counting them again; only the checks column changes")
    parser.add_argument("--reverse-from", type=Path, metavar="FILE",
                        help="with --recheck of one row: its second count read from FILE, the JSON that `mechsynth "
                        "<query> --count --method tight-reverse` (orbits with multiple joints) printed (run beside the "
                        "first count, on workers "
                        "of its own), compared code by code instead of running it")
    parser.add_argument("--size", action="store_true",
                        help="count nothing: print the engine's sizing of the rows chosen (--only, --quick, or every "
                        "row) as a Markdown table on stdout, beside the counts and CPU seconds recorded in the CSV; "
                        "nothing is written")
    parser.add_argument("--csv", type=Path, default=ROOT / "benchmarks" / "records.csv",
                        help="the table of counts, one line a query, updated in place (default: %(default)s)")
    parser.add_argument("--md", type=Path, default=ROOT / "benchmarks" / "RECORDS.md",
                        help="its section 'Published counts' is written from the CSV (default: %(default)s)")
    parser.add_argument("--by-code", type=Path, default=ROOT / "benchmarks" / "records",
                        help="folder of the counts by code, one JSON file a query (default: %(default)s)")
    parser.add_argument("--figure", type=Path,
                        help="the growth figure (PNG), drawn from the whole CSV whenever the Markdown file is written "
                        "(default: records_growth.png beside the Markdown file)")
    args = parser.parse_args(argv)
    checking = {"--list-max": args.list_max, "--list-codes-max": args.list_codes_max, "--second-max": args.second_max, "--second-every": args.second_every,
                "--reverse-max": args.reverse_max}
    if args.size:
        given = [name for name, value in [*checking.items(), ("--again", args.again or None),
                                           ("--recheck", args.recheck or None), ("--figure", args.figure)]
                 if value is not None]
        if given:
            fail(f"--size counts and writes nothing, so {given[0]} has no use with it")
    args.list_max = LIST_MAX if args.list_max is None else args.list_max
    args.list_codes_max = 0 if args.list_codes_max is None else args.list_codes_max
    args.second_max = LIST_MAX if args.second_max is None else args.second_max
    args.second_every = 1 if args.second_every is None else args.second_every
    args.reverse_max = REVERSE_MAX if args.reverse_max is None else args.reverse_max
    args.figure = args.figure or args.md.parent / "records_growth.png"
    if args.quick and args.only is not None:
        fail("--quick and --only choose the rows in two different ways: give one of them")
    if args.list_max < 0:
        fail(f"--list-max must be 0 (no listing check) or more, not {args.list_max}")
    if args.list_codes_max < 0:
        fail(f"--list-codes-max must be 0 (no listing of single codes) or more, not {args.list_codes_max}")
    if args.second_max < 0:
        fail(f"--second-max must be 0 (no check with the kernels off) or more, not {args.second_max}")
    if args.reverse_max < 0:
        fail(f"--reverse-max must be 0 (no second count) or more, not {args.reverse_max}")
    if args.second_every < 1:
        fail(f"--second-every must be 1 (every code) or more, not {args.second_every}")
    if args.recheck and (args.only is None or args.again):
        fail("--recheck checks the rows chosen by --only again, without counting them: give --only, not --again")
    if args.only is not None and not args.only.strip():
        fail("--only needs some text of a query, such as 'dof 2 --links 11'")
    reverse = None
    if args.reverse_from is not None:
        if not args.recheck or args.size:
            fail("--reverse-from gives the second count of a recorded row: use it with --recheck and --only")
        reverse = _second_count(args.reverse_from)
    for path, what, directory in ((args.csv, "CSV file", False), (args.md, "Markdown file", False),
                                  (args.by_code, "by-code folder", True), (args.figure, "figure", False)):
        if not args.size:
            _writable(path, what, directory)
    if args.figure.suffix.lower() != ".png" and not args.size:
        fail(f"the figure {args.figure} must be a .png file")
    if args.csv.exists():
        with args.csv.open(newline="") as f:
            header = next(csv.reader(f), None)
        if header != COLUMNS:
            fail(f"{args.csv} is not a records CSV (its first line is not the header {','.join(COLUMNS)})")
    if args.only is not None:
        rows = ([row for row in ROWS if row.query == args.only.strip()]  # a whole query: that row alone
                or [row for row in ROWS if args.only in row.query])
        if not rows:
            print(f"records: no row's query contains {args.only!r}", file=sys.stderr)
            return 1
        if reverse is not None and len(rows) > 1:
            fail(f"--reverse-from is the second count of one row, and --only {args.only!r} chooses {len(rows)} rows")
    elif args.size:
        rows = [row for row in ROWS if row.quick or not args.quick]
    else:
        rows = [row for row in ROWS if (row.quick if args.quick else not row.heavy)]
    lines = read_csv(args.csv)
    if args.size:
        try:
            return size_table(rows, lines)
        except KeyboardInterrupt:
            print("records: interrupted", file=sys.stderr)
            return 130
    if args.recheck:
        missing = [row.query for row in rows if row.query not in lines]
        if missing:
            fail(f"--recheck needs counts in {args.csv}, and it has none of `{missing[0]}`")
    if args.only is None and not args.again:
        rows = [row for row in rows if row.query not in lines]
    rows.sort(key=lambda row: row.published is None)  # the published counts first, should the run be cut short
    commit, bad = _commit(), 0
    try:
        for k, row in enumerate(rows, 1):
            print(f"records [{k}/{len(rows)}] mechsynth {row.query} --count", file=sys.stderr, flush=True)
            if args.recheck:  # the counts recorded, checked again
                line = lines[row.query]
                found = json.loads((ROOT / line["by_code_file"]).read_text())
                check, ok = checks(row, found, args.list_max, args.second_max, args.second_every, args.reverse_max,
                                   args.list_codes_max, reverse)
                line["check"] = merge_checks(line["check"], check)
                bad += not ok
                write_csv(args.csv, lines)
                write_md(args.md, lines, args.figure)
                print(f"records   {found['count']} chains recorded at {line['commit']}, checked at {commit}: "
                      f"{line['check']}", file=sys.stderr, flush=True)
                continue
            found = run_count(row)
            check, ok = checks(row, found, args.list_max, args.second_max, args.second_every, args.reverse_max,
                               args.list_codes_max)
            bad += not ok
            args.by_code.mkdir(parents=True, exist_ok=True)
            by_code_file = args.by_code / f"{row.slug}.json"
            by_code_file.write_text(json.dumps({"query": row.query, "count": found["count"],
                                                "by_code": found["by_code"]}, indent=0) + "\n")
            shown = by_code_file.relative_to(ROOT) if by_code_file.is_relative_to(ROOT) else by_code_file
            lines[row.query] = {
                "query": row.query, "count": found["count"], "published": row.published or "",
                "source": row.source, "check": check, "by_code_file": str(shown), "wall_s": found["wall_s"],
                "cpu_s": found["cpu_s"], "peak_mib": found["peak_mib"],
                "method": "count path (stage B vectors, no chain built), 2 workers, store off",
                "commit": commit, "date": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M")}
            write_csv(args.csv, lines)
            write_md(args.md, lines, args.figure)
            print(f"records   {found['count']} chains, {found['cpu_s']} CPU s, {found['wall_s']} s, "
                  f"{found['peak_mib']} MiB; {check}", file=sys.stderr, flush=True)
    except KeyboardInterrupt:
        print("records: interrupted; the rows finished so far are written (the figure is drawn by the next run)",
              file=sys.stderr)
        return 130
    except RuntimeError as failed:  # a count's command failed (killed, out of memory): its own stderr says why
        print(f"records: {failed}; the rows finished so far are written", file=sys.stderr)
        return 2
    if not rows:
        write_md(args.md, lines, args.figure)
    draw_growth(lines, args.figure)
    if not rows:
        print(f"records: every row chosen is recorded; {args.md} and {args.figure} written again from {args.csv}",
              file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
