"""Running a sweep: chunks in order, locally or on a Dask cluster, streamed
to writers, with a progress bar on a terminal."""

from __future__ import annotations

import collections
import math
import os
import shutil
import tempfile
import time
from concurrent.futures.process import BrokenProcessPool

from contactsep import output
from contactsep.errors import InputError
from contactsep.model.evaluate import costly
from contactsep.studies import chatter_sweep, dask_run
from contactsep.studies.chunks import Chunks
from contactsep.studies.dask_run import (  # noqa: F401 - the runner's API
    SCHEDULER_TIMEOUT_S,
    SchedulerLost,
    connect,
)
from contactsep.studies.pool import (  # noqa: F401 - the runner's API
    WORKERS_PER_CORE,
    max_workers,
    quiet_worker,
    stop_pool,
    usable_cores,
    worker_pool,
)
from contactsep.studies.resume import (  # noqa: F401 - the runner's API
    ChunkStore,
    ResumeError,
    load_columns,
    save_columns,
)
from contactsep.studies.stops import StopRequests, progress_bar, wait_for
from contactsep.studies.sweep import (
    CHUNK_SIZE,
    MAX_CHUNK_SIZE,
    Summary,
    SweepSpec,
    evaluate_chunk,
)
from contactsep.studies.writers import (  # noqa: F401 - the runner's API
    COLUMNS_NOTE,
    TITLE,
    CsvWriter,
    ParquetWriter,
    require_pyarrow,
)


class SweepInterrupted(InputError):
    """A sweep stopped by the user; its outputs are left as they were,
    the chunks it finished are in its store (if it had one).  The
    command reports it in one line and exits 130, as for Ctrl-C."""

    interrupted = True


#: The pool workers' set-up (the name studies.preload imports).
_quiet_worker = quiet_worker


def default_chunk_size(spec: SweepSpec) -> int:
    """The most designs a chunk has unless asked: 100,000 of eq. 23 (one
    compiled batch), 8 chatter simulations (a design takes 10-400 ms:
    the progress bar moves, the workers stay evenly loaded)."""
    return CHUNK_SIZE if spec.model == "eq23" else chatter_sweep.CHUNK_SIZE


def check_threshold(spec: SweepSpec, threshold) -> None:
    """A threshold is on eq23's max y3: a chatter sweep refuses it."""
    if threshold is not None and spec.model != "eq23":
        raise InputError(f"--threshold: eq23's max y3; a {spec.model} "
                         f"sweep reports p_open, the designs with a "
                         f"discontinuity event")


def evaluate(spec: SweepSpec, first: int, last: int) -> dict:
    """The columns of designs first..last-1, by the sweep's model."""
    if spec.model == "eq23":
        return evaluate_chunk(spec, first, last)
    return chatter_sweep.evaluate_chunk(spec, first, last)


def evaluate_chunk_timed(spec, first, last) -> tuple[dict, float]:
    """A chunk's columns and the seconds it took (chunks are sized by
    the time per design: Chunks.record)."""
    start = time.perf_counter()
    columns = evaluate(spec, first, last)
    return columns, time.perf_counter() - start


def _new_summary(spec: SweepSpec, threshold):
    return Summary(threshold=threshold) if spec.model == "eq23" \
        else chatter_sweep.ChatterSummary()


def chunk_result(spec, first, last, threshold, mode, directory=None):
    """A chunk computed where it runs (a worker), in the form the parent
    wants, with the seconds it took: ``mode`` "summary" (nothing is
    written: the chunk's own summary, a few numbers), "file" (its
    columns saved as ``directory``/FIRST-LAST.npz, the message back a
    short path: a worker killed while it sent megabytes of columns
    would leave the pool reading the rest of the message forever), or
    "columns" (the NumPy columns themselves: Dask)."""
    columns, seconds = evaluate_chunk_timed(spec, first, last)
    if mode == "summary":
        summary = _new_summary(spec, threshold)
        summary.add(columns)
        return summary, last - first, seconds
    if mode == "file":
        path = os.path.join(directory, f"{first:012d}-{last:012d}.npz")
        save_columns(path, columns)
        return path, last - first, seconds
    return columns, last - first, seconds


def chunk_result_on_dask(spec, first, last, threshold, mode):
    """:func:`chunk_result` on a Dask worker, its malloc set back to
    glibc's own thresholds first (dask_run.heap_as_glibc_default)."""
    dask_run.heap_as_glibc_default()
    return chunk_result(spec, first, last, threshold, mode)


