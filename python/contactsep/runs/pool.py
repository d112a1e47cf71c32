"""Local worker processes for the sweeps and the preload searches: a
process pool whose workers die with their parent, a stop that never
leaves a traceback or a process behind, and a pool that a dead worker
does not end (:class:`RestartingPool`).

A worker (:func:`worker_pool`) ignores Ctrl-C (the parent stops the work
between chunks), takes SIGTERM's default action, closes its copies of the
parent's output locks (:func:`contactsep.output.forget_locks`) and asks
the kernel to kill it when the parent ends by any signal, SIGKILL
included (Linux: ``prctl(PR_SET_PDEATHSIG)``; a parent gone before that:
it exits at once).  Elsewhere the pool's own pipe ends it when its next
task cannot arrive.
"""

from __future__ import annotations

import collections
import functools
import os
import signal
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures import wait as wait_done
from concurrent.futures.process import BrokenProcessPool
from queue import Empty, SimpleQueue

from contactsep import output
from contactsep.errors import InputError

#: Most local worker processes per usable core: more only costs memory
#: (each holds the kernel and a chunk).
WORKERS_PER_CORE = 4


def usable_cores() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:      # not on Linux
        return os.cpu_count() or 1


def max_workers() -> int:
    """The most local workers a command takes (--workers)."""
    return WORKERS_PER_CORE * usable_cores()


