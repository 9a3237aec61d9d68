"""Sweeps of a linkage's inputs, its range of motion, and the result types."""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import cached_property, partial
from typing import NamedTuple

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..errors import BadSweep, CannotAssemble, MotionError
from ..structure.joints import MESH, REVOLUTE
from ._dyads import Closure, decompose
from ._linkage import Linkage, joint_name
from ._system import System

__all__ = ["Motion", "MotionRange", "LinkPoses", "Branch", "sweep", "sweep_grid", "motion_range", "pose_branch", "assemble",
           "link_poses", "LinkRates", "link_rates", "refine_extreme"]


@dataclass(frozen=True, eq=False)
class Motion:
    """The result of a sweep: where every joint and tracer point is at each step.

    Attributes
    ----------
    linkage : Linkage
    inputs : ndarray (S, W)
        Input values per step: a revolute input's angle in rad, a prismatic input's displacement.
    joints : ndarray (S, J, 2)
        Every joint's position (a prismatic joint: its point carried by the joint's first link).
    tracers : dict str -> ndarray (S, 2)
    velocities, accelerations : ndarray (S, J, 2) or None
        Per unit input rate (rad/s or length/s), input accelerating at zero; None unless asked for.
        With W > 1, velocities are (S, W, J, 2): one per input.  NaN where the step is a dead position.
    tracer_velocities, tracer_accelerations : dict str -> ndarray (S, 2) or None
        The same for each tracer point ((S, W, 2) for W > 1); None unless asked for.
    stopped : str or None
        One sentence when the sweep ended at a dead or singular position (with the input there).
    grid : tuple of int or None
        For a grid (:func:`sweep_grid`): the values per input, the steps in row-major order.
    transmission : dict
        Per closed-form dyad: least and greatest transmission angle and where (computed when read).
    angles : ndarray (S, n)
        Each link's rotation from the pose (rad, modulo a turn; computed when read for a linkage of
        dyads, whose sweep needs no angle).
    """

    linkage: Linkage
    inputs: np.ndarray
    joints: np.ndarray
    tracers: dict
    velocities: np.ndarray | None = None
    accelerations: np.ndarray | None = None
    stopped: str | None = None
    grid: tuple[int, ...] | None = None
    #: the angles (S, n), or a function that computes them
    _angles: np.ndarray | Callable[[], np.ndarray] | None = field(default=None, repr=False)
    tracer_velocities: dict | None = None
    tracer_accelerations: dict | None = None

    @cached_property
    def angles(self) -> np.ndarray:
        """(S, n): each link's rotation from the pose (rad, modulo a turn)."""
        return self._angles() if callable(self._angles) else self._angles

    @cached_property
    def transmission(self) -> dict:
        """Per closed-form dyad (key ``"links i, j"``): its ``kind``, ``min`` and ``max`` transmission
        angle over the sweep (rad; π/2 best, 0 or π a dead position) and the inputs ``at_min``,
        ``at_max`` where they occur, refined between steps by a bounded search.  Empty for a
        linkage moved by Newton's method, or a grid."""
        solver = _solver(self.linkage)
        if solver.plan is None or self.inputs.shape[1] != 1 or self.steps < 2:
            return {}
        offsets = self.inputs[:, 0] - self.linkage.pose_inputs[0]
        return _transmission(solver, offsets, solver.closed(offsets[:, None])[3], float(self.linkage.pose_inputs[0]))

    @property
    def steps(self) -> int:
        return len(self.inputs)

    def extent(self) -> dict[str, tuple[float, float, float, float]]:
        """Each tracer's curve extent ``(x_min, y_min, x_max, y_max)`` over the sweep (NaN steps left
        out).  For one input each extreme is refined between the steps beside it by a bounded search
        (input to 1e-10), so where the steps are closer than the curve's turns it is the curve's own to
        about 1e-12 of its size, not the samples' (a sampled extreme falls short by up to (step)² × the
        curvature: 1.4e-5 on a four-bar of size 2 at 360 steps); a grid's extent is its samples'.

        >>> from synth.structure.chain import Chain, Mechanism
        >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [0, 1], [3.5, 3]],
        ...              tracers={"A": (1, (0.0, 1.0))})
        >>> [round(v, 12) for v in sweep(lk, steps=7).extent()["A"]]  # samples 60° apart: the circle's own box
        [-1.0, -1.0, 1.0, 1.0]
        """
        point = self._tracer_at if self.inputs.shape[1] == 1 and self.grid is None and self.steps >= 2 else None
        out = {}
        for name, xy in self.tracers.items():
            finite = np.flatnonzero(np.isfinite(xy).all(axis=1))
            if not len(finite):
                out[name] = (math.nan,) * 4
                continue
            box = []
            for sign, axis in ((1.0, 0), (1.0, 1), (-1.0, 0), (-1.0, 1)):
                k = int(finite[np.argmin(sign * xy[finite, axis])])
                best = float(xy[k, axis])
                if point is not None:
                    best = refine_extreme(lambda x: point(name, x)[axis], *_beside(self.inputs[:, 0], k),
                                          (self.inputs[k, 0], best), largest=sign < 0)[1]
                box.append(best)
            out[name] = tuple(box)
        return out

    def _tracer_at(self, name: str, value: float) -> np.ndarray:
        """Tracer ``name``'s point at input ``value`` on the sweep's branch (NaN where it does not close)."""
        solver = _solver(self.linkage)
        x = value - float(self.linkage.pose_inputs[0])
        if solver.plan is not None:
            return solver.closure.points(np.array([[x]]))[1][name][0]
        lo, hi, _, _ = solver.branch
        if solver.revolute[0] and math.isfinite(lo) and not lo <= x <= hi:  # the same angle a turn on or back
            x -= 2 * math.pi * math.floor((x - lo) / (2 * math.pi))
        try:
            theta, t, _ = solver.poses_along(np.array([x]))
        except CannotAssemble:
            return np.full(2, math.nan)
        return _points(self.linkage, theta, t)[1][name][0]

    def rows(self) -> Iterator[dict]:
        """One JSON-able dict per step: ``step``, ``input`` (for W > 1 one column per input joint,
        ``"input.0-1"``), each joint's ``x``/``y`` keyed by its name (``"1-2.x"``), each tracer's, and
        velocities (``"1-2.vx"``, a tracer's ``"P.vx"``; for W > 1 per unit rate of each input,
        ``"1-2.vx.0-1"``) and accelerations (``"1-2.ax"``) where computed (None where undefined:
        beyond a grid's reach).

        >>> from synth.structure.chain import Chain, Mechanism
        >>> five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
        ...                    [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])
        >>> list(next(sweep_grid(five_bar, [(1.4, 1.8), (1.4, 1.8)], steps=2).rows()))[:4]
        ['step', 'input.0-1', 'input.0-4', '0-1.x']
        """
        chain = self.linkage.chain
        names = [joint_name(chain, k) for k in range(len(chain.joints))]
        inputs = [joint_name(chain, k) for k in self.linkage.inputs]

        def num(v):
            v = float(v)
            return v if math.isfinite(v) else None

        for s in range(self.steps):
            row = {"step": s}
            if len(inputs) == 1:
                row["input"] = num(self.inputs[s, 0])
            else:
                row.update((f"input.{name}", num(v)) for name, v in zip(inputs, self.inputs[s]))
            for k, name in enumerate(names):
                row[f"{name}.x"], row[f"{name}.y"] = num(self.joints[s, k, 0]), num(self.joints[s, k, 1])
            for name, xy in self.tracers.items():
                row[f"{name}.x"], row[f"{name}.y"] = num(xy[s, 0]), num(xy[s, 1])
            for label, values, of_tracers in (("v", self.velocities, self.tracer_velocities),
                                              ("a", self.accelerations, self.tracer_accelerations)):
                if values is None:
                    continue
                of_tracers = of_tracers or {}
                per_input = ([("", values[s], {n: xy[s] for n, xy in of_tracers.items()})] if values.ndim == 3 else
                             [(f".{w}", values[s, i], {n: xy[s, i] for n, xy in of_tracers.items()})
                              for i, w in enumerate(inputs)])
                for tail, at_joints, at_tracers in per_input:
                    for name, (vx, vy) in [*zip(names, at_joints), *at_tracers.items()]:
                        row[f"{name}.{label}x{tail}"], row[f"{name}.{label}y{tail}"] = num(vx), num(vy)
            yield row


