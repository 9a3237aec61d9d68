"""Work units of any query, inline or on a pool, give exactly the chains of the query.

``plan_units`` + ``run_unit`` is how atlases and other drivers split a query; it must
give the same chains as ``type_synthesis`` for every option, not only the defaults.
"""

from __future__ import annotations

import math

import pytest

import synth


def _query_id(query):
    """A test id that names a query's options: dof=1,links=8,v=(0, 2)."""
    return ",".join(f"{k}={v}" for k, v in query.items())


QUERIES = [
    dict(dof=1, links=8, v=(0, 2)),
    dict(dof=2, links=7, fractionated=False),
    dict(dof=1, links=10, planar_only=True),
    dict(dof=1, links=10, v=(0, 1), require=["5=1.."]),
    dict(dof=1, links=10, v=(0, 3), cranks={5: 5}),
    dict(dof=1, code="6301/0"),
    dict(dof=0, links=7, rigid_subchains=False),
    dict(dof=2, links=7),  # the default keeps fractionated chains (4 chains, 3 without)
    dict(dof=2, links=7, fractionated=True),
    dict(dof=3, links=6, n1=(0, 2)),
    dict(dof=1, links=6, h=2),
    dict(dof=1, links=8, v=(0, 4), max_multiplicity=3),
]


@pytest.mark.parametrize("query", QUERIES, ids=_query_id)
@pytest.mark.parametrize("workers", [1, 2])
def test_units_give_the_query_chains(query, workers):
    units = synth.plan_units(**query, workers=workers)
    assert len({u.key for u in units}) == len(units)
    flat = [c.certificate for u in units for c in synth.run_unit(u)]
    want = [c.certificate for c in synth.type_synthesis(**query, workers=1)]
    assert flat == want and want
    counted = synth.count_chains(**query, workers=workers)
    assert counted["count"] == len(want)


def test_run_unit_statistics_and_the_single_loop():
    stats: dict = {}
    units = synth.plan_units(1, 8)
    for u in units:
        synth.run_unit(u, stats)
    assert stats["candidates"] >= 16 and {"cpsat_s", "subchain_s", "nauty_s"} <= set(stats)
    (loop,) = synth.plan_units(0, 3)  # the triangle: a code without branch vertices
    assert loop.contracted is None and [c.compact() for c in synth.run_unit(loop)] == ["0-1 0-2 1-2"]
    (four,) = synth.plan_units(1, 4)
    # the four-bar loop 0-1-2-3-0, numbered as every listing and the atlas number it (nauty's canonical labelling)
    assert [c.compact() for c in synth.run_unit(four)] == ["0-1 0-2 1-3 2-3"]


@pytest.mark.parametrize("query", [dict(dof=1, links=10, v=(0, 3)), dict(dof=0, links=9), dict(dof=2, links=9),
                                   dict(dof=1, links=10, cranks={4: 2})], ids=str)
@pytest.mark.parametrize("group_limit,lex_bits", [(4096, 52), (1, 52), (4096, 3)],
                         ids=["whole group", "generators only", "lex-leader on one edge in the model"])
def test_counting_a_unit_equals_its_distinct_chains(query, group_limit, lex_bits, monkeypatch):
    """count_realised counts stage B's vectors when they are one per orbit of Aut(H), else it
    compares certificates (forced here by a group limit of 1): either way it equals realise.  With
    the model's lex-leader cut to one edge the lex-least filter over the solutions keeps one per orbit."""
    from synth.synthesis import stage_a, stage_b

    monkeypatch.setattr(stage_a, "_GROUP_LIMIT", group_limit)
    monkeypatch.setattr(stage_b, "_LEX_BITS", lex_bits)
    monkeypatch.setattr(stage_b, "_FEW_VECTORS", 0)  # every unit through the model
    units = [u for u in synth.plan_units(**query, workers=1) if u.contracted is not None]
    args = [(u.code, u.contracted, u.conventions) for u in units]
    assert [stage_b.count_realised(*a) for a in args] == [len(stage_b.realise(*a)) for a in args]
    assert sum(len(stage_b.realise(*a)) for a in args) > 0


