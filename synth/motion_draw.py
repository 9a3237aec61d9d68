"""Pictures of mechanisms that move: the pose with its coupler curves (PNG, SVG), the pose alone to
scale (``draw LINKAGE_FILE``), animations (GIF, animated SVG), the frames a web page plays, and every
atlas mechanism as a linkage from its drawing.

One geometry serves every output: :func:`_elements` turns a :class:`~synth.motion.Motion` (or a
linkage's pose alone) into drawing elements — link bodies, pins, ground pivots, sliders on their
guides, gear pitch circles, tracer paths — each with its points at every frame, in pixels.  The
writers only lay these out: a static SVG (one frame), an animated SVG (SMIL ``<animate>`` on each
element's points), the site's player (the frames as JSON, a few lines of script), matplotlib for PNG
and for the frames of a GIF.  A link is placed at a frame by its rotation from the pose
(``Motion.angles``) and one of its joints' positions, so a slider's block and guide, a gear's spoke
and a ternary link's plate move exactly as the solver moved the link.

This module is on the top floor: it imports :mod:`synth.motion` and the drawings' layout
(:func:`synth.draw.layout`), never the reverse.

Example
-------
>>> from synth.structure.chain import Chain, Mechanism
>>> from synth.motion import Linkage
>>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
>>> linkage_svg(four_bar).startswith("<svg")
True
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

import numpy as np

from mechbase import save_figure

from .errors import InvalidOption
from .motion import Linkage, Motion, joint_name, linkage_from_pose
from .structure.chain import Mechanism
from .structure.joints import MESH, PRISMATIC, REVOLUTE

__all__ = ["linkage_from_layout", "linkage_svg", "motion_svg", "draw_linkage", "draw_motion", "draw_motion_sheet",
           "animate_motion", "player_svg", "PICTURE_SUFFIXES", "ANIMATION_SUFFIXES"]

#: what a still picture and an animation may be written as
PICTURE_SUFFIXES = (".png", ".svg")
ANIMATION_SUFFIXES = (".gif", ".svg")

_BODY, _EDGE, _INPUT, _FRAME = "#dbe6f4", "#1f3a5f", "#c0632b", "#6b7785"
_CURVES = ("#c0392b", "#1e7a46", "#7d3c98", "#b9770e", "#2471a3")
_PATH = "#8f9baa"
_MARK = "#1f4e9c"  # target points of a synthesis


# ------------------------------------------------------------------ linkages from the atlas's drawings
def linkage_from_layout(mechanism: Mechanism, *, size: float = 100.0, tries: int = 24) -> Linkage:
    """A dimensioned linkage for any planar mechanism of the atlas: its drawing's layout as the pose.

    The joints stand where :func:`synth.draw.layout` draws them, scaled so that the drawing is
    ``size`` across.  A drawing is made to be read, not to move: its symmetric poses are often
    locked, or parallelograms that fold at a change point.  So each input joint of the frame (the
    mechanism's input link's, if it has one) is tried on the drawing's pose and then on ``tries`` poses
    whose joints are moved at random (fixed seed) by 5 … 30 % of the size, and the first that moves well
    is kept: its input turns fully (a crank) and no transmission angle falls under 20°; failing that,
    the best found (a crank first, then the widest transmission angle, then the largest swing).
    :attr:`Linkage.note` says when the joints were moved, by how much, and why.

    Parameters
    ----------
    mechanism : Mechanism
        A chain (revolute, prismatic and gear joints, h = 3) with its frame.
    size : float
        The drawing's width and height in the linkage's length unit.
    tries : int
        Moved poses tried after the drawing's own.

    Returns
    -------
    Linkage

    Raises
    ------
    MotionError
        The chain is not planar (h ≠ 3), rigid, or no pose tried moves.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = linkage_from_layout(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0))
    >>> lk.dof
    1
    """
    from .draw import layout
    from .errors import MotionError

    chain = mechanism.chain
    if chain.h != 3:
        raise MotionError(f"a linkage moves in the plane (h = 3); this chain's loops are in motion space h = {chain.h}")
    drawn = layout(chain).joints * (size / 2.0)
    if chain.dof != 1:
        return linkage_from_pose(mechanism, drawn, nudge=True)
    kinds = chain.kinds
    inputs = [k for k, j in enumerate(chain.joints) if len(j) == 2 and mechanism.frame in j and kinds[k] != MESH
              and (mechanism.input_link is None or mechanism.input_link in j)]
    rng = np.random.default_rng(0)
    best = None
    first_why = None
    for attempt in range(tries + 1):
        pose = drawn if attempt == 0 else drawn + rng.uniform(-1, 1, drawn.shape) * size * 0.05 * (1 + 5 * attempt / tries)
        turns = rng.uniform(0, 2 * math.pi, len(kinds))  # a slider's line is a choice too: tried at random
        slides = None if attempt == 0 else {k: (math.cos(turns[k]), math.sin(turns[k]))
                                            for k, kind in enumerate(kinds) if kind == PRISMATIC}
        for k in sorted(inputs, key=lambda k: (kinds[k] != REVOLUTE, k)):
            try:
                candidate = linkage_from_pose(mechanism, pose, inputs=(k,), slides=slides, nudge=attempt == 0)
                score, why, measured = _how_well(candidate)
            except MotionError as exc:
                score, why, measured = None, str(exc), None
            if attempt == 0 and first_why is None:
                first_why = why
            if score is not None and (best is None or score > best[0]):
                best = (score, candidate, attempt, measured)
        if best is not None and best[0][0]:
            break
    if best is None:
        raise MotionError(f"no pose near the drawing of {chain.compact()} with frame {mechanism.frame} moves "
                          f"({first_why})")
    score, linkage, attempt, measured = best
    if attempt == 0:
        return linkage
    shift = float(np.hypot(*(linkage.points - drawn).T).max())
    if score[1]:
        swing = "turns fully"
    elif linkage.kind(linkage.inputs[0]) == REVOLUTE:
        swing = f"swings {math.degrees(score[3]):.0f}°"
    else:
        swing = f"slides {score[3] * linkage.scale / (2 * math.pi):.3g}"
    note = (f"the drawing's pose does not move well ({first_why}); its joints were moved by up to {shift:.3g} "
            f"({shift / size:.0%} of its size) to a pose whose input {swing}"
            # (whole degrees down: a bound of 23.7° is "at least 23°"; a group moved by Newton's method has none)
            + (f" with transmission angles of at least {math.floor(math.degrees(measured))}°"
               if score[1] and measured is not None else ""))
    return Linkage(linkage.mechanism, linkage.inputs, linkage.points, linkage.slides, linkage.meshes, linkage.tracers,
                   note)


#: the worst transmission angle a pose from a drawing may have and count as moving well
_GOOD_TRANSMISSION = math.radians(20)


def _how_well(linkage: Linkage) -> tuple[tuple, str | None, float | None]:
    """How well a linkage moves, as a sortable score (moves well, turns fully, worst transmission
    angle, swing), what is wrong with it in words (None when nothing is), and a crank's worst
    transmission angle as measured (None where none is: a rocker, or a group moved by Newton's method,
    which reports none and is scored as 90°)."""
    from .motion import pose_branch, sweep

    lo, hi, closed_form = pose_branch(linkage)
    revolute = linkage.kind(linkage.inputs[0]) == REVOLUTE
    full = revolute and math.isinf(lo) and math.isinf(hi)
    # a crank turns once; a rocker swings from limit to limit (which may span more than a turn), an
    # endless slide as far as a sweep takes it (four sizes); a stroke as long as the mechanism is worth
    # a turn
    start = lo if math.isfinite(lo) else 0.0
    span = 2 * math.pi if full else (hi if math.isfinite(hi) else start + 4 * linkage.scale) - start
    if not revolute:
        span *= 2 * math.pi / linkage.scale
    # a rocker's ends are dead positions, where some transmission angle is 0 by nature: only a crank's
    # count (a group moved by Newton's method reports none)
    worst = 0.0
    if full:
        transmission = sweep(linkage, steps=73).transmission.values() if closed_form else ()
        worst = min([min(t["min"], math.pi - t["max"]) for t in transmission] + [math.pi / 2])
    good = full and worst >= _GOOD_TRANSMISSION
    if good:
        why = None
    elif full:
        why = f"a transmission angle falls to {math.degrees(worst):.2g}°"
    else:
        why = "its input does not turn fully"
    return (good, full, round(worst, 3), span), why, worst if full and closed_form else None


# ------------------------------------------------------------------ the geometry of each frame
class _Placement:
    """Where each link is at each frame: its rotation from the pose and one of its joints.

    A revolute joint moves with every link it joins; a prismatic joint's point in a Motion is carried
    by the joint's first link; the frame never moves."""

    def __init__(self, linkage: Linkage, joints: np.ndarray, angles: np.ndarray):
        self.linkage, self.joints, self.angles = linkage, joints, angles
        self.anchor: list[int | None] = []
        for link in range(linkage.chain.links):
            on = linkage.joints_of(link)
            pins = [k for k in on if linkage.kind(k) == REVOLUTE]
            carried = [k for k in on if linkage.kind(k) == PRISMATIC and linkage.chain.joints[k][0] == link]
            self.anchor.append((pins + carried + [None])[0])

    def place(self, link: int, p) -> np.ndarray:
        """Positions (F, m, 2) at every frame of the points ``p`` (m, 2) of ``link`` as placed in the pose."""
        p = np.atleast_2d(np.asarray(p, dtype=float))
        frames = len(self.joints)
        if link == self.linkage.frame:
            return np.broadcast_to(p, (frames, *p.shape)).copy()
        a = self.anchor[link]
        theta = self.angles[:, link]
        c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
        origin = self.linkage.points[a] if a is not None else p.mean(axis=0)
        d = p - origin
        rotated = np.stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]], axis=-1)
        moved = self.joints[:, a][:, None, :] if a is not None else origin
        return rotated + moved


