"""Independent oracle: planar chains with revolute (R) and prismatic (P) pairs, by generic mobility.

Test helper; imports nothing from ``synth`` (numpy, networkx and the standard library only).
It answers: for a mobility W and a number of links n (n <= 7), every non-isomorphic planar closed
chain with simple joints whose generic mobility is exactly W and which is admissible, each joint R
or P, listed and counted by its number of P pairs.

Definitions (the ground truth this module implements)
------------------------------------------------------
* **Chain**: links 0..n-1, joints = pairs (a, b) of distinct links, at most one joint between two
  links, every link on >= 2 joints, the link graph connected; each joint revolute or prismatic.
* **Velocity model**: link i has (omega_i, vx_i, vy_i), the velocity of its point at the origin.
  A revolute pair between a and b at a random point (x, y) equates the two links' velocities of that
  point: rows (-y, 1, 0) and (x, 0, 1) on a, the negatives on b.  A prismatic pair between a and b
  with a random slide normal (nx, ny), independent of any point: omega_a = omega_b, and the relative
  velocity of a w.r.t. b has zero component along the normal: row (0, nx, ny) on a, its negative on
  b (with omega_a = omega_b the relative velocity is the same at every point).  The frame (link 0,
  or the smallest link of a sub-chain) has its three columns deleted.
* **Generic mobility** W = 3(n - 1) - rank of that matrix at a random configuration.  The rank is
  exact: integers modulo the prime p = 2^31 - 1, the points and normals uniform random residues
  (a polynomial identity in them, so Schwartz-Zippel makes a wrong rank a ~1e-8 event per draw);
  the largest rank over up to three seeded draws (the search stops early when a draw reaches the
  rank's upper bound below, since no draw can exceed it).  A computed rank never exceeds the true
  generic rank, so a computed W = 0 (or any computed upper bound on W) is a certificate.
  Sub-chain S: the same with S's links and the pairs joining two links of S.
* **Count** (the wedge rule): 3(n - 1) - 2 * (pairs) + c_P, c_P the cycle rank of the graph of P
  pairs.  **W >= count always**: around every all-P cycle the rows omega_a - omega_b add up to
  zero, c_P independent linear relations among the 2 * pairs rows, so rank <= 2 * pairs - c_P.
  The redundancy D = W - count >= 0 counts the dependencies beyond those; it is monotone: the
  left null space of a sub-chain's rows lies in the whole chain's, and the all-P cycles lying in
  the sub-chain are exactly the sub-chain's own, so D(S) <= D(chain).
* **Admissible**: for W >= 1, every proper subset S of links with |S| >= 2 has generic mobility
  >= 1 (no rigid sub-chain).  A disconnected S has a free part (W(S) >= 3), so only connected
  induced sub-chains are tested, and only those with count(S) <= 0 need a rank (W(S) >= count(S)).
  For W = 0 (trusses) "W(S) >= 0" holds for every S, so taken literally every chain with W = 0
  would be admissible, over-braced ones included (every R/P assignment of K7, for one: none of
  them statically determinate, and no count-based engine lists them).  The oracle keeps the
  trusses of the truss convention: W = 0 and no redundant constraint beyond the wedge relations,
  D = 0, i.e. W = count = 0; by the monotonicity
  of D this implies count(S) >= 0 for every sub-chain (the count convention "rigid sub-chains
  allowed"), and for all-revolute chains it is exactly that convention (Tay's theorem).
* **Idle joint** (W >= 1): the relative motion of its two links is zero on the whole null space:
  R: omega_a - omega_b == 0; P: (vx_a - vx_b, vy_a - vy_b) == 0.  Chains with an idle joint are
  kept apart (``idle=True`` includes them, as the engine's ``--idle-joints``).  For W = 0 the null
  space is {0} and the test would call every joint idle, so it is not applied to trusses.
* **Fractionated**: the link graph has a cut vertex.  Included by default.
* **Isomorphism**: a bijection of links mapping joints to joints of the same kind.  ``canonical``
  is the lexicographically least labelled form over the labellings that order the links by a
  colour-refinement invariant (brute force over permutations inside the invariant classes).

Generation and why each pruning is safe
---------------------------------------
Every unlabelled simple graph up to 7 vertices is in ``networkx.graph_atlas_g()`` exactly once;
the oracle takes those with n vertices, connected, minimum degree >= 2, and every R/P assignment
(bit mask of P edges) up to the graph's automorphisms (networkx VF2; an assignment is processed
only when its mask is the least in its orbit).  Pruning, none of which can drop an answer:

1. count <= W (W >= count): the graph needs 3(n - 1) - 2 * pairs <= W since c_P >= 0.
2. W = 0: count = 0 (W = count is required); since c_P <= pairs - n + 1 this needs pairs <= 2(n - 1).
3. W >= 1, n >= 4: every triangle of the link graph is all-P.  A triangle with an R pair is a
   proper sub-chain of generic mobility 0 (certified by a full-rank draw at import, see
   ``_RIGID_TRIANGLES``), so it would make the chain inadmissible.

Every kept chain carries its count, its generic mobility, its idle joints and whether it is
fractionated; chains with W != count are flagged (``Record.redundancy``).  ``count_misses`` lists
the chains the count alone would place at W (count = W, count(S) >= 1 for every proper S, or >= 0
for trusses) whose generic mobility is not W.  ``rp_survey(..., prune=False)`` evaluates every
assignment orbit with no pruning and no count shortcut (the self-test compares the two at 6 links).

>>> generic_mobility(4, [(0, 1), (1, 2), (2, 3), (3, 0)], "PPPP")
2
>>> rp_counts(1, 4)
{0: 1, 1: 1, 2: 2, 5: 1}
"""

