"""Design constraints on a chain's links as synth's TOML files write them (grid files, scenes).

The value types every file shares (``Whole``, ``RangeText``, ``Text`` …) and the tables that hold
them are the project's one dialect, :mod:`mechbase.schema`.

Example
-------
>>> from mechbase.schema import Table
>>> class Drive(Table):
...     require: Require = []
>>> Drive.read({"require": {"5": "1.."}}, source="x.toml", where="[structure]").require
['5=1..']
>>> try:
...     Drive.read({"require": ["5=x"]}, source="x.toml", where="[structure]")
... except ValueError as exc:
...     print(exc)
x.toml: [structure] key 'require' must be a list of strings like "5=1.." or a table { 5 = "1.." }, not ['5=x'].
"""

from __future__ import annotations

import re
from typing import Annotated, Any

from pydantic import Field, StrictStr
from pydantic_core import PydanticCustomError

from mechbase.schema import RangeText, expect, parse_range_text, refine

__all__ = ["Require"]


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
