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
±2 SE covered the truth in 63 % of 30 seeds, not 95 %; read it as an order of magnitude.  At 16
links (every code, 30 units each, 1415 of 58 559 units) the chains came out +83 % (1.5 SE): see
PROFILE.md, section 7, for every check and the ratio estimator (``*_mean`` keys: the plain mean).
With the engine of 25 Nov 2026 (PROFILE.md, section 12; 30 units of every code): 14 links 11.8 ± 0.8
CPU s against 11.1 real, 16 links 720 ± 80 against 742 real, 18 links 80 025 ± 10 431 CPU s, i.e.
13.1 ± 3.4 h on 2 workers.

Run: ``python benchmarks/bench_projection.py 18 [--codes M] [--units 40] [--seed 1] [--json FILE]``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import random
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SAVE_EVERY = 30.0  # seconds between writes of --cache during a run (and once at its end)
PUBLISHED = {4: 1, 6: 2, 8: 16, 10: 230, 12: 6856, 14: 318162, 16: 19819281, 18: 1535380884}  # OEIS A233288


def _cpu(fn, *args):
    t0 = time.process_time()
    out = fn(*args)
    return out, time.process_time() - t0


def size_hint(unit) -> float:
    """A unit's size known before it runs: distributions of its binary links over the strings of
    H, C(n2 + e − 1, e − 1), divided by the order of H's automorphism group (each chain is one
    orbit of distributions).  Used as the auxiliary variable of the ratio estimator."""
    import pynauty

    if unit.contracted is None:
        return 1.0
    n2, e = unit.code.count(2), len(unit.contracted.edges)
    _, size1, size2, _, _ = pynauty.autgrp(unit.contracted._subdivided())
    return math.comb(n2 + e - 1, e - 1) / (size1 * 10.0**size2)


def _plans(all_codes, conv, drawn, cache: str | None):
    """Stage A of the drawn codes: {index: (units, CPU s)}, read from / written to ``cache``."""
    import pickle

    from synth.synthesis.type_synthesis import job_units

    def save():  # whole or not at all: a run killed while writing keeps the previous file
        temporary = Path(f"{cache}.partial")
        temporary.write_bytes(pickle.dumps(stored))
        os.replace(temporary, cache)

    stored = {}
    if cache and Path(cache).exists():
        stored = pickle.loads(Path(cache).read_bytes())
    out, saved, added = {}, time.monotonic(), False
    for i in drawn:
        key = str(all_codes[i])
        if key not in stored:
            stored[key] = _cpu(job_units, (all_codes[i], conv))
            added = True
            if cache and time.monotonic() - saved > SAVE_EVERY:  # not after every code: the file grows with them
                save()
                saved, added = time.monotonic(), False
        out[i] = stored[key]
    if cache and added:
        save()
    return out


def project(dof: int, links: int, *, codes: int, units: int, seed: int, v="0", progress=None,
            cache: str | None = None) -> dict:
    """Sample ``codes`` codes and ``units`` units of each; return the projected totals and their errors.

    Two estimators of the within-code totals: the plain mean (``*_mean`` keys, unbiased) and the
    ratio to :func:`size_hint`, known for every unit (the main keys: far smaller error when the
    units' sizes are uneven, bias of order 1/k).  ``cache`` keeps stage A's results in a file so
    that another seed does not redo it (its CPU time is kept with it).
    """
    from synth import ChainQuery
    from synth.synthesis.type_synthesis import count_unit, plan_jobs

    rng = random.Random(seed)
    start = time.perf_counter()
    jobs = plan_jobs(ChainQuery(dof, links, v=v))
    all_codes, conv = [c for c, _ in jobs], jobs[0][1]
    C = len(all_codes)
    drawn = sorted(rng.sample(range(C), min(codes, C)))
    plans = _plans(all_codes, conv, drawn, cache)
    per_code = []  # (a_c, U_c, X_c, [(x_u, t_u, chains_u)])
    for i in drawn:
        plan, a_c = plans[i]
        hints = [size_hint(u) for u in plan]
        picked = rng.sample(range(len(plan)), min(units, len(plan)))
        sample = []
        for k in picked:
            counts, t_u = _cpu(count_unit, plan[k])  # what `chains --count` runs
            chains = sum(counts.values())
            sample.append((hints[k], t_u, chains))
        per_code.append((a_c, len(plan), sum(hints), sample))
        if progress:
            progress(f"code {all_codes[i]}: {len(plan)} units, stage A {a_c:.2f} s, {len(sample)} sampled")
    m = len(per_code)

    def total(value_of_code, which: int | None, ratio: bool):
        ys, within = [], 0.0
        for a_c, U, X, sample in per_code:
            vals = [s[which] for s in sample] if which is not None else []
            xs = [s[0] for s in sample]
            k = len(vals)
            if k and ratio and sum(xs) > 0:
                R = sum(vals) / sum(xs)
                est, resid = X * R, [y - R * x for y, x in zip(vals, xs)]
            else:
                mean = sum(vals) / k if k else 0.0
                est, resid = U * mean, [y - mean for y in vals]
            ys.append(value_of_code(a_c, U) + est)
            if k > 1 and U > k:
                s2 = sum(r * r for r in resid) / (k - 1)
                within += U * U * (1 - k / U) * s2 / k
        ybar = sum(ys) / m
        s1 = sum((y - ybar) ** 2 for y in ys) / (m - 1) if m > 1 else 0.0
        var = C * C * (1 - m / C) * s1 / m + C / m * within
        return C * ybar, math.sqrt(max(var, 0.0))

    cpu, cpu_se = total(lambda a, U: a, 1, True)
    chains, chains_se = total(lambda a, U: 0.0, 2, True)
    cpu_mean, cpu_mean_se = total(lambda a, U: a, 1, False)
    chains_mean, chains_mean_se = total(lambda a, U: 0.0, 2, False)
    n_units, units_se = total(lambda a, U: U, None, False)
    return {"dof": dof, "links": links, "v": v, "codes": C, "codes_sampled": m, "units_per_code": units,
            "units_sampled": sum(len(s) for *_, s in per_code), "seed": seed,
            "units_projected": round(n_units), "units_se": round(units_se),
            "chains_projected": round(chains), "chains_se": round(chains_se),
            "chains_mean": round(chains_mean), "chains_mean_se": round(chains_mean_se),
            "published": PUBLISHED.get(links) if dof == 1 and v == "0" else None,
            "cpu_s_projected": round(cpu, 1), "cpu_s_se": round(cpu_se, 1),
            "cpu_s_mean": round(cpu_mean, 1), "cpu_s_mean_se": round(cpu_mean_se, 1),
            "stage_a_cpu_s": round(sum(a for a, *_ in per_code), 1),
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
    parser.add_argument("--cache", help="keep stage A's results in this file (another seed reuses them)")
    args = parser.parse_args(argv)
    result = project(args.dof, args.links, codes=args.codes, units=args.units, seed=args.seed, v=args.v,
                     progress=lambda s: print(s, file=sys.stderr), cache=args.cache)
    result["wall_2_workers_h"] = round(result["cpu_s_projected"] / 2 / args.efficiency / 3600, 2)
    result["wall_2_workers_h_2se"] = round(2 * result["cpu_s_se"] / 2 / args.efficiency / 3600, 2)
    print(json.dumps(result))
    if args.json:
        with open(args.json, "a") as fh:
            fh.write(json.dumps(result) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
