"""Gear trains in the atlas: [[gears]] grid cells, their counts against the enumerator, resume,
rotation representatives whatever order units finish in, --where, exports read back, site pages,
bad input, and atlases of schema version 3."""

from __future__ import annotations

import csv
import hashlib
import io
import json
import re
import sqlite3
from pathlib import Path

import pytest

from mechsynth.cli import main
from synth import Chain
from synth.atlas import export, run_grid, summary
from synth.atlas import runs
from synth.atlas.grid import load_grid, parse_grid
from synth.atlas.site import write_site
from synth.gears import GearTrain, count_trains, trains

from .helpers import as_version_3, units_in_reverse

ROOT = Path(__file__).resolve().parents[2]
GEARS = ROOT / "models" / "grid_gears.toml"
SIX = '[[gears]]\nlinks = 6\n\n[[gears]]\nlinks = 6\ngraphs = "rotation"\n'


def _cell(n: int, graphs: str, dof: int = 1) -> str:
    return f"gears F={dof} n={n} graphs={graphs}"


def _members(db, cell: str) -> set[str]:
    with sqlite3.connect(db) as conn:
        return {c for (c,) in conn.execute("SELECT c.certificate FROM members m JOIN chains c ON c.id = m.chain "
                                           "WHERE m.cell = ?", (cell,))}


def _content(db) -> dict:
    """Everything a run stores, independent of timing and order."""
    with sqlite3.connect(db) as conn:
        return {
            "chains": sorted(conn.execute("SELECT certificate, code, dof, links, v, meshes, fractionated, chain "
                                          "FROM chains")),
            "trains": sorted(conn.execute("SELECT c.certificate, t.train, t.lever_code, t.carriers, t.rotation, t.rank "
                                          "FROM trains t JOIN chains c ON c.id = t.chain")),
            "members": sorted(conn.execute("SELECT m.cell, c.certificate FROM members m JOIN chains c ON c.id = m.chain")),
            "mechanisms": sorted(conn.execute("SELECT c.certificate, k.frame FROM mechanisms k JOIN chains c "
                                              "ON c.id = k.chain")),
            "units": sorted(conn.execute("SELECT cell, unit, status FROM units")),
        }


@pytest.fixture(scope="module")
def atlas(tmp_path_factory) -> Path:
    db = tmp_path_factory.mktemp("gears") / "gears.sqlite"
    assert main(["grid", str(GEARS), "--db", str(db), "--workers", "2", "--format", "json"]) == 0
    return db


@pytest.mark.parametrize("links, displacement, rotation", [(5, 13, 6), (6, 81, 27), (7, 647, 152)])
def test_stored_trains_are_the_enumerated_ones(atlas, links, displacement, rotation):
    assert count_trains(1, links)["count"] == displacement  # the published counts
    assert count_trains(1, links, "rotation")["count"] == rotation
    for graphs in ("displacement", "rotation"):
        wanted = {t.to_chain().certificate for t in trains(1, links, graphs)}
        assert _members(atlas, _cell(links, graphs)) == wanted
    cells = {c["cell"]: c for c in summary(atlas)["cells"]}
    assert cells[_cell(links, "displacement")]["chains"] == displacement
    assert cells[_cell(links, "rotation")]["chains"] == rotation
    # a rotation cell's trains are one per rotation graph, and they are all of them
    with sqlite3.connect(atlas) as conn:
        got = conn.execute("SELECT COUNT(DISTINCT t.rotation) FROM members m JOIN trains t ON t.chain = m.chain "
                           "WHERE m.cell = ?", (_cell(links, "displacement"),)).fetchone()[0]
    assert got == rotation


def test_stored_rows_describe_their_trains(atlas):
    with sqlite3.connect(atlas) as conn:
        rows = conn.execute("SELECT c.certificate, c.meshes, c.dof, c.links, t.train, t.lever_code, t.carriers, "
                            "t.rotation FROM chains c JOIN trains t ON t.chain = c.id WHERE c.links = 6").fetchall()
        assert conn.execute("SELECT COUNT(*) FROM chains WHERE id NOT IN (SELECT chain FROM trains)").fetchone()[0] == 0
    assert len(rows) == 81
    for certificate, meshes, dof, links, text, lever, carriers, rotation in rows:
        train = GearTrain.parse(text)
        assert train.to_chain().certificate == certificate  # the text is in the stored chain's labelling
        assert (meshes, dof, links) == (len(train.meshes), train.dof, train.links) == (4, 1, 6)
        assert lever == str(train.lever_analogue().code) and carriers == len(set(train.carriers))
        assert rotation == train.rotation_certificate


