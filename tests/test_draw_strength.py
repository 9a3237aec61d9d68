"""What a drawing holds, mark by mark: for each joint its mark by kind (a pin circle, a slider's block or a
cylinder's barrel, two pitch circles), where it stands and its colour; the multiple joint's ring and number, the
fixed link's hatching and pivot signs, the input arrow, the link numbers at their links, the captions; a sheet's
grid; the inline SVG's elements at the layout's points.  Read from the matplotlib artists and the SVG itself."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from synth.draw import _render
from synth.draw._layout import layout
from synth.draw._render import _Marks, _caption, _draw, draw_one, draw_sheet, expand, svg_inline
from synth.errors import InvalidOption
from synth.gears import GearTrain
from synth.structure.chain import Chain, Mechanism
from synth.structure.joints import MESH, PRISMATIC, REVOLUTE

WATT_MULTIPLE = Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1")  # a joint of three links: 0, 1, 2
SLIDER_CRANK = Chain.parse("0-1 1-2 2-3 3=0")  # joint 1 = (0, 3) slides; both its links binary: a cylinder
SLIDER_ON_TERNARY = Chain.parse("0-1 1-2 2-3 3=0 0-4 4-5 5-1")  # link 0 is ternary: a block on a bar
GEARS = GearTrain.parse("0-3 1-3 2-3 0~2 1~2").to_chain()  # joints 0 and 2 are meshes
OPEN = Chain.parse("0-1 1-2 2-0 2-3")  # link 3 hangs on one joint


def _axes(item, **options):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    _draw(ax, item, **options)
    return fig, ax


def _by_gid(ax, prefix):
    artists = list(ax.patches) + list(ax.lines) + list(ax.texts)
    return {a.get_gid(): a for a in artists if (a.get_gid() or "").startswith(prefix)}


def _colour(artist):
    from matplotlib.colors import to_hex

    return to_hex(artist.get_edgecolor())


@pytest.fixture(autouse=True)
def _close():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def test_each_joint_is_marked_by_its_kind_where_it_stands():
    for chain in (SLIDER_CRANK, SLIDER_ON_TERNARY, GEARS, WATT_MULTIPLE):
        fig, ax = _axes(chain)
        marks = _Marks(chain)
        pos, r = marks.pos, marks.r
        pins, sliders = _by_gid(ax, "pin"), _by_gid(ax, "slider")
        sliders.update(_by_gid(ax, "cylinder"))
        for k, kind in enumerate(chain.kinds):
            if kind == REVOLUTE:
                pin = pins[f"pin{k}"]
                assert np.allclose(pin.center, pos[k]) and pin.radius == pytest.approx(r)
                assert _colour(pin) == "#000000"
            elif kind == PRISMATIC:
                (block,) = [v for g, v in sliders.items() if g.endswith(str(k))]
                corners = block.get_xy()[:4]
                # the block lies along its guide link's side through the joint
                guide = marks.lay.polygons[chain.joints[k][0]]
                other = next(j for j in guide if j != k)
                along = (pos[other] - pos[k]) / np.linalg.norm(pos[other] - pos[k])
                edge = corners[1] - corners[0]
                assert abs(edge[0] * along[1] - edge[1] * along[0]) < 1e-9  # parallel to the side
                assert _colour(block) == PRISMATIC.stroke
            else:
                circles = [p for p in ax.patches if p.get_gid() == f"mesh{k}"]
                assert len(circles) == 2
                c0, c1 = circles
                assert c0.radius == c1.radius == pytest.approx(1.25 * r)
                # tangent to each other at the joint: centres one radius away on either side
                assert np.allclose((np.array(c0.center) + c1.center) / 2, pos[k])
                assert np.linalg.norm(np.array(c0.center) - c1.center) == pytest.approx(2 * 1.25 * r)
                assert _colour(c0) == MESH.stroke
        expected_pins = sum(kind == REVOLUTE for kind in chain.kinds)
        assert len(pins) == expected_pins
        assert len([p for p in ax.patches if (p.get_gid() or "").startswith("mesh")]) == 2 * chain.kinds.count(MESH)
        assert len(sliders) == chain.kinds.count(PRISMATIC)
        assert ax.get_xlim() == pytest.approx((-marks.reach, marks.reach))
        assert ax.get_ylim() == pytest.approx((-marks.reach, marks.reach))


def test_a_cylinder_is_a_long_dark_barrel_and_a_slider_a_short_white_block():
    from matplotlib.colors import to_hex

    fig, ax = _axes(SLIDER_CRANK)
    (barrel,) = _by_gid(ax, "cylinder").values()
    marks = _Marks(SLIDER_CRANK)
    pos, r = marks.pos, marks.r
    corners = barrel.get_xy()[:4]
    guide = marks.lay.polygons[0]  # link 0, the cylinder: from joint 1 towards its other joint
    other = next(j for j in guide if j != 1)
    length = np.linalg.norm(pos[other] - pos[1])
    assert np.linalg.norm(corners[1] - corners[0]) == pytest.approx(0.55 * length)
    assert np.linalg.norm(corners[3] - corners[0]) == pytest.approx(2 * 1.3 * r)
    assert to_hex(barrel.get_facecolor()) == PRISMATIC.stroke
    fig, ax = _axes(SLIDER_ON_TERNARY)
    (block,) = _by_gid(ax, "slider").values()
    r = _Marks(SLIDER_ON_TERNARY).r
    corners = block.get_xy()[:4]
    assert np.linalg.norm(corners[1] - corners[0]) == pytest.approx(3.2 * r)
    assert np.linalg.norm(corners[3] - corners[0]) == pytest.approx(2 * r)
    assert to_hex(block.get_facecolor()) == "#ffffff"


def _distance_to_link(at: np.ndarray, corners: np.ndarray) -> float:
    """From a point to a link drawn as a bar (two joints) or a plate (0 inside it)."""
    from matplotlib.path import Path as MplPath

    if len(corners) > 2 and MplPath(corners).contains_point(at):
        return 0.0
    sides = zip(corners, np.roll(corners, -1, axis=0)) if len(corners) > 2 else [tuple(corners)]
    return min(float(np.linalg.norm(at - (a + np.clip((at - a) @ (b - a) / ((b - a) @ (b - a)), 0, 1) * (b - a))))
               for a, b in sides)


def test_a_mechanism_shows_its_frame_pivots_input_and_link_numbers():
    mechanism = Mechanism(WATT_MULTIPLE, 0, 4)
    fig, ax = _axes(mechanism, labels=True, caption="a caption")
    marks = _Marks(WATT_MULTIPLE)
    pos, r = marks.pos, marks.r
    frame_joints = [k for k, j in enumerate(WATT_MULTIPLE.joints) if 0 in j]
    grounds = _by_gid(ax, "ground")
    assert sorted(grounds) == sorted(f"ground{k}" for k in frame_joints)
    for k in frame_joints:
        apex = grounds[f"ground{k}"].get_xy()[0]
        assert np.allclose(apex, pos[k])  # the support's struts meet at the pin
    hatched = [p for p in ax.patches if p.get_hatch() == "////"]
    assert len(hatched) == 1 + len(frame_joints)  # the ternary frame itself and one base per pivot
    from matplotlib.patches import FancyArrowPatch

    assert sum(isinstance(p, FancyArrowPatch) for p in ax.patches) == 1
    labels = _by_gid(ax, "label")
    assert sorted(labels) == sorted(f"label{i}" for i in range(6))
    for link, text in labels.items():
        i = int(link[len("label"):])
        assert text.get_text() == str(i)
        # beside its bar or inside its plate: nearer its own link than any other (not at the middle of its joints,
        # where cylinders and pivot signs covered it)
        at = np.array(text.get_position())
        near = [_distance_to_link(at, pos[poly]) for poly in marks.lay.polygons]
        assert near[i] == min(near) and near[i] < 3 * r, (link, near)
    (number,) = _by_gid(ax, "multiplicity").values()
    k = next(i for i, j in enumerate(WATT_MULTIPLE.joints) if len(j) == 3)
    assert number.get_text() == "3" and number.get_gid() == f"multiplicity{k}"
    assert np.linalg.norm(np.array(number.get_position()) - pos[k]) == pytest.approx(3.2 * r)
    rings = [p for p in ax.patches if getattr(p, "radius", None) == pytest.approx(1.75 * r)]
    assert len(rings) == 1 and np.allclose(rings[0].center, pos[k]) and _colour(rings[0]) == "#c0392b"
    assert ax.get_title() == "a caption"
    fig, ax = _axes(Mechanism(WATT_MULTIPLE, 0))
    assert not _by_gid(ax, "label") and not any(isinstance(p, FancyArrowPatch) for p in ax.patches)


def test_a_single_joint_link_ends_free_in_a_square():
    fig, ax = _axes(Mechanism(OPEN, 3), labels=True)
    marks = _Marks(OPEN)
    end = marks.free_ends[3]
    bar = _by_gid(ax, "bar3")["bar3"]
    assert np.allclose(bar.get_xydata(), [marks.pos[marks.lay.polygons[3][0]], end])
    from matplotlib.colors import to_hex

    assert to_hex(bar.get_color()) == "#1f3a5f" and bar.get_linewidth() == 2.2 and bar.get_solid_capstyle() == "butt"
    square = _by_gid(ax, "end3")["end3"]
    assert np.allclose(square.get_xy()[:4].mean(axis=0), end) and square.get_hatch() == "////"  # the frame
    assert np.linalg.norm(end - marks.pos[marks.lay.polygons[3][0]]) == pytest.approx(max(0.35, 6 * marks.r))


def test_captions_by_hand():
    # links 0, 2 and 3 of WATT_MULTIPLE form a rigid triangle (W(S) = 0): a degenerate mechanism, and says so
    assert _caption(Mechanism(WATT_MULTIPLE, 0, 4), 3) == "51/1  #3  fixed 0, input 4 (degenerate)"
    assert _caption(Mechanism(WATT_MULTIPLE, 2), None) == "51/1  fixed 2 (degenerate)"
    assert _caption(Mechanism(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), 2), None) == "42/0  fixed 2"  # Watt
    assert _caption(Mechanism(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4"), 3), None) == "32/0  fixed 3 (truss)"  # W = 0
    assert _caption(SLIDER_CRANK, None) == "4/0 P1"
    assert _caption(Chain.parse("0-3 0-4 0-5 1-3 1-4 1-5 2-3 2-4 2-5"), 1) == "0600/0  non-planar  #1"
    assert _caption(Chain(5, ((0, 1), (1, 2), (2, 3), (3, 4), (4, 0)), h=4), None) == "5/0  h=4"


def test_a_sheet_is_a_grid_of_captioned_drawings(tmp_path, monkeypatch):
    saved = []
    monkeypatch.setattr(_render, "_save", lambda fig, path, dpi: saved.append((fig, path, dpi)))
    items = expand([Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), Chain.parse("0-1 1-2 2-3 3-0 1-4 4-5 5-3")],
                   mechanisms=True)
    assert len(items) == 2 + 3  # Watt's two inversions and Stephenson's three
    draw_sheet(items, tmp_path / "s.png", title="six links")
    ((fig, path, dpi),) = saved
    assert path == tmp_path / "s.png" and dpi == 150
    # 5 drawings: ceil(sqrt(5 × 1.3)) = 3 columns, 2 rows; the sixth cell is empty
    assert len(fig.axes) == 6 and not fig.axes[5].axison
    titles = [ax.get_title() for ax in fig.axes[:5]]
    assert titles == [_caption(m, i + 1) for i, m in enumerate(items)]
    assert all(f"#{i + 1}" in t for i, t in enumerate(titles))
    assert fig._suptitle.get_text() == "six links"
    assert all(_by_gid(ax, "label") for ax in fig.axes[:5])  # mechanisms: links numbered
    w, h = fig.get_size_inches()
    assert w == pytest.approx(3 * 1.9) and h == pytest.approx(2 * 1.9 + 0.45)
    saved.clear()
    draw_sheet([SLIDER_CRANK], tmp_path / "one.svg", notes=["a note long enough to wrap " * 3])
    ((fig, _, _),) = saved
    assert fig.axes[0].get_title().startswith("4/0 P1  #1\na note") and _by_gid(fig.axes[0], "label")
    with pytest.raises(InvalidOption, match="nothing to draw: the selection is empty"):
        draw_sheet([], tmp_path / "e.png")
    with pytest.raises(InvalidOption, match="^2 notes for 1 drawings$"):
        draw_sheet([SLIDER_CRANK], tmp_path / "e.png", notes=["a", "b"])


@pytest.mark.parametrize("call, sentence", [
    (lambda p: draw_one(SLIDER_CRANK, p / "x.gif"), "draw writes .svg, .png, .pdf files, not '.gif'"),
    (lambda p: draw_one(SLIDER_CRANK, p / "x"), "draw writes .svg, .png, .pdf files, not 'a file without suffix'"),
    (lambda p: draw_one(SLIDER_CRANK, p / "x.png", size=0.4), "a drawing's size is 0.5 to 30 inches, not 0.4"),
    (lambda p: draw_one(SLIDER_CRANK, p / "x.png", size=31), "a drawing's size is 0.5 to 30 inches, not 31"),
    (lambda p: draw_one(SLIDER_CRANK, p / "x.png", dpi=29), "the resolution is 30 to 1200 dpi, not 29"),
    (lambda p: draw_one(SLIDER_CRANK, p / "x.png", dpi=1201), "the resolution is 30 to 1200 dpi, not 1201"),
    (lambda p: draw_one(SLIDER_CRANK, p / "x.png", size=30, dpi=1200),
     "this picture would be 36000 × 38000 pixels, more than 100 megapixels (or 65 536 on a side); lower dpi=DPI or "
     "size=INCHES, narrow the selection, or write .svg"),
])
def test_bad_drawings_are_refused_with_their_sentence(tmp_path, call, sentence):
    with pytest.raises(InvalidOption) as e:
        call(tmp_path)
    assert str(e.value) == sentence
    assert not list(tmp_path.iterdir())


def test_the_edges_of_size_resolution_and_pixels_are_accepted(tmp_path, monkeypatch):
    monkeypatch.setattr(_render, "_save", lambda fig, path, dpi: None)
    draw_one(SLIDER_CRANK, tmp_path / "a.png", size=0.5, dpi=30)
    draw_one(SLIDER_CRANK, tmp_path / "b.svg", size=30, dpi=1200)  # a vector file has no pixels
    with pytest.raises(_render.DrawError) as e:
        draw_one(SLIDER_CRANK, tmp_path / "none" / "a.png")
    assert str(e.value) == f"cannot write {tmp_path / 'none' / 'a.png'}: the directory {tmp_path / 'none'} does not exist"


def _svg_elements(text):
    root = ET.fromstring(text)
    return [(el.tag.split("}")[1], el.attrib) for el in root.iter()][1:]


def test_the_inline_svg_marks_each_joint_at_the_layouts_point():
    for chain, mechanism in ((GEARS, None), (SLIDER_CRANK, None), (WATT_MULTIPLE, Mechanism(WATT_MULTIPLE, 0))):
        item = mechanism or chain
        text = svg_inline(item, size=200, labels=True)
        elements = _svg_elements(text)
        marks = _Marks(chain)
        scale = 200 / (2 * marks.reach)

        def at(p):
            return round((p[0] + marks.reach) * scale, 1), round((marks.reach - p[1]) * scale, 1)

        circles = [(float(a["cx"]), float(a["cy"]), a) for tag, a in elements if tag == "circle"]
        pins = [c for c in circles if c[2]["stroke"] == REVOLUTE.stroke]
        assert sorted((x, y) for x, y, _ in pins) == sorted(at(marks.pos[k]) for k, kind in enumerate(chain.kinds)
                                                            if kind == REVOLUTE)
        assert sum(a.get("class") == "mesh" and a["stroke"] == MESH.stroke for *_, a in circles) == \
            2 * chain.kinds.count(MESH)
        rings = [c for c in circles if c[2]["stroke"] == "#c0392b"]
        assert len(rings) == sum(len(j) > 2 for j in chain.joints)
        blocks = [a for tag, a in elements if tag == "polygon" and a.get("stroke") == PRISMATIC.stroke
                  and a.get("stroke-width") == "1.1"]
        assert len(blocks) == chain.kinds.count(PRISMATIC)
        bars = [a for tag, a in elements if tag == "line" and a.get("stroke-width") in ("2.2", "4.5")]
        assert len(bars) == sum(len(p) == 2 for p in marks.lay.polygons)
        faces = [a for tag, a in elements if tag == "polygon" and a.get("stroke-width") == "1.2"]
        assert len(faces) == sum(len(p) >= 3 for p in marks.lay.polygons)
        numbers = [t for t in ET.fromstring(text).iter() if t.tag.endswith("text") and t.get("font-size") == "8"]
        assert sorted(int(t.text) for t in numbers) == list(range(chain.links))
        assert ('<pattern id="hatch"' in text) == (mechanism is not None)
        assert text.startswith('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200" viewBox="0 0 200 200">')
    frame = [a for tag, a in _svg_elements(svg_inline(Mechanism(WATT_MULTIPLE, 0))) if a.get("fill") == "url(#hatch)"]
    assert len(frame) == 1  # the ternary frame
    dashed = [a for tag, a in _svg_elements(svg_inline(Mechanism(SLIDER_CRANK, 2))) if "stroke-dasharray" in a]
    assert len(dashed) == 1 and dashed[0]["stroke-width"] == "4.5"  # a binary frame: a wide dashed bar


def test_layout_sides_by_hand():
    lay = layout(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"))  # two triangles and four bars
    sides = lay.segments()
    assert len(sides) == 3 + 3 + 4
    assert all(len({a, b}) == 2 and a in lay.polygons[link] and b in lay.polygons[link] for link, a, b in sides)
    open_lay = layout(OPEN)
    assert not any(link == 3 for link, _, _ in open_lay.segments())  # a free end is no side between joints


def test_the_widest_free_angle_at_a_joint_by_hand():
    from synth.draw._render import _free_ends, _widest_gap

    pos = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [3.0, 3.0]])
    # sides to 0°, 90° and 180°: the widest free angle is the lower half, its middle straight down
    turn, gap = _widest_gap(pos, [(0, 1), (2, 0), (0, 3)], 0)
    assert turn == pytest.approx(1.5 * math.pi) and gap == pytest.approx(math.pi)
    # one side only: the whole turn is free, the middle opposite the side
    assert _widest_gap(pos, [(0, 1)], 0) == pytest.approx((math.pi, 2 * math.pi))
    # and a direction ``also`` counted with the sides: 0°, 90°, 180° and 225° leave 135° free from 225° to 360°
    assert _widest_gap(pos, [(0, 1), (2, 0), (0, 3)], 0, also=[-0.75 * math.pi]) == pytest.approx(
        (-0.75 * math.pi + 0.375 * math.pi, 0.75 * math.pi))
    # nothing meets the joint: away from the centre of the drawing (its mean joint (0.6, 0.8)); half a turn said
    assert _widest_gap(pos, [], 4) == pytest.approx((math.atan2(3 - 0.8, 3 - 0.6), math.pi))
    centred = np.array([[0.0, 0.0]])
    assert _widest_gap(centred, [], 0) == pytest.approx((-math.pi / 2, math.pi))
    # two single-joint links on joint 0 (sides to 0° and 180°: two free halves, the first counted from 0° taken,
    # its middle at 90°) fan out 0.7 × 180° / 2 = 63°, at most 1 rad, apart: at 90° ∓ 0.5 rad, 0.4 long
    ends = _free_ends(pos[:4], [[1, 0], [0, 3], [0], [0]], length=0.4)
    base = 0.5 * math.pi
    assert sorted(ends) == [2, 3]
    assert np.allclose(ends[2], 0.4 * np.array([math.cos(base - 0.5), math.sin(base - 0.5)]))
    assert np.allclose(ends[3], 0.4 * np.array([math.cos(base + 0.5), math.sin(base + 0.5)]))


def test_a_fixed_pivot_sign_and_a_fixed_bar_by_hand():
    # the slider-crank's frame 3 is binary: a hatched bar 1.8 r wide along its side, and a pivot sign at its pin
    mechanism = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 3)
    fig, ax = _axes(mechanism)
    marks = _Marks(mechanism.chain)
    pos, r = marks.pos, marks.r
    a, b = pos[marks.lay.polygons[3]]
    hatched = [p for p in ax.patches if p.get_hatch() == "////" and not (p.get_gid() or "").startswith("end")]
    (bar,) = [p for p in hatched if p.get_gid() == "framebar3"]
    corners = bar.get_xy()[:4]
    normal = np.array([-(b - a)[1], (b - a)[0]]) / np.linalg.norm(b - a) * 0.9 * r
    assert np.allclose(corners, [a + normal, b + normal, b - normal, a - normal])
    assert _colour(bar) == "#1f3a5f"
    for k in (1, 3):  # the frame's two joints, 0-3 (joint 1) and 2-3 (joint 3)
        direction = marks.ground(k)
        across = np.array([-direction[1], direction[0]])
        base = pos[k] + 2.4 * r * direction
        (strut,) = [p for p in ax.patches if p.get_gid() == f"ground{k}"]
        assert np.allclose(strut.get_xy()[:3], [pos[k], base + 1.5 * r * across, base - 1.5 * r * across])
        (plate,) = [p for p in hatched if p.get_gid() == f"pivotbase{k}"]
        assert plate.get_zorder() == 3.5
        assert np.allclose(plate.get_xy()[:4], [base + 2.1 * r * across, base - 2.1 * r * across,
                                                 base - 2.1 * r * across + 0.8 * r * direction,
                                                 base + 2.1 * r * across + 0.8 * r * direction])
        # the sign stands in the widest free angle at its pin: no side of a link points into it
        sides = [pos[j] - pos[k] for j in (0, 1, 2, 3) if j != k and any(
            {j, k} <= set(p) for p in marks.lay.polygons)]
        assert all(np.dot(s / np.linalg.norm(s), direction) < 0.99 for s in sides)
    assert len(hatched) == 1 + 2


def test_a_heterogeneous_chain_colours_its_base_and_keys_the_classes():
    from matplotlib.colors import to_hex

    # Watt's chain with its four-bar loop 0-1-2-3 of class 4, the other loops planar
    chain = Chain(6, WATT := Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1").joints, classes=(4, 4, 4, 4, 3, 3))
    del WATT
    fig, ax = _axes(chain)
    marks = _Marks(chain)
    bars = _by_gid(ax, "bar")
    for link, poly in enumerate(marks.lay.polygons):
        if len(poly) == 2:
            colour, width = ("#b8860b", 2.2 * 1.4) if link < 4 else ("#1f3a5f", 2.2)
            assert to_hex(bars[f"bar{link}"].get_color()) == colour and bars[f"bar{link}"].get_linewidth() == width
    faces = [p for p in ax.patches if type(p).__name__ == "Polygon" and p.get_zorder() == 1]
    for face in faces:  # the ternary links 0 and 1 are base links: drawn in their class's colour, wider
        assert _colour(face) == "#b8860b" and face.get_linewidth() == 2.4
    assert len(faces) == 2
    legend = ax.get_legend()
    assert [t.get_text() for t in legend.get_texts()] == ["h = 4: 1 loop", "h = 3: 1 other loop"]
    assert not legend.get_frame_on() and legend._loc == 2 and legend.get_texts()[0].get_fontsize() == 6
    fig, ax = _axes(chain, legend=False)
    assert ax.get_legend() is None


def test_one_drawing_written_with_its_title_and_a_64_colour_png(tmp_path):
    from PIL import Image

    draw_one(Mechanism(WATT_MULTIPLE, 0, 4), tmp_path / "w.png", size=1.0, dpi=60, title="Watt, fixed 0")
    with Image.open(tmp_path / "w.png") as image:
        assert image.mode == "P" and len(image.getcolors()) <= 64
        assert max(image.size) <= 70  # one inch at 60 dpi, cut to the drawing
    draw_one(SLIDER_CRANK, tmp_path / "s.svg", title="a & b")
    text = (tmp_path / "s.svg").read_text()
    assert ">a &amp; b</text>" in text and "<dc:date>" not in text
    plain = _render.svg(SLIDER_CRANK)
    assert ">4/0 P1</text>" in plain and plain.lstrip().startswith("<?xml")
    import matplotlib.pyplot as plt

    assert not plt.get_fignums()
    with pytest.raises(InvalidOption) as e:
        _render.svg(SLIDER_CRANK, size=0.4)
    assert str(e.value) == "a drawing's size is 0.5 to 30 inches, not 0.4"


def test_the_pixel_limit_by_hand():
    from pathlib import Path

    from synth.draw._render import check_pixels

    check_pixels(Path("a.png"), 100, 100, 100)  # 10 000 × 10 000: exactly 100 megapixels
    with pytest.raises(InvalidOption, match=r"^this picture would be 10001 × 10000 pixels"):
        check_pixels(Path("a.png"), 100.01, 100, 100)
    check_pixels(Path("a.png"), 655.35, 1, 100)  # 65 535 on a side
    with pytest.raises(InvalidOption, match=r"^this picture would be 65536 × 100 pixels"):
        check_pixels(Path("a.png"), 655.36, 1, 100)
    check_pixels(Path("a.PDF"), 1000, 1000, 1200)  # no pixels in a vector file


def test_a_sheet_with_notes_and_loop_classes_grows_to_hold_them(monkeypatch, tmp_path):
    saved = []
    monkeypatch.setattr(_render, "_save", lambda fig, path, dpi: saved.append(fig))
    mixed = Chain(6, Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1").joints, classes=(4, 4, 4, 4, 3, 3))
    draw_sheet([mixed, SLIDER_CRANK], tmp_path / "m.svg", notes=["x " * 40, "y"], size=2.0, columns=1)
    (fig,) = saved
    # two lines of note under the first caption (80 characters at 33 a line: 3 lines): 3 × 0.14 in a row,
    # and 0.3 in for the key of loop classes
    assert fig.get_size_inches() == pytest.approx((2.0, (2.0 + 3 * 0.14) * 2 + 0.3))
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == ["h = 4: base loops", "h = 3: other loops"]
    assert fig.axes[0].get_legend() is None  # one key for the sheet, none per drawing
    assert fig.axes[0].get_title().count("\n") == 3 and fig.axes[1].get_title() == "4/0 P1  #2\ny"


# ------------------------------------------------------------------ the layout's own measures, by hand
def test_corner_angles_by_hand_in_both_orientations_and_any_size():
    from synth.draw._layout import _corner_angles

    # a dart: (0, 0), (2, 1), (4, 0), (2, 3) turns counter-clockwise; its notch (2, 1) is a reflex corner
    dart = np.array([[0, 0], [2, 1], [4, 0], [2, 3]], dtype=float)
    tip = math.degrees(math.atan(1.5) - math.atan(0.5))  # between (2, 3) and (2, 1) seen from the origin
    notch = 360 - (180 - 2 * math.degrees(math.atan(0.5)))
    top = 2 * math.degrees(math.atan(2 / 3))
    expected = [tip, notch, tip, top]
    assert sum(expected) == pytest.approx(360)
    for scale in (0.1, 1.0, 10.0):  # small drawings too: the [-1, 1]² frame's polygons are
        assert _corner_angles(scale * dart) == pytest.approx(expected)
        assert _corner_angles(scale * dart[::-1]) == pytest.approx(expected[::-1])  # clockwise
    assert _corner_angles(np.array([[0, 0], [0, 1], [1, 0.0]])) == pytest.approx([90, 45, 45])  # clockwise
    # a batch of polygons, each with its own orientation
    batch = np.stack([0.1 * dart, 10 * dart[::-1]])
    assert _corner_angles(batch) == pytest.approx(np.array([expected, expected[::-1]]))


def test_defects_by_hand():
    from synth.draw._layout import _defects

    bars = [[0, 1], [2, 3]]
    crossing = np.array([[0, 0], [1, 1], [0, 1], [1, 0.0]])
    assert _defects(crossing, bars, 0.1) == 1000
    # a bar in line with the other, past its end: nothing touches (a side ends at its joints)
    in_line = np.array([[0, 0], [1, 0], [1.5, 0], [2.5, 0.0]])
    assert _defects(in_line, bars, 0.1) == 0
    assert _defects(in_line, bars, 0.6) == 2  # joints 1 and 2 each within 0.6 of the other bar's end
    # a joint 0.05 from a foreign side
    touching = np.array([[0, 0], [1, 0], [0.5, 0.05], [0.5, 1.0]])
    assert _defects(touching, bars, 0.1) == 1 and _defects(touching, bars, 0.04) == 0
    # a bar inside a triangle: two joints inside a foreign link
    inside = np.array([[0, 0], [2, 0], [0, 2], [0.3, 0.3], [0.6, 0.6]])
    assert _defects(inside, [[0, 1, 2], [3, 4]], 0.1) == 2000
    assert _defects(inside + np.array([[0, 0]] * 3 + [[3, 0]] * 2), [[0, 1, 2], [3, 4]], 0.1) == 0  # the bar moved out


def _crossings(points, sides):
    """Pairs of sides (no joint in common) that cross, by the plain orientation test."""
    def orient(p, q, r):
        return np.sign((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))

    found = 0
    for i, (a, b) in enumerate(sides):
        for c, d in sides[i + 1:]:
            if {a, b} & {c, d}:
                continue
            p, q, r, s = points[[a, b, c, d]]
            found += orient(p, q, r) * orient(p, q, s) < 0 and orient(r, s, p) * orient(r, s, q) < 0
    return found


def test_a_non_planar_chain_lets_its_string_of_binary_links_cross_the_rest():
    from synth.draw._layout import _crossing_strings, _incidence, _strings

    # K3,3 of ternary links 0, 1, 2 and 3, 4, 5, its edge 0–3 a string of two binary links 6 and 7
    chain = Chain.parse("0-6 6-7 7-3 0-4 0-5 1-3 1-4 1-5 2-3 2-4 2-5")
    assert not chain.is_planar()
    g = _incidence(chain)
    assert _strings(chain, g) == [[6, 7]] and _crossing_strings(chain, g) == [[[6, 7]]]
    # a string walked both ways from its lowest link: 0 – 7 – 6 – 8 – 3, listed in its order along the chain
    three = Chain.parse("0-7 7-6 6-8 8-3 0-4 0-5 1-3 1-4 1-5 2-3 2-4 2-5")
    assert _strings(three, _incidence(three)) in ([[7, 6, 8]], [[8, 6, 7]])
    # two edges subdivided: either string alone, set aside, leaves a planar rest
    two = Chain.parse("0-6 6-3 0-4 0-5 1-3 1-7 7-4 1-5 2-3 2-4 2-5")
    assert _strings(two, _incidence(two)) == [[6], [7]]
    assert _crossing_strings(two, _incidence(two)) == [[[6]], [[7]]]
    # no binary link at all: nothing to set aside
    k33 = Chain.parse("0-3 0-4 0-5 1-3 1-4 1-5 2-3 2-4 2-5")
    assert _crossing_strings(k33, _incidence(k33)) == []
    lay = layout(chain)
    assert not lay.planar
    joint = {tuple(sorted(j)): k for k, j in enumerate(chain.joints)}
    # the string is a straight bar across: its middle joint halfway between its ends
    ends = lay.joints[[joint[(0, 6)], joint[(3, 7)]]]
    assert np.allclose(lay.joints[joint[(6, 7)]], ends.mean(axis=0))
    # the rest is drawn without a crossing; the string crosses it
    rest = [(a, b) for link, a, b in lay.segments() if link < 6]
    assert _crossings(lay.joints, rest) == 0
    assert _crossings(lay.joints, [(a, b) for _, a, b in lay.segments()]) >= 1
    assert np.abs(lay.joints).max() == pytest.approx(1.0)  # scaled into [-1, 1]²
    # the chain's six ternary links are triangles of distinct joints
    assert [len(set(p)) for p in lay.polygons] == [3] * 6 + [2, 2]
    # of two ways (either string may cross), the drawing keeps one: only that string's bar crosses the rest
    lay = layout(two)
    crossing = {link for link, a, b in lay.segments()
                if any(_crossings(lay.joints, [(a, b), (c, d)]) for other, c, d in lay.segments() if other != link)}
    assert not lay.planar and len(crossing & {6, 7}) == 1
    assert _crossings(lay.joints, [(a, b) for link, a, b in lay.segments() if link not in {6, 7}]) == 0


def test_a_polygon_without_an_embedding_goes_round_its_own_centre():
    from synth.draw._layout import _incidence, _polygons

    # link 0 has four joints (to links 1 … 4) on a square about (10, 0), handed over out of turn
    chain = Chain.parse("0-1 0-2 0-3 0-4 1-2 2-3 3-4 4-1")
    corners = {(0, 1): (11, 1), (0, 2): (9, -1), (0, 3): (11, -1), (0, 4): (9, 1)}
    pos = {("J", k): np.array(corners.get(tuple(sorted(j)), (0, 5)), dtype=float) for k, j in enumerate(chain.joints)}
    order = _polygons(chain, _incidence(chain), None, pos)[0]
    at = [tuple(pos[("J", k)]) for k in order]
    # counter-clockwise from the lower left: (9, −1), (11, −1), (11, 1), (9, 1)
    assert at == [(9, -1), (11, -1), (11, 1), (9, 1)]


def test_chains_without_a_side_between_joints_are_laid_out():
    # two links on one joint, and three: a point; two joints on a bar: the bar, upright, filling the frame
    for text in ("0-1", "0-1-2"):
        lay = layout(Chain.parse(text))
        assert np.allclose(lay.joints, [[0, 0]]) and lay.polygons == [[0]] * Chain.parse(text).links and lay.planar
        assert lay.segments() == []
    lay = layout(Chain.parse("0-1 1-2"))
    assert lay.polygons == [[0], [0, 1], [1]] and lay.segments() == [(1, 0, 1)]
    assert np.linalg.norm(lay.joints[0] - lay.joints[1]) == pytest.approx(2.0)


def test_distances_to_sides_and_the_shaping_cost_by_hand():
    from synth.draw._layout import _gaps, _Shape

    a, ab = np.array([[1.0, 1.0]]), np.array([[2.0, 0.0]])  # the side from (1, 1) to (3, 1)
    points = np.array([[2.0, 3.0], [0.0, 1.0], [4.0, 2.0], [1.5, 0.5]])
    assert _gaps(points[:, None], a[None], ab[None]).ravel() == pytest.approx([2.0, 1.0, math.sqrt(2), 0.5])
    # two bars, 0-1 along y = 0 and 2-3 along y = 1, of four joints: spacing 2/√4 = 1, so sides are kept 0.36
    # apart from foreign joints, joints 0.72 from each other
    pos = np.array([[0, 0], [1, 0], [0, 1], [1, 1.0]])
    shape = _Shape(pos, [[0, 1], [2, 3]])
    assert (shape.side_gap, shape.joint_gap) == pytest.approx((0.36, 0.72))

    def near(d, gap):
        return (40 * max(0.0, 1 - d / gap)) ** 2

    cost = shape.cost(0, np.array([[0, 0], [0.5, 0.6], [0.5, 0.8]]))
    # where it is, nothing is too near; at (0.5, 0.6) it is 0.64 from joints 2 and 3 (the sides clear); at
    # (0.5, 0.8) it is 0.2 from bar 2-3 and √0.29 from joints 2 and 3
    assert cost == pytest.approx([0.0, 2 * near(math.sqrt(0.41), 0.72),
                                  near(0.2, 0.36) + 2 * near(math.sqrt(0.29), 0.72)])
    # a corner under 30° or over 160° costs the square of the degrees it is past; three joints: spacing 2/√3
    big = np.array([[0, 0], [4, 0], [4, 4 * math.tan(math.radians(20))]])  # corners 20°, 90°, 70°, all apart
    assert _Shape(big, [[0, 1, 2]]).cost(1, big[1:2]) == pytest.approx([(30 - 20) ** 2])
    flat = np.array([[0, 0], [2, 0], [1, math.tan(math.radians(5))]])  # corners 5°, 5°, 170°; joint 2 near 0-1
    shape = _Shape(flat, [[0, 1, 2]])
    assert shape.cost(2, flat[2:]) == pytest.approx(
        [(170 - 160) ** 2 + 2 * (30 - 5) ** 2 + near(math.tan(math.radians(5)), 0.36 * 2 / math.sqrt(3))])


def test_the_inline_svg_places_each_mark_at_its_size():
    def parsed(item, **options):
        return [(tag, a) for tag, a in _svg_elements(svg_inline(item, **options))]

    for chain in (WATT_MULTIPLE, GEARS, OPEN):
        marks = _Marks(chain)
        scale = 160 / (2 * marks.reach)

        def at(p):
            return round((p[0] + marks.reach) * scale, 1), round((marks.reach - p[1]) * scale, 1)

        elements = parsed(chain, labels=True)
        circles = [a for tag, a in elements if tag == "circle"]
        for k, kind in enumerate(chain.kinds):
            if kind == REVOLUTE:
                (pin,) = [a for a in circles if a["stroke"] == REVOLUTE.stroke and
                          (float(a["cx"]), float(a["cy"])) == at(marks.pos[k])]
                assert float(pin["r"]) == pytest.approx(marks.r * scale, abs=0.06) and pin["fill"] == "white"
            if len(chain.joints[k]) > 2:  # the ring and the multiplicity at its place
                (ring,) = [a for a in circles if a["stroke"] == "#c0392b"]
                assert (float(ring["cx"]), float(ring["cy"])) == at(marks.pos[k])
                assert float(ring["r"]) == pytest.approx(1.75 * marks.r * scale, abs=0.06)
                (number,) = [a for tag, a in elements if tag == "text" and a.get("fill") == "#c0392b"]
                assert (float(number["x"]), float(number["y"])) == at(marks.numbers[k])
            if kind == MESH:
                pitch = [a for a in circles if a.get("class") == "mesh"
                         and any((float(a["cx"]), float(a["cy"])) == at(c) for c, _ in marks.meshes[k])]
                assert len(pitch) == 2 and all(float(a["r"]) == pytest.approx(1.25 * marks.r * scale, abs=0.06)
                                               for a in pitch)
        labels = {t.text: t for t in ET.fromstring(svg_inline(chain, labels=True)).iter() if t.tag.endswith("text")
                  and t.get("font-size") == "8"}
        places = _render._label_places(marks, None, 8 / scale)  # where a sheet puts them, for 8-pixel numbers
        for link in range(chain.links):
            assert (float(labels[str(link)].get("x")), float(labels[str(link)].get("y"))) == at(places[link])
    # a single-joint link: a bar from its joint to its free end and a square of side 2r there
    marks = _Marks(OPEN)
    scale = 160 / (2 * marks.reach)
    end = marks.free_ends[3]
    x, y = (end[0] + marks.reach) * scale, (marks.reach - end[1]) * scale
    (square,) = [a for tag, a in parsed(OPEN) if tag == "rect"]
    assert float(square["x"]) == pytest.approx(x - marks.r * scale, abs=0.11)
    assert float(square["y"]) == pytest.approx(y - marks.r * scale, abs=0.11)
    assert float(square["width"]) == float(square["height"]) == pytest.approx(2 * marks.r * scale, abs=0.06)
    (bar,) = [a for tag, a in parsed(OPEN) if tag == "polyline"]
    assert bar["points"].split()[1] == f"{x:.1f},{y:.1f}"


def test_the_inline_frame_number_stands_on_a_gap_in_its_hatching():
    """As on the sheets: the frame plate's hatching, then an opaque white gap 0.3 em wider on each side than its
    number's light box, then every plate's outline, bar and pin over them, and every number on top in its light box
    (no white outline round its text). On main the number stood on the hatching in a white outline, the hatch lines
    running up to it, and no gap was drawn."""
    braced = Chain.parse("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-7 7-2")  # 440/0: a tiny frame plate beside a four-bar
    for mechanism in (Mechanism(WATT_MULTIPLE, 0), Mechanism(braced, 0), Mechanism(braced, 1)):
        root = ET.fromstring(svg_inline(mechanism, size=200, labels=True))
        elements = [(el.tag.split("}")[1], el.attrib, el.text) for el in root.iter()][1:]
        (hatching,) = [i for i, (_, a, _) in enumerate(elements) if a.get("fill") == "url(#hatch)"]
        (gap,) = [i for i, (_, a, _) in enumerate(elements) if a.get("class") == "hatchgap"]
        drawn = [i for i, (tag, a, _) in enumerate(elements) if tag in ("polygon", "line", "circle", "polyline")
                 and i > hatching]  # (the pattern's own line comes before)
        numbers = {text: i for i, (tag, a, text) in enumerate(elements) if tag == "text" and a["font-size"] == "8"}
        assert sorted(map(int, numbers)) == list(range(mechanism.chain.links))
        assert hatching < gap < min(drawn) and max(drawn) < min(numbers.values()), mechanism
        assert elements[gap][1]["fill"] == "white" and "fill-opacity" not in elements[gap][1]
        for i in numbers.values():  # each just after its light box, centred in it, without an outline
            tag, box, _ = elements[i - 1]
            x, y = float(elements[i][1]["x"]), float(elements[i][1]["y"])
            assert tag == "rect" and box["fill-opacity"] == "0.8" and "stroke" not in elements[i][1]
            assert float(box["x"]) + float(box["width"]) / 2 == pytest.approx(x, abs=0.11)
            assert float(box["y"]) + float(box["height"]) / 2 == pytest.approx(y, abs=0.11)
        wide, light = elements[gap][1], elements[numbers[str(mechanism.frame)] - 1][1]
        for start, side in (("x", "width"), ("y", "height")):  # the same middle, 0.3 em of 8 px more each side
            assert float(wide[side]) - float(light[side]) == pytest.approx(2 * 0.3 * 8, abs=0.11)
            assert float(wide[start]) + float(wide[side]) / 2 == pytest.approx(
                float(light[start]) + float(light[side]) / 2, abs=0.11)


def test_the_input_arrow_turns_at_the_input_joint():
    from matplotlib.patches import FancyArrowPatch

    mechanism = Mechanism(WATT_MULTIPLE, 0, 4)
    fig, ax = _axes(mechanism)
    marks = _Marks(WATT_MULTIPLE)
    k = next(i for i, j in enumerate(WATT_MULTIPLE.joints) if set(j) == {0, 4})
    (arrow,) = [p for p in ax.patches if isinstance(p, FancyArrowPatch)]
    x, y = marks.pos[k]
    start, end = arrow._posA_posB
    assert np.allclose(start, (x + 2.6 * marks.r, y)) and np.allclose(end, (x, y + 2.6 * marks.r))
    assert _colour(arrow) == "#c0392b"
