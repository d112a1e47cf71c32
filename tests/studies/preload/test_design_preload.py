"""``contactsep preload`` / ``contactsep.preload(design)`` (issue 25,
item 5): the answer for one design against direct simulate() runs on
designs of the family, planted windows of events the search must find,
the robust answer's p_open against a direct count, the command's
outputs and refusals."""

from __future__ import annotations

import csv
import io
import json
import math
import types
import warnings

import numpy as np
import pytest
from design_family import FAMILY
from planted_preload import threshold as _threshold

import contactsep
from contactsep import output
from contactsep.chatter import simulate
from contactsep.chatter.stack import largest_preload
from contactsep.cli import main
from contactsep.errors import InputError
from contactsep.studies.preload import command as design_preload
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload.checks import windows
from contactsep.studies.preload import robust as preload_robust
from contactsep.studies.stats import wilson_interval
from contactsep.studies.sweep.spec import chunk_inputs

# a planted physics: the search sees only whether a run has an event
# (the threshold: tests/planted_preload.py)


def _planted(window=None):
    """A fake simulate(): an event below the threshold, except inside
    ``window`` (lo, hi) lb if it lies below it; an event inside it if
    it lies above."""
    def has_event(design, settings, load):
        below = load < _threshold(design, settings)
        inside = window is not None and window[0] <= load <= window[1]
        return below != inside

    def fake_event(task):
        design, load = task.design, task.preload_lb
        settings = task.settings
        return has_event(design, settings, load)

    def fake_simulate(design, model, preload=0.0, **settings):
        settings.pop("samples", None)
        settings.pop("single_impulse", None)
        return types.SimpleNamespace(
            dt=settings.get("dt", 5e-8), open_threshold_in=1e-6,
            min_open_s=1e-5, t_end_s=0.06,
            longest_open_s=2e-5 if has_event(design, settings, preload)
            else 5e-6)
    return fake_event, fake_simulate, has_event


@pytest.fixture
def planted(monkeypatch):
    def plant(window=None):
        fake_event, fake_simulate, has_event = _planted(window)
        monkeypatch.setattr(preload, "_simulate_event", fake_event)
        monkeypatch.setattr(design_preload, "simulate", fake_simulate)
        return has_event
    return plant


@pytest.mark.parametrize("name", ["thesis", "steel_relay", "becu_light"])
def test_the_answer_and_its_change_on_a_planted_threshold(name, planted):
    planted()
    design = FAMILY[name].replace(n_modes=8)
    with pytest.warns(UserWarning, match="moves by -"):
        answer = contactsep.preload(design, workers=1, converge=False)
    assert answer.converged is None
    t = _threshold(design, {})
    assert t <= answer.min_preload_lb <= t * 1.01
    finer = _threshold(design.replace(n_modes=16), {"dt": 2.5e-8})
    assert finer <= answer.verify_min_preload_lb <= finer * 1.01
    # (finer - t) / t, to the search's 1 %
    assert answer.min_preload_change == pytest.approx(
        finer / t - 1.0, abs=0.011)
    assert answer.closed_windows == ()
    assert answer.event_windows[-1][1] < answer.min_preload_lb


@pytest.mark.parametrize("where", [0.72, 0.95, 1.003, 1.2, 1.5, 1.97])
def test_a_planted_window_one_percent_wide_is_found(where, planted):
    """Windows 1 % wide at 0.72-1.97 times the threshold (between the
    scan's 19 % steps): of events above the threshold, found, and the
    answer is above them; closed below it, with band_below reported as a
    closed window between event windows, the answer unmoved (without it
    the scan, monotone here, gives no sign of it: not looked for, the
    same answer)."""
    design = FAMILY["thesis"].replace(n_modes=8)
    t = _threshold(design, {})
    lo = where * t
    has_event = planted((lo, lo * 1.01))
    answer = contactsep.preload(design, workers=1, verify=False,
                                band_below=True)
    assert not has_event(design, {}, answer.min_preload_lb)
    lean = contactsep.preload(design, workers=1, verify=False)
    assert lean.min_preload_lb == answer.min_preload_lb
    if where > 1.0:
        assert lo * 1.01 <= answer.min_preload_lb <= lo * 1.01 ** 2
    else:
        assert t <= answer.min_preload_lb <= t * 1.01
        assert lean.closed_windows == ()
        assert len(answer.closed_windows) == 1
        a, b = answer.closed_windows[0]
        assert lo <= a <= b <= lo * 1.01
        assert len(answer.event_windows) == 2
    # every closed window lies below the answer, every event window too
    assert all(b < answer.min_preload_lb for _, b in answer.closed_windows)
    assert all(b < answer.min_preload_lb for _, b in answer.event_windows)


