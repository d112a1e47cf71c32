"""The static point flexibility G(x) and the residual flexibility of the
modes past N (contactsep.beams.static_flexibility,
residual_flexibility): the static correction's series spring.

Independent paths: the static deflection of a point load solved here from
the beam equation (two cubics joined at the load, 8 conditions), the
published eigenvalue k_1L (tests/data/beam-constants.md), and tails of
the modal series summed in closed form (pinned-pinned: sin modes; the
cantilever's tip: X_j(L) = 2 (-1)^(j+1), k_jL -> (j - 1/2) pi, so the tail
is a Hurwitz zeta value)."""

import math

import mpmath
import numpy as np
import pytest

from contactsep import beams

ENDS = ("clamped-free", "clamped-clamped", "clamped-pinned",
        "pinned-pinned")
POINTS = (0.1, 0.3, 0.5, 0.77, 0.95)


def _cubic_rows(x, order):
    """Row of d^order/dx^order of [1, x, x^2, x^3] at x."""
    powers = [[1, x, x**2, x**3], [0, 1, 2 * x, 3 * x**2],
              [0, 0, 2, 6 * x], [0, 0, 0, 6]]
    return np.array(powers[order], dtype=float)


def point_load_deflection(end, a):
    """y(a) of EI y'''' = delta(x - a) on [0, 1] (EI = 1, unit load in +y):
    cubics A on [0, a] and B on [a, 1]; y, y', y'' continuous at a, y'''
    jumps by the load; each end's two conditions."""
    left, right = end.split("-")
    conditions = {"clamped": (0, 1), "pinned": (0, 2), "free": (2, 3)}
    rows, rhs = [], []
    for order in conditions[left]:
        rows.append(np.concatenate([_cubic_rows(0.0, order), np.zeros(4)]))
        rhs.append(0.0)
    for order in conditions[right]:
        rows.append(np.concatenate([np.zeros(4), _cubic_rows(1.0, order)]))
        rhs.append(0.0)
    for order in (0, 1, 2):
        rows.append(np.concatenate([_cubic_rows(a, order),
                                    -_cubic_rows(a, order)]))
        rhs.append(0.0)
    # integrating EI y'''' = P delta(x - a) across a: EI (y'''(a+) -
    # y'''(a-)) = P (rows hold A - B)
    rows.append(np.concatenate([_cubic_rows(a, 3), -_cubic_rows(a, 3)]))
    rhs.append(-1.0)
    coefficients = np.linalg.solve(np.array(rows), np.array(rhs))
    return float(_cubic_rows(a, 0) @ coefficients[:4])


@pytest.mark.parametrize("end", ENDS)
@pytest.mark.parametrize("xi", POINTS)
def test_static_flexibility_is_the_point_load_deflection(end, xi):
    assert beams.static_flexibility(end, xi) == pytest.approx(
        point_load_deflection(end, xi), rel=1e-12)


def test_the_cantilever_tip_is_l3_over_3ei():
    assert beams.static_flexibility("cantilever", 1.0) == pytest.approx(
        point_load_deflection("clamped-free", 1.0), rel=1e-12)
    assert beams.static_flexibility("cantilever", 1.0) == 1.0 / 3.0


@pytest.mark.parametrize("n", [8, 16, 64, 200])
def test_cantilever_tip_residual_is_the_zeta_tail(n):
    """r_N(1) = sum_{j>N} 4 / (k_jL)^4 with k_jL = (j - 1/2) pi up to
    e^{-k_jL} (below 1e-11 relative for j > 8)."""
    tail = 4.0 * float(mpmath.zeta(4, n + 0.5)) / math.pi**4
    assert beams.residual_flexibility("clamped-free", n, 1.0)[0] == \
        pytest.approx(tail, rel=1e-9)


def test_first_mode_residual_from_the_published_eigenvalue():
    """r_1 at the cantilever tip: 1/3 - 4/(k_1L)^4, k_1L = 1.87510407
    (Blevins, 8 digits: relative 2e-8 in the fourth power)."""
    expected = 1.0 / 3.0 - 4.0 / 1.87510407**4
    assert beams.residual_flexibility("clamped-free", 1, 1.0)[0] == \
        pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize("n", [1, 4, 16, 64])
@pytest.mark.parametrize("xi", [0.1, 0.5, 0.77])
def test_pinned_pinned_residual_is_the_sine_series_tail(n, xi):
    j = np.arange(n + 1, 400_001, dtype=float)
    # the tail past 4e5 is below 2 / (3 pi^4 4e5^3) ~ 1e-19
    tail = math.fsum(2.0 * np.sin(j * math.pi * xi)**2
                     / (j * math.pi)**4)
    assert beams.residual_flexibility("pinned-pinned", n, xi)[0] == \
        pytest.approx(tail, rel=1e-8)


@pytest.mark.parametrize("end", ENDS)
def test_residual_is_positive_and_falls_like_n_cubed(end):
    """Each term X_j^2 / (k_jL)^4 is >= 0 and ~ j^-4 on average: the
    residual never grows with N and, at a point in the span, falls by
    about 2^3 a doubling."""
    xi = 0.37
    values = [beams.residual_flexibility(end, n, xi)[0]
              for n in (8, 16, 32, 64, 128)]
    assert all(v >= 0.0 for v in values)
    assert all(b <= a for a, b in zip(values, values[1:]))
    ratios = [a / b for a, b in zip(values, values[1:])]
    assert all(5.0 < r < 12.0 for r in ratios), ratios


def test_residual_at_several_points_at_once():
    xi = np.array([0.1, 0.5, 1.0])
    together = beams.residual_flexibility("clamped-free", 12, xi)
    apart = [beams.residual_flexibility("clamped-free", 12, x)[0]
             for x in xi]
    np.testing.assert_array_equal(together, apart)
    with pytest.raises(ValueError):
        beams.residual_flexibility("clamped-free", 12, 1.5)
