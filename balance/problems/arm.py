"""Static balancing of an arm by its potential function: devices, checks, payload.

Each harmonic term ``A_k·cos(φ_k + α_k)`` of the gravity potential gets a spring device on a
shaft turning by ``φ_k`` whose potential is ``−A_k·cos(φ_k + α_k)``; the device's moment on
its shaft is ``−A_k·sin(φ_k + α_k)``. The problem (:class:`ArmProblem`) is read from an
``[arm]`` table (links and loads, or a URDF file) and solved into an :class:`ArmBalance`: the
terms, the devices, the residual over the workspace (a true extreme), the payload's effect,
the counterweight alternative, Pinocchio's independent check and, on request, the gear trains.

Examples
--------
>>> from balance.model.arm import Arm, Link
>>> res = ArmProblem(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), samples=10).solve()
>>> [round(t.amplitude, 12) for t in res.terms], res.check.relative_residual < 1e-14
([5.0], True)
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field, replace
from typing import Any, Mapping, Sequence

import numpy as np

from mechbase import Row

from ..budget import WORK_LIMIT, ensure_affordable, unit_seconds
from ..devices.counterweights import Counterweights, counterweights
from ..devices.transmission import GearTrain, transmissions
from ..errors import InvalidArm, InvalidInput, SchemaError
from ..extremes import EXTREMES_NOTE, box_extremes
from ..model.arm import Arm, ArmModel, Link, Load, DescribedTerm, base_drives, describe_term, gear_ratio_for_accuracy
from ..model.potential import HarmonicTerm, terms_forces, terms_potential
from ..model.urdf import PinocchioCheck, UrdfArm, load_urdf, pinocchio_check, pinocchio_gravity
from ..schema import ArmTable, check_seed, parse

__all__ = ["ArmProblem", "ArmBalance", "CheckResult", "DeviceSizes", "TermDevices", "SlideApproximation",
           "PayloadEffect", "JointRow", "SpringFitRequest", "SineSizes", "TensionSizes", "CompressionFit", "joint_rows",
           "balance_arm", "check_terms", "arm_from_dict", "arm_problem"]

G = 9.80665


# ------------------------------------------------------------------------------ the check
@dataclass(frozen=True)
class CheckResult(Row):
    """Residual generalised forces of gravity plus devices over the workspace.

    Every maximum is a true one (:mod:`balance.extremes`): the random samples are the starts
    of a bounded local search. ``max_residual`` is in N·m (revolute) or N (prismatic);
    ``relative_residual`` divides it by ``max_gravity_force``, the largest gravity force over
    the workspace. ``potential_spread`` is ``max − min`` of the total potential (J).
    ``worst`` holds, per joint, the configuration of its largest residual.
    """

    samples: int
    seed: int
    max_residual: float
    max_gravity_force: float
    relative_residual: float
    potential_spread: float
    per_joint: tuple[float, ...]
    seconds: float
    worst: tuple[tuple[float, ...], ...] = ()
    sampled_max_residual: float = 0.0
    extremes: str = EXTREMES_NOTE


def largest_gravity_force(arm: ArmModel, q: np.ndarray) -> float:
    """The largest ``|Q_gravity|`` over the arm's workspace, searched from the configurations ``q``."""
    lo, hi = arm.box
    return max(max(-a.value, b.value) for a, b in box_extremes(arm.gravity_forces, lo, hi, q))


