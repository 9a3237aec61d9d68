"""The size estimate's arithmetic and its refusals, on calibrations given by hand.

The calibration counts are handed to :func:`estimate` through stand-ins of the plan and of the unit
runs, and its CPU clock advances by the seconds each size is said to take, so every number of the
estimate is computed here by hand from the module's stated method (the growth ratio of chains
extrapolated linearly, r(n + 2) = r(n) + (r(n) − r(n − 2))) — not with its own formula.  The
refusals of :func:`size_check` get estimates given by hand and are read sentence by sentence.
"""

from __future__ import annotations

import math
import types

import pytest

from synth.errors import ImpossibleParameters, QueryTooLarge, flag
from synth.structure.query import ChainQuery
from synth.synthesis import estimate as est
from synth.synthesis import stage_a, stage_b
from synth.synthesis import type_synthesis as ts

#: links -> units of each code (their chain counts), the CPU seconds the size takes, and of those the
#: seconds of its units' own work (none where not given), spread over the units by their chains, and
#: whether stage B counts those units without visiting their chains (no where not given)
SIZES = {
    4: ([[1]], 0.0), 6: ([[2]], 0.0), 8: ([[16]], 0.0), 10: ([[230]], 0.01),
    12: ([[6000, 356], [500]], 0.01), 14: ([[100000, 100000, 18162], [100000]], 0.5, 0.4),
}


class _Calibrations:
    """Stand-ins of plan_jobs and _map_units over a table like SIZES, with a CPU clock."""

    def __init__(self, monkeypatch, sizes):
        self.sizes, self.now, self.runs, self.kernels, self.planned = sizes, 100.0, [], 0, []
        self.empty_unit_seconds = 0.0  # what a unit that finds no chain takes, within the units' work
        monkeypatch.setattr(est, "_COUNTED", {})
        monkeypatch.setattr(est, "time", types.SimpleNamespace(process_time=lambda: self.now))
        monkeypatch.setattr(ts, "plan_jobs", self.plan_jobs)
        monkeypatch.setattr(ts, "_map_units", self.map_units)
        monkeypatch.setattr(stage_b, "load_kernel", self.load_kernel)

    def load_kernel(self):
        self.kernels += 1

    def plan_jobs(self, query):
        self.planned.append(query.links)
        if query.links not in self.sizes:
            raise ImpossibleParameters("no chain of that size")
        return [((query.links, k), ts._conventions(query)) for k in range(len(self.sizes[query.links][0]))]

    def map_units(self, work, jobs, workers, progress):
        """The units of the table run through ``work`` (the estimate's timed wrapper), with the
        query's own work (recorded) replaced by one that takes the unit's share of the seconds."""
        n = jobs[0][0][0]
        query_work, units_seconds = work.work, (self.sizes[n][2] if len(self.sizes[n]) > 2 else 0.0)
        tight = len(self.sizes[n]) > 3 and self.sizes[n][3]
        self.runs.append((n, query_work, workers, progress, jobs[0][1].kernel_loops))
        total = sum(map(sum, self.sizes[n][0]))

        def run(chains, stats):
            self.now += units_seconds * chains / total if total else 0.0
            self.now += 0.0 if chains else self.empty_unit_seconds
            if tight:
                stats["tight"] = 1
            return ["chain"] * chains if query_work is ts.run_unit else {"7201/1": chains}

        work.work = run
        for index, ((_, k), _) in enumerate(jobs):
            units = self.sizes[n][0][k]
            for chains in units:
                yield index, f"unit of {chains} chains", work(chains)
            yield index, None, len(units)
        self.now += self.sizes[n][1] - units_seconds


def test_the_estimate_extrapolates_the_growth_ratio_linearly(monkeypatch):
    calibrations = _Calibrations(monkeypatch, SIZES)
    found = est.estimate(ChainQuery(1, 16))
    assert [run[0] for run in calibrations.runs] == [4, 6, 8, 10, 12, 14]  # every smaller size, smallest first
    assert calibrations.planned == [2, 4, 6, 8, 10, 12, 14]  # (2 links: no chain, refused)
    assert found.basis == "exact counts at 10, 12, 14 links"
    r14, r12 = 318162 / 6856, 6856 / 230
    chains = 318162 * (r14 + (r14 - r12))  # one step of two links
    assert found.chains == pytest.approx(chains, rel=1e-12)
    assert found.log10_chains == pytest.approx(math.log10(chains), rel=1e-12)
    # units 1, 3, 4: ratio 4/3, its change 4/3 − 3 clipped to 0 (a ratio never shrinks by extrapolation)
    assert found.units == pytest.approx(4 * 4 / 3, rel=1e-12)
    assert found.log10_units == pytest.approx(math.log10(16 / 3), rel=1e-12)
    # the largest code's share of the units is that of the largest calibration: 3 of 4
    assert found.largest_code_units == pytest.approx(16 / 3 * 3 / 4, rel=1e-12)
    # time: the largest calibration's units' work per chain (0.4 s) times the chains, and the rest
    # (0.1 s) per unit, 1.27 times more a loop (h = 3) beyond it, times the units
    seconds = chains * 0.4 / 318162 + 16 / 3 * 0.1 / 4 * 1.27
    assert found.seconds == pytest.approx(seconds, rel=1e-12)
    assert found.log10_seconds == pytest.approx(math.log10(seconds), rel=1e-12)


