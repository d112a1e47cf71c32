"""Values with units on input (issue 30, item 4): every design option, a
--design file and the chatter settings take a number with a unit, equal
to its inch-pound twin; bare numbers keep the package's units; numbers
that look like another unit system are warned about.

The expected values come from the units' definitions (1 in = 25.4 mm,
1 lbf = 4.4482216152605 N, 1 lb = 0.45359237 kg, standard gravity
9.80665 m/s^2), not from pint."""

from __future__ import annotations

import json

import pytest

from contactsep import units
from contactsep.cli import main
from contactsep.errors import InputError

pytest.importorskip("pint")

INCH_M = 0.0254
LBF_N = 4.4482216152605
PSI_PA = LBF_N / INCH_M**2
#: 1 lb/in^3 of mass, in kg/m^3; under standard gravity it weighs 1
#: lbf/in^3.
LB_IN3_KG_M3 = 0.45359237 / INCH_M**3


def rounded(value: float) -> float:
    return float(f"{value:.15g}")


@pytest.mark.parametrize("text, unit, expected", [
    ("30.5mm", "in", 30.5e-3 / INCH_M),
    ("25.4 mm", "in", 1.0),
    ("1e-3 m", "in", 1e-3 / INCH_M),
    ("200GPa", "psi", 200e9 / PSI_PA),
    ("69 GPa", "psi", 69e9 / PSI_PA),
    ("7.85g/cm3", "lb/in^3", 7850.0 / LB_IN3_KG_M3),
    ("7.85 g/cm^3", "lb/in^3", 7850.0 / LB_IN3_KG_M3),
    ("77kN/m^3", "lb/in^3", 77e3 / 9.80665 / LB_IN3_KG_M3),
    ("10us", "s", 1e-5),
    ("1us", "s", 1e-6),
    ("2ms", "s", 2e-3),
    ("1.5N", "lb", 1.5 / LBF_N),
    ("0.3lb", "lb", 0.3),
    ("0.3 lbf", "lb", 0.3),
])
def test_a_value_with_a_unit_is_its_inch_pound_twin(text, unit, expected):
    assert units.convert(text, unit, "--x") == rounded(expected)


@pytest.mark.parametrize("text, unit, words", [
    ("3 kg", "in", "expected a quantity in in"),
    ("12 parsecs/fortnight", "psi", "expected a quantity in psi"),
    ("5 foo", "in", "not a unit pint knows"),
    ("5 mm", "", "dimensionless"),
])
def test_a_wrong_unit_is_refused_in_one_line(text, unit, words):
    with pytest.raises(InputError, match=words) as caught:
        units.convert(text, unit, "--x")
    assert "\n" not in str(caught.value)


@pytest.mark.parametrize("text", ["0.5", "-1e-3", "1_000", "inf", "nan",
                                  "1e5000", "", "abc"])
def test_a_bare_number_or_no_number_has_no_unit(text):
    assert units.split(text) is None


