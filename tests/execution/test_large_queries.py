"""Large queries: streamed execution, resumable counts (real SIGKILL), Dask, size estimates and refusals.

No test here measures time: processes are killed when they *say* they have committed, and
every assertion is about results, exit statuses and messages.
"""

from __future__ import annotations

import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
import types

import psutil
import pytest

import synth
from synth.execution import executor as _executor
from synth.synthesis.type_synthesis import count_chains, count_mechanisms
from synth.execution.checkpoint import CheckpointMismatch
from synth.errors import QueryTooLarge
from synth.synthesis.estimate import estimate

from .servers import local_server

CLI = [sys.executable, "-m", "mechsynth"]


def _run(*args, **kwargs):
    return subprocess.run([*CLI, *args], capture_output=True, text=True, **kwargs)


# ---------------------------------------------------------------- executor
def _units(item):
    return list(range(item))


def _square(x):
    return x * x


def _slow_square(x):
    time.sleep(0.004)
    return x * x


def _pool2(*args, **kwargs) -> list:
    """Every event of run_plan on an executor of two local workers, closed after it."""
    with _executor.Executor(2) as executor:
        return list(_executor.run_plan(*args, executor=executor, **kwargs))


# task_seconds: None (stage A's worker works on every unit of these small items), 1e-9 (on none:
# every unit goes out in a batch), and a slow work of which the worker does a few, the rest batched
_FUSION = [(None, _square), (1e-9, _square), (0.01, _slow_square)]


@pytest.mark.parametrize("task_seconds, work", _FUSION)
@pytest.mark.parametrize("window", [1, 2, 64])
def test_pool_pipeline_keeps_plan_order(window, task_seconds, work):
    items = [3, 0, 5, 1, 4]
    inline = list(_executor.run_plan(items, _units, _square))
    pooled = _pool2(items, _units, work, inline_seconds=0, window=window, task_seconds=task_seconds)
    assert pooled == inline
    assert [e for e in inline if e[1] is None] == [(0, None, 3), (1, None, 0), (2, None, 5), (3, None, 1), (4, None, 4)]


def test_inline_phase_hands_the_rest_of_an_item_to_the_pool(monkeypatch):
    import itertools

    ticks = itertools.count()
    monkeypatch.setattr(_executor.time, "perf_counter", lambda: float(next(ticks)))  # a clock that counts calls
    items = [5, 3]
    events = _pool2(items, _units, _square, inline_seconds=3)
    assert events == list(_executor.run_plan(items, _units, _square))


@pytest.mark.parametrize("task_seconds, work", _FUSION)
@pytest.mark.parametrize("window", [1, 3, 64])
def test_unordered_pipeline_yields_every_unit_before_its_item(window, task_seconds, work):
    items = [3, 0, 5, 1, 4, 7, 2]
    events = _pool2(items, _units, work, inline_seconds=0, window=window, ordered=False,
                    task_seconds=task_seconds)
    assert sorted(events, key=repr) == sorted(_executor.run_plan(items, _units, _square), key=repr)
    closed = {index: k for k, (index, unit, _) in enumerate(events) if unit is None}
    assert all(k < closed[index] for k, (index, unit, _) in enumerate(events) if unit is not None)


def test_stage_a_task_works_on_the_first_units_for_its_budget():
    expand_and_work = _executor._expand_and_work
    assert expand_and_work((_units, _square, 4, 10.0))[:2] == ([0, 1, 2, 3], [0, 1, 4, 9])
    assert expand_and_work((_units, _square, 4, 0.0))[:2] == ([0, 1, 2, 3], [])
    units, results, seconds = expand_and_work((_units, _slow_square, 50, 0.01))
    assert units == list(range(50)) and 1 <= len(results) < 50 and results == [u * u for u in units[:len(results)]]
    assert seconds >= 0.01


def _square_but_zero(x):
    assert x != 0, "a skipped unit was run"
    return x * x


