"""Drawings of chains and mechanisms as a designer draws them (matplotlib, Agg).

Each link is a polygon through its joints (binary links as bars, ternary as
triangles, …), joints are small circles, a multiple joint carries a ring and its
multiplicity, the fixed link of a mechanism is hatched, an input link gets an
arrow and a prismatic pair is a block on a bar (a cylinder: a dark barrel).  Layout: when the
link–joint incidence graph is planar and 2-connected (single-joint links aside), a Tutte (barycentric) embedding of the joint graph with the longest loop
outside, in which every link polygon is a convex face and nothing crosses; then joints move
one at a time to open up corners under 30° and crowded joints, never adding a crossing.
Other chains start from networkx's planar or Kamada–Kawai layout.  Everything is deterministic.

Example
-------
>>> import tempfile, os
>>> from synth import Chain
>>> out = os.path.join(tempfile.mkdtemp(), "watt.svg")
>>> draw_one(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), out)
>>> os.path.getsize(out) > 0
True
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .structure.chain import Chain, Mechanism
from .structure.joints import MESH, PRISMATIC, REVOLUTE
from .errors import InvalidOption, SynthesisError, option

__all__ = ["Layout", "layout", "expand", "draw_one", "draw_sheet", "svg", "svg_inline", "DrawError"]

_FORMATS = (".svg", ".png", ".pdf")


class DrawError(SynthesisError):
    """A drawing cannot be written (unknown format, unwritable file)."""


class Layout:
    """Joint positions of a chain and, per link, its joints in polygon order.

    Attributes
    ----------
    joints : ndarray, shape (J, 2)
        Position of each joint (index as in ``chain.joints``), scaled into [-1, 1]².
    polygons : list of list of int
        For each link, its joints in the order the polygon visits them.
    planar : bool
        Whether the drawing is free of crossings by construction.
    """

    def __init__(self, joints: np.ndarray, polygons: list[list[int]], planar: bool):
        self.joints = joints
        self.polygons = polygons
        self.planar = planar

    def segments(self) -> list[tuple[int, int, int]]:
        """Drawn sides (link, joint a, joint b)."""
        out = []
        for link, poly in enumerate(self.polygons):
            if len(poly) == 2:
                out.append((link, poly[0], poly[1]))
            elif len(poly) > 2:  # a single-joint link's free end is not a side between joints
                out += [(link, poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly))]
        return out


# ------------------------------------------------------------------- layout
def _incidence(chain: Chain):
    import networkx as nx

    g = nx.Graph()
    g.add_nodes_from(("L", i) for i in range(chain.links))
    for k, joint in enumerate(chain.joints):
        g.add_edges_from((("J", k), ("L", x)) for x in joint)
    return g


def _faces(embedding) -> list[list]:
    seen, faces = set(), []
    for u, v in sorted(embedding.edges()):
        if (u, v) in seen:
            continue
        face = embedding.traverse_face(u, v, mark_half_edges=seen)
        faces.append(face)
    return faces


def _tutte(polygons: list[list[int]], loops: list[list[int]], outer: list[int], joints: int) -> np.ndarray:
    """Barycentric embedding of the *joint graph* (joints as vertices, link sides as edges).

    The outer loop's joints sit on a regular polygon; every other joint is the mean of its
    neighbours along link sides, and a virtual centre in every inner loop pulls on that loop's
    joints (so that strings meeting at two joints only do not collapse onto one line).  Every
    link polygon is a face of this graph, so it comes out convex (Tutte's theorem) and the drawing
    has no crossings.
    """
    pos = np.zeros((joints, 2))
    for i, k in enumerate(outer):
        angle = math.pi / 2 + 2 * math.pi * i / len(outer)
        pos[k] = (math.cos(angle), math.sin(angle))
    placed = {k for poly in polygons for k in poly}  # a joint of crossing bars only is placed after
    free = [k for k in range(joints) if k not in set(outer) and k in placed]
    centres = [sorted(set(loop)) for loop in loops if loop is not outer and len(set(loop)) >= 3]
    index = {k: i for i, k in enumerate(free)}
    size = len(free) + len(centres)
    if not free:
        return pos
    a = np.zeros((size, size))
    b = np.zeros((size, 2))

    def pull(i: int, k: int, weight: float) -> None:  # row i of the system is drawn towards joint k
        a[i, i] += weight
        if k in index:
            a[i, index[k]] -= weight
        else:
            b[i] += weight * pos[k]

    for x, y in _sides(polygons):
        for u, w in ((x, y), (y, x)):
            if u in index:
                pull(index[u], w, 1.0)
    for c, loop in enumerate(centres):
        row = len(free) + c
        for k in loop:
            pull(row, k, 0.5)
            if k in index:
                a[index[k], index[k]] += 0.5
                a[index[k], row] -= 0.5
    sol = np.linalg.solve(a, b)
    pos[free] = sol[: len(free)]
    return pos


def _sides(polygons: list[list[int]]) -> list[tuple[int, int]]:
    """Drawn sides as joint pairs (a binary link is one side)."""
    return [(a, b) for _, a, b in Layout(np.zeros((0, 2)), polygons, True).segments()]


def _segment_arrays(polygons: list[list[int]]) -> tuple[np.ndarray, np.ndarray]:
    segs = Layout(np.zeros((0, 2)), polygons, True).segments()
    ends = np.array([(a, b) for _, a, b in segs], dtype=int).reshape(-1, 2)
    shared = (ends[:, None, 0] == ends[None, :, 0]) | (ends[:, None, 0] == ends[None, :, 1]) | \
             (ends[:, None, 1] == ends[None, :, 0]) | (ends[:, None, 1] == ends[None, :, 1])
    return ends, ~shared & np.triu(np.ones_like(shared), 1).astype(bool)


def _defects(pos: np.ndarray, polygons: list[list[int]], tol: float, cache=None) -> int:
    """Crossings of drawn sides, joints on foreign sides, joints inside foreign polygons (vectorised)."""
    ends, pairs = cache or _segment_arrays(polygons)
    a, b = pos[ends[:, 0]], pos[ends[:, 1]]

    def orient(p, q, r):
        return (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])

    eps = 1e-9
    d1 = orient(a[None, :], b[None, :], a[:, None])  # segment j against endpoint a of i
    d2 = orient(a[None, :], b[None, :], b[:, None])
    d3, d4 = d1.T, d2.T
    straddle = ((d1 > eps) & (d2 < -eps)) | ((d1 < -eps) & (d2 > eps))
    cross = straddle & (((d3 > eps) & (d4 < -eps)) | ((d3 < -eps) & (d4 > eps)))
    bad = 1000 * int((cross & pairs).sum())  # a crossing is never traded for a near miss
    ab = b - a
    t = np.clip(((pos[:, None, :] - a[None]) * ab[None]).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-12)[None], 0, 1)
    gap = np.linalg.norm(a[None] + t[..., None] * ab[None] - pos[:, None, :], axis=-1)
    own = (np.arange(len(pos))[:, None] == ends[None, :, 0]) | (np.arange(len(pos))[:, None] == ends[None, :, 1])
    bad += int(((gap < tol) & ~own).sum())
    for poly in polygons:
        if len(poly) >= 3:
            corners = pos[poly]
            c0, c1 = corners, np.roll(corners, -1, axis=0)
            py = pos[:, 1][:, None]
            span = (c0[None, :, 1] > py) != (c1[None, :, 1] > py)
            dy = np.where(c1[:, 1] == c0[:, 1], 1e-12, c1[:, 1] - c0[:, 1])
            x = c0[None, :, 0] + (py - c0[None, :, 1]) * (c1[None, :, 0] - c0[None, :, 0]) / dy[None]
            inside = ((span & (x > pos[:, 0][:, None])).sum(1) % 2).astype(bool)
            inside[poly] = False
            bad += 1000 * int(inside.sum())
    return bad


#: a link polygon's corners are kept between these angles (degrees): convex, no slivers
_LOW_ANGLE, _HIGH_ANGLE = 30.0, 160.0


def _corner_angles(pts: np.ndarray) -> np.ndarray:
    """Interior angles (degrees) of polygons given in order (``pts``: ``(..., corners, 2)``);
    a reflex corner has more than 180.

    >>> [round(a) for a in _corner_angles(np.array([[0, 0], [1, 0], [0, 1.0]]))]
    [90, 45, 45]
    """
    before, after = np.roll(pts, 1, axis=-2), np.roll(pts, -1, axis=-2)
    u, w = before - pts, after - pts
    cross = u[..., 0] * w[..., 1] - u[..., 1] * w[..., 0]
    angle = np.degrees(np.arctan2(np.abs(cross), (u * w).sum(-1)))
    x, y = pts[..., 0], pts[..., 1]
    area = (x * np.roll(y, -1, axis=-1) - np.roll(x, -1, axis=-1) * y).sum(-1, keepdims=True)
    reflex = cross * np.where(area >= 0, 1, -1) > 0  # turning against the polygon's orientation
    return np.where(reflex, 360 - angle, angle)


def _gaps(points: np.ndarray, a: np.ndarray, ab: np.ndarray) -> np.ndarray:
    """Distances from ``points`` to the sides ``a + t·ab`` (0 ≤ t ≤ 1), broadcast over leading axes."""
    t = np.clip(((points - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-12), 0, 1)
    return np.linalg.norm(a + t[..., None] * ab - points, axis=-1)


class _Shape:
    """What a good drawing keeps (the terms that depend on one joint): link corners between
    ``_LOW_ANGLE`` and ``_HIGH_ANGLE``, joints clear of foreign sides and of each other."""

    def __init__(self, pos: np.ndarray, polygons: list[list[int]]):
        n = len(pos)
        self.pos, self.ends = pos, np.array(_sides(polygons), dtype=int).reshape(-1, 2)
        self.corners = [[(np.array(p), p.index(k)) for p in polygons if len(p) >= 3 and k in p] for k in range(n)]
        self.at = np.zeros((n, len(self.ends)), dtype=bool)  # joint k is an end of side s
        self.at[self.ends[:, 0], np.arange(len(self.ends))] = True
        self.at[self.ends[:, 1], np.arange(len(self.ends))] = True
        spacing = 2.0 / math.sqrt(n)  # of joints spread evenly over the [-1, 1]² frame
        self.side_gap, self.joint_gap = 0.36 * spacing, 0.72 * spacing

    def cost(self, k: int, trials: np.ndarray) -> np.ndarray:
        """The cost of joint ``k`` at each of the positions ``trials`` (``(m, 2)``), the others fixed."""
        pos, ends = self.pos, self.ends
        m = len(trials)
        total = np.zeros(m)
        for poly, at in self.corners[k]:
            pts = np.repeat(pos[poly][None], m, axis=0)
            pts[:, at] = trials
            angles = _corner_angles(pts)
            total += ((np.maximum(0, _LOW_ANGLE - angles) ** 2).sum(1)
                      + (np.maximum(0, angles - _HIGH_ANGLE) ** 2).sum(1))
        others = np.arange(len(pos)) != k
        far, near = ~self.at[k], np.flatnonzero(self.at[k])
        a, b = pos[ends[:, 0]], pos[ends[:, 1]]
        # joint k against the sides not at k ...
        side = [_gaps(trials[:, None], a[far][None], (b - a)[far][None]).reshape(m, -1)]
        if len(near):  # ... and every other joint against the sides at k, which move with it
            a_near = np.repeat(a[near][None], m, axis=0)
            b_near = np.repeat(b[near][None], m, axis=0)
            a_near[:, ends[near, 0] == k] = trials[:, None]
            b_near[:, ends[near, 1] == k] = trials[:, None]
            gap = _gaps(pos[others][None, :, None], a_near[:, None], (b_near - a_near)[:, None])
            side.append(gap[:, ~self.at[others][:, near]])
        side = np.concatenate(side, axis=1)
        joint = np.linalg.norm(pos[others][None] - trials[:, None], axis=-1)
        return total + ((40 * np.maximum(0, 1 - side / self.side_gap)) ** 2).sum(1) \
            + ((40 * np.maximum(0, 1 - joint / self.joint_gap)) ** 2).sum(1)


def _shape(pos: np.ndarray, polygons: list[list[int]], iterations: int = 80) -> np.ndarray:
    """Move one joint at a time to the best of 24 trial positions that lowers its cost
    (:class:`_Shape`), accepting a move only when it adds no crossing, touching or enclosed joint."""
    n = len(pos)
    if n < 3:
        return pos
    pos = pos.copy()
    shape = _Shape(pos, polygons)
    cache = _segment_arrays(polygons)
    tol = 0.12 * 2.0 / math.sqrt(n)
    current = _defects(pos, polygons, tol, cache)
    turns = np.linspace(0, 2 * math.pi, 12, endpoint=False)
    directions = np.stack([np.cos(turns), np.sin(turns)], axis=1)
    step = 0.1
    for _ in range(iterations):
        moved = False
        moves = np.concatenate([np.zeros((1, 2)), step * directions, step / 3 * directions])  # 0: stay
        for k in range(n):
            old = pos[k].copy()
            costs = shape.cost(k, old + moves)
            base = costs[0]
            if base == 0:
                continue
            for trial in 1 + np.argsort(costs[1:], kind="stable")[:4]:
                if costs[trial] >= base:
                    break
                pos[k] = old + moves[trial]
                defects = _defects(pos, polygons, tol, cache)
                if defects <= current:
                    current, moved = defects, True
                    break
                pos[k] = old
        step *= 0.95
        if not moved:
            break
    return pos


def _polygons(chain: Chain, g, embedding, pos: dict | None) -> list[list[int]]:
    """Each link's joints in polygon order: the embedding's rotation, else by angle about their centre."""
    polygons = []
    for i in range(chain.links):
        node = ("L", i)
        joints = [y[1] for y in g[node]]
        if embedding is not None and len(joints) >= 3:
            order = [y[1] for y in embedding.neighbors_cw_order(node)]
        elif pos is None:
            order = joints
        else:
            centre = np.mean([pos[("J", k)] for k in joints], axis=0)
            order = sorted(joints, key=lambda k: math.atan2(*(pos[("J", k)] - centre)[::-1]))
        polygons.append(order)
    return polygons


def _strings(chain: Chain, g) -> list[list[int]]:
    """The strings of binary links: maximal paths of binary links on simple joints, in order."""
    binary = {x for x in range(chain.links) if g.degree[("L", x)] == 2}
    seen, out = set(), []
    for start in sorted(binary):
        if start in seen:
            continue
        path, ends = [start], []
        seen.add(start)
        for joint in [j for _, j in g.edges(("L", start))]:
            current, at = start, joint
            while True:
                others = [y for _, y in g.edges(at) if y != ("L", current)]
                if len(others) != 1 or others[0][1] not in binary or others[0][1] in seen:
                    break
                current = others[0][1]
                seen.add(current)
                path.append(current) if ends else path.insert(0, current)
                at = next(j for _, j in g.edges(("L", current)) if j != at)
            ends.append(at)
        out.append(path)
    return out


def _crossing_strings(chain: Chain, g) -> list[list[list[int]]]:
    """Every way to set aside the fewest strings of binary links (one, else two) so that the rest
    of the incidence graph is planar and 2-connected: what a designer lets cross the drawing.
    Empty where there is none (every link has three joints or more, as in K3,3)."""
    import itertools

    import networkx as nx

    strings = _strings(chain, g)
    for size in (1, 2):
        found = []
        for chosen in itertools.combinations(strings, size):
            links = {("L", x) for string in chosen for x in string}
            rest = g.copy()
            rest.remove_nodes_from(links)
            rest.remove_nodes_from([n for n in list(rest) if rest.degree[n] == 0])
            core = rest.subgraph(n for n in rest if rest.degree[n] >= 2)
            if (nx.check_planarity(rest)[0] and core.number_of_nodes() > 2 and nx.is_biconnected(core)
                    and all(("L", x) in core for x in range(chain.links) if ("L", x) not in links
                            and g.degree[("L", x)] >= 2)):
                found.append(list(chosen))
        if found:
            return found
    return []


def _place_strings(pos: np.ndarray, chain: Chain, strings: list[list[int]]) -> np.ndarray:
    """Joints inside crossing strings evenly on the straight line between the string's ends."""
    pos = pos.copy()
    for string in strings:
        joints = [k for k, j in enumerate(chain.joints) if any(x in j for x in string)]
        inner = [k for k in joints if all(x in string for x in chain.joints[k])]
        ends = [k for k in joints if k not in inner]
        if not inner or len(ends) != 2:
            continue
        # the joints in the order of the string's links
        order, at = [ends[0]], ends[0]
        for link in (string if ends[0] in [k for k, j in enumerate(chain.joints) if string[0] in j] else string[::-1]):
            at = next(k for k, j in enumerate(chain.joints) if link in j and k != at)
            order.append(at)
        a, b = pos[order[0]], pos[order[-1]]
        for i, k in enumerate(order[1:-1], start=1):
            pos[k] = a + (b - a) * i / (len(order) - 1)
    return pos


def _tutte_drawing(chain: Chain, g, strings: list[list[int]]):
    """The Tutte drawing of the chain without the links of ``strings`` (placed after, straight
    across), over the candidate outer loops: ``(score, joints, polygons, polygons drawn by Tutte,
    strings)`` of the best.  Without strings the first loop drawn without a defect wins; with
    them (crossings are then unavoidable) the fewest crossings, then the largest least spacing
    of joints."""
    import networkx as nx

    crossing = {x for string in strings for x in string}
    drawn = g.copy()
    drawn.remove_nodes_from(("L", x) for x in crossing)
    drawn.remove_nodes_from([x for x in list(drawn) if drawn.degree[x] == 0])  # joints inside those strings
    core = drawn.subgraph(x for x in drawn if not (x[0] == "L" and drawn.degree[x] == 1))  # without free ends
    _, embedding = nx.check_planarity(core)
    polygons = _polygons(chain, g, embedding, None)
    inner = [[] if link in crossing else poly for link, poly in enumerate(polygons)]  # the planar part
    loops = [list(dict.fromkeys(x[1] for x in face if x[0] == "J")) for face in _faces(embedding)]
    # outside: the loop that carries most single-joint links (free ends point out), then the
    # longest (as designers draw); the next one where that degenerates
    hanging = {k for k, j in enumerate(chain.joints) if any(g.degree[("L", x)] == 1 for x in j)}
    order = sorted(loops, key=lambda loop: (-len(hanging.intersection(loop)), -len(loop), sorted(loop)))
    best = None
    for outer in order[:10 if strings else 6]:
        trial = _normalise(_place_strings(_tutte(inner, loops, outer, len(chain.joints)), chain, strings))
        score = _defects(trial, polygons, 0.02)
        if strings:
            score = _roominess(trial, polygons)
        if best is None or score < best[0]:
            best = (score, trial, polygons, inner, strings)
        if score == 0:
            break
    return best


def _roominess(joints: np.ndarray, polygons: list[list[int]]) -> tuple[int, float]:
    """How a drawing with crossings is ranked (lower is better): its crossings, then minus the
    least distance between two joints."""
    gaps = np.linalg.norm(joints[:, None] - joints[None], axis=-1) + 9 * np.eye(len(joints))
    return _defects(joints, polygons, 0.02) // 1000, -float(gaps.min())


def _normalise(pos: np.ndarray) -> np.ndarray:
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    centre, span = (lo + hi) / 2, max(float((hi - lo).max()), 1e-9)
    return (pos - centre) * (2.0 / span)


def layout(chain: Chain) -> Layout:
    """Positions of the joints and the polygon order of each link's joints.

    A chain whose links and joints form a planar, 2-connected incidence graph (single-joint
    links aside) is drawn from a Tutte embedding of its joint graph with the longest loop
    outside: convex link polygons, no crossings.  A non-planar chain is drawn the way designers
    draw one: the fewest strings of binary links are set aside until the rest is planar, the rest
    is drawn so, and the strings set aside cross it as straight bars (so link polygons never
    overlap).  Other chains
    start from networkx's planar or Kamada–Kawai layout.  Then :func:`_shape` opens up slivers and
    crowded joints without adding a crossing.

    >>> lay = layout(Chain.parse("0-1 1-2 2-3 3-0"))
    >>> lay.joints.shape, lay.planar, [len(p) for p in lay.polygons]
    ((4, 2), True, [2, 2, 2, 2])
    """
    import networkx as nx

    g = _incidence(chain)
    planar, embedding = nx.check_planarity(g)
    if not planar:
        choices = _crossing_strings(chain, g)
        if choices:  # the crossing strings are drawn over a planar drawing of the rest: the roomiest
            shaped = []
            for _, joints, polygons, inner, strings in sorted((_tutte_drawing(chain, g, strings) for strings in choices),
                                                              key=lambda found: found[0])[:3]:
                joints = _normalise(_place_strings(_shape(joints, inner), chain, strings))  # no move trades crossings
                shaped.append((_roominess(joints, polygons), joints, polygons))
            _, joints, polygons = min(shaped, key=lambda found: found[0])
            return Layout(joints, polygons, False)
    best = None
    core = g.subgraph(x for x in g if not (x[0] == "L" and g.degree[x] == 1))  # without single-joint links
    if planar and core.number_of_nodes() > 2 and nx.is_connected(core):
        _, embedding = nx.check_planarity(core)  # (the force layout below orders polygons by it too)
        best = _tutte_drawing(chain, g, [])[:3]
    if best is None or best[0] > 0:  # not 2-connected (fractionated, open): try a force layout too
        pos = nx.kamada_kawai_layout(g, pos=nx.planar_layout(g) if planar else None)
        polys = _polygons(chain, g, embedding if planar else None, pos)
        trial = _normalise(np.array([pos[("J", k)] for k in range(len(chain.joints))], dtype=float))
        score = _defects(trial, polys, 0.02)
        if best is None or score < best[0]:
            best = (score, trial, polys)
    _, joints, polygons = best
    joints = _normalise(_shape(joints, polygons))
    return Layout(joints, polygons, planar and _defects(joints, polygons, 1e-3) == 0)


# ------------------------------------------------------------------ drawing
_FILL = "#dbe6f4"
_EDGE = "#1f3a5f"
_BAR = "#1f3a5f"
_MULTI = "#c0392b"


class _Marks:
    """Where everything of a drawing goes, shared by the matplotlib and the inline SVG drawings:
    the layout, the joint radius ``r``, the free end of each single-joint link, the place of
    each multiple joint's multiplicity number and of each link's number, the two pitch circles
    of each gear mesh, and the half-width ``reach`` of the square the drawing fills."""

    def __init__(self, chain: Chain):
        lay = layout(chain)
        pos = lay.joints
        nj = len(pos)
        gaps = [float(np.linalg.norm(pos[a] - pos[b])) for a in range(nj) for b in range(a + 1, nj)]
        self.chain, self.lay, self.pos = chain, lay, pos
        self.r = r = min(0.07, 0.28 * min(gaps, default=1.0))
        self.free_ends = _free_ends(pos, lay.polygons, length=max(0.35, 6 * r))
        self.sides = sides = _sides(lay.polygons)
        self.numbers = {}
        for k, joint in enumerate(chain.joints):
            if len(joint) > 2:  # in the widest free angle at the joint, free-end bars counted
                bars = [math.atan2(*(end - pos[k])[::-1]) for link, end in self.free_ends.items()
                        if lay.polygons[link] == [k]]
                turn, _ = _widest_gap(pos, sides, k, bars)
                self.numbers[k] = pos[k] + 3.2 * r * np.array([math.cos(turn), math.sin(turn)])
        self.labels = {}
        for link, poly in enumerate(lay.polygons):
            points = [pos[j] for j in poly] + ([self.free_ends[link]] if len(poly) == 1 else [])
            self.labels[link] = np.mean(points, axis=0)
        self.meshes = {k: _pitch_circles(chain, lay, k, r) for k, kind in enumerate(chain.kinds) if kind == MESH}
        self.reach = max([1.25] + [float(np.abs(end).max()) + 2 * r for end in self.free_ends.values()]
                         + [float(np.abs(n).max()) + 2 * r for n in self.numbers.values()])


    def ground(self, k: int) -> np.ndarray:
        """The unit direction of the fixed-pivot sign at joint ``k`` of the frame: into the widest
        free angle there, clear of the sides, free-end bars and multiplicity number drawn at it."""
        pos = self.pos
        also = [math.atan2(*(end - pos[k])[::-1]) for link, end in self.free_ends.items()
                if self.lay.polygons[link] == [k]]
        if k in self.numbers:
            also.append(math.atan2(*(self.numbers[k] - pos[k])[::-1]))
        turn, _ = _widest_gap(pos, self.sides, k, also)
        return np.array([math.cos(turn), math.sin(turn)])


def _pitch_circles(chain: Chain, lay: Layout, k: int, r: float) -> list[tuple[np.ndarray, float]]:
    """A gear mesh: two pitch circles touching at the joint, each on the side of its gear (the
    centre of its link's joints), as a designer sketches two gears in mesh."""
    pos = lay.joints
    a, b = chain.joints[k]
    toward = np.mean([pos[j] for j in lay.polygons[b]], axis=0) - np.mean([pos[j] for j in lay.polygons[a]], axis=0)
    if np.linalg.norm(toward) < 1e-9:
        toward = np.array([1.0, 0.0])
    u = toward / np.linalg.norm(toward)
    radius = 1.25 * r
    return [(pos[k] - u * radius, radius), (pos[k] + u * radius, radius)]


#: the links of a heterogeneous chain's base, by its loops' class (the other links keep the usual colours)
_CLASS_COLOURS = {2: "#7b3294", 3: "#1b9e77", 4: "#b8860b", 5: "#e66101", 6: "#e7298a"}


def _class_keys(chain: Chain, counted: bool = True) -> list:
    """Which colour is which loop class in a heterogeneous chain's drawing (with the number of
    loops of each class where ``counted``: one chain; a sheet's captions give each chain's)."""
    from matplotlib.lines import Line2D

    loops = chain.loop_classes

    def said(x, other=""):
        return f"h = {x}: {loops[x]} {other}loop{'s' * (loops[x] > 1)}" if counted else f"h = {x}: {other or 'base '}loops"

    return [Line2D([0], [0], color=_CLASS_COLOURS[x], lw=3, label=said(x)) for x in sorted(set(chain.classes) - {chain.h})
            ] + [Line2D([0], [0], color=_BAR, lw=3, label=said(chain.h, "other "))]


def _draw(ax, item: Chain | Mechanism, *, labels: bool = False, caption: str | None = None,
          legend: bool = True) -> None:
    from matplotlib.patches import Circle, FancyArrowPatch, Polygon

    mech = item if isinstance(item, Mechanism) else None
    chain = item.chain if mech else item
    marks = _Marks(chain)
    lay, pos, r = marks.lay, marks.pos, marks.r
    lw = 2.2
    for link, poly in enumerate(lay.polygons):
        pts = pos[poly]
        frame = mech is not None and link == mech.frame
        based = chain.classes is not None and chain.classes[link] != chain.h
        bar = _CLASS_COLOURS[chain.classes[link]] if based else _BAR
        edge = _CLASS_COLOURS[chain.classes[link]] if based else _EDGE
        if len(poly) == 1:  # a single-joint link (an arm's base or gripper): a bar with a free end
            end = marks.free_ends[link]
            pts = np.array([pos[poly[0]], end])
            ax.plot(pts[:, 0], pts[:, 1], color=_BAR, lw=lw, solid_capstyle="butt", zorder=2, gid=f"bar{link}")
            ax.add_patch(Polygon([end + (-r, -r), end + (r, -r), end + (r, r), end + (-r, r)], closed=True,
                                 facecolor=_EDGE, edgecolor=_EDGE, hatch="////" if frame else None, zorder=3,
                                 gid=f"end{link}"))
        elif len(poly) == 2:
            if frame:
                a, b = pts
                d = b - a
                nrm = np.array([-d[1], d[0]]) / (np.linalg.norm(d) + 1e-12) * r * 0.9
                ax.add_patch(Polygon([a + nrm, b + nrm, b - nrm, a - nrm], closed=True, facecolor="white",
                                     edgecolor=_EDGE, hatch="////", lw=1.2, zorder=2))
            else:
                ax.plot(pts[:, 0], pts[:, 1], color=bar, lw=lw * (1.4 if based else 1), solid_capstyle="round",
                        zorder=2, gid=f"bar{link}")
        else:
            ax.add_patch(Polygon(pts, closed=True, facecolor="white" if frame else _FILL, edgecolor=edge,
                                 hatch="////" if frame else None, lw=2.4 if based else 1.4, joinstyle="round",
                                 zorder=1))
        if labels:
            x, y = marks.labels[link]
            ax.text(x, y, str(link), fontsize=7, color="#555555", ha="center", va="center", zorder=5,
                    gid=f"label{link}", bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8))
    for k, joint in enumerate(chain.joints):
        x, y = pos[k]
        kind = chain.kinds[k]
        if len(joint) > 2:  # a ring, and the multiplicity in the widest free angle at the joint
            ax.add_patch(Circle((x, y), r * 1.75, facecolor="white", edgecolor=_MULTI, lw=1.6, zorder=3))
            nx_, ny_ = marks.numbers[k]
            ax.text(nx_, ny_, str(len(joint)), color=_MULTI, fontsize=7, fontweight="bold", ha="center",
                    va="center", zorder=6, gid=f"multiplicity{k}")
        if kind == PRISMATIC:
            corners, cylinder = _slider(chain, lay, k, r)
            ax.add_patch(Polygon(corners, closed=True, facecolor=PRISMATIC.stroke if cylinder else "white", edgecolor=PRISMATIC.stroke,
                                 lw=1.2, zorder=4, gid=f"{'cylinder' if cylinder else 'slider'}{k}"))
        elif kind == MESH:
            for centre, radius in marks.meshes[k]:
                ax.add_patch(Circle(centre, radius, facecolor="white", edgecolor=MESH.stroke, lw=1.4, zorder=4,
                                    gid=f"mesh{k}"))
        else:
            ax.add_patch(Circle((x, y), r, facecolor="white", edgecolor=REVOLUTE.stroke, lw=1.2, zorder=4, gid=f"pin{k}"))
    if mech is not None:  # the frame's pivots as a designer marks them: a support on a hatched base at each
        for k, joint in enumerate(chain.joints):  # (a short fixed link's own hatching hides under its pins)
            if mech.frame in joint:
                _fixed_pivot(ax, pos[k], marks.ground(k), r, gid=f"ground{k}")
    if mech is not None and mech.input_link is not None:
        k = next(i for i, j in enumerate(chain.joints) if mech.frame in j and mech.input_link in j)
        x, y = pos[k]
        ax.add_patch(FancyArrowPatch((x + 2.6 * r, y), (x, y + 2.6 * r), connectionstyle="arc3,rad=0.5",
                                     arrowstyle="-|>", mutation_scale=9, color=_MULTI, lw=1.2, zorder=6))
    ax.set_aspect("equal")
    ax.set_xlim(-marks.reach, marks.reach)
    ax.set_ylim(-marks.reach, marks.reach)
    ax.axis("off")
    if chain.classes is not None and legend:
        ax.legend(handles=_class_keys(chain), loc="upper left", fontsize=6, frameon=False, handlelength=1.6,
                  borderaxespad=0)
    if caption:
        if "\n" in caption:  # lines of notes grow downwards, into the room the sheet keeps for them
            ax.set_title(caption, fontsize=8, pad=0, y=-0.02, va="top")
        else:
            ax.set_title(caption, fontsize=8, pad=2, y=-0.08)


