"""Running a query's plan: inline, on a local process pool, or on Dask — streamed, bounded, in order.

A plan is a list of *items* (one per code); ``expand(item)`` (stage A) turns an item into
its units and ``work(unit)`` (stage B) gives a unit's result (its chains, or a count).
:func:`run_plan` yields ``(index, unit, result)`` for every unit and ``(index, None, n_units)``
once item ``index`` is complete, in plan order (a listing) or as units finish (a count),
whatever the backend:

* a small query runs inline and never pays for a process pool: units run in this process
  until ``inline_seconds`` have passed, and only then are the remaining units and items handed
  to a pool (the caller passes ``inline_seconds=0`` when one item's stage A alone may be long);
* the pool (or Dask) keeps at most ``window`` tasks in flight: stage A of the next items
  runs ahead of stage B only that far, so memory stays flat however large the plan is;
* units travel in batches sized from the measured time per unit (about ``task_seconds``
  per task), so inter-process traffic stays small next to the work; the worker that runs
  stage A of an item also works on its first units for that long, so an item of small units
  (h = 2: a few hundred of 70 µs) sends none of them out again.

Example
-------
>>> double = lambda xs: list(xs)
>>> [e for e in run_plan([[1, 2], [3]], double, abs)]
[(0, 1, 1), (0, 2, 2), (0, None, 2), (1, 3, 3), (1, None, 1)]
"""

from __future__ import annotations

import multiprocessing
import os
import queue
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator

__all__ = ["process_pool", "run_plan"]


def _worker_start(parent: int) -> None:
    """Workers leave Ctrl-C to the parent and do not outlive it (``kill -9`` of a long count)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):  # pragma: no cover - no prctl: workers end after their task
            pass
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)


def process_pool(workers: int):
    """A process pool whose workers leave Ctrl-C to the parent and die with it (fork on Linux).

    Ctrl-C is held back while the workers are forked: a KeyboardInterrupt raised inside a fork
    handler is printed and dropped by Python ("Exception ignored …"), so the run would go on.
    Released afterwards, the held signal interrupts the caller as usual.
    """
    ctx = multiprocessing.get_context("fork" if sys.platform.startswith("linux") else "spawn")
    hold = hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread()
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT}) if hold else None
    try:
        return ctx.Pool(workers, initializer=_worker_start, initargs=(os.getpid(),))
    finally:
        if hold:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _expand_and_work(args):
    """Stage A of an item, then ``work`` on its first units for up to ``budget`` seconds, in the
    same worker (those units never travel back out): the units, the results of the first ones
    and the seconds they took."""
    expand, work, item, budget = args
    units = expand(item)
    start, results = time.perf_counter(), []
    for unit in units:
        if time.perf_counter() - start >= budget:
            break
        results.append(work(unit))
    return units, results, time.perf_counter() - start


class _Finished:
    """The results of units a stage-A task already worked on, standing where a batch's task would."""

    def __init__(self, results: list, seconds: float):
        self._value = results, seconds

    def ready(self) -> bool:
        return True

    def get(self):
        return self._value


def _apply_batch(args):
    """Run ``work`` on a batch of units (in a worker); returns the results and the seconds taken."""
    work, units = args
    start = time.perf_counter()
    return [work(u) for u in units], time.perf_counter() - start


class _PoolTask:
    """A task on the process pool; puts itself on ``done`` when it finishes."""

    def __init__(self, pool, fn, arg, done: queue.SimpleQueue | None):
        notify = None if done is None else (lambda _: done.put(self))
        self._result = pool.apply_async(fn, (arg,), callback=notify, error_callback=notify)

    def ready(self) -> bool:
        return self._result.ready()

    def get(self):
        return self._result.get()


#: how often a wait on a Dask cluster asks whether it still has workers (a cluster without any
#: never finishes a task: Dask waits for workers that may never come)
LIVENESS_SECONDS = 30.0


class _Liveness:
    """Raises :class:`SchedulerUnreachable` when a cluster has had no worker at two checks in a row
    (a nanny restarting a worker leaves it empty for a moment, not for a minute)."""

    def __init__(self, client):
        self.client, self.empty = client, 0

    def __call__(self) -> None:
        from .scheduler import SchedulerUnreachable

        try:
            workers = self.client.scheduler_info().get("workers", {})
        except Exception as exc:  # the scheduler itself is gone
            raise SchedulerUnreachable(f"the Dask scheduler stopped answering ({type(exc).__name__})") from None
        self.empty = 0 if workers else self.empty + 1
        if self.empty >= 2:
            raise SchedulerUnreachable(f"the Dask cluster has had no workers for {2 * LIVENESS_SECONDS:.0f} s: "
                                       "its units cannot run (start workers, or run without a scheduler)")


