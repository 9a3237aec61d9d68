"""The synthesis problem of one topology: its unknowns, how a vector of them becomes a linkage, and
the error and constraint violations of that linkage against the target.

The unknowns are the joint positions of the assembled pose (a prismatic joint also its sliding
direction), the tracer point, and — without timing — the input values at the target points, all
non-dimensional: a position is the target's centre plus the target's size times the unknown.
The pose is the mechanism at the first target point (its input offset is 0), so every candidate
is assembled by construction, on the assembly branch of its own pose: the dyads' closed forms keep
the pose's assembly mode at every input (no branch defect can occur); a candidate whose input
meets a dead position between the target points is penalised (a circuit defect).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace

import numpy as np

from mechbase.pairs import finite_pair

from ..errors import BadTarget, DimensionError, MotionError, option
from ..structure.joints import MESH, PRISMATIC, REVOLUTE
from ..motion import Linkage, assemble, link_poses
from ._target import FunctionTarget, MotionTarget, PathTarget

__all__ = ["Constraints", "Problem", "link_ratio", "input_joint_of", "placement", "read_order"]

#: the widest step (rad, or target sizes for a slide) between the inputs where the dyads must close
SPAN_STEP = 0.02
#: samples of a full turn of the input where a crank's dyads must close
TURN_SAMPLES = 72
#: rounds of the search between two samples for a dyad's least discriminant (each narrows it fourfold:
#: six take a crank's 5° between samples to 0.003°, where a parabola through the last three is exact)
DIP_ROUNDS = 6
#: samples of the traced curve, each way from the pose, for a target without timing (global stage)
CURVE_SAMPLES = 120
#: a dyad's discriminant this far below 0 still closes (a target point at a dead position, up to rounding)
ROUNDING = 1e-12
#: the search aims this far inside each of the designer's limits (rad, relative, target sizes)
MARGIN = 1e-4
#: the cost of a candidate that cannot reach the target on its branch (plus the share of samples lost)
INFEASIBLE = 1e3
#: a link-length order's violation row in the search is (log(shorter / longer) + MARGIN)⁺, as the other
#: constraints'; the answer is then polished with the link-length constraints (orders, the length and ratio
#: bounds) as inequality constraints, held this far inside their bounds (``_Search.stiffen``): met to 1e-9
#: at a cost of 1e-10 of the lengths, where MARGIN alone cost 0.6 % of CE2's error and 0.04 % of the ten
#: points' of [HCDJ] under a length bound of 80
HELD_MARGIN = 1e-10
#: the least frame length along a fixed frame direction (target sizes)
SHORTEST_FRAME = 1e-3
#: a designer's constraint is met within this (rad, log-ratio, target sizes)
MET = 1e-9


@dataclass(frozen=True)
class Constraints:
    """What a designer asks of the mechanism besides the target.

    Parameters
    ----------
    crank : bool
        The input turns fully (a crank) on the pose's branch.
    rocker : (float, float), optional
        The input rocks within these limits (rad, absolute input angle; or lengths for a slide)
        while it passes the target.
    min_transmission : float
        Least transmission angle (rad) of every dyad between the target's inputs (over the whole
        turn for a crank): the angle stays within [μ, π − μ].  0 asks nothing.
    max_ratio : float, optional
        Bound on the longest over the shortest distance between two joints of one link (the frame
        included).
    max_length : float, optional
        Bound on every distance between two joints of one link, the frame's pivots included (target
        units; the tracer point is no joint and is not bound).
    pivots : (x0, x1, y0, y1), optional
        A box the frame's joints (fixed pivots, slide lines' points) must lie in.
    reach : float, optional
        The search box: every joint within ``reach`` target sizes of the target's centre (default 4;
        for a function, frame lengths from the input pivot, default 2; for a slider's function, its largest
        displacement, default 2, or with a free origin its stroke about the stroke's middle, default 8).
    pivot_at : dict joint -> (x, y), optional
        Revolute joints of the frame held at given points (a joint named by its links, ``"0-1"``, or by
        its index).  They are no unknowns: the search places the mechanism about them.
    frame_angle : float, optional
        The frame line's direction (rad, from the x axis): the line from the input pivot to
        ``frame_line``.  Its far end then moves along it only.
    frame_line : joint, optional
        The revolute joint of the frame at the frame line's far end (default: the frame's only other
        joint; named when the frame has more), for ``frame_angle`` or an absolute timing.
    timing : "relative" or "absolute"
        A timed path's inputs counted from the first point's (relative: the crank may start anywhere)
        or the input's angles from the frame line (absolute), as a function's are; the frame line's
        direction is then ``frame_angle`` where given, else free (found with the rest).
    order : tuple of str
        Link-length orders, each written ``"1 <= 2 <= 3 <= 0"`` (link numbers; ``>=`` for a
        descending one) or, for a four-bar, in its classical names ``"r2 <= r3 <= r4 <= r1"`` (r1 the
        frame, r2 the input link, r3 the coupler, r4 the output link).  Each named link is a binary
        link; its length is the distance between its two pins.

    Examples
    --------
    >>> Constraints(crank=True, min_transmission=math.radians(30)).crank
    True
    >>> c = Constraints(pivot_at={"0-1": (0, 0)}, frame_angle=0.0, timing="absolute", order=("r2<=r3<=r4<=r1",))
    >>> c.pivot_at, c.order
    ((('0-1', (0.0, 0.0)),), ('r2<=r3<=r4<=r1',))
    """

    crank: bool = False
    rocker: tuple[float, float] | None = None
    min_transmission: float = 0.0
    max_ratio: float | None = None
    max_length: float | None = None
    pivots: tuple[float, float, float, float] | None = None
    reach: float | None = None
    pivot_at: tuple = ()
    frame_angle: float | None = None
    frame_line: int | str | None = None
    timing: str = "relative"
    order: tuple[str, ...] = ()

    def __post_init__(self):
        if not isinstance(self.crank, (bool, np.bool_)):
            raise DimensionError(f"crank is True or False, not {self.crank!r}")
        if self.crank and self.rocker is not None:
            raise DimensionError("the input cannot be both a crank (a full turn) and a rocker within limits")
        if self.rocker is not None:
            limits = f"the rocker's limits must be two finite numbers, lower first, not {self.rocker}"
            lo, hi = finite_pair(self.rocker, error=DimensionError, malformed=limits)
            if not lo < hi:
                raise DimensionError(limits)
            object.__setattr__(self, "rocker", (lo, hi))
        mu = _real(self.min_transmission, f"the least transmission angle must be a number (rad), not {self.min_transmission}")
        if not 0 <= mu < math.pi / 2:
            raise DimensionError(f"the least transmission angle must be 0 … 90° (exclusive), not {math.degrees(mu):g}°")
        object.__setattr__(self, "min_transmission", mu)
        self._number("max_ratio", f"the link-length ratio bound must be a number above 1, not {self.max_ratio}",
                     lambda r: math.isfinite(r) and r > 1)
        self._number("max_length", f"the link-length bound must be a positive length, not {self.max_length}",
                     lambda length: math.isfinite(length) and length > 0)
        self._number("reach", f"the search reach must be a positive number of target sizes, not {self.reach}",
                     lambda r: math.isfinite(r) and r > 0)
        if self.pivots is not None:
            box = f"the pivots' region must be four finite numbers x0 < x1, y0 < y1, not {self.pivots}"
            if isinstance(self.pivots, (str, bytes, dict)) or not hasattr(self.pivots, "__len__") or len(self.pivots) != 4:
                raise DimensionError(box)
            x0, x1, y0, y1 = (_real(v, box) for v in self.pivots)
            if not all(map(math.isfinite, (x0, x1, y0, y1))) or x0 >= x1 or y0 >= y1:
                raise DimensionError(box)
            object.__setattr__(self, "pivots", (x0, x1, y0, y1))
        self._check_placing()
        if self.max_length is not None:
            held = self.pivot_at
            for i, (a, p) in enumerate(held):
                for b, q in held[i + 1:]:
                    if math.dist(p, q) > self.max_length:
                        raise DimensionError(f"the fixed pivots of joints {a} and {b} lie {math.dist(p, q):g} apart, "
                                             f"beyond the link-length bound {self.max_length:g}")
        if isinstance(self.order, str):
            object.__setattr__(self, "order", (self.order,))
        if not isinstance(self.order, (tuple, list)):
            raise DimensionError(f"the link-length orders are a text or a list of texts, e.g. ('r2 <= r3 <= r4 <= r1',), "
                                 f"not {self.order!r}")
        object.__setattr__(self, "order", tuple(self.order))
        for text in self.order:
            _order_terms(text)

    def _number(self, field: str, sentence: str, holds) -> None:
        """Field ``field``, unless None, as a float for which ``holds`` is true; else ``sentence``."""
        value = getattr(self, field)
        if value is not None:
            value = _real(value, sentence)
            if not holds(value):
                raise DimensionError(sentence)
            object.__setattr__(self, field, value)

    def _check_placing(self) -> None:
        """The fixed pivots, the frame's direction and the timing: each well formed, none contradicting
        another or the pivots' box."""
        pairs = f"the fixed pivots are a mapping joint -> (x, y), e.g. {{'0-1': (0, 0)}}, not {self.pivot_at!r}"
        given = self.pivot_at.items() if isinstance(self.pivot_at, Mapping) else self.pivot_at
        if isinstance(given, (str, bytes)) or not isinstance(given, Iterable):
            raise DimensionError(pairs)
        given = list(given)
        if not all(isinstance(g, (tuple, list)) and len(g) == 2 for g in given):
            raise DimensionError(pairs)
        held = []
        for joint, at in given:
            x, y = finite_pair(at, error=DimensionError, malformed=f"a fixed pivot is a point (x, y), not {at!r} (joint {joint})",
                               not_finite=f"the fixed pivot of joint {joint} must be at finite coordinates, not {at!r}")
            if self.pivots is not None:
                x0, x1, y0, y1 = self.pivots
                if not (x0 <= x <= x1 and y0 <= y <= y1):
                    raise DimensionError(f"the fixed pivot of joint {joint} at ({x:g}, {y:g}) lies outside the "
                                         f"pivots' region x {x0:g}..{x1:g}, y {y0:g}..{y1:g}")
            held.append((joint, (x, y)))
        object.__setattr__(self, "pivot_at", tuple(held))
        if self.frame_angle is not None:
            self._number("frame_angle", f"the frame's direction must be a finite angle, not {self.frame_angle}",
                         math.isfinite)
        if self.timing not in ("relative", "absolute"):
            raise DimensionError(f"the timing is 'relative' or 'absolute', not {self.timing!r}")
        if self.frame_line is not None and self.frame_angle is None and self.timing != "absolute":
            raise DimensionError(f"{option('frame_line', 'JOINT')} names the far end of the frame line, which only a "
                                 f"fixed direction ({option('frame_angle', 'ANGLE')}) or an absolute timing "
                                 f"({option('timing', 'absolute')}) uses")