class _Done:
    """A chunk that needs no work (stored by an earlier run)."""

    def __init__(self, value) -> None:
        self.value = value


def _submit_all(bounds: Chunks, submit, store, window_size, take):
    """Submit each chunk the store lacks (``submit(first, last)``, a
    future), ``window_size`` at most in flight, and yield
    ``take(item)`` of each chunk in order."""
    window = collections.deque()
    for first, last, stored in bounds.plan():
        if stored:
            window.append((first, last, _Done(store.load(first))))
        else:
            window.append((first, last, submit(first, last)))
        while len(window) >= window_size or (
                window and isinstance(window[0][2], _Done)):
            yield take(window.popleft())
    while window:
        yield take(window.popleft())


#: Times a sweep's local pool is started again after a worker died.
MAX_POOL_RESTARTS = 3


def _results_local(spec, bounds: Chunks, workers, stop, mode, threshold,
                   store):
    """(kind, value, designs) of each chunk in order: kind "summary"
    (value a partial summary) or "columns"."""
    if workers <= 1:
        for first, last, stored in bounds.plan():
            stop.check()
            if stored:
                yield "columns", store.load(first), last - first
                continue
            value, designs, seconds = chunk_result(
                spec, first, last, threshold,
                "summary" if mode == "summary" else "columns")
            bounds.record(designs, seconds)
            if store is not None:
                store.save(first, last, value)
            yield ("summary" if mode == "summary" else "columns"), value, \
                designs
        return
    if store is not None:
        directory = store.path          # the workers save into the store
    else:
        shared = "/dev/shm" if os.path.isdir("/dev/shm") else None
        directory = tempfile.mkdtemp(prefix="contactsep-sweep-",
                                     dir=shared)
    pools = [worker_pool(workers)]      # the last one is in use
    finished = started = False
    task_mode = "summary" if mode == "summary" else "file"

    def restart(broken: int) -> None:
        """Pool number ``broken`` lost a worker: a new one, unless that
        happened MAX_POOL_RESTARTS times (a chunk that kills its worker
        each time, as the OOM killer would)."""
        if broken == len(pools):
            if len(pools) > MAX_POOL_RESTARTS:
                raise BrokenProcessPool("a worker died too often")
            stop_pool(pools[-1], finished=False)
            pools.append(worker_pool(workers))

    def submit(first, last):
        nonlocal started
        while True:
            try:
                future = pools[-1].submit(chunk_result, spec, first, last,
                                          threshold, task_mode, directory)
                break
            except BrokenProcessPool:
                stop.check()
                restart(len(pools))
        future.pool = len(pools)
        started = True
        return future

    def result(first, last, work):
        """A chunk's result; a worker killed meanwhile (its pool broken)
        costs the chunks in flight, run again on a new pool (the same
        bits: a chunk does not depend on where it runs)."""
        while True:
            try:
                return wait_for(work, stop)
            except BrokenProcessPool:
                stop.check()   # a SIGTERM to the group: workers went first
                restart(work.pool)
                work = submit(first, last)

    def take(item):
        first, last, work = item
        if isinstance(work, _Done):
            return "columns", work.value, last - first
        value, designs, seconds = result(first, last, work)
        bounds.record(designs, seconds)
        if task_mode == "summary":
            return "summary", value, designs
        columns = load_columns(value)
        if store is None:
            os.unlink(value)
        else:
            store.chunks[first] = last
        return "columns", columns, designs

    try:
        yield from _submit_all(bounds, submit, store, 2 * workers, take)
        finished = True
    except BrokenProcessPool:
        stop.check()   # a SIGTERM to the whole group: the workers went first
        raise InputError(f"a worker process died {MAX_POOL_RESTARTS + 1} "
                         f"times (killed, or out of memory: try a smaller "
                         f"--chunk-size)") from None
    except OSError as error:
        if started:
            raise
        # the pool starts its processes at the first chunk: one that
        # could not start (a process limit) left the others waiting for
        # work forever, and the interpreter's exit waiting for them
        raise InputError(f"--workers {workers}: the worker processes could "
                         f"not be started ({error.strerror or error}); try "
                         f"fewer") from None
    finally:
        # stopped early (a signal, a writer's error, a dead worker, a
        # pool that could not start): the chunks still running are
        # dropped, so their workers are stopped now rather than waited
        # for (a design may take seconds)
        stop_pool(pools[-1], finished, wait=started)
        if store is None:
            shutil.rmtree(directory, ignore_errors=True)


