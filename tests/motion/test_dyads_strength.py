"""The decomposition into dyads, each group's fields and assembly sign worked out from the pose by
hand (the side of a line a pin is on), the dead positions it names, and the closure's angles."""

import math

import numpy as np
import pytest

from synth.motion import Linkage, linkage_from_pose
from synth.motion._dyads import Closure, Dyad, decompose, locked_groups
from synth.structure.chain import Chain, Mechanism

from .helpers import four_bar, inverted_slider_crank, slider_crank

SLIDER_CRANK = Mechanism(Chain.parse("0-1 1-2 2-3 0=3"), 0)  # joints 0-1 0=3 1-2 2-3


@pytest.mark.parametrize("mode", [1, -1])
def test_a_four_bars_dyad_has_the_sign_of_the_side_its_pin_is_on(mode):
    # joints 0-1 0-3 1-2 2-3: the coupler 2 and the rocker 3 close on the crank pin 1-2 and the pivot 0-3
    # with the middle pin 2-3 on the left (+1) or the right (−1) of the line crank pin → pivot
    lk = four_bar(1.0, 3.5, 3.0, 4.0, mode=mode)
    assert decompose(lk) == [Dyad("RRR", (2, 3), (2, 1), 3, (1, 0), float(mode))]


@pytest.mark.parametrize("side", [1, -1])
def test_a_slider_cranks_dyad_is_written_from_its_slider_with_the_side_of_its_rod(side):
    # crank pin A, slider pin B on y = 0.5 ahead of A (side +1) or behind it (−1): sign of (B − A)·slide
    a = np.array([math.cos(1.0), math.sin(1.0)])
    b = np.array([a[0] + side * math.sqrt(9 - (0.5 - a[1]) ** 2), 0.5])
    lk = Linkage(SLIDER_CRANK, (0,), [[0, 0], b, a, b], slides={1: (1.0, 0.0)})
    # seen from the crank it is R (1-2), R (2-3), P (0=3): RRP, written from its other end as PRR
    assert decompose(lk) == [Dyad("PRR", (3, 2), (1, 2), 3, (0, 1), float(side))]
    flipped = Linkage(SLIDER_CRANK, (0,), [[0, 0], b, a, b], slides={1: (-1.0, 0.0)})
    assert decompose(flipped)[0].sign == -side


def test_an_inverted_slider_cranks_dyad_has_the_sign_of_its_slide_along_the_pivots():
    # joints 0-1 0-3 1-2 2=3: the guide 3 turns about C = (2, 0), its slide u points from C to the crank pin A;
    # the sign is that of u · (C − A) = −|A − C|
    lk = inverted_slider_crank(1.0, 2.0)
    assert decompose(lk) == [Dyad("RPR", (2, 3), (2, 1), 3, (1, 0), -1.0)]
    turned = Linkage(lk.mechanism, (0,), lk.points, {3: tuple(-np.array(lk.slides[3]))})
    assert decompose(turned)[0].sign == 1.0
    # a crank longer than the frame (a quick-return drive) and the whole mechanism moved far off: the same
    # side, u · (C − A) = −|A − C| < 0, whatever |A| and |C|
    whitworth = inverted_slider_crank(2.0, 1.0)
    assert decompose(whitworth)[0].sign == -1.0
    far = Linkage(whitworth.mechanism, (0,), whitworth.points + [-50, 30], whitworth.slides)
    assert decompose(far)[0].sign == -1.0


def test_two_slides_and_a_pin_are_a_prp_dyad_of_sign_one():
    chain = Chain.parse("0-1 1=2 2-3 3=0")  # joints 0-1 0=3 1=2 2-3
    lk = Linkage(Mechanism(chain, 0), (0,), [[0, 0], [3, 1], [1, 1], [3, 1]], slides={1: (1, 0), 2: (0, 1)})
    assert decompose(lk) == [Dyad("PRP", (2, 3), (2, 1), 3, (1, 0), 1.0)]


def test_a_planet_on_a_driven_carrier_is_a_gear_group():
    # sun 1 and carrier 2 driven on the frame's axis; the planet 4 turns on the carrier's pin 2-4 and
    # meshes with the sun (1~4); the ring 3 turns on the central axis and meshes with the planet (3~4)
    chain = Chain.parse("0-1-2-3 2-4 1~4 3~4")  # joints 0-1-2-3, 1~4, 2-4, 3~4
    lk = Linkage(Mechanism(chain, 0), (0, 0), [[0, 0], [1, 0], [1.5, 0], [2, 0]], driven=(1, 2))
    assert decompose(lk) == [Dyad("gear", (4, 4), (2, 1), -1, (2, 2), 1.0), Dyad("gear", (3, 3), (0, 3), -1, (0, 2), 1.0)]
    # the ring turns by the planet's ratio: (θ3 − θ2) = ρ(θ4 − θ2) with ρ = +0.25 (planet ~ ring, 3~4: θ3 … θ4)
    theta = Closure(lk, decompose(lk)).angles(np.array([[0.4, 0.1]]))[0]
    assert theta[1] == pytest.approx(0.4) and theta[2] == pytest.approx(0.1)
    assert theta[4] - 0.1 == pytest.approx((0.4 - 0.1) / -0.5)  # sun ~ planet: θ1 − θ2 = −0.5 (θ4 − θ2)
    assert theta[3] - 0.1 == pytest.approx(0.25 * (theta[4] - 0.1))


