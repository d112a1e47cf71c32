"""Repeated impacts: Appendix E against analytic cases and the model's
first impact; Moreau-Jean against Appendix E on the rigid stop; energy
laws; Hertz against a general ODE solver; the compiled steppers against
their NumPy twins; circuit intervals; the command."""

from __future__ import annotations

import json

import numpy as np
import pytest

import contactsep
from contactsep import chatter
from contactsep.chatter import steppers
from contactsep.chatter.contacts import solve_lcp
from contactsep.chatter.laws import HertzLaw
from contactsep.chatter.event_driven import (
    rigid_stop_from_design,
    simulate_rigid_stop,
)
from contactsep.chatter.stack import _stack
from contactsep.chatter.system import members
from contactsep.cli import main

api = pytest.importorskip("contactsep.chatter._chatter").chatter_api


def test_one_mode_against_the_stop_is_analytic():
    """A 1-DOF oscillator released at 0.1 above a stop at its equilibrium:
    impacts at pi/(2p) + (n-1) pi/p, each rebound e times the last."""
    p, x, e = 10.0, 2.0, 0.5
    r = simulate_rigid_stop([p], [x], 1.0, [0.1], [0.0], e, 2.0)
    n = np.arange(len(r.impact_t))
    assert len(n) == 6
    assert np.allclose(r.impact_t, np.pi / (2 * p) + n * np.pi / p,
                       rtol=1e-13, atol=0)
    assert np.allclose(r.v_before, -0.1 * p * x * e**n, rtol=1e-12, atol=0)
    assert np.allclose(r.v_after, -e * r.v_before, rtol=1e-12, atol=0)


def test_appendix_e_first_impact_is_the_models():
    design = contactsep.thesis_design(n_modes=8)
    r = rigid_stop_from_design(design, t_end=0.0225)
    ev = contactsep.evaluate(design, backend="numpy")
    assert abs(r.impact_t[0] / ev.t1 - 1) < 1e-12
    upper = members(design)[0]
    # Appendix E, eq. 9: psi = (1+e) M v- / sum X^2
    expected = 1.375 * upper.mass * ev.v_impact / np.sum(upper.x**2)
    assert abs(r.impulse[0] / expected - 1) < 1e-10


def test_appendix_e_conserves_energy_for_e_one_and_never_gains():
    design = contactsep.thesis_design(n_modes=4, e=1.0)
    r = rigid_stop_from_design(design, t_end=0.06)
    assert len(r.impact_t) > 3
    assert np.allclose(r.energy_after, r.initial_energy, rtol=1e-12, atol=0)
    lossy = rigid_stop_from_design(contactsep.thesis_design(n_modes=4),
                                   t_end=0.06)
    energies = np.concatenate([[lossy.initial_energy], lossy.energy_after])
    assert np.all(np.diff(energies) <= 1e-14 * energies[0])


def test_appendix_e_never_penetrates_and_rests_with_a_compressive_force():
    design = contactsep.thesis_design(n_modes=4)
    r = rigid_stop_from_design(design, t_end=0.06)
    t = np.linspace(0, 0.06, 200_001)
    y = r.displacement(t)
    assert y.min() > -1e-12
    assert len(r.rest_intervals) >= 1
    start, end = r.rest_intervals[0]
    inside = (t > start) & (t < end)
    assert np.all(np.abs(y[inside]) < 1e-12)


@pytest.mark.parametrize("n, dt", [
    (1, 1e-7), (2, 1e-7), (4, 1e-7),
    (8, 1e-7),
    (16, 5e-8)])
def test_moreau_jean_matches_appendix_e_on_the_rigid_stop(n, dt):
    """Moreau-Jean activates the contact in the step whose predicted gap
    g + (dt/2) u closes, i.e. the exact impact t* lies within dt/2 of
    that step's start t_n, and reports the step's end t_n + dt: so
    t_MJ - t* lies in [dt/2, 3 dt/2) (measured 0.92-1.40 dt); a shift
    of one step leaves that band.  Impulse to 1e-5 (measured <= 1.0e-5),
    energy at 0.03 s to 1e-3."""
    design = contactsep.thesis_design(n_modes=n)
    upper = members(design)[0]
    t_end = 0.03
    exact = rigid_stop_from_design(design, t_end=t_end)
    steps = int(round(t_end / dt))
    _, _, energy, _, first, *_, status = api.run_moreau_jean(
        np.full(n, upper.mass), upper.p, upper.x[None, :], np.zeros(1),
        upper.q0, upper.v0, 0.375, dt, 0.5, steps, 1000, steps // 1000 + 1,
        1e-6, 1000)
    assert status == 0
    assert 0.5 <= (first[0] - exact.impact_t[0]) / dt < 1.5
    assert abs(first[1] / exact.impulse[0] - 1) < 1e-5
    assert abs(energy[-1] / exact.final_energy - 1) < 1e-3


