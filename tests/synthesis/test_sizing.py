"""The size of a counting problem, known before any model is built, bounds what CP-SAT lists.

The bound of :mod:`synth.synthesis._sizing` may only exceed the true number of codes (it leaves
n2 ≥ 0 and the split of v into joints to the model); for closed chains with simple joints it is
exact.  A refusal is sized in milliseconds, however large the query.
"""

from __future__ import annotations

import itertools

import pytest

from synth.errors import QueryTooLarge
from synth.synthesis._sizing import code_bound
from synth.synthesis.number_synthesis import MAX_CODES, _solve, make_problem, number_synthesis

PROBLEMS = [
    dict(dof=w, loops=k, h=h) for w, k, h in itertools.product((0, 1, 2, 3), range(1, 7), (3, 4))
] + [
    dict(dof=1, loops=4, require=["5=1.."]), dict(dof=1, loops=5, v="0..2", compositions=True),
    dict(dof=2, loops=3, n1="0..3"), dict(dof=4, loops=3, n1=2, v=2), dict(dof=1, loops=6, max_link_degree=3),
    dict(dof=1, loops=6, max_multiplicity=3, compositions=True), dict(dof=3, loops=5, max_link_degree="K+W"),
    dict(dof=1, loops=6, require=["3=2..4", "2=0..7"]), dict(dof=1, loop_classes={3: 4, 5: 1}),
    dict(dof=1, loops=7, compositions=True, max_multiplicity=4), dict(dof=0, loops=5, v=0, require=["4=0"]),
]


@pytest.mark.parametrize("query", PROBLEMS, ids=str)
def test_the_bound_is_never_below_the_codes(query):
    q = dict(query)
    dof = q.pop("dof")
    problem = make_problem(dof, **q)
    listed = len(_solve(problem))
    bound = code_bound(problem)
    assert bound.exact and bound.value >= listed
    closed_simple = problem.n1 == (0, 0) and problem.v == (0, 0) and not problem.requirements
    if closed_simple:
        assert bound.value == listed


def test_the_universal_table_is_sized_exactly():
    for k, count in zip(range(1, 9), (1, 3, 9, 23, 53, 113, 227, 433)):
        assert code_bound(make_problem(1, loops=k)).value == count == len(number_synthesis(1, loops=k))


def test_large_queries_are_refused_by_their_size_without_a_model(monkeypatch):
    from synth.synthesis import number_synthesis as ns

    monkeypatch.setattr(ns, "_solve", lambda *a, **k: pytest.fail("a model was built"))
    for query in (dict(loops=30), dict(loops=1000), dict(links=100_000_000), dict(loops="1..100000")):
        with pytest.raises(QueryTooLarge):
            number_synthesis(1, **query)
    with pytest.raises(QueryTooLarge, match="up to 140 606 codes") as refused:
        number_synthesis(1, loops=20, max_codes=100_000)
    assert "K = 20" in str(refused.value)
    assert MAX_CODES >= 140_606  # the table of K = 20 is listed unasked


def test_a_bound_beyond_floating_point_is_infinite_not_an_error():
    bound = code_bound(make_problem(1, loops=9000), stop=MAX_CODES)
    assert bound.value > MAX_CODES


@pytest.mark.parametrize("query", PROBLEMS + [dict(dof=1, loops=20), dict(dof=2, loops=12, n1="0..30"),
                                              dict(dof=1, loops=51), dict(dof=3, loops=9, v="0..8", compositions=True)],
                         ids=str)
def test_the_coarse_bound_is_never_below_the_bound(query):
    """coarse_bound decides alone (no numpy) when it is at most the limit: it must bound code_bound."""
    from synth.synthesis._sizing import coarse_bound

    q = dict(query)
    problem = make_problem(q.pop("dof"), **q)
    coarse = coarse_bound(problem)
    assert coarse is not None and coarse >= code_bound(problem).value
