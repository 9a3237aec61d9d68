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
>>> e = estimate(dict(dof=1, links=16))
>>> 1.5e7 < e.chains < 2.5e7, e.basis
(True, 'exact counts at 8, 10, 12 links')
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from ..errors import ImpossibleParameters

__all__ = ["Estimate", "estimate", "describe_seconds"]


@dataclass(frozen=True)
class Estimate:
    """Extrapolated size of a query: chains, units, one-core seconds, and the sizes it rests on."""

    chains: float
    units: float
    seconds: float
    basis: str


def estimate(query: dict, *, budget: float = 2.0) -> Estimate | None:
    """Estimate ``query`` (keywords of :func:`synth.count_chains` with ``dof`` and ``links``).

    Only sizes below ``links`` are counted (the query itself never is), for about ``budget``
    seconds.  Returns None when fewer than three smaller sizes have chains (no basis for a ratio).
    """
    from ..synthesis.type_synthesis import _codes_of, _count_unit, _map_units

    dof, links = query["dof"], query["links"]
    start = time.perf_counter()
    points = []  # (links, chains, units, seconds)
    for n in range(2 + links % 2, links, 2):  # n = W + 1 + 2K: the same parity as the query's n
        if points and time.perf_counter() - start > budget:
            break
        if len(points) >= 2 and points[-1][3] * points[-1][1] / points[-2][1] > 3 * budget:
            break  # the next size would cost far more than the budget
        t0 = time.perf_counter()
        try:
            codes, conv = _codes_of(dict(query, links=n))
        except ImpossibleParameters:
            continue
        chains = units = 0
        for _, unit, result in _map_units(_count_unit, codes, conv, 1, False):
            if unit is not None:
                chains += result[1]
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
