"""Where the time of a chain query goes: per stage, per unit size, per multiple-joint count v.

One process, inline (no pool), with light timers wrapped around the engine's functions
from outside (this script only; the engine is not changed).  Times are CPU seconds of this
process (``time.process_time``), so other work on a shared machine hardly changes them.
Stages:

* ``number synthesis``  the CP-SAT model of the counting equations (codes);
* ``stage A``           branch multigraphs of every code (CP-SAT + nauty);
* ``stage B model``     building the CP-SAT model of one multigraph (``realise`` minus the rest),
  of which ``CpModel()`` is the construction of the empty model object itself (``cp_model.CpModel``);
* ``stage B CP-SAT``    enumerating its solutions (``all_solutions``);
* ``automorphisms``     nauty's group of H (lex-leader constraints);
* ``sub-chain test``    ``_exact_test``: the exact test of a unit's candidates in one batch (none
  where stage B's model wrote the exact conditions: simple joints);
* ``Chain``             building the ``Chain`` objects (``_expand``);
* ``nauty``             certificates of the chains (duplicates removed);
* ``placements``        the compiled kernel's search over the placements (large queries), the
  rest of stage B being its per-unit set-up.

``--by-code`` adds, per code, stage A, the automorphisms, the kernel's placements and the rest of
stage B (CPU seconds).

Run: ``python benchmarks/profile_stages.py 12 [--v 0..10] [--count] [--json FILE]``.  Timers cost
about 1 µs per call; the total is printed next to the sum of the stages.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

T: dict[str, float] = defaultdict(float)
N: dict[str, int] = defaultdict(int)
STAGE_A: dict[str, float] = defaultdict(float)  # stage A's CPU seconds by code


STAGE = ["stage B"]  # the stage running now: CP-SAT time is charged to it


def _timed(name, fn, stage: str | None = None):
    def wrapper(*args, **kwargs):
        key = name if name != "CP-SAT" else f"{STAGE[-1]} CP-SAT"
        if stage:
            STAGE.append(stage)
        t0 = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            T[key] += time.process_time() - t0
            N[key] += 1
            if stage:
                STAGE.pop()

    return wrapper


def instrument() -> None:
    """Wrap the engine's stage functions with timers (this process only)."""
    from synth.synthesis import _cpsat, stage_a, stage_b, type_synthesis as ts
    from synth.structure.chain import Chain

    ts.number_synthesis = _timed("number synthesis", ts.number_synthesis, "number synthesis")
    timed_a = _timed("stage A", ts.contracted_graphs, "stage A")

    def stage_a_by_code(code, conv):
        t0 = time.process_time()
        try:
            return timed_a(code, conv)
        finally:
            STAGE_A[str(code)] += time.process_time() - t0

    ts.contracted_graphs = stage_a_by_code
    ts.realise = _timed("stage B (all)", ts.realise)
    ts.count_realised = _timed("stage B (all)", ts.count_realised)
    # stages A and B import the solver when they run: the timer wraps it where they find it
    # (number synthesis too, whose time is taken out of stage B's below)
    _cpsat.all_solutions = _timed("CP-SAT", _cpsat.all_solutions)
    stage_b._exact_test = _timed("sub-chain test", stage_b._exact_test)
    stage_b._expand = _timed("Chain", stage_b._expand)
    stage_a.Contracted.edge_group = _timed("automorphisms", stage_a.Contracted.edge_group)
    stage_a.Contracted.bundle_group = _timed("automorphisms", stage_a.Contracted.bundle_group)  # (the kernel's)
    from synth.synthesis import _stage_b_kernel

    _stage_b_kernel.place = _timed("placements (kernel)", _stage_b_kernel.place)
    cert = Chain.certificate.fget
    Chain.certificate = property(_timed("nauty", cert))

    class TimedModel(_cpsat.cp_model.CpModel):
        def __init__(self, *args, **kwargs):
            t0 = time.process_time()
            super().__init__(*args, **kwargs)
            T["CpModel()"] += time.process_time() - t0
            N["CpModel()"] += 1

    _cpsat.cp_model.CpModel = TimedModel  # the stages build their models as cp_model.CpModel()


