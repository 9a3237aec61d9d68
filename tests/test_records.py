"""benchmarks/records.py: the published counts reproduced as data (benchmarks/records.csv, RECORDS.md).

The fast path (``--quick``: the four smallest rows) runs the real command line and its checks; the
CSV's columns, the by-code files and the section of RECORDS.md are read back.  The checks must be
able to fail: a count that is off is reported by each of them.
"""

from __future__ import annotations

import csv
import importlib.util
import json
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _records():
    spec = importlib.util.spec_from_file_location("records", ROOT / "benchmarks" / "records.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["records"] = module  # its dataclass looks its module up by name
    spec.loader.exec_module(module)
    return module


def _run(*args):
    return subprocess.run([sys.executable, str(ROOT / "benchmarks" / "records.py"), *map(str, args)], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)


def test_quick_run_writes_the_csv_the_by_code_files_and_its_section(tmp_path):
    records = _records()
    md = tmp_path / "RECORDS.md"
    md.write_text("# Records\n\n## Published counts\n\nold text\n\n## Gear trains\n\nthe gear rows stay\n")
    p = _run("--quick", "--csv", tmp_path / "new" / "r.csv", "--md", md, "--by-code", tmp_path / "bc")
    assert p.returncode == 0, p.stderr
    assert p.stdout == ""  # progress and results of the rows go to stderr; the data to the files
    with (tmp_path / "new" / "r.csv").open(newline="") as f:  # (a folder not there yet is made)
        reader = csv.DictReader(f)
        assert reader.fieldnames == records.COLUMNS == [
            "query", "count", "published", "source", "check", "by_code_file", "wall_s", "cpu_s", "peak_mib",
            "method", "commit", "date"]
        lines = list(reader)
    quick = [row for row in records.ROWS if row.quick]
    assert [line["query"] for line in lines] == [row.query for row in quick]
    assert len(lines) == 4
    for line, row in zip(lines, quick):
        assert int(line["count"]) == row.published == int(line["published"])
        assert line["check"] == "published; oracle by code; listing by code"
        assert float(line["cpu_s"]) > 0 and float(line["wall_s"]) > 0 and int(line["peak_mib"]) > 0
        found = json.loads(Path(line["by_code_file"]).read_text())
        assert found["query"] == row.query and sum(found["by_code"].values()) == int(line["count"])
    text = md.read_text()
    assert "old text" not in text and "the gear rows stay" in text
    assert text.index("## Published counts") < text.index("`chains --dof 3 --links 6`") < text.index("## Gear")
    assert "- `chains --dof 3 --links 16`: not run yet" in text  # every row not run is named, heavy ones with why
    assert "- `chains --dof 3 --links 20`: run on its own (--only): 8 loops" in text  # heavy: run by hand
    figure = tmp_path / "records_growth.png"  # beside the Markdown file, shown in its section
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "](records_growth.png)" in text.split("## Gear")[0]


def test_each_check_reports_a_count_that_is_off():
    records = _records()
    row = records.ROWS[0]
    assert row.query == "chains --dof 1 --links 4" and row.published == 1 and row.oracle
    check, ok = records.checks(row, {"count": 2, "by_code": {"4/0": 2}})
    assert not ok
    assert check == "PUBLISHED DIFFERS; ORACLE DIFFERS; LISTING DIFFERS"
    assert records.checks(row, {"count": 1, "by_code": {"4/0": 1}}) == (
        "published; oracle by code; listing by code", True)


def test_engine_codes_read_as_the_oracles_keys():
    records = _records()
    assert records._oracle_key("440/0") == ((4, 4), ())
    assert records._oracle_key("620/0-1") == ((6, 2), (0, 1))
    assert records._oracle_key("60/2") == ((6,), (2,))


def test_bad_options_are_refused_in_one_sentence_and_no_file_is_touched(tmp_path):
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    not_a_count, a_count = tmp_path / "not_a_count.json", tmp_path / "a_count.json"
    not_a_count.write_text('{"count": 3, "by_code": {"440/0": 2}}')
    a_count.write_text('{"count": 2, "by_code": {"440/0": 2}}')
    h4_rows = sum("--h 4" in row.query for row in _records().ROWS)  # the rows '--only "--h 4"' chooses
    cases = [
        (["--quick", "--only", "dof 1"], "give one of them"),
        (["--only", " "], "--only needs some text"),
        (["--csv", other], "is not a records CSV"),
        (["--csv", tmp_path], "is a folder, not a file"),
        (["--md", other / "R.md"], "is not a folder"),
        (["--frobnicate"], "unrecognized arguments"),
        (["--list-max", "-1"], "--list-max must be 0"),
        (["--list-max", "many"], "invalid int value"),
        (["--list-codes-max", "-1"], "--list-codes-max must be 0"),
        (["--size", "--only", "links 8", "--list-codes-max", "5"], "--list-codes-max has no use with it"),
        (["--second-max", "-1"], "--second-max must be 0"),
        (["--second-every", "0"], "--second-every must be 1"),
        (["--recheck"], "give --only"),
        (["--recheck", "--only", "links 8 --v", "--again"], "not --again"),
        (["--recheck", "--only", "links 8 --v", "--csv", tmp_path / "none.csv"], "has none of"),
        (["--size", "--again"], "--again has no use with it"),
        (["--size", "--only", "links 8", "--list-max", "5"], "--list-max has no use with it"),
        (["--size", "--only", "links 8 --v", "--recheck"], "--recheck has no use with it"),
        (["--size", "--figure", tmp_path / "g.png"], "--figure has no use with it"),
        (["--size", "--quick", "--only", "dof 1"], "give one of them"),
        (["--size", "--csv", other], "is not a records CSV"),
        (["--figure", tmp_path / "g.svg"], "must be a .png file"),
        (["--figure", other / "g.png"], "is not a folder"),
        (["--reverse-from", other], "use it with --recheck"),
        (["--recheck", "--only", "links 20 --h 4", "--reverse-from", other], "cannot be read as the JSON of a count"),
        (["--recheck", "--only", "links 20 --h 4", "--reverse-from", not_a_count], "is not the JSON of a count"),
        (["--recheck", "--only", "--h 4", "--reverse-from", a_count], f"chooses {h4_rows} rows"),
    ]
    for args, words in cases:
        p = _run(*args, "--md", tmp_path / "R.md") if "--md" not in args else _run(*args)
        assert p.returncode == 2, (args, p.stderr)
        assert p.stderr.count("\n") == 1 and words in p.stderr and "Traceback" not in p.stderr, (args, p.stderr)
    assert other.read_text() == "a,b\n1,2\n" and not (tmp_path / "R.md").exists()
    p = _run("--only", "no such query", "--csv", tmp_path / "r.csv", "--md", tmp_path / "R.md")
    assert p.returncode == 1 and "no row's query contains" in p.stderr
    assert not (tmp_path / "r.csv").exists()


def test_ctrl_c_stops_a_long_row_within_two_seconds_and_keeps_the_rows_written(tmp_path):
    import os
    import signal
    import time

    from tests.load import allowed_seconds

    csv_file = tmp_path / "r.csv"
    proc = subprocess.Popen([sys.executable, str(ROOT / "benchmarks" / "records.py"), "--only", "chains --dof 1 --links 20",
                             "--csv", str(csv_file), "--md", str(tmp_path / "R.md"), "--by-code", str(tmp_path)],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    # Ctrl-C once the 16-link count (about a minute of CPU) is running: its workers are started. A fixed
    # sleep (4 s) was not that under load: it could fall in records.py's or mechsynth's start-up, where
    # Ctrl-C meets Python's imports (a traceback, exit -2), not their handlers.
    deadline = time.monotonic() + allowed_seconds(120)
    while not _count_workers(proc.pid):
        assert proc.poll() is None and time.monotonic() < deadline, "the 16-link count did not start its workers"
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGINT)  # as a terminal's Ctrl-C: the whole process group
    start = time.monotonic()
    _, err = proc.communicate(timeout=60)
    assert time.monotonic() - start < allowed_seconds(2.0)
    assert proc.returncode == 130 and "interrupted" in err.splitlines()[-1] and "Traceback" not in err
    assert not csv_file.exists()  # no row finished, none written


def test_a_kill_stops_the_count_it_runs_and_leaves_no_folder(tmp_path):
    """A ``kill`` (SIGTERM) of records.py while its count runs: the count's command is stopped with it (it
    used to run on, orphaned, to its end, its temporary folder of units on disk meanwhile: the 20-link count
    for an hour), its folder is removed, and records.py still ends by SIGTERM."""
    import os
    import signal

    import psutil

    from tests.load import allowed_seconds

    temporary = tmp_path / "tmp"
    temporary.mkdir()
    proc = subprocess.Popen([sys.executable, str(ROOT / "benchmarks" / "records.py"), "--only", "chains --dof 1 --links 20",
                             "--csv", str(tmp_path / "r.csv"), "--md", str(tmp_path / "R.md"), "--by-code", str(tmp_path)],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=dict(os.environ, TMPDIR=str(temporary)))
    count = []
    try:
        deadline = time.monotonic() + allowed_seconds(120)
        while not (_count_workers(proc.pid) and list(temporary.glob("mechsynth-units-*"))):
            assert proc.poll() is None and time.monotonic() < deadline, "the 20-link count did not start its workers"
            time.sleep(0.05)
        count = psutil.Process(proc.pid).children(recursive=True)
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=allowed_seconds(60))
        _, alive = psutil.wait_procs(count, timeout=allowed_seconds(30))
    finally:
        for process in [proc, *count]:  # (nothing left running, whatever failed)
            try:
                process.kill()
            except psutil.NoSuchProcess:
                pass
    assert proc.returncode == -signal.SIGTERM and "Traceback" not in err, err
    assert not alive, "the count's command or its workers outlived records.py"
    assert not list(temporary.iterdir())


