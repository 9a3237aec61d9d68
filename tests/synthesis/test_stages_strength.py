"""Stages A and B of type synthesis, on every path they can take, against the brute-force oracle.

Small queries (at most 8 links) take the plain search of stage A and the direct listing of stage B;
the CP-SAT models and the compiled kernels take over for larger ones.  Here every path is forced
on the small queries, so that each is judged by the independent oracle (tests/oracles/chains.py,
no engine code) in seconds:

* ``listing``: the engine's own choice (stage A's search, stage B's listing, the exact test), the
  conditions checked on stage A's multigraphs in blocks of one;
* ``kernel``: the compiled searches of both stages (``Conventions.kernel_loops = 1``), stage A's
  in batches of two multigraphs and stage B's listing from a first pass of one placement;
* ``model``: stage A's CP-SAT model and stage B's CP-SAT model (their size thresholds set to 0);
* ``generators``: the models with the automorphisms of H known by their generators only (as for a
  group of more than 4 096 elements): stage B then compares the chains by certificate.

On each path the chains listed (``realise``), the chains counted (``count_realised``,
``count_listed``, ``count_orbits``) and the branch multigraphs must give the oracle's chains:
the same number per code and, for the listing, one chain of each isomorphism class of the oracle
(networkx VF2, no nauty).  The solver store is off: a stored stage-A result would hide the stage.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import replace
from time import perf_counter

import pytest

from synth.structure.query import ChainQuery
from synth.synthesis import stage_a, stage_b
from synth.synthesis.stage_a import JOINT, LINK, Vertex, contracted_graphs
from synth.synthesis.stage_b import count_listed, count_orbits, count_realised, realise
from synth.synthesis.type_synthesis import plan_jobs
from tests.oracles.chains import ChainIndex, brute_force_chains, code_key

# name: (the engine's query, the oracle's arguments); oracle CPU time under 1.2 s each
CASES = {
    "W1-n6-v2": (dict(dof=1, links=6, v=(0, 2)), dict(links=6, dof=1, v_max=2)),
    "W1-n8": (dict(dof=1, links=8), dict(links=8, dof=1)),
    "W1-n6-v2-rigid": (dict(dof=1, links=6, v=(0, 2), rigid_subchains=True),
                       dict(links=6, dof=1, v_max=2, rigid_subchains=True)),
    "W2-n7-v3-nofrac": (dict(dof=2, links=7, v=(0, 3), fractionated=False),
                        dict(links=7, dof=2, v_max=3, fractionated=False)),
    "W2-n7-v1": (dict(dof=2, links=7, v=(0, 1)), dict(links=7, dof=2, v_max=1)),
    "W3-n8-nofrac": (dict(dof=3, links=8, fractionated=False), dict(links=8, dof=3, fractionated=False)),
    "W0-n7-v1-rigid": (dict(dof=0, links=7, v=(0, 1), rigid_subchains=True),
                       dict(links=7, dof=0, v_max=1, rigid_subchains=True)),
    # trusses without rigid sub-chains: the whole chain is exempt from the rule its parts keep
    "W0-n7-v2": (dict(dof=0, links=7, v=(0, 2), rigid_subchains=False), dict(links=7, dof=0, v_max=2)),
    # open chains: single-joint links
    "W2-n7-n1-v1": (dict(dof=2, links=7, n1=(0, 3), v=(0, 1)), dict(links=7, dof=2, n1=(0, 3), v_max=1)),
    "W3-n6-n1-nofrac": (dict(dof=3, links=6, n1=(1, 2), fractionated=False),
                        dict(links=6, dof=3, n1=(1, 2), fractionated=False)),
    # trees (no loop): a serial arm of four links and the star of three arms on one link
    "W3-n4-n1-tree": (dict(dof=3, links=4, n1=(0, 4)), dict(links=4, dof=3, n1=(0, 4))),
    # wedge systems (motion space h = 2)
    "h2-W1-n6": (dict(dof=1, links=6, h=2), dict(links=6, dof=1, h=2)),
    "h2-W1-n5-v1": (dict(dof=1, links=5, h=2, v=(0, 1)), dict(links=5, dof=1, h=2, v_max=1)),
    "h2-W0-n5-rigid": (dict(dof=0, links=5, h=2, rigid_subchains=True), dict(links=5, dof=0, h=2, rigid_subchains=True)),
    # h = 2 with rigid sub-chains and multiple joints: two joints on the same links pass the rule
    # (W = 2 − h = 0), so stage B compares the chains (two joints of the same links are one)
    "h2-W1-n5-v2-rigid": (dict(dof=1, links=5, h=2, v=(0, 2), rigid_subchains=True),
                          dict(links=5, dof=1, h=2, v_max=2, rigid_subchains=True)),
}

PATHS = ("listing", "kernel", "model", "generators")


def key(joints, links: int) -> str:
    """A chain's code written from its joints alone: single-joint links | assortment / composition."""
    degree = Counter(i for joint in joints for i in joint)
    assortment, composition = code_key(joints, links)
    single = sum(1 for i in range(links) if degree[i] == 1)
    return f"{single}|{'.'.join(map(str, assortment))}/{'.'.join(map(str, composition))}"


