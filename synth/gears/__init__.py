"""Gear trains: planetary (epicyclic) trains — the train type, the atlas enumerator, mechanisms with
their speed ratios, tooth numbers designed in integers (docs/gears.md) — and the lever analogues of
the source's planetary layout (``planetary``).  Their functional schematics are drawn on the top
floor, by :mod:`synth.draw` (``draw_train``, ``draw_train_sheet``).

The names below are loaded on first use (the enumerator and the ratio design load CP-SAT and nauty).

Example
-------
>>> from synth.gears import count_trains
>>> count_trains(1, 6)["count"], count_trains(1, 6, graphs="rotation")["count"]
(81, 27)
"""

from .._lazy import lazy_exports

_WHERE = {
    "GearTrain": ".train",
    "GRAPHS": ".enumeration", "trains": ".enumeration", "count_trains": ".enumeration", "census": ".enumeration", "Census": ".enumeration", "link_axis_trees": ".enumeration", "tree_trains": ".enumeration", "tree_census": ".enumeration",
    "check_query": ".enumeration", "estimate_trains": ".enumeration", "size_check_trains": ".enumeration",
    "GearMechanism": ".ratios", "RatioFormula": ".ratios", "mechanisms": ".ratios",
    "speed_ratio": ".ratios",
    "Design": ".ratio_design", "NoDesign": ".ratio_design", "RatioUnreached": ".ratio_design", "design": ".ratio_design", "MIN_TEETH": ".ratio_design",
    "ratio_and_tolerance": ".ratio_design",
    "planetary_row": ".planetary", "planetary_rows": ".planetary", "planetary_table": ".planetary",
}

__all__ = list(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
