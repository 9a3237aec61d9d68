"""Typed tables of the project's TOML files (pydantic v2) and their one-sentence errors: one dialect
for both engines.

Every table a file holds is a :class:`Table` (strict types: ``true`` is not 1, ``"3"`` is not 3;
unknown keys refused).  A value type may say in words what a designer must write (``expect``:
"a whole number ≥ 0"); pydantic's own checks (numbers, bounds, one of several words, arrays) have
words here too.  The value types below (``Whole``, ``RangeText``, ``Text`` …) carry their words.  :meth:`Table.read` turns pydantic's error into one sentence that names the file,
the table (nested tables and arrays of tables included: ``[[arm.links]] #2``), the key, what was
expected and what was found.

Example
-------
>>> from pydantic import Field
>>> class Loops(Table):
...     dof: int
...     size: float = Field(1.0, gt=0)
>>> Loops.read({"dof": 1}, source="x.toml", where="[structure]").size
1.0
>>> for raw in ({"dof": True}, {"dof": 1, "lops": 2}, {"dof": 1, "size": -2.0}, {}):
...     try:
...         Loops.read(raw, source="x.toml", where="[structure]")
...     except ValueError as exc:
...         print(exc)
x.toml: [structure] key 'dof' must be a whole number, not true.
x.toml: [structure] has an unknown key 'lops' (allowed: dof, size).
x.toml: [structure] key 'size' must be > 0, not -2.0.
x.toml: [structure] needs the key 'dof'.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Annotated, Any

from pydantic import (AfterValidator, BaseModel, ConfigDict, Field, GetCoreSchemaHandler, StrictBool, StrictInt,
                      StrictStr, ValidationError)
from pydantic_core import PydanticCustomError, core_schema

from .ranges import RangeSyntax, parse_range
from .text import show

__all__ = ["Table", "expect", "refine", "sentence",
           "Text", "Flag", "Whole", "Count", "Number", "RangeText", "FileName", "parse_range_text"]


class expect:
    """Annotation metadata: a value that fails its type is reported as "must be ``words``".

    A ``ValueError`` raised on purpose by a :func:`refine` check inside keeps its own words.  With
    ``only`` (pydantic error types), only those failures of the value as a whole take the words;
    a failure inside it (an element of an array) is reported as itself.
    """

    def __init__(self, words: str, only: tuple[str, ...] | None = None):
        self.words, self.only = words, only

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        return core_schema.no_info_wrap_validator_function(self._validate, handler(source))

    def _validate(self, value: Any, handler: Callable[[Any], Any]) -> Any:
        try:
            return handler(value)
        except ValidationError as exc:
            errors = exc.errors()
            if self.only is not None and not any(e["type"] in self.only and not e["loc"] for e in errors):
                raise
            for err in errors:
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


def parse_range_text(value: int | str) -> tuple[int, int | None]:
    """``N``, ``"A..B"`` or ``"A.."`` as ``(A, B)`` (B is None when the range is open); RangeSyntax if
    it is none of these in whole numbers ≥ 0, ValueError if it is empty.

    >>> parse_range_text("2..5"), parse_range_text("3.."), parse_range_text(4)
    ((2, 5), (3, None), (4, 4))
    """
    try:
        lo, hi = parse_range(value)
    except RangeSyntax:
        lo = -1
    if lo < 0 or (hi is not None and hi < 0):
        raise RangeSyntax(f"is not a whole number or a range \"A..B\": {value!r}")
    if hi is not None and hi < lo:
        raise ValueError(f"is the empty range {value!r} ({hi} < {lo})")
    return lo, hi


def _check_range(value: int | str) -> int | str:
    """The one grammar of ranges (:func:`parse_range`): text that is no range of whole numbers takes
    ``RangeText``'s words; an empty range says which it is."""
    try:
        parse_range_text(value)
    except RangeSyntax:
        raise PydanticCustomError("range", "not a range") from None
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
RangeText = Annotated[Annotated[StrictInt, Field(ge=0)] | StrictStr,
                      refine(_check_range),
                      expect('a whole number or a range "A..B"')]

def _file_name(name: str) -> str:
    if "/" in name or "\\" in name or not name.lower().endswith((".svg", ".png", ".pdf")):
        raise PydanticCustomError("file_name", "bad file name")
    return name


