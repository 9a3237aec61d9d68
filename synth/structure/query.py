"""A chain query: what a designer asks type synthesis for, read and checked once.

Every command, grid cell, scene and API call builds one :class:`ChainQuery`; the engine derives
from it the loops, the codes, the conventions of each unit and the size of the work.  Ranges
are written ``N``, ``A..B`` or ``A..`` (open above) and read into ``(A, B)`` pairs, B None when
open.

Example
-------
>>> q = ChainQuery(1, 10, v="0..3", require=["5=1.."], cranks=["5=5"])
>>> q.v, q.require, q.cranks, q.loops
((0, 3), ((5, (1, None)),), ((5, 5),), 4)
>>> ChainQuery(1, 5, prismatic="1..6").skeleton_slacks()   # Task 3: one wedge loop on a truss; or three
[1, 3]
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, fields, replace

from mechbase import RangeSyntax, parse_range as split_range

from ..errors import ImpossibleParameters, InvalidOption, QueryTooLarge
from ._params import H_MAX
from .code import Code

__all__ = ["ChainQuery", "Range", "parse_range", "parse_requirements", "parse_cranks", "parse_cylinders",
           "CYLINDER_KINDS"]

Range = tuple[int, int | None]
MAX_CODE_LINKS = 1000  # a code's chains beyond this are beyond what certificates and drawings are used for
CYLINDER_KINDS = ("guide", "swinging", "floating", "slider")  # prismatic pairs of a mechanism, by where they sit


def parse_range(text: str | int | tuple | None, what: str, *, minimum: int = 0) -> Range | None:
    """Read ``N``, ``A..B`` or ``A..`` (open upper end) into ``(A, B)``; B is None when open.

    >>> parse_range("0..4", "v"), parse_range("2..", "n5"), parse_range(3, "K")
    ((0, 4), (2, None), (3, 3))
    """
    if text is None:
        return None
    if isinstance(text, (tuple, list)) and len(text) == 2:
        lo, hi = text
    else:
        try:
            lo, hi = split_range(text, open_low=True)
        except RangeSyntax:
            raise InvalidOption(f"{what} must be a whole number or a range A..B, not {text!r}") from None
        lo = minimum if lo is None else lo
    if any(isinstance(x, bool) or not isinstance(x, (int, type(None))) for x in (lo, hi)):
        raise InvalidOption(f"{what} must be a whole number or a range A..B, not {text!r}")
    if lo is None or lo < minimum or (hi is not None and hi < minimum):
        raise ImpossibleParameters(f"{what} must not be below {minimum} (got {text!r})")
    if hi is not None and hi < lo:
        raise InvalidOption(f"the range for {what} is empty: {lo}..{hi}")
    return (lo, hi)


def _split_pair(text, what: str, example: str) -> tuple[str, str]:
    if not isinstance(text, str) or "=" not in text:
        raise InvalidOption(f"{what} is written {example}, not {text!r}")
    key, value = text.split("=", 1)
    return key.strip(), value.strip()


def parse_requirements(items: Iterable[str] | Mapping | None) -> dict[int, Range]:
    """Read design requirements ``I=N``, ``I=A..B``, ``I=A..`` on n_I (links with I joints).

    >>> parse_requirements(["5=1..", "3=0..2"])
    {3: (0, 2), 5: (1, None)}
    """
    if not items:
        return {}
    if isinstance(items, (tuple, list)) and all(isinstance(x, tuple) and len(x) == 2 for x in items):
        items = dict(items)
    pairs = items.items() if isinstance(items, Mapping) else (
        _split_pair(s, "a requirement", "I=N, I=A..B or I=A.. (e.g. 5=1..)") for s in items)
    out: dict[int, Range] = {}
    for key, value in pairs:
        try:
            i = int(key)
        except (TypeError, ValueError):
            raise InvalidOption(f"a requirement names the number of joints on a link, not {key!r}") from None
        if i < 1:
            raise ImpossibleParameters(f"a link carries at least one joint; requirement on n{i} is impossible")
        rng = parse_range(value, f"n{i}")
        if i in out and out[i] != rng:
            raise ImpossibleParameters(f"conflicting requirements on n{i}: {out[i]} and {rng}")
        out[i] = rng
    return dict(sorted(out.items()))


def parse_cranks(cranks: Mapping | Iterable[str] | None) -> tuple[tuple[int, int], ...]:
    """``{5: 5}`` or ``["5=5"]``: a link with 5 joints carrying at least 5 cranks.

    >>> parse_cranks(["5=5", "3=1"])
    ((3, 1), (5, 5))
    """
    if not cranks:
        return ()
    pairs = cranks.items() if isinstance(cranks, Mapping) else (
        c if isinstance(c, tuple) else str(c).split("=", 1) for c in cranks)
    out = []
    for pair in pairs:
        try:
            i, c = (int(x) for x in pair)
        except (TypeError, ValueError):
            text = "=".join(map(str, pair))
            raise InvalidOption(f"cranks are written I=C (a link with I joints carrying C cranks), not {text!r}") from None
        if i < 1 or c < 1 or c > i:
            raise ImpossibleParameters(f"a link with {i} joints cannot carry {c} cranks")
        out.append((i, c))
    return tuple(sorted(out))


def parse_cylinders(items: Mapping | Iterable[str] | str | None) -> tuple[tuple[str, Range], ...]:
    """Required prismatic pairs of a mechanism by kind: ``floating=1,swinging=2`` (a cylinder
    whose two links both move; one pinned to the frame), ``guide=0`` (a slider on the frame).

    >>> parse_cylinders("floating=1, swinging=2..")
    (('swinging', (2, None)), ('floating', (1, 1)))
    """
    if not items:
        return ()
    if isinstance(items, str):
        items = [s for s in items.split(",") if s.strip()]
    if isinstance(items, (tuple, list)) and all(isinstance(x, tuple) and len(x) == 2 for x in items):
        items = dict(items)
    pairs = items.items() if isinstance(items, Mapping) else (
        _split_pair(s, "a cylinder requirement", "KIND=N or KIND=A..B with KIND guide, swinging or floating")
        for s in items)
    out = {}
    for kind, value in pairs:
        if kind not in CYLINDER_KINDS:
            raise InvalidOption(f"a prismatic pair of a mechanism is a guide, swinging, floating or slider, not {kind!r}")
        out[kind] = parse_range(value, f"{kind} cylinders")
    return tuple((k, out[k]) for k in CYLINDER_KINDS if k in out)


def _whole(value, name: str, least: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise InvalidOption(f"{name} must be a whole number, not {value!r}")
    if value < least:
        raise ImpossibleParameters(f"{name} must be {least} or more, not {value}")
    return value


@dataclass(frozen=True)
class ChainQuery:
    """Which chains (or mechanisms) a designer asks for, validated and normalised.

    Parameters
    ----------
    dof : int
        W, the mobility of every chain returned (0 for trusses); with prismatic pairs too.
    links : int, optional
        n, the frame included (or give ``code``).
    code : Code or str, optional
        Only this code (with or without composition); its revolute skeleton with ``prismatic``.
    v, n1 : N or range
        Multiple-joint count and single-joint links (default 0, or the code's own).
    h : int
        Motion space of the loops, 2 … 6 (prismatic pairs: 3 only).
    require : strings ``"I=N"`` / mapping
        Bounds on n_I, the links with I joints.
    cranks : strings ``"I=C"`` / mapping
        A link with I joints carrying at least C cranks.
    max_multiplicity : int, optional
        Most links on one joint (default the limit theorem where it holds).
    rigid_subchains : bool, optional
        Allow rigid sub-chains (default: for W = 0 only).
    fractionated, planar_only : bool
        Keep chains that one link or joint splits (default yes); only planar graphs.
    prismatic : N or range, optional
        Every assignment of that many prismatic pairs to simple joints, up to symmetry (None:
        revolute chains only).  Wedge loops (K_2) raise the mobility: the chains come from
        revolute skeletons of mobility W − K_2.
    idle_joints : bool
        With ``prismatic``: keep chains with joints that never move.
    cylinders : ``"floating=1,swinging=2"`` / mapping
        With ``prismatic``, for mechanisms: the prismatic pairs by kind (guide on the frame,
        swinging cylinder pinned to the frame, floating cylinder).

    Examples
    --------
    >>> ChainQuery(1, 8).loops, ChainQuery(1, code="7201/1").links
    (3, 10)
    >>> ChainQuery(1, 9).loops
    Traceback (most recent call last):
    ...
    synth.errors.ImpossibleParameters: no whole number of loops fits: n = W + 1 + (h − 1)·K needs n − W − 1 = 7 to be a non-negative multiple of h − 1 = 2 (W=1, n=9, h=3)
    """

    dof: int
    links: int | None = None
    code: Code | None = None
    v: Range | None = None
    n1: Range | None = None
    h: int = 3
    require: tuple = ()
    cranks: tuple = ()
    max_multiplicity: int | None = None
    rigid_subchains: bool | None = None
    fractionated: bool = True
    planar_only: bool = False
    prismatic: Range | None = None
    idle_joints: bool = False
    cylinders: tuple = ()

    def __post_init__(self):
        put = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731 - frozen dataclass
        _whole(self.dof, "the degree of freedom W", 0)
        if not isinstance(self.h, int) or isinstance(self.h, bool) or not 2 <= self.h <= H_MAX:
            raise ImpossibleParameters(f"the motion space h of a loop is 2 … {H_MAX} "
                                       f"({H_MAX}: general spatial loop), not {self.h!r}")
        code = Code.parse(self.code) if isinstance(self.code, str) else self.code
        if code is not None and not isinstance(code, Code):
            raise InvalidOption(f"a code is a Code or its text, e.g. '6301/0', not {code!r}")
        if code is not None and code.links > MAX_CODE_LINKS:
            raise QueryTooLarge(f"the code given has {code.links} links; chains are built here up to "
                                f"{MAX_CODE_LINKS} links")
        put("code", code)
        if self.links is None and code is None:
            raise InvalidOption("give the number of links (or a code)")
        if self.links is not None:
            _whole(self.links, "the number of links", 1)
        put("links", code.links if self.links is None else self.links)
        if code is not None and code.links != self.links:
            raise ImpossibleParameters(f"code {code} has {code.links} links, not {self.links}")
        put("v", parse_range(self.v, "v"))
        put("n1", parse_range(self.n1, "n1"))
        put("require", tuple(parse_requirements(self.require).items()))
        put("cranks", parse_cranks(self.cranks))
        put("cylinders", parse_cylinders(self.cylinders))
        put("prismatic", parse_range(self.prismatic, "the number of prismatic pairs"))
        for name in ("fractionated", "planar_only", "idle_joints"):
            if not isinstance(getattr(self, name), bool):
                raise InvalidOption(f"{name} is true or false, not {getattr(self, name)!r}")
        if self.rigid_subchains is not None and not isinstance(self.rigid_subchains, bool):
            raise InvalidOption(f"rigid_subchains is true, false or None, not {self.rigid_subchains!r}")
        if self.max_multiplicity is not None:
            _whole(self.max_multiplicity, "the largest multiplicity (links on one joint)", 2)
        if self.prismatic is not None and self.h != 3:
            raise InvalidOption(f"prismatic pairs are assigned in planar chains (h = 3), not in motion space h = {self.h}")
        if self.idle_joints and self.prismatic is None:
            raise InvalidOption("idle joints go with prismatic pairs (an all-revolute chain has no idle joint)")
        if self.cylinders and self.prismatic is None:
            raise InvalidOption("cylinders go with prismatic pairs: give the number of prismatic pairs too")
        if code is not None:
            self._check_code(code)
        elif self.prismatic is None:
            _ = self.loops  # refuses a number of links no whole number of loops fits
        if self.prismatic is not None:
            self._check_prismatic(code)

    def _check_prismatic(self, code: Code | None) -> None:
        """Refuse more prismatic pairs than the chains have simple joints."""
        lo = self.prismatic[0]
        if code is not None:
            simple = code.joints - sum(code.composition or ())
            if code.composition is None and code.v:
                simple = code.joints - 1  # at least one multiple joint
            if lo > simple:
                raise ImpossibleParameters(f"code {code} has {simple} simple joint(s) and prismatic pairs go on simple "
                                           f"joints: {lo} do not fit" if simple else f"code {code} has no simple joint: "
                                           "prismatic pairs go on simple joints (a multiple joint is a pin)")
            return
        slacks = self.skeleton_slacks()
        if not slacks and self.dof > self.links - 1:
            raise ImpossibleParameters(f"no chain of {self.links} links has W = {self.dof}: an open chain of n links "
                                       f"moves with W = n − 1 = {self.links - 1}, and every loop, wedge loops of "
                                       "prismatic pairs included, takes mobility away")
        most = max((self.links - 1 - self.dof + k) // 2 + self.links - 1 for k in slacks or [0])
        if lo > most:
            raise ImpossibleParameters(f"{lo} prismatic pairs do not fit: a chain with W = {self.dof} and "
                                       f"{self.links} links has at most {most} joints")

    def _check_code(self, code: Code) -> None:
        """Refuse a code that contradicts the other options of the same query."""
        W = code.dof(self.h)
        if self.prismatic is None and W != self.dof:
            raise ImpossibleParameters(f"code {code} gives W = {W} with h = {self.h}, not the requested W = {self.dof}")
        if self.prismatic is not None and not 0 <= self.dof - W <= code.loops:
            raise ImpossibleParameters(f"code {code} gives W = {W} with revolute pairs; its wedge loops can raise "
                                       f"that to at most {W + code.loops}, not to the requested W = {self.dof}")
        if self.v is not None and not self.v[0] <= code.v <= (code.v if self.v[1] is None else self.v[1]):
            raise ImpossibleParameters(f"code {code} has v = {code.v}, outside the requested v = {_shown(self.v)}")
        if self.n1 is not None and not self.n1[0] <= code.n1 <= (code.n1 if self.n1[1] is None else self.n1[1]):
            raise ImpossibleParameters(f"code {code} has n1 = {code.n1}, not the requested n1 = {_shown(self.n1)}")
        for i, (lo, hi) in self.require:
            if not lo <= code.count(i) <= (code.count(i) if hi is None else hi):
                raise ImpossibleParameters(f"code {code} has {code.count(i)} link(s) with {i} joints, but the "
                                           f"requirement asks for n{i} = {_shown((lo, hi))}")

    @classmethod
    def of(cls, query=None, links=None, **options) -> "ChainQuery":
        """A query from the arguments of the API functions (``type_synthesis(1, 8, v="0..2")``,
        ``dof=1, links=8``), or the query itself; W defaults to the code's own.

        >>> ChainQuery.of(code="7201/1").dof, ChainQuery.of(dof=1, links=8) == ChainQuery(1, 8)
        (1, True)
        >>> ChainQuery.of(1, loops=4, h=5).links                  # n = W + 1 + (h − 1)·K
        18
        """
        if isinstance(query, ChainQuery):
            if links is not None or options:
                raise InvalidOption("give a query or its options, not both")
            return query
        dof = options.pop("dof", None) if query is None else query
        if "dof" in options:
            raise InvalidOption("W is given twice (as the first argument and as dof)")
        loops = options.pop("loops", None)
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(options) - known)
        if unknown:
            raise InvalidOption(f"unknown option(s) for a chain query: {', '.join(unknown)}")
        if dof is None:
            code = options.get("code")
            if code is None:
                raise InvalidOption("give the degree of freedom W (and the links), or a code")
            text = code.strip() if isinstance(code, str) else str(code)
            code = Code.parse(code) if isinstance(code, str) else code
            if code.links > MAX_CODE_LINKS:
                raise QueryTooLarge(f"code {text} has {code.links} links; chains are built here up to "
                                    f"{MAX_CODE_LINKS} links")
            dof = code.dof(options.get("h", 3))
            if dof < 0:
                raise ImpossibleParameters(f"code {text} gives W = {dof} in motion space h = {options.get('h', 3)}: its "
                                           "links are over-constrained, and a chain has W ≥ 0")
        if loops is not None:  # n = W + 1 + (h − 1)·K
            if links is not None:
                raise InvalidOption("give the links or the loops, not both")
            _whole(loops, "the number of loops K", 0)
            links = _whole(dof, "the degree of freedom W", 0) + 1 + (options.get("h", 3) - 1) * loops
        return cls(dof, links, **options)

    # ------------------------------------------------------------------ derived
    @property
    def loops(self) -> int:
        """K of the revolute chains asked for: n = W + 1 + (h − 1)·K."""
        extra = self.links - self.dof - 1
        if extra < 0 or extra % (self.h - 1):
            raise ImpossibleParameters(
                f"no whole number of loops fits: n = W + 1 + (h − 1)·K needs n − W − 1 = {extra} to be a "
                f"non-negative multiple of h − 1 = {self.h - 1} (W={self.dof}, n={self.links}, h={self.h})")
        return extra // (self.h - 1)

    @property
    def rigid(self) -> bool:
        """Whether rigid sub-chains are allowed (default: for trusses, W = 0)."""
        return self.dof == 0 if self.rigid_subchains is None else self.rigid_subchains

    def skeleton_slacks(self) -> list[int]:
        """The numbers K_2 of wedge loops the chains can have: 0 for revolute chains; with
        prismatic pairs every k whose revolute skeleton (mobility W − k, K = (n − 1 − W + k)/2
        loops) exists and has room for k independent loops of at least three sliders each.

        >>> ChainQuery(1, 6, prismatic="0..").skeleton_slacks(), ChainQuery(1, 7, prismatic=(0, 4)).skeleton_slacks()
        ([0, 2, 4], [1])
        """
        if self.prismatic is None:
            return [0]
        most = self.prismatic[1]
        out = []
        for k in range(0, self.links + 1):
            extra = self.links - 1 - self.dof + k
            if extra < 0 or extra % 2:
                continue
            K = extra // 2
            if k > K or (most is not None and k and most < k + 2):
                continue
            if self.code is not None and (self.code.loops != K or self.code.dof(3) != self.dof - k):
                continue
            out.append(k)
        return out

    @property
    def cylinders_only(self) -> bool:
        """Whether the cylinders asked for are every prismatic pair a chain can have (then each
        joins two binary links: the engine need not try the others).

        >>> ChainQuery(3, code="8310/1", prismatic=3, cylinders="floating=1,swinging=2").cylinders_only
        True
        """
        wanted = sum(lo for kind, (lo, _) in self.cylinders if kind in ("swinging", "floating"))
        return self.prismatic is not None and self.prismatic[1] is not None and wanted >= self.prismatic[1] > 0

    def to_dict(self) -> dict:
        """The query as plain values (ranges as ``"A..B"``), for logs and checkpoints.

        >>> ChainQuery(1, 8, v="0..2").to_dict()
        {'dof': 1, 'links': 8, 'v': '0..2'}
        """
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "code" and value is not None:
                value = str(value)
            if value in (None, ()) or value == f.default:
                continue  # (a default; but fractionated=False and rigid_subchains=False are choices)
            if f.name in ("v", "n1", "prismatic"):
                value = _shown(value)
            elif f.name in ("require", "cylinders"):
                value = [f"{k}={_shown(r)}" for k, r in value]
            elif f.name == "cranks":
                value = [f"{i}={c}" for i, c in value]
            out[f.name] = value
        if self.code is not None:
            out.pop("links", None)
        return out

    def with_options(self, **changes) -> "ChainQuery":
        """The same query with some options changed (validated again)."""
        return replace(self, **changes)


def _shown(rng: Range) -> str:
    lo, hi = rng
    return f"{lo}" if lo == hi else f"{lo}..{'' if hi is None else hi}"
