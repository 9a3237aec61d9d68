"""A value quoted as a TOML file writes it, for the sentences that name a wrong value.

>>> show(True), show("one"), show([1, 2.5]), show({"a": 4}), show("x" * 80, width=10)
('true', "'one'", '[1, 2.5]', '{ a = 4 }', "'xxxxxxxx…")
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

__all__ = ["show"]


def show(value: Any, width: int = 60) -> str:
    """``value`` as a TOML file writes it (``true``, ``'one'``, ``[1, 2]``), shortened to ``width``."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, (list, tuple)):
        text = "[" + ", ".join(show(v, width) for v in value) + "]"
    elif isinstance(value, Mapping):
        text = "{ " + ", ".join(f"{k} = {show(v, width)}" for k, v in value.items()) + " }" if value else "{}"
    else:
        text = repr(value)
    return text if len(text) <= width else text[: width - 1] + "…"
