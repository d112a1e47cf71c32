"""Where the work runs, chosen once: in this process, on local worker
processes or on a Dask cluster (:func:`backend_for`, the dispatch table
BACKENDS).  Every caller (a sweep's chunks, a search's batches of
simulations, a study's runs) takes the one backend it is given through
the same contract, so a new backend is one class here.

The contract of a backend:

1. ``stream(function, items, window, ordered=True, stop=None, ...)``:
   ``function(*args)`` for each ``(tag, args)`` of ``items``, at most
   ``window`` of them ahead of those handed back, and (tag, result) of
   each: in the items' order (``ordered``; an item whose args are None
   needs no work: (tag, None) in its place) or as they arrive.  Items
   are taken only as the window has room (a sweep's chunks are sized by
   the ones before); ``stop.check()`` is called between results; what
   is left is cancelled when the stream ends early.
2. ``map(function, tasks, cost=None, finished=None, progress=None,
   kept=None)``: ``function(task)`` of every task, the results in the
   tasks' order, handed out the costliest first (``cost(task)``) where
   workers could otherwise wait on a long one; ``finished(index,
   result)`` and ``progress(1)`` are called in this thread as each
   result arrives (a journal keeps it before the next is waited for).
3. A task's result does not depend on the backend that ran it (the same
   bits); a worker lost costs only the tasks it held, run again.
4. ``workers``: the workers the work is spread over (1 in process);
   ``share(value)``: ``value`` as it is best sent with every task (on
   Dask, scattered to the workers once); ``scratch()``: a directory the
   workers may write results into (removed once the workers stopped).
5. A backend is a context manager: leaving it stops its workers, at once
   where it ends early (an error, a stop), the tasks still running
   being dropped; a client it did not open is left open.
"""

from __future__ import annotations

import os
import shutil
import tempfile

from contactsep.errors import InputError
from contactsep.runs import dask_map, dask_run
from contactsep.runs.dask_packs import Packs
from contactsep.runs.pool import (
    RestartingPool,
    map_longest_first,
    stream as pool_stream,
    usable_cores,
    worker_pool,
)

#: A sweep's chunks in flight per Dask worker thread when only summaries
#: come back (DaskCluster.chunk_window).
DASK_WINDOW_PER_WORKER = 4


class Backend:
    """The base of every backend (module docstring: the contract)."""

    #: The workers the work is spread over, and whether it is spread
    #: at all (in process: the caller's plan is kept as it is).
    workers = 1
    parallel = True
    #: Whether large results come back best as files the workers write
    #: (:meth:`scratch`) rather than as messages.
    results_by_file = False

    def __enter__(self):
        return self

    def __exit__(self, kind, *exc) -> None:
        self.close(finished=kind is None)

    def close(self, finished: bool = True) -> None:
        """Stop the workers (``finished`` False: at once)."""

    def share(self, value):
        """``value`` as it is sent with every task."""
        return value

    def scratch(self) -> str:
        """A directory for the workers' result files (results_by_file)."""
        raise NotImplementedError("this backend sends results back")

    def check_code(self) -> None:
        """Refuse workers that run other simulation code (InputError)."""

    def chunk_window(self, summaries: bool) -> int:
        """A sweep's chunks in flight (``summaries``: only a chunk's
        summary comes back, a few numbers)."""
        return 2 * self.workers

    def stream(self, function, items, window: int, ordered=True,
               stop=None, advice="", lost=None, what="a task"):
        raise NotImplementedError

    def map(self, function, tasks: list, cost=None, finished=None,
            progress=None, kept=None) -> list:
        raise NotImplementedError


class InProcess(Backend):
    """Every task in this process, as it is taken: a stream's window is
    one; a batch runs in its tasks' order (nothing waits on a long
    task: there is no other worker)."""

    parallel = False

    def stream(self, function, items, window: int, ordered=True,
               stop=None, advice="", lost=None, what="a task"):
        for tag, args in items:
            if stop is not None:
                stop.check()
            if args is None and not ordered:
                raise ValueError("an unordered stream's items all need "
                                 "work")
            yield tag, None if args is None else function(*args)

    def map(self, function, tasks: list, cost=None, finished=None,
            progress=None, kept=None) -> list:
        out = []
        for i, task in enumerate(tasks):
            out.append(function(task))
            if finished is not None:
                finished(i, out[-1])
            if progress is not None:
                progress(1)
        return out


