"""The drawing fixes of the review (issue 32), each measured on the drawing itself: multiplicity
numbers clear of the bars and free ends apart on open chains, label size in pixels at the
default sizes, non-planar chains without overlapping link polygons and captioned so, repair
sheets with link numbers and the edits, gear meshes unlike pins, the site keeping joint kinds."""

from __future__ import annotations

import itertools
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.path import Path as MplPath  # noqa: E402

import synth  # noqa: E402
from synth import draw  # noqa: E402
from synth.draw import _render  # noqa: E402
from synth.structure.chain import Chain  # noqa: E402
from mechsynth.cli import main  # noqa: E402

from .test_draw import MOVES_2  # noqa: E402  (440/0, a braced four-bar beside a six-bar loop: a tiny frame plate)


def _drawn(item, labels=True):
    """Draw one item on an axes and return the axes (closed by the caller through plt.close)."""
    fig, ax = plt.subplots(figsize=(3, 3))
    _render._draw(ax, item, labels=labels, caption="x")
    return fig, ax


def _segment_distance(p, a, b) -> float:
    ab = b - a
    t = np.clip(np.dot(p - a, ab) / max(np.dot(ab, ab), 1e-12), 0, 1)
    return float(np.linalg.norm(a + t * ab - p))


def _open_chains():
    found = list(synth.type_synthesis(4, code="2|5/2", workers=1))
    found += [c for c in synth.type_synthesis(3, 8, n1=(1, 3), v=(0, 2), workers=1)]
    return found


def test_open_chains_numbers_clear_of_every_bar_and_free_ends_apart():
    """Every multiplicity number is at least 1.5 joint radii from every bar (the bars to free
    ends included) and 2 radii from every free end's block; two free ends on one joint keep a
    gap of at least two radii between their blocks."""
    chains = [c for c in _open_chains() if 1 in c.degrees]
    assert len(chains) > 20
    numbers = 0
    for chain in chains:
        fig, ax = _drawn(chain)
        try:
            r = _render._Marks(chain).r
            bars = [np.asarray(line.get_xydata()) for line in ax.lines if (line.get_gid() or "").startswith("bar")]
            ends = [np.asarray(p.get_xy())[:4].mean(axis=0) for p in ax.patches if (p.get_gid() or "").startswith("end")]
            assert len(ends) == chain.degrees.count(1)
            for text in ax.texts:
                if (text.get_gid() or "").startswith("multiplicity"):
                    numbers += 1
                    at = np.asarray(text.get_position())
                    clear = min(_segment_distance(at, bar[0], bar[1]) for bar in bars)
                    assert clear >= 1.5 * r, (chain.compact(), text.get_text(), clear / r)
                    assert all(np.linalg.norm(at - e) >= 2 * r for e in ends), chain.compact()
            for a, b in itertools.combinations(ends, 2):
                assert np.abs(a - b).max() >= 4 * r, (chain.compact(), np.abs(a - b).max() / r)  # blocks 2r wide
        finally:
            plt.close(fig)
    assert numbers > 20


def _label_heights(monkeypatch, run) -> list[float]:
    """Heights in pixels of the link numbers of the picture ``run`` writes, at its own resolution."""
    seen = []

    def keep(fig, path, dpi):
        fig.set_dpi(dpi)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        seen.extend(t.get_window_extent(renderer).height for ax in fig.axes for t in ax.texts
                    if (t.get_gid() or "").startswith("label"))

    monkeypatch.setattr(_render, "_save", keep)
    run()
    return seen


def test_labels_are_at_least_14_px_at_the_default_sizes(monkeypatch, tmp_path):
    """The README's watt.png (a sheet of mechanisms) and a single drawing, at their defaults: link
    numbers of 14 px or more (their digits about 10 px; they were 9.7 and 7)."""
    watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    sheet = _label_heights(monkeypatch, lambda: draw.draw_sheet(draw.expand([watt], mechanisms=True),
                                                                 tmp_path / "watt.png"))
    one = _label_heights(monkeypatch, lambda: draw.draw_one(watt, tmp_path / "one.png"))
    assert len(sheet) == 12 and len(one) == 6
    assert min(sheet) >= 14 and min(one) >= 14, (min(sheet), min(one))