def _fixed_pivot(ax, at: np.ndarray, direction: np.ndarray, r: float, gid: str) -> None:
    """A fixed pivot's sign at ``at``: two struts from the pin to a base line across ``direction``,
    hatched beyond it (under the pin, over a multiple joint's ring)."""
    from matplotlib.patches import Polygon

    across = np.array([-direction[1], direction[0]])
    base, half, depth = at + direction * 2.4 * r, 1.5 * r, 0.8 * r
    ax.add_patch(Polygon([at, base + across * half, base - across * half], closed=True, facecolor="white",
                         edgecolor=_EDGE, lw=1.2, zorder=3.5, gid=gid))
    ax.add_patch(Polygon([base + across * half * 1.4, base - across * half * 1.4,
                          base - across * half * 1.4 + direction * depth, base + across * half * 1.4 + direction * depth],
                         closed=True, facecolor="white", edgecolor=_EDGE, hatch="////", lw=1.2, zorder=3.5))


def _slider(chain: Chain, lay: Layout, k: int, r: float) -> tuple[list[np.ndarray], bool]:
    """A prismatic pair: the corners of a block sliding along a side of its first link at the
    joint, and whether it is a cylinder (both links binary: a cylinder and its rod), drawn as a
    longer, darker barrel along the cylinder's bar."""
    pos, guide = lay.joints, lay.polygons[chain.joints[k][0]]
    other = next((j for j in guide if j != k), None)
    direction = pos[other] - pos[k] if other is not None else np.array([1.0, 0.0])
    length = float(np.linalg.norm(direction))
    along = direction / max(length, 1e-12)
    across = np.array([-along[1], along[0]])
    cylinder = all(len(lay.polygons[x]) == 2 for x in chain.joints[k])
    if cylinder:  # from the joint towards the cylinder's far end, leaving room for a block there
        reach = 0.4 if other is not None and chain.kinds[other] == PRISMATIC else 0.55
        start, end, half = pos[k], pos[k] + along * reach * length, 1.3 * r
    else:
        start, end, half = pos[k] - along * 1.6 * r, pos[k] + along * 1.6 * r, 1.0 * r
    return [start + across * half, end + across * half, end - across * half, start - across * half], cylinder


