"""How big and how long, in words a reader takes in at once: :func:`magnitude` of a count,
:func:`describe_seconds` of a duration, both for numbers beyond floating point too.

>>> magnitude(1_535_380_884), describe_seconds(1782)
('1.5e+09', '30 min')
"""

from __future__ import annotations

import math

__all__ = ["describe_seconds", "magnitude"]


def describe_seconds(seconds: float, log10: float | None = None) -> str:
    """A duration in the largest sensible unit (``log10``: its base-10 logarithm, for durations
    beyond floating point).

    >>> describe_seconds(42), describe_seconds(5400), describe_seconds(3e5), describe_seconds(1e12)
    ('42 s', '90 min', '3.5 days', '3.2e+04 years')
    >>> describe_seconds(math.inf, 2000.0)
    '3.2e+1992 years'
    """
    if not math.isfinite(seconds):
        return f"{_scientific((log10 or math.inf) - math.log10(365.25 * 86400))} years"
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.1f} h"
    if seconds < 365 * 86400:
        return f"{seconds / 86400:.1f} days"
    years = seconds / (365.25 * 86400)
    if years >= 1e4:
        return f"{years:.2g} years"
    return f"{years:.0f} year" + "s" * (round(years) != 1)


def magnitude(x: float, log10: float | None = None) -> str:
    """A count in words a reader takes in at once (``log10``: its base-10 logarithm, for counts
    beyond floating point).

    >>> magnitude(6856), magnitude(1.43e9), magnitude(3e40), magnitude(math.inf, 2400.3)
    ('6 856', '1.4e+09', '3e+40', '2e+2400')
    """
    if not math.isfinite(x):
        return _scientific(math.inf if log10 is None else log10)
    if x >= 1e7:
        return f"{x:.2g}"
    return f"{round(x):,}".replace(",", " ")


def _scientific(log10: float) -> str:
    """10^log10 written as 1.2e+345 (any size); 'more than 1e+308' when unknown."""
    if not math.isfinite(log10):
        return "more than 1e+308"
    exponent = math.floor(log10)
    mantissa = 10 ** (log10 - exponent)
    if round(mantissa, 1) >= 10:
        mantissa, exponent = mantissa / 10, exponent + 1
    return f"{mantissa:.2g}e+{exponent}"
