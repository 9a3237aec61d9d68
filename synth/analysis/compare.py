"""Compare an atlas from elsewhere with the engine's enumeration of the same query.

Published atlases disagree because of how they generate chains, test isomorphism and treat
fractionated or degenerate chains.  :func:`compare` settles such a dispute chain by chain: the
given chains are matched with the engine's by certificate, and every difference is named:

* **duplicate**: given chains that are the same chain (isomorphic), with where each was given;
* **missing**: a chain of the engine's listing that the atlas does not hold, with its row;
* **extra**: a given chain the engine does not list, with the reason — not connected, other
  link count or motion space, wrong mobility, a rigid or over-constrained sub-chain (its
  links), redundant constraints, fractionated, non-planar, multiple joints, prismatic pairs or
  idle joints outside the query — or, when it meets every convention of the query, a chain
  the engine misses.

Example
-------
>>> from synth.structure.query import ChainQuery
>>> from synth.exchange import read_text
>>> given = read_text("0-1 1-2 2-3 3-0 0-4 4-5 5-1\\n5-4 4-3 3-2 2-5 5-0 0-1 1-4\\n0-1 1-2 2-0 0-3 3-4 4-5 5-1\\n")
>>> r = compare(given, ChainQuery(1, 6))
>>> r.matched, [(f.kind, f.reason) for f in r.findings]
(1, [('duplicate', 'the same chain (isomorphic) given 2 times'), ('missing', 'row 1 of the engine, not in the atlas'), ('extra', 'a rigid sub-chain: links 0, 1, 2 with W(S) = 0')])
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mechbase import Row

from ..structure.chain import Chain
from ..structure.joints import MESH, PRISMATIC
from .identify import chain_id

__all__ = ["Finding", "Comparison", "compare", "why_extra"]


@dataclass(frozen=True)
class Finding(Row):
    """One difference: ``kind`` duplicate, missing or extra; the chain's ``id`` and joint list;
    ``given`` where it was given (sources, empty for a missing chain); ``row`` in the engine's
    listing (missing chains); ``reason`` in words; ``links`` the links it concerns (the rigid or
    over-constrained sub-chain of an extra chain, named as its source names them)."""

    kind: str
    id: str
    joints: str
    given: list
    reason: str
    row: int | None = None
    links: list = field(default_factory=list)


@dataclass(frozen=True)
class Comparison(Row):
    """The outcome of :func:`compare`: counts and the findings (duplicates, missing, extra)."""

    query: dict
    listing: str
    given: int
    distinct: int
    engine: int
    matched: int
    findings: list
    missing: int = 0

    @property
    def agree(self) -> bool:
        """Whether the atlas holds exactly the engine's chains, each once."""
        return not self.findings

    def count(self, kind: str) -> int:
        """How many findings of a kind (missing chains: all of them, listed or not)."""
        return self.missing if kind == "missing" else sum(1 for f in self.findings if f.kind == kind)

    @property
    def duplicates(self) -> int:
        return self.count("duplicate")

    @property
    def extra(self) -> int:
        return self.count("extra")

    row_keys = ("query", "listing", "given", "distinct", "engine", "matched", "findings", "missing", "agree",
                "duplicates", "extra")


def _named(entry, links) -> list:
    return [entry.name(x) for x in links]


def _range_text(rng) -> str:
    lo, hi = rng
    return f"{lo}" if lo == hi else f"{lo}..{'' if hi is None else hi}"


def _outside(value: int, rng) -> bool:
    lo, hi = rng
    return value < lo or (hi is not None and value > hi)