def _joints(chain) -> tuple[tuple[int, ...], ...]:
    return tuple(sorted(tuple(sorted(j)) for j in chain.joints))


def _jobs(query: dict, path: str, monkeypatch) -> list:
    jobs = plan_jobs(ChainQuery(**query))
    if path == "kernel":  # (in small batches: stage A's search resumed, stage B's listing read in a second pass)
        monkeypatch.setattr(stage_a, "_CONDITION_BATCH", 2)
        monkeypatch.setattr(stage_b, "_KERNEL_ROWS", 1)
        return [(code, replace(conv, kernel_loops=1)) for code, conv in jobs]
    if path == "generators":  # Aut(H) as its generators only, as for a group too large to list
        monkeypatch.setattr(stage_a, "_GROUP_LIMIT", 0)
    if path == "listing":  # (the conditions checked on the search's multigraphs one at a time)
        monkeypatch.setattr(stage_a, "_CONDITION_BLOCK", 1)
    if path in ("model", "generators"):
        monkeypatch.setattr(stage_a, "_SEARCH_VERTICES", 0)
        monkeypatch.setattr(stage_b, "_FEW_VECTORS", 0)
    return jobs


def _single_loop(code) -> bool:
    """A code of binary links alone (one loop): no branch multigraph, no stage A or B."""
    return code.count(2) == code.links and not code.v


@pytest.mark.parametrize("name", CASES)
def test_every_path_lists_and_counts_the_oracles_chains(name, monkeypatch, no_solver_store):
    query, oracle_args = CASES[name]
    expected = brute_force_chains(**oracle_args)
    assert expected, name
    want = Counter(key(c.joints, c.links) for c in expected)
    index = ChainIndex(expected)
    for path in PATHS:
        listed, counted, by_listing, by_orbits, classes = Counter(), Counter(), Counter(), Counter(), []
        for code, conv in _jobs(query, path, monkeypatch):
            if _single_loop(code):
                listed[f"0|{code.links}/"] += 1
                counted[f"0|{code.links}/"] += 1
                by_listing[f"0|{code.links}/"] += 1
                by_orbits[f"0|{code.links}/"] += 1
                classes.append(index.find(tuple((i, (i + 1) % code.links) for i in range(code.links)), code.links))
                continue
            for graph in contracted_graphs(code, conv):
                chains = realise(code, graph, conv)
                for chain in chains:
                    listed[key(_joints(chain), chain.links)] += 1
                    classes.append(index.find(_joints(chain), chain.links))
                label = key(_joints(chains[0]), chains[0].links) if chains else None
                for tally, count in ((counted, count_realised), (by_listing, count_listed), (by_orbits, count_orbits)):
                    n = count(code, graph, conv)
                    assert n == len(chains), (path, str(code), graph.edges, count.__name__)
                    if n:
                        tally[label] += n
        assert listed == want, (path, name)
        assert counted == by_listing == by_orbits == want, (path, name)
        assert sorted(classes, key=lambda k: -1 if k is None else k) == list(range(len(expected))), (path, name)


