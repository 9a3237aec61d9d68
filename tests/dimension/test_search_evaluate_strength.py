"""The search's costs and residual vectors on candidates whose answer is known by construction (a
crank-rocker's own points, the same points moved, a rocker driven past its dead positions), the curve
a candidate traces each way, a motion target polished from the mechanism that made it, and a designer's
region met on its edge (issue 37 item 8: the survivors of `dimension/_search`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, MotionTarget, PathTarget, synthesize
from synth.dimension._problem import CURVE_SAMPLES, INFEASIBLE
from synth.dimension._search import PENALTY, _checked, _Evaluate, _problem
from synth.motion import Linkage, motion_range, sweep
from synth.structure.chain import Chain, Mechanism

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
CRANK_ROCKER = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]], tracers={"P": (2, (2.0, 3.0))})
#: a rocker (crank 2.5, coupler 3.3, rocker 3, frame 4: 2.5 + 4 > 3.3 + 3, not Grashof): dead positions at ±q
ROCKER = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [2.5 * math.cos(0.5), 2.5 * math.sin(0.5)], [3.2, 2.9]],
                 tracers={"P": (2, (2.0, 3.0))})


def own_points(linkage: Linkage, steps: int = 7, turn: float = 240.0) -> PathTarget:
    motion = sweep(linkage, steps=steps, stop=float(linkage.pose_inputs[0]) + math.radians(turn))
    return PathTarget(motion.tracers["P"], motion.inputs[:, 0])


def test_the_cost_of_a_timed_candidate_is_its_mean_squared_error():
    """The crank-rocker's own seven points cost nothing; the same points moved by (0.3, −0.4) leave an error of
    0.5 at every point, so the cost is (0.5/scale)² — a mean over the points, not a sum."""
    target = own_points(CRANK_ROCKER)
    problem, _ = _problem(CRANK_ROCKER, target, None, Constraints())
    assert _Evaluate(problem)(problem.unknowns_of(CRANK_ROCKER)) == pytest.approx(0.0, abs=1e-20)
    moved = PathTarget(target.points + [0.3, -0.4], target.inputs)
    problem, _ = _problem(CRANK_ROCKER, moved, None, Constraints())
    cost = _Evaluate(problem)(problem.unknowns_of(CRANK_ROCKER))
    assert cost == pytest.approx((0.5 / problem.scale) ** 2, rel=1e-9)


def test_a_candidate_that_does_not_close_costs_more_than_every_one_that_does():
    """The rocker driven through 240° leaves its range: the share of samples where its dyad
    does not close raises the cost above INFEASIBLE, and the residual vector is that cost spread evenly."""
    target = own_points(CRANK_ROCKER)
    problem, _ = _problem(ROCKER, target, None, Constraints())
    evaluate, x = _Evaluate(problem), problem.unknowns_of(ROCKER)
    share = evaluate.timed(x)
    assert isinstance(share, float) and 0 < share < 1
    assert evaluate(x) == pytest.approx(INFEASIBLE * (1 + share), rel=1e-12) and evaluate(x) > INFEASIBLE
    vector = evaluate.vector(x, 1)
    assert len(vector) == problem.equations and np.all(vector == vector[0])
    assert float(vector @ vector) == pytest.approx(INFEASIBLE * (1 + share) ** 2, rel=1e-12)


def untimed(linkage: Linkage, constraints: Constraints = Constraints()):
    target = PathTarget(own_points(CRANK_ROCKER, steps=10, turn=300).points)
    return _problem(linkage, target, None, constraints)[0]


def test_an_untimed_candidate_off_its_branch_gets_an_even_vector_and_one_on_it_no_turn_penalty():
    problem = untimed(ROCKER)
    evaluate, x = _Evaluate(problem), problem.unknowns_of(ROCKER)
    size = problem.equations + 1  # the rows, then the turn beyond a full one
    far = np.concatenate((x, np.full(problem.points - 1, 0.6)))  # 5.4 rad: past the rocker's dead position
    vector = evaluate.vector(far, 1)
    assert len(vector) == size and np.all(vector == vector[0]) and vector[0] > math.sqrt(INFEASIBLE / size)
    assert vector[0] <= 2 * math.sqrt(INFEASIBLE / size)
    problem = untimed(CRANK_ROCKER)
    evaluate, x = _Evaluate(problem), problem.unknowns_of(CRANK_ROCKER)
    near = evaluate.vector(np.concatenate((x, np.full(problem.points - 1, 0.5))), 1)  # 4.5 rad, within a turn
    assert len(near) == size and near[-1] == 0.0 and np.all(np.isfinite(near))
    beyond = evaluate.vector(np.concatenate((x, np.full(problem.points - 1, 0.8))), 1)  # 7.2 rad
    assert beyond[-1] == pytest.approx(math.sqrt(PENALTY) * (7.2 - 2 * math.pi), rel=1e-12)


def test_the_curve_of_a_rocker_stops_at_its_dead_positions_each_way():
    """The motion layer's own range of the rocker bounds the inputs each way from the pose; a crank-rocker's
    curve goes the whole span both ways.  The transmission angles follow the samples they belong to."""
    lo, hi = motion_range(ROCKER).limits
    pose = float(ROCKER.pose_inputs[0])
    problem = untimed(ROCKER, Constraints(min_transmission=math.radians(5)))
    _, ways = _Evaluate(problem).curve(problem.unknowns_of(ROCKER))
    for way, end in ((1, hi), (-1, lo)):
        values, xs, mu, (theta, t) = ways[way]
        assert xs[0] == 0.0 and np.all(np.diff(way * xs) > 0)
        assert abs(xs[-1] + pose - end) < 2 * math.pi / CURVE_SAMPLES  # the last sample before the dead position
        assert mu is not None and len(mu) == len(values) == len(xs) == len(theta) == len(t)
        # the coupler's motion carries its point P (2, 3) of the pose through the traced values
        turn = np.exp(1j * theta) * (2 + 3j) + t[:, 0] + 1j * t[:, 1]
        assert np.abs(turn - (values[:, 0] + 1j * values[:, 1])).max() < 1e-12
    problem = untimed(CRANK_ROCKER, Constraints(min_transmission=math.radians(5)))
    _, ways = _Evaluate(problem).curve(problem.unknowns_of(CRANK_ROCKER))
    assert [len(ways[w][1]) for w in (1, -1)] == [CURVE_SAMPLES + 1] * 2
    values, xs, mu, _ = ways[-1]
    _, _, mu_all = problem.move(problem.linkage(problem.unknowns_of(CRANK_ROCKER)), xs)
    assert np.allclose(mu, mu_all, atol=1e-12)


def poses_of(linkage: Linkage, steps: int = 6) -> MotionTarget:
    """The coupler's poses (x, y of P and the coupler's angle) as the crank turns."""
    motion = sweep(linkage, steps=steps, stop=float(linkage.pose_inputs[0]) + math.radians(200))
    pins = np.asarray(motion.joints)[:, 3] - np.asarray(motion.joints)[:, 2]  # the coupler: joints 1-2 and 2-3
    return MotionTarget(np.column_stack((motion.tracers["P"], np.arctan2(pins[:, 1], pins[:, 0]))))


def test_a_motion_target_polished_from_the_mechanism_that_made_it_returns_it():
    target = poses_of(CRANK_ROCKER)
    result = synthesize(CRANK_ROCKER, target, polish_only=True, budget=30)
    assert result.kind == "motion" and result.error_max < 1e-9 and result.angle_errors.max() < 1e-9
    assert np.abs(result.traced[:, :2] - target.points).max() < 1e-9


def test_the_curve_places_a_motion_targets_own_poses_on_it():
    """Poses taken from the crank-rocker's own motion (a motion target has no timing): each lies on the curve
    its pose traces (distance 0), in order."""
    target = poses_of(CRANK_ROCKER)
    problem, _ = _problem(CRANK_ROCKER, target, None, Constraints())
    evaluate = _Evaluate(problem)
    _, ways = evaluate.curve(problem.unknowns_of(CRANK_ROCKER))
    values, _, _, link = ways[1]
    assert link is None  # a motion's body is matched as it is: no point of it to fit
    d, places = evaluate.project(values, target.poses)
    # (the curve is sampled: a pose between two samples is off their chord by about h²/8 of the curve's
    # radius, h = 2π/120, so its squared distance is below 1e-6 of the target's size squared)
    assert d[0] < 1e-24 and np.all(d < 1e-6) and np.all(np.diff(places) > 0)


def test_a_pivot_on_the_edge_of_the_designers_region_is_inside_it():
    """The crank-rocker's pivots (0, 0) and (4, 0) in the region x 0 … 4, y 0 … 1: both on its edges."""
    problem, _ = _problem(FOUR_BAR, own_points(CRANK_ROCKER), None, Constraints(pivots=(0.0, 4.0, 0.0, 1.0)))
    checked = _checked(problem, CRANK_ROCKER, np.array([0.0, 0.3]))
    assert checked["pivots"]["met"] is True
    problem, _ = _problem(FOUR_BAR, own_points(CRANK_ROCKER), None, Constraints(pivots=(0.0, 3.99, 0.0, 1.0)))
    assert _checked(problem, CRANK_ROCKER, np.array([0.0, 0.3]))["pivots"]["met"] is False


