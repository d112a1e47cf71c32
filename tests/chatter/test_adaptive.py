"""The adaptive steppers (fortran/chatter/adaptive*.f90) against the
fixed-step ones, and one Hertz impact against its closed form.

Error model, Hertz.  Where a contact may close, the adaptive stepper
takes the fixed-step splitting's own steps on the same grid; elsewhere
it merges runs of force-free steps into one exact flow, which the
splitting would have composed step by step.  In exact arithmetic the two
are one trajectory; they differ by round-off (the composed rotations),
which the contact dynamics amplify: measured over the 0.06 s window,
gaps within 4.2e-8 in, first impulse within 4e-11, largest lower gap
within 1.7e-7 relative and every open/close instant within 0.03 dt.
With a preload the fixed-step splitting rocks at its O(dt^2) fixed point
while the adaptive stepper holds the static start still, and the
difference grows after the first impact: the preloaded cases run to
0.025 s (measured gaps within 1.2e-9 in, instants within 0.002 dt, the
first impulse within 3e-8 relative: the upper contact meets a separator
rocking by O(dt^2)).
Tolerances: 10x or more over the measured.

Newton.  The adaptive stepper (exact flow, the impulse at mid-step) and
Moreau-Jean (trapezoidal) are different schemes with one limit: on the
thesis rig at N = 4 (largest lower gap, limit 0.08643 in: Moreau-Jean
at 2e-9 s) the adaptive stepper at its default 5e-8 s is 4.5e-4 below
it, Moreau-Jean at 1e-8 s 3.0e-4 below: they agree to 1e-3, the first
impacts within 2 dt, the first impulses to 1e-4 (measured 1.2e-7).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import contactsep
from contactsep import chatter
from contactsep.chatter.laws import HertzLaw

api = pytest.importorskip("contactsep.chatter._chatter").chatter_api


@pytest.mark.parametrize("n, d, preload, damping, t_end", [
    (4, 0.125, 0.0, "none", 0.06),
    (8, 0.75, 0.0, "flores", 0.06),
    (16, 0.25, 0.0, "none", 0.06),
    (8, 0.25, 0.1, "none", 0.025),
    (8, 0.5, 0.3, "flores", 0.025)])
def test_the_adaptive_hertz_stepper_is_the_fixed_step_one(n, d, preload,
                                                          damping, t_end):
    design = contactsep.thesis_design(n_modes=n, d=d)
    dt = 5e-8
    options = dict(model="hertz", dt=dt, preload=preload, damping=damping,
                   t_end=t_end)
    fast = chatter.simulate(design, **options)
    # the reference sampled at every step: its crossings interpolated
    # within one step
    fixed = chatter.simulate(design, stepper="fixed",
                             samples=int(round(t_end / dt)), **options)
    assert fast.work["fixed_steps"] < 0.25 * fixed.work["fixed_steps"]
    same = np.searchsorted(fixed.t, fast.t)
    np.testing.assert_allclose(fixed.t[same], fast.t, rtol=0, atol=1e-15)
    for a, b in ((fast.gap_upper, fixed.gap_upper[same]),
                 (fast.gap_lower, fixed.gap_lower[same])):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-6 * 0.5)
    assert fast.first_impact_s == fixed.first_impact_s
    assert fast.first_impulse_lb_s == pytest.approx(
        fixed.first_impulse_lb_s, rel=3e-7 if preload else 1e-9)
    assert fast.max_lower_gap_in == pytest.approx(fixed.max_lower_gap_in,
                                                  rel=1e-5)
    assert fast.circuit_open_intervals.shape == \
        fixed.circuit_open_intervals.shape
    np.testing.assert_allclose(fast.circuit_open_intervals,
                               fixed.circuit_open_intervals, rtol=0,
                               atol=0.3 * dt)
    np.testing.assert_allclose(fast.energy, fixed.energy[same], rtol=1e-6)


def test_adaptive_newton_and_moreau_jean_share_their_limit():
    design = contactsep.thesis_design(n_modes=4)
    fast = chatter.simulate(design, model="newton", samples=1, dt=5e-8,
                            t_end=0.06)
    reference = chatter.simulate(design, model="newton", dt=1e-8,
                                 stepper="fixed", samples=1, t_end=0.06)
    assert abs(fast.first_impact_s - reference.first_impact_s) < 2 * fast.dt
    assert fast.first_impulse_lb_s == pytest.approx(
        reference.first_impulse_lb_s, rel=1e-4)
    assert fast.max_lower_gap_in == pytest.approx(
        reference.max_lower_gap_in, rel=1e-3)
    assert fast.first_circuit_open_s == pytest.approx(
        reference.first_circuit_open_s, abs=2 * fast.dt)


def _textbook_hertz_constant(modulus, nu, radius):
    """k of F = k delta^{3/2} for a sphere of radius R on a flat of the
    same material (Johnson, Contact Mechanics, eq. 4.22-4.23):
    1/E* = 2 (1 - nu^2) / E, k = (4/3) E* sqrt(R)."""
    e_star = 1.0 / (2.0 * (1.0 - nu**2) / modulus)
    return 4.0 / 3.0 * e_star * math.sqrt(radius)


def test_one_hertz_impact_has_the_closed_form_duration_and_peak_force():
    """A free mass m at speed v on a rigid flat through the Hertz law:
    delta_max = (5 m v^2 / (4 k))^(2/5), the force peaks at
    k delta_max^(3/2) and the contact lasts
    2 (delta_max / v) int_0^1 (1 - x^(5/2))^(-1/2) dx
    = (4/5) B(2/5, 1/2) delta_max / v, with k the textbook constant of
    the default button (R = 0.125 in, nu = 0.33, aluminium E = 1e7 psi).
    The simulation's penetration, force and contact time (its crossings
    of the threshold 0 on the exact flow) are the stepper's."""
    law = HertzLaw.for_materials(10.0e6)
    k = _textbook_hertz_constant(10.0e6, 0.33, 0.125)
    mass, speed, height = 1e-3, 10.0, 1e-4
    delta = (5.0 * mass * speed**2 / (4.0 * k)) ** 0.4
    beta = math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
    duration = 0.8 * beta * delta / speed
    peak = k * delta**1.5
    dt = 1e-8
    t_end = height / speed + 1.5 * duration
    steps = int(round(t_end / dt))
    # one mode of negligible stiffness: a free mass (p t_end ~ 1e-6)
    p = np.array([1e-3])
    out = api.run_hertz_adaptive(
        np.array([mass]), p, np.ones((1, 1)), np.zeros(1), np.zeros((1, 1)),
        np.array([height]), np.array([-speed]), law.k, 0.0, dt, steps, 1,
        steps + 1, 0.0, 1, mass * speed**2, 100)
    t, gaps, _, first, crossings, n_cross, _, _, status = out
    assert status == 0 and n_cross == 2
    (closes, code_in), (opens, code_out) = crossings[:, :2].T
    assert (code_in, code_out) == (-1, 1)
    assert closes == pytest.approx(height / speed, rel=1e-9)
    assert opens - closes == pytest.approx(duration, rel=1e-4)
    depth = -gaps[0].min()
    assert depth == pytest.approx(delta, rel=1e-4)
    assert law.k * depth**1.5 == pytest.approx(peak, rel=1e-4)
    # elastic: the impulse returns the momentum
    assert first[1] == pytest.approx(2 * mass * speed, rel=1e-4)


