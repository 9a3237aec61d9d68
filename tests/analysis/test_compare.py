"""compare on a deliberately damaged copy of the 1-DOF 8-link atlas finds each change, with its
reason; an intact copy in any format agrees."""

from __future__ import annotations

import json
import random

import pytest

import synth
from synth.analysis.compare import compare
from synth.analysis.identify import chain_id
from synth.exchange import read_file, read_text, text_of
from synth.structure.query import ChainQuery
from mechsynth.cli import main

# a rigid triangle 0-1-2 in an 8-link chain of W = 1 by the count
DEGENERATE = "0-1 1-2 2-0 0-3 3-4 4-5 5-1 2-6 6-7 7-4"


@pytest.fixture(scope="module")
def atlas():
    return list(synth.type_synthesis(1, 8, workers=1))


def _damaged(atlas, tmp_path):
    """The atlas as jsonl rows (as `chains --format jsonl` prints them), renumbered, with chain 5
    removed, chain 3 given twice (renumbered again) and a degenerate chain added."""
    rng = random.Random(8)
    lines = []
    for i, chain in enumerate(atlas, start=1):
        if i == 5:
            continue
        perm = list(range(8))
        rng.shuffle(perm)
        lines.append(json.dumps(chain.relabel(perm).to_dict()))
        if i == 3:
            lines.append(json.dumps(chain.relabel(perm[::-1]).to_dict()))
    lines.append(json.dumps(synth.Chain.parse(DEGENERATE).to_dict()))
    path = tmp_path / "damaged.jsonl"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_the_damaged_atlas_shows_each_change(atlas, tmp_path):
    result = compare(read_file(_damaged(atlas, tmp_path)), ChainQuery(1, 8))
    assert (result.given, result.distinct, result.engine, result.matched) == (17, 16, 16, 15)
    duplicate, missing, extra = result.findings
    assert duplicate.kind == "duplicate" and duplicate.id == chain_id(atlas[2].certificate)
    assert duplicate.given == ["%s line 3" % (tmp_path / "damaged.jsonl"), "%s line 4" % (tmp_path / "damaged.jsonl")]
    assert missing.kind == "missing" and missing.row == 5 and missing.id == chain_id(atlas[4].certificate)
    assert extra.kind == "extra" and extra.links == [0, 1, 2] and "rigid sub-chain" in extra.reason


def test_the_reasons_of_extra_chains():
    q = ChainQuery(1, 8)
    cases = {
        "0-1 1-2 2-3 3-0 4-5 5-6 6-7 7-4": "not connected",
        "0-1 1-2 2-3 3-0": "4 links, not 8",
        "0-1 1-2 2-3 3-4 4-5 5-6 6-7 7-0": "wrong mobility: W = 5",
        next(synth.type_synthesis(1, 8, v=1, workers=1)).compact(): "v = 1",  # a double joint, outside v = 0
        "0-1 0=2 0-3 1-4 1-5 2-6 3-7 4-6 5-7 6-7": "prismatic",
    }
    for text, words in cases.items():
        (result,) = [compare(read_text(text), q)]
        (extra,) = [f for f in result.findings if f.kind == "extra"]
        assert words in extra.reason, (text, extra.reason)
    two_dof = compare(read_text("0-1 1-2 2-3 3-0 0-4 4-5 5-6 6-0"), ChainQuery(2, 7, fractionated=False))  # two loops on link 0
    assert any("fractionated" in f.reason for f in two_dof.findings if f.kind == "extra")


def test_the_command_on_files_of_several_formats(atlas, tmp_path, capsys):
    half = len(atlas) // 2
    (tmp_path / "a.graphml").write_text(text_of(atlas[:half], "graphml"))
    (tmp_path / "b.txt").write_text(text_of(atlas[half:], "text"))
    assert main(["compare", str(tmp_path / "a.graphml"), str(tmp_path / "b.txt"), "--dof", "1", "--links", "8",
                 "--workers", "1", "--exit-code"]) == 0
    out = capsys.readouterr().out
    assert "16 chains given, 16 distinct; the engine lists 16" in out and "the atlases agree" in out
    damaged = _damaged(atlas, tmp_path)
    assert main(["compare", str(damaged), "--dof", "1", "--links", "8", "--workers", "1", "--format", "json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert main(["compare", str(damaged), "--dof", "1", "--links", "8", "--workers", "1", "--format", "json",
                 "--exit-code"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert (report["duplicates"], report["missing"], report["extra"], report["agree"]) == (1, 1, 1, False)
    assert main(["compare", str(damaged), "--dof", "1", "--links", "8", "--workers", "1"]) == 0
    table = capsys.readouterr().out
    assert "matched 15, duplicates 1, missing 1, extra 1" in table and "rigid sub-chain: links 0, 1, 2" in table


@pytest.mark.parametrize("argv, words", [
    (["compare", "{d}/missing.txt", "--dof", "1", "--links", "8"], "no file"),
    (["compare", "{d}/picture.png", "--dof", "1", "--links", "8"], "not a text file"),
    (["compare", "{d}/self.txt", "--dof", "1", "--links", "8"], "joined to itself"),
    (["compare", "{d}/self.txt", "--dof", "1", "--links", "9"], "no whole number of loops"),
    (["identify", "{d}/picture.png"], "not a text file"),
    (["identify", "0-1 1-1 1-2"], "link 1 is joined to itself"),
    (["identify", "{d}/toml.toml"], "holds no chain"),
    # a linkage file is read whole, as move reads it: a NaN point was passed over (only its chain was read)
    (["identify", "{d}/nan.toml"], "nan.toml: the position of joint 2-3 is not finite: [nan, 1]"),
    (["identify", "0-1 1-2", "--input-format", "graphml"], "not a GraphML document"),
    (["identify", "0-1 1-2 2-0", "--frame", "7"], "frame 7"),
])
def test_bad_input_is_one_sentence_and_exit_2(tmp_path, capsys, argv, words):
    (tmp_path / "picture.png").write_bytes(bytes(range(256)) * 4)
    (tmp_path / "self.txt").write_text("0-1 1-2 2-3 3-0\n0-1 1-1\n")
    (tmp_path / "toml.toml").write_text('dof = 1\nlinks = "4..8"\n')
    (tmp_path / "nan.toml").write_text('[linkage]\nchain = "0-1 1-2 2-3 3-0"\nframe = 0\ninputs = ["0-1"]\n'
                                       'points = { "0-1" = [0, 0], "1-2" = [1, 1], "2-3" = [nan, 1], "0-3" = [4, 0] }\n')
    assert main([a.replace("{d}", str(tmp_path)) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsynth: ") and err.count("\n") == 1 and words in err and "Traceback" not in err


def test_missing_chains_beyond_the_limit_are_counted_not_listed():
    result = compare(read_text("0-1 1-2 2-3 3-0"), ChainQuery(1, 8), max_missing=3)
    listed = [f for f in result.findings if f.kind == "missing"]
    assert result.count("missing") == 16 and len(listed) == 4 and listed[-1].reason.startswith("and 13 more")
    assert [f.row for f in listed[:3]] == [1, 2, 3]
