"""Bernoulli-Euler characteristic beam functions for any number of modes.

The thesis uses two supports (Chapter III; Appendices A and C):

* ``"cantilever"`` (the contacts): X(0) = X'(0) = 0, X''(L) = X'''(L) = 0,
  frequency equation cos kL cosh kL = -1 (Appendix A, eq. 5);
* ``"clamped-clamped"`` (the separator): X(0) = X'(0) = X(L) = X'(L) = 0,
  frequency equation cos kL cosh kL = +1 (Appendix C, eq. 3).

Both use the mode function (Appendix C, eq. 4)

    X_j(x) = cosh k_j x - cos k_j x - alpha_j (sinh k_j x - sin k_j x),

normalised so that the integral of X_j^2 over [0, L] is L (Appendix A,
orthogonality condition).  The listing calls k_jL ``V``, alpha_j ``ALPHA``
and reads them, with X_j(L) or X_j(L/2), from the deck.

The textbook form subtracts numbers of size e^{kL}/2 to get a result of
size 1 and has no correct digit left by j ~ 10 in double precision.  Here
every hyperbolic term is rewritten with e^{-kL} factored out, using
g_j = (1 - alpha_j) e^{k_jL}, which has a cancellation-free closed form.
"""

from __future__ import annotations

import numpy as np

from contactsep.model import modes

#: The two supports of the thesis.
SUPPORTS = ("cantilever", "clamped-clamped")


def _check(support: str, n: int) -> None:
    if support not in SUPPORTS:
        raise ValueError(f"support must be one of {SUPPORTS}, got {support!r}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {n!r}")


_END = {"cantilever": "clamped-free", "clamped-clamped": "clamped-clamped"}


def eigenvalues(support: str, n: int) -> np.ndarray:
    """k_jL, j = 1..n: the roots of cos kL cosh kL = -1 (cantilever) or
    +1 (clamped-clamped), to the nearest double or its neighbour
    (bisection of the bounded form, contactsep.model.modes)."""
    _check(support, n)
    return modes.eigenvalues(_END[support], n)


def _alpha_parts(support: str, kl: np.ndarray):
    """alpha_j and g_j = (1 - alpha_j) e^{k_jL}, both without cancellation."""
    return modes._sigma_parts(_END[support], kl)


def alphas(support: str, n: int) -> np.ndarray:
    """alpha_j (sigma_j), j = 1..n: (sinh - sin)/(cosh + cos) of k_jL for
    the cantilever, (cosh - cos)/(sinh - sin) for clamped-clamped,
    computed without cancellation (alpha_j rounds to 1.0 from j ~ 12)."""
    _check(support, n)
    return modes.sigmas(_END[support], n)


def mode_shapes(support: str, n: int, xi, derivative: int = 0) -> np.ndarray:
    """X_j(xi L) for j = 1..n, as an array of shape (n, len(xi)).

    ``xi`` = x/L in [0, 1].  ``derivative`` m = 0..3 gives d^m X_j / d xi^m
    (divide by L^m for d/dx).  Accurate to a few ulps of their unit size
    for any j (the hyperbolic terms are evaluated with e^{-kL} factored
    out; contactsep.model.modes).
    """
    _check(support, n)
    return modes.mode_shapes(_END[support], n, xi, derivative)


def tip_values(n: int) -> np.ndarray:
    """Cantilever X_j(L), j = 1..n (the listing's C and C3); 2(-1)^(j+1)."""
    return mode_shapes("cantilever", n, [1.0])[:, 0]


def midspan_values(n: int) -> np.ndarray:
    """Clamped-clamped X_j(L/2), j = 1..n (the listing's C2).

    Even modes are antisymmetric about mid-span, so their value is exactly
    0.0 rather than a rounding residue.
    """
    values = mode_shapes("clamped-clamped", n, [0.5])[:, 0]
    values[1::2] = 0.0
    return values
