"""Balancing hardware compared: which strategy, how many devices, how much mass, how much torque saved.

For one arm (TOML or URDF), one workspace (a box of joint ranges inside the limits) and one
payload range, five strategies side by side (:class:`CompareProblem` → :class:`Comparison`):

1. ``none`` — the baseline: the gravity torque the drives carry;
2. ``counterweights`` — a mass per joint putting each sub-arm's centre of mass on its axis
   (:mod:`balance.devices.counterweights`), with the inertia it adds to each joint and the
   motor torque that costs at a stated acceleration;
3. ``springs per joint`` — the industrial layout: one zero-free-length spring device at each
   revolute joint, cancelling that joint's gravity torque averaged over the other joints'
   ranges (a sinusoid of the joint's own angle, so the device is exact for it), with a
   helical spring to order (:mod:`balance.devices.helical`); a slide gets a constant force;
4. ``harmonic, pruned`` — the source's decomposition (one device per harmonic term, gear trains
   forming its shaft), keeping the fewest terms, largest first, that hold the residual under
   ``target`` × the baseline; each dropped term's own torque is reported;
5. ``exact springs`` — for an arm whose terms are the absolute angles of a planar chain (the
   parallelogram-equivalent arms of Agrawal & Fattah 2004, Deepak & Ananthasuresh 2012): one
   zero-free-length spring per link on a parallelogram, exact; otherwise the term that stops it.

For each: the residual torque per joint over the workspace and the payload range — its largest
value (a true extreme, :mod:`balance.extremes`, with the configuration and payload reaching it)
and its RMS (over uniform configurations, Simpson's rule over the payload, exact for the linear
dependence) — the share of the baseline removed, the devices, the added mass and the payload
the devices are tuned for: the one minimising the worst residual (the middle of the range for
the exact strategies, where the residual is the payload's deviation alone; the source's "half
the maximum payload" when the range starts at 0). Every strategy's residual is recomputed
independently with Pinocchio (``rnea`` at zero velocity and acceleration, on a model rebuilt
from URDF text) at random configurations and at the reported worst ones.

Examples
--------
>>> from balance.model.arm import Arm, Link, Load
>>> arm = Arm((Link("upper", "revolute", 0.5, 40.0, 0.25), Link("fore", "revolute", 0.4, 20.0, 0.2)),
...           (Load(1, 20.0, 0.4, payload=True),), zero="horizontal")
>>> c = CompareProblem(arm, payload=(0.0, 2.0), samples=200).solve()
>>> [s.name for s in c.strategies]
['none', 'counterweights', 'springs per joint', 'harmonic, pruned', 'exact springs']
>>> ex = c.strategy("exact springs").joints[0]  # left: the payload's half-range, 1 kg at 0.9 m
>>> round(ex.max / 9.80665, 9), round(ex.baseline_max, 4)  # of 40·0.25 + 20·0.7 + 2·9.80665·0.9 N·m
(0.9, 41.652)
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping, Sequence

import numpy as np
from scipy import optimize

from mechbase import Row

from ..budget import WORK_LIMIT, ensure_affordable
from ..devices.counterweights import Counterweight, place_counterweights
from ..devices.fit import SpringBounds, fit_spring
from ..devices.helical import HelicalSpring, design_for_device
from ..devices.transmission import transmissions
from ..errors import BalanceError, InvalidInput, SchemaError
from ..extremes import EXTREMES_NOTE, box_extremes
from ..model.arm import Arm, ArmModel, Load, describe_term
from ..model.potential import HarmonicTerm, merge_terms, terms_forces
from ..model.urdf import UrdfArm, arm_to_urdf, pinocchio_gravity, pinocchio_model
from ..schema import parse
from .arm import G, JointRow, _ensure_terms_affordable, arm_problem, joint_rows

__all__ = ["CompareProblem", "Comparison", "Strategy", "JointResidual", "PinocchioRecheck", "CompareJoint", "compare_problem", "STRATEGIES"]

#: the spring devices' crank geometry when the arm's file gives none (m)
DEVICE_BOUNDS = SpringBounds(r=(0.02, 0.1), r0=(0.05, 0.3), a=(0.0, 0.3))


# ----------------------------------------------------------------------------- results
@dataclass(frozen=True)
class CompareJoint(JointRow):
    """A joint of the arm compared, as the comparison lists it: its coordinate first."""

    row_keys = ("coordinate", "name", "kind")


@dataclass(frozen=True)
class JointResidual(Row):
    """One joint's residual torque (N·m, or N on a slide) under a strategy, against the baseline.

    ``max`` is the largest ``|residual|`` over the workspace and the payload range (a true extreme),
    reached at ``worst_at`` (joint coordinates) with the payload ``worst_payload`` (kg); ``rms`` its
    root mean square over uniform configurations and payloads.
    """

    coordinate: str
    name: str
    max: float
    rms: float
    baseline_max: float
    baseline_rms: float
    worst_at: tuple[float, ...]
    worst_payload: float

    row_keys = ("coordinate", "name", "max", "rms", "baseline_max", "baseline_rms", "removed_max", "removed_rms",
                "worst_at", "worst_payload")

    @property
    def removed_max(self) -> float:
        """The share of the baseline's largest torque removed (1 = all of it)."""
        return 1 - self.max / self.baseline_max if self.baseline_max > 0 else 0.0

    @property
    def removed_rms(self) -> float:
        return 1 - self.rms / self.baseline_rms if self.baseline_rms > 0 else 0.0



@dataclass(frozen=True)
class TensionFit(Row):
    """A zero-free-length tension device fitted to a torque amplitude: its spring rate ``c`` (N/m), crank
    ``r``, ``r0`` and pre-extension ``a`` (m), its largest spring force (N) and relative error."""

    c: float
    r: float
    r0: float
    a: float
    max_force: float
    max_rel_error: float


