"""The search: differential evolution over the dimensions, restarted while the budget lasts, each
run's best candidates polished by bounded least squares; the result re-checked by the motion layer."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import differential_evolution, least_squares, minimize

from mechbase import Row

from ..errors import DimensionError, MotionError
from ..motion import Linkage, motion_range, sweep
from ..structure import single_threaded
from ..structure.chain import Mechanism
from ._problem import (CURVE_SAMPLES, HELD_MARGIN, INFEASIBLE, MARGIN, MET, Constraints, Problem, input_joint_of,
                       link_ratio, longest_link, point_carried)
from ._target import FunctionTarget, MotionTarget, PathTarget

__all__ = ["DimensionalResult", "synthesize", "equations_and_unknowns"]

#: weight of a constraint's squared violation against the mean squared relative error
PENALTY = 1e2
#: a search stops early once the relative RMS error is below this (the target is met exactly)
EXACT = 1e-11
#: shares of the curve (from the pose on: of its length, and of the input's span) an untimed path's
#: points are first spread over
SPANS = (0.5, 1.0)
#: rounds of fitting the placement and moving the points to their places on the carried curve
ALIGN_ROUNDS = 4
#: rounds of moving an untimed path's inputs onto the mechanism's own motion (Newton) and fitting its
#: placement again, before the global stage's cost is taken
SETTLE_STEPS = 2
#: the given starts' share of the budget before differential evolution, polished one by one (least cost first)
#: while it lasts, each for at most a SAMPLED_STARTS-th of it
SAMPLED_STARTS, SAMPLED_SHARE = 5, 0.5
#: the share of the budget the given starts' ranking by the global stage's cost may take, and the
#: share the best of their polishes may then go on with
RANK_SHARE, GO_ON_SHARE = 0.1, 0.2
#: runs of the constrained polish of a link-length order (:meth:`_Search.constrained`), 100 steps each; and
#: polishes of the final shifted penalty of a length or ratio bound (:meth:`_Search.aim_bounds`)
STIFF_RUNS, AIM_ROUNDS = 5, 4
#: least squares of one polish, each holding the length and ratio bounds reached so far as equalities
#: (:meth:`_Search.polish`): the first, then one after a bound is reached, and one after a held bound is let go
HOLD_ROUNDS = 3
#: the least dyad discriminant over the turn the final polish holds a crank to (normalised; :meth:`_Search.constrained`):
#: held to 1e-10 the half circle's crank touched a dead position the motion layer counted as reached (seed 3)
TURN_MARGIN = 1e-8
#: the steps of each constrained polish of a crank on the verge of stopping (:meth:`_Search.stiffen`: a run of 100
#: took the eighteen points' 12 CPU s beyond a budget of 30)
VERGE_STEPS = 20
#: the share of the budget the shifted penalty's polishes (and a crank's on the verge) may take after it (seed 0 of the ten points: 47 CPU s
#: after a budget of 60 without a limit)
AIM_SHARE = 0.1
#: a polish's least squares under a link-length order stop once their best cost falls less than this share over
#: the last CRAWL_WINDOW evaluations per unknown (the constrained polish goes on from there): CE1 as stated, seed 4's
#: first polish took 14 CPU s of its 30, its least squares crawling 15 100 evaluations on the hinge of two binding
#: orders (2 379 with the stop, the polish 2.4 CPU s)
CRAWL, CRAWL_WINDOW = 1e-3, 20


class _OutOfTime(Exception):
    pass


class _Reached(Exception):
    """A polish's least squares reached a length or ratio bound it does not yet hold (:meth:`_Search.polish`)."""


class _Crawling(Exception):
    pass


class _Crawl:
    """The best cost of a least squares after each evaluation, raising :class:`_Crawling` once it falls less than
    :data:`CRAWL` (a share) over the last :data:`CRAWL_WINDOW` evaluations per unknown.

    >>> crawl = _Crawl(unknowns=1)
    >>> for cost in np.geomspace(1.0, 0.5, 25):   # halved over 25 evaluations: 2.8 % each 20
    ...     crawl.seen(cost)
    >>> try:
    ...     for _ in range(21):
    ...         crawl.seen(0.5)
    ... except _Crawling:
    ...     print("crawling")
    crawling
    """

    def __init__(self, unknowns: int):
        self.window, self.trail = CRAWL_WINDOW * unknowns, []

    def seen(self, best: float) -> None:
        self.trail.append(best)
        if len(self.trail) > self.window and best > (1 - CRAWL) * self.trail[-self.window - 1]:
            raise _Crawling


@dataclass
class DimensionalResult(Row):
    """A dimensioned mechanism found for a target, with its errors and the constraints it meets.

    Attributes
    ----------
    linkage : Linkage
        The mechanism in its pose at the first target point; its tracer point is named "P".
    target : PathTarget, FunctionTarget or MotionTarget
        The target it was dimensioned for.
    kind : str
        "path", "function" or "motion".
    inputs : ndarray (N,)
        The input's value at each target point (rad or length; on the pose's branch).
    traced : ndarray
        What the linkage does there: tracer points (N, 2), output angles or displacements (N,), or poses (N, 3)
        (the body's angle measured as the target's: the first pose's angle plus its turn).
    errors : ndarray (N,)
        Each target point's error in the target's units (distance; rad or length for a function; for a
        motion the position error — the angle errors are in ``angle_errors``).
    size : float
        The target's size (bounding-box diagonal; 1 for a function of angles, the displacements'
        range for a slider's): relative errors are over it.
    seconds : float
        CPU seconds of the search (this process).
    evaluations : int
        Candidate mechanisms evaluated.
    method : str
    constraints : dict name -> {"value", "limit", "met"}
        Each constraint as re-checked by the motion layer on the returned linkage.
    angle_errors : ndarray (N,) or None
        A motion's angle errors (rad).
    weights : ndarray (N,) or None
        The target's weights (None: every point counts once).  ``error_max``, ``error_rms`` and the
        relative errors are over the points each counted once; ``weighted_sum_squares`` is what the
        search minimised.
    on_reach : list of str
        The joints (and "the tracer point") the search left on the edge of its reach (``reach``): there
        the box, not the target, stopped it, and a larger reach may do better.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
    >>> r = DimensionalResult(lk, None, "path", np.zeros(2), np.zeros((2, 2)), np.array([0.1, 0.2]), 1.0, 0.0, 1, "m",
    ...                       weights=np.array([2.0, 1.0]))
    >>> round(r.weighted_sum_squares, 12), round(r.error_rms ** 2, 12)   # 2 × 0.1² + 0.2², (0.1² + 0.2²) / 2
    (0.06, 0.025)
    """

    linkage: Linkage
    target: object
    kind: str
    inputs: np.ndarray
    traced: np.ndarray
    errors: np.ndarray
    size: float
    seconds: float
    evaluations: int
    method: str
    constraints: dict = field(default_factory=dict)
    angle_errors: np.ndarray | None = None
    weights: np.ndarray | None = None
    on_reach: list = field(default_factory=list)

    @property
    def error_max(self) -> float:
        """The largest point's error (target units; rad or length for a function)."""
        return float(self.errors.max())

    @property
    def error_rms(self) -> float:
        """The root mean square of the points' errors, each point counted once (its weight ignored)."""
        return float(np.sqrt(np.mean(self.errors ** 2)))

    @property
    def weighted_sum_squares(self) -> float | None:
        """Σ weight × error² over the points (target units²; rad² for a function; a motion's position
        errors): the sum of squared errors the search minimised, a point of weight 2 counted twice, as
        a source that lists it twice sums it.  None for a target without weights."""
        return None if self.weights is None else float(self.weights @ self.errors ** 2)

    @property
    def relative_max(self) -> float:
        return self.error_max / self.size

    @property
    def relative_rms(self) -> float:
        return self.error_rms / self.size

    @property
    def met(self) -> bool:
        """Every constraint met (the branch reaching every target point included)."""
        return all(c["met"] for c in self.constraints.values())

    def failed(self) -> list[str]:
        """The constraints not met, each as a short phrase."""
        return [f"{name} ({_said(c)})" for name, c in self.constraints.items() if not c["met"]]

    #: the row (:meth:`to_dict`): first the flat summary of :meth:`row`, then the constraints as re-checked,
    #: the input, traced value and error at each target point, and the linkage (its file object)
    row_keys = ("kind", "chain=chain_text", "frame=linkage_frame", "points=point_count", "error_max", "error_rms",
                "relative_max", "relative_rms", "weighted_sum_squares?", "size", "angle_error_max_deg?", "met",
                "seconds=seconds_rounded", "evaluations", "method", "constraints", "inputs=inputs_list",
                "traced=traced_list", "errors=errors_list", "weights=weights_list?", "linkage")
    _SUMMARY = 15  # row_keys[:15] are the flat row

    @property
    def chain_text(self) -> str:
        return self.linkage.chain.compact()

    @property
    def linkage_frame(self) -> int:
        return self.linkage.frame

    @property
    def point_count(self) -> int:
        return len(self.errors)

    @property
    def angle_error_max_deg(self) -> float | None:
        return None if self.angle_errors is None else math.degrees(float(self.angle_errors.max()))

    @property
    def seconds_rounded(self) -> float:
        return round(self.seconds, 3)

    @property
    def inputs_list(self) -> list:
        return self.inputs.tolist()

    @property
    def traced_list(self) -> list:
        return self.traced.tolist()

    @property
    def errors_list(self) -> list:
        return self.errors.tolist()

    @property
    def weights_list(self) -> list | None:
        return None if self.weights is None else self.weights.tolist()

    def row(self) -> dict:
        """One flat JSON-able row: errors, time, work, whether the constraints are met (the first keys of
        :meth:`to_dict`)."""
        summary = {entry.rstrip("?").partition("=")[0] for entry in self.row_keys[:self._SUMMARY]}
        return {key: value for key, value in self.to_dict().items() if key in summary}