def _order(points: np.ndarray) -> list[int]:
    """Indices of distinct points in turning order about their centre (a link's plate)."""
    keep: list[int] = []
    for i, p in enumerate(points):
        if all(np.hypot(*(p - points[j])) > 1e-9 for j in keep):
            keep.append(i)
    centre = points[keep].mean(axis=0)
    return sorted(keep, key=lambda i: math.atan2(*(points[i] - centre)[::-1]))


def _elements(linkage: Linkage, joints: np.ndarray, angles: np.ndarray, tracers: dict[str, np.ndarray],
              paths: dict[str, list[np.ndarray]], reach: tuple[np.ndarray, np.ndarray] | None = None) -> list[dict]:
    """The drawing's elements at every frame (world coordinates): ``tag`` (polygon, polyline,
    circle, text), ``style`` (SVG attributes), ``frames`` (F, m, 2) and for circles ``r``, for
    texts ``text``.  ``paths`` (curves by name) are drawn as still curves (pins' paths under the links, coupler
    curves over them); ``reach`` (joints and angles of more steps than the frames) sets how long
    a slider's guide is drawn: over the block's whole travel."""
    chain, scale = linkage.chain, linkage.scale
    place = _Placement(linkage, joints, angles)
    pin = 0.018 * scale
    out: list[dict] = []
    colours = {name: _CURVES[i % len(_CURVES)] for i, name in enumerate(linkage.tracers)}

    def curves(of_tracers: bool) -> None:  # grey pin paths over the plates' fill, coupler curves over the links
        for name, lines in paths.items():
            for xy in lines:
                ok = xy[np.isfinite(xy).all(axis=1)]
                if len(ok) > 1 and (name in tracers) == of_tracers:
                    out.append({"tag": "polyline", "frames": ok[None], "static": True, "curve": True,
                                "style": {"fill": "none", "stroke": colours[name] if of_tracers else _PATH,
                                          "stroke-width": (1.8 if len(lines) == 1 else 0.9) if of_tracers else 1.0}})

    driven = {linkage.input_link(i) for i in range(linkage.dof)}
    slides = {k: np.array(v) for k, v in linkage.slides.items()}
    links = []  # the moving links: a plate's outline or a bar, drawn over the pin paths
    for link in range(chain.links):
        on = [k for k in linkage.joints_of(link) if linkage.kind(k) == REVOLUTE]  # sliders: a block and a guide
        if link == linkage.frame or not on:
            continue
        marks = [at for _, (carrier, at) in linkage.tracers.items() if carrier == link]  # a coupler's plate
        pose = np.array([*linkage.points[on], *marks])
        order = _order(pose)
        colour = _INPUT if link in driven else _EDGE
        if len(order) >= 3:  # its fill under the pins' paths (a rocker's pin swings under the coupler), its outline over
            out.append({"tag": "polygon", "frames": place.place(link, pose[order]),
                        "style": {"fill": _BODY, "stroke": "none"}})
            links.append({"tag": "polygon", "frames": place.place(link, pose[order]),
                          "style": {"fill": "none", "stroke": colour, "stroke-width": 1.4, "stroke-linejoin": "round"}})
        elif len(order) == 2:
            links.append({"tag": "polyline", "frames": place.place(link, pose[order]),
                          "style": {"fill": "none", "stroke": colour, "stroke-width": 3.2, "stroke-linecap": "round"}})
    curves(False)
    out += links
    for k in range(len(chain.joints)):  # gears: pitch circle and a spoke that turns with the gear
        if linkage.kind(k) != MESH:
            continue
        carrier = linkage.carrier(k)
        for gear in chain.joints[k]:
            axis = linkage.points[linkage.axis(gear, carrier)]
            radius = float(np.hypot(*(linkage.points[k] - axis)))
            out.append({"tag": "circle", "r": radius, "frames": place.place(gear, axis),
                        "style": {"fill": "none", "stroke": MESH.stroke, "stroke-width": 1.4}})
            out.append({"tag": "polyline", "frames": place.place(gear, [axis, linkage.points[k]]),
                        "style": {"fill": "none", "stroke": MESH.stroke, "stroke-width": 1.2}})
    span = _Placement(linkage, *reach) if reach is not None else place
    for k, d in slides.items():  # a prismatic pair: a slot or guide on one link, a block on the other
        guide, block = _guide_and_block(linkage, k)
        p = linkage.points[k]
        u = d / np.hypot(*d)
        theta = span.angles[:, guide] if guide != linkage.frame else np.zeros(len(span.angles))
        travel = _along(span.place(block, p)[:, 0] - span.place(guide, p)[:, 0], theta, u)
        pins = [float((linkage.points[m] - p) @ u) for m in linkage.joints_of(guide)
                if m != k and linkage.kind(m) == REVOLUTE]  # the guide reaches its own pins (a lever's pivot)
        # the joint's point is any point of its line (a synthesis leaves it where it lies): the block is
        # drawn where it is, at the foot of its pin nearest the line
        feet = [(abs(u[0] * (q[1] - p[1]) - u[1] * (q[0] - p[0])), float((q - p) @ u))
                for q in (linkage.points[m] for m in linkage.joints_of(block) if m != k and linkage.kind(m) == REVOLUTE)]
        at = min(feet)[1] if feet else 0.0
        p = p + at * u
        pins = [f - at for f in pins]
        half = 0.06 * scale
        reach_along = [0.0, *travel[np.isfinite(travel)], *pins]
        ends = [p + u * (min(reach_along) - 2 * half), p + u * (max(reach_along) + 2 * half)]
        out.append({"tag": "polyline", "frames": place.place(guide, ends),
                    "style": {"fill": "none", "stroke": _FRAME if guide == linkage.frame else _EDGE,
                              "stroke-width": 2.0, "stroke-dasharray": "5 3" if guide == linkage.frame else None}})
        for link in (guide, block):  # a pin off the line (an offset slot or slider): an arm to the line
            for m in linkage.joints_of(link):
                if m != k and linkage.kind(m) == REVOLUTE and link != linkage.frame:
                    foot = p + float((linkage.points[m] - p) @ u) * u
                    if math.dist(foot, linkage.points[m]) > 1e-9 * scale:
                        out.append({"tag": "polyline", "frames": place.place(link, [linkage.points[m], foot]),
                                    "style": {"fill": "none", "stroke": _EDGE, "stroke-width": 3.2,
                                              "stroke-linecap": "round"}})
        n = np.array([-u[1], u[0]])
        corners = [p - half * u - 0.6 * half * n, p + half * u - 0.6 * half * n,
                   p + half * u + 0.6 * half * n, p - half * u + 0.6 * half * n]
        out.append({"tag": "polygon", "frames": place.place(block, corners),
                    "style": {"fill": "white", "stroke": _INPUT if block in driven else PRISMATIC.stroke,
                              "stroke-width": 1.4}})
    base = [k for k in linkage.joints_of(linkage.frame) if linkage.kind(k) == REVOLUTE]
    if len(base) >= 2:  # the fixed link: a dashed line through its joints
        pose = linkage.points[base]
        out.append({"tag": "polygon" if len(base) > 2 else "polyline", "static": True,
                    "frames": pose[_order(pose)][None],
                    "style": {"fill": "none", "stroke": _FRAME, "stroke-width": 1.0, "stroke-dasharray": "6 4"}})
    for k, joint in enumerate(chain.joints):  # ground pivots under the frame's pins
        if linkage.frame in joint and linkage.kind(k) == REVOLUTE:
            support, base, *hatch = _ground_sign(linkage.points[k], pin)
            out.append({"tag": "polygon", "frames": support[None], "static": True,
                        "style": {"fill": "#eef1f4", "stroke": _FRAME, "stroke-width": 1.2}})
            out.append({"tag": "polyline", "static": True, "frames": base[None],
                        "style": {"fill": "none", "stroke": _FRAME, "stroke-width": 2.4}})
            out += [{"tag": "polyline", "static": True, "frames": stroke[None],
                     "style": {"fill": "none", "stroke": _FRAME, "stroke-width": 1.2}} for stroke in hatch]
    curves(True)
    for k, joint in enumerate(chain.joints):
        if linkage.kind(k) == REVOLUTE:
            out.append({"tag": "circle", "r": pin * (1.6 if len(joint) > 2 else 1.0), "frames": joints[:, k][:, None],
                        "style": {"fill": "white", "stroke": "#c0392b" if len(joint) > 2 else REVOLUTE.stroke,
                                  "stroke-width": 1.2}})
    for name, xy in tracers.items():
        colour = colours[name]
        out.append({"tag": "circle", "r": 0.8 * pin, "frames": xy[:, None],
                    "style": {"fill": colour, "stroke": colour, "stroke-width": 1.0}})
        out.append({"tag": "text", "text": name, "frames": xy[:, None] + np.array([1.6 * pin, 1.6 * pin]),
                    "style": {"fill": colour, "font-size": 12, "font-family": "sans-serif", "font-weight": "bold"}})
    return out