@pytest.mark.parametrize("units_seconds", [0.0, 0.5])
def test_a_calibration_whose_time_is_all_in_one_part_scales_that_part_only(monkeypatch, units_seconds):
    """Every second in the units' work: time per chain times the chains; none there: per unit times the units."""
    _Calibrations(monkeypatch, {**SIZES, 14: (SIZES[14][0], 0.5, units_seconds)})
    found = est.estimate(ChainQuery(1, 16))
    per_chain = 0.5 / 318162 * found.chains
    assert found.seconds == pytest.approx(per_chain if units_seconds else 0.5 / 4 * 1.27 * found.units, rel=1e-12)


def test_units_counted_without_visiting_their_chains_are_timed_per_unit(monkeypatch):
    """Stage B's tight count does not grow with the chains of a unit: all 0.5 s of 14 links are then
    the units' (1.27 times more a unit at 16 links), none the chains'."""
    _Calibrations(monkeypatch, {**SIZES, 14: (SIZES[14][0], 0.5, 0.4, True)})
    found = est.estimate(ChainQuery(1, 16))
    assert found.seconds == pytest.approx(0.5 / 4 * 1.27 * found.units, rel=1e-12)
    assert found.seconds < 0.5 / 318162 * found.chains / 10  # (per chain, it would be 14 times longer)


def test_a_unit_that_finds_no_chain_is_timed_per_unit(monkeypatch):
    """14 links take 0.7 s: 0.4 s of units' work that found chains scale with the chains, the 0.1 s of a
    unit that found none and the other 0.2 s (stage A, the plan) with the units (5 at 14 links, each
    1.27 times longer at 16)."""
    sizes = {**SIZES, 14: ([[100000, 100000, 18162, 0], [100000]], 0.6, 0.4)}
    calibrations = _Calibrations(monkeypatch, sizes)
    calibrations.empty_unit_seconds = 0.1
    found = est.estimate(ChainQuery(1, 16))
    assert [p for (_, n), p in est._COUNTED.items() if n == 14][0][3:] == pytest.approx((0.7, 4, 0.4), rel=1e-12)
    assert found.seconds == pytest.approx(found.chains * 0.4 / 318162 + found.units * 0.3 / 5 * 1.27, rel=1e-12)


def test_sizes_past_the_budget_are_not_counted_and_the_ratio_steps_on(monkeypatch):
    sizes = {**SIZES, 14: (SIZES[14][0], 3.0), 16: ([[10**7]], 0.0)}
    calibrations = _Calibrations(monkeypatch, sizes)
    found = est.estimate(ChainQuery(1, 18), budget=2.0)  # 14 ends past the budget: 16 is not counted
    assert [run[0] for run in calibrations.runs] == [4, 6, 8, 10, 12, 14]
    r14, r12 = 318162 / 6856, 6856 / 230
    d = r14 - r12
    assert found.basis == "exact counts at 10, 12, 14 links"
    assert found.chains == pytest.approx(318162 * (r14 + d) * (r14 + 2 * d), rel=1e-12)
    assert found.seconds == pytest.approx(found.units * 3.0 / 4 * 1.27**2, rel=1e-12)  # (no units' work given)


@pytest.mark.parametrize("seconds_12, counted_14", [(0.09, True), (0.1, False)])
def test_a_size_predicted_to_end_past_one_and_a_half_budgets_is_not_started(monkeypatch, seconds_12, counted_14):
    # before 14 links: 0.01 s (10) + s12 spent, and 14 predicted to take s12 · 6856 / 230 (29.8 s12):
    # 0.1 + 2.683 = 2.78 s < 3 s starts it; 0.11 + 2.981 = 3.09 s > 3 s does not
    sizes = {**SIZES, 12: (SIZES[12][0], seconds_12)}
    calibrations = _Calibrations(monkeypatch, sizes)
    found = est.estimate(ChainQuery(1, 16), budget=2.0)
    assert (14 in [run[0] for run in calibrations.runs]) is counted_14
    assert found.basis == ("exact counts at 10, 12, 14 links" if counted_14 else "exact counts at 8, 10, 12 links")


