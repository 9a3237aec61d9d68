"""CLI commands ``chains`` and ``mechanisms`` (type synthesis).

Example
-------
>>> from mechsynth.cli import main
>>> main(["chains", "--dof", "1", "--links", "8", "--count", "--workers", "1"])
{"count": 16, "by_code": {"440/0": 9, "521/0": 5, "602/0": 2}}
0
"""

from __future__ import annotations

import sys

from .._argtypes import YesOrNo, chain_text, seconds, whole, workers
from .._output import FORMATS, nothing_found, write_count, write_rows

WRITTEN = ("graphml", "gml", "dot", "edgelist", "adjacency", "incidence")  # synth.exchange.WRITTEN, unloaded


def _add_selection(p, command: str) -> None:
    p.add_argument("--dof", type=whole, help="mobility W of every chain listed (0 = trusses); default: the code's W")
    p.add_argument("--links", type=whole, help="number of links n (frame included)")
    p.add_argument("--v", help="multiple-joint count or range A..B (default 0: simple joints; with --code its own)")
    p.add_argument("--code", help="only this code, e.g. 6301/0, 620/0-1 or the open 2|5/2 (with --prismatic: the "
                   "revolute skeleton's code)")
    p.add_argument("--h", type=whole,
                   help="motion space of the loops, 2 … 6 (default 3: planar and spherical; 5 Bricard; 6 spatial; not "
                   "with --loop-classes, which give each loop's)")
    p.add_argument("--n1", help="single-joint links (open chains: arms, grippers), N or A..B (default 0; "
                   "with --code its own)")
    p.add_argument("--max-multiplicity", type=whole,
                   help="most links on one joint (default: the limit theorem's K + 1 closed, K + W + 1 open)")
    p.add_argument("--require", action="append", default=[], metavar="I=N|I=A..B|I=A..",
                   help="design constraint on n_I, the links with I joints (repeatable)")
    p.add_argument("--cranks", action="append", default=[], metavar="I=C",
                   help="required sub-structure: a link with I joints carrying ≥ C cranks (repeatable)")
    p.add_argument("--rigid-subchains", action="store_true", default=None,
                   help="allow rigid sub-chains, W(S) ≥ 0 (default only for W = 0)")
    p.add_argument("--fractionated", action=YesOrNo, default=True,
                   help="keep chains split by one link or joint (default: keep)")
    p.add_argument("--planar-only", action="store_true", help="keep only chains with planar graphs")
    p.add_argument("--prismatic", metavar="A..B",
                   help="chains with A…B prismatic pairs on their simple joints, up to symmetry; wedge loops of "
                   "prismatic pairs add to W, so --dof stays the mobility of every chain listed")
    p.add_argument("--loop-classes", metavar="H=K,H=K",
                   help="heterogeneous chains with K loops of each class H, two classes (e.g. 3=4,5=1: the linear "
                   "translator): a base holding the higher class's loops on a chain of the lower class; --dof is W by "
                   "the heterogeneous count; with --chain, every base on that chain")
    p.add_argument("--chain", type=chain_text(command), help="one given chain instead of a query (a joint list '0-1 1=2 2~3 …' or a JSON row "
                   "a command printed): its row, its mechanisms, or with --prismatic its variants, renumbered as "
                   "every listing and atlas numbers its id, with the chain as given beside (column as_given)")
    p.add_argument("--idle-joints", action="store_true",
                   help="with --prismatic: keep chains with joints that never move, and list them")
    p.add_argument("--count", action="store_true", help='print {"count": N, "by_code": {...}} only')
    p.add_argument("--workers", type=workers, help="processes, at most the number of cores (default: all cores)")
    p.add_argument("--checkpoint", metavar="FILE",
                   help="with --count: commit unit counts to this SQLite file as they finish; rerun to resume")
    p.add_argument("--scheduler", metavar="ADDRESS", help="with --count: run the units on a Dask scheduler, "
                   "e.g. tcp://host:8786")
    p.add_argument("--timeout", type=seconds, help="with --scheduler: seconds to wait for it (default 5)")
    p.add_argument("--force", action="store_true",
                   help="run a query estimated to take more than a day (see docs/cli.md, 'Large queries')")
    p.add_argument("--format", choices=FORMATS + WRITTEN,
                   help="table (default), jsonl, csv or json; graphml, gml, dot, edgelist, adjacency or incidence "
                   "(docs/exchange.md); with --count json (default), table, jsonl or csv")


