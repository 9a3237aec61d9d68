"""Universal type synthesis: chains in every motion space h and open chains, against the brute force.

The brute force (tests/oracles/chains.py) shares no code with the engine: labelled joint sets, the
sub-chain rule W_h(S) = h(|S| − 1) − (h − 1)·Σ max(m_j(S) − 1, 0) checked on every subset, and
isomorphism by networkx.  Each case compares the number of chains per code and every chain.
"""

from __future__ import annotations

import json
from collections import Counter

import pytest

import synth
from tests.oracles.chains import ChainIndex, brute_force_chains
from synth import Chain
from synth.analysis.chains import analyze_chain
from synth.structure.subchains import check_subchains


def _limit(h, dof, links, n1, rigid, fractionated):
    """The engine's default largest joint: the limit theorem where it holds (see plan_codes)."""
    K = (links - dof - 1) // (h - 1)
    if rigid or fractionated and not (dof == 1 and n1 == 0):
        return None
    return K + 1 if n1 == 0 else K + dof + 1


def _compare(h, dof, links, *, v=0, n1=0, rigid=None, fractionated=True):
    rigid = dof == 0 if rigid is None else rigid
    expected = brute_force_chains(links, dof, v_max=v, h=h, n1=(n1, n1), rigid_subchains=rigid,
                                  fractionated=fractionated,
                                  max_multiplicity=_limit(h, dof, links, n1, rigid, fractionated))
    got = list(synth.type_synthesis(dof, links, h=h, v=(0, v), n1=n1, rigid_subchains=rigid,
                                    fractionated=fractionated, workers=1))
    where = f"h={h} W={dof} n={links} v≤{v} n1={n1} rigid={rigid} fractionated={fractionated}"
    assert len(got) == len(expected), f"{where}: engine {len(got)} chains, brute force {len(expected)}"
    index = ChainIndex(expected)
    hits = Counter(index.find(c.joints, c.links) for c in got)
    assert None not in hits, f"{where}: an engine chain is not in the brute-force set"
    assert all(k == 1 for k in hits.values()), f"{where}: isomorphic duplicates"
    for c in got:
        assert c.h == h and c.dof == dof and c.code.n1 == n1, where
        assert check_subchains(c, rigid_subchains=rigid).ok, where
    return got


@pytest.mark.parametrize("h", [2, 4, 5, 6])
def test_the_single_loop_of_each_space(h):
    """The smallest 1-DOF chain of motion space h is one loop of h + 1 links (Theorem I: n = W + h)."""
    got = _compare(h, 1, h + 1)
    assert [str(c.code) for c in got] == [f"{h + 1}/0"]


@pytest.mark.parametrize("h, links, v", [
    (2, 4, 0), (2, 5, 0), (2, 6, 0), (2, 4, 2), (2, 5, 2),
    (4, 5, 0), (4, 5, 2), (4, 8, 0), (5, 6, 2), (6, 7, 2),
])
def test_one_dof_chains_of_other_spaces(h, links, v):
    _compare(h, 1, links, v=v)


@pytest.mark.parametrize("h, dof, links, v", [
    (2, 0, 4, 2), (2, 0, 5, 2), (2, 0, 6, 0), (2, 2, 5, 2), (2, 3, 6, 2),
    (4, 0, 7, 0), (4, 2, 6, 2), (4, 2, 9, 0), (5, 0, 5, 2), (5, 3, 8, 0), (6, 2, 8, 2),
])
def test_trusses_and_multi_dof_chains_of_other_spaces(h, dof, links, v):
    _compare(h, dof, links, v=v)


@pytest.mark.parametrize("h, dof, links", [(2, 2, 5), (2, 3, 6), pytest.param(4, 2, 9, marks=pytest.mark.slow), (3, 3, 8)])
def test_not_fractionated_and_the_limit_theorem(h, dof, links):
    """Without fractionated chains the limit theorem holds: the default limit drops nothing."""
    kept = _compare(h, dof, links, v=2, fractionated=False)
    free = brute_force_chains(links, dof, v_max=2, h=h, fractionated=False)
    assert len(kept) == len(free)