def profile(dof: int, links: int, v: str, count: bool = False) -> dict:
    """Stage times, per-unit records and candidates by v of one inline query (its listing, or
    with ``count`` its ``--count``, which builds chains only where it must)."""
    from synth.synthesis import type_synthesis as ts

    T.clear()
    N.clear()
    STAGE_A.clear()
    t0 = time.process_time()
    units = ts.plan_units(dof, links, v=v, workers=1)
    t_plan = time.process_time() - t0
    records = []
    for unit in units:
        stats: dict = {}
        before = T["automorphisms"], T["placements (kernel)"]
        t1 = time.process_time()
        if count and unit.contracted is not None:
            found = ts.count_realised(unit.code, unit.contracted, unit.conventions, stats)
        else:
            found = len(ts.run_unit(unit, stats))
        records.append({"code": str(unit.code), "v": unit.code.v,
                        "edges": len(unit.contracted.edges) if unit.contracted else 0,
                        "candidates": stats.get("candidates", 0), "chains": found,
                        "seconds": time.process_time() - t1,
                        "automorphisms": T["automorphisms"] - before[0],
                        "placements": T["placements (kernel)"] - before[1]})
    total = time.process_time() - t0
    stage_b = T["stage B (all)"]
    inner = sum(T[k] for k in ("stage B CP-SAT", "sub-chain test", "Chain", "nauty", "automorphisms",
                                "placements (kernel)"))
    stages = {
        "number synthesis": T["number synthesis"],
        "stage A": T["stage A"],
        "stage B model (CpModel() included)": stage_b - inner,
        "  of which CpModel()": T["CpModel()"],
        "stage B CP-SAT": T["stage B CP-SAT"],
        "automorphisms of H": T["automorphisms"],
        "placements (kernel)": T["placements (kernel)"],
        "sub-chain test": T["sub-chain test"],
        "Chain": T["Chain"],
        "nauty": T["nauty"],
        "plan, outside stages": t_plan - T["number synthesis"] - T["stage A"],
        "units, outside realise": total - t_plan - stage_b,
    }
    return {"dof": dof, "links": links, "v": v, "units": len(units), "total": total, "stage A": dict(STAGE_A),
            "chains": sum(r["chains"] for r in records), "stages": stages, "calls": dict(N), "records": records}


def by_size(records: list[dict]) -> list[dict]:
    """Units grouped by the number of chains they produce."""
    bins = [(0, 0), (1, 9), (10, 99), (100, 999), (1000, 9999), (10000, 10**9)]
    total = sum(r["seconds"] for r in records) or 1.0
    out = []
    for lo, hi in bins:
        rs = [r for r in records if lo <= r["chains"] <= hi]
        if not rs:
            continue
        secs = sum(r["seconds"] for r in rs)
        chains = sum(r["chains"] for r in rs)
        out.append({"chains per unit": f"{lo}–{hi}" if hi < 10**9 else f"{lo}+", "units": len(rs),
                    "seconds": round(secs, 3), "share": f"{100 * secs / total:.0f} %",
                    "ms per unit": round(1000 * secs / len(rs), 2),
                    "µs per chain": round(1e6 * secs / chains, 1) if chains else None})
    return out


def by_code(records: list[dict], stage_a: dict[str, float]) -> list[dict]:
    """Per code: units, chains, stage A, automorphisms of H, the kernel's placements and the rest
    of stage B (per-unit set-up), CPU seconds."""
    out = []
    for code in dict.fromkeys(r["code"] for r in records):
        rs = [r for r in records if r["code"] == code]
        autos, places = sum(r["automorphisms"] for r in rs), sum(r["placements"] for r in rs)
        out.append({"code": code, "units": len(rs), "chains": sum(r["chains"] for r in rs),
                    "stage A": round(stage_a.get(code, 0.0), 2), "automorphisms": round(autos, 2),
                    "placements": round(places, 2),
                    "rest of stage B": round(sum(r["seconds"] for r in rs) - autos - places, 2)})
    return out


def by_v(records: list[dict]) -> list[dict]:
    """Candidates (CP-SAT solutions) per chain and time, by multiple-joint count v."""
    out = []
    for v in sorted({r["v"] for r in records}):
        rs = [r for r in records if r["v"] == v]
        chains = sum(r["chains"] for r in rs)
        cands = sum(r["candidates"] for r in rs)
        out.append({"v": v, "units": len(rs), "chains": chains, "candidates": cands,
                    "candidates per chain": round(cands / chains, 3) if chains else None,
                    "seconds": round(sum(r["seconds"] for r in rs), 3)})
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("links", type=int)
    parser.add_argument("--dof", type=int, default=1)
    parser.add_argument("--v", default="0")
    parser.add_argument("--count", action="store_true", help="profile the count (chains built only where needed)")
    parser.add_argument("--by-code", action="store_true", help="stage A and stage B's parts per code")
    parser.add_argument("--json", help="write the full result (per-unit records included) here")
    args = parser.parse_args(argv)
    instrument()
    result = profile(args.dof, args.links, args.v, args.count)
    print(f"W={args.dof} n={args.links} v={args.v}{' (count)' if args.count else ''}: {result['chains']} chains, {result['units']} units, "
          f"{result['total']:.3f} CPU s inline")
    for name, secs in result["stages"].items():
        print(f"  {name:38s} {secs:8.3f} s  {100 * secs / result['total']:5.1f} %")
    for row in by_size(result["records"]):
        print("  ", row)
    if args.by_code:
        for row in by_code(result["records"], result["stage A"]):
            print("  ", row)
    if args.v != "0":
        for row in by_v(result["records"]):
            print("  ", row)
    slow = sorted(result["records"], key=lambda r: -r["seconds"])[:5]
    print("  slowest units:", [(r["code"], r["edges"], r["chains"], round(r["seconds"], 3)) for r in slow])
    if args.json:
        Path(args.json).write_text(json.dumps(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