def add_commands(sub) -> None:
    """Mount ``chains`` and ``mechanisms`` on the ``mechsynth`` parser."""
    p = sub.add_parser("chains", help="type synthesis: every non-isomorphic chain")
    _add_selection(p, "chains")
    p.add_argument("--method", choices=("listing", "orbits", "tight-reverse"),
                   help="with --count: how each branch multigraph's chains are counted — listing (default: one "
                   "placement of the binary links per chain, as a listing finds them), orbits (Burnside's lemma "
                   "over the multigraph's automorphisms, without listing them; stderr says which units it "
                   "counted by the listing's search instead, and why) or tight-reverse (the second count "
                   "of a record: the counting programme over the strings in reverse, with another reading of the "
                   "automorphisms); the same counts; orbits and tight-reverse refused with prismatic pairs or cranks")
    p.set_defaults(run=_run, what="chains")
    p = sub.add_parser("mechanisms", help="chains with a fixed link (and input link) up to symmetry")
    _add_selection(p, "mechanisms")
    p.add_argument("--input-link", action="store_true", help="also choose the input link, jointed to the frame "
                   "(refused for trusses, W = 0: nothing moves)")
    p.add_argument("--cylinders", metavar="KIND=N,…",
                   help="with --prismatic: prismatic pairs by kind, e.g. floating=1,swinging=2 (guide: on the frame; "
                   "swinging: a cylinder pinned to the frame; floating: a cylinder between moving links; slider: "
                   "any other)")
    p.set_defaults(run=_run, what="mechanisms")


def query_of(args):
    """The :class:`synth.ChainQuery` of a ``chains``/``mechanisms``/``draw`` command line."""
    from synth import ChainQuery

    if args.links is None and args.code is None:
        raise _invalid("give --links N (or --code C)" if args.dof is not None else "give --dof (and --links), or --code")
    return ChainQuery.of(args.dof, args.links, code=args.code, v=args.v, n1=args.n1, h=3 if args.h is None else args.h,
                         require=args.require, cranks=args.cranks, max_multiplicity=args.max_multiplicity,
                         rigid_subchains=args.rigid_subchains, fractionated=args.fractionated,
                         planar_only=args.planar_only, prismatic=args.prismatic, idle_joints=args.idle_joints,
                         cylinders=getattr(args, "cylinders", None))


def _invalid(message: str):
    from synth import InvalidOption

    return InvalidOption(message)


def _check_options(args) -> None:
    for option in ("checkpoint", "scheduler"):
        if getattr(args, option) is not None and not args.count:
            raise _invalid(f"--{option} goes with --count (listings are not resumed or distributed)")
    if args.prismatic is not None and (args.checkpoint is not None or args.scheduler is not None):
        raise _invalid("chains with prismatic pairs are counted on this machine: drop --checkpoint and --scheduler")
    if args.scheduler is not None and args.workers is not None:
        raise _invalid("--workers and --scheduler contradict each other: the scheduler's workers run the units")
    if args.timeout is not None and args.scheduler is None:
        raise _invalid("--timeout goes with --scheduler (it is how long to wait for the scheduler)")
    if getattr(args, "method", None) is not None and not args.count:
        raise _invalid("--method goes with --count (it says how chains are counted; a listing lists them)")
    if getattr(args, "method", None) is not None and (args.chain is not None or args.loop_classes is not None):
        raise _invalid("--method goes with a query's count, not with --chain or --loop-classes")
    if args.count and args.format in WRITTEN:
        raise _invalid(f"--count prints a count as json, table, jsonl or csv, not {args.format} (a format of chains)")


