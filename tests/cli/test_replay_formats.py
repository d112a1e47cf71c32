"""replay's data formats (issue 19, items 1 and 8): JSON lines that
json.loads reads, a CSV with the thickness, `replay -` on standard
input, and numbers with the digits of the build's precision."""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys

import numpy as np
import pytest

import contactsep
from conftest import DECK_DIR

ALL = DECK_DIR / "thesis_all.dat"
#: The thesis's five separators, in the order of thesis_all.dat (the deck
#: names say so: thesis_d0125 ... thesis_d0750).
THICKNESSES = [0.125, 0.25, 0.35, 0.5, 0.75]


def replay(*args, stdin=None) -> str:
    done = subprocess.run([sys.executable, "-m", "contactsep", "replay",
                           *args], stdin=stdin, capture_output=True,
                          check=True)
    assert done.stderr == b""
    return done.stdout.decode("ascii")


def _no_constant(name):
    raise AssertionError(f"not strict JSON: {name}")


@pytest.mark.parametrize("precision", ["single", "double"])
def test_jsonl_is_one_strict_object_per_data_set(precision):
    text = replay(str(ALL), "--format", "jsonl", "--precision", precision)
    results = contactsep.replay(ALL, precision)
    lines = text.splitlines()
    assert len(lines) == len(results) == 5
    for index, (line, result) in enumerate(zip(lines, results), 1):
        record = json.loads(line, parse_constant=_no_constant)
        assert record["data_set"] == index
        assert record["precision"] == precision
        assert record["ey_lb_s"] == result.ey
        assert record["ty2dt_in_s"] == result.ty2dt
        assert record["history_ty3_in"] == result.history_ty3.tolist()
        assert record["p_rad_s"] == result.p.tolist()
        assert record["inputs"]["h2_in"] == pytest.approx(
            THICKNESSES[index - 1], rel=1e-7)
        assert record["inputs"]["rho_lb_ft3"] == result.inputs.rho
        assert "listing" not in record


def test_json_is_no_longer_a_format(capsys):
    from contactsep.cli import main
    assert main(["replay", str(ALL), "--format", "json"]) == 2
    assert "jsonl" in capsys.readouterr().err


@pytest.mark.parametrize("precision", ["single", "double"])
def test_csv_has_the_thickness_and_the_builds_digits(precision):
    text = replay(str(ALL), "--format", "csv", "--precision", precision)
    rows = list(csv.DictReader(io.StringIO(text)))
    results = contactsep.replay(ALL, precision)
    assert [float(r["d_in"]) for r in rows] == THICKNESSES
    assert [int(r["n_modes"]) for r in rows] == [4] * 5
    kind = np.float32 if precision == "single" else np.float64
    for row, result in zip(rows, results):
        for key, name in (("ey_lb_s", "ey"), ("t_impact_s", "t_impact"),
                          ("extreme_ty3_in", "extreme_ty3"),
                          ("wm2_lb_s2_in", "wm2")):
            value = getattr(result, name)
            # the text reads back to the very number of the build
            assert kind(row[key]) == kind(value), (key, row[key], value)
            # and is no longer than that precision's shortest form
            assert len(row[key]) <= len(repr(float(value)))
            if precision == "single":
                assert len(row[key].lstrip("-").replace(".", "")
                           .split("e")[0].lstrip("0")) <= 9


@pytest.mark.parametrize("fmt", ["listing", "csv", "jsonl", "summary"])
def test_dash_reads_standard_input(fmt):
    with open(ALL, "rb") as deck:
        piped = replay("-", "--format", fmt, stdin=deck)
    assert piped == replay(str(ALL), "--format", fmt)


def test_dash_with_output_file(tmp_path):
    target = tmp_path / "listing.txt"
    with open(ALL, "rb") as deck:
        assert replay("-", "-o", str(target), stdin=deck) == ""
    assert target.read_text() == "".join(r.listing for r in
                                         contactsep.replay(ALL))
