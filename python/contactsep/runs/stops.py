"""A sweep's progress bar, and how it hears Ctrl-C and SIGTERM: noted
by a handler, acted on between chunks and while it waits for one."""

from __future__ import annotations

import signal
import sys
import threading
import warnings

from contactsep.errors import ContactsepWarning


def progress_bar(total: int, enabled: bool | None):
    """A tqdm bar on a terminal (stderr), or nothing.  Asked for
    (``enabled`` True) without tqdm installed: a warning says so."""
    if enabled is None:
        enabled = sys.stderr.isatty()
        required = False
    else:
        required = enabled
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        if required:
            warnings.warn("no progress bar: it needs tqdm (pip install "
                          "'contactsep[progress]')", ContactsepWarning)
        return None
    # no monitor thread: a live thread keeps every later long call of
    # this process from forking (output.interruptible runs it here, deaf
    # to Ctrl-C until it returns)
    tqdm.monitor_interval = 0
    # shown only once the run has taken a second
    return tqdm(total=total, unit="design", unit_scale=True, delay=1.0,
                file=sys.stderr)


class StopRequests:
    """SIGINT and SIGTERM during a sweep only note the request; the sweep
    acts on it between chunks and while it waits for one.  An exception
    raised by a handler anywhere else (inside the process pool's own
    code, holding its locks) could deadlock the pool's shutdown."""

    def __init__(self) -> None:
        self.signum = None
        self._previous = {}

    def __enter__(self) -> "StopRequests":
        if threading.current_thread() is threading.main_thread():
            for signum in (signal.SIGINT, signal.SIGTERM):
                previous = signal.getsignal(signum)
                if previous not in (signal.SIG_IGN, None):
                    self._previous[signum] = previous
                    signal.signal(signum, self._note)
        return self

    def _note(self, signum, frame) -> None:
        if self.signum is None:
            self.signum = signum

    def check(self) -> None:
        """Act on a noted signal: its own handler runs now, here (Ctrl-C
        raises KeyboardInterrupt; the command's SIGTERM handler raises
        its exception; a default SIGTERM ends the process)."""
        if self.signum is not None:
            self.__exit__()
            signal.raise_signal(self.signum)

    def __exit__(self, *exc) -> None:
        for signum, previous in self._previous.items():
            signal.signal(signum, previous)
        self._previous = {}


def wait_for(future, stop: StopRequests):
    """A chunk's columns, listening for a stop every quarter second (a
    chunk that failed because the same Ctrl-C ended it: the stop)."""
    while True:
        stop.check()
        try:
            return future.result(timeout=0.25)
        except TimeoutError:
            continue
        except BaseException:
            stop.check()
            raise
