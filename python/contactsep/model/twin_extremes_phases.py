"""Exact phases of the extremes search
(:mod:`~contactsep.model.twin_extremes`): the NumPy twin of
fortran/model/extremes.f90's root_phase and two_product and of
extremes_cells.f90's halve.

Phases are exact: p_j tau/2 is split into hi + lo (Dekker's product), the
root centre's sin and cos are sin(hi) + lo cos(hi) and cos(hi) - lo
sin(hi), and every finer level's half-angle comes from the coarser one by
the half-angle formulas, its quadrant read from the bits of
floor(p_j tau/pi) (computed with a three-double pi).  So the accuracy does
not fall with the window's length: rounding adds ~9 eps per level and
~n eps per sum, which the bounds carry as a margin.
"""

from __future__ import annotations

import numpy as np

_SPLIT = 134217729.0                    # 2^27 + 1 (Dekker)
_PI = (3.141592653589793, 1.2246467991473532e-16, -2.9947698097183397e-33)


def _two_product(x, y):
    """(hi, lo) with hi + lo = x y exactly (Dekker, no fused multiply-add)."""
    hi = x * y
    tx = _SPLIT * x
    xh = tx - (tx - x)
    xl = x - xh
    ty = _SPLIT * y
    yh = ty - (ty - y)
    yl = y - yh
    lo = ((xh * yh - hi) + xh * yl + xl * yh) + xl * yl
    return hi, lo


def half_angle_quadrants(p, tau):
    """floor(p tau / pi) as int64: bit l of it and the next are the
    quadrant of p tau / 2^(l+1) (exact while below 2^52)."""
    hi, lo = _two_product(p, tau)
    k = np.floor(hi / _PI[0])
    rest = hi
    for part in _PI:
        u, e = _two_product(k, part)
        rest = (rest - u) - e
    rest = rest + lo
    k = k + np.floor(rest / _PI[0])
    return np.where(np.isfinite(k), k, 0.0).astype(np.int64)


def root_phases(p, tau):
    """cos and sin of p tau / 2, from the exact product."""
    hi, lo = _two_product(p, 0.5 * tau)
    c, s = np.cos(hi), np.sin(hi)
    return c - lo * s, s + lo * c


def halve(cos_phi, sin_phi, quadrant):
    """cos and sin of phi/2 from those of phi; quadrant (0-3) of phi/2."""
    up = cos_phi >= 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        hc = np.where(up, np.sqrt(0.5 * (1.0 + cos_phi)), 0.0)
        hs = np.where(up, 0.0, np.sqrt(0.5 * (1.0 - cos_phi)))
        hs = np.where(up, np.abs(sin_phi) / (2.0 * hc), hs)
        hc = np.where(up, hc, np.abs(sin_phi) / (2.0 * hs))
    hc = np.where(np.isfinite(hc), hc, 0.0)
    hs = np.where(np.isfinite(hs), hs, 0.0)
    cos_sign = np.where((quadrant == 1) | (quadrant == 2), -1.0, 1.0)
    sin_sign = np.where(quadrant >= 2, -1.0, 1.0)
    return cos_sign * hc, sin_sign * hs
