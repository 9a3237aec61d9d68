"""Typed results as rows: the one way a frozen dataclass of either engine becomes the dict that
JSON, JSON lines, CSV and tables print.

A result is a frozen dataclass that inherits :class:`Row`; its row holds its fields in the order
they are declared, tuples written as lists and nested rows as dicts, so that a row prints the same
whether it came from a dataclass or was written by hand.

A result whose row is not simply its fields (it keeps a model the row does not show, or shows a
value derived from its fields) names the row's keys in ``row_keys``: each the name of a field or a
property, in the order the row shows them; ``key=name`` shows the attribute ``name`` under ``key``
(a row's key kept while the attribute has another name); a key ending in ``?`` is left out of the
row while its value is None; ``*name`` puts the row of the attribute ``name`` in its place, key by
key (a result that adds to another's row; ``*name?``: nothing while it is None). ``row_keys`` may be a property when the keys depend on
the result (a device that is not available shows only why). That is the only other way: no result
builds its row by hand.

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
>>> @dataclass(frozen=True)
... class Spring(Row):
...     rate: float
...     note: str | None = None
...     row_keys = ("rate", "per_mm=rate_per_mm", "note?")
...     @property
...     def rate_per_mm(self) -> float:
...         return self.rate / 1000
>>> Spring(2000.0).to_dict()
{'rate': 2000.0, 'per_mm': 2.0}
>>> @dataclass(frozen=True)
... class Design(Row):
...     spring: Spring
...     mass: float
...     row_keys = ("*spring", "mass")
>>> Design(Spring(2000.0, "wound"), 0.1).to_dict()
{'rate': 2000.0, 'per_mm': 2.0, 'note': 'wound', 'mass': 0.1}
"""

from __future__ import annotations

from dataclasses import fields, is_dataclass
from typing import Any, ClassVar

__all__ = ["Row", "as_row"]


def as_row(value: Any) -> Any:
    """``value`` as JSON writes it: a value with a row of its own (``to_dict``, every :class:`Row`) as that
    row, another dataclass as a dict of its fields in order, tuples and lists as lists, dicts with
    their values converted; anything else as it is.

    >>> as_row({"a": (1, (2, 3))})
    {'a': [1, [2, 3]]}
    """
    if hasattr(value, "to_dict") and not isinstance(value, type):
        return value.to_dict()
    if is_dataclass(value) and not isinstance(value, type):
        return {f.name: as_row(getattr(value, f.name)) for f in fields(value)}
    if isinstance(value, (tuple, list)):
        return [as_row(x) for x in value]
    if isinstance(value, dict):
        return {k: as_row(x) for k, x in value.items()}
    return value


class Row:
    """A mixin of frozen dataclasses whose instances are printed as rows (:func:`as_row`).

    ``row_keys`` (a class attribute, or a property where the keys depend on the result) names the
    row's keys when they are not the fields: fields or
    properties in the row's order, ``key=name`` for an attribute shown under another key, ``key?``
    left out while None, ``*name`` for the keys of the row of ``name``. Empty: every field in order.
    """

    __slots__ = ()

    row_keys: ClassVar[tuple[str, ...]] = ()

    def to_dict(self) -> dict:
        """The row: its keys in order (every field, or ``row_keys``), tuples as lists, nested rows as dicts."""
        if not self.row_keys:
            return {f.name: as_row(getattr(self, f.name)) for f in fields(self)}
        row = {}
        for entry in self.row_keys:
            if entry.startswith("*"):
                value = getattr(self, entry[1:].rstrip("?"))
                if value is not None or not entry.endswith("?"):
                    row.update(as_row(value))
                continue
            key, _, name = entry.rstrip("?").partition("=")
            value = getattr(self, name or key)
            if value is not None or not entry.endswith("?"):
                row[key] = as_row(value)
        return row
