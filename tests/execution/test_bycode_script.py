"""benchmarks/bycode.py refuses a record it cannot read with one sentence and exit 2."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "benchmarks" / "bycode.py"


@pytest.mark.parametrize("content", [None, "not json", "[1]", '{"commit": "x"}'])
def test_compare_refuses_a_record_it_cannot_read(tmp_path, content):
    record = tmp_path / "record.json"
    if content is not None:
        record.write_text(content)
    run = subprocess.run([sys.executable, str(SCRIPT), "compare", str(record)], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and "is not a record of counts by code" in run.stderr
    assert "Traceback" not in run.stderr and run.stdout == ""
