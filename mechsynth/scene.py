"""Scenes: one design problem per TOML file, run and checked against its ``[expect]`` table.

A scene says what the problem is (``[structure]`` for structural synthesis, or one of
the balance tables ``[arm]``, ``[spring]``, ``[slider]``, ``[pantograph]``), what to
compute (``[scene] compute = [...]``) and, optionally, what the results must be
(``[expect]``).  The runner validates the whole file before any work, builds only the
models the requested computations need (a codes-only scene never imports the graph
realisation, a balancing scene never imports synth's solvers) and reports every
expectation as met, failed (with both values) or skipped (a drawing when
:mod:`synth.draw` is not installed).  The format is described in ``docs/scenes.md``.

Example
-------
>>> import pathlib, tempfile
>>> path = pathlib.Path(tempfile.mkdtemp()) / "two_loops.toml"
>>> _ = path.write_text('''
... [scene]
... name = "two_loops"
... description = "1-DOF codes with two loops"
... compute = ["codes"]
... [structure]
... dof = 1
... loops = 2
... [expect]
... codes = ["42/0", "51/1", "60/2"]
... ''')
>>> result = run_scene(path)
>>> result.ok, [c.status for c in result.checks]
(True, ['met'])
"""

from __future__ import annotations

import importlib
import importlib.util
import math
import re
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from synth.errors import SynthesisError

__all__ = [
    "SceneError", "Scene", "Check", "SceneResult", "DirectoryResult",
    "COMPUTE_KINDS", "BALANCE_TABLES",
    "load_scene", "is_scene", "run_scene", "run_directory", "iter_scene_paths",
]


class SceneError(SynthesisError):
    """A scene file cannot be read or run; the message names the file and the key."""


#: What a scene can compute, with a one-line description each.
COMPUTE_KINDS: dict[str, str] = {
    "codes": "number synthesis: every standard code n2n3…/v for the structure",
    "count": "type synthesis: the number of chains, by code, by v, non-planar and fractionated",
    "chains": "type synthesis: the chains themselves (joint lists and certificates) and their counts",
    "mechanisms": "chains with a fixed link (and input link) up to symmetry",
    "analysis": "W, K, Y, D of a code, of explicit counts or of a chain",
    "drawing": "an atlas sheet of the chains or mechanisms (needs synth.draw)",
    "plot": "a figure of the balance result (balance.plots): device moment, laws or residuals",
    "balance arm": "static balancing of an [arm]: harmonic terms, devices, residuals",
    "balance spring": "fit of a crank-and-rocker spring device ([spring])",
    "balance prismatic": "counter-masses of a sliding link ([slider])",
    "balance pantograph": "pantograph balanced manipulator ([pantograph])",
}

#: The problem table each balance computation reads, and the ``balance.problems`` solver.
BALANCE_TABLES: dict[str, tuple[str, str]] = {
    "balance arm": ("arm", "solve_arm"),
    "balance spring": ("spring", "solve_spring"),
    "balance prismatic": ("slider", "solve_prismatic"),
    "balance pantograph": ("pantograph", "solve_pantograph"),
}

_CHAIN_KINDS = frozenset({"count", "chains", "mechanisms", "drawing"})
_SYNTH_KINDS = frozenset({"codes", "analysis"}) | _CHAIN_KINDS
_TOP_LEVEL = ("scene", "structure", "drawing", "plot", "expect") + tuple(t for t, _ in BALANCE_TABLES.values())
_ALL = _SYNTH_KINDS

# --------------------------------------------------------------------------- value types
_RANGE_RE = re.compile(r"^\s*\d+\s*(\.\.\s*\d*\s*)?$")
_REQUIRE_RE = re.compile(r"^\s*\d+\s*=\s*\d+\s*(\.\.\s*\d*\s*)?$")


def _is_int(x: Any) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


