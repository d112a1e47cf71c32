"""What the user sees of a command: the standard streams (a closed one
is an error at the first write), text written a megabyte at a time,
strict JSON (NaN and the infinities as null) and errors as one printable
line (``prog: error: ...``)."""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import sys
from typing import TextIO

from contactsep.errors import InputError, printable

#: Characters written at a time: a listing of tens of megabytes is never
#: encoded whole.
_CHUNK = 1 << 20


class _ClosedBinary:
    def __init__(self, name: str) -> None:
        self.name = name

    def write(self, data) -> int:
        raise OSError(errno.EBADF, f"{self.name} is closed")

    def flush(self) -> None:
        pass

    def fileno(self) -> int:
        raise OSError(errno.EBADF, f"{self.name} is closed")

    def isatty(self) -> bool:
        return False


class _ClosedText(_ClosedBinary):
    """Stands for a standard stream that was closed when the command
    started: writing to it is an OSError, flushing it (nothing written)
    is not."""

    @property
    def buffer(self) -> _ClosedBinary:
        return _ClosedBinary(self.name)


def guard_closed_streams() -> None:
    """Python sets ``sys.stdout`` to None when file descriptor 1 is closed
    at start-up (likewise 0 and 2).  Put a stand-in there that fails on
    write with a clear OSError, and hold descriptors 0-2 open on the null
    device, so that no file the command opens can take their place."""
    for fd, name in ((0, "stdin"), (1, "stdout"), (2, "stderr")):
        if getattr(sys, name) is not None:
            continue
        try:
            os.fstat(fd)
        except OSError:
            null = os.open(os.devnull, os.O_RDWR)
            if null != fd:
                os.dup2(null, fd)
                os.close(null)
        if name == "stdout":
            sys.stdout = _ClosedText("standard output")
        elif name == "stderr":
            sys.stderr = open(os.devnull, "w")


def write_text(stream: TextIO, text: str) -> None:
    """Write ``text`` a megabyte at a time (no copy of a long listing)."""
    for start in range(0, len(text), _CHUNK):
        stream.write(text[start:start + _CHUNK])


def named(error: OSError, path: str) -> OSError:
    """The error with the user's path in it (not a temporary file's)."""
    if error.strerror is None:
        return error
    renamed = OSError(error.errno, error.strerror, path)
    renamed.__cause__ = None
    return renamed


def strict_json(value):
    """``value`` with NaN and the infinities as None and NumPy scalars
    and arrays as Python numbers and lists, recursively."""
    if isinstance(value, dict):
        return {str(k): strict_json(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [strict_json(v) for v in value]
    if hasattr(value, "tolist"):         # a NumPy array or scalar
        return strict_json(value.tolist())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def json_text(value, indent: int | None = 2) -> str:
    """Strict JSON text of ``value`` (:func:`strict_json`), no newline."""
    return json.dumps(strict_json(value), indent=indent, allow_nan=False)


def write_json(stream: TextIO, value, indent: int | None = 2) -> None:
    """Write ``value`` as strict JSON and a newline."""
    write_text(stream, json_text(value, indent) + "\n")


def _silence_stdout() -> None:
    """After a failed write, point stdout at the null device so that the
    interpreter's last flush cannot print a second message."""
    try:
        sys.stdout.flush()
    except (OSError, ValueError):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            null = os.open(os.devnull, os.O_WRONLY)
            os.dup2(null, sys.stdout.fileno())
            os.close(null)


def one_line(error: BaseException) -> str:
    """An error's message as one printable line (an OSError's strerror
    and the path it names)."""
    if isinstance(error, OSError) and error.strerror:
        message = error.strerror
        if error.filename is not None:
            message += f": {os.fsdecode(error.filename)}"
    else:
        message = str(error)
    return printable(message)


def report(prog: str, error: BaseException) -> None:
    """Print ``prog: error: <message>``: one printable line."""
    message = one_line(error)
    _silence_stdout()
    with contextlib.suppress(OSError, ValueError):
        sys.stderr.write(f"{prog}: error: {message}\n")
        sys.stderr.flush()


def stop_quietly(status: int) -> int:
    """After SIGINT or SIGTERM: flush what was printed, say nothing."""
    _silence_stdout()
    return status


def require_pandas():
    """pandas, or the InputError a DataFrame gives without it."""
    try:
        import pandas
    except ImportError:
        raise InputError("a DataFrame needs pandas: pip install "
                         "'contactsep[tables]'") from None
    return pandas
