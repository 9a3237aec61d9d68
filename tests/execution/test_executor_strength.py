"""The pipeline of :func:`run_plan` without processes: tasks run when they are submitted and finish
in an order the test chooses, on a clock the units advance by a known time, so what is yielded,
how many tasks are in flight and how units are batched can be checked against the plan itself.
"""

from __future__ import annotations

import os
import random
import threading
import time
import types

import pytest

from synth.execution import executor as module
from synth.execution.executor import Executor, run_plan
from tests.load import allowed_seconds

UNIT = 1 / 64  # seconds a unit takes on the test's clock


class _Clock:
    def __init__(self):
        self.now = 100.0  # (not 0: durations are differences of its readings)

    def perf_counter(self):
        return self.now


@pytest.fixture
def clock(monkeypatch):
    c = _Clock()
    monkeypatch.setattr(module, "time", types.SimpleNamespace(perf_counter=c.perf_counter))
    return c


def _plan(sizes):
    return [[(i, u) for u in range(n)] for i, n in enumerate(sizes)]


def _expected(plan, skip_item=None, skip_unit=None):
    """What run_plan yields in plan order, from the plan alone."""
    out = []
    for i, units in enumerate(plan):
        if skip_item and skip_item(i):
            continue
        out += [(i, u, ("done", u)) for u in units if not (skip_unit and skip_unit(u))]
        out.append((i, None, len(units)))
    return out


class _Tasks:
    """submit(fn, arg) runs fn(arg) at once; next_done hands back the tasks in a chosen order."""

    def __init__(self, clock, order="fifo", seed=0):
        self.clock, self.order, self.rng = clock, order, random.Random(seed)
        self.launched, self.waiting, self.in_flight, self.most = [], [], 0, 0
        self.batches, self.worked = [], []

    def work(self, unit):
        self.worked.append(unit)
        self.clock.now += UNIT
        return ("done", unit)

    def submit(self, fn, arg):
        tasks = self

        class Task:
            def __init__(self):
                self.value, self.taken = fn(arg), False

            def ready(self):
                return True

            def get(self):
                if not self.taken:
                    self.taken = True
                    tasks.in_flight -= 1
                return self.value

        if fn is module._apply_batch:
            self.batches.append(len(arg[1]))
        task = Task()
        self.launched.append(task)
        self.waiting.append(task)
        self.in_flight += 1
        self.most = max(self.most, self.in_flight)
        return task

    def next_done(self):
        pick = {"fifo": 0, "lifo": -1}.get(self.order)
        return self.waiting.pop(self.rng.randrange(len(self.waiting)) if pick is None else pick)


@pytest.mark.parametrize("sizes", [[3], [0, 2, 0, 5], [40, 1, 17, 0, 64], [1] * 9])
@pytest.mark.parametrize("window", [1, 2, 5])
@pytest.mark.parametrize("task_seconds", [UNIT / 2, 4 * UNIT, 1000.0])
def test_in_order_the_pipeline_yields_the_plan_and_bounds_the_tasks_in_flight(clock, sizes, window, task_seconds):
    plan = _plan(sizes)
    tasks = _Tasks(clock)
    got = list(module._pipeline(list(enumerate(plan)), list, tasks.work, tasks.submit, None, window, task_seconds))
    assert got == _expected(plan)
    assert tasks.most <= window + 1  # the head's batch may go beyond a full window, by one
    assert sorted(tasks.worked) == sorted(u for units in plan for u in units)  # each unit worked on once


@pytest.mark.parametrize("order", ["fifo", "lifo", "random"])
@pytest.mark.parametrize("sizes", [[3], [0, 2, 0, 5], [40, 1, 17, 0, 64]])
@pytest.mark.parametrize("window", [1, 3])
def test_as_they_finish_every_unit_comes_once_and_before_its_item(clock, order, sizes, window):
    plan = _plan(sizes)
    tasks = _Tasks(clock, order, seed=sum(sizes) + window)
    got = list(module._pipeline(list(enumerate(plan)), list, tasks.work, tasks.submit, None, window, 4 * UNIT,
                                next_done=tasks.next_done))
    assert sorted(got, key=repr) == sorted(_expected(plan), key=repr)
    for i, units in enumerate(plan):
        where = got.index((i, None, len(units)))
        assert all(got.index((i, u, ("done", u))) < where for u in units)
    assert tasks.most <= window


