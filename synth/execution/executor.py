"""Where work runs — inline, on a local process pool, or on Dask — through one :class:`Executor`.

Every command that runs many independent pieces of work (type synthesis, grid runs, gear trains,
the site's drawings) runs them through one :class:`Executor`: picklable module-level functions
mapped over picklable units (:meth:`Executor.map`), in order or as they finish, with at most a
*window* of tasks in flight so memory stays flat however many units there are.  The pool starts
on first use, so a query that stays inline never pays for it; its workers ignore Ctrl-C and die
with this process, which terminates them when the executor closes, so Ctrl-C stops a run within a
moment whatever the workers are doing.  On Dask, a cluster that has lost all its workers is
reported in one sentence instead of waited on for ever.

A query's *plan* is a list of items (one per code); ``expand(item)`` (stage A) turns an item into
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
  (h = 2: a few hundred of 70 µs) sends none of them out again;
* an item's units may come as a :class:`~synth.execution.spill.Spilled` file (a count's large
  codes): they are read from it a batch at a time as they are submitted, never held whole, and
  the file is removed once read through (but for a :class:`~synth.execution.spill.Kept` file,
  which a count with a checkpoint removes once the item is complete).

Example
-------
>>> with Executor(workers=1) as executor:
...     list(executor.map(abs, [-3, 1, -2]))
[3, 1, 2]
>>> double = lambda xs: list(xs)
>>> [e for e in run_plan([[1, 2], [3]], double, abs)]
[(0, 1, 1), (0, 2, 2), (0, None, 2), (1, 3, 3), (1, None, 1)]
"""

from __future__ import annotations

import os
import queue
import signal
import sys
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from itertools import islice

from .spill import Spilled

__all__ = ["Executor", "process_pool", "run_plan"]


#: the signals that stop a run (Ctrl-C, the ``kill`` of a batch system's time limit, a closed terminal): held
#: back while the workers are forked, left by the workers to their parent
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


