"""The restored core (through f2py) prints what the original program prints,
byte for byte, in both precisions; its dataclasses hold the printed numbers.

The oracle is the transcribed program itself (`contactsep legacy`); for
N > 4, the same transcription with its DIMENSIONs enlarged, built here only
for these tests with the flags meson uses.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import (
    PRECISIONS,
    ROOT,
    THESIS_DECKS,
    variant_data_sets,
    with_modes,
    write_deck,
)
from contactsep.restored import cards, core, legacy, listing, thesis_decks

WIDE_DIMENSION = 8


@pytest.fixture(scope="session")
def wide_legacy(tmp_path_factory) -> dict[str, Path]:
    """appg.f with DIMENSION (4) -> (8): the oracle for N = 5..8."""
    gfortran = shutil.which("gfortran")
    if gfortran is None:
        pytest.skip("needs gfortran")
    source = (ROOT / "fortran" / "legacy" / "appg.f").read_text()
    wide = "\n".join(
        re.sub(r"\(4(,6)?\)", lambda m: f"({WIDE_DIMENSION}{m.group(1) or ''})",
               line) if line.lstrip().startswith("DIMENSION") else line
        for line in source.splitlines()) + "\n"
    assert wide.count(f"({WIDE_DIMENSION})") == 32      # + B1(8,6)
    assert wide.count(f"({WIDE_DIMENSION},6)") == 1
    directory = tmp_path_factory.mktemp("wide_legacy")
    (directory / "appg8.f").write_text(wide)
    programs = {}
    for precision in PRECISIONS:
        exe = directory / f"appg8-{precision}"
        extra = ["-fdefault-real-8"] if precision == "double" else []
        subprocess.run(
            [gfortran, "-std=legacy", "-O2", "-fno-tree-vectorize",
             "-ffp-contract=off", *extra, "-o", str(exe),
             str(directory / "appg8.f")], check=True)
        programs[precision] = exe
    return programs


def replayed(path: Path, precision: str) -> str:
    return "".join(r.listing for r in core.replay(path, precision))


@pytest.mark.parametrize("deck", THESIS_DECKS, ids=lambda p: p.stem)
def test_thesis_decks_byte_identical(deck, precision):
    assert replayed(deck, precision) == legacy.run(deck, precision)


@pytest.mark.parametrize("name", sorted(variant_data_sets()))
def test_generated_decks_byte_identical(name, precision, tmp_path):
    deck = write_deck(tmp_path, name, variant_data_sets()[name])
    assert replayed(deck, precision) == legacy.run(deck, precision)


def test_long_search_and_history_byte_identical(precision, tmp_path):
    """DELT = 2e-6 s: a search of thousands of lines (the core's trace
    room grows from 64 rows by doubling; the listing is reserved once
    the search is done) and 30,000 history lines, against the original
    program; the tables come back at exactly their length."""
    lines = THESIS_DECKS[0].read_text().split("\n")
    lines[3] = "    0.000002000" + lines[3][15:]
    deck = tmp_path / "long.dat"
    deck.write_text("\n".join(lines))
    results = core.replay(deck, precision)
    assert "".join(r.listing for r in results) == legacy.run(deck, precision)
    r = results[0]
    assert len(r.trace_t) > 64 * 2**6
    assert len(r.trace_t) == len(r.trace_ty) == len(r.trace_tydtl)
    # (T accumulated in float32 runs ahead: a few lines fewer there)
    assert len(r.history_t) == len(r.history_ty3) > 0.999 * 0.06 / 2e-6
    lean = core.solve(r.inputs, precision, listing=False)
    assert lean.listing == ""
    np.testing.assert_array_equal(lean.trace_ty, r.trace_ty)
    np.testing.assert_array_equal(lean.history_ty3, r.history_ty3)


@pytest.mark.parametrize("n", [5, 6, 8])
def test_more_modes_than_the_listing_holds(n, precision, tmp_path,
                                           wide_legacy):
    base = thesis_decks.thesis_data_set(0.350)
    deck = write_deck(tmp_path, f"n{n}", [with_modes(base, n)])
    expected = legacy.run(deck, precision, max_modes=WIDE_DIMENSION,
                          program=wide_legacy[precision])
    assert replayed(deck, precision) == expected
    assert listing.parse(expected)[0].n == n


def _thesis_text() -> str:
    return cards.format_deck([thesis_decks.thesis_data_set(0.5),
                              thesis_decks.thesis_data_set(0.125)])


def _without_decimal_points(text: str) -> str:
    """Every F15.9 field rewritten without its point: '   19.000000000'
    becomes '    19000000000', which F15.9 reads as 19 (9 implied
    decimals)."""
    out = []
    for number, line in enumerate(text.split("\n")):
        if number % 18 == 4 or not line:   # card 5 is E15.9,I2
            out.append(line)
            continue
        fields = [line[i:i + 15] for i in range(0, len(line), 15)]
        out.append("".join(f.replace(".", "").rjust(15) for f in fields))
    return "\n".join(out)


def _modulus_as_typed(text: str) -> str:
    """Card 5 with E typed by hand: '10.0E6' right-justified."""
    lines = text.split("\n")
    for number in range(4, len(lines), 18):
        if lines[number]:
            lines[number] = "10.0E6".rjust(15) + lines[number][15:]
    return "\n".join(lines)


@pytest.mark.parametrize("form", [
    "no_decimal_points", "modulus_as_typed", "crlf", "trailing_blank_lines",
    "sequence_numbers"])
def test_card_forms_byte_identical(form, precision, tmp_path):
    text = _thesis_text()
    if form == "no_decimal_points":
        text = _without_decimal_points(text)
    elif form == "modulus_as_typed":
        text = _modulus_as_typed(text)
    elif form == "crlf":
        text = text.replace("\n", "\r\n")
    elif form == "trailing_blank_lines":
        text += "\n\n   \n"
    elif form == "sequence_numbers":   # columns 76-80 are never read
        text = "\n".join(line.ljust(75) + f"{i:05d}" if line else line
                         for i, line in enumerate(text.split("\n")))
    deck = tmp_path / f"{form}.dat"
    deck.write_bytes(text.encode("ascii"))
    plain = tmp_path / "plain.dat"
    plain.write_text(_thesis_text())
    assert cards.read_deck(deck) == cards.read_deck(plain)
    assert replayed(deck, precision) == legacy.run(deck, precision)
    assert replayed(deck, precision) == replayed(plain, precision)


def _printed(value: float) -> float:
    try:
        return float(cards.format_f(value))
    except ValueError:      # gfortran prints asterisks
        return float("nan")


def test_dataclass_holds_the_printed_numbers(precision):
    """Every field, written with F15.9, is the listing's number."""
    for result in core.replay(THESIS_DECKS[0], precision):
        out = listing.parse(result.listing)[0]
        pairs = [
            (result.p, out.modal_table[:, 3]), (result.ape, out.modal_table[:, 4]),
            (result.trace_t, out.trace[:, 0]), (result.trace_ty, out.trace[:, 1]),
            (result.trace_tydtl, out.trace[:, 2]),
            ([result.t_impact, result.ey, result.ct, result.ct2, result.ct3],
             out.impact),
            (result.a1, out.coefficients[:, 0]), (result.b1, out.coefficients[:, 1]),
            ([result.tip_ty, result.tip_tydtl, result.tip_act], out.tip[1:]),
            ([result.ty2dt], [out.ty2dt]),
            (result.history_t, out.history[:, 0]),
            (result.history_ty3, out.history[:, 1]),
            (result.p2, out.separator_modes[:, 3]),
            (result.p3, out.lower_modes[:, 3]),
            ([result.wm, result.wm2, result.wm3], out.masses[:3]),
            ([result.gr, result.beta, result.mr1, result.mr3], out.ratios),
        ]
        for values, printed in pairs:
            np.testing.assert_array_equal(
                [_printed(v) for v in np.asarray(values, dtype=np.float64)],
                printed)
        dtype = np.float32 if precision == "single" else np.float64
        assert result.p.dtype == dtype and result.history_ty3.dtype == dtype
        assert result.precision == precision


