"""The compiled kernels of stages A and B against the CP-SAT models they stand in for: stage A's
branch multigraphs code by code, stage B's placements of the binary links unit by unit (and the
direct listing checked by the exact sub-chain test on every subset).  Small queries do not load
the kernels (a second per process), so these tests force them on every code."""

from __future__ import annotations

import pytest

import synth
from synth.synthesis import stage_a, stage_b

from .kernel_units import kernel_units

# every kind of unit the kernel takes: h = 2…6, W = 0…3, both conventions, open chains (leaves),
# loops, fractionated and non-fractionated, planar only, prismatic skeletons (slack: lower thresholds)
QUERIES = [
    dict(dof=1, links=12), dict(dof=0, links=9), dict(dof=2, links=11, fractionated=False), dict(dof=2, links=11),
    dict(dof=3, links=10, n1=(0, 3)), dict(dof=1, links=7, h=2), dict(dof=2, links=8, h=2), dict(dof=1, links=11, h=4),
    dict(dof=1, links=14, h=5), dict(dof=1, links=12, h=6), dict(dof=2, links=9, rigid_subchains=True),
    dict(dof=3, links=10), dict(dof=4, links=9, n1=(1, 4)),
    dict(dof=1, links=10, planar_only=True), dict(dof=2, links=9, h=4, rigid_subchains=True),
    # multiple joints: the kernel's weaker rule, then the exact test
    dict(dof=1, links=10, v=(1, 8)), dict(dof=0, links=9, v=(1, 4)), dict(dof=1, links=7, h=2, v=(1, 3)),
    dict(dof=1, links=6, h=2, v=(1, 2), rigid_subchains=True), dict(dof=1, links=11, h=4, v=(1, 4)),
    dict(dof=2, links=9, v=(1, 7)), dict(dof=3, links=8, v=(1, 4), n1=(0, 2)),
]


# the same kinds of unit, larger: 7 loops of h = 2 (20 CPU s a test; 5 loops stay in QUERIES)
SLOW_QUERIES = [pytest.param(dict(dof=1, links=9, h=2), marks=pytest.mark.slow, id="dof=1,links=9,h=2")]


def _ids(query):
    return ",".join(f"{k}={v}" for k, v in query.items())


@pytest.fixture
def kernel_everywhere(monkeypatch):
    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})


@pytest.mark.parametrize("query", QUERIES + SLOW_QUERIES, ids=_ids)
def test_the_kernel_finds_the_model_placements(query, kernel_everywhere, monkeypatch):
    """Unit by unit, the kernel's placements are the CP-SAT model's (whose conditions are the exact
    test for simple joints), one per orbit of Aut(H) the same way; and the listing's read of more
    rows than its first pass holds (``_KERNEL_ROWS``) loses none."""
    compared = 0
    for u, args in kernel_units(query):
        graph = args[1]
        monkeypatch.setattr(stage_b, "_KERNEL_ROWS", 1)
        kernel, whole, checked = stage_b._distributions(*args, None)
        simple = all(vertex.is_link for vertex in graph.vertices)
        assert checked == simple  # multiple joints: a weaker rule, then the exact test
        with monkeypatch.context() as model_only:
            model_only.setattr(stage_a, "_KERNEL_LOOPS", {None: 10**6})
            model_only.setattr(stage_b, "_FEW_VECTORS", 0)
            model, model_whole, model_checked = stage_b._distributions(*args, None)
        assert whole == model_whole
        if whole:  # the model's lex-leader and its filter keep the lex-least vector of each orbit, as the kernel
            if simple:
                assert sorted(kernel) == sorted(model), u.key
            valid = stage_b._passing(graph, u.conventions, kernel, None, checked)
            assert sorted(valid) == sorted(stage_b._passing(graph, u.conventions, model, None, model_checked)), u.key
        assert stage_b.count_realised(*args) == len(stage_b.realise(*args)), u.key
        compared += 1
    assert compared


