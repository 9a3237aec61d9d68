"""Prismatic pairs: the wedge rule against the Jacobian rank, variant counts against a brute force."""

from __future__ import annotations

from itertools import product

import networkx as nx
import numpy as np
import pytest

from tests.oracles.prismatic import brute_variant_count, count_rule, generic_mobility, has_idle_joint
from synth.synthesis.type_synthesis import type_synthesis
from synth.structure.chain import Chain
from synth.errors import InvalidOption
from synth.synthesis.variants import generic_mobility as exact_generic_mobility
from synth.synthesis.variants import (idle_joints, prismatic_count, prismatic_variants, wedge_loops, wedge_mobility,
                             wedge_subchain_minimum)

FOUR_BAR = Chain.parse("0-1 1-2 2-3 3-0")
WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
STEPHENSON = Chain.parse("0-2 2-1 0-3 3-1 0-4 4-5 5-1")  # ternaries 0, 1 not adjacent


def _assignments(chain: Chain):
    for bits in product(("revolute", "prismatic"), repeat=len(chain.joints)):
        yield Chain(chain.links, chain.joints, bits)


def _disagreements(chain: Chain, rng) -> list[Chain]:
    """Assignments without idle joints where the count and the Jacobian rank differ."""
    out = []
    for variant in _assignments(chain):
        kinds = variant.kinds or ("revolute",) * len(chain.joints)
        assert bool(idle_joints(variant)) == has_idle_joint(chain.links, variant.joints, kinds)
        assert wedge_mobility(variant) == count_rule(chain.links, variant.joints, kinds)
        if idle_joints(variant):
            continue
        jacobian = generic_mobility(chain.links, variant.joints, kinds, rng)
        assert exact_generic_mobility(variant) == jacobian, variant
        if wedge_mobility(variant) != jacobian:
            assert jacobian > wedge_mobility(variant)  # a hidden redundant constraint, never a lost one
            out.append(variant)
    return out


@pytest.mark.parametrize("dof,links,hidden", [(1, 4, 0), (1, 6, 0), (1, 8, 1), (2, 5, 0), (2, 7, 0), (3, 6, 0),
                                              (0, 3, 0), (0, 5, 0),
                                              pytest.param(0, 7, 33, marks=pytest.mark.slow),
                                              pytest.param(3, 8, 0, marks=pytest.mark.slow)])
def test_wedge_rule_against_jacobian_rank_on_every_assignment(dof, links, hidden):
    """Every chain of the atlas and every R/P assignment without idle joints: the count equals the
    generic mobility except on a few assignments with a hidden redundancy (at 8 links: a revolute
    four-bar loop whose opposite links are held parallel by two chains of P pairs), which the engine
    recognises by the exact rank and leaves out."""
    rng = np.random.default_rng(dof * 100 + links)
    chains = list(type_synthesis(dof, links, workers=1))
    assert chains
    found = [v for chain in chains for v in _disagreements(chain, rng)]
    assert len(found) == hidden
    for v in found:
        kept = {c.certificate for c in prismatic_variants(Chain(v.links, v.joints), prismatic_count(v), idle=True)}
        assert v.certificate not in kept


def test_wedge_rule_equals_jacobian_rank_on_every_small_graph():
    """Every connected simple graph of 3…5 links, every R/P assignment without idle joints and
    without an over-constrained sub-chain: here all-P loops rescue chains that are over-constrained
    as revolute chains (two wedge triangles on a common pair: W = 1)."""
    rng = np.random.default_rng(5)
    checked = rescued = 0
    for g in nx.graph_atlas_g():
        if not 3 <= g.number_of_nodes() <= 5 or not nx.is_connected(g):
            continue
        base = Chain(g.number_of_nodes(), list(g.edges()))
        for variant in _assignments(base):
            if idle_joints(variant) or wedge_subchain_minimum(variant)[0] < 0 or wedge_mobility(variant) < 0:
                continue
            kinds = variant.kinds or ("revolute",) * len(base.joints)
            assert wedge_mobility(variant) == generic_mobility(base.links, variant.joints, kinds, rng), variant
            checked += 1
            rescued += base.dof < 0
    assert checked > 300 and rescued > 0


