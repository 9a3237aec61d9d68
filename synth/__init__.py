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
    "Code": ".structure.code", "Chain": ".structure.chain", "Mechanism": ".structure.chain",
    "Analysis": ".analysis.codes", "analyze": ".analysis.codes", "mobility": ".analysis.codes",
    "SubchainReport": ".structure.subchains", "check_subchains": ".structure.subchains", "subchain_mobility": ".structure.subchains",
    "number_synthesis": ".synthesis.number_synthesis",
    "Conventions": ".synthesis.type_synthesis", "Unit": ".synthesis.type_synthesis", "type_synthesis": ".synthesis.type_synthesis",
    "count_chains": ".synthesis.type_synthesis", "count_mechanisms": ".synthesis.type_synthesis", "mechanisms": ".synthesis.type_synthesis", "mechanisms_of": ".synthesis.type_synthesis",
    "ChainQuery": ".structure.query", "variants_of": ".synthesis.variants",
    "prismatic_variants": ".synthesis.variants", "structural_mobility": ".structure.kinds",
    "generic_mobility": ".structure.kinds", "idle_joints": ".structure.kinds", "wedge_loops": ".structure.kinds",
    "prismatic_roles": ".structure.kinds", "lever_analogue": ".structure.kinds", "planetary_table": ".gears.planetary",
    "chain_repairs": ".analysis.repair", "code_repairs": ".analysis.repair",
    "identify": ".analysis.identify", "identify_all": ".analysis.identify", "compare": ".analysis.compare",
    "plan_codes": ".synthesis.type_synthesis", "plan_units": ".synthesis.type_synthesis", "plan_many": ".synthesis.type_synthesis", "run_unit": ".synthesis.type_synthesis",
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
