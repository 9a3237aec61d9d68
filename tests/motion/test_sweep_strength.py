"""A sweep's sentences and rows to the letter: the limits it names worked out from the dimensions
(a rocker's crank stops where coupler and rocker are in line, a piston where crank and rod are),
each refusal, every column of a row and the extent of a traced curve."""

import math

import numpy as np
import pytest

from synth.errors import BadSweep, CannotAssemble, WrongInputs
from synth.motion import Linkage, Motion, assemble, refine_extreme, sweep, sweep_grid
from synth.structure.chain import Chain, Mechanism

from .helpers import four_bar, slider_crank
from tests.refusals import refused

#: crank a = 2.5, coupler b = 3.2, rocker c = 3, frame d = 4: the crank stops where b and c are in line,
#: |A − O4| = b + c, at cos φ = (a² + d² − (b + c)²) / 2ad
ROCKER_LIMIT = math.acos((2.5 ** 2 + 4 ** 2 - 6.2 ** 2) / (2 * 2.5 * 4))
DYAD = "the RRR dyad of links 2, 3 is aligned (a dead position)"


def said(value: float) -> str:
    return f"{value:.9f} rad ({math.degrees(value):.6f}°)"


def test_the_sweeps_arguments_are_refused_in_one_sentence_each():
    lk = four_bar(1, 3.5, 3, 4)
    assert refused(BadSweep, sweep, lk, steps="9") == "steps must be a whole number of steps, not '9'"
    assert refused(BadSweep, sweep, lk, steps=False) == "steps must be a whole number of steps, not False"
    assert refused(BadSweep, sweep, lk, steps=1) == \
        "steps must be 2 … 10,000,000 (a sweep's steps, start and stop included), not 1"
    assert refused(BadSweep, sweep, lk, steps=10_000_001) == \
        "steps must be 2 … 10,000,000 (a sweep's steps, start and stop included), not 10000001"
    assert sweep(lk, steps=np.int64(2)).steps == 2
    assert refused(BadSweep, sweep, lk, start="x") == "start must be a number, not 'x'"
    assert refused(BadSweep, sweep, lk, stop=None, start=[1]) == "start must be a number, not [1]"
    assert refused(BadSweep, sweep, lk, start=True) == "start must be a finite number, not True"
    assert refused(BadSweep, sweep, lk, stop=-math.inf) == "stop must be a finite number, not -inf"
    assert refused(BadSweep, sweep, lk, start=0.5, stop=0.5) == "start and stop are the same input: a sweep needs a range"
    # a start too far from zero for its float to hold an angle (1e308°: start + one turn is start; no stop was given)
    assert refused(BadSweep, sweep, lk, start=math.radians(1e308)) == (
        "start 1e+308° (1.74533e+306 rad) is too far from zero: a float that large is known only to "
        "3.12e+290 rad; give an input within a few turns (or sizes) of the pose")
    assert refused(BadSweep, sweep, lk, start=1.0, stop=1e300).startswith("stop 5.72958e+301° (1e+300 rad) is too far")
    assert refused(BadSweep, sweep, lk, start=2e7).endswith("known only to 3.73e-09 rad; give an input within a few "
                                                              "turns (or sizes) of the pose")  # (ulp 2⁻²⁸ > 1e-9)
    assert sweep(lk, start=1e6, steps=3).steps == 3  # (ulp 1.2e-10: held)
    crank = slider_crank(1.0, 3.0, 0.5)
    piston = Linkage(crank.mechanism, (1,), crank.points, crank.slides)  # (its size some 4: 1e-9 of it is 4e-9)
    assert refused(BadSweep, sweep, piston, start=1e8, stop=1e8 + 1).startswith("start 1e+08 is too far from zero")
    # a grid's input too (a five-bar's crank 0-1 from 1e17°: rows of no meaning), the other input's range as it was
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    assert refused(BadSweep, sweep_grid, five_bar, [(1e15, 2e15), (0, 1)], steps=[3, 3]).startswith(
        "input 0-1's start 5.72958e+16° (1e+15 rad) is too far from zero: a float that large is known only to 0.125 rad")
    assert sweep_grid(five_bar, [(0.5, 0.5), (0, 1)], steps=[2, 2]).steps == 4  # (one value of an input: no step)
    # a pose at such an input too ('draw FILE --at 1e12' drew a garbage pose, then named a "start")
    assert refused(BadSweep, assemble, lk, 1e10).startswith("the input 5.72958e+11° (1e+10 rad) is too far from zero")
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    assert refused(WrongInputs, sweep, five_bar) == "this linkage has 2 inputs: sweep a grid of them with sweep_grid"