def test_the_default_budget_is_two_cpu_seconds(monkeypatch):
    # 10 links take 2.1 s: past two seconds, 12 is not started (with three, 12 and 14 would be: 2.5 s in all)
    sizes = {4: ([[1]], 0.0), 6: ([[50]], 0.0), 8: ([[100]], 0.0), 10: ([[110]], 2.1), 12: ([[120]], 0.4),
             14: ([[130]], 0.0)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)).basis == "exact counts at 6, 8, 10 links"
    assert [run[0] for run in calibrations.runs] == [4, 6, 8, 10]
    assert est.estimate(ChainQuery(1, 16), budget=3.0).basis == "exact counts at 10, 12, 14 links"


def test_a_query_with_multiple_joints_is_sized_for_eight_cpu_seconds(monkeypatch):
    # 4 … 10 links take 2.1 s, 12 links 5 s: 7.1 s in all; 14 would end at 12.6 s, past one and a half budgets
    sizes = {4: ([[1]], 0.0), 6: ([[50]], 0.0), 8: ([[100]], 0.0), 10: ([[110]], 2.1), 12: ([[120]], 5.0),
             14: ([[130]], 0.0)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.MULTIPLE_BUDGET == 8.0
    assert est.estimate(ChainQuery(1, 16, v=(0, 14))).basis == "exact counts at 8, 10, 12 links"
    assert [run[0] for run in calibrations.runs] == [4, 6, 8, 10, 12]
    assert est.estimate(ChainQuery(1, 16, v=(0, 0))).basis == "exact counts at 6, 8, 10 links"  # (simple joints only)


@pytest.mark.slow
def test_the_estimate_with_multiple_joints_at_14_links_is_within_one_percent():
    """Run for real: 1-DOF chains of 14 links with multiple joints, 35 396 111 (benchmarks/RECORDS.md, the
    count; from 6, 8, 10 links the estimate was 1.98e7, −44 %)."""
    found = est.estimate(ChainQuery(1, 14, v=(0, 12)))
    assert found.basis == "exact counts at 8, 10, 12 links"
    assert found.chains == pytest.approx(35_396_111, rel=0.01)


def test_fewer_than_three_sizes_with_chains_give_no_estimate(monkeypatch):
    sizes = {4: ([[]], 0.0), 6: ([[]], 0.0), 8: ([[3]], 0.0), 10: ([[]], 0.0), 12: ([[5]], 0.0)}
    _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 14)) is None
    sizes[10] = ([[4]], 0.0)
    est._COUNTED.clear()  # (the sizes counted are remembered)
    assert est.estimate(ChainQuery(1, 14)).basis == "exact counts at 8, 10, 12 links"


def test_calibrations_are_shared_by_the_same_query_and_work_only(monkeypatch):
    calibrations = _Calibrations(monkeypatch, SIZES)
    first = est.estimate(ChainQuery(1, 16))
    assert len(calibrations.runs) == 6
    assert est.estimate(ChainQuery(1, 16)) == first and len(calibrations.runs) == 6  # nothing counted again
    est.estimate(ChainQuery(1, 16), work="list")  # another work: its own calibrations
    assert len(calibrations.runs) == 12
    est.estimate(ChainQuery(1, 16, fractionated=False))  # another query: its own too
    assert len(calibrations.runs) == 18


@pytest.mark.parametrize("work, unit_work", [
    ("count", ts.count_unit), ("list", ts.run_unit), ("mechanisms", ts._MechanismCount(False)),
    ("mechanisms with input", ts._MechanismCount(True)),
])
def test_each_work_times_what_the_query_will_do(monkeypatch, work, unit_work):
    calibrations = _Calibrations(monkeypatch, SIZES)
    found = est.estimate(ChainQuery(1, 16), work=work)
    ran = calibrations.runs[0][1]
    assert ran == unit_work if isinstance(unit_work, ts._MechanismCount) else ran is unit_work
    assert {run[2:4] for run in calibrations.runs} == {(1, False)}  # one process, no progress bar
    assert found.chains == pytest.approx(318162 * (2 * 318162 / 6856 - 6856 / 230), rel=1e-12)  # lists too


@pytest.mark.parametrize("query, compiled", [(ChainQuery(1, 16), True), (ChainQuery(1, 14), True),
                                             (ChainQuery(1, 12), False), (ChainQuery(1, 12, v="0..1"), True),
                                             (ChainQuery(1, 12, v="0.."), True), (ChainQuery(1, 12, v=0), False)])
