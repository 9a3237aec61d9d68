"""Which chain is this?  Identify a chain or mechanism from anywhere against the engine's atlas.

A chain read from any format (:mod:`synth.exchange`) is checked — connected, its true mobility,
the exact sub-chain verdict, the conventions it passes, fractionation, planarity, idle joints —
and identified:

* its **id** (the first 12 hex digits of the SHA-1 of its nauty certificate: the address of its
  page in an atlas web site, ``chain.html#<id>``, and the ``id`` column of every listing) and
  its certificate, and its joints **as listed**: in the one numbering every listing and atlas
  gives that id (:meth:`~synth.structure.chain.Chain.canonical`), a mechanism's frame too;
* its **code** and its **place in the listing** of that code: the row number ``index`` in
  ``mechsynth chains --code C`` with the options its conventions need (``--rigid-subchains``
  for a chain with a rigid sub-chain, ``--dof W --prismatic P`` for prismatic pairs, …);
* its **symmetry**: the order of its automorphism group and its link orbits;
* its **classical name** where it has one (:mod:`synth.analysis.classical`);
* for a mechanism (a chain with a frame), the **frame's orbit** (the links whose fixing gives the
  same mechanism), the mechanism's certificate, its row in ``mechanisms --code C`` and its
  classical inversion name.

The listing order is deterministic: codes in the order of number synthesis, then the branch
multigraphs of each code by nauty certificate, then the chains of each multigraph by
certificate (with prismatic pairs: the revolute skeletons in that order, then their
assignments in order) — all canonical, so the index does not depend on the numbering of the
links, the number of workers or the run (docs/exchange.md, "The listing order").

Example
-------
>>> from synth import identify                            # reads any source (synth.exchange.identify)
>>> r = identify("0-3 3-5 5-1 1-0 0-2 2-4 4-1")        # a Watt chain, numbered at random
>>> r.code, r.index, r.listed, r.listing, r.classical
('42/0', 2, 2, 'mechsynth chains --code 42/0', ['Watt chain'])
>>> r.id == identify("0-1 1-2 2-3 3-0 0-4 4-5 5-1").id
True
>>> m = identify("0-1 1-2 2-3 3-0 0-4 4-5 5-1", frame=3)
>>> m.frame_orbit, m.inversion
([2, 3, 4, 5], ['Watt I'])
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field, fields
from functools import lru_cache

from mechbase import Row

from ..errors import MalformedChain
from ..structure.chain import Chain, Mechanism, chain_id
from ..structure.joints import MESH, PRISMATIC

__all__ = ["Identity", "identify_entry", "chain_id", "listing_query", "index_size", "INDEX_SECONDS"]

# The place in a code's listing is found by listing the code.  Unasked, that is done when listing
# every chain of the chain's link count (an upper bound of its code's listing) is estimated to take
# at most this long on one core: 14 links at W = 1 (about 26 s), not 16 links at W = 3 (4.0e+06
# chains, 4 to 7 min estimated; one code of it holds 2.4 million).
INDEX_SECONDS = 60.0
# a heterogeneous chain's listing (its bases laid on every skeleton) is not sized: found unasked up to 4 loops
_INDEXED_CLASS_LOOPS = 4


@dataclass(frozen=True)
class Identity(Row):
    """What a chain (or mechanism) is: see the module docstring.  Links are named as the source
    named them (``names``; numbers 0 … n − 1 where the source used those).

    ``index`` is the 1-based row of the chain in ``listing`` (``listed`` rows), None with the
    reason in ``note`` when no listing holds it or it was not computed.  The mechanism fields
    (``frame`` … ``inversion``) are None for a chain without a frame.
    """

    source: str
    links: int
    joints: list
    kinds: list | None
    h: int
    names: list | None
    id: str
    certificate: str
    listed_joints: str
    code: str
    dof: int
    dof_count: int
    loops: int
    v: int
    connected: bool
    subchains: str
    worst_subchain: list
    worst_mobility: int | None
    fractionated: bool | None
    planar: bool
    idle_joints: list
    conventions: dict
    symmetry: int
    link_orbits: list
    classical: list
    listing: str | None
    index: int | None
    listed: int | None
    note: str = ""
    frame: object = None
    input_link: object = None
    frame_orbit: list | None = None
    listed_frame: int | None = None
    listed_input_link: int | None = None
    mechanism_certificate: str | None = None
    mechanism_listing: str | None = None
    mechanism_index: int | None = None
    mechanisms_listed: int | None = None
    inversion: list | None = None
    classes: list | None = None  # a heterogeneous chain's loop class of each link
    chain: Chain | None = field(default=None, repr=False, compare=False)

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The row, a chain row again (``identify`` reads its own output back): every field but the chain,
        the kinds, input link and classes where there are some, the mechanism's fields where there is a frame."""
        mechanism = {"frame", "frame_orbit", "listed_frame", "mechanism_certificate", "mechanism_listing",
                     "mechanism_index", "mechanisms_listed", "inversion"}
        optional = {"kinds", "input_link", "listed_input_link", "classes"}
        return tuple(f.name + "?" * (f.name in optional) for f in fields(self)
                     if f.name != "chain" and (self.frame is not None or f.name not in mechanism))


