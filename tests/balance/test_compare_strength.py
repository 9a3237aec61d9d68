"""Issue 37 (item 8): numbers of the counterweights and the hardware comparison that a user reads and no
other test asked for — the counterweights' weight against the arm's own, the added kilograms, and the RMS
of the residual (per joint, and the table's "RMS removed" column) — each against a hand computation."""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from balance import CompareProblem, load_toml, load_urdf, solve_arm
from balance.devices.counterweights import counterweights, place_counterweights
from balance.model.arm import Arm, Link, Load
from mechsynth.cli import main

MODELS = Path(__file__).resolve().parents[2] / "models"
G = 9.80665

# a planar arm of two links, stretched horizontally in a workspace of one configuration (q = 0), so every
# torque is a lever-arm sum: link 1 0.5 m, 40 N at 0.2 m; link 2 0.4 m, 20 N at 0.2 m; payload at the tip
TWO_LINKS = ('[arm]\nname = "two links"\nzero = "horizontal"\n'
             '[[arm.links]]\nname = "upper"\nlength = 0.5\nweight = 40.0\ncom = 0.2\n'
             '[[arm.links]]\nname = "fore"\nlength = 0.4\nweight = 20.0\ncom = 0.2\n')


def two_links(payload_n: float = 0.0) -> Arm:
    loads = (Load(1, payload_n, 0.4, payload=True),) if payload_n else ()
    return Arm((Link("upper", "revolute", 0.5, 40.0, 0.2), Link("fore", "revolute", 0.4, 20.0, 0.2)), loads,
               zero="horizontal")


def hand_counterweights(lengths, items, arms):
    """Counterweights (N) of a planar chain of parallel joints, by moments about each joint from the tip:
    ``items`` are (link, weight N, distance along the link), ``arms`` each joint's counterweight distance
    behind it. Joint k's counterweight balances everything beyond it, counterweights beyond included."""
    x = np.concatenate([[0.0], np.cumsum(lengths)])  # joint positions along the stretched arm
    out = {}
    for k in reversed(range(len(lengths))):
        moment = sum(w * (x[i] + at - x[k]) for i, w, at in items if i >= k)
        moment += sum(w * (x[j] - arms[j] - x[k]) for j, w in out.items())  # those of the joints beyond
        out[k] = moment / arms[k]
    return out


# --------------------------------------------------------------------- the counterweights' ratio
def test_the_counterweights_weigh_ratio_times_the_arm():
    """``ratio`` is the added weight over the arm's own weight: the two-link arm weighs 60 N, its
    counterweights 20 N (0.2 m behind q2) and 112 N (0.25 m, half the link, behind q1): 132/60 = 2.2."""
    by_hand = hand_counterweights([0.5, 0.4], [(0, 40.0, 0.2), (1, 20.0, 0.2)], {0: 0.25, 1: 0.2})
    assert by_hand == pytest.approx({0: 112.0, 1: 20.0})
    cw = counterweights(two_links(), samples=20)
    assert [w.weight for w in cw.weights] == pytest.approx([112.0, 20.0], rel=1e-12)
    assert [w.mass for w in cw.weights] == pytest.approx([112.0 / G, 20.0 / G], rel=1e-12)
    assert cw.arm_weight == pytest.approx(60.0, rel=1e-12) and cw.added_weight == pytest.approx(132.0, rel=1e-12)
    assert cw.ratio == pytest.approx(2.2, rel=1e-12) and cw.to_dict()["ratio"] == cw.ratio


def test_the_ratio_of_a_urdf_arm_counts_its_published_mass_and_the_tuned_payload():
    """UR5e: 17.7 kg of links (Universal Robots' table), 20.2 kg with the 2.5 kg payload tuned for."""
    arm = load_urdf(str(MODELS / "arm_ur5e.urdf"))
    for payload, kg in ((0.0, 17.7), (2.5, 20.2)):
        cw = counterweights(arm.with_payload(payload) if payload else arm, samples=50)
        assert cw.arm_weight == pytest.approx(kg * G, rel=1e-12)
        assert cw.ratio == pytest.approx(sum(w.mass for w in cw.weights) / kg, rel=1e-12)