def test_stage_a_s_task_works_on_the_first_units_then_batches_follow_the_time_per_unit(clock):
    # 100 units of 1/64 s and tasks of 1/8 s: stage A's task works on the first 8 (1/8 s), and once a
    # unit's time is known every batch holds 8; before that, one unit a batch
    plan = _plan([100])
    tasks = _Tasks(clock)
    got = list(module._pipeline(list(enumerate(plan)), list, tasks.work, tasks.submit, None, 2, 8 * UNIT))
    assert got == _expected(plan)
    first = tasks.launched[0].value
    assert first[0] == plan[0] and first[1] == [("done", (0, u)) for u in range(8)] and first[2] == 8 * UNIT
    known = tasks.batches[tasks.batches.index(8):]
    assert tasks.batches[0] == 1 and known[:-1] == [8] * (len(known) - 1) and 1 <= known[-1] <= 8
    assert sum(tasks.batches) == 92


@pytest.mark.parametrize("expansions", [1, 2])
def test_stage_a_waits_while_units_of_an_expanded_item_are_waiting(clock, expansions):
    # a count with a checkpoint (stage A's task works on no unit) and a wide window: the pool runs
    # tasks first come first served, so no more than `expansions` stage-A tasks may be submitted
    # before the first batch of units (a window of stage-A tasks held every unit of 8 items at once)
    plan = _plan([30] * 6)
    tasks = _Tasks(clock)
    kinds = []
    submit = lambda fn, arg: (kinds.append(fn is module._apply_batch), tasks.submit(fn, arg))[1]  # noqa: E731
    keep_all = lambda unit: False  # noqa: E731
    got = list(module._pipeline(list(enumerate(plan)), list, tasks.work, submit, keep_all, 8, 4 * UNIT,
                                next_done=tasks.next_done, expansions=expansions))
    assert sorted(got, key=repr) == sorted(_expected(plan), key=repr)
    assert kinds.index(True) == expansions  # the first batch follows the first expansions


def test_units_of_no_time_travel_512_a_batch(clock):
    plan = _plan([1500])
    tasks = _Tasks(clock)
    work = lambda unit: ("done", unit)  # noqa: E731 - no time on the clock
    keep_all = lambda unit: False  # noqa: E731 - (a filter of units: stage A's task then works on none)
    got = list(module._pipeline(list(enumerate(plan)), list, work, tasks.submit, keep_all, 2, 0.05))
    assert got == _expected(plan)
    assert tasks.batches[:3] == [1, 1, 512] and max(tasks.batches) == 512


def test_skipped_units_are_not_worked_on_and_still_counted(clock):
    plan = _plan([6, 4, 5])
    skip = lambda unit: unit[1] % 2 == 0  # noqa: E731
    tasks = _Tasks(clock)
    got = list(module._pipeline(list(enumerate(plan)), list, tasks.work, tasks.submit, skip, 2, 4 * UNIT))
    assert got == _expected(plan, skip_unit=skip)
    assert all(not skip(u) for u in tasks.worked)
    assert all(task.value[1] == [] for task in tasks.launched if len(task.value) == 3)  # stage A worked on none


def test_a_plan_runs_inline_on_one_worker_with_skips(clock):
    plan = _plan([3, 2, 4, 1])
    skip_item = lambda i: i == 1  # noqa: E731
    skip_unit = lambda unit: unit == (2, 0) or unit == (3, 0)  # noqa: E731
    tasks = _Tasks(clock)
    got = list(run_plan(plan, list, tasks.work, skip_item=skip_item, skip_unit=skip_unit))
    assert got == _expected(plan, skip_item, skip_unit)


def _pool_of_two(clock, monkeypatch, submitted: list | None = None):
    """A two-worker executor whose submissions run on the hand-driven tasks (each also noted in
    ``submitted`` if given): (tasks, executor)."""
    tasks = _Tasks(clock)
    executor = Executor(workers=2)

    def submit(fn, arg, done=None):
        if submitted is not None:
            submitted.append((fn, arg))
        return tasks.submit(fn, arg)
    monkeypatch.setattr(executor, "_submit", submit)
    return tasks, executor

