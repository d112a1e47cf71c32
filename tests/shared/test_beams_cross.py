"""The static cross influence G(xi, eta) and the residual cross
flexibility of the modes past N (contactsep.beams.static_influence,
residual_cross_flexibility): the static correction's off-diagonal term
when the upper and lower contacts touch the separator at different
points (issue 28, item 4).

Independent paths: the beam equation solved here (two cubics joined at
the load, 8 conditions) and read at another point; the modal series
summed to many modes; the transfer-matrix solution (contactsep.beams.
timoshenko_static) of the same Bernoulli-Euler beam; Maxwell's reciprocity of
two separate load cases of a Timoshenko beam on elastic supports."""

import numpy as np
import pytest

from contactsep import beams
from contactsep.beams import member, timoshenko, timoshenko_static

ENDS = ("clamped-free", "clamped-clamped", "clamped-pinned",
        "pinned-pinned")
PAIRS = ((0.3, 0.7), (0.5, 0.2), (0.4, 0.4), (0.9, 0.15), (0.05, 0.95))


def _rows(x, order):
    powers = [[1, x, x**2, x**3], [0, 1, 2 * x, 3 * x**2],
              [0, 0, 2, 6 * x], [0, 0, 0, 6]]
    return np.array(powers[order], dtype=float)


def deflection(end, load, at):
    """y(at) of EI y'''' = delta(x - load) on [0, 1], EI = 1."""
    left, right = end.split("-")
    conditions = {"clamped": (0, 1), "pinned": (0, 2), "free": (2, 3)}
    rows = [np.concatenate([_rows(0.0, k), np.zeros(4)])
            for k in conditions[left]]
    rows += [np.concatenate([np.zeros(4), _rows(1.0, k)])
             for k in conditions[right]]
    rows += [np.concatenate([_rows(load, k), -_rows(load, k)])
             for k in (0, 1, 2, 3)]
    rhs = np.zeros(8)
    rhs[-1] = -1.0
    c = np.linalg.solve(np.array(rows), rhs)
    return float(_rows(at, 0) @ (c[:4] if at <= load else c[4:]))


@pytest.mark.parametrize("end", ENDS)
@pytest.mark.parametrize("xi,eta", PAIRS)
def test_influence_is_the_point_load_deflection(end, xi, eta):
    assert beams.static_influence(end, xi, eta) == pytest.approx(
        deflection(end, eta, xi), rel=1e-12, abs=1e-16)


@pytest.mark.parametrize("end", ENDS)
def test_influence_is_symmetric_and_the_flexibility_on_the_diagonal(end):
    for xi, eta in PAIRS:
        assert beams.static_influence(end, xi, eta) == pytest.approx(
            beams.static_influence(end, eta, xi), rel=1e-13)
        assert beams.static_influence(end, xi, xi) == pytest.approx(
            beams.static_flexibility(end, xi), rel=1e-13)


@pytest.mark.parametrize("end", ENDS)
@pytest.mark.parametrize("xi,eta", PAIRS)
def test_residual_cross_is_the_tail_of_the_modal_series(end, xi, eta):
    # the tail past n = 8 from the modes 9..4000 (the rest ~ 4000^-3)
    n, far = 8, 4000
    shapes = beams.mode_shapes(end, far, [xi, eta])
    kl = beams.eigenvalues(end, far)
    tail = float(np.sum((shapes[:, 0] * shapes[:, 1] / kl**4)[n:]))
    assert beams.residual_cross_flexibility(end, n, xi, eta) == \
        pytest.approx(tail, abs=2e-11)
    if xi == eta:
        assert beams.residual_cross_flexibility(end, n, xi, eta) == \
            pytest.approx(float(beams.residual_flexibility(end, n, xi)[0]),
                          rel=1e-12)


@pytest.mark.parametrize("end", ENDS)
@pytest.mark.parametrize("xi,eta", PAIRS)
def test_transfer_matrices_agree_with_the_closed_form(end, xi, eta):
    got = timoshenko_static.static_influence(timoshenko.Beam(end), xi,
                                             eta)
    assert got == pytest.approx(beams.static_influence(end, xi, eta),
                                rel=1e-9, abs=1e-15)


def test_maxwell_reciprocity_of_a_timoshenko_beam_on_springs():
    beam = timoshenko.Beam("clamped-clamped", s2=0.01, kr=30.0, kt=5e3)
    for xi, eta in PAIRS:
        assert member.static_influence(beam, xi, eta) == pytest.approx(
            member.static_influence(beam, eta, xi), rel=1e-9)
        if xi == eta:
            assert member.static_influence(beam, xi, xi) == pytest.approx(
                float(member.static_flexibility(beam, xi)), rel=1e-9)