def test_skipped_items_and_units_are_not_run():
    items = [3, 2]
    events = _pool2(items, _units, _square_but_zero, inline_seconds=0, skip_item=lambda i: i == 1,
                    skip_unit=lambda u: u == 0)
    assert events == [(0, 1, 1), (0, 2, 4), (0, None, 3)]


def test_small_query_starts_no_pool(monkeypatch):
    """A query done within the inline budget (50 ms) starts no pool.  The budget is counted here in
    this process's CPU time, which a busy machine does not stretch as it stretches wall time (the
    16 chains of 8 links take 15 ms of it); the query runs once before, so that its imports are
    not in it."""
    def no_pool(workers):
        raise AssertionError("a pool was started for a small query")

    assert count_chains(1, 8, workers=1)["count"] == 16
    monkeypatch.setattr(_executor, "time", types.SimpleNamespace(perf_counter=time.process_time))
    monkeypatch.setattr(_executor, "process_pool", no_pool)
    assert count_chains(1, 8, workers=2)["count"] == 16


def test_pool_and_inline_counts_agree():
    inline = count_chains(1, 10, workers=1)
    # inline_seconds=0 through run_plan: every code goes to the pool
    events = _pool2([1], _units, _square, inline_seconds=0)
    assert events == [(0, 0, 0), (0, None, 1)]
    assert count_chains(1, 10, workers=2) == inline
    assert count_mechanisms(1, 8, workers=2) == count_mechanisms(1, 8, workers=1)


def test_listing_through_the_pool_is_the_inline_listing(monkeypatch):
    from synth.synthesis import type_synthesis as _type_synthesis

    inline = [c.certificate for c in synth.type_synthesis(1, 10, v="0..2", workers=1)]
    monkeypatch.setattr(_type_synthesis, "_INLINE_SECONDS", 0.0)  # every unit goes to the pool
    assert [c.certificate for c in synth.type_synthesis(1, 10, v="0..2", workers=2)] == inline
    assert count_chains(1, 10, v="0..2", workers=2)["count"] == len(inline)


