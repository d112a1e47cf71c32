"""A batch of simulations on a Dask cluster (``contactsep preload
--scheduler``, the studies of :class:`~contactsep.studies.preload.chart.
Simulations`): the sweep's machinery of :mod:`dask_run` (the connection,
the probe, the wait that tells a lost scheduler from a lost worker)
applied to a list of tasks instead of a sweep's chunks.

What travels: each task (a Design, the model, the settings, a preload:
a few hundred bytes) and back its result (a bool or a few numbers).
Every task of a batch is submitted in one ``client.map``, the costliest
first (the local pool's longest-first order), and each result is handed
to ``finished`` as it is fetched, so that a journal keeps it before the
next ones are waited for.  A worker lost mid-batch
costs its tasks, which Dask runs again (a simulation's result does not
depend on where it runs); a scheduler lost mid-batch is one
:class:`~contactsep.runs.dask_run.SchedulerLost` line, the results
fetched before it kept by the journal.
"""

from __future__ import annotations

import time
from concurrent.futures import CancelledError

from contactsep.errors import InputError
from contactsep.output import one_line
from contactsep.runs import dask_run


def on_worker(function, task):
    """``function(task)`` on a Dask worker, with glibc's own heap
    thresholds (dask_run.heap_as_glibc_default)."""
    dask_run.heap_as_glibc_default()
    return function(task)


def _code() -> tuple[str, str]:
    from contactsep import __version__
    from contactsep.runs.code_digest import code_digest
    return __version__, code_digest()


def check_code(client) -> None:
    """Refuse (InputError) a cluster whose workers run other simulation
    code than this process, or cannot import contactsep at all: their
    results would be kept in a journal made for this code.  Workers that
    join later are not asked."""
    mine = _code()
    try:
        theirs = client.run(_code, on_error="return")
    except Exception as error:   # noqa: BLE001 - the cluster's own failure
        raise InputError(f"the Dask cluster could not say what code its "
                         f"workers run: {one_line(error)}"
                         ) from None
    # a worker that cannot import contactsep (another environment) fails
    # to unpickle _code: Dask returns that as an Exception whose text
    # names the ModuleNotFoundError
    failed = {address: answer for address, answer in theirs.items()
              if isinstance(answer, BaseException)}
    if failed:
        address, error = min(failed.items(), key=lambda item: item[0])
        raise InputError(f"the Dask worker {address} cannot run "
                         f"contactsep ({one_line(error)}); {len(failed)} "
                         f"of {len(theirs)} workers fail: start them from "
                         f"this environment")
    other = {address: code for address, code in theirs.items()
             if tuple(code) != mine}
    if other:
        address, (version, digest) = sorted(other.items())[0]
        raise InputError(f"the Dask worker {address} runs other "
                         f"simulation code (contactsep {version}, code "
                         f"sha256 {digest[:12]}) than this command "
                         f"(contactsep {mine[0]}, {mine[1][:12]}); "
                         f"{len(other)} of {len(theirs)} workers differ: "
                         f"start them from this environment")


#: Seconds between two fetches of the results that have arrived: each
#: fetch is a round trip to the scheduler, so results arriving faster
#: (short simulations on many workers) come in one fetch of many.
FETCH_GAP_S = 0.02


def run_tasks(client, function, tasks: list, order=None, finished=None,
              progress=None, kept=None) -> list:
    """``function(task)`` for every task on the cluster of ``client``,
    the results in the tasks' order; ``order``: the indices, costliest
    first (None: as given); ``finished(index, result)`` and
    ``progress(1)`` are called in this thread as each result arrives;
    ``kept(done)``: what a lost scheduler's line says of the ``done``
    results fetched before it.

    The batch is one ``client.map`` in ``order`` (Dask runs a map's
    tasks in the order given: the costliest first); Dask's
    ``as_completed`` collects the finished ones, and those that have
    arrived are fetched in one gather every FETCH_GAP_S at most: the
    parent's work is a constant per task, not a scan of the batch after
    every result.
    """
    from distributed import as_completed
    order = list(range(len(tasks))) if order is None else list(order)
    out = [None] * len(tasks)
    if not order:
        return out
    where = dask_run.scheduler_where(client)
    with dask_run.quiet_dask():
        mapped = client.map(on_worker, [function] * len(order),
                            [tasks[i] for i in order], pure=False)
    #: The futures not yet fetched, by key, and their tasks' indices.
    left = {future.key: future for future in mapped}
    index = {future.key: i for future, i in zip(mapped, order)}
    done = 0

    def lost():
        note = None if kept is None else kept(done)
        return dask_run.scheduler_lost(where, done, note)

    try:
        with dask_run.quiet_dask():
            arrived = as_completed(mapped)
            del mapped
            lost_since = None
            while left:
                time.sleep(FETCH_GAP_S)
                if not arrived.has_ready():
                    # nothing arrives, and no connection for
                    # SCHEDULER_LOST_S: a scheduler that never cancelled
                    if client.status in dask_run.CONNECTED:
                        lost_since = None
                    else:
                        lost_since = lost_since or time.monotonic()
                        if time.monotonic() - lost_since >= \
                                dask_run.SCHEDULER_LOST_S:
                            raise lost() from None
                    continue
                # each future once, and only those not yet fetched
                ready = list({f.key: f for f in arrived.next_batch(
                    block=False) if f.key in left}.values())
                for key, result in _fetch(client, ready, arrived, lost,
                                          where):
                    del left[key]
                    out[index[key]] = result
                    done += 1
                    if finished is not None:
                        finished(index[key], result)
                    if progress is not None:
                        progress(1)
        return out
    finally:
        if left:
            with dask_run.quiet_dask():
                try:
                    client.cancel(list(left.values()))
                except Exception:    # noqa: BLE001 - a lost scheduler
                    pass


def _fetch(client, ready: list, arrived, lost, where: str) -> list:
    """[(key, result)] of the done futures ``ready``, in one gather (a
    worker lost holding one: Dask runs it again and the gather waits for
    it).  A cancelled one (the scheduler forgot it) or a connection lost
    is ``lost()``; a connection error while the client still holds its
    scheduler gives them back to ``arrived`` (an as_completed), to be
    fetched when done again; a task the cluster could not run is one
    InputError."""
    if any(future.status == "cancelled" for future in ready):
        raise lost()
    try:
        values = client.gather(ready)
    except CancelledError:                   # cancelled during the gather
        raise lost() from None
    except OSError:                          # CommClosedError
        if client.status not in dask_run.CONNECTED:
            raise lost() from None
        arrived.update(ready)
        return []
    except (RuntimeError, ImportError, AttributeError, TypeError) as error:
        if isinstance(error, InputError):
            raise
        # the cluster's own failure (another environment on the workers
        # cannot unpickle the task): one line, no trace
        raise InputError(f"the Dask cluster{where} could not run a "
                         f"simulation: {one_line(error)}") from None
    return [(future.key, value) for future, value in zip(ready, values)]
