"""Independent brute-force enumerator of planar kinematic chains (test oracle).

This module is the slow, obviously-correct reference that the test suite uses
to cross-check the fast engine (``synth``).  It deliberately shares **no** code
with the engine: it imports neither ``synth`` nor ``ortools`` nor ``pynauty``.
Only the standard library and ``networkx`` are used.

Definitions (as in docs/theory.md, "From codes to chains" and "The sub-chain rule")
-----------------------------------------------------------------------------------
* A chain has links ``0..n-1`` and joints; a joint is a set of ``m >= 2``
  links (``m`` = multiplicity).  ``p = sum(m - 1)``, ``v = sum(m - 2)``,
  planar mobility ``W = 3(n - 1) - 2p``; loops ``K = p - n + 1``.
* Sub-chain mobility of a link set ``S``:
  ``W(S) = 3(|S| - 1) - 2 * sum_j max(m_j(S) - 1, 0)``.
* ``rigid_subchains=False`` (non-degenerate): every proper ``S`` with
  ``|S| >= 2`` has ``W(S) >= 1``.  ``rigid_subchains=True``: every ``S`` with
  ``|S| >= 2`` has ``W(S) >= 0``.
* Fractionated: the link-joint incidence bipartite graph has a cut vertex.
* Closed: every link lies on at least two joints.  Connected.
* Isomorphism: bijections links->links, joints->joints preserving incidence.

Enumeration method
------------------
Labelled backtracking over *sets* of joints.  The candidate joints are all
subsets of ``{0..n-1}`` of size ``2..v_max+2``, written as sorted tuples and
ordered lexicographically; a chain is built by choosing candidates in strictly
increasing order, so every set of joints is produced exactly once (as a
labelled object).  Since tuples are ordered lexicographically, the *first
element* of the chosen joints never decreases: once a joint with first element
``a`` has been chosen, links ``< a`` can never receive another joint, i.e. they
are *closed* and their degree is final.

Every labelled chain whose link degrees are non-increasing
(``deg(0) >= deg(1) >= ... >= deg(n-1)``) is reachable, and every chain has such
a labelling (sort the links by degree), so every isomorphism class is reached.
Pruning rules, each of which only rejects partial joint sets that cannot be
completed into an admissible chain (so exhaustiveness is preserved):

1. **Budget**: ``p_used + (m - 1) <= p`` and ``v_used + (m - 2) <= v_max``; both
   sums only grow when joints are added.
2. **Sub-chain condition, checked on every subset at every node**: adding a
   joint never decreases ``sum_j max(m_j(S) - 1, 0)`` for any ``S``, so
   ``W(S)`` is non-increasing along a branch; a subset that already violates
   the convention violates it in every completion.  (This also rejects two
   joints sharing two links: ``S`` = that pair gives ``W(S) = 3 - 4 < 0``.)
   The check is done on all ``2**n`` subsets at once with packed big
   integers (``_SubsetChecker``); ``subchain_ok`` is the plain
   ``itertools.combinations`` version, used to re-check every result and
   compared against the packed one in the tests.
3. **Linearity** (speed only, implied by rule 2): a new joint may not contain
   two links that already share a joint.
4. **Closure**: choosing a joint with first element ``a`` closes all links
   ``< a`` for good, so they must already have degree >= 2 (closed chain) and
   non-increasing degrees (the labelling convention above), and every still
   open link must have degree <= deg(a - 1) (degrees only grow).  Validity for
   prefix ``a`` implies validity for every smaller prefix, so the scan over
   candidates may stop at the first invalid ``a``.
5. **Degree cap** ``deg <= min(n - 1, 2K)``: a link's joints each contain
   another link and those are pairwise distinct (linearity), hence ``<= n-1``;
   and ``sum(deg) = sum(m) = p + J`` with ``J <= p`` joints and every other
   link of degree >= 2 gives ``deg <= 2p - 2(n - 1) = 2K``.
6. **Deficit**: open links of degree < 2 need ``sum(2 - deg)`` more incidences;
   a joint adds ``m <= 2(m - 1)`` incidences for ``m - 1`` of the ``p``
   budget, so at most ``2 * (p - p_used)`` incidences remain.

Leaves (``p_used == p``) are deduplicated exactly: when a new class is found,
all relabellings of it that permute links *within equal-degree label blocks*
are put in a set.  Any isomorphism between two degree-sorted labellings maps a
link to a link of equal degree, hence stays inside the blocks, so a leaf is
isomorphic to a known class **iff** it is in that set.  Each new class is
additionally confirmed non-isomorphic to every earlier one with networkx VF2
(``ChainIndex``); a disagreement raises.  Connectivity, the fractionated rule,
planarity, the plain sub-chain check and the fixed-link orbits are
isomorphism invariants and are computed once per class.
"""

