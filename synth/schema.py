"""Typed values of synth's TOML files (grid files, scenes), each saying in words what a designer
must write ("a whole number ≥ 0").

The tables that hold them and their one-sentence errors are the project's one dialect,
:mod:`mechbase.schema` (:class:`~mechbase.schema.Table`, ``expect``, ``refine``): :meth:`Table.read`
names the file, the table, the key, what was expected and what was found.

Example
-------
>>> from mechbase.schema import Table
>>> class Loops(Table):
...     dof: Whole
...     loops: RangeText = 1
>>> Loops.read({"dof": 1, "loops": "1..3"}, source="x.toml", where="[structure]").loops
'1..3'
>>> try:
...     Loops.read({"dof": True}, source="x.toml", where="[structure]")
... except ValueError as exc:
...     print(exc)
x.toml: [structure] key 'dof' must be a whole number ≥ 0, not true.
>>> try:
...     Loops.read({"dof": 1, "lops": 2}, source="x.toml", where="[structure]")
... except ValueError as exc:
...     print(exc)
x.toml: [structure] has an unknown key 'lops' (allowed: dof, loops).
"""

from __future__ import annotations

import re
from typing import Annotated, Any

from pydantic import AfterValidator, Field, StrictBool, StrictInt, StrictStr
from pydantic_core import PydanticCustomError

from mechbase import RangeSyntax, parse_range
from mechbase.schema import expect, refine

__all__ = ["Text", "Flag", "Whole", "Count", "Number", "RangeText", "Require", "FileName", "parse_range_text"]


def _non_blank(text: str) -> str:
    if not text.strip():
        raise PydanticCustomError("blank", "blank")
    return text


_RANGE_PATTERN = r"^\s*(\d+)\s*(?:\.\.\s*(\d*)\s*)?$"
_RANGE = re.compile(_RANGE_PATTERN)


def parse_range_text(value: int | str) -> tuple[int, int | None]:
    """``N``, ``"A..B"`` or ``"A.."`` as ``(A, B)`` (B is None when the range is open); ValueError if empty.

    >>> parse_range_text("2..5"), parse_range_text("3.."), parse_range_text(4)
    ((2, 5), (3, None), (4, 4))
    """
    try:
        lo, hi = parse_range(value)
    except RangeSyntax:
        lo = -1
    if lo < 0 or (hi is not None and hi < 0):
        raise ValueError(f"is not a whole number or a range \"A..B\": {value!r}")
    if hi is not None and hi < lo:
        raise ValueError(f"is the empty range {value!r} ({hi} < {lo})")
    return lo, hi


def _check_range(value: int | str) -> int | str:
    parse_range_text(value)
    return value


#: A non-empty string.
Text = Annotated[StrictStr, AfterValidator(_non_blank), expect("a non-empty string")]
#: ``true`` or ``false``.
Flag = Annotated[StrictBool, expect("true or false")]
#: A whole number ≥ 0.
Whole = Annotated[StrictInt, Field(ge=0), expect("a whole number ≥ 0")]
#: A whole number ≥ 1.
Count = Annotated[StrictInt, Field(ge=1), expect("a whole number ≥ 1")]
#: A finite number (a whole number is accepted).
Number = Annotated[float, Field(strict=True, allow_inf_nan=False), expect("a finite number")]
#: A whole number ≥ 0 or a range ``"A..B"`` / ``"A.."`` that is not empty.
RangeText = Annotated[Annotated[StrictInt, Field(ge=0)] | Annotated[StrictStr, Field(pattern=_RANGE_PATTERN)],
                      refine(_check_range),
                      expect('a whole number or a range "A..B"')]

_REQUIREMENT = re.compile(r"^\s*\d+\s*=\s*\d+\s*(\.\.\s*\d*\s*)?$")


def _requirements(value: list[str] | dict[str, Any]) -> list[str]:
    """Design constraints on n_I as the engine's ``["I=A..B", …]`` list."""
    if isinstance(value, list):
        for item in value:
            if not _REQUIREMENT.match(item):
                raise PydanticCustomError("requirement", "bad requirement")
            parse_range_text(item.split("=", 1)[1])
        return value
    return [f"{int(k)}={v}" for k, v in value.items()]


#: Design constraints on n_I, the links with I joints: ``["5=1..", "3=0..2"]`` or ``{ 5 = "1..", 3 = 0 }``.
Require = Annotated[
    list[StrictStr] | dict[Annotated[str, Field(pattern=r"^\s*\d+\s*$")], RangeText],
    refine(_requirements), expect('a list of strings like "5=1.." or a table { 5 = "1.." }')]


def _file_name(name: str) -> str:
    if "/" in name or "\\" in name or not name.lower().endswith((".svg", ".png", ".pdf")):
        raise PydanticCustomError("file_name", "bad file name")
    return name


#: A picture's file name without directories, ending in .svg, .png or .pdf.
FileName = Annotated[StrictStr, AfterValidator(_file_name), expect("a file name ending in .svg, .png or .pdf")]
