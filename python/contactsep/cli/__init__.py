"""The ``contactsep`` command: the top layer, above the restoration, the
model, the contact dynamics and the studies.  Each layer's subcommands are
registered by a module of this package (``contactsep.cli.restored``:
legacy, replay, compare; ``.model``: model; ``.studies``: study, sweep;
``.chatter``: chatter; ``.preload``: preload; ``.report``: report).

Errors are reported as ``contactsep: error: <message>`` on stderr with exit
status 2; listings of the data sets before a bad one are printed first.
A write error (closed standard output, full disk) is such an error too;
Ctrl-C (SIGINT) ends any command with status 130 and SIGTERM with 143,
quietly.  ``-o FILE``: module :mod:`contactsep.output`.
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import signal
import sys
import warnings
from typing import Sequence

from contactsep import output
from contactsep.errors import DeckError, InputError
from contactsep.restored.legacy import LegacyError

EXIT_OK, EXIT_TOLERANCE, EXIT_ERROR = 0, 1, 2
#: Exit status when whoever reads the listing stops reading (| head): the
#: shell's status for a process ended by SIGPIPE.
EXIT_BROKEN_PIPE = 128 + 13
#: Exit statuses after SIGINT (Ctrl-C) and SIGTERM, as the shell reports
#: a process they end.
EXIT_INTERRUPTED = 128 + signal.SIGINT
EXIT_TERMINATED = 128 + signal.SIGTERM


def _version() -> str:
    from contactsep import __version__
    return __version__


class UsageError(InputError):
    """A command line argparse cannot read (an unknown option, a missing
    value, a value of the wrong type): reported as every error is, in
    one line, instead of argparse's usage and ``prog: error:`` lines."""


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors raised as :class:`UsageError` and values
    that start with a minus sign read as values when they are numbers in
    any of Python's spellings (``--d -inf``, ``--gap -1e-3``; argparse
    takes only ``-1`` and ``-.5`` and says '--d: expected one argument')."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def parse_args(self, args=None, namespace=None):
        # argparse's own, except that extra words are reported with the
        # subcommand they were given to
        args, extras = self.parse_known_args(args, namespace)
        if extras:
            command = getattr(args, "command", None)
            where = f"contactsep {command}" if command else "contactsep"
            raise UsageError((f"{command}: " if command else "")
                             + f"unrecognized arguments: {' '.join(extras)}"
                             f" ({where} --help lists the options)")
        return args

    def error(self, message: str):
        # 'argument --dt: found ...' as every other error names an
        # option: '--dt: found ...'; the rest with its subcommand
        option = re.match(r"argument (\S+?)(/\S+)?: ", message)
        if option:
            raise UsageError(f"{option.group(1)}: {message[option.end():]}")
        command = self.prog.partition(" ")[2]
        raise UsageError(f"{command}: {message}" if command else message)


_NEGATIVE_NUMBER = re.compile(
    r"^-(\d[\d_]*(\.[\d_]*)?|\.\d[\d_]*)(e[-+]?\d+)?$|^-(inf|infinity|nan)$",
    re.IGNORECASE)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="contactsep",
        description="Contact separation due to impact in a redundant "
                    "contact system: the thesis program of Appendix G.")
    parser.add_argument("--version", action="version",
                        version=f"%(prog)s {_version()}")
    commands = parser.add_subparsers(dest="command", required=True,
                                     metavar="COMMAND")

    for layer in _LAYERS:
        importlib.import_module(f"contactsep.cli.{layer}").register(commands)
    return parser


#: The commands of each layer; module ``contactsep.cli.<layer>`` registers
#: its own subcommands.
_LAYERS = ("restored", "model", "studies", "chatter", "preload", "report")


def _one_line_warning(message, category, filename, lineno, file=None,
                      line=None) -> None:
    """Warnings as one line on stderr: ``contactsep: warning: ...``, each
    text once a command (compare solved each data set twice and said
    the same twice)."""
    text = f"contactsep: warning: {output.one_line(Warning(message))}"
    if text not in _WARNED:
        _WARNED.add(text)
        print(text, file=sys.stderr)


#: The warnings this command has printed.
_WARNED: set = set()


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contactsep`` command; returns the exit status."""
    output.guard_closed_streams()
    previous = signal.getsignal(signal.SIGTERM)
    if previous in (signal.SIG_DFL, None):
        signal.signal(signal.SIGTERM, output.raise_terminated)
    try:
        return _main(argv)
    except KeyboardInterrupt:
        return output.stop_quietly(EXIT_INTERRUPTED)
    except output.Terminated:
        return output.stop_quietly(EXIT_TERMINATED)
    finally:
        if previous in (signal.SIG_DFL, None):
            signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _main(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    _WARNED.clear()
    warnings.showwarning = _one_line_warning
    try:
        args = parser.parse_args(argv)
        # the words given, for an output that names its command
        args.argv = list(sys.argv[1:] if argv is None else argv)
        status = args.handler(args)
        sys.stdout.flush()
        return status
    except BrokenPipeError:
        # Python's recipe: point stdout at devnull so the interpreter's
        # final flush does not fail again, and stop quietly.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except (DeckError, LegacyError, InputError, OSError) as error:
        try:
            sys.stdout.flush()
        except OSError as late:
            error = error if isinstance(error, OSError) else late
        output.report(parser.prog, error)
        # an interrupt that kept what it had (a sweep's written chunks)
        # still ends as Ctrl-C does
        return EXIT_INTERRUPTED if getattr(error, "interrupted", False) \
            else EXIT_ERROR
