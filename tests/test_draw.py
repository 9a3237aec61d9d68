"""Drawings: layouts without crossings for planar chains, files written, CLI selections."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

import synth
from synth import draw
from synth.draw import _render
from synth.structure.chain import Chain, Mechanism
from mechsynth.cli import main


@pytest.fixture(scope="module")
def eight() -> list[Chain]:
    return list(synth.type_synthesis(1, 8, workers=1))


def test_layout_shapes_and_polygons(eight):
    for chain in eight:
        lay = draw.layout(chain)
        assert lay.joints.shape == (len(chain.joints), 2) and np.isfinite(lay.joints).all()
        for link, poly in enumerate(lay.polygons):
            assert sorted(poly) == sorted(k for k, j in enumerate(chain.joints) if link in j)
        gaps = [np.linalg.norm(lay.joints[a] - lay.joints[b])
                for a in range(len(lay.joints)) for b in range(a + 1, len(lay.joints))]
        assert min(gaps) > 0.05  # no two joints drawn on top of each other


def test_planar_chains_are_drawn_without_crossings(eight):
    clean = [draw.layout(c).planar for c in eight]
    assert sum(clean) >= len(eight) - 1, clean  # the relaxation never adds a crossing to the Tutte start
    assert draw.layout(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")).planar


def test_layout_is_deterministic(eight):
    a, b = draw.layout(eight[3]), draw.layout(eight[3])
    assert np.array_equal(a.joints, b.joints) and a.polygons == b.polygons


def test_non_planar_chain_still_draws(tmp_path):
    # K3,3-like: 2-DOF? any chain whose incidence graph is not planar
    chain = Chain.parse("0-3 0-4 0-5 1-3 1-4 1-5 2-3 2-4 2-5")
    assert not chain.is_planar()
    lay = draw.layout(chain)
    assert not lay.planar and np.isfinite(lay.joints).all()
    draw.draw_one(chain, tmp_path / "k33.png")
    assert (tmp_path / "k33.png").stat().st_size > 0


def test_one_mechanism_svg_has_hatching_and_multiple_joint(tmp_path):
    out = tmp_path / "m.svg"
    draw.draw_one(Mechanism(Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1"), frame=0), out)
    text = out.read_text()
    assert "<svg" in text and "pattern" in text  # the fixed link is hatched
    again = tmp_path / "m2.svg"
    draw.draw_one(Mechanism(Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1"), frame=0), again)
    assert again.read_text() == text  # deterministic output


def test_sheet_png(tmp_path, eight):
    out = tmp_path / "sheet.png"
    draw.draw_sheet(eight, out, title="1-DOF, 8 links")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size < 300_000


def test_cli_draw_sources(tmp_path, capsys):
    assert main(["draw", "--code", "620/0-1", "--out", str(tmp_path / "a.svg")]) == 0
    assert main(["draw", "--chain", "0-1 1-2 2-3 3-0", "--frame", "0", "--out", str(tmp_path / "b.png")]) == 0
    assert main(["draw", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--mechanisms",
                 "--out", str(tmp_path / "c.png")]) == 0
    db = tmp_path / "a.sqlite"
    assert main(["grid", "--db", str(db), "--workers", "1", str(_grid(tmp_path))]) == 0
    assert main(["draw", "--db", str(db), "--where", "n=6", "--out", str(tmp_path / "d.png")]) == 0
    for name in "abcd":
        assert next(tmp_path.glob(f"{name}.*")).stat().st_size > 0
    capsys.readouterr()
    assert main(["draw", "--db", str(db), "--where", "n=12", "--out", str(tmp_path / "e.png")]) == 1
    assert main(["draw", "--code", "440/0", "--out", str(tmp_path / "f.gif")]) == 2
    assert main(["draw", "--code", "440/0", "--frame", "1", "--out", str(tmp_path / "g.png")]) == 2
    assert main(["draw", "--code", "440/0", "--out", str(tmp_path / "no" / "h.png")]) == 2
    errors = [line for line in capsys.readouterr().err.splitlines() if line.startswith("mechsynth:")]
    assert len(errors) == 4


def _grid(tmp_path):
    path = tmp_path / "g.toml"
    path.write_text('dof = 1\nlinks = "4..6"\n')
    return path


def test_chains_and_mechanisms_show_themselves_in_jupyter():
    """_repr_svg_: an SVG with one circle per joint and a hatched frame for a mechanism."""
    from synth.structure.chain import Chain, Mechanism

    watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    text = watt._repr_svg_()
    assert text.lstrip().startswith("<?xml") and "</svg>" in text and "42/0" in text
    mech = Mechanism(watt, 0)._repr_svg_()
    assert "fixed 0" in mech and mech != text
    arm = Chain(4, ((0, 2), (1, 3), (2, 3)), h=4)  # a serial arm in h = 4: free ends and the space named
    assert "h=4" in arm._repr_svg_()


# ------------------------------------------------------------ drawing quality, checked independently
def _sides_of(polygons):
    out = []
    for poly in polygons:
        if len(poly) == 2:
            out.append(tuple(poly))
        elif len(poly) > 2:
            out += [(poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly))]
    return out


def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _segments_meet(p, q, r, s, eps=1e-9):
    """Closed segments pq and rs share a point (touching counts)."""
    d1, d2, d3, d4 = _cross(r, s, p), _cross(r, s, q), _cross(p, q, r), _cross(p, q, s)
    if ((d1 > eps and d2 < -eps) or (d1 < -eps and d2 > eps)) and ((d3 > eps and d4 < -eps) or (d3 < -eps and d4 > eps)):
        return True

    def on(a, b, c):  # c on segment ab
        return abs(_cross(a, b, c)) <= eps and min(a[0], b[0]) - eps <= c[0] <= max(a[0], b[0]) + eps \
            and min(a[1], b[1]) - eps <= c[1] <= max(a[1], b[1]) + eps
    return on(r, s, p) or on(r, s, q) or on(p, q, r) or on(p, q, s)


def _inside(point, polygon):
    """Ray casting: point strictly inside the polygon."""
    x, y = point
    hit = False
    for (x0, y0), (x1, y1) in zip(polygon, np.roll(polygon, -1, axis=0)):
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            hit = not hit
    return hit


def _drawing_faults(chain: Chain) -> list[str]:
    """What a designer would reject in a drawing: crossings, joints on foreign sides or inside foreign
    links, concave link polygons, corners under 15°."""
    lay = draw.layout(chain)
    pos, faults = lay.joints, []
    sides = _sides_of(lay.polygons)
    for i, (a, b) in enumerate(sides):
        for c, d in sides[i + 1:]:
            if len({a, b, c, d}) == 4 and _segments_meet(pos[a], pos[b], pos[c], pos[d]):
                faults.append(f"sides {a}-{b} and {c}-{d} cross")
        for k in range(len(pos)):
            if k not in (a, b) and _segments_meet(pos[a], pos[b], pos[k], pos[k], eps=1e-6):
                faults.append(f"joint {k} lies on side {a}-{b}")
    for link, poly in enumerate(lay.polygons):
        if len(poly) < 3:
            continue
        pts = pos[poly]
        turns = [_cross(pts[i - 1], pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
        if not (all(t > 0 for t in turns) or all(t < 0 for t in turns)):
            faults.append(f"link {link} is concave")
        for i in range(len(pts)):
            u, w = pts[i - 1] - pts[i], pts[(i + 1) % len(pts)] - pts[i]
            angle = np.degrees(np.arccos(np.clip(u @ w / np.linalg.norm(u) / np.linalg.norm(w), -1, 1)))
            if angle < 15:
                faults.append(f"link {link} has a {angle:.0f}° corner")
        for k in range(len(pos)):
            if k not in poly and _inside(pos[k], pts):
                faults.append(f"joint {k} lies inside link {link}")
    return faults


@pytest.mark.parametrize("dof, links, query", [
    (1, 4, {}), (1, 6, {}), (1, 8, {}), (1, 10, {}),
    (2, 5, {}), (2, 7, {}), (2, 9, {}),
    (3, 6, {}), (3, 8, {}), (3, 10, {}),
    (1, 6, {"v": (1, 2)}), (1, 8, {"v": (1, 4)}),
    (3, 6, {"n1": (1, 3)}), (3, 8, {"n1": (1, 3)}),
])
def test_every_planar_chain_is_drawn_convex_without_crossings(dof, links, query):
    """Every planar chain up to 10 links (fractionated, multiple joints and open chains included):
    convex link polygons, corners of 15° or more, no crossing, no joint on a foreign side or link."""
    chains = [c for c in synth.type_synthesis(dof, links, workers=1, **query) if c.is_planar()]
    assert chains
    faults = {c.compact(): f for c in chains if (f := _drawing_faults(c))}
    assert not faults, faults


def test_the_quality_check_sees_a_bad_drawing(monkeypatch):
    """The checker itself: a sliver triangle and swapped joints are found."""
    chain = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    good = draw.layout(chain)
    bent = good.joints.copy()
    triangle = next(p for p in good.polygons if len(p) == 3)
    bent[triangle[0]] = bent[triangle[1:]].mean(axis=0) * 0.999 + 0.001 * bent[triangle[0]]  # a sliver
    monkeypatch.setattr(draw, "layout", lambda c: draw.Layout(bent, good.polygons, True))
    assert any("corner" in f for f in _drawing_faults(chain))
    crossed = good.joints.copy()
    crossed[[0, 1]] = crossed[[1, 0]]
    monkeypatch.setattr(draw, "layout", lambda c: draw.Layout(crossed, good.polygons, True))
    assert _drawing_faults(chain)


def test_cli_size_dpi_and_labels(tmp_path, capsys):
    from PIL import Image

    chain = ["draw", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1"]
    assert main([*chain, "--out", str(tmp_path / "small.png")]) == 0
    assert main([*chain, "--size", "6", "--dpi", "200", "--out", str(tmp_path / "big.png")]) == 0
    with Image.open(tmp_path / "small.png") as small, Image.open(tmp_path / "big.png") as big:
        assert small.width >= 400 and big.width > 2 * small.width  # print size on request
    assert main([*chain, "--no-labels", "--out", str(tmp_path / "bare.svg")]) == 0
    assert main([*chain, "--out", str(tmp_path / "numbered.svg")]) == 0
    assert len((tmp_path / "numbered.svg").read_text()) > len((tmp_path / "bare.svg").read_text())
    capsys.readouterr()
    for bad in (["--dpi", "100", "--out", str(tmp_path / "x.svg")], ["--size", "0.1", "--out", str(tmp_path / "x.png")],
                ["--dpi", "5000", "--out", str(tmp_path / "x.png")]):
        assert main([*chain, *bad]) == 2
        err = capsys.readouterr().err
        assert err.startswith("mechsynth:") and err.count("\n") == 1 and "Traceback" not in err


def test_columns_arrange_a_sheet_and_are_refused_for_one_drawing(tmp_path, capsys):
    """'draw --chain … --columns 3' drew the one chain and ignored --columns: it is refused where the picture is
    one drawing, and on a sheet it sets the drawings per row (one column: a sheet taller than wide)."""
    from PIL import Image

    watt = ["draw", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1"]
    for one in ([], ["--frame", "0"]):
        assert main([*watt, *one, "--columns", "3", "--out", str(tmp_path / "x.png")]) == 2
        err = capsys.readouterr().err
        assert err.startswith("mechsynth: --columns") and err.count("\n") == 1 and not (tmp_path / "x.png").exists()
    shapes = []
    for columns in ("1", "4"):
        assert main([*watt, "--mechanisms", "--columns", columns, "--out", str(tmp_path / f"c{columns}.png")]) == 0
        with Image.open(tmp_path / f"c{columns}.png") as sheet:
            shapes.append(sheet.height / sheet.width)
    assert shapes[0] > 1 > shapes[1]  # Watt's two mechanisms (I and II) one above the other, then side by side


def test_mechanism_sheets_number_their_links(tmp_path, monkeypatch):
    """Captions of mechanisms name the fixed link, so the sheet numbers the links."""
    labels, real = [], _render._draw

    def spy(ax, item, **kw):
        labels.append(kw["labels"])
        return real(ax, item, **kw)

    monkeypatch.setattr(_render, "_draw", spy)
    mechanisms = draw.expand([Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")], mechanisms=True)
    draw.draw_sheet(mechanisms, tmp_path / "m.png")
    draw.draw_sheet([Chain.parse("0-1 1-2 2-3 3-0")], tmp_path / "c.png")
    draw.draw_sheet([Chain.parse("0-1 1-2 2-3 3-0")], tmp_path / "l.png", labels=True)
    assert labels == [True] * len(mechanisms) + [False, True]


def test_draw_prismatic_variants(tmp_path, capsys):
    """Sliders drawn as blocks, cylinders as barrels: one drawing per R/P variant, as many as
    ``chains --chain … --prismatic`` lists; the caption carries the P count."""
    from synth.synthesis.variants import variants_of

    watt = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"
    variants = list(variants_of([Chain.parse(watt)], (1, 2)))
    assert main(["draw", "--chain", watt, "--prismatic", "1..2", "--out", str(tmp_path / "w.svg")]) == 0
    assert f"{len(variants)} drawings" in capsys.readouterr().err
    assert _render._caption(variants[-1], None).startswith("42/0 P2")
    for bad in (["--idle-joints"], ["--prismatic", "1", "--frame", "0"], ["--prismatic", "9"],
                ["--prismatic", "1", "--h", "4"]):
        assert main(["draw", "--chain", watt, *bad, "--out", str(tmp_path / "x.png")]) == 2
        err = capsys.readouterr().err
        assert err.startswith("mechsynth:") and err.count("\n") == 1


def test_cli_draw_checks_its_output_before_drawing(tmp_path, monkeypatch, capsys):
    """An --out that cannot be written (a path under a file) is refused before any chain is drawn:
    `draw --code 7201/1 --out /proc/x.png` once drew its 27 chains for seconds, then failed to save."""
    (tmp_path / "plain").write_text("a file, not a folder")

    def never(*args, **kwargs):
        raise AssertionError("drawn before the output was checked")

    monkeypatch.setattr(draw, "draw_sheet", never)
    monkeypatch.setattr(draw, "draw_one", never)
    assert main(["draw", "--code", "7201/1", "--out", str(tmp_path / "plain" / "x.png")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsynth: ") and "plain" in err and "Traceback" not in err


def test_a_structure_has_no_mechanisms_to_draw_or_list(tmp_path, capsys):
    """A chain of W = −1 by the count (a four-bar with a diagonal) is a structure: its mechanisms are refused,
    drawn or listed, as a code of W < 0 is; the chain itself is still drawn, and its R/P variants that move
    (wedge loops add to W) keep their mechanisms."""
    braced = "0-1 1-2 2-3 3-0 1-3"
    out = tmp_path / "m.png"
    assert main(["draw", "--chain", braced, "--mechanisms", "--out", str(out)]) == 2
    assert "is a structure, not a mechanism's chain: W = -1 by the count" in capsys.readouterr().err
    assert not out.exists()
    assert main(["mechanisms", "--chain", braced]) == 2
    assert "is a structure, not a mechanism's chain: W = -1" in capsys.readouterr().err
    assert main(["draw", "--chain", braced, "--out", str(out)]) == 0  # the chain, drawn as analyze reports it
    assert main(["draw", "--chain", braced, "--mechanisms", "--prismatic", "1..5", "--out", str(out)]) == 0
    assert "11 drawings" in capsys.readouterr().err  # its 11 variants of W ≥ 0 on each frame
    assert main(["draw", "--chain", "0-1 1-2 2-0", "--mechanisms", "--out", str(out)]) == 0  # W = 0: a truss, fixed


def test_a_structure_is_not_drawn_on_a_frame(tmp_path, capsys):
    """`draw --chain C --frame F` drew a chain of W = −1 by the count as a mechanism on F, without a word, where
    --mechanisms refused it: one fixed link is refused as every one is."""
    out = tmp_path / "f.png"
    assert main(["draw", "--chain", "0-1 1-2 2-3 3-0 1-3", "--frame", "0", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "is a structure, not a mechanism's chain: W = -1 by the count" in err and err.count("\n") == 1
    assert not out.exists()
    assert main(["draw", "--chain", "0-1 1-2 2-3 3-0", "--frame", "0", "--out", str(out)]) == 0 and out.exists()


TRUSS = "0-3 0-4 1-3 1-4 2-3 2-4"  # 32/0, the five-link statically determinate truss (W = 0)


def _table_end(capsys, *words) -> tuple[int, str]:
    """The rows and the last line of a ``mechanisms`` table."""
    assert main(["mechanisms", *words]) == 0
    lines = capsys.readouterr().out.splitlines()
    return len(lines) - 3, lines[-1]  # the heading, its rule, the last line


def test_a_chain_of_w_0_on_a_frame_is_named_a_truss(tmp_path, capsys):
    """A chain of W = 0 on a frame is a statically determinate structure, not a mechanism: the listings, the
    sheets and the captions named them "N mechanisms"; they say trusses on a frame, and a listing mixing both
    counts each (against the W column of the same rows as CSV)."""
    assert _table_end(capsys, "--chain", TRUSS) == (2, "2 trusses on a frame (W = 0: statically determinate, nothing "
                                                       "moves)")
    assert _table_end(capsys, "--dof", "0", "--links", "5") == (7, "7 trusses on a frame (W = 0: statically "
                                                                   "determinate, nothing moves)")
    assert _table_end(capsys, "--dof", "1", "--links", "6") == (5, "5 mechanisms")
    braced = ["--chain", "0-1 1-2 2-3 3-0 1-3", "--prismatic", "1..5"]  # W = -1: its variants of W = 0 and 1
    rows, end = _table_end(capsys, *braced)
    assert main(["mechanisms", *braced, "--format", "csv"]) == 0
    dofs = [row["dof"] for row in csv.DictReader(io.StringIO(capsys.readouterr().out))]
    assert len(dofs) == rows == 11
    assert end == (f"{sum(w != '0' for w in dofs)} mechanisms and {dofs.count('0')} trusses on a frame (W = 0: "
                   "statically determinate, nothing moves)") == ("2 mechanisms and 9 trusses on a frame (W = 0: "
                                                                 "statically determinate, nothing moves)")
    out = tmp_path / "t.png"
    assert main(["draw", "--chain", TRUSS, "--frame", "0", "--out", str(out)]) == 0  # a truss on its frame: drawn
    assert main(["draw", "--chain", TRUSS, "--mechanisms", "--out", str(out)]) == 0
    assert "2 drawings" in capsys.readouterr().err


@pytest.mark.parametrize("words", [["--chain", TRUSS], ["--dof", "0", "--links", "5"], ["--code", "32/0", "--count"],
                                   ["--dof", "0", "--links", "5", "--prismatic", "1"]])
def test_a_truss_has_no_input_link(words, capsys):
    """--input-link chose an input link of each truss on a frame (11 of W = 0 at 5 links), which nothing moves."""
    assert main(["mechanisms", *words, "--input-link"]) == 2
    err = capsys.readouterr().err
    assert "W = 0 by the count: on a frame a truss is a statically determinate structure" in err
    assert err.count("\n") == 1
    assert main(["mechanisms", "--dof", "1", "--links", "4", "--input-link"]) == 0  # a crank-rocker's crank


def test_among_variants_that_move_a_truss_gets_no_input_link(capsys):
    """The braced four-bar's variants with --input-link: each of W = 1 with its input links, each truss (W = 0)
    on its frame alone, as without --input-link."""
    braced = ["mechanisms", "--chain", "0-1 1-2 2-3 3-0 1-3", "--prismatic", "1..5", "--format", "csv"]

    def rows(*more):
        assert main([*braced, *more]) == 0
        return list(csv.DictReader(io.StringIO(capsys.readouterr().out)))

    plain, driven = rows(), rows("--input-link")
    trusses = [(r["chain_id"], r["frame"]) for r in driven if r["dof"] == "0"]
    assert trusses == [(r["chain_id"], r["frame"]) for r in plain if r["dof"] == "0"] and len(trusses) == 9
    assert all(r["input_link"] == "" for r in driven if r["dof"] == "0")
    moving = [r for r in driven if r["dof"] != "0"]
    assert moving and all(r["input_link"] not in ("", r["frame"]) for r in moving)


MOVING = "0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-2"  # a braced four-bar (W(S) = -1) beside a five-bar loop: W = 0, moves


def test_a_chain_of_w_0_by_the_count_that_moves_is_no_truss(capsys):
    """The truss wording went by the count: this chain, which moves with one degree of freedom, was listed as
    "4 trusses on a frame (W = 0: statically determinate, nothing moves)", its sheet titled '4 trusses on a frame'
    and its drawings captioned 'fixed 0 (truss)'; --input-link was refused as for a truss that does not move."""
    from mechsynth.commands.draw import _chain_sheet_title
    from argparse import Namespace

    assert _table_end(capsys, "--chain", MOVING) == (4, "4 chains on a frame, not trusses: W = 0 by the count, but a "
                                                        "sub-chain is over-constrained (W(S) = -1) and the links move "
                                                        "with W = 1 ('mechsynth analyze' says where)")
    chain = Chain.parse(MOVING)
    items = synth.mechanisms_of(chain)
    sheet = Namespace(loop_classes=None, prismatic=None, mechanisms=True)
    assert _chain_sheet_title(chain, items, sheet) == "340/0 (W = 0 by the count): 4 chains on a frame, not trusses"
    assert [_render._caption(m, None)[-len("(not a truss)"):] for m in items] == ["(not a truss)"] * 4
    truss = Chain.parse(TRUSS)
    assert _render._caption(Mechanism(truss, 0), None).endswith("fixed 0 (truss)")
    assert main(["mechanisms", "--chain", MOVING, "--input-link"]) == 2
    err = capsys.readouterr().err
    assert ("has W = 0 by the count, not a truss: a sub-chain is over-constrained (W(S) = -1) and the links move "
            "with W = 1; an input link is chosen by the count's W, so --input-link would name links that cannot "
            "drive it") in err
    assert err.count("\n") == 1


MOVES_2 = "0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-7 7-2"  # a braced four-bar beside a six-bar loop: W = 1, moves with 2
RIGID = "0-1 1-2 2-0 2-3 3-4 4-5 5-0"  # a four-bar whose frame is a triangle of three links: W = 1, degenerate


def test_a_chain_of_w_1_whose_count_misleads_is_not_named_a_mechanism_of_w_1(tmp_path, capsys):
    """The check of a chain given by hand ran at W = 0 only: a chain of W = 1 by the count that moves with two
    degrees of freedom was listed as "4 mechanisms", its sheet titled so; and a four-bar whose frame is a rigid
    triangle was listed as a plain mechanism.  Now the listing, the sheet's title, the captions and
    --input-link say what each is."""
    from mechsynth.commands.draw import _chain_sheet_title
    from argparse import Namespace

    assert _table_end(capsys, "--chain", MOVES_2) == (4, "4 chains on a frame, not mechanisms of W = 1: W = 1 by the "
                                                         "count, but a sub-chain is over-constrained (W(S) = -1) and "
                                                         "the links move with W = 2 ('mechsynth analyze' says where)")
    assert _table_end(capsys, "--chain", RIGID) == (4, "4 degenerate mechanisms: W = 1, but a sub-chain is rigid "
                                                       "(W(S) = 0), one link in effect ('mechsynth analyze' says where)")
    sheet = Namespace(loop_classes=None, prismatic=None, mechanisms=True)
    for given, title, caption in ((MOVES_2, "440/0 (W = 1 by the count): 4 chains on a frame, not mechanisms of "
                                   "W = 1", "(not W = 1)"), (RIGID, "42/0 (W = 1): 4 degenerate mechanisms",
                                                             "(degenerate)")):
        chain = Chain.parse(given)
        items = synth.mechanisms_of(chain)
        assert _chain_sheet_title(chain, items, sheet) == title
        assert all(_render._caption(m, 1).endswith(caption) for m in items)
        assert main(["mechanisms", "--chain", given, "--input-link"]) == 2
        err = capsys.readouterr().err
        assert "has W = 1 by the count, " in err and "so --input-link would name links that cannot drive it" in err
        assert err.count("\n") == 1
    watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")  # the engine's Watt chain: no word more
    assert [_render._caption(m, 1) for m in synth.mechanisms_of(watt)] == ["42/0  #1  fixed 0", "42/0  #1  fixed 2"]
    assert _table_end(capsys, "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1") == (2, "2 mechanisms")
    out = tmp_path / "m.png"
    assert main(["draw", "--chain", MOVES_2, "--mechanisms", "--out", str(out)]) == 0 and out.exists()
    assert main(["draw", "--chain", MOVES_2, "--frame", "0", "--out", str(out)]) == 0


def test_mechanisms_of_a_listing_of_trusses_are_not_checked_again(capsys):
    """Listed chains passed the exact sub-chain test in type synthesis: a listing of trusses names them by their
    count without testing each again (the test runs on a chain given by hand only)."""
    from unittest import mock

    with mock.patch("synth.structure.trusses.check_subchains", side_effect=AssertionError("tested again")):
        assert _table_end(capsys, "--dof", "0", "--links", "5", "--workers", "1")[1].startswith("7 trusses on a frame")
        with pytest.raises(AssertionError, match="tested again"):  # where a chain given by hand is
            main(["mechanisms", "--chain", TRUSS])


def test_a_chain_beyond_the_exact_test_is_listed_by_its_count_with_a_note(capsys):
    """The check of a chain given by hand ran at W ≥ 1 too, and the exact test takes 24 non-binary links: a
    ladder of 15 rungs (26) would have been refused where it was listed before; it is listed by its count, with
    a note that the count is not checked, and its drawings' captions claim nothing."""
    rungs = 15
    joints = [f"{i}-{i + 1} {rungs + i}-{rungs + i + 1}" for i in range(rungs - 1)] + [f"{i}-{rungs + i}"
                                                                                       for i in range(rungs)]
    ladder = " ".join(joints)
    rows, end = _table_end(capsys, "--chain", ladder)
    assert rows == 8 and end == "8 mechanisms"
    assert main(["mechanisms", "--chain", ladder, "--count"]) == 0
    assert "not 26, so this chain's W by the count is not checked" in capsys.readouterr().err
    assert _render._caption(Mechanism(Chain.parse(ladder), 0), 1).endswith("fixed 0")
