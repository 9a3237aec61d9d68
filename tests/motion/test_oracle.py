"""The engine against an independent solver (tests/oracles/motion.py: absolute link poses, Newton
on joint coincidences, small steps), on dyad mechanisms and on a triad (class III)."""

import math

import numpy as np
import pytest

from synth.motion._sweep import _solver
from synth.motion import assemble, linkage_from_pose, motion_range, sweep
from synth.structure.chain import Chain, Mechanism

from ..oracles.motion import follow, oracle_of, traced_by_the_oracle
from .helpers import four_bar, inverted_slider_crank, scotch_yoke, slider_crank


def triad():
    """A Stephenson six-bar driven so that its group is a triad (class III): the crank 1 drives link 2,
    which joins the ternary link 3; link 3 is held by links 4 and 5 to the frame."""
    chain = Chain.parse("0-1 1-2 2-3 3-4 4-0 3-5 5-0")
    pts = {(0, 1): (0, 0), (1, 2): (0.6, 0.8), (2, 3): (1.6, 1.9), (3, 4): (2.9, 1.6), (0, 4): (3.4, 0.2),
           (3, 5): (2.2, 2.8), (0, 5): (-0.6, 2.2)}
    points = np.array([pts[j] for j in chain.joints], dtype=float)
    return linkage_from_pose(Mechanism(chain, 0, 1), points)


CASES = {
    "four-bar": lambda: four_bar(1.0, 3.5, 3.0, 4.0),
    "four-bar other mode": lambda: four_bar(1.3, 2.2, 2.9, 3.1, mode=-1),
    "slider-crank": lambda: slider_crank(1.0, 3.0, 0.5),
    "inverted slider-crank": lambda: inverted_slider_crank(1.0, 2.0),
    "watt": lambda: linkage_from_pose(Mechanism(Chain.parse("0-1 1-2 2-3 3-0 2-4 4-5 5-3"), 0, 1),
                                      [[0, 0], [3, 0], [0.5, 1], [1.5, 2], [2.5, 2.2], [3.2, 1.4], [2.4, 3.4]]),
    "triad": triad,
    "Scotch yoke (RPP)": lambda: scotch_yoke(1.3),
    "Scotch yoke (PPR)": lambda: scotch_yoke(0.7, phi=2.0, reversed_chain=True),
}


@pytest.mark.parametrize("name", CASES)
def test_engine_agrees_with_the_independent_solver(name):
    lk = CASES[name]()
    rng = motion_range(lk)
    phi0 = lk.pose_inputs[0]
    lo, hi = (phi0 - 4, phi0 + 4) if rng.full_rotation else rng.limits
    span = min(hi - phi0, math.radians(120)), max(lo - phi0, -math.radians(120))
    for end in span:
        turns = np.linspace(0, end * 0.98, 12)
        expected = follow(oracle_of(lk), turns)
        got = sweep(lk, steps=12, start=phi0, stop=phi0 + end * 0.98).joints
        assert np.abs(got - expected).max() < 1e-9, name
    if name == "triad":
        assert _solver(lk).plan is None  # it really is solved by Newton's method


def test_a_tracer_moved_by_the_independent_solver_is_the_engines():
    """The oracle's tracer point (tests/oracles/motion.py, a joint of its link alone), which re-checks the answers of
    dimensional synthesis and of the atlas search, passes where the engine's sweep puts it, at inputs either side of
    the pose, in any order."""
    lk = four_bar(1.0, 3.5, 3.0, 4.0, tracer=(2.2, 3.1))
    phi0 = float(lk.pose_inputs[0])
    inputs = phi0 + np.array([0.0, 0.7, 2.9, 1.2, -0.8])
    expected = np.array([assemble(lk, float(v)).tracers["P"][1] for v in inputs])
    assert np.abs(traced_by_the_oracle(lk, inputs) - expected).max() < 1e-9
    assert np.abs(expected - expected[0]).max() > 1  # (the point moves)
