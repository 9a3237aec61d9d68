"""Targets checked to the letter: every refusal's sentence names the row, the count or the values at
fault (worked out by hand here), the tolerances of a duplicate point and of a monotonic timing, the
sizes, and what a file's columns and units become."""

from __future__ import annotations

import math

import pytest

from synth.dimension import FunctionTarget, MotionTarget, PathTarget, read_target
from synth.errors import BadTarget
from tests.refusals import refused


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_arrays_are_refused_by_what_is_wrong_with_them():
    assert refused(BadTarget, PathTarget, [[0, 0], ["a", 1]]) == "the points must be numbers"
    assert refused(BadTarget, PathTarget, [[0, 0], [1]]) == "the points must be numbers"
    assert refused(BadTarget, PathTarget, []) == "the target has no points"
    assert refused(BadTarget, PathTarget, [0, 1, 2]) == "the points must be rows of 2 numbers, not an array of shape (3,)"
    assert refused(BadTarget, PathTarget, [[0, 0, 0], [1, 1, 1]]) == \
        "the points must be rows of 2 numbers, not an array of shape (2, 3)"
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 1], [2, math.inf]]) == \
        "the points are not all finite numbers: row 3 is [2.0, inf]"
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 1]], [[0], [1]]) == \
        "the input values must be a list of numbers, not an array of shape (2, 1)"
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 1]], [0, math.nan]) == \
        "the input values are not all finite numbers: row 2 is nan"
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 1]], []) == "the target has no input values"
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 1]], [0, 1, 2]) == "the timing gives 3 input values for 2 points"
    assert refused(BadTarget, MotionTarget, [[0, 0], [1, 1]]) == "the poses must be rows of 3 numbers, not an array of shape (2, 2)"
    assert refused(BadTarget, FunctionTarget, [0, 1], [0, "x"]) == "the output values must be numbers"
    assert refused(BadTarget, FunctionTarget, [0, 1], [0, 1, 2]) == "the function gives 2 input values and 3 output values"
    assert refused(BadTarget, FunctionTarget, [0], [1]) == "the target has 1 pair: give at least 2"
    assert refused(BadTarget, PathTarget, [[0, 0]]) == "the target has 1 point: give at least 2"
    assert refused(BadTarget, MotionTarget, [[0, 0, 1]]) == "the target has 1 pose: give at least 2"
    assert refused(BadTarget, FunctionTarget, [0, "x"], [0, 1]) == "the input values must be numbers"
    assert refused(BadTarget, FunctionTarget, [0, 1], [[0], [1]]) == \
        "the output values must be a list of numbers, not an array of shape (2, 1)"
    t = PathTarget([[0, 0], [1, 2]], [0.5, 0.25])
    assert not t.points.flags.writeable and not t.inputs.flags.writeable
    f = FunctionTarget((0, 1), [2, 3])
    assert not f.inputs.flags.writeable and not f.outputs.flags.writeable and f.outputs.dtype == float


def test_a_duplicate_is_a_point_within_a_billionth_of_the_targets_size():
    # size √(3² + 4²) = 5: a gap of 4e-9 (below 5e-9) is a duplicate, 6e-9 is not
    assert refused(BadTarget, PathTarget, [[0, 0], [3, 4], [1, 1], [1 + 4e-9, 1]]) == \
        "points 3 and 4 are the same ([1.0, 1.0]): give each once (one that counts twice: give it a weight of 2)"
    assert len(PathTarget([[0, 0], [3, 4], [1, 1], [1 + 6e-9, 1]])) == 4
    # the pair found first is the closest one, named in the order of the rows
    assert refused(BadTarget, PathTarget, [[2, 2], [0, 0], [3, 4], [2, 2]]) == "points 1 and 4 are the same ([2.0, 2.0]): give each once (one that counts twice: give it a weight of 2)"
    # a pose at the same point but another angle is another pose; the same angle is a duplicate
    assert len(MotionTarget([[1, 1, 0], [1, 1, 0.5]])) == 2
    assert refused(BadTarget, MotionTarget, [[1, 1, 0.5], [2, 1, 0], [1, 1, 0.5]]) == \
        "poses 1 and 3 are the same ([1.0, 1.0, 0.5]): give each once (one that counts twice: give it a weight of 2)"


def test_the_timing_must_be_strictly_monotonic_and_says_where_it_is_not():
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 0], [2, 0], [3, 0]], [0, 1, 2, 1.5]) == \
        "the input values must increase (or decrease) from row to row, but rows 3 and 4 go 2 → 1.5"
    assert refused(BadTarget, PathTarget, [[0, 0], [1, 0], [2, 0]], [3, 2, 2]) == \
        "the input values must increase (or decrease) from row to row, but rows 2 and 3 go 2 → 2"
    # a timing that starts still is refused at its first rows
    assert refused(BadTarget, FunctionTarget, [0.125, 0.125, 1], [0, 1, 2]) == \
        "the input values must increase (or decrease) from row to row, but rows 1 and 2 go 0.125 → 0.125"
    assert refused(BadTarget, FunctionTarget, [1 / 3, 0.5, 0.4], [0, 1, 2]) == \
        "the input values must increase (or decrease) from row to row, but rows 2 and 3 go 0.5 → 0.4"
    assert len(FunctionTarget([3, 2, 1], [0, 0, 0])) == 3  # outputs need not be monotonic
    assert PathTarget([[0, 0], [1, 0], [2, 0]], [0, -1, -5]).inputs.tolist() == [0, -1, -5]


