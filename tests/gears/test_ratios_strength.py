"""Speed ratios of gear trains by hand: every mechanism of the simple planetary train from its two Willis
equations, a stepped planet, the mesh kinds left open as signs, the text of a formula, each refusal."""

from __future__ import annotations

from fractions import Fraction

import pytest

from synth.errors import InvalidOption
from synth.gears import GearTrain
from synth.gears.ratios import RatioFormula, mechanisms, speed_ratio, wheel_names, willis_rows

SIMPLE = GearTrain.parse("0-1-2 2-3 0~3i 1~3")  # ring 0, sun 1, carrier 2, planet 3


def test_every_mechanism_of_the_simple_planetary_train():
    """Willis, ring-planet (internal) z0(ω0 − ω2) = z3(ω3 − ω2), sun-planet z1(ω1 − ω2) = −z3(ω3 − ω2).
    Ring fixed: ω1/ω2 = 1 + z0/z1; sun fixed: ω0/ω2 = 1 + z1/z0; carrier fixed: z0·ω0 = z3·ω3 and
    z1·ω1 = −z3·ω3.  The planet turns on no axis of the ring or the sun: only the carrier holds it, so
    frames 0 and 1 have two shafts each, frame 2 three, frame 3 one (no pair)."""
    found = {(m.frame, m.input_link, m.output_link): m.ratio.text for m in mechanisms(SIMPLE, input_output=True)}
    assert found == {
        (0, 1, 2): "(z0 + z1)/z1", (0, 2, 1): "z1/(z0 + z1)",
        (1, 0, 2): "(z0 + z1)/z0", (1, 2, 0): "z0/(z0 + z1)",
        (2, 0, 1): "-z1/z0", (2, 1, 0): "-z0/z1", (2, 0, 3): "z3/z0", (2, 3, 0): "z0/z3",
        (2, 1, 3): "-z3/z1", (2, 3, 1): "-z1/z3",
    }
    rows = [m.to_dict() for m in mechanisms(SIMPLE, input_output=True)]
    assert [(r["frame"], r["input_link"], r["output_link"], r["ratio"]) for r in rows][:2] == [
        (0, 1, 2, "(z0 + z1)/z1"), (0, 2, 1, "z1/(z0 + z1)")]


def test_frames_are_taken_up_to_the_trains_symmetry():
    """Two planets 3 and 4 on one carrier are alike: four frames, not five; without input and output each
    mechanism names only its frame."""
    two = GearTrain.parse("0-1 1-3 1-4 0~3i 0~4i 2~3@1 2~4@1")
    assert [(m.frame, m.input_link, m.output_link, m.ratio) for m in mechanisms(two)] == [
        (0, None, None, None), (1, None, None, None), (2, None, None, None), (3, None, None, None)]
    assert set(mechanisms(two)[0].to_dict()) >= {"frame", "train"} and "ratio" not in mechanisms(two)[0].to_dict()


def test_a_stepped_planet_by_hand():
    """A compound planet 3 (wheel z3_0 on the ring, z3_1 on the sun): ring fixed, ω3 − ω2 = −(z0/z3_0)·ω2 and
    z1(ω1 − ω2) = −z3_1(ω3 − ω2), so i = ω1/ω2 = 1 + z0·z3_1/(z1·z3_0)."""
    assert wheel_names(SIMPLE, compound=[3]) == [("z0", "z3_0"), ("z1", "z3_1")]
    formula = speed_ratio(SIMPLE, 0, 1, 2, compound=[3])
    assert formula.text == "(z0·z3_1 + z1·z3_0)/(z1·z3_0)" and formula.wheels == ("z0", "z1", "z3_0", "z3_1")
    teeth = {"z0": 80, "z1": 20, "z3_0": 30, "z3_1": 18}
    assert formula.evaluate(teeth) == 1 + Fraction(80 * 18, 20 * 30)