from __future__ import annotations

import itertools
import random
import time
from dataclasses import dataclass
from functools import lru_cache

import networkx as nx
import numpy as np

__all__ = ["PRIME", "Record", "Survey", "canonical", "count_misses", "count_rule", "generic_mobility",
           "idle_joints", "is_fractionated", "rp_chains", "rp_counts", "rp_survey"]

PRIME = 2_147_483_647
_NAMES = ("revolute", "prismatic")
_IS_P = {"revolute": False, "R": False, "-": False, "prismatic": True, "P": True, "=": True}
_DRAWS = 3


# --------------------------------------------------------------------------- chain normal form

def _pairs(joints, kinds) -> tuple[tuple[int, int, bool], ...]:
    """Joints as (a, b, is_prismatic) with a < b, sorted; kinds are names or letters R/P (or -/=)."""
    kinds = list(kinds)
    if len(kinds) != len(joints):
        raise ValueError("one kind per joint")
    out = []
    for (a, b), k in zip(joints, kinds):
        if a == b or k not in _IS_P:
            raise ValueError(f"bad joint {a, b} of kind {k!r}")
        out.append((min(a, b), max(a, b), _IS_P[k]))
    out.sort()
    if len({(a, b) for a, b, _ in out}) != len(out):
        raise ValueError("two joints between the same two links")
    return tuple(out)


def _cycle_rank(links, pairs) -> int:
    """Cycle rank of the multigraph of the given pairs on the given links: E − V + components."""
    graph = nx.MultiGraph()
    graph.add_nodes_from(links)
    graph.add_edges_from(pairs)
    return graph.number_of_edges() - graph.number_of_nodes() + nx.number_connected_components(graph)


def count_rule(n: int, joints, kinds, links=None) -> int:
    """3(|S| - 1) - 2 * pairs(S) + c_P(S) for the links S (default: all n)."""
    s = set(range(n) if links is None else links)
    inside = [(a, b, p) for a, b, p in _pairs(joints, kinds) if a in s and b in s]
    c_p = _cycle_rank(s, [(a, b) for a, b, p in inside if p])
    return 3 * (len(s) - 1) - 2 * len(inside) + c_p


# --------------------------------------------------------------------------- exact linear algebra