SIMPLE_JOINT_QUERIES = [dict(dof=1, links=12), dict(dof=0, links=9), dict(dof=2, links=11, fractionated=False),
                        dict(dof=3, links=10, n1=(0, 3)), dict(dof=1, links=8, h=2), dict(dof=1, links=11, h=4),
                        dict(dof=1, links=14, h=5), dict(dof=2, links=9, rigid_subchains=True),
                        dict(dof=1, links=10, cranks={4: 2})]


@pytest.mark.parametrize("query", SIMPLE_JOINT_QUERIES, ids=str)
def test_the_model_conditions_are_the_exact_subchain_test(query, monkeypatch):
    """With simple joints stage B's model writes the exact sub-chain test on the strings, so its
    solutions skip the test: each of them is a valid chain (the independent test on the chain), and
    they are exactly the valid ones of the direct listing, which writes no conditions."""
    from synth.synthesis import stage_b
    from synth.structure.subchains import check_subchains

    units = [u for u in synth.plan_units(**query, workers=1) if u.contracted is not None]
    assert units
    checked_any = 0
    for u in units:
        args = (u.code, u.contracted, u.conventions)
        monkeypatch.setattr(stage_b, "_FEW_VECTORS", 0)
        solutions, one_per_orbit, checked = stage_b._distributions(*args, None)
        assert checked
        for s in solutions:
            chain = stage_b._expand(u.contracted.vertices, u.contracted.edges, s, u.conventions.h)
            assert check_subchains(chain, rigid_subchains=u.conventions.rigid_subchains).ok, (u.key, s)
        if one_per_orbit and not u.conventions.cranks:
            monkeypatch.setattr(stage_b, "_FEW_VECTORS", 10**9)
            listed, _, listed_checked = stage_b._distributions(*args, None)
            assert not listed_checked
            kept = stage_b._passing(u.contracted, u.conventions, listed, None)
            assert sorted(kept) == sorted(solutions), u.key
            checked_any += 1
    assert checked_any or query.get("cranks")  # a crank requirement has no direct listing


class _PoolSpy:
    """A process pool that says how many tasks it was given (``apply_async``) and that it was shut down."""

    made: list = []

    def __init__(self, workers):
        import multiprocessing

        self.workers, self.tasks, self._pool = workers, 0, multiprocessing.get_context("fork").Pool(workers)
        _PoolSpy.made.append(self)

    def apply_async(self, func, args, **callbacks):
        self.tasks += 1
        return self._pool.apply_async(func, args, **callbacks)

    def terminate(self):
        self._pool.terminate()

    def join(self):
        self._pool.join()


def test_plan_units_is_inline_on_one_worker_and_on_a_pool_otherwise(monkeypatch):
    import os

    import synth.execution.executor as ex
    import synth.synthesis.type_synthesis as ts

    monkeypatch.setattr(ex, "process_pool", _PoolSpy)
    _PoolSpy.made = []
    inline = ts.plan_units(1, 8, workers=1)
    ts.plan_units(1, 8)  # the default: inline (a plan is small next to its units)
    assert _PoolSpy.made == []
    pooled = ts.plan_units(1, 8, workers=2)
    assert [(p.workers, p.tasks) for p in _PoolSpy.made] == [(2, 3)]  # stage A of the three codes
    assert [u.key for u in pooled] == [u.key for u in inline]
    _PoolSpy.made = []
    ts.plan_units(1, 8, workers=None)  # every core
    cores = os.cpu_count() or 1
    assert [(p.workers, p.tasks) for p in _PoolSpy.made] == ([] if cores == 1 else [(cores, 3)])


