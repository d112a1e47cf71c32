"""The verdict line of ``contactsep preload`` (studies.preload.verdict): the
answer to use and how converged it is, or what moved and the rerun with
its time; the robust answer's verdict (not shown below the samples its
rule needs; held; not held); the same text in the JSON; the early stop's
savings against the same search with every sample run.  Planted physics
(tests/planted_preload.py, and thresholds planted here) whose answers
are known."""

from __future__ import annotations

import json
import math
import re
import types
import warnings

import pytest
from design_family import FAMILY
from planted_preload import CALLS

import contactsep
from contactsep.chatter.stack import largest_preload
from contactsep.cli import main
from contactsep.errors import ContactsepWarning
from contactsep.studies.preload import command as design_preload
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload import robust as preload_robust
from contactsep.studies.preload.chart import Simulations
from contactsep.studies.preload.robust import (
    parse_tolerances,
    robust_preload,
)
from contactsep.studies.stats import Z95

TOLERANCE = ["d=uniform(0.2,0.3)"]


def _last_line(argv, capsys) -> tuple[str, dict]:
    """The text output's last line and the JSON of the same command."""
    assert main([*argv, "--progress", "never"]) == 0
    text = capsys.readouterr().out.splitlines()[-1]
    assert main([*argv, "--progress", "never", "--json"]) == 0
    return text, json.loads(capsys.readouterr().out)


class _Clock:
    """The search's clock (contactsep.studies.preload.chart reads
    time.perf_counter): it moves only by the planted runs' costs, so an
    estimate made from it is arithmetic, not a timing under whatever
    load shares the machine."""

    def __init__(self):
        self.now = 0.0

    def perf_counter(self):
        return self.now


def _threshold_moving(monkeypatch, coefficient, cost_s=0.0):
    """The nominal threshold 0.25 x the largest preload x (1 +
    coefficient / N^3); each run costs cost_s x (N / 8) x (step'/dt) on
    the search's clock (:class:`_Clock`), its step dt given or, as a
    design's own step does, shrinking as 1/sqrt(N) (step' = 5e-8 s at
    N = 8)."""
    clock = _Clock()
    if cost_s:
        monkeypatch.setattr(preload, "time", clock)
    def threshold(design):
        n = int(design.n_modes)
        return 0.25 * largest_preload(design) * (1.0 + coefficient / n**3)

    def step(design, settings):
        return settings.get("dt", 5e-8 * math.sqrt(8 / design.n_modes))

    def fake_event(task):
        design, load = task.design, task.preload_lb
        settings = task.settings
        if cost_s:
            clock.now += (cost_s * design.n_modes / 8 * 5e-8
                          / step(design, settings))
        return load < threshold(design)

    def fake_simulate(design, model, preload=0.0, **settings):
        return types.SimpleNamespace(
            dt=step(design, settings), open_threshold_in=1e-6,
            min_open_s=1e-5, t_end_s=0.06,
            longest_open_s=2e-5 if preload < threshold(design) else 5e-6)
    monkeypatch.setattr(preload, "_simulate_event", fake_event)
    monkeypatch.setattr(design_preload, "simulate", fake_simulate)
    threshold.clock = clock
    return threshold


def test_a_converged_answer_says_its_n_and_change(monkeypatch, capsys):
    threshold = _threshold_moving(monkeypatch, 1.0)   # 1/512 - 1/4096
    text, data = _last_line(["preload", "--n-modes", "8", "--workers",
                             "1"], capsys)
    t8, t16 = threshold(contactsep.thesis_design(n_modes=8)), threshold(
        contactsep.thesis_design(n_modes=16))
    found = re.fullmatch(r"answer: ([0-9.]+) lb \(converged: N = 8 within "
                         r"([0-9.]+) %\)", text)
    assert found, text
    assert t8 <= float(found[1]) <= 1.01 * t8 * (1 + 1e-3)
    # the change at 2N: the planted thresholds' to the search's 1 %
    assert abs(float(found[2]) / 100 - (1 - t16 / t8)) <= 0.011
    assert data["verdict"] == text


