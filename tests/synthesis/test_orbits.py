"""Counting by orbits (Burnside's lemma over the automorphisms of each branch multigraph H,
``stage_b.count_orbits``) against the listing path and the brute-force oracle.

* the claim it rests on: the exact sub-chain test of a weight vector depends only on its
  pattern min(w_e, h − 1), checked on every weight vector of every H up to 12 links (W = 1);
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


@pytest.mark.parametrize("query", [dict(dof=1, links=10), dict(dof=1, links=12), dict(dof=2, links=9),
                                   dict(dof=3, links=10), dict(dof=1, links=11, h=4), dict(dof=0, links=9)],
                         ids=lambda q: "-".join(f"{k}{v}" for k, v in q.items()))
def test_the_identity_fixes_every_valid_vector(query):
    """Fix(identity) of the search is the number of weight vectors the exact test passes."""
    from synth.synthesis._stage_b_kernel import fixed_total

    compared = 0
    for unit in _units(query):
        graph, conv = unit.contracted, unit.conventions
        if not stage_b.orbits_apply(unit.code, graph, conv):
            continue
        vectors = _all_vectors(unit)
        valid = int(stage_b._exact_test(graph.vertices, graph.edges, vectors, conv).sum()) if len(vectors) else 0
        # every string a bundle of its own and the identity alone: the search counts labelled vectors
        lows, _ = stage_b._string_limits(graph, conv)
        inner, k, _, _ = stage_b._pebble_vertices(graph.vertices, conv.h, conv.threshold)
        a_end, b_end = (np.array(x, dtype=np.int64) for x in stage_b._game_ends(graph, inner))
        C, l, n2 = conv.h - 1, conv.h + conv.threshold, unit.code.count(2)
        b0 = n2 - sum(C if a >= 0 else low for a, low in zip(a_end, lows))
        x_most, need = stage_b._deficit_bounds(k, l, b0, n2, conv.h)
        E = len(graph.edges)
        least = np.array(lows, dtype=np.int64)
        fixed = fixed_total(len(inner), a_end, b_end, least, least, np.ones(E, dtype=np.int64), n2, k, C, l, x_most,
                            need, np.arange(E, dtype=np.int64)[None, :])
        assert fixed == valid, unit.key
        compared += 1
    assert compared


QUERIES = [dict(dof=1, links=n) for n in (6, 8, 10, 12)] + [
    dict(dof=2, links=11), dict(dof=3, links=12), dict(dof=0, links=9), dict(dof=2, links=9, fractionated=False),
    dict(dof=1, links=10, rigid_subchains=True), dict(dof=1, links=11, h=4), dict(dof=1, links=12, h=6),
    dict(dof=1, links=10, h=5), dict(dof=1, links=8, h=2), dict(dof=3, links=8, n1=(0, 3)),
    dict(dof=1, links=10, v=(0, 3)), dict(dof=1, links=12, planar_only=True)]


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
    assert applied or query.get("v")


@pytest.mark.slow
def test_orbits_equal_the_listing_on_every_unit_of_14_links():
    """The same at 14 links, W = 1 (1 040 units; the listing there is the compiled kernel)."""
    units = list(_units(dict(dof=1, links=14)))
    assert len(units) == 1040
    for unit in units:
        args = unit.code, unit.contracted, unit.conventions
        assert stage_b.count_orbits(*args) == stage_b.count_realised(*args), unit.key


@pytest.mark.parametrize("dof, links, rigid", [(1, 6, False), (1, 8, False), (2, 7, False), (3, 8, False),
                                               (1, 8, True), (0, 7, True)])
def test_counts_by_orbits_equal_the_brute_force(dof, links, rigid):
    """Counts by code of the orbit count against the oracle (which shares no code with the engine)."""
    got = synth.count_chains(dof, links, rigid_subchains=rigid, workers=1, method="orbits")
    expected = count_by_code(brute_force_chains_once(links, dof, rigid_subchains=rigid))

    assert engine_counts_by_key(got.by_code) == expected
    assert got.count == sum(expected.values())


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


@pytest.mark.parametrize("options, words", [
    (dict(prismatic="0..2"), "prismatic"), (dict(cranks=["3=2"]), "crank"),
    (dict(h=2, rigid_subchains=True), "h = 2"), (dict(v="0..6"), "multiple joints"), (dict(v="1.."), "multiple joints"),
    (dict(links=None, code="7201/1"), "multiple joints")])
def test_orbits_are_refused_where_a_chain_needs_what_they_do_not_check(options, words):
    """Refused, never counted by another method under the name of orbits: prismatic pairs, cranks, two empty
    parallel strings, and any chain with a multiple joint (a range of v reaching 1, or a code with v > 0)."""
    with pytest.raises(synth.InvalidOption, match=words):
        synth.count_chains(1, options.pop("links", 8), workers=1, method="orbits", **options)


@pytest.mark.parametrize("options", [dict(links=8, v=0), dict(links=8, v="0..0"), dict(code="440/0"),
                                     dict(links=8, v="0..6", max_multiplicity=2)])
def test_orbits_count_a_query_of_simple_joints_given_by_its_v_or_its_code(options):
    """v = 0 (or a code of simple joints) is not refused, and counts what the listing counts."""
    assert synth.count_chains(1, workers=1, method="orbits", **options) == synth.count_chains(1, workers=1, **options)


def test_an_unknown_method_is_refused():
    with pytest.raises(synth.InvalidOption, match="listing, orbits"):
        synth.count_chains(1, 8, workers=1, method="burnside")


def test_the_command_counts_by_either_method(capsys):
    from mechsynth.cli import main

    outputs = []
    for method in ("listing", "orbits"):
        assert main(["chains", "--dof", "1", "--links", "10", "--count", "--workers", "1", "--method", method]) == 0
        outputs.append(capsys.readouterr().out)
    assert outputs[0] == outputs[1] and '"count": 230' in outputs[0]


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