def _named(names, links):
    return [x if names is None else names[x] for x in links]


def listing_query(chain: Chain, dof: int, verdict, idle: bool):
    """The :class:`~synth.structure.query.ChainQuery` whose listing holds ``chain`` (mobility
    ``dof``, sub-chain ``verdict`` of the non-degenerate test, ``idle`` joints or not), and the
    command that prints it; or None and the reason no listing holds it.

    >>> q, command = listing_query(Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-1"), 1, None, False)
    >>> command
    'mechsynth chains --code 42/0'
    """
    from ..structure.query import ChainQuery

    if MESH in chain.kinds:
        return None, ("type synthesis lists revolute and prismatic chains, not gear meshes (gear trains are "
                      "listed by 'mechsynth gears')")
    if chain.classes is not None:
        return _class_listing(chain, dof, verdict)
    rigid = None
    # (redundant constraints: of a sub-chain, or of the whole chain, whose true W is above its count)
    if verdict is not None and (verdict.worst_mobility < 0 or verdict.redundant or dof != chain.dof):
        return None, "an over-constrained chain (a sub-chain with W(S) < 0, or redundant constraints) is in no listing"
    if verdict is not None and verdict.worst_mobility < 1:
        rigid = True if dof >= 1 else None
    code = str(chain.code)
    prismatic = chain.kinds.count(PRISMATIC) if not chain.all_revolute else None
    query = ChainQuery(dof, code=code, h=chain.h, rigid_subchains=rigid, prismatic=prismatic,
                       idle_joints=bool(idle and prismatic))
    words = ["mechsynth chains --code", code]
    if prismatic is not None:
        words += ["--dof", str(dof)]
    if chain.h != 3:
        words += ["--h", str(chain.h)]
    if rigid:
        words.append("--rigid-subchains")
    if prismatic is not None:
        words += ["--prismatic", str(prismatic)]
        if idle:
            words.append("--idle-joints")
    return query, " ".join(words)


@dataclass(frozen=True)
class _ClassQuery:
    """The listing of heterogeneous chains that holds a chain: ``chains --dof W --loop-classes … --code C``."""

    dof: int
    loop_classes: tuple[tuple[int, int], ...]
    code: str
    rigid_subchains: bool | None


def _class_listing(chain: Chain, dof: int, verdict):
    """:func:`listing_query` of a heterogeneous chain: two classes, the base's above the others'."""
    classes = chain.loop_classes
    if len(classes) != 2 or min(classes) != chain.h or min(classes.values()) < 1:
        return None, ("heterogeneous chains are listed with two loop classes, a base of the higher class on a chain "
                      "of the lower one")
    rigid = None
    if verdict is not None and verdict.worst_mobility < 1:
        if verdict.worst_mobility < 0:
            return None, "an over-constrained chain (a sub-chain with W(S) < 0) is in no listing"
        rigid = True if dof >= 1 else None
    code = str(chain.code)
    words = ["mechsynth chains --dof", str(dof), "--loop-classes", ",".join(f"{x}={k}" for x, k in classes.items()),
             "--code", code] + (["--rigid-subchains"] if rigid else [])
    return _ClassQuery(dof, tuple(classes.items()), code, rigid), " ".join(words)


@lru_cache(maxsize=32)
def _chain_rows(query) -> dict[bytes, int]:
    """Row (1-based) of every chain of a listing, by the SHA-1 digest of its certificate (20 bytes a
    chain, where a certificate takes hundreds)."""
    if isinstance(query, _ClassQuery):
        from ..synthesis.classes import heterogeneous_synthesis

        chains = heterogeneous_synthesis(query.dof, dict(query.loop_classes), code=query.code,
                                         rigid_subchains=query.rigid_subchains, workers=1)
    else:
        from ..synthesis.type_synthesis import type_synthesis

        chains = type_synthesis(query, workers=1)
    return {_digest(c.certificate): i for i, c in enumerate(chains, start=1)}


