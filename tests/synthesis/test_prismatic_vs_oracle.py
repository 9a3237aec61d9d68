"""Prismatic pairs: the count, the generic mobility and idle joints against an independent
Jacobian (floating point, tests/oracles/prismatic.py), variant counts against a brute force over
permutations, and what ``--dof`` means with wedge loops (the h = 2 chains are the all-P ones)."""

from __future__ import annotations

import json
from itertools import product

import networkx as nx
import numpy as np
import pytest

from synth import Chain, ChainQuery, InvalidOption, count_chains, type_synthesis
from synth.structure.kinds import generic_mobility, idle_joints, kind_count, structural_mobility, wedge_loops
from synth.structure.subchains import check_subchains
from synth.synthesis.type_synthesis import mechanisms_of
from synth.synthesis.variants import prismatic_variants
from tests.oracles import prismatic as oracle

FOUR_BAR = Chain.parse("0-1 1-2 2-3 3-0")
WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
STEPHENSON = Chain.parse("0-2 2-1 0-3 3-1 0-4 4-5 5-1")  # ternaries 0, 1 not adjacent


def _assignments(chain: Chain):
    for bits in product(("revolute", "prismatic"), repeat=len(chain.joints)):
        yield Chain(chain.links, chain.joints, bits)


def _kinds(chain: Chain):
    return chain.kinds


def _hidden(chain: Chain, rng) -> list[Chain]:
    """Every R/P assignment: the engine's generic mobility and idle joints equal the oracle's;
    the count is never above the generic mobility; the assignments without idle joints where
    they differ (a hidden redundant constraint) are returned."""
    out = []
    for variant in _assignments(chain):
        kinds = _kinds(variant)
        assert structural_mobility(variant) == oracle.count_rule(chain.links, variant.joints, kinds)
        truth = oracle.generic_mobility(chain.links, variant.joints, kinds, rng)
        assert generic_mobility(variant) == truth, variant
        assert set(idle_joints(variant)) == set(oracle.idle_joints(chain.links, variant.joints, kinds, rng)), variant
        assert structural_mobility(variant) <= truth
        if (truth == 0 or not idle_joints(variant)) and structural_mobility(variant) != truth:
            out.append(variant)
    return out


@pytest.mark.parametrize("dof,links,hidden", [(1, 4, 0), (1, 6, 0), pytest.param(1, 8, 0, marks=pytest.mark.slow), (2, 5, 0), (2, 7, 0), (3, 6, 0),
                                              (0, 3, 0), (0, 5, 0),
                                              pytest.param(0, 7, 33, marks=pytest.mark.slow),
                                              pytest.param(3, 8, 0, marks=pytest.mark.slow)])
def test_count_and_generic_mobility_on_every_assignment(dof, links, hidden):
    """Every chain of the atlas and every R/P assignment: generic mobility and idle joints as the
    oracle finds them; the count equals the generic mobility except on assignments with a hidden
    redundancy, which the exact test refuses: in mobile chains they always come with idle joints
    (at 8 links a revolute four-bar whose opposite links two chains of P pairs hold parallel cannot
    move), in trusses they make a structure move that the count calls rigid."""
    rng = np.random.default_rng(dof * 100 + links)
    chains = list(type_synthesis(dof, links, workers=1))
    assert chains
    found = [v for chain in chains for v in _hidden(chain, rng)]
    assert len(found) == hidden
    for v in found:
        assert check_subchains(v, rigid_subchains=True).kind == "redundant constraints"
        kept = {c.certificate for c in prismatic_variants(Chain(v.links, v.joints), kind_count(v, "prismatic"),
                                                          idle=True)}
        assert v.certificate not in kept


