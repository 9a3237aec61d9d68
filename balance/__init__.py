"""Static and dynamic balancing of robot arms.

The pipeline, in the package's layout:

- :mod:`balance.model` — what is balanced: the gravity potential as harmonic terms
  (``potential``), planar arms from TOML (``arm``), arms from URDF with Pinocchio as the
  independent check (``urdf``), the pantograph manipulator (``pantograph``);
- :mod:`balance.devices` — what balances: spring devices (``springs``), their fit
  (``fit``) and trade-offs (``tradeoff``), helical springs a maker can wind (``helical``),
  gear trains (``transmission``), counterweights, counter-masses and the mass-matrix check of
  a sliding link (``countermass``, ``dynamics``);
- :mod:`balance.problems` — a TOML table (or the caller) states a problem; ``solve()``
  returns a typed result whose ``to_dict()`` is the JSON the CLI writes; ``compare`` sets the
  balancing strategies side by side for one arm;
- :mod:`balance.extremes` (true extremes over a workspace), :mod:`balance.budget` (the work a
  problem may take), :mod:`balance.schema` (the TOML tables), :mod:`balance.plots`,
  :mod:`balance.errors`.

``balance`` never imports ``synth``; names below load their module when first used.
See ``docs/balance.md``.

Examples
--------
>>> import balance
>>> doc = {"arm": {"links": [{"joint": "revolute", "length": 1.0, "weight": 10.0}]}}
>>> balance.solve_arm(doc).terms[0].amplitude
5.0
"""

from __future__ import annotations

import importlib

#: public name → the module that defines it
_WHERE = {
    # problems and results
    "read_problem": "problems", "load_toml": "schema", "solve_arm": "problems", "solve_spring": "problems",
    "solve_prismatic": "problems", "solve_pantograph": "problems",
    "ArmProblem": "problems.arm", "ArmBalance": "problems.arm", "CheckResult": "problems.arm",
    "DeviceSizes": "problems.arm", "balance_arm": "problems.arm", "check_terms": "problems.arm",
    "arm_from_dict": "problems.arm",
    "SpringProblem": "problems.spring", "SpringDesign": "problems.spring", "SpringOptions": "problems.spring",
    "SliderProblem": "problems.slider", "SliderBalance": "problems.slider", "DynamicsCheck": "problems.slider",
    "PantographProblem": "problems.pantograph", "PantographBalance": "problems.pantograph",
    "solve_compare": "problems", "CompareProblem": "problems.compare", "Comparison": "problems.compare",
    "LinkageProblem": "problems.linkage", "LinkageBalance": "problems.linkage", "BalanceState": "problems.linkage",
    # model
    "Arm": "model.arm", "Link": "model.arm", "Load": "model.arm", "Coordinate": "model.arm",
    "ArmModel": "model.arm", "gear_ratio_for_accuracy": "model.arm",
    "HarmonicTerm": "model.potential", "merge_terms": "model.potential",
    "UrdfArm": "model.urdf", "load_urdf": "model.urdf", "Pantograph": "model.pantograph",
    "DHLink": "model.urdf", "urdf_from_dh": "model.urdf",
    "LinkBody": "model.linkage", "bar_bodies": "model.linkage", "first_moment": "model.linkage",
    "body_arrays": "model.linkage", "moment_rate": "model.linkage",
    # devices
    "SpringBounds": "devices.fit", "FitResult": "devices.fit", "fit_spring": "devices.fit",
    "METHODS": "devices.fit", "NORMS": "devices.fit", "DEFAULT_METHOD": "devices.fit", "DEVICES": "devices.fit",
    "SliderSpringDevice": "devices.sliders",
    "CrankRockerDevice": "devices.springs", "SineDevice": "devices.springs", "crank_moment": "devices.springs",
    "spring_length": "devices.springs", "HelicalSpring": "devices.helical", "design_spring": "devices.helical",
    "CounterMass": "devices.countermass", "c_min": "devices.countermass",
    "counter_mass_laws": "devices.countermass", "crank_construction": "devices.countermass",
    "verify_counter_mass": "devices.countermass",
    "Counterweights": "devices.counterweights", "counterweights": "devices.counterweights",
    "place_counterweights": "devices.counterweights",
    "LinkCounterweight": "devices.link_counterweights", "fit_counterweights": "devices.link_counterweights",
    # reading a problem's tables and writing its results
    "parse": "schema", "linkage_table": "schema", "arm_problem": "problems.arm", "pantograph_problem": "problems.pantograph",
    "compare_problem": "problems.compare", "DEFAULT_GRID": "devices.fit", "format_form": "model.potential",
    "plot_spring": "plots", "plot_arm": "plots", "plot_prismatic": "plots", "plot_pantograph": "plots",
    "plot_compare": "plots", "plot_linkage": "plots",
    # the rest
    "Extreme": "extremes", "box_extremes": "extremes", "TooMuchWork": "budget",
    "BalanceError": "errors", "InvalidInput": "errors", "InvalidArm": "errors", "InvalidRange": "errors",
    "InfeasibleBounds": "errors", "WrongSense": "errors", "FitFailed": "errors", "SchemaError": "errors",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'balance' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