def _widest_gap(pos: np.ndarray, sides: list[tuple[int, int]], joint: int, also=()) -> tuple[float, float]:
    """Direction (radians) of the middle of the widest free angle at a joint between the sides
    drawn there (and the directions ``also``), and that angle; away from the drawing's centre
    where nothing meets the joint."""
    turns = sorted([math.atan2(*(pos[b if a == joint else a] - pos[joint])[::-1])
                    for a, b in sides if joint in (a, b)] + list(also))
    if not turns:
        away = pos[joint] - pos.mean(axis=0)
        return (math.atan2(away[1], away[0]) if np.linalg.norm(away) > 1e-9 else -math.pi / 2), math.pi
    gaps = [((turns[(i + 1) % len(turns)] - t) % (2 * math.pi)) or 2 * math.pi for i, t in enumerate(turns)]
    i = int(np.argmax(gaps))
    return turns[i] + gaps[i] / 2, gaps[i]


def _free_ends(pos: np.ndarray, polygons: list[list[int]], length: float) -> dict[int, np.ndarray]:
    """Where each single-joint link ends: into the widest free angle at its joint, fanned out
    where several hang on one joint."""
    hanging: dict[int, list[int]] = {}
    for link, poly in enumerate(polygons):
        if len(poly) == 1:
            hanging.setdefault(poly[0], []).append(link)
    sides = _sides(polygons)
    ends = {}
    for joint, links in hanging.items():
        base, width = _widest_gap(pos, sides, joint)
        spread = min(1.0, 0.7 * width / len(links))  # two grippers on one joint open like a pair of jaws
        for i, link in enumerate(links):
            angle = base + (i - (len(links) - 1) / 2) * spread
            ends[link] = pos[joint] + length * np.array([math.cos(angle), math.sin(angle)])
    return ends


