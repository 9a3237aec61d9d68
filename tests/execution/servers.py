"""A local TCP endpoint for the tests of the Dask scheduler's address: it accepts every connection and
closes it, or first reads what the client sends and answers ``reply``."""

from __future__ import annotations

import socket
import threading
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def local_server(reply: bytes | None = None) -> Iterator[int]:
    """The port of a server on 127.0.0.1, served by a daemon thread until the ``with`` block ends."""
    server = socket.create_server(("127.0.0.1", 0))

    def serve():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            with conn:
                if reply is not None:
                    conn.recv(1024)
                    conn.sendall(reply)

    threading.Thread(target=serve, daemon=True).start()
    try:
        yield server.getsockname()[1]
    finally:
        server.close()
