"""CLI command ``draw``: chains, mechanisms and gear trains drawn as a designer does (SVG, PNG, PDF),
and a dimensioned mechanism (a linkage file) to scale at its pose or at an input value.

Example
-------
>>> import tempfile, pathlib
>>> from mechsynth.cli import main
>>> out = str(pathlib.Path(tempfile.mkdtemp()) / "watt.svg")
>>> main(["draw", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--out", out])
0
>>> pathlib.Path(out).read_text().count("<svg") >= 1
True
"""

from __future__ import annotations

import math
import os
import sys

from .._argtypes import YesOrNo, add_row, chain_text, finite, inches, picture_file, positive, where_conditions, whole

__all__ = ["add_commands"]

SHEET_LIMIT = 400  # drawings of a sheet unless --limit says otherwise


def add_commands(sub) -> None:
    """Mount ``draw`` on the ``mechsynth`` parser."""
    p = sub.add_parser("draw", help="draw chains or mechanisms as a designer does (SVG/PNG)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("linkage", nargs="?", metavar="LINKAGE_FILE",
                   help="a dimensioned mechanism (.toml or .json, as move --save and dimension --save write it), "
                        "drawn to scale at its pose; or the rows of an atlas search (.json or .jsonl) with --row K")
    g.add_argument("--code", help="every chain of this code, e.g. 7201/1 (synthesised now)")
    g.add_argument("--chain", type=chain_text("draw"), help="one chain as a joint list '0-1 1-2 2-3 3-0' or JSON")
    g.add_argument("--db", help="chains of an atlas selected with --where or --id")
    p.add_argument("--dof", type=whole, help="with --code: W (default: the code's own in motion space h); "
                   "with --repairs: the intended W")
    p.add_argument("--h", type=whole, help="with --code or --chain: motion space of the loops, 2 … 6 (default 3, or "
                   "the chain's own)")
    p.add_argument("--where", action="append", nargs="+", default=[], metavar="FIELD OP VALUE",
                   help="with --db: filter (as for 'mechsynth atlas')")
    p.add_argument("--id", help="with --db: the chain with this id (12 hex digits, as listings and the site show it)")
    p.add_argument("--at", type=finite, metavar="VALUE",
                   help="with a linkage file: draw it with its input at VALUE (degrees for a revolute input, a "
                        "length for a prismatic one, as move's --start), on the branch of its pose")
    p.add_argument("--frame", type=whole, help="with --chain: the fixed link (hatched)")
    p.add_argument("--loop-classes", metavar="H=K,H=K",
                   help="with --chain: every base of the higher class's loops on that chain (e.g. 3=4,5=1), "
                        "each base's links in its class's colour")
    p.add_argument("--repairs", type=positive, nargs="?", const=5, metavar="N",
                   help="with --chain: draw it beside its N (default 5) nearest valid rebuilt chains")
    p.add_argument("--mechanisms", action="store_true", help="draw every mechanism (fixed link up to symmetry)")
    p.add_argument("--prismatic", metavar="A..B",
                   help="draw every assignment of A…B prismatic pairs to the simple joints, up to symmetry "
                        "(a slider is a block on a bar, a cylinder a dark barrel)")
    p.add_argument("--idle-joints", action="store_true",
                   help="with --prismatic: keep revolute pairs whose links are also joined by prismatic pairs")
    p.add_argument("--columns", type=positive, help="drawings per row of a sheet (refused for one drawing)")
    p.add_argument("--size", type=inches, help="edge of each drawing in inches (default 3.6 alone, 1.9 on a sheet)")
    p.add_argument("--dpi", type=positive, help="resolution of a .png in dots per inch (default 150)")
    p.add_argument("--labels", action=YesOrNo, default=None,
                   help="number the links (default: on for one drawing and for mechanisms, off on chain sheets)")
    p.add_argument("--limit", type=positive, help=f"refuse sheets larger than this (default {SHEET_LIMIT})")
    p.add_argument("--title", help="the title over the sheet or drawing (default: the selection; a linkage file: "
                   "its chain, frame and input)")
    p.add_argument("-o", "--out", required=True, type=picture_file,
                   help="output file, .svg or .png (or .pdf), checked writable before any drawing")
    add_row(p)
    p.set_defaults(run=_run_draw)


