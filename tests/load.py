"""Time bounds that a busy machine cannot break.

A test that says "within two seconds" means two seconds of a machine with a core to spare.  On a
shared machine whose run queue is longer than its cores, every process gets its turn that much
less often, so a bound is stretched by the same factor: a command that ignores Ctrl-C for ten
minutes still fails it, one that is merely waiting for a core does not.
"""

from __future__ import annotations

import os


def allowed_seconds(seconds: float) -> float:
    """``seconds`` on an idle machine, stretched by this machine's load per core (1-minute average).

    >>> allowed_seconds(2.0) >= 2.0
    True
    """
    return seconds * max(1.0, os.getloadavg()[0] / (os.cpu_count() or 1))
