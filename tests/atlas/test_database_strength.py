"""The atlas file itself: its schema read back from SQLite, every refusal's sentence, the upgrade of a
version-3 file, the run lock and the runs table, each checked against values set by hand."""

from __future__ import annotations

import hashlib
import os
import socket
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from synth.atlas import AtlasError, AtlasLocked, database, open_atlas, parse_grid, run_grid
from synth.atlas.database import SCHEMA_VERSION, acquire_run, refuse_unwritable, release_run, transaction
from synth.structure.chain import Chain, chain_id

from .helpers import as_version_3, sql

#: every table of a version-4 atlas and its columns, written out from the module docstring's schema
TABLES = {
    "meta": {"key", "value"},
    "chains": {"id", "certificate", "code", "base_code", "dof", "h", "links", "loops", "v", "prismatic",
               "max_degree", "degrees", "fractionated", "chain", "meshes"},
    "link_counts": {"chain", "degree", "count"},
    "trains": {"chain", "train", "lever_code", "carriers", "rotation", "rank"},
    "rotations": {"cell", "rotation", "chain", "rank"},
    "cells": {"cell", "dof", "h", "links", "v_min", "v_max", "rigid_subchains", "fractionated", "planar_only",
              "require", "units"},
    "members": {"cell", "chain"},
    "mechanisms": {"chain", "frame", "input_link"},
    "units": {"cell", "unit", "code", "status", "chains", "mechanisms", "attempts", "seconds", "finished", "run"},
    "runs": {"id", "pid", "host", "grid", "started", "finished", "status", "executor", "units_run"},
    "run_lock": {"id", "run", "pid", "host", "started"},
}


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _tables(db: Path) -> dict[str, set[str]]:
    with sqlite3.connect(db) as conn:
        names = [r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
        out = {name: {r[1] for r in conn.execute(f"PRAGMA table_info({name})")} for name in names}
    conn.close()
    return out


@pytest.fixture
def four_bar(tmp_path) -> Path:
    """An atlas of the one 1-DOF chain of four links (the four-bar)."""
    db = tmp_path / "four.sqlite"
    run_grid(parse_grid("dof = 1\nlinks = 4"), db, workers=1)
    return db


def test_a_new_atlas_has_every_table_and_column_and_its_version(tmp_path):
    db = tmp_path / "a.sqlite"
    before = time.strftime("%Y-%m-%dT%H:%M:%S")
    open_atlas(db, write=True).close()
    after = time.strftime("%Y-%m-%dT%H:%M:%S")
    assert _tables(db) == TABLES
    meta = dict(sql(db, "SELECT key, value FROM meta"))
    assert meta["schema_version"] == str(SCHEMA_VERSION) == "4"
    assert before <= meta["created"] <= after and len(meta["created"]) == 19
    # an empty file (as `touch` leaves it) is a new atlas too
    empty = tmp_path / "empty.sqlite"
    empty.touch()
    open_atlas(empty, write=True).close()
    assert _tables(empty) == TABLES


def test_opening_an_atlas_twice_for_writing_keeps_it(four_bar):
    rows = sql(four_bar, "SELECT certificate FROM chains")
    created = sql(four_bar, "SELECT value FROM meta WHERE key = 'created'")
    open_atlas(four_bar, write=True).close()
    assert sql(four_bar, "SELECT certificate FROM chains") == rows and len(rows) == 1
    assert sql(four_bar, "SELECT value FROM meta WHERE key = 'created'") == created


def test_every_refusal_of_a_path_is_its_sentence(tmp_path):
    folder = tmp_path / "folder"
    folder.mkdir()
    with pytest.raises(AtlasError) as e:
        refuse_unwritable(folder)
    assert str(e.value) == f"the atlas path {folder} is a directory, not a file"
    missing = tmp_path / "nowhere" / "a.sqlite"
    with pytest.raises(AtlasError) as e:
        open_atlas(missing, write=True)
    assert str(e.value) == (f"cannot create the atlas {missing}: the directory {tmp_path / 'nowhere'} "
                            "does not exist")
    read_only = tmp_path / "ro.sqlite"
    open_atlas(read_only, write=True).close()
    os.chmod(read_only, 0o444)
    try:
        with pytest.raises(AtlasError) as e:
            open_atlas(read_only, write=True)
        assert str(e.value) == f"cannot write the atlas {read_only}: the file is read-only"
    finally:
        os.chmod(read_only, 0o644)
    os.chmod(read_only, 0o200)  # writable by its owner only: still writable
    try:
        refuse_unwritable(read_only)
    finally:
        os.chmod(read_only, 0o644)
    locked = tmp_path / "locked"
    locked.mkdir()
    os.chmod(locked, 0o555)
    try:
        with pytest.raises(AtlasError) as e:
            open_atlas(locked / "a.sqlite", write=True)
        assert str(e.value) == (f"cannot write the atlas {locked / 'a.sqlite'}: the directory {locked} is read-only "
                                "(SQLite needs to write its journal next to the file)")
    finally:
        os.chmod(locked, 0o755)
    with pytest.raises(AtlasError) as e:
        open_atlas(tmp_path / "none.sqlite")
    none = tmp_path / "none.sqlite"
    assert str(e.value) == f"no atlas at {none} (run 'mechsynth grid GRID.toml --db {none}' first)"
    assert not none.exists()


def test_a_file_name_alone_is_created_in_the_working_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    open_atlas("bare.sqlite", write=True).close()
    assert _tables(tmp_path / "bare.sqlite") == TABLES
    os.chmod(tmp_path, 0o555)
    try:
        with pytest.raises(AtlasError, match="the directory . is read-only"):
            refuse_unwritable(Path("other.sqlite"))
    finally:
        os.chmod(tmp_path, 0o755)


@pytest.mark.parametrize("make, sentence", [
    (lambda c: c.execute("CREATE TABLE t (x)"), "{db} is an SQLite file but not a mechsynth atlas (no 'meta' table)"),
    (lambda c: c.execute("CREATE TABLE meta (key TEXT, value TEXT)"),
     "{db} is an SQLite file but not a mechsynth atlas (its meta table names no schema version)"),
    (lambda c: c.executescript("CREATE TABLE meta (key TEXT, value TEXT); INSERT INTO meta VALUES ('schema_version', '5')"),
     "{db} is an atlas of schema version 5, but this mechsynth reads only versions 3 and 4; use a new atlas file "
     "(or the mechsynth release that wrote it)"),
    (lambda c: c.executescript("CREATE TABLE meta (key TEXT, value TEXT); INSERT INTO meta VALUES ('schema_version', '4')"),
     "{db} is not a complete mechsynth atlas: table 'chains' lacks everything (it does not exist)"),
])
def test_a_file_that_is_not_an_atlas_is_refused_with_its_sentence_and_kept(tmp_path, make, sentence):
    db = tmp_path / "x.sqlite"
    with sqlite3.connect(db) as conn:
        make(conn)
    conn.close()
    digest = _digest(db)
    for write in (False, True):
        with pytest.raises(AtlasError) as e:
            open_atlas(db, write=write)
        assert str(e.value) == sentence.format(db=db)
    assert _digest(db) == digest


def test_a_missing_column_is_named(four_bar):
    with sqlite3.connect(four_bar) as conn:
        conn.execute("ALTER TABLE units DROP COLUMN seconds")
        conn.execute("ALTER TABLE units DROP COLUMN finished")
    conn.close()
    with pytest.raises(AtlasError) as e:
        open_atlas(four_bar)
    assert str(e.value) == f"{four_bar} is not a complete mechsynth atlas: table 'units' lacks finished, seconds"


def test_text_and_damaged_pages_are_refused_before_anything_is_written(four_bar, tmp_path, monkeypatch):
    text = tmp_path / "text.sqlite"
    text.write_bytes(b"hello, not a database\n" * 100)
    with pytest.raises(AtlasError) as e:
        open_atlas(text)
    assert str(e.value) == f"{text} is not an SQLite atlas or is damaged (file is not a database)"
    (root,), = sql(four_bar, "SELECT rootpage FROM sqlite_master WHERE name = 'chains'")
    data = bytearray(four_bar.read_bytes())
    page = int.from_bytes(data[16:18], "big")
    data[(root - 1) * page] = 0x42  # the chains table's root page: not a page type SQLite knows
    damaged = tmp_path / "damaged.sqlite"
    damaged.write_bytes(bytes(data))
    digest = _digest(damaged)
    for write in (False, True):
        with pytest.raises(AtlasError) as e:
            open_atlas(damaged, write=write)
        # SQLite's verdict without its "*** in database main ***" line
        assert str(e.value) == (f"the atlas {damaged} is damaged (Page {root}: btreeInitPage() returns error code 11); "
                                "it was only read, not changed")
    assert _digest(damaged) == digest
    # the page check can be skipped: the damage is then found when a query meets it
    open_atlas(damaged, check_pages=False).close()
    # an atlas too large to be checked when it is only read is still checked before a write
    monkeypatch.setattr(database, "_CHECKED_READ_BYTES", 0)
    open_atlas(damaged).close()
    with pytest.raises(AtlasError, match="is damaged"):
        open_atlas(damaged, write=True)
    assert _digest(damaged) == digest


def test_a_file_sqlite_cannot_create_is_one_sentence(tmp_path):
    link = tmp_path / "link.sqlite"
    link.symlink_to(tmp_path / "none" / "a.sqlite")  # a dangling link passes the path checks
    with pytest.raises(AtlasError) as e:
        open_atlas(link, write=True)
    assert str(e.value) == f"cannot write the atlas {link}: unable to open database file"


def test_the_tables_of_a_schema_are_read_back_from_sqlite():
    schema = "CREATE TABLE a (x INTEGER, y TEXT NOT NULL); CREATE INDEX i ON a (x); CREATE TABLE b (z)"
    assert database._columns(schema) == {"a": {"x", "y"}, "b": {"z"}}  # the index is no table


def test_a_version_3_atlas_is_read_through_views_and_upgraded_by_a_write(four_bar):
    as_version_3(four_bar)
    digest = _digest(four_bar)
    conn = open_atlas(four_bar)
    assert conn.execute("SELECT meshes FROM chains").fetchall() == [(0,)]
    assert conn.execute("SELECT COUNT(*) FROM trains").fetchone() == (0,)
    assert conn.execute("SELECT COUNT(*) FROM rotations").fetchone() == (0,)
    conn.close()
    assert _digest(four_bar) == digest
    with sqlite3.connect(four_bar) as raw:  # a version-3 file lacking a column of version 3 is refused
        raw.execute("ALTER TABLE cells DROP COLUMN planar_only")
    raw.close()
    with pytest.raises(AtlasError, match="table 'cells' lacks planar_only"):
        open_atlas(four_bar)


def test_the_upgrade_adds_the_gear_tables_and_keeps_every_chain(four_bar):
    rows = sql(four_bar, "SELECT certificate, code, chain FROM chains")
    as_version_3(four_bar)
    conn = open_atlas(four_bar, write=True)
    conn.close()
    assert _tables(four_bar) == TABLES
    assert sql(four_bar, "SELECT value FROM meta WHERE key = 'schema_version'") == [("4",)]
    assert sql(four_bar, "SELECT certificate, code, chain FROM chains") == rows
    assert sql(four_bar, "SELECT meshes FROM chains") == [(0,)]


def test_the_connection_knows_chain_ids_and_writes_at_once(four_bar):
    conn = open_atlas(four_bar)
    certificate = conn.execute("SELECT certificate FROM chains").fetchone()[0]
    assert certificate == Chain.parse("0-1 1-2 2-3 3-0").certificate
    assert conn.execute("SELECT chain_id(certificate) FROM chains").fetchone()[0] == chain_id(certificate) == \
        hashlib.sha1(certificate.encode()).hexdigest()[:12]
    assert conn.execute("SELECT chain_id(NULL)").fetchone() == (None,)
    assert conn.execute("PRAGMA foreign_keys").fetchone() == (0,)
    conn.close()
    conn = open_atlas(four_bar, write=True)
    assert conn.isolation_level is None  # autocommit: each write is its own or inside transaction()
    conn.execute("INSERT INTO meta VALUES ('note', 'x')")
    conn.close()
    assert sql(four_bar, "SELECT value FROM meta WHERE key = 'note'") == [("x",)]


def test_a_transaction_lands_whole_or_not_at_all(tmp_path):
    db = tmp_path / "a.sqlite"
    conn = open_atlas(db, write=True)
    with transaction(conn):
        conn.execute("INSERT INTO meta VALUES ('a', '1')")
        assert conn.in_transaction
    assert not conn.in_transaction
    with pytest.raises(KeyboardInterrupt):
        with transaction(conn):
            conn.execute("INSERT INTO meta VALUES ('b', '2')")
            raise KeyboardInterrupt
    assert not conn.in_transaction
    conn.close()
    assert dict(sql(db, "SELECT key, value FROM meta")).keys() == {"schema_version", "created", "a"}


def test_a_run_is_recorded_and_its_lock_taken_and_freed(tmp_path):
    db = tmp_path / "a.sqlite"
    grid = parse_grid("dof = 1\nlinks = 4", source="g.toml")
    conn = open_atlas(db, write=True)
    t0 = time.time()
    run = acquire_run(conn, db, grid, "local 2")
    t1 = time.time()
    assert run == 1
    (rid, pid, host, source, started, finished, status, executor, units), = sql(db, "SELECT * FROM runs")
    assert (rid, pid, host, source, finished, status, executor, units) == (
        1, os.getpid(), socket.gethostname(), "g.toml", None, "running", "local 2", 0)
    assert t0 <= started <= t1
    assert sql(db, "SELECT * FROM run_lock") == [(1, 1, os.getpid(), socket.gethostname(), started)]
    # the same process may take its own lock again (a second run of one session): the first is closed as killed
    second = acquire_run(conn, db, grid, "local 1")
    assert second == 2
    assert sql(db, "SELECT id, status FROM runs ORDER BY id") == [(1, "killed"), (2, "running")]
    assert sql(db, "SELECT finished >= ? FROM runs WHERE id = 1", started) == [(1,)]
    release_run(conn, second, "interrupted", 7)
    t2 = time.time()
    (status, finished, units), = sql(db, "SELECT status, finished, units_run FROM runs WHERE id = 2")
    assert (status, units) == ("interrupted", 7) and t1 <= finished <= t2
    assert sql(db, "SELECT COUNT(*) FROM run_lock") == [(0,)]
    assert sql(db, "SELECT status FROM runs WHERE id = 1") == [("killed",)]  # a finished run is not touched
    conn.close()


def test_a_live_lock_names_its_holder_and_changes_nothing(tmp_path):
    db = tmp_path / "a.sqlite"
    grid = parse_grid("dof = 1\nlinks = 4")
    conn = open_atlas(db, write=True)
    sleeper = subprocess.Popen([sys.executable, "-c", "import signal; signal.pause()"])
    try:
        started = time.time()
        with transaction(conn):
            conn.execute("INSERT INTO runs (pid, host, grid, started, status, executor) "
                         "VALUES (?, ?, 'x', ?, 'running', 'local 1')", (sleeper.pid, socket.gethostname(), started))
            conn.execute("INSERT INTO run_lock VALUES (1, 1, ?, ?, ?)", (sleeper.pid, socket.gethostname(), started))
        with pytest.raises(AtlasLocked) as e:
            acquire_run(conn, db, grid, "local 1")
        when = time.strftime("%H:%M:%S", time.localtime(started))
        assert str(e.value) == (f"the atlas {db} is being written by another grid run (pid {sleeper.pid} on "
                                f"{socket.gethostname()}, started {when}); wait for it to finish or use another atlas file")
        assert sql(db, "SELECT id, status FROM runs") == [(1, "running")]
    finally:
        sleeper.kill()
        sleeper.wait()
    # the holder is dead now: its run is closed as killed and the lock taken over
    assert acquire_run(conn, db, grid, "local 1") == 2
    assert sql(db, "SELECT id, status FROM runs ORDER BY id") == [(1, "killed"), (2, "running")]
    assert sql(db, "SELECT run, pid FROM run_lock") == [(2, os.getpid())]
    conn.close()


def test_a_lock_held_on_another_host_is_never_taken_over(tmp_path):
    db = tmp_path / "a.sqlite"
    conn = open_atlas(db, write=True)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    with transaction(conn):
        conn.execute("INSERT INTO run_lock VALUES (1, 9, ?, 'elsewhere', ?)", (dead.pid, time.time()))
    with pytest.raises(AtlasLocked, match=f"pid {dead.pid} on elsewhere"):
        acquire_run(conn, db, parse_grid("dof = 1\nlinks = 4"), "dask tcp://x:1")
    assert sql(db, "SELECT COUNT(*) FROM runs") == [(0,)]
    conn.close()


def test_a_dead_process_is_not_alive_and_a_live_one_is(monkeypatch):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    assert database._alive(os.getpid()) and not database._alive(dead.pid)

    def kill(pid, signal):  # another user's process: signal 0 is refused, but the process is there
        assert signal == 0
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(os, "kill", kill)
    assert database._alive(dead.pid)


def test_an_empty_file_is_said_to_be_empty_not_an_sqlite_file(tmp_path, capsys):
    """`atlas --db empty.txt` said 'empty.txt is an SQLite file but not a mechsynth atlas'; the file
    stays empty."""
    from mechsynth.cli import main

    empty = tmp_path / "empty.txt"
    empty.write_bytes(b"")
    assert main(["atlas", "--db", str(empty)]) == 2
    err = capsys.readouterr().err
    assert "is empty" in err and "SQLite file" not in err and empty.read_bytes() == b""


def test_a_counts_checkpoint_given_as_an_atlas_is_named(tmp_path, capsys):
    """`atlas --db c16.sqlite` called a checkpoint 'an SQLite file but not a mechsynth atlas (its meta table
    names no schema version)'; the checkpoint, unchanged, says the reverse of what --checkpoint says of an atlas."""
    from mechsynth.cli import main

    checkpoint = tmp_path / "c6.sqlite"
    assert main(["chains", "--dof", "1", "--links", "6", "--count", "--checkpoint", str(checkpoint)]) == 0
    before = checkpoint.read_bytes()
    capsys.readouterr()
    assert main(["atlas", "--db", str(checkpoint)]) == 2
    assert capsys.readouterr().err == f"mechsynth: {checkpoint} is the checkpoint of a count (chains dof=1 links=6), not an atlas\n"
    assert checkpoint.read_bytes() == before