def _is_num(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _int_table(x: Any) -> bool:
    return isinstance(x, Mapping) and all(str(k).strip().isdigit() and _is_int(v) and v >= 0 for k, v in x.items())


#: type name -> (test, what the sentence says was expected)
_TYPES: dict[str, tuple[Callable[[Any], bool], str]] = {
    "nat": (lambda x: _is_int(x) and x >= 0, "a whole number ≥ 0"),
    "pos": (lambda x: _is_int(x) and x >= 1, "a whole number ≥ 1"),
    "int": (_is_int, "a whole number"),
    "num": (_is_num, "a number"),
    "bool": (lambda x: isinstance(x, bool), "true or false"),
    "str": (lambda x: isinstance(x, str) and x.strip() != "", "a non-empty string"),
    "range": (lambda x: (_is_int(x) and x >= 0) or (isinstance(x, str) and bool(_RANGE_RE.match(x))),
              'a whole number or a range "A..B"'),
    "vrange": (lambda x: (_is_int(x) and x >= 0) or (isinstance(x, str) and bool(_RANGE_RE.match(x)))
               or (isinstance(x, list) and len(x) == 2 and all(_is_int(i) and i >= 0 for i in x)),
               'a whole number, a range "A..B" or a pair [A, B]'),
    "degree": (lambda x: (_is_int(x) and x >= 2) or (isinstance(x, str) and x.replace(" ", "").upper() in {"K+1", "K+W"}),
               'a whole number ≥ 2, "K+1" or "K+W"'),
    "classes": (lambda x: _int_table(x) and len(x) > 0, "a table of loop classes {H = K_H, …} with whole numbers"),
    "counts": (lambda x: _int_table(x) and len(x) > 0, "a table of link counts {I = n_I, …} with whole numbers"),
    "require": (lambda x: (isinstance(x, list) and all(isinstance(i, str) and _REQUIRE_RE.match(i) for i in x))
                or (isinstance(x, Mapping) and all(str(k).strip().isdigit() and ((_is_int(v) and v >= 0) or (
                    isinstance(v, str) and _RANGE_RE.match(v))) for k, v in x.items())),
                'a list of strings like "5=1.." or a table {5 = "1.."}'),
    "cranks": (lambda x: isinstance(x, Mapping) and len(x) > 0 and all(
        str(k).strip().isdigit() and _is_int(v) and v >= 1 for k, v in x.items()),
        "a table {I = C, …}: a link with I joints carrying at least C cranks"),
    "list[str]": (lambda x: isinstance(x, list) and all(isinstance(i, str) for i in x), "a list of strings"),
    "list[nat]": (lambda x: isinstance(x, list) and all(_is_int(i) and i >= 0 for i in x), "a list of whole numbers"),
    "list[num]": (lambda x: isinstance(x, list) and all(_is_num(i) for i in x), "a list of numbers"),
    "list[list[num]]": (lambda x: isinstance(x, list) and all(isinstance(r, list) and all(_is_num(i) for i in r) for r in x),
                        "a list of lists of numbers"),
    "table[nat]": (lambda x: isinstance(x, Mapping) and all(_is_int(v) and v >= 0 for v in x.values()),
                   "a table of whole numbers"),
    "table[num]": (lambda x: isinstance(x, Mapping) and all(_is_num(v) for v in x.values()), "a table of numbers"),
}

# --------------------------------------------------------------------------- schema tables
#: [scene] keys: type, required
_SCENE_KEYS: dict[str, tuple[str, bool]] = {
    "name": ("str", True),
    "description": ("str", True),
    "compute": ("list[str]", True),
    "source": ("str", False),
    "rel_tol": ("num", False),
}

#: [structure] keys: type, the computations that use it, meaning
_STRUCTURE_KEYS: dict[str, tuple[str, frozenset, str]] = {
    "dof": ("nat", _ALL, "required mobility W"),
    "loops": ("range", frozenset({"codes"}) | _CHAIN_KINDS, "K, independent loops"),
    "links": ("range", frozenset({"codes"}) | _CHAIN_KINDS, "n, links with the frame"),
    "loop_classes": ("classes", frozenset({"codes", "analysis"}), "K_h of a heterogeneous system"),
    "h": ("pos", frozenset({"codes", "analysis"}) | _CHAIN_KINDS, "motion space of a loop"),
    "f": ("nat", frozenset({"codes", "analysis"}) | _CHAIN_KINDS, "extra mobility of multi-DOF pairs"),
    "v": ("vrange", _ALL, "multiple-joint count"),
    "n1": ("range", frozenset({"codes"}), "single-joint links"),
    "max_link_degree": ("degree", frozenset({"codes"}), "largest joints on one link"),
    "max_multiplicity": ("pos", frozenset({"codes"}), "largest links on one joint"),
    "compositions": ("bool", frozenset({"codes"}), "split v into v2-v3-…"),
    "require": ("require", frozenset({"codes"}) | _CHAIN_KINDS, "design constraints on n_I"),
    "cranks": ("cranks", _CHAIN_KINDS, "required sub-structure: a link with I joints carrying C cranks"),
    "rigid_subchains": ("bool", _CHAIN_KINDS, "allow rigid sub-chains"),
    "fractionated": ("bool", _CHAIN_KINDS, "keep fractionated chains"),
    "planar_only": ("bool", _CHAIN_KINDS, "keep planar graphs only"),
    "input_link": ("bool", frozenset({"mechanisms", "drawing"}), "mark an input link too"),
    "code": ("str", frozenset({"analysis"}) | _CHAIN_KINDS, "one standard code"),
    "counts": ("counts", frozenset({"analysis"}), "explicit link counts {1 = n1, 2 = n2, …}"),
    "chain": ("str", frozenset({"analysis"}), "a chain as a joint list '0-1 1-2 …'"),
}

_DRAWING_KEYS: dict[str, str] = {
    "out": "str", "mechanisms": "bool", "columns": "pos", "title": "str", "labels": "bool", "limit": "pos",
}

_ANALYSIS_CODE_ONLY = frozenset({"simple_joint_equivalents", "criterion_holds", "defect", "formulas_agree"})
_ANALYSIS_CHAIN_ONLY = frozenset({"standard_code", "subchain_defect", "planar", "fractionated",
                                  "worst_subchain_mobility", "connected"})


@dataclass(frozen=True)
class _Expectation:
    """How one ``[expect]`` key is read from a computation's result and compared."""

    kinds: frozenset          # computations that provide it (any one suffices)
    type: str                 # value type of the expected value
    path: tuple               # where the actual value sits in that computation's result
    compare: str = "equal"    # equal | codes | codes_include | codes_exclude | multiset | table | below
    below: bool = False       # a `_below` key is allowed (actual < expected)


def _E(kinds, type_, path, compare="equal", below=False) -> _Expectation:
    if isinstance(kinds, str):
        kinds = {kinds}
    return _Expectation(frozenset(kinds), type_, tuple(path), compare, below)


_CHAINLIKE = {"count", "chains"}
#: Every [expect] key: what provides it, its type, where it is read and how it is compared.
_EXPECT: dict[str, _Expectation] = {
    # number synthesis
    "codes": _E("codes", "list[str]", ["codes", "codes"], "codes"),
    "codes_include": _E("codes", "list[str]", ["codes", "codes"], "codes_include"),
    "codes_exclude": _E("codes", "list[str]", ["codes", "codes"], "codes_exclude"),
    "code_count": _E("codes", "nat", ["codes", "count"]),
    "code_count_by_loops": _E("codes", "table[nat]", ["codes", "by_loops"], "table"),
    "code_links": _E("codes", "list[nat]", ["codes", "links"]),
    "i_max": _E("codes", "nat", ["codes", "i_max"]),
    # type synthesis
    "count": _E(_CHAINLIKE, "nat", ["chains", "count"]),
    "by_code": _E(_CHAINLIKE, "table[nat]", ["chains", "by_code"], "codes_table"),
    "count_by_v": _E(_CHAINLIKE, "table[nat]", ["chains", "by_v"], "table"),
    "count_nonplanar": _E(_CHAINLIKE, "nat", ["chains", "nonplanar"]),
    "count_fractionated": _E(_CHAINLIKE, "nat", ["chains", "fractionated"]),
    "mechanisms": _E("mechanisms", "nat", ["mechanisms", "count"]),
    "mechanisms_by_code": _E("mechanisms", "table[nat]", ["mechanisms", "by_code"], "codes_table"),
    "drawn": _E("drawing", "nat", ["drawing", "items"]),
    "plotted": _E("plot", "bool", ["plot", "written"]),
    # analysis
    **{k: _E("analysis", t, ["analysis", k], c) for k, t, c in [
        ("dof", "int", "equal"), ("loops", "int", "equal"), ("complexity", "int", "equal"),
        ("links", "nat", "equal"), ("joints", "nat", "equal"), ("v", "nat", "equal"),
        ("simple_joint_equivalents", "nat", "equal"), ("code", "str", "code"),
        ("defect", "int", "equal"), ("criterion_holds", "bool", "equal"), ("formulas_agree", "bool", "equal"),
        ("standard_code", "bool", "equal"), ("subchain_defect", "str", "equal"), ("planar", "bool", "equal"),
        ("fractionated", "bool", "equal"), ("connected", "bool", "equal"),
        ("worst_subchain_mobility", "int", "equal")]},
    # balance arm
    "amplitudes": _E("balance arm", "list[num]", ["balance arm", "amplitudes"], "multiset"),
    "phases_deg": _E("balance arm", "list[num]", ["balance arm", "phases_deg"]),
    "forms": _E("balance arm", "list[list[num]]", ["balance arm", "forms"]),
    "drive_forms": _E("balance arm", "list[list[num]]", ["balance arm", "drive_forms"]),
    "eT": _E("balance arm", "list[num]", ["balance arm", "eT"], "multiset"),
    "gear_ratio": _E("balance arm", "num", ["balance arm", "prismatic", 0, "gear_ratio"]),
    "gamma_max": _E("balance arm", "num", ["balance arm", "prismatic", 0, "gamma_max"]),
    "residual_bound_per_joint": _E("balance arm", "list[num]", ["balance arm", "prismatic", 0, "residual_bound_per_joint"]),
    "potential_spread": _E("balance arm", "num", ["balance arm", "potential_spread"], below=True),
    # shared by arm and pantograph
    "relative_residual": _E({"balance arm", "balance pantograph"}, "num", ["relative_residual"], below=True),
    "max_residual": _E({"balance arm", "balance pantograph"}, "num", ["max_residual"], below=True),
    # spring
    **{k: _E("balance spring", "num", ["balance spring", k], below=True)
       for k in ("r", "r0", "a", "c", "d", "free_length", "max_force", "max_rel_error", "rms_rel_error", "seconds")},
    "active_bounds": _E("balance spring", "list[str]", ["balance spring", "active_bounds"]),
    "sense": _E("balance spring", "int", ["balance spring", "sense"]),
    # slider
    **{k: _E("balance prismatic", "num", ["balance prismatic", k], below=True)
       for k in ("C_min", "C", "max_com_error", "max_inertia_error")},
    "crank_exact": _E("balance prismatic", "bool", ["balance prismatic", "crank", "exact"]),
    # pantograph
    "point_weights": _E("balance pantograph", "table[num]", ["balance pantograph", "point_weights"], "table"),
    "spring_amplitude": _E("balance pantograph", "num", ["balance pantograph", "term", "amplitude"], below=True),
    "drive_force": _E("balance pantograph", "num", ["balance pantograph", "drive_force"], below=True),
    "drive_force_range": _E("balance pantograph", "list[num]", ["balance pantograph", "drive_force_range"]),
}

_DEFAULT_REL_TOL = 1e-9
_ABS_TOL = 1e-12
_TIMING_RUNS = 3


# --------------------------------------------------------------------------- values
@dataclass(frozen=True)
class Scene:
    """A validated scene file.

    Attributes
    ----------
    path : str
        The file it came from (used in every message).
    name, description : str
    compute : tuple of str
        Keys of :data:`COMPUTE_KINDS`, in the order given.
    structure, drawing, expect, plot : dict
        The ``[structure]``, ``[drawing]``, ``[expect]`` and ``[plot]`` tables (empty when absent).
    problem : dict
        The balance tables of the document (``arm``, ``spring``, ``slider``, ``pantograph``).
    rel_tol : float
        Relative tolerance of numeric expectations.
    """

    path: str
    name: str
    description: str
    compute: tuple[str, ...]
    structure: dict = field(default_factory=dict)
    drawing: dict = field(default_factory=dict)
    expect: dict = field(default_factory=dict)
    problem: dict = field(default_factory=dict)
    source: str = ""
    rel_tol: float = _DEFAULT_REL_TOL
    plot: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Check:
    """One expectation: ``status`` is ``"met"``, ``"failed"`` or ``"skipped"``."""

    key: str
    expected: Any
    actual: Any
    status: str
    message: str

    def to_dict(self) -> dict:
        return {"key": self.key, "expected": self.expected, "actual": self.actual,
                "status": self.status, "message": self.message}


@dataclass(frozen=True)
class SceneResult:
    """What a scene computed and how each expectation fared.

    ``results`` maps each computation to its JSON-able result; ``files`` lists the
    pictures written; ``notes`` what was skipped and why.
    """

    path: str
    name: str
    description: str
    compute: tuple[str, ...]
    results: dict
    checks: tuple[Check, ...]
    files: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        """True when no expectation failed (skipped ones do not count against it)."""
        return all(c.status != "failed" for c in self.checks)

    @property
    def failed(self) -> list[Check]:
        return [c for c in self.checks if c.status == "failed"]

    def to_dict(self) -> dict:
        return {"path": self.path, "name": self.name, "description": self.description,
                "compute": list(self.compute), "ok": self.ok, "results": self.results,
                "checks": [c.to_dict() for c in self.checks], "files": list(self.files),
                "notes": list(self.notes), "seconds": round(self.seconds, 3)}


@dataclass(frozen=True)
class DirectoryResult:
    """Every scene of a directory: results, errors (one sentence each) and skipped files."""

    directory: str
    results: tuple[SceneResult, ...]
    errors: tuple[tuple[str, str], ...]
    skipped: tuple[tuple[str, str], ...]

    @property
    def ok(self) -> bool:
        return not self.errors and all(r.ok for r in self.results)

    def to_dict(self) -> dict:
        return {"directory": self.directory, "ok": self.ok,
                "scenes": [r.to_dict() for r in self.results],
                "errors": [{"path": p, "message": m} for p, m in self.errors],
                "skipped": [{"path": p, "reason": m} for p, m in self.skipped]}


# --------------------------------------------------------------------------- loading
def _read_toml(path: Path) -> dict:
    import tomllib

    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise SceneError(f"{path}: no such scene file.") from None
    except IsADirectoryError:
        raise SceneError(f"{path}: is a directory; give a scene file, or use --all for a directory.") from None
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{path}: not valid TOML ({exc}).") from None
    except OSError as exc:
        raise SceneError(f"{path}: cannot be read ({exc.strerror or exc}).") from None


def is_scene(doc: Mapping[str, Any]) -> bool:
    """True when a parsed TOML document has a ``[scene]`` table (grid files and the like have none).

    >>> is_scene({"scene": {"name": "x"}}), is_scene({"dof": "1..3"})
    (True, False)
    """
    return isinstance(doc, Mapping) and "scene" in doc


def _bad_type(path, where: str, key: str, type_: str, value: Any) -> SceneError:
    return SceneError(f"{path}: {where} key '{key}' must be {_TYPES[type_][1]}, not {value!r}.")


def _check_type(path, where: str, key: str, type_: str, value: Any) -> None:
    if not _TYPES[type_][0](value):
        raise _bad_type(path, where, key, type_, value)


def _check_table(path, doc: Mapping, name: str) -> dict:
    value = doc[name]
    if not isinstance(value, Mapping):
        raise SceneError(f"{path}: '{name}' must be a table [{name}], not {value!r}.")
    return dict(value)


def load_scene(path: str | Path) -> Scene:
    """Read and validate a scene file; raise :class:`SceneError` with one sentence otherwise.

    Every key is checked before any work: unknown tables and keys, wrong types, a
    missing ``[scene]``, ``[structure]`` or balance table, structure keys that no
    requested computation uses, and expectations that no requested computation provides.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "bad.toml"
    >>> _ = p.write_text('[scene]\\nname = "x"\\ndescription = "y"\\ncompute = ["codes"]\\n'
    ...                  '[structure]\\ndof = 1\\nloops = 2\\nloopz = 3\\n')
    >>> try:
    ...     load_scene(p)
    ... except SceneError as exc:
    ...     print(str(exc).split(": ", 1)[1])
    [structure] has an unknown key 'loopz' (allowed: chain, code, compositions, counts, cranks, dof, f, fractionated, h, input_link, links, loop_classes, loops, max_link_degree, max_multiplicity, n1, planar_only, require, rigid_subchains, v).
    """
    path = Path(path)
    doc = _read_toml(path)
    if "scene" not in doc:
        raise SceneError(f"{path}: missing section [scene] (a scene needs name, description and compute).")
    for key in doc:
        if key not in _TOP_LEVEL:
            raise SceneError(f"{path}: unknown top-level key '{key}' (allowed: "
                             + ", ".join(f"[{k}]" for k in _TOP_LEVEL) + ").")
    scene = _check_table(path, doc, "scene")
    for key in scene:
        if key not in _SCENE_KEYS:
            raise SceneError(f"{path}: [scene] has an unknown key '{key}' (allowed: {', '.join(_SCENE_KEYS)}).")
    for key, (type_, required) in _SCENE_KEYS.items():
        if key not in scene:
            if required:
                raise SceneError(f"{path}: [scene] needs the key '{key}' ({_TYPES[type_][1]}).")
            continue
        _check_type(path, "[scene]", key, type_, scene[key])
    compute = tuple(scene["compute"])
    if not compute:
        raise SceneError(f"{path}: [scene] key 'compute' is empty; list at least one of {', '.join(COMPUTE_KINDS)}.")
    for kind in compute:
        if kind not in COMPUTE_KINDS:
            raise SceneError(f"{path}: [scene] key 'compute' holds unknown '{kind}' (allowed: {', '.join(COMPUTE_KINDS)}).")
    if len(set(compute)) != len(compute):
        raise SceneError(f"{path}: [scene] key 'compute' lists a computation twice.")
    kinds = set(compute)
    rel_tol = float(scene.get("rel_tol", _DEFAULT_REL_TOL))
    if not 0 < rel_tol < 1:
        raise SceneError(f"{path}: [scene] key 'rel_tol' must lie between 0 and 1, not {rel_tol!r}.")

    structure = _validate_structure(path, doc, kinds)
    drawing = _validate_drawing(path, doc, kinds)
    plot = _validate_plot(path, doc, kinds)
    problem = {}
    for kind, (table, _) in BALANCE_TABLES.items():
        if kind in kinds:
            if table not in doc:
                raise SceneError(f"{path}: compute '{kind}' needs the section [{table}].")
            problem[table] = doc[table]
        elif table in doc:
            raise SceneError(f"{path}: section [{table}] is given but [scene] compute does not list '{kind}'.")
    expect = _validate_expect(path, doc, kinds, structure)
    return Scene(str(path), scene["name"], scene["description"], compute, structure, drawing, expect, problem,
                 scene.get("source", ""), rel_tol, plot)


def _validate_structure(path, doc, kinds: set) -> dict:
    synth_kinds = kinds & _SYNTH_KINDS
    if "structure" not in doc:
        if synth_kinds:
            raise SceneError(f"{path}: missing section [structure] (compute {', '.join(sorted(synth_kinds))} "
                             "needs dof and loops, links, a code, counts or a chain).")
        return {}
    structure = _check_table(path, doc, "structure")
    if not synth_kinds:
        raise SceneError(f"{path}: section [structure] is given but [scene] compute lists no structural "
                         "computation (codes, count, chains, mechanisms, analysis, drawing).")
    for key, value in structure.items():
        if key not in _STRUCTURE_KEYS:
            raise SceneError(f"{path}: [structure] has an unknown key '{key}' (allowed: "
                             f"{', '.join(sorted(_STRUCTURE_KEYS))}).")
        type_, used_by, meaning = _STRUCTURE_KEYS[key]
        _check_type(path, "[structure]", key, type_, value)
        if not used_by & kinds:
            raise SceneError(f"{path}: [structure] key '{key}' ({meaning}) is not used by compute "
                             f"{list(sorted(synth_kinds))}; remove it or add one of {sorted(used_by)}.")
    if "dof" not in structure and synth_kinds - {"analysis"}:
        raise SceneError(f"{path}: [structure] needs the key 'dof' (the required mobility W, a whole number ≥ 0).")
    if synth_kinds & _CHAIN_KINDS:
        for key, allowed in (("h", 3), ("f", 0)):
            if structure.get(key, allowed) != allowed:
                raise SceneError(f"{path}: [structure] key '{key}' must be {allowed} for chains, mechanisms and "
                                 "drawings (type synthesis builds planar chains with one-DOF pairs).")
        for key in ("loops", "links"):
            if isinstance(structure.get(key), str) and ".." in structure[key]:
                raise SceneError(f"{path}: [structure] key '{key}' must be one whole number for chains, "
                                 f"mechanisms and drawings, not the range {structure[key]!r}.")
        if not any(k in structure for k in ("links", "loops", "code")):
            raise SceneError(f"{path}: [structure] needs 'links', 'loops' or 'code' for chains, mechanisms and drawings.")
    if "analysis" in kinds:
        given = [k for k in ("code", "counts", "chain") if k in structure]
        if len(given) != 1:
            raise SceneError(f"{path}: [structure] needs exactly one of 'code', 'counts' or 'chain' for the "
                             f"analysis, not {given or 'none'}.")
        if "code" in structure:
            _parse_code(path, "[structure]", "code", structure["code"])
        if "v" in structure and not _is_int(structure["v"]):
            raise SceneError(f"{path}: [structure] key 'v' must be one whole number for the analysis, "
                             f"not {structure['v']!r}.")
    if "codes" in kinds and sum(k in structure for k in ("loops", "links", "loop_classes")) != 1:
        raise SceneError(f"{path}: [structure] needs exactly one of 'loops', 'links' or 'loop_classes' for the codes.")
    return structure


def _validate_drawing(path, doc, kinds: set) -> dict:
    if "drawing" not in doc:
        return {}
    drawing = _check_table(path, doc, "drawing")
    if "drawing" not in kinds:
        raise SceneError(f"{path}: section [drawing] is given but [scene] compute does not list 'drawing'.")
    for key, value in drawing.items():
        if key not in _DRAWING_KEYS:
            raise SceneError(f"{path}: [drawing] has an unknown key '{key}' (allowed: {', '.join(_DRAWING_KEYS)}).")
        _check_type(path, "[drawing]", key, _DRAWING_KEYS[key], value)
    _check_out_name(path, "drawing", drawing.get("out"))
    return drawing


def _check_out_name(path, table: str, out: str | None) -> None:
    if out is not None and (Path(out).suffix.lower() not in {".svg", ".png", ".pdf"} or Path(out).name != out):
        raise SceneError(f"{path}: [{table}] key 'out' must be a file name ending in .svg, .png or .pdf, not {out!r}.")


def _validate_plot(path, doc, kinds: set) -> dict:
    if "plot" in kinds and not kinds & set(BALANCE_TABLES):
        raise SceneError(f"{path}: [scene] compute 'plot' needs a balance computation "
                         f"({', '.join(BALANCE_TABLES)}) to plot.")
    if "plot" not in doc:
        return {}
    plot = _check_table(path, doc, "plot")
    if "plot" not in kinds:
        raise SceneError(f"{path}: section [plot] is given but [scene] compute does not list 'plot'.")
    for key, value in plot.items():
        if key != "out":
            raise SceneError(f"{path}: [plot] has an unknown key '{key}' (allowed: out).")
        _check_type(path, "[plot]", key, "str", value)
    _check_out_name(path, "plot", plot.get("out"))
    return plot


def _parse_code(path, where: str, key: str, text: str):
    from synth.code import Code
    from synth.errors import MalformedCode

    try:
        return Code.parse(text)
    except MalformedCode as exc:
        raise SceneError(f"{path}: {where} key '{key}' holds {text!r}, which is not a standard code ({exc}).") from None


def _expect_base(key: str) -> tuple[str, bool]:
    if key.endswith("_below") and key[: -len("_below")] in _EXPECT:
        return key[: -len("_below")], True
    return key, False


def _validate_expect(path, doc, kinds: set, structure: dict) -> dict:
    if "expect" not in doc:
        return {}
    expect = _check_table(path, doc, "expect")
    for key, value in expect.items():
        base, below = _expect_base(key)
        spec = _EXPECT.get(base)
        if spec is None:
            raise SceneError(f"{path}: [expect] has an unknown key '{key}' (see docs/scenes.md for the keys "
                             "each computation provides).")
        if not spec.kinds & kinds:
            raise SceneError(f"{path}: [expect] key '{key}' needs compute {' or '.join(repr(k) for k in sorted(spec.kinds))} "
                             "in [scene], which is not listed.")
        if below:
            if not spec.below:
                raise SceneError(f"{path}: [expect] key '{key}': '{base}' has no upper-bound form; write '{base}' = value.")
            _check_type(path, "[expect]", key, "num", value)
        else:
            _check_type(path, "[expect]", key, spec.type, value)
        if spec.compare in {"codes", "codes_include", "codes_exclude"}:
            for text in value:
                _parse_code(path, "[expect]", key, text)
        if spec.compare == "codes_table" or base == "code":
            for text in (value if isinstance(value, Mapping) else [value]):
                _parse_code(path, "[expect]", key, text)
        if base in _ANALYSIS_CODE_ONLY and "chain" in structure:
            raise SceneError(f"{path}: [expect] key '{key}' belongs to the analysis of a code or counts, "
                             "but [structure] gives a chain.")
        if base in _ANALYSIS_CHAIN_ONLY and "analysis" in kinds and "chain" not in structure and not spec.kinds - {"analysis"}:
            raise SceneError(f"{path}: [expect] key '{key}' belongs to the analysis of a chain, "
                             "but [structure] gives no 'chain'.")
        if base in {"defect", "criterion_holds"} and "dof" not in structure:
            raise SceneError(f"{path}: [expect] key '{key}' needs 'dof' (the required W) in [structure].")
    return expect


# --------------------------------------------------------------------------- running
def _range_arg(value: Any):
    if isinstance(value, list):
        return tuple(value)
    return value


def _require_arg(value: Any):
    if value is None or isinstance(value, list):
        return value
    return [f"{int(str(k).strip())}={v}" for k, v in value.items()]


def _int_keys(table: Mapping) -> dict[int, int]:
    return {int(str(k).strip()): int(v) for k, v in table.items()}


def _compute_codes(s: dict) -> dict:
    from synth._number_synthesis import number_synthesis  # CP-SAT counting model only

    codes = number_synthesis(
        s["dof"], loops=s.get("loops"), links=s.get("links"),
        loop_classes=_int_keys(s["loop_classes"]) if "loop_classes" in s else None,
        h=s.get("h", 3), f=s.get("f", 0), v=_range_arg(s.get("v")), n1=s.get("n1", 0),
        max_link_degree=s.get("max_link_degree"), require=_require_arg(s.get("require")),
        max_multiplicity=s.get("max_multiplicity"), compositions=s.get("compositions", False),
    )
    by_loops: dict[str, int] = {}
    for c in codes:
        by_loops[str(c.loops)] = by_loops.get(str(c.loops), 0) + 1
    return {
        "codes": [str(c) for c in codes],
        "count": len(codes),
        "by_loops": by_loops,
        "links": sorted({c.links for c in codes}),
        "i_max": max((c.max_degree for c in codes), default=0),
    }


def _chain_query(s: dict) -> tuple[int, int | None, dict]:
    links = s.get("links")
    if links is not None:
        links = int(links)
    elif "loops" in s:
        links = s["dof"] + 1 + 2 * int(s["loops"])
    kwargs = {"v": _range_arg(s.get("v", 0)), "code": s.get("code"), "rigid_subchains": s.get("rigid_subchains"),
              "fractionated": s.get("fractionated", True), "planar_only": s.get("planar_only", False),
              "require": _require_arg(s.get("require")),
              "cranks": {int(k): int(v) for k, v in s.get("cranks", {}).items()} or None}
    return s["dof"], links, kwargs


def _compute_chains(s: dict, workers: int, listing: bool) -> tuple[dict, list]:
    from synth._type_synthesis import type_synthesis  # graph models: only for chain queries

    dof, links, kwargs = _chain_query(s)
    chains = list(type_synthesis(dof, links, workers=workers, **kwargs))
    by_code: dict[str, int] = {}
    by_v: dict[str, int] = {}
    for ch in chains:
        by_code[str(ch.code)] = by_code.get(str(ch.code), 0) + 1
        by_v[str(ch.v)] = by_v.get(str(ch.v), 0) + 1
    result = {
        "count": len(chains),
        "by_code": by_code,
        "by_v": dict(sorted(by_v.items(), key=lambda kv: int(kv[0]))),
        "nonplanar": sum(1 for ch in chains if not ch.is_planar()),
        "fractionated": sum(1 for ch in chains if ch.is_fractionated()),
    }
    if listing:
        result["chains"] = [{"code": str(ch.code), "joints": ch.compact(), "certificate": ch.certificate}
                            for ch in chains]
    return result, chains


def _compute_mechanisms(s: dict, chains: list) -> tuple[dict, list]:
    from synth._type_synthesis import mechanisms_of

    input_link = bool(s.get("input_link", False))
    mechs = [m for ch in chains for m in mechanisms_of(ch, input_link=input_link)]
    by_code: dict[str, int] = {}
    for m in mechs:
        by_code[str(m.chain.code)] = by_code.get(str(m.chain.code), 0) + 1
    return {"count": len(mechs), "by_code": by_code, "input_link": input_link}, mechs


def _compute_analysis(s: dict) -> dict:
    if "chain" in s:
        from synth.chain_analysis import analyze_chain

        return analyze_chain(s["chain"], dof=s.get("dof")).to_dict()
    from synth.analysis import analyze  # pure counting: no solver

    common = dict(dof=s.get("dof"), h=s.get("h", 3), f=s.get("f", 0),
                  loop_classes=_int_keys(s["loop_classes"]) if "loop_classes" in s else None)
    if "code" in s:
        out = analyze(s["code"], **common).to_dict()
    else:
        out = analyze(counts=_int_keys(s["counts"]), v=int(s.get("v", 0)), **common).to_dict()
    out["formulas_agree"] = len(set(out["formulas"].values())) == 1
    return out


def _draw_module():
    """``synth.draw`` when it is installed and offers ``draw_sheet``, else None."""
    if importlib.util.find_spec("synth.draw") is None:
        return None
    module = importlib.import_module("synth.draw")
    return module if callable(getattr(module, "draw_sheet", None)) else None


def _compute_drawing(scene: Scene, items: list, out_dir: Path) -> tuple[dict | None, str]:
    draw = _draw_module()
    if draw is None:
        return None, "drawing skipped: synth.draw is not installed"
    opts = scene.drawing
    limit = opts.get("limit", 200)
    chosen = items[:limit]
    out = out_dir / opts.get("out", f"{scene.name}.svg")
    out_dir.mkdir(parents=True, exist_ok=True)
    title = opts.get("title", scene.description)
    draw.draw_sheet(chosen, out, columns=opts.get("columns"), title=title, labels=opts.get("labels", False))
    note = f"drew {len(chosen)} of {len(items)} items to {out}" if len(chosen) < len(items) else ""
    return {"file": str(out), "items": len(chosen), "of": len(items)}, note


def _solve_balance(scene: Scene, kind: str) -> dict:
    table, solver_name = BALANCE_TABLES[kind]
    problems = importlib.import_module("balance.problems")  # balance only: no synth solver
    errors = importlib.import_module("balance.errors")
    doc = {table: scene.problem[table]}
    try:
        out = getattr(problems, solver_name)(doc, scene.path)
    except errors.BalanceError as exc:
        msg = str(exc).rstrip(".")
        prefix = f"{scene.path}: "
        raise SceneError((msg if msg.startswith(prefix) else prefix + f"[{table}] " + msg) + ".") from None
    if kind == "balance arm":
        terms = sorted(out["terms"], key=lambda t: -t["amplitude"])
        out["amplitudes"] = [t["amplitude"] for t in terms]
        out["phases_deg"] = [t["phase_deg"] for t in terms]
        out["forms"] = [t["form"] for t in terms]
        out["drive_forms"] = [t["drive_form"] for t in terms]
        out["eT"] = sorted((d["sine"]["eT"] for d in out["devices"] if "sine" in d), reverse=True)
    return out


def _plot_balance(scene: Scene, kind: str, result: dict, out: Path) -> None:
    """Write the balance package's figure of ``kind`` to ``out``."""
    plots = importlib.import_module("balance.plots")
    table = BALANCE_TABLES[kind][0]
    doc = {table: scene.problem[table]}
    if kind == "balance arm":
        arm = importlib.import_module("balance.arm").arm_from_dict(doc, scene.path)
        plots.plot_arm(arm, arm.with_payload_fraction(0.5).harmonic_terms(), str(out))
    elif kind == "balance spring":
        problems = importlib.import_module("balance.problems")
        fit = importlib.import_module("balance.fit").fit_spring
        plots.plot_spring(fit(**problems.spring_from_dict(doc, scene.path)), str(out))
    elif kind == "balance prismatic":
        plots.plot_prismatic(result["m"], result["I"], result["M"], result["q_max"], result["stroke"], result["C"],
                             str(out))
    else:
        pantograph = importlib.import_module("balance.pantograph").pantograph_from_dict(doc, scene.path)[0]
        plots.plot_pantograph(pantograph, str(out))


def run_scene(scene: Scene | str | Path, *, out_dir: str | Path | None = None, workers: int = 1) -> SceneResult:
    """Run one scene: compute what ``[scene] compute`` lists and check ``[expect]``.

    Parameters
    ----------
    scene : Scene or path
        A validated :class:`Scene` or the path of a scene file.
    out_dir : path, optional
        Where drawings go (default: the current directory).
    workers : int
        Processes for type synthesis (default 1: inline).

    Returns
    -------
    SceneResult
        ``ok`` is False when an expectation failed; each :class:`Check` says why.

    Raises
    ------
    SceneError
        The file is malformed, or the problem it states is impossible (one sentence
        naming the file and the key).

    Examples
    --------
    >>> r = run_scene("models/chains_1dof_8links.toml")  # doctest: +SKIP
    >>> r.results["count"]["count"]                      # doctest: +SKIP
    16
    """
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    out_dir = Path(out_dir) if out_dir is not None else Path.cwd()
    started = time.perf_counter()
    kinds = set(scene.compute)
    results: dict[str, Any] = {}
    notes: list[str] = []
    files: list[str] = []
    timings: dict[str, Callable[[], dict]] = {}
    try:
        if "codes" in kinds:
            results["codes"] = _compute_codes(scene.structure)
        if "analysis" in kinds:
            results["analysis"] = _compute_analysis(scene.structure)
        if kinds & _CHAIN_KINDS:
            listing = "chains" in kinds
            chain_result, chains = _compute_chains(scene.structure, workers, listing)
            if kinds & {"count", "chains"}:
                results["chains" if listing else "count"] = chain_result
            items = chains
            if "mechanisms" in kinds or scene.drawing.get("mechanisms"):
                mech_result, mechs = _compute_mechanisms(scene.structure, chains)
                if "mechanisms" in kinds:
                    results["mechanisms"] = mech_result
                if scene.drawing.get("mechanisms"):
                    items = mechs
            if "drawing" in kinds:
                drawing, note = _compute_drawing(scene, items, out_dir)
                if drawing is not None:
                    results["drawing"] = drawing
                    files.append(drawing["file"])
                if note:
                    notes.append(note)
    except SceneError:
        raise
    except SynthesisError as exc:
        raise SceneError(f"{scene.path}: [structure] {str(exc).rstrip('.')}.") from None
    for kind in scene.compute:
        if kind in BALANCE_TABLES:
            results[kind] = _solve_balance(scene, kind)
            timings[kind] = lambda kind=kind: _solve_balance(scene, kind)
    if "plot" in kinds:
        balance_kinds = [k for k in scene.compute if k in BALANCE_TABLES]
        written = []
        for kind in balance_kinds:
            suffix = "" if len(balance_kinds) == 1 else "_" + BALANCE_TABLES[kind][0]
            name = scene.plot.get("out", f"{scene.name}.png")
            out = out_dir / (Path(name).stem + suffix + Path(name).suffix)
            out_dir.mkdir(parents=True, exist_ok=True)
            try:
                _plot_balance(scene, kind, results[kind], out)
            except OSError as exc:
                raise SceneError(f"{scene.path}: cannot write the plot {out} ({exc.strerror or exc}).") from None
            written.append(str(out))
        files.extend(written)
        results["plot"] = {"files": written, "written": bool(written)}
    checks = tuple(_check_all(scene, results, timings))
    return SceneResult(scene.path, scene.name, scene.description, scene.compute, results, checks,
                       tuple(files), tuple(notes), time.perf_counter() - started)


# --------------------------------------------------------------------------- checking
def _lookup(results: dict, spec: _Expectation) -> tuple[bool, Any]:
    path = list(spec.path)
    if path[0] not in results and path[0] not in COMPUTE_KINDS:
        # shared keys (relative_residual, max_residual): the first computation that has it
        for kind in sorted(spec.kinds):
            if kind in results:
                path = [kind, *path]
                break
    if path[0] == "chains" and "chains" not in results:
        path[0] = "count"
    value: Any = results
    for step in path:
        try:
            value = value[step]
        except (KeyError, IndexError, TypeError):
            return False, None
    return True, value


def _close(a: Any, b: Any, rel: float) -> bool:
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if _is_num(a) and _is_num(b):
        return math.isclose(float(a), float(b), rel_tol=rel, abs_tol=_ABS_TOL)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_close(x, y, rel) for x, y in zip(a, b))
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        return set(map(str, a)) == set(map(str, b)) and all(_close(a[k], {str(j): w for j, w in b.items()}[str(k)], rel)
                                                            for k in a)
    return a == b


