"""Identities of the chatter layer that no mistake shared by its twins
survives (issue 26): each holds for the physics whatever the stepper,
and each is checked against a closed form, a symmetry or brute force.
Every simulate call goes through package_call.run (all settings
explicit)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import contactsep
import independent_hertz as ih
from contactsep.chatter import circuit, runners
from contactsep.chatter.laws import HertzLaw
from design_family import FAMILY, UNSEEN
from package_call import run

pytest.importorskip("scipy")
from scipy.integrate import solve_ivp  # noqa: E402


# ------------------------------------------------ mirror symmetry

@pytest.mark.parametrize("end2", ["clamped-clamped", "pinned-pinned"])
def test_a_symmetric_separator_mirrors_its_contact_point(end2):
    """x2 = a and L2 - a give the same run (each mode is symmetric or
    antisymmetric about mid-span: X_j(L - x) = +-X_j(x), and only the
    products X_j(x2) q_j enter), and a different one from mid-span: a
    simulation that ignores x2 fails the second half, one that mirrors
    it wrongly the first."""
    design = contactsep.thesis_design(n_modes=8, d=0.25).replace(end2=end2)
    a = 0.8
    runs = [run(design.replace(x2=x), dt=5e-8, t_end=0.026, samples=520)
            for x in (a, float(design.L2) - a, float(design.L2) / 2)]
    left, right, middle = runs
    # measured 3e-17 and 7e-16 in (round-off of the modal sums)
    np.testing.assert_allclose(left.gap_lower, right.gap_lower, rtol=0,
                               atol=1e-12)
    np.testing.assert_allclose(left.gap_upper, right.gap_upper, rtol=0,
                               atol=1e-12)
    np.testing.assert_allclose(left.circuit_open_intervals,
                               right.circuit_open_intervals, rtol=0,
                               atol=1e-12)
    assert left.first_impulse_lb_s == pytest.approx(
        right.first_impulse_lb_s, rel=1e-12)
    # off mid-span the separator is stiffer and the kick differs:
    # measured 4e-3 in of lower gap, 10 % of the first impulse (clamped)
    assert np.max(np.abs(left.gap_lower - middle.gap_lower)) > 1e-4
    assert abs(left.first_impulse_lb_s / middle.first_impulse_lb_s
               - 1.0) > 0.01


# ---------------------------------------- the preload's static state

def _point_flexibility(design, i, x):
    """Closed-form static deflection per unit force at x (in/lb): the
    beam equation solved as two cubics (independent_hertz.static_shape),
    over E I."""
    length = float(getattr(design, "L" + i))
    inertia = float(getattr(design, "b" + i)) * float(
        getattr(design, "h" + i))**3 / 12.0
    y = ih.static_shape(str(getattr(design, "end" + i)), length, x)
    return float(y(x)) / (float(getattr(design, "E" + i)) * inertia)


def test_the_static_shapes_are_the_textbook_point_load_deflections():
    for end, xi, g in (("clamped-free", 1.0, 1 / 3),
                       ("clamped-clamped", 0.5, 1 / 192),
                       ("clamped-pinned", 0.5, 7 / 768),
                       ("pinned-pinned", 0.5, 1 / 48),
                       ("clamped-free", 0.5, 1 / 24)):
        assert float(ih.static_shape(end, 2.0, 2.0 * xi)(2.0 * xi)) == \
            pytest.approx(g * 8.0, rel=1e-12)


@pytest.mark.parametrize("name, x2, x3, end2", [
    ("thesis", None, None, "clamped-clamped"),
    ("thesis", 0.7, 0.6 * 19.0, "clamped-clamped"),
    ("thesis", 1.0, 0.8 * 19.0, "pinned-pinned"),
    ("bronze_offset", None, None, "clamped-pinned"),
])
def test_the_preload_state_is_the_closed_form_point_load_deflection(
        name, x2, x3, end2):
    """The preload's strain energy at t = 0, E0(F) - E0(0) - the Hertz
    energy 0.4 k delta^2.5, is F^2 (c2 + c3) / 2 with c the closed-form
    point-load flexibility of the separator at x2 and the lower contact
    at x3.  At N = 64 the modal sums' remainder is below 1e-6 of c
    (sum over j > N of X_j^2 / (k_j L)^4 < 4 / (3 pi^4 (N - 1/2)^3));
    tolerance 1e-5.  Nothing moves before the upper contact arrives."""
    base = FAMILY[name]
    fields = dict(n_modes=64, end2=end2)
    if x2 is not None:
        fields.update(x2=x2, x3=x3)
    design = base.replace(**fields)
    x2v = float(design.L2) / 2 if design.x2 is None else float(design.x2)
    x3v = float(design.L3) if design.x3 is None else float(design.x3)
    c2 = _point_flexibility(design, "2", x2v)
    c3 = _point_flexibility(design, "3", x3v)
    force = 0.02 * float(design.L3) / c3          # 2 % of L3 at x3
    law = HertzLaw.for_materials(float(design.E1), 0.33, 0.125)
    depth = (force / law.k) ** (2.0 / 3.0)
    t_end = 1e-3 if float(design.L1) < 5 else 0.01   # before the impact
    dt = t_end / 2000
    free = run(design, dt=dt, t_end=t_end, samples=20)
    pressed = run(design, dt=dt, t_end=t_end, samples=20, preload=force)
    strain = pressed.energy[0] - free.energy[0] - 0.4 * law.k * depth**2.5
    assert strain == pytest.approx(0.5 * force**2 * (c2 + c3), rel=1e-5)
    np.testing.assert_allclose(pressed.gap_lower, -depth, rtol=1e-9)
    np.testing.assert_allclose(pressed.gap_upper, free.gap_upper, rtol=0,
                               atol=1e-12 * float(design.ys))


# ------------------------------- a free mass on a rigid flat (Flores)

def _law_rebound(k, chi, mass, speed):
    """The rebound speed of m x'' = -k d^1.5 (1 + chi d'), d = -x, from
    SciPy's DOP853 (the law's own ODE, independent of the steppers)."""
    def rhs(_, y):
        d, rate = max(-y[0], 0.0), -y[1]
        f = k * d**1.5 * (1.0 + chi * rate)
        return [y[1], max(f, 0.0) / mass]

    def leave(_, y):
        return y[0]
    leave.terminal, leave.direction = True, 1.0
    sol = solve_ivp(rhs, (0.0, 1.0), [0.0, -speed], method="DOP853",
                    rtol=1e-12, atol=1e-16, events=leave)
    return float(sol.y_events[0][0][1])


@pytest.mark.parametrize("e", [0.3, 0.6, 0.9, 1.0])
def test_a_free_mass_rebounds_from_a_rigid_flat_as_the_law_says(e):
    """One free mode (p -> 0) against a fixed contact: the Hertz law
    with Flores damping chi = 8(1 - e) / (5 e V), built by the package
    (HertzLaw.for_materials), integrated by the adaptive stepper.  The
    rebound speed is the law's own ODE's (DOP853) to 1e-6, and near e:
    Flores et al.'s law gives e_eff = 0.256, 0.563, 0.887 for e = 0.3,
    0.6, 0.9 (measured; the law's known bias at small e), exactly 1 for
    e = 1.  The impulse is m V (1 + e_eff) (momentum).  A Flores constant
    without e in its denominator fails every e < 1."""
    mass, speed = 1e-3, 10.0
    law = HertzLaw.for_materials(1.0e7, 0.33, 0.125, e=e, v_ref=speed)
    assert law.chi == pytest.approx(8 * (1 - e) / (5 * e * speed),
                                    rel=1e-15)
    system = runners.System(
        m=np.array([mass]), p=np.array([1e-6]),
        h=np.array([[1.0], [0.0]]), g0=np.array([1e-4, 1.0]),
        q0=np.array([0.0]), v0=np.array([-speed]), n_upper=1)
    dt, t_end = 1e-8, 3e-3
    steps = int(round(t_end / dt))
    out = runners.hertz_adaptive(system, law, dt, steps, 1000, 1e-6)
    e_eff = math.sqrt(out.energy[-1] / out.energy[0])
    e_law = _law_rebound(law.k, law.chi, mass, speed) / speed
    assert e_eff == pytest.approx(e_law, rel=1e-6)
    # the stepper's impulse is a Riemann sum of the force over its grid
    # (error O(dt / T_c), T_c ~ 4e-4 s the contact's duration; measured
    # 3.6e-5 at e = 0.3, 3.3e-6 at 0.6): bound 10 dt / T_c
    assert out.first[1] == pytest.approx(mass * speed * (1 + e_law),
                                         rel=10 * dt / 4e-4)
    assert e_law == pytest.approx(e, rel=0.2 if e < 0.5 else 0.07)
    if e == 1.0:
        assert e_law == pytest.approx(1.0, rel=1e-9)


# ------------------------------------- energy of every elastic run

#: Steps at which the elastic splitting holds the energy to 1e-6 over
#: the window (measured at N = 8: thesis rigs 1.5e-7 at 5e-8 s; relays
#: 3e-8 to 2.4e-7 at 2e-9 s, where 5e-8 s gives 2e-5 to 1.5e-4).
ELASTIC_DT = {"thesis": 5e-8, "relay": 2e-9}


@pytest.mark.parametrize("name", sorted({**FAMILY, **UNSEEN}))
def test_every_elastic_run_conserves_energy_to_1e_6(name):
    design = {**FAMILY, **UNSEEN}[name].replace(n_modes=8)
    rig = float(design.L1) > 5.0
    result = run(design, dt=ELASTIC_DT["thesis" if rig else "relay"],
                 t_end=0.06 if rig else 0.004, samples=2000)
    assert result.n_events > 0           # the window holds the rattles
    assert np.max(np.abs(result.energy / result.energy[0] - 1.0)) < 1e-6
    assert abs(result.energy_ratio - 1.0) < 1e-6


# ------------------------------------------- the min_open boundary

def test_an_opening_of_exactly_min_open_is_an_event():
    """Dyadic instants (exact in binary): an opening of exactly min_open
    counts ("at least min_open"), one a binary ulp-scale step shorter
    does not."""
    upper = np.array([[0.25, 0.5], [0.625, 0.6875]])
    lower = np.array([[0.0, 1.0]])
    found = circuit.discontinuity(upper, lower, min_open=0.25)
    assert found["n_events"] == 1
    np.testing.assert_array_equal(found["events"], [[0.25, 0.5]])
    found = circuit.discontinuity(upper, lower, min_open=0.0625)
    assert found["n_events"] == 2          # 0.6875 - 0.625 = 2^-4
    shorter = np.array([[0.25, 0.5 - 2.0**-40]])
    assert circuit.discontinuity(shorter, lower, 0.25)["n_events"] == 0
    assert circuit.discontinuity(shorter, lower, 0.0)["n_events"] == 1


def test_simulate_counts_an_opening_of_exactly_min_open():
    """Through simulate: min_open set to the length of a simulated
    opening (its instants as computed) counts it; the next float up
    does not."""
    design = FAMILY["thesis"].replace(n_modes=4)
    first = run(design, dt=5e-8, t_end=0.026, samples=100, min_open=0.0)
    lengths = np.diff(first.circuit_open_intervals, axis=1)[:, 0]
    shortest = float(lengths.min())
    exact = run(design, dt=5e-8, t_end=0.026, samples=100,
                min_open=shortest)
    assert exact.n_events == len(lengths)
    above = run(design, dt=5e-8, t_end=0.026, samples=100,
                min_open=float(np.nextafter(shortest, 1.0)))
    assert above.n_events == len(lengths) - int(np.sum(lengths == shortest))


# --------------------------- every sampled path at other thresholds

def _intervals_from_samples(t, gap, threshold, t_end):
    """Open intervals of a sampled gap, by the test's own linear
    interpolation (not circuit.py's)."""
    spans, start = [], (0.0 if gap[0] > threshold else None)
    for k in range(1, len(t)):
        a, b = gap[k - 1] - threshold, gap[k] - threshold
        if (a > 0) != (b > 0):
            when = t[k - 1] + (t[k] - t[k - 1]) * a / (a - b)
            if b > 0:
                start = when
            else:
                if when > start:
                    spans.append((start, when))
                start = None
    if start is not None and t_end > start:
        spans.append((start, t_end))
    return np.array(spans).reshape(-1, 2)


@pytest.mark.parametrize("backend, dt", [("compiled", 1e-7),
                                         ("numpy", 1e-6)])
def test_every_sampled_path_judges_at_the_thresholds_asked(backend, dt):
    """The fixed-step paths (compiled and NumPy) take their open
    intervals from the samples: at open_threshold = 2e-4 in and
    min_open = 2e-4 s, with a preload, each contact's intervals are the
    test's own interpolation of the returned samples at 2e-4 in, the
    events those of at least 2e-4 s, and the adaptive stepper (which
    finds its crossings on the exact flow) agrees on the events."""
    design = FAMILY["thesis"].replace(n_modes=2)
    # the NumPy twin steps in Python: a coarse step keeps it to seconds
    # (the adaptive stepper runs the same grid where a contact may close)
    threshold, min_open, t_end = 2e-4, 2e-4, 0.025
    steps = int(round(t_end / dt))
    options = dict(dt=dt, t_end=t_end, preload=0.3,
                   open_threshold=threshold, min_open=min_open)
    fixed = run(design, samples=steps, stepper="fixed", backend=backend,
                **options)
    for gap, spans in ((fixed.gap_upper, fixed.upper_open_intervals),
                       (fixed.gap_lower, fixed.lower_open_intervals)):
        mine = _intervals_from_samples(fixed.t, gap, threshold, t_end)
        assert mine.shape == spans.shape
        np.testing.assert_allclose(spans, mine, rtol=0, atol=1e-12)
    circuit_spans = fixed.circuit_open_intervals
    lengths = circuit_spans[:, 1] - circuit_spans[:, 0]
    assert fixed.n_events == int(np.sum(lengths >= min_open))
    adaptive = run(design, samples=250, **options)
    assert adaptive.n_events == fixed.n_events
    np.testing.assert_allclose(adaptive.events, fixed.events, rtol=0,
                               atol=2 * dt)