def test_balance_arm_prints_the_counterweights_ratio(tmp_path, capsys):
    """`balance arm` on Example 1 (0.2 m arms): 2242.5 + 462.5 + 75 = 2780 N on an arm of
    120 + 80 + 40 + 30 = 270 N, "10.3× the arm"; the same in its JSON."""
    items = [(1, 120.0, 0.3), (2, 80.0, 0.25), (3, 40.0, 0.15), (3, 30.0, 0.3)]
    by_hand = hand_counterweights([0.4, 0.6, 0.5, 0.3], items, {0: 0.2, 1: 0.2, 2: 0.2, 3: 0.2})
    assert [by_hand[k] for k in (1, 2, 3)] == pytest.approx([2242.5, 462.5, 75.0])
    path = str(MODELS / "arm_base_drives.toml")
    assert main(["balance", "arm", path]) == 0
    out = capsys.readouterr().out
    assert "  added 2780 N (10.3× the arm), residual " in out
    assert main(["balance", "arm", path, "--format", "json"]) == 0
    cw = json.loads(capsys.readouterr().out)["counterweights"]
    assert cw["arm_weight"] == pytest.approx(270.0, rel=1e-12)
    assert cw["ratio"] == pytest.approx(2780.0 / 270.0, rel=1e-12)
    assert solve_arm(load_toml(path)).counterweights.ratio == pytest.approx(2780.0 / 270.0, rel=1e-12)


# --------------------------------------------------------------------- the comparison's added mass
@pytest.fixture(scope="module")
def two_link_comparison():
    """The two-link arm at q = 0 with 1..4 kg at its tip: every strategy tuned for 2.5 kg."""
    return CompareProblem(two_links(4 * G), payload=(1.0, 4.0), workspace=((0.0, 0.0), (0.0, 0.0)),
                          samples=40).solve()


def test_the_comparisons_counterweights_weigh_what_the_moments_say(two_link_comparison):
    """Tuned for 2.5 kg at the tip: the counterweights by moments (q2's 0.2 m behind its joint, q1's
    0.25 m, half their links), and the strategy's added mass (kg, not N) and hardware lines from them."""
    cw = two_link_comparison.strategy("counterweights")
    items = [(0, 40.0, 0.2), (1, 20.0, 0.2), (1, 2.5 * G, 0.4)]
    by_hand = hand_counterweights([0.5, 0.4], items, {0: 0.25, 1: 0.2})
    masses = [by_hand[k] / G for k in (0, 1)]
    assert [w.mass for w in cw.details.weights] == pytest.approx(masses, rel=1e-12)
    assert cw.devices == 2 and cw.added_mass == pytest.approx(sum(masses), rel=1e-12)
    assert cw.hardware == (f"{masses[0]:.4g} kg on upper, 0.25 m from the axis of q1",
                           f"{masses[1]:.4g} kg on fore, 0.2 m from the axis of q2")


def test_the_comparison_measures_what_the_counterweights_leave_once(monkeypatch):
    """compare finds the counterweights' residual over the workspace and the payload range itself: their own
    check of the balanced arm (a second search of 200 starts, whose result nothing read) no longer runs."""
    import balance.devices.counterweights as module

    def no_second_search(*args, **kwargs):
        raise AssertionError("the counterweights' own residual search ran")

    monkeypatch.setattr(module, "box_extremes", no_second_search)
    comparison = CompareProblem(two_links(4 * G), payload=(1.0, 4.0), workspace=((0.0, 0.0), (0.0, 0.0)), samples=40)
    cw = comparison.solve().strategy("counterweights")
    assert cw.available and cw.devices == 2
    assert max(j.max for j in cw.joints) == pytest.approx(1.5 * G * 0.9, rel=1e-9)  # the payload's deviation at q1


def test_placing_the_counterweights_is_counterweights_without_the_check():
    placed, checked = place_counterweights(two_links()), counterweights(two_links(), samples=20)
    assert placed.weights == checked.weights and placed.added_weight == checked.added_weight
    assert (placed.max_residual, placed.potential_spread, placed.worst) == (None, None, None)
    assert checked.max_residual < 1e-12 * 60.0 and checked.worst is not None


# --------------------------------------------------------------------- the RMS of the residual
def rms_over_payload(a: float, b: float, lo: float, hi: float) -> float:
    """The RMS of a + b·p over p uniform in [lo, hi]: the mean of the square, integrated exactly."""
    if hi == lo:
        return abs(a + b * lo)
    return math.sqrt(((a + b * hi) ** 3 - (a + b * lo) ** 3) / (3 * b * (hi - lo)))