@pytest.mark.parametrize("query", QUERIES + SLOW_QUERIES, ids=_ids)
def test_the_kernel_placements_pass_the_exact_test_on_every_subset(query, kernel_everywhere):
    """Every placement the kernel keeps is a chain that the independent test (every subset of links)
    passes, and no valid placement of the direct listing is missing."""
    from synth.structure.subchains import check_subchains

    compared = 0
    for u, (_, graph, conv) in kernel_units(query):
        kernel, whole, checked = stage_b._distributions(u.code, graph, conv, None)
        kernel = stage_b._passing(graph, conv, kernel, None, checked)
        for s in kernel:
            chain = stage_b._expand(graph.vertices, graph.edges, s, conv.h)
            report = check_subchains(chain, rigid_subchains=conv.rigid_subchains)
            assert report.worst_mobility >= conv.threshold, (u.key, s)
        lows, parallel = stage_b._string_limits(graph, conv)
        spare = u.code.count(2) - sum(lows)
        if whole and spare >= 0 and len(graph.edges) <= 14:
            listed = stage_b._few_distributions(lows, spare, parallel, graph, None)[0]
            valid = stage_b._passing(graph, conv, listed, None)
            assert sorted(valid) == sorted(kernel), u.key
            compared += 1
    assert compared


# (W = 0 with the non-degenerate rule: the whole chain is exempt, a unit the kernel does not take)
@pytest.mark.parametrize("query", QUERIES + SLOW_QUERIES + [dict(dof=1, links=6, prismatic="0.."), dict(dof=1, links=8, prismatic="0..2", cylinders="swinging=2"),
                                             dict(dof=0, links=9, rigid_subchains=False), dict(dof=1, links=8, v=(0, 3))],
                         ids=_ids)
def test_counts_and_listings_by_code_are_the_same_with_the_kernel(query, monkeypatch):
    """Counts by code with and without the kernel, and the listing with it, agree."""
    without = synth.count_chains(**query, workers=1)["by_code"]
    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})
    assert synth.count_chains(**query, workers=1)["by_code"] == without and without
    listed: dict = {}
    for chain in synth.type_synthesis(**query, workers=1):
        key = str(chain.code) + chain.kind_suffix
        listed[key] = listed.get(key, 0) + 1
    assert listed == without


# 8 links of h = 2 here, 10 in the slow set (17 CPU s)
STAGE_A_QUERIES = QUERIES + [dict(dof=1, links=14), dict(dof=1, links=8, h=2), dict(dof=0, links=11),
                             dict(dof=1, links=12, planar_only=True), dict(dof=1, links=8, prismatic="0.."),
                             dict(dof=2, links=9, fractionated=False, n1=(0, 2))]


@pytest.mark.parametrize("query", STAGE_A_QUERIES + SLOW_QUERIES + [
    pytest.param(dict(dof=1, links=10, h=2), marks=pytest.mark.slow, id="dof=1,links=10,h=2")], ids=_ids)
def test_stage_a_kernel_finds_the_model_branch_multigraphs(query, kernel_everywhere, monkeypatch):
    """Code by code, the kernel's branch multigraphs (pebble games for the sub-chain conditions on sets of links,
    those with multiple joints on each complete multigraph, batches of 3 to exercise the resumed search) are the
    CP-SAT model's or the plain search's, each once, in the same order; each in its least labelling where the
    kernel's test shows it, which need not be the model's first (a listing's chains do not depend on it:
    tests/synthesis/test_stage_a_least.py)."""
    _kernel_against_model(query, monkeypatch, 3, lambda code, conv: [
        graph.certificate for graph in stage_a.contracted_graphs(code, conv)])


def _kernel_against_model(query, monkeypatch, batch, kernel_certificates, joints_only=False):
    """Code by code of ``query`` where the kernel applies (with a multiple joint only, if asked), the certificates
    ``kernel_certificates(code, conv)`` gives with the kernel's search in batches of ``batch`` equal those of the
    CP-SAT model's or the plain search's branch multigraphs, in order; some are compared."""
    from synth.synthesis.type_synthesis import plan_jobs

    monkeypatch.setattr(stage_a, "_CONDITION_BATCH", batch)
    compared = 0
    for code, conv in plan_jobs(synth.ChainQuery.of(**query)):
        if (joints_only and not code.v) or not stage_a._stage_a_kernel_applies(code, conv):
            continue
        kernel = kernel_certificates(code, conv)
        with monkeypatch.context() as model_only:
            model_only.setattr(stage_a, "_KERNEL_LOOPS", {None: 10**6})
            model = [graph.certificate for graph in stage_a.contracted_graphs(code, conv)]
        assert kernel == model, code
        compared += len(model)
    assert compared


