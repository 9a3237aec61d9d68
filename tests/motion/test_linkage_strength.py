"""A linkage's checks and views, each against a value worked out by hand: every refusal names what
is wrong (the joint, the link, the number), the pose's inputs, references, lengths, gear ratios
and carriers, and the files' round trip of every entry."""

import json
import math

import numpy as np
import pytest

from synth.errors import BadPose, LockedMechanism, MotionError, WrongInputs
from synth.motion import Linkage, joint_name, read_linkage
from synth.structure.chain import Chain, Mechanism
from tests.refusals import refused

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1 0-3 1-2 2-3
GOOD = [[0, 0], [4, 0], [1, 0], [3.5, 3]]
SLIDER = Mechanism(Chain.parse("0-1 1-2 2-3 0=3"), 0)  # joints 0-1 0=3 1-2 2-3
SLIDER_POINTS = [[0, 0], [3, 0.5], [0.6, 0.8], [3, 0.5]]
#: sun 1, carrier 2, ring 3 on the frame's axis; planet 4 on the carrier (joints 0-1-2-3, 1~4, 2-4, 3~4)
PLANETARY = Mechanism(Chain.parse("0-1-2-3 2-4 1~4 3~4"), 0)
PLANETARY_POINTS = [[0, 0], [1, 0], [1.5, 0], [2, 0]]


# ------------------------------------------------------------------ the pose
def test_the_pose_is_refused_in_a_sentence_that_names_what_is_wrong():
    assert refused(MotionError, Linkage, Mechanism(Chain(6, tuple((i, (i + 1) % 6) for i in range(6)), h=5), 0), (0,),
                    np.zeros((6, 2))) == "a linkage moves in the plane (h = 3), not in motion space h = 5"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), [[0, 0], [4, 0], [1, 0], ["a", 3]]) == \
        "the joint positions must be numbers, one [x, y] per joint"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), np.zeros((4, 3))) == \
        "the pose needs one [x, y] per joint (4), not an array of shape (4, 3)"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), [[0, 0], [4, 0], [1, math.nan], [3.5, 3]]) == \
        "joint 1-2 has a position that is not finite: [1.0, nan]"
    # the crank's two pins at one point: joints 0-1 and 1-2 of link 1
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), [[0, 0], [4, 0], [0, 0], [3.5, 3]]) == \
        ("joints 0-1 and 1-2 of link 1 are at the same point: a link's pins must be apart (a zero-length link)")
    # a gap of 1e-8 of the mechanism's size is a length; 1e-10 is not
    Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [4e-8, 0], [3.5, 3]])
    with pytest.raises(BadPose):
        Linkage(FOUR_BAR, (0,), [[0, 0], [4, 0], [4e-10, 0], [3.5, 3]])