@dataclass(frozen=True)
class MotionRange:
    """How far the input of a 1-DOF linkage moves on the branch of its pose.

    Attributes
    ----------
    full_rotation : bool
        The (revolute) input turns fully: a crank.
    limits : (float, float) or None
        The input's lower and upper limits (rad or length) where it does not turn fully, each a
        dead position located to 1e-9.
    dead_positions : tuple of (float, str)
        The inputs where the branch ends, with a sentence naming the group that locks.
    toggles : tuple of (float, int)
        Inputs where a link jointed to the frame (an output) stops and turns back, and that link:
        a dead position if that link drives.
    grashof : str or None
        For a four-bar of revolute joints: its Grashof class, e.g. ``"crank-rocker"``.
    """

    full_rotation: bool
    limits: tuple[float, float] | None
    dead_positions: tuple = ()
    toggles: tuple = ()
    grashof: str | None = None


#: the most steps one sweep computes (a grid: in all)
MAX_STEPS = 10_000_000
#: samples of the input's circle (or line) when the branch's ends are looked for
SAMPLES = 4096
#: the ends of a branch are located to this (rad, or this × the mechanism's size)
LIMIT_TOL = 1e-11
#: a sweep's start and stop are held to this (rad, or this × the mechanism's size) by a float, and their last
#: place is less than a step: else they are too far from zero to sweep (refused)
RESOLVED = 1e-9
#: Newton's method stops where every closure equation holds to this × the mechanism's size
CLOSURE_TOL = 1e-14


def _dyad_name(linkage: Linkage, d) -> str:
    i, j = d.links
    return f"the {d.kind} dyad of links {i}, {j}"