def test_an_answer_converged_at_2n_says_where_it_held(monkeypatch, capsys):
    threshold = _threshold_moving(monkeypatch, 40.0)  # 7.8 %, then 1 %
    text, data = _last_line(["preload", "--n-modes", "8", "--workers",
                             "1"], capsys)
    t16 = threshold(contactsep.thesis_design(n_modes=16))
    found = re.fullmatch(r"answer: ([0-9.]+) lb \(converged: N = 16, held "
                         r"within 2 % at N = 32\)", text)
    assert found, text
    assert t16 <= float(found[1]) <= 1.01 * t16 * (1 + 1e-3)
    assert data["verdict"] == text


def test_an_unconverged_answer_says_what_moved_and_the_reruns_time(
        monkeypatch, capsys):
    """--no-converge, a threshold 7.8 % lower at 2N: the verdict names the
    move and the rerun at 2N; its time, estimated from this run's, is at
    least the rerun's (less 10 %: it prints two digits) and at most twice
    it (each run's cost, on the search's own clock,
    planted as N / step; the rerun's own step at 2N is 0.71 of this one,
    not the half the estimate's measured ratio assumes)."""
    threshold = _threshold_moving(monkeypatch, 40.0, cost_s=0.002)
    argv = ["preload", "--n-modes", "8", "--workers", "1",
            "--no-converge", "--progress", "never"]
    assert main(argv) == 0
    captured = capsys.readouterr()
    assert "moves by" in captured.err         # the command's warning
    text = captured.out.splitlines()[-1]
    t8 = threshold(contactsep.thesis_design(n_modes=8))
    t16 = threshold(contactsep.thesis_design(n_modes=16))
    found = re.fullmatch(
        r"not converged: the answer moved ([-+0-9.]+)% from N = 8 "
        r"\(([0-9.]+) lb\) to N = 16 \(([0-9.]+) lb\); rerun with "
        r"--n-modes 16 \(about ([0-9.]+) (s|min)\)", text)
    assert found, text
    assert abs(float(found[1]) / 100 - (t16 / t8 - 1)) <= 0.011
    estimate = float(found[4]) * (60 if found[5] == "min" else 1)
    started = threshold.clock.now
    assert main(["preload", "--n-modes", "16", "--workers", "1",
                 "--no-converge", "--progress", "never"]) == 0
    measured = threshold.clock.now - started
    capsys.readouterr()
    print(f"estimate {estimate} s, measured {measured:.3g} s")
    assert 0.9 * measured <= estimate <= 2.0 * measured, (estimate, measured)


def test_an_answer_that_never_settles_names_the_failed_check(
        planted_preload, capsys):
    """The planted threshold moves with 1/N and dt at every N:
    --converge searches to N = 64 and its check at 128 fails."""
    with pytest.warns(ContactsepWarning, match="not converged"):
        answer = contactsep.preload(FAMILY["thesis"].replace(n_modes=8),
                                    workers=1, converge=True)
    (n0, a0), (n1, a1) = answer.converge_history[-2:]
    verdict = answer.verdict
    assert verdict.text == (
        f"not converged: the answer moved {a1 / a0 - 1:+.1%} from N = 32 "
        f"({a0:.4g} lb) to N = 64 ({a1:.4g} lb), and its check at N = 128 "
        f"failed; rerun with --n-modes 128")
    assert (n0, n1) == (32, 64) and a1 < a0
    assert verdict.rerun_s is not None and verdict.rerun_s > 0
    assert answer.to_json_dict()["verdict"] == verdict.text