def _count_workers(pid: int) -> bool:
    """Whether the count that records.py (process ``pid``) runs has its worker processes (the children of
    its mechsynth child): both are then past their start-up, inside their Ctrl-C handlers."""
    import psutil

    try:
        return any(p.ppid() != pid for p in psutil.Process(pid).children(recursive=True))
    except psutil.NoSuchProcess:  # (a process that ended while it was read)
        return False


def _multiple_joint_row(records, links):
    row = next(r for r in records.ROWS if r.query == f"chains --dof 1 --links {links} --v 0..{links - 2}")
    return row, json.loads((ROOT / "benchmarks" / "records" / f"{row.slug}.json").read_text())


def _sample(links, every, found):
    """The codes and the recorded chains of every ``every``-th code of the plan, the first included."""
    from synth import ChainQuery
    from synth.synthesis.type_synthesis import plan_jobs

    codes = [str(code) for code, _ in plan_jobs(ChainQuery(1, links, v=(0, links - 2)))][::every]
    return f"{len(codes)} codes, {sum(found['by_code'].get(c, 0) for c in codes)} chains"


def test_the_count_with_the_kernels_off_checks_multiple_joints_code_by_code_and_reports_a_code_off():
    """At 10 links (2 645 chains, 49 codes) the second check passes on the recorded counts, whole and on a
    sample of the codes; one code off by one, or a code missing, is reported as a difference."""
    records = _records()
    row, found = _multiple_joint_row(records, 10)
    assert records.checks(row, found) == ("listing by code; kernels off by code", True)
    assert records.checks(row, found, list_max=0, second_every=4) == (
        f"kernels off by code (1 code in 4: {_sample(10, 4, found)})", True)
    off = dict(found, by_code=dict(found["by_code"], **{"6400/0-1": found["by_code"]["6400/0-1"] + 1}))
    assert records.checks(row, off, list_max=0) == ("KERNELS OFF DIFFERS", False)
    missing = dict(found, by_code={c: n for c, n in found["by_code"].items() if c != "5410/0"})
    assert records.checks(row, missing, list_max=0) == ("KERNELS OFF DIFFERS", False)
    simple = next(r for r in records.ROWS if r.query == "chains --dof 1 --links 10")
    assert records.checks(simple, {"count": 230, "by_code": {}}, list_max=0) == ("published", True)  # no 2nd check


