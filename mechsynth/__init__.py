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

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("mechsynth")
except PackageNotFoundError:  # run from a checkout that was never installed
    __version__ = "0+unknown"

__all__ = ["__version__"]