@dataclass(frozen=True)
class SpringDevice(Row):
    """The device fitted (None when none fits), the helical spring made for it (None when none is made)
    and both in words (or why not)."""

    device: TensionFit | None
    spring: HelicalSpring | None
    summary: str


@dataclass(frozen=True)
class JointSpring(Row):
    """One joint's spring of the springs-per-joint strategy: a device for the torque ``amplitude``·sin(q +
    phase) averaged over the other joints."""

    fitted: SpringDevice
    coordinate: str
    amplitude: float
    phase_deg: float

    row_keys = ("*fitted", "coordinate", "amplitude", "phase_deg")


@dataclass(frozen=True)
class ConstantForce(Row):
    """A slide's constant averaged gravity force (N), held by a gas spring."""

    coordinate: str
    constant_force: float


@dataclass(frozen=True)
class TermSpring(Row):
    """A spring device for one harmonic term (its form as text and its amplitude, N·m)."""

    fitted: SpringDevice
    form_text: str
    amplitude: float

    row_keys = ("*fitted", "form_text", "amplitude")


@dataclass(frozen=True)
class DroppedTerm(Row):
    """A term the pruned decomposition leaves out, and the largest torque it puts on each joint."""

    amplitude: float
    form: tuple[float, ...]
    form_text: str
    largest_torque_per_joint: tuple[float, ...]


@dataclass(frozen=True)
class CounterweightDetails(Row):
    """The counterweights, the inertia they add to each joint (kg·m², or kg on a slide) and the motor
    torque that inertia alone needs at the comparison's acceleration."""

    weights: tuple[Counterweight, ...]
    added_inertia: tuple[float, ...]
    motor_torque_at_acceleration: tuple[float, ...]
    note: str = ("added inertia: the largest increase of each joint's diagonal mass-matrix entry over the workspace "
                 "(kg·m², or kg on a slide); the motor torque accelerates it alone at the stated acceleration")


@dataclass(frozen=True)
class JointSpringDetails(Row):
    """The springs of the springs-per-joint strategy."""

    springs: tuple[JointSpring | ConstantForce, ...]
    note: str = "each device cancels its joint's gravity torque averaged over the other joints' ranges (uniformly)"


@dataclass(frozen=True)
class PrunedDetails(Row):
    """The pruned decomposition: terms in all, kept, the target torque (N·m), the terms dropped, the springs of
    the kept ones, the differentials of their shafts, and why the target is missed (None: it is met)."""

    terms: int
    kept: int
    target_torque: float
    dropped: tuple[DroppedTerm, ...]
    springs: tuple[TermSpring, ...]
    differentials: int
    note: str | None = None

    row_keys = ("terms", "kept", "target_torque", "dropped", "springs", "differentials", "note?")


@dataclass(frozen=True)
class ExactDetails(Row):
    """The exact springs, one per link's absolute angle, and the parallelograms that carry those angles."""

    springs: tuple[TermSpring, ...]
    parallelograms: int
    note: str = "each link's absolute angle is carried to the base by a parallelogram (its bars are not weighed)"


@dataclass(frozen=True)
class PinocchioRecheck(Row):
    """A strategy's residual recomputed by Pinocchio at random configurations (``configurations`` of
    them, at each payload of ``payloads``) and at the worst ones: the largest difference from the
    project's own residual, and the residual at each worst configuration against the one reported."""

    configurations: int
    payloads: tuple[float, ...]
    max_difference: float
    at_worst: tuple[float, ...]
    reported: tuple[float, ...]
    method: str = "rnea(q, 0, 0) on a model rebuilt from URDF text"