def test_count_equals_jacobian_rank_on_every_small_graph():
    """Every connected simple graph of 3…5 links, every R/P assignment that moves (W ≥ 1 by the
    count) without idle joints and without an over-constrained sub-chain: the count is the generic
    mobility; all-P loops rescue chains that are over-constrained as revolute chains (two wedge
    triangles on a common pair).  (A truss by the count may hide a redundancy that lets it move:
    the exact test's rank finds those.)"""
    rng = np.random.default_rng(5)
    checked = rescued = 0
    for g in nx.graph_atlas_g():
        if not 3 <= g.number_of_nodes() <= 5 or not nx.is_connected(g):
            continue
        base = Chain(g.number_of_nodes(), list(g.edges()))
        for variant in _assignments(base):
            if (structural_mobility(variant) < 1 or idle_joints(variant)
                    or check_subchains(variant, rigid_subchains=True).worst_mobility < 0):
                continue
            kinds = _kinds(variant)
            assert structural_mobility(variant) == oracle.generic_mobility(base.links, variant.joints, kinds, rng)
            checked += 1
            rescued += base.dof < 0
    assert checked > 150 and rescued > 0


def test_idle_joints_beyond_the_prismatic_path_rule():
    """The four-bar 0-2-1-3 cannot move when 0=4=5=1 locks the rotation of 1 against 0, though no
    revolute joint has its own links on a P path: its four pins are idle, only the wedge slides."""
    locked = Chain.parse("0-2 0-3 0=4 1-2 1-3 1=5 4=5")
    assert idle_joints(locked) == [(0, 2), (0, 3), (1, 2), (1, 3)] and generic_mobility(locked) == 1
    assert set(oracle.idle_joints(6, locked.joints, locked.kinds, np.random.default_rng(3))) == set(idle_joints(locked))
    c = Chain(4, FOUR_BAR.joints, ["prismatic", "prismatic", "prismatic", "revolute"])
    assert len(idle_joints(c)) == 1 and structural_mobility(c) == generic_mobility(c) == 1
    assert prismatic_variants(FOUR_BAR, 3) == [] and len(prismatic_variants(FOUR_BAR, 3, idle=True)) == 1
    # the query lists no chain with idle joints unless asked
    rows = list(type_synthesis(1, 6, prismatic=3, workers=1))
    assert locked.certificate not in {c.certificate for c in rows}
    assert locked.certificate in {c.certificate for c in type_synthesis(1, 6, prismatic=3, idle_joints=True,
                                                                         workers=1)}


@pytest.mark.parametrize("chain,counts", [(FOUR_BAR, range(5)), (WATT, (1, 2)), (STEPHENSON, (1, 2))])
def test_variant_counts_match_brute_force(chain, counts):
    for k in counts:
        for idle in (False, True):
            got = len(prismatic_variants(chain, k, idle=idle))
            assert got == oracle.brute_variant_count(chain.links, chain.joints, k, idle=idle), (k, idle)


@pytest.mark.parametrize("chain", [FOUR_BAR, WATT, STEPHENSON])
def test_mechanism_counts_match_brute_force(chain):
    """Each variant with a fixed link: the inversions (slider-crank: guide or slider fixed, …)."""
    for k in (1, 2):
        got = sum(len(mechanisms_of(v)) for v in prismatic_variants(chain, k))
        assert got == oracle.brute_variant_count(chain.links, chain.joints, k, frames=True), k


def test_dof_is_the_mobility_of_every_chain_returned():
    """--dof 1 with prismatic pairs: the all-P four-bar (a wedge loop, W = 2) is not a 1-DOF chain;
    every chain listed has W = 1 by the count and by the generic mobility."""
    chains = list(type_synthesis(1, 4, prismatic="0..4", workers=1))
    assert [kind_count(c, "prismatic") for c in chains] == [0, 1, 2, 2]
    for links in (4, 5, 6):
        for c in type_synthesis(1, links, prismatic="0..", workers=1):
            assert c.dof == generic_mobility(c) == 1 and not idle_joints(c), c.compact()
    (wedge,) = prismatic_variants(FOUR_BAR, 4)
    assert (structural_mobility(wedge), wedge_loops(wedge)) == (2, 1)
    assert [c.certificate for c in type_synthesis(2, 4, prismatic=4, workers=1)] == [wedge.certificate]


