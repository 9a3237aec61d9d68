"""The compression-lever device, helical spring design (EN 13906-1 formulas) and fit trade-offs."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from balance import InfeasibleBounds, InvalidInput, SpringBounds, SpringOptions, SpringProblem, fit_spring
from balance.devices.helical import (
    MATERIALS, NoSpringFits, WIRE_SERIES_MM, _candidates, bergstraesser, buckling_deflection, design_for_device,
    design_spring,
)

RAD = (math.radians(20), math.radians(160))
BOUNDS = SpringBounds(r=(0.01, 0.2), r0=(0.05, 0.4), a=(0.0, 1.0))


def lever_moment(phi, c, r, r0, s, l_s):
    """Positions: A = 0, C = (r + r0, 0), B on the crank; the spring sits on the lever C→B beyond B,
    between B and a stop at s from C, so its length is s − |CB| and it pushes B towards C."""
    B = np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1)
    CB = B - np.array([r + r0, 0.0])
    L = np.linalg.norm(CB, axis=-1)
    push = c * (l_s - (s - L))  # compression force of the spring, > 0
    F = -(push / L)[:, None] * CB  # on B, towards C
    return B[:, 0] * F[:, 1] - B[:, 1] * F[:, 0]


@pytest.mark.parametrize("rng", [(20.0, 160.0), (0.0, 180.0), (-150.0, 170.0)])
def test_compression_lever_is_exact_and_reports_its_length(rng):
    phi_rng = tuple(math.radians(v) for v in rng)
    res = fit_spring("compression-lever", -100.0, phi_rng, BOUNDS)
    assert res.method == "exact" and res.a == res.r0 and res.sense == -1 and res.norm == "max"
    assert res.message == "compression spring on the lever beyond B, a = r0: exact"
    phi = np.linspace(*phi_rng, 20001)
    s = res.lever.stop_distance_from_C
    m = lever_moment(phi, res.c, res.r, res.r0, s, s)  # a = r0: the spring's free length equals s
    assert np.max(np.abs(m + 100.0 * np.sin(phi))) / 100.0 <= 1e-12
    assert res.max_rel_error <= 1e-12
    L = np.hypot(res.r + res.r0 - res.r * np.cos(phi), res.r * np.sin(phi))
    lv = res.lever.to_dict()
    assert lv["reach_from_C_fig_a"] == pytest.approx(np.max(L), rel=1e-6)
    assert lv["extra_length"] == pytest.approx(s - np.max(L), rel=1e-6) and lv["extra_length"] > 0
    assert lv["spring_length_min"] == pytest.approx(s - np.max(L), rel=1e-6)
    assert any("beyond the farthest crank-pin" in n for n in res.notes)
    # the spring takes compressions |CB| from min to max; its free length s = max|CB|/δ (δ = 0.5)
    assert (lv["compression_min"], lv["compression_max"]) == pytest.approx((np.min(L), np.max(L)), rel=1e-6)
    assert s == lv["spring_free_length"] == lv["reach_from_C"] == pytest.approx(np.max(L) / 0.5, rel=1e-6)
    assert lv["spring_length_max"] == pytest.approx(s - np.min(L), rel=1e-6)
    assert lv["deflection_ratio"] == res.deflection == 0.5 and lv["size_ratio"] == pytest.approx(2.0)
    (note,) = [n for n in res.notes if "lever reaches" in n]
    assert f"{s:.4g} m from C, {s - np.max(L):.4g} m beyond" in note and f"(2× the {np.max(L):.4g} m" in note


def test_compression_lever_with_a_deflection_and_length_limit():
    """δ = 0.25 makes the spring 4× its longest compression; a free-length limit then bounds the
    longest compression, and with it the crank: the device stays exact, or is refused by name."""
    b = SpringBounds(r=(0.01, 0.2), r0=(0.05, 0.4), a=(0.0, 1.0), max_deflection=0.25, max_free_length=1.2)
    res = fit_spring("compression-lever", -100.0, RAD, b)
    lv = res.lever.to_dict()
    assert res.max_rel_error <= 1e-12 and lv["deflection_ratio"] == 0.25
    assert lv["spring_free_length"] == pytest.approx(4 * lv["compression_max"]) and lv["spring_free_length"] <= 1.2
    free = fit_spring("compression-lever", -100.0, RAD, SpringBounds(b.r, b.r0, b.a, max_deflection=0.25))
    assert free.lever.spring_free_length > 1.2  # the limit binds
    tight = SpringBounds(b.r, b.r0, b.a, max_force=2000.0, max_deflection=0.25, max_free_length=0.2)
    with pytest.raises(InfeasibleBounds) as ei:
        fit_spring("compression-lever", -100.0, RAD, tight)
    assert ("keeps the spring force below 2000 N and fits a spring of at most 0.2 m at a deflection ratio of 0.25"
            in str(ei.value))


def test_compression_lever_refusals():
    with pytest.raises(InfeasibleBounds, match=r"a ∈ \[0.5, 1\] m and r0 ∈ \[0.05, 0.4\] m never meet"):
        fit_spring("compression-lever", -100.0, RAD, SpringBounds((0.01, 0.2), (0.05, 0.4), (0.5, 1.0)))
    # ranges that meet in one value still give the device there
    for a, r0 in (((0.4, 1.0), 0.4), ((0.0, 0.05), 0.05)):
        res = fit_spring("compression-lever", -100.0, RAD, SpringBounds((0.01, 0.2), (0.05, 0.4), a))
        assert res.a == res.r0 == pytest.approx(r0) and res.max_rel_error < 1e-12
    # the least force a = r0 device needs, less 1 %: no lever device keeps below it
    least = fit_spring("compression-lever", -100.0, RAD, BOUNDS).max_force
    with pytest.raises(InfeasibleBounds, match=r"keeps the spring force below .* N; raise the force limit, "
                                               r"the maximum free length or the maximum deflection\.$"):
        fit_spring("compression-lever", -100.0, RAD, SpringBounds(BOUNDS.r, BOUNDS.r0, BOUNDS.a, max_force=0.99 * least))
    with pytest.raises(Exception, match="compression"):
        fit_spring("compression-lever", 100.0, RAD, BOUNDS)


# --------------------------------------------------------------------- helical springs
def test_wire_series_is_r20():
    assert WIRE_SERIES_MM[:3] == (0.1, 0.112, 0.125) and 1.25 in WIRE_SERIES_MM and WIRE_SERIES_MM[-1] == 20.0
    ratios = np.diff(np.log10(WIRE_SERIES_MM))
    assert np.all(np.abs(ratios - 0.05) < 0.01)  # twenty steps per decade


@pytest.mark.parametrize("kind, moment, material", [
    ("compression", 100.0, "oil-tempered"), ("tension", -100.0, "music-wire"),
    ("compression-lever", -100.0, "chrome-silicon")])
def test_designed_spring_realises_the_device(kind, moment, material):
    b = SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.4), a=(0.0, 0.3), max_force=1500.0)
    res = fit_spring(kind, moment, RAD, b)
    sp = design_for_device(res, material=material).to_dict()
    G, d, D, n = sp["shear_modulus_Pa"], sp["wire_diameter_m"], sp["mean_diameter_m"], sp["active_coils"]
    # rate from the textbook formula, independently of the design code
    assert G * d ** 4 / (8 * D ** 3 * n) == pytest.approx(res.c, rel=0.01)
    assert round(1e3 * d, 6) in WIRE_SERIES_MM and 2 * n == round(2 * n) and n >= 2
    w = D / d
    assert 4 <= w <= 20
    tau = (w + 0.5) / (w - 0.75) * 8 * D * res.max_force / (math.pi * d ** 3)
    assert tau == pytest.approx(sp["max_shear_stress_Pa"], rel=1e-12)
    frac = 0.45 if kind == "tension" else 0.5
    mat = MATERIALS[material]
    assert sp["allowed_shear_stress_Pa"] == pytest.approx(frac * 1e6 * mat.A / (1e3 * d) ** mat.m)
    assert tau <= sp["allowed_shear_stress_Pa"]
    assert sp["stress_correction_factor"] == pytest.approx((w + 0.5) / (w - 0.75), rel=1e-12)
    if sp["kind"] == "compression":
        assert sp["solid_length_m"] == pytest.approx((n + 2) * d)
        assert sp["solid_length_m"] + sp["min_gap_sum_m"] <= sp["min_working_length_m"] + 1e-12
    if kind == "compression":  # between C and B: |CB| over the range, longest at 160°, shortest at 20°
        phi = np.linspace(*RAD, 20001)
        L = np.hypot(res.r + res.r0 - res.r * np.cos(phi), res.r * np.sin(phi))
        assert sp["max_working_length_m"] == pytest.approx(L.max(), rel=1e-9)
        assert sp["min_working_length_m"] == pytest.approx(L.min(), rel=1e-9)


def test_buckling_formula_limits():
    G, E = 81.5e9, 206e9
    # a short fat spring cannot buckle; a long thin one buckles at a small deflection
    assert buckling_deflection(0.05, 0.05, G, E, 1.0) == math.inf
    sk = buckling_deflection(0.5, 0.02, G, E, 1.0)
    assert 0 < sk < 0.05
    # fixed ends (ν = 0.5) are twice as stiff against buckling as pinned: larger critical deflection
    assert buckling_deflection(0.5, 0.02, G, E, 0.5) > sk
    # the closed form against a direct solve of EN 13906-1's relation for the critical length ratio
    nu, L0, D = 1.0, 0.3, 0.04
    r = 1 - G / E
    lam = (math.pi * D / (nu * L0)) ** 2 * r / (0.5 + G / E)
    assert sk > 0 and buckling_deflection(L0, D, G, E, nu) == pytest.approx(L0 * 0.5 / r * (1 - math.sqrt(1 - lam)))
    assert bergstraesser(6.0) == pytest.approx(6.5 / 5.25)


def test_refusal_names_the_reason():
    with pytest.raises(NoSpringFits, match="outer diameter") as ei:
        design_spring("compression", 2000.0, 400.0, free_length=0.5, min_length=0.3, max_length=0.45,
                      max_outer_diameter=0.005)
    assert "\n" not in str(ei.value)
    with pytest.raises(NoSpringFits, match="shear stress"):  # 10 kN on music wire
        design_spring("extension", 10000.0, 10000.0, max_deflection=0.5)
    with pytest.raises(NoSpringFits, match="solid length"):
        design_spring("compression", 500.0, 200.0, free_length=0.405, min_length=0.005, max_length=0.405)
    with pytest.raises(InvalidInput, match="material"):
        design_spring("compression", 1.0, 1.0, free_length=1, min_length=0.5, max_length=1, material="unobtainium")


def spring_problem(kind, moment, rng, bounds, design=None, **kw):
    """The JSON of a solved :class:`SpringProblem` and its fit."""
    d = SpringProblem(kind, moment, rng, bounds, design=None if design is None else SpringOptions(**design), **kw).solve()
    return d.to_dict(), d.fit


def test_unguided_long_spring_warns_about_buckling():
    out, _ = spring_problem("compression", 100.0, RAD, SpringBounds((0.05, 0.2), (0.1, 0.4), (0, 0.3), 1500.0),
                            design={"material": "oil-tempered"})
    assert not out["spring"]["buckling"]["safe"]
    assert any("buckles" in w for w in out["warnings"])
    out, _ = spring_problem("compression", 100.0, RAD, SpringBounds((0.05, 0.2), (0.1, 0.4), (0, 0.3), 1500.0),
                            design={"material": "oil-tempered", "guided": True})
    assert out["spring"]["buckling"]["safe"] and not any("buckles" in w for w in out["warnings"])


# --------------------------------------------------------------------- trade-offs
def test_bound_warnings_say_which_bound_to_move():
    b = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0))
    out, res = spring_problem("compression", 100.0, RAD, b, target_error=0.001)
    assert list(res.active_bounds[:3]) == ["r=min", "r0=max", "a=max"]
    sens = out["sensitivity"]
    assert {s["bound"] for s in sens} == {"r=min", "r0=max", "a=max"}
    assert all(s["error"] < res.max_rel_error for s in sens)  # each move helps ...
    assert sens == sorted(sens, key=lambda s: -s["gain"])  # ... and the best comes first
    on_bound, missed = out["warnings"]
    assert "trade-off" in on_bound and sens[0]["move"] in on_bound
    assert "misses the requested 0.1 %" in missed and out["target_met"] is False


def test_pareto_front_is_nondominated_and_contains_better_devices():
    b = SpringBounds(r=(0.01, 0.5), r0=(0.01, 1.0), a=(0.0, 1.0), max_force=2000.0, max_free_length=1.5)
    out, res = spring_problem("compression", 100.0, RAD, b, pareto=True, target_error=0.03)
    front = out["pareto"]
    keys = ("error", "size", "force")
    for p in front:
        for q in front:
            assert not (all(q[k] <= p[k] for k in keys) and any(q[k] < p[k] * (1 - 1e-6) for k in keys))
    # smaller devices cost error, stronger springs buy it back
    assert min(p["error"] for p in front) < res.max_rel_error < max(p["error"] for p in front)
    assert any("raise the maximum free length or the force limit" in w for w in out["warnings"])
    # every front point is a real device: its error recomputed from (c, r, r0, a)
    from balance.devices.springs import CrankRockerDevice

    phi = np.linspace(*RAD, 4001)
    for p in front[::5]:
        e = (CrankRockerDevice("compression", p["c"], p["r"], p["r0"], p["a"]).moment(phi) - 100 * np.sin(phi)) / 100
        assert np.max(np.abs(e)) == pytest.approx(p["error"], rel=1e-3)


# ------------------------------------------------ helical springs worked out by hand (EN 13906-1/-2)
# Music wire (EN 10270-1 DH): G = 81.5 GPa, E = 206 GPa, ρ = 7850 kg/m³, R_m = 2211·d^−0.145 MPa (d in mm).
G_MUSIC, E_MUSIC, RHO_MUSIC = 81.5e9, 206e9, 7850.0


def music_wire_strength(d):
    """R_m (Pa) of music wire of diameter d (m)."""
    return 2211e6 / (1e3 * d) ** 0.145


def coil_for_rate(c, d, n):
    """The mean coil diameter at which d and n give the rate c: D from c = G·d⁴/(8·D³·n)."""
    return (G_MUSIC * d ** 4 / (8 * c * n)) ** (1 / 3)


def corrected_stress(d, D, F):
    """Bergsträsser-corrected shear stress k·8·D·F/(π·d³), k = (w + 0.5)/(w − 0.75), w = D/d."""
    w = D / d
    return (w + 0.5) / (w - 0.75) * 8 * D * F / (math.pi * d ** 3)


def test_helical_compression_spring_by_hand():
    c, F, L0, Lmin, Lmax = 2000.0, 100.0, 0.5, 0.3, 0.45
    s = design_spring("compression", c, F, free_length=L0, min_length=Lmin, max_length=Lmax)
    d, n = s.wire_diameter_m, s.active_coils
    D = coil_for_rate(c, d, n)
    assert s.mean_diameter_m == pytest.approx(D, rel=1e-12)
    # two closed and ground end coils: total coils n + 2, solid length (n + 2)·d
    mass = RHO_MUSIC * math.pi * d ** 2 / 4 * math.pi * D * (n + 2)
    gaps = (0.0015 * D ** 2 / d + 0.1 * d) * n
    assert s.mass_kg == pytest.approx(mass, rel=1e-12)
    assert s.solid_length_m == pytest.approx((n + 2) * d, rel=1e-12)
    assert s.min_gap_sum_m == pytest.approx(gaps, rel=1e-12)
    assert (n + 2) * d + gaps <= Lmin
    tau, allowed = corrected_stress(d, D, F), 0.5 * music_wire_strength(d)
    assert s.max_shear_stress_Pa == pytest.approx(tau, rel=1e-12) and tau <= allowed
    assert s.allowed_shear_stress_Pa == pytest.approx(allowed, rel=1e-12)
    assert s.solid_shear_stress_Pa == pytest.approx(8 * D * c * (L0 - (n + 2) * d) / (math.pi * d ** 3), rel=1e-12)
    r = 1 - G_MUSIC / E_MUSIC  # pinned ends, ν = 1
    s_k = L0 * 0.5 / r * (1 - math.sqrt(1 - r / (0.5 + G_MUSIC / E_MUSIC) * (math.pi * D / L0) ** 2))
    assert s.buckling.critical_deflection_m == pytest.approx(s_k, rel=1e-12)
    assert s.buckling.max_deflection_m == pytest.approx(L0 - Lmin, rel=1e-12)
    out = s.to_dict()
    assert out["outer_diameter_m"] == pytest.approx(D + d, rel=1e-12)
    assert out["inner_diameter_m"] == pytest.approx(D - d, rel=1e-12)
    assert out["spring_index"] == pytest.approx(D / d, rel=1e-12) and out["total_coils"] == n + 2
    assert out["safe_when_solid"] == (out["solid_shear_stress_Pa"] <= allowed) and "initial_tension_N" not in out
    assert out["material_description"] == "patented cold-drawn spring steel, EN 10270-1 DH (ASTM A228)"
    assert out["elastic_modulus_Pa"] == E_MUSIC and out["buckling"]["seating_coefficient"] == 1.0


@pytest.mark.parametrize("bore_mm", [6.3, 6.6, 7.1, 7.6, 10.6, 10.7, 14.0])
def test_helical_spring_fits_its_bore(bore_mm):
    """The coil diameter re-solved from the half-coil count may land just past the bore (at 6.3 … 10.6 mm the
    widest coil of some wire does): that coil is refused and a narrower one chosen."""
    bore = bore_mm * 1e-3
    s = design_spring("compression", 2000.0, 100.0, free_length=0.5, min_length=0.3, max_length=0.45,
                      max_outer_diameter=bore)
    assert s.mean_diameter_m + s.wire_diameter_m <= bore * (1 + 1e-9)


def test_helical_candidates_cover_the_coil_range():
    """Every half-coil count from the widest coil's (the fewest coils) to the narrowest's is offered, at the rate."""
    c, d = 500.0, 0.002
    lo, hi = 4 * d, 20 * d
    got = list(_candidates(MATERIALS["music-wire"], "compression", c, d, lo, hi))
    ns = [n for _, n in got]
    # 5 coils at D = 40 mm … 636.5 coils at D = 8 mm, every half coil between
    assert ns[0] == round(2 * G_MUSIC * d ** 4 / (8 * hi ** 3 * c)) / 2 == 5.0
    assert ns[-1] == round(2 * G_MUSIC * d ** 4 / (8 * lo ** 3 * c)) / 2 == 636.5
    assert ns == [k / 2 for k in range(10, 1274)]
    assert all(D == pytest.approx(coil_for_rate(c, d, n), rel=1e-12) for D, n in got)
    # a range of no width (or reversed) holds no coil: no count of half coils gives exactly that diameter
    assert list(_candidates(MATERIALS["music-wire"], "compression", c, d, 0.01, 0.01)) == []
    assert list(_candidates(MATERIALS["music-wire"], "compression", c, d, 0.02, 0.01)) == []


def lightest_by_enumeration(kind, c, F, free_length=None, min_length=None):
    """The lightest music-wire spring (buckling-safe first) over every wire of the series and every half-coil
    count, the checks written out from EN 13906-1's definitions: (mass, wire, active coils)."""
    best = None
    for d_mm in (x for x in WIRE_SERIES_MM if 0.1 <= x <= 6.5):
        d = d_mm * 1e-3
        for twice_n in range(4, math.ceil(2 * G_MUSIC * d / (8 * 4 ** 3 * c)) + 2):
            n = twice_n / 2
            D = coil_for_rate(c, d, n)
            allowed = (0.5 if kind == "compression" else 0.45) * music_wire_strength(d)
            if not 4 - 1e-9 <= D / d <= 20 + 1e-9 or corrected_stress(d, D, F) > allowed:
                continue
            mass = RHO_MUSIC * math.pi * d * d / 4 * math.pi * D * (n + (2 if kind == "compression" else 3))
            buckles = False
            if kind == "compression":
                if min_length < (n + 2) * d + (0.0015 * D * D / d + 0.1 * d) * n - 1e-12:
                    continue
                buckles = not free_length - min_length < buckling_deflection(free_length, D, G_MUSIC, E_MUSIC, 1.0)
            if best is None or (buckles, mass) < best[0]:
                best = ((buckles, mass), d, n)
    return best[0][1], best[1], best[2]


