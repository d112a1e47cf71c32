"""The ``contactsep`` command.

``contactsep legacy DECK``   run the original program (Appendix G) on a deck
``contactsep replay DECK``   run the restored core; same listing, byte for byte
``contactsep compare DECK``  all implementations side by side, with tolerances

Errors are reported as ``contactsep: error: <message>`` on stderr with exit
status 2; listings of the data sets before a bad one are printed first.
"""

from __future__ import annotations

import argparse
import sys
from typing import Sequence

from contactsep import core
from contactsep.errors import DeckError
from contactsep.legacy import LegacyError

EXIT_OK, EXIT_TOLERANCE, EXIT_ERROR = 0, 1, 2


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


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="contactsep",
        description="Contact separation due to impact in a redundant "
                    "contact system: the thesis program of Appendix G.")
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

    compare = commands.add_parser(
        "compare", help="compare all implementations on a deck",
        description="For each data set, a table of the key results from the "
                    "legacy program, the restored core (single and double) "
                    "and the NumPy reference, with relative differences and "
                    "tolerances. Exit status 1 if any is out of tolerance.")
    compare.add_argument("deck")
    return parser


def _legacy(args: argparse.Namespace) -> int:
    from contactsep import legacy

    try:
        listing = legacy.run(args.deck, args.precision)
    except DeckError as error:
        sys.stdout.write(error.listing_before)
        raise
    sys.stdout.write(listing)
    return EXIT_OK


def _replay(args: argparse.Namespace) -> int:
    out = open(args.output, "w", encoding="ascii", newline="") \
        if args.output else sys.stdout
    try:
        try:
            results = core.replay(args.deck, args.precision, blank=args.blank)
        except DeckError as error:
            out.write("".join(r.listing for r in error.partial))
            raise
        out.write("".join(r.listing for r in results))
    finally:
        if out is not sys.stdout:
            out.close()
    return EXIT_OK


def _compare(args: argparse.Namespace) -> int:
    from contactsep import compare

    report = compare.compare_deck(args.deck)
    sys.stdout.write(report.text)
    if report.error is not None:
        raise report.error
    return EXIT_OK if report.passed else EXIT_TOLERANCE


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contactsep`` command; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    handler = {"legacy": _legacy, "replay": _replay,
               "compare": _compare}[args.command]
    try:
        status = handler(args)
        sys.stdout.flush()
        return status
    except (DeckError, LegacyError, OSError) as error:
        sys.stdout.flush()
        if isinstance(error, OSError) and error.filename:
            message = f"{error.strerror}: {error.filename}"
        else:
            message = str(error)
        print(f"{parser.prog}: error: {message}", file=sys.stderr)
        return EXIT_ERROR
