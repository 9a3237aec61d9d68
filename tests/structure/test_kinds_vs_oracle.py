"""Joint kinds (synth/structure/kinds.py) against the independent R/P oracle, fast enough to judge
every mutant of the module: every R/P assignment of every graph of four links and of a sample of
five-link graphs, every set of links — the count with its own wedge loops, the generic mobility,
the redundancy, the idle joints — and the lever analogue and prismatic roles by their definitions."""

from __future__ import annotations

import itertools
import random

import networkx as nx
import pytest

from synth import Chain
from synth.structure.kinds import (generic_mobility, idle_joints, kind_count, lever_analogue, motion,
                                   prismatic_roles, redundant_constraints, structural_mobility, wedge_loops)
from tests.oracles import gear_mobility
from tests.oracles import rp_chains as oracle


def _graphs(n):
    return [Chain(n, list(g.edges())) for g in nx.graph_atlas_g()
            if g.number_of_nodes() == n and nx.is_connected(g) and min(d for _, d in g.degree()) >= 2]


def _cases():
    rng = random.Random(2811)
    out = []
    for base in _graphs(4) + rng.sample([g for g in _graphs(5) if len(g.joints) <= 7], 3):
        for kinds in itertools.product("RP", repeat=len(base.joints)):
            out.append((base, "".join(kinds)))
    return out


CASES = _cases()


def _chain(base: Chain, kinds: str) -> Chain:
    return Chain(base.links, base.joints, ["prismatic" if k == "P" else "revolute" for k in kinds])


@pytest.mark.parametrize("start", range(0, len(CASES), 128))
def test_every_set_of_links(start):
    for base, kinds in CASES[start:start + 128]:
        chain = _chain(base, kinds)
        n = chain.links
        assert wedge_loops(chain) == oracle.count_rule(n, chain.joints, kinds) - 3 * (n - 1) + 2 * len(chain.joints)
        assert kind_count(chain, "prismatic") == kinds.count("P") and kind_count(chain, "revolute") == kinds.count("R")
        for size in range(1, n + 1):
            for s in itertools.combinations(range(n), size):
                truth = oracle.generic_mobility(n, chain.joints, kinds, links=s)
                count = oracle.count_rule(n, chain.joints, kinds, links=s)
                assert generic_mobility(chain, s) == truth, (chain.compact(), s)
                assert structural_mobility(chain, s) == count, (chain.compact(), s)
                assert redundant_constraints(chain, s) == truth - count, (chain.compact(), s)
        whole = oracle.generic_mobility(n, chain.joints, kinds)
        assert motion(chain)[0] == whole == generic_mobility(chain)
        if whole > 0:
            assert set(idle_joints(chain)) == set(oracle.idle_joints(n, chain.joints, kinds)), chain.compact()


def test_idle_joints_of_every_kind():
    """A pin that never turns, a slider that never slides, a multiple joint two of whose links
    never turn relative to each other; a moving chain has none."""
    assert idle_joints(Chain.parse("0=1 1=2 2=3 3-0")) == [(0, 3)]
    slider = Chain.parse("0-1 1-2 2-0 0=3 3-1")   # 0, 1, 2 a rigid triangle: 3 cannot slide on 0 and pin on 1
    assert (0, 3) in idle_joints(slider)
    assert idle_joints(Chain.parse("0-1 1-2 2-3 3-0")) == [] and idle_joints(Chain.parse("0-1-2 2-3 3-4 4-0")) == []
    locked = Chain(6, [(0, 1, 4), (1, 2), (2, 3), (3, 4), (0, 5), (2, 5)],
                   ["revolute", "prismatic", "prismatic", "prismatic", "revolute", "revolute"])
    assert idle_joints(locked) == [(0, 1, 4)]
    gears = Chain.parse("0-1 0-2 1~2")  # a gear pair on the frame: both turn, the mesh moves
    assert idle_joints(gears) == [] and generic_mobility(gears) == 1
    jammed = Chain.parse("0-1 0-2 1~2 1-3 3-2")  # the gears' centres also held by a link 3: W = 9 − 8 − 1 = 0
    assert generic_mobility(jammed) == structural_mobility(jammed) == 0


