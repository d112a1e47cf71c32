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

import functools
import os
import signal
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool

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
    cancelled (``Executor.map`` cancels the rest when its caller is
    interrupted) are given stand-ins first: the pool's manager thread
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
    """``function(task)`` for every task on ``pool``, the results in the
    tasks' order; the tasks are handed out one at a time, the costliest
    first (``cost(task)``, a number; None: in order), so that a batch
    ends with short tasks on every worker instead of one long task on
    one worker while the others wait (longest processing time first);
    ``done(1)`` is called as each task ends (a progress bar), and
    ``finished(index, result)`` in this thread as each task's result
    arrives (a journal that keeps it)."""
    order = list(range(len(tasks)))
    if cost is not None:
        order.sort(key=lambda i: -cost(tasks[i]))
    futures = {i: pool.submit(function, tasks[i]) for i in order}
    if done is not None:
        # a task that failed (its pool broken: RestartingPool.map runs
        # it again) is not done
        for future in futures.values():
            future.add_done_callback(
                lambda f: f.cancelled() or f.exception() is not None
                or done(1))
    try:
        if finished is not None:
            index = {future: i for i, future in futures.items()}
            broken = None
            for future in as_completed(index):
                try:
                    result = future.result()
                except BrokenProcessPool as error:
                    # every task left fails at once: the results that
                    # arrived are still handed on, then the pool's error
                    broken = broken or error
                    continue
                finished(index[future], result)
            if broken is not None:
                raise broken
        return [futures[i].result() for i in range(len(tasks))]
    except BaseException:
        for future in futures.values():
            future.cancel()
        raise


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
    the tasks in flight are run again there (the same bits: a task's
    result does not depend on where it runs).  The one local backend of
    the sweeps' chunks (:meth:`submit`, :meth:`result`) and of the
    preload searches' batches (:meth:`map`).  ``make(workers)``: a new
    pool (looked up by the caller, so that a test may plant one)."""

    def __init__(self, workers: int, make=None) -> None:
        self.workers = workers
        self._make = make or worker_pool
        #: The pools started, the last one in use.
        self.pools = [self._make(workers)]

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
        return future

    def result(self, future, again, stop):
        """The result of ``future`` (waited for between ``stop``'s
        checks); a worker killed meanwhile (its pool broken) costs the
        tasks in flight: ``again()`` submits this one on a new pool."""
        from contactsep.runs.stops import wait_for
        while True:
            try:
                return wait_for(future, stop)
            except BrokenProcessPool:
                stop.check()   # a SIGTERM to the group: workers went first
                self.restart(future.pool)
                future = again()

    def map(self, mapper, function, tasks: list, finished=None,
            **options) -> list:
        """``mapper(pool, function, tasks, finished=..., **options)``
        (:func:`map_longest_first`) on the pool in use, the results in
        the tasks' order; a worker killed meanwhile: the tasks whose
        results had not arrived go again to a new pool.  ``finished
        (index, result)`` as each result arrives.  Workers that died
        too often: :func:`died_too_often`."""
        out, todo = [None] * len(tasks), list(range(len(tasks)))
        while True:
            arrived = set()

            def kept(j, result, todo=todo, arrived=arrived):
                out[todo[j]] = result
                arrived.add(j)
                if finished is not None:
                    finished(todo[j], result)
            broken = len(self.pools)
            try:
                results = mapper(self.pool, function,
                                 [tasks[i] for i in todo], finished=kept,
                                 **options)
            except BrokenProcessPool:
                try:
                    self.restart(broken)
                except BrokenProcessPool:
                    raise died_too_often() from None
                todo = [i for j, i in enumerate(todo) if j not in arrived]
                continue
            for i, result in zip(todo, results):
                out[i] = result
            return out

    def stop(self, finished: bool = True, wait: bool = True) -> None:
        """:func:`stop_pool` of the pool in use."""
        stop_pool(self.pools[-1], finished, wait=wait)
