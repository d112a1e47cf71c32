"""Modal sums and root finding for the NumPy reference
(contactsep.restored.reference).

The tip's displacement and velocity as sums of cosines and sines over the
modes, a vectorised bisection to adjacent doubles, and the first-impact
search of III-(3) that no dip between samples escapes.  Split out of
reference.py, which re-exports ``first_impact`` and
``MAX_SEARCH_SAMPLES``.
"""

from __future__ import annotations

import math

import numpy as np

#: Grid points per period of the fastest mode when bracketing roots.
_SAMPLES_PER_PERIOD = 32



def _cos_sum(coef: np.ndarray, p: np.ndarray, t) -> np.ndarray:
    """sum_j coef_j cos(p_j t), vectorised over t (any shape)."""
    t = np.asarray(t)
    phase = p.reshape((-1,) + (1,) * t.ndim) * t
    return np.tensordot(coef, np.cos(phase), axes=(0, 0))


def _sin_sum(coef: np.ndarray, p: np.ndarray, t) -> np.ndarray:
    """sum_j coef_j sin(p_j t), vectorised over t (any shape)."""
    t = np.asarray(t)
    phase = p.reshape((-1,) + (1,) * t.ndim) * t
    return np.tensordot(coef, np.sin(phase), axes=(0, 0))


def _as_output(values: np.ndarray, t) -> np.ndarray | float:
    return float(values) if np.ndim(t) == 0 else values


def _bisect(fun, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Vectorised bisection of ``fun`` on brackets [lo, hi] across which the
    predicate fun > 0 changes, to adjacent doubles; returns, for each
    bracket, the end with the smaller |fun|."""
    lo = np.array(lo, dtype=np.float64)
    hi = np.array(hi, dtype=np.float64)
    if lo.size == 0:
        return lo
    pos_lo = fun(lo) > 0.0
    for _ in range(2100):          # enough for any pair of finite doubles
        mid = lo + 0.5 * (hi - lo)
        done = (mid <= lo) | (mid >= hi)
        if np.all(done):
            break
        same = (fun(mid) > 0.0) == pos_lo
        lo = np.where(same & ~done, mid, lo)
        hi = np.where(~same & ~done, mid, hi)
    return np.where(np.abs(fun(lo)) <= np.abs(fun(hi)), lo, hi)


def _minima_between(vel, t: np.ndarray, v_grid: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Intervals [t_k, t_k+1] in which the velocity goes from < 0 to >= 0 (a
    minimum of the displacement): their indices k and the bisected times."""
    k = np.nonzero((v_grid[:-1] < 0.0) & ~(v_grid[1:] < 0.0))[0]
    # predicate fun > 0 must change: use -vel, positive while falling
    return k, _bisect(lambda s: -vel(s), t[k], t[k + 1])


#: Most samples the first-impact search may take (at 1/32 of the shortest
#: period): a search that needs more is refused with a ValueError rather
#: than run for hours (a deck with all lengths 1e-6 in asks for ~1e15).
MAX_SEARCH_SAMPLES = 10_000_000
_SEARCH_CHUNK = 1 << 16


def first_impact(ape, p, c, dely: float, *, horizon: float | None = None
                 ) -> float:
    """The first t > 0 at which y(L,t) = sum ape_j c_j cos p_j t (III-(3))
    falls to ``dely``.

    The tip is sampled at 1/32 of the shortest period over [0, horizon]
    (default: four periods of the slowest mode).  A crossing is bracketed
    either by a sample at or below DELY or, between two samples above it, by
    a displacement minimum below DELY (velocity III-(4) bisected to its
    root), so a dip shorter than the sampling step is still caught as long
    as it contains a single minimum.  The earliest bracket is bisected to
    adjacent doubles.  Raises ValueError if the tip starts at or below DELY
    or never reaches it within the horizon.
    """
    ape, p, c = (np.asarray(x, dtype=np.float64) for x in (ape, p, c))
    amp = ape * c
    disp = lambda s: _cos_sum(amp, p, s) - dely          # noqa: E731
    vel = lambda s: _sin_sum(-p * amp, p, s)              # noqa: E731
    if p.size == 0 or not np.all(p > 0.0):
        raise ValueError("the frequencies must be positive")
    if not disp(0.0) > 0.0:
        raise ValueError(
            f"the tip starts at {disp(0.0) + dely!r}, not above DELY = {dely!r}")
    if horizon is None:
        horizon = 4.0 * 2.0 * math.pi / float(np.min(p))
    step = 2.0 * math.pi / float(np.max(p)) / _SAMPLES_PER_PERIOD
    samples = horizon / step
    if not samples < MAX_SEARCH_SAMPLES:
        raise ValueError(
            f"the first impact search would take {samples:.3g} samples "
            f"(1/{_SAMPLES_PER_PERIOD} of the shortest period, {step:.3g} "
            f"s, over {horizon:.3g} s), more than MAX_SEARCH_SAMPLES = "
            f"{MAX_SEARCH_SAMPLES:.3g}")
    count = int(math.ceil(samples)) + 1
    # in chunks that share their end samples: memory does not grow with
    # the horizon
    for start in range(0, count - 1, _SEARCH_CHUNK):
        t = np.arange(start, min(start + _SEARCH_CHUNK, count - 1) + 1) * step
        y = disp(t)
        below = np.nonzero(~(y > 0.0))[0]
        k_direct = int(below[0]) if below.size else t.size
        # displacement minima in the intervals up to the first sample at
        # or below DELY
        scan = t[:k_direct + 1]
        k_min, t_min = _minima_between(vel, scan, vel(scan))
        dips = np.nonzero(~(disp(t_min) > 0.0))[0] if t_min.size else t_min
        if dips.size:
            first = int(dips[0])
            lo, hi = t[k_min[first]], t_min[first]
            break
        if k_direct < t.size:
            lo, hi = t[k_direct - 1], t[k_direct]
            break
    else:
        raise ValueError(
            f"the tip does not reach DELY = {dely!r} within {horizon!r} s")
    return float(_bisect(disp, np.array([lo]), np.array([hi]))[0])
