"""How many codes a counting problem can have, before any model is built.

Subtracting twice the link equation from the joint equation of the counting system leaves
one equation in the *excess* of each link over two joints:

    Σ_{i≥3} (i − 2)·n_i + v = 2K − 2 + n1

so, for each n1, the codes are the partitions of 2K − 2 + n1 − v into parts i − 2 (a link with
i joints), each part used n_i times within its requirement, times the ways of splitting v into
joints (with compositions: the partitions of v into parts m − 2, a joint of m links).  Counted
by dynamic programming over the parts, this is an upper bound of the codes: the binary links
n2 (≥ 0, and their requirement) and, without compositions, the existence of a split of v are
left to the model.  The bound is exact for the planar closed chains of the universal table.

Example
-------
>>> from synth.synthesis.number_synthesis import make_problem
>>> [code_bound(make_problem(1, loops=k)).value for k in (2, 3, 4, 5)]  # table 1: 3, 9, 23, 53
[3.0, 9.0, 23.0, 53.0]
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING

from ..errors import QueryTooLarge

if TYPE_CHECKING:
    import numpy as np

__all__ = ["Bound", "code_bound", "coarse_bound", "check_excess", "MAX_EXCESS"]

# The table of partitions has one entry per unit of excess 2K − 2 + n1: beyond this the
# problem is refused unsized (K = 500 000 loops; the largest published tables stop at K = 10).
MAX_EXCESS = 1_000_000
# coarse_bound counts in integers up to this excess (K = 51 closed loops; 10 000 steps of its table)
_COARSE_EXCESS = 100
_SECONDS = 1.0  # time allowed for sizing (a problem whose bound is already above ``stop`` ends then)


@dataclass(frozen=True)
class Bound:
    """An upper bound of the codes (``value``; ``math.inf`` beyond floating point); ``exact`` is
    False when sizing stopped early because ``value`` already exceeded the limit it was given."""

    value: float
    exact: bool = True


def _partitions_bounded(table: np.ndarray, part: int, most: int | None) -> np.ndarray:
    """Convolve ``table`` with 0 … ``most`` copies of ``part`` (None: any number)."""
    import numpy as np

    size = len(table)
    if most is None or most * part >= size:
        rows = -(-size // part)
        padded = np.zeros(rows * part)
        padded[:size] = table
        return np.cumsum(padded.reshape(rows, part), axis=0).reshape(-1)[:size]
    out = table.copy()
    for k in range(1, most + 1):
        out[k * part:] += table[: size - k * part]
    return out


def _open_links(problem) -> tuple[int, int]:
    """The range of n1 the problem and its requirement on n1 allow."""
    n1_lo, n1_hi = problem.n1
    lo, hi = dict(problem.requirements).get(1, (0, None))
    return max(n1_lo, lo), n1_hi if hi is None else min(n1_hi, hi)


def check_excess(problem) -> int:
    """The largest excess 2K − 2 + n1 of a problem, refused above :data:`MAX_EXCESS` (such a problem
    cannot even be sized: its model alone would not fit, whatever is asked)."""
    n1_hi = _open_links(problem)[1]
    top = 2 * problem.loops - 2 + n1_hi
    if top > MAX_EXCESS:
        open_links = f" and up to {n1_hi} single-joint links" if n1_hi else ""
        raise QueryTooLarge(
            f"n = {problem.links} links, K = {problem.loops} loops{open_links} are far beyond what number synthesis "
            f"can list or even size (the excess 2K − 2 + n1 = {top} is above {MAX_EXCESS:_})".replace("_", " "))
    return top


def coarse_bound(problem) -> int | None:
    """A coarser upper bound of the codes than :func:`code_bound`, from the excess alone, in
    integers and without numpy (a small count never loads it); None above an excess of 100.

    Each of the ``n1`` values adds at most one term per split of the excess e = 2K − 2 + n1 − v
    between the links (a partition of e) and v (a partition of v, or one way): at most
    q(top) = Σ_v p(v)·p(top − v) codes, with p the partition numbers and top the largest excess
    (q grows with its argument, p being non-decreasing).

    >>> from synth.synthesis.number_synthesis import make_problem
    >>> problem = make_problem(1, loops=5)
    >>> coarse_bound(problem), code_bound(problem).value   # 12 links: 53 codes of table 1
    (185, 53.0)
    """
    n1_lo, n1_hi = _open_links(problem)
    top = 2 * problem.loops - 2 + n1_hi
    if n1_hi < n1_lo or top < 0:
        return 0
    if top > _COARSE_EXCESS:
        return None
    return (n1_hi - n1_lo + 1) * _partition_pairs(top)


@lru_cache(maxsize=None)
def _partition_pairs(top: int) -> int:
    """Σ_{v=0..top} p(v)·p(top − v): the pairs of partitions of two numbers adding up to ``top``.

    >>> [_partition_pairs(n) for n in range(5)]   # the coefficients of P(x)², OEIS A000712
    [1, 2, 5, 10, 20]
    """
    p = [1] + [0] * top
    for part in range(1, top + 1):
        for x in range(part, top + 1):
            p[x] += p[x - part]
    return sum(p[v] * p[top - v] for v in range(top + 1))


def _too_slow(problem, n1_hi: int) -> str:
    open_links = f" and up to {n1_hi} single-joint links" if n1_hi else ""
    return f"the codes of K = {problem.loops} loops{open_links} cannot be sized within {_SECONDS:g} s"


def code_bound(problem, *, stop: float = math.inf) -> Bound:
    """An upper bound of the codes of a validated :class:`~synth.synthesis.number_synthesis.Problem`.

    Sizing takes milliseconds up to thousands of loops; it stops as soon as the sum exceeds
    ``stop`` (the bound found so far is returned, not exact), and when it runs out of time (K of
    tens of thousands, or hundreds of thousands of single-joint links) the bound found so far is
    returned if it already exceeds ``stop``, else the problem is refused.

    Raises
    ------
    QueryTooLarge
        When the excess 2K − 2 + n1 exceeds :data:`MAX_EXCESS` (the table alone would not fit).

    >>> from synth.synthesis.number_synthesis import make_problem
    >>> code_bound(make_problem(1, loops=4, require=["5=1.."])).value  # the seven codes of the locomotive drive
    7.0
    """
    import numpy as np

    K = problem.loops
    requirements = dict(problem.requirements)
    n1_lo, n1_hi = _open_links(problem)
    if n1_hi < n1_lo:
        return Bound(0.0)
    top = check_excess(problem)
    if top < 0:
        return Bound(0.0)
    start = time.perf_counter()
    shift = 0
    parts = []  # (excess of the link kind, most copies beyond the required ones)
    for i in range(3, problem.max_link_degree + 1):
        lo, hi = requirements.get(i, (0, None))
        if hi is not None and hi < lo:
            return Bound(0.0)
        shift += (i - 2) * lo
        if i - 2 <= top and hi != lo:
            parts.append((i - 2, None if hi is None else hi - lo))
    # ways to write v as a sum of joint sizes (m − 2, m ≤ the largest multiplicity)
    v_lo, v_hi = problem.v
    v_hi = min(v_hi, max(top - shift, 0))
    biggest = (problem.max_multiplicity or problem.links) - 2
    with np.errstate(over="ignore", invalid="ignore"):
        splits = np.zeros(v_hi + 1)
        splits[0] = 1.0
        if problem.compositions:
            for part in range(1, min(biggest, v_hi) + 1):
                splits = _partitions_bounded(splits, part, None)
                if part % 64 == 0 and time.perf_counter() - start > _SECONDS:
                    raise QueryTooLarge(_too_slow(problem, n1_hi))
        elif biggest >= 1:
            splits[:] = 1.0
        table = np.zeros(top + 1)
        table[0] = 1.0

        def total() -> tuple[float, bool]:
            """The codes of the parts added so far summed over n1, and whether every n1 was summed:
            the sum stops once above ``stop`` (it only grows), and is refused when the second is out
            (a range of n1 of hundreds of thousands)."""
            found = 0.0
            for n1 in range(n1_lo, n1_hi + 1):
                rest = 2 * K - 2 + n1 - shift  # excess left for the links with 3+ joints and v
                if rest < 0:
                    continue
                vs = np.arange(v_lo, min(v_hi, rest) + 1)
                found += float(np.dot(splits[vs], table[rest - vs])) if len(vs) else 0.0
                if found > stop and n1 < n1_hi:
                    return found, False
                if (n1 - n1_lo) % 256 == 255 and time.perf_counter() - start > _SECONDS:
                    raise QueryTooLarge(_too_slow(problem, n1_hi))
            return found, True

        for number, (part, most) in enumerate(parts, 1):
            table = _partitions_bounded(table, part, most)
            if number % 16 == 0 and time.perf_counter() - start > _SECONDS / 2:
                partial, _ = total()  # the parts not yet added at their least: a lower bound of the bound
                if partial > stop or not math.isfinite(partial):
                    return Bound(partial if math.isfinite(partial) else math.inf, exact=False)
                if time.perf_counter() - start > _SECONDS:
                    raise QueryTooLarge(_too_slow(problem, n1_hi))
        value, complete = total()
    return Bound(value if math.isfinite(value) else math.inf, exact=complete)
