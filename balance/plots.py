"""Figures of the balance results (matplotlib, Agg backend, imported only when a plot is asked for).

Each function draws a result as solved (:mod:`balance.problems`): it reads the result's numbers
(extremes, fits, terms) and never solves again; curves over a range are the result's own model
evaluated for the picture.
"""

from __future__ import annotations

import math

import numpy as np

from mechbase import save_figure

from .devices.fit import relative_errors
from .model.potential import terms_forces

ZERO_SHARE = 1e-9  # a swept curve below this share of the joint's largest torque is rounding, drawn flat

__all__ = ["plot_spring", "plot_arm", "plot_prismatic", "plot_pantograph", "plot_compare", "plot_linkage"]


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_spring(design, path: str) -> str:
    """A :class:`~balance.problems.spring.SpringDesign`: target ``Φ0·sin φ`` against the device moment,
    the relative residual, and (when solved) the Pareto front of error against free length and peak force."""
    plt = _plt()
    res, front, spring = design.fit, design.pareto, design.spring
    lo, hi = res.phi_range
    phi = np.linspace(lo, hi, 1001)
    dev = res.device
    panels = 3 if front else 2
    fig, axes = plt.subplots(panels, 1, figsize=(7.5, 3.2 * panels + 0.4), constrained_layout=True)
    ax1, ax2 = axes[0], axes[1]
    deg = np.degrees(phi)
    ax1.plot(deg, res.moment * np.sin(phi), "k-", lw=2, label="target  Φ0·sin φ")
    label = f"{res.kind} device" if res.family == "slotted-lever" else f"{res.family} device"
    ax1.plot(deg, dev.moment(phi), "C1--", lw=1.5, label=label)
    ax1.set_ylabel("moment on the crank (N·m)")
    angle = "crank angle φ (deg, from the base point C)" if res.family == "slotted-lever" else \
        "crank angle φ (deg, from the direction of the guide)"
    ax1.set_xlabel(angle)
    if res.family == "slotted-lever":
        title = (f"{res.kind} device ({res.method}): c = {res.c:.4g} N/m, r = {res.r:.4g} m, "
                 f"r0 = {res.r0:.4g} m, a = {res.a:.4g} m")
    else:
        rod = "" if res.rod is None else f", l = {res.rod:.4g} m, e = {res.offset:.4g} m"
        title = f"{res.family} device ({res.method}): c = {res.c:.4g} N/m, r = {res.r:.4g} m{rod}, a = {res.a:.4g} m"
    if spring:
        title += (f"\nspring: d = {1e3 * spring.wire_diameter_m:.3g} mm, D = {1e3 * spring.mean_diameter_m:.4g} mm, "
                  f"n = {spring.active_coils:g}, {spring.material}")
    ax1.set_title(title, fontsize=9)
    ax1.legend(loc="best", fontsize=8)
    ax1.grid(alpha=0.3)
    e = relative_errors(dev, res.moment, phi)
    ax2.plot(deg, 100 * e, "C3-")
    ax2.axhline(0, color="k", lw=0.5)
    ax2.set_ylabel("(M − Φ0·sin φ)/|Φ0|  (%)")
    ax2.set_xlabel(angle)
    if res.max_rel_error < 1e-12:
        ax2.set_ylim(-1, 1)
        ax2.set_title(f"exact to rounding: max |error| {res.max_rel_error:.2g}", fontsize=9)
    else:
        ax2.set_title(f"relative error: max {100 * res.max_rel_error:.3g} %, RMS {100 * res.rms_rel_error:.3g} %",
                      fontsize=9)
    ax2.grid(alpha=0.3)
    if front:
        ax3 = axes[2]
        groups: dict[float, list[dict]] = {}
        for pt in front:
            groups.setdefault(float(f"{pt.force:.3g}"), []).append(pt)
        cmap = plt.get_cmap("viridis")
        levels = sorted(groups)
        for i, f in enumerate(levels):
            pts = sorted(groups[f], key=lambda q: q.size)
            ax3.plot([q.size for q in pts], [100 * q.error for q in pts], "o-", ms=4, lw=1.2,
                     color=cmap(i / max(len(levels) - 1, 1)), label=f"peak force {f:.3g} N")
        ax3.plot(res.free_length, 100 * (res.max_rel_error if res.norm == "max" else res.rms_rel_error), "o",
                 ms=13, mfc="none", mec="red", mew=2, label="this fit")
        ax3.set_xscale("log")
        ax3.set_yscale("log")
        from matplotlib.ticker import FormatStrFormatter

        for axis in (ax3.xaxis, ax3.yaxis):
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_formatter(FormatStrFormatter("%g"))
        ax3.tick_params(which="minor", labelsize=7)
        ax3.set_xlabel("device size: free length 2r + r0 + a (m)")
        ax3.set_ylabel(f"{res.norm} relative error (%)")
        ax3.set_title("Pareto front: error against size, one line per peak spring force", fontsize=9)
        ax3.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
        ax3.grid(alpha=0.3, which="both")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def plot_arm(result, path: str, n: int = 241) -> str:
    """An :class:`~balance.problems.arm.ArmBalance`: per joint, swept over its range with the others at
    80 % of theirs, the gravity moment the devices must carry, the devices' moment, and the residual
    relative to the gravity moment (at the tuned, smallest and largest payload when the arm has one).
    The titles give the result's residual over the whole workspace (a true extreme)."""
    plt = _plt()
    tuned, terms = result.arm, result.terms
    lim = [c.limits for c in tuned.coordinates]
    mid = np.array([a + 0.8 * (b - a) for a, b in lim])  # a generic pose: symmetric ones hide terms
    joints = [i for i, c in enumerate(tuned.coordinates) if c.joint != "vertical"]
    has_payload = result.payload is not None
    sweeps = {}
    for i in joints:
        x = np.linspace(*lim[i], n)
        q = np.tile(mid, (n, 1))
        q[:, i] = x
        g = -tuned.gravity_forces(q)[:, i]  # what the drive would carry without devices
        if np.max(np.abs(g)) > 0:
            sweeps[i] = (x, q, g)
    cols = max(len(sweeps), 1)
    fig, axes = plt.subplots(2, cols, figsize=(max(4.3 * cols + 0.6, 9.0), 6.6), constrained_layout=True,
                             squeeze=False)
    for c, (i, (x, q, g)) in enumerate(sweeps.items()):
        ln = tuned.coordinates[i]
        rev = ln.joint == "revolute"
        xs = np.degrees(x) if rev else x
        unit, xunit = ("N·m", "deg") if rev else ("N", "m")
        dev = -terms_forces(terms, q)[:, i]  # the devices' generalised force, opposing gravity
        top, bot = axes[0][c], axes[1][c]
        top.plot(xs, g, "k-", lw=2, label="gravity moment (to carry)")
        top.plot(xs, dev, "C1--", lw=1.5, label="spring devices")
        top.set_title(f"q{i + 1} ({ln.name}) swept, other joints at 80 % of their ranges", fontsize=9)
        top.set_ylabel(f"generalised force on q{i + 1} ({unit})")
        top.set_xlabel(f"q{i + 1} ({xunit})")
        top.grid(alpha=0.3)
        top.legend(fontsize=7, loc="best")
        scale = float(np.max(np.abs(g)))
        cases = [("half payload (tuned)" if has_payload else "balanced", tuned, "C3")]
        if has_payload:
            cases += [("no payload", result.empty, "C0"), ("full payload", result.full_payload, "C2")]
        worst = 0.0
        for label, a, color in cases:
            res = (-a.gravity_forces(q)[:, i] - dev) / scale
            worst = max(worst, float(np.max(np.abs(res))))
            bot.plot(xs, 100 * res, color=color, lw=1.3, label=label)
        bot.axhline(0, color="k", lw=0.5)
        bot.set_xlabel(f"q{i + 1} ({xunit})")
        bot.set_ylabel("residual / max |gravity moment| (%)")
        whole = result.check.per_joint[i] if not has_payload else result.payload.per_joint[i]
        if worst < 1e-12:
            bot.set_ylim(-1, 1)
            bot.set_title(f"exact to rounding: |residual| ≤ {worst:.1e} of {scale:.4g} {unit}", fontsize=9)
        else:
            bot.set_title(f"largest residual {100 * worst:.3g} % of {scale:.4g} {unit} on this sweep;\n"
                          f"{whole:.4g} {unit} over the whole workspace", fontsize=9)
        if has_payload:
            bot.legend(fontsize=7, loc="best")
        bot.grid(alpha=0.3)
    title = f"{tuned.name}: gravity against the spring devices"
    if has_payload:
        pl = result.payload
        title += f" (tuned for {pl.tuned_for:.4g} N, payload {pl.min_payload:.4g} … {pl.max_payload:.4g} N)"
    fig.suptitle(title, fontsize=11)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def plot_prismatic(result, path: str) -> str:
    """A :class:`~balance.problems.slider.SliderBalance`: the counter-mass laws ``z1(q)``, ``z2(q)`` and
    the inertia they keep, with ``C`` against ``C_min``."""
    from .devices.countermass import counter_mass_laws

    plt = _plt()
    r = result.counter_mass
    m, inertia, M, q_max, stroke, C = r.m, r.inertia, r.M, r.q_max, r.stroke, r.C
    cmin, valid = r.C_min, r.law_valid_stroke
    q = np.linspace(-stroke, stroke, 801)
    z1, z2, disc = counter_mass_laws(q, m, inertia, M, C)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, constrained_layout=True)
    ax1.plot(q, z1, "C0", lw=2, label="counter-mass 1: z1(q)")
    ax1.plot(q, z2, "C2", lw=2, label="counter-mass 2: z2(q)")
    ax1.plot(q, q, "k:", lw=1, label="sliding link: q")
    for ax in (ax1, ax2):
        if valid < stroke:
            for side in (-1, 1):
                ax.axvspan(side * valid, side * stroke, color="C3", alpha=0.12, lw=0)
        ax.grid(alpha=0.3)
    ax1.set_ylabel("position along the slide axis (m)")
    ax1.set_title(f"laws z1,2 = [−m·q ± √(2M(C − I − m·q²) − m²q²)]/(2M): m = {m:g} kg, I = {inertia:g} kg·m², "
                  f"M = {M:g} kg", fontsize=9)
    ax1.legend(fontsize=8, loc="upper right")
    total = inertia + m * q * q + M * (z1 * z1 + z2 * z2)
    ax2.plot(q, total, "C3", lw=2, label="transverse inertia I + m·q² + M·(z1² + z2²)")
    ax2.axhline(C, color="k", lw=1, ls="--", label=f"C = {C:.4g} kg·m² (used)")
    ax2.axhline(cmin, color="0.5", lw=1, ls=":", label=f"C_min = {cmin:.4g} kg·m² (full stroke ±{q_max:g} m)")
    ax2.set_ylabel("inertia about the slide's origin (kg·m²)")
    ax2.set_xlabel("slide q (m, from mid-stroke)")
    margin = C - cmin
    msg = (f"margin C − C_min = {margin:.3g} kg·m²: the laws are real for |q| ≤ {valid:.4g} m"
           if margin >= -1e-15 else f"C is {-margin:.3g} kg·m² below C_min: real only for |q| ≤ {valid:.4g} m")
    if np.any(disc < 0):
        msg += "; shaded: beyond it the inertia cannot be kept"
    ax2.set_title(msg, fontsize=9)
    lo = min(cmin, C)  # the laws keep the inertia at C where they are real and raise it beyond: never below C
    hi = max(float(np.max(total)), cmin, C)
    pad = max(0.1 * (hi - lo), 0.05 * abs(C))
    ax2.set_ylim(lo - pad, hi + pad)
    ax2.legend(fontsize=8, loc="upper center")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def plot_pantograph(result, path: str, n: int = 61) -> str:
    """A :class:`~balance.problems.pantograph.PantographBalance`: the mechanism at mid-range with its links
    numbered, the cylinder force and the operator's force over the workspace (the result's extremes in
    the titles and marked where they are reached), and the spring moment against ``W_D``'s."""
    from .model.pantograph import PAYLOADS

    plt = _plt()
    p = result.pantograph
    t2 = 0.5 * (p.range2[0] + p.range2[1])
    t3 = 0.5 * (p.range3[0] + p.range3[1])
    P = {k: v[0] for k, v in p.points(np.array([[t2, t3]])).items()}
    base = p.cylinder_base
    fig, axes = plt.subplots(2, 2, figsize=(12, 9.5), constrained_layout=True)
    ax = axes[0, 0]
    bars = [("2", "A", "D"), ("3", "D", "C"), ("9", "E", "B"), ("8", "F", "B"), ("14", "A1", "D1"),
            ("15", "D1", "C1"), ("16", "D", "D1"), ("4", "C", "C1")]
    for num, a, b in bars:
        ax.plot(*zip(P[a], P[b]), "k-", lw=2.5 if num in ("2", "3") else 1.5, solid_capstyle="round")
        d = P[b] - P[a]
        nrm = np.array([-d[1], d[0]]) / max(np.hypot(*d), 1e-12)
        if (nrm[1] < 0) != (num in ("14", "15")):  # parallelogram bars labelled below, the rest above
            nrm = -nrm
        at, offset = 0.5 * (P[a] + P[b]), 11 * nrm
        if num == "9":  # E–B spans the band between link 2 and bar 14, which a label beside it would sit on:
            at, offset = (P["A"] + P["E"] + P["B"]) / 3, (0, 0)  # its label goes in the triangle A, E, B
        if num == "16":  # beside the short D–D1, link 3 leaving D and bar 8 crossing it touch a label: it goes
            at, offset = P["D1"], 20 * d / max(np.hypot(*d), 1e-12)  # beyond D1, in the open angle of bars 14 and 15
        ax.annotate(num, at, textcoords="offset points", xytext=tuple(offset),
                    fontsize=9, color="C0", fontweight="bold", ha="center", va="center")
    pts = np.array([v for v in P.values()])
    lo_y, hi_y = pts[:, 1].min(), pts[:, 1].max()
    span = max(np.ptp(pts[:, 0]), hi_y - lo_y)
    bottom = lo_y - 0.35 * span
    cut = P["B"] + (base - P["B"]) * min(1.0, (P["B"][1] - bottom) / max(P["B"][1] - base[1], 1e-12))
    ax.plot(*zip(cut, P["B"]), color="C2", lw=6, alpha=0.6, solid_capstyle="butt")
    ax.annotate(f"10: cylinder\nto P ({base[0]:.3g}, {base[1]:.3g}) m", cut, textcoords="offset points",
                xytext=(-8, 4), fontsize=8, color="C2", ha="right")
    ax.plot(*zip(P["A"], P["C"]), ":", color="0.5", lw=1)
    for name in ("A", "A1"):
        ax.plot(*P[name], "k^", ms=9)
    ax.annotate("13: spring\non link 2", P["A"], textcoords="offset points", xytext=(-10, 12), fontsize=8,
                color="C1", ha="right")
    w = p.point_weights()
    wmax = max(w.values())
    for name in "ADBC":
        ax.plot(*P[name], "o", ms=5 + 12 * w[name] / wmax, color="C3", alpha=0.6)
    for name in ("A", "B", "C", "D", "E", "F"):
        ax.annotate(name, P[name], textcoords="offset points", xytext=(-4, 7), fontsize=9, ha="right")
    ax.text(0.98, 0.97, "substitution weights (half payload):\n" + "\n".join(
        f"W_{k} = {w[k]:.4g} N" for k in "ADBC"), transform=ax.transAxes, fontsize=8, ha="right", va="top",
        bbox={"fc": "white", "ec": "0.7", "alpha": 0.9})
    ax.set_aspect("equal")
    ax.set_ylim(bottom, hi_y + 0.45 * span)
    ax.set_xlim(pts[:, 0].min() - 0.3 * span, pts[:, 0].max() + 0.15 * span)
    ax.set_xlabel("x from A (m)")
    ax.set_ylabel("height from A (m)")
    ax.set_title("mechanism at mid-range (link numbers in blue)", fontsize=9)
    ax.grid(alpha=0.3)

    a2 = np.linspace(*p.range2, n)
    a3 = np.linspace(*p.range3, n)
    X, Y = np.meshgrid(a2, a3)
    th = np.stack([X.ravel(), Y.ravel()], axis=1)
    for ax, fn, label, title, (lo_e, hi_e) in (
        (axes[0, 1], p.cylinder_force, "cylinder force F (N)", "cylinder 10 force, half payload", result.force[0.5]),
        (axes[1, 0], p.hand_force, "operator's force along A→C (N)", "what the operator holds, half payload",
         result.hand[0.5]),
    ):
        Z = fn(th, 0.5).reshape(X.shape)
        im = ax.contourf(np.degrees(X), np.degrees(Y), Z, levels=14, cmap="viridis")
        cs = ax.contour(np.degrees(X), np.degrees(Y), Z, levels=7, colors="w", linewidths=0.6)
        ax.clabel(cs, fontsize=7, fmt="%.0f")
        fig.colorbar(im, ax=ax, label=label)
        ax.set_xlabel("upper arm angle θ2 (deg from horizontal)")
        ax.set_ylabel("forearm angle θ3 (deg from horizontal)")
        for e, mark in ((lo_e, "v"), (hi_e, "^")):
            ax.plot(*np.degrees(e.at), mark, ms=9, mfc="w", mec="k", clip_on=False)
        ax.set_title(f"{title}: {lo_e.value:.4g} … {hi_e.value:.4g} N (▽ least, △ largest)", fontsize=9)
    ax = axes[1, 1]
    th2 = np.linspace(*p.range2, 200)
    t = p.term()
    ax.plot(np.degrees(th2), t.moment(th2), "C1-", lw=2, label="spring 13 moment on link 2")
    ax.plot(np.degrees(th2), -w["D"] * p.l2 * np.cos(th2), "k--", lw=1.5, label="gravity moment of W_D about A")
    ax.set_xlabel("upper arm angle θ2 (deg from horizontal)")
    ax.set_ylabel("moment about A (N·m)")
    ax.legend(fontsize=8, loc="lower center")
    ax.grid(alpha=0.3)
    loads = ", ".join(f"{p.vertical_load(f):.4g}" for f in PAYLOADS)
    ax.set_title(f"spring cancels W_D·l2·cos θ2 exactly; vertical load at B {loads} N (payload 0, ½, 1)",
                 fontsize=9)
    fig.suptitle(f"Pantograph manipulator, k = {p.k:g}: cylinder base P = ({base[0]:.3g}, {base[1]:.3g}) m",
                 fontsize=11)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def plot_compare(result, path: str, n: int = 241) -> str:
    """A :class:`~balance.problems.compare.Comparison`: per loaded joint, its torque before and after each
    strategy along a sweep of the joint (the others at 80 % of their workspace ranges, the largest payload),
    and bars of the largest (a true extreme over the workspace and payloads) and RMS residual."""
    plt = _plt()
    arm, strategies = result.arm, [s for s in result.strategies if s.available]
    base = strategies[0]
    joints = [i for i, j in enumerate(base.joints) if j.baseline_max > 0]
    lo = np.array([w[0] for w in result.workspace])
    hi = np.array([w[1] for w in result.workspace])
    pose = lo + 0.8 * (hi - lo)
    payload = result.payload[1]
    colors = {"none": "k", "counterweights": "C0", "springs per joint": "C1", "harmonic, pruned": "C2",
              "exact springs": "C3"}
    dashes = {"counterweights": (0, (1, 1.5)), "springs per joint": "--", "harmonic, pruned": (0, (6, 2)),
              "exact springs": (0, (3, 1, 1, 1))}
    cols = max(len(joints), 1)
    fig, axes = plt.subplots(2, cols, figsize=(max(4.2 * cols, 9.0), 7.4), constrained_layout=True, squeeze=False)
    for c, i in enumerate(joints):
        rev = arm.coordinates[i].joint != "prismatic"
        x = np.linspace(lo[i], hi[i], n)
        q = np.tile(pose, (n, 1))
        q[:, i] = x
        grav = result.gravity(q, payload)
        xs = np.degrees(x) if rev else x
        unit = "N·m" if rev else "N"
        top, bot = axes[0][c], axes[1][c]
        curves = {s.name: grav[:, i] + s.forces(q)[:, i] for s in strategies}
        for s in strategies:
            r = curves[s.name]
            top.plot(xs, r, color=colors[s.name], lw=2.2 if s.name in ("none", "counterweights") else 1.4,
                     ls=dashes.get(s.name, "-"), label="gravity (no balancing)" if s.name == "none" else s.name)
        top.axhline(0, color="0.5", lw=0.6)
        largest = max(s.joints[i].max for s in strategies)
        if max(np.abs(r).max() for r in curves.values()) <= ZERO_SHARE * largest:  # rounding only: not magnified
            top.set_ylim(-largest, largest)
            top.text(0.5, 0.62, f"every curve zero at this pose\n(below {ZERO_SHARE:g} of {largest:.3g} {'N·m' if rev else 'N'},\n"
                     "the largest over the workspace)", transform=top.transAxes, ha="center", va="center", fontsize=8)
        top.set_title(f"q{i + 1} ({arm.coordinates[i].name}) swept\nothers at 80 % of their ranges, payload "
                      f"{payload:g} kg", fontsize=9)
        top.set_xlabel(f"q{i + 1} ({'deg' if rev else 'm'})")
        top.set_ylabel(f"torque the drive carries ({unit})")
        top.grid(alpha=0.3)
        if c == 0:
            top.legend(fontsize=7, loc="best")
        names = [s.name for s in strategies]
        y = np.arange(len(strategies))[::-1]
        bot.barh(y, [s.joints[i].max for s in strategies], color=[colors[m] for m in names], alpha=0.35,
                 label="largest (true extreme)")
        bot.barh(y, [s.joints[i].rms for s in strategies], height=0.4, color=[colors[m] for m in names],
                 label="RMS")
        for yy, s in zip(y, strategies):
            j = s.joints[i]
            bot.text(j.max, yy, f" {j.max:.3g} ({round(100 * j.removed_max) + 0:.0f} %)", va="center", fontsize=7)
        bot.set_yticks(y, names, fontsize=8)
        bot.set_xlabel(f"residual torque ({unit})\nover the workspace and payloads")  # (one line ran off the page)
        bot.set_xlim(0, 1.3 * max(s.joints[i].max for s in strategies))
        bot.grid(alpha=0.3, axis="x")
        if c == 0:
            bot.legend(fontsize=7, loc="lower right")
    unavailable = [f"{s.name}: {s.reason}" for s in result.strategies if not s.available]
    title = (f"{arm.name}: gravity torque before and after each strategy (payload {result.payload[0]:g} … "
             f"{result.payload[1]:g} kg)")
    if unavailable:
        import textwrap

        title += "\n" + "\n".join(textwrap.fill(u, 24 * max(cols, 4)) for u in unavailable)
    fig.suptitle(title, fontsize=10)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def plot_linkage(result, path: str, n: int = 361) -> str:
    """A :class:`~balance.problems.linkage.LinkageBalance`: left, the shaking force's amplitude per ω² over
    the input before and after (or, where the range ends at a dead position, the first moment's distance
    from its value at the range's start); right, the linkage in its pose with its centres of mass, the
    counterweights (area ∝ mass) and the path of the centre of mass before and after."""
    from .model.linkage import first_moment

    plt = _plt()
    problem = result.problem
    lo, hi = result.input_range
    q = np.linspace(lo, hi, n)
    motion = problem.motion(q)
    revolute = result.input_kind == "revolute"
    x = np.degrees(q) if revolute else q
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.6), constrained_layout=True)
    for balanced, style, label in ((False, "C3-", "before"), (True, "C0--", "after")):
        mass, moment = result.masses(balanced)
        if problem.dead_ends:
            m = first_moment(mass, moment, motion)
            ax1.plot(x, np.hypot(*(m - m[0]).T), style, lw=1.8, label=label)
        else:
            ax1.plot(x, np.hypot(*first_moment(mass, moment, motion, order=2).T), style, lw=1.8, label=label)
        com = first_moment(mass, moment, motion) / mass.sum()
        ax2.plot(com[:, 0], com[:, 1], style, lw=1.2, marker="." if balanced else None, markevery=[0],
                 label=f"centre of mass, {label}")
    ax1.set_xlabel(f"input {result.input} ({'deg' if revolute else 'm'})")
    ax1.set_ylabel("|M(q) − M(start)| (kg·m)" if problem.dead_ends else
                   f"shaking force per ω² ({result.shaking_force_unit})")
    b, a = result.before, result.after
    value = (lambda v: "—" if v is None else f"{v:.4g}")
    first = (f"first moment's excursion {b.moment_excursion:.4g} → {a.moment_excursion:.3g} kg·m (dead positions at the "
             "range's ends)" if problem.dead_ends else
             f"shaking force per ω² {value(b.shaking_force)} → {value(a.shaking_force)}")
    ax1.set_title(f"{result.name}: {first}\ncentre of mass's excursion {b.com_excursion:.3g} → {a.com_excursion:.3g} m",
                  fontsize=9)
    ax1.legend(loc="best", fontsize=8)
    ax1.grid(alpha=0.3)
    for body in result.links:
        pts = np.array([p for _, p in body.joints], dtype=float)
        ring = np.vstack([pts, pts[:1]]) if len(pts) > 2 else pts
        ax2.plot(ring[:, 0], ring[:, 1], "k-", lw=2.5, solid_capstyle="round")
        ax2.plot(pts[:, 0], pts[:, 1], "o", ms=5, mfc="white", mec="k")
        if body.mass > 0:
            ax2.plot(*body.centre, "k+", ms=8)
        if body.pivot is not None:
            ax2.plot(*body.joint(body.pivot), "k^", ms=10, mfc="0.7")
        ax2.annotate(str(body.link), np.mean(pts, axis=0), fontsize=9, color="0.3", xytext=(4, 4),
                     textcoords="offset points")
    # the counterweights found (blue) and those the links carried already (grey), each on a rod to its link's joint
    weights = [(c.at, c.mass, dict(next(bd for bd in result.links if bd.link == c.link).joints)[c.joint], "C0")
               for c in result.counterweights] + [(b.centre, b.mass, b.joint(b.anchor), "0.55") for b in result.carried]
    biggest = max([m for _, m, _, _ in weights] + [1e-300])
    middle = np.mean([p for body in result.links for _, p in body.joints], axis=0)[0]
    for at, mass, joint, colour in weights:
        if mass > 0:
            ax2.plot(*zip(at, joint), "-", color=colour, lw=1.5)
            area = 60 + 240 * mass / biggest  # points²: the label starts beyond the dot's radius, on the side of
            ax2.scatter(*at, s=area, color=colour, zorder=5)  # the linkage's middle (inwards)
            side = 1 if at[0] <= middle else -1
            ax2.annotate(f"{mass:.3g} kg", at, fontsize=8, color=colour, textcoords="offset points", va="center",
                         xytext=(side * (math.sqrt(area / math.pi) + 3), 0), ha="left" if side > 0 else "right")
    ax2.margins(0.15)  # room in the panel for the dots (drawn in points) and their labels at its edges,
    ax2.set_aspect("equal", adjustable="box")  # kept: the panel's box takes the aspect, not its limits
    ax2.set_title("the pose: links (black), their centres (+), frame pivots (▲),\ncounterweights (blue, area ∝ mass"
                  + ("; grey: carried already)" if result.carried else ")"), fontsize=9)
    ax2.legend(loc="best", fontsize=8)
    ax2.grid(alpha=0.3)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path
