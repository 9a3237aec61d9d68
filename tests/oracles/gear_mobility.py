"""Independent mobility of gear trains: the rank of their velocity constraints (a test oracle,
no code from ``synth``).

A planar body has a velocity field (ω, vx, vy): the point (x, y) moves at (vx − ω·y, vy + ω·x).
Each pair is written out by its definition and nothing else:

* a *pin* at the point P joining links a, b, c, …: every link has the velocity of the first
  at P (two equations per link after the first);
* a *gear mesh* between links a and b touching at the point C with the common normal n (a
  higher pair with two freedoms, f = 1): their velocities at C agree along n (one equation).

The mobility of a set S of links with the pairs among them is 3(|S| − 1) minus the rank of
those equations (rigid motions of the whole set are always solutions), computed exactly in
rationals.  A set's pairs are *independent* when the rank equals the number of equations.

Two kinds of geometry:

* :func:`generic_geometry` — every pin and contact point and every normal drawn at random
  (rational), the generic configuration of the structure;
* :func:`train_geometry` — a gear train as built: each axis a point, each mesh touching on the
  line of centres of its two gears (between them for an external pair, beyond the smaller for
  an internal one) with its normal tilted from the perpendicular by a pressure angle.

Example
-------
>>> import random
>>> pins, contacts = generic_geometry(3, [(0, 1), (0, 2)], [(1, 2)], random.Random(1))
>>> mobility(3, pins, contacts)   # a gear pair on a frame
1
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

__all__ = ["rows", "rank", "mobility", "generic_geometry", "train_geometry", "subsets_verdict"]


def _point_row(columns, a, b, x, y, nx, ny):
    """Velocity of a minus velocity of b at (x, y), along (nx, ny)."""
    row = [Fraction(0)] * (3 * len(columns))
    for link, sign in ((a, 1), (b, -1)):
        c = 3 * columns[link]
        row[c] += sign * (x * ny - y * nx)
        row[c + 1] += sign * nx
        row[c + 2] += sign * ny
    return row


def rows(links, pins, contacts):
    """The velocity equations of the pairs whose links are all in ``links``.

    ``pins``: [(point, links of the pin)], ``contacts``: [(a, b, point, normal)].
    """
    columns = {x: i for i, x in enumerate(sorted(links))}
    out = []
    for (x, y), members in pins:
        inside = [m for m in members if m in columns]
        for other in inside[1:]:
            out.append(_point_row(columns, inside[0], other, x, y, 1, 0))
            out.append(_point_row(columns, inside[0], other, x, y, 0, 1))
    for a, b, (x, y), (nx, ny) in contacts:
        if a in columns and b in columns:
            out.append(_point_row(columns, a, b, x, y, nx, ny))
    return out


def rank(matrix) -> int:
    """Exact rank by Gaussian elimination in rationals."""
    m = [list(r) for r in matrix]
    r = 0
    for c in range(len(m[0]) if m else 0):
        pivot = next((i for i in range(r, len(m)) if m[i][c] != 0), None)
        if pivot is None:
            continue
        m[r], m[pivot] = m[pivot], m[r]
        for i in range(len(m)):
            if i != r and m[i][c] != 0:
                f = m[i][c] / m[r][c]
                m[i] = [u - f * v for u, v in zip(m[i], m[r])]
        r += 1
        if r == len(m):
            break
    return r


def mobility(n, pins, contacts, links=None) -> int:
    """3(|S| − 1) − rank of the equations of the pairs inside S (all links by default)."""
    s = sorted(range(n) if links is None else links)
    eqs = rows(s, pins, contacts)
    return 3 * (len(s) - 1) - (rank(eqs) if eqs else 0)


def _rational(rng) -> Fraction:
    return Fraction(rng.randint(-10**6, 10**6), rng.randint(1, 10**6))


def generic_geometry(n, pins, meshes, rng):
    """Random points for every pin and contact, random normals: ``(pins, contacts)``.

    ``pins``: link tuples (a pin each, two or more links), ``meshes``: link pairs.
    """
    placed = [((_rational(rng), _rational(rng)), tuple(p)) for p in pins]
    contacts = [(a, b, (_rational(rng), _rational(rng)), (_rational(rng), _rational(rng))) for a, b in meshes]
    return placed, contacts


def train_geometry(n, axes, triples, rng, internal=None):
    """A gear train as built: a random point per axis; mesh (a, b) on carrier t touches on the line
    from a's axis with t to b's axis with t, between them for an external pair and beyond the
    first gear (the ring) for an internal one, its normal tilted by a random pressure angle
    (tangent of half the angle rational, so sines and cosines are rational)."""
    points = [(_rational(rng), _rational(rng)) for _ in axes]

    def axis_point(gear, carrier):
        return next(points[k] for k, axis in enumerate(axes) if gear in axis and carrier in axis)

    contacts = []
    for k, (a, b, t) in enumerate(triples):
        (xa, ya), (xb, yb) = axis_point(a, t), axis_point(b, t)
        inner = bool(internal and internal[k])
        lam = Fraction(rng.randint(1, 99), 100)
        if inner:  # the pinion b inside the ring a: the contact lies beyond b, seen from a
            lam = 1 + lam
        x, y = xa + lam * (xb - xa), ya + lam * (yb - ya)
        dx, dy = xb - xa, yb - ya
        h = Fraction(rng.randint(1, 9), 10)  # tan(φ/2): cos φ = (1 − h²)/(1 + h²), sin φ = 2h/(1 + h²)
        cos, sin = (1 - h * h) / (1 + h * h), 2 * h / (1 + h * h)
        nx, ny = dx * cos - dy * sin, dx * sin + dy * cos  # the line of centres turned by φ
        contacts.append((a, b, (x, y), (nx, ny)))
    return [(p, tuple(axis)) for p, axis in zip(points, axes)], contacts


def subsets_verdict(n, pins, contacts, least: int = 1):
    """Over every proper set S of two links or more: (ok, worst S, its mobility) — ok when every
    S keeps ``least`` freedoms (1: no rigid sub-chain; 0: rigid ones allowed, as in a truss) with
    independent pairs (no over-constrained sub-chain)."""
    worst, low, ok = None, None, True
    for size in range(2, n):
        for s in combinations(range(n), size):
            eqs = rows(s, pins, contacts)
            r = rank(eqs) if eqs else 0
            m = 3 * (size - 1) - r
            if m < least or r < len(eqs):
                ok = False
            if low is None or m < low:
                worst, low = s, m
    return ok, worst, low