#: Chunks in flight per Dask worker thread when only summaries come back.
DASK_WINDOW_PER_WORKER = 4


def _results_dask(spec, bounds: Chunks, address, stop, mode, threshold,
                  store):
    """As :func:`_results_local`, the chunks on a Dask cluster
    (contactsep.studies.dask_run).

    The parent's loop is the limit on many workers (measured on 16:
    docs/performance.md): a result fetched alone costs a round trip to
    the scheduler and a worker, and a window of two chunks a worker
    left workers idle while the parent fetched the oldest.  So the
    window holds DASK_WINDOW_PER_WORKER chunks a worker (the scheduler
    queues them), and each fetch takes every finished chunk in one
    gather; the chunks are still taken in order."""
    client = address if hasattr(address, "submit") else connect(address)
    task_mode = "summary" if mode == "summary" else "columns"
    bounds.workers = dask_run.threads(client)
    pending = {}        # key -> future, submitted and not yet taken
    fetched = {}        # key -> result, gathered ahead of its turn
    done = 0
    # the spec goes to the workers once, not with every task
    try:
        shared = client.scatter(spec, broadcast=True, hash=False)
    except Exception:        # noqa: BLE001 - a client without scatter
        shared = spec

    def submit(first, last):
        future = client.submit(chunk_result_on_dask, shared, first, last,
                               threshold, task_mode, pure=False)
        pending[future.key] = future
        return future

    def take(item):
        nonlocal done
        first, last, work = item
        if isinstance(work, _Done):
            done += last - first
            return "columns", work.value, last - first
        if work.key in fetched:
            value, designs, seconds = fetched.pop(work.key)
        else:
            value, designs, seconds = dask_run.wait(client, work, stop,
                                                    done)
            fetched.update(dask_run.gather_finished(
                client, [f for key, f in pending.items()
                         if key != work.key and key not in fetched]))
        del pending[work.key]
        bounds.record(designs, seconds)
        if store is not None:
            store.save(first, last, value)
        done += designs
        return task_mode, value, designs

    window = DASK_WINDOW_PER_WORKER * bounds.workers + 2
    if task_mode == "columns":
        # columns wait in the parent until their turn: fewer of them
        window = 2 * bounds.workers + 2
    try:
        with dask_run.quiet_dask():
            yield from _submit_all(bounds, submit, store, window, take)
    finally:
        with dask_run.quiet_dask():
            try:
                client.cancel([f for f in pending.values() if not f.done()])
            except Exception:    # noqa: BLE001 - a lost scheduler
                pass
            if client is not address:
                client.close()


def check_run(*, chunk_size=None, workers=None, threshold=None
              ) -> None:
    """The run options of :func:`run_sweep`, checked before any work or
    file (InputError naming the option; ``chunk_size`` None: the
    model's default)."""
    if chunk_size is not None and (
            isinstance(chunk_size, bool) or not isinstance(chunk_size, int)
            or not 1 <= chunk_size <= MAX_CHUNK_SIZE):
        raise InputError(f"--chunk-size: found {chunk_size!r}, expected an "
                         f"integer from 1 to {MAX_CHUNK_SIZE:,}")
    if workers is not None and (
            isinstance(workers, bool) or not isinstance(workers, int)
            or not 1 <= workers <= max_workers()):
        raise InputError(f"--workers: found {workers!r}, expected an "
                         f"integer from 1 to {max_workers()} "
                         f"({WORKERS_PER_CORE} per usable core)")
    if threshold is not None and (
            isinstance(threshold, bool)
            or not isinstance(threshold, (int, float))
            or not math.isfinite(threshold)):
        raise InputError(f"--threshold: found {threshold!r}, expected a "
                         f"finite number (in)")


