"""Number synthesis time against K (every v), with table 1's counts checked.

Writes ``benchmarks/out/codes.csv``.  Run: ``python benchmarks/bench_codes.py [--quick]``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from benchmarks._out import OUT, print_rows, write_csv  # noqa: E402
TABLE_1 = {1: 1, 2: 3, 3: 9, 4: 23, 5: 53}


def run(quick: bool = False) -> list[dict]:
    """Time ``number_synthesis`` for W = 1 and K = 1 … 10 (… 6 with ``quick``), best of 3."""
    from synth import number_synthesis

    rows = []
    t0 = time.perf_counter()
    table = number_synthesis(1, loops="1..5")
    rows.append({"query": "table 1 (W=1, K=1..5)", "codes": len(table), "reference": 89,
                 "error": len(table) - 89, "seconds": round(time.perf_counter() - t0, 4)})
    for K in range(1, 7 if quick else 11):
        best = float("inf")
        for _ in range(3):
            t0 = time.perf_counter()
            codes = number_synthesis(1, loops=K)
            best = min(best, time.perf_counter() - t0)
        ref = TABLE_1.get(K)
        rows.append({"query": f"W=1, K={K}", "codes": len(codes), "reference": ref,
                     "error": None if ref is None else len(codes) - ref, "seconds": round(best, 4)})
    write_csv(OUT / "codes.csv", rows)
    return rows


if __name__ == "__main__":
    print_rows(run, __doc__)
