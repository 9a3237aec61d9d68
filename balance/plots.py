"""Matplotlib figures (Agg backend, imported only when a plot is asked for)."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .arm import Arm
from .fit import FitResult, relative_errors
from .potential import HarmonicTerm, terms_forces

__all__ = ["plot_spring", "plot_arm", "plot_prismatic", "plot_pantograph"]


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_spring(res: FitResult, path: str, front: list[dict] | None = None, spring: dict | None = None) -> str:
    """Target ``Φ0·sin φ`` against the device moment, the relative residual, and (given) the
    Pareto front of error against free length and peak force."""
    plt = _plt()
    lo, hi = res.phi_range
    phi = np.linspace(lo, hi, 1001)
    dev = res.device
    panels = 3 if front else 2
    fig, axes = plt.subplots(panels, 1, figsize=(7.5, 3.2 * panels + 0.4), constrained_layout=True)
    ax1, ax2 = axes[0], axes[1]
    deg = np.degrees(phi)
    ax1.plot(deg, res.moment * np.sin(phi), "k-", lw=2, label="target  Φ0·sin φ")
    ax1.plot(deg, dev.moment(phi), "C1--", lw=1.5, label=f"{res.kind} device")
    ax1.set_ylabel("moment on the crank (N·m)")
    ax1.set_xlabel("crank angle φ (deg, from the base point C)")
    title = (f"{res.kind} device ({res.method}): c = {res.c:.4g} N/m, r = {res.r:.4g} m, "
             f"r0 = {res.r0:.4g} m, a = {res.a:.4g} m")
    if spring:
        title += (f"\nspring: d = {1e3 * spring['wire_diameter_m']:.3g} mm, D = {1e3 * spring['mean_diameter_m']:.4g} mm, "
                  f"n = {spring['active_coils']:g}, {spring['material']}")
    ax1.set_title(title, fontsize=9)
    ax1.legend(loc="best", fontsize=8)
    ax1.grid(alpha=0.3)
    e = relative_errors(dev, res.moment, phi)
    ax2.plot(deg, 100 * e, "C3-")
    ax2.axhline(0, color="k", lw=0.5)
    ax2.set_ylabel("(M − Φ0·sin φ)/|Φ0|  (%)")
    ax2.set_xlabel("crank angle φ (deg, from the base point C)")
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
            groups.setdefault(float(f"{pt['force']:.3g}"), []).append(pt)
        cmap = plt.get_cmap("viridis")
        levels = sorted(groups)
        for i, f in enumerate(levels):
            pts = sorted(groups[f], key=lambda q: q["size"])
            ax3.plot([q["size"] for q in pts], [100 * q["error"] for q in pts], "o-", ms=4, lw=1.2,
                     color=cmap(i / max(len(levels) - 1, 1)), label=f"peak force {f:.3g} N")
        ax3.plot(res.free_length, 100 * (res.max_rel_error if res.norm == "max" else res.rms_rel_error), "o",
                 ms=13, mfc="none", mec="red", mew=2, label="this fit")
        ax3.set_xscale("log")
        ax3.set_yscale("log")
        ax3.set_xlabel("device size: free length 2r + r0 + a (m)")
        ax3.set_ylabel(f"{res.norm} relative error (%)")
        ax3.set_title("Pareto front: error against size, one line per peak spring force", fontsize=9)
        ax3.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
        ax3.grid(alpha=0.3, which="both")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _log_norm(values):
    from matplotlib.colors import LogNorm

    v = np.asarray(values)
    return LogNorm(vmin=max(float(np.min(v)), 1e-12), vmax=max(float(np.max(v)), float(np.min(v)) * 1.01, 1e-12))


def _two_joints(arm: Arm) -> tuple[int, int]:
    moving = [i for i, ln in enumerate(arm.links) if ln.joint != "vertical"]
    if len(moving) >= 2:
        return moving[0], moving[1]
    return moving[0], moving[0]


def plot_arm(arm: Arm, terms: Sequence[HarmonicTerm], path: str, n: int = 121) -> str:
    """Residual generalised force (max over joints) over a 2-D slice of the workspace.

    The slice spans the first two in-plane joints; the other joints sit at mid-range.
    With a payload the right panel shows the residual at full payload.
    """
    plt = _plt()
    i, j = _two_joints(arm)
    lim = [ln.limits for ln in arm.links]
    mid = np.array([(a + b) / 2 for a, b in lim])
    xi = np.linspace(*lim[i], n)
    xj = np.linspace(*lim[j], n) if j != i else np.array([mid[j]])
    X, Y = np.meshgrid(xi, xj)
    q = np.tile(mid, (X.size, 1))
    q[:, i] = X.ravel()
    if j != i:
        q[:, j] = Y.ravel()
    panels = [("tuned (half payload)", arm.with_payload_fraction(0.5))]
    if any(ld.payload for ld in arm.loads):
        panels.append(("full payload", arm.with_payload_fraction(1.0)))
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 5), constrained_layout=True, squeeze=False)
    for ax, (title, a) in zip(axes[0], panels):
        res = np.max(np.abs(a.gravity_forces(q) - terms_forces(terms, q)), axis=1).reshape(X.shape)
        scale = lambda v: np.degrees(v) if arm.links[i].joint == "revolute" else v  # noqa: E731
        val = np.log10(np.maximum(res, 1e-16))
        if j != i:
            im = ax.pcolormesh(scale(X), np.degrees(Y) if arm.links[j].joint == "revolute" else Y, val,
                               shading="auto", cmap="viridis")
            fig.colorbar(im, ax=ax, label="log10 max |residual| (N·m or N)")
            ax.set_ylabel(f"q{j + 1} ({'deg' if arm.links[j].joint == 'revolute' else 'm'})")
        else:
            ax.semilogy(scale(xi), np.maximum(res.ravel(), 1e-16))
            ax.set_ylabel("max |residual|")
        ax.set_xlabel(f"q{i + 1} ({'deg' if arm.links[i].joint == 'revolute' else 'm'})")
        ax.set_title(f"{arm.name}: {title}\nmax residual {np.max(res):.3g}", fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_prismatic(m: float, inertia: float, M: float, q_max: float, stroke: float, C: float, path: str) -> str:
    """Counter-mass laws ``z1(q)``, ``z2(q)`` and the inertia they keep."""
    from .countermass import counter_mass_laws

    plt = _plt()
    q = np.linspace(-stroke, stroke, 801)
    z1, z2, disc = counter_mass_laws(q, m, inertia, M, C)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    ax1.plot(q, z1, label="z1(q)")
    ax1.plot(q, z2, label="z2(q)")
    ax1.plot(q, q, "k:", lw=1, label="link q")
    ax1.set_ylabel("position along Z (m)")
    ax1.set_title(f"m = {m:g} kg, I = {inertia:g} kg·m², M = {M:g} kg, C = {C:.4g} kg·m²", fontsize=9)
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    inert = inertia + m * q * q + M * (z1 * z1 + z2 * z2)
    ax2.plot(q, inert - C, "C3")
    ax2.set_ylabel("I_total − C (kg·m²)")
    ax2.set_xlabel("slide q (m)")
    ax2.grid(alpha=0.3)
    if np.any(disc < 0):
        ax2.set_title("stroke beyond the design limit: inertia no longer constant", fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_pantograph(p, path: str, n: int = 61) -> str:
    """The mechanism at mid-range with its links numbered, the cylinder force and the
    operator's force over the workspace, and the spring moment against ``W_D``'s."""
    from .pantograph import PAYLOADS

    plt = _plt()
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
        ax.annotate(num, 0.5 * (P[a] + P[b]), textcoords="offset points", xytext=tuple(11 * nrm),
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
    for ax, fn, label, title in (
        (axes[0, 1], p.cylinder_force, "cylinder force F (N)", "cylinder 10 force, half payload"),
        (axes[1, 0], p.hand_force, "operator's force along A→C (N)", "what the operator holds, half payload"),
    ):
        Z = fn(th, 0.5).reshape(X.shape)
        im = ax.contourf(np.degrees(X), np.degrees(Y), Z, levels=14, cmap="viridis")
        cs = ax.contour(np.degrees(X), np.degrees(Y), Z, levels=7, colors="w", linewidths=0.6)
        ax.clabel(cs, fontsize=7, fmt="%.0f")
        fig.colorbar(im, ax=ax, label=label)
        ax.set_xlabel("upper arm angle θ2 (deg from horizontal)")
        ax.set_ylabel("forearm angle θ3 (deg from horizontal)")
        lo, hi = float(np.min(Z)), float(np.max(Z))
        ax.set_title(f"{title}: {lo:.4g} … {hi:.4g} N", fontsize=9)
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
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
