"""`contactsep compare` passes on the thesis decks and generated decks, and
fails when an implementation is wrong."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import pytest

from conftest import THESIS_DECKS, variant_data_sets, write_deck
from contactsep.restored import compare, reference


@pytest.mark.parametrize("deck", THESIS_DECKS, ids=lambda p: p.stem)
def test_thesis_decks_within_tolerance(deck):
    report = compare.compare_deck(deck)
    assert report.error is None
    assert report.tables and report.passed, report.text


@pytest.mark.parametrize("name", sorted(variant_data_sets()))
def test_generated_decks_within_tolerance(name, tmp_path):
    deck = write_deck(tmp_path, name, variant_data_sets()[name])
    report = compare.compare_deck(deck)
    assert len(report.tables) == len(variant_data_sets()[name])
    assert report.passed, report.text


def test_more_modes_than_the_original_holds(tmp_path):
    """N = 6: the original program cannot run it (DIMENSION 4), the other
    three implementations are still compared."""
    from conftest import with_modes
    from contactsep.restored import thesis_decks

    deck = write_deck(tmp_path, "n6", [with_modes(thesis_decks.thesis_data_set(0.5),
                                                  6)])
    report = compare.compare_deck(deck)
    rows = report.tables[0][1]
    assert report.passed and report.error is None
    assert [r.name for r in rows].count("A_6") == 1
    assert all(r.legacy_single is None for r in rows)
    assert "n/a" in report.text


@pytest.mark.parametrize("name,changes", [
    # the listing finds its impact 4 periods in: the reference must look
    # that far too (it used to give up and raise)
    ("late_impact", dict(h2=0.125, xl2c=3.6, delt=0.0002,
                         dely=-0.498869481)),
    # history times drift in float32 over 6000 additions of DELT
    ("fine_step", dict(h2=0.125, xl2c=3.6, delt=0.00001)),
    # a short contact: P2, P3 too wide for F15.9 print as asterisks
    ("asterisks", dict(xl=2.0, xl3=2.0)),
])
def test_awkward_valid_decks_compare(name, changes, tmp_path):
    from contactsep.restored import thesis_decks

    deck = write_deck(tmp_path, name,
                      [thesis_decks.thesis_data_set(0.25).replace(**changes)])
    report = compare.compare_deck(deck)
    assert report.error is None and not report.notes
    assert report.passed, report.text


def test_many_modes_fail_rather_than_pass_vacuously(tmp_path):
    """N = 20: the listing's D1-D8 amplitudes lose every digit past mode
    ~10 even in double; compare must say so, not widen its tolerance."""
    from conftest import with_modes
    from contactsep.restored import thesis_decks

    deck = write_deck(tmp_path, "n20", [with_modes(thesis_decks.thesis_data_set(
        0.25), 20)])
    report = compare.compare_deck(deck)
    failed = {r.name for _, rows in report.tables for r in rows
              if not r.passed}
    assert not report.passed and "A_20" in failed and "A_1" not in failed
    assert all(r.tol_double <= compare.MAX_DOUBLE_RTOL + 1e-7
               for _, rows in report.tables for r in rows
               if r.name.startswith("A_"))


def test_a_wrong_implementation_is_caught(monkeypatch):
    """An impulse 1e-6 off in the reference must fail the comparison."""
    real_run = reference.run

    def slightly_wrong(data_set, **options):
        result = real_run(data_set, **options)
        return dataclasses.replace(result, ey=result.ey * (1 + 1e-6))

    monkeypatch.setattr(reference, "run", slightly_wrong)
    report = compare.compare_deck(THESIS_DECKS[0])
    failed = [row.name for _, rows in report.tables for row in rows
              if not row.passed]
    assert set(failed) == {"impulse"} and len(failed) == len(report.tables)
    assert not report.passed


def test_a_short_history_is_caught(monkeypatch):
    """A restored history one line shorter than the legacy one fails."""
    from contactsep.restored import core, listing
    real_solve = core.solve

    def short(data_set, precision="single", **kw):
        result = real_solve(data_set, precision, **kw)
        if precision != "single":
            return result
        lines = result.listing.splitlines(keepends=True)
        # drop one history line: the restored history is the run of
        # 2-field lines after the closing table
        parsed = listing.parse(result.listing)[0]
        last = f"{parsed.history[-1, 0]:15.9f}"
        index = max(i for i, line in enumerate(lines)
                    if line.startswith(last))
        del lines[index]
        return dataclasses.replace(result, listing="".join(lines))

    monkeypatch.setattr(core, "solve", short)
    report = compare.compare_deck(THESIS_DECKS[0])
    assert not report.passed
    assert any("history has" in note for _, note in report.notes)


def cli(*args):
    return subprocess.run([sys.executable, "-m", "contactsep", *args],
                          capture_output=True, text=True, timeout=300)


def test_cli_exit_status_and_table():
    done = cli("compare", str(THESIS_DECKS[0]))
    assert done.returncode == 0, done.stdout + done.stderr
    assert "legacy single" in done.stdout and "numpy dbl" in done.stdout
    assert done.stdout.rstrip().endswith("0 outside")
