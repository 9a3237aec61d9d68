"""Verdicts of ``synth.Chain`` and the planar filter against methods that share no code with them.

* planarity: Boyer–Myrvold (the ``planarity`` package) with checked Kuratowski / Euler
  certificates (``tests/oracles/planarity.py``), against ``Chain.is_planar`` (networkx)
  and the engine's ``planar_only`` filter (decided on the branch multigraph);
* fractionation: a link or joint whose removal disconnects the chain, by search;
* symmetry: automorphism group order and link orbits by trying every permutation of
  the links; certificates with joint kinds against VF2 with kind colours.
"""

from __future__ import annotations

import functools
import itertools
import random
from collections import defaultdict

import networkx as nx
import pytest

import synth
from synth import Chain

from tests.oracles.planarity import planar_verdict  # noqa: E402

SAMPLE_12 = 150  # 12-link chains checked by default (fixed seed); all 6856 under -m slow


@functools.lru_cache(maxsize=None)
def chains(W, n, v=0, planar_only=False):
    return tuple(synth.type_synthesis(W, n, v=v, planar_only=planar_only, workers=1))


def _planarity_case(W, n, v, sample=None):
    every = chains(W, n, v)
    kept = {c.certificate for c in chains(W, n, v, planar_only=True)}
    picked = every if sample is None else random.Random(n).sample(every, sample)
    for c in picked:
        truth = planar_verdict(c.links, c.joints)
        assert c.is_planar() == truth, c.compact()
        assert (c.certificate in kept) == truth, c.compact()
    return sum(not planar_verdict(c.links, c.joints) for c in picked)


@pytest.mark.parametrize("W, n, v", [(1, 8, (0, 4)), (2, 9, 0), (3, 8, (0, 2)), (0, 7, (0, 2))], ids=str)
def test_planarity_by_a_second_method(W, n, v):
    _planarity_case(W, n, v)


def test_ten_link_non_planar_chains():
    """1-DOF, 10 links: 11 of the 230 chains have non-planar graphs (published)."""
    assert _planarity_case(1, 10, 0) == 11


def test_twelve_link_sample():
    _planarity_case(1, 12, 0, sample=SAMPLE_12)


@pytest.mark.slow
def test_twelve_link_non_planar_chains():
    """1-DOF, 12 links: 938 of the 6856 chains have non-planar graphs (published)."""
    assert _planarity_case(1, 12, 0) == 938


def _fractionated(c: Chain) -> bool:
    nodes = [("L", i) for i in range(c.links)] + [("J", k) for k in range(len(c.joints))]
    for cut in nodes:
        g = nx.Graph()
        g.add_nodes_from(x for x in nodes if x != cut)
        g.add_edges_from((("J", k), ("L", x)) for k, j in enumerate(c.joints) for x in j
                         if cut not in (("J", k), ("L", x)))
        if not nx.is_connected(g):
            return True
    return False


@pytest.mark.parametrize("W, n, v", [(2, 7, (0, 1)), (2, 9, 0), (3, 8, (0, 2)), (0, 7, (0, 2)), (1, 8, (0, 4))], ids=str)
def test_fractionated_by_removing_each_link_and_joint(W, n, v):
    every = chains(W, n, v)
    kept = {c.certificate for c in synth.type_synthesis(W, n, v=v, fractionated=False, workers=1)}
    for c in every:
        truth = _fractionated(c)
        assert c.is_fractionated() == truth, c.compact()
        assert (c.certificate in kept) == (not truth), c.compact()


def _automorphisms(c: Chain) -> list[tuple[int, ...]]:
    """Link permutations that map the multiset of joints onto itself (tried one by one)."""
    joints = sorted(c.joints)
    return [p for p in itertools.permutations(range(c.links))
            if sorted(tuple(sorted(p[x] for x in j)) for j in c.joints) == joints]