def _rref(m: np.ndarray) -> tuple[np.ndarray, list[int]]:
    """Reduced row echelon form modulo PRIME (int64: products stay below 2^62) and pivot columns."""
    m = m % PRIME
    rows, cols = m.shape
    pivots: list[int] = []
    r = 0
    for c in range(cols):
        if r == rows:
            break
        nz = np.flatnonzero(m[r:, c])
        if nz.size == 0:
            continue
        i = r + int(nz[0])
        if i != r:
            m[[r, i]] = m[[i, r]]
        m[r] = m[r] * pow(int(m[r, c]), PRIME - 2, PRIME) % PRIME
        col = m[:, c].copy()
        col[r] = 0
        m = (m - np.outer(col, m[r])) % PRIME
        pivots.append(c)
        r += 1
    return m[:r], pivots


def _draw(seed: str, pairs) -> list[tuple[int, int]]:
    """Random residues per joint: the point (x, y) of an R pair, the normal (nx, ny) of a P pair."""
    rnd = random.Random(seed)
    return [(rnd.randrange(1, PRIME), rnd.randrange(1, PRIME)) for _ in pairs]


def _matrix(pairs, values, links) -> np.ndarray:
    """Velocity constraints of the pairs joining two of ``links`` (sorted; the first is the frame)."""
    col = {x: 3 * (i - 1) for i, x in enumerate(links)}      # the frame gets -3: dropped below
    inside = [(a, b, p, v) for (a, b, p), v in zip(pairs, values) if a in col and b in col]
    m = np.zeros((2 * len(inside), 3 * len(links)), dtype=np.int64)
    for k, (a, b, p, (u, w)) in enumerate(inside):
        rows = ((1, 0, 0), (0, u, w)) if p else ((-w, 1, 0), (u, 0, 1))   # P: omega, normal; R: point
        for r, coeffs in enumerate(rows):
            m[2 * k + r, col[a] + 3: col[a] + 6] = coeffs
            m[2 * k + r, col[b] + 3: col[b] + 6] = [-c for c in coeffs]
    return m[:, 3:]


def _rank_bound(pairs, links) -> int:
    """rank <= min(columns, rows - c_P): the wedge relations are dependencies among the rows."""
    s = set(links)
    inside = [(a, b, p) for a, b, p in pairs if a in s and b in s]
    c_p = _cycle_rank(s, [(a, b) for a, b, p in inside if p])
    return min(3 * (len(s) - 1), 2 * len(inside) - c_p)


def _best_draw(pairs, links, seed) -> tuple[int, np.ndarray, list[int]]:
    """(rank, rref, pivots) of the draw with the largest rank among up to _DRAWS draws."""
    bound = _rank_bound(pairs, links)
    best = None
    for t in range(_DRAWS):
        reduced, pivots = _rref(_matrix(pairs, _draw(f"{seed}/{t}", pairs), links))
        if best is None or len(pivots) > len(best[2]):
            best = (len(pivots), reduced, pivots)
        if best[0] == bound:
            break
    return best


def _mobility(pairs, links, seed) -> int:
    links = sorted(links)
    return 3 * (len(links) - 1) - _best_draw(pairs, links, seed)[0]


def generic_mobility(n: int, joints, kinds, links=None) -> int:
    """3(|S| - 1) - the exact generic rank of the velocity constraints of the links S (default all).

    >>> generic_mobility(3, [(0, 1), (1, 2), (0, 2)], "PPP")   # wedge triangle
    1
    """
    pairs = _pairs(joints, kinds)
    return _mobility(pairs, range(n) if links is None else links, repr((n, pairs)))