def test_the_inputs_are_refused_in_a_sentence_that_names_what_is_wrong():
    assert refused(WrongInputs, Linkage, FOUR_BAR, (), GOOD) == \
        "this mechanism has W = 1 and needs 1 input joint on the frame, not 0"
    five_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0)  # joints 0-1 0-4 1-2 2-3 3-4
    five = [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]]
    assert refused(WrongInputs, Linkage, five_bar, (0,), five) == \
        "this mechanism has W = 2 and needs 2 input joints on the frame, not 1"
    assert refused(WrongInputs, Linkage, FOUR_BAR, (7,), GOOD) == "input joint 7 is not a joint of the chain (0 … 3)"
    assert refused(WrongInputs, Linkage, FOUR_BAR, (-1,), GOOD) == "input joint -1 is not a joint of the chain (0 … 3)"
    assert refused(WrongInputs, Linkage, FOUR_BAR, (3,), GOOD) == \
        "input joint 2-3 must join the frame (link 0) to one moving link, or name the link it drives"
    assert refused(WrongInputs, Linkage, five_bar, (0, 0), five) == "an input joint is named twice"
    assert refused(WrongInputs, Linkage, FOUR_BAR, (0,), GOOD, driven=(1, 3)) == \
        "2 driven links given for 1 inputs"
    assert refused(WrongInputs, Linkage, FOUR_BAR, (0,), GOOD, driven=(3,)) == \
        "input joint 0-1 does not join the frame (link 0) to link 3"
    assert refused(WrongInputs, Linkage, FOUR_BAR, (0,), GOOD, driven=(0,)) == \
        "input joint 0-1 does not join the frame (link 0) to link 0"
    assert refused(WrongInputs, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, driven=(1, 1)) == \
        "an input joint is named twice"
    # a mesh of the frame as an input
    geared = Mechanism(Chain.parse("0-1 1-2 0~2"), 0)  # a planet 2 on the arm 1 rolling on the fixed sun 0
    assert geared.chain.joints == ((0, 1), (0, 2), (1, 2))
    assert refused(WrongInputs, Linkage, geared, (1,), [[0, 0], [2, 0], [3, 0]]) == \
        "input joint 0~2 is a gear mesh: drive a revolute or prismatic joint of the frame"
    assert refused(LockedMechanism, Linkage, Mechanism(Chain.parse("0-1 1-2 2-0"), 0), (0,),
                    [[0, 0], [1, 0], [0.5, 1]]) == "the chain 0-1 0-2 1-2 is rigid (W = 0): nothing can move it"
    # the only revolute input of each joint of the frame: the link it drives
    assert Linkage(FOUR_BAR, (1,), GOOD).driven == (3,) and Linkage(FOUR_BAR, (0,), GOOD).driven == (1,)


def test_slides_are_checked_and_made_unit():
    assert Linkage(SLIDER, (0,), SLIDER_POINTS, {1: (3, 4)}).slides == {1: (0.6, 0.8)}
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {}) == \
        "prismatic joint 0=3 needs its sliding direction"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (0, 0)}) == \
        "the sliding direction of joint 0=3 has zero length"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (1, 0), 2: (1, 0)}) == \
        "a sliding direction is given for joint 2, which is not a prismatic joint"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (1, 0), 9: (1, 0)}) == \
        "a sliding direction is given for joint 9, which is not a prismatic joint"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (1, 0), 4: (1, 0)}) == \
        "a sliding direction is given for joint 4, which is not a prismatic joint"  # one past the last joint
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (1, 0), -1: (1, 0)}) == \
        "a sliding direction is given for joint -1, which is not a prismatic joint"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (1, 0), "0=3": (1, 0)}) == \
        "a sliding direction is given for joint '0=3', which is not a prismatic joint"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: "ab"}) == \
        "the sliding direction of joint 0=3 must be two numbers [x, y], not 'ab'"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: "10"}) == \
        "the sliding direction of joint 0=3 must be two numbers [x, y], not '10'"  # no direction (1, 0)
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (True, 0)}) == \
        "the sliding direction of joint 0=3 must be two numbers [x, y], not (True, 0)"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (1, math.inf)}) == \
        "the sliding direction of joint 0=3 is not finite: (1, inf)"
    assert refused(BadPose, Linkage, SLIDER, (0,), SLIDER_POINTS, {1: (math.nan, 1)}) == \
        "the sliding direction of joint 0=3 is not finite: (nan, 1)"


