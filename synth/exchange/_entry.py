"""One chain read from elsewhere: the chain, its frame, the names its source gave the links.

Every reader builds its chains here, from joints written with the source's own link names
(numbers or words), so that the checks and their sentences are the same for every format.

Example
-------
>>> e = entry_of([("base", "crank"), ("crank", "rod"), ("rod", "slider"), ("slider", "base")],
...              ["revolute", "revolute", "revolute", "prismatic"], "example", frame="base")
>>> e.chain.compact(), e.frame, e.names
('0-1 0=3 1-2 2-3', 0, ('base', 'crank', 'rod', 'slider'))
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

from ..errors import MalformedChain
from ..structure.chain import JOINT_KINDS, Chain, Mechanism, _check_as_written

__all__ = ["Entry", "entry_of", "kind_of", "check_distinct"]

_KIND_WORDS = {
    "revolute": "revolute", "r": "revolute", "-": "revolute", "pin": "revolute",
    "prismatic": "prismatic", "p": "prismatic", "=": "prismatic", "slider": "prismatic",
    "mesh": "mesh", "gear": "mesh", "g": "mesh", "~": "mesh",
}


@dataclass(frozen=True)
class Entry:
    """A chain (and, for a mechanism, its frame) as read from ``source``.

    ``names`` are the source's names of links 0 … n − 1 (None when the source numbered them
    0 … n − 1 itself), so that a report can speak of the links as the source does.
    """

    chain: Chain
    frame: int | None = None
    names: tuple[str, ...] | None = None
    source: str = ""

    @property
    def item(self) -> Chain | Mechanism:
        """The chain, or the mechanism when the source fixed a frame."""
        return self.chain if self.frame is None else Mechanism(self.chain, self.frame)

    def name(self, link: int) -> int | str:
        """The source's name of a link (its number where the source numbered the links 0 … n − 1)."""
        return link if self.names is None else self.names[link]


def kind_of(value, where: str) -> str:
    """A joint kind from the words other tools use: revolute/R/pin/-, prismatic/P/slider/=, mesh/gear/G/~.

    >>> kind_of("P", "x"), kind_of("gear", "x")
    ('prismatic', 'mesh')
    """
    kind = _KIND_WORDS.get(str(value).strip().lower())
    if kind is None:
        raise MalformedChain(f"{where}: joint kind {str(value)!r} is not one of {', '.join(JOINT_KINDS)} "
                             "(or R, P, G; -, =, ~)")
    return kind


def check_distinct(joints, source: str) -> None:
    """Refuse a joint that names a link twice, in the words a designer uses.

    >>> check_distinct([(0, 1), (1, 1)], "x")
    Traceback (most recent call last):
    ...
    synth.errors.MalformedChain: x: link 1 is joined to itself (joint 1-1): a joint joins different links
    """
    for j in joints:
        if len(set(map(str, j))) < len(j):
            twice = next(x for x in j if list(map(str, j)).count(str(x)) > 1)
            raise MalformedChain(f"{source}: link {twice} is joined to itself (joint {'-'.join(map(str, j))}): a "
                                 "joint joins different links")


def _order(names) -> list:
    """Link names in a stable order: by number where every name is a whole number, else as text."""
    names = list(names)
    if all(re.fullmatch(r"-?\d+", str(x)) for x in names):
        return sorted(names, key=lambda x: int(str(x)))
    return sorted(names, key=str)


def entry_of(joints: Sequence[Sequence], kinds: Sequence[str] | None, source: str, *, frame=None,
             links: Sequence | None = None) -> Entry:
    """Build an :class:`Entry` from joints written with the source's link names.

    ``links`` lists every link name when the source lists them (a graph's nodes; a link in no
    joint is then refused); ``frame`` is a link name or None.  Names that are the numbers
    0 … n − 1 keep their numbers.

    Raises
    ------
    MalformedChain
        One sentence naming ``source``: a link joined to itself, two joints on the same links,
        a link in no joint, an empty chain, an unknown frame.
    """
    joints = [tuple(j) for j in joints]
    if not joints:
        raise MalformedChain(f"{source}: no joint: an empty joint list is not a chain")
    check_distinct(joints, source)
    for j in joints:
        if len(j) < 2:
            raise MalformedChain(f"{source}: a joint on link {j[0]} alone joins nothing: a joint joins two links "
                                 "or more")
    named = {str(x): x for j in joints for x in j}
    if links is not None:
        loose = [x for x in links if str(x) not in named]
        if loose:
            shown = ", ".join(map(str, loose[:5])) + (", …" if len(loose) > 5 else "")
            raise MalformedChain(f"{source}: link{'s' * (len(loose) > 1)} {shown} {'are' if len(loose) > 1 else 'is'} "
                                 "in no joint: a chain's links are all jointed")
    order = _order(named.values())
    number = {str(x): i for i, x in enumerate(order)}
    numbered = [tuple(number[str(x)] for x in j) for j in joints]
    try:
        _check_as_written(None, numbered)
        chain = Chain(len(order), numbered, list(kinds) if kinds is not None else None)
    except MalformedChain as exc:
        raise MalformedChain(f"{source}: {_renamed(str(exc), order)}") from None
    names = tuple(str(x) for x in order)
    if names == tuple(str(i) for i in range(len(order))):
        names = None
    at = None
    if frame is not None:
        if str(frame) not in number:
            raise MalformedChain(f"{source}: the frame {frame} is not a link of the chain")
        at = number[str(frame)]
    return Entry(chain, at, names, source)


def _renamed(message: str, order: list) -> str:
    """A chain's sentence about links 0 … n − 1 said with the source's names, where they differ."""
    if [str(x) for x in order] == [str(i) for i in range(len(order))]:
        return message
    return message + f" (links numbered in the order {', '.join(map(str, order[:8]))}{', …' if len(order) > 8 else ''})"
