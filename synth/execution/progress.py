"""Progress of a long run on stderr, readable both on a terminal and in a log file.

On a terminal :class:`Progress` draws a tqdm bar.  Anywhere else (stderr redirected to a file,
a batch job) a bar would print nothing, or one line per step; there it writes one plain line
every ``every`` seconds instead (60 by default): steps done of the total, the counters the
caller keeps (units, chains …), the time elapsed, and — when the total is known — the time
to go if the remaining steps go at the rate of those done (or, given an estimate of a counter's
total, at the rate of that counter).  The line comes on time even when no step ends for an hour
(a 20-link count's first codes): a thread of its own writes it.  :class:`Every` is the same gate
for any other line a run logs (a checkpoint's commits): the first line at once, then at most
one every ``every`` seconds.

Example
-------
>>> import io
>>> log, clock = io.StringIO(), iter([0.0, 30.0, 61.0, 62.0, 125.0]).__next__
>>> with Progress(4, "codes", desc="count", every=60, stream=log, clock=clock) as progress:
...     progress.update(1, chains=10)      # 30 s: not yet a minute
...     progress.update(1, chains=15)      # 61 s: a line
...     progress.update(0, chains=5)       # 62 s: too soon after the last
...     progress.update(2)                 # 125 s: a line
>>> print(log.getvalue(), end="")
count: 2/4 codes, 25 chains; 61 s elapsed, about 61 s to go at the rate so far
count: 4/4 codes, 30 chains; 2 min elapsed
"""

from __future__ import annotations

import os
import sys
import threading
import time
from typing import Callable

from .sizes import describe_seconds, magnitude

__all__ = ["Every", "Progress", "LOG_EVERY"]

LOG_EVERY = 60.0  # seconds between the lines of a log (where stderr is not a terminal)


def _whole(n: int) -> str:
    """A count in full, its thousands apart (a log keeps the exact number): 1 535 380 884."""
    return f"{n:,}".replace(",", " ")


class Every:
    """Pass a line on to ``write`` at once the first time, then at most once every ``every`` seconds
    (default :data:`LOG_EVERY`).

    ``flush()`` passes the last line held back, if any (a run's final state).

    >>> lines, clock = [], iter([0.0, 1.0, 61.0, 62.0]).__next__
    >>> say = Every(lines.append, 60, clock=clock)
    >>> for text in ("first", "dropped", "third", "held"):
    ...     say(text)
    >>> say.flush(); lines
    ['first', 'third', 'held']
    """

    def __init__(self, write: Callable[[str], object], every: float | None = None, *, clock=time.monotonic):
        self._write, self.every, self._clock = write, LOG_EVERY if every is None else every, clock
        self.last: float | None = None  # when a line last passed
        self._held: str | None = None

    def due(self) -> bool:
        """Whether a line may pass now (and if so, it is counted as passed)."""
        now = self._clock()
        if self.last is None or now - self.last >= self.every:
            self.last = now
            return True
        return False

    def __call__(self, line: str) -> None:
        if self.due():
            self._held = None
            self._write(line)
        else:
            self._held = line

    def flush(self) -> None:
        """Pass the line last held back (none if the last line passed)."""
        if self._held is not None:
            line, self._held = self._held, None
            self._write(line)


