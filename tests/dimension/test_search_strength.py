"""The search's cheap parts to the letter: its refusals (with the number of points an
underdetermined target lacks, counted by hand), the similarity in closed form, a polish from an exact
start (a mechanism's own points: its answer known by construction), the result's errors and row,
and each constraint as the motion layer re-checks it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, FunctionTarget, MotionTarget, PathTarget, synthesize
from synth.dimension._search import DimensionalResult, _checked, _problem
from synth.errors import BadTarget, DimensionError
from synth.motion import Linkage, sweep
from synth.structure.chain import Chain, Mechanism
from tests.refusals import refused

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)  # joints 0-1, 0-3, 1-2, 2-3
#: a crank-rocker (crank 1, coupler 3.5, rocker 3, frame 4) with a coupler point
CRANK_ROCKER = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]], tracers={"P": (2, (2.0, 3.0))})
TIMED = PathTarget([[0, 0], [1, 0], [1, 1]], [0.0, 0.1, 0.2])


def own_points(linkage: Linkage, steps: int = 7, turn: float = 240.0) -> PathTarget:
    motion = sweep(linkage, steps=steps, stop=float(linkage.pose_inputs[0]) + math.radians(turn))
    return PathTarget(motion.tracers["P"], motion.inputs[:, 0])


def test_refusals_name_what_is_wrong():
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    assert refused(DimensionError, synthesize, five_bar, TIMED) == "dimensional synthesis drives one input, not W = 2"
    assert refused(DimensionError, synthesize, "0-1 1-2", TIMED) == "synthesize takes a Mechanism or a Linkage, not str"
    assert refused(DimensionError, synthesize, FOUR_BAR, [[0, 0], [1, 1]]) == \
        "the target must be a PathTarget, FunctionTarget or MotionTarget, not list"
    assert refused(DimensionError, synthesize, FOUR_BAR, TIMED, constraints={"crank": True}) == \
        "constraints must be a Constraints object"
    assert refused(DimensionError, synthesize, FOUR_BAR, TIMED, polish_only=True) == \
        "a polish alone starts from a dimensioned linkage, not from a Mechanism"
    for budget in (0, -1, math.nan, math.inf, "5"):
        assert refused(DimensionError, synthesize, FOUR_BAR, TIMED, budget=budget) == \
            f"the budget must be a positive number of seconds, not {budget!r}"
    for workers in (0, True, 1.5):
        assert refused(DimensionError, synthesize, FOUR_BAR, TIMED, workers=workers) == \
            f"workers must be a whole number ≥ 1, not {workers!r}"
    assert refused(DimensionError, synthesize, FOUR_BAR, TIMED, workers=2, scheduler="tcp://127.0.0.1:1") == \
        "workers and a scheduler contradict each other: the scheduler's workers evaluate the candidates"


@pytest.mark.parametrize("target, sentence", [
    # timed path: 8 coordinates + the tracer's 2 = 10 unknowns, 2 equations a point: 5 points
    (TIMED, "3 target points give 6 equations for the 10 unknowns of this path synthesis: give at least 5 points"),
    # untimed: 10 + the 3 inputs after the first = 13; each point adds 2 equations and 1 input: 2N ≥ 9 + N, 9 points
    (PathTarget([[0, 0], [1, 0], [1, 1], [0, 1]]),
     "4 target points give 8 equations for the 13 unknowns of this path synthesis: give at least 9 points"),
    # a function: the two moving pins (4) less the pose's place on its branch = 3 unknowns, 1 equation a pair
    (FunctionTarget([0.1, 0.2], [0.3, 0.5]),
     "2 target points give 2 equations for the 3 unknowns of this function synthesis: give at least 3 points"),
    # a motion: 10 + 2 inputs = 12 for 9 equations; 3 equations and 1 input a pose: 5 poses
    (MotionTarget([[0, 0, 0], [1, 0, 0.1], [1, 1, 0.3]]),
     "3 target points give 9 equations for the 12 unknowns of this motion synthesis: give at least 5 points"),
])
def test_an_underdetermined_target_says_how_many_points_it_needs(target, sentence):
    assert refused(BadTarget, synthesize, FOUR_BAR, target, budget=1).startswith(sentence + " (or allow")


@pytest.mark.parametrize("make", [
    lambda n: PathTarget([[math.cos(t), math.sin(t)] for t in range(n)], [0.1 * t for t in range(n)]),
    lambda n: PathTarget([[math.cos(t), math.sin(t)] for t in range(n)]),
    lambda n: FunctionTarget([0.1 * t for t in range(n)], [0.2 * t for t in range(n)]),
    lambda n: MotionTarget([[math.cos(t), math.sin(t), 0.1 * t] for t in range(n)]),
])
def test_the_points_a_refusal_asks_for_are_the_fewest_that_suffice(make):
    # the number said is read from the refusal; that many points give at least as many equations as unknowns,
    # one fewer do not (an untimed target's message once asked for one point more than it needs)
    message = refused(BadTarget, synthesize, FOUR_BAR, make(2), budget=1)
    enough = int(message.split("give at least ")[1].split()[0])
    problem = _problem(FOUR_BAR, make(enough), None, Constraints())[0]
    fewer = _problem(FOUR_BAR, make(enough - 1), None, Constraints())[0]
    assert problem.equations >= problem.unknowns and fewer.equations < fewer.unknowns


def test_a_polish_from_the_mechanism_that_traced_the_points_returns_it():
    target = own_points(CRANK_ROCKER)
    result = synthesize(CRANK_ROCKER, target, polish_only=True, budget=30,
                        constraints=Constraints(crank=True, max_ratio=4.5, pivots=(-1, 5, -1, 1), rocker=None))
    assert result.error_max < 1e-9 * target.size and result.kind == "path" and result.size == target.size
    assert result.method == "bounded least squares (trf) from a given start, timed"
    assert np.abs(result.inputs - target.inputs).max() < 1e-9
    assert np.abs(result.traced - target.points).max() < 1e-9
    assert result.evaluations >= 1 and result.seconds >= 0
    assert set(result.constraints) == {"branch", "crank", "ratio", "pivots"} and result.met and result.failed() == []
    assert result.constraints["crank"]["value"] == "turns fully"
    assert result.constraints["ratio"]["value"] == pytest.approx(4.0) and result.constraints["ratio"]["limit"] == 4.5
    assert np.abs(np.array(result.constraints["pivots"]["value"]) - [[0, 0], [4, 0]]).max() < 1e-9
    row = result.row()
    assert list(row) == ["kind", "chain", "frame", "points", "error_max", "error_rms", "relative_max", "relative_rms",
                         "size", "met", "seconds", "evaluations", "method"]
    assert row["chain"] == "0-1 0-3 1-2 2-3" and row["frame"] == 0 and row["points"] == 7
    full = result.to_dict()
    assert full["traced"] == result.traced.tolist() and full["linkage"]["chain"] == "0-1 0-3 1-2 2-3"


def test_the_results_errors_and_failures_are_said():
    errors = np.array([3.0, 4.0, 0.0])
    r = DimensionalResult(CRANK_ROCKER, TIMED, "motion", np.zeros(3), np.zeros((3, 3)), errors, 2.0, 1.23456, 9, "m",
                          {"crank": {"value": "rocks between 1° and 2°", "limit": None, "met": False},
                           "ratio": {"value": 5.0, "limit": 4.0, "met": False},
                           "branch": {"value": "every target point on the pose's branch", "limit": None, "met": True}},
                          angle_errors=np.array([0.0, math.pi / 180, 0.0]))
    assert r.error_max == 4.0 and r.error_rms == pytest.approx(math.sqrt(25 / 3))
    assert r.relative_max == 2.0 and r.relative_rms == pytest.approx(math.sqrt(25 / 3) / 2)
    assert r.angle_error_max_deg == pytest.approx(1.0) and r.seconds_rounded == 1.235
    assert not r.met and r.failed() == ["crank (rocks between 1° and 2°)", "ratio (5.0 against 4.0)"]
    assert r.row()["angle_error_max_deg"] == pytest.approx(1.0)
    plain = DimensionalResult(CRANK_ROCKER, TIMED, "path", np.zeros(3), np.zeros((3, 2)), errors, 2.0, 0.0, 1, "m")
    assert plain.met and "angle_error_max_deg" not in plain.row()


def test_each_constraint_is_rechecked_by_the_motion_layer():
    problem, _ = _problem(FOUR_BAR, TIMED, None, Constraints(rocker=(-0.5, 0.5), min_transmission=math.radians(10)))
    checked = _checked(problem, CRANK_ROCKER, np.array([0.0, 0.3, -0.2]))
    assert checked["branch"] == {"value": "every target point on the pose's branch", "limit": None, "met": True}
    assert checked["rocker"] == {"value": [-0.2, 0.3], "limit": [-0.5, 0.5], "met": True}
    # the transmission angle of the crank-rocker between the inputs −0.2 and 0.3: its least there, by hand
    # from the coupler b = √(2.5² + 3²), rocker c = √(0.5² + 3²) and the diagonal from the crank pin to the pivot
    b, c = math.hypot(2.5, 3), math.hypot(0.5, 3)
    worst = math.inf
    for phi in np.linspace(-0.2, 0.3, 2001):
        e2 = (4 - math.cos(phi)) ** 2 + math.sin(phi) ** 2
        mu = math.acos((b * b + c * c - e2) / (2 * b * c))
        worst = min(worst, mu, math.pi - mu)
    assert checked["transmission"]["value"] == pytest.approx(math.degrees(worst), abs=1e-4)
    assert checked["transmission"]["limit"] == pytest.approx(10.0) and checked["transmission"]["met"]
    outside = _checked(problem, CRANK_ROCKER, np.array([0.0, 0.6]))
    assert outside["rocker"] == {"value": [0.0, 0.6], "limit": [-0.5, 0.5], "met": False}
    # a rocker: a target beyond its limits (±2.518 rad) is off the branch, and it is no crank
    rocker = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [2.5 * math.cos(0.5), 2.5 * math.sin(0.5)], [3.2, 2.9]])
    crank_problem, _ = _problem(FOUR_BAR, PathTarget([[0, 0], [1, 0], [1, 1], [0, 1]]), None, Constraints(crank=True))
    off = _checked(crank_problem, rocker, np.array([0.0, 1.0, 2.0, 3.0]))
    assert off["branch"] == {"value": "a dead position lies between the target points", "limit": None, "met": False}
    assert off["crank"]["met"] is False and off["crank"]["value"].startswith("rocks between ")
    assert off["order"] == {"value": "the input turns 171.887° over the points, in order", "limit": None, "met": True}
    many = _checked(crank_problem, CRANK_ROCKER, np.array([0.0, 3.0, 5.0, 7.0]))
    assert many["order"]["met"] is False and many["crank"] == {"value": "turns fully", "limit": None, "met": True}


def test_a_budget_spent_before_any_polish_is_overrun_by_one_budget_at_most(monkeypatch):
    # the closing polish of the best candidate seen, where the budget ran out before any polish, did not watch the
    # clock: 'dimension --db … --budget 1' ran 112 CPU s, a six-bar's share of 0.09 s polished for 94.  On a clock
    # that reads 1 ms more at every reading (CPU time made exact), a budget of 0.05 s ends at 0.1 s, not 5
    import itertools
    import time

    readings = itertools.count()
    monkeypatch.setattr(time, "process_time", lambda: next(readings) * 1e-3)
    t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    result = synthesize(FOUR_BAR, PathTarget(np.c_[3 + np.cos(t), 2 + 0.5 * np.sin(t)]), budget=0.05)
    assert result.seconds <= 2 * 0.05 + 0.01 and result.evaluations < 100
    assert np.isfinite(result.error_max)  # an answer all the same: the best seen, polished for what was left
