"""Positions against closed forms: Freudenstein's equation for a four-bar, the offset slider-crank's
stroke and quick-return ratio, the inverted slider-crank's guide angle."""

import math

import numpy as np
import pytest

from synth.motion import motion_range, sweep

from .helpers import four_bar, inverted_slider_crank, slider_crank


@pytest.mark.parametrize("a, b, c, d, mode", [(1.0, 3.5, 3.0, 4.0, 1), (1.0, 3.5, 3.0, 4.0, -1),
                                              (2.0, 5.0, 4.5, 6.0, 1), (1.3, 2.2, 2.9, 3.1, -1)])
def test_four_bar_follows_freudenstein(a, b, c, d, mode):
    lk = four_bar(a, b, c, d, mode=mode)
    motion = sweep(lk, steps=721)
    assert motion.stopped is None
    phi = motion.inputs[:, 0]
    A, B = motion.joints[:, 2], motion.joints[:, 3]
    assert np.abs(A - np.c_[a * np.cos(phi), a * np.sin(phi)]).max() < 1e-12
    psi = np.arctan2(B[:, 1], B[:, 0] - d)
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    assert np.abs(k1 * np.cos(psi) - k2 * np.cos(phi) + k3 - np.cos(phi - psi)).max() < 1e-12
    # the rocker angle from Freudenstein's equation solved in closed form (P cos ψ + Q sin ψ + R = 0)
    P, Q, R = k1 - np.cos(phi), -np.sin(phi), k3 - k2 * np.cos(phi)
    root = np.sqrt(P * P + Q * Q - R * R)
    both = [2 * np.arctan2(-Q + s * root, R - P) for s in (1, -1)]
    pins = [np.c_[d + c * np.cos(x), c * np.sin(x)] for x in both]
    closest = np.minimum(*(np.abs(p - B).max(axis=1) for p in pins))
    assert closest.max() < 1e-12
    side = np.sign((d - A[:, 0]) * (B[:, 1] - A[:, 1]) - (-A[:, 1]) * (B[:, 0] - A[:, 0]))
    assert (side == mode).all()  # one assembly mode throughout


def test_grashof_classes_and_rocker_limits():
    assert motion_range(four_bar(1, 3.5, 3, 4)).grashof == "crank-rocker (Grashof)"
    assert motion_range(four_bar(4, 3.5, 3, 1)).grashof == "double-crank (Grashof)"
    assert motion_range(four_bar(3, 1, 3.5, 4, phi=1.0)).grashof == "double-rocker (Grashof)"
    a, b, c, d = 2.5, 3.2, 3.0, 4.0
    rocker = four_bar(a, b, c, d, phi=0.5)
    r = motion_range(rocker)
    assert r.grashof == "triple-rocker (non-Grashof)" and not r.full_rotation
    # the dead positions: coupler and rocker in line, |A O4| = b + c
    limit = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    assert abs(r.limits[0] + limit) < 1e-9 and abs(r.limits[1] - limit) < 1e-9
    assert len(r.dead_positions) == 2


def test_crank_rocker_toggles_where_crank_and_coupler_are_in_line():
    a, b, c, d = 1.0, 3.5, 3.0, 4.0
    r = motion_range(four_bar(a, b, c, d))
    assert r.full_rotation and r.limits is None
    # rocker extremes: |O2 B| = b + a (extended) or b − a (folded), with B on the rocker circle
    angles = []
    for length, behind in ((b + a, 0.0), (b - a, math.pi)):
        gamma = math.acos((length ** 2 + d * d - c * c) / (2 * length * d))  # angle of O2B above the frame
        angles.append((gamma + behind) % (2 * math.pi))
    got = [x for x, _ in r.toggles]
    assert len(got) == 2 and {link for _, link in r.toggles} == {3}
    assert all(min(abs(math.remainder(x - y, 2 * math.pi)) for y in angles) < 1e-9 for x in got)


@pytest.mark.parametrize("r, l, e", [(1.0, 3.0, 0.5), (1.0, 2.5, -0.8), (0.7, 4.0, 0.0)])
def test_offset_slider_crank_stroke_and_quick_return(r, l, e):
    lk = slider_crank(r, l, e)
    motion = sweep(lk, steps=1441)
    phi = motion.inputs[:, 0]
    x = motion.joints[:, 3, 0]
    assert np.abs(x - (r * np.cos(phi) + np.sqrt(l * l - (e - r * np.sin(phi)) ** 2))).max() < 1e-12
    assert np.abs(motion.joints[:, 3, 1] - e).max() < 1e-12
    rng = motion_range(lk)
    assert rng.full_rotation
    (f1, _), (f2, _) = rng.toggles
    far = math.atan2(e, math.sqrt((l + r) ** 2 - e * e))
    near = math.atan2(e, math.sqrt((l - r) ** 2 - e * e)) + math.pi
    def gap(x, y):
        return abs(math.remainder(x - y, 2 * math.pi))

    assert min(max(gap(f1, far), gap(f2, near)), max(gap(f1, near), gap(f2, far))) < 1e-9
    ends = sweep(lk, steps=2, start=far, stop=near).joints[:, 3, 0]
    stroke = math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e)
    assert abs(abs(ends[0] - ends[1]) - stroke) < 1e-12
    forward = (near - far) % (2 * math.pi)
    ratio = max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward)
    expected = (math.pi + (math.asin(e / (l - r)) - math.asin(e / (l + r)))) if e >= 0 else None
    if expected is not None:
        assert abs(max(expected, 2 * math.pi - expected) / min(expected, 2 * math.pi - expected) - ratio) < 1e-9


