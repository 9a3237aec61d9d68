"""Linkages the motion tests share, built from their textbook dimensions."""

import math

import numpy as np

from synth.motion import Linkage
from synth.structure.chain import Chain, Mechanism


def four_bar(a, b, c, d, phi=1.0, mode=1, tracer=None):
    """Crank a (0-1 at the origin), coupler b (1-2), rocker c (2-3 at (d, 0)), frame d; crank at phi;
    mode ±1 the side of the coupler pin from the line crank pin → rocker pivot."""
    A = np.array([a * math.cos(phi), a * math.sin(phi)])
    O4 = np.array([d, 0.0])
    v = O4 - A
    e = np.hypot(*v)
    along = (b * b - c * c + e * e) / (2 * e)
    h = math.sqrt(b * b - along * along)
    B = A + along * v / e + mode * h * np.array([-v[1], v[0]]) / e
    chain = Chain.parse("0-1 1-2 2-3 3-0")  # joints 0-1 0-3 1-2 2-3
    tracers = {} if tracer is None else {"P": (2, tuple(tracer))}
    return Linkage(Mechanism(chain, 0), (0,), np.array([[0, 0], O4, A, B]), tracers=tracers)


def slider_crank(r, l, e, phi=1.0):
    """Crank r (0-1 at the origin), rod l (1-2), slider 3 on the line y = e of the frame (0=3)."""
    A = np.array([r * math.cos(phi), r * math.sin(phi)])
    B = np.array([A[0] + math.sqrt(l * l - (e - A[1]) ** 2), e])
    chain = Chain.parse("0-1 1-2 2-3 0=3")  # joints 0-1 0=3 1-2 2-3
    return Linkage(Mechanism(chain, 0), (0,), np.array([[0, 0], B, A, B]), slides={1: (1.0, 0.0)})


def inverted_slider_crank(r, d, phi=1.0):
    """Crank r (0-1 at the origin), block 2 pinned to the crank (1-2), sliding on the guide 3 (2=3)
    that turns about (d, 0) on the frame (0-3)."""
    A = np.array([r * math.cos(phi), r * math.sin(phi)])
    C = np.array([d, 0.0])
    u = (A - C) / np.hypot(*(A - C))
    chain = Chain.parse("0-1 1-2 2=3 3-0")  # joints 0-1 0-3 1-2 2=3
    return Linkage(Mechanism(chain, 0), (0,), np.array([[0, 0], C, A, A]), slides={3: tuple(u)})


def scotch_yoke(r, phi=1.0, reversed_chain=False):
    """Crank r (0-1 at the origin), block 2 pinned to the crank (1-2), sliding in the yoke's vertical
    slot (2=3); the yoke 3 slides horizontally on the frame (0=3) and carries the tracer Y at
    (2, −1) in the pose.  Its group (links 2, 3) is an RPP dyad; ``reversed_chain`` numbers the
    links so that the search meets it from its other end, as PPR (crank 3, yoke 1, block 2)."""
    A = np.array([r * math.cos(phi), r * math.sin(phi)])
    if reversed_chain:
        chain = Chain.parse("0-3 3-2 2=1 1=0")  # joints 0=1 0-3 1=2 2-3
        points, slides, crank, yoke = np.array([[2, -1], [0, 0], A, A]), {0: (1.0, 0.0), 2: (0.0, 1.0)}, 1, 1
    else:
        chain = Chain.parse("0-1 1-2 2=3 3=0")  # joints 0-1 0=3 1-2 2=3
        points, slides, crank, yoke = np.array([[0, 0], [2, -1], A, A]), {1: (1.0, 0.0), 3: (0.0, 1.0)}, 0, 3
    return Linkage(Mechanism(chain, 0), (crank,), points, slides=slides, tracers={"Y": (yoke, (2.0, -1.0))})