def _canonical_codes(texts) -> list[str]:
    from synth.code import Code

    return [str(Code.parse(t)) for t in texts]


def _compare(key: str, spec: _Expectation, below: bool, expected: Any, actual: Any, rel: float) -> tuple[bool, str]:
    """(met, detail): detail says what differs when not met."""
    if below:
        ok = _is_num(actual) and actual < expected
        return ok, f"{actual!r} is not below {expected!r}"
    if spec.compare in {"codes", "codes_include", "codes_exclude"}:
        want, got = _canonical_codes(expected), set(actual)
        missing = [c for c in want if c not in got]
        if spec.compare == "codes_exclude":
            present = [c for c in want if c in got]
            return not present, f"found {', '.join(present)}"
        if spec.compare == "codes_include":
            return not missing, f"missing {', '.join(missing)}"
        extra = [c for c in actual if c not in set(want)]
        parts = ([f"missing {', '.join(missing)}"] if missing else []) + ([f"unexpected {', '.join(extra)}"] if extra else [])
        return not parts, "; ".join(parts) or "different order"
    if spec.compare == "code":
        return _canonical_codes([expected]) == _canonical_codes([actual]), f"the run gave {actual!r}"
    if spec.compare == "codes_table":
        want = dict(zip(_canonical_codes(expected), expected.values()))
        got = dict(zip(_canonical_codes(actual), actual.values()))
        diff = [f"{c}: expected {want.get(c, 0)}, got {got.get(c, 0)}" for c in sorted(set(want) | set(got))
                if want.get(c, 0) != got.get(c, 0)]
        return not diff, "; ".join(diff)
    if spec.compare == "multiset":
        ok = isinstance(actual, list) and _close(sorted(expected), sorted(actual), rel)
        return ok, f"the run gave {actual!r}"
    if spec.compare == "table":
        exp = {str(k).strip(): v for k, v in expected.items()}
        got = {str(k): v for k, v in (actual or {}).items()}
        diff = [f"{k}: expected {exp.get(k, 0)!r}, got {got.get(k, 0)!r}" for k in sorted(set(exp) | set(got))
                if not _close(exp.get(k, 0), got.get(k, 0), rel)]
        return not diff, "; ".join(diff)
    return _close(expected, actual, rel), f"the run gave {actual!r}"


