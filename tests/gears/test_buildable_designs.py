"""Designed tooth numbers can be built: the engine's best designs against a brute force over every
tooth number (and every mesh kind) of small ranges, each candidate's ratio re-derived by an exact
Willis solve (tests/oracles/gear_ratios.py) and its buildability by placing the carriers' axes in
the plane (tests/oracles/gear_build.py).  Each rule is shown to matter: without it the brute
force's best designs break it.
"""

from __future__ import annotations

import itertools
import json
from math import gcd
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest

from synth.gears import GearTrain
from synth.gears.ratio_design import NoDesign, carrier_cycles, design, planet_clearance
from tests.oracles import gear_build, gear_ratios

KINDS = ("ext", "first", "second")  # a mesh external, or internal with its first / second gear the ring


def _variants(layout: GearTrain, free: bool):
    """(kinds, oracle meshes (a, b, carrier, internal) with a the ring) of the layout."""
    choices = itertools.product(KINDS, repeat=len(layout.meshes)) if free else [
        tuple("first" if inner else "ext" for inner in layout.internal)]
    for kinds in choices:
        yield kinds, [((b, a) if k == "second" else (a, b)) + (t, k != "ext")
                      for (a, b), t, k in zip(layout.meshes, layout.carriers, kinds)]


def _float_ratios(meshes, links: int, grid: np.ndarray, wheels, frame: int, driver: int, driven: int):
    """i = ω_driver/ω_driven for every row of tooth numbers in ``grid`` (columns: ``wheels``), by
    the Willis equations in floating point (a filter; NaN where the speeds are not fixed)."""
    unknown = [x for x in range(links) if x not in (frame, driver)]
    col = {x: i for i, x in enumerate(unknown)}
    z = {w: grid[:, j].astype(float) for j, w in enumerate(wheels)}
    a_mat = np.zeros((len(grid), len(meshes), len(unknown)))
    rhs = np.zeros((len(grid), len(meshes)))
    for row, (a, b, t, internal) in enumerate(meshes):
        za, zb = z[a], (-z[b] if internal else z[b])  # za(ωa − ωt) + zb(ωb − ωt) = 0
        for x, c in ((a, za), (b, zb), (t, -za - zb)):
            if x == driver:
                rhs[:, row] -= c
            elif x != frame:
                a_mat[:, row, col[x]] += c
    out = np.full(len(grid), np.nan)
    ok = np.abs(np.linalg.det(a_mat)) > 1e-9
    speeds = np.linalg.solve(a_mat[ok], rhs[ok][..., None])[..., 0]
    with np.errstate(divide="ignore"):
        out[ok] = 1.0 / speeds[:, col[driven]]
    return out


def brute_force(layout: GearTrain, frame: int, driver: int, driven: int, target: Fraction, tol: Fraction,
                teeth: tuple[int, int], *, free: bool = False, planets: int | None = None, ignore: str | None = None):
    """Every design within the tolerance that the oracle finds buildable, best first: (error, tooth
    sum, teeth, kinds, problems); with ``ignore`` also those whose only problems name it (a rule
    left out, to show what it removes)."""
    wheels = sorted({x for m in layout.meshes for x in m})
    grid = np.array(list(itertools.product(range(teeth[0], teeth[1] + 1), repeat=len(wheels))))
    found = []
    for kinds, meshes in _variants(layout, free):
        close = _float_ratios(meshes, layout.links, grid, wheels, frame, driver, driven)
        near = np.abs(close - float(target)) <= float(tol * abs(target)) + 1e-9
        for z in grid[near]:
            t = dict(zip(wheels, map(int, z)))
            try:
                exact = gear_ratios.ratio(meshes, layout.links, t, frame, driver, driven)
            except (ValueError, ZeroDivisionError):
                continue
            error = abs(exact - target) / abs(target)
            if error > tol:
                continue
            problems = gear_build.problems(meshes, [set(a) for a in layout.axes], t, frame=frame, planets=planets)
            if any(ignore is None or ignore not in problem for problem in problems):
                continue
            found.append((error, sum(t.values()), tuple(t.values()), kinds, problems))
    return sorted(found)


def _oracle_meshes(train: GearTrain):
    return [(a, b, t, inner) for (a, b, t), inner in zip(train.triples, train.internal)]