def _real(value, sentence: str) -> float:
    """``value`` — a number or the text of one, as :func:`mechbase.finite_pair` reads them — as a float;
    a truth value, None or anything else is ``DimensionError(sentence)``.

    >>> _real(np.float32(0.5), "a number"), _real("2", "a number")
    (0.5, 2.0)
    """
    if isinstance(value, (bool, np.bool_)):
        raise DimensionError(sentence)
    try:
        return float(value)
    except (TypeError, ValueError):
        raise DimensionError(sentence) from None


def _wrap(a):
    return np.remainder(np.asarray(a) + math.pi, 2 * math.pi) - math.pi


class Problem:
    """One topology against one target: unknowns ↔ linkage, error and violations.

    Parameters
    ----------
    mechanism : Mechanism
    input_joint : int
        The input joint (of the frame).
    target : PathTarget, FunctionTarget or MotionTarget
    tracer_link : int, optional
        The link carrying the tracer point "P" (path, motion) — by default the moving link with the
        most joints that is not jointed to the frame (the coupler).
    constraints : Constraints
    """

    def __init__(self, mechanism, input_joint: int, target, tracer_link: int | None, constraints: Constraints,
                 driven: int | None = None):
        self.mechanism, self.target, self.constraints = mechanism, target, constraints
        chain = mechanism.chain
        self.chain, self.frame, self.input_joint = chain, mechanism.frame, input_joint
        self.driven = driven
        kinds = chain.kinds
        self.kinds = kinds
        if MESH in kinds:
            raise DimensionError("a mechanism with gear meshes is not dimensioned by this synthesis (links and "
                                 "revolute or prismatic pairs only)")
        if chain.h != 3 or chain.dof != 1:
            raise DimensionError(f"dimensional synthesis moves a planar mechanism of one input (W = 1), not W = "
                                 f"{chain.dof}" + (f" in motion space h = {chain.h}" if chain.h != 3 else ""))
        self.revolute_input = kinds[input_joint] == REVOLUTE
        self.input_link = driven if driven is not None else next(x for x in chain.joints[input_joint] if x != self.frame)
        frame_joints = [k for k, j in enumerate(chain.joints) if self.frame in j]
        self.frame_joints = frame_joints
        # a function's slider on the frame (its prismatic joint with the frame, the pin whose place along the line is
        # the displacement), its line the x axis: None for angles against angles and for paths and motions
        self.slider = None
        if isinstance(target, FunctionTarget):
            self.output_link = self._output_link(target.output_link)
            self.output_joint = next(k for k in frame_joints if self.output_link in chain.joints[k])
            self._check_measures(target)
            self.tracer_link = None
            if constraints.pivot_at or constraints.pivots is not None or constraints.timing == "absolute":
                raise DimensionError("a function's frame is fixed by its gauge (the input pivot at (0, 0), the output's "
                                     "at (1, 0), or a slider's line along the x axis) and its values are absolute: fixed "
                                     "pivots, a pivots' region and a timing do not apply")
            if target.input_is == target.output_is:  # angles: the frame line is the x axis, one long
                self.centre, self.scale = np.zeros(2), 1.0
                self.fixed = {input_joint: np.zeros(2), self.output_joint: np.array([1.0, 0.0])}
            else:  # the revolute side's pivot at the origin, the slider's line along the x axis
                slide, pivot = ((self.output_joint, input_joint) if target.output_is == "displacement"
                                else (input_joint, self.output_joint))
                self.slider = (slide, self._slider_pin(slide))
                lengths = target.outputs if target.output_is == "displacement" else target.inputs
                if target.origin == "pivot":
                    self.centre, self.scale = np.zeros(2), float(np.abs(lengths).max()) or 1.0
                    self.fixed = {pivot: np.zeros(2)}
                else:  # the pivot on the x axis at an unknown place: the box about the stroke's middle, strokes wide
                    self.centre = np.array([(lengths.min() + lengths.max()) / 2, 0.0])
                    self.scale, self.fixed = float(np.ptp(lengths)), {}
                    self.origin_pivot = pivot
        else:
            self.tracer_link = self._tracer_link(tracer_link)
            pts = target.points
            self.centre = (pts.min(axis=0) + pts.max(axis=0)) / 2
            self.scale = target.size
            self.fixed = self._fixed_pivots()
        self.timed = isinstance(target, FunctionTarget) or (isinstance(target, PathTarget) and target.inputs is not None)
        if self.timed and self.revolute_input:
            values = target.inputs
            if np.ptp(values) >= 2 * math.pi:
                raise BadTarget("the timing spans a full turn of the input or more: the points would repeat")
        if self.timed and constraints.rocker is not None and np.ptp(target.inputs) > np.ptp(constraints.rocker):
            shown = (lambda v: f"{math.degrees(v):g}°") if self.revolute_input else (lambda v: f"{v:g}")
            raise DimensionError(f"the target's inputs span {shown(np.ptp(target.inputs))}, more than the "
                                 f"{shown(np.ptp(constraints.rocker))} between the rocker's limits "
                                 f"({option('rocker', 'A..B')}): no input within them passes every point")
        self.absolute = constraints.timing == "absolute"
        if self.absolute and not (self.timed and self.revolute_input):
            raise DimensionError(f"{option('timing', 'absolute')} gives a crank's angles from the frame line: it needs a "
                                 "timed path (an input column) and a revolute input")
        self.frame_line = self._frame_ends()
        self.along = self._frame_line()
        self.order = tuple(read_order(text, chain, self.frame, self.input_link) for text in constraints.order)
        # where the penalty rows of the link-length constraints (:meth:`length_gaps`) aim: this far inside each
        # (log); the final polish moves each aim by the overshoot its penalty leaves (``_Search.stiffen``)
        self.aim = np.concatenate((np.full(self.order_pairs, MARGIN),
                                   np.full(self.length_bounds - self.order_pairs, -math.log1p(-MARGIN))))
        # which of those rows are held as equalities, gap + aim signed rather than its hinge (gap + aim)⁺: a polish
        # follows a binding length or ratio bound so (``_Search.polish``), where the hinge's kink makes it crawl
        self.held = np.zeros(self.length_bounds, bool)
        # whether a crank's whole turn is sampled where the dyads must close (:meth:`samples`); the final constrained
        # polish of an answer holds the turn as an inequality instead (:meth:`turn_clearance`, ``_Search.constrained``)
        self.turn_sampled = True
        # the unknowns: per free joint x, y (and a prismatic joint's direction), then the tracer
        self.layout = []  # (joint, kind) or ("tracer", None)
        lower, upper = [], []
        free = isinstance(target, FunctionTarget) and target.origin == "free"
        reach = self.reach = constraints.reach or (8.0 if free else 2.0 if isinstance(target, FunctionTarget) else 4.0)
        for k in range(len(chain.joints)):
            if k in self.fixed or (self.slider is not None and k == self.slider[0]):  # (a slider's line: the x axis)
                continue
            if free and k == self.origin_pivot:  # the pivot's place along the x axis
                self.layout.append(("origin", k))
                lower.append(-reach)
                upper.append(reach)
                continue
            if self.along is not None and k == self.along[0]:  # the frame line's free end: its distance along it
                self.layout.append(("along", k))
                lower.append(SHORTEST_FRAME)
                upper.append(2 * reach)
                continue
            box = self._pivot_box(k)
            self.layout.append(("joint", k))
            lower += [box[0], box[2]]
            upper += [box[1], box[3]]
            if kinds[k] == PRISMATIC:
                self.layout.append(("slide", k))
                lower.append(0.0)
                upper.append(math.pi)
        if self.tracer_link is not None:
            self.layout.append(("tracer", None))
            lower += [-reach, -reach]
            upper += [reach, reach]
        self.lower, self.upper = np.array(lower), np.array(upper)
        self.dims = len(self.lower)
        # a path's tracer point is found by linear least squares for the rest (timed: at the target's
        # inputs; untimed: at the points' places on the curve): the global stage searches the other
        # unknowns only (the tracer's two come last)
        self.projected = isinstance(target, PathTarget)
        self.searched = self.dims - (2 if self.projected else 0)
        self.points = len(target)
        # the target's weights over their mean (None: 1 each), so the cost is a weighted mean of squared errors
        self.weights = None if target.weights is None else target.weights / target.weights.mean()
        self.input_span = 2 * math.pi if self.revolute_input else 2 * reach * self.scale
        self.unknowns = self._count_unknowns()
        self.rows_per_point = {"path": 2, "function": 1, "motion": 3}[target.kind]
        counted = self.points if self.weights is None else int(np.count_nonzero(self.weights))
        self.equations = counted * self.rows_per_point  # (a point of weight 0 gives none)
        self._check_region_reached()

    # ------------------------------------------------------------ set-up
    def _check_measures(self, target: FunctionTarget) -> None:
        """Each side of a function measured as its joint moves: an angle at a revolute joint, a displacement
        at a prismatic one."""
        from ..motion import joint_name

        for side, k, measure in (("input", self.input_joint, target.input_is),
                                 ("output", self.output_joint, target.output_is)):
            name = joint_name(self.chain, k)
            if measure == "angle" and self.kinds[k] != REVOLUTE:
                raise DimensionError(f"the target gives the {side} as angles, but the {side} joint {name} is prismatic "
                                     f"(a slider): give its displacements (an {side}_displacement column)")
            if measure == "displacement" and self.kinds[k] != PRISMATIC:
                other = " or drive a prismatic joint of the frame" if side == "input" else ""
                raise DimensionError(f"the target gives the {side} as displacements, but the {side} joint {name} is "
                                     f"revolute: give its angles (an {side} or {side}_deg column){other}")

    def _slider_pin(self, slide: int) -> int:
        """The slider's pin: the revolute joint of the link sliding at joint ``slide`` (the first, where it
        has several) whose place along the line is the slider's displacement."""
        link = next(x for x in self.chain.joints[slide] if x != self.frame)
        pins = [k for k, j in enumerate(self.chain.joints) if link in j and self.kinds[k] == REVOLUTE]
        if not pins:
            raise DimensionError(f"the slider (link {link}) has no revolute joint: its displacement is measured at its "
                                 "pin, which it lacks")
        return pins[0]

    def _output_link(self, given: int | None) -> int:
        chain = self.chain
        pivoted = [x for k in self.frame_joints for x in chain.joints[k] if x not in (self.frame, self.input_link)]
        if given is not None:
            if given not in pivoted:
                why = (f"is not a link of the mechanism (links 0 … {chain.links - 1})" if not 0 <= given < chain.links
                       else "is the frame" if given == self.frame else "is the input link" if given == self.input_link
                       else f"is not pivoted on the frame (link {self.frame})")
                raise DimensionError(f"the output link {given} {why}: it must be a link pivoted on the frame besides "
                                     f"the input; links pivoted there: {sorted(set(pivoted))}")
            return given
        if len(set(pivoted)) != 1:
            raise DimensionError(f"name the output link: links {sorted(set(pivoted))} are pivoted on the frame besides "
                                 "the input")
        return pivoted[0]

    def _tracer_link(self, given: int | None) -> int:
        chain = self.chain
        moving = [x for x in range(chain.links) if x != self.frame]
        if given is not None:
            if given not in moving:
                raise DimensionError(f"the tracer link {given} must be a moving link of the chain (links "
                                     f"{', '.join(map(str, moving))})")
            return given
        on_frame = {x for k in self.frame_joints for x in self.chain.joints[k]}
        floating = [x for x in moving if x not in on_frame]
        degree = [sum(x in j for j in chain.joints) for x in range(chain.links)]
        pick = max(floating or moving, key=lambda x: (degree[x], -x))
        return pick

    def _pivot_box(self, k: int) -> tuple[float, float, float, float]:
        """The search box of joint k's position, non-dimensional (the pivots' region for the frame's joints)."""
        reach = self.reach
        box = (-reach, reach, -reach, reach)
        if self.constraints.pivots is not None and k in self.frame_joints:
            x0, x1, y0, y1 = self.constraints.pivots
            cx, cy = self.centre
            box = ((x0 - cx) / self.scale, (x1 - cx) / self.scale, (y0 - cy) / self.scale, (y1 - cy) / self.scale)
        return box

    def _check_region_reached(self) -> None:
        """Refuse a pivots' region no link within the length bound can join to the search box: every moving
        joint is sought within ``reach`` target sizes of the target's centre, each pivot of the frame is jointed
        to a moving link with another pin, so a region farther from that box than the bound leaves no
        candidate (the search would spend its budget and find none)."""
        c = self.constraints
        if c.pivots is None or c.max_length is None or self.tracer_link is None:
            return
        revolute = [k for k, kind in enumerate(self.kinds) if kind == REVOLUTE]
        jointed = any(j not in self.frame_joints
                      for k in self.frame_joints if self.kinds[k] == REVOLUTE
                      for link in self.chain.joints[k] if link != self.frame
                      for j in revolute if j != k and link in self.chain.joints[j])
        if not jointed:
            return
        x0, x1, y0, y1 = c.pivots
        half = self.reach * self.scale
        (cx, cy) = self.centre
        gap = math.hypot(max(0.0, x0 - (cx + half), (cx - half) - x1), max(0.0, y0 - (cy + half), (cy - half) - y1))
        if gap > c.max_length:
            raise DimensionError(
                f"the pivots' region x {x0:g}..{x1:g}, y {y0:g}..{y1:g} lies {gap:.4g} from every place a moving joint "
                f"is sought (within {self.reach:g} target sizes, {half:.4g}, of the target's centre "
                f"({cx:.4g}, {cy:.4g})), beyond the link-length bound {c.max_length:g}: no link joins a pivot there "
                f"to the mechanism; give a region of the fixed pivots ({option('pivots', 'x0..x1,y0..y1')}) nearer "
                f"the target, or a larger {option('reach', 'R')} or {option('max_length', 'L')}")

    def _count_unknowns(self) -> int:
        """The problem's real unknowns: a pin's 2 coordinates, a slide's line (2: a point along it is
        no unknown), the tracer's 2, the inputs of an untimed target after the first, and the body's
        reference angle of a motion."""
        count = sum(2 if kind == "joint" and self.kinds[k] == REVOLUTE else 1
                    for kind, k in self.layout if kind in ("joint", "slide", "along", "origin"))
        count += 2 if self.tracer_link is not None else 0
        if not self.timed:
            count += self.points - 1
        if isinstance(self.target, FunctionTarget) or self.absolute:
            count -= 1  # the pose may be anywhere on its branch: only the dimensions count
        return count

    def _fixed_pivots(self) -> dict[int, np.ndarray]:
        """The designer's pivots held at points: revolute joints of the frame, at distinct points."""
        chain, fixed = self.chain, {}
        for name, at in self.constraints.pivot_at:
            k = chain.joint_index(name, "a fixed pivot")
            if k not in self.frame_joints or self.kinds[k] != REVOLUTE:
                raise DimensionError(f"a fixed pivot is a revolute joint of the frame (link {self.frame}); joint "
                                     f"{name} is not")
            if k in fixed:
                raise DimensionError(f"joint {name} is held at two points: give each fixed pivot once")
            fixed[k] = np.array(at, dtype=float)
        spots = list(fixed.values())
        if any(np.array_equal(a, b) for i, a in enumerate(spots) for b in spots[i + 1:]):
            raise DimensionError("two fixed pivots are held at one point: a link's pins must be apart")
        return fixed

    def _frame_ends(self) -> tuple[int, int] | None:
        """The frame line (the input pivot, its far joint) where a fixed direction or an absolute timing
        measures from it; None otherwise."""
        c = self.constraints
        if c.frame_angle is None and not self.absolute:
            return None
        if isinstance(self.target, FunctionTarget):
            raise DimensionError("a function's frame is fixed by its gauge (the input pivot at (0, 0), the output's at "
                                 f"(1, 0)): {option('frame_angle', 'ANGLE')} does not apply")
        chain, k_in = self.chain, self.input_joint
        others = [k for k in self.frame_joints if k != k_in]
        if c.frame_line is not None:
            far = chain.joint_index(c.frame_line, "the frame line")
            if far not in others:
                raise DimensionError(f"the frame line runs from the input pivot to another joint of the frame (link "
                                     f"{self.frame}); joint {c.frame_line} is not one")
        elif len(others) == 1:
            far = others[0]
        else:
            from ..motion import joint_name

            raise DimensionError(f"the frame has joints {', '.join(joint_name(chain, k) for k in others)} besides the "
                                 f"input: name the frame line's far end ({option('frame_line', 'JOINT')})")
        if self.kinds[far] != REVOLUTE or self.kinds[k_in] != REVOLUTE:
            raise DimensionError("the frame line, whose direction is fixed or from which the crank's angles are "
                                 "counted, runs between two revolute joints of the frame")
        return k_in, far

    def _frame_line(self) -> tuple[int, int, np.ndarray] | None:
        """The frame line of a fixed direction: (its free end, the end it is measured from, the unit
        vector from that end), the free end then an unknown distance along it; None without one."""
        c = self.constraints
        if c.frame_angle is None:
            return None
        k_in, far = self.frame_line
        if k_in in self.fixed and far in self.fixed:
            raise DimensionError("the frame line's two pivots are both held at points: its direction is theirs, "
                                 f"{option('frame_angle', 'ANGLE')} contradicts or repeats it")
        u = np.array([math.cos(c.frame_angle), math.sin(c.frame_angle)])
        return (k_in, far, -u) if far in self.fixed else (far, k_in, u)

    def on_reach(self, x: np.ndarray) -> list[str]:
        """The joints (and "the tracer point") whose unknowns ``x`` lie on the edge of the search's reach
        (not on a pivots' region the designer set): there the box, not the target, stopped the search.

        >>> from synth.structure.chain import Chain, Mechanism
        >>> p = Problem(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), 0, PathTarget(np.eye(2)), 2, Constraints())
        >>> x = np.zeros(p.dims)
        >>> p.on_reach(x), [name for name, _ in p.layout]
        ([], ['joint', 'joint', 'joint', 'joint', 'tracer'])
        >>> x[2] = p.upper[2]; x[-1] = p.lower[-1]      # the second joint's x, the tracer's y
        >>> p.on_reach(x)
        ['0-3', 'the tracer point']
        """
        from ..motion import joint_name

        edge = 1e-9 * (self.upper - self.lower)
        touching = (x <= self.lower + edge) | (x >= self.upper - edge)
        names, at = [], 0
        for kind, k in self.layout:
            width = 1 if kind in ("slide", "along", "origin") else 2
            region = kind == "joint" and self.constraints.pivots is not None and k in self.frame_joints
            if kind != "slide" and not region and touching[at:at + width].any():
                names.append("the tracer point" if kind == "tracer" else joint_name(self.chain, k))
            at += width
        return names

    # ------------------------------------------------------------ unknowns → linkage
    def linkage(self, x: np.ndarray) -> Linkage:
        """The linkage of the unknowns ``x`` (its pose the mechanism at the first target point).

        Raises
        ------
        MotionError
            The pose contradicts the chain (two pins of one link at one point).
        """
        chain = self.chain
        points = np.zeros((len(chain.joints), 2))
        slides = {}
        tracer = None
        i = 0
        for kind, k in self.layout:
            if kind == "joint":
                points[k] = self.centre + self.scale * x[i:i + 2]
                i += 2
            elif kind == "slide":
                slides[k] = (math.cos(x[i]), math.sin(x[i]))
                i += 1
            elif kind == "along":
                distance = x[i]
                i += 1
            elif kind == "origin":  # a function's pivot on the slider's line, the x axis
                points[k] = (self.centre[0] + self.scale * x[i], 0.0)
                i += 1
            else:  # (the tracer's two are the layout's last)
                tracer = self.centre + self.scale * x[i:i + 2]
        for k, p in self.fixed.items():
            points[k] = p
        if self.slider is not None:  # the slider's line along the x axis, through its pin
            slide, pin = self.slider
            points[slide], slides[slide] = points[pin], (1.0, 0.0)
        if self.along is not None:
            end, start, u = self.along
            points[end] = points[start] + self.scale * distance * u
        tracers = {} if tracer is None else {"P": (self.tracer_link, (float(tracer[0]), float(tracer[1])))}
        return Linkage(self.mechanism, (self.input_joint,), points, slides, {}, tracers,
                       driven=None if self.driven is None else (self.driven,))

    def unknowns_of(self, linkage: Linkage) -> np.ndarray:
        """The unknowns of a linkage of this mechanism (the start of a search), clipped to the box."""
        x = []
        for kind, k in self.layout:
            if kind == "joint":
                x += list((linkage.points[k] - self.centre) / self.scale)
            elif kind == "slide":
                u = linkage.slides[k]
                x.append(math.atan2(u[1], u[0]) % math.pi)
            elif kind == "along":
                end, start, u = self.along
                x.append(float((linkage.points[end] - linkage.points[start]) @ u) / self.scale)
            elif kind == "origin":
                x.append(float(linkage.points[k][0] - self.centre[0]) / self.scale)
            else:
                at = linkage.tracers.get("P", next(iter(linkage.tracers.values()), None))
                if at is None or at[0] != self.tracer_link:
                    xy = self.centre
                else:
                    xy = np.array(at[1])
                x += list((xy - self.centre) / self.scale)
        return np.clip(np.array(x), self.lower, self.upper)

    # ------------------------------------------------------------ the motion of a candidate
    def input_at_pose(self, linkage: Linkage) -> float:
        """The input's value in the pose as the target measures it: a revolute input's angle from the x axis;
        a function's input slider's pin along the x axis (the slider's line); else
        the motion layer's prismatic input, 0 in the pose."""
        if self.slider is not None and self.slider[0] == self.input_joint:
            return float(linkage.points[self.slider[1]][0])
        return float(linkage.pose_inputs[0])

    def offsets_of_timing(self, linkage: Linkage) -> np.ndarray:
        """Input offsets from the pose at each target point, for a timed target."""
        target = self.target
        if isinstance(target, FunctionTarget):
            change = target.inputs - self.input_at_pose(linkage)
            return _wrap(change) if self.revolute_input else change
        if self.absolute:  # the pose anywhere on its branch: the first point's turn from it, then the timing's
            return _wrap(self.absolute_start(linkage) - linkage.pose_inputs[0]) + target.inputs - target.inputs[0]
        return target.inputs - target.inputs[0]

    def posed(self, linkage: Linkage) -> Linkage:
        """The linkage posed at its first target input where that input is prescribed (:meth:`absolute_start`),
        as results are returned; as it is where the motion layer cannot find that pose on its branch."""
        start = self.absolute_start(linkage)
        if start is None:
            return linkage
        try:
            posed = assemble(linkage, start)
        except (MotionError, ValueError):
            return linkage
        if self.slider is None:
            return posed
        slide, pin = self.slider  # (the slider's line drawn through its pin, as the unknowns place it)
        points = np.array(posed.points)
        points[slide] = points[pin]
        return replace(posed, points=points)

    def absolute_start(self, linkage: Linkage) -> float | None:
        """The input's angle from the x axis at the first target point, where it is prescribed (a
        function's; an absolute timing's: the frame line's direction — fixed, or the linkage's own —
        plus the first angle); a function's input slider's displacement there from the pose.

        Examples
        --------
        >>> from synth.structure.chain import Chain, Mechanism
        >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [0, 4], [1, 0], [2, 3]])
        >>> target = PathTarget(np.array([[0.0, 0.0], [1.0, 1.0]]), np.radians([30.0, 60.0]))
        >>> problem = Problem(lk.mechanism, 0, target, 2, Constraints(timing="absolute"))
        >>> round(math.degrees(problem.absolute_start(lk)), 9)   # the frame line points up: 90° + 30°
        120.0
        """
        if isinstance(self.target, FunctionTarget):
            return float(self.target.inputs[0] - self.input_at_pose(linkage) if not self.revolute_input
                         else self.target.inputs[0])
        if not self.absolute:
            return None
        if self.constraints.frame_angle is not None:
            return self.constraints.frame_angle + float(self.target.inputs[0])
        k_in, far = self.frame_line
        d = linkage.points[far] - linkage.points[k_in]
        return math.atan2(d[1], d[0]) + float(self.target.inputs[0])

    def poses(self, linkage: Linkage, offsets: np.ndarray):
        """Every link's rotation θ (S, n) and translation t (S, n, 2) from the pose, g (S,) the least
        dyad discriminant, up to rounding (NaN-free: −1 where a dyad cannot close), μ (S,) the worst
        transmission angle from the ideal, min(μ, π − μ), at the input offsets; g and μ are None for a
        linkage moved by Newton's method (it raises MotionError where it cannot reach)."""
        theta, t, gs, mus = link_poses(linkage, offsets)
        if gs is None:
            return theta, t, None, None
        g = np.where(np.isfinite(gs), gs + ROUNDING, -1.0).min(axis=1) if gs.shape[1] else np.ones(len(offsets))
        g = np.where(np.isfinite(theta).all(axis=1), g, -1.0)
        worst = np.minimum(mus, math.pi - mus)
        mu = (np.where(np.isfinite(worst), worst, math.pi / 2).min(axis=1) if mus.shape[1]
              else np.full(len(offsets), math.pi / 2))
        return theta, t, g, mu

    def move(self, linkage: Linkage, offsets: np.ndarray):
        """(tracer points (S, 2), poses (S, 3: x, y and the body's turn) or output angles (S,), g, μ)
        at the input offsets (g and μ as :meth:`poses` gives them)."""
        theta, t, g, mu = self.poses(linkage, offsets)
        if self.slider is not None and self.slider[0] == self.output_joint:  # the pin's place along the x axis
            pin = linkage.points[self.slider[1]]
            return point_carried(theta[:, self.output_link], t[:, self.output_link], pin)[:, 0], g, mu
        if self.tracer_link is None:
            ref = linkage.points[self.output_reference(linkage)] - linkage.points[self.output_joint]
            return math.atan2(ref[1], ref[0]) + theta[:, self.output_link], g, mu
        link = self.tracer_link
        xy = point_carried(theta[:, link], t[:, link], np.array(linkage.tracers["P"][1]))
        if isinstance(self.target, MotionTarget):
            return np.column_stack((xy, theta[:, link])), g, mu
        return xy, g, mu

    def best_placement(self, theta: np.ndarray, t: np.ndarray, longest: float | None = None):
        """Where the mechanism and its tracer point best meet a timed path, for the tracer link's
        rotations θ (N,) and translations t (N, 2) at the target's inputs (variable projection).

        The whole mechanism may be moved by a similarity z ↦ λz + s (a turn, a scale and a shift:
        timing is relative, so its motion is the same) and the tracer put anywhere on its link; in
        complex numbers over the target's size the tracer then passes e^{iθᵢ}q + λtᵢ + s, linear
        in q, λ, s, which least squares gives (:func:`placement`; scaled within the length bound, given the
        ``longest`` link unplaced, :meth:`place`).  Returns (tracer, λ, s, traced points (N, 2)): the tracer in
        the placed pose is q + s (both over the target's size, from the origin).
        """
        turn, moves = np.exp(1j * theta), (t[:, 0] + 1j * t[:, 1]) / self.scale
        q, lam, shift = self.place(turn, moves, (self.target.points[:, 0] + 1j * self.target.points[:, 1]) / self.scale,
                                   longest)
        z = turn * q + lam * moves + shift
        return complex(q + shift), complex(lam), complex(shift), np.column_stack((z.real, z.imag)) * self.scale

    def place(self, turn: np.ndarray, moves: np.ndarray, w: np.ndarray,
              longest: float | None = None) -> tuple[complex, complex, complex]:
        """:func:`placement` as the designer's constraints allow it: about the fixed pivot (two or more
        fixed: no similarity, the tracer point alone fitted), without a turn where the frame's
        direction is fixed, and — given the ``longest`` link of the mechanism unplaced — scaled no
        larger than the length bound allows (:meth:`largest_scale`).  Positions are complex, over the
        target's size."""
        if len(self.fixed) > 1:
            return placement(turn, moves, w, similar=False, weights=self.weights)
        pivot = None
        if self.fixed:
            (at,) = self.fixed.values()
            pivot = complex(at[0], at[1]) / self.scale
        return placement(turn, moves, w, pivot=pivot, turns=self.along is None, weights=self.weights,
                         most=self.largest_scale(longest))

    def largest_scale(self, longest: float | None) -> float | None:
        """The largest scale a placement may give a mechanism whose longest link is ``longest``: the length
        bound's, as its penalty row aims (None without a bound).  Measured where it stands, a candidate of the
        right shape placed beyond the bound was penalised as far from the target, however close it came at the
        bound: the half circle's record lies on the bound, its shapes' best fits beyond it
        (benchmarks/DIMENSION.md, *The half circle at the default budget*).

        >>> from synth.structure.chain import Chain, Mechanism
        >>> p = Problem(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), 0, PathTarget(np.eye(2)), 2,
        ...             Constraints(max_length=8))
        >>> round(p.largest_scale(4.0), 6)   # a longest link of 4 doubles at most (1e-4 inside)
        1.9998
        """
        limit = self.constraints.max_length
        if limit is None or longest is None or not longest > 0:
            return None
        return limit * math.exp(-self.aim[self.order_pairs]) / longest

    def weighed(self, residuals: np.ndarray) -> np.ndarray:
        """Residual rows (one per target point) times the square root of their point's weight: their
        squares sum to the weighted sum the search minimises."""
        if self.weights is None:
            return residuals
        return residuals * np.sqrt(self.weights).reshape((-1,) + (1,) * (residuals.ndim - 1))

    def mean(self, squares: np.ndarray) -> float:
        """The weighted mean of squared errors, one per target point (the plain mean without weights)."""
        return float(np.mean(squares if self.weights is None else self.weights * squares))

    def output_reference(self, linkage: Linkage) -> int:
        """The joint of the output link whose direction from its pivot is the output angle."""
        others = [k for k in linkage.joints_of(self.output_link) if k != self.output_joint]
        return others[0]

    def residuals(self, values: np.ndarray, target_rows: np.ndarray | None = None) -> np.ndarray:
        """Non-dimensional residuals (one row per target point) of traced values against the target."""
        target = self.target
        if isinstance(target, FunctionTarget):
            if target.output_is == "displacement":
                return ((values - target.outputs) / self.scale)[:, None]
            return _wrap(values - target.outputs)[:, None]
        if isinstance(target, MotionTarget):
            rows = target.poses if target_rows is None else target_rows
            dxy = (values[:, :2] - rows[:, :2]) / self.scale
            turn = _wrap(values[:, 2] - (rows[:, 2] - target.poses[0, 2]))
            return np.column_stack((dxy, turn))
        return (values - (target.points if target_rows is None else target_rows)) / self.scale

    # ------------------------------------------------------------ constraints
    def samples(self, offsets: np.ndarray) -> np.ndarray:
        """Inputs where the dyads must close: across the target's span (the pose included), and the
        whole turn for a crank (unless :attr:`turn_sampled` is off)."""
        lo, hi = min(0.0, float(offsets.min())), max(0.0, float(offsets.max()))
        step = SPAN_STEP * (1.0 if self.revolute_input else self.scale)
        parts = [np.linspace(lo, hi, 2 + int((hi - lo) / step))]
        if self.constraints.crank and self.revolute_input and self.turn_sampled:  # (one step before 0 too: every
            parts.append(np.linspace(-2 * math.pi / TURN_SAMPLES, 2 * math.pi, TURN_SAMPLES + 2))
        return np.concatenate(parts)

    @property
    def turn_held(self) -> bool:
        """Whether a constrained polish may hold the crank's turning as an inequality (:meth:`turn_clearance`)
        rather than refuse a candidate whose crank stops: a crank without a transmission limit (a limit above
        0 keeps the answer off the dead positions anyway)."""
        c = self.constraints
        return bool(c.crank and self.revolute_input and c.min_transmission == 0)

    def turn_clearance(self, linkage: Linkage) -> float | None:
        """The least normalised dyad discriminant over a whole turn of the input: ≥ 0 where the crank turns,
        0 on the verge (a four-bar on Grashof's bound), and smooth in the dimensions across it (a dyad that
        cannot close has a negative discriminant, not a wall).  The turn is sampled and the least sample's
        neighbourhood searched for the minimum (Brent's method); None for a linkage moved by Newton's method.

        Examples
        --------
        >>> from synth.structure.chain import Chain, Mechanism
        >>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)
        >>> problem = Problem(four_bar, 0, PathTarget(np.eye(2)), 2, Constraints(crank=True))
        >>> turns = Linkage(four_bar, (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])   # 1 + 4 < 3.905 + 3.041
        >>> stops = Linkage(four_bar, (0,), [[0, 0], [3, 0], [0, 1], [3.93586, 1.767531]])   # 1 + 4.01 > 3 + 2
        >>> problem.turn_clearance(turns) > 0, problem.turn_clearance(stops) < 0
        (True, True)
        """
        from scipy.optimize import minimize_scalar

        def least(xs):
            g = link_poses(linkage, np.atleast_1d(xs)).discriminants
            if g is None:
                return None
            finite = np.isfinite(g)
            return np.where(finite.any(axis=1), np.where(finite, g, np.inf).min(axis=1), -1.0)

        step = 2 * math.pi / TURN_SAMPLES
        xs = np.arange(TURN_SAMPLES) * step
        sampled = least(xs)
        if sampled is None:
            return None
        k = int(np.argmin(sampled))
        found = minimize_scalar(lambda x: float(least(x)[0]), bounds=(xs[k] - step, xs[k] + step), method="bounded",
                                options={"xatol": 1e-12})
        return float(min(found.fun, sampled[k]))

    def dips(self, linkage: Linkage, xs: np.ndarray, g: np.ndarray | None) -> np.ndarray | None:
        """The least discriminants g (as :meth:`poses` gives them at the input offsets xs) with each
        sampled local minimum that may hide a dead position replaced by the least found between its
        neighbouring samples.

        Samples alone miss a dyad that cannot close over an interval narrower than their step, and
        the search's optimum often lies on such a boundary (a four-bar on the verge of Grashof's
        condition: Kunjur and Krishnamurty's eighteen points ended with a crank that rocked, its
        dead positions 0.17° apart between two samples 5° apart).  A sample is looked into where
        it is a local minimum no higher than its rises to its neighbours (3·g ≤ left + right: a
        smooth g that dips below 0 between samples always is one; a broad minimum far from 0 is
        not): :data:`DIP_ROUNDS` rounds of nine samples each narrow the interval fourfold round its
        least, and the vertex of the parabola through the last three gives the minimum.  A linkage
        moved by Newton's method (g None) is returned as it is.

        Examples
        --------
        >>> from synth.structure.chain import Chain, Mechanism
        >>> from synth.dimension import PathTarget
        >>> # frame 3, crank 1, coupler 4.01, rocker 2: the crank cannot pass within 6.6° of the frame line
        >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [3, 0], [0, 1], [3.93586, 1.767531]])
        >>> problem = Problem(lk.mechanism, 0, PathTarget(np.eye(2)), 2, Constraints())
        >>> xs = np.linspace(-np.pi, np.pi, 8)                 # samples 51° apart, none within 12° of the frame line
        >>> _, _, g, _ = problem.poses(lk, xs)
        >>> bool((g >= 0).all()), bool((problem.dips(lk, xs, g) < 0).any())
        (True, True)
        """
        if g is None or len(xs) < 3:
            return g
        s, first = np.unique(xs, return_index=True)
        v = g[first]
        left, mid, right = v[:-2], v[1:-1], v[2:]
        (i,) = np.nonzero((mid >= 0) & (mid <= left) & (mid <= right) & (3 * mid <= left + right))
        if not len(i):
            return g
        a, b, ga, gb, least = s[i], s[i + 2], v[i], v[i + 2], v[i + 1].copy()
        fractions = np.linspace(0.0, 1.0, 9)
        for _ in range(DIP_ROUNDS):
            grid = a[:, None] + (b - a)[:, None] * fractions[None, :]
            _, _, inner, _ = self.poses(linkage, grid[:, 1:-1].ravel())
            values = np.column_stack((ga, inner.reshape(len(a), 7), gb))
            least = np.minimum(least, values.min(axis=1))
            j = np.clip(values.argmin(axis=1), 1, 7)
            rows = np.arange(len(a))
            a, b, ga, gb = grid[rows, j - 1], grid[rows, j + 1], values[rows, j - 1], values[rows, j + 1]
            middle = values[rows, j]
        bend = ga - 2 * middle + gb
        vertex = middle - (gb - ga) ** 2 / (8 * np.where(bend > 0, bend, 1.0))
        least = np.minimum(least, np.where(bend > 0, vertex, least))
        out = np.array(g, dtype=float)
        out[first[i + 1]] = np.minimum(out[first[i + 1]], least)
        return out

    def violations(self, linkage: Linkage, offsets: np.ndarray, g, mu) -> np.ndarray:
        """Non-negative violations of the designer's constraints (0 where met; a ``held`` row signed), non-dimensional:
        transmission (rad), ratio and length (log), pivots (target sizes), rocker limits (rad or sizes).  Each is
        measured against a limit :data:`MARGIN` inside the designer's, since a penalised constraint
        that binds settles a little beyond its limit (the link-length ones: ``aim`` inside, which the final
        polish moves)."""
        c = self.constraints
        out = []
        if c.min_transmission > 0:
            out.append(max(0.0, c.min_transmission + MARGIN - float(np.min(mu))) if mu is not None else 0.0)
        # the link-length constraints' rows: (gap + aim)⁺ for the orders' pairs, the length and the ratio (gap + aim
        # where ``held``)
        lengths = None
        if self.length_bounds:
            lengths = self.length_gaps(linkage) + self.aim
            lengths = np.where(self.held, lengths, np.maximum(lengths, 0.0))
        if c.max_ratio is not None:
            out.append(float(lengths[-1]))
        if c.max_length is not None:
            out.append(float(lengths[self.order_pairs]))
        if c.pivots is not None:
            inset = MARGIN * self.scale
            x0, x1, y0, y1 = c.pivots[0] + inset, c.pivots[1] - inset, c.pivots[2] + inset, c.pivots[3] - inset
            p = linkage.points[self.frame_joints]
            gap = np.maximum.reduce([x0 - p[:, 0], p[:, 0] - x1, y0 - p[:, 1], p[:, 1] - y1, np.zeros(len(p))])
            out.append(float(np.hypot.reduce(gap)) / self.scale if len(gap) else 0.0)
        if c.rocker is not None:
            unit = 1.0 if self.revolute_input else self.scale
            values = self.input_at_pose(linkage) + np.array([min(0.0, offsets.min()), max(0.0, offsets.max())])
            over = max(0.0, c.rocker[0] + MARGIN * unit - values[0]) + max(0.0, values[1] - c.rocker[1] + MARGIN * unit)
            out.append(over / unit)
        if self.order:
            out += list(lengths[:self.order_pairs])  # a row per pair of an order
        return np.array(out)

    @property
    def order_pairs(self) -> int:
        """The neighbouring pairs of the link-length orders: a violation row each."""
        return sum(len(links) - 1 for links in self.order)

    def order_gaps(self, linkage: Linkage) -> np.ndarray:
        """log(shorter / longer) of every pair of neighbours in the designer's link-length orders: ≤ 0
        where the order holds."""
        lengths = linkage.lengths()
        gaps = [math.log(max(lengths[a], 1e-300) / max(lengths[b], 1e-300))
                for links in self.order for a, b in zip(links, links[1:])]
        return np.array(gaps)

    @property
    def length_bounds(self) -> int:
        """The designer's link-length constraints: a row each in :meth:`length_gaps`."""
        c = self.constraints
        return self.order_pairs + (c.max_length is not None) + (c.max_ratio is not None)

    def length_gaps(self, linkage: Linkage) -> np.ndarray:
        """log(value / limit) of each link-length constraint — the orders' pairs (:meth:`order_gaps`), the
        longest link over the length bound, the ratio over its bound — ≤ 0 where it holds.

        >>> from synth.structure.chain import Chain, Mechanism
        >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
        >>> p = Problem(lk.mechanism, 0, PathTarget(np.eye(2)), 2, Constraints(max_length=8, order=("r2<=r1",)))
        >>> np.round(p.length_gaps(lk), 6).tolist()   # crank 1 over frame 4; frame 4 over the bound 8
        [-1.386294, -0.693147]
        """
        c, gaps = self.constraints, [self.order_gaps(linkage)]
        if c.max_length is not None:
            gaps.append([math.log(max(longest_link(linkage), 1e-300) / c.max_length)])
        if c.max_ratio is not None:
            gaps.append([math.log(link_ratio(linkage) / c.max_ratio)])
        return np.concatenate(gaps)

    def placing(self, linkage: Linkage) -> dict:
        """The designer's fixed pivots, frame direction, absolute timing and link-length orders, each
        re-checked on a linkage posed at the first target point: {name: {"value", "limit", "met"}}
        (met to :data:`MET` target sizes, rad or relative length)."""
        from ..motion import joint_name

        out = {}
        if self.fixed and self.tracer_link is not None:
            gap = max(float(np.hypot(*(linkage.points[k] - at))) for k, at in self.fixed.items())
            out["pivot_at"] = {"value": {joint_name(self.chain, k): linkage.points[k].tolist() for k in self.fixed},
                               "limit": {joint_name(self.chain, k): at.tolist() for k, at in self.fixed.items()},
                               "met": gap <= MET * self.scale}
        if self.along is not None:
            end, start, u = self.along
            d = linkage.points[end] - linkage.points[start]
            turn = float(_wrap(math.atan2(d[1], d[0]) - math.atan2(u[1], u[0])))
            angle = self.constraints.frame_angle
            out["frame_angle"] = {"value": math.degrees(angle + turn), "limit": math.degrees(angle),
                                  "met": abs(turn) <= MET}
        if self.absolute:
            start = self.absolute_start(linkage)
            first = float(_wrap(linkage.pose_inputs[0] - start))
            frame = math.degrees(start - float(self.target.inputs[0]))
            out["timing"] = {"value": f"absolute: the input at {math.degrees(start + first):.9g}° from the x axis at "
                                      f"the first point, the frame line at {frame:.9g}°", "limit": None,
                             "met": abs(first) <= MET}
        if self.order:
            lengths = linkage.lengths()
            gaps = self.order_gaps(linkage)
            out["link_order"] = {"value": [[lengths[k] for k in links] for links in self.order],
                                 "limit": list(self.constraints.order), "met": bool((gaps <= MET).all())}
        return out


