"""Dimensional synthesis of a given topology: the dimensions with which a mechanism traces a path
(with or without prescribed timing), generates a function (input–output angle pairs) or guides a
body through poses, under the constraints a designer sets.

The unknowns are the joint positions of the mechanism's pose at the first target point (the tracer
point's too), so every candidate is assembled by construction and keeps its pose's assembly
branch; a global search (differential evolution, restarted while the CPU budget lasts) is polished
by bounded least squares, and the answer is re-checked by the motion layer (docs/dimension.md).
This floor imports the chain types, the motion layer and the execution service only.

Example
-------
>>> import numpy as np
>>> from synth.structure.chain import Chain, Mechanism
>>> from synth.dimension import FunctionTarget, synthesize
>>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
>>> result = synthesize(four_bar, FunctionTarget(np.radians([40, 60, 80]), np.radians([70, 85, 105])), budget=5)
>>> result.error_max < 1e-9, result.met
(True, True)
"""

from .._lazy import lazy_exports

_WHERE = {
    "PathTarget": "._target", "FunctionTarget": "._target", "MotionTarget": "._target", "read_target": "._target",
    "Constraints": "._problem", "link_ratio": "._problem",
    "DimensionalResult": "._search", "synthesize": "._search", "equations_and_unknowns": "._search",
}

__all__ = list(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
