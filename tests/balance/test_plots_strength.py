"""What the balance figures draw: each curve's data against the result's numbers or a hand formula, the axis
labels, the markers and the captions (the figure is caught as it is saved, then read back)."""

from __future__ import annotations

import math
import struct
from pathlib import Path

import matplotlib.colors as mcolors
import numpy as np
import pytest

from balance import (
    Arm, CompareProblem, Link, Load, load_toml, plot_arm, plot_compare, plot_pantograph, plot_prismatic, plot_spring,
    solve_arm, solve_pantograph, solve_prismatic, solve_spring,
)

MODELS = Path(__file__).resolve().parents[2] / "models"
G = 9.80665


@pytest.fixture
def drawn(monkeypatch, tmp_path):
    """Draw with a plot function and return the figure it saved (and check the file is there)."""
    from matplotlib.figure import Figure

    saved = []
    keep = Figure.savefig

    def savefig(self, path, **kw):
        saved.append(self)
        return keep(self, path, **kw)

    monkeypatch.setattr(Figure, "savefig", savefig)

    def draw(plot, result, **kw):
        path = tmp_path / f"{plot.__name__}.png"
        assert plot(result, str(path), **kw) == str(path) and path.stat().st_size > 10_000
        assert len(saved) == 1
        # a PNG at 110 dots an inch: its width and height in its header (bytes 16–24, big-endian)
        width, height = struct.unpack(">II", path.read_bytes()[16:24])
        assert (width, height) == tuple(round(110 * v) for v in saved[0].get_size_inches())
        return saved.pop()

    return draw


def lines(ax):
    return [(np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)) for ln in ax.get_lines()]