def test_the_kernels_are_off_for_the_largest_multiple_joint_codes():
    """The second check's conventions turn off the kernels of both stages even at 16 links (where a count
    with multiple joints runs them from five loops on)."""
    from dataclasses import replace

    from synth import ChainQuery
    from synth.synthesis.stage_a import uses_kernel
    from synth.synthesis.type_synthesis import plan_jobs

    records = _records()
    jobs = plan_jobs(ChainQuery(1, 16, v=(0, 14)))
    assert all(uses_kernel(code, conv) for code, conv in jobs)
    assert not any(uses_kernel(code, replace(conv, kernel_loops=records._NO_KERNEL)) for code, conv in jobs)


def test_a_recheck_keeps_the_count_and_merges_the_checks(tmp_path):
    """--recheck checks a recorded count again without counting it: only the checks column changes."""
    for name in ("records.csv", "RECORDS.md"):
        (tmp_path / name).write_bytes((ROOT / "benchmarks" / name).read_bytes())
    def lines():
        with (tmp_path / "records.csv").open(newline="") as f:
            return list(csv.DictReader(f))

    before = lines()
    done = _run("--only", "links 8 --v 0..6", "--recheck", "--list-max", "0", "--reverse-max", "0", "--second-every", "2",
                "--csv", tmp_path / "records.csv", "--md", tmp_path / "RECORDS.md", "--by-code", tmp_path / "bc")
    assert done.returncode == 0, done.stderr
    after = lines()
    changed = [(a, b) for a, b in zip(before, after) if a != b]
    assert len(before) == len(after) and len(changed) == 1
    (was, now), = changed
    assert {k for k in was if was[k] != now[k]} == {"check"} and was["check"] == "oracle by code; listing by code"
    _, found = _multiple_joint_row(_records(), 8)
    assert now["check"] == f"listing by code; oracle by code; kernels off by code (1 code in 2: {_sample(8, 2, found)})"
    assert not (tmp_path / "bc").exists()  # no count was run, so no by-code file was written


