"""``--resume`` for the commands of three-beam simulations
(``preload``, and the studies of ``cli.study_runs.RESUMABLE``): every
finished simulation kept beside the output CSV in ``.FILE.resume/``
(:class:`contactsep.runs.journal.RunJournal`), what the command
says about it, and its removal once the CSV is in place."""

from __future__ import annotations

import contextlib
import os
import shutil
import stat
import sys

from contactsep import output
from contactsep.errors import InputError


def check_resume(resume: bool, csv, give: str = "--csv") -> None:
    """--resume needs a regular CSV file to keep its journal beside
    (``give``: how the command names one)."""
    if not resume:
        return
    if not csv:
        raise InputError(f"--resume keeps the finished simulations beside "
                         f"the output: give {give}")
    info = output.target_info(os.fspath(csv))
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise InputError(f"--resume keeps the finished simulations beside "
                         f"the output: {csv} is not a regular file")


def open_journal(resume: bool, csv, inputs: dict):
    """With ``resume``, the journal beside ``csv`` (continued if one of
    the same inputs is there) and a line on stderr saying what it holds;
    None without."""
    if not resume:
        return None
    from contactsep.runs.journal import RunJournal, store_path
    csv = os.fspath(csv)
    path = store_path(csv)
    journal = RunJournal(path, inputs, label=csv + " (" +
                         os.path.basename(path) + ")")
    if len(journal):
        sys.stderr.write(f"contactsep: --resume: {len(journal):,} finished "
                         f"simulations in {os.path.basename(path)}, not "
                         f"run again\n")
        sys.stderr.flush()
    return journal


def stopped(journal, csv, error: BaseException) -> None:
    """The command stopped by ``error`` before its CSV: a journal with no
    run goes (refused, or stopped before a run); one with runs is closed
    and, on an interrupt, the command says where they are kept."""
    interrupted = isinstance(error, (KeyboardInterrupt, output.Terminated))
    if journal is None:
        if interrupted:     # else quiet: SIGTERM prints nothing else
            _say("stopped; nothing was kept: with --csv FILE --resume "
                 "every finished simulation is kept beside FILE and the "
                 "same command continues from them")
        return
    if not len(journal):
        journal.remove()
        return
    journal.close()
    if interrupted:
        _say(f"{os.fspath(csv)}: not written; {len(journal):,} finished "
             f"simulations kept in {os.path.basename(journal.path)}: rerun "
             f"the command to continue")


def _say(text: str) -> None:
    """One line on stderr, as the command's own words."""
    with contextlib.suppress(OSError, ValueError):
        sys.stderr.write(f"contactsep: {text}\n")
        sys.stderr.flush()


def finished(csv, journal) -> None:
    """The CSV is in place: this command's journal, or one an earlier run
    without --resume could not continue, is obsolete."""
    if journal is not None:
        journal.remove()
        return
    from contactsep.output import locks
    from contactsep.runs.journal import store_path
    path = store_path(os.fspath(csv))
    if not os.path.isdir(path):
        return
    try:
        lock = locks.take(path + ".lock", os.fspath(csv))
    except InputError:
        return              # another command is continuing it
    shutil.rmtree(path, ignore_errors=True)
    locks.release(lock)