def _digest(certificate: str) -> bytes:
    return hashlib.sha1(certificate.encode()).digest()


def index_size(chain: Chain, query, mechanisms: bool = False):
    """The size of the listing that finds a chain's row, before it runs: an
    :class:`~synth.synthesis.estimate.Estimate` of listing every chain of its link count with the
    same conventions (``query`` is its code's listing query, from :func:`listing_query`), an upper
    bound of its code's listing (with ``mechanisms``, of their mechanisms); None where no estimate
    can be made (fewer than three smaller sizes with chains: a small query, unless it has many loops).

    >>> from synth.structure.chain import Chain
    >>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    >>> index_size(watt, listing_query(watt, 1, None, False)[0]) is None   # 6 links: 2 and 4 below
    True
    """
    from dataclasses import replace

    from ..errors import SynthesisError
    from ..synthesis.estimate import estimate

    n1 = chain.code.n1
    try:
        whole = replace(query, code=None, v=(chain.v, chain.v), n1=(n1, n1))
        return estimate(whole, work="mechanisms" if mechanisms else "list")
    except SynthesisError:
        return None


@lru_cache(maxsize=32)
def _mechanism_rows(query, input_link: bool) -> dict[bytes, int]:
    """Row (1-based) of every mechanism of ``mechanisms`` with the same query (``--input-link``:
    with every input link), by the digest of its certificate."""
    from ..synthesis.type_synthesis import mechanisms

    return {_digest(m.certificate): i for i, m in enumerate(mechanisms(query, input_link=input_link, workers=1),
                                                           start=1)}


def _place(chain: Chain, mechanism, dof: int, verdict, idle: bool, index: bool | None) -> dict:
    """The listing, row and row count of a chain (and of its mechanism), or the reason there is none."""
    out = dict(listing=None, index=None, listed=None, note="")
    query, said = listing_query(chain, dof, verdict, idle)
    if query is None:
        out["note"] = said
        return out
    out["listing"] = said
    if index is False:
        out["note"] = "its place in the listing was not asked for"
        return out
    if index is None and isinstance(query, _ClassQuery) and chain.loops > _INDEXED_CLASS_LOOPS - (1 if chain.v else 0):
        out["note"] = (f"its place in the listing was not computed: the code has {chain.loops} loops and its "
                       "heterogeneous listing is built whole to find it (ask for its index to have it computed)")
        return out
    if index is None and not isinstance(query, _ClassQuery):
        from ..execution.sizes import describe_seconds, magnitude
        from ..synthesis.estimate import sized_loops

        size = index_size(chain, query, mechanisms=mechanism is not None)
        if size is None and chain.loops >= sized_loops(chain.h, multiple=chain.v > 0):
            out["note"] = (f"its place in the listing was not computed: the code has {chain.loops} loops and its "
                           "listing cannot be sized (ask for its index to have it computed)")
            return out
        if size is not None and size.seconds > INDEX_SECONDS:
            items = "mechanisms" if mechanism is not None else "chains"
            took = describe_seconds(size.seconds, size.log10_seconds)
            out["note"] = (f"its place in the listing was not computed: it is found by listing the code, and listing "
                           f"every {chain.links}-link chain like it is about {magnitude(size.chains, size.log10_chains)} "
                           f"{items}, {took} on one core ({size.basis}); ask for its index to have it computed")
            return out
    rows = _chain_rows(query)
    out.update(index=rows.get(_digest(chain.certificate)), listed=len(rows))
    if out["index"] is None:  # the conventions say it is there: a chain the engine misses
        out["note"] = "not found in its listing: the engine misses this chain (please report it)"
    if mechanism is not None and (mechanism.input_link is None or chain.dof != 0):  # a truss's input: in no listing
        moved = mechanism.input_link is not None
        mechs = _mechanism_rows(query, moved)
        listing = said.replace("mechsynth chains", "mechsynth mechanisms", 1) + (" --input-link" if moved else "")
        out.update(mechanism_listing=listing, mechanism_index=mechs.get(_digest(mechanism.certificate)),
                   mechanisms_listed=len(mechs))
    return out


