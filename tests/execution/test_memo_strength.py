"""The store of solver results in one process: where it is, what makes it stale, what an entry
holds, and every way an entry or a folder can fail — each read around, nothing raised.
"""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import pytest

from synth.execution import memo


@pytest.fixture
def store(tmp_path, monkeypatch):
    """A fresh store under tmp_path (the process's own is left alone)."""
    monkeypatch.setenv("MECHSYNTH_CACHE", str(tmp_path / "store"))
    memo._store.cache_clear()
    yield memo.cache_folder()
    memo._store.cache_clear()


def test_an_entry_is_a_json_file_named_by_the_key_s_digest(store):
    memo.keep("codes", "W=1 K=2", ["42/0", "51/1"])
    entry = store / "codes" / f"{hashlib.sha1(b'W=1 K=2').hexdigest()}.json"
    assert json.loads(entry.read_text()) == {"key": "W=1 K=2", "value": ["42/0", "51/1"]}
    assert sorted(p.name for p in entry.parent.iterdir()) == [entry.name]  # no temporary file left
    assert memo.is_remembered("codes", "W=1 K=2") and not memo.is_remembered("codes", "W=1 K=3")
    assert not memo.is_remembered("graphs", "W=1 K=2")  # each kind its own folder
    assert memo.recall("codes", "W=1 K=2") == ["42/0", "51/1"]


def test_values_are_encoded_and_decoded(store):
    memo.keep("pairs", "k", {(1, 2), (3, 4)}, encode=sorted)
    assert json.loads(next((store / "pairs").iterdir()).read_text())["value"] == [[1, 2], [3, 4]]
    assert memo.recall("pairs", "k", decode=lambda v: {tuple(x) for x in v}) == {(1, 2), (3, 4)}


def test_a_value_is_computed_once_then_read(store):
    calls = []

    def compute():
        calls.append(1)
        return {"n": 3}

    assert memo.remembered("x", "k", compute, encode=lambda v: [v["n"]], decode=lambda v: {"n": v[0]}) == {"n": 3}
    assert memo.remembered("x", "k", compute, encode=lambda v: [v["n"]], decode=lambda v: {"n": v[0]}) == {"n": 3}
    assert len(calls) == 1
    assert json.loads(next((store / "x").iterdir()).read_text()) == {"key": "k", "value": [3]}


@pytest.mark.parametrize("text", ["not json", '{"value": 1}', '{"key": "other", "value": 1}', "[1, 2]", '"k"', ""])
def test_an_entry_that_cannot_be_read_or_holds_another_key_is_computed_again_and_mended(store, text):
    entry = store / "x" / f"{hashlib.sha1(b'k').hexdigest()}.json"
    entry.parent.mkdir(parents=True)
    entry.write_text(text)
    assert memo.recall("x", "k") is None
    assert not memo.is_remembered("x", "other")
    assert memo.remembered("x", "k", lambda: 7) == 7
    assert json.loads(entry.read_text()) == {"key": "k", "value": 7}


def test_a_stored_none_is_computed_again(store):
    memo.keep("x", "k", None)
    assert memo.remembered("x", "k", lambda: 5) == 5


@pytest.mark.parametrize("setting", ["off", "OFF", " Off ", "0", "no", "false", "False", ""])
def test_the_store_is_off(setting, monkeypatch):
    monkeypatch.setenv("MECHSYNTH_CACHE", setting)
    memo._store.cache_clear()
    try:
        assert memo.cache_folder() is None
        memo.keep("x", "k", 1)  # nothing stored, nothing raised
        assert memo.recall("x", "k") is None and not memo.is_remembered("x", "k")
        calls = []
        assert memo.remembered("x", "k", lambda: calls.append(1) or 2) == 2
        assert memo.remembered("x", "k", lambda: calls.append(1) or 2) == 2
        assert len(calls) == 2
    finally:
        memo._store.cache_clear()


def test_the_store_s_folder_follows_the_environment(tmp_path, monkeypatch):
    monkeypatch.delenv("MECHSYNTH_CACHE")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    memo._store.cache_clear()
    try:
        folder = memo.cache_folder()
        assert folder.parent == tmp_path / "xdg" / "mechsynth"
        assert folder.name == f"engine-{memo._fingerprint()}"
        monkeypatch.delenv("XDG_CACHE_HOME")
        monkeypatch.setenv("HOME", str(tmp_path / "home"))
        memo._store.cache_clear()
        assert memo.cache_folder().parent == tmp_path / "home" / ".cache" / "mechsynth"
        monkeypatch.setenv("XDG_CACHE_HOME", "")  # empty: as if unset
        memo._store.cache_clear()
        assert memo.cache_folder().parent == tmp_path / "home" / ".cache" / "mechsynth"
    finally:
        memo._store.cache_clear()


