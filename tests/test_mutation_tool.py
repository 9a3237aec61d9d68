"""tools/mutation.py --write-docs: a run of some modules replaces their rows and mutant lists in
docs/mutation.md and keeps every other module's as it was."""

from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _tool():
    spec = importlib.util.spec_from_file_location("mutation_tool", ROOT / "tools" / "mutation.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _result(file, killed, survivors=(), equivalent=()):
    return {"file": file, "date": "2026-11-28", "total": 10, "killed": killed, "not_checked": 0, "minutes": 1.5,
            "survivors": [{"function": f, "before": "a", "after": "b", "status": "survived"} for f in survivors],
            "equivalent": [{"function": f, "before": "c", "after": "d", "reason": "why"} for f in equivalent],
            "score": killed / (10 - len(equivalent))}


def test_a_run_replaces_its_modules_rows_and_keeps_the_others():
    tool = _tool()
    old = tool._markdown([_result("a.py", 9, ["fa"]), _result("b.py", 8, ["fb"], ["gb"])])
    assert tool._merged("\n" + old, old) == old  # (the block in the file starts on a new line)
    new = tool._markdown([_result("b.py", 9, [], ["gb"]), _result("c.py", 7, ["fc"])])
    merged = tool._merged("\n" + old, new)
    rows = [line for line in merged.splitlines() if line.startswith("| `")]
    assert [r.split("`")[1] for r in rows] == ["a.py", "b.py", "c.py"]
    assert "| 9 | 0 | 1 | 0 | 90.0 % |" in rows[0] and "| 9 | 1 | 0 | 0 | 100.0 % |" in rows[1]
    assert "Surviving in `a.py`:\n\n- `fa`: `a` → `b` (survived)" in merged
    assert "Surviving in `b.py`" not in merged and "Equivalent in `b.py`:\n\n- `gb`: `c` → `d` — why" in merged
    assert merged.index("`a.py`:") < merged.index("`b.py`:") < merged.index("`c.py`:")
    assert merged.startswith(new.split("\n| `")[0])  # the new header (mutmut's version) heads the block


def test_the_copies_hold_every_package_of_the_checkout():
    """A mutant's copy of the tree must import like the checkout: every top-level package is copied."""
    packages = {d.name for d in ROOT.iterdir() if (d / "__init__.py").exists()}
    assert packages and packages <= set(_tool().COPY)
