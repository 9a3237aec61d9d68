"""Every docstring example of the synth and mechsynth packages runs."""

import doctest
import importlib

import pytest

MODULES = ["synth.code", "synth.chain", "synth.mobility", "synth.analysis", "synth.chain_analysis",
           "synth._number_synthesis", "synth._type_synthesis", "synth._realise", "synth._nauty", "synth._cpsat", "synth._executor", "synth._scheduler", "synth.checkpoint", "synth",
           "mechsynth", "mechsynth._argtypes", "mechsynth._output", "mechsynth.scene", "mechsynth.cli",
           "mechsynth.scene.registry", "mechsynth.scene.results", "mechsynth.scene.compare", "mechsynth.scene.types",
           "mechsynth.scene.structure", "mechsynth.scene.balancing", "mechsynth.scene.runner", "synth.schema",
           "mechsynth.commands.codes", "mechsynth.commands.chains", "mechsynth.commands.scene",
           "mechsynth.commands.balance", "synth.prismatic", "synth.planetary", "synth.repair",
           "mechsynth.commands.planetary"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0
