"""Normal modes of a uniform Bernoulli-Euler beam for the four orthodox
end conditions, any number of modes: shared by every layer (the restored
core's mode cards, the general model, the contact dynamics).

End conditions (x = 0 is always the first-named end):

* ``"clamped-free"`` (cantilever, the contacts; also called
  ``"cantilever"``): cos kL cosh kL = -1 (Appendix A, eq. 5);
* ``"clamped-clamped"`` (the separator): cos kL cosh kL = +1 (Appendix C,
  eq. 3);
* ``"clamped-pinned"`` (propped cantilever): tan kL = tanh kL;
* ``"pinned-pinned"``: sin kL = 0, k_jL = j pi, X_j = sqrt(2) sin(j pi x/L).

The first three share the mode function (Appendix C, eq. 4)
X_j(x) = cosh k_j x - cos k_j x - sigma_j (sinh k_j x - sin k_j x), with
sigma_j = (sinh - sin)/(cosh + cos) of k_jL for the cantilever and
(cosh - cos)/(sinh - sin) for the other two.  Every mode is normalised so
that the integral of X_j^2 over [0, L] is L (Appendix A).  The listing
calls k_jL ``V``, sigma_j ``ALPHA`` and reads them, with X_j(L) or
X_j(L/2), from the deck.

The textbook form subtracts numbers of size e^{kL}/2 to get a result of
size 1 and has no correct digit left by j ~ 10 in double precision.  Here
every hyperbolic term is evaluated with e^{-kL} factored out through
g_j = (1 - sigma_j) e^{k_jL}, which has a cancellation-free closed form,
so that no term is larger than a few units and the modes are accurate to
a few ulps for any j.
"""

from __future__ import annotations

import numpy as np

#: The end conditions, in the order of their integer codes 1..4.
END_CONDITIONS = ("clamped-free", "clamped-clamped", "clamped-pinned",
                  "pinned-pinned")


#: Other names of an end condition.
ALIASES = {"cantilever": "clamped-free"}

#: The thesis's two supports (the restored core's members).
SUPPORTS = ("cantilever", "clamped-clamped")


def end_code(end: str) -> int:
    """Integer code 1..4 of an end condition name."""
    try:
        return END_CONDITIONS.index(ALIASES.get(end, end)) + 1
    except ValueError:
        raise ValueError(f"end condition must be one of {END_CONDITIONS}, "
                         f"got {end!r}") from None


def _canonical(end: str) -> str:
    return END_CONDITIONS[end_code(end) - 1]


def _check(end: str, n: int) -> str:
    end = _canonical(end)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {n!r}")
    return end


def _sech(x):
    q = np.exp(-x)
    return 2.0 * q / (1.0 + q * q)


def _frequency_function(end: str, x):
    """The frequency equation divided by cosh x: bounded, same roots."""
    if end == "clamped-free":
        return np.cos(x) + _sech(x)
    if end == "clamped-clamped":
        return np.cos(x) - _sech(x)
    # tan x = tanh x  <=>  cos x tanh x - sin x = 0
    q = np.exp(-2.0 * x)
    return np.cos(x) * (1.0 - q) / (1.0 + q) - np.sin(x)


def _brackets(end: str, j):
    """Intervals [lo, hi] holding exactly root j of the frequency equation."""
    if end == "clamped-free":
        return (j - 1.0) * np.pi, j * np.pi
    if end == "clamped-clamped":
        return j * np.pi, (j + 1.0) * np.pi
    # clamped-pinned: f(j pi) = (-1)^j tanh(j pi), f(j pi + pi/2) = -(-1)^j
    return j * np.pi, (j + 0.5) * np.pi


def eigenvalues(end: str, n: int) -> np.ndarray:
    """k_jL, j = 1..n, to the nearest double or its neighbour.

    Bisection of the bounded form of the frequency equation until the
    bracket ends are adjacent doubles; pinned-pinned is j pi exactly.
    """
    end = _check(end, n)
    j = np.arange(1, n + 1, dtype=np.float64)
    if end == "pinned-pinned":
        return j * np.pi
    lo, hi = _brackets(end, j)
    lo_sign = np.sign(_frequency_function(end, lo))
    while True:
        mid = 0.5 * (lo + hi)
        if np.all((mid == lo) | (mid == hi)):
            break
        same = np.sign(_frequency_function(end, mid)) == lo_sign
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    f_lo = np.abs(_frequency_function(end, lo))
    f_hi = np.abs(_frequency_function(end, hi))
    return np.where(f_lo <= f_hi, lo, hi)