class _Solver:
    """How one linkage is moved: its dyads in closed form, else Newton with continuation; its
    branch's ends (computed once per linkage)."""

    def __init__(self, linkage: Linkage):
        self.linkage = linkage
        self.system = System(linkage)
        self.plan = decompose(linkage)
        self.closure = None if self.plan is None else Closure(linkage, self.plan)
        self.revolute = [linkage.kind(k) == REVOLUTE for k in linkage.inputs]

    # ------------------------------------------------------------ positions
    def closed(self, offsets: np.ndarray):
        """θ, t, g, μ and the joints' positions at input offsets (S, W) by the dyads' closed forms."""
        return self.closure(offsets)

    def discriminants(self, x: float) -> np.ndarray:
        """The dyads' discriminants at 1-DOF offset x (each ≥ 0 where its dyad closes; −1 for NaN)."""
        g = self.closed(np.array([[x]]))[2][0]
        return np.where(np.isfinite(g), g, -1.0)

    @cached_property
    def pose_sign(self) -> int:
        """The sign of det J in the pose: constant along its branch, which ends where J is singular."""
        return _det_sign(self.system, *self.system.poses(np.zeros((1, self.system.size))))

    def trace(self, q: np.ndarray, x_from: np.ndarray, x_to: np.ndarray, targets: np.ndarray, sign: int):
        """Follow the branch from (q, x_from) along the straight path to x_to in input offsets.

        The path is traced by pseudo-arclength continuation in (q, u), u the distance along the
        input path: each step is predicted along the curve's tangent and corrected by Newton's
        method on the closure equations bordered by the step's hyperplane, so the curve is
        followed through near-singular places and turns, never jumping to another branch (the
        step shrinks until successive tangents differ by less than 0.1 rad).  Where u turns back
        (a fold: det J = 0, a dead position), the trace stops and the fold's u is located as the
        maximum of u along the curve.

        Returns (solutions at ``targets`` — distances along the path, ascending — as an array
        (T', 3m) of those reached, the distance where the trace stopped or None).
        """
        system, lk = self.system, self.linkage
        span = np.asarray(x_to, dtype=float) - x_from
        length = float(np.abs(span).max())
        direction = span / length
        cols = system.size
        weight = np.ones(cols + 1)  # translations measured in sizes of the mechanism
        weight[0:cols:3] = weight[1:cols:3] = lk.scale
        rate = system.rate_column() @ direction

        def values(u):
            return (lk.pose_inputs + x_from + u * direction)[None, :]

        def matrix(y):  # the closure Jacobian in the scaled unknowns (q/weight, u)
            theta, t = system.poses((y[:-1] * weight[:-1])[None])
            return np.concatenate((system.jacobian(theta, t)[0] * weight[:-1], -rate[:, None]), axis=1), theta, t

        def residual(y):
            theta, t = system.poses((y[:-1] * weight[:-1])[None])
            return system.residual(theta, t, values(y[-1]))[0]

        def tangent(y, previous):
            a = matrix(y)[0]
            bordered = np.vstack((a, previous))
            try:
                tan = np.linalg.solve(bordered, np.append(np.zeros(len(a)), 1.0))
            except np.linalg.LinAlgError:
                return None
            return tan / np.linalg.norm(tan)

        def correct(y_guess, normal):
            y = y_guess.copy()
            for _ in range(12):
                r = residual(y)
                if np.abs(r).max() <= CLOSURE_TOL * lk.scale and abs(normal @ (y - y_guess)) <= 1e-15:
                    return y
                a = matrix(y)[0]
                g = np.append(r, normal @ (y - y_guess))
                try:
                    dy = np.linalg.solve(np.vstack((a, normal)), -g)
                except np.linalg.LinAlgError:
                    return None
                if not np.isfinite(dy).all():
                    return None
                y = y + dy
            return y if np.abs(residual(y)).max() <= CLOSURE_TOL * lk.scale * 10 else None

        def natural(y_guess, u):  # the curve's point at distance u, near y_guess
            y = y_guess.copy()
            y[-1] = u
            for _ in range(12):
                theta, t = system.poses((y[:-1] * weight[:-1])[None])
                r = system.residual(theta, t, values(u))[0]
                jac = system.jacobian(theta, t)[0] * weight[:-1]
                if np.abs(r).max() <= CLOSURE_TOL * lk.scale:
                    return y if int(np.sign(np.linalg.det(jac))) == sign or system.rows != system.size else None
                try:
                    y[:-1] -= np.linalg.lstsq(jac, r, rcond=None)[0] if system.rows != system.size \
                        else np.linalg.solve(jac, r)
                except np.linalg.LinAlgError:
                    return None
            return None

        y = np.append(q / weight[:-1], 0.0)
        start = np.zeros(cols + 1)
        start[-1] = 1.0
        tan = tangent(y, start)
        if tan is None or tan[-1] <= 0:
            return np.empty((0, cols)), 0.0
        targets = np.asarray(targets, dtype=float)
        out = []
        if len(targets) and targets[0] <= 0:
            out = [q.copy() for _ in targets[targets <= 0]]
        k = len(out)
        h, hmax = 0.05, 0.05
        while k < len(targets):
            guess = y + h * tan
            new = correct(guess, tan)
            new_tan = None if new is None else tangent(new, tan)
            if new is None or new_tan is None or new_tan @ tan < math.cos(0.1) \
                    or np.abs(new - guess).max() > 0.1 * h + 1e-12:
                h /= 2
                if h < 1e-13:
                    return np.array(out).reshape(-1, cols), float(y[-1])
                continue
            if new_tan[-1] <= 0:  # u turned back: a fold between y and new
                found = minimize_scalar(lambda s: -(c[-1] if (c := correct(y + s * tan, tan)) is not None else -np.inf),
                                        bounds=(0.0, h), method="bounded", options={"xatol": 1e-9 * h})
                top = correct(y + float(found.x) * tan, tan) if found.success else None
                if top is None or top[-1] < max(y[-1], new[-1]):
                    top = y if y[-1] >= new[-1] else new
                fold = float(top[-1])
                while k < len(targets) and targets[k] <= fold + LIMIT_TOL:
                    point = natural(y, targets[k]) if targets[k] < fold - 1e-9 else top
                    if point is None:
                        break
                    out.append(point[:-1] * weight[:-1])
                    k += 1
                return np.array(out).reshape(-1, cols), fold
            while k < len(targets) and targets[k] <= new[-1]:
                point = natural(y + (targets[k] - y[-1]) / (new[-1] - y[-1]) * (new - y), targets[k])
                if point is None:  # the interpolated start fell off the branch: step on, smaller
                    break
                out.append(point[:-1] * weight[:-1])
                k += 1
            else:
                y, tan = new, new_tan
                h = min(1.5 * h, hmax)
                continue
            h /= 2
            if h < 1e-13:
                break
        return np.array(out).reshape(-1, cols), None if k == len(targets) else float(y[-1])

    # ---------------------------------------------------------- the branch
    @cached_property
    def branch(self) -> tuple[float, float, str, str]:
        """(lo, hi, why lo, why hi): the 1-DOF input offsets where the pose's branch ends (±inf for a
        crank or an unbounded slide; why: a sentence naming the group that locks there)."""
        if self.linkage.dof != 1:
            raise MotionError("the range of motion is for a linkage of one input (W = 1)")
        if self.plan is not None:
            return self._branch_closed()
        return self._branch_newton()

    def _span(self) -> float:
        return 2 * math.pi if self.revolute[0] else 4.0 * self.linkage.scale

    def _measure(self, xs: np.ndarray) -> np.ndarray:
        """(S, G): each dyad's distance from a singular place at 1-DOF offsets xs — its discriminant g
        (negative where it cannot close) and, for an RRR dyad, also the gap between its outer pins
        over the size (0 at a change point, where its two links could turn together)."""
        _, _, g, _, joints = self.closed(xs[:, None])
        out = np.where(np.isfinite(g), g, -1.0)
        for m, d in enumerate(self.plan):
            if d.kind == "RRR":
                gap = np.hypot(*(joints[:, d.outer[1]] - joints[:, d.outer[0]]).T) / self.linkage.scale
                out[:, m] = np.where(out[:, m] >= 0, np.minimum(out[:, m], gap), out[:, m])
        return out

    def _touches(self, xs: np.ndarray, measure: np.ndarray) -> list[tuple[float, int]]:
        """(offset, dyad) where a dyad touches a singular place between samples without going
        negative (a change point), found by a bounded search around each small local minimum."""
        found = []
        for m in range(measure.shape[1]):
            col = measure[:, m]
            mid = col[1:-1]
            for i in np.flatnonzero((mid <= col[:-2]) & (mid <= col[2:]) & (mid >= 0) & (mid < 1e-3)) + 1:
                res = minimize_scalar(lambda x: float(self._measure(np.array([x]))[0, m]),
                                      bounds=(xs[i - 1], xs[i + 1]), method="bounded", options={"xatol": 1e-12})
                if res.fun <= 1e-9:
                    found.append((float(res.x), m))
        return found

    def _branch_closed(self):
        span = self._span()
        while True:
            xs = (np.linspace(-2 * math.pi, 2 * math.pi, 2 * SAMPLES + 1) if self.revolute[0]
                  else np.linspace(-span, span, SAMPLES + 1))
            measure = self._measure(xs)
            bad = (measure < 0).any(axis=1)
            if self.revolute[0] or bad[0] and bad[-1] or span > 1e4 * self.linkage.scale:
                break
            span *= 4
        touches = self._touches(xs, measure)
        centre = len(xs) // 2
        ends = []
        for step in (-1, 1):
            beyond = np.flatnonzero(bad[centre + 1:] if step > 0 else bad[:centre][::-1])  # the first sample that fails
            k = centre + step * (int(beyond[0]) if len(beyond) else (len(xs) - 1 - centre if step > 0 else centre))
            end = (step * math.inf, "")
            if 0 <= k + step < len(xs):
                good_x, bad_x = xs[k], xs[k + step]
                while abs(bad_x - good_x) > LIMIT_TOL:  # bisection: every dyad closes at good_x, one not at bad_x
                    middle = 0.5 * (good_x + bad_x)
                    if self.discriminants(middle).min() >= 0:
                        good_x = middle
                    else:
                        bad_x = middle
                root, m = good_x, int(np.argmin(self.discriminants(bad_x)))
                end = (root, f"{_dyad_name(self.linkage, self.plan[m])} is aligned (a dead position)")
            for x, m in sorted(touches, key=lambda found: abs(found[0])):
                if x * step > 0 and abs(x) < abs(end[0]):
                    end = (x, f"{_dyad_name(self.linkage, self.plan[m])} passes a change point (its links could "
                              "turn together there: a singular position)")
                    break
            ends.append(end)
        (lo, why_lo), (hi, why_hi) = ends
        if self.revolute[0] and hi - lo >= 2 * math.pi:
            return -math.inf, math.inf, "", ""
        return lo, hi, why_lo, why_hi

    def _branch_newton(self):
        ends = []
        span = self._span()
        for step in (-1, 1):
            found, stop = self.trace(np.zeros(self.system.size), np.zeros(1), np.array([step * span]), [span],
                                     self.pose_sign)
            if self.revolute[0] and len(found):
                if _same_pose(self.system, found[0]):
                    return -math.inf, math.inf, "", ""  # back to the pose after one turn: a crank
                # a branch that returns to the input's angle in another pose: follow it up to three turns more
                more, stop = self.trace(found[0], np.array([step * span]), np.array([4 * step * span]), [3 * span],
                                        self.pose_sign)
                stop = None if stop is None else span + stop
            if stop is None:  # (a slide that runs on, or a revolute input that turns on for four turns)
                ends.append((step * math.inf, ""))
            else:
                ends.append((step * stop, "the loop-closure equations of its links are singular (a dead position)"))
        (lo, why_lo), (hi, why_hi) = ends
        return lo, hi, why_lo, why_hi

    # ------------------------------------------------------------- sweeps
    def poses_along(self, offsets: np.ndarray):
        """θ, t (and the joints, or None) at 1-DOF offsets, all on the branch of the pose."""
        if self.plan is not None:
            theta, t, _, _, joints = self.closed(offsets[:, None])
            return theta, t, joints
        out = np.empty((len(offsets), self.system.size))
        for side in (-1, 1):
            chosen = np.flatnonzero(offsets * side > 0) if side > 0 else np.flatnonzero(offsets * side >= 0)
            if not len(chosen):
                continue
            order = chosen[np.argsort(np.abs(offsets[chosen]))]
            far = float(np.abs(offsets[order[-1]]))
            if far == 0:
                out[order] = 0.0
                continue
            found, _ = self.trace(np.zeros(self.system.size), np.zeros(1), np.array([side * far]),
                                  np.abs(offsets[order]), self.pose_sign)
            if len(found) < len(order):
                raise CannotAssemble(f"the linkage cannot reach input offset {offsets[order[len(found)]]:.9g} from its "
                                     "pose on its branch")
            out[order] = found
        theta, t = self.system.poses(out)
        return theta, t, None