def _overlap_points(polygons) -> int:
    """Points of a fine grid strictly inside two link polygons at once."""
    xs = np.linspace(-1.05, 1.05, 351)
    grid = np.array([(x, y) for x in xs for y in xs])
    inside = np.zeros(len(grid), dtype=int)
    for poly in polygons:  # shrunk by 1 % towards its centre: polygons sharing a joint or a side do not overlap
        centre = poly.mean(axis=0)
        inside += MplPath(centre + 0.99 * (poly - centre)).contains_points(grid)
    return int((inside >= 2).sum())


def test_non_planar_chains_have_no_overlapping_link_polygons_and_say_so():
    chains = [c for c in synth.type_synthesis(1, 10, workers=1) if not c.is_planar()]
    assert len(chains) == 11
    for chain in chains:
        lay = draw.layout(chain)
        polygons = [lay.joints[p] for p in lay.polygons if len(p) >= 3]
        assert _overlap_points(polygons) == 0, chain.compact()
        assert "non-planar" in _render._caption(chain, 1)
    assert "non-planar" not in _render._caption(synth.Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), 1)


def test_the_overlap_measure_sees_overlapping_polygons():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float) * 0.5
    assert _overlap_points([square, square + 0.25]) > 0 and _overlap_points([square, square + [0.5, 0]]) == 0


def test_repair_sheet_numbers_links_and_says_each_edit(tmp_path, capsys):
    out = tmp_path / "repairs.svg"
    assert main(["draw", "--chain", "0-1 1-2 2-0 0-3 3-4 4-5 5-1", "--repairs", "--out", str(out)]) == 0
    text = out.read_text()
    words = " ".join(re.findall(r">([^<>]+)</text>", text))
    for link in range(6):
        assert f'id="label{link}"' in text
    assert "move joint 0-1 from link 0" in words and "rigid sub-chain of links 0, 1, 2" in words


def test_gear_meshes_are_drawn_as_pitch_circles_not_pins(tmp_path):
    train = Chain.parse("0-1 0-3 0-4 2-4 1~2 2~3")  # sun 1, planet 2 on carrier 4, ring 3
    out = tmp_path / "train.svg"
    draw.draw_one(train, out)
    text = out.read_text()
    assert len(re.findall(r'id="mesh\d+"', text)) == 4  # two pitch circles for each of the two meshes
    assert len(re.findall(r'id="pin\d+"', text)) == 4  # the four bearings
    inline = draw.svg_inline(train)
    assert inline.count('class="mesh"') == 4
    slider = draw.svg(Chain.parse("0-1 1-2 2=3 3-0"))
    assert re.search(r'id="cylinder\d+"|id="slider\d+"', slider) and "mesh" not in slider


def test_the_site_keeps_joint_kinds_in_its_lists_and_draw_commands(tmp_path):
    from synth.atlas.grid import parse_grid
    from synth.atlas.site import write_site
    from synth.atlas import run_grid

    db = tmp_path / "rp.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..6"\nprismatic = "0..1"'), db, workers=1)
    write_site(db, tmp_path / "site", workers=1)
    pages = " ".join(p.read_text() for p in (tmp_path / "site" / "codes").glob("*.html"))
    commands = re.findall(r'mechsynth draw --chain "([^"]+)"', pages)
    assert commands and any("=" in c for c in commands)
    for command in commands:
        assert Chain.parse(command).compact() == command  # a joint list the draw command reads back as written


def test_every_frame_pivot_carries_a_fixed_pivot_sign_nothing_covers():
    """The fixed link is marked at each of its joints by a support on a hatched base (a short fixed
    link's own hatching hid under its pins and a multiple joint's ring in Fig. 6): drawn above the
    rings and bars, its base clear of every joint's circle and of the multiplicity numbers."""
    from synth import Mechanism

    chain = Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1 1-6 6-3")
    for frame in range(chain.links):
        mech = Mechanism(chain, frame)
        fig, ax = _drawn(mech)
        try:
            marks = _render._Marks(chain)
            r = marks.r
            signs = {p.get_gid(): p for p in ax.patches if (p.get_gid() or "").startswith("ground")}
            assert set(signs) == {f"ground{k}" for k, j in enumerate(chain.joints) if frame in j}
            others = [p for p in ax.patches if p not in signs.values() and not (p.get_gid() or "").startswith("pin")]
            for gid, sign in signs.items():
                assert all(sign.get_zorder() > p.get_zorder() for p in others if p.get_hatch() is None)
                base = np.asarray(sign.get_xy())[1:3].mean(axis=0)  # the middle of the base line
                for j, at in enumerate(marks.pos):
                    reach = 1.75 * r if len(chain.joints[j]) > 2 else r
                    assert np.linalg.norm(base - at) > reach, (frame, gid, j)
                for number in marks.numbers.values():
                    assert np.linalg.norm(base - number) > 1.5 * r, (frame, gid)
        finally:
            plt.close(fig)


