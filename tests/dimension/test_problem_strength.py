"""One topology against one target, part by part against values worked out by hand: the designer's
constraints and their refusals, the unknowns (their layout, box and count), a linkage built from them
and read back, the residuals of each kind of target, the samples where the dyads must close and
each violation's size."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import Constraints, FunctionTarget, MotionTarget, PathTarget, link_ratio
from synth.dimension._problem import MARGIN, SPAN_STEP, TURN_SAMPLES, Problem, point_carried, input_joint_of
from synth.errors import BadTarget, DimensionError
from synth.motion import Linkage
from synth.structure.chain import Chain, Mechanism
from tests.refusals import refused

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1 0-3 1-2 2-3
SLIDER_CRANK = Mechanism(Chain.parse("0-1 1-2 2-3 0=3"), 0)  # joints 0-1 0=3 1-2 2-3
PATH = PathTarget([[1, 1], [4, 1], [4, 5]])  # centre (2.5, 3), size 5


def close(got, want, tol=1e-12) -> bool:
    return np.shape(got) == np.shape(want) and np.abs(np.asarray(got, dtype=float) - np.asarray(want, dtype=float)).max() <= tol


def test_the_constraints_are_refused_in_one_sentence_each():
    assert refused(DimensionError, Constraints, crank=True, rocker=(0, 1)) == \
        "the input cannot be both a crank (a full turn) and a rocker within limits"
    assert refused(DimensionError, Constraints, rocker=(1, 1)) == \
        "the rocker's limits must be two finite numbers, lower first, not (1, 1)"
    assert refused(DimensionError, Constraints, rocker=(0, math.inf)) == \
        "the rocker's limits must be two finite numbers, lower first, not (0, inf)"
    assert refused(DimensionError, Constraints, rocker=(math.nan, 1)).startswith("the rocker's limits must be")
    assert refused(DimensionError, Constraints, rocker=(0, "x")) == \
        "the rocker's limits must be two finite numbers, lower first, not (0, 'x')"
    assert refused(DimensionError, Constraints, rocker=1.5) == \
        "the rocker's limits must be two finite numbers, lower first, not 1.5"
    assert refused(DimensionError, Constraints, rocker="12") == \
        "the rocker's limits must be two finite numbers, lower first, not 12"
    assert Constraints(rocker=("0.5", 2)).rocker == (0.5, 2.0)
    assert refused(DimensionError, Constraints, pivot_at={"0-1": "12"}) == \
        "a fixed pivot is a point (x, y), not '12' (joint 0-1)"  # no point (1, 2)
    assert refused(DimensionError, Constraints, pivot_at={"0-1": (0, True)}) == \
        "a fixed pivot is a point (x, y), not (0, True) (joint 0-1)"
    assert refused(DimensionError, Constraints, pivot_at={"0-1": (0, math.nan)}) == \
        "the fixed pivot of joint 0-1 must be at finite coordinates, not (0, nan)"
    assert Constraints(pivot_at={"0-1": ("1", 2)}).pivot_at == (("0-1", (1.0, 2.0)),)
    assert refused(DimensionError, Constraints, min_transmission=-0.1) == \
        "the least transmission angle must be 0 … 90° (exclusive), not -5.72958°"
    assert refused(DimensionError, Constraints, min_transmission=math.pi / 2) == \
        "the least transmission angle must be 0 … 90° (exclusive), not 90°"
    Constraints(min_transmission=0.0)
    Constraints(min_transmission=1.5)
    assert refused(DimensionError, Constraints, max_ratio=1.0) == \
        "the link-length ratio bound must be a number above 1, not 1.0"
    assert refused(DimensionError, Constraints, max_ratio=math.inf) == \
        "the link-length ratio bound must be a number above 1, not inf"
    Constraints(max_ratio=1.01)
    for bad in (0.0, -1.0, math.inf, math.nan):
        assert refused(DimensionError, Constraints, max_length=bad) == \
            f"the link-length bound must be a positive length, not {bad}"
    Constraints(max_length=1e-3)
    assert refused(DimensionError, Constraints, max_length=80, pivot_at={"0-1": (0, 0), "0-3": (100, 0)}) == \
        "the fixed pivots of joints 0-1 and 0-3 lie 100 apart, beyond the link-length bound 80"
    Constraints(max_length=100, pivot_at={"0-1": (0, 0), "0-3": (100, 0)})
    assert refused(DimensionError, Constraints, pivots=(1, 1, 0, 1)) == \
        "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (1, 1, 0, 1)"
    assert refused(DimensionError, Constraints, pivots=(0, 1, 2, 1)) == \
        "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (0, 1, 2, 1)"
    assert refused(DimensionError, Constraints, pivots=(0, 1, 0, math.nan)).startswith("the pivots' region")
    assert Constraints(pivots=(0, "1", 0, 1)).pivots == (0.0, 1.0, 0.0, 1.0)
    assert refused(DimensionError, Constraints, reach=0) == \
        "the search reach must be a positive number of target sizes, not 0"
    assert refused(DimensionError, Constraints, reach=math.inf) == \
        "the search reach must be a positive number of target sizes, not inf"


@pytest.mark.parametrize("field, bad, sentence", [
    ("pivots", (0, 1, 0), "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (0, 1, 0)"),
    ("pivots", (0, 1, 0, 1, 2), "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (0, 1, 0, 1, 2)"),
    ("pivots", ("a", 1, 0, 1), "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not ('a', 1, 0, 1)"),
    ("pivots", (None, 1, 0, 1), "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (None, 1, 0, 1)"),
    ("pivots", (True, 2, 0, 1), "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (True, 2, 0, 1)"),
    ("pivots", "0..1,0..1", "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not 0..1,0..1"),
    ("pivots", 5, "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not 5"),
    ("pivots", (0, math.inf, 0, 1), "the pivots' region must be four finite numbers x0 < x1, y0 < y1, not (0, inf, 0, 1)"),
    ("pivot_at", 5, "the fixed pivots are a mapping joint -> (x, y), e.g. {'0-1': (0, 0)}, not 5"),
    ("pivot_at", "0-1", "the fixed pivots are a mapping joint -> (x, y), e.g. {'0-1': (0, 0)}, not '0-1'"),
    ("pivot_at", [("0-1",)], "the fixed pivots are a mapping joint -> (x, y), e.g. {'0-1': (0, 0)}, not [('0-1',)]"),
    ("min_transmission", None, "the least transmission angle must be a number (rad), not None"),
    ("min_transmission", "wide", "the least transmission angle must be a number (rad), not wide"),
    ("max_ratio", [2], "the link-length ratio bound must be a number above 1, not [2]"),
    ("max_length", "long", "the link-length bound must be a positive length, not long"),
    ("reach", True, "the search reach must be a positive number of target sizes, not True"),
    ("frame_angle", "east", "the frame's direction must be a finite angle, not east"),
    ("crank", "no", "crank is True or False, not 'no'"),
    ("order", 5, "the link-length orders are a text or a list of texts, e.g. ('r2 <= r3 <= r4 <= r1',), not 5"),
])
def test_a_field_of_the_wrong_kind_is_refused_in_one_sentence(field, bad, sentence):
    """A non-number, a truth value, a wrong count or a wrong container raised Python's own TypeError or
    ValueError (or, for a truth value in the pivots' box or crank='no', was taken) before."""
    assert refused(DimensionError, Constraints, **{field: bad}) == sentence


def test_numbers_of_any_kind_and_their_texts_are_taken_as_floats():
    c = Constraints(pivots=(np.int64(0), "1", np.float32(0.5), 2), reach="4", max_ratio=np.float64(3), frame_angle=0)
    assert (c.pivots, c.reach, c.max_ratio, c.frame_angle) == ((0.0, 1.0, 0.5, 2.0), 4.0, 3.0, 0.0)
    assert all(type(v) is float for v in (*c.pivots, c.reach, c.max_ratio, c.frame_angle))
    assert Constraints(crank=np.bool_(True)).crank


def test_the_problems_refusals():
    geared = Mechanism(Chain.parse("0-1 1-2 0~2"), 0)
    assert refused(DimensionError, Problem, geared, 0, PATH, None, Constraints()) == (
        "a mechanism with gear meshes is not dimensioned by this synthesis (links and revolute or prismatic pairs only)")
    five_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0)
    assert refused(DimensionError, Problem, five_bar, 0, PATH, None, Constraints()) == \
        "dimensional synthesis moves a planar mechanism of one input (W = 1), not W = 2"
    spatial = Mechanism(Chain(6, tuple((i, (i + 1) % 6) for i in range(6)), h=5), 0)
    assert refused(DimensionError, Problem, spatial, 0, PATH, None, Constraints()) == \
        "dimensional synthesis moves a planar mechanism of one input (W = 1), not W = 1 in motion space h = 5"
    f = FunctionTarget([0, 1], [0, 1])
    assert refused(DimensionError, Problem, SLIDER_CRANK, 0, f, None, Constraints()) == (
        "the target gives the output as angles, but the output joint 0=3 is prismatic (a slider): give its "
        "displacements (an output_displacement column)")
    for given, why in ((2, "is not pivoted on the frame (link 0)"), (9, "is not a link of the mechanism (links 0 … 3)"),
                       (0, "is the frame"), (1, "is the input link")):
        assert refused(DimensionError, Problem, FOUR_BAR, 0, FunctionTarget([0, 1], [0, 1], given), None,
                       Constraints()) == (f"the output link {given} {why}: it must be a link pivoted on the frame "
                                          "besides the input; links pivoted there: [3]")
    watt = Mechanism(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-2"), 0)
    assert refused(DimensionError, Problem, watt, 0, f, None, Constraints()) == \
        "name the output link: links [3, 4] are pivoted on the frame besides the input"
    assert refused(DimensionError, Problem, FOUR_BAR, 0, PATH, 0, Constraints()) == \
        "the tracer link 0 must be a moving link of the chain (links 1, 2, 3)"
    assert refused(DimensionError, Problem, FOUR_BAR, 0, PATH, 7, Constraints()) == \
        "the tracer link 7 must be a moving link of the chain (links 1, 2, 3)"
    turn = PathTarget([[0, 0], [1, 0], [1, 1]], [0, 3, 2 * math.pi])
    assert refused(BadTarget, Problem, FOUR_BAR, 0, turn, None, Constraints()) == \
        "the timing spans a full turn of the input or more: the points would repeat"
    Problem(FOUR_BAR, 0, PathTarget([[0, 0], [1, 0], [1, 1]], [0, 3, 6.28]), None, Constraints())
    # a slider's timing is a length: any span
    Problem(SLIDER_CRANK, 1, PathTarget([[0, 0], [1, 0], [1, 1]], [0, 3, 7]), None, Constraints())


def test_the_unknowns_their_box_and_their_count():
    p = Problem(FOUR_BAR, 0, PATH, None, Constraints(pivots=(0, 5, -2, 3)))
    assert p.tracer_link == 2  # the coupler: the moving link not on the frame with the most joints (2 vs 2: the first)
    assert p.centre.tolist() == [2.5, 3.0] and p.scale == 5.0 and p.reach == 4.0
    assert p.layout == [("joint", 0), ("joint", 1), ("joint", 2), ("joint", 3), ("tracer", None)]
    # the frame's joints 0-1 and 0-3 in the pivots' box, over the size from the centre; the others ±4
    box = [-0.5, 0.5, -1.0, 0.0]
    assert p.lower.tolist() == [box[0], box[2]] * 2 + [-4.0] * 6 and p.upper.tolist() == [box[1], box[3]] * 2 + [4.0] * 6
    assert (p.dims, p.searched, p.points, p.equations) == (10, 8, 3, 6)  # the tracer point is fitted, not searched
    assert p.unknowns == 8 + 2 + 2 and not p.timed and p.projected and p.input_span == 2 * math.pi
    timed = Problem(FOUR_BAR, 0, PathTarget(PATH.points, [0, 1, 2]), 3, Constraints(reach=2))
    assert timed.tracer_link == 3 and timed.reach == 2 and timed.lower.min() == -2
    assert (timed.dims, timed.searched, timed.unknowns, timed.equations) == (10, 8, 10, 6)
    slider = Problem(SLIDER_CRANK, 0, MotionTarget([[1, 1, 0], [4, 1, 1], [4, 5, 2]]), None, Constraints())
    assert slider.layout == [("joint", 0), ("joint", 1), ("slide", 1), ("joint", 2), ("joint", 3), ("tracer", None)]
    assert slider.lower[4] == 0 and slider.upper[4] == math.pi
    assert slider.tracer_link == 2  # the rod: 3 is on the frame's slide
    assert (slider.unknowns, slider.equations) == (2 + 2 + 2 + 2 + 2 + 2, 9)
    f = Problem(FOUR_BAR, 0, FunctionTarget([0.1, 0.2, 0.4], [1, 2, 3]), None, Constraints())
    assert f.output_link == 3 and f.output_joint == 1 and f.tracer_link is None and f.reach == 2.0
    assert f.layout == [("joint", 2), ("joint", 3)] and f.fixed[0].tolist() == [0, 0] and f.fixed[1].tolist() == [1, 0]
    assert (f.unknowns, f.equations, f.searched) == (3, 3, 4)
    piston = Problem(SLIDER_CRANK, 1, PATH, None, Constraints())
    assert piston.input_span == 2 * 4.0 * 5.0 and not piston.revolute_input and piston.input_link == 3


def test_a_linkage_is_built_from_the_unknowns_and_read_back():
    p = Problem(SLIDER_CRANK, 0, PATH, None, Constraints())
    x = np.array([0.1, -0.2, 0.5, 0.0, math.pi / 3, 0.3, 0.4, 0.5, 0.0, 0.2, 0.1])
    lk = p.linkage(x)
    # a position is the centre (2.5, 3) plus the size 5 times the unknown
    assert close(lk.points, [[3.0, 2.0], [5.0, 3.0], [4.0, 5.0], [5.0, 3.0]])
    assert lk.slides[1] == pytest.approx((0.5, math.sqrt(3) / 2)) and lk.inputs == (0,)
    assert lk.tracers == {"P": (2, pytest.approx((3.5, 3.5)))}
    assert p.unknowns_of(lk) == pytest.approx(x)
    # outside the box: clipped; a slide read modulo a half turn
    far = Linkage(lk.mechanism, (0,), lk.points + [[30, 0], [0, 0], [0, 0], [0, 0]], {1: (-0.5, -math.sqrt(3) / 2)},
                  tracers={"Q": (3, (0, 0))})
    back = p.unknowns_of(far)
    assert back[0] == 4.0 and back[4] == pytest.approx(math.pi / 3)
    assert back[-2:].tolist() == [0.0, 0.0]  # a tracer on another link: the target's centre
    # the tracer named P is read, whichever comes first
    two = Linkage(lk.mechanism, (0,), lk.points, lk.slides, tracers={"Q": (3, (0, 0)), "P": (2, (3.5, 3.5))})
    assert p.unknowns_of(two)[-2:].tolist() == pytest.approx([0.2, 0.1])
    f = Problem(FOUR_BAR, 0, FunctionTarget([0.1, 0.2], [1, 2]), None, Constraints())
    built = f.linkage(np.array([0.2, 0.3, 1.2, 0.9]))
    assert close(built.points, [[0, 0], [1, 0], [0.2, 0.3], [1.2, 0.9]]) and built.tracers == {}
    assert f.output_reference(built) == 3


def test_the_residuals_of_each_kind_of_target():
    p = Problem(FOUR_BAR, 0, PATH, None, Constraints())
    traced = PATH.points + [[0.5, 0], [0, 0], [0, -1]]
    assert close(p.residuals(traced), [[0.1, 0], [0, 0], [0, -0.2]])
    assert close(p.residuals(traced, PATH.points[::-1]), [[-0.5, -0.8], [0, 0], [0.6, 0.6]])
    m = Problem(FOUR_BAR, 0, MotionTarget([[1, 1, 0.5], [4, 1, 1], [4, 5, 3.5]]), None, Constraints())
    # the body's angle counts from the first pose: a turn of 0, 0.5, 3 wanted
    got = m.residuals(np.array([[1, 1, 0.0], [4, 2, 0.75], [4, 5, 3.0 - 2 * math.pi]]))
    assert close(got, [[0, 0, 0], [0, 0.2, 0.25], [0, 0, 0]])
    f = Problem(FOUR_BAR, 0, FunctionTarget([0.1, 0.2], [1, 3]), None, Constraints())
    assert close(f.residuals(np.array([1.5, 3 - 2 * math.pi + 0.1])), [[0.5], [0.1]])
    assert f.offsets_of_timing(f.linkage(np.array([0.2, 0.3, 1.2, 0.9]))).tolist() == \
        pytest.approx([math.remainder(0.1 - math.atan2(0.3, 0.2), 2 * math.pi),
                       math.remainder(0.2 - math.atan2(0.3, 0.2), 2 * math.pi)])
    timed = Problem(FOUR_BAR, 0, PathTarget(PATH.points, [2, 1.5, 1]), None, Constraints())
    assert timed.offsets_of_timing(None).tolist() == [0, -0.5, -1]


def test_the_samples_where_the_dyads_must_close():
    p = Problem(FOUR_BAR, 0, PATH, None, Constraints())
    s = p.samples(np.array([0.3, -0.1]))
    assert s[0] == -0.1 and s[-1] == pytest.approx(0.3) and len(s) == 2 + int(0.4 / SPAN_STEP)
    assert len(p.samples(np.array([0.5]))) == 2 + int(0.5 / SPAN_STEP) and p.samples(np.array([0.5]))[0] == 0
    crank = Problem(FOUR_BAR, 0, PATH, None, Constraints(crank=True)).samples(np.array([0.3]))
    # a turn from one step before 0 to 2π: every input of the turn lies between two samples (Problem.dips)
    turn = crank[2 + int(0.3 / SPAN_STEP):]
    assert len(turn) == TURN_SAMPLES + 2 and turn[-1] == pytest.approx(2 * math.pi)
    assert np.diff(turn) == pytest.approx(np.full(TURN_SAMPLES + 1, 2 * math.pi / TURN_SAMPLES))
    piston = Problem(SLIDER_CRANK, 1, PATH, None, Constraints(crank=True)).samples(np.array([1.0]))
    assert len(piston) == 2 + int(1.0 / (SPAN_STEP * 5))  # a slide's step is over the size, and it has no turn


def test_each_violation_is_measured_inside_the_designers_limit():
    lk = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])  # frame 4, crank 1: ratio 4
    none = Problem(FOUR_BAR, 0, PATH, None, Constraints())
    assert none.violations(lk, np.array([0.5]), None, None).tolist() == []
    t = Problem(FOUR_BAR, 0, PATH, None, Constraints(min_transmission=0.5))
    assert t.violations(lk, np.array([0.5]), None, np.array([0.3, 0.9])).tolist() == pytest.approx([0.2 + MARGIN])
    assert t.violations(lk, np.array([0.5]), None, np.array([0.6])).tolist() == [0.0]
    assert t.violations(lk, np.array([0.5]), None, None).tolist() == [0.0]
    r = Problem(FOUR_BAR, 0, PATH, None, Constraints(max_ratio=2.0))
    assert r.violations(lk, np.array([0.5]), None, None).tolist() == pytest.approx([math.log(4 / (2 * (1 - MARGIN)))])
    assert Problem(FOUR_BAR, 0, PATH, None, Constraints(max_ratio=5.0)).violations(lk, np.array([0.5]), None, None) \
        .tolist() == [0.0]
    n = Problem(FOUR_BAR, 0, PATH, None, Constraints(max_length=2.0))  # the frame, 4, is the longest
    assert n.violations(lk, np.array([0.5]), None, None).tolist() == pytest.approx([math.log(4 / (2 * (1 - MARGIN)))])
    assert Problem(FOUR_BAR, 0, PATH, None, Constraints(max_length=4.5)).violations(lk, np.array([0.5]), None, None) \
        .tolist() == [0.0]
    # pivots (0, 0) and (4, 0) against the box x 1 … 3, y −1 … 1: 1 + MARGIN·5 out in x, each; over the size 5
    pv = Problem(FOUR_BAR, 0, PATH, None, Constraints(pivots=(1, 3, -1, 1)))
    gap = 1 + MARGIN * 5
    assert pv.violations(lk, np.array([0.5]), None, None).tolist() == pytest.approx([math.hypot(gap, gap) / 5])
    # pivots at y = 1 inside the box's y range 0.2 … 2: only their x is out
    high = Linkage(FOUR_BAR, (0,), [[0, 1], [4, 1], [1, 1], [3, 3]])
    box = Problem(FOUR_BAR, 0, PATH, None, Constraints(pivots=(1, 3, 0.2, 2)))
    assert box.violations(high, np.array([0.5]), None, None).tolist() == pytest.approx([math.hypot(gap, gap) / 5])
    # the input starts at atan2(0, 1) = 0 and runs to 0.5; limits (0.1, 0.4): 0.1 + M below, 0.1 + M above;
    # run back to −0.05 instead: 0.15 + M below only
    rk = Problem(FOUR_BAR, 0, PATH, None, Constraints(rocker=(0.1, 0.4)))
    assert rk.violations(lk, np.array([0.5, 0.2]), None, None).tolist() == pytest.approx([0.2 + 2 * MARGIN])
    assert rk.violations(lk, np.array([-0.05]), None, None).tolist() == pytest.approx([0.15 + MARGIN])


