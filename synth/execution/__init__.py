"""Running work units: inline, a process pool or Dask; checkpoints and size estimates."""