def check_terms(arm: ArmModel, terms: Sequence[HarmonicTerm], samples: int = 1000, seed: int = 0,
                q: np.ndarray | None = None) -> CheckResult:
    """Residual ``Q_gravity + Q_devices`` over the workspace (always run).

    The ``samples`` random configurations (or ``q``) start a bounded local search for every
    joint's largest residual and gravity force (:mod:`balance.extremes`).

    Examples
    --------
    >>> arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5),))
    >>> check_terms(arm, arm.harmonic_terms(), samples=50).relative_residual < 1e-14
    True
    """
    if samples < 1:
        raise InvalidInput(f"the check needs at least one sample, not {samples}.")
    t0 = time.perf_counter()
    if q is None:
        q = arm.sample(samples, seed)
    mg = largest_gravity_force(arm, q)
    lo, hi = arm.box
    ref = float(arm.potential(q[:1])[0] - terms_potential(terms, q[:1])[0])

    def f(x):
        r = arm.gravity_forces(x) - terms_forces(terms, x)
        u = arm.potential(x) - terms_potential(terms, x) - ref
        return np.column_stack([r, u])

    ext = box_extremes(f, lo, hi, q, floor=1e-11 * mg)
    per = [max(-a.value, b.value) for a, b in ext[:-1]]
    worst = [a.at if -a.value > b.value else b.at for a, b in ext[:-1]]
    mr = float(max(per))
    u_lo, u_hi = ext[-1]
    return CheckResult(
        samples=len(q), seed=seed, max_residual=mr, max_gravity_force=mg,
        relative_residual=mr / mg if mg > 0 else (0.0 if mr == 0 else math.inf),
        potential_spread=u_hi.value - u_lo.value, per_joint=tuple(float(v) for v in per),
        seconds=time.perf_counter() - t0, worst=tuple(worst),
        sampled_max_residual=max(max(-a.sampled, b.sampled) for a, b in ext[:-1]),
    )


# ---------------------------------------------------------------------------- devices
@dataclass(frozen=True)
class DeviceSizes:
    """Optional sizes of the devices: a sine device's crank eccentricity ``e`` (then ``T = A/e``), a
    tension crank-and-rocker's ``r`` and ``r0`` (then ``c = A/(r·(r + r0))``, ``a = r0``), in m."""

    eccentricity: float | None = None
    r: float | None = None
    r0: float | None = None


@dataclass(frozen=True)
class SpringFitRequest(Row):
    """What ``balance spring`` is asked to fit a spring device to one term: the spring kind, the moment
    amplitude ``Φ0`` (N·m) and the shaft angle ``φ`` the device turns by, as text."""

    kind: str
    moment: float
    phi: str


@dataclass(frozen=True)
class SineSizes(Row):
    """A sine device for amplitude ``A``: ``e·T = A``; with a chosen eccentricity ``e``, ``T = A/e``."""

    eT: float
    e: float | None = None
    T: float | None = None

    row_keys = ("eT", "e?", "T?")


@dataclass(frozen=True)
class TensionSizes(Row):
    """A zero-free-length tension crank-and-rocker for amplitude ``A``: ``c·r·d = A`` with its zero at
    ``zero_at_deg``; with chosen ``r`` and ``r0``, ``a = r0`` and ``c = A/(r·(r + r0))``."""

    crd: float
    zero_at_deg: float
    spring_fit: SpringFitRequest | None = None
    r: float | None = None
    r0: float | None = None
    a: float | None = None
    c: float | None = None

    row_keys = ("crd", "zero_at_deg", "spring_fit?", "r?", "r0?", "a?", "c?")

    @classmethod
    def of(cls, amplitude: float, zero_at_deg: float, r: float | None, r0: float | None,
           spring_fit: SpringFitRequest | None = None) -> "TensionSizes":
        """The device for ``amplitude``, sized when both ``r`` and ``r0`` are given.

        >>> TensionSizes.of(6.0, 90.0, 0.1, 0.5).c
        100.0
        >>> TensionSizes.of(6.0, 90.0, 0.1, None).to_dict()
        {'crd': 6.0, 'zero_at_deg': 90.0}
        """
        if r is None or r0 is None:
            return cls(amplitude, zero_at_deg, spring_fit)
        return cls(amplitude, zero_at_deg, spring_fit, r, r0, r0, amplitude / (r * (r + r0)))


@dataclass(frozen=True)
class CompressionFit(Row):
    """A compression crank-and-rocker for a term: fitted, not exact (the request to fit it)."""

    spring_fit: SpringFitRequest