def test_gear_ratios_follow_from_the_pitch_points_or_are_checked():
    lk = Linkage(PLANETARY, (0, 0), PLANETARY_POINTS, driven=(1, 2))
    # sun ~ planet: pitch point 1 from the sun's axis, 0.5 from the planet's, on opposite sides: −0.5
    # planet ~ ring: 0.5 from the planet's axis, 2 from the ring's, on the same side: +0.25
    assert lk.meshes == {1: -0.5, 3: 0.25}
    # the same train anywhere: the same ratios (radii from each gear's own axis)
    moved = Linkage(PLANETARY, (0, 0), np.array(PLANETARY_POINTS) + [5.0, -3.0], driven=(1, 2))
    assert moved.meshes == pytest.approx({1: -0.5, 3: 0.25})
    assert lk.carrier(1) == 2 and lk.carrier(3) == 2 and lk.axis(4, 2) == 2 and lk.axis(1, 2) == 0
    given = Linkage(PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: (2.0, 3.0), 3: -0.7}, driven=(1, 2))
    assert given.meshes == {1: -1.5, 3: -0.7}
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: (0, 3)}, driven=(1, 2)) == \
        "a pitch radius of mesh 1~4 is zero"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: (3, 0)}, driven=(1, 2)) == \
        "a pitch radius of mesh 1~4 is zero"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: (1, "x")}, driven=(1, 2)) == \
        "the pitch radii of mesh 1~4 must be two numbers [x, y], not (1, 'x')"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: [1, math.inf]}, driven=(1, 2)) == \
        "the pitch radii of mesh 1~4 is not finite: [1, inf]"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: "x"}, driven=(1, 2)) == \
        "the ratio of mesh 1~4 must be a number or a pair of pitch radii, not 'x'"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: 0}, driven=(1, 2)) == \
        "the ratio of mesh 1~4 must be finite and not zero, not 0"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: math.inf}, driven=(1, 2)) == \
        "the ratio of mesh 1~4 must be finite and not zero, not inf"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={2: 1.0}, driven=(1, 2)) == \
        "a gear ratio is given for joint 2, which is not a gear mesh"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={9: 1.0}, driven=(1, 2)) == \
        "a gear ratio is given for joint 9, which is not a gear mesh"
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={4: 1.0}, driven=(1, 2)) == \
        "a gear ratio is given for joint 4, which is not a gear mesh"  # one past the last joint
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), PLANETARY_POINTS, meshes={-1: 1.0}, driven=(1, 2)) == \
        "a gear ratio is given for joint -1, which is not a gear mesh"
    # the pitch point on the planet's axis
    assert refused(BadPose, Linkage, PLANETARY, (0, 0), [[0, 0], [1.5, 0], [1.5, 0], [2, 0]], driven=(1, 2)) == \
        "the pitch point of mesh 1~4 is on a gear's axis: give the ratio or move the point"
    # no link carries both gears' axes
    loose = Mechanism(Chain.parse("0-1 1~2 2-3 3-0"), 0)
    assert refused(BadPose, Linkage, loose, (0, 1), [[0, 0], [4, 0], [1, 0], [3.5, 3]]) == \
        "gear mesh 1~2 needs a link carrying both gears' axes (a carrier)"


def test_the_frame_is_the_carrier_preferred_among_several():
    # gears 1 and 2 pinned to the frame (0) and to link 3: both carry both axes; the frame is chosen
    chain = Chain.parse("0-1 0-2 1~2 1-3 2-3")
    lk = Linkage.__new__(Linkage)
    object.__setattr__(lk, "mechanism", Mechanism(chain, 0))
    object.__setattr__(lk, "points", np.zeros((len(chain.joints), 2)))
    k = chain.joints.index((1, 2))
    assert lk.carrier(k) == 0
    object.__setattr__(lk, "mechanism", Mechanism(chain, 3))
    assert lk.carrier(k) == 3


def test_tracers_are_checked():
    assert Linkage(FOUR_BAR, (0,), GOOD, tracers={7: ("2", [1, "2"])}).tracers == {"7": (2, (1.0, 2.0))}
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), GOOD, tracers={"P": (2,)}) == \
        "tracer 'P' must be (link, [x, y]), not (2,)"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), GOOD, tracers={"P": ("a", (1, 2))}) == \
        "tracer 'P' must be (link, [x, y]), not ('a', (1, 2))"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), GOOD, tracers={"P": (4, (1, 2))}) == \
        "tracer 'P' is on link 4, which is not a link of the chain"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), GOOD, tracers={"P": (-1, (1, 2))}) == \
        "tracer 'P' is on link -1, which is not a link of the chain"
    assert refused(BadPose, Linkage, FOUR_BAR, (0,), GOOD, tracers={"P": (3, (1, math.inf))}) == \
        "the position of tracer 'P' is not finite: (1, inf)"