def test_the_progress_callback_counts_every_simulation(planted,
                                                       monkeypatch):
    planted()
    monkeypatch.setattr(preload_robust, "simulate_design", _fake_sample)
    counted = []
    with pytest.warns(UserWarning, match="moves by -"):
        answer = contactsep.preload(
            FAMILY["becu_light"].replace(n_modes=8), workers=1,
            tolerance=["ys=normal(0.03,0.001)"], samples=7, p_target=0.4,
            progress=counted.append, converge=False)
    # each preload's samples up to where its decision settled
    robust_runs = sum(n + f for _, n, _, f in answer.robust.tested)
    assert robust_runs == answer.robust.simulations > 0
    assert sum(counted) == answer.simulations + robust_runs
    assert answer.simulations == len(answer.tested) + len(
        answer.verify_tested)
    # by default the check's runs at 4N too: 2 preloads, and the 7
    # between them where the one below is closed
    counted.clear()
    with pytest.warns(UserWarning, match="not converged"):
        checked = contactsep.preload(
            FAMILY["becu_light"].replace(n_modes=8), workers=1,
            progress=counted.append)
    extra = checked.simulations - len(checked.tested) - len(
        checked.verify_tested)
    assert sum(counted) == checked.simulations
    assert 2 <= extra <= 2 + 7


def test_windows_are_runs_of_tested_preloads():
    tested = [(0.5, True), (1.0, True), (1.5, False), (2.0, True),
              (2.5, False), (3.0, False), (3.5, True), (4.0, False)]
    assert windows(tested) == ((0.5, 1.0), (2.0, 2.0), (3.5, 3.5))
    assert windows(tested, below=4.0, event=False) == (
        (1.5, 1.5), (2.5, 3.0))


def _fake_sample(fields, model, settings):
    """A planted tolerance study: an event below 10 lb per inch of the
    separator's thickness."""
    event = settings["preload"] < 10.0 * fields["h2"]
    return (0.0,) * 5 + (int(event), 0)


@pytest.mark.parametrize("p_target", [0.08, 0.1, 0.3])
def test_the_robust_answer_meets_its_target_on_the_upper_bound(
        p_target, planted, monkeypatch):
    planted()
    monkeypatch.setattr(preload_robust, "simulate_design", _fake_sample)
    design = FAMILY["thesis"].replace(n_modes=8)
    answer = contactsep.preload(design, workers=1, verify=False,
                                tolerance=["d=uniform(0.2,0.3)"],
                                samples=50, seed=3, p_target=p_target)
    r = answer.robust
    # the samples' thresholds, counted here from the drawn thicknesses
    spec = preload_robust.parse_tolerances(["d=uniform(0.2,0.3)"], 50, 3)
    h2 = chunk_inputs(spec, 0, 50)["h2"]
    assert np.all((h2 >= 0.2) & (h2 <= 0.3)) and len(set(h2)) == 50
    opened = int(np.sum(10.0 * h2 > r.min_preload_lb))
    assert (r.n, r.n_open, r.n_failed) == (50, opened, 0)
    # the rule: the 95 % Wilson interval's upper end within the target
    assert wilson_interval(opened, 50)[1] <= p_target
    assert r.p_open_ci95_high == wilson_interval(opened, 50)[1]
    # 1 % below the answer, the upper end is above the target
    below = int(np.sum(10.0 * h2 > r.min_preload_lb / 1.01))
    assert wilson_interval(below, 50)[1] > p_target
    assert r.p_open_ci95 == wilson_interval(opened, 50)
    assert r.p_open_ci95[0] <= r.p_open <= r.p_open_ci95[1]


