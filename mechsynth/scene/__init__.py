"""Scenes: one design problem per TOML file, run and checked against its ``[expect]`` table.

A scene says what the problem is (``[structure]`` for structural synthesis, or one of
the balance package's tables ``[arm]``, ``[spring]``, ``[slider]``, ``[pantograph]``),
what to compute (``[scene] compute = [...]``) and, optionally, what the results must be
(``[expect]``).  The runner validates the whole file before any work (pydantic models,
one sentence per mistake), builds only the models the requested computations need (a
codes-only scene never imports the graph realisation, a balancing scene never imports
synth's solvers) and reports every expectation as met, failed (with both values) or
skipped (a picture when no output directory was given).  The format is described in
``docs/scenes.md``.

The package is organised so that a computation is added in one place:

- :mod:`~mechsynth.scene.registry` — :class:`ComputeKind` (a word of ``compute``),
  :class:`Expectation` (an ``[expect]`` key), :class:`SceneTable` (a table), the registries;
- :mod:`~mechsynth.scene.structure` — ``[structure]`` and the structural computations;
- :mod:`~mechsynth.scene.balancing` — the balance tables (delegated to ``balance.problems``) and ``plot``;
- :mod:`~mechsynth.scene.runner` — load, run, check; :mod:`~mechsynth.scene.results` — the values.

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

from . import balancing, gear_trains, gears, motion, structure
from .registry import KINDS, TABLES, ComputeKind, Expectation, Run, SceneTable, register

# The run order of a scene's computations: structure first (others may read its results), then
# balancing, joint kinds and the planetary layout, gear trains, dimensioned mechanisms.
register(structure.FAMILY, balancing.FAMILY, gears.FAMILY, gear_trains.FAMILY, motion.FAMILY)
from .results import Check, DirectoryResult, Scene, SceneError, SceneResult
from .runner import is_scene, iter_scene_paths, load_scene, run_directory, run_scene

__all__ = [
    "SceneError", "Scene", "Check", "SceneResult", "DirectoryResult",
    "KINDS", "TABLES", "ComputeKind", "Expectation", "SceneTable", "Run",
    "load_scene", "is_scene", "run_scene", "run_directory", "iter_scene_paths",
]