def _worker_start(parent: int, stopping=None) -> None:
    """Workers leave Ctrl-C, SIGHUP and SIGTERM to the parent and do not outlive it (``kill -9`` of a long
    count); the parent's wake-up pipe for signals (:mod:`synth.execution.interrupt`), inherited by the
    fork, is let go, so no signal a worker catches reads in the parent as its own.

    The pool ends its workers by SIGTERM, so a worker obeys the SIGTERM its parent sends, at once
    (whatever its main thread is doing), and no other: one sent to the whole process group (``kill --
    -PGID``, ``timeout``) would kill it in the middle of reading the pool's queue, holding the queue's
    lock, and the parent, ending the pool, would wait for that lock for ever.  Two SIGTERMs pending at
    once are one (standard signals do not queue): the parent's, merged with the group's, reads as the
    group's, so the parent raises ``stopping`` (shared memory; :func:`process_pool`) as it ends a worker,
    once it holds that lock, and from then on a worker obeys any SIGTERM."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "sigwaitinfo"):  # SIGTERM blocked in every thread, read by one that checks who sent it
        import threading

        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})
        threading.Thread(target=_obey_parent_only, args=(parent, stopping), daemon=True,
                         name="sigterm-from-parent").start()
    signal.set_wakeup_fd(-1)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):  # pragma: no cover - no prctl: workers end after their task
            pass
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)


def _obey_parent_only(parent: int, stopping=None) -> None:
    """End this worker on a SIGTERM from ``parent`` (the pool's terminate), on any SIGTERM once the parent
    is ending the workers (``stopping`` raised), or once the parent is gone."""
    while True:
        sender = signal.sigwaitinfo({signal.SIGTERM}).si_pid
        if sender == parent or (stopping is not None and stopping.value) or os.getppid() != parent:
            os._exit(128 + signal.SIGTERM)


def _new_pool(ctx, workers: int):
    """A pool of ``workers`` started by :func:`_worker_start`; forked, its workers' ``terminate`` raises
    the pool's ``stopping`` flag before it sends SIGTERM (the pool calls it holding its queue's lock), and
    the pool ends through :class:`_Ending`, so that no thread of this process waits for a lock a worker
    held as it was ended."""
    if ctx.get_start_method() != "fork":  # (spawned workers are pickled: no flag, no class made here)
        return ctx.Pool(workers, initializer=_worker_start, initargs=(os.getpid(),))
    from multiprocessing.pool import Pool

    stopping = ctx.RawValue("b", 0)
    ending: list[_Ending] = []  # the pool's, once it is being ended

    class Worker(ctx.Process):
        def terminate(self):
            if ending:  # (ending the pool: not the interpreter's exit ending a worker left behind)
                ending[0].settle()
            stopping.value = 1
            super().terminate()

    class StoppingPool(Pool):
        @staticmethod
        def Process(ctx, *args, **kwds):  # noqa: N802 - multiprocessing's name
            return Worker(*args, **kwds)

        @classmethod
        def _terminate_pool(cls, taskqueue, inqueue, outqueue, pool, change_notifier, worker_handler,
                            task_handler, result_handler, cache):
            ending.append(_Ending(inqueue, outqueue, task_handler, result_handler))
            super()._terminate_pool(taskqueue, inqueue, ending[0], pool, change_notifier, worker_handler,
                                    task_handler, result_handler, cache)

    return StoppingPool(workers, initializer=_worker_start, initargs=(os.getpid(), stopping), context=ctx)


class _Ending:
    """The end of a forked pool (``Pool.terminate``) without a hang when a worker is in the middle of
    sending a result (cpython#96995: a result larger than a pipe holds waits, holding the result queue's
    lock, for a reader).  The pool stops its result thread first; ended then, the worker keeps the lock
    for ever, and the pool's task thread, posting its last sentinel to that queue, waits for it for ever
    (as ``terminate`` itself may, posting its own while that thread has stopped reading).  So this
    process posts its sentinel only while the result thread still reads (:meth:`put`, which stands for
    the result queue in ``_terminate_pool``), and before the first worker is ended it reads and drops
    what the workers and the task thread still send until both threads have ended (:meth:`settle`):
    no thread of this process touches the queues after a worker is ended.

    >>> import multiprocessing, threading
    >>> queue, ended = multiprocessing.SimpleQueue(), threading.Thread(target=int)
    >>> ended.start(); ended.join()
    >>> _Ending(queue, queue, ended, ended).put(None)   # no result thread left to tell: nothing posted
    >>> queue.empty()
    True
    """

    def __init__(self, inqueue, outqueue, task_handler, result_handler):
        self.inqueue, self.outqueue = inqueue, outqueue
        self.task_handler, self.result_handler = task_handler, result_handler
        self._settled = False

    def put(self, obj) -> None:
        """Post ``obj`` (the result thread's stop sentinel) while that thread still reads: a worker
        holding the queue's lock then finishes sending; once the thread has ended there is no one to tell."""
        from multiprocessing.reduction import ForkingPickler

        lock = self.outqueue._wlock
        while self.result_handler.is_alive():
            if lock.acquire(timeout=0.01):
                try:
                    self.outqueue._writer.send_bytes(ForkingPickler.dumps(obj))
                finally:
                    lock.release()
                return

    def settle(self) -> None:
        """Once, before the first worker is ended: wait for the result thread to end (it reads what is
        being sent, then the sentinel), then read and drop what is sent on both queues (this process
        holds the task queue's read lock by now) until the task thread has posted its sentinels and ended."""
        from multiprocessing.connection import wait

        if self._settled:
            return
        self._settled = True
        self.result_handler.join()
        readers = [self.outqueue._reader, self.inqueue._reader]
        while self.task_handler.is_alive():
            for reader in wait(readers, timeout=0.01):
                reader.recv_bytes()


def process_pool(workers: int):
    """A process pool whose workers leave Ctrl-C to the parent and die with it (fork on Linux).

    Ctrl-C (and SIGTERM, SIGHUP: :data:`STOP_SIGNALS`) is held back while the workers are forked: a
    KeyboardInterrupt raised inside a fork handler is printed and dropped by Python ("Exception
    ignored …"), so the run would go on.  Blocking the signals in this thread is not enough where
    another thread runs (the progress lines): a signal reaches that thread and Python runs the
    handler in the main thread all the same, so there the handlers are also replaced, for the
    fork, by one that only notes the signal.  Released afterwards, a held signal goes to the
    handler put back (it interrupts the caller as usual), the pool ended first (the caller never
    holds it).
    """
    import multiprocessing  # (here: a query that stays inline never loads it)
    import threading

    ctx = multiprocessing.get_context("fork" if sys.platform.startswith("linux") else "spawn")
    hold = hasattr(signal, "pthread_sigmask")  # (in any thread: the forking thread's mask is what the fork sees)
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, set(STOP_SIGNALS)) if hold else None
    noted: list[int] = []
    handlers = {}
    if threading.current_thread() is threading.main_thread():
        handlers = {signum: signal.signal(signum, lambda signum, frame: noted.append(signum))
                    for signum in STOP_SIGNALS if signal.getsignal(signum) is not None}
    try:
        pool = _new_pool(ctx, workers)
    finally:
        if hold:  # (a signal held by the mask reaches the noting handler, still in place)
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)
        for signum, handler in handlers.items():
            signal.signal(signum, handler)
    if noted:  # to the handler put back; the pool, which the caller will never hold, is ended first
        try:
            signal.raise_signal(noted[0])
        except BaseException:
            pool.terminate()
            raise
    return pool


