"""mechsynth: the application layer over the libraries :mod:`synth` and :mod:`balance`.

``synth`` (structural synthesis) and ``balance`` (balancing of arms) never import each
other; this package is the composition root that knows both: the ``mechsynth``
command (:mod:`mechsynth.cli`, one module per command group in
:mod:`mechsynth.commands`) and the scene runner (:mod:`mechsynth.scene`).

Example
-------
>>> import mechsynth
>>> mechsynth.__version__ == __import__("importlib.metadata").metadata.version("mechsynth")
True
"""

__all__ = ["__version__"]


def __getattr__(name: str) -> str:
    """``__version__``, looked up on first use (importlib.metadata costs a query 15–50 ms of start-up)."""
    if name != "__version__":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("mechsynth")
    except PackageNotFoundError:  # run from a checkout that was never installed
        return "0+unknown"
