"""Grid files: parameter ranges of a batch run, read from TOML and split into cells and units.

A grid file names ranges of W, n (or K) and v, the conventions (sub-chain rule,
fractionated chains, planar graphs only) and design constraints.  Top-level keys are
defaults; each ``[[block]]`` table overrides them for one block of cells.  Without
blocks the top level is the only block.  A block expands to one *cell* per (W, n)
pair whose n gives a whole number of loops (planar chains: n = W + 1 + 2K); other
pairs are skipped.  A cell keeps its v range whole.  Each cell is split into the
independent work units of :func:`synth.plan_units`.

Keys (all optional except ``dof`` and one of ``links`` / ``loops``):

===================  =====================================================  ==============
key                  value                                                  default
===================  =====================================================  ==============
``name``             text (top level only)                                  file stem
``description``      text (top level only)                                  ""
``input_link``       also store input-link mechanisms (top level only)      false
``dof``              W: integer, ``"A..B"`` or list of integers             required
``links``            n: integer, ``"A..B"`` or list of integers             one of the two
``loops``            K: integer, ``"A..B"`` or list of integers             one of the two
``v``                multiple-joint count: integer, ``"A..B"``, ``"A.."``   0
``rigid_subchains``  allow rigid sub-chains W(S) ≥ 0                        true only at W = 0
``fractionated``     keep fractionated chains                               true
``planar_only``      keep only planar chains                                false
``require``          design constraints ``["5=0", "3=0..2"]``               none
===================  =====================================================  ==============

Example
-------
>>> grid = parse_grid('dof = "1..3"\\nlinks = "4..8"\\nv = "0..1"')
>>> [c.key for c in grid.cells][:2]
['W=1 n=4 v=0..1 rigid=0 frac=1 planar=0', 'W=1 n=6 v=0..1 rigid=0 frac=1 planar=0']
>>> len(grid.cells)  # W=1: n=4,6,8; W=2: n=5,7; W=3: n=6,8
7
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from ._number_synthesis import parse_range, parse_requirements
from ._type_synthesis import Unit, plan_many
from .errors import SynthesisError

__all__ = ["GridFileError", "Cell", "Grid", "load_grid", "parse_grid"]

Range = tuple[int, int | None]


class GridFileError(SynthesisError):
    """A grid file could not be read or has a key with a wrong name, type or value."""


_TOP_ONLY = {"name": str, "description": str, "input_link": bool}
_CELL_KEYS = ("dof", "links", "loops", "v", "rigid_subchains", "fractionated", "planar_only", "require")
_BOOL_KEYS = ("rigid_subchains", "fractionated", "planar_only")
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

    @property
    def loops(self) -> int:
        """K = (n − W − 1) / 2 for planar chains."""
        return (self.links - self.dof - 1) // 2

    @property
    def key(self) -> str:
        """Stable text naming the cell (the atlas's cell key)."""
        hi = "" if self.v[1] is None else str(self.v[1])
        text = (f"W={self.dof} n={self.links} v={self.v[0]}..{hi} rigid={int(self.rigid_subchains)} "
                f"frac={int(self.fractionated)} planar={int(self.planar_only)}")
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
                    planar_only=self.planar_only, require=dict(self.require) or None)

    def query(self) -> dict:
        """This cell as keyword arguments of :func:`synth.plan_units` / :func:`synth.plan_many`."""
        return dict(dof=self.dof, links=self.links, **self.selection())

    def plan(self) -> list[Unit]:
        """The cell's work units (an empty list when the engine finds the cell impossible)."""
        return plan_many([self.query()], skip_impossible=True)[0]


@dataclass(frozen=True)
class Grid:
    """A validated grid: its cells in file order (duplicates removed) and run options."""

    name: str
    cells: tuple[Cell, ...]
    description: str = ""
    input_link: bool = False
    source: str = "<string>"


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
        raise GridFileError(f"grid file {path} does not exist") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise GridFileError(f"cannot read grid file {path}: {getattr(exc, 'strerror', None) or exc}") from None
    return parse_grid(text, source=str(path), default_name=path.stem.removeprefix("grid_"))