def _said(c: dict) -> str:
    value, limit = c["value"], c["limit"]
    return f"{value} against {limit}" if limit is not None else f"{value}"


class _Watch:
    """The budget (CPU seconds of this process) and the best candidate seen by any evaluation."""

    def __init__(self, budget: float, progress, wall: bool = False):
        self.clock = time.monotonic if wall else time.process_time
        self.start = self.clock()
        self.budget = budget
        self.progress = progress
        self.best = (math.inf, None)
        self.count = 0
        self.last = 0.0

    def used(self) -> float:
        return self.clock() - self.start

    def over(self) -> bool:
        return self.used() >= self.budget

    def seen(self, cost: float, x) -> None:
        self.count += 1
        if cost < self.best[0]:
            self.best = (cost, np.array(x, dtype=float))
        if self.progress is not None and self.count % 64 == 0:
            used = self.used()
            if used - self.last > 0.2:
                self.last = used
                self.progress(min(used, self.budget), self.best[0])


class _Evaluate:
    """A candidate's residuals and cost (picklable: the search's workers call it)."""

    def __init__(self, problem: Problem):
        self.problem = problem

    # ---- timed targets: the unknowns are the dimensions only
    def timed(self, x):
        """(residuals, violations, unknowns) of the unknowns x, or the share of samples where the dyads
        do not close (a float), or None where the pose contradicts the chain.  For a timed path x may
        leave out the tracer point: the mechanism is then placed by the best similarity (no larger than a
        length bound allows, which is then measured where it stands) and its tracer point is the best for
        the rest (:meth:`Problem.best_placement`), and the unknowns returned are the placed mechanism's, its
        tracer point included."""
        p = self.problem
        short = len(x) < p.dims
        try:
            lk = p.linkage(np.concatenate((x, [0.0, 0.0])) if short else x)
            offsets = p.offsets_of_timing(lk)
            samples = p.samples(offsets)
            every = np.concatenate((offsets, samples))
            n = len(offsets)
            if short:
                theta, t, g, mu = p.poses(lk, every)
                g = p.dips(lk, every, g)
                if g is not None and (g < 0).any():
                    return float((g < 0).mean())
                link, c = p.tracer_link, p.constraints
                longest = longest_link(lk) if c.max_length is not None else None
                tracer, lam, shift, values = p.best_placement(theta[:n, link], t[:n, link], longest)
                x = self.moved(np.concatenate((x, [0.0, 0.0])), lam, shift, tracer)
                if c.pivots is not None or c.rocker is not None or c.max_length is not None:
                    lk = p.linkage(x)  # the designer's region, limits and length bound are measured where it stands
            else:
                values, g, mu = p.move(lk, every)
                g = p.dips(lk, every, g)
        except MotionError:
            return None
        if g is not None and (g < 0).any():
            return float((g < 0).mean())
        if not np.isfinite(values[:n]).all():
            return 1.0
        return (p.weighed(p.residuals(values[:n])).ravel(), p.violations(lk, offsets, g, None if mu is None else mu[n:]),
                x)

    def complete(self, x) -> np.ndarray:
        """The full unknowns of searched ones: a path's mechanism placed best, with its best tracer
        point."""
        p = self.problem
        if len(x) == p.dims:
            return np.asarray(x, dtype=float)
        out = self.timed(x) if p.timed else self.untimed(x)
        if out is None or isinstance(out, float):
            return np.concatenate((x, [0.0, 0.0]))
        return np.clip(out[2] if p.timed else out[3], p.lower, p.upper)

    # ---- untimed targets: dimensions, then the inputs (a direction and increments)
    def curve(self, x):
        """The traced curve each way from the pose: (linkage, {direction: (values, xs, μ, link)}) on
        the branch, ``link`` the tracer link's rotations θ and translations t at the samples (for a
        path: its tracer point is then fitted, :meth:`aligned`)."""
        p = self.problem
        lk = p.linkage(x)
        span = p.input_span
        xs = np.linspace(-span, span, 2 * CURVE_SAMPLES + 1)
        if p.projected:
            theta, t, g, mu = p.poses(lk, xs)
            theta, t = theta[:, p.tracer_link], t[:, p.tracer_link]
            values = point_carried(theta, t, np.array(lk.tracers["P"][1]))
        else:
            values, g, mu = p.move(lk, xs)
        g = p.dips(lk, xs, g)
        ok = np.ones(len(xs), bool) if g is None else g >= 0
        ok &= np.isfinite(np.asarray(values).reshape(len(xs), -1)).all(axis=1)
        m = CURVE_SAMPLES
        if not ok[m]:
            return lk, None
        fwd = m + (np.flatnonzero(~ok[m:])[0] if (~ok[m:]).any() else len(xs) - m)
        back = m - (np.flatnonzero(~ok[:m + 1][::-1])[0] if (~ok[:m + 1]).any() else m + 1)
        forward, backward = np.arange(m, fwd), np.arange(m, back, -1)
        ways = {d: (values[k], xs[k], None if mu is None else mu[k], (theta[k], t[k]) if p.projected else None)
                for d, k in ((1, forward), (-1, backward))}
        return lk, ways

    def project(self, values, rows, weights=None):
        """The target rows' places on the sampled curve (segments between samples), in order:
        each row's place is at or after the one before (dynamic programming over the segments, the
        sum of the rows' squared distances, each times its weight where ``weights`` are given, least);
        (distance² per row, place as a float sample index)."""
        p = self.problem
        if isinstance(p.target, MotionTarget):
            angle = np.unwrap(values[:, 2])
            curve = np.column_stack((values[:, :2] / p.scale, angle))
            want = np.column_stack((rows[:, :2] / p.scale, rows[:, 2] - p.target.poses[0, 2]))
        else:
            curve, want = values / p.scale, rows / p.scale
        if len(curve) < 2:
            d = ((want[:, None, :] - curve[None, :1, :]) ** 2).sum(axis=2)
            return d[:, 0], np.zeros(len(want))
        a, b = curve[:-1], curve[1:]
        ab = b - a
        w = want[:, None, :] - a[None, :, :]
        if isinstance(p.target, MotionTarget):  # the angle's difference modulo a turn
            w[:, :, 2] = np.remainder(w[:, :, 2] + math.pi, 2 * math.pi) - math.pi
        ab2 = (ab ** 2).sum(axis=1)
        f = np.clip(np.einsum("rsk,sk->rs", w, ab) / np.where(ab2 > 0, ab2, 1.0), 0.0, 1.0)
        w -= f[:, :, None] * ab[None]
        d = np.einsum("rsk,rsk->rs", w, w)
        weighed = d if weights is None else weights[:, None] * d
        total = np.empty_like(d)
        total[0] = weighed[0]
        for i in range(1, len(d)):
            total[i] = weighed[i] + np.minimum.accumulate(total[i - 1])
        # each row's first least total up to each segment: where a new least begins, carried on
        least = np.minimum.accumulate(total, axis=1)
        begins = np.ones(total.shape, bool)
        begins[:, 1:] = total[:, 1:] < least[:, :-1]
        first = np.maximum.accumulate(np.where(begins, np.arange(total.shape[1]), 0), axis=1)
        k = np.empty(len(d), dtype=int)
        k[-1] = first[-1, -1]
        for i in range(len(d) - 2, -1, -1):
            k[i] = first[i, k[i + 1]]
        rows_ = np.arange(len(d))
        return d[rows_, k], np.maximum.accumulate(k + f[rows_, k])

    def untimed(self, x):
        """The global stage's cost of the dimensions alone: each later target point's distance to the
        curve, in order, the better direction; returns (cost, direction, input offsets, unknowns).

        For a path the curve is first carried onto the target by the best similarity (turn, scale,
        shift: the whole mechanism moved with it traces the moved curve) with the best tracer point
        on its link, so the search explores the mechanism's shape only; the unknowns returned are the
        moved mechanism's with that tracer point.  x may leave out the tracer point (the searched
        unknowns): its first guess is then the middle of its link's joints.  A motion's poses are
        matched where the mechanism stands."""
        p = self.problem
        try:
            if len(x) < p.dims:
                lk = p.linkage(np.concatenate((x, [0.0, 0.0])))
                joints = [k for k, j in enumerate(p.chain.joints) if p.tracer_link in j]
                x = np.concatenate((x, (lk.points[joints].mean(axis=0) - p.centre) / p.scale))
            lk, ways = self.curve(x)
        except MotionError:
            return None
        if ways is None:
            return 1.0
        motion = isinstance(p.target, MotionTarget)
        rows = p.target.poses if motion else p.target.points
        best = None
        for direction, (values, xs, mu, link) in ways.items():
            if len(values) < 2 or (p.constraints.crank and p.revolute_input and len(values) <= CURVE_SAMPLES):
                continue
            if motion:
                first = p.residuals(values[:1], rows[:1]).ravel()
                weights = np.ones(len(rows)) if p.weights is None else p.weights
                d2, where = self.project(values, rows[1:], weights[1:])
                cost = (weights[0] * float(first @ first) + float((weights[1:] * d2).sum())) / len(rows)
                moved, placed = x, lk
                offsets = np.interp(where, np.arange(len(xs)), xs)
            else:
                fit = self.aligned(values, rows, link)
                if fit is None:
                    continue
                _, where, lam, shift, tracer = fit
                found = self.settled(lk, np.interp(where, np.arange(len(xs)), xs), (tracer - shift, lam, shift),
                                     direction, float(xs[1] - xs[0]))
                if found is None:
                    continue
                cost, offsets, (q, lam, shift) = found
                moved = self.moved(x, lam, shift, q + shift)
                try:
                    placed = p.linkage(moved)
                except MotionError:
                    continue
                outside = np.maximum(moved - p.upper, 0.0) + np.maximum(p.lower - moved, 0.0)
                cost += PENALTY * float(outside @ outside)  # the placed mechanism must stay in the search box
            reached = int(math.ceil(where.max())) + 1 if len(where) else 1
            viol = p.violations(placed, offsets, None, None if mu is None else mu[:reached])
            cost += PENALTY * float(viol @ viol)
            if best is None or cost < best[0]:
                best = (cost, direction, offsets, moved)
        return best if best is not None else 1.0

    def settled(self, linkage: Linkage, offsets: np.ndarray, coefficients, direction: int, step: float):
        """A path's placement and inputs where the mechanism itself passes the target, from those on
        its sampled curve: up to :data:`SETTLE_STEPS` rounds of a Newton step of each later point's
        input offset along the motion (at most ``step``, the curve's sample step) and the placement
        fitted again (:meth:`Problem.place`), while the error falls.  ``linkage`` unplaced, ``coefficients``
        the placement (q, λ, t) as :meth:`aligned` fits it; returns (mean squared distance, offsets,
        (q, λ, t)), or None where the motion does not reach the offsets.

        The places on the sampled curve lie on its chords, and a chord is straight: points on a line
        lie exactly on one chord of almost any curve, within one sample step of input, so the chords'
        distance alone ranks a sliver of any curve as exact (six points on a line were met within 13°
        of crank turn where the exact four-bar turns 209°).  The error ranked is the mechanism's own
        at its own inputs."""
        p = self.problem
        w = (p.target.points[:, 0] + 1j * p.target.points[:, 1]) / p.scale
        n, h = len(offsets), -direction * _STEP  # (the slope's step towards the pose: the motion reaches there)

        def columns(at):  # the columns the carried tracer point is linear in (as aligned's), and where it is reached
            theta, t, g, _ = p.poses(linkage, np.concatenate(([0.0], at, at + h)))
            theta, t = theta[:, p.tracer_link], t[:, p.tracer_link]
            ok = np.isfinite(theta) & np.isfinite(t).all(axis=1) & (True if g is None else g >= 0)
            basis = np.column_stack((np.exp(1j * theta), (t[:, 0] + 1j * t[:, 1]) / p.scale, np.ones(len(theta))))
            return basis[:n + 1], (basis[n + 1:] - basis[1:n + 1]) / h, ok[1:n + 1] & ok[n + 1:]

        on, slope, ok = columns(offsets)
        if not ok.all():
            return None
        c = np.array(coefficients)
        cost = p.mean(np.abs(on @ c - w) ** 2)
        for _ in range(SETTLE_STEPS):
            moved = offsets + np.clip(_places_step(on, slope @ c, w), -step, step)
            on_, slope_, ok_ = columns(moved)
            moved = np.where(ok_, moved, offsets)  # (a point whose step leaves the branch stays)
            on_[1:][~ok_], slope_[~ok_] = on[1:][~ok_], slope[~ok_]
            c_ = np.array(p.place(on_[:, 0], on_[:, 1], w))
            again = p.mean(np.abs(on_ @ c_ - w) ** 2)
            if not again < cost:
                break
            offsets, on, slope, c, cost = moved, on_, slope_, c_, again
        return cost, offsets, tuple(c)

    def aligned(self, values, rows, link):
        """The curve (samples from the pose on, in the target's units) carried onto the target rows by
        the best similarity z ↦ λz + t of the whole mechanism (complex, non-dimensional) with the best
        tracer point q on its link, ``link`` the link's rotations θ and translations m at the samples:
        the rows w ≈ e^{iθ}q + λm + t (:func:`placement`).  Returns (mean squared distance, each later
        row's place on the curve as a float sample index, λ, t, the placed tracer point q + t), or
        None for a curve that is a point.

        The rows start at their nearest places in order on the curve where it stands (so the fit is
        never worse than the curve unmoved), or at their share of the target polygon's length along
        a span of the curve (half or all of its length, or of the input's span: :data:`SPANS`); for
        each, the placement is fitted and the rows moved to their nearest places in order on the
        curve as carried (:meth:`project`).  The best start is then improved, up to
        :data:`ALIGN_ROUNDS` times while the fit improves, by the better of the same move and a
        Gauss-Newton step of the places and the placement together (the rows slide along the curve's
        chords as the placement changes: closest points alone crawl, a step converges)."""
        p = self.problem
        z = (values[:, 0] + 1j * values[:, 1]) / p.scale
        w = (rows[:, 0] + 1j * rows[:, 1]) / p.scale
        later_weights = None if p.weights is None else p.weights[1:]
        index = np.arange(len(z), dtype=float)  # (a place on the curve: a float sample index)
        arc = np.concatenate(([0.0], np.cumsum(np.abs(np.diff(z)))))
        share = np.concatenate(([0.0], np.cumsum(np.abs(np.diff(w)))))
        if arc[-1] <= 1e-12:
            return None
        share /= share[-1]
        # the columns the carried curve is linear in: the link's turn (times q), its translation (λ), 1 (t)
        basis = np.column_stack((np.exp(1j * link[0]), (link[1][:, 0] + 1j * link[1][:, 1]) / p.scale, np.ones(len(z))))

        def at(places):  # the columns at the places (on the chords between samples), and each place's chord
            k = np.minimum(places.astype(int), len(z) - 2)
            return basis[k] + (places - k)[:, None] * (basis[k + 1] - basis[k]), k

        def fitted(places):  # (mean squared distance, places, λ, t, tracer, coefficients) for these places
            on, _ = at(places)
            c = np.array(p.place(on[:, 0], on[:, 1], w))
            return p.mean(np.abs(on @ c - w) ** 2), places, c[1], c[2], c[0] + c[2], c

        def replaced(fit):  # the rows moved to their places in order on the curve carried by the fit
            carried = basis @ fit[5]
            _, later = self.project(np.column_stack((carried.real, carried.imag)) * p.scale, rows[1:], later_weights)
            return fitted(np.concatenate(([0.0], later)))

        def stepped(fit):  # the rows' places and the coefficients moved together by a Gauss-Newton step
            places, c = fit[1], fit[5]
            on, k = at(places)
            moved = np.clip(places[1:] + _places_step(on, ((basis[k + 1] - basis[k]) @ c)[1:], w), 0.0, len(z) - 1.0)
            return fitted(np.concatenate(([0.0], np.maximum.accumulate(moved))))

        _, later = self.project(values, rows[1:], later_weights)
        steps = np.arange(len(w)) / len(w)
        starts = ([np.concatenate(([0.0], later))] + [np.interp(span * arc[-1] * share, arc, index) for span in SPANS]
                  + [span * index[-1] * share for span in SPANS] + [span * index[-1] * steps for span in SPANS])
        best = min((replaced(fitted(places)) for places in starts), key=lambda f: f[0])
        for _ in range(ALIGN_ROUNDS):
            again = min(replaced(best), stepped(best), key=lambda f: f[0])
            if again[0] >= best[0]:
                break
            best, crawling = again, again[0] > best[0] * (1 - 1e-3)
            if crawling:  # less than 0.1 % better: the fit has settled
                break
        return best[0], best[1][1:], best[2], best[3], best[4]

    def moved(self, x, lam: complex, shift: complex, tracer: complex) -> np.ndarray:
        """The unknowns of the mechanism ``x`` carried by the similarity w = λz + t (z, w positions over
        the target's size, as :meth:`aligned` gives it), its tracer point put at ``tracer`` (a position
        as w)."""
        p = self.problem
        out = np.array(x, dtype=float)
        origin = (p.centre[0] + 1j * p.centre[1]) / p.scale
        turn = math.atan2(lam.imag, lam.real)
        i = 0
        for kind, _ in p.layout:
            if kind == "slide":
                out[i] = (out[i] + turn) % math.pi
                i += 1
                continue
            if kind == "along":  # a distance along the frame's fixed direction (λ is then real)
                out[i] *= abs(lam)
                i += 1
                continue
            q = lam * (origin + out[i] + 1j * out[i + 1]) + shift - origin
            out[i], out[i + 1] = q.real, q.imag
            i += 2
        out[-2:] = [tracer.real - origin.real, tracer.imag - origin.imag]  # (the tracer's two are the layout's last)
        return out

    def __call__(self, x) -> float:
        """The global stage's cost of the dimensions ``x``."""
        p = self.problem
        if p.timed:
            out = self.timed(x)
            if out is None or isinstance(out, float):
                return INFEASIBLE * (2.0 if out is None else 1.0 + out)
            r, viol, placed = out
            outside = np.maximum(placed - p.upper, 0.0) + np.maximum(p.lower - placed, 0.0)
            return float(r @ r) / p.points + PENALTY * (float(viol @ viol) + float(outside @ outside))
        out = self.untimed(x)
        if out is None or isinstance(out, float):
            return INFEASIBLE * (2.0 if out is None else 1.0 + out)
        return out[0]

    # ---- the polish: a residual vector of fixed length
    def vector(self, z, direction: int):
        """Residuals for least squares: target rows, then constraint violations, then (untimed) the
        turn beyond one full turn; a candidate off its branch gets a large constant vector."""
        p = self.problem
        size = p.points * p.rows_per_point + self.n_violations + (0 if p.timed else 1)
        if p.timed:
            out = self.timed(z)
            if out is None or isinstance(out, float):
                return np.full(size, math.sqrt(INFEASIBLE / size) * (2.0 if out is None else 1.0 + out))
            r, viol, _ = out
            return np.concatenate((r / math.sqrt(p.points), math.sqrt(PENALTY) * viol))
        x, steps = z[:p.dims], z[p.dims:]
        offsets = direction * np.concatenate(([0.0], np.cumsum(steps)))
        try:
            lk = p.linkage(x)
            every = np.concatenate((offsets, p.samples(offsets)))
            values, g, mu = p.move(lk, every)
            g = p.dips(lk, every, g)
        except MotionError:
            return np.full(size, 2.0 * math.sqrt(INFEASIBLE / size))
        n = len(offsets)
        if g is not None and (g < 0).any():
            return np.full(size, math.sqrt(INFEASIBLE / size) * (1.0 + float((g < 0).mean())))
        if not np.isfinite(values[:n]).all():
            return np.full(size, 2.0 * math.sqrt(INFEASIBLE / size))
        r = p.weighed(p.residuals(values[:n])).ravel() / math.sqrt(p.points)
        viol = p.violations(lk, offsets, g, None if mu is None else mu[n:])
        beyond = max(0.0, abs(offsets[-1]) - p.input_span) if p.revolute_input else 0.0
        return np.concatenate((r, math.sqrt(PENALTY) * viol, [math.sqrt(PENALTY) * beyond]))

    @property
    def n_violations(self) -> int:
        c = self.problem.constraints
        return sum((c.min_transmission > 0, c.max_ratio is not None, c.max_length is not None, c.pivots is not None,
                    c.rocker is not None, self.problem.order_pairs))


