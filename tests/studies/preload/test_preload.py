"""The preload chart (issue 16, item 2): the search against event
functions whose answer is known, the chart's rows against simulate() 3 %
either side of their preload, the command's outputs and refusals."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
from planted_preload import threshold as planted_threshold

from contactsep.chatter import simulate
from contactsep.cli import main
from contactsep.model import thesis_design
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload import scan as preload_scan

ROOT = Path(__file__).resolve().parents[3]
COLUMNS = ["model", "n_modes", "d_in", "ys_in", "min_preload_lb"]


def _search(*functions, **options):
    calls = []

    def has_event(tasks):
        calls.append(len(tasks))
        return [functions[row](p) for row, p in tasks]

    return preload.search(len(functions), has_event, **options), calls


# the search, on event functions with a known answer

def test_a_monotone_threshold_is_found_to_one_percent():
    thresholds = (3.7, 0.07, 100.0, 0.5)
    found, calls = _search(*(lambda p, t=t: p < t for t in thresholds))
    for t, result in zip(thresholds, found):
        assert t <= result.min_preload_lb <= t * 1.01
        # the bracket: an event within 1 % below the answer
        events = [p for p, event in result.tested if event]
        assert result.min_preload_lb <= max(events) * 1.01
        assert result.closed_below == ()
    # one batch per scan octave, bisection step or band, for all rows
    # at once; the band: every step of at most 1 % (relative) from the
    # answer to 2 times it (the scan is monotone: nothing below it), and
    # with band_below from 0.7 times it, counted here independently of
    # fine_band; the same answers
    assert len(calls) < 25
    below, _ = _search(*(lambda p, t=t: p < t for t in thresholds),
                       band_below=True)
    for result, looked in zip(found, below):
        answer = result.min_preload_lb
        assert looked.min_preload_lb == answer
        for tested, low in ((result.tested, 1.0), (looked.tested, 0.7)):
            band = sorted(p for p, _ in tested
                          if low * answer <= p <= 2.0 * answer)
            assert band[0] <= low * answer * 1.01
            assert band[-1] >= 2.0 * answer / 1.01
            assert all(b / a <= 1.01 for a, b in zip(band, band[1:]))
        # by default not the ~35 fine steps from 0.7 to 0.99 times it
        def under(tested, a=answer):
            return [p for p, _ in tested if 0.7 * a <= p < a / 1.01]
        assert len(under(looked.tested)) - len(under(result.tested)) >= 25


def test_above_the_answer_every_tested_preload_is_closed():
    """Closed 3.3-3.4 lb and 5.6-5.7 lb inside open ranges: the answer is
    above the highest event found, the closed values below it are named,
    and everything tested above it is closed."""
    def events(p):
        return not (3.3 <= p <= 3.4 or 5.6 <= p <= 5.7 or p >= 7.9)

    (result,), _ = _search(events)
    assert 7.9 <= result.min_preload_lb <= 7.9 * 1.01
    assert all(not event for p, event in result.tested
               if p >= result.min_preload_lb)
    # the scan's grid, 2^(k/4) lb, has 2^1.75 and 2^2.5 in the closed
    # ranges; the band (from 0.7 x 7.9 = 5.53 lb) one more, 5.61 lb
    assert {round(p, 2) for p in result.closed_below} == {3.36, 5.61, 5.66}
    assert all(3.3 <= p <= 3.4 or 5.6 <= p <= 5.7
               for p in result.closed_below)


def test_a_window_one_percent_wide_is_found_wherever_it_lies():
    """A window of events 1 % wide anywhere from 0.7 to 2 times the
    answer, between the scan's values, is found: the answer moves above
    it."""
    for start in np.geomspace(3.7 * 1.001, 3.7 * 1.98, 23):
        (result,), _ = _search(
            lambda p, s=start: p < 3.7 or s <= p <= s * 1.01)
        assert start * 1.01 <= result.min_preload_lb <= start * 1.01 ** 2


def test_an_open_window_beyond_the_band_the_grid_misses_is_not_seen():
    """The answer is the tested one: a narrow open window more than 2
    times above the last event and between two scan values (8.0-8.5 lb,
    between 7.55 and 8.98) is not found, as the docs say."""
    (result,), _ = _search(lambda p: p < 3.7 or 8.0 < p < 8.5)
    assert 3.7 <= result.min_preload_lb <= 3.7 * 1.01


def test_closed_without_a_preload_and_below_the_floor():
    found, _ = _search(lambda p: False, lambda p: p < 1e-9,
                       lambda p: p < 3e-6, lambda p: True)
    never, tiny, small, always = found
    assert never.min_preload_lb == 0.0
    # below 2^-20 lb the chart says 2^-20 lb: 0 has an event, 2^-20 none
    assert tiny.min_preload_lb == preload_scan.grid(preload_scan.LOWEST_K)
    assert (0.0, True) in tiny.tested
    assert 3e-6 <= small.min_preload_lb <= 3e-6 * 1.01
    # an event within an octave of the grid's top (1024 lb): no answer
    assert math.isnan(always.min_preload_lb)
    top = max(p for p, _ in always.tested)
    assert preload_scan.grid(preload_scan.HIGHEST_K) / 2 < top <= preload_scan.grid(
        preload_scan.HIGHEST_K)


def test_nothing_above_a_ceiling_is_tested():
    """A ceiling (the largest preload the simulation takes) cuts the
    scan's closed octave and the band short; an event at the highest
    grid value below it leaves no answer."""
    calls = []

    def has_event(tasks):
        calls.extend(tasks)
        return [p < (3.7, 10.0, 3.7)[row] for row, p in tasks]

    found = preload.search(3, has_event, ceilings=[5.0, 10.5, math.inf])
    cut, beyond, free = found
    assert 3.7 <= cut.min_preload_lb <= 3.7 * 1.01
    assert cut.min_preload_lb == free.min_preload_lb
    assert max(p for row, p in calls if row == 0) <= 5.0
    # without a ceiling: an octave above the last event, 2^(7/4) lb,
    # and the band, to 2 times the answer
    top = max(p for row, p in calls if row == 2)
    assert top >= preload_scan.grid(11)
    assert 2.0 * free.min_preload_lb / 1.01 <= top <= 2.0 * \
        free.min_preload_lb
    # 2^(13/4) = 9.51 lb has an event, 2^(14/4) = 11.3 lb is above 10.5
    assert math.isnan(beyond.min_preload_lb)
    assert max(p for row, p in calls if row == 1) == preload_scan.grid(13)


# the chart against simulate(), 3 % either side

#: The chart's step and window (the thesis's, given: preload_chart).
THESIS = {"dt": 5e-8, "t_end": 0.06}


def _check(row_model, d, ys, n_modes, answer, dt=None):
    design = thesis_design(d=d, ys=ys, n_modes=n_modes)
    settings = dict(THESIS) if dt is None else {**THESIS, "dt": dt}
    below, above = (simulate(design, model=row_model, preload=f * answer,
                             samples=1, single_impulse=False, **settings)
                    for f in (0.97, 1.03))
    return below.n_events, above.n_events


@pytest.mark.slow
def test_the_search_at_n4_holds_3_percent_either_side():
    """Two rows at N = 4 where it holds.  At N = 4 "closed" is far from
    monotone: for 10 of the 15 rows the answer sits at the top of an
    open window narrower than 3 %, and 3 % below it is closed too
    (docs/preload-family.md, "The preload chart"); at N = 32 the 14 rows with
    an answer hold (test_the_committed_chart_holds_3_percent_either_side)."""
    rows = [(0.5, 0.25), (0.75, 0.5)]
    found = preload.min_preloads(
        [thesis_design(d=d, ys=ys, n_modes=4) for d, ys in rows],
        settings=THESIS, workers=2)
    for (d, ys), result in zip(rows, found):
        below, above = _check("hertz", d, ys, 4, result.min_preload_lb)
        assert below > 0 and above == 0


def test_the_chart_has_its_rows_and_columns(monkeypatch):
    """The chart's table around the search, the simulation replaced by a
    known event function: an event below 0.3 lb per inch of y_s."""
    seen = []

    def fake(task):
        design, load = task.design, task.preload_lb
        seen.append((float(design.h2), float(design.ys), design.n_modes))
        return load < 0.3 * float(design.ys)

    monkeypatch.setattr(preload, "_simulate_event", fake)
    chart = preload.preload_chart(n_modes=7, workers=1)
    assert list(chart.columns) == COLUMNS and len(chart) == 15
    assert chart["model"].tolist() == ["hertz"] * 15
    assert chart["n_modes"].tolist() == [7] * 15
    assert [(d, ys) for d, ys in zip(chart["d_in"], chart["ys_in"])] == [
        (d, ys) for d in preload.THICKNESSES for ys in preload.HEIGHTS]
    ratio = chart["min_preload_lb"] / (0.3 * chart["ys_in"])
    assert np.all((ratio >= 1.0) & (ratio <= 1.01))
    assert {n for _, _, n in seen} == {7}
    assert f"{len(seen)} simulations" in chart.notes
    assert not any("not monotone" in note for note in chart.notes)


def test_the_chart_refuses_its_own_fields():
    with pytest.raises(Exception, match="study preload sets d/h2 itself"):
        preload.preload_chart(n_modes=2, h2=0.3)


@pytest.mark.parametrize("argv, message", [
    (["study", "preload", "--d", "0.3"], "study preload sets d/h2 itself"),
    (["study", "preload", "--ys", "0.3"], "study preload sets ys itself"),
    (["study", "preload", "--backend", "numpy"],
     "study preload runs the chatter simulation"),
    (["study", "preload", "--workers", "0"], "--workers: found '0'"),
    (["study", "preload", "--model", "newton", "--damping", "flores"],
     "damping: the Hertz contact's"),
    (["study", "fig5", "--damping", "flores"],
     "--damping is study preload's option"),
    (["study", "conclusion5", "--converge"],
     "--converge is study preload's option"),
    (["study", "fig5", "--model", "hertz"],
     "--model and --workers are options of study preload, conclusion3"),
])
def test_bad_chart_requests_are_one_line_errors(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def _read(path):
    lines = Path(path).read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    assert lines[:len(comments)] == comments
    body = lines[len(comments):]
    assert all(len(line.split(",")) == len(body[0].split(","))
               for line in body)
    return comments, list(csv.DictReader(body))


def test_the_command_writes_fifteen_rows_and_a_png(tmp_path, capsys,
                                                  planted_preload):
    """The command's files, on the planted physics (tests/
    planted_preload.py: 900 real runs at N = 2 took three minutes in the
    slow set; the chart's real runs are checked by
    test_the_search_at_n4_holds_3_percent_either_side, and the committed
    chart's deciding runs by tests/project/test_committed_searches.py)."""
    csv_path, png = tmp_path / "p.csv", tmp_path / "p.png"
    assert main(["study", "preload", "--n-modes", "2", "--csv",
                 str(csv_path), "--png", str(png)]) == 0
    _, rows = _read(csv_path)
    assert list(rows[0]) == COLUMNS and len(rows) == 15
    assert {(float(r["d_in"]), float(r["ys_in"])) for r in rows} == {
        (d, ys) for d in preload.THICKNESSES for ys in preload.HEIGHTS}
    assert all(r["model"] == "hertz" and r["n_modes"] == "2" for r in rows)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the answers are the planted thresholds' (the search to 1 %)
    for r in rows:
        design = thesis_design(d=float(r["d_in"]), ys=float(r["ys_in"]),
                               n_modes=2)
        planted = planted_threshold(design, {})
        assert planted <= float(r["min_preload_lb"]) <= 1.01 * planted


