"""Gear trains: links, axes (coaxial groups) and meshes with their carriers.

A gear train has links ``0 … n−1`` (the frame is one of them; a compound gear is one link),
*axes* — each the set of links that turn about one axis, a multiple revolute joint — and
*meshes*, each a pair of gears (a, b) held at its centre distance by a *carrier* t: the link that
both gears turn on (a turns on t about one axis, b about another).  Planetary-train atlases use
trains whose axes join the links as a tree; :class:`GearTrain` takes any layout (a floating sun
meshes with planets and turns on no axis of its own), with the carrier of a mesh given, or found
as the middle link of the tree path a – X – t – Y – b.

Its mobility counts each mesh as a higher pair with two freedoms (f = 1):
F = 3(n − 1) − 2·Σ (|X| − 1) − g.  Its *lever analogue* replaces each mesh by a binary link
with two simple revolute joints — the same mobility, loops and sub-chain mobilities — so the
engine's exact sub-chain test on that chain decides whether a set of links is rigid.

Example
-------
>>> simple = GearTrain.parse("0-1-2 2-3 1~3 0~3")  # frame/ring 0, sun 1, carrier 2, planet 3
>>> simple.dof, simple.carriers, str(simple.lever_analogue().code)
(1, (2, 2), '51/1')
>>> simple.is_rigid_free()
True
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cached_property

import pynauty

from ..structure.chain import Chain
from ..structure.joints import MESH, PRISMATIC, REVOLUTE
from ..errors import MalformedChain
from ..structure.kinds import lever_analogue
from ..structure.subchains import check_subchains

__all__ = ["GearTrain", "axis_paths", "rotation_graph", "fractionated"]


def axis_paths(links: int, axes) -> dict[int, dict[int, list]]:
    """Breadth-first paths from each link through the link–axis graph: ``{start: {link: path}}``,
    a path alternating links and axis indexes (a mesh's path a, X, t, Y, b has its carrier third).

    >>> axis_paths(4, [(0, 1, 2), (2, 3)])[0][3]
    [0, 0, 2, 1, 3]
    """
    by_link = [[] for _ in range(links)]
    for k, axis in enumerate(axes):
        for x in axis:
            by_link[x].append(k)
    out = {}
    for start in range(links):
        paths = {start: [start]}
        frontier = [start]
        while frontier:
            nxt = []
            for x in frontier:
                for k in by_link[x]:
                    for y in axes[k]:
                        if y not in paths:
                            paths[y] = paths[x] + [k, y]
                            nxt.append(y)
            frontier = nxt
        out[start] = paths
    return out


def rotation_graph(links: int, triples) -> pynauty.Graph:
    """nauty graph of a rotation graph: the links, a node per mesh joined to its gears and a node
    per carrier role joined to that mesh node and to the carrier, three colours.  Its certificate
    is the same for two sets of triples (a, b, t) exactly when a renumbering of the links maps
    one onto the other.

    >>> g = rotation_graph(4, [(0, 3, 2), (1, 3, 2)]); g.number_of_vertices
    8
    """
    mesh0, role0 = links, links + len(triples)
    adjacency: dict[int, list[int]] = {}
    for k, (a, b, t) in enumerate(triples):
        adjacency[mesh0 + k] = [a, b, role0 + k]
        adjacency[role0 + k] = [t]
    cells = [set(range(links)), set(range(mesh0, role0)), set(range(role0, role0 + len(triples)))]
    return pynauty.Graph(role0 + len(triples), adjacency_dict=adjacency, vertex_coloring=cells)


def fractionated(links: int, triples) -> bool:
    """Whether the Willis equations of the meshes ``triples`` (a, b, t) split at a link: the graph
    on links 0 … n − 1 in which each mesh and its carrier form a triangle is not 2-connected
    (disconnected, or a link whose removal disconnects the rest).  Bit masks: n ≤ 64 links
    cost n flood fills.

    >>> fractionated(5, [(1, 2, 0), (3, 4, 0)]), fractionated(4, [(0, 3, 2), (1, 3, 2)])
    (True, False)
    """
    near = [0] * links
    for a, b, t in triples:
        near[a] |= 1 << b | 1 << t
        near[b] |= 1 << a | 1 << t
        near[t] |= 1 << a | 1 << b
    every = (1 << links) - 1
    if not _connected(near, every):
        return True
    return links > 2 and not all(_connected(near, every & ~(1 << x)) for x in range(links))


def _check_joined(links: int, axes, meshes) -> None:
    """Refuse a train whose axes and meshes do not join its links into one body of links: a link
    in no axis and no mesh (a carrier too turns on an axis or meshes), or a group of links apart
    from the rest.

    >>> _check_joined(4, [(0, 1)], [(0, 3)])
    Traceback (most recent call last):
    ...
    synth.errors.MalformedChain: link 2 is in no axis and no mesh: every link of a gear train turns on an axis or meshes
    """
    near = [0] * links
    for group in (*axes, *meshes):
        mask = 0
        for x in group:
            mask |= 1 << x
        for x in group:
            near[x] |= mask
    every = (1 << links) - 1
    seen = _reached(near, every)
    if seen == every:
        return
    loose = [x for x in range(links) if not near[x]]
    if loose:
        raise MalformedChain(f"{_links_are(loose)} in no axis and no mesh: every link of a gear train turns on an "
                             "axis or meshes")
    apart = [x for x in range(links) if not seen >> x & 1]
    raise MalformedChain(f"{_links_are(apart)} not joined to link 0 by axes and meshes: a gear train is one connected "
                         "set of links")


def _links_are(links: list[int]) -> str:
    """``link 2 is`` / ``links 2, 3 are`` (the first five named)."""
    if len(links) == 1:
        return f"link {links[0]} is"
    return "links " + ", ".join(map(str, links[:5])) + (", …" if len(links) > 5 else "") + " are"


def _connected(near: list[int], within: int) -> bool:
    """Whether the links of the bit mask ``within`` are connected by the neighbours ``near``."""
    return _reached(near, within) == within


def _reached(near: list[int], within: int) -> int:
    """The bit mask of the links of ``within`` that its lowest link reaches through the neighbours ``near``."""
    seen = frontier = within & -within
    while frontier:
        reach = 0
        while frontier:
            low = frontier & -frontier
            reach |= near[low.bit_length() - 1]
            frontier ^= low
        frontier = reach & within & ~seen
        seen |= frontier
    return seen


@dataclass(frozen=True)
class GearTrain:
    """Immutable gear train.

    Parameters
    ----------
    links : int
        Number of links n (frame included).
    axes : sequence of sequences of int
        Each axis as the links that turn about it (two or more).
    meshes : sequence of pairs of int
        Each mesh as its two gears.
    carriers : sequence of int, optional
        The carrier of each mesh; None finds each as the middle link of the axis path
        a – X – t – Y – b (which must then exist and be unique).
    internal : sequence of bool, optional
        Per mesh, whether it is an internal mesh (its first gear a ring); None: all external.
    frame : int, optional
        The fixed link, when the train is a mechanism.

    Examples
    --------
    >>> t = GearTrain(4, [(2, 3), (0, 1, 2)], [(3, 1), (0, 3)], internal=[False, True])
    >>> t.axes, t.meshes, t.internal
    (((0, 1, 2), (2, 3)), ((0, 3), (1, 3)), (True, False))
    """

    links: int
    axes: tuple[tuple[int, ...], ...]
    meshes: tuple[tuple[int, int], ...]
    carriers: tuple[int, ...] | None = None
    internal: tuple[bool, ...] | None = None
    frame: int | None = None

    def __post_init__(self):
        n = self.links
        if isinstance(n, bool) or not isinstance(n, int) or n < 2:
            raise MalformedChain(f"a gear train needs a whole number of links ≥ 2, not {n!r}")
        try:
            axes = [tuple(sorted(int(x) for x in a)) for a in self.axes]
            raw = [tuple(int(x) for x in m) for m in self.meshes]
        except (TypeError, ValueError):
            raise MalformedChain("axes and meshes must be lists of link numbers") from None
        for a in axes:
            if len(a) < 2 or len(set(a)) != len(a):
                raise MalformedChain(f"axis {list(a)} must join two or more different links")
            if a[0] < 0 or a[-1] >= n:
                raise MalformedChain(f"axis {list(a)} names a link outside 0…{n - 1}")
        if len(set(axes)) != len(axes):
            raise MalformedChain("two axes join the same links: write them as one axis")
        for m in raw:
            if len(m) != 2 or m[0] == m[1] or min(m) < 0 or max(m) >= n:
                raise MalformedChain(f"mesh {list(m)} must join two different links of 0…{n - 1}")
        internal = [False] * len(raw) if self.internal is None else [bool(x) for x in self.internal]
        if len(internal) != len(raw):
            raise MalformedChain(f"{len(internal)} mesh kinds given for {len(raw)} meshes")
        carriers = self.carriers
        if carriers is not None:
            carriers = [int(t) for t in carriers]
            if len(carriers) != len(raw):
                raise MalformedChain(f"{len(carriers)} carriers given for {len(raw)} meshes")
        else:
            carriers = GearTrain._carriers_or_none(n, axes, raw)
            for (a, b), t in zip(raw, carriers):
                if t is None:
                    raise MalformedChain(
                        f"mesh {a}~{b} has no carrier: its gears must turn on one link about two different axes "
                        f"(a – axis – carrier – axis – b); give the carrier as {a}~{b}@t")
        for (a, b), t in zip(raw, carriers):
            if not 0 <= t < n or t in (a, b):
                raise MalformedChain(f"the carrier of mesh {a}~{b} must be a third link of 0…{n - 1}, not {t}")
        # a ring (internal mesh) is written first; an external mesh in increasing order
        rows = sorted((m if inner else tuple(sorted(m)), t, inner) for m, t, inner in zip(raw, carriers, internal))
        keys = [frozenset(m) for m, _, _ in rows]
        if len(set(keys)) != len(keys):
            raise MalformedChain("two meshes join the same two links: a pair of gears meshes once")
        if self.frame is not None and (isinstance(self.frame, bool) or not (isinstance(self.frame, int) and 0 <= self.frame < n)):
            raise MalformedChain(f"the frame {self.frame!r} is not a link of 0…{n - 1}")
        _check_joined(n, axes, raw)
        object.__setattr__(self, "axes", tuple(sorted(axes)))
        object.__setattr__(self, "meshes", tuple(m for m, _, _ in rows))
        object.__setattr__(self, "carriers", tuple(t for _, t, _ in rows))
        object.__setattr__(self, "internal", tuple(inner for _, _, inner in rows))

    # ------------------------------------------------------------------ numbers
    @property
    def revolute_equivalents(self) -> int:
        """p = Σ (|X| − 1) over the axes."""
        return sum(len(a) - 1 for a in self.axes)

    @property
    def dof(self) -> int:
        """F = 3(n − 1) − 2p − g (a mesh: a higher pair, f = 1)."""
        return 3 * (self.links - 1) - 2 * self.revolute_equivalents - len(self.meshes)

    @property
    def is_tree(self) -> bool:
        """Whether the axes alone join every link as a tree (the planetary-train atlases' kind)."""
        return self.revolute_equivalents == self.links - 1 and len(axis_paths(self.links, self.axes)[0]) == self.links

    @property
    def triples(self) -> tuple[tuple[int, int, int], ...]:
        """(a, b, t) per mesh: its gears and its carrier — what the Willis equations see."""
        return tuple((a, b, t) for (a, b), t in zip(self.meshes, self.carriers))

    def to_chain(self) -> Chain:
        """The train as a chain with joint kinds: each axis a revolute (multiple) joint, each mesh a
        gear-mesh joint (``~``), as ``analyze`` and ``draw`` read it.

        >>> GearTrain.parse("0-1-2 2-3 1~3 0~3").to_chain().compact()
        '0-1-2 0~3 1~3 2-3'
        """
        joints = list(self.axes) + list(self.meshes)
        return Chain(self.links, joints, [REVOLUTE] * len(self.axes) + [MESH] * len(self.meshes))

    @classmethod
    def from_chain(cls, chain: Chain) -> "GearTrain":
        """The gear train of a chain with gear meshes (revolute joints as its axes), carriers found
        from the axes.

        >>> GearTrain.from_chain(Chain.parse("0-1-2 2-3 1~3 0~3")).compact() == GearTrain.parse("0-1-2 2-3 1~3 0~3").compact()
        True
        """
        kinds = chain.kinds
        if PRISMATIC in kinds:
            raise MalformedChain("a gear train turns on axes and meshes: it has no prismatic pair")
        axes = [j for j, k in zip(chain.joints, kinds) if k == REVOLUTE]
        meshes = [j for j, k in zip(chain.joints, kinds) if k == MESH]
        return cls(chain.links, axes, meshes)

    @cached_property
    def _lever(self) -> Chain:
        return lever_analogue(self.to_chain())

    def lever_analogue(self) -> Chain:
        """The chain with each mesh replaced by a binary link (numbered n, n + 1, … in mesh order)
        jointed to both gears; each axis stays one (multiple) joint.

        >>> GearTrain.parse("0-1-2 2-3 1~3 0~3").lever_analogue().compact()
        '0-1-2 0-4 1-5 2-3 3-4 3-5'
        """
        return self._lever

    def is_rigid_free(self) -> bool:
        """Whether every set S of two links or more, the whole train included, keeps a freedom:
        3(|S| − 1) − 2p(S) − g(S) ≥ 1 — F ≥ 1 and the engine's exact test on the lever analogue
        (which judges the proper sub-chains).

        >>> GearTrain.parse("0-1-4-5 0-2 1-3 0~3 2~4 2~5 3~4 3~5").is_rigid_free()  # F = 0: a structure
        False
        """
        return self.dof >= 1 and check_subchains(self.lever_analogue()).ok

    def is_fractionated(self) -> bool:
        """Whether a link splits the train's Willis equations into two independent groups: the
        graph of links with each mesh and its carrier as a triangle is not 2-connected (a link in
        no mesh and carrying none splits it too).  See :func:`fractionated`.

        >>> GearTrain.parse("0-1-4 0-2 0-3 1~2 3~4").is_fractionated()  # two gear pairs on one frame
        True
        """
        return fractionated(self.links, self.triples)

    # ------------------------------------------------------------ certificates
    def _graph(self, marked=()) -> pynauty.Graph:
        """nauty graph of the displacement graph: links, axes (joined to their links) and meshes
        (joined to their gears), three colours.  ``marked`` links get cells of their own, in order
        (frame, input, output)."""
        n = self.links
        adjacency: dict[int, list[int]] = {}
        axis0, mesh0 = n, n + len(self.axes)
        for k, axis in enumerate(self.axes):
            adjacency[axis0 + k] = list(axis)
        for k, (a, b) in enumerate(self.meshes):  # an internal mesh: a node of its own colour
            adjacency[mesh0 + k] = [a, b]
        inner = {mesh0 + k for k, x in enumerate(self.internal) if x}
        cells = [set(range(axis0, mesh0)), set(range(mesh0, mesh0 + len(self.meshes))) - inner, inner]
        total = mesh0 + len(self.meshes)
        if inner:  # the ring of an internal mesh is its first gear: mark which by a tag node
            for k in sorted(inner):
                adjacency[total] = [k, self.meshes[k - mesh0][0]]
                total += 1
            cells.append(set(range(mesh0 + len(self.meshes), total)))
        marked = list(marked)
        cells = [{m} for m in marked] + [set(range(n)) - set(marked)] + [c for c in cells]
        return pynauty.Graph(total, adjacency_dict=adjacency, vertex_coloring=cells)

    @cached_property
    def certificate(self) -> str:
        """Canonical certificate of the displacement graph (links, axes, meshes; internal meshes
        and the frame told apart): equal exactly for isomorphic trains.

        >>> a = GearTrain.parse("0-1-2 2-3 1~3 0~3"); b = GearTrain.parse("3-2-1 1-0 2~0 3~0")
        >>> a.certificate == b.certificate
        True
        """
        marked = () if self.frame is None else (self.frame,)
        sizes = f"g{self.links:02x}{len(self.axes):02x}{len(self.meshes):02x}{sum(self.internal):02x}{len(marked)}"
        return sizes + pynauty.certificate(self._graph(marked=marked)).hex()

    @cached_property
    def rotation_certificate(self) -> str:
        """Canonical certificate of the rotation graph: the triples (a, b; t) up to renumbering links.

        >>> GearTrain.parse("0-1-2 2-3 1~3 0~3").rotation_certificate == GearTrain.parse("0-2 0-1-3 2~3 1~2").rotation_certificate
        True
        """
        return f"r{self.links:02x}{len(self.meshes):02x}" + pynauty.certificate(rotation_graph(self.links, self.triples)).hex()

    def automorphisms(self, marked=()) -> tuple[list[list[int]], list[int]]:
        """Generators (on links) and link orbits of the displacement graph's symmetry, fixing ``marked``."""
        gens, _, _, orbits, _ = pynauty.autgrp(self._graph(marked=marked))
        return [g[: self.links] for g in gens], list(orbits[: self.links])

    # ------------------------------------------------------------------ text and JSON
    def compact(self) -> str:
        """Text form: axes as ``0-1-2``, meshes as ``1~3`` (``0~3i`` internal, ring first), with the
        carrier as ``@t`` where it is not found from the axes.

        >>> GearTrain.parse("0-1 1-3 2~3@1 0~3i").compact()
        '0-1 1-3 0~3i 2~3@1'
        """
        parts = ["-".join(map(str, a)) for a in self.axes]
        found = GearTrain._carriers_or_none(self.links, self.axes, self.meshes)
        for (a, b), t, inner, auto in zip(self.meshes, self.carriers, self.internal, found):
            parts.append(f"{a}~{b}" + ("i" if inner else "") + ("" if auto == t else f"@{t}"))
        return " ".join(parts)

    @classmethod
    def parse(cls, text: str, frame: int | None = None) -> "GearTrain":
        """Read the text form (see :meth:`compact`) or JSON (see :meth:`to_dict`)."""
        s = text.strip()
        if s.startswith("{"):
            try:
                return cls.from_dict(json.loads(s))
            except json.JSONDecodeError as exc:
                raise MalformedChain(f"gear train JSON is not valid JSON: {exc.msg} at position {exc.pos}") from None
        axes, meshes, carriers, internal, given = [], [], [], [], False
        for token in s.replace(",", " ").split():
            try:
                if "~" in token:
                    body, _, carrier = token.partition("@")
                    inner = body.endswith("i")
                    a, b = (int(x) for x in body.rstrip("i").split("~"))
                    meshes.append((a, b))
                    internal.append(inner)
                    carriers.append(int(carrier) if carrier else None)
                    given |= bool(carrier)
                else:
                    axes.append(tuple(int(x) for x in token.split("-")))
            except ValueError:
                raise MalformedChain(f"cannot read {token!r}: write axes as '0-1-2' and meshes as '1~3', "
                                     "'0~3i' (internal, ring first) or '2~3@1' (carrier 1)") from None
        if not meshes and not axes:
            raise MalformedChain("an empty text is not a gear train")
        n = 1 + max(x for item in axes + meshes + [(t,) for t in carriers if t is not None] for x in item)
        if given:
            found = GearTrain._carriers_or_none(n, axes, meshes)
            carriers = [t if t is not None else f for t, f in zip(carriers, found)]
            missing = [f"{a}~{b}" for (a, b), t in zip(meshes, carriers) if t is None]
            if missing:
                raise MalformedChain(f"mesh {missing[0]} has no carrier: give it as {missing[0]}@t")
        return cls(n, tuple(axes), tuple(meshes), tuple(carriers) if given else None, tuple(internal), frame)

    @staticmethod
    def _carriers_or_none(n, axes, meshes) -> list[int | None]:
        """The carrier of each mesh from the axes (the middle link of a path a – X – t – Y – b), or None."""
        paths = axis_paths(n, sorted(tuple(sorted(a)) for a in axes))
        out = []
        for a, b in meshes:
            path = paths.get(a, {}).get(b)
            out.append(path[2] if path is not None and len(path) == 5 else None)
        return out

    def to_dict(self) -> dict:
        """JSON-able row: the train, its numbers and its certificates."""
        d = {"train": self.compact(), "links": self.links, "axes": [list(a) for a in self.axes],
             "meshes": [list(m) for m in self.meshes], "carriers": list(self.carriers),
             "dof": self.dof, "code": str(self.lever_analogue().code),
             "certificate": self.certificate, "rotation_certificate": self.rotation_certificate}
        if any(self.internal):
            d["internal"] = list(self.internal)
        if self.frame is not None:
            d["frame"] = self.frame
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "GearTrain":
        """A train from its JSON row (:meth:`to_dict`): ``axes`` and ``meshes`` (with ``links``,
        ``carriers``, ``internal`` and ``frame`` where given), or ``train``, its text form.

        >>> GearTrain.from_dict({"axes": [[0, 1, 2], [2, 3]], "meshes": [[1, 3], [0, 3]]}).compact()
        '0-1-2 2-3 0~3 1~3'
        >>> GearTrain.from_dict({"axes": [], "meshes": []})
        Traceback (most recent call last):
        ...
        synth.errors.MalformedChain: the gear train object has no axes and no meshes: give each axis as the links that turn about it and each mesh as its two gears
        """
        if not isinstance(d, dict) or "axes" not in d or "meshes" not in d:
            if isinstance(d, dict) and isinstance(d.get("train"), str):
                return cls.parse(d["train"], d.get("frame"))
            raise MalformedChain("a gear train object needs 'axes' and 'meshes' (or 'train', its text form)")
        if not d["axes"] and not d["meshes"]:
            raise MalformedChain("the gear train object has no axes and no meshes: give each axis as the links that "
                                 "turn about it and each mesh as its two gears")
        links = d.get("links")
        if links is None:
            try:
                links = 1 + max(int(x) for item in list(d["axes"]) + list(d["meshes"]) for x in item)
            except (TypeError, ValueError):
                raise MalformedChain("axes and meshes must be lists of link numbers") from None
        return cls(links, tuple(map(tuple, d["axes"])), tuple(map(tuple, d["meshes"])),
                   tuple(d["carriers"]) if d.get("carriers") is not None else None,
                   tuple(d["internal"]) if d.get("internal") is not None else None, d.get("frame"))

    def to_json(self) -> str:
        return json.dumps(self.to_dict())
