"""Any gear train by its lever analogue (issue 28 #4): the engine's W, sub-chain verdict and lever
analogue against an independent count of the freedoms — the rank of the train's velocity
constraints with each mesh a higher pair (tests/oracles/gear_mobility.py, no engine code) — on
random small trains; the source's planetary result through the general path.
"""

from __future__ import annotations

import random
from fractions import Fraction as Fr

import pytest

from synth.analysis.chains import analyze_chain
from synth.analysis.repair import chain_repairs, redundant_joints
from synth.gears import GearTrain
from synth.gears.planetary import planetary_row, planetary_train
from synth.structure.chain import Chain
from synth.structure.kinds import lever_analogue
from synth.structure.subchains import check_subchains
from tests.oracles import gear_mobility as oracle


def _random_chain(rng: random.Random):
    """A connected chain of 3 … 7 links with pins (some on three links) and gear meshes anywhere,
    no two joints on the same two links: (links, pins, meshes)."""
    n = rng.randint(3, 7)
    pins, meshes, used = [], [], set()

    def free(a, b):
        return frozenset((a, b)) not in used

    def join(a, b, kind):
        used.add(frozenset((a, b)))
        (pins if kind == "pin" else meshes).append((a, b))

    for x in range(1, n):  # a random tree first: the chain is connected
        join(rng.randrange(x), x, rng.choice(["pin", "pin", "mesh"]))
    for _ in range(rng.randint(0, n + 2)):
        a, b = rng.sample(range(n), 2)
        if free(a, b):
            join(a, b, rng.choice(["pin", "mesh", "mesh"]))
    if rng.random() < 0.4:  # a pin on three links: two pins of one link merged
        for i, p in enumerate(pins):
            for j, q in enumerate(pins[i + 1:], start=i + 1):
                common = set(p) & set(q)
                other = (set(p) | set(q)) - common
                if len(common) == 1 and free(*other):
                    merged = tuple(sorted(set(p) | set(q)))
                    pins = [x for k, x in enumerate(pins) if k not in (i, j)] + [merged]
                    used.add(frozenset(other))
                    return n, pins, meshes
    return n, pins, meshes


def _random_train(rng: random.Random) -> GearTrain:
    """A train of the atlas kind with 4 … 7 links: a random link–axis tree and random meshes at
    distance 4 in it (one or more: rigid and over-constrained trains included)."""
    n = rng.randint(4, 7)
    axes = [[0, 1]]
    for x in range(2, n):
        if rng.random() < 0.4:
            rng.choice(axes).append(x)
        else:
            axes.append([rng.randrange(x), x])
    plain = GearTrain(n, axes, [])
    candidates = [(a, b) for a in range(n) for b in range(a + 1, n)
                  if GearTrain._carriers_or_none(n, plain.axes, [(a, b)])[0] is not None]
    if not candidates:  # a tree without two axes on one link: no room for a mesh
        return _random_train(rng)
    chosen = rng.sample(candidates, rng.randint(1, len(candidates)))
    internal = [rng.random() < 0.3 for _ in chosen]
    return GearTrain(n, axes, chosen, internal=internal)


def _chain(n, pins, meshes) -> Chain:
    return Chain(n, list(pins) + list(meshes), ["revolute"] * len(pins) + ["mesh"] * len(meshes))


def _compare(chain: Chain, pins, contacts) -> None:
    n = chain.links
    truth = oracle.mobility(n, pins, contacts)
    eqs = oracle.rows(range(n), pins, contacts)
    independent = oracle.rank(eqs) == len(eqs)
    ok, worst, low = oracle.subsets_verdict(n, pins, contacts, least=0 if chain.dof == 0 else 1)
    lever = lever_analogue(chain)
    a = analyze_chain(chain)
    assert a.dof == truth, chain.compact()  # the generic mobility
    assert lever.dof == chain.dof == a.dof_count  # the lever analogue keeps the count
    if independent:
        assert lever.dof == truth, chain.compact()
    assert a.lever_analogue == str(lever.code)
    if chain.dof >= 0:  # the exact test on the train and on its lever analogue, against every subset
        assert (a.subchain_defect == "none") == ok, (chain.compact(), worst, low)
        assert check_subchains(lever, rigid_subchains=chain.dof == 0).ok == ok, chain.compact()