def _idle(pairs, n, seed) -> tuple[tuple[int, int], ...]:
    """Joints whose relative motion vanishes on the whole null space (of the best draw)."""
    rank, reduced, pivots = _best_draw(pairs, list(range(n)), seed)
    cols = 3 * (n - 1)
    free = [c for c in range(cols) if c not in set(pivots)]
    basis = np.zeros((cols, len(free)), dtype=np.int64)    # columns: null-space vectors
    for j, f in enumerate(free):
        basis[f, j] = 1
        for r, pc in enumerate(pivots):
            basis[pc, j] = -reduced[r, f] % PRIME
    out = []
    for a, b, p in pairs:
        funcs = []
        for part in ((1, 2) if p else (0,)):                   # P: vx, vy; R: omega
            f = np.zeros(cols, dtype=np.int64)
            if a:
                f[3 * (a - 1) + part] = 1
            if b:
                f[3 * (b - 1) + part] = -1
            funcs.append(f)
        if all(not np.any(f @ basis % PRIME) for f in funcs):   # two entries ±1: no overflow
            out.append((a, b))
    return tuple(out)


def idle_joints(n: int, joints, kinds) -> tuple[tuple[int, int], ...]:
    """Joints (a, b), a < b, whose relative motion is zero on the whole generic null space.

    >>> idle_joints(4, [(0, 1), (1, 2), (2, 3), (3, 0)], "PPPR")   # the R pair cannot turn
    ((0, 3),)
    """
    pairs = _pairs(joints, kinds)
    return _idle(pairs, n, repr((n, pairs)))


def is_fractionated(n: int, joints) -> bool:
    """A cut vertex in the link graph."""
    g = nx.Graph(list(joints))
    g.add_nodes_from(range(n))
    return next(nx.articulation_points(g), None) is not None


# --------------------------------------------------------------------------- isomorphism

def canonical(n: int, joints, kinds) -> tuple[tuple[tuple[int, int], ...], tuple[str, ...]]:
    """Least labelled form (joints sorted, kinds aligned) over the refinement-ordered labellings."""
    pairs = _pairs(joints, kinds)
    nbrs = {x: [] for x in range(n)}
    for a, b, p in pairs:
        nbrs[a].append((b, p))
        nbrs[b].append((a, p))
    colour = {x: 0 for x in range(n)}
    for _ in range(n):                                          # colour refinement to a fixed point
        sig = {x: (colour[x], tuple(sorted((colour[y], p) for y, p in nbrs[x]))) for x in range(n)}
        order = sorted(set(sig.values()))
        new = {x: order.index(sig[x]) for x in range(n)}
        if len(set(new.values())) == len(set(colour.values())):
            colour = new
            break
        colour = new
    classes = [[x for x in range(n) if colour[x] == c] for c in sorted(set(colour.values()))]
    best = None
    for parts in itertools.product(*(itertools.permutations(c) for c in classes)):
        label = {x: i for i, x in enumerate(y for part in parts for y in part)}
        form = tuple(sorted((min(label[a], label[b]), max(label[a], label[b]), p) for a, b, p in pairs))
        if best is None or form < best:
            best = form
    return tuple((a, b) for a, b, _ in best), tuple(_NAMES[p] for _, _, p in best)


# --------------------------------------------------------------------------- the survey

@dataclass(frozen=True)
class Record:
    """One chain class: canonical joints and kinds, its count and generic mobility, idle joints."""
    joints: tuple[tuple[int, int], ...]
    kinds: tuple[str, ...]
    prismatic: int
    mobility: int
    count: int
    idle: tuple[tuple[int, int], ...]
    fractionated: bool

    @property
    def redundancy(self) -> int:
        """Generic mobility minus the count: dependencies the wedge rule does not see."""
        return self.mobility - self.count

    def text(self) -> str:
        """Joint list in the table notation: ``0-1`` revolute, ``0=1`` prismatic."""
        return " ".join(f"{a}{'=' if k == 'prismatic' else '-'}{b}" for (a, b), k in zip(self.joints, self.kinds))


@dataclass(frozen=True)
class Survey:
    W: int
    n: int
    p_max: int | None                  # None: every number of P pairs
    records: tuple[Record, ...]        # generic mobility W, admissible (idle and fractionated included)
    count_misses: tuple[Record, ...]   # count = W and count-admissible, generic mobility != W
    candidates: int                    # assignment orbits that reached a rank computation
    seconds: float


