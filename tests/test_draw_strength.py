"""What a drawing holds, mark by mark: for each joint its mark by kind (a pin circle, a slider's block or a
cylinder's barrel, two pitch circles), where it stands and its colour; the multiple joint's ring and number, the
fixed link's hatching and pivot signs, the input arrow, the link numbers at their links, the captions; a sheet's
grid; the inline SVG's elements at the layout's points.  Read from the matplotlib artists and the SVG itself."""

from __future__ import annotations

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
        joints = marks.lay.polygons[i]
        assert np.allclose(text.get_position(), pos[joints].mean(axis=0))
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
    square = _by_gid(ax, "end3")["end3"]
    assert np.allclose(square.get_xy()[:4].mean(axis=0), end) and square.get_hatch() == "////"  # the frame
    assert np.linalg.norm(end - marks.pos[marks.lay.polygons[3][0]]) == pytest.approx(max(0.35, 6 * marks.r))


def test_captions_by_hand():
    assert _caption(Mechanism(WATT_MULTIPLE, 0, 4), 3) == "51/1  #3  fixed 0, input 4"
    assert _caption(Mechanism(WATT_MULTIPLE, 2), None) == "51/1  fixed 2"
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
