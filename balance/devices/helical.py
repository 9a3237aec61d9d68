"""Helical springs a maker can wind, after the formulas of EN 13906-1/-2 (DIN 2089).

Given what a balancing device needs from its spring (stiffness, free length or the
working lengths, peak force) and the space it may take, :func:`design_spring` picks a
wire diameter from a standard series, the mean coil diameter and the active coils, and
checks what a spring maker checks:

- stiffness ``R = G·d⁴/(8·D³·n)`` (``n`` rounded to half coils, ``D`` then re-solved so
  ``R`` equals the device's ``c``);
- spring index ``w = D/d`` within 4 … 20 and at least two active coils;
- shear stress ``τ = 8·D·F/(π·d³)`` with the Bergsträsser curvature correction
  ``k = (w + 0.5)/(w − 0.75)`` against the allowed static stress (``0.5·R_m`` for
  compression, ``0.45·R_m`` for extension springs; ``R_m`` the wire's minimum tensile
  strength, ``A·d^−m`` with ``d`` in mm);
- compression springs (ends closed and ground): solid length ``(n + 2)·d`` plus the
  minimum sum of coil gaps ``S_a = (0.0015·D²/d + 0.1·d)·n`` within the shortest working
  length, and buckling: the critical deflection

      s_K = L0·(1/2)/(1 − G/E)·[1 − √(1 − (1 − G/E)/(1/2 + G/E)·(π·D/(ν·L0))²)]

  (no buckling when the root is imaginary) against the largest deflection, with the
  seating coefficient ``ν`` of the end condition;
- extension springs: close-wound body ``(n + 1)·d`` plus two full loops (``≈ D_i`` each),
  no initial tension; the anchor offset that gives the device's force law is reported.

The lightest spring that passes every check is returned (for a compression spring the
lightest that cannot buckle, if any; otherwise the lightest, marked as needing a guide);
when none passes, the reason of the closest candidate is given in one sentence.

Examples
--------
>>> s = design_spring("compression", stiffness=2000.0, max_force=400.0, free_length=0.5,
...                   min_length=0.3, max_length=0.45)
>>> abs(s.stiffness_N_per_m / 2000.0 - 1) < 1e-9, s.max_shear_stress_Pa <= s.allowed_shear_stress_Pa
(True, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

import numpy as np

from mechbase import Row

from ..errors import InfeasibleBounds, InvalidInput

__all__ = ["Material", "MATERIALS", "WIRE_SERIES_MM", "END_CONDITIONS", "design_spring", "design_for_device",
           "NoSpringFits", "HelicalSpring", "Buckling",
           "stiffness", "bergstraesser", "buckling_deflection"]


class NoSpringFits(InfeasibleBounds):
    """No helical spring realises the device in the space given."""


@dataclass(frozen=True)
class Material:
    """Spring wire: moduli, density and ``R_m = A·d^−m`` (MPa, ``d`` in mm) over ``d_range`` (mm)."""

    name: str
    description: str
    shear_modulus: float  # Pa
    elastic_modulus: float  # Pa
    density: float  # kg/m³
    A: float  # MPa·mm^m
    m: float
    d_range: tuple[float, float]  # mm

    def tensile_strength(self, d: float) -> float:
        """Minimum tensile strength ``R_m`` (Pa) of wire of diameter ``d`` (m)."""
        return 1e6 * self.A / (1e3 * d) ** self.m


#: Moduli as EN 13906-1 tabulates them for each wire standard; strength laws A·d^−m as
#: fitted in Shigley's Mechanical Engineering Design (9th ed., Table 10-4) for the
#: equivalent ASTM wires.
MATERIALS = {
    m.name: m for m in (
        Material("music-wire", "patented cold-drawn spring steel, EN 10270-1 DH (ASTM A228)",
                 81.5e9, 206e9, 7850.0, 2211.0, 0.145, (0.10, 6.5)),
        Material("oil-tempered", "oil-hardened tempered spring steel, EN 10270-2 VDC (ASTM A229)",
                 79.5e9, 206e9, 7850.0, 1855.0, 0.187, (0.5, 12.7)),
        Material("chrome-vanadium", "oil-hardened CrV spring steel, EN 10270-2 VDCrV (ASTM A232)",
                 79.5e9, 206e9, 7850.0, 2005.0, 0.168, (0.8, 11.1)),
        Material("chrome-silicon", "oil-hardened SiCr spring steel, EN 10270-2 VDSiCr (ASTM A401)",
                 79.5e9, 206e9, 7850.0, 1974.0, 0.108, (1.6, 9.5)),
        Material("stainless", "stainless spring steel 1.4310, EN 10270-3 (ASTM A313 type 302)",
                 70.0e9, 185e9, 7900.0, 1867.0, 0.146, (0.3, 2.5)),
    )
}

_R20 = (1.00, 1.12, 1.25, 1.40, 1.60, 1.80, 2.00, 2.24, 2.50, 2.80,
        3.15, 3.55, 4.00, 4.50, 5.00, 5.60, 6.30, 7.10, 8.00, 9.00)
#: Wire diameters (mm): the R20 preferred numbers of ISO 3 from 0.1 to 20 mm
WIRE_SERIES_MM = tuple(round(v * s, 3) for s in (0.1, 1.0, 10.0) for v in _R20 if v * s <= 20.0)

#: seating coefficient ν of EN 13906-1 for each end condition of a compression spring
END_CONDITIONS = {"fixed-free": 2.0, "pinned": 1.0, "fixed-pinned": 0.7, "fixed": 0.5}
ALLOWED_FRACTION = {"compression": 0.5, "extension": 0.45}
INDEX_RANGE = (4.0, 20.0)
MIN_ACTIVE_COILS = 2.0


def stiffness(G: float, d: float, D: float, n: float) -> float:
    """Spring rate ``G·d⁴/(8·D³·n)`` (N/m).

    >>> round(stiffness(81.5e9, 0.004, 0.032, 10.0), 3)
    7958.984
    """
    return G * d ** 4 / (8 * D ** 3 * n)


def bergstraesser(w: float) -> float:
    """Stress correction factor ``(w + 0.5)/(w − 0.75)`` for the spring index ``w = D/d``."""
    return (w + 0.5) / (w - 0.75)


def buckling_deflection(free_length: float, D: float, G: float, E: float, nu: float) -> float:
    """Critical deflection ``s_K`` (m) of EN 13906-1; ``inf`` when the spring cannot buckle."""
    ratio = 1 - G / E
    rad = 1 - ratio / (0.5 + G / E) * (math.pi * D / (nu * free_length)) ** 2
    if rad < 0:
        return math.inf
    return free_length * 0.5 / ratio * (1 - math.sqrt(rad))


def _candidates(mat: Material, kind: str, c: float, d: float, lo_D: float, hi_D: float):
    """Coil diameters and half-coil counts giving exactly the stiffness ``c`` with wire ``d``.

    Every half-coil count from the one nearest the widest coil ``hi_D`` (the fewest coils, the lightest
    spring of the wire) to the one nearest the narrowest ``lo_D``, at least :data:`MIN_ACTIVE_COILS`;
    each coil diameter is re-solved for its count, so the first and last may lie just outside the range.
    """
    if hi_D <= lo_D:
        return
    half_coils = 2 * mat.shear_modulus * d ** 4 / (8 * c)  # 2n·D³
    fewest = max(round(half_coils / hi_D ** 3), round(2 * MIN_ACTIVE_COILS))
    for twice_n in range(fewest, round(half_coils / lo_D ** 3) + 1):
        n = twice_n / 2
        yield (mat.shear_modulus * d ** 4 / (8 * c * n)) ** (1 / 3), n


def design_spring(
    kind: str,
    stiffness: float,
    max_force: float,
    *,
    free_length: float | None = None,
    min_length: float | None = None,
    max_length: float | None = None,
    max_deflection: float | None = None,
    material: str = "music-wire",
    max_outer_diameter: float | None = None,
    min_inner_diameter: float = 0.0,
    ends: str = "pinned",
    guided: bool = False,
) -> HelicalSpring:
    """The lightest helical spring that realises a device's spring.

    Parameters
    ----------
    kind : {"compression", "extension"}
    stiffness : float
        Required spring rate ``c`` (N/m).
    max_force : float
        Largest working force (N).
    free_length, min_length, max_length : float, optional
        Compression springs whose free length the device fixes: the free length and the
        shortest/longest working lengths (m). Without ``free_length`` the spring is made
        as short as the checks allow for a working deflection up to ``max_deflection``
        (the compression-lever device, whose lever is then as short as possible).
        Extension springs: ignored except ``max_deflection`` (largest extension, m).
    max_deflection : float, optional
        Largest deflection from free (m) when ``free_length`` is not given.
    material : str
        A key of :data:`MATERIALS`.
    max_outer_diameter, min_inner_diameter : float
        Space for the coils (m): a bore it must fit in, a rod it must fit over.
    ends : {"pinned", "fixed-free", "fixed-pinned", "fixed"}
        End condition of a compression spring for buckling.
    guided : bool
        A compression spring on a rod or in a sleeve cannot buckle sideways.

    Raises
    ------
    InvalidInput
        Unknown material or end condition, non-positive stiffness or force.
    NoSpringFits
        No wire of the series and no coil diameter passes every check.
    """
    if kind not in ALLOWED_FRACTION:
        raise InvalidInput(f"a helical spring is 'compression' or 'extension', not {kind!r}.")
    if material not in MATERIALS:
        raise InvalidInput(f"unknown spring material {material!r}; choose one of {', '.join(MATERIALS)}.")
    if ends not in END_CONDITIONS:
        raise InvalidInput(f"unknown end condition {ends!r}; choose one of {', '.join(END_CONDITIONS)}.")
    for name, v in (("stiffness", stiffness), ("peak force", max_force)):
        if not (math.isfinite(v) and v > 0):
            raise InvalidInput(f"the spring's {name} must be a positive number, not {v}.")
    if max_outer_diameter is not None and not (math.isfinite(max_outer_diameter) and max_outer_diameter > 0):
        raise InvalidInput(f"the largest outer diameter must be positive, not {max_outer_diameter}.")
    if not (math.isfinite(min_inner_diameter) and min_inner_diameter >= 0):
        raise InvalidInput(f"the smallest inner diameter must be ≥ 0, not {min_inner_diameter}.")
    mat = MATERIALS[material]
    c = float(stiffness)
    tau_frac = ALLOWED_FRACTION[kind]
    nu = END_CONDITIONS[ends]
    best, closest = None, None
    for d_mm in WIRE_SERIES_MM:
        if not mat.d_range[0] <= d_mm <= mat.d_range[1]:
            continue
        d = d_mm * 1e-3
        lo_D = max(INDEX_RANGE[0] * d, min_inner_diameter + d)
        hi_D = INDEX_RANGE[1] * d
        if max_outer_diameter is not None:
            hi_D = min(hi_D, max_outer_diameter - d)
        tau_allowed = tau_frac * mat.tensile_strength(d)
        for D, n in _candidates(mat, kind, c, d, lo_D * (1 - 1e-9), hi_D * (1 + 1e-9)):
            w = D / d
            k = bergstraesser(w)
            tau = k * 8 * D * max_force / (math.pi * d ** 3)
            mass = mat.density * math.pi * d * d / 4 * math.pi * D * (n + (2 if kind == "compression" else 3))
            if best is not None and best[0] < (False, mass):
                break  # every further coil of this wire is heavier: D·(n + 2 or 3) grows with n ≥ 2
            why = []
            if not INDEX_RANGE[0] - 1e-9 <= w <= INDEX_RANGE[1] + 1e-9:
                why.append((abs(w - min(max(w, INDEX_RANGE[0]), INDEX_RANGE[1])) / 4,
                            f"its spring index D/d = {w:.4g} is outside 4 … 20", "another wire size or material"))
            if max_outer_diameter is not None and D + d > max_outer_diameter * (1 + 1e-9):
                why.append(((D + d) / max_outer_diameter - 1,
                            f"its outer diameter {1e3 * (D + d):.4g} mm exceeds {1e3 * max_outer_diameter:.4g} mm",
                            "a larger outer diameter"))
            if D - d < min_inner_diameter * (1 - 1e-9):
                why.append((1 - (D - d) / min_inner_diameter,
                            f"its inner diameter {1e3 * (D - d):.4g} mm does not clear {1e3 * min_inner_diameter:.4g} mm",
                            "a thinner guide rod"))
            if tau > tau_allowed:
                why.append((tau / tau_allowed - 1, f"its shear stress {tau / 1e6:.4g} MPa exceeds the allowed "
                                                   f"{tau_allowed / 1e6:.4g} MPa",
                            "a lower peak force (a force limit on the device) or a material drawn thicker (oil-tempered, up to "
                            "12.7 mm)"))
            row = {"d": d, "D": D, "n": n, "k": k, "tau": tau, "tau_allowed": tau_allowed, "mass": mass}
            if kind == "compression":
                solid = (n + 2) * d
                gaps = (0.0015 * D * D / d + 0.1 * d) * n
                if free_length is None:
                    if max_deflection is None:
                        raise InvalidInput("a compression spring needs its free length or its largest deflection.")
                    L0 = max_deflection + solid + gaps
                    Lmin, Lmax = L0 - max_deflection, L0
                else:
                    L0, Lmin, Lmax = free_length, min_length, max_length
                if Lmin < solid + gaps - 1e-12:
                    why.append(((solid + gaps - Lmin) / max(Lmin, 1e-9),
                                f"its solid length plus the minimum coil gaps ({1e3 * (solid + gaps):.4g} mm) "
                                f"exceed the shortest working length {1e3 * Lmin:.4g} mm",
                                "a longer spring (larger r0 or a)"))
                s_max = L0 - Lmin
                s_k = math.inf if guided else buckling_deflection(L0, D, mat.shear_modulus, mat.elastic_modulus, nu)
                row.update(L0=L0, Lmin=Lmin, Lmax=Lmax, solid=solid, gaps=gaps, s_max=s_max, s_k=s_k)
            else:
                body = (n + 1) * d
                loop = D - d
                row.update(body=body, loop=loop, L0=body + 2 * loop)
            if why:
                score = (len(why), sum(v for v, _, _ in why))
                if closest is None or score < closest[0]:
                    closest = (score, row, why)
                continue
            key = (kind == "compression" and not row["s_max"] < row["s_k"], mass)
            if best is None or key < best[0]:
                best = (key, row)
    if best is None:
        space = []
        if max_outer_diameter is not None:
            space.append(f"outer diameter ≤ {1e3 * max_outer_diameter:.4g} mm")
        if min_inner_diameter > 0:
            space.append(f"inner diameter ≥ {1e3 * min_inner_diameter:.4g} mm")
        where = f" ({', '.join(space)})" if space else ""
        if closest is None:
            raise NoSpringFits(f"no {mat.name} wire of the series gives a spring of {c:.4g} N/m in the space "
                               f"given{where}; allow a larger outer diameter or another material.")
        row, why = closest[1], closest[2]
        raise NoSpringFits(
            f"no {mat.name} spring of {c:.4g} N/m for {max_force:.4g} N fits{where}: the closest, wire "
            f"{1e3 * row['d']:.3g} mm on a {1e3 * row['D']:.4g} mm coil with {row['n']:g} active coils, fails because "
            f"{' and '.join(t for _, t, _ in why)}; try {' or '.join(dict.fromkeys(h for _, _, h in why))}."
        )
    return _report(best[1], kind, mat, c, max_force, ends, nu, guided)


@dataclass(frozen=True)
class Buckling(Row):
    """A compression spring's buckling check (EN 13906-1): the critical against the working deflection."""

    end_condition: str
    seating_coefficient: float
    guided: bool
    critical_deflection_m: float
    max_deflection_m: float

    row_keys = ("end_condition", "seating_coefficient", "guided", "critical_deflection_m", "max_deflection_m", "safe")

    @property
    def safe(self) -> bool:
        return self.max_deflection_m < self.critical_deflection_m


