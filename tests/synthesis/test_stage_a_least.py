"""A count's and a listing's stage A keep only the least labelling of each branch multigraph (benchmarks/PROFILE.md
§31 and §46): the kernel's test of a least labelling against every relabelling of equal vertices on small
multigraphs; the classes of the count's stream unchanged (each once) on every code of 12 and 14 links and of the
stage-A test queries, with the test's budget ample and with a budget of one node (where it must keep what it
cannot show smaller); a listing's chains the same whichever labelling of H they are placed on."""

from __future__ import annotations

import itertools
import random

import numpy as np
import pytest

import synth
from synth.synthesis import stage_a
from synth.synthesis._stage_a_kernel import _least_labelling
from synth.synthesis.type_synthesis import plan_jobs

from .test_kernels import QUERIES, _ids


def _upper_rows(A, order):
    """A relabelled by ``order`` (position i holds vertex order[i]), read row by row along the upper
    triangle, each row from its diagonal."""
    m = len(order)
    return [A[order[i]][order[j]] for i in range(m) for j in range(i, m)]


def _least_by_every_relabelling(A, classes) -> bool:
    m = len(classes)
    runs = [list(group) for _, group in itertools.groupby(range(m), key=lambda u: classes[u])]
    own = _upper_rows(A, list(range(m)))
    for parts in itertools.product(*(itertools.permutations(run) for run in runs)):
        if _upper_rows(A, [u for part in parts for u in part]) < own:
            return False
    return True


def _call(A, classes, budget, known=None):
    m = len(classes)
    first = np.array([1 if u == 0 or classes[u] != classes[u - 1] else 0 for u in range(m)], dtype=np.int64)
    work = np.zeros((m, m), dtype=np.int64), np.zeros((m, m), dtype=np.int64), np.zeros(m, dtype=np.int64)
    return _least_labelling(np.array(A, dtype=np.int64), m, m if known is None else known, first, budget, *work)


def test_the_least_labelling_is_the_least_by_every_relabelling_of_equal_vertices():
    """2 000 random multigraphs of 2–7 vertices in runs of equal ones (loops on the diagonal, up to 3
    strings a pair, some with automorphisms by construction), against all relabellings (up to 7!); with
    a small budget, and with only the first rows known (as in the search), a labelling is dropped only
    where it is not least."""
    rng = random.Random(41)
    kept = dropped = partial = 0
    for _ in range(2000):
        m = rng.randint(2, 7)
        classes = sorted(rng.randint(0, rng.randint(0, 2)) for _ in range(m))
        A = [[0] * m for _ in range(m)]
        for u in range(m):
            for v in range(u, m):
                A[u][v] = A[v][u] = rng.choice((0, 0, 0, 1, 1, 2, 3))
        if rng.random() < 0.3:  # a relabelling of a symmetric one: least or not, with automorphisms
            for u in range(m):
                for v in range(m):
                    A[u][v] = A[m - 1 - u][m - 1 - v] = max(A[u][v], A[m - 1 - u][m - 1 - v])
            classes = [0] * m
        least = _least_by_every_relabelling(A, classes)
        assert bool(_call(A, classes, 10**9)) == least, (A, classes)
        if not _call(A, classes, 3):
            assert not least, (A, classes)  # a small budget drops only what is not least
        for known in range(1, m):  # rows from ``known`` on not read: no completion of them is least
            if not _call(A, classes, 10**9, known):
                other = [row[:] for row in A]
                for u in range(known, m):
                    for v in range(u, m):
                        other[u][v] = other[v][u] = rng.choice((0, 1, 2))
                assert not least and not _least_by_every_relabelling(other, classes), (A, other, classes, known)
                partial += 1
        kept += least
        dropped += not least
    assert kept > 300 and dropped > 300 and partial > 300


def _jobs():
    jobs = {}
    for query in [dict(dof=1, links=12), dict(dof=1, links=14)] + [q for q in QUERIES if not q.get("v")]:
        for code, conv in plan_jobs(synth.ChainQuery.of(**query)):
            if stage_a._branch_vertices(code) and stage_a._stage_a_kernel_applies(code, conv):
                jobs[code, conv] = None
    return list(jobs)


def test_a_counts_stream_meets_the_same_classes_each_once_with_fewer_labellings(monkeypatch):
    """Every code of 12 and 14 links (W = 1) and of the stage-A test queries (h = 2…6, W = 0…3, open
    chains, both conventions) through the kernel: the set of certificates of the count's stream is the
    one without the least-labelling test, each met once, with the default budget and with 1 node."""
    monkeypatch.setattr(stage_a, "_CONDITION_BATCH", 7)  # resumed batches too
    jobs = _jobs()
    assert len(jobs) > 150
    classes = 0
    for code, conv in jobs:
        before = [graph.certificate for graph in stage_a._kernel_stream(code, conv, 0)]
        for budget in (stage_a._LEAST_BUDGET, 1):
            after = [graph.certificate for graph in stage_a._kernel_stream(code, conv, budget)]
            assert len(after) == len(set(after)) and set(after) == set(before), (str(code), conv, budget)
        classes += len(before)
    assert classes > 1500


def test_a_count_and_a_listing_use_the_least_labelling_test(monkeypatch):
    """The count's stream and the listing's stage A (:func:`contracted_graphs`) both ask for the test (16 ternary
    links: 212 classes, one labelling each, against 18 160 labellings without it)."""
    code, conv = synth.Code.parse("4.12.0.0.0.0.0/0"), stage_a.Conventions()
    calls = []
    real = stage_a._kernel_stream
    monkeypatch.setattr(stage_a, "_kernel_stream", lambda *args: calls.append(args[2:]) or real(*args))
    assert len(list(stage_a.contracted_stream(code, conv))) == 212 and calls == [(stage_a._LEAST_BUDGET,)]
    assert len(stage_a.contracted_graphs(code, conv)) == 212 and calls[1:] == [(stage_a._LEAST_BUDGET,)]


@pytest.mark.parametrize("query", [dict(dof=2, links=10, h=2), dict(dof=1, links=9, h=2)], ids=_ids)
def test_a_listings_chains_do_not_depend_on_the_labelling_of_h(query, monkeypatch):
    """The listing's units (the least labelling of each H, the compiled stage A on every code) are the units of
    each class's first labelling (the listing's stage A before) in the same order, and where the two labellings
    of an H differ (39 and 6 H of these queries, 27 of the 39 with 57 chains: the first labelling found is
    mostly the least) they give the same chains, numbered and ordered alike — each renumbered canonically, a
    unit's sorted by certificate."""
    from synth.synthesis.type_synthesis import Unit, job_units, run_unit

    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})
    relabelled, chains = 0, 0
    for code, conv in plan_jobs(synth.ChainQuery.of(**query)):
        if not stage_a._branch_vertices(code) or not stage_a._stage_a_kernel_applies(code, conv):
            continue
        least = job_units((code, conv))
        first = [Unit(code, graph, conv) for graph in sorted(stage_a._kernel_stream(code, conv, 0),
                                                             key=lambda graph: graph.certificate)]
        assert [u.key for u in least] == [u.key for u in first], str(code)
        for a, b in zip(least, first):
            if a.contracted.edges != b.contracted.edges:
                relabelled += 1
                listed = [c.to_dict() for c in run_unit(a)]
                assert listed == [c.to_dict() for c in run_unit(b)], a.key
                chains += len(listed)
    assert relabelled and (chains or query["links"] == 9)
