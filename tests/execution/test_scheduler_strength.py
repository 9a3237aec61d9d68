"""The Dask scheduler's address, in this process: every refusal's sentence in full, and the address
each accepted spelling hands to Dask (no cluster is started: Dask's client is stood in for).
"""

from __future__ import annotations

import socket
import threading
import time

import pytest

from synth.execution import scheduler
from synth.execution.scheduler import SchedulerUnreachable, connect
from tests.load import allowed_seconds

from .servers import local_server


@pytest.fixture
def listening():
    """A local TCP port that accepts connections (and says nothing)."""
    with local_server() as port:
        yield port


@pytest.fixture
def client(monkeypatch):
    """Dask's handshake and Client stood in for: the Client's arguments are recorded."""
    distributed = pytest.importorskip("distributed")
    made, shaken = [], []
    monkeypatch.setattr(scheduler, "_handshake", lambda address, timeout: shaken.append((address, timeout)))
    monkeypatch.setattr(distributed, "Client", lambda *a, **k: made.append((a, k)) or "client")
    return made, shaken


@pytest.mark.parametrize("address", ["nonsense", "tcp://host", "tcp://host:0", "tcp://host:65536", "tcp://host:123456",
                                     "http://host:8786", "tcp://ho st:8786", "tcp://host:8786/x", "", 8786, None])
def test_a_malformed_address_is_refused_before_anything_is_tried(address, monkeypatch):
    monkeypatch.setattr(scheduler.socket, "create_connection", lambda *a, **k: pytest.fail("a connection was tried"))
    with pytest.raises(SchedulerUnreachable) as refused:
        connect(address, 1.0)
    assert str(refused.value) == (f"{address!r} is not a Dask scheduler address: write tcp://HOST:PORT "
                                  "(e.g. tcp://127.0.0.1:8786)")


@pytest.mark.parametrize("address, scheme, host, target", [
    ("tcp://127.0.0.1:{port}", "tcp", "127.0.0.1", "tcp://127.0.0.1:{port}"),
    ("127.0.0.1:{port}", "tcp", "127.0.0.1", "tcp://127.0.0.1:{port}"),        # no scheme: TCP
    ("  tls://127.0.0.1:{port}/ ", "tls", "127.0.0.1", "tls://127.0.0.1:{port}"),  # spaces and a slash around it
    ("ws://localhost:{port}", "ws", "localhost", "ws://localhost:{port}"),
])
def test_an_address_that_answers_is_handed_to_dask(address, scheme, host, target, listening, client, monkeypatch):
    made, shaken = client
    tried = []
    real = socket.create_connection
    monkeypatch.setattr(scheduler.socket, "create_connection", lambda where, timeout: tried.append(where) or
                        real(where, timeout=timeout))
    assert connect(address.format(port=listening), 2.5) == "client"
    target = target.format(port=listening)
    assert tried == [(host, listening)]
    assert shaken == [(target, 2.5)]
    assert made == [((target,), {"timeout": "2.5s", "set_as_default": False})]


def test_an_ipv6_address_is_tried_without_its_brackets(client, monkeypatch):
    made, shaken = client
    tried = []

    class Connection:
        def close(self):
            pass

    monkeypatch.setattr(scheduler.socket, "create_connection", lambda where, timeout: tried.append(where) or Connection())
    connect("tcp://[::1]:8786", 1.0)
    assert tried == [("::1", 8786)] and shaken == [("tcp://[::1]:8786", 1.0)]
    connect("[::1]:65535", 1.0)  # the largest port
    assert tried[-1] == ("::1", 65535)


def test_a_port_where_nothing_listens_is_one_sentence():
    spare = socket.create_server(("127.0.0.1", 0))
    port = spare.getsockname()[1]
    spare.close()  # nothing listens there now
    with pytest.raises(SchedulerUnreachable) as refused:
        connect(f"tcp://127.0.0.1:{port}", 1.5)
    assert str(refused.value) == f"cannot reach the Dask scheduler at tcp://127.0.0.1:{port} within 1.5 s (connection refused)"


@pytest.mark.parametrize("error, reason", [(TimeoutError("timed out"), "no answer"),
                                           (OSError("no errno"), "oserror"),
                                           (ConnectionResetError(104, "Connection reset by peer"), "connection reset by peer")])
def test_a_connection_that_fails_says_why(error, reason, monkeypatch):
    def fail(where, timeout):
        raise error

    monkeypatch.setattr(scheduler.socket, "create_connection", fail)
    with pytest.raises(SchedulerUnreachable) as refused:
        connect("tcp://10.0.0.1:8786", 5.0)
    assert str(refused.value) == f"cannot reach the Dask scheduler at tcp://10.0.0.1:8786 within 5 s ({reason})"


def test_an_answer_that_is_not_dask_s_is_one_sentence(listening, client, monkeypatch):
    def garbled(address, timeout):
        raise MemoryError

    monkeypatch.setattr(scheduler, "_handshake", garbled)
    with pytest.raises(SchedulerUnreachable) as refused:
        connect(f"tcp://127.0.0.1:{listening}", 1.0)
    assert str(refused.value) == f"tcp://127.0.0.1:{listening} answered, but not as a Dask scheduler (MemoryError)"
    assert client[0] == []  # no Client was built