def test_meshes_count_one_constraint_and_have_a_lever_analogue():
    """A mesh is a higher pair (two freedoms): W = 3(n − 1) − 2p − g; its lever analogue is a
    binary link with a pin on each gear — the same mobility, every sub-chain's too."""
    train = Chain.parse("0-1-2 2-3 0~3 1~3")   # simple planetary: frame/ring 0, sun 1, carrier 2, planet 3
    analogue = lever_analogue(train)
    assert structural_mobility(train) == 3 * 3 - 2 * 3 - 2 == 1 == generic_mobility(train)
    assert analogue.all_revolute and analogue.links == 6 and analogue.compact() == "0-1-2 0-4 1-5 2-3 3-4 3-5"
    assert generic_mobility(analogue) == 1 == analogue.dof
    for size in range(2, 5):
        for s in itertools.combinations(range(4), size):
            inside = [train.links + k for k, (a, b) in enumerate(j for j, k in zip(train.joints, train.kinds)
                                                                  if k == "mesh") if a in s and b in s]
            assert structural_mobility(train, s) == structural_mobility(analogue, list(s) + inside)
    assert lever_analogue(Chain.parse("0-1 1-2 2-0")) == Chain.parse("0-1 1-2 2-0")
    # a rack (a slider on the frame) and a pinion: the rack keeps its prismatic pair in the analogue
    rack = lever_analogue(Chain.parse("0=1 1~2 2-0"))
    assert [j for j, k in zip(rack.joints, rack.kinds) if k == "prismatic"] == [(0, 1)] and rack.links == 4
    # a chain without meshes comes back as it is, in its own motion space (a wedge triangle, h = 2)
    wedge = Chain(3, [(0, 1), (1, 2), (0, 2)], h=2)
    assert lever_analogue(wedge) == wedge and lever_analogue(wedge).h == 2


def test_a_mesh_inside_a_truss_is_redundant():
    """Gears on two links of a rigid truss (32/0: three dyads between links 0 and 1) cannot turn
    relative to each other: their mesh repeats the truss's constraints.  Every set of links against
    the independent gear oracle (rational rank, its own random geometry): W = 0, the count −1."""
    chain = Chain.parse("0-2 2-1 0-3 3-1 0-4 4-1 2~3")
    pins = [j for j, k in zip(chain.joints, chain.kinds) if k == "revolute"]
    meshes = [j for j, k in zip(chain.joints, chain.kinds) if k == "mesh"]
    placed, contacts = gear_mobility.generic_geometry(5, pins, meshes, random.Random(23))
    for size in range(2, 6):
        for s in itertools.combinations(range(5), size):
            assert generic_mobility(chain, s) == gear_mobility.mobility(5, placed, contacts, s), s
    assert generic_mobility(chain) == 0 and structural_mobility(chain) == -1 and redundant_constraints(chain) == 1


def test_motion_is_kept_with_the_chain():
    """The elimination runs once per chain: a second call hands back the same result."""
    chain = Chain.parse("0-2 0-3 0=4 1-2 1-3 1=5 4=5")
    assert motion(chain) is motion(chain)


def test_generic_mobility_and_idle_joints_are_planar():
    """Outside the plane (a wedge triangle, motion space h = 2: three blocks that slide on each
    other, W = 1) there is no velocity model: generic mobility refuses, and no joint is called idle
    (a planar model would find the pinned triangle rigid and every joint idle)."""
    wedge = Chain(3, [(0, 1), (1, 2), (0, 2)], h=2)
    with pytest.raises(ValueError, match=r"^generic mobility is computed for planar chains \(h = 3\)$"):
        generic_mobility(wedge)
    assert wedge.dof == 1 and idle_joints(wedge) == []