@pytest.mark.filterwarnings("ignore:dt:UserWarning")
@pytest.mark.parametrize("stepper", ["fixed", "adaptive"])
def test_newton_three_beams_conserve_energy_for_e_one(stepper):
    r = chatter.simulate(contactsep.thesis_design(n_modes=4, e=1.0),
                         model="newton", dt=1e-6, stepper=stepper,
                         t_end=0.06)
    # the trapezoidal flight (Moreau-Jean) and the exact flow (adaptive)
    # conserve the quadratic energy exactly, and the velocity-level law
    # with e = 1 returns it at each impact
    assert np.max(np.abs(r.energy / r.energy[0] - 1)) < 1e-9
    lossy = chatter.simulate(contactsep.thesis_design(n_modes=4),
                             model="newton", dt=1e-6, stepper=stepper,
                             t_end=0.06)
    assert np.all(np.diff(lossy.energy) <= 1e-12 * lossy.energy[0])
    # interpenetration of the velocity-level law: below dt x impact speed
    assert lossy.gap_upper.min() > -1e-6 * 35.0


def test_elastic_hertz_conserves_energy_and_flores_dissipates():
    design = contactsep.thesis_design(n_modes=4)
    elastic = chatter.simulate(design, model="hertz", dt=2e-8, t_end=0.06)
    assert np.max(np.abs(elastic.energy / elastic.energy[0] - 1)) < 1e-6
    damped = chatter.simulate(design, model="hertz", damping="flores",
                              dt=5e-8, t_end=0.06)
    assert np.all(np.diff(damped.energy) <= 1e-12 * damped.energy[0])
    assert damped.energy_ratio < 0.9


