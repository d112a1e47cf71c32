"""Sweeps that survive being killed (``contactsep sweep ... --resume``).

A resumable sweep keeps each finished chunk in a directory beside its
output, ``.NAME.resume/`` (NAME the --csv file, else the --parquet one):
``manifest.json``, what made the sweep (:meth:`SweepSpec.inputs`, the
package version, the digest of its code: :mod:`.code_digest`), and one
``FIRST-LAST.npz`` per chunk of designs FIRST..LAST-1, its output
columns.  Every file is written to a temporary
name and renamed into place, so a SIGKILL at any moment leaves whole
chunks or none.  Rerun with ``--resume``, the sweep takes the chunks it
finds, computes the designs between them, and writes the outputs afresh
from the first row: they do not depend on the chunking (the CSV row by
row, the Parquet row groups and the summary's sums in fixed blocks of
designs), so they are byte-identical to an uninterrupted run's.  A
manifest whose inputs differ is refused; the directory is removed once
the outputs are in place.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import tempfile

import numpy as np

from contactsep.errors import InputError
from contactsep.output import json_text
from contactsep.studies.sweep.spec import SweepSpec

_CHUNK_FILE = re.compile(r"^(\d+)-(\d+)\.npz$")


class ResumeError(InputError):
    """A --resume that cannot continue the sweep it finds."""


def store_path(output_path: str) -> str:
    """The chunk directory of an output file: ``.NAME.resume`` beside
    it (links followed, as the output is)."""
    target = os.path.realpath(output_path)
    directory, name = os.path.split(target)
    return os.path.join(directory, f".{name}.resume")


def manifest(spec: SweepSpec) -> dict:
    """What a chunk's columns depend on: the sweep's inputs, its model
    and backend, the package version (another version may compute
    other digits) and the digest of the code that computes them (an
    edited development install too: :mod:`.code_digest`)."""
    from contactsep import __version__
    from contactsep.runs.code_digest import STUDIES, code_digest
    return {"contactsep": __version__, "code_sha256": code_digest(STUDIES),
            "model": spec.model, "inputs": spec.inputs()}


def differences(old: dict, new: dict, prefix: str = "") -> list:
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
        with open(os.path.join(directory, "manifest.json"),
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


def save_columns(path: str, columns: dict) -> None:
    """A chunk's columns to ``path`` (.npz), atomically."""
    atomic_write(path, lambda handle: np.savez(
        handle, **{k: np.ascontiguousarray(v) for k, v in columns.items()}))


def load_columns(path: str) -> dict:
    with np.load(path) as data:
        return {name: data[name] for name in data.files}


class ChunkStore:
    """The finished chunks of a resumable sweep (module docstring).

    ``resume`` True: a directory left by an earlier run of the same
    inputs is continued (other inputs: :class:`ResumeError`, one line
    naming what differs); False: it is started afresh.  The output's
    lock (taken by its writer) keeps a second command out."""

    def __init__(self, output_path: str, spec: SweepSpec,
                 resume: bool = True) -> None:
        self.path = store_path(output_path)
        self.label = output_path
        wanted = manifest(spec)
        manifest_path = os.path.join(self.path, "manifest.json")
        self.chunks = {}
        if resume and same_inputs(
                self.path, wanted, f"sweep beside {output_path} "
                                   f"({os.path.basename(self.path)})"):
            self.chunks = self._scan(spec.size)
        if not self.chunks:
            shutil.rmtree(self.path, ignore_errors=True)
            os.makedirs(self.path, exist_ok=True)
            atomic_write(manifest_path, lambda handle: handle.write(
                json_text(wanted).encode("utf-8")))

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
        return os.path.join(self.path, f"{first:012d}-{last:012d}.npz")

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

    def remove(self) -> None:
        """The sweep is finished and its outputs in place."""
        shutil.rmtree(self.path, ignore_errors=True)
