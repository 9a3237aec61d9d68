"""Gear trains forming the device shafts, composed back into the linear forms."""

from __future__ import annotations

import numpy as np
import pytest

from balance import solve_arm
from balance.devices.transmission import compose, design_train


def run_train(train, shafts, psi):
    """Turn the drive shafts by ``psi`` and read the angle of the train's output (independent walk)."""
    angle = dict(zip(shafts, psi))
    for el in train:
        if el.element == "differential":
            # side gears of a bevel differential: (side1 − carrier) = −(side2 − carrier)
            angle[el.output] = angle[el.carrier] - (angle[el.side] - angle[el.carrier])
        else:
            angle[el.output] = angle[el.input] / el.ratio
    return angle[train[-1].output]


def test_example1_trains_are_the_textbook_ones(model):
    doc = model("arm_base_drives")
    doc["arm"]["transmission"] = True
    out = solve_arm(doc).to_dict()
    assert len(out["transmission"]) == 3
    for tr in out["transmission"]:
        assert tr["differentials"] == 1 and tr["error"] == 0.0
        stages = [el for el in tr["train"] if el["element"] != "differential"]
        # one input through a reducer of ratio 2 from ψ2, ψ3 or ψ4, the other by a spur stage of ratio 1 from ψ1
        assert sorted((el["element"], el["ratio"], el["input"]) for el in stages)[0][:2] == ("reducer", 2.0)
        assert ("spur stage", 1.0, "ψ1") in [(el["element"], el["ratio"], el["input"]) for el in stages]


@pytest.mark.parametrize("seed", range(5))
def test_random_forms_compose_back(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 7))
    shafts = [f"ψ{i + 1}" for i in range(n)]
    for _ in range(20):
        form = rng.choice([0.0, 1.0, -1.0, 0.5, -2.0, 0.122], size=n)
        if not np.any(form):
            continue
        form = form if form[np.flatnonzero(form)[0]] > 0 else -form
        train = design_train(form, shafts, "φ")
        np.testing.assert_allclose(compose(train, shafts), form, atol=1e-12)
        psi = rng.uniform(-3, 3, n)
        assert run_train(train, shafts, psi) == pytest.approx(float(form @ psi), abs=1e-12)
        assert sum(el.element == "differential" for el in train) == max(np.count_nonzero(form) - 1, 0)


def test_prismatic_example_uses_opposite_reducers(model):
    doc = model("arm_prismatic")
    doc["arm"]["transmission"] = True
    out = solve_arm(doc).to_dict()
    k = out["prismatic"][0]["gear_ratio"]
    ratios = sorted(el["ratio"] for tr in out["transmission"] for el in tr["train"]
                    if el["element"] == "reducer" and el["input"] == "ψ2")
    assert ratios == pytest.approx([-k, k])  # the textbook's two reducers of ratios +k and −k
    assert all(tr["error"] < 1e-15 for tr in out["transmission"])


def test_elements_by_hand():
    """A stage is a reducer above ratio 1, a spur stage at ±1, a step-up stage below; a reversing
    stage has a negative ratio; one shaft turning the crank at its own speed needs no stage."""
    (only,) = design_train([0.0, 1.0], ["ψ1", "ψ2"], "φ1")
    assert only.to_dict() == {"element": "shaft", "input": "ψ2", "output": "φ1", "ratio": 1.0, "reverses": False}
    (half,) = design_train([0.5, 0.0], ["ψ1", "ψ2"], "φ1")
    assert (half.element, half.ratio, half.input, half.output) == ("reducer", 2.0, "ψ1", "φ1")
    (double,) = design_train([0.0, -2.0], ["ψ1", "ψ2"], "φ1")
    assert (double.element, double.ratio, double.reverses) == ("step-up stage", -0.5, True)
    (back,) = design_train([-1.0], ["ψ1"], "φ1")
    assert (back.element, back.ratio, back.reverses) == ("spur stage", -1.0, True)
    assert design_train([1e-13, -1e-13], ["ψ1", "ψ2"], "φ1") == []  # below the tolerance: nothing to drive
    assert design_train([1e-13, 1.0], ["ψ1", "ψ2"], "φ1", tol=1e-14)[0].element == "reducer"
    assert compose([], ["ψ1", "ψ2"]) == [0.0, 0.0]