def run_sweep(spec: SweepSpec, *, writers=(), threshold=None,
              chunk_size: int | None = None, workers: int | None = None,
              scheduler=None, progress: bool | None = None,
              store: ChunkStore | None = None) -> dict:
    """Evaluate every design of ``spec`` chunk by chunk, in order; each
    chunk goes to every writer as it arrives (without writers each
    worker sends back its chunk's summary only).  Returns the summary
    (:meth:`Summary.as_dict`, or :meth:`ChatterSummary.as_dict
    <contactsep.studies.chatter_sweep.ChatterSummary.as_dict>` for a
    chatter model; ``elapsed_s``; and ``inputs``: what made the sweep,
    :meth:`SweepSpec.inputs`).

    ``chunk_size``: the most designs a chunk has (default
    :func:`default_chunk_size`; chunks are sized by cost below it:
    :class:`~contactsep.studies.chunks.Chunks`); ``threshold`` (in, eq23
    only): also report P(max y3 > threshold);
    ``workers``: local processes (default: the usable cores; 1 runs in
    this process; at most WORKERS_PER_CORE a core); ``scheduler``: a Dask
    scheduler address (or Client).  A sweep that does not finish (an
    interrupt, Ctrl-C or SIGTERM: :class:`SweepInterrupted`, SIGTERM the
    command's own exception; a dead worker; any other error) drops the
    writers' files (:meth:`CsvWriter.abort`: the old file, or none,
    stays under the final name); what it finished is in ``store``.
    ``store``: a :class:`~contactsep.studies.resume.ChunkStore` that
    keeps every finished chunk (and gives those an earlier run kept),
    removed when the writers' files are in place.
    """
    check_run(chunk_size=chunk_size, workers=workers, threshold=threshold)
    check_threshold(spec, threshold)
    if chunk_size is None:
        chunk_size = default_chunk_size(spec)
    if workers is None:
        workers = usable_cores()
    # a chatter design takes 10-400 ms: the first chunk is one design
    bounds = Chunks(spec.size, chunk_size, spec.max_modes,
                    spec.model != "eq23"
                    or costly(spec.max_modes, spec.max_tau),
                    workers=workers,
                    stored=store.chunks if store is not None else None)
    if spec.size - (store.designs if store is not None else 0) \
            <= bounds.next:
        workers = 1
    summary = _new_summary(spec, threshold)
    mode = "columns" if writers or store is not None else "summary"
    bar = progress_bar(spec.size, progress)
    done = 0
    start = time.perf_counter()
    with StopRequests() as stop, output.stop_checks(stop.check):
        results = _results_dask(
            spec, bounds, scheduler, stop, mode, threshold, store) \
            if scheduler else _results_local(
                spec, bounds, workers, stop, mode, threshold, store)
        ended = None
        try:
            for kind, value, designs in results:
                if kind == "summary":
                    summary.merge(value)
                else:
                    for writer in writers:
                        writer.write(value)
                    summary.add(value)
                done += designs
                if bar is not None:
                    bar.update(designs)
                stop.check()
        except KeyboardInterrupt:
            ended = "interrupted"
            raise SweepInterrupted(
                f"interrupted: {done} of {spec.size} designs were "
                f"evaluated{kept_note(store, writers)}") from None
        except OSError:
            ended = "failed"        # a file that cannot be trusted
            raise
        except BaseException as error:
            # a SIGTERM, a dead worker: the finished chunks are kept
            ended = "interrupted" if isinstance(error, output.Terminated) \
                else f"stopped ({output.one_line(error)})"
            raise
        finally:
            # stops the workers now (a stop acted on in this loop leaves
            # the generator suspended, its pool running)
            results.close()
            _close(writers, ended, f"{ended} after {done} of {spec.size} "
                                   f"designs")
            if bar is not None:
                bar.close()
    if store is not None:
        store.remove()          # the outputs are in place
    result = summary.as_dict()
    result["elapsed_s"] = time.perf_counter() - start
    result["inputs"] = spec.inputs()
    return result


def kept_note(store, writers) -> str:
    """What an unfinished sweep left: its outputs unchanged, its finished
    chunks in ``store`` for a rerun with --resume (or nothing kept)."""
    files = ", ".join(str(w.path) for w in writers
                      if getattr(w, "path", None))
    unchanged = f"; {files} not replaced" if files else ""
    if store is None:
        return unchanged
    return (f"{unchanged}; the finished chunks are kept in {store.path}: "
            f"the same command with --resume finishes the sweep")


def _close(writers, ended: str | None, note: str) -> None:
    """Close every writer: a finished sweep's files go in place; one
    that stopped early (``note``: how far it got) closes them with
    ``interrupted=note`` (a file writer then leaves the old file: its
    finished chunks are the store's, which the command always keeps
    beside its output; an in-memory one keeps its rows); after a write
    error all are dropped.  The first error of a writer is raised after
    the others are closed."""
    error = None
    for writer in writers:
        try:
            if ended == "failed":
                getattr(writer, "abort", writer.close)()
            elif ended is not None and hasattr(writer, "abort"):
                writer.close(interrupted=note)
                writer.partial = note
            else:
                writer.close()
        except Exception as caught:      # noqa: BLE001 - raised below
            error = error or caught
    if error is not None and ended is None:
        raise error