def why_extra(entry, query) -> tuple[str, list]:
    """Why the engine does not list a given chain for ``query``: a sentence, and the links it
    concerns (named as the source names them).

    >>> from synth.structure.query import ChainQuery
    >>> from synth.exchange import read_text
    >>> why_extra(read_text("0-1 1-2 2-3 3-0 4-5 5-6 6-7 7-4")[0], ChainQuery(1, 8))[0]
    'not connected: links 0, 1, 2, 3 and 4, 5, 6, 7 are separate pieces'
    """
    from ..structure.kinds import idle_joints
    from ..structure.subchains import check_subchains
    from .chains import mobility_of

    chain: Chain = entry.chain
    if not chain.is_connected():
        import networkx as nx

        pieces = sorted(sorted(c) for c in nx.connected_components(chain.link_graph()))
        shown = " and ".join(", ".join(map(str, _named(entry, p))) for p in pieces[:3])
        return f"not connected: links {shown} are separate pieces", []
    if chain.links != query.links:
        return f"{chain.links} links, not {query.links}", []
    if chain.h != query.h:
        return f"loops in motion space h = {chain.h}, not {query.h}", []
    if MESH in chain.kinds:
        return "gear meshes: type synthesis lists revolute and prismatic chains", []
    dof = mobility_of(chain)
    if dof != query.dof:
        extra = f" (the count gives {chain.dof}: redundant constraints)" if dof != chain.dof else ""
        return f"wrong mobility: W = {dof}, not {query.dof}{extra}", []
    report = check_subchains(chain, rigid_subchains=query.rigid)
    if not report.ok:
        links = _named(entry, report.worst)
        if report.kind == "redundant constraints":
            return f"redundant constraints: its pairs constrain each other beyond the count ({report.redundant})", links
        kind = "a rigid sub-chain" if report.worst_mobility == 0 else "an over-constrained sub-chain"
        return f"{kind}: links {', '.join(map(str, links))} with W(S) = {report.worst_mobility}", links
    prismatic = chain.kinds.count(PRISMATIC)
    if query.prismatic is None and prismatic:
        return f"{prismatic} prismatic pair(s): the query lists revolute chains (it asks for no prismatic pair)", []
    if query.prismatic is not None and _outside(prismatic, query.prismatic):
        return f"{prismatic} prismatic pair(s), outside the query's {_range_text(query.prismatic)}", []
    code = chain.code
    if query.code is not None and (code.assortment, code.v, code.n1) != (query.code.assortment, query.code.v,
                                                                            query.code.n1):
        return f"code {code}, not {query.code}", []
    if query.code is not None and query.code.composition is not None and code.composition != query.code.composition:
        return f"joint composition of code {code}, not {query.code}", []
    v = query.v or ((query.code.v, query.code.v) if query.code else (0, 0))
    if _outside(chain.v, v):
        return f"v = {chain.v} (multiple joints), outside the query's v = {_range_text(v)}", []
    n1 = query.n1 or ((query.code.n1, query.code.n1) if query.code else (0, 0))
    if _outside(code.n1, n1):
        return f"{code.n1} single-joint link(s), outside the query's n1 = {_range_text(n1)}", []
    for i, rng in query.require:
        if _outside(code.count(i), rng):
            return f"{code.count(i)} link(s) with {i} joints, outside the requirement n{i} = {_range_text(rng)}", []
    if query.max_multiplicity is not None and max(len(j) for j in chain.joints) > query.max_multiplicity:
        return (f"a joint of {max(len(j) for j in chain.joints)} links, beyond the query's largest multiplicity "
                f"{query.max_multiplicity}", [])
    if not query.fractionated and chain.is_fractionated():
        return "fractionated: one link or joint splits it (the query drops fractionated chains)", []
    if query.planar_only and not chain.is_planar():
        return "non-planar (the query keeps planar chains only)", []
    if prismatic and not query.idle_joints:
        idle = idle_joints(chain)
        if idle:
            joints = ", ".join("-".join(map(str, _named(entry, j))) for j in idle)
            return f"idle joint(s) {joints}: they never move (the query drops such chains)", []
    return ("it meets every convention of the query, yet the engine does not list it: a chain the engine misses "
            "(please report it)"), []