def parse_grid(text: str, *, source: str = "<string>", default_name: str = "grid") -> Grid:
    """Validate grid TOML text (see the module docstring for the keys)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise GridFileError(f"grid file {source} is not valid TOML: {exc}") from None

    def fail(where: str, message: str):
        raise GridFileError(f"grid file {source}, {where}: {message}")

    allowed_top = set(_TOP_ONLY) | set(_CELL_KEYS) | {"block"}
    for key in data:
        if key not in allowed_top:
            fail("top level", f"unknown key '{key}' (allowed: {', '.join(sorted(allowed_top))})")
    for key, kind in _TOP_ONLY.items():
        if key in data and not isinstance(data[key], kind):
            fail(f"key '{key}'", f"must be {'true or false' if kind is bool else 'text'}, not {data[key]!r}")
    blocks = data.get("block", [{}])
    if not isinstance(blocks, list) or not all(isinstance(b, dict) for b in blocks) or not blocks:
        fail("key 'block'", "blocks are written as [[block]] tables")
    defaults = {k: data[k] for k in _CELL_KEYS if k in data}

    cells: dict[str, Cell] = {}
    for number, block in enumerate(blocks, 1):
        where = "top level" if "block" not in data else f"[[block]] {number}"
        for key in block:
            if key not in _CELL_KEYS:
                fail(where, f"unknown key '{key}' (allowed in a block: {', '.join(_CELL_KEYS)})")
        spec = {**defaults, **block}
        if "links" in block and "loops" not in block:
            spec.pop("loops", None)
        if "loops" in block and "links" not in block:
            spec.pop("links", None)
        for cell in _expand(spec, where, fail):
            cells.setdefault(cell.key, cell)
    return Grid(name=data.get("name", default_name), cells=tuple(cells.values()),
                description=data.get("description", ""), input_link=data.get("input_link", False), source=source)


def _values(value, key: str, where: str, fail, *, minimum: int) -> list[int]:
    """An integer, "A..B" or a list of integers -> the sorted values."""
    if isinstance(value, list):
        if not value or not all(isinstance(x, int) and not isinstance(x, bool) for x in value):
            fail(f"key '{key}'", f"a list must hold whole numbers, not {value!r}")
        out = sorted(set(value))
        if out[0] < minimum:
            fail(f"key '{key}'", f"values must be at least {minimum}, not {out[0]}")
        return out
    if isinstance(value, bool) or not isinstance(value, (int, str)):
        fail(f"key '{key}'", f"must be a whole number, a range \"A..B\" or a list, not {value!r}")
    try:
        lo, hi = parse_range(value, key, minimum=minimum)
    except SynthesisError as exc:
        fail(f"key '{key}'", str(exc))
    if hi is None:
        fail(f"key '{key}'", f"the range {value!r} has no upper end")
    return list(range(lo, hi + 1))


def _expand(spec: dict, where: str, fail) -> list[Cell]:
    if "dof" not in spec:
        fail(where, "key 'dof' (W) is missing")
    if ("links" in spec) == ("loops" in spec):
        fail(where, "give exactly one of 'links' (n) and 'loops' (K)")
    dofs = _values(spec["dof"], "dof", where, fail, minimum=0)
    v = spec.get("v", 0)
    if isinstance(v, bool) or not isinstance(v, (int, str)):
        fail("key 'v'", f"must be a whole number or a range \"A..B\", not {v!r}")
    try:
        v_range = parse_range(v, "v")
    except SynthesisError as exc:
        fail("key 'v'", str(exc))
    flags = {}
    for key in _BOOL_KEYS:
        if key in spec and not isinstance(spec[key], bool):
            fail(f"key '{key}'", f"must be true or false, not {spec[key]!r}")
        flags[key] = spec.get(key)
    require = spec.get("require")
    if require is not None:
        if isinstance(require, dict):
            items = [f"{k}={val}" for k, val in require.items()]
        elif isinstance(require, list) and all(isinstance(x, str) for x in require):
            items = require
        else:
            fail("key 'require'", f"must be a list such as [\"5=0\", \"3=0..2\"] or a table, not {require!r}")
        try:
            reqs = tuple(parse_requirements(items).items())
        except SynthesisError as exc:
            fail("key 'require'", str(exc))
    else:
        reqs = ()

    pairs = []
    if "links" in spec:
        for n in _values(spec["links"], "links", where, fail, minimum=1):
            pairs += [(w, n) for w in dofs if n - w - 1 >= 2 and (n - w - 1) % 2 == 0]
        top = max(_values(spec["links"], "links", where, fail, minimum=1))
    else:
        loops = _values(spec["loops"], "loops", where, fail, minimum=1)
        pairs = [(w, w + 1 + 2 * k) for w in dofs for k in loops]
        top = max(n for _, n in pairs)
    if top > _MAX_LINKS:
        fail(where, f"{top} links is beyond what a grid run can finish (at most {_MAX_LINKS})")
    if not pairs:
        fail(where, "no (W, n) pair of the ranges gives a whole number of loops K ≥ 1 (n = W + 1 + 2K)")
    pairs.sort()
    return [
        Cell(w, n, v_range,
             rigid_subchains=(w == 0) if flags["rigid_subchains"] is None else flags["rigid_subchains"],
             fractionated=True if flags["fractionated"] is None else flags["fractionated"],
             planar_only=bool(flags["planar_only"]), require=reqs)
        for w, n in pairs
    ]
