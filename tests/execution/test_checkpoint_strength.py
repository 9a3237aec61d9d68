"""A checkpoint file on its own: what it stores, when it commits, what it says, and every refusal in
full with the refused file left byte for byte as it was.
"""

from __future__ import annotations

import os
import re
import sqlite3
from pathlib import Path

import pytest

from synth.errors import flag
from synth.execution import checkpoint as module
from synth.execution.checkpoint import PLAN_FORMAT, Checkpoint, CheckpointError, CheckpointMismatch


def _rows(path, table):
    with sqlite3.connect(path) as db:
        return sorted(db.execute(f"SELECT * FROM {table}").fetchall())


def _untouched(path):
    """The file's bytes and the names beside it, to compare before and after a refusal."""
    return path.read_bytes(), sorted(p.name for p in path.parent.iterdir())


def test_a_new_file_holds_the_query_and_its_plan_format(tmp_path):
    path = tmp_path / "c.sqlite"
    with Checkpoint(path, "plan-a", "chains W=1 n=8"):
        pass
    meta = dict(_rows(path, "meta"))
    assert meta["identity"] == f"{PLAN_FORMAT}:plan-a" and meta["query"] == "chains W=1 n=8"
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d", meta["created"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.sqlite"]  # closed: one file, no -wal or -shm


def test_units_and_codes_are_read_back_with_the_units_done(tmp_path):
    path = tmp_path / "c.sqlite"
    with Checkpoint(path, "p", "q") as ck:
        ck.add_unit("a|1", "a", 2)
        ck.finish_code("a", 6, units=4)
        ck.add_unit("b|1", "b", 3)
        ck.add_unit("c|1", "c", 0)
    again = Checkpoint(path, "p", "q")
    assert again.codes == {"a": 6}
    assert again.units == {"b|1": ("b", 3), "c|1": ("c", 0)}
    assert again.resumed_units == 4 + 2  # the complete code's units and the two still running
    assert (again.committed_units, again.committed_codes) == (0, 0)
    again.close()


def test_a_unit_is_committed_once_every_seconds_have_passed(tmp_path, monkeypatch):
    clock = [100.0]
    monkeypatch.setattr(module.time, "monotonic", lambda: clock[0])
    lines = []
    path = tmp_path / "c.sqlite"
    ck = Checkpoint(path, "p", "q", every=2.0, log=lines.append)
    clock[0] = 101.9
    ck.add_unit("a|1", "a", 1)
    assert _rows(path, "units") == [] and lines == []  # 1.9 s after the start: kept for later
    clock[0] = 102.0
    ck.add_unit("a|2", "a", 2)
    assert _rows(path, "units") == [("a|1", "a", 1), ("a|2", "a", 2)]  # 2 s: both written
    assert lines == [f"checkpoint {path}: 2 units (0 codes complete) committed in this run, 0 units done before"]
    clock[0] = 103.9
    ck.add_unit("a|3", "a", 3)
    assert len(_rows(path, "units")) == 2  # 1.9 s after the last commit
    ck.finish_code("a", 6, units=3)  # a complete code commits at once
    assert _rows(path, "codes") == [("a", 6, 3)] and _rows(path, "units") == []
    assert lines[-1] == f"checkpoint {path}: 3 units (1 code complete) committed in this run, 0 units done before"
    ck.commit()  # nothing pending: no commit, no line
    assert len(lines) == 2
    ck.finish_code("b", 0, units=0)
    assert lines[-1] == f"checkpoint {path}: 3 units (2 codes complete) committed in this run, 0 units done before"
    ck.close()
    resumed = []
    Checkpoint(path, "p", "q", every=0.0, log=resumed.append).add_unit("c|1", "c", 1)
    assert resumed == [f"checkpoint {path}: 1 units (0 codes complete) committed in this run, 3 units done before"]
    clock[0] = 200.0
    default = Checkpoint(path, "p", "q", log=resumed.append)  # one second by default
    clock[0] = 200.99
    default.add_unit("c|2", "c", 1)
    assert len(resumed) == 1
    clock[0] = 201.0
    default.add_unit("c|3", "c", 1)
    assert len(resumed) == 2 and resumed[-1].startswith(f"checkpoint {path}: 2 units")


def test_ctrl_c_keeps_what_finished_and_an_error_drops_what_was_not_committed(tmp_path):
    kept, dropped = tmp_path / "kept.sqlite", tmp_path / "dropped.sqlite"
    with pytest.raises(KeyboardInterrupt):
        with Checkpoint(kept, "p", "q", every=1e9) as ck:
            ck.add_unit("a|1", "a", 5)
            raise KeyboardInterrupt
    assert _rows(kept, "units") == [("a|1", "a", 5)]
    with pytest.raises(ValueError):
        with Checkpoint(dropped, "p", "q", every=1e9) as ck:
            ck.add_unit("a|1", "a", 5)
            raise ValueError("a unit failed")
    assert _rows(dropped, "units") == []


