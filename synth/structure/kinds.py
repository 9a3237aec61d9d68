"""The mobility joint kinds give a planar chain — revolute, prismatic, gear mesh (their table:
:mod:`synth.structure.joints`).

A pin gives one relative rotation and removes 2 freedoms (a multiple joint ``0-1-2`` is a pin
shared by all its links); a slider one relative translation, removing 2 and fixing the relative
rotation, so a loop of prismatic pairs only is a *wedge loop* (motion space 2) that gives one
freedom back; a gear mesh is a higher pair with two freedoms that removes 1, and its *lever
analogue* is a binary link with a revolute joint on each gear.

The structural count of a set S of links (docs/theory.md, "Joint kinds") sums each kind's
term of the table, h − freedom per pair, and gives back h − x per loop of a kind whose loops
live in motion space x::

    W(S) = 3(|S| − 1) − 2·p(S) − g(S) + c_P(S)

p(S): simple-joint equivalents of the revolute and prismatic joints inside S, g(S): meshes
inside S, c_P(S): the cycle rank of the prismatic pairs inside S (K_2, its wedge loops).  The
ground truth is the *generic mobility*: 3(|S| − 1) minus the rank of the velocity constraints
of S's own pairs at a random configuration, computed exactly in modular arithmetic.  It is
never below the count (the wedge loops' rotation constraints are the only dependencies the
count knows); where it is above, the pairs carry redundant constraints.  A joint is *idle*
when the relative motion of its links is zero on the whole generic motion space.

Example
-------
>>> from synth.structure.chain import Chain
>>> wedge = Chain.parse("0=1 1=2 2=3 3=0")            # four prismatic pairs: a wedge loop
>>> structural_mobility(wedge), generic_mobility(wedge), wedge_loops(wedge)
(2, 2, 1)
>>> locked = Chain.parse("0-2 0-3 0=4 1-2 1-3 1=5 4=5")  # 0=4=5=1 locks the four-bar 0-2-1-3
>>> generic_mobility(locked), idle_joints(locked)
(1, [(0, 2), (0, 3), (1, 2), (1, 3)])
"""

from __future__ import annotations

import random
from typing import TYPE_CHECKING

import numpy as np

from .disjoint import DisjointSets
from .joints import JOINT_KINDS, MESH, PRISMATIC, REVOLUTE

if TYPE_CHECKING:  # the chain calls the counts below; they read a chain and never import its type
    from .chain import Chain

__all__ = ["kind_count", "cycle_rank", "restricted_pairs", "wedge_loops", "kind_loops", "class_loops",
           "structural_mobility", "generic_mobility", "mobility_of",
           "redundant_constraints", "idle_joints", "motion", "lever_analogue", "prismatic_roles"]

_PRIME = 2_147_483_647  # 2^31 − 1: a product of two residues fits in a 64-bit integer
_DRAWS = 2  # random configurations; the largest rank is kept (a draw can only lose rank by chance)


def kind_count(chain: Chain, kind: str) -> int:
    """Number of joints of ``kind``.

    >>> from synth.structure.chain import Chain
    >>> kind_count(Chain.parse("0-1 1=2 2~3 3-0"), "mesh")
    1
    """
    return chain.kinds.count(kind)


def _members(chain: Chain, links) -> set[int]:
    return set(range(chain.links)) if links is None else set(links)


def cycle_rank(nodes, edges) -> int:
    """Independent loops of a graph: its edges minus the edges of a spanning forest (union–find).

    >>> cycle_rank(range(3), [(0, 1), (1, 2), (2, 0)]), cycle_rank(range(4), [(0, 1), (2, 3)])
    (1, 0)
    """
    joined = DisjointSets(nodes)
    return sum(not joined.union(a, b) for a, b in edges)


def wedge_loops(chain: Chain, links=None) -> int:
    """c_P(S): independent loops made only of prismatic pairs among ``links`` (all by default).

    >>> from synth.structure.chain import Chain
    >>> wedge_loops(Chain.parse("0=1 1=2 2=0 2-3 3-0"))
    1
    """
    return kind_loops(chain, PRISMATIC, links)


