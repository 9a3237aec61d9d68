"""Ctrl-C for a CP-SAT search: :func:`solve_stoppably` stops a running search within milliseconds.

CP-SAT searches without the GIL, and Python runs its SIGINT handler only between bytecodes of
the main thread: a search that finds no solution for minutes would hold Ctrl-C back for
minutes.  Python also writes the number of every caught signal to its wakeup file descriptor; a
daemon thread reading it stops the searches running now, and the pending handler raises
KeyboardInterrupt as soon as ``solve`` returns.  For one second after each Ctrl-C, the thread
stops every search that began before it or in the instant after it, checking every 50 ms (SIGTERM,
which the command handles as Ctrl-C, does the same); other signals stop nothing, and a full descriptor is never reported on stderr.  (Pool workers ignore
SIGINT: their parent terminates them.)  The solver is whatever has ``solve(model, callback)`` and ``stop_search()``
(OR-Tools' ``CpSolver``): this module never loads OR-Tools itself.  :func:`ending_signals_unwind` has
SIGTERM and SIGHUP, whose default ends a process at once, unwind a block first, as Ctrl-C does.

Example
-------
>>> class Instant:   # a solver that answers at once
...     def solve(self, model, callback=None):
...         return "OPTIMAL"
...     def stop_search(self):
...         pass
>>> solve_stoppably(Instant(), model=None)
'OPTIMAL'
"""

from __future__ import annotations

import os
import signal
import threading
import time
from contextlib import contextmanager

__all__ = ["solve_stoppably", "ending_signals_unwind"]

_RUNNING: dict = {}  # solver -> when its search began (time.monotonic)
#: a search that began this long after a Ctrl-C was caught is stopped too (it was being entered as the
#: signal came); one that began later belongs to a caller that has handled the KeyboardInterrupt
#: already (a notebook, a test) and runs to its end
_INSTANT = 0.1
_watching = False
#: signals whose default action ends the process at once, without running a ``finally`` (a ``kill``, a batch
#: system's time limit, a closed terminal): :func:`ending_signals_unwind` has them unwind first
_ENDING = (signal.SIGTERM, signal.SIGHUP)
#: the signals that stop the searches: Ctrl-C, and those (which the ``mechsynth`` command, or
#: :func:`ending_signals_unwind`, handles as Ctrl-C)
_STOPPING = frozenset({signal.SIGINT, *_ENDING})


def solve_stoppably(solver, model, callback=None):
    """``solver.solve(model, callback)``, stopped within milliseconds by Ctrl-C (KeyboardInterrupt).

    Parameters
    ----------
    solver : ortools.sat.python.cp_model.CpSolver
        With ``catch_sigint_signal = False`` (Ctrl-C belongs to the caller).
    model : ortools.sat.python.cp_model.CpModel
    callback : CpSolverSolutionCallback, optional

    Returns
    -------
    The solver's status.
    """
    _watch_interrupts()
    _RUNNING[solver] = time.monotonic()
    try:
        return solver.solve(model, callback)
    finally:
        del _RUNNING[solver]


@contextmanager
def ending_signals_unwind():
    """Inside the block, SIGTERM and SIGHUP unwind it as Ctrl-C does (KeyboardInterrupt), so that what
    it holds is released (a count's temporary folder removed, its pool ended); on leaving it, the
    signal is sent again, its default action restored: the process still ends, by that signal.

    Only signals left at their default are taken (the ``mechsynth`` command's own SIGTERM handler is
    kept), and only in the main thread (elsewhere Python cannot set a handler): a library call such as
    ``count_chains`` leaves nothing on disk however a ``kill`` stops it (short of ``kill -9``).

    >>> outside = signal.getsignal(signal.SIGTERM)   # (the default, unless the caller has a handler)
    >>> with ending_signals_unwind():
    ...     inside = signal.getsignal(signal.SIGTERM)
    >>> signal.getsignal(signal.SIGTERM) is outside, inside is outside or outside == signal.SIG_DFL
    (True, True)
    """
    caught, taken = [], {}

    def unwind(signum, frame):
        caught.append(signum)
        raise KeyboardInterrupt

    if threading.current_thread() is threading.main_thread():
        for signum in _ENDING:
            if signal.getsignal(signum) == signal.SIG_DFL:
                taken[signum] = signal.signal(signum, unwind)
    try:
        yield
    finally:
        for signum, handler in taken.items():
            signal.signal(signum, handler)
        if caught:
            signal.raise_signal(caught[0])


def _watch_interrupts() -> None:
    """Start the thread that stops searches on Ctrl-C (once, from the main thread only).

    A wakeup descriptor set by someone else (an asyncio loop) is left alone.
    """
    global _watching
    if _watching or threading.current_thread() is not threading.main_thread():
        return
    _watching = True
    read, write = os.pipe()
    os.set_blocking(write, False)
    try:
        previous = signal.set_wakeup_fd(write, warn_on_full_buffer=False)
    except ValueError:  # pragma: no cover - not the main thread of the main interpreter
        previous = None
    if previous != -1:
        if previous is not None:
            signal.set_wakeup_fd(previous)
        os.close(read)
        os.close(write)
        return
    threading.Thread(target=_stop_on_interrupt, args=(read,), daemon=True, name="cp-sat-ctrl-c").start()


def _stop_on_interrupt(fd: int) -> None:
    while True:
        if not _STOPPING.intersection(os.read(fd, 64)):
            continue
        caught = time.monotonic()
        for _ in range(20):  # a search started in the instant after the signal is caught too
            for solver, began in list(_RUNNING.items()):
                if began <= caught + _INSTANT:
                    solver.stop_search()
            time.sleep(0.05)
