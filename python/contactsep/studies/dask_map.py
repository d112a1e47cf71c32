"""A batch of simulations on a Dask cluster (``contactsep preload
--scheduler``, the studies of :class:`~contactsep.studies.preload.
Simulations`): the sweep's machinery of :mod:`dask_run` (the connection,
the probe, the wait that tells a lost scheduler from a lost worker)
applied to a list of tasks instead of a sweep's chunks.

What travels: each task (a Design, the model, the settings, a preload:
a few hundred bytes) and back its result (a bool or a few numbers).
Every task of a batch is submitted at once, the costliest with the
highest priority (the local pool's longest-first order), and each
result is handed to ``finished`` as it is fetched, so that a journal
keeps it before the next one is waited for.  A worker lost mid-batch
costs its tasks, which Dask runs again (a simulation's result does not
depend on where it runs); a scheduler lost mid-batch is one
:class:`~contactsep.studies.dask_run.SchedulerLost` line, the results
fetched before it kept by the journal.
"""

from __future__ import annotations

from contactsep.errors import InputError
from contactsep.output import one_line
from contactsep.studies import dask_run


class _NoStop:
    """A batch has no stop requests of its own: Ctrl-C and SIGTERM
    reach the waiting thread as exceptions."""

    @staticmethod
    def check() -> None:
        return None


def on_worker(function, task):
    """``function(task)`` on a Dask worker, with glibc's own heap
    thresholds (dask_run.heap_as_glibc_default)."""
    dask_run.heap_as_glibc_default()
    return function(task)


def _code() -> tuple[str, str]:
    from contactsep import __version__
    from contactsep.studies.code_digest import code_digest
    return __version__, code_digest()


def check_code(client) -> None:
    """Refuse (InputError) a cluster whose workers run other simulation
    code than this process: their results would be kept in a journal
    made for this code.  Workers that join later are not asked."""
    mine = _code()
    try:
        theirs = client.run(_code)
    except Exception as error:   # noqa: BLE001 - the cluster's own failure
        raise InputError(f"the Dask cluster could not say what code its "
                         f"workers run: {one_line(error)}"
                         ) from None
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


def run_tasks(client, function, tasks: list, order=None, finished=None,
              progress=None, kept=None) -> list:
    """``function(task)`` for every task on the cluster of ``client``,
    the results in the tasks' order; ``order``: the indices, costliest
    first (None: as given); ``finished(index, result)`` and
    ``progress(1)`` are called in this thread as each result arrives;
    ``kept(done)``: what a lost scheduler's line says of the ``done``
    results fetched before it."""
    order = list(range(len(tasks))) if order is None else list(order)
    count = len(order)
    futures = {}
    with dask_run.quiet_dask():
        for rank, i in enumerate(order):
            futures[i] = client.submit(on_worker, function, tasks[i],
                                       pure=False, priority=count - rank)
    index = {future.key: i for i, future in futures.items()}
    out, have = [None] * len(tasks), set()

    def take(i, result):
        out[i] = result
        have.add(i)
        if finished is not None:
            finished(i, result)
        if progress is not None:
            progress(1)

    try:
        with dask_run.quiet_dask():
            for i in order:
                if i in have:
                    continue
                note = None if kept is None else kept(len(have))
                take(i, dask_run.wait(client, futures[i], _NoStop,
                                      len(have), kept=note))
                ready = dask_run.gather_finished(
                    client, [f for j, f in futures.items()
                             if j not in have])
                for key, result in ready.items():
                    take(index[key], result)
        return out
    finally:
        left = [f for j, f in futures.items() if j not in have]
        if left:
            with dask_run.quiet_dask():
                try:
                    client.cancel(left)
                except Exception:    # noqa: BLE001 - a lost scheduler
                    pass
