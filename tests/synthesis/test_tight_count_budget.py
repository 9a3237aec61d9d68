"""The memory of a count's programme over the strings (``tight_count``, issue 41 "memory ≤ 2 GiB"): its
layers of states held within ``LAYER_BYTES``, a layer that would pass it made in buckets by a hash of the
state, the buckets the budget cannot hold in memory in unlinked files — the same counts, unit by unit and by
code, whatever the budget.

With a budget of one byte every bucket is as small as it can be (some successors of one state) and every one
goes to a file.  Faults put by hand into the kernel (a copy of the tree each; numba: not patchable from a test),
each caught by the eight tests named ``listings``, ``stops``, ``within`` and ``no_file`` (benchmarks/PROFILE.md
section 38):

* the half of a bucket put aside when it is cut dropped: 7 of the 8 fail (all but the stop's);
* each pass over a layer of several buckets skipping its last: 7 of the 8 fail;
* no stop before a state whose successors might pass the cap:
  ``test_a_layer_stops_before_a_state_whose_successors_might_pass_the_cap`` fails.
"""

from __future__ import annotations

import numpy as np
import pytest

import synth
from synth.synthesis import _stage_b_kernel, stage_a, stage_b

from .test_count_search import QUERIES, _ids


@pytest.fixture
def kernel_everywhere(monkeypatch):
    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})


def _unit_counts(query, budget, monkeypatch):
    """Per unit: the first count (Burnside over the bundle group) and the second (in reverse) at ``budget``."""
    monkeypatch.setattr(_stage_b_kernel, "LAYER_BYTES", budget)
    out = []
    for u in synth.plan_units(**query, workers=1):
        if u.contracted is not None and stage_b._kernel_applies(u.code, u.contracted, u.conventions):
            args = (u.code, u.contracted, u.conventions)
            out.append((u.key, stage_b._kernel_placements(*args, None, listing=False)[0],
                        stage_b.count_reversed(*args)))
    return out


@pytest.mark.parametrize("query", QUERIES, ids=_ids)
def test_a_byte_of_budget_counts_every_unit_the_same(query, kernel_everywhere, monkeypatch):
    """Every unit of the 13 queries of the count's own tests: the same counts, both methods, with the
    layers a few states at a time as with the whole layers."""
    whole = _unit_counts(query, _stage_b_kernel.LAYER_BYTES, monkeypatch)
    assert whole and any(first > 1 for _, first, _ in whole)
    assert _unit_counts(query, 1, monkeypatch) == whole


def _one_bundle_layer(cap, key_mask=0, key=0):
    """``_tight_layer`` on a layer of one state, one bundle of deficits 0 … 4 between two vertices (k = 3, l = 0:
    each t a state of its own)."""
    k, l, W, P, T = 3, 0, 4, 0, 4
    states, totals, ways_in = np.zeros((1, W), dtype=np.int16), np.zeros(1, dtype=np.int64), np.ones(1, dtype=np.int64)
    ways = np.ones((T + 1, 1, 1), dtype=np.int64)  # (no excess: x_most = 0; one class of sets)
    opens, open_k = np.array([0, 1], dtype=np.int64), np.array([k, k], dtype=np.int64)
    open_link = np.zeros(2, dtype=np.int64)
    shut = np.array([-1, -1], dtype=np.int64)  # (both vertices stay open: no set is merged)
    out = np.zeros((0, W), dtype=np.int16), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return _stage_b_kernel._tight_layer(states, totals, ways_in, 0, 1, *out, 0, np.full(128, -1, dtype=np.int64), cap,
                                        key_mask, key, opens, open_k, open_link, 3, shut, 2, ways, T, -1, -1, False, 2 * k - l,
                                        2 * k - l, l, 0, W, P, np.zeros(W + P, dtype=np.int64))


def test_a_layer_stops_before_a_state_whose_successors_might_pass_the_cap():
    """Five successors where the cap allows five; none, and a stop at the state, where it allows four."""
    m, stop, new_states, new_totals, new_ways, _ = _one_bundle_layer(5)
    assert (m, stop) == (5, 1) and new_totals[:m].tolist() == [0, 1, 2, 3, 4] and new_ways[:m].tolist() == [1] * 5
    assert new_states[:m, 3].tolist() == [-6, -5, -4, -3, -2]  # the set of both: −2k + t
    assert _one_bundle_layer(4)[:2] == (0, 0)


def test_the_buckets_of_a_layer_share_out_its_states():
    """The successors kept by each of the four buckets of two hash bits: the five states, each in one bucket, not
    all in one."""
    kept = []
    for key in range(4):
        m, stop, _, new_totals, _, _ = _one_bundle_layer(5, 3, key)
        assert stop == 1
        kept.append(new_totals[:m].tolist())
    assert sorted(t for bucket in kept for t in bucket) == [0, 1, 2, 3, 4]
    assert max(len(bucket) for bucket in kept) < 5


def test_the_hash_table_takes_no_more_than_the_budget_counts_a_state():
    """The budget counts 64 bytes of hash table a state (``_row_bytes``): a table made for m states has at most
    8 slots of 8 bytes a state (128 at least), and at least 4, so the layer may grow to twice m before the next."""
    W, P = 4, 0
    share = _stage_b_kernel._row_bytes(W, P) - (2 * (W + P) + 16)
    for m in (16, 17, 31, 32, 33, 1000, 1025, 4096, 5000):
        states, totals = np.zeros((m, W + P), dtype=np.int16), np.arange(m, dtype=np.int64)
        table = _stage_b_kernel._rehash(states, totals, m, W, W, P)
        assert 4 * m <= len(table) <= max(128, 8 * m) and table.itemsize * len(table) <= share * m
        assert sorted(table[table >= 0].tolist()) == list(range(m))


