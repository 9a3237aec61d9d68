"""Kinematic chains: links and joints, canonical certificates and symmetry from nauty.

A chain has links ``0 … n−1`` and joints; each joint is the tuple of links it joins
(multiplicity = its length: 2 for a simple joint, 3 for a double joint, …).  Its
link–joint incidence graph (links and joints as the two vertex colours) is what
nauty canonises, so two chains share a certificate exactly when they are the same
chain up to renumbering of links and joints.

Example
-------
>>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
>>> str(watt.code), watt.dof, watt.loops
('42/0', 1, 2)
>>> watt.certificate == watt.relabel([5, 4, 3, 2, 1, 0]).certificate
True
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import pynauty

from ..errors import MalformedChain, UnknownJoint
from .nauty_graph import NautyGraph
from .code import Code
from ..display import svg_of
from .disjoint import DisjointSets
from .joints import JOINT_KINDS, MESH, PRISMATIC, REVOLUTE, JointKind

__all__ = ["Chain", "Mechanism", "JOINT_KINDS", "JointKind", "chain_id", "check_as_written", "joint_links"]


@dataclass(frozen=True)
class Chain:
    """Immutable link–joint structure.

    Parameters
    ----------
    links : int
        Number of links n, numbered 0 … n−1 (the frame is one of them).
    joints : sequence of sequences of int
        Each joint as the links it joins (at least two, all different).
    kinds : sequence of str, optional
        A :class:`~synth.structure.joints.JointKind` or its name (``"revolute"``, ``"prismatic"``,
        ``"mesh"``: a gear mesh) per joint; None means all revolute.  Held as a tuple of
        ``JointKind`` always (all ``REVOLUTE`` for a plain chain).  Prismatic pairs and meshes
        join two links, in planar chains (see :mod:`synth.structure.kinds`).
    h : int
        Motion space of its loops (2 … 6; 3 planar and spherical, 6 general spatial): the same
        graph is a different design in another space, with W = h(n − 1) − (h − 1)·p.
    classes : sequence of int, optional
        A heterogeneous chain: the loop class of each link (2 … 6).  Links of class x ≠ h form
        *bases*: the loops made of class-x links only are of class x, every other loop is of
        class h (docs/theory.md, "Heterogeneous chains"); each base link lies on such a loop.
        None (or every link of class h) means a homogeneous chain.

    Two joints on the same two links hold them together as one link: synthesis never builds
    such a chain, and the analysis reports it as an over-constrained sub-chain.

    Examples
    --------
    >>> c = Chain(4, [(0, 1), (1, 2), (2, 3), (3, 0)])
    >>> c.joints, str(c.code)
    (((0, 1), (0, 3), (1, 2), (2, 3)), '4/0')
    >>> Chain.parse("0-1 1=2 2-3 3-0").compact()      # a slider-crank: '=' is a prismatic pair
    '0-1 0-3 1=2 2-3'
    """

    links: int
    joints: tuple[tuple[int, ...], ...]
    kinds: tuple[JointKind, ...] | None = None
    h: int = 3
    classes: tuple[int, ...] | None = None

    def __post_init__(self):
        if isinstance(self.links, bool) or not isinstance(self.links, int) or self.links < 1:
            raise MalformedChain(f"a chain needs a whole number of links ≥ 1, not {self.links!r}")
        if isinstance(self.h, bool) or not isinstance(self.h, int) or not 2 <= self.h <= 6:
            raise MalformedChain(f"the motion space h of a chain's loops is 2 … 6, not {self.h!r}")
        try:
            raw = [tuple(sorted(int(x) for x in j)) for j in self.joints]
        except (TypeError, ValueError):
            raise MalformedChain("each joint must be a list of link numbers") from None
        if self.kinds is None:
            kinds = (REVOLUTE,) * len(raw)
        else:
            kinds = _read_kinds(self.kinds)
            if len(kinds) != len(raw):
                raise MalformedChain(f"{len(kinds)} joint kinds given for {len(raw)} joints")
        for k, j in enumerate(raw):
            if len(j) < 2:
                raise MalformedChain(f"joint {list(j)} joins fewer than two links")
            if len(set(j)) != len(j):
                raise MalformedChain(f"joint {list(j)} names a link twice")
            if j[0] < 0 or j[-1] >= self.links:
                raise MalformedChain(f"joint {list(j)} names a link outside 0…{self.links - 1}")
            if not kinds[k].joins_many and len(j) > 2:
                raise MalformedChain(f"joint {list(j)} joins {len(j)} links: a multiple joint is a pin (revolute), "
                                     f"a {kinds[k]} pair joins two links")
        if MESH in kinds:
            for k, j in enumerate(raw):
                if kinds[k] is MESH and raw.count(j) > 1:
                    raise MalformedChain(f"links {j[0]} and {j[1]} are joined twice, once by a gear mesh: two gears "
                                         "mesh once, and gears on one axis cannot mesh")
        if self.h != 3 and any(k.planar for k in kinds):
            raise MalformedChain(f"prismatic pairs and gear meshes are planar (h = 3), not in motion space h = {self.h}")
        order = sorted(range(len(raw)), key=lambda k: (raw[k], kinds[k]))
        object.__setattr__(self, "joints", tuple(raw[k] for k in order))
        object.__setattr__(self, "kinds", tuple(kinds[k] for k in order))
        object.__setattr__(self, "classes", self._checked_classes())

    def _checked_classes(self) -> tuple[int, ...] | None:
        """The loop classes as given, checked: one per link, 2 … 6, revolute joints only, each
        base link on a loop of its own class; None where every link is of class h."""
        if self.classes is None:
            return None
        try:
            classes = tuple(self.classes)
        except TypeError:
            raise MalformedChain("loop classes are one whole number 2 … 6 per link") from None
        if len(classes) != self.links:
            raise MalformedChain(f"{len(classes)} loop classes given for {self.links} links: give one per link")
        bad = [x for x in classes if isinstance(x, bool) or not isinstance(x, int) or not 2 <= x <= 6]
        if bad:
            raise MalformedChain(f"a loop class is a motion space 2 … 6, not {bad[0]!r}")
        if all(x == self.h for x in classes):
            return None
        if not self.all_revolute:
            raise MalformedChain("a chain with loop classes has revolute joints only (prismatic pairs and meshes are "
                                 "planar, h = 3)")
        for x in sorted(set(classes) - {self.h}):
            base = {i for i, c in enumerate(classes) if c == x}
            lonely = sorted(base - _links_on_loops(base, self.joints))
            if lonely:
                raise MalformedChain(f"link{'s' * (len(lonely) > 1)} {', '.join(map(str, lonely))} of class h = {x} "
                                     f"{'lie' if len(lonely) > 1 else 'lies'} on no loop of class-{x} links: a loop's "
                                     "class belongs to the links of that loop")
        return classes

    @classmethod
    def trusted(cls, links: int, joints, h: int = 3, kinds=None, classes=None) -> "Chain":
        """Build a chain the engine constructed itself (valid by construction): skips the checks.
        With ``kinds``, the joints must be given sorted (as a chain's own), the kinds in their order.

        >>> Chain.trusted(3, [(1, 0), (1, 2), (2, 0)]) == Chain(3, [(0, 1), (1, 2), (0, 2)])
        True
        >>> c = Chain.parse("0-1 1-2 2-3 3-0"); Chain.trusted(4, c.joints, 3, ("prismatic",) + ("revolute",) * 3).compact()
        '0=1 0-3 1-2 2-3'
        """
        self = object.__new__(cls)
        object.__setattr__(self, "links", links)
        object.__setattr__(self, "joints", tuple(sorted(tuple(sorted(j)) for j in joints)))
        object.__setattr__(self, "kinds", (REVOLUTE,) * len(self.joints) if kinds is None
                           else tuple(_BY_NAME[k] for k in kinds))
        object.__setattr__(self, "h", h)
        object.__setattr__(self, "classes", None if classes is None or all(x == h for x in classes)
                           else tuple(classes))
        return self

    # ---------------------------------------------------------------- numbers
    @property
    def all_revolute(self) -> bool:
        """Whether every joint is a pin (a plain chain: its kinds are not written in its rows).

        >>> Chain.parse("0-1 1-2 2-0").all_revolute, Chain.parse("0-1 1=2 2-0").all_revolute
        (True, False)
        """
        return self.kinds.count(REVOLUTE) == len(self.kinds)

    @property
    def degrees(self) -> tuple[int, ...]:
        """Number of joints on each link."""
        deg = [0] * self.links
        for j in self.joints:
            for x in j:
                deg[x] += 1
        return tuple(deg)

    @property
    def simple_joint_equivalents(self) -> int:
        """p = Σ (m_j − 1)."""
        return sum(len(j) - 1 for j in self.joints)

    @property
    def v(self) -> int:
        """Multiple-joint count Σ (m_j − 2)."""
        return sum(len(j) - 2 for j in self.joints)

    @property
    def loops(self) -> int:
        """K = p − n + 1 (for a connected chain)."""
        return self.simple_joint_equivalents - self.links + 1

    @property
    def dof(self) -> int:
        """Mobility W by the count: h(n − 1) − (h − 1)·p, planar with joint kinds
        3(n − 1) − 2·p − g + K_2 (g gear meshes, K_2 wedge loops of prismatic pairs).

        It is the chain's true (generic) mobility wherever no sub-chain is over-constrained
        and no joint is idle — every chain synthesis lists; :func:`~synth.structure.kinds.generic_mobility`
        gives it for any chain.

        >>> Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0").dof, Chain(6, Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0").joints, h=5).dof
        (3, 1)
        >>> Chain.parse("0=1 1=2 2=3 3=0").dof          # a wedge loop
        2
        >>> Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 | h5: 0 1 2 3 4 5").dof   # the toroidal loop, in the plane
        1
        """
        if self.classes is None and self.all_revolute:
            return self.h * (self.links - 1) - (self.h - 1) * self.simple_joint_equivalents
        from .kinds import structural_mobility

        return structural_mobility(self)

    @property
    def loop_classes(self) -> dict[int, int]:
        """K_h, the loops of each class: the cycle rank of each base (its class-x links alone),
        the rest of the K loops of the chain's class h.

        >>> Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5").loop_classes
        {3: 1, 5: 1}
        """
        from .kinds import class_loops

        based = {x: class_loops(self, x) for x in sorted(set(self.classes or ())) if x != self.h}
        return dict(sorted({self.h: self.loops - sum(based.values()), **based}.items()))

    @property
    def code(self) -> Code:
        """Standard code with its joint composition."""
        deg = self.degrees
        top = max(deg, default=0)
        n1 = deg.count(1)
        assortment = tuple(deg.count(i) for i in range(2, top + 1))
        mult = [len(j) for j in self.joints]
        composition = tuple(mult.count(m) for m in range(3, max(mult, default=2) + 1))
        return Code(assortment, self.v, composition, n1)

    def is_connected(self) -> bool:
        """Whether every link is reachable from link 0 through joints."""
        seen, stack = {0}, [0]
        by_link = self._joints_by_link
        while stack:
            x = stack.pop()
            for j in by_link[x]:
                for y in self.joints[j]:
                    if y not in seen:
                        seen.add(y)
                        stack.append(y)
        return len(seen) == self.links

    @cached_property
    def _joints_by_link(self) -> tuple[tuple[int, ...], ...]:
        out = [[] for _ in range(self.links)]
        for k, j in enumerate(self.joints):
            for x in j:
                out[x].append(k)
        return tuple(tuple(x) for x in out)

    # ------------------------------------------------------------ nauty views
    def _nauty_graph(self, marked: Sequence[int] = ()) -> pynauty.Graph:
        """Incidence graph for nauty: links 0…n−1, joints n…; colour cells marked links, links, joints by kind."""
        n = self.links
        if len(set(marked)) != len(marked) or not all(0 <= m < n for m in marked):
            raise MalformedChain(f"the links marked, {list(marked)}, must be distinct links of the chain (0 … {n - 1})")
        adjacency = {n + k: list(j) for k, j in enumerate(self.joints)}  # (a joint's links are distinct)
        if self.classes is None:
            coloring = [{m} for m in marked] + [set(range(n)) - set(marked)]
        else:  # a cell of links per loop class: two class assignments of one graph are two chains
            coloring = [{m} for m in marked] + [{i for i in range(n) if self.classes[i] == x and i not in marked}
                                                for x in sorted(set(self.classes))]
        # a cell per kind up to the last kind the chain has (joints.py: appending a kind keeps every id)
        coloring += [{n + k for k, kk in enumerate(self.kinds) if kk is kind} for kind in self._shown_kinds()]
        return NautyGraph(n + len(self.joints), adjacency, coloring)  # (the cells cover every vertex)

    @property
    def certificate(self) -> str:
        """Canonical certificate (hex): equal exactly for isomorphic chains.

        The sizes (n, J, joint kinds) and the motion space (where h ≠ 3) are part of it, so
        chains of different size or space never collide.
        """
        cert = self.__dict__.get("_certificate")
        if cert is None:
            cert = self._sizes() + pynauty.certificate(self._nauty_graph()).hex()
            object.__setattr__(self, "_certificate", cert)
        return cert

    def _sizes(self) -> str:
        """The certificate's prefix: motion space (where h ≠ 3), links, joints, and the number of
        prismatic pairs and meshes (where there are any)."""
        sizes = ("" if self.h == 3 else f"h{self.h}") + f"{self.links:02x}{len(self.joints):02x}"
        sizes += "".join(f"{kind.tag}{self.kinds.count(kind):02x}" for kind in self._shown_kinds() if kind.tag)
        if self.classes is not None:  # the links of each class, cell by cell as nauty sees them
            sizes += "c" + "".join(f"{x}{self.classes.count(x):02x}" for x in sorted(set(self.classes)))
        return sizes

    def _shown_kinds(self) -> tuple[JointKind, ...]:
        """The kinds whose colour cells and tags the certificate shows: the table up to the last kind
        the chain has (the revolute cell alone for a plain chain)."""
        return JOINT_KINDS[: 1 + max((kind.cell for kind in set(self.kinds)), default=0)]

    def automorphisms(self, marked: Sequence[int] = ()) -> tuple[list[list[int]], float, list[int]]:
        """Generators (on links), group order and link orbits, fixing the ``marked`` links.

        >>> Chain.parse("0-1 1-2 2-3 3-0").automorphisms()[1:]
        (8.0, [0, 0, 0, 0])
        """
        gens, size1, size2, orbits, _ = pynauty.autgrp(self._nauty_graph(marked))
        return [g[: self.links] for g in gens], size1 * 10.0**size2, list(orbits[: self.links])

    @property
    def link_orbits(self) -> list[list[int]]:
        """Links grouped by the automorphism group (fixing any one of them gives the same mechanism)."""
        orbits = self.automorphisms()[2]
        groups: dict[int, list[int]] = {}
        for link, o in enumerate(orbits):
            groups.setdefault(o, []).append(link)
        return sorted(groups.values())

    def relabel(self, permutation: Sequence[int]) -> "Chain":
        """The same chain with link ``i`` renamed ``permutation[i]``."""
        if sorted(permutation) != list(range(self.links)):
            raise MalformedChain("a relabelling must be a permutation of the links")
        classes = None
        if self.classes is not None:
            classes = [0] * self.links
            for i, x in enumerate(self.classes):
                classes[permutation[i]] = x
        return Chain(self.links, tuple(tuple(permutation[x] for x in j) for j in self.joints), self.kinds, self.h,
                     classes)

    def canonical_numbering(self) -> list[int]:
        """Where :meth:`canonical` puts each link: link ``i`` of this chain is link ``numbering[i]`` of the
        canonical chain (a chain given by the user, listed canonical, is mapped back by it).

        >>> Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1").canonical_numbering()   # the Watt chain: its link 0 is link 5
        [5, 4, 0, 3, 2, 1]
        """
        labels = pynauty.canon_label(self._nauty_graph())
        numbering = [0] * self.links
        for position, link in enumerate(labels[: self.links]):
            numbering[link] = position
        return numbering

    def canonical(self) -> "Chain":
        """The chain in its canonical labelling (nauty's): isomorphic chains come out with the same
        joints, so a chain id names one numbering of its links.  Every listing, the atlas and
        ``move --db`` number a chain so, and a frame read from one names the same link in all.

        >>> Chain.parse("0-1 0-2 0-4 1-3 1-5 2-3 4-5").canonical().compact()   # the Watt chain, id 814ad964fad2
        '0-3 0-4 1-2 1-4 2-5 3-5 4-5'
        >>> Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1").canonical().compact()  # the same chain written otherwise
        '0-3 0-4 1-2 1-4 2-5 3-5 4-5'
        """
        out = self.relabel(self.canonical_numbering())
        if "_certificate" in self.__dict__:  # the same chain: its certificate is known
            object.__setattr__(out, "_certificate", self._certificate)
        return out

    def to_networkx(self):
        """Bipartite incidence graph: nodes ``("link", i)`` and ``("joint", k)`` with attribute ``kind``;
        the graph attribute ``h`` is the motion space.

        >>> g = Chain.parse("0-1 1-2 2-0").to_networkx(); g.number_of_nodes(), g.number_of_edges(), g.graph
        (6, 6, {'h': 3})
        """
        import networkx as nx

        g = nx.Graph(h=self.h)
        for i in range(self.links):
            g.add_node(("link", i), kind="link")
        for k, j in enumerate(self.joints):
            g.add_node(("joint", k), kind="joint", multiplicity=len(j),
                       joint_kind=self.kinds[k].value)
            g.add_edges_from((("joint", k), ("link", x)) for x in j)
        return g

    def link_graph(self):
        """Graph of links, an edge where two links share a joint (a multiple joint gives a clique)."""
        import networkx as nx

        g = nx.Graph()
        g.add_nodes_from(range(self.links))
        for j in self.joints:
            g.add_edges_from((a, b) for i, a in enumerate(j) for b in j[i + 1 :])
        return g

    def is_planar(self) -> bool:
        """Whether the link–joint incidence graph is planar (a listing's chain reads it off its branch
        multigraph, decided once for all the chains on it)."""
        branch = self.__dict__.get("_branch")
        if branch is not None:
            return branch.planar
        import networkx as nx

        return nx.check_planarity(self.to_networkx())[0]

    def closed_part(self) -> "Chain":
        """The chain without its open branches: links with a single joint are removed, again and
        again (with joints left holding one link), until every link carries 2 joints or more.
        Link numbers are kept; removed links are left without joints.  Empty for a serial or
        tree-shaped arm.

        >>> Chain.parse("0-1 1-2 2-0 2-3 3-4").closed_part().compact()
        '0-1 0-2 1-2'
        """
        joints = [(list(j), k) for j, k in zip(self.joints, self.kinds)]
        while True:
            degree = [0] * self.links
            for j, _ in joints:
                for x in j:
                    degree[x] += 1
            if all(degree[x] >= 2 for j, _ in joints for x in j):
                break
            joints = [([x for x in j if degree[x] >= 2], k) for j, k in joints]
            joints = [(j, k) for j, k in joints if len(j) >= 2]
        return Chain(self.links, [j for j, _ in joints], [k for _, k in joints], self.h, self.classes)

    def is_fractionated(self) -> bool:
        """Whether removing one link or one joint of the closed part disconnects it (a cut vertex
        of its incidence graph).  Open branches (links with a single joint and the links that
        carry them out to the closed part) do not count: an arm's gripper does not split its
        mobility.

        >>> Chain.parse("0-1 1-2 2-3 3-0 3-4").is_fractionated(), Chain.parse("0-1 1-2 2-0 0-3 3-4 4-0").is_fractionated()
        (False, True)
        """
        branch = self.__dict__.get("_branch")
        if branch is not None:
            return branch.fractionated
        import networkx as nx

        core = self.closed_part() if 1 in self.degrees else self
        g = core.to_networkx()
        g.remove_nodes_from([node for node in list(g) if g.degree(node) == 0])
        return g.number_of_nodes() > 2 and not nx.is_biconnected(g)

    # ------------------------------------------------------------------- I/O
    def to_dict(self) -> dict:
        """JSON-able object (the `jsonl` row of `mechsynth chains`)."""
        d = {
            "code": str(self.code),
            "links": self.links,
            "joints": [list(j) for j in self.joints],
            "certificate": self.certificate,
            "dof": self.dof,
            "loops": self.loops,
            "v": self.v,
        }
        if not self.all_revolute:  # the code says how many pairs are prismatic and meshes, e.g. '42/0 P2'
            from .kinds import wedge_loops

            d["kinds"] = list(self.kinds)
            d["code"] += self.kind_suffix
            k2 = wedge_loops(self)
            d.update(prismatic=self.kinds.count(PRISMATIC), meshes=self.kinds.count(MESH), loops_2=k2,
                     loops_3=self.loops - k2)
        if self.h != 3:
            d["h"] = self.h
        if self.classes is not None:
            d["classes"] = list(self.classes)
            d["loop_classes"] = {str(x): k for x, k in self.loop_classes.items()}
            d["code"] += self.class_suffix
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "Chain":
        if not isinstance(d, dict) or "joints" not in d:
            raise MalformedChain("a chain object needs 'joints' (a list of lists of link numbers)")
        joints = d["joints"]
        if not isinstance(joints, list) or not all(isinstance(j, list) for j in joints):
            raise MalformedChain("'joints' must be a list of lists of link numbers")
        links = d.get("links")
        if links is None:
            links = 1 + max((x for j in joints for x in j if isinstance(x, int)), default=-1)
        if any(not isinstance(x, int) or isinstance(x, bool) for j in joints for x in j):
            raise MalformedChain("joints must list links by whole numbers")
        h = d.get("h", 3)
        if isinstance(h, bool) or not isinstance(h, int):
            raise MalformedChain(f"'h' must be a whole number 2 … 6, not {h!r}")
        check_as_written(None, joints)
        classes = d.get("classes")
        if classes is not None and not isinstance(classes, list):
            raise MalformedChain("'classes' must be a list of loop classes, one per link")
        return cls(links, tuple(tuple(j) for j in joints), d.get("kinds"), h, classes)

    @property
    def kind_suffix(self) -> str:
        """What the code leaves out: ``" P2"`` for two prismatic pairs, ``" G3"`` for three gear
        meshes (empty for an all-revolute chain).

        >>> Chain.parse("0-1 1=2 2~3 3-0").kind_suffix
        ' P1 G1'
        """
        counts = ((kind, self.kinds.count(kind)) for kind in JOINT_KINDS if kind is not REVOLUTE)
        return "".join(f" {kind.letter}{count}" for kind, count in counts if count)

    @property
    def class_suffix(self) -> str:
        """What the code leaves out of a heterogeneous chain: its loops by class, ``" K3=4 K5=1"``
        (empty for a homogeneous chain).

        >>> Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5").class_suffix
        ' K3=1 K5=1'
        """
        if self.classes is None:
            return ""
        return "".join(f" K{x}={k}" for x, k in self.loop_classes.items())

    def to_json(self) -> str:
        return json.dumps(self.to_dict())

    @classmethod
    def from_json(cls, text: str) -> "Chain":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise MalformedChain(f"chain JSON is not valid JSON: {exc.msg} at position {exc.pos}") from None
        if isinstance(data, list):
            data = {"joints": data}
        return cls.from_dict(data)

    @classmethod
    def parse(cls, text: str) -> "Chain":
        """Read JSON, or a compact joint list: ``-`` a revolute joint (``"0-1-2"`` a double
        joint), ``=`` a prismatic pair, ``~`` a gear mesh.

        >>> Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1").v
        1
        >>> Chain.parse("0=1 1-2 2~0").kinds       # joints sorted: (0, 1), (0, 2), (1, 2)
        ('prismatic', 'mesh', 'revolute')

        A heterogeneous chain names its base links after ``|``, class by class (the other links
        are of the chain's class h, 3 here): ``"… | h5: 0 1 2 3 4 5"``.

        >>> Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5").loop_classes
        {3: 1, 5: 1}
        """
        s = text.strip()
        if s.startswith("{") or s.startswith("["):
            return cls.from_json(s)
        s, _, declared = s.partition("|")
        joints, kinds = [], []
        signs = JointKind.symbols()
        for token in s.replace(",", " ").split():
            symbols = {c for c in token if c in signs}
            parts = token.translate(_TO_DASH).split("-")
            try:
                joint = tuple(int(x) for x in parts)
            except ValueError:
                joint = None
            if joint is None or len(symbols) != 1 or any(x < 0 for x in joint):
                raise MalformedChain(
                    f"cannot read joint {token!r}: write joints as link numbers joined by '-' (revolute, "
                    "'0-1-2' joins three links), '=' (prismatic) or '~' (gear mesh), e.g. '0-1 1=2 2~3'"
                ) from None
            joints.append(joint)
            kinds.append(JointKind.by_symbol(symbols.pop()))
        if not joints:
            raise MalformedChain("an empty joint list is not a chain")
        links = 1 + max(max(j) for j in joints)
        check_as_written(links, joints)
        h, classes = _read_classes(declared, links) if declared.strip() else (3, None)
        return cls(links, tuple(joints), kinds, h, classes)

    def compact(self) -> str:
        """The compact joint-list notation read by :meth:`parse`, joint kinds included.

        >>> Chain.parse("2~1 0=1 0-2").compact()
        '0=1 0-2 1~2'
        """
        text = " ".join(k.symbol.join(map(str, j)) for j, k in zip(self.joints, self.kinds))
        if self.classes is not None:
            bases = [f"h{x}: " + " ".join(str(i) for i, c in enumerate(self.classes) if c == x)
                     for x in sorted(set(self.classes) - {self.h})]
            text += " | " + "; ".join(([] if self.h == 3 else [f"h{self.h}"]) + bases)
        return text

    def joint_index(self, name, what: str = "a joint name") -> int:
        """The index of the joint a user names by its links — ``"1-2"``, ``"2=1"`` (any kind's sign, in
        any order), ``[1, 2]`` — or by its index (an ``int``).

        ``what`` says where the name was written (``"--input"``, ``"'inputs'"``); the error's sentence
        begins with it.

        Raises
        ------
        UnknownJoint
            The name cannot be read as links, or names no joint of the chain.

        Examples
        --------
        >>> four_bar = Chain.parse("0-1 1-2 2-3 3-0")
        >>> four_bar.joint_index("2-1"), four_bar.joint_index([3, 0]), four_bar.joint_index(3)
        (2, 1, 3)
        >>> four_bar.joint_index("1-3", "--input")
        Traceback (most recent call last):
        ...
        synth.errors.UnknownJoint: --input names joint '1-3', which is not a joint of the chain 0-1 0-3 1-2 2-3
        """
        if isinstance(name, int) and not isinstance(name, bool):
            if 0 <= name < len(self.joints):
                return name
            raise UnknownJoint(f"{what} names joint {name}, but the chain has joints 0 … {len(self.joints) - 1}")
        links = joint_links(name)
        if links is None:
            raise UnknownJoint(f"{what} names joint {name!r}: write a joint by its links, e.g. '1-2'")
        try:
            return self.joints.index(links)
        except ValueError:
            raise UnknownJoint(f"{what} names joint {name!r}, which is not a joint of the chain "
                               f"{self.compact()}") from None

    def _repr_svg_(self) -> str:
        """The drawing Jupyter shows (links as polygons, multiple joints marked, links numbered)."""
        return svg_of(self)


def joint_links(name) -> tuple[int, ...] | None:
    """The links, sorted, of a joint written as ``"1-2"``, ``"2=1"``, ``"0-1-2"`` (any kind's sign) or
    ``[1, 2]``; None if ``name`` is not written so (an index is not: see :meth:`Chain.joint_index`).

    >>> joint_links("2=1"), joint_links((3, 0)), joint_links("1-x"), joint_links(2)
    ((1, 2), (0, 3), None, None)
    """
    try:
        return tuple(sorted(int(x) for x in (name.translate(_TO_DASH).split("-") if isinstance(name, str)
                                             else name)))
    except (TypeError, ValueError):
        return None


_BY_NAME = {kind.value: kind for kind in JointKind}  # a name or a member: members hash as their names


def _read_kinds(kinds) -> tuple[JointKind, ...]:
    """Joint kinds given by name or as members, as members.

    >>> _read_kinds(["revolute", JointKind.MESH])
    ('revolute', 'mesh')
    """
    try:
        given = [kinds] if isinstance(kinds, str) else list(kinds)
    except TypeError:
        given = [kinds]
    out = []
    for kind in given:
        if not isinstance(kind, str) or kind not in _BY_NAME:
            raise MalformedChain(f"joint kind {kind!r} is not one of {', '.join(JOINT_KINDS)}")
        out.append(_BY_NAME[kind])
    return tuple(out)
_TO_DASH = str.maketrans({symbol: "-" for symbol in JointKind.symbols()})


def _links_on_loops(links: set[int], joints) -> set[int]:
    """The links of ``links`` that lie on a loop of those links alone (each joint restricted to
    them): a cycle of their link–joint incidence graph, so two joints of the link still reach each
    other without it.

    >>> sorted(_links_on_loops({0, 1, 2, 3}, [(0, 1), (1, 2), (2, 0), (2, 3)]))
    [0, 1, 2]
    >>> sorted(_links_on_loops({0, 1, 2}, [(0, 1, 2)]))     # three links on one pin: no loop
    []
    """
    inside = [[x for x in j if x in links] for j in joints]
    inside = [j for j in inside if len(j) >= 2]
    on = set()
    for x in links:
        own = [k for k, j in enumerate(inside) if x in j]
        if len(own) < 2:
            continue
        joined = DisjointSets(range(len(inside)))  # joints joined through the links other than x
        first: dict[int, int] = {}
        for k, j in enumerate(inside):
            for y in j:
                if y != x:
                    joined.union(k, first.setdefault(y, k))
        if len({joined.find(k) for k in own}) < len(own):
            on.add(x)
    return on


def _read_classes(text: str, links: int) -> tuple[int, tuple[int, ...]]:
    """The motion spaces written after ``|`` in a joint list: each base's class and links,
    ``h5: 0 1 2 3 4 5`` (several separated by ``;``), and the class of the other links, ``h2``
    alone (3 when not written).  Returns (h, the class of each link).

    >>> _read_classes(" h5: 0 1 2", 4)
    (3, (5, 5, 5, 3))
    >>> _read_classes(" h2; h3: 0 1 2", 4)
    (2, (3, 3, 3, 2))
    """
    ambient, bases = 3, []
    for part in text.split(";"):
        head, colon, body = part.partition(":")
        head = head.strip()
        try:
            x = int(head[1:]) if head[:1] == "h" else None
            members = [int(t) for t in body.replace(",", " ").split()]
        except ValueError:
            x = None
        if x is None or bool(colon) != bool(members):
            raise MalformedChain(f"cannot read the loop classes {part.strip()!r}: after '|' write each base's class and "
                                 "links, e.g. '| h5: 0 1 2 3 4 5' ('| h2; h3: 0 1 2 3' where the other links are not of "
                                 "class 3)")
        if colon:
            bases.append((x, members))
        else:
            ambient = x
    classes = [ambient] * links
    for x, members in bases:
        for i in members:
            if not 0 <= i < links:
                raise MalformedChain(f"link {i} of class h = {x} is not a link of the chain (0 … {links - 1})")
            classes[i] = x
    return ambient, tuple(classes)


def check_as_written(links: int | None, joints) -> None:
    """A chain as a user writes it: no two joints join the same links, and (with ``links``, for a
    joint list) every link number 0 … links − 1 is in some joint (a gap is a typo, not a separate link).

    >>> check_as_written(3, [(0, 1), (1, 2), (2, 0), (1, 0)])
    Traceback (most recent call last):
    ...
    synth.errors.MalformedChain: joints 0-1 and 1-0 join the same links: two joints never join the same set of links
    >>> check_as_written(100, [(0, 1), (1, 2), (2, 99)])
    Traceback (most recent call last):
    ...
    synth.errors.MalformedChain: links 3…98 are in no joint: number the links 0 … n − 1 without gaps (here 0 … 3)
    """
    seen: dict = {}
    for j in joints:
        key = frozenset(j) if len(set(j)) == len(j) else None  # a link named twice is refused by Chain itself
        if key is not None and key in seen:
            raise MalformedChain(f"joints {'-'.join(map(str, seen[key]))} and {'-'.join(map(str, j))} join the same "
                                 "links: two joints never join the same set of links")
        seen.setdefault(key, j)
    if links is None:
        return
    used = sorted({x for j in joints for x in j if isinstance(x, int) and 0 <= x < links})
    if len(used) == links or any(not isinstance(x, int) or not 0 <= x < links for j in joints for x in j):
        return  # complete, or a link outside 0 … links − 1, which Chain names
    gaps, before = [], -1
    for x in used + [links]:
        if x > before + 1:
            gaps.append(f"{before + 1}" if x == before + 2 else f"{before + 1}, {x - 1}" if x == before + 3
                        else f"{before + 1}…{x - 1}")
        before = x
    missing = links - len(used)
    names = ", ".join(gaps[:5]) + (", …" if len(gaps) > 5 else "")
    raise MalformedChain(f"link{'s' * (missing > 1)} {names} {'are' if missing > 1 else 'is'} in no joint: number "
                         f"the links 0 … n − 1 without gaps (here 0 … {len(used) - 1})")


@dataclass(frozen=True)
class Mechanism:
    """A chain with a fixed link (the frame) and optionally an input link jointed to it.

    >>> m = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0, input_link=1)
    >>> m.certificate == Mechanism(m.chain.relabel([1, 2, 3, 0]), frame=1, input_link=2).certificate
    True
    """

    chain: Chain
    frame: int
    input_link: int | None = None

    def __post_init__(self):
        if not 0 <= self.frame < self.chain.links:
            raise MalformedChain(f"fixed link {self.frame} is not a link of the chain")
        if self.input_link is not None:
            if self.input_link == self.frame or not any(
                self.frame in j and self.input_link in j for j in self.chain.joints
            ):
                raise MalformedChain(f"input link {self.input_link} is not jointed to the fixed link {self.frame}")

    @property
    def marked(self) -> tuple[int, ...]:
        return (self.frame,) if self.input_link is None else (self.frame, self.input_link)

    @property
    def certificate(self) -> str:
        """Canonical certificate of the chain with the frame (and input) as their own colours."""
        g = self.chain._nauty_graph(self.marked)
        return f"m{len(self.marked)}" + self.chain._sizes() + pynauty.certificate(g).hex()

    def _repr_svg_(self) -> str:
        """The drawing Jupyter shows: the fixed link hatched, the input link marked."""
        return svg_of(self)

    def to_dict(self) -> dict:
        """The chain's row with its frame (and input link), and its prismatic pairs by kind
        (guide, swinging or floating cylinder, slider) where it has some."""
        d = self.chain.to_dict()
        d["frame"] = self.frame
        if PRISMATIC in self.chain.kinds:
            from .kinds import prismatic_roles

            d.update(prismatic_roles(self.chain, self.frame))
        d["chain_certificate"] = d.pop("certificate")
        d["certificate"] = self.certificate
        if self.input_link is not None:
            d["input_link"] = self.input_link
        return d


def chain_id(certificate: str) -> str:
    """A chain's stable id: the first 12 hex digits of the SHA-1 of its certificate (its address in
    an atlas web site, ``chain.html#<id>``, and the ``id`` of every listing and atlas export).

    >>> chain_id(Chain.parse("0-1 1-2 2-3 3-0").certificate) == chain_id(Chain.parse("3-2 2-1 1-0 0-3").certificate)
    True
    """
    return hashlib.sha1(certificate.encode()).hexdigest()[:12]
