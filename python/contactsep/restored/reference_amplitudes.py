"""The upper contact's initial amplitudes for the NumPy reference
(contactsep.restored.reference): the deck's mode functions and the
integral A-(7) of the static tip-load curve against them, in closed form
(the boundary-term formula derived in contactsep.restored.reference's
docstring), by Gauss-Legendre quadrature, or for exact modes."""

from __future__ import annotations

import math

import numpy as np

from contactsep.restored.dataset import DataSet

#: ``amplitudes=`` choices of :func:`reference.run` and
#: :func:`initial_amplitudes`.
AMPLITUDE_METHODS = ("closed-form", "quadrature", "exact-mode")

#: Gauss-Legendre points per panel of the composite quadrature.
_GAUSS_ORDER = 20


def _choice(name: str, value: str, allowed: tuple[str, ...]) -> str:
    if value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value


# ---------------------------------------------------------------------------
# Mode function from the deck's constants, and the initial amplitudes
# ---------------------------------------------------------------------------

def mode_values(v, alpha, xi) -> np.ndarray:
    """The deck's mode functions X_j(xi L) = cosh v xi - cos v xi
    - alpha (sinh v xi - sin v xi), shape (len(v), len(xi)).

    ``v`` = k_jL and ``alpha`` as read from the deck (either support: the
    form is the same, Appendix C eq. 4).  Evaluated as
    e^{-v xi} + (1 - alpha) sinh v xi - cos v xi + alpha sin v xi, which
    has no cancellation beyond what the deck's alpha itself implies.
    """
    v = np.atleast_1d(np.asarray(v, dtype=np.float64))[:, None]
    alpha = np.atleast_1d(np.asarray(alpha, dtype=np.float64))[:, None]
    xi = np.atleast_1d(np.asarray(xi, dtype=np.float64))[None, :]
    z = v * xi
    return np.exp(-z) + (1.0 - alpha) * np.sinh(z) - np.cos(z) + alpha * np.sin(z)


def _amplitudes_closed_form(ystat: float, v: np.ndarray, alpha: np.ndarray
                            ) -> np.ndarray:
    """Exact integral A-(7) of the deck's mode function
    (contactsep.restored.reference's docstring derives it)."""
    beta = 1.0 - alpha
    q, sh, ch = np.exp(-v), np.sinh(v), np.cosh(v)
    c, s = np.cos(v), np.sin(v)
    x0 = q + beta * sh - c + alpha * s          # X(1)
    x2 = q + beta * sh + c - alpha * s          # X''(1)/v^2
    x3 = -q + beta * ch - s - alpha * c         # X'''(1)/v^3
    return ystat * (3.0 * x0 / v**4 - 1.5 * x2 / v**2 + x3 / v)


def _amplitudes_quadrature(ystat: float, v: np.ndarray, alpha: np.ndarray,
                           panels: int | None = None) -> np.ndarray:
    """A-(7) by composite Gauss-Legendre quadrature over xi in [0, 1].

    ``panels`` equal panels of ``_GAUSS_ORDER`` points; by default 2 k_NL
    panels (at least 2), each spanning half a radian of the fastest cos/sin.
    The rule is exact to far below rounding with a tenth of that; the extra
    nodes average the rounding of the integrand (whose integral is smaller
    than the integral of its modulus by the factor kappa_j ~ (k_jL)^4/18):
    measured |quadrature/closed-form - 1| <= eps kappa_j for modes 1-10,
    i.e. <= 2e-13 for modes 1-6 and <= 4e-12 for modes 7-10.  (numpy's
    leggauss weights carry relative errors up to 7e-14, which these
    averages also absorb.)
    """
    if v.size == 0:
        return np.zeros(0)
    if panels is None:
        panels = max(2, int(math.ceil(2.0 * float(np.max(v)))))
    x, w = np.polynomial.legendre.leggauss(_GAUSS_ORDER)
    edges = np.linspace(0.0, 1.0, panels + 1)
    half = 0.5 * np.diff(edges)
    xi = (0.5 * (edges[:-1] + edges[1:])[:, None] + half[:, None] * x).ravel()
    wt = (half[:, None] * w).ravel()
    f = 0.5 * ystat * (3.0 * xi**2 - xi**3)
    return (mode_values(v, alpha, xi) * (f * wt)).sum(axis=1)


def initial_amplitudes(ds: DataSet, method: str = "closed-form", *,
                       panels: int | None = None) -> np.ndarray:
    """A_j of the upper contact, A-(7), in inches (the listing's APE).

    ``method``:
      ``"closed-form"`` (default)  the exact integral of f times the deck's
          mode function (V, ALPHA), by the boundary-term formula of the
          module docstring; the listing's D1..D8 integral, without its
          cancellation.
      ``"quadrature"``  the same integral by composite Gauss-Legendre
          (``panels`` panels, default automatic).
      ``"exact-mode"``  3 y_s C_j / V_j^4: the integral for a mode that meets
          the free-end conditions exactly, from the deck's V and C
          (C = X_j(L)); ALPHA is not used.
    """
    _choice("amplitudes", method, AMPLITUDE_METHODS)
    v = np.asarray(ds.v, dtype=np.float64)
    alpha = np.asarray(ds.alpha, dtype=np.float64)
    if method == "closed-form":
        return _amplitudes_closed_form(ds.ystat, v, alpha)
    if method == "quadrature":
        return _amplitudes_quadrature(ds.ystat, v, alpha, panels)
    return 3.0 * ds.ystat * np.asarray(ds.c, dtype=np.float64) / v**4
