"""Locks on the files a sweep writes (``.NAME.lock`` beside the target,
held with flock): a second command writing the same file is refused at
once; a lock whose writer died is taken over and the dead writer's
temporary file removed; a forked child closes its copies of the
parent's locks (:func:`forget_locks`)."""

from __future__ import annotations

import contextlib
import os

from contactsep.errors import InputError
from contactsep.output.streams import named

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


def take(lock_path: str, path: str) -> tuple[str, int]:
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
            raise named(error, path) from None
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


def release(lock: tuple[str, int]) -> None:
    """Remove and close a lock :func:`take` returned."""
    lock_path, fd = lock
    with contextlib.suppress(OSError):
        os.unlink(lock_path)
    _HELD_LOCKS.discard(fd)
    os.close(fd)
