"""Connecting to a Dask scheduler (``--scheduler ADDRESS``): one sentence when it cannot be done.

The address is checked before Dask is even imported, and a TCP scheduler must accept a
connection and answer Dask's handshake, both within the timeout, before a ``distributed.Client``
is built, so a wrong address fails fast and quietly (a half-built Client would otherwise spend
ten seconds closing itself at exit and print "Exception ignored …").

Example
-------
>>> connect("nonsense", 1.0)
Traceback (most recent call last):
...
synth.execution.scheduler.SchedulerUnreachable: 'nonsense' is not a Dask scheduler address: write tcp://HOST:PORT (e.g. tcp://127.0.0.1:8786)
"""

from __future__ import annotations

import re
import socket

from ..errors import SynthesisError

__all__ = ["SchedulerUnreachable", "connect"]

_ADDRESS = re.compile(r"^(?:(tcp|tls|ws|wss)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9._-]+):(\d{1,5})/?$")


class SchedulerUnreachable(SynthesisError):
    """The Dask scheduler named by ``--scheduler`` did not answer."""


def connect(address: str, timeout: float = 5.0):
    """A ``distributed.Client`` for the scheduler at ``address``.

    Raises
    ------
    SchedulerUnreachable
        The address is malformed, nothing answers there within ``timeout`` seconds, or
        the answer is not a Dask scheduler.
    """
    match = _ADDRESS.match(address.strip()) if isinstance(address, str) else None
    if not match or not 0 < int(match.group(3)) < 65536:
        raise SchedulerUnreachable(f"{address!r} is not a Dask scheduler address: write tcp://HOST:PORT "
                                   "(e.g. tcp://127.0.0.1:8786)")
    scheme, host, port = match.group(1) or "tcp", match.group(2).strip("[]"), int(match.group(3))
    try:
        socket.create_connection((host, port), timeout=timeout).close()
    except OSError as exc:
        reason = "no answer" if isinstance(exc, TimeoutError) else (exc.strerror or type(exc).__name__).lower()
        raise SchedulerUnreachable(f"cannot reach the Dask scheduler at {address} within {timeout:g} s ({reason})") from None
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - dask is a dependency
        raise SchedulerUnreachable("a Dask scheduler needs the 'distributed' package (pip install dask[distributed])") from None
    try:
        _handshake(f"{scheme}://{match.group(2)}:{port}", timeout)
    except TimeoutError:
        raise SchedulerUnreachable(f"{address} accepted the connection but did not answer as a Dask scheduler "
                                   f"within {timeout:g} s") from None
    except Exception as exc:  # a garbled answer can raise anything in Dask's reader (a 3 EiB frame: MemoryError)
        raise SchedulerUnreachable(f"{address} answered, but not as a Dask scheduler ({type(exc).__name__})") from None
    try:
        return Client(f"{scheme}://{match.group(2)}:{port}", timeout=f"{timeout}s", set_as_default=False)
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        detail = str(exc).splitlines()[0] if str(exc) else "no answer"
        raise SchedulerUnreachable(f"{address} answered, but not as a Dask scheduler within {timeout:g} s "
                                   f"({type(exc).__name__}: {detail})") from None


def _handshake(address: str, timeout: float) -> None:
    """Dask's handshake on a connection of its own, closed at once: whatever answers there but is not
    a scheduler fails here (a proxy's HTTP reply read as a frame length), before a ``Client`` exists,
    which once half built cannot be closed quietly.  The whole of it within ``timeout`` seconds: Dask's
    ``connect`` bounds its connection attempts only and then waits for the handshake's answer for ever,
    so a port that accepts and stays silent raises TimeoutError here.  In a thread of its own, so that a
    caller with a running event loop (a notebook) can call it too."""
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect as dask_connect

    async def shake():
        comm = await dask_connect(address)  # (bounded as a whole below)
        await comm.close()

    with ThreadPoolExecutor(1) as thread:
        thread.submit(asyncio.run, asyncio.wait_for(shake(), timeout)).result()
