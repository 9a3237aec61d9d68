"""``mechsynth dimension``: a result chained into ``move`` and ``scene``, and every refusal one
sentence with exit status 2, before any work and with nothing written."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from mechsynth.cli import main

MODELS = Path(__file__).resolve().parents[2] / "models"
FOUR_BAR = ["--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0"]


def test_a_function_found_is_saved_and_moved(tmp_path, capsys):
    saved, picture = tmp_path / "found.toml", tmp_path / "found.png"
    code = main(["dimension", str(MODELS / "dimension_function.csv"), *FOUR_BAR, "--budget", "20",
                 "--save", str(saved), "--out", str(picture), "--format", "json"])
    out = capsys.readouterr().out
    assert code == 0
    result = json.loads(out)
    assert result["kind"] == "function" and result["error_max"] < 1e-9 and result["met"]
    assert picture.stat().st_size > 0
    assert main(["move", str(saved), "--range", "--format", "json"]) == 0  # the saved linkage moves
    moved = json.loads(capsys.readouterr().out)
    assert moved["input"] == "0-1"
    assert main(["scene", str(saved)]) == 0  # and is a scene
    capsys.readouterr()


@pytest.mark.slow  # about 11 CPU seconds of search
def test_a_path_found_is_drawn_over_its_target(tmp_path, capsys):
    picture = tmp_path / "path.svg"
    code = main(["dimension", str(MODELS / "dimension_path.csv"), *FOUR_BAR, "--budget", "60", "--out",
                 str(picture), "--format", "jsonl"])
    row = json.loads(capsys.readouterr().out)
    assert code == 0 and row["relative_max"] < 1e-6
    svg = picture.read_text()
    assert svg.count('stroke="#1f4e9c"') == 7  # the seven target points


def test_the_bar_on_a_terminal_reads_seconds_then_the_best_error(monkeypatch, capsys):
    """The search's bar read '2.8/3.0 s , best 0.00738' (tqdm puts its own ', ' before the postfix)."""
    import io
    import sys

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert main(["dimension", str(MODELS / "dimension_path.csv"), *FOUR_BAR, "--budget", "1",
                 "--min-transmission", "60"]) == 0
    capsys.readouterr()
    frames = [f for f in terminal.getvalue().split("\r") if "best" in f]
    assert frames and all(" s, best " in f and " , " not in f for f in frames), frames[-1:]


def test_a_constraint_the_search_cannot_meet_exits_1_and_says_which(tmp_path, capsys):
    saved = tmp_path / "none.toml"
    code = main(["dimension", str(MODELS / "dimension_path.csv"), *FOUR_BAR, "--budget", "2",
                 "--crank", "--min-transmission", "89", "--save", str(saved)])
    err = capsys.readouterr().err
    assert code == 1 and "fails" in err and not saved.exists()


