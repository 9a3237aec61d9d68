"""Dimensional synthesis against exact answers: a four-bar's own coupler points found again (with
and without timing), Freudenstein's closed form, a slider-crank, Burmester's three poses; every
answer re-checked by the motion layer."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, FunctionTarget, MotionTarget, PathTarget, link_ratio, synthesize
from synth.errors import BadTarget, DimensionError
from synth.motion import Linkage, assemble, motion_range, sweep
from synth.structure.chain import Chain, Mechanism

from ..oracles.motion import follow, oracle_of, traced_by_the_oracle

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)  # joints 0-1, 0-3, 1-2, 2-3
SLIDER_CRANK = Mechanism(Chain.parse("0-1 1-2 2-3 3=0"), frame=0)


def random_crank_rocker(seed: int) -> Linkage:
    """A crank-rocker with a coupler point P, its dimensions drawn at random."""
    rng = np.random.default_rng(seed)
    while True:
        a, d, b, c = rng.uniform(0.5, 1.0), rng.uniform(2.5, 3.5), rng.uniform(2.5, 3.5), rng.uniform(2.0, 3.0)
        phi = rng.uniform(0, 2 * math.pi)
        crank_pin, pivot = a * np.array([math.cos(phi), math.sin(phi)]), np.array([d, 0.0])
        r = math.dist(crank_pin, pivot)
        if not abs(b - c) < r < b + c:
            continue
        along = (b * b - c * c + r * r) / (2 * r)
        u = (pivot - crank_pin) / r
        rocker_pin = crank_pin + along * u + math.sqrt(b * b - along * along) * np.array([-u[1], u[0]])
        side = rocker_pin - crank_pin
        coupler = crank_pin + rng.uniform(-0.5, 1.5) * side + rng.uniform(0.3, 1.0) * np.array([-side[1], side[0]])
        linkage = Linkage(FOUR_BAR, (0,), [[0, 0], pivot, crank_pin, rocker_pin], tracers={"P": (2, tuple(coupler))})
        if motion_range(linkage).full_rotation:
            return linkage


def traced_again(result) -> np.ndarray:
    """The tracer's points at the result's inputs, by the motion layer's own assembly."""
    return np.array([assemble(result.linkage, float(v)).tracers["P"][1] for v in result.inputs])


def test_a_four_bars_coupler_points_with_timing_are_found_exactly():
    original = random_crank_rocker(7)
    motion = sweep(original, steps=7, stop=float(original.pose_inputs[0]) + math.radians(240))
    target = PathTarget(motion.tracers["P"], motion.inputs[:, 0])
    result = synthesize(FOUR_BAR, target, budget=60, seed=1)
    assert result.relative_max < 1e-6
    assert result.met
    # the answer re-checked: the linkage, moved by the motion layer, passes the reported points; and so it does
    # moved by the independent reference solver (tests/oracles/motion.py)
    assert np.abs(traced_again(result) - result.traced).max() < 1e-9
    assert np.abs(traced_by_the_oracle(result.linkage, result.inputs) - result.traced).max() < 1e-9
    assert np.abs(result.traced - target.points).max() <= result.error_max + 1e-12
    # the timing is kept: the inputs step as the target's
    assert np.allclose(np.diff(result.inputs), np.diff(target.inputs), atol=1e-12)


@pytest.mark.slow  # up to 30–60 CPU seconds
def test_a_four_bars_coupler_points_without_timing_are_found_exactly_from_a_near_guess():
    """Without timing the inputs are unknowns; from a guess 2 % off the search returns to the curve."""
    original = random_crank_rocker(3)
    motion = sweep(original, steps=11)
    target = PathTarget(motion.tracers["P"][:10])
    rng = np.random.default_rng(0)
    guess = Linkage(FOUR_BAR, (0,), original.points * (1 + 0.02 * rng.standard_normal((4, 2))),
                    tracers=original.tracers)
    result = synthesize(guess, target, budget=30, seed=2)
    assert result.relative_max < 1e-6
    assert np.abs(traced_again(result) - result.traced).max() < 1e-9
    order = np.diff(result.inputs)
    assert (order > 0).all() or (order < 0).all()  # the points passed in their order
    assert result.constraints["order"]["met"] and result.constraints["branch"]["met"]