def model_json(argv, capsys) -> dict:
    assert main(["model", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_design_options_with_units_equal_their_twins(capsys):
    with_units = model_json(["--L1", "482.6mm", "--E2", "68.9476GPa",
                             "--gamma3", "2.76799g/cm3", "--ys", "12.7mm",
                             "--d", "0.25in"], capsys)
    twins = model_json(["--L1", "19", "--E2",
                        repr(rounded(68.9476e9 / PSI_PA)), "--gamma3",
                        repr(rounded(2767.99 / LB_IN3_KG_M3)), "--ys",
                        "0.5", "--d", "0.25"], capsys)
    assert with_units == twins


def test_a_design_file_may_carry_units(tmp_path, capsys):
    path = tmp_path / "relay.json"
    path.write_text(json.dumps({"L1": "30.48 mm", "h1": "0.254mm",
                                "E1": "206.8 GPa", "gamma1": "7.85 g/cm^3",
                                "ys": 0.02}))
    with_units = model_json(["--design", str(path)], capsys)
    twins = model_json(["--L1", "1.2", "--h1", "0.01", "--E1",
                        repr(rounded(206.8e9 / PSI_PA)), "--gamma1",
                        repr(rounded(7850.0 / LB_IN3_KG_M3)), "--ys",
                        "0.02"], capsys)
    assert with_units == twins


def test_chatter_settings_take_units(capsys):
    argv = ["chatter", "--model", "hertz", "--n-modes", "4", "--json"]
    assert main(argv + ["--t-end", "5ms", "--min-open", "10us",
                        "--dt", "100ns", "--button-radius", "3.175mm"]) == 0
    with_units = json.loads(capsys.readouterr().out)
    assert main(argv + ["--t-end", "0.005", "--min-open", "1e-05",
                        "--dt", "1e-07", "--button-radius", "0.125"]) == 0
    assert with_units == json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("argv, words", [
    (["model", "--L1", "30.5kg"], "--L1: found '30.5kg', expected a "
                                  "quantity in in"),
    (["model", "--E1", "200 furlongs"], "--E1: found '200 furlongs'"),
    (["model", "--e", "0.5 mm"], "--e: found '0.5 mm', expected a "
                                 "dimensionless number"),
    (["chatter", "--min-open", "10kg"], "--min-open: found '10kg'"),
])
def test_commands_refuse_a_wrong_unit_in_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


def test_without_pint_a_unit_says_what_to_install(monkeypatch):
    monkeypatch.setattr(units, "_registry", lambda: None)
    with pytest.raises(InputError, match=r"contactsep\[units\]"):
        units.convert("30.5mm", "in", "--L1")


@pytest.mark.parametrize("argv, words", [
    (["--E1", "200"], "--E1: 200 psi is softer than any metal"),
    (["--gamma2", "7.85"], "--gamma2: 7.85 lb/in^3 is denser than any"),
    (["--L3", "304.8"], "--L3: a member 304.8 in long: a length in mm?"),
])
def test_numbers_of_another_unit_system_are_warned_about(argv, words,
                                                         capsys):
    assert main(["model", *argv]) == 0
    err = capsys.readouterr().err
    assert f"contactsep: warning: {words}" in err


@pytest.mark.parametrize("argv", [[], ["--E1", "30e6", "--gamma1",
                                       "0.283", "--L1", "1.2"],
                                  ["--E2", "200GPa", "--L2", "30mm"]])
def test_designs_in_inches_and_psi_raise_no_doubt(argv, capsys):
    assert main(["model", *argv]) == 0
    assert "warning" not in capsys.readouterr().err


@pytest.mark.parametrize("preset, seconds", [("1us", "1e-06"),
                                             ("10us", "1e-05"),
                                             ("2ms", "0.002")])
def test_detection_time_presets_are_their_seconds(preset, seconds, capsys,
                                                  tmp_path):
    """docs/chatter.md's table: --min-open 1us, 10us, 2ms are exactly
    the seconds the standards name, in chatter and in chatter sweeps."""
    argv = ["chatter", "--model", "hertz", "--n-modes", "4", "--dt",
            "5e-8", "--t-end", "0.03", "--json"]
    assert main([*argv, "--min-open", preset]) == 0
    with_unit = json.loads(capsys.readouterr().out)
    assert main([*argv, "--min-open", seconds]) == 0
    assert with_unit == json.loads(capsys.readouterr().out)
    assert with_unit["inputs"]["min_open_s"] == float(seconds)
    sweep = ["sweep", "--model", "hertz", "--n-modes", "4", "--vary",
             "h2=0.2:0.3:2", "--workers", "1", "--json"]
    assert main([*sweep, "--min-open", preset]) == 0
    swept = json.loads(capsys.readouterr().out)
    assert main([*sweep, "--min-open", seconds]) == 0
    plain = json.loads(capsys.readouterr().out)
    swept.pop("elapsed_s"), plain.pop("elapsed_s")
    assert swept == plain
