"""One design file for Python and the command line (issue 49):
Design.to_file, contactsep.load_design, contactsep.read, model --json
and --design read and write one format, every field round-trips, the
file holds n_modes only when it was asked for, a file's n_modes is said
so (stderr note, n_modes_source), and bad files are refused in one
line."""

from __future__ import annotations

import dataclasses
import json
import os
import re

import pytest
from design_family import FAMILY
from hostile.hostile_cli import refusal, strict_json

import contactsep
from contactsep.cli import build_parser
from contactsep.cli import main as cli_main
from contactsep.errors import InputError
from contactsep.model import Design, fields

FIELDS = [f.name for f in dataclasses.fields(Design)]
DEFAULTS = {f.name: f.default for f in dataclasses.fields(Design)}

#: Every field away from its default (materials of steel, bronze and
#: beryllium copper; Timoshenko members on elastic supports with point
#: masses; per-member mode counts): a valid design eq. 23 evaluates.
EVERY_FIELD = dict(
    L1=18.0, b1=1.5, h1=0.1, gamma1=0.283, E1=30e6, end1="clamped-clamped",
    x1=9.5, L2=2.25, b2=0.45, h2=0.3, gamma2=0.32, E2=16e6,
    end2="clamped-pinned", x2=1.0, Lc=2.0, L3=17.5, b3=1.75, h3=0.11,
    gamma3=0.298, E3=18.5e6, end3="clamped-pinned", x3=12.0, ys=0.4, e=0.5,
    n_modes=(5, 6, 7), tau=0.05, gap=0.01, impact_velocity="listing",
    lower_response="as-printed", lc_reading="frequencies", release="contact",
    beam1="timoshenko", beam2="timoshenko", beam3="timoshenko", nu1=0.3,
    nu2=0.31, nu3=0.29, kappa1=0.8, kappa2=0.82, kappa3=0.84, kr1=1e5,
    kr2=2e4, kr3=3e5, kt1=1e6, kt2=2e6, kt3=3e6, mass1=0.01, mass2=0.002,
    mass3=0.02, x_mass1=9.0, x_mass2=1.1, x_mass3=11.0, x2_lower=1.0)


def main(capsys, *argv) -> tuple[int, str, str]:
    code = cli_main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def set_options(design_fields: dict) -> list[str]:
    """--set FIELD=VALUE for each field (the command line's own text)."""
    argv = []
    for name, value in design_fields.items():
        text = ",".join(map(str, value)) if isinstance(value, tuple) \
            else repr(value) if isinstance(value, float) else str(value)
        argv += ["--set", f"{name}={text}"]
    return argv


def same_fields(found: Design, expected: Design) -> None:
    for name in FIELDS:
        a, b = getattr(found, name), getattr(expected, name)
        assert a == b and type(a) is type(b), (name, a, b)


def test_the_every_field_design_sets_every_field():
    # a field added to the Design must be added here to be round-tripped
    assert set(EVERY_FIELD) == set(FIELDS)
    for name in FIELDS:
        assert EVERY_FIELD[name] != DEFAULTS[name], name
    assert int(contactsep.evaluate(Design(**EVERY_FIELD)).status) == 0


@pytest.mark.parametrize("name", ["every_field", *FAMILY])
@pytest.mark.parametrize("n_modes", [4, 9, (3, 8, 5)])
def test_to_file_then_load_design_is_the_same_design(tmp_path, name,
                                                     n_modes):
    design = Design(**EVERY_FIELD) if name == "every_field" else FAMILY[name]
    if name != "every_field":
        design = design.replace(n_modes=n_modes)
    path = tmp_path / "d.json"
    design.to_file(path)
    same_fields(contactsep.load_design(path), design)
    same_fields(contactsep.read(path), design)
    data = strict_json(path.read_text())
    # the unit system first, then each field under its name with unit
    assert list(data)[0] == "units" and data["units"] == "us"
    assert set(data) - {"units"} <= {fields.column_name(f) for f in FIELDS}
    # N only where it is not the Design's default (4)
    assert ("n_modes" in data) == (design.n_modes != 4)
    assert os.listdir(tmp_path) == ["d.json"]       # no temporary left


def test_to_file_writes_n_modes_only_when_it_is_not_the_default(tmp_path):
    path = tmp_path / "d.json"
    contactsep.thesis_design(d=0.5).to_file(path)
    assert "n_modes" not in json.loads(path.read_text())
    contactsep.thesis_design(n_modes=(4, 4, 4)).to_file(path)
    assert json.loads(path.read_text())["n_modes"] == [4, 4, 4]
    assert contactsep.load_design(path).n_modes == (4, 4, 4)


def test_to_file_refuses_a_batch_and_leaves_the_target(tmp_path):
    path = tmp_path / "d.json"
    path.write_text("kept")
    with pytest.raises(InputError, match="one design, not a batch of 2"):
        contactsep.thesis_design(d=[0.2, 0.3]).to_file(path)
    assert path.read_text() == "kept"
    assert os.listdir(tmp_path) == ["d.json"]


