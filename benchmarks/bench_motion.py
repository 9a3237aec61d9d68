"""Speed of the motion layer: steps per second of a four-bar and a six-bar, side by side with
pylinkage 1.3.0's numba solver, and every 1-DOF mechanism of 8 links swept through 360 steps.

pylinkage is not a dependency of the project: it runs in a virtual environment of its own, made once
with

    python -m venv /tmp/pylinkage-venv
    /tmp/pylinkage-venv/bin/pip install pylinkage==1.3.0 numba

(``--pylinkage-python PATH`` names another interpreter; without one the comparison is left out).
The same mechanisms are built in both: the crank-rocker of models/motion_four_bar.toml and the Watt
II six-bar of models/motion_watt_ii.toml, and their positions are compared at common inputs before
anything is timed (pylinkage picks each RRR dyad's intersection nearest the previous step, the
engine keeps the pose's branch; on these mechanisms, which never pass a dead position, both follow
the same branch).  Each timing is the best of ``--reps`` runs after a warm-up (numba compiles on the
first call of both), in CPU seconds (the machine is shared), pinned to one core by ``taskset``.

    taskset -c 0 python benchmarks/bench_motion.py [--steps 1000000] [--reps 5] [--out benchmarks/MOTION.md]

writes a table and a plot (benchmarks/figures/motion_speed.png) into MOTION.md.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import synth  # noqa: E402
from synth.motion import read_linkage, sweep  # noqa: E402
from synth.motion_draw import linkage_from_layout  # noqa: E402
from mechbase import save_figure  # noqa: E402

DEFAULT_VENV = "/tmp/pylinkage-venv/bin/python"

# The pylinkage side: the same two mechanisms, from the joint positions of the pose (passed as
# JSON), timed with step_fast (its numba loop), and their trajectories at a few steps returned.
PYLINKAGE = r"""
import json, math, sys, time
import numpy as np
from pylinkage.components import Ground
from pylinkage.actuators import Crank
from pylinkage.dyads import RRRDyad, FixedDyad
from pylinkage.simulation import Linkage

job = json.loads(sys.argv[1])
p = {k: tuple(v) for k, v in job["points"].items()}
steps, reps = job["steps"], job["reps"]
dist = lambda a, b: math.dist(p[a], p[b])
angle = lambda a, b: math.atan2(p[b][1] - p[a][1], p[b][0] - p[a][0])

def four_bar():
    o2, o4 = Ground(*p["0-1"], name="O2"), Ground(*p["0-3"], name="O4")
    crank = Crank(anchor=o2, radius=dist("0-1", "1-2"), angular_velocity=2 * math.pi / steps,
                  initial_angle=angle("0-1", "1-2"))
    b = RRRDyad(crank.output, o4, distance1=dist("1-2", "2-3"), distance2=dist("0-3", "2-3"))
    return Linkage([o2, o4, crank, b]), ["O2", "O4", "A", "B"]

def watt_ii():
    o3, o1, o4 = Ground(*p["0-3"]), Ground(*p["0-1"]), Ground(*p["0-4"])
    crank = Crank(anchor=o3, radius=dist("0-3", "2-3"), angular_velocity=2 * math.pi / steps,
                  initial_angle=angle("0-3", "2-3"))
    b = RRRDyad(crank.output, o1, distance1=dist("2-3", "1-2"), distance2=dist("0-1", "1-2"))
    c = FixedDyad(anchor1=o1, anchor2=b, distance=dist("0-1", "1-5"),
                  angle=angle("0-1", "1-5") - angle("0-1", "1-2"))
    d = RRRDyad(c, o4, distance1=dist("1-5", "4-5"), distance2=dist("0-4", "4-5"))
    return Linkage([o3, o1, o4, crank, b, c, d]), ["O3", "O1", "O4", "A", "B", "C", "D"]

linkage, names = {"four_bar": four_bar, "watt_ii": watt_ii}[job["mechanism"]]()
linkage.step_fast(iterations=10)  # numba compiles (or loads its cache)
best = math.inf
for _ in range(reps):
    linkage, names = {"four_bar": four_bar, "watt_ii": watt_ii}[job["mechanism"]]()
    start = time.process_time()
    trajectory = linkage.step_fast(iterations=steps)
    best = min(best, time.process_time() - start)
