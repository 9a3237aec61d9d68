"""The [arm] problem (balance.problems.arm) checked by hand: Example 1 read from URDF with a payload range on
its flange (the amplitudes grow by the payload's moment arms), the device sizes and the options of the table
handed over, the payload on the Moon, the work estimate of a URDF arm's terms and its refusal."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

import balance.problems.arm as problems_arm
from balance.budget import TooMuchWork
from balance.errors import InvalidInput
from balance.model.arm import Arm, Link, Load
from balance.model.urdf import load_urdf
from balance.problems.arm import ArmProblem, arm_problem

URDF = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "models", "arm_base_drives.urdf"))
G = 9.80665
# Example 1: link lengths 0.6, 0.5, 0.3 m; A1 = 126, A2 = 55, A3 = 15 N·m without payload
LENGTHS, EMPTY = (0.6, 0.5, 0.3), (126.0, 55.0, 15.0)


def test_example1_from_urdf_with_a_payload_range_on_its_flange():
    doc = {"arm": {"urdf": URDF, "drives": "base", "counterweights": {"arm": 0.2}, "check": {"samples": 50, "seed": 3},
                   "payload": {"mass": [0, 2], "link": "link4", "at": [0, 0, 0.3]},
                   "devices": {"eccentricity": 0.05, "r": 0.1, "r0": 0.4}, "transmission": True}}
    p = arm_problem(doc, "x.toml")
    assert (p.samples, p.seed, p.urdf, p.payload, p.transmission) == (50, 3, URDF, (0.0, 2.0), True)
    assert p.counterweight_arms == {0: 0.2, 1: 0.2, 2: 0.2, 3: 0.2}
    assert (p.devices.eccentricity, p.devices.r, p.devices.r0) == (0.05, 0.1, 0.4)
    res = p.solve()
    # tuned for 1 kg at the end of link 4: each amplitude grows by 1·g times the lengths from its joint
    reach = (sum(LENGTHS), sum(LENGTHS[1:]), LENGTHS[2])
    want = [EMPTY[0] + G * LENGTHS[0], EMPTY[1] + G * LENGTHS[1], EMPTY[2] + G * LENGTHS[2]]
    assert [t.amplitude for t in res.terms] == pytest.approx(want, rel=1e-12)
    # the payload's half range (1 kg) alone, its largest moment at full reach
    pl = res.payload
    assert (pl.min_payload, pl.max_payload, pl.tuned_for) == pytest.approx((0.0, 2 * G, G), rel=1e-15)
    assert pl.half_payload_effect_per_joint[1:] == pytest.approx([G * r for r in reach], rel=1e-9)
    assert pl.max_residual == pytest.approx(G * reach[0], rel=1e-9)
    # the sine devices e·T = A with e = 50 mm; the tension devices c = A/(r·(r + r0))
    for dev, a in zip(res.devices, want):
        assert dev.sine.e == 0.05 and dev.sine.T == pytest.approx(a / 0.05, rel=1e-12)
        assert dev.tension.c == pytest.approx(a / (0.1 * 0.5), rel=1e-12) and dev.tension.a == 0.4
        assert dev.tension.zero_at_deg == 0.0  # every term's phase is 0: the spring's zero at 0°
        fit = dev.tension.spring_fit  # the request to fit a tension spring to the term, sized or not
        assert (fit.kind, fit.moment, fit.phi) == ("tension", -dev.amplitude, f"φ{dev.term + 1} + 0°")
    assert res.transmission is not None and len(res.transmission) == 3
    assert res.pinocchio.relative_residual < 1e-9 and res.check.relative_residual < 1e-9


def test_a_payload_weighed_under_another_gravity_is_read_back_in_kilograms():
    moon = 1.62
    arm = Arm((Link("a", "revolute", 0.7, 50.0, 0.35), Link("b", "revolute", 0.5, 30.0, 0.25)),
              (Load(1, 4 * moon, 0.5, payload=True, name="payload"),))
    res = ArmProblem(arm, samples=30, g=moon).solve()
    assert res.payload.g == moon
    assert res.payload.mass_range_kg == pytest.approx((0.0, 4.0), rel=1e-14)
    assert res.to_dict()["payload"]["mass_range_kg"] == pytest.approx([0.0, 4.0], rel=1e-14)
    # tuned for 2 kg: the second link's amplitude 30·0.25 + 2·1.62·0.5
    by_form = {t.form: t.amplitude for t in res.terms}
    assert by_form[(1.0, 1.0)] == pytest.approx(30 * 0.25 + 2 * moon * 0.5, rel=1e-12)
    # the payload's half range (2 kg under the Moon) alone at the tip, 1.2 m and 0.5 m from the joints
    assert res.payload.per_joint == pytest.approx((2 * moon * 1.2, 2 * moon * 0.5), rel=1e-9)
    # the arm at the payload's ends (for the figures): 4 kg and none, weighed under the Moon's gravity
    assert res.full_payload.payload_weight == pytest.approx(4 * moon, rel=1e-14)
    assert res.empty.payload_weight == 0.0
    # the counterweights' masses weigh their weights under the same gravity
    for cw in res.counterweights.weights:
        assert cw.mass == pytest.approx(cw.weight / moon, rel=1e-12)


def test_the_work_of_a_urdf_arms_terms_is_estimated_from_its_largest_count_and_refused_past_the_limit(monkeypatch):
    arm = load_urdf(URDF)
    own = arm.sample(16)
    # every timing one millisecond: per value 1 ms over 8 probe terms × 16 configurations, per text 1 ms / 8
    monkeypatch.setattr(problems_arm, "unit_seconds", lambda unit: (unit(), 1e-3)[1])
    most = (3 ** 4 + 1) // 2  # 41 terms at most for four joints
    seconds = most * (2 * 100 * 1e-3 / (8 * 16) + 2 * 1e-3 / 8)
    with pytest.raises(TooMuchWork) as err:
        problems_arm._ensure_terms_affordable(arm, own, 100, seconds / 2)
    assert err.value.seconds == pytest.approx(seconds, rel=1e-12)
    assert str(err.value).startswith("checking 100 configurations against up to 41 harmonic terms would take about ")
    problems_arm._ensure_terms_affordable(arm, own, 100, seconds * 2)
    problems_arm._ensure_terms_affordable(arm, own, 100, None)


LINK = {"joint": "revolute", "length": 1.0, "weight": 2.0}


@pytest.mark.parametrize("arm, words", [
    ({"urdf": URDF, "links": [LINK]}, "s.toml: [arm] takes its links from 'urdf'; remove [[arm.links]] and [[arm.loads]]."),
    ({"urdf": URDF, "loads": [{"weight": 1.0}]},
     "s.toml: [arm] takes its links from 'urdf'; remove [[arm.links]] and [[arm.loads]]."),
    ({"urdf": URDF, "payload": {"mass": [0, 1], "at": 0.3}},
     "s.toml: [arm.payload] key 'at' must be [x, y, z] (m, in the link's frame) for a URDF arm."),
    ({"urdf": URDF, "drives": [[1, 0], [0, 1]]},
     "s.toml: [arm] key 'drives' must be a non-singular 4×4 matrix for this URDF arm."),
    ({"urdf": URDF, "drives": [[1, 0, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
     "s.toml: [arm] key 'drives' must be a non-singular 4×4 matrix for this URDF arm."),
    ({"urdf": URDF, "payload": {"mass": [0, 1], "link": "base", "at": [0, 0, 0]}},
     "s.toml: [arm.payload] the payload's link 'base' is the base: it does not move."),
    ({"urdf": URDF, "payload": {"mass": [0, 1], "link": "nope", "at": [0, 0, 0]}},
     "s.toml: [arm.payload] the URDF has no link 'nope' to carry the payload (links: base, link1, link2, link3, link4)."),
    ({"links": [LINK], "loads": [{"weight": 1.0, "payload": True}], "payload": {"mass": [0, 1]}},
     "s.toml: give the payload either as [arm.payload] or as [[arm.loads]] with payload = true, not both."),
    ({"links": [LINK], "payload": {"mass": [0, 1], "at": [0, 0, 0]}},
     "s.toml: [arm.payload] key 'at' must be a number (m along the link) for a TOML arm."),
    ({"links": [LINK], "payload": {"mass": [0, 1], "link": "zz"}},
     "s.toml: [arm.payload] key 'link' names no link: 'zz' (links: link1)."),
    ({"links": [LINK], "payload": {"mass": [0, 1], "weight": [0, 1]}},
     "s.toml: [arm.payload] needs either the key 'mass' = [low, high] (kg) or 'weight' (N), not both or neither."),
    ({"links": [LINK], "payload": {}},
     "s.toml: [arm.payload] needs either the key 'mass' = [low, high] (kg) or 'weight' (N), not both or neither."),
    ({"links": [LINK], "payload": {"mass": [2, 1]}}, "s.toml: [arm.payload] range 2 .. 1 kg must have 0 ≤ low ≤ high."),
    ({}, "s.toml: [arm] needs at least one [[arm.links]] table (or the key 'urdf')."),
    ({"links": [LINK], "loads": [{"weight": 1.0, "mass": 1.0}]},
     "s.toml: [[arm.loads]] #1 gives both 'weight' (N) and 'mass' (kg); keep one."),
    ({"links": []}, "s.toml: [arm] needs at least one [[arm.links]] table (or the key 'urdf')."),
    ({"urdf": URDF, "payload": {"mass": [2, 1]}}, "s.toml: [arm.payload] range 2 .. 1 kg must have 0 ≤ low ≤ high."),
    # a counterweight's distance named by its key and file (it read "joint q4: … distance from the axis …")
    ({"links": [LINK], "counterweights": {"arm": -0.2}}, "s.toml: [arm.counterweights] key 'arm' must be > 0, not -0.2."),
    ({"links": [{**LINK, "counterweight_arm": 0}]}, "s.toml: [[arm.links]] #1 key 'counterweight_arm' must be > 0, not 0."),
])
def test_a_table_that_contradicts_itself_is_refused_in_one_sentence(arm, words):
    with pytest.raises(Exception) as err:
        arm_problem({"arm": arm}, "s.toml")
    assert str(err.value) == words


def test_a_urdf_is_found_next_to_its_scene_file_or_from_the_working_directory(monkeypatch):
    import tomllib

    scene = os.path.join(os.path.dirname(URDF), "arm_urdf_example1.toml")
    with open(scene, "rb") as fh:
        doc = tomllib.load(fh)
    assert doc["arm"]["urdf"] == "arm_base_drives.urdf"
    assert arm_problem(doc, scene).urdf == URDF
    monkeypatch.chdir(os.path.dirname(URDF))  # a document with no file: the name is the working directory's
    p = arm_problem(doc)
    assert p.urdf == "arm_base_drives.urdf" and p.arm.n == 4
    # a document named after a file that does not exist (a table built in code): the working directory too
    assert arm_problem(doc, os.path.join("elsewhere", "scene.toml")).urdf == "arm_base_drives.urdf"


def test_a_toml_arms_payload_given_in_newtons_sits_at_the_end_of_its_link_unless_placed():
    two = [dict(LINK, name="upper"), dict(LINK, name="fore", length=0.8)]
    p = arm_problem({"arm": {"links": two, "payload": {"weight": [G, 3 * G]}}}, "s.toml")
    assert p.payload == pytest.approx((1.0, 3.0), rel=1e-15)
    (load,) = p.arm.loads
    assert (load.link, load.weight, load.at, load.payload, load.name) == (1, pytest.approx(3 * G), 0.8, True, "payload")
    placed = arm_problem({"arm": {"links": two, "payload": {"mass": [0, 2], "link": "upper", "at": 0.4}}}, "s.toml")
    (load,) = placed.arm.loads
    assert (load.link, load.weight, load.at) == (0, pytest.approx(2 * G), 0.4)
    light = arm_problem({"arm": {"links": two, "payload": {"mass": [0, 0.5]}}}, "s.toml")
    assert [ld.weight for ld in light.arm.loads] == [pytest.approx(0.5 * G)]
    none = arm_problem({"arm": {"links": two, "payload": {"mass": [0, 0]}}}, "s.toml")
    assert none.arm.loads == () and none.payload == (0.0, 0.0)
    # payload loads of the links' table carry the largest payload, from none
    loads = arm_problem({"arm": {"links": two, "loads": [{"weight": 5.0, "payload": True}]}}, "s.toml")
    assert loads.payload == pytest.approx((0.0, 5.0 / G), rel=1e-15)
    assert arm_problem({"arm": {"links": two}}, "s.toml").payload is None


def test_a_urdf_arm_takes_the_tables_name_gravity_and_accuracy():
    p = arm_problem({"arm": {"urdf": URDF, "name": "robot", "g": 1.62, "accuracy": 1e-4}}, "s.toml")
    assert (p.arm.name, p.arm.g, p.arm.accuracy, p.g) == ("robot", 1.62, 1e-4, 1.62)
    # Example 1's first amplitude weighs the same masses under the Moon's gravity: 126·1.62/g
    assert p.solve().terms[0].amplitude == pytest.approx(126.0 * 1.62 / G, rel=1e-12)
    assert arm_problem({"arm": {"urdf": URDF}}, "s.toml").arm.name == "arm_base_drives.urdf"


def test_a_urdf_payload_without_a_place_sits_at_its_links_origin():
    # 2 kg on link 4's joint (the wrist): it loads the first two terms (0.6 m, 0.5 m), not the third
    p = arm_problem({"arm": {"urdf": URDF, "payload": {"mass": [2, 2], "link": "link4"}, "check": {"samples": 20}}},
                    "s.toml")
    assert p.arm.payload_point == (4, (0.0, 0.0, 0.0))  # joint 4's own origin
    res = p.solve()
    want = [EMPTY[0] + 2 * G * LENGTHS[0], EMPTY[1] + 2 * G * LENGTHS[1], EMPTY[2]]
    assert [t.amplitude for t in res.terms] == pytest.approx(want, rel=1e-12)


def test_a_toml_arm_turns_a_full_turn_and_names_its_loads_unless_told():
    p = arm_problem({"arm": {"links": [LINK, dict(LINK, joint="prismatic", stroke=0.4, gear_ratio=2.0)],
                             "loads": [{"weight": 3.0}, {"weight": 1.0, "name": "tool", "link": "link1"}]}}, "s.toml")
    assert p.arm.links[0].limits == (-math.pi, math.pi)
    assert p.arm.links[1].limits == (-0.2, 0.2)
    assert [(ld.name, ld.link, ld.at) for ld in p.arm.loads] == [("load1", 1, 1.0), ("tool", 0, 1.0)]
    ranged = arm_problem({"arm": {"links": [dict(LINK, joint="prismatic", stroke=0.4, gear_ratio=2.0,
                                                 range=[-0.1, 0.15])]}}, "s.toml")
    assert ranged.arm.links[0].limits == (-0.1, 0.15)
    with pytest.raises(Exception) as err:
        arm_problem({"arm": {"links": [dict(LINK, name="a"), dict(LINK, name="a")]}}, "s.toml")
    assert str(err.value) == "s.toml: [[arm.links]] #2 repeats the name 'a' of [[arm.links]] #1."


def test_the_check_finds_the_largest_residual_inside_the_workspace_where_it_is_on_its_edge():
    # devices for half the link's weight: the residual is 2.5·sin q, over q ∈ [−1, −0.2] largest at q = −1
    # (the search must not leave the range for −π/2, where it would be 2.5)
    from balance.model.potential import HarmonicTerm
    from balance.problems.arm import check_terms

    arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5, q_range=(-1.0, -0.2)),))
    (term,) = arm.harmonic_terms()
    half = HarmonicTerm(term.amplitude / 2, term.phase, term.form)
    chk = check_terms(arm, [half], samples=40, seed=5)
    assert chk.seed == 5 and chk.samples == 40
    # the best of the samples alone, read off the residual −2.5·sin q at each of them
    q = arm.sample(40, 5)
    assert chk.sampled_max_residual == pytest.approx(np.max(np.abs(2.5 * np.sin(q[:, 0]))), rel=1e-12)
    assert chk.sampled_max_residual < chk.max_residual
    assert chk.max_residual == pytest.approx(2.5 * math.sin(1.0), rel=1e-9)
    assert chk.max_gravity_force == pytest.approx(5.0 * math.sin(1.0), rel=1e-9)
    assert chk.relative_residual == pytest.approx(0.5, rel=1e-9)
    assert chk.worst[0] == pytest.approx((-1.0,), abs=1e-9)


def test_a_slide_is_reported_with_its_coordinate_stroke_ratio_and_bounds():
    arm = Arm((Link("upper", "revolute", 0.5, 10.0, 0.25),
               Link("s", "prismatic", 0.5, 20.0, 0.2, stroke=0.4, gear_ratio=2.0)), zero="horizontal")
    res = ArmProblem(arm, samples=20, seed=4).solve()
    assert res.check.seed == 4
    (sl,) = res.slides
    assert (sl.link, sl.coordinate, sl.stroke, sl.gear_ratio) == ("s", "q2", 0.4, 2.0)
    # γ_max = 0.2/2 = 0.1: the slide's force within 20·(1 − cos 0.1), the upper joint's within 20·0.2·(1 − sin γ/γ)
    assert sl.residual_bound_per_joint == pytest.approx((20 * 0.2 * (1 - math.sin(0.1) / 0.1), 20 * (1 - math.cos(0.1))),
                                                        rel=1e-12)


@pytest.mark.parametrize("payload", [(0.0, math.inf), (math.nan, 1.0), (2.0, 1.0), (-1.0, 1.0)])
def test_a_payload_range_that_is_not_one_is_refused(payload):
    arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5),), (Load(0, 1.0, 1.0, payload=True),))
    with pytest.raises(InvalidInput) as err:
        ArmProblem(arm, samples=10, payload=payload).solve()
    assert str(err.value) == (f"the payload range must be finite with 0 ≤ low ≤ high, not {payload[0]:g} .. "
                              f"{payload[1]:g} kg.")


def test_the_work_estimate_times_the_terms_at_the_arms_own_configurations(monkeypatch):
    arm = load_urdf(URDF)
    own = arm.sample(16)
    seen = []
    for name in ("terms_forces", "terms_potential"):
        real = getattr(problems_arm, name)
        monkeypatch.setattr(problems_arm, name, lambda terms, q, real=real, name=name: (
            seen.append((name, len(terms), q is own)), real(terms, q))[1])
    problems_arm._ensure_terms_affordable(arm, own, 100, None)
    # each timed call evaluates the eight probe terms at the sixteen configurations, forces and potential
    assert {("terms_forces", 8, True), ("terms_potential", 8, True)} == set(seen)


def test_the_check_needs_a_sample_and_says_when_there_is_no_gravity_to_measure_by():
    from balance.model.potential import HarmonicTerm
    from balance.problems.arm import check_terms

    arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5),))
    for call in (lambda: check_terms(arm, arm.harmonic_terms(), samples=0),
                 lambda: ArmProblem(arm, samples=0).solve()):
        with pytest.raises(InvalidInput) as err:
            call()
        assert str(err.value) == "the check needs at least one sample, not 0."
    assert ArmProblem(arm, samples=1).solve().check.samples == 1
    # a weightless link under a device: a residual with no gravity force to divide it by
    weightless = Arm((Link("l", "revolute", 1.0, 0.0, 0.5),))
    chk = check_terms(weightless, [HarmonicTerm(1.0, 0.0, (1.0,))], samples=20)
    assert chk.max_gravity_force == 0.0 and chk.max_residual == pytest.approx(1.0, rel=1e-9)
    assert chk.relative_residual == math.inf
    assert check_terms(weightless, [], samples=20).relative_residual == 0.0


def test_the_check_samples_the_configurations_of_its_random_seed():
    # a slide's γ = q/k substitution leaves a true residual: its best sample is read off the configurations of its random seed
    from balance.model.potential import terms_forces

    arm = Arm((Link("u", "revolute", 0.5, 10.0, 0.25),
               Link("s", "prismatic", 0.5, 20.0, 0.2, stroke=0.4, gear_ratio=0.2)), zero="horizontal")
    res = ArmProblem(arm, samples=30, seed=3).solve()
    q = arm.sample(30, 3)
    want = np.max(np.abs(arm.gravity_forces(q) - terms_forces(res.terms, q)))
    assert res.check.sampled_max_residual == pytest.approx(want, rel=1e-12) and want > 1e-3
