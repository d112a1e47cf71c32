"""Cheap versions of the slow studies' catches in the default run
(issue 26): the preload search's event rule, and each conclusion study's
first row, at small N with the preload search stubbed out (its own
tests: test_preload.py).  Every simulate call of these tests goes
through package_call.run, with every setting explicit."""

from __future__ import annotations

import numpy as np
import pytest

from contactsep.model import evaluate, thesis_design
from contactsep.studies.thesis import conclusions
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload.runs import PreloadRun
from package_call import run

N = 2
DT = 5e-8


def test_the_preload_search_counts_only_openings_of_at_least_min_open():
    """The search's one simulation (preload._simulate_event) has an
    event when some opening lasts at least min_open, not when the
    circuit merely opens: min_open just above the longest opening gives
    no event, min_open equal to it one."""
    design = thesis_design(n_modes=N)
    window = dict(dt=DT, t_end=0.03)
    # the search runs simulate() with its defaults: the static correction
    free = run(design, samples=1, min_open=0.0, static_correction=True,
               **window)
    longest = free.longest_open_s
    assert longest > 0.0 and free.circuit_open_s > 0.0
    settings = dict(damping="none", **window)
    above = dict(settings, min_open=float(np.nextafter(longest, 1.0)))
    assert not preload._simulate_event(
        PreloadRun(design, "hertz", above, 0.0))
    assert preload._simulate_event(
        PreloadRun(design, "hertz", dict(settings, min_open=longest), 0.0))


@pytest.mark.parametrize("name, field, damping", [
    ("conclusion3", "e", "flores"),
    ("conclusion5", "h2", "none"),
    ("conclusion6", "gamma2", "none"),
    ("conclusion7", "x3", "none"),
])
def test_each_conclusions_first_row(name, field, damping, monkeypatch):
    """Each study's first row (its rows cut to the first, the preload
    search stubbed): eq. 23's y3 is evaluate()'s, and the no-preload
    columns are a simulation of that row's design with the study's law
    (Flores damping for conclusion 3, elastic otherwise), window
    0.06 s, the model's step."""
    first = conclusions._values(name, thesis_design(n_modes=N))[:1]
    monkeypatch.setattr(conclusions, "_values", lambda *_: first)
    stub = preload.PreloadSearch(min_preload_lb=1.0, tested=((1.0, False),))
    monkeypatch.setattr(conclusions, "min_preloads",
                        lambda designs, *a, **k: [stub for _ in designs])
    study = conclusions.conclusion(name, n_modes=N, dt=DT, workers=1)
    design = thesis_design(n_modes=N, **{field: float(first[0])})
    # the thesis's studies keep eq. 23 as printed (the model's default is
    # the impulse form)
    printed = evaluate(design.replace(lower_response="as-printed"))
    assert study["y3_max_in"][0] == pytest.approx(printed.y3_max,
                                                  rel=1e-12)
    free = run(design, dt=DT, t_end=0.06, samples=1, damping=damping,
               static_correction=True)   # the studies' default
    assert study["max_lower_gap_in"][0] == pytest.approx(
        free.max_lower_gap_in, rel=1e-9)
    assert study["circuit_open_s"][0] == pytest.approx(free.circuit_open_s,
                                                       rel=1e-9)
    assert study["n_events"][0] == free.n_events
