"""Drawings of chains and mechanisms as a designer draws them (matplotlib, Agg, and inline SVG).

Each link is a polygon through its joints (binary links as bars, ternary as
triangles, …), joints are small circles, a multiple joint carries a ring and its
multiplicity, the fixed link of a mechanism is hatched, an input link gets an
arrow and a prismatic pair is a block on a bar (a cylinder: a dark barrel).  Where the joints
stand is :func:`synth.draw.layout`'s; this module places the marks around them and draws.

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

import functools
import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mechbase import save_figure

from ..structure.chain import Chain, Mechanism
from ..structure.joints import MESH, PRISMATIC, REVOLUTE
from ..structure.trusses import count_defect
from ..errors import InvalidOption, MalformedChain, SynthesisError, option
from ._layout import Layout, _sides, layout

__all__ = ["expand", "draw_one", "draw_sheet", "svg", "svg_inline", "DrawError", "SINGLE", "CELL", "check_size",
           "check_pixels"]

_FORMATS = (".svg", ".png", ".pdf")


class DrawError(SynthesisError):
    """A drawing cannot be written (unknown format, unwritable file)."""


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
        """The unit direction of the fixed-pivot sign at joint ``k`` of the frame (:meth:`sign`)."""
        return self.sign(k)[0]

    def sign(self, k: int) -> tuple[np.ndarray, float]:
        """The fixed-pivot sign at joint ``k`` of the frame: its unit direction, into the widest free angle
        there, clear of the sides, free-end bars and multiplicity number drawn at it, and out of the plates at
        it where an angle outside them has the sign's room, else its struts' (a sign in a plate stood under
        its number, at a tiny plate's corner too: 440/0's braced four-bar); and its width, 1, or less where
        the angle is narrower than the sign, to fit it (:func:`_sign_width`)."""
        pos = self.pos
        also = [math.atan2(*(end - pos[k])[::-1]) for link, end in self.free_ends.items()
                if self.lay.polygons[link] == [k]]
        if k in self.numbers:
            also.append(math.atan2(*(self.numbers[k] - pos[k])[::-1]))
        plates = [poly for poly in self.lay.polygons if len(poly) > 2 and k in poly]  # a sign in one hides it
        turn, angle = _widest_gap(pos, self.sides, k, also, plates, room=_SIGN_ANGLE, least=_STRUTS_ANGLE)
        return np.array([math.cos(turn), math.sin(turn)]), _sign_width(angle)


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
                                     edgecolor=_EDGE, hatch="////", lw=1.2, zorder=2, gid=f"framebar{link}"))
            else:
                ax.plot(pts[:, 0], pts[:, 1], color=bar, lw=lw * (1.4 if based else 1), solid_capstyle="round",
                        zorder=2, gid=f"bar{link}")
        else:  # a frame plate's hatching under the box around its number (_HATCH_GAP), every plate's outline over it
            if frame:
                ax.add_patch(Polygon(pts, closed=True, facecolor="white", edgecolor=edge, hatch="////", lw=0,
                                     zorder=_HATCH_GAP - 0.1, gid=f"hatching{link}"))
            ax.add_patch(Polygon(pts, closed=True, facecolor=_FILL, fill=not frame, edgecolor=edge,
                                 lw=2.4 if based else 1.4, joinstyle="round", zorder=1, gid=f"plate{link}"))
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
                _fixed_pivot(ax, pos[k], *marks.sign(k), r, k)
    if labels:  # over everything, in a light box; the frame's number on its hatching, which a wider opaque box
        for link, (x, y) in _label_places(marks, mech, _em(ax, marks)).items():  # under every line and pin keeps off it
            number = dict(s=str(link), fontsize=7, ha="center", va="center")
            if mech is not None and link == mech.frame:
                ax.text(x, y, color="none", zorder=_HATCH_GAP, gid=f"hatchgap{link}", **number,
                        bbox=dict(boxstyle=f"round,pad={_HATCH_PAD}", fc="white", ec="none"))
            ax.text(x, y, color="#555555", zorder=5, gid=f"label{link}", **number,
                    bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8))
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


#: the padding, in ems, of the opaque box that keeps the frame's hatching off its number (the numbers' own: 0.1)
_HATCH_PAD = 0.4
#: the layer of that box: over a frame plate's hatching, under every plate, line and pin (1 up). The number's own
#: box at 0.8 let the hatch lines run through it a fifth as dark (440/0's tiny frame plate, #2); opaque over
#: everything it hid a pin there; the number under the lines, a pivot sign crossed it (4600/0's tiny plates)
_HATCH_GAP = 0.9


def _em(ax, marks: _Marks) -> float:
    """The drawing's length of one 7-point em of the numbers on ``ax``, by the width of a cell of the sheet (as the
    sheet's layout leaves the drawing)."""
    _, columns = ax.get_subplotspec().get_gridspec().get_geometry()
    inches = 0.95 * ax.figure.get_figwidth() / columns
    return 2 * marks.reach / inches * 7 / 72