def _teeth_by_link(d) -> dict:
    return {int(name[1:]): z for name, z in d.teeth.items()}


def _assert_buildable(d, layout: GearTrain, frame: int, driver: int, driven: int, target, tol, planets=None):
    train = d.train or layout
    teeth = _teeth_by_link(d)
    meshes = _oracle_meshes(train)
    assert gear_ratios.ratio(meshes, train.links, teeth, frame, driver, driven) == d.ratio
    assert abs(d.ratio - target) / abs(target) == d.error <= tol
    assert gear_build.problems(meshes, [set(a) for a in train.axes], teeth, frame=frame, planets=planets) == []


# ------------------------------------------------------------------ a carrier with three axes
# Issue 37's train: carrier 0 holds three axes, A (0, 1, 4), B (0, 2) and C (0, 3); gears 1 and 4
# on A, 2 on B, 3 on C; meshes 1~2 (A–B), 2~3 (B–C), 3~4 (C–A).
THREE_AXES = GearTrain.parse("0-1-4 0-2 0-3 1~2 2~3 4~3i")


def test_carrier_cycles_name_the_triangle():
    assert carrier_cycles(THREE_AXES) == [(0, [[0], [1], [2]])]
    assert carrier_cycles(GearTrain.parse("0-1-2 2-3 0~3i 1~3")) == []  # two axes: one distance


def test_triangle_inequality_is_kept_and_needed():
    """Carrier fixed (frame 0), input 1, output 3: i = z3/z1 whatever the idlers 2 and 4.  The ring 4
    closes the triangle A–B–C only when 2·z3 ≤ z1 + z4: for i = 28/17 the least tooth sums
    (z4 = z3 + 10 = 38) break it, z4 = 39 closes it."""
    target, tol, teeth = Fraction(28, 17), Fraction(0), (17, 40)
    loose = brute_force(THREE_AXES, 0, 1, 3, target, tol, teeth, ignore="cannot hold its axes")
    assert any(p for *_, p in loose[:6])  # without the rule the best designs break it
    found = design(THREE_AXES, 0, 1, 3, "28/17", tolerance="0", teeth=teeth, best=6)
    kept = brute_force(THREE_AXES, 0, 1, 3, target, tol, teeth)
    assert [(d.error, sum(d.teeth.values())) for d in found] == [k[:2] for k in kept[:6]]
    for d in found:
        _assert_buildable(d, THREE_AXES, 0, 1, 3, target, tol)
        z = _teeth_by_link(d)
        assert 2 * z[3] <= z[1] + z[4]


def test_four_axes_on_a_carrier_close_as_a_quadrilateral():
    """Frame 0 carries axes A (1, 4), B (2), C (3), D (5), meshed around A–B–C–D–A: i = z4/z1 through
    the idlers 2, 3, 5.  For i = 6 with z1 = 17, z4 = 102: the side D–A (z4 + z5) is at most the
    other three (z1 + 2·z2 + 2·z3 + z5) only when z2 + z3 ≥ 43, so the least idlers (17, 17) do
    not close and the best design is 17, 17, 26, 102, 17 (tooth sum 179)."""
    train = GearTrain.parse("0-1-4 0-2 0-3 0-5 1~2 2~3 3~5 4~5")
    assert carrier_cycles(train) == [(0, [[0], [1], [2], [3]])]
    found = design(train, 0, 1, 4, "6", tolerance="0", teeth=(17, 110), best=3)
    assert found[0].teeth == {"z1": 17, "z2": 17, "z3": 26, "z4": 102, "z5": 17}
    for d in found:
        z = _teeth_by_link(d)
        sides = [z[1] + z[2], z[2] + z[3], z[3] + z[5], z[4] + z[5]]
        assert all(2 * side <= sum(sides) for side in sides) and sum(d.teeth.values()) == 179


def test_a_carrier_with_four_axes_at_mutually_fixed_distances_is_refused():
    """Eight links: carrier 0 holds axes whose meshes join four of them pairwise (a K4 minor): the
    polygon inequalities no longer place them, and the design says so instead of guessing."""
    train = GearTrain.parse("0-1-4-6 0-2-7 0-3 0-5 1~2 2~3 3~4 3~5 5~6 5~7")
    with pytest.raises(NoDesign, match="four axes at mutually fixed distances"):
        carrier_cycles(train)
    with pytest.raises(NoDesign, match="four axes"):
        design(train, 0, 1, 2, "2", tolerance="1%", teeth=(17, 40))