@pytest.mark.parametrize("args, words", [
    ([*FOUR_BAR, "--db", "atlas.sqlite"], "does not go with --mechanism"),
    ([*FOUR_BAR, "--links", "4..8"], "--links goes with --db"),
    (["--frame", "0"], "give one mechanism"),
    ([*FOUR_BAR, "--linkage", "x.toml"], "give one mechanism"),
    (["--mechanism", "0-1 1-2 2-3 3-0"], "needs --frame"),
    ([*FOUR_BAR, "--crank", "--rocker", "0..90"], "contradict"),
    ([*FOUR_BAR, "--rocker", "90..0"], "A < B"),
    # the function's inputs span 45°: a rocker within 40° cannot pass them (the search ran its budget, then said
    # to give a longer one)
    ([*FOUR_BAR, "--rocker", "20..60"], "inputs span 45°, more than the 40° between the rocker's limits (--rocker"),
    ([*FOUR_BAR, "--min-transmission", "95"], "between 0 and 90"),
    ([*FOUR_BAR, "--max-ratio", "0.5"], "above 1"),
    ([*FOUR_BAR, "--max-length", "0"], "--max-length must be a positive length"),
    ([*FOUR_BAR, "--max-length", "-3"], "--max-length must be a positive length"),
    ([*FOUR_BAR, "--max-length", "inf"], "finite number"),
    ([*FOUR_BAR, "--max-length", "5", "--pivot-at", "0-1=0,0", "--pivot-at", "0-3=6,8"], "lie 10 apart"),
    ([*FOUR_BAR, "--pivots", "0..1"], "x0..x1,y0..y1"),
    # a function's pivots are its gauge's, (0, 0) and (1, 0): a region excluding them ran the budget, then said
    # that no mechanism was found
    ([*FOUR_BAR, "--pivots", "5..6,5..6"], "fixed pivots, a pivots' region and a timing do not apply"),
    ([*FOUR_BAR, "--budget", "0"], "positive number of seconds"),
    ([*FOUR_BAR, "--out", "picture.gif"], "PNG or SVG"),
    ([*FOUR_BAR, "--save", "x.txt"], "TOML or JSON"),
    (["--mechanism", "0-1 1-2 2-3 3-0", "--frame", "9"], "not a link"),  # (FOUR_BAR has its --frame already)
    (["--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0", "--input", "1-2"], "must be a joint of the frame"),
    ([*FOUR_BAR, "--tracer-link", "2"], "this target is a function"),
    (["--mechanism", "0-1 1-2 2-0", "--frame", "0"], "W = 0"),
    # three function pairs for a four-bar's three unknowns: nothing underdetermined to allow (it was accepted silently)
    ([*FOUR_BAR, "--underdetermined"], "--underdetermined allows fewer target equations than unknowns, and this target "
                                       "gives 3 equations for the 3 unknowns of this function synthesis: drop it"),
    ([*FOUR_BAR, "--output-link", "9"], "the output link 9 is not a link of the mechanism (links 0 … 3)"),
])
def test_a_contradiction_is_one_sentence_and_exit_2(tmp_path, capsys, monkeypatch, args, words):
    monkeypatch.chdir(tmp_path)
    shutil.copy(MODELS / "dimension_function.csv", tmp_path / "f.csv")
    assert main(["dimension", "f.csv", *args]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.csv"]  # nothing written


def test_a_pivots_region_far_from_the_target_is_named_when_nothing_reaches_it(capsys):
    """A region of the fixed pivots 140 target units away: the search ends with one sentence and exit 2, which
    advised only a longer budget or a larger reach (the reach does not bound the frame's joints)."""
    assert main(["dimension", str(MODELS / "dimension_path.csv"), *FOUR_BAR, "--budget", "1",
                 "--pivots", "100..101,100..101"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.rstrip().endswith(
        "or a region of the fixed pivots (--pivots x0..x1,y0..y1) nearer the target")


def test_a_pivots_region_no_link_within_the_length_bound_reaches_is_refused_before_the_search(capsys):
    """The same region with every link at most 5 long: no link joins it to the search box (the moving joints
    within 4 target sizes of the target's centre), so it is refused at once — it spent the whole budget (the
    default 60 CPU s), then said no mechanism was found."""
    assert main(["dimension", str(MODELS / "dimension_path.csv"), *FOUR_BAR, "--budget", "86400",
                 "--pivots", "100..101,100..101", "--max-length", "5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "lies 129.4 from every place a moving joint is sought" in err
    assert err.rstrip().endswith("give a region of the fixed pivots (--pivots x0..x1,y0..y1) nearer the target, or a "
                                 "larger --reach R or --max-length L")


def test_a_bad_target_file_is_one_sentence_and_exit_2(tmp_path, capsys):
    bad = tmp_path / "nan.csv"
    bad.write_text("x,y,input\n0,0,0\nnan,1,1\n")
    assert main(["dimension", str(bad), *FOUR_BAR]) == 2
    err = capsys.readouterr().err
    assert "not all finite" in err and err.count("\n") == 1
    few = tmp_path / "few.csv"
    few.write_text("x,y,input\n0,0,0\n1,0,1\n1,1,2\n")
    assert main(["dimension", str(few), *FOUR_BAR]) == 2
    assert "give at least 5 points" in capsys.readouterr().err


def test_the_target_read_is_never_overwritten(tmp_path, capsys):
    target = tmp_path / "f.csv"
    shutil.copy(MODELS / "dimension_function.csv", target)
    before = target.read_text()
    assert main(["dimension", str(target), *FOUR_BAR, "--save", str(tmp_path / "f.json"), "--out",
                 str(tmp_path / "f.json")]) == 2
    assert main(["dimension", str(target), *FOUR_BAR, "--out", str(target.with_suffix(".svg")), "--save",
                 str(target)]) == 2
    assert target.read_text() == before
    capsys.readouterr()


def test_the_tables_constraints_carry_their_units(capsys):
    """'constraint transmission  met: 51.8704 (limit 20)' gave no unit: angles are in degrees, lengths in
    the target's units."""
    assert main(["dimension", str(MODELS / "dimension_function.csv"), *FOUR_BAR, "--budget", "3",
                 "--min-transmission", "10", "--max-length", "3", "--rocker", "30..90"]) == 0
    rows = dict(line.split(None, 2)[1:] for line in capsys.readouterr().out.splitlines()
                if line.startswith("constraint "))
    assert rows["transmission"].startswith("met: ") and rows["transmission"].endswith("° (limit 10°)")
    assert rows["length"].endswith(" target units (limit 3 target units)")
    # the rocker's limits, given in degrees, were shown in radians without a unit: [0.523599, 1.5708]
    assert rows["rocker"] == "met: [35, 80]° (limit [30, 90]°)"  # the function's inputs, 35° … 80°


def test_an_answer_on_the_edge_of_the_reach_says_so(tmp_path, capsys):
    # eight timed points of a four-bar whose frame pivots lie 40 apart, its coupler point's path some 10 across:
    # within a reach of half the target's size the search stops on the box's edge and must say which joint
    import math

    from synth.motion import Linkage, sweep
    from synth.structure.chain import Chain, Mechanism

    wide = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [40, 0], [1, 0], [35, 30]],
                   tracers={"P": (2, (2.0, 3.0))})
    motion = sweep(wide, steps=8, stop=float(wide.pose_inputs[0]) + math.radians(300))
    target = tmp_path / "wide.csv"
    target.write_text("x,y,input\n" + "".join(f"{x!r},{y!r},{t!r}\n" for (x, y), t in
                                              zip(motion.tracers["P"].tolist(), motion.inputs[:, 0].tolist())))
    main(["dimension", str(target), *FOUR_BAR, "--budget", "3", "--seed", "0", "--reach", "0.5", "--format", "json"])
    captured = capsys.readouterr()
    assert json.loads(captured.out)["relative_max"] > 1e-3
    (note,) = [line for line in captured.err.splitlines() if "edge of the search's reach" in line]
    assert note.startswith("mechsynth: 0-3 ") and "a larger reach may lower the error" in note


def test_underdetermined_is_taken_where_the_target_needs_it(tmp_path, capsys):
    """Two function pairs give 2 equations for a four-bar's 3 unknowns: refused without the option, met exactly with it."""
    two = tmp_path / "two.csv"
    two.write_text("input_deg,output_deg\n35,60\n55,72\n")
    assert main(["dimension", str(two), *FOUR_BAR, "--budget", "2"]) == 2
    assert "give at least 3 points (or allow an underdetermined problem: --underdetermined)" in capsys.readouterr().err
    assert main(["dimension", str(two), *FOUR_BAR, "--budget", "2", "--underdetermined", "--format", "jsonl"]) == 0
    row = json.loads(capsys.readouterr().out)
    assert row["points"] == 2 and row["error_max"] < 1e-9


def test_the_help_gives_the_pivots_box_its_unit(capsys):
    """--pivots said 'a box the frame's joints must lie in' and no unit (--pivot-at said target units)."""
    with pytest.raises(SystemExit):
        main(["dimension", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "a box the frame's joints must lie in, in target units (the target's x, y)" in text


def test_a_jsonl_row_of_one_mechanism_carries_its_linkage_and_a_csv_of_rows_is_refused_by_every_reader(
        tmp_path, capsys):
    """'dimension --mechanism … --format jsonl' wrote a row without the linkage (move, draw and balance linkage
    could not read it, where the atlas search's rows carry theirs); a csv of rows with --row K said only that a
    linkage file is .toml or .json: each reader of --row now names the formats that carry a linkage."""
    assert main(["dimension", str(MODELS / "dimension_function.csv"), *FOUR_BAR, "--budget", "5",
                 "--format", "jsonl"]) == 0
    out = capsys.readouterr().out
    one = tmp_path / "one.jsonl"
    one.write_text(out)
    row = json.loads(out)
    assert row["error_max"] < 1e-9 and row["linkage"]["chain"] == "0-1 0-3 1-2 2-3"
    for given in ([], ["--row", "1"]):
        assert main(["move", str(one), *given, "--range", "--format", "json"]) == 0
        assert json.loads(capsys.readouterr().out)["input"] == "0-1"
    table = tmp_path / "rows.csv"
    table.write_text("rank,links,error_max\n1,4,0.0\n2,4,0.0\n")
    for command in (["move", str(table)], ["draw", str(table), "--out", str(tmp_path / "x.png")],
                    ["balance", "linkage", str(table), "--density", "1"],
                    ["dimension", str(MODELS / "dimension_function.csv"), "--linkage", str(table)]):
        assert main([*command, "--row", "2"]) == 2
        assert capsys.readouterr().err == (
            "mechsynth: rows.csv is a csv file, whose rows carry no linkage: the rows of 'dimension … --format json' "
            "or 'jsonl' carry each linkage (--row K picks one), a linkage file is .toml or .json\n"), command


def test_a_sheet_panel_whose_mechanism_dwarfs_the_target_says_so_in_its_title():
    """Each panel of the atlas search's sheet is drawn to its own scale: a four-bar thousands of times the target
    drew the target as a speck under a title that did not say why.  Above 10× the target's size (bounding-box
    diagonals) the title says how many times; the pivots alone are 4 k apart, so the mark is at least 4 k / size."""
    import math
    import re
    from types import SimpleNamespace

    import numpy as np

    from mechsynth.commands.dimension import _panel_title
    from synth.motion import sweep
    from tests.motion.helpers import four_bar

    curve = sweep(four_bar(1, 3.5, 3, 4, phi=math.pi / 2, tracer=(2.5, 4.5)), steps=90).tracers["P"]
    size = float(np.hypot(*(curve.max(axis=0) - curve.min(axis=0))))  # the target: the unscaled curve
    marks = {}
    for k in (1, 2, 100, 1000):
        lk = four_bar(k, 3.5 * k, 3 * k, 4 * k, phi=math.pi / 2, tracer=(2.5 * k, 4.5 * k))
        title = _panel_title(3, SimpleNamespace(linkage=lk, error_max=0.0122, size=size), sweep(lk, steps=90))
        assert title.startswith("3: 0-1 0-3 1-2 2-3, frame 0\n4 links, error max 0.0122")
        found = re.fullmatch(r".*, mechanism (\d+)× target", title.splitlines()[1])
        marks[k] = found and int(found.group(1))
    assert marks[1] is None and marks[2] is None  # 3.0× and 5.9× the target: no mark
    assert 4 * 100 / size <= marks[100] <= 3 * 4 * 100 / size
    assert abs(marks[1000] - 10 * marks[100]) <= 10  # (rounded to a whole number each)