def test_an_untimed_candidate_with_no_usable_curve_costs_twice_infeasible():
    """A crank is asked for, and the rocker's curve stops short of a turn both ways: no direction is usable."""
    problem = untimed(ROCKER, Constraints(crank=True))
    evaluate, x = _Evaluate(problem), problem.unknowns_of(ROCKER)
    assert evaluate.untimed(x) == 1.0 and evaluate(x) == 2 * INFEASIBLE



def test_a_linkage_given_starts_the_first_run_of_the_global_search():
    """The crank-rocker that traced the points, given as the start: it is in the first generation, which ends
    the run at once (a few hundred evaluations, then the polish); from the bare mechanism the same search
    takes thousands (3 536 measured)."""
    result = synthesize(CRANK_ROCKER, own_points(CRANK_ROCKER), budget=30, seed=0)
    assert result.error_max < 1e-9 and result.evaluations < 1000
    assert result.method == "differential evolution (1 run) + bounded least squares (trf), timed"


def test_the_same_seed_gives_the_same_search():
    """Freudenstein's three precision points (test_synthesize.py): two searches with seed 3 evaluate the same
    candidates, as many of them, and return the same linkage."""
    from synth.dimension import FunctionTarget

    target = FunctionTarget(np.radians([35.0, 55.0, 80.0]), np.radians([60.0, 72.0, 95.0]))
    first, second = (synthesize(FOUR_BAR, target, budget=30, seed=3) for _ in range(2))
    assert first.error_max < 1e-9 and first.evaluations == second.evaluations
    assert np.array_equal(first.linkage.points, second.linkage.points)