#: the hatch strokes under a ground pivot's base
_HATCH_STROKES = 5


def _ground_sign(at, pin: float) -> list[np.ndarray]:
    """A ground pivot's sign at ``at`` as a designer draws a fixed pivot (the sheets' sign, pointing down): its
    support (a triangle under the pin), its base line, and the short strokes hatched under the base that mark it
    fixed, ``pin`` the pins' radius.

    >>> [len(part) for part in _ground_sign((0.0, 0.0), 1.0)]
    [3, 2, 2, 2, 2, 2, 2]
    """
    x, y = at
    w = 2.6 * pin
    foot, half, step = y - 1.8 * w, 1.6 * w, 3.2 * w / _HATCH_STROKES
    return [np.array([[x, y], [x - w, foot], [x + w, foot]]), np.array([[x - half, foot], [x + half, foot]]),
            *(np.array([[x - half + (i + 1) * step, foot], [x - half + i * step, foot - 0.5 * w]])
              for i in range(_HATCH_STROKES))]


def _guide_and_block(linkage: Linkage, k: int) -> tuple[int, int]:
    """The two links of prismatic joint ``k`` as a designer draws them: the frame is the guide of a
    slider on it; otherwise the block is the link pinned nearest the sliding line (a block on a crank
    pin), the guide the other.  (The distance is to the line, not to the joint's point: that may be
    anywhere along it.)"""
    a, b = linkage.chain.joints[k]
    if linkage.frame in (a, b):
        return linkage.frame, b if a == linkage.frame else a
    p, u = linkage.points[k], np.asarray(linkage.slides[k], dtype=float) / math.hypot(*linkage.slides[k])

    def gap(link: int) -> float:
        pins = [abs(u[0] * (q[1] - p[1]) - u[1] * (q[0] - p[0]))
                for q in (linkage.points[m] for m in linkage.joints_of(link) if linkage.kind(m) == REVOLUTE)]
        return min(pins, default=math.inf)

    return (b, a) if gap(a) < gap(b) else (a, b)