def _same_pose(system: System, q: np.ndarray) -> bool:
    """Whether the link poses q are the pose's (angles modulo a turn)."""
    angles = q[2::3]
    turned = np.abs(np.remainder(angles + math.pi, 2 * math.pi) - math.pi).max(initial=0.0)
    moved = np.abs(np.delete(q, np.s_[2::3])).max(initial=0.0)
    return bool(turned < 1e-7 and moved < 1e-7 * system.linkage.scale)


def _det_sign(system: System, theta, t) -> int:
    if system.rows != system.size:
        return 1
    return int(np.sign(np.linalg.det(system.jacobian(theta, t)[0])))


def _solver(linkage: Linkage) -> _Solver:
    """The linkage's solver, built on first use and kept on the (immutable) linkage."""
    solver = linkage.__dict__.get("_motion_solver")
    if solver is None:
        solver = linkage.__dict__["_motion_solver"] = _Solver(linkage)
    return solver


class LinkPoses(NamedTuple):
    """Every link's pose at given input offsets, as rigid motions from the linkage's own pose.

    A point p of link l (placed as in the pose) is at R(θ[s, l]) p + t[s, l] at step s.

    Attributes
    ----------
    rotations : ndarray (S, n)
        θ: each link's rotation from the pose (rad).
    translations : ndarray (S, n, 2)
        t: each link's translation after that rotation about the origin.
    discriminants : ndarray (S, G) or None
        Each closed-form dyad's normalised discriminant (it closes where ≥ 0; NaN where the dyads
        before it did not close); None for a linkage moved by Newton's method.
    transmission : ndarray (S, G) or None
        Each dyad's transmission angle (rad, in [0, π]; NaN for a gear mesh); None as above.
    """

    rotations: np.ndarray
    translations: np.ndarray
    discriminants: np.ndarray | None
    transmission: np.ndarray | None


def link_poses(linkage: Linkage, offsets) -> LinkPoses:
    """The poses of every link at the given input offsets from the pose, on the pose's branch (1-DOF).

    The public entry to the motion layer's position solver for callers that move many dimensioned
    candidates at a few inputs each (dimensional synthesis, the curve index): no sweep is built and
    nothing is checked beyond the branch.  A linkage of dyads is closed in closed form at every
    offset independently (where a dyad cannot close its links' poses are NaN and its discriminant
    negative); a linkage with a triad or higher group is followed by Newton continuation from the
    pose, outwards on each side, and raises where the branch ends.

    Parameters
    ----------
    linkage : Linkage
        One input (W = 1).
    offsets : array_like (S,)
        Input values less the pose's input (rad, or a length for a prismatic input).

    Returns
    -------
    LinkPoses
        (rotations, translations, discriminants, transmission); the last two are None for a
        linkage moved by Newton's method.

    Raises
    ------
    BadSweep
        A linkage with more than one input, or offsets that are not finite numbers.
    CannotAssemble
        (Newton's method only) the branch does not reach an offset.

    Notes
    -----
    Closed forms cost O(S·G) in the compiled kernel; Newton continuation costs a trace of the
    branch out to the farthest offset on each side.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> poses = link_poses(lk, [0.0, np.pi / 2])
    >>> poses.rotations[:, 1].round(12).tolist()          # the crank (link 1) turns by the offset
    [0.0, 1.570796326795]
    >>> theta, t = poses.rotations[1, 1], poses.translations[1, 1]
    >>> (np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]]) @ [1, 0] + t).round(12).tolist()
    [0.0, 1.0]
    >>> bool((poses.discriminants >= 0).all())
    True
    """
    if linkage.dof != 1:
        raise BadSweep(f"link_poses moves a linkage of one input, not W = {linkage.dof}")
    try:
        offsets = np.asarray(offsets, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise BadSweep("the input offsets must be numbers") from None
    if not np.isfinite(offsets).all():
        raise BadSweep("the input offsets must be finite numbers")
    plan = decompose(linkage)
    if plan is None:
        theta, t, _ = _solver(linkage).poses_along(offsets)
        return LinkPoses(theta, t, None, None)
    theta, t, g, mu, _ = Closure(linkage, plan)(offsets[:, None])
    return LinkPoses(theta, t, g, mu)


class LinkRates(NamedTuple):
    """Every link's pose and its first and second derivatives with respect to the input (1-DOF).

    The input's derivatives: per radian of a revolute input, per unit length of a prismatic one.
    Multiplied by the input's rate ω (and ω²) they are the links' velocities (and their accelerations
    at a constant ω).  A point p of link l is at R(θ) p + t; its derivative is θ' J R(θ) p + t'.

    Attributes
    ----------
    rotations, translations : ndarray (S, n), (S, n, 2)
        θ and t, as :class:`LinkPoses`.
    rotation_rates, translation_rates : ndarray (S, n), (S, n, 2)
        θ' = dθ/dq and t' = dt/dq.
    rotation_accelerations, translation_accelerations : ndarray (S, n), (S, n, 2)
        θ'' and t''; NaN with the rates where the input is at a dead position.
    """

    rotations: np.ndarray
    translations: np.ndarray
    rotation_rates: np.ndarray
    translation_rates: np.ndarray
    rotation_accelerations: np.ndarray
    translation_accelerations: np.ndarray


def link_rates(linkage: Linkage, offsets) -> LinkRates:
    """The poses of every link at the given input offsets (as :func:`link_poses`) and their first and
    second derivatives with respect to the input: linear solves of the closure Jacobian, as a sweep's
    velocities and accelerations.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> r = link_rates(lk, [0.0, 1.0])
    >>> r.rotation_rates[:, 1].tolist(), bool(np.abs(r.rotation_accelerations[:, 1]).max() < 1e-12)  # crank: θ' = 1, θ'' = 0
    ([1.0, 1.0], True)
    """
    theta, t = link_poses(linkage, offsets)[:2]
    system = _solver(linkage).system
    qd, qdd = system.rates(theta, t, accelerations=True)
    dtheta, dt = system.poses(qd[:, 0])
    ddtheta, ddt = system.poses(qdd[:, 0])
    return LinkRates(theta, t, dtheta, dt, ddtheta, ddt)


def _check_steps(steps, name: str = "steps") -> int:
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)):
        raise BadSweep(f"{name} must be a whole number of steps, not {steps!r}")
    if not 2 <= steps <= MAX_STEPS:
        raise BadSweep(f"{name} must be 2 … {MAX_STEPS:,} (a sweep's steps, start and stop included), not {steps}")
    return int(steps)


