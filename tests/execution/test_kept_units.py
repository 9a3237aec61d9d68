"""A count's stage A kept beside its checkpoint: a resumed run reads a code's units back instead of
running stage A again; a truncated or foreign file is never used; nothing is left once the run ends.

A kill is played in-process (workers=1): the count is interrupted (KeyboardInterrupt, which the
checkpoint survives as it does Ctrl-C) after the first unit of a code of several units, and stage A
is watched by wrapping ``contracted_stream``.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from synth.execution.checkpoint import read_checkpoint
from synth.execution.spill import Kept, read_kept, write_kept
from synth.structure.query import ChainQuery
from synth.synthesis import type_synthesis as ts

QUERY = ChainQuery(1, 12)


def _interrupted_count(checkpoint, monkeypatch) -> str:
    """Count QUERY with ``checkpoint``, interrupted once the first unit of a code of three or more
    units is counted; return that code's name."""
    jobs = ts.plan_jobs(QUERY)
    sizes = [len(ts.job_units(job)) for job in jobs]
    middle = next(i for i, n in enumerate(sizes) if i and n >= 3)
    budget = sum(sizes[:middle]) + 1
    real = ts.count_unit

    def count_then_stop(unit, method="listing", stats=None):
        nonlocal budget
        if budget == 0:
            raise KeyboardInterrupt
        budget -= 1
        return real(unit, method, stats)

    with monkeypatch.context() as patch:
        patch.setattr(ts, "count_unit", count_then_stop)
        with pytest.raises(KeyboardInterrupt):
            ts.count_chains(QUERY, workers=1, checkpoint=checkpoint)
    return str(jobs[middle][0])


def _stage_a_runs(monkeypatch) -> list[str]:
    """The codes whose stage A runs from now on (in this process), in order."""
    runs, real = [], ts.contracted_stream

    def watched(code, conv):
        runs.append(str(code))
        return real(code, conv)

    monkeypatch.setattr(ts, "contracted_stream", watched)
    return runs


@pytest.fixture(scope="module")
def reference():
    return ts.count_chains(QUERY, workers=1)


def test_a_resumed_count_reads_a_code_s_units_back_instead_of_running_stage_a(tmp_path, monkeypatch, reference):
    checkpoint = tmp_path / "c.sqlite"
    code = _interrupted_count(checkpoint, monkeypatch)
    expand = ts._StreamedUnits(str(tmp_path / "c.sqlite.units"), 1)
    # the codes complete before the kill have had their files removed: only the code begun is kept
    assert [p.name for p in (tmp_path / "c.sqlite.units").iterdir()] == [os.path.basename(expand.path(code))]
    state = read_checkpoint(checkpoint)
    assert code in state.partial and code not in state.complete  # its first unit committed, not the code
    runs = _stage_a_runs(monkeypatch)
    resumed = ts.count_chains(QUERY, workers=1, checkpoint=checkpoint)
    assert resumed == reference
    assert code not in runs  # read back from its file
    assert runs and all(name not in state.complete for name in runs)  # the codes not begun did run
    assert not (tmp_path / "c.sqlite.units").exists()  # every file, and the folder, removed


@pytest.mark.parametrize("spoil", ["truncated", "another plan", "another code", "another engine",
                                   "not units", "empty"])
def test_a_spoilt_or_foreign_file_is_not_used(tmp_path, monkeypatch, reference, spoil):
    checkpoint = tmp_path / "c.sqlite"
    code = _interrupted_count(checkpoint, monkeypatch)
    [path] = (tmp_path / "c.sqlite.units").iterdir()
    data = path.read_bytes()
    job = next(job for job in ts.plan_jobs(QUERY) if str(job[0]) == code)
    if spoil == "truncated":
        path.write_bytes(data[:-7])
    elif spoil == "another plan":
        write_kept(ts.job_units(job), str(path), chunk=4, label=f"another plan|{code}|{job[1]!r}|{ts._UNIT_LAYOUT}")
    elif spoil == "another code":  # the units of the next code of the same plan, under this code's name
        jobs = ts.plan_jobs(QUERY)
        other = jobs[jobs.index(job) + 1]
        expand = ts._StreamedUnits(str(tmp_path), 4, ts.count_identity(QUERY)[0])
        expand(other)
        os.replace(expand.path(other[0]), path)
    elif spoil == "another engine":  # this code's units, by an engine whose units had other fields
        with monkeypatch.context() as patch:
            patch.setattr(ts, "_UNIT_LAYOUT", ts._UNIT_LAYOUT.replace("certificate", "certificate slack"))
            ts._StreamedUnits(str(path.parent), 4, ts.count_identity(QUERY)[0])(job)
        assert len(list(path.parent.iterdir())) == 1 and path.read_bytes() != data  # (written in its place)
    elif spoil == "not units":
        path.write_bytes(b"SQLite format 3\0" + bytes(range(256)) * 4)
    else:
        path.write_bytes(b"")
    runs = _stage_a_runs(monkeypatch)
    assert ts.count_chains(QUERY, workers=1, checkpoint=checkpoint) == reference
    assert code in runs  # stage A ran again
    assert not (tmp_path / "c.sqlite.units").exists()