def test_inverted_slider_crank_guide_points_at_the_crank_pin():
    r, d = 1.0, 2.0
    lk = inverted_slider_crank(r, d)
    motion = sweep(lk, steps=721)
    assert motion.stopped is None
    phi = motion.inputs[:, 0]
    A = np.c_[r * np.cos(phi), r * np.sin(phi)]
    assert np.abs(motion.joints[:, 2] - A).max() < 1e-12
    guide = np.arctan2(A[:, 1], A[:, 0] - d)  # closed form: the guide's line passes through A
    turned = motion.angles[:, 3] + math.atan2(*lk.slides[3][::-1])
    assert np.abs(np.sin(turned - guide)).max() < 1e-12
    assert motion_range(lk).full_rotation  # r < d: the crank turns fully


def test_transmission_angle_extremes_of_a_crank_rocker():
    # μ between coupler and rocker: cos μ = (b² + c² − e²)/(2bc), e = |A O4| = d ∓ a at φ = 0, π
    a, b, c, d = 1.0, 3.5, 3.0, 4.0
    m = sweep(four_bar(a, b, c, d), steps=360)  # neither 0 nor π is a step
    t = m.transmission["links 2, 3"]
    assert abs(t["min"] - math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c))) < 1e-9
    assert abs(t["max"] - math.acos((b * b + c * c - (d + a) ** 2) / (2 * b * c))) < 1e-9
    assert abs(math.remainder(t["at_min"], 2 * math.pi)) < 1e-4
    assert abs(math.remainder(t["at_max"] - math.pi, 2 * math.pi)) < 1e-4


def test_planetary_train_shaft_speeds_follow_willis():
    """Sun 1, carrier 2 and ring 3 on the frame's central axis (the multiple joint 0-1-2-3), planet
    4 on the carrier meshing with both; the sun and the carrier drive (W = 2) and the ring turns as
    Willis's formula says: (θ3 − θ2)/(θ1 − θ2) = −z1/z3 = −r1/r3."""
    from synth.motion import Linkage, sweep_grid
    from synth.structure.chain import Chain, Mechanism

    r_sun, r_planet = 1.0, 0.5
    r_ring = r_sun + 2 * r_planet
    chain = Chain.parse("0-1-2-3 2-4 1~4 3~4")  # joints: 0-1-2-3, 1~4, 2-4, 3~4
    points = {(0, 1, 2, 3): (0, 0), (1, 4): (r_sun, 0), (2, 4): (r_sun + r_planet, 0), (3, 4): (r_ring, 0)}
    lk = Linkage(Mechanism(chain, 0), (0, 0), np.array([points[j] for j in chain.joints], dtype=float),
                 driven=(1, 2))
    assert math.isclose(lk.meshes[1], -r_planet / r_sun) and math.isclose(lk.meshes[3], r_planet / r_ring)
    m = sweep_grid(lk, [(0.0, 1.0), (0.0, 0.5)], steps=3, velocities=True)
    ring = m.angles[:, 3]
    sun, carrier = m.inputs[:, 0], m.inputs[:, 1]
    assert np.allclose(ring - carrier, -(r_sun / r_ring) * (sun - carrier), atol=1e-12, rtol=0)
    again = Linkage.from_dict(lk.to_dict())
    assert again.driven == (1, 2) and again.to_dict()["inputs"] == ["0-1", "0-2"]


def test_a_piston_driving_a_slider_crank_moves_through_its_stroke():
    """The slider as a prismatic input: its branch ends where crank and rod are in line, one
    stroke apart (√((l + r)² − e²) − √((l − r)² − e²))."""
    from synth.motion import Linkage

    r, l, e = 1.0, 3.0, 0.5
    lk = slider_crank(r, l, e)
    piston = Linkage(lk.mechanism, (1,), lk.points, lk.slides)
    lo, hi = motion_range(piston).limits
    assert abs((hi - lo) - (math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e))) < 1e-9
    m = sweep(piston, steps=101)
    phi = np.arctan2(m.joints[:, 2, 1], m.joints[:, 2, 0])
    x = m.joints[:, 3, 0]
    assert np.abs(x - (r * np.cos(phi) + np.sqrt(l * l - (e - r * np.sin(phi)) ** 2))).max() < 1e-12


