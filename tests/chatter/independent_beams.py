"""The beams of the independent Hertz simulator (independent_hertz.py;
issue 26), written from the equations without importing contactsep:
each end condition's frequency equation solved by Brent's method, the
mode shapes without cancellation and normalised to int X^2 = L by
quadrature, and a point load's static deflection from the beam equation
(two cubics) projected on the modes."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

#: Gravity (in/s^2): the thesis's listing value (Appendix B).
GRAVITY = 386.4


# --------------------------------------------------------------- modes

def _frequency_function(end, x):
    if end == "clamped-free":
        return math.cos(x) + 1.0 / math.cosh(x)
    if end == "clamped-clamped":
        return math.cos(x) - 1.0 / math.cosh(x)
    if end == "clamped-pinned":
        return math.sin(x) - math.cos(x) * math.tanh(x)
    raise ValueError(end)


def wavenumbers(end: str, n: int) -> np.ndarray:
    """k_j L of the first n modes of ``end`` (own root finder)."""
    out = []
    for j in range(1, n + 1):
        if end == "pinned-pinned":
            out.append(j * math.pi)
            continue
        if end == "clamped-free":
            lo, hi = (j - 1) * math.pi + 1e-9, j * math.pi
        elif end == "clamped-clamped":
            lo, hi = j * math.pi, (j + 1) * math.pi
        else:
            lo, hi = j * math.pi + 1e-9, j * math.pi + math.pi / 2
        out.append(brentq(lambda x: _frequency_function(end, x), lo, hi,
                          xtol=1e-15, rtol=4 * np.finfo(float).eps,
                          maxiter=500))
    return np.array(out)


def _raw_shape(end, kl, xi):
    """Unnormalised X(xi) for one wavenumber kl, xi in [0, 1] (array)."""
    xi = np.asarray(xi, dtype=float)
    if end == "pinned-pinned":
        return np.sin(kl * xi)
    kx = kl * xi
    if end == "clamped-free":
        c_a, s_b = math.cos(kl), math.sin(kl)
    else:   # clamped-clamped, clamped-pinned
        c_a, s_b = -math.cos(kl), -math.sin(kl)
    # sigma = (cosh kL + c_a) / (sinh kL + s_b), and
    # cosh kx - sigma sinh kx = (sinh k(L-x) + s_b cosh kx - c_a sinh kx)
    #                           / (sinh kL + s_b), both scaled by 2 e^-kL
    em = math.exp(-kl)
    den = 1.0 - em * em + 2.0 * s_b * em
    sigma = (1.0 + em * em + 2.0 * c_a * em) / den
    num = (np.exp(-kx) - np.exp(-(2.0 * kl - kx))
           + s_b * (np.exp(kx - kl) + np.exp(-(kx + kl)))
           - c_a * (np.exp(kx - kl) - np.exp(-(kx + kl))))
    return num / den - np.cos(kx) + sigma * np.sin(kx)


@functools.lru_cache(maxsize=None)
def _gauss(n):
    """n-point Gauss-Legendre nodes and weights on [0, 1], read-only:
    made once for each n (an eigenvalue problem of order n >= 200, a
    fifth of a random design's reference run when made for every
    beam)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    x.setflags(write=False)
    w.setflags(write=False)
    return x, w


@dataclass(frozen=True)
class Beam:
    """A member: its modes' frequencies, mass, and shape functions."""

    end: str
    length: float
    mass: float
    p: np.ndarray
    kl: np.ndarray
    norm: np.ndarray       # divide the raw shapes by these

    def shapes(self, x) -> np.ndarray:
        """X_j(x) (n, len(x)) with int X^2 = L."""
        xi = np.atleast_1d(np.asarray(x, dtype=float)) / self.length
        return np.array([_raw_shape(self.end, k, xi) / c
                         for k, c in zip(self.kl, self.norm)])


def beam(end, length, width, thick, gamma, modulus, n) -> Beam:
    """A uniform Bernoulli-Euler beam's first n modes."""
    area, inertia = width * thick, width * thick**3 / 12.0
    mass = gamma * area * length / GRAVITY
    a = math.sqrt(modulus * inertia * GRAVITY / (area * gamma))
    kl = wavenumbers(end, n)
    xi, w = _gauss(max(200, int(8 * kl[-1])))
    norm = np.array([math.sqrt(np.sum(w * _raw_shape(end, k, xi)**2))
                     for k in kl])
    return Beam(end=end, length=length, mass=mass, p=kl**2 * a / length**2,
                kl=kl, norm=norm)


# ------------------------------------------------------------ release

def _clamped(end_at_zero: bool, end: str):
    """Boundary rows for y = c0 + c1 s + c2 s^2 + c3 s^3 at one end:
    which derivatives (0..3) vanish there."""
    left, right = end.split("-")
    kind = left if end_at_zero else right
    return {"clamped": (0, 1), "pinned": (0, 2), "free": (2, 3)}[kind]


def _cubic_row(s, derivative):
    if derivative == 0:
        return [1.0, s, s * s, s**3]
    if derivative == 1:
        return [0.0, 1.0, 2 * s, 3 * s * s]
    if derivative == 2:
        return [0.0, 0.0, 2.0, 6 * s]
    return [0.0, 0.0, 0.0, 6.0]


def static_shape(end, length, a):
    """The deflection y(x) (callable, unit EI and unit force) of the beam
    under a point load at x = a: two cubics, the ends' conditions, y, y'
    and y'' continuous at a, EI (y'''(a+) - y'''(a-)) = F (an upward
    load deflects the beam up: y(a) > 0)."""
    rows, rhs = [], []
    zero = [0.0] * 4
    for d in _clamped(True, end):
        rows.append(_cubic_row(0.0, d) + zero)
        rhs.append(0.0)
    for d in _clamped(False, end):
        rows.append(zero + _cubic_row(length, d))
        rhs.append(0.0)
    for d in (0, 1, 2):
        rows.append(_cubic_row(a, d) + [-v for v in _cubic_row(a, d)])
        rhs.append(0.0)
    rows.append(_cubic_row(a, 3) + [-v for v in _cubic_row(a, 3)])
    rhs.append(-1.0)        # left - right
    c = np.linalg.solve(np.array(rows), np.array(rhs))

    def y(x):
        x = np.asarray(x, dtype=float)
        left = c[0] + c[1] * x + c[2] * x**2 + c[3] * x**3
        right = c[4] + c[5] * x + c[6] * x**2 + c[7] * x**3
        return np.where(x <= a, left, right)
    return y


def release_modes(b: Beam, a: float, ys: float) -> np.ndarray:
    """q_j of the static shape with deflection ys at x = a (projection)."""
    y = static_shape(b.end, b.length, a)
    scale = ys / float(y(a))
    q = np.zeros(b.p.size)
    xi, w = _gauss(max(200, int(8 * b.kl[-1])))
    # integrate the two smooth pieces separately
    for lo, hi in ((0.0, a), (a, b.length)):
        if hi <= lo:
            continue
        x = lo + (hi - lo) * xi
        q += (hi - lo) * (b.shapes(x) * (scale * y(x))) @ w
    return q / b.length
