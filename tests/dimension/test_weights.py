"""Per-point weights of a target: the synthesis minimises Σ weight × squared error, a point of weight 2
counting as the point given twice (benchmarks/DIMENSION.md: [HCDJ]'s ten points repeat the first);
bad weights are refused in one sentence."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechsynth.cli import main
from synth.dimension import FunctionTarget, MotionTarget, PathTarget, read_target, synthesize
from synth.errors import BadTarget

from .test_synthesize import FOUR_BAR, traced_again

# six timed points off a circle: a point on the crank (link 1) passes c + q·e^{iθ}, linear in c and q,
# so the best crank point for any weights is a weighted linear least squares (an independent method)
ANGLES = np.radians([0.0, 40.0, 80.0, 120.0, 160.0, 200.0])
POINTS = np.array([[1.0, 0.0], [0.8, 0.62], [0.2, 1.05], [-0.45, 0.9], [-0.98, 0.3], [-0.9, -0.35]])


def circle_fit(points: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """The points c + q·e^{iθ} nearest the points in plain least squares (rows listed twice count twice)."""
    a = np.column_stack((np.ones(len(angles)), np.exp(1j * angles)))
    coef, *_ = np.linalg.lstsq(a, points[:, 0] + 1j * points[:, 1], rcond=None)
    z = a @ coef
    return np.column_stack((z.real, z.imag))


def crank_point(target: PathTarget):
    result = synthesize(FOUR_BAR, target, tracer_link=1, budget=3, seed=0, underdetermined=True)
    # re-checked: the linkage, moved by the motion layer, passes the reported points
    assert np.abs(traced_again(result) - result.traced).max() < 1e-9
    return result


def test_a_point_of_weight_2_counts_as_the_point_given_twice():
    weights = np.array([2.0, 1, 1, 1, 1, 1])
    result = crank_point(PathTarget(POINTS, ANGLES, weights))
    twice = np.concatenate(([0], np.arange(6)))  # the first point listed twice
    best = circle_fit(POINTS[twice], ANGLES[twice])[1:]
    assert np.abs(result.traced - best).max() < 1e-7
    squares = ((best - POINTS) ** 2).sum(axis=1)
    assert result.weighted_sum_squares == pytest.approx(float(weights @ squares), rel=1e-9)
    # the reported errors are the distances, each point once; the weighted sum is recomputed from them
    assert np.allclose(result.errors, np.hypot(*(result.traced - POINTS).T), atol=1e-12)
    assert result.error_rms == pytest.approx(math.sqrt(np.mean(result.errors ** 2)), rel=1e-12)
    assert result.row()["weighted_sum_squares"] == result.weighted_sum_squares


def test_weights_move_the_optimum_towards_the_heavy_point():
    plain = crank_point(PathTarget(POINTS, ANGLES))
    heavy = crank_point(PathTarget(POINTS, ANGLES, [1, 1, 1, 10, 1, 1]))
    assert np.abs(plain.traced - circle_fit(POINTS, ANGLES)).max() < 1e-7
    assert plain.weighted_sum_squares is None and "weighted_sum_squares" not in plain.row()
    assert heavy.errors[3] < plain.errors[3] / 2  # the heavy point is met closer ...
    assert (heavy.errors ** 2).sum() > (plain.errors ** 2).sum()  # ... at the others' expense


def test_a_point_of_weight_0_is_left_out():
    extra = np.vstack((POINTS, [[3.0, 3.0]]))
    result = crank_point(PathTarget(extra, np.append(ANGLES, math.radians(240)), [1, 1, 1, 1, 1, 1, 0]))
    assert np.abs(result.traced[:6] - circle_fit(POINTS, ANGLES)).max() < 1e-7
    assert result.errors[6] > 1.0  # (the far point, counted for nothing, is not met)


def test_weights_count_the_equations():
    # nine untimed points: 18 equations for the four-bar's 18 unknowns (its 8 coordinates, the tracer's 2, 8 inputs);
    # with one point of weight 0, 16
    points = np.c_[np.cos(np.arange(9)), np.sin(np.arange(9)) * 0.5]
    with pytest.raises(BadTarget, match=r"^9 target points \(8 of weight above 0\) give 16 equations for the 18 "):
        synthesize(FOUR_BAR, PathTarget(points, weights=[1] * 8 + [0]), budget=1)


@pytest.mark.parametrize("weights, said", [
    ([1, -1, 1], "a weight must be 0 or more: row 2 has -1"),
    ([1, math.nan, 1], "the weights are not all finite numbers: row 2 is nan"),
    ([0, 0, 0], "the weights are all 0: no point would count"),
    ([1, 2], "the target gives 2 weights for 3 points: give one per row"),
    ([[1, 2, 3]], "the weights must be a list of numbers, not an array of shape (1, 3)"),
])
def test_bad_weights_are_refused_in_one_sentence(weights, said):
    with pytest.raises(BadTarget) as caught:
        PathTarget([[0, 0], [1, 0], [1, 1]], weights=weights)
    assert str(caught.value) == said


def test_every_kind_of_target_takes_weights():
    assert FunctionTarget([0.1, 0.2, 0.3], [1, 2, 3], weights=[1, 2, 1]).weights.tolist() == [1, 2, 1]
    assert MotionTarget([[0, 0, 0], [1, 0, 0], [1, 1, 0]], weights=[0, 1, 1]).weights.tolist() == [0, 1, 1]
    with pytest.raises(BadTarget, match="^the target gives 4 weights for 3 pairs: give one per row$"):
        FunctionTarget([0.1, 0.2, 0.3], [1, 2, 3], weights=[1, 1, 1, 1])
    with pytest.raises(BadTarget, match="^the target gives 1 weights for 2 poses: give one per row$"):
        MotionTarget([[0, 0, 0], [1, 0, 0]], weights=[1])


def test_a_weight_column_is_read_from_csv_and_json(tmp_path):
    csv = tmp_path / "t.csv"
    csv.write_text("x,y,input_deg,weight\n0,0,0,2\n1,0,30,1\n1,1,60,0.5\n")
    target = read_target(csv)
    assert target.weights.tolist() == [2, 1, 0.5] and target.inputs[1] == pytest.approx(math.radians(30))
    js = tmp_path / "f.json"
    js.write_text('[{"input": 0.1, "output": 1, "weight": 3}, {"input": 0.2, "output": 2, "weight": 1}]')
    assert read_target(js).weights.tolist() == [3, 1]
    assert read_target(tmp_path / "t.csv").kind == "path"


def test_a_bad_weight_in_a_file_is_one_sentence_and_exit_2(tmp_path, capsys):
    bad = tmp_path / "t.csv"
    bad.write_text("x,y,weight\n0,0,1\n1,0,-2\n1,1,1\n")
    assert main(["dimension", str(bad), "--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0", "--budget", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["mechsynth: a weight must be 0 or more: row 2 has -2"]