def test_a_resumed_count_on_a_pool_reads_the_file_in_its_workers(tmp_path, monkeypatch, reference):
    checkpoint = tmp_path / "c.sqlite"
    _interrupted_count(checkpoint, monkeypatch)
    monkeypatch.setattr(ts, "_INLINE_SECONDS", 0.0)  # every code's stage A in a worker
    assert ts.count_chains(QUERY, workers=2, checkpoint=checkpoint) == reference
    assert not (tmp_path / "c.sqlite.units").exists()


def test_without_a_checkpoint_no_folder_is_made(tmp_path, monkeypatch, reference):
    monkeypatch.chdir(tmp_path)
    assert ts.count_chains(QUERY, workers=1) == reference
    assert not list(tmp_path.iterdir())


def test_what_a_killed_run_was_writing_is_removed_and_a_file_in_the_folder_s_place_refused(tmp_path):
    folder = ts.kept_units_folder(tmp_path / "c.sqlite")
    (folder / "48000_0-abc.units.x1y2.part").write_bytes(b"half")
    (folder / "notes.txt").write_text("mine")
    ts.kept_units_folder(tmp_path / "c.sqlite")
    assert sorted(p.name for p in folder.iterdir()) == ["notes.txt"]
    ts._remove_kept_folder(folder)  # a folder holding something else is left, with that thing
    assert [p.name for p in folder.iterdir()] == ["notes.txt"]
    (tmp_path / "d.sqlite.units").write_text("a file")
    out = subprocess.run([sys.executable, "-m", "mechsynth", "chains", "--dof", "1", "--links", "8", "--count",
                          "--checkpoint", str(tmp_path / "d.sqlite")], capture_output=True, text=True)
    assert out.returncode == 2 and out.stdout == "" and out.stderr.count("\n") == 1
    assert "keeps its units in the folder" in out.stderr and "Traceback" not in out.stderr
    assert (tmp_path / "d.sqlite.units").read_text() == "a file" and not (tmp_path / "d.sqlite").exists()


# ------------------------------------------------------------------ the file itself
@pytest.mark.parametrize("n, chunk", [(0, 3), (1, 3), (3, 3), (10, 3), (10, 1)])
def test_kept_items_are_read_back_whole_in_order(tmp_path, n, chunk):
    path = str(tmp_path / "u.units")
    written = write_kept(iter(range(n)), path, chunk=chunk, label="p|c")
    again = read_kept(path, "p|c")
    assert isinstance(again, Kept) and len(again) == len(written) == n
    assert list(again) == list(again) == list(range(n))
    again.remove()  # the count removes it, not its reader
    assert os.listdir(tmp_path) == ["u.units"]


def test_an_interrupted_write_leaves_nothing(tmp_path):
    def items():
        yield from range(5)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_kept(items(), str(tmp_path / "u.units"), chunk=2, label="p|c")
    assert not list(tmp_path.iterdir())


def test_a_file_cut_anywhere_or_of_another_label_is_not_read(tmp_path):
    path = tmp_path / "u.units"
    write_kept(iter(range(10)), str(path), chunk=3, label="plan|code")
    data = path.read_bytes()
    assert read_kept(str(path), "plan|other") is None and read_kept(str(path), "plan|cod") is None
    for cut in range(len(data)):
        path.write_bytes(data[:cut])
        assert read_kept(str(path), "plan|code") is None, cut
    assert read_kept(str(tmp_path / "missing.units"), "plan|code") is None
