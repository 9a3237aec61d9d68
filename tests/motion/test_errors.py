"""Bad input: one sentence, a specific MotionError, nothing half done."""

import json
import math

import numpy as np
import pytest

from synth.errors import BadPose, BadSweep, CannotAssemble, LockedMechanism, MotionError, WrongInputs
from synth.motion import Linkage, linkage_from_pose, read_linkage, sweep, sweep_grid
from synth.structure.chain import Chain, Mechanism

from .helpers import four_bar

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1 0-3 1-2 2-3
GOOD = [[0, 0], [4, 0], [1, 0], [3.5, 3]]


def one_sentence(exc):
    text = str(exc.value)
    assert text and "\n" not in text and "Traceback" not in text
    return text


@pytest.mark.parametrize("points, error, words", [
    ([[0, 0], [4, 0], [1, 0], [1, 0]], BadPose, "same point"),           # link 2: a zero-length coupler
    ([[0, 0], [4, 0], [0, 0], [3.5, 3]], BadPose, "same point"),         # crank pin on the crank pivot
    ([[0, 0], [4, 0], [1, 0], [math.nan, 3]], BadPose, "not finite"),
    ([[0, 0], [math.inf, 0], [1, 0], [3.5, 3]], BadPose, "not finite"),
    ([[0, 0], [4, 0], [1, 0]], BadPose, "one [x, y] per joint"),
])
def test_a_pose_that_contradicts_the_chain(points, error, words):
    with pytest.raises(error) as exc:
        Linkage(FOUR_BAR, (0,), points)
    assert words in one_sentence(exc)


def test_wrong_inputs():
    with pytest.raises(WrongInputs) as exc:
        Linkage(FOUR_BAR, (), GOOD)
    assert "needs 1 input" in one_sentence(exc)
    with pytest.raises(WrongInputs):
        Linkage(FOUR_BAR, (0, 1), GOOD)
    with pytest.raises(WrongInputs) as exc:
        Linkage(FOUR_BAR, (2,), GOOD)  # 1-2 is not on the frame
    assert "must join the frame" in one_sentence(exc)
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
                       [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    with pytest.raises(WrongInputs) as exc:
        sweep(five_bar)
    assert "sweep_grid" in one_sentence(exc)


def test_rigid_and_locked():
    with pytest.raises(LockedMechanism) as exc:
        Linkage(Mechanism(Chain.parse("0-1 1-2 2-0"), 0), (0,), [[0, 0], [1, 0], [0.5, 1]])
    assert "rigid" in one_sentence(exc)
    with pytest.raises(LockedMechanism) as exc:  # a pose with coupler and rocker in line
        linkage_from_pose(FOUR_BAR, [[0, 0], [4, 0], [1, 0], [2, 0]])
    assert "links 2, 3 are aligned" in one_sentence(exc)
    nudged = linkage_from_pose(FOUR_BAR, [[0, 0], [4, 0], [1, 0], [2, 0]], nudge=True)
    assert nudged.note and "moved by up to" in nudged.note
    assert sweep(nudged, steps=5).joints.shape == (5, 4, 2)


def test_cannot_assemble_names_the_group():
    lk = four_bar(2.5, 3.2, 3.0, 4.0, phi=0.5)  # a rocker between ±2.518 rad
    with pytest.raises(CannotAssemble) as exc:
        sweep(lk, start=3.0, stop=3.1)
    text = one_sentence(exc)
    assert "RRR dyad of links 2, 3" in text and "between" in text


@pytest.mark.parametrize("kwargs, words", [
    ({"steps": 1}, "2 …"), ({"steps": 10 ** 9}, "2 …"), ({"steps": 2.5}, "whole number"), ({"steps": True}, "whole"),
    ({"start": math.nan}, "finite"), ({"stop": math.inf}, "finite"), ({"start": "a"}, "number"),
    ({"start": 1.0, "stop": 1.0}, "same input"),
])
def test_absurd_sweeps(kwargs, words):
    lk = four_bar(1, 3.5, 3, 4)
    with pytest.raises(BadSweep) as exc:
        sweep(lk, **kwargs)
    assert words in one_sentence(exc)


def test_grids_refuse_too_many_steps_and_wrong_ranges():
    five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
                       [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
    with pytest.raises(BadSweep):
        sweep_grid(five_bar, [(0, 1)], steps=3)
    with pytest.raises(BadSweep):
        sweep_grid(five_bar, [(0, 1), (0, 1)], steps=10_000)


@pytest.mark.parametrize("content, words", [
    ("not json", "not valid JSON"),
    ("[1, 2]", "must be an object"),
    (json.dumps({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"], "points": {"0-1": [0, 0]}}), "no position"),
    (json.dumps({"chain": "0-1 1-2 2-3 3-0", "frame": 9, "inputs": ["0-1"], "points": {}}), "'frame'"),
    (json.dumps({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["5-6"], "points": {}}), "not a joint"),
    (json.dumps({"chain": "0-1 1-1", "frame": 0, "inputs": [], "points": {}}), "chain cannot be read"),
    (json.dumps({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"], "pints": {}}), "no entry 'pints'"),
])
def test_bad_files_are_one_sentence_and_untouched(tmp_path, content, words):
    path = tmp_path / "bad.json"
    path.write_text(content)
    with pytest.raises(MotionError) as exc:
        read_linkage(path)
    assert words in one_sentence(exc)
    assert path.read_text() == content
    with pytest.raises(MotionError):
        read_linkage(tmp_path / "missing.toml")


def test_toml_and_json_round_trip(tmp_path):
    lk = four_bar(1, 3.5, 3, 4, tracer=(2, 3))
    (tmp_path / "a.json").write_text(lk.to_json())
    again = read_linkage(tmp_path / "a.json")
    assert again.to_dict() == lk.to_dict() and np.array_equal(again.points, lk.points)
    toml = ('[linkage]\nchain = "0-1 1-2 2=3 3-0"\nframe = 0\ninputs = ["0-1"]\n'
            '[linkage.points]\n"0-1" = [0, 0]\n"1-2" = [1, 0]\n"2=3" = [3, 0.5]\n"0-3" = [4, 0]\n'
            '[linkage.slides]\n"2=3" = [0, 2]\n[linkage.tracers]\nP = {link = 2, at = [2, 1]}\n')
    (tmp_path / "b.toml").write_text(toml)
    lk2 = read_linkage(tmp_path / "b.toml")
    assert lk2.slides == {3: (0.0, 1.0)} and lk2.tracers == {"P": (2, (2.0, 1.0))}