def quiet_worker(parent: int | None = None) -> None:
    """A pool worker's set-up (module docstring); ``parent`` the pid of
    the process that made the pool (None: the worker's parent now)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    output.die_with_parent(os.getppid() if parent is None else parent)
    output.forget_locks()


def worker_pool(workers: int) -> ProcessPoolExecutor:
    """A pool of ``workers`` processes set up by :func:`quiet_worker`."""
    return ProcessPoolExecutor(
        max_workers=workers,
        initializer=functools.partial(quiet_worker, os.getpid()))


def stop_pool(pool: ProcessPoolExecutor, finished: bool = True,
              wait: bool = True) -> None:
    """Shut ``pool`` down; ``finished`` False (stopped early: a signal, a
    failed task): kill its workers first, the tasks still running being
    dropped (a design may take a minute).  The futures another caller
    cancelled (:func:`stream` cancels the rest when it ends early) are
    given stand-ins first: the pool's manager thread
    would mark them failed and print an ``InvalidStateError`` traceback
    (CPython 3.11's ``terminate_broken``); for the same reason the
    shutdown cancels nothing itself: the killed pool fails the rest."""
    if not finished:
        pending = getattr(pool, "_pending_work_items", None)
        if isinstance(pending, dict):
            for item in list(pending.values()):
                if item.future.cancelled():
                    item.future = Future()    # nobody waits for it

        # killed, not terminated: a SIGTERM can reach one before its
        # initializer, while it still has the parent's handlers
        for process in list((getattr(pool, "_processes", None)
                             or {}).values()):
            process.kill()
    pool.shutdown(wait=wait)


def map_longest_first(pool, function, tasks: list, cost=None,
                      done=None, finished=None) -> list:
    """``function(task)`` for every task on ``pool`` (a
    :class:`RestartingPool`), the results in the tasks' order: the
    :func:`stream` over the whole batch, the tasks handed out the
    costliest first (``cost(task)``, a number; None: in order), so that
    a batch ends with short tasks on every worker instead of one long
    task on one worker while the others wait (longest processing time
    first), their results taken as they arrive; ``finished(index,
    result)`` and then ``done(1)`` (a journal that keeps it, a progress
    bar) are called in this thread as each result arrives."""
    order = list(range(len(tasks)))
    if cost is not None:
        order.sort(key=lambda i: -cost(tasks[i]))
    out = [None] * len(tasks)
    work = stream(pool, function, ((i, (tasks[i],)) for i in order),
                  len(order), ordered=False)
    try:
        for i, result in work:
            out[i] = result
            if finished is not None:
                finished(i, result)
            if done is not None:
                done(1)
    finally:
        work.close()        # what is left cancelled before the pool stops
    return out


#: Times a local pool is started again after a worker died.
MAX_POOL_RESTARTS = 3


def died_too_often(advice: str = "") -> InputError:
    """The error of a pool whose workers died MAX_POOL_RESTARTS + 1
    times (``advice``: what may help, after a colon)."""
    return InputError(f"a worker process died {MAX_POOL_RESTARTS + 1} "
                      f"times (killed, or out of memory{advice})")


class RestartingPool:
    """Local worker processes (:func:`worker_pool`) that a dead worker
    does not end: the pool it broke is stopped and a new one started
    (MAX_POOL_RESTARTS times at most: a task that kills its worker each
    time, as the OOM killer would, then raises BrokenProcessPool), and
    the tasks in flight are run again there by the one local loop,
    :func:`stream` (the same bits: a task's result does not depend on
    where it runs): the one local backend of the sweeps' chunks and of
    the preload searches' batches (:func:`map_longest_first`).
    ``make(workers)``: a new pool (looked up by the caller, so that a
    test may plant one)."""

    def __init__(self, workers: int, make=None) -> None:
        self.workers = workers
        self._make = make or worker_pool
        #: The pools started, the last one in use.
        self.pools = [self._make(workers)]
        #: Whether a task was submitted (the processes start with it).
        self.started = False

    @property
    def pool(self):
        return self.pools[-1]

    def restart(self, broken: int) -> None:
        """Pool number ``broken`` (its count, from 1) lost a worker: a
        new one, unless that happened MAX_POOL_RESTARTS times (a second
        caller of the same broken pool finds the new one)."""
        if broken == len(self.pools):
            if len(self.pools) > MAX_POOL_RESTARTS:
                raise BrokenProcessPool("a worker died too often")
            stop_pool(self.pools[-1], finished=False)
            self.pools.append(self._make(self.workers))

    def submit(self, function, *args, stop=None):
        """``function(*args)`` on the pool in use (a new one if that one
        broke: ``stop.check()`` first), a future that knows its pool."""
        while True:
            try:
                future = self.pool.submit(function, *args)
                break
            except BrokenProcessPool:
                if stop is not None:
                    stop.check()
                self.restart(len(self.pools))
        future.pool = len(self.pools)
        self.started = True
        return future

    def stop(self, finished: bool = True, wait: bool = True) -> None:
        """:func:`stop_pool` of the pool in use."""
        stop_pool(self.pools[-1], finished, wait=wait)


#: Seconds the local loop waits for a result before it looks again for
#: a stop (the Dask loop's LISTEN_S).
LISTEN_S = 0.25


def _submitted(pool, function, args, stop, advice):
    """``function(*args)`` on ``pool`` (:meth:`RestartingPool.submit`);
    a pool that broke too often: :func:`died_too_often`."""
    try:
        return pool.submit(function, *args, stop=stop)
    except BrokenProcessPool:
        raise died_too_often(advice) from None


def stream(pool, function, items, window: int, ordered=True, stop=None,
           advice=""):
    """The one loop of work on local worker processes (``pool`` a
    :class:`RestartingPool`), the contract of the Dask loop
    (:func:`contactsep.runs.dask_map.stream`): ``function(*args)`` for
    each ``(tag, args)`` of ``items``, at most ``window`` of them ahead
    of those handed back, and (tag, result) of each: in the items' order
    (``ordered``; an item whose args are None needs no work: (tag, None)
    in its place) or as they arrive.

    The items are taken only as the window has room (a sweep's chunks
    are sized by the ones before).  ``stop.check()`` (a
    :class:`~contactsep.runs.stops.StopRequests`) is called before each
    wait of LISTEN_S at most, before a dead worker's pool is started
    again and before a failed task's error is raised.  A worker that
    died (its pool broken) costs the tasks in flight whose results had
    not arrived: they go again to a new pool (the same bits: a task's
    result does not depend on where it runs); workers that died too
    often: :func:`died_too_often` (``advice``).  What is left is
    cancelled when the stream ends early."""
    items = iter(items)
    queue = collections.deque()   # [tag, args, future], ordered only
    pending = {}                  # future -> its entry, not handed back
    arrived = SimpleQueue()       # futures as they end, unordered only
    more = True
    try:
        while True:
            if stop is not None:
                stop.check()
            while more and (len(queue) if ordered else len(pending)) \
                    < window:
                try:
                    tag, args = next(items)
                except StopIteration:
                    more = False
                    break
                entry = [tag, args, None]
                if args is not None:
                    entry[2] = _submitted(pool, function, args, stop,
                                          advice)
                    pending[entry[2]] = entry
                    if not ordered:
                        entry[2].add_done_callback(arrived.put)
                elif not ordered:
                    raise ValueError("an unordered stream's items all "
                                     "need work")
                if ordered:
                    queue.append(entry)
            if ordered:
                if not queue:
                    return
                if queue[0][2] is None:
                    yield queue.popleft()[0], None
                    continue
                future = queue[0][2]
                if not wait_done([future], timeout=LISTEN_S).done:
                    continue
            else:
                if not pending:
                    return
                try:
                    future = arrived.get(timeout=LISTEN_S)
                except Empty:
                    continue
                if future not in pending:
                    continue      # one a broken pool failed: sent again
            error = future.exception()
            if isinstance(error, BrokenProcessPool):
                _again(pool, function, pending, future.pool, stop, advice,
                       None if ordered else arrived)
                continue
            if error is not None:
                if stop is not None:
                    stop.check()  # failed because the same Ctrl-C ended it
                future.result()
            entry = pending.pop(future)
            if ordered:
                queue.popleft()
            yield entry[0], future.result()
    finally:
        for future in pending:
            future.cancel()


def _again(pool, function, pending, broken: int, stop, advice, arrived):
    """Pool number ``broken`` lost a worker: a new pool (``stop.check()``
    first: a SIGTERM to the group, the workers went first) and every
    task of ``pending`` it held whose result had not arrived sent to it
    (``arrived``: told as they end, or None)."""
    if stop is not None:
        stop.check()
    try:
        pool.restart(broken)
    except BrokenProcessPool:
        raise died_too_often(advice) from None
    for future, entry in list(pending.items()):
        if future.pool != broken or (future.done() and not
                                     future.cancelled() and
                                     future.exception() is None):
            continue
        del pending[future]
        entry[2] = _submitted(pool, function, entry[1], stop, advice)
        pending[entry[2]] = entry
        if arrived is not None:
            entry[2].add_done_callback(arrived.put)