# --------------------------------------------------------------- checkpoint
def _kill_after_first_commit(args, env=None):
    """Start a counting run, SIGKILL it as soon as it reports a commit; return its pool workers."""
    proc = subprocess.Popen([*CLI, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        for line in proc.stderr:
            if "committed in this run" in line:
                break
        else:
            pytest.fail("the run ended without reporting a commit")
        workers = psutil.Process(proc.pid).children()
        os.kill(proc.pid, signal.SIGKILL)  # if it finished first, the resumed run simply finds every unit done
        proc.wait()
    finally:
        proc.kill()
        proc.stdout.close()
        proc.stderr.close()
    return workers


def _kill_while_a_code_is_half_done(args, checkpoint, env, attempts=5) -> int:
    """SIGKILL a counting run while its checkpoint holds units of a code not complete (watched
    every 10 ms; a code's completion replaces its unit rows by its total, so the moment can be
    missed: tried again on a new file); return those units."""

    def partial_units() -> int:
        try:
            with sqlite3.connect(checkpoint, timeout=1) as conn:
                return conn.execute("SELECT COUNT(*) FROM units").fetchone()[0]
        except sqlite3.OperationalError:  # (not created yet)
            return 0

    for _ in range(attempts):
        for name in (checkpoint, checkpoint + "-wal", checkpoint + "-shm"):
            if os.path.exists(name):
                os.remove(name)
        proc = subprocess.Popen([*CLI, *args], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        try:
            while proc.poll() is None and not partial_units():
                time.sleep(0.01)
            proc.kill()
            proc.wait()
        finally:
            proc.kill()
        if partial_units():
            return partial_units()
    return 0


@pytest.mark.parametrize("workers", ["1", "2"])
def test_checkpoint_resumes_after_sigkill(tmp_path, workers):
    query = ["chains", "--dof", "1", "--links", "12", "--count", "--workers", workers]
    reference = _run(*query)
    assert reference.returncode == 0
    ck = str(tmp_path / "count.sqlite")
    # (the killed run's units are kept beside its checkpoint, in tmp_path; TMPDIR too, to be sure)
    children = _kill_after_first_commit([*query, "--checkpoint", ck], env=dict(os.environ, TMPDIR=str(tmp_path)))
    _, alive = psutil.wait_procs(children, timeout=60)
    assert not alive, "pool workers outlived their killed parent"
    resumed = _run(*query, "--checkpoint", ck)
    assert resumed.returncode == 0, resumed.stderr
    assert resumed.stdout == reference.stdout
    first = resumed.stderr.splitlines()[0]
    done_before = int(first.split(", ")[-1].split()[0])
    assert done_before > 0, first
    again = _run(*query, "--checkpoint", ck)  # everything done: nothing runs, same answer
    assert again.stdout == reference.stdout
    assert not os.path.exists(ck + ".units")  # the stage A kept for the resumed run, removed once it ended


def test_a_code_larger_than_the_window_is_spilled_and_read_back_whole(tmp_path):
    """Stage A for a count hands on the same units as the listing's stage A, a code of more than
    the window through a file that the pipeline removes once it has read it."""
    from synth.execution.spill import Spilled
    from synth.structure.query import ChainQuery
    from synth.synthesis.type_synthesis import _StreamedUnits, job_units, plan_jobs

    expand = _StreamedUnits(str(tmp_path), 3)
    spilled = 0
    for job in plan_jobs(ChainQuery(1, 12)):
        units = expand(job)
        assert sorted(u.key for u in units) == sorted(u.key for u in job_units(job))
        if len(units) > 3:
            assert isinstance(units, Spilled) and os.path.exists(units.path)
            spilled += 1
            events = _pool2([job], _StreamedUnits(str(tmp_path), 3), _count_keys, inline_seconds=0)
            assert sorted(unit.key for _, unit, _ in events if unit is not None) == sorted(u.key for u in units)
            units.remove()
        else:
            assert isinstance(units, list)
    assert spilled >= 5
    assert not list(tmp_path.iterdir())  # every file read through by the pipeline was removed by it


def _count_keys(unit):
    return {unit.key: 1}


def test_a_tiny_window_counts_the_same_and_resumes_without_double_counting(tmp_path):
    """Counts by code with a window of 2 units (MECHSYNTH_UNIT_WINDOW) are those of the default
    window; killed while a code is half done (its units committed one by one), the rerun skips those
    units and gives the same counts: no unit lost or counted twice; no spilled file is left once a
    run ends."""
    query = ["chains", "--dof", "1", "--links", "14", "--count", "--workers", "2"]
    env = dict(os.environ, MECHSYNTH_CACHE="off", TMPDIR=str(tmp_path))
    tiny = dict(env, MECHSYNTH_UNIT_WINDOW="2")
    reference = _run(*query, env=env)
    assert reference.returncode == 0 and json.loads(reference.stdout)["count"] == 318162
    assert _run(*query, env=tiny).stdout == reference.stdout
    assert not list(tmp_path.glob("mechsynth-units-*"))  # removed by the runs that ended
    ck = str(tmp_path / "count.sqlite")
    assert _kill_while_a_code_is_half_done([*query, "--checkpoint", ck], ck, env=tiny) > 0
    killed_runs_folders = set(tmp_path.glob("mechsynth-units-*"))
    resumed = _run(*query, "--checkpoint", ck, env=tiny)
    assert resumed.returncode == 0, resumed.stderr
    assert resumed.stdout == reference.stdout
    assert int(resumed.stderr.splitlines()[0].split(", ")[-1].split()[0]) > 0
    assert set(tmp_path.glob("mechsynth-units-*")) <= killed_runs_folders  # the resumed run left none
    assert not os.path.exists(ck + ".units")  # nor any of the units kept beside the checkpoint
    bad = _run(*query, env=dict(env, MECHSYNTH_UNIT_WINDOW="0"))
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "MECHSYNTH_UNIT_WINDOW" in bad.stderr


def _pool_at_work(proc, folder) -> list:
    """The workers of the count ``proc`` once its pool works and its temporary folder of units is made in
    ``folder`` (the moment a kill is to land in)."""
    workers = []
    while proc.poll() is None and not (workers and list(folder.glob("mechsynth-units-*"))):
        time.sleep(0.01)
        workers = psutil.Process(proc.pid).children()
    assert proc.poll() is None, "the count ended before it could be stopped"
    return workers


@pytest.mark.parametrize("group", [False, True], ids=["kill-pid", "kill-group"])
def test_sigterm_stops_a_count_cleanly(tmp_path, group):
    """A ``kill`` (SIGTERM) of a count working on the pool, its temporary folder of units made: the
    workers end, the folder is removed, one line, status 143 (SIGTERM's default used to end the
    process at once and leave the folder behind, 115 MB after one long count).  Sent to the whole
    process group (``timeout``, a batch system), the workers leave it to their parent: killed while
    reading the pool's queue, they would leave its lock held and the parent waiting for ever."""
    env = dict(os.environ, MECHSYNTH_CACHE="off", TMPDIR=str(tmp_path))
    query = ["chains", "--dof", "1", "--links", "16", "--count", "--workers", "2", "--force"]
    proc = subprocess.Popen([*CLI, *query], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=group)
    try:
        workers = _pool_at_work(proc, tmp_path)
        if group:
            os.killpg(proc.pid, signal.SIGTERM)
        else:
            proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 143 and out == "" and err == "mechsynth: terminated\n", err
    _, alive = psutil.wait_procs(workers, timeout=30)
    assert not alive, "pool workers outlived the terminated count"
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP], ids=["SIGTERM", "SIGHUP"])
def test_a_kill_of_a_script_counting_leaves_no_folder(tmp_path, signum):
    """``count_chains`` in a script with no handler of its own (benchmarks/bycode.py, a notebook's kernel):
    a ``kill`` while its pool works removes the temporary folder of units (the signal's default used to end
    the process at once and leave the folder behind), ends the workers, and still ends the process by
    that signal."""
    env = dict(os.environ, MECHSYNTH_CACHE="off", TMPDIR=str(tmp_path))
    script = "import synth; synth.count_chains(1, 16, workers=2)"
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=env)
    try:
        workers = _pool_at_work(proc, tmp_path)
        proc.send_signal(signum)
        _, err = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == -signum and "Traceback" not in err, err
    _, alive = psutil.wait_procs(workers, timeout=30)
    assert not alive, "pool workers outlived the count"
    assert not list(tmp_path.iterdir())


