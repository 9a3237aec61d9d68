"""The exact sub-chain test and ``analyze CHAIN`` against an exhaustive subset check.

``synth.structure.subchains.check_subchains`` never looks at most subsets of links (it scans
sets of core links and closed strings).  Here every verdict it gives — sound or
not, the least mobility, and the worst sub-chain it names — is compared with
``tests/oracles/subchains.py``, which evaluates W(S) on every subset S by the
definition and shares no code with the engine.  The chains are random members of
families chosen to break the test (rigid triangles, over-constrained clusters,
closed strings through one link, parallel and multiple joints, free links, any
W from 0 to 3), with fixed seeds, and are mostly *invalid*: the generated
engine chains of the other tests are all valid and cannot catch a test that is
too lenient.
"""

from __future__ import annotations

import itertools
import json
import random
from collections import Counter

import pytest

from synth import Chain
from synth.analysis.chains import analyze_chain
from synth.structure.subchains import check_subchains, subchain_mobility

from tests.oracles.planarity import planar_verdict  # noqa: E402
from tests.oracles.subchains import FAMILIES, exhaustive_subchains, random_chain, subset_mobility  # noqa: E402

PER_FAMILY = 60  # random chains per family in the default suite (420 in all)
SLOW_PER_FAMILY = 600


def _cases(count: int, seed: int):
    out = []
    for family in FAMILIES:
        rng = random.Random(f"{seed}-{family}")
        out += [(family, *random_chain(rng, family)) for _ in range(count)]
    return out


CASES = _cases(PER_FAMILY, 16)


def _parallel(joints) -> bool:
    """Two joints on the same pair of links (W of that pair is −1)."""
    return any(len(set(a) & set(b)) >= 2 for a, b in itertools.combinations(joints, 2))


def _check(links, joints, rigid):
    chain = Chain(links, joints)
    truth = exhaustive_subchains(links, joints)
    got = check_subchains(chain, rigid_subchains=rigid)
    where = f"chain {chain.compact()} (rigid sub-chains {'allowed' if rigid else 'refused'})"
    assert got.ok == truth.ok(rigid), f"{where}: engine says ok={got.ok}, every subset says {truth.ok(rigid)}"
    assert got.kind == truth.kind(rigid), where
    if truth.least is None:
        return got, truth
    assert got.worst_mobility == truth.least, f"{where}: least W(S) {got.worst_mobility} ≠ {truth.least}"
    # the named sub-chain is proper and really has that mobility, by the definition
    assert 2 <= len(got.worst) < links, where
    assert len(set(got.worst)) == len(got.worst) and all(0 <= x < links for x in got.worst), where
    assert subset_mobility(joints, got.worst) == got.worst_mobility, f"{where}: worst {got.worst}"
    # and it is a smallest one, as documented
    assert len(got.worst) == len(truth.smallest_worst[0]), (
        f"{where}: worst {got.worst} has {len(got.worst)} links, {truth.smallest_worst[0]} has fewer")
    return got, truth


def test_the_families_give_both_verdicts():
    """The sample is not all sound or all unsound, and W = 0 … 3 all occur."""
    verdicts = Counter()
    dofs = Counter()
    for family, links, joints in CASES:
        truth = exhaustive_subchains(links, joints)
        verdicts[family, truth.ok(False)] += 1
        dofs[3 * (links - 1) - 2 * sum(len(j) - 1 for j in joints)] += 1
    for family in FAMILIES:
        assert verdicts[family, False] > 0, family
    assert sum(n for (_, ok), n in verdicts.items() if ok) >= 20
    assert all(dofs[w] > 0 for w in range(4))


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("rigid", [False, True], ids=["nondegenerate", "rigid-allowed"])
@pytest.mark.parametrize("block", [1 << 16, 3], ids=["one block", "blocks of 3 subsets"])
def test_check_subchains_equals_every_subset(family, rigid, block, monkeypatch):
    """The scan agrees with every subset, whether the subsets of the core links come in one block
    or in many (then the least sub-chain and the whole chain fall in later blocks)."""
    import synth.structure.subchains as mobility

    monkeypatch.setattr(mobility, "_BLOCK", block)
    for fam, links, joints in CASES:
        if fam == family:
            _check(links, joints, rigid)


PARALLEL = [(links, joints) for _, links, joints in CASES if _parallel(joints)]


def test_parallel_joints_occur_in_the_sample():
    assert len(PARALLEL) >= 20


