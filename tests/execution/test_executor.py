"""The one executor: Executor.map inline, on a pool and on Dask — order, window, chunks, errors, shutdown."""

from __future__ import annotations

import os
import time

import psutil
import pytest

from synth.execution.executor import Executor


def _square(x):
    return x * x


def _pid(_):
    return os.getpid()


def _late_for_zero(x):
    """0 takes a second, the others no time: an unordered map yields the others first."""
    time.sleep(1.0 if x == 0 else 0.0)
    return x


def _fail_on_three(x):
    if x == 3:
        raise ValueError("three")
    return x


@pytest.mark.parametrize("chunk", [1, 3, 50])
@pytest.mark.parametrize("window", [None, 1, 2])
def test_pool_map_in_order_is_the_inline_map(chunk, window):
    items = list(range(23))
    with Executor(2) as executor:
        assert list(executor.map(_square, iter(items), window=window, chunk=chunk)) == [x * x for x in items]


@pytest.mark.parametrize("chunk, window", [(1, 3), (4, 3), (1, 10)])
def test_unordered_map_yields_each_result_once_as_tasks_finish(chunk, window):
    # (a window of 3 takes the slow task while submitting, one of 10 after every task is submitted)
    with Executor(2) as executor:
        found = list(executor.map(_late_for_zero, range(8), ordered=False, chunk=chunk, window=window))
    assert sorted(found) == list(range(8))
    if chunk == 1:
        assert found[0] != 0  # the slow first task did not hold the others back


def test_one_worker_runs_inline_and_starts_no_pool(monkeypatch):
    import synth.execution.executor as ex

    monkeypatch.setattr(ex, "process_pool", lambda workers: pytest.fail("a pool was started"))
    with Executor(1) as executor:
        assert not executor.parallel
        assert set(executor.map(_pid, range(5))) == {os.getpid()}


def test_pool_starts_on_first_use_and_close_ends_its_workers():
    executor = Executor(2)
    before = {p.pid for p in psutil.Process().children()}
    assert executor._pool is None  # nothing started yet: a query that stays inline pays nothing
    pids = set(executor.map(_pid, range(8)))
    assert os.getpid() not in pids and 1 <= len(pids) <= 2
    workers = [p for p in psutil.Process().children() if p.pid not in before]
    assert {p.pid for p in workers} >= pids
    executor.close()
    _, alive = psutil.wait_procs(workers, timeout=5)
    assert not alive


def test_a_task_error_is_raised_where_the_results_are_read():
    with Executor(2) as executor:
        with pytest.raises(ValueError, match="three"):
            list(executor.map(_fail_on_three, range(6), ordered=False))
        assert list(executor.map(_square, range(3))) == [0, 1, 4]  # the executor is still usable


def test_the_window_bounds_the_tasks_in_flight(monkeypatch):
    import synth.execution.executor as ex

    submitted, taken = [], []
    real_submit, real_take = Executor._submit, Executor._take

    def submit(self, fn, arg, done=None):
        submitted.append(arg)
        return real_submit(self, fn, arg, done)

    def take(self, flight, done):
        taken.append(len(flight))
        return real_take(self, flight, done)

    monkeypatch.setattr(ex.Executor, "_submit", submit)
    monkeypatch.setattr(ex.Executor, "_take", take)
    with Executor(2) as executor:
        assert list(executor.map(_square, range(20), window=3)) == [x * x for x in range(20)]
    assert len(submitted) == 20 and max(taken) == 3


def test_map_on_a_dask_cluster_in_order_and_as_finished():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            executor = Executor(client=client)
            assert executor.slots == 2 and executor.parallel
            assert list(executor.map(_square, range(10), chunk=3)) == [x * x for x in range(10)]
            assert sorted(executor.map(_square, range(10), ordered=False)) == sorted(x * x for x in range(10))
            with pytest.raises(ValueError, match="three"):
                list(executor.map(_fail_on_three, range(6)))
