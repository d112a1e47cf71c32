"""Files a command writes, replaced only by finished ones
(:class:`Replacement`, :func:`open_output`; the rules are
:mod:`contactsep.output`'s), and the checks made before any work
(:func:`check_targets`)."""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
from typing import Iterator, TextIO

from contactsep.errors import DeckError, InputError
from contactsep.output import locks
from contactsep.output.streams import named


class Replacement:
    """A file that replaces ``path`` only when it is finished (module
    docstring): ``stream`` writes a temporary file beside the target,
    :meth:`commit` renames it into place, :meth:`discard` removes it.  A
    device, FIFO or terminal is written in place (commit and discard
    close it); a directory is refused.

    ``lock=True`` (sweeps, which write for minutes): a second command
    writing the same file is refused at once, while this one runs
    (``.NAME.lock`` beside the target, held with flock and removed at the
    end), instead of two temporary files racing to be renamed.
    """

    def __init__(self, path: str | os.PathLike, binary: bool = False,
                 lock: bool = False) -> None:
        self.path = os.fspath(path)
        how, text = ("wb", {}) if binary else \
            ("w", {"encoding": "ascii", "newline": ""})
        self._target = os.path.realpath(self.path)
        self._temp = None
        self._lock = None
        info = target_info(self.path)
        if info is not None and not stat.S_ISREG(info.st_mode):
            try:
                self.stream = open(self._target, how, **text)
            except OSError as error:
                raise named(error, self.path) from None
            return
        directory, name = os.path.split(self._target)
        if lock:
            self._lock = locks.take(os.path.join(directory, f".{name}.lock"),
                               self.path)
        try:
            fd, self._temp = tempfile.mkstemp(prefix=f".{name}.",
                                              suffix=".tmp",
                                              dir=directory or ".")
        except OSError as error:
            self._unlock()
            raise named(error, self.path) from None
        locks.record_temporary(self._lock, self._temp)
        try:
            if info is not None:
                mode = stat.S_IMODE(info.st_mode)
            else:
                umask = os.umask(0)
                os.umask(umask)
                mode = 0o666 & ~umask
            os.fchmod(fd, mode)
            self.stream = os.fdopen(fd, how, **text)
        except BaseException:
            os.close(fd)
            self.discard()
            raise

    def commit(self) -> None:
        """Close; a temporary file replaces the target."""
        try:
            self.stream.close()
            if self._temp is not None:
                os.replace(self._temp, self._target)
                self._temp = None
        except OSError as error:
            self.discard()
            raise named(error, self.path) from None
        self._unlock()

    def discard(self) -> None:
        """Close; the target stays as it was (a device: as written)."""
        with contextlib.suppress(OSError, AttributeError):
            self.stream.close()
        if self._temp is not None:
            with contextlib.suppress(OSError):
                os.unlink(self._temp)
            self._temp = None
        self._unlock()

    def _unlock(self) -> None:
        if self._lock is not None:
            locks.release(self._lock)
            self._lock = None


def target_info(path: str | os.PathLike) -> os.stat_result | None:
    """stat() of the file ``path`` names (links followed), None if there
    is none yet; a directory is refused (OSError naming ``path``)."""
    path = os.fspath(path)
    try:
        info = os.stat(os.path.realpath(path))
    except FileNotFoundError:
        return None
    except OSError as error:
        raise named(error, path) from None
    if stat.S_ISDIR(info.st_mode):
        raise OSError(errno.EISDIR, "Is a directory, not a file", path)
    return info


@contextlib.contextmanager
def open_output(path: str | os.PathLike, binary: bool = False
                ) -> Iterator[TextIO]:
    """A text stream (a binary one with ``binary``) to ``path`` for
    ``-o`` and every file a command writes (module docstring): a
    :class:`Replacement` committed when the block ends."""
    out = Replacement(path, binary)
    kept: BaseException | None = None
    try:
        try:
            yield out.stream
        except (DeckError, InputError) as error:
            # the deck's fault, not the output's: keep what was done
            kept = error
        out.commit()
    except BaseException as error:
        out.discard()
        if isinstance(error, OSError):
            raise named(error, out.path) from None
        raise
    if kept is not None:
        raise kept


def check_targets(outputs: dict, inputs: dict | None = None) -> None:
    """Before a command does any work: every output (label -> path, None
    for none) a file that can be written (not a directory), no two of
    them one file, none of them an input (label -> path) the command
    reads.  An InputError or OSError names the label and the path."""
    seen = {}
    for label, path in outputs.items():
        if path is None:
            continue
        info = target_info(path)
        if info is None or stat.S_ISREG(info.st_mode):
            _check_directory(label, path)
        for other, earlier in {**seen, **(inputs or {})}.items():
            if same_file(path, earlier):
                what = f"the same file as {other} {earlier}" if \
                    other in seen else f"the {other} file the command reads"
                raise InputError(f"{label} {path}: {what}; write each "
                                 f"output to its own file")
        seen[label] = path


def _check_directory(label: str, path: str | os.PathLike) -> None:
    """The directory a regular output file is written in (its temporary
    file beside it) exists and can be written, or an InputError names
    ``label`` and ``path`` (issue 31: refused before the work, not
    after it)."""
    directory = os.path.dirname(os.path.realpath(path)) or "."
    if not os.path.isdir(directory):
        raise InputError(f"{label} {os.fspath(path)}: no such directory "
                         f"{directory}")
    if not os.access(directory, os.W_OK | os.X_OK):
        raise InputError(f"{label} {os.fspath(path)}: directory "
                         f"{directory} is not writable")


def same_file(first: str | os.PathLike, second: str | os.PathLike) -> bool:
    """True when two paths name one file (links followed; a file not yet
    written by its resolved path)."""
    a, b = os.path.realpath(first), os.path.realpath(second)
    if a == b:
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False