def test_sampled_starts_of_the_same_chain_are_polished_first():
    """A source of starts hands an offset slider-crank (another chain: left out) and the crank-rocker that traced
    the points: the crank-rocker is polished before any global search and meets the points exactly."""
    slider_crank = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3=0"), 0), (0,), [[0, 0], [3.0, 0.4], [0.6, 0.8], [3.0, 0.4]],
                           {1: (1.0, 0.0)}, tracers={"P": (2, (1.5, 1.6))})
    handed = []

    def starts(mechanism, tracer_link, target, seed):
        handed.append((mechanism.chain.certificate == FOUR_BAR.chain.certificate, tracer_link, seed))
        return [slider_crank, CRANK_ROCKER]

    result = synthesize(FOUR_BAR, own_points(CRANK_ROCKER), budget=30, seed=4, starts=starts)
    assert handed == [(True, 2, 4)]
    assert result.error_max < 1e-9
    assert result.method == "sampled crank curves + bounded least squares (trf) from them, timed"


def test_a_transmission_angle_met_to_the_stated_tolerance(monkeypatch):
    """The worst transmission angle (stubbed) exactly MET below the limit is met; twice MET below is not."""
    from synth.dimension import _search

    limit = math.radians(30.0)
    problem, _ = _problem(FOUR_BAR, own_points(CRANK_ROCKER), None, Constraints(min_transmission=limit))
    for worst, met in ((limit - _search.MET, True), (limit - 2 * _search.MET, False), (None, False)):
        monkeypatch.setattr(_search, "_worst_transmission", lambda *a, w=worst: w)
        row = _checked(problem, CRANK_ROCKER, np.array([0.0, 0.3]))["transmission"]
        assert row["met"] is met and row["limit"] == pytest.approx(30.0)


def test_a_branch_the_motion_layer_cannot_trace_is_reported_unmet(monkeypatch):
    """When the re-check of the found linkage fails in the motion layer, the result says so in its one
    constraint row, unmet (a stand-in for the motion layer's refusal)."""
    from synth.dimension import _search
    from synth.errors import MotionError

    def refuse(*args):
        raise MotionError("the dyad does not close at 1.2 rad")
    monkeypatch.setattr(_search, "_checked", refuse)
    result = synthesize(CRANK_ROCKER, poses_of(CRANK_ROCKER), polish_only=True, budget=30)
    assert result.constraints == {"branch": {
        "value": "the motion layer could not trace the branch: the dyad does not close at 1.2 rad",
        "limit": None, "met": False}}