def freudenstein(phi, psi):
    """K1, K2, K3 of Freudenstein's equation K1 cos ψ − K2 cos φ + K3 = cos(φ − ψ) (K1 = d/a,
    K2 = d/c, K3 = (a² − b² + c² + d²)/(2ac); a the input crank, b the coupler, c the output
    rocker, d the frame), solved for three precision points."""
    rows = np.column_stack((np.cos(psi), -np.cos(phi), np.ones(3)))
    return np.linalg.solve(rows, np.cos(phi - psi))


def test_function_generation_matches_freudensteins_closed_form():
    phi, psi = np.radians([35.0, 55.0, 80.0]), np.radians([60.0, 72.0, 95.0])
    result = synthesize(FOUR_BAR, FunctionTarget(phi, psi), budget=30, seed=0)
    assert result.error_max < 1e-9
    lk = result.linkage
    d = math.dist(lk.points[0], lk.points[1])
    a = math.dist(lk.points[0], lk.points[2])
    b = math.dist(lk.points[2], lk.points[3])
    c = math.dist(lk.points[1], lk.points[3])
    found = np.array([d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)])
    assert np.allclose(found, freudenstein(phi, psi), rtol=1e-8, atol=1e-10)
    # the output angles, measured by the motion layer from the frame line, are the target's
    for value, want in zip(result.inputs, psi):
        posed = assemble(lk, float(value))
        rocker = posed.points[3] - posed.points[1]
        assert abs(math.remainder(math.atan2(rocker[1], rocker[0]) - want, math.tau)) < 1e-9
    assert abs(float(lk.pose_inputs[0]) - phi[0]) < 1e-9  # posed at the first input
    # and by the independent reference solver (tests/oracles/motion.py), moved input after input from the pose
    moved = follow(oracle_of(lk), np.asarray(result.inputs) - float(lk.pose_inputs[0]), math.radians(1))
    rocker = moved[:, 3] - moved[:, 1]
    assert np.abs(np.remainder(np.arctan2(rocker[:, 1], rocker[:, 0]) - psi + math.pi, math.tau) - math.pi).max() < 1e-9


@pytest.mark.slow  # up to 30–60 CPU seconds
def test_a_slider_cranks_coupler_points_are_found_exactly_from_a_near_guess():
    """A slide's line is two unknowns (a point and a direction): from a guess 2 % off (its slide
    turned by 0.02 rad) the search returns to the timed points."""
    # joints 0-1, 0=3, 1-2, 2-3: an offset slider-crank with a point on its rod
    original = Linkage(SLIDER_CRANK, (0,), [[0, 0], [3.0, 0.4], [0.6, 0.8], [3.0, 0.4]], {1: (1.0, 0.0)},
                       tracers={"P": (2, (1.5, 1.6))})
    motion = sweep(original, steps=8, stop=float(original.pose_inputs[0]) + math.radians(300))
    target = PathTarget(motion.tracers["P"], motion.inputs[:, 0])
    rng = np.random.default_rng(4)
    guess = Linkage(SLIDER_CRANK, (0,), original.points * (1 + 0.02 * rng.standard_normal((4, 2))),
                    {1: (math.cos(0.02), math.sin(0.02))}, tracers={"P": (2, (1.53, 1.58))})
    result = synthesize(guess, target, budget=30, seed=0)
    assert result.relative_max < 1e-6
    assert np.abs(traced_again(result) - result.traced).max() < 1e-9


def circumcentre(p):
    (ax, ay), (bx, by), (cx, cy) = p
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / d
    uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / d
    return np.array([ux, uy])


