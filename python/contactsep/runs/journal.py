"""Work that survives being killed: the one journal of every resumable
command, kept beside its output in ``.NAME.resume/`` (NAME the output
file: :func:`store_path`).

A journal is a directory holding ``manifest.json`` (what made the work:
the package version, the digest of the code that computes it,
:mod:`.code_digest`, and what the caller says made it) and records of
finished work, read back by a later run of the same inputs:

- :class:`ChunkStore`, a sweep's (``contactsep sweep ... --resume``):
  one ``FIRST-LAST.npz`` per chunk of designs FIRST..LAST-1, its output
  columns.  The sweep writes its outputs afresh from the first row, and
  they do not depend on the chunking, so they are byte-identical to an
  uninterrupted run's.  The output's lock (taken by its writer) keeps a
  second command out.
- :class:`RunJournal`, a search's or a study's (``contactsep preload
  ... --csv F --resume``, ``contactsep.preload(..., journal=DIR)``):
  ``runs.jsonl``, one line per finished simulation, a digest of its
  task (:func:`~contactsep.runs.task_keys.task_key`) and its result.  A search is deterministic:
  the same inputs ask for the same simulations in the same order, so a
  rerun takes each result the journal holds instead of simulating it,
  and its answer, notes and CSV are those of an uninterrupted run.  A
  second command on the same journal is refused while the first runs
  (``.NAME.resume.lock``, held with flock).

Every file is written whole: a manifest or a chunk to a temporary name
renamed into place, a run as one line (a line cut by a SIGKILL is
dropped), so a kill at any moment leaves whole records or none.  A
journal whose manifest differs from the one wanted is refused in one
line naming what differs (:class:`ResumeError`); one without a manifest
(killed before it was written) is started afresh; a journal is removed
once the outputs are in place.  What the caller records of its inputs
is JSON data the journal only compares: the sweep's spec stays in the
sweep (:class:`contactsep.studies.sweep.run.ChunkStore`)."""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import stat
import tempfile

import numpy as np

from contactsep.errors import InputError
from contactsep.output import json_text, locks, target_info
from contactsep.output.streams import named
from contactsep.runs.task_keys import canonical

MANIFEST = "manifest.json"
_RUNS = "runs.jsonl"
_CHUNK_FILE = re.compile(r"^(\d+)-(\d+)\.npz$")


class ResumeError(InputError):
    """A --resume that cannot continue the work it finds."""


def store_path(output_path: str) -> str:
    """The journal of an output file: ``.NAME.resume`` beside it (links
    followed, as the output is)."""
    target = os.path.realpath(output_path)
    directory, name = os.path.split(target)
    return os.path.join(directory, f".{name}.resume")


def regular_or_new(path) -> bool:
    """Whether ``path`` is a regular file or none yet (a device or FIFO
    output has no folder beside it for a journal)."""
    info = target_info(os.fspath(path))
    return info is None or stat.S_ISREG(info.st_mode)


def manifest(layers, about: dict) -> dict:
    """A journal's manifest: the package version (another version may
    compute other digits), the digest of the code of ``layers`` (an
    edited development install too: :mod:`.code_digest`), then
    ``about``, what the caller says made the work."""
    from contactsep import __version__
    from contactsep.runs import code_digest
    return {"contactsep": __version__,
            "code_sha256": code_digest.code_digest(layers), **about}


def differences(old: dict, new: dict, prefix: str = "") -> list:
    """The dotted keys at which ``old`` and ``new`` differ, sorted."""
    keys = sorted(set(old) | set(new))
    out = []
    for key in keys:
        a, b = old.get(key), new.get(key)
        if isinstance(a, dict) and isinstance(b, dict):
            out += differences(a, b, f"{prefix}{key}.")
        elif a != b:
            out.append(f"{prefix}{key}")
    return out


def same_inputs(directory: str, wanted: dict, what: str,
                advice: str = "rerun without --resume") -> bool:
    """Whether ``directory`` holds a manifest.json equal to ``wanted``
    (False: none, or one a kill cut short: start afresh); one of other
    inputs is refused (:class:`ResumeError`, one line naming what
    differs: ``--resume: the unfinished {what} was made with other
    inputs (...); {advice} to start afresh``)."""
    if not os.path.isdir(directory):
        return False
    try:
        with open(os.path.join(directory, MANIFEST),
                  encoding="utf-8") as handle:
            found = json.load(handle)
    except (OSError, ValueError):
        return False            # killed before its manifest: afresh
    if found != wanted:
        differ = differences(found, wanted) or ["the manifest"]
        raise ResumeError(
            f"--resume: the unfinished {what} was made with other inputs "
            f"({', '.join(differ[:4])} "
            f"{'differs' if len(differ) == 1 else 'differ'}); {advice} to "
            f"start afresh")
    return True