# ------------------------------------------------------------------ the views
def test_the_pose_inputs_and_references_are_the_cranks_angle():
    lk = Linkage(FOUR_BAR, (0,), GOOD)
    assert lk.input_reference(0) == 2 and lk.pose_inputs.tolist() == [0.0]
    turned = Linkage(FOUR_BAR, (0,), [[1, 1], [4, 0], [0, 2], [3.5, 3]])
    assert turned.pose_inputs[0] == pytest.approx(3 * math.pi / 4, abs=1e-15)
    rocker = Linkage(FOUR_BAR, (1,), GOOD)  # the rocker 3 from (4, 0) to (3.5, 3)
    assert rocker.input_reference(0) == 3 and rocker.pose_inputs[0] == pytest.approx(math.atan2(3, -0.5), abs=1e-15)
    slider = Linkage(SLIDER, (1,), SLIDER_POINTS, {1: (1, 0)})
    assert slider.input_reference(0) is None and slider.pose_inputs.tolist() == [0.0]
    # a ternary crank whose first other pin is on its pivot: the reference is the pin away from it
    chain = Chain.parse("0-1 1-2 2-3 3-0 1-4 4-5 5-0")  # joints 0-1 0-3 0-5 1-2 1-4 2-3 4-5
    pts = [[0, 0], [4, 0], [2, -3], [0, 0], [-1, 1], [3, 2], [1, -2]]
    ternary = Linkage(Mechanism(chain, 0), (0,), pts)
    assert ternary.input_reference(0) == 4 and ternary.pose_inputs[0] == pytest.approx(3 * math.pi / 4, abs=1e-15)
    assert Linkage(FOUR_BAR, (0,), GOOD).scale == 4.0


def test_lengths_are_the_distances_between_two_pins():
    lk = Linkage(FOUR_BAR, (0,), GOOD)
    assert lk.lengths() == pytest.approx({1: 1.0, 2: math.hypot(2.5, 3), 3: math.hypot(0.5, 3), 0: 4.0})
    slider = Linkage(SLIDER, (0,), SLIDER_POINTS, {1: (1, 0)})
    assert set(slider.lengths()) == {1, 2}  # the frame and the block have one pin each
    assert slider.lengths()[2] == pytest.approx(math.hypot(2.4, 0.3))
    assert lk.joints_of(2) == (2, 3) and lk.joints_of(0) == (0, 1) and lk.kind(0) == "revolute"
    assert joint_name(SLIDER.chain, 1) == "0=3"


# ------------------------------------------------------------------ reading and writing
def test_every_entry_is_written_and_read_back():
    lk = Linkage(SLIDER, (0,), SLIDER_POINTS, {1: (0, 2)}, tracers={"P": (2, (1, 1))}, note="moved")
    d = lk.to_dict()
    assert d == {"chain": "0-1 0=3 1-2 2-3", "frame": 0, "inputs": ["0-1"],
                 "points": {"0-1": [0.0, 0.0], "0=3": [3.0, 0.5], "1-2": [0.6, 0.8], "2-3": [3.0, 0.5]},
                 "slides": {"0=3": [0.0, 1.0]}, "tracers": {"P": {"link": 2, "at": [1.0, 1.0]}}, "note": "moved"}
    again = Linkage.from_dict(d)
    assert again.note == "moved" and again.slides == {1: (0.0, 1.0)} and again.tracers == {"P": (2, (1.0, 1.0))}
    geared = Linkage(PLANETARY, (0, 0), PLANETARY_POINTS, meshes={1: -2.0}, driven=(1, 2))
    assert geared.to_dict()["meshes"] == {"1~4": -2.0, "3~4": 0.25}
    assert geared.to_dict()["inputs"] == ["0-1", "0-2"]
    back = Linkage.from_dict(geared.to_dict())
    assert back.meshes == {1: -2.0, 3: 0.25} and back.driven == (1, 2)
    plain = Linkage(FOUR_BAR, (0,), GOOD).to_dict()
    assert set(plain) == {"chain", "frame", "inputs", "points"}


