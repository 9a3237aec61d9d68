"""The package's front doors: ``balance``'s lazily loaded names and ``balance.problems``' readers."""

from __future__ import annotations

import importlib

import pytest

import balance
from balance import SchemaError
from balance.problems import (
    READERS, ArmProblem, CompareProblem, PantographProblem, SliderProblem, SpringProblem, read_problem, solve_arm,
    solve_compare, solve_pantograph, solve_prismatic, solve_spring,
)

#: the public names and the module each is defined in, written out here (not read from the package)
SOME_HOMES = {"solve_arm": "problems", "ArmProblem": "problems.arm", "Arm": "model.arm", "load_urdf": "model.urdf",
              "fit_spring": "devices.fit", "design_spring": "devices.helical", "c_min": "devices.countermass",
              "plot_compare": "plots", "box_extremes": "extremes", "InvalidInput": "errors", "parse": "schema"}


@pytest.mark.parametrize("name, home", sorted(SOME_HOMES.items()))
def test_a_public_name_is_its_modules_object_and_stays_loaded(name, home, monkeypatch):
    value = getattr(importlib.import_module(f"balance.{home}"), name)
    if name in vars(balance):  # loaded by an earlier import: unload it, so that reading it loads it again
        monkeypatch.delattr(balance, name)
    assert name not in vars(balance)
    assert getattr(balance, name) is value
    assert vars(balance)[name] is value  # loaded once: later reads do not go through __getattr__
    assert balance.__getattr__(name) is value


def test_every_listed_name_loads():
    assert balance.__all__ == sorted(balance.__all__) and set(SOME_HOMES) <= set(balance.__all__)
    for name in balance.__all__:
        assert getattr(balance, name) is not None, name


def test_an_unknown_name_is_refused_in_pythons_words():
    with pytest.raises(AttributeError) as ei:
        balance.no_such_device  # noqa: B018
    assert str(ei.value) == "module 'balance' has no attribute 'no_such_device'"
    assert not hasattr(balance, "synth")  # balance never imports synth


def test_dir_lists_the_public_names_and_the_loaded_ones_sorted():
    names = dir(balance)
    assert names == sorted(names) and len(names) == len(set(names))
    assert set(balance.__all__) <= set(names) and {"importlib", "__getattr__", "__dir__"} <= set(names)


@pytest.mark.parametrize("table, problem", [("arm", ArmProblem), ("spring", SpringProblem), ("slider", SliderProblem),
                                            ("pantograph", PantographProblem), ("compare", CompareProblem)])
def test_read_problem_reads_the_one_table_its_reader_names(table, problem):
    assert READERS[table].__module__ == f"balance.problems.{table}" and type(READERS[table]).__name__ == "function"
    with pytest.raises(SchemaError) as ei:
        read_problem({table: {"nonsense": 1}, "scene": {}}, "p.toml")  # [scene] belongs to the scene runner
    assert str(ei.value).startswith(f"p.toml: [{table}] has an unknown key 'nonsense' (allowed: ")
    assert problem.__name__.endswith("Problem")


def test_read_problem_of_the_docstrings_arm():
    doc = {"arm": {"links": [{"joint": "revolute", "length": 1.0, "weight": 10.0}]}}
    pb = read_problem(doc)
    assert isinstance(pb, ArmProblem) and pb.solve().terms[0].amplitude == 5.0  # 10 N at half of 1 m


@pytest.mark.parametrize("doc, source, listed", [
    ({}, None, "none"),
    ({"scene": {}, "expect": {}, "plot": {}}, "s.toml", "none"),  # the runner's tables are not balance tables
    ({"foo": {}, "scene": {}}, None, "[foo]"),
    ({"arm": {}, "spring": {}}, "y.toml", "[arm], [spring]"),
])
def test_read_problem_needs_exactly_one_table(doc, source, listed):
    with pytest.raises(SchemaError) as ei:
        read_problem(doc) if source is None else read_problem(doc, source)
    assert str(ei.value) == (f"{source or '<input>'}: a balance problem needs exactly one of the tables [arm], "
                             f"[spring], [slider], [pantograph] or [compare], not {listed}.")


@pytest.mark.parametrize("solve, table", [(solve_arm, "arm"), (solve_spring, "spring"), (solve_prismatic, "slider"),
                                          (solve_pantograph, "pantograph"), (solve_compare, "compare")])
def test_each_solver_names_its_file_or_its_table(solve, table):
    default = {"slider": "<slider>"}.get(table, f"<{table}>")
    for args, where in ((("x.toml",), "x.toml"), ((), default)):
        with pytest.raises(SchemaError) as ei:
            solve({table: {"nonsense": 1}}, *args)
        assert str(ei.value).startswith(f"{where}: [{table}] has an unknown key 'nonsense'")


def test_solve_prismatic_of_the_docstrings_slider():
    """The discriminant 2M(C − I − m·q²) − m²q² of the laws is zero at the stroke's end for C_min: 2 kg,
    0.1 kg·m², two 2 kg counter-masses, ±0.5 m."""
    res = solve_prismatic({"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 2, "q_max": 0.5}})
    C, m, inertia, M, q = res.counter_mass.C_min, 2.0, 0.1, 2.0, 0.5
    assert 2 * M * (C - inertia - m * q * q) - m * m * q * q == pytest.approx(0.0, abs=1e-12)
