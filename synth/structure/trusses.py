"""A chain fixed by a link: a mechanism (W ≥ 1), a truss (W = 0), or a chain given by hand whose count
misleads, and the words for each.

Fixed by a link, a chain of W = 0 by the count is a truss — a statically determinate structure, nothing
moves — only when no sub-chain is over-constrained and its links do not move (true mobility 0); a chain
of W ≥ 1 by the count is a mechanism of that W only when no sub-chain is over-constrained and the links
move with that W, and a non-degenerate one when no sub-chain is rigid either (W(S) ≥ 1: a rigid
sub-chain acts as one link).  A braced four-bar (W(S) = −1) joined to a five-bar loop counts W = 0, yet
moves with one degree of freedom: it is no truss.  Every chain type synthesis lists passes the exact
sub-chain test, so its count is true; :func:`count_defect` checks a chain given by hand (a sub-chain scan
and one rank, about a millisecond at 9 links).

Example
-------
>>> from synth.structure.chain import Chain
>>> count_defect(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4")) is None      # 32/0: a truss
True
>>> print(count_defect(Chain.parse("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-2")))  # braced four-bar and five-bar loop
a sub-chain is over-constrained (W(S) = -1) and the links move with W = 1
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..errors import ImpossibleParameters, InvalidOption
from .kinds import mobility_of
from .subchains import check_subchains

if TYPE_CHECKING:
    from .chain import Chain

__all__ = ["TRUSS_NOTE", "CountDefect", "count_defect", "mechanisms_summary", "on_a_frame", "not_a_mechanisms_chain",
           "truss_has_no_input"]

#: what a listing of mechanisms adds after its count of trusses on a frame
TRUSS_NOTE = "W = 0: statically determinate, nothing moves"


@dataclass(frozen=True)
class CountDefect:
    """Why a chain's W by the count (``dof``) is not what it is fixed by a link: ``kind`` as
    :attr:`~synth.structure.subchains.SubchainReport.kind` ('none' where only the true mobility ``moves``
    differs), its words as ``str()``."""

    dof: int
    moves: int
    kind: str
    worst_mobility: int

    @property
    def degenerate_only(self) -> bool:
        """A rigid sub-chain in a chain of W ≥ 1 that moves as counted: a mechanism of that W, one link in
        effect where the sub-chain is."""
        return self.kind == "rigid sub-chain" and self.moves == self.dof

    @property
    def what(self) -> str:
        """What such chains on a frame are, after their number: 'chains on a frame, not trusses', 'chains on
        a frame, not mechanisms of W = 1' or 'degenerate mechanisms'."""
        if self.degenerate_only:
            return "degenerate mechanisms"
        return "chains on a frame, not " + ("trusses" if self.dof == 0 else f"mechanisms of W = {self.dof}")

    @property
    def caption(self) -> str:
        """A drawing's word for it: 'not a truss', 'not W = 1' or 'degenerate'."""
        return "degenerate" if self.degenerate_only else "not a truss" if self.dof == 0 else f"not W = {self.dof}"

    def __str__(self) -> str:
        why = []
        if self.kind == "over-constrained sub-chain":
            why.append(f"a sub-chain is over-constrained (W(S) = {self.worst_mobility})")
        elif self.kind == "rigid sub-chain":
            why.append("a sub-chain is rigid (W(S) = 0), one link in effect")
        elif self.kind == "redundant constraints":
            why.append("its pairs carry redundant constraints the count does not see")
        if self.moves != self.dof:
            why.append(f"the links move with W = {self.moves}" if self.moves else "nothing moves (true W = 0)")
        return " and ".join(why)


def count_defect(chain: Chain) -> CountDefect | None:
    """Why ``chain`` (W ≥ 0 by the count), fixed by a link, is not a truss (W = 0) or a non-degenerate
    mechanism of its W (W ≥ 1); None when it is: every sub-chain S has W(S) ≥ 0 (a truss) or W(S) ≥ 1 (a
    mechanism), no pair carries a redundant constraint and the true mobility is the count.  A chain of W < 0
    is a structure by its count alone: None.

    >>> from synth.structure.chain import Chain
    >>> count_defect(Chain.parse("0-1 1-2 2-0")), count_defect(Chain.parse("0-1 1-2 2-3 3-0"))
    (None, None)
    >>> print(count_defect(Chain.parse("0-1 1-2 2-0 2-3 3-4 4-5 5-0")))   # a four-bar whose frame is a triangle
    a sub-chain is rigid (W(S) = 0), one link in effect
    """
    if chain.dof < 0:
        return None
    report = check_subchains(chain, rigid_subchains=chain.dof == 0)
    moving = mobility_of(chain)
    if report.ok and moving == chain.dof:
        return None
    return CountDefect(chain.dof, moving, report.kind, report.worst_mobility)