def test_rms_per_joint_is_that_of_the_payload_range(two_link_comparison):
    """At q = 0 the two-link arm's torques are 22 + 0.9·g·p and 4 + 0.4·g·p (p the payload, kg, uniform in
    1..4): the baseline's RMS is the exact mean of their squares over p; a strategy tuned for the middle
    leaves 0.9·g·(p − 2.5) and 0.4·g·(p − 2.5), whose RMS is 0.9·g·3/√12 and 0.4·g·3/√12."""
    c = two_link_comparison
    base = [rms_over_payload(22.0, 0.9 * G, 1.0, 4.0), rms_over_payload(4.0, 0.4 * G, 1.0, 4.0)]
    left = [0.9 * G * 3 / math.sqrt(12), 0.4 * G * 3 / math.sqrt(12)]
    none = c.strategy("none")
    assert [j.rms for j in none.joints] == pytest.approx(base, rel=1e-12)
    assert [j.baseline_rms for j in none.joints] == pytest.approx(base, rel=1e-12)
    assert [j.max for j in none.joints] == pytest.approx([22 + 3.6 * G, 4 + 1.6 * G], rel=1e-12)
    for name in ("counterweights", "exact springs"):
        s = c.strategy(name)
        assert s.tuned_for == pytest.approx(2.5)
        assert [j.rms for j in s.joints] == pytest.approx(left, rel=1e-9), name
        assert [j.removed_rms for j in s.joints] == pytest.approx([1 - r / b for r, b in zip(left, base)], rel=1e-9)
        assert [j.to_dict()["rms"] for j in s.joints] == [j.rms for j in s.joints]


def test_rms_over_the_workspace_is_that_of_uniform_configurations():
    """One link turning a full turn (10 N at 0.5 m, no payload): the torque is 5·cos q, whose RMS over a
    uniform angle is 5/√2; 4000 random configurations reach it within 2 %, and a fixed payload adds its
    moment to the amplitude."""
    arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5),), (Load(0, 2 * G, 1.0, payload=True),), zero="horizontal")
    for payload, amplitude in ((0.0, 5.0), (2.0, 5.0 + 2 * G)):
        c = CompareProblem(arm, payload=(payload, payload), samples=4000).solve()
        none = c.strategy("none").joints[0]
        assert none.max == pytest.approx(amplitude, rel=1e-9)
        assert none.rms == pytest.approx(amplitude / math.sqrt(2), rel=0.02)


def test_the_tables_rms_column_is_the_share_of_the_rms_removed(tmp_path, capsys):
    """`balance compare` on the two-link arm at q = 0: "RMS removed" is 1 − √(Σ rms²)/√(Σ baseline rms²)
    over the joints, with the hand values above; "added kg" the counterweights' mass."""
    f = tmp_path / "two.toml"
    f.write_text(TWO_LINKS)
    argv = ["balance", "compare", str(f), "--payload", "1..4", "--range", "q1=0..0", "--range", "q2=0..0",
            "--samples", "40"]
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    head = next(i for i, ln in enumerate(lines) if ln.startswith("strategy"))
    assert lines[head].split()[-2:] == ["RMS", "removed"]
    rows = {}
    for ln in lines[head + 2:head + 7]:
        name = next(n for n in ("none", "counterweights", "springs per joint", "harmonic, pruned", "exact springs")
                    if ln.startswith(n))
        cells = ln[len(name):].split()
        rows[name] = {"added": float(cells[1]), "removed": cells[-2], "rms_removed": cells[-1]}
    base = [rms_over_payload(22.0, 0.9 * G, 1.0, 4.0), rms_over_payload(4.0, 0.4 * G, 1.0, 4.0)]
    left = [0.9 * G * 3 / math.sqrt(12), 0.4 * G * 3 / math.sqrt(12)]
    share = 1 - math.hypot(*left) / math.hypot(*base)
    assert f"{100 * share:.1f}%" == "82.2%"
    assert rows["none"]["rms_removed"] == "0.0%"
    for name in ("counterweights", "exact springs"):
        assert rows[name]["rms_removed"] == f"{100 * share:.1f}%", name
        assert rows[name]["removed"] == f"{100 * (1 - 0.9 * G * 1.5 / (22 + 3.6 * G)):.1f}%", name
    fore = (20 * 0.2 + 2.5 * G * 0.4) / 0.2  # N, 0.2 m behind q2 (half the link)
    upper = (40 * 0.2 + 20 * 0.7 + 2.5 * G * 0.9 + fore * 0.3) / 0.25
    assert rows["counterweights"]["added"] == pytest.approx((fore + upper) / G, rel=1e-3)