def test_a_triad_does_not_decompose_and_names_no_dyad():
    chain = Chain.parse("0-1 1-2 2-3 3-4 4-0 3-5 5-0")
    pts = {(0, 1): (0, 0), (1, 2): (0.6, 0.8), (2, 3): (1.6, 1.9), (3, 4): (2.9, 1.6), (0, 4): (3.4, 0.2),
           (3, 5): (2.2, 2.8), (0, 5): (-0.6, 2.2)}
    lk = linkage_from_pose(Mechanism(chain, 0, 1), [pts[j] for j in chain.joints])
    assert decompose(lk) is None and locked_groups(lk) == []


def test_the_dead_positions_named_are_the_aligned_dyads_only():
    flat = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [2, 0]])
    assert locked_groups(flat) == [(2, 3)]
    assert locked_groups(four_bar(1.0, 3.5, 3.0, 4.0)) == []
    # a slider-crank's rod-and-slider dyad closes where the slide's line meets the circle of the rod about
    # the crank pin: square to the slide, the line touches the circle (aligned, dead); along it, it
    # crosses the circle's centre (far from dead)
    a = np.array([0.0, 1.0])
    square = Linkage(SLIDER_CRANK, (0,), [[0, 0], [0, 4], a, [0, 4]], slides={1: (1.0, 0.0)})
    assert locked_groups(square) == [(3, 2)]
    along = Linkage(SLIDER_CRANK, (0,), [[0, 0], [4, 1], a, [4, 1]], slides={1: (1.0, 0.0)})
    assert locked_groups(along) == []


def test_the_closure_carries_the_tracers_and_turns_the_links():
    lk = four_bar(1.0, 3.5, 3.0, 4.0, tracer=(2.0, 3.0))
    closure = Closure(lk, decompose(lk))
    joints, tracers = closure.points(np.array([[0.0], [0.3]]))
    assert np.abs(joints[0] - lk.points).max() < 1e-12 and np.abs(tracers["P"][0] - [2.0, 3.0]).max() < 1e-12
    theta, t, g, mu, every = closure(np.array([[0.3]]))
    assert theta[0, 1] == pytest.approx(0.3) and theta[0, 0] == 0.0
    # the tracer is carried by the coupler 2: R(θ2)·P + t2
    c, s = math.cos(theta[0, 2]), math.sin(theta[0, 2])
    assert np.abs(np.array([c * 2 - s * 3, s * 2 + c * 3]) + t[0, 2] - tracers["P"][1]).max() < 1e-12
    assert np.abs(every[0] - joints[1]).max() < 1e-12
    assert np.abs(closure.angles(np.array([[0.3]]))[0] - theta[0]).max() < 1e-12
    # the transmission angle of the pose: between coupler (2-3 − 1-2) and rocker (2-3 − 0-3)
    p = lk.points
    u, v = p[3] - p[2], p[3] - p[1]
    _, _, _, mu0, _ = closure(np.array([[0.0]]))
    assert mu0[0, 0] == pytest.approx(math.acos(u @ v / np.hypot(*u) / np.hypot(*v)), abs=1e-12)
    assert slider_crank(1.0, 3.0, 0.5).dof == 1


def test_a_dyad_held_by_a_multiple_joint_keeps_every_links_lengths():
    # a four-bar 0-1-2-3 whose coupler-rocker pin 2-3-5 also holds link 5; links 4 and 5 close a second
    # dyad on that pin and the frame pivot 0-4 (joints 0-1 0-3 0-4 1-2 2-3-5 4-5)
    chain = Chain.parse("0-1 1-2 2-3-5 3-0 5-4 4-0")
    at = {(0, 1): (0, 0), (1, 2): (0.6, 0.8), (2, 3, 5): (3, 2.5), (0, 3): (4, 0), (4, 5): (5.5, 3.5), (0, 4): (7, 0)}
    lk = linkage_from_pose(Mechanism(chain, 0, 1), [at[j] for j in chain.joints])
    plan = decompose(lk)
    assert plan == [Dyad("RRR", (2, 3), (3, 1), 4, (1, 0), 1.0), Dyad("RRR", (4, 5), (2, 4), 5, (0, 2), -1.0)]
    joints = Closure(lk, plan).points(np.linspace(0, 0.6, 7)[:, None])[0]
    for a, b in ((0, 3), (1, 4), (3, 4), (4, 5), (2, 5), (1, 2)):  # the pins of one link stay apart by their length
        d = np.hypot(*(joints[:, a] - joints[:, b]).T)
        assert np.abs(d - d[0]).max() < 1e-12, (a, b)
    assert np.abs(joints[:, 0]).max() == 0 and np.abs(joints[:, 2] - [7, 0]).max() == 0
