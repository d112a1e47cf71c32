"""The preload chart converged row by row (issue 25 item 5,
contactsep.studies.preload.converge): the check at 2N, dt/2 and the
search again where it fails, against simulators whose threshold at each
N is known (a preload has an event below it, none at or above it), so
every answer and verdict below follows from the thresholds alone."""

from __future__ import annotations

import math

import numpy as np
import pytest

from contactsep.studies.preload import converge as pc
from contactsep.studies.preload.chart import min_preloads
from contactsep.studies.study import thesis_study_design

DT = 5e-8


class Thresholds:
    """Simulations whose event is preload < threshold[N][row] (the row
    is the design's separator thickness); records the N and step of
    every run."""

    def __init__(self, thresholds):
        self.thresholds = thresholds
        self.runs = []

    def events(self, tasks):
        out = []
        for task in tasks:
            design, settings, load = task.design, task.settings, \
                task.preload_lb
            n = int(design.n_modes)
            self.runs.append((n, settings["dt"]))
            rule = self.thresholds[n][float(design.h2)]
            out.append(rule(load) if callable(rule) else load < rule)
        return out


ROWS = (0.25, 0.5)


def designs_at(n, rows):
    return [thesis_study_design(d=ROWS[i], n_modes=n) for i in rows]


def converge(thresholds, answers, max_modes=pc.MAX_MODES, t_end=None):
    sims = Thresholds(thresholds)
    return pc.converge_rows(designs_at, answers, 32, DT, "hertz",
                            {"damping": "none"}, sims, max_modes,
                            search_again=min_preloads, t_end=t_end), sims


def budget_steps_x_modes(n_modes, dt, t_end):
    """A run's work as the simulation counts it against its budget of
    1e10 (docs/chatter.md): window / step steps over 3N modes."""
    return t_end / dt * 3 * n_modes


def test_an_answer_that_holds_at_2n_is_converged_at_n():
    # the threshold moves +1 % from N = 32 to 64: 2 % below it an
    # event, 2 % above none
    found, sims = converge({64: {0.25: 10.1, 0.5: 4.0}}, [10.0, 4.0])
    a, b = found
    assert (a.n_modes, a.check_n_modes, a.converged) == (32, 64, True)
    assert a.min_preload_lb == 10.0 and a.dt_s == DT
    assert (b.n_modes, b.converged) == (32, True)
    # two runs a row, all at 2N and half the step
    assert sims.runs == [(64, DT / 2)] * 4


def test_a_closed_preload_2_percent_below_holds_by_an_event_between():
    # "closed" not monotone at 2N: closed at 0.98 a, a window of events
    # at 0.985-0.99 a, closed above; the threshold 0.9 a below
    def window(load, a=10.0):
        return load < 0.9 * a or 0.985 * a <= load < 0.99 * a

    found, sims = converge({64: {0.25: window, 0.5: 4.0}}, [10.0, 4.0])
    assert found[0].converged and found[0].n_modes == 32
    # the scan between ran for that row only: 7 runs
    assert len(sims.runs) == 4 + len(pc.BETWEEN)


def test_a_closed_window_wider_than_the_scan_fails_the_check():
    def closed_below(load, a=10.0):
        return load < 0.9 * a

    found, _ = converge({64: {0.25: closed_below, 0.5: 4.0},
                         128: {0.25: 9.0, 0.5: 4.0}}, [10.0, 4.0])
    assert found[0].n_modes == 64 and found[0].converged
    assert 9.0 <= found[0].min_preload_lb <= 9.09


def test_an_answer_that_moves_down_more_than_2_percent_is_searched_again():
    # N = 64 moves the first row to 9.0 (-10 %), N = 128 to 9.05
    found, sims = converge({64: {0.25: 9.0, 0.5: 4.0},
                            128: {0.25: 9.05, 0.5: 4.0}}, [10.0, 4.0])
    a, b = found
    assert (a.n_modes, a.dt_s, a.check_n_modes, a.converged) == (
        64, DT / 2, 128, True)
    # the chart's search: within 1 % above the threshold at N = 64
    assert 9.0 <= a.min_preload_lb <= 9.0 * 1.01
    assert a.history[0] == (32, 10.0) and a.history[1][0] == 64
    assert (b.n_modes, b.converged) == (32, True)
    # the second row is not run again after it held
    assert {n for n, _ in sims.runs} == {64, 128}
    assert all(step == DT / 4 for n, step in sims.runs if n == 128)


def test_an_answer_that_moves_up_fails_its_check():
    # 2 % above the answer still has an event at N = 64
    found, _ = converge({64: {0.25: 12.0, 0.5: 4.0},
                         128: {0.25: 12.05, 0.5: 4.0}}, [10.0, 4.0])
    assert 12.0 <= found[0].min_preload_lb <= 12.0 * 1.01
    assert (found[0].n_modes, found[0].converged) == (64, True)


def test_a_row_failing_its_last_check_keeps_its_answer_unconverged():
    # at max_modes = 64 there is no check of an N = 64 answer: no search
    found, sims = converge({64: {0.25: 9.0, 0.5: 4.0}}, [10.0, 4.0],
                           max_modes=64)
    a = found[0]
    assert (a.min_preload_lb, a.n_modes, a.check_n_modes, a.converged) == (
        10.0, 32, 64, False)
    assert len(a.history) == 1
    assert {n for n, _ in sims.runs} == {64}
    # and at 128 a row still moving at 128 stays unconverged at N = 64
    found, _ = converge({64: {0.25: 9.0, 0.5: 4.0},
                         128: {0.25: 8.0, 0.5: 4.0}}, [10.0, 4.0])
    a = found[0]
    assert (a.n_modes, a.check_n_modes, a.converged) == (64, 128, False)
    assert 9.0 <= a.min_preload_lb <= 9.09