@pytest.mark.parametrize("links", [5, 6, 7])
def test_all_prismatic_chains_are_the_wedge_systems(links):
    """A chain of prismatic pairs only is a wedge system (motion space h = 2): the 1-DOF chains with
    2(n − 1) − 1 P pairs, found on revolute skeletons of W = 1 − K_2, are exactly the h = 2 chains,
    code by code."""
    p = 2 * (links - 1) - 1
    with_p = count_chains(1, links, prismatic=p, workers=1)["by_code"]
    wedge = count_chains(1, links, h=2, workers=1)["by_code"]
    assert {code.split(" P")[0]: n for code, n in with_p.items()} == wedge


def test_wedge_lever_system():
    """Task 3: 5 links, n2 = 3, n3 = 2, one wedge loop and one lever loop, W = 1, found by the query
    `chains --dof 1 --links 5 --prismatic 1..6`: its revolute skeletons are the 5-link trusses."""
    found = list(type_synthesis(1, 5, prismatic="1..6", workers=1))
    assert found and all(str(c.code) == "32/0" and wedge_loops(c) == 1 and c.loops == 2 for c in found)
    assert "32/0" in {str(c.code) for c in type_synthesis(0, 5, workers=1)}  # a truss as a revolute chain
    fewest = min(kind_count(c, "prismatic") for c in found)
    (lever,) = [c for c in found if kind_count(c, "prismatic") == fewest]
    assert fewest == 3 and sorted(lever.degrees) == [2, 2, 2, 3, 3]
    prismatic = [j for j, k in zip(lever.joints, lever.kinds) if k == "prismatic"]
    assert len({x for j in prismatic for x in j}) == 3  # the three P pairs close one triangle


@pytest.mark.parametrize("call,message", [
    (lambda: prismatic_variants(FOUR_BAR, 5), "only 4 simple joints"),
    (lambda: prismatic_variants(Chain(3, [(0, 1, 2), (0, 1, 2)]), 1),
     "^prismatic pairs go on simple joints and this chain has multiple joints only$"),  # parse refuses twins
    (lambda: prismatic_variants(FOUR_BAR, -1), "≥ 0"),
    (lambda: prismatic_variants(FOUR_BAR, True), "whole number ≥ 0, not True"),
    (lambda: prismatic_variants(FOUR_BAR, 1.0), "whole number ≥ 0, not 1.0"),
    (lambda: prismatic_variants(Chain.parse("0=1 1-2 2-3 3-0"), 1), r"joint kinds already \(0=1 0-3 1-2 2-3\)"),
    (lambda: ChainQuery(1, 4, h=4, prismatic=1), "planar chains"),
    (lambda: ChainQuery(1, 4, cylinders="floating=1"), "cylinders go with prismatic pairs"),
    (lambda: ChainQuery(1, 4, prismatic=1, cylinders="rolling=1"), "guide, swinging, floating or slider"),
])
def test_refusals(call, message):
    with pytest.raises(InvalidOption, match=message):
        call()


def test_no_prismatic_pair_asked_for_is_no_refusal():
    """Zero prismatic pairs on a chain without simple joints is the chain itself, kept if it passes:
    two pins on the same three links (W = 6 − 8 < 0) do not."""
    assert prismatic_variants(Chain(3, [(0, 1, 2), (0, 1, 2)]), 0) == []
    assert prismatic_variants(FOUR_BAR, 0) == [FOUR_BAR]