@dataclass(frozen=True)
class TermDevices(Row):
    """The devices that can cancel one term ``A·cos(φ + α)``: a sine device (``e·T = A``), a
    zero-free-length tension crank-and-rocker (``c·r·d = A``) or a fitted compression one."""

    term: int
    shaft: str
    amplitude: float
    phase: float
    sizes: DeviceSizes = DeviceSizes()

    row_keys = ("term", "shaft", "moment=moment_text", "sine", "tension", "compression")

    @property
    def moment_text(self) -> str:
        """The moment the device applies to its shaft, ``−A·sin(φ + α)``, as text."""
        ph = self.phase
        return f"{-self.amplitude:.6g}·sin(φ{self.term + 1} {'+' if ph >= 0 else '−'} {abs(math.degrees(ph)):.6g}°)"

    @property
    def sine(self) -> SineSizes:
        e = self.sizes.eccentricity
        return SineSizes(self.amplitude) if e is None else SineSizes(self.amplitude, e, self.amplitude / e)

    @property
    def tension(self) -> TensionSizes:
        a, ph = self.amplitude, self.phase
        fit = SpringFitRequest("tension", -a, f"φ{self.term + 1} + {math.degrees(ph):.6g}°")
        return TensionSizes.of(a, math.degrees(-ph), self.sizes.r, self.sizes.r0, fit)

    @property
    def compression(self) -> CompressionFit:
        return CompressionFit(SpringFitRequest("compression", self.amplitude,
                                               f"φ{self.term + 1} + {math.degrees(self.phase) + 180:.6g}°"))


@dataclass(frozen=True)
class SlideApproximation(Row):
    """A slide's ``γ = q/k`` substitution: its gear ratio ``k`` (m/rad), ``γ_max``, the relative
    error bound ``1 − sin γ/γ`` and the residual bound it gives on every joint (N·m or N)."""

    link: str
    coordinate: str
    stroke: float
    gear_ratio: float
    residual_bound_per_joint: tuple[float, ...]

    row_keys = ("link", "coordinate", "stroke", "gear_ratio", "gamma_max", "rel_error_bound",
                "rel_error_bound_gamma2_over_6", "residual_bound_per_joint")

    @property
    def gamma_max(self) -> float:
        return (self.stroke / 2) / self.gear_ratio

    @property
    def rel_error_bound(self) -> float:
        return 1 - math.sin(self.gamma_max) / self.gamma_max

    @property
    def rel_error_bound_gamma2_over_6(self) -> float:
        """The bound ``γ_max²/6`` the gear ratio was chosen by."""
        return self.gamma_max ** 2 / 6


def slide_approximations(arm: ArmModel) -> tuple[SlideApproximation, ...]:
    bounds = tuple(float(v) for v in arm.approx_potential_error_bounds())
    return tuple(SlideApproximation(c.name, f"q{i + 1}", c.stroke, c.gear_ratio, bounds)
                 for i, c in enumerate(arm.coordinates) if c.joint == "prismatic")


@dataclass(frozen=True)
class PayloadEffect(Row):
    """The payload as a range (weights in N): the devices are tuned for ``tuned_for``, the middle of the
    range, which minimises the worst residual (it is the payload's deviation alone, linear in it) — the
    source's "half the maximum payload" when the range starts at 0; the worst residual over the range
    and the effect of the payload's half-range, per joint (true extremes)."""

    max_payload: float
    min_payload: float
    tuned_for: float
    per_joint: tuple[float, ...]
    half_payload_effect_per_joint: tuple[float, ...]
    approximation_bound_per_joint: tuple[float, ...]
    g: float = G

    row_keys = ("max_payload", "min_payload", "tuned_for", "mass_range_kg", "max_residual", "per_joint",
                "half_payload_effect", "half_payload_effect_per_joint", "approximation_bound_per_joint")

    @property
    def mass_range_kg(self) -> tuple[float, float]:
        return self.min_payload / self.g, self.max_payload / self.g

    @property
    def max_residual(self) -> float:
        return max(self.per_joint)

    @property
    def half_payload_effect(self) -> float:
        return max(self.half_payload_effect_per_joint)



def payload_effect(arm: ArmModel, terms: Sequence[HarmonicTerm], q: np.ndarray, scale: float,
                   payload: tuple[float, float], g: float = G) -> PayloadEffect:
    """The worst residual over the payload range (kg) with devices tuned for ``terms``, and the effect of
    half the range alone. Both are linear in the payload, so their extremes over the range are those
    at its ends; each is a true extreme over the workspace."""
    lo, hi = arm.box
    low, high = arm.with_payload(payload[0], g), arm.with_payload(payload[1], g)
    mid = arm.with_payload(0.5 * (payload[0] + payload[1]), g)

    def f(x):
        t = terms_forces(terms, x)
        return np.column_stack([low.gravity_forces(x) - t, high.gravity_forces(x) - t,
                                mid.gravity_forces(x) - low.gravity_forces(x)])

    ext = box_extremes(f, lo, hi, q, floor=1e-11 * scale)
    mags = np.array([max(-a.value, b.value) for a, b in ext]).reshape(3, arm.n)
    return PayloadEffect(payload[1] * g, payload[0] * g, 0.5 * (payload[0] + payload[1]) * g,
                         tuple(float(v) for v in np.maximum(mags[0], mags[1])), tuple(float(v) for v in mags[2]),
                         tuple(float(v) for v in mid.approx_potential_error_bounds()), g)