def test_counterweights_of_a_urdf_arm_put_each_sub_arm_on_its_axis():
    """UR5e with 2.5 kg (the counterweights alone, without the comparison): q1 stays vertical and q6's
    sub-arm is on its axis already, so q2–q5 get one each; at random configurations the centre of mass of
    everything each of them carries (computed here from the balanced model's placements) lies on its axis,
    and no gravity torque is left. The counterweights of q2 and q3 sit half the next joint's offset from
    their axes (a = 0.425 and 0.3922 m); the wrist's next joints lie on their axes, so 0.1 m."""
    import pinocchio as pin

    cw = counterweights(load_urdf(str(MODELS / "arm_ur5e.urdf")).with_payload(2.5), samples=50)
    assert [w.coordinate for w in cw.weights] == ["q2", "q3", "q4", "q5"]
    assert [w.arm for w in cw.weights] == pytest.approx([0.425 / 2, 0.3922 / 2, 0.1, 0.1], rel=1e-12)
    for w in cw.weights:  # a URDF counterweight's position is its point in the joint's frame
        assert w.position == w.point and w.weight == pytest.approx(w.mass * G, rel=1e-12)
    assert cw.max_residual <= 1e-12 * 100 and cw.potential_spread <= 1e-12 * 100
    model, data = cw.balanced.model, cw.balanced.model.createData()
    for q in np.random.default_rng(4).uniform(-math.pi, math.pi, (10, 6)):
        pin.forwardKinematics(model, data, cw.balanced.config(q))
        pin.computeJointJacobians(model, data, cw.balanced.config(q))
        for j in (2, 3, 4, 5):
            below = [k for k in range(j, model.njoints) if _carried(model, j, k)]
            mass = sum(model.inertias[k].mass for k in below)
            com = sum(model.inertias[k].mass * data.oMi[k].act(model.inertias[k].lever) for k in below) / mass
            axis = np.asarray(pin.getJointJacobian(model, data, j, pin.ReferenceFrame.WORLD))[3:, j - 1]
            assert np.linalg.norm(np.cross(com - data.oMi[j].translation, axis)) <= 1e-12, j
        assert np.max(np.abs(cw.balanced.gravity_forces(q))) <= 1e-12 * 100


def _carried(model, j: int, k: int) -> bool:
    while k > j:
        k = model.parents[k]
    return k == j


def test_counterweights_of_a_toml_arm_in_the_links_words():
    """A hub of no length whose centre of mass lies 0.1 m to its left, then a 0.5 m link: q2's
    counterweight sits on the link's line 0.25 m behind the joint (half the link), q1's on the hub 0.1 m
    from the axis (the default for a link of no length), opposite its centre of mass; the JSON row says so.
    Example 1 (angles from the vertical): every counterweight on its link's line, 0.2 m behind."""
    arm = Arm((Link("hub", "revolute", 0.0, 10.0, 0.0, com_lateral=0.1), Link("l", "revolute", 0.5, 20.0, 0.25)),
              zero="horizontal")
    cw = counterweights(arm, samples=20)
    d = cw.to_dict()
    assert d.keys() == {"available", "weights", "added_weight", "arm_weight", "ratio", "max_residual",
                        "potential_spread", "worst"}
    assert d["weights"] == [
        {"link": "hub", "coordinate": "q1", "weight": pytest.approx(10.0, rel=1e-12),
         "mass": pytest.approx(10.0 / G, rel=1e-12), "arm": 0.1, "position": pytest.approx([0.0, -0.1], abs=1e-15)},
        {"link": "l", "coordinate": "q2", "weight": pytest.approx(20.0, rel=1e-12),
         "mass": pytest.approx(20.0 / G, rel=1e-12), "arm": 0.25, "position": pytest.approx([-0.25, 0.0], abs=1e-15)}]
    assert d["added_weight"] == pytest.approx(30.0) and d["arm_weight"] == pytest.approx(30.0)
    assert d["max_residual"] == cw.max_residual <= 1e-12 * 10 and d["potential_spread"] == cw.potential_spread
    assert d["worst"] == list(cw.worst) and len(d["worst"]) == 2
    assert counterweights(Arm((Link("s", "prismatic", 0.5, 10.0, 0.25, stroke=0.2, gear_ratio=0.1),)),
                          samples=5).to_dict() == {"available": False, "reason": (
        "a prismatic link moves its centre of mass along the stroke; no fixed counterweight can follow it (use "
        "springs or the counter-mass mechanism).")}
    example1 = counterweights(solve_arm(load_toml(str(MODELS / "arm_base_drives.toml"))).arm, {1: 0.2, 2: 0.2, 3: 0.2},
                              samples=20)
    assert [w.position for w in example1.weights] == [pytest.approx((-0.2, 0.0), abs=1e-15)] * 3


