"""Error against time of every spring device × fitting method, and the residual point by point.

One case per device (slotted lever with a compression spring, offset slider-crank, sine device
with a real spring), each with bounds that bind inside the box (force, free length), so the optimum
is no corner of it. Each device is fitted by least squares (trf, RMS norm), by three minimax methods
(SLSQP, trf with Lawson's reweighting, Nelder–Mead) and by a global search polished locally (DE then
SLSQP). Times are the best of three runs; errors are measured on the physical device (the largest by
a bracketed maximiser from a fine grid). Writes benchmarks/DEVICES.md (tables) and two figures in benchmarks/figures/.

    python benchmarks/bench_devices.py            # about a minute on a quiet 2-core machine

From Python: ``rows, residuals = run()``.
"""

from __future__ import annotations

import math
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from balance import SpringBounds, fit_spring  # noqa: E402
from mechbase import save_figure  # noqa: E402

FIGURES = ROOT / "benchmarks" / "figures"
REPORT = ROOT / "benchmarks" / "DEVICES.md"

#: device -> (spring kind, Φ0 N·m, range in degrees, bounds)
CASES = {
    "slotted-lever": ("compression", 100.0, (20.0, 160.0),
                      SpringBounds((0.01, 0.5), (0.01, 1.0), (0.0, 1.0), max_force=2000.0, max_free_length=1.5,
                                   max_deflection=0.4)),
    "slider-crank": ("compression", 40.0, (-10.0, 150.0),
                     SpringBounds((0.03, 0.15), None, (0.0, 0.4), max_force=900.0, max_free_length=0.5,
                                  rod=(0.15, 0.5), offset=(-0.08, 0.08))),
    "sine": ("compression", -30.0, (-80.0, 250.0),
             SpringBounds((0.02, 0.12), None, (0.0, 0.3), max_force=1500.0, max_free_length=0.5)),
}
#: label -> (method, norm)
METHODS = {
    "least squares (trf, RMS)": ("trf", "rms"),
    "minimax (SLSQP)": ("slsqp", "max"),
    "minimax (trf + Lawson)": ("trf", "max"),
    "minimax (Nelder–Mead)": ("nelder-mead", "max"),
    "global then polish (DE + SLSQP)": ("de", "max"),
}
REPEATS = 3
#: the angles of the point-by-point table (every 20° of the range, and its ends)
STEP_DEG = 20.0


def run():
    """Rows (device, method, seconds, errors) and the residual moment of each fit along the range."""
    rows, residuals = [], {}
    for device, (kind, moment, rng, bounds) in CASES.items():
        lo, hi = math.radians(rng[0]), math.radians(rng[1])
        for label, (method, norm) in METHODS.items():
            best = None
            for _ in range(REPEATS):
                t0 = time.perf_counter()
                res = fit_spring(kind, moment, (lo, hi), bounds, method=method, norm=norm, device=device)
                wall = time.perf_counter() - t0
                best = wall if best is None else min(best, wall)
            print(f"{device:14s} {label:32s} {best:7.3f} s  max {100 * res.max_rel_error:.4f} %  "
                  f"RMS {100 * res.rms_rel_error:.4f} %", file=sys.stderr)
            rows.append({"device": device, "method": label, "seconds": best, "max_rel_error": res.max_rel_error,
                         "rms_rel_error": res.rms_rel_error, "max_residual": res.max_rel_error * abs(moment),
                         "moment": moment, "nfev": res.nfev, "active": ", ".join(res.active_bounds),
                         "x": res.x, "restarts": res.restarts})
            residuals[(device, label)] = res.device
    return rows, residuals


def _angles(rng) -> np.ndarray:
    inner = np.arange(math.ceil(rng[0] / STEP_DEG) * STEP_DEG, rng[1], STEP_DEG)
    return np.unique(np.concatenate([[rng[0]], inner, [rng[1]]]))


