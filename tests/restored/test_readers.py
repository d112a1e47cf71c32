"""The two card readers (the core's Fortran one and the pure-Python one)
read every deck to the same numbers, under both blank rules."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from conftest import THESIS_DECKS, variant_data_sets, write_deck
from contactsep.errors import DeckError
from contactsep.restored import cards, core, thesis_decks


def fortran_read(path, precision="double", blank="null"):
    return [item.data_set for item in core.iter_deck(
        core.read_text(path), precision=precision, blank=blank)]


def all_decks(tmp_path):
    decks = list(THESIS_DECKS)
    for name, data_sets in variant_data_sets().items():
        decks.append(write_deck(tmp_path, name, data_sets))
    return decks


@pytest.mark.parametrize("blank", core.BLANK_MODES)
def test_fortran_and_python_readers_agree(tmp_path, blank):
    for deck in all_decks(tmp_path):
        python_sets = cards.read_deck(deck, blank=blank)
        assert fortran_read(deck, "double", blank) == python_sets, deck.name
        # single precision: the Fortran reader rounds each decimal field to
        # float32 directly; none of these fields lies at a tie between two
        # float32 values, so rounding it to float64 first changes nothing
        for single, exact in zip(fortran_read(deck, "single", blank),
                                 python_sets):
            for field in dataclasses.fields(exact):
                value = getattr(exact, field.name)
                expected = value if field.name == "n" else \
                    np.float32(value).astype(np.float64)
                np.testing.assert_array_equal(getattr(single, field.name),
                                              expected, err_msg=field.name)


# One card 1, with field 2 (columns 16-30) typed in various ways, and the
# value each blank rule gives (Fortran 77, 13.5.9 BN/BZ; checked against
# gfortran reading a file in tests/restored/test_cards.py).
FIELD_CASES = [
    # field text,          BN value,   BZ value
    ("    2.000000000", 2.0, 2.0),
    ("    2 .00000000", 2.0, 20.0),
    ("2.0            ", 2.0, 2.0),       # blanks after the point: zeros
    ("             20", 20e-9, 20e-9),    # implied decimal point
    ("20             ", 20e-9, 20e-9 * 1e13),
    ("  -1 5.25      ", -15.25, -105.25),
]


@pytest.mark.parametrize("field,bn,bz", FIELD_CASES)
def test_blank_rule(tmp_path, field, bn, bz):
    text = cards.format_deck([thesis_decks.thesis_data_set(0.25)])
    lines = text.split("\n")
    lines[0] = lines[0][:15] + field + lines[0][30:]
    deck = tmp_path / "deck.dat"
    deck.write_text("\n".join(lines))
    for blank, expected in (("null", bn), ("zero", bz)):
        assert cards.read_deck(deck, blank=blank)[0].b == pytest.approx(
            expected, rel=1e-15)
        if expected <= 0:
            # the Python reader only reads; the core also checks ranges
            with pytest.raises(DeckError, match="card 1, columns 16-30: "
                               r"found '-1 ?5\.25', expected a positive "
                               "width"):
                fortran_read(deck, blank=blank)
            continue
        assert fortran_read(deck, blank=blank)[0].b == pytest.approx(
            expected, rel=1e-15)


def test_replay_honours_the_blank_option(tmp_path):
    text = cards.format_deck([thesis_decks.thesis_data_set(0.25)])
    lines = text.split("\n")
    lines[0] = lines[0][:15] + "    2 .00000000" + lines[0][30:]
    deck = tmp_path / "deck.dat"
    deck.write_text("\n".join(lines))
    bn = core.replay(deck, blank="null")[0]
    bz = core.replay(deck, blank="zero")[0]
    assert bn.inputs.b == 2.0 and bz.inputs.b == 20.0
    assert bn.listing != bz.listing


def test_data_set_with_modes_and_a_clear_replace_message():
    import numpy as np
    import pytest

    from contactsep import beams
    from contactsep.restored import thesis_decks

    ds = thesis_decks.thesis_data_set(0.25)
    three = ds.with_modes(3)
    assert three.n == 3 and three.h2 == ds.h2 and three.xl2c == ds.xl2c
    assert np.array_equal(three.v, beams.eigenvalues("cantilever", 3))
    assert np.array_equal(three.c2, beams.midspan_values(3))
    with pytest.raises(ValueError, match=r"with_modes\(3\)"):
        ds.replace(n=3)
    # changing N together with the mode arrays stays possible
    assert ds.replace(n=3, **{k: v for k, v in
                              thesis_decks.mode_constants(3).items()
                              if k != "n"}) == three