def test_model_json_of_the_options_loads_as_the_design(capsys, tmp_path):
    """model --json from --set of every field, read by load_design, is
    the design built in Python from the same values; --design of a
    to_file file prints the same bytes as those options."""
    design = Design(**EVERY_FIELD)
    code, by_options, err = main(capsys, "model", *set_options(EVERY_FIELD),
                                 "--json")
    assert code == 0, err
    printed = tmp_path / "printed.json"
    printed.write_text(by_options)
    same_fields(contactsep.load_design(printed), design)
    saved = tmp_path / "saved.json"
    design.to_file(saved)
    code, by_file, err = main(capsys, "model", "--design", str(saved),
                              "--json")
    assert code == 0, err
    assert by_file == by_options
    # the file's N is said so, naming model's default (the Design's, 4)
    assert err == (f"contactsep: note: n_modes = 5,6,7 from the design "
                   f"file {saved} (the command's default is 4)\n")
    # and model --json's design object is the to_file object
    assert json.loads(by_options)["design"] == json.loads(saved.read_text())


@pytest.mark.parametrize("name", sorted(FAMILY))
def test_a_family_design_through_the_command_line_and_back(capsys,
                                                           tmp_path, name):
    design = FAMILY[name]
    values = {f: getattr(design, f) for f in FIELDS
              if getattr(design, f) != DEFAULTS[f]}
    code, out, err = main(capsys, "model", *set_options(values), "--json")
    assert code == 0, err
    path = tmp_path / "m.json"
    path.write_text(out)
    same_fields(contactsep.load_design(path), design)
    assert "n_modes" not in json.loads(out)["design"]


@pytest.mark.parametrize("argv, written", [
    ([], None),
    (["--n-modes", "6"], 6),
    (["--set", "n_modes=6"], 6),
    (["--n-modes", "4"], 4),             # asked for, though the default
    (["--n-modes", "2,3,4"], [2, 3, 4]),
])
def test_model_json_writes_n_modes_only_when_given(capsys, tmp_path, argv,
                                                   written):
    code, out, err = main(capsys, "model", "--d", "0.4", *argv, "--json")
    assert code == 0 and err == ""
    design = json.loads(out)["design"]
    assert design.get("n_modes") == written
    # every other key as before: each field under its output name
    assert set(design) == {"units"} | {
        fields.column_name(f) for f in FIELDS
        if f not in fields.SHOWN_WHEN_GIVEN} - (
        set() if written is not None else {"n_modes"})
    # a file that had it passes it on; one that did not, does not
    path = tmp_path / "m.json"
    path.write_text(out)
    code, again, _ = main(capsys, "model", "--design", str(path), "--json")
    assert code == 0 and again == out


def _help_default(command: str) -> int:
    """The N a command's help says it runs at."""
    parser = build_parser()._subparsers._group_actions[0].choices[command]
    text = " ".join(parser.format_help().split())
    found = re.search(r"N (?:is|defaults to) (\d+)", text)
    assert found, text
    return int(found.group(1))


class _Reached(Exception):
    """The simulation was called: the command's design is known."""


@pytest.fixture
def seen(monkeypatch):
    """Stops chatter and preload at their simulation, keeping the design
    they were given."""
    import contactsep.chatter
    import contactsep.studies.preload.command as design_preload
    got = {}

    def reached(design, **kwargs):
        got["n_modes"] = design.n_modes
        raise _Reached

    monkeypatch.setattr(contactsep.chatter, "simulate", reached)
    monkeypatch.setattr(design_preload, "preload", reached)
    return got


@pytest.mark.parametrize("command", ["chatter", "preload"])
def test_a_model_json_file_leaves_the_simulations_n_at_its_default(
        capsys, tmp_path, seen, command):
    """Issue 49: chatter and preload ran at model's N = 4 from the file
    (preload 41 % below its converged answer)."""
    code, out, _ = main(capsys, "model", "--d", "0.4", "--json")
    assert code == 0
    path = tmp_path / "my.json"
    path.write_text(out)
    with pytest.raises(_Reached):
        main(capsys, command, "--design", str(path),
             *(["--preload", "0.2"] if command == "chatter" else []))
    assert seen["n_modes"] == _help_default(command)
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("command", ["chatter", "preload"])
def test_a_files_n_modes_is_used_and_said_so(capsys, tmp_path, seen,
                                             command):
    path = tmp_path / "my.json"
    path.write_text('{"units": "us", "d_in": 0.4, "n_modes": 4}')
    with pytest.raises(_Reached):
        main(capsys, command, "--design", str(path))
    assert seen["n_modes"] == 4
    assert capsys.readouterr().err == (
        f"contactsep: note: n_modes = 4 from the design file {path} (the "
        f"command's default is {_help_default(command)})\n")
    # the command line's N wins, and needs no note
    with pytest.raises(_Reached):
        main(capsys, command, "--design", str(path), "--n-modes", "3")
    assert seen["n_modes"] == 3
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("argv, source", [
    (["--n-modes", "2"], "given"),
    (["--design", "FILE"], "design file"),
])
def test_chatter_json_says_where_n_came_from(capsys, tmp_path, argv,
                                            source):
    path = tmp_path / "two.json"
    path.write_text('{"n_modes": 2}')
    argv = [str(path) if a == "FILE" else a for a in argv]
    code, out, err = main(capsys, "chatter", "--model", "newton",
                          "--t-end", "0.03", *argv, "--json")
    assert code == 0, err
    inputs = strict_json(out)["inputs"]
    assert inputs["n_modes"] == 2 and inputs["n_modes_source"] == source
    # beside n_modes, as dt_source is in the same object
    keys = list(inputs)
    assert keys[keys.index("n_modes") + 1] == "n_modes_source"
    assert ("note: n_modes = 2" in err) == (source == "design file")