def test_solve_takes_parameters_directly(precision):
    """The designer's call: a DataSet, no deck file, same numbers."""
    deck_result = core.replay(THESIS_DECKS[0], precision)[0]
    direct = core.solve(deck_result.inputs, precision)
    assert direct.listing == deck_result.listing
    thicker = core.solve(deck_result.inputs.replace(h2=0.5, xl2c=4.07),
                         precision)
    assert abs(thicker.ty2dt) < abs(direct.ty2dt)


def test_results_are_frozen():
    result = core.replay(THESIS_DECKS[0])[0]
    with pytest.raises(AttributeError):
        result.ey = 0.0


def contactsep_cli(*args):
    return subprocess.run([sys.executable, "-m", "contactsep", *args],
                          capture_output=True, text=True, timeout=300)


def test_cli_replay_equals_cli_legacy(precision):
    deck = str(THESIS_DECKS[0])
    replay = contactsep_cli("replay", deck, "--precision", precision)
    old = contactsep_cli("legacy", deck, "--precision", precision)
    assert replay.returncode == old.returncode == 0
    assert replay.stdout == old.stdout and replay.stderr == ""


def test_cli_replay_output_file(tmp_path):
    deck, target = str(THESIS_DECKS[0]), tmp_path / "listing.txt"
    done = contactsep_cli("replay", deck, "-o", str(target))
    assert done.returncode == 0 and done.stdout == ""
    assert target.read_text() == legacy.run(deck, "single")

