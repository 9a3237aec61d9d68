"""Counting by orbits (Burnside's lemma over the automorphisms of each branch multigraph H,
``stage_b.count_orbits``) against the listing path and the brute-force oracle.

* the claim it rests on: the exact sub-chain test of a weight vector depends only on its
  pattern min(w_e, h − 1), checked on every weight vector of every H up to 12 links (W = 1); with
  multiple joints on min(w_e, h) and not on min(w_e, h − 1) alone (a string of exactly h − 1 brings
  its links to a set at no cost), every H up to 10 links;
* the number of valid weight vectors the search fixes under the identity equals the number the
  exact test passes (no symmetry involved: the search's rule against the independent test);
* per unit, ``count_orbits`` equals ``count_realised`` (the listing path) on every H of every
  code, W = 1 to 14 links, other mobilities, motion spaces and conventions at smaller sizes;
* counts by code of ``count_chains(method="orbits")`` equal the brute-force oracle's;
* the 16-link comparison by code is ``slow`` (benchmarks/logs/orbits_vs_listing_16.txt).
"""

from __future__ import annotations

from collections import Counter, defaultdict

import numpy as np
import pytest

import synth
from synth.synthesis import stage_b
from synth.synthesis.type_synthesis import job_units, plan_jobs
from tests.oracles.chains import brute_force_chains_once, count_by_code, engine_counts_by_key


def _units(query):
    for code, conv in plan_jobs(synth.ChainQuery.of(**query)):
        for unit in job_units((code, conv)):
            if unit.contracted is not None:
                yield unit


def _all_vectors(unit):
    """Every weight vector of the unit's H: n2 binary links on its strings above their least weights
    (no symmetry removed)."""
    lows, _ = stage_b._string_limits(unit.contracted, unit.conventions)
    spare = unit.code.count(2) - sum(lows)
    if spare < 0:
        return np.zeros((0, len(lows)), dtype=np.int64)
    return np.asarray(stage_b._compositions(spare, len(lows)), dtype=np.int64) + np.array(lows)


@pytest.mark.parametrize("links", [6, 8, 10, 12])
def test_the_exact_test_depends_only_on_the_pattern(links):
    """Two weight vectors of one H with the same pattern min(w, h − 1) pass or fail the exact
    sub-chain test together (so counting patterns is counting valid vectors)."""
    tested = 0
    for unit in _units(dict(dof=1, links=links)):
        graph, conv = unit.contracted, unit.conventions
        assert stage_b.orbits_apply(unit.code, graph, conv)
        vectors = _all_vectors(unit)
        if not len(vectors):
            continue
        passes = stage_b._exact_test(graph.vertices, graph.edges, vectors, conv)
        by_pattern = defaultdict(set)
        for w, ok in zip(np.minimum(vectors, conv.h - 1).tolist(), passes.tolist()):
            by_pattern[tuple(w)].add(ok)
        assert all(len(results) == 1 for results in by_pattern.values()), unit.key
        tested += len(vectors)
    assert tested


def _core_patterns(unit, vectors, top):
    """min(w, top) on the strings the exact test reads (its core: loops included), the rest left out."""
    _, ends = stage_b._core(unit.contracted.vertices, unit.contracted.edges)
    return np.minimum(vectors, top)[:, ends[:, 0] >= 0]


@pytest.mark.parametrize("links", [6, 8, 10])
def test_with_multiple_joints_the_exact_test_reads_min_w_h_and_needs_it(links):
    """With a multiple joint, two weight vectors of one H with the same min(w, h) on the exact test's
    strings pass or fail together; min(w, h − 1) is not enough (on some H two vectors that agree on it
    do not), which is why the orbit count's patterns go up to h there."""
    tested = split = 0
    for unit in _units(dict(dof=1, links=links, v=(0, links - 2))):
        graph, conv = unit.contracted, unit.conventions
        vectors = _all_vectors(unit)
        if not any(vertex.is_joint for vertex in graph.vertices) or not len(vectors):
            continue
        passes = stage_b._exact_test(graph.vertices, graph.edges, vectors, conv).tolist()
        for top, rule in ((conv.h, "reads"), (conv.h - 1, "short")):
            by_pattern = defaultdict(set)
            for w, ok in zip(_core_patterns(unit, vectors, top).tolist(), passes):
                by_pattern[tuple(w)].add(ok)
            if rule == "reads":
                assert all(len(results) == 1 for results in by_pattern.values()), unit.key
            else:
                split += any(len(results) == 2 for results in by_pattern.values())
        tested += len(vectors)
    assert tested and (split or links < 10)


