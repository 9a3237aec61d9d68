"""Run the README's commands (and docs/cli.md's, the full tour) and every scene in two checkouts and compare
what they print.

A refactoring that must not change any output (keys, columns, table text) is checked with this:
each command of the ``bash`` blocks of README.md, then of docs/cli.md where the checkout has it, runs
once in each checkout (``python -m mechsynth``, the checkout on ``PYTHONPATH``, one scratch folder per
checkout with a copy of ``models/``, commands in the pages' order so that the atlases the first ones
write are there for the later ones), again with
``--format json``, ``jsonl`` and ``csv`` where it writes no file, and ``scene --all models/`` in
both of its formats. Standard output, standard error, the exit status and the bytes of every file
written are compared; run times printed by the program (``"seconds": 1.234``, ``(0.31 s)``) are
masked first. The log is one line per command: ``same`` or ``DIFF`` with the first differing line.

It is a log to keep beside a change, not a test: it takes minutes and runs programs that write files.

Usage::

    nice -n 10 python tools/outputs_before_after.py BEFORE --save before.json
    nice -n 10 python tools/outputs_before_after.py AFTER --save after.json --compare before.json > log.txt

``--only balance,gears`` keeps the README commands of those subcommands; ``--each-scene`` runs each scene
alone instead of ``scene --all``; ``--reuse`` compares a saved run again without running it. The two
runs may go side by side (each works in a scratch folder of its own); checkouts made with
``git archive REV | tar -x -C DIR`` keep a run from seeing edits made meanwhile.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

#: commands left out, with the reason written in the log
SKIP = {
    "--scheduler": "needs a Dask scheduler",
    "pip install": "installs the package",
    "--links 16": "a count of minutes",
    "--cranks 3=3": "a count of minutes",
    "--index-curves": "indexes curves for minutes",
    "dimension ": "dimensional synthesis: searches for a time budget",
}
#: seconds a command may take (then it and its children are stopped and "timeout" is recorded)
TIMEOUT = 900
#: options naming a file the command writes; the variants in other formats drop them
WRITES = ("--out", "--plot", "--save", "--animate", "--html", "--checkpoint")
TIMINGS = [(re.compile(r'"(seconds|time|elapsed|wall_seconds|cpu_seconds)": [0-9.e+-]+'), r'"\1": T'),
           (re.compile(r"\(\d+\.\d+ s\)"), "(T s)"), (re.compile(r"\b\d+\.\d+ s\b"), "T s")]


def readme_commands(readme: Path) -> list[str]:
    """The ``mechsynth`` commands of the README's bash blocks, continuation lines joined, comments cut."""
    commands, inside, pending = [], False, ""
    for line in readme.read_text().splitlines():
        if line.startswith("```"):
            inside = line.strip() == "```bash"
            continue
        if not inside:
            continue
        line = pending + line
        if line.rstrip().endswith("\\"):
            pending = line.rstrip()[:-1] + " "
            continue
        pending = ""
        text = line.split(" #")[0].strip()
        if "mechsynth " in text:
            commands.append(text)
    return commands


def variants(command: str) -> list[str]:
    """The command, and in each other format when it prints its result (one command, no &&)."""
    out = [command]
    if "&&" in command or "--format" in command:
        return out
    words = shlex.split(command)
    kept, skip = [], False
    for w in words:
        if skip:
            skip = False
            continue
        if w in WRITES:
            skip = True
            continue
        if w.split("=")[0] in WRITES:
            continue
        kept.append(w)
    base = shlex.join(kept)
    out += [f"{base} --format {f}" for f in ("json", "jsonl", "csv")]
    return out


def masked(text: str) -> str:
    for pattern, repl in TIMINGS:
        text = pattern.sub(repl, text)
    return text


def run(checkout: Path, command: str, cwd: Path) -> tuple[str, str, int, dict[str, str]]:
    before = {p: p.stat().st_mtime_ns for p in cwd.rglob("*") if p.is_file()}
    env = dict(os.environ, PYTHONPATH=str(checkout), COLUMNS="120")
    shell = command.replace("mechsynth ", f"{shlex.quote(sys.executable)} -m mechsynth ")
    p = subprocess.Popen(shell, shell=True, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, start_new_session=True)
    try:
        out, err = p.communicate(timeout=TIMEOUT)
        result = (masked(out), masked(err), p.returncode)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)  # the shell and the command it started
        p.communicate()
        result = ("", "timeout", -1)
    files = {str(p.relative_to(cwd)): hashlib.sha256(p.read_bytes()).hexdigest()[:16]
             for p in cwd.rglob("*") if p.is_file() and before.get(p) != p.stat().st_mtime_ns}
    return (*result, files)


