"""Typed schemas of the balance problem tables (pydantic v2), one sentence per mistake.

Each TOML table a balance problem reads (``[arm]``, ``[spring]``, ``[slider]``,
``[pantograph]``) is a pydantic model: types, required keys, unknown keys and
finiteness are checked by the library; physical domains (a negative weight, an
inverted range) are checked by the model objects themselves (:mod:`balance.model.arm`,
:mod:`balance.devices.fit` …) so the Python API refuses them too. A failed check becomes one
:class:`~balance.errors.SchemaError` sentence naming the file, the table and the key.

Examples
--------
>>> parse({"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 2, "q_max": 0.5}}, "slider", "s.toml").mass
2.0
>>> parse({"slider": {"mass": "2"}}, "slider", "s.toml")
Traceback (most recent call last):
...
balance.errors.SchemaError: s.toml: [slider] key 'mass' must be a number, not '2'.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal, Mapping

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, field_validator

from mechbase import read_toml, show

from .errors import InvalidInput, SchemaError

__all__ = [
    "parse", "load_toml", "show", "check_seed", "OWNED_BY_RUNNER",
    "ArmTable", "LinkTable", "LoadTable", "SpringTable", "SpringDesignTable", "SliderTable",
    "PantographTable", "PayloadTable", "CompareTable",
]

#: top-level tables the scene runner owns; balance ignores them
OWNED_BY_RUNNER = frozenset({"scene", "expect", "plot"})


class _Table(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False, frozen=True)


def _inf_allowed(v: Any) -> Any:
    """``"inf"`` (TOML has no way to say "no bound" in an array of numbers otherwise)."""
    if isinstance(v, str) and v.strip().lower() in {"inf", "+inf", "infinity"}:
        return math.inf
    return v


Number = float
Pair = Annotated[list[float], Field(min_length=2, max_length=2)]
OpenPair = Annotated[
    list[Annotated[float, Field(allow_inf_nan=True), BeforeValidator(_inf_allowed)]],
    Field(min_length=2, max_length=2),
]
Positive = Annotated[float, Field(gt=0)]
Count = Annotated[int, Field(ge=1)]


def _seed_fault(seed: int) -> str | None:
    """What is wrong with a random seed (numpy's generators take 0 ≤ seed < 2**32), or None."""
    if 0 <= seed < 2**32:
        return None
    return f"must be a whole number from 0 to {2**32 - 1}, not {seed}."


def check_seed(seed: int) -> int:
    """A random seed as numpy takes it, or :class:`InvalidInput` — the rule the TOML tables'
    ``seed`` keys and the ``--seed`` options share.

    >>> check_seed(7)
    7
    >>> check_seed(-1)
    Traceback (most recent call last):
    ...
    balance.errors.InvalidInput: the random seed must be a whole number from 0 to 4294967295, not -1.
    """
    fault = _seed_fault(seed)
    if fault:
        raise InvalidInput(f"the random seed {fault}")
    return seed


def _valid_seed(seed: int) -> int:
    fault = _seed_fault(seed)
    if fault:
        raise ValueError(fault)
    return seed


Seed = Annotated[int, AfterValidator(_valid_seed)]


# ----------------------------------------------------------------------------- arm
class LinkTable(_Table):
    name: str | None = None
    joint: Literal["vertical", "revolute", "prismatic"] = "revolute"
    length: float = 0.0
    weight: float | None = None
    mass: float | None = None
    com: float | None = None
    com_lateral: float = 0.0
    offset_deg: float = 0.0
    range: Pair | None = None
    range_deg: Pair | None = None
    stroke: float = 0.0
    accuracy: float | None = None
    gear_ratio: float | None = None
    counterweight_arm: float | None = None


class LoadTable(_Table):
    name: str | None = None
    link: str | None = None
    weight: float | None = None
    mass: float | None = None
    at: float | None = None
    lateral: float = 0.0
    payload: bool = False


class CheckTable(_Table):
    samples: Count = 1000
    seed: Seed = 0


class DevicesTable(_Table):
    eccentricity: Positive | None = None
    r: Positive | None = None
    r0: Positive | None = None


class CounterweightsTable(_Table):
    arm: float | None = None


class PayloadTable(_Table):
    mass: Pair | None = None
    weight: Pair | None = None
    link: str | None = None
    at: float | Annotated[list[float], Field(min_length=3, max_length=3)] | None = None


class ArmTable(_Table):
    name: str = "arm"
    zero: Literal["vertical", "horizontal"] = "vertical"
    g: Positive = 9.80665
    drives: Any = "joint"
    accuracy: float = 1e-3
    links: list[LinkTable] | None = None
    loads: list[LoadTable] = []
    urdf: str | None = None
    transmission: bool = False
    devices: DevicesTable = DevicesTable()
    check: CheckTable = CheckTable()
    counterweights: CounterweightsTable = CounterweightsTable()
    payload: PayloadTable | None = None

    @field_validator("drives")
    @classmethod
    def _drives(cls, v: Any) -> Any:
        if v in ("joint", "base"):
            return v
        ok = isinstance(v, list) and v and all(
            isinstance(row, list) and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                          and math.isfinite(x) for x in row) for row in v)
        if not ok:
            raise ValueError(f"must be 'joint', 'base' or a square matrix of numbers, not {v!r}.")
        return [[float(x) for x in row] for row in v]