@dataclass(frozen=True)
class Strategy(Row):
    """One balancing strategy: its hardware and what it leaves of the gravity torque.

    ``devices`` counts springs or counterweights; ``added_mass`` (kg) is what the hardware adds
    that the project sizes (counterweights, helical springs; cranks, gear trains and parallelogram
    bars are listed in ``hardware`` but not weighed). ``pinocchio`` holds the independent recheck:
    Pinocchio's residual at random configurations and at the worst ones, against the reported one.
    """

    name: str
    available: bool
    reason: str | None = None
    devices: int = 0
    added_mass: float = 0.0
    tuned_for: float | None = None
    joints: tuple[JointResidual, ...] = ()
    hardware: tuple[str, ...] = ()
    details: CounterweightDetails | JointSpringDetails | PrunedDetails | ExactDetails | dict = field(
        default_factory=dict)
    pinocchio: PinocchioRecheck | None = None
    forces: Any = field(default=None, repr=False, compare=False)  # the devices' forces, q → (m, n), for figures

    @property
    def max_residual(self) -> float:
        return max((j.max for j in self.joints), default=0.0)

    @property
    def removed(self) -> float:
        """The share of the baseline's largest torque (over all joints) removed."""
        base = max((j.baseline_max for j in self.joints), default=0.0)
        return 1 - self.max_residual / base if base > 0 else 0.0

    @property
    def worst_payload(self) -> float | None:
        worst = max(self.joints, key=lambda j: j.max, default=None)
        return None if worst is None else worst.worst_payload

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The row: why the strategy is not available, or what it leaves."""
        if not self.available:
            return ("name", "available", "reason")
        return ("name", "available", "devices", "added_mass", "tuned_for", "max_residual", "removed", "worst_payload",
                "joints", "hardware", "details", "pinocchio")


@dataclass(frozen=True)
class Comparison(Row):
    """What :class:`CompareProblem` finds: the strategies side by side (see :meth:`to_dict`)."""

    arm: ArmModel
    workspace: tuple[tuple[float, float], ...]
    payload: tuple[float, float]
    target: float
    acceleration: float
    samples: int
    seed: int
    strategies: tuple[Strategy, ...]
    gravity: Any = field(default=None, repr=False, compare=False)  # Q(q, payload), for the figure

    row_keys = ("kind", "name", "joints", "workspace", "payload", "target", "acceleration", "samples", "seed",
                "extremes", "strategies")
    kind = "compare"
    extremes = EXTREMES_NOTE

    def strategy(self, name: str) -> Strategy:
        return next(s for s in self.strategies if s.name == name)

    @property
    def name(self) -> str:
        return self.arm.name

    @property
    def joints(self) -> tuple[CompareJoint, ...]:
        return joint_rows(self.arm, CompareJoint)


# ----------------------------------------------------------------------------- the problem
@dataclass(frozen=True)
class CompareProblem:
    """An arm, its workspace and payload range, and the strategies' settings.

    Attributes
    ----------
    arm : ArmModel
        A TOML arm (its payload loads carry the payload) or a URDF arm (its payload point).
    payload : (float, float)
        The payload range (kg), low ≤ high.
    workspace : sequence of (float, float), optional
        Per joint, the range the comparison covers (rad, or m on a slide); default the limits.
    target : float
        The pruned decomposition's target: the largest residual, as a share of the baseline's.
    acceleration : float
        The joint acceleration (rad/s² or m/s²) at which the counterweights' motor torque is given.
    counterweight_arms : mapping
        Each joint's counterweight distance from its axis (m); default half the link.
    spring_bounds : SpringBounds
        The crank geometry of every spring device.
    material : str
        The spring wire.
    samples, seed : int
        Random configurations that start the searches for the largest residuals and give the RMS.
    g : float
    work_limit : float or None
    """

    arm: ArmModel
    payload: tuple[float, float] = (0.0, 0.0)
    workspace: tuple[tuple[float, float], ...] | None = None
    target: float = 0.05
    acceleration: float = 1.0
    counterweight_arms: Mapping[int, float] = field(default_factory=dict)
    spring_bounds: SpringBounds = DEVICE_BOUNDS
    material: str = "music-wire"
    samples: int = 1000
    seed: int = 0
    g: float = G
    work_limit: float | None = WORK_LIMIT

    def solve(self) -> Comparison:
        return _Solver(self).run()


class _Solver:
    """The comparison's shared state: the arm at its payloads, the box, the samples, the baseline."""

    def __init__(self, pb: CompareProblem):
        self.pb = pb
        arm = pb.arm
        lo_p, hi_p = (float(v) for v in pb.payload)
        if not (math.isfinite(lo_p) and math.isfinite(hi_p) and 0 <= lo_p <= hi_p):
            raise InvalidInput(f"the payload range must be finite with 0 ≤ low ≤ high, not {lo_p:g} .. {hi_p:g} kg.")
        if not (math.isfinite(pb.target) and 0 < pb.target < 1):
            raise InvalidInput(f"the target must be a share of the baseline torque in (0, 1), not {pb.target:g}.")
        if not (math.isfinite(pb.acceleration) and pb.acceleration >= 0):
            raise InvalidInput(f"the acceleration must be a finite number ≥ 0, not {pb.acceleration:g}.")
        lim_lo, lim_hi = arm.box
        ws = pb.workspace or tuple(zip(lim_lo, lim_hi))
        if len(ws) != arm.n:
            raise InvalidInput(f"the workspace needs a range for each of the {arm.n} joints, not {len(ws)}.")
        for i, ((a, b), c) in enumerate(zip(ws, arm.coordinates)):
            unit, k = ("°", 180 / math.pi) if c.joint != "prismatic" else (" m", 1.0)
            if not (math.isfinite(a) and math.isfinite(b) and a <= b):
                raise InvalidInput(f"the workspace of q{i + 1} must be finite with low ≤ high, not "
                                   f"{a * k:g}{unit} .. {b * k:g}{unit}.")
            if a < c.limits[0] - 1e-12 or b > c.limits[1] + 1e-12:
                raise InvalidInput(f"the workspace of q{i + 1}, {a * k:g}{unit} .. {b * k:g}{unit}, leaves the joint's "
                                   f"limits {c.limits[0] * k:g}{unit} .. {c.limits[1] * k:g}{unit}.")
        self.lo = np.array([w[0] for w in ws], dtype=float)
        self.hi = np.array([w[1] for w in ws], dtype=float)
        self.workspace = tuple((float(a), float(b)) for a, b in ws)
        self.p = (lo_p, hi_p)
        self.p_mid = 0.5 * (lo_p + hi_p)
        self.span = hi_p - lo_p
        self.g = pb.g
        self.arm_lo = arm.with_payload(lo_p, self.g)
        self.arm_hi = arm.with_payload(hi_p, self.g)
        probe = self.lo + (self.hi - self.lo) * np.random.default_rng(pb.seed).random((16, arm.n))
        ensure_affordable(f"comparing the strategies at {pb.samples} configurations", pb.samples,
                          lambda: [self.arm_lo.gravity_forces(probe) for _ in range(40)], pb.work_limit, per=16)
        if isinstance(arm, UrdfArm):  # its harmonic terms: a grid of 3ʳ·2ᵖ and up to (3ⁿ + 1)/2 terms
            self.arm_lo.ensure_decomposable(pb.work_limit)
            _ensure_terms_affordable(self.arm_lo, probe, pb.samples, pb.work_limit)
        self.q = self.lo + (self.hi - self.lo) * np.random.default_rng(pb.seed).random((pb.samples, arm.n))
        # the harmonic terms at the two ends of the payload range; between them they are linear
        self.terms_lo = _phasors(self.arm_lo.harmonic_terms())
        self.terms_hi = _phasors(self.arm_hi.harmonic_terms()) if self.span > 0 else self.terms_lo
        self.slides = any(c.joint == "prismatic" for c in arm.coordinates)

    # -- the arm at a payload ------------------------------------------------------------
    def gravity(self, x: np.ndarray, payload: float) -> np.ndarray:
        """Q_gravity(q) with ``payload`` kg (linear in the payload)."""
        out = self.arm_lo.gravity_forces(x)
        if self.span > 0 and payload != self.p[0]:
            t = (payload - self.p[0]) / self.span
            out = out + t * (self.arm_hi.gravity_forces(x) - out)
        return out

    def terms(self, payload: float) -> list[HarmonicTerm]:
        """The harmonic terms of the arm carrying ``payload`` kg."""
        t = 0.0 if self.span == 0 else (payload - self.p[0]) / self.span
        out = []
        for key in sorted(set(self.terms_lo) | set(self.terms_hi)):
            z_lo, form = self.terms_lo.get(key, (0j, None))
            z_hi, form_hi = self.terms_hi.get(key, (0j, None))
            out.append(((1 - t) * z_lo + t * z_hi, form if form is not None else form_hi))
        return merge_terms(out)

    # -- residuals -------------------------------------------------------------------------
    def _extremes(self, devices) -> list[tuple[float, tuple, float, float]]:
        """Per joint (largest |Q_gravity(q, p) + devices(q)|, where, at which payload, RMS): true extremes at
        both ends of the payload range (the residual is linear in p); the RMS over the samples, Simpson's
        rule over the payload (exact: the square is quadratic in p)."""
        n = self.pb.arm.n
        ends = sorted({self.p[0], self.p[1]})
        arms = [self.arm_lo, self.arm_hi][:len(ends)]

        def f(x):
            d = devices(x)
            return np.concatenate([a.gravity_forces(x) + d for a in arms], axis=1)

        ext = box_extremes(f, self.lo, self.hi, self.q, floor=1e-11 * self.scale)
        d = devices(self.q)
        sq = [(self.gravity(self.q, p) + d) ** 2 for p in (self.p[0], self.p_mid, self.p[1])]
        rms = np.sqrt(np.mean((sq[0] + 4 * sq[1] + sq[2]) / 6, axis=0))
        out = []
        for j in range(n):
            cands = []
            for e_i, p in enumerate(ends):
                lo_e, hi_e = ext[e_i * n + j]
                cands += [(-lo_e.value, lo_e.at, p), (hi_e.value, hi_e.at, p)]
            value, at, p = max(cands, key=lambda c: c[0])
            out.append((abs(float(value)), tuple(at), float(p), float(rms[j])))
        return out

    def residuals(self, devices) -> tuple[JointResidual, ...]:
        """The residual per joint against the baseline; a joint gravity never loads (a turntable, or below
        rounding) reads 0 before and after."""
        arm, out = self.pb.arm, []
        for j, ((v, at, p, r), b) in enumerate(zip(self._extremes(devices), self.baseline)):
            if b[0] <= 1e-11 * self.scale:
                v = r = 0.0
            out.append(JointResidual(f"q{j + 1}", arm.coordinates[j].name, v, r, b[0], b[1], at, p))
        return tuple(out)

    def run(self) -> Comparison:
        pb, arm = self.pb, self.pb.arm
        self.scale = max(float(np.max(np.abs(self.gravity(self.q, p)))) for p in self.p)
        zero = (lambda x: np.zeros((len(x), arm.n)))
        base = self._extremes(zero)
        self.scale = max(v for v, _, _, _ in base)
        self.baseline = [(v, r) if v > 1e-11 * self.scale else (0.0, 0.0) for v, _, _, r in base]
        if self.scale <= 1e-12 * max(1.0, self.g):
            raise InvalidInput(f"the arm's gravity torque is zero in every configuration of the workspace and payload "
                               f"(the largest is {self.scale:.3g} N·m): there is nothing to balance.")
        self.recheck = _PinocchioRecheck(self)
        self.zero = zero
        strategies = [build(self) for build in _BUILDERS.values()]
        return Comparison(arm, self.workspace, self.p, pb.target, pb.acceleration, pb.samples, pb.seed,
                          tuple(strategies), self.gravity)

    def tuned(self, devices_at) -> tuple[float, tuple[JointResidual, ...]]:
        """The payload the devices are tuned for and their residuals: the payload minimising the worst
        residual (convex in it) over the samples and the worst configurations found so far, which are
        added after each search until the tuning settles (three rounds at most).
        ``devices_at(p0)`` returns the devices' forces as a function of configurations."""
        extra = np.empty((0, self.pb.arm.n))
        p0 = None
        for _ in range(3):
            new = self.best_tuning(devices_at, extra)
            if p0 is not None and abs(new - p0) <= 1e-6 * max(self.span, 1e-300):
                break
            p0 = new
            joints = self.residuals(devices_at(p0))
            extra = np.concatenate([extra, np.array([j.worst_at for j in joints])])
        return p0, joints

    def best_tuning(self, devices_at, extra=None) -> float:
        """The payload minimising the worst residual over the samples (and ``extra`` configurations)."""
        if self.span == 0:
            return self.p[0]
        q = self.q if extra is None or not len(extra) else np.concatenate([self.q, extra])
        ends = [self.gravity(q, p) for p in self.p]

        def worst(p0):
            d = devices_at(p0)(q)
            return max(float(np.max(np.abs(e + d))) for e in ends)

        sol = optimize.minimize_scalar(worst, bounds=self.p, method="bounded", options={"xatol": 1e-4 * self.span})
        return min((self.p_mid, float(sol.x), self.p[0], self.p[1]), key=worst)  # the ends: Brent stops short of them

    # -- 1. nothing ------------------------------------------------------------------------------
    def none(self) -> Strategy:
        joints = self.residuals(self.zero)
        return Strategy("none", True, devices=0, added_mass=0.0, tuned_for=None, joints=joints,
                        hardware=("the drives carry the whole gravity torque",),
                        pinocchio=self.recheck(self.zero, joints), forces=self.zero)

    # -- 2. counterweights -------------------------------------------------------------------
    def counterweights(self) -> Strategy:
        pb, arm = self.pb, self.pb.arm
        tuned = arm.with_payload(self.p_mid, self.g)
        cw = place_counterweights(tuned, dict(pb.counterweight_arms), g=self.g)  # what they leave: self.residuals
        if not cw.available:
            return Strategy("counterweights", False, cw.reason)
        balanced = cw.balanced
        plain = pinocchio_gravity(tuned, self.g)  # the same arm without them, in the same model

        def counter(x):  # the counterweights' own generalised forces
            return balanced.gravity_forces(x) - plain.gravity_forces(x)

        joints = self.residuals(counter)

        def added_inertia(x):
            return np.array([np.diag(balanced.mass_matrix(r) - plain.mass_matrix(r)) for r in x])

        ext = box_extremes(added_inertia, self.lo, self.hi, self.q[:200], starts=2)
        inertia = [max(b.value, 0.0) for _, b in ext]
        mass = sum(w.mass for w in cw.weights)
        hardware = tuple(f"{w.mass:.4g} kg on {w.link}, {w.arm:.3g} m from the axis of {w.coordinate}"
                         for w in cw.weights)
        details = CounterweightDetails(cw.weights, tuple(inertia), tuple(v * pb.acceleration for v in inertia))
        return Strategy("counterweights", True, None, len(cw.weights), mass, self.p_mid, joints, hardware, details,
                        self.recheck(counter, joints, counterweights=cw.weights), counter)

    # -- 3. one spring per joint --------------------------------------------------------------
    def springs_per_joint(self) -> Strategy:
        pb, arm = self.pb, self.pb.arm

        def averages(p0):
            return _joint_averages(self.terms(p0), self.lo, self.hi, arm, lambda x: self.gravity(x, p0), self.q)

        def devices_at(p0):
            avg = averages(p0)

            def forces(x):
                out = np.zeros((len(x), arm.n))
                for j, a in avg.items():
                    out[:, j] = -np.imag(a * np.exp(1j * x[:, j])) if isinstance(a, complex) else -a
                return out
            return forces

        p0, joints = self.tuned(devices_at)
        avg = {j: a for j, a in averages(p0).items() if abs(a) > 1e-9 * self.scale}
        devices = devices_at(p0)
        hardware, springs, mass = [], [], 0.0
        for j, a in sorted(avg.items()):
            c = arm.coordinates[j]
            if isinstance(a, complex):
                amp, phase = abs(a), cmath.phase(a)  # Q̄ = amp·sin(q + phase): the device gives −amp·sin(φ)
                fitted, m = _spring_device(amp, (float(self.lo[j] + phase), float(self.hi[j] + phase)), pb)
                mass += m
                springs.append(JointSpring(fitted, f"q{j + 1}", amp, math.degrees(phase)))
                hardware.append(f"q{j + 1} ({c.name}): crank-and-rocker, zero free length, c·r·d = {amp:.4g} N·m, "
                                + fitted.summary)
            else:
                springs.append(ConstantForce(f"q{j + 1}", -a))
                hardware.append(f"q{j + 1} ({c.name}): a constant-force spring of {abs(a):.4g} N (gas spring)")
        return Strategy("springs per joint", True, None, len(avg), mass, p0, joints, tuple(hardware),
                        JointSpringDetails(tuple(springs)),
                        self.recheck(devices, joints), devices)

    # -- 4. the source's decomposition, pruned ---------------------------------------------------
    def pruned(self) -> Strategy:
        pb, arm = self.pb, self.pb.arm
        terms = sorted(self.terms(self.p_mid), key=lambda t: -t.amplitude)
        limit = pb.target * self.scale
        ends = [self.gravity(self.q, p) for p in self.p]

        def sampled_worst(kept) -> float:  # the greedy's guide; the true extremes decide below
            d = -terms_forces(kept, self.q)
            return max(float(np.max(np.abs(e + d))) for e in ends)

        kept, trace = list(terms), []
        for t in sorted(terms, key=lambda t: t.amplitude):
            trial = [k for k in kept if k is not t]
            if trial and sampled_worst(trial) <= limit:
                kept, trace = trial, trace + [t]
        while True:  # tune, then the true residual: a term comes back while it is above the target
            p0, joints = self.tuned(lambda p, ks=tuple(kept): (lambda x, ts=self._at(ks, p): -terms_forces(ts, x)))
            at_p0 = self._at(kept, p0)
            devices = (lambda x, ts=tuple(at_p0): -terms_forces(ts, x))
            if max(j.max for j in joints) <= limit or not trace:
                break
            kept.append(trace.pop())
        dropped = []
        for t in trace:
            ext = box_extremes(lambda x, t=t: terms_forces([t], x), self.lo, self.hi, self.q[:200])
            dropped.append(DroppedTerm(t.amplitude, t.form, describe_term(arm, t).form_text,
                                       tuple(abs(max(-a.value, b.value)) for a, b in ext)))
        trains = transmissions([describe_term(arm, t).drive_form for t in at_p0], arm.shaft_names)
        hardware, springs, mass = [], [], 0.0
        for k, (t, tr) in enumerate(zip(at_p0, trains)):
            fitted, m = _spring_device(t.amplitude, _phi_range(t, self.lo, self.hi), pb)
            mass += m
            text = describe_term(arm, t)
            springs.append(TermSpring(fitted, text.form_text, t.amplitude))
            hardware.append(f"φ{k + 1} = {text.drive_form_text} ({tr.differentials} differential(s)): spring "
                            f"device c·r·d = {t.amplitude:.4g} N·m, {fitted.summary}")
        missed = None
        if max(j.max for j in joints) > limit:
            missed = (f"every term kept still leaves {max(j.max for j in joints):.4g} N·m over the payload "
                      f"range, above the target {limit:.4g} N·m: the payload's range alone exceeds it")
        details = PrunedDetails(len(terms), len(at_p0), limit, tuple(dropped), tuple(springs),
                                sum(t.differentials for t in trains), missed)
        return Strategy("harmonic, pruned", True, None, len(at_p0), mass, p0, joints, tuple(hardware), details,
                        self.recheck(devices, joints), devices)

    def _at(self, kept: Sequence[HarmonicTerm], p0: float) -> list[HarmonicTerm]:
        """The kept terms (chosen by their forms) at the payload ``p0``."""
        forms = {tuple(round(v, 12) for v in t.form) for t in kept}
        return [t for t in self.terms(p0) if tuple(round(v, 12) for v in t.form) in forms]

    # -- 5. exact springs on parallelograms -------------------------------------------------------
    def exact(self) -> Strategy:
        pb, arm = self.pb, self.pb.arm
        terms = self.terms(self.p_mid)
        reason = _not_planar_chain(arm, terms)
        if reason:
            return Strategy("exact springs", False, reason)
        devices = (lambda x, ts=tuple(terms): -terms_forces(ts, x))
        joints = self.residuals(devices)
        hardware, springs, mass = [], [], 0.0
        for t in sorted(terms, key=lambda t: -t.amplitude):
            text = describe_term(arm, t).form_text
            fitted, m = _spring_device(t.amplitude, _phi_range(t, self.lo, self.hi), pb)
            mass += m
            springs.append(TermSpring(fitted, text, t.amplitude))
            hardware.append(f"absolute angle {text}: zero-free-length spring c·r·d = {t.amplitude:.4g} N·m on a "
                            f"parallelogram, {fitted.summary}")
        links = len({int(np.flatnonzero(np.abs(t.form) > 0)[-1]) for t in terms})
        details = ExactDetails(tuple(springs), max(links - 1, 0))
        return Strategy("exact springs", True, None, len(terms), mass, self.p_mid, joints, tuple(hardware), details,
                        self.recheck(devices, joints), devices)