def test_hertz_splitting_against_a_general_ode_solver():
    """N = 2 per member, from just before the first impact through it."""
    integrate = pytest.importorskip("scipy.integrate")
    design = contactsep.thesis_design(n_modes=2)
    m, p, h, q0, v0, _ = _stack(design)
    law = HertzLaw.for_materials(10.0e6)
    t1 = float(contactsep.evaluate(design, backend="numpy").t1)
    # the exact free flight up to t1 - 20 us, then both integrators
    t0 = t1 - 2e-5
    q = q0 * np.cos(p * t0) + v0 / p * np.sin(p * t0)
    v = -q0 * p * np.sin(p * t0) + v0 * np.cos(p * t0)
    span = 6e-4

    def rhs(_, state):
        qq, vv = state[:p.size], state[p.size:]
        force = law.force(h @ qq, h @ vv)
        return np.concatenate([vv, -p**2 * qq + h.T @ force / m])

    ode = integrate.solve_ivp(rhs, (0, span), np.concatenate([q, v]),
                              method="DOP853", rtol=1e-11, atol=1e-16,
                              dense_output=True)
    dt = 1e-8
    steps = int(round(span / dt))
    t, g, _, _, first, _ = api.run_hertz(m, p, h, np.zeros(2),
                                         np.zeros((2, 2)), q, v, law.k,
                                         law.chi, dt, steps, 100,
                                         steps // 100 + 1)
    reference = h @ ode.sol(t)[:p.size]
    scale = np.abs(reference).max()
    assert np.max(np.abs(g - reference)) < 1e-5 * scale
    assert first[1] > 0


def test_compiled_steppers_equal_their_twins():
    design = contactsep.thesis_design(n_modes=3)
    m, p, h, q0, v0, _ = _stack(design)
    dt, steps, stride = 1e-6, 23_000, 100
    samples = steps // stride + 1
    a = steppers.moreau_jean(m, p, h, np.zeros(2), q0, v0, e=0.375, dt=dt,
                             steps=steps, stride=stride)
    b = api.run_moreau_jean(m, p, h, np.zeros(2), q0, v0, 0.375, dt, 0.5,
                            steps, stride, samples, 1e-6, 1000)
    # the same operations in another order: rounding only (until an
    # active-set decision flips, which the window ends before)
    assert np.allclose(a[1], b[1].T, rtol=0, atol=1e-12)
    assert np.allclose(a[4], b[4], rtol=1e-10, atol=0)
    law = HertzLaw.for_materials(10.0e6)
    c = steppers.hertz(m, p, h, np.zeros(2), q0, v0, law=law, dt=dt,
                       steps=steps, stride=stride)
    d = api.run_hertz(m, p, h, np.zeros(2), np.zeros((2, 2)), q0, v0,
                      law.k, law.chi, dt, steps, stride, samples)
    assert np.allclose(c[1], d[1].T, rtol=0, atol=1e-12)
    assert np.allclose(c[2], d[2], rtol=1e-12, atol=0)


def test_lcp_solution_is_complementary():
    matrix = np.array([[2.0, 0.5], [0.5, 1.0]])
    for vector in ([-1.0, -1.0], [-1.0, 2.0], [1.0, 1.0], [3.0, -0.2]):
        z = solve_lcp(matrix, np.array(vector))
        w = matrix @ z + vector
        assert np.all(z >= 0) and np.all(w >= -1e-14)
        assert abs(z @ w) < 1e-14


def _inertia_modulus(design, i):
    """E I (lb in^2) of member i from the design's own fields."""
    b, h = float(getattr(design, "b" + i)), float(getattr(design, "h" + i))
    return float(getattr(design, "E" + i)) * b * h**3 / 12.0


def test_modal_flexibilities_converge_to_the_beam_formulas():
    """The preload's static state uses the N-mode models' flexibility
    sum X_j^2 / (M p_j^2); it tends to the exact point-load deflections,
    L^3/(192 EI) at a clamped-clamped mid-span and L^3/(3 EI) at a
    cantilever tip, from below (each mode adds a positive term)."""
    from contactsep.chatter.system import flexibility
    design = contactsep.thesis_design(n_modes=32)
    _, sep, low = members(design)
    exact_sep = float(design.L2)**3 / (192 * _inertia_modulus(design, "2"))
    exact_low = float(design.L3)**3 / (3 * _inertia_modulus(design, "3"))
    assert 0.999 < flexibility(sep) / exact_sep <= 1.0
    assert 0.999 < flexibility(low) / exact_low <= 1.0


@pytest.mark.parametrize("model", ["newton", "hertz"])
def test_a_preload_is_a_static_equilibrium(model):
    """Before the upper contact arrives nothing moves: the lower gap stays
    at its start value (closed: 0 for Newton, minus the Hertz penetration
    (F/k)^(2/3) for Hertz), the contact carrying the preload."""
    design = contactsep.thesis_design(n_modes=8)
    force = 0.05
    r = chatter.simulate(design, model=model, preload=force, t_end=0.02,
                         dt=5e-8)
    assert r.preload_lb == force
    if model == "hertz":
        law = HertzLaw.for_materials(float(design.E1))
        depth = (force / law.k) ** (2 / 3)
        assert r.gap_lower[0] == pytest.approx(-depth, rel=1e-9)
        # the adaptive stepper holds the static start still
        assert np.ptp(r.gap_lower) == 0.0
        # the fixed-step splitting's fixed point lies O(dt^2) from the
        # static state: the gap rocks by that much, a quarter when dt
        # halves
        fixed = [chatter.simulate(design, model=model, preload=force,
                                  t_end=0.02, dt=dt, stepper="fixed")
                 for dt in (r.dt, 2 * r.dt)]
        wobble = np.ptp(fixed[0].gap_lower)
        assert 3.5 < np.ptp(fixed[1].gap_lower) / wobble < 4.5
        assert wobble < 1e-6 * depth
    else:
        assert -1e-15 < r.gap_lower[0] <= 0.0
        assert np.ptp(r.gap_lower) < 1e-15
    # the release height is measured from the preloaded separator
    plain = chatter.simulate(design, model=model, t_end=0.02, dt=5e-8)
    assert r.gap_upper[0] == pytest.approx(plain.gap_upper[0], rel=1e-12)
    np.testing.assert_allclose(r.gap_upper, plain.gap_upper, rtol=0,
                               atol=1e-12)


def test_preload_holds_the_lower_contact_down():
    """More preload, less lower-contact separation (newton, N = 8)."""
    design = contactsep.thesis_design(n_modes=8)
    gaps = [chatter.simulate(design, model="newton", preload=f,
                             t_end=0.03).max_lower_gap_in
            for f in (0.0, 0.1, 1.0)]
    assert gaps[0] > gaps[1] > gaps[2] > 0


@pytest.mark.parametrize("model, preload", [
    ("newton", -0.1), ("newton", float("nan")), ("appE", 0.1)])
def test_a_bad_preload_is_refused(model, preload):
    with pytest.raises(chatter.ChatterError, match="preload"):
        chatter.simulate(contactsep.thesis_design(n_modes=2), model=model,
                         preload=preload, t_end=0.01)


def test_appE_json_lists_every_impact_and_rest(capsys):
    """--json of appE carries the event table: the first impact is the
    summary's, impulses positive, each rebound reversing the approach by
    e (the Newton law at the contact point, 1e-12), energy never rising,
    rests inside the window."""
    assert main(["chatter", "--model", "appE", "--n-modes", "4",
                 "--t-end", "0.06", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    impacts = out["impacts"]
    assert impacts[0]["t_s"] == out["first_impact_s"]
    assert impacts[0]["impulse_lb_s"] == out["first_impulse_lb_s"]
    for event in impacts:
        assert event["impulse_lb_s"] > 0 and event["v_before_in_s"] < 0
        assert event["v_after_in_s"] == pytest.approx(
            -0.375 * event["v_before_in_s"], rel=1e-12)
    energies = [e["energy_after_in_lb"] for e in impacts]
    assert all(b <= a * (1 + 1e-14) for a, b in zip(energies, energies[1:]))
    rests = np.array(out["rest_intervals"])
    assert rests.shape[1] == 2 and np.all(np.diff(rests, axis=1) > 0)
    assert rests.min() > 0 and rests.max() <= 0.060


@pytest.mark.parametrize("options, match", [
    (dict(dt=1e-30), "at most 1e\\+09 steps"),
    (dict(samples=0), "samples"), (dict(theta=0.2), "theta"),
    (dict(nu=0.7), "nu"), (dict(button_radius=-1.0), "radius"),
    (dict(n_modes=5000), "at most 1024 modes"),
    (dict(ys=-0.01), "release height > 0")])
def test_settings_that_cannot_run_are_refused_at_once(options, match):
    """Each refused before any work (a dt of 1e-30 s would be 6e28 steps,
    5000 modes a 15,000-mode system, a negative ys an interpenetrated
    start): a ChatterError, exit 2 in the command."""
    design_options = {k: options.pop(k) for k in ("n_modes", "ys")
                      if k in options}
    design = contactsep.thesis_design(**{"n_modes": 2, **design_options})
    with pytest.raises(chatter.ChatterError, match=match):
        chatter.simulate(design, model="hertz", **options)


@pytest.mark.parametrize("n, order", [(1, 0.8), (4, 0.4)])
def test_stiff_hertz_tends_to_appendix_e_at_the_predicted_rate(n, order):
    """The upper contact on a rigid stop through an elastic Hertz contact
    (the compiled splitting with one contact row): as k grows the contact
    lasts tau_c ~ k^(-2/5), and the contact episode's impulse tends to
    Appendix E's elastic Newton impulse (e = 1).  One mode: the error is
    O((p tau_c)^2) ~ k^(-4/5) (symmetric contact); several modes exchange
    energy during the contact, O(p_j tau_c) ~ k^(-2/5).  Measured: each
    100x in k divides the error by 100^order within 10 %."""
    design = contactsep.thesis_design(n_modes=n, e=1.0)
    upper = members(design)[0]
    newton = rigid_stop_from_design(design, t_end=0.0235)
    law = HertzLaw.for_materials(float(design.E1))
    errors = []
    for scale in (1.0, 100.0):
        dt = 2e-8
        steps = int(0.0235 / dt)
        stride = steps // 100
        *_, first, _ = api.run_hertz(
            np.full(n, upper.mass), upper.p, upper.x.reshape(1, n),
            np.zeros(1), np.zeros((1, 1)), upper.q0, upper.v0,
            law.k * scale, 0.0, dt, steps, stride, steps // stride + 1)
        assert abs(first[0] - newton.impact_t[0]) < 2 * dt
        errors.append(abs(first[1] / newton.impulse[0] - 1))
    assert errors[0] < 1e-2
    assert errors[0] / errors[1] == pytest.approx(100**order, rel=0.1)