def _along(local: np.ndarray, theta: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The block's displacement along the guide's direction ``u`` (as placed in the pose), from the
    world offsets ``local`` of the block from the guide's point, the guide turned by ``theta``."""
    c, s = np.cos(theta), np.sin(theta)
    back = np.stack([c * local[:, 0] + s * local[:, 1], -s * local[:, 0] + c * local[:, 1]], axis=-1)
    return back @ u


def _still(linkage: Linkage) -> tuple[np.ndarray, np.ndarray, dict]:
    """The pose alone as one frame: joints, link angles (all zero) and tracer points."""
    tracers = {name: np.array([at]) for name, (_, at) in linkage.tracers.items()}
    return linkage.points[None], np.zeros((1, linkage.chain.links)), tracers


def _frames(motion: Motion, count: int) -> np.ndarray:
    """Indices of up to ``count`` finite steps spread over the sweep."""
    ok = np.flatnonzero(np.isfinite(motion.joints).all(axis=(1, 2)) & np.isfinite(motion.angles).all(axis=1))
    if len(ok) <= count:
        return ok
    return ok[np.unique(np.linspace(0, len(ok) - 1, count).round().astype(int))]


def _box(elements: list[dict]) -> tuple[np.ndarray, np.ndarray]:
    """The lower-left and upper-right corners around every element at every frame (a circle whole)."""
    corners = np.array([[0.0, 0.0], [-1.0, -1.0], [1.0, 1.0]])[:, None, :]
    pts = np.concatenate([(e["frames"].reshape(-1, 2) + e.get("r", 0.0) * corners).reshape(-1, 2) for e in elements])
    pts = pts[np.isfinite(pts).all(axis=1)]
    return pts.min(axis=0), pts.max(axis=0)


#: the drawings' text: 9 pt bold (12 px of an SVG at the CSS inch's 96 px), a line's height and depth in ems
_FONT_PT, _LINE_EM, _DEPTH_EM = 9.0, 1.25, 0.3


def _text_size(text: str, per_inch: float) -> tuple[float, float, float]:
    """Width, height above the anchor and depth below it (px at ``per_inch``) of a drawing's text: the
    width as matplotlib sets the bold sans-serif, a whole line's height (matplotlib anchors a name's box
    bottom, an SVG its baseline: the box covers both)."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextToPath

    font = FontProperties(family="sans-serif", weight="bold", size=_FONT_PT)
    width = TextToPath().get_text_width_height_descent(text, font, ismath=False)[0]
    em = per_inch / 72
    return width * em, _LINE_EM * _FONT_PT * em, _DEPTH_EM * _FONT_PT * em


class _Canvas:
    """World coordinates to pixels: the box around every element at every frame, the texts' boxes
    whole (their size in pixels fixed, ``per_inch`` to the inch), ``size`` pixels on its longer side,
    y upwards on the page."""

    def __init__(self, elements: list[dict], size: int, per_inch: float = 96):
        lo, hi = _box(elements)
        texts = [(e["frames"].reshape(-1, 2), _text_size(e["text"], per_inch)) for e in elements if e["tag"] == "text"]
        shape = lo, hi
        for _ in range(20):  # the texts widen the box, which shrinks the scale, which widens the texts
            span = max(float((hi - lo).max()), 1e-9)
            scale = size / (1.12 * span)
            grown = [shape[0], shape[1]]
            for at, (w, h, d) in texts:
                ok = at[np.isfinite(at).all(axis=1)]
                if len(ok):
                    grown += [ok.min(axis=0) - np.array([0.0, d / scale]), ok.max(axis=0) + np.array([w, h]) / scale]
            wider_lo, wider_hi = np.min(grown, axis=0), np.max(grown, axis=0)
            if np.allclose((wider_lo, wider_hi), (lo, hi), rtol=0, atol=1e-6 * span):
                break
            lo, hi = wider_lo, wider_hi
        span = max(float((hi - lo).max()), 1e-9)
        margin = 0.06 * span
        self.lo, self.scale = lo - margin, size / (span + 2 * margin)
        self.width = int(math.ceil((hi[0] - lo[0] + 2 * margin) * self.scale))
        self.height = int(math.ceil((hi[1] - lo[1] + 2 * margin) * self.scale))

    def pixels(self, xy: np.ndarray) -> np.ndarray:
        out = (xy - self.lo) * self.scale
        out[..., 1] = self.height - out[..., 1]
        return out


def _attrs(style: dict) -> str:
    return " ".join(f'{k}="{v}"' for k, v in style.items() if v is not None)


def _coords(points: np.ndarray) -> str:
    return " ".join(f"{x:.1f},{y:.1f}" for x, y in points)


def _svg(elements: list[dict], canvas: _Canvas, frame: int | None, *, seconds: float = 0.0, player: bool = False,
         title: str | None = None) -> str:
    """The SVG text: still at ``frame``, or animated (SMIL) over all frames in ``seconds``, or with
    ``player`` the elements numbered for the site's script (``data-k``) and the frames as JSON."""
    w, h = canvas.width, canvas.height
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}"'
           + (' class="moving"' if player else "") + ">"]
    if title:
        out.append(f"<title>{html.escape(title)}</title>")
    data = []
    for e in elements:
        frames = canvas.pixels(e["frames"])
        static = e.get("static") or len(frames) == 1
        at = frames[0 if static or frame is None else frame]
        style = _attrs(e["style"])
        key = ""
        if player and not static:
            key = f' data-k="{len(data)}"'
            data.append([[round(float(v), 1) for v in f.ravel()] for f in frames])
        animated = not static and not player and frame is None
        if e["tag"] == "circle":
            head = f'<circle cx="{at[0, 0]:.1f}" cy="{at[0, 1]:.1f}" r="{e["r"] * canvas.scale:.1f}" {style}{key}'
            values = [("cx", ";".join(f"{f[0, 0]:.1f}" for f in frames)), ("cy", ";".join(f"{f[0, 1]:.1f}" for f in frames))]
        elif e["tag"] == "text":
            head = f'<text x="{at[0, 0]:.1f}" y="{at[0, 1]:.1f}" {style}{key}'
            values = [("x", ";".join(f"{f[0, 0]:.1f}" for f in frames)), ("y", ";".join(f"{f[0, 1]:.1f}" for f in frames))]
        else:
            head = f'<{e["tag"]} points="{_coords(at)}" {style}{key}'
            values = [("points", ";".join(_coords(f) for f in frames))]
        body = "".join(f'<animate attributeName="{name}" dur="{seconds:.2f}s" repeatCount="indefinite" '
                       f'values="{v}"/>' for name, v in values) if animated else ""
        text = html.escape(e["text"]) if e["tag"] == "text" else ""
        out.append(f"{head}>{body}{text}</{e['tag']}>" if body or text else f"{head}/>")
    out.append("</svg>")
    svg = "".join(out)
    if player:
        blob = html.escape(json.dumps({"n": len(elements[0]["frames"]) if not data else len(data[0]), "e": data},
                                      separators=(",", ":")), quote=True)
        svg = svg.replace('class="moving">', f'class="moving" data-motion="{blob}">', 1)
    return svg


