"""Directed repair: every proposed chain checked by the exhaustive sub-chain oracle."""

from __future__ import annotations

import json

import pytest

from tests.oracles.subchains import connected, exhaustive_subchains
from synth.structure.chain import Chain
from synth.structure.code import Code
from synth.analysis.repair import chain_repairs, code_repairs


def _w(links: int, joints) -> int:
    return 3 * (links - 1) - 2 * sum(len(j) - 1 for j in joints)


def _check(text: str, dof: int) -> None:
    joints = [tuple(int(x) for x in t.split("-")) for t in text.split()]
    links = 1 + max(max(j) for j in joints)
    assert connected(links, joints) and _w(links, joints) == dof
    assert exhaustive_subchains(links, joints).ok(rigid_subchains=dof == 0)


@pytest.mark.parametrize("text", ["0-1 1-2 2-0 0-3 3-4 4-5 5-1", "0-1 1-2 2-0 0-3 3-4 4-5 5-0"])
def test_rigid_triangle_chains_get_verified_repairs(text):
    chain = Chain.parse(text)
    assert not exhaustive_subchains(chain.links, chain.joints).ok(False)  # the triangle is rigid
    repairs = chain_repairs(chain)
    assert repairs and all(len(r.edits) == 1 for r in repairs)  # one move mends it
    for r in repairs:
        _check(r.chain, 1)
        assert r.code == str(Chain.parse(r.chain).code)


@pytest.mark.parametrize("text", ["0-1 1-2 2-0 0-3 3-4 4-5 5-1", "0-1 1-2 2-0 0-3 3-4 4-5 5-0",
                                  "0=1 1-2 2-0 0-3 3-4 4-5 5-1"])
def test_repairs_are_distinct_chains_and_keep_joint_kinds(text):
    """No two proposed chains are the same chain (certificates compared directly, kinds included),
    and a prismatic pair stays prismatic: the slider-crank's triangle 0=1-2 mended keeps its slider."""
    from synth import analyze_chain

    chain = Chain.parse(text)
    repairs = chain_repairs(chain)
    proposed = [Chain.parse(r.chain) for r in repairs]
    assert len({c.certificate for c in proposed}) == len(proposed) > 0
    for c in proposed:
        assert sorted(c.kinds or ["revolute"] * len(c.joints)) == sorted(chain.kinds or ["revolute"] * len(chain.joints))
        report = analyze_chain(c)
        assert report.dof == 1 and report.subchain_defect == "none"


def test_over_constrained_code_gets_verified_repairs():
    """6301/0 has W = 1: with W = 2 required, D = −1.  One binary link fewer mends the counts."""
    repairs = code_repairs(Code.parse("6301/0"), 2)
    assert repairs and all(len(r.edits) == 1 for r in repairs)
    for r in repairs:
        assert Code.parse(r.code).dof() == 2
        assert str(Chain.parse(r.chain).code) == r.code
        _check(r.chain, 2)


def test_valid_structures_need_no_repair():
    assert chain_repairs(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")) == []
    assert code_repairs(Code.parse("6301/0"), 1) == []


def test_cli_json_repairs(capsys):
    from mechsynth.cli import main

    assert main(["analyze", "0-1 1-2 2-0 0-3 3-4 4-5 5-1", "--repairs", "1", "--format", "json"]) == 0
    (r,) = json.loads(capsys.readouterr().out)["repairs"]
    assert set(r) >= {"edits", "code", "chain"}
    assert main(["analyze", r["chain"], "--format", "json"]) == 0  # analyze reads the proposed chain back
    assert json.loads(capsys.readouterr().out)["subchain_defect"] == "none"


@pytest.mark.parametrize("argv,message", [
    (["analyze", "2=4,3=2", "--repairs"], "--repairs works on a code or a chain"),
    (["analyze", "6301/0", "--repairs", "0"], "--repairs"),
])
def test_cli_refusals(capsys, argv, message):
    from mechsynth.cli import main

    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsynth: ") and message in err and err.count("\n") == 1


def test_draw_repairs(capsys, tmp_path):
    from mechsynth.cli import main

    out = tmp_path / "repairs.svg"
    assert main(["draw", "--chain", "0-1 1-2 2-0 0-3 3-4 4-5 5-1", "--repairs", "--out", str(out)]) == 0
    assert out.exists() and "3 drawings" in capsys.readouterr().err  # the chain and its two repairs
    assert main(["draw", "--code", "42/0", "--repairs", "--out", str(out)]) == 2
