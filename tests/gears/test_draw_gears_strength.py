"""A gear train's functional schematic, part by part, against values worked out by hand: each axis's
height, each link's shaft level (concentric shafts a little apart, the frame lowest), each gear bar
from its shaft to its pitch point (with tooth numbers, pitch radii in the ratio of the teeth), the
ring's bracket, the carrier's arm, the frame's hatching, the link numbers left of the shafts, the
legend, captions and sheets; read from the matplotlib artists (Agg, nothing written)."""

from __future__ import annotations

import numpy as np
import pytest

from synth.draw import _gears
from synth.draw._gears import _axis_heights, _caption, _draw_on, _label_places, schematic, sheet_figure, svg_text
from synth.errors import InvalidOption
from synth.gears import GearTrain

#: a simple planetary train: sun 1 and carrier 2 on the frame's axis, planet 3 on the carrier, ring 0 the frame
PLANETARY = GearTrain.parse("0-1-2 2-3 0~3i 1~3", frame=0)
#: three parallel axes on the frame: a spur chain 1 ~ 2 ~ 3 ~ 4 with 1 and 4 coaxial
SPUR_CHAIN = GearTrain.parse("0-1-4 0-2 0-3 1~2 2~3 3~4", frame=0)


@pytest.fixture(autouse=True)
def _close():
    import matplotlib

    matplotlib.use("Agg")
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def _axes(train, teeth=None, compound=(), title="t"):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    _draw_on(ax, train, teeth, compound, title)
    return fig, ax


def test_axis_heights_by_hand():
    # the frame's axis is the main one, at 0; an axis held by a carrier 2 above it; two axes held side by
    # side by the same carrier are staggered by 0.9
    assert _axis_heights(PLANETARY) == {0: 0.0, 1: 2.0}
    assert _axis_heights(SPUR_CHAIN) == {0: 0.0, 1: 2.0, 2: 2.9}
    # without a frame the axis with most links is the main one (the first of equals)
    free = GearTrain.parse("0-1 0-2-3 1~2 2~3@0")
    assert free.frame is None and _axis_heights(free) == {1: 0.0, 0: 2.0}
    assert _axis_heights(GearTrain.parse("0-1 0-2 1~2")) == {0: 0.0, 1: 2.0}
    # the frame's axis wins over a longer one
    assert _axis_heights(GearTrain.parse("0-1 0-2-3 1~2 2~3@0", frame=1)) == {0: 0.0, 1: 2.0}


def test_the_planetary_schematic_by_hand():
    s = schematic(PLANETARY)
    # sun 1 on the main axis at 0, carrier 2 and frame 0 concentric below it (0.16 apart, the frame lowest);
    # the planet 3 on the carrier's axis, 2 up
    assert {x: s["shafts"][x]["y"] for x in range(4)} == pytest.approx({1: 0.0, 2: -0.16, 0: -0.32, 3: 2.0})
    # one column at x = 1 (the planet, meshing two gears: a bar 0.18 + 0.3 wide, centred between them);
    # its pitch radius without teeth: 0.4 of the nearer axis distance (2.0 to the sun, 2.32 to the ring)
    planet, ring, sun = s["gears"]
    assert planet == pytest.approx({"link": 3, "x": 1.15, "from": 1.2, "to": 2.8, "ring": False, "width": 0.48,
                                    "label": None})
    assert ring == pytest.approx({"link": 0, "x": 1.0, "from": -0.32, "to": 2.8, "ring": True, "label": None})
    assert sun == pytest.approx({"link": 1, "x": 1.3, "from": 0.0, "to": 1.2, "ring": False, "label": None})
    # the carrier's arm half a unit left of the column, from its shaft up to the planet's axis
    assert s["arms"] == [pytest.approx({"link": 2, "x": 0.5, "from": -0.16, "to": 2.0})]
    # each shaft reaches 0.3 past the outermost bar or arm on it
    assert np.allclose([(x, v["from"], v["to"]) for x, v in sorted(s["shafts"].items())],
                       [(0, 0.7, 1.3), (1, 1.0, 1.6), (2, 0.2, 0.8), (3, 0.2, 1.3)])