def test_too_few_samples_are_not_shown_and_not_run(planted_preload,
                                                   capsys):
    """Issue 49's case: 20 samples at the default p_target 0.01, which
    none open of 20 cannot show (95 % upper end 0.161): no robust run,
    a warning, the samples needed (381: z^2 (1 - p) / p = 380.3)."""
    argv = ["preload", "--n-modes", "8", "--workers", "1", "--tolerance",
            TOLERANCE[0], "--samples", "20", "--progress", "never"]
    assert main(argv) == 0
    captured = capsys.readouterr()
    assert "needs >= 381 samples" in captured.err     # the warning
    text = captured.out.splitlines()[-1]
    assert not [c for c in CALLS if c[0] == "sample"]
    assert math.ceil(Z95 ** 2 * 0.99 / 0.01) == 381
    assert text.startswith(
        "not shown at this sample count: needs >= 381 samples (p_target "
        "0.01 on p_open's 95 % upper bound; 20 give at best 0.161); "
        "rerun with --samples 381 (about ")
    assert main([*argv, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["robust"]["samples_needed"] == 381
    assert data["robust"]["min_preload_lb"] is None
    assert data["robust"]["simulations"] == 0
    assert data["verdict"] == text.rsplit(" (about ", 1)[0]


def test_a_held_robust_answer_is_the_answer(planted_preload, capsys):
    """20 samples at p_target 0.2: none open meets it (upper end
    z^2 / (20 + z^2) = 0.161); the study does not move with N."""
    text, data = _last_line(
        ["preload", "--n-modes", "8", "--workers", "1", "--tolerance",
         TOLERANCE[0], "--samples", "20", "--p-target", "0.2"], capsys)
    r = data["robust"]
    assert f"{Z95 ** 2 / (20 + Z95 ** 2):.3g}" == "0.161"
    assert text == (f"answer: {r['min_preload_lb']:.4g} lb robust (p_open "
                    f"<= 0.2 on its 95 % upper bound 0.161: 0 of 20 open; "
                    f"held within 2 % at N = 16)")
    assert data["verdict"] == text and r["p_open_ci95_high"] <= 0.2


def test_a_robust_answer_that_moves_at_2n_is_not_converged(
        planted_preload, monkeypatch):
    def sample(fields, model, settings):     # 6 % lower at 2N
        factor = 1.0 + 0.5 / fields["n_modes"]
        event = settings["preload"] < 10.0 * fields["h2"] * factor
        return (0.0,) * 5 + (int(event), 0)
    monkeypatch.setattr(preload_robust, "simulate_design", sample)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        answer = contactsep.preload(FAMILY["thesis"].replace(n_modes=8),
                                    workers=1, tolerance=TOLERANCE,
                                    samples=20, p_target=0.2)
    r = answer.robust
    assert r.converged is False
    verdict = answer.verdict
    assert verdict.text == (
        f"not converged: the robust answer {r.min_preload_lb:.4g} lb at "
        f"N = 8 does not hold at N = 16 (p_target failed within 2 % above "
        f"it, or met within 2 % below); rerun with --n-modes 16")
    assert verdict.rerun_s > 0


def test_the_early_stop_spares_runs_and_keeps_the_answer(planted_preload):
    """400 samples at p_target 0.01 (the planted study: an event below 10
    lb per inch of each sample's thickness): the same answer and the same
    preloads tried as with every sample run (one block), fewer runs."""
    design = FAMILY["thesis"].replace(n_modes=8)
    spec = parse_tolerances(TOLERANCE, 400, 2)
    found = {}
    for first in (10, 400):
        with Simulations(1) as sims:
            found[first] = robust_preload(design, "hertz", {}, spec, 0.01,
                                          sims, start=2.5,
                                          first_block=first)
    early, full = found[10], found[400]
    assert early.min_preload_lb == full.min_preload_lb
    assert [p for p, *_ in early.tested] == [p for p, *_ in full.tested]
    assert full.simulations == 400 * len(full.tested)
    assert full.simulations_saved == 0
    assert early.simulations + early.simulations_saved == full.simulations
    assert early.simulations < full.simulations
    # met from the answer up: all 400 ran there; spared only where one
    # failed, and there in whole blocks after the first open sample
    a = early.min_preload_lb
    assert all(n == 400 for p, n, k, f in early.tested if p >= a)
    spared = sum(400 - n for p, n, k, f in early.tested if p < a)
    assert spared == early.simulations_saved > 0
    opened = {p: k for p, _, k, _ in full.tested}
    assert all(n <= 20 for p, n, k, f in early.tested
               if p < a and opened[p] > 40)
    print(f"planted, 400 samples: {early.simulations} runs of "
          f"{full.simulations} ({len(full.tested)} preloads)")