WATT = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"
TRANSLATOR = "0-1-6 1-2-7 2-3-8 3-4-9 4-5-10 5-0-11 6-12 8-12 10-12 7-13 9-13 11-13"


def _title_and_drawings(monkeypatch, run):
    """The sheet title's box and the top of its highest drawing, in figure fractions, and the title's
    band (0.45 inch) in the same unit, of the picture ``run`` writes."""
    seen = {}

    def keep(fig, path, dpi):
        fig.canvas.draw()
        seen["title"] = fig._suptitle.get_window_extent().transformed(fig.transFigure.inverted())
        seen["title"].text = fig._suptitle.get_text()
        seen["title"].drawn = sum(1 for ax in fig.axes if ax.has_data())
        seen["top"] = max(ax.get_position().y1 for ax in fig.axes if ax.has_data())
        seen["band"] = 0.45 / fig.get_size_inches()[1]

    monkeypatch.setattr(_render, "_save", keep)
    run()
    return seen["title"], seen["top"], seen["band"]


def test_a_sheet_title_sits_above_every_drawing(monkeypatch, tmp_path):
    """`draw --code 7201/1` (6 columns, its multiple joints' numbers at the top of the first row) and the
    same sheet two columns wide (14 rows): the title's box ends above every drawing's square — its first
    row's "3"s were printed over the title."""
    for columns in ("6", "2"):
        title, top, band = _title_and_drawings(monkeypatch, lambda: main(
            ["draw", "--code", "7201/1", "--columns", columns, "--out", str(tmp_path / "sheet.png")]))
        assert top <= title.y0 < title.y1 <= 1, (columns, title, top)  # over the first row, on the sheet
        assert title.y0 - top <= 2 * band  # and not far above it


def test_the_help_states_the_resolution_the_pictures_have(capsys):
    """`draw --help` said a sheet's PNG had 100 dots per inch; sheets and single drawings have 150."""
    try:
        main(["draw", "--help"])
    except SystemExit:
        pass
    text = " ".join(capsys.readouterr().out.split())
    stated = re.search(r"--dpi DPI resolution of a \.png [^(]*\(default ([^)]*)\)", text).group(1)
    assert {int(d) for d in re.findall(r"\d+", stated)} == {_render.SINGLE[1], _render.CELL[1]}, stated


def _texts_of_other_drawings_overlapping(monkeypatch, run) -> list:
    """Pairs of texts (captions, link and multiplicity numbers, the title) of two different drawings of the
    sheet ``run`` writes whose boxes overlap, in pixels at the sheet's own resolution."""
    seen = []

    def keep(fig, path, dpi):
        fig.set_dpi(dpi)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        boxes = [(k, t.get_text(), t.get_window_extent(renderer)) for k, ax in enumerate(fig.axes)
                 for t in [*ax.texts, ax.title] if t.get_visible() and t.get_text()]
        boxes.append((-1, "title", fig._suptitle.get_window_extent(renderer)))
        seen.extend((a[:2], b[:2]) for a, b in itertools.combinations(boxes, 2) if a[0] != b[0] and a[2].overlaps(b[2]))

    monkeypatch.setattr(_render, "_save", keep)
    run()
    return seen


def test_no_caption_runs_into_the_next_row(monkeypatch, tmp_path):
    """`draw --code 530/1` and the linear translator's bases (loop classes, labels, a key): no text of one
    drawing overlaps a text of another — the captions of 530/1's first two rows lay over the '3's at the tops
    of the rows below (tight_layout set the rows before their equal aspect shrank them; a second pass holds)."""
    for argv in (["--code", "530/1"], ["--chain", TRANSLATOR, "--loop-classes", "3=4,5=1", "--labels", "--title", "t"]):
        assert _texts_of_other_drawings_overlapping(
            monkeypatch, lambda: main(["draw", *argv, "--out", str(tmp_path / "sheet.png")])) == [], argv


