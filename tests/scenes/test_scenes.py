"""Scenes: every model under models/ runs and meets its [expect] table; malformed scenes fail cleanly.

The whole directory is run once through the ``mechsynth scene --all`` command (JSON
output) and each scene is then checked as its own test case.
"""

from __future__ import annotations

import argparse
import io
import json
import os
import re
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest

from mechsynth.commands import scene as cli_scene
from synth.errors import InvalidOption, SynthesisError
from mechsynth.scene import KINDS, SceneError, load_scene, run_directory, run_scene

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
SCENE_FILES = sorted(p for p in MODELS.glob("*.toml") if "scene" in tomllib.loads(p.read_text()))

# the worked examples of docs/theory.md (structure and balancing) and the scene that runs each
WORKED_EXAMPLES = {
    "universal table 1": "table1_universal",
    "locomotive drive": "locomotive_drive",
    "64200/0 planetary lever analogue": "planetary_lever_64200",
    "NaCl lattice 12,000/6": "nacl_lattice",
    "3-DOF drive 8310/1": "drive_3dof_8310",
    "trusses": "trusses",
    "limit mechanisms": "limit_mechanism",
    "open robot chain": "open_robot_chain",
    "Bricard / toroidal h=5": "bricard_toroidal",
    "Bricard with h=6": "bricard_classical_h6",
    "Bennett and spherical 4-bars": "bennett_spherical",
    "simplest 6-space loop": "spatial_loop_h6",
    "linear translator": "linear_translator",
    "wedge-lever system": "wedge_lever",
    "four-link wedge mechanism (Fig. 6в)": "wedge_fig6v",
    "24-link planar system": "task1_24_links",
    "single loop with prismatic pairs": "task2_prismatic_loop",
    "two links with an elastic coupling": "task4_elastic_coupling",
    "2-DOF pair loop": "two_dof_pair_loop",
    "8-link chain count": "chains_1dof_8links",
    "8-link multiple joints": "multiple_joints_1dof_8links",
    "Example 1 arm": "arm_base_drives",
    "Example 2 arm": "arm_prismatic",
    "compression spring": "spring_compression",
    "pantograph": "pantograph",
    "sliding link counter-masses": "slider_countermass",
}


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="mechsynth")
    cli_scene.add_commands(parser.add_subparsers(dest="command", required=True))
    return parser


def run_cli(*argv: str) -> tuple[int, str, str]:
    """Run ``mechsynth scene …`` as cli.py will (SynthesisError -> one line, exit 2)."""
    out, err = io.StringIO(), io.StringIO()
    args = _parser().parse_args(["scene", *argv])
    try:
        code = cli_scene.run_scene_command(args, out=out, err=err)
    except SynthesisError as exc:
        err.write(f"mechsynth: {exc}\n")
        code = 2
    return code, out.getvalue(), err.getvalue()


TIMING_EXPECTATION = re.compile(r"^\s*seconds(_below)?\s*=.*$", re.MULTILINE)

# scenes too long for the default suite, each with the smaller case of it that stays there
SLOW_SCENES = {
    "fig6_cylinders": "every 8310/1 drive with three cylinders, 8 096 mechanisms: 30 CPU seconds "
                      "(test_a_smaller_cylinder_scene_equals_a_count_by_roles runs it on the 71/1 drives)",
}


def _without_timing(path: Path, folder: Path) -> Path:
    """A copy of the model at ``path`` in ``folder`` without its timing expectations."""
    copy = folder / path.name
    copy.write_text(TIMING_EXPECTATION.sub("", path.read_text()))
    return copy


@pytest.fixture(scope="module")
def all_models(tmp_path_factory) -> dict:
    """Every model, run from a copy without its timing expectations: speed is measured in
    benchmarks/, never asserted by a test (a loaded machine would fail it)."""
    out_dir = tmp_path_factory.mktemp("drawings")
    models = tmp_path_factory.mktemp("models")
    for path in MODELS.iterdir():
        if path.is_file() and path.stem not in SLOW_SCENES:
            _without_timing(path, models)
    code, out, err = run_cli("--all", str(models), "--format", "json", "--out", str(out_dir))
    report = json.loads(out)
    report["exit"] = code
    report["stderr"] = err
    return report


# ---------------------------------------------------------------------------- every model
def test_all_models_pass_with_zero_exit(all_models):
    assert all_models["errors"] == [], all_models["stderr"]
    assert all_models["ok"] is True
    assert all_models["exit"] == 0
    assert len(all_models["scenes"]) == len(SCENE_FILES) - len(SLOW_SCENES)


def test_non_scene_files_are_skipped_with_a_note(all_models):
    skipped = {Path(s["path"]).name: s["reason"] for s in all_models["skipped"]}
    assert "grid_small.toml" in skipped
    assert "[scene]" in skipped["grid_small.toml"]


@pytest.mark.parametrize("path", [pytest.param(p, marks=pytest.mark.slow) if p.stem in SLOW_SCENES else p
                                  for p in SCENE_FILES], ids=lambda p: p.stem)
def test_scene_meets_every_expectation(path, all_models, tmp_path):
    if path.stem in SLOW_SCENES:
        scene = run_scene(_without_timing(path, tmp_path), out_dir=tmp_path).to_dict()
    else:
        (scene,) = [s for s in all_models["scenes"] if Path(s["path"]).name == path.name]
    not_met = [c["message"] for c in scene["checks"] if c["status"] != "met"]
    assert not not_met and scene["checks"]


