"""CLI commands ``identify`` (which chain is this?) and ``compare`` (an atlas from elsewhere
against the engine's enumeration).

Example
-------
>>> from mechsynth.cli import main
>>> main(["identify", "0-3 3-5 5-1 1-0 0-2 2-4 4-1", "--format", "json"])  # doctest: +ELLIPSIS
{
  "source": "the chain given",
...
  "classical": [
    "Watt chain"
  ],
  "listing": "mechsynth chains --code 42/0",
  "index": 2,
  "listed": 2,
...
0
"""

from __future__ import annotations

import sys

from .._argtypes import YesOrNo, whole, workers
from .._output import pairs, write_document, write_rows

__all__ = ["add_commands"]


def add_commands(sub) -> None:
    """Mount ``identify`` and ``compare`` on the ``mechsynth`` parser."""
    from synth.exchange import FORMATS

    p = sub.add_parser("identify", help="which chain is this: id, code, place in the listing, symmetry, name")
    p.add_argument("chain", metavar="CHAIN_OR_FILE",
                   help="a joint list ('0-1 1=2 2-3 3-0'), a JSON row, or a file (or folder) of chains in any format "
                        "of --input-format; '-' reads standard input")
    p.add_argument("--input-format", choices=FORMATS, help="the input's format (default: from the file suffix or "
                   "its first characters)")
    p.add_argument("--frame", help="fix this link (as the input names it): identify the mechanism")
    p.add_argument("--h", type=whole, help="motion space of the loops, 2 … 6, for a source that states none (default "
                   "the chain's own, 3 for a joint list); a source that states another is refused")
    p.add_argument("--index", action=YesOrNo, default=None,
                   help="find the chain's row in its code's listing (default: where listing the chains of its link "
                        "count is estimated at a minute or less on one core)")
    p.add_argument("--format", choices=("table", "json", "jsonl"), default="table",
                   help="table (default), json or jsonl (one row per chain)")
    p.set_defaults(run=_run_identify)

    p = sub.add_parser("compare", help="an atlas from elsewhere against the engine's enumeration of the same query")
    p.add_argument("atlas", nargs="+", metavar="ATLAS_FILE",
                   help="files (or folders) of chains: one per line (joint lists, JSON rows) or per graph or file "
                        "(GraphML, GML, DOT, edge lists, matrices)")
    p.add_argument("--input-format", choices=FORMATS, help="the files' format (default: from each file)")
    p.add_argument("--dof", type=whole, help="W of the atlas's chains (default: the code's)")
    p.add_argument("--links", type=whole, help="number of links n")
    p.add_argument("--code", help="only this code, e.g. 6301/0")
    p.add_argument("--v", help="multiple-joint count or range A..B (default 0)")
    p.add_argument("--h", type=whole, default=3, help="motion space of the loops, 2 … 6 (default 3); chains whose "
                   "file states no h are read in it")
    p.add_argument("--n1", help="single-joint links, N or A..B (default 0)")
    p.add_argument("--max-multiplicity", type=whole, help="most links on one joint")
    p.add_argument("--require", action="append", default=[], metavar="I=N|I=A..B|I=A..",
                   help="design constraint on n_I (repeatable)")
    p.add_argument("--cranks", action="append", default=[], metavar="I=C", help="a link with I joints carrying ≥ C "
                   "cranks (repeatable)")
    p.add_argument("--rigid-subchains", action="store_true", default=None,
                   help="the atlas allows rigid sub-chains, W(S) ≥ 0 (default only for W = 0)")
    p.add_argument("--fractionated", action=YesOrNo, default=True,
                   help="the atlas holds fractionated chains (default: yes)")
    p.add_argument("--planar-only", action="store_true", help="the atlas holds planar chains only")
    p.add_argument("--prismatic", metavar="A..B", help="chains with A…B prismatic pairs")
    p.add_argument("--idle-joints", action="store_true", help="with --prismatic: the atlas keeps idle joints")
    p.add_argument("--workers", type=workers, help="processes for the engine's enumeration (default: all cores)")
    p.add_argument("--force", action="store_true", help="run an enumeration estimated to take more than a day")
    p.add_argument("--format", choices=("table", "json", "jsonl"), default="table",
                   help="table (default), json (one document) or jsonl (a row per finding)")
    p.add_argument("--exit-code", action="store_true",
                   help="exit with status 1 when the atlases differ (as diff and git diff --exit-code do)")
    p.set_defaults(run=_run_compare)


# ------------------------------------------------------------------ identify
def _listed(row: dict, prefix: str = "") -> str:
    index, listed = row[f"{prefix}index"], row[f"{prefix}listed" if not prefix else "mechanisms_listed"]
    listing = row[f"{prefix}listing"]
    if listing is None:
        return "none"
    if index is None:
        return listing
    return f"#{index} of {listed} in '{listing}'"


_CONVENTIONS = {"non_degenerate": "non-degenerate (every sub-chain moves)",
                "rigid_subchains": "W(S) ≥ 0 (--rigid-subchains)", "not_fractionated": "not fractionated",
                "planar": "planar", "no_idle_joint": "no idle joint"}


