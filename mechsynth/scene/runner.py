"""Load a scene file, run the computations it lists, check its ``[expect]`` table.

The runner knows no computation by name: :data:`~mechsynth.scene.registry.KINDS` and
:data:`~mechsynth.scene.registry.TABLES` say what each word of ``compute`` and each
table means.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Annotated, Any

from pydantic import StrictStr, create_model

from mechbase import as_row, read_toml, show
from synth import SynthesisError
from mechbase.schema import Table, expect, refine

from .registry import KINDS, TABLES, ComputeKind, Run
from .results import Check, DirectoryResult, Scene, SceneError, SceneResult
from .types import Fraction, Number, Text

__all__ = ["load_scene", "is_scene", "run_scene", "run_directory", "iter_scene_paths"]


def _known_kinds(compute: list[str]) -> list[str]:
    allowed = ", ".join(KINDS)
    if not compute:
        raise ValueError(f"is empty; list at least one of {allowed}")
    for word in compute:
        if word not in KINDS:
            raise ValueError(f"holds unknown {word!r} (allowed: {allowed})")
    if len(set(compute)) != len(compute):
        raise ValueError("lists a computation twice")
    return compute


class _SceneTable(Table):
    """The ``[scene]`` table."""

    name: Text
    description: Text
    compute: Annotated[list[StrictStr], refine(_known_kinds), expect("a list of strings")]
    source: Text = ""
    rel_tol: Fraction = 1e-9


# --------------------------------------------------------------------------- loading
def _read_toml(path: Path) -> dict:
    if Path(path).suffix.lower() == ".json":  # a linkage saved as JSON: it read "not valid TOML (Invalid statement …)"
        raise SceneError(f"{path}: a scene file is TOML, and this is JSON (a linkage saved as .json moves with "
                         "'mechsynth move'; 'move' or 'dimension' with --save NAME.toml writes one as a scene).")
    return read_toml(path, error=SceneError, what="scene file", directory="use --all for a directory of scenes")


def is_scene(doc: Mapping[str, Any]) -> bool:
    """True when a parsed TOML document has a ``[scene]`` table (grid files and the like have none).

    >>> is_scene({"scene": {"name": "x"}}), is_scene({"dof": "1..3"})
    (True, False)
    """
    return isinstance(doc, Mapping) and "scene" in doc


def load_scene(path: str | Path) -> Scene:
    """Read and validate a scene file; raise :class:`SceneError` with one sentence otherwise.

    Every key is checked before any work: unknown tables and keys, wrong types, a
    missing ``[scene]``, ``[structure]`` or balance table, structure keys that no
    requested computation uses, and expectations that no requested computation provides.
    (The balance tables are the balance package's: it checks them when the scene runs.)

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
    [structure] has an unknown key 'loopz' (allowed: chain, code, compositions, counts, cranks, cylinders, dof, f, fractionated, h, idle_joints, input_link, links, loop_classes, loops, max_link_degree, max_multiplicity, n1, planar_only, prismatic, require, rigid_subchains, v).
    """
    path = Path(path)
    p = str(path)
    doc = _read_toml(path)
    if "scene" not in doc:
        raise SceneError(f"{p}: missing section [scene] (a scene needs name, description and compute).")
    allowed = ("scene", *TABLES, "expect")
    for name, value in doc.items():
        if name not in allowed:
            raise SceneError(f"{p}: unknown top-level key '{name}' (allowed: {', '.join(f'[{k}]' for k in allowed)}).")
        if not isinstance(value, Mapping):
            raise SceneError(f"{p}: key '{name}' must be a table [{name}], not {show(value)}.")
    head = _SceneTable.read(doc["scene"], source=p, where="[scene]", error=SceneError)
    compute = frozenset(head.compute)
    kinds = [KINDS[k] for k in head.compute]
    for kind in kinds:
        if kind.table is not None and kind.table not in doc:
            users = [k.name for k in kinds if k.table == kind.table]
            raise SceneError(f"{p}: missing section [{kind.table}] (compute {' and '.join(map(repr, users))} "
                             f"{'needs' if len(users) == 1 else 'need'} {TABLES[kind.table].hint}).")
    for name in TABLES:
        readers = [k for k, kind in KINDS.items() if name in (kind.table, *kind.reads)]
        if name in doc and not compute & set(readers):
            raise SceneError(f"{p}: section [{name}] is given but [scene] compute lists none of the computations "
                             f"that read it ({', '.join(map(repr, readers))}).")
    tables = {name: TABLES[name].read(doc[name], p, compute) for name in TABLES if name in doc}
    expect = _read_expect(p, doc.get("expect", {}), kinds)
    scene = Scene(p, head.name, head.description, tuple(head.compute), tables, expect, head.source, head.rel_tol)
    for kind in kinds:
        if kind.check is not None:
            kind.check(scene)
    return scene


def _read_expect(path: str, raw: Mapping[str, Any], kinds: list[ComputeKind]) -> dict:
    """Check that each key is provided by a listed computation and has the right type."""
    fields = {}
    for key in raw:
        providers = [k.name for k in KINDS.values() if k.provides(key)]
        base = key.removesuffix("_below")
        if not providers and any(base in k.expect for k in KINDS.values()):
            raise SceneError(f"{path}: [expect] key '{key}': '{base}' has no upper-bound form; write '{base}' = value.")
        if not providers:
            mine = sorted({e for k in kinds for e in k.expect})
            raise SceneError(f"{path}: [expect] has an unknown key '{key}' (the computations listed give: "
                             f"{', '.join(mine) or 'nothing to expect'}; see docs/scenes.md).")
        kind = next((k for k in kinds if k.provides(key)), None)
        if kind is None:
            raise SceneError(f"{path}: [expect] key '{key}' needs compute "
                             f"{' or '.join(repr(k) for k in sorted(providers))} in [scene], which is not listed.")
        fields[key] = (kind.expect[key].type if key in kind.expect else Number, ...)
    model = create_model("Expect", __base__=Table, **fields)
    model.read(raw, source=path, where="[expect]", error=SceneError)
    return dict(raw)


# --------------------------------------------------------------------------- running
def run_scene(scene: Scene | str | Path, *, out_dir: str | Path | None = None, workers: int = 1) -> SceneResult:
    """Run one scene: compute what ``[scene] compute`` lists and check ``[expect]``.

    Parameters
    ----------
    scene : Scene or path
        A validated :class:`Scene` or the path of a scene file.
    out_dir : path, optional
        Where drawings and plots are written.  Without it none is written: a ``drawing``
        or ``plot`` computation is then reported as not done, and its expectation skipped.
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
    >>> r.results["chains"].count                        # doctest: +SKIP
    16
    """
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    started = time.perf_counter()
    run = Run(scene, Path(out_dir) if out_dir is not None else None, workers)
    for name, kind in KINDS.items():  # registry order: a kind may use the results of earlier ones
        if name in scene.compute:
            run.results[name] = _run_kind(run, kind)
    rows = {name: as_row(result) for name, result in run.results.items()}  # as every output prints them
    checks = tuple(_check(run, rows, key, expected) for key, expected in scene.expect.items())
    files = tuple(f for r in rows.values() for f in r.get("files", ()))
    notes = tuple(f"{name} skipped: {r['skipped']}" for name, r in rows.items() if r.get("skipped"))
    return SceneResult(scene.path, scene.name, scene.description, scene.compute, run.results, checks, files, notes,
                       time.perf_counter() - started)


def _run_kind(run: Run, kind: ComputeKind) -> Any:
    try:
        return kind.run(run)
    except SceneError:
        raise
    except SynthesisError as exc:
        raise run.scene.error(f"[{kind.table}] {str(exc).rstrip('.')}") from None
    except OSError as exc:
        raise run.scene.error(f"compute '{kind.name}' cannot write {exc.filename or 'its file'} "
                              f"({exc.strerror or exc})") from None


# --------------------------------------------------------------------------- checking
def _lookup(result: Any, path: tuple) -> tuple[bool, Any]:
    for step in path:
        try:
            result = result[step]
        except (KeyError, IndexError, TypeError):
            return False, None
    return True, result


def _check(run: Run, rows: dict, key: str, expected: Any) -> Check:
    """How the expectation ``key`` fares against the rows of the scene's results."""
    scene = run.scene
    kind = next(KINDS[k] for k in KINDS if k in run.results and KINDS[k].provides(key))
    below = key not in kind.expect
    base = key.removesuffix("_below") if below else key
    spec = kind.expect[base]
    result = rows[kind.name]
    if result.get("skipped"):
        return Check(key, expected, None, "skipped", f"{key}: skipped ({result['skipped']})")
    found, actual = _lookup(result, spec.path or (base,))
    if not found:
        return Check(key, expected, None, "failed",
                     f"{scene.path}: [expect] {key} = {expected!r}, but the run produced no such value.")

    def compare(actual: Any) -> tuple[bool, str]:
        if below:
            ok = isinstance(actual, (int, float)) and not isinstance(actual, bool) and actual < expected
            return ok, f"{actual!r} is not below {expected!r}"
        return spec.compare(expected, actual, scene.rel_tol)

    ok, detail = compare(actual)
    for _ in range(spec.best_of - 1):
        if ok:
            break
        found, again = _lookup(as_row(kind.run(run)), spec.path or (base,))
        actual = min(actual, again)
        ok, detail = compare(actual)
    if ok:
        return Check(key, expected, actual, "met", f"{key} = {_short(expected)}: met")
    return Check(key, expected, actual, "failed",
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
            if not is_scene(_read_toml(path)):
                skipped.append((str(path), "no [scene] table: not a scene file"))
                continue
            results.append(run_scene(path, out_dir=out_dir, workers=workers))
        except SceneError as exc:
            errors.append((str(path), str(exc)))
    return DirectoryResult(str(directory), tuple(results), tuple(errors), tuple(skipped))


def iter_scene_paths(directory: str | Path) -> Sequence[Path]:
    """The ``*.toml`` files of ``directory`` in the order :func:`run_directory` runs them."""
    return sorted(Path(directory).glob("*.toml"))