def legend_texts(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


# --------------------------------------------------------------------------------------------- spring devices
@pytest.mark.parametrize("doc", [
    {"spring": {"kind": "compression", "moment": 100.0, "range_deg": [20.0, 160.0], "r": [0.01, 0.5],
                "r0": [0.01, 1.0], "a": [0.0, 1.0], "norm": "max"}},
    {"spring": {"kind": "tension", "moment": -100.0, "range_deg": [20.0, 160.0], "r": [0.05, 0.2],
                "r0": [0.1, 0.4], "a": [0.0, 0.3], "max_force": 1500.0, "design": {"material": "music-wire"}}},
])
def test_spring_figure_draws_the_target_the_device_and_their_difference(drawn, doc):
    design = solve_spring(doc)
    res = design.fit
    fig = drawn(plot_spring, design)
    ax1, ax2 = fig.axes[:2]
    assert len(fig.axes) == (3 if design.pareto else 2)
    (x, target), (x2, device) = lines(ax1)
    phi = np.radians(x)
    assert len(x) == 1001 and x[0] == pytest.approx(math.degrees(res.phi_range[0]))
    assert x[-1] == pytest.approx(math.degrees(res.phi_range[1])) and np.array_equal(x, x2)
    assert np.allclose(target, res.moment * np.sin(phi), rtol=0, atol=1e-12 * abs(res.moment))
    # the device's moment differs from the target by the fit's error: at most its largest, reached on the grid
    gap = np.abs(device - target) / abs(res.moment)
    assert 0.99 * res.max_rel_error <= gap.max() <= max(res.max_rel_error * (1 + 1e-9), 1e-12)
    # the lower panel is that difference in percent
    (xe, err), (_, zero) = lines(ax2)
    assert np.array_equal(xe, x) and np.allclose(err, 100 * (device - target) / abs(res.moment), atol=1e-9)
    assert np.all(zero == 0)
    assert ax1.get_ylabel() == "moment on the crank (N·m)" and ax2.get_ylabel() == "(M − Φ0·sin φ)/|Φ0|  (%)"
    assert ax1.get_xlabel() == ax2.get_xlabel() == "crank angle φ (deg, from the base point C)"
    assert legend_texts(ax1) == ["target  Φ0·sin φ", f"{res.kind} device"]
    title = (f"{res.kind} device ({res.method}): c = {res.c:.4g} N/m, r = {res.r:.4g} m, r0 = {res.r0:.4g} m, "
             f"a = {res.a:.4g} m")
    if design.spring:
        s = design.spring
        title += (f"\nspring: d = {1e3 * s.wire_diameter_m:.3g} mm, D = {1e3 * s.mean_diameter_m:.4g} mm, "
                  f"n = {s.active_coils:g}, {s.material}")
    assert ax1.get_title() == title
    assert ax1.title.get_fontsize() == ax2.title.get_fontsize() == 9
    if res.max_rel_error < 1e-12:  # the tension spring of zero free length
        assert ax2.get_title() == f"exact to rounding: max |error| {res.max_rel_error:.2g}"
        assert ax2.get_ylim() == (-1, 1)
    else:
        assert ax2.get_title() == (f"relative error: max {100 * res.max_rel_error:.3g} %, "
                                   f"RMS {100 * res.rms_rel_error:.3g} %")


def test_spring_figures_pareto_panel_has_a_line_per_peak_force_and_marks_the_fit(drawn):
    doc = {"spring": {"kind": "compression", "moment": 100.0, "range_deg": [20.0, 160.0], "r": [0.01, 0.5],
                      "r0": [0.01, 1.0], "a": [0.0, 1.0], "norm": "max", "pareto": True}}
    design = solve_spring(doc)
    res, front = design.fit, design.pareto
    ax3 = drawn(plot_spring, design).axes[2]
    levels = sorted({float(f"{pt.force:.3g}") for pt in front})
    drawn_lines = lines(ax3)
    assert len(drawn_lines) == len(levels) + 1
    for level, (x, y) in zip(levels, drawn_lines):
        pts = sorted((pt for pt in front if float(f"{pt.force:.3g}") == level), key=lambda q: q.size)
        assert list(x) == [q.size for q in pts] and np.allclose(y, [100 * q.error for q in pts], rtol=1e-15)
    (fx, fy) = drawn_lines[-1]
    assert list(fx) == [res.free_length] and list(fy) == pytest.approx([100 * res.max_rel_error])
    # the peak forces from dark violet to yellow along viridis (its ends written out), the fit a red ring alone
    colours = [mcolors.to_rgba(ln.get_color()) for ln in ax3.get_lines()]
    assert len(levels) >= 2 and len(set(colours[:-1])) == len(levels)
    assert colours[0] == pytest.approx((0.267004, 0.004874, 0.329415, 1.0), abs=1e-6)
    assert colours[len(levels) - 1] == pytest.approx((0.993248, 0.906157, 0.143936, 1.0), abs=1e-6)
    ring = ax3.get_lines()[-1]
    assert ring.get_marker() == "o" and ring.get_linestyle() == "None" and ring.get_markersize() == 13
    assert ring.get_markeredgecolor() == "red" and ring.get_markerfacecolor() == "none"
    assert legend_texts(ax3) == [f"peak force {f:.3g} N" for f in levels] + ["this fit"]
    assert ax3.get_xscale() == ax3.get_yscale() == "log"
    assert ax3.get_xlabel() == "device size: free length 2r + r0 + a (m)"
    assert ax3.get_ylabel() == "max relative error (%)"


# --------------------------------------------------------------------------------------------- counter-masses
@pytest.mark.parametrize("C, valid", [(None, 0.5), (0.6, math.sqrt(1 / 6))])  # 4(0.5 − 2q²) = 4q² at C = 0.6
def test_prismatic_figure_draws_the_laws_and_the_inertia_they_keep(drawn, C, valid):
    """m = 2 kg, I = 0.1 kg·m², M = 2 kg, ±0.5 m: C_min = I + (m² + 2mM)·q_max²/(2M) = 0.85 kg·m²."""
    doc = {"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 2, "q_max": 0.5}}
    if C is not None:
        doc["slider"]["C"] = C
    C = 0.85 if C is None else C
    fig = drawn(plot_prismatic, solve_prismatic(doc))
    ax1, ax2 = fig.axes
    (q, z1), (q2, z2), (q3, link) = lines(ax1)
    assert len(q) == 801 and q[0] == -0.5 and q[-1] == 0.5 and np.array_equal(q, q2) and np.array_equal(link, q3)
    root = np.sqrt(np.maximum(2 * 2 * (C - 0.1 - 2 * q * q) - 4 * q * q, 0))
    assert np.allclose(z1, (-2 * q + root) / 4, atol=1e-12) and np.allclose(z2, (-2 * q - root) / 4, atol=1e-12)
    (qt, total), (_, c_line), (_, cmin_line) = lines(ax2)
    assert mcolors.same_color(ax2.get_lines()[0].get_color(), "C3")  # the inertia kept, red as the spans where it is not
    inside = np.abs(qt) <= valid + 1e-12
    assert np.allclose(total[inside], C, atol=1e-12)  # the laws keep the inertia where they are real
    # beyond, both counter-masses sit at −m·q/(2M) = −q/2: I + m·q² + 2M·q²/4 = 0.1 + 3q², more than C
    assert np.allclose(total[~inside], 0.1 + 3 * qt[~inside] ** 2, atol=1e-12) and np.all(total[~inside] > C)
    assert np.all(c_line == C) and np.all(cmin_line == pytest.approx(0.85))
    shaded = [p for p in ax2.patches]
    if valid < 0.5:
        assert len(shaded) == 2 and len(ax1.patches) == 2
        spans = sorted(sorted((p.get_x(), p.get_x() + p.get_width())) for p in shaded)
        assert np.allclose(spans, [(-0.5, -valid), (valid, 0.5)], atol=1e-12)
        assert ax2.get_title() == (f"C is {0.85 - C:.3g} kg·m² below C_min: real only for |q| ≤ {valid:.4g} m; "
                                   "shaded: beyond it the inertia cannot be kept")
    else:
        assert shaded == [] and ax2.get_title() == ("margin C − C_min = 0 kg·m²: the laws are real for "
                                                    "|q| ≤ 0.5 m")
    assert legend_texts(ax1) == ["counter-mass 1: z1(q)", "counter-mass 2: z2(q)", "sliding link: q"]
    assert [ln.get_linewidth() for ln in ax1.get_lines()] == [2, 2, 1]  # the laws bold, the link thin
    assert legend_texts(ax2) == ["transverse inertia I + m·q² + M·(z1² + z2²)", f"C = {C:.4g} kg·m² (used)",
                                 "C_min = 0.85 kg·m² (full stroke ±0.5 m)"]
    assert ax1.get_title() == ("laws z1,2 = [−m·q ± √(2M(C − I − m·q²) − m²q²)]/(2M): m = 2 kg, I = 0.1 kg·m², "
                               "M = 2 kg")
    assert ax1.get_ylabel() == "position along the slide axis (m)"
    assert ax2.get_ylabel() == "inertia about the slide's origin (kg·m²)"
    assert ax2.get_xlabel() == "slide q (m, from mid-stroke)"
    lo, hi = ax2.get_ylim()
    assert lo < min(total.min(), 0.85, C) and hi > max(total.max(), 0.85, C)


# --------------------------------------------------------------------------------------------- arms
def potential(q1, q2, payload):
    """Height-weighted potential (J) of the two-link arm below, angles from the vertical."""
    return (50 * 0.35 * np.cos(q1) + 30 * (0.7 * np.cos(q1) + 0.25 * np.cos(q1 + q2))
            + payload * (0.7 * np.cos(q1) + 0.5 * np.cos(q1 + q2)))


def moment_to_carry(q, i, payload, h=1e-6):
    """dV/dq_i by central differences: the moment a drive holds against gravity."""
    up, down = q.copy(), q.copy()
    up[:, i] += h
    down[:, i] -= h
    return (potential(*up.T, payload) - potential(*down.T, payload)) / (2 * h)


def test_arm_figure_sweeps_each_joint_with_gravity_devices_and_payload_residuals(drawn):
    from balance import balance_arm

    arm = Arm((Link("a", "revolute", 0.7, 50.0, 0.35), Link("b", "revolute", 0.5, 30.0, 0.25)),
              (Load(1, 40.0, 0.5, payload=True, name="payload"),))
    result = balance_arm(arm, samples=1000, seed=2)
    fig = drawn(plot_arm, result)
    assert len(fig.axes) == 4
    mid = -math.pi + 0.8 * 2 * math.pi  # every other joint at 80 % of its range −180° … 180°
    for i, whole in ((0, 20 * 1.2), (1, 20 * 0.5)):  # half the payload's reach: the residual's true extreme
        top, bot = fig.axes[i], fig.axes[2 + i]
        (x, g), (x2, dev) = lines(top)
        assert len(x) == 241 and x[0] == -180 and x[-1] == 180 and np.array_equal(x, x2)
        q = np.full((241, 2), mid)
        q[:, i] = np.radians(x)
        hand = moment_to_carry(q, i, 20.0)  # tuned for half of the 40 N payload
        scale = np.max(np.abs(hand))
        assert np.allclose(g, hand, atol=1e-6 * scale) and np.allclose(dev, hand, atol=1e-6 * scale)
        drawn_res = lines(bot)
        assert [label for label in legend_texts(bot)] == ["half payload (tuned)", "no payload", "full payload"]
        for (xr, r), payload in zip(drawn_res[:3], (20.0, 0.0, 40.0)):
            assert np.array_equal(xr, x)
            assert np.allclose(r, 100 * (moment_to_carry(q, i, payload) - hand) / scale, atol=1e-5)
        worst = max(np.max(np.abs(r)) for _, r in drawn_res[:3]) / 100
        assert bot.get_title() == (f"largest residual {100 * worst:.3g} % of {scale:.4g} N·m on this sweep;\n"
                                   f"{whole:.4g} N·m over the whole workspace")
        assert top.get_title() == f"q{i + 1} ({'ab'[i]}) swept, other joints at 80 % of their ranges"
        assert top.get_ylabel() == f"generalised force on q{i + 1} (N·m)" and top.get_xlabel() == f"q{i + 1} (deg)"
        assert bot.get_ylabel() == "residual / max |gravity moment| (%)" and bot.get_xlabel() == f"q{i + 1} (deg)"
        assert legend_texts(top) == ["gravity moment (to carry)", "spring devices"]
        # two panels a joint on a page 9.2 inches wide: titles at 9 pt, legends at 7 pt
        assert top.title.get_fontsize() == bot.title.get_fontsize() == 9
        assert {t.get_fontsize() for ax in (top, bot) for t in ax.get_legend().get_texts()} == {7}
    assert fig._suptitle.get_text() == "arm: gravity against the spring devices (tuned for 20 N, payload 0 … 40 N)"
    assert fig._suptitle.get_fontsize() == 11 and tuple(fig.get_size_inches()) == (9.2, 6.6)


def test_arm_figure_of_an_exactly_balanced_arm_without_payload(drawn):
    """One link, 10 N at mid-length of 1 m: the drive holds −5·sin q, the devices exactly that."""
    result = solve_arm({"arm": {"links": [{"joint": "revolute", "length": 1.0, "weight": 10.0}]}})
    fig = drawn(plot_arm, result)
    top, bot = fig.axes
    (x, g), (_, dev) = lines(top)
    assert np.allclose(g, -5 * np.sin(np.radians(x)), atol=1e-12) and np.allclose(dev, g, atol=1e-12)
    (_, r), (_, zero) = lines(bot)
    assert np.max(np.abs(r)) < 1e-10 and np.all(zero == 0) and bot.get_ylim() == (-1, 1)
    worst = np.max(np.abs(r)) / 100
    assert bot.get_title() == f"exact to rounding: |residual| ≤ {worst:.1e} of 5 N·m" and bot.get_legend() is None
    assert fig._suptitle.get_text() == "arm: gravity against the spring devices"


# --------------------------------------------------------------------------------------------- pantograph
def test_pantograph_figure_draws_the_mechanism_forces_extremes_and_spring(drawn):
    result = solve_pantograph(load_toml(str(MODELS / "pantograph.toml")))
    p = result.pantograph
    fig = drawn(plot_pantograph, result)
    mech, cyl, hand, spring = fig.axes[:4]
    assert len(fig.axes) == 6  # and the two colour bars
    # the mechanism at mid-range: θ2 = (−30° + 80°)/2 = 25°, θ3 = (−80° + 40°)/2 = −20°; bar 2 is l2 = 0.8 m from A,
    # bar 3 is l3 = 1 m from D, and the parallelogram's bars 14, 15 repeat them 0.15 m away
    bars = lines(mech)[:8]
    ends = [np.array([x, y]).T for x, y in bars]
    (a, d), (d2, c) = ends[0], ends[1]
    assert np.allclose(a, 0, atol=1e-15) and np.array_equal(d, d2)
    assert np.allclose(d - a, 0.8 * np.array([math.cos(math.radians(25)), math.sin(math.radians(25))]), atol=1e-12)
    assert np.allclose(c - d, 1.0 * np.array([math.cos(math.radians(-20)), math.sin(math.radians(-20))]), atol=1e-12)
    for (u, v), (s, t) in ((ends[4], ends[0]), (ends[5], ends[1])):  # 14 ∥ 2 and 15 ∥ 3, as long
        assert np.allclose(v - u, t - s, atol=1e-12)
    assert [t.get_text() for t in mech.texts][:8] == ["2", "3", "9", "8", "14", "15", "16", "4"]
    # every link's number is clear of every bar, as drawn at the file's 110 dots an inch (9 sat on link 2, which E–B
    # meets at E; 16, beside the short D–D1, on link 3 leaving D and bar 8 crossing D–D1)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig.set_dpi(110)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    for label in mech.texts[:8]:
        box = label.get_window_extent(renderer)
        for x, y in bars:
            run = mech.transData.transform(np.column_stack([np.linspace(x[0], x[1], 400), np.linspace(y[0], y[1], 400)]))
            assert not any(box.contains(*q) for q in run), (label.get_text(), x, y)
    # the arm's links 2 and 3 drawn thicker than the bars; the numbers in blue, as the title says
    assert [ln.get_linewidth() for ln in mech.get_lines()[:8]] == [2.5, 2.5] + [1.5] * 6
    assert [t.get_color() for t in mech.texts[:8]] == ["C0"] * 8 and mech.get_title().endswith("(link numbers in blue)")
    # the cylinder runs from B down to the panel's lower edge (its base P = (0.3, −1.6) m is far below)
    cylinder = next(ln for ln in mech.get_lines() if ln.get_color() == "C2")
    (cut_x, b_x), (cut_y, b_y) = cylinder.get_xdata(), cylinder.get_ydata()
    assert (b_x, b_y) == pytest.approx(tuple(ends[2][1])) and cut_y == mech.get_ylim()[0]
    assert (cut_x - b_x) / (cut_y - b_y) == pytest.approx((0.3 - b_x) / (-1.6 - b_y), rel=1e-12)  # towards P
    # the mechanism fills most of its panel's width (1.66 m of 2.41 m), with more room left of A for the labels
    (left, right), x_ends = mech.get_xlim(), np.concatenate([e[:, 0] for e in ends])
    assert (x_ends.max() - x_ends.min()) / (right - left) > 0.6 and x_ends.min() - left > right - x_ends.max() > 0
    w = {"A": 43.0, "D": 54.75, "B": 7.0, "C": 103.25}  # the scene's substitution weights, by hand
    assert mech.texts[-1].get_text() == ("substitution weights (half payload):\n" +
                                         "\n".join(f"W_{k} = {w[k]:.4g} N" for k in "ADBC"))
    assert mech.texts[-1].get_fontsize() == 8 and tuple(fig.get_size_inches()) == (12, 9.5)
    dots = [ln for ln in mech.get_lines() if ln.get_marker() == "o"]
    assert [ln.get_markersize() for ln in dots] == pytest.approx([5 + 12 * w[k] / 103.25 for k in "ADBC"])
    pivots = [ln for ln in mech.get_lines() if ln.get_marker() == "^"]
    assert len(pivots) == 2 and {ln.get_markersize() for ln in pivots} == {9}  # the two ground pivots A and A1
    assert mech.get_xlabel() == "x from A (m)" and mech.get_ylabel() == "height from A (m)"
    # the force maps: the true extremes marked where the result reached them, said in the title
    grid = np.radians(np.stack(np.meshgrid(np.linspace(-30, 80, 61), np.linspace(-80, 40, 61)), -1).reshape(-1, 2))
    for ax, fn, (lo, hi), title in ((cyl, p.cylinder_force, result.force[0.5], "cylinder 10 force, half payload"),
                                    (hand, p.hand_force, result.hand[0.5], "what the operator holds, half payload")):
        (lx, ly), (hx, hy) = lines(ax)
        assert np.allclose([lx[0], ly[0]], np.degrees(lo.at)) and np.allclose([hx[0], hy[0]], np.degrees(hi.at))
        # the extremes drawn whole where they are (on the map's edge too), ▽ and △ of 9 points
        assert [(ln.get_marker(), ln.get_markersize(), ln.get_clip_on()) for ln in ax.get_lines()] == [
            ("v", 9, False), ("^", 9, False)]
        on_grid = fn(grid, 0.5)
        filled = ax.collections[0]  # the map is filled from the 61 × 61 grid: its values' range is the grid's
        assert (filled.zmin, filled.zmax) == pytest.approx((on_grid.min(), on_grid.max()), rel=1e-12)
        assert lo.value <= on_grid.min() + 1e-9 and hi.value >= on_grid.max() - 1e-9  # true extremes
        assert fn(np.array([lo.at]), 0.5)[0] == pytest.approx(lo.value, rel=1e-9)
        assert ax.get_title() == f"{title}: {lo.value:.4g} … {hi.value:.4g} N (▽ least, △ largest)"
        assert ax.get_xlabel() == "upper arm angle θ2 (deg from horizontal)"
        assert ax.get_ylabel() == "forearm angle θ3 (deg from horizontal)"
    # the spring on link 2 cancels W_D's moment about A: 54.75 N at l2 = 0.8 m
    (x, moment), (x2, gravity) = lines(spring)
    assert len(x) == 200 and np.array_equal(x, x2) and x[0] == pytest.approx(-30) and x[-1] == pytest.approx(80)
    assert np.allclose(gravity, -54.75 * 0.8 * np.cos(np.radians(x)), atol=1e-12)
    assert np.allclose(moment, -gravity, atol=1e-9)
    assert legend_texts(spring) == ["spring 13 moment on link 2", "gravity moment of W_D about A"]
    loads = ", ".join(f"{p.vertical_load(f):.4g}" for f in (0.0, 0.5, 1.0))
    assert spring.get_title() == (f"spring cancels W_D·l2·cos θ2 exactly; vertical load at B {loads} N "
                                  "(payload 0, ½, 1)")
    assert fig._suptitle.get_text() == "Pantograph manipulator, k = 4: cylinder base P = (0.3, -1.6) m"


# --------------------------------------------------------------------------------------------- comparison
def test_compare_figure_draws_each_strategys_torque_and_its_bars(drawn):
    """One link: 40 N at 0.2 m and a payload of 1 … 4 kg at 0.5 m.  Unbalanced, the drive carries
    (8 + 4·G·0.5)·sin q at the largest payload; every strategy, tuned for 2.5 kg, leaves 1.5·G·0.5·sin q."""
    arm = Arm((Link("upper", "revolute", 0.5, 40.0, 0.2),), (Load(0, 4 * G, 0.5, payload=True),))
    result = CompareProblem(arm, payload=(1.0, 4.0), samples=200).solve()
    fig = drawn(plot_compare, result)
    top, bot = fig.axes
    names = ["none", "counterweights", "springs per joint", "harmonic, pruned", "exact springs"]
    assert [s.name for s in result.strategies] == names and all(s.available for s in result.strategies)
    drawn_lines = top.get_lines()
    assert len(drawn_lines) == 6  # five strategies and the zero line
    for ln, name in zip(drawn_lines, names):
        x, y = np.asarray(ln.get_xdata()), np.asarray(ln.get_ydata())
        assert len(x) == 241 and x[0] == -180 and x[-1] == 180
        amplitude = 8 + 2 * G if name == "none" else 0.75 * G
        assert np.allclose(y, amplitude * np.sin(np.radians(x)), atol=1e-9), name
    assert [ln.get_color() for ln in drawn_lines[:5]] == ["k", "C0", "C1", "C2", "C3"]
    assert [ln.get_linewidth() for ln in drawn_lines[:5]] == [2.2, 2.2, 1.4, 1.4, 1.4]
    assert drawn_lines[2].get_linestyle() == "--" and drawn_lines[0].get_linestyle() == "-"
    assert legend_texts(top) == ["gravity (no balancing)"] + names[1:]
    assert top.get_title() == "q1 (upper) swept\nothers at 80 % of their ranges, payload 4 kg"
    assert top.get_xlabel() == "q1 (deg)" and top.get_ylabel() == "torque the drive carries (N·m)"
    # bars: the largest residual (a true extreme: 8 + 2G unbalanced, 0.75·G balanced) and the RMS, strategy by
    # strategy from the top
    bars = bot.patches
    assert len(bars) == 10
    largest = [8 + 2 * G] + [0.75 * G] * 4
    assert [b.get_width() for b in bars[:5]] == pytest.approx(largest, rel=1e-9)
    assert [b.get_width() for b in bars[5:]] == pytest.approx([s.joints[0].rms for s in result.strategies])
    assert [b.get_y() + b.get_height() / 2 for b in bars[:5]] == pytest.approx([4, 3, 2, 1, 0])
    assert [b.get_height() for b in bars[5:]] == pytest.approx([0.4] * 5)
    removed = round(100 * (1 - 0.75 * G / (8 + 2 * G)))  # 73 %
    assert [t.get_text() for t in bot.texts] == [f" {8 + 2 * G:.3g} (0 %)"] + [f" {0.75 * G:.3g} ({removed} %)"] * 4
    ticks = dict(zip(bot.get_yticks(), (t.get_text() for t in bot.get_yticklabels())))
    assert ticks == dict(zip([4, 3, 2, 1, 0], names))  # "none" on top
    assert bot.get_xlim() == pytest.approx((0, 1.3 * (8 + 2 * G)))
    assert bot.get_xlabel() == "residual torque (N·m)\nover the workspace and payloads"
    assert legend_texts(bot) == ["largest (true extreme)", "RMS"]
    assert fig._suptitle.get_text() == "arm: gravity torque before and after each strategy (payload 1 … 4 kg)"
    assert fig._suptitle.get_fontsize() == 10 and top.title.get_fontsize() == 9
    # the largest residual's bars pale (α 0.35) behind the RMS bars, which are solid
    assert [b.get_alpha() for b in bars] == [0.35] * 5 + [None] * 5
    assert tuple(fig.get_size_inches()) == (9.0, 7.4)  # one joint: the least width, 9 inches


def test_compare_figure_has_a_column_per_loaded_joint(drawn):
    """The two-link arm of test_compare_strength.py (40 N at 0.2 m on 0.5 m, 20 N at 0.2 m on 0.4 m), both
    joints loaded: two columns of a sweep above its bars, on a page 4.2 inches a column but at least 9."""
    arm = Arm((Link("upper", "revolute", 0.5, 40.0, 0.2), Link("fore", "revolute", 0.4, 20.0, 0.2)))
    fig = drawn(plot_compare, CompareProblem(arm, samples=100).solve())
    assert len(fig.axes) == 4 and tuple(fig.get_size_inches()) == (9.0, 7.4)
    assert [ax.get_title().split(" swept")[0] for ax in fig.axes[:2]] == ["q1 (upper)", "q2 (fore)"]
    assert [ax.get_xlabel() for ax in fig.axes[2:]] == ["residual torque (N·m)\nover the workspace and payloads"] * 2


# --------------------------------------------------------------------------------------------- linkages
@pytest.mark.parametrize("model, dead", [("motion_four_bar.toml", False), ("rocker", True)])
def test_linkage_figure_draws_the_shaking_force_and_the_counterweights(drawn, model, dead):
    """Left: before and after over the input (the shaking force, or the first moment's distance from its start
    where the range ends at dead positions); right: the counterweights at their points, sized by mass."""
    from balance import plot_linkage
    from mechsynth._linkage_balance import linkage_problem
    from synth.motion import Linkage, read_linkage
    from synth.structure.chain import Chain, Mechanism

    if model == "rocker":  # a triple-rocker's input: limits at dead positions
        lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [1, 0], [1.5, 1.5], [1.6, 1.0]])
    else:
        lk = read_linkage(Path(__file__).resolve().parents[2] / "models" / model)
    res = linkage_problem(lk, {"density": 2.0}, None, model).solve()
    assert res.problem.dead_ends is dead
    fig = drawn(plot_linkage, res)
    left, right = fig.axes
    (_, before), (_, after) = lines(left)
    if dead:
        assert "M(start)" in left.get_ylabel()
        assert before.max() <= res.before.moment_excursion * (1 + 1e-9)
    else:
        assert "shaking force" in left.get_ylabel()
        assert res.before.shaking_force * 0.999 <= before.max() <= res.before.shaking_force * (1 + 1e-9)
    assert np.abs(after).max() <= 1e-9 * np.abs(before).max()  # both balanced in full
    points = np.concatenate([c.get_offsets() for c in right.collections])
    expected = np.array([c.at for c in res.counterweights if c.mass > 0])
    assert np.allclose(np.sort(points, axis=0), np.sort(expected, axis=0))
    assert legend_texts(right) == ["centre of mass, before", "centre of mass, after"]


