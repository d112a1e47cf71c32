"""Eq. 23 with other beam physics than the thesis's (issue 27 item 5):
Timoshenko members, elastic supports, point masses.

Other paths than the code under test:

* the thesis's physics sent through the general path (the members' modes
  given, from contactsep.beams' closed forms) against the compiled kernel
  that computes them itself: the same arithmetic, so the same numbers;
* an independent eq. 23 written here: the upper contact's initial modal
  coordinates by numerical quadrature of its closed-form static shape
  (a cantilever with root springs, shear flexibility, a tip load) against
  the modes (with rotary inertia and the point mass in the inner
  product), the first impact by a grid and Brent's method, the impulse
  from the test's own sums, the lower contact's response by integrating
  its modal equations (solve_ivp) and its maximum by sampling and a
  bounded search; none of the package's formulas (A_j = y_s X_j(a) /
  (b_j^2 G(a)), the safe-step impact search, c_j sin p_j t, the branch
  and bound) is used.
"""

from __future__ import annotations

import dataclasses
import sys
import warnings

import numpy as np
import pytest
from design_family import FAMILY
from scipy import integrate, optimize

import contactsep
from contactsep.beams import timoshenko_modes
from contactsep.model import compiled, evaluate, given, physics, twin
from contactsep.model.design import pack
from contactsep.model.energy import EnergyBoundWarning

GRAVITY = 386.4        # in/s^2, the thesis's g (docs/model.md, Units)

NAMES = ("thesis_thick", "steel_thick", "bronze_offset", "becu_light")


@pytest.mark.parametrize("name", sorted(FAMILY))
def test_given_closed_form_modes_are_the_kernels(name):
    """The thesis's physics through the general path (modes given) gives
    the fast path's numbers, compiled (to 1e-13) and twin (1e-12)."""
    design = FAMILY[name].replace(n_modes=(5, 7, 6), tau=0.02)
    packed = pack(design)
    fast = compiled.evaluate_packed(packed)
    with_modes = dataclasses.replace(
        packed, modes=given.given_modes(design, packed))
    for backend, rtol in ((compiled, 1e-13), (twin, 1e-12)):
        out = backend.evaluate_packed(with_modes)
        assert out["status"].tolist() == fast["status"].tolist() == [0]
        for key in ("t1", "v_impact", "psi", "v0", "R", "y3_max",
                    "y3_min", "M1", "M2", "M3", "p1", "p2", "p3"):
            np.testing.assert_allclose(out[key], fast[key], rtol=rtol,
                                       err_msg=f"{name} {key}")


@pytest.mark.parametrize("options", [
    dict(Lc=3.6, lc_reading="listing"), dict(Lc=3.6, lc_reading="mass"),
    dict(Lc=3.6, lc_reading="frequencies"),
    dict(impact_velocity="listing", lower_response="as-printed"),
    dict(release="contact", x1=15.0, end1="clamped-pinned")])
def test_given_modes_take_every_option_as_the_kernel(options):
    """L_c's readings, the listing's impact speed, eq. 13 as printed and
    a release at the contact point through the given-modes path."""
    design = FAMILY["thesis"].replace(n_modes=6, tau=0.02, **options)
    packed = pack(design)
    fast = compiled.evaluate_packed(packed)
    with_modes = dataclasses.replace(
        packed, modes=given.given_modes(design, packed))
    for backend, rtol in ((compiled, 1e-13), (twin, 1e-12)):
        out = backend.evaluate_packed(with_modes)
        assert out["status"].tolist() == fast["status"].tolist() == [0]
        for key in ("t1", "v_impact", "psi", "v0", "R", "y3_max", "M2",
                    "p2"):
            np.testing.assert_allclose(out[key], fast[key], rtol=rtol,
                                       err_msg=f"{options} {key}")


def _general(design):
    """The design with every member a Timoshenko beam on elastic
    supports, a point mass on each (the upper's off its contact point)."""
    length1 = float(design.L1)
    ei1 = float(design.E1) * float(design.b1) * float(design.h1)**3 / 12.0
    ei2 = float(design.E2) * float(design.b2) * float(design.h2)**3 / 12.0
    weight1 = float(design.gamma1 * design.b1 * design.h1 * design.L1)
    weight2 = float(design.gamma2 * design.b2 * design.h2 * design.L2)
    weight3 = float(design.gamma3 * design.b3 * design.h3 * design.L3)
    return design.replace(
        beam1="timoshenko", beam2="timoshenko", beam3="timoshenko",
        kr1=3.0 * ei1 / length1, kt1=30.0 * ei1 / length1**3,
        mass1=0.2 * weight1, x_mass1=0.6 * length1,
        kr2=2.0 * ei2 / float(design.L2), mass2=0.3 * weight2,
        nu3=0.3, kappa3=0.8, kt3=1e3 * ei1 / length1**3,
        mass3=0.1 * weight3, n_modes=5)