# ---------------------------------------------------------------------------- the problem
@dataclass(frozen=True)
class JointRow(Row):
    """A joint of an arm as a result lists it: its name, its coordinate ``q1, q2, …`` and its kind."""

    name: str
    coordinate: str
    kind: str


def joint_rows(arm: ArmModel, row: type[JointRow] = JointRow) -> tuple[JointRow, ...]:
    """The arm's joints, in order, as rows (of the class ``row``).

    >>> joint_rows(Arm((Link("upper", "revolute", 1.0, 10.0, 0.5),)))[0].to_dict()
    {'name': 'upper', 'coordinate': 'q1', 'kind': 'revolute'}
    """
    return tuple(row(c.name, f"q{i + 1}", c.joint) for i, c in enumerate(arm.coordinates))


@dataclass(frozen=True)
class ArmBalance(Row):
    """Everything :class:`ArmProblem` finds for an arm (its row, :meth:`to_dict`, is the JSON).

    ``arm`` is the arm as balanced (its payload at the tuned value), ``terms`` the harmonic terms
    the devices cancel, ``devices`` one :class:`TermDevices` per term.
    """

    arm: ArmModel
    terms: tuple[HarmonicTerm, ...]
    devices: tuple[TermDevices, ...]
    check: CheckResult
    slides: tuple[SlideApproximation, ...]
    payload: PayloadEffect | None
    counterweights: Counterweights
    pinocchio: PinocchioCheck
    transmission: tuple[GearTrain, ...] | None = None
    urdf: str | None = None
    full_payload: ArmModel | None = field(default=None, repr=False)  # the arm at its largest payload (plots)
    empty: ArmModel | None = field(default=None, repr=False)  # and at its smallest

    row_keys = ("name", "joints", "terms=described_terms", "devices", "max_residual", "max_gravity_force",
                "relative_residual", "potential_spread", "check", "prismatic=slides", "payload", "counterweights",
                "pinocchio", "kind", "urdf?", "transmission?")
    kind = "arm"

    @property
    def name(self) -> str:
        return self.arm.name

    @property
    def joints(self) -> tuple[JointRow, ...]:
        return joint_rows(self.arm)

    @property
    def described_terms(self) -> tuple[DescribedTerm, ...]:
        """The terms with their forms written out over the joints and the drive shafts."""
        return tuple(describe_term(self.arm, t) for t in self.terms)

    @property
    def max_residual(self) -> float:
        return self.check.max_residual

    @property
    def max_gravity_force(self) -> float:
        return self.check.max_gravity_force

    @property
    def relative_residual(self) -> float:
        return self.check.relative_residual

    @property
    def potential_spread(self) -> float:
        return self.check.potential_spread


