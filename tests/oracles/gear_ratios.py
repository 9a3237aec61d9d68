"""Independent speed ratios of gear trains: the Willis equations solved in exact rationals
(a test oracle: plain Python, no code from ``synth``).

For a mesh of gears a, b on carrier t: z_a (ω_a − ω_t) = −z_b (ω_b − ω_t) for an external pair,
+z_b (ω_b − ω_t) for an internal pair whose first gear a is the ring.  With the frame at rest and
the input at speed 1, Gauss–Jordan elimination over fractions gives every speed.

Example
-------
>>> # simple planetary: ring 0 fixed, sun 1 in, carrier 2 out, planet 3 (72, 24, 24 teeth)
>>> speeds([(0, 3, 2, True), (1, 3, 2, False)], 4, {0: 72, 1: 24, 3: 24}, frame=0, driver=1)[2]
Fraction(1, 4)
"""

from __future__ import annotations

from fractions import Fraction

__all__ = ["speeds", "ratio"]


def _teeth(teeth: dict, gear: int, mate: int) -> int:
    """Teeth of ``gear``'s wheel meshing ``mate``: ``teeth[(gear, mate)]`` or ``teeth[gear]``."""
    return teeth[(gear, mate)] if (gear, mate) in teeth else teeth[gear]


def speeds(meshes, links: int, teeth: dict, frame: int, driver: int) -> dict:
    """Every link's angular speed (frame 0, driver 1); ``meshes`` as (a, b, carrier, internal).

    Raises ValueError when the equations leave a speed free or contradict each other.
    """
    unknown = [x for x in range(links) if x not in (frame, driver)]
    col = {x: i for i, x in enumerate(unknown)}
    rows = []
    for a, b, t, internal in meshes:
        za, zb = _teeth(teeth, a, b), _teeth(teeth, b, a)
        sb = -zb if internal else zb  # za(ωa − ωt) + sb(ωb − ωt) = 0
        coef = {a: Fraction(za), b: Fraction(sb)}
        coef[t] = coef.get(t, 0) - za - sb
        row = [Fraction(0)] * (len(unknown) + 1)
        for x, c in coef.items():
            if x == frame:
                continue
            if x == driver:
                row[-1] -= c  # moved to the right-hand side, ω_driver = 1
            else:
                row[col[x]] += c
        rows.append(row)
    pivots = []
    r = 0
    for c in range(len(unknown)):
        pick = next((i for i in range(r, len(rows)) if rows[i][c] != 0), None)
        if pick is None:
            raise ValueError(f"the speed of link {unknown[c]} is not fixed by the input")
        rows[r], rows[pick] = rows[pick], rows[r]
        rows[r] = [v / rows[r][c] for v in rows[r]]
        for i in range(len(rows)):
            if i != r and rows[i][c] != 0:
                f = rows[i][c]
                rows[i] = [v - f * w for v, w in zip(rows[i], rows[r])]
        pivots.append(c)
        r += 1
    if any(row[-1] != 0 for row in rows[r:]):
        raise ValueError("the equations contradict each other: the train is locked")
    out = {frame: Fraction(0), driver: Fraction(1)}
    for i, c in enumerate(pivots):
        out[unknown[c]] = rows[i][-1]
    return out


def ratio(meshes, links: int, teeth: dict, frame: int, driver: int, driven: int) -> Fraction:
    """i = ω_driver / ω_driven."""
    return 1 / speeds(meshes, links, teeth, frame, driver)[driven]