@pytest.mark.parametrize("h, dof, links, n1, v", [
    (3, 1, 2, 2, 0), (3, 2, 3, 2, 0), (3, 3, 4, 3, 0), (3, 2, 5, 1, 0), (3, 2, 5, 2, 2), (3, 3, 6, 2, 2),
    (3, 3, 6, 3, 2), (3, 3, 8, 2, 0), (3, 2, 7, 1, 0), (2, 2, 4, 1, 2), (2, 3, 5, 2, 0), (4, 2, 6, 1, 0),
    (5, 2, 7, 1, 2), (6, 3, 9, 2, 0),
])
def test_open_chains(h, dof, links, n1, v):
    """Serial, tree-shaped and looped arms: single-joint links on links and on multiple joints."""
    _compare(h, dof, links, v=v, n1=n1)


@pytest.mark.parametrize("h, dof, links, n1, v", [
    (3, 3, 6, 2, 2), (2, 3, 5, 2, 0), (4, 2, 6, 1, 0), (2, 2, 5, 1, 2),
    pytest.param(3, 3, 8, 2, 0, marks=pytest.mark.slow), pytest.param(3, 4, 7, 2, 2, marks=pytest.mark.slow),
])
def test_open_chains_without_fractionated_closed_parts(h, dof, links, n1, v):
    """--no-fractionated judges the closed part: a loop with an arm on it is kept."""
    _compare(h, dof, links, v=v, n1=n1, fractionated=False)


def test_serial_and_tree_arms_have_no_loop():
    serial = _compare(3, 3, 4, n1=2)
    assert [(c.loops, str(c.code)) for c in serial] == [(0, "2|2/0")]  # four links in a row
    tree = _compare(3, 3, 4, n1=3, v=2)
    assert sorted(str(c.code) for c in tree) == ["3|01/0", "3|1/1"]  # a link with three, or one joint of four


def test_open_robot_chain_of_the_source():
    """Code 2|5/2 (n1 = 2, n2 = 5, v = 2, W = 4): every chain, by joint composition."""
    got = list(synth.type_synthesis(4, code="2|5/2", workers=1))
    expected = [c for c in brute_force_chains(7, 4, v_max=2, h=3, n1=(2, 2)) if c.v == 2 and c.code_key[0] == (5,)]
    assert len(got) == len(expected) and {str(c.code) for c in got} == {"2|5/2", "2|5/0-1"}
    assert all(analyze_chain(c).dof == 4 and not c.is_fractionated() for c in got)


@pytest.mark.parametrize("h, links", [(5, 6), (6, 7)])
def test_bricard_and_spatial_loops(h, links):
    chains = list(synth.type_synthesis(1, links, h=h, workers=1))
    assert len(chains) == 1 and chains[0].dof == 1 and chains[0].loops == 1
    assert analyze_chain(chains[0]).subchain_defect == "none"
    planar = Chain(links, chains[0].joints)  # the same loop read as planar has W = n − 3
    assert planar.dof == links - 3


def test_h3_is_unchanged():
    """Published counts (1-DOF 4 … 10 links; 6 and 8 links with multiple joints)."""
    assert [synth.count_chains(1, n, workers=1)["count"] for n in (4, 6, 8, 10)] == [1, 2, 16, 230]
    assert [synth.count_chains(1, n, v=(0, 2 * n), workers=1)["count"] for n in (6, 8)] == [4, 60]


#: OEIS A227117, minimally rigid (Laman) graphs on 3 … 10 vertices (docs/theory.md, [A227117])
LAMAN = {3: 1, 4: 1, 5: 3, 6: 13, 7: 70, 8: 608, 9: 7222, 10: 110132}


@pytest.mark.parametrize("links", [3, 4, 5, 6, 7, 8, 9, pytest.param(10, marks=pytest.mark.slow)])
def test_wedge_systems_are_laman_graphs(links):
    """h = 2, 1-DOF, simple joints: every k links hold at most 2k − 3 joints and all n hold 2n − 3,
    the (2,3)-tight graphs, which are Laman's minimally rigid graphs: the published counts."""
    assert synth.count_chains(1, links, h=2, workers=1)["count"] == LAMAN[links]


