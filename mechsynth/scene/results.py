"""The values of the scene runner: a validated :class:`Scene`, its :class:`SceneResult` and checks.

>>> scene = Scene("s.toml", "s", "demo", ("codes",), {}, {})
>>> print(scene.error("[structure] needs the key 'dof'"))
s.toml: [structure] needs the key 'dof'.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

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
    pictures written; ``notes`` what was not done and why.
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
    errors: tuple[tuple[str, str], ...] = field(default=())
    skipped: tuple[tuple[str, str], ...] = field(default=())

    @property
    def ok(self) -> bool:
        return not self.errors and all(r.ok for r in self.results)

    def to_dict(self) -> dict:
        return {"directory": self.directory, "ok": self.ok,
                "scenes": [r.to_dict() for r in self.results],
                "errors": [{"path": p, "message": m} for p, m in self.errors],
                "skipped": [{"path": p, "reason": m} for p, m in self.skipped]}
