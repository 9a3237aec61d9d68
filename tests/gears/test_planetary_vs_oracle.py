"""Planetary trains by lever analogue: W, D and the sub-chain verdict against independent counts."""

from __future__ import annotations

import pytest

from tests.oracles.subchains import exhaustive_subchains
from synth.errors import InvalidOption
from synth.gears.planetary import CARRIER, RING, assur_groups, lever_analogue, planetary_table


def _w(links: int, joints) -> int:
    return 3 * (links - 1) - 2 * sum(len(j) - 1 for j in joints)


@pytest.mark.parametrize("sun,offset", [("floating", 4), ("fixed", 2)])
def test_table_against_hand_counts_and_every_subset(sun, offset):
    """n = 3·k0 + 3 links, p = 5·k0 + 1 (+1 for a fixed sun): W = 4 − k0 floating, 2 − k0 fixed;
    the sub-chain verdict of every row equals the verdict over every subset (k0 ≤ 4)."""
    rows = planetary_table((1, 6), sun)
    for r in rows:
        k0 = r.satellites
        assert r.links == 3 * k0 + 3 and r.dof == offset - k0 == _w(r.links, r.joints)
        assert r.defect == r.dof - 1
        if k0 <= 4:
            assert r.subchains == exhaustive_subchains(r.links, r.joints).kind(False)
    determinate = [r.satellites for r in rows if r.determinate]
    if sun == "floating":
        assert determinate == [3] and rows[2].code == "64200/0" and rows[2].loops == 5
    else:  # a fixed sun is never statically determinate with two or more satellites
        assert all(r.defect != 0 for r in rows if r.satellites >= 2) and determinate == [1]


def test_three_satellites_assur_groups():
    """Ring fixed and carrier driving: three dyads (satellite + ring mesh) and one triad (the sun
    with its three mesh links: a 4-link group with 3 outer joints), each of zero mobility."""
    chain = lever_analogue(3)
    groups = assur_groups(chain, RING, CARRIER)
    assert [g.name for g in groups] == ["dyad", "dyad", "dyad", "triad"]
    placed = {RING, CARRIER}
    for g in groups:
        s = set(g.links)
        inner = [j for j in chain.joints if set(j) & s and set(j) <= s | placed]
        assert 3 * len(s) - 2 * len(inner) == 0
        placed |= s
    assert placed == set(range(chain.links))
    (triad,) = [g for g in groups if g.name == "triad"]
    assert 2 in triad.links and len(triad.outer_joints) == 3  # the sun


@pytest.mark.parametrize("call,message", [
    (lambda: lever_analogue(0), "≥ 1"), (lambda: lever_analogue(2, "orbiting"), "floating or fixed"),
    (lambda: planetary_table((0, 3)), "at least one satellite"),
])
def test_refusals(call, message):
    with pytest.raises(InvalidOption, match=message):
        call()


@pytest.mark.parametrize("argv,message", [
    (["--satellites", "-2"], "--satellites"), (["--satellites", "0..3"], "at least one satellite"),
    (["--satellites", "2.."], "upper end"), (["--satellites", "3", "--sun", "x"], "--sun"),
])
def test_cli_refusals(capsys, argv, message):
    from mechsynth.cli import main

    code = main(["planetary", *argv])
    _, err = capsys.readouterr()
    assert code == 2 and err.startswith("mechsynth: ") and message in err and err.count("\n") == 1