@pytest.mark.parametrize("query", [dict(dof=1, links=10), dict(dof=1, links=12), dict(dof=2, links=9),
                                   dict(dof=3, links=10), dict(dof=1, links=11, h=4), dict(dof=0, links=9),
                                   dict(dof=1, links=10, v=(0, 8)), dict(dof=2, links=9, v=(0, 7)),
                                   dict(dof=0, links=9, v=(0, 5)), dict(dof=1, links=11, h=4, v=(0, 6))],
                         ids=lambda q: "-".join(f"{k}{v}" for k, v in q.items()))
def test_the_identity_fixes_every_valid_vector(query, monkeypatch):
    """Fix(identity) of the search is the number of weight vectors the exact test passes, taken up to the
    order of parallel strings (non-decreasing in each bundle, the second string of a bundle on at least its
    own least weight); with multiple joints the pebble games prune and the exact test decides one
    placement per pattern min(w, h)."""
    monkeypatch.setattr(type(next(_units(query)).contracted), "bundle_group", lambda self: ([], True))
    compared = 0
    for unit in _units(query):
        graph, conv = unit.contracted, unit.conventions
        if not stage_b.orbits_apply(unit.code, graph, conv):
            continue
        vectors = _all_vectors(unit)
        _, parallel = stage_b._string_limits(graph, conv)
        for e, least in parallel:
            vectors = vectors[(vectors[:, e] >= vectors[:, e - 1]) & (vectors[:, e] >= least)]
        valid = int(stage_b._exact_test(graph.vertices, graph.edges, vectors, conv).sum()) if len(vectors) else 0
        assert stage_b.count_orbits(unit.code, graph, conv) == valid, unit.key  # the identity alone: Fix(identity)
        compared += 1
    assert compared


QUERIES = [dict(dof=1, links=n) for n in (6, 8, 10, 12)] + [
    dict(dof=2, links=11), dict(dof=3, links=12), dict(dof=0, links=9), dict(dof=2, links=9, fractionated=False),
    dict(dof=1, links=10, rigid_subchains=True), dict(dof=1, links=11, h=4), dict(dof=1, links=12, h=6),
    dict(dof=1, links=10, h=5), dict(dof=1, links=8, h=2), dict(dof=3, links=8, n1=(0, 3)),
    dict(dof=1, links=10, v=(0, 3)), dict(dof=1, links=12, planar_only=True), dict(dof=1, links=10, v=(0, 8)),
    dict(dof=2, links=9, v=(0, 7)), dict(dof=0, links=9, v=(0, 5)), dict(dof=1, links=11, h=4, v=(0, 6)),
    dict(dof=3, links=10, v=(0, 5), n1=(0, 3)),
    # about a CPU minute: every unit of h = 2 with multiple joints (test_counts_by_orbits_equal_the_brute_force covers h = 2)
    pytest.param(dict(dof=1, links=8, h=2, v=(0, 4)), marks=pytest.mark.slow)]


@pytest.mark.parametrize("query", QUERIES, ids=lambda q: "-".join(f"{k}{v}" for k, v in q.items()))
def test_orbits_equal_the_listing_on_every_unit(query):
    """count_orbits == count_realised on every branch multigraph (the listing path: CP-SAT or the
    direct listing at these sizes, lex-least vectors or certificates), where orbits apply and where
    they fall back."""
    applied = 0
    for unit in _units(query):
        args = unit.code, unit.contracted, unit.conventions
        runs = [e for i, e in enumerate(unit.contracted.edges) if not i or e != unit.contracted.edges[i - 1]]
        assert len(runs) == len(set(runs)), unit.key  # parallel strings adjacent: the bundles count_orbits reads
        assert stage_b.count_orbits(*args) == stage_b.count_realised(*args), unit.key
        applied += stage_b.orbits_apply(*args)
    assert applied