def expand(chains: Sequence[Chain], *, mechanisms: bool = False, input_link: bool = False) -> list:
    """The items of a sheet: the chains themselves, or every mechanism of each."""
    if not mechanisms:
        return list(chains)
    from .synthesis.type_synthesis import mechanisms_of

    return [m for c in chains for m in mechanisms_of(c, input_link=input_link)]


def _check_out(out: str | Path) -> Path:
    path = Path(out)
    if path.suffix.lower() not in _FORMATS:
        raise InvalidOption(f"draw writes {', '.join(_FORMATS)} files, not {path.suffix or 'a file without suffix'!r}")
    if not path.parent.exists():
        raise DrawError(f"cannot write {path}: the directory {path.parent} does not exist")
    return path


def _save(fig, path: Path, dpi: int) -> None:
    kwargs = {"metadata": {"Date": None}} if path.suffix.lower() == ".svg" else {}
    import matplotlib

    try:
        # stable SVG ids (same input, same file) and text kept as text (searchable, selectable)
        with matplotlib.rc_context({"svg.hashsalt": "mechsynth", "svg.fonttype": "none"}):
            fig.savefig(path, dpi=dpi, bbox_inches="tight", **kwargs)
        if path.suffix.lower() == ".png":  # a 64-colour palette: line art, a third of the size
            from PIL import Image

            with Image.open(path) as image:
                small = image.convert("RGB").quantize(colors=64)
            small.save(path, optimize=True)
    except OSError as exc:
        raise DrawError(f"cannot write {path}: {exc.strerror or exc}") from None