def test_linkage_figure_draws_the_counterweights_a_saved_linkage_carries(drawn, tmp_path):
    """The balanced four-bar saved and balanced again: no counterweight found, the two it carries drawn grey at
    their points, sized by mass."""
    import json

    from balance import linkage_table, plot_linkage
    from mechsynth._linkage_balance import linkage_problem
    from mechsynth.cli import main
    from synth.motion import read_linkage

    saved = tmp_path / "balanced.json"
    model = Path(__file__).resolve().parents[2] / "models" / "motion_four_bar.toml"
    assert main(["balance", "linkage", str(model), "--density", "2", "--save", str(saved), "--format", "json"]) == 0
    table = linkage_table(json.loads(saved.read_text()))
    res = linkage_problem(read_linkage(saved), {}, table.links, "balanced", None, table.counterweights).solve()
    assert res.added_mass == 0 and len(res.carried) == 2
    right = drawn(plot_linkage, res).axes[1]
    dots = [c for c in right.collections if len(c.get_offsets())]  # (the found ones: none, no dot)
    points = np.concatenate([c.get_offsets() for c in dots])
    assert np.allclose(np.sort(points, axis=0), np.sort([b.centre for b in res.carried], axis=0))
    assert all(mcolors.to_hex(c.get_facecolor()[0]) == mcolors.to_hex("0.55") for c in dots)
    assert "grey: carried already" in right.get_title()


