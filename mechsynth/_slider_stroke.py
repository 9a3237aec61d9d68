"""Dead centres measured on the solver's own positions: a crank-driven slider's stroke and quick-return
ratio, shared by ``mechsynth move --range`` and the scene's ``closed form`` (which checks them against
the textbook's formulas, written independently).

Example
-------
>>> from synth.motion import read_linkage, sweep
>>> offset = read_linkage("models/motion_slider_crank.toml")   # crank 1, rod 3.5, offset 0.5
>>> sliders_on_frame(offset)                                     # the pair 0=3, slider 3, its pin 2-3
[(1, 3, 3)]
>>> s = slider_stroke(offset, sweep(offset, steps=360), 3, offset.slides[1])
>>> round(s.length, 10), round(s.quick_return_ratio, 7)       # √20 − √6 and (π + δ)/(π − δ)
(2.0226462122, 1.058997)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Stroke", "dead_centres", "slider_stroke", "sliders_on_frame"]


@dataclass(frozen=True)
class Stroke:
    """A slider's stroke over a crank's turn: its length, the quick-return ratio (the slower stroke's crank
    angle over the faster's) and the crank's inputs (rad) at the far and the near dead centre."""

    length: float
    quick_return_ratio: float
    far: float
    near: float


def dead_centres(linkage, motion, value) -> tuple[tuple[float, float], tuple[float, float]]:
    """The inputs and values of the largest and smallest ``value(motion)`` over a crank's turn (``motion``
    a sweep of it), each refined between the samples beside it by the motion layer's bounded search
    (:func:`synth.motion.refine_extreme`), the solver posing the linkage at each input it tries."""
    from synth.motion import refine_extreme, sweep

    def at(x: float) -> float:
        return float(value(sweep(linkage, steps=2, start=x, stop=x + 1e-3))[0])

    v = value(motion)
    step = float(motion.inputs[1, 0] - motion.inputs[0, 0])
    out = []
    for largest in (True, False):
        i = int(np.nanargmax(v if largest else -v))
        x = float(motion.inputs[i, 0])  # a crank turns on beyond its sweep's ends: the bracket is not cut there
        out.append(refine_extreme(at, x - step, x + step, (x, float(v[i])), largest=largest))
    return out[0], out[1]


def slider_stroke(linkage, motion, pin: int, along) -> Stroke:
    """The stroke of joint ``pin`` (a slider's pin) along the direction ``along`` (its slide on the frame) over
    a crank's turn (``motion`` a sweep of it); ``far`` is the input where the pin is farthest along it."""
    p = linkage.points
    u = np.asarray(along, dtype=float)
    u = u / np.hypot(*u)

    def slide(m):
        return (m.joints[:, pin] - p[pin]) @ u

    (far, s_far), (near, s_near) = dead_centres(linkage, motion, slide)
    forward = (far - near) % (2 * math.pi)
    ratio = max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward)
    return Stroke(s_far - s_near, ratio, far, near)


def sliders_on_frame(linkage) -> list[tuple[int, int, int]]:
    """Each slider on the frame that is not an input: (its prismatic pair, the slider link, its pin — the
    slider's first revolute joint, whose travel is the slider's)."""
    from synth import JointKind

    chain = linkage.chain
    out = []
    for k, joint in enumerate(chain.joints):
        if linkage.kind(k) != JointKind.PRISMATIC or linkage.frame not in joint or k in linkage.inputs:
            continue
        link = next(x for x in joint if x != linkage.frame)
        pin = next((m for m in linkage.joints_of(link) if linkage.kind(m) == JointKind.REVOLUTE), None)
        if pin is not None:
            out.append((k, link, pin))
    return out
