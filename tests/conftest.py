import atexit
import os
import shutil
import signal
import sys
import tempfile

import pytest
from hypothesis import HealthCheck, settings

# Tests (and the subprocesses they start) use this checkout's packages, whatever is installed.
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)
os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (ROOT, os.environ.get("PYTHONPATH")) if p)
os.environ.setdefault("MPLBACKEND", "Agg")
# The solver results the engine keeps between runs (synth.execution.memo) go to a folder of this
# session's own: the suite starts cold, and never reads or fills the user's store.
_MEMO = tempfile.mkdtemp(prefix="mechsynth-memo-")
os.environ["MECHSYNTH_CACHE"] = _MEMO
atexit.register(shutil.rmtree, _MEMO, ignore_errors=True)

# The Ctrl-C tests send SIGINT to the commands they start.  A suite started in the background
# (`cmd &` in a script, nohup) inherits SIGINT *ignored*, and so would every command it starts
# (Python installs no KeyboardInterrupt handler then).  Handled here, the children start with the
# default disposition, as under a terminal; a blocked SIGINT is unblocked for the same reason.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT])

# Hypothesis: the same examples on every run and no wall-clock limits (CI and default).
# Randomised search locally: HYPOTHESIS_PROFILE=explore python -m pytest tests/test_properties.py
settings.register_profile(
    "ci", derandomize=True, deadline=None, print_blob=True, database=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("explore", deadline=None, max_examples=500, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


@pytest.fixture
def no_solver_store(monkeypatch):
    """Solver results computed afresh, none read from the store (synth.execution.memo off): for the
    tests that change how stage A or number synthesis computes them."""
    from synth.execution import memo

    monkeypatch.setenv("MECHSYNTH_CACHE", "off")
    memo._store.cache_clear()
    yield
    memo._store.cache_clear()