@dataclass(frozen=True)
class ArmProblem:
    """An arm to balance and how to check it.

    Attributes
    ----------
    arm : ArmModel
        A TOML :class:`~balance.model.arm.Arm` or a :class:`~balance.model.urdf.UrdfArm`.
    samples, seed : int
        Random configurations (seeded) that start the searches for the largest residuals.
    devices : DeviceSizes
    counterweight_arms : mapping of int to float
        Distance from each joint's axis of its counterweight (m); others: half the link.
    transmission : bool
        Design the gear trains forming each device shaft.
    g : float
        Gravity (m/s²) of the Pinocchio model written for a TOML arm.
    urdf : str or None
        The URDF file the arm was read from.
    payload : (float, float) or None
        The payload range (kg); the devices are tuned for its middle. None: a TOML arm's payload loads
        (``payload=True``) carry the largest, from 0; no payload otherwise.
    work_limit : float or None
        Seconds of estimated work allowed (:mod:`balance.budget`); None lifts the limit.
    """

    arm: ArmModel
    samples: int = 1000
    seed: int = 0
    devices: DeviceSizes = DeviceSizes()
    counterweight_arms: Mapping[int, float] = field(default_factory=dict)
    transmission: bool = False
    g: float = G
    urdf: str | None = None
    payload: tuple[float, float] | None = None
    work_limit: float | None = WORK_LIMIT

    def solve(self) -> ArmBalance:
        """Terms, devices, residual over the workspace, payload, counterweights, Pinocchio's check."""
        if self.samples < 1:
            raise InvalidInput(f"the check needs at least one sample, not {self.samples}.")
        check_seed(self.seed)
        arm = self.arm
        payload = self.payload
        if payload is None and isinstance(arm, Arm) and arm.payload_weight > 0:
            payload = (0.0, arm.payload_weight / self.g)  # payload loads carry the largest payload
        if payload is not None and not (math.isfinite(payload[0]) and math.isfinite(payload[1])
                                        and 0 <= payload[0] <= payload[1]):
            raise InvalidInput(f"the payload range must be finite with 0 ≤ low ≤ high, not {payload[0]:g} .. "
                               f"{payload[1]:g} kg.")
        tuned = arm.with_payload(0.5 * (payload[0] + payload[1]), self.g) if payload else arm
        own = tuned.sample(16, self.seed)
        pin_arm = pinocchio_gravity(tuned, self.g)
        passes = 8 if payload else 5

        def unit():  # one configuration through every pass: the arm's own model, then Pinocchio's
            for _ in range(passes):
                tuned.gravity_forces(own)
            pin_arm.gravity_forces(own)  # the counterweights' check
            pin_arm.gravity_forces(own)  # and Pinocchio's

        ensure_affordable(f"checking {self.samples} configurations", self.samples, unit, self.work_limit, per=len(own))
        if isinstance(tuned, UrdfArm):
            tuned.ensure_decomposable(self.work_limit)
            _ensure_terms_affordable(tuned, own, self.samples, self.work_limit)
        terms = tuple(tuned.harmonic_terms())
        q = tuned.sample(self.samples, self.seed)
        check = check_terms(tuned, terms, q=q, seed=self.seed)
        effect = None
        if payload:
            effect = payload_effect(arm, terms, q, check.max_gravity_force, payload, self.g)
        cw = counterweights(tuned, dict(self.counterweight_arms), self.samples, self.seed, self.g)
        pc = pinocchio_check(tuned, terms, self.samples, self.seed, self.g, worst=check.worst,
                             scale=check.max_gravity_force)
        trains = None
        if self.transmission:
            forms = [describe_term(tuned, t).drive_form for t in terms]
            trains = tuple(transmissions(forms, tuned.shaft_names))
        devices = tuple(TermDevices(k, describe_term(tuned, t).drive_form_text, t.amplitude, t.phase,
                                    self.devices) for k, t in enumerate(terms))
        return ArmBalance(tuned, terms, devices, check, slide_approximations(tuned), effect, cw, pc, trains,
                          self.urdf, arm.with_payload(payload[1], self.g) if payload else None,
                          arm.with_payload(payload[0], self.g) if payload else None)


def _ensure_terms_affordable(arm: UrdfArm, own: np.ndarray, samples: int, limit: float | None) -> None:
    """Refuse an arm whose harmonic terms would cost more than ``limit`` seconds downstream: a URDF arm
    of n joints has up to (3ⁿ + 1)/2 terms (a 12-joint arm: 265 721), each evaluated at every
    configuration the checks visit (about two per sample: the residual search, Pinocchio's check)
    and described in the report."""
    passes = 2
    most = (3 ** arm.n + 1) // 2
    probe = [HarmonicTerm(1.0, 0.5, tuple(float(x) for x in np.resize((1, -1, 0), arm.n))) for _ in range(8)]
    per_value = unit_seconds(lambda: (terms_forces(probe, own), terms_potential(probe, own))) / (len(probe) * len(own))
    per_text = unit_seconds(lambda: [describe_term(arm, t) for t in probe]) / len(probe)
    ensure_affordable(f"checking {samples} configurations against up to {most} harmonic terms", most,
                      passes * samples * per_value + 2 * per_text, limit)