@pytest.mark.parametrize("W, n, v", [(1, 4, 0), (1, 6, (0, 2)), (2, 5, 0), (2, 7, 0), (3, 6, (0, 3)), (0, 5, 0)], ids=str)
def test_group_order_and_orbits_by_every_permutation(W, n, v):
    for c in chains(W, n, v):
        group = _automorphisms(c)
        _, order, orbits = c.automorphisms()
        assert order == len(group), c.compact()
        brute = [sorted({p[x] for p in group}) for x in range(c.links)]
        assert [sorted(x for x in range(c.links) if orbits[x] == orbits[y]) for y in range(c.links)] == brute
        for frame in range(c.links):  # the stabiliser of a frame
            stab = [p for p in group if p[frame] == frame]
            _, order, orbits = c.automorphisms([frame])
            assert order == len(stab), (c.compact(), frame)
            assert [sorted(x for x in range(c.links) if orbits[x] == orbits[y]) for y in range(c.links)] == [
                sorted({p[x] for p in stab}) for x in range(c.links)], (c.compact(), frame)


_KIND = nx.algorithms.isomorphism.categorical_node_match("colour", None)


def _coloured(c: Chain) -> nx.Graph:
    g = nx.Graph()
    g.add_nodes_from((("L", i), {"colour": "link"}) for i in range(c.links))
    for k, j in enumerate(c.joints):
        g.add_node(("J", k), colour=c.kinds[k])
        g.add_edges_from((("J", k), ("L", x)) for x in j)
    return g


