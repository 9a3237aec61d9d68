"""One grammar of ranges for every option, key and condition: ``N``, ``A..B``, ``A..`` (no upper end)
and, where the caller allows it, ``..B`` (no lower end).

The numbers are read by ``number`` (``int`` for counts, ``float`` for lengths and angles); what a
range must also satisfy (not empty, not below a minimum) is said by the caller in its own words.

>>> parse_range("2..5"), parse_range(" 3 .."), parse_range(4), parse_range("..7", open_low=True)
((2, 5), (3, None), (4, 4), (None, 7))
>>> parse_range("0.5..0.01", float, open_high=False)
(0.5, 0.01)
>>> parse_range("2..x")
Traceback (most recent call last):
...
mechbase.ranges.RangeSyntax: '2..x' is not a number or a range A..B
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["RangeSyntax", "parse_range"]


class RangeSyntax(ValueError):
    """Text that is not ``N`` or a range ``A..B`` of the numbers asked for."""


def parse_range(text: str | int | float, number: Callable[[str], int | float] = int, *, open_low: bool = False,
                 open_high: bool = True) -> tuple:
    """``(A, B)`` of ``text``; an end left out, where allowed, is None.

    Raises
    ------
    RangeSyntax
        ``text`` is not one number or two joined by ``..``, or leaves out an end that must be given.
    """
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise RangeSyntax(f"{text!r} is not a number or a range A..B")
    low, sep, high = str(text).strip().partition("..")
    try:
        if not sep:
            value = number(low)
            return value, value
        lo = number(low) if low.strip() else None
        hi = number(high) if high.strip() else None
    except ValueError:
        raise RangeSyntax(f"{text!r} is not a number or a range A..B") from None
    if (lo is None and not open_low) or (hi is None and not open_high):
        raise RangeSyntax(f"{text!r} leaves out an end of the range A..B")
    return lo, hi
