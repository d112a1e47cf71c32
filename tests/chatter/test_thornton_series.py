"""Thornton's plastic law with the static correction: each element
carries Thornton's force of its own penetration delta, in series with
the residual flexibility C (delta + C_ii F(delta) = a), and remembers
delta, not the modal overlap.

Independent path: one free mass m at speed V against a rigid flat through
a Thornton element in series with a massless linear spring of compliance
c, integrated here by scipy's solve_ivp (DOP853, rtol 1e-13) from
Thornton's formulas written out below (not the package's), the element's
depth from x = delta + c F(delta) by brentq: loading on the envelope
until the mass stops (delta_m), then unloading on the curve from delta_m
until the force vanishes (delta = delta_p).  The package runs the same
system as one mode of negligible stiffness (p = 1e-3 rad/s) with a 1 x 1
series flexibility, as the closed-form Thornton tests do with c = 0."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from design_family import FAMILY
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from contactsep.chatter import runners, steppers
from contactsep.chatter.laws import HertzLaw
from contactsep.chatter.stack import largest_preload
from contactsep.chatter.stack import _system
from contactsep.cli import main

E, NU, RADIUS, YIELD = 30.0e6, 0.33, 0.125, 45.0e3
#: The free mass (lb s^2/in), its approach speed (in/s) and release
#: height above the flat (in).
MASS, SPEED, HEIGHT = 2.0e-5, 33.9, 1e-7


def api():
    from contactsep.chatter import _chatter
    return _chatter.chatter_api


def independent_impact(c: float) -> dict:
    """Restitution, peak force (lb) and contact time (s) of the free mass
    through Thornton's element in series with compliance c (in/lb)."""
    e_star = E / (2.0 * (1.0 - NU**2))
    k = 4.0 / 3.0 * e_star * math.sqrt(RADIUS)
    d_y = (math.pi * YIELD / (2.0 * e_star))**2 * RADIUS
    f_y = k * d_y**1.5

    def envelope(d):
        return k * d**1.5 if d <= d_y else f_y + math.pi * YIELD * RADIUS \
            * (d - d_y)

    def depth(x, force, low):
        # the element's delta of the approach x: delta + c F(delta) = x
        if x <= low:
            return x
        return brentq(lambda d: d + c * force(d) - x, low, x, xtol=1e-22,
                      rtol=1e-15, maxiter=500)

    def loading(t, y):
        return [y[1], -envelope(depth(y[0], envelope, 0.0)) / MASS]

    def stops(t, y):
        return y[1]
    stops.terminal, stops.direction = True, -1
    one = solve_ivp(loading, (0.0, 1.0), [0.0, SPEED], method="DOP853",
                    rtol=1e-13, atol=1e-20, events=stops)
    x_m, t_1 = one.y_events[0][0][0], one.t_events[0][0]
    d_m = depth(x_m, envelope, 0.0)
    f_m = envelope(d_m)
    a2 = RADIUS * d_m
    r_p = 4.0 * e_star * a2**1.5 / (3.0 * f_m)
    d_p = d_m - a2 / r_p
    k_p = 4.0 / 3.0 * e_star * math.sqrt(r_p)

    def unload(d):
        return k_p * (d - d_p)**1.5 if d > d_p else 0.0

    def unloading(t, y):
        return [y[1], -unload(depth(y[0], unload, d_p)) / MASS]

    def leaves(t, y):
        return y[0] - d_p
    leaves.terminal, leaves.direction = True, -1
    two = solve_ivp(unloading, (0.0, 1.0), [x_m, 0.0], method="DOP853",
                    rtol=1e-13, atol=1e-20, events=leaves)
    t_2, rebound = two.t_events[0][0], -two.y_events[0][0][1]
    # the energy route to e: what the unloading curve and the spring
    # give back of the kinetic energy
    back = 0.4 * f_m * (d_m - d_p) + 0.5 * c * f_m**2
    assert rebound / SPEED == pytest.approx(math.sqrt(
        back / (0.5 * MASS * SPEED**2)), rel=1e-9)
    return {"e": rebound / SPEED, "peak": f_m, "contact": t_1 + t_2}