@pytest.mark.parametrize("kind, c, F, lengths", [
    ("extension", 1515.699505563206, 57.44211824541962, {}),  # 22.5 coils of 1.12 mm wire (160 sampled coils: 23)
    ("extension", 200.5510312559761, 46.27968248839384, {}),  # 1.25 mm wire (sampled: 1.12 mm, 2 % heavier)
    ("extension", 20000.0, 300.0, {}),
    ("compression", 2000.0, 100.0, {"free_length": 0.5, "min_length": 0.3}),
    ("compression", 800.0, 150.0, {"free_length": 0.3, "min_length": 0.12}),
])
def test_helical_spring_is_the_lightest_of_every_wire_and_half_coil(kind, c, F, lengths):
    """The design is the lightest spring that passes every check, found by trying every wire and half coil."""
    kw = dict(lengths, max_length=lengths["free_length"]) if lengths else {}
    s = design_spring(kind, c, F, **kw)
    mass, d, n = lightest_by_enumeration(kind, c, F, **lengths)
    assert (s.wire_diameter_m, s.active_coils) == (d, n)
    assert s.mass_kg == pytest.approx(mass, rel=1e-12)


def test_helical_spring_index_may_be_exactly_twenty():
    """The thinnest wire wound at index 20 with a whole number of coils: that widest (lightest) coil is taken."""
    d, n = 0.0001, 40.0
    c = G_MUSIC * d / (8 * 20 ** 3 * n)  # the rate of 40 coils at D = 20·d
    s = design_spring("extension", c, 0.01)
    assert (s.wire_diameter_m, s.active_coils) == (d, n)
    assert s.spring_index == pytest.approx(20.0, rel=1e-12)


