"""Steppers that always end (issue 31, item 2; issue 26's energy bound):
every compiled stepper loop stops at a hard energy bound (status 7,
ENERGY_BOUND) and at the stop flag Ctrl-C and SIGTERM set (status 8,
INTERRUPTED); a blown-up run reports no circuit figures; the step/mode
budget is refused before the run, with its numbers."""

from __future__ import annotations

import importlib
import math
import threading
import time
import warnings

import numpy as np
import pytest
from hostile_cli import main, refusal, strict_json

from contactsep.chatter import simulate, status
from contactsep.chatter import steppers as twins
from contactsep.chatter.laws import HertzLaw
from contactsep.chatter.stack import _system
from contactsep.errors import InputError
from contactsep.model import thesis_design

api = importlib.import_module("contactsep.chatter._chatter").chatter_api


def _coarse(**kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return simulate(thesis_design(), model="hertz", dt=1e-3, t_end=0.06,
                        **kwargs)


def test_the_coarse_hertz_step_really_blows_up_in_the_numpy_twin():
    """The independent path: the NumPy twin of the Hertz splitting at
    dt = 1e-3 s takes the energy far past twice the release's (or to
    NaN), so stopping that run is right, not a false alarm."""
    law = HertzLaw.for_materials(10.0e6)
    s = _system(thesis_design(), 0.0, law)
    with np.errstate(all="ignore"):
        _, _, energy, _, _ = twins.hertz(s.m, s.p, s.h, s.g0, s.q0, s.v0,
                                         law=law, dt=1e-3, steps=60)
    assert not np.all(energy <= 2.0 * energy[0])


@pytest.mark.parametrize("stepper", ["fixed", "adaptive"])
def test_a_blown_up_hertz_run_stops_with_no_circuit_figures(stepper):
    """The issue's case: dt = 1e-3 s reported circuit_open_s 6e-5 and
    one event (fixed); the adaptive stepper never ended."""
    start = time.monotonic()
    result = _coarse(stepper=stepper)
    assert time.monotonic() - start < 10.0
    assert result.status == status.ENERGY_BOUND
    assert math.isnan(result.circuit_open_s)
    assert math.isnan(result.max_lower_gap_in)
    assert math.isnan(result.first_lift_in)
    assert math.isnan(result.first_circuit_open_s)
    assert result.n_events == -1 and not result.chatters
    data = result.to_json_dict()
    assert data["status"] == 7 and data["circuit_open_s"] is None
    # the samples it reached (every 1 ms), NaN after the stop
    reached = ~np.isnan(result.t)
    assert reached[0] and not reached[-1]
    assert np.array_equal(reached, np.arange(len(result.t)) < reached.sum())
    assert np.allclose(result.t[reached], 1e-3 * np.arange(reached.sum()))
    assert np.all(np.isnan(result.gap_upper[~reached]))


@pytest.mark.parametrize("d, dt", [(0.1, 3e-5), (0.1, 1e-4)])
def test_the_adaptive_stepper_ends_at_other_coarse_steps(d, dt):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        start = time.monotonic()
        result = simulate(thesis_design(d), model="hertz", dt=dt,
                          t_end=0.06)
    assert time.monotonic() - start < 10.0
    # it ends: converged, stopped at the bound, or flagged unconverged
    # by the energy check (issue 25)
    assert result.status in (status.OK, status.ENERGY_BOUND,
                             status.UNCONVERGED)
    if result.status != status.ENERGY_BOUND:
        assert abs(result.energy_ratio - 1.0) < 1.0


def test_a_converged_run_is_status_ok():
    result = simulate(thesis_design(), model="hertz")
    assert result.status == status.OK
    assert math.isfinite(result.circuit_open_s)


def test_the_cli_refuses_a_blown_up_run(capsys):
    """exit 2, one line naming --dt; no JSON of NaN figures."""
    code, out, err = main(capsys, "chatter", "--model", "hertz",
                          "--stepper", "fixed", "--dt", "1e-3", "--json")
    message = refusal(code, err)
    assert message.startswith("--dt: ") and "status 7" in message
    assert out == ""


def _small_system():
    law = HertzLaw.for_materials(10.0e6)
    return _system(thesis_design(n_modes=4), 0.0, law), law


def _energy0(s, law):
    return 0.5 * np.sum(s.m * (s.v0**2 + (s.p * s.q0)**2)) + np.sum(
        law.energy(s.h @ s.q0 + s.g0))


def _plain(s):
    """No series compliance (the static correction off)."""
    return np.zeros((s.g0.size, s.g0.size))


@pytest.mark.parametrize("which", ["hertz", "moreau_jean",
                                   "hertz_adaptive", "newton_adaptive"])
def test_every_compiled_loop_honours_a_tight_energy_bound(which):
    """A bound below the release's energy: each loop stops with status
    7 (the adaptive ones check it where the energy can change: at the
    contacts, reached at 0.022 s); a bound of 1e300 (twice the energy,
    adaptive): status 0, the same run."""
    s, law = _small_system()
    dt, steps = 5e-7, 60_000

    def call(bound):
        if which == "hertz":
            out = api.run_hertz(s.m, s.p, s.h, s.g0, _plain(s), s.q0, s.v0, law.k,
                                law.chi, dt, steps, 100, steps // 100 + 1,
                                energy_bound=bound)
        elif which == "moreau_jean":
            out = api.run_moreau_jean(s.m, s.p, s.h, s.g0, s.q0, s.v0,
                                      0.375, dt, 0.5, steps, 100,
                                      steps // 100 + 1, 1e-6, 4096,
                                      energy_bound=bound)
        elif which == "hertz_adaptive":
            out = api.run_hertz_adaptive(
                s.m, s.p, s.h, s.g0, _plain(s), s.q0, s.v0, law.k, law.chi,
                dt,
                steps, 100, steps // 100 + 1, 1e-6, s.n_upper, bound, 4096)
        else:
            out = api.run_newton_adaptive(
                s.m, s.p, s.h, s.g0, s.q0, s.v0, 0.375, dt, steps, 100,
                steps // 100 + 1, 1e-6, s.n_upper, bound, 4096)
        return out[-1]

    e0 = _energy0(s, law)
    assert call(1e300 if which in ("hertz", "moreau_jean") else 2 * e0) \
        == status.OK
    assert call(0.5 * e0) == status.ENERGY_BOUND


@pytest.mark.parametrize("which", ["hertz", "moreau_jean",
                                   "hertz_adaptive"])
def test_every_compiled_loop_stops_at_the_flag(which):
    """request_stop() before a long call: it returns status 8 after a
    few thousand steps, long before its end (200 ms, not minutes)."""
    s, law = _small_system()
    dt, steps = 1e-9, 60_000_000
    api.request_stop()
    try:
        start = time.monotonic()
        if which == "hertz":
            code = api.run_hertz(s.m, s.p, s.h, s.g0, _plain(s), s.q0, s.v0, law.k,
                                 law.chi, dt, steps, steps, 2)[-1]
        elif which == "moreau_jean":
            code = api.run_moreau_jean(s.m, s.p, s.h, s.g0, s.q0, s.v0,
                                       0.375, dt, 0.5, steps, steps, 2,
                                       1e-6, 4096)[-1]
        else:
            code = api.run_hertz_adaptive(
                s.m, s.p, s.h, s.g0, _plain(s), s.q0, s.v0, law.k, law.chi,
                dt,
                steps, steps, 2, 1e-6, s.n_upper,
                2 * _energy0(s, law), 4096)[-1]
        took = time.monotonic() - start
    finally:
        api.clear_stop()
    assert code == status.INTERRUPTED
    assert took < 2.0


def test_a_signal_stops_a_run_inside_the_compiled_loop():
    """simulate() in the main thread; a KeyboardInterrupt raised there
    (as Ctrl-C's handler does) 0.7 s into a 1.9 s stepper call (6e6
    fixed steps x 48 modes, below the forked size): raised within
    0.3 s of the signal, not at the call's end, the stepper stopped by
    its flag (the thread the run used is gone)."""
    import _thread

    design = thesis_design(n_modes=16)
    simulate(design, model="hertz", t_end=1e-3)    # modes cached
    fired = []

    def interrupt():
        fired.append(time.monotonic())
        _thread.interrupt_main()

    timer = threading.Timer(0.7, interrupt)
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        simulate(design, model="hertz", stepper="fixed", dt=1e-8)
    ended = time.monotonic()
    timer.cancel()
    assert fired and ended - fired[0] < 0.3, (ended - start)
    assert not any(t.name == "contactsep-stepper" and t.is_alive()
                   for t in threading.enumerate())


def test_the_step_budget_is_refused_before_the_run_with_its_numbers():
    start = time.monotonic()
    with pytest.raises(InputError) as caught:
        simulate(thesis_design(n_modes=1024), model="hertz", t_end=10.0)
    assert time.monotonic() - start < 5.0
    message = str(caught.value)
    # the design's own step at N = 1024 (its highest mode: numerics.py)
    step = float(message.split("the design's step ")[1].split(" s:")[0])
    assert message.startswith("t_end: found 10 s at N = 1024")
    assert f"{10.0 / step:.3g} steps x 3072 modes" in message
    assert "1e+10" in message


def test_the_cli_names_t_end_for_the_budget(capsys):
    code, _, err = main(capsys, "chatter", "--model", "hertz",
                        "--n-modes", "1024", "--t-end", "10")
    assert refusal(code, err).startswith("--t-end: found 10 s")


def test_a_sweep_counts_blown_up_designs_as_status_7(capsys):
    code, out, err = main(capsys, "sweep", "--model", "hertz",
                          "--n-modes", "2", "--vary", "h2=0.2,0.3",
                          "--dt", "3e-4", "--json", "--workers", "1")
    message = refusal(code, err)
    assert "2 energy bound" in message
    assert strict_json(out)["n_failed_by_status"] == {"7": 2}


@pytest.mark.slow
@pytest.mark.parametrize("signum, code", [(2, 130), (15, 143)])
@pytest.mark.parametrize("args", [
    # the regression: 5 s of work given Ctrl-C at 2 s exited 0
    # after finishing (a child process: 3e8 steps x modes and more; dt
    # given: the design's own step at N = 1024, 6.8e-10 s, exceeds the
    # work budget over 0.15 s, a refusal before any work)
    ["--n-modes", "1024", "--dt", "5e-8", "--t-end", "0.15"],
    # below the forked size: the thread and the compiled loop's flag
    ["--stepper", "fixed", "--n-modes", "16", "--dt", "1e-8"],
])
def test_a_long_hertz_run_stops_at_a_signal(tmp_path, signum, code, args):
    from test_signals import PROMPT, _stop
    status_, took, err = _stop(["chatter", "--model", "hertz", *args],
                               signum, 1.0, tmp_path, signum == 2)
    assert status_ == code, err
    assert took < PROMPT


def test_a_stop_asked_of_an_earlier_run_does_not_stop_the_next():
    """The flag is the process's: a run after an interrupted one (an
    interactive session's Ctrl-C) runs to its end."""
    api.request_stop()
    try:
        # 12 modes x 2.4e5 steps: below the threaded size, > 4096 steps
        result = simulate(thesis_design(n_modes=4), model="hertz",
                          stepper="fixed", dt=2.5e-7)
    finally:
        api.clear_stop()
    assert result.status == status.OK


@pytest.mark.parametrize("model", ["hertz", "newton"])
def test_the_bound_never_stops_a_converged_run_of_the_family(model):
    """The family's designs (and the unseen two) at the default steps:
    status 0, elastic Hertz energy kept, Newton's lost (e < 1): the
    bound (twice the release's energy) is met only by a blow-up."""
    from design_family import FAMILY, UNSEEN
    designs = [*FAMILY.values(), *(UNSEEN.values() if isinstance(
        UNSEEN, dict) else UNSEEN)]
    for design in designs:
        result = simulate(design.replace(n_modes=8), model=model,
                          single_impulse=False, samples=1)
        assert result.status == status.OK
        if model == "hertz":
            assert abs(result.energy_ratio - 1.0) < 1e-3
        else:
            assert result.energy_ratio <= 1.0 + 1e-9


def test_a_long_run_stops_at_a_signal_with_other_threads_running():
    """With another thread running (a progress bar's monitor, Dask's),
    a long run cannot go to a forked child and ran in-process, deaf to
    Ctrl-C until its end (one way to the issue's 'exits 0 after
    finishing'): the compiled loop's flag stops it now."""
    import _thread

    design = thesis_design(n_modes=1024)
    simulate(design, model="hertz", t_end=1e-4, dt=5e-8)  # modes cached
    busy = threading.Event()
    other = threading.Thread(target=busy.wait, daemon=True)
    other.start()
    fired = []

    def interrupt():
        fired.append(time.monotonic())
        _thread.interrupt_main()

    timer = threading.Timer(1.0, interrupt)
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            simulate(design, model="hertz", t_end=0.15, dt=5e-8)
        ended = time.monotonic()
    finally:
        timer.cancel()
        busy.set()
    assert fired and ended - fired[0] < 0.5