def test_an_empty_file_is_made_a_checkpoint(tmp_path):
    path = tmp_path / "c.sqlite"
    path.write_bytes(b"")
    with Checkpoint(path, "p", "q") as ck:
        ck.finish_code("a", 1, units=1)
    assert _rows(path, "codes") == [("a", 1, 1)]


def test_a_checkpoint_in_the_working_directory_is_accepted(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with Checkpoint("c.sqlite", "p", "q") as ck:
        ck.finish_code("a", 1, units=1)
    assert _rows(tmp_path / "c.sqlite", "codes") == [("a", 1, 1)]


def test_another_query_s_checkpoint_is_refused_untouched(tmp_path):
    path = tmp_path / "c.sqlite"
    with Checkpoint(path, "plan-a", "chains W=1 n=8") as ck:
        ck.finish_code("a", 1, units=1)
    before = _untouched(path)
    with pytest.raises(CheckpointMismatch) as refused:
        Checkpoint(path, "plan-b", "chains W=1 n=10")
    assert refused.value.text(flag) == (
        f"the checkpoint {path} belongs to another query (chains W=1 n=8), not to chains W=1 n=10; give a new "
        "--checkpoint FILE or repeat that query")
    assert _untouched(path) == before


def test_a_checkpoint_of_an_older_plan_format_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "c.sqlite"
    monkeypatch.setattr(module, "PLAN_FORMAT", PLAN_FORMAT - 1)
    Checkpoint(path, "plan", "q").close()
    monkeypatch.setattr(module, "PLAN_FORMAT", PLAN_FORMAT)
    with pytest.raises(CheckpointMismatch, match="belongs to another query"):
        Checkpoint(path, "plan", "q")


def test_a_directory_or_a_missing_directory_is_refused(tmp_path):
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(tmp_path, "p", "q")
    assert str(refused.value) == f"the checkpoint {tmp_path} is a directory, not a file"
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(tmp_path / "nowhere" / "c.sqlite", "p", "q")
    assert str(refused.value) == (f"cannot create the checkpoint {tmp_path}/nowhere/c.sqlite: the directory "
                                  f"{tmp_path}/nowhere does not exist")
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def _sqlite(path, *statements):
    with sqlite3.connect(path) as db:
        for statement in statements:
            db.execute(statement)
    db.close()


@pytest.mark.parametrize("statements, what", [
    (["CREATE TABLE chains (id TEXT)"], "a mechsynth atlas"),
    (["CREATE TABLE notes (x)"], "an SQLite file of something else"),
    # the three tables, but no identity row, or a table short of a column, or a fourth table
    (["CREATE TABLE meta (key, value)", "CREATE TABLE codes (code, count, units)",
      "CREATE TABLE units (unit, code, count)"], "an SQLite file of something else"),
    (["CREATE TABLE meta (key, value)", "INSERT INTO meta VALUES ('identity', '2:p')",
      "CREATE TABLE codes (code, count)", "CREATE TABLE units (unit, code, count)"], "an SQLite file of something else"),
    (["CREATE TABLE meta (key, value)", "INSERT INTO meta VALUES ('identity', '2:p')",
      "CREATE TABLE codes (code, count, units)", "CREATE TABLE units (unit, code, count)",
      "CREATE TABLE chains (id)"], "a mechsynth atlas"),
])
def test_a_file_that_is_not_a_checkpoint_is_refused_untouched(tmp_path, statements, what):
    path = tmp_path / "other.sqlite"
    _sqlite(path, *statements)
    before = _untouched(path)
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(path, "p", "q")
    assert refused.value.text(flag) == (f"{path} is not a checkpoint of mechsynth but {what}; it was not changed "
                                        "(give a new --checkpoint FILE)")
    assert _untouched(path) == before


def test_a_checkpoint_without_its_query_in_words_is_read_as_unknown(tmp_path):
    path = tmp_path / "c.sqlite"
    _sqlite(path, "CREATE TABLE meta (key, value)", f"INSERT INTO meta VALUES ('identity', '{PLAN_FORMAT}:p')",
            "CREATE TABLE codes (code, count, units)", "CREATE TABLE units (unit, code, count)")
    assert module._check_file(path) == (f"{PLAN_FORMAT}:p", "unknown")
    with pytest.raises(CheckpointMismatch, match=r"belongs to another query \(unknown\), not to q2;"):
        Checkpoint(path, "p2", "q2")


def test_a_file_that_is_no_database_is_refused_untouched(tmp_path):
    path = tmp_path / "c.sqlite"
    path.write_text("not a database, but some text a user cared about\n" * 20)
    before = _untouched(path)
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(path, "p", "q")
    assert str(refused.value) == f"{path} is not a usable checkpoint (file is not a database); it was not changed"
    assert _untouched(path) == before


def test_a_damaged_checkpoint_is_refused_untouched(tmp_path):
    path = tmp_path / "c.sqlite"
    with Checkpoint(path, "p", "q") as ck:
        for k in range(50):
            ck.add_unit(f"unit {k:04}", "a", k)
    with sqlite3.connect(path) as db:
        size = db.execute("PRAGMA page_size").fetchone()[0]
        root = db.execute("SELECT rootpage FROM sqlite_master WHERE name = 'sqlite_autoindex_units_1'").fetchone()[0]
    db.close()
    data = bytearray(path.read_bytes())
    start = (root - 1) * size
    assert data[start] == 0x0A  # the index of the units is one leaf page; its cell count is made 900
    data[start + 3:start + 5] = (900).to_bytes(2, "big")
    path.write_bytes(bytes(data))
    before = _untouched(path)
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(path, "p", "q")
    assert refused.value.text(flag) == (
        f"the checkpoint {path} is damaged (*** in database main *** Page {root}: btreeInitPage() returns error "
        "code 11); it was not changed (give a new --checkpoint FILE)")
    assert _untouched(path) == before


def test_a_write_that_fails_is_one_sentence(tmp_path):
    path = tmp_path / "c.sqlite"
    ck = Checkpoint(path, "p", "q", every=1e9)
    ck.add_unit("a|1", "a", 1)
    blocker = sqlite3.connect(path, timeout=0)
    blocker.execute("BEGIN EXCLUSIVE")
    ck._conn.execute("PRAGMA busy_timeout = 0")
    with pytest.raises(CheckpointError) as refused:
        ck.commit()
    assert str(refused.value) == f"cannot write the checkpoint {path}: database is locked"
    blocker.rollback()
    blocker.close()


def test_a_checkpoint_another_count_wrote_meanwhile_is_refused(tmp_path, monkeypatch):
    # the file was empty when looked at (so not checked read-only first), and another count wrote its
    # identity before this one took the lock: refused all the same, and the file left unlocked
    path = tmp_path / "c.sqlite"
    Checkpoint(path, "plan-a", "chains W=1 n=8").close()
    before_meta = _rows(path, "meta")
    real = Path.stat
    monkeypatch.setattr(Path, "stat", lambda self, **kw: os.stat_result((0,) * 10) if self == path else real(self, **kw))
    with pytest.raises(CheckpointMismatch) as refused:
        Checkpoint(path, "plan-b", "chains W=1 n=10")
    assert refused.value.text(flag) == (
        f"the checkpoint {path} belongs to another query (chains W=1 n=8), not to chains W=1 n=10; give a new "
        "--checkpoint FILE or repeat that query")
    monkeypatch.undo()
    db = sqlite3.connect(path, timeout=0)
    db.execute("BEGIN EXCLUSIVE")  # no connection of the refused checkpoint holds it
    db.rollback()
    db.close()
    assert _rows(path, "meta") == before_meta  # (its journal mode may be the other count's WAL: that count runs)


def test_a_file_that_cannot_be_opened_is_one_sentence(tmp_path, monkeypatch):
    path = tmp_path / "c.sqlite"
    Checkpoint(path, "p", "q").close()

    def refuse(*args, **kwargs):
        raise sqlite3.OperationalError("unable to open database file")

    monkeypatch.setattr(module.sqlite3, "connect", refuse)  # (as a file the user may not read would)
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(path, "p", "q")
    assert str(refused.value) == (f"cannot read the checkpoint {path} (unable to open database file); "
                                  "it was not changed")


def test_a_new_checkpoint_that_cannot_be_written_is_one_sentence(tmp_path, monkeypatch):
    def refuse(*args, **kwargs):
        raise sqlite3.OperationalError("disk I/O error")

    monkeypatch.setattr(module.sqlite3, "connect", refuse)  # (as a full or failing disk would)
    with pytest.raises(CheckpointError) as refused:
        Checkpoint(tmp_path / "c.sqlite", "p", "q")
    assert str(refused.value) == f"{tmp_path / 'c.sqlite'} is not a usable checkpoint (disk I/O error)"
