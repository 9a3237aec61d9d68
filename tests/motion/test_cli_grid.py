"""`mechsynth move` for a linkage of W > 1 inputs: a grid of inputs, a row per grid point, the
workspace drawn; and what a grid refuses."""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
import pytest

from mechsynth.cli import main
from synth.motion import read_linkage, sweep_grid

# a five-bar driven by both cranks (joints 0-1 0-4 1-2 2-3 3-4), a tracer on the left coupler
FIVE_BAR = """[linkage]
chain = "0-1 1-2 2-3 3-4 4-0"
frame = 0
inputs = ["0-1", "0-4"]
points = { "0-1" = [0, 0], "0-4" = [3, 0], "1-2" = [0, 1], "2-3" = [1.5, 2.5], "3-4" = [3, 1] }
tracers = { P = { link = 2, at = [1.0, 2.2] } }
"""


@pytest.fixture
def five_bar(tmp_path):
    path = tmp_path / "five_bar.toml"
    path.write_text(FIVE_BAR)
    return path


def _run(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def test_grid_rows_hold_every_grid_point_in_row_major_order(capsys, five_bar):
    """5 × 4 values of the two cranks (degrees on the command line, rad in the rows); each reached
    point keeps the coupler's lengths; the points beyond the branch are written without positions."""
    code, out, err = _run(capsys, "move", five_bar, "--steps", "5x4", "--start", "30,0", "--stop", "150,120",
                          "--format", "csv")
    assert code == 0 and "grid points are on the branch" in err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 20 and list(rows[0])[:3] == ["step", "input.0-1", "input.0-4"]
    first = np.array([float(r["input.0-1"]) for r in rows]).reshape(5, 4)
    second = np.array([float(r["input.0-4"]) for r in rows]).reshape(5, 4)
    assert np.allclose(first[:, 0], np.radians(np.linspace(30, 150, 5)), atol=1e-15)
    assert np.allclose(second[0], np.radians(np.linspace(0, 120, 4)), atol=1e-15)
    assert (first == first[:, :1]).all() and (second == second[:1]).all()  # the last input varies fastest
    reached = [r for r in rows if r["2-3.x"] != ""]
    assert 0 < len(reached) < 20  # some of this grid is beyond the branch: empty cells, not dropped rows
    for r in reached:
        phi, psi = float(r["input.0-1"]), float(r["input.0-4"])
        a, b = np.array([math.cos(phi), math.sin(phi)]), np.array([3 + math.cos(psi), math.sin(psi)])
        pin = np.array([float(r["2-3.x"]), float(r["2-3.y"])])
        assert np.hypot(*(pin - a)) == pytest.approx(math.hypot(1.5, 1.5), abs=1e-12)
        assert np.hypot(*(pin - b)) == pytest.approx(math.hypot(1.5, 1.5), abs=1e-12)
    grid = sweep_grid(read_linkage(five_bar), [(math.radians(30), math.radians(150)),
                                               (math.radians(0), math.radians(120))], steps=[5, 4])
    assert [r["2-3.x"] != "" for r in rows] == np.isfinite(grid.joints).all(axis=(1, 2)).tolist()


def test_grid_velocities_per_input_match_differences(capsys, five_bar):
    """The velocity of the coupler pin per unit rate of each crank, against central differences over
    the grid's own neighbours (a fine grid around the pose)."""
    h = 1e-4
    code, out, _ = _run(capsys, "move", five_bar, "--steps", "3x3", "--velocities", "--format", "jsonl",
                        "--start", f"{90 - math.degrees(h)},{90 - math.degrees(h)}",
                        "--stop", f"{90 + math.degrees(h)},{90 + math.degrees(h)}")
    assert code == 0
    rows = [json.loads(line) for line in out.splitlines()]
    centre = rows[4]
    for axis in "xy":
        along_first = (rows[7][f"2-3.{axis}"] - rows[1][f"2-3.{axis}"]) / (2 * h)
        along_second = (rows[5][f"2-3.{axis}"] - rows[3][f"2-3.{axis}"]) / (2 * h)
        assert centre[f"2-3.v{axis}.0-1"] == pytest.approx(along_first, rel=1e-6, abs=1e-9)
        assert centre[f"2-3.v{axis}.0-4"] == pytest.approx(along_second, rel=1e-6, abs=1e-9)


def test_the_workspace_is_drawn(capsys, five_bar, tmp_path):
    svg = tmp_path / "workspace.svg"
    code, out, err = _run(capsys, "move", five_bar, "--steps", "13", "--out", svg)
    assert code == 0 and out == "" and "workspace ->" in err
    text = svg.read_text()
    assert text.count("<polyline") > 20  # the images of the grid's lines, coupler and pins


GRID_BAD = [
    (["--range"], "--range is for one input"),
    (["--animate", "m.gif"], "--animate is for one input"),
    (["--accelerations"], "--accelerations is for one input"),
    (["--steps", "3x3x3"], "2 counts"),
    (["--start", "10"], "one value per input"),
    (["--start", "10,20"], "both --start and --stop"),
    (["--start", "10,20", "--stop", "30"], "one each per input"),
    (["--start", "10,20", "--stop", "30,20"], "two different ends"),
    (["--steps", "200x200"], "--format jsonl or csv"),
    (["--steps", "2000x2000", "--format", "csv"], "--steps must be"),
    (["--steps", "3x1"], "--steps must be"),
    (["--start", "180,0", "--stop", "181,1", "--steps", "3"], "cannot be assembled"),
]


@pytest.mark.parametrize("argv, words", GRID_BAD, ids=[" ".join(a)[:40] for a, _ in GRID_BAD])
def test_grid_refusals_are_one_sentence_and_exit_2(argv, words, capsys, five_bar, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = five_bar.read_text()
    code, out, err = _run(capsys, "move", five_bar, *argv)
    assert code == 2, err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err and out == ""
    assert sorted(p.name for p in tmp_path.iterdir()) == ["five_bar.toml"] and five_bar.read_text() == before


@pytest.mark.parametrize("argv, words", [(["--steps", "10x10"], "one count"), (["--start", "10,20"], "one value")])
def test_a_one_input_linkage_refuses_a_grid(argv, words, capsys):
    from tests.motion.test_cli_move import FOUR_BAR

    code, _, err = _run(capsys, "move", FOUR_BAR, *argv)
    assert code == 2 and words in err and err.count("\n") == 1