def _sigma_parts(end: str, kl):
    """sigma_j and g_j = (1 - sigma_j) e^{k_jL}, without cancellation."""
    q = np.exp(-kl)
    c, s = np.cos(kl), np.sin(kl)
    if end == "clamped-free":
        den = 1.0 + q * q + 2.0 * q * c
        sigma = (1.0 - q * q - 2.0 * q * s) / den
        g = 2.0 * (q + c + s) / den
    else:
        den = 1.0 - q * q - 2.0 * q * s
        sigma = (1.0 + q * q - 2.0 * q * c) / den
        g = 2.0 * (c - s - q) / den
    return sigma, g


def sigmas(end: str, n: int) -> np.ndarray:
    """sigma_j (the listing's ALPHA), j = 1..n; 0 for pinned-pinned."""
    end = _check(end, n)
    kl = eigenvalues(end, n)
    if end == "pinned-pinned":
        return np.zeros(n)
    return _sigma_parts(end, kl)[0]


def mode_shapes(end: str, n: int, xi, derivative: int = 0) -> np.ndarray:
    """X_j(xi L), j = 1..n, shape (n, len(xi)); ``derivative`` m = 0..3
    gives d^m X_j/d xi^m (divide by L^m for d/dx)."""
    end = _check(end, n)
    if derivative not in (0, 1, 2, 3):
        raise ValueError(
            f"derivative must be 0, 1, 2 or 3, got {derivative!r}")
    xi = np.atleast_1d(np.asarray(xi, dtype=np.float64))
    if xi.ndim != 1:
        raise ValueError("xi must be a scalar or a 1-D array")
    if np.any(~np.isfinite(xi)) or np.any((xi < 0.0) | (xi > 1.0)):
        raise ValueError("xi must lie in [0, 1]")
    kl = eigenvalues(end, n)[:, None]
    z = kl * xi[None, :]
    if end == "pinned-pinned":
        # d^m/dxi^m sin z = kl^m sin(z + m pi/2)
        phase = [np.sin, np.cos, lambda a: -np.sin(a),
                 lambda a: -np.cos(a)][derivative]
        return np.sqrt(2.0) * phase(z) * kl**derivative
    sigma, g = _sigma_parts(end, kl)
    grow = 0.5 * g * np.exp(z - kl)
    decay = 0.5 * (1.0 + sigma) * np.exp(-z)
    cos, sin = np.cos(z), np.sin(z)
    if derivative == 0:
        shape = grow + decay - cos + sigma * sin
    elif derivative == 1:
        shape = grow - decay + sin + sigma * cos
    elif derivative == 2:
        shape = grow + decay + cos - sigma * sin
    else:
        shape = grow - decay - sin - sigma * cos
    return shape * kl**derivative


def static_flexibility(end: str, xi) -> np.ndarray:
    """G(xi) = y(a) EI / (F L^3): deflection under a point load F at
    a = xi L, exact (strength of materials, not a truncated mode sum).

    Equal to sum over all j of X_j(xi)^2 / (k_jL)^4 (the modal expansion
    of the static influence function), which the tests check.
    """
    end = _canonical(end)
    xi = np.asarray(xi, dtype=np.float64)
    b = 1.0 - xi
    if end == "clamped-free":
        return xi**3 / 3.0
    if end == "clamped-clamped":
        return xi**3 * b**3 / 3.0
    if end == "clamped-pinned":
        return xi**3 * b**2 * (3.0 + b) / 12.0
    return xi**2 * b**2 / 3.0


def _cantilever_influence(xi, eta):
    """y(xi) of a cantilever (clamped at 0) under a unit load at eta."""
    near, far = np.minimum(xi, eta), np.maximum(xi, eta)
    return near**2 * (3.0 * far - near) / 6.0


