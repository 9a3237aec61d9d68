"""The bound of the codes against its definition counted term by term, and its refusals in full.

The module's definition: for each n1, the link assortments n3 … n_D within their requirements
whose excess Σ (i − 2)·n_i is 2K − 2 + n1 − v, times the ways of splitting v into joints (with
compositions: the partitions of v into parts m − 2, m up to the largest multiplicity; without:
one way, or none for v > 0 when no joint may join three links).  Here it is counted by walking
every assortment and every split — slow, and sharing nothing with the dynamic programming of
:func:`code_bound` — on problems with open chains, requirements of every shape and multiple joints.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import types
import warnings

import numpy as np
import pytest

from synth.errors import QueryTooLarge
from synth.synthesis import _sizing
from synth.synthesis._sizing import MAX_EXCESS, check_excess, coarse_bound, code_bound
from synth.synthesis.number_synthesis import make_problem, number_synthesis


def _assortments(degrees, requirements, excess):
    """The tuples (n_i for i in degrees) with Σ (i − 2)·n_i = excess within the requirements."""
    return _walk(tuple(degrees), tuple(sorted(requirements.items())), excess)


@functools.lru_cache(maxsize=None)
def _walk(degrees, requirements, excess):
    if not degrees:
        return 1 if excess == 0 else 0
    i, rest = degrees[0], degrees[1:]
    lo, hi = dict(requirements).get(i, (0, None))
    top = excess // (i - 2) if hi is None else min(hi, excess // (i - 2))
    return sum(_walk(rest, requirements, excess - (i - 2) * n) for n in range(lo, top + 1))


@functools.lru_cache(maxsize=None)
def _partitions(v, largest):
    """Partitions of v into parts 1 … largest, counted by recursion."""
    if v == 0:
        return 1
    return sum(_partitions(v - part, part) for part in range(1, min(v, largest) + 1))


def _brute_bound(problem):
    requirements = dict(problem.requirements)
    lo1, hi1 = requirements.get(1, (0, None))
    n1_lo, n1_hi = max(problem.n1[0], lo1), problem.n1[1] if hi1 is None else min(problem.n1[1], hi1)
    biggest = (problem.max_multiplicity or problem.links) - 2
    total = 0
    for n1 in range(n1_lo, n1_hi + 1):
        for v in range(problem.v[0], problem.v[1] + 1):
            excess = 2 * problem.loops - 2 + n1 - v
            if excess < 0:
                continue
            splits = _partitions(v, biggest) if problem.compositions else (1 if biggest >= 1 or v == 0 else 0)
            total += splits * _assortments(list(range(3, problem.max_link_degree + 1)), requirements, excess)
    return total


PROBLEMS = [
    dict(dof=1, loops=4), dict(dof=1, loops=5, v="0..3"), dict(dof=2, loops=3, n1="0..3"),
    dict(dof=2, loops=3, n1="1..4", require=["1=2..3"]), dict(dof=2, loops=3, n1="0..4", require=["1=..2"]),
    dict(dof=2, loops=3, n1="0..3", require=["1=2"]), dict(dof=3, loops=3, n1=4, v="0..2"),
    dict(dof=1, loops=5, require=["3=2..4"]), dict(dof=1, loops=5, require=["3=..2", "4=1.."]),
    dict(dof=1, loops=5, require=["4=2"]), dict(dof=1, loops=5, require=["3=3", "5=0"]),
    dict(dof=1, loops=5, require=["2=1..3"]), dict(dof=1, loops=5, require=["6=2.."]),
    dict(dof=1, loops=4, v="0..4", max_multiplicity=2), dict(dof=1, loops=4, v="0..4", max_multiplicity=3),
    dict(dof=1, loops=4, v="1..4", compositions=True), dict(dof=1, loops=4, v="0..5", compositions=True, max_multiplicity=3),
    dict(dof=1, loops=5, v="0..6", compositions=True, max_multiplicity=4), dict(dof=1, loops=6, v="2..3", max_link_degree=4),
    dict(dof=1, loops=6, max_link_degree=3), dict(dof=3, loops=4, max_link_degree="K+W", v="0..2"),
    dict(dof=0, loops=3, v="0..2", require=["4=1..1", "3=0..2"]), dict(dof=1, loops=3, v=4),
    # links of as many joints as the whole excess (a part equal to it), and beyond it
    dict(dof=1, loops=3, max_link_degree=6), dict(dof=1, loops=2, max_link_degree=5),
    dict(dof=2, loops=2, n1="0..2", max_link_degree=7),
    # the required links leave no excess for the first values of n1; v's least is above it
    dict(dof=2, loops=3, n1="0..5", require=["3=5.."]), dict(dof=2, loops=2, n1="0..3", v="3..4"),
]


@pytest.mark.parametrize("query", PROBLEMS, ids=str)
def test_the_bound_is_its_definition_counted_term_by_term(query):
    q = dict(query)
    problem = make_problem(q.pop("dof"), **q)
    assert code_bound(problem) == _sizing.Bound(float(_brute_bound(problem)), exact=True)


def test_contradictory_requirements_bound_nothing():
    problem = make_problem(1, loops=5)
    for requirements in (((3, (4, 2)),), ((1, (2, 1)),)):
        assert code_bound(dataclasses.replace(problem, requirements=requirements)) == _sizing.Bound(0.0)
    wide = make_problem(2, loops=3, n1="0..3")
    assert code_bound(dataclasses.replace(wide, n1=(3, 2))) == _sizing.Bound(0.0)
    assert code_bound(dataclasses.replace(problem, loops=0)) == _sizing.Bound(0.0)  # excess −2: no code


@pytest.mark.parametrize("size, part, most", [(10, 1, None), (10, 3, None), (10, 3, 2), (10, 3, 3), (10, 3, 4),
                                              (12, 4, 3), (12, 4, 2), (7, 2, 0), (9, 5, 1), (9, 10, 2)])
def test_a_part_up_to_most_times_convolves_the_table(size, part, most):
    rng = np.random.default_rng(size * 31 + part)
    table = rng.integers(0, 5, size).astype(float)
    expected = [sum(table[x - k * part] for k in range(0, x // part + 1) if most is None or k <= most)
                for x in range(size)]
    assert _sizing._partitions_bounded(table.copy(), part, most).tolist() == expected


@pytest.mark.parametrize("query, open_range", [
    (dict(dof=1, loops=5), (0, 0)), (dict(dof=2, loops=3, n1="0..3"), (0, 3)),
    (dict(dof=2, loops=3, n1="1..4", require=["1=2..3"]), (2, 3)), (dict(dof=2, loops=3, n1="0..4", require=["1=..2"]), (0, 2)),
    (dict(dof=2, loops=3, n1="2..3", require=["1=0..9"]), (2, 3)),
])
def test_the_coarse_bound_is_the_pairs_of_partitions_of_the_largest_excess(query, open_range):
    q = dict(query)
    problem = make_problem(q.pop("dof"), **q)
    top = 2 * problem.loops - 2 + open_range[1]
    pairs = sum(_partitions(v, v) * _partitions(top - v, top - v) for v in range(top + 1))
    assert coarse_bound(problem) == (open_range[1] - open_range[0] + 1) * pairs


def test_the_coarse_bound_of_an_empty_or_a_large_problem():
    problem = make_problem(1, loops=5)
    assert coarse_bound(dataclasses.replace(problem, loops=0)) == 0  # excess −2
    assert coarse_bound(dataclasses.replace(problem, loops=1, n1=(0, 0))) == 1  # excess 0: one pair of empty partitions
    wide = make_problem(2, loops=3, n1="0..3")
    assert coarse_bound(dataclasses.replace(wide, n1=(3, 2))) == 0
    assert coarse_bound(dataclasses.replace(wide, n1=(5, 2))) == 0  # (not −3 times the pairs)
    assert coarse_bound(make_problem(1, loops=51)) == _sizing._partition_pairs(100)  # excess 100: still counted
    assert coarse_bound(make_problem(1, loops=52)) is None  # 102: beyond the integers it counts in


def test_the_partition_pairs_are_oeis_a000712():
    assert [_sizing._partition_pairs(n) for n in range(12)] == [1, 2, 5, 10, 20, 36, 65, 110, 185, 300, 481, 752]


def test_an_excess_beyond_the_table_is_refused_in_full():
    problem = make_problem(1, loops=5)
    assert check_excess(dataclasses.replace(problem, loops=500_001)) == MAX_EXCESS  # 2K − 2 = 1 000 000: sized
    with pytest.raises(QueryTooLarge) as refused:
        check_excess(dataclasses.replace(problem, loops=500_002, links=1_000_005))
    assert str(refused.value) == ("n = 1000005 links, K = 500002 loops are far beyond what number synthesis can list or "
                                  "even size (the excess 2K − 2 + n1 = 1000002 is above 1 000 000)")
    with pytest.raises(QueryTooLarge) as refused:
        check_excess(dataclasses.replace(problem, loops=500_000, links=1_000_007, n1=(0, 5)))
    assert str(refused.value) == ("n = 1000007 links, K = 500000 loops and up to 5 single-joint links are far beyond "
                                  "what number synthesis can list or even size (the excess 2K − 2 + n1 = 1000003 is "
                                  "above 1 000 000)")
    # a requirement on n1 narrows the open links before the excess is taken
    assert check_excess(dataclasses.replace(problem, loops=500_000, n1=(0, 5), requirements=((1, (0, 2)),))) == 1_000_000


class _Clock:
    """A perf_counter that reads ``reads`` in turn (and fails past them: a look not expected)."""

    def __init__(self, *reads):
        self.reads = list(reads)

    def perf_counter(self):
        return self.reads.pop(0)


def _clock(monkeypatch, *reads):
    monkeypatch.setattr(_sizing, "time", types.SimpleNamespace(perf_counter=_Clock(*reads).perf_counter))


def test_a_bound_past_its_limit_when_time_runs_short_is_returned_inexact(monkeypatch):
    # K = 20: links of 3 … 21 joints, 19 parts; after 16 parts the clock is past half a second, and the
    # sum so far — the bound of the links of up to 18 joints — is returned when it is above the limit
    problem = make_problem(1, loops=20)
    partial = code_bound(dataclasses.replace(problem, max_link_degree=18))
    full = code_bound(problem)
    assert partial.exact and partial.value < full.value
    _clock(monkeypatch, 10.0, 10.6)
    assert code_bound(problem, stop=partial.value - 1) == _sizing.Bound(partial.value, exact=False)
    _clock(monkeypatch, 10.0, 10.6, 10.9)  # the sum so far is not above the limit: on to the end, within 1 s
    assert code_bound(problem, stop=partial.value) == full
    _clock(monkeypatch, 10.0, 10.5)  # not past half a second: no sum so far
    assert code_bound(problem, stop=1) == full


def test_a_bound_that_cannot_be_sized_in_time_is_refused(monkeypatch):
    problem = make_problem(1, loops=20)
    _clock(monkeypatch, 10.0, 10.6, 11.01)
    with pytest.raises(QueryTooLarge) as refused:
        code_bound(problem)
    assert str(refused.value) == "the codes of K = 20 loops cannot be sized within 1 s"
    _clock(monkeypatch, 10.0, 10.6, 11.0)
    assert code_bound(problem) == _sizing.Bound(float(_brute_bound(problem)), exact=True)


def test_time_is_looked_at_every_16_parts_only(monkeypatch):
    _clock(monkeypatch, 0.0)  # K = 8: 7 parts, no look at the clock after the start
    assert code_bound(make_problem(1, loops=8), stop=1) == _sizing.Bound(433.0)


def test_the_sum_over_the_single_joint_links_stops_once_above_the_limit():
    problem = make_problem(2, loops=3, n1="0..3")
    first = _brute_bound(dataclasses.replace(problem, n1=(0, 0)))  # the codes without a single-joint link
    full = _brute_bound(problem)
    assert code_bound(problem, stop=first - 1) == _sizing.Bound(float(first), exact=False)
    assert code_bound(problem, stop=full - 1) == _sizing.Bound(float(full), exact=True)  # the last n1: all summed
    two = _brute_bound(dataclasses.replace(problem, n1=(0, 1)))
    assert code_bound(problem, stop=first) == _sizing.Bound(float(two), exact=False)  # equal is not above: on to n1 = 1
    assert code_bound(problem, stop=full) == _sizing.Bound(float(full), exact=True)


def test_a_wide_range_of_single_joint_links_is_refused_when_the_second_is_out(monkeypatch):
    # (``codes --dof 2 --loops 3 --n1 0..999000`` summed for minutes before it was refused within a second; a query
    # now keeps n1 within its n links, so the wide problem is built as it was: n1 up to 600, v up to 2p − 2n + 600)
    problem = dataclasses.replace(make_problem(2, loops=3, n1="0..9"), n1=(0, 600), v=(0, 604))
    _clock(monkeypatch, 10.0, 10.9, 11.0)  # the clock is read after every 256 values of n1: at 255 and 511
    assert code_bound(problem) == _sizing.Bound(float(_brute_bound(problem)))  # within 1 s
    _clock(monkeypatch, 10.0, 10.5, 11.01)
    with pytest.raises(QueryTooLarge) as refused:
        code_bound(problem)
    assert str(refused.value) == "the codes of K = 3 loops and up to 600 single-joint links cannot be sized within 1 s"


def test_the_splits_of_many_multiple_joints_are_refused_when_the_second_is_out(monkeypatch):
    problem = make_problem(1, loops=40, v="0..70", compositions=True, max_multiplicity=80)  # v in parts 1 … 70: read at 64
    _clock(monkeypatch, 10.0, 11.01)
    with pytest.raises(QueryTooLarge) as refused:
        code_bound(problem)
    assert str(refused.value) == "the codes of K = 40 loops cannot be sized within 1 s"


def test_problems_of_many_parts_of_v_or_many_single_joint_links_are_sized_when_quick():
    # the clock is looked at every 64 parts of v and every 256 values of n1, and only a second past refuses
    many_parts = make_problem(1, loops=40, v="0..70", compositions=True, max_multiplicity=80)
    assert code_bound(many_parts) == _sizing.Bound(float(_brute_bound(many_parts)))
    wide = make_problem(2, loops=3, n1="0..600")
    assert code_bound(wide) == _sizing.Bound(float(_brute_bound(wide)))


def test_a_refusal_of_the_splits_names_the_single_joint_links(monkeypatch):
    problem = make_problem(2, loops=40, n1="0..3", v="0..70", compositions=True, max_multiplicity=80)
    _clock(monkeypatch, 10.0, 11.01)
    with pytest.raises(QueryTooLarge) as refused:
        code_bound(problem)
    assert str(refused.value) == "the codes of K = 40 loops and up to 3 single-joint links cannot be sized within 1 s"


def test_tables_beyond_floating_point_warn_of_nothing(monkeypatch):
    # links of up to 300 joints and up to 200 000 single-joint links: the partitions pass 1e308 within the
    # second (on a clock that does not move here); the bound is then the sum so far, without a warning
    monkeypatch.setattr(_sizing, "time", types.SimpleNamespace(perf_counter=lambda: 0.0))
    # (built as a query of n1 up to 200 000 was before n1 was kept within n: v up to 2p − 2n + 200 000)
    problem = dataclasses.replace(make_problem(2, loops=3, n1="0..9", max_link_degree=300), n1=(0, 200000),
                                  v=(0, 200004))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        found = code_bound(problem, stop=1e6)
    assert not found.exact and 1e6 < found.value < math.inf


class _Reads:
    """A perf_counter that reads 0 s ``quiet`` times, then ``then`` s."""

    def __init__(self, quiet, then):
        self.quiet, self.then = quiet, then

    def perf_counter(self):
        self.quiet -= 1
        return 0.0 if self.quiet >= 0 else self.then


@pytest.mark.parametrize("quiet, exact", [(10**9, True), (23, False)])
def test_a_bound_lost_to_overflow_is_infinite_never_nan(monkeypatch, quiet, exact):
    # no joint of three links (the splits of v are 1, 0, 0): 0 · inf in the sum is nan, which would pass every
    # limit unnoticed; the bound is inf instead — at the end (a clock that never moves), or in the sum so far
    # when the clock is past half a second at the 368th part (after the start and 22 quiet looks)
    monkeypatch.setattr(_sizing, "time", types.SimpleNamespace(perf_counter=_Reads(quiet, 0.6).perf_counter))
    # (built as a query of n1 up to 100 000 was before n1 was kept within the chain's n links)
    problem = dataclasses.replace(make_problem(2, loops=3, n1="0..9", v="0..2", max_link_degree=400, max_multiplicity=2),
                                  n1=(0, 100000))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert code_bound(problem) == _sizing.Bound(math.inf, exact=exact)


def test_a_refusal_at_the_parts_names_the_single_joint_links(monkeypatch):
    problem = make_problem(2, loops=20, n1="0..3")  # links of up to 22 joints: the clock read at the 16th part
    _clock(monkeypatch, 10.0, 10.6, 11.01)
    with pytest.raises(QueryTooLarge) as refused:
        code_bound(problem)
    assert str(refused.value) == "the codes of K = 20 loops and up to 3 single-joint links cannot be sized within 1 s"


def test_single_joint_links_beyond_the_links_of_the_chain_change_nothing():
    """n1 ≤ n: a range of single-joint links past the chain's n links is the range up to n (it was sized as
    written: ``--n1 0..999000`` with n = 9 was refused as "more than 202 729 codes" where there are 99)."""
    wide, tight = make_problem(2, loops=3, n1="0..999000"), make_problem(2, loops=3, n1="0..9")
    assert wide == tight and wide.n1 == (0, 9)
    assert len(number_synthesis(2, loops=3, n1="0..999000")) == len(number_synthesis(2, loops=3, n1="0..9")) == 99