def test_a_rocker_cannot_start_beyond_its_limit_and_stops_at_it():
    lk = four_bar(2.5, 3.2, 3.0, 4.0, phi=0.5)
    assert refused(CannotAssemble, sweep, lk, start=3.0, stop=3.1) == (
        f"the linkage cannot be assembled at input {said(3.0)} on the branch of its pose, which moves between "
        f"{said(-ROCKER_LIMIT)} and {said(ROCKER_LIMIT)} ({DYAD} at that end)")
    # the same angle a turn back is inside: 3 − 2π = −3.28 is not, −2.5 + 2π is
    assert sweep(lk, start=-2.5 + 2 * math.pi, stop=2.5, steps=3).inputs[0, 0] == pytest.approx(-2.5 + 2 * math.pi)
    m = sweep(lk, start=0.0, stop=3.0, steps=5)
    assert m.inputs[:, 0].tolist() == pytest.approx([0, 0.75, 1.5, 2.25, ROCKER_LIMIT], abs=1e-9)
    assert m.stopped == f"the sweep stops at input {said(ROCKER_LIMIT)}: {DYAD}; the input cannot go further"
    back = sweep(lk, start=0.0, stop=-3.0, steps=5)
    assert back.inputs[-1, 0] == pytest.approx(-ROCKER_LIMIT, abs=1e-9) and back.stopped.startswith(
        f"the sweep stops at input {said(-ROCKER_LIMIT)}")
    # by default a rocker goes from its lower to its upper limit
    whole = sweep(lk, steps=3)
    assert whole.inputs[:, 0].tolist() == pytest.approx([-ROCKER_LIMIT, 0, ROCKER_LIMIT], abs=1e-9) and whole.stopped is None


def test_a_piston_names_its_stroke_in_lengths():
    # the slider's x in the pose: A_x + √(l² − (e − A_y)²); its ends at √((l ± r)² − e²)
    r, l, e = 1.0, 3.0, 0.5
    lk = slider_crank(r, l, e)
    piston = Linkage(lk.mechanism, (1,), lk.points, lk.slides)
    x0 = math.cos(1.0) + math.sqrt(l * l - (e - math.sin(1.0)) ** 2)
    lo, hi = math.sqrt((l - r) ** 2 - e * e) - x0, math.sqrt((l + r) ** 2 - e * e) - x0
    assert refused(CannotAssemble, sweep, piston, start=5.0, stop=6.0) == (
        f"the linkage cannot be assembled at input 5 on the branch of its pose, which moves between {lo:.9g} and "
        f"{hi:.9g} (the RRR dyad of links 1, 2 is aligned (a dead position) at that end)")
    m = sweep(piston, steps=4)
    assert m.inputs[:, 0].tolist() == pytest.approx([lo, lo + (hi - lo) / 3, lo + 2 * (hi - lo) / 3, hi], abs=1e-9)


def test_every_column_of_a_row():
    lk = four_bar(1, 3.5, 3, 4, tracer=(2, 3))
    m = sweep(lk, steps=3, velocities=True, accelerations=True)
    rows = list(m.rows())
    names = ["0-1", "0-3", "1-2", "2-3"]
    assert list(rows[0]) == (["step", "input"] + [f"{n}.{c}" for n in names + ["P"] for c in "xy"]
                             + [f"{n}.v{c}" for n in names + ["P"] for c in "xy"]
                             + [f"{n}.a{c}" for n in names + ["P"] for c in "xy"])
    for s, row in enumerate(rows):
        assert row["step"] == s and row["input"] == m.inputs[s, 0]
        assert row["1-2.x"] == m.joints[s, 2, 0] and row["2-3.y"] == m.joints[s, 3, 1]
        assert row["P.x"] == m.tracers["P"][s, 0] and row["P.y"] == m.tracers["P"][s, 1]
        assert row["1-2.vx"] == m.velocities[s, 2, 0] and row["2-3.ay"] == m.accelerations[s, 3, 1]
    # the crank pin turns on a unit circle: velocity (−sin φ, cos φ), acceleration −(cos φ, sin φ)
    phi = m.inputs[1, 0]
    assert (rows[1]["1-2.vx"], rows[1]["1-2.vy"]) == pytest.approx((-math.sin(phi), math.cos(phi)), abs=1e-12)
    assert (rows[1]["1-2.ax"], rows[1]["1-2.ay"]) == pytest.approx((-math.cos(phi), -math.sin(phi)), abs=1e-12)
    # a value that is not finite is written as None
    nan = Motion(lk, np.array([[0.0], [math.nan]]), np.full((2, 4, 2), math.nan), {"P": np.array([[1, 2], [math.inf, 0]])})
    row = list(nan.rows())[1]
    assert row["input"] is None and row["0-1.x"] is None and row["P.x"] is None and row["P.y"] == 0.0
    assert "0-1.vx" not in row


