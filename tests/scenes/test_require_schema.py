"""The ``require`` key of scene and grid files (synth.schema.Require): both spellings read as the
engine's ``I=A..B`` list, every malformed one refused in one sentence naming the file and the key."""

from __future__ import annotations

import pytest
from mechbase.schema import Table

from synth.schema import Require


class _Structure(Table):
    require: Require = []


def _read(value):
    return _Structure.read({"require": value}, source="x.toml", where="[structure]").require


def test_both_spellings_read_as_the_engines_list():
    assert _read(["5=1..", " 3 = 0..2 ", "4=2", "6 = 2 .. 6"]) == ["5=1..", " 3 = 0..2 ", "4=2", "6 = 2 .. 6"]
    assert _read({"5": "1..", " 3 ": 0, "4": "2..5"}) == ["5=1..", "3=0", "4=2..5"]
    assert _read([]) == [] and _read({}) == []


SHAPE = 'x.toml: [structure] key \'require\' must be a list of strings like "5=1.." or a table { 5 = "1.." }, not '


@pytest.mark.parametrize("value, said", [
    (["5=x"], "['5=x']"), (["x5=1"], "['x5=1']"), (["5=1x"], "['5=1x']"), (["5"], "['5']"),
    (["=1"], "['=1']"), (["5=1..2..3"], "['5=1..2..3']"), (["5=1", "5=..2"], "['5=1', '5=..2']"),
    ({"x": "1"}, "{ x = '1' }"), ("5=1", "'5=1'"), ([5], "[5]"),
])
def test_a_malformed_requirement_is_refused_in_one_sentence(value, said):
    with pytest.raises(ValueError) as info:
        _read(value)
    assert str(info.value) == SHAPE + said + "."


@pytest.mark.parametrize("value", [["5=3..1"], {"5": "3..1"}, ["4=0", "5=3..1"]])
def test_an_empty_range_is_refused_in_either_spelling(value):
    with pytest.raises(ValueError) as info:
        _read(value)
    assert str(info.value) == "x.toml: [structure] key 'require' is the empty range '3..1' (1 < 3)."
