"""Running a sweep: chunks in order, locally or on a Dask cluster, streamed
to writers, with a progress bar on a terminal."""

from __future__ import annotations

import collections
import csv
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

from contactsep.errors import ContactsepWarning, InputError
from contactsep.output import json_text
from contactsep.studies.study import csv_comments
from contactsep.studies.sweep import (
    CHUNK_SIZE,
    Summary,
    SweepSpec,
    chunks,
    evaluate_chunk,
)


class SweepInterrupted(InputError):
    """A sweep stopped by the user; the chunks before it are written.
    The command reports it in one line and exits 130, as for Ctrl-C."""

    interrupted = True


#: The first comment line of a sweep's CSV and its Parquet metadata.
TITLE = "contactsep sweep of the general model (eq. 23) on the thesis design"
#: How to read the columns (a comment line of the CSV).
COLUMNS_NOTE = ("units in each column's name: _in inch, _s second, _lb_s "
                "lb s, _in_s in/s, _lb_in3 lb/in^3, _psi psi; status 0 = "
                "ok, 1 no impact, 2 invalid input, 3 overflow "
                "(contactsep.model.status); failed designs have nan results")
#: Significant digits of the CSV's numbers: the compiled kernel and its
#: NumPy twin agree to 1e-12 relative (tests/model), so later digits are
#: round-off; Parquet keeps every bit.
CSV_DIGITS = 12


def _row_format(columns: dict) -> str:
    """%-format of one CSV row, from the columns' kinds."""
    formats = []
    for values in columns.values():
        kind = np.asarray(values).dtype.kind
        formats.append("%d" if kind in "iub" else "%s" if kind in "USO"
                       else f"%.{CSV_DIGITS}g")
    return ",".join(formats) + "\n"


class CsvWriter:
    """Streams chunks to a CSV file: '#' lines (what the sweep is), a
    header, the rows.  The file is written as the sweep goes, so that an
    interrupted sweep keeps its finished chunks."""

    def __init__(self, path: str, spec: SweepSpec, notes=()):
        self.path = path
        self._handle = open(path, "w", newline="", encoding="ascii")
        self._handle.write(csv_comments([TITLE, *spec.describe(),
                                         COLUMNS_NOTE, *notes]))
        self._writer = csv.writer(self._handle, lineterminator="\n")
        self._line = None

    def write(self, columns: dict) -> None:
        if self._line is None:
            self._writer.writerow(list(columns))
            self._line = _row_format(columns)
        # Python's own %-formatting, row by row: numpy.char.mod is slower
        # (~15 us a row) and swallows a signal raised while it runs, so
        # Ctrl-C and SIGTERM went unheard during a long write
        rows = zip(*(np.asarray(v).tolist() for v in columns.values()))
        self._handle.writelines(self._line % row for row in rows)
        self._handle.flush()

    def close(self) -> None:
        self._handle.close()


class ParquetWriter:
    """Streams chunks to a Parquet file (needs pyarrow); the file's
    metadata key ``contactsep`` holds what the CSV's comments say, as
    JSON (``title``, ``inputs``, ``notes``)."""

    def __init__(self, path: str, spec: SweepSpec | None = None):
        try:
            import pyarrow  # noqa: F401
            import pyarrow.parquet  # noqa: F401
        except ImportError:
            raise InputError("--parquet needs pyarrow: pip install "
                             "'contactsep[tables]'") from None
        self.path = path
        self._metadata = {"contactsep": json_text({
            "title": TITLE, "notes": [COLUMNS_NOTE],
            "inputs": spec.inputs() if spec is not None else None},
            indent=None)}
        self._writer = None

    def write(self, columns: dict) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq
        table = pa.table({k: np.ascontiguousarray(v)
                          for k, v in columns.items()})
        table = table.replace_schema_metadata(self._metadata)
        if self._writer is None:
            self._writer = pq.ParquetWriter(self.path, table.schema)
        self._writer.write_table(table)

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()


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
    """A chunk's columns, listening for a stop every quarter second."""
    while True:
        stop.check()
        try:
            return future.result(timeout=0.25)
        except TimeoutError:
            continue