def test_rows_of_two_inputs_name_each_inputs_column():
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    m = Motion(five_bar, np.array([[0.1, 0.2]]), np.zeros((1, 5, 2)), {}, np.ones((1, 2, 5, 2)), None)
    row = next(m.rows())
    assert row["input.0-1"] == 0.1 and row["input.0-4"] == 0.2 and "input" not in row
    assert row["1-2.vx.0-1"] == 1.0 and row["3-4.vy.0-4"] == 1.0


def test_the_extent_of_a_curve_leaves_out_what_is_not_finite():
    lk = four_bar(1, 3.5, 3, 4, tracer=(2, 3))
    m = Motion(lk, np.zeros((3, 1)), np.zeros((3, 4, 2)),
               {"P": np.array([[1.0, 5.0], [math.nan, 9.0], [-2.0, 3.0]]), "Q": np.full((2, 2), math.nan)})
    assert m.extent()["P"] == (-2.0, 3.0, 1.0, 5.0)
    assert all(math.isnan(v) for v in m.extent()["Q"]) and len(m.extent()["Q"]) == 4
    # a crank pin's circle of radius 1 about the origin
    turned = sweep(Linkage(lk.mechanism, (0,), lk.points, tracers={"A": (1, (1.0, 0.0))}), steps=361)
    assert turned.extent()["A"] == pytest.approx((-1, -1, 1, 1), abs=1e-12)


def _coupler_points(a, b, c, d, phi, tracer, angles):
    """The four-bar's coupler point P at crank angles, worked out apart from the motion layer: the
    coupler pin B where the circles about A (radius b) and O4 (radius c) meet on the pose's side, P
    fixed in the frame of A → B as in the pose."""
    def pins(t):
        A = np.stack((a * np.cos(t), a * np.sin(t)), axis=-1)
        v = np.array([d, 0.0]) - A
        e = np.hypot(v[..., 0], v[..., 1])[..., None]
        along = (b * b - c * c + e * e) / (2 * e)
        B = A + along * v / e + np.sqrt(b * b - along * along) * np.stack((-v[..., 1], v[..., 0]), axis=-1) / e
        return A, B
    A0, B0 = pins(np.array(phi))
    u0 = (B0 - A0) / b
    rel = np.array(tracer) - A0
    local = (rel @ u0, rel[0] * -u0[1] + rel[1] * u0[0])
    A, B = pins(angles)
    u = (B - A) / b
    return A + local[0] * u + local[1] * np.stack((-u[:, 1], u[:, 0]), axis=-1)


def test_the_extent_of_a_curve_is_the_curves_not_the_samples():
    # the scene's crank-rocker (models/motion_four_bar.toml): 'move --range' printed x max 2.71272 from its
    # 360 samples where the curve reaches 2.712734 (1.4e-5 short, wrong in the sixth digit it prints)
    lk = four_bar(1, 3.5, 3, 4, phi=math.pi / 2, tracer=(2.5, 4.5))
    dense = _coupler_points(1, 3.5, 3, 4, math.pi / 2, (2.5, 4.5), np.linspace(0, 2 * math.pi, 400_001))
    truth = (*dense.min(axis=0), *dense.max(axis=0))  # samples 1.6e-5 rad apart: within 1e-9 of the curve's own
    m = sweep(lk)
    sampled = (*m.tracers["P"].min(axis=0), *m.tracers["P"].max(axis=0))
    assert max(abs(s - t) for s, t in zip(sampled, truth)) > 1e-6
    assert m.extent()["P"] == pytest.approx(truth, abs=1e-9)
    # a rocker's sweep: the extremes inside its range refined too, those at its dead positions kept
    rocker = four_bar(2.5, 3.2, 3, 4, phi=1.0, tracer=(1.0, 3.0))
    r = sweep(rocker, steps=37)
    fine = sweep(rocker, steps=200_001).tracers["P"]
    assert r.extent()["P"] == pytest.approx((*fine.min(axis=0), *fine.max(axis=0)), abs=1e-9)


