"""``simulate(..., stop_at_event=True)``: a run that only has to answer
"is there a discontinuity event?" stops at its first one.  On the
family (the thesis rig and three relays, N = 8, a preload with an event
and one without) the stopped run is checked against the same design's
run over the whole window, the independent path here: the same answer,
its stop where the full run's own first event reaches min_open, the
trajectory up to there bit for bit (samples, crossings, first impact),
fewer fixed steps; and a run without an event is the full run itself.
Then the refusals, the fall-backs to the full run, and the default."""

from __future__ import annotations

import inspect
import math
import warnings

import numpy as np
import pytest
from design_family import FAMILY

from contactsep import chatter
from contactsep.chatter import numerics, simulate, status, stop_event

#: (design, preload lb with an event, preload lb without one, window s:
#: None the design's own); N = 8.  The preloads without an event were
#: found on full runs (tens of events below them).
CASES = [("thesis", 0.54, 20.0, 0.06),
         ("steel_relay", 0.1, 0.3907, None),
         ("becu_light", 0.0026, 0.0781, 0.005),
         ("bronze_offset", 0.0112, 0.3371, None)]
#: Samples enough to compare the trajectories sample by sample.
SAMPLES = 2000


def _run(name, preload, t_end, **keywords):
    design = FAMILY[name].replace(n_modes=8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return simulate(design, preload=preload, t_end=t_end,
                        samples=SAMPLES, single_impulse=False, **keywords)


def _same_up_to_the_stop(stopped, full):
    """The stopped run's trajectory is the full run's up to its stop:
    the samples it reached, every open interval before the last, the
    last one's start, and the first impact."""
    reached = np.isfinite(stopped.t)
    assert 2 <= reached.sum() < len(full.t)
    assert np.all(reached[:reached.sum()])          # a prefix
    np.testing.assert_array_equal(stopped.t[reached], full.t[reached])
    for name in ("gap_upper", "gap_lower", "energy"):
        np.testing.assert_array_equal(getattr(stopped, name)[reached],
                                      getattr(full, name)[reached])
    for name in ("upper_open_intervals", "lower_open_intervals",
                 "circuit_open_intervals"):
        mine, whole = getattr(stopped, name), getattr(full, name)
        k = len(mine)
        assert k >= 1
        np.testing.assert_array_equal(mine[:k - 1], whole[:k - 1])
        assert mine[k - 1, 0] == whole[k - 1, 0]
        assert mine[k - 1, 1] <= whole[k - 1, 1]
    assert stopped.first_impact_s == full.first_impact_s
    assert stopped.first_impulse_lb_s == full.first_impulse_lb_s
    assert stopped.first_circuit_open_s == full.first_circuit_open_s


@pytest.mark.parametrize("name, with_event, without, t_end", CASES,
                         ids=[case[0] for case in CASES])
def test_on_the_family_a_stopped_run_answers_as_the_full_one(
        name, with_event, without, t_end):
    full = _run(name, with_event, t_end)
    stopped = _run(name, with_event, t_end, stop_at_event=True)
    assert full.status == status.OK and full.chatters
    assert stopped.status == status.STOPPED_AT_EVENT
    assert stopped.chatters and stopped.n_events >= 1
    # the stop: the full run's own first event's start + min_open
    first = full.events[0]
    assert stopped.stopped_s == first[0] + full.min_open_s
    assert stopped.events[0, 0] == first[0]
    assert stopped.events[0, 1] - stopped.events[0, 0] >= full.min_open_s
    assert math.isnan(full.stopped_s)
    _same_up_to_the_stop(stopped, full)
    assert stopped.work["fixed_steps"] < full.work["fixed_steps"]
    if name == "steel_relay":       # docs/preload.md: 737,000 -> 25,000
        assert 20 * stopped.work["fixed_steps"] < full.work["fixed_steps"]

    full = _run(name, without, t_end)
    stopped = _run(name, without, t_end, stop_at_event=True)
    assert full.status == stopped.status == status.OK
    assert not full.chatters and not stopped.chatters
    assert math.isnan(stopped.stopped_s)
    # no event: the run of the whole window, bit for bit
    assert stopped.work == full.work
    for field in ("t", "gap_upper", "gap_lower", "energy",
                  "upper_open_intervals", "lower_open_intervals",
                  "circuit_open_intervals"):
        np.testing.assert_array_equal(getattr(stopped, field),
                                      getattr(full, field))
    assert stopped.max_lower_gap_in == full.max_lower_gap_in
    assert stopped.energy_ratio == full.energy_ratio


def test_newton_stops_at_its_first_event_too():
    full = _run("steel_relay", 0.0, None, model="newton")
    stopped = _run("steel_relay", 0.0, None, model="newton",
                   stop_at_event=True)
    assert full.chatters and stopped.status == status.STOPPED_AT_EVENT
    assert stopped.stopped_s == full.events[0, 0] + full.min_open_s
    _same_up_to_the_stop(stopped, full)
    assert stopped.work["fixed_steps"] < full.work["fixed_steps"]
    # its energy is the state's at the stop: Newton's impacts (e = 0.5)
    # only remove energy, so it lies between the last sample reached and
    # the end of the whole window
    last = stopped.energy[np.isfinite(stopped.t)][-1] / stopped.energy[0]
    assert full.energy_ratio - 1e-9 <= stopped.energy_ratio <= last + 1e-9
    assert stopped.energy_ratio < 1.0 - 1e-3


@pytest.mark.parametrize("keywords, match", [
    ({"verify": True}, "verify"),
    ({"model": "appE"}, "appE"),
    ({"stepper": "fixed"}, "adaptive"),
    ({"backend": "numpy", "stepper": "fixed"}, "adaptive"),
    ({"backend": "numpy"}, "adaptive")])
def test_what_the_stop_does_not_cover_is_refused_in_one_line(keywords,
                                                             match):
    design = FAMILY["steel_relay"].replace(n_modes=4)
    with pytest.raises(chatter.ChatterError, match=match) as error:
        simulate(design, stop_at_event=True, t_end=1e-3, **keywords)
    message = str(error.value)
    assert message.startswith("stop_at_event: ") and "\n" not in message


@pytest.mark.parametrize("value", ["yes", 1, None])
def test_stop_at_event_takes_a_boolean(value):
    with pytest.raises(chatter.ChatterError, match="stop_at_event: found"):
        simulate(FAMILY["steel_relay"].replace(n_modes=4), t_end=1e-3,
                 stop_at_event=value)


def test_the_default_runs_the_whole_window():
    assert inspect.signature(simulate).parameters[
        "stop_at_event"].default is False
    r = _run("steel_relay", 0.1, None)
    assert r.status == status.OK and math.isnan(r.stopped_s)
    # events after the first one: the whole window's
    assert r.n_events > 1 and np.all(np.isfinite(r.t))
    # (the last sample may fall a few steps before the end)
    assert r.t[-1] > r.t_end_s * (1.0 - 1e-3)


def test_a_stopped_run_failing_its_energy_check_is_run_again_whole(
        monkeypatch):
    """A planted failure of every energy check: the stopped run is not
    kept; the answer is the full run's (status 9 at the given step)."""
    dt = _run("steel_relay", 0.0, None).dt
    monkeypatch.setattr(numerics, "energy_converged",
                        lambda ratio, damped: False)
    full = _run("steel_relay", 0.0, None, dt=dt)
    stopped = _run("steel_relay", 0.0, None, dt=dt, stop_at_event=True)
    assert full.status == stopped.status == status.UNCONVERGED
    assert math.isnan(stopped.stopped_s)
    assert stopped.n_events == full.n_events > 1
    assert stopped.work == full.work
    np.testing.assert_array_equal(stopped.circuit_open_intervals,
                                  full.circuit_open_intervals)


def test_a_stop_the_circuit_rule_does_not_confirm_is_run_again_whole(
        monkeypatch):
    """The answer is circuit.discontinuity's: planted to see no event in
    the stopped run, the full run is taken instead."""
    real = stop_event.circuit.discontinuity
    seen = []

    def blind(upper, lower, min_open):
        seen.append(len(upper))
        return dict(real(upper, lower, min_open), chatters=False)

    full = _run("steel_relay", 0.0, None)
    # the stop's own check only: simulate's figures keep the real rule
    monkeypatch.setattr(stop_event, "circuit", type(
        "Planted", (), {"discontinuity": staticmethod(blind)}))
    stopped = _run("steel_relay", 0.0, None, stop_at_event=True)
    assert seen                       # the stopped run was re-checked
    assert stopped.status == status.OK and math.isnan(stopped.stopped_s)
    assert stopped.work == full.work


def _spy(monkeypatch, module):
    """Record the stop_at_event and the status of every simulate() that
    ``module`` makes."""
    seen = []

    def spy(*args, **keywords):
        result = simulate(*args, **keywords)
        seen.append((keywords.get("stop_at_event"), result.status))
        return result
    monkeypatch.setattr(module, "simulate", spy)
    return seen


def test_the_preload_search_runs_stop_at_their_first_event(monkeypatch):
    from contactsep.studies.preload import chart as preload
    from contactsep.studies.preload.runs import PreloadRun
    seen = _spy(monkeypatch, preload)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    for load, t_end in ((0.1, None), (0.3907, 0.005)):
        settings = {} if t_end is None else {"t_end": t_end}
        full = _run("steel_relay", load, t_end)
        assert preload._simulate_event(PreloadRun(design, "hertz", settings, load)) \
            is full.chatters
    assert seen == [(True, status.STOPPED_AT_EVENT), (True, status.OK)]
    # a stepper the stop does not cover runs the whole window, refused
    # nowhere
    fixed = {"stepper": "fixed", "t_end": 2e-3}
    assert preload._simulate_event(PreloadRun(design, "hertz", fixed, 0.0)) is \
        _run("steel_relay", 0.0, 2e-3, stepper="fixed").chatters
    assert seen[-1] == (False, status.OK)


def test_the_robust_search_samples_stop_at_their_first_event(monkeypatch):
    from contactsep.studies.preload import robust as preload_robust
    from contactsep.studies.sweep import chatter as chatter_sweep
    from contactsep.studies.preload.runs import SampleRun
    seen = _spy(monkeypatch, chatter_sweep)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    fields = {name: getattr(design, name)
              for name in type(design).__dataclass_fields__}
    events, code = preload_robust._sample_run(SampleRun(fields, "hertz", {},
                                                     0.1))
    assert seen == [(True, status.STOPPED_AT_EVENT)]
    # "at least one": all the search reads of it, and its status is ok
    assert events >= 1 and code == 0
    assert _run("steel_relay", 0.1, None).n_events >= events
