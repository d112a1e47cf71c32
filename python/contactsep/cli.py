"""The ``contactsep`` command.

``contactsep legacy DECK``   run the original program (Appendix G) on a deck
``contactsep replay DECK``   run the restored core; same listing, byte for byte
``contactsep compare DECK``  all implementations side by side, with tolerances

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
import signal
import sys
import warnings
from pathlib import Path
from typing import Sequence

from contactsep import core, formats, output
from contactsep.errors import DeckError, InputError
from contactsep.legacy import LegacyError

EXIT_OK, EXIT_TOLERANCE, EXIT_ERROR = 0, 1, 2
#: Exit status when whoever reads the listing stops reading (| head): the
#: shell's status for a process ended by SIGPIPE.
EXIT_BROKEN_PIPE = 128 + 13
#: Exit statuses after SIGINT (Ctrl-C) and SIGTERM, as the shell reports
#: a process they end.
EXIT_INTERRUPTED = 128 + signal.SIGINT
EXIT_TERMINATED = 128 + signal.SIGTERM


def _precision(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--precision", choices=core.PRECISIONS, default="single",
        help="single: the listing's REAL (default); double: "
             "the -fdefault-real-8 build")


def _blank(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--blank", choices=core.BLANK_MODES, default="null",
        help="blanks inside a numeric field: null = ignored (BN, default, "
             "what the original program does under gfortran); zero = read "
             "as zeros (BZ, as on the original card readers)")


def _version() -> str:
    from contactsep import __version__
    return __version__


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="contactsep",
        description="Contact separation due to impact in a redundant "
                    "contact system: the thesis program of Appendix G.")
    parser.add_argument("--version", action="version",
                        version=f"%(prog)s {_version()}")
    commands = parser.add_subparsers(dest="command", required=True,
                                     metavar="COMMAND")

    legacy = commands.add_parser(
        "legacy", help="run the original program on a card deck",
        description="Feed the deck to the transcribed Appendix G program on "
                    "standard input and print its listing unchanged.")
    legacy.add_argument("deck", help="card-image deck (6 + 3N cards per "
                                     "data set)")
    _precision(legacy)

    replay = commands.add_parser(
        "replay", help="run the restored core on a card deck",
        description="Print the listing the restored Fortran core writes for "
                    "the deck (identical to `contactsep legacy`).")
    replay.add_argument("deck")
    _precision(replay)
    _blank(replay)
    replay.add_argument("-o", "--output", metavar="FILE",
                        help="write the listing to FILE instead of stdout")
    replay.add_argument(
        "--format", choices=("listing", "summary", "json", "csv"),
        default="listing",
        help="listing (default: the program's, byte-identical), summary "
             "(every number with name, unit, meaning), json (one object "
             "per data set and line), csv (one row per data set)")

    compare = commands.add_parser(
        "compare", help="compare all implementations on a deck",
        description="For each data set, a table of the key results from the "
                    "legacy program, the restored core (single and double) "
                    "and the NumPy reference, with relative differences and "
                    "tolerances. Exit status 1 if any is out of tolerance.")
    compare.add_argument("deck")
    for layer in _LAYERS:
        importlib.import_module(f"contactsep.{layer}.cli").register(commands)
    return parser


#: Layers beside the restoration; each module ``contactsep.<layer>.cli``
#: registers its own subcommands.
_LAYERS = ("model", "studies", "chatter")


class CommandError(InputError):
    """A request the command refuses (not a problem with the deck)."""


def _legacy(args: argparse.Namespace) -> int:
    from contactsep import legacy

    sys.stdout.flush()
    try:
        legacy.run(Path(args.deck), args.precision, stream=sys.stdout.buffer)
    finally:
        sys.stdout.buffer.flush()
    return EXIT_OK


def _replay(args: argparse.Namespace) -> int:
    deck = Path(args.deck)
    if args.output is None:
        for index, result in enumerate(core.iter_replay(
                deck, args.precision, blank=args.blank), 1):
            output.write_text(sys.stdout,
                              formats.render(result, args.format, index))
            sys.stdout.flush()
        return EXIT_OK
    target = Path(args.output)
    if target.exists() and target.samefile(args.deck):
        raise CommandError(f"will not write the listing over the deck "
                           f"{args.deck}")
    with output.open_output(args.output) as out:
        for index, result in enumerate(core.iter_replay(
                deck, args.precision, blank=args.blank), 1):
            output.write_text(out, formats.render(result, args.format,
                                                  index))
    return EXIT_OK


def _compare(args: argparse.Namespace) -> int:
    from contactsep import compare

    report = compare.compare_deck(Path(args.deck), stream=sys.stdout)
    if report.error is not None:
        raise report.error
    return EXIT_OK if report.passed else EXIT_TOLERANCE


def _one_line_warning(message, category, filename, lineno, file=None,
                      line=None) -> None:
    """Warnings as one line on stderr: ``contactsep: warning: ...``."""
    print(f"contactsep: warning: {message}", file=sys.stderr)


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
    args = parser.parse_args(argv)
    warnings.showwarning = _one_line_warning
    handler = getattr(args, "handler", None) or {
        "legacy": _legacy, "replay": _replay,
        "compare": _compare}[args.command]
    try:
        status = handler(args)
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
