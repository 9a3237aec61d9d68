"""Every docstring example of the mechbase, synth, balance and mechsynth packages runs (every module is
found by walking the packages: a new module cannot be left out)."""

import doctest
import importlib
import pkgutil

import pytest

import balance
import mechbase
import mechsynth
import synth

MODULES = sorted(
    [pkg.__name__ for pkg in (mechbase, synth, balance, mechsynth)]
    + [m.name for pkg in (mechbase, synth, balance, mechsynth) for m in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + ".")
       if not m.name.endswith(".__main__")]  # runs the command when imported
)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