def package_impact(how: str, c: float, dt: float, t_end: float):
    """The package's run of the same system: (e, peak force, contact
    time, first impulse, energy book closure, the raw outputs); peak
    and contact time from the steps' impulses (fixed and numpy), None
    for the adaptive stepper (it keeps none)."""
    law = HertzLaw.for_materials(E, NU, RADIUS, yield_pressure=YIELD)
    m, p = np.array([MASS]), np.array([1e-3])
    h, g0, cmat = np.ones((1, 1)), np.zeros(1), np.array([[c]])
    q0, v0 = np.array([HEIGHT]), np.array([-SPEED])
    steps = int(round(t_end / dt))
    args = (law.k, law.chi, law.yield_pressure, law.e_star, law.radius, 0)
    impulses = None
    if how == "fixed":
        out = api().run_hertz_book(m, p, h, g0, cmat, q0, v0, *args, dt,
                                   steps, 1, steps + 1, 1e300)
        t, g, e, impulses, first, q, v, book, status = out
        impulses = impulses[0]
    elif how == "adaptive":
        out = api().run_hertz_adaptive_book(
            m, p, h, g0, cmat, q0, v0, *args, dt, steps, steps, 2, 1e-6,
            1, 1e300, 4096)
        t, g, e, first, _, _, _, _, q, v, book, status = out
    else:
        out = steppers.hertz(m, p, h, g0, q0, v0, law=law, dt=dt,
                             steps=steps, stride=1, c_matrix=cmat,
                             book=True)
        t, g, e, impulses, first, end = out
        v, book, status = end["v"], (end["dissipated"], end["stored"]), 0
        impulses = impulses[:, 0]
    assert status == 0
    peak = contact = None
    if impulses is not None:
        peak = impulses.max() / dt
        contact = np.count_nonzero(impulses) * dt
        # the contact ended inside the window
        assert impulses[-1] == 0.0
    closure = (e[-1] + book[0]) / e[0] - 1.0
    return float(v[0]) / SPEED, peak, contact, float(first[1]), closure, out


# the twin is slow: one compliance
@pytest.mark.parametrize("c, how", [
    (5e-6, "fixed"), (5e-6, "adaptive"), (2e-5, "fixed"),
    (2e-5, "adaptive"), (2e-5, "numpy")])
def test_a_free_mass_through_the_series_element_is_the_integration(c, how):
    exact = independent_impact(c)
    dt = 4e-9 if how == "numpy" else 1e-9
    e, peak, contact, impulse, closure, _ = package_impact(
        how, c, dt, 1.1 * exact["contact"])
    assert e == pytest.approx(exact["e"], abs=1e-8 if how != "numpy"
                              else 1e-7)
    # the impulse returns the momentum m V (1 + e)
    assert impulse == pytest.approx(MASS * SPEED * (1.0 + exact["e"]),
                                    rel=1e-7)
    assert abs(closure) < 1e-9
    if peak is not None:
        assert peak == pytest.approx(exact["peak"], rel=1e-7)
        assert abs(contact - exact["contact"]) <= 2.0 * dt


def test_the_series_spring_changes_the_impact():
    # the check above is no tautology: the spring's compliance moves
    # every figure far beyond its tolerances
    plain, soft = independent_impact(0.0), independent_impact(2e-5)
    assert soft["e"] > plain["e"] + 0.1
    assert soft["contact"] > 1.2 * plain["contact"]
    e, *_ = package_impact("fixed", 0.0, 1e-9, 1.1 * plain["contact"])
    assert e == pytest.approx(plain["e"], abs=1e-8)


def _same(a, b):
    """Every output of two raw stepper answers, bit for bit."""
    for x, y in zip(a, b):
        if isinstance(x, dict):
            assert x.keys() == y.keys()
            for key in x:
                assert np.array_equal(x[key], y[key]), key
        else:
            assert np.array_equal(np.asarray(x), np.asarray(y),
                                  equal_nan=True)


@pytest.mark.parametrize("how", ["fixed", "numpy"])
def test_a_vanishing_compliance_is_the_plain_law_bit_for_bit(how):
    # c far below every force's last bit: the series solve's root is the
    # overlap itself, and the run is today's Thornton without the
    # correction (c = 0 takes the plain path), every bit
    dt, t_end = (1e-9, 7.5e-5) if how == "fixed" else (4e-9, 7.5e-5)
    *_, plain = package_impact(how, 0.0, dt, t_end)
    *_, tiny = package_impact(how, 1e-300, dt, t_end)
    _same(plain, tiny)


@pytest.mark.parametrize("preload", [0.0, 0.5])
def test_a_vanishing_compliance_on_a_design_is_the_plain_law(preload):
    design = FAMILY["steel_thick"].replace(n_modes=8)
    law = HertzLaw.for_materials(float(design.E1), yield_pressure=YIELD)
    preload *= largest_preload(design)
    plain = _system(design, preload, law, False)
    corrected = _system(design, preload, law, True)
    tiny = dataclasses.replace(plain, c=1e-300 * corrected.c
                               / np.abs(corrected.c).max())
    a, b = (runners.hertz_fixed(s, law, 5e-9, 100000, 1000, 1e-6)
            for s in (plain, tiny))
    assert not math.isnan(a.first[1])
    for field in ("t", "gaps", "energy", "upper_open", "lower_open"):
        assert np.array_equal(getattr(a, field), getattr(b, field)), field
    assert a.first == b.first
    for key in a.book:
        assert np.array_equal(a.book[key], b.book[key]), key


def _design_system(name, preload, law):
    design = FAMILY[name].replace(n_modes=8)
    return design, _system(design, preload * largest_preload(design), law,
                           True)


