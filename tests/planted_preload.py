"""A planted preload physics for the preload command's tests: the search
sees only whether a run has an event, so a fake with a known threshold
(and a known tolerance study) tests the search and its bookkeeping, not
the simulation.  Module-level, so that pool workers can run them; the
fixture ``planted_preload`` (tests/conftest.py) plants them."""

from __future__ import annotations

import types

import pytest

from contactsep.chatter.stack import largest_preload
from contactsep.studies.preload import command as design_preload
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload import robust as preload_robust
CALLS: list = []


def threshold(design, settings) -> float:
    """A quarter of the largest preload the design takes x (1 + 1/N) x
    (1 + dt/1e-7): half the step and twice the modes move it by a known
    amount."""
    n = design.n_modes if isinstance(design.n_modes, int) else max(
        design.n_modes)
    return 0.25 * largest_preload(design) * (1.0 + 1.0 / n) * (
        1.0 + settings.get("dt", 5e-8) / 1e-7)


def fake_event(task) -> bool:
    design, load = task.design, task.preload_lb
    settings = task.settings
    CALLS.append(("event", load))
    return load < threshold(design, settings)


def _probe(where, design, preload, settings):
    """The probe simulate() a search makes, under the threshold
    ``where(design, settings)``: an opening of 20 us below it, 5 us
    above."""
    settings.pop("samples", None)
    settings.pop("single_impulse", None)
    return types.SimpleNamespace(
        dt=settings.get("dt", 5e-8), open_threshold_in=1e-6,
        min_open_s=1e-5, t_end_s=0.06,
        longest_open_s=2e-5 if preload < where(design, settings)
        else 5e-6)


def fake_simulate(design, model, preload=0.0, **settings):
    return _probe(threshold, design, preload, settings)


def fake_sample(fields, model, settings):
    """A tolerance study: an event below 10 lb per inch of the
    separator's thickness."""
    CALLS.append(("sample", settings["preload"]))
    event = settings["preload"] < 10.0 * fields["h2"]
    return (0.0,) * 5 + (int(event), 0)


def plant(monkeypatch):
    """The nominal runs, the probe and the samples planted; CALLS
    emptied."""
    monkeypatch.setattr(preload, "_simulate_event", fake_event)
    monkeypatch.setattr(design_preload, "simulate", fake_simulate)
    monkeypatch.setattr(preload_robust, "simulate_design", fake_sample)
    CALLS.clear()


@pytest.fixture
def planted_preload(monkeypatch):
    """:func:`plant`, for one test."""
    plant(monkeypatch)


def plant_threshold(monkeypatch, where):
    """Plant an event below ``where(design, settings)`` lb instead of
    :func:`threshold`; every run is kept in CALLS as ("event", preload,
    N), so that a test can tell the runs at N from those at 2N."""
    def event(task):
        design, load = task.design, task.preload_lb
        settings = task.settings
        CALLS.append(("event", load, design.n_modes))
        return load < where(design, settings)

    def simulate(design, model, preload=0.0, **settings):
        return _probe(where, design, preload, settings)
    monkeypatch.setattr(preload, "_simulate_event", event)
    monkeypatch.setattr(design_preload, "simulate", simulate)
    CALLS.clear()


def fake_zero_preload(task):
    """A conclusion study's run with no preload: (largest lower gap,
    open time, events) from the separator's thickness alone."""
    design = task.design
    CALLS.append(("free", float(design.h2)))
    return 0.01 * float(design.h2), 0.0, 0
