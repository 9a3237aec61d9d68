"""Function generation with a slider's displacement (issue 40): a slider-crank's crank angle → slider
displacement, and the inverse (the slider drives, the crank's angle is the output), each of random
dimensions recovered from no guess and re-checked by the motion layer (and the reference solver); every
mismatch of a target's columns and the mechanism's joints refused in one sentence (exit 2)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from mechsynth.cli import main
from synth.errors import BadTarget, DimensionError
from synth.dimension import Constraints, FunctionTarget, read_target, synthesize
from synth.dimension._problem import Problem
from synth.motion import assemble
from synth.structure.chain import Chain, Mechanism

from ..oracles.motion import follow, oracle_of

MODELS = Path(__file__).resolve().parents[2] / "models"
SLIDER_CRANK = Chain.parse("0-1 1-2 2-3 3=0")  # joints 0-1, 0=3, 1-2, 2-3: crank 1, rod 2, slider 3
CRANK_PIN, SLIDER_PIN = 2, 3


@pytest.mark.parametrize("seed", [40, 41])
def test_a_random_slider_cranks_displacement_function_is_recovered_exactly(slider_bench, seed):
    """Crank, rod and offset drawn at random; 14 pairs (crank angle, displacement) over 120°–330°."""
    theta, s, dims = slider_bench.pairs(seed, driven_by_slider=False)
    result = synthesize(Mechanism(SLIDER_CRANK, 0), FunctionTarget(theta, s, output_is="displacement"), budget=10)
    assert result.met and result.relative_max <= 1e-9 and result.size == pytest.approx(np.ptp(s))
    assert result.error_max <= 1e-9 * np.ptp(s)  # (in the target's length unit)
    assert slider_bench.recovered(result.linkage, dims) <= 1e-9  # the closed form's r, l, e
    # moved by the motion layer, the answer's slider pin passes each displacement at each crank angle
    lk = result.linkage
    assert np.allclose(lk.slides[1], (1, 0)) and lk.points[0].tolist() == [0, 0]  # the gauge: pivot, line along x
    moved = np.array([assemble(lk, angle).points[SLIDER_PIN][0] for angle in theta])
    assert np.abs(moved - s).max() <= 1e-9 * np.ptp(s)
    # and moved by the independent reference solver (tests/oracles/motion.py: Newton on absolute link poses)
    oracle = follow(oracle_of(lk), theta - theta[0], step=math.radians(1))
    assert np.abs(oracle[:, SLIDER_PIN, 0] - s).max() <= 1e-9 * np.ptp(s)
    turns = (result.inputs - theta) / (2 * math.pi)  # (the inputs as reported: each angle within a turn)
    assert np.abs(turns - np.round(turns)).max() <= 1e-12 and np.abs(result.traced - s).max() <= 1e-9 * np.ptp(s)


def test_a_slider_driving_a_crank_is_recovered_exactly(slider_bench):
    """The inverse: the slider's displacement is the input, the crank's angle the output (within one stretch of
    the slider's stroke, between the dead positions where the crank lines up with the rod)."""
    theta, s, dims = slider_bench.pairs(7, driven_by_slider=True)
    fine = slider_bench.displacement(np.linspace(theta[0], theta[-1], 10_001), *dims)
    assert (np.diff(fine) < 0).all()  # (the pairs lie on one stroke: the slider can drive them)
    m = Mechanism(SLIDER_CRANK, 0, input_link=3)
    result = synthesize(m, FunctionTarget(s, theta, input_is="displacement"), budget=10)
    assert result.met and result.error_max <= 1e-9 and result.size == 1.0  # (angles: rad)
    assert slider_bench.recovered(result.linkage, dims) <= 1e-9
    lk = result.linkage
    assert lk.inputs == (1,)
    pin = lk.points[SLIDER_PIN][0]  # the input's value in the pose: the pin along the line
    crank = [assemble(lk, value - pin).points[CRANK_PIN] for value in s]  # (the motion layer's: from the pose)
    assert np.abs(np.remainder(np.arctan2(*np.array(crank).T[::-1]) - theta + math.pi, 2 * math.pi) - math.pi).max() <= 1e-9
    assert np.allclose(result.inputs, s)


@pytest.mark.parametrize("seed, driven_by_slider", [(40, False), (3, True)])
def test_displacements_from_the_targets_own_zero_are_met_with_a_free_origin(slider_bench, seed, driven_by_slider):
    """Displacements given from a datum of the designer's (here the first pair's place, less 0.37): with a free
    origin the pivot's place along the line is found too, at the datum's distance from it."""
    theta, s, dims = slider_bench.pairs(seed, driven_by_slider)
    datum = s[0] - 0.37
    if driven_by_slider:
        m, target = Mechanism(SLIDER_CRANK, 0, 3), FunctionTarget(s - datum, theta, input_is="displacement",
                                                                  origin="free")
    else:
        m, target = Mechanism(SLIDER_CRANK, 0), FunctionTarget(theta, s - datum, output_is="displacement",
                                                               origin="free")
    result = synthesize(m, target, budget=30)
    assert result.met and result.relative_max <= 1e-9 and slider_bench.recovered(result.linkage, dims) <= 1e-9
    lk = result.linkage
    assert lk.points[0][1] == 0 and abs(lk.points[0][0] + datum) <= 1e-9 * dims[1]  # on the line, the datum away
    if not driven_by_slider:  # moved by the motion layer, the pin passes the displacements from the datum
        moved = np.array([assemble(lk, angle).points[SLIDER_PIN][0] for angle in theta])
        assert np.abs(moved - (s - datum)).max() <= 1e-9 * np.ptp(s)


def test_an_input_sliders_limits_are_its_displacements_as_the_target_measures_them(slider_bench):
    """The rocker's limits of a slider input are displacements from the output pivot's foot, as the target's inputs
    (the motion layer counts a slide from the pose): limits round the pairs are met and reported as the inputs'
    span; limits that cut off the first pairs (wide enough for their span) are reported as failed."""
    theta, s, _ = slider_bench.pairs(7, driven_by_slider=True)
    m = Mechanism(SLIDER_CRANK, 0, input_link=3)
    target = FunctionTarget(s, theta, input_is="displacement")
    result = synthesize(m, target, constraints=Constraints(rocker=(s.min() - 0.1, s.max() + 0.1)), budget=10)
    assert result.met and result.constraints["rocker"]["value"] == pytest.approx([s.min(), s.max()], abs=1e-9)
    cut = synthesize(m, target, constraints=Constraints(rocker=(s.min() + 0.05, s.max() + 1.0)), budget=2)
    assert not cut.constraints["rocker"]["met"] and cut.constraints["rocker"]["value"][0] < s.min() + 0.05


def test_the_files_columns_say_which_side_is_a_displacement(tmp_path):
    out = tmp_path / "out.csv"
    out.write_text("input_deg,output_displacement\n0,4\n90,3\n180,2\n")
    t = read_target(out)
    assert (t.input_is, t.output_is) == ("angle", "displacement")
    assert t.inputs.tolist() == pytest.approx([0, math.pi / 2, math.pi]) and t.outputs.tolist() == [4, 3, 2]
    assert t.size == 2.0
    back = tmp_path / "in.json"
    back.write_text(json.dumps([{"input_displacement": 4, "output": 0.1}, {"input_displacement": 3, "output": 0.3}]))
    t = read_target(back)
    assert (t.input_is, t.output_is, t.size) == ("displacement", "angle", 1.0)


def test_the_targets_refusals():
    with pytest.raises(BadTarget, match="^a free origin is a displacement's: this function relates two angles$"):
        FunctionTarget([0, 1], [2, 3], origin="free")
    with pytest.raises(BadTarget, match=r"^a displacement's origin is 'pivot' or 'free', not 'datum'$"):
        FunctionTarget([0, 1], [2, 3], output_is="displacement", origin="datum")
    with pytest.raises(BadTarget, match="^function generation relates two angles or an angle and a displacement"):
        FunctionTarget([0, 1], [2, 3], input_is="displacement", output_is="displacement")
    with pytest.raises(BadTarget, match=r"^output_is is 'angle' or 'displacement', not 'length'$"):
        FunctionTarget([0, 1], [2, 3], output_is="length")
    yoke = Mechanism(Chain.parse("0-1 1-2 2=3 3=0"), 0)  # a Scotch yoke: the yoke has no pin
    with pytest.raises(DimensionError, match=r"^the slider \(link 3\) has no revolute joint"):
        Problem(yoke, 0, FunctionTarget([0, 1], [2, 3], output_is="displacement"), None, Constraints())


def test_a_slider_cranks_unknowns_are_crank_rod_and_offset():
    p = Problem(Mechanism(SLIDER_CRANK, 0), 0, FunctionTarget([0, 1, 2], [4, 3, 2], output_is="displacement"), None,
                Constraints())
    assert p.layout == [("joint", CRANK_PIN), ("joint", SLIDER_PIN)] and p.unknowns == 3 and p.scale == 4.0
    free = Problem(Mechanism(SLIDER_CRANK, 0), 0, FunctionTarget([0, 1, 2, 3], [4, 3, 2, 1.5], output_is="displacement",
                                                                 origin="free"), None, Constraints())
    # the crank pivot's place along the line is a fourth; the box about the stroke's middle (2.75), a stroke (2.5) wide
    assert free.layout == [("origin", 0), ("joint", CRANK_PIN), ("joint", SLIDER_PIN)] and free.unknowns == 4
    assert free.centre.tolist() == [2.75, 0.0] and free.scale == 2.5 and free.reach == 8.0


FILES = {
    "angles.csv": "input_deg,output_deg\n35,60\n55,72\n80,95\n",
    "out.csv": "input_deg,output_displacement\n35,6\n55,7.2\n80,9.5\n",
    "in.csv": "input_displacement,output_deg\n6,35\n7.2,55\n9.5,80\n",
}


@pytest.mark.parametrize("target, chain, extra, sentence", [
    ("angles.csv", "0-1 1-2 2-3 3=0", [], "the target gives the output as angles, but the output joint 0=3 is "
     "prismatic (a slider): give its displacements (an output_displacement column)"),
    ("out.csv", "0-1 1-2 2-3 3-0", [], "the target gives the output as displacements, but the output joint 0-3 is "
     "revolute: give its angles (an output or output_deg column)"),
    ("in.csv", "0-1 1-2 2-3 3-0", [], "the target gives the input as displacements, but the input joint 0-1 is "
     "revolute: give its angles (an input or input_deg column) or drive a prismatic joint of the frame"),
    ("angles.csv", "0-1 1-2 2-3 3=0", ["--input", "0=3"], "the target gives the input as angles, but the input joint "
     "0=3 is prismatic (a slider): give its displacements (an input_displacement column)"),
])
def test_a_displacement_where_the_joint_turns_or_an_angle_where_it_slides_is_one_sentence_and_exit_2(
        tmp_path, capsys, monkeypatch, target, chain, extra, sentence):
    monkeypatch.chdir(tmp_path)
    (tmp_path / target).write_text(FILES[target])
    assert main(["dimension", target, "--mechanism", chain, "--frame", "0", *extra, "--save", "x.toml"]) == 2
    assert capsys.readouterr().err == f"mechsynth: {sentence}\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == [target]  # nothing written


def test_a_displacement_origin_for_a_target_without_displacements_is_one_sentence_and_exit_2(tmp_path, capsys):
    (tmp_path / "p.csv").write_text("x,y\n0,0\n1,0\n1,1\n")
    assert main(["dimension", str(tmp_path / "p.csv"), "--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0",
                 "--displacement-origin", "free"]) == 2
    assert capsys.readouterr().err == ("mechsynth: --displacement-origin is where a slider's displacements are measured "
                                       "from; this target gives none (no input_displacement or output_displacement "
                                       "column)\n")


def test_the_slider_crank_model_is_found_saved_and_moved(tmp_path, capsys):
    saved = tmp_path / "slider.toml"
    code = main(["dimension", str(MODELS / "dimension_slider_function.csv"), "--mechanism", "0-1 1-2 2-3 3=0",
                 "--frame", "0", "--budget", "10", "--save", str(saved), "--format", "json"])
    result = json.loads(capsys.readouterr().out)
    assert code == 0 and result["met"] and result["relative_max"] <= 1e-9
    lk = result["linkage"]
    # the model's crank 1, rod 3.2, offset 0.4 (models/dimension_slider_function.csv)
    assert sorted(np.round(list(map(float, _lengths(lk))), 9)) == [1.0, 3.2] and abs(result["traced"][0] - 4.139167317704143) < 1e-9
    assert main(["move", str(saved), "--range", "--format", "json"]) == 0  # the saved linkage moves: a crank
    assert json.loads(capsys.readouterr().out)["input"] == "0-1"


def _lengths(linkage: dict):
    from synth.motion import Linkage

    return Linkage.from_dict(linkage).lengths().values()
