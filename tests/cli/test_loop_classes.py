"""The command line of heterogeneous chains: ``chains --loop-classes`` (a query, or the bases of one
chain), its rows read back by ``identify`` and ``analyze``, ``draw`` with each class's colour."""

from __future__ import annotations

import csv
import io
import json

import pytest

from mechsynth.cli import main
from synth import Chain

TRANSLATOR = "0-1-6 1-2-7 2-3-8 3-4-9 4-5-10 5-0-11 6-12 8-12 10-12 7-13 9-13 11-13"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_count_and_rows_agree(capsys):
    """The count and the listing of the same query: five chains of 62/0 with K3 = 1, K5 = 1, each a
    row that reads back as the same chain and analyses to W = 1."""
    code, out, _ = run(capsys, "chains", "--dof", "1", "--loop-classes", "3=1,5=1", "--count")
    assert code == 0 and json.loads(out) == {"count": 5, "by_code": {"62/0 K3=1 K5=1": 5}}
    code, out, _ = run(capsys, "chains", "--dof", "1", "--loop-classes", "3=1,5=1", "--format", "jsonl")
    rows = [json.loads(line) for line in out.splitlines()]
    assert code == 0 and len(rows) == 5 and len({r["certificate"] for r in rows}) == 5
    for row in rows:
        assert row["loop_classes"] == {"3": 1, "5": 1} and row["dof"] == 1 and len(row["classes"]) == 8
        assert Chain.from_dict(row).certificate == row["certificate"]
        code, out, _ = run(capsys, "analyze", json.dumps(row), "--format", "json")
        assert code == 0 and json.loads(out)["dof"] == 1 and json.loads(out)["subchain_defect"] == "none"