@pytest.mark.parametrize("query", [q for q in STAGE_A_QUERIES if q.get("v")], ids=_ids)
def test_a_counts_stage_a_stream_with_multiple_joints_is_the_models_each_once(query, kernel_everywhere, monkeypatch):
    """Codes with multiple joints: the stream a count reads (the kernel's least labellings, each class once)
    holds the certificates of the model's or the plain search's branch multigraphs, none lost or doubled."""
    _kernel_against_model(query, monkeypatch, 5, lambda code, conv: sorted(
        graph.certificate for graph in stage_a.contracted_stream(code, conv)), joints_only=True)


@pytest.mark.parametrize("code", ["8800000/2-1", "760100/1", "10.4.0.0.0.0/2-2", "941000/2-1", "530/1"])
def test_stage_a_kernels_joint_conditions_are_meet_compiled(code):
    """The kernel's check of the sub-chain conditions with multiple joints against ``_StringBounds.meet`` (numpy,
    the model's and the plain search's) on 3 000 random multiplicity rows of each code: the same verdicts, and
    both ways met (a check that always says yes or no would fail)."""
    import numpy as np
    from itertools import combinations

    from synth.structure.code import Code
    from synth.synthesis._stage_a_kernel import _joint_conditions_hold

    code, conv = Code.parse(code), stage_a.Conventions()
    vertices = stage_a._branch_vertices(code)
    m = len(vertices)
    pairs = list(combinations(range(m), 2))
    bounds = stage_a._StringBounds(vertices, pairs, code, conv)
    conditions = [c for c in stage_a._subset_conditions(vertices, code.dof(conv.h), conv) if c[1]]
    sets = np.array([(stage_a._mask(TL + TJ), stage_a._mask(TL), stage_a._mask(TJ), bound)
                     for TL, TJ, bound in conditions], dtype=np.int64)
    rng = np.random.default_rng(7)
    X = rng.choice(3, size=(3000, len(pairs)), p=[0.75, 0.2, 0.05]).astype(np.int64)
    Y = rng.choice(2, size=(3000, m), p=[0.9, 0.1]).astype(np.int64)
    strings = np.arange(int(X.max()) + 1)
    lb_of = np.maximum(0, bounds.slope[:, None] * strings[None, :] + bounds.offset[:, None])
    cost_of = (conv.h - 1) * strings[None, :] - lb_of
    pu, pv = np.array(pairs, dtype=np.int64).T.copy()
    slack = code.count(2) - lb_of[np.arange(len(pairs)), X].sum(axis=1) - Y @ bounds.loop
    work = np.zeros(m, dtype=np.int64), np.zeros(len(pairs), dtype=np.int64), np.zeros(len(pairs), dtype=np.int64)
    compiled = [_joint_conditions_hold(m, pu, pv, x, cost_of, s, sets[:, 0], sets[:, 1], sets[:, 2], sets[:, 3], *work)
                for x, s in zip(X, slack)]
    expected = bounds.meet(X, Y, conditions)
    assert compiled == expected.tolist()
    assert 0 < expected.sum() < len(expected)


@pytest.mark.parametrize("pairs, vertices", [(0, 1), (1, 2), (6, 4), (45, 10)])
def test_stage_a_kernel_new_state_holds_every_slot_of_the_search(pairs, vertices):
    """The state :func:`multigraphs` lays out, counted from its slices: depth and started, five values
    per pair (multiplicity, largest left, least weight and game units added, loops' least weight),
    three per vertex (joints left, loops, pebbles), the arcs of the pebble game (vertices²) and the
    binary links used so far; all zero (a search not started) and int64, the kernel's type."""
    from synth.synthesis._stage_a_kernel import new_state

    state = new_state(pairs, vertices)
    assert state.shape == (2 + 5 * pairs + 3 * vertices + vertices ** 2 + 1,)
    assert state.dtype == "int64" and not state.any()