def _problem(mechanism, target, tracer_link, constraints) -> tuple[Problem, Linkage | None]:
    if isinstance(mechanism, Linkage):
        linkage = mechanism
        if linkage.dof != 1:
            raise DimensionError(f"dimensional synthesis drives one input, not W = {linkage.dof}")
        mech = linkage.mechanism
    elif isinstance(mechanism, Mechanism):
        linkage, mech = None, mechanism
    else:
        raise DimensionError(f"synthesize takes a Mechanism or a Linkage, not {type(mechanism).__name__}")
    if not isinstance(target, (PathTarget, FunctionTarget, MotionTarget)):
        raise DimensionError(f"the target must be a PathTarget, FunctionTarget or MotionTarget, not "
                             f"{type(target).__name__}")
    if not isinstance(constraints, Constraints):
        raise DimensionError("constraints must be a Constraints object")
    joint, driven = input_joint_of(mech, linkage)
    return Problem(mech, joint, target, tracer_link, constraints, driven), linkage


def equations_and_unknowns(mechanism, target, *, tracer_link: int | None = None,
                           constraints: Constraints = Constraints()) -> tuple[int, int]:
    """The equations the target gives and the unknowns of its synthesis (fewer equations: an underdetermined
    problem, which :func:`synthesize` refuses unless asked).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.dimension import FunctionTarget
    >>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)
    >>> equations_and_unknowns(four_bar, FunctionTarget(np.radians([40, 60, 80]), np.radians([70, 85, 105])))
    (3, 3)
    """
    problem, _ = _problem(mechanism, target, tracer_link, constraints)
    return problem.equations, problem.unknowns


