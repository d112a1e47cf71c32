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
"""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import pickle
import select
import signal
import stat
import sys
import tempfile
import threading
from typing import Iterator, TextIO

from contactsep.errors import DeckError, InputError, printable

#: Characters written at a time: a listing of tens of megabytes is never
#: encoded whole.
_CHUNK = 1 << 20


class Terminated(BaseException):
    """SIGTERM arrived: unwind (removing temporary files) and stop."""


#: SIGTERMs seen by raise_terminated: an exception raised where Python
#: ignores exceptions (an os.fork() at-fork callback) is lost, the count
#: is not (interruptible() checks it).
_terminations = [0]


def raise_terminated(signum, frame) -> None:
    _terminations[0] += 1
    raise Terminated


class ComputationLost(InputError):
    """The child process of :func:`interruptible` died without an answer
    (killed, out of memory): a fault of the machine, not of the input."""


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


def _named(error: OSError, path: str) -> OSError:
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
                raise _named(error, self.path) from None
            return
        directory, name = os.path.split(self._target)
        if lock:
            self._lock = _lock(os.path.join(directory, f".{name}.lock"),
                               self.path)
        try:
            fd, self._temp = tempfile.mkstemp(prefix=f".{name}.",
                                              suffix=".tmp",
                                              dir=directory or ".")
        except OSError as error:
            self._unlock()
            raise _named(error, self.path) from None
        record_temporary(self._lock, self._temp)
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
            raise _named(error, self.path) from None
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
            lock_path, fd = self._lock
            with contextlib.suppress(OSError):
                os.unlink(lock_path)
            _HELD_LOCKS.discard(fd)
            os.close(fd)
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
        raise _named(error, path) from None
    if stat.S_ISDIR(info.st_mode):
        raise OSError(errno.EISDIR, "Is a directory, not a file", path)
    return info


#: Lock files this process holds (fds): a forked child closes its copies
#: (:func:`forget_locks`), so that a worker outliving its parent never
#: keeps a sweep's output locked.
_HELD_LOCKS: set = set()


def forget_locks() -> None:
    """In a forked child: close the inherited descriptors of the parent's
    output locks (flock is shared by every copy of a descriptor: a worker
    holding one kept the output "in use" after its parent was killed)."""
    for fd in list(_HELD_LOCKS):
        with contextlib.suppress(OSError):
            os.close(fd)
    _HELD_LOCKS.clear()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:             # another user's process: alive
        return True
    return True


def _lock_record(fd: int) -> tuple[int | None, str | None]:
    """The process id and temporary file name a lock file records (None
    where there is none, or it cannot be read)."""
    try:
        words = os.pread(fd, 4096, 0).decode("utf-8", "replace").split()
    except OSError:
        return None, None
    pid = int(words[0]) if words and words[0].isdigit() else None
    return pid, (words[1] if len(words) > 1 else None)


def _holder(fd: int) -> int | None:
    """The process id a lock file records (None: none, or unreadable)."""
    return _lock_record(fd)[0]


def _drop_dead_writers_file(fd: int, lock_path: str) -> None:
    """A lock just taken whose last holder died without removing it
    (SIGKILL, a lost machine): remove the temporary file it recorded, its
    unfinished output (only a name of this target's own form, beside
    it)."""
    pid, temp = _lock_record(fd)
    if pid is None or temp is None or _alive(pid):
        return
    directory, name = os.path.split(lock_path)
    target = name[1:-len(".lock")]
    if temp.startswith(f".{target}.") and temp.endswith(".tmp") and \
            "/" not in temp:
        with contextlib.suppress(OSError):
            os.unlink(os.path.join(directory, temp))


def record_temporary(lock: tuple[str, int] | None, temp: str) -> None:
    """Write this process's id and its temporary file into its lock (a
    later command removes the file if this one dies first)."""
    if lock is None:
        return
    with contextlib.suppress(OSError):
        os.ftruncate(lock[1], 0)
        os.pwrite(lock[1], f"{os.getpid()} {os.path.basename(temp)}\n"
                  .encode("utf-8"), 0)


def _lock(lock_path: str, path: str) -> tuple[str, int]:
    """Hold ``lock_path`` (flock, exclusive, created if need be, this
    process's id written in it); a lock held by another running command
    is refused with an InputError naming ``path``.  A lock whose recorded
    writer is dead (a descendant it left behind holds the flock) is
    stale: it is unlinked and a new one taken, the dead writer's
    temporary file never being renamed.  The inode check: a holder that
    just finished (or a stale lock taken over) unlinked the file this
    process opened, so lock the one now at the path instead."""
    import fcntl
    while True:
        try:
            fd = os.open(lock_path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC,
                         0o600)
        except OSError as error:
            raise _named(error, path) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = _holder(fd)
            if holder is not None and holder != os.getpid() and \
                    not _alive(holder):
                with contextlib.suppress(OSError):
                    if os.path.samestat(os.fstat(fd), os.stat(lock_path)):
                        _drop_dead_writers_file(fd, lock_path)
                        os.unlink(lock_path)      # stale: take it over
                os.close(fd)
                continue
            os.close(fd)
            who = f" (process {holder})" if holder else ""
            raise InputError(f"{path}: in use: another contactsep command"
                             f"{who} is writing it (it holds "
                             f"{os.path.basename(lock_path)}); wait for it "
                             f"or write elsewhere") from None
        try:
            same = os.path.samestat(os.fstat(fd), os.stat(lock_path))
        except FileNotFoundError:
            same = False
        if same:
            _drop_dead_writers_file(fd, lock_path)
            with contextlib.suppress(OSError):
                os.ftruncate(fd, 0)
                os.pwrite(fd, f"{os.getpid()}\n".encode("ascii"), 0)
            _HELD_LOCKS.add(fd)
            return lock_path, fd
        os.close(fd)


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
            raise _named(error, out.path) from None
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


#: Checks a long wait calls now and then (:func:`stop_checks`): each
#: raises when a stop was asked for (a sweep notes its signals and acts
#: on them at such points).
_STOP_CHECKS: list = []


@contextlib.contextmanager
def stop_checks(check) -> Iterator[None]:
    """Within the block, :func:`interruptible`'s wait calls ``check()``
    every quarter second (and when its child dies)."""
    _STOP_CHECKS.append(check)
    try:
        yield
    finally:
        _STOP_CHECKS.remove(check)


def _check_stops() -> None:
    for check in list(_STOP_CHECKS):
        check()


def check_stops() -> None:
    """Call the :func:`stop_checks` checks now: a wait on a compiled
    call that runs in a thread does, as :func:`interruptible` does."""
    _check_stops()


def interruptible(long: bool, function, *args):
    """``function(*args)``; when the call is ``long``, in a child process.

    A compiled call is one that Python cannot interrupt: Ctrl-C and
    SIGTERM wait for it to return (a chatter run at N = 1024 takes a
    minute, one design of the model seconds).  In a child (forked:
    nothing is pickled but the answer) they stop the wait at once, as
    does a stop noted by a :func:`stop_checks` check; the child ends with
    the parent's Ctrl-C (it shares the terminal), with the parent (Linux:
    PR_SET_PDEATHSIG), or is killed.  Exceptions come back as they were
    raised (one that cannot be pickled, as an InputError with its
    message).  With other threads running (fork would copy their locks),
    or without fork, the call runs here."""
    if not long or not hasattr(os, "fork") or \
            threading.active_count() > 1:
        return function(*args)
    read_fd, write_fd = os.pipe()
    parent = os.getpid()
    # Ctrl-C and SIGTERM wait while fork runs: raised inside its at-fork
    # callbacks (logging's), Python would print and ignore the exception
    # and the command would run on and exit 0 (seen under load)
    stops = {signal.SIGINT, signal.SIGTERM}
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, stops)
    seen = _terminations[0]
    try:
        pid = os.fork()
    except BaseException:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        raise
    if pid == 0:                        # the child: never returns
        try:
            os.close(read_fd)
            signal.signal(signal.SIGINT, signal.SIG_DFL)
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
            die_with_parent(parent)
            forget_locks()
            data = _answer(function, args)
            with os.fdopen(write_fd, "wb") as pipe:
                pipe.write(data)
        finally:
            os._exit(0)
    os.close(write_fd)
    chunks = []
    try:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        if _terminations[0] != seen:
            raise Terminated
        with os.fdopen(read_fd, "rb", buffering=0) as pipe:
            while True:
                _check_stops()
                ready, _, _ = select.select([pipe], [], [], 0.25)
                if ready:
                    chunk = pipe.read(1 << 20)
                    if not chunk:
                        break
                    chunks.append(chunk)
    except BaseException:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        raise
    _, code = os.waitpid(pid, 0)
    try:
        ok, value = pickle.loads(b"".join(chunks))
    except Exception:                    # noqa: BLE001 - no whole answer
        _check_stops()      # a Ctrl-C that ended the child ends this too
        raise ComputationLost(f"the computation's process ended without "
                              f"an answer (status {code}: killed, or out "
                              f"of memory)") from None
    if not ok:
        raise value
    return value


def die_with_parent(parent: int) -> None:
    """In a child: be killed when ``parent`` ends, by any signal (Linux:
    PR_SET_PDEATHSIG), so that a command killed outright leaves no
    worker or computation behind; a parent already gone: exit now."""
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)        # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:               # it ended before prctl
        os._exit(1)


def _answer(function, args) -> bytes:
    """The pickled (True, result) or (False, exception) of a call."""
    try:
        answer = (True, function(*args))
    except BaseException as error:       # noqa: BLE001 - sent back
        answer = (False, error)
    try:
        return pickle.dumps(answer, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:                    # noqa: BLE001 - said instead
        return pickle.dumps((False, InputError(one_line(answer[1]) if not
                                               answer[0] else "the answer "
                                               "could not be sent back")))


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
