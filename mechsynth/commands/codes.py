"""CLI commands ``codes`` (number synthesis) and ``analyze`` (a code, counts or a chain).

Example
-------
>>> from mechsynth.cli import main
>>> main(["codes", "--dof", "1", "--loops", "2", "--format", "csv"])
code,links,loops,v,assortment
42/0,6,2,0,4 2
51/1,6,2,1,5 1
60/2,6,2,2,6
0
"""

from __future__ import annotations

import itertools
import json
import sys
from collections import Counter

from synth import InvalidOption
from synth import MAX_CODES

from .._argtypes import chain_text, positive, whole
from .._output import FORMATS, nothing_found, write_rows

__all__ = ["add_commands"]


def add_commands(sub) -> None:
    """Mount ``codes`` and ``analyze`` on the ``mechsynth`` parser."""
    _add_codes(sub)
    _add_analyze(sub)


def parse_classes(text: str, what: str = "loop classes are written H=K,H=K (e.g. 3=4,5=1)") -> dict[int, int]:
    """The loop classes of ``--loop-classes`` (motion space H → loops K), read by ``codes`` and ``chains``.

    Raises
    ------
    InvalidOption
        With ``what`` (how to write them) when the text is not H=K pairs, or gives an H twice.

    >>> parse_classes("3=4,5=1")
    {3: 4, 5: 1}
    """
    try:
        pairs = [[int(x) for x in item.split("=")] for item in text.replace(",", " ").split()]
        classes = {h: k for h, k in pairs}
    except ValueError:
        raise InvalidOption(f"{what}, not {text!r}") from None
    if len(classes) != len(pairs):
        twice = next(h for h in classes if sum(p[0] == h for p in pairs) > 1)
        raise InvalidOption(f"{what}: {twice}= is given twice in {text!r}")
    if not classes:
        raise InvalidOption(f"{what}, not {text!r}")
    return classes


# ------------------------------------------------------------------- codes
def _add_codes(sub):
    p = sub.add_parser("codes", help="number synthesis: every standard code n2n3…/v")
    p.add_argument("--dof", type=whole, required=True, help="required mobility W (0 = truss)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--loops", help="K, or a range A..B")
    g.add_argument("--links", help="n, or a range A..B")
    g.add_argument("--loop-classes", help="heterogeneous systems: H=K_H,… (e.g. 3=4,5=1)")
    p.add_argument("--v", help="multiple-joint count or range A..B (default: every possible)")
    p.add_argument("--h", type=whole, help="motion space of a loop (default 3, planar)")
    p.add_argument("--f", type=whole, default=0, help="extra mobility of multi-DOF pairs")
    p.add_argument("--n1", default="0", help="single-joint links (open chains), N or A..B")
    p.add_argument("--max-link-degree", help="largest joints per link: N, K+1 (default) or K+W (the limit theorem, for W ≥ 1); "
                   "a bound below K + 1 names on stderr the codes it leaves out")
    p.add_argument("--max-multiplicity", type=whole, help="largest number of links on one joint")
    p.add_argument("--compositions", action="store_true", help="split v into its composition v2-v3-…")
    p.add_argument("--require", action="append", default=[], metavar="I=N|I=A..B|I=A..",
                   help="design constraint on n_I, the links with I joints (repeatable)")
    p.add_argument("--force", action="store_true",
                   help=f"list a query that may have more than {MAX_CODES:_} codes (refused unasked)".replace("_", " "))
    p.add_argument("--format", choices=FORMATS, default="table", help="table (default), jsonl, csv or json")
    p.set_defaults(run=_run_codes)


def _run_codes(args) -> int:
    from synth import QueryTooLarge
    from synth import iter_codes

    h = motion_space(args)
    args.h = 3 if h is None else h

    bar = None
    if sys.stderr.isatty():  # codes stream out; the bar counts them on a terminal
        from tqdm import tqdm

        bar = tqdm(unit=" codes", file=sys.stderr, leave=False, delay=2.0)
    codes = iter_codes(
        args.dof, loops=args.loops, links=args.links,
        loop_classes=parse_classes(args.loop_classes) if args.loop_classes else None,
        h=args.h, f=args.f, v=args.v, n1=args.n1, max_link_degree=args.max_link_degree,
        require=args.require, max_multiplicity=args.max_multiplicity, compositions=args.compositions,
        max_codes=None if args.force else MAX_CODES, progress=bar.update if bar is not None else None,
    )
    per_k: Counter = Counter()
    try:
        first = next(codes, None)  # validated and sized before anything is written
    except QueryTooLarge as exc:
        if "unasked" in str(exc):
            raise QueryTooLarge(f"{exc}, or give --force to list them anyway") from None
        raise

    listed: set[str] = set()

    def rows():
        for code in ([] if first is None else itertools.chain([first], codes)):
            per_k[code.loops] += 1
            listed.add(str(code))
            yield dict(code.to_dict(), dof=args.dof)

    columns = ["code", "links", "loops", "v", "assortment"] + (["composition"] if args.compositions else [])
    try:
        write_rows(rows(), columns, args.format)
    finally:
        if bar is not None:
            bar.close()
    if args.max_link_degree is not None:
        _note_left_out(args, listed)
    if first is None:
        return nothing_found("standard code satisfies these parameters and requirements")
    if args.format == "table":
        summary = ", ".join(f"K={k}: {m}" for k, m in sorted(per_k.items()))
        total = sum(per_k.values())
        print(f"{total} code{'s' * (total != 1)} ({summary})")
    return 0


