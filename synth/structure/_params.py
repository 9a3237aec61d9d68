"""Checks of the parameters every query shares (W, h, f), each refusing nonsense with one sentence.

>>> check_motion_space(3), check_dof(0), check_extra_mobility(1)
(3, 0, 1)
>>> check_motion_space(7)
Traceback (most recent call last):
...
synth.errors.ImpossibleParameters: the motion space h of a loop is 1 … 6 (6: general spatial loop), not 7
"""

from __future__ import annotations

from ..errors import ImpossibleParameters, InvalidOption

__all__ = ["check_dof", "check_motion_space", "check_extra_mobility", "H_MAX"]

H_MAX = 6  # six independent relative motions close a general spatial loop


def _whole(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise InvalidOption(f"{name} must be a whole number, not {value!r}")
    return value


def check_dof(dof) -> int:
    """W ≥ 0 (0: a statically determinate truss)."""
    if _whole(dof, "the degree of freedom W") < 0:
        raise ImpossibleParameters(f"the degree of freedom W must be 0 or more, not {dof}")
    return dof


def check_motion_space(h, lowest: int = 1) -> int:
    """h = lowest … 6: the independent relative motions that close a loop (1 elastic coupling, 2 wedge, 3 planar …)."""
    if not lowest <= _whole(h, "the motion space h") <= H_MAX:
        raise ImpossibleParameters(
            f"the motion space h of a loop is {lowest} … {H_MAX} ({H_MAX}: general spatial loop), not {h}")
    return h


def check_extra_mobility(f) -> int:
    """f ≥ 0: extra mobility of multi-DOF pairs (a 2-DOF pair adds 1)."""
    if _whole(f, "the extra pair mobility f") < 0:
        raise ImpossibleParameters(f"the extra pair mobility f must be 0 or more, not {f}")
    return f
