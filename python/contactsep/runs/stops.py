"""A long command's progress bar (a sweep's, whose total is known; a
search's, whose total grows as it plans its batches), and how a sweep
hears Ctrl-C and SIGTERM: noted by a handler, acted on between chunks and
while it waits for one."""

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


class SearchProgress:
    """The progress of a search whose run count is known only batch by
    batch (``contactsep preload``): a callable taking the number of runs
    that finished, as any progress callback, and told of every batch
    before it runs (:meth:`planned`).  The bar's total starts at an
    estimate of the whole search (``expected``) and grows whenever the
    runs planned so far pass it, so its ETA is for the work known at the
    time: it lengthens where the search finds more to check (a window of
    events, the robust search's preloads)."""

    def __init__(self, bar, expected: int = 0) -> None:
        self.bar = bar
        #: Runs asked for so far (those a journal answers included).
        self.asked = 0
        bar.unit = "run"
        bar.total = max(int(expected), 0) or None

    def __call__(self, finished: int) -> None:
        self.bar.update(finished)

    def estimated(self, estimate) -> None:
        """The search's estimate before its first run (an object with
        ``runs`` and ``line()``: :class:`contactsep.studies.preload.
        estimate.SearchEstimate`): its line written above the bar, its
        runs the bar's total where they pass the first estimate."""
        if estimate.runs > (self.bar.total or 0):
            self.bar.total = estimate.runs
        self.bar.write(estimate.line(), file=sys.stderr)

    def planned(self, phase: str, count: int) -> None:
        """A batch of ``count`` runs of ``phase`` is about to run."""
        self.asked += count
        if self.bar.total is None or self.asked > self.bar.total:
            self.bar.total = self.asked
        # shown at the bar's next refresh (a forced one would show a bar
        # the delay keeps hidden in a short command)
        self.bar.set_description_str(phase, refresh=False)

    def close(self, finished: bool = True) -> None:
        """Closes the bar; ``finished``: the total is then what ran (an
        estimate that was too high does not leave the bar short)."""
        if finished:
            self.bar.total = max(self.bar.n, 1)
        self.bar.close()


def search_progress(expected: int, enabled: bool | None):
    """A :class:`SearchProgress` on a terminal (stderr), or None (as
    :func:`progress_bar`)."""
    bar = progress_bar(None, enabled)
    return None if bar is None else SearchProgress(bar, expected)


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