def _variants(args, chains: list) -> list:
    """The chains themselves, or with ``--prismatic A..B`` every R/P variant of each."""
    if args.prismatic is None:
        return chains
    from synth import InvalidOption
    from synth import parse_range
    from synth import variants_of

    lo, hi = parse_range(args.prismatic, "--prismatic")
    chains = [c for c in chains if c.all_revolute]  # an atlas may hold variants already
    if not chains:
        return []
    simple = max(sum(1 for j in c.joints if len(j) == 2) for c in chains)
    if lo > simple:
        raise InvalidOption(f"--prismatic {args.prismatic} asks for more prismatic pairs than the {simple} "
                            "simple joints of these chains")
    return list(variants_of(chains, (lo, simple if hi is None else min(hi, simple)), idle=args.idle_joints))


def _chain_sheet_title(chain, items: list, args) -> str:
    """The title of a sheet drawn from one ``--chain``, as a ``--code`` sheet's: the chain's code, its
    W and what the drawings are (a chain given alone, fixed by each link: mechanisms, trusses, or what it is
    where its count misleads).

    >>> from argparse import Namespace; from synth import Chain, Mechanism
    >>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    >>> _chain_sheet_title(watt, [watt] * 11, Namespace(loop_classes=None, prismatic="1..2", mechanisms=False))
    '42/0 (W = 1): 11 variants with 1..2 prismatic pairs'
    >>> truss = Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4")
    >>> _chain_sheet_title(truss, [Mechanism(truss, 0), Mechanism(truss, 3)], Namespace(loop_classes=None,
    ...                    prismatic=None, mechanisms=True))
    '32/0 (W = 0): 2 trusses on a frame'
    >>> moving = Chain.parse("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-2")  # a braced four-bar beside a five-bar loop
    >>> _chain_sheet_title(moving, [Mechanism(moving, 0), Mechanism(moving, 4)], Namespace(loop_classes=None,
    ...                    prismatic=None, mechanisms=True))
    '340/0 (W = 0 by the count): 2 chains on a frame, not trusses'
    >>> _chain_sheet_title(Chain.parse("0-1 1-2 2-0 2-3 3-4 4-5 5-0"), [Mechanism(watt, 0)] * 4,
    ...                    Namespace(loop_classes=None, prismatic=None, mechanisms=True))  # a four-bar's frame a triangle
    '42/0 (W = 1): 4 degenerate mechanisms'
    """
    n, s = len(items), "s" * (len(items) != 1)
    dofs = {getattr(item, "chain", item).dof for item in items}  # the bases of loop classes carry their own W
    kind, detail = (("base", f" of loop classes {args.loop_classes}") if args.loop_classes is not None
                    else ("variant", f" with {args.prismatic} prismatic pair{'s' * (args.prismatic != '1')}") if args.prismatic is not None
                    else ("chain", ""))
    defect = None  # of the chain given, where its count misleads
    if not args.mechanisms:
        what = f"{n} {kind}{s}{detail}"
    else:  # a chain of W = 0 on a frame is a truss, not a mechanism
        from synth import count_defect, on_a_frame

        defect = count_defect(chain) if kind == "chain" else None  # (variants and bases passed the exact test)
        what = on_a_frame(n, sum(item.chain.dof == 0 for item in items), defect=defect) + (
            "" if kind == "chain" else f" of its {kind}s{detail}")
    w = f"W = {dofs.pop()}" if len(dofs) == 1 else "W = " + ", ".join(map(str, sorted(dofs)))
    w += " by the count" if defect and not defect.degenerate_only else ""
    h = "" if chain.h == 3 else f", h = {chain.h}"
    return f"{chain.code} ({w}{h}): {what}"