def test_three_shafts_by_hand():
    """φ = 0.5·ψ1 − ψ2 + 2·ψ3, the positive terms first: the first differential's carrier from ψ1 through a
    reducer 2/0.5 = 4, its side from ψ3 through a reversing step-up of −1/2; the second's carrier from the
    first's output through a reducer of 2, its side from ψ2 through a spur stage of −1/−1 = 1."""
    train = design_train([0.5, -1.0, 2.0], ["ψ1", "ψ2", "ψ3"], "φ")
    rows = [e.to_dict() for e in train]
    assert rows == [
        {"element": "reducer", "input": "ψ1", "output": "φ.c1", "ratio": 4.0, "reverses": False},
        {"element": "step-up stage", "input": "ψ3", "output": "φ.s1", "ratio": -0.5, "reverses": True},
        {"element": "differential", "carrier": "φ.c1", "side": "φ.s1", "output": "φ.1", "ratio": None,
         "reverses": False},
        {"element": "reducer", "input": "φ.1", "output": "φ.c2", "ratio": 2.0, "reverses": False},
        {"element": "spur stage", "input": "ψ2", "output": "φ.s2", "ratio": 1.0, "reverses": False},
        {"element": "differential", "carrier": "φ.c2", "side": "φ.s2", "output": "φ", "ratio": None,
         "reverses": False},
    ]
    assert compose(train, ["ψ1", "ψ2", "ψ3"]) == pytest.approx([0.5, -1.0, 2.0], abs=1e-15)


def test_trains_of_an_arm_with_their_check():
    from balance.devices.transmission import transmissions

    first, second, none = transmissions([[-1.0, 1.0], [0.0, 3.0], [0.0, 0.0]], ["ψ1", "ψ2"])
    assert (first.term, first.shaft, first.form, first.differentials, first.error) == (0, "φ1", (-1.0, 1.0), 1, 0.0)
    assert first.composed_form == pytest.approx((-1.0, 1.0))
    assert (second.shaft, second.differentials, second.train[0].ratio) == ("φ2", 0, pytest.approx(1 / 3))
    assert (none.train, none.composed_form, none.error) == ((), (0.0, 0.0), 0.0)
    d = first.to_dict()
    assert d == {"term": 0, "shaft": "φ1", "form": [-1.0, 1.0], "train": [e.to_dict() for e in first.train],
                 "differentials": 1, "composed_form": list(first.composed_form), "error": 0.0}
    from balance.devices.transmission import GearTrain

    off = GearTrain(1, "φ2", (1.0, 2.0), (), (1.0, 2.5))
    assert off.error == 0.5 and GearTrain(0, "φ", (), (), ()).error == 0.0


def test_the_tolerances_of_a_form():
    """A coefficient counts above ``tol``; a single one within ``tol`` of 1 is the shaft itself."""
    assert [e.input for e in design_train([1e-12, 1.0], ["ψ1", "ψ2"], "φ", tol=1e-12)] == ["ψ2"]
    assert design_train([1.5], ["ψ1"], "φ", tol=0.5)[0].element == "shaft"
    assert design_train([1.5], ["ψ1"], "φ", tol=0.4)[0].element == "step-up stage"


@pytest.mark.parametrize("ratio, kind", [
    (1 + 5e-13, "spur stage"), (-(1 - 5e-13), "spur stage"), (1 + 1e-12, "reducer"),  # (was a step-up stage)
    (1 + 3e-12, "reducer"), (1 - 3e-12, "step-up stage"), (-2.0, "reducer"), (-0.5, "step-up stage")])
def test_a_stage_is_named_by_its_ratio_with_no_gap(ratio, kind):
    """Within 1e-12 of ±1 a spur stage, above a reducer, below a step-up stage: every ratio has its name."""
    from balance.devices.transmission import _stage

    assert _stage("a", "b", ratio).element == kind