def _own_modes(design, member, xi):
    """b_j, X_j(xi), Psi_j(xi) of a member (the package's modes, which
    tests/shared checks against a finite-element beam)."""
    beam = physics.member_beam(design, member).dimensionless()
    n = design.n_modes
    return timoshenko_modes.modes(beam, n, np.asarray(xi, dtype=float))


def _quadrature(panels=60, order=12):
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(0.0, 1.0, panels + 1)
    h = np.diff(edges)
    nodes = (edges[:-1, None] + 0.5 * h[:, None] * (x[None, :] + 1.0))
    return nodes.ravel(), (0.5 * h[:, None] * w[None, :]).ravel()


def _independent(design):
    """y3_max and the impact's figures of eq. 23 (impulse form), written
    from the mechanics (module docstring)."""
    L1, b1, h1 = (float(design.L1), float(design.b1), float(design.h1))
    E1, gamma1, nu1 = float(design.E1), float(design.gamma1), 0.33
    area, inertia = b1 * h1, b1 * h1**3 / 12.0
    rho_a = gamma1 * area / GRAVITY
    ei = E1 * inertia
    kappa = 10.0 * (1.0 + nu1) / (12.0 + 11.0 * nu1)   # Cowper
    kga = kappa * E1 / (2.0 * (1.0 + nu1)) * area
    kr, kt = float(design.kr1), float(design.kt1)

    def static(x):
        """Deflection and rotation under a unit tip load: springs at the
        root, bending, shear (a cantilever's closed form)."""
        w = 1 / kt + L1 * x / kr + (L1 * x**2 / 2 - x**3 / 6) / ei + x / kga
        psi = L1 / kr + (L1 * x - x**2 / 2) / ei
        return w, psi

    force = float(design.ys) / static(L1)[0]        # tip released at ys
    xq, wq = _quadrature()
    x_mass, mass = float(design.x_mass1), float(design.mass1) / GRAVITY
    x1 = L1 if design.x1 is None else float(design.x1)
    points = np.concatenate([xq, [x_mass / L1, x1 / L1]])
    b, X, Psi = _own_modes(design, "1", points)
    Xq, Psiq = X[:, :-2], Psi[:, :-2]
    w0, psi0 = (force * v for v in static(xq * L1))
    w_mass = force * static(x_mass)[0]
    # q_j(0) = <X_j, (w0, psi0)> / (rho A L), the inner product of the
    # modes' normalisation (rotary inertia, the point mass); psi = Psi/L
    inner = (rho_a * L1 * (Xq * w0) @ wq
             + rho_a * inertia / area * (Psiq * psi0) @ wq
             + mass * w_mass * X[:, -2])
    q0 = inner / (rho_a * L1)
    p1 = b * np.sqrt(ei / rho_a) / L1**2
    at_x1 = q0 * X[:, -1]
    gap = float(design.gap)

    def y1(t):
        return np.sum(at_x1 * np.cos(p1 * t)) - gap

    grid = np.arange(0.0, 2 * np.pi / p1[0], 2 * np.pi / p1[-1] / 50)
    values = np.array([y1(t) for t in grid])
    k = int(np.flatnonzero(values <= 0.0)[0])
    t1 = optimize.brentq(y1, grid[k - 1], grid[k], xtol=1e-16, rtol=1e-15)
    v = abs(np.sum(at_x1 * p1 * np.sin(p1 * t1)))

    sums, masses, modes = [], [], []
    for m in "123":
        member = physics.member_beam(design, m)
        x = {"1": x1, "2": float(design.L2) / 2, "3": float(design.L3)}[m]
        x = x if getattr(design, "x" + m) is None else float(
            getattr(design, "x" + m))
        bm, Xm, _ = _own_modes(design, m, [x / member.length])
        sums.append(float(np.sum(Xm[:, 0]**2)))
        masses.append(member.gamma * member.width * member.thickness
                      * member.length / GRAVITY)
        modes.append((bm * np.sqrt(member.modulus * member.width
                                   * member.thickness**3 / 12.0
                                   * GRAVITY / (member.gamma * member.width
                                                * member.thickness))
                       / member.length**2, Xm[:, 0]))
    # the momentum balance with restitution: each member's contact point
    # takes psi sum_j X_j^2 / M of velocity
    psi = (1.0 + float(design.e)) * v / sum(
        s / mm for s, mm in zip(sums, masses))
    v0 = psi * sums[1] / masses[1]
    p3, x3v = modes[2]

    def motion(t, state):
        q, qdot = state[:p3.size], state[p3.size:]
        return np.concatenate([qdot, -p3**2 * q])

    start = np.concatenate([np.zeros(p3.size), psi * x3v / masses[2]])
    tau = float(design.tau)
    run = integrate.solve_ivp(motion, (0.0, tau), start, method="DOP853",
                              rtol=1e-13, atol=1e-20 * psi, dense_output=True)

    def y3(t):
        return float(x3v @ run.sol(t)[:p3.size])

    samples = np.linspace(0.0, tau, int(tau * p3[-1] / np.pi * 20) + 2)
    values = np.array([y3(t) for t in samples])
    k = int(np.argmax(values))
    lo, hi = samples[max(k - 1, 0)], samples[min(k + 1, samples.size - 1)]
    best = optimize.minimize_scalar(lambda t: -y3(t), bounds=(lo, hi),
                                    method="bounded",
                                    options={"xatol": 1e-14})
    return {"t1": t1, "v_impact": v, "psi": psi, "v0": v0,
            "y3_max": max(-best.fun, values[k])}