def test_checkpoint_commit_keeps_the_order_of_units_and_codes(tmp_path):
    """Unit rows are written in runs between complete codes: a code's units recorded before it
    completes are gone with it, those of a code still running stay."""
    from synth.execution.checkpoint import Checkpoint

    path = tmp_path / "c.sqlite"
    with Checkpoint(path, "plan", "q", every=1e9) as ck:  # one commit, at the code's completion
        ck.add_unit("a|1", "a", 2)
        ck.add_unit("b|1", "b", 3)
        ck.add_unit("a|2", "a", 4)
        ck.finish_code("a", 6, units=2)
        ck.add_unit("b|2", "b", 5)
    again = Checkpoint(path, "plan", "q")
    assert again.codes == {"a": 6} and again.units == {"b|1": ("b", 3), "b|2": ("b", 5)}


def test_checkpoint_belongs_to_one_query(tmp_path):
    ck = tmp_path / "count.sqlite"
    assert count_chains(1, 8, workers=1, checkpoint=ck) == count_chains(1, 8, workers=1)
    with pytest.raises(CheckpointMismatch):
        count_chains(1, 10, workers=1, checkpoint=ck)
    with pytest.raises(CheckpointMismatch):
        count_mechanisms(1, 8, workers=1, checkpoint=ck)
    out = _run("chains", "--dof", "1", "--links", "8", "--v", "0..2", "--count", "--checkpoint", str(ck))
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.startswith("mechsynth: the checkpoint") and "belongs to another query" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
    bad = tmp_path / "not.sqlite"
    bad.write_text("not a database")
    out = _run("chains", "--dof", "1", "--links", "8", "--count", "--checkpoint", str(bad))
    assert out.returncode == 2 and "not a usable checkpoint" in out.stderr and "Traceback" not in out.stderr