def _number_half(link: int, unit: float, hatched: bool) -> np.ndarray:
    """Half the width and height of link ``link``'s number in its light box, ``unit`` the drawing's length of one
    em; on the frame's hatching, of the opaque gap around it, :data:`_HATCH_PAD` em wide.

    >>> _number_half(12, 1.0, False).round(2).tolist(), _number_half(0, 1.0, True).round(2).tolist()
    ([0.92, 0.62], [0.86, 0.92])
    """
    half = np.array([0.36 * unit * len(str(link)) + 0.2 * unit, 0.62 * unit])
    return half + (_HATCH_PAD - 0.1) * unit if hatched else half


def _label_places(marks: _Marks, mech: Mechanism | None, unit: float) -> dict[int, np.ndarray]:
    """Where each link's number goes, as the motion drawings place them: of a few places (either side of
    a bar, along it; a plate's middle, towards its pins), the first clear of every pin, ring, slider,
    cylinder, fixed-pivot sign, bar, multiplicity number and number placed before, else the clearest
    (numbers at the middle of each link stood under the cylinders and pivot signs of 12-link drawings); a plate
    too narrow for any of them takes the clearest point of a grid over it.
    ``unit`` is the drawing's length of one em of the numbers (:func:`_em` on a sheet); the frame's number, in
    its wider box over the hatching, counts that box, and a frame's bar its hatched width."""
    from matplotlib.path import Path as MplPath

    chain, lay, pos, r = marks.chain, marks.lay, marks.pos, marks.r
    samples = []

    def segment(a, b):
        samples.append(np.linspace(a, b, 2 + int(np.linalg.norm(b - a) / (0.4 * r))))

    def outline(corners):
        for a, b in zip(corners, [*corners[1:], corners[0]]):
            segment(np.asarray(a, float), np.asarray(b, float))

    circle = np.array([[math.cos(t), math.sin(t)] for t in np.linspace(0, 2 * math.pi, 12, endpoint=False)])
    for link, poly in enumerate(lay.polygons):
        ends = [pos[j] for j in poly] + ([marks.free_ends[link]] if len(poly) == 1 else [])
        if len(ends) == 2 and mech is not None and link == mech.frame:  # a hatched bar, 1.8 r wide
            a, b = ends
            across = np.array([a[1] - b[1], b[0] - a[0]]) / (np.linalg.norm(b - a) + 1e-12) * r * 0.9
            outline([a + across, b + across, b - across, a - across])
        elif len(ends) == 2:
            segment(*ends)
        else:
            outline(ends)
        if len(poly) == 1:
            outline(marks.free_ends[link] + r * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]))
    for k, joint in enumerate(chain.joints):
        samples.append(pos[k] + (1.75 if len(joint) > 2 else 1.0) * r * np.vstack([circle, [0, 0]]))
        if k in marks.numbers:
            samples.append(marks.numbers[k] + 0.9 * unit * np.vstack([circle, [0, 0]]))
        if chain.kinds[k] == PRISMATIC:
            corners = _slider(chain, lay, k, r)[0]
            outline(corners)
            segment((corners[0] + corners[3]) / 2, (corners[1] + corners[2]) / 2)
        if mech is not None and mech.frame in joint:
            d, width = marks.sign(k)
            across = np.array([-d[1], d[0]]) * width
            base = pos[k] + d * 2.4 * r
            outline([pos[k], base + across * 2.1 * r, base + across * 2.1 * r + d * 0.8 * r,
                     base - across * 2.1 * r + d * 0.8 * r, base - across * 2.1 * r])
    obstacles = np.concatenate(samples)
    placed: list[np.ndarray] = []
    plates = [MplPath(pos[poly]) for poly in lay.polygons if len(poly) > 2]

    def clearance(centre: np.ndarray, half: np.ndarray) -> float:
        if np.any(np.abs(centre) + half > marks.reach):  # off the drawing
            return -math.inf
        pts = np.concatenate([obstacles, *placed]) if placed else obstacles
        gap = np.maximum(np.abs(pts - centre) - half, 0.0)
        return float(np.hypot(gap[:, 0], gap[:, 1]).min(initial=math.inf))

    out = {}
    for link, poly in enumerate(lay.polygons):
        half = _number_half(link, unit, mech is not None and link == mech.frame)
        ends = [pos[j] for j in poly] + ([marks.free_ends[link]] if len(poly) == 1 else [])
        middle = np.mean(ends, axis=0)
        if len(ends) == 2:  # a bar: beside it, the upper side and its middle first; on it last
            d = ends[1] - ends[0]
            n = np.array([-d[1], d[0]]) / max(float(np.linalg.norm(d)), 1e-12)
            n = n if n[1] >= 0 else -n
            lift = 0.4 * r + float(np.abs(n) @ half)
            centres = [ends[0] + t * d + side * (lift + wide) * n for wide in (0, 1.4 * r) for side, t in
                       ((1, 0.5), (-1, 0.5), (1, 0.3), (1, 0.7), (-1, 0.3), (-1, 0.7), (1, 0.15), (1, 0.85),
                        (-1, 0.15), (-1, 0.85))]  # beside a cylinder's barrel, 1.3 r wide, too
            inside = [c for c in centres if any(plate.contains_point(c) for plate in plates)]
            centres = [c for c in centres if not any(c is i for i in inside)] + inside + [middle]  # not read as a plate's
        else:  # a plate: its middle, else towards one of its corners
            sides = [(a + b) / 2 for a, b in zip(ends, ends[1:] + ends[:1])]
            centres = [middle] + [middle + f * (p - middle) for f in (0.3, 0.55, 0.75) for p in ends + sides]
        gaps = [clearance(c, half) for c in centres]
        clear = [c for c, g in zip(centres, gaps) if g >= 0.3 * r]
        if not clear and len(ends) > 2:  # a narrow plate: the clearest of a grid over it (outside, a number
            low, high = np.min(ends, axis=0), np.max(ends, axis=0)  # would be read as a neighbour's)
            grid = [c for c in (low + (high - low) * [i / 8, j / 8] for i in range(1, 8) for j in range(1, 8))
                    if MplPath(np.array(ends)).contains_point(c)]
            centres, gaps = centres + grid, gaps + [clearance(c, half) for c in grid]
        centre = clear[0] if clear else centres[int(np.argmax(gaps))]
        placed.append(np.array([centre + half * [sx, sy] for sx in (-1, 0, 1) for sy in (-1, 0, 1)]))
        out[link] = centre
    return out