def _expand_and_work(args):
    """Stage A of an item, then ``work`` on its first units for up to ``budget`` seconds, in the
    same worker (those units never travel back out): the units (a list, or a spilled file's name),
    the results of the first ones and the seconds they took."""
    expand, work, item, budget = args
    units = expand(item)
    start, results = time.perf_counter(), []
    for unit in units:
        if time.perf_counter() - start >= budget:
            break
        results.append(work(unit))
    return units, results, time.perf_counter() - start


class _Finished:
    """The results of units a stage-A task already worked on, standing where a batch's task would
    (only ever read: it is never in flight)."""

    def __init__(self, results: list, seconds: float):
        self._value = results, seconds

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
        self.future = client.submit(fn, arg, pure=False)
        self._alive = alive
        if done is not None:
            self.future.add_done_callback(lambda _: done.put(self))

    def ready(self) -> bool:
        return self.future.done()

    def get(self):
        while True:
            try:
                return self.future.result(timeout=LIVENESS_SECONDS)
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


class Executor:
    """Where picklable work runs: inline (one worker), a local process pool, or a Dask cluster.

    Parameters
    ----------
    workers : int
        Local processes; 1 runs everything in this process.  Ignored with ``client``.
    client : distributed.Client, optional
        Run the tasks on this Dask cluster instead.

    Notes
    -----
    The pool starts on the first parallel task and is terminated by :meth:`close` (or the end
    of a ``with`` block): no worker outlives the executor, and Ctrl-C (which the workers leave
    to this process) ends a run at once.  The caller owns the ``client`` and closes it.

    Example
    -------
    >>> with Executor(workers=1) as executor:
    ...     list(executor.map(abs, [-1, -2], ordered=False))
    [1, 2]
    """

    def __init__(self, workers: int = 1, client=None):
        self.workers, self.client = workers, client
        self._pool = None
        self._alive = _Liveness(client) if client is not None else None

    @property
    def parallel(self) -> bool:
        """Whether tasks leave this process (a pool of two or more workers, or Dask)."""
        return self.client is not None or self.workers > 1

    @property
    def slots(self) -> int:
        """How many tasks run at once: the workers, or the cluster's threads."""
        if self.client is not None:
            return max(1, sum(self.client.nthreads().values()))
        return self.workers

    def _submit(self, fn, arg, done: queue.SimpleQueue | None = None):
        """Start ``fn(arg)`` on the pool or the cluster; the task puts itself on ``done`` when it ends."""
        if self.client is not None:
            return _DaskTask(self.client, fn, arg, done, self._alive)
        if self._pool is None:
            self._pool = process_pool(self.workers)
        return _PoolTask(self._pool, fn, arg, done)

    def map(self, fn: Callable, items: Iterable, *, ordered: bool = True, window: int | None = None,
            chunk: int = 1) -> Iterator:
        """``fn(item)`` for every item: in item order, or as the tasks finish (``ordered=False``).

        Items travel ``chunk`` to a task (for small ones); at most ``window`` tasks (default 4
        per slot) are in flight, so the results of a long iterable never pile up.  ``fn`` and
        the items must pickle (module-level functions).  A task's exception is raised here, and
        the tasks still in flight are dropped.
        """
        if not self.parallel:
            yield from map(fn, items)
            return
        window = window or 4 * self.slots
        done = None if ordered else queue.SimpleQueue()
        flight: dict[int, object] = {}  # id(task) -> task, in submission order
        items = iter(items)
        try:
            while part := list(islice(items, chunk)):
                task = self._submit(_apply_batch, (fn, part), done)
                flight[id(task)] = task
                if len(flight) >= window:
                    yield from self._take(flight, done)
            while flight:
                yield from self._take(flight, done)
        finally:
            self._cancel(flight.values())

    def _take(self, flight: dict, done: queue.SimpleQueue | None) -> list:
        """The results of the first task in flight (``done`` is None), or of the next to finish."""
        task = flight[next(iter(flight))] if done is None else _next_done(done, self._alive)
        del flight[id(task)]
        return task.get()[0]

    def _cancel(self, tasks) -> None:
        """Drop tasks whose results nobody will read (on Dask; a pool's are dropped when it ends)."""
        futures = [t.future for t in tasks if isinstance(t, _DaskTask)]
        if futures:
            self.client.cancel(futures)

    def close(self) -> None:
        """Terminate the pool (if one started): no worker goes on working."""
        if self._pool is not None:
            self._pool.terminate()
            self._pool.join()
            self._pool = None

    def __enter__(self) -> "Executor":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


