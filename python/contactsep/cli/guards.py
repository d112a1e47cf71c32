"""Guards and shared options of the study and sweep commands (issue 31):
a --design file's echoes of defaults the command does not read, an
--out folder that will be made, a sweep writer whose write errors name
its file, the outputs checked before any work, and --backend."""

from __future__ import annotations

import argparse
import os

from contactsep import output
from contactsep.cli.design_options import fields_from_file
from contactsep.errors import InputError


def drop_echoes(args, overrides: dict, unused) -> dict:
    """``overrides`` less the fields in ``unused`` (fields the command
    does not read) that only the --design file gave, at the thesis rig's
    default: a file from ``contactsep model --json`` lists every field,
    and its echo of a default changes nothing.  A value the user set
    (another value, or on the command line) stays, to be refused."""
    from contactsep.model import thesis_design
    rig = thesis_design()
    return {k: v for k, v in overrides.items() if not (
        k in unused and k in fields_from_file(args)
        and _same(v, getattr(rig, k)))}


def _same(value, default) -> bool:
    try:
        return bool(value == default)
    except (TypeError, ValueError):
        return False


def check_creatable(path: str) -> None:
    """The folder ``path`` (not there yet) can be made: its nearest
    existing ancestor is a writable directory."""
    parent = os.path.dirname(os.path.abspath(path))
    while not os.path.exists(parent):
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent) or not os.access(parent, os.W_OK
                                                  | os.X_OK):
        raise InputError(f"--out {path}: cannot be made in {parent} (not "
                         f"a writable directory)")


class NamedWriter:
    """A sweep's writer whose write errors name its file: a full disk
    with --csv and --parquet said only 'No space left on device' (issue
    31).  Everything else goes to the writer."""

    def __init__(self, writer, option: str, path: str) -> None:
        self._writer, self._option, self._path = writer, option, path

    def __getattr__(self, name):
        return getattr(self._writer, name)

    def _named(self, error: OSError) -> OSError:
        if error.filename is not None or error.strerror is None:
            return error
        return OSError(error.errno, f"{self._option}: {error.strerror}",
                       self._path)

    def write(self, columns) -> None:
        try:
            self._writer.write(columns)
        except OSError as error:
            raise self._named(error) from None

    def close(self, *args, **kwargs) -> None:
        try:
            self._writer.close(*args, **kwargs)
        except OSError as error:
            raise self._named(error) from None


def add_backend_option(parser: argparse.ArgumentParser) -> None:
    """--backend: the compiled batch or its NumPy twin."""
    parser.add_argument("--backend", choices=("compiled", "numpy"),
                        default=None,
                        help="compiled: the Fortran batch (default); "
                             "numpy: its NumPy twin")


def check_targets(args: argparse.Namespace, targets: dict) -> None:
    """Before any work: the outputs (option -> path) can be written, no
    two are one file, none is the --design file the command reads."""
    design = getattr(args, "design", None)
    output.check_targets(targets, {"--design": design} if design else {})