def test_the_inline_phase_hands_an_unfinished_item_to_the_pool(clock, monkeypatch):
    # two workers: units run here for inline_seconds (4 units of 1/64 s), then the rest of that item and the
    # later items go to the pool; the answer is the plan's either way
    plan = _plan([6, 3])
    tasks, executor = _pool_of_two(clock, monkeypatch)
    got = list(run_plan(plan, list, tasks.work, executor=executor, inline_seconds=4 * UNIT, task_seconds=UNIT))
    assert got == _expected(plan)
    assert tasks.worked[:4] == [(0, 0), (0, 1), (0, 2), (0, 3)] and len(tasks.launched) > 0
    inline = Executor(workers=1)
    monkeypatch.setattr(inline, "_submit", lambda fn, arg, done=None: pytest.fail("one worker started a task"))
    assert list(run_plan(plan, list, tasks.work, executor=inline, inline_seconds=0.0)) == _expected(plan)


def test_map_on_one_worker_is_the_builtin_map():
    assert Executor().workers == 1 and not Executor().parallel  # by default everything runs in this process
    with Executor(workers=1) as executor:
        assert not executor.parallel and executor.slots == 1
        assert list(executor.map(abs, [-3, 2, -1], ordered=False, window=1, chunk=2)) == [3, 2, 1]
    assert Executor(workers=2).parallel and Executor(workers=3).slots == 3


# ------------------------------------------------------------------ Dask, stood in for
class _Future:
    """A Dask future whose task ran at submission; ``late`` waits time out before its result comes."""

    def __init__(self, value, late=0):
        self.value, self.late, self.waits = value, late, []

    def result(self, timeout):
        self.waits.append(timeout)
        if self.late:
            self.late -= 1
            raise TimeoutError
        if isinstance(self.value, Exception):
            raise self.value
        return self.value

    def done(self):
        return True

    def add_done_callback(self, callback):
        callback(self)


class _Client:
    """A Dask client: runs a task when it is submitted; ``nthreads`` per worker; ``infos`` are the
    successive answers of ``scheduler_info`` (an exception is raised)."""

    def __init__(self, nthreads=None, infos=(), late=0):
        self.threads = {"tcp://a:1": 2, "tcp://b:1": 1} if nthreads is None else nthreads
        self.infos, self.late = list(infos), late
        self.submitted, self.cancelled = [], []

    def submit(self, fn, arg, pure=True):
        try:
            value = fn(arg)
        except Exception as exc:  # noqa: BLE001 - raised where the result is read, as Dask does
            value = exc
        future = _Future(value, self.late)
        self.submitted.append((fn, arg, pure, future))
        return future

    def nthreads(self):
        return self.threads

    def scheduler_info(self):
        info = self.infos.pop(0)
        if isinstance(info, Exception):
            raise info
        return info

    def cancel(self, futures):
        self.cancelled.extend(futures)


def _fail_on_three(x):
    if x == 3:
        raise ValueError("three")
    return x


def test_on_dask_map_runs_every_task_on_the_cluster_in_order_and_as_they_finish():
    client = _Client()
    executor = Executor(workers=1, client=client)  # the workers are ignored with a client
    assert executor.parallel and executor.slots == 3
    assert list(executor.map(abs, range(-5, 5), chunk=3)) == [abs(x) for x in range(-5, 5)]
    assert [arg[1] for _, arg, _, _ in client.submitted] == [[-5, -4, -3], [-2, -1, 0], [1, 2, 3], [4]]
    assert all(fn is module._apply_batch and pure is False for fn, _, pure, _ in client.submitted)  # never merged
    assert sorted(executor.map(abs, range(-4, 0), ordered=False)) == [1, 2, 3, 4]
    assert Executor(client=_Client(nthreads={})).slots == 1  # a cluster without threads yet: one slot


def test_on_dask_a_task_error_is_raised_and_the_tasks_in_flight_are_cancelled():
    client = _Client()
    executor = Executor(client=client)
    with pytest.raises(ValueError, match="three"):
        list(executor.map(_fail_on_three, [3, 4, 5], window=10))
    futures = [future for *_, future in client.submitted]
    assert len(futures) == 3 and client.cancelled == futures[1:]  # the failed task's own is no longer in flight