def _size_note(query, args) -> tuple[str, float] | None:
    """Refuse a query too large to run unasked, and say how long a long one takes (stderr), with
    ``--force`` too; return what a count of chains reckons its time to go from: the units, with multiple
    joints, or the chains, and how many are expected (:func:`synth.time_to_go_from`; None: not sized)."""
    import os

    from synth import NOTE_SECONDS, describe_estimate, estimate, plan_jobs, size_check, time_to_go_from, worth_sizing

    processes = 1 if args.scheduler else (args.workers or os.cpu_count() or 1)
    mechanisms = None if args.what == "chains" else ("mechanisms with input" if args.input_link else "mechanisms")
    note = size_check(query, processes=processes, count=args.count, table=(args.format or "table") == "table",
                      force=args.force, mechanisms=mechanisms, scheduler=args.scheduler is not None)
    found = None
    if args.count and mechanisms is None and worth_sizing(query):
        plan_jobs(query)  # a plan this engine cannot build is refused alone, not after an estimate of it
        found = estimate(query)  # (the sizing's calibrations are kept in this process: counted once)
        if args.force and found is not None and found.seconds / processes > NOTE_SECONDS:  # skipped by size_check
            note = "a long query: " + describe_estimate(found, processes=processes, scheduler=args.scheduler is not None)
    if note:
        resumable = "" if not args.count or args.checkpoint else " (give --checkpoint FILE to make it resumable)"
        print(f"mechsynth: {note}{resumable}", file=sys.stderr)
    return None if found is None else time_to_go_from(query, found)


def _run_one_chain(args) -> int:
    """``--chain C``: that one chain (any joint list or JSON row a command printed) in its canonical
    numbering (the one its id has in every listing and atlas) — its row, or its mechanisms; with
    ``--prismatic A..B`` the variants of that chain (Fig. 6: a drive's cylinders)."""
    from synth import mechanisms_of
    from synth.exchange import read_chain
    from synth import parse_range
    from synth import prismatic_variants, variants_of

    given = [f"--{k.replace('_', '-')}" for k in ("dof", "links", "code", "v", "rigid_subchains", "planar_only", "n1")
             if getattr(args, k) not in (None, False)] + (["--require"] if args.require else []) + (
             ["--cranks"] if args.cranks else [])
    if given:
        raise _invalid(f"{given[0]} selects chains of a query and contradicts --chain")
    chain = read_chain(args.chain, None if args.h == 3 else args.h).chain  # as analyze, identify and draw read it
    if args.loop_classes is not None or chain.classes is not None:
        _refuse_classless_format(args)
    if args.loop_classes is not None:
        items = class_variants_of(chain, args)
    elif args.prismatic is None:
        if args.idle_joints or getattr(args, "cylinders", None):
            raise _invalid("--idle-joints and --cylinders go with --prismatic")
        items = [chain]
    else:
        lo, hi = parse_range(args.prismatic, "--prismatic")
        prismatic_variants(chain, lo)  # refuses a count beyond the chain's simple joints, with the reason
        items = variants_of([chain], (lo, hi), idle=args.idle_joints)
    # listed in the canonical numbering (a frame printed names the link move --db --id fixes), each row with the
    # chain as the user numbered it beside (which of the user's links a base or a prismatic pair took)
    back = {}  # id of a canonical chain listed -> (the chain as given, its links' numbers as given by canonical number)
    listed = []
    for given in items:
        numbering = given.canonical_numbering()
        listed.append(given.relabel(numbering))
        back[id(listed[-1])] = given, [numbering.index(k) for k in range(given.links)]
    items = listed
    defect = None
    if args.what == "mechanisms":
        if args.prismatic is None and args.loop_classes is None:  # the chain as given: a truss or a mechanism of its
            defect = _count_defect(chain)  # W? (variants and bases passed the exact test: their count is true)
        refuse_structure(chain, items, input_link=args.input_link, defect=defect)
        items = (m for c in items for m in mechanisms_of(c, input_link=args.input_link and c.dof != 0,  # a truss:
                                                         cylinders=getattr(args, "cylinders", None)))  # no input
    return write_items(items, args.what, fmt=args.format, count=args.count,
                       kinds=args.prismatic is not None or not chain.all_revolute, idle=args.idle_joints, h=chain.h,
                       as_given=lambda item: _as_given(item, *back[id(getattr(item, "chain", item))]), defect=defect)


def _count_defect(chain):
    """:func:`synth.count_defect` of a chain given by hand, or None with a note on stderr where the exact test
    cannot run (more non-binary links than it takes): its mechanisms are then listed by the count."""
    from synth import MalformedChain, count_defect

    try:
        return count_defect(chain)
    except MalformedChain as err:
        print(f"mechsynth: note: {err}, so this chain's W by the count is not checked", file=sys.stderr)
        return None


