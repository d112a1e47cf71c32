"""``--resume`` on the command line: the one life cycle of every
resumable command's journal (:mod:`contactsep.runs.journal`), kept
beside its output in ``.FILE.resume/``: --resume checked before any
work, the journal opened, what the command says when it stops, and the
journal's removal once the output is in place.

``contactsep sweep`` keeps its finished chunks (a
:class:`~contactsep.studies.sweep.run.ChunkStore`, beside every output
file, --resume or not: a sweep started afresh drops an earlier one's);
``preload`` and the studies of ``cli.study_runs.RESUMABLE`` keep their
finished simulations (a :class:`~contactsep.runs.journal.RunJournal`,
with --resume only)."""

from __future__ import annotations

import contextlib
import os
import shutil
import sys

from contactsep import output
from contactsep.errors import InputError, printable


def _say(text: str) -> None:
    """One line on stderr, as the command's own words."""
    with contextlib.suppress(OSError, ValueError):
        sys.stderr.write(f"contactsep: {text}\n")
        sys.stderr.flush()


class Resume:
    """The journal of one command beside its ``output`` file (a path, or
    None without one), from --resume checked to the journal removed.

    ``kept``: what the journal keeps, as the messages name it
    ("simulations" or "chunks"); ``give``: how the command names its
    output options.  Made before any work: --resume needs a regular
    output file (or a new one) to keep its journal beside."""

    def __init__(self, resume: bool, output_path, *,
                 kept: str = "simulations", give: str = "--csv") -> None:
        self.resume = bool(resume)
        self.output = None if not output_path else os.fspath(output_path)
        self.kept = kept
        #: The journal open (:meth:`open_runs`, :meth:`open_chunks`).
        self.journal = None
        if not self.resume:
            return
        where = f"--resume keeps the finished {kept} beside the output"
        if self.output is None:
            raise InputError(f"{where}: give {give}")
        if not self.regular_or_new:
            raise InputError(f"{where}: {self.output} is not a regular "
                             f"file")

    @property
    def regular_or_new(self) -> bool:
        """Whether the output is a regular file or none yet (a device or
        FIFO output has no folder beside it for a journal)."""
        from contactsep.runs.journal import regular_or_new
        return self.output is not None and regular_or_new(self.output)

    def open_runs(self, inputs: dict):
        """With --resume, the journal of the simulations beside the
        output (continued if one of the same ``inputs`` is there) and a
        line on stderr saying what it holds; None without."""
        if not self.resume:
            return None
        from contactsep.runs.journal import RunJournal, store_path
        path = store_path(self.output)
        self.journal = RunJournal(path, inputs, label=self.output + " (" +
                                  os.path.basename(path) + ")")
        if len(self.journal):
            _say(f"--resume: {len(self.journal):,} finished simulations in "
                 f"{os.path.basename(path)}, not run again")
        return self.journal

    def open_chunks(self, spec):
        """The store of the sweep ``spec``'s finished chunks beside its
        output file (with --resume an earlier run's is continued, else
        dropped); None for no output, or one that is not a regular
        file.  The output's writers hold its lock: open it after them."""
        from contactsep.studies.sweep.run import ChunkStore
        if self.regular_or_new:
            self.journal = ChunkStore(self.output, spec, resume=self.resume)
        return self.journal

    def stopped(self, error: BaseException, unfinished=None) -> None:
        """The command stopped by ``error`` before its output was in
        place.  Finished chunks stay, but for a fresh sweep's after a
        write error (a full disk: no place for them either); on SIGTERM
        the sweep says ``unfinished()``, what it left, in one line.
        Finished simulations: a journal with none goes (refused, or
        stopped before a run); one with some is closed and, on an
        interrupt, the command says where they are kept."""
        journal = self.journal
        if self.kept == "chunks":
            if isinstance(error, OSError) and journal is not None and \
                    not self.resume:
                journal.remove()
            if isinstance(error, output.Terminated) and unfinished:
                note = unfinished()
                if note:
                    _say(printable(note))
            return
        interrupted = isinstance(error, (KeyboardInterrupt,
                                         output.Terminated))
        if journal is None:
            if interrupted:     # else quiet: SIGTERM prints nothing else
                _say("stopped; nothing was kept: with --csv FILE --resume "
                     "every finished simulation is kept beside FILE and "
                     "the same command continues from them")
            return
        if not len(journal):
            journal.remove()
            return
        journal.close()
        if interrupted:
            _say(f"{self.output}: not written; {len(journal):,} finished "
                 f"simulations kept in {os.path.basename(journal.path)}: "
                 f"rerun the command to continue")

    def finished(self) -> None:
        """The output is in place: this command's journal, or one an
        earlier run without --resume could not continue, is obsolete."""
        if self.journal is not None:
            self.journal.remove()
            return
        if self.output is None:
            return
        from contactsep.output import locks
        from contactsep.runs.journal import store_path
        path = store_path(self.output)
        if not os.path.isdir(path):
            return
        try:
            lock = locks.take(path + ".lock", self.output)
        except InputError:
            return              # another command is continuing it
        shutil.rmtree(path, ignore_errors=True)
        locks.release(lock)