def _paths(motion: Motion, most: int = 2000) -> dict[str, list[np.ndarray]]:
    """The curves a picture shows, thinned to ``most`` points each: the paths of the pins that
    move (not on the frame) under every tracer's coupler curve.  Of a grid of inputs, the images of
    up to 25 of its lines along each input (the workspace, as a mesh), cut where the branch does
    not reach."""
    linkage = motion.linkage
    pins = [k for k in range(len(linkage.chain.joints))
            if linkage.kind(k) == REVOLUTE and linkage.frame not in linkage.chain.joints[k]]
    curves = {joint_name(linkage.chain, k): motion.joints[:, k] for k in pins} | dict(motion.tracers)
    if motion.grid is None:
        keep = np.unique(np.linspace(0, motion.steps - 1, min(most, motion.steps)).round().astype(int))
        return {name: [xy[keep]] for name, xy in curves.items()}
    return {name: _grid_lines(xy.reshape(*motion.grid, 2)) for name, xy in curves.items()}


def _grid_lines(grid: np.ndarray, most: int = 25) -> list[np.ndarray]:
    """The images (runs of reached points) of up to ``most`` lines of a grid along each of its axes."""
    lines = []
    for axis in range(grid.ndim - 1):
        along = np.moveaxis(grid, axis, -2).reshape(-1, grid.shape[axis], 2)
        for line in along[np.unique(np.linspace(0, len(along) - 1, min(most, len(along))).round().astype(int))]:
            ok = np.isfinite(line).all(axis=1)
            cuts = np.flatnonzero(np.diff(ok.astype(int))) + 1
            lines += [run for run, good in zip(np.split(line, cuts), np.split(ok, cuts)) if good[0] and len(run) > 1]
    return lines


def _motion_elements(motion: Motion, frames: int, numbers: bool = False) -> tuple[list[dict], np.ndarray]:
    """The elements of up to ``frames`` frames spread over the sweep (with ``numbers`` each link's number moving
    with it), and the steps they show."""
    steps = _frames(motion, frames)
    if len(steps) == 0:
        raise InvalidOption("the sweep has no step where the mechanism is assembled: there is nothing to draw")
    tracers = {name: xy[steps] for name, xy in motion.tracers.items()}
    joints, angles = motion.joints[steps], motion.angles[steps]
    elements = _elements(motion.linkage, joints, angles, tracers, _paths(motion))
    if numbers:
        elements += _link_numbers(motion.linkage, _Placement(motion.linkage, joints, angles))
    return elements, steps


# ------------------------------------------------------------------ public writers
def linkage_svg(linkage: Linkage, *, size: int = 360) -> str:
    """A linkage in its pose as SVG text (what a notebook shows): links, ground pivots, sliders,
    gears and tracer points with their names.

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]],
    ...              tracers={"P": (2, (2.5, 2.5))})
    >>> ">P</text>" in linkage_svg(lk)
    True
    """
    joints, angles, tracers = _still(linkage)
    elements = _elements(linkage, joints, angles, tracers, {})
    return _svg(elements, _Canvas(elements, size), 0, title=_title(linkage))


def motion_svg(motion: Motion, *, size: int = 480, frames: int = 90, seconds: float = 3.0) -> str:
    """An animated SVG (SMIL, plays in any browser) of a sweep: the mechanism moving over its
    joints' paths and coupler curves, ``frames`` frames in ``seconds`` a cycle.

    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.motion import sweep
    >>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3, 3]])
    >>> motion_svg(sweep(four_bar, steps=19), frames=10).count('repeatCount="indefinite"') > 4
    True
    """
    elements, _ = _motion_elements(motion, frames)
    return _svg(elements, _Canvas(elements, size), None, seconds=seconds, title=_title(motion.linkage))


def player_svg(motion: Motion, *, size: int = 300, frames: int = 36, seconds: float = 3.0) -> str:
    """The SVG of a sweep for a web page's script: its moving elements carry ``data-k`` and the
    frames (pixels, one decimal) are in ``data-motion`` as JSON ``{"n": frames, "e": [...]}``; the
    script :data:`PLAYER_SCRIPT` plays them, ``seconds`` a cycle (a click pauses and resumes it).  Each
    link's number moves with it (the page names links and joints by them).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.motion import sweep
    >>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3, 3]])
    >>> 'data-motion="{&quot;n&quot;:12' in player_svg(sweep(four_bar, steps=37), frames=12)
    True
    """
    elements, _ = _motion_elements(motion, frames, numbers=True)
    svg = _svg(elements, _Canvas(elements, size), 0, player=True, title=_title(motion.linkage))
    return svg.replace('class="moving"', f'class="moving" data-ms="{1000 * seconds / max(frames, 1):.0f}"', 1)


