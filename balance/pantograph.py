"""Balanced manipulator with a pantograph (docs/theory.md; balancing textbook, Fig. 6.6).

Geometry (angles from the horizontal, ``A`` the fixed pivot at the origin):

- upper arm (link 2) ``A→D``, length ``l2``, angle ``θ2``;
- forearm (link 3) ``D→C``, length ``l3``, angle ``θ3``; ``C`` carries the tool and payload;
- bar ``E→B`` parallel to the forearm, ``E`` on the upper arm at ``l2/k`` from ``A``, length ``l3/k``;
- bar ``F→B`` parallel to the upper arm, ``F`` on the forearm at ``l3/k`` from ``D``.

Then ``A``, ``B``, ``C`` are collinear and ``C − A = k·(B − A)``: the driven point ``B`` and
the output ``C`` move similarly with ratio ``k``. A vertical drive at ``B`` holds its
height; ``B`` moves freely sideways.

Each link's weight is replaced by point weights at its joints (substitution points);
after moving the weights at ``E`` and ``F`` to the ends of their links, only ``A``, ``D``,
``B`` and ``C`` carry weight. With ``y_B`` held, ``y_C = k·y_B`` is held too, and the
potential that remains is ``W_D·l2·sin θ2``: one crank spring device on the upper arm
balances it, and the drive carries the constant force ``W_B + k·W_C``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from ._schema import check_keys, check_top_level, get_number, get_range
from .errors import InvalidArm, SchemaError
from .potential import HarmonicTerm

__all__ = ["Pantograph", "pantograph_from_dict", "balance_pantograph"]


@dataclass(frozen=True)
class Pantograph:
    """A pantograph manipulator (SI units, weights in N). See the module docstring.

    Examples
    --------
    >>> p = Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0)
    >>> round(p.point_weights()["D"], 9)
    50.0
    """

    l2: float
    l3: float
    k: float
    w2: float = 0.0
    w3: float = 0.0
    w_eb: float = 0.0
    w_fb: float = 0.0
    s2: float | None = None
    s3: float | None = None
    tool: float = 0.0
    payload: float = 0.0
    range2: tuple[float, float] = (math.radians(-60), math.radians(80))
    range3: tuple[float, float] = (math.radians(-80), math.radians(60))

    def __post_init__(self) -> None:
        for name in ("l2", "l3"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InvalidArm(f"the pantograph length {name} must be positive, not {v}.")
        if not (math.isfinite(self.k) and self.k > 1):
            raise InvalidArm(f"the pantograph ratio k = AC/AB must exceed 1, not {self.k}.")
        for name in ("w2", "w3", "w_eb", "w_fb", "tool", "payload"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InvalidArm(f"the pantograph weight {name} must be a finite number ≥ 0, not {v}.")
        for rng in (self.range2, self.range3):
            if not (math.isfinite(rng[0]) and math.isfinite(rng[1]) and rng[0] < rng[1]):
                raise InvalidArm(f"a pantograph angle range must be finite with low < high, not {rng}.")

    @property
    def e(self) -> float:
        return self.l2 / self.k

    @property
    def g(self) -> float:
        return self.l3 / self.k

    def _s2(self) -> float:
        return self.l2 / 2 if self.s2 is None else self.s2

    def _s3(self) -> float:
        return self.l3 / 2 if self.s3 is None else self.s3

    def point_weights(self, payload_fraction: float = 0.5) -> dict[str, float]:
        """Substitution weights at ``A``, ``D``, ``B``, ``C`` (N)."""
        k, l2, l3 = self.k, self.l2, self.l3
        s2, s3 = self._s2(), self._s3()
        wa = self.w2 * (1 - s2 / l2)
        wd = self.w2 * s2 / l2 + self.w3 * (1 - s3 / l3)
        wc = self.w3 * s3 / l3 + self.tool + payload_fraction * self.payload
        wb = 0.5 * self.w_eb + 0.5 * self.w_fb
        we, wf = 0.5 * self.w_eb, 0.5 * self.w_fb  # bars' centres at mid-length
        wa += we * (1 - 1 / k)
        wd += we / k + wf * (1 - 1 / k)
        wc += wf / k
        return {"A": wa, "D": wd, "B": wb, "C": wc}

    def height_coefficients(self, payload_fraction: float = 0.5) -> list[tuple[float, float, float]]:
        """Direct model (no substitution): ``(weight, a, b)`` with height ``a·sin θ2 + b·sin θ3``."""
        l2, l3, e, g = self.l2, self.l3, self.e, self.g
        return [
            (self.w2, self._s2(), 0.0),
            (self.w3, l2, self._s3()),
            (self.w_eb, e, g / 2),
            (self.w_fb, (l2 + e) / 2, g),
            (self.tool + payload_fraction * self.payload, l2, l3),
        ]

    def gravity_forces(self, th: np.ndarray, payload_fraction: float = 0.5) -> np.ndarray:
        """Exact ``−∂U/∂(θ2, θ3)`` from the links' own centres of mass, shape (m, 2)."""
        th = np.atleast_2d(th)
        out = np.zeros_like(th)
        for w, a, b in self.height_coefficients(payload_fraction):
            out[:, 0] -= w * a * np.cos(th[:, 0])
            out[:, 1] -= w * b * np.cos(th[:, 1])
        return out

    def term(self) -> HarmonicTerm:
        """The one harmonic term the spring cancels: ``W_D·l2·cos(θ2 − 90°)``."""
        return HarmonicTerm(self.point_weights()["D"] * self.l2, -math.pi / 2, (1.0, 0.0))

    def drive_force(self, payload_fraction: float = 0.5) -> float:
        """Vertical force the drive at ``B`` carries: ``W_B + k·W_C`` (N), the same everywhere."""
        w = self.point_weights(payload_fraction)
        return w["B"] + self.k * w["C"]