def test_helical_spring_may_fill_its_bore_and_hug_its_rod_exactly():
    """The thinnest wire's coil of 30 active coils at index 12 with a bore and a rod that leave it no play: it
    fits (the limits hold to 1e-9 of their size), and nothing else does."""
    d, n = 0.0001, 30.0
    D = 12 * d
    c = G_MUSIC * d ** 4 / (8 * D ** 3 * n)
    s = design_spring("extension", c, 0.01, max_outer_diameter=D + d, min_inner_diameter=D - d)
    assert (s.wire_diameter_m, s.active_coils) == (d, n)
    assert s.outer_diameter_m == pytest.approx(D + d, rel=1e-12)
    assert s.inner_diameter_m == pytest.approx(D - d, rel=1e-12)


def test_helical_refusal_names_a_coil_past_its_bore():
    """A rod and a bore that leave the thinnest wire only the coil of 30 coils at index 12, 1 µm too wide: the
    refusal names that coil and its outer diameter against the bore."""
    d, n = 0.0001, 30.0
    D = 12 * d
    c = G_MUSIC * d ** 4 / (8 * D ** 3 * n)
    with pytest.raises(NoSpringFits) as ei:
        design_spring("extension", c, 0.01, max_outer_diameter=D + d - 1e-6, min_inner_diameter=D - d - 1e-6)
    assert str(ei.value) == (
        f"no music-wire spring of {c:.4g} N/m for 0.01 N fits (outer diameter ≤ 1.299 mm, inner diameter ≥ 1.099 mm): "
        f"the closest, wire 0.1 mm on a 1.2 mm coil with 30 active coils, fails because its outer diameter 1.3 mm "
        f"exceeds 1.299 mm; try a larger outer diameter.")


