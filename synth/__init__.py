"""synth: structural synthesis of planar mechanisms after Pozhbelko's counting theory.

Example
-------
>>> import synth
>>> [str(c) for c in synth.number_synthesis(1, loops=2)]
['42/0', '51/1', '60/2']
>>> synth.count_chains(1, 8, workers=1)["count"]
16
"""

from ._number_synthesis import number_synthesis
from ._type_synthesis import Conventions, Unit, count_chains, mechanisms, mechanisms_of, plan_codes, plan_units, run_unit, type_synthesis
from .analysis import Analysis, analyze, mobility
from .chain import Chain, Mechanism
from .code import Code
from .errors import *  # noqa: F401,F403
from .errors import __all__ as _errors_all
from .mobility import SubchainReport, check_subchains, subchain_mobility

__all__ = [
    "Code", "Chain", "Mechanism", "Conventions", "Unit", "Analysis", "SubchainReport",
    "number_synthesis", "type_synthesis", "count_chains", "mechanisms", "mechanisms_of", "plan_codes", "plan_units", "run_unit",
    "analyze", "mobility", "check_subchains", "subchain_mobility",
    *_errors_all,
]
