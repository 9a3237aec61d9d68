"""synth: structural synthesis of planar mechanisms after Pozhbelko's counting theory."""
from .code import Code
from .errors import *  # noqa: F401,F403
from .errors import __all__ as _errors_all
from ._number_synthesis import number_synthesis

__all__ = ["Code", "number_synthesis", *_errors_all]
