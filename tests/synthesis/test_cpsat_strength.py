"""Every solution of a CP-SAT model, against the solutions counted by brute force: the projection,
the fixed search's order, the limit, the progress ticks, the batches, and the refusal of an
enumeration that did not finish.
"""

from __future__ import annotations

import itertools

import pytest

from synth.synthesis._cpsat import _solver, all_solutions, cp_model, each_solution


def _sum_model(total=5, top=4, count=3, free=False):
    """count variables in 0..top adding up to total (and one more, free in 0..1)."""
    m = cp_model.CpModel()
    xs = [m.new_int_var(0, top, f"x{i}") for i in range(count)]
    other = m.new_int_var(0, 1, "free") if free else None
    m.add(sum(xs) == total)
    return m, xs, other


def _brute(total=5, top=4, count=3):
    return [t for t in itertools.product(range(top + 1), repeat=count) if sum(t) == total]


def test_every_solution_projected_on_the_variables():
    m, xs, _ = _sum_model()
    assert sorted(all_solutions(m, xs)) == _brute()
    m, xs, free = _sum_model(free=True)
    assert sorted(all_solutions(m, xs + [free])) == sorted(t + (f,) for t in _brute() for f in (0, 1))
    m, xs, free = _sum_model(free=True)  # a solution of the model per value of the free variable, each projected
    assert sorted(all_solutions(m, xs)) == sorted(_brute() * 2)


def test_the_fixed_search_lists_the_solutions_in_lexicographic_order():
    m, xs, _ = _sum_model()
    assert all_solutions(m, xs, fixed_search=True) == _brute()  # itertools.product's order: least value first
    m, xs, _ = _sum_model()
    assert all_solutions(m, xs[::-1], fixed_search=True) == sorted(t[::-1] for t in _brute())


def test_a_limit_stops_the_search_after_that_many_solutions():
    for limit in (1, 2, 18):
        m, xs, _ = _sum_model()
        found = all_solutions(m, xs, limit=limit, fixed_search=True)
        assert found == _brute()[:limit]
    m, xs, _ = _sum_model()
    assert sorted(all_solutions(m, xs, limit=1000)) == _brute()  # more than there are: all of them


def test_an_infeasible_model_has_no_solution_and_is_no_error():
    m, xs, _ = _sum_model(total=13)
    assert all_solutions(m, xs) == []
    seen = []
    m, xs, _ = _sum_model(total=13)
    each_solution(m, xs, seen.append)
    assert seen == []


def test_an_enumeration_stopped_by_its_time_limit_is_an_error_not_a_partial_list():
    m = cp_model.CpModel()
    xs = [m.new_int_var(0, 9, f"x{i}") for i in range(6)]  # 10^6 solutions: seconds, not 0.05 s
    with pytest.raises(RuntimeError, match=r"^CP-SAT stopped before the enumeration was complete \(FEASIBLE\)$"):
        all_solutions(m, xs, time_limit=0.05)
    m = cp_model.CpModel()
    xs = [m.new_int_var(0, 9, f"x{i}") for i in range(6)]
    assert len(all_solutions(m, xs, time_limit=0.05, limit=3)) == 3  # a limit reached is complete enough


def test_an_invalid_model_is_an_error():
    for run in (lambda m, x: all_solutions(m, [x]), lambda m, x: each_solution(m, [x], print)):
        m = cp_model.CpModel()
        x = m.new_int_var(0, 3, "x")
        m.add_division_equality(x, x, 0)  # division by zero: MODEL_INVALID
        with pytest.raises(RuntimeError, match=r"\(MODEL_INVALID\)$"):
            run(m, x)


def test_ticks_count_the_solutions_in_steps_of_1024():
    m = cp_model.CpModel()
    x = m.new_int_var(0, 3000, "x")
    ticks = []
    assert len(all_solutions(m, [x], tick=ticks.append)) == 3001
    assert ticks == [1024, 1024]
    m = cp_model.CpModel()
    x = m.new_int_var(0, 1022, "x")
    all_solutions(m, [x], tick=ticks.append)
    assert ticks == [1024, 1024]  # 1023 solutions: no step completed


@pytest.mark.parametrize("batch, sizes", [(4, [4, 4, 4, 4, 2]), (6, [6, 6, 6]), (18, [18]), (100, [18]), (1, [1] * 18)])
def test_each_solution_hands_over_batches_in_the_order_of_all_solutions(batch, sizes):
    m, xs, _ = _sum_model()
    seen = []
    each_solution(m, xs, lambda b: seen.append(list(b)), batch=batch, fixed_search=True)
    assert [len(b) for b in seen] == sizes
    assert [t for b in seen for t in b] == _brute()


def test_each_solution_keeps_no_batch_it_handed_over():
    m, xs, _ = _sum_model()
    seen = []
    each_solution(m, xs, seen.append, batch=4, fixed_search=True)
    assert [t for b in seen for t in b] == _brute()  # each batch a new list: none refilled after handing over


def test_the_solver_leaves_ctrl_c_to_the_caller():
    m, xs, _ = _sum_model()
    solver = _solver(m, xs, None, False)
    assert solver.parameters.catch_sigint_signal is False  # KeyboardInterrupt, not CP-SAT's own handler
    assert solver.parameters.enumerate_all_solutions and solver.parameters.num_workers == 1
    assert _solver(m, xs, 2.5, False).parameters.max_time_in_seconds == 2.5


def test_a_tick_comes_at_exactly_1024_solutions():
    m = cp_model.CpModel()
    x = m.new_int_var(0, 1023, "x")
    ticks = []
    all_solutions(m, [x], tick=ticks.append)
    assert ticks == [1024]


def test_the_default_batch_is_4096_solutions():
    m = cp_model.CpModel()
    x = m.new_int_var(0, 4999, "x")
    seen = []
    each_solution(m, [x], lambda b: seen.append(len(b)))
    assert seen == [4096, 904]


def test_the_model_gets_a_search_strategy_only_when_the_fixed_search_is_asked():
    for run in (lambda m, xs: all_solutions(m, xs), lambda m, xs: each_solution(m, xs, list)):
        m, xs, _ = _sum_model()
        run(m, xs)
        assert len(m.proto.search_strategy) == 0  # the caller's model is left as it was
    m, xs, _ = _sum_model()
    all_solutions(m, xs, fixed_search=True)
    assert len(m.proto.search_strategy) == 1
