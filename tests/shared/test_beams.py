"""Tests of contactsep.beams against published constants and exact identities.

Expected numbers come from outside the code under test: the published table
below, closed-form identities of Bernoulli-Euler beams, and an independent
high-precision evaluation of the textbook formulas with mpmath.
"""

import math

import numpy as np
import pytest

from contactsep import beams

CANT, CC = "cantilever", "clamped-clamped"

# R. D. Blevins, Formulas for Natural Frequency and Mode Shape (1979),
# Table 8-1, as quoted in tests/data/beam-constants.md.  Strings, so that
# the tolerance is half a unit in the last printed digit.
PUBLISHED = {
    CANT: {
        "k": ["1.87510407", "4.69409113", "7.85475744", "10.99554073",
              "14.13716839", "17.27875953"],
        "sigma": ["0.734095514", "1.018467319", "0.999224497", "1.000033553",
                  "0.999998550", "1.000000063"],
    },
    CC: {
        "k": ["4.73004074", "7.85320462", "10.9956078", "14.1371655",
              "17.2787597"],
        "sigma": ["0.982502215", "1.000777312", "0.999966450", "1.000001450",
                  "0.999999937"],
    },
}


def half_unit_in_last_digit(text):
    return 0.5 * 10.0 ** -len(text.split(".")[1])


