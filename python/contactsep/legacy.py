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

import os
import signal
import subprocess
from importlib import resources
from pathlib import Path
from typing import BinaryIO

from contactsep import core
from contactsep.errors import DeckError

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
    path = resources.files("contactsep") / "_bin" / f"appg-{precision}"
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


def validated_cards(text: str, precision: str = "single", *,
                    max_modes: int | None = LEGACY_MAX_MODES,
                    blank: str = "null"
                    ) -> tuple[str, int, DeckError | None]:
    """The cards of the leading data sets that pass validation.

    Returns the card images (one line each, as in the file) of every data
    set up to the first bad one, how many data sets they hold, and the
    error for the bad one (or None).
    """
    # a card is a line ended by LF, as for the core's reader (a trailing CR
    # stays: gfortran drops it, like the core's reader)
    lines = text.split("\n")
    kept_through = passed = 0
    failure: DeckError | None = None
    try:
        for item in core.iter_deck(text, precision=precision, blank=blank):
            if max_modes is not None and item.data_set.n > max_modes:
                first_card = item.first_card + 4
                raise DeckError(
                    f"data set {item.index}, card {first_card}, columns "
                    f"16-17: N = {item.data_set.n}, but the original program "
                    f"holds at most {max_modes} modes (DIMENSION (4))",
                    data_set=item.index, card=first_card, columns=(16, 17))
            core.solve(item.data_set, precision, data_set_index=item.index,
                       first_card=item.first_card)
            kept_through, passed = item.last_card, item.index
    except DeckError as error:
        failure = error
    cards = "".join(line + "\n" for line in lines[:kept_through])
    return cards, passed, failure


def run(path: str | os.PathLike, precision: str = "single", *,
        max_modes: int | None = LEGACY_MAX_MODES,
        program: str | os.PathLike | None = None,
        stream: BinaryIO | None = None) -> str:
    """The listing the original program prints for the deck at ``path``.

    With ``stream``, the listing is written there as it is printed and ""
    is returned.  Raises :class:`DeckError` for the first bad data set,
    with the listing of the data sets before it in
    ``error.listing_before`` (or already written to ``stream``).
    """
    cards, passed, failure = validated_cards(
        core.read_text(path), precision, max_modes=max_modes)
    listing = run_cards(cards, precision, program=program, stream=stream,
                        time_limit=TIME_LIMIT_PER_DATA_SET * passed) \
        if cards else ""
    if failure is not None:
        failure.listing_before = listing
        raise failure
    return listing