def refuse_structure(given, chains, *, input_link: bool = False, defect=None) -> None:
    """Refuse the mechanisms of a chain ``given`` whose W by the count is below 0 (one of ``chains``, the
    chain itself or its variants, to be fixed by each link in turn): it is a structure, over-constrained, and a
    link is fixed in a chain of W ≥ 0 only (a mechanism, W ≥ 1, or a truss on a frame, W = 0) — as a code of
    W < 0 is refused.  With ``input_link``, refuse too chains that are all of W = 0 (trusses on a frame, where
    nothing moves, so no link drives them) and, with ``defect`` (:func:`synth.count_defect` of ``given``), a chain
    whose count misleads, whatever its W: its input links would be chosen by that count.

    >>> from synth import Chain
    >>> refuse_structure(Chain.parse("0-1 1-2 2-3 3-0 1-3"), [Chain.parse("0-1 1-2 2-3 3-0 1-3")])
    Traceback (most recent call last):
    synth.errors.ImpossibleParameters: the chain 0-1 0-3 1-2 1-3 2-3 is a structure, not a mechanism's chain: W = -1 by the count (over-constrained): a mechanism fixes a link of a chain with W ≥ 1, a truss on a frame one of W = 0 ('mechsynth analyze' says why and how to mend it)
    """
    from synth import not_a_mechanisms_chain, truss_has_no_input

    dofs = [c.dof for c in chains]
    dof = min(dofs, default=0)
    if dof < 0:
        raise not_a_mechanisms_chain(given, dof)
    if input_link and (defect is not None or dofs and max(dofs) == 0):
        raise truss_has_no_input(f"the chain {given.compact()} has", "--input-link", defect)


def _as_given(item, given, as_given: list[int]) -> dict:
    """The columns of a row of ``chains --chain C``: the chain in the user's numbering, and a mechanism's fixed
    and input links by their numbers there."""
    out = {"as_given": given.compact()}
    if item is not getattr(item, "chain", item):
        out["frame_as_given"] = as_given[item.frame]
        out["input_link_as_given"] = None if item.input_link is None else as_given[item.input_link]
    return out


def _refuse_classless_format(args) -> None:
    """Other tools' formats have no place for loop classes: they would drop them silently."""
    if args.format in WRITTEN:
        raise _invalid(f"--format {args.format} has no place for loop classes: list heterogeneous chains as table, "
                       "jsonl, json or csv (their joint lists and rows carry the classes)")


def class_variants_of(chain, args) -> list:
    """``--chain C --loop-classes H=K,X=K``: every base of K_X loops of class X on that chain, read
    in class H (the lower one)."""
    from dataclasses import replace

    from synth import class_variants, split_classes

    from .codes import parse_classes

    h, k_h, x, k_x = split_classes(parse_classes(args.loop_classes))
    if not chain.all_revolute or chain.classes is not None:
        raise _invalid("--loop-classes lays bases on a revolute chain without classes: give its joint list without "
                       "'=', '~' or '|'")
    if chain.loops != k_h + k_x:
        raise _invalid(f"the chain has {chain.loops} loop{'s' * (chain.loops != 1)} and --loop-classes asks for "
                       f"{k_h + k_x}")
    return class_variants(replace(chain, h=h), x, k_x)


def _run_classes(args) -> int:
    """``chains --dof W --loop-classes H=K,X=K``: every heterogeneous chain (a base of class X on a
    chain of class H), skeletons built by type synthesis in the process, bases laid here."""
    from synth import heterogeneous_synthesis, mechanisms_of, size_note, skeleton_query

    from .codes import parse_classes

    refused = [name for name, value in (("--prismatic", args.prismatic is not None),
                                        ("--n1", args.n1 is not None), ("--checkpoint", args.checkpoint is not None),
                                        ("--scheduler", args.scheduler is not None)) if value]
    if refused:
        raise _invalid(f"{refused[0]} contradicts --loop-classes (heterogeneous chains are closed, revolute and "
                       "listed on this machine)")
    if args.dof is None:
        raise _invalid("give --dof W (the heterogeneous count's W) with --loop-classes")
    _refuse_classless_format(args)
    classes = parse_classes(args.loop_classes)
    selection = dict(code=args.code, v=args.v, require=args.require, cranks=args.cranks,
                     max_multiplicity=args.max_multiplicity, rigid_subchains=args.rigid_subchains,
                     fractionated=args.fractionated, planar_only=args.planar_only)
    import os

    _refuse_input_of_trusses(args, args.dof)
    skeletons = skeleton_query(args.dof, classes, links=args.links, **selection)
    note = size_note(skeletons, processes=args.workers or os.cpu_count() or 1, force=args.force)
    if note:
        print(f"mechsynth: {note}", file=sys.stderr)
    items = heterogeneous_synthesis(args.dof, classes, links=args.links, workers=args.workers, progress=True,
                                    **selection)
    if args.what == "mechanisms":
        items = (m for c in items for m in mechanisms_of(c, input_link=args.input_link))
    return _write(items, args)