# ----------------------------------------------------------------------------- helpers
#: Every strategy, in the order a comparison shows them: its name and the solver's method that builds
#: it (a strategy that does not apply to the arm — counterweights or exact springs with a slide, exact
#: springs where a term is not a link's absolute angle — is built unavailable, with the reason).
_BUILDERS = {
    "none": _Solver.none,
    "counterweights": _Solver.counterweights,
    "springs per joint": _Solver.springs_per_joint,
    "harmonic, pruned": _Solver.pruned,
    "exact springs": _Solver.exact,
}
STRATEGIES = tuple(_BUILDERS)


def _phasors(terms: Sequence[HarmonicTerm]) -> dict:
    """form key → (phasor, form) of a list of terms."""
    return {tuple(round(v, 12) for v in t.form): (t.amplitude * cmath.exp(1j * t.phase), t.form) for t in terms}


def _joint_averages(terms, lo, hi, arm: ArmModel, gravity, q) -> dict:
    """Per loaded joint, its gravity force averaged over the other joints' uniform ranges: a phasor
    ``Z`` with ``Q̄_j(q_j) = Im(Z·e^{i q_j})`` for a revolute joint (exact: every term is of degree one
    in it), the mean force (sampled) for a slide."""
    out: dict[int, Any] = {}
    for j, c in enumerate(arm.coordinates):
        if c.joint == "prismatic":
            out[j] = float(np.mean(gravity(q)[:, j]))
            continue
        if c.joint != "revolute":
            continue
        z = 0j
        for t in terms:
            a = t.form[j]
            if abs(a) < 1e-12:
                continue
            factor = t.amplitude * cmath.exp(1j * t.phase)
            for i, b in enumerate(t.form):
                if i == j or abs(b) < 1e-12:
                    continue
                w = hi[i] - lo[i]
                factor *= cmath.exp(1j * b * lo[i]) if w == 0 else \
                    (cmath.exp(1j * b * hi[i]) - cmath.exp(1j * b * lo[i])) / (1j * b * w)
            # Q = a·A·sin(a·q_j + …): a term of coefficient −1 is the conjugate's
            z += a * (factor if a > 0 else -factor.conjugate()) * (1 if abs(abs(a) - 1) < 1e-12 else math.nan)
        if not cmath.isfinite(z):
            raise BalanceError(f"joint q{j + 1}: a term of degree other than one in it; no single device fits it.")
        out[j] = z
    return out