def refusal_parts(message):
    """Wire d (m) and active coils n of the closest candidate a refusal names."""
    m = re.search(r"the closest, wire ([\d.]+) mm on a [\d.]+ mm coil with ([\d.]+) active coils", message)
    return float(m.group(1)) * 1e-3, float(m.group(2))


def test_helical_refusal_sentences_in_full():
    hint_stress = ("a lower peak force (a force limit on the device) or a material drawn thicker "
                   "(oil-tempered, up to 12.7 mm)")
    # 10 kN at 10 kN/m on music wire: too much stress for every wire
    with pytest.raises(NoSpringFits) as ei:
        design_spring("extension", 10000.0, 10000.0, max_deflection=0.5)
    d, n = refusal_parts(str(ei.value))
    D = coil_for_rate(1e4, d, n)
    tau, allowed = corrected_stress(d, D, 1e4), 0.45 * music_wire_strength(d)
    assert str(ei.value) == (
        f"no music-wire spring of 1e+04 N/m for 1e+04 N fits: the closest, wire {1e3 * d:.3g} mm on a "
        f"{1e3 * D:.4g} mm coil with {n:g} active coils, fails because its shear stress {tau / 1e6:.4g} MPa "
        f"exceeds the allowed {allowed / 1e6:.4g} MPa; try {hint_stress}.")
    # 5 mm shortest length: no spring's solid length and gaps fit
    with pytest.raises(NoSpringFits) as ei:
        design_spring("compression", 500.0, 200.0, free_length=0.405, min_length=0.005, max_length=0.405)
    d, n = refusal_parts(str(ei.value))
    D = coil_for_rate(500.0, d, n)
    least = (n + 2) * d + (0.0015 * D * D / d + 0.1 * d) * n
    assert str(ei.value) == (
        f"no music-wire spring of 500 N/m for 200 N fits: the closest, wire {1e3 * d:.3g} mm on a {1e3 * D:.4g} mm "
        f"coil with {n:g} active coils, fails because its solid length plus the minimum coil gaps "
        f"({1e3 * least:.4g} mm) exceed the shortest working length 5 mm; try a longer spring (larger r0 or a).")
    # a 30 mm rod inside a 34 mm bore: the closest is both too tight on the rod and too stressed
    with pytest.raises(NoSpringFits) as ei:
        design_spring("compression", 2000.0, 100.0, free_length=0.5, min_length=0.3, max_length=0.45,
                      min_inner_diameter=0.03, max_outer_diameter=0.034)
    d, n = refusal_parts(str(ei.value))
    D = coil_for_rate(2000.0, d, n)
    tau, allowed = corrected_stress(d, D, 100.0), 0.5 * music_wire_strength(d)
    assert D - d < 0.03 and tau > allowed
    assert str(ei.value) == (
        f"no music-wire spring of 2000 N/m for 100 N fits (outer diameter ≤ 34 mm, inner diameter ≥ 30 mm): the "
        f"closest, wire {1e3 * d:.3g} mm on a {1e3 * D:.4g} mm coil with {n:g} active coils, fails because its "
        f"inner diameter {1e3 * (D - d):.4g} mm does not clear 30 mm and its shear stress {tau / 1e6:.4g} MPa "
        f"exceeds the allowed {allowed / 1e6:.4g} MPa; try a thinner guide rod or {hint_stress}.")
    # a 50 mm rod in a 54 mm bore: no wire of the series gives any coil there
    with pytest.raises(NoSpringFits) as ei:
        design_spring("compression", 2000.0, 100.0, free_length=0.5, min_length=0.3, max_length=0.45,
                      min_inner_diameter=0.05, max_outer_diameter=0.054)
    assert str(ei.value) == ("no music-wire wire of the series gives a spring of 2000 N/m in the space given "
                             "(outer diameter ≤ 54 mm, inner diameter ≥ 50 mm); allow a larger outer diameter or "
                             "another material.")


