"""How big a chain query is before it runs: chains, units and time, extrapolated from exact counts.

Method
------
The same query (same W, v, conventions and requirements) is counted exactly at the
smaller link counts n − 2k, smallest first, in this process, until about ``budget``
seconds have been spent (never at n itself, and never a size predicted to cost more than
three budgets).  From the last three sizes with chains,
the growth ratio r(n) = chains(n) / chains(n − 2) is extrapolated *linearly*:
r(n + 2) = r(n) + (r(n) − r(n − 2)); chains and units are multiplied by it step by step.
Time is the largest calibration size's measured seconds per chain times the chains.

For 1-DOF chains the ratio grows by 15–16 a step from 10 links on (2, 8, 14.4, 29.8, 46.4,
62.3, 77.5 up to 18 links), so from the counts at 8, 10 and 12 links the estimate is
−2.5 % at 14 links, −5.0 % at 16 and −6.7 % at 18 against the published counts (318 162,
19 819 281, 1 535 380 884).  The time per chain falls as n grows (on one core: ≈ 120 µs at
12 links, ≈ 110 µs at 14 and 16), so the time estimate is an upper bound of the right order,
not a prediction: it assumes the workers scale perfectly and no faster per-chain rate.

Example
-------
>>> from synth.structure.query import ChainQuery
>>> e = estimate(ChainQuery(1, 16))
>>> 1.5e7 < e.chains < 2.5e7, e.basis
(True, 'exact counts at 8, 10, 12 links')
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from ..errors import ImpossibleParameters, QueryTooLarge

__all__ = ["Estimate", "estimate", "size_check", "describe_seconds", "magnitude"]

# Queries at least this large (loops K of their largest skeleton; multiple joints grow faster)
# are sized before they run.
SIZED_LOOPS, SIZED_LOOPS_MULTIPLE = 7, 6
LIMIT_SECONDS = 86400.0  # refused without force when estimated to take longer (wall, on the workers)
TABLE_ROWS = 1_000_000  # a table is held in memory to align its columns: refused above this
NOTE_SECONDS = 600.0  # a query estimated to take longer says so before it starts


@dataclass(frozen=True)
class Estimate:
    """Extrapolated size of a query: chains, units, one-core seconds, and the sizes it rests on."""

    chains: float
    units: float
    seconds: float
    basis: str


def estimate(query, *, budget: float = 2.0) -> Estimate | None:
    """Estimate a :class:`~synth.structure.query.ChainQuery` (with ``links``; not its code).

    Only sizes below ``links`` are counted (the query itself never is), for about ``budget``
    seconds.  Returns None when fewer than three smaller sizes have chains (no basis for a ratio).
    """
    from ..synthesis.type_synthesis import _count_unit, _map_units, plan_jobs

    links = query.links
    start = time.perf_counter()
    points = []  # (links, chains, units, seconds)
    for n in range(2 + links % 2, links, 2):  # n = W + 1 + 2K: the same parity as the query's n
        if points and time.perf_counter() - start > budget:
            break
        if len(points) >= 2 and points[-1][3] * points[-1][1] / points[-2][1] > 3 * budget:
            break  # the next size would cost far more than the budget
        t0 = time.perf_counter()
        try:
            jobs = plan_jobs(query.with_options(links=n))
        except ImpossibleParameters:
            continue
        chains = units = 0
        for _, unit, result in _map_units(_count_unit, jobs, 1, False):
            if unit is not None:
                chains += sum(result.values())
                units += 1
        if chains:
            points.append((n, chains, units, time.perf_counter() - t0))
    if len(points) < 3:
        return None
    (_, c0, u0, _), (_, c1, u1, _), (n2, c2, u2, s2) = points[-3:]
    rate = s2 / c2
    chains, units = float(c2), float(u2)
    r_c, d_c = c2 / c1, max(c2 / c1 - c1 / c0, 0.0)
    r_u, d_u = u2 / max(u1, 1), max(u2 / max(u1, 1) - u1 / max(u0, 1), 0.0)
    for _ in range((links - n2) // 2):
        r_c += d_c
        r_u += d_u
        chains *= r_c
        units *= max(r_u, 1.0)
    basis = "exact counts at " + ", ".join(str(p[0]) for p in points[-3:]) + " links"
    return Estimate(chains, units, chains * rate, basis)


def size_check(query, *, processes: int, count: bool, table: bool, force: bool = False,
               where: str | None = None) -> str | None:
    """Refuse, within seconds and with an estimate, a query too large to run unasked.

    A query with fewer loops than :data:`SIZED_LOOPS` (6 with multiple joints) passes at once.
    Others are estimated (:func:`estimate`) and refused with :class:`QueryTooLarge` when they
    would take more than a day on ``processes`` workers (unless ``force``), or when a ``table``
    listing would hold more than a million rows (whatever ``force`` says); a query of more
    than ten minutes passes with a sentence to show before it starts (returned).

    >>> from synth.structure.query import ChainQuery
    >>> size_check(ChainQuery(1, 10), processes=2, count=True, table=False) is None
    True
    """
    if query.code is not None:
        return None
    K = max((query.links - 1 - query.dof + k) // (query.h - 1) for k in query.skeleton_slacks() or [0])
    multiple = (query.v or (0, 0)) != (0, 0)
    if K < (SIZED_LOOPS_MULTIPLE if multiple else SIZED_LOOPS) or (force and count):
        return None
    found = estimate(query)
    if found is None:
        if not force:
            raise QueryTooLarge(f"this query ({query.links} links) is large and its size cannot be estimated "
                                "(fewer than three smaller sizes have chains); give --force to run it anyway")
        return None
    where = where or f"on {processes} worker{'s' * (processes > 1)}"
    size = (f"about {magnitude(found.chains)} chains in {magnitude(found.units)} units, "
            f"{describe_seconds(found.seconds / processes)} {where}, extrapolated from the {found.basis}")
    if not count and table and found.chains > TABLE_ROWS:
        raise QueryTooLarge(f"a table is held in memory to align it and this listing is too large for one ({size}); "
                            "use --format jsonl or csv (streamed), or --count")
    if not force and found.seconds / processes > LIMIT_SECONDS:
        hint = " (with --checkpoint FILE it can be stopped and resumed)" if count else ""
        raise QueryTooLarge(f"this query is too large to run unasked: {size}; give --force to run it anyway{hint}")
    if found.seconds / processes > NOTE_SECONDS:
        return f"a long query: {size}"
    return None


def describe_seconds(seconds: float) -> str:
    """A duration in the largest sensible unit.

    >>> describe_seconds(42), describe_seconds(5400), describe_seconds(3e5), describe_seconds(1e12)
    ('42 s', '90 min', '3.5 days', '3.2e+04 years')
    """
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.1f} h"
    if seconds < 365 * 86400:
        return f"{seconds / 86400:.1f} days"
    years = seconds / (365.25 * 86400)
    return f"{years:.0f} years" if years < 1e4 else f"{years:.2g} years"


def magnitude(x: float) -> str:
    """A count in words a reader takes in at once.

    >>> magnitude(6856), magnitude(1.43e9), magnitude(3e40)
    ('6 856', '1.4e+09', '3e+40')
    """
    if not math.isfinite(x) or x >= 1e7:
        return f"{x:.2g}"
    return f"{round(x):,}".replace(",", " ")