def kind_loops(chain: Chain, kind, links=None) -> int:
    """Independent loops made only of pairs of ``kind`` among ``links`` (all by default).

    >>> from synth.structure.chain import Chain
    >>> kind_loops(Chain.parse("0~1 1~2 2~0 2-3 3-0"), "mesh"), kind_loops(Chain.parse("0~1 1~2 2-0"), "mesh")
    (1, 0)
    """
    s = _members(chain, links)
    pairs = [j for j, k in zip(chain.joints, chain.kinds) if k == kind and j[0] in s and j[1] in s]
    return cycle_rank(s, pairs)


def restricted_pairs(joint, links) -> list[tuple[int, int]]:
    """A joint restricted to ``links``, as the pairs of a path through those of its links (a pin that
    holds m of them joins them as m − 1 pairs: the loops it closes are the loops of those pairs).

    >>> restricted_pairs((0, 3, 5), {0, 5, 7})
    [(0, 5)]
    """
    inside = [x for x in joint if x in links]
    return list(zip(inside, inside[1:]))


def class_loops(chain: Chain, h: int, links=None) -> int:
    """c_h(S): independent loops made only of links of class ``h`` among ``links`` (all by
    default) — the loops of a heterogeneous chain's base of that class (each joint restricted
    to those links: a pin of m of them closes m − 1 pairs).

    >>> from synth.structure.chain import Chain
    >>> toroid = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h5: 0 1 2 3 4 5")
    >>> class_loops(toroid, 5), class_loops(toroid, 5, [0, 1, 2, 3, 6])
    (1, 0)
    """
    s = _members(chain, links) & {i for i, x in enumerate(chain.classes or ()) if x == h}
    return cycle_rank(s, [pair for j in chain.joints for pair in restricted_pairs(j, s)])


def structural_mobility(chain: Chain, links=None) -> int:
    """The count W(S) of the links ``links`` (the whole chain by default), in the chain's motion space;
    in a heterogeneous chain each base's loops inside S count in their own class x:
    + (h − x)·c_x(S).

    >>> from synth.structure.chain import Chain
    >>> structural_mobility(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), [0, 1, 2, 3])
    1
    >>> structural_mobility(Chain.parse("0~1 1-2 2-0"))   # a mesh and two pins: W = 6 − 4 − 1
    1
    """
    s = _members(chain, links)
    h = chain.h
    removed = 0
    for j, k in zip(chain.joints, chain.kinds):  # a pair removes h − freedom; a pin of m links, m − 1 times that
        inside = sum(1 for x in j if x in s)
        if inside > 1:
            removed += k.removes(h) * (inside - 1)
    extra = sum((h - k.loop_space) * kind_loops(chain, k, s) for k in JOINT_KINDS if k.loop_space is not None)
    extra += sum((h - x) * class_loops(chain, x, s) for x in set(chain.classes or ()) - {h})
    return h * (len(s) - 1) - removed + extra


def _rows(chain: Chain, s: list[int], rng: random.Random) -> np.ndarray:
    """Velocity constraints of the pairs inside ``s`` (columns ω, vx, vy of each link of s, mod p).

    A link's velocity field is (ω, vx, vy) at the origin: a point (x, y) moves at
    (vx − ω·y, vy + ω·x).  A pin at a random point: its links' velocities there agree (two rows
    per link after the first: a multiple joint is one pin).  A slider with a random normal:
    equal ω, and no relative velocity along the normal.  A mesh: no relative velocity along a
    random normal at a random contact point.
    """
    col = {x: 3 * i for i, x in enumerate(s)}
    rows: list[dict[int, int]] = []  # each row's non-zero entries: the matrix is sparse (a pair touches two links)

    def point_row(a, b, x, y, nx, ny):
        row = {}
        for link, sign in ((a, 1), (b, -1)):
            c = col[link]
            row[c], row[c + 1], row[c + 2] = sign * (x * ny - y * nx), sign * nx, sign * ny
        rows.append(row)

    for j, kind in zip(chain.joints, chain.kinds):
        inside = [x for x in j if x in col]
        if len(inside) < 2:
            continue
        x, y = rng.randrange(_PRIME), rng.randrange(_PRIME)
        if kind is REVOLUTE:
            for b in inside[1:]:
                point_row(inside[0], b, x, y, 1, 0)
                point_row(inside[0], b, x, y, 0, 1)
        elif kind is PRISMATIC:
            a, b = inside
            rows.append({col[a]: 1, col[b]: -1})
            point_row(a, b, 0, 0, x, y)
        else:
            point_row(inside[0], inside[1], x, y, rng.randrange(_PRIME), rng.randrange(_PRIME))
    m = np.zeros((len(rows), 3 * len(s)), dtype=np.int64)
    for i, row in enumerate(rows):
        for c, v in row.items():
            m[i, c] = v % _PRIME
    return m