def test_a_parallelogram_stops_at_its_change_points():
    """A parallelogram four-bar (a = c, b = d) meets the crossed branch where all four links are in
    line (φ = 0 and π): the branch of its pose ends there, though no dyad fails to close."""
    lk = four_bar(1.0, 2.0, 1.0, 2.0, phi=1.0, mode=1)
    r = motion_range(lk)
    assert not r.full_rotation
    lo, hi = r.limits
    assert abs(lo) < 1e-6 and abs(hi - math.pi) < 1e-6
    assert all("change point" in why for _, why in r.dead_positions)
    assert motion_range(four_bar(1.0, 3.5, 3.0, 4.0)).full_rotation  # a crank-rocker has none


@pytest.mark.parametrize("reversed_chain", [False, True], ids=["RPP", "PPR"])
def test_scotch_yoke_in_closed_form(reversed_chain):
    """The yoke moves by r cos φ and never turns; the block in its slot moves with the crank pin
    (velocity and acceleration too); the group is a dyad (RPP, met from either end), not a group for
    Newton's method; its slides stay square (90°)."""
    from synth.motion._dyads import decompose

    from .helpers import scotch_yoke

    r, phi0 = 1.3, 1.0
    lk = scotch_yoke(r, phi0, reversed_chain)
    assert [d.kind for d in decompose(lk)] == ["RPP"]
    m = sweep(lk, steps=721, velocities=True, accelerations=True)
    phi = m.inputs[:, 0]
    yoke = 1 if reversed_chain else 3
    x = 2 + r * (np.cos(phi) - math.cos(phi0))
    assert np.abs(m.tracers["Y"] - np.c_[x, np.full_like(x, -1.0)]).max() < 1e-12
    assert np.abs(np.remainder(m.angles[:, yoke] + math.pi, 2 * math.pi) - math.pi).max() < 1e-12  # it never turns
    # the block's points: its pin on the crank (2-3 / 1-2) and, in the yoke's slot, the prismatic
    # joint's point where the block carries it (2=3; 1=2 is carried by the yoke: its x is the yoke's)
    pin, slot = (3, 2) if reversed_chain else (2, 3)
    circle = np.c_[np.cos(phi), np.sin(phi)]
    assert np.abs(m.joints[:, pin] - r * circle).max() < 1e-12
    assert np.abs(m.velocities[:, pin] - r * circle[:, ::-1] * [-1, 1]).max() < 1e-12
    assert np.abs(m.accelerations[:, pin] + r * circle).max() < 1e-12
    if reversed_chain:  # carried by the yoke: up and down with nothing, across with the yoke
        assert np.abs(m.joints[:, slot, 0] - r * circle[:, 0]).max() < 1e-12
        assert np.abs(m.velocities[:, slot] - np.c_[-r * circle[:, 1], 0 * phi]).max() < 1e-12
    else:
        assert np.abs(m.joints[:, slot] - r * circle).max() < 1e-12
    t = m.transmission["links 2, 1" if reversed_chain else "links 2, 3"]
    assert t["min"] == pytest.approx(math.pi / 2, abs=1e-12) and t["max"] == pytest.approx(math.pi / 2, abs=1e-12)
    assert motion_range(lk).full_rotation


def test_the_sweeps_crank_table_agrees_with_each_angles_own_cosine():
    """A sweep turns its crank by a table of rotations from each block's exact first angle; over
    10⁵ steps and four turns its points agree with those solved from every angle's own cos and sin
    (the search for a branch's ends uses those) to 1e-13, and its link angles, computed only when
    read, agree modulo a turn."""
    from synth.motion._sweep import _solver

    lk = four_bar(1.0, 3.5, 3.0, 4.0, tracer=(2.5, 4.5))
    m = sweep(lk, steps=100_001, start=-7.0, stop=20.0)
    assert "angles" not in m.__dict__  # not computed by the sweep
    theta, _, _, _, joints = _solver(lk).closed(m.inputs - lk.pose_inputs)
    assert np.abs(m.joints - joints).max() < 1e-13
    turned = np.remainder(m.angles - theta + math.pi, 2 * math.pi) - math.pi
    assert np.abs(turned).max() < 1e-13


@pytest.mark.parametrize("past", [1e-3, -1e-3])
def test_a_stroke_measured_from_a_sweep_that_starts_at_a_dead_centre(past):
    """The crank posed a hair past the slider's far dead centre (the extreme between the sweep's last sample and
    its first: refined across the turn's seam, where a bracket cut at the sweep's ends left the stroke 6.5e-7
    short), or a hair short of it (between the first sample and the second)."""
    from mechsynth._slider_stroke import slider_stroke

    r, l, e = 1.0, 3.5, 0.5
    far = math.atan2(e, math.sqrt((l + r) ** 2 - e * e))
    lk = slider_crank(r, l, e, phi=far + past)
    s = slider_stroke(lk, sweep(lk, steps=360), 3, (1.0, 0.0))
    assert s.length == pytest.approx(math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e), abs=1e-12)
    assert abs(math.remainder(s.far - far, 2 * math.pi)) < 1e-7
