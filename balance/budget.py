"""The resource contract: how much work a problem asks for, estimated before it starts.

Every input that scales the work (random samples of a check, the grid of a URDF
decomposition, the configurations of a dynamics check) is priced before anything runs: the
cost of one unit is measured on a few units (so the estimate holds on the machine at hand),
multiplied by the count, and a problem above :data:`WORK_LIMIT` seconds is refused with the
estimate (:class:`TooMuchWork`), unless its ``work_limit`` is lifted (``None``). Memory
stays bounded whatever the count: the searches evaluate in chunks.

Examples
--------
>>> ensure_affordable("checking 10 configurations", 10, 1e-4, limit=1.0)  # seconds
0.001
>>> try:
...     ensure_affordable("checking 1e9 configurations", 10**9, 1e-4, limit=30.0)
... except TooMuchWork as exc:
...     print(exc)
checking 1e9 configurations would take about 1 day (100 µs each, measured here), more than the 30 s a problem may take unless its limit is lifted
"""

from __future__ import annotations

import time
from typing import Callable

from .errors import InvalidInput

__all__ = ["WORK_LIMIT", "TooMuchWork", "ensure_affordable", "unit_seconds", "duration"]

#: seconds of estimated work a problem may take without its limit lifted
WORK_LIMIT = 30.0


class TooMuchWork(InvalidInput):
    """A problem would take longer than its work limit; the message holds the estimate."""

    def __init__(self, message: str, seconds: float, limit: float):
        super().__init__(message)
        self.seconds, self.limit = seconds, limit


def duration(seconds: float) -> str:
    """``95`` → ``'2 min'``: a rough human duration.

    >>> duration(0.4), duration(95), duration(7200), duration(3e6)
    ('0.4 s', '2 min', '2 h', '35 days')
    """
    for unit, size in (("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= 1.5 * size or (unit == "min" and seconds >= 90):
            n = round(seconds / size)
            return f"{n} {unit}"  # days from 1.5 on: n ≥ 2
        if unit == "days" and seconds >= size:
            return "1 day"
    return f"{seconds:.2g} s"


def _short(seconds: float) -> str:
    """A short time to three digits in the unit that keeps it below 1000: ``'100 µs'``, ``'2.5 ms'``, ``'3 s'``
    (0.9996 s is ``'1 s'``, not ``'1e+03 ms'``)."""
    for scale, unit in ((1e6, "µs"), (1e3, "ms")):
        text = f"{seconds * scale:.3g}"
        if float(text) < 1000:
            return f"{text} {unit}"
    return f"{seconds:.3g} s"


def unit_seconds(unit: Callable[[], object], repeat: int = 3) -> float:
    """The least time of ``repeat`` calls of ``unit`` (the estimate's price of one unit)."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        unit()
        best = min(best, time.perf_counter() - t0)
    return best


def ensure_affordable(what: str, count: float, unit: Callable[[], object] | float, limit: float | None = WORK_LIMIT,
                      per: float = 1.0) -> float:
    """Refuse ``what`` when ``count`` units would take longer than ``limit`` seconds.

    Parameters
    ----------
    what : str
        The work, as the sentence names it ("checking 100000000 configurations").
    count : float
        How many units.
    unit : callable or float
        One call of ``per`` units (timed), or the seconds of one unit.
    limit : float or None
        None: no limit (the estimate is still returned).
    per : float
        Units done by one call of ``unit``.

    Returns
    -------
    float
        The estimated seconds.
    """
    each = (unit if isinstance(unit, (int, float)) else unit_seconds(unit)) / per
    seconds = each * count
    if limit is not None and seconds > limit:
        raise TooMuchWork(f"{what} would take about {duration(seconds)} ({_short(each)} each, measured here), "
                          f"more than the {duration(limit)} a problem may take unless its limit is lifted",
                          seconds, limit)
    return seconds