def test_a_light_arm_with_a_massless_tip_and_an_offset_centre_of_mass():
    """Angles from the vertical; link a: 4 N (0.41 kg) at 0.25 m along and 0.1 m to the left; link b weighs
    nothing. b gets no counterweight (its sub-arm has no mass: no 0/0, no warning); a's sits 0.25 m from
    the axis (half its link) opposite its centre of mass, √(0.25² + 0.1²)·4/0.25 N."""
    arm = Arm((Link("a", "revolute", 0.5, 4.0, 0.25, com_lateral=0.1), Link("b", "revolute", 0.3, 0.0, 0.15)),
              zero="vertical")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cw = counterweights(arm, samples=20)
    r = math.hypot(0.25, 0.1)
    (w,) = cw.weights
    assert (w.link, w.coordinate, w.arm) == ("a", "q1", 0.25)
    assert w.weight == pytest.approx(4 * r / 0.25, rel=1e-12)
    assert w.position == pytest.approx((-0.25 * 0.25 / r, -0.25 * 0.1 / r), rel=1e-12)
    assert cw.max_residual <= 1e-12 * 4 and cw.arm_weight == pytest.approx(4.0, rel=1e-12)
    refused = counterweights(Arm((Link("s", "prismatic", 0.5, 10.0, 0.25, stroke=0.2, gear_ratio=0.1),)), samples=5)
    assert refused.available is False and refused.weights == () and refused.ratio == math.inf


def test_the_counterweights_of_a_urdf_arm_name_its_links():
    cw = counterweights(load_urdf(str(MODELS / "arm_ur5e.urdf")), samples=20)
    assert [w.link for w in cw.weights] == ["upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link"]


def test_two_turntables_get_no_counterweight_and_gravity_sets_the_masses():
    """Two vertical axes in a row (turntables, the second with its centre of mass off its axis) carry no
    gravity torque in any configuration: only the revolute joint after them gets a counterweight. With g = 10 m/s² the weights (N) are those of the
    moments and the masses weight/10."""
    arm = Arm((Link("t1", "vertical", 0.3, 5.0, 0.15), Link("t2", "vertical", 0.4, 5.0, 0.2, com_lateral=0.05),
               Link("r", "revolute", 0.5, 10.0, 0.25)), zero="horizontal")
    cw = counterweights(arm, samples=10)
    assert [(w.coordinate, w.arm) for w in cw.weights] == [("q3", 0.25)]
    assert cw.weights[0].weight == pytest.approx(10.0, rel=1e-12)
    cw = counterweights(two_links(), samples=10, g=10.0)
    assert [w.weight for w in cw.weights] == pytest.approx([112.0, 20.0], rel=1e-12)
    assert [w.mass for w in cw.weights] == pytest.approx([11.2, 2.0], rel=1e-12)
    assert cw.arm_weight == pytest.approx(60.0, rel=1e-12)


@pytest.mark.parametrize("b", [0.0, -0.1, math.nan, math.inf])
def test_a_counterweight_distance_must_be_positive(b):
    from balance.errors import InvalidArm

    with pytest.raises(InvalidArm) as caught:
        counterweights(two_links(), {1: b}, samples=5)
    assert str(caught.value) == f"joint q2: the counterweight's distance from the axis must be positive, not {b}."