def balance_arm(arm: ArmModel, samples: int = 1000, seed: int = 0, **options) -> ArmBalance:
    """Harmonic terms, devices and the checks of an arm (payload tuned at half): :class:`ArmProblem`.

    Examples
    --------
    >>> res = balance_arm(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), samples=10)
    >>> res.check.relative_residual < 1e-14
    True
    """
    return ArmProblem(arm, samples, seed, **options).solve()


# ------------------------------------------------------------------------- reading [arm]
def arm_problem(doc: Mapping[str, Any], source: str = "<arm>") -> ArmProblem:
    """The :class:`ArmProblem` of a parsed TOML document with an ``[arm]`` table (links or a URDF file).

    Examples
    --------
    >>> arm_problem({"arm": {"links": [{"joint": "revolute", "length": 1, "weight": 2}]}}).arm.links[0].com
    0.5
    """
    t = parse(doc, "arm", source)
    d = t.devices
    common = dict(samples=t.check.samples, seed=t.check.seed, devices=DeviceSizes(d.eccentricity, d.r, d.r0),
                  transmission=t.transmission, g=t.g)
    if t.urdf is not None:
        if t.links or t.loads:
            raise SchemaError(f"{source}: [arm] takes its links from 'urdf'; remove [[arm.links]] and [[arm.loads]].")
        base = os.path.dirname(source) if os.path.exists(source) else ""
        path = t.urdf if os.path.isabs(t.urdf) else os.path.join(base, t.urdf)
        arm = load_urdf(path, accuracy=t.accuracy, g=t.g, name=t.name if t.name != "arm" else None)
        if t.drives != "joint":
            try:
                drives = base_drives(arm.n) if t.drives == "base" else t.drives
                arm = UrdfArm(arm.model, arm.name, arm.accuracy, drives)
            except (InvalidArm, ValueError):
                raise SchemaError(f"{source}: [arm] key 'drives' must be a non-singular {arm.n}×{arm.n} matrix "
                                  "for this URDF arm.") from None
        cw = {} if t.counterweights.arm is None else {j: t.counterweights.arm for j in range(arm.n)}
        payload = None
        if t.payload is not None:
            pl = t.payload
            if isinstance(pl.at, float):
                raise SchemaError(f"{source}: [arm.payload] key 'at' must be [x, y, z] (m, in the link's frame) for "
                                  "a URDF arm.")
            try:
                arm = arm.with_payload_at(pl.link, pl.at or (0.0, 0.0, 0.0))
            except InvalidArm as exc:
                raise InvalidArm(f"{source}: [arm.payload] {exc}") from None
            payload = _payload_range(pl, t.g, source)
        return ArmProblem(arm, counterweight_arms=cw, urdf=path, payload=payload, **common)
    arm = arm_from_table(t, source)
    cw = {}
    for i, ln in enumerate(t.links):
        b = ln.counterweight_arm if ln.counterweight_arm is not None else t.counterweights.arm
        if b is not None:
            cw[i] = b
    payload = (0.0, arm.payload_weight / t.g) if arm.payload_weight > 0 else None
    if t.payload is not None:
        if arm.payload_weight > 0:
            raise SchemaError(f"{source}: give the payload either as [arm.payload] or as [[arm.loads]] with payload = "
                              "true, not both.")
        pl = t.payload
        payload = _payload_range(pl, t.g, source)
        if isinstance(pl.at, list):
            raise SchemaError(f"{source}: [arm.payload] key 'at' must be a number (m along the link) for a TOML arm.")
        names = [ln.name for ln in arm.links]
        link = names.index(pl.link) if pl.link in names else len(names) - 1
        if pl.link is not None and pl.link not in names:
            raise SchemaError(f"{source}: [arm.payload] key 'link' names no link: {pl.link!r} (links: "
                              f"{', '.join(names)}).")
        at = arm.links[link].length if pl.at is None else pl.at
        if payload[1] > 0:
            arm = replace(arm, loads=arm.loads + (Load(link, payload[1] * t.g, at, 0.0, True, "payload"),))
    return ArmProblem(arm, counterweight_arms=cw, payload=payload, **common)


