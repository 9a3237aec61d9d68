"""One reader of a pair of finite numbers ``(x, y)``: a point, a direction, two radii, two limits.

Each caller says in its own words what is wrong (``malformed``: not two numbers; ``not_finite``:
NaN or infinite) and which error carries it, so one function serves every engine and command.

>>> finite_pair([1, 2.5], error=ValueError, malformed="not a point")
(1.0, 2.5)
>>> finite_pair("12", error=ValueError, malformed="a fixed pivot is a point (x, y), not '12'")
Traceback (most recent call last):
...
ValueError: a fixed pivot is a point (x, y), not '12'
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

__all__ = ["finite_pair"]


def finite_pair(value: Any, *, error: type[Exception], malformed: str, not_finite: str | None = None) -> tuple[float, float]:
    """``(x, y)`` of a list, tuple or array of two numbers, both finite.

    Parameters
    ----------
    value : sequence of two numbers
        Numbers or texts of numbers (``["1.5", "2"]``, as a command line splits them). A text as a
        whole (``"12"`` would otherwise read as 1 and 2), a mapping, a truth value or any other
        length is refused.
    error : exception class
        What is raised, with one of the two sentences.
    malformed : str
        The sentence when ``value`` is not two numbers.
    not_finite : str, optional
        The sentence when a number is NaN or infinite (default: ``malformed``).

    Returns
    -------
    (float, float)

    Raises
    ------
    error
        ``malformed`` or ``not_finite``.

    Examples
    --------
    >>> finite_pair(("0", "-3e2"), error=ValueError, malformed="expected x,y")
    (0.0, -300.0)
    >>> finite_pair([1, float("inf")], error=ValueError, malformed="two numbers", not_finite="not finite")
    Traceback (most recent call last):
    ...
    ValueError: not finite
    >>> finite_pair([True, 0], error=ValueError, malformed="two numbers [x, y], not [True, 0]")
    Traceback (most recent call last):
    ...
    ValueError: two numbers [x, y], not [True, 0]
    """
    if isinstance(value, (str, bytes, Mapping)):
        raise error(malformed)
    try:
        x, y = value
        if isinstance(x, bool) or isinstance(y, bool):
            raise TypeError
        x, y = float(x), float(y)
    except (TypeError, ValueError):
        raise error(malformed) from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise error(not_finite or malformed)
    return x, y
