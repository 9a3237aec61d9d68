"""CLI command ``grid``: a grid file of W, n, v ranges run into an SQLite atlas (resumable).

Example
-------
>>> import tempfile, pathlib
>>> from mechsynth.cli import main
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> grid, db = str(folder / "g.toml"), str(folder / "a.sqlite")
>>> _ = pathlib.Path(grid).write_text('dof = 1\\nlinks = "4..8"\\n')
>>> main(["grid", grid, "--db", db, "--workers", "1", "--format", "json"])  # doctest: +ELLIPSIS
{"status": "done", "units_total": 6, ...}
0
"""

from __future__ import annotations

import json
import sys

from .._argtypes import seconds, workers

__all__ = ["add_commands"]


def add_commands(sub) -> None:
    """Mount ``grid`` on the ``mechsynth`` parser."""
    p = sub.add_parser("grid", help="run a grid file of W, n, v ranges into an SQLite atlas (resumable)")
    p.add_argument("grid", help="grid file (TOML), e.g. models/grid_small.toml")
    p.add_argument("--db", required=True, help="SQLite atlas to create or resume")
    p.add_argument("--workers", type=workers, help="local processes (default: all cores)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="run the units on a Dask scheduler, e.g. tcp://host:8786")
    p.add_argument("--timeout", type=seconds, help="with --scheduler: seconds to wait for it (default 5)")
    p.add_argument("--force", action="store_true", help="run a grid estimated to take more than a day")
    p.add_argument("--format", choices=("table", "json"), default="table", help="table (default) or json")
    p.set_defaults(run=_run_grid)


def _run_grid(args) -> int:
    import os

    from synth import InvalidOption
    from synth.atlas import index_gap, load_grid, run_grid, size_grid

    if args.timeout is not None and args.scheduler is None:
        raise InvalidOption("--timeout goes with --scheduler (it is how long to wait for the scheduler)")
    if args.workers is not None and args.scheduler is not None:
        raise InvalidOption("--workers and --scheduler contradict each other: the scheduler's workers run the units")
    grid = load_grid(args.grid)
    if not args.force:
        processes = 1 if args.scheduler else (args.workers or os.cpu_count() or 1)
        note = size_grid(grid, processes=processes, db=args.db, scheduler=args.scheduler is not None)
        if note:
            print(f"mechsynth: {note}", file=sys.stderr)
    result = run_grid(grid, args.db, workers=args.workers, scheduler=args.scheduler,
                      progress=True, connect_timeout=5.0 if args.timeout is None else args.timeout)
    if args.format == "json":
        print(json.dumps(result.to_dict()))
    else:
        print(f"grid {grid.name}: {result.cells} cells, {result.units_total} units "
              f"({result.units_skipped} already done, {result.units_run} run) on {result.executor}; "
              f"{result.chains_found} chains found ({result.chains_new} new), {result.mechanisms_found} mechanisms; "
              f"{result.seconds:.1f} s, {result.chains_per_second:.0f} chains/s -> {args.db}")
    gap = index_gap(args.db)  # (chains this run added to an atlas whose curve index was built before)
    if gap:
        print(f"mechsynth: {gap}", file=sys.stderr)
    return 0