def on_a_frame(items: int, trusses: int, *, defect: CountDefect | None = None) -> str:
    """What ``items`` chains fixed by a link are, ``trusses`` of them of W = 0: mechanisms (W ≥ 1) and
    trusses on a frame (W = 0, statically determinate); with ``defect`` (:func:`count_defect`) what they are
    where their count misleads.

    >>> on_a_frame(2, 0), on_a_frame(1, 1), on_a_frame(4, 2)
    ('2 mechanisms', '1 truss on a frame', '2 mechanisms and 2 trusses on a frame')
    >>> on_a_frame(4, 4, defect=CountDefect(0, 1, "over-constrained sub-chain", -1))
    '4 chains on a frame, not trusses'
    """
    if defect is not None:
        return f"{items} {defect.what}"
    moving = items - trusses
    named = [f"{moving} mechanism{'s' * (moving != 1)}"] if moving or not trusses else []
    if trusses:
        named.append(f"{trusses} truss{'es' * (trusses != 1)} on a frame")
    return " and ".join(named)


def mechanisms_summary(items: int, trusses: int, *, defect: CountDefect | None = None) -> str:
    """The line under a listing of ``items`` mechanisms, ``trusses`` of them of W = 0 (:func:`on_a_frame`, and
    what a truss is); with ``defect`` (:func:`count_defect` of the one chain given) why its count misleads.

    >>> mechanisms_summary(4, 2)
    '2 mechanisms and 2 trusses on a frame (W = 0: statically determinate, nothing moves)'
    >>> print(mechanisms_summary(2, 0, defect=CountDefect(1, 2, "over-constrained sub-chain", -1)))
    2 chains on a frame, not mechanisms of W = 1: W = 1 by the count, but a sub-chain is over-constrained (W(S) = -1) and the links move with W = 2 ('mechsynth analyze' says where)
    """
    if defect is None:
        return on_a_frame(items, trusses) + (f" ({TRUSS_NOTE})" if trusses else "")
    count = "" if defect.degenerate_only else " by the count"
    return (f"{on_a_frame(items, trusses, defect=defect)}: W = {defect.dof}{count}, but {defect} "
            "('mechsynth analyze' says where)")


def not_a_mechanisms_chain(chain: Chain, dof: int) -> ImpossibleParameters:
    """The refusal of the mechanisms of ``chain`` given by hand, W = ``dof`` < 0 by the count (it, or the least
    of its variants): a structure, over-constrained; a link is fixed in a chain of W ≥ 0 only.

    >>> from synth.structure.chain import Chain
    >>> print(not_a_mechanisms_chain(Chain.parse("0-1 1-2 2-3 3-0 1-3"), -1))
    the chain 0-1 0-3 1-2 1-3 2-3 is a structure, not a mechanism's chain: W = -1 by the count (over-constrained): a mechanism fixes a link of a chain with W ≥ 1, a truss on a frame one of W = 0 ('mechsynth analyze' says why and how to mend it)
    """
    return ImpossibleParameters(f"the chain {chain.compact()} is a structure, not a mechanism's chain: W = {dof} by "
                                "the count (over-constrained): a mechanism fixes a link of a chain with W ≥ 1, a truss "
                                "on a frame one of W = 0 ('mechsynth analyze' says why and how to mend it)")


def truss_has_no_input(subject: str, option: str = "input_link", defect: CountDefect | None = None) -> InvalidOption:
    """The refusal of an input link (asked by ``option``) for chains of W = 0 by the count, ``subject``
    named (e.g. 'these chains have'); with ``defect`` (:func:`count_defect`) for one whose count misleads,
    whatever its W: the input links are chosen by the count, which is wrong there.

    >>> print(truss_has_no_input("these chains have", "--input-link"))
    these chains have W = 0 by the count: on a frame a truss is a statically determinate structure, it does not move, so --input-link has no link to drive (list them without it)
    >>> print(truss_has_no_input("the chain has", defect=CountDefect(0, 1, "none", 1)))
    the chain has W = 0 by the count, not a truss: the links move with W = 1; an input link is chosen by the count's W, so input_link would name links that cannot drive it (its analysis says how to mend the chain)
    """
    if defect is not None:
        what = (defect.caption if defect.dof == 0 or defect.degenerate_only
                else f"not a mechanism of W = {defect.dof}")
        return InvalidOption(f"{subject} W = {defect.dof} by the count, {what}: {defect}; an input link is chosen "
                             f"by the count's W, so {option} would name links that cannot drive it (its analysis "
                             "says how to mend the chain)")
    return InvalidOption(f"{subject} W = 0 by the count: on a frame a truss is a statically determinate structure, "
                         f"it does not move, so {option} has no link to drive (list them without it)")
