"""An independent reference for the extremes of the lower contact's
response y3(t) = sum_j c_j sin(p_j t) over 0 <= t <= tau (issue 17).

It shares no code with the model (neither the compiled kernel nor its
NumPy twin) and no method with them: every stationary point of y3 is
found from the sign changes of y3' on a uniform grid whose step is at most
1/40 of the shortest period, refined by Brent's method on y3'
(scipy.optimize.brentq), and the two ends of the window are added; the
extremes are the largest and smallest y3 among these candidates.

The grid values come from complex phase factors: with t = (b B + k) dt,
exp(i p t) = exp(i p b B dt) exp(i p k dt), so for blocks of B points one
complex matrix product gives sum_j w_j exp(i p_j t) at every grid point
from N (n_blocks + B) phase factors; Im with w = c is y3, Re with w = c p
is y3'.  A local maximum's cell [t_k, t_k+1] (y3' from + to -) is refined
only where it can reach the best grid value: on a cell of width dt,
y3 <= max(y3(t_k), y3(t_k+1)) + M2 dt^2 / 8 with M2 = sum |c_j| p_j^2
(and likewise for minima).  Both ends of every refined cell are kept as
candidates as well, so a bracket whose signs rounding blurs is still
represented.

A pair of stationary points closer than one grid step (a maximum and a
minimum of y3 merging) is not seen; the grid of 1/40 period makes such a
pair's height difference below ~4e-3 of the fastest mode's amplitude, and
the test's random designs find none that matter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

#: Grid points per shortest period (the issue's 1/40).
POINTS_PER_PERIOD = 40
#: Most complex grid values held at once (memory: 16 bytes each, x2).
BLOCK_VALUES = 2_000_000


@dataclass(frozen=True)
class Candidates:
    """Stationary points of y3 and the window's ends, in time order."""

    #: Times (s), increasing.
    t: np.ndarray
    #: y3 at those times (in), summed directly with numpy.sin.
    y: np.ndarray
    #: Scale of the response, sum |c_j| (in).
    scale: float

    def extreme(self, sign: float, tie: float = 0.0):
        """(value, time) of the largest sign*y3; among values within
        ``tie`` (in) of it, the earliest."""
        s = sign * self.y
        best = s.max()
        k = int(np.flatnonzero(s >= best - tie)[0])
        return float(self.y[k]), float(self.t[k])


def y3(c, p, t) -> np.ndarray:
    """sum_j c_j sin(p_j t) at times t, directly, in extended precision
    (numpy.longdouble, 64-bit significands on x86): the phases p_j t lose
    ~2^-64 p_j t instead of ~1e-16 p_j t, so that even a long window's
    values are true to ~1e-14 of sum |c_j| (double phases lose up to
    ~1e-11 at tau = 1 s and N = 120).  Returned as float64."""
    t = np.atleast_1d(np.asarray(t, dtype=np.longdouble))
    phases = np.outer(t, np.asarray(p, dtype=np.longdouble))
    return (np.sin(phases) @ np.asarray(c, dtype=np.longdouble)).astype(
        np.float64)


def y3_slope(c, p, t) -> np.ndarray:
    """dy3/dt = sum_j c_j p_j cos(p_j t), directly."""
    t = np.atleast_1d(np.asarray(t, dtype=np.float64))
    return np.cos(np.outer(t, p)) @ (c * p)


def _grid(c, p, tau):
    """Times, y3 and y3' on the uniform grid over [0, tau]."""
    period = 2.0 * math.pi / float(np.max(p))
    cells = max(1, math.ceil(tau * POINTS_PER_PERIOD / period))
    dt = tau / cells
    count = cells + 1
    block = max(1, math.isqrt(count))
    n_blocks = -(-count // block)
    step = np.exp(1j * np.outer(p, np.arange(block) * dt))      # (N, B)
    weights = np.stack([c, c * p]).astype(complex)               # (2, N)
    rows = max(1, BLOCK_VALUES // block)
    y = np.empty(n_blocks * block)
    slope = np.empty(n_blocks * block)
    for first in range(0, n_blocks, rows):
        b = np.arange(first, min(first + rows, n_blocks))
        start = np.exp(1j * np.outer(b * (block * dt), p))       # (nb, N)
        lo, hi = first * block, (b[-1] + 1) * block
        y[lo:hi] = ((start * weights[0]) @ step).imag.ravel()
        slope[lo:hi] = ((start * weights[1]) @ step).real.ravel()
    t = np.arange(count) * dt
    t[-1] = tau
    return t, y[:count], slope[:count], dt


def _refine(c, p, a, b):
    """A root of y3' in [a, b] by Brent's method, or None when the direct
    slopes at the ends do not bracket one."""
    f = lambda t: float(y3_slope(c, p, t)[0])  # noqa: E731
    fa, fb = f(a), f(b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        return None
    return brentq(f, a, b, xtol=1e-300, rtol=4.0 * np.finfo(float).eps,
                  maxiter=200)


def candidates(c, p, tau) -> Candidates:
    """Every refined stationary point of y3 that may hold an extreme, both
    ends of their cells, and t = 0 and t = tau."""
    c = np.asarray(c, dtype=np.float64)
    p = np.asarray(p, dtype=np.float64)
    live = ~np.isnan(p) & ~np.isnan(c)
    c, p = c[live], p[live]
    tau = float(tau)
    t, y, slope, dt = _grid(c, p, tau)
    scale = float(np.sum(np.abs(c)))
    # the grid values carry the products' rounding and the phases' (a
    # double p_j t is off by up to eps p_j t): a generous margin
    eps = np.finfo(float).eps
    margin = 4.0 * eps * (tau * float(np.sum(np.abs(c) * p))
                          + 16.0 * (c.size + 2) * scale)
    bump = float(np.sum(np.abs(c) * p**2)) * dt * dt / 8.0 + 2.0 * margin
    rising = slope > 0.0
    times = [0.0, tau]
    for sign in (1.0, -1.0):
        s = sign * y
        turns = np.flatnonzero(rising[:-1] != rising[1:])
        if sign > 0:
            turns = turns[rising[turns]]        # + to -: a maximum
        else:
            turns = turns[~rising[turns]]       # - to +: a minimum
        cell_top = np.maximum(s[turns], s[turns + 1]) + bump
        keep = turns[cell_top >= s.max()]
        for k in keep:
            a, b = float(t[k]), float(t[k + 1])
            times += [a, b]
            root = _refine(c, p, a, b)
            if root is not None:
                times.append(root)
    times = np.unique(np.array(times))
    return Candidates(t=times, y=y3(c, p, times), scale=scale)


def extremes(c, p, tau, tie: float = 0.0):
    """(y3_max, t_max, y3_min, t_min) from :func:`candidates`; ``tie`` is
    relative to sum |c_j|: the earliest value within it is reported."""
    cand = candidates(c, p, tau)
    y_max, t_max = cand.extreme(1.0, tie * cand.scale)
    y_min, t_min = cand.extreme(-1.0, tie * cand.scale)
    return y_max, t_max, y_min, t_min