#: the angles a fixed-pivot sign spans at its pin: its hatched base (2.1 r either side, 2.4 r out), its struts (1.5 r)
_SIGN_ANGLE, _STRUTS_ANGLE = 2 * math.atan2(2.1, 2.4), 2 * math.atan2(1.5, 2.4)
_SIGN_MARGIN = math.radians(4)  # a narrowed sign's base stops this far inside each side of its angle (their width)


def _sign_width(angle: float) -> float:
    """The width of a fixed-pivot sign in a free angle of ``angle`` radians, as a fraction of its own: 1 where the
    angle has its 82°, else narrowed so its hatched base ends 4° inside each side, down to a half.

    >>> [round(_sign_width(math.radians(a)), 2) for a in (120, 82, 78, 64, 30)]
    [1.0, 0.86, 0.8, 0.61, 0.5]
    """
    if angle >= _SIGN_ANGLE:
        return 1.0
    return max(0.5, math.tan(angle / 2 - _SIGN_MARGIN) / math.tan(_SIGN_ANGLE / 2))


def _fixed_pivot(ax, at: np.ndarray, direction: np.ndarray, width: float, r: float, k: int) -> None:
    """A fixed pivot's sign at ``at`` (joint ``k``): two struts from the pin to a base line across ``direction``,
    hatched beyond it (under the pin, over a multiple joint's ring); ``width`` a fraction of its usual width."""
    from matplotlib.patches import Polygon

    across = np.array([-direction[1], direction[0]]) * width
    base, half, depth = at + direction * 2.4 * r, 1.5 * r, 0.8 * r
    ax.add_patch(Polygon([at, base + across * half, base - across * half], closed=True, facecolor="white",
                         edgecolor=_EDGE, lw=1.2, zorder=3.5, gid=f"ground{k}"))
    ax.add_patch(Polygon([base + across * half * 1.4, base - across * half * 1.4,
                          base - across * half * 1.4 + direction * depth, base + across * half * 1.4 + direction * depth],
                         closed=True, facecolor="white", edgecolor=_EDGE, hatch="////", lw=1.2, zorder=3.5,
                         gid=f"pivotbase{k}"))


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


