"""``synth.motion.link_poses``: the public position solver the dimensional synthesis and the curve index
use.  Every joint, carried by each link that holds it through the rigid motion R(θ)p + t, lands where a
sweep of the same linkage puts it — closed forms (a four-bar, a slider-crank) and Newton (a triad)."""

import math
import os

import numpy as np
import pytest

from synth.errors import BadSweep, CannotAssemble
from synth.motion import link_poses, motion_range, read_linkage, sweep
from synth.motion import Linkage
from synth.structure.chain import Chain, Mechanism

MODELS = os.path.join(os.path.dirname(__file__), "..", "..", "models")


def _carried(poses, linkage):
    """Every joint as each of its links carries it: (S, J, links per joint, 2)."""
    theta, t = poses.rotations, poses.translations
    out = []
    for k, joint in enumerate(linkage.chain.joints):
        p = linkage.points[k]
        per_link = []
        for link in joint:
            c, s = np.cos(theta[:, link]), np.sin(theta[:, link])
            per_link.append(np.stack((c * p[0] - s * p[1], s * p[0] + c * p[1]), axis=1) + t[:, link])
        out.append(per_link)
    return out


def _check_against_sweep(linkage, start, stop, steps=9):
    motion = sweep(linkage, steps=steps, start=start, stop=stop)
    poses = link_poses(linkage, motion.inputs[:, 0] - linkage.pose_inputs[0])
    for k, per_link in enumerate(_carried(poses, linkage)):
        if k in linkage.slides:  # a slide's point is carried by its first link only
            per_link = per_link[:1]
        for xy in per_link:
            assert np.abs(xy - motion.joints[:, k]).max() <= 1e-10 * linkage.scale, (k, linkage.chain.joints[k])
    return poses


def test_a_four_bar_in_closed_form_matches_its_sweep():
    lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    poses = _check_against_sweep(lk, lk.pose_inputs[0], lk.pose_inputs[0] + 2 * math.pi)
    assert poses.discriminants.shape == (9, 1) and (poses.discriminants >= 0).all()
    assert np.allclose(poses.rotations[:, 1], np.linspace(0, 2 * math.pi, 9))  # the crank turns by the offset
    assert ((poses.transmission >= 0) & (poses.transmission <= math.pi)).all()


def test_a_slider_crank_in_closed_form_matches_its_sweep():
    lk = read_linkage(os.path.join(MODELS, "motion_slider_crank.toml"))
    phi = float(lk.pose_inputs[0])
    _check_against_sweep(lk, phi, phi + 2 * math.pi)


def test_a_triad_by_newton_matches_its_sweep_and_has_no_discriminants():
    lk = read_linkage(os.path.join(MODELS, "motion_triad.toml"))
    lo, hi = motion_range(lk).limits
    poses = _check_against_sweep(lk, lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo), steps=5)
    assert poses.discriminants is None and poses.transmission is None
    with pytest.raises(CannotAssemble):  # a rocker's branch does not reach a whole turn
        link_poses(lk, [2 * math.pi])


def test_a_dyad_that_cannot_close_gives_nan_poses_and_a_negative_discriminant():
    # a crank as long as the frame with short rockers: the dyad opens beyond its reach at half a turn
    lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [3, 0], [3.5, 0.5]])
    poses = link_poses(lk, [0.0, math.pi])
    assert poses.discriminants[0, 0] >= 0 and poses.discriminants[1, 0] < 0
    assert np.isnan(poses.rotations[1, [2, 3]]).all()


@pytest.mark.parametrize("offsets", [[0.0, float("nan")], [math.inf], ["a"]])
def test_offsets_that_are_not_finite_numbers_are_refused(offsets):
    lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    with pytest.raises(BadSweep, match="finite numbers|must be numbers"):
        link_poses(lk, offsets)


def test_two_inputs_are_refused():
    chain = Chain.parse("0-1 1-2 2-3 3-4 4-0")
    grounded = tuple(k for k, j in enumerate(chain.joints) if 0 in j)
    lk = Linkage(Mechanism(chain, 0), grounded, np.random.default_rng(0).normal(size=(5, 2)))
    with pytest.raises(BadSweep, match="one input"):
        link_poses(lk, [0.0])


@pytest.mark.parametrize("model, offsets", [
    ("motion_four_bar.toml", [0.3, 2.0, 4.4]),
    ("motion_slider_crank.toml", [0.3, 2.0, 4.4]),
    ("motion_triad.toml", [0.1, 0.25, 0.4]),   # a rocker moved by Newton's method, inside its limits
])
def test_link_rates_are_the_derivatives_of_the_poses(model, offsets):
    """θ', t', θ'', t'' of ``link_rates`` against central differences of ``link_poses``, and its poses its own."""
    from synth.motion import link_rates

    lk = read_linkage(os.path.join(MODELS, model))
    h = 1e-4
    rates = link_rates(lk, offsets)
    here = link_poses(lk, offsets)
    assert np.array_equal(rates.rotations, here.rotations)
    up, down = link_poses(lk, np.add(offsets, h)), link_poses(lk, np.subtract(offsets, h))
    for value, first, second in ((here.rotations, rates.rotation_rates, rates.rotation_accelerations),
                                 (here.translations, rates.translation_rates, rates.translation_accelerations)):
        lo, hi = (down.rotations, up.rotations) if value is here.rotations else (down.translations, up.translations)
        scale = 1 + np.abs(first).max()
        assert np.abs((hi - lo) / (2 * h) - first).max() <= 1e-6 * scale
        assert np.abs((hi - 2 * value + lo) / h ** 2 - second).max() <= 1e-4 * (1 + np.abs(second).max())