@pytest.mark.parametrize("links, workers, message", [
    (0, 1, "the number of links must be 1 or more, not 0"),
    (True, 1, "the number of links must be a whole number, not True"),
    (8, 0, "workers must be a whole number ≥ 1, not 0"),
    (8, 2.0, "workers must be a whole number ≥ 1, not 2.0"),
    (1, 1, "no whole number of loops fits: n = W + 1 + (h − 1)·K needs n − W − 1 = -1 to be a non-negative "
           "multiple of h − 1 = 2 (W=1, n=1, h=3)"),  # one link is a size, just not a chain's
])
def test_plan_units_refuses_bad_sizes_in_one_sentence(links, workers, message):
    with pytest.raises(synth.SynthesisError) as refused:
        synth.plan_units(1, links, workers=workers)
    assert str(refused.value) == message


def test_plan_many_keeps_each_query_its_own_units():
    """Several queries in one batch: each gets exactly its own plan; impossible ones none when asked."""
    from synth.synthesis.type_synthesis import plan_many

    queries = [dict(dof=1, links=8), dict(dof=2, links=7), dict(dof=1, links=9), dict(dof=1, links=6)]
    plans = plan_many(queries, skip_impossible=True)
    assert [len(p) for p in plans] == [4, len(synth.plan_units(2, 7)), 0, len(synth.plan_units(1, 6))]
    assert [[u.key for u in p] for p in plans[:2]] == [[u.key for u in synth.plan_units(1, 8)],
                                                      [u.key for u in synth.plan_units(2, 7)]]
    with pytest.raises(synth.ImpossibleParameters):
        plan_many(queries)


def test_count_descriptions_and_identities():
    """What a checkpoint file records: a readable query and a digest that tells plans apart."""
    from synth.synthesis.type_synthesis import _describe, _identity, plan_jobs

    query = synth.ChainQuery(1, 8, v=None, require=["3=2"], planar_only=True, fractionated=False, cranks=())
    assert _describe("chains", query) == "chains dof=1 links=8 require=[3=2] fractionated=False planar_only=True"
    jobs = plan_jobs(synth.ChainQuery(1, 8))
    assert _identity("chains", jobs) != _identity("chains", jobs[:1])
    assert _identity("chains", jobs) != _identity("mechanisms", jobs)
    assert _identity("chains", jobs) == _identity("chains", list(jobs))
    assert _identity("chains", jobs[:1]) != _identity("chains", jobs[1:2])  # which codes, not how many


@pytest.mark.parametrize("dof, message", [(-1, "the degree of freedom W must be 0 or more, not -1"),
                                          ("1", "the degree of freedom W must be a whole number, not '1'"),
                                          (True, "the degree of freedom W must be a whole number, not True")])
def test_every_entry_point_refuses_a_bad_mobility(dof, message):
    for call in (lambda: synth.plan_units(dof, 8), lambda: list(synth.type_synthesis(dof, 8)),
                 lambda: synth.count_chains(dof, 8), lambda: synth.count_mechanisms(dof, 8)):
        with pytest.raises(synth.SynthesisError) as refused:
            call()
        assert str(refused.value) == message
    for call in (lambda: list(synth.type_synthesis(1, 0)), lambda: synth.count_chains(1, 0),
                 lambda: synth.count_mechanisms(1, 0)):
        with pytest.raises(synth.SynthesisError, match="^the number of links must be 1 or more, not 0$"):
            call()
    for call in (lambda: list(synth.type_synthesis(1, 8, workers=0)), lambda: synth.count_chains(1, 8, workers=0),
                 lambda: synth.count_mechanisms(1, 8, workers=0)):
        with pytest.raises(synth.SynthesisError, match="^workers must be a whole number ≥ 1, not 0$"):
            call()


def test_one_worker_never_starts_a_pool(monkeypatch):
    """A query longer than the inline start (0.25 s) still runs in this process with one worker."""
    import synth.execution.executor as ex

    def refuse(workers):
        raise AssertionError(f"a pool of {workers} was started")

    monkeypatch.setattr(ex, "process_pool", refuse)
    assert synth.count_chains(1, 12, workers=1)["count"] == 6856
    assert sum(1 for _ in synth.type_synthesis(1, 12, workers=1)) == 6856
    assert synth.count_mechanisms(1, 10, workers=1)["count"] == 1834