def test_a_gear_on_no_axis_is_drawn_one_gap_above_its_carrier():
    # wheel 2 meshes the frame 0 and is carried by link 1, but no axis holds it: it sits 0.16 above link 1's shaft
    s = schematic(GearTrain.parse("0-1 0~2@1", frame=0))
    assert {x: v["y"] for x, v in s["shafts"].items()} == pytest.approx({0: -0.16, 1: 0.0, 2: 0.16})
    # wheel 2 is carried by wheel 3, itself on no axis and not yet placed: one gap above the main level; wheel 3
    # one gap above its carrier 1 (a link in no axis and no mesh is no train: refused by GearTrain)
    s = schematic(GearTrain.parse("0-1 1~2@3 2~3@1 0~3@1"))
    assert {x: v["y"] for x, v in s["shafts"].items()} == pytest.approx({0: 0.0, 1: -0.16, 2: 0.16, 3: 0.0})


def test_three_axes_staggered_and_two_columns_by_hand():
    s = schematic(SPUR_CHAIN)
    levels = {x: v["y"] for x, v in s["shafts"].items()}
    assert levels == pytest.approx({1: 0.0, 4: -0.16, 0: -0.32, 2: 2.0, 3: 2.9})
    # column 1 (wheel 2 over 1) at x = 1, column 2 (wheel 3 over 2 and 4) at 1 + 1.3 (a column of one mesh is
    # 1.3 wide); radii 0.4 × the least axis distance: 0.8, then 0.4 × 0.9 = 0.36
    bars = [(g["link"], g["x"], g["from"], g["to"]) for g in s["gears"]]
    assert np.allclose(bars, [(2, 1.0, 1.2, 2.8), (1, 1.0, 0.0, 1.2),
                              (3, 2.45, 2.54, 3.26), (2, 2.3, 2.0, 2.54), (4, 2.6, -0.16, 2.54)])
    assert np.allclose([(a["link"], a["x"], a["from"], a["to"]) for a in s["arms"]],
                       [(0, 0.5, -0.32, 2.0), (0, 1.8, -0.32, 2.9)])


def test_tooth_numbers_set_the_pitch_radii_and_label_the_wheels():
    teeth = {"z1": 20, "z3": 30, "z0": 80}
    s = schematic(PLANETARY, teeth)
    planet, ring, sun = s["gears"]
    # the planet's pitch radius r3 against the sun over an axis distance of 2: r1 + r3 = 2, r3 / r1 = 30 / 20;
    # against the ring over 2.32: r0 − r3 = 2.32, r0 / r3 = 80 / 30; the bar takes the smaller (1.2 < 1.392)
    r3 = 2.0 * 30 / (20 + 30)
    assert r3 < 2.32 * 30 / (80 - 30)
    assert (planet["from"], planet["to"]) == pytest.approx((2.0 - r3, 2.0 + r3))
    assert sun["to"] - sun["from"] == pytest.approx(r3 * 20 / 30)  # the sun reaches the pitch point
    assert ring["to"] == pytest.approx(2.0 + r3)
    assert [g["label"] for g in s["gears"]] == ["z3=30", "z0=80", "z1=20"]
    # a compound link's wheels: one per mesh, each named after its mate, and each its own column
    compound = schematic(PLANETARY, {"z1": 20, "z3_0": 31, "z3_1": 29, "z0": 80}, compound=(3,))
    assert [(g["link"], g["label"]) for g in compound["gears"]] == [(3, "z3_0=31"), (0, "z0=80"),
                                                                     (3, "z3_1=29"), (1, "z1=20")]
    first, _, second, _ = compound["gears"]
    assert second["x"] - first["x"] == pytest.approx(1.3)  # two columns of one mesh each
    # ring column: r3 = 2.32 × 31 / (80 − 31); sun column: r3 = 2 × 29 / (20 + 29)
    assert first["to"] - first["from"] == pytest.approx(2 * 2.32 * 31 / 49)
    assert second["to"] - second["from"] == pytest.approx(2 * 2.0 * 29 / 49)


def _colour(artist):
    from matplotlib.colors import to_hex

    getter = getattr(artist, "get_color", None) or artist.get_facecolor
    return to_hex(getter())


