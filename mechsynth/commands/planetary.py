"""CLI command ``planetary``: planetary gear trains judged through their lever analogues.

Example
-------
>>> from mechsynth.cli import main
>>> main(["planetary", "--satellites", "2..4", "--format", "csv"])
satellites,sun,code,links,dof,loops,defect,subchains,determinate,assur_groups
2,floating,540/0,9,2,3,1,none,,
3,floating,64200/0,12,1,5,0,none,yes,dyad dyad dyad triad
4,floating,8412000/0,15,0,7,-1,none,,
0
"""

from __future__ import annotations

import itertools

from .._output import write_rows

COLUMNS = ["satellites", "sun", "code", "links", "dof", "loops", "defect", "subchains", "determinate", "assur_groups"]


def add_commands(sub) -> None:
    """Mount ``planetary`` on the ``mechsynth`` parser."""
    p = sub.add_parser("planetary", help="planetary gear trains by lever analogue: code, W, K, D per number of satellites")
    p.add_argument("--satellites", required=True, metavar="A..B", help="number of satellites k0, or a range A..B")
    p.add_argument("--sun", choices=("floating", "fixed"), default="floating",
                   help="floating sun (held by its meshes, the default) or sun on a fixed axis")
    p.add_argument("--format", choices=("table", "jsonl", "csv", "json"), default="table",
                   help="table (default), jsonl, csv or json")
    p.set_defaults(run=_run)


def _run(args) -> int:
    from synth import parse_range
    from synth import InvalidOption
    from synth import planetary_rows

    if args.satellites.lstrip().startswith("-"):
        raise InvalidOption(f"--satellites must be a whole number ≥ 1 or a range A..B, not {args.satellites!r}")
    lo, hi = parse_range(args.satellites, "--satellites")
    if hi is None:
        raise InvalidOption("--satellites needs an upper end: give A..B")
    rows = planetary_rows((lo, hi), args.sun)  # streamed: a row is written when its exact test is done
    first = next(rows)  # the range is checked before anything is written
    write_rows((_cells(r.to_dict(), args.format) for r in itertools.chain([first], rows)), COLUMNS, args.format)
    if args.format == "table":
        print("determinate: W = 1, D = 0 and no rigid or over-constrained sub-chain (ring fixed, carrier driving)")
    return 0


def _cells(row: dict, fmt: str) -> dict:
    if fmt in ("table", "csv"):
        row["determinate"] = "yes" if row["determinate"] else ""
        row["assur_groups"] = " ".join(g["name"] for g in row["assur_groups"])
    return row
