"""A command run in a forked child that kills or stops itself at a
chosen moment: the state on disk of a command killed there (SIGKILL: no
clean-up of any kind) or stopped by SIGTERM (its own handler runs).
Shared by the tests of the resumable sweeps, searches and studies."""

from __future__ import annotations

import os
import signal
import sys

from contactsep.cli import main
from contactsep.runs.journal import RunJournal


def _in_child(patch, args, stderr=None) -> int:
    """Run ``main(args)`` in a forked child after ``patch()``, stdout
    (and stderr, unless it goes to the file ``stderr``) to /dev/null;
    the child's wait status."""
    pid = os.fork()
    if pid == 0:
        status = 3
        try:
            patch()
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, 1)
            if stderr is None:
                os.dup2(devnull, 2)
            else:
                sys.stderr = open(stderr, "w", encoding="utf-8")
            status = main(list(args))
            sys.stderr.flush()
        finally:
            os._exit(status)
    _, code = os.waitpid(pid, 0)
    return code


def on_call(owner, name: str, count: int, action, after: bool = False):
    """A patch of ``owner.name`` that calls ``action(self, args)`` at its
    ``count``-th call (before the call, or ``after`` it)."""
    def patch():
        calls = [0]
        original = getattr(owner, name)

        def counted(self, *args, **kwargs):
            calls[0] += 1
            if after:
                out = original(self, *args, **kwargs)
            if calls[0] == count:
                action(self, args)
            return out if after else original(self, *args, **kwargs)
        setattr(owner, name, counted)
    return patch


def sigkill(self, args) -> None:
    os.kill(os.getpid(), signal.SIGKILL)


def killed_at(args, owner, name: str, count: int, action=sigkill) -> None:
    """Run the command ``args`` in a forked child that SIGKILLs itself at
    the ``count``-th call of ``owner.name`` (``action``: what it does
    first, then kills)."""
    code = _in_child(on_call(owner, name, count, action), args)
    assert os.WIFSIGNALED(code) and os.WTERMSIG(code) == signal.SIGKILL


def terminated_at(args, owner, name: str, count: int, stderr) -> None:
    """Run the command ``args`` in a forked child that sends itself
    SIGTERM after the ``count``-th call of ``owner.name``, its stderr to
    the file ``stderr``; the command's own handler exits 143."""
    code = _in_child(on_call(owner, name, count, lambda self, args: os.kill(
        os.getpid(), signal.SIGTERM), after=True), args, stderr)
    assert os.WIFEXITED(code) and os.WEXITSTATUS(code) == 143


def terminated_then_resumed(command, path, count: int) -> None:
    """The resumable command ``command`` (its CSV at ``path``, with
    ``--resume``) stopped by SIGTERM after its ``count``-th finished
    simulation: no CSV, one line on stderr naming the journal beside it
    and what it holds; the same command run again finishes it, writes
    the CSV and removes the journal."""
    err = path.parent / "terminated-stderr.txt"
    journal = path.parent / f".{path.name}.resume"
    terminated_at(command, RunJournal, "record", count, err)
    kept = len((journal / "runs.jsonl").read_text().splitlines())
    assert kept >= count
    assert err.read_text() == (f"contactsep: {path}: not written; {kept} "
                               f"finished simulations kept in "
                               f"{journal.name}: rerun the command to "
                               f"continue\n")
    assert not path.exists()
    assert main(command) == 0 and path.exists()
    assert not journal.exists()