def gauss_legendre_01(panels=32, points=40):
    """Composite Gauss-Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(points)
    edges = np.linspace(0.0, 1.0, panels + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[:-1] + edges[1:])
    nodes = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    weights = (half[:, None] * w[None, :]).ravel()
    return nodes, weights


def textbook_modes(support, kl, xi):
    """The printed formulas, evaluated literally (cancels badly for high j)."""
    if support == CANT:
        sigma = (np.sinh(kl) - np.sin(kl)) / (np.cosh(kl) + np.cos(kl))
    else:
        sigma = (np.cosh(kl) - np.cos(kl)) / (np.sinh(kl) - np.sin(kl))
    z = kl[:, None] * xi[None, :]
    return (np.cosh(z) - np.cos(z)
            - sigma[:, None] * (np.sinh(z) - np.sin(z)))


@pytest.mark.parametrize("support", [CANT, CC])
@pytest.mark.parametrize("quantity", ["k", "sigma"])
def test_matches_published_table(support, quantity):
    table = PUBLISHED[support][quantity]
    n = len(table)
    got = (beams.eigenvalues(support, n) if quantity == "k"
           else beams.alphas(support, n))
    for j, text in enumerate(table):
        assert abs(got[j] - float(text)) <= half_unit_in_last_digit(text) * (1 + 1e-9), (
            f"{support} {quantity}_{j + 1}: {got[j]!r} vs published {text}")


@pytest.mark.parametrize("support", [CANT, CC])
def test_eigenvalues_solve_frequency_equation_in_high_precision(support):
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 50
    rhs = -1 if support == CANT else 1
    k = beams.eigenvalues(support, 40)
    for kj in k:
        # cos kL cosh kL = rhs divided by cosh kL, to keep the residual O(1)
        root = mp.findroot(lambda x: mp.cos(x) - rhs / mp.cosh(x), mp.mpf(float(kj)))
        ulp = math.ulp(float(kj))
        assert abs(float(kj) - float(root)) <= ulp, (kj, root)


@pytest.mark.parametrize("support", [CANT, CC])
def test_alpha_and_one_minus_alpha_in_high_precision(support):
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 80
    k = beams.eigenvalues(support, 30)
    alpha, g = beams._alpha_parts(support, k)
    for kj, aj, gj in zip(k, alpha, g):
        x = mp.mpf(float(kj))
        if support == CANT:
            exact = (mp.sinh(x) - mp.sin(x)) / (mp.cosh(x) + mp.cos(x))
        else:
            exact = (mp.cosh(x) - mp.cos(x)) / (mp.sinh(x) - mp.sin(x))
        assert abs(aj - float(exact)) <= 2 * math.ulp(float(exact))
        one_minus = (1 - exact)
        # g = (1 - alpha) e^{kL}: 1 - alpha to a few ulps of itself
        assert abs(gj * math.exp(-float(kj)) - float(one_minus)) <= (
            1e-14 * abs(float(one_minus)))


@pytest.mark.parametrize("support", [CANT, CC])
def test_modes_match_high_precision_textbook_form(support):
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 80
    n = 40
    xi = np.array([0.0, 0.05, 0.2, 0.5, 0.77, 0.95, 1.0])
    k = beams.eigenvalues(support, n)
    got = beams.mode_shapes(support, n, xi)
    for j in range(n):
        x = mp.mpf(float(k[j]))
        if support == CANT:
            sigma = (mp.sinh(x) - mp.sin(x)) / (mp.cosh(x) + mp.cos(x))
        else:
            sigma = (mp.cosh(x) - mp.cos(x)) / (mp.sinh(x) - mp.sin(x))
        for i, s in enumerate(xi):
            z = x * mp.mpf(float(s))
            exact = mp.cosh(z) - mp.cos(z) - sigma * (mp.sinh(z) - mp.sin(z))
            assert abs(got[j, i] - float(exact)) <= 1e-13, (j + 1, s)


@pytest.mark.parametrize("support", [CANT, CC])
def test_stable_form_agrees_with_textbook_form_for_low_modes(support):
    n = 5
    xi = np.linspace(0.0, 1.0, 101)
    k = beams.eigenvalues(support, n)
    stable = beams.mode_shapes(support, n, xi)
    textbook = textbook_modes(support, k, xi)
    # the textbook form loses about e^{kL} ulps
    tolerance = 100 * np.finfo(float).eps * np.exp(k)[:, None]
    assert np.all(np.abs(stable - textbook) <= tolerance)


@pytest.mark.parametrize("support", [CANT, CC])
def test_orthonormal_for_thirty_modes(support):
    n = 30
    nodes, weights = gauss_legendre_01()
    modes = beams.mode_shapes(support, n, nodes)
    gram = (modes * weights) @ modes.T
    assert np.max(np.abs(gram - np.eye(n))) < 1e-10


def test_quadrature_is_exact_enough():
    # the rule integrates the steepest integrand factor, e^{2 kL (xi - 1)}
    nodes, weights = gauss_legendre_01()
    for a in (2 * 100.0, 50.0, 3.0):
        exact = -math.expm1(-a) / a
        assert abs(weights @ np.exp(a * (nodes - 1.0)) - exact) < 1e-14


@pytest.mark.parametrize("support", [CANT, CC])
def test_derivatives_match_finite_differences(support):
    n, h = 6, 1e-5
    xi = np.linspace(0.1, 0.9, 9)
    for m in (1, 2, 3):
        plus = beams.mode_shapes(support, n, xi + h, derivative=m - 1)
        minus = beams.mode_shapes(support, n, xi - h, derivative=m - 1)
        central = (plus - minus) / (2 * h)
        analytic = beams.mode_shapes(support, n, xi, derivative=m)
        scale = beams.eigenvalues(support, n)[:, None] ** m
        assert np.all(np.abs(central - analytic) <= 1e-6 * scale), m
    # and the beam equation X'''' = (kL)^4 X, from the third derivative
    k = beams.eigenvalues(support, n)[:, None]
    fourth = (beams.mode_shapes(support, n, xi + h, derivative=3)
              - beams.mode_shapes(support, n, xi - h, derivative=3)) / (2 * h)
    assert np.all(np.abs(fourth - k**4 * beams.mode_shapes(support, n, xi))
                  <= 1e-6 * k**4)


@pytest.mark.parametrize("support", [CANT, CC])
def test_boundary_conditions(support):
    n = 40
    k = beams.eigenvalues(support, n)
    ends = [0.0, 1.0]
    x = [beams.mode_shapes(support, n, ends, derivative=m) for m in range(4)]
    tol = 1e-13
    # clamped at x = 0: X = X' = 0
    assert np.all(np.abs(x[0][:, 0]) <= tol)
    assert np.all(np.abs(x[1][:, 0]) <= tol * k)
    if support == CANT:
        # free at x = L: no moment, no shear
        assert np.all(np.abs(x[2][:, 1]) <= tol * k**2)
        assert np.all(np.abs(x[3][:, 1]) <= tol * k**3)
    else:
        assert np.all(np.abs(x[0][:, 1]) <= tol)
        assert np.all(np.abs(x[1][:, 1]) <= tol * k)


def test_cantilever_tip_value_is_two_alternating():
    n = 40
    j = np.arange(1, n + 1)
    expected = 2.0 * (-1.0) ** (j + 1)
    assert np.all(np.abs(beams.tip_values(n) - expected) <= 1e-13)


def test_cantilever_tip_flexibility():
    """sum 1/(k_jL)^4 = 1/12: the static tip deflection L^3/(3EI) in modes.

    Root j lies in [(j-1)pi, j pi] (|cos| = 1 > 1/cosh at the ends), so the
    tail beyond n modes lies between 1/(3 pi^4 (n+1)^3) and 1/(3 pi^4 (n-1)^3).
    """
    n = 2000
    k = beams.eigenvalues(CANT, n)
    tail = 1.0 / 12.0 - math.fsum(1.0 / k**4)
    assert 1.0 / (3 * math.pi**4 * (n + 1) ** 3) - 1e-16 <= tail
    assert tail <= 1.0 / (3 * math.pi**4 * (n - 1) ** 3) + 1e-16


def test_clamped_midspan_flexibility():
    """sum X_j(L/2)^2/(k_jL)^4 = 1/192: mid-span deflection L^3/(192EI).

    k_jL > j pi and |X_j(L/2)| < 1.5 for j >= 2 (cos z - sin z plus terms of
    order e^{-kL/2}), so the tail beyond n modes is below 2.25/(3 pi^4 n^3).
    """
    n = 2000
    k = beams.eigenvalues(CC, n)
    mid = beams.midspan_values(n)
    assert np.all(np.abs(mid[1:]) < 1.5)
    tail = 1.0 / 192.0 - math.fsum(mid**2 / k**4)
    assert -1e-16 <= tail <= 2.25 / (3 * math.pi**4 * n**3) + 1e-16


def test_clamped_symmetry_and_even_modes_vanish_at_midspan():
    n = 30
    xi = np.linspace(0.0, 1.0, 41)
    modes = beams.mode_shapes(CC, n, xi)
    parity = (-1.0) ** np.arange(n)  # + for odd j, - for even j
    assert np.all(np.abs(modes[:, ::-1] - parity[:, None] * modes) <= 1e-12)
    raw = beams.mode_shapes(CC, n, [0.5])[:, 0]
    assert np.all(np.abs(raw[1::2]) <= 1e-13)
    mid = beams.midspan_values(n)
    assert np.all(mid[1::2] == 0.0)
    assert np.array_equal(mid[::2], raw[::2])


def test_thesis_midspan_value_of_first_mode():
    # X_1(L/2) = cosh(k/2) - cos(k/2) - sigma (sinh(k/2) - sin(k/2)) with the
    # published k_1L and sigma_1: the textbook form is accurate for j = 1
    k, sigma = 4.73004074, 0.982502215
    z = k / 2
    expected = math.cosh(z) - math.cos(z) - sigma * (math.sinh(z) - math.sin(z))
    assert abs(beams.midspan_values(1)[0] - expected) < 1e-7


@pytest.mark.parametrize("call", [
    lambda: beams.eigenvalues("pinned", 3),
    lambda: beams.eigenvalues(CANT, 0),
    lambda: beams.alphas(CC, 2.0),
    lambda: beams.mode_shapes(CANT, 3, [1.5]),
    lambda: beams.mode_shapes(CANT, 3, [[0.5]]),
    lambda: beams.mode_shapes(CANT, 3, [0.5], derivative=4),
])
def test_rejects_bad_arguments(call):
    with pytest.raises(ValueError):
        call()


def test_scalar_xi_and_shapes():
    assert beams.mode_shapes(CANT, 3, 0.25).shape == (3, 1)
    assert beams.mode_shapes(CC, 7, np.linspace(0, 1, 5)).shape == (7, 5)
    assert beams.eigenvalues(CANT, 1).shape == (1,)
