"""Bad decks get clear errors: one case per kind of failure, through the API
and the command line (replay, legacy, compare), and nothing already
computed is lost."""

from __future__ import annotations

import subprocess
import sys

import pytest

from contactsep.errors import DeckError
from contactsep.restored import cards, core, legacy, listing, thesis_decks

GOOD = cards.format_deck([thesis_decks.thesis_data_set(0.25)]).split("\n")[:-1]
CARDS = len(GOOD)      # 18: one data set of N = 4


def put(card: int, column: int, text: str, lines=GOOD) -> list[str]:
    """The deck with `text` typed over card `card` from column `column`."""
    lines = list(lines)
    image = lines[card - 1].ljust(column - 1 + len(text))
    lines[card - 1] = (image[:column - 1] + text
                       + image[column - 1 + len(text):]).rstrip()
    return lines


# name: (deck lines, message fragment, card, columns) -- card and columns
# as DeckError reports them (None where the error has no one place).
CASES = {
    "non_numeric": (put(2, 16, "      ABC.00000"),
                    "found 'ABC.00000', expected a number (B2", 2, (16, 30)),
    "truncated": (GOOD[:11], "expected 6 + 3N = 18 cards, found 11", None,
                  None),
    "empty": ([], "no data set", None, None),
    "only_blank_lines": (["", "   ", ""], "no data set", None, None),
    "n_zero": (put(5, 16, " 0"), "expected N >= 1", 5, (16, 17)),
    "n_negative": (put(5, 16, "-3"), "expected N >= 1", 5, (16, 17)),
    "zero_length": (put(1, 1, "    0.000000000"),
                    "expected a positive length, in (XL,", 1, (1, 15)),
    "negative_width": (put(3, 16, "   -2.000000000"),
                       "expected a positive width, in (B3,", 3, (16, 30)),
    "zero_thickness": (put(2, 31, "    0.000000000"),
                       "expected a positive thickness, in (H2,", 2, (31, 45)),
    "negative_density": (put(1, 46, " -172.800000000"),
                         "expected a positive weight density", 1, (46, 60)),
    "zero_modulus": (put(5, 1, "0.000000000E+00"),
                     "expected a positive modulus, psi (E,", 5, (1, 15)),
    "zero_time_step": (put(4, 1, "    0.000000000"),
                       "expected a positive time step", 4, (1, 15)),
    "negative_time_step": (put(4, 1, "   -0.000500000"),
                           "expected a positive time step", 4, (1, 15)),
    "tiny_time_step": (put(4, 1, "    0.000000010"),
                       "at least 6.0E-8 s", 4, (1, 15)),
    "restitution_above_one": (put(4, 16, "    1.500000000"),
                              "restitution in [0, 1] (ER,", 4, (16, 30)),
    "restitution_negative": (put(4, 16, "   -0.100000000"),
                             "restitution in [0, 1] (ER,", 4, (16, 30)),
    "zero_eigenvalue": (put(12, 1, "    0.000000000"),
                        "positive eigenvalue k_jL (V2(2)", 12, (1, 15)),
    "nan": (put(1, 61, "            NaN"), "found 'NaN', expected a finite",
            1, (61, 75)),
    "infinity": (put(6, 1, "       Infinity"),
                 "found 'Infinity', expected a finite", 6, (1, 15)),
    "overflow": (put(5, 1, "       1.0E+400"),
                 "found '1.0E+400', expected a finite", 5, (1, 15)),
    "release_below_separator": (put(4, 31, "    0.600000000"),
                                "below the separator DELY", 4, (31, 45)),
    "release_at_separator": (
        put(1, 61, "    0.000000000"), "exactly at the separator DELY", 4,
        (31, 45)),
    "no_impact": (put(4, 31, "   -0.900000000"), "no impact found", 4,
                  (1, 45)),
    "line_too_long": (put(3, 76, "1234567890"),
                      "expected nothing past column 80", 3, (81, 85)),
    "tab": (put(3, 5, "\t"), "found a TAB", 3, (5, 5)),
    "non_ascii_byte": (put(2, 20, "\u00e9"), "found character 0xE9",
                       2, (20, 20)),
    "nul_byte": (put(2, 21, "\x00"), "found character 0x00 (NUL)", 2,
                 (21, 21)),
    "nul_after_the_last_card": (GOOD + ["   \x00"],
                                "found character 0x00 (NUL)", 19,
                                (4, 4)),
}


def write(tmp_path, lines, name="deck.dat"):
    """The deck file, one byte per character (latin-1)."""
    path = tmp_path / name
    path.write_bytes(("\n".join(lines) + ("\n" if lines else ""))
                     .encode("latin-1"))
    return path


#: The no-impact case runs a million search lines (~2 s); the message is
#: built by the same code for both precisions and for replay and compare,
#: so it is run once per path that differs: the API in double, the CLI of
#: replay (the restored core) and of legacy (validation before feeding).
SLOW = "no_impact"


@pytest.mark.parametrize("name, precision", [
    (name, precision) for name in sorted(CASES)
    for precision in core.PRECISIONS
    if name != SLOW or precision == "double"])
def test_replay_reports(name, precision, tmp_path):
    lines, fragment, card, columns = CASES[name]
    with pytest.raises(DeckError) as info:
        core.replay(write(tmp_path, lines), precision)
    error = info.value
    assert isinstance(error, ValueError)
    assert fragment in str(error)
    assert error.card == card and error.columns == columns
    if name not in ("empty", "only_blank_lines"):
        assert error.data_set == (2 if name == "nul_after_the_last_card"
                                  else 1)
        assert str(error).startswith(f"data set {error.data_set}")
        assert len(error.partial) == error.data_set - 1
    else:
        assert error.partial == []