def test_the_drawing_puts_each_part_where_the_schematic_says():
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_hex

    tab = [to_hex(c) for c in plt.get_cmap("tab10").colors]
    colour = {0: "#000000", 1: tab[1], 2: tab[2], 3: tab[3]}
    teeth = {"z1": 20, "z3": 30, "z0": 80}
    fig, ax = _axes(PLANETARY, teeth, title="a planetary train")
    s = schematic(PLANETARY, teeth)
    lines = [(tuple(np.round(line.get_xdata(), 6)), tuple(np.round(line.get_ydata(), 6)), line) for line in ax.lines]

    def line(xs, ys):
        found = [ln for x, y, ln in lines if len(x) == len(xs) and np.allclose(x, xs) and np.allclose(y, ys)]
        assert len(found) == 1, (xs, ys)
        return found[0]

    for x, shaft in s["shafts"].items():  # a thick line in the link's colour
        drawn = line([shaft["from"], shaft["to"]], [shaft["y"]] * 2)
        assert drawn.get_linewidth() == 2.2 and _colour(drawn) == colour[x]
    # the frame's ground: a line 0.12 under its shaft and a hatch stroke every 0.15 along it
    frame = s["shafts"][0]
    ground = line([frame["from"], frame["to"]], [frame["y"] - 0.12] * 2)
    assert _colour(ground) == "#000000" and ground.get_linewidth() == 1
    strokes = [ln for x, y, ln in lines if len(y) == 2 and np.allclose(y, [frame["y"] - 0.12, frame["y"] - 0.24])]
    starts = sorted(ln.get_xdata()[0] for ln in strokes)
    assert len(strokes) == int(round((frame["to"] - frame["from"]) / 0.15)) + 1 == 5
    assert np.allclose(starts, frame["from"] + 0.15 * np.arange(5))
    assert all(np.isclose(ln.get_xdata()[0] - ln.get_xdata()[1], 0.1) for ln in strokes)
    assert all(ln.get_linewidth() == 0.8 and _colour(ln) == "#000000" for ln in strokes)
    # the carrier's arm: a vertical line in its colour
    arm = s["arms"][0]
    assert _colour(line([arm["x"]] * 2, [arm["from"], arm["to"]])) == colour[2]
    # the ring: a bracket from its shaft up past the planet and back over it, with a bar on top
    ring = s["gears"][1]
    bracket = line([ring["x"] + 0.3, ring["x"] + 0.3, ring["x"] - 0.12], [ring["from"], ring["to"] + 0.06,
                                                                         ring["to"] + 0.06])
    assert _colour(bracket) == "#000000"
    rectangles = [p for p in ax.patches if type(p).__name__ == "Rectangle"]
    top = [p for p in rectangles if np.allclose(p.get_xy(), (ring["x"] - 0.12, ring["to"] + 0.06))]
    assert len(top) == 1 and top[0].get_width() == pytest.approx(0.42) and top[0].get_height() == pytest.approx(0.14)
    # each external wheel: a bar of its width from its shaft to its pitch point, in its colour
    for gear in (s["gears"][0], s["gears"][2]):
        w = gear.get("width", 0.18)
        (bar,) = [p for p in rectangles if np.allclose(p.get_xy(), (gear["x"] - w / 2, min(gear["from"], gear["to"])))]
        assert bar.get_width() == pytest.approx(w) and bar.get_height() == pytest.approx(abs(gear["to"] - gear["from"]))
        assert to_hex(bar.get_facecolor()) == to_hex(bar.get_edgecolor()) == colour[gear["link"]]
        assert bar.get_alpha() == 0.85
    assert len(rectangles) == 3
    # tooth numbers beside their wheels, the ring's over its bracket
    texts = {t.get_text(): t for t in ax.texts}
    planet, sun = s["gears"][0], s["gears"][2]
    assert texts["z3=30"].get_position() == pytest.approx((planet["x"] + 0.3 + 0.08, 2.0))
    assert texts["z1=20"].get_position() == pytest.approx((sun["x"] + 0.3 + 0.08, (sun["from"] + sun["to"]) / 2))
    assert texts["z0=80"].get_position() == pytest.approx((ring["x"] + 0.36, ring["to"] + 0.13))
    assert _colour(texts["z3=30"]) == colour[3] and _colour(texts["z0=80"]) == "#000000"
    # the link numbers, left of every shaft, in the link's colour, with a dotted leader to the shaft
    left = min(v["from"] for v in s["shafts"].values())
    for x, shaft in s["shafts"].items():
        at, y = texts[str(x)].get_position()
        assert at == pytest.approx(left - 0.2) and _colour(texts[str(x)]) == colour[x]
        leader = line([at + 0.04, shaft["from"]], [y, shaft["y"]])
        assert leader.get_linestyle() == ":"
    assert len(ax.texts) == 4 + 3
    assert ax.get_title() == "a planetary train" and not ax.axison and ax.get_aspect() == 1.0