def _triangle_rigid() -> frozenset[tuple[bool, bool, bool]]:
    """Kinds of the triangle (pairs 0-1, 0-2, 1-2) with generic mobility 0, certified by rank."""
    out = set()
    for kinds in itertools.product((False, True), repeat=3):
        pairs = tuple((a, b, p) for (a, b), p in zip(((0, 1), (0, 2), (1, 2)), kinds))
        if _mobility(pairs, range(3), f"triangle{kinds}") == 0:
            out.add(kinds)
    return frozenset(out)


_RIGID_TRIANGLES = _triangle_rigid()
if _RIGID_TRIANGLES != {k for k in itertools.product((False, True), repeat=3) if not all(k)}:
    raise AssertionError(f"pruning 3 assumes every triangle with an R pair is rigid: {_RIGID_TRIANGLES}")


def _automorphisms(g: nx.Graph, edges) -> list[tuple[int, ...]]:
    """Edge permutations induced by the graph's automorphisms (VF2)."""
    index = {e: i for i, e in enumerate(edges)}
    out = []
    for m in nx.algorithms.isomorphism.GraphMatcher(g, g).isomorphisms_iter():
        out.append(tuple(index[tuple(sorted((m[a], m[b])))] for a, b in edges))
    return out


def _least_in_orbit(mask: int, tables) -> bool:
    for t0, t1, t2 in tables:
        if t0[mask & 255] | t1[(mask >> 8) & 255] | t2[mask >> 16] < mask:
            return False
    return True


def _byte_tables(perm):
    tabs = []
    for byte in range(3):
        t = [0] * 256
        for v in range(256):
            img = 0
            for bit in range(8):
                e = 8 * byte + bit
                if v >> bit & 1 and e < len(perm):
                    img |= 1 << perm[e]
            t[v] = img
        tabs.append(t)
    return tabs


def _connected_subsets(n, adj):
    """Proper link subsets S, 2 <= |S| < n, whose induced link graph is connected (bit masks)."""
    out = []
    for s in range(1, (1 << n) - 1):
        if s & (s - 1) == 0:
            continue
        start = s & -s
        seen, todo = start, start
        while todo:
            x = (todo & -todo).bit_length() - 1
            todo &= todo - 1
            new = adj[x] & s & ~seen
            seen |= new
            todo |= new
        if seen == s:
            out.append(s)
    out.sort(key=lambda s: (s.bit_count(), s))
    return out


def _sub_count(pairs, s_links) -> int:
    inside = [(a, b, p) for a, b, p in pairs if a in s_links and b in s_links]
    return 3 * (len(s_links) - 1) - 2 * len(inside) + _cycle_rank(s_links, [(a, b) for a, b, p in inside if p])


