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
from ..structure.chain import JOINT_KINDS, Chain, Mechanism, check_as_written
from ..structure.joints import JointKind

__all__ = ["Entry", "entry_of", "kind_of", "is_kind_word", "check_distinct", "motion_space_of", "in_motion_space", "settings_of"]

@dataclass(frozen=True)
class Entry:
    """A chain (and, for a mechanism, its frame) as read from ``source``.

    ``names`` are the source's names of links 0 … n − 1 (None when the source numbered them
    0 … n − 1 itself), so that a report can speak of the links as the source does.  ``h`` is the
    motion space the source states (a row's ``h``, a graph attribute, a ``# h H`` line), None
    where it states none: the chain is then read in the plane (h = 3) and
    :func:`in_motion_space` may put it in another space.  ``input_link`` is a mechanism's input.
    """

    chain: Chain
    frame: int | None = None
    names: tuple[str, ...] | None = None
    source: str = ""
    h: int | None = None
    input_link: int | None = None

    @property
    def item(self) -> Chain | Mechanism:
        """The chain, or the mechanism when the source fixed a frame (with its input link)."""
        return self.chain if self.frame is None else Mechanism(self.chain, self.frame, self.input_link)

    def name(self, link: int) -> int | str:
        """The source's name of a link (its number where the source numbered the links 0 … n − 1)."""
        return link if self.names is None else self.names[link]


def is_kind_word(word: str) -> bool:
    """Whether a word names a joint kind (see :func:`kind_of`).

    >>> is_kind_word("P"), is_kind_word("crank")
    (True, False)
    """
    return JointKind.read(word) is not None


def kind_of(value, where: str) -> JointKind:
    """A joint kind from the words other tools use: revolute/R/pin/-, prismatic/P/slider/=, mesh/gear/G/~.

    >>> kind_of("P", "x"), kind_of("gear", "x")
    ('prismatic', 'mesh')
    """
    kind = JointKind.read(value)
    if kind is None:
        raise MalformedChain(f"{where}: joint kind {str(value)!r} is not one of {', '.join(JOINT_KINDS)} "
                             f"(or {', '.join(k.letter for k in JointKind)}; {', '.join(JointKind.symbols())})")
    return kind


def motion_space_of(value, where: str) -> int:
    """The motion space h a source states (a number or its text), checked: 2 … 6.

    >>> motion_space_of("4", "x"), motion_space_of(5, "x")
    (4, 5)
    >>> motion_space_of("planar", "x")
    Traceback (most recent call last):
    ...
    synth.errors.MalformedChain: x: the motion space h is a whole number 2 … 6 (3 planar and spherical), not 'planar'
    """
    text = str(value).strip()
    if isinstance(value, bool) or not re.fullmatch(r"\d+(\.0*)?", text) or not 2 <= int(float(text)) <= 6:
        raise MalformedChain(f"{where}: the motion space h is a whole number 2 … 6 (3 planar and spherical), "
                             f"not {value!r}")
    return int(float(text))


def in_motion_space(entry: Entry, h: int | None, given: str = "--h") -> Entry:
    """The entry with its chain in motion space ``h`` (None: as read).  A source that states
    another h contradicts ``given`` and is refused: its chain is another design there.

    >>> e = entry_of([(0, 1), (1, 2), (2, 0)], None, "x")
    >>> in_motion_space(e, 5).chain.h, in_motion_space(e, None).chain.h
    (5, 3)
    >>> in_motion_space(entry_of([(0, 1), (1, 2), (2, 0)], None, "y", h=4), 5)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    synth.errors.MalformedChain: y states motion space h = 4, and --h 5 was given: ... or give --h 4
    """
    from dataclasses import replace

    if h is None or h == entry.chain.h and entry.h in (None, h):
        return entry
    if entry.h is not None and entry.h != h:
        raise MalformedChain(f"{entry.source} states motion space h = {entry.h}, and {given} {h} was given: leave out "
                             f"{given} (the chain's own h is used) or give {given} {entry.h}")
    if entry.chain.classes is not None:
        raise MalformedChain(f"{entry.source} names its loop classes (its other links are of class {entry.chain.h}): "
                             f"{given} {h} contradicts them")
    try:
        chain = Chain(entry.chain.links, entry.chain.joints, entry.chain.kinds, h)
    except MalformedChain as exc:
        raise MalformedChain(f"{entry.source}: {exc}") from None
    return replace(entry, chain=chain, h=h)


_SETTING = re.compile(r"(frame|input|h)(?![A-Za-z_])\s*[:=]?\s*([^\s,;]+)", re.IGNORECASE)


def settings_of(comment: str) -> dict | None:
    """The settings of a comment that holds nothing else: ``frame F``, ``input I``, ``h H``
    (separated by spaces, commas or semicolons), or None for any other comment.

    >>> settings_of("# frame 2, h 4"), settings_of("# h=5"), settings_of("# a slider-crank"), settings_of("# hello")
    ({'frame': '2', 'h': '4'}, {'h': '5'}, None, None)
    """
    body = comment.strip().lstrip("#").strip()
    found = {}
    at = 0
    while at < len(body):
        m = _SETTING.match(body, at)
        if m is None or m.group(1).lower() in found:
            return None
        found[m.group(1).lower()] = m.group(2)
        at = m.end()
        while at < len(body) and body[at] in " \t,;":
            at += 1
    return found or None


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
             links: Sequence | None = None, h=None, input_link=None) -> Entry:
    """Build an :class:`Entry` from joints written with the source's link names.

    ``links`` lists every link name when the source lists them (a graph's nodes; a link in no
    joint is then refused); ``frame`` and ``input_link`` are link names or None; ``h`` the
    motion space the source states (a number or its text) or None.  Names that are the numbers
    0 … n − 1 keep their numbers.

    Raises
    ------
    MalformedChain
        One sentence naming ``source``: a link joined to itself, two joints on the same links,
        a link in no joint, an empty chain, an unknown frame or input link, a motion space
        outside 2 … 6.
    """
    stated = None if h is None else motion_space_of(h, source)
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
        check_as_written(None, numbered)
        chain = Chain(len(order), numbered, list(kinds) if kinds is not None else None, stated or 3)
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
    moved = None
    if input_link is not None:
        if at is None or str(input_link) not in number:
            raise MalformedChain(f"{source}: the input link {input_link} is not a link of the mechanism"
                                 + ("" if at is not None else " (an input link needs a frame)"))
        moved = number[str(input_link)]
        try:
            Mechanism(chain, at, moved)
        except MalformedChain as exc:
            raise MalformedChain(f"{source}: {exc}") from None
    return Entry(chain, at, names, source, stated, moved)


def _renamed(message: str, order: list) -> str:
    """A chain's sentence about links 0 … n − 1 said with the source's names, where they differ."""
    if [str(x) for x in order] == [str(i) for i in range(len(order))]:
        return message
    return message + f" (links numbered in the order {', '.join(map(str, order[:8]))}{', …' if len(order) > 8 else ''})"
