"""A count's checkpoint read back (synth.read_checkpoint, benchmarks/checkpoints.py) and two counts compared code by code."""

from __future__ import annotations

import csv
import io
import json
import shutil
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest

import synth
from synth import ChainQuery, count_chains, count_identity, read_checkpoint
from synth.execution.checkpoint import Checkpoint

SCRIPT = Path(__file__).resolve().parents[2] / "benchmarks" / "checkpoints.py"


def _script(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def counted(tmp_path_factory):
    """The 10-link count by both methods, each with its checkpoint, and the listing's JSON."""
    folder = tmp_path_factory.mktemp("counts")
    listing = count_chains(1, 10, workers=1, checkpoint=folder / "listing.sqlite")
    orbits = count_chains(1, 10, workers=1, checkpoint=folder / "orbits.sqlite", method="orbits")
    (folder / "listing.json").write_text(json.dumps(listing.to_dict()) + "\n")
    return folder, listing, orbits


def _partial(path: Path) -> dict:
    """A checkpoint of the 10-link count as a running count leaves it: one code complete, two
    units of another, the rest not begun; returns what it holds."""
    digest, words = count_identity(ChainQuery(1, 10))
    with Checkpoint(path, digest, words) as ck:
        ck.add_unit("5410/0|u1", "5410/0", 40)
        ck.add_unit("5410/0|u2", "5410/0", 2)
        ck.finish_code("4600/0", 50, units=3)
    return {"5410/0": (42, 2), "4600/0": (50, 3)}


def test_a_finished_checkpoint_is_read_back_whole_and_unchanged(counted):
    folder, listing, _ = counted
    path = folder / "listing.sqlite"
    before = path.read_bytes()
    state = read_checkpoint(path)
    assert state.query == "chains dof=1 links=10" and not state.partial
    assert {code: n for code, (n, _) in state.complete.items() if n} == listing.by_code
    assert state.chains == listing.count == 230 and state.units >= len(state.complete)
    assert path.read_bytes() == before


def test_status_of_a_running_count_counts_codes_of_the_plan(tmp_path):
    path = tmp_path / "running.sqlite"
    held = _partial(path)
    state = read_checkpoint(path)
    assert state.complete == {"4600/0": held["4600/0"]} and state.partial == {"5410/0": held["5410/0"]}
    assert (state.units, state.chains) == (5, 92)
    result = _script("status", path)
    assert result.returncode == 0, result.stderr
    shown = json.loads(result.stdout)
    codes = [str(c) for c in synth.plan_codes(1, 10)]
    assert shown["codes_in_plan"] == len(codes) == 7
    assert (shown["codes_complete"], shown["codes_partial"], shown["codes_not_begun"]) == (1, 1, 5)
    assert shown["partial"] == {"5410/0": {"units": 2, "count": 42}} and shown["chains_so_far"] == 92


def test_a_checkpoint_is_read_while_its_count_holds_it_open(tmp_path):
    path = tmp_path / "open.sqlite"
    digest, words = count_identity(ChainQuery(1, 10))
    with Checkpoint(path, digest, words, every=3600) as ck:
        ck.add_unit("5410/0|a", "5410/0", 7)
        ck.commit()
        ck.add_unit("5410/0|b", "5410/0", 9)  # not committed yet: not seen
        assert read_checkpoint(path).partial == {"5410/0": (7, 1)}


def test_the_table_is_csv_by_code_and_complete_refuses_a_count_not_finished(counted, tmp_path):
    folder, listing, _ = counted
    result = _script("table", folder / "listing.sqlite", "--complete")
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert {r["code"]: int(r["count"]) for r in rows if int(r["count"])} == listing.by_code
    assert [r["code"] for r in rows if int(r["count"])] == list(listing.by_code)  # in the count's order
    assert {r["state"] for r in rows} == {"complete"}
    path = tmp_path / "running.sqlite"
    _partial(path)
    assert _script("table", path).returncode == 0
    refused = _script("table", path, "--complete")
    assert refused.returncode == 1 and "not finished (6 codes of its plan are not complete)" in refused.stderr


def test_two_methods_agree_code_by_code_and_with_the_count_s_json(counted):
    folder, listing, orbits = counted
    assert listing == orbits
    for other in ("orbits.sqlite", "listing.json"):
        result = _script("compare", folder / "listing.sqlite", folder / other)
        assert result.returncode == 0, result.stderr
        found = json.loads(result.stdout)
        assert found["verdict"] == "equal" and found["codes_compared"] == found["codes_equal"] == len(listing.by_code)
        assert found["chains_compared"] == 230 and found["finished"] == [True, True]


def test_a_planted_difference_is_found(counted, tmp_path):
    folder, listing, _ = counted
    planted = tmp_path / "planted.sqlite"
    shutil.copy(folder / "orbits.sqlite", planted)
    code = next(iter(listing.by_code))
    with sqlite3.connect(planted) as conn:
        conn.execute("UPDATE codes SET count = count + 1 WHERE code = ?", (code,))
    conn.close()
    result = _script("compare", folder / "listing.sqlite", planted)
    assert result.returncode == 1
    found = json.loads(result.stdout)
    n = listing.by_code[code]
    assert found["verdict"] == "different" and found["different"] == {code: [n, n + 1]}
    assert found["codes_equal"] == len(listing.by_code) - 1
    # a code the finished count lacks is a difference too
    trimmed = tmp_path / "trimmed.json"
    by_code = dict(listing.by_code)
    del by_code[code]
    trimmed.write_text(json.dumps({"count": sum(by_code.values()), "by_code": by_code}))
    found = json.loads(_script("compare", folder / "listing.sqlite", trimmed).stdout)
    assert found["verdict"] == "different" and found["only_in_a"] == [code]


def test_a_running_count_is_equal_so_far_and_a_wrong_partial_code_is_different(counted, tmp_path):
    folder, listing, _ = counted
    path = tmp_path / "running.sqlite"
    digest, words = count_identity(ChainQuery(1, 10))
    right = next(iter(listing.by_code))
    with Checkpoint(path, digest, words) as ck:
        ck.finish_code(right, listing.by_code[right], units=1)
    result = _script("compare", path, folder / "listing.json")
    found = json.loads(result.stdout)
    assert result.returncode == 0 and found["verdict"] == "equal so far" and found["codes_compared"] == 1
    assert found["finished"] == [False, True] and found["only_in_b"] == [] and len(found["pending"]) == 6
    with Checkpoint(path, digest, words) as ck:
        wrong = list(listing.by_code)[1]
        ck.finish_code(wrong, listing.by_code[wrong] - 1, units=1)
    result = _script("compare", path, folder / "listing.json")
    assert result.returncode == 1 and json.loads(result.stdout)["different"] == {
        wrong: [listing.by_code[wrong] - 1, listing.by_code[wrong]]}


def test_bad_inputs_are_one_sentence_and_exit_2(counted, tmp_path):
    folder, _, _ = counted
    text = tmp_path / "notes.txt"
    text.write_text("no count here\n")
    other = tmp_path / "other.sqlite"
    count_chains(1, 8, workers=1, checkpoint=other)
    eight = tmp_path / "eight.json"
    eight.write_text(json.dumps(count_chains(1, 8, workers=1).to_dict()))
    bad_json = tmp_path / "bad.json"
    bad_json.write_text(json.dumps({"count": 5, "by_code": {"440/0": 9}}))
    listing = folder / "listing.sqlite"
    cases = {("status", tmp_path / "missing.sqlite"): "there is no checkpoint",
             ("status", tmp_path): "it is a folder",
             ("table", text): "is not a usable checkpoint",
             ("compare", listing, text): "neither a checkpoint nor a count's JSON",
             ("compare", listing, listing): "compared with itself",
             ("compare", listing, other): "counts another query",
             ("compare", listing, bad_json): "is not the sum of its counts by code",
             ("compare", listing, eight): "counts chains of 10 links and",
             ("compare", listing): "the following arguments are required",
             ("verify", listing): "invalid choice"}
    for args, words in cases.items():
        result = _script(*args)
        assert result.returncode == 2, (args, result.stderr)
        assert words in result.stderr and len(result.stderr.strip().splitlines()) == 1, (args, result.stderr)
        assert "Traceback" not in result.stderr


def test_a_reader_that_stops_early_changes_no_exit_status(counted, tmp_path):
    folder, listing, _ = counted
    planted = tmp_path / "planted.json"
    by_code = dict(listing.by_code)
    by_code["4600/0"] += 1
    planted.write_text(json.dumps({"by_code": by_code}))
    # ``true`` reads nothing and is gone long before Python starts: the result meets a closed pipe
    shell = subprocess.run(f"{sys.executable} {SCRIPT} compare {folder / 'listing.sqlite'} {planted} | true; "
                           "exit ${PIPESTATUS[0]}", shell=True, executable="/bin/bash", capture_output=True, text=True)
    assert shell.returncode == 1 and shell.stderr == ""


def test_a_spot_check_of_some_codes_is_compared_as_a_part(counted, tmp_path):
    folder, listing, _ = counted
    spot = count_chains(1, 10, code="5410/0", workers=1, method="orbits")
    assert spot.by_code == {"5410/0": 95}
    part = tmp_path / "spot.json"
    part.write_text(json.dumps(spot.to_dict()))
    whole = json.loads(_script("compare", part, folder / "listing.json").stdout)
    assert whole["verdict"] == "different" and len(whole["only_in_b"]) == 6  # as a whole count it lacks six codes
    result = _script("compare", "--part", part, folder / "listing.json")
    found = json.loads(result.stdout)
    assert result.returncode == 0 and found["verdict"] == "equal" and found["codes_compared"] == 1
    ck = tmp_path / "spot.sqlite"  # a --code query's checkpoint against the whole query's
    count_chains(1, 10, code="5410/0", workers=1, method="orbits", checkpoint=ck)
    assert json.loads(_script("compare", "--part", ck, folder / "listing.sqlite").stdout)["verdict"] == "equal"
    refused = _script("compare", ck, folder / "listing.sqlite")
    assert refused.returncode == 2 and "counts another query" in refused.stderr
    wrong = tmp_path / "wrong.json"
    wrong.write_text(json.dumps({"by_code": {"5410/0": 94}}))
    assert _script("compare", "--part", wrong, folder / "listing.json").returncode == 1


def test_a_records_file_whose_query_is_a_command_line_is_compared_with_its_checkpoint(counted, tmp_path):
    folder, listing, _ = counted
    same = tmp_path / "dof_1_links_10.json"  # as benchmarks/records/*.json write it
    same.write_text(json.dumps({"query": "chains --dof 1 --links 10", **listing.to_dict()}))
    assert json.loads(_script("compare", same, folder / "listing.sqlite").stdout)["verdict"] == "equal"
    other = tmp_path / "dof_1_links_12.json"
    other.write_text(json.dumps({"query": "chains --dof 1 --links 12", **listing.to_dict()}))
    refused = _script("compare", other, folder / "listing.sqlite")
    assert refused.returncode == 2 and "counts another query" in refused.stderr