def test_open_mesh_kinds_are_signs():
    """With the kinds open, s0·z0(…) terms: carrier fixed, z0·ω0 + s0·z3·ω3 = 0 and z1·ω1 + s1·z3·ω3 = 0 give
    ω1/ω0 = s1·z0/(s0·z1); ring fixed, ω1/ω2 = 1 − s1·z0/(s0·z1).  The signs of the train (−1 internal,
    +1 external) give back the fixed-kind formulas."""
    carrier = speed_ratio(SIMPLE, 2, 1, 0, signs=True)
    ring = speed_ratio(SIMPLE, 0, 1, 2, signs=True)
    assert carrier.text == "(s1·z0)/(s0·z1)" and ring.text == "(s0·z1 - s1·z0)/(s0·z1)"
    assert carrier.wheels == ("z0", "z1", "z3", "s0", "s1")
    teeth = {"z0": 72, "z1": 24, "z3": 24, "s0": -1, "s1": 1}
    assert carrier.evaluate(teeth) == Fraction(-72, 24) and ring.evaluate(teeth) == Fraction(96, 24)
    rows = willis_rows(SIMPLE, signs=True)
    assert rows[1] == {1: {(("z1", 1),): 1}, 3: {(("s1", 1), ("z3", 1)): 1},
                       2: {(("z1", 1),): -1, (("s1", 1), ("z3", 1)): -1}}


def test_the_text_of_a_formula():
    """Terms by falling degree, then by name; coefficients with a dot, powers with a caret, the sign in front;
    a denominator of 1 is not written, a one-wheel numerator or denominator is not bracketed."""
    formula = RatioFormula(((((("z1", 2),), 2)), ((("z2", 1),), -3), ((), 5)), (((), 1),), ("z1", "z2"))
    assert formula.text == "2·z1^2 - 3·z2 + 5"
    assert RatioFormula((((("z2", 1),), -1),), (((("z1", 1),), 2),), ("z1", "z2")).text == "-z2/(2·z1)"
    assert RatioFormula((((("z2", 1),), 1),), (((("z1", 1),), 1),), ("z1", "z2")).text == "z2/z1"
    assert RatioFormula(((((), 3)),), (((("z1", 1), ("z2", 1)), 1),), ("z1", "z2")).text == "3/(z1·z2)"


def test_a_common_factor_and_the_sign_are_divided_out():
    """Carrier fixed, sun in, ring out: −z0/z1 (not −2·z0/(2·z1), nor z0/(−z1)); the Cramer determinants
    carry z3 in both, which goes."""
    formula = speed_ratio(SIMPLE, 2, 1, 0)
    assert formula.numerator == (((("z0", 1),), -1),) and formula.denominator == (((("z1", 1),), 1),)


def test_refusals_say_what_is_wrong():
    fractionated = GearTrain.parse("0-1 0-2 0-3 0-4 0-5 1~2@0 3~4@0 4~5@0 3~5@0")  # a pair and a locked triangle
    locked = GearTrain.parse("0-1 0-2 0-3 1~2@0 2~3@0 1~3@0")
    cases = [
        (lambda: speed_ratio(SIMPLE, 0, 0, 2), "the frame, the input and the output must be three different links of the train"),
        (lambda: speed_ratio(SIMPLE, 0, 1, 4), "the frame, the input and the output must be three different links of the train"),
        (lambda: speed_ratio(SIMPLE, -1, 1, 2), "the frame, the input and the output must be three different links of the train"),
        (lambda: speed_ratio(fractionated, 0, 1, 3), "output link 3 stands still whatever the tooth numbers"),
        (lambda: speed_ratio(fractionated, 0, 3, 1),
         "with link 0 fixed, driving link 3 leaves the train free to move (more than one degree of freedom)"),
        (lambda: speed_ratio(locked, 0, 1, 2), "with link 0 fixed the train cannot turn (its Willis equations lock it)"),
        (lambda: mechanisms(GearTrain.parse("0-1 1-3 1-4 0~3i 0~4i 2~3@1 2~4@1"), input_output=True),
         "input and output fix the speed ratio of a 1-DOF train; this one has F = 2"),
        (lambda: speed_ratio(SIMPLE, 0, 1, 2).evaluate({"z0": 72, "z3": 24}), "no tooth number given for wheel z1"),
        (lambda: speed_ratio(SIMPLE, 0, 1, 2).evaluate({"z0": 72, "z1": 0, "z3": 24}),
         "the output does not turn with these tooth numbers (ratio infinite)"),
    ]
    assert fractionated.dof == 1 and locked.dof == 0
    for call, sentence in cases:
        with pytest.raises(InvalidOption) as refused:
            call()
        assert str(refused.value) == sentence
    assert speed_ratio(fractionated, 0, 1, 2).text == "-z2/z1"  # the pair itself turns
