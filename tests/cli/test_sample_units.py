"""Units inside the distributions of ``sweep --sample`` and ``preload
--tolerance`` (issue 49, item 4): each number of ``normal(MEAN,SD)`` and
``uniform(LO,HI)`` may carry a unit, converted as the design options
convert theirs; a bare number keeps the field's unit.

The expected values are converted by hand from the units' definitions
(1 in = 25.4 mm exactly, 1 lbf = 4.4482216152605 N), not by pint."""

from __future__ import annotations

import json

import pytest

from contactsep.cli import main
from contactsep.errors import InputError
from contactsep.studies.preload.robust import parse_tolerances
from contactsep.studies.sweep.spec import parse_sample

pytest.importorskip("pint")

LBF_N = 4.4482216152605


def rounded(value: float) -> float:
    """As contactsep.units rounds a converted value (15 digits)."""
    return float(f"{value:.15g}")


@pytest.mark.parametrize("text, expected", [
    ("d=normal(1mm,0.02mm)", ("h2", "normal", 1 / 25.4, 0.02 / 25.4)),
    ("h2=normal(1 mm, 0.02 mm)", ("h2", "normal", 1 / 25.4, 0.02 / 25.4)),
    ("ys=uniform(0.45in,0.55in)", ("ys", "uniform", 0.45, 0.55)),
    ("ys=uniform(11.43mm,0.55)", ("ys", "uniform", 11.43 / 25.4, 0.55)),
    ("E2=normal(200GPa,2GPa)",
     ("E2", "normal", 200e9 / (LBF_N / 0.0254**2),
      2e9 / (LBF_N / 0.0254**2))),
    ("preload=uniform(1N,2N)", ("preload", "uniform", 1 / LBF_N,
                                2 / LBF_N)),
    ("d=normal(0.25,0.01)", ("h2", "normal", 0.25, 0.01)),
])
def test_each_number_of_a_distribution_may_carry_a_unit(text, expected):
    field, kind, a, b = parse_sample(text)
    assert (field, kind) == expected[:2]
    assert a == pytest.approx(rounded(expected[2]), rel=1e-14)
    assert b == pytest.approx(rounded(expected[3]), rel=1e-14)


def test_a_tolerance_with_units_is_its_inch_twin():
    with_units = parse_tolerances(["d=normal(1mm,0.02mm)"], 10, 0)
    twin = parse_tolerances([f"d=normal({rounded(1 / 25.4)!r},"
                             f"{rounded(0.02 / 25.4)!r})"], 10, 0)
    assert with_units == twin


@pytest.mark.parametrize("argv, words", [
    (["sweep", "--sample", "d=normal(1kg,0.02mm)"],
     "--sample d: found '1kg', expected a quantity in in"),
    (["sweep", "--sample", "e=uniform(0.4mm,0.6)"],
     "--sample e: found '0.4mm', expected a dimensionless number"),
    (["sweep", "--sample", "ys=uniform(0.4 furlongz,0.6)"],
     "--sample ys: found '0.4 furlongz'"),
    (["preload", "--tolerance", "d=normal(1N,0.02mm)"],
     "--tolerance d: found '1N', expected a quantity in in"),
])
def test_a_unit_of_the_wrong_kind_is_refused_in_one_line(argv, words,
                                                         capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


def test_a_wrong_unit_is_an_input_error():
    with pytest.raises(InputError, match="--sample d"):
        parse_sample("d=normal(1s,0.1)")


def test_a_sweep_sampled_in_millimetres_is_its_inch_twin(capsys):
    argv = ["sweep", "--samples", "20", "--seed", "3", "--workers", "1",
            "--json"]
    assert main([*argv, "--sample", "d=normal(6.35mm,0.254mm)"]) == 0
    with_units = json.loads(capsys.readouterr().out)
    assert main([*argv, "--sample", f"d=normal({rounded(6.35 / 25.4)!r},"
                 f"{rounded(0.254 / 25.4)!r})"]) == 0
    twin = json.loads(capsys.readouterr().out)
    with_units.pop("elapsed_s"), twin.pop("elapsed_s")
    assert with_units == twin
    assert with_units["n"] == 20
