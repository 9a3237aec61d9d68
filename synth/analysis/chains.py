"""Structural analysis of a given chain: W, K, code, whether the code is standard, defects.

Example
-------
>>> a = analyze_chain("0-1 1-2 2-0 0-3 3-4 4-5 5-1")  # triangle 0-1-2 in a six-bar
>>> a.dof, a.code, a.subchain_defect, a.worst_subchain
(1, '42/0', 'rigid sub-chain', [0, 1, 2])
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

from ..synthesis.number_synthesis import number_synthesis
from ..structure.chain import Chain
from ..errors import ImpossibleParameters, MalformedChain
from ..structure.subchains import check_subchains
from .codes import LOWER_W, RAISE_W

__all__ = ["ChainAnalysis", "analyze_chain"]


@dataclass(frozen=True)
class ChainAnalysis:
    """What the theory says about one chain; ``advice`` tells how to remove a defect."""

    code: str
    h: int
    links: int
    joints: int
    dof: int
    loops: int
    complexity: int
    v: int
    standard_code: bool
    connected: bool
    fractionated: bool
    planar: bool
    subchain_defect: str
    worst_subchain: list
    worst_subchain_mobility: int | None  # None: no proper sub-chain of two links or more
    advice: str

    def to_dict(self) -> dict:
        return asdict(self)


def analyze_chain(chain: Chain | str, *, dof: int | None = None, h: int | None = None) -> ChainAnalysis:
    """Analyse a chain given as :class:`Chain`, JSON or compact joint list ``"0-1 1-2 …"``.

    ``dof`` sets the convention: W = 0 allows rigid sub-chains, otherwise none is allowed.
    ``h`` is the motion space of the loops (default the chain's own, 3 for a joint list).

    >>> a = analyze_chain("0-1 1-2 2-3 3-4 4-5 5-0", h=5)  # the Bricard six-bar
    >>> a.dof, a.subchain_defect
    (1, 'none')
    >>> analyze_chain("0-1 1-2 2-3 3-0 0-4 4-5").code  # a four-bar carrying a two-link arm: one free end
    '1|41/0'
    """
    if isinstance(chain, str):
        chain = Chain.parse(chain)
    loose = [link for link, degree in enumerate(chain.degrees) if degree == 0]
    if loose and chain.links > 1:
        shown = ", ".join(map(str, loose[:10])) + (", …" if len(loose) > 10 else "")
        verb = "are" if len(loose) > 1 else "is"
        raise MalformedChain(f"link{'s' * (len(loose) > 1)} {shown} of the {chain.links} {verb} in no joint: a chain's "
                             "links are all jointed")
    if h is not None and h != chain.h:
        chain = replace(chain, h=h)
    W = chain.dof
    rigid_ok = (dof if dof is not None else W) == 0
    report = check_subchains(chain, rigid_subchains=rigid_ok)  # refuses a chain in pieces
    code = chain.code
    try:
        exact = {i: (code.count(i), code.count(i)) for i in range(2, code.max_degree + 1)}  # one code to find
        standard = code in number_synthesis(
            W, loops=code.loops, v=code.v, n1=code.n1, max_link_degree=max(code.loops + 1, code.max_degree),
            compositions=True, h=chain.h, max_multiplicity=max((len(j) for j in chain.joints), default=2),
            require=exact,
        ) if W >= 0 and code.loops >= 0 else False
    except ImpossibleParameters:
        standard = False
    advice = []
    if dof is not None and dof != W:
        d = W - dof
        advice.append(f"the chain has W = {W}, not {dof}: "
                      + (LOWER_W.format(k=d) if d > 0 else RAISE_W.format(k=-d)))
    if not report.ok:
        k = report.threshold - report.worst_mobility
        advice.append(
            f"links {list(report.worst)} form a {report.kind} with W(S) = {report.worst_mobility}: it acts as "
            f"one link; insert {k} binary link(s) into its joints (a–b becomes a–x–b) or move one of its joints "
            "to a link outside it")
    if chain.is_fractionated():
        advice.append("a link or joint splits the closed part of the chain: its mobility divides between the parts")
    return ChainAnalysis(
        code=str(code), h=chain.h, links=chain.links, joints=len(chain.joints), dof=W, loops=chain.loops,
        complexity=chain.loops - 1, v=chain.v, standard_code=standard, connected=True,
        fractionated=chain.is_fractionated(), planar=chain.is_planar(), subchain_defect=report.kind,
        worst_subchain=list(report.worst), worst_subchain_mobility=report.worst_mobility if report.worst else None,
        advice="; ".join(advice) or "no defect: no rigid or over-constrained sub-chain",
    )