def _check_value(value, name: str) -> float:
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise BadSweep(f"{name} must be a number, not {value!r}") from None
    if isinstance(value, bool) or not math.isfinite(out):
        raise BadSweep(f"{name} must be a finite number, not {value!r}")
    return out


def _check_resolved(linkage: Linkage, ends, step: float, i: int = 0) -> None:
    """Refuse a value of input ``i`` (``ends``: (name, value) pairs) so far from zero that a float does not hold
    it to :data:`RESOLVED` (rad, or times the mechanism's size) or tells it from the next, ``step`` on (a crank
    from 1e308°: start + one turn is start)."""
    revolute = linkage.kind(linkage.inputs[i]) == REVOLUTE
    for name, value in ends:
        last = math.ulp(value)
        if last > RESOLVED * (1.0 if revolute else linkage.scale) or last >= step:
            shown = f"{math.degrees(value):.6g}° ({value:.6g} rad)" if revolute else f"{value:.6g}"
            raise BadSweep(f"{name} {shown} is too far from zero: a float that large is known only to "
                           f"{last:.3g}{' rad' if revolute else ''}; give an input within a few turns (or sizes) of "
                           "the pose")


def _describe(linkage: Linkage, value: float) -> str:
    """An input value as a designer reads it: degrees for a revolute input."""
    if linkage.kind(linkage.inputs[0]) == REVOLUTE:
        return f"{value:.9f} rad ({math.degrees(value):.6f}°)"
    return f"{value:.9g}"


def _points(linkage: Linkage, theta, t, joints=None):
    """Every joint's position (S, J, 2) (unless given) and every tracer's (S, 2) from link poses."""
    if joints is None:
        p = linkage.points
        first = np.array([j[0] for j in linkage.chain.joints])
        c, s = np.cos(theta[:, first]), np.sin(theta[:, first])
        joints = np.stack((c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]), axis=-1) + t[:, first]
    tracers = {}
    for name, (link, (x, y)) in linkage.tracers.items():
        c, s = np.cos(theta[:, link]), np.sin(theta[:, link])
        tracers[name] = np.stack((c * x - s * y, s * x + c * y), axis=-1) + t[:, link]
    return joints, tracers


def _point_rates(linkage: Linkage, theta, dtheta, dt, ddtheta=None, ddt=None):
    """Velocities (or accelerations, given second derivatives) of every joint and tracer."""
    p = linkage.points
    links = [j[0] for j in linkage.chain.joints] + [link for link, _ in linkage.tracers.values()]
    pts = np.concatenate([p, np.array([at for _, at in linkage.tracers.values()]).reshape(-1, 2)])
    links = np.array(links)
    c, s = np.cos(theta[:, links]), np.sin(theta[:, links])
    rp = np.stack((c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]), axis=-1)
    perp = np.stack((-rp[..., 1], rp[..., 0]), axis=-1)
    if ddtheta is None:
        out = dt[:, links] + dtheta[:, links, None] * perp
    else:
        out = ddt[:, links] + ddtheta[:, links, None] * perp - dtheta[:, links, None] ** 2 * rp
    j = len(linkage.chain.joints)
    return out[:, :j], {name: out[:, j + i] for i, name in enumerate(linkage.tracers)}


def _rates(linkage: Linkage, theta, t, accelerations: bool):
    """Velocities and accelerations per unit rate of each input: the joints' (S, W, J, 2) and each
    tracer's (S, W, 2) by name, velocities then accelerations (None unless asked for)."""
    system = _solver(linkage).system
    qd, qdd = system.rates(theta, t, accelerations)
    vel, acc = [], []
    for i in range(linkage.dof):
        dtheta, dt = system.poses(qd[:, i])
        vel.append(_point_rates(linkage, theta, dtheta, dt))
        if accelerations:
            ddtheta, ddt = system.poses(qdd[:, i])
            acc.append(_point_rates(linkage, theta, dtheta, dt, ddtheta, ddt))

    def stacked(per_input):
        if not per_input:
            return None, None
        return (np.stack([joints for joints, _ in per_input], axis=1),
                {name: np.stack([tracers[name] for _, tracers in per_input], axis=1) for name in linkage.tracers})
    return (*stacked(vel), *stacked(acc))