def test_issue_37_free_kinds_five_links_are_buildable():
    """The issue's query: every design listed over the 5-link atlas is buildable, its ratio exact."""
    out = subprocess.run([sys.executable, "-m", "mechsynth", "gears", "--links", "5", "--ratio", "5", "--tolerance",
                          "0.5%", "--teeth", "17..80", "--best", "10", "--format", "jsonl"],
                         capture_output=True, text=True)
    rows = [json.loads(line) for line in out.stdout.splitlines()]
    assert out.returncode == 0 and len(rows) == 10
    for r in rows:
        train = GearTrain.parse(r["train"], r["frame"])
        teeth = {int(k[1:]): v for k, v in r["teeth"].items()}
        meshes = _oracle_meshes(train)
        assert gear_ratios.ratio(meshes, train.links, teeth, r["frame"], r["input_link"], r["output_link"]) == 5
        assert gear_build.problems(meshes, [set(a) for a in train.axes], teeth, frame=r["frame"]) == []


def test_free_kinds_on_three_axes_equal_the_brute_force():
    """Every mesh kind of the three-axis layout (27 trains), teeth 17..30, frame 1, input 0, output 4:
    the engine's best are the brute force's best buildable designs; without the rule of one kind
    per wheel the brute force's best break it."""
    layout = GearTrain.parse("0-1-4 0-2 0-3 1~2 2~3 3~4")
    target, tol, teeth = Fraction(6), Fraction(1, 100), (17, 30)
    loose = brute_force(layout, 1, 0, 4, target, tol, teeth, free=True, ignore="both a ring and an external gear")
    assert any(p for *_, p in loose[:8])  # without the rule the best designs break it
    kept = brute_force(layout, 1, 0, 4, target, tol, teeth, free=True)
    found = design(layout, 1, 0, 4, "6", tolerance="1%", teeth=teeth, best=8, kinds="free")
    assert [(d.error, sum(d.teeth.values())) for d in found] == [k[:2] for k in kept[:8]]
    for d in found:
        _assert_buildable(d, layout, 1, 0, 4, target, tol)


def test_one_kind_per_wheel_refused_for_a_given_train_and_allowed_for_a_compound_link():
    ring_and_pinion = GearTrain.parse("0-1-4 0-2 0-3 1~2 3~2i 3~4")  # wheel 3: ring of 2, pinion of 4
    with pytest.raises(NoDesign, match="wheel z3 is the ring of mesh 3~2i and an external gear of mesh 3~4.*--compound"):
        design(ring_and_pinion, 1, 0, 4, "5", tolerance="1%", teeth=(17, 80))
    found = design(ring_and_pinion, 1, 0, 4, "5", tolerance="1%", teeth=(17, 80), compound=[3], best=2)
    assert found and all({"z3_2", "z3_4"} <= set(d.teeth) for d in found)


# ------------------------------------------------------------------ planets that clear each other
def test_planet_clearance_is_the_least_distance():
    for k in range(2, 9):
        for zp in range(17, 90):
            least = planet_clearance(k, zp)
            assert least * np.sin(np.pi / k) > zp + 2 >= (least - 1) * np.sin(np.pi / k) - 1e-12
    assert planet_clearance(6, 20) == 45  # 44·sin 30° = 22 = 20 + 2 exactly: touching is refused
    assert planet_clearance(1, 50) == 0


@pytest.mark.parametrize("planets,ratio,lowest,touching", [(3, "6", 17, False), (4, "6", 12, True),
                                                           (5, "3.5", 17, False), (6, "4.2", 17, True)])
