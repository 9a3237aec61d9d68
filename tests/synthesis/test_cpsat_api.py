"""The engine calls OR-Tools' CP-SAT through its PEP 8 API only: every kind of model it builds
(number synthesis, stage A's branch multigraphs, stage B's weight vectors, gear tooth design) is
built and solved here with OR-Tools' deprecation warnings — which every pre-PEP 8 name such as
``NewIntVar`` raises — turned into errors, and with the model class OR-Tools ships (nothing of it
overridden, no stand-in module in ``sys.modules``)."""

from __future__ import annotations

import subprocess
import sys
import warnings

import pytest

import synth
from synth.gears import GearTrain, design
from synth.synthesis import _cpsat

DEPRECATED = r".* is a deprecated function\. Use .* instead\."


@pytest.fixture
def solver_calls(monkeypatch):
    """Every model solved, by the module that built it (the helpers are imported where a model is
    built); results kept by earlier runs are not read (synth.execution.memo off)."""
    from synth.execution import memo

    monkeypatch.setenv("MECHSYNTH_CACHE", "off")
    memo._store.cache_clear()
    monkeypatch.setattr(memo, "_store", memo._store)  # cleared again on the way out (below)
    seen: list[str] = []

    def counted(name):
        real = getattr(_cpsat, name)

        def wrapper(model, *args, **kwargs):
            seen.append(sys._getframe(1).f_globals["__name__"])
            return real(model, *args, **kwargs)

        return wrapper

    for name in ("all_solutions", "each_solution"):
        monkeypatch.setattr(_cpsat, name, counted(name))
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=DEPRECATED, category=DeprecationWarning)
        yield seen
    memo._store.cache_clear()


def test_every_synthesis_model_uses_the_pep8_api(solver_calls):
    from synth.synthesis.number_synthesis import _solve_model, make_problem

    # (a query this small is listed without the model: its model is solved here)
    assert [str(c) for c in sorted(_solve_model(make_problem(1, loops=2)))] == ["42/0", "51/1", "60/2"]
    # five parallel cranks on a 5-joint frame: stage A's model and stage B's CP-SAT model (the
    # crank constraint is the one stage B's shortcuts do not take)
    counts = synth.count_chains(1, 10, v="0..3", require=["5=1.."], cranks=["5=5"], workers=1)
    assert counts["count"] == 32  # models/locomotive_cranks.toml
    # (stage A of codes this small runs its plain search: its model is solved here)
    from synth.synthesis.stage_a import Conventions, _contracted_by_model

    assert len(_contracted_by_model(synth.Code.parse("6301/0"), Conventions())) > 0
    assert {"synth.synthesis.number_synthesis", "synth.synthesis.stage_a", "synth.synthesis.stage_b"} <= set(solver_calls)


def test_gear_design_uses_the_pep8_api(solver_calls):
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=DEPRECATED, category=DeprecationWarning)
        found = design(GearTrain.parse("0-1-2 2-3 0~3i 1~3"), 0, 1, 2, "4.63", tolerance="0.5%",
                       teeth=(17, 100), planets=3, best=2)
    assert found


def test_the_model_class_is_or_tools_own_and_no_module_stands_in():
    code = ("import sys, synth; synth.count_chains(1, 8, workers=1); "
            "from ortools.sat.python import cp_model; import synth.synthesis._cpsat as c; "
            "assert c.cp_model.CpModel is cp_model.CpModel; "
            "assert type(sys.modules['pandas']).__name__ == 'module', 'a stand-in pandas'; "
            "m = cp_model.CpModel(); assert callable(m.NewIntVar), 'pre-PEP 8 names removed by the engine'")
    subprocess.run([sys.executable, "-c", code], check=True)
