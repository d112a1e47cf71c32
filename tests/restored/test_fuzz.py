"""Property-based tests: decks mutated at random never crash, hang or give
anything but results or a DeckError.

Each example runs in this interpreter, so a STOP or an unhandled I/O error
inside the Fortran extension would kill the test run itself; a time limit
per example (Hypothesis's deadline, and the legacy runner's own limit)
bounds every run.  Example counts are kept small so CI stays fast; set
HYPOTHESIS_PROFILE=thorough for a longer run.
"""

from __future__ import annotations

import os
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from contactsep.errors import DeckError
from contactsep.restored import cards, core, legacy, thesis_decks

settings.register_profile(
    "ci", max_examples=60, deadline=20_000, derandomize=True,
    suppress_health_check=[HealthCheck.too_slow])
settings.register_profile(
    "thorough", max_examples=2_000, deadline=60_000,
    suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

#: Seconds any one run may take (the slowest valid deck takes well under 1 s).
RUN_BOUND = 15.0

VALID = cards.format_deck([thesis_decks.thesis_data_set(0.250),
                           thesis_decks.thesis_data_set(0.500)])
LINES = VALID.split("\n")[:-1]
CARD_CHARS = st.sampled_from(
    list("0123456789 .+-EeDd") + ["\t", "\r", "A", "*", "/", ",", "\x00"])


@st.composite
def mutated_decks(draw) -> str:
    lines = list(LINES)
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(
            ["char", "insert", "delete", "swap", "truncate", "blank_field",
             "long_line", "duplicate"]))
        i = draw(st.integers(0, len(lines) - 1))
        line = lines[i]
        col = draw(st.integers(0, max(0, len(line))))
        if kind == "char":
            lines[i] = line[:col] + draw(CARD_CHARS) + line[col + 1:]
        elif kind == "insert":
            lines[i] = line[:col] + draw(CARD_CHARS) + line[col:]
        elif kind == "delete":
            lines[i] = line[:col] + line[col + 1:]
        elif kind == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif kind == "truncate":
            lines = lines[:i]
            if not lines:
                break
        elif kind == "blank_field":
            start = 15 * (col // 15)
            lines[i] = line[:start] + " " * 15 + line[start + 15:]
        elif kind == "long_line":
            lines[i] = line.ljust(draw(st.integers(76, 120)), "9")
        elif kind == "duplicate":
            lines.insert(i, line)
    newline = draw(st.sampled_from(["\n", "\r\n", "\r"]))
    return newline.join(lines) + draw(st.sampled_from(["", newline]))


def _outcome(run):
    started = time.monotonic()
    try:
        value = run()
    except DeckError as error:
        value = error
    assert time.monotonic() - started < RUN_BOUND
    return value


@given(deck=mutated_decks(), precision=st.sampled_from(core.PRECISIONS))
def test_replay_gives_results_or_deck_error(deck, precision):
    outcome = _outcome(lambda: core.replay_text(deck, precision))
    if isinstance(outcome, DeckError):
        # the error locates itself consistently, inside the deck
        lines = deck.split("\n")
        if outcome.data_set is not None:
            assert str(outcome).startswith(f"data set {outcome.data_set}")
            assert len(outcome.partial) == outcome.data_set - 1
        if outcome.card is not None:
            assert 1 <= outcome.card <= len(lines)
            assert f"card {outcome.card}" in str(outcome)
        if outcome.columns is not None:
            first, last = outcome.columns
            assert 1 <= first <= last
        assert all(r.listing for r in outcome.partial)
    else:
        assert outcome and all(r.listing for r in outcome)


@settings(max_examples=25)
@given(deck=mutated_decks())
def test_legacy_gives_listing_or_deck_error(deck, tmp_path_factory):
    path = tmp_path_factory.mktemp("fuzz") / "deck.dat"
    path.write_bytes(deck.encode("latin-1"))
    outcome = _outcome(lambda: legacy.run(path, "single"))
    replayed = _outcome(lambda: core.replay(path, "single"))
    # the two paths agree: same listing, or an error for the same data set
    if isinstance(outcome, DeckError):
        assert isinstance(replayed, DeckError)
        assert outcome.data_set == replayed.data_set or (
            "at most 4 modes" in str(outcome))
    else:
        assert not isinstance(replayed, DeckError)
        assert outcome == "".join(r.listing for r in replayed)


@pytest.mark.parametrize("cut", range(1, 6 + 3 * 4))
def test_every_truncation_is_reported(cut):
    deck = "\n".join(LINES[:cut]) + "\n"
    with pytest.raises(DeckError, match=r"6 \+ 3N"):
        core.replay_text(deck, "single")
