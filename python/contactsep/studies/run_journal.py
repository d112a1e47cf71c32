"""Searches that survive being killed (``contactsep preload ... --csv F
--resume``, ``contactsep.preload(..., journal=DIR)``): every finished
simulation kept beside the output, so that a rerun computes only the
ones missing.

A preload search (the nominal search, its repeat at 2N, the convergence
checks, the perturbed and the robust searches) is deterministic: the
same inputs ask for the same simulations in the same order, and each
simulation gives the same result whatever process runs it.  The journal,
a directory (``.NAME.resume/`` beside the --csv file), holds
``manifest.json`` (what made the search: its inputs, the package version
and the digest of the simulation code,
:mod:`~contactsep.runs.code_digest`) and ``runs.jsonl``, one line per
finished simulation: a digest of its task (the function, the design, the
model, every setting, the preload) and its result; a named task
(:mod:`~contactsep.studies.preload.runs`) is digested as the plain tuple
it replaced, and the code digest reads the simulation layers only, so a
journal kept before the tasks were named is still answered from.  A
line is written whole as its simulation ends, so a SIGKILL at any moment
can cut only the last line, which is then dropped.  Rerun on the same journal, the
search takes each result the journal holds instead of simulating it, and
its answer, notes and CSV are those of an uninterrupted run.  A journal
made with other inputs is refused in one line; a second command on the
same journal is refused while the first runs (``.NAME.resume.lock``,
held with flock).
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import os
import shutil

import numpy as np

from contactsep.output import json_text, locks
from contactsep.output.streams import named
from contactsep.studies.resume import atomic_write, same_inputs

_MANIFEST = "manifest.json"
_RUNS = "runs.jsonl"


def canonical(value):
    """``value`` as plain JSON data, the same for equal inputs: a
    dataclass (a Design) as its class name and fields, a dict by sorted
    keys, a NumPy scalar or array as Python numbers (floats keep every
    digit: ``json`` writes their shortest exact repr)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {"__class__": type(value).__name__,
                **{field.name: canonical(getattr(value, field.name))
                   for field in dataclasses.fields(value)}}
    if isinstance(value, dict):
        return {str(key): canonical(item)
                for key, item in sorted(value.items(),
                                        key=lambda pair: str(pair[0]))}
    if isinstance(value, (list, tuple)):
        return [canonical(item) for item in value]
    if isinstance(value, np.ndarray):
        return {"__array__": str(value.dtype),
                "values": canonical(value.tolist())}
    if isinstance(value, np.generic):
        return value.item()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    # an unforeseen type: its repr (at worst a miss, a rerun of the task)
    return {"__repr__": type(value).__qualname__, "text": repr(value)}


def task_key(function, task) -> str:
    """The digest that names one simulation: ``function`` (by module and
    name) applied to ``task``; a task with a ``key_tuple()`` (a
    :class:`~contactsep.studies.preload.runs.PreloadRun`) by that tuple,
    so that its key is the one its plain tuple had."""
    if callable(getattr(task, "key_tuple", None)):
        task = task.key_tuple()
    text = json.dumps([f"{function.__module__}.{function.__qualname__}",
                       canonical(task)], sort_keys=True,
                      separators=(",", ":"), allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


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


class RunJournal:
    """The finished simulations of one search, in the directory ``path``
    (module docstring).

    ``inputs``: what made the search (JSON data): a journal found at
    ``path`` with the same inputs is continued, one with other inputs is
    refused (:class:`~contactsep.studies.resume.ResumeError`, naming
    what differs); none, or one killed before its manifest, is started
    afresh.  ``label``: the path as messages name it.  Close it
    (:meth:`close`, or use it as a context manager) to release the lock;
    :meth:`remove` deletes it once the answer is saved."""

    def __init__(self, path: str | os.PathLike, inputs: dict,
                 label: str | None = None) -> None:
        from contactsep import __version__
        from contactsep.runs.code_digest import code_digest
        self.path = os.fspath(path)
        self.label = label or self.path
        self.results: dict = {}
        #: Results this run took from the journal, and recorded itself.
        self.reused = 0
        self.recorded = 0
        self._file = None
        wanted = {"contactsep": __version__, "code_sha256": code_digest(),
                  "inputs": canonical(inputs)}
        self._lock = locks.take(self.path.rstrip(os.sep) + ".lock",
                                self.label)
        try:
            self._open(wanted)
        except BaseException:
            self.close()
            raise

    def _open(self, wanted: dict) -> None:
        manifest = os.path.join(self.path, _MANIFEST)
        found = same_inputs(self.path, wanted, f"search in {self.label}",
                            "rerun without --resume, or remove it,")
        try:
            if not found:
                shutil.rmtree(self.path, ignore_errors=True)
                os.makedirs(self.path, exist_ok=True)
                atomic_write(manifest, lambda handle: handle.write(
                    json_text(wanted).encode("utf-8")))
            else:
                self._read()
            runs = os.path.join(self.path, _RUNS)
            self._file = open(runs, "a", encoding="ascii", newline="\n",
                              buffering=1)
            # a line cut by a kill: the next one starts on its own line
            if self._file.tell() and not self._ends_in_newline(runs):
                self._file.write("\n")
        except OSError as error:
            raise named(error, self.label) from None

    @staticmethod
    def _ends_in_newline(path: str) -> bool:
        with open(path, "rb") as handle:
            handle.seek(-1, os.SEEK_END)
            return handle.read(1) == b"\n"

    def _read(self) -> None:
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
        if self._lock is not None:
            locks.release(self._lock)
            self._lock = None

    def remove(self) -> None:
        """The search is finished and its answer saved: delete the
        journal."""
        self.close()
        shutil.rmtree(self.path, ignore_errors=True)