class _DaskTask:
    """A task on a Dask cluster; puts itself on ``done`` when it finishes."""

    def __init__(self, client, fn, arg, done: queue.SimpleQueue | None, alive: _Liveness):
        self._future = client.submit(fn, arg, pure=False)
        self._alive = alive
        if done is not None:
            self._future.add_done_callback(lambda _: done.put(self))

    def ready(self) -> bool:
        return self._future.done()

    def get(self):
        while True:
            try:
                return self._future.result(timeout=LIVENESS_SECONDS)
            except TimeoutError:  # (Dask's is the built-in one)
                self._alive()


def _next_done(done: queue.SimpleQueue, alive: Callable[[], None] | None):
    """The next finished task; while none finishes, ``alive`` (if any) checks the workers exist."""
    while True:
        try:
            return done.get(timeout=LIVENESS_SECONDS)
        except queue.Empty:
            if alive is not None:
                alive()


class _Item:
    """One item of the plan on its way through the pipeline."""

    __slots__ = ("index", "expansion", "units", "batches", "total")

    def __init__(self, index: int, expansion):
        self.index = index
        self.expansion = expansion  # stage A task, None once its units are known
        self.units: deque = deque()  # units not yet submitted
        self.batches: deque = deque()  # (units, task) in flight, in order
        self.total = 0


def run_plan(
    items: Iterable,
    expand: Callable,
    work: Callable,
    *,
    workers: int = 1,
    client=None,
    skip_item: Callable[[int], bool] | None = None,
    skip_unit: Callable | None = None,
    inline_seconds: float = 0.25,
    window: int | None = None,
    task_seconds: float | None = None,
    ordered: bool = True,
) -> Iterator[tuple]:
    """Yield ``(index, unit, work(unit))`` for every unit and ``(index, None, n_units)`` per item.

    Parameters
    ----------
    items : iterable
        The plan; ``expand(item)`` returns the item's units (a list).
    expand, work : callables
        Module-level functions (they are pickled to the workers).
    workers : int
        Local processes; 1 runs everything inline.
    client : distributed.Client, optional
        Run the tasks on this Dask cluster instead (no inline phase).
    skip_item, skip_unit : callables, optional
        Items (by index) and units already done elsewhere (a checkpoint): not run, not yielded;
        ``n_units`` still counts every unit of the item.
    inline_seconds : float
        Run inline for this long before starting a pool (a small query finishes first).
    window : int, optional
        Tasks in flight at most (default 8 per worker).
    task_seconds : float, optional
        Target duration of one task (default 0.05 s on a pool, 0.5 s on Dask).
    ordered : bool
        Yield in plan order (a listing); False yields results as they finish, so one long
        task never holds the other workers back (a count).  Every unit of an item comes
        before the item's ``(index, None, n_units)`` either way.
    """
    todo = [(i, item) for i, item in enumerate(items) if not (skip_item and skip_item(i))]
    position, first = 0, None
    if client is None:
        start = time.perf_counter()
        over = lambda: workers > 1 and time.perf_counter() - start >= inline_seconds  # noqa: E731
        while position < len(todo) and not over():
            index, item = todo[position]
            units = expand(item)
            position += 1
            pending = deque(u for u in units if not (skip_unit and skip_unit(u)))
            while pending and not over():
                unit = pending.popleft()
                yield index, unit, work(unit)
            if pending:  # the rest of this item goes to the pool first
                first = _Item(index, None)
                first.units, first.total = pending, len(units)
                break
            yield index, None, len(units)
        if position == len(todo) and first is None:
            return
    done = None if ordered else queue.SimpleQueue()
    if client is not None:
        slots = max(1, sum(client.nthreads().values()))
        alive = _Liveness(client)
        submit = lambda fn, arg: _DaskTask(client, fn, arg, done, alive)  # noqa: E731
        pool = None
    else:
        slots, alive = workers, None
        pool = process_pool(workers)
        submit = lambda fn, arg: _PoolTask(pool, fn, arg, done)  # noqa: E731
    try:
        yield from _pipeline(todo[position:], expand, work, submit, skip_unit, window or 8 * slots,
                             task_seconds or (0.5 if client is not None else 0.05), first, done, alive)
    finally:
        if pool is not None:
            pool.terminate()
            pool.join()


