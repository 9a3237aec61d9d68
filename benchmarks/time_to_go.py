"""How well a count's progress line would have told the time to go, read from the logs of counts run to their end.

A count's log (``mechsynth chains … --count`` with stderr to a file) has one line a minute: codes, units and
chains so far and the time elapsed, and its first line the estimate (``about 6.9e+09 chains in 8 511 997
units``).  Given the logs of one count in order (its parts, each resumed from the checkpoint the one before
left), this script takes every progress line, works out the time that was really left (the rest of its part
and the whole of every later part, wall clock as logged), and what three predictors would have said at that
line, each at the rate of the part so far: the **chains** counted against the chains estimated (the line of
30 Nov 2026), the **units** counted against the units estimated, and the **larger** of the two::

    python benchmarks/time_to_go.py count16v.log count16v_part2.log … count16v_part5.log
    python benchmarks/time_to_go.py benchmarks/logs/count_w3_20_links.txt:4-31 --chains 3.3e10 --units 612338

``PATH:FIRST-LAST`` takes those lines of a file only (one run of several in a log); ``--units`` and ``--chains``
give the estimate where the log has no first line.  It prints one row every ``--every`` lines (and the last
before the end), then for each predictor the median and the largest factor it was off by (``pred / actual``
or its inverse, each at least a minute: the lines' grain) and how many lines it gave no time (past its estimate).  The last
line, every code done, is left out (nothing to go).  The last part must have ended by itself (its last
line has every code done); a part ends at its ``/usr/bin/time -v`` wall clock, else at its last line.  Exit
status 2 for bad input.
"""

from __future__ import annotations

import re
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from benchmarks._out import emit, refusals  # noqa: E402

fail, _Parser = refusals("time_to_go")

LINE = re.compile(r"mechsynth: (\d+)/(\d+) codes, ([\d ]+) units, ([\d ]+) chains; ([\d.]+) (s|min|h|days) elapsed")
ESTIMATE = re.compile(r"a long query: about ([\d.e+ ]+) chains in ([\d ]+) units")  # 6.9e+09, or 318 162
BEFORE = re.compile(r"committed in this run, (\d+) units done before")
WALL = re.compile(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)")
SECONDS = {"s": 1, "min": 60, "h": 3600, "days": 86400}
PREDICTORS = ("chains", "units", "larger")


def _number(text: str) -> int:
    return int(text.replace(" ", ""))


def _lines(spec: str) -> list[str]:
    """The lines of ``PATH`` or ``PATH:FIRST-LAST`` (1-based, inclusive)."""
    path, _, span = spec.partition(":")
    try:
        lines = Path(path).read_text().splitlines()
    except OSError as exc:
        fail(f"cannot read {path}: {exc.strerror}")
    if span:
        if not re.fullmatch(r"\d+-\d+", span):
            fail(f"{spec}: a line range is FIRST-LAST, as in {path}:4-27")
        first, last = map(int, span.split("-"))
        lines = lines[first - 1:last]
    return lines


def read_part(spec: str) -> dict:
    """One part's estimate, units done before it, progress lines ``(codes, of, units, chains, seconds)`` and end."""
    part = {"estimate": None, "before": 0, "rows": [], "wall": None}
    for text in _lines(spec):
        if (m := ESTIMATE.search(text)) and part["estimate"] is None:
            part["estimate"] = (float(m[1].replace(" ", "")), _number(m[2]))
        elif (m := BEFORE.search(text)) and not part["rows"]:
            part["before"] = int(m[1])
        elif m := LINE.search(text):
            part["rows"].append((int(m[1]), int(m[2]), _number(m[3]), _number(m[4]), float(m[5]) * SECONDS[m[6]]))
        elif m := WALL.search(text):
            part["wall"] = sum(float(x) * 60**i for i, x in enumerate(reversed(m[1].split(":"))))
    if not part["rows"]:
        fail(f"{spec} has no progress line ('mechsynth: 3/739 codes, … units, … chains; 60 s elapsed')")
    return part