def _table(row: dict) -> str:
    from synth import JointKind

    names = row.get("names")
    joints = " ".join(JointKind(k).symbol.join(str(names[x]) if names else str(x) for x in j)
                      for j, k in zip(row["joints"], row.get("kinds") or [JointKind.REVOLUTE] * len(row["joints"])))
    if row.get("classes"):  # a heterogeneous chain: its bases, class by class, as a joint list writes them
        bases = [f"h{x}: " + " ".join(str(names[i]) if names else str(i) for i, c in enumerate(row["classes"]) if c == x)
                 for x in sorted(set(row["classes"]) - {row["h"]})]
        joints += " | " + "; ".join(([] if row["h"] == 3 else [f"h{row['h']}"]) + bases)
    passed = [_CONVENTIONS[name] for name, ok in row["conventions"].items() if ok]
    lines = [
        ("chain", joints),
        ("id", row["id"]),
        ("as listed", row["listed_joints"] + "  (this id's numbering in every listing and atlas)"),
        ("code", row["code"] + ("" if row["h"] == 3 else f"  h = {row['h']}")),
        ("W", f"{row['dof']}" + ("" if row["dof"] == row["dof_count"] else f" (the count says {row['dof_count']})")),
        ("links, loops, v", f"{row['links']}, {row['loops']}, {row['v']}"),
        ("sub-chains", row["subchains"] + (f": links {', '.join(map(str, row['worst_subchain']))}, W(S) = "
                                          f"{row['worst_mobility']}" if row["subchains"] not in ("none", "not connected")
                                          else "")),
        ("conventions passed", ", ".join(passed) or "none"),
        ("fractionated", {True: "yes", False: "no", None: "-"}[row["fractionated"]]),
        ("planar", "yes" if row["planar"] else "no"),
        ("symmetry", f"|Aut| = {row['symmetry']}; link orbits "
                     + " ".join("{" + ", ".join(map(str, o)) + "}" for o in row["link_orbits"])),
        ("classical name", "; ".join(row["classical"]) or "-"),
        ("listing", _listed(row)),
    ]
    if row["idle_joints"]:
        lines.insert(6, ("idle joints", " ".join("-".join(map(str, j)) for j in row["idle_joints"])))
    if row["note"]:
        lines.append(("note", row["note"]))
    if "frame" in row:
        lines += [("frame", str(row["frame"]) + (f", input link {row['input_link']}" if "input_link" in row else "")),
                  ("frame's orbit", ", ".join(map(str, row["frame_orbit"]))),
                  ("frame as listed", str(row["listed_frame"]) + (f", input link {row['listed_input_link']}"
                                                                  if "listed_input_link" in row else "")),
                  ("inversion", "; ".join(row["inversion"]) or "-"),
                  ("mechanism listing", _listed(row, "mechanism_") if row.get("mechanism_listing") else "none")]
    lines.append(("certificate", row["certificate"]))
    return pairs(lines)


def _run_identify(args) -> int:
    from synth import identify_all

    found = identify_all(args.chain, fmt=args.input_format, frame=args.frame, h=args.h, index=args.index)
    rows = [r.to_dict() for r in found]
    if args.format == "jsonl":
        write_rows(rows, [], "jsonl")
    elif args.format == "json":
        write_document(rows[0] if len(rows) == 1 else {"chains": rows}, "json", "")
    else:
        print("\n\n".join(f"{r['source']}\n{_table(r)}" if len(rows) > 1 else _table(r) for r in rows))
    return 0


# ------------------------------------------------------------------- compare
def _run_compare(args) -> int:
    import os

    from synth import compare
    from synth.exchange import read_file
    from synth import size_check
    from synth import InvalidOption

    from .chains import query_of

    if args.idle_joints and args.prismatic is None:
        raise InvalidOption("--idle-joints goes with --prismatic (an all-revolute chain has no idle joint)")
    query = query_of(args)
    entries = [e for path in args.atlas for e in read_file(path, args.input_format)]  # all read before any work
    note = size_check(query, processes=args.workers or os.cpu_count() or 1, count=False, table=False,
                      force=args.force)
    if note:
        print(f"mechsynth: {note}", file=sys.stderr)
    result = compare(entries, query, workers=args.workers, progress=True)
    if args.format == "json":
        write_document(result.to_dict(), "json", "")
    elif args.format == "jsonl":
        write_rows(({k: v for k, v in f.__dict__.items()} for f in result.findings), [], "jsonl")
    else:
        _print_comparison(result)
    return 1 if args.exit_code and not result.agree else 0


def _print_comparison(result) -> None:
    print(f"{result.given} chains given, {result.distinct} distinct; the engine lists {result.engine} "
          f"({result.listing})")
    print(f"matched {result.matched}, duplicates {result.count('duplicate')}, missing {result.count('missing')}, "
          f"extra {result.count('extra')}" + (": the atlases agree" if result.agree else ""))
    if result.findings:
        print()
        rows = [{"finding": f.kind, "id": f.id, "where": _where(f.given) or f"engine row {f.row}",
                 "joints": f.joints, "reason": f.reason} for f in result.findings]
        write_rows(rows, ["finding", "id", "where", "joints", "reason"], "table")


def _where(sources: list[str]) -> str:
    """Where a chain was given, a file named once: ``a.txt lines 6, 7``.

    >>> _where(["a.txt line 6", "a.txt line 7", "b.graphml"])
    'a.txt lines 6, 7; b.graphml'
    """
    import re

    groups: dict[str, list[str]] = {}
    for source in sources:
        m = re.fullmatch(r"(.*) (line|graph|row) (\d+)", source)
        file, part = (m.group(1), (m.group(2), m.group(3))) if m else (source, None)
        groups.setdefault(file, []).append(part)
    shown = []
    for file, parts in groups.items():
        numbered = [p for p in parts if p is not None]
        if not numbered:
            shown.append(file)
        else:
            word = numbered[0][0] + ("s" if len(numbered) > 1 else "")
            shown.append(f"{file} {word} {', '.join(n for _, n in numbered)}")
    return "; ".join(shown)
