"""How the engine's values show themselves in a notebook, without importing the drawings above them.

A chain, a mechanism (and the values of the floors above, such as a dimensioned linkage) answer
Jupyter's ``_repr_svg_`` through :func:`svg_of`.  The drawings live on the top floor; the package
facade (``synth/__init__.py``), which stands above every floor, names here the function that draws
each kind of value, and that function's module is loaded on first use only.

>>> from synth.structure.chain import Chain
>>> "</svg>" in svg_of(Chain.parse("0-1 1-2 2-3 3-0"))
True
"""

from __future__ import annotations

from importlib import import_module

__all__ = ["register_drawing", "svg_of"]

#: the value's class name -> "module:function" that returns its SVG
_DRAWINGS: dict[str, str] = {}


def register_drawing(kind: str, drawer: str) -> None:
    """Name the function (``"package.module:function"``) that draws values of the class ``kind``."""
    _DRAWINGS[kind] = drawer


def svg_of(value) -> str:
    """The SVG of ``value`` by the function registered for its class (or a base class of it)."""
    for cls in type(value).__mro__:
        if cls.__name__ in _DRAWINGS:
            module, name = _DRAWINGS[cls.__name__].split(":")
            return getattr(import_module(module), name)(value)
    raise TypeError(f"no drawing is registered for a {type(value).__name__}")