def test_an_extreme_is_refined_between_samples_by_one_public_search():
    """refine_extreme, the motion layer's one way of refining a sampled extreme (the curve's extent, the
    transmission angle and the application's dead centres all use it): the least or greatest to 1e-10 of the
    input, the sample kept where the search finds none better or has no room."""
    x, v = refine_extreme(lambda t: (t - 1.3) ** 2, 1.0, 2.0, (1.0, 0.09))
    assert x == pytest.approx(1.3, abs=1e-8) and v == pytest.approx(0.0, abs=1e-15)
    x, v = refine_extreme(math.sin, 1.0, 2.0, (2.0, math.sin(2.0)), largest=True)
    assert x == pytest.approx(math.pi / 2, abs=1e-7) and v == 1.0
    assert refine_extreme(lambda t: t, 1.0, 2.0, (1.0, 1.0)) == (1.0, 1.0)  # least at the sample itself
    assert refine_extreme(lambda t: math.nan, 1.0, 2.0, (1.5, 7.0), largest=True) == (1.5, 7.0)  # nowhere finite
    assert refine_extreme(math.sin, 2.0, 2.0, (2.0, 0.5)) == (2.0, 0.5)  # no bracket


def test_a_tracers_velocity_and_acceleration_are_in_the_rows():
    # 'move --velocities --accelerations' gave every joint's rates but none of the coupler point's (P.x, P.y only):
    # checked against central differences of the coupler point worked out apart from the motion layer
    lk = four_bar(1, 3.5, 3, 4, phi=math.pi / 2, tracer=(2.5, 4.5))
    m = sweep(lk, steps=13, velocities=True, accelerations=True)
    angles = m.inputs[:, 0]
    h, g = 1e-6, 1e-4
    at = lambda shift: _coupler_points(1, 3.5, 3, 4, math.pi / 2, (2.5, 4.5), angles + shift)
    velocity = (at(h) - at(-h)) / (2 * h)
    acceleration = (at(g) - 2 * at(0.0) + at(-g)) / g ** 2
    assert m.tracer_velocities["P"] == pytest.approx(velocity, abs=1e-8)
    assert m.tracer_accelerations["P"] == pytest.approx(acceleration, abs=1e-6)
    rows = list(m.rows())
    assert [(r["P.vx"], r["P.vy"], r["P.ax"], r["P.ay"]) for r in rows] == [
        (*v, *a) for v, a in zip(m.tracer_velocities["P"].tolist(), m.tracer_accelerations["P"].tolist())]
    assert list(rows[0])[-4:] == ["2-3.ax", "2-3.ay", "P.ax", "P.ay"]  # after the joints', as the positions are
    # W = 2: a five-bar's tracer per unit rate of each input, against differences of the grid's own points
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
                       [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]], tracers={"T": (2, (1.0, 2.5))})
    grid = sweep_grid(five_bar, [(1.5, 1.6), (1.5, 1.6)], steps=2, velocities=True)
    row = next(grid.rows())
    shifted = sweep_grid(five_bar, [(1.5 + h, 1.6), (1.5, 1.6)], steps=2).tracers["T"][0]
    assert (row["T.vx.0-1"], row["T.vy.0-1"]) == pytest.approx(tuple((shifted - grid.tracers["T"][0]) / h), abs=1e-5)
    assert "T.vx.0-4" in row and list(row).index("T.vy.0-1") < list(row).index("0-1.vx.0-4")


