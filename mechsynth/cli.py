"""The ``mechsynth`` command: the root parser, ``--version`` and the error contract.

Results go to stdout, progress to stderr, errors to stderr as one sentence with exit
status 2 (1 when a query is valid but has no answer, 130 on Ctrl-C).

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

import argparse
import os
import signal
import sys
import threading

# The engine runs in parallel by processes, and its linear algebra is small (the drawing's Tutte
# solve, fits of a few parameters): OpenBLAS threads only spin between such calls and take the
# cores from the other workers (a site drawn on 2 workers: 40 s with them, 16 s without).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from synth import InvalidOption, SynthesisError  # noqa: E402 - after the thread setting

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    """argparse that raises instead of printing usage and exiting."""

    def error(self, message):  # noqa: D401 - argparse API
        raise InvalidOption(f"{message} (see '{self.prog} --help')")

    def parse_known_args(self, args=None, namespace=None):
        """As argparse's, remembering the innermost command that left words unread: the root parser
        refuses them, and its message points at that command's help, not the root's."""
        namespace, extras = super().parse_known_args(args, namespace)
        if extras and not hasattr(namespace, "unread_by"):
            namespace.unread_by = self.prog
        return namespace, extras

    def parse_args(self, args=None, namespace=None):
        namespace, extras = self.parse_known_args(args, namespace)
        if extras:
            raise InvalidOption(f"unrecognized arguments: {' '.join(extras)} (see '{namespace.unread_by} --help')")
        return namespace


class _Version(argparse.Action):
    """``--version``: the installed version, looked up only when asked."""

    def __call__(self, parser, namespace, values, option_string=None):
        from . import __version__

        print(f"mechsynth {__version__}")
        parser.exit()


# each command by the module of mechsynth.commands that mounts it, in the order of --help
COMMANDS = {"codes": "codes", "analyze": "codes", "chains": "chains", "mechanisms": "chains",
            "identify": "identify", "compare": "identify", "grid": "grid", "atlas": "atlas", "draw": "draw",
            "scene": "scene", "planetary": "planetary", "gears": "gears", "move": "move", "dimension": "dimension",
            "balance": "balance"}


def _build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The root parser: with ``argv`` naming a command, only the module of that command is
    imported and mounted (a small query's start-up: 50 → 10 ms); else every command (help, errors).

    >>> sorted(_build_parser(["chains", "--dof", "1"])._subparsers._group_actions[0].choices)
    ['chains', 'mechanisms']
    """
    import importlib

    parser = _Parser(prog="mechsynth", description="Structural synthesis of mechanisms and balancing of arms.")
    parser.add_argument("--version", action=_Version, nargs=0, help="show the version and exit")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    # the root parser has options only, so the first word that is not one names the command
    word = next((a for a in argv or () if not a.startswith("-")), None)
    modules = [COMMANDS[word]] if word in COMMANDS else dict.fromkeys(COMMANDS.values())
    for name in modules:
        importlib.import_module(f".commands.{name}", __package__).add_commands(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    interrupted, previous, pending = [], None, []

    def on_interrupt(signum, frame):
        interrupted.append(signum)
        raise KeyboardInterrupt

    def on_unraisable(unraisable):
        """A Ctrl-C raised inside a finaliser or a ctypes callback, where Python drops it after printing it:
        raised again in the main thread a moment later, once that code has returned (from another thread:
        in this one the handler would run at once, inside this hook, and be dropped again)."""
        if interrupted and isinstance(unraisable.exc_value, KeyboardInterrupt):
            import _thread

            again = threading.Timer(0.05, _thread.interrupt_main)
            again.daemon = True
            pending.append(again)
            again.start()
        else:
            previous_hook(unraisable)

    # Ctrl-C raises KeyboardInterrupt as Python's own handler does, and is remembered: an extension
    # interrupted in the middle of a call (nauty building a graph) may raise something else instead
    previous_hook = sys.unraisablehook
    if threading.current_thread() is threading.main_thread() and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        previous = signal.signal(signal.SIGINT, on_interrupt)
        sys.unraisablehook = on_unraisable
    try:
        args = _build_parser(argv).parse_args(argv)
        return args.run(args)
    except SynthesisError as exc:
        from synth import flag

        print(f"mechsynth: {exc.text(flag)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("mechsynth: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except Exception:
        if not interrupted:
            raise
        print("mechsynth: interrupted", file=sys.stderr)
        return 130
    finally:
        for again in pending:  # none outlives the command
            again.cancel()
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
            sys.unraisablehook = previous_hook


if __name__ == "__main__":
    raise SystemExit(main())