def synthesize(mechanism, target, *, tracer_link: int | None = None, constraints: Constraints = Constraints(),
               budget: float = 60.0, seed: int = 0, workers: int = 1, scheduler: str | None = None,
               underdetermined: bool = False, progress=None, polish_only: bool = False,
               connect_timeout: float = 5.0, starts=None) -> DimensionalResult:
    """Dimension a mechanism of given topology so that it meets a target as closely as it can.

    Parameters
    ----------
    mechanism : Mechanism or Linkage
        The topology, frame and input (a Mechanism's ``input_link``, else the frame's first revolute
        joint); a Linkage also gives a first guess (its pose).
    target : PathTarget, FunctionTarget or MotionTarget
    tracer_link : int, optional
        The link carrying the tracer point (default: the coupler, see :class:`Problem`).
    constraints : Constraints
    budget : float
        CPU seconds of the search (this process's; with ``workers`` > 1 or a ``scheduler`` the
        parent's wall-clock seconds).  The search stops earlier once the target is met exactly
        (relative RMS 1e-11); one whose budget ends before any polish polishes the best candidate
        it saw for at most one budget more.
    seed : int
        Seeds the search: the same seed and budget give the same result on an idle machine (the
        budget cuts the last run where the clock says).
    workers : int
        Local processes evaluating each generation of the global stage (the project's one
        :class:`~synth.execution.executor.Executor`); 1 evaluates in this process.
    scheduler : str, optional
        A Dask scheduler's address (``tcp://HOST:PORT``): the generations are evaluated on its
        cluster instead (not with ``workers`` > 1).
    underdetermined : bool
        Allow fewer target equations than unknowns (infinitely many exact solutions: one is
        returned), as in Burmester's three poses.
    progress : callable (seconds, best cost), optional
    polish_only : bool
        No global search: only the least-squares polish from the given Linkage's pose (the atlas
        search starts each topology from its nearest indexed sample this way).
    connect_timeout : float
        Seconds to wait for the ``scheduler``.
    starts : callable, optional
        A source of start linkages polished before the global search (from no guess only), called as
        ``starts(mechanism, tracer_link, target, seed)`` within the budget: :func:`synth.atlas.sampled_starts`
        (the mechanism's own crank curves sampled at random, for points all round a closed curve)
        finds untimed paths far more reliably than the global search alone.

    Returns
    -------
    DimensionalResult

    Raises
    ------
    BadTarget
        Fewer target equations than unknowns (unless ``underdetermined``), a timing over a full turn.
    DimensionError
        A mechanism this synthesis does not dimension (gear meshes, W ≠ 1), contradictory constraints.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> from synth.dimension import FunctionTarget
    >>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0)
    >>> r = synthesize(four_bar, FunctionTarget(np.radians([40, 60, 80]), np.radians([70, 85, 105])), budget=10)
    >>> r.error_max < 1e-9, r.met
    (True, True)
    """
    from ..errors import BadTarget

    problem, start = _problem(mechanism, target, tracer_link, constraints)
    if polish_only and start is None:
        raise DimensionError("a polish alone starts from a dimensioned linkage, not from a Mechanism")
    if not (isinstance(budget, (int, float)) and math.isfinite(budget) and budget > 0):
        raise DimensionError(f"the budget must be a positive number of seconds, not {budget!r}")
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise DimensionError(f"workers must be a whole number ≥ 1, not {workers!r}")
    if scheduler is not None and workers != 1:
        raise DimensionError("workers and a scheduler contradict each other: the scheduler's workers evaluate the "
                             "candidates")
    if problem.equations < problem.unknowns and not underdetermined:
        per = problem.rows_per_point
        need = problem.unknowns - (0 if problem.timed else problem.points)  # (N points: per·N ≥ dims + N − 1)
        enough = math.ceil(need / (per - (0 if problem.timed else 1)))
        counted = problem.equations // per
        of_weight = f" ({counted} of weight above 0)" if counted < problem.points else ""
        raise BadTarget(f"{problem.points} target points{of_weight} give {problem.equations} equations for the "
                        f"{problem.unknowns} unknowns of this {target.kind} synthesis: give at least {enough} points "
                        f"(or allow an underdetermined problem: {_option('underdetermined')})")
    parallel = not polish_only and (workers > 1 or scheduler is not None)
    watch = _Watch(float(budget), progress, wall=parallel)
    search = _Search(_Evaluate(problem), problem, watch)
    rng = np.random.default_rng(seed)
    executor = client = None
    if parallel:
        from ..execution.executor import Executor

        if scheduler is not None:
            from ..execution.scheduler import connect

            client = connect(scheduler, connect_timeout)
        executor = Executor(workers, client)
    # BLAS on one thread: the polish's SVDs are of matrices of a few hundred entries, and OpenBLAS's
    # threads spinning between them cost 60 times the CPU of the SVD itself on the loaded 2-core machine
    with single_threaded():
        try:
            if polish_only:
                search.polish(problem.unknowns_of(start))
            elif start is None and (starts is not None or isinstance(target, MotionTarget)):
                search.from_samples(_with_dyads(starts) if isinstance(target, MotionTarget) else starts, seed)
            while not (polish_only or watch.over() or search.exact):
                search.runs += 1
                for x in search.evolve(rng, start if search.runs == 1 else None, executor):
                    if search.exact:  # (met by a polish during the run: its candidates need none)
                        break
                    search.polish(x)
        except _OutOfTime:
            pass
        finally:
            if executor is not None:
                executor.close()  # no worker outlives the search (Ctrl-C included)
            if client is not None:
                client.close()
        if search.best is None and watch.best[1] is not None and watch.best[0] < INFEASIBLE:
            # the budget ran out before any polish: polish the best seen, for one budget more at most (unbounded, a
            # six-bar's share of 0.09 CPU s in 'dimension --db … --budget 1' polished for 94 s)
            search.polish(watch.best[1], grace=True, until=watch.used() + watch.budget)
        if search.binding():
            search.stiffen()
    if search.best is None:
        region = "" if problem.constraints.pivots is None else \
            f", or a region of the fixed pivots ({_option('pivots', 'x0..x1,y0..y1')}) nearer the target"
        raise DimensionError("the search found no mechanism that reaches the target on one assembly branch "
                             f"within {budget:g} s: give a longer budget or a larger reach{region}")
    return _result(problem, search.evaluate, search.best, watch, search.runs, bool(search.sampled))


def _with_dyads(starts):
    """A motion's start linkages: a four-bar's from its dyads (:func:`~._dyads.dyad_starts`), then those of
    ``starts``."""
    from ._dyads import dyad_starts

    def source(mechanism, tracer_link, target, seed):
        return dyad_starts(mechanism, tracer_link, target, seed) + list(starts(mechanism, tracer_link, target, seed)
                                                                       if starts is not None else [])
    return source


def _option(name: str, value: str = "True") -> str:
    from ..errors import option

    return option(name, value)