def sweep(linkage: Linkage, *, steps: int = 360, start: float | None = None, stop: float | None = None,
          velocities: bool = False, accelerations: bool = False) -> Motion:
    """Move a 1-DOF linkage through its input range on the assembly branch of its pose.

    Parameters
    ----------
    linkage : Linkage
    steps : int
        Number of input values, start and stop included (2 … 10 000 000).
    start, stop : float, optional
        Input range (rad for a revolute input — the angle of the driven link's line from the input
        joint to its reference joint — or displacement from the pose for a prismatic input).
        Default: a crank turns once from its pose; a rocker goes from its lower to its upper limit.
    velocities, accelerations : bool
        Also compute them, per unit input rate (linear solves of the closure Jacobian).

    Returns
    -------
    Motion
        ``stopped`` says where the sweep ended early at a dead position; its last step is that
        position (located to 1e-9).

    Raises
    ------
    WrongInputs
        The linkage has more than one input (use :func:`sweep_grid`).
    BadSweep
        ``steps``, ``start`` or ``stop`` is not a usable number.
    CannotAssemble
        ``start`` is outside what the pose's branch reaches.

    Notes
    -----
    A linkage that decomposes into dyads is computed in closed form for all steps at once
    (numpy), the assembly mode of each dyad kept from the pose; any other by Newton's method with
    continuation from the pose.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> m = sweep(lk, steps=5)
    >>> m.inputs[:, 0].round(4).tolist(), m.stopped
    ([0.0, 1.5708, 3.1416, 4.7124, 6.2832], None)
    """
    from ..errors import WrongInputs

    steps = _check_steps(steps)
    if linkage.dof != 1:
        raise WrongInputs(f"this linkage has {linkage.dof} inputs: sweep a grid of them with sweep_grid")
    solver = _solver(linkage)
    phi0 = float(linkage.pose_inputs[0])
    lo, hi, why_lo, why_hi = solver.branch
    revolute = solver.revolute[0]
    start = None if start is None else _check_value(start, "start")
    stop = None if stop is None else _check_value(stop, "stop")
    crank = revolute and math.isinf(lo) and math.isinf(hi)
    stop_given = stop is not None
    both = start is not None and stop_given
    if start is None:
        start = phi0 if crank or math.isinf(lo) else phi0 + lo
    if stop is None:
        stop = start + 2 * math.pi if crank else (phi0 + hi if math.isfinite(hi) else start + 4 * linkage.scale)
    if both and start == stop:
        raise BadSweep("start and stop are the same input: a sweep needs a range")
    _check_resolved(linkage, (('start', start), ('stop', stop)) if stop_given else (('start', start),),
                    abs(stop - start) / (steps - 1))
    x0 = start - phi0
    if revolute and not crank and not lo - LIMIT_TOL <= x0 <= hi + LIMIT_TOL:  # the same angle a turn on or back
        x0 -= 2 * math.pi * math.floor((x0 - lo) / (2 * math.pi))
    if not lo - LIMIT_TOL <= x0 <= hi + LIMIT_TOL:
        raise CannotAssemble(f"the linkage cannot be assembled at input {_describe(linkage, start)} on the branch of "
                             f"its pose, which moves between {_describe(linkage, phi0 + lo)} and "
                             f"{_describe(linkage, phi0 + hi)} ({why_lo if x0 < lo else why_hi} at that end)")
    x0 = min(max(x0, lo), hi)
    x1 = x0 + (stop - start)
    offsets = np.linspace(x0, x1, steps)
    stopped = None
    end, why = (hi, why_hi) if x1 > x0 else (lo, why_lo)
    if (x1 - end) * (x1 - x0) > 0 and abs(x1 - end) > LIMIT_TOL:
        inside = offsets[(offsets - end) * np.sign(x1 - x0) < 0]
        offsets = np.append(inside, end)
        stopped = f"the sweep stops at input {_describe(linkage, phi0 + end)}: {why}; the input cannot go further"
    np.clip(offsets, lo, hi, out=offsets)  # (a range that ends at a limit, written as an input, rounds past it)
    if solver.plan is not None and not (velocities or accelerations):  # the poses and points only: in one pass
        joints, tracers = solver.closure.points(offsets[:, None])
        theta = partial(solver.closure.angles, offsets[:, None])
    else:
        theta, t, joints = solver.poses_along(offsets)
        if joints is None or linkage.tracers:
            joints, tracers = _points(linkage, theta, t, joints)
        else:
            tracers = {}
    inputs = (offsets + (start - x0))[:, None]
    rates = [None] * 4  # the joints' and tracers' velocities, then accelerations
    if velocities or accelerations:
        at_limit = np.isclose(offsets, lo, atol=1e-9, rtol=0) | np.isclose(offsets, hi, atol=1e-9, rtol=0)
        for i, found in enumerate(_rates(linkage, theta, t, accelerations)):
            if found is None or (i < 2 and not velocities):
                continue
            for values in ([found] if i % 2 == 0 else found.values()):
                values[at_limit] = np.nan
            rates[i] = found[:, 0] if i % 2 == 0 else {name: xy[:, 0] for name, xy in found.items()}
    vel, tracer_vel, acc, tracer_acc = rates
    return Motion(linkage, inputs, joints, tracers, vel, acc, stopped, None, theta, tracer_vel, tracer_acc)


def refine_extreme(f: Callable[[float], float], a: float, b: float, sample: tuple[float, float], *,
                   largest: bool = False) -> tuple[float, float]:
    """Refine an extreme found by sampling: the input and value of the least ``f`` on [a, b] (the
    greatest with ``largest=True``) by a bounded search to 1e-10 of the input; ``sample``, the sampled
    (input, value), where the search finds none better (a value that is not finite counts as worst).

    >>> x, v = refine_extreme(math.cos, 3.0, 3.3, (3.0, math.cos(3.0)))   # cos is least at π
    >>> round(x, 7), v
    (3.1415927, -1.0)
    """
    sign = -1.0 if largest else 1.0
    if not b > a:
        return sample

    def value(x):
        v = sign * float(f(x))
        return v if math.isfinite(v) else math.inf

    found = minimize_scalar(value, bounds=(a, b), method="bounded", options={"xatol": 1e-10})
    if found.success and found.fun < sign * sample[1]:
        return float(found.x), sign * float(found.fun)
    return sample


def _beside(xs: np.ndarray, k: int) -> tuple[float, float]:
    """The samples beside ``xs[k]`` (within the sweep's range): the bracket of a sampled extreme."""
    lo, hi = min(xs[0], xs[-1]), max(xs[0], xs[-1])
    a, b = xs[max(k - 1, 0)], xs[min(k + 1, len(xs) - 1)]
    return max(min(a, b), lo), min(max(a, b), hi)


def _transmission(solver: _Solver, offsets: np.ndarray, mu: np.ndarray, phi0: float) -> dict:
    """Each dyad's least and greatest transmission angle over the sweep, refined between samples; at a
    dead position where the branch ends because this dyad is aligned, exactly 0 or π (the end is
    located to 1e-11 of the input, where the angle is still about its square root: 1e-4°)."""
    out = {}
    branch_lo, branch_hi, why_lo, why_hi = solver.branch

    def aligned_end(x: float, d) -> bool:
        """Whether offset x is an end of the branch (a turn on or back, for a revolute input) where dyad d
        is aligned."""
        for end, why in ((branch_lo, why_lo), (branch_hi, why_hi)):
            gap = x - end
            if solver.revolute[0]:
                gap = (gap + math.pi) % (2 * math.pi) - math.pi
            if abs(gap) <= 1e-9 and why.startswith(_dyad_name(solver.linkage, d)):
                return True
        return False

    for m, d in enumerate(solver.plan):
        if d.kind == "gear":
            continue
        entry = {"kind": d.kind}
        for label, sign in (("min", 1.0), ("max", -1.0)):
            k = int(np.nanargmin(sign * mu[:, m]))
            best_x, best = refine_extreme(lambda x: solver.closed(np.array([[x]]))[3][0, m], *_beside(offsets, k),
                                          (float(offsets[k]), float(mu[k, m])), largest=sign < 0)
            snap = 0.0 if best < math.pi / 2 else math.pi
            if abs(best - snap) < 1e-3 and aligned_end(float(offsets[k]), d):
                best, best_x = snap, float(offsets[k])
            entry[label], entry[f"at_{label}"] = best, float(phi0 + best_x)
        out[f"links {d.links[0]}, {d.links[1]}"] = entry
    return out