@pytest.mark.parametrize("error, detail", [(OSError("timed out\nand more"), "OSError: timed out"),
                                           (TimeoutError(), "TimeoutError: no answer"),
                                           (ValueError("bad"), "ValueError: bad")])
def test_a_client_that_cannot_be_built_is_one_sentence(error, detail, listening, monkeypatch):
    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(scheduler, "_handshake", lambda address, timeout: None)

    def fail(*a, **k):
        raise error

    monkeypatch.setattr(distributed, "Client", fail)
    with pytest.raises(SchedulerUnreachable) as refused:
        connect(f"127.0.0.1:{listening}", 3.0)
    assert str(refused.value) == (f"127.0.0.1:{listening} answered, but not as a Dask scheduler within 3 s ({detail})")


def test_the_handshake_fails_on_an_http_answer_even_inside_a_running_loop():
    pytest.importorskip("distributed")
    import asyncio

    async def in_a_notebook(port):
        with pytest.raises(Exception):
            scheduler._handshake(f"tcp://127.0.0.1:{port}", 3.0)

    with local_server(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n" * 4) as port:
        asyncio.run(in_a_notebook(port))


def test_the_address_is_tried_as_written_with_the_timeout(monkeypatch):
    tried = []

    def refuse(where, timeout):
        tried.append((where, timeout))
        raise ConnectionRefusedError(111, "Connection refused")

    monkeypatch.setattr(scheduler.socket, "create_connection", refuse)
    for address in ("tcp://Xhost:1", "[::1]:8786"):
        with pytest.raises(SchedulerUnreachable, match="cannot reach the Dask scheduler"):
            connect(address, 2.5)
    assert tried == [(("Xhost", 1), 2.5), (("::1", 8786), 2.5)]  # port 1 is a port; only the brackets go
    with pytest.raises(SchedulerUnreachable) as refused:
        connect("tcp://10.0.0.1:8786")
    assert str(refused.value) == "cannot reach the Dask scheduler at tcp://10.0.0.1:8786 within 5 s (connection refused)"


def test_without_dask_the_sentence_says_what_to_install(listening, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "distributed", None)  # importing it raises ImportError
    with pytest.raises(SchedulerUnreachable) as refused:
        connect(f"tcp://127.0.0.1:{listening}", 1.0)
    assert str(refused.value) == "a Dask scheduler needs the 'distributed' package (pip install dask[distributed])"


@pytest.fixture
def silent():
    """A local TCP port that accepts connections and then says nothing (``nc -l``, a forwarded port with
    nothing behind it)."""
    server = socket.create_server(("127.0.0.1", 0))
    held = []

    def accept():
        while True:
            try:
                held.append(server.accept()[0])
            except OSError:
                return

    threading.Thread(target=accept, daemon=True).start()
    yield server.getsockname()[1]
    server.close()
    for conn in held:
        conn.close()


def _within(seconds, call):
    """``call()``'s exception, raised within ``seconds`` of a machine with a core to spare, or a failure
    (the call is left waiting in a daemon thread, so that a test of a hang fails instead of hanging)."""
    outcome = []

    def run():
        try:
            outcome.append(("returned", call()))
        except BaseException as exc:  # noqa: BLE001 - the outcome is judged by the test
            outcome.append(("raised", exc))

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    worker.join(allowed_seconds(seconds))
    assert outcome, f"still waiting after {allowed_seconds(seconds):.1f} s"
    return outcome[0]


def test_a_port_that_accepts_and_stays_silent_is_one_sentence_within_the_timeout(silent, monkeypatch):
    """Dask's own connect waits for the handshake's answer without a bound: the whole handshake is bounded by
    the timeout (this once waited for ever, and Ctrl-C then hung in the thread pool's exit)."""
    distributed = pytest.importorskip("distributed")
    made = []
    monkeypatch.setattr(distributed, "Client", lambda *a, **k: made.append((a, k)))
    began = time.monotonic()
    how, refused = _within(10.0, lambda: connect(f"tcp://127.0.0.1:{silent}", 0.5))
    assert how == "raised" and isinstance(refused, SchedulerUnreachable), refused
    assert str(refused) == (f"tcp://127.0.0.1:{silent} accepted the connection but did not answer as a Dask "
                            "scheduler within 0.5 s")
    assert time.monotonic() - began >= 0.5  # (it waited the timeout, not less)
    assert made == []  # no Client was built


def test_the_handshake_succeeds_with_a_dask_endpoint_and_closes_its_connection():
    """Against Dask's own listener (no scheduler: the comm layer that answers the handshake), the handshake
    returns, and the listener sees one connection that is closed at once."""
    pytest.importorskip("distributed")
    import asyncio

    from distributed.comm import listen

    loop = asyncio.new_event_loop()
    threading.Thread(target=loop.run_forever, daemon=True).start()
    seen = []

    async def handler(comm):
        seen.append(await comm.read())  # the client closes without a message: the read ends the comm
        await comm.close()

    async def start():
        listener = listen("tcp://127.0.0.1:0", handler)
        await listener.start()
        return listener

    listener = asyncio.run_coroutine_threadsafe(start(), loop).result()
    try:
        how, result = _within(10.0, lambda: scheduler._handshake(listener.contact_address, 2.0))
        assert (how, result) == ("returned", None)
    finally:
        loop.call_soon_threadsafe(listener.stop)
        loop.call_soon_threadsafe(loop.stop)