_END = object()


class _Waiting:
    """The units of an item not yet submitted, less the skipped ones, taken from its list or its
    spilled file as they are needed (the file is removed once read through).  True while any is left."""

    __slots__ = ("_units", "_skip", "_source", "_next")

    def __init__(self, units: Iterable = (), skip: Callable | None = None, source=None):
        self._units, self._skip, self._source = iter(units), skip, source
        self._next: list = []  # a unit looked at by ``bool`` and not yet taken

    def __bool__(self) -> bool:
        if not self._next:
            self._next = self.take(1)
        return bool(self._next)

    def take(self, n: int) -> list:
        """Up to ``n`` (≥ 1) units, in order; fewer only when none is left."""
        out, self._next = self._next, []
        while len(out) < n:
            unit = next(self._units, _END)
            if unit is _END:
                if isinstance(self._source, Spilled):
                    self._source.remove()
                self._source = None
                break
            if not (self._skip and self._skip(unit)):
                out.append(unit)
        return out


class _Item:
    """One item of the plan on its way through the pipeline."""

    __slots__ = ("index", "expansion", "units", "batches", "total")

    def __init__(self, index: int, expansion):
        self.index = index
        self.expansion = expansion  # stage A task, None once its units are known
        self.units = _Waiting()  # units not yet submitted
        self.batches: deque = deque()  # (units, task) in flight, in order
        self.total = 0