@dataclass(frozen=True)
class HelicalSpring(Row):
    """A helical spring a maker can wind, with the checks it passed (SI units).

    Compression springs fill ``solid_length_m`` … ``buckling``; extension springs
    ``body_length_m``, ``loop_length_m`` and, for a crank device, ``anchor_offset_m`` (where the
    near loop sits relative to ``C``) and ``max_extension_m``.
    """

    kind: str
    material: str
    material_description: str
    wire_diameter_m: float
    mean_diameter_m: float
    active_coils: float
    shear_modulus_Pa: float
    elastic_modulus_Pa: float
    stiffness_N_per_m: float
    required_stiffness_N_per_m: float
    max_force_N: float
    stress_correction_factor: float
    max_shear_stress_Pa: float
    allowed_shear_stress_Pa: float
    tensile_strength_Pa: float
    mass_kg: float
    free_length_m: float
    solid_length_m: float | None = None
    min_gap_sum_m: float | None = None
    min_working_length_m: float | None = None
    max_working_length_m: float | None = None
    solid_shear_stress_Pa: float | None = None
    buckling: Buckling | None = None
    body_length_m: float | None = None
    loop_length_m: float | None = None
    anchor_offset_m: float | None = None
    max_extension_m: float | None = None

    standard = "EN 13906-1 (compression) / EN 13906-2 (extension) formulas"

    @property
    def outer_diameter_m(self) -> float:
        return self.mean_diameter_m + self.wire_diameter_m

    @property
    def inner_diameter_m(self) -> float:
        return self.mean_diameter_m - self.wire_diameter_m

    @property
    def spring_index(self) -> float:
        return self.mean_diameter_m / self.wire_diameter_m

    @property
    def total_coils(self) -> float:
        return self.active_coils + (2 if self.kind == "compression" else 1)

    @property
    def stiffness_error(self) -> float:
        return self.stiffness_N_per_m / self.required_stiffness_N_per_m - 1

    @property
    def stress_ratio(self) -> float:
        return self.max_shear_stress_Pa / self.allowed_shear_stress_Pa

    @property
    def safe_when_solid(self) -> bool | None:
        """A compression spring's shear stress when pressed solid is allowed (None: an extension spring)."""
        if self.solid_shear_stress_Pa is None:
            return None
        return self.solid_shear_stress_Pa <= self.allowed_shear_stress_Pa

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The row: every field given (the kind's own), the derived sizes, and the kind's last check."""
        last = ("safe_when_solid",) if self.kind == "compression" else ("initial_tension_N",)
        return (*(f.name + "?" for f in fields(self)), "standard", "outer_diameter_m", "inner_diameter_m",
                "spring_index", "total_coils", "stiffness_error", "stress_ratio", *last)

    #: an extension spring wound without initial tension (the formulas assume none)
    initial_tension_N = 0.0


def _report(b: dict, kind: str, mat: Material, c: float, F: float, ends: str, nu: float,
            guided: bool) -> HelicalSpring:
    d, D, n = b["d"], b["D"], b["n"]
    rate = stiffness(mat.shear_modulus, d, D, n)
    common = dict(kind=kind, material=mat.name, material_description=mat.description, wire_diameter_m=d,
                  mean_diameter_m=D, active_coils=n, shear_modulus_Pa=mat.shear_modulus,
                  elastic_modulus_Pa=mat.elastic_modulus, stiffness_N_per_m=rate, required_stiffness_N_per_m=c,
                  max_force_N=F, stress_correction_factor=b["k"], max_shear_stress_Pa=b["tau"],
                  allowed_shear_stress_Pa=b["tau_allowed"], tensile_strength_Pa=mat.tensile_strength(d),
                  mass_kg=b["mass"], free_length_m=b["L0"])
    if kind == "compression":
        F_solid = rate * (b["L0"] - b["solid"])
        return HelicalSpring(**common, solid_length_m=b["solid"], min_gap_sum_m=b["gaps"],
                             min_working_length_m=b["Lmin"], max_working_length_m=b["Lmax"],
                             solid_shear_stress_Pa=8 * D * F_solid / (math.pi * d ** 3),
                             buckling=Buckling(ends, nu, guided, b["s_k"], b["s_max"]))
    return HelicalSpring(**common, body_length_m=b["body"], loop_length_m=b["loop"])


def design_for_device(res, **options) -> HelicalSpring:
    """A helical spring for a fitted or exact crank-and-rocker device (:class:`~balance.devices.fit.FitResult`).

    - ``compression``: the spring between ``C`` and ``B`` has the device's free length
      ``2r + r0 + a`` and works between its shortest and longest lengths ``L``;
    - ``compression-lever``: the spring on the lever is compressed by ``L`` (``r0`` … ``L_max``);
      it is made as short as the checks allow, which fixes the lever (the stop at its free
      length from ``C``: :meth:`~balance.devices.fit.LeverGeometry.for_spring`);
    - ``tension``: an extension spring with the device's rate; ``anchor_offset_m`` is how far
      beyond ``C`` its near loop must sit (negative: behind ``C``, e.g. a cable over a pulley at
      ``C``) so that its force is ``c·(L − (r0 − a))``.

    The slider devices (:mod:`balance.devices.sliders`) carry a compression spring whose deflection runs
    from ``a`` to ``a + stroke``, of the free length the fit reports.

    ``options`` are passed to :func:`design_spring` (material, space, ends, guided).
    """
    if res.family != "slotted-lever":
        longest_deflection = res.max_force / res.c
        return design_spring("compression", res.c, res.max_force, free_length=res.free_length,
                             min_length=res.free_length - longest_deflection, max_length=res.free_length - res.a,
                             **options)
    dev = res.device
    L = dev.length(_phi_extremes(res.phi_range))
    lmin, lmax = float(np.min(L)), float(np.max(L))
    if res.kind == "compression":
        return design_spring("compression", res.c, res.max_force, free_length=res.free_length, min_length=lmin,
                             max_length=lmax, **options)
    if res.kind == "compression-lever":
        options.setdefault("guided", True)  # it rides on the slotted lever
        return design_spring("compression", res.c, res.max_force, max_deflection=lmax, **options)
    out = design_spring("extension", res.c, res.max_force, **options)
    l0_dev = res.free_length  # r0 − a: the device's effective free length
    return replace(out, anchor_offset_m=l0_dev - out.free_length_m, max_extension_m=lmax - l0_dev)


def _phi_extremes(phi_range) -> np.ndarray:
    """φ at the range ends and at any multiple of π inside: where L is extreme."""
    lo, hi = phi_range
    ks = range(math.ceil(lo / math.pi), math.floor(hi / math.pi) + 1)
    return np.array([lo, hi] + [k * math.pi for k in ks])
