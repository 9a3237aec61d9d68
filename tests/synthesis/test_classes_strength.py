"""Heterogeneous queries' sizing and options, on estimates given by hand: every sentence of
:func:`size_note` in full, the day's limit at its exact value, and what reaches type synthesis.
"""

from __future__ import annotations

import math

import pytest

from synth.errors import QueryTooLarge, flag
from synth.synthesis import estimate as sizing
from synth.synthesis.classes import heterogeneous_synthesis, size_note, skeleton_query


def _found(chains, seconds, log10_chains=None):
    return sizing.Estimate(chains=chains, units=10, seconds=seconds, basis="exact counts at 8, 10, 12 links",
                           log10_chains=math.log10(chains) if log10_chains is None else log10_chains, log10_units=1,
                           log10_seconds=math.log10(seconds) if math.isfinite(seconds) else 2000.0)


@pytest.fixture
def given(monkeypatch):
    asked = []

    def give(found):
        monkeypatch.setattr(sizing, "estimate", lambda q, **kw: asked.append((q, kw)) or found)
        return asked

    return give


QUERY = skeleton_query(1, {3: 6, 5: 1})  # 18 links, seven loops: skeletons of W = 3 in h = 3


def test_a_query_of_more_than_a_day_is_refused_in_full(given):
    asked = given(_found(2.0e8, 1.0e5))
    with pytest.raises(QueryTooLarge) as refused:
        size_note(QUERY, processes=2)
    # 1e5 s / 2 + 2e8 · 0.006 s = 1 250 000 s = 14.5 days
    assert refused.value.text(flag) == (
        "this heterogeneous query (18 links) is too large to run unasked: about 2e+08 skeletons of W = 3 in class "
        "h = 3, each given its bases, 14.5 days on 2 workers (extrapolated from the exact counts at 8, 10, 12 links); "
        "give --force to run it anyway, or narrow it (--code C, --v N)")
    assert asked == [(QUERY, {"work": "list", "budget": 5.0})]


def test_a_day_exactly_runs_with_a_note(given):
    given(_found(1000, 86394.0))  # 86 394 s + 1 000 · 0.006 s = 86 400 s: not more than a day
    assert size_note(QUERY, processes=1) == (
        "a long query: about 1 000 skeletons of W = 3 in class h = 3, each given its bases, 24.0 h on 1 worker "
        "(extrapolated from the exact counts at 8, 10, 12 links)")


def test_a_query_beyond_floating_point_is_written_from_its_logarithm(given):
    given(_found(math.inf, math.inf, log10_chains=2100.3))
    with pytest.raises(QueryTooLarge, match=r"about 2e\+2100 skeletons of W = 3"):
        size_note(QUERY, processes=2)


def test_a_forced_query_and_a_short_one(given):
    given(_found(2.0e8, 1.0e5))
    assert size_note(QUERY, processes=2, force=True).startswith("a long query: about 2e+08 skeletons")
    given(_found(1.0e3, 1194.0))  # 597 s + 6 s = 603 s: more than ten minutes
    assert size_note(QUERY, processes=2).startswith("a long query: about 1 000 skeletons")
    given(_found(1.0e3, 1188.0))  # 594 s + 6 s = 600 s: not more
    assert size_note(QUERY, processes=2) is None
    given(None)  # no estimate (too few smaller sizes)
    assert size_note(QUERY, processes=2) is None


def test_queries_of_fewer_than_five_loops_are_not_estimated(given):
    asked = given(_found(2.0e8, 1.0e5))
    assert size_note(skeleton_query(1, {3: 3, 5: 1}), processes=2) is None  # 4 loops
    assert asked == []
    with pytest.raises(QueryTooLarge):
        size_note(skeleton_query(1, {3: 4, 5: 1}), processes=2)  # 5 loops


def test_the_skeletons_are_listed_with_the_caller_s_workers_and_progress(monkeypatch):
    from synth.synthesis import type_synthesis as ts

    calls = []
    monkeypatch.setattr(ts, "type_synthesis", lambda q, **kw: calls.append((q, kw)) or iter(()))
    assert list(heterogeneous_synthesis(1, {3: 1, 5: 1})) == []
    assert list(heterogeneous_synthesis(1, {3: 1, 5: 1}, workers=3, progress=True)) == []
    query = skeleton_query(1, {3: 1, 5: 1})
    assert calls == [(query, {"workers": None, "progress": False}), (query, {"workers": 3, "progress": True})]