def _in_space(entry, h: int):
    """The entry in motion space ``h`` where its source states none (and its joint kinds allow it)."""
    from dataclasses import replace

    if entry.h is not None or entry.chain.h == h or not entry.chain.all_revolute:
        return entry
    return replace(entry, chain=replace(entry.chain, h=h))


def compare(entries, query, *, workers: int | None = 1, progress: bool = False,
            max_missing: int = 1000) -> Comparison:
    """Compare the given chains (:class:`~synth.exchange.Entry` objects) with the engine's listing
    of ``query`` (a :class:`~synth.structure.query.ChainQuery`), see the module docstring.

    A chain whose source states no motion space (``entry.h`` None: a joint list, a foreign
    graph or matrix) is taken in the query's; one that states another is another design there,
    an extra chain.  Findings come in the order duplicates, missing (by engine row), extra (in
    the order given).  The engine's listing streams by (memory holds the given chains); the
    first ``max_missing`` missing chains are listed one by one, the others counted in one last
    finding.
    """
    from ..synthesis.type_synthesis import type_synthesis

    groups: dict[str, list] = {}
    for entry in map(lambda e: _in_space(e, query.h), entries):
        groups.setdefault(entry.chain.certificate, []).append(entry)
    findings = []
    for cert, group in groups.items():
        if len(group) > 1:
            findings.append(Finding("duplicate", chain_id(cert), group[0].chain.compact(), [e.source for e in group],
                                    f"the same chain (isomorphic) given {len(group)} times"))
    # the engine's chains stream by: memory holds the given chains, not the listing
    matched, rows, missing = set(), 0, 0
    for rows, chain in enumerate(type_synthesis(query, workers=workers, progress=progress), start=1):
        if chain.certificate in groups:
            matched.add(chain.certificate)
            continue
        missing += 1
        if missing <= max_missing:
            findings.append(Finding("missing", chain_id(chain.certificate), chain.compact(), [],
                                    f"row {rows} of the engine, not in the atlas", row=rows))
    if missing > max_missing:
        findings.append(Finding("missing", "", "", [], f"and {missing - max_missing} more chains of the engine, "
                                                       "not in the atlas (not listed one by one)"))
    for cert, group in groups.items():
        if cert not in matched:
            reason, links = why_extra(group[0], query)
            findings.append(Finding("extra", chain_id(cert), group[0].chain.compact(), [e.source for e in group],
                                    reason, links=links))
    shown = {**query.to_dict(), **({} if query.fractionated else {"fractionated": False})}
    return Comparison(shown, listing_command(query), sum(len(g) for g in groups.values()), len(groups),
                      rows, len(matched), findings, missing)


def listing_command(query) -> str:
    """The ``mechsynth chains`` command that lists a query.

    >>> from synth.structure.query import ChainQuery
    >>> listing_command(ChainQuery(1, 10, v="0..2", fractionated=False))
    'mechsynth chains --dof 1 --links 10 --v 0..2 --no-fractionated'
    """
    words = ["mechsynth chains", f"--dof {query.dof}"]
    words.append(f"--code {query.code}" if query.code is not None else f"--links {query.links}")
    for name in ("v", "n1", "prismatic"):
        if getattr(query, name) is not None:
            words.append(f"--{name} {_range_text(getattr(query, name))}")
    if query.h != 3:
        words.append(f"--h {query.h}")
    words += [f"--require {i}={_range_text(r)}" for i, r in query.require]
    words += [f"--cranks {i}={c}" for i, c in query.cranks]
    if query.max_multiplicity is not None:
        words.append(f"--max-multiplicity {query.max_multiplicity}")
    for name, flag in (("rigid_subchains", "--rigid-subchains"), ("planar_only", "--planar-only"),
                       ("idle_joints", "--idle-joints")):
        if getattr(query, name):
            words.append(flag)
    if not query.fractionated:
        words.append("--no-fractionated")
    return " ".join(words)
