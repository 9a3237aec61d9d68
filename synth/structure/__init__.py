"""Core types of a structure and the exact sub-chain test: codes, chains, mechanisms.

The checks of the parameters every query shares (W, h, f) are named here for the floors above,
which validate their own queries with them, and ``single_threaded`` (BLAS held to one thread while
many small numpy problems run):

>>> from synth.structure import check_dof, check_motion_space
>>> check_dof(1), check_motion_space(3)
(1, 3)
"""

from ._blas import single_threaded
from ._params import H_MAX, check_dof, check_extra_mobility, check_motion_space

__all__ = ["H_MAX", "check_dof", "check_extra_mobility", "check_motion_space", "single_threaded"]