@pytest.mark.parametrize("args, words", [
    (["--checkpoint", "x.sqlite"], "--checkpoint goes with --count"),
    (["--scheduler", "tcp://127.0.0.1:1"], "--scheduler goes with --count"),
    (["--count", "--scheduler", "tcp://127.0.0.1:1", "--workers", "2"], "contradict"),
])
def test_contradictory_options(args, words, tmp_path):
    out = _run("chains", "--dof", "1", "--links", "8", *args, cwd=tmp_path)
    assert out.returncode == 2 and words in out.stderr and len(out.stderr.strip().splitlines()) == 1


# -------------------------------------------------------------------- Dask
@pytest.mark.parametrize("command", [["chains", "--dof", "1", "--links", "8", "--count"], ["grid", "GRID", "--db", "DB"]])
@pytest.mark.parametrize("address", ["nonsense", "tcp://127.0.0.1:1", "tcp://host:99999"])
def test_bad_scheduler_is_one_sentence(command, address, tmp_path):
    grid = tmp_path / "g.toml"
    grid.write_text('dof = 1\nlinks = "4..6"\n')
    command = [str(grid) if a == "GRID" else str(tmp_path / "a.sqlite") if a == "DB" else a for a in command]
    out = _run(*command, "--scheduler", address, "--timeout", "1")
    assert out.returncode == 2 and out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mechsynth: ") and "Exception" not in out.stderr, out.stderr