def test_a_dask_result_late_past_the_liveness_interval_asks_for_workers_then_comes():
    client = _Client(infos=[{"workers": {"a": {}}}, {"workers": {"a": {}}}], late=2)
    executor = Executor(client=client)
    assert list(executor.map(abs, [-7])) == [7]
    [(*_, future)] = client.submitted
    assert future.waits == [module.LIVENESS_SECONDS] * 3 and module.LIVENESS_SECONDS == 30.0
    assert client.infos == []  # asked twice, once per wait that timed out


def test_a_cluster_without_workers_at_two_checks_in_a_row_is_one_sentence():
    from synth.execution.scheduler import SchedulerUnreachable

    alive = module._Liveness(_Client(infos=[{"workers": {}}, {"workers": {"a": {}}}, {"workers": {}}, {}]))
    alive()  # empty once: a nanny restarting its worker
    alive()  # workers again: the count starts over
    alive()
    with pytest.raises(SchedulerUnreachable) as refused:
        alive()  # (no workers listed at all is empty too)
    assert str(refused.value) == ("the Dask cluster has had no workers for 60 s: its units cannot run (start workers, "
                                  "or run without a scheduler)")
    gone = module._Liveness(_Client(infos=[ConnectionResetError("reset")]))
    with pytest.raises(SchedulerUnreachable) as refused:
        gone()
    assert str(refused.value) == "the Dask scheduler stopped answering (ConnectionResetError)"


def test_waiting_for_the_next_finished_task_checks_the_workers_between_waits(monkeypatch):
    import queue

    monkeypatch.setattr(module, "LIVENESS_SECONDS", 0.01)
    done, checks = queue.SimpleQueue(), []

    def alive():
        checks.append(1)
        if len(checks) == 3:
            done.put("task")

    assert module._next_done(done, alive) == "task" and len(checks) == 3
    done.put("next")
    assert module._next_done(done, None) == "next"


def test_on_dask_there_is_no_inline_phase_and_tasks_aim_at_half_a_second(clock):
    """With a client every unit runs on the cluster (none in this process first), stage A's task works on
    the first units for 0.5 s (32 units of 1/64 s), and at most 8 tasks a thread are in flight."""
    plan = _plan([100, 3])
    client = _Client()
    worked = []

    def work(unit):
        worked.append(unit)
        clock.now += UNIT
        return ("done", unit)

    executor = Executor(client=client)
    assert list(run_plan(plan, list, work, executor=executor, inline_seconds=1e9)) == _expected(plan)
    fns = [fn for fn, *_ in client.submitted]
    assert fns[0] is module._expand_and_work and client.submitted[0][1][3] == 0.5
    _, first, _ = client.submitted[0][3].value
    assert len(first) == 32
    assert len(worked) == 103 and fns.count(module._expand_and_work) == 2


# ------------------------------------------------------------------ the pool's workers
def test_a_worker_leaves_ctrl_c_to_its_parent_and_dies_with_it(monkeypatch):
    """In this process, with the calls a worker makes stood in for: SIGINT and SIGHUP ignored, SIGTERM blocked and
    read by a thread of its own (which obeys the parent's only), the kernel asked to kill it with
    SIGKILL when its parent dies (PR_SET_PDEATHSIG = 1), and an orphan exits at once."""
    import ctypes
    import signal
    import threading

    calls = []

    class Libc:
        def prctl(self, option, value):
            calls.append(("prctl", option, value))

    class Thread:
        def __init__(self, target, args, daemon, name):
            calls.append(("thread", target, args, daemon))

        def start(self):
            pass

    monkeypatch.setattr(module.signal, "signal", lambda sig, action: calls.append(("signal", sig, action)))
    monkeypatch.setattr(module.signal, "pthread_sigmask", lambda how, sigs: calls.append(("mask", how, set(sigs))))
    monkeypatch.setattr(threading, "Thread", Thread)
    monkeypatch.setattr(module.signal, "set_wakeup_fd", lambda fd: calls.append(("wakeup", fd)))
    monkeypatch.setattr(ctypes, "CDLL", lambda name: Libc())
    monkeypatch.setattr(module.os, "getppid", lambda: 4242)
    monkeypatch.setattr(module.os, "_exit", lambda status: calls.append(("exit", status)))
    module._worker_start(4242)
    assert calls == [("signal", signal.SIGINT, signal.SIG_IGN), ("signal", signal.SIGHUP, signal.SIG_IGN),
                     ("signal", signal.SIGTERM, signal.SIG_DFL),
                     ("mask", signal.SIG_BLOCK, {signal.SIGTERM}), ("thread", module._obey_parent_only, (4242, None), True),
                     ("wakeup", -1), ("prctl", 1, signal.SIGKILL)]
    calls.clear()
    module._worker_start(1)  # the parent died before prctl took effect: the worker is an orphan
    assert calls[-1] == ("exit", 1)


