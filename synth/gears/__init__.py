"""Planetary (epicyclic) gear trains: the train type, the atlas enumerator, mechanisms with their
speed ratios, tooth numbers designed in integers, and functional schematics (docs/gears.md).

Example
-------
>>> from synth.gears import count_trains
>>> count_trains(1, 6)["count"], count_trains(1, 6, graphs="rotation")["count"]
(81, 27)
"""

from .ratio_design import Design, design
from .enumeration import census, count_trains, trains
from .mechanisms import GearMechanism, RatioFormula, mechanisms, speed_ratio
from .train import GearTrain

__all__ = ["GearTrain", "trains", "count_trains", "census", "GearMechanism", "RatioFormula", "mechanisms",
           "speed_ratio", "Design", "design"]