@pytest.mark.parametrize("points", [
    [[0, 0], [1, 0], [0.9714545931334975, 0.6802198291405213], [1.5818277369324332, 1.0077552016197229]],
    None,  # models/motion_four_bar.toml
])
def test_linkage_figure_counterweight_labels_clear_of_their_dots_and_inside_the_panel(drawn, points):
    """Each counterweight's mass label lies beside its dot, not under it, and dot and label lie inside the
    panel: the README's four-bar (`dimension … --save freudenstein.toml`, then `balance linkage … --range 30..110
    --plot`) had '1.86 kg' covered by its dot at the panel's lower edge, cut by it."""
    from balance import plot_linkage
    from mechsynth._linkage_balance import linkage_problem
    from synth.motion import Linkage, read_linkage
    from synth.structure.chain import Chain, Mechanism

    if points is None:
        lk, options = read_linkage(MODELS / "motion_four_bar.toml"), {"density": 2.0}
    else:
        lk = Linkage(Mechanism(Chain.parse("0-1 0-3 1-2 2-3"), 0), (0,), points)
        options = {"density": 2.0, "range": (30.0, 110.0)}
    res = linkage_problem(lk, options, None, "four-bar").solve()
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = drawn(plot_linkage, res)
    fig.set_dpi(110)  # as saved
    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    right = fig.axes[1]
    panel = right.get_window_extent(renderer)
    labels = [t for t in right.texts if t.get_text().endswith(" kg")]
    dots = [c for c in right.collections if len(c.get_offsets())]
    assert len(labels) == len(dots) == len([c for c in res.counterweights if c.mass > 0]) > 0
    for label, dot in zip(labels, dots):
        centre = right.transData.transform(dot.get_offsets()[0])
        radius = math.sqrt(dot.get_sizes()[0] / math.pi) * right.figure.dpi / 72  # the dot's area is in points²
        box = label.get_window_extent(renderer)
        nearest = np.clip(centre, [box.x0, box.y0], [box.x1, box.y1])  # the label's point nearest the dot's centre
        assert np.hypot(*(nearest - centre)) >= radius, (label.get_text(), radius)
        for x, y in ((box.x0, box.y0), (box.x1, box.y1), centre - radius, centre + radius):
            assert panel.x0 <= x <= panel.x1 and panel.y0 <= y <= panel.y1, (label.get_text(), x, y, panel)


def test_compare_figure_keeps_every_label_on_the_page(monkeypatch, tmp_path):
    """The scene compare_example1 (three loaded joints, a column each): every axis label, title and bar label
    lies on the page — the bars' x label of the last column ran past the right edge, '(N·m)' cut off."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from mechsynth.cli import main

    saved = []
    keep = Figure.savefig
    monkeypatch.setattr(Figure, "savefig", lambda self, path, **kw: (saved.append(self), keep(self, path, **kw))[1])
    assert main(["balance", "compare", str(MODELS / "compare_example1.toml"), "--plot", str(tmp_path / "c.png")]) == 0
    (fig,) = saved
    fig.set_dpi(110)
    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    page = fig.bbox
    assert len(fig.axes) == 6
    for ax in fig.axes:
        for text in [ax.xaxis.label, ax.yaxis.label, ax.title, *ax.texts]:
            if text.get_visible() and text.get_text():
                box = text.get_window_extent(renderer)
                assert page.x0 - 0.5 <= box.x0 and box.x1 <= page.x1 + 0.5, (text.get_text(), box, page)