def _worker_settings(_):
    import ctypes
    import signal

    death = ctypes.c_int(0)
    ctypes.CDLL(None).prctl(2, ctypes.byref(death))  # PR_GET_PDEATHSIG
    wakeup = signal.set_wakeup_fd(-1)  # (the worker's own, returned: -1 when it holds none)
    return signal.getsignal(signal.SIGINT) is signal.SIG_IGN, death.value, os.getppid(), wakeup


def test_pool_workers_are_forked_ignore_ctrl_c_and_die_with_this_process():
    """… and do not keep this process's wake-up pipe for signals (set here as the Ctrl-C watcher sets it)."""
    import signal

    read, write = os.pipe()
    os.set_blocking(write, False)
    previous = signal.set_wakeup_fd(write)
    try:
        with Executor(workers=2) as executor:
            assert set(executor.map(_worker_settings, range(4))) == {(True, signal.SIGKILL, os.getpid(), -1)}
            assert executor._pool._ctx.get_start_method() == "fork"
    finally:
        signal.set_wakeup_fd(previous)
        os.close(read)
        os.close(write)
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])  # Ctrl-C no longer held back


def _pid(_):
    return os.getpid()


def test_a_worker_ignores_a_sigterm_that_is_not_its_parents():
    """A SIGTERM from another process (a group's ``kill``) leaves the workers working; the pool's own
    terminate, SIGTERM from this process, ends them all."""
    import signal
    import subprocess

    import psutil

    with Executor(workers=2) as executor:
        workers = [psutil.Process(pid) for pid in set(executor.map(_pid, range(8)))]
        for worker in workers:
            subprocess.run(["kill", "-TERM", str(worker.pid)], check=True)
        assert sorted(executor.map(abs, range(-40, 0))) == list(range(1, 41))  # the workers work on
        assert all(w.is_running() and w.status() != psutil.STATUS_ZOMBIE for w in workers)
    _, alive = psutil.wait_procs(workers, timeout=30)
    assert not alive
    assert signal.SIGTERM not in signal.pthread_sigmask(signal.SIG_BLOCK, [])  # (this process's mask untouched)


def _sleep(seconds):
    time.sleep(seconds)
    return seconds


def test_the_pools_sigterm_merged_with_a_group_one_still_ends_a_worker(monkeypatch):
    """Standard signals do not queue: a worker's SIGTERM from elsewhere (a group's ``kill``) still pending
    when the pool ends the worker merges with the pool's and reads as the foreign one.  Made here by
    stopping the worker (SIGSTOP) while both are sent; before the ``stopping`` flag, the worker ignored the
    merged signal and ``terminate`` waited for its 600-s task (the suite's intermittent hang)."""
    import signal
    import subprocess

    import psutil

    pool = module.process_pool(1)
    (worker,) = pool._pool
    sent = threading.Event()
    kill = os.kill

    def spy(pid, signum):
        kill(pid, signum)
        if pid == worker.pid and signum == signal.SIGTERM:
            sent.set()

    monkeypatch.setattr(os, "kill", spy)
    pool.apply_async(_sleep, (600,))
    time.sleep(0.5)  # (the task under way: the queue's lock is free)
    kill(worker.pid, signal.SIGSTOP)
    stopped = psutil.Process(worker.pid)
    while stopped.status() != psutil.STATUS_STOPPED:  # (both SIGTERMs are to arrive while it is stopped)
        time.sleep(0.01)
    subprocess.run(["kill", "-TERM", str(worker.pid)], check=True)  # pending, from another process
    ending = threading.Thread(target=pool.terminate, daemon=True)
    ending.start()
    assert sent.wait(allowed_seconds(30))  # the pool's own SIGTERM, merged with the pending one
    kill(worker.pid, signal.SIGCONT)
    ending.join(allowed_seconds(30))
    assert not ending.is_alive() and worker.exitcode in (-signal.SIGTERM, 128 + signal.SIGTERM)