class Progress:
    """Steps done of ``total`` (``unit``: what a step is, in the plural) and counters, on ``stream``.

    Parameters
    ----------
    total : int, optional
        Steps in all (None: unknown, no time to go is given).
    unit : str
        What one step is, plural (``"codes"``, ``"trees"``).
    desc : str
        The line's prefix (the program's name).
    every : float, optional
        Seconds between plain lines where ``stream`` is not a terminal (default :data:`LOG_EVERY`);
        the first comes after ``every`` seconds, so a short run writes nothing.
    stream : file, optional
        Default ``sys.stderr``.
    clock : callable
        Seconds, monotonic (tests give their own).
    expected : (str, float), optional
        A counter and the total an estimate expects of it (``("units", 8.5e6)``: the units of a count with
        multiple joints, the chains of one without, :func:`~synth.synthesis.estimate.time_to_go_from`): the time
        to go is then reckoned from that counter's share of it, not from the steps.
    before : dict, optional
        What a resumed run found done by the runs before it: ``"steps"`` and counters
        (``{"steps": 468, "chains": 6_051_000_000}``). The line shows the whole run's totals, and the
        time to go is reckoned from the rate of this run alone.

    ``update(n, **counters)`` adds ``n`` steps and adds each counter (``chains=12``) to its total;
    ``write(text)`` prints a line without breaking the bar; ``close()`` clears the bar.
    """

    def __init__(self, total: int | None, unit: str, *, desc: str = "", every: float | None = None, stream=None,
                 clock=time.monotonic, expected: tuple[str, float] | None = None, before: dict | None = None):
        self.stream = stream if stream is not None else sys.stderr
        self.expected = expected
        self.total, self.unit, self.desc = total, unit, desc
        self._before = {name: n for name, n in (before or {}).items() if n}
        self.done = self._before.get("steps", 0)
        self.counters = {name: n for name, n in self._before.items() if name != "steps"}
        self._clock = clock
        self._start = clock()
        self._gate = Every(self._print, LOG_EVERY if every is None else every, clock=clock)
        self._gate.last = self._start  # the first line after ``every`` seconds, not at once
        self._shown: str | None = None  # the last plain line written (a log that has one ends with one)
        self._bar = self._ticker = None
        self._lock, self._stop = threading.Lock(), threading.Event()
        if self.stream.isatty():  # tqdm is imported only where it draws
            import tqdm

            self._bar = tqdm.tqdm(total=total, initial=self.done, unit=f" {unit}", file=self.stream, leave=False,
                                  desc=desc or None)
        elif clock is time.monotonic and self._gate.every > 0:  # (a test's own clock moves only when it says)
            self._ticker = threading.Thread(target=self._tick, daemon=True, name="progress-lines")
            self._ticker.start()

    def update(self, n: int = 1, **counters: int) -> None:
        """``n`` more steps done; each counter increased by its value."""
        with self._lock:
            self.done += n
            for name, value in counters.items():
                self.counters[name] = self.counters.get(name, 0) + value
            if self._bar is not None:
                if n:
                    self._bar.update(n)
                if counters:
                    self._bar.set_postfix(self.counters, refresh=False)
            elif self._gate.due():
                self._print(self.line(self._gate.last))

    def _tick(self) -> None:
        """The line of a run whose steps take longer than ``every``: looked at four times a period."""
        while not self._stop.wait(min(self._gate.every / 4, 15.0)):
            with self._lock:
                if self._gate.due():
                    self._print(self.line(self._gate.last))

    def line(self, now: float | None = None) -> str:
        """The plain line of the state at ``now`` (default: the clock's time)."""
        elapsed = (self._clock() if now is None else now) - self._start
        text = f"{self._state()}; {describe_seconds(elapsed)} elapsed"
        if self.expected is not None:
            name, total = self.expected
            done = self.counters.get(name, 0)
            here = done - self._before.get(name, 0)  # (the rate is this run's: a resumed run's start took no time)
            if done >= total:
                text += f", past the {magnitude(total)} {name} estimated"
            elif here > 0 and (self.total is None or self.done < self.total):  # (every step done: nothing to go)
                text += (f", about {describe_seconds(elapsed * (total - done) / here)} to go if the {name} are "
                         f"the {magnitude(total)} estimated")
        elif self.total is not None and self.done < self.total and self.done > self._before.get("steps", 0):
            here = self.done - self._before.get("steps", 0)
            text += f", about {describe_seconds(elapsed * (self.total - self.done) / here)} to go at the rate so far"
        return text

    def _state(self) -> str:
        steps = f"{self.done}/{self.total} {self.unit}" if self.total is not None else f"{self.done} {self.unit}"
        counted = "".join(f", {_whole(value)} {name}" for name, value in self.counters.items())
        return f"{self.desc}: {steps}{counted}"

    def write(self, text: str) -> None:
        """A line of its own (a finding), above the bar on a terminal."""
        if self._bar is not None:
            self._bar.write(text, file=self.stream)
        else:
            print(text, file=self.stream, flush=True)

    def _print(self, line: str) -> None:
        self._shown = line
        try:
            fd = self.stream.fileno()
        except (AttributeError, OSError, ValueError):  # a stream in memory (a test's)
            print(line, file=self.stream, flush=True)
        else:  # a file descriptor written directly: the thread holds no lock of the stream a fork could copy
            os.write(fd, f"{line}\n".encode())

    def close(self) -> None:
        """Clear the bar; in a log that has progress lines, write the final state (if not the last line)."""
        self._stop.set()
        if self._ticker is not None:
            self._ticker.join()
        if self._bar is not None:
            self._bar.close()
        elif self._shown is not None and not self._shown.startswith(self._state() + ";"):
            self._print(self.line())

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