@lru_cache(maxsize=None)
def rp_survey(W: int, n: int, p_max: int | None = None, *, prune: bool = True) -> Survey:
    """Classify every R/P chain of n links (at most ``p_max`` P pairs) that can have generic
    mobility W (see the module doc).  ``prune=False`` (the oracle's self-test) skips the prunings
    and the sub-chain count shortcut: every assignment orbit gets its ranks."""
    if not (W >= 0 and 3 <= n <= 7):
        raise ValueError("W >= 0 and 3 <= n <= 7 (graph atlas)")
    t0 = time.perf_counter()
    base = 3 * (n - 1)
    records, misses, candidates = [], [], 0
    for g in nx.graph_atlas_g():
        if g.number_of_nodes() != n or not nx.is_connected(g) or min(d for _, d in g.degree()) < 2:
            continue
        edges = sorted(tuple(sorted(e)) for e in g.edges())
        m = len(edges)
        if prune and (base - 2 * m > W or (W == 0 and m > 2 * (n - 1))):  # prunings 1 and 2
            continue
        forced = 0
        if prune and W >= 1 and n >= 4:                                    # pruning 3
            for i, (a, b) in enumerate(edges):
                if any(g.has_edge(a, c) and g.has_edge(b, c) for c in range(n)):
                    forced |= 1 << i
        free = [i for i in range(m) if not forced >> i & 1]
        budget = len(free) if p_max is None else min(len(free), p_max - forced.bit_count())
        if budget < 0:
            continue
        tables = [_byte_tables(perm) for perm in _automorphisms(g, edges)]
        adj = [sum(1 << y for y in g[x]) for x in range(n)]
        subsets = None
        masks = (forced | sum(1 << i for i in chosen) for k in range(budget + 1)
                 for chosen in itertools.combinations(free, k))
        for mask in masks:
            c_p = _cycle_rank(range(n), [e for i, e in enumerate(edges) if mask >> i & 1])
            count = base - 2 * m + c_p
            if prune and (count > W or (W == 0 and count != 0)) or not _least_in_orbit(mask, tables):
                continue
            candidates += 1
            pairs = tuple((a, b, bool(mask >> i & 1)) for i, (a, b) in enumerate(edges))
            seed = repr((n, pairs))
            mobility = _mobility(pairs, range(n), seed)
            if mobility < count:
                raise AssertionError(f"rank above its bound for {pairs}")
            if subsets is None:
                subsets = [frozenset(x for x in range(n) if s >> x & 1) for s in _connected_subsets(n, adj)]
            need = 1 if W >= 1 else 0
            if mobility == W and (W >= 1 or count == 0):
                if W >= 1 and any((not prune or _sub_count(pairs, s) <= 0) and _mobility(pairs, s, seed) < 1
                                  for s in subsets):
                    continue
                bucket = records
            elif count == W and all(_sub_count(pairs, s) >= need for s in subsets):
                bucket = misses
            else:
                continue
            joints = [(a, b) for a, b, _ in pairs]
            kinds = [_NAMES[p] for *_, p in pairs]
            cj, ck = canonical(n, joints, kinds)
            bucket.append(Record(joints=cj, kinds=ck, prismatic=sum(k == "prismatic" for k in ck),
                                 mobility=mobility, count=count,
                                 idle=idle_joints(n, cj, ck) if W >= 1 and mobility == W else (),
                                 fractionated=is_fractionated(n, cj)))
    key = lambda r: (r.prismatic, r.joints, r.kinds)  # noqa: E731
    records.sort(key=key)
    misses.sort(key=key)
    forms = [(r.joints, r.kinds) for r in records + misses]
    if len(set(forms)) != len(forms):
        raise AssertionError("two assignment orbits gave the same canonical form")
    return Survey(W, n, p_max, tuple(records), tuple(misses), candidates, time.perf_counter() - t0)


def _select(W, n, p_range, idle, fractionated):
    lo, hi = p_range
    return [r for r in rp_survey(W, n, hi).records
            if lo <= r.prismatic and (hi is None or r.prismatic <= hi)
            and (idle or not r.idle) and (fractionated or not r.fractionated)]


def rp_chains(W: int, n: int, p_range=(0, None), idle: bool = False, fractionated: bool = True):
    """Canonical (joints, kinds) of every admissible chain of n links with generic mobility W whose
    number of P pairs lies in ``p_range`` (inclusive; None: no upper bound), sorted.

    >>> rp_chains(1, 3)   # the wedge triangle
    [(((0, 1), (0, 2), (1, 2)), ('prismatic', 'prismatic', 'prismatic'))]
    """
    return [(r.joints, r.kinds) for r in _select(W, n, p_range, idle, fractionated)]


def rp_counts(W: int, n: int, p_range=(0, None), idle: bool = False, fractionated: bool = True) -> dict:
    """{number of P pairs: number of chains} for ``rp_chains`` with the same arguments."""
    out: dict[int, int] = {}
    for r in _select(W, n, p_range, idle, fractionated):
        out[r.prismatic] = out.get(r.prismatic, 0) + 1
    return dict(sorted(out.items()))


def count_misses(W: int, n: int) -> list[Record]:
    """Chains the count alone places at W (count = W, count(S) >= 1 for proper S; >= 0 for W = 0)
    whose generic mobility differs."""
    return list(rp_survey(W, n).count_misses)
