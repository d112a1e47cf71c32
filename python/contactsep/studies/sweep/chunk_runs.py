"""A sweep's chunks: what a worker computes of one
(:func:`chunk_result`) and how they come back, in order, from the
backend the command chose (:func:`chunk_results`: in this process, on
local worker processes or on a Dask cluster, :mod:`contactsep.runs.
backend`); :func:`contactsep.studies.sweep.run.run_sweep` drives them
and streams the results to its writers.
"""

from __future__ import annotations

import os
import time

from contactsep.runs import dask_run
from contactsep.runs.backend import backend_for
from contactsep.runs.chunks import Chunks
from contactsep.runs.journal import chunk_file, load_columns, save_columns
from contactsep.studies.sweep import chatter as chatter_sweep
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
    short path: a backend whose results come back best as files,
    Backend.results_by_file), or "columns" (the NumPy columns
    themselves)."""
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


def chunk_results(spec, bounds: Chunks, stop, mode, threshold, store,
                  workers: int = 1, scheduler=None):
    """(kind, value, designs) of each chunk in order: kind "summary"
    (value a partial summary; ``mode`` "summary") or "columns", the
    chunks computed on the backend of ``workers`` and ``scheduler``
    (:func:`contactsep.runs.backend.backend_for`) through its one
    stream, in the chunks' order; a chunk ``store`` holds is given as
    it is, a new one kept there as it arrives."""
    summaries = mode == "summary"
    with backend_for(workers=workers, scheduler=scheduler) as backend:
        if backend.parallel:
            # the last chunks sized for the workers there are
            bounds.workers = backend.workers
        by_file = not summaries and backend.results_by_file
        task_mode = "summary" if summaries else "file" if by_file \
            else "columns"
        directory = None
        if by_file:
            # the workers save into the store
            directory = store.path if store is not None \
                else backend.scratch()
        # the spec goes to the workers once (Dask), not with every task
        shared = backend.share(spec)
        chunks = planned(bounds, store, lambda first, last: (
            shared, first, last, threshold, task_mode, directory))
        done = 0
        work = backend.stream(
            chunk_result, chunks, backend.chunk_window(summaries),
            stop=stop, advice=": try a smaller --chunk-size",
            lost=lambda where: dask_run.scheduler_lost(where, done),
            what="a chunk")
        try:
            for (first, last, stored), result in work:
                if stored is not None:
                    done += last - first
                    yield "columns", stored.value, last - first
                    continue
                value, designs, seconds = result
                bounds.record(designs, seconds)
                if by_file:
                    path, value = value, load_columns(value)
                    if store is None:
                        os.unlink(path)
                    else:
                        store.chunks[first] = last
                elif store is not None:
                    store.save(first, last, value)
                done += designs
                yield "summary" if summaries else "columns", value, designs
        finally:
            # stopped early (a signal, a writer's error, a dead worker):
            # what is left is cancelled before the backend stops its
            # workers (a design may take seconds)
            work.close()