def _widest_gap(pos: np.ndarray, sides: list[tuple[int, int]], joint: int, also=(), plates=(),
                room: float = 0.0, least: float | None = None) -> tuple[float, float]:
    """Direction (radians) of the middle of the widest free angle at a joint between the sides
    drawn there (and the directions ``also``), and that angle; away from the drawing's centre
    where nothing meets the joint.  With ``plates`` (polygons of joints), the widest angle outside
    them where one is ``room`` wide (radians), else where one is ``least`` wide (default ``room``).

    >>> pos = np.array([[0, 0], [1, 0], [-1, 0.1], [-1, -0.36], [1, -0.36]])  # bars at 0°, 174°, 200°, 340°
    >>> sides = [(0, 1), (0, 2), (0, 3), (0, 4)]
    >>> [round(math.degrees(t)) for t in _widest_gap(pos, sides, 0)]  # 0° … 174°: the widest
    [87, 174]
    >>> [round(math.degrees(t)) for t in _widest_gap(pos, sides, 0, plates=[[0, 1, 2]])]  # a plate's: under it
    [-90, 140]
    >>> [round(math.degrees(t)) for t in _widest_gap(pos, sides, 0, plates=[[0, 1, 2]], room=math.pi)]  # none so wide
    [87, 174]
    >>> [round(math.degrees(t)) for t in _widest_gap(pos, sides, 0, plates=[[0, 1, 2]], room=math.pi, least=2)]
    [-90, 140]
    """
    turns = sorted([math.atan2(*(pos[b if a == joint else a] - pos[joint])[::-1])
                    for a, b in sides if joint in (a, b)] + list(also))
    if not turns:
        away = pos[joint] - pos.mean(axis=0)
        return (math.atan2(away[1], away[0]) if np.linalg.norm(away) > 1e-9 else -math.pi / 2), math.pi
    gaps = [((turns[(i + 1) % len(turns)] - t) % (2 * math.pi)) or 2 * math.pi for i, t in enumerate(turns)]
    wedges = []  # each plate's corner at the joint (convex): from one side's direction, its angle
    for plate in plates:
        at = plate.index(joint)
        ends = [pos[plate[at - 1]] - pos[joint], pos[plate[(at + 1) % len(plate)]] - pos[joint]]
        ta, tb = (math.atan2(e[1], e[0]) for e in ends)
        wedge = (tb - ta) % (2 * math.pi)
        wedges.append((ta, wedge) if wedge <= math.pi else (tb, 2 * math.pi - wedge))

    def outside(i: int) -> bool:
        turn = turns[i] + gaps[i] / 2
        return not any(0 < (turn - start) % (2 * math.pi) < wide for start, wide in wedges)

    # the widest angle outside the plates with the room; else the widest outside them with ``least`` (a tiny
    # plate's corner is wider than a free angle beside it, and a sign in it stood under the plate's number); else
    # the widest of all (a joint ringed by plates)
    least = room if least is None else least
    free = [i for i in range(len(gaps)) if outside(i)]
    i = max([i for i in free if gaps[i] >= room] or [i for i in free if gaps[i] >= least] or range(len(gaps)),
            key=gaps.__getitem__)
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
    from ..synthesis.type_synthesis import mechanisms_of

    return [m for c in chains for m in mechanisms_of(c, input_link=input_link)]


