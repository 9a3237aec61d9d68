"""Progress where stderr is not a terminal: a plain line a minute (not nothing, not a line a step)."""

import io
import subprocess
import sys

import synth
from synth.execution import progress as _progress
from synth.execution.progress import Every, Progress

from .test_large_queries import CLI


class Clock:
    """A clock the test moves by hand."""

    def __init__(self):
        self.now = 1000.0

    def __call__(self):
        return self.now


def test_plain_lines_come_once_a_minute_with_the_time_to_go():
    log, clock = io.StringIO(), Clock()
    progress = Progress(10, "trees", desc="census", stream=log, clock=clock)
    for _ in range(3):
        clock.now += 10
        progress.update(1, trains=7)
    assert log.getvalue() == ""  # 30 s: nothing yet
    clock.now += 30
    progress.update(1, trains=3)  # 60 s, 4 of 10 done: 90 s to go at 15 s a tree
    clock.now += 59
    progress.update(1)  # too soon after the last line
    assert log.getvalue() == "census: 4/10 trees, 24 trains; 60 s elapsed, about 90 s to go at the rate so far\n"
    clock.now += 1
    progress.update(0, trains=1)
    assert log.getvalue().splitlines()[-1] == "census: 5/10 trees, 25 trains; 2 min elapsed, about 2 min to go at the rate so far"
    clock.now += 5
    progress.update(5)
    progress.close()  # a log that has lines ends with the final state
    assert log.getvalue().splitlines()[-1] == "census: 10/10 trees, 25 trains; 2 min elapsed"
    assert len(log.getvalue().splitlines()) == 3


def test_a_short_run_writes_nothing_and_an_unknown_total_gives_no_time_to_go():
    log, clock = io.StringIO(), Clock()
    with Progress(None, "units", desc="run", stream=log, clock=clock) as progress:
        progress.update(3)
    assert log.getvalue() == ""  # finished within the minute: no line, and none at the close
    with Progress(None, "units", desc="run", stream=log, clock=clock, every=5) as progress:
        clock.now += 6
        progress.update(2)
    assert log.getvalue() == "run: 2 units; 6 s elapsed\n"  # the close repeats nothing already said


def test_every_lets_the_first_line_through_then_one_a_period():
    lines, clock = [], Clock()
    say = Every(lines.append, 60, clock=clock)
    for step in range(200):  # one line a second for 200 s
        say(f"commit {step}")
        clock.now += 1
    assert lines == ["commit 0", "commit 60", "commit 120", "commit 180"]
    say.flush()  # the last line, held back, is the final state
    assert lines[-1] == "commit 199"
    say.flush()
    assert len(lines) == 5  # written once


def test_a_count_logs_codes_units_and_chains_where_stderr_is_a_file(monkeypatch):
    monkeypatch.setattr(_progress, "LOG_EVERY", 0.0)  # a line at every step
    log = io.StringIO()
    monkeypatch.setattr(sys, "stderr", log)
    assert synth.count_chains(1, 10, workers=1, progress=True)["count"] == 230
    lines = log.getvalue().splitlines()
    assert lines[-1].startswith("mechsynth: 7/7 codes, ") and lines[-1].endswith(" s elapsed")
    last = lines[-1].split(";")[0].split(", ")
    assert last[1].endswith(" units") and last[2] == "230 chains"
    assert all(line.startswith("mechsynth: ") and "elapsed" in line for line in lines)


def test_a_batch_count_with_a_checkpoint_logs_its_first_commit_not_every_one(tmp_path):
    err = tmp_path / "count.err"
    with err.open("w") as f:  # stderr a file, as in a batch job
        done = subprocess.run([*CLI, "chains", "--dof", "1", "--links", "12", "--count", "--workers", "1",
                               "--checkpoint", str(tmp_path / "c.sqlite")], stdout=subprocess.PIPE, stderr=f,
                              text=True, timeout=600)
    assert done.returncode == 0
    committed = [line for line in err.read_text().splitlines() if "committed in this run" in line]
    codes = len(synth.plan_codes(1, 12))
    # the first commit, then (the run is shorter than a minute) only the last, held back until the end
    assert len(committed) == 2 and all(line.startswith("mechsynth: checkpoint ") for line in committed)
    assert f"({codes} codes complete) committed in this run, 0 units done before" in committed[-1]