def test_helical_extension_spring_for_a_tension_device():
    b = SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.4), a=(0.0, 0.3), max_force=1500.0)
    res = fit_spring("tension", -100.0, RAD, b)
    s = design_for_device(res, material="oil-tempered")  # G = 79.5 GPa, ρ = 7850 kg/m³
    assert s.material == "oil-tempered" and s.kind == "extension"
    d, D, n = s.wire_diameter_m, s.mean_diameter_m, s.active_coils
    assert 79.5e9 * d ** 4 / (8 * D ** 3 * n) == pytest.approx(res.c, rel=1e-9)
    # close-wound body of n + 1 coils and two loops of about one inner diameter each (one coil of wire each)
    free = (n + 1) * d + 2 * (D - d)
    assert s.body_length_m == pytest.approx((n + 1) * d, rel=1e-12)
    assert s.free_length_m == pytest.approx(free, rel=1e-12) and s.loop_length_m == pytest.approx(D - d, rel=1e-12)
    assert s.mass_kg == pytest.approx(7850.0 * math.pi * d ** 2 / 4 * math.pi * D * (n + 3), rel=1e-12)
    assert s.anchor_offset_m == pytest.approx(res.free_length - free, rel=1e-12)
    out = s.to_dict()
    assert out["initial_tension_N"] == 0.0 and out["total_coils"] == n + 1 and "buckling" not in out