def test_a_timing_in_degrees_is_refused_in_the_files_degrees(tmp_path):
    # a crank angle typed 700 for 70: the sentence quotes the column as written, not 12.2173048 → 1.57079633 rad
    timed = write(tmp_path, "timed.csv", "x,y,input_deg\n1,2,0\n3,4,30\n5,1,700\n2,0,90\n")
    assert refused(BadTarget, read_target, timed) == \
        "the input_deg values must increase (or decrease) from row to row, but rows 3 and 4 go 700 → 90"
    function = write(tmp_path, "function.csv", "input_deg,output_deg\n10,5\n10,7\n")
    assert refused(BadTarget, read_target, function) == \
        "the input_deg values must increase (or decrease) from row to row, but rows 1 and 2 go 10 → 10"


def test_sizes_are_the_diagonal_of_the_points_box():
    t = PathTarget([[1, 1], [4, 1], [2, 5]])
    assert t.size == 5.0 and len(t) == 3 and t.kind == "path"
    m = MotionTarget([[1, 1, 0], [4, 1, 1], [2, 5, 2]])
    assert m.size == 5.0 and m.points.tolist() == [[1, 1], [4, 1], [2, 5]] and m.kind == "motion"
    assert MotionTarget([[1, 1, 0], [1, 1, 1]]).size == 1.0  # one point turning: size 1
    f = FunctionTarget([0, 1], [5, 9], output_link=2)
    assert f.size == 1.0 and f.kind == "function" and f.output_link == 2 and len(f) == 2


def test_files_say_their_kind_and_units_by_their_columns(tmp_path):
    f = read_target(write(tmp_path, "f.CSV", " Input_Deg , OUTPUT_DEG \n\n30,60\n , \n90,45\n"), output_link=3)
    assert isinstance(f, FunctionTarget) and f.output_link == 3
    assert f.inputs.tolist() == pytest.approx([math.pi / 6, math.pi / 2], abs=1e-15)
    assert f.outputs.tolist() == pytest.approx([math.pi / 3, math.pi / 4], abs=1e-15)
    radians = read_target(write(tmp_path, "r.csv", "input,output\n30,60\n90,45\n"))
    assert radians.inputs.tolist() == [30, 90] and radians.outputs.tolist() == [60, 45] and radians.output_link is None
    m = read_target(write(tmp_path, "m.csv", "x,y,angle\n0,0,1\n1,2,3\n"))
    assert isinstance(m, MotionTarget) and m.poses.tolist() == [[0, 0, 1], [1, 2, 3]]
    md = read_target(write(tmp_path, "md.csv", "x,y,angle_deg\n0,0,180\n1,2,90\n"))
    assert md.poses[:, :2].tolist() == [[0, 0], [1, 2]] and md.poses[:, 2].tolist() == pytest.approx([math.pi, math.pi / 2])
    timed = read_target(write(tmp_path, "t.json", '[{"x": 0, "y": 0, "input": 2}, {"x": 1, "y": 0, "input": 3}]'))
    assert isinstance(timed, PathTarget) and timed.inputs.tolist() == [2, 3] and timed.points.tolist() == [[0, 0], [1, 0]]
    untimed = read_target(write(tmp_path, "p.JSON", '[{"x": 0, "y": 1}, {"x": 2, "y": 3}]'))
    assert untimed.inputs is None and untimed.points.tolist() == [[0, 1], [2, 3]]


@pytest.mark.parametrize("name, text, sentence", [
    ("e.csv", " \n\n", "the target file e.csv is empty"),
    ("h.csv", "x,y\n\n", "the target file h.csv has a header but no rows"),
    ("c.csv", "x,z\n0,0\n", "c.csv has the columns x, z; a target's are x,y (a path), x,y,input (timed path), "
                             "input,output (a function; input_displacement or output_displacement for a slider's side) or x,y,angle "
                             "(a motion), an angle column named *_deg in degrees, and last an optional weight column"),
    ("r.csv", "x,y\n0,0\n1,1\n2\n", "r.csv line 4 has 1 values for the 2 columns x, y"),
    ("w.csv", "x,y\n0,0\n1,zero\n", "w.csv: 'zero' is not a number"),
    ("l.json", '{"x": 0}', 'l.json must hold a list of rows, each an object such as {"x": 0, "y": 1}'),
    ("n.json", "[]", 'n.json must hold a list of rows, each an object such as {"x": 0, "y": 1}'),
    ("o.json", "[[0, 1]]", 'o.json must hold a list of rows, each an object such as {"x": 0, "y": 1}'),
    ("k.json", '[{"x": 0, "y": 0}, {"y": 1, "x": 1}]', "k.json: every row must have the same keys as the first (x, y)"),
    ("j.json", '[{"x": 0,\n "y": }]', "j.json: not valid JSON (Expecting value at line 2)"),
    ("q.json", '[{"a": 0}]', "q.json has the columns a; a target's are x,y (a path), x,y,input (timed path), "
                             "input,output (a function; input_displacement or output_displacement for a slider's side) or x,y,angle "
                             "(a motion), an angle column named *_deg in degrees, and last an optional weight column"),
    ("t.tsv", "x,y\n0,0\n1,1\n", "a target file is .csv or .json, not 't.tsv'"),
])
def test_a_bad_file_is_refused_in_the_sentence_that_names_its_fault(tmp_path, name, text, sentence):
    path = write(tmp_path, name, text)
    assert refused(BadTarget, read_target, path) == sentence
    assert path.read_text() == text


def test_a_json_value_that_is_not_a_number_is_named(tmp_path):
    assert refused(BadTarget, read_target, write(tmp_path, "v.json", '[{"x": 0, "y": 0}, {"x": null, "y": 1}]')) == \
        "v.json: None is not a number"