def sweep_grid(linkage: Linkage, ranges, *, steps=None, velocities: bool = False,
               progress: Callable[[int], None] | None = None) -> Motion:
    """Move a linkage over a grid of its W inputs, on the assembly branch of its pose.

    Parameters
    ----------
    ranges : sequence of (start, stop)
        One input range per input, in the units of :func:`sweep`.
    steps : int or sequence of int
        Values per input (default 21 each); the grid has their product of steps (≤ 10 000 000).
    velocities : bool
        Velocities per unit rate of each input: ``Motion.velocities`` of shape (S, W, J, 2).
    progress : callable, optional
        Called with the number of cells solved since its last call (the cells of a linkage moved by
        Newton's method are solved one by one, each from a neighbour; closed forms solve all at once).

    Returns
    -------
    Motion
        ``inputs`` (S, W) in row-major grid order (the last input varying fastest), ``grid`` the
        steps per input; the cells the pose's branch does not reach (beyond a dead position, or only
        across one) are NaN.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> five_bar = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-4 4-0"), 0), (0, 1),
    ...                    [[0, 0], [3, 0], [0, 1], [1.5, 2.5], [3, 1]])   # joints 0-1 0-4 1-2 2-3 3-4
    >>> m = sweep_grid(five_bar, [(1.4, 1.8), (1.4, 1.8)], steps=3)
    >>> m.inputs.shape, bool(np.isfinite(m.joints).all())
    ((9, 2), True)
    """
    w = linkage.dof
    if isinstance(steps, (int, np.integer)) and not isinstance(steps, bool) or steps is None:
        steps = [21 if steps is None else steps] * w
    try:
        ranges = [(_check_value(a, "a range's start"), _check_value(b, "a range's stop")) for a, b in ranges]
        steps = [_check_steps(s, "each input's steps") for s in steps]
    except (TypeError, ValueError):
        raise BadSweep("ranges must be one (start, stop) pair per input, steps one count per input") from None
    if len(ranges) != w or len(steps) != w:
        raise BadSweep(f"this linkage has {w} input{'s' * (w > 1)}: give {w} range{'s' * (w > 1)} and step counts, "
                       f"not {len(ranges)} and {len(steps)}")
    total = math.prod(steps)
    if total > MAX_STEPS:
        raise BadSweep(f"the grid has {total:,} steps; at most {MAX_STEPS:,}")
    for i, ((a, b), count) in enumerate(zip(ranges, steps)):
        name = joint_name(linkage.chain, linkage.inputs[i])
        _check_resolved(linkage, ((f"input {name}'s start", a), (f"input {name}'s stop", b)),
                        abs(b - a) / (count - 1) if a != b else math.inf, i)
    axes = [np.linspace(a, b, s) for (a, b), s in zip(ranges, steps)]
    values = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, w)
    solver = _solver(linkage)
    shape = tuple(steps)
    # the cell nearest the pose, then every cell reached from a solved neighbour; the offsets from the pose less the
    # whole turns between the pose and that cell (the same positions: Newton's method starts from the pose)
    start, gap = _nearest_cell(axes, linkage.pose_inputs, solver.revolute)
    offsets = values - linkage.pose_inputs[None, :]
    offsets -= offsets[np.ravel_multi_index(start, shape)] - gap
    n = linkage.chain.links
    theta = np.full((total, n), np.nan)
    t = np.full((total, n, 2), np.nan)
    if solver.plan is not None:
        th, tt, g, _, _ = solver.closed(offsets)
        closes = (g >= 0).all(axis=1)
        reached = _flood(closes.reshape(shape), start)
        theta[reached], t[reached] = th[reached], tt[reached]
        if progress is not None:
            progress(int(reached.sum()))
    else:
        flat = np.ravel_multi_index(start, shape)
        reached = np.zeros(total, dtype=bool)
        qs = np.zeros((total, solver.system.size))
        first = _step(solver, np.zeros(solver.system.size), np.zeros(w), offsets[flat])
        if first is not None:
            qs[flat], reached[flat] = first, True
            if progress is not None:
                progress(1)
            queue = deque([start])
            while queue:
                cell = queue.popleft()
                here = np.ravel_multi_index(cell, shape)
                for axis in range(w):
                    for step in (-1, 1):
                        nxt = list(cell)
                        nxt[axis] += step
                        if not 0 <= nxt[axis] < shape[axis]:
                            continue
                        there = np.ravel_multi_index(tuple(nxt), shape)
                        if reached[there]:
                            continue
                        q = _step(solver, qs[here], offsets[here], offsets[there])
                        if q is not None:
                            qs[there], reached[there] = q, True
                            queue.append(tuple(nxt))
                            if progress is not None:
                                progress(1)
        th, tt = solver.system.poses(qs[reached])
        theta[reached], t[reached] = th, tt
    if not reached.any():
        raise CannotAssemble("the linkage cannot be assembled at the grid's input nearest to its pose on the branch "
                             "of its pose: widen the ranges to include the pose's inputs "
                             + ", ".join(f"{v:.6g}" for v in linkage.pose_inputs))
    joints, tracers = _points(linkage, np.nan_to_num(theta), np.nan_to_num(t))
    joints[~reached] = np.nan
    for xy in tracers.values():
        xy[~reached] = np.nan
    vel = tracer_vel = None
    if velocities:
        vel = np.full((total, w, len(linkage.chain.joints), 2), np.nan)
        tracer_vel = {name: np.full((total, w, 2), np.nan) for name in linkage.tracers}
        vel[reached], found = _rates(linkage, theta[reached], t[reached], False)[:2]
        for name, xy in found.items():
            tracer_vel[name][reached] = xy
    return Motion(linkage, values, joints, tracers, vel, None, None, shape, theta, tracer_vel)


def _nearest_cell(axes: list[np.ndarray], pose: np.ndarray, revolute: list[bool]) -> tuple[tuple[int, ...], np.ndarray]:
    """The grid's cell nearest the pose's inputs, a revolute input's angles compared within a turn (a grid from
    350° to 370° starts at 365° for a pose at 5°; of cells a whole turn apart, the nearer one), and the cell's
    inputs less the pose's, so reduced.

    >>> cell, gap = _nearest_cell([np.radians([340.0, 355.0, 370.0]), np.array([0.0, 1.0])],
    ...                           np.array([math.radians(5.0), 0.8]), [True, False])  # an angle, a slide
    >>> cell, round(math.degrees(gap[0]), 9), round(float(gap[1]), 12)  # 370° is 5° on (340°: 25° back)
    ((2, 1), 5.0, 0.2)
    """
    cell, gap = [], []
    for axis, value, turns in zip(axes, pose, revolute):
        raw = axis - value
        reduced = np.remainder(raw + math.pi, 2 * math.pi) - math.pi if turns else raw
        k = int(np.lexsort((np.abs(raw), np.round(np.abs(reduced), 12)))[0])
        cell.append(k)
        gap.append(float(reduced[k]))
    return tuple(cell), np.array(gap)


def _step(solver: _Solver, q: np.ndarray, x_from: np.ndarray, x_to: np.ndarray) -> np.ndarray | None:
    """The branch's pose at offsets x_to, followed from (q, x_from); None if a dead position is between."""
    length = float(np.abs(x_to - x_from).max())
    if length == 0:
        return q
    sign = _det_sign(solver.system, *solver.system.poses(q[None]))
    found, _ = solver.trace(q, x_from, x_to, [length], sign)
    return found[0] if len(found) else None