def test_planar_only_drops_the_one_non_planar_wedge_chain(monkeypatch, no_solver_store):
    expected = [c for c in brute_force_chains(links=6, dof=1, h=2) if c.planar]
    assert len(expected) == 12  # of 13: one chain of 1-DOF wedge systems of 6 links is not planar
    want = Counter(key(c.joints, c.links) for c in expected)
    for path in PATHS:
        got = Counter()
        for code, conv in _jobs(dict(dof=1, links=6, h=2, planar_only=True), path, monkeypatch):
            for graph in contracted_graphs(code, conv):
                got.update(key(_joints(c), c.links) for c in realise(code, graph, conv))
        assert got == want, path


def _cranks(joints, links: int, joints_on_link: int) -> int:
    """The most cranks (binary links jointed to it by a simple joint) of a link with that many joints."""
    degree = Counter(i for joint in joints for i in joint)
    most = 0
    for link in range(links):
        if degree[link] == joints_on_link:
            most = max(most, sum(1 for j in joints if len(j) == 2 and link in j and degree[j[0] + j[1] - link] == 2))
    return most


@pytest.mark.parametrize("joints_on_link, cranks", [(3, 2), (4, 2), (3, 3)])
def test_a_crank_requirement_keeps_the_chains_with_such_a_link(joints_on_link, cranks, monkeypatch, no_solver_store):
    """Stage B's model carries the requirement (the listing cannot): the oracle's 1-DOF 8-link chains
    with a link of ``joints_on_link`` joints carrying at least ``cranks`` binary links."""
    expected = [c for c in brute_force_chains(links=8, dof=1) if _cranks(c.joints, 8, joints_on_link) >= cranks]
    want = Counter(key(c.joints, c.links) for c in expected)
    got = Counter()
    query = dict(dof=1, links=8, require={joints_on_link: (1, None)}, cranks={joints_on_link: cranks})
    for code, conv in plan_jobs(ChainQuery(**query)):
        for graph in contracted_graphs(code, conv):
            chains = realise(code, graph, conv)
            assert count_realised(code, graph, conv) == len(chains)
            got.update(key(_joints(c), c.links) for c in chains)
    assert got == want


def test_the_branch_multigraphs_of_watt_and_stephenson():
    """6 links, 1 DOF (4 binary, 2 ternary links): Watt's and Stephenson's chains share one H, two
    ternary links joined by three strings; of the three ordered ways to put the 4 binary links on
    them with one empty string at most, (0, 1, 3) leaves a rigid triangle (the direct joint beside
    a one-link string): Watt is (0, 2, 2), Stephenson (1, 1, 2)."""
    code = plan_jobs(ChainQuery(dof=1, links=6))[0][0]
    for conv in (stage_a.Conventions(), stage_a.Conventions(kernel_loops=1)):
        graphs = contracted_graphs(code, conv)
        assert [g.vertices for g in graphs] == [(Vertex(LINK, 3), Vertex(LINK, 3))]
        assert [g.edges for g in graphs] == [((0, 1), (0, 1), (0, 1))]
        solutions, whole_group, checked = stage_b._distributions(code, graphs[0], conv, None)
        kept = stage_b._passing(graphs[0], conv, solutions, None, checked)
        assert sorted(map(tuple, kept)) == [(0, 2, 2), (1, 1, 2)]
    assert sorted([Vertex(LINK, 1), Vertex(JOINT, 3)]) == [Vertex(JOINT, 3), Vertex(LINK, 1)]


def test_loading_the_kernels_runs_both_stages_on_a_code():
    """What a pool runs before it forks its workers: stage A's and stage B's kernels on 440/0, whose
    results it throws away (a mistake there would stop every large query)."""
    assert stage_b.load_kernel() is None


_COMPILED_BY_A_COUNT = """
from numba.core.registry import CPUDispatcher
from synth.synthesis import _stage_a_kernel, _stage_b_kernel, stage_b
from synth import count_chains

def compiled():
    return {name: len(kernel.signatures) for module in (_stage_a_kernel, _stage_b_kernel)
            for name, kernel in vars(module).items() if isinstance(kernel, CPUDispatcher)}

stage_b.load_kernel()
before = compiled()
assert count_chains(1, 12, v=1, workers=1).count == 34129
after = compiled()
print(sorted(name for name in after if after[name] != before[name]))
"""