@pytest.mark.slow
def test_orbits_equal_the_listing_on_every_unit_of_14_links():
    """The same at 14 links, W = 1 (1 040 units; the listing there is the compiled kernel)."""
    units = list(_units(dict(dof=1, links=14)))
    assert len(units) == 1040
    for unit in units:
        args = unit.code, unit.contracted, unit.conventions
        assert stage_b.count_orbits(*args) == stage_b.count_realised(*args), unit.key


@pytest.mark.slow
def test_orbits_with_multiple_joints_equal_the_listing_on_every_unit_of_12_links():
    """With multiple joints at 12 links, W = 1, v ≤ 10 (6 530 units with a multiple joint): against the
    listing's own count (the kernel's listing without the count's set checks, then the exact test)."""
    units = [u for u in _units(dict(dof=1, links=12, v=(0, 10))) if any(x.is_joint for x in u.contracted.vertices)]
    assert len(units) == 6530
    for unit in units:
        args = unit.code, unit.contracted, unit.conventions
        assert stage_b.orbits_apply(*args) and stage_b.count_orbits(*args) == stage_b.count_listed(*args), unit.key


@pytest.mark.parametrize("dof, links, rigid, v", [(1, 6, False, 0), (1, 8, False, 0), (2, 7, False, 0),
                                                  (3, 8, False, 0), (1, 8, True, 0), (0, 7, True, 0), (1, 8, False, 6),
                                                  (2, 7, False, 5), (0, 7, True, 3)])
def test_counts_by_orbits_equal_the_brute_force(dof, links, rigid, v):
    """Counts by code of the orbit count against the oracle (which shares no code with the engine), with
    multiple joints up to ``v``."""
    got = synth.count_chains(dof, links, rigid_subchains=rigid, workers=1, method="orbits", v=(0, v))
    expected = count_by_code(brute_force_chains_once(links, dof, v_max=v, rigid_subchains=rigid))

    assert engine_counts_by_key(got.by_code) == expected
    assert got.count == sum(expected.values())
    assert any(composition for _, composition in expected) == bool(v)  # chains with multiple joints where asked


def test_the_two_methods_count_alike_by_code_and_apart_in_the_store():
    """count_chains by either method: the same counts by code; a count kept in the store by one
    method is not read back for the other."""
    from synth.synthesis import type_synthesis as ts

    ran = Counter()
    real = ts.count_unit
    try:
        ts.count_unit = lambda unit, method="listing", stats=None: ran.update([method]) or real(unit, method, stats)
        listing = synth.count_chains(1, 10, workers=1, remember=True)
        orbits = synth.count_chains(1, 10, workers=1, remember=True, method="orbits")
    finally:
        ts.count_unit = real
    assert orbits == listing and listing.count == 230
    assert ran["orbits"] == len(list(_units(dict(dof=1, links=10))))  # every unit ran: none read as the listing's


def test_two_joints_on_the_same_links_leave_a_unit_to_the_search():
    """h = 2 with rigid sub-chains allowed (refused by the query): a unit with a multiple joint that
    count_orbits is given is counted as count_realised counts it (from the built chains), under its own
    reason, and one of simple joints under the empty strings'."""
    reasons = Counter()
    for unit in _units(dict(dof=1, links=7, h=2, rigid_subchains=True, v=(0, 3))):
        args = unit.code, unit.contracted, unit.conventions
        stats = {}
        assert stage_b.count_orbits(*args, stats) == stage_b.count_realised(*args), unit.key
        joint = any(vertex.is_joint for vertex in unit.contracted.vertices)
        assert [k for k in stats if k.startswith("by_search_")] == ["by_search_" + ("joint_pairs" if joint else
                                                                                   "empty_strings")], unit.key
        reasons[joint] += 1
    assert reasons[True] and reasons[False]


@pytest.mark.parametrize("options, words", [
    (dict(prismatic="0..2"), "prismatic"), (dict(cranks=["3=2"]), "crank"),
    (dict(h=2, rigid_subchains=True), "h = 2"), (dict(h=2, rigid_subchains=True, v="0..4"), "h = 2")])
def test_orbits_are_refused_where_a_chain_needs_what_they_do_not_check(options, words):
    """Refused, never counted by another method under the name of orbits: prismatic pairs, cranks, two empty
    parallel strings (with h = 2 and rigid sub-chains allowed; with multiple joints there, two joints on the
    same links too)."""
    with pytest.raises(synth.InvalidOption, match=words):
        synth.count_chains(1, options.pop("links", 8), workers=1, method="orbits", **options)