def test_joints_are_named_by_links_or_index_and_refused_clearly():
    base = {"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["1-0"],
            "points": {"0-1": [0, 0], "1-2": [1, 0], "2-3": [3.5, 3], "0-3": [4, 0]}}
    assert Linkage.from_dict(base).inputs == (0,)
    assert Linkage.from_dict({**base, "inputs": 1}).inputs == (1,)
    assert Linkage.from_dict({**base, "inputs": "0-3"}).inputs == (1,)
    assert Linkage.from_dict({**base, "inputs": [[3, 0]]}).inputs == (1,)
    assert Linkage.from_dict({**base, "points": {0: [0, 0], 2: [1, 0], 3: [3.5, 3], 1: [4, 0]}}).points.tolist() == \
        [[0, 0], [4, 0], [1, 0], [3.5, 3]]
    assert Linkage.from_dict({**base, "chain": [[0, 1], [1, 2], [2, 3], [3, 0]]}).chain == FOUR_BAR.chain
    cases = [
        ({**base, "inputs": [4]}, "'inputs' names joint 4, but the chain has joints 0 … 3"),
        ({**base, "inputs": [True]}, "'inputs' names joint True: write a joint by its links, e.g. '1-2'"),
        ({**base, "inputs": ["a-b"]}, "'inputs' names joint 'a-b': write a joint by its links, e.g. '1-2'"),
        ({**base, "inputs": ["1-3"]}, "'inputs' names joint '1-3', which is not a joint of the chain 0-1 0-3 1-2 2-3"),
        ({**base, "inputs": [[1, 3]]}, "'inputs' names joint [1, 3], which is not a joint of the chain 0-1 0-3 1-2 2-3"),
        ({**base, "inputs": {"0-1": 1}}, "'inputs' must be a list of joints, e.g. ['0-1']"),
        ({**base, "points": [[0, 0]]}, "'points' must map each joint to its position, e.g. {'0-1': [0, 0]}"),
        ({**base, "points": {**base["points"], "1-0": [0, 0]}}, "'points' gives joint 0-1 twice"),
        ({**base, "points": {"0-1": [0, 0], "1-2": [1, 0]}}, "joints 0-3, 2-3 have no position in 'points'"),
        ({**base, "points": {"0-1": [0, 0], "1-2": [1, 0], "2-3": [3.5, 3]}}, "joint 0-3 has no position in 'points'"),
        ({**base, "points": {**base["points"], "0-1": [0, "x"]}},
         "the position of joint 0-1 must be two numbers [x, y], not [0, 'x']"),
        ({**base, "frame": True}, "'frame' must be a link number 0 … 3, not True"),
        ({**base, "frame": -1}, "'frame' must be a link number 0 … 3, not -1"),
        ({**base, "frame": 4}, "'frame' must be a link number 0 … 3, not 4"),
        ({**base, "slides": [1, 0]}, "'slides' must map joints to values"),
        ({**base, "meshes": 2}, "'meshes' must map joints to values"),
        ({**base, "tracers": {"P": [2, [1, 1]]}}, "'tracers' must map each name to {link = L, at = [x, y]}"),
        ({**base, "tracers": {"P": {"link": 2}}}, "'tracers' must map each name to {link = L, at = [x, y]}"),
        ({**base, "tracers": []}, "'tracers' must map each name to {link = L, at = [x, y]}"),
        ({k: v for k, v in base.items() if k != "inputs"}, "a linkage needs 'inputs'"),
        ({k: v for k, v in base.items() if k != "chain"}, "a linkage needs 'chain'"),
        ({**base, "speed": 1, "angle": 2}, "a linkage has no entry 'angle' (it has chain, frame, inputs, points, "
                                            "slides, meshes, tracers)"),
    ]
    for d, words in cases:
        assert refused(MotionError, Linkage.from_dict, d) == words, words
    assert refused(MotionError, Linkage.from_dict, [base]) == \
        "a linkage must be an object (a table) with 'chain', 'frame', 'inputs' and 'points'"
    assert refused(MotionError, Linkage.from_dict, {**base, "chain": {"joints": "x"}}).startswith(
        "the linkage's chain cannot be read: ")


