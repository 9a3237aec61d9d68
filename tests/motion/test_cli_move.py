"""`mechsynth move` end to end: rows, range, pictures and animations, and bad inputs (one sentence,
exit 2, nothing written or changed)."""

from __future__ import annotations

import csv
import io
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from mechsynth.cli import main
from tests.load import allowed_seconds

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = ROOT / "models" / "motion_four_bar.toml"
SLIDER = ROOT / "models" / "motion_slider_crank.toml"


def _run(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def test_rows_of_a_crank_rocker_follow_the_closed_form(capsys):
    """csv rows: input from the pose's 90° through a turn; the coupler pin B on both circles."""
    code, out, err = _run(capsys, "move", FOUR_BAR, "--steps", "37", "--format", "csv")
    assert code == 0 and err == ""
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 37
    phi = np.array([float(r["input"]) for r in rows])
    assert phi[0] == pytest.approx(math.pi / 2) and phi[-1] - phi[0] == pytest.approx(2 * math.pi)
    a = np.array([[float(r["1-2.x"]), float(r["1-2.y"])] for r in rows])
    b = np.array([[float(r["2-3.x"]), float(r["2-3.y"])] for r in rows])
    assert np.allclose(a, np.c_[np.cos(phi), np.sin(phi)], atol=1e-12)
    assert np.allclose(np.hypot(*(b - a).T), 3.5, atol=1e-12)
    assert np.allclose(np.hypot(*(b - [4, 0]).T), 3.0, atol=1e-12)
    assert {"P.x", "P.y"} <= set(rows[0])


def test_velocities_match_central_differences(capsys):
    code, out, _ = _run(capsys, "move", FOUR_BAR, "--steps", "721", "--velocities", "--accelerations",
                        "--format", "jsonl")
    assert code == 0
    rows = [json.loads(line) for line in out.splitlines()]
    h = rows[1]["input"] - rows[0]["input"]
    for s in (100, 400, 650):
        for axis in "xy":
            diff = (rows[s + 1][f"2-3.{axis}"] - rows[s - 1][f"2-3.{axis}"]) / (2 * h)
            assert rows[s][f"2-3.v{axis}"] == pytest.approx(diff, rel=1e-3, abs=1e-6)
            second = (rows[s + 1][f"2-3.{axis}"] - 2 * rows[s][f"2-3.{axis}"] + rows[s - 1][f"2-3.{axis}"]) / h**2
            assert rows[s][f"2-3.a{axis}"] == pytest.approx(second, rel=1e-3, abs=1e-5)


def test_every_format_gives_the_same_rows(capsys):
    outs = {fmt: _run(capsys, "move", SLIDER, "--steps", "5", "--format", fmt)[1] for fmt in ("jsonl", "json", "csv")}
    from_jsonl = [json.loads(line) for line in outs["jsonl"].splitlines()]
    assert json.loads(outs["json"]) == from_jsonl
    from_csv = list(csv.DictReader(io.StringIO(outs["csv"])))
    assert [float(r["2-3.x"]) for r in from_csv] == [r["2-3.x"] for r in from_jsonl]
    code, table, _ = _run(capsys, "move", SLIDER, "--steps", "5")
    assert code == 0 and table.splitlines()[0].split()[:2] == ["step", "input"] and len(table.splitlines()) == 7
    # a table is read by eye: six significant digits ('4.499999999999999' and '-1.2246467991473532e-16' were
    # printed whole), the csv and JSON keep every digit
    header, _, *lines = table.splitlines()
    shown = [dict(zip(header.split(), line.split())) for line in lines]
    assert [s["2-3.x"] for s in shown] == [f"{r['2-3.x']:.6g}" for r in from_jsonl]
    assert any(len(r["2-3.x"]) > 8 for r in from_csv)


def test_range_of_the_four_bar(capsys):
    code, out, _ = _run(capsys, "move", FOUR_BAR, "--range", "--format", "json")
    doc = json.loads(out)
    assert code == 0 and doc["full_rotation"] is True and doc["limits"] is None
    assert doc["grashof"].startswith("crank-rocker")
    worst = min(min(t["min"], math.pi - t["max"]) for t in doc["transmission"].values())
    assert math.degrees(worst) == pytest.approx(54.31466528734795, abs=1e-6)
    x0, y0, x1, y1 = doc["extent"]["P"]
    assert x0 < x1 and y0 < y1
    code, table, _ = _run(capsys, "move", FOUR_BAR, "--range")
    assert code == 0 and "turns fully" in table and "Grashof" in table and "curve P" in table


def test_range_says_each_dyads_worst_transmission_angle(capsys, tmp_path):
    # min and max alone left the designer's figure, how far the dyad stays from a dead position, to be worked out:
    # crank 1.5, coupler 2.2, rocker 2.5, frame 3 (a crank-rocker): μ from acos(8.84/11) = 36.53° (crank pin
    # nearest the rocker's pivot, |A O4| = 1.5) to acos(-9.16/11) = 146.38° (|A O4| = 4.5): the worst is 180 − 146.38
    from .helpers import four_bar

    path = tmp_path / "wide.json"
    path.write_text(four_bar(1.5, 2.2, 2.5, 3).to_json())
    code, out, _ = _run(capsys, "move", path, "--range", "--format", "json")
    t = json.loads(out)["transmission"]["links 2, 3"]
    low, high = math.acos((2.2 ** 2 + 2.5 ** 2 - 1.5 ** 2) / 11), math.acos((2.2 ** 2 + 2.5 ** 2 - 4.5 ** 2) / 11)
    assert code == 0 and (t["min"], t["max"]) == pytest.approx((low, high), abs=1e-9)
    assert t["worst"] == pytest.approx(math.pi - high, abs=1e-9)
    code, table, _ = _run(capsys, "move", path, "--range")
    assert f"; worst {math.degrees(math.pi - high):.4g}°" in table


def test_a_rocker_reports_true_limits(capsys, tmp_path):
    """The triad scene's linkage rocks: its limits are dead positions, and a sweep ends at them."""
    triad = ROOT / "models" / "motion_triad.toml"
    code, out, _ = _run(capsys, "move", triad, "--range", "--format", "json")
    doc = json.loads(out)
    assert code == 0 and doc["full_rotation"] is False and doc["limits"][0] < doc["limits"][1]
    assert len(doc["dead_positions"]) == 2


def test_pictures_and_animations_are_written(capsys, tmp_path):
    png, gif, svg = tmp_path / "c.png", tmp_path / "m.gif", tmp_path / "m.svg"
    code, out, err = _run(capsys, "move", FOUR_BAR, "--out", png, "--animate", gif, "--frames", "12")
    assert code == 0 and out == "" and "12 frames" in err
    from PIL import Image

    with Image.open(png) as im:
        assert im.size[0] >= 300
    with Image.open(gif) as im:
        assert im.n_frames == 12
        im.seek(0)
        first = np.asarray(im.convert("RGB")).copy()
        im.seek(6)
        assert (np.asarray(im.convert("RGB")) != first).any()  # the frames differ: it moves
    code, _, _ = _run(capsys, "move", FOUR_BAR, "--animate", svg)
    text = svg.read_text()
    assert code == 0 and text.count("<animate ") > 10 and 'repeatCount="indefinite"' in text


def test_a_chain_dimensioned_by_its_drawing_moves_and_can_be_saved(capsys, tmp_path):
    saved = tmp_path / "watt.json"
    code, _, err = _run(capsys, "move", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--frame", "0", "--save", saved)
    assert code == 0
    linkage = json.loads(saved.read_text())
    assert linkage["chain"] == "0-1 0-3 0-4 1-2 1-5 2-3 4-5" and linkage["frame"] == 0
    code, out, _ = _run(capsys, "move", saved, "--steps", "3", "--format", "jsonl")
    assert code == 0 and len(out.splitlines()) == 3


def test_a_linkage_saved_as_toml_is_a_scene_that_moves_and_equals_the_json(capsys, tmp_path):
    """move --save took .json only: a .toml is a scene whose [linkage] table is the linkage (note included)."""
    watt = ["move", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--frame", "2", "--save"]
    as_json, as_toml = tmp_path / "watt.json", tmp_path / "watt.toml"
    assert _run(capsys, *watt, as_json)[0] == 0 and _run(capsys, *watt, as_toml)[0] == 0
    import tomllib

    scene = tomllib.loads(as_toml.read_text())
    assert scene["linkage"] == json.loads(as_json.read_text()) and scene["scene"]["compute"] == ["motion"]
    assert scene["linkage"]["note"].endswith("at least 32°")
    rows = [_run(capsys, "move", f, "--steps", "5", "--format", "csv") for f in (as_json, as_toml)]
    assert rows[0] == rows[1] and rows[0][0] == 0 and len(rows[0][1].splitlines()) == 6
    code, out, _ = _run(capsys, "scene", as_toml)
    assert code == 0 and "input turns fully, worst transmission 32.19°" in out


def test_a_sweep_into_a_dead_position_stops_there_and_says_so(capsys):
    code, out, err = _run(capsys, "move", ROOT / "models" / "motion_triad.toml", "--start", "130", "--stop", "200",
                          "--steps", "50", "--format", "jsonl")
    rows = [json.loads(line) for line in out.splitlines()]
    assert code == 0 and err.count("stop") == 1 and "dead position" in err and 0 < len(rows) < 50
    assert math.degrees(rows[-1]["input"]) <= 161.1


BAD = [
    (["move"], "give one mechanism"),
    (["move", str(FOUR_BAR), "--chain", "0-1 1-2 2-3 3-0"], "give one mechanism"),
    (["move", "--chain", "0-1 1-2 2-3 3-0"], "--frame"),
    (["move", "--chain", "0-1 1-2 2-3 3-0", "--frame", "7"], "not a link"),
    (["move", "--chain", "0-1 1-2 2-3 3-0", "--frame", "0", "--input", "1-2"], "joint of the frame"),
    (["move", "--chain", "0-1 1-2 2-0", "--frame", "0"], "rigid"),
    (["move", "--chain", "0-1 1-2 2-3 3-4 4-0", "--frame", "0", "--range"], "W = 2"),
    (["move", "--db", "x.sqlite"], "--id"),
    (["move", "--id", "814ad964fad2", "--chain", "0-1 1-2 2-3 3-0", "--frame", "0"], "--db"),
    (["move", str(FOUR_BAR), "--frame", "0"], "--frame"),
    (["move", str(FOUR_BAR), "--steps", "1"], "--steps"),
    (["move", str(FOUR_BAR), "--steps", "100000000"], "--steps"),
    (["move", str(FOUR_BAR), "--steps", "ten"], "number of steps"),
    (["move", str(FOUR_BAR), "--steps", "30000"], "--format jsonl or csv"),
    (["move", str(FOUR_BAR), "--start", "nan"], "finite"),
    (["move", str(FOUR_BAR), "--start", "10", "--stop", "10"], "two different ends"),
    # it said "start and stop are the same input" with no --stop given (1e308° plus a turn is 1e308°)
    (["move", str(FOUR_BAR), "--start", "1e308"], "start 1e+308° (1.74533e+306 rad) is too far from zero"),
    (["move", str(FOUR_BAR), "--range", "--format", "csv"], "--range"),
    (["move", str(FOUR_BAR), "--range", "--velocities"], "--range"),
    (["move", str(FOUR_BAR), "--frames", "10"], "--animate"),
    # it said "expected a whole number ≥ 1, not 0" where the frames are 2 … 1000
    (["move", str(FOUR_BAR), "--frames", "0", "--animate", "m.gif"], "--frames must be 2 … 1000, not 0"),
    (["move", str(FOUR_BAR), "--out", "curves.jpg"], "PNG or SVG"),
    (["move", str(FOUR_BAR), "--animate", "m.mp4"], "GIF or SVG"),
    (["move", str(FOUR_BAR), "--out", "/no/such/dir/c.png"], "cannot write"),
    (["move", str(FOUR_BAR), "--out", "same.svg", "--animate", "same.svg"], "same file"),
    (["move", "no_such_file.toml"], "no linkage file"),
    (["move", "README.md"], ".toml or .json"),
]


@pytest.mark.parametrize("argv, words", BAD, ids=[" ".join(a[1:])[:40] for a, _ in BAD])
def test_bad_inputs_are_one_sentence_and_exit_2(argv, words, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = main(argv)
    err = capsys.readouterr().err
    assert code == 2, err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err
    assert not any(tmp_path.iterdir())  # nothing written


@pytest.mark.parametrize("content, words", [
    ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1"]\n'
     'points = { "0-1" = [0, 0], "0-3" = [4, 0], "1-2" = [0, 0], "2-3" = [3, 2] }\n', "same point"),
    ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1", "0-3"]\n'
     'points = { "0-1" = [0, 0], "0-3" = [4, 0], "1-2" = [1, 0], "2-3" = [3, 2] }\n', "needs 1 input"),
    ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = []\n'
     'points = { "0-1" = [0, 0], "0-3" = [4, 0], "1-2" = [1, 0], "2-3" = [3, 2] }\n', "needs 1 input"),
    ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1"]\n'
     'points = { "0-1" = [0, 0], "0-3" = [4, 0], "1-2" = [1, 0], "2-3" = [nan, 2] }\n', "not finite"),
    ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1"]\n'
     'points = { "0-1" = [0, 0], "0-3" = [4, 0], "1-2" = [1, 0], "2-3" = [inf, 2] }\n', "not finite"),
    ('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1"]\npoints = { "0-1" = [0, 0] }\n', "no position"),
    ('[linkage]\nchain = "0-1 1-2 2-0"\nframe = 0\ninputs = ["0-1"]\n'
     'points = { "0-1" = [0, 0], "1-2" = [1, 0], "0-2" = [0, 1] }\n', "rigid"),
    ("not toml at all [", "not valid TOML"),
])
def test_bad_linkage_files(content, words, capsys, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(content)
    before = path.read_bytes()
    code = main(["move", str(path), "--out", str(tmp_path / "c.png")])
    err = capsys.readouterr().err
    assert code == 2 and words in err and err.count("\n") == 1, err
    assert path.read_bytes() == before and not (tmp_path / "c.png").exists()


def test_an_input_the_branch_cannot_reach_is_refused_with_its_range(capsys):
    """The triad's input rocks between 125.4° and 161.0°: a sweep from 0° cannot be assembled there."""
    code, out, err = _run(capsys, "move", ROOT / "models" / "motion_triad.toml", "--start", "0", "--stop", "10",
                          "--format", "csv")
    assert code == 2 and out == "" and "cannot be assembled" in err and "125.4" in err and err.count("\n") == 1


def test_ctrl_c_stops_a_long_sweep_within_two_seconds(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([sys.executable, "-m", "mechsynth", "move", str(FOUR_BAR), "--steps", "1000000",
                             "--velocities", "--format", "jsonl"], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, env=env, start_new_session=True)
    time.sleep(4)
    os.killpg(proc.pid, signal.SIGINT)
    start = time.monotonic()
    proc.wait(timeout=max(30.0, allowed_seconds(2.0)))
    assert time.monotonic() - start < allowed_seconds(2.0) and proc.returncode == 130  # 2 s of an idle machine


def test_a_chain_of_an_atlas_by_its_id(capsys, tmp_path):
    """The Watt chain of an atlas (id 814ad964fad2), its ternary link 4 fixed: Watt II."""
    from synth.atlas import run_grid
    from synth.atlas.grid import parse_grid

    db = tmp_path / "a.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..6"'), str(db), workers=1)
    before = db.read_bytes()
    code, out, err = _run(capsys, "move", "--db", db, "--id", "814ad964fad2", "--frame", "4", "--range",
                          "--format", "json")
    assert code == 0 and "4" in json.loads(out)["input"].split("-")  # a joint of the frame drives
    assert db.read_bytes() == before  # the atlas is only read
    code, _, err = _run(capsys, "move", "--db", db, "--id", "000000000000", "--frame", "0")
    assert code == 2 and "000000000000" in err


def test_an_id_and_frame_from_the_listings_move_the_same_mechanism_from_an_atlas(capsys, tmp_path):
    """One numbering of a chain by id: the joints and frames printed by ``chains``, ``mechanisms``
    and ``identify`` are the atlas's, so ``move --db --id --frame`` moves the very mechanism listed
    (the Watt chain 814ad964fad2 was listed 0-1 0-2 0-4 … but stored 0-3 0-4 1-2 …)."""
    from synth import Chain, Mechanism
    from synth.atlas import run_grid
    from synth.atlas.grid import parse_grid

    db = tmp_path / "a.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "6..8"'), str(db), workers=1)

    def moved(chain_id, frame):
        saved = tmp_path / f"{chain_id}_{frame}.json"
        assert _run(capsys, "move", "--db", db, "--id", chain_id, "--frame", frame, "--save", saved)[0] == 0
        linkage = json.loads(saved.read_text())
        return Mechanism(Chain.parse(linkage["chain"]), linkage["frame"])

    listed = []
    for query in (["--links", "6"], ["--code", "602/0"]):
        code, out, _ = _run(capsys, "chains", "--dof", "1", *query, "--format", "jsonl", "--workers", "1")
        for row in map(json.loads, out.splitlines()):
            code, stored, _ = _run(capsys, "atlas", "--db", db, "--where", f"id={row['id']}")
            assert code == 0 and json.loads(stored)["joints"] == row["joints"]
        code, out, _ = _run(capsys, "mechanisms", "--dof", "1", *query, "--format", "jsonl", "--workers", "1")
        listed += [json.loads(line) for line in out.splitlines()]
    assert len({(r["chain_id"], r["frame"]) for r in listed}) == len(listed) >= 8
    for row in listed:
        mechanism = moved(row["chain_id"], row["frame"])
        assert mechanism.chain.compact() == Chain.from_dict(row).compact()
        assert mechanism.certificate == row["certificate"], row  # the frame names the same link
    # identify, given the Watt chain numbered another way with a ternary fixed (Watt II)
    code, out, _ = _run(capsys, "identify", "0-1 0-2 0-4 1-3 1-5 2-3 4-5", "--frame", "0", "--format", "json")
    found = json.loads(out)
    assert code == 0 and found["id"] == "814ad964fad2" and found["inversion"] == ["Watt II"]
    mechanism = moved(found["id"], found["listed_frame"])
    assert mechanism.certificate == found["mechanism_certificate"]
    assert mechanism.chain.compact() == found["listed_joints"] and mechanism.chain.degrees[mechanism.frame] == 3


def test_a_long_sweep_written_piece_by_piece_is_the_one_sweep(capsys):
    """More than 20 000 steps are computed a piece at a time (Ctrl-C is seen between pieces): the
    rows are those of one sweep over the same inputs."""
    from synth.motion import read_linkage, sweep

    code, out, _ = _run(capsys, "move", FOUR_BAR, "--steps", "45001", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    whole = sweep(read_linkage(FOUR_BAR), steps=45001)
    assert code == 0 and len(rows) == 45001 and [int(r["step"]) for r in rows[::9000]] == list(range(0, 45001, 9000))
    for s in (0, 19999, 20000, 20001, 45000):
        assert float(rows[s]["input"]) == pytest.approx(whole.inputs[s, 0], abs=1e-12)
        assert float(rows[s]["2-3.x"]) == pytest.approx(whole.joints[s, 3, 0], abs=1e-9)


@pytest.mark.parametrize("start, stop", [(0, 720), (350, 370), (355, -400)], ids=str)
def test_a_cranks_rows_give_a_continuous_input_past_a_turn(capsys, start, stop):
    """A crank turned more than once, or from near 360°: the rows' input (rad) runs on past 2π, never wrapped."""
    for fmt in ("csv", "jsonl"):
        code, out, _ = _run(capsys, "move", FOUR_BAR, "--steps", "73", "--start", start, "--stop", stop, "--format", fmt)
        rows = list(csv.DictReader(io.StringIO(out))) if fmt == "csv" else [json.loads(x) for x in out.splitlines()]
        phi = np.array([float(r["input"]) for r in rows])
        assert code == 0 and phi == pytest.approx(np.radians(np.linspace(start, stop, 73)), abs=1e-12)


def test_a_triad_says_why_it_reports_no_transmission_angle(capsys):
    code, out, _ = _run(capsys, "move", ROOT / "models" / "motion_triad.toml", "--range", "--format", "json")
    doc = json.loads(out)
    assert code == 0 and doc["transmission"] == {} and "class III" in doc["transmission_note"]
    code, out, _ = _run(capsys, "move", FOUR_BAR, "--range", "--format", "json")
    assert "transmission_note" not in json.loads(out)


def test_a_saved_linkage_read_back_does_not_repeat_the_note_of_its_drawing(capsys, tmp_path):
    """The note 'the drawing's pose does not move well; its joints were moved …' is said when the pose is
    moved and kept in the saved file, but reading the file back moves nothing: the command says nothing."""
    saved = tmp_path / "watt_i.json"
    code, _, err = _run(capsys, "move", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--frame", "2", "--save", saved)
    assert code == 0 and "note: the drawing's pose" in err and "note" in json.loads(saved.read_text())
    code, _, err = _run(capsys, "move", saved, "--range")
    assert code == 0 and "note" not in err


def test_a_cranks_angles_are_read_in_one_turn_0_to_360(capsys):
    """The four-bar's least transmission angle was reported 'at input 360°': a full turn from its pose,
    359.9999999997°, printed to six digits."""
    code, out, _ = _run(capsys, "move", FOUR_BAR, "--range")
    assert code == 0 and "at input 360°" not in out and "at input 0°" in out


def test_range_gives_a_crank_driven_sliders_stroke_and_quick_return_ratio(capsys):
    """Only the scene computed them; --range printed none.  The offset slider-crank (crank 1, rod 3.5, offset
    0.5): stroke √((l + r)² − e²) − √((l − r)² − e²), ratio (π + δ)/(π − δ), dead centres where crank and rod
    line up (written here from the geometry, independently of the solver)."""
    r, l, e = 1.0, 3.5, 0.5
    delta = math.asin(e / (l - r)) - math.asin(e / (l + r))
    code, out, _ = _run(capsys, "move", SLIDER, "--range", "--format", "json")
    stroke = json.loads(out)["strokes"]["3"]
    assert code == 0 and stroke["pair"] == "0=3"
    assert stroke["stroke"] == pytest.approx(math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e),
                                             abs=1e-12)
    assert stroke["quick_return_ratio"] == pytest.approx((math.pi + delta) / (math.pi - delta), abs=1e-7)
    outer = math.atan2(e, math.sqrt((l + r) ** 2 - e * e))  # the crank along the rod
    inner = math.pi + math.atan2(e, math.sqrt((l - r) ** 2 - e * e))  # the crank folded back on it
    assert stroke["dead_centres"] == pytest.approx([outer, inner], abs=1e-7)
    code, out, _ = _run(capsys, "move", SLIDER, "--range")
    assert code == 0 and ("slider 3 (0=3)           stroke 2.02265 between the dead centres at input 6.37937° and "
                          "191.537°; quick-return ratio 1.059") in out
    code, out, _ = _run(capsys, "move", FOUR_BAR, "--range", "--format", "json")
    assert code == 0 and json.loads(out)["strokes"] == {}  # no slider


def test_range_json_gives_a_cranks_angles_within_one_turn_as_the_table_does(capsys):
    """A 350 … 1070° sweep gave the toggles within a turn but the transmission angles' inputs past 2π."""
    code, out, _ = _run(capsys, "move", FOUR_BAR, "--range", "--start", "350", "--stop", "1070", "--format", "json")
    doc = json.loads(out)
    inputs = [t["input"] for t in doc["toggles"]] + [v for t in doc["transmission"].values()
                                                      for v in (t["at_min"], t["at_max"])]
    assert code == 0 and len(inputs) == 4 and all(0 <= v < 2 * math.pi for v in inputs), inputs
    code, table, _ = _run(capsys, "move", FOUR_BAR, "--range", "--start", "350", "--stop", "1070")
    t = next(iter(doc["transmission"].values()))
    shown = [f"{math.degrees(v) % 360:.6g}".replace("360", "0") for v in (t["at_min"], t["at_max"])]
    assert f"at input {shown[0]}°, max" in table and f"at {shown[1]}°; worst" in table


def test_the_help_says_which_unit_and_turn_the_range_gives(capsys):
    with pytest.raises(SystemExit):
        main(["move", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "the table's angles in degrees, the JSON's in radians, a crank's within one turn (0 … 360°, 0 … 2π) in both" \
        in text