@pytest.mark.parametrize("query, by_code, flags, method", [
    ("chains --dof 1 --links 20 --h 4", "dof_1_links_20_h_4.json", (), "tight-reverse"),
    ("chains --dof 1 --links 12 --v 0..10", "dof_1_links_12_v_0-10.json", ("--list-max", "0", "--second-max", "0"),
     "orbits")])
def test_a_second_count_run_beside_is_compared_code_by_code(tmp_path, query, by_code, flags, method):
    """--recheck --reverse-from: the second count read from its command's JSON (tight-reverse for simple joints, the
    count by orbits with multiple joints), compared code by code with the recorded count; one code off by one is
    reported and the exit status is 1."""
    for name in ("records.csv", "RECORDS.md"):
        (tmp_path / name).write_bytes((ROOT / "benchmarks" / name).read_bytes())
    recorded = json.loads((ROOT / "benchmarks" / "records" / by_code).read_text())
    same, off = tmp_path / "same.json", tmp_path / "off.json"
    same.write_text(json.dumps({"count": recorded["count"], "by_code": recorded["by_code"]}))
    code = next(iter(recorded["by_code"]))
    off.write_text(json.dumps({"count": recorded["count"] + 1,
                               "by_code": {**recorded["by_code"], code: recorded["by_code"][code] + 1}}))
    files = ("--csv", tmp_path / "records.csv", "--md", tmp_path / "RECORDS.md", "--by-code", tmp_path / "bc")

    def check():
        with (tmp_path / "records.csv").open(newline="") as f:
            return next(line for line in csv.DictReader(f) if line["query"] == query)["check"]

    done = _run("--only", query, "--recheck", *flags, "--reverse-from", same, *files)
    assert done.returncode == 0 and f"{method}: {recorded['count']} chains" in done.stderr, done.stderr
    assert f"{method} by code" in check().split("; ")
    done = _run("--only", query, "--recheck", *flags, "--reverse-from", off, *files)
    assert done.returncode == 1 and f"{method.upper()} DIFFERS" in check().split("; ")


def test_one_ternary_joint_rows_keep_the_oracles_chains_of_that_excess():
    """A row of exactly one ternary joint (``--v 1``) reads its query as v = (1, 1) and the brute force keeps only
    the chains whose joints' excess Σ (w − 2) is 1: at 8 links the engine's count by code passes the oracle and
    the listing, and the oracle's codes are those of compositions (1,) only."""
    records = _records()
    row = next(r for r in records.ROWS if r.query == "chains --dof 1 --links 8 --v 1")
    import synth

    found = synth.count_chains(1, 8, v=(1, 1)).to_dict()
    assert found["count"] > 0 and all(code.endswith("/1") for code in found["by_code"])
    assert set(key[1] for key in records.oracle_by_code(row)) == {(1,)}
    assert records.checks(row, found) == ("oracle by code; listing by code; kernels off by code", True)


def test_a_large_counts_small_codes_are_listed_one_by_one_and_a_code_off_is_named(tmp_path):
    """--list-codes-max: the codes of at most N chains of a count the listing does not check whole are listed
    one by one (W = 3 at 12 links, not fractionated, with --list-max 0: its codes of up to 300 chains), and a code
    off is named."""
    for name in ("records.csv", "RECORDS.md"):
        (tmp_path / name).write_bytes((ROOT / "benchmarks" / name).read_bytes())
    query = "chains --dof 3 --links 12 --no-fractionated"
    done = _run("--only", query, "--recheck", "--list-max", "0", "--list-codes-max", "300", "--reverse-max", "0",
                "--csv", tmp_path / "records.csv", "--md", tmp_path / "RECORDS.md")
    assert done.returncode == 0, done.stderr
    with (tmp_path / "records.csv").open(newline="") as f:
        line, = [x for x in csv.DictReader(f) if x["query"] == query]
    found = json.loads((ROOT / line["by_code_file"]).read_text())
    small = [n for n in found["by_code"].values() if 0 < n <= 300]
    assert 3 <= len(small) < len(found["by_code"])  # some codes listed, not all
    assert (f"listing by code on the {len(small)} codes of at most 300 chains ({sum(small)} chains)"
            in line["check"].split("; "))
    records = _records()
    row = next(r for r in records.ROWS if r.query == "chains --dof 1 --links 8")
    check, ok = records.checks(row, {"count": 17, "by_code": {"440/0": 3, "521/0": 14}}, list_max=0,
                               list_codes_max=5)
    assert not ok and check.endswith("LISTING DIFFERS on 1 of 1 codes (440/0)")