@pytest.mark.parametrize("alpha", [None, 0.0676])
@pytest.mark.parametrize("stepper", ["fixed", "adaptive"])
@pytest.mark.parametrize("preload", [0.0, 0.5])
def test_the_energy_book_closes_on_a_design(preload, stepper, alpha):
    # elastic (unloading curves and series springs) + plastic work (+
    # Hunt-Crossley's work) + modal energy stay the release energy; a
    # preload past yield has done its plastic work before the start (the
    # book counts it)
    design = FAMILY["steel_thick"].replace(n_modes=8)
    law = HertzLaw.for_materials(float(design.E1), yield_pressure=YIELD,
                                 alpha=alpha)
    _, system = _design_system("steel_thick", preload, law)
    run = getattr(runners, f"hertz_{stepper}")
    # the damping's kicks keep the book to O(dt^2) (as Hertz's do): at
    # half the design's step
    dt = 5e-9 if alpha is None else 2.5e-9
    before = runners.hertz_fixed(system, law, dt, 1, 1, 1e-6)
    r = run(system, law, dt, int(round(5e-4 / dt)), 1000, 1e-6)
    assert r.status == 0 and not math.isnan(r.first[1])
    e0 = r.energy[0]
    plastic = r.book["dissipated"] - before.book["dissipated"]
    # (a book that lost the plastic work would miss by 100 times the
    # tolerance)
    assert plastic > 1e-4 * e0
    assert abs(r.book["end"] + plastic - e0) < 1e-6 * e0


@pytest.mark.parametrize("name, alpha", [
    ("steel_thick", None), ("bronze_offset", None),
    ("steel_thick", 0.0676)])
@pytest.mark.parametrize("preload", [0.0, 0.5])
def test_compiled_equals_its_numpy_twin_on_a_design(name, alpha, preload):
    # from a state just before the first impact (the compiled fixed run
    # to there), both steppers through the impact
    law = HertzLaw.for_materials(float(FAMILY[name].E1),
                                 yield_pressure=YIELD, alpha=alpha)
    _, system = _design_system(name, preload, law)
    dt = 5e-9
    probe = runners.hertz_adaptive(system, law, dt, 400000, 400000, 1e-6)
    lead = int(probe.first[0] / dt) - 200
    start = runners.hertz_fixed(system, law, dt, lead, lead, 1e-6)
    near = dataclasses.replace(system, q0=start.book["q"],
                               v0=start.book["v"])
    a = runners.hertz_fixed(near, law, dt, 6000, 100, 1e-6)
    b = runners.hertz_fixed(near, law, dt, 6000, 100, 1e-6,
                            backend="numpy")
    assert a.first[1] > 0.0
    assert np.allclose(a.gaps, b.gaps, rtol=0.0, atol=1e-12)
    assert a.first[1] == pytest.approx(b.first[1], rel=1e-10)
    assert a.book["dissipated"] == pytest.approx(b.book["dissipated"],
                                                 rel=1e-10)
    assert a.book["end"] == pytest.approx(b.book["end"], rel=1e-12)


@pytest.mark.parametrize("stepper", ["fixed", "adaptive"])
@pytest.mark.parametrize("preload", [0.0, 0.5])
def test_far_above_yield_it_is_the_elastic_law_with_the_correction(
        preload, stepper):
    # p_y beyond every contact pressure: Thornton's law is Hertz's, and
    # its series solve (a bracketed Newton on F) is the elastic law's
    # (Newton on k delta^{3/2}) to round-off
    name = "steel_thick"
    modulus = float(FAMILY[name].E1)
    hard = HertzLaw.for_materials(modulus, yield_pressure=1e12)
    elastic = HertzLaw.for_materials(modulus)
    _, s_hard = _design_system(name, preload, hard)
    _, s_elastic = _design_system(name, preload, elastic)
    run = getattr(runners, f"hertz_{stepper}")
    a = run(s_hard, hard, 5e-9, 100000, 1000, 1e-6)
    b = run(s_elastic, elastic, 5e-9, 100000, 1000, 1e-6)
    assert b.first[1] > 0.0
    assert np.allclose(a.gaps, b.gaps, rtol=0.0,
                       atol=1e-13 * np.abs(b.gaps).max())
    assert np.allclose(a.energy, b.energy, rtol=1e-13, atol=0.0)
    assert a.first[1] == pytest.approx(b.first[1], rel=1e-12)
    assert a.book["dissipated"] < 1e-15 * b.energy[0]


def test_the_command_runs_thornton_at_the_defaults(capsys):
    assert main(["chatter", "--contact", "thornton", "--yield-pressure",
                 "1e5", "--n-modes", "8", "--t-end", "0.003"]) == 0
    settings = capsys.readouterr().out.splitlines()[1]
    assert "contact thornton" in settings
    assert settings.endswith(", static correction")