def test_least_mobility_with_parallel_joints():
    for links, joints in PARALLEL:
        for rigid in (False, True):
            _check(links, joints, rigid)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(3))
def test_check_subchains_equals_every_subset_many(seed):
    for _, links, joints in _cases(SLOW_PER_FAMILY // 3, 1000 + seed):
        for rigid in (False, True):
            _check(links, joints, rigid)


@pytest.mark.parametrize("text, sound, least", [
    ("0-1 1-2 2-0 0-3 3-4 4-5 5-0", False, 0),       # a rigid triangle closed through link 0
    ("0-1 1-2 2-3 3-0 0-4 4-5 5-6 6-0", True, 1),   # two four-bars through link 0: W(S) = 1
    ("0-1 1-2 2-0", True, 1),                        # the triangle itself: only its proper parts count
    ("0-1 1-2 2-3 3-0 0-4 4-1", False, 0),          # triangle 0-1-4 in a four-bar
    ("0-1 0-1 1-2 2-0", False, -1),                  # two joints between links 0 and 1
    ("0-1-2 1-2 2-3 3-0", False, -1),                # a double joint and a joint on the same pair
    ("0-1-2", True, 1),                              # one double joint: its pairs have W = 1
    ("0-1-2 0-3 3-4 3-5 1-4 2-5", True, 1),          # 51/1: its double joint is listed first
    ("0-1 0-2 0-3 1-2 1-3 2-3", False, 0),          # K4: the whole chain (W = −3) is not a sub-chain
    ("0-2 2-1 0-3 3-1 0-4 4-1 0-5 5-1", False, 0),  # four strings between two links: W = −1, parts 0
    # all but one binary link ties with a smaller sub-chain (found by a search over dense chains)
    ("0-5 0-6 1-2 1-3 1-4 1-6 1-7 2-4 2-5 3-5 3-8 3-9 5-7 5-8 6-9", False, -2),
    ("0-1 0-4 0-5 0-8 1-2 1-3 1-6 1-9 2-4 3-4 3-9 4-7 4-8 5-6 5-7", False, -2),
])

def test_named_chains(text, sound, least):
    joints = [tuple(map(int, j.split("-"))) for j in text.split()]  # built directly: Chain.parse refuses twin joints
    chain = Chain(1 + max(max(j) for j in joints), joints)
    report = check_subchains(chain)
    assert (report.ok, report.worst_mobility) == (sound, least)
    truth = exhaustive_subchains(chain.links, chain.joints)
    assert (truth.ok(False), truth.least) == (sound, least)
    for rigid in (False, True):
        got, _ = _check(chain.links, chain.joints, rigid)
        assert got.threshold == (0 if rigid else 1)


def test_no_proper_subchain():
    """Two links on one joint have no proper sub-chain of two or more links: sound, none named."""
    for joints in ([(0, 1)], [(0, 1, 2), (0, 1)], [(0, 1), (0, 1)]):
        chain = Chain(1 + max(max(j) for j in joints), joints)  # built directly: Chain.parse refuses twin joints
        if chain.links == 2:
            report = check_subchains(chain)
            assert report.ok and report.worst == () and report.threshold == 1


def test_subset_bits_of_wide_cores():
    """The scan reads the subsets of up to 24 core links in blocks: every block's bits and sizes
    are those of the subsets it stands for, the last block cut at 2^c."""
    from synth.structure.subchains import _BLOCK, _block

    for c, start in [(3, 0), (17, _BLOCK), (24, (1 << 24) - _BLOCK), (20, 5 * _BLOCK)]:
        bits, size = _block(c, start)
        assert len(bits) == min(_BLOCK, (1 << c) - start)
        for t in (0, 1, len(bits) // 2, len(bits) - 1):
            T = start + t
            assert bits[t].tolist() == [float(T >> i & 1) for i in range(c)] and size[t] == bin(T).count("1")


def test_core_limit(monkeypatch):
    """The scan is exponential in the non-binary links: up to the limit they are scanned, one
    more is refused with a sentence naming the limit (shown with the limit lowered to 6)."""
    import synth.structure.subchains as mobility
    from synth.errors import MalformedChain

    def ring_on_one_joint(n):  # a loop of n links that all share one more (multiple) joint: n core links
        return Chain(n, [(i, (i + 1) % n) for i in range(n)] + [tuple(range(n))])

    assert mobility.MAX_CORE == 24
    monkeypatch.setattr(mobility, "MAX_CORE", 6)
    chain = ring_on_one_joint(6)
    _check(chain.links, chain.joints, False)
    with pytest.raises(MalformedChain, match="up to 6 non-binary links, not 7"):
        check_subchains(ring_on_one_joint(7))


def test_subchain_mobility_is_the_definition():
    rng = random.Random(5)
    for family, links, joints in CASES[::7]:
        chain = Chain(links, joints)
        for _ in range(5):
            s = rng.sample(range(links), rng.randint(1, links))
            assert subchain_mobility(chain, s) == subset_mobility(joints, s)


# ------------------------------------------------------------------ analyze CHAIN
def _fractionated(links, joints) -> bool:
    """A link or joint whose removal disconnects the closed part of the incidence graph (own
    search; the closed part is what is left after pruning links and joints with one neighbour
    again and again: open branches do not fractionate a chain)."""
    nodes = [("L", i) for i in range(links)] + [("J", k) for k in range(len(joints))]
    adj = {v: set() for v in nodes}
    for k, j in enumerate(joints):
        for x in j:
            adj["L", x].add(("J", k))
            adj["J", k].add(("L", x))
    while any(len(adj[v]) <= 1 for v in adj):
        leaf = next(v for v in adj if len(adj[v]) <= 1)
        for u in adj.pop(leaf):
            adj[u].discard(leaf)
    nodes = list(adj)
    if len(nodes) <= 2:
        return False
    for cut in nodes:
        rest = [v for v in nodes if v != cut]
        seen, todo = {rest[0]}, [rest[0]]
        while todo:
            for u in adj[todo.pop()]:
                if u != cut and u not in seen:
                    seen.add(u)
                    todo.append(u)
        if len(seen) < len(rest):
            return True
    return False


def _expected_analysis(links, joints, dof=None):
    p = sum(len(j) - 1 for j in joints)
    W = 3 * (links - 1) - 2 * p
    K = p - links + 1
    deg = Counter(x for j in joints for x in j)
    truth = exhaustive_subchains(links, joints)
    rigid = (W if dof is None else dof) == 0
    return {
        "links": links, "joints": len(joints), "dof": W, "loops": K, "complexity": K - 1,
        "v": sum(len(j) - 2 for j in joints),
        "degrees": sorted(deg[i] for i in range(links)),
        "subchain_defect": truth.kind(rigid), "least": truth.least,
        "fractionated": _fractionated(links, joints), "planar": planar_verdict(links, joints),
        "connected": True,
    }


ANALYSE = CASES[::3]


@pytest.mark.parametrize("k", range(0, len(ANALYSE), 20))
def test_analyze_chain_verdicts(k):
    for family, links, joints in ANALYSE[k:k + 20]:
        chain = Chain(links, joints)
        want = _expected_analysis(links, joints)
        a = analyze_chain(chain)  # the object: Chain.parse refuses the twin joints some cases have
        got = a.to_dict()
        got["dof_count"], got["dof"] = got["dof"], got["dof_count"]  # the count is the oracle's W here
        for key in ("links", "joints", "dof", "loops", "complexity", "v", "subchain_defect", "fractionated",
                    "planar", "connected"):
            assert got[key] == want[key], (key, chain.compact())
        # the true mobility is the count where nothing is over-constrained (Laman-type counts), else above it
        if want["least"] >= 0 and want["dof"] >= 0:
            assert a.dof == want["dof"] and a.redundant == 0, chain.compact()
        else:
            assert a.dof >= max(want["dof"], 0) and a.redundant == a.dof - want["dof"], chain.compact()
        assert subset_mobility(chain.joints, a.worst_subchain) == a.worst_subchain_mobility
        assert a.worst_subchain_mobility == want["least"]
        # the code is the chain's own link assortment (n2, n3, …) and v
        from synth import Code

        code = Code.parse(a.code)
        n = Counter(want["degrees"])
        assert code.n1 == n[1] and code.assortment == tuple(n[i] for i in range(2, max(n) + 1)) and code.v == want["v"]
        # a chain's own counts satisfy the counting equations: standard when W ≥ 0 and it is closed with K ≥ 1
        if want["dof"] >= 0 and want["loops"] >= 1:
            assert a.standard_code, chain.compact()
        if want["subchain_defect"] == "none":
            assert "acts as one link" not in a.advice
        else:
            assert str(list(a.worst_subchain)) in a.advice


@pytest.mark.parametrize("dof", [0, 1])
def test_analyze_convention_follows_the_requested_dof(dof):
    """``dof=0`` allows rigid sub-chains, any other W refuses them, whatever the chain's own W."""
    for family, links, joints in CASES[1::11]:
        want = exhaustive_subchains(links, joints).kind(dof == 0)
        assert analyze_chain(Chain(links, joints), dof=dof).subchain_defect == want


def test_cli_analyze_chain_json(capsys):
    from mechsynth.cli import main

    for family, links, joints in CASES[::41]:
        chain = Chain(links, joints)
        code = main(["analyze", chain.compact(), "--format", "json"])
        if len({frozenset(j) for j in chain.joints}) < len(chain.joints):  # twin joints: refused as written
            assert code == 2 and "join the same links" in capsys.readouterr().err
            continue
        out = json.loads(capsys.readouterr().out)
        want = _expected_analysis(links, joints)
        assert code in (0, 1)
        assert (out["dof_count"], out["subchain_defect"]) == (want["dof"], want["subchain_defect"])
        assert out["worst_subchain_mobility"] == want["least"]


BATCH_QUERIES = [dict(dof=1, links=8, v="0..4"), dict(dof=0, links=7, v="0..3"), dict(dof=1, links=7, h=2, v="0..3"),
                 dict(dof=2, links=9, h=4, v="0..2"), dict(dof=3, links=8, n1=(0, 3), v="0..2"),
                 dict(dof=1, links=8, v="0..3", rigid_subchains=True), dict(dof=1, links=10, h=5, v="0..2"),
                 dict(dof=2, links=7, h=2, n1=(0, 2), v="0..2")]


@pytest.mark.parametrize("query", BATCH_QUERIES, ids=str)
def test_the_batched_test_of_stage_b_equals_every_subset(query, monkeypatch):
    """Stage B judges all candidate vectors of a unit at once on its branch multigraph (a multiple
    joint is a vertex of h − 1 freedoms, a single-joint link ends a free path).  Every verdict, on
    valid and invalid candidates alike, is that of every subset of links of the chain it stands for
    (tests/oracles/chains.py, any h)."""
    import synth
    from synth.synthesis import stage_b

    from tests.oracles.chains import subchain_ok  # noqa: E402

    monkeypatch.setattr(stage_b, "_FEW_VECTORS", 10**9)  # every placement listed, none pruned by a model
    judged = {True: 0, False: 0}
    for u in synth.plan_units(**query, workers=1):
        if u.contracted is None:
            continue
        vertices, edges, conv = u.contracted.vertices, u.contracted.edges, u.conventions
        candidates = stage_b._distributions(u.code, u.contracted, conv, None)[0]
        if not candidates:
            continue
        for s, ok in zip(candidates, stage_b._exact_test(vertices, edges, candidates, conv)):
            chain = stage_b._expand(vertices, edges, s, conv.h)
            truth = subchain_ok(chain.joints, chain.links, conv.rigid_subchains, conv.h)
            assert bool(ok) == truth, (u.key, s, chain.compact())
            judged[truth] += 1
    assert judged[True] and judged[False]  # both verdicts occur


@pytest.mark.parametrize("query", [dict(dof=1, links=10), dict(dof=1, links=8, v="0..4"),
                                   dict(dof=1, links=7, h=2, v="0..2"), dict(dof=3, links=8, n1=(0, 3), v="0..2")],
                         ids=str)
@pytest.mark.parametrize("pairs", [1, 100], ids=["one candidate a chunk", "a few"])
def test_the_exact_test_gives_the_same_verdicts_in_chunks(query, pairs, monkeypatch):
    """The batched exact test splits a unit's candidates so that its arrays (candidates × subsets)
    stay bounded; one candidate at a time, or a few, gives every verdict of the whole batch."""
    import importlib

    import numpy as np

    from synth.synthesis import stage_b

    mobility = importlib.import_module("synth.structure.subchains")  # (synth.structure.subchains is also a function's name)
    import synth

    units = [u for u in synth.plan_units(**query, workers=1) if u.contracted is not None]
    batches = [(u, stage_b._distributions(u.code, u.contracted, u.conventions, None)[0]) for u in units]
    batches = sorted(((u, s) for u, s in batches if len(s) > 1), key=lambda b: -len(b[1]))[:10]  # the largest
    assert batches
    whole = [stage_b._exact_test(u.contracted.vertices, u.contracted.edges, s, u.conventions) for u, s in batches]
    assert any(not v.all() for v in whole) and any(v.any() for v in whole)
    monkeypatch.setattr(mobility, "_CANDIDATE_SUBSETS", pairs)
    for (u, s), verdicts in zip(batches, whole):
        assert np.array_equal(stage_b._exact_test(u.contracted.vertices, u.contracted.edges, s, u.conventions), verdicts)


@pytest.mark.parametrize("text", ["0-1 1-2 2-0 0-3 4-5 5-6 6-7 7-4", "0-1 1-2 2-3 3-0 4-5 5-6 6-4", "0-1 2-3"])
def test_a_chain_in_pieces_is_refused_in_one_sentence(text):
    """The exact test is defined on a connected chain; pieces get the command line's sentence."""
    from synth.errors import MalformedChain

    with pytest.raises(MalformedChain) as refused:
        check_subchains(Chain.parse(text))
    assert str(refused.value) == "the chain is not connected: every link must be reachable through joints"


def test_a_long_chain_with_few_branch_links():
    """The test scans the subsets of the branch (core) links only: a Watt chain whose strings hold 26
    binary links in all (30 links) is judged exactly, and a triangle closed on one of its links found."""
    def string(a, b, first, n):  # a path of n binary links first … first + n − 1 from link a to link b
        body = list(range(first, first + n))
        return [(a, body[0])] + list(zip(body, body[1:])) + [(body[-1], b)]

    joints = [(0, 1), (2, 3)] + string(0, 2, 4, 8) + string(1, 3, 12, 8) + string(0, 1, 20, 5) + string(2, 3, 25, 5)
    chain = Chain(30, joints)
    report = check_subchains(chain)
    assert report.ok and report.worst_mobility == 1
    loop = Chain(32, joints + [(4, 30), (30, 31), (31, 4)])  # links 4, 30, 31: a rigid triangle
    report = check_subchains(loop)
    assert not report.ok and report.worst_mobility == 0 and report.worst == (4, 30, 31)


def _least_by_every_subset(links, joints, h):
    """The least W(S) over the proper sub-chains (2 ≤ |S| < n), from the definition, any h."""
    masks = [sum(1 << x for x in set(j)) for j in joints]
    least = None
    for s in range(1, (1 << links) - 1):
        size = s.bit_count()
        if size >= 2:
            p = sum(max((s & m).bit_count() - 1, 0) for m in masks)
            w = h * (size - 1) - (h - 1) * p
            least = w if least is None else min(least, w)
    return least


@pytest.mark.parametrize("h", [2, 4, 6])
def test_check_subchains_in_other_motion_spaces_equals_every_subset(h):
    """The random families again, each chain in motion space h: the least W(S) of the scan (longer
    strings of binary links are 'short' when h > 3) is that of every subset."""
    from tests.oracles.chains import subchain_mobility as by_definition  # noqa: E402

    for _, links, joints in CASES[::3]:
        chain = Chain(links, joints, h=h)
        if not chain.is_connected() or links > 14:
            continue
        report = check_subchains(chain)
        least = _least_by_every_subset(links, joints, h)
        if least is not None:
            assert report.worst_mobility == least, (chain.compact(), h)
            assert by_definition(joints, report.worst, h) == least



@pytest.mark.parametrize("h", [2, 3, 4])
@pytest.mark.parametrize("where", [0, 1])
def test_a_closed_string_alone_in_the_batched_test(h, where):
    """Two branch links joined by three strings of one binary link, and a closed string of w binary
    links on one of them (on the first vertex or the second): the batched test's least W(S) over the
    proper sub-chains is that of every subset of the chain, for w = 1 … h + 1."""
    from synth.structure.subchains import least_mobilities

    ends = [[0, 1], [0, 1], [0, 1], [where, where]]
    for w in range(1, h + 2):
        lengths = [1, 1, 1, w]
        joints, nxt = [], 2
        for (a, b), n in zip(ends, lengths):  # the chain itself: each string a path of n binary links
            path = [a] + list(range(nxt, nxt + n)) + [b]
            joints += list(zip(path, path[1:]))
            nxt += n
        got = least_mobilities(h, [True, True], [], ends, [lengths])[0]
        assert got == _least_by_every_subset(nxt, joints, h), (h, where, w)