#: A picture's file name without directories, ending in .svg, .png or .pdf.
FileName = Annotated[StrictStr, AfterValidator(_file_name), expect("a file name ending in .svg, .png or .pdf, without a folder (the pictures go into one folder)")]


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


#: what a designer must write, by pydantic's error type (a value type's ``expect`` words come first)
_TYPE_WORDS = {
    "float_type": "a number", "int_type": "a whole number", "bool_type": "true or false",
    "string_type": "a string", "finite_number": "a finite number", "list_type": "an array",
    "model_type": "a table", "dict_type": "a table",
}
_BOUNDS = {"greater_than": ">", "greater_than_equal": "≥", "less_than": "<", "less_than_equal": "≤"}


def _place(where: str, loc: tuple) -> tuple[str, str | None]:
    """The table and the key of an error at ``loc`` inside the table ``where``: ``("[arm]",
    ("links", 0, "weight"))`` → ``("[[arm.links]] #1", "weight")``; an index into an array of
    values belongs to its key."""
    items = list(loc)
    if len(items) >= 2 and isinstance(items[-1], int) and isinstance(items[-2], str):
        items = items[:-1]
    key = items.pop() if items and isinstance(items[-1], str) else None
    table = where
    for part in items:
        if isinstance(part, int):
            table = f"[{table}] #{part + 1}"
        elif table.startswith("[") and not table.startswith("[[") and table.endswith("]"):
            table = f"{table[:-1]}.{part}]"
        else:
            table = f"{table} [{part}]" if table else f"[{part}]"
    return table, key


def _model_at(model: type[BaseModel], loc: tuple) -> type[BaseModel] | None:
    """The table model that holds the last key of ``loc`` (``model`` itself for a key of its own)."""
    for part in loc[:-1]:
        if isinstance(part, int):
            continue
        field = model.model_fields.get(part)
        model = field and _model_in(field.annotation)
        if model is None:
            return None
    return model


def _model_in(annotation: Any) -> type[BaseModel] | None:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in getattr(annotation, "__args__", ()) or ():
        found = _model_in(arg)
        if found is not None:
            return found
    return None


def sentence(exc: ValidationError, model: type[BaseModel], raw: Mapping[str, Any], where: str) -> str:
    """The first error of ``exc`` as one sentence (no file name, no final period), the table
    ``where`` (``""``: the file's top level) holding ``raw``, validated by ``model``.

    Unknown keys come first: a misspelt key is the likeliest cause of what follows.
    """
    errors = exc.errors(include_url=False)
    err = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
    loc, kind = tuple(err["loc"]), err["type"]
    table, key = _place(where, loc)
    head = f"{table} " if table else ""
    what = f"{head}key '{key}'" if key else table
    found = show(err.get("input"))
    if key is None:
        return head + str(err["ctx"]["error"] if kind == "value_error" else err["msg"])
    holder = _model_at(model, loc)
    if kind == "extra_forbidden":
        allowed = sorted(holder.model_fields) if holder is not None else []
        return f"{head}{'has an ' if head else ''}unknown key '{key}' (allowed: {', '.join(allowed)})"
    if kind == "missing":
        field = holder.model_fields.get(key) if holder is not None else None
        words = next((m.words for m in (field.metadata if field else ()) if isinstance(m, expect)), None)
        return f"{head}needs the key '{key}'" + (f" ({words})" if words else "")
    if kind == "value_error":
        return f"{what} {err['ctx']['error']}"
    if kind == "expected":
        return f"{what} {err['msg']}, not {found}"
    if kind == "literal_error":
        return f"{what} must be {err.get('ctx', {}).get('expected', '')}, not {found}"
    if kind in _BOUNDS:
        ctx = err.get("ctx", {})
        bound = next(ctx[k] for k in ("gt", "ge", "lt", "le") if k in ctx)
        return f"{what} must be {_BOUNDS[kind]} {bound:g}, not {found}"
    if kind in _TYPE_WORDS:
        return f"{what} must be {_TYPE_WORDS[kind]}, not {found}"
    return f"{what} is not valid ({err['msg']}), not {found}"