def test_a_urdf_counterweight_sits_level_with_its_sub_arms_centre_of_mass():
    """Along its joint's axis (z of the joint frame in this URDF) a counterweight sits at the height of the
    centre of mass it balances, so the balanced sub-arm's centre of mass is level with it."""
    import pinocchio as pin

    cw = counterweights(load_urdf(str(MODELS / "arm_ur5e.urdf")), samples=20)
    model, data = cw.balanced.model, cw.balanced.model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))
    for w in cw.weights:
        j = int(w.coordinate[1:])
        below = [k for k in range(j, model.njoints) if _carried(model, j, k)]
        mass = sum(model.inertias[k].mass for k in below)
        com = sum(model.inertias[k].mass * data.oMi[k].act(model.inertias[k].lever) for k in below) / mass
        assert data.oMi[j].actInv(com)[2] == pytest.approx(w.point[2], abs=1e-12), w.coordinate
    assert any(abs(w.point[2]) > 0.05 for w in cw.weights)  # (not all level with the joint's origin)


def test_a_compare_workspace_is_in_degrees_for_a_pin_and_in_metres_for_a_slide():
    """models/arm_prismatic.toml: q1 revolute (±90°), q2 a slide of 0.4 m stroke."""
    from balance.problems.compare import compare_problem

    doc = {"compare": {"arm": str(MODELS / "arm_prismatic.toml"), "workspace": {"q1": [-30, 60], "q2": [0.1, 0.3]}}}
    pb = compare_problem(doc, "c.toml")
    assert pb.workspace[0] == pytest.approx((-math.pi / 6, math.pi / 3), rel=1e-15)
    assert pb.workspace[1] == (0.1, 0.3)


def test_a_compare_table_without_a_file_names_compare_in_its_refusals():
    from balance import SchemaError
    from balance.problems.compare import compare_problem

    with pytest.raises(SchemaError) as ei:
        compare_problem({"compare": {"nonsense": 1}})
    assert str(ei.value).startswith("<compare>: [compare] has an unknown key 'nonsense'")


def test_each_strategy_pushes_back_the_tuned_payloads_torque():
    """One link: 40 N at 0.2 m and a payload of 1 … 4 kg at 0.5 m, tuned for 2.5 kg: every device pushes with
    −(8 + 2.5·G·0.5)·sin q (angles from the vertical), the unbalanced arm with nothing."""
    arm = Arm((Link("upper", "revolute", 0.5, 40.0, 0.2),), (Load(0, 4 * G, 0.5, payload=True),))
    c = CompareProblem(arm, payload=(1.0, 4.0), samples=200).solve()
    q = np.random.default_rng(3).uniform(-math.pi, math.pi, (7, 1))
    assert np.allclose(c.gravity(q, 4.0)[:, 0], (8 + 2 * G) * np.sin(q[:, 0]), atol=1e-12)
    for s in c.strategies:
        expected = 0.0 if s.name == "none" else -(8 + 1.25 * G) * np.sin(q[:, 0])
        assert np.allclose(s.forces(q)[:, 0], expected, atol=1e-9), s.name
    assert c.strategy("none").hardware == ("the drives carry the whole gravity torque",)
    # the exact spring: zero free length (a = r0), c·r·d = the term's amplitude (d = r + r0), and over a full
    # turn its longest stretch, crank pointing away from the anchor: L = r + d, so the largest force c·(2r + r0)
    (spring,) = c.strategy("exact springs").details.springs
    device = spring.fitted.device
    assert spring.amplitude == pytest.approx(8 + 1.25 * G, rel=1e-12) and device.a == pytest.approx(device.r0)
    assert device.c * device.r * (device.r + device.r0) == pytest.approx(spring.amplitude, rel=1e-9)
    assert device.max_force == pytest.approx(device.c * (2 * device.r + device.r0), rel=1e-9)


def test_a_compare_table_names_the_arm_file_a_mistake_is_in(tmp_path):
    from balance import SchemaError
    from balance.problems.compare import compare_problem

    arm = tmp_path / "arm.toml"
    arm.write_text('[arm]\nnonsense = 1\n')
    table = tmp_path / "c.toml"  # the arm is found beside it
    table.write_text('[compare]\narm = "arm.toml"\n')
    with pytest.raises(SchemaError) as ei:
        compare_problem(load_toml(str(table)), str(table))
    assert str(ei.value).startswith(f"{arm}: [arm] has an unknown key 'nonsense'")


