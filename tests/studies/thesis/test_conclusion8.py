"""Conclusion 8 (issue 28 item 6): the first mode's share and the swings
of the lower contact's response against its contact point.  The share
and the node are checked against the cantilever's own formulas written
here (eigenvalues from the frequency equation by bisection, mode shapes
from their closed form), the maxima count against a naive count over
every sample, and the study's N against twice its N."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

import contactsep
from contactsep.cli import main
from contactsep.studies.thesis import mode_share as c8
#: at x/L = 0.783.
PUBLISHED_NODE = 0.783


def cantilever_kl(n: int) -> np.ndarray:
    """Roots of cos(kL) cosh(kL) = -1, i.e. cos k + 1/cosh k = 0, by
    mpmath's root finder from the bracket's middle."""
    with mpmath.workdps(40):
        return np.array([float(mpmath.findroot(
            lambda k: mpmath.cos(k) + 1 / mpmath.cosh(k),
            (j - 0.5) * mpmath.pi)) for j in range(1, n + 1)])


def cantilever_mode(kl: float, xi: float) -> float:
    """X(xi) normalised to int X^2 = L (sigma from the tip conditions),
    in 40-digit arithmetic (the hyperbolic terms cancel)."""
    with mpmath.workdps(40):
        k = mpmath.mpf(kl)
        sigma = (mpmath.sinh(k) - mpmath.sin(k)) / (mpmath.cosh(k)
                                                    + mpmath.cos(k))
        x = k * mpmath.mpf(xi)
        return float(mpmath.cosh(x) - mpmath.cos(x)
                     - sigma * (mpmath.sinh(x) - mpmath.sin(x)))


def test_the_node_is_the_published_one():
    node = c8.second_mode_node()
    assert abs(node - PUBLISHED_NODE) < 5e-4
    kl = cantilever_kl(2)[1]
    assert abs(cantilever_mode(kl, node)) < 1e-9


def test_the_share_is_the_formulas():
    """c3_j ~ X_j(x3)^2 / p_j (eq. 23) with p_j ~ (k_jL)^2."""
    study = c8.conclusion8(n_modes=16)
    kl = cantilever_kl(16)
    for r, share in zip(study["r"][::7], study["first_mode_share"][::7]):
        c = np.array([cantilever_mode(k, r)**2 / k**2 for k in kl])
        assert share == pytest.approx(c[0]**2 / np.sum(c**2), rel=1e-9)


def naive_count(y: np.ndarray, prominence: float) -> int:
    """Every sample's prominence from its definition, no shortcut."""
    count = 0
    for k in range(1, y.size - 1):
        if not (y[k] > y[k - 1] and y[k] >= y[k + 1]):
            continue
        bases = []
        for side in (y[:k + 1][::-1], y[k:]):
            base = y[k]
            for value in side:
                if value > y[k]:
                    break
                base = min(base, value)
            bases.append(base)
        count += y[k] - max(bases) >= prominence
    return count


@pytest.mark.parametrize("seed", range(5))
def test_the_maxima_count_equals_a_naive_count(seed):
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, 3001)
    y = sum(rng.normal() / (j * j) * np.sin(2 * np.pi * j * t
                                             + rng.uniform(0, 6))
            for j in range(1, 40))
    for fraction in (0.0, 0.05, 0.2, 0.5):
        threshold = fraction * np.abs(y).max()
        assert c8.count_maxima(y, threshold) == naive_count(y, threshold)


def test_one_swing_where_the_first_mode_holds_the_response():
    study = c8.conclusion8()
    one_dof = study["first_mode_share"] > 0.999
    assert one_dof.any() and np.all(study["n_maxima"][one_dof] == 1)
    node = c8.second_mode_node()
    at_node = np.argmin(np.abs(study["r"] - node))
    assert study["first_mode_share"][at_node] > 0.998
    assert study["n_maxima"][at_node] == 1
    # the tip swings twice in the first period, mid-length more
    assert study["n_maxima"][-1] == 2 and study["n_maxima"][0] > 2


def test_the_command_writes_the_study(tmp_path, capsys):
    path = tmp_path / "c8.csv"
    assert main(["study", "conclusion8", "--csv", str(path)]) == 0
    frame = contactsep.read(path)
    assert frame.columns.tolist() == ["r", "x3_in", "first_mode_share",
                                      "n_maxima", "y3_max_in"]
    assert all(line.startswith("#") for line in path.read_text()
               .splitlines()[:len(frame.attrs["comments"])])
    assert main(["study", "conclusion8", "--x3", "5"]) == 2
    assert "x3" in capsys.readouterr().err


@pytest.mark.slow
def test_the_study_is_converged_in_n():
    """The share to 1e-4; the swings' count is a step function of x3
    whose steps move by at most one grid point (0.01 L3) from N to 2N
    (docs/studies.md, Conclusion 8: at x3/L3 = 0.67, 1 at N = 32 and 2
    at N = 64)."""
    coarse = c8.conclusion8()
    fine = c8.conclusion8(n_modes=2 * c8.MODES)
    np.testing.assert_allclose(coarse["first_mode_share"],
                               fine["first_mode_share"], rtol=1e-4)
    counts = coarse["n_maxima"], fine["n_maxima"]
    for k in np.flatnonzero(counts[0] != counts[1]):
        neighbours = [counts[i][j] for i in (0, 1)
                      for j in (k - 1, k + 1) if 0 <= j < len(counts[i])]
        assert {counts[0][k], counts[1][k]} <= set(neighbours), k
    assert np.sum(counts[0] != counts[1]) <= 2
