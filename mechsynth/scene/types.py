"""Value types of scene tables and expectations, each with the words of its error.

Built on :mod:`mechbase.schema` (the one dialect of every TOML table) and :mod:`synth.schema` (value types shared with grid files).

>>> from pydantic import TypeAdapter
>>> TypeAdapter(Numbers).validate_python([1, 2.5])
[1.0, 2.5]
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field, StrictInt, StrictStr

from mechbase.schema import Count, Flag, Number, RangeText, Text, Whole, expect, refine
from synth import Require

__all__ = ["Flag", "Number", "Count", "RangeText", "Require", "Text", "Whole", "Int", "Numbers", "NumberRows",
           "Texts", "Wholes", "WholeTable", "NumberTable", "IndexTable", "Fraction"]

#: Any whole number (a mobility or a defect may be negative).
Int = Annotated[StrictInt, expect("a whole number")]
#: A number strictly between 0 and 1 (a relative tolerance).
Fraction = Annotated[float, Field(strict=True, gt=0, lt=1), expect("a number between 0 and 1")]
Numbers = Annotated[list[Number], expect("a list of numbers")]
NumberRows = Annotated[list[list[Number]], expect("a list of lists of numbers")]
Texts = Annotated[list[StrictStr], expect("a list of strings")]
Wholes = Annotated[list[Whole], expect("a list of whole numbers ≥ 0")]
WholeTable = Annotated[dict[str, Whole], expect("a table of whole numbers ≥ 0")]
NumberTable = Annotated[dict[str, Number], expect("a table of numbers")]

_INDEX = Annotated[str, Field(pattern=r"^\s*\d+\s*$")]


def _int_keys(table: dict) -> dict[int, int]:
    return {int(k): v for k, v in table.items()}


def IndexTable(words: str, minimum: int = 0):  # noqa: N802 - a type factory
    """A non-empty table ``{ I = N, … }`` with whole-number keys, read as ``{int: int}``."""
    value = Annotated[StrictInt, Field(ge=minimum)]
    return Annotated[dict[_INDEX, value], Field(min_length=1), refine(_int_keys), expect(words)]
