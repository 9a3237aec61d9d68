"""Whether a designed gear train can be built: its carriers' axes placed in the plane from the
tooth numbers, wheels of one kind, planets that clear each other and assemble (a test oracle:
plain Python, no code from ``synth``).

A train is given as the oracle of ratios takes it: ``meshes`` as (a, b, carrier, internal) with a
the ring of an internal mesh, ``axes`` as sets of links, ``teeth`` by link or by (link, mate).
Each gear turns on its mesh's carrier about the axis the two share (a gear that shares none, a
floating sun, about the carrier's axis with the frame, or else the carrier's first axis).  The
centre distance of a mesh in half modules is z_a + z_b (external) or z_ring − z_pinion
(internal).  A carrier's axes are *placed*, one after another, at the distances its meshes ask:
the first at the origin, the second on the x axis, each next one where two circles about placed
axes cross (both crossings tried); every distance is then measured.

Example
-------
>>> axes = [{0, 1, 2}, {2, 3}]                          # ring 0, sun 1, carrier 2, planet 3
>>> problems([(0, 3, 2, True), (1, 3, 2, False)], axes, {0: 72, 1: 24, 3: 24}, frame=0, planets=3)
[]
>>> problems([(0, 3, 2, True), (1, 3, 2, False)], axes, {0: 70, 1: 24, 3: 24}, frame=0)
['carrier 2 holds two meshes between one pair of axes at 46 and 48']
"""

from __future__ import annotations

import itertools
import math

__all__ = ["problems", "centre_distance"]

RING_MARGIN = 10


def _teeth(teeth: dict, gear: int, mate: int) -> int:
    return teeth[(gear, mate)] if (gear, mate) in teeth else teeth[gear]


def centre_distance(mesh, teeth: dict) -> int:
    """2a/m of a mesh (a, b, carrier, internal)."""
    a, b, _, internal = mesh
    za, zb = _teeth(teeth, a, b), _teeth(teeth, b, a)
    return za - zb if internal else za + zb


def _axis(axes, gear: int, carrier: int, frame: int, other=None) -> frozenset:
    shared = [frozenset(x) for x in axes if gear in x and carrier in x]
    if shared:
        return shared[0]
    own = [frozenset(x) for x in axes if carrier in x and frozenset(x) != other]
    with_frame = [x for x in own if frame in x]
    return (with_frame or own)[0]


def _placeable(distances: dict) -> bool:
    """Whether points can be put in the plane at the given distances (``{frozenset({P, Q}): d}``)."""
    points = sorted({p for pair in distances for p in pair}, key=repr)
    if len(points) <= 2:
        return True
    for order in itertools.permutations(points):
        for signs in itertools.product((1, -1), repeat=len(points)):
            place = {order[0]: (0.0, 0.0)}
            ok = True
            for k, p in enumerate(order[1:], start=1):
                known = [(q, distances[frozenset((p, q))]) for q in order[:k] if frozenset((p, q)) in distances]
                if not known:
                    place[p] = (1e6 * k, 0.0)  # unconstrained: far away on its own
                elif len(known) == 1:  # one distance: along the x axis (enough for trees and triangles)
                    (q, d), = known
                    place[p] = (place[q][0] + d, place[q][1])
                else:  # where the circles about the first two placed neighbours cross
                    (q1, d1), (q2, d2) = known[:2]
                    (x1, y1), (x2, y2) = place[q1], place[q2]
                    base = math.dist((x1, y1), (x2, y2))
                    along = (d1 * d1 - d2 * d2 + base * base) / (2 * base) if base else math.nan
                    h2 = d1 * d1 - along * along
                    if not h2 >= -1e-9:
                        ok = False
                        break
                    h = math.sqrt(max(h2, 0.0)) * signs[k]
                    ux, uy = (x2 - x1) / base, (y2 - y1) / base
                    place[p] = (x1 + along * ux - h * uy, y1 + along * uy + h * ux)
            if ok and all(abs(math.dist(place[p], place[q]) - d) < 1e-6 for (p, q), d in
                          ((tuple(pair), d) for pair, d in distances.items())):
                return True
    return False


def problems(meshes, axes, teeth: dict, *, frame: int, planets: int | None = None) -> list[str]:
    """What keeps the train from being built (an empty list when nothing does)."""
    found = []
    kind_of: dict = {}  # wheel -> set of "ring" / "external"
    for a, b, t, internal in meshes:
        for gear, mate, ring in ((a, b, internal), (b, a, False)):
            wheel = (gear, mate) if (gear, mate) in teeth else gear
            kind_of.setdefault(wheel, set()).add("ring" if ring else "external")
        if internal and _teeth(teeth, a, b) < _teeth(teeth, b, a) + RING_MARGIN:
            found.append(f"ring {a} is less than {RING_MARGIN} teeth above its pinion {b}")
    for wheel, kinds in kind_of.items():
        if len(kinds) > 1:
            found.append(f"wheel {wheel} is both a ring and an external gear")
    per_carrier: dict = {}
    for mesh in meshes:
        a, b, t, _ = mesh
        axis_b = _axis(axes, b, t, frame)
        axis_a = _axis(axes, a, t, frame, other=axis_b)
        per_carrier.setdefault(t, []).append((frozenset((axis_a, axis_b)), centre_distance(mesh, teeth), mesh))
    for t, items in per_carrier.items():
        distances: dict = {}
        for pair, d, _ in items:
            if distances.setdefault(pair, d) != d:
                found.append(f"carrier {t} holds two meshes between one pair of axes at {distances[pair]} and {d}")
        if not _placeable(distances):
            found.append(f"carrier {t} cannot hold its axes at the distances {', '.join(map(str, sorted(distances.values())))}")
    if planets and planets >= 2:
        for t, items in per_carrier.items():
            by_planet: dict = {}  # a planet: a gear on an axis of the carrier meshing two gears on one other axis
            for pair, d, (a, b, _, internal) in items:
                for planet, central in ((a, b), (b, a)):
                    if internal and planet == a:
                        continue  # a ring is no planet
                    shared = [frozenset(x) for x in axes if planet in x and t in x]
                    if shared and len(pair) == 2:
                        (other,) = pair - {shared[0]}
                        by_planet.setdefault((planet, shared[0], other), []).append((central, d, (a, b, t, internal)))
            for (planet, _, _), mates in by_planet.items():
                if len(mates) < 2:
                    continue
                for central, d, mesh in mates:  # neighbours 2a·sin(π/k) apart, tips m(z + 2) across
                    zp = _teeth(teeth, planet, central)
                    if not d * math.sin(math.pi / planets) > zp + 2 + 1e-9:
                        found.append(f"{planets} planets {planet} of {zp} teeth touch at centre distance {d}")
                (c1, _, m1), (c2, _, m2) = mates[:2]
                sign = (-1 if m1[3] else 1) * (-1 if m2[3] else 1)
                z1, z2 = _teeth(teeth, c1, planet), _teeth(teeth, c2, planet)
                if (z1 - sign * z2) % planets:  # simple planets: (z_sun + z_ring)/k whole
                    found.append(f"{planets} planets do not assemble between {c1} and {c2}")
    return found