def test_the_translator_among_the_bases_of_its_chain(capsys):
    """``--chain C --loop-classes``: every class-V loop of the translator's graph; identify names the
    translator's row in the query of its code."""
    code, out, _ = run(capsys, "chains", "--chain", TRANSLATOR, "--loop-classes", "3=4,5=1", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    code, out, _ = run(capsys, "identify", TRANSLATOR + " | h5: 0 1 2 3 4 5", "--format", "json")
    found = json.loads(out)
    assert code == 0 and len(rows) == 5 and len({r["certificate"] for r in rows}) == 5
    assert [r["joints"] for r in rows if r["id"] == found["id"]] == [found["listed_joints"]]  # numbered as listed
    assert found["code"] == "12.2.0.0.0/6 K3=4 K5=1" and found["dof"] == 1 and found["classes"][:6] == [5] * 6
    assert found["listing"] == "mechsynth chains --dof 1 --loop-classes 3=4,5=1 --code 12.2.0.0.0/6"


def test_the_bases_of_a_chain_given_are_shown_in_its_own_numbering(capsys):
    """Each base listed in the canonical numbering (the id's) has beside it the user's chain, links numbered as
    given: its class-V links are those of one base of the user's graph (the translator's toroidal loop 0 … 5
    among them), and read back it is the chain of its row."""
    code, out, _ = run(capsys, "chains", "--chain", TRANSLATOR, "--loop-classes", "3=4,5=1", "--format", "jsonl")
    rows = [json.loads(line) for line in out.splitlines()]
    graph = Chain.parse(TRANSLATOR).compact()
    assert code == 0 and len(rows) == 5
    bases = set()
    for row in rows:
        joints, _, h5 = row["as_given"].partition(" | h5: ")
        assert joints == graph  # the user's joints, the user's link numbers
        assert Chain.parse(row["as_given"]).certificate == row["certificate"]  # the same chain as the row's
        bases.add(tuple(map(int, h5.split())))
    assert len(bases) == 5 and (0, 1, 2, 3, 4, 5) in bases


def test_a_mechanism_of_a_chain_given_names_its_links_as_given(capsys):
    """``mechanisms --chain C``: the Watt chain written otherwise than the listing numbers it; each mechanism's
    fixed link by its number in the chain as given is the same mechanism as the row's."""
    from synth import Mechanism

    watt = "0-1 1-2 2-3 3-0 0-4 4-5 5-1"
    code, out, _ = run(capsys, "mechanisms", "--chain", watt, "--format", "jsonl")
    rows = [json.loads(line) for line in out.splitlines()]
    assert code == 0 and len(rows) == 2 and {r["as_given"] for r in rows} == {Chain.parse(watt).compact()}
    listed = {" ".join("-".join(map(str, j)) for j in r["joints"]) for r in rows}
    assert listed == {"0-3 0-4 1-2 1-4 2-5 3-5 4-5"} != {r["as_given"] for r in rows}  # renumbered: the map is needed
    for row in rows:
        given = Mechanism(Chain.parse(row["as_given"]), row["frame_as_given"])
        assert given.certificate == row["certificate"] and row["input_link_as_given"] is None


def test_a_query_that_matches_nothing_exits_1(capsys):
    """W = 1 with K3 = 1, K5 = 1 and a four-joint link carrying two cranks: a valid query, no chain."""
    code, out, err = run(capsys, "chains", "--dof", "1", "--loop-classes", "3=1,5=1", "--cranks", "4=2", "--count")
    assert code == 1 and json.loads(out)["count"] == 0


def test_draw_the_bases(capsys, tmp_path):
    """A sheet of the translator's class-V loops, and one drawing of the translator itself."""
    sheet, one = tmp_path / "bases.png", tmp_path / "translator.svg"
    code, _, err = run(capsys, "draw", "--chain", TRANSLATOR, "--loop-classes", "3=4,5=1", "--out", str(sheet))
    assert code == 0 and sheet.stat().st_size > 10_000 and "5 drawings" in err
    code, _, _ = run(capsys, "draw", "--chain", TRANSLATOR + " | h5: 0 1 2 3 4 5", "--out", str(one))
    text = one.read_text()
    assert code == 0 and "#e66101" in text and "h = 5: 1 loop" in text  # the base's colour and its key


def test_fig_6v_wedge_loop_from_the_command_line(capsys):
    """Fig. 6в: the four-link loop of prismatic pairs is read as a chain (not as counts) and has
    W = 2 in the plane; with one pin among its pairs W = 1; a one-DOF planar wedge loop is 3/0."""
    code, out, _ = run(capsys, "analyze", "0=1 1=2 2=3 3=0", "--format", "json")
    assert code == 0 and json.loads(out)["dof"] == 2 and json.loads(out)["loops_2"] == 1
    code, out, _ = run(capsys, "analyze", "0=1 1=2 2=3 3-0", "--format", "json")
    assert code == 0 and json.loads(out)["dof"] == 1
    code, out, _ = run(capsys, "codes", "--dof", "1", "--loop-classes", "2=1", "--format", "csv")
    assert code == 0 and out.splitlines()[1:] == ["3/0,3,1,0,3"]
    code, out, _ = run(capsys, "analyze", "2=4,3=2", "--format", "json")
    assert code == 0 and json.loads(out)["code"] == "42/0"  # counts stay counts


@pytest.mark.parametrize("argv", [
    ["codes", "--dof", "1", "--loop-classes", "3=1,5=1"],
    ["chains", "--dof", "1", "--loop-classes", "3=1,5=1", "--count"],
    ["mechanisms", "--dof", "1", "--loop-classes", "3=1,5=1", "--count"],
    ["chains", "--chain", TRANSLATOR, "--loop-classes", "3=4,5=1"],
    ["draw", "--chain", TRANSLATOR, "--loop-classes", "3=4,5=1", "--out", "never.svg"],
])
@pytest.mark.parametrize("h", ["3", "5"])
def test_any_h_beside_loop_classes_is_refused(capsys, tmp_path, monkeypatch, argv, h):
    """The classes give each loop's motion space: codes refused any --h beside them, chains and mechanisms took
    --h 3 (the listing in the classes' h), as a scene took h = 3 beside loop_classes for the chains; one sentence
    (synth.h_beside_classes) for every command and the scene, exit 2, nothing written."""
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, *argv, "--h", h)
    assert (code, out) == (2, "") and not list(tmp_path.iterdir())
    assert err == ("mechsynth: --h and --loop-classes contradict each other: the classes give each loop's motion "
                   "space (the lower class is the chain's h)\n")
