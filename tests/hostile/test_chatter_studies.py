"""Hostile input to issue 16's commands: the chatter sweep's settings
and the preload and conclusion studies' options at every extreme are
refused in one line naming them, or answered with finite numbers; their
outputs go through the same writers (replaced only when finished)."""

from __future__ import annotations

import math

import pytest
from hostile_cli import main, refusal, strict_json
from test_numbers import NEVER, VALUES


@pytest.mark.parametrize("option", ["--preload", "--min-open", "--dt"])
@pytest.mark.parametrize("value", VALUES)
def test_chatter_sweep_settings_at_every_extreme(capsys, option, value):
    """One design at N = 2: a value the simulation refuses (a preload
    past the lower contact's limit, a detection time past the window)
    is refused before any work, naming the option."""
    status, out, err = main(capsys, "sweep", "--model", "hertz",
                            "--n-modes", "2", option, value, "--json")
    if status == 2 or value in NEVER:
        assert refusal(status, err).startswith(f"{option}: found "), err
        return
    assert status == 0, err
    data = strict_json(out)
    assert data["n"] == 1 and data["n_failed"] == 0
    assert math.isfinite(data["circuit_open_mean_s"])


@pytest.mark.parametrize("args", [
    ["--workers", "0"], ["--workers", "-1"], ["--workers", "1e300"],
    ["--workers", "nan"], ["--workers", "9223372036854775808"],
    ["--n-modes", "0"], ["--n-modes", "nan"], ["--n-modes", "-1"],
    ["--n-modes", "1e300"], ["--n-modes", "2000"], ["--e", "nan"],
    ["--e", "inf"],
    ["--L2", "-1"], ["--L3", "1e300"], ["--model", "appE"],
    ["--damping", "nan"], ["--dpi", "0"],
])
@pytest.mark.parametrize("name", ["preload", "conclusion5"])
def test_search_study_options_are_refused_before_any_work(capsys, name,
                                                          args):
    status, _, err = main(capsys, "study", name, *args)
    message = refusal(status, err)
    option = args[0]
    assert message.startswith((option, option[2:] + ":", "n_modes:",
                               f"study {name}")) or \
        "designs of the study failed" in message, message


@pytest.mark.parametrize("name", ["preload", "conclusion7"])
def test_a_refused_study_leaves_its_outputs_alone(tmp_path, capsys, name):
    """The CSV and PNG are written only when the study has finished: a
    refused one leaves the old files as they were, and no debris."""
    old = tmp_path / "old.csv"
    old.write_text("kept\n")
    status, _, err = main(capsys, "study", name, "--e", "nan", "--csv",
                          str(old), "--png", str(tmp_path / "p.png"))
    refusal(status, err)
    assert old.read_text() == "kept\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.csv"]
