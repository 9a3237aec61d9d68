"""Counts by code of a fixed set of queries, recorded once and compared after every engine change.

Issue 31 asks that the engine's counts by code stay identical at every size up to 16 links for
W = 1…3, h = 2…6, open chains and multiple joints.  ``record`` counts every query of
:data:`QUERIES` (``count_chains``, by code) and writes them to a JSON file with the commit and
the CPU seconds; ``compare`` counts them again with the engine of this tree and prints each
query whose counts differ, code by code (exit 1 if any does); ``--method orbits`` counts them by
orbits instead (``count_chains(method="orbits")``), and leaves out, saying so, the queries that
method refuses (prismatic pairs, crank requirements, multiple joints).  ``--list`` also lists the chains
of the queries up to ``--list-max`` chains and checks that the listing's codes equal the count's.

Run from the project root::

    python benchmarks/bycode.py record benchmarks/out/bycode_base.json
    python benchmarks/bycode.py compare benchmarks/out/bycode_base.json [--only SUBSTRING] [--list] [--method orbits]
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path.cwd()
sys.path.insert(0, str(ROOT))


def _q(**kw):
    return kw


QUERIES = (
    # planar 1-DOF, every size to 16 links
    [_q(dof=1, links=n) for n in range(4, 17, 2)]
    # W = 2 and 3, fractionated chains included (the default) and not
    + [_q(dof=2, links=n) for n in range(5, 16, 2)]
    + [_q(dof=2, links=n, fractionated=False) for n in range(5, 14, 2)]
    + [_q(dof=3, links=n) for n in range(6, 17, 2)]
    + [_q(dof=3, links=n, fractionated=False) for n in range(6, 15, 2)]
    # trusses and the other convention
    + [_q(dof=0, links=n) for n in range(3, 14, 2)]
    + [_q(dof=0, links=n, rigid_subchains=False) for n in range(5, 14, 2)]
    + [_q(dof=2, links=n, rigid_subchains=True) for n in range(5, 14, 2)]
    + [_q(dof=1, links=n, planar_only=True) for n in range(8, 15, 2)]
    # every motion space h
    + [_q(dof=1, links=n, h=2) for n in range(3, 11)]
    + [_q(dof=2, links=n, h=2) for n in range(3, 10)]
    + [_q(dof=3, links=n, h=2) for n in range(3, 10)]
    + [_q(dof=1, links=n, h=4) for n in (5, 8, 11, 14)]
    + [_q(dof=2, links=n, h=4) for n in (6, 9, 12, 15)]
    + [_q(dof=3, links=n, h=4) for n in (7, 10, 13, 16)]
    + [_q(dof=1, links=n, h=5) for n in (6, 10, 14)]
    + [_q(dof=2, links=n, h=5) for n in (7, 11, 15)]
    + [_q(dof=1, links=n, h=6) for n in (7, 12)]
    + [_q(dof=3, links=n, h=6) for n in (9, 14)]
    # open chains
    + [_q(dof=3, links=n, n1=(0, 3)) for n in range(4, 13)]
    + [_q(dof=2, links=n, n1=(0, 2)) for n in range(3, 12)]
    + [_q(dof=4, links=n, n1=(1, 4)) for n in range(4, 11)]
    # multiple joints
    + [_q(dof=1, links=n, v=(0, n - 2)) for n in range(4, 13, 2)]
    + [_q(dof=2, links=n, v=(0, n - 2)) for n in range(5, 12, 2)]
    + [_q(dof=3, links=n, v=(0, 4)) for n in range(6, 13, 2)]
    + [_q(dof=1, links=n, h=2, v=(0, 3)) for n in range(4, 9)]
    + [_q(dof=1, links=n, h=4, v=(0, 4)) for n in (5, 8, 11)]
    + [_q(dof=0, links=n, v=(0, 4)) for n in range(5, 12, 2)]
    + [_q(dof=1, links=10, v=(0, 6), max_multiplicity=3), _q(dof=1, links=10, v=(0, 5), cranks={5: 5})]
    # prismatic pairs (skeletons with slack)
    + [_q(dof=1, links=n, prismatic="0..") for n in range(4, 9)]
    + [_q(dof=2, links=n, prismatic="0..") for n in range(5, 9)]
    + [_q(dof=1, links=n, prismatic="1..", idle_joints=True) for n in range(4, 8)]
    + [_q(dof=1, links=n, prismatic="0..2", cylinders="swinging=2") for n in range(4, 9)]
)


def name(query: dict) -> str:
    return ",".join(f"{k}={v}" for k, v in query.items())


def _cpu() -> float:
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def count(query: dict, workers: int, method: str = "listing") -> tuple[dict, float]:
    """Counts by code and CPU seconds; a query the engine refuses counts as ``{"refused": sentence}``
    (a refusal must stay a refusal, with the same words)."""
    import synth

    t0 = _cpu()
    try:
        by_code = synth.count_chains(**query, workers=workers, method=method)["by_code"]
    except synth.SynthesisError as exc:
        by_code = {"refused": str(exc)}
    return by_code, _cpu() - t0


def listed(query: dict) -> dict:
    import synth

    out: dict[str, int] = {}
    for chain in synth.type_synthesis(**query, workers=2):
        key = str(chain.code) + chain.kind_suffix
        out[key] = out.get(key, 0) + 1
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=["record", "compare"])
    parser.add_argument("file")
    parser.add_argument("--only", help="queries whose name contains this")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--list", action="store_true", help="list the chains too, where few enough")
    parser.add_argument("--list-max", type=int, default=400_000)
    parser.add_argument("--method", choices=["listing", "orbits"], default="listing", help="how compare counts")
    args = parser.parse_args()
    queries = [q for q in QUERIES if args.only is None or args.only in name(q)]
    path = Path(args.file)
    if args.mode == "record":
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
        record = {"commit": commit, "queries": {}}
        if path.exists():
            record = json.loads(path.read_text())
        for q in queries:
            if name(q) in record["queries"]:
                continue
            by_code, cpu = count(q, args.workers)
            total = sum(n for n in by_code.values() if isinstance(n, int))
            record["queries"][name(q)] = {"by_code": by_code, "count": total, "cpu_s": round(cpu, 2)}
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(record, indent=1))
            print(f"{name(q)}: {total} chains, {cpu:.1f} CPU s", flush=True)
        return 0
    try:
        record = json.loads(path.read_text())["queries"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        print(f"bycode: {path} is not a record of counts by code ({type(exc).__name__}); make one with "
              f"'bycode.py record FILE'", file=sys.stderr)
        return 2
    bad = skipped = 0
    for q in queries:
        if args.method == "orbits" and (q.get("prismatic") is not None or q.get("cranks")):
            print(f"{name(q)}: not counted by orbits (the method refuses it)")
            skipped += 1
            continue
        if name(q) not in record:
            print(f"{name(q)}: not recorded")
            continue
        want = record[name(q)]
        t0 = time.perf_counter()
        got, cpu = count(q, args.workers, args.method)
        status = "same" if got == want["by_code"] else "DIFFERENT"
        if got != want["by_code"]:
            bad += 1
            for code in sorted(set(got) | set(want["by_code"])):
                if got.get(code) != want["by_code"].get(code):
                    print(f"   {code}: {want['by_code'].get(code)} -> {got.get(code)}")
        if args.list and want["count"] <= args.list_max and got == want["by_code"]:
            if listed(q) != got:
                bad += 1
                status += ", LISTING DIFFERS"
            else:
                status += ", listing same"
        print(f"{name(q)}: {status} ({sum(n for n in got.values() if isinstance(n, int))} chains; CPU {want['cpu_s']} -> {cpu:.2f} s, "
              f"wall {time.perf_counter() - t0:.2f} s)", flush=True)
    print(f"{len(queries)} queries, {bad} different" + (f", {skipped} refused by the method" if skipped else ""))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