def _flood(ok: np.ndarray, start: tuple[int, ...]) -> np.ndarray:
    """The cells of ``ok`` connected to ``start`` through neighbours along each axis (flattened)."""
    reached = np.zeros(ok.shape, dtype=bool)
    if not ok[start]:
        return reached.ravel()
    reached[start] = True
    queue = deque([start])
    while queue:
        cell = queue.popleft()
        for axis in range(ok.ndim):
            for step in (-1, 1):
                nxt = list(cell)
                nxt[axis] += step
                nxt = tuple(nxt)
                if 0 <= nxt[axis] < ok.shape[axis] and ok[nxt] and not reached[nxt]:
                    reached[nxt] = True
                    queue.append(nxt)
    return reached.ravel()


_GRASHOF = {"frame": "double-crank", "input": "crank-rocker", "output": "rocker-crank", "coupler": "double-rocker"}


def _grashof(linkage: Linkage) -> str | None:
    """Grashof's class of a four-bar of revolute joints (None for any other linkage)."""
    chain = linkage.chain
    if chain.links != 4 or len(chain.joints) != 4 or not chain.all_revolute or chain.v:
        return None
    p, frame = linkage.points, linkage.frame
    length = {x: float(np.hypot(*np.subtract(*[p[k] for k in linkage.joints_of(x)]))) for x in range(4)}
    order = sorted(length, key=length.get)
    s, l = length[order[0]], length[order[-1]]
    pq = sum(length.values()) - s - l
    crank = linkage.input_link(0)
    if math.isclose(s + l, pq, rel_tol=1e-12, abs_tol=0):
        return "change-point (s + l = p + q)"
    if s + l > pq:
        return "triple-rocker (non-Grashof)"
    shortest = order[0]
    role = ("frame" if shortest == frame else "input" if shortest == crank
            else "coupler" if not any(frame in chain.joints[k] for k in linkage.joints_of(shortest)) else "output")
    return f"{_GRASHOF[role]} (Grashof)"


class Branch(NamedTuple):
    """Where the input of a 1-DOF linkage ends on the branch of its pose, and how the branch is moved.

    Attributes
    ----------
    low, high : float
        The input's offsets from the pose where the branch ends (rad or length; −inf and +inf for a
        crank or an endless slide).
    closed_form : bool
        Every group moves by a dyad's closed form (False: Newton's method with continuation, which
        reports no transmission angles).
    """

    low: float
    high: float
    closed_form: bool


def pose_branch(linkage: Linkage) -> Branch:
    """The ends of the branch of a 1-DOF linkage's pose, as offsets of its input (the search of
    :func:`motion_range` without its toggles and Grashof class: a cheap question for ranking poses).

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> pose_branch(lk)
    Branch(low=-inf, high=inf, closed_form=True)
    """
    solver = _solver(linkage)
    low, high, _, _ = solver.branch
    return Branch(low, high, solver.plan is not None)


def motion_range(linkage: Linkage) -> MotionRange:
    """Whether the input of a 1-DOF linkage turns fully, its limits, dead and toggle positions.

    Returns
    -------
    MotionRange
        Limits are the true ends of the pose's branch (dead positions located to 1e-9); toggles
        are where an output link (jointed to the frame) stops and turns back, found as roots of
        its velocity.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> r = motion_range(lk)
    >>> r.full_rotation, r.grashof, len(r.toggles)
    (True, 'crank-rocker (Grashof)', 2)
    """
    from ..errors import WrongInputs

    if linkage.dof != 1:
        raise WrongInputs(f"this linkage has {linkage.dof} inputs: its range of motion is a region, sweep a grid")
    solver = _solver(linkage)
    lo, hi, why_lo, why_hi = solver.branch
    phi0 = float(linkage.pose_inputs[0])
    revolute = solver.revolute[0]
    full = revolute and math.isinf(lo) and math.isinf(hi)
    dead = tuple((phi0 + x, why) for x, why in ((lo, why_lo), (hi, why_hi)) if math.isfinite(x))
    a, b = (0.0, 2 * math.pi) if full else (max(lo, -10 * linkage.scale), min(hi, 10 * linkage.scale))
    return MotionRange(full, None if full else (phi0 + lo, phi0 + hi), dead, _toggles(linkage, a, b), _grashof(linkage))


def _toggles(linkage: Linkage, a: float, b: float) -> tuple:
    """(input, link) where an output link jointed to the frame stops: roots of its rate in (a, b)."""
    solver = _solver(linkage)
    frame = linkage.frame
    outputs = []
    for k, j in enumerate(linkage.chain.joints):
        if frame in j and k not in linkage.inputs and linkage.kind(k) != MESH:
            for x in j:
                if x != frame and x != linkage.input_link(0):
                    outputs.append((x, linkage.kind(k), np.array(linkage.slides.get(k, (1.0, 0.0)))))
    if not outputs:
        return ()
    system = solver.system

    def rates(xs):
        theta, t, _ = solver.poses_along(np.atleast_1d(xs))
        qd, _ = system.rates(theta, t)
        dtheta, dt = system.poses(qd[:, 0])
        return np.stack([dtheta[:, x] if kind == REVOLUTE else dt[:, x] @ u for x, kind, u in outputs], axis=1)

    margin = 1e-7 * (b - a)
    xs = np.linspace(a + margin, b - margin, 721)
    r = rates(xs)
    found = []
    phi0 = float(linkage.pose_inputs[0])
    for m, (link, _, _) in enumerate(outputs):
        col = np.where(np.isfinite(r[:, m]), r[:, m], 0.0)
        quiet = 1e-9 * np.abs(col).max(initial=0.0)  # a link standing still: its rate's rounding is no toggle
        moving = np.abs(col) > quiet
        for k in np.flatnonzero((np.sign(col[:-1]) * np.sign(col[1:]) < 0) & moving[:-1] & moving[1:]):
            try:
                root = brentq(lambda x: float(rates(x)[0, m]), xs[k], xs[k + 1], xtol=1e-12, rtol=1e-15)
            except ValueError:  # the rate is not finite between the samples (a singular place): the sample
                root = xs[k] if abs(r[k, m]) <= abs(r[k + 1, m]) else xs[k + 1]
            found.append((phi0 + root, link))
    return tuple(sorted(found))


def assemble(linkage: Linkage, value: float) -> Linkage:
    """The same linkage posed at input ``value`` on the branch of its pose (1-DOF).

    Raises
    ------
    CannotAssemble
        The branch does not reach ``value`` (the sentence gives its range and the group that locks).
    BadSweep
        ``value`` is not finite, or too far from zero for a float to hold an input to 1e-9.

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> round(float(assemble(lk, np.pi / 2).pose_inputs[0]), 12)
    1.570796326795
    """
    value = _check_value(value, "the input")
    _check_resolved(linkage, (("the input", value),), 1e-3)
    motion = sweep(linkage, steps=2, start=value, stop=value + (1e-3 if value < 1e300 else -1e-3))
    p = motion.joints[0]
    tracers = {name: (link, tuple(motion.tracers[name][0])) for name, (link, _) in linkage.tracers.items()}
    theta = motion.angles[0]
    slides = {}
    for k, (ux, uy) in linkage.slides.items():
        c, s = math.cos(theta[linkage.chain.joints[k][0]]), math.sin(theta[linkage.chain.joints[k][0]])
        slides[k] = (c * ux - s * uy, s * ux + c * uy)
    return Linkage(linkage.mechanism, linkage.inputs, p, slides, linkage.meshes, tracers)