def static_influence(end: str, xi, eta) -> np.ndarray:
    """G(xi, eta) = y(xi) EI / (F L^3): deflection at x = xi L under a
    point load F at a = eta L, exact (strength of materials).

    Symmetric (Maxwell's reciprocity), equal to :func:`static_flexibility`
    on the diagonal, and to sum over all j of X_j(xi) X_j(eta) /
    (k_jL)^4 (the modal expansion), which the tests check.  The propped
    cantilever is the cantilever less its prop's reaction,
    R = eta^2 (3 - eta) / 2, at the pinned end.
    """
    end = _canonical(end)
    xi, eta = np.broadcast_arrays(np.asarray(xi, dtype=np.float64),
                                  np.asarray(eta, dtype=np.float64))
    near, far = np.minimum(xi, eta), np.maximum(xi, eta)
    if end == "clamped-free":
        return _cantilever_influence(xi, eta)
    if end == "clamped-clamped":
        # near side x <= a of the load, b = 1 - a: b^2 x^2 (3a - x(3a + b))/6
        b = 1.0 - far
        return b**2 * near**2 * (3.0 * far - near * (1.0 + 2.0 * far)) / 6.0
    if end == "clamped-pinned":
        reaction = eta**2 * (3.0 - eta) / 2.0
        return _cantilever_influence(xi, eta) - reaction * \
            _cantilever_influence(xi, 1.0)
    b = 1.0 - far
    return b * near * (1.0 - b**2 - near**2) / 6.0


def residual_cross_flexibility(end: str, n: int, xi, eta) -> float:
    """r_N(xi, eta) = G(xi, eta) - sum_{j<=n} X_j(xi) X_j(eta) / (k_jL)^4:
    the static cross flexibility between two points of the modes the
    n-mode model leaves out (units of :func:`static_flexibility`).  The
    static correction's off-diagonal term when two contacts touch one
    member at different points; on the diagonal it is
    :func:`residual_flexibility`.  Summed with compensation."""
    import math
    end = _check(end, n)
    shapes = mode_shapes(end, n, [float(xi), float(eta)])
    terms = shapes[:, 0] * shapes[:, 1] / eigenvalues(end, n)**4
    return math.fsum([float(static_influence(end, xi, eta))]
                     + list(-terms))


def residual_flexibility(end: str, n: int, xi) -> np.ndarray:
    """r_N(xi) = G(xi) - sum_{j<=n} X_j(xi)^2 / (k_jL)^4: the static point
    flexibility at a = xi L of the modes the n-mode model leaves out, in
    the same units as :func:`static_flexibility` (EI / L^3).

    Times L^3 / (EI) = 1 / (M p_j^2 / (k_jL)^4) it is the flexibility
    (in/lb) of a massless spring that, in series with the n-mode model at
    that point, gives its exact static deflection under a point load (the
    "static correction", docs/static-correction.md).  Falls like n^-3 (the terms
    X_j^2/(k_jL)^4 like j^-4); summed with compensation (math.fsum), so
    that its absolute error is a few ulps of G, not n of them.
    """
    import math
    end = _check(end, n)
    xi = np.atleast_1d(np.asarray(xi, dtype=np.float64))
    flex = np.atleast_1d(static_flexibility(end, xi))
    terms = mode_shapes(end, n, xi)**2 / eigenvalues(end, n)[:, None]**4
    out = np.array([math.fsum([float(flex[i])] + list(-terms[:, i]))
                    for i in range(xi.size)])
    # the n-mode sum of a positive series cannot exceed its limit; a
    # negative residue is round-off (a point where G is ~0: a support)
    return np.maximum(out, 0.0)


#: The thesis's name for sigma_j (the listing's ALPHA).
alphas = sigmas


def _alpha_parts(end: str, kl):
    """sigma_j and g_j of ``end`` (either naming), without cancellation."""
    return _sigma_parts(_canonical(end), kl)


def tip_values(n: int) -> np.ndarray:
    """Cantilever X_j(L), j = 1..n (the listing's C and C3); 2(-1)^(j+1)."""
    return mode_shapes("clamped-free", n, [1.0])[:, 0]


def midspan_values(n: int) -> np.ndarray:
    """Clamped-clamped X_j(L/2), j = 1..n (the listing's C2).

    Even modes are antisymmetric about mid-span, so their value is exactly
    0.0 rather than a rounding residue.
    """
    values = mode_shapes("clamped-clamped", n, [0.5])[:, 0]
    values[1::2] = 0.0
    return values