def _payload_range(pl, g: float, source: str) -> tuple[float, float]:
    """``[arm.payload]``'s mass (kg) or weight (N) range, in kg."""
    if (pl.mass is None) == (pl.weight is None):
        raise SchemaError(f"{source}: [arm.payload] needs either the key 'mass' = [low, high] (kg) or 'weight' "
                          "(N), not both or neither.")
    lo, hi = pl.mass if pl.mass is not None else (w / g for w in pl.weight)
    if not 0 <= lo <= hi:
        raise SchemaError(f"{source}: [arm.payload] range {lo:g} .. {hi:g} kg must have 0 ≤ low ≤ high.")
    return float(lo), float(hi)


def arm_from_dict(doc: Mapping[str, Any], source: str = "<arm>") -> Arm:
    """The :class:`~balance.model.arm.Arm` of an ``[arm]`` document with links (not URDF).

    Examples
    --------
    >>> doc = {"arm": {"zero": "vertical", "links": [{"joint": "revolute", "length": 1, "weight": 2}]}}
    >>> arm_from_dict(doc).links[0].com
    0.5
    """
    t = parse(doc, "arm", source)
    if t.urdf is not None:
        raise SchemaError(f"{source}: [arm] reads its links from 'urdf'; use balance.model.urdf.load_urdf to load it.")
    return arm_from_table(t, source)


def arm_from_table(a: ArmTable, source: str = "<arm>") -> Arm:
    """An :class:`~balance.model.arm.Arm` from a validated ``[arm]`` table."""
    if not a.links:
        raise SchemaError(f"{source}: [arm] needs at least one [[arm.links]] table (or the key 'urdf').")
    links: list[Link] = []
    names: dict[str, int] = {}
    for i, t in enumerate(a.links):
        name = t.name if t.name is not None else f"link{i + 1}"
        where = f"[[arm.links]] #{i + 1}"
        if name in names:
            raise SchemaError(f"{source}: {where} repeats the name '{name}' of [[arm.links]] #{names[name] + 1}.")
        names[name] = i
        weight = _weight(t, where, source, a.g)
        com = t.length / 2 if t.com is None else t.com
        off = math.radians(t.offset_deg)
        k = 0.0
        if t.joint == "prismatic":
            if not t.stroke > 0:
                raise InvalidArm(f"{source}: {where} is prismatic and needs a positive 'stroke' (m).")
            rng = tuple(t.range) if t.range is not None else None  # None: the whole stroke (Link.limits)
            if t.gear_ratio is not None:
                k = t.gear_ratio
            else:
                k = gear_ratio_for_accuracy(t.stroke, a.accuracy if t.accuracy is None else t.accuracy)
        else:
            if t.range is not None:
                raise SchemaError(f"{source}: {where} is {t.joint}: give its range as 'range_deg'.")
            rd = t.range_deg if t.range_deg is not None else (-180.0, 180.0)
            rng = (math.radians(rd[0]), math.radians(rd[1]))
        links.append(Link(name, t.joint, t.length, weight, com, t.com_lateral, off, rng, t.stroke, k))
    loads: list[Load] = []
    for i, t in enumerate(a.loads):
        where = f"[[arm.loads]] #{i + 1}"
        link = t.link if t.link is not None else links[-1].name
        if link not in names:
            raise SchemaError(f"{source}: {where} key 'link' names no link: {link!r} (links: {', '.join(names)}).")
        li = names[link]
        at = links[li].length if t.at is None else t.at
        name = t.name if t.name is not None else f"load{i + 1}"
        loads.append(Load(li, _weight(t, where, source, a.g), at, t.lateral, t.payload, name))
    try:
        drives = None if a.drives == "joint" else base_drives(len(links)) if a.drives == "base" else \
            tuple(tuple(row) for row in a.drives)
        return Arm(tuple(links), tuple(loads), a.zero, drives, a.name)
    except InvalidArm as exc:
        raise InvalidArm(f"{source}: {exc}") from None


def _weight(t: Any, where: str, source: str, g: float) -> float:
    if t.weight is not None and t.mass is not None:
        raise SchemaError(f"{source}: {where} gives both 'weight' (N) and 'mass' (kg); keep one.")
    if t.mass is not None:
        return t.mass * g
    return 0.0 if t.weight is None else t.weight
