"""``mechsynth draw LINKAGE_FILE``: a dimensioned mechanism (as ``move``/``dimension --save`` write it)
drawn to scale by the motion layer's drawing, at its saved pose or at ``--at``; what does not apply refused."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from mechsynth.cli import main
from synth.motion import read_linkage

ROOT = Path(__file__).resolve().parents[2]


def _pins(svg: str) -> np.ndarray:
    """The pin circles' centres in pixels (drawn in joint order), y turned upwards."""
    found = re.findall(r'<circle cx="([-\d.]+)" cy="([-\d.]+)" r="[\d.]+" fill="white"', svg)
    return np.array([(float(x), -float(y)) for x, y in found])


@pytest.fixture(scope="module")
def saved(tmp_path_factory) -> Path:
    """A Watt six-bar with its frame 2, dimensioned from its drawing and saved by ``move --save``."""
    path = tmp_path_factory.mktemp("linkage") / "watt.json"
    assert main(["move", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--frame", "2", "--save", str(path)]) == 0
    return path


def test_a_saved_linkage_is_drawn_to_scale_at_its_pose(saved, tmp_path, capsys):
    out = tmp_path / "watt.svg"
    assert main(["draw", str(saved), "--out", str(out)]) == 0
    svg = out.read_text()
    pose = read_linkage(saved).points
    px = _pins(svg)
    assert len(px) == len(pose) == 7
    # the pixels are a similarity of the saved pose: every distance in one ratio, to the pixel rounding
    pairs = [(i, j) for i in range(7) for j in range(i)]
    ratio = sum(np.hypot(*(px[i] - px[j])) for i, j in pairs) / sum(np.hypot(*(pose[i] - pose[j])) for i, j in pairs)
    for i, j in pairs:  # (each centre is written to 0.1 px: a distance to 0.15 px)
        assert np.hypot(*(px[i] - px[j])) == pytest.approx(ratio * np.hypot(*(pose[i] - pose[j])), abs=0.15)
    # the scale bar's length in pixels is its written length at that ratio
    bar = re.search(r'<polyline points="([-\d., ]+)" fill="none" stroke="#6b7785" stroke-width="1.4"', svg).group(1)
    ends = [tuple(map(float, p.split(","))) for p in bar.split()]
    written = float(re.findall(r">([\d.e+-]+)</text>", svg)[-1])
    assert ends[2][0] - ends[1][0] == pytest.approx(ratio * written, abs=0.15)
    assert all(f">{link}</text>" in svg for link in range(6))  # the links numbered as the chain numbers them
    assert "1 drawing" in capsys.readouterr().err


def test_at_poses_the_input_on_the_branch_and_keeps_every_link_rigid(saved, tmp_path):
    linkage = read_linkage(saved)
    out = tmp_path / "at.svg"
    assert main(["draw", str(saved), "--at", "-75", "--out", str(out)]) == 0
    px = _pins(out.read_text())
    pose = linkage.points
    ratio = [np.hypot(*(px[a] - px[b])) / np.hypot(*(pose[a] - pose[b]))
             for link in range(6) for a in linkage.joints_of(link) for b in linkage.joints_of(link) if a < b]
    assert np.ptp(ratio) < 0.01 * np.mean(ratio)  # each link keeps its saved dimensions
    k, b = linkage.inputs[0], linkage.input_reference(0)
    turned = math.degrees(math.atan2(*(px[b] - px[k])[::-1]))
    assert turned == pytest.approx(-75, abs=0.2)  # the input's line at -75°, to the pixel rounding
    saved_angle = math.degrees(math.atan2(*(pose[b] - pose[k])[::-1]))
    assert abs(saved_angle + 75) > 5  # (the saved pose was elsewhere: the drawing moved it)


def test_a_png_is_the_size_asked(saved, tmp_path):
    out = tmp_path / "watt.png"
    assert main(["draw", str(saved), "--size", "4", "--dpi", "50", "--title", "Watt", "--out", str(out)]) == 0
    width, height = Image.open(out).size
    assert max(width, height - 15) == pytest.approx(200, abs=1)  # 4 in at 50 dpi, a 0.3 in title strip over it


@pytest.mark.parametrize("extra, words", [
    (["--frame", "1"], "--frame does not apply"),
    (["--mechanisms", "--columns", "2"], "--mechanisms, --columns do not apply"),
    (["--dpi", "300"], "--dpi sets the resolution of a .png"),
    (["--limit", "400"], "--limit does not apply"),  # (the default's value, given: told apart from the default)
])
def test_what_does_not_apply_to_a_linkage_is_refused(saved, tmp_path, capsys, extra, words):
    out = tmp_path / "x.svg"
    assert main(["draw", str(saved), *extra, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1 and not out.exists()


def test_a_title_wider_than_a_narrow_drawing_is_wrapped_not_cut(saved, tmp_path):
    short, long = tmp_path / "short.png", tmp_path / "long.png"
    assert main(["draw", str(saved), "--size", "4", "--dpi", "50", "--title", "Watt", "--out", str(short)]) == 0
    title = "a Watt six-bar with its frame 2, dimensioned from its drawing"  # about 4.5 in at 9 pt: wider than it
    assert main(["draw", str(saved), "--size", "4", "--dpi", "50", "--title", title, "--out", str(long)]) == 0
    (w1, h1), (w2, h2) = Image.open(short).size, Image.open(long).size
    assert w1 == w2 and h2 - h1 == 8  # the same drawing under a strip 0.16 in (a line) taller


def test_at_is_refused_where_it_cannot_pose(saved, tmp_path, capsys):
    triad = ROOT / "models" / "motion_triad.toml"  # rocks between 125.43° and 161.03°
    assert main(["draw", str(triad), "--at", "170", "--out", str(tmp_path / "t.png")]) == 2
    assert "cannot be assembled at input" in capsys.readouterr().err
    assert main(["draw", "--chain", "0-1 1-2 2-3 3-0", "--at", "30", "--out", str(tmp_path / "c.png")]) == 2
    assert "--at poses a linkage file's input" in capsys.readouterr().err
    five = tmp_path / "five_bar.json"
    assert main(["move", "--chain", "0-1 1-2 2-3 3-4 4-0", "--frame", "0", "--save", str(five)]) == 0
    capsys.readouterr()
    assert main(["draw", str(five), "--at", "30", "--out", str(tmp_path / "f.png")]) == 2
    assert "W = 2 inputs" in capsys.readouterr().err
    assert main(["draw", str(five), "--out", str(tmp_path / "f.png")]) == 0  # at its saved pose it is drawn
    assert main(["draw", "--chain", str(saved), "--out", str(tmp_path / "c.png")]) == 2
    assert f"draws it to scale: 'mechsynth draw {saved} --out FILE'" in capsys.readouterr().err
    assert main(["draw", "0-1 1-2 2-3 3-0", "--out", str(tmp_path / "c.png")]) == 2  # a chain given as a file
    assert "a chain's drawing is 'mechsynth draw --chain \"0-1 1-2 2-3 3-0\"" in capsys.readouterr().err


@pytest.mark.parametrize("words, hint, elsewhere", [
    (["analyze", "{f}"], "'mechsynth identify {f}' gives its chain's code, W", "mechsynth analyze \"$(cat {f})\""),
    (["chains", "--chain", "{f}"], "'mechsynth identify {f}' gives its chain's id and row",
     "mechsynth chains --chain \"$(cat {f})\""),
    (["mechanisms", "--chain", "{f}"], "'mechsynth identify {f}' gives its mechanism's row",
     "mechsynth mechanisms --chain \"$(cat {f})\""),
    (["draw", "--chain", "{f}", "--out", "{d}/x.png"], "'mechsynth draw {f} --out FILE'", None),
    (["move", "--chain", "{f}"], "'mechsynth move {f}'", None),
])
def test_a_linkage_file_given_as_a_chain_is_named_with_what_the_command_can_do(saved, tmp_path, capsys, words, hint,
                                                                               elsewhere):
    """Each command that reads a chain's text names, for a linkage file, what it (or identify) does with that
    file — no other command's use; a .json linkage's text is the chain that analyze, chains and mechanisms read."""
    argv = [w.format(f=saved, d=tmp_path) for w in words]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"{saved} is a linkage file, and {words[0]}" in err and hint.format(f=saved) in err
    others = {"analyze", "chains", "mechanisms", "draw", "move"} - {words[0]}
    assert not [c for c in others if f"mechsynth {c} " in err.replace(f"mechsynth {words[0]} --help", "")]
    if elsewhere is not None:
        assert elsewhere.format(f=saved) in err
        text = ["$(cat)" if w == "{f}" else w for w in words]  # the hint's command line, run: it reads the chain
        assert main([saved.read_text() if w == "$(cat)" else w for w in text]) == 0
    toml = ROOT / "models" / "motion_four_bar.toml"  # a TOML linkage's text is no chain: only identify's hint
    assert main([str(toml) if w == "{f}" else w.format(d=tmp_path) for w in words]) == 2
    err = capsys.readouterr().err
    assert hint.format(f=toml) in err and "$(cat" not in err


@pytest.mark.parametrize("command", [["analyze"], ["chains", "--chain"], ["mechanisms", "--chain"], ["move", "--chain"]])
def test_a_files_text_given_as_a_chain_is_named_as_such_not_echoed(command, capsys):
    """'analyze "$(cat L.toml)"' quoted the whole file back in a sentence about counts; a text of several lines
    (not JSON, whose rows a chain may be) is named by its first line, once."""
    toml = (ROOT / "models" / "motion_four_bar.toml").read_text()
    assert main([*command, toml]) == 2
    err = capsys.readouterr().err
    first = toml.strip().splitlines()[0][:40]
    assert f"the text given is {len(toml.strip().splitlines())} lines, beginning {first!r}" in err
    assert "'mechsynth identify FILE'" in err and len(err.splitlines()) == 1 and len(err) < 400


def test_a_file_that_holds_no_linkage_is_named_with_identify(tmp_path, capsys):
    rows = tmp_path / "rows.txt"
    rows.write_text("0-1 1-2 2-3 3-0\n")
    assert main(["analyze", str(rows)]) == 2
    err = capsys.readouterr().err
    assert f"{rows} is a file, and analyze reads a chain" in err and f"'mechsynth identify {rows}' reads" in err
    assert "linkage" not in err


@pytest.mark.parametrize("command", ["arm", "solve", "compare", "pantograph"])
def test_balance_refuses_a_linkage_naming_what_it_takes(saved, capsys, command):
    assert main(["balance", command, str(saved)]) == 2
    err = capsys.readouterr().err
    assert "watt.json is a linkage" in err and "'mechsynth balance linkage watt.json --density" in err
    assert err.count("\n") == 1
    json.loads(saved.read_text())  # (the file is untouched)


@pytest.mark.parametrize("at", [None, "30"])
def test_no_link_number_stands_on_a_pin_or_a_ground_pivot(saved, tmp_path, monkeypatch, at):
    # 'draw watt.json --at 30' wrote the frame's number 2 on a ground pivot's triangle and base (its two pivots one
    # above the other, the number beside the middle of the line between them)
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_hex

    figures = []
    monkeypatch.setattr(plt, "close", lambda fig=None: figures.append(fig))
    assert main(["draw", str(saved), "--out", str(tmp_path / "w.png"), *(["--at", at] if at else [])]) == 0
    (fig,) = figures
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    numbers = [t.get_window_extent(renderer) for t in ax.texts if t.get_text() in "012345"]
    pivots = [p.get_window_extent(renderer) for p in ax.patches if type(p).__name__ == "Polygon"
              and to_hex(p.get_facecolor()) == "#eef1f4"]
    pins = [p.get_window_extent(renderer) for p in ax.patches if type(p).__name__ == "Circle"]
    bases = [ln.get_window_extent(renderer) for ln in ax.lines if len(ln.get_xdata()) == 2
             and ln.get_ydata()[0] == ln.get_ydata()[1] and ln.get_linewidth() == pytest.approx(2.4 * 0.75)]
    assert len(numbers) == 6 and len(pivots) == 2 and len(bases) == 2 and len(pins) == 7
    assert not [(n, o) for n in numbers for o in pivots + pins + bases if n.overlaps(o)]
    assert not [(a, b) for i, a in enumerate(numbers) for b in numbers[:i] if a.overlaps(b)]


@pytest.mark.parametrize("tracers, extra", [
    (None, []),  # the four-bar balanced: its counterweight CW3 the drawing's rightmost point ('CW3' was cut)
    ({"COUPLER_POINT": {"link": 2, "at": [2.5, 4.5]}, "FAR_RIGHT": {"link": 3, "at": [6.0, 0.0]}}, []),
    ({"TOP": {"link": 2, "at": [1.0, 6.0]}, "RIGHT_SIDE": {"link": 3, "at": [5.0, -2.8]}},
     ["--size", "2", "--dpi", "300"]),
])
def test_every_name_lies_inside_the_picture(tmp_path, monkeypatch, capsys, tracers, extra):
    """Each text's box, as matplotlib's renderer sets it, inside the drawing (under the title), the title inside
    the figure: the drawing's extent counts the tracers' names, not only their points."""
    import matplotlib.pyplot as plt

    path = tmp_path / "linkage.json"
    if tracers is None:
        assert main(["balance", "linkage", str(ROOT / "models" / "motion_four_bar.toml"), "--density", "2",
                     "--save", str(path)]) == 0
    else:
        lk = read_linkage(ROOT / "models" / "motion_four_bar.toml").to_dict()
        path.write_text(json.dumps(lk | {"tracers": tracers}))
    figures = []
    monkeypatch.setattr(plt, "close", lambda fig=None: figures.append(fig))
    assert main(["draw", str(path), "--out", str(tmp_path / "x.png"), *extra]) == 0
    (fig,) = figures
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    area, whole = ax.get_window_extent(renderer), fig.bbox
    names = {t.get_text(): t.get_window_extent(renderer) for t in ax.texts}
    assert set(tracers or {"CW1", "CW3", "P"}) <= set(names)
    outside = {n: b.bounds for n, b in names.items() if not (area.x0 <= b.x0 and b.x1 <= area.x1 and area.y0 <= b.y0
                                                            and b.y1 <= area.y1)}
    assert not outside, (outside, area.bounds)
    title = fig.texts[0].get_window_extent(renderer)
    assert whole.x0 <= title.x0 and title.x1 <= whole.x1 and title.y1 <= whole.y1 and title.y0 >= area.y1 - 1
    width, height = Image.open(tmp_path / "x.png").size
    assert (width, height) == (round(whole.width), round(whole.height))


def test_a_slider_crank_is_drawn_with_its_links_numbered(tmp_path):
    # a link with one pin (the slider's block) is numbered off its pin: 'draw models/motion_slider_crank.toml' (and any
    # slider dimension --save wrote) ended in a TypeError there
    out = tmp_path / "slider.svg"
    assert main(["draw", str(ROOT / "models" / "motion_slider_crank.toml"), "--out", str(out)]) == 0
    svg = out.read_text()
    assert len(_pins(svg)) == 3 and all(f">{link}</text>" in svg for link in range(4))


def test_row_goes_with_a_file_of_rows_alone(saved, tmp_path, capsys):
    """--row picks a row of an atlas search's rows: with a chain, an atlas or a file of one linkage it is refused
    in one sentence (exit 2), by draw, move and balance linkage alike."""
    out, chain, alone = str(tmp_path / "x.png"), "0-1 1-2 2-3 3-0", "holds one linkage: give it without --row"
    for command, words in ((["draw", "--chain", chain, "--row", "1", "--out", out], "not a chain or an atlas"),
                           (["move", "--chain", chain, "--frame", "0", "--row", "1", "--range"], "not --chain"),
                           (["draw", str(saved), "--row", "1", "--out", out], alone),
                           (["move", str(saved), "--row", "1", "--range"], alone),
                           (["balance", "linkage", str(saved), "--row", "1", "--density", "2"], alone),
                           (["dimension", str(ROOT / "models" / "dimension_path.csv"), "--mechanism", chain, "--frame",
                             "0", "--row", "1"], "it goes with --linkage ROWS.json")):
        assert main(command) == 2
        err = capsys.readouterr().err
        assert words in err and err.count("\n") == 1, err
