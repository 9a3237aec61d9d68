"""The memory of a count's programme over the strings (``tight_count``, issue 41 "memory ≤ 2 GiB"): its
layers of states held within ``LAYER_BYTES``, a layer taken a part at a time where the next one would pass
it — the same counts, unit by unit and by code, whatever the budget.

With a budget of one byte every part is as small as it can be (the successors of one state), so every
layer of more than some tens of states is split.  Faults put by hand into the kernel (numba: not patchable
from a test), each caught:

* the second half of a split part dropped (``level_next[i]`` set to the end of the layer after a split):
  9 of the 13 queries of ``test_a_byte_of_budget_counts_every_unit_the_same`` fail (counts that differ, or
  Burnside's sum no multiple of the group), and the count by code at 17 links;
* no part refused (the cap on a part's successors never reached, the arrays grown as before):
  ``test_a_part_with_too_many_successors_is_refused`` fails (the counts cannot show it: only the memory changes).
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


def test_a_part_with_too_many_successors_is_refused():
    """``_tight_layer`` on a layer of one state, one bundle of deficits 0 … 4 between two vertices (k = 3,
    l = 0: each t a state of its own): five states where the cap allows five, −1 where it allows four."""
    k, l, W, P, T = 3, 0, 4, 0, 4
    states, totals, ways_in = np.zeros((1, W), dtype=np.int16), np.zeros(1, dtype=np.int64), np.ones(1, dtype=np.int64)
    ways = np.ones((T + 1, 1), dtype=np.int64)  # (no excess: x_most = 0)
    opens, open_k = np.array([0, 1], dtype=np.int64), np.array([k, k], dtype=np.int64)
    shut = np.array([-1, -1], dtype=np.int64)  # (both vertices stay open: no set is merged)

    def layer(cap):
        out = np.zeros((0, W), dtype=np.int16), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        return _stage_b_kernel._tight_layer(states.copy(), totals, ways_in, 0, 1, *out, cap, opens, open_k, 3, shut, 2,
                                            ways, T, -1, -1, False, 2 * k - l, 2 * k - l, l, 0, W, P,
                                            np.zeros(W + P, dtype=np.int64))

    m, new_states, new_totals, new_ways = layer(5)
    assert m == 5 and new_totals[:m].tolist() == [0, 1, 2, 3, 4] and new_ways[:m].tolist() == [1] * 5
    assert new_states[:m, 3].tolist() == [-6, -5, -4, -3, -2]  # the set of both: −2k + t
    assert layer(4)[0] == -1


def test_a_count_by_code_is_the_same_at_a_byte_of_budget(monkeypatch):
    """The 17-link chains of h = 4 (the listing checked these by code, benchmarks/RECORDS.md): 156 275, the
    same codes counted the same with the layers whole and a few states at a time."""
    whole = synth.count_chains(1, 17, h=4, workers=1)
    monkeypatch.setattr(_stage_b_kernel, "LAYER_BYTES", 1)
    parts = synth.count_chains(1, 17, h=4, workers=1)
    assert whole.count == parts.count == 156_275
    assert parts.by_code == whole.by_code