def test_a_check_the_budget_refuses_at_half_the_step_runs_at_its_finest():
    """A window of 0.4 s: at N = 128 half of 2.5e-8 s is 3.1e7 steps x
    384 modes = 1.2e10, over the budget of 1e10; the check runs at the
    finest step within it, 1.5e-8 s (0.62 of the last step)."""
    found, sims = converge({64: {0.25: 9.0, 0.5: 4.0},
                            128: {0.25: 9.05, 0.5: 4.0}}, [10.0, 4.0],
                           t_end=0.4)
    a = found[0]
    assert (a.n_modes, a.dt_s, a.check_n_modes, a.converged) == (
        64, DT / 2, 128, True)
    steps = {step for n, step in sims.runs if n == 128}
    assert len(steps) == 1
    step, = steps
    assert budget_steps_x_modes(128, DT / 4, 0.4) > 1e10
    assert 0.97e10 < budget_steps_x_modes(128, step, 0.4) <= 1e10
    assert DT / 4 < step <= 0.75 * DT / 2


def test_checks_stop_where_not_even_the_finest_step_refines():
    """A window of 0.6 s: at N = 128 the budget's finest step, 2.3e-8 s,
    is 0.93 of the last step, 2.5e-8 s: no check there, so a row failing
    at N = 64 is not searched again and keeps its answer, unconverged."""
    assert budget_steps_x_modes(128, 0.75 * DT / 2, 0.6) > 1e10
    found, sims = converge({64: {0.25: 9.0, 0.5: 4.0},
                            128: {0.25: 9.05, 0.5: 4.0}}, [10.0, 4.0],
                           t_end=0.6)
    a = found[0]
    assert (a.min_preload_lb, a.n_modes, a.check_n_modes, a.converged) == (
        10.0, 32, 64, False)
    assert {n for n, _ in sims.runs} == {64}
    assert pc.reachable(32, DT, 0.6, 128) == 64
    assert pc.reachable(32, DT, 0.4, 128) == 128
    assert pc.reachable(32, DT, None, 128) == 128


def test_the_refined_step_is_half_where_the_budget_allows():
    assert pc.refined_step(64, DT) == DT / 2
    assert pc.refined_step(64, DT, t_end=0.06) == DT / 2
    # becu_light's window at N = 128 after its N = 64 step
    step = pc.refined_step(128, 3.13e-9, t_end=0.0486)
    assert budget_steps_x_modes(128, 3.13e-9 / 2, 0.0486) > 1e10
    assert budget_steps_x_modes(128, step, 0.0486) <= 1e10
    assert step < 0.75 * 3.13e-9
    assert pc.refined_step(128, 2.4e-9, t_end=0.0486) is None


def test_a_row_without_an_answer_is_not_simulated():
    found, sims = converge({64: {0.5: 4.0}}, [math.nan, 4.0])
    assert math.isnan(found[0].min_preload_lb)
    assert (found[0].check_n_modes, found[0].converged) == (0, False)
    assert found[1].converged
    assert len(sims.runs) == 2


@pytest.mark.parametrize("max_modes", [16, 32])
def test_no_check_above_max_modes(max_modes):
    found, sims = converge({}, [10.0, 4.0], max_modes=max_modes)
    assert sims.runs == []
    assert all(not r.converged and r.check_n_modes == 0 for r in found)


def test_the_chart_columns_say_each_row_s_n_and_verdict():
    from contactsep.studies.preload.chart import PreloadSearch
    sims = Thresholds({64: {0.25: 9.0, 0.5: 4.0},
                       128: {0.25: 9.05, 0.5: 4.0}})
    found = [PreloadSearch(10.0, ((9.9, True), (10.0, False))),
             PreloadSearch(4.0, ((3.96, True), (4.0, False)))]
    columns, notes, answers = pc.chart_columns(
        [(0.25, 0.5), (0.5, 0.5)], designs_at, found, 32, DT, "hertz",
        {"damping": "none"}, sims, search_again=min_preloads)
    assert list(columns["n_modes"]) == [64, 32]
    assert list(columns["dt_s"]) == [DT / 2, DT]
    assert list(columns["check_n_modes"]) == [128, 64]
    assert list(columns["converged"]) == [1, 1]
    assert answers[0].search is not None and answers[1].search is None
    assert any(n.startswith("d = 0.25 in, y_s = 0.5 in: searched again: "
                            "10 lb at N = 32, 9.0") for n in notes)
    assert not any("not converged" in n for n in notes)


@pytest.mark.parametrize("bad", ["yes", 3, 1.5, 2048, np.bool_(True)])
def test_a_bad_converge_is_one_line_before_any_work(bad):
    from contactsep.errors import InputError
    from contactsep.studies.preload.chart import preload_chart
    with pytest.raises(InputError, match=r"^converge: found .*, expected "
                       r"True, False or the largest N of a check") as info:
        preload_chart(n_modes=2, converge=bad, thicknesses=(0.5,),
                      heights=(0.5,), workers=1)
    assert "\n" not in str(info.value)


def test_converge_true_checks_up_to_128_or_twice_n():
    assert pc.largest_check(True, 32) == 128
    assert pc.largest_check(True, 100) == 200
    assert pc.largest_check(False, 32) is None
    assert pc.largest_check(64, 32) == 64