picks = [0, steps // 7, steps // 3, steps // 2, steps - 1]
print(json.dumps({"seconds": best, "nan": bool(np.isnan(trajectory).any()),
                  "samples": {str(s): trajectory[s].tolist() for s in picks}}))
"""


def _engine(linkage, steps: int, reps: int) -> tuple[float, object]:
    """Best time of ``reps`` sweeps of ``steps`` steps (after a warm-up), and the last motion."""
    sweep(linkage, steps=1000)
    best, motion = math.inf, None
    for _ in range(reps):
        start = time.process_time()
        motion = sweep(linkage, steps=steps)
        best = min(best, time.process_time() - start)
    return best, motion


def _pylinkage(python: str, mechanism: str, linkage, steps: int, reps: int) -> dict | None:
    names = {k: synth.motion.joint_name(linkage.chain, k) for k in range(len(linkage.chain.joints))}
    job = {"mechanism": mechanism, "steps": steps, "reps": reps,
           "points": {names[k]: [float(x), float(y)] for k, (x, y) in enumerate(linkage.points)}}
    done = subprocess.run([python, "-c", PYLINKAGE, json.dumps(job)], capture_output=True, text=True, timeout=1800)
    if done.returncode != 0:
        print(f"pylinkage failed: {done.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    return json.loads(done.stdout)


def _agree(motion, samples: dict, order: list[str], steps: int) -> float:
    """The largest distance between the engine's and pylinkage's joints at the sampled steps (pylinkage's
    row s is the pose after s + 1 steps: the crank turned by (s + 1)·2π/steps from the pose).  Its
    components come in the order Ground…, crank output, dyads…; ``order`` names the engine's joints
    in that order."""
    linkage = motion.linkage
    index = {synth.motion.joint_name(linkage.chain, k): k for k in range(len(linkage.chain.joints))}
    phi0 = float(motion.inputs[0, 0])
    worst = 0.0
    for s, points in samples.items():
        value = phi0 + (int(s) + 1) * 2 * math.pi / steps
        at = sweep(linkage, steps=2, start=value, stop=value + 1e-9).joints[0]
        for name, xy in zip(order, points):
            worst = max(worst, math.dist(at[index[name]], xy))
    return worst


def _every_mechanism(links: int) -> dict:
    """Every 1-DOF mechanism of ``links`` links dimensioned by its drawing and swept through 360 steps
    (CPU seconds): how many moved, how many needed their drawing's joints moved, and those without a
    moving pose with the reason."""
    build = run = 0.0
    moved = nudged = 0
    failed, kinds = [], {"dyads": 0, "Newton": 0}
    for mechanism in synth.mechanisms(1, links, workers=1):
        start = time.process_time()
        try:
            linkage = linkage_from_layout(mechanism)
        except synth.MotionError as exc:
            failed.append(f"{mechanism.chain.compact()} frame {mechanism.frame}: {exc}")
            continue
        finally:
            build += time.process_time() - start
        nudged += linkage.note is not None
        start = time.process_time()
        motion = sweep(linkage, steps=360)
        run += time.process_time() - start
        # a linkage of dyads reports their transmission angles; one moved by Newton's method none
        kinds["dyads" if motion.transmission else "Newton"] += 1
        moved += 1
        print(f"{moved + len(failed)} mechanisms, {build:.1f} s for poses, {run:.2f} s for sweeps", file=sys.stderr,
              end="\r", flush=True)
    return {"links": links, "moved": moved, "nudged": nudged, "failed": failed, "build_seconds": build,
            "sweep_seconds": run, "by_solver": kinds}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=1_000_000, help="steps of each timed sweep (default 1e6)")
    parser.add_argument("--reps", type=int, default=5, help="timed runs, the best kept (default 5)")
    parser.add_argument("--pylinkage-python", default=DEFAULT_VENV, help=f"pylinkage's interpreter ({DEFAULT_VENV})")
    parser.add_argument("--links", type=int, default=8, help="every 1-DOF mechanism of this many links (default 8)")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "MOTION.md"))
    args = parser.parse_args(argv)
    have_pylinkage = Path(args.pylinkage_python).exists()
    rows = []
    for mechanism, scene, order in (("four_bar", "motion_four_bar", ["0-1", "0-3", "1-2", "2-3"]),
                                    ("watt_ii", "motion_watt_ii", ["0-3", "0-1", "0-4", "2-3", "1-2", "1-5", "4-5"])):
        linkage = read_linkage(ROOT / "models" / f"{scene}.toml")
        seconds, motion = _engine(linkage, args.steps, args.reps)
        row = {"mechanism": mechanism, "steps": args.steps, "engine_seconds": seconds,
               "engine_steps_per_second": args.steps / seconds}
        if have_pylinkage:
            theirs = _pylinkage(args.pylinkage_python, mechanism, linkage, args.steps, args.reps)
            if theirs is not None:
                row.update(pylinkage_seconds=theirs["seconds"], pylinkage_steps_per_second=args.steps / theirs["seconds"],
                           ratio=theirs["seconds"] / seconds,
                           largest_difference=_agree(motion, theirs["samples"], order, args.steps),
                           pylinkage_nan=theirs["nan"])
        rows.append(row)
        print(json.dumps(row), flush=True)
    every = _every_mechanism(args.links)
    print(json.dumps(every), flush=True)
    _write(Path(args.out), rows, every, args)
    return 0


def _write(out: Path, rows: list[dict], every: dict, args) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure = out.parent / "figures" / "motion_speed.png"
    figure.parent.mkdir(exist_ok=True)
    fig, ax = plt.subplots(figsize=(6, 3.2))
    names = [r["mechanism"].replace("_", " ") for r in rows]
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [r["engine_steps_per_second"] / 1e6 for r in rows], 0.4, label="mechsynth (synth.motion.sweep)",
           color="#1f3a5f")
    if all("pylinkage_steps_per_second" in r for r in rows):
        ax.bar(x + 0.2, [r["pylinkage_steps_per_second"] / 1e6 for r in rows], 0.4,
               label="pylinkage 1.3.0 (step_fast, numba)", color="#c0632b")
    ax.set_xticks(x, names)
    ax.set_ylabel("million steps per second")
    ax.set_title(f"position analysis, {args.steps:,} steps, best of {args.reps}, one core", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, figure, dpi=110)
    plt.close(fig)
    lines = ["# Motion: speed of the position analysis", "",
             f"`python benchmarks/bench_motion.py --steps {args.steps} --reps {args.reps}` on "
             f"{platform.node()} ({platform.processor() or platform.machine()}, {os.cpu_count()} cores shared with "
             f"other work; load average {os.getloadavg()[0]:.1f} at the end), {time.strftime('%d %b %Y %H:%M UTC', time.gmtime())}.",
             "pylinkage 1.3.0 ran in its own virtual environment with numba (see the script's docstring).", "",
             "| mechanism | steps | mechsynth steps/s | pylinkage steps/s | speed ratio mechsynth : pylinkage | largest difference |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        theirs = (f"{r['pylinkage_steps_per_second']:,.0f} | {r['ratio']:.2f}× | {r['largest_difference']:.1e}"
                  if "ratio" in r else "— | — | —")
        lines.append(f"| {r['mechanism'].replace('_', ' ')} | {r['steps']:,} | {r['engine_steps_per_second']:,.0f} | "
                     f"{theirs} |")
    lines += ["", f"![steps per second](figures/{figure.name})", ""]
    ratios = [r["ratio"] for r in rows if "ratio" in r]
    if ratios:
        cores = len(os.sched_getaffinity(0))
        pinned = "pinned to one core" if cores == 1 else f"on {cores} cores (not pinned: run it under `taskset -c 0`)"
        lines += [f"The issue's goal is 3× pylinkage: here {min(ratios):.1f}× to {max(ratios):.1f}× (CPU time, best of "
                  f"{args.reps}, {pinned}). The largest difference is between the two solvers' joint positions at "
                  "the same inputs (pylinkage accumulates its crank angle step by step).", ""]
    lines += [f"Every 1-DOF mechanism of {every['links']} links ({every['moved'] + len(every['failed'])}, a frame each "
              f"up to symmetry; {every['moved']} moved: {every['by_solver']['dyads']} by the dyads' closed forms, "
              f"{every['by_solver']['Newton']} by Newton's method), dimensioned by its drawing "
              f"(`synth.motion_draw.linkage_from_layout`; {every['nudged']} needed their joints moved off the drawing's "
              f"pose) and swept through 360 steps: {every['sweep_seconds']:.2f} CPU s for the sweeps, "
              f"{every['build_seconds']:.1f} CPU s to find the poses.", ""]
    if every["failed"]:
        lines += [f"Without a moving pose ({len(every['failed'])}):", ""] + [f"- {why}" for why in every["failed"]] + [""]
    else:
        lines += ["Every one of them has a moving pose.", ""]
    out.write_text("\n".join(lines))


if __name__ == "__main__":
    raise SystemExit(main())
