"""Balanced manipulator with a pantograph: the mechanism, its spring and its lifting cylinder.

Links are numbered as in the textbook figure this follows (see ``docs/theory.md``).
Angles are measured from the horizontal; ``A`` is the fixed pivot at the origin:

- upper arm **2** ``A→D`` (length ``l2``, angle ``θ2``) and forearm **3** ``D→C`` (``l3``,
  ``θ3``); ``C`` carries the wrist, tool and payload;
- pantograph bars **9** ``E→B`` parallel to the forearm (``E`` on link 2 at ``l2/k`` from
  ``A``, length ``l3/k``) and **8** ``F→B`` parallel to the upper arm (``F`` on link 3 at
  ``l3/k`` from ``D``): ``A``, ``B``, ``C`` stay on one line with ``C − A = k·(B − A)``,
  ``k = l3/|EB|`` the similarity ratio;
- parallelograms **1-2-14-16** and **16-3-4-15** (bars 14, 15 at a vertical offset below
  links 2, 3; the elbow plate 16 and the wrist plate 4 translate, so the gripper keeps its
  orientation);
- the hydraulic cylinder **10** from the frame pivot ``P`` to the driving point ``B``;
- the spring device **13** on link 2 at ``A``.

Each link's weight is replaced by point weights at its joints (substitution points);
after moving the weights at ``E``, ``F`` and the parallelogram joints to the ends of the
links that carry them, only ``A``, ``D``, ``B`` and ``C`` carry weight (``W_A … W_C``).
With the cylinder holding ``B`` the potential that remains is ``W_D·l2·sin θ2``: the
spring device cancels it exactly (``W_D·l2·cos θ2`` on link 2). The cylinder's force
depends on the configuration: the moment of ``W_B`` and ``W_C`` about ``A`` divided by
the cylinder's lever arm about ``A``,

    F = (W_B·x_B + W_C·x_C) / ((B − A) × u),   u = (B − P)/|B − P|,

and what the cylinder's line of action cannot hold along ``A→C`` the operator holds at
the handle: ``R = (W·sin β − F·u·b̂)/k`` with ``W = W_B + k·W_C`` and ``b̂`` the unit
vector ``A→B`` at angle ``β``. Both follow from virtual work (a rotation of the whole
pantograph about ``A`` and a stretch along ``A→C``); :func:`virtual_work_forces` solves
the same equilibrium from the links' own centres of mass as the independent check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidArm
from .potential import HarmonicTerm

__all__ = ["Pantograph", "virtual_work_forces", "stroke_gradients", "PAYLOADS"]

PAYLOADS = (0.0, 0.5, 1.0)


@dataclass(frozen=True)
class Pantograph:
    """A pantograph manipulator (SI units, weights in N). See the module docstring.

    ``w8``/``w9``: pantograph bars F→B and E→B; ``w14``/``w15``: each parallelogram bar;
    ``w16``/``w4``: elbow and wrist plates; ``offset``: the parallelograms' vertical side
    (m); ``base``: the cylinder's frame pivot ``P`` relative to ``A`` (default below ``B``
    at mid-range, ``2·l2`` lower).

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
    w9: float = 0.0
    w8: float = 0.0
    w14: float = 0.0
    w15: float = 0.0
    w16: float = 0.0
    w4: float = 0.0
    s2: float | None = None
    s3: float | None = None
    tool: float = 0.0
    payload: float = 0.0
    offset: float = 0.15
    base: tuple[float, float] | None = None
    range2: tuple[float, float] = (math.radians(-60), math.radians(80))
    range3: tuple[float, float] = (math.radians(-80), math.radians(60))

    def __post_init__(self) -> None:
        for name in ("l2", "l3", "offset"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InvalidArm(f"the pantograph length {name} must be positive, not {v}.")
        if not (math.isfinite(self.k) and self.k > 1):
            raise InvalidArm(f"the pantograph ratio k = AC/AB must exceed 1, not {self.k}.")
        for name in ("w2", "w3", "w9", "w8", "w14", "w15", "w16", "w4", "tool", "payload"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InvalidArm(f"the pantograph weight {name} must be a finite number ≥ 0, not {v}.")
        for name, rng in (("upper arm's (θ2)", self.range2), ("forearm's (θ3)", self.range3)):
            if not (math.isfinite(rng[0]) and math.isfinite(rng[1]) and rng[0] < rng[1]):  # said in degrees, as given
                raise InvalidArm(f"the pantograph's {name} angle range must be finite with low < high, not "
                                 f"{math.degrees(rng[0]):g}° .. {math.degrees(rng[1]):g}°.")

    # ------------------------------------------------------------------ geometry
    @property
    def e(self) -> float:
        """``|AE| = l2/k``."""
        return self.l2 / self.k

    @property
    def g(self) -> float:
        """``|EB| = |DF| = l3/k`` (link 9)."""
        return self.l3 / self.k

    def _s2(self) -> float:
        return self.l2 / 2 if self.s2 is None else self.s2

    def _s3(self) -> float:
        return self.l3 / 2 if self.s3 is None else self.s3

    @property
    def cylinder_base(self) -> np.ndarray:
        """Frame pivot ``P`` of the cylinder (m, relative to ``A``)."""
        if self.base is not None:
            return np.asarray(self.base, dtype=float)
        t2 = 0.5 * (self.range2[0] + self.range2[1])
        t3 = 0.5 * (self.range3[0] + self.range3[1])
        b = self.points(np.array([[t2, t3]]))["B"][0]
        return np.array([b[0], b[1] - 2 * self.l2])

    def sample(self, count: int, seed: int = 0) -> np.ndarray:
        """``count`` configurations ``(θ2, θ3)`` drawn uniformly from the ranges."""
        rng = np.random.default_rng(seed)
        lo = np.array([self.range2[0], self.range3[0]])
        hi = np.array([self.range2[1], self.range3[1]])
        return lo + (hi - lo) * rng.random((count, 2))

    def points(self, th: np.ndarray) -> dict[str, np.ndarray]:
        """Joint points at configurations ``th`` (m, 2): each an (m, 2) array."""
        th = np.atleast_2d(th)
        u2 = np.stack([np.cos(th[:, 0]), np.sin(th[:, 0])], axis=1)
        u3 = np.stack([np.cos(th[:, 1]), np.sin(th[:, 1])], axis=1)
        v = np.array([0.0, -self.offset])
        A = np.zeros_like(u2)
        D = self.l2 * u2
        C = D + self.l3 * u3
        E = self.e * u2
        B = E + self.g * u3
        F = D + self.g * u3
        return {"A": A, "D": D, "C": C, "E": E, "B": B, "F": F,
                "A1": A + v, "D1": D + v, "C1": C + v}

    # ------------------------------------------------------------------- weights
    def point_weights(self, payload_fraction: float = 0.5) -> dict[str, float]:
        """Substitution weights at ``A``, ``D``, ``B``, ``C`` (N)."""
        k, l2, l3 = self.k, self.l2, self.l3
        s2, s3 = self._s2(), self._s3()
        wa = self.w2 * (1 - s2 / l2) + 0.5 * self.w9 * (1 - 1 / k) + 0.5 * self.w14
        wd = (self.w2 * s2 / l2 + self.w3 * (1 - s3 / l3) + 0.5 * self.w9 / k + 0.5 * self.w8 * (1 - 1 / k)
              + 0.5 * self.w14 + 0.5 * self.w15 + self.w16)
        wb = 0.5 * self.w9 + 0.5 * self.w8
        wc = (self.w3 * s3 / l3 + 0.5 * self.w8 / k + 0.5 * self.w15 + self.w4 + self.tool
              + payload_fraction * self.payload)
        return {"A": wa, "D": wd, "B": wb, "C": wc}

    def height_coefficients(self, payload_fraction: float = 0.5) -> list[tuple[str, float, float, float]]:
        """Each body's own centre of mass: ``(link, weight, a, b)`` with height
        ``a·sin θ2 + b·sin θ3`` (+ a constant) and horizontal position ``a·cos θ2 + b·cos θ3``."""
        l2, l3, e, g = self.l2, self.l3, self.e, self.g
        return [
            ("2", self.w2, self._s2(), 0.0),
            ("3", self.w3, l2, self._s3()),
            ("9", self.w9, e, g / 2),
            ("8", self.w8, (l2 + e) / 2, g),
            ("14", self.w14, l2 / 2, 0.0),
            ("15", self.w15, l2, l3 / 2),
            ("16", self.w16, l2, 0.0),
            ("4", self.w4, l2, l3),
            ("tool", self.tool, l2, l3),
            ("payload", payload_fraction * self.payload, l2, l3),
        ]

    def potential(self, th: np.ndarray, payload_fraction: float = 0.5) -> np.ndarray:
        """Gravity potential of the links' own centres of mass (J, up to a constant)."""
        th = np.atleast_2d(th)
        return sum(w * (a * np.sin(th[:, 0]) + b * np.sin(th[:, 1]))
                   for _, w, a, b in self.height_coefficients(payload_fraction))

    def gravity_forces(self, th: np.ndarray, payload_fraction: float = 0.5) -> np.ndarray:
        """Exact ``−∂U/∂(θ2, θ3)`` from the links' own centres of mass, shape (m, 2)."""
        th = np.atleast_2d(th)
        out = np.zeros_like(th)
        for _, w, a, b in self.height_coefficients(payload_fraction):
            out[:, 0] -= w * a * np.cos(th[:, 0])
            out[:, 1] -= w * b * np.cos(th[:, 1])
        return out

    # --------------------------------------------------------- spring and drive
    def term(self) -> HarmonicTerm:
        """The one harmonic term the spring cancels: ``W_D·l2·cos(θ2 − 90°)``."""
        return HarmonicTerm(self.point_weights()["D"] * self.l2, -math.pi / 2, (1.0, 0.0))

    def vertical_load(self, payload_fraction: float = 0.5) -> float:
        """Vertical load reduced to ``B``: ``W_B + k·W_C`` (N), the same in every configuration."""
        w = self.point_weights(payload_fraction)
        return w["B"] + self.k * w["C"]

    def cylinder(self, th: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Cylinder length ``|B − P|`` (m), its unit vector ``u`` (P→B) and lever arm
        ``(B − A) × u`` about ``A`` (m, signed: + turns the pantograph counter-clockwise)."""
        B = self.points(th)["B"]
        d = B - self.cylinder_base
        length = np.hypot(d[:, 0], d[:, 1])
        u = d / length[:, None]
        return length, u, B[:, 0] * u[:, 1] - B[:, 1] * u[:, 0]

    def cylinder_force(self, th: np.ndarray, payload_fraction: float = 0.5) -> np.ndarray:
        """``F = (W_B·x_B + W_C·x_C)/lever`` (N, + pushes B away from P) at ``th``."""
        w = self.point_weights(payload_fraction)
        p = self.points(th)
        moment = w["B"] * p["B"][:, 0] + w["C"] * p["C"][:, 0]
        return moment / self.cylinder(th)[2]

    def hand_force(self, th: np.ndarray, payload_fraction: float = 0.5) -> np.ndarray:
        """Force along ``A→C`` (N, + outward) the operator holds at the handle: what the
        cylinder's line of action leaves of the load along the pantograph's line."""
        B = self.points(th)["B"]
        bhat = B / np.hypot(B[:, 0], B[:, 1])[:, None]
        _, u, _ = self.cylinder(th)
        F = self.cylinder_force(th, payload_fraction)
        return (self.vertical_load(payload_fraction) * bhat[:, 1] - F * np.sum(u * bhat, axis=1)) / self.k


def stroke_gradients(p: Pantograph, th: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``∂s/∂θ`` of the cylinder length and ``∂ρ_C/∂θ`` of the reach ``|C − A|``, each (m, 2)."""
    pts = p.points(th)
    c2, s2, c3, s3 = np.cos(th[:, 0]), np.sin(th[:, 0]), np.cos(th[:, 1]), np.sin(th[:, 1])
    dB = np.stack([np.stack([-p.e * s2, p.e * c2], 1), np.stack([-p.g * s3, p.g * c3], 1)], axis=2)
    dC = np.stack([np.stack([-p.l2 * s2, p.l2 * c2], 1), np.stack([-p.l3 * s3, p.l3 * c3], 1)], axis=2)
    _, u, _ = p.cylinder(th)
    chat = pts["C"] / np.hypot(pts["C"][:, 0], pts["C"][:, 1])[:, None]
    return np.einsum("mi,mij->mj", u, dB), np.einsum("mi,mij->mj", chat, dC)


def virtual_work_forces(p: Pantograph, th: np.ndarray, payload_fraction: float = 0.5) -> np.ndarray:
    """Cylinder and hand forces ``(F, R)`` from virtual work on the links' own masses.

    Solves ``Q_gravity + Q_spring + F·∂s/∂θ + R·∂ρ_C/∂θ = 0`` for each configuration,
    with ``s = |B − P|`` the cylinder's length and ``ρ_C = |C − A|``; independent of the
    substitution weights and of the moment formula. Shape (m, 2).
    """
    th = np.atleast_2d(th)
    ds, drho = stroke_gradients(p, th)
    q = p.gravity_forces(th, payload_fraction)
    q[:, 0] += p.term().moment(th[:, 0])  # the spring's force on θ2: +W_D·l2·cos θ2
    mat = np.stack([ds, drho], axis=2)  # (m, 2 equations, 2 unknowns)
    return np.linalg.solve(mat, -q[..., None])[..., 0]