def test_idle_joint_never_turns():
    """A four-bar with three P pairs moves (W = 1: three slides close a triangle of displacements)
    but its revolute pair never turns: it is an idle joint, left out unless asked for."""
    c = Chain(4, FOUR_BAR.joints, ["prismatic", "prismatic", "prismatic", "revolute"])
    assert len(idle_joints(c)) == 1 and wedge_mobility(c) == 1
    assert generic_mobility(4, c.joints, c.kinds, np.random.default_rng(1)) == 1
    assert prismatic_variants(FOUR_BAR, 3) == [] and len(prismatic_variants(FOUR_BAR, 3, idle=True)) == 1


@pytest.mark.parametrize("chain,counts", [(FOUR_BAR, range(5)), (WATT, (1, 2)), (STEPHENSON, (1, 2))])
def test_variant_counts_match_brute_force(chain, counts):
    for k in counts:
        for idle in (False, True):
            got = len(prismatic_variants(chain, k, idle=idle))
            assert got == brute_variant_count(chain.links, chain.joints, k, idle=idle), (k, idle)


@pytest.mark.parametrize("chain", [FOUR_BAR, WATT, STEPHENSON])
def test_mechanism_counts_match_brute_force(chain):
    """Each variant with a fixed link: the inversions (slider-crank: guide or slider fixed, …)."""
    from synth.synthesis.type_synthesis import mechanisms_of

    for k in (1, 2):
        got = sum(len(mechanisms_of(v)) for v in prismatic_variants(chain, k))
        assert got == brute_variant_count(chain.links, chain.joints, k, frames=True), k


def test_four_bar_counts():
    """R-R-R-R; slider-crank; two P pairs adjacent (Scotch yoke) or opposite; three P pairs always
    make an idle joint; four P pairs: the wedge loop of W = 2."""
    (wedge,) = prismatic_variants(FOUR_BAR, 4)
    assert (wedge_mobility(wedge), wedge_loops(wedge)) == (2, 1)


def test_wedge_lever_system():
    """Task 3: 5 links, n2 = 3, n3 = 2, one wedge loop and one lever loop, W = 1.  The code 32/0 is a
    truss as a revolute chain; P pairs that close a wedge loop give it one freedom.  The fewest P
    pairs: a wedge triangle (three P pairs) and a lever four-bar sharing one of its links' pairs."""
    found = [c for base in type_synthesis(0, 5, code="32/0", workers=1)
             for k in range(7) for c in prismatic_variants(base, k) if wedge_mobility(c) == 1]
    assert found and all(str(c.code) == "32/0" and wedge_loops(c) == 1 and c.loops == 2 for c in found)
    fewest = min(prismatic_count(c) for c in found)
    (lever,) = [c for c in found if prismatic_count(c) == fewest]
    assert fewest == 3 and sorted(lever.degrees) == [2, 2, 2, 3, 3]
    prismatic = [j for j, k in zip(lever.joints, lever.kinds) if k == "prismatic"]
    assert len({x for j in prismatic for x in j}) == 3  # the three P pairs close one triangle


@pytest.mark.parametrize("call,message", [
    (lambda: prismatic_variants(FOUR_BAR, 5), "only 4 simple joints"),
    (lambda: prismatic_variants(Chain(3, [(0, 1, 2), (0, 1, 2)]), 1), "multiple joints only"),  # parse refuses twins
    (lambda: prismatic_variants(FOUR_BAR, -1), "≥ 0"),
])
def test_refusals(call, message):
    with pytest.raises(InvalidOption, match=message):
        call()


def _cli(capsys, argv):
    from mechsynth.cli import main

    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_four_bar_variants_match_brute_force(capsys):
    import json

    code, out, _ = _cli(capsys, ["chains", "--dof", "1", "--links", "4", "--prismatic", "0..4", "--count",
                                 "--workers", "1"])
    by_code = json.loads(out)["by_code"]
    expected = {k: brute_variant_count(4, FOUR_BAR.joints, k) for k in range(5)}
    assert code == 0 and {k: by_code.get(f"4/0 P{k}" if k else "4/0", 0) for k in range(5)} == expected