def _refuse_input_of_trusses(args, dof: int) -> None:
    """``mechanisms --input-link`` of a query whose chains have W = ``dof`` = 0: trusses, with nothing to drive."""
    if args.what == "mechanisms" and args.input_link and dof == 0:
        from synth import truss_has_no_input

        raise truss_has_no_input("the chains of this query have", "--input-link")


def _run(args) -> int:
    from synth import count_chains, count_mechanisms, mechanisms, type_synthesis

    from .codes import motion_space

    _check_options(args)
    motion_space(args)  # (refuses --h beside --loop-classes)
    if getattr(args, "cylinders", None) and args.prismatic is None:
        raise _invalid("--cylinders goes with --prismatic (a revolute chain has no cylinder)")
    if args.chain is not None:
        return _run_one_chain(args)
    if args.idle_joints and args.prismatic is None:
        raise _invalid("--idle-joints goes with --prismatic (an all-revolute chain has no idle joint)")
    if args.loop_classes is not None:
        return _run_classes(args)
    query = query_of(args)
    _refuse_input_of_trusses(args, query.dof)
    most_v = query.code.v if query.code is not None else (query.v or (0, 0))[1]
    if args.format == "adjacency" and most_v != 0:
        raise _invalid("an adjacency matrix holds simple joints only, and this query lists multiple joints (--v): "
                       "use --format incidence")
    expected = _size_note(query, args)
    if args.count:  # counted in the worker processes: flat memory at any size
        log = None
        if args.checkpoint is not None and not sys.stderr.isatty():  # batch runs log the first commit, then one a minute
            from synth import Every

            log = Every(lambda line: print(f"mechsynth: {line}", file=sys.stderr, flush=True))
        extra = dict(workers=args.workers, progress=True, checkpoint=args.checkpoint, scheduler=args.scheduler,
                     timeout=args.timeout or 5.0, log=log)
        try:
            if args.what == "chains":  # a code counted before is read from the solver store (not on request for units)
                result = count_chains(query, remember=args.checkpoint is None and args.scheduler is None,
                                      method=args.method or "listing", expected=expected, **extra)
            else:
                result = count_mechanisms(query, input_link=args.input_link, **extra)
        finally:
            if log is not None:
                log.flush()  # the checkpoint's last commit, held back by the minute, ends the log
        found = write_count(result.to_dict(), args.format or "json")
        for note in (result.by_search_note, result.shared_note):  # --method orbits says where it did not count by
            if note is not None:  # orbits, --method tight-reverse where it shared the first count's path
                print(f"mechsynth: {note}", file=sys.stderr)
        if found == 0:
            return nothing_found(f"{args.what} satisfy these parameters and conventions")
        return 0
    if args.what == "chains":
        items = type_synthesis(query, workers=args.workers, progress=True)
    else:
        items = mechanisms(query, input_link=args.input_link, workers=args.workers, progress=True)
    return _write(items, args)


def _write(items, args) -> int:
    return write_items(items, args.what, fmt=args.format, count=args.count, kinds=args.prismatic is not None,
                       idle=args.idle_joints, h=3 if args.h is None else args.h)


