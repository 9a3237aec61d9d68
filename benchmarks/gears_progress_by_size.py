"""How well the time to go of ``gears_two_methods_by_tree.py`` is reckoned from the trees compared so far:
by trees alike, or by their sizes (``tree_size``: pairs of links on a common axis).

For each finished log, trees in the engine's order (a whole run's), after 5, 10, 25, 50 and 75 % of the
trees: the CPU the rate so far predicts for the whole size over the CPU it took (1.00 is exact)::

    python benchmarks/gears_progress_by_size.py benchmarks/logs/gears_two_methods_rotation_F1_n11.jsonl
"""

from __future__ import annotations

import json
import math
import statistics
import sys

from gears_two_methods_by_tree import tree_size

SHARES = (0.05, 0.10, 0.25, 0.50, 0.75)


def predicted_over_taken(cpu: list[float], weight: list[float]) -> list[float]:
    """At each share of the trees: (CPU so far / weight so far × all the weight) / all the CPU.

    >>> predicted_over_taken([1.0] * 20, [1.0] * 20)
    [1.0, 1.0, 1.0, 1.0, 1.0]
    """
    out = []
    for share in SHARES:
        k = max(1, int(len(cpu) * share))
        out.append(round(sum(cpu[:k]) / sum(weight[:k]) * sum(weight) / sum(cpu), 2))
    return out


def main(paths: list[str]) -> int:
    print("log | weight | " + " | ".join(f"{s:.0%}" for s in SHARES))
    for path in paths:
        rows = {}
        for line in open(path):
            row = json.loads(line)
            if "tree" in row:
                rows[row["tree"]] = row
        ordered = [rows[k] for k in sorted(rows)]
        cpu = [r["engine_cpu"] + r["second_cpu"] for r in ordered]
        size = [tree_size(r["axes"]) for r in ordered]
        for name, weight in (("trees alike", [1.0] * len(ordered)), ("tree size", size)):
            print(f"{path.rsplit('/', 1)[-1]} ({len(ordered)} trees) | {name} | "
                  + " | ".join(f"{v:.2f}" for v in predicted_over_taken(cpu, weight)))
        logs = [math.log(c + 1e-3) for c in cpu]  # (a tree of 0.000 CPU s)
        print(f"  correlation of log CPU with log size {statistics.correlation(logs, [math.log(w) for w in size]):.2f}, "
              f"with log trains {statistics.correlation(logs, [math.log(r['engine'] + 1) for r in ordered]):.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
