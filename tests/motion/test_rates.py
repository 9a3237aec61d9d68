"""Velocities and accelerations (linear solves) against central differences of positions."""

import numpy as np
import pytest

from synth.motion import motion_range, sweep

from .helpers import four_bar, inverted_slider_crank, slider_crank


CASES = {
    "four-bar": lambda: four_bar(1.0, 3.5, 3.0, 4.0, tracer=(2.0, 3.0)),
    "slider-crank": lambda: slider_crank(1.0, 3.0, 0.5),
    "inverted slider-crank": lambda: inverted_slider_crank(1.0, 2.0),
}


def triad_linkage():
    """The class-III linkage of the oracle test (Newton's method)."""
    from .test_oracle import triad

    return triad()


@pytest.mark.parametrize("name", [*CASES, "triad"])
def test_velocities_and_accelerations_match_central_differences(name):
    lk = triad_linkage() if name == "triad" else CASES[name]()
    r = motion_range(lk)
    lo, hi = (lk.pose_inputs[0], lk.pose_inputs[0] + 2) if r.full_rotation else r.limits
    phi = lo + (hi - lo) * np.array([0.2, 0.5, 0.8])
    h = 1e-5
    for x in phi:
        m = sweep(lk, steps=3, start=x - h, stop=x + h, velocities=True, accelerations=True)
        v_fd = (m.joints[2] - m.joints[0]) / (2 * h)
        a_fd = (m.joints[2] - 2 * m.joints[1] + m.joints[0]) / h ** 2
        size = lk.scale
        assert np.abs(m.velocities[1] - v_fd).max() < 1e-7 * size
        assert np.abs(m.accelerations[1] - a_fd).max() < 2e-4 * size
