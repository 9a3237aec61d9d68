"""The SQLite atlas: grid runs on 2 workers and on Dask, kill -9 and resume, refusals, queries."""

from __future__ import annotations

import hashlib
import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

import synth
from synth.atlas import AtlasLocked, export, parse_where, run_grid, summary
from synth.atlas.runs import SchedulerUnreachable
from mechsynth.cli import main
from synth.errors import InvalidOption
from synth.atlas.grid import load_grid, parse_grid

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "models" / "grid_small.toml"


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _content(db: Path) -> dict:
    """Everything a run produces, independent of timing and order."""
    with sqlite3.connect(db) as conn:
        content = {
            "chains": sorted(conn.execute("SELECT certificate, code, base_code, dof, links, loops, v, max_degree, "
                                          "degrees, fractionated, chain FROM chains")),
            "members": sorted(conn.execute(
                "SELECT m.cell, c.certificate FROM members m JOIN chains c ON c.id = m.chain")),
            "mechanisms": sorted(conn.execute(
                "SELECT c.certificate, k.frame, k.input_link FROM mechanisms k JOIN chains c ON c.id = k.chain")),
            "link_counts": sorted(conn.execute(
                "SELECT c.certificate, l.degree, l.count FROM link_counts l JOIN chains c ON c.id = l.chain")),
            "units": sorted(conn.execute("SELECT cell, unit, code, status, chains, mechanisms FROM units")),
            "cells": sorted(conn.execute("SELECT * FROM cells")),
            "counts": [conn.execute(f"SELECT COUNT(*) FROM {t}").fetchone()[0]
                       for t in ("chains", "members", "mechanisms", "link_counts")],
        }
    conn.close()
    return content


@pytest.fixture(scope="module")
def small_atlas(tmp_path_factory) -> Path:
    """The issue's grid W = 1..3, n <= 10, v <= 2, run on 2 workers without interruption."""
    db = tmp_path_factory.mktemp("atlas") / "small.sqlite"
    result = run_grid(load_grid(SMALL), db, workers=2)
    assert result.status == "done" and result.units_run == result.units_total > 0
    return db


def test_per_cell_counts_equal_count_chains(small_atlas):
    grid = load_grid(SMALL)
    info = summary(small_atlas)
    cells = {c["cell"]: c for c in info["cells"]}
    assert set(cells) == {c.key for c in grid.cells}
    for cell in grid.cells:
        expected = synth.count_chains(cell.dof, cell.links, workers=1, **cell.selection())
        got = cells[cell.key]
        assert got["units_done"] == got["units_total"]
        assert got["by_code"] == expected["by_code"], cell.key
        assert got["chains"] == expected["count"]
    assert info["units"]["done"] == info["units"]["total"]
    assert info["chains"] == sum(c["chains"] for c in info["cells"])  # cells are disjoint here


@pytest.mark.parametrize("links, expected", [(4, 1), (6, 5), (8, 71)])
def test_mechanism_counts_one_dof(small_atlas, links, expected):
    rows = list(export(small_atlas, "mechanisms", where=["W=1", f"n={links}", "v=0"]))
    assert len(rows) == expected
    assert len({r["certificate"] for r in rows}) == expected
    assert sum(1 for _ in synth.mechanisms(1, links, workers=1)) == expected


def test_rerun_does_nothing(small_atlas):
    before = _content(small_atlas)
    with sqlite3.connect(small_atlas) as conn:
        attempts = sorted(conn.execute("SELECT cell, unit, attempts, finished FROM units"))
    result = run_grid(load_grid(SMALL), small_atlas, workers=2)
    assert result.units_run == 0 and result.units_skipped == result.units_total
    assert _content(small_atlas) == before
    with sqlite3.connect(small_atlas) as conn:
        assert sorted(conn.execute("SELECT cell, unit, attempts, finished FROM units")) == attempts


