"""The preload search's time, estimated before its first run: a run
costs about its window over its step in steps (most of the search's
runs keep the lower contact pressed, and a pressed step is a fixed step
of the splitting), each at the probe's measured cost a step."""

from __future__ import annotations

import re
import sys
import types

import pytest

from contactsep.chatter import simulate
from contactsep.chatter.stack import largest_preload
from contactsep.cli import main
from contactsep.runs import stops
from contactsep.studies.preload.estimate import (
    run_seconds,
    search_estimate,
    step_seconds,
)
from contactsep.studies.preload.verify import expected_runs
from design_family import FAMILY

tqdm = pytest.importorskip("tqdm").tqdm


def _result(dt=1e-8, t_end=0.01, **work):
    return types.SimpleNamespace(dt=dt, t_end_s=t_end, work=work)


def test_a_step_s_cost_is_the_time_over_the_steps_counted():
    # 2,000 steps in 0.5 s: 250 us a step; a window of 1e6 steps: 250 s
    probe = _result(flight_steps=500, fixed_steps=1500)
    assert step_seconds(probe, 0.5) == pytest.approx(2.5e-4, rel=1e-12)
    assert run_seconds(probe, 0.5) == pytest.approx(250.0, rel=1e-12)
    # a stepper that counts none: its window over its step
    bare = _result()
    assert step_seconds(bare, 2.0) == pytest.approx(2e-6, rel=1e-12)
    assert run_seconds(bare, 2.0) == pytest.approx(2.0, rel=1e-12)
    # no step to read: one step, never a division by zero
    assert run_seconds(_result(dt=0.0), 3.0) == 3.0


def test_the_estimate_shares_the_runs_over_the_workers():
    # 120 runs of 2 s and 5 of 8 s: 280 s of work, 70 s on 4 workers
    estimate = search_estimate(120, 2.0, 5, 8.0, workers=4)
    assert (estimate.runs, estimate.workers) == (125, 4)
    assert estimate.seconds == pytest.approx(70.0, rel=1e-12)
    assert "about 125 simulations" in estimate.line()
    assert "1.2 min on 4 workers" in estimate.line()
    assert "\n" not in estimate.line() and estimate.line().isprintable()
    assert "1 worker " in search_estimate(1, 1.0).line()


@pytest.mark.parametrize("name", sorted(FAMILY))
def test_a_pressed_run_takes_about_its_window_over_its_step(name):
    """The estimate's premise, counted by the stepper itself: at the
    ceiling and at half of it (events on the thinner separators), every
    family design's run takes 80-100 % of its window over its step."""
    design = FAMILY[name].replace(n_modes=8)
    ceiling = largest_preload(design)
    for preload in (ceiling, 0.5 * ceiling):
        result = simulate(design, model="hertz", preload=preload,
                          samples=1, single_impulse=False)
        steps = result.work["flight_steps"] + result.work["fixed_steps"]
        share = steps / (result.t_end_s / result.dt)
        assert 0.8 <= share <= 1.0, (name, preload, share)


def test_the_command_says_its_estimate_before_its_first_run(
        planted_preload, monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(stops, "progress_bar", lambda total, enabled: tqdm(
        total=total, file=sys.stderr, mininterval=0, miniters=1))
    out = tmp_path / "p.csv"
    assert main(["preload", "--n-modes", "4", "--workers", "1",
                 "--progress", "always", "--csv", str(out)]) == 0
    err = capsys.readouterr().err
    lines = [line for line in re.split(r"[\r\n]", err) if line.strip()]
    said = [i for i, line in enumerate(lines)
            if line.startswith("preload: about ")]
    assert len(said) == 1, err
    assert f"about {expected_runs()} simulations" in lines[said[0]]
    assert "on 1 worker " in lines[said[0]]
    ran = [i for i, line in enumerate(lines)
           if re.search(r"\b[1-9]\d*/\d+ ", line)]
    assert ran and said[0] < ran[0], err


def test_no_bar_no_estimate(planted_preload, tmp_path, capsys):
    assert main(["preload", "--n-modes", "4", "--workers", "1",
                 "--progress", "never"]) == 0
    assert "preload: about" not in capsys.readouterr().err
