"""Exceptions of the synth package.

Every error a designer can cause carries one sentence that says what is wrong
and, where possible, what to change.  The CLI prints ``str(exc)`` and exits 2.

Example
-------
>>> from synth.errors import ImpossibleParameters, SynthesisError
>>> issubclass(ImpossibleParameters, SynthesisError)
True
"""

__all__ = [
    "SynthesisError",
    "ImpossibleParameters",
    "MalformedCode",
    "MalformedChain",
    "InvalidOption",
    "QueryTooLarge",
]


class SynthesisError(Exception):
    """Base class of every error raised by :mod:`synth`."""


class ImpossibleParameters(SynthesisError):
    """The requested W, K, n, v, h, f or requirements cannot all hold."""


class MalformedCode(SynthesisError):
    """A standard-code string such as ``6301/0`` could not be read."""


class MalformedChain(SynthesisError):
    """A chain description (JSON or joint list) could not be read or is not a chain."""


class InvalidOption(SynthesisError):
    """An option has a value outside the allowed ones."""


class QueryTooLarge(SynthesisError):
    """The query's plan or output cannot fit in this machine's memory or time (says which, with an estimate)."""
