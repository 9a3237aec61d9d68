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
from dataclasses import dataclass

import numpy as np

from ..errors import BadTarget, DimensionError
from ..structure.joints import MESH, PRISMATIC, REVOLUTE
from ..motion import Linkage, link_poses
from ._target import FunctionTarget, MotionTarget, PathTarget

__all__ = ["Constraints", "Problem", "link_ratio", "input_joint_of", "placement"]

#: the widest step (rad, or target sizes for a slide) between the inputs where the dyads must close
SPAN_STEP = 0.02
#: samples of a full turn of the input where a crank's dyads must close
TURN_SAMPLES = 72
#: samples of the traced curve, each way from the pose, for a target without timing (global stage)
CURVE_SAMPLES = 120
#: a dyad's discriminant this far below 0 still closes (a target point at a dead position, up to rounding)
ROUNDING = 1e-12
#: the search aims this far inside each of the designer's limits (rad, relative, target sizes)
MARGIN = 1e-4
#: the cost of a candidate that cannot reach the target on its branch (plus the share of samples lost)
INFEASIBLE = 1e3


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
    pivots : (x0, x1, y0, y1), optional
        A box the frame's joints (fixed pivots, slide lines' points) must lie in.
    reach : float, optional
        The search box: every joint within ``reach`` target sizes of the target's centre (default 4;
        for a function, frame lengths from the input pivot, default 2).

    Examples
    --------
    >>> Constraints(crank=True, min_transmission=math.radians(30)).crank
    True
    """

    crank: bool = False
    rocker: tuple[float, float] | None = None
    min_transmission: float = 0.0
    max_ratio: float | None = None
    pivots: tuple[float, float, float, float] | None = None
    reach: float | None = None

    def __post_init__(self):
        if self.crank and self.rocker is not None:
            raise DimensionError("the input cannot be both a crank (a full turn) and a rocker within limits")
        if self.rocker is not None:
            lo, hi = (float(v) for v in self.rocker)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise DimensionError(f"the rocker's limits must be two finite numbers, lower first, not {self.rocker}")
            object.__setattr__(self, "rocker", (lo, hi))
        if not 0 <= self.min_transmission < math.pi / 2:
            raise DimensionError(f"the least transmission angle must be 0 … 90° (exclusive), not "
                                 f"{math.degrees(self.min_transmission):g}°")
        if self.max_ratio is not None and not (math.isfinite(self.max_ratio) and self.max_ratio > 1):
            raise DimensionError(f"the link-length ratio bound must be a number above 1, not {self.max_ratio}")
        if self.pivots is not None:
            x0, x1, y0, y1 = (float(v) for v in self.pivots)
            if not all(map(math.isfinite, (x0, x1, y0, y1))) or x0 >= x1 or y0 >= y1:
                raise DimensionError(f"the pivots' region must be x0 < x1 and y0 < y1, finite, not {self.pivots}")
            object.__setattr__(self, "pivots", (x0, x1, y0, y1))
        if self.reach is not None and not (math.isfinite(self.reach) and self.reach > 0):
            raise DimensionError(f"the search reach must be a positive number of target sizes, not {self.reach}")


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
        if isinstance(target, FunctionTarget):
            self.output_link = self._output_link(target.output_link)
            self.output_joint = next(k for k in frame_joints if self.output_link in chain.joints[k])
            if kinds[self.output_joint] != REVOLUTE or not self.revolute_input:
                raise DimensionError("function generation relates the angles of two links pivoted on the frame: the "
                                     "input and the output joints must be revolute")
            self.tracer_link = None
            self.centre, self.scale = np.zeros(2), 1.0
            self.fixed = {input_joint: np.zeros(2), self.output_joint: np.array([1.0, 0.0])}  # the frame line: x axis
        else:
            self.tracer_link = self._tracer_link(tracer_link)
            pts = target.points
            self.centre = (pts.min(axis=0) + pts.max(axis=0)) / 2
            self.scale = target.size
            self.fixed = {}
        self.timed = isinstance(target, FunctionTarget) or (isinstance(target, PathTarget) and target.inputs is not None)
        if self.timed and self.revolute_input:
            values = target.inputs
            if np.ptp(values) >= 2 * math.pi:
                raise BadTarget("the timing spans a full turn of the input or more: the points would repeat")
        # the unknowns: per free joint x, y (and a prismatic joint's direction), then the tracer
        self.layout = []  # (joint, kind) or ("tracer", None)
        lower, upper = [], []
        reach = self.reach = constraints.reach or (2.0 if isinstance(target, FunctionTarget) else 4.0)
        for k in range(len(chain.joints)):
            if k in self.fixed:
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
        self.input_span = 2 * math.pi if self.revolute_input else 2 * reach * self.scale
        self.unknowns = self._count_unknowns()
        self.equations = self.points * {"path": 2, "function": 1, "motion": 3}[target.kind]

    # ------------------------------------------------------------ set-up
    def _output_link(self, given: int | None) -> int:
        chain = self.chain
        pivoted = [x for k in self.frame_joints for x in chain.joints[k] if x not in (self.frame, self.input_link)]
        if given is not None:
            if given not in pivoted:
                raise DimensionError(f"the output link {given} must be pivoted on the frame (link {self.frame}) and "
                                     f"not be the input link; links pivoted there: {sorted(set(pivoted))}")
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

    def _count_unknowns(self) -> int:
        """The problem's real unknowns: a pin's 2 coordinates, a slide's line (2: a point along it is
        no unknown), the tracer's 2, the inputs of an untimed target after the first, and the body's
        reference angle of a motion."""
        count = sum(2 if kind == "joint" and self.kinds[k] == REVOLUTE else 1
                    for kind, k in self.layout if kind in ("joint", "slide"))
        count += 2 if self.tracer_link is not None else 0
        if not self.timed:
            count += self.points - 1
        if isinstance(self.target, FunctionTarget):
            count -= 1  # the pose may be anywhere on its branch: only the dimensions count
        return count

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
            else:  # (the tracer's two are the layout's last)
                tracer = self.centre + self.scale * x[i:i + 2]
        for k, p in self.fixed.items():
            points[k] = p
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
            else:
                at = linkage.tracers.get("P", next(iter(linkage.tracers.values()), None))
                if at is None or at[0] != self.tracer_link:
                    xy = self.centre
                else:
                    xy = np.array(at[1])
                x += list((xy - self.centre) / self.scale)
        return np.clip(np.array(x), self.lower, self.upper)

    # ------------------------------------------------------------ the motion of a candidate
    def offsets_of_timing(self, linkage: Linkage) -> np.ndarray:
        """Input offsets from the pose at each target point, for a timed target."""
        target = self.target
        if isinstance(target, FunctionTarget):
            return _wrap(target.inputs - linkage.pose_inputs[0])
        return target.inputs - target.inputs[0]

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
        if self.tracer_link is None:
            ref = linkage.points[self.output_reference(linkage)] - linkage.points[self.output_joint]
            return math.atan2(ref[1], ref[0]) + theta[:, self.output_link], g, mu
        link = self.tracer_link
        xy = point_carried(theta[:, link], t[:, link], np.array(linkage.tracers["P"][1]))
        if isinstance(self.target, MotionTarget):
            return np.column_stack((xy, theta[:, link])), g, mu
        return xy, g, mu

    def best_placement(self, theta: np.ndarray, t: np.ndarray):
        """Where the mechanism and its tracer point best meet a timed path, for the tracer link's
        rotations θ (N,) and translations t (N, 2) at the target's inputs (variable projection).

        The whole mechanism may be moved by a similarity z ↦ λz + s (a turn, a scale and a shift:
        timing is relative, so its motion is the same) and the tracer put anywhere on its link; in
        complex numbers over the target's size the tracer then passes e^{iθᵢ}q + λtᵢ + s, linear
        in q, λ, s, which least squares gives (:func:`placement`).  Returns (tracer, λ, s, traced
        points (N, 2)): the tracer in the placed pose is q + s (both over the target's size, from the
        origin).
        """
        turn, moves = np.exp(1j * theta), (t[:, 0] + 1j * t[:, 1]) / self.scale
        q, lam, shift = placement(turn, moves, (self.target.points[:, 0] + 1j * self.target.points[:, 1]) / self.scale)
        z = turn * q + lam * moves + shift
        return complex(q + shift), complex(lam), complex(shift), np.column_stack((z.real, z.imag)) * self.scale

    def output_reference(self, linkage: Linkage) -> int:
        """The joint of the output link whose direction from its pivot is the output angle."""
        others = [k for k in linkage.joints_of(self.output_link) if k != self.output_joint]
        return others[0]

    def residuals(self, values: np.ndarray, target_rows: np.ndarray | None = None) -> np.ndarray:
        """Non-dimensional residuals (one row per target point) of traced values against the target."""
        target = self.target
        if isinstance(target, FunctionTarget):
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
        whole turn for a crank."""
        lo, hi = min(0.0, float(offsets.min())), max(0.0, float(offsets.max()))
        step = SPAN_STEP * (1.0 if self.revolute_input else self.scale)
        parts = [np.linspace(lo, hi, 2 + int((hi - lo) / step))]
        if self.constraints.crank and self.revolute_input:
            parts.append(np.linspace(0, 2 * math.pi, TURN_SAMPLES, endpoint=False))
        return np.concatenate(parts)

    def violations(self, linkage: Linkage, offsets: np.ndarray, g, mu) -> np.ndarray:
        """Non-negative violations of the designer's constraints (0 where met), non-dimensional:
        transmission (rad), ratio (log), pivots (target sizes), rocker limits (rad or sizes).  Each is
        measured against a limit :data:`MARGIN` inside the designer's, since a penalised constraint
        that binds settles a little beyond its limit."""
        c = self.constraints
        out = []
        if c.min_transmission > 0:
            out.append(max(0.0, c.min_transmission + MARGIN - float(np.min(mu))) if mu is not None else 0.0)
        if c.max_ratio is not None:
            out.append(max(0.0, math.log(link_ratio(linkage) / (c.max_ratio * (1 - MARGIN)))))
        if c.pivots is not None:
            inset = MARGIN * self.scale
            x0, x1, y0, y1 = c.pivots[0] + inset, c.pivots[1] - inset, c.pivots[2] + inset, c.pivots[3] - inset
            p = linkage.points[self.frame_joints]
            gap = np.maximum.reduce([x0 - p[:, 0], p[:, 0] - x1, y0 - p[:, 1], p[:, 1] - y1, np.zeros(len(p))])
            out.append(float(np.hypot.reduce(gap)) / self.scale if len(gap) else 0.0)
        if c.rocker is not None:
            unit = 1.0 if self.revolute_input else self.scale
            values = linkage.pose_inputs[0] + np.array([min(0.0, offsets.min()), max(0.0, offsets.max())])
            over = max(0.0, c.rocker[0] + MARGIN * unit - values[0]) + max(0.0, values[1] - c.rocker[1] + MARGIN * unit)
            out.append(over / unit)
        return np.array(out)