def test_resume_after_interrupt_stores_nothing_twice(tmp_path, monkeypatch):
    grid = parse_grid(SIX)
    whole = tmp_path / "whole.sqlite"
    run_grid(grid, whole, workers=1)
    db = tmp_path / "stopped.sqlite"
    real, calls = runs.compute_unit, []

    def stop_on_the_thirtieth(task):
        calls.append(task)
        if len(calls) == 30:
            raise KeyboardInterrupt
        return real(task)

    monkeypatch.setattr(runs, "compute_unit", stop_on_the_thirtieth)
    with pytest.raises(KeyboardInterrupt):
        run_grid(grid, db, workers=1)
    monkeypatch.setattr(runs, "compute_unit", real)
    with sqlite3.connect(db) as conn:
        assert conn.execute("SELECT COUNT(*) FROM units WHERE status = 'done'").fetchone()[0] == 29
        assert conn.execute("SELECT status FROM runs").fetchone()[0] == "interrupted"
    again = run_grid(grid, db, workers=1)
    assert (again.units_skipped, again.units_run) == (29, 44 - 29)
    assert _content(db) == _content(whole)
    assert run_grid(grid, db, workers=1).units_run == 0  # a third run finds everything done
    assert _content(db) == _content(whole)


def test_rotation_cells_keep_the_first_train_whatever_order_units_finish(tmp_path, monkeypatch):
    grid = parse_grid('[[gears]]\nlinks = 7\ngraphs = "rotation"\n')
    units_in_reverse(monkeypatch)
    db = tmp_path / "reversed.sqlite"
    run_grid(grid, db, workers=1)
    wanted = {t.to_chain().certificate for t in trains(1, 7, "rotation")}
    assert _members(db, _cell(7, "rotation")) == wanted
    with sqlite3.connect(db) as conn:  # the displaced trains left the atlas with everything of theirs
        assert conn.execute("SELECT COUNT(*) FROM chains").fetchone()[0] == 152
        for table in ("trains", "mechanisms", "link_counts"):
            assert conn.execute(f"SELECT COUNT(*) FROM {table} WHERE chain NOT IN (SELECT id FROM chains)"
                                ).fetchone()[0] == 0


def _count(db, *where) -> dict:
    return {"count": sum(1 for _ in export(db, "chains", where=list(where)))}