def test_a_transmission_angle_at_a_dead_position_is_exactly_0_or_180_degrees():
    # a double-rocker input stops where coupler and rocker fold (|b − c|: μ = 0) and stretch (b + c: μ = π);
    # 'move --range' said "min 0.0001439°" there and the scene "worst transmission 4.572e-05°" (the end found to
    # 1e-11 of the input, where μ is still about its square root)
    a, b, c, d = 1.2, 0.7, 1.15, 1.0
    folded = math.acos((a * a + d * d - (b - c) ** 2) / (2 * a * d))
    stretched = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    t = sweep(four_bar(a, b, c, d, phi=1.0)).transmission["links 2, 3"]
    assert (t["min"], t["max"]) == (0.0, math.pi)
    assert (t["at_min"], t["at_max"]) == pytest.approx((folded, stretched), abs=1e-9)
    # a sweep that stops short of the dead positions keeps the refined values
    inside = sweep(four_bar(a, b, c, d, phi=1.0), start=folded + 0.1, stop=stretched - 0.1).transmission["links 2, 3"]
    assert 0 < inside["min"] < inside["max"] < math.pi


def test_grashofs_classes_by_the_shortest_links_place():
    from synth.motion import motion_range
    from synth.motion._sweep import _grashof

    # s + l < p + q with the shortest link the output (rocker 3): a rocker-crank
    assert _grashof(four_bar(3, 3.5, 1, 4, phi=1.2)) == "rocker-crank (Grashof)"
    # s + l = p + q: a change point (a parallelogram)
    assert _grashof(four_bar(1.0, 2.0, 1.0, 2.0)) == "change-point (s + l = p + q)"
    # s + l > p + q: 1 + 4.4 against 3.5 + 1.8
    assert _grashof(four_bar(1.8, 3.5, 1.0, 4.4, phi=1.2)) == "triple-rocker (non-Grashof)"
    # only four-bars of revolute joints have a class
    assert _grashof(slider_crank(1, 3, 0.5)) is None and motion_range(slider_crank(1, 3, 0.5)).grashof is None


def test_a_linkage_assembled_at_another_input_carries_its_slides_and_tracers():
    from synth.motion import assemble

    from .helpers import inverted_slider_crank

    lk = inverted_slider_crank(1.0, 2.0)  # the guide 3 about (2, 0) points at the crank pin
    posed = assemble(lk, 2.5)
    pin = np.array([math.cos(2.5), math.sin(2.5)])
    u = (pin - [2, 0]) / np.hypot(*(pin - [2, 0]))
    assert posed.pose_inputs[0] == pytest.approx(2.5, abs=1e-12)
    assert np.abs(posed.points[2] - pin).max() < 1e-12 and np.abs(np.array(posed.slides[3]) - u).max() < 1e-12
    traced = assemble(four_bar(1, 3.5, 3, 4, tracer=(2, 3)), 1.0)
    assert traced.tracers == {"P": (2, pytest.approx((2.0, 3.0), abs=1e-12))}  # helpers pose it at φ = 1
    assert refused(BadSweep, assemble, lk, math.nan) == "the input must be a finite number, not nan"


def test_a_grid_by_continuation_steps_a_whole_radian_at_a_time():
    from synth.motion import sweep_grid
    from synth.motion._sweep import _solver

    # the crank-rocker posed at φ = 0 (its crank pin at (1, 0)): the grid's inputs 0, 1, 2 rad are its offsets,
    # one whole radian apart; continuation (its dyad ignored) must reach each as the closed form does
    closed = sweep_grid(four_bar(1, 3.5, 3, 4, phi=0.0), [(0.0, 2.0)], steps=3)
    lk = four_bar(1, 3.5, 3, 4, phi=0.0)
    _solver(lk).plan = None
    newton = sweep_grid(lk, [(0.0, 2.0)], steps=3)
    assert closed.inputs[:, 0].tolist() == [0.0, 1.0, 2.0] and lk.pose_inputs[0] == 0.0
    assert np.abs(newton.joints - closed.joints).max() < 1e-10
    assert np.abs(newton.joints[1, 2] - [math.cos(1.0), math.sin(1.0)]).max() < 1e-12