def test_random_chains_with_meshes_against_the_velocity_rank():
    rng = random.Random(2028)
    verdicts = set()
    for _ in range(120):
        n, pins, meshes = _random_chain(rng)
        chain = _chain(n, pins, meshes)
        if not meshes:
            continue
        placed, contacts = oracle.generic_geometry(n, pins, meshes, rng)
        _compare(chain, placed, contacts)
        verdicts.add(analyze_chain(chain).subchain_defect)
    assert {"none", "rigid sub-chain"} <= verdicts  # both answers were met


def test_random_trains_against_their_gear_geometry():
    """Atlas-like trains with the contact on the line of centres and a pressure angle: the generic
    count of the lever analogue is the train's own mobility."""
    rng = random.Random(30)
    kinds = set()
    for _ in range(80):
        train = _random_train(rng)
        chain = train.to_chain()
        pins, contacts = oracle.train_geometry(train.links, train.axes, train.triples, rng, train.internal)
        generic = oracle.generic_geometry(train.links, train.axes, train.meshes, rng)
        assert oracle.mobility(train.links, pins, contacts) == oracle.mobility(train.links, *generic)
        _compare(chain, pins, contacts)
        kinds.add((train.dof >= 1, analyze_chain(chain).subchain_defect))
    assert len(kinds) >= 3


# ------------------------------------------------------------------ the source's planetary train
def _planetary_geometry(satellites: int, sun: str):
    """The planetary train as built: ring, carrier and (fixed) sun about the origin, planets on
    the carrier at radius 5 on rational points of the circle, sun radius 2, planet radius 3,
    ring radius 8, every contact on a line of centres with a 3-4-5 pressure angle."""
    spots = [(5, 0), (3, 4), (-4, 3), (0, -5), (-3, -4), (4, -3)][:satellites]
    pins = [((0, 0), (0, 1) + ((2,) if sun == "fixed" else ()))]
    contacts = []
    for k, (x, y) in enumerate(spots):
        p = 3 + k
        pins.append(((Fr(x), Fr(y)), (1, p)))
        ux, uy = Fr(x, 5), Fr(y, 5)  # unit vector to the planet
        for gear, r in ((0, 8), (2, 2)):  # ring contact at radius 8, sun contact at radius 2
            cx, cy = r * ux, r * uy
            nx, ny = -uy * Fr(4, 5) + ux * Fr(3, 5), ux * Fr(4, 5) + uy * Fr(3, 5)  # tilted tangent
            contacts.append((gear, p, (cx, cy), (nx, ny)))
    return 3 + satellites, pins, contacts


