"""Package layout contracts and the benchmark entry point."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_balance_does_not_import_synth_matplotlib_or_pinocchio():
    code = ("import sys, balance, mechsynth.commands.balance; "
            "assert 'synth' not in sys.modules, 'synth imported'; "
            "assert 'matplotlib' not in sys.modules, 'matplotlib imported eagerly'; "
            "assert 'pinocchio' not in sys.modules, 'pinocchio imported eagerly'")
    p = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr


def test_public_api_listed():
    import balance

    for name in balance.__all__:
        assert hasattr(balance, name), name


@pytest.mark.slow
def test_benchmark_quick_rows(tmp_path):
    spec = importlib.util.spec_from_file_location("bench_balance", ROOT / "benchmarks" / "bench_balance.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    rows = mod.run(quick=True)
    fit = [r for r in rows if r["table"] == "fit"]
    arm = [r for r in rows if r["table"] == "arm_check"]
    assert fit and arm
    assert all(r["max_rel_error"] < 0.1 for r in fit if r["default"])  # timings are reported, never asserted
    assert all(r["relative_residual"] < 1e-9 for r in arm if r["arm"] == "arm_base_drives")


def _imports(path: Path) -> list[tuple[str, str]]:
    """(module, name) for every import in a file (name '' for ``import module``)."""
    import ast

    out = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out += [(a.name, "") for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0:
            out += [(node.module or "", a.name) for a in node.names]
    return out


def test_layers_balance_never_imports_the_app_or_synth_and_the_app_only_public_balance_names():
    for f in (ROOT / "balance").rglob("*.py"):
        for mod, _ in _imports(f):
            assert not mod.split(".")[0] in ("synth", "mechsynth"), (f, mod)
    for f in list((ROOT / "synth").rglob("*.py")):
        assert not any(mod.split(".")[0] == "balance" for mod, _ in _imports(f)), f
    for f in list((ROOT / "mechsynth").rglob("*.py")) + list((ROOT / "benchmarks").rglob("*.py")):
        for mod, name in _imports(f):
            if mod.split(".")[0] == "balance":
                assert not any(part.startswith("_") for part in mod.split(".") + [name]), (f, mod, name)


def test_balance_init_lists_what_it_offers_and_loads_nothing_until_asked():
    code = ("import sys, balance; assert [m for m in sys.modules if m.startswith('balance.')] == [], "
            "sorted(m for m in sys.modules if m.startswith('balance.'))")
    p = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    import balance

    assert balance.__all__ == sorted(set(balance.__all__)) and "solve_arm" in dir(balance)
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        balance.nope  # noqa: B018