def test_a_smaller_cylinder_scene_equals_a_count_by_roles(tmp_path):
    """The Fig. 6 scene on the 71/1 drives (W = 3 and one double joint, as 8310/1): its mechanisms
    are counted again from every drive with three prismatic pairs, each fixed link up to symmetry,
    the pairs sorted by hand into one floating and two swinging cylinders."""
    from synth import ChainQuery, type_synthesis

    expected = 0
    for chain in type_synthesis(ChainQuery(3, code="71/1", prismatic=3), workers=1):
        degree = chain.degrees
        sliding = [j for j, k in zip(chain.joints, chain.kinds) if k == "prismatic"]
        if not all(degree[a] == degree[b] == 2 for a, b in sliding):
            continue  # a cylinder is a barrel and a rod: two binary links
        for frame, *_ in chain.link_orbits:
            pinned = {x for j, k in zip(chain.joints, chain.kinds) if k == "revolute" and frame in j for x in j}
            swinging = sum(1 for a, b in sliding if frame not in (a, b) and {a, b} & pinned)
            floating = sum(1 for a, b in sliding if frame not in (a, b) and not {a, b} & pinned)
            expected += (floating, swinging) == (1, 2)
    assert expected > 10
    text = (MODELS / "fig6_cylinders.toml").read_text().replace("8310/1", "71/1")  # the code, title and text
    text = re.sub(r"mechanisms = 8096", f"mechanisms = {expected}", text)
    (tmp_path / "fig6_cylinders.toml").write_text(text)
    result = run_scene(tmp_path / "fig6_cylinders.toml", out_dir=tmp_path)
    assert result.ok and result.results["mechanisms"].count == expected
    assert result.results["drawing"].items == 12 and (tmp_path / "fig6_cylinders.png").stat().st_size > 1000


@pytest.mark.parametrize("path", SCENE_FILES, ids=lambda p: p.stem)
def test_every_scene_has_expectations_and_a_description(path):
    scene = load_scene(path)
    assert scene.expect, f"{path.name} has no [expect] table"
    assert scene.name == path.stem
    assert scene.description and set(scene.compute) <= set(KINDS)


def test_every_worked_example_has_a_scene():
    names = {p.stem for p in SCENE_FILES}
    missing = {example: name for example, name in WORKED_EXAMPLES.items() if name not in names}
    assert not missing


def test_locomotive_drawing_written(tmp_path):
    result = run_scene(MODELS / "locomotive_drive.toml", out_dir=tmp_path)
    assert result.ok
    svg = tmp_path / "locomotive_drive.svg"
    assert [str(svg)] == list(result.files)
    assert svg.stat().st_size > 1000
    assert result.results["drawing"].items == 25


def test_translator_drawing_shows_its_classes(tmp_path):
    """The linear translator's scene lists the class-V loops of its chain, the translator among
    them, and draws them in the class colours with a key."""
    result = run_scene(MODELS / "linear_translator.toml", out_dir=tmp_path)
    assert result.ok and result.results["chains"].count == 5
    png = tmp_path / "linear_translator.png"
    assert [str(png)] == list(result.files) and png.stat().st_size > 20_000


def test_spring_plot_written(all_models):
    (scene,) = [s for s in all_models["scenes"] if s["name"] == "spring_compression"]
    (png,) = scene["files"]
    assert png.endswith("spring_compression.png") and Path(png).stat().st_size > 10_000


def test_without_out_no_picture_is_written(tmp_path, monkeypatch):
    """``scene --all`` writes nothing into the current directory unless --out says where."""
    monkeypatch.chdir(tmp_path)
    for name in ("locomotive_drive", "spring_compression"):
        result = run_scene(MODELS / f"{name}.toml")
        assert result.ok and result.files == ()
        assert [c.key for c in result.checks if c.status == "skipped"] == (["drawn"] if name == "locomotive_drive" else [])
        (note,) = result.notes
        assert note.endswith(f"skipped: no --out DIR given to write {name}.{'svg' if 'drive' in name else 'png'}")
    code, out, err = run_cli(str(MODELS / "locomotive_drive.toml"))
    assert code == 0 and "not drawn: no --out DIR given to write locomotive_drive.svg" in out
    assert not list(tmp_path.iterdir())


def test_table_output_and_json_of_one_scene():
    code, out, err = run_cli(str(MODELS / "chains_1dof_8links.toml"))
    assert code == 0 and err == ""
    assert "16 chains" in out and "3 of 3 expectations met" in out
    code, out, _ = run_cli(str(MODELS / "nacl_lattice.toml"), "--format", "json")
    doc = json.loads(out)
    assert code == 0 and doc["ok"] and doc["results"]["analysis"]["dof"] == 3


def test_output_is_deterministic():
    a = run_scene(MODELS / "multiple_joints_1dof_8links.toml").to_dict()
    b = run_scene(MODELS / "multiple_joints_1dof_8links.toml").to_dict()
    a.pop("seconds"), b.pop("seconds")
    assert json.dumps(a) == json.dumps(b)


def test_copy_change_a_number_and_rerun(tmp_path):
    """A designer copies a scene, changes the links, and gets the new answer."""
    text = (MODELS / "chains_1dof_8links.toml").read_text()
    text = text.replace("links = 8", "links = 6").replace("count = 16", "count = 2")
    text = text.replace('by_code = { "440/0" = 9, "521/0" = 5, "602/0" = 2 }', 'by_code = { "42/0" = 2 }')
    path = tmp_path / "six.toml"
    path.write_text(text)
    assert run_scene(path).ok


