"""Typed results as rows: the one way a frozen dataclass of either engine becomes the dict that
JSON, JSON lines, CSV and tables print.

A result is a frozen dataclass that inherits :class:`Row`; its row holds its fields in the order
they are declared, tuples written as lists and nested rows as dicts, so that a row prints the same
whether it came from a dataclass or was written by hand.

Example
-------
>>> from dataclasses import dataclass
>>> @dataclass(frozen=True)
... class Group(Row):
...     name: str
...     links: tuple[int, ...]
>>> @dataclass(frozen=True)
... class Train(Row):
...     code: str
...     groups: tuple[Group, ...]
>>> Train("22/0", (Group("dyad", (1, 2)),)).to_dict()
{'code': '22/0', 'groups': [{'name': 'dyad', 'links': [1, 2]}]}
"""

from __future__ import annotations

from dataclasses import fields, is_dataclass
from typing import Any

__all__ = ["Row", "as_row"]


def as_row(value: Any) -> Any:
    """``value`` as JSON writes it: a dataclass as a dict of its fields in order, tuples and lists
    as lists, dicts with their values converted; anything else as it is.

    >>> as_row({"a": (1, (2, 3))})
    {'a': [1, [2, 3]]}
    """
    if is_dataclass(value) and not isinstance(value, type):
        return {f.name: as_row(getattr(value, f.name)) for f in fields(value)}
    if isinstance(value, (tuple, list)):
        return [as_row(x) for x in value]
    if isinstance(value, dict):
        return {k: as_row(x) for k, x in value.items()}
    return value


class Row:
    """A mixin of frozen dataclasses whose instances are printed as rows (:func:`as_row`)."""

    __slots__ = ()

    def to_dict(self) -> dict:
        """The row: every field in declared order, tuples as lists, nested rows as dicts."""
        return as_row(self)