def test_an_input_inside_a_multiple_joint_is_named_by_the_frame_and_its_link():
    base = {"chain": "0-1-2-3 2-4 1~4 3~4", "frame": 0,
            "points": {"0-1-2-3": [0, 0], "1~4": [1, 0], "2-4": [1.5, 0], "3~4": [2, 0]}}
    lk = Linkage.from_dict({**base, "inputs": ["0-1", "2-0"]})
    assert lk.inputs == (0, 0) and lk.driven == (1, 2)
    for inputs, words in ((["1-2", "0-3"], "'inputs' names joint '1-2', which is not a joint"),
                          (["0-1-2", "0-3"], "'inputs' names joint '0-1-2', which is not a joint"),
                          (["0-5", "0-3"], "'inputs' names joint '0-5', which is not a joint"),
                          (["0-x", "0-3"], "'inputs' names joint '0-x': write a joint by its links, e.g. '1-2'"),
                          ([(0, 1), "0-3"], "'inputs' names joint (0, 1), which is not a joint")):
        assert refused(MotionError, Linkage.from_dict, {**base, "inputs": inputs}).startswith(words), inputs


def test_files_are_read_as_toml_or_json_only(tmp_path):
    assert refused(MotionError, read_linkage, tmp_path / "a.yaml") == (
        "a linkage file is .toml or .json (or the .json/.jsonl rows of an atlas search), not 'a.yaml'")
    bad = tmp_path / "a.json"
    bad.write_text('{"chain": ')
    assert refused(MotionError, read_linkage, bad) == "a.json: not valid JSON (Expecting value at line 1)."
    top = tmp_path / "top.JSON"
    top.write_text(Linkage(FOUR_BAR, (0,), GOOD).to_json())
    assert read_linkage(top).points.tolist() == [[0, 0], [4, 0], [1, 0], [3.5, 3]]