def test_where_filters(atlas, capsys):
    assert _count(atlas, "kind=gears")["count"] == 13 + 81 + 647
    assert _count(atlas, "kind!=chains", "n=6")["count"] == 81
    assert _count(atlas, "kind=chains")["count"] == 0
    assert _count(atlas, "meshes=4")["count"] == 81 and _count(atlas, "G>=5")["count"] == 647
    by_code = count_trains(1, 7)["by_code"]
    assert all(_count(atlas, f"lever={code}", "n=7")["count"] == n for code, n in by_code.items())
    one = sum(1 for t in trains(1, 7) if len(set(t.carriers)) == 1)
    assert _count(atlas, "carriers=1", "n=7")["count"] == one
    row = next(export(atlas, "chains", where=["n=7", "cell=" + _cell(7, "rotation")]))
    same = [r for r in export(atlas, "chains", where=[f"rotation={row['rotation_id']}"])]
    assert all(r["rotation_certificate"] == row["rotation_certificate"] for r in same)
    assert len(same) == sum(1 for t in trains(1, 7) if t.rotation_certificate == row["rotation_certificate"])
    assert main(["atlas", "--db", str(atlas), "--where", "kind=gears", "--where", "meshes=3", "--count"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] == 13


@pytest.mark.parametrize("where, words", [
    ("kind=gear", "kind is gears or chains"),
    ("kind>gears", "kind is gears or chains"),
    ("lever>530/1", "compared with = or != only"),
    ("rotation=abc", "a rotation graph id is 12 hex digits"),
    ("gearz=3", "unknown field 'gearz'"),
    ("meshes=x", "is not a whole number"),
])
def test_bad_conditions_are_one_sentence(atlas, capsys, where, words):
    assert main(["atlas", "--db", str(atlas), "--where", where]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err


def test_exports_read_back(atlas, capsys):
    rows = list(export(atlas, "chains", where=["n=6"]))
    assert len(rows) == 81
    for row in rows:
        assert row["kind"] == "gears"
        assert GearTrain.parse(row["train"]).to_chain().certificate == row["certificate"]
        assert GearTrain.from_dict(row).to_chain().certificate == row["certificate"]  # the JSON row itself
        assert Chain.from_dict(row).certificate == row["certificate"]
    assert main(["atlas", "--db", str(atlas), "--where", "n=6", "--format", "csv"]) == 0
    table = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    assert [r["id"] for r in table] == [r["id"] for r in rows]
    assert {"train", "lever_code", "rotation_id", "meshes", "carriers"} <= set(table[0])
    for line, row in zip(table, rows):
        assert GearTrain.parse(line["train"]).to_chain().certificate == row["certificate"]
    # the text form is what 'mechsynth gears --train' and 'analyze' read
    text = rows[0]["train"]
    assert main(["gears", "--train", text, "--format", "jsonl"]) == 0
    assert json.loads(capsys.readouterr().out)["certificate"] == GearTrain.parse(text).certificate
    assert main(["analyze", text, "--format", "json"]) == 0
    capsys.readouterr()
    mechanisms = list(export(atlas, "mechanisms", where=["n=5"]))
    assert mechanisms and all(m["train"] and 0 <= m["frame"] < 5 for m in mechanisms)
    frames = {(m["chain_id"], m["frame"]) for m in mechanisms}
    for row in export(atlas, "chains", where=["n=5"]):
        orbits = GearTrain.parse(row["train"]).automorphisms()[1]
        assert {f for c, f in frames if c == row["id"]} == set(orbits)  # a fixed link per orbit


def test_draw_from_the_atlas_gives_schematics(atlas, tmp_path, capsys):
    """draw --db draws gear trains as functional schematics (one per train, titled by code and id),
    as gears --out and the site do; a single --id is one schematic titled by its text form."""
    rows = list(export(atlas, "chains", where=["kind=gears", "n=5"]))
    sheet = tmp_path / "five.svg"
    assert main(["draw", "--db", str(atlas), "--where", "kind=gears", "--where", "n=5", "--out", str(sheet)]) == 0
    assert capsys.readouterr().err.startswith(f"{len(rows)} schematics -> ")
    text = sheet.read_text()
    assert all(f"id {row['id']}" in text for row in rows)
    one = tmp_path / "one.svg"
    assert main(["draw", "--db", str(atlas), "--id", rows[0]["id"], "--out", str(one)]) == 0
    assert GearTrain.parse(rows[0]["train"]).compact() in one.read_text()
    capsys.readouterr()
    assert main(["draw", "--db", str(atlas), "--where", "n=5", "--dpi", "200", "--out", str(tmp_path / "t.png")]) == 2
    assert "take no --dpi" in capsys.readouterr().err


def test_a_listing_row_is_found_on_the_atlas_sheet_by_its_codes(atlas, tmp_path, capsys):
    """`gears` listed a train by its lever analogue's code (530/1), `draw --db` captioned it with the
    train's own (230/1 G3), and nothing said which was which: the listing gives both (`code` the lever
    analogue's, `train_code` the train's own) and each caption names the lever analogue's, so every row
    of `gears --links 5` has its drawing, found by either code."""
    assert main(["gears", "--links", "5", "--format", "jsonl"]) == 0
    listed = {r["certificate"]: r for r in map(json.loads, capsys.readouterr().out.splitlines())}
    rows = list(export(atlas, "chains", where=["kind=gears", "n=5"]))
    sheet = tmp_path / "five.svg"
    assert main(["draw", "--db", str(atlas), "--where", "kind=gears", "--where", "n=5", "--out", str(sheet)]) == 0
    text = sheet.read_text()
    assert len(rows) == len(listed) == 13
    for row in rows:
        mine = listed[GearTrain.parse(row["train"]).certificate]  # the same train, however numbered
        assert (mine["train_code"], mine["code"]) == (row["code"], row["lever_code"])
        assert f"{row['code']} (lever analogue {row['lever_code']})" in text
    assert main(["gears", "--links", "5"]) == 0
    out = capsys.readouterr().out
    assert "code: the lever analogue's, train_code: the train's own" in out.splitlines()[-1]


def test_site_pages_draw_every_train(atlas, tmp_path):
    db = tmp_path / "five.sqlite"
    run_grid(parse_grid("[[gears]]\nlinks = 5\n"), db, workers=1)
    result = write_site(db, tmp_path / "site", workers=1)
    assert (result.chains, result.drawn) == (13, 13)
    pages = sorted((tmp_path / "site" / "codes").glob("*.html"))
    text = "".join(p.read_text() for p in pages)
    assert all("-G3-" in p.name for p in pages)
    cards = re.findall(r'<figure id="([0-9a-f]{12})" class="train"><svg', text)
    assert sorted(cards) == sorted(r["id"] for r in export(db, "chains"))
    for row in export(db, "chains"):
        assert f'mechsynth gears --train "{row["train"]}" --input-output' in text
    index = (tmp_path / "site" / "index.html").read_text()
    assert '"kind":"gears"' in index and "G3" in index


@pytest.mark.parametrize("text, words", [
    ("[[gears]]\nlinks = 6\nv = 1\n", "[[gears]] 1 has an unknown key 'v'"),
    ("[[gears]]\nlinks = 6\ndof = 0\n", "key 'dof' must be at least 1"),
    ("[[gears]]\nlinks = 13\n", "key 'links': gear trains are enumerated up to 12 links"),
    ("[[gears]]\nlinks = 2\n", "needs at least 3 links"),
    ("[[gears]]\ndof = 2\nlinks = 3\n", "F = 2 needs at least 4 links"),
    ("[[gears]]\nlinks = 6\ngraphs = \"rotations\"\n", "key 'graphs' must be \"displacement\" or \"rotation\""),
    ("[[gears]]\ndof = 1\n", "needs the key 'links'"),
    ("gears = 1\n", "key 'gears' must be [[gears]] tables"),
])
def test_bad_gear_cells_are_one_sentence(tmp_path, capsys, text, words):
    grid, db = tmp_path / "g.toml", tmp_path / "a.sqlite"
    grid.write_text(text)
    assert main(["grid", str(grid), "--db", str(db)]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err
    assert not db.exists()


def test_version_3_atlases_are_read_and_upgraded(tmp_path, capsys):
    db = tmp_path / "old.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..6"'), db, workers=1)
    before = list(export(db, "chains"))
    as_version_3(db)
    digest = hashlib.sha256(db.read_bytes()).hexdigest()
    assert list(export(db, "chains")) == before
    assert _count(db, "kind=chains")["count"] == len(before) and _count(db, "kind=gears")["count"] == 0
    assert main(["atlas", "--db", str(db)]) == 0 and "schema" in capsys.readouterr().out
    write_site(db, tmp_path / "site", workers=1)
    assert hashlib.sha256(db.read_bytes()).hexdigest() == digest  # read, never changed
    grid = tmp_path / "g.toml"
    grid.write_text('dof = 1\nlinks = "4..6"\n\n[[gears]]\nlinks = 5\n')
    assert main(["grid", str(grid), "--db", str(db), "--workers", "1"]) == 0
    capsys.readouterr()
    with sqlite3.connect(db) as conn:
        assert conn.execute("SELECT value FROM meta WHERE key = 'schema_version'").fetchone()[0] == "4"
    assert list(export(db, "chains", where=["kind=chains"])) == before
    assert _count(db, "kind=gears")["count"] == 13


def test_other_versions_are_refused(tmp_path, capsys):
    db = tmp_path / "v2.sqlite"
    run_grid(parse_grid("dof = 1\nlinks = 4"), db, workers=1)
    with sqlite3.connect(db) as conn:
        conn.execute("UPDATE meta SET value = '2' WHERE key = 'schema_version'")
    digest = hashlib.sha256(db.read_bytes()).hexdigest()
    assert main(["atlas", "--db", str(db)]) == 2
    assert "schema version 2" in capsys.readouterr().err
    assert main(["grid", str(GEARS), "--db", str(db)]) == 2
    assert "schema version 2" in capsys.readouterr().err
    assert hashlib.sha256(db.read_bytes()).hexdigest() == digest


def test_shipped_gear_grid():
    grid = load_grid(GEARS)
    assert not grid.cells
    assert [c.key for c in grid.gear_cells] == [_cell(n, g) for g in ("displacement", "rotation") for n in (5, 6, 7)]