def atomic_write(path: str, write) -> None:
    """``write(handle)`` into a temporary file beside ``path``, renamed
    into place once whole (removed on any error)."""
    directory, name = os.path.split(path)
    fd, temp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp",
                                dir=directory)
    try:
        with os.fdopen(fd, "wb") as handle:
            write(handle)
        os.replace(temp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temp)
        raise


def chunk_file(directory: str, first: int, last: int) -> str:
    """The file of the chunk of designs first..last-1 in ``directory``."""
    return os.path.join(directory, f"{first:012d}-{last:012d}.npz")


def save_columns(path: str, columns: dict) -> None:
    """A chunk's columns to ``path`` (.npz), atomically."""
    atomic_write(path, lambda handle: np.savez(
        handle, **{k: np.ascontiguousarray(v) for k, v in columns.items()}))


def load_columns(path: str) -> dict:
    with np.load(path) as data:
        return {name: data[name] for name in data.files}


def _result_json(result):
    """A result as JSON data (a tuple as a list, NumPy scalars as Python
    numbers)."""
    if isinstance(result, (list, tuple)):
        return [_result_json(item) for item in result]
    if isinstance(result, np.generic):
        return result.item()
    return result


def _result_value(data):
    """A result read back: lists as tuples, as the workers return them."""
    if isinstance(data, list):
        return tuple(_result_value(item) for item in data)
    return data


class Journal:
    """The directory ``path`` of a resumable command's finished work
    (module docstring), for its subclasses' records.

    ``wanted``: its manifest (:func:`manifest`).  With ``resume`` a
    journal found with the same manifest is continued
    (:meth:`_continue`, its records read), one with another is refused
    (:class:`ResumeError`, naming ``what`` and what differs, then
    ``advice``); else, or where none is found, or where nothing was
    continued, it is started afresh (emptied, its manifest written).
    ``lock``: the label of the journal's own lock (``PATH.lock``, held
    until :meth:`close`), or None where the output's lock covers it."""

    def __init__(self, path, wanted: dict, what: str, *,
                 advice: str = "rerun without --resume",
                 resume: bool = True, lock: str | None = None) -> None:
        self.path = os.fspath(path)
        self._lock = None
        if lock is not None:
            self._lock = locks.take(self.path.rstrip(os.sep) + ".lock",
                                    lock)
        try:
            found = resume and same_inputs(self.path, wanted, what, advice)
            if not (found and self._continue()):
                shutil.rmtree(self.path, ignore_errors=True)
                os.makedirs(self.path, exist_ok=True)
                atomic_write(os.path.join(self.path, MANIFEST),
                             lambda handle: handle.write(
                                 json_text(wanted).encode("utf-8")))
        except BaseException:
            self.close()
            raise

    def _continue(self) -> bool:
        """Read the records of a journal of the same manifest; whether
        there is one to continue (False: start afresh)."""
        return True

    def close(self) -> None:
        """Release the lock (the journal stays)."""
        if self._lock is not None:
            locks.release(self._lock)
            self._lock = None

    def remove(self) -> None:
        """The work is finished and its outputs in place: delete the
        journal."""
        self.close()
        shutil.rmtree(self.path, ignore_errors=True)


