"""Ctrl-C for a CP-SAT search: :func:`solve_stoppably` stops a running search within milliseconds.

CP-SAT searches without the GIL, and Python runs its SIGINT handler only between bytecodes of
the main thread: a search that finds no solution for minutes would hold Ctrl-C back for
minutes.  Python also writes the number of every caught signal to its wakeup file descriptor; a
daemon thread reading it stops the searches running now, and the pending handler raises
KeyboardInterrupt as soon as ``solve`` returns.  For one second after each Ctrl-C, the thread
stops every search that began before it or in the instant after it, checking every 50 ms (SIGTERM,
which the command handles as Ctrl-C, does the same); other signals stop nothing, and a full descriptor is never reported on stderr.  (Pool workers ignore
SIGINT: their parent terminates them.)  The solver is whatever has ``solve(model, callback)`` and ``stop_search()``
(OR-Tools' ``CpSolver``): this module never loads OR-Tools itself.

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

__all__ = ["solve_stoppably"]

_RUNNING: dict = {}  # solver -> when its search began (time.monotonic)
#: a search that began this long after a Ctrl-C was caught is stopped too (it was being entered as the
#: signal came); one that began later belongs to a caller that has handled the KeyboardInterrupt
#: already (a notebook, a test) and runs to its end
_INSTANT = 0.1
_watching = False
#: the signals that stop the searches: Ctrl-C, and SIGTERM (which the ``mechsynth`` command handles as it does Ctrl-C)
_STOPPING = frozenset({signal.SIGINT, signal.SIGTERM})


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