def _phi_range(t: HarmonicTerm, lo, hi) -> tuple[float, float]:
    """The range of ``φ + α`` over the box (for a device's fit): the form's extremes, at most a turn."""
    f = np.asarray(t.form)
    a = float(np.sum(np.where(f > 0, f * lo, f * hi))) + t.phase
    b = float(np.sum(np.where(f > 0, f * hi, f * lo))) + t.phase
    return (a, min(b, a + 2 * math.pi))


def _spring_device(amplitude: float, phi: tuple[float, float], pb: CompareProblem) -> tuple[SpringDevice, float]:
    """A zero-free-length tension device of ``c·r·d = amplitude`` over ``phi`` and its helical spring:
    (the device, spring mass in kg; 0 when no spring is made, the reason then in its summary)."""
    lo, hi = phi
    if hi - lo < 1e-6:
        hi = lo + 1e-6
    try:
        fit = fit_spring("tension", -amplitude, (lo, hi), pb.spring_bounds)
    except BalanceError as exc:
        return SpringDevice(None, None, f"no device: {exc}"), 0.0
    device = TensionFit(fit.c, fit.r, fit.r0, fit.a, fit.max_force, fit.max_rel_error)
    try:
        spring = design_for_device(fit, material=pb.material)
    except BalanceError as exc:
        return SpringDevice(device, None, f"r = {fit.r:.3g} m, c = {fit.c:.4g} N/m; no spring: {exc}"), 0.0
    summary = (f"r = {fit.r:.3g} m, c = {fit.c:.4g} N/m, {pb.material} spring d = {1e3 * spring.wire_diameter_m:.3g} "
               f"mm, {spring.mass_kg:.3g} kg")
    return SpringDevice(device, spring, summary), spring.mass_kg


