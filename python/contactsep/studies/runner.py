"""Running a sweep: chunks in order, locally or on a Dask cluster, streamed
to writers, with a progress bar on a terminal."""

from __future__ import annotations

import csv
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from contactsep.errors import InputError
from contactsep.studies.sweep import (CHUNK_SIZE, Summary, SweepSpec, chunks,
                                      evaluate_chunk)


class SweepInterrupted(InputError):
    """A sweep stopped by the user; the chunks before it are written."""


class CsvWriter:
    """Streams chunks to a CSV file: '#' lines, a header, the rows."""

    def __init__(self, path: str, spec: SweepSpec, notes=()):
        self.path = path
        self._handle = open(path, "w", newline="", encoding="ascii")
        self._handle.write("# contactsep sweep of the general model "
                           "(eq. 23) on the thesis design\n")
        for name, values in spec.vary:
            self._handle.write(f"# vary {name}: {len(values)} values from "
                               f"{values[0]:.12g} to {values[-1]:.12g}\n")
        for name, kind, a, b in spec.sample:
            self._handle.write(f"# sample {name} ~ {kind}({a:.12g}, "
                               f"{b:.12g}), seed {spec.seed}\n")
        for key, value in spec.base.items():
            self._handle.write(f"# fixed {key} = {value}\n")
        for note in notes:
            self._handle.write(f"# {note}\n")
        self._writer = csv.writer(self._handle, lineterminator="\n")
        self._header = False

    def write(self, columns: dict) -> None:
        if not self._header:
            self._writer.writerow(list(columns))
            self._header = True
        formatted = [np.char.mod("%.17g", np.asarray(v, dtype=float))
                     if k != "status" else np.asarray(v).astype(str)
                     for k, v in columns.items()]
        self._writer.writerows(zip(*formatted))
        self._handle.flush()

    def close(self) -> None:
        self._handle.close()


class ParquetWriter:
    """Streams chunks to a Parquet file (needs pyarrow)."""

    def __init__(self, path: str):
        try:
            import pyarrow  # noqa: F401
            import pyarrow.parquet  # noqa: F401
        except ImportError:
            raise InputError("--parquet needs pyarrow: pip install "
                             "'contactsep[tables]'") from None
        self.path = path
        self._writer = None

    def write(self, columns: dict) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq
        table = pa.table({k: np.ascontiguousarray(v)
                          for k, v in columns.items()})
        if self._writer is None:
            self._writer = pq.ParquetWriter(self.path, table.schema)
        self._writer.write_table(table)

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()


def _progress(total: int, enabled: bool | None):
    """A tqdm bar on a terminal (stderr), or nothing."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    # shown only once the run has taken a second
    return tqdm(total=total, unit="design", unit_scale=True, delay=1.0,
                file=sys.stderr)


def _results_local(spec, bounds, workers):
    if workers <= 1:
        for first, last in bounds:
            yield evaluate_chunk(spec, first, last)
        return
    with ProcessPoolExecutor(max_workers=workers) as pool:
        window = []
        for first, last in bounds:
            window.append(pool.submit(evaluate_chunk, spec, first, last))
            if len(window) >= 2 * workers:
                yield window.pop(0).result()
        for future in window:
            yield future.result()


def _results_dask(spec, bounds, address):
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--scheduler needs dask.distributed: pip install "
                         "'contactsep[scale]'") from None
    client = address if hasattr(address, "submit") else Client(address)
    try:
        window = []
        for first, last in bounds:
            window.append(client.submit(evaluate_chunk, spec, first, last,
                                        pure=False))
            if len(window) >= 8:
                yield window.pop(0).result()
        for future in window:
            yield future.result()
    finally:
        if client is not address:
            client.close()


def run_sweep(spec: SweepSpec, *, writers=(), threshold=None,
              chunk_size: int = CHUNK_SIZE, workers: int | None = None,
              scheduler=None, progress: bool | None = None) -> dict:
    """Evaluate every design of ``spec`` chunk by chunk, in order; each
    chunk goes to every writer as it arrives.  Returns the summary.

    ``workers``: local processes (default: the machine's cores; 1 runs in
    this process); ``scheduler``: a Dask scheduler address (or Client).
    An interrupt (Ctrl-C) raises :class:`SweepInterrupted` after closing
    the writers: the chunks already written stay.
    """
    if chunk_size < 1:
        raise InputError("--chunk-size must be at least 1")
    if workers is None:
        workers = os.cpu_count() or 1
    bounds = list(chunks(spec.size, chunk_size))
    if len(bounds) == 1:
        workers = 1
    summary = Summary(threshold=threshold)
    bar = _progress(spec.size, progress)
    done = 0
    start = time.perf_counter()
    try:
        results = _results_dask(spec, bounds, scheduler) if scheduler \
            else _results_local(spec, bounds, workers)
        for columns in results:
            for writer in writers:
                writer.write(columns)
            summary.add(columns)
            done += len(columns["status"])
            if bar is not None:
                bar.update(len(columns["status"]))
    except KeyboardInterrupt:
        raise SweepInterrupted(
            f"interrupted: {done} of {spec.size} designs were evaluated and "
            f"written") from None
    finally:
        for writer in writers:
            writer.close()
        if bar is not None:
            bar.close()
    result = summary.as_dict()
    result["seconds"] = time.perf_counter() - start
    return result
