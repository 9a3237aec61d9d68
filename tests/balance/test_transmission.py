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
