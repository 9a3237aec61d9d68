"""Gear trains: planetary (epicyclic) trains — the train type, the atlas enumerator, mechanisms with
their speed ratios, tooth numbers designed in integers, functional schematics (docs/gears.md) — and
the lever analogues of the source's planetary layout (``planetary``).

The names below are loaded on first use (the enumerator and the ratio design load CP-SAT and nauty).

Example
-------
>>> from synth.gears import count_trains
>>> count_trains(1, 6)["count"], count_trains(1, 6, graphs="rotation")["count"]
(81, 27)
"""

from importlib import import_module

_WHERE = {
    "GearTrain": ".train", "trains": ".enumeration", "count_trains": ".enumeration", "census": ".enumeration",
    "GearMechanism": ".mechanisms", "RatioFormula": ".mechanisms", "mechanisms": ".mechanisms",
    "speed_ratio": ".mechanisms", "Design": ".ratio_design", "design": ".ratio_design",
    "planetary_row": ".planetary", "planetary_table": ".planetary",
}

__all__ = list(_WHERE)


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(import_module(_WHERE[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'synth.gears' has no attribute {name!r}")


def __dir__():
    return sorted(__all__)