@pytest.mark.slow  # up to 30–60 CPU seconds
def test_three_poses_of_a_body_are_met_as_burmester_constructs_them():
    """Three poses: each fixed pivot is the centre of the circle through its moving pivot's three
    positions (the body's points carried by each pose) — Burmester's construction."""
    poses = np.array([[0.0, 0.0, 0.0], [1.0, 0.3, math.radians(20)], [1.8, 1.0, math.radians(45)]])
    with pytest.raises(BadTarget, match="at least 5 points"):
        synthesize(FOUR_BAR, MotionTarget(poses), budget=5)
    result = synthesize(FOUR_BAR, MotionTarget(poses), budget=60, seed=0, underdetermined=True)
    assert result.error_max < 1e-9 and result.angle_errors.max() < 1e-9
    lk = result.linkage
    p0 = np.array(lk.tracers["P"][1])
    for moving, fixed in ((2, 0), (3, 1)):  # crank pin about 0-1, rocker pin about 0-3
        local = lk.points[moving] - p0
        places = []
        for x, y, angle in poses:
            turn = angle - poses[0, 2]
            c, s = math.cos(turn), math.sin(turn)
            places.append([x + c * local[0] - s * local[1], y + s * local[0] + c * local[1]])
        assert np.allclose(circumcentre(np.array(places)), lk.points[fixed], atol=1e-7)


@pytest.mark.slow  # up to 30–60 CPU seconds
def test_the_designers_constraints_are_met_and_reported():
    original = random_crank_rocker(5)
    motion = sweep(original, steps=7, stop=float(original.pose_inputs[0]) + math.radians(200))
    target = PathTarget(motion.tracers["P"], motion.inputs[:, 0])
    c = target.points.mean(axis=0)
    box = (c[0] - 6, c[0] + 6, c[1] - 6, c[1] + 6)
    constraints = Constraints(crank=True, min_transmission=math.radians(20), max_ratio=8.0, pivots=box)
    result = synthesize(FOUR_BAR, target, constraints=constraints, budget=30, seed=0)
    assert result.met, result.failed()
    assert set(result.constraints) == {"branch", "crank", "transmission", "ratio", "pivots"}
    assert motion_range(result.linkage).full_rotation
    assert link_ratio(result.linkage) <= 8.0 * (1 + 1e-9)
    assert result.constraints["transmission"]["value"] >= 20 - 1e-6


def test_a_constraint_no_candidate_meets_is_reported_as_failed():
    """A crank whose transmission angle stays within 89° … 91° over its whole turn: no four-bar has one."""
    target = PathTarget([[0, 0], [1, 0], [2, 0.1], [3, 0.5], [4, 1.5]], np.radians([0, 20, 40, 60, 80]))
    impossible = Constraints(crank=True, min_transmission=math.radians(89))
    result = synthesize(FOUR_BAR, target, constraints=impossible, budget=3, seed=0)
    assert not result.met
    assert any(f.startswith("transmission") or f.startswith("crank") for f in result.failed())


def test_refusals():
    target = PathTarget([[0, 0], [1, 0], [1, 1]], [0.0, 0.1, 0.2])
    with pytest.raises(BadTarget, match="equations for the 10 unknowns"):
        synthesize(FOUR_BAR, target, budget=1)
    with pytest.raises(BadTarget, match="full turn"):
        synthesize(FOUR_BAR, PathTarget(np.random.default_rng(1).random((10, 2)), np.linspace(0, 7, 10)), budget=1)
    with pytest.raises(DimensionError, match="crank .* and a rocker"):
        Constraints(crank=True, rocker=(0, 1))
    with pytest.raises(DimensionError, match="gear meshes"):
        synthesize(Mechanism(Chain.parse("0-1 1~2 2-0"), 0), target, budget=1)
    with pytest.raises(DimensionError, match="budget"):
        synthesize(FOUR_BAR, PathTarget(np.random.default_rng(0).random((6, 2)), np.arange(6.0) / 10), budget=0)