def test_mechanism_counts_with_and_without_input_link_keep_apart(tmp_path):
    """A checkpoint of the mechanisms count is refused for the count with input links (another plan)."""
    path = tmp_path / "m.sqlite"
    assert synth.count_mechanisms(1, 6, workers=1, checkpoint=path)["count"] == 5
    with pytest.raises(synth.SynthesisError) as refused:
        synth.count_mechanisms(1, 6, input_link=True, workers=1, checkpoint=path)
    assert "another query (mechanisms dof=1 links=6), not to mechanisms with input link dof=1 links=6" in str(
        refused.value)


def test_count_resumes_in_process_without_losing_or_repeating_a_unit(tmp_path, monkeypatch):
    """Ctrl-C in the middle of a count (in this process, so the checkpoint code itself is judged):
    the rerun adds the stored codes and units to what it computes, and computes only the rest."""
    import synth.synthesis.type_synthesis as ts

    full = synth.count_chains(1, 10, workers=1)
    total_units = len(synth.plan_units(1, 10))
    real, calls = ts.count_unit, []

    def interrupted(unit):
        if len(calls) == 10:  # 4600/0 and 5410/0 complete, two of the four units of 6220/0 done
            raise KeyboardInterrupt
        calls.append(unit.key)
        return real(unit)

    path = tmp_path / "c.sqlite"
    monkeypatch.setattr(ts, "count_unit", interrupted)
    with pytest.raises(KeyboardInterrupt):
        synth.count_chains(1, 10, workers=1, checkpoint=path)
    done = list(calls)
    calls.clear()
    monkeypatch.setattr(ts, "count_unit", lambda unit: (calls.append(unit.key), real(unit))[1])
    assert synth.count_chains(1, 10, workers=1, checkpoint=path) == full
    assert len(done) == 10 and not set(done) & set(calls) and len(done) + len(calls) == total_units
    calls.clear()
    assert synth.count_chains(1, 10, workers=1, checkpoint=path) == full and calls == []  # all stored


def test_a_checkpoint_knows_its_conventions_and_reports_its_commits(tmp_path):
    """The same codes under other conventions are another plan; every commit is reported to ``log``."""
    path, lines = tmp_path / "f.sqlite", []
    assert synth.count_chains(1, 10, planar_only=True, workers=1, checkpoint=path, log=lines.append)["count"] == 219
    assert lines and all(line.startswith(f"checkpoint {path}: ") for line in lines)
    with pytest.raises(synth.SynthesisError, match="belongs to another query") as refused:
        synth.count_chains(1, 10, workers=1, checkpoint=path)  # the same codes, non-planar chains included: 230
    assert "another query (chains dof=1 links=10 planar_only=True), not to chains dof=1 links=10;" in str(refused.value)
    mechanisms = []
    assert synth.count_mechanisms(1, 8, workers=1, checkpoint=tmp_path / "m.sqlite", log=mechanisms.append)["count"] == 71
    assert mechanisms and all(line.startswith(f"checkpoint {tmp_path / 'm.sqlite'}: ") for line in mechanisms)


MODEL_QUERIES = [
    dict(dof=1, links=8),
    dict(dof=1, links=10),
    dict(dof=2, links=9),
    dict(dof=0, links=9),
    dict(dof=1, links=8, v=(0, 3)),
    dict(dof=2, links=7, fractionated=False),
    dict(dof=1, links=10, planar_only=True),
    dict(dof=0, links=7, rigid_subchains=False),
    dict(dof=3, links=6, n1=(0, 2)),
    dict(dof=1, links=6, h=2),
    dict(dof=2, links=7, h=2),
    dict(dof=1, links=6, h=2, v=(0, 2)),
    dict(dof=1, links=6, h=2, v=(0, 2), rigid_subchains=True),  # two joints on the same links refused
    dict(dof=1, links=8, h=4),
    dict(dof=1, links=10, h=5, v=(0, 2)),
    dict(dof=1, links=12, h=6),
    dict(dof=0, links=9, rigid_subchains=False),  # the whole chain exempt: the model needs the exact test
    dict(dof=1, links=8, v=(0, 4), max_multiplicity=3),
]


