"""Motion generation of a slider-crank from no guess: its slider's RP dyad is the body point whose places at the
poses are collinear (Ball's point for four poses), checked against a closed form and a line fitted to the places;
a random slider-crank's 3, 4 and 5 coupler poses met exactly from the dyads (before: the global stage, 2–12 CPU s
for five poses; benchmarks/DIMENSION.md, *A slider-crank's poses from its dyads*)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from synth.dimension import MotionTarget, equations_and_unknowns, synthesize
from synth.dimension._dyads import dyad_starts, slider_dyads

from ..oracles.motion import follow, oracle_of

SLIDE, ROD_PIN = 1, 3  # the slider-crank's joints 0-1, 0=3, 1-2, 2-3: the guide 0=3 and the rod's pin 2-3


def balls_point(target: MotionTarget) -> complex:
    """The body point (from P, in the first pose's axes, as x + iy) whose places at four poses are collinear, by
    a closed form: in complex numbers X_j = p_j + e^{iφ_j} m, and the places 1, j, k are collinear where
    Im[(X_j − X_1) conj(X_k − X_1)] = 0, a circle A|m|² + Im[B m] + C = 0 through the pole of poses 1 and j.  The
    circles of (2, 3) and (2, 4) meet there and at Ball's point."""
    p = target.poses[:, 0] + 1j * target.poses[:, 1]
    a, d = np.exp(1j * (target.poses[:, 2] - target.poses[0, 2])) - 1, p - p[0]

    def circle(j, k):
        return (a[j] * np.conj(a[k])).imag, a[j] * np.conj(d[k]) - np.conj(d[j]) * a[k], (d[j] * np.conj(d[k])).imag

    (a1, b1, c1), (a2, b2, c2) = circle(1, 2), circle(1, 3)
    pole = -d[1] / a[1]
    along = np.conj(a2 * b1 - a1 * b2)  # the line of the circles' two common points: Im[(A₂B₁ − A₁B₂) m] = const
    t = -(2 * a1 * (pole * np.conj(along)).real + (b1 * along).imag) / (a1 * abs(along) ** 2)
    return complex(pole + t * along)


def fitted_line(places: np.ndarray) -> tuple[float, np.ndarray]:
    """The total least-squares line of points (N, 2) by numpy's SVD: (the largest distance from it, its unit
    direction)."""
    centred = places - places.mean(axis=0)
    _, _, vt = np.linalg.svd(centred)
    return float(np.abs(centred @ vt[1]).max()), vt[0]


def parallel(u, v) -> float:
    """|sin| of the angle between two directions."""
    return abs(u[0] * v[1] - u[1] * v[0]) / (np.hypot(*u) * np.hypot(*v))


def test_four_poses_slider_dyad_is_balls_point_and_the_sliders_own_pin(motion_poses):
    made = motion_poses.random_slider_crank(11)
    target = motion_poses.poses(made, 4, 200.0)
    error, m, along = slider_dyads(target)[0]
    first = target.poses[0, :2]
    ball = balls_point(target)
    assert error < 1e-12
    assert np.hypot(*(m - [ball.real, ball.imag])) < 1e-9 * target.size
    assert np.hypot(*(first + m - made.points[ROD_PIN])) < 1e-9 * target.size
    assert parallel(along, made.slides[SLIDE]) < 1e-9


def test_three_poses_slider_dyads_are_pins_whose_places_a_fitted_line_passes(motion_poses):
    target = motion_poses.poses(motion_poses.random_slider_crank(12), 3, 200.0)
    found = slider_dyads(target)
    assert len(found) >= 2  # three poses: a circle of them (the grid's minima give a few)
    turns = target.poses[:, 2] - target.poses[0, 2]
    for error, m, along in found:
        places = target.poses[:, :2] + np.column_stack((np.cos(turns) * m[0] - np.sin(turns) * m[1],
                                                        np.sin(turns) * m[0] + np.cos(turns) * m[1]))
        off, direction = fitted_line(places)
        assert error < 1e-12 and off < 1e-9 * target.size and parallel(along, direction) < 1e-9


def test_a_slider_dyad_of_poses_no_slider_passes_is_its_least_squares_line(motion_poses):
    """Six poses of a four-bar's coupler: no point of it moves on a line, and the best is no better than a line
    fitted to its places."""
    target = motion_poses.poses(motion_poses.random_four_bar(3), 6, 200.0)
    error, m, along = slider_dyads(target)[0]
    turns = target.poses[:, 2] - target.poses[0, 2]
    places = target.poses[:, :2] + np.column_stack((np.cos(turns) * m[0] - np.sin(turns) * m[1],
                                                    np.sin(turns) * m[0] + np.cos(turns) * m[1]))
    centred = places - places.mean(axis=0)
    assert error > 1e-4
    assert error * target.size == pytest.approx(np.sqrt(((centred @ [-along[1], along[0]]) ** 2).mean()), rel=1e-9)
    assert parallel(along, fitted_line(places)[1]) < 1e-9


def test_a_slider_cranks_dyad_starts_hold_the_slider_crank_itself(motion_poses):
    made = motion_poses.random_slider_crank(13)
    starts = dyad_starts(motion_poses.SLIDER_CRANK, 2, motion_poses.poses(made, 5, 200.0))
    assert any(np.allclose(s.points[[0, 2, 3]], made.points[[0, 2, 3]], atol=1e-9)
               and parallel(s.slides[SLIDE], made.slides[SLIDE]) < 1e-9 for s in starts)


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("count", [3, 4, 5])
def test_a_random_slider_cranks_coupler_poses_are_met_exactly_from_no_guess(motion_poses, seed, count):
    mechanism = motion_poses.SLIDER_CRANK
    target = motion_poses.poses(motion_poses.random_slider_crank(seed), count, 200.0)
    equations, unknowns = equations_and_unknowns(mechanism, target)
    assert (equations < unknowns) == (count < 5)  # 5 poses: the precision-point count of a slider-crank
    result = synthesize(mechanism, target, seed=seed, underdetermined=count < 5)
    assert result.relative_max < 1e-9 and result.angle_errors.max() < 1e-9, (result.relative_max, result.method)
    assert result.method.startswith("the target's dyads + bounded least squares") and result.met
    # re-checked by the independent reference solver: moved to the reported inputs, the found slider-crank passes
    # every pose, and its rod's pin stays on its guide — the line fitted to the pin's places is the guide's
    lk = result.linkage
    moved = follow(oracle_of(lk, tracers=True), np.asarray(result.inputs) - float(lk.pose_inputs[0]), math.radians(1))
    assert np.abs(moved[:, 4] - target.points).max() < 1e-9 * target.size
    rod = moved[:, 3] - moved[:, 2]
    turns = np.unwrap(np.arctan2(rod[:, 1], rod[:, 0]))
    want = target.poses[:, 2] - target.poses[0, 2]
    assert np.abs(np.angle(np.exp(1j * ((turns - turns[0]) - want)))).max() < 1e-9
    off, direction = fitted_line(moved[:, ROD_PIN])
    assert off < 1e-9 * target.size and parallel(direction, lk.slides[SLIDE]) < 1e-9


def test_the_commands_slider_crank_poses_are_met_and_three_refused_without_underdetermined(tmp_path, capsys,
                                                                                           motion_poses):
    """models/dimension_slider_motion.csv: five poses of the random slider-crank of seed 0, written to 12 digits."""
    from mechsynth.cli import main

    slider_crank = ["--mechanism", "0-1 1-2 2-3 3=0", "--frame", "0"]
    poses = Path(__file__).resolve().parents[2] / "models" / "dimension_slider_motion.csv"
    assert main(["dimension", str(poses), *slider_crank, "--format", "json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found["relative_max"] < 1e-11 and found["met"] and found["method"].startswith("the target's dyads")
    made = motion_poses.random_slider_crank(0)
    for name, k in (("0-1", 0), ("1-2", 2), ("2-3", 3)):  # the crank's pivot and pin, the rod's pin on the block
        assert np.hypot(*(np.asarray(found["linkage"]["points"][name]) - made.points[k])) < 1e-9
    three = tmp_path / "three.csv"
    three.write_text("".join(poses.read_text().splitlines(keepends=True)[:4]))
    assert main(["dimension", str(three), *slider_crank]) == 2
    err = capsys.readouterr().err
    assert "3 target points give 9 equations for the 12 unknowns" in err and err.count("\n") == 1