def test_the_calibrations_take_the_compiled_path_of_a_large_query(monkeypatch, query, compiled):
    # the kernel from K = 6 loops (5 with multiple joints): 16 and 14 links have 7 and 6, 12 links 5
    calibrations = _Calibrations(monkeypatch, SIZES)
    est.estimate(query)
    assert calibrations.kernels == compiled
    assert {run[4] for run in calibrations.runs} == ({1} if compiled else {est._NEVER})  # (plain: never compiled)
    calibrations.runs.clear()
    est._COUNTED.clear()
    est.estimate(query, plain=True)  # the plain path whatever the query: nothing compiled
    assert {run[4] for run in calibrations.runs} == {est._NEVER}


def test_growth_beyond_floating_point_is_infinite_with_a_finite_logarithm(monkeypatch):
    _Calibrations(monkeypatch, SIZES)
    found = est.estimate(ChainQuery(1, 400))
    r14, r12 = 318162 / 6856, 6856 / 230
    d = r14 - r12
    log10 = math.log10(318162) + sum(math.log10(r14 + k * d) for k in range(1, (400 - 14) // 2 + 1))
    assert found.chains == math.inf and found.seconds == math.inf
    assert found.log10_chains == pytest.approx(log10, rel=1e-9)
    log10_units = math.log10(4 * (4 / 3) ** 193)  # the rest's 0.1 s per unit is far below the chains' share
    log10_unit_time = log10_units + math.log10(0.1 / 4) + 193 * math.log10(1.27)
    assert found.log10_seconds == pytest.approx(log10 + math.log10(0.4 / 318162 + 10 ** (log10_unit_time - log10)),
                                                rel=1e-9)
    assert found.units == pytest.approx(4 * (4 / 3) ** 193, rel=1e-9)  # the units' ratio does not grow


@pytest.mark.parametrize("ratio, step, steps", [(2.0, 1.0, 3), (46.4, 16.6, 1), (46.4, 16.6, 25), (1.3, 0.01, 7),
                                                (3.0, 0.0, 5), (1.0, 0.0, 4), (5.0, 2.0, 0)])
def test_the_growth_factor_is_the_product_of_the_extrapolated_ratios(ratio, step, steps):
    product = math.prod(ratio + k * step for k in range(1, steps + 1))
    assert 10 ** est._log10_growth(ratio, step, steps) == pytest.approx(product, rel=1e-10)


@pytest.mark.parametrize("query, table, sized", [
    (ChainQuery(1, 16), False, True), (ChainQuery(1, 14), False, False), (ChainQuery(1, 14), True, True),
    (ChainQuery(1, 12), True, False),
    (ChainQuery(1, 11, h=2), False, True), (ChainQuery(1, 10, h=2), False, False),   # h = 2: from K = 9
    (ChainQuery(1, 10, h=2), True, True), (ChainQuery(1, 9, h=2), True, False),
    (ChainQuery(1, 14, v="0..2"), False, True), (ChainQuery(1, 12, v="0..2"), False, False),  # multiple: K = 6
    (ChainQuery(1, 14, v=0), False, False),                          # v = 0 only: simple joints, K = 7
    (ChainQuery(1, 14, code="662000/0"), True, False),            # one code: never sized
    (ChainQuery(1, 12, prismatic="0.."), False, True),   # wedge loops: skeletons of up to K = (10 + 10)/2 loops
    (ChainQuery(1, 15, prismatic=(0, 2)), False, False),  # no skeleton at all: K = (15 − 2)//2 = 6 from n alone
    (ChainQuery(1, 15, prismatic=(0, 2)), True, True),
    (ChainQuery(1, 20, h=4), False, False), (ChainQuery(1, 23, h=4), False, True),  # h = 4: K = (n − 2)/3 = 6, 7
])
def test_which_queries_are_sized_before_they_run(query, table, sized):
    assert est.worth_sizing(query, table=table) is sized


def test_the_least_sized_loops_of_each_motion_space():
    assert [est.sized_loops(h) for h in (2, 3, 4, 5, 6)] == [9, 7, 7, 7, 7]
    assert [est.sized_loops(h, multiple=True) for h in (2, 3, 6)] == [8, 6, 6]


# ------------------------------------------------------------------ size_check on estimates given by hand
def _given(monkeypatch, found):
    """``found`` for the compiled path's sizing; none for the plain path's (which then refuses nothing)."""
    asked = []

    def fake(query, *, budget=2.0, work="count", plain=False):
        if plain:
            return None
        asked.append(work)
        return found

    monkeypatch.setattr(est, "estimate", fake)
    return asked


def _estimate(chains, units, seconds, largest=0.0):
    return est.Estimate(chains, units, seconds, "exact counts at 10, 12, 14 links", math.log10(chains),
                        math.log10(units), math.log10(seconds), largest)


def test_a_refusal_on_the_plain_path_comes_before_the_compiled_sizing(monkeypatch):
    """A query on the compiled path is sized first on the plain one: refused there when its counts pass a limit
    PLAIN_MARGIN times over or its floor of time passes a day, the compiled sizing (which compiles the kernels on a
    cold cache) is never asked; within the margin it is."""
    from dataclasses import replace

    asked = []
    answers = {}

    def fake(query, *, budget=2.0, work="count", plain=False):
        asked.append(plain)
        return answers[plain]

    monkeypatch.setattr(est, "estimate", fake)
    answers[True] = replace(_estimate(2.5e6, 1e3, 1e-4), floor=True)
    answers[False] = _estimate(2.5e6, 1e3, 10.0)
    with pytest.raises(QueryTooLarge, match="a table is held in memory") as refused:
        est.size_check(ChainQuery(1, 16), processes=2, count=False, table=True)
    assert asked == [True] and " s on 2 workers" not in str(refused.value)  # (no time said: it was a floor)
    asked.clear()
    answers[True] = replace(_estimate(1.5e6, 1e3, 1e-4), floor=True)  # within the margin: sized again, refused there
    with pytest.raises(QueryTooLarge, match="a table is held in memory"):
        est.size_check(ChainQuery(1, 16), processes=2, count=False, table=True)
    assert asked == [True, False]
    asked.clear()
    answers[True] = replace(_estimate(1e12, 1e6, 2 * 86400 * 2.5), floor=True)  # a floor of 2.5 days on 2 workers
    with pytest.raises(QueryTooLarge, match="it would take at least 2.5 days on 2 workers"):
        est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False)
    assert asked == [True]
    asked.clear()
    answers[True] = replace(_estimate(1e12, 1e6, 86400.0), floor=True)  # half a day on 2: the compiled path decides
    assert est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False) is None
    assert asked == [True, False]


