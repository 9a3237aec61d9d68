"""Small helpers to read TOML tables with one clear sentence per mistake."""

from __future__ import annotations

import math
from typing import Any, Iterable, Mapping

from .errors import SchemaError

__all__ = ["check_keys", "get_number", "get_range", "check_top_level", "OWNED_BY_RUNNER"]

OWNED_BY_RUNNER = frozenset({"scene", "expect"})


def check_top_level(doc: Mapping[str, Any], own: str, source: str) -> Mapping[str, Any]:
    """Return ``doc[own]``; ``[scene]`` and ``[expect]`` are ignored, any other key is an error."""
    if not isinstance(doc, Mapping):
        raise SchemaError(f"{source}: the document must be a TOML table.")
    for key in doc:
        if key != own and key not in OWNED_BY_RUNNER:
            raise SchemaError(
                f"{source}: unknown top-level key '{key}' (expected [{own}], [scene] or [expect])."
            )
    if own not in doc or not isinstance(doc[own], Mapping):
        raise SchemaError(f"{source}: missing table [{own}].")
    return doc[own]


def check_keys(table: Mapping[str, Any], allowed: Iterable[str], where: str, source: str) -> None:
    """Raise :class:`SchemaError` naming the first key of ``table`` not in ``allowed``."""
    allowed = set(allowed)
    for key in table:
        if key not in allowed:
            raise SchemaError(
                f"{source}: unknown key '{key}' in {where} (allowed: {', '.join(sorted(allowed))})."
            )


def get_number(
    table: Mapping[str, Any],
    key: str,
    where: str,
    source: str,
    default: float | None = None,
    required: bool = False,
) -> float | None:
    """A finite float from ``table[key]`` (ints accepted), or ``default``."""
    if key not in table:
        if required:
            raise SchemaError(f"{source}: {where} needs '{key}'.")
        return default
    v = table[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise SchemaError(f"{source}: '{key}' in {where} must be a number, not {v!r}.")
    v = float(v)
    if not math.isfinite(v):
        raise SchemaError(f"{source}: '{key}' in {where} must be finite, not {v}.")
    return v


def get_range(
    table: Mapping[str, Any], key: str, where: str, source: str, default=None
) -> tuple[float, float] | None:
    """A pair ``[lo, hi]`` of numbers (``inf`` allowed as a string "inf")."""
    if key not in table:
        return default
    v = table[key]
    if not isinstance(v, (list, tuple)) or len(v) != 2:
        raise SchemaError(f"{source}: '{key}' in {where} must be a pair [low, high], not {v!r}.")
    out = []
    for x in v:
        if isinstance(x, str) and x.strip().lower() in {"inf", "+inf", "infinity"}:
            out.append(math.inf)
        elif isinstance(x, (int, float)) and not isinstance(x, bool):
            out.append(float(x))
        else:
            raise SchemaError(f"{source}: '{key}' in {where} must hold two numbers, not {v!r}.")
    return out[0], out[1]
