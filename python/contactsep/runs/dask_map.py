"""The one loop of work on a Dask cluster (:func:`stream`: a window of
tasks, their results fetched in batched gathers, handed back in order or
as they arrive), and the batch of simulations on it (``contactsep
preload --scheduler``, the studies of :class:`~contactsep.studies.
preload.chart.Simulations`: :func:`run_tasks`); a sweep's chunks take
the same loop (:class:`contactsep.runs.backend.DaskCluster`, the backend
every caller takes), the connection and the probe are :mod:`dask_run`'s.

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

import collections
import time
from concurrent.futures import CancelledError

from contactsep.errors import InputError
from contactsep.output import one_line
from contactsep.runs import dask_run
from contactsep.runs.dask_packs import Pack, Packs, run_pack


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
              progress=None, kept=None, packs=None) -> list:
    """``function(task)`` for every task on the cluster of ``client``,
    the results in the tasks' order; ``order``: the indices, costliest
    first (None: as given); ``finished(index, result)`` and
    ``progress(1)`` are called in this thread as each result arrives;
    ``kept(done)``: what a lost scheduler's line says of the ``done``
    results fetched before it; ``packs``: a
    :class:`~contactsep.runs.dask_packs.Packs` that sizes the packs from
    the runs timed in earlier batches (None: one run a pack).

    The batch is cut into packs of short runs (:mod:`dask_packs`: one
    Dask task each, many runs of a few milliseconds together) and run
    as one :func:`stream` whose window is the whole batch: one
    ``client.map`` in ``order`` (Dask runs a map's tasks in the order
    given: the costliest first), each pack's results handed back as it
    arrives, a run's in the pack's order.  A run that failed is raised
    once the pack's other runs are handed back (kept by a journal).
    """
    order = list(range(len(tasks))) if order is None else list(order)
    out = [None] * len(tasks)
    if not order:
        return out
    packs = Packs() if packs is None else packs
    done = 0

    def lost(where):
        note = None if kept is None else kept(done)
        return dask_run.scheduler_lost(where, done, note)

    cut = packs.cut(order)
    for indices, (results, seconds) in stream(
            client, run_pack,
            ((indices, (Pack(function, [tasks[i] for i in indices]),))
             for indices in cut),
            len(cut), lost, ordered=False, what="a simulation"):
        packs.record(len(indices), seconds)
        failed = [result for ok, result in results if not ok]
        for i, (ok, result) in zip(indices, results):
            if not ok:
                continue
            out[i] = result
            done += 1
            if finished is not None:
                finished(i, result)
            if progress is not None:
                progress(1)
        if failed:
            raise _task_error(failed[0], dask_run.scheduler_where(client),
                              "a simulation")
    return out


def stream(client, function, items, window: int, lost, ordered=True,
           stop=None, what="a task"):
    """The one loop of work on a Dask cluster: ``function(*args)`` for
    each ``(tag, args)`` of ``items``, at most ``window`` of them ahead
    of those handed back, and (tag, result) of each: in the items' order
    (``ordered``; an item whose args are None needs no work: (tag, None)
    in its place) or as they arrive.

    The items are taken only as the window has room (a sweep's chunks
    are sized by the ones before) and those taken together are one
    ``client.map``; Dask's ``as_completed`` collects the finished ones,
    and those that have arrived are fetched in one gather, one every
    FETCH_GAP_S at most: the parent's work is a constant per task, not
    a scan of the futures in flight.  ``stop.check()`` (a
    :class:`~contactsep.runs.stops.StopRequests`) is called between
    fetches.  ``lost(where)`` is the exception of a lost scheduler (a
    task the scheduler cancelled, a connection closed, or none for
    SCHEDULER_LOST_S); a task the cluster could not run (``what``) is
    one InputError.  A worker lost costs its tasks, which Dask runs
    again.  What is left is cancelled when the stream ends early.
    """
    from distributed import as_completed
    items = iter(items)
    where = dask_run.scheduler_where(client)
    queue = collections.deque()  # [tag, future or None], ordered only
    pending = {}                 # key -> future not yet handed back
    tags = {}                    # key -> tag
    fetched = {}                 # key -> result, or _FAILED
    arrived = as_completed(loop=client.loop)
    lost_since = fetch_at = None
    more = True
    try:
        with dask_run.quiet_dask():
            while True:
                if stop is not None:
                    stop.check()
                if more:
                    more = _submit(client, function, items, window, queue,
                                   pending, tags, arrived, ordered)
                key = _next_key(queue, fetched, ordered)
                if key is not None:
                    yield _hand_back(client, key, queue, pending, tags,
                                     fetched, lost, where, what, ordered)
                    continue
                if not more and not pending and not queue:
                    return
                _arrival(arrived, fetch_at)
                if not arrived.has_ready():
                    # nothing arrives, and no connection for
                    # SCHEDULER_LOST_S: a scheduler that never cancelled
                    if client.status in dask_run.CONNECTED:
                        lost_since = None
                    else:
                        lost_since = lost_since or time.monotonic()
                        if time.monotonic() - lost_since >= \
                                dask_run.SCHEDULER_LOST_S:
                            raise lost(where) from None
                    continue
                # each future once, and only those not yet fetched
                ready = list({f.key: f for f in arrived.next_batch(
                    block=False) if f.key in pending and f.key not in
                    fetched}.values())
                fetched.update(_fetch(client, ready, arrived, lost, where,
                                      what))
                fetch_at = time.monotonic()
    finally:
        if pending:
            with dask_run.quiet_dask():
                try:
                    client.cancel(list(pending.values()))
                except Exception:    # noqa: BLE001 - a lost scheduler
                    pass


#: Seconds the loop waits for a result before it looks again for a stop
#: and for its scheduler.
LISTEN_S = 0.25


def _arrival(arrived, fetch_at):
    """Wait (LISTEN_S at most) until a result has arrived in ``arrived``
    (an as_completed: it notifies its ``thread_condition`` at each), and
    until FETCH_GAP_S after the last fetch ended (``fetch_at``, monotonic
    seconds, None: none yet): the first result after a pause is fetched
    at once, those arriving faster together, and at once when every task
    in flight has arrived (nothing more is worth the wait: the end of a
    batch of a few runs)."""
    condition = getattr(arrived, "thread_condition", None)
    if condition is None:
        # an as_completed without it (it is not distributed's documented
        # API): look again after FETCH_GAP_S, as a poll
        time.sleep(FETCH_GAP_S)
    else:
        with condition:
            if not arrived.has_ready():
                condition.wait(LISTEN_S)
    # as_completed's futures not yet done (distributed's own attribute;
    # without it, the gap)
    if fetch_at is not None and getattr(arrived, "futures", True):
        time.sleep(max(0.0, fetch_at + FETCH_GAP_S - time.monotonic()))


class OnWorker:
    """``function(*args)`` on a Dask worker, its malloc given glibc's own
    thresholds back first (:func:`contactsep.runs.dask_run.
    heap_as_glibc_default`: every task of the loop), named as
    ``function`` (its tasks' keys on the dashboard)."""

    def __init__(self, function) -> None:
        self.function = function
        self.__name__ = getattr(function, "__name__", "task")

    def __call__(self, *args):
        dask_run.heap_as_glibc_default()
        return self.function(*args)


#: A fetched task that failed: its error is raised at its turn.
_FAILED = object()


def _submit(client, function, items, window: int, queue, pending, tags,
            arrived, ordered) -> bool:
    """Take items while the window has room, their work one
    ``client.map``; False once the items are all taken."""
    new, more = [], True
    while (len(queue) if ordered else len(pending) + len(new)) < window:
        try:
            tag, args = next(items)
        except StopIteration:
            more = False
            break
        entry = [tag, None]
        if ordered:
            queue.append(entry)
        if args is not None:
            new.append((entry, args))
        elif not ordered:
            raise ValueError("an unordered stream's items all need work")
    if new:
        futures = client.map(OnWorker(function),
                             *zip(*(args for _, args in new)), pure=False)
        for (entry, _), future in zip(new, futures):
            entry[1] = future
            pending[future.key] = future
            tags[future.key] = entry[0]
        arrived.update(futures)
    return more


def _next_key(queue, fetched, ordered):
    """The key of the next result to hand back (False: an ordered item
    that needed no work), or None while it has not arrived."""
    if ordered:
        if queue and queue[0][1] is None:
            return False
        if queue and queue[0][1].key in fetched:
            return queue[0][1].key
        return None
    return next(iter(fetched), None)


def _hand_back(client, key, queue, pending, tags, fetched, lost, where,
               what, ordered):
    """(tag, result) of ``key`` (False: the ordered head that needed no
    work), taken out of the stream's books; a failed task's error is
    raised here, at its turn."""
    if key is False:
        return queue.popleft()[0], None
    if ordered:
        queue.popleft()
    result = fetched.pop(key)
    if result is _FAILED:
        # its error, mapped as any fetch's (the future stays pending:
        # cancelled on the way out)
        _gather(client, [pending[key]], lost, where, what)
        pending[key].result()
    del pending[key]
    return tags.pop(key), result


def _fetch(client, ready: list, arrived, lost, where: str, what) -> dict:
    """{key: result} of the done futures ``ready``, those finished in
    one gather (a worker lost holding one: Dask runs it again and the
    gather waits for it), those failed _FAILED.  A cancelled one (the
    scheduler forgot it) or a connection lost is ``lost(where)``; a
    connection error while the client still holds its scheduler gives
    them back to ``arrived`` (an as_completed), to be fetched when done
    again."""
    if any(future.status == "cancelled" for future in ready):
        raise lost(where)
    failed = {f.key: _FAILED for f in ready if f.status == "error"}
    ready = [f for f in ready if f.key not in failed]
    values = _gather(client, ready, lost, where, what) if ready else []
    if values is None:
        arrived.update(ready)
        return failed
    return {**{f.key: value for f, value in zip(ready, values)}, **failed}


def _gather(client, futures: list, lost, where: str, what):
    """``client.gather(futures)``, None where the connection failed
    while the client still holds its scheduler; the cluster's own
    failure to run a task is one InputError."""
    try:
        return client.gather(futures)
    except CancelledError:                   # cancelled during the gather
        raise lost(where) from None
    except OSError:                          # CommClosedError
        if client.status not in dask_run.CONNECTED:
            raise lost(where) from None
        return None
    except (RuntimeError, ImportError, AttributeError, TypeError) as error:
        raise _task_error(error, where, what) from None


def _task_error(error, where: str, what) -> BaseException:
    """The exception the parent raises for a task's ``error``: the
    cluster's own failure (another environment on the workers cannot
    unpickle the task: a RuntimeError, ImportError, AttributeError or
    TypeError other than an InputError) one InputError line, no trace;
    any other error itself."""
    if isinstance(error, InputError) or not isinstance(
            error, (RuntimeError, ImportError, AttributeError, TypeError)):
        return error
    return InputError(f"the Dask cluster{where} could not run "
                      f"{what}: {one_line(error)}")