@pytest.mark.parametrize("query", MODEL_QUERIES, ids=_query_id)
def test_stage_b_model_and_direct_listing_agree(query, monkeypatch):
    """Stage B lists a small unit's weight vectors directly and leaves the sub-chain rule to the
    exact test; a large unit gets a CP-SAT model whose conditions *are* the rule for simple joints
    (no exact test after it).  Forced through the model, every unit gives the same chains, and
    the same count; the model's candidates are never more than the listing's."""
    from synth.synthesis import stage_b

    listed, listed_stats = _chains_and_stats(query)
    monkeypatch.setattr(stage_b, "_FEW_VECTORS", 0)
    modelled, modelled_stats = _chains_and_stats(query)
    assert modelled == listed and listed
    assert synth.count_chains(**query, workers=1)["count"] == len(listed)
    assert modelled_stats["candidates"] <= listed_stats["candidates"]


def _chains_and_stats(query):
    """The query's chains unit by unit, and stage B's statistics, which counting a unit reports
    the same (its candidates) as listing it."""
    from time import perf_counter

    from synth.synthesis.stage_b import count_realised

    stats: dict = {}
    chains = []
    start = perf_counter()
    for u in synth.plan_units(**query, workers=1):
        before = stats.get("candidates", 0)
        found = synth.run_unit(u, stats)
        chains += [c.certificate for c in found]
        if u.contracted is not None:
            counted: dict = {}
            assert count_realised(u.code, u.contracted, u.conventions, counted) == len(found)
            assert counted["candidates"] == stats["candidates"] - before
            assert {"cpsat_s", "subchain_s"} <= set(counted)
    spent = perf_counter() - start  # (each stage's time is a part of it: an invariant, not a speed goal)
    assert all(0 <= stats[k] <= spent for k in ("cpsat_s", "subchain_s", "nauty_s") if k in stats)
    return sorted(chains), stats


STAGE_A_QUERIES = [dict(dof=1, links=8, v=(0, 4)), dict(dof=1, links=6, h=2, v=(0, 2)), dict(dof=0, links=9, v=(0, 3)),
                   dict(dof=1, links=11, h=4, v=(0, 3)), dict(dof=2, links=9, v=(0, 3), rigid_subchains=True),
                   dict(dof=1, links=10, v=(0, 5)), dict(dof=1, links=8, h=3, v=(0, 3))]


@pytest.mark.parametrize("query", STAGE_A_QUERIES, ids=_query_id)
def test_stage_a_conditions_in_the_model_or_on_its_solutions_agree(query, monkeypatch, no_solver_store):
    """Stage A writes the sub-chain conditions of small codes into its CP-SAT model and checks those of
    large codes on the model's solutions (``_StringBounds.meet``, in blocks).  With every condition
    checked on the solutions, in blocks of 5, each query gets the same branch graphs H; and the
    check is no formality: without it (and without the model's conditions) there are more."""
    import numpy as np

    from synth.synthesis import stage_a

    def graphs():
        return sorted((str(u.code), u.contracted.certificate) for u in synth.plan_units(**query, workers=1)
                      if u.contracted is not None)

    in_model = graphs()
    monkeypatch.setattr(stage_a, "_split_conditions", lambda conditions, kinds: ([], list(conditions)))
    monkeypatch.setattr(stage_a, "_CONDITION_BLOCK", 5)
    assert graphs() == in_model and in_model
    monkeypatch.setattr(stage_a._StringBounds, "meet", lambda self, X, Y, conditions: np.ones(len(X), dtype=bool))
    assert len(graphs()) > len(in_model)


@pytest.mark.parametrize("edges", [2, 3, 6, 15])
def test_edge_group_of_parallel_strings(edges):
    """Two links joined by k parallel strings: the strings permute in every way (k! edge maps; the
    swap of the two links maps each string to itself).  Up to 4096 the whole group is listed; beyond
    (15! ≈ 1.3e12, which nauty reports as 1.3·10^12 with a mantissa and an exponent) only generators
    and their inverses, each a permutation of the strings."""
    from synth.synthesis.stage_a import LINK, Contracted, Vertex

    group, whole = Contracted((Vertex(LINK, edges),) * 2, ((0, 1),) * edges, "").edge_group()
    assert all(sorted(g) == list(range(edges)) and g != tuple(range(edges)) for g in group)
    if math.factorial(edges) <= 4096:
        assert whole and len(set(group)) == math.factorial(edges) - 1
    else:
        assert not whole and 0 < len(group) <= 4 * edges


