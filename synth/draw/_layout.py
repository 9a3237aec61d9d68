"""Where links and joints go in a drawing of a chain: the joint positions and each link's polygon.

When the link–joint incidence graph is planar and 2-connected (single-joint links aside), a Tutte
(barycentric) embedding of the joint graph with the longest loop outside, in which every link
polygon is a convex face and nothing crosses; then joints move one at a time to open up corners
under 30° and crowded joints, never adding a crossing.  A non-planar chain sets aside the fewest
strings of binary links and lets them cross a planar drawing of the rest.  Other chains start from
networkx's planar or Kamada–Kawai layout.  Everything is deterministic.

Example
-------
>>> from synth import Chain
>>> lay = layout(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"))
>>> lay.planar, [len(p) for p in lay.polygons]
(True, [3, 3, 2, 2, 2, 2])
"""

from __future__ import annotations

import math

import numpy as np

from ..structure.chain import Chain

__all__ = ["Layout", "layout"]


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
