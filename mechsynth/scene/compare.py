"""How an ``[expect]`` value is compared with the value a run produced.

Each function is ``compare(expected, actual, rel_tol) -> (met, what differs)``.

>>> equal(0.1 + 0.2, 0.3, 1e-9)[0], multiset([1, 2], [2, 1.0], 1e-9)[0]
(True, True)
>>> table({"2": 1}, {"2": 1, "3": 4}, 1e-9)
(False, '3: expected 0, got 4')
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

__all__ = ["equal", "multiset", "table", "close"]


def close(a: Any, b: Any, rel_tol: float) -> bool:
    """Numbers within ``rel_tol`` (absolute 1e-12), everything else exactly; lists and tables item by item."""
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(float(a), float(b), rel_tol=rel_tol, abs_tol=1e-12)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(close(x, y, rel_tol) for x, y in zip(a, b))
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        bb = {str(k).strip(): v for k, v in b.items()}
        return ({str(k).strip() for k in a} == set(bb)
                and all(close(v, bb[str(k).strip()], rel_tol) for k, v in a.items()))
    return a == b


def equal(expected: Any, actual: Any, rel_tol: float) -> tuple[bool, str]:
    """The same value (numbers within ``rel_tol``)."""
    return close(expected, actual, rel_tol), f"the run gave {actual!r}"


def multiset(expected: list, actual: Any, rel_tol: float) -> tuple[bool, str]:
    """The same numbers in any order."""
    ok = isinstance(actual, list) and close(sorted(expected), sorted(actual), rel_tol)
    return ok, f"the run gave {actual!r}"


def table(expected: Mapping, actual: Any, rel_tol: float) -> tuple[bool, str]:
    """The same table; a key missing on one side counts as 0."""
    want = {str(k).strip(): v for k, v in expected.items()}
    got = {str(k): v for k, v in (actual or {}).items()}
    diff = [f"{k}: expected {want.get(k, 0)!r}, got {got.get(k, 0)!r}" for k in sorted(set(want) | set(got))
            if not close(want.get(k, 0), got.get(k, 0), rel_tol)]
    return not diff, "; ".join(diff)