def test_the_line_comes_on_time_while_no_step_ends(tmp_path):
    """A step may take an hour (stage A of a 20-link code): the line a period is written all the same,
    by the thread, to the file, and the thread ends with the progress."""
    import threading
    import time

    path = tmp_path / "run.err"
    with path.open("w") as stream:
        progress = Progress(3, "codes", desc="mechsynth", every=0.2, stream=stream)
        progress.update(0, chains=12)  # before the first period: no line
        time.sleep(0.9)  # no step ends
        progress.close()
    lines = path.read_text().splitlines()
    assert len(lines) >= 2 and all(line.startswith("mechsynth: 0/3 codes, 12 chains; ") for line in lines)
    assert not any(t.name == "progress-lines" for t in threading.enumerate())


def test_the_time_to_go_is_reckoned_from_the_chains_an_estimate_expects():
    log, clock = io.StringIO(), Clock()
    progress = Progress(100, "codes", desc="mechsynth", stream=log, clock=clock, expected=("chains", 1000.0))
    clock.now += 60
    progress.update(50, chains=250)  # half the codes, a quarter of the chains: 3 minutes to go, not 1
    clock.now += 60
    progress.update(50, chains=900)
    assert log.getvalue().splitlines() == [
        "mechsynth: 50/100 codes, 250 chains; 60 s elapsed, about 3 min to go if the chains are the 1 000 estimated",
        "mechsynth: 100/100 codes, 1 150 chains; 2 min elapsed, past the 1 000 chains estimated"]


def test_a_count_with_multiple_joints_reckons_its_time_to_go_from_the_units():
    """The chains a unit holds fall by orders of magnitude along a count with multiple joints (the 16-link count
    said hours where minutes were left): its line reckons from the units an estimate expects, and says so; once
    every code is done it gives no time to go, short of the estimate as it may be."""
    from synth.structure.query import ChainQuery
    from synth.synthesis.estimate import Estimate

    found = Estimate(chains=6.9e9, units=8_511_997, seconds=2e4, basis="exact counts at 8, 10, 12 links")
    expected = synth.time_to_go_from(ChainQuery(1, 16, v=(0, 14)), found)
    log, clock = io.StringIO(), Clock()
    progress = Progress(10, "codes", desc="mechsynth", stream=log, clock=clock, expected=expected)
    clock.now += 60
    progress.update(2, units=3_000_000, chains=5_000_000_000)  # 72 % of the chains (23 s to go), 35 % of the units
    clock.now += 60
    progress.update(8, units=5_000_000, chains=1_700_000_000)  # every code done, 6 % short of the units
    assert log.getvalue().splitlines() == [
        "mechsynth: 2/10 codes, 3 000 000 units, 5 000 000 000 chains; 60 s elapsed, about 110 s to go if the "
        "units are the 8 511 997 estimated",
        "mechsynth: 10/10 codes, 8 000 000 units, 6 700 000 000 chains; 2 min elapsed"]
    assert synth.time_to_go_from(ChainQuery(1, 16), found) == ("chains", 6.9e9)  # simple joints: as before


