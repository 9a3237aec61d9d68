"""Ctrl-C for a search, in this process: the watcher is installed once, from the main thread only,
never over someone else's wakeup descriptor, and stops a running search at once.
"""

from __future__ import annotations

import os
import select
import signal
import threading
import time

import pytest

from synth.execution import interrupt
from synth.execution.interrupt import solve_stoppably
from tests.load import allowed_seconds


class _Slow:
    """A search of ``seconds`` that reports whether it was stopped."""

    def __init__(self, seconds):
        self.seconds, self.stopped, self.seen = seconds, False, None

    def solve(self, model, callback=None):
        self.seen = (model, callback, dict(interrupt._RUNNING))
        end = time.monotonic() + self.seconds
        while time.monotonic() < end and not self.stopped:
            time.sleep(0.005)
        return "UNKNOWN" if self.stopped else "OPTIMAL"

    def stop_search(self):
        self.stopped = True


def test_a_search_is_known_while_it_runs_and_answers_its_status():
    search = _Slow(0.0)
    before = time.monotonic()
    assert solve_stoppably(search, "model", "callback") == "OPTIMAL"
    model, callback, running = search.seen
    assert (model, callback) == ("model", "callback")
    assert before <= running[search] <= time.monotonic()  # when it began
    assert search not in interrupt._RUNNING  # and forgotten once it ended


def test_a_search_that_fails_is_forgotten_too():
    class Failing:
        def solve(self, model, callback=None):
            raise ValueError("invalid model")

    failing = Failing()
    with pytest.raises(ValueError):
        solve_stoppably(failing, None)
    assert failing not in interrupt._RUNNING


class _Blocking:
    """A search that waits in C without the GIL's signal checks, as CP-SAT does: SIGINT is blocked in
    this thread (the kernel hands it to another), and only ``stop_search`` ends the wait."""

    def __init__(self, seconds):
        self.seconds, self.stopped = seconds, False
        self._read, self._write = os.pipe()

    def solve(self, model, callback=None):
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            select.select([self._read], [], [], self.seconds)
        finally:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
        return "UNKNOWN" if self.stopped else "OPTIMAL"

    def stop_search(self):
        self.stopped = True
        os.write(self._write, b"x")


@pytest.fixture
def watcher(monkeypatch):
    """The watcher of this process: a process forked from one that had it (mutation testing forks each
    mutant's tests from the process that ran the tests first) has no thread but the flag, so it is
    made a fresh process's state, where the first search installs the watcher."""
    if not any(t.name == "cp-sat-ctrl-c" and t.is_alive() for t in threading.enumerate()):
        monkeypatch.setattr(interrupt, "_watching", False)
        signal.set_wakeup_fd(-1)
    solve_stoppably(_Slow(0.0), None)
    assert any(t.name == "cp-sat-ctrl-c" and t.is_alive() for t in threading.enumerate())


def test_ctrl_c_stops_a_running_search_of_this_process_at_once(watcher):
    time.sleep(allowed_seconds(0.3))  # past the instant of a Ctrl-C an earlier test sent to this process
    search = _Blocking(30.0)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    sent = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        solve_stoppably(search, None)
        time.sleep(5)  # (the handler raises at the next bytecode after solve returns)
    took = time.monotonic() - sent - 0.3
    assert search.stopped and took < allowed_seconds(1.0), took
    time.sleep(allowed_seconds(1.2))  # the watcher's second of stopping new searches passes before the next test


def test_the_watcher_starts_once_and_from_the_main_thread_only(monkeypatch):
    started = []
    monkeypatch.setattr(interrupt, "_watching", False)
    monkeypatch.setattr(interrupt.threading, "Thread", lambda **kw: started.append(kw) or _NoThread())
    saved = signal.set_wakeup_fd(-1)  # as before any watcher: no descriptor
    try:
        helper = _real_thread(interrupt._watch_interrupts)
        helper.start()
        helper.join()
        assert not interrupt._watching and started == []  # not from another thread
        interrupt._watch_interrupts()
        assert interrupt._watching and len(started) == 1
        assert started[0]["target"] is interrupt._stop_on_interrupt and started[0]["daemon"] is True
        read = started[0]["args"][0]
        ours = signal.set_wakeup_fd(-1)
        assert ours != -1 and ours != read  # the writing end is the wakeup descriptor, the reading end the thread's
        os.close(read)
        os.close(ours)
        interrupt._watch_interrupts()
        assert len(started) == 1  # once
    finally:
        signal.set_wakeup_fd(saved)


def test_someone_else_s_wakeup_descriptor_is_left_alone(monkeypatch):
    started = []
    monkeypatch.setattr(interrupt, "_watching", False)
    monkeypatch.setattr(interrupt.threading, "Thread", lambda **kw: started.append(kw) or _NoThread())
    read, write = os.pipe()
    os.set_blocking(write, False)
    saved = signal.set_wakeup_fd(write)  # an asyncio loop's, say
    try:
        opened = set(os.listdir("/proc/self/fd"))
        interrupt._watch_interrupts()
        assert signal.set_wakeup_fd(write) == write  # still that one
        assert started == [] and interrupt._watching
        assert set(os.listdir("/proc/self/fd")) == opened  # the watcher's own pipe closed again
    finally:
        signal.set_wakeup_fd(saved)
        os.close(read)
        os.close(write)


class _NoThread:
    def start(self):
        pass


_THREAD = threading.Thread


def _real_thread(target):
    return _THREAD(target=target)
