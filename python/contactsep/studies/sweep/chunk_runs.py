"""Where a sweep's chunks are computed and how they come back, in order:
in this process, on a local worker pool (restarted where a worker
dies), or on a Dask cluster; :func:`contactsep.studies.sweep.run.run_sweep`
drives them and streams the results to its writers.
"""

from __future__ import annotations

import os
import shutil
import tempfile
import time

from contactsep.errors import InputError
from contactsep.runs import dask_map, dask_run
from contactsep.studies.sweep import chatter as chatter_sweep
from contactsep.runs.chunks import Chunks
from contactsep.runs.dask_run import connect
from contactsep.runs.pool import RestartingPool, stream
from contactsep.runs.journal import chunk_file, load_columns, save_columns
from contactsep.studies.sweep.spec import Summary, SweepSpec, evaluate_chunk


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


def new_summary(spec: SweepSpec, threshold):
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
        summary = new_summary(spec, threshold)
        summary.add(columns)
        return summary, last - first, seconds
    if mode == "file":
        path = chunk_file(directory, first, last)
        save_columns(path, columns)
        return path, last - first, seconds
    return columns, last - first, seconds


def chunk_result_on_dask(spec, first, last, threshold, mode):
    """:func:`chunk_result` on a Dask worker, its malloc set back to
    glibc's own thresholds first (dask_run.heap_as_glibc_default)."""
    dask_run.heap_as_glibc_default()
    return chunk_result(spec, first, last, threshold, mode)


class Done:
    """A chunk that needs no work (stored by an earlier run)."""

    def __init__(self, value) -> None:
        self.value = value


def planned(bounds: Chunks, store, args):
    """A sweep stream's items (a local or Dask ``stream``'s): ((first,
    last, Done or None), ``args(first, last)`` or None) of each chunk
    in order, a chunk the store holds loaded as it is taken."""
    for first, last, stored in bounds.plan():
        if stored:
            yield (first, last, Done(store.load(first))), None
        else:
            yield (first, last, None), args(first, last)


def results_local(spec, bounds: Chunks, workers, stop, mode, threshold,
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
    pool = RestartingPool(workers)
    finished = False
    task_mode = "summary" if mode == "summary" else "file"
    chunks = planned(bounds, store, lambda first, last: (
        spec, first, last, threshold, task_mode, directory))
    work = stream(pool, chunk_result, chunks, 2 * workers, stop=stop,
                  advice=": try a smaller --chunk-size")
    try:
        for (first, last, stored), result in work:
            if stored is not None:
                yield "columns", stored.value, last - first
                continue
            value, designs, seconds = result
            bounds.record(designs, seconds)
            if task_mode == "summary":
                yield "summary", value, designs
                continue
            columns = load_columns(value)
            if store is None:
                os.unlink(value)
            else:
                store.chunks[first] = last
            yield "columns", columns, designs
        finished = True
    except OSError as error:
        if pool.started:
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
        work.close()
        pool.stop(finished, wait=pool.started)
        if store is None:
            shutil.rmtree(directory, ignore_errors=True)


#: Chunks in flight per Dask worker thread when only summaries come back.
DASK_WINDOW_PER_WORKER = 4


def results_dask(spec, bounds: Chunks, address, stop, mode, threshold,
                  store):
    """As :func:`results_local`, the chunks on a Dask cluster
    (contactsep.runs.dask_run), through the one Dask loop
    (:func:`contactsep.runs.dask_map.stream`, in the chunks' order).

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
    done = 0
    # the spec goes to the workers once, not with every task
    try:
        shared = client.scatter(spec, broadcast=True, hash=False)
    except Exception:        # noqa: BLE001 - a client without scatter
        shared = spec

    chunks = planned(bounds, store, lambda first, last: (
        shared, first, last, threshold, task_mode))
    window = DASK_WINDOW_PER_WORKER * bounds.workers + 2
    if task_mode == "columns":
        # columns wait in the parent until their turn: fewer of them
        window = 2 * bounds.workers + 2
    try:
        for (first, last, stored), result in dask_map.stream(
                client, chunk_result_on_dask, chunks, window,
                lambda where: dask_run.scheduler_lost(where, done),
                stop=stop, what="a chunk"):
            if stored is not None:
                done += last - first
                yield "columns", stored.value, last - first
                continue
            value, designs, seconds = result
            bounds.record(designs, seconds)
            if store is not None:
                store.save(first, last, value)
            done += designs
            yield task_mode, value, designs
    finally:
        if client is not address:
            client.close()
