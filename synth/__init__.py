"""synth: structural synthesis of planar mechanisms after Pozhbelko's counting theory.

The names below are loaded on first use, so ``import synth`` (and a balancing scene run
through ``mechsynth``) does not load OR-Tools, nauty or networkx.

Example
-------
>>> import synth
>>> [str(c) for c in synth.number_synthesis(1, loops=2)]
['42/0', '51/1', '60/2']
>>> synth.count_chains(1, 8, workers=1)["count"]
16
"""

from importlib import import_module

from .errors import *  # noqa: F401,F403
from .errors import __all__ as _errors_all

_WHERE = {
    "Code": ".code", "Chain": ".chain", "Mechanism": ".chain",
    "Analysis": ".analysis", "analyze": ".analysis", "mobility": ".analysis",
    "SubchainReport": ".mobility", "check_subchains": ".mobility", "subchain_mobility": ".mobility",
    "number_synthesis": "._number_synthesis",
    "Conventions": "._type_synthesis", "Unit": "._type_synthesis", "type_synthesis": "._type_synthesis",
    "count_chains": "._type_synthesis", "count_mechanisms": "._type_synthesis", "mechanisms": "._type_synthesis", "mechanisms_of": "._type_synthesis",
    "prismatic_variants": ".prismatic", "wedge_mobility": ".prismatic", "generic_mobility": ".prismatic",
    "idle_joints": ".prismatic", "lever_analogue": ".planetary", "planetary_table": ".planetary",
    "chain_repairs": ".repair", "code_repairs": ".repair",
    "plan_codes": "._type_synthesis", "plan_units": "._type_synthesis", "plan_many": "._type_synthesis", "run_unit": "._type_synthesis",
}

__all__ = [*_WHERE, *_errors_all]


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(import_module(_WHERE[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'synth' has no attribute {name!r}")


def __dir__():
    return sorted(__all__)
