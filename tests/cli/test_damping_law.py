"""e honoured (issue 49, item 5): where the user gives e and names no
damping law, chatter and preload run Hertz contact with the law
calibrated to e (Flores) instead of the elastic one, and say so (a note
on stderr, the damping in the text and the JSON); a named law wins, and
a design file's echo of the rig's e is not the user's e.

The evidence that the law changed is physical, not the label: an
elastic contact dissipates nothing, Flores's does (the energy book)."""

from __future__ import annotations

import json
import types

import pytest

from contactsep.cli import main
from contactsep.studies.preload import command as design_preload
from contactsep.studies.preload import chart as preload
CHATTER = ["chatter", "--n-modes", "2", "--t-end", "0.03", "--preload",
           "0.05", "--json"]


def chatter_json(argv, capsys):
    assert main([*CHATTER, *argv]) == 0
    captured = capsys.readouterr()
    return json.loads(captured.out), captured.err


def test_a_given_e_runs_the_law_calibrated_to_it(capsys):
    chosen, err = chatter_json(["--e", "0.5"], capsys)
    named, _ = chatter_json(["--e", "0.5", "--damping", "flores"], capsys)
    elastic, warned = chatter_json(["--e", "0.5", "--damping", "none"],
                                   capsys)
    assert chosen["inputs"]["damping"] == "flores"
    assert "contactsep: note: damping flores, calibrated to the given " \
           "e = 0.5" in err
    assert chosen == named
    assert chosen["energy_dissipated_contact_lbin"] > 0.0
    assert elastic["inputs"]["damping"] == "none"
    assert elastic["energy_dissipated_contact_lbin"] == 0.0
    assert "elastic Hertz contact does not use" in warned


@pytest.mark.parametrize("argv", [[], ["--model", "newton", "--e", "0.5"]])
def test_without_e_or_without_hertz_contact_nothing_changes(argv, capsys):
    data, err = chatter_json(argv, capsys)
    assert data["inputs"]["damping"] == "none"
    assert "damping flores" not in err


def test_a_design_file_with_e_counts_and_its_echo_does_not(tmp_path,
                                                           capsys):
    given = tmp_path / "given.json"
    given.write_text(json.dumps({"e": 0.6}))
    data, err = chatter_json(["--design", str(given)], capsys)
    assert data["inputs"]["damping"] == "flores"
    assert "e = 0.6" in err
    echo = tmp_path / "echo.json"
    assert main(["model", "--json"]) == 0
    echo.write_text(capsys.readouterr().out)
    data, err = chatter_json(["--design", str(echo)], capsys)
    assert data["inputs"]["damping"] == "none"


@pytest.fixture
def seen_settings(monkeypatch):
    """The preload search planted (an event below 1 lb), recording the
    settings every run was given."""
    seen = []

    def fake_event(task):
        settings, load = task.settings, task.preload_lb
        seen.append(dict(settings))
        return load < 1.0

    def fake_simulate(design, model, preload=0.0, **settings):
        seen.append(dict(settings))
        return types.SimpleNamespace(
            dt=settings.get("dt", 5e-8), open_threshold_in=1e-6,
            min_open_s=1e-5, t_end_s=0.06,
            longest_open_s=2e-5 if preload < 1.0 else 5e-6)
    monkeypatch.setattr(preload, "_simulate_event", fake_event)
    monkeypatch.setattr(design_preload, "simulate", fake_simulate)
    return seen


@pytest.mark.parametrize("argv, law", [(["--e", "0.5"], "flores"),
                                       (["--e", "0.5", "--damping",
                                         "none"], "none"),
                                       ([], None)])
def test_preload_runs_and_names_the_law(argv, law, seen_settings, capsys):
    base = ["preload", "--n-modes", "4", "--workers", "1", "--progress",
            "never"]
    assert main([*base, *argv, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert seen_settings
    assert {s.get("damping") for s in seen_settings} == {law}
    assert data["inputs"]["settings"].get("damping") == law
    assert main([*base, *argv]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.endswith("simulations" if law is None else
                          f"simulations, damping {law}")


def test_report_searches_with_the_law_preload_would(seen_settings,
                                                    tmp_path):
    pytest.importorskip("matplotlib")
    relay = ["--L1", "1.2", "--b1", "0.25", "--h1", "0.01", "--L3", "1.2",
             "--b3", "0.25", "--h3", "0.01", "--L2", "0.3", "--b2", "0.1",
             "--h2", "0.05", "--ys", "0.02", "--material", "steel",
             "--n-modes", "4", "--workers", "1"]
    assert main(["report", *relay, "--e", "0.5", "-o",
                 str(tmp_path / "r.html")]) == 0
    assert {s.get("damping") for s in seen_settings} == {"flores"}