@pytest.mark.parametrize("options", [dict(links=8, v=0), dict(links=8, v="0..0"), dict(code="440/0"),
                                     dict(links=8, v="0..6", max_multiplicity=2), dict(links=8, v="0..6"),
                                     dict(links=8, v="1.."), dict(code="7201/1")])
def test_orbits_count_a_query_given_by_its_v_or_its_code(options):
    """A query of simple joints or with multiple joints (v reaching 1, or a code with v > 0), by its v or
    its code, counts by orbits what the listing counts, every unit by orbits."""
    got = synth.count_chains(1, workers=1, method="orbits", **options)
    assert got == synth.count_chains(1, workers=1, **options) and got.count and not got.by_search
    assert synth.count_chains(1, workers=1, method="orbits", **options) == synth.count_chains(1, workers=1, **options)


def test_an_unknown_method_is_refused():
    with pytest.raises(synth.InvalidOption, match="listing, orbits"):
        synth.count_chains(1, 8, workers=1, method="burnside")


@pytest.mark.parametrize("query, count", [(["--links", "10"], 230), (["--links", "10", "--v", "0..8"], 2645)])
def test_the_command_counts_by_either_method(capsys, query, count):
    """The same counts by code by either method, with multiple joints too (no unit left to the search)."""
    from mechsynth.cli import main

    outputs = []
    for method in ("listing", "orbits"):
        assert main(["chains", "--dof", "1", *query, "--count", "--workers", "1", "--method", method]) == 0
        out, err = capsys.readouterr()
        outputs.append(out)
        assert "counted by the search" not in err
    assert outputs[0] == outputs[1] and f'"count": {count}' in outputs[0]


@pytest.mark.parametrize("argv, words", [
    (["--dof", "1", "--links", "10", "--method", "orbits"], "--method goes with --count"),
    (["--chain", "0-1 1-2 2-3 3-0", "--count", "--method", "orbits"], "not with --chain"),
    (["--dof", "1", "--links", "8", "--count", "--method", "orbits", "--prismatic", "0..2"],
     "cannot be counted by orbits")])
