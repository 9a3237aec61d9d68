"""Grid files: expansion into cells and units, and one clear sentence for every malformed file."""

from __future__ import annotations

from pathlib import Path

import pytest

import synth
from mechsynth.cli import main
from synth.atlas.grid import Cell, GridFileError, load_grid, parse_grid

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "models" / "grid_small.toml"


def test_small_grid_cells():
    grid = load_grid(SMALL)
    assert grid.name == "small"
    pairs = [(c.dof, c.links) for c in grid.cells]
    assert pairs == [(1, 4), (1, 6), (1, 8), (1, 10), (2, 5), (2, 7), (2, 9), (3, 6), (3, 8), (3, 10)]
    assert all(c.v == (0, 2) and c.fractionated and not c.rigid_subchains for c in grid.cells)
    keys = [c.key for c in grid.cells]
    assert len(set(keys)) == len(keys)


def test_cell_units_are_the_engine_units():
    cell = Cell(1, 8, (0, 0))
    assert [u.key for u in cell.plan()] == [u.key for u in synth.plan_units(1, 8)]
    assert sum(len(synth.run_unit(u)) for u in cell.plan()) == 16


def test_blocks_override_defaults_and_duplicates_merge():
    grid = parse_grid("""
dof = 1
v = 0
[[block]]
links = [6, 8]
[[block]]
links = 8            # the same cell again: merged
[[block]]
loops = 2
dof = "2..3"
fractionated = false
require = ["4=0"]
""")
    keys = [c.key for c in grid.cells]
    assert keys == [
        "W=1 n=6 v=0..0 rigid=0 frac=1 planar=0",
        "W=1 n=8 v=0..0 rigid=0 frac=1 planar=0",
        "W=2 n=7 v=0..0 rigid=0 frac=0 planar=0 require=4=0..0",
        "W=3 n=8 v=0..0 rigid=0 frac=0 planar=0 require=4=0..0",
    ]


def test_truss_cells_allow_rigid_subchains_by_default():
    (cell,) = parse_grid("dof = 0\nlinks = 5").cells
    assert cell.rigid_subchains


@pytest.mark.parametrize(
    "text, words",
    [
        ("dof = 1\nlinks = [4, 6\n", ["not valid TOML"]),
        ("dof = 1\nlinks = 8\nlnks = 9\n", ["unknown key 'lnks'"]),
        ("dof = 1\n[[block]]\nlinks = 8\nplanar = true\n", ["[[block]] 1", "'planar'"]),
        ("dof = 1\nlinks = true\n", ["'links'", "whole number"]),
        ("dof = 1\nlinks = 8\nfractionated = \"yes\"\n", ["'fractionated'", "true or false"]),
        ("dof = 1\nlinks = 8\nv = 1.5\n", ["'v'"]),
        ("dof = 1\nlinks = \"10..4\"\n", ["'links'", "empty"]),
        ("dof = \"3..1\"\nlinks = 8\n", ["'dof'", "empty"]),
        ("dof = 1\nlinks = []\n", ["'links'"]),
        ("links = 8\n", ["'dof'", "missing"]),
        ("dof = 1\nlinks = 8\nloops = 3\n", ["exactly one of 'links'"]),
        ("dof = 1\nlinks = 5\n", ["whole number of loops"]),
        ("dof = 1\nlinks = \"4..\"\n", ["no upper end"]),
        ("dof = 1\nlinks = 8\nrequire = [\"x=1\"]\n", ["'require'"]),
        ("dof = 1\nlinks = 8\nname = 3\n", ["'name'", "string"]),
    ],
)
def test_malformed_grid_is_one_sentence(text, words):
    with pytest.raises(GridFileError) as info:
        parse_grid(text, source="g.toml")
    message = str(info.value)
    assert message.startswith("grid file g.toml") and "\n" not in message
    for word in words:
        assert word in message


@pytest.mark.parametrize("text", ["dof = 1\nlinks = 8\nlnks = 9\n", "dof = 1\nlinks = \"9..4\"\n", "dof = [\n"])
def test_cli_refuses_malformed_grid_without_touching_db(tmp_path, capsys, text):
    grid = tmp_path / "bad.toml"
    grid.write_text(text)
    db = tmp_path / "atlas.sqlite"
    assert main(["grid", str(grid), "--db", str(db)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("mechsynth: grid file") and str(grid) in err and "\n" not in err
    assert not db.exists()


def test_missing_grid_file(tmp_path, capsys):
    assert main(["grid", str(tmp_path / "none.toml"), "--db", str(tmp_path / "a.sqlite")]) == 2
    assert "does not exist" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["synth.atlas.grid", "synth.atlas.database", "synth.atlas.runs", "synth.atlas.queries", "synth.atlas.trains", "synth.draw", "mechsynth.commands.atlas"])
def test_docstring_examples(name, tmp_path, monkeypatch):
    import doctest
    import importlib

    monkeypatch.chdir(ROOT)
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0


@pytest.mark.parametrize("path", sorted((ROOT / "models").glob("grid_*.toml")), ids=lambda p: p.name)
def test_every_shipped_grid_file_reads(path):
    grid = load_grid(path)
    assert grid.cells or grid.gear_cells
    assert all(cell.plan() for cell in grid.cells if cell.links <= 8)


@pytest.mark.parametrize("text, words", [
    ('dof = 1\nlinks = 8\nv = "50..60"\n', "v = 50 is too large"),
    ('dof = 1\nlinks = "6..8"\nrequire = ["9=1"]\n', "a link with 9 joints"),
])
def test_a_grid_no_cell_of_which_can_hold_a_chain_is_refused(tmp_path, capsys, text, words):
    """Every cell ruled out by the counting equations: one sentence naming the first cell and why, exit 2 and
    no atlas written — as `chains` refuses the same query (the grid ran, stored nothing and exited 0)."""
    grid, db = tmp_path / "impossible.toml", tmp_path / "atlas.sqlite"
    grid.write_text(text)
    assert main(["grid", str(grid), "--db", str(db), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert "no cell of grid 'impossible' can hold a chain" in err and words in err and err.count("\n") == 1, err
    assert not db.exists()


def test_a_grid_with_one_possible_cell_runs_and_leaves_the_others_empty(tmp_path, capsys):
    grid, db = tmp_path / "partly.toml", tmp_path / "atlas.sqlite"
    grid.write_text('dof = 1\nlinks = "4..6"\nv = "2..2"\n')  # four links: no multiple joint; six: one chain (60/2)
    assert main(["grid", str(grid), "--db", str(db), "--workers", "1"]) == 0
    assert "1 chains found" in capsys.readouterr().out
