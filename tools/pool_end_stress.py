"""Run a 2-worker listing many times onto a full disk or a closed pipe and count the runs that hang.

A run is a fresh ``python -m mechsynth chains --dof 1 --links N --workers 2 --format jsonl`` (the store of
solver results off) whose stdout is ``/dev/full`` (``full:N``) or a pipe closed after its first line
(``pipe:N``, as ``| head -1``); the cases are cycled.  A run still alive after ``--timeout`` seconds is a
hang: its processes are dumped with ``py-spy dump --locals`` (when installed) into the log, then killed.
The last line printed (and logged) is a JSON summary: runs, hangs, outcomes (case, exit status, last line
of stderr), wall seconds, the runs' CPU seconds and the load (docs/testing.md).

Example::

    python tools/pool_end_stress.py --runs 300 full:12 pipe:12 full:10 pipe:10 --log /tmp/stress.log
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _case(text: str) -> tuple[str, int]:
    """``full:N`` or ``pipe:N`` (N links, an even number of at least 4)."""
    kind, _, links = text.partition(":")
    if kind not in ("full", "pipe") or not links.isdigit() or int(links) < 4 or int(links) % 2:
        raise argparse.ArgumentTypeError(f"a case is full:N or pipe:N, N an even number of links ≥ 4, not {text!r}")
    return kind, int(links)


def _session(pid: int) -> list[str]:
    """The processes of the session ``pid`` leads (the run and its workers)."""
    return subprocess.run(["ps", "-o", "pid=", "-s", str(pid)], capture_output=True, text=True).stdout.split()


def run_once(kind: str, links: int, timeout: float, log) -> tuple[object, str]:
    """One run: its exit status ("HANG" when it outlived ``timeout``) and the last line of its stderr."""
    cmd = [sys.executable, "-m", "mechsynth", "chains", "--dof", "1", "--links", str(links), "--workers", "2",
           "--format", "jsonl"]
    env = dict(os.environ, PYTHONPATH=str(ROOT), MECHSYNTH_CACHE="off")
    with open("/dev/full", "w") as full:
        out = subprocess.PIPE if kind == "pipe" else full
        run = subprocess.Popen(cmd, stdout=out, stderr=subprocess.PIPE, env=env, cwd=ROOT, start_new_session=True)
    if kind == "pipe":
        run.stdout.readline()
        run.stdout.close()
    try:
        run.wait(timeout=timeout)
        status = run.returncode
    except subprocess.TimeoutExpired:
        status = "HANG"
        pids = _session(run.pid)
        print(f"=== hang: {kind}:{links}, processes {pids}", file=log, flush=True)
        for pid in pids if shutil.which("py-spy") else ():
            dump = subprocess.run(["py-spy", "dump", "--pid", pid, "--locals"], capture_output=True, text=True)
            print(f"--- {pid}\n{dump.stdout}{dump.stderr}", file=log, flush=True)
        os.killpg(run.pid, signal.SIGKILL)
        run.wait()
    err = run.stderr.read().decode(errors="replace").strip().splitlines()
    run.stderr.close()
    left = _session(run.pid)
    if left:
        print(f"processes left by a {kind}:{links} run: {left}", file=log, flush=True)
        for pid in left:
            os.kill(int(pid), signal.SIGKILL)
    return status, err[-1] if err else ""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cases", nargs="+", type=_case, help="full:N or pipe:N, cycled")
    parser.add_argument("--runs", type=int, default=300, help="runs in all (default 300)")
    parser.add_argument("--timeout", type=float, default=20.0, help="seconds after which a run is a hang (default 20)")
    parser.add_argument("--log", type=Path, required=True, help="where hangs' dumps and the summary go")
    args = parser.parse_args(argv)
    if args.runs < 1 or args.timeout <= 0:
        parser.error("--runs must be at least 1 and --timeout positive")
    outcomes, start, before = Counter(), time.time(), os.times()
    with open(args.log, "a") as log:
        for i in range(args.runs):
            kind, links = args.cases[i % len(args.cases)]
            status, last = run_once(kind, links, args.timeout, log)
            outcomes[f"{kind}:{links} exit {status}: {last}"] += 1
        after = os.times()
        summary = dict(runs=args.runs, hangs=sum(n for k, n in outcomes.items() if " exit HANG" in k),
                       outcomes=dict(outcomes), wall_s=round(time.time() - start, 1),
                       cpu_s=round(after.children_user + after.children_system
                                   - before.children_user - before.children_system, 1),
                       load=[round(x, 2) for x in os.getloadavg()])
        print(json.dumps(summary, ensure_ascii=False), file=log)
    print(json.dumps(summary, ensure_ascii=False))
    return 1 if summary["hangs"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