def _check_out(out: str | Path) -> Path:
    path = Path(out)
    if path.suffix.lower() not in _FORMATS:
        raise InvalidOption(f"draw writes {', '.join(_FORMATS)} files, not {path.suffix or 'a file without suffix'!r}")
    if not path.parent.exists():
        raise DrawError(f"cannot write {path}: the directory {path.parent} does not exist")
    return path


def _save(fig, path: Path, dpi: int) -> None:
    try:
        save_figure(fig, path, dpi=dpi, bbox_inches="tight")
        if path.suffix.lower() == ".png":  # a 64-colour palette: line art, a third of the size
            from PIL import Image

            with Image.open(path) as image:
                small = image.convert("RGB").quantize(colors=64)
            small.save(path, optimize=True)
    except OSError as exc:
        raise DrawError(f"cannot write {path}: {exc.strerror or exc}") from None


def _caption(item, index: int | None) -> str:
    """The words under a drawing: the chain's code, its number on a sheet, the fixed and input links; a chain of
    W = 0 on a frame is a truss (a statically determinate structure), and says so — or, where its count
    misleads, what it is (:func:`~synth.structure.trusses.count_defect`: not a truss, not of its W, degenerate).

    >>> _caption(Mechanism(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4"), 0), 2)
    '32/0  #2  fixed 0 (truss)'
    >>> _caption(Mechanism(Chain.parse("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-2"), 0), None)
    '340/0  fixed 0 (not a truss)'
    >>> _caption(Mechanism(Chain.parse("0-1 1-2 2-3 3-0 1-3 0-4 4-5 5-6 6-7 7-2"), 0), None)  # moves with W = 2
    '440/0  fixed 0 (not W = 1)'
    """
    chain = item.chain if isinstance(item, Mechanism) else item
    text = str(chain.code) + ("" if chain.h == 3 else f"  h={chain.h}") + chain.kind_suffix + chain.class_suffix
    if not chain.is_planar():
        text += "  non-planar"
    if index is not None:
        text += f"  #{index}"
    if isinstance(item, Mechanism):
        text += f"  fixed {item.frame}" + (f", input {item.input_link}" if item.input_link is not None else "")
        word = _count_word(chain)
        text += f" ({word})" if word else ""
    return text


@functools.lru_cache(maxsize=16)
def _count_word(chain: Chain) -> str:
    """What a caption adds of a chain on a frame: 'truss', or what it is where its count misleads
    (:func:`~synth.structure.trusses.count_defect`, once a chain for a sheet of its mechanisms: a millisecond
    beside a drawing's tens); nothing for a mechanism of its W, or beyond the exact test's 24 non-binary links.

    >>> _count_word(Chain.parse("0-1 1-2 2-0 2-3 3-4 4-5 5-0")), _count_word(Chain.parse("0-1 1-2 2-3 3-0"))
    ('degenerate', '')
    """
    try:
        defect = count_defect(chain)
    except MalformedChain:  # too large to test: no word rather than a guess
        return ""
    return defect.caption if defect else "truss" if chain.dof == 0 else ""


#: the edge of one drawing in inches, and the PNG resolution: a single drawing, a sheet's cell
SINGLE, CELL = (3.6, 150), (1.9, 150)


_MAX_PIXELS = 100_000_000  # a PNG is drawn in memory at 4 bytes a pixel: 400 MB


def check_pixels(path: Path, width: float, height: float, dpi: int) -> None:
    """Refuse a PNG of ``width`` × ``height`` inches at ``dpi`` too large to draw in memory (a vector
    file has no pixels).

    >>> check_pixels(Path("sheet.png"), 100, 100, 100)  # 10 000 × 10 000 pixels: the most allowed
    """
    if path.suffix.lower() != ".png":
        return
    pixels = width * dpi * height * dpi
    if pixels > _MAX_PIXELS or max(width, height) * dpi >= 2**16:
        raise InvalidOption(f"this picture would be {width * dpi:.0f} × {height * dpi:.0f} pixels, more than "
                            f"{_MAX_PIXELS / 1e6:.0f} megapixels (or 65 536 on a side); lower {option('dpi', 'DPI')} or "
                            f"{option('size', 'INCHES')}, narrow "
                            "the selection, or write .svg")


