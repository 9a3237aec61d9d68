"""Balancing computations of a scene: ``balance arm``, ``balance spring``, ``balance prismatic``,
``balance pantograph`` and the ``plot`` of their results.

The balance package owns its tables (``[arm]``, ``[spring]``, ``[slider]``,
``[pantograph]``): the runner hands each table to ``balance.problems`` unchanged and
turns a :class:`balance.errors.BalanceError` into the scene's one sentence.  The typed
result is the computation's result and is kept for the figure (which draws it, never solving
again); its row is what ``[expect]`` compares, with the values a scene derives from it (the arm's
terms in order, the strategies compared) added by :class:`Derived`.  Nothing here imports balance until a balancing scene runs,
and nothing imports synth's solvers.

To add a balance problem, call :func:`balance_kind` once: its table, the
``balance.problems`` function that solves it, the ``[expect]`` keys of its result, its
summary lines and, optionally, its figure.

>>> sorted(k for k in KINDS if k.startswith("balance"))    # (balance linkage moves a linkage: mechsynth.scene.motion)
['balance arm', 'balance compare', 'balance linkage', 'balance pantograph', 'balance prismatic', 'balance spring']
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mechbase import Row
from mechbase.schema import FileName, Table

from . import compare
from .registry import KINDS, ComputeKind, Expectation, Run, SceneTable, Family
from .results import Scene, SceneError
from .types import Flag, Int, Number, NumberRows, Numbers, NumberTable, Texts

__all__ = ["balance_kind", "Plot", "Derived", "Figures"]

#: balance kind -> the name of its figure in ``balance.plots``: ``plot(result, out)``.
_PLOTTERS: dict[str, str] = {}


def _read_balance_table(raw, path: str, compute: frozenset):
    return dict(raw)  # validated by balance.problems when the scene runs


FAMILY = Family("balancing")  # its tables and computations, registered by mechsynth.scene


@dataclass(frozen=True)
class Derived(Row):
    """A balance result and the values a scene derives from its row: the result's row, then the
    derived keys (``derive(row) -> dict``)."""

    result: Any
    derive: Callable[[dict], dict]
    row_keys = ("*result", "*derived")

    @property
    def derived(self) -> dict:
        return self.derive(self.result.to_dict())


def balance_kind(name: str, table: str, solver: str, summary: str, hint: str, *,
                 expect: Mapping[str, Expectation], report: Callable[[dict], list[str]],
                 after: Callable[[dict], dict] | None = None, plot: str | None = None) -> ComputeKind:
    """Register the compute word ``name`` solving the table ``[table]`` with ``balance.<solver>``.

    ``after(row)`` derives values from the result's row (added after it, :class:`Derived`); ``plot`` names
    its figure's function in ``balance``.
    """

    def run(r: Run) -> Row:
        import balance
        from balance import BalanceError

        try:
            result = getattr(balance, solver)({table: r.scene.tables[table]}, r.scene.path)
        except BalanceError as exc:
            msg = str(exc).rstrip(".")
            prefix = f"{r.scene.path}: "
            raise SceneError((msg if msg.startswith(prefix) else f"{prefix}[{table}] {msg}") + ".") from None
        r.shared(f"{name} result", dict)["result"] = result  # the typed result, for the figure
        return Derived(result, after) if after else result

    FAMILY.table(SceneTable(table, _read_balance_table, hint))
    if plot is not None:
        _PLOTTERS[name] = plot
    return FAMILY.kind(ComputeKind(name, summary, table, run, expect=expect, report=report))


# --------------------------------------------------------------------------- the kinds
def _arm_terms(row: dict) -> dict:
    terms = sorted(row["terms"], key=lambda t: -t["amplitude"])
    return {"amplitudes": [t["amplitude"] for t in terms], "phases_deg": [t["phase_deg"] for t in terms],
            "forms": [t["form"] for t in terms], "drive_forms": [t["drive_form"] for t in terms],
            "eT": sorted((d["sine"]["eT"] for d in row["devices"] if "sine" in d), reverse=True)}


def _below(path: tuple = ()) -> Expectation:
    return Expectation(Number, path, below=True)


_RESIDUALS = {"relative_residual": _below(), "max_residual": _below()}

balance_kind(
    "balance arm", "arm", "solve_arm", "static balancing of an [arm]: harmonic terms, devices, residuals",
    "the arm's links, joints and weights",
    expect={
        "amplitudes": Expectation(Numbers, compare=compare.multiset),
        "phases_deg": Expectation(Numbers),
        "forms": Expectation(NumberRows),
        "drive_forms": Expectation(NumberRows),
        "eT": Expectation(Numbers, compare=compare.multiset),
        "gear_ratio": Expectation(Number, ("prismatic", 0, "gear_ratio")),
        "gamma_max": Expectation(Number, ("prismatic", 0, "gamma_max")),
        "residual_bound_per_joint": Expectation(Numbers, ("prismatic", 0, "residual_bound_per_joint")),
        "potential_spread": _below(),
        **_RESIDUALS,
    },
    report=lambda r: [f"terms: {' '.join(str(round(a, 6)) for a in r['amplitudes'])} (amplitudes)",
                      f"max residual {r['max_residual']:.3g}, relative {r['relative_residual']:.3g}"],
    after=_arm_terms, plot="plot_arm")

balance_kind(
    "balance spring", "spring", "solve_spring", "fit of a spring device ([spring]: slotted lever, slider-crank, sine)",
    "the moment, the angle range and the bounds of the device",
    expect={
        **{k: _below() for k in ("r", "r0", "a", "c", "d", "free_length", "max_force", "max_rel_error",
                                 "rms_rel_error", "rod", "offset", "neutral")},
        "seconds": Expectation(Number, below=True, best_of=3),  # timings on a shared machine are noisy
        "active_bounds": Expectation(Texts),
        "sense": Expectation(Int),
    },
    report=lambda r: [f"{r['family']}: c = {r['c']:.6g} N/m, r = {r['r']:.6g} m, "
                      + "".join(f"{key} = {r[key]:.6g} m, " for key in ("r0", "rod", "offset") if r[key] is not None)
                      + f"a = {r['a']:.6g} m",
                      f"max relative error {r['max_rel_error']:.4g}; "
                      f"active bounds {', '.join(r['active_bounds']) or 'none'}"],
    plot="plot_spring")

balance_kind(
    "balance prismatic", "slider", "solve_prismatic", "counter-masses of a sliding link ([slider])",
    "the sliding link's mass, counter-mass and stroke",
    expect={**{k: _below() for k in ("C_min", "C", "max_com_error", "max_inertia_error")},
            "crank_exact": Expectation(Flag, ("crank", "exact"))},
    report=lambda r: [f"C_min = {r['C_min']:.6g}, C = {r['C']:.6g}; max com error {r['max_com_error']:.3g}, "
                      f"inertia error {r['max_inertia_error']:.3g}"],
    plot="plot_prismatic")

balance_kind(
    "balance pantograph", "pantograph", "solve_pantograph", "pantograph balanced manipulator ([pantograph])",
    "the pantograph's lengths, ratio and weights",
    expect={
        "point_weights": Expectation(NumberTable, compare=compare.table),
        "spring_amplitude": _below(("term", "amplitude")),
        "drive_force": _below(),
        "drive_force_range": Expectation(Numbers),
        **_RESIDUALS,
    },
    report=lambda r: [f"point weights {', '.join(f'{k}: {v}' for k, v in r['point_weights'].items())}",
                      f"spring amplitude {r['term']['amplitude']:.6g} N·m, drive force {r['drive_force']:.6g} N, "
                      f"relative residual {r['relative_residual']:.3g}"],
    plot="plot_pantograph")


def _compare_summary(row: dict) -> dict:
    ok = [s for s in row["strategies"] if s["available"]]
    pruned = next(s for s in ok if s["name"] == "harmonic, pruned")
    return {"available": [s["name"] for s in ok], "removed": {s["name"]: s["removed"] for s in ok},
            "devices": {s["name"]: s["devices"] for s in ok}, "baseline": row["strategies"][0]["max_residual"],
            "pruned_residual": pruned["max_residual"], "pruned_target": pruned["details"]["target_torque"],
            "recheck": max(s["pinocchio"]["max_difference"] for s in ok)}


balance_kind(
    "balance compare", "compare", "solve_compare",
    "balancing strategies side by side for one arm ([compare]): residual torque, devices, added mass",
    "the arm's file, its payload range and workspace",
    expect={
        "available": Expectation(Texts),
        "removed": Expectation(NumberTable, compare=compare.table),
        "devices": Expectation(NumberTable, compare=compare.table),
        "baseline": Expectation(Number),
        "pruned_residual": _below(),
        "recheck": _below(),
    },
    report=lambda r: [f"{s['name']}: {100 * s['removed']:.1f} % of the largest torque removed, {s['devices']} "
                      f"devices, {s['added_mass']:.3g} kg" if s["available"] else f"{s['name']}: not available"
                      for s in r["strategies"]],
    after=_compare_summary, plot="plot_compare")


# --------------------------------------------------------------------------- plot
class Plot(Table):
    """The ``[plot]`` table: the figure's file name (default ``NAME.png``)."""

    out: FileName | None = None


