"""A long count's checkpoint read back, its counts by code as a table, and two counts compared code by code.

A count run with ``--checkpoint FILE`` commits every finished unit to an SQLite file (issue 41:
the 20-link count).  This script reads such a file without changing it — while the count
is still writing it, too — and compares two counts of the same query made by different runs
(``--method listing`` and ``--method orbits`` or ``tight-reverse``, each with its own checkpoint), code by code::

    python benchmarks/checkpoints.py status c20.sqlite                 # how far it is
    python benchmarks/checkpoints.py table c20.sqlite > by_code.csv    # code,count,units,state
    python benchmarks/checkpoints.py compare c18_orbits.sqlite benchmarks/logs/count_18_links_e43e1b1.txt
    python benchmarks/checkpoints.py compare --part small_codes.json benchmarks/logs/count_18_links_e43e1b1.txt

``status`` prints the query, the units done, the chains counted so far and the codes complete,
partial and not begun (the plan's codes are rebuilt from the query in the file, by number
synthesis in milliseconds, and matched to the file by the plan's digest).  ``table`` prints the
counts by code as CSV (``--complete`` refuses a count not finished).  ``compare A B`` takes two
checkpoints, or a checkpoint and a count's JSON (``{"count": …, "by_code": {…}}``: the output of
``mechsynth chains … --count``, a file of ``benchmarks/records/``, or a log whose last JSON line
is that), or two of either, and compares every code complete in both (with ``--part``, A is a
spot check of some of B's codes — ``--code`` queries — and only those are compared).  It prints
one JSON object: the codes compared, equal, different (with both counts), complete in one count
only, pending (complete in one of two counts still running), and whether each count is
finished; the verdict is "equal" only when both are finished and agree on every code.
``status`` and ``compare`` also give ``shared_path_units``: the units a second count
(``--method tight-reverse``) counted by the first count's own path, so no independent check of it
(``null`` for a count's JSON, which does not say; 0 for a checkpoint of before 29 Nov 2026, 18 h,
which did not record them).

Exit status: 0 when every code compared is equal (``status``, ``table``: the file was read),
1 when a code differs or one side has a complete code the other lacks, 2 for bad input
(a missing file, a file of something else, two checkpoints of different queries).
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from benchmarks._out import emit, refusals  # noqa: E402

SQLITE_HEADER = b"SQLite format 3\x00"


fail, _Parser = refusals("checkpoints")


def _state(path: Path):
    from synth import SynthesisError, read_checkpoint

    try:
        return read_checkpoint(path)
    except SynthesisError as exc:
        fail(str(exc))


def plan_codes_of(state) -> list[str] | None:
    """The codes of the plan the checkpoint belongs to, in plan order, or None when its query in
    words cannot be read back into the same plan (the digest in the file decides)."""
    from synth import PLAN_FORMAT, ChainQuery, SynthesisError, count_identity, plan_jobs

    words = state.query.split()
    first = next((i for i, word in enumerate(words) if "=" in word), len(words))
    what, options = " ".join(words[:first]), {}
    for word in words[first:]:
        key, _, value = word.partition("=")
        options[key] = int(value) if value.lstrip("-").isdigit() else value
    try:
        query = ChainQuery.of(**options)
        if f"{PLAN_FORMAT}:{count_identity(query, what)[0]}" != state.identity:
            return None
        return [str(code) for code, _ in plan_jobs(query)]
    except (SynthesisError, TypeError, ValueError):
        return None


def status(state) -> dict:
    """How far the count of a checkpoint is: units, chains, codes complete / partial / not begun."""
    codes = plan_codes_of(state)
    out = {"query": state.query, "created": state.created, "units_done": state.units, "chains_so_far": state.chains,
           "shared_path_units": state.shared_units, "codes_complete": len(state.complete), "codes_partial": len(state.partial)}
    if codes is not None:
        out["codes_in_plan"] = len(codes)
        out["codes_not_begun"] = len([c for c in codes if c not in state.complete and c not in state.partial])
    out["partial"] = {code: {"units": units, "count": n} for code, (n, units) in state.partial.items()}
    return out


def table_rows(state, plan: list[str] | None = None) -> list[dict]:
    """One row a code: code, count, units, state (complete or partial); in the order of the ``plan``'s
    codes where it is known (the order of ``--count``'s output), else complete codes first, as they finished."""
    rows = ([{"code": code, "count": n, "units": units, "state": "complete"} for code, (n, units) in state.complete.items()]
            + [{"code": code, "count": n, "units": units, "state": "partial"} for code, (n, units) in state.partial.items()])
    if plan is not None:
        place = {code: i for i, code in enumerate(plan)}
        rows.sort(key=lambda row: place.get(row["code"], len(place)))
    return rows


def _in_words(query: str) -> str:
    """A query as a command line (benchmarks/records/*.json) in a checkpoint's words; other text unchanged.

    >>> _in_words("chains --dof 1 --links 12 --h 2")
    'chains dof=1 links=12 h=2'
    """
    words = query.split()
    keys, values = words[1::2], words[2::2]
    if len(words) % 2 == 0 or not all(k.startswith("--") for k in keys) or any(v.startswith("--") for v in values):
        return query  # a flag (--no-fractionated) or other text: left as it is, so it matches no checkpoint
    return " ".join([words[0]] + [f"{k[2:]}={v}" for k, v in zip(keys, values)])


def read_counts(path: Path) -> tuple[dict, bool, str, int | None]:
    """(complete codes → count, whether the count is finished, its query in words, its shared-path units)
    of a checkpoint or a count's JSON (finished; codes without chains left out; the units a second count
    counted by the first count's own path are in a checkpoint only: None for a JSON)."""
    if not path.is_file():
        fail(f"there is no file {path}" + (" (it is a folder)" if path.is_dir() else ""))
    try:
        with path.open("rb") as f:
            head = f.read(len(SQLITE_HEADER))
    except OSError as exc:
        fail(f"cannot read {path} ({exc.strerror})")
    if head == SQLITE_HEADER:
        state = _state(path)  # a code complete with no chain is no row of a count's JSON: left out here too
        codes = plan_codes_of(state)
        finished = codes is not None and not state.partial and set(codes) <= set(state.complete)
        return {code: n for code, (n, _) in state.complete.items() if n}, finished, state.query, state.shared_units
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        fail(f"cannot read {path} as text ({exc.__class__.__name__})")
    for chunk in [text, *reversed(text.splitlines())]:  # the whole file, or its last JSON line (a log)
        try:
            found = json.loads(chunk)
        except ValueError:
            continue
        if isinstance(found, dict) and isinstance(found.get("by_code"), dict) and all(
                isinstance(n, int) and not isinstance(n, bool) for n in found["by_code"].values()):
            if "count" in found and found["count"] != sum(found["by_code"].values()):
                fail(f"{path}: its count {found['count']} is not the sum of its counts by code")
            return {code: n for code, n in found["by_code"].items() if n}, True, _in_words(found.get("query", "")), None
    fail(f"{path} is neither a checkpoint nor a count's JSON (a line {{\"count\": …, \"by_code\": {{…}}}})")


def compare(a: tuple[dict, bool], b: tuple[dict, bool]) -> dict:
    """Two counts code by code, each given as (complete codes → count, finished): every code complete
    in both is compared; a code complete in one is a difference if the other is finished without
    it, and pending while the other runs.

    >>> compare(({"440/0": 9, "521/0": 5}, True), ({"440/0": 9}, False))["verdict"]
    'equal so far'
    >>> found = compare(({"440/0": 9}, True), ({"440/0": 8, "602/0": 2}, True))
    >>> found["verdict"], found["different"], found["only_in_b"]
    ('different', {'440/0': [9, 8]}, ['602/0'])
    """
    (done_a, finished_a), (done_b, finished_b) = a, b
    both = [code for code in done_a if code in done_b]
    different = {code: [done_a[code], done_b[code]] for code in both if done_a[code] != done_b[code]}
    only_a = [code for code in done_a if code not in done_b and finished_b]
    only_b = [code for code in done_b if code not in done_a and finished_a]
    pending = [code for code in [*done_a, *done_b] if (code in done_a) != (code in done_b)
               and code not in only_a and code not in only_b]
    verdict = ("different" if different or only_a or only_b else "equal" if finished_a and finished_b
               else "equal so far")
    return {"verdict": verdict, "codes_compared": len(both), "codes_equal": len(both) - len(different),
            "chains_compared": sum(done_a[code] for code in both if code not in different),
            "finished": [finished_a, finished_b], "different": different, "only_in_a": only_a,
            "only_in_b": only_b, "pending": pending}


def _links(code: str) -> int | None:
    """The links of a code's chains (None for a name that is not a code)."""
    from synth import Code, SynthesisError

    try:
        return Code.parse(code.split(" ")[0]).links
    except (SynthesisError, ValueError):
        return None


def _words(sizes: list[int]) -> str:
    return ", ".join(map(str, sizes))


def main(argv=None) -> int:
    parser = _Parser(description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    p = commands.add_parser("status", help="how far a count is: units, chains, codes complete and partial")
    p.add_argument("checkpoint", type=Path)
    p = commands.add_parser("table", help="the counts by code as CSV: code,count,units,state")
    p.add_argument("checkpoint", type=Path)
    p.add_argument("--complete", action="store_true", help="refuse a count not finished (exit 1)")
    p = commands.add_parser("compare", help="two counts (checkpoints or JSON) code by code")
    p.add_argument("a", type=Path)
    p.add_argument("b", type=Path)
    p.add_argument("--part", action="store_true",
                   help="A counts some codes of B's query (--code queries, a spot check): B's other codes are left out")
    args = parser.parse_args(argv)
    if args.command == "compare":
        if args.a.resolve() == args.b.resolve():
            fail(f"{args.a} compared with itself proves nothing: give the two counts to compare")
        *a, query_a, shared_a = read_counts(args.a)
        *b, query_b, shared_b = read_counts(args.b)  # (a checkpoint's query in words; a records file's command line, put in words; a count's JSON has none)
        # a spot check's --code query has no links= (the code says them, and the sizes are checked below)
        bare = [" ".join(word for word in re.sub(r" by [\w-]+", "", q).split()  # (the method: " by orbits")
                         if not (args.part and word.startswith(("code=", "links=")))) for q in (query_a, query_b)]
        if query_a and query_b and bare[0] != bare[1]:
            fail(f"{args.a} counts another query ({query_a}) than {args.b} ({query_b})")
        if args.part:
            if not a[0]:
                fail(f"{args.a} has no complete code to compare (--part compares A's codes)")
            b[0] = {code: n for code, n in b[0].items() if code in a[0]}
        sizes = [sorted({_links(code) for code in side[0]} - {None}) for side in (a, b)]
        if all(sizes) and sizes[0] != sizes[1]:
            fail(f"{args.a} counts chains of {_words(sizes[0])} links and {args.b} of {_words(sizes[1])}")
        # the units of a second count (tight-reverse) counted by the first count's own path: no independent check
        result = {"a": str(args.a), "b": str(args.b), **compare(tuple(a), tuple(b)),
                  "shared_path_units": {"a": shared_a, "b": shared_b}}
        emit(json.dumps(result, indent=1))
        return 1 if result["verdict"] == "different" else 0
    state = _state(args.checkpoint)
    if args.command == "status":
        emit(json.dumps({"checkpoint": str(args.checkpoint), **status(state)}, indent=1))
        return 0
    codes = plan_codes_of(state)
    if args.complete and (state.partial or codes is None or set(codes) - set(state.complete)):
        missing = len(codes) - len(state.complete) if codes is not None else "some"
        print(f"checkpoints: the count of {args.checkpoint} is not finished ({missing} codes of its plan are not "
              "complete)" if codes is not None else f"checkpoints: the plan of {args.checkpoint} cannot be rebuilt, "
              "so whether it is finished is unknown", file=sys.stderr)
        return 1
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=["code", "count", "units", "state"], lineterminator="\n")
    writer.writeheader()
    writer.writerows(table_rows(state, codes))
    emit(text.getvalue().rstrip("\n"))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("checkpoints: interrupted", file=sys.stderr)
        sys.exit(130)