class ChunkStore(Journal):
    """The finished chunks of a resumable sweep (module docstring), in
    the journal beside ``output_path``: ``about``, what the sweep
    records of its spec in the manifest (beside the digest of the code
    of the studies and the layers below), ``size`` its designs.

    ``resume`` True: a journal left by an earlier run of the same inputs
    is continued (other inputs: :class:`ResumeError`, one line naming
    what differs); False: it is started afresh."""

    def __init__(self, output_path: str, about: dict, size: int,
                 resume: bool = True) -> None:
        from contactsep.runs.code_digest import STUDIES
        self.label = output_path
        self.size = size
        self.chunks = {}
        path = store_path(output_path)
        super().__init__(path, manifest(STUDIES, about),
                         f"sweep beside {output_path} "
                         f"({os.path.basename(path)})", resume=resume)

    def _continue(self) -> bool:
        self.chunks = self._scan(self.size)
        return bool(self.chunks)

    def _scan(self, size: int) -> dict:
        """first -> last of the whole chunk files found, in order, none
        overlapping an earlier one (a temporary file is dropped)."""
        found = []
        for name in os.listdir(self.path):
            match = _CHUNK_FILE.match(name)
            if match:
                found.append((int(match.group(1)), int(match.group(2))))
            elif name.endswith(".tmp"):
                with contextlib.suppress(OSError):
                    os.unlink(os.path.join(self.path, name))
        chunks, end = {}, 0
        for first, last in sorted(found):
            if first >= end and first < last <= size:
                chunks[first] = last
                end = last
        return chunks

    def file(self, first: int, last: int) -> str:
        return chunk_file(self.path, first, last)

    @property
    def designs(self) -> int:
        """Designs already computed."""
        return sum(last - first for first, last in self.chunks.items())

    def load(self, first: int) -> dict:
        """The stored chunk starting at design ``first``."""
        return load_columns(self.file(first, self.chunks[first]))

    def save(self, first: int, last: int, columns: dict) -> None:
        save_columns(self.file(first, last), columns)
        self.chunks[first] = last


class RunJournal(Journal):
    """The finished simulations of one search, in the directory ``path``
    (module docstring).

    ``inputs``: what made the search (JSON data): a journal found at
    ``path`` with the same inputs is continued, one with other inputs is
    refused (:class:`ResumeError`, naming what differs); none, or one
    killed before its manifest, is started afresh.  ``label``: the path
    as messages name it.  Close it (:meth:`close`, or use it as a
    context manager) to release the lock; :meth:`remove` deletes it
    once the answer is saved."""

    def __init__(self, path: str | os.PathLike, inputs: dict,
                 label: str | None = None) -> None:
        from contactsep.runs.code_digest import SIMULATION
        self.label = label or os.fspath(path)
        self.results: dict = {}
        #: Results this run took from the journal, and recorded itself.
        self.reused = 0
        self.recorded = 0
        self._file = None
        wanted = manifest(SIMULATION, {"inputs": canonical(inputs)})
        try:
            super().__init__(path, wanted, f"search in {self.label}",
                             advice="rerun without --resume, or remove "
                                    "it,", lock=self.label)
        except OSError as error:
            raise named(error, self.label) from None
        runs = os.path.join(self.path, _RUNS)
        try:
            self._file = open(runs, "a", encoding="ascii", newline="\n",
                              buffering=1)
            # a line cut by a kill: the next one starts on its own line
            if self._file.tell() and not self._ends_in_newline(runs):
                self._file.write("\n")
        except OSError as error:
            self.close()
            raise named(error, self.label) from None

    def _continue(self) -> bool:
        """The whole lines of runs.jsonl (a cut or garbled one is
        dropped: its simulation runs again)."""
        with contextlib.suppress(FileNotFoundError), \
                open(os.path.join(self.path, _RUNS), "rb") as handle:
            for line in handle:
                try:
                    record = json.loads(line)
                    key, result = record["key"], record["result"]
                except (ValueError, KeyError, TypeError):
                    continue
                if isinstance(key, str):
                    self.results[key] = _result_value(result)
        return True

    @staticmethod
    def _ends_in_newline(path: str) -> bool:
        with open(path, "rb") as handle:
            handle.seek(-1, os.SEEK_END)
            return handle.read(1) == b"\n"

    def __len__(self) -> int:
        return len(self.results)

    def __enter__(self) -> "RunJournal":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def lookup(self, key: str) -> tuple[bool, object]:
        """(found, result) of the simulation ``key`` names."""
        if key in self.results:
            return True, self.results[key]
        return False, None

    def record(self, key: str, result) -> None:
        """One finished simulation, written as one whole line now."""
        data = _result_json(result)
        try:
            line = json.dumps({"key": key, "result": data},
                              allow_nan=False)
        except (TypeError, ValueError):
            return          # not strict JSON: the task runs again
        self._file.write(line + "\n")
        self.results[key] = _result_value(data)
        self.recorded += 1

    def close(self) -> None:
        """Close the file and release the lock (the journal stays)."""
        if self._file is not None:
            with contextlib.suppress(OSError):
                self._file.close()
            self._file = None
        super().close()