@pytest.mark.parametrize("text", ["0-1 1-2 2-3 3-0", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "0-1 1-2 2-3 3-4 4-5 5-0 0-3"])
def test_certificates_with_joint_kinds_equal_isomorphism(text):
    """Every revolute/prismatic assignment of a chain: equal certificates exactly for isomorphic ones."""
    base = Chain.parse(text)
    kinds = ("revolute", "prismatic")
    variants = [Chain(base.links, base.joints, list(k)) for k in itertools.product(kinds, repeat=len(base.joints))]
    by_cert = defaultdict(list)
    for c in variants:
        by_cert[c.certificate].append(c)
    reps = [group[0] for group in by_cert.values()]
    for group in by_cert.values():
        assert all(nx.is_isomorphic(_coloured(group[0]), _coloured(c), node_match=_KIND) for c in group), text
    for a, b in itertools.combinations(reps, 2):
        assert not nx.is_isomorphic(_coloured(a), _coloured(b), node_match=_KIND), text
    for c in variants[:: max(1, len(variants) // 12)]:  # mechanisms on chains with kinds: frames apart
        by_cert = defaultdict(set)
        for members in _frame_classes(c):
            for f in members:
                by_cert[synth.Mechanism(c, f).certificate].add(tuple(members))
        assert all(len(v) == 1 for v in by_cert.values()), (text, c.kinds)
        assert len(by_cert) == len(_frame_classes(c)), (text, c.kinds)
    rng = random.Random(7)
    for c in variants:  # and a relabelled copy keeps its certificate
        perm = list(range(c.links))
        rng.shuffle(perm)
        assert c.relabel(perm).certificate == c.certificate


def _frame_classes(c: Chain) -> list[list[int]]:
    """Frames grouped by isomorphism of the chain with that frame marked (VF2 with kind colours)."""
    classes: list[tuple[nx.Graph, list[int]]] = []
    for f in range(c.links):
        g = _coloured(c)
        g.nodes["L", f]["colour"] = "frame"
        for rep, members in classes:
            if nx.is_isomorphic(g, rep, node_match=_KIND):
                members.append(f)
                break
        else:
            classes.append((g, [f]))
    return [m for _, m in classes]


def test_chain_numbers_by_definition():
    """dof, loops, v, p and degrees of every chain of a mixed query, from its joint list."""
    for c in chains(1, 8, (0, 4)) + chains(3, 8, 0) + chains(0, 7, (0, 2)):
        p = sum(len(j) - 1 for j in c.joints)
        assert c.simple_joint_equivalents == p
        assert c.dof == 3 * (c.links - 1) - 2 * p
        assert c.loops == p - c.links + 1
        assert c.v == sum(len(j) - 2 for j in c.joints)
        assert list(c.degrees) == [sum(x in j for j in c.joints) for x in range(c.links)]
        assert c.is_connected() and Chain.parse(c.compact()) == c


# ------------------------------------------------------------------ reading and refusing chains
@pytest.mark.parametrize("make, sentence", [
    (lambda: Chain(0, []), "a chain needs a whole number of links ≥ 1, not 0"),
    (lambda: Chain(True, [(0, 1)]), "a chain needs a whole number of links ≥ 1, not True"),
    (lambda: Chain(2.0, [(0, 1)]), "a chain needs a whole number of links ≥ 1, not 2.0"),
    (lambda: Chain(3, [(0, "a")]), "each joint must be a list of link numbers"),
    (lambda: Chain(3, [5]), "each joint must be a list of link numbers"),
    (lambda: Chain(3, [(0, 1), (1, 2)], ["revolute"]), "1 joint kinds given for 2 joints"),
    (lambda: Chain(3, [(0, 1), (1, 2)], ["revolute", "screw"]), "joint kind 'screw' is not one of revolute, prismatic"),
    (lambda: Chain(3, [(0, 1), (1, 2)], ["screw", "revolute"]), "joint kind 'screw' is not one of revolute, prismatic"),
    (lambda: Chain(3, [(0, 1), (1,)]), "joint [1] joins fewer than two links"),
    (lambda: Chain(3, [(0, 1), (1, 1)]), "joint [1, 1] names a link twice"),
    (lambda: Chain(3, [(0, 1), (1, 3)]), "joint [1, 3] names a link outside 0…2"),
    (lambda: Chain(3, [(-1, 1), (1, 2)]), "joint [-1, 1] names a link outside 0…2"),
    (lambda: Chain(4, [(0, 1, 4)]), "joint [0, 1, 4] names a link outside 0…3"),
    (lambda: Chain.parse("0-1 1-x"), "cannot read joint '1-x'"),
    (lambda: Chain.parse("  "), "an empty joint list is not a chain"),
    (lambda: Chain.from_json('{"joints": [[0, 1], [1'), "chain JSON is not valid JSON"),
    (lambda: Chain.from_json('{"links": 3}'), "a chain object needs 'joints' (a list of lists of link numbers)"),
    (lambda: Chain.from_json('[1, 2]'), "'joints' must be a list of lists of link numbers"),
    (lambda: Chain.from_json('{"joints": [[0, 1.5]]}'), "joints must list links by whole numbers"),
    (lambda: Chain.from_json('{"joints": [[0, true]]}'), "joints must list links by whole numbers"),
    (lambda: Chain.from_dict("0-1"), "a chain object needs 'joints'"),
    (lambda: Chain.from_dict({"joints": []}), "a chain needs a whole number of links ≥ 1, not 0"),
    (lambda: Chain.parse("0-1 1-2 2-0").relabel([0, 1, 1]), "a relabelling must be a permutation of the links"),
    (lambda: Chain.parse("0-1 1-2 2-0").relabel([0, 1]), "a relabelling must be a permutation of the links"),
    (lambda: synth.Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 4), "fixed link 4 is not a link of the chain"),
    (lambda: synth.Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), -1), "fixed link -1 is not a link of the chain"),
    (lambda: synth.Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 0), "input link 0 is not jointed to the fixed link 0"),
    (lambda: synth.Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 2), "input link 2 is not jointed to the fixed link 0"),
    (lambda: synth.Mechanism(Chain.parse("0-1 1-2-3 3-0"), 0, 2), "input link 2 is not jointed to the fixed link 0"),
])
def test_malformed_chains_refused_with_a_sentence(make, sentence):
    from synth.errors import MalformedChain

    with pytest.raises(MalformedChain) as info:
        make()
    assert str(info.value).startswith(sentence) and "\n" not in str(info.value)


