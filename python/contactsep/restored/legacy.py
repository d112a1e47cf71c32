"""Run the transcribed Appendix G program (fortran/legacy/appg.f) on a deck.

The program is installed with the package in two builds: ``appg-single``
(the listing's REAL) and ``appg-double`` (``-fdefault-real-8``).  It reads
the deck on standard input and prints its listing on standard output.

The original program trusts its cards: given a bad one it stops with a
runtime error, loops for ever or prints garbage.  So every data set is first
read and run by the restored core, which reports bad cards precisely, and
only the cards of data sets that passed are fed to the program, under a time
limit.  Its output is returned unchanged.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import threading
import time
from importlib import resources
from pathlib import Path
from typing import BinaryIO, Iterator

from contactsep.errors import DeckError
from contactsep.restored import core

#: The listing's DIMENSION (4): the most modes the original program holds.
LEGACY_MAX_MODES = 4
#: Seconds the program may take per data set before it is stopped (a
#: valid data set takes well under a second; the limit only guards
#: against a hang).
TIME_LIMIT_PER_DATA_SET = 60.0


class LegacyError(RuntimeError):
    """The original program failed on cards the restored core accepted."""


def executable(precision: str = "single") -> Path:
    """Path of the installed legacy program for ``precision``."""
    if precision not in core.PRECISIONS:
        raise ValueError(
            f"precision must be one of {core.PRECISIONS}, not {precision!r}")
    path = (resources.files("contactsep.restored") / "_bin"
            / f"appg-{precision}")
    return Path(os.fspath(path))


def run_cards(cards: str, precision: str = "single", *,
              program: str | os.PathLike | None = None,
              time_limit: float = TIME_LIMIT_PER_DATA_SET,
              stream: BinaryIO | None = None) -> str:
    """Feed card images to the program and return what it prints.

    No validation: the caller vouches for the cards.  ``program`` overrides
    the installed executable (tests use a build with larger DIMENSIONs).
    With ``stream`` (a binary file), the listing goes straight there as the
    program writes it, and "" is returned.
    """
    command = [os.fspath(program or executable(precision))]
    try:
        completed = subprocess.run(
            command, input=cards.encode("latin-1"),
            stdout=stream if stream is not None else subprocess.PIPE,
            stderr=subprocess.PIPE, timeout=time_limit, check=False)
    except subprocess.TimeoutExpired as error:
        raise LegacyError(
            f"the original program did not finish within {time_limit:g} s"
        ) from error
    if stream is not None and completed.returncode == -signal.SIGPIPE:
        raise BrokenPipeError("the reader of the listing went away")
    if completed.returncode != 0:
        detail = completed.stderr.decode("latin-1", "replace").splitlines()
        raise LegacyError(
            f"the original program failed (exit status "
            f"{completed.returncode}): {' '.join(detail[:2])}")
    return "" if stream is not None else completed.stdout.decode("latin-1")


def iter_validated(source: core.Deck, precision: str = "single", *,
                   max_modes: int | None = LEGACY_MAX_MODES,
                   blank: str = "null") -> Iterator[core.DeckSet]:
    """The data sets of the deck that pass validation (read by the
    restored core, N <= ``max_modes``, run by the restored core), one at
    a time as they are read; raises :class:`DeckError` at the first bad
    one.  Their ``cards`` are what the original program may be fed."""
    for item in core.iter_deck(source, precision=precision, blank=blank):
        if max_modes is not None and item.data_set.n > max_modes:
            first_card = item.first_card + 4
            raise DeckError(
                f"data set {item.index}, card {first_card}, columns "
                f"16-17: N = {item.data_set.n}, but the original program "
                f"holds at most {max_modes} modes (DIMENSION (4))",
                data_set=item.index, card=first_card, columns=(16, 17))
        # validation only: the original program prints the listing
        core.solve(item.data_set, precision, data_set_index=item.index,
                   first_card=item.first_card, listing=False)
        yield item


def validated_cards(text: core.Deck, precision: str = "single", *,
                    max_modes: int | None = LEGACY_MAX_MODES,
                    blank: str = "null"
                    ) -> tuple[str, int, DeckError | None]:
    """The cards of the leading data sets that pass validation.

    Returns the card images (one line each, as in the file, a CR before
    the LF dropped) of every data set up to the first bad one, how many
    data sets they hold, and the error for the bad one (or None).  Holds
    them all: :func:`run` feeds them to the program as they pass.
    """
    fed: list[str] = []
    failure: DeckError | None = None
    try:
        for item in iter_validated(text, precision, max_modes=max_modes,
                                   blank=blank):
            fed.append(item.cards)
    except DeckError as error:
        failure = error
    return "".join(fed), len(fed), failure


class _Program:
    """The original program running while its cards are fed, its listing
    copied to a stream (or kept) as it comes.  Each data set fed gives it
    ``time_limit`` more seconds; past the deadline it is killed."""

    def __init__(self, precision: str, program, stream: BinaryIO | None,
                 time_limit: float) -> None:
        self.stream, self.time_limit = stream, time_limit
        self.chunks: list[bytes] = []
        self.errors: list[BaseException] = []
        self.stderr = b""
        self.timed_out = False
        self.deadline = time.monotonic() + time_limit
        self.process = subprocess.Popen(
            [os.fspath(program or executable(precision))],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE,
            stderr=subprocess.PIPE, bufsize=0)
        self.done = threading.Event()
        self.threads = [threading.Thread(target=target, daemon=True)
                        for target in (self._copy, self._keep_stderr,
                                       self._watch)]
        for thread in self.threads:
            thread.start()

    def _copy(self) -> None:
        fd = self.process.stdout.fileno()
        try:
            while True:
                chunk = os.read(fd, 1 << 16)
                if not chunk:
                    return
                if self.stream is None:
                    self.chunks.append(chunk)
                else:
                    self.stream.write(chunk)
                    self.stream.flush()
        except BaseException as error:      # the stream failed: stop
            self.errors.append(error)
            self.process.kill()

    def _keep_stderr(self) -> None:
        for line in self.process.stderr:
            if len(self.stderr) < 4096:
                self.stderr += line

    def _watch(self) -> None:
        while not self.done.wait(0.2):
            if time.monotonic() > self.deadline and \
                    self.process.poll() is None:
                self.timed_out = True
                self.process.kill()
                return

    def feed(self, cards: str) -> None:
        self.deadline = time.monotonic() + self.time_limit
        try:
            self.process.stdin.write(cards.encode("ascii"))
        except BrokenPipeError:
            pass            # it stopped: finish() says why

    def finish(self) -> str:
        with contextlib.suppress(BrokenPipeError):
            self.process.stdin.close()
        self.process.wait()
        self.done.set()
        for thread in self.threads:
            thread.join()
        if self.errors:
            raise self.errors[0]
        if self.timed_out:
            raise LegacyError(f"the original program did not finish "
                              f"within {self.time_limit:g} s of its last "
                              f"data set")
        if self.process.returncode != 0:
            detail = self.stderr.decode("latin-1", "replace").splitlines()
            raise LegacyError(
                f"the original program failed (exit status "
                f"{self.process.returncode}): {' '.join(detail[:2])}")
        return b"".join(self.chunks).decode("latin-1")

    def kill(self) -> None:
        self.process.kill()
        self.process.wait()
        self.done.set()
        for thread in self.threads:
            thread.join(5)


def run(path: core.Deck, precision: str = "single", *,
        max_modes: int | None = LEGACY_MAX_MODES,
        program: str | os.PathLike | None = None,
        stream: BinaryIO | None = None) -> str:
    """The listing the original program prints for the deck at ``path``
    (a path, or any deck :func:`contactsep.restored.core.iter_deck` takes; a str
    is a file name here).

    The deck is read a data set at a time; each is fed to the program as
    soon as it passes validation, so the listing starts before the rest of
    the deck is read.  With ``stream``, the listing is written there as it
    is printed and "" is returned.  Raises :class:`DeckError` for the first
    bad data set, with the listing of the data sets before it in
    ``error.listing_before`` (or already written to ``stream``).
    """
    if isinstance(path, str):
        path = Path(path)
    items = iter_validated(path, precision, max_modes=max_modes)
    failure: DeckError | None = None
    try:
        first = next(items)
    except DeckError as error:
        error.listing_before = ""
        raise
    except StopIteration:        # pragma: no cover (iter_deck raises)
        return ""
    program_run = _Program(precision, program, stream,
                           TIME_LIMIT_PER_DATA_SET)
    try:
        program_run.feed(first.cards)
        try:
            for item in items:
                program_run.feed(item.cards)
        except DeckError as error:
            failure = error
        listing = program_run.finish()
    except BaseException:
        program_run.kill()
        raise
    if failure is not None:
        failure.listing_before = listing
        raise failure
    return listing