def test_a_wheel_of_several_meshes_is_labelled_clear_of_its_bar():
    teeth = {"z1": 20, "z2": 40, "z3": 18, "z4": 25}
    fig, ax = _axes(SPUR_CHAIN, teeth)
    wheel = schematic(SPUR_CHAIN, teeth)["gears"][2]  # wheel 3 over 2 and 4: 0.48 wide, its label 0.3 + 0.08 right
    assert wheel["width"] == pytest.approx(0.48)
    text = next(t for t in ax.texts if t.get_text() == "z3=18")
    assert text.get_position() == pytest.approx((wheel["x"] + 0.38, (wheel["from"] + wheel["to"]) / 2))
    # wheel 4, highest, over 1, 2 and 3 (one column of three meshes): 0.78 wide, its label 0.39 + 0.08 right
    star = GearTrain.parse("0-1 0-2 0-3 0-4 1~4 2~4 3~4", frame=0)
    fig, ax = _axes(star, {"z1": 20, "z2": 21, "z3": 22, "z4": 30})
    wheel = schematic(star, {"z1": 20, "z2": 21, "z3": 22, "z4": 30})["gears"][0]
    assert wheel["link"] == 4 and wheel["width"] == pytest.approx(0.78)
    text = next(t for t in ax.texts if t.get_text() == "z4=30")
    assert text.get_position() == pytest.approx((wheel["x"] + 0.39 + 0.08, (wheel["from"] + wheel["to"]) / 2))
    # no frame given: nothing hatched, nothing drawn black
    fig, ax = _axes(GearTrain.parse("0-1 0-2 1~2"))
    assert not [ln for ln in ax.lines if _colour(ln) == "#000000"]


def test_link_numbers_of_concentric_shafts_spread_a_line_apart():
    s = schematic(SPUR_CHAIN)
    places = _label_places(s["shafts"], 0.2, 0.3)
    # from the lowest shaft up: 0 (−0.32), 4 (−0.16), 1 (0) are nearer than a line (0.3): one run a line apart
    # about their mean −0.16; 2 (2.0) and 3 (2.9) are far apart: at their shafts; all in one column
    assert np.allclose(places, [(0, 0.0, -0.46), (4, 0.0, -0.16), (1, 0.0, 0.14), (2, 0.0, 2.0), (3, 0.0, 2.9)])
    # exactly a line apart is far enough
    assert [y for *_, y in _label_places({0: {"y": 0.0}, 1: {"y": 0.45}}, 1.0, 0.45)] == pytest.approx([0.0, 0.45])
    # a run spread about its mean that comes too near the one below joins it: 1 and 2 first, then 0
    spread = _label_places({0: {"y": 0.0}, 1: {"y": 0.5}, 2: {"y": 0.55}}, 1.0, 0.5)
    assert [y for *_, y in spread] == pytest.approx([-0.15, 0.35, 0.85])


def test_link_numbers_never_overlap_on_the_small_inline_drawing():
    """The site's schematics (2.6 in wide): the numbers of concentric shafts, once stepped left by a fixed
    0.3, overprinted each other (154 pairs over the 81 six-link trains); now a text line apart as drawn."""
    import matplotlib.pyplot as plt

    from synth.gears import trains

    for train in list(trains(1, 6))[::4]:
        fig, ax = plt.subplots(figsize=(2.6, 2.6 * 0.75))
        _draw_on(ax, train, None, (), "")
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        numbers = [t.get_window_extent(renderer) for t in ax.texts if t.get_text().isdigit()]
        assert len(numbers) == 6 and not any(a.overlaps(b) for i, a in enumerate(numbers) for b in numbers[i + 1:])
        plt.close(fig)