def placement(turn: np.ndarray, moves: np.ndarray, w: np.ndarray, *, pivot: complex | None = None,
              turns: bool = True, similar: bool = True, weights: np.ndarray | None = None,
              most: float | None = None) -> tuple[complex, complex, complex]:
    """The tracer point q of a link and the similarity (λ, s) of the whole mechanism that carry the
    link's points nearest the points w in least squares: w ≈ turnᵢ q + λ movesᵢ + s (complex; turnᵢ
    the link's rotation e^{iθᵢ} and movesᵢ its translation at each point), each point's squared
    distance times its weight where ``weights`` are given.  Where λ is not determined (a link turning
    about a fixed point) the mechanism stays (λ = 1, s = 0) and only q is fitted.

    A similarity that keeps a ``pivot`` has s = pivot·(1 − λ); one that keeps the directions
    (``turns=False``) has λ real and positive; ``similar=False`` keeps the mechanism where it is.
    With ``most`` the scale is at most that, |λ| ≤ most (a length bound: the best placement of a
    mechanism whose best fit would be larger is the best at that scale, λ's direction then the one
    the fit favours, the rest fitted again).

    >>> theta = np.array([0.0, 1.0, 2.0]); moves = np.array([0, 1 + 1j, 2])
    >>> q, lam, s = placement(np.exp(1j * theta), moves, np.exp(1j * theta) * (1 - 2j) + 3j * moves + 0.5)
    >>> [round(abs(v - want), 12) for v, want in zip((q, lam, s), (1 - 2j, 3j, 0.5))]
    [0.0, 0.0, 0.0]
    >>> w = np.exp(1j * theta) * (1 - 2j) + 2 * (moves - 1j) + 1j          # scaled by 2 about the pivot i
    >>> q, lam, s = placement(np.exp(1j * theta), moves, w, pivot=1j, turns=False)
    >>> [round(abs(v - want), 12) for v, want in zip((q, lam, s), (1 - 2j, 2, -1j))]
    [0.0, 0.0, 0.0]
    >>> round(abs(placement(np.exp(1j * theta), moves, w, pivot=1j, turns=False, most=1.5)[1]), 12)  # scale held at 1.5
    1.5
    """
    root = np.ones(len(w)) if weights is None else np.sqrt(weights)
    if similar:
        origin = 0j if pivot is None else pivot
        columns = [root * turn, root * (moves - origin)] + ([root] if pivot is None else [])
        a, b = np.column_stack(columns), root * (w - origin)
        if turns:
            coef, *_ = np.linalg.lstsq(a, b, rcond=None)
        else:  # λ real: the real and imaginary parts of every column but λ's are unknowns of their own
            real = np.vstack((np.column_stack([f(c) for c in columns for f in (np.real, lambda z: -z.imag)]),
                              np.column_stack([f(c) for c in columns for f in (np.imag, np.real)])))
            real = np.delete(real, 3, axis=1)  # λ's imaginary part
            x, *_ = np.linalg.lstsq(real, np.concatenate((b.real, b.imag)), rcond=None)
            coef = [x[0] + 1j * x[1], x[2]] + ([x[3] + 1j * x[4]] if pivot is None else [])
        q, lam = complex(coef[0]), complex(coef[1])
        if most is not None and abs(lam) > most:  # the bound holds the scale: λ on |λ| = most, the rest fitted again
            others = np.delete(a, 1, axis=1)
            apart = [v - others @ np.linalg.lstsq(others, v, rcond=None)[0] for v in (a[:, 1], b)]
            lam = most * (np.exp(1j * np.angle(np.vdot(*apart))) if turns else 1.0)
            rest, *_ = np.linalg.lstsq(others, b - lam * a[:, 1], rcond=None)
            coef = [rest[0], lam] + list(rest[1:])
            q = complex(coef[0])
        shift = complex(coef[2]) if pivot is None else origin * (1 - lam)
        if abs(lam) > 1e-6 and (turns or lam.real > 1e-6):
            return q, lam, shift
    return complex(np.average((w - moves) / turn, weights=weights)), 1.0 + 0j, 0j


