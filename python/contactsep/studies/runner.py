"""Running a sweep: chunks in order, locally or on a Dask cluster, streamed
to writers, with a progress bar on a terminal."""

from __future__ import annotations

import collections
import math
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
import warnings
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

import numpy as np

from contactsep import output
from contactsep.errors import ContactsepWarning, InputError
from contactsep.model.evaluate import costly
from contactsep.studies import chatter_sweep
from contactsep.studies.sweep import (
    CHUNK_SIZE,
    MAX_CHUNK_SIZE,
    Chunks,
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
    """A sweep stopped by the user; the chunks before it are written.
    The command reports it in one line and exits 130, as for Ctrl-C."""

    interrupted = True


def _progress(total: int, enabled: bool | None):
    """A tqdm bar on a terminal (stderr), or nothing.  Asked for
    (``enabled`` True) without tqdm installed: a warning says so."""
    if enabled is None:
        enabled = sys.stderr.isatty()
        required = False
    else:
        required = enabled
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        if required:
            warnings.warn("no progress bar: it needs tqdm (pip install "
                          "'contactsep[progress]')", ContactsepWarning)
        return None
    # shown only once the run has taken a second
    return tqdm(total=total, unit="design", unit_scale=True, delay=1.0,
                file=sys.stderr)


class _StopRequests:
    """SIGINT and SIGTERM during a sweep only note the request; the sweep
    acts on it between chunks and while it waits for one.  An exception
    raised by a handler anywhere else (inside the process pool's own
    code, holding its locks) could deadlock the pool's shutdown."""

    def __init__(self) -> None:
        self.signum = None
        self._previous = {}

    def __enter__(self) -> "_StopRequests":
        if threading.current_thread() is threading.main_thread():
            for signum in (signal.SIGINT, signal.SIGTERM):
                previous = signal.getsignal(signum)
                if previous not in (signal.SIG_IGN, None):
                    self._previous[signum] = previous
                    signal.signal(signum, self._note)
        return self

    def _note(self, signum, frame) -> None:
        if self.signum is None:
            self.signum = signum

    def check(self) -> None:
        """Act on a noted signal: its own handler runs now, here (Ctrl-C
        raises KeyboardInterrupt; the command's SIGTERM handler raises
        its exception; a default SIGTERM ends the process)."""
        if self.signum is not None:
            self.__exit__()
            signal.raise_signal(self.signum)

    def __exit__(self, *exc) -> None:
        for signum, previous in self._previous.items():
            signal.signal(signum, previous)
        self._previous = {}


def _wait(future, stop: _StopRequests):
    """A chunk's columns, listening for a stop every quarter second (a
    chunk that failed because the same Ctrl-C ended it: the stop)."""
    while True:
        stop.check()
        try:
            return future.result(timeout=0.25)
        except TimeoutError:
            continue
        except BaseException:
            stop.check()
            raise


def _quiet_worker() -> None:
    """Ctrl-C reaches the whole process group: the workers leave it to
    the parent (which stops them between chunks) instead of printing a
    KeyboardInterrupt each.  SIGTERM ends a worker (as the pool ends the
    rest when one has died), never with the parent's handler."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


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


def _evaluate_to_file(spec, first, last, directory) -> tuple[str, float]:
    """A worker's chunk, saved beside the parent: the message back is a
    short path, written to the pipe at once (a worker killed while it
    sent megabytes of columns would leave the pool reading the rest of
    the message forever), and no pickling of the columns."""
    columns, seconds = evaluate_chunk_timed(spec, first, last)
    path = os.path.join(directory, f"{first}.npz")
    np.savez(path, **{k: np.ascontiguousarray(v) for k, v in columns.items()})
    return path, seconds


def _load(path: str) -> dict:
    with np.load(path) as data:
        columns = {name: data[name] for name in data.files}
    os.unlink(path)
    return columns


def _results_local(spec, bounds: Chunks, workers, stop):
    if workers <= 1:
        for first, last in bounds:
            stop.check()
            columns, seconds = evaluate_chunk_timed(spec, first, last)
            bounds.record(last - first, seconds)
            yield columns
        return
    shared = "/dev/shm" if os.path.isdir("/dev/shm") else None
    directory = tempfile.mkdtemp(prefix="contactsep-sweep-", dir=shared)
    pool = ProcessPoolExecutor(max_workers=workers,
                               initializer=_quiet_worker)
    finished = started = False

    def result(future):
        path, seconds = _wait(future, stop)
        columns = _load(path)
        bounds.record(len(columns["status"]), seconds)
        return columns

    try:
        window = collections.deque()
        for first, last in bounds:
            window.append(pool.submit(_evaluate_to_file, spec, first, last,
                                      directory))
            started = True
            if len(window) >= 2 * workers:
                yield result(window.popleft())
        while window:
            yield result(window.popleft())
        finished = True
    except BrokenProcessPool:
        stop.check()   # a SIGTERM to the whole group: the workers went first
        raise InputError("a worker process died (killed, or out of "
                         "memory: try a smaller --chunk-size)") from None
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
        if not finished:
            # stopped early (a signal, a writer's error, a dead worker,
            # a pool that could not start): the chunks still running are
            # dropped, so their workers are stopped now rather than
            # waited for (a design may take seconds).  Killed, not
            # terminated: a SIGTERM can reach one before its initializer,
            # while it still has this process's handlers
            for process in list((getattr(pool, "_processes", None)
                                 or {}).values()):
                process.kill()
        pool.shutdown(wait=started, cancel_futures=not finished)
        shutil.rmtree(directory, ignore_errors=True)


def _results_dask(spec, bounds: Chunks, address, stop):
    client = address if hasattr(address, "submit") else connect(address)
    try:
        window = collections.deque()
        for first, last in bounds:
            window.append(client.submit(evaluate_chunk_timed, spec, first,
                                        last, pure=False))
            if len(window) >= 8:
                columns, seconds = _wait(window.popleft(), stop)
                bounds.record(len(columns["status"]), seconds)
                yield columns
        while window:
            columns, seconds = _wait(window.popleft(), stop)
            bounds.record(len(columns["status"]), seconds)
            yield columns
    finally:
        if client is not address:
            client.close()


#: Seconds to wait for a Dask scheduler to answer.
SCHEDULER_TIMEOUT_S = 10


def connect(address: str):
    """A Client of the scheduler at ``address``; an address Dask cannot
    read, or a scheduler that does not answer, is one InputError."""
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--scheduler needs dask.distributed: pip install "
                         "'contactsep[scale]'") from None
    try:
        return Client(address, timeout=SCHEDULER_TIMEOUT_S)
    except (ValueError, TypeError) as error:
        raise InputError(f"--scheduler: found {address!r}, expected a "
                         f"scheduler address such as tcp://HOST:8786 "
                         f"({error})") from None
    except (OSError, TimeoutError) as error:
        raise InputError(f"--scheduler {address}: no scheduler answered "
                         f"within {SCHEDULER_TIMEOUT_S} s "
                         f"({error})") from None


def usable_cores() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:      # not on Linux
        return os.cpu_count() or 1


#: Most local worker processes per usable core: more only costs memory
#: (each holds the kernel and a chunk).
WORKERS_PER_CORE = 4


def max_workers() -> int:
    return WORKERS_PER_CORE * usable_cores()


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
              scheduler=None, progress: bool | None = None) -> dict:
    """Evaluate every design of ``spec`` chunk by chunk, in order; each
    chunk goes to every writer as it arrives.  Returns the summary
    (:meth:`Summary.as_dict`, or :meth:`ChatterSummary.as_dict
    <contactsep.studies.chatter_sweep.ChatterSummary.as_dict>` for a
    chatter model; ``elapsed_s``; and ``inputs``: what made the sweep,
    :meth:`SweepSpec.inputs`).

    ``chunk_size``: the most designs a chunk has (default
    :func:`default_chunk_size`; chunks are sized by cost below it:
    :class:`~contactsep.studies.sweep.Chunks`); ``threshold`` (in, eq23
    only): also report P(max y3 > threshold);
    ``workers``: local processes (default: the usable cores; 1 runs in
    this process; at most WORKERS_PER_CORE a core); ``scheduler``: a Dask
    scheduler address (or Client).  An interrupt (Ctrl-C, SIGTERM)
    closes the writers with the chunks already written, then raises
    :class:`SweepInterrupted` (SIGTERM: the command's own exception); any
    other error drops the writers' files (:meth:`CsvWriter.abort`).
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
                    or costly(spec.max_modes, spec.max_tau))
    if spec.size <= bounds.next:
        workers = 1
    summary = Summary(threshold=threshold) if spec.model == "eq23" \
        else chatter_sweep.ChatterSummary()
    bar = _progress(spec.size, progress)
    done = 0
    start = time.perf_counter()
    with _StopRequests() as stop, output.stop_checks(stop.check):
        results = _results_dask(spec, bounds, scheduler, stop) \
            if scheduler else _results_local(spec, bounds, workers, stop)
        ended = None
        try:
            for columns in results:
                for writer in writers:
                    writer.write(columns)
                summary.add(columns)
                done += len(columns["status"])
                if bar is not None:
                    bar.update(len(columns["status"]))
                stop.check()
        except KeyboardInterrupt:
            ended = "interrupted"
            raise SweepInterrupted(
                f"interrupted: {done} of {spec.size} designs were evaluated "
                f"and written") from None
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
    result = summary.as_dict()
    result["elapsed_s"] = time.perf_counter() - start
    result["inputs"] = spec.inputs()
    return result


def _close(writers, ended: str | None, note: str) -> None:
    """Put every writer's file in place (a sweep that stopped early with
    ``note`` as its last comment: its finished chunks are kept), or drop
    them all after a write error; the first error of a writer is raised
    after the others are closed."""
    error = None
    for writer in writers:
        try:
            if ended == "failed":
                getattr(writer, "abort", writer.close)()
            elif ended is not None and hasattr(writer, "abort"):
                writer.close(interrupted=note)
            else:
                writer.close()
        except Exception as caught:      # noqa: BLE001 - raised below
            error = error or caught
    if error is not None and ended is None:
        raise error
