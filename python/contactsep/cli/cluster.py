"""``--scheduler ADDRESS`` and ``--scheduler-file FILE``: the commands'
work on a Dask cluster (Dask's own two ways of naming a scheduler:
``distributed.Client(address)``, ``Client(scheduler_file=FILE)``).  The
connection is made once every option is checked, and closed when the
command ends (contactsep.runs.dask_run.connect: a scheduler that does
not answer is one line)."""

from __future__ import annotations

import argparse
import contextlib

from contactsep.errors import InputError


def add_cluster_options(group, what: str, address: bool = True) -> None:
    """The two options on ``group`` (``address`` False: only
    --scheduler-file, for a command that has its own --scheduler);
    ``what``: what runs on the cluster, for the help."""
    if address:
        group.add_argument("--scheduler", metavar="ADDRESS",
                           help=f"run {what} on this Dask scheduler "
                                f"(tcp://HOST:8786) instead of local "
                                f"processes")
    group.add_argument("--scheduler-file", metavar="FILE",
                       help=f"run {what} on the Dask scheduler this file "
                            f"names (dask scheduler --scheduler-file FILE "
                            f"writes it)")


def given(args: argparse.Namespace) -> bool:
    """Whether the command was given a Dask scheduler."""
    return bool(getattr(args, "scheduler", None)
                or getattr(args, "scheduler_file", None))


def check_cluster(args: argparse.Namespace, workers: bool = True) -> None:
    """One scheduler at most; ``workers``: --workers (local processes)
    refused beside one (the cluster's workers run the work)."""
    if getattr(args, "scheduler", None) and \
            getattr(args, "scheduler_file", None):
        raise InputError("--scheduler and --scheduler-file: give one "
                         "(each names a Dask scheduler)")
    if workers and given(args) and getattr(args, "workers", None) \
            is not None:
        option = "--scheduler" if args.scheduler else "--scheduler-file"
        raise InputError(f"--workers: local processes; with {option} the "
                         f"Dask cluster's workers run the simulations "
                         f"(give one of them)")


def connect(args: argparse.Namespace):
    """The Client of the scheduler the options name, or None."""
    if not given(args):
        return None
    from contactsep.runs import dask_run
    if getattr(args, "scheduler_file", None):
        return dask_run.connect(scheduler_file=args.scheduler_file)
    return dask_run.connect(args.scheduler)


@contextlib.contextmanager
def cluster(args: argparse.Namespace):
    """:func:`connect` for the block, the client closed after (quietly:
    a lost scheduler has had its one line)."""
    client = connect(args)
    try:
        yield client
    finally:
        if client is not None:
            from contactsep.runs import dask_run
            with dask_run.quiet_dask(), contextlib.suppress(Exception):
                client.close(timeout=2)
