"""SQLite atlases: grid files, grid runs, the ``--where`` language, exports and the static web site.

=============  ======================================================================
``grid``       grid files (TOML): cells of W, n, v, conventions
``database``   the atlas file: its schema and version, opening it checked, the run lock
``runs``       grid runs, resumable unit by unit on a pool or Dask, and their sizing
``trains``     gear-train cells: their units (link–axis trees) and rows, one train per rotation graph
``queries``    the ``--where`` language, exports and the summary
``site``       the atlas as a static web site
``curves``     the curve index: coupler curves of sampled crank poses as Fourier descriptors
``search``     type and dimensional synthesis over the atlas: retrieval from the index, then the polish
=============  ======================================================================

The names below are loaded on first use.

Example
-------
>>> from synth.atlas import parse_grid
>>> [c.key for c in parse_grid('dof = 1\\nlinks = "4..6"').cells]
['W=1 n=4 v=0..0 rigid=0 frac=1 planar=0', 'W=1 n=6 v=0..0 rigid=0 frac=1 planar=0']
"""

from .._lazy import lazy_exports

_WHERE = {
    "GridFileError": ".grid", "Cell": ".grid", "GearCell": ".grid", "Grid": ".grid", "load_grid": ".grid", "parse_grid": ".grid",
    "SCHEMA_VERSION": ".database", "AtlasError": ".database", "AtlasLocked": ".database", "open_atlas": ".database",
    "chain_id": ".database",
    "GridRunResult": ".runs", "compute_unit": ".runs", "run_grid": ".runs", "size_grid": ".runs",
    "parse_where": ".queries", "export": ".queries", "summary": ".queries",
    "IndexSettings": ".curves", "IndexResult": ".curves", "NoCurveIndex": ".curves", "index_curves": ".curves",
    "index_info": ".curves", "index_gap": ".curves",
    "AtlasSearchResult": ".search", "AtlasMatch": ".search", "search_atlas": ".search", "retrieve": ".search",
    "sampled_starts": ".search",
    "write_site": ".site", "SiteResult": ".site", "EmptyAtlas": ".site", "MAX_PAGE_SIZE": ".site",
}

__all__ = list(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