def write(rows, residuals) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    FIGURES.mkdir(parents=True, exist_ok=True)
    devices = list(CASES)
    from matplotlib.ticker import FormatStrFormatter, NullFormatter

    fig, axes = plt.subplots(1, len(devices), figsize=(13, 4.8), constrained_layout=True)
    for ax, device in zip(axes, devices):
        for k, label in enumerate(METHODS):
            (r,) = [r for r in rows if r["device"] == device and r["method"] == label]
            ax.plot(r["seconds"], 100 * r["max_rel_error"], "o", color=f"C{k}", ms=8, label=f"{label}: max")
            ax.plot(r["seconds"], 100 * r["rms_rel_error"], "s", color=f"C{k}", ms=7, mfc="none",
                    label=f"{label}: RMS")
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("seconds (best of 3, log scale)")
        ax.set_ylabel("error relative to |Φ0| (%)")
        kind, moment, rng, _ = CASES[device]
        ax.set_title(f"{device}: Φ0 = {moment:g} N·m, {rng[0]:g}°..{rng[1]:g}°", fontsize=10)
        ax.grid(alpha=0.3, which="both")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=5, fontsize=7.5)
    fig.suptitle("filled: largest error, hollow: RMS error", fontsize=9)
    save_figure(fig, FIGURES / "devices_error_time.png", dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, len(devices), figsize=(13, 4.2), constrained_layout=True)
    for ax, device in zip(axes, devices):
        kind, moment, rng, _ = CASES[device]
        phi = np.linspace(math.radians(rng[0]), math.radians(rng[1]), 1001)
        for k, label in enumerate(METHODS):
            dev = residuals[(device, label)]
            ax.plot(np.degrees(phi), dev.moment(phi) - moment * np.sin(phi), color=f"C{k}",
                    lw=2.5 if k == 0 else 1.2, ls="-" if k < 2 else "--", label=label)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlabel("crank angle φ (deg)")
        ax.set_ylabel("residual moment M − Φ0·sin φ (N·m)")
        ax.set_title(f"{device}: Φ0 = {moment:g} N·m", fontsize=10)
        ax.grid(alpha=0.3)
        right = ax.secondary_yaxis("right", functions=(lambda m, s=abs(moment): 100 * m / s,
                                                      lambda p, s=abs(moment): p * s / 100))
        right.set_ylabel("relative to |Φ0| (%)")
    axes[0].legend(fontsize=7, loc="best")
    save_figure(fig, FIGURES / "devices_residuals.png", dpi=110)
    plt.close(fig)

    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    lines = ["# Spring devices: error against time, and the residual point by point", "",
             f"`python benchmarks/bench_devices.py` on {platform.processor() or platform.machine()}, "
             f"Python {platform.python_version()}, commit `{commit}`, "
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}. "
             "Times are the best of three runs on a shared 2-core machine (noise ~10 %); errors are measured on the "
             "fitted device (the largest by a bracketed maximiser: every local maximum of a 4001-point grid "
             "refined by bounded Brent between its neighbours; the RMS on that grid).", "",
             "Cases (each optimum has a bound binding inside the box: no corner of it):", ""]
    for device, (kind, moment, rng, b) in CASES.items():
        given = ", ".join(f"{k} {v[0]:g}..{v[1]:g} m" for k, v in (("r", b.r), ("r0", b.r0), ("a", b.a), ("rod", b.rod),
                                                                    ("offset", b.offset)) if v is not None)
        limits = ", ".join(f"{k} {v:g}" for k, v in (("max force (N)", b.max_force),
                                                      ("max free length (m)", b.max_free_length),
                                                      ("max deflection", b.max_deflection)) if v is not None)
        lines.append(f"- **{device}** ({kind} spring): Φ0 = {moment:g} N·m over {rng[0]:g}°..{rng[1]:g}°; {given}; "
                     f"{limits}.")
    lines += ["", "![error against time](figures/devices_error_time.png)", "",
              "| device | method | seconds | max error (%) | RMS error (%) | max residual (N·m) | evaluations | "
              "restarts | bounds it sits on |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['device']} | {r['method']} | {r['seconds']:.3f} | {100 * r['max_rel_error']:.4f} | "
                     f"{100 * r['rms_rel_error']:.4f} | {r['max_residual']:.4g} | {r['nfev']} | {r['restarts']} | "
                     f"{r['active'] or 'none'} |")
    minimax = [label for label, (_, norm) in METHODS.items() if norm == "max"]
    spread = max(abs(float(residuals[(d, m)].moment(math.radians(deg))) - float(residuals[(d, minimax[0])].moment(
        math.radians(deg)))) / abs(CASES[d][1]) for d in CASES for m in minimax for deg in _angles(CASES[d][2]))
    lines += ["", "## The residual moment point by point", "",
              "Residual `M(φ) − Φ0·sin φ` in N·m, and in brackets relative to |Φ0| (%), at every 20° of the range "
              "and its ends, for least squares, minimax by SLSQP and the global search; the other minimax methods "
              f"differ from SLSQP's residual by at most {100 * spread:.2g} % of |Φ0| at these points.", "",
              "![residuals](figures/devices_residuals.png)", ""]
    for device, (kind, moment, rng, _) in CASES.items():
        labels = ["least squares (trf, RMS)", "minimax (SLSQP)", "global then polish (DE + SLSQP)"]
        lines += [f"### {device} (Φ0 = {moment:g} N·m)", "", "| φ (°) | " + " | ".join(labels) + " |",
                  "|---" * (len(labels) + 1) + "|"]
        for deg in _angles(rng):
            phi = math.radians(deg)
            cells = []
            for label in labels:
                res = float(residuals[(device, label)].moment(phi)) - moment * math.sin(phi)
                cells.append(f"{res:+.4f} ({100 * res / abs(moment):+.3f} %)")
            lines.append(f"| {deg:g} | " + " | ".join(cells) + " |")
        lines.append("")
    REPORT.write_text("\n".join(lines))


if __name__ == "__main__":
    write(*run())
    print(f"wrote {REPORT.relative_to(ROOT)} and benchmarks/figures/devices_*.png", file=sys.stderr)