def test_the_command_refuses_a_method_that_cannot_apply(capsys, argv, words):
    from mechsynth.cli import main

    assert main(["chains", *argv]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


@pytest.mark.slow
def test_counts_by_orbits_of_16_links_equal_the_recorded_listing_by_code():
    """The 19 819 281 chains of 16 links counted by orbits, code by code, against the listing's counts
    recorded in benchmarks/logs/bycode_27a4901.json (about a CPU minute a method)."""
    import json
    from pathlib import Path

    recorded = json.loads((Path(__file__).parents[2] / "benchmarks/logs/bycode_27a4901.json").read_text())
    want = recorded["queries"]["dof=1,links=16"]["by_code"]
    got = synth.count_chains(1, 16, workers=2, method="orbits")
    assert got.by_code == want and got.count == 19_819_281


def test_a_group_too_large_to_list_falls_back_to_the_listing(monkeypatch):
    """Where the group of H is not listed whole (forced here: at most one element), a unit is
    counted as the listing counts it, by certificates, and the counts stay."""
    from synth.synthesis import stage_a

    units = list(_units(dict(dof=1, links=10)))
    want = [stage_b.count_orbits(u.code, u.contracted, u.conventions) for u in units]
    monkeypatch.setattr(stage_a, "_GROUP_LIMIT", 1)
    assert any(not u.contracted.edge_group()[1] for u in units)
    assert [stage_b.count_orbits(u.code, u.contracted, u.conventions) for u in units] == want


def test_a_count_by_orbits_says_which_units_it_counted_by_the_search_and_why(monkeypatch):
    """Counts.by_search: the units count_orbits handed to the search, by reason, each reason checked
    against the units read one by one; the counts are the listing's all the same."""
    from synth.synthesis import stage_a

    plain = synth.count_chains(1, 10, workers=1, method="orbits")
    assert (plain.count, plain.units_run, plain.by_search, plain.by_search_note) == (230, 16, {}, None)
    assert plain.units_run == len(synth.plan_units(1, 10))
    # W = 0 with no rigid sub-chain: the whole chain is below the threshold, the kernel's rule does not hold
    exempt = synth.count_chains(0, 9, rigid_subchains=False, workers=1, method="orbits")
    units = synth.plan_units(0, 9, rigid_subchains=False)
    assert all(u.code.dof(3) < u.conventions.threshold for u in units)
    assert exempt.by_search == {"exempt": len(units)} == {"exempt": 22} and exempt.units_run == 22
    assert exempt.by_code == synth.count_chains(0, 9, rigid_subchains=False, workers=1).by_code
    assert exempt.by_search_note.startswith("22 of the 22 units run were counted by the search, not by orbits")
    assert "22 because the chain's W is below" in exempt.by_search_note and "\n" not in exempt.by_search_note
    # groups "too large" (more than one element): every unit whose bundles some automorphism permutes
    units = synth.plan_units(1, 10)
    moved = sum(1 for u in units if u.contracted is not None and u.contracted.bundle_group()[0])
    monkeypatch.setattr(stage_a, "_GROUP_LIMIT", 1)
    forced = synth.count_chains(1, 10, workers=2, method="orbits")  # (the pool's forks inherit the limit)
    assert 0 < moved < len(units) and forced.by_search == {"group": moved} and forced.units_run == 16
    assert forced == plain and forced.to_dict() == plain.to_dict()  # the count and its row (count, by_code) alike


def test_the_command_says_once_on_stderr_which_units_it_counted_by_the_search(monkeypatch, capsys,
                                                                               no_solver_store):
    """``--method orbits``: one line on stderr after the count where some unit was counted by the search,
    none where every unit was counted by orbits; stdout's count keeps its keys in every format."""
    import json

    from mechsynth.cli import main
    from synth.synthesis import stage_a

    argv = ["chains", "--dof", "1", "--links", "10", "--count", "--workers", "1", "--method", "orbits"]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert json.loads(out) == synth.count_chains(1, 10, workers=1).to_dict() and "by the search" not in err
    monkeypatch.setattr(stage_a, "_GROUP_LIMIT", 1)
    moved = sum(1 for u in synth.plan_units(1, 10) if u.contracted is not None and not u.contracted.bundle_group()[1])
    for fmt in ("json", "table"):
        assert main([*argv, "--format", fmt]) == 0
        out, err = capsys.readouterr()
        if fmt == "json":
            assert list(json.loads(out)) == ["count", "by_code"]
        notes = [line for line in err.splitlines() if "by the search" in line]
        assert notes == [f"mechsynth: {moved} of the 16 units run were counted by the search, not by orbits (the "
                         f"same counts, found as the listing finds them): {moved} because the permutations of their "
                         f"branch multigraph's bundles of parallel strings are more than 4 096, too many to list"]


def test_a_count_by_orbits_resumes_from_its_checkpoint(tmp_path, monkeypatch):
    """Ctrl-C in the middle of a count by orbits with a checkpoint: the rerun computes only the units
    left and gives the whole count; the listing is refused that checkpoint (another method's)."""
    from synth.synthesis import type_synthesis as ts

    real, calls = ts.count_unit, []

    def interrupted(unit, method="listing", stats=None):
        if len(calls) == 7:
            raise KeyboardInterrupt
        calls.append(unit.key)
        return real(unit, method, stats)

    path = tmp_path / "c.sqlite"
    monkeypatch.setattr(ts, "count_unit", interrupted)
    with pytest.raises(KeyboardInterrupt):
        synth.count_chains(1, 10, workers=1, checkpoint=path, method="orbits")
    done = list(calls)
    calls.clear()
    monkeypatch.setattr(ts, "count_unit", lambda unit, method="listing", stats=None: (calls.append(unit.key),
                                                                                       real(unit, method, stats))[1])
    assert synth.count_chains(1, 10, workers=1, checkpoint=path, method="orbits").count == 230
    assert len(done) == 7 and not set(done) & set(calls) and len(done) + len(calls) == len(synth.plan_units(1, 10))
    with pytest.raises(synth.SynthesisError, match="belongs to another query"):
        synth.count_chains(1, 10, workers=1, checkpoint=path)