def _pipeline(todo, expand, work, submit, skip_unit, window: int, task_seconds: float,
              first: _Item | None = None, done: queue.SimpleQueue | None = None,
              alive: Callable[[], None] | None = None) -> Iterator[tuple]:
    """The pool / Dask part of :func:`run_plan`: at most ``window`` tasks in flight.

    ``first`` is an item the inline phase expanded but did not finish (its remaining units).
    Results come in plan order, or as they finish when ``done`` (the queue that finished
    tasks put themselves on) is given.
    """
    pending = iter(todo)
    # stage A's worker works on the item's first units too, unless units are skipped (a checkpoint
    # the workers cannot read: every unit then goes through the parent's filter)
    fused = 0.0 if skip_unit else task_seconds
    entries: deque[_Item] = deque([first] if first is not None else [])
    owner: dict[int, _Item] = {}  # id(task) -> its item, for the tasks in flight
    per_unit: float | None = None  # measured seconds per unit

    def launch(entry: _Item, fn, arg):
        task = submit(fn, arg)
        owner[id(task)] = entry
        return task

    def expanded(entry: _Item) -> tuple[list, _Finished] | None:
        """Stage A of ``entry`` is done (or about to be): its units wait for submission, but for
        the first ones its task already worked on, returned as a finished batch (or None)."""
        units, results, seconds = entry.expansion.get()
        del owner[id(entry.expansion)]
        entry.expansion = None
        entry.total = len(units)
        entry.units = deque(u for u in units[len(results):] if not (skip_unit and skip_unit(u)))
        return (units[:len(results)], _Finished(results, seconds)) if results else None

    def collected(entry: _Item, batch: list, task) -> Iterator[tuple]:
        nonlocal per_unit
        results, seconds = task.get()
        owner.pop(id(task), None)  # (a finished batch was never in flight)
        rate = seconds / len(batch)
        per_unit = rate if per_unit is None else 0.8 * per_unit + 0.2 * rate
        for unit, result in zip(batch, results):
            yield entry.index, unit, result

    def expand_in_order(entry: _Item) -> None:
        finished = expanded(entry)
        if finished is not None:
            entry.batches.appendleft(finished)  # (no batch of the item was submitted before)

    def submit_batch(entry: _Item) -> None:
        size = 1 if per_unit is None else max(1, min(512, int(task_seconds / max(per_unit, 1e-6))))
        batch = [entry.units.popleft() for _ in range(min(size, len(entry.units)))]
        entry.batches.append((batch, launch(entry, _apply_batch, (work, batch))))

    def top_up() -> None:
        while len(owner) < window:
            if done is None:  # in order: take the units of later items as soon as they are known
                for entry in entries:
                    if entry.expansion is not None and entry.expansion.ready():
                        expand_in_order(entry)
            target = next((e for e in entries if e.expansion is None and e.units), None)
            if target is not None:
                submit_batch(target)
                continue
            nxt = next(pending, None)
            if nxt is None:
                return
            entry = _Item(nxt[0], None)
            entry.expansion = launch(entry, _expand_and_work, (expand, work, nxt[1], fused))
            entries.append(entry)

    if done is not None:  # as they finish
        while True:
            top_up()
            for entry in [e for e in entries if e.expansion is None and not e.units and not e.batches]:
                entries.remove(entry)
                yield entry.index, None, entry.total
            if not entries:
                return
            task = _next_done(done, alive)
            entry = owner[id(task)]
            if task is entry.expansion:
                finished = expanded(entry)
                if finished is not None:
                    yield from collected(entry, *finished)
                continue
            position = next(i for i, (_, t) in enumerate(entry.batches) if t is task)
            batch, _ = entry.batches[position]
            del entry.batches[position]
            yield from collected(entry, batch, task)

    while True:  # in plan order
        top_up()
        if not entries:
            return
        head = entries[0]
        if head.expansion is not None:
            expand_in_order(head)  # waits for stage A of the head item
            continue
        if head.units and not head.batches:
            submit_batch(head)  # the head goes first even with a full window
        if head.batches:
            batch, task = head.batches.popleft()
            yield from collected(head, batch, task)
            continue
        entries.popleft()
        yield head.index, None, head.total