def _cli(capsys, argv):
    from mechsynth.cli import main

    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_four_bar_variants_match_brute_force(capsys):
    code, out, _ = _cli(capsys, ["chains", "--dof", "1", "--links", "4", "--prismatic", "0..4", "--count",
                                 "--workers", "1"])
    by_code = json.loads(out)["by_code"]
    expected = {k: oracle.brute_variant_count(4, FOUR_BAR.joints, k) for k in range(4)}  # (P4: W = 2)
    assert code == 0 and {k: by_code.get(f"4/0 P{k}" if k else "4/0", 0) for k in range(4)} == expected


def test_cli_wedge_lever_query(capsys):
    """Task 3 found by a query over the truss code 32/0 with three P pairs and W = 1."""
    code, out, _ = _cli(capsys, ["chains", "--dof", "1", "--code", "32/0", "--prismatic", "3", "--format", "jsonl",
                                 "--workers", "1"])
    rows = [json.loads(line) for line in out.splitlines()]
    assert code == 0 and len(rows) == 1
    assert (rows[0]["code"], rows[0]["dof"], rows[0]["loops_2"], rows[0]["loops_3"]) == ("32/0 P3", 1, 1, 1)
    code, out, _ = _cli(capsys, ["chains", "--dof", "1", "--links", "5", "--prismatic", "1..6", "--count",
                                 "--workers", "1"])
    assert code == 0 and json.loads(out) == {"count": 4, "by_code": {"32/0 P3": 1, "32/0 P4": 3}}


@pytest.mark.parametrize("argv,message", [
    (["chains", "--dof", "1", "--links", "4", "--prismatic", "7"], "7 prismatic pairs do not fit"),
    (["chains", "--code", "12.0/8-0", "--prismatic", "1"], "no simple joint"),
    (["chains", "--dof", "1", "--links", "4", "--idle-joints"], "--idle-joints goes with --prismatic"),
    (["chains", "--dof", "1", "--links", "4", "--prismatic", "-1"], "prismatic pairs"),
    (["chains", "--dof", "1", "--links", "4", "--prismatic", "1", "--count", "--checkpoint", "x.db"], "--checkpoint"),
    (["mechanisms", "--dof", "1", "--links", "4", "--cylinders", "floating=1"], "--cylinders goes with --prismatic"),
])
def test_cli_refusals(capsys, argv, message):
    code, out, err = _cli(capsys, argv + ["--workers", "1"])
    assert code == 2 and err.startswith("mechsynth: ") and message in err and err.count("\n") == 1


def test_atlas_export_of_variants_matches_chains_query(capsys, tmp_path):
    """The atlas's chains, exported with --prismatic, give the same counts as the chains query
    (one or two P pairs close no wedge loop: W stays the chains')."""
    grid = tmp_path / "g.toml"
    grid.write_text('dof = 1\nlinks = "4..6"\n')
    db = str(tmp_path / "a.sqlite")
    assert _cli(capsys, ["grid", str(grid), "--db", db, "--workers", "1"])[0] == 0
    code, out, _ = _cli(capsys, ["atlas", "--db", db, "--prismatic", "1..2", "--count"])
    by_code = json.loads(out)["by_code"]
    expected = {}
    for links in (4, 6):
        _, out, _ = _cli(capsys, ["chains", "--dof", "1", "--links", str(links), "--prismatic", "1..2", "--count",
                                  "--workers", "1"])
        expected.update(json.loads(out)["by_code"])
    assert code == 0 and by_code == expected
    assert _cli(capsys, ["atlas", "--db", db, "--idle-joints"])[0] == 2


def test_multiple_joint_locked_by_prismatic_string_is_idle():
    """The double joint 0-1-4 turns links 1 and 4 about one pin; P pairs along 1-2-3-4 lock them,
    while the wedge slides (W = 1).  Pin 1-2 instead of a slider and the double joint turns."""
    c = Chain(6, [(0, 1, 4), (1, 2), (2, 3), (3, 4), (0, 5), (2, 5)],
              ["revolute", "prismatic", "prismatic", "prismatic", "revolute", "revolute"])
    assert idle_joints(c) == [(0, 1, 4)] and generic_mobility(c) == 1
    assert set(oracle.idle_joints(6, c.joints, c.kinds, np.random.default_rng(2))) == {(0, 1, 4)}
    free = Chain(6, c.joints, ["revolute", "revolute", "prismatic", "prismatic", "revolute", "revolute"])
    assert idle_joints(free) == [] == oracle.idle_joints(6, free.joints, _kinds(free), np.random.default_rng(2))


