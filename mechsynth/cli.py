"""The ``mechsynth`` command: the error contract around the root parser (:mod:`mechsynth._parser`).

Results go to stdout, progress to stderr, errors to stderr as one sentence with exit
status 2 (1 when a query is valid but has no answer, 130 on Ctrl-C, 143 on SIGTERM; a stdout that
cannot be written, a full disk, is an error too).

The console script imports this module and calls :func:`main`; so that a Ctrl-C at any moment
after the interpreter has started ends in one line and status 130, this module imports nothing
the interpreter has not already loaded but :mod:`signal`: the parser, argparse and the engine are
imported inside :func:`main`, under its Ctrl-C handler (tests/cli/test_contract.py).  SIGTERM (a
``kill``, a batch system's time limit) stops a run the same way, through the same clean-up (the
pool's workers ended, a count's temporary folder removed), with status 143.

Example
-------
>>> main(["codes", "--dof", "1", "--loops", "2", "--format", "csv"])
code,links,loops,v,assortment
42/0,6,2,0,4 2
51/1,6,2,1,5 1
60/2,6,2,2,6
0
"""

from __future__ import annotations

import os
import signal
import sys
import threading

# The engine runs in parallel by processes, and its linear algebra is small (the drawing's Tutte
# solve, fits of a few parameters): OpenBLAS threads only spin between such calls and take the
# cores from the other workers (a site drawn on 2 workers: 40 s with them, 16 s without).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__all__ = ["main"]


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    interrupted, previous, pending = [], {}, []

    def on_interrupt(signum, frame):
        interrupted.append(signum)
        raise KeyboardInterrupt

    def on_unraisable(unraisable):
        """A Ctrl-C (or SIGTERM) raised inside a finaliser or a ctypes callback, where Python drops it after printing it:
        raised again in the main thread a moment later, once that code has returned (from another thread:
        in this one the handler would run at once, inside this hook, and be dropped again)."""
        if interrupted and isinstance(unraisable.exc_value, KeyboardInterrupt):
            import _thread

            again = threading.Timer(0.05, _thread.interrupt_main, (interrupted[0],))
            again.daemon = True
            pending.append(again)
            again.start()
        else:
            previous_hook(unraisable)

    # Ctrl-C raises KeyboardInterrupt as Python's own handler does, and is remembered: an extension
    # interrupted in the middle of a call (nauty building a graph) may raise something else instead;
    # SIGTERM, whose default would end the process at once (its workers' temporary files left behind),
    # does the same
    previous_hook = sys.unraisablehook
    if threading.current_thread() is threading.main_thread():
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            previous[signal.SIGINT] = signal.signal(signal.SIGINT, on_interrupt)
        if signal.getsignal(signal.SIGTERM) == signal.SIG_DFL:
            previous[signal.SIGTERM] = signal.signal(signal.SIGTERM, on_interrupt)
        if previous:
            sys.unraisablehook = on_unraisable
    try:
        return _run(argv)
    except KeyboardInterrupt:
        return _stopped(interrupted)
    except BrokenPipeError:
        return 0
    except OSError as exc:
        if interrupted:
            return _stopped(interrupted)
        if not _output_lost(exc):
            raise
        print(f"mechsynth: cannot write the output: {exc.strerror}", file=sys.stderr)
        return 2
    except Exception:
        if not interrupted:
            raise
        return _stopped(interrupted)
    finally:
        for again in pending:  # none outlives the command
            again.cancel()
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        sys.unraisablehook = previous_hook


def _output_lost(exc: OSError) -> bool:
    """Whether ``exc`` is stdout failing (a full disk or quota, a file too large, an I/O error: no file named):
    then nothing more reaches it — it is pointed at the null device, so that the interpreter's last flush at
    exit raises no second error — and the command ends in one sentence."""
    import errno

    if exc.filename is not None or exc.errno not in (errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EIO):
        return False
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
        os.close(null)
    except (OSError, ValueError):  # stdout without a file descriptor (a test's capture): nothing to silence
        pass
    return True


def _stopped(signals: list[int]) -> int:
    """Say that the run was stopped, in one line; the status is 128 + the first signal (130 for Ctrl-C)."""
    terminated = bool(signals) and signals[0] == signal.SIGTERM
    print(f"mechsynth: {'terminated' if terminated else 'interrupted'}", file=sys.stderr)
    return 128 + (signal.SIGTERM if terminated else signal.SIGINT)


def _run(argv: list[str]) -> int:
    """Import the parser and the engine, parse ``argv`` and run its command; a refused query is one sentence, status 2."""
    from synth import SynthesisError

    from ._parser import build_parser

    try:
        args = build_parser(argv).parse_args(argv)
        return args.run(args)
    except SynthesisError as exc:
        from synth import flag

        print(f"mechsynth: {exc.text(flag)}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    raise SystemExit(main())
