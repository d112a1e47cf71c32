"""The stepper registry: every (model, stepper, backend) simulate steps in
time runs the function, with the arguments, that simulate's former
if/elif chose (the expected calls are written out here by hand from that
if/elif, not read from the registry); simulate asks it for its own
combination, and a warning of one of simulate's steps names its caller."""

from __future__ import annotations

import importlib
import itertools
from types import SimpleNamespace

import numpy as np
import pytest

import contactsep
from contactsep.chatter import runners, stepper_registry, stop_event
from contactsep.chatter.settings import ChatterError
from contactsep.chatter.limits import MODELS, STEPPERS
from contactsep.chatter.stack import COARSE_DT, CoarseStepWarning
from contactsep.chatter.stepper_registry import RunRequest

sim = importlib.import_module("contactsep.chatter.simulate")

BACKENDS = ("compiled", "numpy")
RUNNERS = ("newton_adaptive", "moreau_jean", "moreau_jean_numpy",
           "hertz_adaptive", "hertz_fixed")
E, THETA, DT, STEPS, STRIDE, THRESHOLD, STOP = (0.7, 0.6, 1e-7, 40, 4,
                                                2e-6, 3e-5)
STACK = SimpleNamespace(m=np.ones(6))
LAW = object()


def expected(model, stepper, backend):
    """The runner and its arguments after the system, as the if/elif of
    simulate._run chose them: Newton adaptive on the compiled backend;
    other Newton runs Moreau-Jean (its NumPy twin on numpy); Hertz
    adaptive on the compiled backend; every other Hertz run the
    fixed-step splitting, told its backend."""
    if model == "newton":
        if stepper == "adaptive" and backend == "compiled":
            return "newton_adaptive", (E, DT, STEPS, STRIDE, THRESHOLD,
                                       STOP)
        name = "moreau_jean" if backend == "compiled" else \
            "moreau_jean_numpy"
        return name, (E, DT, THETA, STEPS, STRIDE, THRESHOLD)
    if stepper == "adaptive" and backend == "compiled":
        return "hertz_adaptive", (LAW, DT, STEPS, STRIDE, THRESHOLD, STOP)
    return "hertz_fixed", (LAW, DT, STEPS, STRIDE, THRESHOLD, backend)


STEPPED = [key for key in itertools.product(MODELS, STEPPERS, BACKENDS)
           if key[0] != "appE"]


@pytest.fixture
def calls(monkeypatch):
    """Every runner replaced by one that records its call."""
    seen = []
    for name in RUNNERS:
        def record(system, *args, name=name):
            seen.append((name, system, args))
            return name
        monkeypatch.setattr(runners, name, record)
    return seen


def test_the_registry_holds_every_stepped_combination_and_no_other():
    # 2 stepped models x 2 steppers x 2 backends; appE takes no step
    assert len(STEPPED) == 8
    assert set(stepper_registry.REGISTRY) == set(STEPPED)


@pytest.mark.parametrize("model,stepper,backend", STEPPED)
def test_each_combination_runs_the_function_the_if_elif_chose(
        calls, model, stepper, backend):
    request = RunRequest(model, stepper, backend, STACK,
                         None if model == "newton" else LAW,
                         SimpleNamespace(e=E), THETA, DT, STEPS, STRIDE,
                         THRESHOLD, STOP)
    name, args = expected(model, stepper, backend)
    assert sim._run(request) == name
    assert calls == [(name, STACK, args)]


@pytest.mark.parametrize("key", [("appE", "adaptive", "compiled"),
                                 ("hertz", "leapfrog", "compiled"),
                                 ("newton", "fixed", "gpu")])
def test_a_combination_without_a_stepper_is_refused_in_one_line(key):
    with pytest.raises(ChatterError) as info:
        stepper_registry.lookup(*key)
    message = str(info.value)
    assert "\n" not in message and message.startswith("stepper: found")
    assert repr(key[1]) in message and repr(key[0]) in message


class Stop(Exception):
    """Raised by the recording _run: the test needs no run."""


@pytest.mark.parametrize("model,stepper,backend", STEPPED)
def test_simulate_asks_the_registry_for_its_own_combination(
        monkeypatch, model, stepper, backend):
    seen = []

    def record(request):
        seen.append(request)
        raise Stop
    monkeypatch.setattr(sim, "_run", record)
    design = contactsep.thesis_design(n_modes=4)
    with pytest.raises(Stop):
        sim.simulate(design, model=model, stepper=stepper, backend=backend,
                     theta=0.75, open_threshold=3e-6, t_end=1e-3,
                     samples=10, single_impulse=False)
    (request,) = seen
    assert request.key == (model, stepper, backend)
    assert (request.theta, request.open_threshold) == (0.75, 3e-6)
    assert request.stop_open == stop_event.NEVER
    assert request.design is design and request.stack.m.size == 12
    assert (request.law is None) == (model == "newton")
    assert request.steps * request.dt == pytest.approx(1e-3, rel=1e-12)
    assert request.stride == max(1, request.steps // 10)


def test_a_coarse_step_is_warned_at_simulates_caller():
    """The step is chosen in a step of simulate's, the warning still
    names the line that called simulate (as a warning filter sees it)."""
    design = contactsep.thesis_design(n_modes=4)
    chosen = sim.simulate(design, t_end=2e-3, single_impulse=False,
                          samples=10).numerics["design_dt_s"]
    with pytest.warns(CoarseStepWarning) as seen:
        sim.simulate(design, t_end=2e-3, dt=4 * COARSE_DT * chosen,
                     single_impulse=False, samples=10)
    assert [w.filename for w in seen] == [__file__]
