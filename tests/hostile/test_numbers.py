"""Silently wrong numbers (issue 18, class 1) through the commands and the
API: every numeric option at NaN, +-inf, 0, -1, 1e-300, 1e300, a word and
2^63 is refused in one line naming it, or answered with finite numbers.
The model's own domain: test_domain.py."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hostile_cli import main, refusal, strict_json

from contactsep.chatter import simulate
from contactsep.errors import InputError
from contactsep.model import DesignError, thesis_design

VALUES = ("nan", "inf", "-inf", "0", "-1", "1e-300", "1e300", "abc",
          "9223372036854775808")
#: Values no field takes: each must be refused.
NEVER = ("nan", "inf", "-inf", "abc")
REAL_OPTIONS = ("--L1", "--b1", "--h1", "--gamma1", "--E1", "--x1", "--L2",
                "--b2", "--d", "--gamma2", "--E2", "--x2", "--Lc", "--L3",
                "--b3", "--h3", "--gamma3", "--E3", "--x3", "--ys", "--e",
                "--gap", "--n-modes")


def _answer_or_refusal(status, out, err, value, option):
    """Exit 2 naming the option, or exit 0 with strict, finite JSON."""
    if status == 2 or value in NEVER:
        message = refusal(status, err)
        # (a window of 1e-300 s is refused through what no longer fits
        # in it: the default --min-open)
        assert message.startswith((option, option[2:] + ":",
                                   "no impact")) or \
            "t_end = " in message, message
        return None
    assert status == 0, err
    return strict_json(out)


@pytest.mark.parametrize("option", REAL_OPTIONS)
@pytest.mark.parametrize("value", VALUES)
def test_model_option_at_every_extreme(capsys, option, value):
    status, out, err = main(capsys, "model", option, value, "--json")
    data = _answer_or_refusal(status, out, err, value, option)
    if data is not None:
        assert data["status"] == 0
        for key, value in data.items():
            if key != "design":     # null: a NaN or an infinity
                assert value is not None, key
        assert data["t1_s"] > 0 and data["v_impact_in_s"] > 0


@pytest.mark.parametrize("option", ["--dt", "--t-end", "--preload",
                                    "--open-threshold", "--min-open",
                                    "--nu", "--button-radius", "--dpi"])
@pytest.mark.parametrize("value", VALUES)
def test_chatter_option_at_every_extreme(capsys, option, value):
    """A short window and two modes: each run is milliseconds, and the
    values a long run would need are refused before it starts."""
    args = ["chatter", "--model", "hertz", "--n-modes", "2", "--t-end",
            "0.03", option, value, "--json"]
    if option == "--t-end":
        args[5:7] = []
    status, out, err = main(capsys, *args)
    data = _answer_or_refusal(status, out, err, value, option)
    if data is not None:
        assert math.isfinite(data["max_lower_gap_in"])
        assert abs(data["max_lower_gap_in"]) < 19.0


@pytest.mark.parametrize("name", ["fig5", "fig6", "fig7", "fig8", "fig23",
                                  "table1", "table2", "table3",
                                  "convergence"])
@pytest.mark.parametrize("option, value", [
    ("--e", "2"), ("--e", "nan"), ("--tau", "0"), ("--ys", "nan"),
    ("--ys", "-1"), ("--ys", "1e300"), ("--L2", "0.3"), ("--E2", "1e100")])
def test_studies_refuse_what_made_tables_of_nan(capsys, name, option,
                                                value):
    """study table2 --e 2 and table3 --tau 0 printed tables of nan."""
    status, out, err = main(capsys, "study", name, option, value)
    if status == 0:
        assert "nan" not in out.lower() and "inf" not in out.lower(), out
        return
    message = refusal(status, err)
    assert message.startswith((option, f"study {name} sets")) or \
        " designs of the study failed" in message, message


def test_a_study_names_the_design_that_failed(capsys):
    status, _, err = main(capsys, "study", "fig5", "--L2", "0.5")
    assert refusal(status, err) == (
        "30 of 57 designs of the study failed; the first (d = 0.55 in, "
        "ys = 0.25 in): h2: found 0.55, expected at most L2 = 0.5 in (a "
        "beam is longer than it is thick)")


@pytest.mark.parametrize("args, message", [
    (["--vary", "h2=0.1:1:4294967296", "--vary", "ys=0.1:1:4294967296"],
     "the sweep has 1.84e+19 designs (4294967296 x 4294967296), expected "
     "at most 1,000,000,000,000"),
    (["--vary", "h2=0.1:1:9223372036854775808"],
     "--vary h2=0.1:1:9223372036854775808: found COUNT 9223372036854775808"
     ", expected 1 to 1,000,000,000,000 values"),
    (["--vary", "h2=0.1:nan:3"], "--vary h2=0.1:nan:3: found START 0.1 and "
                                 "STOP nan, expected finite numbers"),
    (["--vary", "h2=nan,0.2"], "--vary h2: found nan, expected finite"),
    (["--vary", "n_modes=1,200000"], "--vary n_modes: found 200000, "
                                     "expected at most 100,000 modes"),
    (["--sample", "h2=normal(0.25,0.01)", "--threshold", "nan"],
     "--threshold: found 'nan', expected a finite number (in)"),
    (["--sample", "h2=normal(0.25,0.01)", "--threshold", "inf"],
     "--threshold: found 'inf', expected a finite number (in)"),
    (["--sample", "h2=normal(0.25,nan)"], "--sample h2=normal(0.25,nan): "
                                          "the parameters are out of range"),
])
def test_sweep_sizes_and_thresholds_are_refused(capsys, args, message):
    """A grid of 2^32 x 2^32 points wrapped to n: 0 and exited 0; a NaN
    threshold gave p_exceed 0.0."""
    status, _, err = main(capsys, "sweep", *args, "--json")
    assert refusal(status, err).startswith(message)


def test_the_api_refuses_what_the_command_does():
    from contactsep.studies.sweep import run as runner
    from contactsep.studies.sweep import spec as sweep
    spec = sweep.make_spec(vary=["h2=0.1:0.2:2"])
    for kwargs, name in ((dict(threshold=math.nan), "--threshold"),
                         (dict(chunk_size=0), "--chunk-size"),
                         (dict(workers=-1), "--workers")):
        with pytest.raises(InputError, match=f"^{name}: found "):
            runner.run_sweep(spec, **kwargs)
    with pytest.raises(InputError, match="^--seed: found -1"):
        sweep.make_spec(sample=["h2=normal(0.25,0.01)"], seed=-1)
    with pytest.raises(InputError, match="^--samples: found 0"):
        sweep.make_spec(sample=["h2=normal(0.25,0.01)"], samples=0)


# --- chatter ----------------------------------------------------------------

DESIGN = thesis_design(n_modes=2)


@pytest.mark.parametrize("kwargs, message", [
    (dict(preload=1e300), "preload: found 1e+300, expected at most 27.1"),
    (dict(open_threshold=math.nan), "open_threshold: found nan"),
    (dict(open_threshold=-1.0), "open_threshold: found -1.0"),
    (dict(open_threshold=0.5), "open_threshold: found 0.5, expected 0 <= "
                               "open_threshold < ys = 0.5 in"),
    (dict(t_end=1e300), "t_end: found 1e+300, expected a time > 0 and at "
                        "most 10 s"),
    (dict(min_open=1.0), "min_open: found 1.0, expected 0 to t_end"),
    (dict(dt="abc"), "dt: found 'abc', expected a number (s)"),
    (dict(preload=None), "preload: found None, expected a number (lb)"),
    (dict(t_end=True), "t_end: found True, expected a number (s)"),
    (dict(samples=10**9), "samples: found 1000000000, expected an integer "
                          "from 1 to 4,000,000"),
    (dict(button_radius=1e300), "button_radius: found 1e+300"),
    (dict(model="appE", dt=1e-7), "dt: found 1e-07, expected None: appE"),
])
def test_simulate_refuses_settings_by_name(kwargs, message):
    """preload 1e300 gave a lower gap of -1.3e285 in; open_threshold NaN
    a circuit never open and -1 one always open; dt='abc' and
    preload=None errors that did not name the argument."""
    with pytest.raises(InputError) as info:
        simulate(DESIGN, **{"model": "hertz", **kwargs})
    assert str(info.value).startswith(message), str(info.value)


@pytest.mark.parametrize("changes, message", [
    (dict(gap=1.0), "gap: found 1.0, expected 0"),
    (dict(Lc=3.0), "Lc: found 3.0, expected None"),
])
def test_simulate_refuses_fields_it_would_ignore(changes, message):
    """Design(gap=1.0) had its gap silently ignored by simulate."""
    with pytest.raises(InputError, match=f"^{message}"):
        simulate(DESIGN.replace(**changes), model="newton")


def test_a_design_that_simulated_to_nan_is_refused_when_made():
    """thesis_design(end1="pinned-pinned") simulated to all-NaN: its
    default contact point x1 = L1 is a support, refused at once."""
    with pytest.raises(DesignError, match="^x1: found 19.0 .its default."):
        thesis_design(end1="pinned-pinned")
    # inside the span it runs, with finite answers
    r = simulate(thesis_design(end1="pinned-pinned", x1=9.5, n_modes=2),
                 model="hertz", t_end=0.03)
    assert np.isfinite(r.max_lower_gap_in) and np.all(np.isfinite(r.t))