def test_simple_planetary_planets_clear_and_equal_the_brute_force(planets, ratio, lowest, touching):
    """Ring 0 fixed, sun 1 in, carrier 2 out: i = 1 + z0/z1.  The brute force keeps designs whose
    k planets clear each other and assemble ((z1 + z0)/k whole).  Four planets at i = 6 (planets
    of 2·z1 teeth on a 3·z1 centre distance) clear only from z1 = 17 on (3·17·sin 45° = 36.06 >
    36), so with 12 teeth allowed the smallest designs touch; six planets never clear at i = 4.2
    (1.1·z1 on 2.1·z1: sin 30° < 1.1/2.1)."""
    simple = GearTrain.parse("0-1-2 2-3 0~3i 1~3")
    target, tol, teeth = Fraction(ratio), Fraction(1, 200), (lowest, 100)
    loose = brute_force(simple, 0, 1, 2, target, tol, teeth, planets=planets, ignore="touch")
    assert any(p for *_, p in loose[:5]) == touching  # without the rule the best designs touch
    kept = brute_force(simple, 0, 1, 2, target, tol, teeth, planets=planets)
    if not kept:
        with pytest.raises(NoDesign):
            design(simple, 0, 1, 2, ratio, tolerance="0.5%", teeth=teeth, min_teeth=lowest, planets=planets)
        return
    found = design(simple, 0, 1, 2, ratio, tolerance="0.5%", teeth=teeth, min_teeth=lowest, planets=planets, best=5)
    assert [(d.error, sum(d.teeth.values())) for d in found] == [k[:2] for k in kept[:5]]
    for d in found:
        _assert_buildable(d, simple, 0, 1, 2, target, tol, planets)


def test_a_planet_wheel_that_is_a_ring_needs_no_clearance_from_its_neighbours():
    # carrier 2 holds planet 3, a compound of three wheels: z3_0 meshes sun 0, z3_1 meshes ring 1 inside it, and
    # z3_4 is itself a ring around pinion 4 on the central axis.  Three planets: the two pinion wheels must clear
    # their neighbours, the ring wheel surrounds the central pinion and cannot (it is wider than its centre
    # distance), so only the pinion wheels are held to it.
    layout = GearTrain.parse("0-1-2-4 2-3 0~3 1~3i 3~4i")
    (d,) = design(layout, 0, 1, 2, "147/85", tolerance="0", teeth=(17, 80), planets=3, compound=[3], best=1)
    z = d.teeth
    # ω1/ω2 with the sun fixed, by Willis: 1 + z0·z3_1 / (z1·z3_0)
    assert d.ratio == 1 + Fraction(z["z0"] * z["z3_1"], z["z1"] * z["z3_0"]) == Fraction(147, 85) and d.error == 0
    centre = z["z0"] + z["z3_0"]  # 2a/m, the same for the three meshes on the carrier's two axes
    assert z["z1"] - z["z3_1"] == centre == z["z3_4"] - z["z4"]
    for pinion in ("z3_0", "z3_1"):  # neighbours 2a·sin 60° apart clear tip circles of m(z + 2)
        assert centre ** 2 * Fraction(3, 4) > (z[pinion] + 2) ** 2
    assert centre ** 2 * Fraction(3, 4) <= (z["z3_4"] + 2) ** 2  # the ring wheel would not clear: it is exempt
    assert (z["z0"] * z["z3_1"] + z["z1"] * z["z3_0"]) % (3 * gcd(z["z3_0"], z["z3_1"])) == 0  # the planets assemble


@pytest.mark.parametrize("text, frame, driver, driven, ring", [
    ("0-2-3 0-1 1~2 1~3", 2, 3, 0, "2~1i"),   # the planet 1 numbered first: the ring 2 is a mesh's second gear
    ("0-1-2 2-3 0~3 1~3", 0, 1, 2, "0~3i"),   # the ring 0 numbered first: the first gear of its mesh
])
def test_free_kinds_with_planets_keep_the_clearance_and_name_the_ring(text, frame, driver, driven, ring):
    # the simple planetary (sun fixed or ring fixed) with kinds free: the solver may make either gear of a mesh the
    # ring; three planets of whatever kinds it picks must clear and assemble, and the train it reports names the
    # ring first in its internal mesh
    layout = GearTrain.parse(text)
    target, tol = Fraction(4), Fraction(5, 100)
    found = design(layout, frame, driver, driven, "4", tolerance="5%", teeth=(17, 60), planets=3, kinds="free", best=3)
    assert len(found) == 3
    for d in found:
        _assert_buildable(d, layout, frame, driver, driven, target, tol, planets=3)
        assert ring in d.train_text.split()
        (a, b), = [m for m, inner in zip(d.train.meshes, d.train.internal) if inner]
        assert d.teeth[f"z{a}"] >= d.teeth[f"z{b}"] + 10  # the ring, RING_MARGIN teeth above its pinion