class LocalPool(Backend):
    """``workers`` local worker processes
    (:class:`~contactsep.runs.pool.RestartingPool`: started again where
    a worker dies), through the one local loop
    (:func:`contactsep.runs.pool.stream`).  Large results come back as
    files: a worker killed while it sent megabytes of columns would
    leave the pool reading the rest of the message forever."""

    results_by_file = True

    def __init__(self, workers: int) -> None:
        self.workers = workers
        # looked up here, so that a test may plant a pool
        self.pool = RestartingPool(workers, make=worker_pool)
        self._scratch = []

    def close(self, finished: bool = True) -> None:
        # a pool that could not start its processes leaves nobody to wait
        # for (the interpreter's exit would wait for them forever)
        self.pool.stop(finished, wait=self.pool.started)
        for directory in self._scratch:
            shutil.rmtree(directory, ignore_errors=True)

    def scratch(self) -> str:
        shared = "/dev/shm" if os.path.isdir("/dev/shm") else None
        self._scratch.append(tempfile.mkdtemp(prefix="contactsep-sweep-",
                                              dir=shared))
        return self._scratch[-1]

    def stream(self, function, items, window: int, ordered=True,
               stop=None, advice="", lost=None, what="a task"):
        work = pool_stream(self.pool, function, items, window,
                           ordered=ordered, stop=stop, advice=advice)
        try:
            yield from work
        except OSError as error:
            if self.pool.started:
                raise
            # the pool starts its processes at the first task: one that
            # could not start (a process limit) is the option's error
            raise InputError(f"--workers {self.workers}: the worker "
                             f"processes could not be started "
                             f"({error.strerror or error}); try fewer"
                             ) from None
        finally:
            work.close()

    def map(self, function, tasks: list, cost=None, finished=None,
            progress=None, kept=None) -> list:
        return map_longest_first(self.pool, function, tasks, cost=cost,
                                 done=progress, finished=finished)


class DaskCluster(Backend):
    """The workers of a Dask cluster (``client``; ``owned``: closed with
    the backend), through the one Dask loop
    (:func:`contactsep.runs.dask_map.stream`); a batch's short runs are
    packed into tasks (:mod:`contactsep.runs.dask_packs`)."""

    def __init__(self, client, owned: bool = False) -> None:
        self.client = client
        self.owned = owned
        self.workers = dask_run.threads(client)
        # a search's batches packed by the time a run took so far
        self.packs = Packs(self.workers)

    def close(self, finished: bool = True) -> None:
        if self.owned:
            self.client.close()

    def share(self, value):
        try:
            return self.client.scatter(value, broadcast=True, hash=False)
        except Exception:     # noqa: BLE001 - a client without scatter
            return value

    def check_code(self) -> None:
        dask_map.check_code(self.client)

    def chunk_window(self, summaries: bool) -> int:
        # The parent's loop is the limit on many workers (measured on
        # 16: docs/performance.md): a result fetched alone costs a round
        # trip to the scheduler and a worker, and two chunks a worker
        # left workers idle while the parent fetched the oldest.  So the
        # scheduler queues DASK_WINDOW_PER_WORKER chunks a worker when
        # only summaries come back; columns wait in the parent until
        # their turn: fewer of them.
        per = DASK_WINDOW_PER_WORKER if summaries else 2
        return per * self.workers + 2

    def stream(self, function, items, window: int, ordered=True,
               stop=None, advice="", lost=None, what="a task"):
        if lost is None:
            def lost(where):
                return dask_run.scheduler_lost(where, 0)
        return dask_map.stream(self.client, function, items, window, lost,
                               ordered=ordered, stop=stop, what=what)

    def map(self, function, tasks: list, cost=None, finished=None,
            progress=None, kept=None) -> list:
        order = list(range(len(tasks)))
        if cost is not None:
            order.sort(key=lambda i: -cost(tasks[i]))
        return dask_map.run_tasks(self.client, function, tasks, order=order,
                                  finished=finished, progress=progress,
                                  kept=kept, packs=self.packs)


#: The backends by name (backend_for chooses one).
BACKENDS = {"process": InProcess, "local": LocalPool, "dask": DaskCluster}


def backend_for(workers: int | None = None, scheduler=None) -> Backend:
    """The backend of a command's ``--workers`` and ``--scheduler``: a
    Dask cluster where ``scheduler`` (an address, or a
    ``distributed.Client``, left open) is given, else ``workers`` local
    processes (None: the usable cores), 1 in this process."""
    if scheduler is not None and scheduler != "":
        if hasattr(scheduler, "submit"):        # a Client
            return BACKENDS["dask"](scheduler)
        return BACKENDS["dask"](dask_run.connect(scheduler), owned=True)
    workers = usable_cores() if workers is None else workers
    if workers <= 1:
        return BACKENDS["process"]()
    return BACKENDS["local"](workers)
