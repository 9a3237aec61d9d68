"""Solver results kept between runs (synth.execution.memo): a query answered from the store gives
the same chains, by code and in the same order, as a cold run and as a run with the store off;
a damaged store is read around; a folder that cannot be written is not used; an edit of the
engine's source is a new store; and a query asked again loads no solver."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from synth.execution import memo

QUERIES = [  # (W, links, options): stage A's plain search, its CP-SAT model (codes of 9 branch vertices and
    # more: h = 2 with multiple joints) and the kernel's (the codes themselves are listed without a solver)
    (1, 8, {"h": 2, "v": "0..3"}), (1, 10, {}), (1, 10, {"v": "0..3"}), (3, 8, {"n1": "0..3", "v": "0..2"}),
    (1, 8, {"h": 2}), (1, 8, {"h": 4}), (1, 6, {"prismatic": "0..6"}), (0, 9, {}),
]

SCRIPT = """
import json, sys, synth
out = []
for dof, links, options in json.loads(sys.argv[1]):
    out.append([c.certificate for c in synth.type_synthesis(dof, links, workers=1, **options)])
print(json.dumps(out))
print(json.dumps(sorted(m for m in sys.modules if m.startswith("ortools"))))
"""


def _run(store, queries=QUERIES):
    env = dict(os.environ, MECHSYNTH_CACHE=str(store))
    out = subprocess.run([sys.executable, "-c", SCRIPT, json.dumps(queries)], env=env, capture_output=True,
                         text=True, check=True, timeout=600)
    chains, modules = out.stdout.splitlines()
    return json.loads(chains), json.loads(modules)


def test_a_warm_run_lists_the_chains_of_a_cold_run_and_of_no_store(tmp_path):
    cold, cold_modules = _run(tmp_path)
    warm, warm_modules = _run(tmp_path)
    off, _ = _run("off")
    assert cold == warm == off
    assert all(cold) and sum(map(len, cold)) > 3000
    assert "ortools.sat.python.cp_model" in cold_modules and warm_modules == []  # no solver the second time
    entries = list(tmp_path.rglob("*.json"))
    assert {p.parent.name for p in entries} == {"stage-a"}  # stage A's models: the codes came without one


def test_a_damaged_store_is_read_around_and_mended(tmp_path):
    cold, _ = _run(tmp_path, QUERIES[:2])
    entries = sorted(tmp_path.rglob("*.json"))
    assert len(entries) > 5
    entries[0].write_text("{not json")
    entries[1].write_text(json.dumps({"key": "another problem", "value": [[[4], 0, None, 0]]}))
    entries[2].write_text(json.dumps({"key": json.loads(entries[3].read_text())["key"] + "x", "value": 7}))
    again, _ = _run(tmp_path, QUERIES[:2])
    assert again == cold
    assert all(json.loads(p.read_text())["key"] for p in entries)  # rewritten whole


def test_a_folder_that_cannot_be_written_is_not_used(tmp_path):
    blocked = tmp_path / "file"
    blocked.write_text("")  # a file where the folder would be
    chains, _ = _run(blocked / "store", QUERIES[:1])
    assert chains == _run("off", QUERIES[:1])[0]
    assert blocked.read_text() == ""


def test_an_edit_of_the_engine_is_a_new_store(tmp_path, monkeypatch):
    engine = tmp_path / "synth"
    for folder in memo._SOURCES:
        (engine / folder).mkdir(parents=True)
        for path in (Path(memo.__file__).parents[1] / folder).glob("*.py"):
            (engine / folder / path.name).write_bytes(path.read_bytes())
    monkeypatch.setattr(memo, "_ENGINE", engine)
    before = memo._fingerprint()
    with open(engine / "synthesis" / "stage_a.py", "a") as f:
        f.write("\n# an edit\n")
    assert memo._fingerprint() != before


@pytest.mark.parametrize("setting", ["off", "OFF", "0", ""])
def test_the_store_is_turned_off(setting, monkeypatch):
    monkeypatch.setenv("MECHSYNTH_CACHE", setting)
    memo._store.cache_clear()
    try:
        assert memo.cache_folder() is None
        calls = []
        for _ in range(2):
            memo.remembered("test", "off", lambda: calls.append(1) or 1)
        assert len(calls) == 2
    finally:
        memo._store.cache_clear()


# ------------------------------------------------------------------ counts kept between runs
COUNT_SCRIPT = """
import json, sys
from mechsynth import cli
status = cli.main(sys.argv[1:])
print(json.dumps([status, sorted(m for m in ("numpy", "multiprocessing", "ortools", "importlib.metadata", "tomllib")
                                  if m in sys.modules)]),
      file=sys.stderr)
"""


def _count_cli(store, *args):
    env = dict(os.environ, MECHSYNTH_CACHE=str(store))
    out = subprocess.run([sys.executable, "-c", COUNT_SCRIPT, *args], env=env, capture_output=True, text=True,
                         timeout=600, cwd=Path(__file__).resolve().parents[2])
    status, modules = json.loads(out.stderr.strip().splitlines()[-1])
    return out.stdout, status, modules


def test_a_count_asked_again_is_read_from_the_store_without_numpy_or_a_pool(tmp_path):
    """The 12-link count of the issue: the second run reads each code's count, runs no unit, loads
    neither numpy (its sizing is coarse enough in integers) nor multiprocessing nor importlib.metadata
    (the store's fingerprint reads nauty's version from pynauty's own file) nor tomllib, and prints the same."""
    query = ["chains", "--dof", "1", "--links", "12", "--count", "--workers", "2"]
    first, status, cold_modules = _count_cli(tmp_path, *query)
    again, status_again, warm_modules = _count_cli(tmp_path, *query)
    off, _, _ = _count_cli("off", *query)
    assert first == again == off and status == status_again == 0
    assert json.loads(first)["count"] == 6856
    assert "numpy" in cold_modules and warm_modules == []
    assert len(list(tmp_path.rglob("counts/*.json"))) == 15  # one entry per code


@pytest.fixture
def own_store(monkeypatch, tmp_path):
    """A store of this test's own (the session's may hold counts other tests kept)."""
    monkeypatch.setenv("MECHSYNTH_CACHE", str(tmp_path / "store"))
    memo._store.cache_clear()
    yield tmp_path
    memo._store.cache_clear()


def test_stored_codes_are_read_and_the_others_counted(monkeypatch, own_store):
    from synth.errors import InvalidOption
    from synth.synthesis import type_synthesis as ts

    tmp_path = own_store

    fresh = ts.count_chains(1, 8, v="0..2", workers=1)
    assert ts.count_chains(1, 8, workers=1, remember=True).count == 16  # stores 440/0, 521/0 and 602/0
    ran = []
    real = ts.count_unit
    monkeypatch.setattr(ts, "count_unit", lambda unit: ran.append(str(unit.code)) or real(unit))
    assert ts.count_chains(1, 8, v="0..2", workers=1, remember=True) == fresh
    assert ran and not {"440/0", "521/0", "602/0"} & set(ran)
    ran.clear()
    assert ts.count_chains(1, 8, v="0..2", workers=1, remember=True) == fresh and ran == []  # all stored now
    with pytest.raises(InvalidOption, match="kept between runs only"):
        ts.count_chains(1, 8, workers=1, remember=True, checkpoint=tmp_path / "unused.sqlite")
    assert not (tmp_path / "unused.sqlite").exists()
