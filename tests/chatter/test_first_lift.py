"""The lower contact's first lift (``first_lift_in``, chatter.circuit.
first_lift): the largest sampled lower gap from the first impact to half
a period of the lower contact's first mode after it.  Checked against a
swing of known peak, its refusals, and on runs of the family: never
above the largest gap over the window (tracked at every step), and
read over the span the lower contact's own first mode sets (from the
cantilever's published k_1 L, not the package's modes)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from design_family import FAMILY

from contactsep import chatter
from contactsep.chatter import circuit

G = 386.4


def test_a_swing_of_known_peak_is_read_to_the_sampling_bound():
    t0, half, peak = 0.01, 0.02, 3e-3
    for count in (100, 1000, 10_000):
        t = np.linspace(0.0, 0.05, int(count * 0.05 / half) + 1)
        gap = np.where((t >= t0) & (t <= t0 + half),
                       peak * np.sin(np.pi * (t - t0) / half), -1e-6)
        gap[t > t0 + half] = 2 * peak        # after the swing: not read
        lift = circuit.first_lift(t, gap, t0, half)
        spacing = t[1] - t[0]
        assert lift <= peak
        # the nearest sample is at most half a spacing from the peak
        assert lift >= peak * math.cos(np.pi * spacing / (2 * half))


def test_no_impact_or_too_few_samples_is_nan():
    t = np.linspace(0.0, 1.0, 1001)
    gap = np.ones_like(t)
    assert math.isnan(circuit.first_lift(t, gap, math.nan, 0.5))
    assert math.isnan(circuit.first_lift(t, gap, 0.1, 0.05))   # 50 samples
    assert circuit.first_lift(t, gap, 0.1, 0.2) == 1.0
    assert math.isnan(circuit.first_lift(t[:1], gap[:1], 0.0, 0.5))


@pytest.mark.parametrize("name", ["steel_relay", "bronze_offset",
                                  "becu_light"])
def test_on_the_family_it_is_the_first_swing_of_the_lower_contact(name):
    design = FAMILY[name].replace(n_modes=16)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = chatter.simulate(design, single_impulse=False)
    # the lower contact's first period from the published k_1 L = 1.87510407
    h, length = float(design.h3), float(design.L3)
    a = math.sqrt(float(design.E3) * h**2 / 12.0 * G / float(design.gamma3))
    half = math.pi / (1.87510407**2 * a / length**2)
    inside = (r.t >= r.first_impact_s) & (r.t <= r.first_impact_s + half)
    assert r.first_lift_in == pytest.approx(np.max(r.gap_lower[inside]),
                                            rel=1e-12)
    assert 0.0 < r.first_lift_in <= r.max_lower_gap_in
    assert r.to_json_dict()["first_lift_in"] == r.first_lift_in


def test_without_samples_it_is_nan():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = chatter.simulate(FAMILY["steel_thick"].replace(n_modes=8),
                             samples=1, single_impulse=False)
    assert math.isnan(r.first_lift_in)