def test_a_forced_count_and_a_small_query_are_not_sized(monkeypatch):
    asked = _given(monkeypatch, None)
    assert est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False, force=True) is None
    assert est.size_check(ChainQuery(1, 14), processes=2, count=True, table=False) is None
    assert est.size_check(ChainQuery(1, 14), processes=2, count=False, table=False) is None
    assert asked == []


def test_a_query_that_cannot_be_estimated_is_refused_unless_forced(monkeypatch):
    asked = _given(monkeypatch, None)
    with pytest.raises(QueryTooLarge) as refused:
        est.size_check(ChainQuery(1, 16), processes=2, count=False, table=False)
    assert refused.value.text(flag) == ("this query (16 links) is large and its size cannot be estimated (fewer than three "
                                  "smaller sizes have chains); give --force to run it anyway")
    assert est.size_check(ChainQuery(1, 16), processes=2, count=False, table=False, force=True) is None
    # a table of 14 links is sized for its rows only: it runs when they cannot be estimated
    assert est.size_check(ChainQuery(1, 14), processes=2, count=False, table=True) is None
    assert asked == ["list", "list", "list"]


def test_a_table_of_more_than_a_million_rows_is_refused_even_when_forced(monkeypatch):
    asked = _given(monkeypatch, _estimate(1_000_001, 3400, 7200))
    for force in (False, True):
        with pytest.raises(QueryTooLarge) as refused:
            est.size_check(ChainQuery(1, 14), processes=2, count=False, table=True, force=force)
        assert refused.value.text(flag) == (
            "a table is held in memory to align it and this listing (14 links) is too large for one (about 1 000 001 "
            "chains in 3 400 units, 60 min on 2 workers, extrapolated from the exact counts at 10, 12, 14 links); "
            "use --format jsonl or csv (streamed), or --count")
    _given(monkeypatch, _estimate(1_000_000, 3400, 1200))  # 10 min on each worker: no note either
    assert est.size_check(ChainQuery(1, 14), processes=2, count=False, table=True) is None
    _given(monkeypatch, _estimate(1_000_001, 3400, 1200))
    assert est.size_check(ChainQuery(1, 16), processes=2, count=True, table=True) is None  # a count holds no rows
    assert asked == ["list", "list"]


@pytest.mark.parametrize("count, hint", [(True, " (with --checkpoint FILE it can be stopped and resumed)"),
                                         (False, "")])
