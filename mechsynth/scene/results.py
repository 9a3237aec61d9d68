"""The values of the scene runner: a validated :class:`Scene`, its :class:`SceneResult` and checks.

>>> scene = Scene("s.toml", "s", "demo", ("codes",), {}, {})
>>> print(scene.error("[structure] needs the key 'dof'"))
s.toml: [structure] needs the key 'dof'.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from mechbase import Row, as_row
from synth import SynthesisError

__all__ = ["SceneError", "Scene", "Check", "SceneResult", "DirectoryResult"]


class SceneError(SynthesisError):
    """A scene file cannot be read or run; the message names the file and the key."""


@dataclass(frozen=True)
class Scene:
    """A validated scene file.

    Attributes
    ----------
    path : str
        The file it came from (used in every message).
    name, description : str
    compute : tuple of str
        Words of ``[scene] compute`` (keys of :data:`~mechsynth.scene.KINDS`), in the order given.
    tables : dict
        Each problem table, validated: ``"structure"`` a typed model, a balance table
        (``"arm"``, ``"spring"``, …) the TOML table the balance package reads.
    expect : dict
        The ``[expect]`` table as written.
    source : str
        Where the example comes from.
    rel_tol : float
        Relative tolerance of numeric expectations.
    """

    path: str
    name: str
    description: str
    compute: tuple[str, ...]
    tables: Mapping[str, Any]
    expect: Mapping[str, Any]
    source: str = ""
    rel_tol: float = 1e-9

    def error(self, message: str) -> SceneError:
        """``SceneError("PATH: message.")``: one sentence naming this scene's file."""
        return SceneError(f"{self.path}: {message.rstrip('.')}.")


@dataclass(frozen=True)
class Check(Row):
    """One expectation: ``status`` is ``"met"``, ``"failed"`` or ``"skipped"``."""

    key: str
    expected: Any
    actual: Any
    status: str
    message: str


@dataclass(frozen=True)
class SceneResult(Row):
    """What a scene computed and how each expectation fared.

    ``results`` maps each computation to its typed result (printed as its row, :attr:`rows`);
    ``files`` lists the pictures written; ``notes`` what was not done and why.
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

    row_keys = ("path", "name", "description", "compute", "ok", "results", "checks", "files", "notes",
                "seconds=seconds_shown")

    @property
    def seconds_shown(self) -> float:
        """The run time to the millisecond."""
        return round(self.seconds, 3)

    @property
    def ok(self) -> bool:
        """True when no expectation failed (skipped ones do not count against it)."""
        return all(c.status != "failed" for c in self.checks)

    @property
    def rows(self) -> dict:
        """Each computation's result as its row (``mechbase.as_row``): what every output prints."""
        return {name: as_row(result) for name, result in self.results.items()}

    @property
    def failed(self) -> list[Check]:
        return [c for c in self.checks if c.status == "failed"]



@dataclass(frozen=True)
class SceneFileError(Row):
    """A scene file that could not be run, and why (one sentence)."""

    path: str
    message: str


@dataclass(frozen=True)
class SkippedFile(Row):
    """A file of the directory that is no scene, and why it was passed over."""

    path: str
    reason: str


@dataclass(frozen=True)
class DirectoryResult(Row):
    """Every scene of a directory: results, errors (one sentence each) and skipped files."""

    directory: str
    results: tuple[SceneResult, ...]
    errors: tuple[tuple[str, str], ...] = field(default=())
    skipped: tuple[tuple[str, str], ...] = field(default=())

    row_keys = ("directory", "ok", "scenes=results", "errors=error_rows", "skipped=skipped_rows")

    @property
    def ok(self) -> bool:
        return not self.errors and all(r.ok for r in self.results)

    @property
    def error_rows(self) -> tuple[SceneFileError, ...]:
        return tuple(SceneFileError(*e) for e in self.errors)

    @property
    def skipped_rows(self) -> tuple[SkippedFile, ...]:
        return tuple(SkippedFile(*s) for s in self.skipped)