def test_the_robust_answer_is_above_a_narrow_window_the_nominal_found(
        planted, monkeypatch):
    """A window of events 1 % wide at 1.3 times the threshold, in the
    nominal design and in every sample: the robust search's 19 % steps
    would step over it; it tries the nominal design's events and ends
    above it."""
    design = FAMILY["thesis"].replace(n_modes=8)
    t = _threshold(design, {})
    lo = 1.3 * t
    planted((lo, lo * 1.01))

    def sample(fields, model, settings):
        load = settings["preload"]
        event = load < t * fields["h2"] / 0.25 or lo <= load <= lo * 1.01
        return (0.0,) * 5 + (int(event), 0)

    monkeypatch.setattr(preload_robust, "simulate_design", sample)
    answer = contactsep.preload(design, workers=1, verify=False,
                                tolerance=["d=uniform(0.245,0.255)"],
                                samples=10, p_target=0.3)
    assert lo * 1.01 <= answer.min_preload_lb <= lo * 1.01 ** 2
    r = answer.robust
    assert lo * 1.01 <= r.min_preload_lb and r.n_open == 0


def test_the_robust_answer_is_above_a_window_only_the_samples_have(
        planted, monkeypatch):
    """A window of events 1.2 % wide, 3 % above a grid point of the scan
    (whose next point is 19 % higher), in the thicker half of the
    samples and not in the nominal design (as becu_light's samples at
    N = 64 open at 0.045 lb where the nominal design has no event above
    0.0415 lb): a band of the nominal design's events would not look
    there; the robust answer is above the window, and the search tried
    every preload of the fine grid from its answer to 1.5 times it."""
    from contactsep.studies.preload.scan import grid
    from contactsep.studies.preload.search import FINE_RATIO, fine_band
    design = FAMILY["thesis"].replace(n_modes=8)
    t = _threshold(design, {})
    planted()
    lo = grid(math.ceil(4 * math.log2(1.1 * t))) * 1.03
    hi = lo * 1.012

    def sample(fields, model, settings):
        load = settings["preload"]
        event = load < t * fields["h2"] / 0.25 or (
            fields["h2"] > 0.25 and lo <= load <= hi)
        return (0.0,) * 5 + (int(event), 0)

    monkeypatch.setattr(preload_robust, "simulate_design", sample)
    answer = contactsep.preload(design, workers=1, verify=False,
                                tolerance=["d=uniform(0.245,0.255)"],
                                samples=10, p_target=0.3)
    r = answer.robust
    assert t * 1.01 < lo and hi < 1.5 * t      # above, within the band
    assert hi < r.min_preload_lb <= hi * FINE_RATIO ** 2
    assert r.n_open == 0
    tried = {p for p, *_ in r.tested}
    assert {p for p in fine_band(r.min_preload_lb)
            if r.min_preload_lb < p <= 1.5 * r.min_preload_lb} <= tried
    opened = [p for p, n, k, f in r.tested if k]
    assert any(lo <= p <= hi for p in opened)


@pytest.mark.parametrize("kwargs, message", [
    ({"p_target": 1.0}, "--p-target: found 1.0"),
    ({"p_target": -0.1}, "--p-target: found -0.1"),
    ({"p_target": math.nan}, "--p-target: found nan"),
    ({"tolerance": ["d=gauss(0.25,0.01)"]}, "--tolerance d=gauss"),
    ({"tolerance": ["preload=normal(1,0.1)"]}, "--tolerance preload"),
    ({"tolerance": ["d=normal(0.25,0.01)"], "samples": 0}, "--samples"),
    ({"samples": 10}, "--samples: the draws of --tolerance"),
    ({"preload": 3.0}, "preload: set by the preload search"),
    ({"model": "appE"}, "model: found 'appE'"),
])
def test_bad_requests_are_input_errors(kwargs, message):
    with pytest.raises(InputError, match=message.replace("(", r"\(")):
        contactsep.preload(FAMILY["thesis"], workers=1, **kwargs)