def _echelon(m: np.ndarray) -> tuple[np.ndarray, list[int]]:
    """Reduced row echelon form mod p and its pivot columns.

    >>> _echelon(np.array([[2, 4], [1, 2]], dtype=np.int64))[1]
    [0]
    """
    m = m.copy()
    pivots: list[int] = []
    r = 0
    for c in range(m.shape[1]):
        if r == m.shape[0]:
            break
        nz = np.flatnonzero(m[r:, c])
        if not len(nz):
            continue
        p = r + int(nz[0])
        if p != r:
            m[[r, p]] = m[[p, r]]
        m[r] = m[r] * pow(int(m[r, c]), _PRIME - 2, _PRIME) % _PRIME
        # only the rows with an entry in column c change, and only in the pivot row's non-zero columns:
        # the constraints are sparse, so a chain of n links costs about n² here, not n³
        others = np.flatnonzero(m[:, c])
        others = others[others != r]
        if len(others):
            cols = np.flatnonzero(m[r])
            block = np.ix_(others, cols)
            m[block] = (m[block] - np.outer(m[others, c], m[r, cols]) % _PRIME) % _PRIME
        pivots.append(c)
        r += 1
    return m[:r], pivots


def _best_draw(chain: Chain, s: list[int], seed: int) -> tuple[np.ndarray, list[int]]:
    """The echelon form of the largest rank over a few random configurations."""
    best = None
    for draw in range(_DRAWS):
        reduced = _echelon(_rows(chain, s, random.Random(seed * 7919 + draw)))
        if best is None or len(reduced[1]) > len(best[1]):
            best = reduced
    return best


def generic_mobility(chain: Chain, links=None, *, seed: int = 0) -> int:
    """Mobility of the links ``links`` with their own pairs at a generic configuration (exact).

    3(|S| − 1) minus the rank of the velocity constraints, the rank taken modulo a prime of
    31 bits at random configurations (a wrong answer needs a random draw to hit a root of a
    polynomial: chance below 10⁻⁸).  Defined for planar chains (h = 3).

    >>> from synth.structure.chain import Chain
    >>> generic_mobility(Chain.parse("0-1 1-2 2-3 3-0"))
    1
    >>> generic_mobility(Chain.parse("0-1 1-2 2-3 3-0 0-2 1-3"))   # over-braced: rigid, not −3
    0
    """
    if chain.h != 3:
        raise ValueError("generic mobility is computed for planar chains (h = 3)")
    s = sorted(_members(chain, links))
    if len(s) <= 1:
        return 0
    if links is None and seed == 0:
        return motion(chain)[0]
    return 3 * (len(s) - 1) - len(_best_draw(chain, s, seed)[1])


def mobility_of(chain: Chain) -> int:
    """The chain's true mobility: generic for a planar chain, the count in other motion spaces and
    in heterogeneous chains (whose loops' motion spaces are the designer's statement).

    >>> from synth.structure.chain import Chain
    >>> mobility_of(Chain.parse("0-1 1-2 2-3 3-0 0-2 1-3"))   # over-braced four-bar: rigid
    0
    """
    return generic_mobility(chain) if chain.h == 3 and chain.classes is None else chain.dof


def redundant_constraints(chain: Chain, links=None) -> int:
    """Constraints of the pairs among ``links`` that the others already impose: generic
    mobility minus the count (0 for a chain without over-constrained parts).

    >>> from synth.structure.chain import Chain
    >>> redundant_constraints(Chain.parse("0-1 1-2 2-3 3-0 0-2 1-3"))
    3
    """
    return generic_mobility(chain, links) - structural_mobility(chain, links)


def idle_joints(chain: Chain) -> list[tuple[int, ...]]:
    """Joints whose links never move relative to each other at a generic configuration.

    A pin is idle when its links never turn about it (a multiple joint: when any two of its
    links never do), a slider when it never slides, a mesh when its gears never turn
    relative to each other.  Found on the null space of the velocity constraints, so every
    cause is seen, not only a revolute pair whose links a path of sliders also joins.

    >>> from synth.structure.chain import Chain
    >>> idle_joints(Chain.parse("0=1 1=2 2=3 3-0"))   # 0 and 3 cannot turn: the pin is idle
    [(0, 3)]
    >>> idle_joints(Chain.parse("0-1 1-2 2-3 3-0"))
    []
    """
    return list(motion(chain)[1]) if chain.h == 3 else []


