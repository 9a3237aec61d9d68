"""Names a package exports but loads on first use (PEP 562), so that importing it loads no solver.

>>> import types
>>> demo = types.ModuleType("demo")
>>> demo.__getattr__, demo.__dir__ = lazy_exports("json", {"dumps": ""})
>>> demo.__getattr__("dumps")([1])
'[1]'
"""

from __future__ import annotations

from importlib import import_module

__all__ = ["lazy_exports"]


def lazy_exports(package: str, where: dict[str, str]):
    """``(__getattr__, __dir__)`` for ``package``: ``where`` maps each public name to the module,
    relative to the package, that defines it; a name is imported when first asked for and then
    kept in the package's namespace."""

    def __getattr__(name: str):
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(import_module(where[name], package) if where[name] else import_module(package), name)
        setattr(import_module(package), name, value)
        return value

    def __dir__():
        return sorted(getattr(import_module(package), "__all__", where))

    return __getattr__, __dir__
