"""One BLAS thread for the engine's small matrix products: :func:`single_threaded`.

The exact sub-chain test multiplies matrices of a few thousand rows, thousands of times.
OpenBLAS runs each product on every core and leaves its threads spinning between calls: a
third more CPU time in one process, and cores taken from the other workers of a pool.  The
command line sets ``OPENBLAS_NUM_THREADS=1`` before numpy loads; for the Python API the same
holds while the engine's products run (threadpoolctl), and the caller's settings come back after.
The exact test sets the limit only around products large enough for OpenBLAS to thread them
(entering and leaving costs about 8 µs, a tenth of the test of a small unit).

>>> import numpy as np
>>> with single_threaded():
...     (np.ones((2, 3), dtype=np.float32) @ np.ones((3, 1), dtype=np.float32)).tolist()
[[3.0], [3.0]]
"""

from __future__ import annotations

from functools import lru_cache

__all__ = ["single_threaded"]


@lru_cache(maxsize=1)
def _controller():
    from threadpoolctl import ThreadpoolController  # about 10 ms, once per process

    return ThreadpoolController()


def single_threaded():
    """A context in which BLAS runs on one thread (about 8 µs to enter and leave)."""
    return _controller().limit(limits=1, user_api="blas")