@pytest.mark.parametrize("seed", range(12))
def test_random_designs_adaptive_against_fixed_step(seed):
    """Random separators (end conditions, d), restitution, release height,
    lower-contact length, N 1-16, preload, damping; 0.03 s.  Measured on
    30 such designs: the same openings, instants within 1.8 dt (with a
    preload; 0 without), gaps within 1.5e-7 in, first impulse within
    2.3e-7; and Newton's energy never grows."""
    rng = np.random.default_rng(seed)
    design = contactsep.thesis_design(
        n_modes=int(rng.integers(1, 17)), d=float(rng.uniform(0.1, 0.8)),
        e=float(rng.uniform(0.2, 0.99)), ys=float(rng.uniform(0.05, 0.8)),
        L3=float(rng.uniform(10.0, 25.0)),
        end2=str(rng.choice(["clamped-clamped", "pinned-pinned",
                             "clamped-pinned"])))
    dt, t_end = 5e-8, 0.03
    options = dict(model="hertz", dt=dt, t_end=t_end,
                   preload=float(rng.choice([0.0, 0.05, 0.3])),
                   damping=str(rng.choice(["none", "flores"])))
    fast = chatter.simulate(design, **options)
    fixed = chatter.simulate(design, stepper="fixed",
                             samples=int(round(t_end / dt)), **options)
    same = np.searchsorted(fixed.t, fast.t)
    for a, b in ((fast.gap_upper, fixed.gap_upper[same]),
                 (fast.gap_lower, fixed.gap_lower[same])):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-6)
    assert fast.first_impulse_lb_s == pytest.approx(
        fixed.first_impulse_lb_s, rel=2e-6)
    assert fast.circuit_open_intervals.shape == \
        fixed.circuit_open_intervals.shape
    np.testing.assert_allclose(fast.circuit_open_intervals,
                               fixed.circuit_open_intervals, rtol=0,
                               atol=5 * dt)
    newton = chatter.simulate(design, model="newton", t_end=t_end,
                              preload=options["preload"], samples=1000)
    assert np.all(np.diff(newton.energy) <= 1e-9 * newton.energy[0])