def _not_planar_chain(arm: ArmModel, terms: Sequence[HarmonicTerm]) -> str | None:
    """Why the terms are not the absolute angles of a planar chain (None when they are)."""
    if any(c.joint == "prismatic" for c in arm.coordinates):
        return ("a slide enters the potential bilinearly (q·sin θ), not as an angle: no zero-free-length spring "
                "on a parallelogram cancels it exactly")
    first = None
    for t in terms:
        f = np.round(np.asarray(t.form), 12)
        idx = np.flatnonzero(f)
        if not (np.all(f[idx] == 1) and np.all(np.diff(idx) == 1)):
            return (f"the term {describe_term(arm, t).form_text} is not the absolute angle of a link of a "
                    "planar chain (a sum q_i + … + q_k of consecutive parallel joints): the joints' axes are not "
                    "all parallel")
        first = idx[0] if first is None else first
        if idx[0] != first:
            return (f"the terms start at different joints (q{first + 1} and q{idx[0] + 1}): the loaded joints do not "
                    "form one planar chain")
    return None


class _PinocchioRecheck:
    """Each strategy's residual recomputed with Pinocchio on a model rebuilt from URDF text, by the
    recursive Newton–Euler algorithm at zero velocity and acceleration (not the generalised-gravity
    routine the arm's own model uses), at random configurations and at the reported worst ones."""

    def __init__(self, solver: _Solver):
        self.s = solver
        n = solver.pb.arm.n
        self.q = solver.lo + (solver.hi - solver.lo) * np.random.default_rng(solver.pb.seed + 1).random((100, n))
        self.models: dict = {}

    def __call__(self, devices, joints, counterweights=()) -> PinocchioRecheck:
        import pinocchio as pin

        s = self.s
        worst = [(j.worst_at, j.worst_payload) for j in joints]
        rows = [(q, p) for q in self.q for p in s.p] + worst
        gaps, at_worst = [], []
        for i, (q, p) in enumerate(rows):
            model, data, config = self._model(p, counterweights)
            x = np.asarray(q, dtype=float)
            tau = np.asarray(pin.rnea(model, data, config(x), np.zeros(model.nv), np.zeros(model.nv)))
            d = devices(x[None])[0]
            r = -tau + (0.0 if counterweights else d)
            mine = s.gravity(x[None], p)[0] + d
            gaps.append(float(np.max(np.abs(r - mine))))
            if i >= len(rows) - len(worst):
                at_worst.append(abs(float(r[i - (len(rows) - len(worst))])))
        return PinocchioRecheck(len(self.q), tuple(s.p), max(gaps), tuple(at_worst), tuple(j.max for j in joints))

    def _model(self, payload: float, counterweights):
        """(model, data, q → configuration) of the arm with ``payload`` kg (and the counterweights)."""
        key = (payload, tuple(counterweights))
        if key not in self.models:
            s, arm = self.s, self.s.pb.arm
            if isinstance(arm, UrdfArm):
                text = _add_masses(_model_to_urdf(arm), "j", [(arm.payload_point[0], arm.payload_point[1], payload)],
                                   "payload")
            else:
                text = arm_to_urdf(arm.with_payload(payload, s.g), s.g)
            link = "j" if isinstance(arm, UrdfArm) else "link"
            text = _add_masses(text, link, [(int(w.coordinate[1:]), w.point, w.mass) for w in counterweights],
                               "counterweight")
            model = pinocchio_model(text, s.g)
            self.models[key] = (model, model.createData(), UrdfArm(model, "recheck").config)
        return self.models[key]