# --------------------------------------------------------------------- partial ranges: averages and the recheck
#: the two-link arm (angles from the vertical) over part of a turn at each joint
PARTIAL = ((math.radians(-40.0), math.radians(70.0)), (math.radians(10.0), math.radians(100.0)))


def test_springs_per_joint_cancel_the_torque_averaged_over_the_other_joints_range():
    """2 kg at the tip, angles from the horizontal: gravity's forces −∂V/∂q are Q1 = −A·cos q1 − B·cos(q1 + q2),
    Q2 = −B·cos(q1 + q2) with A = 40·0.2 + (20 + 2g)·0.5 and B = 20·0.2 + 2g·0.4 (N·m).  Each joint's spring cancels its torque averaged
    over the other joint's range, here by Gauss–Legendre quadrature of the hand formula, then written
    α·sin q + β·cos q = amp·sin(q + phase) by least squares on a few angles."""
    A, B = 8 + (20 + 2 * G) * 0.5, 4 + 2 * G * 0.4
    torque = [lambda q1, q2: -A * np.cos(q1) - B * np.cos(q1 + q2), lambda q1, q2: -B * np.cos(q1 + q2)]
    c = CompareProblem(two_links(2 * G), payload=(2.0, 2.0), workspace=PARTIAL, samples=40).solve()
    s = c.strategy("springs per joint")
    nodes, weights = np.polynomial.legendre.leggauss(40)
    q = np.linspace(-1.0, 2.0, 7)
    for j, spring in enumerate(s.details.springs):
        lo, hi = PARTIAL[1 - j]
        other = lo + (hi - lo) * (nodes + 1) / 2  # the other joint's angles, weights / 2 summing to 1
        mean = np.array([np.sum(weights / 2 * (torque[j](x, other) if j == 0 else torque[j](other, x))) for x in q])
        (alpha, beta), *_ = np.linalg.lstsq(np.column_stack([np.sin(q), np.cos(q)]), mean, rcond=None)
        assert spring.coordinate == f"q{j + 1}"
        assert spring.amplitude == pytest.approx(math.hypot(alpha, beta), rel=1e-12)
        assert spring.phase_deg == pytest.approx(math.degrees(math.atan2(beta, alpha)), rel=1e-10)
        x = np.zeros((len(q), 2))
        x[:, j] = q
        assert s.forces(x)[:, j] == pytest.approx(-mean, abs=1e-12 * A)


def test_pinocchio_recomputes_each_strategys_residual_and_its_worst_values():
    """1 … 3 kg at the tip over part of a turn: the recheck's own residual (Pinocchio's RNEA on a model rebuilt
    from URDF, counterweights as masses of the model) is the strategy's everywhere, and at each joint's worst
    configuration and payload it is the largest residual reported for that joint."""
    c = CompareProblem(two_links(3 * G), payload=(1.0, 3.0), workspace=PARTIAL, samples=40).solve()
    scale = max(j.max for j in c.strategy("none").joints)
    for s in c.strategies:
        check = s.pinocchio
        assert check.configurations == 100 and check.payloads == (1.0, 3.0), s.name
        assert check.max_difference < 1e-9 * scale, s.name
        assert check.reported == tuple(j.max for j in s.joints), s.name
        assert check.at_worst == pytest.approx(check.reported, rel=1e-9, abs=1e-9 * scale), s.name


def test_a_terms_angle_ranges_over_the_corners_of_the_box_at_most_a_turn():
    """A harmonic term's angle φ + α = Σ aᵢ·qᵢ + α is linear in q: over a box its extremes are at corners,
    here every corner is tried (coefficients of both signs and zero ones, a range from 0); a range wider
    than a turn is cut at a turn (the device's angle is periodic)."""
    from itertools import product

    from balance.model.potential import HarmonicTerm
    from balance.problems.compare import _phi_range

    rng = np.random.default_rng(5)
    for form in ((1.0, 0.0, 0.0), (1.0, -1.0, 0.0), (0.0, 2.0, -1.0), (0.0, 0.0, 1.0), (1.0, 1.0, 1.0)):
        lo = np.array([0.0, *rng.uniform(-1.0, 0.0, 2)])
        hi = lo + rng.uniform(0.0, 1.2, 3)
        t = HarmonicTerm(3.0, 0.4, form)
        angles = [float(np.dot(form, corner)) + 0.4 for corner in product(*zip(lo, hi))]
        assert _phi_range(t, lo, hi) == pytest.approx((min(angles), min(max(angles), min(angles) + 2 * math.pi)),
                                                      abs=1e-15), form
    wide = HarmonicTerm(1.0, 0.0, (2.0, 1.0))
    assert _phi_range(wide, np.array([0.0, 0.0]), np.array([3.0, 1.0])) == (0.0, 2 * math.pi)


