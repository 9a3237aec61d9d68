"""Project the time (and the count) of a whole chain query from a random sample of its units.

Method (two-stage cluster sampling; the clusters are the codes)
---------------------------------------------------------------
1. Number synthesis gives the C codes of the query (exact, fast).
2. ``m`` codes are drawn uniformly without replacement; stage A runs on each (its CPU
   time a_c and its unit count U_c are exact).
3. From each drawn code ``k`` units are drawn uniformly without replacement (all of them
   when U_c ≤ k); each runs, giving its CPU time t_u and its chain count.
4. Every total Y (CPU seconds, units, chains) is estimated without bias by
   Ŷ = C/m · Σ_c (y_c + U_c · mean of the sampled units), with the standard error of
   two-stage sampling: Var = C²(1 − m/C)·s₁²/m + C/m · Σ_c U_c²(1 − k_c/U_c)·s²_{2c}/k_c.
   The report gives Ŷ ± 2 SE.
5. CPU time is measured with ``time.process_time`` in this one process, so other work on
   a shared machine hardly changes it; the projected wall time on W workers is
   CPU / W / e, with e the parallel efficiency measured on this machine (the 14-link run:
   one-process CPU over 2 × the 2-worker wall).

The chain count is projected with the same sample, so a projection is checked twice:
against the real time where a real run exists (14, 16 links) and against the published
count (OEIS A233288) everywhere.

With every code drawn (the default) the first-stage error vanishes: stage A runs on every code,
so the unit counts and stage A's time are exact and only stage B is sampled.  Measured at
14 links (load average ≈ 10): all 30 codes and 30 units of each (1011 of 3515 units, 36–46 s
wall) projected 42.8 ± 7.1, 44.0 ± 8.2 and 51.4 ± 11.4 CPU s for seeds 1–3 against 47.1 CPU s
measured for the whole query (errors −9 %, −7 %, +9 %; chains −7 %, −1.5 %, +29 %).  With half the
codes drawn (15 of 30) the errors were +9 % to +86 %: the codes' sizes are too uneven to sample.
The standard error comes from few, heavy-tailed values: at 12 links (8 of 15 codes, 2 units each)
±2 SE covered the truth in 63 % of 30 seeds, not 95 %; read it as an order of magnitude.

Run: ``python benchmarks/bench_projection.py 18 [--codes M] [--units 40] [--seed 1] [--json FILE]``.
"""

from __future__ import annotations

import argparse
import json
import math
import random
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

PUBLISHED = {4: 1, 6: 2, 8: 16, 10: 230, 12: 6856, 14: 318162, 16: 19819281, 18: 1535380884}  # OEIS A233288


def _cpu(fn, *args):
    t0 = time.process_time()
    out = fn(*args)
    return out, time.process_time() - t0


def project(dof: int, links: int, *, codes: int, units: int, seed: int, v="0", progress=None) -> dict:
    """Sample ``codes`` codes and ``units`` units of each; return the projected totals and their errors."""
    from synth._type_synthesis import _codes_of, _stage_a, run_unit

    rng = random.Random(seed)
    start = time.perf_counter()
    all_codes, conv = _codes_of(dict(dof=dof, links=links, v=v))
    C = len(all_codes)
    drawn = rng.sample(range(C), min(codes, C))
    per_code = []  # (a_c, U_c, [(t_u, chains_u)])
    for i in drawn:
        plan, a_c = _cpu(_stage_a, (all_codes[i], conv))
        picked = rng.sample(plan, min(units, len(plan)))
        sample = []
        for unit in picked:
            chains, t_u = _cpu(run_unit, unit)
            sample.append((t_u, len(chains)))
        per_code.append((a_c, len(plan), sample))
        if progress:
            progress(f"code {all_codes[i]}: {len(plan)} units, stage A {a_c:.2f} s, {len(sample)} sampled")
    m = len(per_code)

    def total(value_of_code, value_of_unit):
        ys, within = [], 0.0
        for a_c, U, sample in per_code:
            vals = [value_of_unit(s) for s in sample]
            k = len(vals)
            mean = sum(vals) / k if k else 0.0
            ys.append(value_of_code(a_c, U) + U * mean)
            if k > 1 and U > k:
                s2 = sum((x - mean) ** 2 for x in vals) / (k - 1)
                within += U * U * (1 - k / U) * s2 / k
        ybar = sum(ys) / m
        s1 = sum((y - ybar) ** 2 for y in ys) / (m - 1) if m > 1 else 0.0
        var = C * C * (1 - m / C) * s1 / m + C / m * within
        return C * ybar, math.sqrt(max(var, 0.0))

    cpu, cpu_se = total(lambda a, U: a, lambda s: s[0])
    chains, chains_se = total(lambda a, U: 0.0, lambda s: s[1])
    n_units, units_se = total(lambda a, U: U, lambda s: 0.0)
    return {"dof": dof, "links": links, "v": v, "codes": C, "codes_sampled": m, "units_per_code": units,
            "units_sampled": sum(len(s) for _, _, s in per_code), "seed": seed,
            "units_projected": round(n_units), "units_se": round(units_se),
            "chains_projected": round(chains), "chains_se": round(chains_se),
            "published": PUBLISHED.get(links) if dof == 1 and v == "0" else None,
            "cpu_s_projected": round(cpu, 1), "cpu_s_se": round(cpu_se, 1),
            "sampling_s": round(time.perf_counter() - start, 1)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("links", type=int)
    parser.add_argument("--dof", type=int, default=1)
    parser.add_argument("--v", default="0")
    parser.add_argument("--codes", type=int, default=10**6,
                        help="codes drawn (stage A runs on each; default: all of them, no first-stage error)")
    parser.add_argument("--units", type=int, default=40, help="units drawn from each drawn code")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--efficiency", type=float, default=0.85,
                        help="parallel efficiency of 2 workers (measured: see PROFILE.md)")
    parser.add_argument("--json", help="append the result as one JSON line to this file")
    args = parser.parse_args(argv)
    result = project(args.dof, args.links, codes=args.codes, units=args.units, seed=args.seed, v=args.v,
                     progress=lambda s: print(s, file=sys.stderr))
    result["wall_2_workers_h"] = round(result["cpu_s_projected"] / 2 / args.efficiency / 3600, 2)
    result["wall_2_workers_h_2se"] = round(2 * result["cpu_s_se"] / 2 / args.efficiency / 3600, 2)
    print(json.dumps(result))
    if args.json:
        with open(args.json, "a") as fh:
            fh.write(json.dumps(result) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