def run_plan(
    items: Iterable,
    expand: Callable,
    work: Callable,
    *,
    executor: Executor | None = None,
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
        The plan; ``expand(item)`` returns the item's units (a list, or a
        :class:`~synth.execution.spill.Spilled` file of them).
    expand, work : callables
        Module-level functions (they are pickled to the workers).
    executor : Executor, optional
        Where the units run (default: inline).  A local pool starts only after the inline
        phase; on Dask there is no inline phase.  The caller closes it.
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
    executor = executor or Executor()
    todo = [(i, item) for i, item in enumerate(items) if not (skip_item and skip_item(i))]
    position, first = 0, None
    if executor.client is None:
        start = time.perf_counter()
        over = lambda: executor.parallel and time.perf_counter() - start >= inline_seconds  # noqa: E731
        while position < len(todo) and not over():
            index, item = todo[position]
            units = expand(item)
            position += 1
            pending = _Waiting(units, skip_unit, units)
            while not over() and pending:
                [unit] = pending.take(1)
                yield index, unit, work(unit)
            if pending:  # the rest of this item goes to the pool first
                first = _Item(index, None)
                first.units, first.total = pending, len(units)
                break
            yield index, None, len(units)
        if position == len(todo) and first is None:
            return
    done = None if ordered else queue.SimpleQueue()
    submit = lambda fn, arg: executor._submit(fn, arg, done)  # noqa: E731
    next_done = None if ordered else (lambda: _next_done(done, executor._alive))  # noqa: E731
    yield from _pipeline(todo[position:], expand, work, submit, skip_unit, window or 8 * executor.slots,
                         task_seconds or (0.5 if executor.client is not None else 0.05), first, next_done,
                         expansions=executor.slots)


def _pipeline(todo, expand, work, submit, skip_unit, window: int, task_seconds: float,
              first: _Item | None = None, next_done: Callable[[], object] | None = None,
              expansions: int = 1) -> Iterator[tuple]:
    """The pool / Dask part of :func:`run_plan`: at most ``window`` tasks in flight.

    ``first`` is an item the inline phase expanded but did not finish (its remaining units).
    Results come in plan order, or as they finish when ``next_done`` (which waits for the next
    finished task) is given.  A pool runs its tasks first come first served, so a window filled
    with stage-A tasks would expand that many items (and hold all their units) before the first
    unit is worked on: at most ``expansions`` stage-A tasks are in flight (one a worker) until one
    comes back with no unit left for later batches (small items, done by their own stage-A task),
    and again as soon as one comes back with units left.
    """
    pending = iter(todo)
    # stage A's worker works on the item's first units too, unless units are skipped (a checkpoint
    # the workers cannot read: every unit then goes through the parent's filter)
    fused = 0.0 if skip_unit else task_seconds
    entries: deque[_Item] = deque([first] if first is not None else [])
    owner: dict[int, _Item] = {}  # id(task) -> its item, for the tasks in flight
    per_unit: float | None = None  # measured seconds per unit
    stage_a_limit = expansions  # stage-A tasks in flight at most: the window once items are small

    def launch(entry: _Item, fn, arg):
        task = submit(fn, arg)
        owner[id(task)] = entry
        return task

    def expanded(entry: _Item) -> tuple[list, _Finished] | None:
        """Stage A of ``entry`` is done (or about to be): its units wait for submission, but for
        the first ones its task already worked on, returned as a finished batch (or None)."""
        nonlocal stage_a_limit
        units, results, seconds = entry.expansion.get()
        del owner[id(entry.expansion)]
        entry.expansion = None
        entry.total = len(units)
        rest = iter(units)
        worked = list(islice(rest, len(results)))
        entry.units = _Waiting(rest, skip_unit, units)
        stage_a_limit = expansions if entry.units else window
        return (worked, _Finished(results, seconds)) if results else None

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
        batch = entry.units.take(size)
        entry.batches.append((batch, launch(entry, _apply_batch, (work, batch))))

    def top_up() -> None:
        while len(owner) < window:
            if next_done is None:  # in order: take the units of later items as soon as they are known
                for entry in entries:
                    if entry.expansion is not None and entry.expansion.ready():
                        expand_in_order(entry)
            target = next((e for e in entries if e.expansion is None and e.units), None)
            if target is not None:
                submit_batch(target)
                continue
            if sum(e.expansion is not None for e in entries) >= stage_a_limit:
                return
            nxt = next(pending, None)
            if nxt is None:
                return
            entry = _Item(nxt[0], None)
            entry.expansion = launch(entry, _expand_and_work, (expand, work, nxt[1], fused))
            entries.append(entry)

    if next_done is not None:  # as they finish
        while True:
            top_up()
            for entry in [e for e in entries if e.expansion is None and not e.units and not e.batches]:
                entries.remove(entry)
                yield entry.index, None, entry.total
            if not entries:
                return
            task = next_done()
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
