"""Running a sweep: its options checked, its chunks' results (computed
locally or on a Dask cluster: :mod:`contactsep.studies.sweep.chunk_runs`)
streamed in order to writers, with a progress bar on a terminal, and its
writers closed however it ends."""

from __future__ import annotations

import math
import time

from contactsep import output
from contactsep.errors import InputError
from contactsep.model.evaluate import costly
from contactsep.studies.sweep import chatter as chatter_sweep
from contactsep.studies.sweep.chunk_runs import chunk_results, new_summary
from contactsep.runs.chunks import Chunks
from contactsep.runs.pool import WORKERS_PER_CORE, max_workers, usable_cores
from contactsep.runs import journal
from contactsep.runs.stops import StopRequests, progress_bar
from contactsep.studies.sweep.spec import CHUNK_SIZE, MAX_CHUNK_SIZE, SweepSpec


class SweepInterrupted(InputError):
    """A sweep stopped by the user; its outputs are left as they were,
    the chunks it finished are in its store (if it had one).  The
    command reports it in one line and exits 130, as for Ctrl-C."""

    interrupted = True


class ChunkStore(journal.ChunkStore):
    """The finished chunks of a resumable sweep of ``spec`` beside
    ``output_path`` (:class:`contactsep.runs.journal.ChunkStore`): its
    manifest records the sweep's model and inputs
    (:meth:`SweepSpec.inputs`), which the journal only compares."""

    def __init__(self, output_path: str, spec: SweepSpec,
                 resume: bool = True) -> None:
        super().__init__(output_path, {"model": spec.model,
                                       "inputs": spec.inputs()},
                         spec.size, resume=resume)


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
    <contactsep.studies.sweep.chatter.ChatterSummary.as_dict>` for a
    chatter model; ``elapsed_s``; and ``inputs``: what made the sweep,
    :meth:`SweepSpec.inputs`).

    ``chunk_size``: the most designs a chunk has (default
    :func:`default_chunk_size`; chunks are sized by cost below it:
    :class:`~contactsep.runs.chunks.Chunks`); ``threshold`` (in, eq23
    only): also report P(max y3 > threshold);
    ``workers``: local processes (default: the usable cores; 1 runs in
    this process; at most WORKERS_PER_CORE a core); ``scheduler``: a Dask
    scheduler address (or Client).  A sweep that does not finish (an
    interrupt, Ctrl-C or SIGTERM: :class:`SweepInterrupted`, SIGTERM the
    command's own exception; a dead worker; any other error) drops the
    writers' files (:meth:`CsvWriter.abort
    <contactsep.studies.sweep.writers.CsvWriter.abort>`: the old file, or
    none, stays under the final name); what it finished is in ``store``.
    ``store``: a :class:`ChunkStore` that
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
    summary = new_summary(spec, threshold)
    mode = "columns" if writers or store is not None else "summary"
    bar = progress_bar(spec.size, progress)
    done = 0
    start = time.perf_counter()
    with StopRequests() as stop, output.stop_checks(stop.check):
        results = chunk_results(spec, bounds, stop, mode, threshold, store,
                                workers=workers, scheduler=scheduler)
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
