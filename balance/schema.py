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

from pydantic import AfterValidator, BeforeValidator, ConfigDict, Field, field_validator

from mechbase import read_toml, show
from mechbase.schema import Table, expect

from .errors import InvalidInput, SchemaError

__all__ = [
    "parse", "load_toml", "show", "check_seed", "OWNED_BY_RUNNER",
    "ArmTable", "LinkTable", "LoadTable", "SpringTable", "SpringDesignTable", "SliderTable",
    "PantographTable", "PayloadTable", "CompareTable", "LinkMassTable", "LinkageBalanceTable", "linkage_table",
]

#: top-level tables the scene runner owns; balance ignores them
OWNED_BY_RUNNER = frozenset({"scene", "expect", "plot"})


class _Table(Table):
    """A balance table: the project's dialect (:class:`mechbase.schema.Table`), no infinite number."""

    model_config = ConfigDict(allow_inf_nan=False)


def _inf_allowed(v: Any) -> Any:
    """``"inf"`` (TOML has no way to say "no bound" in an array of numbers otherwise)."""
    if isinstance(v, str) and v.strip().lower() in {"inf", "+inf", "infinity"}:
        return math.inf
    return v


Number = float
#: an array of two numbers: one that is no array, or of another length, is "not a pair"
_PAIR = expect("a pair [low, high]", only=("too_short", "too_long", "list_type"))
Pair = Annotated[list[float], Field(min_length=2, max_length=2), _PAIR]
OpenPair = Annotated[
    list[Annotated[float, Field(allow_inf_nan=True), BeforeValidator(_inf_allowed)]],
    Field(min_length=2, max_length=2), _PAIR,
]
Positive = Annotated[float, Field(gt=0)]
Count = Annotated[int, Field(ge=1)]


def _seed_fault(seed: int) -> str | None:
    """What is wrong with a random seed (numpy's generators take 0 ≤ seed < 2**32), or None."""
    if 0 <= seed < 2**32:
        return None
    return f"must be a whole number from 0 to {2**32 - 1}, not {seed}"


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
        raise InvalidInput(f"the random seed {fault}.")
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
    counterweight_arm: Positive | None = None


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
    arm: Positive | None = None


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
            raise ValueError(f"must be 'joint', 'base' or a square matrix of numbers, not {v!r}")
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


# -------------------------------------------------------------------------- linkage
_POINT = expect("a point [x, y]", only=("too_short", "too_long", "list_type"))
Point = Annotated[list[float], Field(min_length=2, max_length=2), _POINT]


class LinkMassTable(_Table):
    """One link's mass (kg), centre of mass [x, y] (m) in the linkage's pose and, for the shaking moment,
    its moment of inertia about that centre (kg·m²)."""

    link: int
    mass: float
    centre: Point
    inertia: float | None = None


class CarriedWeightTable(_Table):
    """A counterweight a link already carries (as ``balance linkage --save`` writes it): ``mass`` kg at ``at``
    [x, y] (m) in the linkage's pose."""

    link: int
    mass: float
    at: Point


class LinkageBalanceTable(_Table):
    """``[linkage_balance]``: the linkage (``file``, else the file's ``[linkage]``), its masses (``density``
    of bars, or per-link ``links``), the counterweights the links already carry (``counterweights``) and the
    options of the counterweights to add."""

    file: str | None = None
    density: float | None = None
    links: list[LinkMassTable] | None = None
    counterweights: list[CarriedWeightTable] | None = None
    on: list[int] | None = None
    counter_mass: float | None = None
    counter_radius: float | None = None
    gravity: Point | None = None
    range: Pair | None = None
    samples: Annotated[int, Field(ge=9, le=100_000)] | None = None


def linkage_table(doc: Mapping[str, Any], source: str = "<input>") -> LinkageBalanceTable:
    """The ``[linkage_balance]`` table of a document that may also hold its ``[linkage]``.

    >>> linkage_table({"linkage_balance": {"file": "L.json", "density": 2}}).density
    2.0
    """
    for key in doc:
        if key not in ("linkage_balance", "linkage") and key not in OWNED_BY_RUNNER:
            raise SchemaError(f"{source}: the file has an unknown table [{key}] (allowed here: [linkage_balance], "
                              f"[linkage], {', '.join(f'[{k}]' for k in sorted(OWNED_BY_RUNNER))}).")
    return LinkageBalanceTable.read(doc["linkage_balance"], source=source, where="[linkage_balance]",
                                    error=SchemaError)


TABLES: dict[str, type[_Table]] = {
    "arm": ArmTable, "spring": SpringTable, "slider": SliderTable, "pantograph": PantographTable,
    "compare": CompareTable,
}

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
    return TABLES[table].read(doc[table], source=source, where=f"[{table}]", error=SchemaError)


def load_toml(path: str) -> dict:
    """Read a TOML file; a missing file or a syntax error becomes one :class:`SchemaError` sentence."""
    return read_toml(path, error=SchemaError, what="TOML file")