from __future__ import annotations

import functools
import itertools
from collections import Counter
from dataclasses import dataclass

import networkx as nx

__all__ = [
    "BruteChain",
    "ChainIndex",
    "brute_force_chains",
    "code_key",
    "count_by_code",
    "incidence_graph",
    "is_connected",
    "is_fractionated",
    "fixed_link_orbits",
    "subchain_ok",
    "mobility",
]


# --------------------------------------------------------------------------
# Plain, definition-level helpers
# --------------------------------------------------------------------------

def _norm(joints) -> tuple[tuple[int, ...], ...]:
    return tuple(sorted(tuple(sorted(j)) for j in joints))


def mobility(joints, links: int, h: int = 3) -> int:
    """Mobility in motion space h: W = h(n - 1) - (h - 1)p (planar 3(n - 1) - 2p)."""
    return h * (links - 1) - (h - 1) * sum(len(j) - 1 for j in joints)


def subchain_mobility(joints, subset, h: int = 3) -> int:
    """W(S) = h(|S| - 1) - (h - 1) * sum_j max(m_j(S) - 1, 0)."""
    s = set(subset)
    load = sum(max(len(s.intersection(j)) - 1, 0) for j in joints)
    return h * (len(s) - 1) - (h - 1) * load


def subchain_ok(joints, links: int, rigid_subchains: bool, h: int = 3) -> bool:
    """Exhaustive check over ALL link subsets with |S| >= 2 (plain version).

    rigid_subchains=False: proper subsets need W(S) >= 1;
    rigid_subchains=True: all subsets (the whole chain included) need W(S) >= 0.
    """
    for k in range(2, links + 1):
        if k == links and not rigid_subchains:
            continue
        need = 0 if rigid_subchains else 1
        for s in itertools.combinations(range(links), k):
            if subchain_mobility(joints, s, h) < need:
                return False
    return True


def incidence_graph(joints, links: int) -> nx.Graph:
    """Link-joint incidence bipartite graph; nodes ('L', i) and ('J', k)."""
    g = nx.Graph()
    for i in range(links):
        g.add_node(("L", i), kind="link")
    for k, j in enumerate(joints):
        g.add_node(("J", k), kind="joint")
        for i in j:
            g.add_edge(("L", i), ("J", k))
    return g


def is_connected(joints, links: int) -> bool:
    return nx.is_connected(incidence_graph(joints, links))


def is_fractionated(joints, links: int) -> bool:
    """True when removing one link or one joint disconnects the chain's closed part: the
    incidence graph after pruning nodes with one neighbour again and again (an open branch
    ending in a single-joint link does not split the chain's mobility)."""
    g = incidence_graph(joints, links)
    while True:
        ends = [x for x in g if g.degree(x) <= 1]
        if not ends:
            break
        g.remove_nodes_from(ends)
    return g.number_of_nodes() > 2 and next(nx.articulation_points(g), None) is not None


def is_planar(joints, links: int) -> bool:
    return nx.check_planarity(incidence_graph(joints, links))[0]


def _strip(t) -> tuple[int, ...]:
    t = list(t)
    while t and t[-1] == 0:
        t.pop()
    return tuple(t)