def test_a_term_below_the_target_is_left_out_and_its_torque_said():
    """A heavy upper link (40 N at 0.2 m) under a light forearm (1 N at 0.2 m of 0.4 m), full turns, no payload:
    the terms are 8.5·cos q1 (40·0.2 + 1·0.5) and 0.2·cos(q1 + q2).  The target, 5 % of the largest torque
    8.5 + 0.2 = 8.7 N·m, is 0.435 N·m: the pruned decomposition drops the 0.2 N·m term and leaves its torque,
    0.2 N·m on each joint; the exact springs keep one spring for each link's absolute angle."""
    arm = Arm((Link("upper", "revolute", 0.5, 40.0, 0.2), Link("fore", "revolute", 0.4, 1.0, 0.2)))
    c = CompareProblem(arm, samples=200).solve()
    assert [j.max for j in c.strategy("none").joints] == pytest.approx([8.7, 0.2], rel=1e-9)
    pruned = c.strategy("harmonic, pruned")
    d = pruned.details
    assert (d.terms, d.kept, d.target_torque, d.note) == (2, 1, pytest.approx(0.435), None)
    (dropped,) = d.dropped
    assert (dropped.amplitude, dropped.form, dropped.form_text) == (pytest.approx(0.2), (1.0, 1.0), "q1 + q2")
    assert dropped.largest_torque_per_joint == pytest.approx((0.2, 0.2), rel=1e-9)
    assert [(t.form_text, t.amplitude) for t in d.springs] == [("q1", pytest.approx(8.5))]
    assert pruned.devices == 1 and len(pruned.hardware) == 1 and "c·r·d = 8.5 N·m" in pruned.hardware[0]
    assert [j.max for j in pruned.joints] == pytest.approx([0.2, 0.2], rel=1e-9)
    exact = c.strategy("exact springs")
    assert [(t.form_text, t.amplitude) for t in exact.details.springs] == [("q1", pytest.approx(8.5)),
                                                                         ("q1 + q2", pytest.approx(0.2))]
    assert [h.split(":")[0] for h in exact.hardware] == ["absolute angle q1", "absolute angle q1 + q2"]
    assert exact.details.parallelograms == 1


def test_a_strategy_that_does_not_apply_says_false_and_why():
    """models/arm_prismatic.toml (a turning arm with a slide): no counterweight follows the slide and no
    parallelogram spring cancels q·sin θ; both strategies read available: false (not null) with the reason."""
    from balance.problems.compare import compare_problem

    c = compare_problem({"compare": {"arm": str(MODELS / "arm_prismatic.toml"), "samples": 100}}, "c.toml").solve()
    off = {s.name: s for s in c.strategies if not s.available}
    assert sorted(off) == ["counterweights", "exact springs"]
    for s in off.values():
        assert s.available is False and s.to_dict()["available"] is False
    assert off["exact springs"].reason.startswith("a slide enters the potential bilinearly (q·sin θ)")


def test_the_recheck_of_a_urdf_arm_rebuilds_its_model_from_urdf_text():
    """models/arm_base_drives.urdf (a turntable under three pitch joints): the recheck writes the loaded model
    back to URDF text, reads it into Pinocchio again and finds each strategy's residual (the turntable,
    never loaded by gravity, carries nothing)."""
    c = CompareProblem(load_urdf(str(MODELS / "arm_base_drives.urdf")), payload=(0.0, 1.0), samples=50).solve()
    scale = max(j.max for j in c.strategy("none").joints)
    assert all(s.available for s in c.strategies) and scale > 100
    for s in c.strategies:
        assert s.joints[0].max == 0.0 and s.pinocchio.max_difference < 1e-9 * scale, s.name
        assert s.pinocchio.at_worst == pytest.approx(s.pinocchio.reported, rel=1e-9, abs=1e-9 * scale), s.name