def test_preload_json_says_where_n_came_from(capsys, monkeypatch):
    import contactsep.studies.preload.command as design_preload

    class Answer:
        def __init__(self, design):
            self.n_modes = design.n_modes

        def to_json_dict(self):
            return {"inputs": {"model": "hertz", "n_modes": self.n_modes,
                               "dt_s": 1e-7}, "min_preload_lb": 0.1}

    monkeypatch.setattr(design_preload, "preload",
                        lambda design, **kwargs: Answer(design))
    code, out, err = main(capsys, "preload", "--json")
    assert code == 0, err
    assert strict_json(out)["inputs"] == {
        "model": "hertz", "n_modes": _help_default("preload"),
        "n_modes_source": "default", "dt_s": 1e-7}


@pytest.mark.parametrize("text, message", [
    ("not json", "not a JSON file"),
    ("[1, 2]", "expected a JSON object of design fields"),
    ('{"L1_in": 19, "L1_in": 18}', "L1_in: given twice"),
    ('{"length": 19}', "F: length: not a design field (one of L1,"),
    ('{"preload_lb": 0.2}', "F: preload_lb: a setting of the chatter "
                            "simulation, not a design field"),
    ('{"L1_in": "long"}', "F: L1_in: found 'long', expected a number (in)"),
    ('{"L1_in": [19, 18]}', "F: L1_in: found [19, 18], expected a number"),
    ('{"end2": 3}', "F: end2: found 3, expected one of clamped-free,"),
    ('{"n_modes": 2.5}', "F: n_modes: found 2.5, expected an integer >= 1"),
    ('{"d_in": -0.1}', "F: d_in: found -0.1, expected a finite number > 0"),
    ('{"units": "SI", "d_in": 0.3}', "F: units: found 'SI', expected us "
                                     "(in, lb, s; E psi, densities "
                                     "lb/in^3); si (m, N, s;"),
    # an SI file (model --units si --json) keys its values in SI
    ('{"units": "si", "d_in": 0.3}', "F: d_in: an inch-pound key in a "
                                     "file whose units are si (give d_m)"),
    ('{"units": 1}', "F: units: found 1, expected us"),
    ('{"design": {"units": "SI"}}', "F: units: found 'SI', expected us"),
])
def test_a_bad_file_is_refused_in_one_line(capsys, tmp_path, monkeypatch,
                                           text, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "F").write_text(text)
    with pytest.raises(InputError) as caught:
        contactsep.load_design("F")
    found = str(caught.value)
    assert message in found and "\n" not in found and found.startswith("F:")
    with pytest.raises(InputError, match=re.escape(message)):
        contactsep.read("F") if text.lstrip().startswith("{") else \
            contactsep.load_design("F")
    code, out, err = main(capsys, "model", "--design", "F")
    assert message in refusal(code, err) and out == ""


def test_a_hand_written_file_without_units_is_in_the_packages_units(
        capsys, tmp_path):
    path = tmp_path / "d.json"
    path.write_text('{"d": 0.3, "restitution": 0.2, "material2": "steel"}')
    design = contactsep.load_design(path)
    assert (design.h2, design.e, design.n_modes) == (0.3, 0.2, 4)
    # the preset as the command line's --material2 steel fills it: a
    # carbon steel (handbook: about 30e6 psi, 0.283 lb/in^3)
    code, out, _ = main(capsys, "model", "--d", "0.3", "--e", "0.2",
                        "--material2", "steel", "--json")
    assert code == 0
    printed = tmp_path / "m.json"
    printed.write_text(out)
    same_fields(contactsep.load_design(printed), design)
    assert design.E2 == pytest.approx(30e6, rel=0.02)
    assert design.gamma2 == pytest.approx(0.283, rel=0.02)


def test_a_study_notes_the_files_n_without_naming_one_default(capsys,
                                                              tmp_path):
    """Each study has its own N: the note names none."""
    path = tmp_path / "my.json"
    path.write_text('{"n_modes": 3}')
    code, _, err = main(capsys, "study", "fig5", "--design", str(path))
    assert code == 0, err
    assert err == (f"contactsep: note: n_modes = 3 from the design file "
                   f"{path} (instead of the command's own default)\n")
