"""The discontinuity criterion: exact open and close instants on analytic
gap histories (through the interpolation of samples and through the
adaptive stepper's search on the exact flow), events shorter than
min_open not counted, nothing past t_end, no zero-length interval."""

from __future__ import annotations

import math

import numpy as np
import pytest

import contactsep
from contactsep import chatter
from contactsep.chatter import circuit

api = pytest.importorskip("contactsep.chatter._chatter").chatter_api


def test_sampled_crossings_are_the_interpolated_roots():
    """A piecewise-linear gap is its own interpolant: the crossings are
    exact (t = 0.5 rising through 1, 2 + 1/3 falling from 2 to -1, and
    4, where the gap touches 1 (not open) and goes on rising)."""
    t = np.arange(6.0)
    gap = np.array([0.0, 2.0, 2.0, -1.0, 1.0, 3.0])
    times, opening = circuit.crossings_from_samples(t, gap, threshold=1.0)
    np.testing.assert_allclose(times, [0.5, 2 + 1 / 3, 4.0], rtol=0,
                               atol=1e-15)
    assert opening.tolist() == [True, False, True]


def test_intervals_stop_at_t_end_and_are_never_empty():
    # open at the start; a zero-length opening at 0.3; a crossing past
    # the window (rounding of a step count) is clipped to it
    spans = circuit.open_intervals(
        True, [0.1, 0.3, 0.3, 0.5, 0.060000000000000005 + 1],
        [False, True, False, True, False], t_end=1.0)
    assert spans.tolist() == [[0.0, 0.1], [0.5, 1.0]]
    assert circuit.open_intervals(False, [], [], 1.0).shape == (0, 2)
    assert circuit.open_intervals(True, [], [], 1.0).tolist() == [[0, 1]]


def test_events_are_the_openings_of_at_least_min_open():
    """Circuit open = both contacts open; an event lasts >= min_open;
    the totals count every opening."""
    upper = np.array([[0.1, 0.3], [0.5, 0.5 + 9e-6], [0.6, 0.7]])
    lower = np.array([[0.2, 0.65], [0.69, 2.0]])
    found = circuit.discontinuity(upper, lower, min_open=1e-5)
    expected = [[0.2, 0.3], [0.5, 0.5 + 9e-6], [0.6, 0.65], [0.69, 0.7]]
    np.testing.assert_allclose(found["circuit_open_intervals"], expected,
                               rtol=0, atol=1e-15)
    assert found["n_events"] == 3 and found["chatters"]
    np.testing.assert_allclose(found["events"],
                               [expected[0], expected[2], expected[3]],
                               rtol=0, atol=1e-15)
    assert found["circuit_open_s"] == pytest.approx(0.1 + 9e-6 + 0.05
                                                    + 0.01, abs=1e-15)
    assert found["first_circuit_open_s"] == 0.2
    assert found["longest_open_s"] == pytest.approx(0.1, abs=1e-15)
    every = circuit.discontinuity(upper, lower, min_open=0.0)
    assert every["n_events"] == 4
    none = circuit.discontinuity(upper, lower, min_open=1.0)
    assert none["n_events"] == 0 and not none["chatters"]
    assert none["circuit_open_s"] == found["circuit_open_s"]


def _free_modes(p, amplitude, offset, t_end, dt, threshold):
    """Two contacts, each watching one free mode that never closes it:
    g_c(t) = offset_c + amplitude_c cos(p_c t)."""
    n = 2
    h = np.eye(n)
    m = np.ones(n)
    q0 = np.asarray(amplitude, dtype=float)
    v0 = np.zeros(n)
    energy = 0.5 * np.sum(m * (p * q0)**2)
    steps = int(round(t_end / dt))
    out = api.run_hertz_adaptive(
        m, p, h, np.asarray(offset, float), np.zeros((len(offset),) * 2),
        q0, v0, 1.0, 0.0, dt, steps,
        steps, 2, threshold, n, 2.0 * energy, 1000)
    _, _, _, _, crossings, n_cross, gap_max, counts, status = out
    assert status == 0
    return crossings[:, :n_cross], gap_max, counts


def test_the_adaptive_stepper_finds_exact_crossings_of_the_flow():
    """No contact closes, so the stepper only flies and searches: each
    crossing of the threshold is acos((thr - offset) / A) / p (+ periods)
    to round-off, both gaps, in time order, with the right direction;
    one gap dips below the threshold for only 0.1 % of its period."""
    p = np.array([2 * math.pi * 100.0, 2 * math.pi * 37.0])
    threshold = 1e-6
    amplitude = np.array([1e-3, 2e-4])
    dip = 1.0 - math.cos(math.pi * 1e-3)          # a 0.1 % dip
    offset = np.array([1e-3 + 0.5e-6, threshold + amplitude[1] * (1 - dip)])
    t_end, dt = 0.05, 1e-7
    crossings, gap_max, counts = _free_modes(p, amplitude, offset, t_end,
                                             dt, threshold)
    assert counts[1] == 0                       # never a fixed step
    expected = []
    for c in range(2):
        phase = math.acos((threshold - offset[c]) / amplitude[c])
        period = 2 * math.pi / p[c]
        for j in range(int(t_end / period) + 2):
            for sign, code in ((1, -(c + 1)), (-1, c + 1)):
                when = (j * 2 * math.pi + sign * phase) / p[c]
                if 0 < when <= t_end:
                    expected.append((when, code))
    expected.sort()
    assert crossings.shape[1] == len(expected) > 10
    np.testing.assert_allclose(crossings[0], [e[0] for e in expected],
                               rtol=0, atol=1e-14)
    assert crossings[1].tolist() == [e[1] for e in expected]
    # the largest second gap: offset + amplitude at t = 0 and each period
    assert gap_max[0, 1] == pytest.approx(offset[1] + amplitude[1],
                                          rel=1e-12)


def test_simulated_intervals_end_in_the_window():
    """The thesis rig opens until the end of the window: its last
    interval ends at t_end exactly (not one rounding past it), none is
    empty, and the events are the intervals of at least min_open."""
    r = chatter.simulate(contactsep.thesis_design(n_modes=4), model="hertz",
                         samples=100, dt=5e-8, t_end=0.06)
    spans = r.circuit_open_intervals
    assert spans[-1, 1] == 0.060 and np.all(spans <= 0.060)
    assert np.all(spans[:, 1] > spans[:, 0])
    long = spans[spans[:, 1] - spans[:, 0] >= r.min_open_s]
    np.testing.assert_array_equal(r.events, long)
    assert r.n_events == len(long) and r.chatters
    assert r.longest_open_s == np.max(spans[:, 1] - spans[:, 0])
    every = chatter.simulate(contactsep.thesis_design(n_modes=4),
                             model="hertz", samples=100, min_open=0.0,
                             dt=5e-8, t_end=0.06)
    assert every.n_events == len(spans)
    assert every.circuit_open_s == r.circuit_open_s