def _defect(chain, dof) -> str:
    """What is wrong with a chain to repair, in a few words (the caption of its drawing)."""
    from synth import check_subchains

    report = check_subchains(chain, rigid_subchains=(chain.dof if dof is None else dof) == 0)
    wrong = f"W = {chain.dof}, not {dof}; " if dof is not None and dof != chain.dof else ""
    if report.ok:
        return f"given: {wrong or 'no defect'}".rstrip("; ")
    return (f"given: {wrong}{report.kind} of links {', '.join(map(str, report.worst))} (W(S) = "
            f"{report.worst_mobility})")


def _at_most(chains, args):
    """The selected chains, stopped once they are more than ``--limit`` drawings (each chain is
    at least one; R/P variants may be none): a large selection is refused without being built."""
    import itertools

    return chains if args.prismatic is not None else itertools.islice(chains, args.limit + 1)


def _one_drawing_takes_no_columns(args, drawings: int) -> None:
    """Refuse ``--columns`` where the picture holds one drawing (it sets the drawings per row of a sheet)."""
    if args.columns is not None and drawings == 1:
        from synth import InvalidOption

        raise InvalidOption("--columns sets the drawings per row of a sheet, and this picture is one drawing "
                            "(a sheet: --code, --db, --mechanisms or --prismatic)")


def _draw_trains(rows, args) -> int:
    """Gear trains of an atlas as functional schematics (shafts, gears on their axes, carriers), as
    ``gears --out`` and the site draw them."""
    from synth import InvalidOption
    from synth.draw import draw_train, draw_train_sheet
    from synth.gears import GearTrain

    if len(rows) > args.limit:
        raise InvalidOption(f"the selection has more than {args.limit} drawings (--limit); narrow it with --where "
                            "or raise --limit")
    unused = [name for name, given in (("--dpi", args.dpi), ("--labels", args.labels is not None),
                                       ("--size", args.size is not None and len(rows) > 1)) if given]
    if unused:
        raise InvalidOption(f"gear trains are drawn as schematics, which take no {', '.join(unused)}"
                            + (" on a sheet" if unused == ["--size"] else ""))
    _one_drawing_takes_no_columns(args, len(rows))
    trains = [GearTrain.parse(row["train"]) for row in rows]
    if len(trains) == 1:
        draw_train(trains[0], args.out, title=args.title, size=args.size or 6.0)
    else:
        draw_train_sheet(trains, args.out, columns=args.columns or 4, limit=args.limit,
                   titles=[f"{k + 1}: {row['code']} (lever analogue {row['lever_code']})\nid {row['id']}"
                           for k, row in enumerate(rows)])
    print(f"{len(trains)} schematic{'s' if len(trains) != 1 else ''} -> {args.out}", file=sys.stderr)
    return 0


def _draw_linkage(args) -> int:
    """A linkage file drawn to scale by the motion layer's drawing, at its saved pose or at ``--at``."""
    from synth import InvalidOption, JointKind
    from synth.draw import SINGLE
    from synth.motion import assemble, read_linkage
    from synth.motion_draw import draw_linkage

    chosen = [name for name, given in (
        ("--frame", args.frame is not None), ("--mechanisms", args.mechanisms), ("--prismatic", args.prismatic),
        ("--idle-joints", args.idle_joints), ("--repairs", args.repairs), ("--loop-classes", args.loop_classes),
        ("--dof", args.dof is not None), ("--h", args.h is not None), ("--where", args.where),
        ("--id", args.id is not None), ("--columns", args.columns is not None), ("--limit", args.limit is not None))
        if given]
    if chosen:
        raise InvalidOption(f"a linkage file is one dimensioned mechanism, drawn as it is (its file names its frame "
                            f"and inputs): {', '.join(chosen)} {'does' if len(chosen) == 1 else 'do'} not apply")
    if args.dpi is not None and not args.out.lower().endswith(".png"):
        raise InvalidOption("--dpi sets the resolution of a .png; .svg and .pdf drawings are vector files")
    if not args.linkage.lower().endswith((".toml", ".json", ".jsonl", ".csv")) and not os.path.exists(args.linkage):
        raise InvalidOption(f"a linkage file is .toml or .json, not {args.linkage!r}: a chain's drawing is "
                            f"'mechsynth draw --chain \"{args.linkage}\" --out FILE'")
    linkage = read_linkage(args.linkage, row=args.row)
    title = args.title
    if args.at is not None:
        if linkage.dof != 1:
            raise InvalidOption(f"--at poses a linkage of one input, and this one has W = {linkage.dof} inputs: draw it "
                                "at its saved pose, or move it over a grid with 'mechsynth move'")
        revolute = linkage.kind(linkage.inputs[0]) == JointKind.REVOLUTE
        linkage = assemble(linkage, math.radians(args.at) if revolute else args.at)
        title = title or f"{linkage.chain.compact()}, frame {linkage.frame}, input at {args.at:g}{'°' * revolute}"
    size, dpi = SINGLE
    draw_linkage(linkage, args.out, size=args.size or size, dpi=args.dpi or dpi, title=title,
                 labels=args.labels is not False)
    print(f"1 drawing -> {args.out}", file=sys.stderr)
    return 0