def test_a_query_of_more_than_a_day_is_refused_unless_forced(monkeypatch, count, hint):
    _given(monkeypatch, _estimate(1.2e8, 5.6e5, 3 * 86400 + 1))
    with pytest.raises(QueryTooLarge) as refused:
        est.size_check(ChainQuery(1, 16), processes=3, count=count, table=False)
    assert refused.value.text(flag) == (
        "this query (16 links) is too large to run unasked: about 1.2e+08 chains in 560 000 units, 24.0 h on 3 "
        f"workers, extrapolated from the exact counts at 10, 12, 14 links; give --force to run it anyway{hint}")
    _given(monkeypatch, _estimate(1.2e8, 5.6e5, 3 * 86400))  # a day on each of the 3 workers: runs, with a note
    assert est.size_check(ChainQuery(1, 16), processes=3, count=count, table=False).startswith("a long query")


def test_the_work_timed_is_the_query_s_own(monkeypatch):
    asked = _given(monkeypatch, _estimate(5e7, 1e4, 1000))
    note = est.size_check(ChainQuery(1, 16), processes=1, count=False, table=False, mechanisms="mechanisms with input",
                          scheduler=True)
    assert asked == ["mechanisms with input"]
    assert note == ("a long query: about 5e+07 mechanisms in 10 000 units, 17 min on the scheduler's workers (one core "
                    "shown), extrapolated from the exact counts at 10, 12, 14 links")
    est.size_check(ChainQuery(1, 16), processes=1, count=True, table=False)
    assert asked[-1] == "count"


@pytest.mark.parametrize("seconds, noted", [(1200.0, False), (1202.0, True)])
def test_a_query_of_more_than_ten_minutes_says_so(monkeypatch, seconds, noted):
    _given(monkeypatch, _estimate(2e7, 1e4, seconds))
    note = est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False)
    assert note == ("a long query: about 2e+07 chains in 10 000 units, 10 min on 2 workers, extrapolated from the exact "
                    "counts at 10, 12, 14 links" if noted else None)


def test_a_plan_that_would_hold_too_much_memory_is_refused_unless_forced(monkeypatch):
    # 1.5 GiB over 2 workers at 400 B a unit (a count: the certificates met): 2 013 265.92 units of the largest code
    limit_units = 1.5 * 2**30 / 400 / 2
    _given(monkeypatch, _estimate(2e7, 1e6, 100.0, largest=math.floor(limit_units) + 1))
    with pytest.raises(QueryTooLarge) as refused:
        est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False)
    assert refused.value.text(flag) == (
        "this query (16 links) would hold too much memory to run unasked: its largest code has about 2 013 266 branch "
        "multigraphs, whose certificates are kept until the code is done: about 1.5 GiB on 2 workers (more than 1.5 "
        "GiB); about 2e+07 chains in 1 000 000 units, 50 s on 2 workers, extrapolated from the exact counts at 10, 12, "
        "14 links; give --force to run it anyway")
    _given(monkeypatch, _estimate(2e7, 1e6, 100.0, largest=math.floor(limit_units)))
    assert est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False).startswith("its largest code")


def test_a_listing_and_a_count_on_a_cluster_keep_whole_codes(monkeypatch):
    # 3 500 B a unit: 1.5 GiB over 2 workers is 230 087.5 units of the largest code
    _given(monkeypatch, _estimate(2e7, 1e6, 100.0, largest=230088))
    whole = ("its largest code has about 230 088 branch multigraphs, kept whole until the code is done: about 1.5 GiB "
             "on 2 workers")
    with pytest.raises(QueryTooLarge, match="too much memory to run unasked: " + whole):
        est.size_check(ChainQuery(1, 16), processes=2, count=False, table=False)
    assert est.size_check(ChainQuery(1, 16), processes=2, count=False, table=False, force=True) == whole
    with pytest.raises(QueryTooLarge, match="kept whole until the code is done: about 1.5 GiB on 2 workers"):
        est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False, scheduler=True)
    assert est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False) is None  # 0.17 GiB, streamed


@pytest.mark.parametrize("largest, noted", [(1342177, False), (1342178, True)])  # 1 GiB / 400 B / 2 = 1 342 177.28
def test_a_plan_of_more_than_a_gibibyte_says_so_with_a_long_query(monkeypatch, largest, noted):
    _given(monkeypatch, _estimate(2e7, 1e6, 4000.0, largest=largest))
    note = est.size_check(ChainQuery(1, 16), processes=2, count=True, table=False)
    long = ("a long query: about 2e+07 chains in 1 000 000 units, 33 min on 2 workers, extrapolated from the exact "
            "counts at 10, 12, 14 links")
    memory = (f"its largest code has about {largest // 10**6} {largest // 1000 % 1000:03} {largest % 1000:03} branch "
              f"multigraphs, whose certificates are kept until the code is done: about 1.0 GiB on 2 workers")
    assert note == (f"{long}; {memory}" if noted else long)


