"""[HCDJ]'s ten points of a closed path (benchmarks/LITERATURE.md) as the source sums them: the first point
counted twice (its tenth repeats the first), posed as nine points with the first's weight 2.

Usage:

    python benchmarks/hcdj_ten_points.py target FILE.csv          # write the weighted target (x,y,weight)
    python benchmarks/hcdj_ten_points.py judge RESULT.json [...]    # our answers (mechsynth dimension --format json)
    python benchmarks/hcdj_ten_points.py lin [--budget S]           # W.Y. Lin's answer, and our polish from it

``judge`` prints, per answer, the weighted sum of squares our motion layer measures, the same answer's sum
by the source's closed form (``Case5/Objf5.m``: its vector, the tenth crank angle the first's, the ``+``
root; None where the answer is on the other assembly branch, which that form cannot represent) and its
link lengths.  ``lin`` prints W.Y. Lin's published vector's sum by the source's form, then our polish alone
(``synthesize(..., polish_only=True)``) from it under ``Constraints(crank=True, max_length=80)``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.bench_dimension import source_linkage, source_model, source_vector  # noqa: E402
from synth.dimension import Constraints, PathTarget, synthesize  # noqa: E402
from synth.motion import Linkage  # noqa: E402

#: [HCDJ] Case5/Objf5.m: ten points, the tenth the first again
POINTS = np.array([[20, 10], [17.66, 15.142], [11.736, 17.878], [5, 16.928], [0.60307, 12.736], [0.60307, 7.2638],
                   [5, 3.0718], [11.736, 2.1215], [17.66, 4.8577], [20, 10]])
WEIGHTS = [2.0] + [1.0] * 8
#: W.Y. Lin's vector as [HCDJ] Case5/CheckCase5.m quotes it: r1, r2, r3, r4, rcx, rcy, x0, y0, θ0, θ2 at each point
LIN = [80.0, 8.045662, 50.81902, 42.20801, -10.63697, -2.29109, 8.494813, -0.7579678, 3.88921,
       2.449437, 3.153969, 3.837114, 4.520171, 5.204799, 5.898536, 0.316204, 1.023555, 1.738992, 2.449437]
BOUND = Constraints(crank=True, max_length=80.0)


def model_vector(quoted) -> list[float]:
    """A vector as [HCDJ] orders it (…, x0, y0, θ0) in the order of :func:`source_model` (…, θ0, x0, y0)."""
    return list(quoted[:6]) + [quoted[8], quoted[6], quoted[7]]


def source_sum(vector, angles) -> float | None:
    """The source's sum of squared distances to the ten points, the tenth at the first's crank angle."""
    point = source_model(vector, list(angles) + [angles[0]])[3]
    value = float(((point - POINTS) ** 2).sum())
    return value if math.isfinite(value) else None


def judged(linkage: Linkage, inputs) -> dict:
    """Our answer's weighted sum by our motion layer and by the source's closed form."""
    vector = source_vector(linkage, inputs)
    ours = source_model(vector[:9], vector[9:])[3]
    lengths = linkage.lengths()
    # the source's form on its + root: equal to our motion where it represents our branch
    same_branch = bool(np.abs(ours - _traced(linkage, inputs)).max() < 1e-6)
    return {"ours": float(WEIGHTS @ ((_traced(linkage, inputs) - POINTS[:9]) ** 2).sum(axis=1)),
            "source": source_sum(vector[:9], vector[9:]) if same_branch else None,
            "lengths": [round(lengths[k], 6) for k in sorted(lengths)]}


def _traced(linkage: Linkage, inputs) -> np.ndarray:
    from synth.motion import assemble

    return np.array([assemble(linkage, float(v)).tracers["P"][1] for v in inputs])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="what", required=True)
    sub.add_parser("target").add_argument("file")
    sub.add_parser("judge").add_argument("results", nargs="+")
    lin = sub.add_parser("lin")
    lin.add_argument("--budget", type=float, default=60.0)
    args = parser.parse_args()
    if args.what == "target":
        rows = ["x,y,weight"] + [f"{x:g},{y:g},{w:g}" for (x, y), w in zip(POINTS[:9], WEIGHTS)]
        Path(args.file).write_text("\n".join(rows) + "\n")
        return
    if args.what == "judge":
        for name in args.results:
            result = json.loads(Path(name).read_text())
            linkage = Linkage.from_dict(result["linkage"])
            print(json.dumps({"result": name, "seconds": result["seconds"], **judged(linkage, result["inputs"])}))
        return
    vector = model_vector(LIN)
    print(json.dumps({"W.Y. Lin, by the source's form": source_sum(vector, LIN[9:18])}))
    clock = time.process_time()
    found = synthesize(source_linkage(vector, LIN[9]), PathTarget(POINTS[:9], weights=WEIGHTS), constraints=BOUND,
                       budget=args.budget, polish_only=True)
    print(json.dumps({"our polish from it": found.weighted_sum_squares, "met": found.met,
                      "cpu_seconds": round(time.process_time() - clock, 1), **judged(found.linkage, found.inputs)}))


if __name__ == "__main__":
    main()