def _large_result(seconds):
    time.sleep(seconds)
    return b"x" * 1_000_000  # far more than a pipe holds: its worker sends it holding the queue's lock


def test_a_pool_ends_while_its_workers_send_results_larger_than_a_pipe():
    """A result larger than a pipe holds is sent holding the result queue's lock, the worker waiting for a
    reader; ``terminate`` stops its result thread first, so a worker ended then kept that lock for ever and
    the pool's task thread (or ``terminate`` itself), posting its sentinel, waited for it for ever
    (cpython#96995: 1 run in 300 of a 2-worker listing onto a full disk or a closed pipe hung so).  Six
    workers finish such tasks as their pool ends, 20 times: before :class:`~synth.execution.executor._Ending`,
    5 series of 10 such ends out of 5 hung."""
    rng = random.Random(7)
    for _ in range(20):
        pool = module.process_pool(6)
        for _ in range(24):
            pool.apply_async(_large_result, (rng.uniform(0, 0.003),))
        time.sleep(rng.uniform(0, 0.003))
        ending = threading.Thread(target=lambda: (pool.terminate(), pool.join()), daemon=True)
        ending.start()
        ending.join(allowed_seconds(30))
        assert not ending.is_alive(), "the pool's end waits for a lock a worker held as it was ended"
        assert all(worker.exitcode is not None for worker in pool._pool)


def test_ctrl_c_is_held_back_while_the_workers_are_forked(monkeypatch):
    import multiprocessing
    import signal

    seen = []

    def new_pool(ctx, workers):
        seen.append((ctx, workers, signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, [])))
        return "pool"

    monkeypatch.setattr(multiprocessing, "get_context", lambda method: method)
    monkeypatch.setattr(module, "_new_pool", new_pool)
    assert module.process_pool(3) == "pool"
    assert seen == [("fork", 3, True)]
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])  # and released afterwards
    seen.clear()
    monkeypatch.setattr(module.sys, "platform", "darwin")  # elsewhere than Linux, fork is not safe: spawn
    module.process_pool(2)
    assert seen[0][0] == "spawn"