def test_loading_the_kernels_loads_every_one_a_count_calls():
    """After :func:`stage_b.load_kernel` (what the pool runs before it forks), a count of units with a
    multiple joint (stage B's ``place``, once left out: each worker compiled it in the middle of a count)
    loads no kernel of its own.  In a fresh process: this one's kernels may be loaded already."""
    import os
    import subprocess
    import sys

    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = {**os.environ, "MECHSYNTH_CACHE": "off"}
    done = subprocess.run([sys.executable, "-c", _COMPILED_BY_A_COUNT], capture_output=True, text=True, cwd=root,
                          env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "[]"


@pytest.mark.parametrize("path, candidates", [
    # the listing: the three ordered vectors (0, 1, 3), (0, 2, 2), (1, 1, 2) (two joints of the same two
    # links would be one: one string at most is empty), tested after
    ("listing", 3),
    # the kernel and the model: their conditions are the exact rule for simple joints, Watt and Stephenson pass
    ("kernel", 2), ("model", 2),
])
def test_the_statistics_of_a_unit_count_its_candidates(path, candidates, monkeypatch, no_solver_store):
    """What the benchmarks read of a unit (candidates per chain, seconds by step): Watt's and
    Stephenson's H, listed and counted; each time within the time of the call."""
    [(code, conv)] = _jobs(dict(dof=1, links=6), path, monkeypatch)
    [graph] = contracted_graphs(code, conv)
    for count, steps in ((realise, {"candidates", "cpsat_s", "subchain_s", "nauty_s"}),
                         (count_realised, {"candidates", "cpsat_s"}
                          | ({"subchain_s"} if path != "kernel" else {"tight"}))):  # (the kernel counts tight units)
        stats: dict = {}
        start = perf_counter()
        found = count(code, graph, conv, stats)
        elapsed = perf_counter() - start
        assert (found if isinstance(found, int) else len(found)) == 2
        assert stats["candidates"] == candidates
        assert set(stats) == steps, count.__name__
        assert all(0 <= seconds <= elapsed for name, seconds in stats.items() if name.endswith("_s"))


@pytest.mark.parametrize("query, chains", [
    (dict(dof=2, links=9), 40),  # the brute force (test_chains_vs_oracle.py, W2-n9)
    (dict(dof=1, links=10), 230),  # the published count of 1-DOF 10-link chains
    (dict(dof=3, links=10), 98),  # the brute force (W3-n10, a slow case of test_chains_vs_oracle.py)
    (dict(dof=0, links=9, rigid_subchains=True), 414),  # the brute force (the slow test below)
], ids=str)
def test_the_kernel_finds_the_models_branch_multigraphs_where_its_game_stops(query, chains, monkeypatch, no_solver_store):
    """Codes of 9 and 10 links, where the binary links to spare exceed the pebble game's l (the
    kernel marks those multigraphs and stage A checks every condition on them) and stage A's model
    writes the conditions of sets of three links and more: the kernel's branch multigraphs (in
    batches of two) are the model's, in one order and labelling, and the chains of each path add
    up to the independent counts."""
    monkeypatch.setattr(stage_a, "_CONDITION_BATCH", 2)
    jobs = plan_jobs(ChainQuery(**query))
    found = {}
    for path, conventions in (("kernel", lambda conv: replace(conv, kernel_loops=1)), ("model", lambda conv: conv)):
        with monkeypatch.context() as setting:
            if path == "model":
                setting.setattr(stage_a, "_SEARCH_VERTICES", 0)
            graphs = [[(g.certificate, g.edges) for g in contracted_graphs(code, conventions(conv))] for code, conv in jobs]
            found[path] = graphs
            total = sum(count_realised(code, g, conventions(conv)) for code, conv in jobs
                        for g in contracted_graphs(code, conventions(conv)))
        assert total + sum(1 for code, _ in jobs if _single_loop(code)) == chains, path
    assert found["kernel"] == found["model"]


def test_stage_a_is_stored_and_read_back(tmp_path, monkeypatch):
    """With the solver store on, stage A's model runs once per code: the second query reads the same
    branch multigraphs back, and a code stored needs no solver."""
    from synth.execution import memo

    monkeypatch.setenv("MECHSYNTH_CACHE", str(tmp_path))
    memo._store.cache_clear()
    monkeypatch.setattr(stage_a, "_SEARCH_VERTICES", 0)  # (the model, not the plain search, of small codes)
    try:
        jobs = plan_jobs(ChainQuery(dof=1, links=8, v=(0, 1)))
        assert [stage_a.needs_solver(code, conv) for code, conv in jobs] == [True] * len(jobs)
        first = [contracted_graphs(code, conv) for code, conv in jobs]
        assert [stage_a.needs_solver(code, conv) for code, conv in jobs] == [False] * len(jobs)
        monkeypatch.setattr(stage_a, "_contracted_by_model", lambda code, conv: pytest.fail("stage A ran again"))
        assert [contracted_graphs(code, conv) for code, conv in jobs] == first
        assert all(isinstance(v, stage_a.Vertex) for graphs in first for g in graphs for v in g.vertices)
    finally:
        memo._store.cache_clear()


def test_which_codes_need_the_solver(monkeypatch, no_solver_store):
    """A single loop has no H; a code the kernel takes (K ≥ 6) or the plain search takes (at most 8
    branch vertices) needs no CP-SAT model; one of more branch vertices below the kernel's size does."""
    from synth.structure.code import Code

    conv = stage_a.Conventions()
    assert not stage_a.needs_solver(Code((4,), 0, ()), conv)
    assert not stage_a.needs_solver(Code((4, 4), 0, ()), conv)  # 4 ternary links: the search
    assert not stage_a.needs_solver(Code((4, 4), 0, ()), replace(conv, kernel_loops=1))  # the kernel
    monkeypatch.setattr(stage_a, "_SEARCH_VERTICES", 3)
    assert stage_a.needs_solver(Code((4, 4), 0, ()), conv)  # 4 branch vertices, K = 3 < 6: the model
    assert not stage_a.needs_solver(Code((4, 4), 0, ()), replace(conv, kernel_loops=3))


@pytest.mark.parametrize("code, vertices", [
    ("521/0", [(LINK, 4), (LINK, 3), (LINK, 3)]),  # links of 3+ joints, most first
    ("610/1-1", [(LINK, 3), (JOINT, 4), (JOINT, 3)]),  # then the multiple joints, most links first
    ("2|5/0-1", [(LINK, 1), (LINK, 1), (JOINT, 4)]),  # single-joint links after the others
    ("4/0", []),  # one loop: no branch vertex
])
def test_the_branch_vertices_of_a_code(code, vertices):
    from synth.structure.code import Code

    assert list(stage_a._branch_vertices(Code.parse(code))) == [Vertex(*v) for v in vertices]


@pytest.mark.parametrize("query", [dict(dof=1, links=8), dict(dof=0, links=7, v=(0, 1), rigid_subchains=True),
                                   dict(dof=2, links=9), dict(dof=1, links=6, v=(0, 2), rigid_subchains=True)], ids=str)
@pytest.mark.parametrize("path", PATHS)
def test_stage_a_leaves_no_branch_multigraph_without_a_chain_here(query, path, monkeypatch, no_solver_store):
    """Stage A's sub-chain conditions on H exist to drop the multigraphs whose binary links are too
    few for every placement (each would be a unit of stage B that finds nothing).  They are
    necessary conditions, not always sufficient (1-DOF 10 links keeps one such H), but on these
    queries they drop every one: each unit gives a chain."""
    for code, conv in _jobs(query, path, monkeypatch):
        for graph in contracted_graphs(code, conv):
            assert realise(code, graph, conv), (str(code), graph.edges)


@pytest.mark.slow
def test_the_brute_force_counts_414_rigid_trusses_of_9_links():
    """The brute-force count the kernel test above uses for trusses of 9 links (about 40 CPU s)."""
    assert len(brute_force_chains(links=9, dof=0, rigid_subchains=True)) == 414