# -------------------------------------------------------------------------- spring
class SpringDesignTable(_Table):
    material: str = "music-wire"
    max_outer_diameter: Positive | None = None
    min_inner_diameter: Annotated[float, Field(ge=0)] = 0.0
    ends: Literal["pinned", "fixed-free", "fixed-pinned", "fixed"] = "pinned"
    guided: bool | None = None


class SpringTable(_Table):
    device: Literal["slotted-lever", "slider-crank", "sine"] = "slotted-lever"
    kind: Literal["tension", "compression", "compression-lever"] = "compression"
    moment: float
    range_deg: Pair
    r: Pair
    r0: Pair | None = None
    rod: Pair | None = None
    offset: Pair | None = None
    a: OpenPair | None = None
    max_force: float | None = None
    max_free_length: float | None = None
    max_deflection: float | None = None
    method: Literal["trf", "slsqp", "nelder-mead", "de"] | None = None
    norm: Literal["max", "rms"] = "max"
    grid: Annotated[int, Field(ge=5)] = 61
    target_error: float | None = None
    pareto: bool = False
    design: SpringDesignTable | None = None


# -------------------------------------------------------------------------- slider
class DynamicsTable(_Table):
    arm: Literal["spatial", "planar"] = "spatial"
    length: Positive = 0.5
    mass: Positive = 10.0
    samples: Count = 200
    seed: Seed = 0


class SliderTable(_Table):
    mass: float
    inertia: float = 0.0
    counter_mass: float
    q_max: float
    stroke: float | None = None
    C: float | None = None
    samples: Annotated[int, Field(ge=3)] = 2001
    dynamics: DynamicsTable | None = None


# ---------------------------------------------------------------------- pantograph
class PartTable(_Table):
    weight: float = 0.0
    com: float | None = None


class CylinderTable(_Table):
    base: Pair | None = None


class SpringSizeTable(_Table):
    r: Positive | None = None
    r0: Positive | None = None


class PantographTable(_Table):
    l2: float
    l3: float
    ratio: float
    tool: float = 0.0
    payload: float = 0.0
    upper: PartTable = PartTable()
    forearm: PartTable = PartTable()
    bar_eb: PartTable = PartTable()
    bar_fb: PartTable = PartTable()
    parallelogram_bars: PartTable = PartTable()
    elbow_plate: PartTable = PartTable()
    wrist_plate: PartTable = PartTable()
    parallelogram_offset: Positive = 0.15
    range_upper_deg: Pair = [-60.0, 80.0]
    range_forearm_deg: Pair = [-80.0, 60.0]
    cylinder: CylinderTable = CylinderTable()
    spring: SpringSizeTable = SpringSizeTable()
    check: CheckTable = CheckTable()


# ------------------------------------------------------------------------- compare
class CompareTable(_Table):
    arm: str
    payload: Pair | None = None
    workspace: dict[str, Pair] = {}
    target: Annotated[float, Field(gt=0, lt=1)] = 0.05
    acceleration: Annotated[float, Field(ge=0)] = 1.0
    samples: Count = 1000
    seed: Seed = 0


TABLES: dict[str, type[_Table]] = {
    "arm": ArmTable, "spring": SpringTable, "slider": SliderTable, "pantograph": PantographTable,
    "compare": CompareTable,
}

# ------------------------------------------------------------------------- parsing
_TYPE_WORDS = {
    "float_type": "a number", "int_type": "a whole number", "bool_type": "true or false",
    "string_type": "a string", "finite_number": "a finite number", "list_type": "an array",
    "model_type": "a table", "dict_type": "a table",
}

_PAIRS = {"range", "range_deg", "range_upper_deg", "range_forearm_deg", "r", "r0", "a", "base", "mass", "weight",
          "payload"}


