"""Standard codes: the link assortment and the multiple-joint count of a chain.

A code is written ``n2 n3 … n_{K+1} / v`` (Pozhbelko): one digit per link kind,
from binary links (2 joints) up to links with K+1 joints, then the number v of
multiple-joint orders.  Where any count reaches 10 every count is separated by
dots (``12.2.0.0.0/6``).  The parser also reads Pozhbelko's forms ``12.2000/6``,
``12,000/6`` and ``12,000/4-1`` (the last gives the composition v2=4, v3=1).
Open chains carry links with a single joint; their count n1 is written in front,
separated by a bar: ``2|50/2`` is n1=2, n2=5, n3=0, v=2.

Example
-------
>>> c = Code.parse("6301/0")
>>> c.assortment, c.links, c.loops
((6, 3, 0, 1), 10, 4)
>>> str(Code.parse("12,000/4-1")), Code.parse("12,000/4-1").v
('12.0.0.0/4-1', 6)
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from functools import cached_property

from ..errors import MalformedCode

__all__ = ["Code", "MAX_LOOPS"]

MAX_LOOPS = 10_000  # the most loops a code is read or written with: it is written with one count per loop (n2 … n_{K+1})
_CODE_RE = re.compile(r"^\s*(?:(\d+)\|)?([0-9.,]+)\s*/\s*([0-9]+(?:-[0-9]+)*)\s*$")


#: What a listing writes after a code, and the option that asks for it.
_SUFFIXES = {"K": "--loop-classes H=K,H=K", "P": "--prismatic N", "G": "mechsynth gears"}


def _unreadable(text: str) -> str:
    """The sentence for a text that is no code; a code copied from a listing with what the listing writes
    beside it (``62/0 K3=1 K5=1``, ``4/0 P1``, ``221/0 G3``) is told which option asks for that.

    >>> _unreadable("4/0 P1")
    "cannot read code '4/0 P1': the code is '4/0'; 'P1' is written beside it by a listing (asked with --prismatic N)"
    """
    head, *rest = text.split() or [""]
    if rest and _CODE_RE.match(head) and all(re.fullmatch(r"K\d+=\d+|[PG]\d+", word) for word in rest):
        asked = " and ".join(dict.fromkeys(_SUFFIXES[word[0]] for word in rest))
        return (f"cannot read code {text!r}: the code is {head!r}; {' '.join(rest)!r} is written beside it by a "
                f"listing (asked with {asked})")
    return f"cannot read code {text!r}: expected digits n2n3…/v such as '6301/0', '12.2.0.0.0/6' or '12,000/4-1'"


def _strip(counts) -> tuple[int, ...]:
    counts = [int(c) for c in counts]
    while counts and counts[-1] == 0:
        counts.pop()
    return tuple(counts)


@dataclass(frozen=True, order=True)
class Code:
    """Link assortment (n2, n3, …), v and, when known, its composition (v2, v3, …).

    Parameters
    ----------
    assortment : tuple of int
        ``(n2, n3, n4, …)``: number of links carrying 2, 3, 4, … joints.
        Trailing zeros are dropped on construction.
    v : int
        Multiple-joint count ``v = v2 + 2·v3 + 3·v4 + …``.
    composition : tuple of int or None
        ``(v2, v3, …)``: number of joints joining 3, 4, … links, or None when
        only v is fixed (a number-synthesis code).
    n1 : int
        Links with a single joint (free ends of open chains).

    Examples
    --------
    >>> Code((6, 3, 0, 1), 0).loops
    4
    >>> Code.parse("8310/1").dof()
    3
    """

    assortment: tuple[int, ...]
    v: int = 0
    composition: tuple[int, ...] | None = None
    n1: int = 0

    def __post_init__(self):
        object.__setattr__(self, "assortment", _strip(self.assortment))
        if self.composition is None and self.v in (0, 1):
            object.__setattr__(self, "composition", (self.v,)[: self.v])  # forced: none, or one double joint
        if self.composition is not None:
            comp = _strip(self.composition)
            object.__setattr__(self, "composition", comp)
            total = sum((k + 1) * vk for k, vk in enumerate(comp))
            if total != self.v:
                raise MalformedCode(
                    f"composition {'-'.join(map(str, comp))} gives v = {total}, not v = {self.v}"
                )
        if any(c < 0 for c in self.assortment) or self.v < 0 or self.n1 < 0 or (
            self.composition is not None and any(c < 0 for c in self.composition)
        ):
            raise MalformedCode("link counts and v must not be negative")
        if (sum(i * c for i, c in enumerate(self.assortment, start=2)) + self.n1 + self.v) % 2:
            raise MalformedCode(
                f"code {self.brief} is impossible: the joint incidences Σ i·n_i + v must be even"
            )

    # ------------------------------------------------------------------ counts
    @property
    def links(self) -> int:
        """n, the number of links (frame included)."""
        return self.n1 + sum(self.assortment)

    @property
    def simple_joint_equivalents(self) -> int:
        """p = Σ (m_j − 1) = (Σ i·n_i + v) / 2."""
        return (self.n1 + sum(i * c for i, c in enumerate(self.assortment, start=2)) + self.v) // 2

    @property
    def joints(self) -> int:
        """J, the number of physical joints: p − v."""
        return self.simple_joint_equivalents - self.v

    @property
    def loops(self) -> int:
        """K = p − n + 1, independent closed loops (does not depend on h)."""
        return self.simple_joint_equivalents - self.links + 1

    @property
    def max_degree(self) -> int:
        """Largest number of joints on one link (1 for a lone free link)."""
        return len(self.assortment) + 1 if self.assortment else (1 if self.n1 else 0)

    def count(self, i: int) -> int:
        """n_i, the number of links carrying i joints."""
        if i == 1:
            return self.n1
        return self.assortment[i - 2] if 2 <= i < len(self.assortment) + 2 else 0

    def dof(self, h: int = 3, f: int = 0) -> int:
        """Mobility W = (n − 1) − (h − 1)·K + f of a chain with this code."""
        return self.links - 1 - (h - 1) * self.loops + f

    # ---------------------------------------------------------------- notation
    def __str__(self) -> str:
        return self._text

    @property
    def brief(self) -> str:
        """The code as written, or for a code longer than 60 characters (thousands of loops, each a
        digit) its head, an ellipsis and the number of counts, as sentences about it quote it.

        >>> Code((0, 20000), 0).brief, Code.parse("6301/0").brief
        ('0.20000.0.0.0.0.0.0.0.0.0.0.0.0.0.0.0.0.0.0.0.0.…/0 (10001 counts n2, n3, …)', '6301/0')
        """
        text = self._text
        if len(text) <= 60:
            return text
        left, right = text.rsplit("/", 1)
        return f"{left[:48]}…/{right} ({max(self.loops, len(self.assortment), 1)} counts n2, n3, …)"

    @cached_property
    def _text(self) -> str:
        """The code as written, computed once (a count names each of its units by its code)."""
        width = max(self.loops, len(self.assortment), 1)
        counts = list(self.assortment) + [0] * (width - len(self.assortment))
        if any(c >= 10 for c in counts):
            if len(counts) == 1 or (len(counts) == 2 and counts[1] >= 10):
                counts.append(0)  # '11.0', '12.20.0': never read back as Pozhbelko's '12.2000' form
            left = ".".join(map(str, counts))
        else:
            left = "".join(map(str, counts))
        if self.n1:
            left = f"{self.n1}|{left}"
        if self.composition is not None and len(self.composition) > 1:
            right = "-".join(map(str, self.composition))
        else:
            right = str(self.v)
        return f"{left}/{right}"

    @classmethod
    def parse(cls, text: str) -> "Code":
        """Read a code in mechsynth's notation or in Pozhbelko's (docs/theory.md, standard codes).

        Raises
        ------
        MalformedCode
            With a sentence saying what is wrong.

        Examples
        --------
        >>> Code.parse("12.2000/6").assortment
        (12, 2)
        >>> Code.parse("4600/0") == Code((4, 6), 0)
        True
        """
        if not isinstance(text, str):
            raise MalformedCode(f"a code must be text such as '6301/0', not {text!r}")
        m = _CODE_RE.match(text)
        if not m:
            raise MalformedCode(_unreadable(text))
        n1_text, left, right = m.groups()
        parts = re.split(r"[.,]", left)
        if any(p == "" for p in parts):
            raise MalformedCode(f"cannot read code {text!r}: empty count between separators")
        if len(parts) == 1:
            counts = [int(ch) for ch in parts[0]]
        elif len(parts) == 2 and len(parts[1]) > 1:
            counts = [int(parts[0])] + [int(ch) for ch in parts[1]]  # Pozhbelko's form 12,000 / 12.2000
        else:
            counts = [int(p) for p in parts]
        numbers = [int(x) for x in right.split("-")]
        if len(numbers) == 1:
            v, composition = numbers[0], None
        else:
            composition = tuple(numbers)
            v = sum((k + 1) * vk for k, vk in enumerate(composition))
        code = cls(tuple(counts), v, composition, int(n1_text) if n1_text else 0)
        if code.loops > MAX_LOOPS:  # its written form alone (one count per loop) would fill memory
            written = text.strip()
            shown = written if len(written) <= 40 else f"{written[:20]}… ({len(written)} characters)"
            raise MalformedCode(f"code {shown} describes a chain of {code.loops} loops, more than the {MAX_LOOPS} "
                                "a code is read with")
        return code

    # --------------------------------------------------------------------- JSON
    def to_dict(self) -> dict:
        """JSON-able description (the `jsonl` object of `mechsynth codes`)."""
        d = {
            "code": str(self),
            "links": self.links,
            "loops": self.loops,
            "v": self.v,
            "assortment": list(self.assortment),
        }
        if self.composition is not None:
            d["composition"] = list(self.composition)
        if self.n1:
            d["n1"] = self.n1
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "Code":
        """Inverse of :meth:`to_dict` (extra keys are ignored)."""
        try:
            comp = d.get("composition")
            return cls(tuple(d["assortment"]), int(d["v"]), None if comp is None else tuple(comp), int(d.get("n1", 0)))
        except (KeyError, TypeError, ValueError) as exc:
            raise MalformedCode(f"not a code object: {exc}") from None

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_json(cls, text: str) -> "Code":
        try:
            return cls.from_dict(json.loads(text))
        except json.JSONDecodeError as exc:
            raise MalformedCode(f"code JSON is not valid JSON: {exc.msg}") from None
