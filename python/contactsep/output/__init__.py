"""Where the command's output goes, and how it stops (issues 9, 18).

``-o PATH`` and every file a command writes (:func:`open_output`, or a
:class:`Replacement` kept open across a sweep's chunks):

* a regular file, new or existing, is written to a temporary file beside
  it (``.NAME.XXXX.tmp``) and renamed into place when the command ends, so
  the target is either what it was or a whole listing.  A new file gets
  the permissions the umask allows (0666 & ~umask); an existing one keeps
  its own.  A bad data set is not a failure of the output: the listings
  of the data sets before it are what the command computed, and are
  renamed into place before the error is reported;
* a write error, Ctrl-C (SIGINT) or SIGTERM removes the temporary file
  and leaves the target as it was;
* a symbolic link is followed: the file it points to is written, the link
  stays;
* anything that is not a regular file (``/dev/null``, a FIFO,
  ``/dev/stdout``, a terminal) is opened and written directly, never
  replaced; a directory is refused;
* messages name the path as the user gave it, never the temporary file;
* ``Replacement(path, lock=True)`` (sweeps) refuses a target another
  command is writing (``.NAME.lock`` beside it, held with flock);
* :func:`check_targets`, before any work: no output a directory, no two
  outputs one file, no output a file the command reads.

Long compiled calls (:func:`interruptible`) run in a forked child, so
that Ctrl-C and SIGTERM stop them at once.

JSON (:func:`json_text`, :func:`write_json`) is strict: NaN and the
infinities are written as null, never as the NaN or Infinity that
``json.load`` in other languages refuses.

Standard output: a closed standard output (``>&-``) is an error at the
first write, ``standard output is closed``; a write error (``/dev/full``)
is reported like any other, exit status 2.

One module per concern, every name importable from ``contactsep.output``
as before: :mod:`~contactsep.output.files` (the replaced files and the
checks before work), :mod:`~contactsep.output.locks` (the sweeps'
locks), :mod:`~contactsep.output.interrupt` (signals, stop checks,
forked long calls) and :mod:`~contactsep.output.streams` (standard
streams, strict JSON, one-line errors).
"""

from __future__ import annotations

from contactsep.output.files import (
    Replacement,
    check_targets,
    open_output,
    same_file,
    target_info,
)
from contactsep.output.interrupt import (
    ComputationLost,
    Terminated,
    check_stops,
    die_with_parent,
    interruptible,
    raise_terminated,
    stop_checks,
)
from contactsep.output.locks import forget_locks, record_temporary
from contactsep.output.streams import (
    guard_closed_streams,
    json_text,
    one_line,
    report,
    require_pandas,
    stop_quietly,
    strict_json,
    write_json,
    write_text,
)

__all__ = [
    "ComputationLost", "Replacement", "Terminated", "check_stops",
    "check_targets", "die_with_parent", "forget_locks",
    "guard_closed_streams", "interruptible", "json_text", "one_line",
    "open_output", "raise_terminated", "record_temporary", "report",
    "require_pandas", "same_file", "stop_checks", "stop_quietly",
    "strict_json", "target_info", "write_json", "write_text",
]