def _check_plot(scene: Scene) -> None:
    if not set(scene.compute) & set(_PLOTTERS):
        raise scene.error(f"[scene] compute 'plot' needs a balance computation ({', '.join(_PLOTTERS)}) to plot")


@dataclass(frozen=True)
class Figures(Row):
    """``plot``: the figures written, or why none was."""

    files: tuple[str, ...]
    written: bool
    skipped: str | None = None
    row_keys = ("files", "written", "skipped?")


def _plot(run: Run) -> Figures:
    scene = run.scene
    kinds = [k for k in scene.compute if k in _PLOTTERS]
    name = Path((scene.tables.get("plot") or Plot()).out or f"{scene.name}.png")
    names = [name.stem + ("" if len(kinds) == 1 else "_" + KINDS[k].table) + name.suffix for k in kinds]
    if run.out_dir is None:
        return Figures((), False, f"no --out DIR given to write {', '.join(names)}")
    import balance

    files = []
    for kind, file_name in zip(kinds, names):
        out = run.picture(file_name)
        getattr(balance, _PLOTTERS[kind])(run.shared(f"{kind} result", dict)["result"], str(out))
        files.append(str(out))
    return Figures(tuple(files), True)


FAMILY.table(SceneTable.typed("plot", Plot, "the figure's file name"))
FAMILY.kind(ComputeKind(
    "plot", "a figure of the balance result (balance.plots): device moment, laws or residuals, written to --out",
    None, _plot, expect={"plotted": Expectation(Flag, ("written",))}, check=_check_plot,
    report=lambda r: [f"not plotted: {r['skipped']}"] if r.get("skipped") else [f"wrote {', '.join(r['files'])}"],
    reads=("plot",)))
