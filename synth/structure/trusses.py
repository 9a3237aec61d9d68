"""A chain of W = 0 fixed by a link: a truss, or a chain whose count misleads, and the words for both.

Fixed by a link, a chain of W = 0 by the count is a truss — a statically determinate structure,
nothing moves — only when no sub-chain is over-constrained and its links do not move (true mobility
0).  A braced four-bar (W(S) = −1) joined to a five-bar loop (W = 1) counts W = 0, yet moves with one
degree of freedom: it is no truss.  Every chain type synthesis lists passes the exact sub-chain test,
so its count is true; :func:`truss_defect` checks a chain given by hand (a sub-chain scan and one
rank, about a millisecond at 9 links).

Example
-------
>>> from synth.structure.chain import Chain
>>> truss_defect(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4")) is None      # 32/0: a truss
True
>>> truss_defect(Chain.parse("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-2"))  # braced four-bar and five-bar loop
'a sub-chain is over-constrained (W(S) = -1) and the links move with W = 1'
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..errors import InvalidOption
from .kinds import mobility_of
from .subchains import check_subchains

if TYPE_CHECKING:
    from .chain import Chain

__all__ = ["TRUSS_NOTE", "on_a_frame", "truss_defect", "truss_has_no_input"]

#: what a listing of mechanisms adds after its count of trusses on a frame
TRUSS_NOTE = "W = 0: statically determinate, nothing moves"


def truss_defect(chain: Chain) -> str | None:
    """Why ``chain``, fixed by a link, is no truss, in a few words; None when it is one (W = 0 by the
    count, no over-constrained sub-chain, no redundant constraint, true mobility 0).

    >>> from synth.structure.chain import Chain
    >>> truss_defect(Chain.parse("0-1 1-2 2-0")), truss_defect(Chain.parse("0-1 1-2 2-3 3-0"))
    (None, 'W = 1 by the count')
    """
    if chain.dof != 0:
        return f"W = {chain.dof} by the count"
    report = check_subchains(chain, rigid_subchains=True)  # W(S) ≥ 0 for every sub-chain S
    why = []
    if report.kind == "over-constrained sub-chain":
        why.append(f"a sub-chain is over-constrained (W(S) = {report.worst_mobility})")
    elif not report.ok:
        why.append("its pairs carry redundant constraints the count does not see")
    moving = mobility_of(chain)
    if moving:
        why.append(f"the links move with W = {moving}")
    return " and ".join(why) or None


def on_a_frame(items: int, trusses: int, *, not_trusses: bool = False) -> str:
    """What ``items`` chains fixed by a link are, ``trusses`` of them of W = 0: mechanisms (W ≥ 1) and
    trusses on a frame (W = 0, statically determinate); with ``not_trusses`` chains on a frame of one chain
    whose W = 0 is the count's only (:func:`truss_defect` says why).

    >>> on_a_frame(2, 0), on_a_frame(1, 1), on_a_frame(4, 2), on_a_frame(4, 4, not_trusses=True)
    ('2 mechanisms', '1 truss on a frame', '2 mechanisms and 2 trusses on a frame', '4 chains on a frame, not trusses')
    """
    if not_trusses:
        return f"{items} chain{'s' * (items != 1)} on a frame, not {'trusses' if items != 1 else 'a truss'}"
    moving = items - trusses
    named = [f"{moving} mechanism{'s' * (moving != 1)}"] if moving or not trusses else []
    if trusses:
        named.append(f"{trusses} truss{'es' * (trusses != 1)} on a frame")
    return " and ".join(named)


def truss_has_no_input(subject: str, option: str = "input_link", defect: str | None = None) -> InvalidOption:
    """The refusal of an input link (asked by ``option``) for chains of W = 0 by the count, ``subject``
    named (e.g. 'these chains have'); with ``defect`` (:func:`truss_defect`) for one that is no truss.

    >>> print(truss_has_no_input("these chains have", "--input-link"))
    these chains have W = 0 by the count: on a frame a truss is a statically determinate structure, it does not move, so --input-link has no link to drive (list them without it)
    >>> print(truss_has_no_input("the chain has", defect="the links move with W = 1"))
    the chain has W = 0 by the count, not a truss: the links move with W = 1; an input link is chosen by the count's W ≥ 1, so input_link has no link to drive (its analysis says how to mend the chain)
    """
    if defect is not None:
        return InvalidOption(f"{subject} W = 0 by the count, not a truss: {defect}; an input link is chosen by the "
                             f"count's W ≥ 1, so {option} has no link to drive (its analysis says how to mend the "
                             "chain)")
    return InvalidOption(f"{subject} W = 0 by the count: on a frame a truss is a statically determinate structure, "
                         f"it does not move, so {option} has no link to drive (list them without it)")
