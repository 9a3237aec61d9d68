"""The global search on the project's one Executor: each generation of the differential evolution is
evaluated by local worker processes (``workers``) or a Dask cluster (``scheduler``), the answer is the
same exact one, Ctrl-C ends the command within two seconds with no worker left, and contradictory or
unreachable choices are refused in one sentence."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from mechsynth.cli import main
from synth.dimension import FunctionTarget, synthesize
from synth.errors import DimensionError
from synth.execution import executor as executor_module
from synth.execution.scheduler import SchedulerUnreachable
from synth.structure.chain import Chain, Mechanism
from tests.load import allowed_seconds

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
#: Freudenstein's three precision points: every four-bar with the closed form's ratios meets them exactly
FUNCTION = FunctionTarget(np.radians([40, 60, 80]), np.radians([70, 85, 105]))


def _spy_on_map(monkeypatch) -> list:
    """Record the size of every batch of candidates the search hands to an Executor."""
    calls = []
    real = executor_module.Executor.map

    def spy(self, fn, items, **kwargs):
        items = list(items)
        calls.append((self.parallel, len(items)))
        return real(self, fn, items, **kwargs)

    monkeypatch.setattr(executor_module.Executor, "map", spy)
    return calls


def test_generations_are_evaluated_on_local_workers(monkeypatch):
    calls = _spy_on_map(monkeypatch)
    result = synthesize(FOUR_BAR, FUNCTION, budget=60, seed=0, workers=2)
    assert result.error_max < 1e-9 and result.met
    assert calls and all(parallel for parallel, _ in calls)
    # every candidate evaluated by the workers is counted (a generation is the population: 15 per unknown or more)
    assert result.evaluations >= sum(n for _, n in calls) >= 15


def test_one_worker_evaluates_in_this_process(monkeypatch):
    calls = _spy_on_map(monkeypatch)
    assert synthesize(FOUR_BAR, FUNCTION, budget=60, seed=0).error_max < 1e-9
    assert calls == []


@pytest.mark.slow  # a local Dask cluster takes seconds to start
def test_generations_are_evaluated_on_a_dask_cluster(monkeypatch):
    distributed = pytest.importorskip("distributed")
    calls = _spy_on_map(monkeypatch)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  host="127.0.0.1") as cluster:
        result = synthesize(FOUR_BAR, FUNCTION, budget=120, seed=0, scheduler=cluster.scheduler_address)
    assert result.error_max < 1e-9 and result.met and calls


def test_workers_with_a_scheduler_and_an_unreachable_scheduler_are_refused():
    with pytest.raises(DimensionError, match="contradict"):
        synthesize(FOUR_BAR, FUNCTION, budget=1, workers=2, scheduler="tcp://127.0.0.1:1")
    with pytest.raises(SchedulerUnreachable, match="cannot reach"):
        synthesize(FOUR_BAR, FUNCTION, budget=1, scheduler="tcp://127.0.0.1:1", connect_timeout=1)


@pytest.mark.parametrize("args, words", [
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "contradict"),
    (["--scheduler", "tcp://127.0.0.1:1"], "cannot reach the Dask scheduler"),
    (["--scheduler", "nonsense"], "not a Dask scheduler address"),
    (["--workers", "0"], "--workers"),
])
def test_the_command_refuses_bad_executor_choices_in_one_sentence(capsys, args, words):
    code = main(["dimension", str(ROOT / "models" / "dimension_function.csv"), "--mechanism", "0-1 1-2 2-3 3-0",
                 "--frame", "0", "--budget", "1", *args])
    err = capsys.readouterr().err
    assert code == 2 and words in err and err.count("\n") == 1, err


def test_ctrl_c_ends_a_search_on_two_workers_within_two_seconds_and_leaves_no_worker():
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([sys.executable, "-m", "mechsynth", "dimension", str(ROOT / "models" / "dimension_path.csv"),
                             "--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0", "--workers", "2", "--budget", "600",
                             "--crank", "--min-transmission", "89"],  # no four-bar meets it: the search runs on
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env, start_new_session=True)
    time.sleep(min(allowed_seconds(4.0), 15.0))  # the pool is up and the generations are running
    assert proc.poll() is None
    os.killpg(proc.pid, signal.SIGINT)
    start = time.monotonic()
    proc.wait(timeout=max(30.0, allowed_seconds(2.0)))
    stopped = time.monotonic() - start
    assert proc.returncode == 130 and stopped < allowed_seconds(2.0), stopped  # 2 s of an idle machine
    assert proc.stderr.read().decode().strip() == "mechsynth: interrupted"
    deadline = time.monotonic() + allowed_seconds(2.0)
    while True:  # the workers died with their parent: nothing of the session is left
        try:
            os.killpg(proc.pid, 0)
        except ProcessLookupError:
            break
        assert time.monotonic() < deadline, "a worker outlived the interrupted search"
        time.sleep(0.05)


def test_the_table_says_its_seconds_are_the_clocks_when_workers_searched(capsys):
    # with --workers 2 the table's 'CPU seconds 8.15' was the parent's wall clock (the command's whole CPU, parent
    # and workers, was 3.1 s under load): the budget is counted so, and the row now says it
    code = main(["dimension", str(ROOT / "models" / "dimension_function.csv"), "--mechanism", "0-1 1-2 2-3 3-0",
                 "--frame", "0", "--budget", "2", "--workers", "2"])
    out = capsys.readouterr().out
    assert code == 0 and "seconds (wall clock: the search ran on workers)" in out and "CPU seconds" not in out
    assert main(["dimension", str(ROOT / "models" / "dimension_function.csv"), "--mechanism", "0-1 1-2 2-3 3-0",
                 "--frame", "0", "--budget", "2"]) == 0
    assert "CPU seconds" in capsys.readouterr().out