def test_plan_bytes_counts_each_worker_expanding_a_code():
    found = _estimate(1e6, 1e5, 10.0, largest=1000)
    assert est.plan_bytes(found, 1) == 3_500_000
    assert est.plan_bytes(found, 3) == 10_500_000
    assert est.plan_bytes(found, 3, streamed=True) == 1_200_000


@pytest.mark.parametrize("processes, wall", [(1, "3.2e+1992 years on 1 worker"), (2, "1.6e+1992 years on 2 workers")])
def test_a_query_beyond_floating_point_is_refused_with_its_size_from_the_logarithms(monkeypatch, processes, wall):
    # 10^2000 s on one worker: 10^(2000 − log10 31 557 600) = 10^1992.5009 years; on two, 10^1992.1998
    found = est.Estimate(math.inf, math.inf, math.inf, "exact counts at 10, 12, 14 links", 2100.3, 1500.0, 2000.0)
    _given(monkeypatch, found)
    with pytest.raises(QueryTooLarge) as refused:
        est.size_check(ChainQuery(1, 400), processes=processes, count=False, table=False)
    assert refused.value.text(flag) == (
        f"this query (400 links) is too large to run unasked: about 2e+2100 chains in 1e+1500 units, {wall}, "
        "extrapolated from the exact counts at 10, 12, 14 links; give --force to run it anyway")


def test_the_memory_limits_are_exclusive_and_one_worker_is_one(monkeypatch):
    # largest code units · 400 B · processes exactly at 1 GiB and at 1.5 GiB (exact in floating point)
    _given(monkeypatch, _estimate(2e7, 1e6, 100.0, largest=2**30 / 400))
    assert est.size_check(ChainQuery(1, 16), processes=1, count=True, table=False) is None  # 1 GiB: no note
    _given(monkeypatch, _estimate(2e7, 1e6, 100.0, largest=1.5 * 2**30 / 400))
    assert est.size_check(ChainQuery(1, 16), processes=1, count=True, table=False) == (
        "its largest code has about 4 026 532 branch multigraphs, whose certificates are kept until the code is done: "
        "about 1.5 GiB on 1 worker")  # 1.5 GiB: noted, not refused


def test_a_size_with_units_but_no_chains_is_no_point_of_the_ratio(monkeypatch):
    sizes = {**SIZES, 12: ([[0, 0], [0]], 0.0)}
    _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)).basis == "exact counts at 8, 10, 14 links"


def test_two_points_are_enough_to_predict_the_next_size_past_the_budget(monkeypatch):
    # only 10 and 12 have chains; 14 is predicted to take 0.5 · 6856/230 = 14.9 s: not started, so no estimate
    sizes = {**SIZES, 4: ([[]], 0.0), 6: ([[]], 0.0), 8: ([[]], 0.0), 10: ([[230]], 0.0), 12: (SIZES[12][0], 0.5)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)) is None
    assert 14 not in [run[0] for run in calibrations.runs]


def test_a_size_predicted_to_end_at_exactly_one_and_a_half_budgets_is_started(monkeypatch):
    # before 14: 1.0 s spent, 14 predicted at 0.5 · 400/100 = 2.0 s: 3.0 s in all, not more than 1.5 · 2 s
    sizes = {4: ([[1]], 0.0), 6: ([[10]], 0.0), 8: ([[50]], 0.0), 10: ([[100]], 0.5), 12: ([[400]], 0.5),
             14: ([[1000]], 0.0)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)).basis == "exact counts at 10, 12, 14 links"
    assert calibrations.runs[-1][0] == 14


def test_past_the_budget_no_size_is_started_even_a_quick_one(monkeypatch):
    # 4 links take 2.1 s: 6 is not started, though the later sizes take no time at all
    sizes = {**SIZES, 4: ([[1]], 2.1), 10: (SIZES[10][0], 0.0), 12: (SIZES[12][0], 0.0)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)) is None
    assert [run[0] for run in calibrations.runs] == [4]


def test_a_budget_spent_exactly_is_not_past(monkeypatch):
    sizes = {**SIZES, 4: ([[1]], 2.0), 10: (SIZES[10][0], 0.0), 12: (SIZES[12][0], 0.0)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)).basis == "exact counts at 10, 12, 14 links"
    assert len(calibrations.runs) == 6


def test_sizes_without_chains_are_tried_up_to_64_links_past_the_budget(monkeypatch):
    # h = 2: every size from 2 links; none has chains and the first takes the whole budget
    sizes = {n: ([[]], 3.0 if n == 2 else 0.0) for n in range(2, 70)}
    calibrations = _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 70, h=2)) is None
    assert calibrations.planned == list(range(2, 65))