def _legend_labels(fig):
    (legend,) = fig.legends
    return [t.get_text() for t in legend.get_texts()], legend


def test_a_single_schematic_has_its_size_caption_and_legend(tmp_path, monkeypatch):
    saved = []
    monkeypatch.setattr(_gears, "_save", lambda fig, path, dpi: saved.append((fig, path, dpi)))
    _gears.draw_train(PLANETARY, tmp_path / "p.svg", size=4.0)
    ((fig, path, dpi),) = saved
    assert path == tmp_path / "p.svg" and dpi == 110
    assert tuple(fig.get_size_inches()) == pytest.approx((4.0, 3.6))
    assert fig.axes[0].get_title() == "0-1-2 2-3 0~3i 1~3  (frame 0)" == _caption(PLANETARY)
    labels, legend = _legend_labels(fig)
    assert labels == ["shaft (its link's number on the left)", "gear wheel (bar: its pitch diameter)",
                      "ring gear (bracket over its pinion)", "carrier arm", "frame (black, hatched)"]
    assert legend._ncols == 3 and not legend.get_frame_on()  # plain, under the drawing
    assert legend._loc == 8 and tuple(legend.get_bbox_to_anchor().transformed(fig.transFigure.inverted()).p0) == \
        pytest.approx((0.5, 0.0))
    # the symbols as drawn: a thick grey shaft, a grey bar, a ring's bracket end (a dash), a carrier's arm (a bar)
    shaft, wheel, ring, arm, frame = legend.legend_handles
    assert [(h.get_marker(), h.get_markersize()) for h in (ring, arm)] == [("_", 10), ("|", 10)]
    assert arm.get_linestyle() == "None"
    assert shaft.get_linewidth() == ring.get_linewidth() == frame.get_linewidth() == 2.2
    assert _colour(frame) == "#000000" and _colour(shaft) == "#808080" and wheel.get_alpha() == 0.85
    assert fig.subplotpars.bottom == pytest.approx(0.6 / 3.6 + 0.04)
    saved.clear()
    _gears.draw_train(GearTrain.parse("0-1 0-2 1~2"), tmp_path / "q.png", title="two wheels")
    ((fig, _, _),) = saved
    labels, legend = _legend_labels(fig)
    assert len(labels) == 4 and legend._ncols == 2 and fig.axes[0].get_title() == "two wheels"
    assert tuple(fig.get_size_inches()) == pytest.approx((6.0, 5.1))
    assert _caption(GearTrain.parse("0-1 0-2 1~2")) == "0-1 0-2 1~2"


