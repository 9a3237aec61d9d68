"""Exceptions of the synth package.

Every error a designer can cause carries one sentence that says what is wrong
and, where possible, what to change.  An option the remedy names is written with
:func:`option`: a Python caller reads its keyword (``force=True``), the command line its flag
(``--force``, through :meth:`SynthesisError.text`), so the engine speaks of the problem, not of
one interface's flags.  The CLI prints the flag form and exits 2.

Example
-------
>>> from synth.errors import ImpossibleParameters, SynthesisError
>>> issubclass(ImpossibleParameters, SynthesisError)
True
>>> exc = SynthesisError(f"too large; give {option('force')} to run it anyway")
>>> str(exc), exc.text(flag)
('too large; give force=True to run it anyway', 'too large; give --force to run it anyway')
"""

import re

from mechbase.errors import ProjectError

__all__ = [
    "option",
    "flag",
    "SynthesisError",
    "ImpossibleParameters",
    "MalformedCode",
    "MalformedChain",
    "UnknownJoint",
    "InvalidOption",
    "QueryTooLarge",
    "MotionError",
    "CannotAssemble",
    "BadPose",
    "LockedMechanism",
    "WrongInputs",
    "BadSweep",
    "DimensionError",
    "BadTarget",
]


_OPTION = re.compile("\x00([a-z_]+)\x01([^\x00]*)\x00")


def option(name: str, value: str = "True") -> str:
    """An option named in a message: ``name=value`` for a Python caller, ``--name [value]`` on the
    command line (see :meth:`SynthesisError.text`)."""
    return f"\x00{name}\x01{value}\x00"


def flag(name: str, value: str) -> str:
    """The command line's form of an option: ``--name``, and its value unless it is a switch.

    >>> flag("checkpoint", "FILE"), flag("force", "True")
    ('--checkpoint FILE', '--force')
    """
    written = "--" + name.replace("_", "-")
    return written if value == "True" else f"{written} {value}"


class SynthesisError(ProjectError):
    """Base class of every error raised by :mod:`synth` (a :class:`mechbase.ProjectError`)."""

    def text(self, name_of=lambda name, value: f"{name}={value}") -> str:
        """The message with each :func:`option` written by ``name_of(name, value)`` (default: as
        a keyword argument)."""
        return _OPTION.sub(lambda m: name_of(m.group(1), m.group(2)), super().__str__())

    def __str__(self) -> str:
        return self.text()


class ImpossibleParameters(SynthesisError):
    """The requested W, K, n, v, h, f or requirements cannot all hold."""


class MalformedCode(SynthesisError):
    """A standard-code string such as ``6301/0`` could not be read."""


class MalformedChain(SynthesisError):
    """A chain description (JSON or joint list) could not be read or is not a chain."""


class UnknownJoint(SynthesisError):
    """A joint named by its links (``"1-2"``) or its index that the chain does not have, or a name that is
    no joint's."""


class InvalidOption(SynthesisError):
    """An option has a value outside the allowed ones."""


class QueryTooLarge(SynthesisError):
    """The query's plan or output cannot fit in this machine's memory or time (says which, with an estimate)."""


class MotionError(SynthesisError):
    """A dimensioned mechanism (:class:`synth.motion.Linkage`) cannot be built or moved as asked."""


class CannotAssemble(MotionError):
    """The links cannot be put together at the input asked for: names the group whose loop cannot close."""


class BadPose(MotionError):
    """The joint positions contradict the chain: a joint off its link, coincident joints of one link, a
    zero-length link, a NaN or infinite coordinate, a sliding direction of zero length."""


class LockedMechanism(MotionError):
    """The mechanism is rigid (W ≤ 0) or locked in its pose: the inputs cannot move it."""


class WrongInputs(MotionError):
    """Too many or too few input joints, or an input that does not join the frame to one moving link."""


class BadSweep(MotionError):
    """A sweep's step count or input range is absurd (not a number, too few or too many steps)."""


class DimensionError(SynthesisError):
    """Dimensional synthesis (:mod:`synth.dimension`) cannot be run as asked."""


class BadTarget(DimensionError):
    """A synthesis target is malformed: NaN or infinite values, duplicate points, a timing that is not
    monotonic, an empty file, fewer points than the problem's unknowns."""