def _where(loc: tuple) -> tuple[str, str | None]:
    """``('arm', 'links', 0, 'weight')`` → (``"[[arm.links]] #1"``, ``"weight"``)."""
    parts: list[str] = []
    table = ""
    key = None
    items = list(loc)
    # an index into an array of numbers (e.g. a range) belongs to its key
    if len(items) >= 2 and isinstance(items[-1], int) and isinstance(items[-2], str):
        items = items[:-1]
    for i, e in enumerate(items):
        last = i == len(items) - 1
        if isinstance(e, int):
            table = f"[[{'.'.join(parts)}]] #{e + 1}"
            continue
        if last and i > 0:
            key = str(e)
            break
        parts.append(str(e))
        table = f"{table} [{e}]" if table.startswith("[[") else f"[{'.'.join(parts)}]"
    return table or "[?]", key


def _allowed(model: type[BaseModel], loc: tuple) -> list[str]:
    """Keys allowed in the table holding the last key of ``loc`` (relative to ``model``)."""
    cur: Any = model
    for e in loc[:-1]:
        if isinstance(e, int):
            continue
        field = getattr(cur, "model_fields", {}).get(e)
        if field is None:
            return []
        cur = _model_in(field.annotation)
        if cur is None:
            return []
    return sorted(getattr(cur, "model_fields", {}))


def _model_in(ann: Any) -> type[BaseModel] | None:
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return ann
    for arg in getattr(ann, "__args__", ()) or ():
        m = _model_in(arg)
        if m is not None:
            return m
    return None


def _sentence(err: dict, model: type[BaseModel], table_name: str, source: str) -> str:
    """One sentence in the words every project file uses: ``SOURCE: [TABLE] key 'K' must be …, not V.``"""
    rel = tuple(err["loc"])
    loc = (table_name,) + rel
    table, key = _where(loc)
    kind = err["type"]
    value = err.get("input")
    if kind == "extra_forbidden":
        return f"{source}: {table} has an unknown key '{loc[-1]}' (allowed: {', '.join(_allowed(model, rel))})."
    if kind == "missing":
        return f"{source}: {table} needs the key '{key}'."
    what = f"{table} key '{key}'" if key else table
    if kind in {"too_short", "too_long"} or (kind == "list_type" and key in _PAIRS):
        return f"{source}: {what} must be a pair [low, high], not {show(value)}."
    if kind == "literal_error":
        expected = err.get("ctx", {}).get("expected", "")
        return f"{source}: {what} must be {expected}, not {show(value)}."
    if kind in {"greater_than", "greater_than_equal", "less_than", "less_than_equal"}:
        ctx = err.get("ctx", {})
        bound = next(ctx[k] for k in ("gt", "ge", "lt", "le") if k in ctx)
        sign = {"greater_than": ">", "greater_than_equal": "≥", "less_than": "<", "less_than_equal": "≤"}[kind]
        return f"{source}: {what} must be {sign} {bound:g}, not {show(value)}."
    if kind == "value_error":
        return f"{source}: {what} {err['ctx']['error']}"
    words = _TYPE_WORDS.get(kind, err["msg"][0].lower() + err["msg"][1:])
    return f"{source}: {what} must be {words}, not {show(value)}."


def parse(doc: Mapping[str, Any], table: str, source: str = "<input>") -> Any:
    """Validate ``doc[table]`` against its schema; ``[scene]``, ``[expect]``, ``[plot]`` are ignored.

    Raises
    ------
    SchemaError
        One sentence naming ``source``, the table and the key.
    """
    if not isinstance(doc, Mapping):
        raise SchemaError(f"{source}: the document must be a TOML table.")
    for key in doc:
        if key != table and key not in OWNED_BY_RUNNER:
            raise SchemaError(f"{source}: the file has an unknown table [{key}] (allowed here: [{table}], "
                              f"{', '.join(f'[{k}]' for k in sorted(OWNED_BY_RUNNER))}).")
    if table not in doc:
        raise SchemaError(f"{source}: the file needs the table [{table}].")
    if not isinstance(doc[table], Mapping):
        raise SchemaError(f"{source}: [{table}] must be a table, not {show(doc[table])}.")
    model = TABLES[table]
    try:
        return model.model_validate(dict(doc[table]))
    except ValidationError as exc:
        err = exc.errors(include_url=False)[0]
        raise SchemaError(_sentence(err, model, table, source)) from None


def load_toml(path: str) -> dict:
    """Read a TOML file; a missing file or a syntax error becomes one :class:`SchemaError` sentence."""
    return read_toml(path, error=SchemaError, what="TOML file")
