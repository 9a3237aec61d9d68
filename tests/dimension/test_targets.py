"""Targets read from files and checked: every refusal is one sentence (BadTarget)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.dimension import FunctionTarget, MotionTarget, PathTarget, read_target
from synth.errors import BadTarget


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_each_kind_of_file_is_read_with_its_units(tmp_path):
    path = read_target(write(tmp_path, "p.csv", "x,y\n0,0\n1,0\n1,1\n"))
    assert isinstance(path, PathTarget) and path.inputs is None and path.points.shape == (3, 2)
    timed = read_target(write(tmp_path, "t.csv", "x,y,input_deg\n0,0,10\n1,0,20\n1,1,30\n"))
    assert np.allclose(timed.inputs, np.radians([10, 20, 30]))
    function = read_target(write(tmp_path, "f.csv", "input,output\n0.1,0.5\n0.2,0.6\n"), output_link=3)
    assert isinstance(function, FunctionTarget) and function.output_link == 3
    motion = read_target(write(tmp_path, "m.json", '[{"x": 0, "y": 0, "angle_deg": 0}, {"x": 1, "y": 2, "angle_deg": 90}]'))
    assert isinstance(motion, MotionTarget) and math.isclose(motion.poses[1, 2], math.pi / 2)
    assert math.isclose(motion.size, math.sqrt(5))


@pytest.mark.parametrize("name, text, words", [
    ("empty.csv", "", "is empty"),
    ("header.csv", "x,y\n", "no rows"),
    ("nan.csv", "x,y\n0,0\nnan,1\n", "not all finite"),
    ("inf.csv", "x,y\n0,0\ninf,1\n", "not all finite"),
    ("word.csv", "x,y\n0,0\none,1\n", "'one' is not a number"),
    ("columns.csv", "a,b\n0,0\n", "has the columns a, b"),
    ("ragged.csv", "x,y\n0,0,1\n", "line 2 has 3 values"),
    ("dup.csv", "x,y\n0,0\n1,1\n0,0\n", "points 1 and 3 are the same"),
    ("timing.csv", "x,y,input\n0,0,0\n1,0,1\n2,0,0.5\n", "must increase"),
    ("still.csv", "x,y,input\n0,0,0\n1,0,1\n2,0,1\n", "must increase"),
    ("one.csv", "x,y\n0,0\n", "give at least 2"),
    ("list.json", '{"x": [0, 1]}', "list of rows"),
    ("keys.json", '[{"x": 0, "y": 0}, {"x": 1}]', "same keys"),
    ("bad.json", "[{", "not valid JSON"),
    ("target.txt", "x,y\n", "is .csv or .json"),
])
def test_a_bad_target_file_is_refused_in_one_sentence(tmp_path, name, text, words):
    with pytest.raises(BadTarget, match=words) as info:
        read_target(write(tmp_path, name, text))
    assert "\n" not in str(info.value)


def test_a_missing_file_is_refused(tmp_path):
    with pytest.raises(BadTarget, match="no target file"):
        read_target(tmp_path / "none.csv")


def test_targets_built_in_python_are_checked_the_same_way():
    with pytest.raises(BadTarget, match="not all finite"):
        PathTarget([[0, 0], [1, float("nan")]])
    with pytest.raises(BadTarget, match="3 input values for 2 points"):
        PathTarget([[0, 0], [1, 1]], [0, 1, 2])
    with pytest.raises(BadTarget, match="must increase"):
        FunctionTarget([0, 1, 1], [0, 1, 2])
    with pytest.raises(BadTarget, match="rows of 3 numbers"):
        MotionTarget([[0, 0], [1, 1]])
    with pytest.raises(BadTarget, match="poses 1 and 2 are the same"):
        MotionTarget([[0, 0, 0.5], [0, 0, 0.5]])
    assert FunctionTarget([3, 2, 1], [0, 1, 2]).size == 1.0  # a decreasing timing is a timing