def _done(db: Path) -> int:
    try:
        conn = sqlite3.connect(f"{db.as_uri()}?mode=ro", uri=True, timeout=5)
        try:
            return conn.execute("SELECT COUNT(*) FROM units WHERE status = 'done'").fetchone()[0]
        finally:
            conn.close()
    except sqlite3.Error:
        return 0


def _children(pid: int) -> list[int]:
    """Processes whose parent is ``pid`` (the run's pool workers), from /proc."""
    out = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                out.append(int(entry.name))
    return out


def test_sigkill_then_resume_equals_uninterrupted_run(small_atlas, tmp_path, capsys):
    db = tmp_path / "killed.sqlite"
    command = [sys.executable, "-m", "mechsynth", "grid", str(SMALL), "--db", str(db), "--workers", "2"]
    proc = subprocess.Popen(command, cwd=ROOT, start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        # wait for the run's own state (units committed), not for a time; the limit only stops a hang
        hang_guard = time.monotonic() + 600
        while _done(db) < 20 and proc.poll() is None and time.monotonic() < hang_guard:
            time.sleep(0.02)
        # freeze the pool workers: the run stays alive, holds its lock and cannot finish, whatever the load
        workers = _children(proc.pid)
        for pid in workers:
            os.kill(pid, signal.SIGSTOP)
        assert proc.poll() is None and workers, "the run finished before it could be stopped"
        assert _done(db) >= 20
        # a second run on the same atlas while the first is alive is refused
        assert main(["grid", str(SMALL), "--db", str(db), "--workers", "1"]) == 2
        assert "being written by another grid run" in capsys.readouterr().err
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == -signal.SIGKILL
    with sqlite3.connect(db) as conn:
        total = conn.execute("SELECT COUNT(*) FROM units").fetchone()[0]
        finished = sorted(conn.execute(
            "SELECT cell, unit, attempts, finished, run, chains FROM units WHERE status = 'done'"))
        stored = conn.execute("SELECT COUNT(*) FROM members").fetchone()[0]
    assert 0 < len(finished) < total
    assert stored == sum(row[5] for row in finished)  # only whole units were committed

    assert main(["grid", str(SMALL), "--db", str(db), "--workers", "2"]) == 0
    assert _content(db) == _content(small_atlas)
    with sqlite3.connect(db) as conn:
        again = {row[:2]: row for row in conn.execute(
            "SELECT cell, unit, attempts, finished, run, chains FROM units")}
        runs = [r[0] for r in conn.execute("SELECT status FROM runs ORDER BY id")]
        assert conn.execute("SELECT COUNT(*) FROM run_lock").fetchone()[0] == 0
    for row in finished:  # not recomputed: same finishing time, same run, one attempt
        assert again[row[:2]] == row and row[2] == 1
    assert all(r[2] == 2 for k, r in again.items() if k not in {f[:2] for f in finished})
    assert runs == ["killed", "done"]


def test_dask_local_cluster_gives_the_same_atlas(small_atlas, tmp_path):
    from distributed import LocalCluster

    db = tmp_path / "dask.sqlite"
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      host="127.0.0.1") as cluster:
        result = run_grid(load_grid(SMALL), db, scheduler=cluster.scheduler_address)
    assert result.status == "done" and result.executor.startswith("dask")
    assert _content(db) == _content(small_atlas)


