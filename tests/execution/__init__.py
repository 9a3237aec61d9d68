"""Tests of large queries: streaming, checkpoints, Dask, estimates."""
