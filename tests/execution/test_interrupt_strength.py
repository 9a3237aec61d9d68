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
    """A watcher of this test's own, installed by a first search as in a fresh process.  (A process forked
    from one that had a watcher has the flag but not the thread — mutation testing forks each mutant's
    tests so —, and a thread started by an earlier test would be the one this test judges.)  A watcher
    left by an earlier test keeps waiting on a pipe that nothing writes to any more; this one stays the
    session's."""
    monkeypatch.setattr(interrupt, "_watching", False)
    signal.set_wakeup_fd(-1)
    before = {t for t in threading.enumerate() if t.name == "cp-sat-ctrl-c"}
    solve_stoppably(_Slow(0.0), None)
    assert any(t.name == "cp-sat-ctrl-c" and t.is_alive() and t not in before for t in threading.enumerate())


def test_ctrl_c_stops_a_running_search_of_this_process_at_once(watcher):
    time.sleep(allowed_seconds(0.3))  # past the instant of a Ctrl-C an earlier test sent to this process
    search = _Blocking(allowed_seconds(1.0) + 1.0)  # longer than the bound below: a search not stopped fails it
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


class _Clock:
    """``time`` for the watcher thread: ``monotonic`` reads ``now``, ``sleep`` moves it on and records the
    pause; ``at`` runs actions once the clock has reached a time (a search that registers meanwhile)."""

    def __init__(self, now):
        self.now, self.sleeps, self.at = now, [], []

    def monotonic(self):
        return self.now

    def sleep(self, seconds):
        self.sleeps.append(seconds)
        self.now += seconds
        for when, action in [a for a in self.at if a[0] <= self.now]:
            self.at.remove((when, action))
            action()


class _Reads:
    """``os`` for the watcher thread: counts the reads it has begun, so that a test knows when it has
    handled what was written and waits for the next signal."""

    def __init__(self):
        self.begun, self.changed = 0, threading.Condition()

    def read(self, fd, size):
        with self.changed:
            self.begun += 1
            self.changed.notify_all()
        return os.read(fd, size)

    def wait_for(self, begun):
        with self.changed:
            return self.changed.wait_for(lambda: self.begun >= begun, allowed_seconds(3.0))


class _Search:
    def __init__(self):
        self.stopped = 0

    def stop_search(self):
        self.stopped += 1


def _watch_by_hand(monkeypatch, now, running):
    """The watcher thread on a pipe of its own, with the clock, reads and searches given by hand."""
    clock, reads = _Clock(now), _Reads()
    monkeypatch.setattr(interrupt, "time", clock)
    monkeypatch.setattr(interrupt, "os", reads)
    monkeypatch.setattr(interrupt, "_RUNNING", running)
    read, write = os.pipe()
    _THREAD(target=interrupt._stop_on_interrupt, args=(read,), daemon=True).start()
    assert reads.wait_for(1), "the watcher does not read its pipe"
    return clock, reads, write


def test_the_watcher_stops_the_searches_of_a_ctrl_c_and_its_instant_for_one_second(monkeypatch):
    """The watcher itself on a clock given by hand: other signals' numbers stop nothing; a Ctrl-C stops every
    search that began before it or up to 0.1 s after it was caught (the bound included), also one that
    registers during the next second, not one that began later; it looks every 50 ms at most for one
    second, then reads the next signal."""
    running = {}
    clock, reads, write = _watch_by_hand(monkeypatch, 100.0, running)
    caught = clock.now  # the clock stands still until the watcher's first pause
    old, edge, late = _Search(), _Search(), _Search()
    running.update({old: caught - 5.0, edge: caught + interrupt._INSTANT, late: caught + interrupt._INSTANT + 1e-6})
    entering, after = _Search(), _Search()  # register at 0.5 s: one began in the instant, one afterwards
    clock.at.append((caught + 0.5, lambda: running.update({entering: caught + 0.05, after: caught + 0.5})))

    os.write(write, bytes([signal.SIGUSR1, signal.SIGCHLD]))  # other signals: nothing is stopped
    assert reads.wait_for(2), "the watcher stopped reading after a signal that is not Ctrl-C"
    assert clock.sleeps == [] and not any(s.stopped for s in running)
    os.write(write, bytes([signal.SIGINT]))  # Ctrl-C, after the other signals were read
    assert reads.wait_for(3), f"the watcher did not read again after its second: {clock.sleeps}"
    assert sum(clock.sleeps) == pytest.approx(1.0) and max(clock.sleeps) <= 0.05 and min(clock.sleeps) > 0
    assert old.stopped and edge.stopped and entering.stopped
    assert not late.stopped and not after.stopped

    again = _Search()  # a second Ctrl-C a second later is read and handled as the first
    running.clear()
    running[again] = clock.now
    os.write(write, bytes([signal.SIGINT]))
    assert reads.wait_for(4)
    assert again.stopped


