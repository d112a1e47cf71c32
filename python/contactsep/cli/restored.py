"""``contactsep legacy``, ``replay`` and ``compare``: the Appendix G
restoration's commands."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from contactsep import output
from contactsep.cli.help import examples
from contactsep.errors import InputError
from contactsep.restored import core, formats

EXIT_OK, EXIT_TOLERANCE = 0, 1


class CommandError(InputError):
    """A request the command refuses (not a problem with the deck)."""


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


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep legacy``, ``replay`` and ``compare``."""
    legacy = commands.add_parser(
        "legacy", help="run the original program on a card deck",
        description="Feed the deck to the transcribed Appendix G program on "
                    "standard input and print its listing unchanged.",
        **examples("contactsep legacy data/decks/thesis_d0125.dat",
                   "contactsep legacy data/decks/thesis_all.dat "
                   "--precision double > listing.txt"))
    legacy.set_defaults(handler=_legacy)
    legacy.add_argument("deck", help="card-image deck (6 + 3N cards per "
                                     "data set)")
    _precision(legacy)

    replay = commands.add_parser(
        "replay", help="run the restored core on a card deck",
        description="Print the listing the restored Fortran core writes for "
                    "the deck (identical to `contactsep legacy`), or its "
                    "numbers labelled (summary) or as data (jsonl, csv).",
        **examples("contactsep replay data/decks/thesis_all.dat -o "
                   "listing.txt",
                   "contactsep replay data/decks/thesis_all.dat --format "
                   "csv > results.csv",
                   "cat data/decks/thesis_d0250.dat | contactsep replay - "
                   "--format summary"))
    replay.add_argument("deck", help="card-image deck, or - for standard "
                                     "input")
    _precision(replay)
    _blank(replay)
    replay.add_argument("-o", "--output", metavar="FILE",
                        help="write the listing to FILE instead of stdout")
    replay.add_argument(
        "--format", choices=formats.FORMATS, default="listing",
        help="listing (default: the program's, byte-identical), summary "
             "(every number with name, unit, meaning), jsonl (JSON lines: "
             "one object per data set and line), csv (one row per data "
             "set, the thickness d_in and N first); keys carry units")

    compare = commands.add_parser(
        "compare", help="compare all implementations on a deck",
        description="For each data set, a table of the key results from the "
                    "legacy program, the restored core (single and double) "
                    "and the NumPy reference, with relative differences and "
                    "tolerances. Exit status 1 if any is out of tolerance.",
        **examples("contactsep compare data/decks/thesis_d0500.dat",
                   "contactsep compare data/decks/thesis_all.dat || echo "
                   "out of tolerance"))
    compare.add_argument("deck")
    replay.set_defaults(handler=_replay)
    compare.set_defaults(handler=_compare)


def _legacy(args: argparse.Namespace) -> int:
    from contactsep.restored import legacy

    sys.stdout.flush()
    try:
        legacy.run(Path(args.deck), args.precision, stream=sys.stdout.buffer)
    finally:
        sys.stdout.buffer.flush()
    return EXIT_OK


def _replay(args: argparse.Namespace) -> int:
    # "-": the deck from standard input, read a data set at a time
    deck = sys.stdin.buffer if args.deck == "-" else Path(args.deck)
    if args.output is None:
        for index, result in enumerate(core.iter_replay(
                deck, args.precision, blank=args.blank), 1):
            output.write_text(sys.stdout,
                              formats.render(result, args.format, index))
            sys.stdout.flush()
        return EXIT_OK
    target = Path(args.output)
    if args.deck != "-" and target.exists() and target.samefile(args.deck):
        raise CommandError(f"will not write the listing over the deck "
                           f"{args.deck}")
    with output.open_output(args.output) as out:
        for index, result in enumerate(core.iter_replay(
                deck, args.precision, blank=args.blank), 1):
            output.write_text(out, formats.render(result, args.format,
                                                  index))
    return EXIT_OK


def _compare(args: argparse.Namespace) -> int:
    from contactsep.restored import compare

    report = compare.compare_deck(Path(args.deck), stream=sys.stdout)
    if report.error is not None:
        raise report.error
    if report.compared_nothing:
        raise CommandError(f"nothing compared: no data set of {args.deck} "
                           f"could be compared (the lines above say why)")
    return EXIT_OK if report.passed else EXIT_TOLERANCE