def test_a_count_by_code_is_the_same_at_64_kib(monkeypatch):
    """The 17-link chains of h = 4 (the listing checked these by code, benchmarks/RECORDS.md): 156 275, the same
    codes counted the same with the layers whole and in buckets of some 20 KiB (a byte would make a bucket of
    each state's successors, and as many passes over the layer: its square)."""
    whole = synth.count_chains(1, 17, h=4, workers=1)
    splits, split = [], _stage_b_kernel._tight_split
    monkeypatch.setattr(_stage_b_kernel, "_tight_split", lambda *args: splits.append(1) or split(*args))
    monkeypatch.setattr(_stage_b_kernel, "LAYER_BYTES", 64 * 2**10)
    parts = synth.count_chains(1, 17, h=4, workers=1)
    assert whole.count == parts.count == 156_275 and splits
    assert parts.by_code == whole.by_code


# small queries whose layers pass a budget of a few kilobytes (h = 4…6; W = 2, with excess; multiple joints, three
# values a set), and the budget
SPLIT_QUERIES = [(dict(dof=1, links=14, h=5), 1), (dict(dof=1, links=17, h=6), 1), (dict(dof=1, links=14, h=4), 16 * 2**10),
                 (dict(dof=1, links=17, h=6), 16 * 2**10), (dict(dof=2, links=13), 16 * 2**10),
                 (dict(dof=1, links=10, v=(1, 8)), 1), (dict(dof=2, links=11, v=(1, 9)), 1)]


@pytest.mark.parametrize("query, budget", SPLIT_QUERIES, ids=lambda x: _ids(x) if isinstance(x, dict) else f"{x} B")
def test_counts_by_code_at_small_budgets_are_the_listings(query, budget, kernel_everywhere, monkeypatch):
    """Counts by code with the layers in buckets (one byte: every bucket in a file; 16 KiB: some in memory, some
    not) equal the count with whole layers and the listing's chains (built and told apart by nauty)."""
    whole = synth.count_chains(**query, workers=1).by_code
    made = []
    spill = _stage_b_kernel._spill_file
    monkeypatch.setattr(_stage_b_kernel, "_spill_file", lambda: made.append(1) or spill())
    monkeypatch.setattr(_stage_b_kernel, "LAYER_BYTES", budget)
    assert synth.count_chains(**query, workers=1).by_code == whole
    assert made  # (the buckets were written out)
    listed: dict = {}
    for chain in synth.type_synthesis(**query, workers=1):
        listed[str(chain.code)] = listed.get(str(chain.code), 0) + 1
    assert listed == whole


def test_no_file_is_left_after_a_count_or_its_interruption(tmp_path, kernel_everywhere, monkeypatch):
    """The files of the buckets are made in the temporary folder and are gone from it while the count runs, after
    it, and after a Ctrl-C in the middle of a layer (the files are unlinked as they are made)."""
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    monkeypatch.setattr(_stage_b_kernel, "LAYER_BYTES", 1)
    made = []
    spill = _stage_b_kernel._spill_file

    def layers_files():  # (other parts of a count keep folders of their own there)
        return list(tmp_path.rglob("mechsynth-layer*"))

    def spill_and_look():
        made.append(spill())
        assert not layers_files()
        return made[-1]

    monkeypatch.setattr(_stage_b_kernel, "_spill_file", spill_and_look)
    assert synth.count_chains(1, 14, h=5, workers=1).count == 116
    assert made and all(f.closed for f in made) and not layers_files()
    made.clear()
    layer, calls = _stage_b_kernel._tight_layer, []

    def interrupted(*args):
        calls.append(1)
        if len(calls) == 50:
            raise KeyboardInterrupt
        return layer(*args)

    monkeypatch.setattr(_stage_b_kernel, "_tight_layer", interrupted)
    with pytest.raises(KeyboardInterrupt):
        synth.count_chains(1, 14, h=5, workers=1)
    assert made and all(f.closed for f in made) and not layers_files()


def test_the_buckets_stay_within_the_budget(kernel_everywhere, monkeypatch):
    """At 64 KiB, on the 14-link chains of h = 4 (1 798, the listing's count): the buckets held in memory never pass a third of the budget, and
    no bucket holds more states than the third of the budget allows (the bucket being made, one read back)."""
    budget = 64 * 2**10
    monkeypatch.setattr(_stage_b_kernel, "LAYER_BYTES", budget)
    seen, split, put = [], _stage_b_kernel._tight_split, _stage_b_kernel._Buckets.put

    def put_and_look(self, states, totals, ways, n):
        bucket = put(self, states, totals, ways, n)
        seen.append((self.held, self.room, n * _stage_b_kernel._row_bytes(self.W, self.P)))
        return bucket

    def split_and_look(*args):  # (its first bucket is the layer handed over, made with the whole budget)
        seen.append(None)
        return split(*args)

    monkeypatch.setattr(_stage_b_kernel._Buckets, "put", put_and_look)
    monkeypatch.setattr(_stage_b_kernel, "_tight_split", split_and_look)
    assert synth.count_chains(1, 14, h=4, workers=1).count == 1_798
    starts = [i for i, x in enumerate(seen) if x is None]
    made = [x for i, x in enumerate(seen) if x is not None and i - 1 not in starts]
    assert len(starts) > 1 and len(made) > 10
    assert all(held <= room for held, room, _ in made) and max(size for _, _, size in made) <= budget // 3