class _Search:
    """Differential evolution runs and their polish, keeping the best polished candidate."""

    #: generations between polishes of a run's best; and without a 1 % improvement before a run ends
    POLISH_EVERY, STAGNANT = 20, 60

    def __init__(self, evaluate: _Evaluate, problem: Problem, watch: _Watch):
        self.evaluate, self.problem, self.watch = evaluate, problem, watch
        self.best = None  # (cost, unknowns, direction)
        self.runs = 0
        self.sampled = []  # searched unknowns of sampled crank curves, least cost first (from_samples)

    @property
    def exact(self) -> bool:
        return self.best is not None and self.best[0] <= EXACT ** 2

    def from_samples(self, source, seed: int) -> None:
        """Polish the start linkages of ``source`` (called as ``source(mechanism, tracer_link, target,
        seed)``, e.g. :func:`synth.atlas.sampled_starts`: the mechanism's own crank curves sampled at
        random, each posed on the target as its Fourier descriptor aligns it), the
        :data:`SAMPLED_STARTS` of least cost first — the global stage's cost, which places each where it
        fits best and matches the points in order: a few points describe a curve's shape too coarsely
        to rank samples by their descriptors alone; the ranking stops once it has taken
        :data:`RANK_SHARE` of the budget, those left being the farthest by the source's own measure.
        They are polished in that order, a polish begun while :data:`SAMPLED_SHARE` of the budget lasts, each for at
        most a :data:`SAMPLED_STARTS`-th of it (the last may end past the share) and stopped once its least squares
        crawl (``brief``), and the best of them goes on with :data:`GO_ON_SHARE` more; the rest seed the first
        population.  A polish that ends early (at its valley's floor, or crawling) leaves its time to the next
        starts: on [HCDJ]'s ten points the start that reaches W.Y. Lin's valley was the sixth (seed 4) behind one
        that crawls for all it is given (benchmarks/DIMENSION.md, *The ten points of [HCDJ]: more starts*), and the
        27th (seed 3) behind polishes that crawled 6 CPU s each far from the points, the share's end then cutting
        it short (*The half circle at the default budget*)."""
        problem, watch = self.problem, self.watch
        if problem.tracer_link is None or problem.driven is not None:
            return
        mechanism = Mechanism(problem.chain, problem.frame, problem.input_link)
        starts = [problem.unknowns_of(start) for start in source(mechanism, problem.tracer_link, problem.target, seed)
                  if start.inputs[0] == problem.input_joint and start.chain.certificate == problem.chain.certificate]
        costs, ranking = [], watch.used()
        for x in starts:  # (nearest first by the source's own measure: those left unranked are the farthest)
            if len(costs) >= SAMPLED_STARTS and watch.used() - ranking >= RANK_SHARE * watch.budget:
                break
            costs.append(self.evaluate(x[:problem.searched]))
            watch.seen(costs[-1], x[:problem.searched])
        order = np.argsort(costs, kind="stable")
        self.sampled = [starts[i][:problem.searched] for i in order if costs[i] < INFEASIBLE]
        part = SAMPLED_SHARE * watch.budget / SAMPLED_STARTS
        for i in order:
            left = SAMPLED_SHARE * watch.budget - watch.used()
            if self.exact or costs[i] >= INFEASIBLE or left <= 0:
                break
            self.polish(self.evaluate.complete(starts[i][:problem.searched]), until=watch.used() + part, brief=True)
        if self.best is not None and not self.exact:  # the best of them goes on, its polish cut by its share
            self.polish(self.best[1][:problem.dims], until=watch.used() + GO_ON_SHARE * watch.budget)

    def evolve(self, rng, start: Linkage | None, executor) -> list:
        """One run of differential evolution (polishing its best now and then); its best distinct
        candidates, best first.  With an executor each generation is evaluated on it."""
        problem, watch = self.problem, self.watch
        state = {"generation": 0, "fun": math.inf, "improved": 0, "polished": None}

        def cost(x):
            if watch.over():
                raise _OutOfTime
            value = self.evaluate(x)
            watch.seen(value, x)
            return value

        def stop(intermediate_result):
            fun, x = float(intermediate_result.fun), intermediate_result.x
            watch.seen(fun, x)
            state["generation"] += 1
            if fun < state["fun"] * (1 - 1e-2):  # a real improvement, not a crawl into a local minimum
                state["fun"], state["improved"] = fun, state["generation"]
            if (state["generation"] % self.POLISH_EVERY == 0 and fun < INFEASIBLE
                    and state["polished"] != state["improved"]):
                state["polished"] = state["improved"]
                self.polish(x)
            return (watch.over() or self.exact or fun <= EXACT ** 2
                    or state["generation"] - state["improved"] > self.STAGNANT)

        lower, upper = self.bounds()
        bounds = list(zip(lower, upper))
        x0 = self.canonical(problem.unknowns_of(start)[:problem.searched]) if start is not None else None
        popsize = max(15, 60 // problem.searched)
        init = "sobol"
        if start is None and self.runs == 1 and self.sampled:  # half the first population from the sampled curves
            size = popsize * problem.searched
            ours = np.array([self.canonical(x) for x in self.sampled[:size // 2]])
            init = np.vstack((ours, lower + rng.random((size - len(ours), problem.searched)) * (upper - lower)))
        kwargs = dict(seed=int(rng.integers(2 ** 31)), strategy="rand1bin", popsize=popsize,
                      maxiter=100_000, tol=1e-6, mutation=(0.5, 1.0), recombination=0.9, init=init, polish=False,
                      callback=stop, x0=x0)
        if executor is not None:
            def generation(fn, population):
                population = list(population)
                chunk = max(1, math.ceil(len(population) / (2 * executor.slots)))
                values = list(executor.map(fn, population, chunk=chunk))
                for x, value in zip(population, values):
                    watch.seen(value, x)  # (the count, the best and the progress bar, as inline)
                return values

            result = differential_evolution(self.evaluate, bounds, workers=generation, updating="deferred", **kwargs)
        else:
            try:
                result = differential_evolution(cost, bounds, **kwargs)
            except _OutOfTime:
                return []
        order = np.argsort(result.population_energies)
        picked = []
        for i in order:
            if result.population_energies[i] >= INFEASIBLE:
                break
            x = self.evaluate.complete(result.population[i])
            if all(np.abs(x - y).max() > 1e-3 for y in picked):
                picked.append(x)
            if len(picked) == 3:
                break
        return picked

    def pinned(self) -> tuple[int, int] | None:
        """Where, in the searched unknowns, the input's pivot and a second fixed pivot are (untimed path
        targets with a turning input on two pivots of the frame placed by the search), else None.  (Timed
        paths are searched unpinned: pinned, a crank-rocker's seven timed points with a transmission
        angle, a link ratio and a pivot region, tests/dimension/test_synthesize.py, ended 0.14° short of
        the transmission limit after 30 CPU s, where unpinned they are met in 9.)"""
        p = self.problem
        if not (p.projected and not p.timed and p.revolute_input) or p.fixed or p.along is not None or p.absolute:
            return None  # (a pivot at a given point, a frame of given direction: the placement is not free)
        at, i = {}, 0
        for kind, k in p.layout:
            if kind == "joint" and k in p.frame_joints:
                at[k] = i
            i += 1 if kind in ("slide", "along", "origin") else 2
        other = [k for k in p.frame_joints if k != p.input_joint and k in at]
        if p.input_joint not in at or not other:
            return None
        return at[p.input_joint], at[other[0]]

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Differential evolution's box: the searched unknowns', with a path's two pivots pinned
        (:meth:`canonical`)."""
        p = self.problem
        lower, upper = p.lower[:p.searched].copy(), p.upper[:p.searched].copy()
        pins = self.pinned()
        if pins is not None:
            a, b = pins
            lower[a:a + 2] = upper[a:a + 2] = 0.0
            lower[b:b + 2] = upper[b:b + 2] = (1.0, 0.0)
        return lower, upper

    def canonical(self, x) -> np.ndarray:
        """The searched unknowns x carried by the similarity that puts the input's pivot at the target's
        centre and the second pivot one target size to its right (:meth:`pinned`), within the box.

        A path's candidates are judged where the best similarity places them, so differential
        evolution need not search where the mechanism stands, how it is turned or its size: with two
        pivots pinned a four-bar's eight searched unknowns are its four of shape."""
        pins = self.pinned()
        if pins is None:
            return np.asarray(x, dtype=float)
        p, (a, b) = self.problem, pins
        origin = (p.centre[0] + 1j * p.centre[1]) / p.scale
        za, zb = complex(x[a], x[a + 1]), complex(x[b], x[b + 1])
        if za == zb:
            return np.asarray(x, dtype=float)
        lam = 1.0 / (zb - za)
        full = self.evaluate.moved(np.concatenate((x, [0.0, 0.0])), lam, origin - lam * (origin + za), 0j)
        lower, upper = self.bounds()
        return np.clip(full[:p.searched], lower, upper)

    def polish(self, x, grace: bool = False, until: float | None = None, direction: int | None = None,
               central: bool = False, brief: bool = False) -> tuple[float, np.ndarray] | None:
        """Bounded least squares from the dimensions ``x`` (untimed: with the inputs found on its
        curve, or, with a ``direction``, x a polished answer's unknowns and input steps); the result kept if it is
        the best yet, and returned as (cost, unknowns) (None where the polish found nothing on the branch).  With
        ``grace`` the budget is not watched; with ``until`` the polish also stops once that many seconds are used
        (with ``grace`` too); ``central`` differences for its Jacobian (twice the evaluations, exact to eps^(2/3)
        rather than eps^(1/2)) where forward ones stall in a flat valley.  A length or ratio bound the polish reaches
        (:meth:`binds`) is held as an equality from there on, the least squares started again along it (from a start
        on the bound, at once): the penalty's hinge (gap + aim)⁺ has a kink there that cuts every step short, and on
        [HCDJ]'s ten points the polish crawled along the bound at 8.6e-4 where, held, it reaches the published
        optimum, 4.0199e-4 (benchmarks/DIMENSION.md, *The ten points of [HCDJ] from no guess*); held only once the
        least squares ended, the crawl first took them to their evaluation limit (12 CPU s of a 16-s polish; *more
        starts*).  With a link-length order, or ``brief`` (a sampled start's polish, the next start waiting:
        :meth:`from_samples`), the least squares stop once they crawl (:class:`_Crawl`), and under an order an inexact
        answer is polished again with the orders as constraints (:meth:`constrained`; first, where the target has
        fewer equations than unknowns, slid into them along the exact answers, :meth:`slide`): the penalty's hinge
        stalls where an order binds."""
        problem, watch, evaluate = self.problem, self.watch, self.evaluate
        if problem.timed:
            z0, lower, upper, direction = evaluate.complete(x), problem.lower, problem.upper, 0
        elif direction is not None:
            lower = np.concatenate((problem.lower, np.zeros(len(x) - problem.dims)))
            upper = np.concatenate((problem.upper, np.full(len(x) - problem.dims, problem.input_span)))
            z0 = np.clip(x, lower, upper)
        else:
            found = evaluate.untimed(x)
            if found is None or isinstance(found, float):
                return None
            _, direction, offsets, x = found
            steps = np.maximum(np.diff(np.concatenate(([0.0], np.abs(offsets)))), 0.0)
            lower = np.concatenate((problem.lower, np.zeros(len(steps))))
            upper = np.concatenate((problem.upper, np.full(len(steps), problem.input_span)))
            z0 = np.clip(np.concatenate((x, steps)), lower, upper)
        best = [math.inf, z0]
        bounded = problem.length_bounds > problem.order_pairs  # (a length or ratio bound: watched as it is reached)
        crawl = _Crawl(len(z0))

        def fun(z):
            if (watch.over() and not grace) or (until is not None and watch.used() >= until):
                raise _OutOfTime
            r = evaluate.vector(z, direction)
            cost = float(r @ r)
            watch.seen(cost, z[:problem.dims])
            if cost < best[0]:
                best[0], best[1] = cost, np.array(z)
                if bounded and (self.binds(z) & ~problem.held & ~let_go).any():
                    raise _Reached  # (held from here: along the hinge the least squares crawl to their limit)
            if problem.order or brief:
                crawl.seen(best[0])
            return r

        jac = ("3-point" if central else "2-point") if problem.timed else (
            lambda z: self.untimed_jacobian(fun, z, upper, central))
        held = self.binds(z0)  # (a start on a length or ratio bound follows it at once)
        let_go = np.zeros_like(held)
        try:
            for _ in range(HOLD_ROUNDS):
                problem.held = held
                crawl.trail.clear()
                try:
                    least_squares(fun, best[1], jac=jac, bounds=(lower, upper), method="trf", x_scale="jac",
                                  xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=200 * len(z0))
                except (_Reached, _Crawling):  # (a bound reached is held below; a crawl under an order goes on
                    pass                        # in the constrained polish)
                # a bound reached is held from here on; a held one whose row ends below its aim pulls the answer
                # inwards (the fit would leave it) and is let go for good
                let_go |= held & (self.length_gaps(best[1]) + problem.aim < 0)
                wanted = self.binds(best[1]) & ~let_go
                if best[0] <= EXACT ** 2 or (wanted == held).all():
                    break
                held = wanted
        except _OutOfTime:
            pass
        finally:
            problem.held = np.zeros(problem.length_bounds, bool)
        if not (math.isfinite(best[0]) and best[0] < INFEASIBLE / 10):
            return None
        if problem.order and best[0] > EXACT ** 2 and problem.equations < problem.unknowns:
            found = self.slide(best[1], direction, watched=not grace)  # exact answers all round: one into the order
            if found is not None and found[0] < best[0]:
                best = list(found)
        if problem.order and best[0] > EXACT ** 2:  # a binding order stalls the penalty: polish on it
            found = self.constrained(best[1], direction, watched=not grace)
            if found is not None and found[0] < best[0]:
                best = list(found)
        if self.best is None or best[0] < self.best[0]:
            self.best = (best[0], best[1], direction)
        return best[0], best[1]

    def slide(self, z0, direction: int, watched: bool = False) -> tuple[float, np.ndarray] | None:
        """For a target with fewer equations than unknowns (its exact answers a family) an answer stalled by a
        link-length order: the least squares from z0 with the orders' rows dropped, and where they meet the target
        exactly, again with each order they leave held as an equality twice the search's margin inside (its row
        signed, :attr:`Problem.held`; an order left in a round joins those held, up to :data:`HOLD_ROUNDS`), so the
        answer moves along the exact ones into the orders; (cost, unknowns) by the search's own cost, or None where
        the target is not met without the orders or the least squares crawl (:class:`_Crawl`).  With ``watched``
        it stops with the budget.

        CE1 as its sources state it (15 unknowns for 12 equations), seed 5 of 30 CPU s: its polish stalled at
        1.65e-8 (mean squared relative error) with r4 = r1, where the constrained polish does not move; from there
        the least squares without the order meet the six points (3.9e-31) with r4 1.7 % longer than r1, and held
        the order brings them back inside it, exact (benchmarks/DIMENSION.md, *CE1 as stated within 30 CPU s*)."""
        problem, evaluate, watch = self.problem, self.evaluate, self.watch
        extra = len(z0) - problem.dims  # (untimed: the input steps)
        lower = np.concatenate((problem.lower, np.zeros(extra)))
        upper = np.concatenate((problem.upper, np.full(extra, problem.input_span)))
        orders = np.arange(problem.length_bounds) < problem.order_pairs

        def solved(z, held):  # (the best of the least squares from z with these orders held, its cost; none held:
            crawl, least = _Crawl(len(z)), [math.inf, z]  # the orders dropped)

            def fun(x):
                if watched and watch.over():
                    raise _OutOfTime
                r = evaluate.vector(x, direction)
                if float(r @ r) < least[0]:
                    least[:] = float(r @ r), np.array(x)
                if least[0] > EXACT ** 2:
                    crawl.seen(least[0])  # (the exact answers converge fast: a crawl is short of them)
                return r

            problem.held = held
            problem.aim = deeper if held.any() else _dropped(problem)
            try:
                least_squares(fun, z, jac=lambda x: self.jacobian(fun, x, upper), bounds=(lower, upper), method="trf",
                              x_scale="jac", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=200 * len(z))
            except _Crawling:
                pass
            return least[1], least[0]

        penalty = problem.aim
        deeper = np.where(orders, 2 * MARGIN, penalty)
        held = np.zeros(problem.length_bounds, bool)
        z = z0
        try:
            for _ in range(HOLD_ROUNDS + 1):
                z, cost = solved(z, held)
                if cost > EXACT ** 2:
                    return None
                left = orders & (self.length_gaps(z) > -MARGIN)  # (the search's penalty aims MARGIN inside)
                if not left.any():
                    break
                held = held | left
        except _OutOfTime:
            return None
        finally:
            problem.aim, problem.held = penalty, np.zeros(problem.length_bounds, bool)
        r = evaluate.vector(z, direction)
        return float(r @ r), z

    def length_gaps(self, z) -> np.ndarray:
        """The link-length constraints' gaps of the unknowns z (:meth:`Problem.length_gaps`; −∞ where z is no
        linkage)."""
        p = self.problem
        try:
            return p.length_gaps(p.linkage(z[:p.dims]))
        except MotionError:
            return np.full(p.length_bounds, -np.inf)

    def binds(self, z) -> np.ndarray:
        """Which link-length rows of the unknowns z are a length or ratio bound within twice :data:`MARGIN` of its
        limit (a polish then holds each as an equality, :attr:`Problem.held`; the orders are held by
        :meth:`constrained`)."""
        p = self.problem
        out = self.length_gaps(z) >= math.log1p(-2 * MARGIN)
        out[:p.order_pairs] = False
        return out

    def binding(self) -> bool:
        """Whether the best answer's constraints call for a final polish (:meth:`stiffen`): an order (always
        polished so), a length or ratio bound within twice the search's margin of its limit, or a crank on the
        verge of stopping (:meth:`on_the_verge`)."""
        if self.best is None:
            return False
        if self.on_the_verge(self.best[1]):
            return True
        if not self.problem.length_bounds:
            return False
        return bool(self.problem.order) or bool(self.binds(self.best[1]).any())

    def on_the_verge(self, z) -> bool:
        """Whether the unknowns z make a crank that turns with less than :data:`TURN_MARGIN` to spare (its least
        dyad discriminant over the turn): the eighteen points' best lies on Grashof's bound, where the coupler and
        rocker fold flat once a turn, and an answer 2e-10 inside it (relative) passed the search's samples while
        the motion layer found it rocking (benchmarks/DIMENSION.md, *A crank on the verge*)."""
        if not self.problem.turn_held:
            return False
        clearance = self._clearance(z)
        return clearance is not None and clearance < TURN_MARGIN

    def stiffen(self) -> None:
        """Polish the best answer once more so that a binding link-length constraint is met on its bound,
        not the search's margin of 1e-4 inside it (``MARGIN``: 0.6 % of CE2's error under an order, 0.04 %
        of the ten points' of [HCDJ] under a length bound); a stiffer penalty slides along a binding
        constraint too slowly (or, from the start, misleads the search).  With orders every link-length
        constraint (a length or ratio bound beside them too) is held as a constraint of its own, and a crank's
        turning (:meth:`constrained`, their penalty rows then dropped for good); a length or ratio bound
        without orders by a shifted penalty (:meth:`aim_bounds`): on CE2 the shifted penalty
        ended 1.8e-4 (relative) above SLSQP's answer, and on the ten points SLSQP crawled (0.03 % short
        after 500 steps) where the shifted penalty met the published optimum.  A crank on the verge of stopping
        without length bounds is polished as under orders, its turn held :data:`TURN_MARGIN` clear.  Kept if it
        meets the constraints (to ``MET``) and errs no more, or the answer before did not meet them."""
        p, kept = self.problem, self.best
        _, z0, direction = kept
        if p.order or not p.length_bounds:  # (without length bounds: a crank on the verge, its turn held)
            z0 = self.posed(z0)
            p.aim = _dropped(p, every=True)
            verge = not p.order  # (then its runs are short, within AIM_SHARE of the budget beyond it)
            found = self.constrained(z0, direction, final=True, until=self.watch.used()
                                     + AIM_SHARE * self.watch.budget if verge else None)
            before = float(np.sum(self.evaluate.vector(z0, direction) ** 2))
            unmet = (self._inside(z0, every=True) < -MET).any() or self.on_the_verge(z0)
            if found is not None and (found[0] <= before or unmet):
                self.best = (found[0], found[1], direction)
            return
        found = self.aim_bounds()
        if found is None:
            return
        after, before = self._fit(found), self._fit(kept)
        met = (p.length_gaps(p.linkage(found[1][:p.dims])) <= MET).all()
        unmet_before = (p.length_gaps(p.linkage(kept[1][:p.dims])) > MET).any()
        if met and after < INFEASIBLE / 10 and (after <= before or unmet_before):
            self.best = (after, found[1], found[2])

    def posed(self, z) -> np.ndarray:
        """A timed answer's unknowns z with the mechanism posed at its first target input where that input is
        prescribed (absolute timing, a function), as the result is returned: the dyads must close from the pose
        to the points, and a pose beyond a dead position the points do not cross (the half circle's search
        left its answers so) walls the polish in."""
        p = self.problem
        if not p.timed:
            return z
        linkage = p.linkage(z[:p.dims])
        posed = p.posed(linkage)
        return z if posed is linkage else p.unknowns_of(posed)

    def constrained(self, z0, direction: int, watched: bool = False, final: bool = False,
                    until: float | None = None) -> tuple[float, np.ndarray] | None:
        """The least squares from z0 with the link-length orders as inequality constraints of their own, held
        :data:`HELD_MARGIN` inside their bounds (SLSQP on the squared residuals, the orders' penalty rows dropped):
        (cost, unknowns) where it meets them, else None.  With ``watched`` it stops with the budget; with ``until``
        no run starts once that many seconds are used, each run of :data:`VERGE_STEPS` steps.  The
        ``final`` polish of the answer holds a length or ratio bound beside the orders so too, and a crank's
        turning where :attr:`Problem.turn_held` (its least dyad discriminant over the turn at least
        :data:`TURN_MARGIN`, the turn then left out of the residuals' samples, and the cost judged again with
        it sampled), and takes central differences.

        SLSQP is given the cost's gradient 2·Jᵀr from the polish's own Jacobian (:meth:`jacobian`: forward
        differences, in the final polish central ones, of the step :data:`_STEP`), and a run is restarted (its
        quasi-Newton matrix afresh, its tolerance 1e-12 of its own start's cost) while the last one stalled or
        lowered the cost tenfold, up to :data:`STIFF_RUNS`, until the target is met exactly. The least squares'
        penalty (a hinge) stalls where an order binds: CE1 as its sources state it stopped at 1.28e-9 with r4 = r1,
        and SLSQP on its own differences of the cost did not move from there in 500 steps; with the gradient it is
        met exactly in 1.1 CPU s, the order kept (benchmarks/DIMENSION.md, *CE1 as stated, met*). A crank that stops
        is refused by the residuals outright (a wall), so SLSQP's steps across Grashof's bound failed; held as an
        inequality the bound is reached. And near a dead position the residuals' curvature grows without bound, so
        forward differences (their error h·f″) mislead SLSQP, and central ones of the usual step eps^(1/3) (error
        h²·f‴) more: on the half circle of [HCDJ], whose last point lies near a dead position, SLSQP from the least
        squares' answer crawled to 3.8e-6 above the record in 10 CPU s with forward differences and went astray with
        those central ones, and reaches the record in 0.2 CPU s with central differences of the step eps^(1/2)
        (benchmarks/DIMENSION.md, *The half circle at its record*)."""
        problem, evaluate, watch = self.problem, self.evaluate, self.watch
        extra = len(z0) - problem.dims  # (untimed: the input steps)
        upper = np.concatenate((problem.upper, np.full(extra, problem.input_span)))
        bounds = list(zip(np.concatenate((problem.lower, np.zeros(extra))), upper))
        held = final and problem.turn_held and self._clearance(z0) is not None  # the crank's turn held too

        def inside(z):
            lengths = self._inside(z, final)
            return np.append(lengths, self._clearance(z) - TURN_MARGIN) if held else lengths

        def held_by(z):  # (SLSQP may end a run outside its constraints: the final polish keeps the last inside)
            return bool((self._inside(z, final) >= -MET).all() and (not held or self._clearance(z) > 0))

        def fun(z):
            if watched and watch.over():
                raise _OutOfTime
            return evaluate.vector(z, direction)

        def cost(z):
            r = fun(z)
            return float(r @ r)

        def gradient(z):  # (the final polish's central differences: see the docstring)
            r = fun(z)
            return 2.0 * self.jacobian(fun, z, upper, central=final, r0=r).T @ r

        penalty, z, value = problem.aim, z0, math.inf
        try:
            problem.aim, problem.turn_sampled = _dropped(problem, final), not held
            try:
                value = start = cost(z0)
                if held and self.on_the_verge(z0):  # (its turn held at some cost: any step that holds it is kept)
                    value = math.inf
                for _ in range(STIFF_RUNS):
                    if until is not None and watch.used() >= until:
                        break
                    found = minimize(cost, z, jac=gradient, method="SLSQP", bounds=bounds,
                                     constraints={"type": "ineq", "fun": inside},
                                     options={"ftol": 1e-12 * start, "maxiter": VERGE_STEPS
                                              if until is not None else 100})
                    moved = np.clip(found.x, *np.array(bounds).T)
                    again = cost(moved)
                    if not (again < value and (not final or held_by(moved))):
                        break
                    z, value, tenfold = moved, again, again <= value / 10 < math.inf
                    if value <= EXACT ** 2 or (found.status == 0 and not tenfold):
                        break
            except _OutOfTime:
                pass
            if held:  # (judged again with the whole turn sampled: a crank that stops is refused)
                problem.turn_sampled = True
                value = float(np.sum(evaluate.vector(z, direction) ** 2))
        finally:
            problem.aim, problem.turn_sampled = penalty, True
        if (self._inside(z, final) >= -MET).all() and value < INFEASIBLE / 10:
            return value, z
        return None

    def _clearance(self, z) -> float | None:
        """The least dyad discriminant over the crank's turn of the unknowns z (:meth:`Problem.turn_clearance`;
        −1 where the mechanism cannot be built, None for one moved by Newton's method)."""
        try:
            return self.problem.turn_clearance(self.problem.linkage(z[:self.problem.dims]))
        except MotionError:
            return -1.0

    def _inside(self, z, every: bool = False) -> np.ndarray:
        """How far inside each link-length order's bound (with ``every``: each link-length constraint's,
        :meth:`Problem.length_gaps`) less :data:`HELD_MARGIN` the unknowns z are (≥ 0 where held)."""
        problem = self.problem
        try:
            linkage = problem.linkage(z[:problem.dims])
            return -((problem.length_gaps(linkage) if every else problem.order_gaps(linkage)) + HELD_MARGIN)
        except MotionError:
            return np.full(problem.length_bounds if every else problem.order_pairs, -1.0)

    def jacobian(self, fun, z, upper, central: bool = False, r0=None) -> np.ndarray:
        """Forward (or ``central``) differences of the residuals ``fun`` at z (``r0``: ``fun(z)``, if the caller
        has it), each of the step :data:`_STEP`: every column for a timed target; without timing z = (dimensions,
        input steps) and the steps' columns cost one evaluation (two) for all (:meth:`untimed_jacobian`)."""
        if not self.problem.timed:
            return self.untimed_jacobian(fun, z, upper, central, _STEP, r0)
        return _differences(fun, z, upper, range(len(z)), _STEP, central, r0)

    def aim_bounds(self):
        """The best answer polished again with the length and ratio bounds aimed :data:`HELD_MARGIN` inside (a
        binding one held there as an equality, :meth:`polish`), each aim then moved inwards by the overshoot its
        penalty leaves, for up to :data:`AIM_ROUNDS`
        polishes with central differences, within :data:`AIM_SHARE` of the budget beyond it (a shifted
        penalty: the least squares converge as the search's do, and the answer lands on the bound); (cost,
        unknowns, direction), or None."""
        p, kept = self.problem, self.best
        aim = np.full(p.length_bounds, HELD_MARGIN)
        best, until = None, self.watch.used() + AIM_SHARE * self.watch.budget
        for _ in range(AIM_ROUNDS):
            p.aim = aim
            self.best = None
            if self.polish((best or kept)[1], grace=True, until=until, direction=kept[2], central=True) is None:
                break
            best = self.best
            gaps = p.length_gaps(p.linkage(best[1][:p.dims]))
            if (gaps <= 0).all():
                break
            aim = aim + np.maximum(gaps + aim, 0.0) * (gaps > -HELD_MARGIN)  # (each active aim moved by its overshoot)
        self.best = kept
        return best

    def _fit(self, best) -> float:
        """The sum of squares of an answer's target rows alone (its constraints' rows left out)."""
        p = self.problem
        r = self.evaluate.vector(best[1], best[2])[:p.points * p.rows_per_point]
        return float(r @ r)

    def untimed_jacobian(self, fun, z, upper, central: bool = False, step: float | None = None,
                         r0=None) -> np.ndarray:
        """Forward (or ``central``) differences of the untimed residuals ``fun`` at z = (dimensions, input
        steps), at the cost of one evaluation (two) per dimension and one (two) for all the steps, and for
        forward differences one at z unless the caller gives it (``r0``); the step :data:`_STEP`
        (:data:`_CENTRAL_STEP` for central ones) unless ``step`` is given.

        Point i is reached at the input offset direction·(s₁ + … + sᵢ) and its residuals depend on that
        offset alone; the constraint rows depend on the last offset (the target's span).  So one step
        of s₁, which moves every later point's offset by the same amount, gives each point's derivative
        along its own offset, and the column of step k is that of s₁ with the points before k zeroed.
        """
        problem = self.problem
        step = step if step is not None else _CENTRAL_STEP if central else _STEP
        known = _differences(fun, z, upper, range(problem.dims + 1), step, central, r0)  # (the dimensions and s₁)
        jac = np.empty((len(known), len(z)))
        jac[:, :problem.dims + 1] = known
        rows = problem.rows_per_point  # residuals per target point
        block = np.arange(problem.points * rows) // rows  # the target point of each residual row
        later = block[:, None] >= np.arange(1, len(z) - problem.dims + 1)[None, :]
        first = jac[:, problem.dims]
        jac[:len(block), problem.dims:] = np.where(later, first[:len(block), None], 0.0)
        jac[len(block):, problem.dims:] = first[len(block):, None]
        return jac


#: the forward-difference step of the untimed polish's Jacobian (relative; scipy's "2-point")
_STEP = float(np.finfo(float).eps) ** 0.5
#: the central-difference step of the final polish's Jacobian (relative; scipy's "3-point")
_CENTRAL_STEP = float(np.finfo(float).eps) ** (1 / 3)


def _forward_steps(z, upper, columns, step: float = _STEP):
    """(z moved, step) for each of the columns: a relative step of :data:`_STEP` (or ``step``), backwards
    where a forward one would leave the box."""
    for j in columns:
        h = step * max(1.0, abs(z[j]))
        if z[j] + h > upper[j]:
            h = -h
        moved = np.array(z)
        moved[j] += h
        yield moved, h


def _differences(fun, z, upper, columns, step: float, central: bool, r0=None) -> np.ndarray:
    """The columns of the residuals ``fun``'s Jacobian at z for the unknowns ``columns``: forward differences
    of the relative ``step`` (backwards at the box's upper bound, :func:`_forward_steps`; ``r0`` is ``fun(z)``
    if the caller has it), or central ones."""
    if not central and r0 is None:
        r0 = fun(z)
    out = []
    for j, (moved, h) in zip(columns, _forward_steps(z, upper, columns, step)):
        if central:
            back = np.array(z)
            back[j] -= h
            out.append((fun(moved) - fun(back)) / (2 * h))
        else:
            out.append((fun(moved) - r0) / h)
    return np.column_stack(out)


def _dropped(problem: Problem, every: bool = False) -> np.ndarray:
    """The problem's aims with the link-length orders' rows (with ``every``: every link-length constraint's)
    dropped (aimed at −∞: their penalty 0), those then held as constraints of their own."""
    if every:
        return np.full(problem.length_bounds, -np.inf)
    return np.concatenate((np.full(problem.order_pairs, -np.inf), problem.aim[problem.order_pairs:]))


def _places_step(on: np.ndarray, along: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The Gauss-Newton step of an untimed path's later places when they move with its placement:
    w ≈ on·c + (0, along·δ) in least squares over c (complex, the placement's coefficients) and δ (real,
    each later row's place), ``on`` (N, 3) the columns the carried curve is linear in at each row's
    place and ``along`` (N − 1,) the carried curve's derivative at each later place; returns δ.

    >>> on = np.column_stack((np.ones(3), [0, 1, 2], np.zeros(3))).astype(complex)
    >>> _places_step(on, np.array([1j, 1j]), np.array([0, 1 + 0.5j, 2 - 0.25j])).round(12).tolist()
    [0.5, -0.25]
    """
    size = np.abs(along)
    still = size == 0  # (a place where the curve stands still keeps both equations, and does not move)
    u = np.where(still, 1.0, along / np.where(still, 1.0, size))
    turned, aim = np.conj(u)[:, None] * on[1:], np.conj(u) * w[1:]  # each later row along and across its tangent
    # δ takes the part along the tangent whatever c is: c is fitted to the first row and the parts across
    a = np.vstack((np.hstack((on[:1].real, -on[:1].imag)), np.hstack((on[:1].imag, on[:1].real)),
                   np.hstack((turned.imag, turned.real)), np.hstack((turned.real, -turned.imag))[still]))
    b = np.concatenate((w[:1].real, w[:1].imag, aim.imag, aim.real[still]))
    solved, *_ = np.linalg.lstsq(a, b, rcond=None)
    c = solved[:on.shape[1]] + 1j * solved[on.shape[1]:]
    return np.where(still, 0.0, (aim - turned @ c).real / np.where(still, 1.0, size))


def _result(problem: Problem, evaluate: _Evaluate, best, watch: _Watch, runs: int,
            sampled: bool = False) -> DimensionalResult:
    """The best candidate as a linkage, its errors and constraints re-checked by the motion layer."""
    _, z, direction = best
    x = z[:problem.dims]
    linkage = problem.posed(problem.linkage(x))  # at the first input where it is prescribed, as every result
    if problem.timed:
        offsets = problem.offsets_of_timing(linkage)
    else:
        offsets = direction * np.concatenate(([0.0], np.cumsum(z[problem.dims:])))
    inputs = problem.input_at_pose(linkage) + offsets
    values, _, _ = problem.move(linkage, offsets)
    target = problem.target
    angle_errors = None
    if isinstance(target, FunctionTarget):
        traced = values
        errors = np.abs(values - target.outputs) if target.output_is == "displacement" else \
            np.abs(problem.residuals(values)[:, 0])
    elif isinstance(target, MotionTarget):
        traced = np.column_stack((values[:, :2], target.poses[0, 2] + values[:, 2]))
        errors = np.hypot(*(values[:, :2] - target.points).T)
        angle_errors = np.abs(problem.residuals(values)[:, 2])
    else:
        traced = values
        errors = np.hypot(*(values - target.points).T)
    try:
        constraints = _checked(problem, linkage, offsets)
    except (MotionError, ValueError) as exc:  # the motion layer could not follow the found linkage's branch
        constraints = {"branch": {"value": f"the motion layer could not trace the branch: {exc}", "limit": None,
                                  "met": False}}
    given = "the target's dyads + " if target.kind == "motion" else "sampled crank curves + "
    method = (given if sampled else "") + (
        ("bounded least squares (trf) from " + ("them, " if sampled else "a given start, ")) if runs == 0 else
        f"differential evolution ({runs} run{'s' * (runs > 1)}) + bounded least squares (trf), ") + (
        "timed" if problem.timed else "inputs as unknowns, in order")
    return DimensionalResult(linkage, target, target.kind, inputs, traced, errors, target.size if target.kind == "function"
                             else problem.scale, watch.used(), watch.count, method, constraints, angle_errors, target.weights,
                             problem.on_reach(x))


def _checked(problem: Problem, linkage: Linkage, offsets: np.ndarray) -> dict:
    """Every constraint re-checked by the motion layer's own tools (true limits, refined angles)."""
    c = problem.constraints
    reach = motion_range(linkage)
    phi0 = float(linkage.pose_inputs[0])
    lo_in, hi_in = phi0 + min(0.0, offsets.min()), phi0 + max(0.0, offsets.max())
    out = {}
    if reach.full_rotation:
        on_branch = True
    else:
        lo, hi = reach.limits
        on_branch = lo - 1e-9 <= lo_in and hi_in <= hi + 1e-9
    out["branch"] = {"value": "every target point on the pose's branch" if on_branch
                     else "a dead position lies between the target points", "limit": None, "met": bool(on_branch)}
    if c.crank:
        out["crank"] = {"value": "turns fully" if reach.full_rotation else
                        f"rocks between {_angle(reach.limits[0])} and {_angle(reach.limits[1])}",
                        "limit": None, "met": bool(reach.full_rotation)}
    if c.rocker is not None:  # (in the target's measure: a function's input slider's pin along its line)
        shift = problem.input_at_pose(linkage) - phi0
        lo, hi = lo_in + shift, hi_in + shift
        inside = c.rocker[0] - 1e-9 <= lo and hi <= c.rocker[1] + 1e-9
        out["rocker"] = {"value": [lo, hi], "limit": list(c.rocker), "met": bool(inside)}
    if c.min_transmission > 0:
        worst = _worst_transmission(linkage, lo_in, hi_in, c.crank and reach.full_rotation)
        out["transmission"] = {"value": None if worst is None else math.degrees(worst),
                               "limit": math.degrees(c.min_transmission),
                               "met": worst is not None and worst >= c.min_transmission - MET}
    if c.max_ratio is not None:
        ratio = link_ratio(linkage)
        out["ratio"] = {"value": ratio, "limit": c.max_ratio, "met": ratio <= c.max_ratio * (1 + MET)}
    if c.max_length is not None:
        longest = longest_link(linkage)
        out["length"] = {"value": longest, "limit": c.max_length, "met": longest <= c.max_length * (1 + MET)}
    if c.pivots is not None:
        x0, x1, y0, y1 = c.pivots
        p = linkage.points[problem.frame_joints]
        tol = MET * problem.scale
        inside = bool(((p[:, 0] >= x0 - tol) & (p[:, 0] <= x1 + tol) & (p[:, 1] >= y0 - tol) & (p[:, 1] <= y1 + tol)).all())
        out["pivots"] = {"value": p.tolist(), "limit": list(c.pivots), "met": inside}
    out.update(problem.placing(linkage))
    if not problem.timed and problem.revolute_input:
        turn = abs(float(offsets[-1]))
        out["order"] = {"value": f"the input turns {math.degrees(turn):.6g}° over the points, in order",
                        "limit": None, "met": turn <= 2 * math.pi + 1e-9}
    return out


def _angle(v: float) -> str:
    return f"{math.degrees(v):.6g}°"


def _worst_transmission(linkage: Linkage, lo: float, hi: float, whole_turn: bool) -> float | None:
    """The least of min(μ, π − μ) over the dyads, between the inputs lo and hi (a whole turn for a
    crank), from the motion layer's refined extremes; None for a linkage moved by Newton's method."""
    if whole_turn:
        motion = sweep(linkage, steps=361)
    else:
        motion = sweep(linkage, steps=181, start=lo, stop=hi if hi > lo else lo + 1e-9)
    if not motion.transmission:
        return None
    return min(min(t["min"], math.pi - t["max"]) for t in motion.transmission.values())