def test_a_file_that_is_not_a_linkage_is_named_and_told_apart(tmp_path):
    # another command's file given to 'move' (an arm to balance): it once read "a linkage has no entry 'arm'"
    arm = tmp_path / "arm.toml"
    arm.write_text('[arm]\nname = "two links"\n[[arm.links]]\njoint = "revolute"\nlength = 0.8\nweight = 50.0\n')
    assert refused(MotionError, read_linkage, arm) == ("arm.toml holds no linkage: a linkage file has a [linkage] "
                                                       "table, or chain, frame, inputs and points at its top; this "
                                                       "one holds arm")
    # the rows of an atlas search ('dimension --db … --format json'), each with its linkage: it read "a linkage must be
    # an object (a table) with 'chain', …", which did not say which of them to give
    rows = tmp_path / "rows.json"
    rows.write_text(json.dumps([{"rank": k, "linkage": Linkage(FOUR_BAR, (0,), GOOD).to_dict()} for k in (1, 2)]))
    assert refused(MotionError, read_linkage, rows) == (
        "rows.json holds 2 rows, not one linkage: pick one with --row K (1 to 2, as the table ranks them)")
    # one line of 'dimension --db … --format jsonl' (a row without dimensions): it read "a linkage has no entry
    # 'chain_id'"; of 'dimension --mechanism … --format jsonl' (its 'points' a count of the target's): "no entry
    # 'error_max'"
    row, one = tmp_path / "row.json", tmp_path / "one.json"
    row.write_text(json.dumps({"rank": 1, "chain": "0-1 0-2 1-3 2-3", "chain_id": "404959cfebdd", "frame": 0,
                               "input": "0-1", "tracer_link": 3, "links": 4, "error_max": 2e-14}))
    one.write_text(json.dumps({"kind": "function", "chain": "0-1 0-3 1-2 2-3", "frame": 0, "points": 3,
                               "error_max": 7.5e-14}))
    for path in (row, one):
        assert refused(MotionError, read_linkage, path) == (
            f"{path.name} is a row of 'mechsynth dimension' without its linkage: its '--format json' or 'jsonl' gives "
            "each answer with its linkage, '--save FILE' the best one's")
    # a linkage with a mistake: the sentence of Linkage.from_dict, of the same class, after the file's name
    pose = tmp_path / "pose.json"
    pose.write_text(json.dumps({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"], "points": {"0-1": [0, 0]}}))
    with pytest.raises(BadPose) as e:
        read_linkage(pose)
    assert str(e.value) == "pose.json: joints 0-3, 1-2, 2-3 have no position in 'points'"


def test_a_row_of_an_atlas_searchs_rows_is_picked_by_its_rank(tmp_path):
    """'dimension --db … --format json' (an array) and '--format jsonl' (a line each) write a row per topology
    with its linkage: row K (1-based, the table's rank) is read, and a row not given, not there, or given for a
    file of one linkage is refused in one sentence (issue 40: 'results as rows any other command reads')."""
    first, second = Linkage(FOUR_BAR, (0,), GOOD), Linkage(FOUR_BAR, (0,), np.array(GOOD) * 2.0)
    rows = [{"rank": k, "error_max": 0.0, "linkage": lk.to_dict()} for k, lk in ((1, first), (2, second))]
    array, lines = tmp_path / "rows.json", tmp_path / "rows.jsonl"
    array.write_text(json.dumps(rows))
    lines.write_text("".join(json.dumps(row) + "\n" for row in rows) + "\n")
    for path in (array, lines):
        assert read_linkage(path, row=2).points.tolist() == second.points.tolist()
        assert read_linkage(path, row=1).points.tolist() == first.points.tolist()
        assert refused(MotionError, read_linkage, path, row=3) == (
            f"--row 3 is not a row of {path.name}: it holds rows 1 to 2")
        assert refused(MotionError, read_linkage, path) == (
            f"{path.name} holds 2 rows, not one linkage: pick one with --row K (1 to 2, as the table ranks them)")
    single = tmp_path / "single.jsonl"  # an atlas search that found one topology: its row is the linkage
    single.write_text(json.dumps(rows[1]) + "\n")
    assert read_linkage(single).points.tolist() == second.points.tolist()
    assert refused(MotionError, read_linkage, single, row=2) == "--row 2 is not a row of single.jsonl: it holds row 1"
    one = tmp_path / "one.json"
    one.write_text(first.to_json())
    assert refused(MotionError, read_linkage, one, row=1) == (
        "--row picks one of the rows of an atlas search ('dimension --db … --format json'), and one.json holds one "
        "linkage: give it without --row")
    bare = tmp_path / "bare.jsonl"  # rows without their linkages (written before jsonl rows carried them)
    bare.write_text("".join(json.dumps({k: v for k, v in row.items() if k != "linkage"}) + "\n" for row in rows))
    assert refused(MotionError, read_linkage, bare, row=1) == (
        "bare.jsonl is a row of 'mechsynth dimension' without its linkage: its '--format json' or 'jsonl' gives each "
        "answer with its linkage, '--save FILE' the best one's")
    assert refused(MotionError, read_linkage, bare) == (
        "bare.jsonl holds 2 rows of 'mechsynth dimension' without their linkages: its '--format json' or 'jsonl' "
        "gives each row with its linkage")
    # a csv of rows ('move rows.csv --row 2' said only that a linkage file is .toml or .json): it names what works
    table = tmp_path / "rows.csv"
    table.write_text("rank,links,error_max\n1,4,0.0\n2,4,0.0\n")
    for row in (2, None):
        assert refused(MotionError, read_linkage, table, row=row) == (
            "rows.csv is a csv file, whose rows carry no linkage: the rows of 'dimension … --format json' or 'jsonl' "
            "carry each linkage (--row K picks one), a linkage file is .toml or .json")
    steps = tmp_path / "steps.jsonl"  # another command's rows ('move --format jsonl')
    steps.write_text('{"step": 0, "input": 0.0}\n{"step": 1, "input": 0.1}\n')
    assert refused(MotionError, read_linkage, steps) == (
        "steps.jsonl holds 2 rows of another kind, not a linkage: a linkage file has a [linkage] table, or chain, "
        "frame, inputs and points at its top")
    broken = tmp_path / "broken.jsonl"
    broken.write_text(json.dumps(rows[0]) + "\n{oops\n")
    said = refused(MotionError, read_linkage, broken)
    assert said.startswith("broken.jsonl: not valid JSON (") and said.endswith("at line 2).")
