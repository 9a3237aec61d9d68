"""Every docstring example of the balance package runs (the package's own files, found by walking it)."""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

import balance

MODULES = ["balance"] + sorted(m.name for m in pkgutil.walk_packages(balance.__path__, "balance."))


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