def test_poses_give_the_least_discriminant_and_the_worst_transmission():
    p = Problem(FOUR_BAR, 0, PATH, 2, Constraints())
    lk = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]], tracers={"P": (2, (2, 3))})
    theta, t, g, mu = p.poses(lk, np.array([0.0, math.pi, 2.0]))
    # the transmission angle at the pose: between coupler and rocker at 2-3
    u, v = np.array([2.5, 3.0]), np.array([-0.5, 3.0])
    angle = math.acos(u @ v / np.hypot(*u) / np.hypot(*v))
    assert mu[0] == pytest.approx(min(angle, math.pi - angle)) and (g > 0).all()
    xy, _, _ = p.move(lk, np.array([0.0]))
    assert close(xy, [[2, 3]])
    assert close(point_carried(np.array([math.pi / 2]), np.array([[1.0, 2.0]]), np.array([1.0, 0.0])), [[1, 3]])
    # a crank too short for its rocker: a dyad that cannot close at some input gives g = −1 there
    short = Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [2.5, 0], [3.5, 1]])
    _, _, g, mu = p.poses(short, np.array([0.0, math.pi]))
    assert g[0] > 0 and g[1] == -1.0
    assert mu[1] == math.pi / 2  # no transmission angle where the dyad does not close: counted as the best
    # a lone crank has no dyad: every input closes, at the best transmission
    crank = Mechanism(Chain.parse("0-1"), 0)
    lone = Problem(crank, 0, PATH, None, Constraints())
    _, _, g, mu = lone.poses(Linkage(crank, (0,), [[0, 0]], tracers={"P": (1, (1, 0))}), np.array([0.0, 1.0, 2.0]))
    assert g.tolist() == [1, 1, 1] and mu.tolist() == [math.pi / 2] * 3