#: plays every ``svg.moving`` of a page: each tick puts the next frame's points on its elements; a click on the
#: drawing pauses it, another resumes it
PLAYER_SCRIPT = """
document.querySelectorAll('svg.moving').forEach(function (svg) {
  var m = JSON.parse(svg.getAttribute('data-motion')), els = svg.querySelectorAll('[data-k]'), f = 0, paused = false;
  svg.style.cursor = 'pointer';
  svg.addEventListener('click', function () { paused = !paused; });
  setInterval(function () {
    if (paused) { return; }
    f = (f + 1) % m.n; svg.setAttribute('data-frame', f);
    els.forEach(function (el) {
      var v = m.e[+el.getAttribute('data-k')][f], t = el.tagName;
      if (t === 'circle') { el.setAttribute('cx', v[0]); el.setAttribute('cy', v[1]); }
      else if (t === 'text') { el.setAttribute('x', v[0]); el.setAttribute('y', v[1]); }
      else { el.setAttribute('points', v.join(' ')); }
    });
  }, +svg.getAttribute('data-ms') || 80);
});
"""


def _title(linkage: Linkage) -> str:
    names = ", ".join(joint_name(linkage.chain, k) for k in linkage.inputs)
    return f"{linkage.chain.compact()}, frame {linkage.frame}, input {names}"


def _check_suffix(out: str | Path, allowed: tuple[str, ...], what: str) -> Path:
    path = Path(out)
    if path.suffix.lower() not in allowed:
        raise InvalidOption(f"{what} is written as {' or '.join(s[1:].upper() for s in allowed)}: end the file name in "
                            f"{' or '.join(allowed)}, not {path.name!r}")
    return path


def _draw_matplotlib(ax, elements: list[dict], canvas: _Canvas, frame: int) -> None:
    from matplotlib.patches import Circle, Polygon

    for order, e in enumerate(elements):  # painted in the order of the list, as in the SVG
        frames = canvas.pixels(e["frames"])
        at = frames[0 if e.get("static") or len(frames) == 1 else frame]
        st = e["style"]
        width = float(st.get("stroke-width", 1.0)) * 0.75
        dash = (0, (4, 2)) if st.get("stroke-dasharray") else "solid"
        if e["tag"] == "circle":
            fill = st.get("fill", "none")
            ax.add_patch(Circle(at[0], e["r"] * canvas.scale, facecolor="none" if fill == "none" else fill,
                                edgecolor=st["stroke"], lw=width, zorder=order))
        elif e["tag"] == "text":
            ax.text(at[0, 0], at[0, 1], e["text"], color=st["fill"], fontsize=9, fontweight="bold",
                    zorder=len(elements) + order, va="bottom")  # (a name over everything, the marks too)
        elif e["tag"] == "polygon":
            fill = st.get("fill", "none")
            ax.add_patch(Polygon(at, closed=True, facecolor="none" if fill == "none" else fill, edgecolor=st["stroke"],
                                 lw=width, linestyle=dash, joinstyle="round", zorder=order))
        else:
            ax.plot(at[:, 0], at[:, 1], color=st["stroke"], lw=width, linestyle=dash, solid_capstyle="round",
                    zorder=order)
    ax.set_xlim(0, canvas.width)
    ax.set_ylim(canvas.height, 0)
    ax.set_aspect("equal")
    ax.axis("off")


def _figure(canvas: _Canvas, dpi: int, title: str):
    """A figure of the canvas's pixels at ``dpi`` under a strip with the title, wrapped to the
    figure's width (a tall, narrow mechanism's title takes two lines rather than being cut)."""
    import textwrap

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = textwrap.wrap(title, max(20, int(canvas.width / dpi * 72 / (9 * 0.6)))) or [""]
    strip = 0.3 + 0.16 * (len(lines) - 1)  # inches
    fig = plt.figure(figsize=(canvas.width / dpi, canvas.height / dpi + strip), dpi=dpi)
    ax = fig.add_axes([0, 0, 1, canvas.height / (canvas.height + strip * dpi)])
    fig.suptitle("\n".join(lines), fontsize=9, y=0.995, va="top")
    return fig, ax


def draw_motion(motion: Motion, out: str | Path, *, size: int = 600, title: str | None = None,
                marks: np.ndarray | None = None) -> None:
    """The mechanism in its pose with every tracer's coupler curve (coloured, labelled) and the
    paths of its moving pins (grey), to scale (a scale bar of a round length under it), to a PNG or
    SVG file; ``marks`` (N, 2) are drawn as hollow circles over them (the points a synthesis was
    asked to pass).

    >>> import os, re, tempfile
    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.motion import sweep
    >>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3, 3]],
    ...                    tracers={"P": (2, (2, 4))})
    >>> out = os.path.join(tempfile.mkdtemp(), "coupler.svg")
    >>> draw_motion(sweep(four_bar, steps=37), out)
    >>> re.findall(r">([^<]+)</text>", open(out).read())  # the scale bar (1 length unit), the tracer's name
    ['1', 'P']
    """
    path = _check_suffix(out, PICTURE_SUFFIXES, "a picture of a motion")
    elements = _motion_picture(motion, marks)
    _write_still(elements, _Canvas(elements, size, 100), path, title or _title(motion.linkage), 100)


def _motion_picture(motion: Motion, marks: np.ndarray | None) -> list[dict]:
    """The elements of :func:`draw_motion`'s picture: the pose over its paths and coupler curves, the
    ``marks`` as hollow circles, a scale bar under them."""
    linkage = motion.linkage
    if len(_frames(motion, 2)) == 0:
        raise InvalidOption("the sweep has no step where the mechanism is assembled: there is nothing to draw")
    joints, angles, tracers = _still(linkage)
    keep = np.unique(np.linspace(0, motion.steps - 1, min(2000, motion.steps)).round().astype(int))
    elements = _elements(linkage, joints, angles, tracers, _paths(motion),  # the pose, over its paths
                         reach=(motion.joints[keep], motion.angles[keep]))
    marks = np.zeros((0, 2)) if marks is None else np.asarray(marks, dtype=float).reshape(-1, 2)
    radius = 0.014 * linkage.scale
    if len(marks) > 1:  # no wider than a third of the nearest two marks' gap (72 points of a closed path, their
        gaps = np.hypot(*(marks[:, None] - marks[None]).transpose(2, 0, 1))  # circles overlapping, hid its curve)
        np.fill_diagonal(gaps, np.inf)
        radius = min(radius, max(gaps.min() / 3, 0.004 * linkage.scale))
    for xy in marks:
        elements.append({"tag": "circle", "r": radius, "frames": xy[None, None], "static": True,
                         "style": {"fill": "none", "stroke": _MARK, "stroke-width": 1.6}})
    elements[:0] = _scale_bar(elements)  # under everything
    return elements


