"""Local worker processes for the sweeps and the preload searches: a
process pool whose workers die with their parent, and a stop that never
leaves a traceback or a process behind.

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

from contactsep import output

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
        for future in futures.values():
            future.add_done_callback(lambda _: done(1))
    try:
        if finished is not None:
            index = {future: i for i, future in futures.items()}
            for future in as_completed(index):
                finished(index[future], future.result())
        return [futures[i].result() for i in range(len(tasks))]
    except BaseException:
        for future in futures.values():
            future.cancel()
        raise