def balance_pantograph(p: Pantograph, samples: int = 1000, seed: int = 0, r: float | None = None,
                       r0: float | None = None) -> dict:
    """Spring device, drive force and residual check of a pantograph manipulator.

    The check: at random ``(θ2, θ3)`` the generalised forces of gravity (direct model),
    of the spring and of the constant drive force at ``B`` must cancel, i.e. with the
    drive holding ``y_B`` the manipulator is in neutral equilibrium.

    Examples
    --------
    >>> out = balance_pantograph(Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0, tool=20.0), samples=50)
    >>> out["relative_residual"] < 1e-12
    True
    """
    rng = np.random.default_rng(seed)
    lo = np.array([p.range2[0], p.range3[0]])
    hi = np.array([p.range2[1], p.range3[1]])
    th = lo + (hi - lo) * rng.random((samples, 2))
    t = p.term()
    jb = np.stack([p.e * np.cos(th[:, 0]), p.g * np.cos(th[:, 1])], axis=1)  # ∂y_B/∂θ
    out_rows = {}
    worst = 0.0
    for frac in (0.0, 0.5, 1.0):
        qg = p.gravity_forces(th, frac)
        q_spring = np.zeros_like(th)
        q_spring[:, 0] = t.moment(th[:, 0])
        q_drive = p.drive_force(frac) * jb
        res = qg + q_spring + q_drive
        out_rows[frac] = float(np.max(np.abs(res)))
        worst = max(worst, out_rows[frac])
    mg = float(np.max(np.abs(p.gravity_forces(th, 0.5))))
    dev = {"sine": {"eT": t.amplitude}, "tension": {"crd": t.amplitude, "zero_at_deg": 90.0}}
    if r is not None and r0 is not None:
        dev["tension"].update({"r": r, "r0": r0, "a": r0, "c": t.amplitude / (r * (r + r0))})
    return {
        "point_weights": p.point_weights(0.5),
        "point_weights_without_payload": p.point_weights(0.0),
        "term": t.to_dict() | {"form_text": "θ2"},
        "device": dev,
        "spring_moment": f"{t.amplitude:.6g}·cos θ2 on the upper arm (base point C above A)",
        "drive_force": p.drive_force(0.5),
        "drive_force_range": [p.drive_force(0.0), p.drive_force(1.0)],
        "max_residual": worst,
        "residual_by_payload": {str(k): v for k, v in out_rows.items()},
        "max_gravity_force": mg,
        "relative_residual": worst / mg if mg > 0 else 0.0,
        "samples": samples,
        "seed": seed,
        "note": "the payload sits at C, so it changes only the drive force, never the spring",
    }


_KEYS = {"l2", "l3", "ratio", "upper", "forearm", "bar_eb", "bar_fb", "tool", "payload",
         "range_upper_deg", "range_forearm_deg", "spring", "check"}


def pantograph_from_dict(doc: Mapping[str, Any], source: str = "<pantograph>") -> tuple[Pantograph, dict]:
    """Parse a ``[pantograph]`` document; returns the model and options (spring, check)."""
    t = check_top_level(doc, "pantograph", source)
    check_keys(t, _KEYS, "[pantograph]", source)
    w = "[pantograph]"

    def link(name: str) -> tuple[float, float | None]:
        sub = t.get(name, {})
        if not isinstance(sub, Mapping):
            raise SchemaError(f"{source}: [pantograph.{name}] must be a table.")
        check_keys(sub, {"weight", "com"}, f"[pantograph.{name}]", source)
        return (get_number(sub, "weight", f"[pantograph.{name}]", source, default=0.0),
                get_number(sub, "com", f"[pantograph.{name}]", source, default=None))

    w2, s2 = link("upper")
    w3, s3 = link("forearm")
    web, _ = link("bar_eb")
    wfb, _ = link("bar_fb")
    r2 = get_range(t, "range_upper_deg", w, source, default=(-60.0, 80.0))
    r3 = get_range(t, "range_forearm_deg", w, source, default=(-80.0, 60.0))
    p = Pantograph(
        l2=get_number(t, "l2", w, source, required=True),
        l3=get_number(t, "l3", w, source, required=True),
        k=get_number(t, "ratio", w, source, required=True),
        w2=w2, w3=w3, w_eb=web, w_fb=wfb, s2=s2, s3=s3,
        tool=get_number(t, "tool", w, source, default=0.0),
        payload=get_number(t, "payload", w, source, default=0.0),
        range2=(math.radians(r2[0]), math.radians(r2[1])),
        range3=(math.radians(r3[0]), math.radians(r3[1])),
    )
    opts: dict = {}
    sp = t.get("spring", {})
    check_keys(sp, {"r", "r0"}, "[pantograph.spring]", source)
    opts["r"] = get_number(sp, "r", "[pantograph.spring]", source)
    opts["r0"] = get_number(sp, "r0", "[pantograph.spring]", source)
    ck = t.get("check", {})
    check_keys(ck, {"samples", "seed"}, "[pantograph.check]", source)
    opts["samples"] = int(get_number(ck, "samples", "[pantograph.check]", source, default=1000))
    opts["seed"] = int(get_number(ck, "seed", "[pantograph.check]", source, default=0))
    return p, opts