def code_key(joints, links: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """``(assortment, composition)`` with trailing zeros stripped.

    assortment = (n2, n3, n4, ...): n_i = number of links on i joints;
    composition = (v2, v3, ...): v_k = number of joints joining k + 1 links.
    """
    deg = Counter(i for j in joints for i in j)
    dcount = Counter(deg[i] for i in range(links))
    top = max(dcount) if dcount else 1
    assortment = _strip(dcount.get(i, 0) for i in range(2, top + 1))
    mult = Counter(len(j) for j in joints)
    mtop = max(mult) if mult else 2
    composition = _strip(mult.get(k + 1, 0) for k in range(2, mtop))
    return assortment, composition


_NM = nx.algorithms.isomorphism.categorical_node_match(["kind", "mark"], [None, 0])


def _invariant(g: nx.Graph) -> str:
    return nx.weisfeiler_lehman_graph_hash(g, node_attr="kind", iterations=4)


def fixed_link_orbits(joints, links: int) -> int:
    """Number of orbits of the automorphism group on links.

    Links a and b are in the same orbit iff the chain with a marked is
    isomorphic to the chain with b marked (networkx VF2; no automorphism
    group machinery).  Equals the number of distinct mechanisms obtained by
    choosing the fixed link.
    """
    g = incidence_graph(joints, links)
    reps: list[nx.Graph] = []
    for a in range(links):
        ga = g.copy()
        nx.set_node_attributes(ga, 0, "mark")
        ga.nodes[("L", a)]["mark"] = 1
        if not any(nx.is_isomorphic(ga, r, node_match=_NM) for r in reps):
            reps.append(ga)
    return len(reps)


# --------------------------------------------------------------------------
# Results and identification
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class BruteChain:
    joints: tuple[tuple[int, ...], ...]
    links: int
    code_key: tuple[tuple[int, ...], tuple[int, ...]]
    v: int
    planar: bool
    fixed_link_orbits: int
    fractionated: bool = False
    h: int = 3

    @property
    def p(self) -> int:
        return sum(len(j) - 1 for j in self.joints)

    @property
    def dof(self) -> int:
        return mobility(self.joints, self.links, self.h)


class ChainIndex:
    """Identify chains up to isomorphism without nauty.

    Buckets by (links, joint count, code key, Weisfeiler-Lehman hash of the
    incidence graph with node attribute 'kind'), then networkx VF2
    ``is_isomorphic`` (node_match on 'kind') inside the bucket.  ``find``
    returns the index of the isomorphic stored chain or ``None``.
    """

    def __init__(self, chains=()):
        self._buckets: dict[tuple, list[tuple[int, nx.Graph]]] = {}
        self.size = 0
        for c in chains:
            self.add(c.joints, c.links)

    def _key(self, joints, links, g):
        return (links, len(joints), code_key(joints, links), _invariant(g))

    def find(self, joints, links: int):
        joints = _norm(joints)
        g = incidence_graph(joints, links)
        for idx, h in self._buckets.get(self._key(joints, links, g), ()):
            if nx.is_isomorphic(g, h, node_match=_NM):
                return idx
        return None

    def add(self, joints, links: int) -> int:
        """Add a chain (must not be isomorphic to a stored one); return its index."""
        joints = _norm(joints)
        g = incidence_graph(joints, links)
        key = self._key(joints, links, g)
        bucket = self._buckets.setdefault(key, [])
        for idx, h in bucket:
            if nx.is_isomorphic(g, h, node_match=_NM):
                raise ValueError(f"chain {joints} duplicates stored chain #{idx}")
        bucket.append((self.size, g))
        self.size += 1
        return self.size - 1


def count_by_code(chains) -> dict:
    """Number of chains per code key ``(assortment, composition)``."""
    return dict(Counter(c.code_key for c in chains))


def engine_counts_by_key(by_code: dict) -> dict:
    """The engine's counts by code name (``'440/0'``, ``'6301/2'``) under the oracle's keys
    ``(assortment, composition)``, trailing zero counts stripped (a code that writes no composition has
    its v ternary joints): only the names are read by the engine's parser, no count."""
    from synth import Code

    def stripped(counts):
        counts = list(counts)
        while counts and counts[-1] == 0:
            counts.pop()
        return tuple(counts)

    def key(name):
        code = Code.parse(name)
        return stripped(code.assortment), stripped(code.composition or ((code.v,) if code.v else ()))

    return {key(name): n for name, n in by_code.items()}


# --------------------------------------------------------------------------
# Packed all-subsets sub-chain check (pruning rule 2)
# --------------------------------------------------------------------------

_FW = 8            # bits per subset field
_OFF = 1 << (_FW - 1)


class _SubsetChecker:
    """Track ``load(S) = sum_j max(m_j(S) - 1, 0)`` for all 2**n subsets at once.

    The vector over subsets is packed into one Python int, ``_FW`` bits per
    subset.  ``cap`` holds ``limit(S) + _OFF`` with
    ``limit(S) = floor((3(|S| - 1) - need) / 2)`` (the largest load for which
    ``W(S) >= need``); unconstrained subsets get ``2 * _OFF - 1``.  Since
    ``0 <= load <= p < _OFF``, ``cap - load`` has no borrow between fields and
    a field's top bit is set iff ``load(S) <= limit(S)``.
    """

    def __init__(self, links: int, p: int, rigid_subchains: bool, h: int = 3):
        if p >= _OFF or h * links >= _OFF:
            raise ValueError("too many joints for the packed checker")
        self.n = links
        full = (1 << links) - 1
        need = 0 if rigid_subchains else 1
        cap = 0
        high = 0
        for s in range(1 << links):
            k = s.bit_count()
            constrained = k >= 2 and (rigid_subchains or s != full)
            val = (h * (k - 1) - need) // (h - 1) + _OFF if constrained else 2 * _OFF - 1
            cap |= val << (_FW * s)
            high |= _OFF << (_FW * s)
        self.cap = cap
        self.high = high

    def vector(self, jmask: int) -> int:
        vec = 0
        for s in range(1 << self.n):
            c = (s & jmask).bit_count() - 1
            if c > 0:
                vec |= c << (_FW * s)
        return vec

    def ok(self, load: int) -> bool:
        return (self.cap - load) & self.high == self.high

    def load_of(self, joints) -> int:
        total = 0
        for j in joints:
            total += self.vector(sum(1 << i for i in j))
        return total


# --------------------------------------------------------------------------
# The enumerator
# --------------------------------------------------------------------------

def brute_force_chains(
    links: int,
    dof: int,
    *,
    v_max: int = 0,
    rigid_subchains: bool = False,
    fractionated: bool = True,
    h: int = 3,
    n1: tuple[int, int] = (0, 0),
    max_multiplicity: int | None = None,
    stats: dict | None = None,
) -> list[BruteChain]:
    """All connected chains with ``links`` links and mobility ``dof`` in motion space ``h``,
    closed (default) or with ``n1[0] … n1[1]`` single-joint links, and joints of at most
    ``max_multiplicity`` links (default: no limit but v_max + 2).

    One representative per isomorphism class, for every v in ``0..v_max``,
    satisfying the sub-chain convention chosen by ``rigid_subchains`` (checked
    exhaustively over all link subsets) and keeping (``fractionated=True``) or
    dropping fractionated chains.  See the module docstring for the method
    and why each pruning rule is safe (with h for 3 and h - 1 for 2, and 1 for
    the least degree of an open chain's links).  If ``stats`` is a dict it
    receives counters (search nodes, leaves).

    Returns a list sorted by (v, code key, joints).
    """
    n = links
    if n < 2 or dof < 0:
        return []
    times_p = h * (n - 1) - dof
    if times_p % (h - 1):
        return []
    p = times_p // (h - 1)
    K = p - n + 1
    if K < 1 and n1[1] == 0 or K < 0:
        return []
    least = 1 if n1[1] > 0 else 2  # fewest joints on a link
    # two joints sharing two links: W = 2 - h for that pair, below the convention unless h = 2 with rigid
    # sub-chains allowed; only then may a new joint hold two links that already share one
    linear = 2 - h < (0 if rigid_subchains else 1)
    # rule 5: Σ deg = p + J ≤ 2p, every other link has 2 joints (n1 of them may have 1); n − 1 needs linearity
    maxdeg = min(n - 1, 2 * K + n1[1]) if linear else 2 * K + n1[1]

    cands = [c for m in range(2, v_max + 3) if m <= n and (max_multiplicity is None or m <= max_multiplicity)
             for c in itertools.combinations(range(n), m)]
    cands.sort()
    cmask = [sum(1 << i for i in c) for c in cands]
    checker = _SubsetChecker(n, p, rigid_subchains, h)
    cvec = [checker.vector(mk) for mk in cmask]
    cindex = {mk: k for k, mk in enumerate(cmask)}

    deg = [0] * n
    adj = [0] * n
    chosen: list[int] = []
    seen: set[int] = set()
    index = ChainIndex()
    results: list[BruteChain] = []
    counters = Counter()

    def prefix_valid(a: int) -> bool:
        # links < a are closed: degree >= 2 and non-increasing;
        # open links may not already exceed deg(a - 1).
        for x in range(a):
            if deg[x] < least or (x and deg[x] > deg[x - 1]):
                return False
        if a:
            lim = deg[a - 1]
            for y in range(a, n):
                if deg[y] > lim:
                    return False
        return True

    def relabellings(joint_masks: list[int]):
        # all permutations inside blocks of equal degree (contiguous labels)
        blocks = []
        start = 0
        for x in range(1, n + 1):
            if x == n or deg[x] != deg[start]:
                blocks.append(list(range(start, x)))
                start = x
        for parts in itertools.product(*(itertools.permutations(b) for b in blocks)):
            perm = [y for part in parts for y in part]
            code = 0
            for jm in joint_masks:
                img = 0
                x = 0
                while jm:
                    if jm & 1:
                        img |= 1 << perm[x]
                    jm >>= 1
                    x += 1
                code |= 1 << cindex[img]
            yield code

    def leaf():
        counters["leaves"] += 1
        if not prefix_valid(n) or not n1[0] <= deg.count(1) <= n1[1]:
            return
        code = 0
        for k in chosen:
            code |= 1 << k
        if code in seen:
            return
        counters["classes_seen"] += 1
        masks = [cmask[k] for k in chosen]
        before = len(seen)
        seen.update(relabellings(masks))
        assert code in seen and len(seen) > before
        joints = tuple(cands[k] for k in chosen)
        # independent confirmation that this is a new class
        index.add(joints, n)
        if not is_connected(joints, n):
            return
        frac = is_fractionated(joints, n)
        if frac and not fractionated:
            return
        if not subchain_ok(joints, n, rigid_subchains, h):  # plain re-check
            raise AssertionError(f"packed sub-chain check let {joints} through")
        results.append(BruteChain(
            joints=_norm(joints),
            links=n,
            code_key=code_key(joints, n),
            v=sum(len(j) - 2 for j in joints),
            planar=is_planar(joints, n),
            fixed_link_orbits=fixed_link_orbits(joints, n),
            fractionated=frac,
            h=h,
        ))

    # candidate index ranges by first element
    first_start = {}
    for k, c in enumerate(cands):
        first_start.setdefault(c[0], k)

    def rec(start: int, p_used: int, v_used: int, load: int):
        counters["nodes"] += 1
        if p_used == p:
            leaf()
            return
        budget = p - p_used
        cur_a = -1
        cap = maxdeg
        for k in range(start, len(cands)):
            c = cands[k]
            a = c[0]
            if a != cur_a:
                cur_a = a
                if not prefix_valid(a):
                    break                   # invalid for every larger a too
                cap = deg[a - 1] if a else maxdeg
                deficit = sum(least - deg[y] for y in range(a, n) if deg[y] < least)
                skip_group = deficit > 2 * budget
            if skip_group:
                continue
            m = len(c)
            if m - 1 > budget or v_used + m - 2 > v_max:
                continue
            mk = cmask[k]
            if any((linear and adj[x] & mk) or deg[x] >= cap for x in c):
                continue
            new_load = load + cvec[k]
            if not checker.ok(new_load):
                continue
            for x in c:
                deg[x] += 1
                adj[x] |= mk & ~(1 << x)
            chosen.append(k)
            rec(k + 1, p_used + m - 1, v_used + m - 2, new_load)
            chosen.pop()
            for x in c:
                deg[x] -= 1
                adj[x] &= ~(mk & ~(1 << x))

    rec(0, 0, 0, 0)
    if stats is not None:
        stats.update(counters)
        stats["labelled_seen"] = len(seen)
    results.sort(key=lambda c: (c.v, c.code_key, c.joints))
    return results


@functools.lru_cache(maxsize=None)
def _once(links: int, dof: int, v_max: int, rigid_subchains: bool, fractionated: bool) -> tuple[BruteChain, ...]:
    return tuple(brute_force_chains(links, dof, v_max=v_max, rigid_subchains=rigid_subchains,
                                    fractionated=fractionated))


def brute_force_chains_once(links: int, dof: int, *, v_max: int = 0, rigid_subchains: bool = False,
                            fractionated: bool = True) -> tuple[BruteChain, ...]:
    """``brute_force_chains`` of a closed planar query, computed once in a session: the test
    modules that check the oracle against published counts and the engine against the oracle ask
    it the same queries (2-DOF chains of 9 links: 5 s each).

    >>> len(brute_force_chains_once(8, 1)), brute_force_chains_once(8, 1) is brute_force_chains_once(8, 1)
    (16, True)
    """
    return _once(links, dof, v_max, rigid_subchains, fractionated)
