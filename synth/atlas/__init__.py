"""SQLite atlases: grid files, grid runs, the ``--where`` language, exports and the static web site.

=============  ======================================================================
``grid``       grid files (TOML): cells of W, n, v, conventions
``store``      the atlas file: its schema and checks, grid runs (resumable, pool or Dask),
               the ``--where`` language, exports and the summary
``site``       the atlas as a static web site
=============  ======================================================================

The names below are loaded on first use.

Example
-------
>>> from synth.atlas import parse_grid
>>> [c.key for c in parse_grid('dof = 1\\nlinks = "4..6"').cells]
['W=1 n=4 v=0..0 rigid=0 frac=1 planar=0', 'W=1 n=6 v=0..0 rigid=0 frac=1 planar=0']
"""

from importlib import import_module

_WHERE = {
    "GridFileError": ".grid", "Cell": ".grid", "Grid": ".grid", "load_grid": ".grid", "parse_grid": ".grid",
    "chain_id": ".site", "write_site": ".site", "SiteResult": ".site", "EmptyAtlas": ".site",
    "MAX_PAGE_SIZE": ".site",
}


__all__ = [*_WHERE, "AtlasError", "AtlasLocked", "GridRunResult", "compute_unit", "open_atlas", "run_grid",
           "parse_where", "export", "summary", "size_grid"]


def __getattr__(name: str):
    where = _WHERE.get(name, ".store" if name in __all__ else None)
    if where is None:
        raise AttributeError(f"module 'synth.atlas' has no attribute {name!r}")
    value = getattr(import_module(where, __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(__all__)