def cli(*args):
    return subprocess.run([sys.executable, "-m", "contactsep", *args],
                          capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("name, command", [
    (name, command) for name in sorted(CASES)
    for command in ("replay", "legacy", "compare")
    if name != SLOW or command != "compare"])
def test_cli_reports(name, command, tmp_path):
    lines, fragment, _, _ = CASES[name]
    done = cli(command, str(write(tmp_path, lines)))
    assert done.returncode == 2, done.stdout + done.stderr
    assert done.stderr.startswith("contactsep: error: ")
    assert fragment in done.stderr
    assert "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("command", ["replay", "legacy", "compare"])
def test_missing_file(command):
    done = cli(command, "no/such/deck.dat")
    assert done.returncode == 2
    assert done.stderr.startswith("contactsep: error: No such file")


def test_output_over_the_deck_is_refused(tmp_path):
    deck = write(tmp_path, GOOD)
    before = deck.read_bytes()
    done = cli("replay", str(deck), "-o", str(deck))
    assert done.returncode == 2 and "over the deck" in done.stderr
    assert deck.read_bytes() == before


def test_output_file_keeps_what_was_computed(tmp_path):
    """A bad second data set: -o FILE still gets the first's listing."""
    deck = write(tmp_path, GOOD + CASES["non_numeric"][0])
    target = tmp_path / "listing.txt"
    done = cli("replay", str(deck), "-o", str(target))
    assert done.returncode == 2
    assert target.read_text() == core.replay(write(tmp_path, GOOD,
                                                   "good.dat"))[0].listing
    assert [p.name for p in tmp_path.iterdir()
            if p.name.startswith(".")] == []


def test_legacy_refuses_n_above_four_but_replay_runs_it(tmp_path):
    from conftest import with_modes, write_deck

    deck = write_deck(tmp_path, "n5", [with_modes(thesis_decks.thesis_data_set(0.5),
                                                  5)])
    with pytest.raises(DeckError, match="holds at most 4 modes"):
        legacy.run(deck)
    assert core.replay(deck)[0].inputs.n == 5


@pytest.mark.parametrize("name", ["non_numeric", "release_below_separator",
                                  "truncated"])
def test_nothing_already_computed_is_lost(name, tmp_path):
    """Data set 2 is bad: data set 1's listing is still printed (CLI) or
    returned (API) before the error."""
    lines, fragment, card, _ = CASES[name]
    deck = write(tmp_path, GOOD + lines)
    first = core.replay(write(tmp_path, GOOD, "good.dat"))[0]
    with pytest.raises(DeckError) as info:
        core.replay(deck)
    assert info.value.data_set == 2
    if card is not None:
        assert info.value.card == CARDS + card
    assert [r.listing for r in info.value.partial] == [first.listing]
    for command in ("replay", "legacy"):
        done = cli(command, str(deck))
        assert done.returncode == 2
        assert done.stdout == first.listing
        assert done.stderr.startswith("contactsep: error: data set 2")
    done = cli("compare", str(deck))
    assert done.returncode == 2
    assert "data set 1" in done.stdout and "data set 2" not in done.stdout


def test_legacy_is_only_fed_data_sets_that_passed(tmp_path):
    cards_fed, passed, failure = legacy.validated_cards(
        "\n".join(GOOD + CASES["no_impact"][0]) + "\n")
    assert cards_fed == "\n".join(GOOD) + "\n" and passed == 1
    assert failure is not None and failure.data_set == 2
    assert listing.parse(legacy.run_cards(cards_fed))[0].n == 4


def test_direct_call_is_validated():
    ds = thesis_decks.thesis_data_set(0.25)
    with pytest.raises(DeckError, match=r"^H2 = -0\.25.*positive thickness"):
        core.solve(ds.replace(h2=-0.25))
    with pytest.raises(DeckError, match=r"ER = 2.*restitution in \[0, 1\]"):
        core.solve(ds.replace(er=2.0), "double")
    with pytest.raises(DeckError, match=r"V3\(3\) = 0.*positive eigenvalue"):
        core.solve(ds.replace(v3=[1.875, 4.694, 0.0, 10.99]))


def test_valid_deck_unchanged_by_validation(tmp_path):
    """The thesis deck still replays to what the original program prints."""
    deck = write(tmp_path, GOOD)
    assert "".join(r.listing for r in core.replay(deck)) == \
        legacy.run_cards("\n".join(GOOD) + "\n")


@pytest.mark.parametrize("command", ["replay", "legacy"])
def test_reader_going_away_is_not_an_error(command, tmp_path):
    """`contactsep replay DECK | head`: stop quietly, as Unix tools do.
    The listing (20 data sets, ~180 kB) is far more than a pipe holds."""
    deck = write(tmp_path, GOOD * 20)
    process = subprocess.Popen(
        [sys.executable, "-m", "contactsep", command, str(deck)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    process.stdout.readline()
    process.stdout.close()
    stderr = process.stderr.read()
    assert process.wait(timeout=60) == 141
    assert stderr == b""


def test_python_and_fortran_agree_on_the_history_limit():
    """core.MAX_HISTORY_LINES is the Fortran validation's limit: a DELT
    just above TAU / limit is accepted, just below is refused."""
    ds = thesis_decks.thesis_data_set(0.25)
    smallest = core.TAU / core.MAX_HISTORY_LINES
    result = core.solve(ds.replace(delt=smallest * 1.001), "double")
    assert len(result.history_t) == pytest.approx(core.MAX_HISTORY_LINES,
                                                  rel=2e-3)
    with pytest.raises(DeckError, match="at least 6.0E-8 s"):
        core.solve(ds.replace(delt=smallest * 0.999), "double")