def first_difference(a: str, b: str) -> str:
    for x, y in zip(a.splitlines(), b.splitlines()):
        if x != y:
            return f"{x[:150]!r} -> {y[:150]!r}"
    return f"{len(a.splitlines())} lines -> {len(b.splitlines())} lines"


def record(checkout: Path, commands: list[str]) -> dict:
    """What every command printed and wrote, run in a scratch folder with a copy of ``models/``."""
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copytree(checkout / "models", Path(tmp) / "models")
        for c in commands:
            out[c] = run(checkout, c, Path(tmp))
            print(f"{c}  exit {out[c][2]}", file=sys.stderr, flush=True)
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("checkout", type=Path, help="the checkout to run")
    ap.add_argument("--save", type=Path, required=True, help="where to write what it printed (JSON)")
    ap.add_argument("--compare", type=Path, help="a JSON saved before: print the log of the comparison")
    ap.add_argument("--reuse", action="store_true", help="read --save instead of running the commands again")
    ap.add_argument("--only", metavar="WORDS", help="only the README commands of these subcommands (comma-separated, "
                                                    "e.g. balance,identify,gears)")
    ap.add_argument("--each-scene", action="store_true",
                    help="run each scene of models/ alone (--format json) instead of scene --all: a slow scene then "
                         "costs its own time only")
    args = ap.parse_args()
    if not (args.checkout / "README.md").is_file() or not (args.checkout / "models").is_dir():
        ap.error(f"{args.checkout} is not a checkout of mechsynth (no README.md and models/ there)")
    if args.reuse and not args.save.is_file():
        ap.error(f"--reuse reads --save, and {args.save} is no file")
    if not args.reuse and not os.access(args.save.parent.resolve(), os.W_OK):
        ap.error(f"cannot write {args.save}: its folder is missing or not writable")
    if args.compare is not None and not args.compare.is_file():
        ap.error(f"--compare reads a saved run, and {args.compare} is no file")
    commands, skipped = [], []
    only = None if args.only is None else set(args.only.split(","))
    pages = [args.checkout / "README.md", args.checkout / "docs" / "cli.md"]
    for c in dict.fromkeys(c for page in pages if page.is_file() for c in readme_commands(page)):
        if only is not None and c.split()[1] not in only:
            continue
        reason = next((r for k, r in SKIP.items() if k in c), None)
        if reason:
            skipped.append(f"skip   {c}   ({reason})")
        else:
            commands += variants(c)
    if args.each_scene:
        commands += [f"mechsynth scene models/{p.name} --format json"
                     for p in sorted((args.checkout / "models").glob("*.toml")) if "[scene]" in p.read_text()]
    else:
        commands += ["mechsynth scene --all models/", "mechsynth scene --all models/ --format json"]
    commands = list(dict.fromkeys(commands))  # each once (the README runs every scene too)
    if args.reuse:
        now = json.loads(args.save.read_text())
    else:
        now = record(args.checkout, commands)
        args.save.write_text(json.dumps(now, ensure_ascii=False, indent=0))
    if args.compare is None:
        return 0
    then = json.loads(args.compare.read_text())
    print("\n".join(skipped))
    same = 0
    for c in commands:
        if c not in then:
            print(f"new    {c}")
            continue
        (o1, e1, s1, f1), (o2, e2, s2, f2) = then[c], now[c]
        if (o1, e1, s1) == (o2, e2, s2) and sorted(f1.values()) == sorted(f2.values()):
            same += 1
            print(f"same   exit {s1}  {len(o1.splitlines()):5d} lines  {c}")
            continue
        what = ("stdout: " + first_difference(o1, o2) if o1 != o2 else
                "stderr: " + first_difference(e1, e2) if e1 != e2 else
                f"exit {s1} -> {s2}" if s1 != s2 else f"files {f1} -> {f2}")
        print(f"DIFF   {c}\n       {what}")
    print(f"{same} of {len(commands)} commands print the same")
    return 0


if __name__ == "__main__":
    sys.exit(main())