def _listed_mechanism(listed: Chain, mechanism: Mechanism) -> Mechanism:
    """The mechanism as listings and atlases number it: the row of ``mechanisms`` (and of an atlas)
    on the canonically numbered chain ``listed`` that is the same mechanism.

    >>> _listed_mechanism(Chain.parse("0-1 0-2 0-4 1-3 1-5 2-3 4-5").canonical(),
    ...                   Mechanism(Chain.parse("0-1 0-2 0-4 1-3 1-5 2-3 4-5"), 0)).frame   # Watt II: a ternary fixed
    4
    """
    from ..synthesis.type_synthesis import mechanisms_of

    if mechanism.input_link is not None and listed.dof == 0:  # a truss has no input link in a listing
        found = (Mechanism(listed, f, x) for j in listed.joints for f in j for x in j if x != f)
        return next(m for m in found if m.certificate == mechanism.certificate)
    return next(m for m in mechanisms_of(listed, input_link=mechanism.input_link is not None)
                if m.certificate == mechanism.certificate)


def identify_entry(entry, *, index: bool | None = None) -> Identity:
    """Identify one chain as read by :mod:`synth.exchange` (an entry: the chain, its frame and input
    link, the names its source gave its links, where it came from); :func:`synth.identify` reads
    any source and calls this for each chain."""
    from ..structure.kinds import idle_joints
    from ..structure.subchains import check_subchains
    from .chains import mobility_of
    from .classical import chain_names, inversion_names

    chain, names = entry.chain, entry.names
    loose = [x for x, d in enumerate(chain.degrees) if d == 0]
    if loose:  # (a Chain made in Python; a reader refuses it first)
        raise MalformedChain(f"{entry.source}: link {_named(names, loose)[0]} is in no joint: a chain's links are all "
                             "jointed")
    connected = chain.is_connected()
    dof = mobility_of(chain) if connected else chain.dof
    verdict = own = None
    if connected:
        verdict = check_subchains(chain, rigid_subchains=False)
        own = verdict if dof >= 1 else check_subchains(chain, rigid_subchains=True)
    idle = [list(j) for j in idle_joints(chain)] if connected else []
    gens, order, orbits = chain.automorphisms()
    groups: dict[int, list[int]] = {}
    for link, o in enumerate(orbits):
        groups.setdefault(o, []).append(link)
    fractionated = chain.is_fractionated() if connected else None
    planar = chain.is_planar()
    conventions = {
        "non_degenerate": bool(verdict and verdict.ok),
        "rigid_subchains": bool(verdict and verdict.worst_mobility >= 0 and not verdict.redundant),
        "not_fractionated": fractionated is False,
        "planar": planar,
        "no_idle_joint": connected and not idle,
    }
    if not connected:
        place = dict(listing=None, index=None, listed=None, note="a chain in pieces is in no listing")
    else:
        place = _place(chain, entry.item if entry.frame is not None else None, dof, verdict, bool(idle), index)
    worst = list(own.worst) if own is not None else []
    listed = chain.canonical()  # the numbering of every listing and atlas
    mechanism = {}
    if entry.frame is not None:
        frame = entry.frame
        orbit = [x for x in range(chain.links) if orbits[x] == orbits[frame]]
        moved = entry.input_link
        same = _listed_mechanism(listed, entry.item)
        mechanism = dict(frame=_named(names, [frame])[0], frame_orbit=_named(names, orbit),
                         input_link=None if moved is None else _named(names, [moved])[0],
                         listed_frame=same.frame, listed_input_link=same.input_link,
                         mechanism_certificate=entry.item.certificate, inversion=inversion_names(chain, frame))
        mechanism.update({k: place.pop(k) for k in ("mechanism_listing", "mechanism_index", "mechanisms_listed")
                          if k in place})
    return Identity(
        source=entry.source, links=chain.links, joints=[list(j) for j in chain.joints],
        kinds=None if chain.all_revolute else list(chain.kinds), h=chain.h, names=list(names) if names else None,
        id=chain_id(chain.certificate), certificate=chain.certificate, listed_joints=listed.compact(),
        code=str(chain.code) + chain.kind_suffix + chain.class_suffix,
        dof=dof, dof_count=chain.dof, loops=chain.loops, v=chain.v, connected=connected,
        subchains=own.kind if own is not None else "not connected", worst_subchain=_named(names, worst),
        worst_mobility=own.worst_mobility if own is not None and own.worst else None,
        fractionated=fractionated, planar=planar,
        idle_joints=[_named(names, j) for j in idle], conventions=conventions, symmetry=round(order),
        link_orbits=[_named(names, g) for g in sorted(groups.values())], classical=chain_names(chain),
        **place, **mechanism, classes=list(chain.classes) if chain.classes else None, chain=chain)
