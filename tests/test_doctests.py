"""Every docstring example of the synth package runs."""

import doctest
import importlib

import pytest

MODULES = ["synth._argtypes", "synth.scene", "synth.cli_scene", "synth.code", "synth.chain", "synth.mobility", "synth.analysis", "synth.chain_analysis",
           "synth._number_synthesis", "synth._type_synthesis", "synth._realise", "synth._cpsat",
           "synth._output", "synth.cli", "synth.cli_chains", "synth"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0