def check_size(size: float, dpi: int) -> None:
    """Refuse a drawing's edge outside 0.5 … 30 inches or a resolution outside 30 … 1200 dpi.

    >>> check_size(3.6, 150)
    """
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
    check_size(size, dpi)
    check_pixels(path, size, size * 19 / 18, dpi)
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

    import matplotlib.pyplot as plt

    check_size(size, SINGLE[1])
    fig = _figure(item, labels, size)
    try:
        out = io.StringIO()
        save_figure(fig, out, fmt="svg", bbox_inches="tight")
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
    check_size(size, dpi)
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
    check_pixels(path, size * columns, height, dpi)
    fig, axes = plt.subplots(rows, columns, figsize=(size * columns, height), squeeze=False)
    try:
        for i, ax in enumerate(axes.flat):
            if i < n:
                _draw(ax, items[i], labels=labels, caption=captions[i], legend=False)
            else:
                ax.axis("off")
        top = 1 - (0.45 / height if title else 0)  # the title's own band: tight_layout leaves the drawings under it
        if title:
            fig.suptitle(title, fontsize=11, y=1 - 0.1 / height, va="top")
        for _ in range(2):  # twice: the first pass sets the drawings before their equal aspect shrinks them, and
            fig.tight_layout(pad=0.4, rect=(0, key / height, 1, top))  # left a caption over the next row's top
        if mixed is not None:  # one key for the sheet, under it
            keys = _class_keys(mixed, counted=False)
            fig.legend(handles=keys, loc="lower center", ncol=len(keys), fontsize=7, frameon=False)
        _save(fig, path, dpi=dpi)
    finally:
        plt.close(fig)


#: the inline drawing's numbers, in pixels
_INLINE_FONT = 8


def svg_inline(item: Chain | Mechanism, *, size: int = 160, labels: bool = False) -> str:
    """A small ``<svg>`` element of a chain or mechanism written directly, without matplotlib
    (about a tenth of the time): the same drawing for web pages of many chains.  Numbered, its
    numbers stand where the sheets put them, in the same light boxes, the frame's on the same
    opaque gap in its hatching under every line and pin (no fixed-pivot signs or input arrow).

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

    unit = _INLINE_FONT / scale  # the drawing's length of one em of the numbers
    numbers = _label_places(marks, mech, unit) if labels else {}
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">']

    def box(link: int, hatched: bool, fill: str) -> str:  # a number's light box, or the frame's gap in its hatching
        (x, y), (w, h) = numbers[link], _number_half(link, unit, hatched)
        return (f'<rect x="{(x - w + reach) * scale:.1f}" y="{(reach - y - h) * scale:.1f}" width="{2 * w * scale:.1f}" '
                f'height="{2 * h * scale:.1f}" rx="{0.3 * _INLINE_FONT:.1f}" {fill}/>')

    for link, poly in enumerate(lay.polygons):  # as on the sheets: a frame plate's hatching, the gap in it under
        if mech is not None and link == mech.frame and len(poly) >= 3:  # its number, then every plate's outline
            out.append(f'<polygon points="{" ".join(xy(pos[k]) for k in poly)}" fill="url(#hatch)" stroke="none"/>')
            if labels:
                out.append(box(link, True, 'fill="white" class="hatchgap"'))
    for link, poly in enumerate(lay.polygons):  # plates first, bars over them, joints on top
        if len(poly) >= 3:
            fill = "none" if mech is not None and link == mech.frame else _FILL
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
    for link, place in numbers.items():  # over everything, in a light box
        x, y = xy(place).split(",")
        out.append(box(link, False, 'fill="white" fill-opacity="0.8"'))
        out.append(f'<text x="{x}" y="{y}" font-size="{_INLINE_FONT}" fill="#444" text-anchor="middle" '
                   f'dominant-baseline="central">{link}</text>')
    if mech is not None:
        out.insert(1, f'<defs><pattern id="hatch" width="5" height="5" patternUnits="userSpaceOnUse" '
                      f'patternTransform="rotate(45)"><rect width="5" height="5" fill="white"/>'
                      f'<line x1="0" y1="0" x2="0" y2="5" stroke="{_EDGE}" stroke-width="1.2"/></pattern></defs>')
    out.append("</svg>")
    return "".join(out)