def test_a_ctrl_c_among_other_signals_read_at_once_stops_the_searches(monkeypatch):
    search = _Search()
    clock, reads, write = _watch_by_hand(monkeypatch, 50.0, {search: 49.0})
    os.write(write, bytes([signal.SIGCHLD, signal.SIGINT, signal.SIGUSR1]))
    assert reads.wait_for(2)
    assert search.stopped


def test_a_sigterm_stops_the_searches_as_ctrl_c_does(monkeypatch):
    """The command handles SIGTERM as Ctrl-C: a search running when it comes is stopped too."""
    search = _Search()
    clock, reads, write = _watch_by_hand(monkeypatch, 50.0, {search: 49.0})
    os.write(write, bytes([signal.SIGTERM]))
    assert reads.wait_for(2)
    assert search.stopped


def test_a_watcher_that_is_not_reading_prints_nothing_when_its_pipe_fills(monkeypatch):
    """The wakeup descriptor is written without complaint when full: a process where nothing reads it
    (a forked child has the descriptor but not the thread) must not print "Exception ignored when trying
    to write to the signal wakeup fd" for every signal."""
    import fcntl
    import sys

    monkeypatch.setattr(interrupt, "_watching", False)
    monkeypatch.setattr(interrupt.threading, "Thread", lambda **kw: _NoThread())  # nothing reads the pipe
    saved = signal.set_wakeup_fd(-1)
    pipes, pipe = [], os.pipe
    monkeypatch.setattr(os, "pipe", lambda: pipes.append(pipe()) or pipes[-1])
    reported = []
    monkeypatch.setattr(sys, "unraisablehook", reported.append)
    handler = signal.signal(signal.SIGUSR1, lambda *_: None)
    try:
        interrupt._watch_interrupts()
        [(read, write)] = pipes
        fcntl.fcntl(write, 1031, 4096)  # F_SETPIPE_SZ: a page, full after 4 096 signals
        for _ in range(5000):
            os.kill(os.getpid(), signal.SIGUSR1)
        time.sleep(0.01)  # the pending reports, if any, are made at the next bytecodes
    finally:
        signal.signal(signal.SIGUSR1, handler)
        signal.set_wakeup_fd(saved)
        for fd in (fd for both in pipes for fd in both):
            os.close(fd)
    assert reported == []


def test_no_watcher_where_the_wakeup_descriptor_cannot_be_set(monkeypatch):
    """Where Python refuses a wakeup descriptor (a sub-interpreter), the search runs without a watcher and
    the pipe made for it is closed again; nothing is raised."""
    started = []
    monkeypatch.setattr(interrupt, "_watching", False)
    monkeypatch.setattr(interrupt.threading, "Thread", lambda **kw: started.append(kw) or _NoThread())
    calls = []

    def refuse(*args, **kwargs):
        calls.append(args)
        raise ValueError("set_wakeup_fd only works in main thread of the main interpreter")

    opened = set(os.listdir("/proc/self/fd"))
    monkeypatch.setattr(interrupt.signal, "set_wakeup_fd", refuse)
    assert solve_stoppably(_Slow(0.0), None) == "OPTIMAL"
    monkeypatch.undo()
    assert len(calls) == 1 and started == []
    assert set(os.listdir("/proc/self/fd")) == opened


_CHILD = """
import os, select, signal, sys, time
from synth.execution.interrupt import solve_stoppably

class Blocking:  # waits in select with SIGINT blocked in its thread, as CP-SAT's C++ does
    def __init__(self):
        self.read, self.write = os.pipe()
    def solve(self, model, callback=None):
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        print("searching", flush=True)
        try:
            select.select([self.read], [], [], 60.0)
        finally:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
        return "UNKNOWN"
    def stop_search(self):
        os.write(self.write, b"x")

try:
    solve_stoppably(Blocking(), None)
    time.sleep(5)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(130)
sys.exit(0)
"""


def test_ctrl_c_ends_a_process_searching_within_two_seconds():
    """A process in a search that holds Python's signal handler back (SIGINT blocked in the searching thread)
    ends on Ctrl-C within 2 s (seconds of a machine with a core to spare) with the KeyboardInterrupt."""
    import subprocess
    import sys

    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    child = subprocess.Popen([sys.executable, "-c", _CHILD], stdout=subprocess.PIPE, text=True, cwd=root,
                             env=dict(os.environ, PYTHONPATH=root))  # (from the root: mutation testing's copy too)
    try:
        assert child.stdout.readline() == "searching\n"
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        status = child.wait(timeout=max(30.0, allowed_seconds(2.0)))
        took = time.monotonic() - sent
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert (status, child.stdout.read()) == (130, "interrupted\n")
    assert took <= allowed_seconds(2.0), took