def test_counts_equal_listings_in_other_spaces():
    for h, dof, links, v in [(2, 1, 6, 2), (4, 2, 6, 2), (2, 0, 5, 2)]:
        listed = Counter(str(c.code) for c in synth.type_synthesis(dof, links, h=h, v=(0, v), workers=1))
        counted = synth.count_chains(dof, links, h=h, v=(0, v), workers=1)
        assert counted["by_code"] == dict(listed) and counted["count"] == sum(listed.values())


def test_chains_of_other_spaces_are_distinct_objects():
    loop = Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0")
    bricard = Chain(6, loop.joints, h=5)
    assert loop.certificate != bricard.certificate and bricard.certificate.startswith("h5")
    assert Chain.from_dict(json.loads(bricard.to_json())) == bricard


@pytest.mark.parametrize("argv, sentence", [
    (["chains", "--dof", "1", "--links", "6", "--h", "1"], "the motion space h of a loop is 2 … 6"),
    (["chains", "--dof", "1", "--links", "6", "--h", "7"], "the motion space h of a loop is 2 … 6"),
    (["chains", "--dof", "1", "--links", "6", "--n1", "-1"], "n1 must not be below 0"),
    (["chains", "--dof", "1", "--links", "7", "--h", "4"], "no whole number of loops fits"),
    (["chains", "--code", "2|5/2", "--dof", "3"], "code 2|5/2 gives W = 4"),
    (["chains", "--code", "2|5/2", "--n1", "1"], "code 2|5/2 has n1 = 2"),
    (["analyze", "0-1 1-2 2-0", "--h", "9"], "the motion space h of a loop is 2 … 6"),
])
def test_bad_input_one_sentence(argv, sentence, capsys):
    from mechsynth.cli import main

    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsynth: " + sentence) and err.count("\n") == 1 and "Traceback" not in err


def test_valid_query_without_chains_exits_1(capsys):
    from mechsynth.cli import main

    assert main(["chains", "--dof", "1", "--links", "6", "--n1", "2"]) == 1  # W = 1 arms: a rigid closed part
    assert "no chains" in capsys.readouterr().err


def test_cli_lists_open_chains_and_other_spaces(capsys):
    from mechsynth.cli import main

    assert main(["chains", "--code", "2|5/2", "--count", "--workers", "1"]) == 0
    assert json.loads(capsys.readouterr().out) == {"count": 7, "by_code": {"2|5/0-1": 2, "2|5/2": 5}}
    assert main(["chains", "--dof", "1", "--links", "6", "--h", "5", "--format", "jsonl", "--workers", "1"]) == 0
    row = json.loads(capsys.readouterr().out)
    assert (row["h"], row["dof"], row["code"]) == (5, 1, "6/0")
    assert main(["analyze", "0-1 1-2 2-3 3-4 4-5 5-0", "--h", "5", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert (out["h"], out["dof"], out["subchain_defect"]) == (5, 1, "none")


def test_grid_cells_in_other_spaces(tmp_path):
    from synth.atlas import export, run_grid, summary
    from synth.atlas.grid import parse_grid

    grid = parse_grid('dof = 1\nlinks = "4..8"\nh = [3, 4]\n[[block]]\n[[block]]\ndof = 4\nlinks = 7\nn1 = 2\nv = 2')
    assert [c.key for c in grid.cells] == [
        "W=1 n=4 v=0..0 rigid=0 frac=1 planar=0", "W=1 n=6 v=0..0 rigid=0 frac=1 planar=0",
        "W=1 n=8 v=0..0 rigid=0 frac=1 planar=0", "W=1 n=5 v=0..0 rigid=0 frac=1 planar=0 h=4",
        "W=1 n=8 v=0..0 rigid=0 frac=1 planar=0 h=4", "W=4 n=7 v=2..2 rigid=0 frac=1 planar=0 n1=2..2"]
    db = tmp_path / "u.sqlite"
    run_grid(grid, db, workers=1)
    info = summary(db)
    assert info["chains"] == 1 + 2 + 16 + 1 + 3 + 7
    assert {(c["dof"], c["h"], c["links"]): c["chains"] for c in info["cells"]}[(1, 4, 8)] == 3
    rows = list(export(db, where=["h=4"]))
    assert len(rows) == 4 and all(r["h"] == 4 for r in rows)