def test_the_largest_calibration_of_one_unit_gives_units_from_one(monkeypatch):
    sizes = {**SIZES, 10: ([[230]], 0.0), 12: ([[6856]], 0.0), 14: ([[318162]], 0.0)}
    _Calibrations(monkeypatch, sizes)
    found = est.estimate(ChainQuery(1, 16))
    assert found.units == 1.0 and found.log10_units == 0.0 and found.largest_code_units == 1.0


def test_a_falling_ratio_is_not_extrapolated_downwards(monkeypatch):
    # ratios 10 then 5: the change −5 is clipped to 0, so the ratio stays 5
    sizes = {**SIZES, 10: ([[100]], 0.0), 12: ([[1000]], 0.0), 14: ([[5000]], 0.0)}
    _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)).chains == pytest.approx(25000, rel=1e-12)


@pytest.mark.parametrize("units, expected", [
    ((1, 1, 3), 3 * (3 + 2)),      # ratios 1 then 3: the next 3 + 2
    ((2, 4, 12), 12 * (3 + 1)),    # ratios 2 then 3: the next 3 + 1
])
def test_the_units_ratio_is_extrapolated_like_the_chains(monkeypatch, units, expected):
    sizes = {**SIZES, **{n: ([[1] * u], 0.0) for n, u in zip((10, 12, 14), units)}}
    _Calibrations(monkeypatch, sizes)
    assert est.estimate(ChainQuery(1, 16)).units == pytest.approx(expected, rel=1e-12)


def test_the_sizes_of_a_query_are_shared_by_its_larger_sizes(monkeypatch):
    calibrations = _Calibrations(monkeypatch, {**SIZES, 14: (SIZES[14][0], 0.0), 16: ([[10**7]], 0.0)})
    est.estimate(ChainQuery(1, 16))
    est.estimate(ChainQuery(1, 18))  # 4 … 14 links again: read back, only 16 counted
    assert [run[0] for run in calibrations.runs] == [4, 6, 8, 10, 12, 14, 16]


def test_powers_of_ten_beyond_floating_point_are_infinite():
    assert est._power(307.5) == pytest.approx(10**307.5, rel=1e-12)
    assert est._power(308.5) == math.inf  # (10.0 ** 308.5 overflows)
    assert est._power(5000.0) == math.inf


def test_a_real_calibration_times_the_units_whose_chains_it_visits(monkeypatch):
    """Run for real (14 links, 8 … 12 counted): a count's units are counted by stage B's tight count,
    none visited; a listing's are visited chain by chain, a share of the size's CPU seconds (stage A
    and the plan take the rest)."""
    monkeypatch.setattr(est, "_COUNTED", {})
    found = est.estimate(ChainQuery(1, 14))
    points = {n: point for (_, n), point in est._COUNTED.items()}
    assert found.basis == "exact counts at 8, 10, 12 links" and points[12][1:3] == (6856, 104)
    assert [points[n][5] for n in (8, 10, 12)] == [0.0, 0.0, 0.0]
    est.estimate(ChainQuery(1, 14), work="list")
    listed = {n: point for ((_, work, _), n), point in est._COUNTED.items() if work == "list"}
    assert listed[12][1:3] == (6856, 104) and 0.0 < listed[12][5] <= listed[12][3]


#: h = 4: a loop adds three links; sizes 5 … 17 as the 1-DOF counts (1, 3, 42, 1 798, 156 275 chains)
SIZES_H4 = {5: ([[1]], 0.0), 8: ([[3]], 0.0), 11: ([[40, 2]], 0.0), 14: ([[1000, 798], [0]], 0.01),
            17: ([[100000, 56275], [0, 0]], 0.1, 0.08, True)}


@pytest.mark.parametrize("links, compiled", [(23, True), (17 + 3, False)])
def test_a_unit_s_time_grows_by_h_s_factor_a_loop_on_the_compiled_path_only(monkeypatch, links, compiled):
    """h = 4: 0.1 s over 4 units at 17 links, all counted without visiting, 2.34 times more a unit
    each loop (three links) beyond on the compiled path (where the factor was measured); not at all
    off it (the path of a query below the kernel's loops, here forced)."""
    _Calibrations(monkeypatch, SIZES_H4)
    if not compiled:
        monkeypatch.setattr(stage_a, "kernel_loops", lambda conv, multiple=False: 99)
    found = est.estimate(ChainQuery(1, links, h=4))
    assert found.basis == "exact counts at 11, 14, 17 links"
    steps = (links - 17) // 3
    assert found.seconds == pytest.approx(found.units * 0.1 / 4 * (2.34 if compiled else 1.0) ** steps, rel=1e-12)