@pytest.mark.parametrize("text, frame, roles", [
    ("0=1 0-3 1-2 2-3", 0, {"guide": 1, "swinging": 0, "floating": 0, "slider": 0}),
    ("0=1 0-3 1-2 2-3", 2, {"guide": 0, "swinging": 1, "floating": 0, "slider": 0}),
    ("0-2 2-1 0-3 3-1 0-4 4=5 5-1", 2, {"guide": 0, "swinging": 0, "floating": 1, "slider": 0}),
    ("0=1 1-2 2-3 3-0 0-4 4-5 5-1", 2, {"guide": 0, "swinging": 0, "floating": 0, "slider": 1}),
    ("0-1 1-2 2=3 3-0 0-4 4=5 5-1", 0, {"guide": 0, "swinging": 2, "floating": 0, "slider": 0}),
    ("0-1 1-2 2-3 3-0", 0, {"guide": 0, "swinging": 0, "floating": 0, "slider": 0}),
    # the trammel of Archimedes: two blocks in the frame's guides and the bar between them
    ("0=1 1-2 2-3 3=0", 0, {"guide": 2, "swinging": 0, "floating": 0, "slider": 0}),
    # Watt's chain with blocks on the ternary link 0: on a moving link that carries more joints
    ("0=1 1-2 2-3 3-0 0=4 4-5 5-1", 2, {"guide": 0, "swinging": 0, "floating": 0, "slider": 2}),
])
def test_prismatic_roles(text, frame, roles):
    assert prismatic_roles(Chain.parse(text), frame) == roles


def _rank_mod_p_slow(rows: list[list[int]], p: int) -> int:
    """Rank mod p by plain Gaussian elimination on Python integers (no numpy): the oracle."""
    rows = [[v % p for v in r] for r in rows]
    rank, cols = 0, len(rows[0]) if rows else 0
    for c in range(cols):
        pivot = next((i for i in range(rank, len(rows)) if rows[i][c]), None)
        if pivot is None:
            continue
        rows[rank], rows[pivot] = rows[pivot], rows[rank]
        inv = pow(rows[rank][c], p - 2, p)
        rows[rank] = [v * inv % p for v in rows[rank]]
        for i in range(len(rows)):
            if i != rank and rows[i][c]:
                f = rows[i][c]
                rows[i] = [(a - f * b) % p for a, b in zip(rows[i], rows[rank])]
        rank += 1
    return rank


@pytest.mark.parametrize("density", [0.05, 0.3, 1.0])
def test_sparse_elimination_is_the_reduced_echelon_form(density):
    """The elimination that touches only non-zero rows and columns gives the reduced row echelon form:
    rows reduced, pivots 1 with zeros above and below, the rank of an independent elimination."""
    import numpy as np

    from synth.structure.kinds import _PRIME, _echelon

    rng = np.random.default_rng(5)
    for _ in range(20):
        r, c = rng.integers(1, 12, size=2)
        m = np.where(rng.random((r, c)) < density, rng.integers(0, _PRIME, size=(r, c)), 0).astype(np.int64)
        if rng.random() < 0.3 and r > 1:
            m[-1] = (m[0] * 3 + m[1 % r]) % _PRIME  # a dependent row
        reduced, pivots = _echelon(m)
        assert len(pivots) == _rank_mod_p_slow(m.tolist(), _PRIME)
        for i, col in enumerate(pivots):
            assert reduced[i, col] == 1 and not np.any(np.delete(reduced[:, col], i))
        # the rows of the reduced form span the rows of m: each row of m is a combination of them
        for row in m:
            left = row.copy()
            for i, col in enumerate(pivots):
                left = (left - left[col] * reduced[i]) % _PRIME
            assert not np.any(left)


def test_a_ring_of_1000_links_is_analysed_and_a_larger_one_refused():
    """A ring of 1000 links (the largest analysed) has W = 997 and its constraints cost about n² (it took
    minutes while the elimination updated the whole matrix for every pivot); 1001 links are refused."""
    from synth import QueryTooLarge, analyze_chain

    ring = lambda n: " ".join(f"{i}-{(i + 1) % n}" for i in range(n))  # noqa: E731
    assert analyze_chain(ring(1000)).dof == 997
    with pytest.raises(QueryTooLarge, match="the chain has 1001 links; chains are analysed here up to 1000 links"):
        analyze_chain(ring(1001))