@pytest.mark.parametrize("satellites", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("sun", ["floating", "fixed"])
def test_planetary_rows_through_the_general_path(satellites, sun):
    """W and D of ``planetary`` are the general analysis of the train; the built train's velocity
    rank moves it with one freedom whenever a satellite is there, its redundant constraints are
    −D (a fixed sun or more than three satellites), and W = 1, D = 0 only for the source's train and the simple planetary."""
    row = planetary_row(satellites, sun)
    train = planetary_train(satellites, sun)
    a = analyze_chain(train.to_chain(), dof=1)
    assert (row.dof, row.loops, row.defect, row.code) == (a.dof_count, a.loops, a.defect,
                                                                       a.lever_analogue)
    n, pins, contacts = _planetary_geometry(satellites, sun)
    built = oracle.mobility(n, pins, contacts)
    eqs = oracle.rows(range(n), pins, contacts)
    redundant = len(eqs) - oracle.rank(eqs)
    # a floating sun with one satellite swings about it; with two, it also slides between them
    free = {("floating", 1): 3, ("floating", 2): 2}.get((sun, satellites), 1)
    assert built == free
    assert row.dof + redundant == built  # the count, plus what the built geometry makes redundant
    if built == 1:
        assert redundant == -row.defect
    assert row.determinate == ((sun, satellites) in {("floating", 3), ("fixed", 1)})


def test_three_satellites_64200_through_the_general_path():
    text = "0-1 1-3 1-4 1-5 0~3i 0~4i 0~5i 2~3@1 2~4@1 2~5@1"
    a = analyze_chain(GearTrain.parse(text).to_chain(), dof=1)
    assert (a.lever_analogue, a.dof, a.dof_count, a.loops, a.defect) == ("64200/0", 1, 1, 5, 0)
    assert a.subchain_defect == "none" and a.redundant_joints is None
    assert planetary_row(3).train == GearTrain.parse(text).to_chain().compact()


def test_four_satellites_name_the_redundant_meshes():
    """D = −1: any one of the eight meshes can go (each planet beyond the third is redundant)."""
    chain = planetary_train(4).to_chain()
    a = analyze_chain(chain, dof=1)
    assert a.defect == -1 and len(a.redundant_joints) == 8 and "carry the redundant" in a.advice
    for j in a.redundant_joints:
        rest = [(x, k) for x, k in zip(chain.joints, chain.kinds) if list(x) != j]
        fixed = Chain(chain.links, [x for x, _ in rest], [k for _, k in rest])
        assert analyze_chain(fixed, dof=1).subchain_defect == "none" and fixed.dof == 1
    assert redundant_joints(planetary_train(3).to_chain(), 1) is None


# ------------------------------------------------------------------ repairs of chains with meshes
@pytest.mark.parametrize("text,dof", [
    ("0-1 1-3 1-4 1-5 1-6 0~3 0~4 0~5 0~6 2~3 2~4 2~5 2~6", 1),  # four satellites: D = −1
    ("0-1 1-3 0~3 2~3", 1),  # one satellite: the sun swings (W = 3)
    ("0-1-2 2-3 0~3 1~3 0~1", 1),  # a mesh between two gears on one axis: a rigid pair
    ("0-1 1=2 2-3 3-0 0~2", 1),  # a mesh with a slider
])
def test_repairs_keep_kinds_and_are_distinct(text, dof):
    chain = Chain.parse(text)
    repairs = chain_repairs(chain, dof=dof, limit=50)
    assert repairs
    certificates = [Chain.parse(r.chain).certificate for r in repairs]
    assert len(set(certificates)) == len(certificates)  # no chain twice
    for r in repairs:
        fixed = Chain.parse(r.chain)
        assert fixed.dof == dof and check_subchains(fixed).ok and fixed.is_connected()
        assert r.code == str(fixed.code) + fixed.kind_suffix
        # kinds are kept: the edits add revolute joints, remove or add meshes by name only
        kinds = fixed.kinds
        edits = " ".join(r.edits)
        assert kinds.count("prismatic") == chain.kinds.count("prismatic") - sum(
            e.count("=") for e in r.edits if e.startswith("remove the binary"))
        assert kinds.count("mesh") == (chain.kinds.count("mesh") + edits.count("mesh links")
                                       - edits.count("remove the gear mesh")
                                       - sum(e.count("~") for e in r.edits if e.startswith("remove the binary")))
        assert all(k == "revolute" for j, k in zip(fixed.joints, kinds) if len(j) > 2)


def test_edits_never_merge_a_mesh_and_add_revolute_joints():
    from synth.analysis.repair import chain_edits

    chain = Chain.parse("0-1 1~2 2-0 0~3 3-1")
    for words, edited in chain_edits(chain):
        kinds = edited.kinds
        assert all(k == "revolute" for j, k in zip(edited.joints, kinds) if len(j) > 2)
        if words.startswith("add a binary link"):
            assert [k for j, k in zip(edited.joints, kinds) if chain.links in j] == ["revolute", "revolute"]
        if words.startswith("merge"):
            assert "~" not in words
        meshes = sum(k == "mesh" for k in kinds)
        assert meshes == 2 + words.startswith("mesh links") - words.startswith("remove the gear mesh") - (
            words.startswith("remove the binary link") and "~" in words)
