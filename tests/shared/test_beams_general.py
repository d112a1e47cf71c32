"""Beam modes of the general model against published constants, mpmath
and analytic identities (never against themselves)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from conftest import ROOT
from contactsep import beams

ENDS = beams.END_CONDITIONS


#: Blevins's published constants (his Table 8-1, and the clamped-pinned
#: table), as the project's shared notes quote them, copied unchanged
#: beside the tests so that every checkout runs the check.
PUBLISHED = ROOT / "tests" / "data" / "beam-constants.md"


def published_table():
    """k_jL columns of the published constants, by end condition."""
    path = PUBLISHED
    table = {"clamped-free": [], "clamped-clamped": [], "clamped-pinned": []}
    for line in path.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not cells or not cells[0].isdigit():
            continue
        if len(cells) == 5:
            if cells[1]:
                table["clamped-free"].append(float(cells[1]))
            if cells[3]:
                table["clamped-clamped"].append(float(cells[3]))
        elif len(cells) == 3:
            table["clamped-pinned"].append(float(cells[1]))
    return table


def test_eigenvalues_match_published_values():
    for end, values in published_table().items():
        assert len(values) >= 5
        ours = beams.eigenvalues(end, len(values))
        # published to 9 significant digits
        assert np.allclose(ours, values, rtol=6e-9, atol=0), end


def test_pinned_pinned_is_j_pi():
    assert np.array_equal(beams.eigenvalues("pinned-pinned", 50),
                          np.arange(1, 51) * np.pi)


def _mp_equation(end):
    return {
        "clamped-free": lambda x: mpmath.cos(x) + 1 / mpmath.cosh(x),
        "clamped-clamped": lambda x: mpmath.cos(x) - 1 / mpmath.cosh(x),
        "clamped-pinned": lambda x: (mpmath.sin(x) * mpmath.cosh(x)
                                     - mpmath.cos(x) * mpmath.sinh(x))
        / mpmath.cosh(x),
    }[end]


def _mp_mode(end, kl, xi):
    """Textbook mode function (cancels e^{kL}: 150 digits are ample)."""
    c, s, ch, sh = (mpmath.cos(kl), mpmath.sin(kl), mpmath.cosh(kl),
                    mpmath.sinh(kl))
    sigma = (sh - s) / (ch + c) if end == "clamped-free" else \
        (ch - c) / (sh - s)
    z = kl * xi
    return (mpmath.cosh(z) - mpmath.cos(z)
            - sigma * (mpmath.sinh(z) - mpmath.sin(z)))


@pytest.mark.parametrize("end", ENDS[:3])
@pytest.mark.parametrize("j", [1, 7, 20, 50])
def test_eigenvalue_and_mode_against_mpmath(end, j):
    ours = beams.eigenvalues(end, j)[-1]
    with mpmath.workdps(150):
        root = mpmath.findroot(_mp_equation(end), mpmath.mpf(ours))
        assert abs(ours - float(root)) <= 4 * np.spacing(ours)
        xi = [0.1, 0.5, 0.78, 0.98, 1.0]
        expected = [float(_mp_mode(end, root, mpmath.mpf(x))) for x in xi]
    got = beams.mode_shapes(end, j, xi)[-1]
    # a few ulps of the mode's unit size, for any j
    assert np.max(np.abs(got - expected)) < 5e-13


@pytest.mark.parametrize("end", ENDS)
def test_modes_are_orthonormal_to_n50(end):
    nodes, weights = np.polynomial.legendre.leggauss(400)
    xi = 0.5 * (nodes + 1.0)
    x = beams.mode_shapes(end, 50, xi)
    gram = (x * (0.5 * weights)) @ x.T
    assert np.max(np.abs(gram - np.eye(50))) < 1e-11


def test_cantilever_tip_values_are_plus_minus_two():
    tip = beams.mode_shapes("clamped-free", 50, [1.0])[:, 0]
    expected = 2.0 * (-1.0) ** np.arange(50)
    assert np.max(np.abs(tip - expected)) < 1e-12


def test_cantilever_tip_flexibility_sum_is_one_twelfth():
    # sum 1/(k_jL)^4 = 1/12; the tail past j = 4000 is below 1e-14
    kl = beams.eigenvalues("clamped-free", 4000)
    assert abs(np.sum(1.0 / kl[::-1]**4) - 1.0 / 12.0) < 1e-13


def test_clamped_clamped_midspan_flexibility_is_1_192():
    n = 4000
    kl = beams.eigenvalues("clamped-clamped", n)
    mid = beams.mode_shapes("clamped-clamped", n, [0.5])[:, 0]
    assert abs(np.sum((mid**2 / kl**4)[::-1]) - 1.0 / 192.0) < 1e-13
    assert np.max(np.abs(mid[1::2])) < 1e-12   # antisymmetric modes


@pytest.mark.parametrize("end", ENDS)
def test_static_flexibility_is_the_mode_sum(end):
    # G(xi) = sum_j X_j(xi)^2 / (k_jL)^4: the closed forms (strength of
    # materials) against the modal expansion of the influence function
    xi = np.linspace(0.05, 1.0, 10)
    n = 3000
    kl = beams.eigenvalues(end, n)
    x = beams.mode_shapes(end, n, xi)
    series = np.sum((x**2 / kl[:, None]**4)[::-1], axis=0)
    # the series' tail past n: X_j^2 <= 4, k_jL >= (j - 1) pi
    tail = 4.0 / (3.0 * np.pi**4 * (n - 1)**3)
    assert np.allclose(series, beams.static_flexibility(end, xi),
                       rtol=1e-13, atol=tail)


def test_static_flexibility_textbook_values():
    # L^3/(3EI), L^3/(192EI), 7L^3/(768EI), L^3/(48EI)
    assert beams.static_flexibility("clamped-free", 1.0) == 1.0 / 3.0
    assert np.isclose(beams.static_flexibility("clamped-clamped", 0.5),
                      1 / 192)
    assert np.isclose(beams.static_flexibility("clamped-pinned", 0.5),
                      7 / 768)
    assert np.isclose(beams.static_flexibility("pinned-pinned", 0.5), 1 / 48)


def test_unknown_end_condition_is_refused():
    with pytest.raises(ValueError, match="end condition must be one of"):
        beams.eigenvalues("free-free", 3)
