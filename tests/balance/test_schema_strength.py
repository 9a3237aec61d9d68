"""The checks of balance/schema.py that no scene exercises: each refusal's sentence, the limits of
the random seed, "inf" in an open pair, a drive matrix of numbers only, the tables a file may hold."""

from __future__ import annotations

import math

import pytest

from balance.errors import InvalidInput, SchemaError
from balance.schema import OWNED_BY_RUNNER, check_seed, load_toml, parse

SPRING = {"moment": 100, "range_deg": [20, 160], "r": [0.01, 0.1]}
SLIDER = {"mass": 1, "counter_mass": 1, "q_max": 1}


@pytest.mark.parametrize("word", ["inf", "+inf", "INF", " Infinity ", "+Inf"])
def test_no_bound_is_written_inf_in_any_case(word):
    assert parse({"spring": SPRING | {"a": [0.0, word]}}, "spring", "s.toml").a == [0.0, math.inf]


@pytest.mark.parametrize("word", ["-inf", "infinite", "1e999x"])
def test_other_words_are_not_a_number(word):
    with pytest.raises(SchemaError, match=r"^s\.toml: \[spring\] key 'a'"):
        parse({"spring": SPRING | {"a": [0.0, word]}}, "spring", "s.toml")


@pytest.mark.parametrize("seed", [0, 1, 2**32 - 1])
def test_every_seed_numpy_takes_is_taken(seed):
    assert check_seed(seed) == seed
    assert parse({"slider": SLIDER | {"dynamics": {"seed": seed}}}, "slider", "s.toml").dynamics.seed == seed


@pytest.mark.parametrize("seed", [-1, 2**32, -(2**40)])
def test_a_seed_numpy_refuses_is_one_sentence(seed):
    with pytest.raises(InvalidInput) as exc:
        check_seed(seed)
    assert str(exc.value) == f"the random seed must be a whole number from 0 to 4294967295, not {seed}."
    with pytest.raises(SchemaError) as exc:
        parse({"slider": SLIDER | {"dynamics": {"seed": seed}}}, "slider", "s.toml")
    assert str(exc.value) == (f"s.toml: [slider.dynamics] key 'seed' must be a whole number from 0 to "
                              f"4294967295, not {seed}.")


def test_drives_are_a_word_or_a_matrix_of_floats():
    assert parse({"arm": {"drives": "base"}}, "arm", "a.toml").drives == "base"
    assert parse({"arm": {}}, "arm", "a.toml").drives == "joint"
    drives = parse({"arm": {"drives": [[1, 0], [2, 1.5]]}}, "arm", "a.toml").drives
    assert drives == [[1.0, 0.0], [2.0, 1.5]] and all(type(x) is float for row in drives for x in row)


@pytest.mark.parametrize("drives", [[], [1, 2], [[1, 0], [True, 1]], [[1, 0], [math.nan, 1]],
                                    [[1, 0], [math.inf, 1]], [[1, "0"], [0, 1]], "joints", 3])
def test_a_drive_matrix_of_anything_but_finite_numbers_is_refused(drives):
    with pytest.raises(SchemaError) as exc:
        parse({"arm": {"drives": drives}}, "arm", "a.toml")
    assert str(exc.value).startswith(
        "a.toml: [arm] key 'drives' must be 'joint', 'base' or a square matrix of numbers, not ")


def test_the_runner_tables_are_ignored_and_any_other_is_named():
    assert OWNED_BY_RUNNER == {"scene", "expect", "plot"}
    doc = {"slider": SLIDER, "scene": {}, "expect": {}, "plot": {}}
    assert parse(doc, "slider", "s.toml").mass == 1.0
    with pytest.raises(SchemaError) as exc:
        parse({"slider": SLIDER, "arm": {}}, "slider", "s.toml")
    assert str(exc.value) == ("s.toml: the file has an unknown table [arm] (allowed here: [slider], [expect], "
                              "[plot], [scene]).")


def test_a_missing_table_or_a_document_that_is_no_table():
    with pytest.raises(SchemaError) as exc:
        parse({"plot": {}}, "pantograph", "p.toml")
    assert str(exc.value) == "p.toml: the file needs the table [pantograph]."
    with pytest.raises(SchemaError) as exc:
        parse([SLIDER], "slider", "p.toml")
    assert str(exc.value) == "p.toml: the document must be a TOML table."


def test_a_key_is_named_with_its_file_and_table():
    with pytest.raises(SchemaError) as exc:
        parse({"compare": {"arm": "x.toml", "target": 1.0}}, "compare", "c.toml")
    assert str(exc.value).startswith("c.toml: [compare] key 'target' must be < 1")


def test_load_toml_reads_a_file_and_refuses_a_missing_one(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text("[slider]\nmass = 2\n")
    assert load_toml(str(path)) == {"slider": {"mass": 2}}
    with pytest.raises(SchemaError) as exc:
        load_toml(str(tmp_path / "none.toml"))
    assert str(exc.value) == f"{tmp_path / 'none.toml'}: no such TOML file."


def test_a_table_given_without_a_file_is_called_input():
    with pytest.raises(SchemaError) as exc:
        parse({"plot": {}}, "slider")
    assert str(exc.value) == "<input>: the file needs the table [slider]."
