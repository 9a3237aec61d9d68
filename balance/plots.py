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


def plot_spring(res: FitResult, path: str) -> str:
    """Target ``Φ0·sin φ`` against the device moment, and the relative residual."""
    plt = _plt()
    lo, hi = res.phi_range
    phi = np.linspace(lo, hi, 1001)
    dev = res.device
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    deg = np.degrees(phi)
    ax1.plot(deg, res.moment * np.sin(phi), "k-", lw=2, label="target  Φ0·sin φ")
    ax1.plot(deg, dev.moment(phi), "C1--", lw=1.5, label=f"{res.kind} device")
    ax1.set_ylabel("moment on the crank (N·m)")
    ax1.set_title(
        f"{res.kind} spring, {res.method}/{res.norm}: c = {res.c:.4g} N/m, r = {res.r:.4g} m, "
        f"r0 = {res.r0:.4g} m, a = {res.a:.4g} m", fontsize=9)
    ax1.legend(loc="best", fontsize=8)
    ax1.grid(alpha=0.3)
    e = relative_errors(dev, res.moment, phi)
    ax2.plot(deg, 100 * e, "C3-")
    ax2.axhline(0, color="k", lw=0.5)
    ax2.set_ylabel("(M − Φ0·sin φ)/|Φ0|  (%)")
    ax2.set_xlabel("crank angle φ (deg, from the base point C)")
    ax2.set_title(f"max {100 * res.max_rel_error:.3g} %, RMS {100 * res.rms_rel_error:.3g} %", fontsize=9)
    ax2.grid(alpha=0.3)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


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


def plot_pantograph(p, path: str) -> str:
    """Sketch at mid-range with the substitution weights, and the spring moment vs θ2."""
    plt = _plt()
    t2 = 0.5 * (p.range2[0] + p.range2[1])
    t3 = 0.5 * (p.range3[0] + p.range3[1])
    u2 = np.array([math.cos(t2), math.sin(t2)])
    u3 = np.array([math.cos(t3), math.sin(t3)])
    A = np.zeros(2)
    D = p.l2 * u2
    C = D + p.l3 * u3
    E = p.e * u2
    B = E + p.g * u3
    F = D + p.g * u3
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
    for P, Q in ((A, D), (D, C), (E, B), (F, B)):
        ax1.plot([P[0], Q[0]], [P[1], Q[1]], "k-", lw=2)
    ax1.plot([A[0], C[0]], [A[1], C[1]], "C0:", lw=1)
    w = p.point_weights()
    for name, P in (("A", A), ("D", D), ("B", B), ("C", C)):
        ax1.plot(*P, "o", ms=4 + 10 * w[name] / max(w.values()), color="C3")
        ax1.annotate(f"{name}: {w[name]:.4g} N", P, textcoords="offset points", xytext=(6, 6), fontsize=8)
    ax1.set_aspect("equal")
    ax1.set_title("substitution weights (half payload)", fontsize=9)
    th = np.linspace(*p.range2, 200)
    t = p.term()
    ax2.plot(np.degrees(th), t.moment(th), "C1", label="spring moment on the upper arm")
    ax2.plot(np.degrees(th), -w["D"] * p.l2 * np.cos(th), "k--", label="gravity moment of W_D")
    ax2.set_xlabel("θ2 (deg from horizontal)")
    ax2.set_ylabel("N·m")
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3)
    ax2.set_title(f"drive force at B: {p.drive_force():.4g} N (constant)", fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
