"""Drawings of chains and mechanisms as a designer draws them (matplotlib, Agg).

Each link is a polygon through its joints (binary links as bars, ternary as
triangles, …), joints are small circles, a multiple joint carries a ring and its
multiplicity, the fixed link of a mechanism is hatched and an input link gets an
arrow.  Layout: when the link–joint incidence graph is planar and 2-connected, a
Tutte (barycentric) embedding with the longest face outside, which has no crossings
and convex faces; then a force relaxation that only accepts steps keeping the drawing
free of crossings.  Fractionated planar chains start from ``nx.planar_layout``;
non-planar chains use Kamada–Kawai.  Everything is deterministic.

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

from .chain import Chain, Mechanism
from .errors import InvalidOption, SynthesisError

__all__ = ["Layout", "layout", "expand", "draw_one", "draw_sheet", "DrawError"]

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
            else:
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


def _tutte(g, faces: list[list], outer: list) -> dict:
    """Barycentric embedding with ``outer`` on a circle and a virtual centre vertex in every
    inner face (so that paths meeting only at two vertices do not collapse onto one line)."""
    # outer joints: a regular polygon; an outer link with 3+ joints sits on the circle between
    # its two outer joints (a strictly convex corner); binary outer links are sides (their
    # node position influences nothing else)
    outer_joints = [x for x in outer if x[0] == "J"]
    m = len(outer_joints)
    angle = {x: math.pi / 2 + 2 * math.pi * i / m + (math.pi / m if m % 4 == 0 else 0.0)
             for i, x in enumerate(outer_joints)}
    pos = {x: np.array([math.cos(a), math.sin(a)]) for x, a in angle.items()}
    for i, node in enumerate(outer):
        if node not in pos:
            before, after = angle[outer[i - 1]], angle[outer[(i + 1) % len(outer)]]
            if g.degree[node] > 2:
                mid = before + ((after - before) % (2 * math.pi)) / 2
                pos[node] = np.array([math.cos(mid), math.sin(mid)])
            else:
                pos[node] = (pos[outer[i - 1]] + pos[outer[(i + 1) % len(outer)]]) / 2
    weights: dict = {x: {y: 1.0 for y in g[x]} for x in g.nodes}
    for f, face in enumerate(faces):
        if face is outer:
            continue
        centre = ("F", f)
        weights[centre] = {}
        for x in set(face):
            weights[centre][x] = 0.5
            weights[x][centre] = 0.5
    inner = [x for x in sorted(weights) if x not in pos]
    if inner:
        index = {x: i for i, x in enumerate(inner)}
        a = np.zeros((len(inner), len(inner)))
        b = np.zeros((len(inner), 2))
        for x in inner:
            i = index[x]
            for y, w in weights[x].items():
                a[i, i] += w
                if y in index:
                    a[i, index[y]] -= w
                else:
                    b[i] += w * pos[y]
        sol = np.linalg.solve(a, b)
        for x in inner:
            pos[x] = sol[index[x]]
    return pos


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


def _relax(pos: np.ndarray, polygons: list[list[int]], fixed: set[int], iterations: int = 60) -> np.ndarray:
    """Spread the joints (springs inside links, repulsion between all), one joint at a time,
    accepting a move only when it adds no crossing, touching or enclosed joint."""
    n = len(pos)
    if n < 3:
        return pos
    pos = pos.copy()
    rng = np.random.default_rng(0)  # separates joints that the barycentric layout put together
    pos += rng.normal(scale=1e-4, size=pos.shape)
    pairs = {tuple(sorted((a, b))) for poly in polygons for a in poly for b in poly if a != b}
    springs = np.array(sorted(pairs)) if pairs else np.zeros((0, 2), int)
    length = 2.0 / math.sqrt(n)
    tol = 0.12 * length
    cache = _segment_arrays(polygons)
    current = _defects(pos, polygons, tol, cache)
    movable = [k for k in range(n) if k not in fixed]
    step = 0.15 * length
    for _ in range(iterations):
        moved = False
        for k in movable:
            delta = pos[k] - pos
            dist = np.maximum(np.linalg.norm(delta, axis=1), 1e-6)
            dist[k] = np.inf
            force = ((length**2 / dist**2)[:, None] * delta / dist[:, None]).sum(axis=0)
            for a, b in springs[(springs[:, 0] == k) | (springs[:, 1] == k)]:
                other = b if a == k else a
                d = pos[other] - pos[k]
                force += d * np.linalg.norm(d) / length
            norm = float(np.linalg.norm(force))
            if norm < 1e-9:
                continue
            move = force / norm * min(norm * 0.1, step)
            for scale in (1.0, 0.4):
                old = pos[k].copy()
                pos[k] = old + scale * move
                defects = _defects(pos, polygons, tol, cache)
                if defects <= current:
                    current, moved = defects, True
                    break
                pos[k] = old
        step *= 0.93
        if not moved:
            break
    return pos


def _polygons(chain: Chain, g, embedding, pos: dict) -> list[list[int]]:
    """Each link's joints in polygon order: the embedding's rotation, else by angle."""
    polygons = []
    for i in range(chain.links):
        node = ("L", i)
        joints = [y[1] for y in g[node]]
        if embedding is not None and len(joints) >= 3:
            order = [y[1] for y in embedding.neighbors_cw_order(node)]
        else:
            centre = np.mean([pos[("J", k)] for k in joints], axis=0)
            order = sorted(joints, key=lambda k: math.atan2(*(pos[("J", k)] - centre)[::-1]))
        polygons.append(order)
    return polygons


def _normalise(pos: np.ndarray) -> np.ndarray:
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    centre, span = (lo + hi) / 2, max(float((hi - lo).max()), 1e-9)
    return (pos - centre) * (2.0 / span)


def layout(chain: Chain) -> Layout:
    """Positions of the joints and the polygon order of each link's joints.

    >>> lay = layout(Chain.parse("0-1 1-2 2-3 3-0"))
    >>> lay.joints.shape, lay.planar, [len(p) for p in lay.polygons]
    ((4, 2), True, [2, 2, 2, 2])
    """
    import networkx as nx

    g = _incidence(chain)
    planar, embedding = nx.check_planarity(g)
    fixed: set[int] = set()
    if planar and nx.is_biconnected(g) and g.number_of_nodes() > 2:
        faces = _faces(embedding)
        # prefer the longest loop outside (as designers draw), but not one that degenerates
        candidates = sorted(faces, key=lambda f: (-sum(1 for x in f if x[0] == "J"), -len(f), sorted(f)))
        best = None
        for outer in candidates[:6]:
            trial = _tutte(g, faces, outer)
            polys = _polygons(chain, g, embedding, trial)
            joints_xy = np.array([trial[("J", k)] for k in range(len(chain.joints))])
            score = _defects(_normalise(joints_xy), polys, 0.02)
            if best is None or score < best[0]:
                best = (score, trial, outer)
            if score == 0:
                break
        _, pos, outer = best
        fixed = {x[1] for x in outer if x[0] == "J"}
    elif planar:
        pos = nx.planar_layout(g)
        pos = nx.kamada_kawai_layout(g, pos=pos)
    else:
        pos = nx.kamada_kawai_layout(g)
    polygons = _polygons(chain, g, embedding if planar else None, pos)
    joints = np.array([pos[("J", k)] for k in range(len(chain.joints))], dtype=float)
    joints = _normalise(joints)
    if planar:
        joints = _normalise(_relax(joints, polygons, fixed))
    return Layout(joints, polygons, planar and _defects(joints, polygons, 1e-3) == 0)


# ------------------------------------------------------------------ drawing
_FILL = "#dbe6f4"
_EDGE = "#1f3a5f"
_BAR = "#1f3a5f"
_MULTI = "#c0392b"


def _draw(ax, item: Chain | Mechanism, *, labels: bool = False, caption: str | None = None) -> None:
    from matplotlib.patches import Circle, FancyArrowPatch, Polygon

    mech = item if isinstance(item, Mechanism) else None
    chain = item.chain if mech else item
    lay = layout(chain)
    pos = lay.joints
    nj = len(pos)
    min_dist = min((float(np.linalg.norm(pos[a] - pos[b])) for a in range(nj) for b in range(a + 1, nj)),
                   default=1.0)
    r = min(0.07, 0.28 * min_dist)
    lw = 2.2
    free_ends = _free_ends(pos, lay.polygons, length=max(0.3, 6 * r))
    for link, poly in enumerate(lay.polygons):
        pts = pos[poly]
        frame = mech is not None and link == mech.frame
        if len(poly) == 1:  # a single-joint link (an arm's base or gripper): a bar with a free end
            end = free_ends[link]
            pts = np.array([pos[poly[0]], end])
            ax.plot(pts[:, 0], pts[:, 1], color=_BAR, lw=lw, solid_capstyle="butt", zorder=2)
            ax.add_patch(Polygon([end + (-r, -r), end + (r, -r), end + (r, r), end + (-r, r)], closed=True,
                                 facecolor=_EDGE, edgecolor=_EDGE, hatch="////" if frame else None, zorder=3))
        elif len(poly) == 2:
            if frame:
                a, b = pts
                d = b - a
                nrm = np.array([-d[1], d[0]]) / (np.linalg.norm(d) + 1e-12) * r * 0.9
                ax.add_patch(Polygon([a + nrm, b + nrm, b - nrm, a - nrm], closed=True, facecolor="white",
                                     edgecolor=_EDGE, hatch="////", lw=1.2, zorder=2))
            else:
                ax.plot(pts[:, 0], pts[:, 1], color=_BAR, lw=lw, solid_capstyle="round", zorder=2)
        else:
            ax.add_patch(Polygon(pts, closed=True, facecolor="white" if frame else _FILL, edgecolor=_EDGE,
                                 hatch="////" if frame else None, lw=1.4, joinstyle="round", zorder=1))
        if labels:
            centre = pts.mean(axis=0)
            ax.text(centre[0], centre[1], str(link), fontsize=7, color="#555555", ha="center", va="center",
                    zorder=5, bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.7)
                    if len(poly) == 2 else None)
    for k, joint in enumerate(chain.joints):
        x, y = pos[k]
        if len(joint) > 2:
            ax.add_patch(Circle((x, y), r * 1.75, facecolor="white", edgecolor=_MULTI, lw=1.6, zorder=3))
            ax.text(x + r * 1.5, y + r * 1.5, str(len(joint)), color=_MULTI, fontsize=7, fontweight="bold",
                    ha="left", va="bottom", zorder=6)
        ax.add_patch(Circle((x, y), r, facecolor="white", edgecolor="black", lw=1.2, zorder=4))
    if mech is not None and mech.input_link is not None:
        k = next(i for i, j in enumerate(chain.joints) if mech.frame in j and mech.input_link in j)
        x, y = pos[k]
        ax.add_patch(FancyArrowPatch((x + 2.6 * r, y), (x, y + 2.6 * r), connectionstyle="arc3,rad=0.5",
                                     arrowstyle="-|>", mutation_scale=9, color=_MULTI, lw=1.2, zorder=6))
    ax.set_aspect("equal")
    reach = max([1.25] + [float(np.abs(end).max()) + 2 * r for end in free_ends.values()])
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.axis("off")
    if caption:
        ax.set_title(caption, fontsize=8, pad=2, y=-0.02)


def _free_ends(pos: np.ndarray, polygons: list[list[int]], length: float) -> dict[int, np.ndarray]:
    """Where each single-joint link ends: away from the drawing's centre, fanned out where several
    hang on one joint."""
    centre = pos.mean(axis=0) if len(pos) else np.zeros(2)
    hanging: dict[int, list[int]] = {}
    for link, poly in enumerate(polygons):
        if len(poly) == 1:
            hanging.setdefault(poly[0], []).append(link)
    ends = {}
    for joint, links in hanging.items():
        away = pos[joint] - centre
        base = math.atan2(away[1], away[0]) if np.linalg.norm(away) > 1e-9 else -math.pi / 2
        for i, link in enumerate(links):
            angle = base + (i - (len(links) - 1) / 2) * 0.6
            ends[link] = pos[joint] + length * np.array([math.cos(angle), math.sin(angle)])
    return ends


def expand(chains: Sequence[Chain], *, mechanisms: bool = False, input_link: bool = False) -> list:
    """The items of a sheet: the chains themselves, or every mechanism of each."""
    if not mechanisms:
        return list(chains)
    from ._type_synthesis import mechanisms_of

    return [m for c in chains for m in mechanisms_of(c, input_link=input_link)]


def _check_out(out: str | Path) -> Path:
    path = Path(out)
    if path.suffix.lower() not in _FORMATS:
        raise InvalidOption(f"draw writes {', '.join(_FORMATS)} files, not {path.suffix or 'a file without suffix'!r}")
    if not path.parent.exists():
        raise DrawError(f"cannot write {path}: the directory {path.parent} does not exist")
    return path


def _save(fig, path: Path, dpi: int = 110) -> None:
    kwargs = {"metadata": {"Date": None}} if path.suffix.lower() == ".svg" else {}
    import matplotlib

    try:
        with matplotlib.rc_context({"svg.hashsalt": "mechsynth"}):  # stable SVG ids: same input, same file
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
    text = str(chain.code) + ("" if chain.h == 3 else f"  h={chain.h}")
    if index is not None:
        text += f"  #{index}"
    if isinstance(item, Mechanism):
        text += f"  fixed {item.frame}" + (f", input {item.input_link}" if item.input_link is not None else "")
    return text


def draw_one(item: Chain | Mechanism, out: str | Path, *, title: str | None = None, labels: bool = True) -> None:
    """Draw one chain or mechanism to ``out`` (.svg, .png or .pdf), links numbered.

    >>> # draw_one(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0), "fourbar.png")
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = _check_out(out)
    fig, ax = plt.subplots(figsize=(3.6, 3.8))
    try:
        _draw(ax, item, labels=labels, caption=None)
        ax.set_title(title or _caption(item, None), fontsize=9)
        _save(fig, path)
    finally:
        plt.close(fig)