@pytest.mark.parametrize("args,title", [
    (["--chain", WATT, "--prismatic", "1..2"], "42/0 (W = 1): {n} variants with 1..2 prismatic pairs"),
    (["--chain", WATT, "--prismatic", "1", "--mechanisms"], "42/0 (W = 1): {n} mechanisms of its variants with 1 "
                                                              "prismatic pair"),
    (["--chain", WATT, "--mechanisms"], "42/0 (W = 1): {n} mechanisms"),
    (["--chain", "0-3 0-4 1-3 1-4 2-3 2-4", "--mechanisms"], "32/0 (W = 0): {n} trusses on a frame"),
    (["--chain", TRANSLATOR, "--loop-classes", "3=4,5=1"], "12.2.0.0.0/6 (W = 1): {n} bases of loop classes 3=4,5=1"),
])
def test_a_sheet_of_one_chain_has_a_title_as_a_code_sheet_has(monkeypatch, tmp_path, args, title):
    """`draw --chain … --prismatic` / `--loop-classes` / `--mechanisms` sheets had no title (a `--code`
    sheet says its code, W and how many it draws): the title names the chain's code, its W, and what the
    sheet's drawings are, counted, over the first row."""
    box, top, _ = _title_and_drawings(monkeypatch, lambda: main(["draw", *args, "--out", str(tmp_path / "s.png")]))
    assert top <= box.y0 < box.y1 <= 1  # over the first row, on the sheet
    assert box.text == title.format(n=box.drawn) and box.drawn > 1


#: the first four drawings of the fig6_cylinders scene's sheet (8310/1 drives, one floating and two swinging cylinders)
FIG6 = ["0-1-2 0-10 1-5 1-6 2=11 3-5 3-7 4-5 4-6 6-7 6-8 7-9 8=9 10=11",
        "0-1-2 0-3 0-6 1=10 2=11 3-4 3-5 4-7 5-6 6-7 6-8 7-9 8=9 10-11",
        "0-1-2 0-10 1-4 1-6 2=11 3-4 3-6 4-7 5-6 5-7 6-8 7-9 8=9 10=11",
        "0-1-2 0-3 0-6 1=10 2=11 3-5 3-7 4-6 4-7 5-6 6-8 7-9 8=9 10-11"]


def _numbers_over_symbols(monkeypatch, run) -> list:
    """(drawing, link number, what it covers) for each link number of the sheet ``run`` writes whose box
    (shrunk by a tenth) meets a pin, slider, cylinder, free end, fixed-pivot sign (struts or hatched base) or
    hatched frame bar, or another number."""
    seen = []

    def keep(fig, path, dpi):
        fig.set_dpi(dpi)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        for k, ax in enumerate(fig.axes):
            numbers = [t for t in ax.texts if (t.get_gid() or "").startswith("label")]
            symbols = [p for p in ax.patches if (p.get_gid() or "").startswith(("pin", "slider", "cylinder", "ground",
                                                                                 "end", "pivotbase", "framebar"))]
            for t in numbers:
                box = t.get_window_extent(renderer).shrunk(0.9, 0.9)
                seen.extend((k, t.get_text(), p.get_gid()) for p in symbols
                            if p.get_path().transformed(p.get_transform()).intersects_bbox(box, filled=True))
            seen.extend((k, a.get_text(), b.get_text()) for a, b in itertools.combinations(numbers, 2)
                        if a.get_window_extent(renderer).overlaps(b.get_window_extent(renderer)))

    monkeypatch.setattr(_render, "_save", keep)
    run()
    return seen


def test_link_numbers_stand_clear_of_cylinders_pins_and_pivot_signs(monkeypatch, tmp_path):
    """A link's number stood at the middle of its joints: on 12-link drawings (the fig6_cylinders scene) under
    its cylinder, a slider, a pin or a fixed-pivot sign (18 overlaps in these four drawings). Placed as the
    motion drawings place them — beside a bar, in a plate, where no symbol is — none is covered, on that
    sheet and on labelled open chains."""
    fig6 = [synth.Mechanism(Chain.parse(text), 0) for text in FIG6]
    assert _numbers_over_symbols(monkeypatch, lambda: draw.draw_sheet(fig6, tmp_path / "f.png", columns=4)) == []
    arm = draw.expand([Chain.parse("0-1 1-2 2-3 3-4")], mechanisms=True)
    assert _numbers_over_symbols(monkeypatch, lambda: draw.draw_sheet(arm, tmp_path / "a.png")) == []
    # open chains with free ends (docs/cli.md's robot_arm.png, labelled): "1" stood over "2" on #3
    assert _numbers_over_symbols(monkeypatch, lambda: main(["draw", "--code", "2|5/2", "--labels", "--out",
                                                            str(tmp_path / "r.png")])) == []