def _note_left_out(args, listed: set) -> None:
    """Say on stderr which codes a ``--max-link-degree`` below the default K + 1 left out: the limit
    theorem's K + W holds for chains that no sub-chain makes rigid (W ≥ 1), so with W = 0 it drops
    trusses that exist (32/0, K = 2, has three-joint links)."""
    from synth import iter_codes

    every = iter_codes(
        args.dof, loops=args.loops, links=args.links,
        loop_classes=parse_classes(args.loop_classes) if args.loop_classes else None,
        h=args.h, f=args.f, v=args.v, n1=args.n1, require=args.require, max_multiplicity=args.max_multiplicity,
        compositions=args.compositions, max_codes=None if args.force else MAX_CODES)
    left = [str(c) for c in every if str(c) not in listed]
    if left:
        why = (" (the limit K + W holds for chains with W ≥ 1 and no rigid sub-chain; a truss's links carry up to "
               "K + 1 joints)" if args.dof == 0 else "")
        shown = ", ".join(left[:5]) + (", …" if len(left) > 5 else "")
        print(f"mechsynth: note: --max-link-degree {args.max_link_degree} leaves out {len(left)} code"
              f"{'s' * (len(left) > 1)} with larger links that the default bound K + 1 lists: {shown}{why}",
              file=sys.stderr)


# ----------------------------------------------------------------- analyze
def _add_analyze(sub):
    p = sub.add_parser("analyze", help="W, K, Y, D of a code, counts or chain, and how to remove defects")
    p.add_argument("subject", type=chain_text("analyze"), help="a code (6301/0), counts (2=4,3=2), a chain as JSON or joint list '0-1 1-2 …' "
                   "('0=1 1=2 2=3 3=0': words a=b are a chain where they number links 0 … n − 1, counts where every "
                   "I ≥ 1)")
    p.add_argument("--dof", type=whole, help="required W (for D and the criterion)")
    p.add_argument("--v", type=whole, help="v, with explicit counts (a code carries its own)")
    p.add_argument("--h", type=whole, help="motion space of a loop (default 3, planar; a chain's own where it states "
                   "one)")
    p.add_argument("--f", type=whole, default=0, help="extra mobility of multi-DOF pairs")
    p.add_argument("--loop-classes", help="H=K_H,… for heterogeneous systems")
    p.add_argument("--repairs", type=positive, nargs="?", const=5, metavar="N",
                   help="the N (default 5) nearest valid codes or chains, fewest elementary edits first")
    p.add_argument("--format", choices=("table", "json"), default="table", help="table (default) or json")
    p.set_defaults(run=_run_analyze)


def _refuse_for_chain(args) -> None:
    """A chain carries its own links, joints and v: options that describe counts do not apply."""
    from synth import not_for_the_subject

    given = [name for name, value in (("--v", args.v), ("--f", args.f or None), ("--loop-classes", args.loop_classes))
             if value is not None]
    if given:
        raise not_for_the_subject(given[0], "chain")


def _subject(text: str) -> str:
    """What ``analyze`` is given: ``"chain"``, ``"counts"`` or ``"code"``.

    A JSON row, a text with loop classes after ``|`` or with ``-`` or ``~`` joints (``0-1 1=2``) is a chain, one with ``/`` a
    code (an open chain's ``2|5/2`` too); words ``a=b`` only are counts ``I=N`` or a chain of prismatic pairs, whichever they
    read as (a chain numbers its links 0 … n − 1 without gaps, counts have I ≥ 1, so a text is
    both only with a zero count ``I=0``: refused, saying how to write each).

    >>> _subject("0-1 1-2 2-0"), _subject("0=1 1=2 2=3 3=0"), _subject("2=4,3=2"), _subject("6301/0"), _subject("2|5/2")
    ('chain', 'chain', 'counts', 'code', 'code')
    """
    from synth import Chain, MalformedChain

    s = text.strip()
    words = s.replace(",", " ").split()
    if s.startswith(("{", "[")) or ("/" not in s and ("|" in s or any("-" in w or "~" in w for w in words))):
        return "chain"
    if "/" in s or "=" not in s:
        return "code"
    try:
        Chain.parse(s)
        as_chain = None
    except MalformedChain as exc:
        as_chain = str(exc)
    try:
        counts = parse_classes(s, "counts are written I=N,I=N (links with I joints, e.g. 2=4,3=2)")
        if min(counts) < 1:
            raise InvalidOption(f"counts are n_I for links with I ≥ 1 joints, and '{s}' names I = {min(counts)}")
        as_counts = None
    except InvalidOption as exc:
        as_counts = str(exc)
    if as_chain is None and as_counts is None:
        zero = [w for w in words if w.split("=")[1] == "0"]
        kept = ",".join(w for w in words if w not in zero)
        at = next(w for w in words if "0" in w.split("="))
        first = "=".join(reversed(at.split("=")))
        raise InvalidOption(f"'{s}' reads both as link counts I=N and as a chain of prismatic pairs: write the counts "
                            f"without their zero counts ('{kept}'), or the chain with link 0 first in its joint "
                            f"('{s.replace(at, first, 1)}')")
    if as_chain is not None and as_counts is not None:  # a text naming link 0 meant a chain (no count has I = 0)
        named = {x for w in words for x in w.split("=")}
        raise InvalidOption(f"cannot read '{s}' as a chain of prismatic pairs: {as_chain}" if "0" in named else as_counts)
    return "chain" if as_chain is None else "counts"