def draw_motion_sheet(panels: list[tuple[Motion, np.ndarray | None, str]], out: str | Path, *, columns: int = 3,
                      size: float = 3.6, dpi: int = 100) -> None:
    """A sheet of :func:`draw_motion`'s pictures, one panel per ``(motion, marks, title)``, ``columns``
    to a row, each ``size`` inches on its longer side and to its own scale (a scale bar in each): the
    rows of an atlas search side by side.  A title wider than its panel is set smaller to fit it.  PNG or
    SVG (both by matplotlib).

    >>> import os, tempfile
    >>> from PIL import Image
    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.motion import sweep
    >>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3, 3]],
    ...                    tracers={"P": (2, (2, 4))})
    >>> out = os.path.join(tempfile.mkdtemp(), "rows.png")
    >>> motion = sweep(four_bar, steps=37)
    >>> draw_motion_sheet([(motion, None, "1"), (motion, None, "2"), (motion, None, "3")], out, columns=2)
    >>> Image.open(out).size  # two columns of 3.6 in, two rows of 3.6 in under a 0.45 in title, at 100 dpi
    (720, 810)
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .draw import check_pixels

    path = _check_suffix(out, PICTURE_SUFFIXES, "a sheet of motions")
    if not panels:
        raise InvalidOption("nothing to draw: the sheet has no panel")
    columns = min(columns, len(panels))
    rows = math.ceil(len(panels) / columns)
    cell, strip = size, 0.45  # inches: a panel's drawing, and its title's strip above it
    check_pixels(path, columns * cell, rows * (cell + strip), dpi)
    fig = plt.figure(figsize=(columns * cell, rows * (cell + strip)), dpi=dpi)
    try:
        for k, (motion, marks, title) in enumerate(panels):
            elements = _motion_picture(motion, marks)
            canvas = _Canvas(elements, round(cell * dpi), dpi)
            row, column = divmod(k, columns)
            ax = fig.add_axes([column / columns, 1 - (row + 1) / rows, 1 / columns, cell / (cell + strip) / rows])
            _draw_matplotlib(ax, elements, canvas, 0)
            side = round(cell * dpi)  # every panel the same square, its drawing in the middle
            dx, dy = (side - canvas.width) / 2, (side - canvas.height) / 2
            ax.set_xlim(-dx, canvas.width + dx)
            ax.set_ylim(canvas.height + dy, -dy)
            text = fig.text((column + 0.5) / columns, 1 - (row * (cell + strip) + 0.06) / (rows * (cell + strip)),
                            title, ha="center", va="top", fontsize=9)
            wide = text.get_window_extent(fig.canvas.get_renderer()).width
            if wide > 0.96 * side:  # a long chain's or a mark's line: smaller, within its panel
                text.set_fontsize(9 * 0.96 * side / wide)
        save_figure(fig, path, dpi=dpi)
    except OSError as exc:
        raise InvalidOption(f"cannot write {path}: {exc.strerror or exc}") from None
    finally:
        plt.close(fig)


def _write_still(elements: list[dict], canvas: _Canvas, path: Path, title: str, dpi: int) -> None:
    """One still picture: SVG by this module's writer, PNG (or PDF) by matplotlib at ``dpi``."""
    try:
        if path.suffix.lower() == ".svg":
            path.write_text(_svg(elements, canvas, 0, title=title))
            return
        import matplotlib.pyplot as plt

        fig, ax = _figure(canvas, dpi, title)
        try:
            _draw_matplotlib(ax, elements, canvas, 0)
            save_figure(fig, path, dpi=dpi)
        finally:
            plt.close(fig)
    except OSError as exc:
        raise InvalidOption(f"cannot write {path}: {exc.strerror or exc}") from None


#: a link number's box (width per digit, height) as a share of the drawing's size, at the default size
_NUMBER_BOX = np.array([0.026, 0.036])


def _link_numbers(linkage: Linkage, place: _Placement | None = None) -> list[dict]:
    """Each link's number (the chain's numbering) beside the middle of its pins in the pose, as a
    chain's drawing numbers its links: of a few places beside it (either side of a bar, along it; about
    a plate's middle), the first clear of every pin, ground pivot, bar and number drawn, else the
    clearest (a short crank's number once stood on its ground pivot, the frame's on a pivot's base).
    With ``place`` (the frames of a motion) each number moves with its link, on a light box as the sheets'
    numbers stand (the other links pass under it)."""
    scale = linkage.scale
    lift = 0.045 * scale
    p = linkage.points
    pin = 0.018 * scale
    # what a number must not stand on: each link's bars (the frame's dashed line), ground pivots, pins, tracers
    segments = []
    for link in range(linkage.chain.links):
        on = [k for k in linkage.joints_of(link) if linkage.kind(k) == REVOLUTE]
        segments += [(p[i], p[j]) for a, i in enumerate(on) for j in on[a + 1:]]
    for k, joint in enumerate(linkage.chain.joints):
        if linkage.frame in joint and linkage.kind(k) == REVOLUTE:
            support, *lines = _ground_sign(p[k], pin)
            segments += [(support[0], support[1]), (support[0], support[2]), *map(tuple, lines)]
    dots = [*p[[k for k in range(len(p)) if linkage.kind(k) == REVOLUTE]], *(at for _, at in linkage.tracers.values())]
    samples = [np.asarray(dot, dtype=float)[None] for dot in dots]
    for a, b in segments:
        count = 2 + int(math.dist(a, b) / (0.01 * scale))
        samples.append(np.linspace(a, b, min(count, 400)))
    obstacles = np.concatenate(samples) if samples else np.zeros((0, 2))
    placed: list[np.ndarray] = []

    def clearance(centre: np.ndarray, half: np.ndarray) -> float:
        pts = np.concatenate([obstacles, *placed]) if placed else obstacles
        gap = np.maximum(np.abs(pts - centre) - half, 0.0)
        return float(np.hypot(gap[:, 0], gap[:, 1]).min(initial=math.inf))

    out = []
    for link in range(linkage.chain.links):
        on = list(linkage.joints_of(link))
        pins = [k for k in on if linkage.kind(k) == REVOLUTE] or on
        middle = p[pins].mean(axis=0)
        half = _NUMBER_BOX * [len(str(link)), 1] * scale / 2
        if len(pins) == 2:  # a bar: beside it, not on it; the upper side first, its middle first
            d = p[pins[1]] - p[pins[0]]
            n = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-300)
            n = n if n[1] >= 0 else -n
            centres = [p[pins[0]] + t * d + side * (lift + float(np.abs(n) @ half)) * n
                       for side, t in ((1, 0.5), (-1, 0.5), (1, 0.3), (1, 0.7), (-1, 0.3), (-1, 0.7))]
        elif len(pins) == 1:  # a slider's block, a crank's frame: off the pin (the frame's off its pivot's base)
            first = np.array([2.0, -1.1]) if link == linkage.frame else np.array([1.0, 1.0])
            centres = [middle + lift * v + half for v in np.array([first, [-2.0, -1.1], [1.0, -1.0], [-1.6, 1.0]])]
        else:  # a plate: its middle, else towards one of its pins
            centres = [middle] + [middle + 0.35 * (p[k] - middle) for k in pins]
        gaps = [clearance(c, half) for c in centres]
        clear = [c for c, g in zip(centres, gaps) if g >= 0.25 * lift]
        centre = clear[0] if clear else centres[int(np.argmax(gaps))]
        placed.append(np.array([centre + half * [sx, sy] for sx in (-1, 0, 1) for sy in (-1, 0, 1)]))
        style = {"fill": _FRAME if link == linkage.frame else _EDGE, "font-size": 12, "font-family": "sans-serif"}
        if place is None:
            out.append({"tag": "text", "text": str(link), "frames": (centre - half)[None, None], "static": True,
                        "style": style})
            continue
        fixed = link == linkage.frame
        at = centre[None, None] if fixed else place.place(link, centre)  # the box's centre at every frame, upright
        pad = half + 0.1 * _NUMBER_BOX[1] * scale
        out.append({"tag": "polygon", "frames": at + pad * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]),
                    "static": fixed, "style": {"fill": "white", "fill-opacity": 0.8, "stroke": "none"}})
        out.append({"tag": "text", "text": str(link), "frames": at - half, "static": fixed, "style": style})
    return out


