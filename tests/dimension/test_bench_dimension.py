"""benchmarks/bench_dimension.py: the classical problems' data, the sources' own answers re-checked, and
a short run's row."""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from synth.dimension import PathTarget

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def bench():
    spec = importlib.util.spec_from_file_location("bench_dimension", ROOT / "benchmarks" / "bench_dimension.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up there
    spec.loader.exec_module(module)
    yield module
    del sys.modules[spec.name]


def test_every_problem_loads_as_a_target_and_names_its_source(bench):
    for name, problem in bench.PROBLEMS.items():
        target = PathTarget(np.array(problem.points, dtype=float),
                            None if problem.inputs is None else np.array(problem.inputs, dtype=float))
        assert len(target) == len(problem.points) >= 4, name
        assert problem.source, name
        if problem.recorded is not None:
            assert problem.differs, f"{name}: a recorded answer needs the statements' difference beside it"


def test_the_eighteen_points_are_the_sources_with_0_05_not_0_005(bench):
    points = bench.PROBLEMS["eighteen points of a closed path, untimed"].points
    assert len(points) == 18 and (0.05, 0.75) in points and (0.005, 0.75) not in points


def test_the_closed_form_keeps_every_link_length(bench):
    """The sources' model, checked against itself: at any crank angle the crank, coupler and rocker keep
    their lengths and the coupler point stays where it is on the coupler."""
    rng = np.random.default_rng(4)
    for _ in range(20):
        r1, r4, r3 = rng.uniform(3, 4, 3)
        vector = [r1, rng.uniform(0.5, 1.0), r3, r4, *rng.uniform(-2, 2, 2), rng.uniform(0, 6.3), *rng.uniform(-5, 5, 2)]
        angles = np.sort(rng.uniform(0, 2 * math.pi, 7))
        pivots, crank, far, point = bench.source_model(vector, angles)
        assert math.dist(*pivots) == pytest.approx(r1)
        assert np.allclose(np.linalg.norm(crank - pivots[0], axis=1), vector[1])
        assert np.allclose(np.linalg.norm(far - crank, axis=1), r3)
        assert np.allclose(np.linalg.norm(far - pivots[1], axis=1), r4)
        assert np.allclose(np.linalg.norm(point - crank, axis=1), math.hypot(*vector[4:6]))
        assert np.allclose(np.linalg.norm(point - far, axis=1), math.hypot(vector[4] - r3, vector[5]))


@pytest.mark.parametrize("name, tolerance", [("six points on a line, untimed", 1e-26),
                                             ("five timed points on an arc, frame free", 1e-5)])
def test_the_sources_recorded_answer_gives_its_recorded_error_when_the_motion_layer_moves_it(bench, name, tolerance):
    problem = bench.PROBLEMS[name]
    again, gap = bench.recorded_by_motion(problem)
    recorded = problem.recorded["sum_squared_error"]
    if recorded < 1e-20:
        assert again < tolerance  # exact to rounding: the points are met
    else:
        assert again == pytest.approx(recorded, rel=tolerance)
    assert gap < 1e-9  # the motion layer and the closed form trace the same points


def test_a_short_run_returns_a_row_with_the_record_beside_it(bench):
    row = bench.run_problem("five timed points on an arc, frame free", budget=2.0)
    assert row["points"] == 5 and row["cpu_seconds"] > 0  # timings are reported, never bounded here
    assert row["sum_squared_error"] == pytest.approx(5 * row["error_rms"] ** 2, rel=1e-9, abs=1e-300)
    assert row["error_max"] <= math.sqrt(row["sum_squared_error"]) + 1e-15
    assert row["recorded_recomputed"] == pytest.approx(row["recorded_sum_squared_error"], rel=1e-5)
    assert "crank" in row["constraints"]  # the source's crank condition reached the synthesis
    assert "differs" in row and row["linkage"]
