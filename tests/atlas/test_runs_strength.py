"""Grid runs row by row on atlases of a few links: every column of a chain, unit, cell and run row against
values worked out by hand (the four-bar, Watt's and Stephenson's chains and their 1 + 2 + 3 inversions, the
fractionated 2-DOF chain of two four-bars on one link) or counted by the engine's own listing; what an
interrupted or failed run leaves; and the sizing of a grid from estimates given by hand."""

from __future__ import annotations

import json
import math
import random
import time
from pathlib import Path

import pytest

import synth
from synth.atlas import parse_grid, run_grid
from synth.atlas import runs
from synth.atlas.runs import GridRunResult, UnitRows, _commit, _log_sum, _power, size_grid
from synth.errors import InvalidOption, QueryTooLarge
from synth.structure.chain import Chain
from synth.synthesis.type_synthesis import mechanisms_of

from .helpers import sql

GRID = 'dof = 1\nlinks = "4..6"\n[[block]]\n[[block]]\ndof = 2\nlinks = 7\n[[gears]]\nlinks = 4\n'
#: the 1-DOF chains by hand: code, base code, loops, sorted degrees, link counts n2, n3, inversions
HAND = {
    "four-bar": ("4/0", 4, 1, "2 2 2 2", {2: 4}, 1),
    "Watt": ("42/0", 6, 2, "3 3 2 2 2 2", {2: 4, 3: 2}, 2),
    "Stephenson": ("42/0", 6, 2, "3 3 2 2 2 2", {2: 4, 3: 2}, 3),
}
WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")  # two ternary links joined directly
STEPHENSON = Chain.parse("0-1 1-2 2-3 3-0 1-4 4-5 5-3")  # ternary links 1 and 3, never joined


@pytest.fixture
def atlas(tmp_path):
    db = tmp_path / "a.sqlite"
    t0 = time.time()
    result = run_grid(parse_grid(GRID, source="g.toml"), db, workers=1)
    return db, result, t0, time.time()


def _chains(db: Path, where: str = "1") -> dict[str, tuple]:
    return {r[0]: r[1:] for r in sql(db, f"SELECT certificate, code, base_code, dof, h, links, loops, v, prismatic, "
                                         f"max_degree, degrees, fractionated, chain, meshes, id FROM chains WHERE {where}")}


def test_every_column_of_the_one_dof_chains_by_hand(atlas):
    db = atlas[0]
    chains = _chains(db, "dof = 1 AND meshes = 0")
    named = {"four-bar": Chain.parse("0-1 1-2 2-3 3-0"), "Watt": WATT, "Stephenson": STEPHENSON}
    assert set(chains) == {c.certificate for c in named.values()}
    for name, chain in named.items():
        code, links, loops, degrees, counts, inversions = HAND[name]
        row = chains[chain.certificate]
        assert row[:12] == (code, code, 1, 3, links, loops, 0, 0, int(degrees[0]), degrees, 0, row[11]), name
        assert row[12] == 0  # no gear mesh
        stored = Chain.from_dict(json.loads(row[11]))
        assert stored.certificate == chain.certificate and stored.links == links
        assert row[11] == json.dumps(json.loads(row[11]), separators=(",", ":"))  # compact: no blank after , and :
        assert dict(sql(db, "SELECT degree, count FROM link_counts WHERE chain = ?", row[13])) == counts
        frames = sql(db, "SELECT frame, input_link FROM mechanisms WHERE chain = ?", row[13])
        assert len(frames) == inversions and all(i == -1 for _, i in frames)
        # each frame is the smallest link of its orbit in the stored labelling: no two frames are alike
        assert len({stored.degrees[f] for f, _ in frames}) <= inversions


def test_the_fractionated_chain_is_flagged_and_only_it(atlas):
    db = atlas[0]
    two = _chains(db, "dof = 2")
    assert sorted((r[0], r[10]) for r in two.values()) == [("52/0", 0), ("52/0", 0), ("52/0", 0), ("601/0", 1)]
    (row,) = [r for r in two.values() if r[0] == "601/0"]
    assert row[9] == "4 2 2 2 2 2 2" and row[8] == 4  # two four-bars sharing one link
    assert dict(sql(db, "SELECT degree, count FROM link_counts WHERE chain = ?", row[13])) == {2: 6, 4: 1}