def _caption(item, index: int | None) -> str:
    chain = item.chain if isinstance(item, Mechanism) else item
    text = str(chain.code) + ("" if chain.h == 3 else f"  h={chain.h}") + chain.kind_suffix + chain.class_suffix
    if not chain.is_planar():
        text += "  non-planar"
    if index is not None:
        text += f"  #{index}"
    if isinstance(item, Mechanism):
        text += f"  fixed {item.frame}" + (f", input {item.input_link}" if item.input_link is not None else "")
    return text


#: the edge of one drawing in inches, and the PNG resolution: a single drawing, a sheet's cell
SINGLE, CELL = (3.6, 150), (1.9, 150)


_MAX_PIXELS = 100_000_000  # a PNG is drawn in memory at 4 bytes a pixel: 400 MB


def _check_pixels(path: Path, width: float, height: float, dpi: int) -> None:
    """Refuse a PNG too large to draw in memory (a vector file has no pixels)."""
    if path.suffix.lower() != ".png":
        return
    pixels = width * dpi * height * dpi
    if pixels > _MAX_PIXELS or max(width, height) * dpi >= 2**16:
        raise InvalidOption(f"this picture would be {width * dpi:.0f} × {height * dpi:.0f} pixels, more than "
                            f"{_MAX_PIXELS / 1e6:.0f} megapixels (or 65 536 on a side); lower {option('dpi', 'DPI')} or "
                            f"{option('size', 'INCHES')}, narrow "
                            "the selection, or write .svg")