def placement(turn: np.ndarray, moves: np.ndarray, w: np.ndarray) -> tuple[complex, complex, complex]:
    """The tracer point q of a link and the similarity (λ, s) of the whole mechanism that carry the
    link's points nearest the points w in least squares: w ≈ turnᵢ q + λ movesᵢ + s (complex; turnᵢ
    the link's rotation e^{iθᵢ} and movesᵢ its translation at each point).  Where λ is not
    determined (a link turning about a fixed point) the mechanism stays (λ = 1, s = 0) and only q is
    fitted.

    >>> theta = np.array([0.0, 1.0, 2.0]); moves = np.array([0, 1 + 1j, 2])
    >>> q, lam, s = placement(np.exp(1j * theta), moves, np.exp(1j * theta) * (1 - 2j) + 3j * moves + 0.5)
    >>> [round(abs(v - want), 12) for v, want in zip((q, lam, s), (1 - 2j, 3j, 0.5))]
    [0.0, 0.0, 0.0]
    """
    a = np.column_stack((turn, moves, np.ones(len(moves))))
    (q, lam, shift), *_ = np.linalg.lstsq(a, w, rcond=None)
    if not abs(lam) > 1e-6:
        return complex(np.mean((w - moves) / turn)), 1.0 + 0j, 0j
    return complex(q), complex(lam), complex(shift)


def point_carried(theta: np.ndarray, t: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Where a point p of a link (as placed in the pose) is when the link is turned by θ and moved by t.

    >>> point_carried(np.array([np.pi / 2]), np.array([[1.0, 2.0]]), np.array([1.0, 0.0])).round(12)
    array([[1., 3.]])
    """
    c, s = np.cos(theta), np.sin(theta)
    return np.stack((c * p[0] - s * p[1], s * p[0] + c * p[1]), axis=1) + t


def link_ratio(linkage: Linkage) -> float:
    """The longest over the shortest distance between two joints of one link (the frame included).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
    >>> round(link_ratio(lk), 6)   # frame 4 over crank 1
    4.0
    """
    lengths = []
    for link in range(linkage.chain.links):
        pins = [k for k in linkage.joints_of(link) if linkage.kind(k) == REVOLUTE]
        p = linkage.points[pins]
        for a in range(len(pins)):
            for b in range(a + 1, len(pins)):
                lengths.append(float(np.hypot(*(p[a] - p[b]))))
    lengths = [v for v in lengths if v > 0]
    return max(lengths) / min(lengths) if lengths else 1.0


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

