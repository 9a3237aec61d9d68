"""Grid files: parameter ranges of a batch run, read from TOML and split into cells and units.

A grid file names ranges of W, n (or K) and v, the conventions (sub-chain rule,
fractionated chains, planar graphs only) and design constraints.  Top-level keys are
defaults; each ``[[block]]`` table overrides them for one block of cells.  Without
blocks the top level is the only block.  A block expands to one *cell* per (W, n, h)
triple whose n gives a whole number of loops (n = W + 1 + (h − 1)·K; planar chains:
n = W + 1 + 2K); other triples are skipped.  A cell keeps its v range whole.  Each cell is split into the
independent work units of :func:`synth.plan_units`.

Keys (all optional except ``dof`` and one of ``links`` / ``loops``):

===================  =====================================================  ==============
key                  value                                                  default
===================  =====================================================  ==============
``name``             text (top level only)                                  file stem
``description``      text (top level only)                                  ""
``input_link``       also store input-link mechanisms, W ≥ 1 (top level)     false
``dof``              W: integer, ``"A..B"`` or list of integers             required
``links``            n: integer, ``"A..B"`` or list of integers             one of the two
``loops``            K: integer, ``"A..B"`` or list of integers             one of the two
``v``                multiple-joint count: integer, ``"A..B"``, ``"A.."``   0
``h``                motion space of the loops: 2 … 6, ``"A..B"`` or list   3
``n1``               single-joint links (open chains): integer or ``"A..B"`` 0
``prismatic``        store every R/P variant with A…B prismatic pairs       0
``idle_joints``      with ``prismatic``: keep variants with idle joints     false
``rigid_subchains``  allow rigid sub-chains W(S) ≥ 0                        true only at W = 0
``fractionated``     keep fractionated chains                               true
``planar_only``      keep only planar chains                                false
``require``          design constraints ``["5=0", "3=0..2"]``               none
===================  =====================================================  ==============

Planetary gear trains are cells of their own, one ``[[gears]]`` table each (top-level keys do
not apply to them): ``dof`` (F, default 1), ``links`` (n, required) — whole numbers, ranges or
lists, a cell per (F, n) — and ``graphs`` ("displacement", the default: every train; "rotation":
one train per rotation graph, the first :func:`synth.gears.trains` lists).  A file of
``[[gears]]`` tables alone has no chain cells.

Example
-------
>>> grid = parse_grid('dof = "1..3"\\nlinks = "4..8"\\nv = "0..1"')
>>> [c.key for c in grid.cells][:2]
['W=1 n=4 v=0..1 rigid=0 frac=1 planar=0', 'W=1 n=6 v=0..1 rigid=0 frac=1 planar=0']
>>> len(grid.cells)  # W=1: n=4,6,8; W=2: n=5,7; W=3: n=6,8
7
>>> [c.key for c in parse_grid('[[gears]]\\nlinks = "5..6"').gear_cells]
['gears F=1 n=5 graphs=displacement', 'gears F=1 n=6 graphs=displacement']
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

from pydantic import Field, StrictInt, StrictStr

from mechbase import read_toml_text, show
from mechbase.schema import Flag, RangeText, Table, Text, expect, parse_range_text, refine

from ..synthesis.number_synthesis import parse_requirements
from ..structure.query import ChainQuery, Range
from ..synthesis.type_synthesis import Unit, plan_many
from ..errors import SynthesisError
from ..schema import Require

__all__ = ["GridFileError", "Cell", "GearCell", "Grid", "load_grid", "parse_grid"]


class GridFileError(SynthesisError):
    """A grid file could not be read or has a key with a wrong name, type or value."""


_MAX_LINKS = 40  # beyond this no run would ever finish; a typo such as 100 is caught early


@dataclass(frozen=True)
class Cell:
    """One (W, n) pair of a grid with its v range, conventions and design constraints.

    ``rigid_subchains`` is resolved (True for W = 0 unless the file says otherwise).

    >>> Cell(1, 8, (0, 0)).key
    'W=1 n=8 v=0..0 rigid=0 frac=1 planar=0'
    """

    dof: int
    links: int
    v: Range
    rigid_subchains: bool = False
    fractionated: bool = True
    planar_only: bool = False
    require: tuple[tuple[int, Range], ...] = ()
    h: int = 3
    n1: Range = (0, 0)
    prismatic: Range = (0, 0)
    idle_joints: bool = False

    @property
    def loops(self) -> int:
        """K = (n − W − 1) / (h − 1) (planar chains: (n − W − 1) / 2)."""
        return (self.links - self.dof - 1) // (self.h - 1)

    @property
    def key(self) -> str:
        """Stable text naming the cell (the atlas's cell key; h, n1 and prismatic appear where they are not 3, 0, 0)."""
        hi = "" if self.v[1] is None else str(self.v[1])
        text = (f"W={self.dof} n={self.links} v={self.v[0]}..{hi} rigid={int(self.rigid_subchains)} "
                f"frac={int(self.fractionated)} planar={int(self.planar_only)}")
        if self.h != 3:
            text += f" h={self.h}"
        if self.n1 != (0, 0):
            text += f" n1={self.n1[0]}..{'' if self.n1[1] is None else self.n1[1]}"
        if self.prismatic != (0, 0):
            text += f" p={self.prismatic[0]}..{'' if self.prismatic[1] is None else self.prismatic[1]}"
            text += " idle=1" if self.idle_joints else ""
        if self.require:
            reqs = ",".join(f"{i}={lo}..{'' if hi is None else hi}" for i, (lo, hi) in self.require)
            text += f" require={reqs}"
        return text

    def selection(self) -> dict:
        """Keyword arguments selecting this cell in :func:`synth.type_synthesis` / :func:`synth.count_chains`.

        >>> Cell(1, 8, (0, 1)).selection()["v"]
        (0, 1)
        """
        return dict(v=self.v, rigid_subchains=self.rigid_subchains, fractionated=self.fractionated,
                    planar_only=self.planar_only, require=dict(self.require) or None, h=self.h, n1=self.n1)

    def query(self) -> ChainQuery:
        """This cell as a chain query (with prismatic pairs: chains of W = ``dof`` whose wedge loops
        count, as ``chains --prismatic`` lists them).

        >>> Cell(1, 6, (0, 0), prismatic=(0, 2)).query().prismatic
        (0, 2)
        """
        return ChainQuery(self.dof, self.links, **self.selection(),
                          prismatic=None if self.prismatic == (0, 0) else self.prismatic,
                          idle_joints=self.idle_joints)

    def plan(self) -> list[Unit]:
        """The cell's work units (an empty list when the engine finds the cell impossible)."""
        return plan_many([self.query()], skip_impossible=True)[0]


@dataclass(frozen=True)
class GearCell:
    """The planetary gear trains of F degrees of freedom and n links: every displacement graph, or
    one train per rotation graph (``graphs``).

    >>> GearCell(1, 7, "rotation").key
    'gears F=1 n=7 graphs=rotation'
    """

    dof: int
    links: int
    graphs: str = "displacement"

    @property
    def key(self) -> str:
        """Stable text naming the cell (the atlas's cell key)."""
        return f"gears F={self.dof} n={self.links} graphs={self.graphs}"


@dataclass(frozen=True)
class Grid:
    """A validated grid: its chain cells and gear-train cells in file order (duplicates removed)
    and run options."""

    name: str
    cells: tuple[Cell, ...]
    description: str = ""
    input_link: bool = False
    source: str = "<string>"
    gear_cells: tuple[GearCell, ...] = ()


def load_grid(path: str | Path) -> Grid:
    """Read and validate a grid TOML file.

    Raises
    ------
    GridFileError
        One sentence naming the file and the key at fault.

    Example
    -------
    >>> load_grid("models/grid_small.toml").name
    'small'
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise GridFileError(f"grid file {path} does not exist.") from None
    except UnicodeDecodeError as exc:
        raise GridFileError(f"grid file {path} is not a text file (byte {exc.start} is not UTF-8); a grid is a "
                            "TOML file.") from None
    except OSError as exc:
        raise GridFileError(f"cannot read grid file {path}: {exc.strerror or exc}.") from None
    return parse_grid(text, source=str(path), default_name=path.stem.removeprefix("grid_"))


def _values(minimum: int):
    """A whole number, a closed range "A..B" or a list of whole numbers, read as the sorted values."""

    def read(value: int | str | list[int]) -> list[int]:
        if isinstance(value, list):
            out = sorted(set(value))
        else:
            lo, hi = parse_range_text(value)
            if hi is None:
                raise ValueError(f"is the range {value!r} with no upper end")
            out = list(range(lo, hi + 1))
        if out[0] < minimum:
            raise ValueError(f"must be at least {minimum}, not {show(value)}")
        return out

    return Annotated[RangeText | Annotated[list[Annotated[StrictInt, Field(ge=0)]], Field(min_length=1)],
                     refine(read), expect('a whole number, a range "A..B" or a list of whole numbers')]


class _Block(Table):
    """The keys of one block of cells (the top level gives their defaults)."""

    dof: _values(0) | None = None
    links: _values(1) | None = None
    loops: _values(1) | None = None
    v: RangeText | None = None
    h: _values(2) | None = None
    n1: RangeText | None = None
    prismatic: RangeText | None = None
    idle_joints: Flag | None = None
    rigid_subchains: Flag | None = None
    fractionated: Flag | None = None
    planar_only: Flag | None = None
    require: Require | None = None


class _Gears(Table):
    """The keys of one ``[[gears]]`` table: planetary gear trains of F = ``dof`` and n = ``links``."""

    dof: _values(1) = [1]
    links: _values(2)
    graphs: Annotated[StrictStr, refine(lambda g: _graphs(g)), expect('"displacement" or "rotation"')] = "displacement"


def _graphs(value: str) -> str:
    from ..gears.enumeration import GRAPHS

    if value not in GRAPHS:
        raise ValueError(f'must be "displacement" or "rotation", not {value!r}')
    return value


class _GridFile(_Block):
    """The top level of a grid file: run options, defaults of the blocks, the blocks and the gear cells."""

    name: Text | None = None
    description: StrictStr = ""
    input_link: Flag = False
    block: Annotated[list[dict[str, Any]], Field(min_length=1), expect("[[block]] tables")] | None = None
    gears: Annotated[list[dict[str, Any]], Field(min_length=1), expect("[[gears]] tables")] | None = None


def parse_grid(text: str, *, source: str = "<string>", default_name: str = "grid") -> Grid:
    """Validate grid TOML text (see the module docstring for the keys)."""
    data = read_toml_text(text, error=GridFileError, source=f"grid file {source}")
    where = f"grid file {source}"
    top = _GridFile.read(data, source=where, where="", error=GridFileError)
    defaults = top.model_dump(include=set(_Block.model_fields) & top.given())
    cells: dict[str, Cell] = {}
    chain_keys = (set(_Block.model_fields) & top.given()) or top.block is not None
    for number, raw in enumerate(data.get("block", [{}]) if chain_keys or top.gears is None else [], 1):
        block = "" if top.block is None else f"[[block]] {number}"
        spec = _Block.read(raw, source=where, where=block, error=GridFileError)
        given = spec.given()
        merged = {**defaults, **spec.model_dump(include=given)}
        if "links" in given and "loops" not in given:
            merged.pop("loops", None)
        if "loops" in given and "links" not in given:
            merged.pop("links", None)
        for cell in _expand(merged, f"{where}: {block + ' ' if block else ''}"):
            cells.setdefault(cell.key, cell)
    gear_cells: dict[str, GearCell] = {}
    for number, raw in enumerate(top.gears or [], 1):
        for cell in _gear_cells(_Gears.read(raw, source=where, where=f"[[gears]] {number}", error=GridFileError),
                                f"{where}: [[gears]] {number} "):
            gear_cells.setdefault(cell.key, cell)
    return Grid(name=top.name or default_name, cells=tuple(cells.values()), description=top.description,
                input_link=top.input_link, source=source, gear_cells=tuple(gear_cells.values()))


def _gear_cells(spec: _Gears, where: str) -> list[GearCell]:
    """The cells of one ``[[gears]]`` table; ``where`` starts each error sentence."""
    from ..gears.enumeration import MAX_LINKS

    for f in spec.dof:
        for n in spec.links:
            if n < f + 2:
                raise GridFileError(f"{where}key 'links': a gear train with F = {f} needs at least {f + 2} links "
                                    f"(one mesh), not {n}.")
            if n > MAX_LINKS:
                raise GridFileError(f"{where}key 'links': gear trains are enumerated up to {MAX_LINKS} links, not {n}.")
    return [GearCell(f, n, spec.graphs) for f in spec.dof for n in spec.links]


def _expand(spec: dict, where: str) -> list[Cell]:
    """The cells of one block; ``where`` starts each error sentence."""
    if "dof" not in spec:
        raise GridFileError(f"{where}key 'dof' (W) is missing.")
    if ("links" in spec) == ("loops" in spec):
        raise GridFileError(f"{where}needs exactly one of 'links' (n) and 'loops' (K).")
    try:
        reqs = tuple(parse_requirements(spec.get("require")).items())
    except SynthesisError as exc:
        raise GridFileError(f"{where}key 'require': {str(exc).rstrip('.')}.") from None
    spaces = spec.get("h") or [3]
    if max(spaces) > 6:
        raise GridFileError(f"{where}key 'h': the motion space of a loop is 2 … 6, not {max(spaces)}.")
    n1 = parse_range_text(spec.get("n1", 0))
    least = 0 if n1[1] is None or n1[1] > 0 else 1  # open chains may have no loop (serial and tree arms)
    if "links" in spec:
        triples = [(w, n, h) for h in spaces for n in spec["links"] for w in spec["dof"]
                   if n - w - 1 >= least * (h - 1) and (n - w - 1) % (h - 1) == 0]
        top = max(spec["links"])
    else:
        triples = [(w, w + 1 + (h - 1) * k, h) for h in spaces for w in spec["dof"] for k in spec["loops"]]
        top = max(n for _, n, _ in triples)
    if top > _MAX_LINKS:
        raise GridFileError(f"{where}{top} links is beyond what a grid run can finish (at most {_MAX_LINKS}).")
    if not triples:
        raise GridFileError(f"{where}no (W, n, h) of the ranges gives a whole number of loops K ≥ {least} "
                            "(n = W + 1 + (h − 1)·K).")
    prismatic = parse_range_text(spec.get("prismatic", 0))
    if prismatic != (0, 0) and any(h != 3 for _, _, h in triples):
        raise GridFileError(f"{where}key 'prismatic': prismatic pairs are assigned in planar chains (h = 3) only.")
    if spec.get("idle_joints") and prismatic == (0, 0):
        raise GridFileError(f"{where}key 'idle_joints' goes with 'prismatic' (an all-revolute chain has no idle joint).")
    rigid, fractionated = spec.get("rigid_subchains"), spec.get("fractionated")
    return [
        Cell(w, n, parse_range_text(spec.get("v", 0)),
             rigid_subchains=(w == 0) if rigid is None else rigid,
             fractionated=True if fractionated is None else fractionated,
             planar_only=bool(spec.get("planar_only")), require=reqs, h=h, n1=n1, prismatic=prismatic,
             idle_joints=bool(spec.get("idle_joints")))
        for h, w, n in sorted((h, w, n) for w, n, h in triples)
    ]
