"""The general beam (contactsep.beams.timoshenko, its modes and static
flexibility: timoshenko_modes, timoshenko_static) against other methods:
a finite-element beam of the tests' own (fe_beam.py), closed-form
frequency equations (the simply supported Timoshenko beam's two
branches, the cantilever with a tip mass), the Bernoulli-Euler closed
forms, the rigid and pinned limits of the springs, closed-form static
beams, and orthogonality by the tests' own quadrature."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

import fe_beam as fe
from contactsep import beams
from contactsep.beams import member as mb
from contactsep.beams import timoshenko as T
from contactsep.beams import timoshenko_modes as TM
from contactsep.beams import timoshenko_static as TS

#: A stubby aluminium beam, h/L = 0.3 (the thickest separator): its
#: second branch starts below the third mode.
R2 = 0.3**2 / 12.0
S2 = R2 * 2.0 * 1.33 / mb.cowper_kappa(0.33)
CASES = {
    "bernoulli-euler": {},
    "timoshenko": {"r2": R2, "s2": S2},
    "timoshenko-springs-mass": {"r2": R2, "s2": S2, "kr": 5.0, "kt": 300.0,
                                "masses": ((0.5, 0.3),)},
    "spring-tip-mass": {"kr": 2.0, "masses": ((1.0, 0.5),)},
}


def quadrature(panels=64, points=16):
    x, w = np.polynomial.legendre.leggauss(points)
    edges = np.linspace(0.0, 1.0, panels + 1)
    width = np.diff(edges)[:, None]
    return ((edges[:-1, None] + width * 0.5 * (x + 1.0)).ravel(),
            (width * 0.5 * w).ravel())


@pytest.mark.parametrize("end", beams.END_CONDITIONS)
def test_bernoulli_euler_limit_reproduces_the_closed_form(end):
    xi = np.linspace(0.0, 1.0, 21)
    b, x, psi = TM.modes(T.Beam(end), 10, xi)
    kl = beams.eigenvalues(end, 10)
    assert np.max(np.abs(np.sqrt(b) / kl - 1.0)) < 1e-13
    assert np.max(np.abs(x - beams.mode_shapes(end, 10, xi))) < 1e-12
    slope = beams.mode_shapes(end, 10, xi, derivative=1)
    assert np.max(np.abs(psi - slope) / kl[:, None]) < 1e-12


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("end", beams.END_CONDITIONS)
def test_frequencies_match_a_converged_finite_element_beam(end, case):
    options = CASES[case]
    exact = T.eigenvalues(T.Beam(end, **options), 6)
    converged, finest = fe.converged(end, 6, **options)
    # the FE values converge onto them (Romberg from 16, 32, 64 elements)
    assert np.all(np.abs(converged / exact - 1.0)[:3] < 1e-7)
    assert np.all(np.abs(converged / exact - 1.0) < 1e-5)
    # and the coarser FE model lies above them (Rayleigh-Ritz bound)
    assert np.all(finest >= exact * (1.0 - 1e-12))


def test_simply_supported_timoshenko_both_branches_and_cutoff_mode():
    """Pinned ends take sin(n pi xi) exactly: r2 s2 b^4 - (1 + (r2 + s2)
    (n pi)^2) b^2 + (n pi)^4 = 0 gives both branches; n = 0 is the
    cut-off b = 1/sqrt(r2 s2) (psi constant, w = 0)."""
    expected = [1.0 / np.sqrt(R2 * S2)]
    for n in range(1, 30):
        k2 = (n * np.pi) ** 2
        p, q = -(1.0 + (R2 + S2) * k2) / (R2 * S2), k2**2 / (R2 * S2)
        root = np.sqrt(p * p / 4.0 - q)
        expected += [np.sqrt(-p / 2.0 - root), np.sqrt(-p / 2.0 + root)]
    expected = np.sort(expected)[:16]
    found = T.eigenvalues(T.Beam("pinned-pinned", R2, S2), 16)
    assert found[3] > expected[0]      # modes above the cut-off included
    np.testing.assert_allclose(found, expected, rtol=1e-12)


def test_cantilever_with_tip_mass_frequency_equation():
    """1 + cos k cosh k + mu k (cos k sinh k - sin k cosh k) = 0 (the
    classical tip-mass cantilever, Bernoulli-Euler), in 30 digits."""
    mu = 0.5
    found = T.eigenvalues(T.Beam("clamped-free", masses=((1.0, mu),)), 6)
    mpmath.mp.dps = 30

    def equation(k):
        return 1 + mpmath.cos(k) * mpmath.cosh(k) + mu * k * (
            mpmath.cos(k) * mpmath.sinh(k) - mpmath.sin(k) * mpmath.cosh(k))

    for b in found:
        root = mpmath.findroot(equation, mpmath.mpf(np.sqrt(b)))
        assert abs(float(root) ** 2 / b - 1.0) < 1e-13


@pytest.mark.parametrize("theory", [{}, {"r2": R2, "s2": S2}])
def test_spring_limits_rigid_and_pinned(theory):
    count = 5
    rigid = T.eigenvalues(T.Beam("clamped-clamped", **theory), count)
    stiff = T.eigenvalues(T.Beam("clamped-clamped", kr=1e10, kt=1e13,
                                 **theory), count)
    np.testing.assert_allclose(stiff, rigid, rtol=1e-7)
    pinned = T.eigenvalues(T.Beam("pinned-pinned", **theory), count)
    soft = T.eigenvalues(T.Beam("clamped-clamped", kr=1e-8, **theory),
                         count)
    np.testing.assert_allclose(soft, pinned, rtol=1e-8)
    # in between, strictly between (min-max)
    mid = T.eigenvalues(T.Beam("clamped-clamped", kr=10.0, **theory),
                        count)
    assert np.all((mid > pinned) & (mid < rigid))


def test_static_flexibility_against_closed_form_beams():
    kr, kt = 7.0, 40.0
    # cantilever, tip load: bending + shear + root rotation + root spring
    got = TS.static_flexibility(T.Beam("clamped-free", R2, S2, kr, kt), 1.0)
    assert got == pytest.approx(1 / 3 + S2 + 1 / kr + 1 / kt, rel=1e-12)
    # simply supported, mid-span: bending + shear + the two springs
    got = TS.static_flexibility(T.Beam("pinned-pinned", R2, S2, None, kt),
                                0.5)
    assert got == pytest.approx(1 / 48 + S2 / 4 + 1 / (2 * kt), rel=1e-12)
    # clamped-clamped with rotational springs, mid-span (Bernoulli-Euler):
    # end moment from the slope condition, 1/48 - kr/(64 (2 + kr))
    got = TS.static_flexibility(T.Beam("clamped-clamped", kr=kr), 0.5)
    assert got == pytest.approx(1 / 48 - kr / (64 * (2 + kr)), rel=1e-12)
    got = TS.static_flexibility(T.Beam("clamped-clamped", R2, S2), 0.5)
    assert got == pytest.approx(1 / 192 + S2 / 4, rel=1e-12)
    # off mid-span, rigid ends: the classical formulas
    for end in beams.END_CONDITIONS:
        np.testing.assert_allclose(
            TS.static_flexibility(T.Beam(end), [0.2, 0.7]),
            beams.static_flexibility(end, [0.2, 0.7]), rtol=1e-12)


def test_static_flexibility_against_the_finite_element_beam():
    for end in beams.END_CONDITIONS:
        for xi in (0.3, 0.5, 0.85):
            options = {"s2": S2, "kr": 3.0, "kt": 90.0}
            exact = TS.static_flexibility(T.Beam(end, **options), xi)
            assert exact == pytest.approx(
                fe.static_deflection(end, xi, **options), rel=1e-9)


@pytest.mark.parametrize("case", sorted(CASES))
def test_modes_are_orthonormal_with_rotary_inertia_and_masses(case):
    options = CASES[case]
    beam = T.Beam("clamped-clamped", **options)
    qx, qw = quadrature()
    b, x, psi = TM.modes(beam, 8, qx)
    gram = np.einsum("p,ip,jp->ij", qw, x, x) + \
        beam.r2 * np.einsum("p,ip,jp->ij", qw, psi, psi)
    for xi, mu in beam.masses:
        _, at, _ = TM.modes(beam, 8, [xi])
        gram += mu * at @ at.T
    np.testing.assert_allclose(gram, np.eye(8), atol=1e-10)


@pytest.mark.parametrize("case", ["bernoulli-euler", "spring-tip-mass"])
def test_mode_sum_is_the_static_flexibility(case):
    """G(xi) = sum X_j(xi)^2 / b_j^2 with the modes normalised in the
    whole mass (the point mass too): a check of the normalisation that
    needs no quadrature.  Without shear the terms fall as j^-4: past 30
    modes (X^2 <= 4, b_j >= (j pi)^2 / 2) the tail is below
    8/(3 pi^4 30^3) = 1.0e-6, 2.4e-4 of G = 4.2e-3, and the sum must
    come within that (with shear the terms fall as j^-2: the
    orthogonality test covers that normalisation)."""
    beam = T.Beam("clamped-clamped", **CASES[case])
    b, x, _ = TM.modes(beam, 30, [0.37])
    total = np.sum(x[:, 0] ** 2 / b**2)
    exact = TS.static_flexibility(beam, 0.37)
    assert 0.0 < exact - total < 8.0 / (3.0 * np.pi**4 * 30**3)


def test_bad_beams_are_refused():
    with pytest.raises(ValueError, match="kr"):
        T.Beam("clamped-free", kr=0.0)
    with pytest.raises(ValueError, match="r2"):
        T.Beam("clamped-free", r2=-1.0)
    with pytest.raises(ValueError, match="point mass"):
        T.Beam("clamped-free", masses=((1.5, 0.1),))
    with pytest.raises(ValueError, match="end condition"):
        T.Beam("free-free")
    with pytest.raises(ValueError, match="n must"):
        T.eigenvalues(T.Beam(), 0)


def test_cowper_coefficient():
    assert mb.cowper_kappa(0.0) == pytest.approx(10 / 12)
    assert mb.cowper_kappa(0.5) == pytest.approx(15 / 17.5)