def _check_all(scene: Scene, results: dict, timings: Mapping[str, Callable[[], dict]]):
    for key, expected in scene.expect.items():
        base, below = _expect_base(key)
        spec = _EXPECT[base]
        found, actual = _lookup(results, spec)
        if not found:
            if "drawing" in spec.kinds and "drawing" not in results:
                yield Check(key, expected, None, "skipped", f"{key}: skipped, synth.draw is not installed")
                continue
            yield Check(key, expected, None, "failed", f"{scene.path}: [expect] {key} = {expected!r}, but the run "
                        "produced no such value.")
            continue
        ok, detail = _compare(key, spec, below, expected, actual, scene.rel_tol)
        if not ok and base == "seconds":
            # timings on a shared machine are noisy: the best of a few runs counts
            kind = next(iter(spec.kinds))
            for _ in range(_TIMING_RUNS - 1):
                actual = min(actual, timings[kind]()["seconds"])
                ok, detail = _compare(key, spec, below, expected, actual, scene.rel_tol)
                if ok:
                    break
        if ok:
            yield Check(key, expected, actual, "met", f"{key} = {_short(expected)}: met")
        else:
            yield Check(key, expected, actual, "failed",
                        f"{scene.path}: [expect] {key} = {_short(expected)} is not met: {detail}.")