def test_helical_spring_may_close_to_its_minimum_gaps():
    """A spring whose solid length plus minimum coil gaps just reach the shortest working length is accepted,
    also at the edge of the 1e-12 m tolerance."""
    s = design_spring("compression", 2000.0, 300.0, free_length=0.5, min_length=0.3, max_length=0.45)
    d, D, n = s.wire_diameter_m, s.mean_diameter_m, s.active_coils
    least = (n + 2) * d + (0.0015 * D * D / d + 0.1 * d) * n
    assert least == pytest.approx(s.solid_length_m + s.min_gap_sum_m, rel=1e-12)
    for shortest in (least, s.solid_length_m + s.min_gap_sum_m - 1e-12):
        t = design_spring("compression", 2000.0, 300.0, free_length=0.5, min_length=shortest, max_length=0.45)
        assert (t.wire_diameter_m, t.active_coils) == (d, n) and t.min_working_length_m == shortest


@pytest.mark.parametrize("force, shortest, reason", [(300.0, 0.02, "solid"), (600.0, 0.04, "stress")])
def test_helical_refusal_names_the_least_failing_candidate(force, shortest, reason):
    """Thin wires are over-stressed, thick ones too long when closed: the refusal names the candidate that
    misses by the smallest fraction (58.6 % too long at 300 N; 44.4 % over-stressed at 600 N)."""
    with pytest.raises(NoSpringFits) as ei:
        design_spring("compression", 2000.0, force, free_length=0.5, min_length=shortest, max_length=0.45)
    d, n = refusal_parts(str(ei.value))
    D = coil_for_rate(2000.0, d, n)
    least = (n + 2) * d + (0.0015 * D * D / d + 0.1 * d) * n
    tau, allowed = corrected_stress(d, D, force), 0.5 * music_wire_strength(d)
    head = (f"no music-wire spring of 2000 N/m for {force:.4g} N fits: the closest, wire {1e3 * d:.3g} mm on a "
            f"{1e3 * D:.4g} mm coil with {n:g} active coils, fails because its ")
    if reason == "solid":
        assert (least - shortest) / shortest == pytest.approx(0.586, abs=1e-3) and tau <= allowed
        assert str(ei.value) == head + (
            f"solid length plus the minimum coil gaps ({1e3 * least:.4g} mm) exceed the shortest working length "
            f"{1e3 * shortest:.4g} mm; try a longer spring (larger r0 or a).")
    else:
        assert tau / allowed - 1 == pytest.approx(0.444, abs=1e-3) and least <= shortest
        assert str(ei.value) == head + (
            f"shear stress {tau / 1e6:.4g} MPa exceeds the allowed {allowed / 1e6:.4g} MPa; try a lower peak force "
            "(a force limit on the device) or a material drawn thicker (oil-tempered, up to 12.7 mm).")


def test_helical_unguided_spring_that_cannot_buckle_is_preferred():
    """Unguided, a heavier spring that cannot buckle beats the lightest, which would buckle by EN 13906-1."""
    L0, Lmin, Lmax = 0.1, 0.06, 0.09
    free = design_spring("compression", 2000.0, 100.0, free_length=L0, min_length=Lmin, max_length=Lmax)
    guided = design_spring("compression", 2000.0, 100.0, free_length=L0, min_length=Lmin, max_length=Lmax, guided=True)
    assert guided.buckling.guided is True and guided.buckling.critical_deflection_m == math.inf
    assert free.buckling.guided is False and free.buckling.safe and guided.mass_kg < free.mass_kg
    r = 1 - G_MUSIC / E_MUSIC  # the guided (lighter) spring's critical deflection with pinned ends, ν = 1
    s_k = L0 * 0.5 / r * (1 - math.sqrt(1 - r / (0.5 + G_MUSIC / E_MUSIC) * (math.pi * guided.mean_diameter_m / L0) ** 2))
    assert s_k < L0 - Lmin