def test_mechanisms_are_the_engines_inversions(atlas):
    db = atlas[0]
    for certificate, row in _chains(db, "meshes = 0").items():
        stored = Chain.from_dict(json.loads(row[11]))
        expected = sorted(m.frame for m in mechanisms_of(stored))
        assert sorted(f for (f,) in sql(db, "SELECT frame FROM mechanisms WHERE chain = ?", row[13])) == expected


def test_the_chain_is_stored_in_its_canonical_labelling():
    rng = random.Random(5)
    for chain in (WATT, STEPHENSON, Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-6 6-0")):
        first = chain.canonical()
        assert first.certificate == chain.certificate
        for _ in range(6):
            labels = list(range(chain.links))
            rng.shuffle(labels)
            assert chain.relabel(labels).canonical().to_dict() == first.to_dict()


def test_units_cells_and_the_run_row(atlas):
    db, result, t0, t1 = atlas
    units = sql(db, "SELECT cell, code, status, chains, mechanisms, attempts, seconds, finished, run FROM units "
                    "WHERE cell NOT LIKE 'gears%' ORDER BY cell, code")
    mechanisms = {"4/0": 1, "42/0": 5}
    assert [(c, code, s, n, a, r) for c, code, s, n, _, a, _, _, r in units] == [
        ("W=1 n=4 v=0..0 rigid=0 frac=1 planar=0", "4/0", "done", 1, 1, 1),
        ("W=1 n=6 v=0..0 rigid=0 frac=1 planar=0", "42/0", "done", 2, 1, 1),
        ("W=2 n=7 v=0..0 rigid=0 frac=1 planar=0", "52/0", "done", 3, 1, 1),
        ("W=2 n=7 v=0..0 rigid=0 frac=1 planar=0", "601/0", "done", 1, 1, 1)]
    for cell, code, _, _, m, _, seconds, finished, _ in units:
        if code in mechanisms:
            assert m == mechanisms[code]
        assert 0 < seconds < t1 - t0 and t0 <= finished <= t1
    two = sum(len(mechanisms_of(c)) for c in synth.type_synthesis(2, 7))
    assert sum(m for _, code, _, _, m, *_ in units if code in ("52/0", "601/0")) == two
    cells = sql(db, "SELECT * FROM cells ORDER BY cell")
    assert cells == [
        ("W=1 n=4 v=0..0 rigid=0 frac=1 planar=0", 1, 3, 4, 0, 0, 0, 1, 0, "[]", 1),
        ("W=1 n=6 v=0..0 rigid=0 frac=1 planar=0", 1, 3, 6, 0, 0, 0, 1, 0, "[]", 1),
        ("W=2 n=7 v=0..0 rigid=0 frac=1 planar=0", 2, 3, 7, 0, 0, 0, 1, 0, "[]", 2),
        ("gears F=1 n=4 graphs=displacement", 1, 3, 4, 0, None, 0, 1, 0, "[]", 4)]
    gear_units = sql(db, "SELECT status, attempts FROM units WHERE cell LIKE 'gears%'")
    assert gear_units == [("done", 1)] * 4
    (run,) = sql(db, "SELECT id, status, executor, units_run, grid, started <= finished FROM runs")
    assert run == (1, "done", "local 1", 8, "g.toml", 1)
    assert sql(db, "SELECT COUNT(*) FROM run_lock") == [(0,)]
    assert sql(db, "PRAGMA journal_mode") == [("delete",)] and not Path(f"{db}-wal").exists()


def test_the_result_counts_units_chains_and_mechanisms(atlas):
    db, result, t0, t1 = atlas
    gears = sql(db, "SELECT COUNT(*) FROM chains WHERE meshes > 0")[0][0]
    gear_mechanisms = sql(db, "SELECT COUNT(*) FROM mechanisms k JOIN chains c ON c.id = k.chain "
                              "WHERE c.meshes > 0")[0][0]
    two = sum(len(mechanisms_of(c)) for c in synth.type_synthesis(2, 7))
    assert gears > 0
    assert (result.status, result.units_total, result.units_skipped, result.units_run, result.executor,
            result.cells) == ("done", 8, 0, 8, "local 1", 4)
    assert result.chains_found == result.chains_new == 3 + 4 + gears
    assert result.mechanisms_found == 6 + two + gear_mechanisms
    assert 0 < result.seconds < t1 - t0
    row = result.to_dict()
    assert row["seconds"] == round(result.seconds, 3)
    assert row["chains_per_second"] == round(result.chains_found / result.seconds, 1)
    again = run_grid(parse_grid(GRID), db, workers=1)
    assert (again.status, again.units_total, again.units_skipped, again.units_run, again.chains_found,
            again.chains_new, again.mechanisms_found) == ("done", 8, 8, 0, 0, 0, 0)
    assert sql(db, "SELECT DISTINCT attempts FROM units") == [(1,)]  # nothing was scheduled again
    assert sql(db, "SELECT id, status, units_run, executor FROM runs ORDER BY id") == [
        (1, "done", 8, "local 1"), (2, "done", 0, "local 1")]


def test_a_rate_without_time_is_zero():
    assert GridRunResult("done", 1, 0, 1, chains_found=5, seconds=0.0).chains_per_second == 0.0
    assert GridRunResult("done", 1, 0, 1, chains_found=5, seconds=2.0).chains_per_second == 2.5


def test_a_chain_found_again_in_another_cell_is_new_once(tmp_path):
    db = tmp_path / "a.sqlite"
    # the 1-DOF chains of 6 links with and without fractionated chains: the same two chains in two cells
    result = run_grid(parse_grid('dof = 1\nlinks = 6\n[[block]]\n[[block]]\nfractionated = false\n'), db, workers=1)
    assert (result.chains_found, result.chains_new, result.mechanisms_found) == (4, 2, 10)
    assert sql(db, "SELECT COUNT(*) FROM chains") == [(2,)] and sql(db, "SELECT COUNT(*) FROM members") == [(4,)]
    assert sql(db, "SELECT COUNT(*) FROM mechanisms") == [(5,)]


def test_input_link_mechanisms_are_the_engines(tmp_path):
    db = tmp_path / "a.sqlite"
    run_grid(parse_grid("input_link = true\ndof = 1\nlinks = 6\n"), db, workers=1)
    for cid, text in sql(db, "SELECT id, chain FROM chains"):
        chain = Chain.from_dict(json.loads(text))
        expected = sorted([(m.frame, -1) for m in mechanisms_of(chain)] +
                          [(m.frame, m.input_link) for m in mechanisms_of(chain, input_link=True)])
        assert sorted(sql(db, "SELECT frame, input_link FROM mechanisms WHERE chain = ?", cid)) == expected
        assert any(i >= 0 for _, i in expected)


@pytest.mark.parametrize("workers", [0, -1, True, 1.5, "2"])
def test_workers_are_a_whole_number(tmp_path, workers):
    with pytest.raises(InvalidOption) as e:
        run_grid(parse_grid("dof = 1\nlinks = 4"), tmp_path / "a.sqlite", workers=workers)
    assert str(e.value) == f"workers must be a whole number ≥ 1, not {workers!r}"
    assert not (tmp_path / "a.sqlite").exists()


@pytest.mark.parametrize("error, status", [(KeyboardInterrupt, "interrupted"), (RuntimeError, "failed")])
def test_a_stopped_run_keeps_its_finished_units_and_frees_the_lock(tmp_path, monkeypatch, error, status):
    db = tmp_path / "a.sqlite"
    grid = parse_grid('dof = 1\nlinks = "4..6"')
    compute, calls = runs.compute_unit, []

    def second_fails(task):
        calls.append(task.cell)
        if len(calls) == 2:
            raise error("stop")
        return compute(task)

    monkeypatch.setattr(runs, "compute_unit", second_fails)
    with pytest.raises(error):
        run_grid(grid, db, workers=1)
    assert sql(db, "SELECT id, status, units_run FROM runs") == [(1, status, 1)]
    assert sql(db, "SELECT COUNT(*) FROM run_lock") == [(0,)]
    assert sorted(sql(db, "SELECT status, attempts FROM units")) == [("done", 1), ("pending", 1)]
    assert sql(db, "SELECT COUNT(*) FROM chains") == [(1,)]
    monkeypatch.setattr(runs, "compute_unit", compute)
    result = run_grid(grid, db, workers=1)  # resumed: the pending unit alone
    assert (result.units_total, result.units_skipped, result.units_run, result.chains_new) == (2, 1, 1, 2)
    assert sorted(sql(db, "SELECT status, attempts FROM units")) == [("done", 1), ("done", 2)]


def test_a_unit_of_more_chains_than_one_lookup_takes_is_stored_whole(tmp_path):
    """Certificates are looked up 500 at a time (SQLite's variable limit): 1 201 made-up rows land whole."""
    from synth.atlas.database import open_atlas, transaction

    db = tmp_path / "a.sqlite"
    conn = open_atlas(db, write=True)
    with transaction(conn):
        conn.execute("INSERT INTO cells VALUES ('c', 1, 3, 4, 0, 0, 0, 1, 0, '[]', 1)")
        conn.execute("INSERT INTO units (cell, unit, code) VALUES ('c', 'u', 'x')")
    certs = [f"cert{i:05d}" for i in range(1201)]
    rows = UnitRows("c", "u", [(c, "4/0", "4/0", 1, 3, 4, 1, 0, 0, 2, "2 2 2 2", 0, "{}", 0) for c in certs],
                    [(c, 2, 4) for c in certs], [(c, 0, -1) for c in certs], 0.5)
    assert _commit(conn, rows, 7) == 1201
    assert _commit(conn, rows, 7) == 0  # stored once
    conn.close()
    for table in ("chains", "link_counts", "members", "mechanisms"):
        assert sql(db, f"SELECT COUNT(*) FROM {table}") == [(1201,)], table
    assert sql(db, "SELECT COUNT(*) FROM link_counts l JOIN chains c ON c.id = l.chain") == [(1201,)]
    assert sql(db, "SELECT status, chains, mechanisms, seconds, run FROM units") == [("done", 1201, 1201, 0.5, 7)]


# ------------------------------------------------------------------ sizing, from estimates given by hand
class _Estimate:
    def __init__(self, log10_seconds, log10_chains):
        self.log10_seconds, self.log10_chains = log10_seconds, log10_chains


@pytest.fixture
def estimates(monkeypatch):
    """The estimate of every large cell replaced by one given by hand; the calls are recorded."""
    from synth.synthesis import estimate as module

    calls, given = [], {}

    def fake(query, *, work, budget, plain=False):
        if plain:  # (the plain path's first pass refuses nothing here: the compiled path's sizing is given by hand)
            return None
        calls.append((query.links, work, budget))
        return given.get(query.links)

    monkeypatch.setattr(module, "estimate", fake)
    return given, calls


LARGE = 'dof = 1\nlinks = "14..16"\nv = "0..1"'  # K = 6 with multiple joints and K = 7: both sized


def test_a_grid_of_small_cells_is_not_sized(estimates):
    given, calls = estimates
    assert size_grid(parse_grid('dof = 1\nlinks = "4..14"'), processes=2, db="a.sqlite") is None
    assert calls == []  # K ≤ 6 without multiple joints: every cell is small


def test_a_long_grid_is_said_with_its_sums(estimates, tmp_path):
    given, calls = estimates
    given.update({14: _Estimate(4.5, 8.0), 16: _Estimate(4.5, 8.0)})
    note = size_grid(parse_grid(LARGE), processes=2, db=str(tmp_path / "a.sqlite"))
    # 2 × 10^4.5 s = 63 246 s on 2 workers: 31 623 s = 8.8 h; 2e8 mechanisms × 210 bytes = 42 GB
    assert note == ("a long grid: its 2 large cells hold about 2e+08 mechanisms, 8.8 h on 2 workers and 42 GB in "
                    "the atlas (extrapolated from exact runs at smaller sizes)")
    assert calls == [(16, "mechanisms", 0.6), (14, "mechanisms", 0.6)]  # the largest first, the budget shared
    given.clear()
    given[16] = _Estimate(4.5, 8.0)
    note = size_grid(parse_grid(LARGE.replace('"0..1"', "0")), processes=1, db=str(tmp_path / "a.sqlite"),
                     scheduler=True)
    assert note == ("a long grid: its cell W=1 n=16 v=0..0 rigid=0 frac=1 planar=0 holds about 1e+08 mechanisms, "
                    "8.8 h on the scheduler's workers (one core shown) and 21 GB in the atlas (extrapolated from exact "
                    "runs at smaller sizes)")
    assert calls[-1] == (16, "mechanisms", 1.2)


def test_the_limits_of_a_day_and_ten_minutes(estimates, tmp_path):
    given, _ = estimates
    grid, db = parse_grid('dof = 1\nlinks = 16'), str(tmp_path / "a.sqlite")
    day, ten_minutes = math.log10(86400), math.log10(600)
    given[16] = _Estimate(day - 1e-6, 3.0)
    assert size_grid(grid, processes=1, db=db).startswith("a long grid: its cell W=1 n=16")
    given[16] = _Estimate(day + 1e-6, 3.0)
    with pytest.raises(QueryTooLarge) as e:
        size_grid(grid, processes=1, db=db)
    assert str(e.value) == ("this grid is too large to run unasked: its cell W=1 n=16 v=0..0 rigid=0 frac=1 planar=0 "
                            "holds about 1 000 mechanisms, 24.0 h on 1 worker and 0 GB in the atlas (extrapolated "
                            "from exact runs at smaller sizes); give force=True to run it anyway (it can be stopped "
                            "and resumed)")
    assert size_grid(grid, processes=2, db=db).startswith("a long grid")  # half a day on two
    given[16] = _Estimate(ten_minutes + 1e-6, 3.0)
    assert size_grid(grid, processes=1, db=db) == (
        "a long grid: its cell W=1 n=16 v=0..0 rigid=0 frac=1 planar=0 holds about 1 000 mechanisms, 10 min on 1 "
        "worker and 0 GB in the atlas (extrapolated from exact runs at smaller sizes)")
    given[16] = _Estimate(ten_minutes - 1e-6, 3.0)
    assert size_grid(grid, processes=1, db=db) is None


def test_a_grid_that_does_not_fit_on_the_disk(estimates, tmp_path, monkeypatch):
    import shutil

    given, _ = estimates
    given[16] = _Estimate(2.0, 8.0)  # 100 s, 1e8 mechanisms: 21 GB
    grid = parse_grid('dof = 1\nlinks = 16')
    monkeypatch.setattr(shutil, "disk_usage", lambda folder: shutil._ntuple_diskusage(100e9, 99e9, 20.9e9))
    with pytest.raises(QueryTooLarge) as e:
        size_grid(grid, processes=1, db=str(tmp_path / "a.sqlite"))
    assert str(e.value) == (f"this grid does not fit on the disk: its cell W=1 n=16 v=0..0 rigid=0 frac=1 planar=0 "
                            f"holds about 1e+08 mechanisms, 100 s on 1 worker and 21 GB in the atlas (extrapolated "
                            f"from exact runs at smaller sizes), and {tmp_path} has 20.9 GB free; give force=True to "
                            f"run it anyway")
    monkeypatch.setattr(shutil, "disk_usage", lambda folder: shutil._ntuple_diskusage(100e9, 79e9, 21.1e9))
    assert size_grid(grid, processes=1, db=str(tmp_path / "a.sqlite")) is None
    monkeypatch.setattr(shutil, "disk_usage", lambda folder: shutil._ntuple_diskusage(1, 1, 0))
    with pytest.raises(QueryTooLarge, match="has 0.0 GB free"):
        size_grid(grid, processes=1, db=str(tmp_path / "a.sqlite"))
    # a folder that does not exist yet is not measured (the run refuses it later)
    assert size_grid(grid, processes=1, db=str(tmp_path / "none" / "a.sqlite")) is None


def test_a_cell_that_cannot_be_estimated_is_refused(estimates):
    with pytest.raises(QueryTooLarge) as e:
        size_grid(parse_grid('dof = 1\nlinks = 16'), processes=2, db="a.sqlite")
    assert str(e.value) == ("the grid's cell W=1 n=16 v=0..0 rigid=0 frac=1 planar=0 is large and its size cannot be "
                            "estimated; give force=True to run it anyway")


def test_sums_of_logarithms_and_powers_by_hand():
    assert _log_sum(2.0, 2.0) == pytest.approx(2 + math.log10(2), abs=1e-15)
    assert _log_sum(3.0, 1.0) == pytest.approx(math.log10(1010), abs=1e-14)
    assert _log_sum(1.0, 3.0) == pytest.approx(math.log10(1010), abs=1e-14)
    assert _log_sum(-math.inf, 3.0) == 3.0 and _log_sum(-math.inf, -math.inf) == -math.inf
    assert _log_sum(400.0, 400.0) == pytest.approx(400 + math.log10(2))  # 10^400 is no float
    assert _power(2.0) == pytest.approx(100.0) and _power(307.9) == pytest.approx(10 ** 307.9)
    assert _power(308.0) == math.inf and _power(500.0) == math.inf


def test_the_run_says_where_it_ran(tmp_path, monkeypatch):
    monkeypatch.setattr(runs.os, "cpu_count", lambda: 5)
    grid = parse_grid("dof = 1\nlinks = 4")
    assert run_grid(grid, tmp_path / "a.sqlite").executor == "local 5"  # every core by default
    assert run_grid(grid, tmp_path / "b.sqlite", workers=3).executor == "local 3"
    assert sql(tmp_path / "b.sqlite", "SELECT executor FROM runs") == [("local 3",)]
    monkeypatch.setattr(runs.os, "cpu_count", lambda: None)
    assert run_grid(grid, tmp_path / "c.sqlite").executor == "local 1"


class _Terminal:
    """A stderr that says it is a terminal (tqdm draws no bar on anything else) and keeps what is written."""

    def __init__(self):
        self.text = ""

    def write(self, text):
        self.text += text

    def flush(self):
        pass

    def isatty(self):
        return True


def test_the_progress_bar_counts_units_and_chains(tmp_path, monkeypatch, plain_bar):
    import sys

    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    run_grid(parse_grid('name = "tiny"\ndof = 1\nlinks = "4..6"'), tmp_path / "a.sqlite", workers=1, progress=True)
    last = terminal.text.replace("\r", "\n").strip().splitlines()[-1]
    assert last.startswith("tiny: 100%") and "2/2 [" in last and "unit" in last and "chains=3" in last


def test_a_grid_of_more_than_any_float_is_said_in_powers_of_ten(estimates):
    given, _ = estimates
    given[16] = _Estimate(400.0, 390.0)
    with pytest.raises(QueryTooLarge) as e:
        size_grid(parse_grid("dof = 1\nlinks = 16"), processes=1, db="a.sqlite")
    # 10^400 s / (365.25 × 86 400 s a year) = 10^392.50 years; 10^390 × 210 bytes = 2.1e+383 GB
    assert ("holds about 1e+390 mechanisms, 3.2e+392 years on 1 worker and 2.1e+383 GB in the atlas"
            in str(e.value))


def test_a_disk_without_a_free_byte_takes_no_grid(estimates, tmp_path, monkeypatch):
    import shutil

    given, _ = estimates
    given[16] = _Estimate(2.0, math.log10(1.5 / 210))  # an atlas of 1.5 bytes
    monkeypatch.setattr(shutil, "disk_usage", lambda folder: shutil._ntuple_diskusage(100, 100, 0))
    with pytest.raises(QueryTooLarge, match="has 0.0 GB free"):
        size_grid(parse_grid("dof = 1\nlinks = 16"), processes=1, db=str(tmp_path / "a.sqlite"))


@pytest.fixture
def plain_bar(monkeypatch):
    """tqdm with a plain thread lock and no monitor thread: its default also makes a multiprocessing lock, which
    hangs in a process forked from a threaded one (mutmut runs each mutant so)."""
    import threading

    import tqdm

    monkeypatch.setattr(tqdm.tqdm, "_lock", threading.RLock(), raising=False)
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", 0)
