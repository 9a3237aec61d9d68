"""Typed values of the project's TOML files (grid files, scenes) and one-sentence errors.

Every table of a file is a pydantic model (:class:`Table`: strict types, unknown keys
refused).  Each value type below says in words what a designer must write ("a whole
number ≥ 0"), and :meth:`Table.read` turns pydantic's error into one sentence that
names the file, the table, the key, what was expected and what was found.

Example
-------
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
from collections.abc import Callable, Mapping
from typing import Annotated, Any

from pydantic import (AfterValidator, BaseModel, ConfigDict, Field, GetCoreSchemaHandler, StrictBool, StrictInt,
                      StrictStr, ValidationError)
from pydantic_core import PydanticCustomError, core_schema

from mechbase import RangeSyntax, parse_range, show

__all__ = ["Table", "expect", "refine", "show", "sentence",
           "Text", "Flag", "Whole", "Count", "Number", "RangeText", "Require", "FileName", "parse_range_text"]


class expect:
    """Annotation metadata: a value that fails its type is reported as "must be ``words``".

    A ``ValueError`` raised on purpose by a :func:`refine` check inside keeps its own words.
    """

    def __init__(self, words: str):
        self.words = words

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        return core_schema.no_info_wrap_validator_function(self._validate, handler(source))

    def _validate(self, value: Any, handler: Callable[[Any], Any]) -> Any:
        try:
            return handler(value)
        except ValidationError as exc:
            for err in exc.errors():
                if err["type"] == "value_error":
                    raise err["ctx"]["error"] from None
            raise PydanticCustomError("expected", "must be {words}", {"words": self.words}) from None


def refine(check: Callable[[Any], Any]) -> AfterValidator:
    """Annotation metadata: ``check(value)`` returns the value to keep or raises ``ValueError(predicate)``.

    The predicate follows the key in the sentence: ``key 'links' is the empty range '9..4'``.
    """
    return AfterValidator(check)


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


class Table(BaseModel):
    """A TOML table: strict types (``true`` is not 1, ``"3"`` is not 3) and no unknown key."""

    model_config = ConfigDict(strict=True, extra="forbid", frozen=True)

    @classmethod
    def read(cls, raw: Any, *, source: str, where: str, error: type[Exception] = ValueError,
             context: Mapping[str, Any] | None = None):
        """Validate ``raw`` or raise ``error`` with one sentence ``SOURCE: WHERE …``.

        ``context`` is passed to the model's validators (a scene's computations, for instance).
        """
        if not isinstance(raw, Mapping):
            raise error(f"{source}: {where or 'the file'} must be a table, not {show(raw)}.")
        try:
            return cls.model_validate(dict(raw), context=dict(context or {}))
        except ValidationError as exc:
            raise error(f"{source}: {sentence(exc, cls, raw, where)}.") from None

    def given(self) -> set[str]:
        """The keys the file wrote (defaults excluded)."""
        return set(self.model_fields_set)


def sentence(exc: ValidationError, model: type[BaseModel], raw: Mapping[str, Any], where: str) -> str:
    """The first error of ``exc`` as one sentence (no file name, no final period).

    Unknown keys come first: a misspelt key is the likeliest cause of what follows.
    """
    errors = exc.errors(include_url=False)
    order = {key: i for i, key in enumerate(raw)}
    err = min(errors, key=lambda e: (e["type"] != "extra_forbidden", order.get(e["loc"][0] if e["loc"] else "", -1)))
    head = f"{where} " if where else ""
    key = err["loc"][0] if err["loc"] else None
    kind = err["type"]
    if key is None:
        return head + str(err["ctx"]["error"] if kind == "value_error" else err["msg"])
    if kind == "extra_forbidden":
        return f"{head}{'has an ' if head else ''}unknown key '{key}' (allowed: {', '.join(sorted(model.model_fields))})"
    if kind == "missing":
        words = next((m.words for m in model.model_fields[key].metadata if isinstance(m, expect)), None)
        return f"{head}needs the key '{key}'" + (f" ({words})" if words else "")
    if kind == "value_error":
        return f"{head}key '{key}' {err['ctx']['error']}"
    if kind == "expected":
        return f"{head}key '{key}' {err['msg']}, not {show(raw.get(key))}"
    return f"{head}key '{key}' is not valid ({err['msg']}), not {show(raw.get(key))}"
