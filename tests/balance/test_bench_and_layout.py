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