def _model_to_urdf(arm: UrdfArm) -> str:
    """URDF text of a URDF arm's model (joints, placements, axes, inertias), for the independent recheck."""
    import pinocchio as pin

    m = arm.model
    out = ['<robot name="recheck">', '<link name="j0"/>']
    for j in range(1, m.njoints):
        inertia = m.inertias[j]
        c, inner = inertia.lever, inertia.inertia
        out.append(f'<link name="j{j}"><inertial><origin xyz="{_n(c[0])} {_n(c[1])} {_n(c[2])}"/>'
                   f'<mass value="{_n(inertia.mass)}"/><inertia ixx="{_n(inner[0, 0])}" ixy="{_n(inner[0, 1])}" '
                   f'ixz="{_n(inner[0, 2])}" iyy="{_n(inner[1, 1])}" iyz="{_n(inner[1, 2])}" izz="{_n(inner[2, 2])}"/>'
                   '</inertial></link>')
        placement = m.jointPlacements[j]
        t, rpy = placement.translation, pin.rpy.matrixToRpy(placement.rotation)
        coord = arm.coordinates[j - 1]
        axis = _joint_axis(m, j)
        kind = "prismatic" if coord.joint == "prismatic" else "revolute"
        out.append(f'<joint name="q{j}" type="{kind}"><parent link="j{m.parents[j]}"/><child link="j{j}"/>'
                   f'<origin xyz="{_n(t[0])} {_n(t[1])} {_n(t[2])}" rpy="{_n(rpy[0])} {_n(rpy[1])} {_n(rpy[2])}"/>'
                   f'<axis xyz="{_n(axis[0])} {_n(axis[1])} {_n(axis[2])}"/><limit lower="{_n(coord.limits[0])}" '
                   f'upper="{_n(coord.limits[1])}" effort="1" velocity="1"/></joint>')
    out.append("</robot>")
    return "\n".join(out)


