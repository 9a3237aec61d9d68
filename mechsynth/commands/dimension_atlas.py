"""``mechsynth dimension TARGET --db ATLAS``: type and dimensional synthesis over an atlas — which
mechanisms trace a closed path, each topology's best dimensions, error against links.

The atlas needs its curve index (``mechsynth atlas --db ATLAS --index-curves``); the target is a path
(columns ``x,y``, or ``x,y,input`` with timing) round a closed curve.  The command ``dimension`` reads
its options (:mod:`mechsynth.commands.dimension`) and hands a ``--db`` run to :func:`run`.
"""

from __future__ import annotations

import sys

from .._output import nothing_found, write_rows

__all__ = ["check", "run", "COLUMNS"]

#: the columns of the table and CSV, one row per topology, best first
COLUMNS = ["rank", "links", "chain", "chain_id", "frame", "input", "tracer_link", "error_max", "error_rms",
           "relative_max", "misfit", "met", "seconds"]


def check(args) -> None:
    """What contradicts a search over an atlas, refused before any work."""
    from synth import InvalidOption

    given = [name for name, value in (("--linkage", args.linkage), ("--mechanism", args.mechanism),
                                      ("--frame", args.frame), ("--input", args.input),
                                      ("--tracer-link", args.tracer_link), ("--output-link", args.output_link))
             if value is not None]
    if given:
        raise InvalidOption(f"--db searches every topology of the atlas: it does not go with {', '.join(given)} "
                            "(which name one topology)")


def links_range(text: str | None) -> tuple[int, int] | None:
    """``--links 4..8`` (or one number) as a range of link counts."""
    from synth import InvalidOption, SynthesisError, parse_range

    if text is None:
        return None
    wrong = InvalidOption(f"--links must be a number of links or a range of them, low to high, from 4 (e.g. 4..8), "
                          f"not {text!r}")
    try:
        lo, hi = parse_range(text, int)
    except SynthesisError:
        raise wrong from None
    if lo is None or hi is None or lo > hi or lo < 4:
        raise wrong
    return lo, hi


def run(args, target, constraints, *, save, draw) -> int:
    """Search the atlas for the target; print a row per topology; ``save`` the best (or row ``--row K``) and
    ``draw`` every row on one sheet (the command's own writers: of a result, and of ``(rank, result)`` pairs)."""
    from synth.atlas import search_atlas
    from synth.errors import flag

    found = search_atlas(args.db, target, links=links_range(args.links), top=args.top, budget=args.budget,
                         constraints=constraints, seed=args.seed, underdetermined=args.underdetermined,
                         workers=args.workers, scheduler=args.scheduler, progress=sys.stderr.isatty())
    for note in found.notes:
        print(f"mechsynth: {note.text(flag)}", file=sys.stderr)
    rows = []
    for rank, match in enumerate(found.matches, 1):
        row = {"rank": rank, **match.row()}
        if args.format in ("json", "jsonl"):  # rows that move, draw and balance linkage read (--row K)
            row["linkage"] = match.result.linkage.to_dict()
        rows.append(row)
    if not found.index_curves:
        return nothing_found(f"curve of the index belongs to a mechanism with {args.links} links")
    print(f"mechsynth: {found.index_curves} indexed curves, {found.topologies} "
          f"topolog{'y' if found.topologies == 1 else 'ies'} polished in {found.polish_seconds:.1f} CPU s"
          + (f" on {args.scheduler or f'{args.workers} processes'}" if args.scheduler or args.workers > 1 else ""),
          file=sys.stderr)
    if not rows:
        return nothing_found("topology of the atlas could be dimensioned for this target within the budget")
    write_rows(rows, COLUMNS, {"table": "table", "json": "json", "jsonl": "jsonl", "csv": "csv"}[args.format])
    best = found.best
    if not best.result.met:
        print(f"mechsynth: no mechanism met the constraints within the budget; the best found fails: "
              f"{'; '.join(best.result.failed())} (nothing saved or drawn)", file=sys.stderr)
        return 1
    status = 0
    if args.save:
        status = _save_row(found.matches, args.row or 1, args.save, save)
    if args.out:
        draw([(rank, match.result) for rank, match in enumerate(found.matches, 1)], args.out)
        print(f"picture of {len(rows)} row{'s' * (len(rows) != 1)} -> {args.out}", file=sys.stderr)
    return status


def _save_row(matches, k: int, path: str, save) -> int:
    """Save row ``k``'s linkage (1 = the best); 1 where the search found no row ``k`` or it fails a constraint."""
    if k > len(matches):
        print(f"mechsynth: --row {k} is not a row of this search: it found row{'s 1 to ' if len(matches) > 1 else ' '}"
              f"{len(matches)} (nothing saved)", file=sys.stderr)
        return 1
    result = matches[k - 1].result
    if not result.met:
        print(f"mechsynth: row {k} fails the constraints: {'; '.join(result.failed())} (nothing saved)", file=sys.stderr)
        return 1
    save(result, path)
    print(f"linkage{f' of row {k}' if k > 1 else ''} -> {path}", file=sys.stderr)
    return 0