def test_link_ratio_and_the_input_joint():
    assert link_ratio(Linkage(FOUR_BAR, (0,), [[0, 0], [8, 0], [2, 0], [5, 4]])) == pytest.approx(4.0)
    lk = Linkage(SLIDER_CRANK, (0,), [[0, 0], [3, 0.5], [0.6, 0.8], [3, 0.5]], {1: (1, 0)})
    assert link_ratio(lk) == pytest.approx(math.hypot(2.4, 0.3) / 1.0)
    assert input_joint_of(FOUR_BAR, None) == (0, None)
    assert input_joint_of(Mechanism(FOUR_BAR.chain, 0, 3), None) == (1, None)
    assert input_joint_of(Mechanism(Chain.parse("0=1 1-2 2-3 3-0"), 0), None) == (1, None)  # revolute first
    assert input_joint_of(Mechanism(Chain.parse("0=1 1-2 2-3 3-0"), 0, 1), None) == (0, None)
    assert input_joint_of(None, lk) == (0, None)
    central = Mechanism(Chain.parse("0-1-2-3 2-4 1~4 3~4"), 0)  # the frame's one joint is the central axis
    assert refused(DimensionError, input_joint_of, central, None) == \
        "the frame (link 0) has no joint with one moving link to drive"
    assert refused(DimensionError, input_joint_of, Mechanism(central.chain, 0, 1), None) == \
        "the frame (link 0) has no joint with one moving link to drive (link 1)"


def test_a_tracer_turning_about_a_fixed_pivot_is_placed_without_moving_the_mechanism():
    # the tracer on the crank: the crank's translation is 0 (it turns about the origin), so no scale or
    # shift can be fitted; the point is q with e^{iθ}·q through the target's points
    theta = np.array([0.0, 0.5, 1.0])
    q0 = 0.8 + 0.6j
    points = np.column_stack(((np.exp(1j * theta) * q0).real, (np.exp(1j * theta) * q0).imag))
    p = Problem(FOUR_BAR, 0, PathTarget(points, theta), 1, Constraints())
    tracer, lam, shift, traced = p.best_placement(theta, np.zeros((3, 2)))
    assert lam == 1 and shift == 0
    assert abs(tracer - q0 / p.scale) < 1e-12 and close(traced, points)