def write_items(items, what: str, *, fmt: str | None, count: bool = False, kinds: bool = False,
                idle: bool = False, h: int = 3, as_given=None, defect=None) -> int:
    """List chains or mechanisms (``what``) in the chosen format, or count them by code; with
    ``kinds`` the columns of joint kinds (W, K_2, K_3; the prismatic pairs of mechanisms by kind),
    with ``idle`` the joints that never move, in motion space ``h`` ≠ 3 its column (a table or
    CSV row is read back in its space); ``as_given`` (an item's extra columns: :func:`_as_given`) adds the
    user's numbering of a chain given; ``defect`` (:func:`synth.count_defect`) says why the mechanisms of one
    chain given are no trusses or not of its W by the count.  Returns the exit status (1 when none)."""
    if count:
        from synth import count_by_code

        by_code = count_by_code(items)
        if write_count({"count": sum(by_code.values()), "by_code": by_code}, fmt or "json") == 0:
            return nothing_found(f"{what} satisfy these parameters and conventions")
        return 0
    fmt = fmt or "table"
    if fmt in WRITTEN:
        from synth.exchange import write

        n = write(items, fmt)
        return 0 if n else nothing_found(f"{what} satisfy these parameters and conventions")
    if what == "mechanisms" and fmt == "table":  # its last line names its trusses on a frame (W = 0) as such
        items = TrussCounter(items)
    rows = (_row(item, fmt, idle) | (as_given(item) if as_given else {}) for item in items)
    columns = ["index", "id", "code", "links", "joints", "certificate"]
    if h != 3:
        columns.insert(3, "h")
    if fmt in ("table", "csv") and what == "chains":  # the atlas site's columns, for people
        columns[-1:-1] = ["planar", "symmetry", "fractionated"]
    if kinds:
        columns[3:3] = ["dof", "loops_2", "loops_3"]
        if idle:
            columns.insert(-1, "idle_joints")
    if what == "mechanisms":
        columns[1] = "chain_id"
        columns[-2:-2] = ["frame", "input_link"]
        if kinds:
            columns[-2:-2] = ["guide", "swinging", "floating", "slider"]
    if as_given:  # beside the joints as listed
        at = columns.index("joints") + 1
        columns[at:at] = ["as_given"] + (["frame_as_given", "input_link_as_given"] if what == "mechanisms" else [])
    n = write_rows(_indexed(rows), columns, fmt)
    if fmt == "table" and what == "mechanisms":
        from synth import mechanisms_summary

        print(mechanisms_summary(n, items.trusses, defect=defect))
    elif fmt == "table":
        print(f"{n} {what if n != 1 else what[:-1]}")  # 1 chain
    if n == 0:
        return nothing_found(f"{what} satisfy these parameters and conventions")
    return 0


class TrussCounter:
    """Mechanisms passed through one at a time (a listing streams), counting the trusses on a frame (W = 0)
    among them in ``trusses``.

    >>> from synth import Chain, Mechanism
    >>> counter = TrussCounter(Mechanism(Chain.parse(c), 0) for c in ("0-3 0-4 1-3 1-4 2-3 2-4", "0-1 1-2 2-3 3-0"))
    >>> len(list(counter)), counter.trusses
    (2, 1)
    >>> import itertools
    >>> truss = Mechanism(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4"), 0)
    >>> counter = TrussCounter(itertools.repeat(truss)); stream = iter(counter)
    >>> next(stream) is truss, next(stream) is truss, counter.trusses   # an endless stream, counted as it goes
    (True, True, 2)
    """

    def __init__(self, mechanisms):
        self.mechanisms = mechanisms
        self.trusses = 0

    def __iter__(self):
        for mechanism in self.mechanisms:
            self.trusses += mechanism.chain.dof == 0
            yield mechanism


def _indexed(rows):
    for i, row in enumerate(rows, start=1):
        row["index"] = i
        yield row


def _row(item, fmt: str, idle: bool) -> dict:
    """The JSON row of a chain or mechanism; in a table or CSV the joint list as ``analyze`` reads it
    (``0=1`` a prismatic pair), in a table a short certificate."""
    from synth import chain_id

    row = item.to_dict()
    chain = getattr(item, "chain", item)
    row["chain_id" if chain is not item else "id"] = chain_id(chain.certificate)
    if fmt in ("table", "csv") and chain is item:
        row.update(planar="yes" if chain.is_planar() else "no", symmetry=round(chain.automorphisms()[1]),
                   fractionated="yes" if chain.is_fractionated() else "no")
    if chain.all_revolute and chain.classes is None:  # a revolute chain among prismatic variants: nothing slides
        row.update(prismatic=0, loops_2=0, loops_3=chain.loops)
        if "frame" in row:
            row.update(guide=0, swinging=0, floating=0, slider=0)
    if idle and not chain.all_revolute:
        from synth import idle_joints

        row["idle_joints"] = [list(j) for j in idle_joints(chain)]
    if fmt in ("table", "csv"):  # the joint list as analyze and chains --chain read it back, kinds included
        row["joints"] = chain.compact()
    if fmt == "table":
        row["certificate"] = "…" + row["certificate"][-16:]
        if "idle_joints" in row:
            row["idle_joints"] = " ".join("-".join(map(str, j)) for j in row["idle_joints"]) or "none"
    return row