# The committed chart itself (study preload --converge, once
# regenerated here in the slow set: 5 minutes on two cores):
# tests/project/test_committed_searches.py simulates again the runs
# that decide each of its rows and checks its '#' lines and columns.


#: Rows of the committed chart (Hertz, N = 32) where "closed" is not
#: monotone 3 % below the answer (docs/preload-family.md, "The preload chart"):
#: there the preload 3 % below has no event either.
NOT_MONOTONE_BELOW = set()
#: Rows with no answer: an event at 26.9 lb, and the simulation takes at
#: most 27.05 lb (the lower contact bent by its length).
NO_ANSWER = {(0.35, 0.75)}


@pytest.mark.slow
def test_the_committed_chart_holds_3_percent_either_side():
    comments, rows = _read(ROOT / "docs" / "studies" / "preload.csv")
    for r in rows:
        key = (float(r["d_in"]), float(r["ys_in"]))
        answer = float(r["min_preload_lb"])
        if key in NO_ANSWER:
            assert math.isnan(answer)
            assert any(c.startswith(f"# no answer at d = {key[0]:g} in, "
                                    f"y_s = {key[1]:g} in") for c in
                       comments), key
            continue
        below, above = _check(r["model"], *key, int(r["n_modes"]), answer,
                              float(r["dt_s"]))
        assert above == 0, key
        assert (below == 0) == (key in NOT_MONOTONE_BELOW), key