@pytest.mark.parametrize("name", NAMES)
def test_eq_23_with_timoshenko_springs_and_masses_by_quadrature(name):
    base = _general(FAMILY[name])
    # a window of three periods of the lower contact's first mode
    p3 = contactsep.modes(base, 3, 1).p_rad_s[0]
    design = base.replace(tau=min(0.5, 6 * np.pi / p3))
    own = _independent(design)
    for backend in ("compiled", "numpy"):
        result = evaluate(design, backend=backend)
        assert int(result.status) == 0
        for key, rtol in (("t1", 1e-10), ("v_impact", 1e-9),
                          ("psi", 1e-9), ("v0", 1e-9), ("y3_max", 1e-8)):
            assert float(getattr(result, key)) == pytest.approx(
                own[key], rel=rtol), (name, backend, key)


def test_a_batch_is_its_designs_and_failures_are_statuses(monkeypatch):
    """A batch of general designs (the modes grouped by member, the
    batch cut into pieces) gives each design's own numbers; a design
    whose modes cannot be computed gets status 2, not an exception."""
    from contactsep.output import pieces as pieces_module
    base = contactsep.thesis_design(beam2="timoshenko", kr2=2e4,
                                    mass3=0.01, n_modes=6, tau=0.02)
    thick = np.array([0.125, 0.75, 0.25, 0.75])
    batch = base.replace(h2=thick, L3=np.array([19.0, 19.0, 20.0, 20.0]))
    monkeypatch.setattr(pieces_module, "FIRST_PIECE_COST", 6)
    whole = evaluate(batch)
    assert whole.status.tolist() == [0, 0, 0, 0]
    for k in range(4):
        one = evaluate(base.replace(h2=float(thick[k]),
                                    L3=float(batch.L3[k])))
        for key in ("psi", "y3_max", "p2", "p3"):
            np.testing.assert_array_equal(getattr(whole, key)[k],
                                          getattr(one, key))
    # a point mass past the lower contact's end in some rows
    wrong = base.replace(L3=np.array([19.0, 12.0]), x_mass3=15.0)
    assert evaluate(wrong).status.tolist() == [0, 2]
    assert evaluate(wrong, backend="numpy").status.tolist() == [0, 2]
    # more modes than a general member takes
    many = evaluate(base.replace(n_modes=(4, 250, 4)))
    assert int(many.status) == 2 and np.isnan(float(many.psi))


def test_a_stiff_spring_is_the_rigid_support():
    """kr, kt -> infinity: eq. 23 with springs tends to the thesis's
    (rigid) numbers; a soft spring moves them."""
    base = FAMILY["thesis"].replace(n_modes=6)
    rigid = evaluate(base)
    stiff = evaluate(base.replace(kr2=1e13, kt2=1e15))
    soft = evaluate(base.replace(kr2=1e3))
    for key in ("psi", "v0", "y3_max"):
        assert float(getattr(stiff, key)) == pytest.approx(
            float(getattr(rigid, key)), rel=1e-7)
    assert abs(float(soft.v0) / float(rigid.v0) - 1.0) > 0.01


@pytest.mark.parametrize("name", NAMES)
def test_the_energy_bound_takes_the_springs_and_shear(name):
    """The release's energy bound with the members' own flexibilities:
    G1 at the tip is the test's closed-form cantilever (springs, shear);
    the impulse form stays within the bound (no warning) at N = 4, 12."""
    design = _general(FAMILY[name])
    packed = pack(design)
    modes = given.given_modes(design, packed)
    L1, E1 = float(design.L1), float(design.E1)
    area, inertia = float(design.b1 * design.h1), float(
        design.b1 * design.h1**3 / 12.0)
    kappa = 10.0 * 1.33 / (12.0 + 11.0 * 0.33)
    tip = (1 / float(design.kt1) + L1**2 / float(design.kr1)
           + L1**3 / (3 * E1 * inertia)
           + L1 / (kappa * E1 / 2.66 * area))
    assert float(modes.flex[0]) == pytest.approx(
        tip * E1 * inertia / L1**3, rel=1e-10)
    for n in (4, 12):
        with warnings.catch_warnings():
            warnings.simplefilter("error", EnergyBoundWarning)
            result = evaluate(design.replace(n_modes=n))
        assert int(result.status) == 0