def _quiet_worker() -> None:
    """Ctrl-C reaches the whole process group: the workers leave it to
    the parent (which stops them between chunks) instead of printing a
    KeyboardInterrupt each.  SIGTERM ends a worker (as the pool ends the
    rest when one has died), never with the parent's handler."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _evaluate_to_file(spec, first, last, directory) -> str:
    """A worker's chunk, saved beside the parent: the message back is a
    short path, written to the pipe at once (a worker killed while it
    sent megabytes of columns would leave the pool reading the rest of
    the message forever), and no pickling of the columns."""
    columns = evaluate_chunk(spec, first, last)
    path = os.path.join(directory, f"{first}.npz")
    np.savez(path, **{k: np.ascontiguousarray(v) for k, v in columns.items()})
    return path


def _load(path: str) -> dict:
    with np.load(path) as data:
        columns = {name: data[name] for name in data.files}
    os.unlink(path)
    return columns


def _results_local(spec, bounds, workers, stop):
    if workers <= 1:
        for first, last in bounds:
            stop.check()
            yield evaluate_chunk(spec, first, last)
        return
    shared = "/dev/shm" if os.path.isdir("/dev/shm") else None
    directory = tempfile.mkdtemp(prefix="contactsep-sweep-", dir=shared)
    pool = ProcessPoolExecutor(max_workers=workers,
                               initializer=_quiet_worker)
    finished = False
    try:
        window = collections.deque()
        for first, last in bounds:
            window.append(pool.submit(_evaluate_to_file, spec, first, last,
                                      directory))
            if len(window) >= 2 * workers:
                yield _load(_wait(window.popleft(), stop))
        while window:
            yield _load(_wait(window.popleft(), stop))
        finished = True
    except BrokenProcessPool:
        stop.check()   # a SIGTERM to the whole group: the workers went first
        raise InputError("a worker process died (killed, or out of "
                         "memory: try a smaller --chunk-size)") from None
    finally:
        # stopped early (a signal, a writer's error, a dead worker): the
        # queued chunks are dropped and the running ones finished
        pool.shutdown(wait=True, cancel_futures=not finished)
        shutil.rmtree(directory, ignore_errors=True)


def _results_dask(spec, bounds, address, stop):
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--scheduler needs dask.distributed: pip install "
                         "'contactsep[scale]'") from None
    client = address if hasattr(address, "submit") else Client(address)
    try:
        window = collections.deque()
        for first, last in bounds:
            window.append(client.submit(evaluate_chunk, spec, first, last,
                                        pure=False))
            if len(window) >= 8:
                yield _wait(window.popleft(), stop)
        while window:
            yield _wait(window.popleft(), stop)
    finally:
        if client is not address:
            client.close()


def run_sweep(spec: SweepSpec, *, writers=(), threshold=None,
              chunk_size: int = CHUNK_SIZE, workers: int | None = None,
              scheduler=None, progress: bool | None = None) -> dict:
    """Evaluate every design of ``spec`` chunk by chunk, in order; each
    chunk goes to every writer as it arrives.  Returns the summary
    (:meth:`Summary.as_dict`, ``elapsed_s``, and ``inputs``: what made the
    sweep, :meth:`SweepSpec.inputs`).

    ``workers``: local processes (default: the machine's cores; 1 runs in
    this process); ``scheduler``: a Dask scheduler address (or Client).
    An interrupt (Ctrl-C) raises :class:`SweepInterrupted` after closing
    the writers: the chunks already written stay.
    """
    if chunk_size < 1:
        raise InputError("--chunk-size must be at least 1")
    if workers is None:
        workers = os.cpu_count() or 1
    bounds = chunks(spec.size, chunk_size)
    if spec.size <= chunk_size:
        workers = 1
    summary = Summary(threshold=threshold)
    bar = _progress(spec.size, progress)
    done = 0
    start = time.perf_counter()
    with _StopRequests() as stop:
        results = _results_dask(spec, bounds, scheduler, stop) \
            if scheduler else _results_local(spec, bounds, workers, stop)
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
            raise SweepInterrupted(
                f"interrupted: {done} of {spec.size} designs were evaluated "
                f"and written") from None
        finally:
            # stops the workers now (a stop acted on in this loop leaves
            # the generator suspended, its pool running)
            results.close()
            for writer in writers:
                writer.close()
            if bar is not None:
                bar.close()
    result = summary.as_dict()
    result["elapsed_s"] = time.perf_counter() - start
    result["inputs"] = spec.inputs()
    return result