@pytest.fixture
def engine(tmp_path, monkeypatch):
    """A copy of the modules the fingerprint reads (and one it does not), in place of the engine."""
    root = tmp_path / "synth"
    for folder in ("structure", "synthesis", "draw"):
        (root / folder).mkdir(parents=True)
        for path in sorted((memo._ENGINE / folder).glob("*.py"))[:3]:
            shutil.copy(path, root / folder / path.name)
    monkeypatch.setattr(memo, "_ENGINE", root)
    return root


def test_the_fingerprint_changes_with_the_engine_s_sources_only(engine, monkeypatch):
    first = memo._fingerprint()
    assert len(first) == 16 and int(first, 16) >= 0
    assert memo._fingerprint() == first
    draw = next((engine / "draw").glob("*.py"))
    draw.write_text(draw.read_text() + "\n# an edit of a drawing\n")
    assert memo._fingerprint() == first  # drawings make no stored result
    (engine / "synthesis" / "notes.txt").write_text("not a module")
    assert memo._fingerprint() == first
    seen = {first}
    for folder in ("structure", "synthesis"):
        module = next((engine / folder).glob("*.py"))
        module.write_text(module.read_text() + "\n# an edit\n")
        assert memo._fingerprint() not in seen
        seen.add(memo._fingerprint())
    module = next((engine / "synthesis").glob("*.py"))
    module.rename(module.with_name("renamed_" + module.name))  # the same bytes under another name
    assert memo._fingerprint() not in seen
    seen.add(memo._fingerprint())
    # the files are read in the order of their names, whatever order the folder lists them in
    listed = Path.glob
    monkeypatch.setattr(Path, "glob", lambda self, pattern: reversed(list(listed(self, pattern))))
    assert memo._fingerprint() == memo._fingerprint() in seen


def test_the_fingerprint_changes_with_nauty(engine, monkeypatch, tmp_path):
    import importlib.util

    first = memo._fingerprint()
    fake = tmp_path / "pynauty_init.py"
    fake.write_text("__version__ = 'another'\n")
    spec = importlib.util.spec_from_file_location("pynauty", fake)
    monkeypatch.setattr(importlib.util, "find_spec", lambda name: spec if name == "pynauty" else None)
    other = memo._fingerprint()
    assert other != first
    monkeypatch.setattr(importlib.util, "find_spec", lambda name: None)  # no nauty at all: still a fingerprint
    assert memo._fingerprint() not in (first, other)


def test_a_store_beneath_a_file_is_not_used(tmp_path, monkeypatch):
    (tmp_path / "file").write_text("in the way")
    monkeypatch.setenv("MECHSYNTH_CACHE", str(tmp_path / "file" / "store"))
    memo._store.cache_clear()
    try:
        memo.keep("x", "k", 1)  # the folder cannot be made: the value is used, not kept
        assert memo.recall("x", "k") is None
        assert memo.remembered("x", "k", lambda: 3) == 3
    finally:
        memo._store.cache_clear()


def test_an_entry_that_cannot_be_put_in_place_leaves_no_temporary_file(store, monkeypatch):
    def refuse(source, target):
        raise PermissionError("not allowed")

    monkeypatch.setattr(memo.os, "replace", refuse)
    memo.keep("x", "k", 1)
    assert list((store / "x").iterdir()) == []


def test_an_entry_is_written_beside_its_place_not_in_the_temporary_folder(store, monkeypatch, tmp_path):
    """The temporary file is made in the entry's own folder, so that the rename stays on one file system:
    with the system's temporary folder unusable (TMPDIR gone, or on another file system) entries are kept."""
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "no such folder"))
    memo.keep("x", "k", [1, 2])
    assert memo.recall("x", "k") == [1, 2]
    assert [p.name for p in (store / "x").iterdir()] == [f"{hashlib.sha1(b'k').hexdigest()}.json"]


def test_the_store_deleted_while_an_entry_is_written_is_no_error(store, monkeypatch):
    """Deleting the folder is safe at any time, also between an entry's temporary file and its rename:
    the value is used, not kept, and nothing is raised."""
    real = memo.os.replace

    def deleted_first(source, target):
        shutil.rmtree(store)
        real(source, target)  # FileNotFoundError: the temporary file went with the folder

    monkeypatch.setattr(memo.os, "replace", deleted_first)
    memo.keep("x", "k", 1)
    assert not store.exists()
    monkeypatch.undo()
    assert memo.remembered("x", "k", lambda: 4) == 4  # and the next value is kept in a folder made anew
    assert memo.recall("x", "k") == 4