def _check_size(size: float, dpi: int) -> None:
    if not 0.5 <= size <= 30:
        raise InvalidOption(f"a drawing's size is 0.5 to 30 inches, not {size:g}")
    if not 30 <= dpi <= 1200:
        raise InvalidOption(f"the resolution is 30 to 1200 dpi, not {dpi}")


def _figure(item: Chain | Mechanism, labels: bool, size: float):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(size, size * 19 / 18))
    _draw(ax, item, labels=labels, caption=None)
    ax.set_title(_caption(item, None), fontsize=9)
    return fig


def draw_one(item: Chain | Mechanism, out: str | Path, *, title: str | None = None, labels: bool = True,
             size: float = SINGLE[0], dpi: int = SINGLE[1]) -> None:
    """Draw one chain or mechanism to ``out`` (.svg, .png or .pdf), links numbered unless
    ``labels=False``; ``size`` is the drawing's edge in inches, ``dpi`` the PNG resolution.

    >>> # draw_one(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0), "fourbar.png", size=5)
    """
    import matplotlib.pyplot as plt

    path = _check_out(out)
    _check_size(size, dpi)
    _check_pixels(path, size, size * 19 / 18, dpi)
    fig = _figure(item, labels, size)
    try:
        if title:
            fig.axes[0].set_title(title, fontsize=9)
        _save(fig, path, dpi=dpi)
    finally:
        plt.close(fig)