def lines_of(parts: list[dict]) -> list[dict]:
    """Every progress line of a count in parts: whole-count and this-part totals, seconds elapsed and left."""
    last = parts[-1]["rows"][-1]
    if last[0] != last[1]:
        fail("the last part did not end by itself (its last line has codes still to do): no time left is known")
    ends = [p["wall"] if p["wall"] is not None else p["rows"][-1][4] for p in parts]
    plan = parts[0]["rows"][0][1]
    out, units_before, chains_before = [], 0, 0
    for k, part in enumerate(parts):
        # a line of before 30 Nov 2026 (23f81d0) counted its part alone: its codes are of the part's plan
        alone = part["rows"][0][1] != plan
        units_before = part["before"]
        for codes, of, units, chains, seconds in part["rows"]:
            here = (units, chains) if alone else (units - units_before, chains - chains_before)
            whole = (units + units_before, chains + chains_before) if alone else (units, chains)
            out.append({"part": k + 1, "elapsed": seconds, "left": ends[k] - seconds + sum(ends[k + 1:]),
                        "finished": codes == of,
                        "units": whole[0], "chains": whole[1], "units here": here[0], "chains here": here[1]})
        chains_before = out[-1]["chains"]
    return out


def predict(line: dict, chains: float, units: float) -> dict:
    """Each predictor's time to go at ``line`` (None: past its estimate, or nothing counted in this part yet)."""
    said = {}
    for name, expected in (("chains", chains), ("units", units)):
        done, here = line[name], line[f"{name} here"]
        said[name] = line["elapsed"] * (expected - done) / here if done < expected and here > 0 else None
    said["larger"] = max((t for t in said.values() if t is not None), default=None)
    return said


def _off(said: float, actual: float) -> float:
    """The factor ``said`` is off from ``actual`` (1 when right; both floored at a minute: the lines' grain)."""
    said, actual = max(said, 60.0), max(actual, 60.0)
    return max(said / actual, actual / said)


def _short(seconds: float | None) -> str:
    if seconds is None:
        return "past"
    return f"{seconds / 60:.0f} min" if seconds < 7200 else f"{seconds / 3600:.1f} h"


def main(argv=None) -> int:
    parser = _Parser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", nargs="+", help="the parts of one count, in order (PATH or PATH:FIRST-LAST)")
    parser.add_argument("--units", type=float, help="units estimated (default: the log's first line)")
    parser.add_argument("--chains", type=float, help="chains estimated (default: the log's first line)")
    parser.add_argument("--every", type=int, default=10, help="print one line in this many (default 10)")
    args = parser.parse_args(argv)
    if args.every < 1:
        fail("--every is a number of lines, 1 or more")
    parts = [read_part(spec) for spec in args.logs]
    logged = next((p["estimate"] for p in parts if p["estimate"]), None)
    chains = args.chains or (logged and logged[0])
    units = args.units or (logged and logged[1])
    if not chains or not units:
        fail("no estimate in the logs: give --chains and --units")
    lines = lines_of(parts)
    emit(f"estimate: {chains:.3g} chains in {units:.0f} units; {len(lines) - 1} lines before the last in "
         f"{len(parts)} part(s)")
    emit("| part | elapsed in part | units | chains | actual left | " + " | ".join(PREDICTORS) + " |")
    emit("|---|---|---|---|---|" + "---|" * len(PREDICTORS))
    offs = {name: [] for name in PREDICTORS}
    past = dict.fromkeys(PREDICTORS, 0)
    for i, line in enumerate(lines):
        if line["finished"]:  # every code done: nothing to go, no time said (the line's rule)
            continue
        said = predict(line, chains, units)
        for name in PREDICTORS:
            if said[name] is None:
                past[name] += 1
            else:
                offs[name].append(_off(said[name], line["left"]))
        if i % args.every == 0 or i == len(lines) - 2:
            emit(f"| {line['part']} | {_short(line['elapsed'])} | {line['units']:,} | {line['chains']:,} | "
                 f"{_short(line['left'])} | " + " | ".join(_short(said[name]) for name in PREDICTORS) + " |")
    for name in PREDICTORS:
        got = offs[name]
        within = sum(f <= 2 for f in got)
        emit(f"{name}: off by a median factor {statistics.median(got):.2f}, at most {max(got):.1f}, within a factor 2 "
             f"at {within} of {len(got)} lines; no time at {past[name]}" if got else f"{name}: no time at any line")
    return 0


if __name__ == "__main__":
    sys.exit(main())
