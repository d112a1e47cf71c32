"""The Hertz family's laws (issue 28, items 1 and 8): Hunt-Crossley and
Thornton against closed forms on a free mass, the energy book on the
family of designs, the laws' options refused where they cannot run.

Independent paths: Hunt-Crossley's ODE m delta'' = -k delta^{3/2}
(1 + alpha delta') is separable, and over a whole impact gives
alpha (1 + e) V = ln((1 + alpha V) / (1 - alpha e V)) (solved here by
brentq); Thornton (1997, J. Appl. Mech. 64:383, eq. 48) gives e of an
elastic-perfectly-plastic sphere on a half-space in closed form, with
V_y = 1.56 sqrt(p_y^5 / (E*^4 rho)) (his eq. 43) for a sphere of density
rho.  The simulations run the compiled steppers (fixed and adaptive)
and the NumPy twin on one mode of a free mass (p -> 0) against a rigid
flat."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from design_family import FAMILY
from scipy.optimize import brentq

from contactsep.chatter import simulate, steppers
from contactsep.chatter.laws import ContactMemory, HertzLaw
from contactsep.chatter.simulate import ChatterError

E, NU, RADIUS = 30.0e6, 0.33, 0.125
#: A free mass (lb s^2/in) and its approach speed (in/s).
MASS, SPEED = 2.0e-5, 33.9


def api():
    from contactsep.chatter import _chatter
    return _chatter.chatter_api


def free_mass_rebound(law: HertzLaw, how: str, speed=SPEED, mass=MASS,
                      dt=1e-9, t_end=2e-4):
    """Rebound speed / approach speed of a free mass released 1e-7 in
    above a rigid flat at ``speed``, and its energy book closure."""
    m, p = np.array([mass]), np.array([1e-3])
    h, g0, c = np.ones((1, 1)), np.zeros(1), np.zeros((1, 1))
    q0, v0 = np.array([1e-7]), np.array([-speed])
    steps = int(round(t_end / dt))
    args = (law.k, law.chi, law.yield_pressure, law.e_star, law.radius,
            int(law.linear))
    if how == "fixed":
        t, g, e, _, _, q, v, book, status = api().run_hertz_book(
            m, p, h, g0, c, q0, v0, *args, dt, steps, steps, 2, 1e300)
    elif how == "adaptive":
        (t, g, e, _, _, _, _, _, q, v, book,
         status) = api().run_hertz_adaptive_book(
            m, p, h, g0, c, q0, v0, *args, dt, steps, steps, 2, 1e-6, 1,
            1e300, 4096)
    else:
        t, g, e, _, _, out = steppers.hertz(
            m, p, h, g0, q0, v0, law=law, dt=dt, steps=steps,
            stride=steps, book=True)
        v, book, status = out["v"], (out["dissipated"], out["stored"]), 0
    assert status == 0
    assert g[..., -1].item() > 0.0 if how != "numpy" else g[-1, 0] > 0.0
    closure = (e[-1] + book[0]) / e[0] - 1.0
    return float(v[0]) / speed, closure


def hunt_crossley_e(alpha: float, speed: float) -> float:
    """e of Hunt and Crossley's law on a rigid stop: the root of
    alpha (1 + e) V = ln((1 + alpha V) / (1 - alpha e V))."""
    top = min(1.0, 1.0 / (alpha * speed)) * (1.0 - 1e-15)
    return brentq(lambda e: alpha * (1.0 + e) * speed - math.log(
        (1.0 + alpha * speed) / (1.0 - alpha * e * speed)), 1e-12, top,
        xtol=1e-15, rtol=1e-15)


@pytest.mark.parametrize("how", ["fixed", "adaptive"])
@pytest.mark.parametrize("alpha", [0.005, 0.0676, 0.2])
def test_hunt_crossley_on_a_rigid_stop_is_its_closed_form(alpha, how):
    law = HertzLaw.for_materials(E, NU, RADIUS, alpha=alpha)
    e, closure = free_mass_rebound(law, how)
    assert e == pytest.approx(hunt_crossley_e(alpha, SPEED), abs=1e-8)
    # the damping's work, summed by the stepper, closes the book
    assert abs(closure) < 1e-8


def test_the_issue_s_constant_gives_its_rigid_stop_restitution():
    # issue 28: one constant with e = 0.375 at 33.9 in/s gives 0.56 at
    # 16.9 and 0.28 at 50.8 in/s on a rigid stop
    alpha = brentq(lambda a: hunt_crossley_e(a, 33.9) - 0.375, 1e-3, 0.08)
    assert alpha == pytest.approx(0.0676, abs=5e-5)
    assert hunt_crossley_e(alpha, 16.9) == pytest.approx(0.56, abs=0.005)
    assert hunt_crossley_e(alpha, 50.8) == pytest.approx(0.28, abs=0.005)


def test_the_numpy_twin_rebounds_as_the_closed_form():
    law = HertzLaw.for_materials(E, NU, RADIUS, alpha=0.0676)
    e, closure = free_mass_rebound(law, "numpy", dt=4e-9)
    assert e == pytest.approx(hunt_crossley_e(0.0676, SPEED), abs=1e-7)
    assert abs(closure) < 1e-7


def thornton_e(law: HertzLaw, mass: float, speed: float) -> float:
    """Thornton's (1997) eq. 48 with V_y the speed whose kinetic energy
    the contact stores at yield, (2/5) F_y delta_y."""
    depth = law.yield_depth
    yield_speed = math.sqrt(2.0 * 0.4 * law.k * depth**2.5 / mass)
    if speed <= yield_speed:
        return 1.0
    r = yield_speed / speed
    return math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * math.sqrt(
        1.0 - r**2 / 6.0) * (r / (r + 2.0 * math.sqrt(
            6.0 / 5.0 - r**2 / 5.0))) ** 0.25


#: (speed in/s, stepper): the compiled steppers at four speeds, the NumPy
#: twin (slow) at the middle two.
THORNTON_CASES = [(speed, how) for speed in (0.04, 0.5, 33.9, 200.0)
                  for how in ("fixed", "adaptive", "numpy")
                  if how != "numpy" or speed in (0.5, 33.9)]


@pytest.mark.parametrize("speed, how", THORNTON_CASES)
def test_thornton_on_a_rigid_stop_is_his_formula(speed, how):
    law = HertzLaw.for_materials(E, NU, RADIUS, yield_pressure=45.0e3)
    # the contact lasts ~4e-5 s at 33.9 in/s, longer when slow
    t_end = 4e-4 if speed > 1.0 else 2e-3
    dt = 1e-9 if how != "numpy" else (2e-8 if speed < 1.0 else 4e-9)
    e, closure = free_mass_rebound(law, how, speed=speed, dt=dt,
                                   t_end=t_end)
    assert e == pytest.approx(thornton_e(law, MASS, speed), abs=2e-7)
    assert abs(closure) < 1e-7


def test_thornton_s_yield_velocity_constant():
    # his eq. 43 for a sphere of density rho: V_y = 1.56 (p_y^5 / (E*^4
    # rho))^{1/2}; here from the law's yield depth and force
    rho = 0.283 / 386.09     # steel, lb s^2 / in^4
    law = HertzLaw.for_materials(E, NU, RADIUS, yield_pressure=45.0e3)
    mass = 4.0 / 3.0 * math.pi * RADIUS**3 * rho
    depth = law.yield_depth
    yield_speed = math.sqrt(2.0 * 0.4 * law.k * depth**2.5 / mass)
    published = 1.56 * math.sqrt(45.0e3**5 / (law.e_star**4 * rho))
    assert yield_speed == pytest.approx(published, rel=0.005)


def test_thornton_below_yield_is_hertz():
    # a slow impact never yields: e = 1, no plastic work
    law = HertzLaw.for_materials(E, NU, RADIUS, yield_pressure=45.0e3)
    e, closure = free_mass_rebound(law, "fixed", speed=0.01, dt=2e-8,
                                   t_end=4e-3)
    assert e == pytest.approx(1.0, abs=1e-9)
    assert abs(closure) < 1e-9


def test_thornton_memory_unloads_on_the_enlarged_radius():
    # continuity at the largest penetration, zero force at the offset,
    # and the stored energy is the unloading curve's integral
    law = HertzLaw.for_materials(E, NU, RADIUS, yield_pressure=45.0e3)
    memory = ContactMemory(law, 1)
    depth = 40.0 * law.yield_depth
    memory.remember(0, depth)
    force = law.envelope(depth)
    assert memory.elastic_force(0, depth) == pytest.approx(force,
                                                           rel=1e-12)
    offset = memory.offset[0]
    assert 0.0 < offset < depth
    assert memory.elastic_force(0, offset * (1 - 1e-12)) == 0.0
    from scipy.integrate import quad
    stored, _ = quad(lambda x: memory.elastic_force(0, x), offset, depth,
                     epsabs=0, epsrel=1e-12)
    assert memory.energy(0, depth) == pytest.approx(stored, rel=1e-9)
    loading, _ = quad(law.envelope, 0.0, depth, points=[law.yield_depth],
                      epsabs=0, epsrel=1e-12)
    assert memory.plastic_work() == pytest.approx(loading - stored,
                                                  rel=1e-9)


LAWS = {"elastic": {},
        "hunt-crossley": {"damping": "hunt-crossley", "alpha": 0.0676},
        "thornton": {"contact": "thornton", "yield_pressure": 45.0e3,
                     "static_correction": False}}


@pytest.mark.parametrize("law", list(LAWS))
@pytest.mark.parametrize("name", list(FAMILY))
def test_the_energy_book_closes_on_the_family(name, law):
    """energy_ratio + dissipated / initial = 1 within 1e-6 (the run's
    energy check: a run that cannot close it reports status 9), the
    members' and contacts' energies sum to the end's; the elastic law
    dissipates nothing and the damped laws dissipate."""
    design = FAMILY[name].replace(n_modes=4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = simulate(design, t_end=0.03 if name.startswith("thesis")
                     else None, single_impulse=False, **LAWS[law])
    book = r.energy_book
    start = book["energy_initial_lbin"]
    closure = r.energy_ratio + book["energy_dissipated_contact_lbin"] \
        / start - 1.0
    assert r.status == 0
    assert abs(closure) <= 1e-6
    parts = sum(book[f"energy_member{i}_lbin"] for i in (1, 2, 3)) \
        + book["energy_contact_lbin"]
    assert parts / start == pytest.approx(r.energy_ratio, abs=1e-12)
    if law == "elastic":
        assert book["energy_dissipated_contact_lbin"] == 0.0
    else:
        assert book["energy_dissipated_contact_lbin"] > 1e-3 * start


def test_the_fixed_and_adaptive_books_agree():
    design = FAMILY["steel_relay"].replace(n_modes=4)
    runs = [simulate(design, damping="hunt-crossley", alpha=0.0676,
                     dt=5e-9, t_end=0.004, stepper=stepper,
                     single_impulse=False) for stepper in ("fixed",
                                                           "adaptive")]
    a, b = (r.energy_book for r in runs)
    assert a["energy_dissipated_contact_lbin"] == pytest.approx(
        b["energy_dissipated_contact_lbin"], rel=1e-6)
    assert a["energy_dissipated_contact_lbin"] > 0.0


@pytest.mark.parametrize("kwargs, name", [
    ({"damping": "hunt-crossley"}, "alpha"),
    ({"damping": "hunt-crossley", "alpha": -1.0}, "alpha"),
    ({"damping": "hunt-crossley", "alpha": math.inf}, "alpha"),
    ({"alpha": 0.05}, "alpha"),
    ({"contact": "thornton", "static_correction": False},
     "yield_pressure"),
    ({"contact": "thornton", "yield_pressure": 0.0,
      "static_correction": False}, "yield_pressure"),
    ({"yield_pressure": 4e4}, "yield_pressure"),
    ({"contact": "plastic"}, "contact"),
    ({"model": "newton", "damping": "hunt-crossley", "alpha": 0.05},
     "damping/contact"),
])
def test_a_law_that_cannot_run_is_refused_in_one_line(kwargs, name):
    import contactsep
    with pytest.raises(ChatterError) as caught:
        simulate(contactsep.thesis_design(n_modes=4), t_end=0.03, **kwargs)
    assert str(caught.value).startswith(f"{name}:")
    assert "\n" not in str(caught.value)


def test_a_cylindrical_button_is_a_linear_spring_on_a_free_mass():
    # F = k delta: the contact is half a period of sqrt(k/m); at a
    # quarter of it the mass stops at delta = V sqrt(m/k), and it leaves
    # at V (the first episode's impulse 2 m V)
    law = HertzLaw.for_materials(E, NU, RADIUS, button="cylinder")
    assert law.k == pytest.approx(math.pi / 4.0 * law.e_star * 2 * RADIUS)
    omega = math.sqrt(law.k / MASS)
    gap0, dt = 1e-7, 1e-10
    touch = gap0 / SPEED
    m, p = np.array([MASS]), np.array([1e-3])
    h, g0, c = np.ones((1, 1)), np.zeros(1), np.zeros((1, 1))
    q0, v0 = np.array([gap0]), np.array([-SPEED])
    args = (law.k, 0.0, 0.0, law.e_star, law.radius, 1)
    steps = int(round((touch + 0.5 * math.pi / omega) / dt))
    *_, q, v, book, status = api().run_hertz_book(
        m, p, h, g0, c, q0, v0, *args, dt, steps, steps, 2, 1e300)
    assert status == 0
    assert -q[0] == pytest.approx(SPEED / omega, rel=1e-4)
    assert abs(v[0]) < 1e-3 * SPEED
    steps = int(round((touch + 2.0 * math.pi / omega) / dt))
    _, _, e, _, first, q, v, book, status = api().run_hertz_book(
        m, p, h, g0, c, q0, v0, *args, dt, steps, steps, 2, 1e300)
    assert v[0] == pytest.approx(SPEED, rel=1e-8)
    assert first[1] == pytest.approx(2.0 * MASS * SPEED, rel=1e-4)
    assert abs((e[-1] + book[0]) / e[0] - 1.0) < 1e-9


def test_the_cylinder_runs_in_both_steppers_and_the_twin():
    import contactsep
    design = contactsep.thesis_design(n_modes=4)
    runs = [simulate(design, button="cylinder", t_end=0.025, dt=2e-8,
                     stepper=stepper, backend=backend, preload=0.2,
                     single_impulse=False)
            for stepper, backend in (("adaptive", "compiled"),
                                     ("fixed", "compiled"))]
    for r in runs:
        assert r.status == 0 and abs(r.energy_ratio - 1.0) < 1e-6
    assert runs[0].first_impulse_lb_s == pytest.approx(
        runs[1].first_impulse_lb_s, rel=1e-6)
    # the twin, plain and with the series correction's linear elements
    from contactsep.chatter import runners
    from contactsep.chatter.stack import _system
    law = HertzLaw.for_materials(float(design.E1), button="cylinder")
    for correct in (False, True):
        system = _system(design, 0.2, law, correct)
        a = runners.hertz_fixed(system, law, 2e-8, 2000, 100, 1e-6)
        b = runners.hertz_fixed(system, law, 2e-8, 2000, 100, 1e-6,
                                backend="numpy")
        assert np.allclose(a.gaps, b.gaps, rtol=0, atol=1e-12)
        assert a.book["end"] == pytest.approx(b.book["end"], rel=1e-12)


@pytest.mark.parametrize("kwargs, name", [
    ({"button": "cone"}, "button"),
    ({"button_length": 0.5}, "button_length"),
    ({"button": "cylinder", "button_length": -1.0}, "button_length"),
    ({"button": "cylinder", "contact": "thornton", "yield_pressure": 4e4,
      "static_correction": False}, "button"),
    ({"model": "newton", "button": "cylinder"}, "button"),
])
def test_a_button_that_cannot_run_is_refused_in_one_line(kwargs, name):
    import contactsep
    with pytest.raises(ChatterError) as caught:
        simulate(contactsep.thesis_design(n_modes=4), t_end=0.03, **kwargs)
    assert str(caught.value).startswith(f"{name}:")


@pytest.mark.parametrize("target", [0.95, 0.9, 0.6])
def test_flores_rebounds_near_its_e_and_exactly_as_its_ode(target):
    # Flores's chi = 8 (1 - e) / (5 e V) is Hunt-Crossley's law with
    # alpha = chi: the closed form is exact; e itself is Flores's
    # approximation (good near e = 1: 0.947 for 0.95, 0.577 for 0.6)
    law = HertzLaw.for_materials(E, NU, RADIUS, e=target, v_ref=SPEED)
    e, closure = free_mass_rebound(law, "adaptive")
    assert e == pytest.approx(hunt_crossley_e(law.chi, SPEED), abs=1e-8)
    assert e == pytest.approx(target, abs=0.25 * (1.0 - target))
    assert abs(closure) < 1e-8