def svg(item: Chain | Mechanism, *, labels: bool = True, size: float = SINGLE[0]) -> str:
    """One chain or mechanism as SVG text (what Jupyter shows for a Chain or Mechanism).

    >>> svg(Chain.parse("0-1 1-2 2-3 3-0")).lstrip().startswith("<?xml")
    True
    """
    import io

    import matplotlib
    import matplotlib.pyplot as plt

    _check_size(size, SINGLE[1])
    fig = _figure(item, labels, size)
    try:
        out = io.StringIO()
        with matplotlib.rc_context({"svg.hashsalt": "mechsynth", "svg.fonttype": "none"}):
            fig.savefig(out, format="svg", bbox_inches="tight", metadata={"Date": None})
        return out.getvalue()
    finally:
        plt.close(fig)


def draw_sheet(items: Sequence[Chain | Mechanism], out: str | Path, *, columns: int | None = None,
               title: str | None = None, labels: bool | None = None, size: float = CELL[0],
               dpi: int = CELL[1], notes: Sequence[str] | None = None) -> None:
    """An atlas sheet: every item on a grid, captioned with its code and index (1, 2, …).

    Links are numbered when ``labels`` is true, and by default on sheets of mechanisms (whose
    captions name the fixed and input links) and on sheets with ``notes`` (a text under each
    caption, wrapped to the drawing's width: the edits of a repair); ``size`` is each drawing's
    edge in inches.

    >>> # draw_sheet(list(synth.type_synthesis(1, 8)), "atlas_8.png", title="1-DOF, 8 links")
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = _check_out(out)
    _check_size(size, dpi)
    if not items:
        raise InvalidOption("nothing to draw: the selection is empty")
    if notes is not None and len(notes) != len(items):
        raise InvalidOption(f"{len(notes)} notes for {len(items)} drawings")
    if labels is None:
        labels = notes is not None or any(isinstance(item, Mechanism) for item in items)
    n = len(items)
    columns = min(columns or max(1, math.ceil(math.sqrt(n * 1.3))), n)
    rows = math.ceil(n / columns)
    captions = [_caption(item, i + 1) for i, item in enumerate(items)]
    if notes is not None:  # about 16 characters a line per inch at 8 points
        import textwrap

        width = max(20, int(size * 16.5))
        captions = [caption + "".join("\n" + line for line in textwrap.wrap(note, width))
                    for caption, note in zip(captions, notes)]
    extra = 0.14 * max(c.count("\n") for c in captions)  # inches under each row for the caption lines
    mixed = next((getattr(item, "chain", item) for item in items if getattr(item, "chain", item).classes), None)
    key = 0.3 if mixed is not None else 0  # inches under the sheet for the key of loop classes
    height = (size + extra) * rows + (0.45 if title else 0) + key
    _check_pixels(path, size * columns, height, dpi)
    fig, axes = plt.subplots(rows, columns, figsize=(size * columns, height), squeeze=False)
    try:
        for i, ax in enumerate(axes.flat):
            if i < n:
                _draw(ax, items[i], labels=labels, caption=captions[i], legend=False)
            else:
                ax.axis("off")
        if title:
            fig.suptitle(title, fontsize=11)
        fig.tight_layout(pad=0.4, rect=(0, key / height, 1, 1))
        if mixed is not None:  # one key for the sheet, under it
            keys = _class_keys(mixed, counted=False)
            fig.legend(handles=keys, loc="lower center", ncol=len(keys), fontsize=7, frameon=False)
        _save(fig, path, dpi=dpi)
    finally:
        plt.close(fig)


def svg_inline(item: Chain | Mechanism, *, size: int = 160, labels: bool = False) -> str:
    """A small ``<svg>`` element of a chain or mechanism written directly, without matplotlib
    (about a tenth of the time): the same drawing for web pages of many chains.

    >>> svg_inline(Chain.parse("0-1 1-2 2-3 3-0")).startswith("<svg")
    True
    """
    mech = item if isinstance(item, Mechanism) else None
    chain = item.chain if mech else item
    marks = _Marks(chain)
    lay, pos, r, free_ends, reach = marks.lay, marks.pos, marks.r, marks.free_ends, marks.reach
    scale = size / (2 * reach)

    def xy(p) -> str:
        return f"{(p[0] + reach) * scale:.1f},{(reach - p[1]) * scale:.1f}"

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">']
    for link, poly in enumerate(lay.polygons):  # polygons first, bars over them, joints on top
        frame = mech is not None and link == mech.frame
        if len(poly) >= 3:
            fill = "url(#hatch)" if frame else _FILL
            out.append(f'<polygon points="{" ".join(xy(pos[k]) for k in poly)}" fill="{fill}" stroke="{_EDGE}" '
                       'stroke-width="1.2" stroke-linejoin="round"/>')
    dash = ' stroke-dasharray="3 2"'  # a fixed binary link: a wide dashed bar
    for link, poly in enumerate(lay.polygons):
        frame = mech is not None and link == mech.frame
        if len(poly) == 2:
            a, b = xy(pos[poly[0]]), xy(pos[poly[1]])
            out.append(f'<line x1="{a.split(",")[0]}" y1="{a.split(",")[1]}" x2="{b.split(",")[0]}" '
                       f'y2="{b.split(",")[1]}" stroke="{_BAR}" stroke-width="{4.5 if frame else 2.2}" '
                       f'stroke-linecap="round"{dash if frame else ""}/>')
        elif len(poly) == 1:
            end = free_ends[link]
            out.append(f'<polyline points="{xy(pos[poly[0]])} {xy(end)}" stroke="{_BAR}" stroke-width="2.2" fill="none"/>')
            x, y = xy(end).split(",")
            half = r * scale
            out.append(f'<rect x="{float(x) - half:.1f}" y="{float(y) - half:.1f}" width="{2 * half:.1f}" '
                       f'height="{2 * half:.1f}" fill="{_EDGE}"/>')
    for k, joint in enumerate(chain.joints):
        x, y = (float(v) for v in xy(pos[k]).split(","))
        if len(joint) > 2:
            tx, ty = (float(v) for v in xy(marks.numbers[k]).split(","))
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{1.75 * r * scale:.1f}" fill="white" stroke="{_MULTI}" '
                       'stroke-width="1.4"/>')
            out.append(f'<text x="{tx:.1f}" y="{ty:.1f}" fill="{_MULTI}" font-size="9" font-weight="bold" '
                       f'text-anchor="middle" dominant-baseline="central">{len(joint)}</text>')
        if chain.kinds[k] == PRISMATIC:
            corners, cylinder = _slider(chain, lay, k, r)
            out.append(f'<polygon points="{" ".join(xy(c) for c in corners)}" fill="{PRISMATIC.stroke if cylinder else "white"}" '
                       f'stroke="{PRISMATIC.stroke}" stroke-width="1.1"/>')
        elif chain.kinds[k] == MESH:  # two pitch circles in mesh
            for centre, radius in marks.meshes[k]:
                cx, cy = xy(centre).split(",")
                out.append(f'<circle class="mesh" cx="{cx}" cy="{cy}" r="{radius * scale:.1f}" fill="white" '
                           f'stroke="{MESH.stroke}" stroke-width="1.2"/>')
        else:
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r * scale:.1f}" fill="white" stroke="{REVOLUTE.stroke}" '
                       'stroke-width="1.1"/>')
    if labels:
        for link in range(chain.links):
            x, y = xy(marks.labels[link]).split(",")
            out.append(f'<text x="{x}" y="{y}" font-size="8" fill="#444" text-anchor="middle" '
                       f'dominant-baseline="central" paint-order="stroke" stroke="white" stroke-width="2">{link}</text>')
    if mech is not None:
        out.insert(1, f'<defs><pattern id="hatch" width="5" height="5" patternUnits="userSpaceOnUse" '
                      f'patternTransform="rotate(45)"><rect width="5" height="5" fill="white"/>'
                      f'<line x1="0" y1="0" x2="0" y2="5" stroke="{_EDGE}" stroke-width="1.2"/></pattern></defs>')
    out.append("</svg>")
    return "".join(out)
