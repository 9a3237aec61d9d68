"""The units of a query that stage B's compiled kernel places (what the kernel tests compare unit by unit)."""

from __future__ import annotations

import synth
from synth.synthesis import stage_b


def kernel_units(query: dict):
    """Each unit of ``query`` (planned with one worker) whose contracted graph the kernel applies to, as
    ``(unit, (code, graph, conventions))``."""
    for u in synth.plan_units(**query, workers=1):
        graph = u.contracted
        if graph is not None and stage_b._kernel_applies(u.code, graph, u.conventions):
            yield u, (u.code, graph, u.conventions)