def test_the_doctests_of_records_py_run():
    """The examples of the script's docstrings (the sizing of a row, the figure's points) hold."""
    import doctest

    assert doctest.testmod(_records(), optionflags=doctest.ELLIPSIS).failed == 0


def test_size_prints_the_engines_estimate_beside_the_recorded_count_and_writes_nothing(tmp_path):
    """--size sizes each row chosen from exact counts at smaller sizes only, as the command line does before a
    long count, beside the count and CPU seconds recorded; rows too small for a basis say so."""
    csv_file = tmp_path / "records.csv"
    csv_file.write_bytes((ROOT / "benchmarks" / "records.csv").read_bytes())
    p = _run("--size", "--only", "dof 2 --links 11", "--csv", csv_file, "--md", tmp_path / "R.md",
             "--by-code", tmp_path / "bc")
    assert p.returncode == 0, p.stderr
    head, rule, *rows = p.stdout.splitlines()
    assert head.startswith("| query | chains, estimated | chains, recorded | error |") and rule.startswith("|---|")
    recorded = {line["query"]: line for line in csv.DictReader(csv_file.open(newline=""))}
    assert [r.split(" | ")[0] for r in rows] == ["| `chains --dof 2 --links 11`",
                                                  "| `chains --dof 2 --links 11 --no-fractionated`"]
    for r in rows:
        query, estimated, counted, error, _, cpu, _, basis = r.strip("| ").split(" | ")
        line = recorded[query.strip("`")]
        assert counted.replace(" ", "") == line["count"] and cpu == line["cpu_s"]
        assert 0.5 < int(estimated.replace(" ", "")) / int(line["count"]) < 2
        assert error == f"{int(estimated.replace(' ', '')) / int(line['count']) - 1:+.0%}"
        assert basis == "5, 7, 9 links"  # the row's own size is never counted
    assert p.stderr.count("sized `chains --dof 2 --links 11") == 2
    assert csv_file.read_bytes() == (ROOT / "benchmarks" / "records.csv").read_bytes()
    assert sorted(x.name for x in tmp_path.iterdir()) == ["records.csv"]  # no Markdown, figure or by-code file
    small = _run("--size", "--quick")
    assert small.returncode == 1 and small.stdout.count("fewer than three smaller sizes have chains") == 4
    whole = _run("--size", "--only", "chains --dof 2 --links 11")  # a whole query chooses its row alone
    assert [r.split(" | ")[0] for r in whole.stdout.splitlines()[2:]] == ["| `chains --dof 2 --links 11`"]


def test_the_figure_draws_every_row_of_the_csv_rows_added_later_included(tmp_path):
    """The growth figure is drawn from the CSV as it is: a row added to it (the 20-link W = 1 count, say) is a
    new point of its series; published values are kept beside the counts to be ringed; gear trains stay out."""
    records = _records()
    lines = records.read_csv(ROOT / "benchmarks" / "records.csv")
    lines = {query: line for query, line in lines.items() if query != "chains --dof 1 --links 20"}
    before = records.draw_growth(lines, tmp_path / "g.png")
    assert set(before) <= set(records.STYLES) and "h = 2 (Laman)" in before
    assert before["W = 1"][:3] == [(4, 1, 1), (6, 2, 2), (8, 16, 16)]
    assert sum(len(p) for p in before.values()) == sum(q.startswith("chains ") for q in lines)
    added = dict(lines, **{"chains --dof 1 --links 20": {"count": "123456789012"}})
    after = records.draw_growth(added, tmp_path / "g.png")
    assert after["W = 1"] == before["W = 1"] + [(20, 123456789012, None)]
    assert (tmp_path / "g.png").read_bytes()[:4] == b"\x89PNG" and not list(tmp_path.glob("*.tmp*"))
