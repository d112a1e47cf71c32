"""docs/reference.md's numbers of the listing's options on the thesis
decks come from docs/studies/reference_options.csv (its table and
sentences are datum roles of that file); the file is what its script
computes now, and its listing-default columns are what the restored
program (the listing, compiled in double precision) computes on the
same decks: the NumPy reference and the listing are two derivations."""

from __future__ import annotations

import csv
import subprocess
import sys

import numpy as np
import pytest

import contactsep
from conftest import ROOT

SCRIPT = ROOT / "docs" / "studies" / "make_reference_options.py"
COMMITTED = ROOT / "docs" / "studies" / "reference_options.csv"
PAGE = ROOT / "docs" / "reference.md"


def rows(text: str) -> list[dict]:
    return list(csv.DictReader(line for line in text.splitlines()
                               if not line.startswith("#")))


def test_the_committed_file_is_what_its_script_prints():
    fresh = subprocess.run([sys.executable, str(SCRIPT)], cwd=ROOT,
                           capture_output=True, text=True, check=True).stdout
    committed = COMMITTED.read_text()
    comments = [line for line in committed.splitlines() if line[:1] == "#"]
    assert comments == [line for line in fresh.splitlines()
                        if line[:1] == "#"]
    old, new = rows(committed), rows(fresh)
    assert [list(r) for r in old] == [list(r) for r in new]
    for a, b in zip(old, new):
        for key in a:
            assert float(a[key]) == pytest.approx(float(b[key]), rel=1e-10,
                                                  abs=0.0), key


@pytest.mark.parametrize("row", rows(COMMITTED.read_text()),
                         ids=lambda r: f"d{r['d_in']}")
def test_the_listing_columns_are_the_restored_programs(row):
    """The impulse and v0 to 1e-9 relative, the largest sample of the
    lower contact's history exactly the listing's grid point (the page
    quotes the listing's F15.9 digits: its agreement is 1.2e-6)."""
    deck = ROOT / "data" / "decks" / \
        f"thesis_d{round(1000 * float(row['d_in'])):04d}.dat"
    result = contactsep.replay(deck, precision="double")[0]
    assert float(row["psi_listing_lb_s"]) == pytest.approx(result.ey,
                                                           rel=1e-9)
    assert float(row["v0_listing_in_s"]) == pytest.approx(result.ty2dt,
                                                          rel=1e-9)
    k = int(np.argmax(np.abs(result.history_ty3)))
    assert float(row["grid_extreme_time_s"]) == pytest.approx(
        result.history_t[k], abs=1e-12)
    assert float(row["y3_grid_extreme_in"]) == pytest.approx(
        result.history_ty3[k], rel=1e-8)
    # the true extremum lies beyond the grid's largest sample, near it
    assert abs(float(row["y3_extreme_listing_in"])) >= \
        abs(float(row["y3_grid_extreme_in"]))
    assert abs(float(row["extreme_time_s"]) - result.history_t[k]) < \
        result.inputs.delt


def test_the_page_shows_every_deck_by_its_roles():
    text = PAGE.read_text()
    for row in rows(COMMITTED.read_text()):
        d = float(row["d_in"])
        spec = f"studies/reference_options.csv:psi_listing_lb_s@d_in={d:g}"
        assert f"| {d:.3f} | {{datum}}`{spec}:.4sci` |" in text, d
    for column in ("t_impact_s", "extreme_time_s"):
        values = {row[column] for row in rows(COMMITTED.read_text())}
        assert len(values) == 1, column      # "for every d"
        assert f"reference_options.csv:max({column})" in text
    assert "make_reference_options.py" in text