@pytest.mark.parametrize("argv, message", [
    (["--p-target", "1.5"], "--p-target: found 1.5"),
    (["--p-target", "abc"], "--p-target: found 'abc'"),
    # an upper bound of p_open is never 0: a target of 0 is never met
    (["--p-target", "0"], "--p-target: found 0.0, expected a probability "
                          "above 0 and below 1"),
    (["--tolerance", "d=normal(0.25)"], "--tolerance d=normal(0.25)"),
    (["--tolerance", "size=normal(1,2)"], "--tolerance size"),
    (["--samples", "5"], "--samples: the draws of --tolerance"),
    (["--dt", "-1"], "--dt:"),
    (["--converge", "3"], "--converge: found 3"),
    (["--converge", "x"], "--converge: found 'x'"),
])
def test_bad_command_lines_are_one_line_errors(argv, message, capsys):
    assert main(["preload", "--n-modes", "2", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("contactsep: error: ") and message in err
    assert err.count("\n") == 1


def _strict(text):
    def refuse(constant):
        raise ValueError(f"not strict JSON: {constant}")
    return json.loads(text, parse_constant=refuse)


def test_the_command_writes_strict_json_and_a_commented_csv(
        planted, monkeypatch, tmp_path, capsys):
    planted()
    monkeypatch.setattr(preload_robust, "simulate_design", _fake_sample)
    path = tmp_path / "p.csv"
    assert main(["preload", "--n-modes", "8", "--workers", "1", "--json",
                 "--csv", str(path), "--tolerance", "d=normal(0.25,0.01)",
                 "--samples", "20", "--p-target", "0.2", "--progress",
                 "never"]) == 0
    data = _strict(capsys.readouterr().out)
    design = FAMILY["thesis"].replace(n_modes=8)
    t = _threshold(design, {})
    assert t <= data["min_preload_lb"] <= t * 1.01
    assert data["inputs"]["n_modes"] == 8
    assert data["robust"]["n"] == 20 and data["robust"]["p_target"] == 0.2
    assert isinstance(data["min_preload_change"], float)
    lines = path.read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    assert lines[:len(comments)] == comments and len(comments) >= 5
    rows = list(csv.DictReader(io.StringIO("\n".join(lines[len(comments):]))))
    assert list(rows[0]) == ["search", "preload_lb", "n", "n_open",
                             "n_failed", "n_modes", "dt_s", "event"]
    assert {r["search"] for r in rows} == {"nominal", "verify", "converge",
                                           "robust", "robust_check"}
    # the planted tolerance study does not depend on N: its answer holds
    assert data["robust"]["converged"] is True
    assert data["robust"]["check_n_modes"] == 16
    nominal = {float(r["preload_lb"]): r["n_open"] == "1" for r in rows
               if r["search"] == "nominal"}
    # the answer's row (12 significant digits in the CSV): closed
    nearest = min(nominal, key=lambda p: abs(p - data["min_preload_lb"]))
    assert nearest == pytest.approx(data["min_preload_lb"], rel=1e-10)
    assert not nominal[nearest]


def test_a_failed_search_leaves_the_csv_as_it_was(planted, monkeypatch,
                                                  tmp_path, capsys):
    planted()

    def broken(task):
        raise InputError("dt: found 1, expected a step below the window")

    monkeypatch.setattr(preload, "_simulate_event", broken)
    path = tmp_path / "p.csv"
    path.write_text("before\n")
    assert main(["preload", "--n-modes", "8", "--workers", "1", "--csv",
                 str(path)]) == 2
    assert "--dt: found 1" in capsys.readouterr().err
    assert path.read_text() == "before\n"


# the real simulation, on designs of the family

#: (design, N, settings): the relays at a step their contacts resolve
#: (issue 25: 5e-8 s is unstable for the steel relay) over the first
#: 5 ms, in which their impacts and rattles lie.  (becu_light and
#: bronze_offset have an event up to the largest preload their
#: contacts take, 0.13 and 0.56 lb, at N = 4: no answer to check.)
REAL = [("thesis_thick", 4, {}),
        ("steel_relay", 4, {"dt": 1e-8, "t_end": 0.005}),
        ("steel_thick", 4, {"dt": 1e-8, "t_end": 0.005})]


def _events(design, load, settings) -> int:
    return simulate(design, model="hertz", preload=load, samples=1,
                    single_impulse=False, **settings).n_events


@pytest.mark.slow
@pytest.mark.parametrize("name, n_modes, settings", REAL)
def test_the_answer_is_closed_and_an_event_lies_within_one_percent_below(
        name, n_modes, settings):
    design = FAMILY[name].replace(n_modes=n_modes)
    answer = contactsep.preload(design, workers=2, verify=False, **settings)
    p = answer.min_preload_lb
    assert math.isfinite(p) and p > 0, name
    assert _events(design, p, settings) == 0, name
    event = answer.event_windows[-1][1]
    assert p / 1.01 <= event < p, name
    assert _events(design, event, settings) > 0, name
    assert answer.longest_open_at_answer_s < 1e-5


@pytest.mark.slow
def test_the_thesis_rig_at_n8_finds_the_narrow_windows_of_issue_25():
    """Issue 25: at N = 8, d = 0.75 in, the old search answered 6.73 and
    10.83 lb above windows of events at 8.60-8.77 lb (y_s = 0.5 in) and
    20.15-20.40 lb (y_s = 0.75 in); the answers, checked there by a
    separate simulator, are 8.79 and 20.45 lb.  At the chart's settings
    when the issue was filed (dt 5e-8 s, the 0.06 s window, the plain
    truncation), which the separate simulator shared: the defaults have
    since become the design's own step and window and the static
    correction, another threshold."""
    settings = {"dt": 5e-8, "t_end": 0.06, "static_correction": False}
    for ys, truth in ((0.5, 8.79), (0.75, 20.45)):
        design = FAMILY["thesis_thick"].replace(n_modes=8, ys=ys)
        answer = contactsep.preload(design, workers=2, verify=False,
                                    **settings)
        assert truth / 1.01 <= answer.min_preload_lb <= truth * 1.01, ys


@pytest.mark.slow
def test_the_robust_answer_against_direct_runs_of_its_samples():
    design = FAMILY["thesis_thick"].replace(n_modes=4)
    tolerance = ["d=normal(0.75,0.01)", "ys=uniform(0.48,0.52)"]
    answer = contactsep.preload(design, workers=2, verify=False,
                                tolerance=tolerance, samples=12, seed=1,
                                p_target=0.25)
    r = answer.robust
    spec = preload_robust.parse_tolerances(tolerance, 12, 1)
    drawn = chunk_inputs(spec, 0, 12)
    opened = sum(_events(design.replace(h2=float(h2), ys=float(ys)),
                         r.min_preload_lb, {}) > 0
                 for h2, ys in zip(drawn["h2"], drawn["ys"]))
    assert opened == r.n_open and r.n == 12
    assert wilson_interval(opened, 12)[1] <= 0.25
    low, high = r.p_open_ci95
    assert low <= opened / 12 <= high


def test_no_answer_below_the_largest_preload_the_design_takes():
    """The light beryllium-copper relay at N = 4 with the plain
    truncation (no static correction: its point contact is stiffer)
    opens up to the largest preload its lower contact takes (0.13 lb):
    no answer (NaN, null in JSON), a note says why, and a direct run at
    the highest preload tested has an event."""
    design = FAMILY["becu_light"].replace(n_modes=4)
    settings = {"dt": 1e-8, "t_end": 0.005, "static_correction": False}
    answer = contactsep.preload(design, workers=1, verify=False,
                                **settings)
    assert math.isnan(answer.min_preload_lb)
    top = max(p for p, _ in answer.tested)
    assert answer.ceiling_lb / 2 ** 0.25 < top <= answer.ceiling_lb
    assert _events(design, top, settings) > 0
    assert any(note.startswith("no answer") for note in answer.notes)
    data = _strict(output.json_text(answer.to_json_dict()))
    assert data["min_preload_lb"] is None


# --converge: the planted threshold converges as 1/N^3 (a converging
# answer) or keeps moving with N and dt (one that never converges)

def _converging(monkeypatch, coefficient=40.0):
    def threshold(design):
        n = int(design.n_modes)
        return 0.25 * largest_preload(design) * (1.0 + coefficient / n**3)

    def fake_event(task):
        design, load = task.design, task.preload_lb
        return load < threshold(design)

    def fake_simulate(design, model, preload=0.0, **settings):
        return types.SimpleNamespace(
            dt=settings.get("dt", 5e-8), open_threshold_in=1e-6,
            min_open_s=1e-5, t_end_s=0.06,
            longest_open_s=2e-5 if preload < threshold(design) else 5e-6)
    monkeypatch.setattr(preload, "_simulate_event", fake_event)
    monkeypatch.setattr(design_preload, "simulate", fake_simulate)
    return threshold


def test_converge_takes_the_answer_at_2n_where_it_holds_at_4n(monkeypatch):
    threshold = _converging(monkeypatch)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        answer = contactsep.preload(design, workers=1, converge=True)
    t8, t16 = threshold(design), threshold(design.replace(n_modes=16))
    assert t8 <= answer.min_preload_lb <= 1.01 * t8
    assert answer.min_preload_change < -0.02      # 40/8^3 - 40/16^3
    assert answer.converged is True
    assert (answer.converged_n_modes, answer.converged_check_n_modes) == \
        (16, 32)
    assert answer.converged_dt_s == pytest.approx(2.5e-8)
    assert t16 <= answer.converged_min_preload_lb <= 1.01 * t16
    assert [n for n, _ in answer.converge_history] == [8, 16]


def test_converge_keeps_the_answer_where_2n_moves_it_under_2_percent(
        monkeypatch):
    _converging(monkeypatch, coefficient=1.0)   # 1/512 - 1/4096 < 2 %
    design = FAMILY["becu_light"].replace(n_modes=8)
    answer = contactsep.preload(design, workers=1, converge=True)
    assert abs(answer.min_preload_change) <= 0.02
    assert answer.converged is True
    assert answer.converged_min_preload_lb == answer.min_preload_lb
    assert (answer.converged_n_modes, answer.converged_check_n_modes) == \
        (8, 16)


def test_converge_says_so_where_the_answer_never_settles(planted):
    planted()      # moves with 1/N and with dt: never within 2 %
    design = FAMILY["thesis"].replace(n_modes=8)
    with pytest.warns(UserWarning, match="not converged to 2% by N = 128"):
        answer = contactsep.preload(design, workers=1, converge=True)
    assert answer.converged is False
    assert answer.converged_check_n_modes == 128
    # searched again at 32 and 64 (a search at 128 could not be checked)
    assert [n for n, _ in answer.converge_history] == [8, 16, 32, 64]
    finer = _threshold(design.replace(n_modes=64), {"dt": 5e-8 / 8})
    assert finer <= answer.converged_min_preload_lb <= 1.01 * finer
    data = json.loads(json.dumps(answer.to_json_dict(), allow_nan=False))
    assert data["converged"] is False
    assert data["converge_history"][-1]["n_modes"] == 64


def test_by_default_the_answer_at_2n_is_checked_once_at_4n(monkeypatch):
    """converge not given: where the answer moves more than 2 % at 2N,
    the 2N answer is checked at 4N (and a quarter of the step), never
    searched again; the planted threshold converging as 1/N^3 holds."""
    threshold = _converging(monkeypatch)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        answer = contactsep.preload(design, workers=1)
    t16 = threshold(design.replace(n_modes=16))
    assert answer.converged is True
    assert (answer.converged_n_modes, answer.converged_check_n_modes) == \
        (16, 32)
    assert t16 <= answer.converged_min_preload_lb <= 1.01 * t16
    assert answer.simulations - len(answer.tested) - len(
        answer.verify_tested) == 2
    assert any(note.startswith("converged: the answer at N = 16 held its "
                               "check at N = 32, which tries the preloads "
                               "2% either side") for note in answer.notes)


def test_the_summary_leads_with_the_converged_answer(monkeypatch, capsys):
    threshold = _converging(monkeypatch)
    assert main(["preload", "--n-modes", "8", "--workers", "1",
                 "--progress", "never"]) == 0
    first = capsys.readouterr().out.splitlines()[1]
    t16 = threshold(contactsep.thesis_design(n_modes=16))
    assert first.startswith("  answer (converged to 2 %) ")
    assert first.endswith(" lb (N = 16, held at N = 32)")
    shown = float(first.split(")")[1].split()[0])
    assert t16 <= shown <= 1.01 * t16 * (1 + 1e-4)


def test_by_default_a_failed_check_is_not_searched_again(planted):
    """The planted answer never settles: the check at 4N fails, the
    warning says so and how to search again; no search at 4N."""
    planted()
    design = FAMILY["thesis"].replace(n_modes=8)
    with pytest.warns(UserWarning, match=r"not converged to 2% by N = 32: "
                      r"its check there failed \(converge=True"):
        answer = contactsep.preload(design, workers=1)
    assert answer.converged is False
    assert [n for n, _ in answer.converge_history] == [8, 16]
    assert answer.converged_n_modes == 16
    assert answer.simulations - len(answer.tested) - len(
        answer.verify_tested) <= 2 + 7


def test_no_check_without_verify_or_with_one_n_per_member(planted):
    planted()
    design = FAMILY["thesis"].replace(n_modes=8)
    answer = contactsep.preload(design, workers=1, verify=False)
    assert answer.converged is None and answer.min_preload_change is None
    with pytest.warns(UserWarning, match="moves by"):
        answer = contactsep.preload(design.replace(n_modes=(8, 8, 8)),
                                    workers=1)
    assert answer.converged is None


@pytest.mark.parametrize("kwargs, message", [
    ({"converge": True, "verify": False}, "converge: starts from the"),
    ({"converge": 8}, "converge: found 8"),
    ({"converge": "yes"}, "converge: found 'yes'"),
    ({"converge": 4096}, "converge: found 4096"),
])
def test_bad_converge_requests_are_one_line_errors(kwargs, message,
                                                   planted):
    planted()
    with pytest.raises(InputError, match=message) as error:
        contactsep.preload(FAMILY["thesis"].replace(n_modes=8), workers=1,
                           **kwargs)
    assert "\n" not in str(error.value)


def test_the_command_converges_on_request(planted, capsys):
    planted()
    assert main(["preload", "--n-modes", "8", "--converge", "32",
                 "--workers", "1", "--progress", "never"]) == 0
    out = capsys.readouterr().out
    assert "converged to 2 %" in out and "NOT held at N = 32" in out


def test_the_command_checks_by_default_and_not_with_no_converge(planted,
                                                               capsys):
    planted()
    argv = ["preload", "--n-modes", "8", "--workers", "1", "--progress",
            "never"]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert "converged to 2 %" in out and "NOT held at N = 32" in out
    assert "warning: the smallest preload is not converged" in err
    assert out.splitlines()[1].split() == [
        "answer", "not", "converged", "to", "2", "%", "by", "N", "=", "32",
        "(below)"]
    assert out.splitlines()[2].startswith("  min preload at N = 8 ")
    assert main(argv + ["--no-converge"]) == 0
    out, err = capsys.readouterr()
    assert "converged to 2 %" not in out and "moves by" in err
    assert main(argv + ["--no-converge", "--converge"]) == 2
    assert "not allowed with" in capsys.readouterr().err


def test_converge_stops_where_the_work_budget_does(planted, monkeypatch):
    """A long window: a run at N = 64 and its step would exceed the
    simulation's work budget (chatter.stack.smallest_dt); the checks
    stop at N = 32 with a note instead of failing the whole search."""
    planted()
    plain = design_preload.simulate

    def long_window(*args, **kwargs):
        result = plain(*args, **kwargs)
        result.t_end_s = 1.0
        return result
    monkeypatch.setattr(design_preload, "simulate", long_window)
    design = FAMILY["thesis"].replace(n_modes=8)
    with pytest.warns(UserWarning, match="not converged to 2% by N = 32"):
        answer = contactsep.preload(design, workers=1, converge=True)
    assert answer.converged is False
    assert answer.converged_check_n_modes == 32
    assert [n for n, _ in answer.converge_history] == [8, 16]
    assert any(note.startswith("converge: checks stop at N = 32")
               for note in answer.notes)


def test_a_verify_run_the_simulation_refuses_is_refused_before_the_search(
        planted, monkeypatch):
    """The run at 2N, dt/2 is probed before the search at N: a refusal
    (the work budget) costs no search."""
    planted()
    plain = design_preload.simulate
    searched = []
    monkeypatch.setattr(preload, "_simulate_event",
                        lambda task: searched.append(task) or True)

    def refuse_2n(design, model, **settings):
        if design.n_modes > 8:
            raise InputError("dt: found 2.5e-08, expected at least 3e-08 s "
                             "at N = 16")
        return plain(design, model, **settings)
    monkeypatch.setattr(design_preload, "simulate", refuse_2n)
    with pytest.raises(InputError, match="at N = 16"):
        contactsep.preload(FAMILY["thesis"].replace(n_modes=8), workers=1)
    assert searched == []