def _run_draw(args) -> int:
    from synth.draw import CELL, SINGLE, draw_one, draw_sheet, expand
    from synth import Chain, Mechanism
    from synth import InvalidOption

    if args.linkage:
        return _draw_linkage(args)
    args.limit = SHEET_LIMIT if args.limit is None else args.limit
    if args.at is not None:
        raise InvalidOption("--at poses a linkage file's input: a chain's drawing has no dimensions to move (save "
                            "one with 'mechsynth move --chain … --frame F --save L.json', then draw L.json --at)")
    if args.row is not None:
        raise InvalidOption("--row picks a row of a file of an atlas search's rows: give that file (draw ROWS.json "
                            "--row K --out FILE), not a chain or an atlas")
    args.where = where_conditions(args.where)
    if args.id is not None:
        if not args.db:
            raise InvalidOption("--id names a chain of an atlas: give --db too (for a chain of your own, "
                                "'mechsynth identify' finds its id)")
        args.where.append(f"id={args.id}")
    if args.dpi is not None and not args.out.lower().endswith(".png"):
        raise InvalidOption("--dpi sets the resolution of a .png; .svg and .pdf drawings are vector files")
    if args.where and not args.db:
        raise InvalidOption("--where filters an atlas: give --db too")
    from .codes import motion_space

    motion_space(args)  # (refuses --h beside --loop-classes)
    if args.loop_classes is not None and not args.chain:
        raise InvalidOption("--loop-classes goes with --chain (for a query: mechsynth chains --loop-classes … "
                            "--format jsonl, then draw a row with --chain)")
    if args.frame is not None and not args.chain:
        raise InvalidOption("--frame goes with --chain (for sheets use --mechanisms)")
    if args.frame is not None and args.mechanisms:
        raise InvalidOption("--frame and --mechanisms contradict each other: one fixed link, or every one up to "
                            "symmetry")
    if args.dof is not None and not (args.code or args.repairs):
        raise InvalidOption("--dof goes with --code (the W of its chains) or --repairs (the intended W); a chain "
                            "and an atlas's chains carry their own")
    if args.h is not None:
        from synth import check_motion_space

        if args.db:
            raise InvalidOption("--h goes with --code or --chain (an atlas's chains carry their own h)")
        check_motion_space(args.h, lowest=2)
        if args.repairs and args.h != 3:
            raise InvalidOption("--repairs rebuilds planar chains (h = 3), not chains in motion space h = "
                                f"{args.h}")
    given = None
    if args.chain:  # read as analyze and identify read it, in its own motion space unless --h says another
        from synth.exchange import read_chain

        given = read_chain(args.chain, args.h).chain
    h = given.h if given is not None else args.h or 3
    if args.repairs and h != 3:
        raise InvalidOption(f"--repairs rebuilds planar chains (h = 3), not chains in motion space h = {h}")
    notes = None  # the words under each drawing of a sheet: the edits of the repairs
    if args.idle_joints and args.prismatic is None:
        raise InvalidOption("--idle-joints goes with --prismatic (an all-revolute chain has no idle joint)")
    if args.prismatic is not None and (args.repairs or args.frame is not None or h != 3):
        raise InvalidOption("--prismatic draws the variants of planar chains (h = 3); it does not go with "
                            "--repairs or --frame (use --mechanisms for every fixed link)")
    if args.repairs and (not args.chain or args.frame is not None or args.mechanisms):
        raise InvalidOption("--repairs goes with --chain alone (not --frame or --mechanisms)")
    if args.chain and args.repairs:
        from synth import chain_repairs

        chain = given
        repairs = chain_repairs(chain, dof=args.dof, limit=args.repairs)
        if not repairs:
            print("mechsynth: no repair: the chain is valid already, or no valid one lies within three edits",
                  file=sys.stderr)
            return 1
        items = [chain, *(Chain.parse(r.chain) for r in repairs)]
        notes = [_defect(chain, args.dof)] + ["; ".join(r.edits) for r in repairs]
        title = args.title or f"{chain.compact()} and {len(repairs)} repairs"
    elif args.chain:
        chain = given
        if args.loop_classes is not None:
            from .chains import class_variants_of

            if args.frame is not None or args.prismatic is not None:
                raise InvalidOption("--loop-classes draws every base on the chain: it does not go with --frame or "
                                    "--prismatic (use --mechanisms for every fixed link)")
            items = expand(class_variants_of(chain, args), mechanisms=args.mechanisms)
            if not items:
                print("mechsynth: no base of those loop classes passes the exact test on this chain", file=sys.stderr)
                return 1
        else:
            from .chains import refuse_structure

            chains = _variants(args, [chain])
            if args.mechanisms or args.frame is not None:
                refuse_structure(chain, chains)
            if args.frame is not None:
                items = [Mechanism(chain, args.frame)]
            else:
                items = expand(chains, mechanisms=args.mechanisms)
        title = args.title or (_chain_sheet_title(chain, items, args) if len(items) > 1 else None)  # one: its caption
    elif args.code:
        import synth

        query = synth.ChainQuery.of(args.dof, code=args.code, h=h)
        code, dof = query.code, query.dof
        chains = list(_at_most(synth.type_synthesis(query, workers=1), args))
        if not chains:
            print(f"mechsynth: no chain has code {args.code} with W = {dof}", file=sys.stderr)
            return 1
        items = expand(_variants(args, chains), mechanisms=args.mechanisms)
        title = args.title or f"{code} (W = {dof}{'' if h == 3 else f', h = {h}'}): {len(chains)} chains"
    else:
        from synth.atlas import export

        rows = list(_at_most(export(args.db, "chains", where=args.where), args))
        if not rows:
            print("mechsynth: no chain of the atlas matches the selection", file=sys.stderr)
            return 1
        if all(row.get("kind") == "gears" for row in rows) and args.prismatic is None and not args.mechanisms:
            return _draw_trains(rows, args)
        chains = [Chain.from_dict(row) for row in rows]
        items = expand(_variants(args, chains), mechanisms=args.mechanisms)
        title = args.title or (None if args.id else f"{' '.join(args.where) or 'atlas'}: {len(chains)} chains")
    if not items:  # only --prismatic can empty a selection here
        print(f"mechsynth: no variant with {args.prismatic} prismatic pairs passes the exact test", file=sys.stderr)
        return 1
    if len(items) > args.limit:
        cut = args.prismatic is None and bool(args.code or args.db) and len(chains) > args.limit  # not all built
        size = (f"more than {args.limit} drawings (--limit)" if cut
                else f"{len(items)} drawings, more than --limit {args.limit}")
        raise InvalidOption(f"the selection has {size}; narrow it with --where or raise --limit")
    _one_drawing_takes_no_columns(args, len(items))
    if len(items) == 1 and not (args.code or (args.db and args.id is None)):
        size, dpi = SINGLE
        draw_one(items[0], args.out, title=title, labels=args.labels is not False,
                      size=args.size or size, dpi=args.dpi or dpi)
    else:
        size, dpi = CELL
        draw_sheet(items, args.out, columns=args.columns, title=title, labels=args.labels,
                        size=args.size or size, dpi=args.dpi or dpi, notes=notes)
    print(f"{len(items)} drawing{'s' if len(items) != 1 else ''} -> {args.out}", file=sys.stderr)
    return 0