def motion_space(args) -> int | None:
    """``--h`` or None (a chain's own; 3 for codes and counts), for ``codes``, ``analyze``, ``chains``,
    ``mechanisms`` and ``draw``: any ``--h`` beside ``--loop-classes`` is refused, as a scene refuses it
    (:func:`synth.h_beside_classes`), since loop classes name each loop's motion space themselves."""
    if args.h is not None and args.loop_classes:  # (imported here: a count read from the store loads no numpy)
        from synth import h_beside_classes

        raise h_beside_classes("--h", "--loop-classes")
    return args.h


def _run_analyze(args) -> int:
    from synth import analyze

    h = motion_space(args)
    classes = parse_classes(args.loop_classes) if args.loop_classes else None
    subject = args.subject.strip()
    kind = _subject(subject)
    if kind == "chain":
        from synth import analyze_chain, check_motion_space
        from synth.exchange import read_chain

        _refuse_for_chain(args)
        if h is not None:
            check_motion_space(h, lowest=2)
        chain = read_chain(subject, h).chain
        if args.repairs and chain.h != 3:
            raise InvalidOption(f"--repairs rebuilds planar chains (h = 3), not chains in motion space h = {chain.h}")
        if args.repairs and chain.classes is not None:
            raise InvalidOption("--repairs rebuilds planar chains of one class, not a chain with loop classes")
        result = analyze_chain(chain, dof=args.dof).to_dict()
        if args.repairs:
            from synth import chain_repairs

            result["repairs"] = [r.to_dict() for r in chain_repairs(chain, dof=args.dof, limit=args.repairs)]
    elif kind == "counts":
        if args.repairs:
            raise InvalidOption("--repairs works on a code or a chain, not on bare counts")
        counts = parse_classes(subject, "counts are written I=N,I=N (links with I joints, e.g. 2=4,3=2)")
        result = analyze(counts=counts, v=args.v or 0, dof=args.dof, h=3 if h is None else h, f=args.f,
                         loop_classes=classes).to_dict()
    else:
        if args.v is not None:
            from synth import not_for_the_subject

            raise not_for_the_subject("--v", "code")
        result = analyze(subject, dof=args.dof, h=3 if h is None else h, f=args.f, loop_classes=classes).to_dict()
        if args.repairs:
            from synth import Code
            from synth import code_repairs

            if h not in (None, 3) or args.f or classes:
                raise InvalidOption("--repairs rebuilds planar codes: drop --h, --f and --loop-classes")
            found = code_repairs(Code.parse(subject), result["dof"] if args.dof is None else args.dof,
                                 limit=args.repairs)
            result["repairs"] = [r.to_dict() for r in found]
    repairs = result.pop("repairs", None)
    if repairs is not None:
        result["repairs"] = repairs
    if args.format == "json":
        print(json.dumps(result, ensure_ascii=False))
    else:
        result = {k: v for k, v in result.items() if v not in (None, "")}  # e.g. D without a required W
        width = max(len(k) for k in result)
        for key, value in result.items():
            if isinstance(value, dict):
                value = "; ".join(f"{k} = {v}" for k, v in value.items())
            elif key == "repairs":
                continue
            elif isinstance(value, list):
                value = json.dumps(value, ensure_ascii=False)
            elif key == "certificate":  # for people: its end, as chain tables show it
                value = "…" + value[-16:]
            print(f"{key.ljust(width)}  {value}")
        _print_repairs(repairs)
    return 0


def _print_repairs(repairs) -> None:
    """One block per repair: its code and chain, then its edits."""
    if repairs is None:
        return
    if not repairs:
        print("repairs   none: the structure is valid already, or no valid one lies within three edits")
    for i, r in enumerate(repairs, start=1):
        print(f"repair {i}  {r['code']}  {r.get('chain', '')}".rstrip())
        for edit in r["edits"]:
            print(f"          - {edit}")
