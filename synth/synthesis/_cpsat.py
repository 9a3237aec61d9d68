"""Small shared helpers around OR-Tools CP-SAT: the ``cp_model`` module, every solution of a model.

Only the modules that build a CP-SAT model import this one, inside the function that builds it, so
a command that runs no solver (``balance``, ``draw``, ``identify`` of a chain) never loads OR-Tools
(nor the pandas it imports, ≈ 0.3 s).  The engine calls OR-Tools' PEP 8 API only (``new_int_var``,
``add``, ``solve`` …; the solution callback reads values by index through ``SolutionIntegerValue``,
the callback base class's own accessor); ``tests/synthesis/test_cpsat_api.py`` runs every model the
engine builds with OR-Tools' deprecation warnings turned into errors.
"""

from __future__ import annotations

from collections.abc import Sequence

from ortools.sat.python import cp_model

from ..execution.interrupt import solve_stoppably

__all__ = ["cp_model", "all_solutions", "each_solution"]


class _Batches(cp_model.CpSolverSolutionCallback):
    """Hands the solutions to ``fn`` in batches of ``size`` (so a long enumeration holds one batch)."""

    def __init__(self, variables: Sequence[cp_model.IntVar], fn, size: int):
        super().__init__()
        self._index = [x.index for x in variables]
        self._fn, self._size = fn, size
        self.batch: list[tuple[int, ...]] = []

    def on_solution_callback(self) -> None:
        self.batch.append(tuple(map(self.SolutionIntegerValue, self._index)))
        if len(self.batch) >= self._size:
            self._fn(self.batch)
            self.batch = []


class _Collector(cp_model.CpSolverSolutionCallback):
    """Keeps each solution's values of ``variables``, read by index (``Value`` per variable
    costs about a tenth of stage B's time at 12–14 links)."""

    def __init__(self, variables: Sequence[cp_model.IntVar], limit: int | None, tick=None):
        super().__init__()
        self._index = [x.index for x in variables]
        self._limit = limit
        self._tick = tick
        self.solutions: list[tuple[int, ...]] = []

    def on_solution_callback(self) -> None:
        self.solutions.append(tuple(map(self.SolutionIntegerValue, self._index)))
        if self._limit is not None and len(self.solutions) >= self._limit:
            self.stop_search()
        if self._tick is not None and len(self.solutions) % 1024 == 0:
            self._tick(1024)


def all_solutions(
    model: cp_model.CpModel,
    variables: Sequence[cp_model.IntVar],
    *,
    limit: int | None = None,
    time_limit: float | None = None,
    fixed_search: bool = False,
    tick=None,
) -> list[tuple[int, ...]]:
    """Every solution of ``model`` projected on ``variables`` (single worker, exhaustive).

    With ``fixed_search`` the solver branches on ``variables`` in their order, least value
    first, instead of its own choice (adds a decision strategy to ``model``).  ``tick(k)`` is
    called each time k more solutions are found (a progress bar).  Ctrl-C stops the search
    within milliseconds (KeyboardInterrupt), however long it runs without a solution.

    Raises ``RuntimeError`` if the search could not be completed (time limit, model
    invalid), so that a partial enumeration is never returned silently.

    Example
    -------
    >>> m = cp_model.CpModel(); x = m.new_int_var(0, 2, "x")
    >>> sorted(all_solutions(m, [x]))
    [(0,), (1,), (2,)]
    """
    solver = _solver(model, variables, time_limit, fixed_search)
    collector = _Collector(variables, limit, tick)
    status = solve_stoppably(solver, model, collector)
    complete = status in (cp_model.OPTIMAL, cp_model.INFEASIBLE)
    if not complete and not (limit is not None and len(collector.solutions) >= limit):
        raise RuntimeError(f"CP-SAT stopped before the enumeration was complete ({solver.status_name(status)})")
    return collector.solutions


def each_solution(model: cp_model.CpModel, variables: Sequence[cp_model.IntVar], fn, *, batch: int = 4096,
                  fixed_search: bool = False) -> None:
    """Call ``fn`` with every solution of ``model`` projected on ``variables``, a list of up to
    ``batch`` at a time, in the order of :func:`all_solutions`: an enumeration whose solutions
    are many (stage A of the largest codes) holds one batch at a time.

    >>> m = cp_model.CpModel(); x = m.new_int_var(0, 4, "x"); seen = []
    >>> each_solution(m, [x], seen.append, batch=2); [len(b) for b in seen]
    [2, 2, 1]
    """
    solver = _solver(model, variables, None, fixed_search)
    collector = _Batches(variables, fn, batch)
    status = solve_stoppably(solver, model, collector)
    if status not in (cp_model.OPTIMAL, cp_model.INFEASIBLE):
        raise RuntimeError(f"CP-SAT stopped before the enumeration was complete ({solver.status_name(status)})")
    if collector.batch:
        fn(collector.batch)


def _solver(model, variables, time_limit: float | None, fixed_search: bool):
    solver = cp_model.CpSolver()
    solver.parameters.enumerate_all_solutions = True
    solver.parameters.num_workers = 1
    # Pure enumeration of small models: presolve, symmetry detection, probing and the LP
    # relaxation cost more than they save (12-link synthesis: CP-SAT time 2.5 s -> 0.34 s).
    solver.parameters.linearization_level = 0
    solver.parameters.cp_model_presolve = False
    solver.parameters.symmetry_level = 0
    solver.parameters.cp_model_probing_level = 0
    solver.parameters.catch_sigint_signal = False  # Ctrl-C belongs to the caller (KeyboardInterrupt)
    if time_limit is not None:
        solver.parameters.max_time_in_seconds = time_limit
    if fixed_search:
        model.add_decision_strategy(variables, cp_model.CHOOSE_FIRST, cp_model.SELECT_MIN_VALUE)
        solver.parameters.search_branching = cp_model.FIXED_SEARCH
    return solver
