"""How big a chain query is before it runs: chains, units and time, extrapolated from exact counts.

Method
------
The same query (same W, v, conventions and requirements) is counted exactly at the
smaller link counts n − 2k, smallest first, in this process, until about ``budget``
CPU seconds have been spent (CPU, not wall: a loaded machine sizes a query as a quiet one does;
never at n itself, and never a size predicted to end later than one and a half budgets).  From the last three sizes with chains,
the growth ratio r(n) = chains(n) / chains(n − 2) is extrapolated *linearly*:
r(n + 2) = r(n) + (r(n) − r(n − 2)); chains and units are multiplied by it step by step.
Time is measured in two parts at the largest calibration size, each scaled by what it grows
with: the CPU seconds of the units whose chains were visited one by one (stage B's search with
multiple joints, a listing, the mechanisms) per chain, times the
chains; and the rest per unit, times the units: number synthesis, stage A, the plan, and stage B
where it counts a unit's placements without visiting them (the programme of every unit of simple
joints, benchmarks/PROFILE.md sections 27 and 37, whose cost does not grow with the unit's chains)
or finds none.  A unit's own time grows with its branch multigraph past
the calibration sizes (:data:`UNIT_GROWTH`, a factor a loop).  The calibrations run on the path
the query will take (the compiled searches of stages A and B when the query is large enough for
them, however small the calibration sizes are), with the engine of the day, so the estimate
follows every change of speed.  Numba's compiling (a cold cache: a fresh checkout, or a kernel's
first call with new types) is left out of every calibration's time and of the budget
(:class:`_CompileClock`): it is paid once, not per unit, and once counted it stopped the sizing of
the 12-link h = 2 query at 6 links, 8 times under in chains and 100 times over in time.

For 1-DOF chains the ratio grows by 15–16 a step from 10 links on (2, 8, 14.4, 29.8, 46.4,
62.3, 77.5 up to 18 links), so from the counts at 8, 10 and 12 links the estimate is
−2.5 % at 14 links, −5.0 % at 16 and −6.7 % at 18 against the published counts (318 162,
19 819 281, 1 535 380 884).  The time, against the count's CPU in one process (section 29):
+22 % at 16 links, −11 % at 18 (188 against 212 CPU s; +1 % against the 186.5 CPU s of the
whole 2-worker command on a quiet machine), 0.6 against 0.40–0.51 s at 14 links.

With multiple joints the counts grow faster and less regularly (1-DOF, v up to n − 2: 1, 4, 60,
2 645, 248 203, 35 396 111 at 4 … 14 links; ratios 4, 15, 44.1, 93.8, 142.6, whose steps 11, 29.1,
49.7, 48.8 settle only from 10 links on), so a basis that ends at 10 links is far off: from 6, 8, 10
links the estimate is −22 % at 12 links and −44 % at 14, from 8, 10, 12 links +0.6 % at 14.  Such a
query is therefore sized for :data:`MULTIPLE_BUDGET` CPU seconds, which reach 12 links (about 6 s)
when the query has 14 links or more (benchmarks/PROFILE.md, section 28).

Example
-------
>>> from synth.structure.query import ChainQuery
>>> e = estimate(ChainQuery(1, 16))
>>> 1.5e7 < e.chains < 2.5e7, e.basis.startswith("exact counts at ")   # 8, 10, 12 or 10, 12, 14 (the budget)
(True, True)
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

from ..errors import ImpossibleParameters, QueryTooLarge, option
from ..execution.sizes import describe_seconds, magnitude

__all__ = ["BUDGET", "MULTIPLE_BUDGET", "UNIT_GROWTH", "Estimate", "estimate", "worth_sizing", "sized_loops", "size_check",
           "describe_estimate", "plan_bytes", "TABLE_ROWS", "MEMORY_LIMIT", "NOTE_SECONDS", "BYTES_PER_UNIT",
           "CERTIFICATE_BYTES", "FLOOR_SECONDS", "PLAIN_MARGIN", "needs_compiled", "time_to_go_from"]

# Queries at least this large (loops K of their largest skeleton, one fewer with multiple joints:
# they grow faster) are sized before they run: the first sized size takes tens of CPU seconds,
# in which the two-second sizing is small.  A loop of the plane adds two links, one of h = 2 a
# single link, so in loops h = 2 grows far more slowly (K = 8, 10 links: 110 132 chains, 5 CPU s,
# where sizing took 0.5 s; K = 9, 11 links: 61 CPU s, as the plane's K = 7, 16 links, takes 51).
SIZED_LOOPS = {2: 9, None: 7}
BUDGET = 2.0  # CPU seconds of exact counts a query is sized from (the module's Method)
MULTIPLE_BUDGET = 8.0  # … with multiple joints: 1-DOF, the 12-link count (5.6 CPU s) after 4 … 10 links (0.17 s)
LIMIT_SECONDS = 86400.0  # refused without force when estimated to take longer (wall, on the workers)
TABLE_ROWS = 1_000_000  # a table is held in memory to align its columns: refused above this
NOTE_SECONDS = 600.0  # a query estimated to take longer says so before it starts
# The time of one unit (stage A, the plan, stage B's count without visiting) grows with its branch
# multigraph from 16 links on, past every calibration: 1-DOF counts in one process (the engine of
# 29 Nov 2026 after PROFILE.md section 27, `time.process_time`, the shared 2-core machine at nice 10)
# took 0.49 ms a unit at 14 and at 16 links and 0.80 at 18 (stage A 0.13, 0.18, 0.36 ms), a factor of
# 1.27 a loop from 14 to 18 links.  With h = 2 it falls instead (0.28, 0.27, 0.22 ms at 8, 9, 10 links),
# and for h = 4, 5, 6 it grows faster (benchmarks/PROFILE.md section 33: every unit counted without
# visiting; one process; each factor from the sizing's largest calibration to the largest count run):
# 0.76 → 4.17 ms a unit from 17 to 23 links at h = 4, 1.89 → 23.2 from 18 to 26 at h = 5, 1.06 → 25.4
# from 17 to 27 at h = 6.  Measured on the compiled path (every sized query takes it) and applied
# there only; h ≥ 7 was not measured: no growth there.
UNIT_GROWTH = {3: 1.27, 4: 2.34, 5: 3.50, 6: 4.89}  # factor a loop on a unit's time beyond the largest calibration, by h
# A listing (and a count on a Dask cluster) keeps every branch multigraph of a code until the code is
# done (its output is in the order of their certificates), and its units travel whole to the parent:
# about this many bytes per unit of the largest code, for each worker expanding a code at the same time
# (h = 2, 10 links: a unit is 830 B held and 480 B pickled; 11 links: 715 MiB peak for the three
# processes, about 150 MiB each at rest, against about 38 000 units in the largest code: 3.5 kB a unit
# per worker).
BYTES_PER_UNIT = 3500
# A count on this machine hands a code's units on as stage A finds them (a window at a time, through a
# file: type_synthesis.UNIT_WINDOW) and keeps only the certificates it has met, as bytes (the rows of the
# strings' vertices), to tell the next ones apart: at most this many bytes per unit of the largest code,
# per worker expanding one (18 links, 78300000/0: 144-byte rows, 236 B a unit with the set's table;
# 20 links, 7.10.3.0.0.0.0.0.0/0: 168-byte rows, about 270 B).
CERTIFICATE_BYTES = 400
NOTE_BYTES = 2**30  # a query whose plan may hold more says so before it starts
# refused without force above this: with the processes' own 150-250 MiB each (numpy, numba's kernels,
# nauty), a run of 2 workers stays within 2 GiB
MEMORY_LIMIT = 1.5 * 2**30
# A query on the compiled path is sized first on the plain one (``estimate(plain=True)``), which compiles nothing
# (numba's compiling of the kernels, some 25 CPU s on a cold cache, came before every refusal). Its counts are the
# compiled path's (chains, units, the largest code's units: the same units, searched otherwise); its time is not
# (the plain search: 20 links counted in 2.1e6 CPU s against 4 063), so it gives a floor of the time instead: this
# many CPU seconds a unit, and a chain or mechanism visited one by one, over a hundred times under every rate
# measured on the compiled path (0.28 to 25 ms a unit, PROFILE.md sections 27 and 33; 22 µs a mechanism counted
# at 20 links).  A refusal on the plain estimate asks its counts to pass the limits PLAIN_MARGIN times over (an
# extrapolation from smaller sizes: 8, 10, 12 links against the compiled path's 10, 12, 14); what it does not
# refuse is sized again on the compiled path, as before.
FLOOR_SECONDS = 1e-7
PLAIN_MARGIN = 2.0


@dataclass(frozen=True)
class Estimate:
    """Extrapolated size of a query: chains, units, one-core seconds, and the sizes it rests on.

    ``chains``, ``units`` and ``seconds`` are ``math.inf`` beyond floating point; their
    base-10 logarithms (``log10_*``) are always finite.
    """

    chains: float
    units: float
    seconds: float
    basis: str
    log10_chains: float = 0.0
    log10_units: float = 0.0
    log10_seconds: float = 0.0
    largest_code_units: float = 0.0  # units of the code with the most: its share of the units at the basis
    floor: bool = False  # ``seconds`` is a floor of the time (the plain path's estimate: :data:`FLOOR_SECONDS`)


class _CompileClock:
    """CPU seconds of this process without numba's compiling (a cold cache, or a kernel's first call
    with new types): what a calibration costs once the kernels are compiled, as the query's workers
    have them.  Install it with ``numba.core.event.install_listener("numba:compile", clock)``; a
    compile nested in another is counted once.

    >>> clock = _CompileClock()
    >>> clock.on_start(None); clock.on_start(None); clock.on_end(None); clock.on_end(None)
    >>> 0.0 <= clock.compiling < 0.01, clock() <= time.process_time()
    (True, True)
    """

    def __init__(self):
        self.compiling = 0.0  # CPU seconds spent compiling so far
        self._depth = 0
        self._started = 0.0

    def on_start(self, event):
        if not self._depth:
            self._started = time.process_time()
        self._depth += 1

    def on_end(self, event):
        self._depth -= 1
        if not self._depth:
            self.compiling += time.process_time() - self._started

    def notify(self, event):  # numba's Listener protocol
        (self.on_start if event.is_start else self.on_end)(event)

    def __call__(self) -> float:
        return time.process_time() - self.compiling


@dataclass
class _TimedWork:
    """A unit work (``count_unit``, ``run_unit``, …) that adds up the CPU seconds it takes: the
    calibrations run inline, so its total is the units' own share of a size's time.  ``visited``
    is the share of the units whose chains were visited one by one (a search or a listing found
    some: their time grows with the chains); the others were counted without visiting them
    (stage B's tight count, ``stats["tight"]``) or found none, and their time is the unit's."""

    work: object
    clock: object = time.process_time  # CPU seconds, numba's compiling left out (:class:`_CompileClock`)
    seconds: float = 0.0
    visited: float = 0.0

    def __call__(self, unit):
        stats: dict = {}
        t0 = self.clock()
        result = self.work(unit, stats=stats)
        spent = self.clock() - t0
        self.seconds += spent
        if not stats.get("tight") and (sum(result.values()) if isinstance(result, dict) else len(result)):
            self.visited += spent
        return result


_COUNTED: dict = {}  # (query without links, work), links -> its calibration: several cells of a grid share them
_NEVER = 10**6  # kernel_loops for "never": the plain searches at every size


def _power(log10: float) -> float:
    return 10.0 ** log10 if log10 < 308 else math.inf


def _log10_growth(ratio: float, step: float, steps: int) -> float:
    """log10 of Π_{k=1}^{steps} (ratio + k·step): the factor the linear ratio extrapolation applies.

    >>> round(10 ** _log10_growth(2.0, 1.0, 3))  # 3 · 4 · 5
    60
    """
    if steps <= 0:
        return 0.0
    if step <= 0:
        return steps * math.log10(ratio)
    start = ratio / step  # Π (ratio + k·step) = step^steps · Γ(start + steps + 1) / Γ(start + 1)
    return steps * math.log10(step) + (math.lgamma(start + steps + 1) - math.lgamma(start + 1)) / math.log(10)


def _multiple(query) -> bool:
    return query.v is not None and (query.v[1] is None or query.v[1] > 0)


def needs_compiled(query) -> bool:
    """Whether ``query`` runs the compiled searches (and :func:`estimate` times them, compiling them first on a
    cold cache).

    >>> from synth.structure.query import ChainQuery
    >>> needs_compiled(ChainQuery(1, 12)), needs_compiled(ChainQuery(1, 14))
    (False, True)
    """
    from . import type_synthesis as ts
    from .stage_a import kernel_loops

    return query.loops >= kernel_loops(ts._conventions(query), _multiple(query))


def estimate(query, *, budget: float | None = None, work: str = "count", plain: bool = False) -> Estimate | None:
    """Estimate a :class:`~synth.structure.query.ChainQuery` (with ``links``; not its code).

    Only sizes below ``links`` with the same number of loops modulo one (n − (h − 1)·k) are
    counted (the query itself never is), for about ``budget`` seconds (None: :data:`BUDGET`, or
    :data:`MULTIPLE_BUDGET` where the query takes multiple joints); the time taken does not
    grow with ``links``.  ``work`` is what the query does with each unit, timed the same way:
    ``"count"`` its chains, ``"list"`` them (each chain built), ``"mechanisms"`` or
    ``"mechanisms with input"`` count its mechanisms (then ``chains`` counts mechanisms).
    With ``plain``, the calibrations run with the compiled searches off (nothing is compiled) and the
    time is a floor (``floor``: :data:`FLOOR_SECONDS` a unit, and a chain visited where ``work`` visits
    them or the query has multiple joints).
    Returns None when fewer than three smaller sizes have chains (no basis for a ratio).
    """
    from . import type_synthesis as ts
    from .stage_b import load_kernel

    conv = ts._conventions(query)
    multiple = _multiple(query)
    if budget is None:
        budget = MULTIPLE_BUDGET if multiple else BUDGET
    # the calibrations run on the path the query will take: compiled searches for a large query
    compiled = not plain and needs_compiled(query)
    if compiled:
        load_kernel()  # before the clock, as the query loads it before its workers start
    from . import _cpsat  # noqa: F401 - the solver's import (≈ 0.3 s, pandas) is the query's, not a calibration's
    from numba.core import event  # (numba's import, like the solver's, is the query's)

    event.Listener.register(_CompileClock)  # numba's listeners are its Listener's (virtual) subclasses
    clock = _CompileClock()  # a kernel compiled in a calibration (a cold cache) is the query's cost, not the calibration's
    with event.install_listener("numba:compile", clock):
        found = _extrapolated(query, _calibrations(query, conv, work, budget, compiled, clock), compiled)
    if found is None or not plain:
        return found
    visited = work != "count" or multiple
    log_floor = math.log10(FLOOR_SECONDS) + (max(found.log10_units, found.log10_chains) if visited else found.log10_units)
    return replace(found, seconds=_power(log_floor), log10_seconds=log_floor, floor=True)


def _calibrations(query, conv, work: str, budget: float, compiled: bool, clock) -> list:
    """The exact counts of :func:`estimate`'s smaller sizes, (links, chains, units, seconds, units of the
    largest code, seconds of the units visited one by one), timed on ``clock``, for about ``budget`` seconds."""
    from . import type_synthesis as ts

    unit_work = {"count": ts.count_unit, "list": ts.run_unit, "mechanisms": ts._MechanismCount(False),
                 "mechanisms with input": ts._MechanismCount(True)}[work]
    links = query.links
    step = query.h - 1
    same = repr(query.to_dict() | {"links": None}), work, compiled  # the calibrations several grid cells share
    start = clock()
    points = []  # (links, chains, units, seconds)
    for n in range(links - step * ((links - 2) // step), links, step):  # the query's sizes, smallest first
        if clock() - start > budget and (points or n > 64):
            break
        elapsed = clock() - start
        if len(points) >= 2 and elapsed + points[-1][3] * points[-1][1] / points[-2][1] > 1.5 * budget:
            break  # the next size would overrun the budget by half
        if (same, n) not in _COUNTED:
            t0 = clock()
            try:
                jobs = ts.plan_jobs(query.with_options(links=n))
            except ImpossibleParameters:
                continue
            # the compiled searches from one loop on, or never (the plain path: below its threshold a query takes it)
            jobs = [(code, replace(conv, kernel_loops=1 if compiled else _NEVER)) for code, conv in jobs]
            chains = units = largest = 0
            timed = _TimedWork(unit_work, clock)
            for _, unit, result in ts._map_units(timed, jobs, 1, False):
                if unit is not None:
                    chains += len(result) if isinstance(result, list) else sum(result.values())
                    units += 1
                else:  # a code is complete: result is its number of units
                    largest = max(largest, result)
            _COUNTED[same, n] = (n, chains, units, clock() - t0, largest, timed.visited)
        if _COUNTED[same, n][1]:
            points.append(_COUNTED[same, n])
    return points


def _extrapolated(query, points: list, compiled: bool) -> Estimate | None:
    """:func:`estimate`'s extrapolation from its calibrations ``points`` (None: fewer than three); a unit's
    time grows by :data:`UNIT_GROWTH` on the ``compiled`` path, where it was measured."""
    links = query.links
    step = query.h - 1
    if len(points) < 3:
        return None
    (_, c0, u0, *_), (_, c1, u1, *_), (n2, c2, u2, s2, l2, w2) = points[-3:]
    steps = (links - n2) // step
    r_c, d_c = c2 / c1, max(c2 / c1 - c1 / c0, 0.0)
    r_u, d_u = max(u2 / max(u1, 1), 1.0), max(u2 / max(u1, 1) - u1 / max(u0, 1), 0.0)
    log_chains = math.log10(c2) + _log10_growth(r_c, d_c, steps)
    log_units = math.log10(max(u2, 1)) + _log10_growth(r_u, d_u, steps)
    # the largest code's share of the units changes slowly (h = 2: 0.21, 0.16, 0.13, 0.12 at 7 … 10 links),
    # so it is kept from the largest calibration (the ratio of its own growth swings with the basis)
    log_largest = log_units + math.log10(max(l2, 1) / max(u2, 1))
    # the largest calibration's time: the work of the units whose chains were visited per chain times the
    # chains, the rest (stage A, the plan, the units counted without visiting) per unit, grown by
    # UNIT_GROWTH a loop, times the units
    parts = [log_chains + math.log10(w2 / c2)] if w2 > 0 else []
    log_growth = steps * math.log10(UNIT_GROWTH.get(query.h, 1.0) if compiled else 1.0)
    parts += [log_units + math.log10((s2 - w2) / max(u2, 1)) + log_growth] if s2 > w2 else []
    top = max(parts, default=log_chains - 9.0)  # (no time measured at all: a nanosecond a chain)
    log_seconds = top + math.log10(sum(10.0 ** (part - top) for part in parts) or 1.0)
    basis = "exact counts at " + ", ".join(str(p[0]) for p in points[-3:]) + " links"
    return Estimate(_power(log_chains), _power(log_units), _power(log_seconds), basis,
                    log_chains, log_units, log_seconds, _power(log_largest))


def worth_sizing(query, *, table: bool = False) -> bool:
    """Whether a query is large enough to be estimated before it runs: its largest revolute
    skeleton has :func:`sized_loops` loops or more — one fewer for a listing as a ``table``, which
    holds its rows (the mechanisms of 14 links are 4.3 million).

    >>> from synth.structure.query import ChainQuery
    >>> worth_sizing(ChainQuery(1, 14)), worth_sizing(ChainQuery(1, 16)), worth_sizing(ChainQuery(1, 10, h=2))
    (False, True, False)
    >>> worth_sizing(ChainQuery(1, 14), table=True), worth_sizing(ChainQuery(1, 12), table=True)
    (True, False)
    """
    if query.code is not None:
        return False
    K = max((query.links - 1 - query.dof + k) // (query.h - 1) for k in query.skeleton_slacks() or [0])
    return K >= sized_loops(query.h, multiple=(query.v or (0, 0)) != (0, 0)) - (1 if table else 0)


def sized_loops(h: int, multiple: bool = False) -> int:
    """The least number of loops K of a query (or a grid's cell) that is sized before it runs, in
    motion space ``h`` (one fewer with multiple joints).

    >>> sized_loops(3), sized_loops(3, multiple=True), sized_loops(2)
    (7, 6, 9)
    """
    return SIZED_LOOPS.get(h, SIZED_LOOPS[None]) - (1 if multiple else 0)


def size_check(query, *, processes: int, count: bool, table: bool, force: bool = False,
               mechanisms: str | None = None, scheduler: bool = False) -> str | None:
    """Refuse, within seconds and with an estimate, a query too large to run unasked.

    A query with fewer loops than :func:`sized_loops` passes at once (a listing as a ``table``:
    one loop fewer, for its rows).  Others are estimated (:func:`estimate`, timing what the query will do: count, list, or
    ``mechanisms`` ``"mechanisms"`` / ``"mechanisms with input"``) and refused with
    :class:`QueryTooLarge` when they would take more than a day on ``processes`` workers (unless
    ``force``), or when a ``table`` listing would hold more than a million rows (whatever
    ``force`` says); a query of more than ten minutes passes with a sentence to show before it
    starts (returned).

    >>> from synth.structure.query import ChainQuery
    >>> size_check(ChainQuery(1, 10), processes=2, count=True, table=False) is None
    True
    """
    rows_held = table and not count
    if (force and count) or not worth_sizing(query, table=rows_held):
        return None
    work = mechanisms or ("count" if count else "list")
    items = "mechanisms" if mechanisms else "chains"
    if needs_compiled(query):  # refused first, if it can be, on the plain path: before anything is compiled
        early = estimate(query, work=work, plain=True)
        if early is not None:
            _refuse(early, query, processes=processes, count=count, rows_held=rows_held, force=force, items=items,
                    scheduler=scheduler, margin=PLAIN_MARGIN)
    found = estimate(query, work=work)
    if found is None:
        if not force and worth_sizing(query):  # (a table only: its rows are counted as it is written)
            raise QueryTooLarge(f"this query ({query.links} links) is large and its size cannot be estimated "
                                f"(fewer than three smaller sizes have chains); give {option('force')} to run it anyway")
        return None
    size, memory, held = _refuse(found, query, processes=processes, count=count, rows_held=rows_held, force=force,
                                 items=items, scheduler=scheduler)
    notes = ([f"a long query: {size}"] if found.seconds / processes > NOTE_SECONDS else []) + (
        [memory] if held > NOTE_BYTES else [])
    return "; ".join(notes) or None


def _refuse(found: Estimate, query, *, processes: int, count: bool, rows_held: bool, force: bool, items: str,
            scheduler: bool, margin: float = 1.0) -> tuple[str, str, float]:
    """:func:`size_check`'s refusals of an estimate (its counts ``margin`` times over a limit; its time, a floor or
    not, over a day); else the estimate in words, the memory in words, and its bytes."""
    size = describe_estimate(found, processes=processes, items=items, scheduler=scheduler)
    if rows_held and found.chains > margin * TABLE_ROWS:
        raise QueryTooLarge(f"a table is held in memory to align it and this listing ({query.links} links) is too "
                            f"large for one ({size}); use {option('format', 'jsonl')} or csv (streamed), or {option('count')}")
    if not force and found.seconds / processes > LIMIT_SECONDS:
        hint = f" (with {option('checkpoint', 'FILE')} it can be stopped and resumed)" if count else ""
        floor = (f"; even at {FLOOR_SECONDS * 1e6:g} µs a unit and a {items[:-1]} visited it would take at least "
                 f"{_time_words(found, processes, scheduler)}") if found.floor else ""
        raise QueryTooLarge(f"this query ({query.links} links) is too large to run unasked: {size}{floor}; give "
                            f"{option('force')} to run it anyway{hint}")
    streamed = count and not scheduler
    held = plan_bytes(found, processes, streamed=streamed)
    kept = "whose certificates are kept" if streamed else "kept whole"
    memory = (f"its largest code has about {magnitude(found.largest_code_units)} branch multigraphs, {kept} "
              f"until the code is done: about {held / 2**30:.1f} GiB on {processes} worker{'s' * (processes > 1)}")
    if not force and held > margin * MEMORY_LIMIT:
        raise QueryTooLarge(f"this query ({query.links} links) would hold too much memory to run unasked: {memory} "
                            f"(more than {MEMORY_LIMIT / 2**30:g} GiB); {size}; give {option('force')} to run it anyway")
    return size, memory, held


def time_to_go_from(query, found: Estimate) -> tuple[str, float]:
    """The counter, and its total ``found`` expects, from whose share a count's progress line reckons the time to
    go (:class:`~synth.execution.progress.Progress` ``expected``): the units where ``query`` has multiple joints,
    the chains otherwise.  With multiple joints the chains a unit holds fall from about 2 000 to 0.07 as the joint
    excess grows (the 16-link count, benchmarks/RECORDS.md), so a count's last hours add few chains: on that
    count's logs the units' share erred by a median factor of 1.3 and the chains' by 2.1–2.2 (benchmarks/RECORDS.md,
    "The time to go of a count with multiple joints"); with simple joints the chains' share is kept.

    >>> from synth.structure.query import ChainQuery
    >>> found = Estimate(chains=6.9e9, units=8.5e6, seconds=1e4, basis="exact counts at 8, 10, 12 links")
    >>> time_to_go_from(ChainQuery(1, 16, v=(0, 14)), found), time_to_go_from(ChainQuery(1, 16), found)
    (('units', 8500000.0), ('chains', 6900000000.0))
    """
    return ("units", found.units) if _multiple(query) else ("chains", found.chains)


def describe_estimate(found: Estimate, *, processes: int, items: str = "chains", scheduler: bool = False) -> str:
    """An estimate in words: chains (or ``items``), units, the time on ``processes`` workers, and its basis.

    >>> describe_estimate(Estimate(1.5e11, 4892940, 1.5e5, "exact counts at 10, 12, 14 links"), processes=2)
    'about 1.5e+11 chains in 4 892 940 units, 20.8 h on 2 workers, extrapolated from the exact counts at 10, 12, 14 links'
    """
    time = "" if found.floor else f"{_time_words(found, processes, scheduler)}, "  # (a floor is said where it refuses)
    return (f"about {magnitude(found.chains, found.log10_chains or None)} {items} in "
            f"{magnitude(found.units, found.log10_units or None)} units, {time}extrapolated from the {found.basis}")


def _time_words(found: Estimate, processes: int, scheduler: bool) -> str:
    """The estimate's time on ``processes`` workers in words, as ``20.8 h on 2 workers``."""
    where = "on the scheduler's workers (one core shown)" if scheduler else \
        f"on {processes} worker{'s' * (processes > 1)}"
    log_wall = (found.log10_seconds or math.log10(found.seconds)) - math.log10(processes)
    return f"{describe_seconds(found.seconds / processes, log_wall)} {where}"


def plan_bytes(found: Estimate, processes: int, *, streamed: bool = False) -> float:
    """Memory a query's plan may hold at once, for each worker expanding a code: the units of its
    largest code, in that worker, in transit and in the parent (:data:`BYTES_PER_UNIT`), or for a
    ``streamed`` count only the certificates of that code's branch multigraphs met so far
    (:data:`CERTIFICATE_BYTES`; its units pass a window at a time, a few tens of MiB in all).

    >>> found = Estimate(1e6, 1e5, 10.0, "", largest_code_units=1000)
    >>> plan_bytes(found, processes=2), plan_bytes(found, processes=2, streamed=True)
    (7000000, 800000)
    """
    return found.largest_code_units * (CERTIFICATE_BYTES if streamed else BYTES_PER_UNIT) * processes