def _stage_a_by_enumeration(code, conv):
    """Stage A without CP-SAT and without its symmetry breaking: every labelled multigraph on the
    branch vertices with their degrees (loops count 2), with as many binary links as the strings
    need, meeting every sub-chain condition, connected and kept — one certificate per class."""
    import itertools

    import numpy as np
    import pynauty

    from synth.synthesis import stage_a

    vertices = stage_a._branch_vertices(code)
    m, deg = len(vertices), [vertex.degree for vertex in vertices]
    pairs = list(itertools.combinations(range(m), 2))
    bounds = stage_a._StringBounds(vertices, pairs, code, conv)
    loops_max = [d // 2 if conv.fractionated or code.n1 else 0 for d in deg]
    rows = []

    def fill(k, left, x):
        if k == len(pairs):
            if all(r % 2 == 0 and r // 2 <= loops_max[u] for u, r in enumerate(left)):
                rows.append(x + [r // 2 for r in left])
            return
        u, v = pairs[k]
        for mult in range(min(left[u], left[v]) + 1):
            left[u] -= mult
            left[v] -= mult
            fill(k + 1, left, x + [mult])
            left[u] += mult
            left[v] += mult

    if m:
        fill(0, list(deg), [])
    if not rows:
        return []
    sol = np.array(rows, dtype=np.int64)
    X, Y = sol[:, :len(pairs)], sol[:, len(pairs):]
    binary = np.maximum(0, X * bounds.slope + bounds.offset).sum(axis=1) + Y @ bounds.loop
    ok = (binary <= code.count(2)) & bounds.meet(X, Y, stage_a._subset_conditions(vertices, code.dof(conv.h), conv))
    found = set()
    for row in sol[ok]:
        edges = [p for p, k in zip(pairs, row) for _ in range(int(k))]
        edges += [(u, u) for u, k in enumerate(row[len(pairs):]) for _ in range(int(k))]
        if stage_a._connected(m, edges) and stage_a._keep_multigraph(m, edges, conv):
            graph = stage_a.Contracted(vertices, tuple(sorted(edges)), "")._subdivided()
            found.add(pynauty.certificate(graph).hex())
    return sorted(found)


BRUTE_STAGE_A_QUERIES = STAGE_A_QUERIES + [
    dict(dof=1, links=10), dict(dof=1, links=10, fractionated=False), dict(dof=1, links=10, planar_only=True),
    dict(dof=1, links=12), dict(dof=2, links=11, v=(0, 2)), dict(dof=0, links=10, h=4, v=(0, 2)),
    dict(dof=3, links=8, n1=(0, 3)), dict(dof=1, links=10, h=5, v=(0, 2)), dict(dof=1, links=12, h=6)]


@pytest.mark.parametrize("query", BRUTE_STAGE_A_QUERIES, ids=_query_id)
def test_stage_a_against_an_enumeration_of_labelled_multigraphs(query):
    """Stage A's branch graphs H, code by code, are the classes of an exhaustive enumeration of
    labelled multigraphs (codes of up to 7 branch vertices): CP-SAT's search and the lexicographic
    row constraints that cut its symmetric solutions lose no class and keep each once."""
    from synth.synthesis import stage_a
    from synth.synthesis.type_synthesis import plan_jobs

    compared = 0
    for code, conv in plan_jobs(synth.ChainQuery.of(**query)):
        if len(stage_a._branch_vertices(code)) > 7:
            continue
        engine = [graph.certificate for graph in stage_a.contracted_graphs(code, conv)]
        assert engine == _stage_a_by_enumeration(code, conv), code
        compared += len(engine)
    assert compared > 0
