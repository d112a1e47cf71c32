"""The design options every design command shares (issue 19, item 3):
one option per Design field with its unit, --d and --h2, --e and
--restitution, --set and --design, errors that name what was typed; and
model --json's keys with units (item 3) and strict JSON (item 1)."""

from __future__ import annotations

import dataclasses
import json
import re

import numpy as np
import pytest

import contactsep
from contactsep.cli import build_parser, main
from contactsep.cli.design_options import _Given
from contactsep.constants import GRAVITY_IN_PER_S2
from contactsep.model import Design, evaluate, thesis_design
from contactsep.model import fields

DESIGN_FIELDS = [f.name for f in dataclasses.fields(Design)]
#: The unit suffixes of docs/names-and-units.md, "The names".
UNIT_KEY = re.compile(r"[A-Za-z0-9_]+_(in|s|lb|lb_s|in_s|psi|lb_in3|rad_s|"
                      r"cps|lb_s2_in|lb_in_rad|lb_per_in)")


def subparser(name: str):
    return build_parser()._subparsers._group_actions[0].choices[name]


def model_json(argv, capsys) -> dict:
    assert main(["model", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out, parse_constant=_no_constant)


def _no_constant(name):
    raise AssertionError(f"not strict JSON: {name}")


@pytest.mark.parametrize("command", ["model", "sweep", "study"])
def test_one_option_per_design_field_with_unit_and_default(command):
    actions = [a for a in subparser(command)._actions
               if isinstance(a, _Given) and a.const is not None]
    assert sorted(a.const for a in actions) == sorted(DESIGN_FIELDS)
    for action in actions:
        unit = fields.unit(action.const)
        assert "default" in action.help
        if unit:
            assert f"({unit};" in action.help, action.help


def test_every_model_option_has_help():
    for action in subparser("model")._actions:
        assert action.help and action.help != "==SUPPRESS==", \
            action.option_strings


def test_dir_lists_the_model_names():
    assert {"evaluate", "Design", "thesis_design"} <= set(dir(contactsep))


def test_d_h2_set_and_design_file_are_one_field(capsys, tmp_path):
    expected = float(evaluate(Design(h2=0.3)).y3_max)
    design_file = tmp_path / "d.json"
    design_file.write_text('{"d_in": 0.3}')
    for argv in (["--d", "0.3"], ["--h2", "0.3"], ["--set", "d=0.3"],
                 ["--set", "h2=0.3"], ["--set", "d_in=0.3"],
                 ["--design", str(design_file)]):
        data = model_json(argv, capsys)
        assert data["y3_max_in"] == expected, argv
        assert data["design"]["d_in"] == 0.3


def test_restitution_is_e(capsys):
    expected = float(evaluate(Design(e=0.2)).v0)
    for argv in (["--e", "0.2"], ["--restitution", "0.2"],
                 ["--set", "restitution=0.2"]):
        assert model_json(argv, capsys)["v0_in_s"] == expected


def test_every_kind_of_field_from_the_command_line(capsys):
    argv = ["--end2", "pinned-pinned", "--n-modes", "4,8,6", "--x3",
            "14.82", "--impact-velocity", "listing", "--set",
            "end1=cantilever", "--gamma2", "0.3"]
    design = Design(end2="pinned-pinned", n_modes=(4, 8, 6), x3=14.82,
                    impact_velocity="listing", gamma2=0.3)
    data = model_json(argv, capsys)
    result = evaluate(design)
    assert data["y3_max_in"] == float(result.y3_max)
    assert data["p2_rad_s"] == result.p2.tolist()
    assert len(data["p2_rad_s"]) == 8 and len(data["p3_rad_s"]) == 6


def test_the_json_design_reads_back(capsys, tmp_path):
    first = model_json(["--d", "0.4", "--x3", "15", "--n-modes", "6"],
                       capsys)
    saved = tmp_path / "saved.json"
    saved.write_text(json.dumps(first))
    assert model_json(["--design", str(saved)], capsys) == first
    # the command line overrides the file
    changed = model_json(["--design", str(saved), "--d", "0.5"], capsys)
    assert changed["design"]["d_in"] == 0.5
    assert changed["y3_max_in"] == float(evaluate(Design(
        h2=0.5, x3=15.0, n_modes=6)).y3_max)


def test_model_json_keys_carry_their_units(capsys):
    data = model_json([], capsys)
    bare = {"R", "at_window_end", "t_max_tied", "t_min_tied", "status",
            "design"}
    for key in data:
        assert key in bare or UNIT_KEY.fullmatch(key), key
    # the design's own keys, after the unit system they are in
    assert list(data["design"])[0] == "units"
    assert data["design"]["units"] == "us"
    for key in list(data["design"])[1:]:
        field = fields.field_name(key)
        assert (UNIT_KEY.fullmatch(key) is not None) == bool(
            fields.unit(field)), key
    # the units are what the keys say: the mass gamma b h L / g in
    # lb s^2/in, the first impact near a quarter period of the
    # cantilever's first mode (10.995 cps, Table I) in seconds
    assert data["M1_lb_s2_in"] == pytest.approx(
        0.100 * 2.0 * 0.125 * 19.0 / GRAVITY_IN_PER_S2, rel=1e-14)
    assert 0.8 < data["t1_s"] * 4 * 10.995 < 1.0
    assert data["p1_rad_s"][0] / (2 * np.pi) == pytest.approx(10.995,
                                                              rel=1e-4)


@pytest.mark.parametrize("command", [["model"], ["sweep", "--workers", "1"],
                                     ["study", "fig6"]])
@pytest.mark.parametrize("argv, message", [
    (["--d", "-0.1"], "--d: found -0.1, expected a finite number > 0"),
    (["--h2", "-0.1"], "--h2: found -0.1, expected a finite number > 0"),
    (["--set", "d=-0.1"], "--set d: found -0.1, expected"),
    (["--d", "thick"], "--d: found 'thick', expected a number (in)"),
    (["--restitution", "2"], "--restitution: found 2.0, expected 0 <= e"),
    (["--h2", "0.3", "--d", "0.2"], "--d: the separator thickness d is "
                                    "already given by --h2"),
    (["--set", "zz=1"], "--set zz: not a design field"),
    (["--set", "d"], "--set d: expected FIELD=VALUE"),
    (["--n-modes", "0"], "--n-modes: found '0', expected an integer >= 1"),
    (["--end2", "welded"], "--end2: found 'welded', expected one of"),
    (["--x3", "25"], "--x3: found 25.0, expected 0 < x3 <= L3"),
])
def test_errors_name_the_option_as_typed(command, argv, message, capsys):
    assert main([*command, *argv]) == 2
    captured = capsys.readouterr()
    assert captured.err.startswith("contactsep: error: ")
    assert captured.err.count("\n") == 1
    assert message in captured.err, captured.err


@pytest.mark.parametrize("content, message", [
    ("{not json", "not a JSON file"),
    ("[1, 2]", "expected a JSON object of design fields"),
    ('{"d_inch": 0.3}', ": d_inch: not a design field"),
    ('{"d_in": "thick"}', ": d_in: found 'thick', expected a number"),
    ('{"d_in": -1}', ": d_in: found -1.0, expected a finite number > 0"),
])
def test_bad_design_files_are_one_line_errors(content, message, capsys,
                                              tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(content)
    assert main(["model", "--design", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err


def test_thesis_design_is_the_default(capsys):
    data = model_json([], capsys)
    assert data["y3_max_in"] == float(evaluate(thesis_design()).y3_max)


@pytest.mark.parametrize("argv, expected", [
    (["--d", "0.3", "--d", "0.5"], 0.5),
    (["--e", "0.2", "--e", "0.4"], None),
    (["--set", "h2=0.3", "--set", "h2=0.6"], 0.6),
    (["--d", "0.4", "--h2", "0.4"], 0.4),
])
def test_a_repeated_option_the_last_one_wins(argv, expected, capsys):
    """A base command line with an override appended (issue 30 item 6):
    the last value of an option wins; two spellings of one field agree
    or are refused (above)."""
    data = model_json(argv, capsys)
    if expected is not None:
        assert data["design"]["d_in"] == expected
    else:
        assert data["design"]["e"] == 0.4
