"""The id in every listing, `atlas --where id=/certificate=`, `draw --db --id`, `identify` on
the rows the commands print, and the export formats of `chains` and `atlas`."""

from __future__ import annotations

import csv
import io
import json

import pytest

import synth
from synth.analysis.identify import chain_id
from mechsynth.cli import main


@pytest.fixture(scope="module")
def atlas(tmp_path_factory):
    from synth.atlas.grid import parse_grid
    from synth.atlas import run_grid

    db = tmp_path_factory.mktemp("atlas") / "a.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..8"'), db, workers=1)
    return db


def test_every_listing_carries_the_id(capsys):
    chains = list(synth.type_synthesis(1, 8, workers=1))
    ids = [chain_id(c.certificate) for c in chains]
    assert main(["chains", "--dof", "1", "--links", "8", "--format", "jsonl", "--workers", "1"]) == 0
    assert [json.loads(line)["id"] for line in capsys.readouterr().out.splitlines()] == ids
    assert main(["chains", "--dof", "1", "--links", "8", "--format", "csv", "--workers", "1"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    assert [r["id"] for r in rows] == ids
    assert {r["planar"] for r in rows} == {"yes"} and {r["fractionated"] for r in rows} == {"no"}
    assert [int(r["symmetry"]) for r in rows] == [round(c.automorphisms()[1]) for c in chains]
    assert main(["chains", "--dof", "1", "--links", "8", "--workers", "1"]) == 0
    table = capsys.readouterr().out
    assert table.splitlines()[0].split() == ["index", "id", "code", "links", "joints", "planar", "symmetry",
                                              "fractionated", "certificate"]
    assert all(i in table for i in ids)
    assert main(["mechanisms", "--dof", "1", "--links", "6", "--format", "jsonl", "--workers", "1"]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert {r["chain_id"] for r in rows} == {chain_id(c.certificate) for c in synth.type_synthesis(1, 6, workers=1)}


def test_atlas_selects_and_draws_by_id_and_certificate(atlas, capsys, tmp_path):
    watt = synth.Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    wanted = chain_id(watt.certificate)
    assert main(["atlas", "--db", str(atlas), "--where", f"id={wanted}"]) == 0
    (row,) = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert row["id"] == wanted and synth.Chain.from_dict(row).certificate == watt.certificate
    assert main(["atlas", "--db", str(atlas), "--where", f"certificate={watt.certificate}", "--count"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] == 1
    assert main(["atlas", "--db", str(atlas), "--where", f"id!={wanted}", "--where", "n=6", "--count"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] == 1  # the Stephenson chain
    assert main(["atlas", "--db", str(atlas), "--where", f"id={wanted}", "--export", "mechanisms"]) == 0
    assert {json.loads(line)["chain_id"] for line in capsys.readouterr().out.splitlines()} == {wanted}
    assert main(["draw", "--db", str(atlas), "--id", wanted, "--out", str(tmp_path / "w.svg")]) == 0
    assert "1 drawing" in capsys.readouterr().err and "42/0" in (tmp_path / "w.svg").read_text()
    assert main(["atlas", "--db", str(atlas), "--where", "id=000000000000"]) == 1
    for bad, words in ((["atlas", "--db", str(atlas), "--where", "id=xyz"], "12 hex digits"),
                       (["atlas", "--db", str(atlas), "--where", "id>abc"], "= or !="),
                       (["draw", "--chain", "0-1 1-2 2-0", "--id", wanted, "--out", str(tmp_path / "x.png")],
                        "--db"),
                       (["chains", "--dof", "1", "--links", "8", "--count", "--format", "graphml"], "--count")):
        capsys.readouterr()
        assert main(bad) == 2
        err = capsys.readouterr().err
        assert err.startswith("mechsynth: ") and err.count("\n") == 1 and words in err


def test_exports_in_exchange_formats_read_back(atlas, capsys):
    from synth.exchange import read_text

    for fmt in ("graphml", "gml", "dot", "edgelist", "adjacency", "incidence"):
        assert main(["atlas", "--db", str(atlas), "--where", "n=8", "--format", fmt]) == 0
        entries = read_text(capsys.readouterr().out, None if fmt not in ("adjacency", "incidence") else fmt)
        assert len(entries) == 16, fmt
        assert main(["mechanisms", "--dof", "1", "--links", "6", "--format", fmt, "--workers", "1"]) == 0
        mechanisms = read_text(capsys.readouterr().out, None if fmt not in ("adjacency", "incidence") else fmt)
        assert [e.frame for e in mechanisms] == [0, 2, 4, 0, 4], fmt  # as the atlas numbers them


def test_identify_reads_the_rows_the_commands_print(capsys):
    assert main(["chains", "--code", "42/0", "--format", "jsonl"]) == 0
    rows = capsys.readouterr().out.splitlines()
    for index, row in enumerate(rows, start=1):
        assert main(["identify", row, "--format", "json"]) == 0
        found = json.loads(capsys.readouterr().out)
        assert (found["index"], found["id"]) == (index, json.loads(row)["id"])
        assert main(["identify", json.dumps(found), "--format", "json"]) == 0  # its own output, read back
        assert json.loads(capsys.readouterr().out)["id"] == found["id"]
    assert main(["mechanisms", "--code", "42/0", "--format", "jsonl"]) == 0
    for index, row in enumerate(capsys.readouterr().out.splitlines(), start=1):
        assert main(["identify", row, "--format", "json"]) == 0
        found = json.loads(capsys.readouterr().out)
        assert found["mechanism_index"] == index and found["frame"] == json.loads(row)["frame"]


def test_identify_table_of_a_mechanism(capsys):
    assert main(["identify", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--frame", "3"]) == 0
    out = capsys.readouterr().out
    for words in ("Watt chain", "Watt I", "#2 of 2 in 'mechsynth chains --code 42/0'", "frame's orbit       2, 3, 4, 5",
                  "|Aut| = 4", "mechanisms --code 42/0"):
        assert words in out, words


def test_a_truss_with_an_input_link_is_identified_in_no_mechanism_listing(tmp_path, capsys):
    """A truss on a frame with an input link (a file may say so) was placed in 'mechanisms --code 32/0
    --input-link', a listing the command refuses (a truss has no input link); it is identified, in no listing."""
    assert main(["mechanisms", "--chain", "0-3 0-4 1-3 1-4 2-3 2-4", "--format", "jsonl"]) == 0
    row = json.loads(capsys.readouterr().out.splitlines()[0])
    given = tmp_path / "truss.json"
    given.write_text(json.dumps(row | {"input_link": 3}))
    assert main(["identify", str(given), "--format", "json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert (found["frame"], found["input_link"], found["listed_input_link"]) == (0, 3, 3)
    assert found.get("mechanism_listing") is None and found["listing"] == "mechsynth chains --code 32/0"