def _short(value: Any, width: int = 70) -> str:
    text = repr(value)
    return text if len(text) <= width else text[: width - 1] + "…"


# --------------------------------------------------------------------------- directories
def run_directory(directory: str | Path, *, out_dir: str | Path | None = None, workers: int = 1,
                  progress: Callable[[str], None] | None = None) -> DirectoryResult:
    """Run every scene ``*.toml`` of ``directory`` (sorted by name).

    Files without a ``[scene]`` table (grid files, …) are skipped with a reason; a
    malformed scene is reported as an error sentence and the others still run.

    >>> r = run_directory("models")   # doctest: +SKIP
    >>> r.ok                          # doctest: +SKIP
    True
    """
    directory = Path(directory)
    if not directory.is_dir():
        raise SceneError(f"{directory}: not a directory of scene files.")
    results, errors, skipped = [], [], []
    for path in iter_scene_paths(directory):
        if progress:
            progress(str(path))
        try:
            doc = _read_toml(path)
            if not is_scene(doc):
                skipped.append((str(path), "no [scene] table: not a scene file"))
                continue
            results.append(run_scene(path, out_dir=out_dir, workers=workers))
        except SceneError as exc:
            errors.append((str(path), str(exc)))
    return DirectoryResult(str(directory), tuple(results), tuple(errors), tuple(skipped))


def iter_scene_paths(directory: str | Path) -> Sequence[Path]:
    """The ``*.toml`` files of ``directory`` in the order :func:`run_directory` runs them."""
    return sorted(Path(directory).glob("*.toml"))