def test_sheets_hold_their_trains_in_a_grid_with_wrapped_captions(tmp_path, monkeypatch):
    trains = [PLANETARY, SPUR_CHAIN, GearTrain.parse("0-1 0-2 1~2"), PLANETARY, SPUR_CHAIN]
    fig = sheet_figure(trains, columns=2)
    assert len(fig.axes) == 5  # 3 rows of 2, the sixth cell removed
    assert tuple(fig.get_size_inches()) == pytest.approx((2 * 3.6, 3 * 3.4 + 0.5))
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[0] == "1: 0-1-2 2-3 0~3i 1~3  (frame 0)"
    # wrapped at 39 characters a line (3.6 inches at 11 an inch)
    assert titles[1] == "2: 0-1-4 0-2 0-3 1~2 2~3 3~4  (frame 0)" and len(titles[1]) == 39
    assert all(max(len(line) for line in t.split("\n")) <= 39 for t in titles)
    assert all(ax.title.get_fontsize() == 8 for ax in fig.axes)
    labels, _ = _legend_labels(fig)
    assert labels[-1] == "frame (black, hatched)"
    fig = sheet_figure([GearTrain.parse("0-1 0-2 1~2")] * 3, titles=["a", "b", "c"])
    assert [ax.get_title() for ax in fig.axes] == ["a", "b", "c"]
    assert tuple(fig.get_size_inches()) == pytest.approx((3 * 3.6, 3.4 + 0.5))  # fewer trains than columns
    assert len(_legend_labels(fig)[0]) == 4  # no frame: no frame in the legend
    long = GearTrain.parse("0-1-2-3-4-5 0-6 0-7 1~6 6~7 7~2 3~5@0 4~6")
    title = sheet_figure([long], columns=1).axes[0].get_title()
    assert "\n" in title and title.replace("\n", " ") == f"1: {_caption(long)}"
    saved = []
    monkeypatch.setattr(_gears, "_save", lambda fig, path, dpi: saved.append((fig, path, dpi)))
    assert _gears.draw_train_sheet(trains, tmp_path / "s.pdf", limit=5) == 5
    ((fig, path, dpi),) = saved
    assert dpi == 90 and len(fig.axes) == 5 and fig.axes[4].get_title().startswith("5: ")
    assert _gears.draw_train_sheet([], tmp_path / "e.png") == 0 and len(saved) == 1
    assert _gears.draw_train_sheet(trains, tmp_path / "t.png", columns=2) == 5
    assert tuple(saved[-1][0].get_size_inches()) == pytest.approx((2 * 3.6, 3 * 3.4 + 0.5))  # 3 rows of 2
    saved.pop()
    with pytest.raises(InvalidOption) as e:
        _gears.draw_train_sheet(trains, tmp_path / "s.png", limit=4)
    assert str(e.value) == "5 trains are more than the 4 a sheet holds here: select fewer"
    assert len(saved) == 1


@pytest.mark.parametrize("name, sentence", [
    ("x.gif", "a drawing is written as .svg, .png, .pdf, not .gif"),
    ("x", "a drawing is written as .svg, .png, .pdf, not no extension"),
])
def test_a_drawing_of_another_format_is_refused(tmp_path, name, sentence):
    for call in (lambda: _gears.draw_train(PLANETARY, tmp_path / name),
                 lambda: _gears.draw_train_sheet([PLANETARY], tmp_path / name)):
        with pytest.raises(InvalidOption) as e:
            call()
        assert str(e.value) == sentence
    assert not list(tmp_path.iterdir())


def test_files_are_written_and_an_unwritable_path_is_one_sentence(tmp_path):
    out = tmp_path / "P.SVG"  # the suffix in capitals is still SVG
    _gears.draw_train(PLANETARY, out)
    text = out.read_text()
    assert text.startswith("<?xml") and ">0-1-2 2-3 0~3i 1~3  (frame 0)</text>" in text  # SVG text stays text
    with pytest.raises(InvalidOption) as e:
        _gears.draw_train(PLANETARY, tmp_path / "none" / "p.png")
    assert str(e.value) == f"cannot write {tmp_path / 'none' / 'p.png'}: No such file or directory"
    import matplotlib.pyplot as plt

    assert not plt.get_fignums()  # the figure is closed after a failed write too


def test_the_inline_svg_is_the_untitled_drawing_and_deterministic():
    import re

    text = svg_text(PLANETARY)
    assert text.startswith("<svg") and text == svg_text(PLANETARY)
    # its only texts are the link numbers, bottom to top 0, 2, 1 (concentric: a 10-point line apart) and 3, in a
    # column; no title
    texts = re.findall(r'<text style="([^"]*)" x="([\d.]+)" y="([\d.]+)"[^>]*>([^<]*)</text>', text)
    assert [label for *_, label in sorted(texts, key=lambda t: -float(t[2]))] == ["0", "2", "1", "3"]
    xs, ys = ({label: float(t[k]) for *t, label in texts} for k in (1, 2))
    assert xs["0"] == pytest.approx(xs["3"]) == pytest.approx(xs["2"]) == pytest.approx(xs["1"])
    assert ys["0"] - ys["2"] >= 10 and ys["2"] - ys["1"] >= 10
    assert "fill: #ff7f0e" in texts[[t[3] for t in texts].index("1")][0]
    width = float(re.search(r'width="([\d.]+)pt"', text).group(1))
    assert width <= 2.6 * 72  # cut to the drawing, never wider than asked
    import matplotlib.pyplot as plt

    assert not plt.get_fignums()
