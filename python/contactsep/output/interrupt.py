"""How a command stops: SIGTERM as an exception (:class:`Terminated`),
the checks a long wait makes (:func:`stop_checks`), and long compiled
calls run in a forked child (:func:`interruptible`) so that Ctrl-C and
SIGTERM stop them at once."""

from __future__ import annotations

import contextlib
import os
import pickle
import select
import signal
import threading
from typing import Iterator

from contactsep.errors import InputError
from contactsep.output.locks import forget_locks
from contactsep.output.streams import one_line


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
