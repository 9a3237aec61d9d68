"""Every docstring example of the synth and mechsynth packages runs."""

import doctest
import importlib

import pytest

MODULES = ["synth.structure.code", "synth.structure.chain", "synth.structure.subchains", "synth.analysis.codes", "synth.analysis.chains",
           "synth.synthesis.number_synthesis", "synth.synthesis.type_synthesis", "synth.synthesis._realise", "synth.structure._nauty", "synth.synthesis._cpsat", "synth.execution.executor", "synth.execution.scheduler", "synth.execution.checkpoint", "synth",
           "mechsynth", "mechsynth._argtypes", "mechsynth._output", "mechsynth.scene", "mechsynth.cli",
           "mechsynth.scene.registry", "mechsynth.scene.results", "mechsynth.scene.compare", "mechsynth.scene.types",
           "mechsynth.scene.structure", "mechsynth.scene.balancing", "mechsynth.scene.runner", "synth.schema",
           "mechsynth.commands.codes", "mechsynth.commands.chains", "mechsynth.commands.scene",
           "mechsynth.commands.balance", "synth.synthesis.variants", "synth.gears.planetary", "synth.analysis.repair",
           "mechsynth.commands.planetary", "synth.execution.estimate", "synth.synthesis._sizing"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0