def test_a_forced_long_count_still_says_its_estimate_before_it_starts():
    """--force skips the refusal, not the estimate (the 20-link count's log began with nothing)."""
    proc = subprocess.Popen([*CLI, "chains", "--dof", "1", "--links", "20", "--count", "--force", "--workers", "1"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = proc.stderr.readline()
    finally:
        proc.kill()
        proc.communicate()
    assert first.startswith("mechsynth: a long query: about ") and "e+11 chains in " in first and " on 1 worker, " in first
    assert first.rstrip().endswith("(give --checkpoint FILE to make it resumable)")


def test_the_gear_census_script_logs_no_line_per_tree_to_a_file(tmp_path):
    """The opposite fault: a script that printed one line per tree into a redirected stderr."""
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "benchmarks" / "gears_two_methods_by_tree.py"
    err = tmp_path / "census.err"
    with err.open("w") as f:
        done = subprocess.run([sys.executable, str(script), str(tmp_path / "log.jsonl"), "--dof", "1", "--links", "7",
                               "--sample", "5", "--seed", "3"], stdout=subprocess.PIPE, stderr=f, text=True,
                              timeout=300)
    assert done.returncode == 0
    assert err.read_text().splitlines() == ["F=1, 7 links: 5 of 59 trees, 0 in the log"]  # a short run: no progress line


def test_a_resumed_run_shows_the_whole_count_and_its_own_rate():
    """A run resumed from a checkpoint starts from what the runs before it did: its line reads the whole count's
    codes and chains, and the time to go is this run's rate (the 16-link count resumed with 6.05e9 of an estimated
    6.9e9 chains said '12.5 h to go', reckoned as if the chains of this run were all)."""
    log, clock = io.StringIO(), Clock()
    progress = Progress(100, "codes", desc="mechsynth", stream=log, clock=clock, expected=("chains", 1000.0),
                        before={"steps": 40, "chains": 600, "units": 0})
    clock.now += 60
    progress.update(10, chains=100)  # 300 chains to go at 100 a minute
    clock.now += 60
    progress.update(0, chains=400)
    log2, clock2 = io.StringIO(), Clock()
    steps = Progress(100, "codes", desc="mechsynth", stream=log2, clock=clock2, before={"steps": 40})
    clock2.now += 60
    steps.update(20)  # 40 codes to go at 20 a minute
    assert log.getvalue().splitlines() + log2.getvalue().splitlines() == [
        "mechsynth: 50/100 codes, 700 chains; 60 s elapsed, about 3 min to go if the chains are the 1 000 estimated",
        "mechsynth: 50/100 codes, 1 100 chains; 2 min elapsed, past the 1 000 chains estimated",
        "mechsynth: 60/100 codes; 60 s elapsed, about 2 min to go at the rate so far"]


def test_a_count_resumed_from_its_checkpoint_logs_the_whole_count(monkeypatch, tmp_path):
    import sqlite3

    path = tmp_path / "c.sqlite"
    assert synth.count_chains(1, 10, workers=1, checkpoint=path)["count"] == 230
    with sqlite3.connect(path) as db:  # one code lost, as if the run had been stopped before it
        lost = db.execute("SELECT code, count, units FROM codes ORDER BY count DESC").fetchone()
        db.execute("DELETE FROM codes WHERE code = ?", lost[:1])
    monkeypatch.setattr(_progress, "LOG_EVERY", 0.0)
    log = io.StringIO()
    monkeypatch.setattr(sys, "stderr", log)
    assert synth.count_chains(1, 10, workers=1, progress=True, checkpoint=path)["count"] == 230
    last = log.getvalue().splitlines()[-1].split(";")[0].split(", ")
    units = synth.count_chains(1, 10, workers=1).units_run
    assert last == ["mechsynth: 7/7 codes", f"{units} units", "230 chains"], (lost, last)


def test_the_time_to_go_script_reads_a_count_in_parts_back(tmp_path):
    """benchmarks/time_to_go.py: a count stopped and resumed (the first part's lines count that part alone, as
    before 30 Nov 2026; the second's the whole count), the time really left and what each predictor said."""
    from pathlib import Path

    first, second = tmp_path / "part1.log", tmp_path / "part2.log"
    first.write_text("mechsynth: a long query: about 1e+06 chains in 1 000 units, 3 min on 2 workers, …\n"
                     "mechsynth: 1/4 codes, 200 units, 600 000 chains; 60 s elapsed, about 40 s to go if …\n"
                     "mechsynth: 2/4 codes, 300 units, 700 000 chains; 2 min elapsed, about 51 s to go if …\n")
    second.write_text("mechsynth: checkpoint c.sqlite: 1 units (0 codes complete) committed in this run, "
                      "300 units done before\n"
                      "mechsynth: 3/4 codes, 800 units, 950 000 chains; 60 s elapsed\n"
                      "mechsynth: 4/4 codes, 1 000 units, 1 000 000 chains; 2 min elapsed\n")
    script = Path(__file__).resolve().parents[2] / "benchmarks" / "time_to_go.py"
    done = subprocess.run([sys.executable, str(script), str(first), str(second), "--every", "1"],
                          capture_output=True, text=True, timeout=60)
    rows = [line for line in done.stdout.splitlines() if line.startswith("| 1 ") or line.startswith("| 2 ")]
    # 3 min left at the first line (1 min of part 1, 2 of part 2): 40 s by the chains, 4 min by the units
    assert rows == ["| 1 | 1 min | 200 | 600,000 | 3 min | 1 min | 4 min | 4 min |",
                    "| 1 | 2 min | 300 | 700,000 | 2 min | 1 min | 5 min | 5 min |",
                    "| 2 | 1 min | 800 | 950,000 | 1 min | 0 min | 0 min | 0 min |"], done.stdout
    # off by 3, 2, 1 (the chains; 40 s and 51 s taken as the lines' minute) and 4/3, 7/3, 1 (the units)
    assert "chains: off by a median factor 2.00, at most 3.0, within a factor 2 at 2 of 3 lines" in done.stdout
    assert "units: off by a median factor 1.33, at most 2.3, within a factor 2 at 2 of 3 lines" in done.stdout
    refused = subprocess.run([sys.executable, str(script), str(first)], capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and refused.stderr.count("\n") == 1 and "did not end by itself" in refused.stderr