def test_chain_reading_and_writing():
    c = Chain(1, [])
    assert (c.links, c.joints, c.degrees, c.loops, c.is_connected()) == (1, (), (0,), 0, True)
    joints = [(3, 2), (0, 1, 2), (0, 3)]
    c = Chain(4, joints, ["prismatic", "revolute", "revolute"])
    assert c.joints == ((0, 1, 2), (0, 3), (2, 3)) and c.kinds == ("revolute", "revolute", "prismatic")
    plain = Chain(4, joints, ["revolute"] * 3)  # kinds are always a tuple: a plain chain's all revolute
    assert plain.kinds == Chain(4, joints).kinds == ("revolute",) * 3 and plain.all_revolute
    assert plain == Chain(4, joints) and hash(plain) == hash(Chain(4, joints))
    d = c.to_dict()
    assert d["joints"] == [[0, 1, 2], [0, 3], [2, 3]] and d["kinds"] == ["revolute", "revolute", "prismatic"]
    assert (d["links"], d["dof"], d["loops"], d["v"], d["code"]) == (4, c.dof, c.loops, 1, f"{c.code} P1")  # the code says P
    assert d["certificate"] == c.certificate and "kinds" not in Chain(4, joints).to_dict()
    assert Chain.from_dict(d) == c and Chain.from_json(c.to_json()) == c
    assert Chain.from_json("[[0, 1], [1, 2], [2, 0]]") == Chain(3, [(0, 1), (1, 2), (0, 2)])
    assert Chain.from_dict({"joints": [[0, 1], [1, 3]]}).links == 4  # links from the largest number
    assert Chain.parse(" 0-1, 1-2-3  3-0 ") == Chain(4, [(0, 1), (1, 2, 3), (0, 3)])
    assert Chain.parse('{"joints": [[0, 1], [1, 2], [2, 0]]}').links == 3
    assert Chain.parse(c.compact()) == c and c.compact() == "0-1-2 0-3 2=3"
    assert Chain.trusted(3, [(1, 0), (2, 1), (0, 2)]) == Chain(3, [(0, 1), (1, 2), (0, 2)])
    assert Chain.parse("[[0, 1], [1, 2], [2, 0]]") == Chain(3, [(0, 1), (1, 2), (0, 2)])
    assert Chain.from_dict({"links": 5, "joints": [[0, 1], [1, 2], [2, 0]]}).links == 5  # two loose links
    # parallel joints of different kinds are ordered by kind too: the input order does not matter
    a = Chain(3, [(0, 1), (0, 1), (1, 2), (0, 2)], ["prismatic", "revolute", "revolute", "revolute"])
    b = Chain(3, [(0, 1), (0, 1), (1, 2), (0, 2)], ["revolute", "prismatic", "revolute", "revolute"])
    assert a == b and a.kinds == ("prismatic", "revolute", "revolute", "revolute")
    # but two gears mesh once, and never on a common axis
    for kinds in (["mesh", "mesh", "revolute", "revolute"], ["mesh", "revolute", "revolute", "revolute"]):
        with pytest.raises(synth.MalformedChain, match="links 0 and 1 are joined twice, once by a gear mesh"):
            Chain(3, [(0, 1), (0, 1), (1, 2), (0, 2)], kinds)
    for m in (synth.Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1), synth.Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 2),
              synth.Mechanism(Chain.parse("0-1 1-2-3 3-0"), 3, 2)):
        d = m.to_dict()
        assert (d["frame"], d.get("input_link")) == (m.frame, m.input_link)
        assert d["certificate"] == m.certificate and d["chain_certificate"] == m.chain.certificate
        assert ("input_link" in d) == (m.input_link is not None)
        assert (d["joints"], d["code"], d["dof"]) == ([list(j) for j in m.chain.joints], str(m.chain.code), m.chain.dof)