def test_cli_one_chain(capsys):
    """Fig. 6 from the command line: the variants of one given chain, each with its own W; refusals."""
    code, out, _ = _cli(capsys, ["chains", "--chain", "0-1 1-2 2-3 3-0", "--prismatic", "0..4", "--count"])
    assert code == 0 and json.loads(out)["count"] == sum(oracle.brute_variant_count(4, FOUR_BAR.joints, k)
                                                         for k in range(5))
    for argv, message in ((["--prismatic", "5"], "only 4 simple joints"), (["--prismatic", "1", "--dof", "1"], "--dof"),
                          (["--idle-joints"], "--idle-joints and --cylinders go with --prismatic")):
        code, _, err = _cli(capsys, ["chains", "--chain", "0-1 1-2 2-3 3-0", *argv])
        assert code == 2 and message in err and err.count("\n") == 1


def test_grid_stores_variants_checked_by_brute_force(capsys, tmp_path):
    """A grid with the key 'prismatic' stores every chain of the cell's W once: per code and P count
    as many as the brute force over assignments finds, each with the W of the Jacobian rank; --where
    P= selects them, and atlas --prismatic still builds variants of the revolute chains only."""
    grid = tmp_path / "g.toml"
    grid.write_text('dof = 1\nlinks = "4..6"\nprismatic = "0..2"\n')
    db = str(tmp_path / "a.sqlite")
    assert _cli(capsys, ["grid", str(grid), "--db", db, "--workers", "1"])[0] == 0
    _, out, _ = _cli(capsys, ["atlas", "--db", db, "--format", "json"])
    stored = json.loads(out)["by_code"]
    expected = {}
    for links in (4, 6):
        for chain in type_synthesis(1, links, workers=1):
            for k in range(3):
                name = str(chain.code) + (f" P{k}" if k else "")
                expected[name] = expected.get(name, 0) + oracle.brute_variant_count(chain.links, chain.joints, k)
    assert stored == {c: n for c, n in expected.items() if n}
    _, out, _ = _cli(capsys, ["atlas", "--db", db, "--where", "P=2", "--export", "chains", "--format", "jsonl"])
    rows = [json.loads(line) for line in out.splitlines()]
    assert len(rows) == stored["4/0 P2"] + stored["42/0 P2"]
    rng = np.random.default_rng(7)
    for row in rows:
        chain = Chain.from_dict(row)
        assert chain.kinds.count("prismatic") == 2
        assert row["dof"] == oracle.generic_mobility(chain.links, chain.joints, chain.kinds, rng)
    _, out, _ = _cli(capsys, ["atlas", "--db", db, "--where", "n=6", "--prismatic", "1", "--count"])
    assert json.loads(out)["count"] == stored["42/0 P1"]


@pytest.mark.parametrize("text, message", [
    ('dof = 1\nlinks = 5\nh = 4\nprismatic = 1\n', "planar chains"),
    ('dof = 1\nlinks = 4\nidle_joints = true\n', "goes with 'prismatic'"),
    ('dof = 1\nlinks = 4\nprismatic = "x"\n', "prismatic"),
])
def test_grid_prismatic_refusals(tmp_path, capsys, text, message):
    grid = tmp_path / "g.toml"
    grid.write_text(text)
    code, _, err = _cli(capsys, ["grid", str(grid), "--db", str(tmp_path / "a.sqlite"), "--workers", "1"])
    assert code == 2 and message in err and err.count("\n") == 1 and "Traceback" not in err
