"""Work units of any query, inline or on a pool, give exactly the chains of the query.

``plan_units`` + ``run_unit`` is how atlases and other drivers split a query; it must
give the same chains as ``type_synthesis`` for every option, not only the defaults.
"""

from __future__ import annotations

import pytest

import synth

QUERIES = [
    dict(dof=1, links=8, v=(0, 2)),
    dict(dof=2, links=7, fractionated=False),
    dict(dof=1, links=10, planar_only=True),
    dict(dof=1, links=10, v=(0, 1), require=["5=1.."]),
    dict(dof=1, links=10, v=(0, 3), cranks={5: 5}),
    dict(dof=1, code="6301/0"),
    dict(dof=0, links=7, rigid_subchains=False),
]


@pytest.mark.parametrize("query", QUERIES, ids=lambda q: ",".join(f"{k}={v}" for k, v in q.items()))
@pytest.mark.parametrize("workers", [1, 2])
def test_units_give_the_query_chains(query, workers):
    units = synth.plan_units(**query, workers=workers)
    assert len({u.key for u in units}) == len(units)
    flat = [c.certificate for u in units for c in synth.run_unit(u)]
    want = [c.certificate for c in synth.type_synthesis(**query, workers=1)]
    assert flat == want and want
    counted = synth.count_chains(**query, workers=workers)
    assert counted["count"] == len(want)


def test_run_unit_statistics_and_the_single_loop():
    stats: dict = {}
    units = synth.plan_units(1, 8)
    for u in units:
        synth.run_unit(u, stats)
    assert stats["candidates"] >= 16 and {"cpsat_s", "subchain_s", "nauty_s"} <= set(stats)
    (loop,) = synth.plan_units(0, 3)  # the triangle: a code without branch vertices
    assert loop.contracted is None and [c.compact() for c in synth.run_unit(loop)] == ["0-1 0-2 1-2"]
    (four,) = synth.plan_units(1, 4)
    assert [c.compact() for c in synth.run_unit(four)] == ["0-1 0-3 1-2 2-3"]


@pytest.mark.parametrize("query", [dict(dof=1, links=10, v=(0, 3)), dict(dof=0, links=9), dict(dof=2, links=9),
                                   dict(dof=1, links=10, cranks={4: 2})], ids=str)
@pytest.mark.parametrize("group_limit", [4096, 1], ids=["whole group", "generators only"])
def test_counting_a_unit_equals_its_distinct_chains(query, group_limit, monkeypatch):
    """count_realised counts stage B's vectors when they are one per orbit of Aut(H), else it
    compares certificates (forced here by a group limit of 1): either way it equals realise."""
    from synth import _realise

    monkeypatch.setattr(_realise, "_GROUP_LIMIT", group_limit)
    units = [u for u in synth.plan_units(**query, workers=1) if u.contracted is not None]
    args = [(u.code, u.contracted, u.conventions) for u in units]
    assert [_realise.count_realised(*a) for a in args] == [len(_realise.realise(*a)) for a in args]
    assert sum(len(_realise.realise(*a)) for a in args) > 0