def test_an_endpoint_that_answers_something_else_is_one_sentence_and_leaves_no_file(tmp_path):
    """A proxy's HTTP reply, read by Dask as the length of a frame, asked Dask for 3 EiB
    (a MemoryError traceback, then a ten-second close of the half-built Client)."""
    checkpoint = tmp_path / "c.sqlite"
    with local_server(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n") as port:
        out = _run("chains", "--dof", "1", "--links", "8", "--count", "--scheduler", f"tcp://127.0.0.1:{port}",
                   "--checkpoint", str(checkpoint), "--timeout", "2", timeout=60)
    assert out.returncode == 2 and out.stdout == "" and not checkpoint.exists()
    assert out.stderr.startswith("mechsynth: ") and "not as a Dask scheduler" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr


def test_a_cluster_without_workers_is_one_sentence_not_a_hang(monkeypatch):
    """Dask waits for ever for workers that never come; the count says so instead (two checks)."""
    distributed = pytest.importorskip("distributed")
    from synth.execution.scheduler import SchedulerUnreachable
    from synth.execution import executor

    monkeypatch.setattr(executor, "LIVENESS_SECONDS", 0.5)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        cluster.scale(0)
        with distributed.Client(cluster) as client:
            deadline = time.monotonic() + 30
            while client.scheduler_info()["workers"] and time.monotonic() < deadline:
                time.sleep(0.1)
        with pytest.raises(SchedulerUnreachable, match="no workers"):
            count_chains(1, 10, scheduler=cluster.scheduler_address)


def test_count_on_a_dask_cluster(tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        assert count_chains(1, 10, scheduler=address) == count_chains(1, 10, workers=1)
        ck = tmp_path / "dask.sqlite"
        out = _run("chains", "--dof", "1", "--links", "10", "--v", "0..2", "--count", "--scheduler", address,
                   "--checkpoint", str(ck))
        assert out.returncode == 0, out.stderr
        assert json.loads(out.stdout) == count_chains(1, 10, v="0..2", workers=1).to_dict()


# ----------------------------------------------------------- size and refusal
def test_estimate_of_14_links_from_smaller_counts():
    found = estimate(synth.ChainQuery(1, 14), budget=600)  # the basis is then 8, 10, 12 links on any machine
    assert found.basis == "exact counts at 8, 10, 12 links"
    assert abs(found.chains - 318162) / 318162 < 0.05
    assert found.units > 271 and found.seconds > 0


def test_giant_query_is_refused_with_an_estimate():
    out = _run("chains", "--dof", "1", "--links", "40", "--count")
    assert out.returncode == 2 and out.stdout == ""
    line = out.stderr.strip()
    assert "\n" not in line and line.startswith("mechsynth: this query (40 links) is too large")
    assert "chains" in line and "units" in line and "years" in line and "--force" in line


@pytest.mark.parametrize("checkpoint", [None, "c.sqlite"])
def test_a_long_query_says_so_before_it_starts(monkeypatch, capsys, checkpoint):
    # a query under the day's limit runs unasked, but one of more than NOTE_SECONDS says how long
    # it will take (here: 16 links against a limit of one second, so the run itself is not started)
    import argparse

    from mechsynth.commands import chains
    from synth.synthesis import estimate

    monkeypatch.setattr(estimate, "NOTE_SECONDS", 1.0)
    args = argparse.Namespace(code=None, links=16, force=False, count=True, h=3, v=None, scheduler=None,
                              workers=2, format=None, checkpoint=checkpoint, what="chains")
    chains._size_note(synth.ChainQuery(1, 16), args)
    note = capsys.readouterr().err.strip()
    assert note.startswith("mechsynth: a long query: about ") and "on 2 workers" in note and "\n" not in note
    assert ("give --checkpoint FILE" in note) == (checkpoint is None)


def test_large_listing_as_a_table_is_refused():
    out = _run("chains", "--dof", "1", "--links", "18", "--force")
    assert out.returncode == 2 and "--format jsonl or csv" in out.stderr and "\n" not in out.stderr.strip()


def test_model_too_large_is_refused_even_when_forced():
    with pytest.raises(QueryTooLarge):
        synth.count_chains(1, 24, workers=1)
    out = _run("chains", "--dof", "1", "--links", "24", "--count", "--force")
    assert out.returncode == 2 and "branch vertices" in out.stderr and "\n" not in out.stderr.strip()


def test_projection_is_exact_when_every_unit_is_sampled():
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "benchmarks" / "bench_projection.py"
    spec = importlib.util.spec_from_file_location("bench_projection", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    full = module.project(1, 10, codes=10**3, units=10**6, seed=0)
    assert (full["chains_projected"], full["chains_se"], full["units_projected"], full["units_se"]) == (230, 0, 16, 0)
    part = module.project(1, 10, codes=4, units=2, seed=0)  # a real sample: an estimate with an error bar
    assert part["codes_sampled"] == 4 and part["chains_se"] > 0


def test_projection_cache_is_written_whole_and_reused(tmp_path, monkeypatch):
    """--cache: one write at the end (atomic, no partial file left), read back by the next seed."""
    import importlib.util
    import pickle
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "benchmarks" / "bench_projection.py"
    spec = importlib.util.spec_from_file_location("bench_projection", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    cache = tmp_path / "plans.pkl"
    writes = []
    real = Path.write_bytes
    monkeypatch.setattr(Path, "write_bytes", lambda self, data: writes.append(self.name) or real(self, data))
    first = module.project(1, 10, codes=10**3, units=10**6, seed=0, cache=str(cache))
    assert writes == ["plans.pkl.partial"] and cache.exists() and not (tmp_path / "plans.pkl.partial").exists()
    assert len(pickle.loads(cache.read_bytes())) == first["codes_sampled"]
    again = module.project(1, 10, codes=10**3, units=10**6, seed=1, cache=str(cache))
    assert writes == ["plans.pkl.partial"]  # every code read from the file: nothing new to write
    assert again["chains_projected"] == first["chains_projected"] == 230