def motion(chain: Chain) -> tuple[int, tuple[tuple[int, ...], ...]]:
    """The generic mobility of a planar chain and its idle joints, from one elimination (kept
    with the chain: the exact test of prismatic variants asks for both).

    >>> from synth.structure.chain import Chain
    >>> motion(Chain.parse("0-2 0-3 0=4 1-2 1-3 1=5 4=5"))
    (1, ((0, 2), (0, 3), (1, 2), (1, 3)))
    """
    found = chain.__dict__.get("_motion")
    if found is not None:
        return found
    s = list(range(chain.links))
    reduced, pivots = _best_draw(chain, s, 0)
    ncols = 3 * chain.links
    free = [c for c in range(ncols) if c not in set(pivots)]
    # null-space basis: one vector per free column (x_free = 1, pivots from the reduced rows)
    basis = np.zeros((len(free), ncols), dtype=np.int64)
    for i, f in enumerate(free):
        basis[i, f] = 1
        basis[i, pivots] = (-reduced[:, f]) % _PRIME
    idle = []
    for j, kind in zip(chain.joints, chain.kinds):
        pairs = [(a, b) for i, a in enumerate(j) for b in j[i + 1:]]
        if kind is PRISMATIC:  # never slides: no relative translation
            moves = any(np.any((basis[:, 3 * a + c] - basis[:, 3 * b + c]) % _PRIME) for a, b in pairs for c in (1, 2))
            if not moves:
                idle.append(j)
        elif any(not np.any((basis[:, 3 * a] - basis[:, 3 * b]) % _PRIME) for a, b in pairs):
            idle.append(j)
    found = (3 * (chain.links - 1) - len(pivots), tuple(idle))
    object.__setattr__(chain, "_motion", found)
    return found


def lever_analogue(chain: Chain) -> Chain:
    """The chain with every gear mesh replaced by a binary link carrying a revolute joint on
    each gear (links n, n + 1, … in the order of the meshes): the same mobility, loops and
    sub-chain mobilities, so the exact sub-chain test of the analogue is the test of the train.

    >>> from synth.structure.chain import Chain
    >>> lever_analogue(Chain.parse("0-1 1~2 2-0")).compact()
    '0-1 0-2 1-3 2-3'
    """
    joints, out_kinds, n = [], [], chain.links
    for j, k in zip(chain.joints, chain.kinds):
        if k is MESH:
            joints += [(j[0], n), (n, j[1])]
            out_kinds += [REVOLUTE, REVOLUTE]
            n += 1
        else:
            joints.append(j)
            out_kinds.append(k)
    return type(chain)(n, joints, out_kinds, chain.h)


def prismatic_roles(chain: Chain, frame: int) -> dict[str, int]:
    """The prismatic pairs of a mechanism (``chain`` with ``frame`` fixed) by what they are:

    * ``guide``: a slider on the frame;
    * ``swinging``: a cylinder (a pair between two binary links: the barrel and its rod) one of
      whose links is pinned to the frame;
    * ``floating``: a cylinder both of whose links move, pinned to moving links only;
    * ``slider``: any other pair (a block on a moving link that carries more joints).

    >>> from synth.structure.chain import Chain
    >>> slider_crank = Chain.parse("0-1 1-2 2=3 3-0")
    >>> prismatic_roles(slider_crank, 0), prismatic_roles(slider_crank, 3)
    ({'guide': 0, 'swinging': 1, 'floating': 0, 'slider': 0}, {'guide': 1, 'swinging': 0, 'floating': 0, 'slider': 0})
    """
    roles = dict.fromkeys(("guide", "swinging", "floating", "slider"), 0)
    degree = chain.degrees
    pinned = {x for j, k in zip(chain.joints, chain.kinds) if k is REVOLUTE and frame in j for x in j}
    for (a, b), k in ((j, k) for j, k in zip(chain.joints, chain.kinds) if k is PRISMATIC):
        if frame in (a, b):
            roles["guide"] += 1
        elif degree[a] == degree[b] == 2:
            roles["swinging" if a in pinned or b in pinned else "floating"] += 1
        else:
            roles["slider"] += 1
    return roles
