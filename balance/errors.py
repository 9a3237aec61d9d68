"""Exceptions raised by the balance package.

Every error carries one sentence a designer can act on; the CLI prints it
verbatim and exits with status 2.
"""

from __future__ import annotations

from mechbase.errors import ProjectError

__all__ = [
    "BalanceError",
    "InvalidArm",
    "InvalidInput",
    "InvalidRange",
    "InfeasibleBounds",
    "WrongSense",
    "FitFailed",
    "SchemaError",
]


class BalanceError(ProjectError):
    """Base class of every error raised by :mod:`balance` (a :class:`mechbase.ProjectError`)."""


class InvalidInput(BalanceError, ValueError):
    """A scalar parameter is out of its physical domain (negative mass, zero moment...)."""


class InvalidArm(InvalidInput):
    """An arm description is inconsistent (negative length, unknown joint kind...)."""


class InvalidRange(InvalidInput):
    """A range ``A..B`` is empty, inverted, not finite or outside the allowed interval."""


class InfeasibleBounds(BalanceError):
    """The physical bounds stated by the user admit no device at all."""


class WrongSense(BalanceError):
    """The chosen spring kind cannot produce a moment of the requested sense."""


class FitFailed(BalanceError):
    """An optimiser stopped without a usable result."""


class SchemaError(InvalidInput):
    """A TOML scene does not follow the documented schema (unknown key, wrong type)."""
