"""Drawings: layouts without crossings for planar chains, files written, CLI selections."""

from __future__ import annotations

import numpy as np
import pytest

import synth
from synth import draw
from synth.chain import Chain, Mechanism
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
    from synth.chain import Chain, Mechanism

    watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    text = watt._repr_svg_()
    assert text.lstrip().startswith("<?xml") and "</svg>" in text and "42/0" in text
    mech = Mechanism(watt, 0)._repr_svg_()
    assert "fixed 0" in mech and mech != text
    arm = Chain(4, ((0, 2), (1, 3), (2, 3)), h=4)  # a serial arm in h = 4: free ends and the space named
    assert "h=4" in arm._repr_svg_()
