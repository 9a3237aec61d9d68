"""Static balancing of an arm by its potential function: devices, checks, payload.

Each harmonic term ``A_k·cos(φ_k + α_k)`` of the gravity potential gets a spring
device on a shaft turning by ``φ_k`` whose potential is ``−A_k·cos(φ_k + α_k)``; the
device's moment on its shaft is ``−A_k·sin(φ_k + α_k)``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from .arm import Arm, describe_form
from .errors import InvalidInput
from .extremes import EXTREMES_NOTE, box_extremes
from .potential import HarmonicTerm, terms_forces, terms_potential

__all__ = ["CheckResult", "ArmBalance", "balance_arm", "check_terms", "device_table", "prismatic_rows"]


@dataclass(frozen=True)
class CheckResult:
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

    def to_dict(self) -> dict:
        return {
            "samples": self.samples, "seed": self.seed, "max_residual": self.max_residual,
            "max_gravity_force": self.max_gravity_force, "relative_residual": self.relative_residual,
            "potential_spread": self.potential_spread, "per_joint": list(self.per_joint),
            "seconds": self.seconds, "worst": [list(w) for w in self.worst],
            "sampled_max_residual": self.sampled_max_residual, "extremes": EXTREMES_NOTE,
        }


def _box(arm) -> tuple[np.ndarray, np.ndarray]:
    lim = np.array([ln.limits for ln in arm.links], dtype=float)
    return lim[:, 0], lim[:, 1]


def largest_gravity_force(arm, q: np.ndarray) -> float:
    """The largest ``|Q_gravity|`` over the arm's workspace, searched from the configurations ``q``."""
    lo, hi = _box(arm)
    return max(max(-a.value, b.value) for a, b in box_extremes(arm.gravity_forces, lo, hi, q))


def residual_extremes(arm, terms: Sequence[HarmonicTerm], q: np.ndarray, scale: float):
    """Per joint: the (min, max) :class:`~balance.extremes.Extreme` of ``Q_gravity + Q_devices``,
    then those of the total potential (relative to its value at ``q[0]``)."""
    lo, hi = _box(arm)
    ref = float(arm.potential(q[:1])[0] - terms_potential(terms, q[:1])[0])

    def f(x):
        r = arm.gravity_forces(x) - terms_forces(terms, x)
        u = arm.potential(x) - terms_potential(terms, x) - ref
        return np.column_stack([r, u])

    return box_extremes(f, lo, hi, q, floor=1e-11 * scale)


