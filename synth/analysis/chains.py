"""Structural analysis of a given chain: W, K, code, whether the code is standard, defects.

Joint kinds count (docs/theory.md, "Joint kinds"): a prismatic pair removes two freedoms and
a loop of prismatic pairs only gives one back (K_2 wedge loops), a gear mesh removes one (its
lever analogue is a binary link).  ``dof`` is the generic mobility of a planar chain — the rank
of its velocity constraints at a random configuration — and ``dof_count`` the count; they differ
by the ``redundant`` constraints the count cannot see.

Example
-------
>>> a = analyze_chain("0-1 1-2 2-0 0-3 3-4 4-5 5-1")  # triangle 0-1-2 in a six-bar
>>> a.dof, a.code, a.subchain_defect, a.worst_subchain
(1, '42/0', 'rigid sub-chain', [0, 1, 2])
>>> a = analyze_chain("0=1 1=2 2=0 2-3 3-4 4-0")     # Task 3: a wedge and a lever
>>> a.dof, a.loops_2, a.loops_3, a.subchain_defect
(1, 1, 1, 'none')
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from mechbase import Row

from ..errors import ImpossibleParameters, InvalidOption, MalformedChain, QueryTooLarge
from ..structure.chain import Chain
from ..structure.joints import MESH, PRISMATIC
from ..structure.kinds import idle_joints, kind_count, lever_analogue, mobility_of, wedge_loops
from ..structure.query import MAX_CODE_LINKS
from ..structure.subchains import check_subchains
from ..synthesis.number_synthesis import number_synthesis
from .codes import LOWER_W, RAISE_W
from .repair import redundant_joints

__all__ = ["ChainAnalysis", "analyze_chain", "mobility_of"]


@dataclass(frozen=True)
class ChainAnalysis(Row):
    """What the theory says about one chain; ``advice`` tells how to remove a defect.

    ``dof`` is the true mobility (generic, for planar chains), ``dof_count`` the count and
    ``redundant`` their difference; ``loops_2``/``loops_3`` the wedge loops (prismatic pairs
    only) and the others; ``idle_joints`` the joints whose links never move relative to each
    other; ``lever_analogue`` the code of the chain with each gear mesh a binary link.  With a
    required W, ``defect`` is D = W by the count − the required W and, for a chain with gear
    meshes and D < 0, ``redundant_joints`` the joints whose removal mends it.
    """

    code: str
    certificate: str
    h: int
    links: int
    joints: int
    dof: int
    dof_count: int
    redundant: int
    loops: int
    loops_2: int
    loops_3: int
    complexity: int
    v: int
    prismatic: int
    meshes: int
    lever_analogue: str | None
    standard_code: bool
    connected: bool
    fractionated: bool
    planar: bool
    subchain_defect: str
    worst_subchain: list
    worst_subchain_mobility: int | None  # None: no proper sub-chain of two links or more
    idle_joints: list
    advice: str
    required_dof: int | None = None
    defect: int | None = None
    redundant_joints: list | None = None
    loop_classes: dict | None = None


def _standard(chain: Chain) -> bool:
    """Whether the code of the chain's revolute reading (meshes as binary links, prismatic pairs
    as pins, W without the wedge loops) is one of the standard codes."""
    base = lever_analogue(chain) if MESH in chain.kinds else chain
    W = base.dof - wedge_loops(base)
    code = base.code
    exact = {i: (code.count(i), code.count(i)) for i in range(2, code.max_degree + 1)}  # one code to find
    size = dict(loop_classes=chain.loop_classes) if chain.classes is not None else dict(loops=code.loops, h=chain.h)
    try:
        return W >= 0 and code.loops >= 0 and code in number_synthesis(
            W, v=code.v, n1=code.n1, max_link_degree=max(code.loops + 1, code.max_degree),
            compositions=True, max_multiplicity=max((len(j) for j in chain.joints), default=2),
            require=exact, **size)
    except ImpossibleParameters:
        return False


def _joint_text(chain: Chain, joints) -> str:
    index = {j: k for k, j in enumerate(chain.joints)}
    return ", ".join(Chain(chain.links, [j], [chain.kinds[index[j]]]).compact()
                     for j in joints)


def analyze_chain(chain: Chain | str, *, dof: int | None = None, h: int | None = None) -> ChainAnalysis:
    """Analyse a chain given as :class:`Chain`, JSON or compact joint list ``"0-1 1=2 2~3 …"``.

    ``dof`` is the intended W and sets the convention: W = 0 allows rigid sub-chains, otherwise
    none is allowed.  ``h`` is the motion space of the loops (default the chain's own, 3 for a
    joint list).

    >>> a = analyze_chain("0-1 1-2 2-3 3-4 4-5 5-0", h=5)  # the Bricard six-bar
    >>> a.dof, a.subchain_defect
    (1, 'none')
    >>> analyze_chain("0-1 1-2 2-3 3-0 0-4 4-5").code  # a four-bar carrying a two-link arm: one free end
    '1|41/0'
    >>> analyze_chain("0=1 1=2 2=3 3=0").dof              # the wedge loop of four sliders
    2
    >>> a = analyze_chain("0-1-6 1-2-7 2-3-8 3-4-9 4-5-10 5-0-11 6-12 8-12 10-12 7-13 9-13 11-13 | h5: 0 1 2 3 4 5")
    >>> a.dof, a.code, a.loop_classes, a.subchain_defect     # the linear translator (Fig. 12б)
    (1, '12.2.0.0.0/6 K3=4 K5=1', {'K3': 4, 'K5': 1}, 'none')
    """
    if isinstance(chain, str):
        chain = Chain.parse(chain)
    if chain.links > MAX_CODE_LINKS:  # its velocity constraints alone are a matrix of 6n² entries
        raise QueryTooLarge(f"the chain has {chain.links} links; chains are analysed here up to {MAX_CODE_LINKS} links "
                            "(the generic mobility's matrix grows with the square of the links)")
    loose = [link for link, degree in enumerate(chain.degrees) if degree == 0]
    if loose and chain.links > 1:
        shown = ", ".join(map(str, loose[:10])) + (", …" if len(loose) > 10 else "")
        verb = "are" if len(loose) > 1 else "is"
        raise MalformedChain(f"link{'s' * (len(loose) > 1)} {shown} of the {chain.links} {verb} in no joint: a chain's "
                             "links are all jointed")
    if h is not None and h != chain.h:
        if chain.classes is not None:
            raise InvalidOption(f"the chain names its loop classes after '|' (its other links are of class "
                                f"{chain.h}): h = {h} contradicts them")
        chain = replace(chain, h=h)
    report = check_subchains(chain, rigid_subchains=(dof if dof is not None else chain.dof) == 0)  # refuses pieces
    W = mobility_of(chain)
    idle = idle_joints(chain)
    k2 = wedge_loops(chain) if not chain.all_revolute else chain.loop_classes.get(2, 0)
    k3 = chain.loops - k2 if chain.classes is None else chain.loop_classes.get(3, 0)
    advice = []
    if dof is not None and dof != W:
        d = W - dof
        advice.append(f"the chain has W = {W}, not {dof}: "
                      + (LOWER_W.format(k=d) if d > 0 else RAISE_W.format(k=-d)))
    if report.kind == "redundant constraints":
        advice.append(f"its pairs carry {report.redundant} redundant constraint(s) the count does not see "
                      f"(W = {W}, the count {chain.dof}): turn a prismatic pair into a revolute one or add a link")
    elif W > chain.dof and report.ok:  # every proper sub-chain passes: the whole chain is over-constrained
        advice.append(f"the chain as a whole carries {W - chain.dof} redundant constraint(s): the count gives "
                      f"{chain.dof}, its links move with W = {W}; remove joints or add links (--repairs)")
    elif not report.ok:
        k = report.threshold - report.worst_mobility
        advice.append(
            f"links {list(report.worst)} form a {report.kind} with W(S) = {report.worst_mobility}: it acts as "
            f"one link; insert {k} binary link(s) into its joints (a–b becomes a–x–b) or move one of its joints "
            "to a link outside it")
    has_mesh = MESH in chain.kinds
    redundant = redundant_joints(chain, dof) if has_mesh and dof is not None and report.ok else None
    if redundant:
        advice.append(f"D = {chain.dof - dof}: joint(s) {_joint_text(chain, redundant)} carry the redundant "
                      f"constraint(s); removing {dof - chain.dof} of them leaves W = {dof} with no rigid sub-chain")
    if idle and report.ok and W > 0:  # (inside a rigid sub-chain every joint is idle: the sub-chain says why)
        why = ("prismatic pairs lock the rotation of their links; make one of those pairs revolute"
               if kind_count(chain, PRISMATIC) else "the rest of the chain holds their links together")
        advice.append(f"joint(s) {_joint_text(chain, idle)} never move: {why}")
    if chain.is_fractionated():
        advice.append("a link or joint splits the closed part of the chain: its mobility divides between the parts")
    return ChainAnalysis(
        code=str(chain.code) + chain.kind_suffix + chain.class_suffix, certificate=chain.certificate, h=chain.h, links=chain.links,
        joints=len(chain.joints), dof=W,
        dof_count=chain.dof, redundant=W - chain.dof, loops=chain.loops, loops_2=k2, loops_3=k3,
        complexity=chain.loops - 1, v=chain.v, prismatic=kind_count(chain, PRISMATIC),
        meshes=kind_count(chain, MESH), lever_analogue=str(lever_analogue(chain).code) if has_mesh else None,
        standard_code=_standard(chain), connected=True, fractionated=chain.is_fractionated(),
        planar=chain.is_planar(), subchain_defect=report.kind, worst_subchain=list(report.worst),
        worst_subchain_mobility=report.worst_mobility if report.worst else None,
        idle_joints=[list(j) for j in idle],
        advice="; ".join(advice) or "no defect: no rigid or over-constrained sub-chain, no idle joint",
        required_dof=dof, defect=None if dof is None else chain.dof - dof,
        redundant_joints=None if redundant is None else [list(j) for j in redundant],
        loop_classes=None if chain.classes is None else {f"K{x}": k for x, k in chain.loop_classes.items()},
    )
