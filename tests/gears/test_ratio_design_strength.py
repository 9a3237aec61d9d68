"""Tooth-number design by hand: every refusal's sentence, the clearance of equally spaced planets from the
geometry of their tip circles, the planet pairs and the carrier cycles, the fractions read."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

from synth.errors import InvalidOption
from synth.gears import GearTrain
from synth.gears.ratio_design import NoDesign, RatioUnreached, carrier_cycles, design, parse_fraction, planet_clearance, planet_pairs
from synth.gears.ratios import wheel_names

SIMPLE = GearTrain.parse("0-1-2 2-3 0~3i 1~3")  # ring 0, sun 1, carrier 2, planet 3


@pytest.mark.parametrize("call,kind,sentence", [
    (lambda: design(SIMPLE, 0, 1, 2, "0"), InvalidOption, "a speed ratio of 0 would need an output that never turns"),
    (lambda: design(SIMPLE, 0, 1, 2, "4", tolerance="-1%"), InvalidOption,
     "the tolerance is the ratio's relative error allowed, 0 … 100 % (exclusive), not -1%"),
    (lambda: design(SIMPLE, 0, 1, 2, "4", teeth=(5, 12)), InvalidOption,
     "no tooth number fits 5..12 with at least 17 teeth (fewer are undercut)"),
    (lambda: design(SIMPLE, 0, 1, 2, "4", teeth=(5, 16), min_teeth=17), InvalidOption,
     "no tooth number fits 5..16 with at least 17 teeth (fewer are undercut)"),
    # (a planet of 0 teeth was designed for tooth ranges from 0 before this refusal: z0 = z1 = 10, z3 = 0)
    (lambda: design(SIMPLE, 0, 1, 2, "3", teeth=(0, 12), min_teeth=0), InvalidOption,
     "a gear has at least 1 tooth: the tooth range 0..12 starts below 1"),
    (lambda: design(GearTrain.parse("0-1 0-2 0-3 1~2 2~3"), 0, 1, 3, "6", compound=[2], teeth=(17, 2 * 10 ** 9)),
     InvalidOption, "these tooth ranges make the ratio's polynomials too large for exact integers: narrow "
                    "teeth=A..B"),  # z2_1·z3 up to 4·10^18 ≥ 2^61
    (lambda: design(SIMPLE, 0, 1, 2, "4.0000000000000000000001"), InvalidOption,
     "the ratio and tolerance need integers too large for an exact model: give the ratio with fewer digits or "
     "narrow teeth=A..B"),
    # (the error's bound, about 6·10^16, fits; times the denominator's bound 10^4 it does not)
    (lambda: design(SIMPLE, 0, 1, 2, "4.0000000001", teeth=(17, 10 ** 4)), InvalidOption,
     "the ratio and tolerance need integers too large for an exact model: give the ratio with fewer digits or "
     "narrow teeth=A..B"),
    (lambda: design(SIMPLE, 0, 1, 2, "4", planets=0), InvalidOption, "the number of planets must be a whole number ≥ 1, not 0"),
    (lambda: design(SIMPLE, 0, 1, 2, "4", kinds="any"), InvalidOption, "mesh kinds are given or free, not 'any'"),
    (lambda: design(SIMPLE, 0, 1, 2, "1.01", tolerance="0.1%", teeth=(17, 60)), RatioUnreached,
     "no tooth numbers in 17..60 give the ratio 1.01 within 0.1% under the coaxial, assembly and undercut conditions"),
    (lambda: design(GearTrain.parse("0-1 0-2 1~2"), 0, 1, 2, "2", planets=3), NoDesign,
     "equally spaced planets need a planet wheel that meshes a sun and a ring on one carrier, and this train has none"),
    (lambda: design(GearTrain.parse("0-1-2 2-3 2-4 0~3i 1~3 0~4"), 0, 1, 2, "4"), NoDesign,
     "wheel z0 is the ring of mesh 0~3i and an external gear of mesh 0~4: one rim has internal or external teeth; "
     "list link 0 with --compound to give it a wheel per mesh"),
    (lambda: carrier_cycles(GearTrain.parse("0-1 0-2 0-3 0-4 1~2 1~3 1~4 2~3 2~4 3~4")), NoDesign,
     "carrier 0 holds four axes at mutually fixed distances (a complete quadrilateral of meshes): whether they lie "
     "in one plane is not modelled; carry fewer meshes on it"),
    (lambda: parse_fraction("x", "the speed ratio"), InvalidOption,
     "the speed ratio must be a number such as 4.25, 17/4 or 1%, not 'x'"),
    (lambda: parse_fraction("1/0", "the tolerance"), InvalidOption,
     "the tolerance must be a number such as 4.25, 17/4 or 1%, not '1/0'"),
])
def test_refusals_in_full(call, kind, sentence):
    with pytest.raises(kind) as refused:
        call()
    assert type(refused.value) is kind and str(refused.value) == sentence


def test_fractions_as_written():
    assert parse_fraction(" 17/4 ", "r") == Fraction(17, 4) and parse_fraction("0.5%", "t") == Fraction(1, 200)
    assert parse_fraction(4, "r") == 4 and parse_fraction("-2.5", "r") == Fraction(-5, 2)


@pytest.mark.parametrize("planets", [2, 3, 4, 5, 6, 7, 8])
@pytest.mark.parametrize("teeth", [17, 20, 33])
def test_planet_clearance_from_the_tip_circles(planets, teeth):
    """Neighbouring planets stand 2a·sin(π/k) apart and need more than the tip diameter m(z + 2): the least whole
    2a/m with (2a/m)·sin(π/k) > z + 2, found here by counting up in floating point with a margin for k = 2, 3, 4, 6,
    where sin² π/k is rational and the bound can be met exactly (the exact case then fails: strictly more)."""
    tip, s = teeth + 2, math.sin(math.pi / planets)
    least = next(d for d in range(1, 10 * tip) if d * s > tip + 1e-9)
    assert planet_clearance(planets, teeth) == least


def test_planet_clearance_where_the_bound_is_met_exactly():
    """Six planets of 20 teeth: 44·sin 30° = 22 = 20 + 2 exactly: touching tips, so 45; two of 20: 22 → 23."""
    assert planet_clearance(6, 20) == 45 and planet_clearance(2, 20) == 23
    assert planet_clearance(1, 20) == 0  # one planet has no neighbour


def test_planet_pairs_and_carrier_cycles():
    """The simple train: planet 3 meshes the ring (internal, ε = −1) and the sun (ε = +1) about one axis of the
    carrier: one pair, ε1·ε2 = −1.  Two planets: two pairs.  Three gears on a frame meshing in a ring close a
    triangle of centre distances."""
    assert planet_pairs(SIMPLE, wheel_names(SIMPLE)) == [("z0", "z3", "z1", "z3", -1)]
    two = GearTrain.parse("0-1-2 2-3 2-4 0~3i 1~3 0~4i 1~4")
    assert planet_pairs(two, wheel_names(two)) == [("z0", "z3", "z1", "z3", -1), ("z0", "z4", "z1", "z4", -1)]
    stepped = wheel_names(SIMPLE, compound=[3])
    assert planet_pairs(SIMPLE, stepped) == [("z0", "z3_0", "z1", "z3_1", -1)]
    assert planet_pairs(GearTrain.parse("0-1-2 2-3 0~3 1~3"), wheel_names(GearTrain.parse("0-1-2 2-3 0~3 1~3"))) == [
        ("z0", "z3", "z1", "z3", 1)]  # two suns
    assert carrier_cycles(SIMPLE) == []
    assert carrier_cycles(GearTrain.parse("0-1 0-2 0-3 1~2 2~3 1~3")) == [(0, [[0], [2], [1]])]


def test_two_suns_of_one_planet_by_hand():
    """Sun 1 and sun 0 (both external) on planet 3, carrier 2, gear 0 fixed, sun 1 in, carrier out: the coaxial
    condition z0 + z3 = z1 + z3 makes z0 = z1, and then i = 1 − z0/z1 = 0: no design turns the output."""
    train = GearTrain.parse("0-1-2 2-3 0~3 1~3")
    with pytest.raises(NoDesign):
        design(train, 0, 1, 2, "2", teeth=(17, 40))


def test_a_design_to_beat_keeps_only_smaller_errors_or_as_small_with_no_more_teeth():
    every = design(SIMPLE, 0, 1, 2, "4.63", tolerance="3%", teeth=(17, 100), best=12)
    assert len(every) == 12 and len({d.error for d in every}) > 2
    # (the ninth design shares its error with three others of 108, 126 and 162 teeth: the last is not kept)
    for worst in (every[3], every[8]):
        error, total = worst.error, sum(worst.teeth.values())
        wanted = [d for d in every if d.error < error or (d.error == error and sum(d.teeth.values()) <= total)]
        found = design(SIMPLE, 0, 1, 2, "4.63", tolerance="3%", teeth=(17, 100), best=12, beat=(error, total))
        assert [d.teeth for d in found] == [d.teeth for d in wanted] and worst.teeth in [d.teeth for d in found]
