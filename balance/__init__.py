"""Static and dynamic balancing of robot arms.

Gravity potentials as harmonic terms of linear forms of the joint coordinates, the
spring devices that cancel them (sine mechanisms, crank-and-rocker devices with
tension or fitted compression springs), counterweights, the pantograph balanced
manipulator and counter-masses for a sliding last link. See ``docs/balance.md``.

Examples
--------
>>> import balance
>>> doc = {"arm": {"links": [{"joint": "revolute", "length": 1.0, "weight": 10.0}]}}
>>> balance.solve_arm(doc)["terms"][0]["amplitude"]
5.0
"""

from .arm import Arm, Link, Load, arm_from_dict, gear_ratio_for_accuracy
from .countermass import CounterMass, c_min, counter_mass_laws, crank_construction, verify_counter_mass
from .counterweights import counterweights
from .errors import (
    BalanceError,
    FitFailed,
    InfeasibleBounds,
    InvalidArm,
    InvalidInput,
    InvalidRange,
    SchemaError,
    WrongSense,
)
from .fit import DEFAULT_METHOD, METHODS, NORMS, FitResult, SpringBounds, fit_spring
from .pantograph import Pantograph, balance_pantograph, pantograph_from_dict
from .potential import HarmonicTerm, merge_terms
from .problems import load_toml, solve_arm, solve_pantograph, solve_prismatic, solve_spring, spring_problem
from .springs import CrankRockerDevice, SineDevice, crank_moment, spring_length
from .static import ArmBalance, CheckResult, balance_arm, check_terms

__all__ = [
    "Arm", "Link", "Load", "arm_from_dict", "gear_ratio_for_accuracy",
    "HarmonicTerm", "merge_terms",
    "ArmBalance", "CheckResult", "balance_arm", "check_terms", "counterweights",
    "CrankRockerDevice", "SineDevice", "crank_moment", "spring_length",
    "SpringBounds", "FitResult", "fit_spring", "METHODS", "NORMS", "DEFAULT_METHOD",
    "CounterMass", "c_min", "counter_mass_laws", "crank_construction", "verify_counter_mass",
    "Pantograph", "balance_pantograph", "pantograph_from_dict",
    "solve_arm", "solve_spring", "spring_problem", "solve_prismatic", "solve_pantograph", "load_toml",
    "BalanceError", "InvalidInput", "InvalidArm", "InvalidRange", "InfeasibleBounds",
    "WrongSense", "FitFailed", "SchemaError",
]