# ---------------------------------------------------------------------------- malformed scenes
GOOD = """\
[scene]
name = "t"
description = "test scene"
compute = ["codes"]

[structure]
dof = 1
loops = 2

[expect]
codes = ["42/0", "51/1", "60/2"]
"""

MALFORMED = {
    # case: (text, words the sentence must contain)
    "syntax error": (GOOD.replace('name = "t"', "name = t t"), ["not valid TOML", "line 2"]),
    "unknown top-level key": (GOOD + "\n[solver]\nx = 1\n", ["'solver'"]),
    "unknown scene key": (GOOD.replace('name = "t"', 'name = "t"\ncolour = "red"'), ["[scene]", "'colour'"]),
    "unknown structure key": (GOOD.replace("loops = 2", "loops = 2\nloopz = 3"), ["[structure]", "'loopz'"]),
    "unknown expect key": (GOOD.replace("[expect]", "[expect]\ncunt = 3"), ["[expect]", "'cunt'"]),
    "unknown compute": (GOOD.replace('["codes"]', '["codez"]'), ["'compute'", "'codez'"]),
    "wrong type dof": (GOOD.replace("dof = 1", 'dof = "one"'), ["[structure]", "'dof'", "whole number", "'one'"]),
    "wrong type loops": (GOOD.replace("loops = 2", "loops = 2.5"), ["'loops'", "2.5"]),
    "wrong type compute": (GOOD.replace('["codes"]', '"codes"'), ["'compute'", "list of strings"]),
    "wrong type expect": (GOOD.replace('codes = ["42/0", "51/1", "60/2"]', "codes = 3"), ["[expect]", "'codes'"]),
    "wrong type table": ("structure = 3\n" + GOOD.replace("[structure]\ndof = 1\nloops = 2\n", ""),
                         ["'structure'", "table"]),
    "bad code in expect": (GOOD.replace('"60/2"', '"61/2"'), ["[expect]", "'codes'", "61/2"]),
    "missing scene": (GOOD.split("[structure]")[1].join(["[structure]", ""]), ["missing section [scene]"]),
    "missing scene name": (GOOD.replace('name = "t"\n', ""), ["[scene]", "'name'"]),
    "missing structure": (GOOD.replace("[structure]\ndof = 1\nloops = 2\n", ""), ["missing section [structure]"]),
    "missing dof": (GOOD.replace("dof = 1\n", ""), ["[structure]", "'dof'"]),
    "missing balance table": ("[scene]\nname = \"t\"\ndescription = \"d\"\ncompute = [\"balance prismatic\"]\n",
                              ["[slider]", "'balance prismatic'"]),
    "expect without its computation": (GOOD.replace("[expect]", "[expect]\ncount = 2"), ["'count'", "compute"]),
    "unused structure key": (GOOD.replace("loops = 2", "loops = 2\nplanar_only = true"), ["'planar_only'", "not used"]),
    "chains in h=1": (GOOD.replace('["codes"]', '["count"]').replace("loops = 2", "loops = 2\nh = 1")
                      .replace('codes = ["42/0", "51/1", "60/2"]', "count = 2"), ["'h'", "2 … 6"]),
    "chains with f": (GOOD.replace('["codes"]', '["count"]').replace("loops = 2", "loops = 2\nf = 1")
                      .replace('codes = ["42/0", "51/1", "60/2"]', "count = 2"), ["'f'", "one-DOF pairs"]),
    "impossible parameters": (GOOD.replace("loops = 2", "loops = 2\nrequire = [\"2=x\"]"), ["[structure]"]),
    "balance error": ("[scene]\nname = \"t\"\ndescription = \"d\"\ncompute = [\"balance prismatic\"]\n"
                      "[slider]\nmass = -2.0\ncounter_mass = 2.0\nq_max = 0.5\n", ["mass"]),
    "plot without balance": (GOOD.replace('["codes"]', '["codes", "plot"]'), ["'plot'", "balance"]),
    "bad drawing file name": (GOOD.replace('["codes"]', '["count", "drawing"]').replace("[expect]", "[drawing]\nout = \"a/b.gif\"\n[expect]")
                              .replace('codes = ["42/0", "51/1", "60/2"]', "count = 2"), ["[drawing]", "'out'", "a/b.gif"]),
    # a folder in a name with the right suffix: the sentence said the name must end in .svg, and it did
    "drawing file in a folder": (GOOD.replace('["codes"]', '["count", "drawing"]').replace("[expect]", "[drawing]\nout = \"/proc/b.svg\"\n[expect]")
                                 .replace('codes = ["42/0", "51/1", "60/2"]', "count = 2"), ["[drawing]", "'out'", "without a folder"]),
    "dof is true": (GOOD.replace("dof = 1", "dof = true"), ["[structure] key 'dof' must be a whole number ≥ 0, not true."]),
    "empty range": (GOOD.replace("loops = 2", 'loops = "5..2"'), ["'loops'", "empty range '5..2'"]),
    "empty compute": (GOOD.replace('["codes"]', "[]"), ["'compute'", "empty"]),
    "compute twice": (GOOD.replace('["codes"]', '["codes", "codes"]'), ["'compute'", "twice"]),
    "rel_tol out of range": (GOOD.replace('name = "t"', 'name = "t"\nrel_tol = 2'), ["'rel_tol'", "between 0 and 1"]),
    "v triple": (GOOD.replace("loops = 2", "loops = 2\nv = [1, 2, 3]"), ["'v'", "pair [A, B]", "[1, 2, 3]"]),
    "bad code in structure": (GOOD.replace('["codes"]', '["analysis"]').replace("dof = 1\nloops = 2", 'code = "63x1/0"')
                              .replace('codes = ["42/0", "51/1", "60/2"]', "dof = 1"), ["[structure]", "'code'", "63x1/0"]),
    "negative link count": (GOOD.replace('["codes"]', '["analysis"]').replace("dof = 1\nloops = 2", "counts = { 2 = -1 }")
                            .replace('codes = ["42/0", "51/1", "60/2"]', "dof = 1"), ["'counts'", "whole numbers"]),
    "below form of an exact key": (GOOD.replace("[expect]", "[expect]\ncode_count_below = 4"), ["no upper-bound form"]),
    "below bound not a number": ("[scene]\nname = \"t\"\ndescription = \"d\"\ncompute = [\"balance prismatic\"]\n"
                                 "[slider]\nmass = 2.0\ncounter_mass = 2.0\nq_max = 0.5\n[expect]\nC_min_below = \"x\"\n",
                                 ["[expect] key 'C_min_below' must be a finite number, not 'x'"]),
    "drawing table without drawing": (GOOD.replace("[expect]", "[drawing]\nlimit = 3\n[expect]"), ["[drawing]", "'drawing'"]),
    "closed-form driver not written as links": ((MODELS / "motion_triad.toml").read_text().replace(
        'driver = "0-2"', 'driver = "0=x"'), ["[closed_form] driver names joint '0=x': write a joint by its links"]),
    "closed-form driver no joint": ((MODELS / "motion_triad.toml").read_text().replace(
        'driver = "0-2"', 'driver = "0-5"'),
        ["[closed_form] driver names joint '0-5', which is not a joint of the chain"]),
    # a truss on a frame (W = 0) does not move: 'mechanisms --input-link' refuses it, and so does a scene
    "input link of trusses": (GOOD.replace('["codes"]', '["mechanisms"]').replace("dof = 1\nloops = 2",
                              "dof = 0\nlinks = 5\ninput_link = true").replace('codes = ["42/0", "51/1", "60/2"]',
                                                                         "mechanisms = 7"),
                              ["the chains of [structure] have W = 0 by the count", "a truss is a statically "
                               "determinate structure", "the key 'input_link' has no link to drive"]),
    # a chain given by hand is one chain, as 'mechanisms --chain C' takes it: a query's keys and another W contradict
    # it, a structure (W < 0) has no mechanisms, and a chain whose count misleads drives nothing by its count
    "chain with a query key": (GOOD.replace('["codes"]', '["chains"]').replace(
        "dof = 1\nloops = 2", 'links = 6\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] key 'links' selects the chains of a query and contradicts 'chain' (the one chain given) for "
         "chains."]),
    "bases on an unreadable chain": (GOOD.replace('["codes"]', '["chains"]').replace(
        "loops = 2", 'loop_classes = { 3 = 1, 4 = 1 }\nchain = "0-1 1-x"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"), ["[structure] key 'chain': cannot read joint '1-x'"]),
    # a refusal names the computations the scene asks for ('chains, mechanisms and drawings' for a count alone)
    "chain with a query key counted": (GOOD.replace('["codes"]', '["count"]').replace(
        "dof = 1\nloops = 2", 'links = 6\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] key 'links' selects the chains of a query and contradicts 'chain' (the one chain given) for "
         "the count of chains."]),
    # every base on a chain has the W its loop classes give it: another dof contradicts them, as it does one chain
    "bases of another W": (GOOD.replace('["codes"]', '["chains", "drawing"]').replace(
        "loops = 2", 'loop_classes = { 3 = 1, 4 = 1 }\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] key 'dof' asks for W = 1 and its bases have W = 0 by the count: for chains and drawings the "
         "chain is taken as it is."]),
    "chain unreadable": (GOOD.replace('["codes"]', '["chains"]').replace("dof = 1\nloops = 2", 'chain = "0-1 1-x"')
                         .replace('codes = ["42/0", "51/1", "60/2"]', "count = 1"),
                         ["[structure] key 'chain': cannot read joint '1-x'"]),
    "chain of another W": (GOOD.replace('["codes"]', '["mechanisms"]').replace(
        "loops = 2", 'chain = "0-1 1-2 2-3 3-0 0-4 4-5 5-6 6-1"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "mechanisms = 7"),
        ["key 'dof' asks for W = 1 and the chain has W = 2 by the count: for mechanisms the chain is taken as it is "
         "(its analysis says how to mend it)."]),
    "mechanisms of a structure": (GOOD.replace('["codes"]', '["mechanisms"]').replace(
        "dof = 1\nloops = 2", 'chain = "0-1 1-2 2-3 3-0 1-3"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "mechanisms = 1"),
        ["the chain 0-1 0-3 1-2 1-3 2-3 is a structure, not a mechanism's chain: W = -1 by the count"]),
    "input link of a degenerate chain drawn": (GOOD.replace('["codes"]', '["drawing"]').replace(
        "dof = 1\nloops = 2", 'chain = "0-1 1-2 2-0 2-3 3-4 4-5 5-0"\ninput_link = true').replace(
        "[expect]", "[drawing]\nmechanisms = true\n\n[expect]").replace(
        'codes = ["42/0", "51/1", "60/2"]', "drawn = 4"),
        ["the chain 0-1 0-2 0-5 1-2 2-3 3-4 4-5 has W = 1 by the count, degenerate: a sub-chain is rigid",
         "so the key 'input_link' would name links that cannot drive it"]),
    # a key that every computation asked leaves unused beside the others is refused, naming the computation and
    # both keys: the analysis of a chain takes no loop_classes (as 'analyze C --loop-classes' refuses them), the
    # base is written in the chain's text
    "loop classes beside a chain analysed": (GOOD.replace('["codes"]', '["analysis"]').replace(
        "loops = 2", 'loop_classes = { 3 = 1, 4 = 1 }\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "dof = 1"),
        ["[structure] for the analysis, key 'loop_classes' beside 'chain' does not apply to a chain (it describes "
         "codes and counts): write a base of a higher class in the chain's text after '|' ('… | h5: 0 1 2 3'"]),
    "v beside a code analysed": (GOOD.replace('["codes"]', '["analysis"]').replace(
        "dof = 1\nloops = 2", 'code = "42/0"\nv = 0').replace('codes = ["42/0", "51/1", "60/2"]', "dof = 1"),
        ["[structure] for the analysis, key 'v' beside 'code' goes with explicit counts: a code carries its own v."]),
    "loops beside links counted": (GOOD.replace('["codes"]', '["count"]').replace(
        "loops = 2", "loops = 2\nlinks = 6").replace('codes = ["42/0", "51/1", "60/2"]', "count = 2"),
        ["[structure] for the count of chains, key 'loops' is fixed by 'links': give one of them."]),
    "query key beside bases": (GOOD.replace('["codes"]', '["count"]').replace("dof = 1\nloops = 2",
        'dof = 0\nloop_classes = { 3 = 1, 4 = 1 }\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"\nplanar_only = true').replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] for the count of chains, key 'planar_only' selects the chains of a query, and 'chain' with "
         "'loop_classes' lays every base on the one chain given."]),
    "idle joints beside loop classes": (GOOD.replace('["codes"]', '["count"]').replace(
        "loops = 2", "loop_classes = { 3 = 1, 4 = 1 }\nlinks = 6\nidle_joints = true").replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] for the count of chains, key 'idle_joints' goes with 'prismatic', which 'loop_classes' does "
         "not take."]),
    "input link on a sheet of chains": (GOOD.replace('["codes"]', '["drawing"]').replace(
        "loops = 2", "links = 6\ninput_link = true").replace('codes = ["42/0", "51/1", "60/2"]', "drawn = 2"),
        ["[structure] for drawings, key 'input_link' is for mechanisms and [drawing] draws the chains "
         "(mechanisms = true draws the mechanisms)."]),
    "h beside loop classes": (GOOD.replace("loops = 2", "loop_classes = { 3 = 1, 4 = 1 }\nh = 4"),
        ["[structure] for the codes, keys 'h' and 'loop_classes' contradict each other: the classes give each "
         "loop's motion space (the lower class is the chain's h)."]),
    # any h, 3 too, beside loop_classes, for every computation (as 'chains --loop-classes … --h 3' refuses it): the
    # chains took h = 3 beside them, where the classes give the lower class's h
    "h = 3 beside loop classes counted": (GOOD.replace('["codes"]', '["count"]').replace(
        "loops = 2", "loop_classes = { 3 = 1, 4 = 1 }\nh = 3").replace('codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] for the count of chains, keys 'h' and 'loop_classes' contradict each other"]),
    "h = 3 beside bases drawn": (GOOD.replace('["codes"]', '["chains", "drawing"]').replace("dof = 1\nloops = 2",
        'dof = 0\nh = 3\nloop_classes = { 3 = 1, 4 = 1 }\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"').replace(
        'codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] for chains and drawings, keys 'h' and 'loop_classes' contradict each other"]),
    # where loop_classes serve the chains, the analysis beside them takes the chain's classes from its text
    "chain analysed in other classes than its bases": (GOOD.replace('["codes"]', '["analysis", "count"]').replace(
        "dof = 1\nloops = 2", 'dof = 0\nloop_classes = { 3 = 1, 4 = 1 }\nchain = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"')
        .replace('codes = ["42/0", "51/1", "60/2"]', "count = 1"),
        ["[structure] for the analysis, 'chain' has loop classes {3: 2} and 'loop_classes' gives {3: 1, 4: 1}: the "
         "analysis takes a chain's classes from its text, a base written after '|'"]),
    "balance unknown key": ("[scene]\nname = \"t\"\ndescription = \"d\"\ncompute = [\"balance prismatic\"]\n"
                            "[slider]\nmass = 2.0\ncounter_mass = 2.0\nq_max = 0.5\nmas = 3\n", ["'mas'"]),
}


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_scene_gives_one_sentence(case, tmp_path):
    text, words = MALFORMED[case]
    path = tmp_path / "bad_scene.toml"
    path.write_text(text)
    with pytest.raises(SceneError) as info:
        run_scene(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(str(path)), message
    assert message.endswith(".") or message.endswith(")"), message
    for word in words:
        assert word in message, (word, message)
    # the command prints the same sentence on stderr, nothing on stdout, exit 2, no traceback
    code, out, err = run_cli(str(path))
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "Traceback" not in err and str(path) in err


@pytest.mark.parametrize("chain,classes", [("0-1 1-2 2-3 3-0 0-4 4-5 5-1", {3: 1, 4: 1}),
                                           ("0-1 1-2 2-3 3-0 0-4 4-5 5-2", {3: 1, 4: 1}),
                                           ("0-1-6 1-2-7 2-3-8 3-4-9 4-5-10 5-0-11 6-12 8-12 10-12 7-13 9-13 11-13",
                                            {3: 4, 5: 1})])
def test_a_chain_with_loop_classes_takes_the_w_of_its_bases(tmp_path, chain, classes):
    """A [structure] chain with loop_classes lists every base on it; its dof was never compared with their W. The
    W it names is the one every base listed has by Chain.dof in its motion spaces: that dof lists them, one more
    is refused naming it."""
    from dataclasses import replace

    from synth import Chain, class_variants

    (h, _), (x, k_x) = sorted(classes.items())
    bases = class_variants(replace(Chain.parse(chain), h=h), x, k_x)
    (w,) = {base.dof for base in bases}
    table = ", ".join(f"{c} = {k}" for c, k in classes.items())
    path = tmp_path / "bases.toml"
    for dof in (w, w + 1):
        path.write_text(GOOD.replace('["codes"]', '["count"]').replace("dof = 1\nloops = 2", f"dof = {dof}\n"
                        f'loop_classes = {{ {table} }}\nchain = "{chain}"').replace(
                        'codes = ["42/0", "51/1", "60/2"]', f"count = {len(bases)}"))
        if dof == w:
            assert run_scene(path).ok
        else:
            with pytest.raises(SceneError, match=f"asks for W = {w + 1} and its bases have W = {w} by the count: "
                                                 "for the count of chains the chain"):
                run_scene(path)


def test_impossible_expectation_is_a_failed_check_with_both_values(tmp_path):
    path = tmp_path / "wrong.toml"
    path.write_text(GOOD.replace('codes = ["42/0", "51/1", "60/2"]', 'codes = ["42/0", "60/2"]\ncode_count = 4'))
    result = run_scene(path)
    assert not result.ok
    (codes, count) = result.checks
    assert codes.status == "failed" and "unexpected 51/1" in codes.message and str(path) in codes.message
    assert count.status == "failed" and "4" in count.message and "3" in count.message
    assert "\n" not in count.message
    code, out, _ = run_cli(str(path))
    assert code == 1 and "FAIL" in out and "0 of 2 expectations met" in out


def test_chain_count_contradicted(tmp_path):
    path = tmp_path / "count.toml"
    path.write_text((MODELS / "chains_1dof_8links.toml").read_text().replace("count = 16", "count = 17"))
    (check,) = [c for c in run_scene(path).checks if c.key == "count"]
    assert check.status == "failed" and check.expected == 17 and check.actual == 16
    assert "count = 17" in check.message and "16" in check.message


def test_directory_with_malformed_and_failing_scenes(tmp_path):
    (tmp_path / "a_good.toml").write_text(GOOD)
    (tmp_path / "b_bad.toml").write_text(GOOD.replace("dof = 1", "dof = -1"))
    (tmp_path / "c_grid.toml").write_text('name = "grid"\ndof = "1..3"\n')
    code, out, err = run_cli("--all", str(tmp_path))
    assert code == 2  # the malformed scene is an error, and the good one still ran
    assert "PASS  t" in out and "1 of 1 scenes passed, 1 malformed" in out and "b_bad.toml" not in out
    assert err.count("\n") == 1 and err.startswith("mechsynth: ") and "b_bad.toml" in err and "'dof'" in err
    assert "skip" in out and "c_grid.toml" in out
    (tmp_path / "b_bad.toml").write_text(GOOD.replace('"60/2"]', '"60/2", "52/0"]'))
    code, out, _ = run_cli("--all", str(tmp_path))
    assert code == 1 and "FAIL" in out and "missing" in out
    result = run_directory(tmp_path)
    assert [Path(p).name for p, _ in result.skipped] == ["c_grid.toml"]


def test_command_line_mistakes():
    with pytest.raises(InvalidOption):
        run_cli_args = _parser().parse_args(["scene"])
        cli_scene.run_scene_command(run_cli_args)
    code, _, err = run_cli(str(MODELS / "no_such_scene.toml"))
    assert code == 2 and "no such scene file" in err
    code, _, err = run_cli("--all", str(MODELS / "no_such_dir"))
    assert code == 2 and "not a directory" in err


@pytest.mark.parametrize("folder, words", [("/proc/figs", "cannot write files into /proc/figs"),
                                           ("{d}/a_good.toml", "is a file")])
def test_unwritable_out_folder_is_refused_before_any_scene_runs(tmp_path, capsys, folder, words):
    from mechsynth.cli import main

    (tmp_path / "a_good.toml").write_text(GOOD)
    folder = folder.format(d=tmp_path)
    assert main(["scene", "--all", str(tmp_path), "--out", folder]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and words in err and "Traceback" not in err


def test_out_folder_is_checked_without_being_left_behind(tmp_path):
    from mechsynth._argtypes import output_folder

    new = tmp_path / "new"
    assert output_folder(str(new)) == str(new) and not new.exists()
    assert output_folder(str(tmp_path)) == str(tmp_path) and list(tmp_path.iterdir()) == []


def test_a_linkage_saved_as_json_is_told_apart_from_a_scene(tmp_path):
    path = tmp_path / "found.json"
    path.write_text('{"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"], "points": {}}')
    with pytest.raises(SceneError) as info:
        run_scene(path)
    assert str(info.value) == (f"{path}: a scene file is TOML, and this is JSON (a linkage saved as .json moves with "
                               "'mechsynth move'; 'move' or 'dimension' with --save NAME.toml writes one as a scene).")
    code, out, err = run_cli(str(path))
    assert code == 2 and out == "" and err.count("\n") == 1


def test_grid_file_alone_is_not_a_scene():
    with pytest.raises(SceneError, match=r"grid_small\.toml: missing section \[scene\]"):
        run_scene(MODELS / "grid_small.toml")


# ---------------------------------------------------------------------------- lazy imports
_PROBE = textwrap.dedent("""
    import json, sys
    root = sys.argv[1]
    sys.path.insert(0, root)
    from mechsynth.scene import run_scene
    assert run_scene(root + "/models/" + sys.argv[2]).ok
    mods = sorted(m for m in sys.modules if m.startswith(("synth", "ortools", "pynauty", "networkx", "balance")))
    print(json.dumps(mods))
""")


def _modules_after(scene: str) -> set[str]:
    env = dict(os.environ, MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, "-c", _PROBE, str(ROOT), scene], capture_output=True, text=True,
                         check=True, env=env, cwd=ROOT)
    return set(json.loads(out.stdout))


def test_balancing_scene_imports_no_synth_solver():
    mods = _modules_after("slider_countermass.toml")
    assert "balance.problems" in mods
    heavy = {m for m in mods if m.startswith(("ortools", "pynauty", "networkx", "synth._")) and m != "synth._lazy"}
    assert not heavy, heavy
    assert {m for m in mods if m.startswith("synth")} <= {"synth", "synth._lazy", "synth.display", "synth.errors",
                                                          "synth.schema"}


def test_codes_only_scene_builds_no_graph_model():
    mods = _modules_after("table1_universal.toml")
    assert "synth.synthesis.number_synthesis" in mods
    assert not {"synth.synthesis.stage_a", "synth.synthesis.stage_b", "synth.synthesis.type_synthesis", "synth.structure.chain", "pynauty", "balance"} & mods


def test_analysis_scene_needs_no_solver():
    mods = _modules_after("task1_24_links.toml")
    assert "synth.analysis.codes" in mods
    solvers = ("ortools", "pynauty", "synth.synthesis._cpsat", "synth.synthesis.number_synthesis", "synth.synthesis.stage_a", "synth.synthesis.stage_b", "synth.synthesis.type_synthesis")
    assert not {m for m in mods if m.startswith((*solvers, "balance"))}


def test_import_synth_loads_no_solver():
    """``import synth`` loads its names lazily: no CP-SAT, nauty or graph model until one is used."""
    loaded = subprocess.run([sys.executable, "-c", "import sys, synth; print(sorted(m for m in sys.modules "
                             "if m.startswith(('synth.', 'ortools', 'pynauty'))))"],
                            capture_output=True, text=True, check=True, cwd=ROOT).stdout.strip()
    assert loaded == "['synth._lazy', 'synth.display', 'synth.errors']"


# ---------------------------------------------------------------------------- through mechsynth
def test_through_the_mechsynth_command(tmp_path, capsys):
    from mechsynth import cli

    assert cli.main(["scene", str(MODELS / "wedge_lever.toml")]) == 0
    assert "8 of 8 expectations met" in capsys.readouterr().out
    bad = tmp_path / "bad.toml"
    bad.write_text(GOOD.replace("dof = 1", "dof = true"))
    assert cli.main(["scene", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsynth: ") and "'dof'" in err and err.count("\n") == 1
    assert cli.main(["scene", str(bad), "--all", str(tmp_path)]) == 2
    assert "not both" in capsys.readouterr().err


# ---------------------------------------------------------------------------- typed results
@pytest.mark.parametrize("scene, kinds", [
    ("chains_1dof_8links.toml", {"chains": "ChainListing"}),
    ("mechanisms_1dof_8links.toml", {"count": "ChainCount", "mechanisms": "MechanismCount"}),
    ("table1_universal.toml", {"codes": "CodeList"}),
    ("task1_24_links.toml", {"analysis": "CodeAnalysis"}),
    ("planetary_lever_64200.toml", {"codes": "CodeList", "analysis": "CodeAnalysis", "planetary": "PlanetaryLever"}),
    ("task2_prismatic_loop.toml", {"analysis": "CodeAnalysis", "prismatic": "Variants"}),
    ("gears_ratio_design.toml", {"gear train": "TrainAnalysis"}),
    ("gears_simpson.toml", {"gear train": "TrainAnalysis", "gear atlas": "GearCensus"}),
    ("motion_four_bar.toml", {"motion": "MotionSummary", "closed form": "DyadCheck"}),
    ("motion_slider_crank.toml", {"motion": "MotionSummary", "closed form": "SliderCrankCheck"}),
    ("motion_planetary_willis.toml", {"motion": "MotionSummary", "closed form": "WillisCheck"}),
    ("arm_prismatic.toml", {"balance arm": "Derived"}),
    ("spring_sine.toml", {"balance spring": "SpringDesign", "plot": "Figures"}),
    ("pantograph.toml", {"balance pantograph": "PantographBalance"}),
    ("balance_four_bar.toml", {"balance linkage": "LinkageBalance"}),
])
def test_every_computation_gives_a_typed_result_printed_as_its_row(scene, kinds):
    """Each computation (structure, gears, motion, balancing) returns a frozen Row; the scene's output is its row, and nothing
    else turns it into one (the expectations are checked on the same rows)."""
    import dataclasses

    from mechbase import Row, as_row

    result = run_scene(ROOT / "models" / scene)
    assert result.ok
    assert {name: type(r).__name__ for name, r in result.results.items()} == kinds
    for name, typed in result.results.items():
        assert isinstance(typed, Row) and dataclasses.is_dataclass(typed)
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(typed, dataclasses.fields(typed)[0].name, None)
        assert result.rows[name] == as_row(typed) == result.to_dict()["results"][name]


def test_a_scene_names_trusses_as_the_command_line_does(tmp_path):
    """A scene of W = 0 reported "7 mechanisms" where 'mechsynth mechanisms' says trusses on a frame."""
    path = tmp_path / "trusses.toml"
    path.write_text(GOOD.replace('["codes"]', '["mechanisms"]').replace("dof = 1\nloops = 2", "dof = 0\nlinks = 5")
                    .replace('codes = ["42/0", "51/1", "60/2"]', "mechanisms = 7"))
    result = run_scene(path)
    assert result.ok and result.results["mechanisms"].trusses == 7
    code, out, _ = run_cli(str(path))
    assert code == 0 and "7 trusses on a frame (W = 0: statically determinate, nothing moves): 32/0: 5, 401/0: 2" in out
    code, out, _ = run_cli(str(MODELS / "mechanisms_1dof_8links.toml"))
    assert code == 0 and "71 mechanisms: 440/0: 35" in out


def _chain_scene(tmp_path, chain: str, mechanisms: int, extra: str = "") -> Path:
    """A scene of the mechanisms of one chain given by hand, expecting that many."""
    path = tmp_path / "one_chain.toml"
    path.write_text(GOOD.replace('["codes"]', '["mechanisms"]').replace("dof = 1\nloops = 2", f'chain = "{chain}"{extra}')
                    .replace('codes = ["42/0", "51/1", "60/2"]', f"mechanisms = {mechanisms}"))
    return path


def _mechanisms_cli(capsys, *argv: str) -> tuple[int, str, str]:
    """``mechsynth mechanisms …`` run as the console script runs it: its exit status, stdout and stderr."""
    from mechsynth.cli import main

    code = main(["mechanisms", *argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("chain, words, by_code, defect", [
    # a braced four-bar beside a five-link loop: W = 1 by the count, the links move with W = 2
    ("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-7 7-2", "4 chains on a frame, not mechanisms of W = 1: W = 1 by the count, "
     "but a sub-chain is over-constrained (W(S) = -1) and the links move with W = 2", "440/0: 4",
     {"dof": 1, "moves": 2, "kind": "over-constrained sub-chain", "worst_mobility": -1}),
    # a four-bar whose frame is a triangle: a rigid sub-chain, one link in effect
    ("0-1 1-2 2-0 2-3 3-4 4-5 5-0", "4 degenerate mechanisms: W = 1, but a sub-chain is rigid (W(S) = 0)", "42/0: 4",
     {"dof": 1, "moves": 1, "kind": "rigid sub-chain", "worst_mobility": 0}),
])
def test_a_scene_names_a_chain_whose_count_misleads_as_the_command_line_does(chain, words, by_code, defect, tmp_path,
                                                                             capsys):
    """A scene of the mechanisms of a chain given by hand said nothing of a count that misleads (polish19)."""
    from synth import Chain

    path = _chain_scene(tmp_path, chain, 4)
    result = run_scene(path)
    assert result.ok and result.rows["mechanisms"]["count_defect"] == defect
    code, out, _ = run_cli(str(path))
    said = out.split("mechanisms  ", 1)[1].splitlines()
    assert code == 0 and said[0].startswith(words) and said[1].strip() == f"by code: {by_code}"
    code, out, _ = _mechanisms_cli(capsys, "--chain", chain)
    assert code == 0 and out.splitlines()[-1] == said[0]  # the command's last line, word for word
    # input_link = true refused before any work, in the command's sentence
    path = _chain_scene(tmp_path, chain, 4, "\ninput_link = true")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    code, _, err = _mechanisms_cli(capsys, "--chain", chain, "--input-link")
    assert code == 2 and err.startswith(f"mechsynth: the chain {Chain.parse(chain).compact()} has W = 1 by the count, ")
    assert str(info.value) == f"{path}: {err.removeprefix('mechsynth: ').strip()}.".replace(
        "--input-link", "the key 'input_link'")


def test_a_sound_chain_given_by_hand_is_listed_as_the_command_line_lists_it(tmp_path, capsys):
    """Watt's chain: its two mechanisms, and with input_link its four, as 'mechanisms --chain C' lists them."""
    watt = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"
    for extra, argv, count in (("", [], 2), ("\ninput_link = true", ["--input-link"], 4)):
        path = _chain_scene(tmp_path, watt, count, extra)
        result = run_scene(path)
        assert result.ok and "count_defect" not in result.rows["mechanisms"]
        code, out, _ = run_cli(str(path))
        _, cli, _ = _mechanisms_cli(capsys, "--chain", watt, *argv)
        assert cli.splitlines()[-1] == f"{count} mechanisms"
        assert code == 0 and f"mechanisms  {count} mechanisms: 42/0: {count}\n" in out