def test_the_frames_number_is_read_clear_of_its_hatching_and_pivot_signs(monkeypatch, tmp_path):
    """On `draw --chain "0-3 0-4 1-3 1-4 2-3 2-4" --mechanisms`, #2, the number 3 of the hatched frame plate stood
    in a box as tight as the other numbers' (a tenth of an em), the hatching's lines running up to it beside a
    pivot sign, and the Watt chain's number 2 touched its hatched frame bar: the frame's number is padded clear
    of the hatching (by an opaque box under it), placed counting that box, and a frame bar counts its hatched width. No number meets a
    symbol — a pivot sign's hatched base and a hatched bar counted now — on these sheets and a 10-link one, and on
    440/0's sheet of MOVES_2, whose tiny frame plate #2 had a pivot sign inside it under its number 1."""
    from matplotlib.patches import FancyBboxPatch

    padding = []

    def keep(fig, path, dpi):
        fig.set_dpi(dpi)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        for ax in fig.axes:
            if not ax.texts:  # a sheet's empty cell
                continue
            frame = int(re.search(r"fixed (\d+)", ax.get_title()).group(1))
            number = next(t for t in ax.texts if t.get_gid() == f"label{frame}")
            gap = next(t for t in ax.texts if t.get_gid() == f"hatchgap{frame}")  # the opaque box under it
            glyph, box = number.get_window_extent(renderer), gap.get_bbox_patch().get_window_extent(renderer)
            assert isinstance(gap.get_bbox_patch(), FancyBboxPatch)
            em = 7 * dpi / 72
            padding.append(min(glyph.x0 - box.x0, box.x1 - glyph.x1, glyph.y0 - box.y0, box.y1 - glyph.y1) / em)

    for chain in ("0-3 0-4 1-3 1-4 2-3 2-4", "0-1 1-2 2-3 3-0 0-4 4-5 5-1",
                  "0-5 0-7 1-5 1-6 2-3 2-7 3-9 4-6 4-9 5-8 6-8 7-9 8-9", MOVES_2):
        run = lambda: main(["draw", "--chain", chain, "--mechanisms", "--out", str(tmp_path / "s.png")])  # noqa: E731
        assert _numbers_over_symbols(monkeypatch, run) == [], chain
        monkeypatch.setattr(_render, "_save", keep)
        run()
    assert len(padding) == 2 + 2 + 10 + 4 and min(padding) >= 0.3, padding


def test_a_fixed_pivot_sign_points_out_of_the_plates_at_its_pin():
    """The sign went into the widest free angle at its pin, which could be a plate's own corner: drawn over
    that plate (the frame's, under its number; a moving one's) in 2 of the 182 pivots of the 1-DOF 8-link
    mechanisms and 6 of the 281 of the 7-link trusses. Every one now points out of the plates there (each
    pin of these has an angle wide enough for it outside them), as matplotlib's point-in-polygon test finds.
    Where no angle outside the plates has the sign's room but one has its struts' (64°), the sign goes there
    too, not into the wider corner of a plate: 440/0's MOVES_2 on its tiny frame plate (fixed 1) and the 10-link
    4600/0 at its frame 4's middle pin (of the 4 840 frame pivots of the 1-DOF 10-link mechanisms 10 pointed into a
    plate, 2 do: no angle there is 64° wide outside the plates; benchmarks/logs/pivot_signs_in_plates.txt) —
    narrowed to the angle, so that its hatched base too stays out of every plate (at full width it reached over
    the tiny plate's side)."""
    tight = [Chain.parse(MOVES_2), Chain.parse("0-3 0-6 1-2 1-8 2-9 3-7 4-5 4-6 4-7 5-8 5-9 6-9 7-8")]
    for chain in [*synth.type_synthesis(1, 8, workers=1), *synth.type_synthesis(0, 7, workers=1), *tight]:
        marks = _render._Marks(chain)
        plates = [MplPath(marks.pos[poly]) for poly in marks.lay.polygons if len(poly) > 2]
        at_pin = [[MplPath(marks.pos[poly]) for poly in marks.lay.polygons if len(poly) > 2 and k in poly]
                  for k in range(len(chain.joints))]
        for k in {k for m in synth.mechanisms_of(chain) for k, j in enumerate(chain.joints) if m.frame in j}:
            direction, width = marks.sign(k)
            assert not any(p.contains_point(marks.pos[k] + 0.01 * direction) for p in at_pin[k]), (chain, k)
            if chain in tight:  # the base's four corners
                across = np.array([-direction[1], direction[0]]) * 2.1 * marks.r * width
                base = marks.pos[k] + 2.4 * marks.r * direction
                corners = [base + s * across + t * marks.r * direction for s in (-1, 1) for t in (0, 0.8)]
                assert not any(p.contains_point(c) for p in plates for c in corners), (chain, k)