def point_carried(theta: np.ndarray, t: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Where a point p of a link (as placed in the pose) is when the link is turned by θ and moved by t.

    >>> point_carried(np.array([np.pi / 2]), np.array([[1.0, 2.0]]), np.array([1.0, 0.0])).round(12)
    array([[1., 3.]])
    """
    c, s = np.cos(theta), np.sin(theta)
    return np.stack((c * p[0] - s * p[1], s * p[0] + c * p[1]), axis=1) + t


def link_lengths(linkage: Linkage) -> list[float]:
    """Every distance between two revolute joints of one link (the frame included), 0 left out.

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
    >>> sorted(round(v, 6) for v in link_lengths(lk))   # crank, rocker, coupler, frame
    [1.0, 2.236068, 2.828427, 4.0]
    """
    lengths = []
    for link in range(linkage.chain.links):
        pins = [k for k in linkage.joints_of(link) if linkage.kind(k) == REVOLUTE]
        p = linkage.points[pins]
        for a in range(len(pins)):
            for b in range(a + 1, len(pins)):
                lengths.append(float(np.hypot(*(p[a] - p[b]))))
    return [v for v in lengths if v > 0]


def link_ratio(linkage: Linkage) -> float:
    """The longest over the shortest distance between two joints of one link (the frame included).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
    >>> round(link_ratio(lk), 6)   # frame 4 over crank 1
    4.0
    """
    lengths = link_lengths(linkage)
    return max(lengths) / min(lengths) if lengths else 1.0


def longest_link(linkage: Linkage) -> float:
    """The longest distance between two joints of one link (the frame included).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
    >>> longest_link(lk)   # the frame
    4.0
    """
    return max(link_lengths(linkage), default=0.0)


def input_joint_of(mechanism, linkage: Linkage | None) -> tuple[int, int | None]:
    """The input joint (and the driven link where it is a multiple joint) of a mechanism or linkage."""
    if linkage is not None:
        return linkage.inputs[0], linkage.driven[0] if len(linkage.chain.joints[linkage.inputs[0]]) > 2 else None
    chain, frame = mechanism.chain, mechanism.frame
    kinds = chain.kinds
    candidates = [k for k, j in enumerate(chain.joints) if frame in j and len(j) == 2 and kinds[k] != MESH
                  and (mechanism.input_link is None or mechanism.input_link in j)]
    if not candidates:
        raise DimensionError(f"the frame (link {frame}) has no joint with one moving link to drive"
                             + (f" (link {mechanism.input_link})" if mechanism.input_link is not None else ""))
    revolute = [k for k in candidates if kinds[k] == REVOLUTE]
    return (revolute or candidates)[0], None



_ORDER_SIGN = re.compile(r"\s*(<=|>=|≤|≥)\s*")
_ORDER_TERM = re.compile(r"r[1-4]|\d+")


def _order_terms(text: str) -> tuple[list[str], bool]:
    """The terms of a written link-length order and whether it ascends (``<=``) — one sign throughout."""
    if not isinstance(text, str):
        raise DimensionError(f"a link-length order is written as text, e.g. 'r2 <= r3 <= r4 <= r1', not {text!r}")
    parts = _ORDER_SIGN.split(text.strip())
    terms, signs = parts[0::2], set(parts[1::2])
    if len(terms) < 2 or not all(_ORDER_TERM.fullmatch(t) for t in terms):
        raise DimensionError(f"a link-length order is link numbers (or a four-bar's r1 … r4) joined by <= or >=, "
                             f"e.g. 'r2 <= r3 <= r4 <= r1', not {text!r}")
    if len(signs) > 1:
        raise DimensionError(f"a link-length order goes one way: {text!r} mixes <= and >=")
    return terms, signs <= {"<=", "≤"}


def read_order(text: str, chain, frame: int, input_link: int) -> tuple[int, ...]:
    """The links of a written link-length order, shortest first.

    Terms are link numbers, or a four-bar's classical names: r1 the frame, r2 the input link, r3 the
    coupler, r4 the output link (the other one pivoted on the frame).  Each link must be binary (two
    revolute joints: its length is their distance) and named once.

    Examples
    --------
    >>> from synth.structure.chain import Chain
    >>> four_bar = Chain.parse("0-1 1-2 2-3 3-0")
    >>> read_order("r2 <= r3 <= r4 <= r1", four_bar, 0, 1), read_order("0 >= 2", four_bar, 0, 1)
    ((1, 2, 3, 0), (2, 0))
    """
    terms, ascending = _order_terms(text)
    names = {}
    if any(t.startswith("r") for t in terms):
        if chain.links != 4 or len(chain.joints) != 4 or any(k != REVOLUTE for k in chain.kinds):
            raise DimensionError(f"r1 … r4 name the links of a four-bar (frame, input link, coupler, output link); "
                                 f"this mechanism has {chain.links} links: name its links by number in {text!r}")
        pivoted = {x for j in chain.joints if frame in j for x in j} - {frame}
        output = next(iter(pivoted - {input_link}))
        coupler = next(iter(set(range(4)) - {frame, input_link, output}))
        names = {"r1": frame, "r2": input_link, "r3": coupler, "r4": output}
    links = [names[t] if t in names else int(t) for t in terms]
    for term, link in zip(terms, links):
        if link >= chain.links:
            raise DimensionError(f"the link-length order {text!r} names link {term}, but the mechanism has links "
                                 f"0 … {chain.links - 1}")
        pins = [k for k, j in enumerate(chain.joints) if link in j and chain.kinds[k] == REVOLUTE]
        if len(pins) != 2 or sum(link in j for j in chain.joints) != 2:
            raise DimensionError(f"the link-length order {text!r} names link {term}, which is not a binary link "
                                 f"with two pins: its length is not one distance")
    if len(set(links)) != len(links):
        raise DimensionError(f"the link-length order {text!r} names a link twice")
    return tuple(links if ascending else links[::-1])
