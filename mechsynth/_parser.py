"""The root parser of the ``mechsynth`` command: ``--version`` and one subparser per command,
mounted from the module of :mod:`mechsynth.commands` that defines it.

Example
-------
>>> sorted(build_parser(["chains", "--dof", "1"])._subparsers._group_actions[0].choices)
['chains', 'mechanisms']
"""

from __future__ import annotations

import argparse
import importlib

from synth import InvalidOption

from ._argtypes import GIVEN, GivenOnce

__all__ = ["COMMANDS", "build_parser"]


class _Parser(argparse.ArgumentParser):
    """argparse that raises instead of printing usage and exiting, and refuses an option that holds one value
    given twice (:class:`mechsynth._argtypes.GivenOnce`), where argparse keeps the last.

    >>> parser = _Parser(prog="mechsynth chains"); _ = parser.add_argument("--links", type=int)
    >>> parser.parse_args(["--links", "8", "--links", "9"])
    Traceback (most recent call last):
    synth.errors.InvalidOption: --links is given twice: give it once (see 'mechsynth chains --help')
    """

    # argparse's actions that hold one value, each made to refuse a second (its argument groups share the registry)
    _ONCE = {name: type(f"Once{cls.__name__}", (GivenOnce, cls), {})
             for name, cls in [(None, argparse._StoreAction), ("store", argparse._StoreAction),
                               ("store_const", argparse._StoreConstAction), ("store_true", argparse._StoreTrueAction),
                               ("store_false", argparse._StoreFalseAction)]}

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        for name, cls in self._ONCE.items():
            self.register("action", name, cls)

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
        vars(namespace).pop(GIVEN, None)
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


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The root parser: with ``argv`` naming a command, only the module of that command is
    imported and mounted (a small query's start-up: 50 → 10 ms); else every command (help, errors).

    >>> "draw" in build_parser()._subparsers._group_actions[0].choices
    True
    """
    parser = _Parser(prog="mechsynth", description="Structural synthesis of mechanisms and balancing of arms.")
    parser.add_argument("--version", action=_Version, nargs=0, help="show the version and exit")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    # the root parser has options only, so the first word that is not one names the command
    word = next((a for a in argv or () if not a.startswith("-")), None)
    modules = [COMMANDS[word]] if word in COMMANDS else dict.fromkeys(COMMANDS.values())
    for name in modules:
        importlib.import_module(f".commands.{name}", __package__).add_commands(sub)
    return parser
