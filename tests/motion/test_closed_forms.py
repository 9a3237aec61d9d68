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
