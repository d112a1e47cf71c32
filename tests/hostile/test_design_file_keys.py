"""--design files (issue 31, item 6): a key twice, or two names of one
field, refused as on the command line; the output of ``contactsep model
--json`` accepted by every command and study that takes a design (its
echo of a study's own field, or of a default the command does not read,
gives way)."""

from __future__ import annotations

import json

import pytest
from hostile_cli import main, refusal

import contactsep.studies.thesis.conclusions as conclusions_module


class _Reached(Exception):
    """The study was called: its arguments passed the command's checks."""


@pytest.mark.parametrize("text, start", [
    ('{"h2": 0.3, "h2": 0.5}', "--design F: h2: given twice"),
    ('{"design": {"e": 0.3, "e": 0.5}}', "--design F: e: given twice"),
    ('{"d_in": 0.3, "h2": 0.4}', "F: h2: the separator thickness d is "
                                 "already given by F: d_in"),
    ('{"restitution": 0.3, "e": 0.3}', "F: e: the "),
])
@pytest.mark.parametrize("command", [["chatter"], ["model"],
                                     ["sweep", "--vary", "ys=0.4,0.5"]])
def test_a_field_given_twice_in_a_file_is_refused(capsys, tmp_path,
                                                  monkeypatch, text, start,
                                                  command):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "F").write_text(text)
    code, out, err = main(capsys, *command, "--design", "F")
    assert refusal(code, err).startswith(start)
    assert out == ""


@pytest.fixture
def model_json(tmp_path, capsys):
    code, out, _ = main(capsys, "model", "--json")
    assert code == 0
    path = tmp_path / "M.json"
    path.write_text(out)
    return str(path)


@pytest.mark.parametrize("name", ["conclusion3", "conclusion5",
                                  "conclusion6", "conclusion7"])
def test_every_conclusion_study_takes_a_model_json_file(
        capsys, monkeypatch, model_json, name):
    """conclusion6 refused it ('sets gamma2 itself; leave it out')
    though the user gave no gamma2: the file's echo of the study's own
    field gives way, as for fig5; the rest reaches the study."""
    seen = {}

    def reached(study, **kwargs):
        seen.update(kwargs, study=study)
        raise _Reached

    monkeypatch.setattr(conclusions_module, "conclusion", reached)
    with pytest.raises(_Reached):
        main(capsys, "study", name, "--design", model_json)
    own = conclusions_module.STUDIES[name][0]
    assert seen["study"] == name and own not in seen
    assert seen["ys"] == 0.5 and "tau" in seen     # eq. 23 reads tau


def test_study_preload_takes_a_model_json_file(capsys, monkeypatch,
                                               model_json):
    """Its echo of tau (the default, which preload does not read) is
    dropped; tau = 1 from the command line is refused."""
    import contactsep.studies.preload.chart as preload_module
    seen = {}

    def reached(**kwargs):
        seen.update(kwargs)
        raise _Reached

    monkeypatch.setattr(preload_module, "preload_chart", reached)
    with pytest.raises(_Reached):
        main(capsys, "study", "preload", "--design", model_json)
    assert "tau" not in seen and "h2" not in seen and "ys" not in seen
    monkeypatch.undo()
    code, _, err = main(capsys, "study", "preload", "--design", model_json,
                        "--tau", "1")
    assert refusal(code, err).startswith("--tau: study preload runs only")


def test_a_chatter_sweep_takes_a_model_json_file(capsys, model_json):
    code, out, err = main(capsys, "sweep", "--model", "hertz", "--design",
                          model_json, "--n-modes", "2", "--vary",
                          "h2=0.25", "--json", "--workers", "1")
    assert code == 0, err
    assert json.loads(out)["n"] == 1


def test_a_file_that_sets_tau_for_a_chatter_sweep_is_refused(
        capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "T.json").write_text('{"tau": 1.0}')
    code, _, err = main(capsys, "sweep", "--model", "hertz", "--design",
                        "T.json", "--vary", "h2=0.2,0.3")
    assert refusal(code, err).startswith("tau: not used")


def test_fig5_and_chatter_take_the_file(capsys, model_json):
    code, _, err = main(capsys, "study", "fig5", "--design", model_json)
    assert code == 0, err
    code, _, err = main(capsys, "chatter", "--design", model_json,
                        "--n-modes", "2")
    assert code == 0, err
