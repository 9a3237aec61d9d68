"""The compression-lever device, helical spring design (EN 13906-1 formulas) and fit trade-offs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import InfeasibleBounds, InvalidInput, SpringBounds, SpringOptions, SpringProblem, fit_spring
from balance.devices.helical import (
    MATERIALS, NoSpringFits, WIRE_SERIES_MM, bergstraesser, buckling_deflection, design_for_device, design_spring,
)
from balance.devices.tradeoff import bound_sensitivity

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
    if sp["kind"] == "compression":
        assert sp["solid_length_m"] == pytest.approx((n + 2) * d)
        assert sp["solid_length_m"] + sp["min_gap_sum_m"] <= sp["min_working_length_m"] + 1e-12


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