def svg(item: Chain | Mechanism, *, labels: bool = True) -> str:
    """One chain or mechanism as SVG text (what Jupyter shows for a Chain or Mechanism).

    >>> svg(Chain.parse("0-1 1-2 2-3 3-0")).lstrip().startswith("<?xml")
    True
    """
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(3.6, 3.8))
    try:
        _draw(ax, item, labels=labels, caption=None)
        ax.set_title(_caption(item, None), fontsize=9)
        out = io.StringIO()
        with matplotlib.rc_context({"svg.hashsalt": "mechsynth"}):
            fig.savefig(out, format="svg", bbox_inches="tight", metadata={"Date": None})
        return out.getvalue()
    finally:
        plt.close(fig)


def draw_sheet(items: Sequence[Chain | Mechanism], out: str | Path, *, columns: int | None = None,
               title: str | None = None, labels: bool = False) -> None:
    """An atlas sheet: every item on a grid, captioned with its code and index (1, 2, …).

    >>> # draw_sheet(list(synth.type_synthesis(1, 8)), "atlas_8.png", title="1-DOF, 8 links")
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = _check_out(out)
    if not items:
        raise InvalidOption("nothing to draw: the selection is empty")
    n = len(items)
    columns = columns or min(n, max(1, math.ceil(math.sqrt(n * 1.3))))
    rows = math.ceil(n / columns)
    size = 1.9
    fig, axes = plt.subplots(rows, columns, figsize=(size * columns, size * rows + (0.45 if title else 0)),
                             squeeze=False)
    try:
        for i, ax in enumerate(axes.flat):
            if i < n:
                _draw(ax, items[i], labels=labels, caption=_caption(items[i], i + 1))
            else:
                ax.axis("off")
        if title:
            fig.suptitle(title, fontsize=11)
        fig.tight_layout(pad=0.4)
        _save(fig, path, dpi=80)
    finally:
        plt.close(fig)
