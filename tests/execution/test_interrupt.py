"""Ctrl-C stops every long command within two seconds, with exit status 130 and no process left.

Each command is started in a session of its own, as a terminal runs it, left working until it is
inside its long part (a CP-SAT search, pool workers counting or drawing), and interrupted as a
terminal does: SIGINT to the whole process group, workers included.  The command and every process
it started must be gone within two seconds (on this shared machine they take 0.03–0.3 s), seconds
of a machine with a core to spare: the bound stretches with the load (tests/load.py).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import psutil
import pytest

from tests.load import allowed_seconds

CLI = [sys.executable, "-m", "mechsynth"]
STOP_SECONDS = 2.0


def _interrupt(args: list[str], cwd, ready, *, wait_at_most: float = 60.0) -> tuple[int, float, str, list]:
    """Run ``mechsynth args``, wait until ``ready(process)`` holds, send Ctrl-C to its process group;
    return the exit status, the seconds it took to end, its stderr and the processes it had started."""
    err_path = cwd / "stderr.txt"
    with open(err_path, "w") as err:
        proc = subprocess.Popen([*CLI, *args], stdout=subprocess.DEVNULL, stderr=err, cwd=cwd,
                                start_new_session=True)
    started: list = []
    try:
        start = time.monotonic()
        while not ready(proc, err_path):
            assert proc.poll() is None, f"ended before it was interrupted: {err_path.read_text()[-800:]}"
            assert time.monotonic() - start < wait_at_most, "never became busy"
            time.sleep(0.1)
        started = psutil.Process(proc.pid).children(recursive=True)
        sent = time.monotonic()
        os.killpg(proc.pid, signal.SIGINT)
        try:
            status = proc.wait(timeout=max(30.0, allowed_seconds(STOP_SECONDS)))
        except subprocess.TimeoutExpired:
            status = None
        took = time.monotonic() - sent
        _, alive = psutil.wait_procs(started, timeout=max(0.0, allowed_seconds(STOP_SECONDS) - took))
        return status, took, err_path.read_text(), alive
    finally:  # whatever the verdict, nothing of this test outlives it
        for p in started:
            try:
                p.kill()
            except psutil.NoSuchProcess:
                pass
        if proc.poll() is None:
            proc.kill()
        proc.wait()


def _after(seconds: float):
    """Ready once ``seconds`` have passed since the first call (the command is then inside its work)."""
    begin = []

    def ready(proc, _):
        begin.append(time.monotonic()) if not begin else None
        return time.monotonic() - begin[0] >= seconds

    return ready


def _with_workers(extra: float = 1.0):
    """Ready once the command has pool workers (plus ``extra`` seconds for them to be busy)."""
    seen = []

    def ready(proc, _):
        if not seen and psutil.Process(proc.pid).children():
            seen.append(time.monotonic())
        return bool(seen) and time.monotonic() - seen[0] >= extra

    return ready


def _check(status, took, err, alive):
    assert status == 130, (status, err[-800:])
    assert err.rstrip().endswith("mechsynth: interrupted"), err[-800:]
    assert "Traceback" not in err, err[-2000:]
    assert took <= allowed_seconds(STOP_SECONDS), f"took {took:.2f} s to stop (load {os.getloadavg()[0]:.1f})"
    assert not alive, f"left behind: {[p.pid for p in alive]}"


def test_ctrl_c_inside_a_cp_sat_search(tmp_path):
    # K = 1000: CP-SAT searches for minutes before its first solution, so no Python code runs meanwhile
    # (without the interrupt thread of synth.synthesis._cpsat this ignored Ctrl-C for ten minutes)
    _check(*_interrupt(["codes", "--dof", "1", "--loops", "1000", "--force", "--format", "csv"], tmp_path,
                       _after(3.0)))


def test_ctrl_c_while_codes_stream(tmp_path):
    _check(*_interrupt(["codes", "--dof", "1", "--loops", "15..22", "--force", "--format", "csv"], tmp_path,
                       _after(3.0)))


def test_ctrl_c_stops_a_count_and_its_pool(tmp_path):
    _check(*_interrupt(["chains", "--dof", "1", "--links", "16", "--count", "--workers", "2"], tmp_path,
                       _with_workers(1.5)))


def test_ctrl_c_stops_a_grid_run_and_its_pool(tmp_path):
    (tmp_path / "grid.toml").write_text("dof = 1\nlinks = 14\n")
    busy = _with_workers(2.0)  # and the atlas begun: before it exists an interrupt leaves no file at all (tested
    # with the refusals), which is not the case this test is about; a loaded machine plans for a while
    ready = lambda proc, err: (tmp_path / "atlas.sqlite").exists() and busy(proc, err)  # noqa: E731
    status, took, err, alive = _interrupt(["grid", "grid.toml", "--db", "atlas.sqlite", "--workers", "2"], tmp_path,
                                          ready)
    _check(status, took, err, alive)
    out = subprocess.run([*CLI, "atlas", "--db", "atlas.sqlite", "--format", "json"], capture_output=True, text=True,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stderr  # the interrupted run left a consistent, readable atlas


def test_ctrl_c_stops_a_site_and_its_drawing_workers(tmp_path):
    (tmp_path / "grid.toml").write_text('dof = 1\nlinks = "4..12"\n')
    made = subprocess.run([*CLI, "grid", "grid.toml", "--db", "atlas.sqlite", "--workers", "2"], capture_output=True,
                          text=True, cwd=tmp_path)
    assert made.returncode == 0, made.stderr

    def drawing(proc, err_path):  # the site is begun and its drawing workers exist
        return bool(psutil.Process(proc.pid).children()) and (tmp_path / "site" / "style.css").exists()

    _check(*_interrupt(["atlas", "--db", "atlas.sqlite", "--html", "site", "--workers", "2"], tmp_path, drawing))


def test_ctrl_c_inside_an_extension_that_raises_something_else(monkeypatch, capsys):
    """An extension interrupted in the middle of a call may turn the KeyboardInterrupt into another
    error (pynauty once raised TypeError "missing 'vertex_coloring' attribute" when Ctrl-C came while it
    built a graph): the command still says "interrupted" and exits 130, with no traceback; the same
    error without a Ctrl-C is not hidden; and the handler of the calling process is put back."""
    from mechsynth import _parser, cli

    class Parser:
        def __init__(self, error):
            self.error = error

        def parse_args(self, argv):
            return self

        def run(self, args):
            try:
                if self.error is None:
                    os.kill(os.getpid(), signal.SIGINT)
                    time.sleep(1)  # the handler raises KeyboardInterrupt at the next bytecode
                raise self.error
            except KeyboardInterrupt:
                raise TypeError("missing 'vertex_coloring' attribute") from None

    monkeypatch.setattr(_parser, "build_parser", lambda argv: Parser(None))
    before = signal.getsignal(signal.SIGINT)
    assert cli.main(["chains"]) == 130
    time.sleep(allowed_seconds(0.3))  # the search watcher's instant after this Ctrl-C passes before the next test
    assert capsys.readouterr().err == "mechsynth: interrupted\n"
    assert signal.getsignal(signal.SIGINT) is before
    monkeypatch.setattr(_parser, "build_parser", lambda argv: Parser(ValueError("a bug")))
    with pytest.raises(ValueError, match="a bug"):
        cli.main(["chains"])


def test_a_search_begun_after_a_handled_ctrl_c_runs_to_its_end():
    """A Ctrl-C caught and handled in this process (a notebook's interrupt, a test) must not stop the
    next search: the watcher stops the searches running when it comes, and those begun in that
    instant, not one begun a quarter of a second after the KeyboardInterrupt was handled."""
    from synth.execution.interrupt import solve_stoppably

    class Slow:  # a search of 0.6 s that reports whether it was stopped
        def __init__(self):
            self.stopped = False

        def solve(self, model, callback=None):
            end = time.monotonic() + 0.6
            while time.monotonic() < end and not self.stopped:
                time.sleep(0.01)
            return "UNKNOWN" if self.stopped else "OPTIMAL"

        def stop_search(self):
            self.stopped = True

    time.sleep(allowed_seconds(0.3))  # past the instant of a Ctrl-C an earlier test sent to this process
    assert solve_stoppably(Slow(), model=None) == "OPTIMAL"  # the watcher is installed by the first search
    ours = signal.set_wakeup_fd(-1)
    signal.set_wakeup_fd(ours)
    assert ours != -1, "the watcher of Ctrl-C is not installed: this test would prove nothing"
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)
    time.sleep(0.25)
    assert solve_stoppably(Slow(), model=None) == "OPTIMAL"


# the console script's own lines (pip writes them), with a tripwire that sends this process a Ctrl-C
# when the module named is first imported, at a moment a person's Ctrl-C could come
_SCRIPT_WITH_A_CTRL_C_AT_IMPORT = """
import os, signal, sys

class Tripwire:
    def find_spec(self, name, path=None, target=None):
        if name == sys.argv[1]:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None

sys.meta_path.insert(0, Tripwire())
from mechsynth.cli import main
sys.exit(main(["codes", "--dof", "1", "--loops", "2"]))
"""


@pytest.mark.parametrize("module", ["argparse", "synth", "mechbase", "mechsynth._parser", "mechsynth.commands.codes"])
def test_ctrl_c_while_the_command_imports_is_one_line_and_130(module):
    """A Ctrl-C while the console script imports the parser or the engine (the first 10-100 ms of
    every command) printed a traceback: the handler was installed only after those imports."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    done = subprocess.run([sys.executable, "-c", _SCRIPT_WITH_A_CTRL_C_AT_IMPORT, module], capture_output=True,
                          text=True, cwd=root, timeout=120)
    assert (done.returncode, done.stdout, done.stderr) == (130, "", "mechsynth: interrupted\n")