def _numbers_on_hatching(monkeypatch, run) -> list:
    """(drawing, link number, hatched shape or line, what is wrong) for each link number of the sheet ``run``
    writes whose glyph box meets a hatched shape (a frame plate's or bar's hatching, a pivot sign's base, a fixed
    free end): only the frame's number on its own plate may, with an opaque box drawn between the hatching and
    the number, 0.3 em clear of the glyph all round, that hides no line or pin."""
    seen = []

    def keep(fig, path, dpi):
        fig.set_dpi(dpi)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        em = 7 * dpi / 72
        for k, ax in enumerate(fig.axes):
            if not ax.texts:  # a sheet's empty cell
                continue
            frame = re.search(r"fixed (\d+)", ax.get_title()).group(1)
            hatched = [p for p in ax.patches if p.get_hatch()]
            drawn = [p for p in ax.patches if not p.get_hatch()] + list(ax.lines)
            boxes = [t for t in ax.texts if t.get_bbox_patch() is not None and t.get_bbox_patch().get_alpha() in (None, 1)]
            for t in (t for t in ax.texts if (t.get_gid() or "").startswith("label")):
                glyph = t.get_window_extent(renderer)
                for p in hatched:
                    if not p.get_path().transformed(p.get_transform()).intersects_bbox(glyph, filled=True):
                        continue
                    if t.get_text() != frame or (p.get_gid() or "").startswith(("framebar", "pivotbase", "end")):
                        seen.append((k, t.get_text(), p.get_gid(), "a number on hatching not its plate's"))
                        continue
                    around = glyph.padded(0.3 * em)
                    cover = [b for b in boxes if p.get_zorder() < b.get_zorder() <= t.get_zorder()
                             and all(b.get_bbox_patch().get_window_extent(renderer).contains(x, y)
                                     for x, y in around.corners())]
                    if not cover:
                        seen.append((k, t.get_text(), p.get_gid(), "the hatching seen through its box"))
                    for b in cover:
                        box = b.get_bbox_patch().get_window_extent(renderer)
                        seen.extend((k, t.get_text(), q.get_gid(), "its box over a line") for q in drawn
                                    if q.get_zorder() < b.get_zorder() and q is not p
                                    and q.get_path().transformed(q.get_transform()).intersects_bbox(box, filled=False))

    monkeypatch.setattr(_render, "_save", keep)
    run()
    return seen


@pytest.mark.parametrize("chain", [MOVES_2, WATT, "0-3 0-4 1-3 1-4 2-3 2-4",
                                   "0-5 0-7 1-5 1-6 2-3 2-7 3-9 4-6 4-9 5-8 6-8 7-9 8-9"])
def test_no_number_is_read_through_a_frames_hatching(monkeypatch, tmp_path, chain):
    """`draw --chain MOVES_2 --mechanisms` (440/0): the numbers 0 and 1 of its hatched frame plates (#1, #2) stood in
    boxes at 0.8 over the hatching, whose lines ran through them a fifth as dark; made opaque over everything, the
    box of 1 on the tiny plate of #2 hid a pin. The frame plate's number stands over an opaque box drawn over its
    hatching and under every line and pin; every other number is clear of every hatched shape (the frame's bar, its
    free ends, the pivot signs' bases), on these sheets: the braced four-bar, the Watt chain, 32/0 and a 10-link
    chain. (Main's 440/0 #3, fixed 4: its number 4 stood 13 px clear of the hatched bar, and stands so.)"""
    run = lambda: main(["draw", "--chain", chain, "--mechanisms", "--out", str(tmp_path / "s.png")])  # noqa: E731
    assert _numbers_on_hatching(monkeypatch, run) == []