def check_terms(arm: Arm, terms: Sequence[HarmonicTerm], samples: int = 1000, seed: int = 0,
                q: np.ndarray | None = None) -> CheckResult:
    """Residual ``Q_gravity + Q_devices`` over the workspace (always run).

    The ``samples`` random configurations (or ``q``) start a bounded local search for every
    joint's largest residual and gravity force (:mod:`balance.extremes`).

    Examples
    --------
    >>> from balance.arm import Link
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
    ext = residual_extremes(arm, terms, q, mg)
    per = [max(-a.value, b.value) for a, b in ext[:-1]]
    worst = [a.at if -a.value > b.value else b.at for a, b in ext[:-1]]
    sampled = max(max(-a.sampled, b.sampled) for a, b in ext[:-1])
    mr = float(max(per))
    u_lo, u_hi = ext[-1]
    return CheckResult(
        samples=len(q), seed=seed, max_residual=mr, max_gravity_force=mg,
        relative_residual=mr / mg if mg > 0 else (0.0 if mr == 0 else math.inf),
        potential_spread=u_hi.value - u_lo.value,
        per_joint=tuple(float(v) for v in per),
        seconds=time.perf_counter() - t0, worst=tuple(worst), sampled_max_residual=sampled,
    )


def prismatic_rows(arm) -> list[dict]:
    """One row per slide: its gear ratio ``k``, ``γ_max``, the relative error bound of the
    ``γ = q/k`` substitution and the residual bound it gives on every joint (N·m or N)."""
    rows = []
    bounds = [float(v) for v in arm.approx_potential_error_bounds()]
    for i, ln in enumerate(arm.links):
        if ln.joint != "prismatic":
            continue
        gm = (ln.stroke / 2) / ln.gear_ratio
        rows.append({
            "link": ln.name, "coordinate": f"q{i + 1}", "stroke": ln.stroke, "gear_ratio": ln.gear_ratio,
            "gamma_max": gm, "rel_error_bound": 1 - math.sin(gm) / gm,
            "rel_error_bound_gamma2_over_6": gm * gm / 6, "residual_bound_per_joint": bounds,
        })
    return rows


def device_table(arm: Arm, terms: Sequence[HarmonicTerm], options: dict | None = None) -> list[dict]:
    """Spring devices cancelling each term, with their parameters.

    ``options`` may hold ``eccentricity`` (m, sine device: then ``T = A/e``) and
    ``r``, ``r0`` (m, tension crank-and-rocker with zero free length: ``c = A/(r·(r+r0))``).
    """
    options = options or {}
    out = []
    for k, t in enumerate(terms):
        zero = math.degrees(-t.phase)
        dev: dict = {
            "term": k,
            "shaft": describe_form(arm, t.form)["drive_form_text"],
            "moment": f"{-t.amplitude:.6g}·sin(φ{k + 1} {'+' if t.phase >= 0 else '−'} {abs(math.degrees(t.phase)):.6g}°)",
            "sine": {"eT": t.amplitude},
            "tension": {
                "crd": t.amplitude,
                "zero_at_deg": zero,
                "spring_fit": {"kind": "tension", "moment": -t.amplitude, "phi": f"φ{k + 1} + {math.degrees(t.phase):.6g}°"},
            },
            "compression": {
                "spring_fit": {"kind": "compression", "moment": t.amplitude, "phi": f"φ{k + 1} + {math.degrees(t.phase) + 180:.6g}°"},
            },
        }
        e = options.get("eccentricity")
        if e is not None:
            dev["sine"].update({"e": e, "T": t.amplitude / e})
        r, r0 = options.get("r"), options.get("r0")
        if r is not None and r0 is not None:
            dev["tension"].update({"r": r, "r0": r0, "a": r0, "c": t.amplitude / (r * (r + r0))})
        out.append(dev)
    return out


@dataclass
class ArmBalance:
    """Everything :func:`balance_arm` finds for an arm (see :meth:`to_dict`)."""

    arm: Arm
    terms: list[HarmonicTerm]
    devices: list[dict]
    check: CheckResult
    prismatic: list[dict] = field(default_factory=list)
    payload: dict | None = None

    def to_dict(self) -> dict:
        terms = []
        for t in self.terms:
            d = t.to_dict()
            d.update(describe_form(self.arm, t.form))
            terms.append(d)
        return {
            "name": self.arm.name,
            "joints": [
                {"name": ln.name, "coordinate": f"q{i + 1}", "kind": ln.joint}
                for i, ln in enumerate(self.arm.links)
            ],
            "terms": terms,
            "devices": self.devices,
            "max_residual": self.check.max_residual,
            "max_gravity_force": self.check.max_gravity_force,
            "relative_residual": self.check.relative_residual,
            "potential_spread": self.check.potential_spread,
            "check": self.check.to_dict(),
            "prismatic": self.prismatic,
            "payload": self.payload,
        }


def payload_effect(arm: Arm, terms: Sequence[HarmonicTerm], q: np.ndarray, scale: float) -> dict:
    """The worst residual over payloads 0 … max with devices tuned for ``terms``, and the effect
    of half the payload alone. Both are linear in the payload, so their extremes over the range
    are those at 0 and at the maximum; each is a true extreme over the workspace."""
    lo, hi = _box(arm)
    empty, full, half = (arm.with_payload_fraction(f) for f in (0.0, 1.0, 0.5))

    def f(x):
        t = terms_forces(terms, x)
        return np.column_stack([empty.gravity_forces(x) - t, full.gravity_forces(x) - t,
                                half.gravity_forces(x) - empty.gravity_forces(x)])

    ext = box_extremes(f, lo, hi, q, floor=1e-11 * scale)
    mags = np.array([max(-a.value, b.value) for a, b in ext]).reshape(3, arm.n)
    worst = np.maximum(mags[0], mags[1])
    total = sum(ld.weight for ld in arm.loads if ld.payload)
    return {
        "max_payload": total,
        "tuned_for": 0.5 * total,
        "max_residual": float(np.max(worst)),
        "per_joint": [float(v) for v in worst],
        "half_payload_effect": float(np.max(mags[2])),
        "half_payload_effect_per_joint": [float(v) for v in mags[2]],
    }


def balance_arm(arm: Arm, samples: int = 1000, seed: int = 0, device_options: dict | None = None) -> ArmBalance:
    """Harmonic terms, devices and residual check of an arm (payload tuned at half).

    Parameters
    ----------
    arm : Arm
    samples : int
        Random configurations of the residual check (uniform over the joint ranges).
    seed : int
        Seed of the sampler.
    device_options : dict, optional
        See :func:`device_table`.

    Returns
    -------
    ArmBalance

    Examples
    --------
    >>> from balance.arm import Link
    >>> res = balance_arm(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), samples=10)
    >>> res.check.relative_residual < 1e-14
    True
    """
    tuned = arm.with_payload_fraction(0.5)
    terms = tuned.harmonic_terms()
    q = tuned.sample(samples, seed)
    check = check_terms(tuned, terms, q=q, seed=seed)
    bounds = tuned.approx_potential_error_bounds()
    prismatic = prismatic_rows(tuned)
    payload = None
    if any(ld.payload for ld in arm.loads):
        payload = payload_effect(arm, terms, q, check.max_gravity_force)
        payload["approximation_bound_per_joint"] = [float(v) for v in bounds]
    return ArmBalance(tuned, terms, device_table(tuned, terms, device_options), check, prismatic, payload)