def test_a_ctrl_c_another_thread_receives_is_held_back_too(monkeypatch):
    """Blocking SIGINT in the forking thread does not hold it back while another thread runs (the progress
    lines): the signal reaches that thread and Python runs the handler in this one, inside the fork's
    handlers, where the KeyboardInterrupt was printed and dropped (a Ctrl-C to records.py's 16-link count
    was lost so).  Now it is raised once the workers are forked, the pool ended first."""
    import signal
    import threading

    raised_inside, go, sent = [], threading.Event(), threading.Event()

    def send():
        go.wait()
        os.kill(os.getpid(), signal.SIGINT)
        sent.set()

    # started before the pool, as the progress lines are: its signal mask lets SIGINT in
    sender = threading.Thread(target=send, daemon=True)
    sender.start()

    def new_pool(ctx, workers):
        try:
            go.set()
            sent.wait()
            for _ in range(200):  # bytecodes, where Python runs a handler
                time.sleep(0.001)
        except KeyboardInterrupt:
            raised_inside.append(True)
            raise
        return pool

    pool = types.SimpleNamespace(terminated=False)
    pool.terminate = lambda: setattr(pool, "terminated", True)
    monkeypatch.setattr(module, "_new_pool", new_pool)
    before = signal.getsignal(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        module.process_pool(2)
    assert raised_inside == [] and signal.getsignal(signal.SIGINT) is before
    assert pool.terminated  # (the caller never holds it: its workers are ended here)


def test_on_a_pool_skipped_units_are_not_run_and_tasks_aim_at_50_ms(clock, monkeypatch):
    # no inline phase: stage A's task works on the first units for 0.05 s (a pool's tasks; Dask's are 0.5 s),
    # except where units are skipped (a checkpoint): then every unit goes through the filter here
    plan = _plan([10, 4])
    submitted = []
    tasks, executor = _pool_of_two(clock, monkeypatch, submitted)
    assert list(run_plan(plan, list, tasks.work, executor=executor, inline_seconds=0.0)) == _expected(plan)
    assert submitted[0][0] is module._expand_and_work and submitted[0][1][3] == 0.05
    skip = lambda unit: unit[1] % 3 == 0  # noqa: E731
    tasks.worked.clear()
    got = list(run_plan(plan, list, tasks.work, executor=executor, inline_seconds=0.0, skip_unit=skip))
    assert got == _expected(plan, skip_unit=skip) and tasks.worked and not any(skip(u) for u in tasks.worked)


def test_the_inline_phase_hands_the_last_item_unfinished_to_the_pool(clock, monkeypatch):
    # the inline phase's time runs out inside the last item of the plan: its other units still go to the pool
    plan = _plan([2, 6])
    tasks, executor = _pool_of_two(clock, monkeypatch)
    got = list(run_plan(plan, list, tasks.work, executor=executor, inline_seconds=4 * UNIT, task_seconds=UNIT))
    assert got == _expected(plan)
    assert tasks.worked[:4] == [(0, 0), (0, 1), (1, 0), (1, 1)] and sum(tasks.batches) == 4


def _units_of(item):
    return list(item)


def _slow_first(unit):
    time.sleep(1.0 if unit == (0, 0) else 0.0)
    return ("done", unit)


def test_a_plan_run_as_units_finish_on_a_pool_is_not_held_back_by_a_slow_unit():
    """ordered=False on a pool of two workers: the other items' units and ends come while item 0's one
    unit (a second long) still runs; everything comes once, each unit before its item's end."""
    plan = _plan([1, 3, 2])
    with Executor(workers=2) as executor:
        got = list(run_plan(plan, _units_of, _slow_first, executor=executor, inline_seconds=0.0, ordered=False))
    assert sorted(got, key=repr) == sorted(_expected(plan), key=repr)
    assert got.index((1, None, 3)) < got.index((0, (0, 0), ("done", (0, 0))))
    for i, units in enumerate(plan):
        assert all(got.index((i, u, ("done", u))) < got.index((i, None, len(units))) for u in units)


def test_an_unordered_map_on_a_cluster_that_lost_its_workers_is_one_sentence_not_a_hang(monkeypatch):
    from synth.execution.scheduler import SchedulerUnreachable

    class Stuck(_Future):  # a task that never finishes: its done-callback is never called
        def add_done_callback(self, callback):
            pass

    client = _Client(infos=[{"workers": {}}, {"workers": {}}])
    client.submit = lambda fn, arg, pure=True: Stuck(None)
    monkeypatch.setattr(module, "LIVENESS_SECONDS", 0.01)
    outcome = []

    def run():  # (in a thread: a map that waits for ever fails this test instead of hanging it)
        try:
            list(Executor(client=client).map(abs, range(3), ordered=False))
        except SchedulerUnreachable as exc:
            outcome.append(str(exc))

    waiting = threading.Thread(target=run, daemon=True)
    waiting.start()
    waiting.join(allowed_seconds(5.0))
    assert outcome and "has had no workers" in outcome[0] and client.infos == []


def test_a_run_in_plan_order_keeps_no_finished_task_and_fills_eight_tasks_a_thread(clock):
    """In plan order no task is told to announce its end (a queue of finished tasks that nobody reads would
    keep every result of a long listing); as they finish, every task is.  At most 8 tasks a thread of the
    cluster are in flight (3 threads: 24), and a long plan fills them."""
    plan = _plan([1] * 60)

    class Counted(_Client):
        def __init__(self):
            super().__init__()
            self.announced, self.read, self.most = 0, 0, 0

        def submit(self, fn, arg, pure=True):
            future = super().submit(fn, arg, pure)
            counted, unread = self, future.result

            def result(timeout):
                counted.read += 1
                return unread(timeout)

            def announce(callback):
                counted.announced += 1
                callback(future)

            future.result, future.add_done_callback = result, announce
            future.done = lambda: False  # (a task not known to be finished: later items' tasks are launched)
            self.most = max(self.most, len(self.submitted) - self.read)
            return future

    for ordered in (True, False):
        client = Counted()
        got = list(run_plan(plan, list, lambda unit: ("done", unit), executor=Executor(client=client), ordered=ordered))
        assert sorted(got, key=repr) == sorted(_expected(plan), key=repr)
        assert client.announced == (0 if ordered else len(client.submitted))
        if ordered:
            assert client.most == 24
