"""Classical names checked against their definitions, written here from the textbooks' words and
evaluated on the engine's chains and mechanisms with their links renumbered at random."""

from __future__ import annotations

import random

import pytest

import synth
from synth.analysis.classical import TABLE, chain_names, inversion_names
from synth.structure.chain import Chain


def _renumbered(chain: Chain, rng: random.Random) -> tuple[Chain, list[int]]:
    perm = list(range(chain.links))
    rng.shuffle(perm)
    return chain.relabel(perm), perm


def _kinds(chain: Chain) -> dict[tuple, str]:
    return dict(zip(chain.joints, chain.kinds or ("revolute",) * len(chain.joints)))


def _ternary(chain: Chain) -> list[int]:
    return [x for x, d in enumerate(chain.degrees) if d == 3]


def _jointed(chain: Chain, a: int, b: int) -> bool:
    return any(a in j and b in j for j in chain.joints)


# ----------------------------------------------------------- the definitions
def six_bar_name(chain: Chain) -> str:
    """Watt: the two ternary links jointed directly; Stephenson: not."""
    t1, t2 = _ternary(chain)
    return "Watt chain" if _jointed(chain, t1, t2) else "Stephenson chain"


def six_bar_inversion(chain: Chain, frame: int) -> str:
    """Watt I: a binary link fixed; Watt II: a ternary one.  Stephenson I: a binary link jointed
    to both ternary links; II: a binary link jointed to one; III: a ternary link."""
    t1, t2 = _ternary(chain)
    if six_bar_name(chain) == "Watt chain":
        return "Watt II" if frame in (t1, t2) else "Watt I"
    if frame in (t1, t2):
        return "Stephenson III"
    both = _jointed(chain, frame, t1) and _jointed(chain, frame, t2)
    return "Stephenson I" if both else "Stephenson II"


def four_link_loop_name(chain: Chain) -> str | None:
    """One loop of four links: four-bar (all pins), slider-crank (one prismatic pair), double
    slider (two prismatic pairs on a common link); other assignments have no name here."""
    kinds = _kinds(chain)
    prismatic = [j for j, k in kinds.items() if k == "prismatic"]
    if not prismatic:
        return "four-bar chain"
    if len(prismatic) == 1:
        return "slider-crank chain"
    if len(prismatic) == 2 and set(prismatic[0]) & set(prismatic[1]):
        return "double-slider chain"
    return None


def four_link_loop_inversion(chain: Chain, frame: int) -> str:
    kinds = _kinds(chain)
    on_frame = sorted(k for j, k in kinds.items() if frame in j)
    name = four_link_loop_name(chain)
    if name == "four-bar chain":
        return "four-bar linkage"
    if name == "slider-crank chain":  # fixing a link of the prismatic pair: the 1st (or 4th) inversion
        return "1st" if "prismatic" in on_frame else "2nd"
    return {("prismatic", "prismatic"): "elliptical trammel", ("prismatic", "revolute"): "Scotch yoke",
            ("revolute", "revolute"): "Oldham coupling"}[tuple(on_frame)]


def dyad_type(chain: Chain, frame: int) -> str:
    """A triangle on its base: the dyad's outer, middle, outer pairs (R or P), the mirror image
    written once (RRP for PRR)."""
    kinds = _kinds(chain)
    outer = sorted("P" if kinds[j] == "prismatic" else "R" for j in chain.joints if frame in j)
    middle = next("P" if kinds[j] == "prismatic" else "R" for j in chain.joints if frame not in j)
    text = outer[0] + middle + outer[1]  # outer pairs sorted: PRR is written RRP below, PPR as RPP
    return "dyad " + {"PRR": "RRP", "PPR": "RPP"}.get(text, text)


def is_triad_on_base(chain: Chain) -> bool:
    """Two ternary links, not jointed, joined by three binary links each jointed to both."""
    if chain.links != 5 or sorted(chain.degrees) != [2, 2, 2, 3, 3]:
        return False
    t1, t2 = _ternary(chain)
    return not _jointed(chain, t1, t2) and all(_jointed(chain, b, t1) and _jointed(chain, b, t2)
                                                for b in range(5) if b not in (t1, t2))


# ------------------------------------------------------------------- tests
def test_watt_and_stephenson_chains_and_their_five_inversions():
    rng = random.Random(6)
    seen = set()
    for mechanism in synth.mechanisms(1, 6, workers=1):
        for _ in range(6):
            chain, perm = _renumbered(mechanism.chain, rng)
            frame = perm[mechanism.frame]
            assert chain_names(chain) == [six_bar_name(chain)]
            assert inversion_names(chain, frame) == [six_bar_inversion(chain, frame)]
            seen.add(six_bar_inversion(chain, frame))
    assert seen == {"Watt I", "Watt II", "Stephenson I", "Stephenson II", "Stephenson III"}


def test_four_link_loops_with_prismatic_pairs():
    rng = random.Random(4)
    seen = set()
    for mechanism in synth.mechanisms(1, 4, prismatic="0..2", workers=1):
        for _ in range(6):
            chain, perm = _renumbered(mechanism.chain, rng)
            frame = perm[mechanism.frame]
            name = four_link_loop_name(chain)
            assert chain_names(chain) == ([name] if name else [])
            found = inversion_names(chain, frame)
            if name is None:
                assert found == []
                continue
            want = four_link_loop_inversion(chain, frame)
            assert len(found) == 1 and (found[0] == want or found[0].startswith(f"slider-crank, {want} inversion"))
            seen.add(want)
    assert seen == {"four-bar linkage", "1st", "2nd", "elliptical trammel", "Scotch yoke", "Oldham coupling"}


def test_assur_dyads_and_triads_on_their_base():
    rng = random.Random(3)
    dyads = set()
    for mechanism in synth.mechanisms(0, 3, prismatic="0..2", workers=1):
        chain, perm = _renumbered(mechanism.chain, rng)
        frame = perm[mechanism.frame]
        assert chain_names(chain) == ["Assur group of class II (a dyad) with its base"]
        assert inversion_names(chain, frame) == [dyad_type(chain, frame)]
        dyads.add(dyad_type(chain, frame))
    assert dyads == {"dyad RRR", "dyad RRP", "dyad RPR", "dyad PRP", "dyad RPP"}
    triads = 0
    for mechanism in synth.mechanisms(0, 5, workers=1):
        chain, perm = _renumbered(mechanism.chain, rng)
        frame = perm[mechanism.frame]
        named = chain_names(chain)
        assert bool(named) == is_triad_on_base(chain)
        if named:
            triads += 1
            ternary = chain.degrees[frame] == 3
            assert inversion_names(chain, frame) == (["triad (Assur group of class III)"] if ternary else
                                                     ["Assur group of class IV, order 2 (a four-link contour)"])
    assert triads == 2  # the triad on its base, with a ternary or a binary link fixed


def test_the_table_names_every_inversion_of_its_chains_once():
    certificates = set()
    for entry in TABLE:
        chain = Chain.parse(entry.chain)
        assert chain.certificate not in certificates
        certificates.add(chain.certificate)
        for orbit in chain.link_orbits:
            assert len(inversion_names(chain, orbit[0])) == 1, (entry.name, orbit)


@pytest.mark.parametrize("links", [8])
def test_larger_chains_have_no_six_bar_name(links):
    assert not any(chain_names(c) for c in synth.type_synthesis(1, links, workers=1))