def test_a_grid_keeps_the_region_of_its_pose():
    from synth.motion import sweep_grid

    # a five-bar whose cranks (1 each, pivots 3 apart) reach each other's coupler links (1.2 each) only
    # pointing towards each other: crank 2 near ±π, which the grid (−π … π) splits in two regions; the
    # pose (0.3, 2.8) is in the upper one, and the grid keeps that one alone
    a, b = np.array([math.cos(0.3), math.sin(0.3)]), np.array([3 + math.cos(2.8), math.sin(2.8)])
    middle, d = (a + b) / 2, b - a
    pin = middle + math.sqrt(1.2 ** 2 - (np.hypot(*d) / 2) ** 2) * np.array([-d[1], d[0]]) / np.hypot(*d)
    lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], a, pin, b])
    m = sweep_grid(lk, [(-math.pi, math.pi), (-math.pi, math.pi)], steps=41)
    reached = np.isfinite(m.joints).all(axis=(1, 2))
    assert reached.sum() > 100 and (m.inputs[reached, 1] > 0).all()
    pose_cell = np.argmin(np.abs(m.inputs - [0.3, 2.8]).max(axis=1))
    assert reached[pose_cell]
    # every reached cell keeps the coupler links' lengths
    c = m.joints[reached]
    assert np.abs(np.hypot(*(c[:, 3] - c[:, 2]).T) - 1.2).max() < 1e-12
    assert np.abs(np.hypot(*(c[:, 3] - c[:, 4]).T) - 1.2).max() < 1e-12


def test_a_grids_refusals():
    from synth.motion import sweep_grid

    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1), [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    assert refused(BadSweep, sweep_grid, five_bar, [(0, 1), (0, 1)], steps=[3, 1]) == \
        "each input's steps must be 2 … 10,000,000 (a sweep's steps, start and stop included), not 1"
    assert refused(BadSweep, sweep_grid, five_bar, [(0, 1)], steps=3) == \
        "this linkage has 2 inputs: give 2 ranges and step counts, not 1 and 2"
    assert refused(BadSweep, sweep_grid, four_bar(1, 3.5, 3, 4), [(0, 1), (0, 1)]) == \
        "this linkage has 1 input: give 1 range and step counts, not 2 and 1"
    assert refused(BadSweep, sweep_grid, five_bar, [(0, math.nan), (0, 1)]) == "a range's stop must be a finite number, not nan"
    assert refused(BadSweep, sweep_grid, five_bar, [1, 2]) == \
        "ranges must be one (start, stop) pair per input, steps one count per input"
    assert refused(BadSweep, sweep_grid, five_bar, [(0, 1), (0, 1)], steps=10_000) == \
        "the grid has 100,000,000 steps; at most 10,000,000"
    # cranks pointing away from each other (pins 5 apart) cannot be joined by couplers of 2.12
    assert refused(CannotAssemble, sweep_grid, five_bar, [(3.0, 3.2), (-0.1, 0.1)], steps=3) == (
        "the linkage cannot be assembled at the grid's input nearest to its pose on the branch of its pose: "
        f"widen the ranges to include the pose's inputs {math.pi / 2:.6g}, {math.pi / 2:.6g}")


def test_a_grids_velocities_of_a_slider_are_a_sweeps():
    from synth.motion import sweep_grid

    lk = slider_crank(1.0, 3.0, 0.5)  # the slider's equations read the links' translations
    grid = sweep_grid(lk, [(0.5, 1.5)], steps=3, velocities=True)
    swept = sweep(lk, start=0.5, stop=1.5, steps=3, velocities=True)
    assert np.abs(grid.velocities[:, 0] - swept.velocities).max() < 1e-12
    # the crank pin: unit speed square to the crank
    phi = grid.inputs[:, 0]
    assert np.abs(grid.velocities[:, 0, 2] - np.c_[-np.sin(phi), np.cos(phi)]).max() < 1e-12


def test_a_rockers_dead_positions_are_its_limits_named():
    from synth.motion import motion_range

    r = motion_range(four_bar(2.5, 3.2, 3.0, 4.0, phi=0.5))
    assert not r.full_rotation and r.limits == pytest.approx((-ROCKER_LIMIT, ROCKER_LIMIT), abs=1e-9)
    assert [why for _, why in r.dead_positions] == [DYAD, DYAD]
    assert [x for x, _ in r.dead_positions] == pytest.approx([-ROCKER_LIMIT, ROCKER_LIMIT], abs=1e-9)
    assert motion_range(four_bar(1, 3.5, 3, 4)).dead_positions == ()
