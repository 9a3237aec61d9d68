"""A moving mechanism's picture, element by element, against values worked out by hand: each link placed
where the solver put its joints at every frame, link bodies by kind and input, pins and the multiple
joint's ring, ground pivots, gears' pitch circles from their tooth numbers, tracer dots and names; the
canvas's pixels, the still, animated and player SVG texts, the matplotlib artists of a PNG, the refusals;
and the score a pose from a drawing gets, against Freudenstein's transmission angles."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from synth.errors import InvalidOption, MotionError
from synth.motion import Linkage, read_linkage, sweep
from synth.motion_draw import (_EDGE, _FRAME, _INPUT, _Canvas, _elements, _frames, _grid_lines, _how_well, _order,
                               _Placement, _still, _svg, animate_motion, draw_motion, linkage_from_layout,
                               linkage_svg, motion_svg, player_svg)
from synth.structure.chain import Chain, Mechanism

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR_CHAIN = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)  # joints 0-1, 0-3, 1-2, 2-3


def _four_bar(a=1.0, b=3.5, c=3.0, d=4.0, crank=math.pi / 2, **options):
    """A four-bar with ground O2 = (0, 0) to O4 = (d, 0), crank a at ``crank``, coupler b, rocker c
    (its upper assembly), built from the lengths by hand."""
    A = np.array([a * math.cos(crank), a * math.sin(crank)])
    e = math.dist(A, (d, 0))
    along = (b * b - c * c + e * e) / (2 * e)  # from A towards O4: the foot of B
    up = math.sqrt(b * b - along * along)
    u = (np.array([d, 0]) - A) / e
    B = A + along * u + up * np.array([-u[1], u[0]])
    return Linkage(FOUR_BAR_CHAIN, (0,), [[0, 0], [d, 0], A, B], **options)


def _transmission_worst(a, b, c, d):
    """The worst transmission angle of a crank-rocker over a turn: cos μ = (b² + c² − e²)/(2bc), e from d − a
    to d + a."""
    angles = [math.acos((b * b + c * c - e * e) / (2 * b * c)) for e in (d - a, d + a)]
    return min(min(angles), math.pi - max(angles))


def test_a_pose_is_scored_by_its_worst_transmission_angle():
    score, why, measured = _how_well(_four_bar())
    assert why is None and score[:2] == (True, True) and score[3] == pytest.approx(2 * math.pi)
    assert measured == pytest.approx(_transmission_worst(1, 3.5, 3, 4), abs=1e-9)  # the note's, unrounded
    assert score[2] == pytest.approx(_transmission_worst(1, 3.5, 3, 4), abs=1e-3)  # 54.31°
    # a crank 1.95 long: the coupler and rocker nearly stretch out, μ reaches 165.2°: 14.8° short of a line
    score, why, _ = _how_well(_four_bar(a=1.95, b=3, c=3))
    worst = _transmission_worst(1.95, 3, 3, 4)
    assert score[:2] == (False, True) and score[2] == pytest.approx(worst, abs=1e-3)
    assert why == f"a transmission angle falls to {math.degrees(worst):.2g}°" == "a transmission angle falls to 15°"
    # a crank 1.9 long keeps 20.9°: just above the 20° a pose needs to move well
    assert math.degrees(_transmission_worst(1.9, 3, 3, 4)) > 20 and _how_well(_four_bar(a=1.9, b=3, c=3))[0][0]


def test_a_rocker_input_is_scored_by_its_swing():
    # the same crank-rocker driven at its rocker (joint 0-3): the rocker swings between the poses where crank and
    # coupler are in line, |O2 B| = b − a and b + a, B = O4 + c (cos φ, sin φ): |O2 B|² = d² + c² + 2dc cos φ
    lk = _four_bar()
    rocker = Linkage(FOUR_BAR_CHAIN, (1,), lk.points)
    score, why, measured = _how_well(rocker)
    assert measured is None  # a rocker's transmission angles are not what its pose is scored by
    phi = [math.acos(((b_a) ** 2 - 16 - 9) / 24) for b_a in (3.5 - 1, 3.5 + 1)]
    assert score[:3] == (False, False, 0.0) and why == "its input does not turn fully"
    assert score[3] == pytest.approx(phi[0] - phi[1], abs=1e-6)


def test_each_link_is_placed_where_the_solver_put_its_joints():
    lk = read_linkage(ROOT / "models" / "motion_four_bar.toml")
    motion = sweep(lk, steps=37)
    place = _Placement(lk, motion.joints, motion.angles)
    assert place.anchor == [0, 0, 2, 1]  # each link's first pin (link 0: the frame)
    for link in range(4):
        on = list(lk.joints_of(link))
        assert np.allclose(place.place(link, lk.points[on]), motion.joints[:, on], atol=1e-9)
    # a tracer point rides on its link: the solver's coupler curve
    (name, (link, at)), = lk.tracers.items()
    assert np.allclose(place.place(link, at)[:, 0], motion.tracers[name], atol=1e-9)
    # the frame never moves, whatever its angles say
    assert np.allclose(place.place(0, [[7.0, -1.0]]), [[7.0, -1.0]])


def _by(elements, tag, **style):
    return [e for e in elements if e["tag"] == tag and all(e["style"].get(k.replace("_", "-")) == v
                                                           for k, v in style.items())]


def test_a_four_bars_elements_by_kind():
    lk = _four_bar(tracers={"P": (2, (2.5, 4.5))})
    pin = 0.018 * lk.scale
    assert lk.scale == 4.0
    elements = _elements(lk, *_still(lk), {})
    O2, O4, A, B = lk.points
    # the crank (the input link) a thick bar in the input's colour, the rocker in the links' colour
    (crank,) = _by(elements, "polyline", stroke=_INPUT, stroke_width=3.2)
    assert sorted(map(tuple, crank["frames"][0])) == sorted([tuple(O2), tuple(A)])
    (rocker,) = _by(elements, "polyline", stroke=_EDGE, stroke_width=3.2)
    assert sorted(map(tuple, rocker["frames"][0])) == sorted([tuple(O4), tuple(B)])
    # the coupler carries the tracer: a plate through A, B and P
    (plate,) = _by(elements, "polygon", stroke=_EDGE)  # its outline, and its fill under the pins' paths
    (fill,) = _by(elements, "polygon", fill="#dbe6f4")
    assert plate["style"]["fill"] == "none" and fill["style"]["stroke"] == "none"
    assert np.array_equal(fill["frames"], plate["frames"])
    assert [e is fill for e in elements].index(True) < [e is plate for e in elements].index(True)
    assert sorted(map(tuple, np.round(plate["frames"][0], 9))) == sorted(map(tuple, np.round([A, B, (2.5, 4.5)], 9)))
    # the frame: a dashed line O2 O4, a triangle and a base line under each pivot
    (base,) = _by(elements, "polyline", stroke_dasharray="6 4")
    assert base["static"] and sorted(map(tuple, base["frames"][0])) == [(0.0, 0.0), (4.0, 0.0)]
    w = 2.6 * pin
    supports = _by(elements, "polygon", fill="#eef1f4")
    assert [s["frames"][0].tolist() for s in supports] == [
        [[x, 0.0], [x - w, -1.8 * w], [x + w, -1.8 * w]] for x in (0.0, 4.0)]
    feet = _by(elements, "polyline", stroke=_FRAME, stroke_width=2.4)
    assert np.allclose([f["frames"][0] for f in feet], [[[x - 1.6 * w, -1.8 * w], [x + 1.6 * w, -1.8 * w]]
                                                        for x in (0.0, 4.0)])
    # five strokes hatched under each base (marking the pivot fixed), from the base down-left, 0.64 w apart
    hatch = _by(elements, "polyline", stroke=_FRAME, stroke_width=1.2)
    assert np.allclose([h["frames"][0] for h in hatch],
                       [[[x - 1.6 * w + (i + 1) * 0.64 * w, -1.8 * w], [x - 1.6 * w + i * 0.64 * w, -2.3 * w]]
                        for x in (0.0, 4.0) for i in range(5)])
    # four pins where the joints are, the tracer's dot and name beside it
    pins = _by(elements, "circle", fill="white")
    assert [p["r"] for p in pins] == pytest.approx([pin] * 4)
    assert np.allclose([p["frames"][0, 0] for p in pins], lk.points)
    assert all(p["style"]["stroke"] == "black" for p in pins)
    (dot,) = _by(elements, "circle", fill="#c0392b")
    (name,) = _by(elements, "text")
    assert dot["r"] == pytest.approx(0.8 * pin) and np.allclose(dot["frames"][0, 0], (2.5, 4.5))
    assert name["text"] == "P" and np.allclose(name["frames"][0, 0], (2.5 + 1.6 * pin, 4.5 + 1.6 * pin))
    assert len(elements) == 3 + 1 + 1 + 4 + 4 + 10 + 2
    # the draw order: links under the frame's signs, pins over them, the tracer on top
    assert [e["tag"] for e in elements][-6:] == ["circle"] * 5 + ["text"]


def test_a_multiple_joint_gets_a_ring_and_gears_their_pitch_circles():
    lk = read_linkage(ROOT / "models" / "motion_planetary_willis.toml")  # teeth 72 (ring), 30 (sun), 21 (planet)
    pin = 0.018 * lk.scale
    elements = _elements(lk, *_still(lk), {})
    circles = _by(elements, "circle", stroke="#1e7a46")
    # a pitch circle per gear of each mesh, about its axis, of radius module × teeth / 2 (the module is 2 here)
    assert sorted((float(c["frames"][0, 0, 1]), c["r"]) for c in circles) == pytest.approx(
        sorted([(0.0, 72.0), (51.0, 21.0), (0.0, 30.0), (51.0, 21.0)]))
    spokes = _by(elements, "polyline", stroke="#1e7a46")
    assert sorted(s["frames"][0, :, 1].tolist() for s in spokes) == [[0.0, 30.0], [0.0, 72.0], [51.0, 30.0],
                                                                    [51.0, 72.0]]
    # the central axis 0-1-3 joins three links: a larger pin ringed in red
    pins = _by(elements, "circle", fill="white")
    assert [(p["r"], p["style"]["stroke"]) for p in pins] == [(pytest.approx(1.6 * pin), "#c0392b"),
                                                              (pytest.approx(pin), "black")]


def test_the_canvas_by_hand():
    elements = [{"tag": "polyline", "frames": np.array([[[0.0, 0.0], [10.0, 5.0]]]), "style": {}},
                {"tag": "circle", "r": 1.0, "frames": np.array([[[10.0, 5.0]], [[np.nan, np.nan]]]), "style": {}}]
    canvas = _Canvas(elements, 120)
    # the box 0 … 11 by 0 … 6 (the circle whole, its radius about its own centre only), span 11, margins
    # 0.66: 120 px over 12.32
    scale = 120 / 12.32
    assert canvas.scale == pytest.approx(scale)
    assert (canvas.width, canvas.height) == (120, math.ceil(7.32 * scale))
    assert np.allclose(canvas.lo, (-0.66, -0.66))
    assert np.allclose(canvas.pixels(np.array([[0.0, 0.0], [11.66, 6.66]])),
                       [[0.66 * scale, canvas.height - 0.66 * scale], [12.32 * scale, canvas.height - 7.32 * scale]])


def test_still_animated_and_player_svgs_by_hand():
    frames = np.array([[[0.0, 0.0], [1.0, 0.0]], [[0.0, 0.0], [0.0, 1.0]], [[0.0, 0.0], [-1.0, 0.0]]])
    elements = [{"tag": "polyline", "frames": frames, "style": {"stroke": "red", "fill": "none", "x": None}},
                {"tag": "circle", "r": 0.1, "frames": frames[:, 1:], "style": {"stroke": "black"}},
                {"tag": "text", "text": "P<1>", "frames": frames[:, 1:], "style": {"fill": "blue"}},
                {"tag": "polygon", "frames": frames[:1], "static": True, "style": {"stroke": "grey"}}]
    canvas = _Canvas(elements, 100)

    def px(points):
        return " ".join(f"{x:.1f},{y:.1f}" for x, y in canvas.pixels(np.array(points, dtype=float)))

    still = _svg(elements, canvas, 1, title="a & b")
    w, h = canvas.width, canvas.height
    cx, cy = canvas.pixels(frames[1, 1])
    assert still == (f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">'
                     f"<title>a &amp; b</title>"
                     f'<polyline points="{px(frames[1])}" stroke="red" fill="none"/>'
                     f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="{0.1 * canvas.scale:.1f}" stroke="black"/>'
                     f'<text x="{cx:.1f}" y="{cy:.1f}" fill="blue">P&lt;1&gt;</text>'
                     f'<polygon points="{px(frames[0])}" stroke="grey"/></svg>')
    moving = _svg(elements, canvas, None, seconds=2.5)
    values = re.findall(r'<animate attributeName="(\w+)" dur="2.50s" repeatCount="indefinite" values="([^"]*)"/>',
                        moving)
    xs = ";".join(f"{x:.1f}" for x, _ in canvas.pixels(frames[:, 1]))
    ys = ";".join(f"{y:.1f}" for _, y in canvas.pixels(frames[:, 1]))
    assert values == [("points", ";".join(px(f) for f in frames)), ("cx", xs), ("cy", ys), ("x", xs), ("y", ys)]
    assert "<title>" not in moving and f'<polygon points="{px(frames[0])}" stroke="grey"/>' in moving
    player = _svg(elements, canvas, 0, player=True)
    data = json.loads(re.search(r'data-motion="([^"]+)"', player).group(1).replace("&quot;", '"'))
    assert data["n"] == 3 and len(data["e"]) == 3  # the static polygon is not played
    assert data["e"][1] == [[round(float(v), 1) for v in canvas.pixels(f).ravel()] for f in frames[:, 1:]]
    assert re.findall(r'data-k="(\d)"', player) == ["0", "1", "2"] and "<animate" not in player
    assert player.startswith('<svg xmlns="http://www.w3.org/2000/svg" width="')
    assert 'class="moving" data-motion=' in player
    # nothing moves: n is the frames of the first element
    static = _svg(elements[3:], canvas, 0, player=True)
    assert json.loads(re.search(r'data-motion="([^"]+)"', static).group(1).replace("&quot;", '"')) == {"n": 1, "e": []}


def test_the_writers_put_the_sweep_in_their_frames():
    lk = read_linkage(ROOT / "models" / "motion_four_bar.toml")
    motion = sweep(lk, steps=19)
    assert list(_frames(motion, 5)) == [0, 4, 9, 14, 18] and list(_frames(motion, 40)) == list(range(19))
    svg = player_svg(motion, frames=6, seconds=1.2)
    assert 'data-ms="200"' in svg and "<title>0-1 0-3 1-2 2-3, frame 0, input 0-1</title>" in svg
    data = json.loads(re.search(r'data-motion="([^"]+)"', svg).group(1).replace("&quot;", '"'))
    assert data["n"] == 6
    animated = motion_svg(motion, frames=6, seconds=1.5)
    assert animated.count('dur="1.50s"') > 0 and "repeatCount" in animated
    still = linkage_svg(lk, size=200)
    assert max(int(re.search(r'width="(\d+)"', still).group(1)), int(re.search(r'height="(\d+)"', still).group(1))) \
        in (200, 201)


def test_order_turns_about_the_centre_and_drops_repeats():
    square = np.array([[1.0, 1.0], [-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0], [1.0, 1.0 + 1e-12]])
    assert _order(square) == [1, 2, 0, 3]  # from −135° round; the repeated corner counted once


def test_grid_lines_cut_where_the_branch_does_not_reach():
    grid = np.arange(4 * 3 * 2, dtype=float).reshape(4, 3, 2)
    grid[1, 1] = np.nan
    lines = _grid_lines(grid)
    # along the first axis (3 lines of 4 points): line 1 is cut at its unreached point into runs of 1 and 2 (the
    # run of 1 is not a line); along the second (4 lines of 3): line 1 keeps its first point alone (dropped)
    # and its last (dropped)
    assert [len(x) for x in lines] == [4, 2, 4, 3, 3, 3]
    assert np.array_equal(lines[1], grid[2:, 1])
    assert len(_grid_lines(np.zeros((30, 2, 2)), most=5)) == 2 + 5


def test_a_png_draws_each_element_as_an_artist(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_hex

    figures = []
    monkeypatch.setattr(plt, "close", lambda fig=None: figures.append(fig))
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", lambda self, path, **kw: Path(path).write_bytes(b"png"))
    lk = _four_bar(tracers={"P": (2, (2.5, 4.5))})
    motion = sweep(lk, steps=37)
    draw_motion(motion, tmp_path / "m.png", size=300, marks=[[1.0, 1.0], [2.0, 2.0]], title="a four-bar")
    (fig,) = figures
    ax = fig.axes[0]
    assert fig._suptitle.get_text() == "a four-bar"
    assert tuple(fig.get_size_inches()) == pytest.approx((ax.get_xlim()[1] / 100, ax.get_ylim()[0] / 100 + 0.3))
    circles = [p for p in ax.patches if type(p).__name__ == "Circle"]
    # four pins, the tracer's dot and two target marks
    assert len(circles) == 7
    marks = [c for c in circles if to_hex(c.get_edgecolor()) == "#1f4e9c"]
    assert len(marks) == 2 and all(c.get_facecolor()[3] == 0 for c in marks)
    white = [c for c in circles if to_hex(c.get_facecolor()) == "#ffffff"]
    assert len(white) == 4 and min(c.zorder for c in white) > max(a.zorder for a in [*ax.lines, *ax.patches]
                                                                       if a not in circles)  # pins over the links
    assert marks[0].radius == pytest.approx(white[0].radius * 0.014 / 0.018)  # 0.014 and 0.018 of the size
    length, text = ax.texts  # the scale bar's length (a round one under the drawing: it is to scale), the tracer's name
    assert length.get_text() == "1" and text.get_text() == "P" and to_hex(text.get_color()) == "#c0392b"
    assert text.get_zorder() > max(a.zorder for a in [*ax.lines, *ax.patches])  # over everything
    assert text.get_va() == "bottom" and text.get_fontsize() == 9
    (dot,) = [c for c in circles if to_hex(c.get_facecolor()) == "#c0392b"]
    beside = 1.6 / 0.8 * dot.radius  # the name 1.6 pin radii right of and above the dot (y down in pixels)
    assert text.get_position() == pytest.approx((dot.center[0] + beside, dot.center[1] - beside))
    dashed = [ln for ln in ax.lines if ln.get_linestyle() != "-"]
    assert len(dashed) == 1  # the frame's line O2 O4
    assert ax.get_ylim()[0] > ax.get_ylim()[1] and not ax.axison
    # the paths of the two moving pins (grey) over the coupler's fill and under the links' outlines and bars
    # (the rocker's pin swings under the coupler: it was hidden by its fill), the coupler curve over the links
    grey = [ln for ln in ax.lines if to_hex(ln.get_color()) == "#8f9baa"]
    curve = [ln for ln in ax.lines if to_hex(ln.get_color()) == "#c0392b"]
    (fill,) = [p for p in ax.patches if to_hex(p.get_facecolor()) == "#dbe6f4"]
    (outline,) = [p for p in ax.patches if to_hex(p.get_edgecolor()) == "#1f3a5f" and p.get_facecolor()[3] == 0]
    bars = [ln for ln in ax.lines if ln.get_linewidth() == pytest.approx(3.2 * 0.75)]
    assert len(grey) == 2 and len(bars) == 2
    assert fill.zorder < min(ln.zorder for ln in grey) < max(ln.zorder for ln in grey) < outline.zorder
    assert max(ln.zorder for ln in grey) < min(ln.zorder for ln in bars)
    assert len(curve) == 1 and curve[0].zorder > max(a.zorder for a in [outline, *bars])
    assert len(curve[0].get_xdata()) == 37


def test_refusals_are_one_sentence(tmp_path):
    motion = sweep(_four_bar(), steps=9)
    with pytest.raises(InvalidOption) as e:
        draw_motion(motion, tmp_path / "x.gif")
    assert str(e.value) == ("a picture of a motion is written as PNG or SVG: end the file name in .png or .svg, "
                            "not 'x.gif'")
    with pytest.raises(InvalidOption) as e:
        animate_motion(motion, tmp_path / "x.png")
    assert str(e.value) == "an animation is written as GIF or SVG: end the file name in .gif or .svg, not 'x.png'"
    for frames in (1, 1001):
        with pytest.raises(InvalidOption) as e:
            animate_motion(motion, tmp_path / "x.gif", frames=frames)
        assert str(e.value) == f"an animation has 2 … 1000 frames, not {frames}"
    with pytest.raises(InvalidOption) as e:
        draw_motion(motion, tmp_path / "none" / "x.svg")
    assert str(e.value) == f"cannot write {tmp_path / 'none' / 'x.svg'}: No such file or directory"
    with pytest.raises(InvalidOption) as e:
        animate_motion(motion, tmp_path / "none" / "x.svg", frames=2)
    assert str(e.value) == f"cannot write {tmp_path / 'none' / 'x.svg'}: No such file or directory"
    assert not list(tmp_path.iterdir())
    assert animate_motion(motion, tmp_path / "X.SVG", frames=1000) == 9 and (tmp_path / "X.SVG").read_text().count(
        'values="') > 0


def test_linkages_from_drawings_say_what_was_moved():
    with pytest.raises(MotionError) as e:
        linkage_from_layout(Mechanism(Chain(4, ((0, 1), (1, 2), (2, 3), (3, 0)), h=4), 0))
    assert str(e.value) == "a linkage moves in the plane (h = 3); this chain's loops are in motion space h = 4"
    # the four-bar's drawing (a square) is locked: the note says how far its joints were moved, and to what
    from synth.draw import layout

    lk = linkage_from_layout(FOUR_BAR_CHAIN, size=100.0)
    drawn = layout(FOUR_BAR_CHAIN.chain).joints * 50.0
    shift = float(np.hypot(*(lk.points - drawn).T).max())
    O2, O4, A, B = lk.points
    a, b, c, d = math.dist(O2, A), math.dist(A, B), math.dist(B, O4), math.dist(O2, O4)
    worst = _transmission_worst(a, b, c, d)
    assert lk.note == ("the drawing's pose does not move well (its input does not turn fully); its joints were moved "
                       f"by up to {shift:.3g} ({shift / 100:.0%} of its size) to a pose whose input turns fully with "
                       f"transmission angles of at least {math.floor(math.degrees(worst))}°")
    assert worst >= math.radians(20) and 0.05 * 100 <= shift
    # Stephenson's chain on link 0 driven at link 1: no pose tried turns fully; the note gives the swing of the
    # best, its input's travel between the two dead positions that motion_range finds
    from synth.motion import motion_range

    rocker = linkage_from_layout(Mechanism(Chain.parse("0-1 1-2 2-3 3-0 1-4 4-5 5-3"), 0, 1))
    low, high = motion_range(rocker).limits
    assert rocker.note.endswith(f"to a pose whose input swings {math.degrees(high - low):.0f}°")
    assert "its input does not turn fully" in rocker.note
    # Watt II from its drawing: its worst transmission angle, 23.7°, is "at least 23°" (it once read "at least 24°")
    watt = linkage_from_layout(Mechanism(Chain.parse("0-3 0-4 1-2 1-4 2-5 3-5 4-5"), 4))
    worst = min(min(t["min"], math.pi - t["max"]) for t in sweep(watt, steps=361).transmission.values())
    assert 23 < math.degrees(worst) < 24 and watt.note.endswith("transmission angles of at least 23°")
    # Stephenson III from its drawing: the crank drives a triad, moved by Newton's method, which has no transmission
    # angle; the note claims none (it once said "at least 90°", the score's stand-in for an angle not measured)
    triad = linkage_from_layout(Mechanism(Chain.parse("0-2 0-3 0-4 1-2 1-3 1-5 4-5"), 0))
    assert motion_range(triad).full_rotation and sweep(triad, steps=5).transmission == {}
    assert triad.note.endswith("to a pose whose input turns fully") and "transmission" not in triad.note
    # a 2-DOF chain takes the drawing's pose as it is (nudged off locked poses)
    five_bar = linkage_from_layout(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0))
    assert five_bar.dof == 2 and five_bar.inputs == (0, 1)


def test_a_blocks_travel_is_read_in_its_turning_guides_direction():
    from synth.motion_draw import _along

    u = np.array([math.cos(0.3), math.sin(0.3)])  # the guide's direction in the pose
    theta = np.array([0.0, math.pi / 2, 2.0, -1.0])  # the guide turned by θ at four frames
    d = np.array([1.5, -0.5, 2.0, 0.25])  # the block that far along the guide
    turned = np.stack([np.cos(0.3 + theta), np.sin(0.3 + theta)], axis=-1)
    across = np.stack([-turned[:, 1], turned[:, 0]], axis=-1)
    local = d[:, None] * turned + 0.7 * across  # an offset across the guide is not travel
    assert _along(local, theta, u) == pytest.approx(d)


def test_a_gif_shows_its_progress_and_plays_in_the_time_asked(tmp_path, monkeypatch):
    import io
    import sys
    import threading

    import tqdm
    from PIL import Image

    # tqdm with a plain thread lock and no monitor thread (its default multiprocessing lock can hang a forked process)
    monkeypatch.setattr(tqdm.tqdm, "_lock", threading.RLock(), raising=False)
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", 0)

    class Terminal(io.StringIO):  # a bar is drawn on a terminal (in a log: a line a minute)
        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stderr", Terminal())
    motion = sweep(_four_bar(), steps=9)
    assert animate_motion(motion, tmp_path / "m.gif", frames=4, seconds=2.0, progress=True) == 4
    err = sys.stderr.getvalue()
    assert "animation:" in err and "/4 [" in err and "frames" in err
    with Image.open(tmp_path / "m.gif") as gif:
        assert gif.n_frames == 4 and gif.info["loop"] == 0 and gif.info["duration"] == 500  # 2 s over 4 frames
    shown = len(err)
    animate_motion(motion, tmp_path / "q.gif", frames=4, seconds=0.01)
    with Image.open(tmp_path / "q.gif") as gif:
        assert gif.info["duration"] == 20  # never faster than 50 frames a second
    assert len(sys.stderr.getvalue()) == shown  # no bar unless asked


def test_an_svg_picture_holds_the_pin_paths_and_the_coupler_curve(tmp_path):
    import xml.etree.ElementTree as ET

    lk = _four_bar(tracers={"P": (2, (2.5, 4.5))})
    motion = sweep(lk, steps=37)
    draw_motion(motion, tmp_path / "m.svg", marks=[[1.0, 1.0]])
    root = ET.fromstring((tmp_path / "m.svg").read_text())
    lines = [el for el in root.iter() if el.tag.endswith("}polyline")]
    grey = [el for el in lines if el.get("stroke") == "#8f9baa"]
    curve = [el for el in lines if el.get("stroke") == "#c0392b"]
    # the two moving pins' paths and the tracer's coupler curve, a point per step of the sweep
    assert len(grey) == 2 and len(curve) == 1 and len(curve[0].get("points").split()) == 37
    assert [len(el.get("points").split()) for el in grey] == [37, 37]
    (mark,) = [el for el in root.iter() if el.tag.endswith("}circle") and el.get("stroke") == "#1f4e9c"]
    assert mark.get("fill") == "none"


def test_dense_target_marks_shrink_so_that_none_overlaps(tmp_path):
    import xml.etree.ElementTree as ET

    # 72 points 0.052 apart about a circle on a four-bar of size 4.6: rings of 0.014 × 4.6 = 0.064 overlapped, as
    # 'dimension --out' of models/dimension_closed_path.csv (points about 1 apart, a six-bar of size 97: rings of
    # 1.4) drew a band of rings over the curve
    lk = _four_bar(tracers={"P": (2, (2.5, 4.5))})
    motion = sweep(lk, steps=37)
    t = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    marks = np.c_[2 + 0.6 * np.cos(t), 4 + 0.6 * np.sin(t)]
    draw_motion(motion, tmp_path / "m.svg", marks=marks)
    root = ET.fromstring((tmp_path / "m.svg").read_text())
    rings = [el for el in root.iter() if el.tag.endswith("}circle") and el.get("stroke") == "#1f4e9c"]
    centres = np.array([(float(el.get("cx")), float(el.get("cy"))) for el in rings])
    gap = np.hypot(*np.diff(centres, axis=0).T).min()
    assert len(rings) == 72 and all(2 * float(el.get("r")) < gap for el in rings)
    # sparse marks keep their size: 0.014 of the mechanism's
    draw_motion(motion, tmp_path / "s.svg", marks=[[1.0, 1.0], [2.0, 2.0]])
    root = ET.fromstring((tmp_path / "s.svg").read_text())
    pins = [float(el.get("r")) for el in root.iter() if el.tag.endswith("}circle") and el.get("fill") == "white"]
    ring = [float(el.get("r")) for el in root.iter() if el.tag.endswith("}circle") and el.get("stroke") == "#1f4e9c"]
    assert ring[0] == pytest.approx(pins[0] * 0.014 / 0.018, abs=0.1)  # (radii written to 0.1 px)


def test_a_sheets_long_titles_stay_within_their_panels(tmp_path):
    """A row of ten links ('1: 0-1 0-2 … 8-9, frame 0', 60 characters) or a mark of a mechanism that dwarfs its
    target ran past its panel's 3.6 in into the next title at 9 pt: a title wider than its panel is set smaller.
    Checked on the picture: no ink in the title strip on the border between two panels, nor at the sheet's
    edges."""
    from PIL import Image

    from synth.motion_draw import draw_motion_sheet

    motion = sweep(_four_bar(tracers={"P": (2, (2.5, 4.5))}), steps=37)
    long = ("1: 0-1 0-2 1-3 2-4 3-5 4-6 5-7 6-8 7-9 8-9 1-4 2-7, frame 0\n"
            "10 links, error max 1.23e-05, mechanism 9999× target")
    out = tmp_path / "sheet.png"
    draw_motion_sheet([(motion, None, long), (motion, None, long)], out, columns=2)
    strip = np.asarray(Image.open(out).convert("L"))[:45]  # the titles' 0.45 in at 100 dpi
    assert strip.shape == (45, 720) and strip.min() < 128  # the titles are there
    for x in (0, 1, 358, 359, 360, 361, 718, 719):
        assert strip[:, x].min() > 200, x