def test_helical_spring_reports_its_rate_error_and_wire_strength():
    s = design_spring("compression", 2000.0, 100.0, free_length=0.5, min_length=0.3, max_length=0.45)
    d, D, n = s.wire_diameter_m, s.mean_diameter_m, s.active_coils
    out = s.to_dict()
    assert out["stiffness_error"] == pytest.approx(G_MUSIC * d ** 4 / (8 * D ** 3 * n) / 2000.0 - 1, abs=1e-12)
    assert abs(out["stiffness_error"]) < 1e-12
    assert out["tensile_strength_Pa"] == pytest.approx(music_wire_strength(d), rel=1e-12)
    assert out["stress_ratio"] == pytest.approx(corrected_stress(d, D, 100.0) / (0.5 * music_wire_strength(d)))


@pytest.mark.parametrize("miss, named", [
    ({"rod": 1e-7, "stress": True}, "rod"),  # the rod's 0.1 µm, not the stress's percent
    ({"rod": 1e-6, "bore": 1e-7}, "bore"),  # 0.1 µm on the bore, 1 µm on the rod
    ({"rod": 1e-7, "bore": 1e-6}, "rod"),
])
def test_helical_refusal_names_the_coil_that_misses_by_less(miss, named):
    """Two coils of the thinnest wire are left: 30 coils at index 12, whose inner diameter may miss the rod, and
    29.5 coils, a wider coil that may overrun the bore or be stressed 2 % past the allowed stress.  Each fails
    once; the refusal names the one that misses by the smaller fraction of its limit."""
    d, n = 0.0001, 30.0
    D0 = 12 * d
    c = G_MUSIC * d ** 4 / (8 * D0 ** 3 * n)
    D1 = coil_for_rate(c, d, n - 0.5)
    rod, bore = D0 - d + miss["rod"], D1 + d - miss.get("bore", 0.0)
    F = 0.45 * music_wire_strength(d) / corrected_stress(d, D0, 1.0) * (1 - 1e-6) if "stress" in miss else 0.01
    with pytest.raises(NoSpringFits) as ei:
        design_spring("extension", c, F, max_outer_diameter=bore, min_inner_diameter=rod)
    if named == "rod":
        coil = "1.2 mm coil with 30 active coils"
        why = f"its inner diameter {1e3 * (D0 - d):.4g} mm does not clear {1e3 * rod:.4g} mm; try a thinner guide rod."
    else:
        coil = f"{1e3 * D1:.4g} mm coil with 29.5 active coils"
        why = f"its outer diameter {1e3 * (D1 + d):.4g} mm exceeds {1e3 * bore:.4g} mm; try a larger outer diameter."
    assert str(ei.value) == (
        f"no music-wire spring of {c:.4g} N/m for {F:.4g} N fits (outer diameter ≤ {1e3 * bore:.4g} mm, inner "
        f"diameter ≥ {1e3 * rod:.4g} mm): the closest, wire 0.1 mm on a {coil}, fails because {why}")


def test_helical_refusal_weighs_a_spring_index_past_twenty_by_its_quarter():
    """The thinnest wire has two coils left: 20 coils at index 20.008 (0.008 past the band, a quarter of it:
    0.002) and 20.5 coils whose inner diameter misses the rod by 0.3 % — the index is named, to four digits."""
    d = 0.0001
    D_A = 20 * d * 1.0004
    c = G_MUSIC * d ** 4 / (8 * D_A ** 3 * 20)
    D_B = coil_for_rate(c, d, 20.5)
    rod, bore = D_B * 1.003 - d, (D_A + d) * (1 + 1e-6)
    assert 0.008 / 4 < 1 - (D_B - d) / rod < 0.008
    with pytest.raises(NoSpringFits) as ei:
        design_spring("extension", c, 0.01, max_outer_diameter=bore, min_inner_diameter=rod)
    assert str(ei.value) == (
        f"no music-wire spring of {c:.4g} N/m for 0.01 N fits (outer diameter ≤ {1e3 * bore:.4g} mm, inner "
        f"diameter ≥ {1e3 * rod:.4g} mm): the closest, wire 0.1 mm on a {1e3 * D_A:.4g} mm coil with 20 active "
        f"coils, fails because its spring index D/d = 20.01 is outside 4 … 20; try another wire size or material.")


def test_helical_refusal_when_only_coils_past_index_twenty_would_fill_the_space():
    """A 25 mm rod in a 27.5 mm bore: wires up to 1.25 mm would need an index above 20 to reach the rod, thicker
    ones overrun the bore — no wire of the series gives a coil there at all."""
    with pytest.raises(NoSpringFits) as ei:
        design_spring("extension", 100.0, 1.0, max_outer_diameter=0.0275, min_inner_diameter=0.025)
    assert str(ei.value) == ("no music-wire wire of the series gives a spring of 100 N/m in the space given "
                             "(outer diameter ≤ 27.5 mm, inner diameter ≥ 25 mm); allow a larger outer diameter or "
                             "another material.")