def _joint_axis(model, j: int) -> np.ndarray:
    """A joint's axis in its own frame (its motion subspace at the neutral configuration)."""
    import pinocchio as pin

    data = model.createData()
    pin.computeJointJacobians(model, data, pin.neutral(model))
    jac = np.asarray(pin.getJointJacobian(model, data, j, pin.ReferenceFrame.LOCAL)).reshape(6, model.nv)
    col = jac[:, model.joints[j].idx_v]
    v = col[3:] if np.linalg.norm(col[3:]) > 1e-12 else col[:3]
    return v / np.linalg.norm(v)


def _add_masses(text: str, prefix: str, masses, tag: str) -> str:
    """URDF text with point masses ``(joint, (x, y, z), kg)`` on fixed joints to the joints' links
    (named ``tag`` and a number)."""
    rows = []
    for k, (joint, at, mass) in enumerate(masses):
        if mass == 0:
            continue
        rows.append(f'<link name="{tag}{k}"><inertial><origin xyz="{_n(at[0])} {_n(at[1])} {_n(at[2])}"/>'
                    f'<mass value="{_n(mass)}"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
                    f'</inertial></link><joint name="{tag}{k}" type="fixed"><parent link="{prefix}{joint}"/>'
                    f'<child link="{tag}{k}"/></joint>')
    return text.replace("</robot>", "".join(rows) + "</robot>")




def _n(v) -> str:
    """A number as URDF text, to the last digit."""
    return repr(float(v))


# ----------------------------------------------------------------------------- reading
def compare_problem(doc: Mapping[str, Any], source: str = "<compare>",
                    overrides: Mapping[str, Any] | None = None) -> CompareProblem:
    """The :class:`CompareProblem` of a ``[compare]`` table: the one reader of that table.

    Parameters
    ----------
    doc : mapping
        A document with a ``[compare]`` table, whose ``arm`` (a TOML file with ``[arm]`` or a URDF
        file) is relative to the file ``source``; or an arm's own document (an ``[arm]`` table and
        no ``[compare]``, as a URDF file reads ``{"arm": {"urdf": PATH}}``): that arm, compared
        with the default settings.
    source : str
        The file the document was read from (named in every error).
    overrides : mapping, optional
        Settings given elsewhere (the command line's ``--payload``, ``--target`` …) that replace
        the table's; the table is checked as written first.

    Raises
    ------
    SchemaError
        A setting is malformed or unknown (the sentence names the file and the key).

    >>> from pathlib import Path
    >>> from balance.schema import load_toml
    >>> example = str(Path(__file__).parents[2] / "models" / "compare_example1.toml")
    >>> pb = compare_problem(load_toml(example), example, {"target": 0.1})   # --target 0.1 over the file's
    >>> pb.target, pb.payload, pb.arm.n
    (0.1, (0.0, 3.0), 4)
    """
    import os

    from ..schema import load_toml

    if "compare" not in doc:  # the arm's own document: its [arm] table (a TOML arm or a URDF file's)
        t = parse({"compare": {"arm": source, **(overrides or {})}}, "compare", source)
        return compare_from_arm(arm_problem({k: v for k, v in doc.items() if k == "arm"}, source), t, source)
    table = dict(doc["compare"])
    if overrides:
        parse({"compare": dict(table)}, "compare", source)  # the file's own table, checked as written
    t = parse({"compare": {**table, **(overrides or {})}}, "compare", source)
    base = os.path.dirname(source) if os.path.exists(source) else ""
    path = t.arm if os.path.isabs(t.arm) else os.path.join(base, t.arm)
    if path.lower().endswith(".urdf"):
        arm_doc = {"arm": {"urdf": os.path.abspath(path), "name": os.path.basename(path)}}
    else:
        arm_doc = {k: v for k, v in load_toml(path).items() if k == "arm"}
    return compare_from_arm(arm_problem(arm_doc, path), t, source)


def compare_from_arm(problem, t, source: str) -> CompareProblem:
    """A :class:`CompareProblem` for an :class:`~balance.problems.arm.ArmProblem` and a ``[compare]`` table
    (its payload range, when given, replaces the arm's; a TOML arm without a payload load then carries it
    at the end of its last link)."""
    arm = problem.arm
    payload = problem.payload or (0.0, 0.0)
    if t.payload is not None:
        payload = (float(t.payload[0]), float(t.payload[1]))
        if isinstance(arm, Arm) and arm.payload_weight == 0 and payload[1] > 0:
            last = arm.n - 1
            arm = replace(arm, loads=arm.loads + (Load(last, payload[1] * problem.g, arm.links[last].length,
                                                       0.0, True, "payload"),))
    ws = None
    if t.workspace:
        lo, hi = arm.box
        ws = [(float(a), float(b)) for a, b in zip(lo, hi)]
        names = {f"q{i + 1}": i for i in range(arm.n)}
        for key, (a, b) in t.workspace.items():
            if key not in names:
                raise SchemaError(f"{source}: [compare] key 'workspace' names the joint {key!r}; the arm's are "
                                  f"{', '.join(names)}.")
            i = names[key]
            k = 1.0 if arm.coordinates[i].joint == "prismatic" else math.pi / 180
            ws[i] = (a * k, b * k)
    return CompareProblem(arm, payload, None if ws is None else tuple(ws), t.target, t.acceleration,
                          problem.counterweight_arms, samples=t.samples, seed=t.seed, g=problem.g)