def test_graph_views():
    c = Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1")
    g = c.to_networkx()
    assert g.number_of_nodes() == c.links + len(c.joints)
    assert g.number_of_edges() == sum(len(j) for j in c.joints)
    assert {d["kind"] for _, d in g.nodes(data=True)} == {"link", "joint"}
    assert sorted(d["multiplicity"] for n, d in g.nodes(data=True) if d["kind"] == "joint") == sorted(len(j) for j in c.joints)
    lg = c.link_graph()
    assert sorted(lg.edges()) == [(0, 1), (0, 2), (0, 3), (0, 4), (1, 2), (1, 5), (2, 3), (4, 5)]
    assert not Chain.parse("0-1 1-2 3-4").is_connected() and Chain.parse("0-1 1-2 2-0").is_connected()
    assert Chain.parse("0-1 1-2 2-0 0-3 3-4 4-0").is_fractionated()   # two triangles on link 0
    assert not Chain.parse("0-1 1-2 2-3 3-0").is_fractionated()
    assert Chain(1, []).is_fractionated() is False
    assert not Chain.parse("0-1").is_fractionated()  # an open chain: no closed part to split
    assert not Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5").is_fractionated()  # a loop with an open branch
    assert Chain.parse("0-1 1-2 2-0 0-3 3-4 4-0 4-5").is_fractionated()  # two loops on link 0, and a branch
    assert Chain(2, []).is_fractionated() is False  # two loose links: nothing to remove that splits them
    kinds = Chain(4, [(0, 1), (1, 2), (2, 3), (3, 0)], ["prismatic", "revolute", "revolute", "revolute"])
    assert sorted(d["joint_kind"] for _, d in kinds.to_networkx().nodes(data=True) if d["kind"] == "joint") == [
        "prismatic", "revolute", "revolute", "revolute"]
    assert {d["joint_kind"] for _, d in g.nodes(data=True) if d["kind"] == "joint"} == {"revolute"}


@pytest.mark.parametrize("h", [2, 3, 4, 5, 6])
def test_the_motion_space_stays_with_the_chain(h):
    """A chain keeps its h through relabelling, its closed part, a trusted build and its JSON row
    (where h = 3 is the default and is not written)."""
    import json

    chain = Chain(4, ((0, 1), (1, 2), (2, 0), (2, 3)), h=h)  # a loop of three and a single-joint link
    assert chain.relabel([3, 2, 1, 0]).h == h and chain.closed_part().h == h
    row = chain.to_dict()
    assert ("h" in row) == (h != 3) and row.get("h", 3) == h
    assert Chain.from_dict(json.loads(json.dumps(row))) == chain
    trusted = Chain.trusted(3, [(1, 0), (2, 1), (0, 2)], h)
    assert trusted.h == h and trusted == Chain(3, ((0, 1), (1, 2), (0, 2)), h=h)


@pytest.mark.parametrize("h", [1, 7, 0, True, 3.0, "3"])
def test_a_motion_space_outside_two_to_six_is_refused(h):
    import re

    from synth.errors import MalformedChain

    with pytest.raises(MalformedChain, match=re.escape(f"the motion space h of a chain's loops is 2 … 6, not {h!r}")):
        Chain(3, ((0, 1), (1, 2), (0, 2)), h=h)
    if isinstance(h, bool) or not isinstance(h, int):
        with pytest.raises(MalformedChain, match=re.escape(f"'h' must be a whole number 2 … 6, not {h!r}")):
            Chain.from_dict({"joints": [[0, 1], [1, 2], [0, 2]], "h": h})
    else:
        with pytest.raises(MalformedChain, match=re.escape(f"is 2 … 6, not {h!r}")):
            Chain.from_dict({"joints": [[0, 1], [1, 2], [0, 2]], "h": h})


@pytest.mark.parametrize("h", [2, 4])
def test_synthesised_chains_carry_their_motion_space(h):
    """Stage B builds its chains without checks (Chain.trusted): each still says its h, and its
    certificate tells it from the same graph in another space."""
    chains = list(synth.type_synthesis(dof=1, links=h + 4, h=h, workers=1))
    assert chains
    for chain in chains:
        assert chain.h == h and chain.to_dict()["h"] == h
        assert chain.certificate.startswith(f"h{h}")
        assert chain.certificate != Chain(chain.links, chain.joints, h=3).certificate


def test_group_order_beyond_ten_to_the_ten():
    """nauty reports a group order as grpsize1 · 10^grpsize2 once it passes 10^10: fourteen links on
    one joint are permuted in every way, 14! ≈ 8.7·10^10."""
    import math

    _, order, orbits = Chain(14, (tuple(range(14)),)).automorphisms()
    assert order == pytest.approx(math.factorial(14), rel=1e-9) and len(set(orbits)) == 1