def test_unreachable_scheduler(tmp_path, capsys, monkeypatch):
    import distributed

    asked = []
    real_client = distributed.Client

    def spy(*args, **kwargs):  # the --timeout given is the one the connection waits for (if a Client is built:
        # an address where nothing listens is refused by a plain TCP probe first)
        asked.append(kwargs.get("timeout"))
        return real_client(*args, **kwargs)

    monkeypatch.setattr(distributed, "Client", spy)
    db = tmp_path / "a.sqlite"
    code = main(["grid", str(SMALL), "--db", str(db), "--scheduler", "tcp://127.0.0.1:1", "--timeout", "1"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and all(float(str(t).rstrip("s")) == 1.0 for t in asked)
    assert err.startswith("mechsynth: cannot reach the Dask scheduler at tcp://127.0.0.1:1") and "\n" not in err
    assert "within 1 s" in err
    assert not db.exists()
    with pytest.raises(SchedulerUnreachable):
        run_grid(parse_grid("dof = 1\nlinks = 4"), db, scheduler="tcp://127.0.0.1:1", connect_timeout=1)


TINY = "dof = 1\nlinks = \"4..6\"\n"


@pytest.fixture
def tiny(tmp_path) -> tuple[Path, Path]:
    grid = tmp_path / "tiny.toml"
    grid.write_text(TINY)
    db = tmp_path / "tiny.sqlite"
    assert main(["grid", str(grid), "--db", str(db), "--workers", "1"]) == 0
    return grid, db


def test_other_schema_version_is_refused(tiny, capsys):
    grid, db = tiny
    with sqlite3.connect(db) as conn:
        conn.execute("UPDATE meta SET value = '99' WHERE key = 'schema_version'")
    conn.close()
    digest = _digest(db)
    capsys.readouterr()
    for argv in (["grid", str(grid), "--db", str(db)], ["atlas", "--db", str(db)]):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert "schema version 99" in err and "\n" not in err
    assert _digest(db) == digest


def test_read_only_atlas_is_refused(tiny, capsys):
    grid, db = tiny
    digest = _digest(db)
    os.chmod(db, 0o444)
    try:
        capsys.readouterr()
        assert main(["grid", str(grid), "--db", str(db)]) == 2
        err = capsys.readouterr().err.strip()
        assert "read-only" in err and "\n" not in err
        assert _digest(db) == digest
        assert main(["atlas", "--db", str(db), "--format", "json"]) == 0  # reading still works
        assert json.loads(capsys.readouterr().out)["chains"] == 3
    finally:
        os.chmod(db, 0o644)


def test_read_only_directory_is_refused(tmp_path, capsys):
    folder = tmp_path / "ro"
    folder.mkdir()
    grid = tmp_path / "g.toml"
    grid.write_text(TINY)
    os.chmod(folder, 0o555)
    try:
        assert main(["grid", str(grid), "--db", str(folder / "a.sqlite")]) == 2
        assert "read-only" in capsys.readouterr().err
        assert not (folder / "a.sqlite").exists()
    finally:
        os.chmod(folder, 0o755)


def test_not_an_atlas(tmp_path, capsys):
    grid = tmp_path / "g.toml"
    grid.write_text(TINY)
    for name, data in (("text.sqlite", b"hello, not a database\n" * 100), ("other.sqlite", None)):
        db = tmp_path / name
        if data is None:
            with sqlite3.connect(db) as conn:
                conn.execute("CREATE TABLE t (x)")
            conn.close()
        else:
            db.write_bytes(data)
        digest = _digest(db)
        assert main(["grid", str(grid), "--db", str(db)]) == 2
        err = capsys.readouterr().err.strip()
        assert "atlas" in err and "\n" not in err
        assert _digest(db) == digest
    assert main(["atlas", "--db", str(tmp_path / "missing.sqlite")]) == 2
    assert "no atlas" in capsys.readouterr().err


def test_live_lock_refused_and_stale_lock_taken_over(tiny, capsys):
    grid, db = tiny
    sleeper = subprocess.Popen([sys.executable, "-c", "import signal; signal.pause()"])  # alive until killed
    try:
        with sqlite3.connect(db) as conn:
            conn.execute("INSERT INTO run_lock VALUES (1, 999, ?, ?, ?)", (sleeper.pid, os.uname().nodename, time.time()))
        conn.close()
        digest = _digest(db)
        with pytest.raises(AtlasLocked, match=f"pid {sleeper.pid}"):
            run_grid(parse_grid(TINY), db, workers=1)
        assert _digest(db) == digest
    finally:
        sleeper.kill()
        sleeper.wait()
    result = run_grid(parse_grid(TINY), db, workers=1)  # the holder is dead: the lock is stale
    assert result.status == "done" and result.units_run == 0


def test_same_chain_in_two_cells_is_stored_once(tmp_path):
    db = tmp_path / "a.sqlite"
    grid = parse_grid("dof = 2\nlinks = 9\n[[block]]\n[[block]]\nfractionated = false\n")
    run_grid(grid, db, workers=1)
    info = summary(db)
    with_frac, without = sorted(info["cells"], key=lambda c: c["cell"])[::-1]
    assert with_frac["chains"] > without["chains"] > 0
    assert info["chains"] == with_frac["chains"]  # every non-fractionated chain is also in the other cell
    rows = list(export(db, "chains", where=["fractionated=0"]))
    assert len(rows) == without["chains"] and all(len(r["cells"]) == 2 for r in rows)


def test_input_link_mechanisms(tmp_path):
    db = tmp_path / "a.sqlite"
    run_grid(parse_grid("input_link = true\ndof = 1\nlinks = 6\n"), db, workers=1)
    chains = list(synth.type_synthesis(1, 6, workers=1))
    info = summary(db)
    assert info["mechanisms"] == 5
    assert info["mechanisms_with_input"] == sum(len(synth.mechanisms_of(c, input_link=True)) for c in chains)


def test_where_filters(small_atlas, capsys):
    count = lambda *where: sum(1 for _ in export(small_atlas, "chains", where=where))  # noqa: E731
    assert count("code=6301/0") == 15
    assert count("W=1", "n=10", "v=0") == 230
    assert count("W=1", "n=8..10", "v<=0") == 230 + 16
    assert count("code=620/0-1") == 1 and count("code=620/2") == 15 and count("basecode=620/2") == 16
    every = list(export(small_atlas, "chains", where=["W=1", "n=10", "v=0"]))
    assert count("W=1", "n=10", "v=0", "n5>=1") == sum(1 for r in every if 5 in r["degrees"]) > 0
    assert count("W=1", "n=10", "v=0", "n2=4") == sum(1 for r in every if r["degrees"].count(2) == 4) > 0
    rows = list(export(small_atlas, "chains", where=["W=3", "n=8", "maxdeg<=3"]))
    assert rows and all(max(r["degrees"]) <= 3 for r in rows)
    keys = [(r["v"], r["code"], r["certificate"]) for r in rows]
    assert keys == sorted(keys)  # deterministic order
    for bad in ("code<6301/0", "n=x", "links=1..2; DROP TABLE chains", "foo=1", "n>1..3", "v"):
        with pytest.raises(InvalidOption):
            parse_where([bad])
    assert main(["atlas", "--db", str(small_atlas), "--where", "n3>=1'; DROP TABLE chains; --"]) == 2
    capsys.readouterr()
    assert main(["atlas", "--db", str(small_atlas), "--where", "code=6301/0", "--format", "csv"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("id,code,links") and len(lines) == 16
    from synth.atlas import chain_id  # the id column is the chain's site address, from its certificate

    assert all(row.split(",")[0] == chain_id(row.rsplit(",", 1)[1]) for row in lines[1:])
    assert main(["atlas", "--db", str(small_atlas), "--export", "mechanisms", "--where", "n=6", "--where", "W=1",
                 "--where", "v=0", "--count"]) == 0
    assert json.loads(capsys.readouterr().out) == {"count": 5, "by_code": {"42/0": 5}}


def test_summary_table_and_json(small_atlas, capsys):
    assert main(["atlas", "--db", str(small_atlas)]) == 0
    out = capsys.readouterr().out
    assert "units 201/201 done" in out and "6301/0" in out
    assert main(["atlas", "--db", str(small_atlas), "--format", "json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["by_code"]["4600/0"] == 50 and info["mechanisms_by_code"]["42/0"] == 5