def test_cli_wedge_lever_query(capsys):
    """Task 3 found by a query: the truss code 32/0 with three P pairs, the row with W = 1."""
    import json

    code, out, _ = _cli(capsys, ["chains", "--code", "32/0", "--prismatic", "3", "--format", "jsonl", "--workers", "1"])
    rows = [json.loads(line) for line in out.splitlines()]
    lever = [r for r in rows if r["dof"] == 1]
    assert code == 0 and len(lever) == 1
    assert (lever[0]["code"], lever[0]["loops_2"], lever[0]["loops_3"]) == ("32/0 P3", 1, 1)


@pytest.mark.parametrize("argv,message", [
    (["chains", "--dof", "1", "--links", "4", "--prismatic", "5"], "more prismatic pairs than the 4 simple joints"),
    (["chains", "--code", "12.0/8-0", "--prismatic", "1"], "multiple joints only"),
    (["chains", "--dof", "1", "--links", "4", "--idle-joints"], "--idle-joints goes with --prismatic"),
    (["chains", "--dof", "1", "--links", "4", "--prismatic", "-1"], "--prismatic"),
    (["chains", "--dof", "1", "--links", "4", "--prismatic", "1", "--count", "--checkpoint", "x.db"], "--checkpoint"),
])
def test_cli_refusals(capsys, argv, message):
    code, out, err = _cli(capsys, argv + ["--workers", "1"])
    assert code == 2 and err.startswith("mechsynth: ") and message in err and err.count("\n") == 1


def test_atlas_export_of_variants_matches_chains_query(capsys, tmp_path):
    """The atlas's chains, exported with --prismatic, give the same counts as the chains query."""
    import json

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
    """The double joint 0-1-4 turns links 1 and 4 about one pin; P pairs along 1-2-3-4 lock them."""
    c = Chain(5, [(0, 1, 4), (1, 2), (2, 3), (3, 4), (0, 2)],
              ["revolute", "prismatic", "prismatic", "prismatic", "revolute"])
    assert idle_joints(c) == [(0, 1, 4)]
    assert idle_joints(Chain(5, c.joints, ["revolute", "revolute", "prismatic", "prismatic", "revolute"])) == []


def test_cli_one_chain(capsys):
    """Fig. 6 from the command line: the variants of one given chain; its refusals."""
    import json

    code, out, _ = _cli(capsys, ["chains", "--chain", "0-1 1-2 2-3 3-0", "--prismatic", "0..4", "--count"])
    assert code == 0 and json.loads(out)["count"] == sum(brute_variant_count(4, FOUR_BAR.joints, k) for k in range(5))
    for argv, message in ((["--prismatic", "5"], "only 4 simple joints"), (["--prismatic", "1", "--dof", "1"], "--dof"),
                          ([], "--chain goes with --prismatic")):
        code, _, err = _cli(capsys, ["chains", "--chain", "0-1 1-2 2-3 3-0", *argv])
        assert code == 2 and message in err and err.count("\n") == 1


def test_grid_stores_variants_checked_by_brute_force(capsys, tmp_path):
    """A grid with the key 'prismatic' stores every variant once: per code and P count as many as the
    brute force over assignments finds, each with the W of the Jacobian rank; --where P= selects them,
    and atlas --prismatic still builds variants of the revolute chains only."""
    import json

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
                expected[name] = expected.get(name, 0) + brute_variant_count(chain.links, chain.joints, k)
    assert stored == {c: n for c, n in expected.items() if n}
    _, out, _ = _cli(capsys, ["atlas", "--db", db, "--where", "P=2", "--export", "chains", "--format", "jsonl"])
    rows = [json.loads(line) for line in out.splitlines()]
    assert len(rows) == stored["4/0 P2"] + stored["42/0 P2"]
    rng = np.random.default_rng(7)
    for row in rows:
        chain = Chain.from_dict(row)
        assert chain.kinds.count("prismatic") == 2
        assert row["dof"] == generic_mobility(chain.links, chain.joints, chain.kinds, rng)
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