def test_helical_compression_spring_made_as_short_as_it_may_be():
    """Without a free length the spring is its solid length, the minimum gaps and the deflection asked for."""
    s = design_spring("compression", 2000.0, 100.0, max_deflection=0.05, guided=True)
    d, D, n = s.wire_diameter_m, s.mean_diameter_m, s.active_coils
    shortest = (n + 2) * d + (0.0015 * D * D / d + 0.1 * d) * n
    assert s.min_working_length_m == pytest.approx(shortest, rel=1e-12)
    assert s.free_length_m == s.max_working_length_m == pytest.approx(shortest + 0.05, rel=1e-12)
    assert s.buckling.max_deflection_m == pytest.approx(0.05, rel=1e-12)


def test_helical_refusal_states_the_allowed_stress_of_its_wire():
    """A rod and a bore 1 mm either side of an 8 mm coil leave 1 mm wire one coil, 20 % over its allowed stress
    (0.45 · 2211 MPa = 994.95 MPa, said as 995 MPa), and every thinner wire more: the refusal names it."""
    d, n = 0.001, 10.0
    D = 8 * d
    c = G_MUSIC * d ** 4 / (8 * D ** 3 * n)
    allowed = 0.45 * music_wire_strength(d)
    F = 1.2 * allowed / corrected_stress(d, D, 1.0)
    with pytest.raises(NoSpringFits) as ei:
        design_spring("extension", c, F, max_outer_diameter=D + d, min_inner_diameter=D - d)
    assert f"{allowed / 1e6:.4g}" == "995"
    assert str(ei.value) == (
        f"no music-wire spring of {c:.4g} N/m for {F:.4g} N fits (outer diameter ≤ 9 mm, inner diameter ≥ 7 mm): "
        f"the closest, wire 1 mm on a 8 mm coil with 10 active coils, fails because its shear stress "
        f"{1.2 * allowed / 1e6:.4g} MPa exceeds the allowed 995 MPa; try a lower peak force (a force limit on the "
        f"device) or a material drawn thicker (oil-tempered, up to 12.7 mm).")


def test_helical_candidates_reach_two_active_coils():
    """At 1600 N/m the widest coil of 2 mm wire would need 1.6 coils: the candidates start at two."""
    c, d = 1600.0, 0.002
    ns = [n for _, n in _candidates(MATERIALS["music-wire"], "compression", c, d, 4 * d, 20 * d)]
    assert G_MUSIC * d ** 4 / (8 * (20 * d) ** 3 * c) < 2 and ns[0] == 2.0


@pytest.mark.parametrize("args, kw, sentence", [
    (("torsion", 1.0, 1.0), {}, "a helical spring is 'compression' or 'extension', not 'torsion'."),
    (("compression", 1.0, 1.0), {"material": "unobtainium"},
     "unknown spring material 'unobtainium'; choose one of music-wire, oil-tempered, chrome-vanadium, "
     "chrome-silicon, stainless."),
    (("compression", 1.0, 1.0), {"ends": "free"},
     "unknown end condition 'free'; choose one of fixed-free, pinned, fixed-pinned, fixed."),
    (("compression", 0.0, 1.0), {}, "the spring's stiffness must be a positive number, not 0.0."),
    (("compression", 1.0, math.nan), {}, "the spring's peak force must be a positive number, not nan."),
    (("compression", 1.0, 1.0), {"max_outer_diameter": -0.01}, "the largest outer diameter must be positive, not -0.01."),
    (("compression", 1.0, 1.0), {"min_inner_diameter": -1.0}, "the smallest inner diameter must be ≥ 0, not -1.0."),
    (("compression", 1.0, 1.0), {}, "a compression spring needs its free length or its largest deflection."),
])
def test_helical_input_refusals_in_full(args, kw, sentence):
    with pytest.raises(InvalidInput) as ei:
        design_spring(*args, **kw)
    assert str(ei.value) == sentence


@pytest.mark.parametrize("degrees", [(20.0, 160.0), (-150.0, 170.0), (-100.0, 200.0)])
def test_helical_lever_spring_is_guided_and_tension_spring_reports_its_stretch(degrees):
    """The longest a tension device's spring gets, also over ranges holding a dead centre (φ = 0, ±π)."""
    rng = tuple(math.radians(v) for v in degrees)
    b = SpringBounds(r=(0.05, 0.2), r0=(0.1, 0.4), a=(0.0, 0.3), max_force=1500.0)
    lever = design_for_device(fit_spring("compression-lever", -100.0, RAD, b), material="chrome-silicon")
    assert lever.buckling.guided is True and lever.buckling.critical_deflection_m == math.inf
    res = fit_spring("tension", -100.0, rng, b)
    s = design_for_device(res, material="oil-tempered")
    longest = float(np.max(res.device.length(np.linspace(*rng, 200001))))  # a dense sweep of the crank
    assert s.max_extension_m == pytest.approx(longest - res.free_length, abs=1e-9)


def test_helical_spring_for_a_slider_device_takes_the_options():
    """A sine (slider) device's compression spring runs from a to the largest force; material and ends pass."""
    res = fit_spring("compression", 30.0, RAD, SpringBounds((0.05, 0.2), None, (0.0, 0.2)), device="sine")
    s = design_for_device(res, material="oil-tempered", ends="fixed", guided=False)
    assert s.material == "oil-tempered" and s.buckling.end_condition == "fixed"
    assert s.buckling.seating_coefficient == 0.5
    assert s.free_length_m == pytest.approx(res.free_length, rel=1e-12)
    assert s.min_working_length_m == pytest.approx(res.free_length - res.max_force / res.c, rel=1e-12)
    assert s.max_working_length_m == pytest.approx(res.free_length - res.a, rel=1e-12)