def _scale_bar(elements: list[dict]) -> list[dict]:
    """A bar of a round length (1, 2 or 5 × 10^k, at most a third of the drawing's width) under the
    drawing, with its length written beside it: the drawing is to scale, in the linkage's unit."""
    lo, hi = _box(elements)
    span = float((hi - lo).max())
    third = (float(hi[0] - lo[0]) or span) / 3
    unit = 10.0 ** math.floor(math.log10(third))
    length = max(m * unit for m in (1, 2, 5) if m * unit <= third)
    x, y, tick = float(lo[0]), float(lo[1]) - 0.08 * span, 0.02 * span
    style = {"fill": "none", "stroke": _FRAME, "stroke-width": 1.4}
    return [{"tag": "polyline", "static": True, "style": style,
             "frames": np.array([[[x, y + tick], [x, y], [x + length, y], [x + length, y + tick]]])},
            {"tag": "text", "text": f"{length:g}", "static": True, "frames": np.array([[[x + length + tick, y]]]),
             "style": {"fill": _FRAME, "font-size": 12, "font-family": "sans-serif"}}]


def draw_linkage(linkage: Linkage, out: str | Path, *, size: float = 3.6, dpi: int = 150, title: str | None = None,
                 labels: bool = True) -> None:
    """A dimensioned linkage in its pose, to scale (a scale bar of a round length in its unit under
    it): links, ground pivots, sliders, gears, tracer points and, unless ``labels=False``, each
    link's number; PNG, SVG or PDF, ``size`` inches on its longer side, ``dpi`` a PNG's resolution.
    Pose it elsewhere first with :func:`synth.motion.assemble`.

    >>> import os, re, tempfile
    >>> from synth.structure.chain import Chain, Mechanism
    >>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3, 3]])
    >>> out = os.path.join(tempfile.mkdtemp(), "four_bar.svg")
    >>> draw_linkage(four_bar, out, labels=False)
    >>> re.findall(r">([^<]+)</text>", open(out).read())  # the scale bar: 1 length unit (the links are 1 … 4)
    ['1']
    """
    from .draw import check_pixels, check_size

    path = _check_suffix(out, (".png", ".svg", ".pdf"), "a drawing of a linkage")
    check_size(size, dpi)
    per_inch = dpi if path.suffix.lower() == ".png" else 96  # a vector file's pixels are the CSS inch's 96
    joints, angles, tracers = _still(linkage)
    elements = _elements(linkage, joints, angles, tracers, {})
    elements += _link_numbers(linkage) if labels else []
    elements += _scale_bar(elements)
    canvas = _Canvas(elements, round(size * per_inch), per_inch)
    check_pixels(path, canvas.width / per_inch, canvas.height / per_inch, per_inch)
    _write_still(elements, canvas, path, title or _title(linkage), per_inch)


def animate_motion(motion: Motion, out: str | Path, *, frames: int = 60, seconds: float = 3.0, size: int = 480,
                   progress: bool = False) -> int:
    """An animation of the sweep: a GIF (``frames`` frames drawn by matplotlib, looping) or an
    animated SVG (SMIL).  Returns the number of frames written.

    >>> import os, tempfile
    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.motion import sweep
    >>> four_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3, 3]])
    >>> animate_motion(sweep(four_bar, steps=37), os.path.join(tempfile.mkdtemp(), "four_bar.gif"), frames=6)
    6
    """
    path = _check_suffix(out, ANIMATION_SUFFIXES, "an animation")
    if not 2 <= frames <= 1000:
        raise InvalidOption(f"an animation has 2 … 1000 frames, not {frames}")
    elements, steps = _motion_elements(motion, frames)
    canvas = _Canvas(elements, size, 100)
    try:
        if path.suffix.lower() == ".svg":
            path.write_text(_svg(elements, canvas, None, seconds=seconds, title=_title(motion.linkage)))
            return len(steps)
        import matplotlib.pyplot as plt
        from PIL import Image

        images = []
        bar = None
        if progress:
            from .execution.progress import Progress

            bar = Progress(len(steps), "frames", desc="animation")
        fig, ax = _figure(canvas, 100, _title(motion.linkage))
        try:
            for i in range(len(steps)):
                ax.clear()
                _draw_matplotlib(ax, elements, canvas, i)
                fig.canvas.draw()
                rgba = np.asarray(fig.canvas.buffer_rgba())
                images.append(Image.fromarray(rgba[..., :3].copy()).quantize(colors=64))
                if bar is not None:
                    bar.update()
        finally:
            plt.close(fig)
            if bar is not None:
                bar.close()
        images[0].save(path, save_all=True, append_images=images[1:], loop=0,
                       duration=max(20, int(1000 * seconds / len(images))), optimize=True)
        return len(images)
    except OSError as exc:
        raise InvalidOption(f"cannot write {path}: {exc.strerror or exc}") from None
