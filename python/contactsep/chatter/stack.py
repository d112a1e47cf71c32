"""The stacked three-member system of one run and the bounds it sets.

:func:`contactsep.chatter.simulate` stacks the modes of the upper
contact, the separator and the lower contact into one system; this module
builds that system (preloaded if asked) and refuses what it cannot carry:
a preload that bends a member by more than its length, a design window
longer than the chatter layer runs, a step outside the run's budget (and
warns of one far coarser than the design's own).
"""

from __future__ import annotations

import warnings

import numpy as np

from contactsep.chatter import numerics, runners, system
from contactsep.chatter.settings import ChatterError
from contactsep.chatter.limits import MAX_STEPS, MAX_T_END, MAX_WORK
from contactsep.chatter.system import members
from contactsep.constants import LISTING_TAU_S

#: A dt more than this many times the default is far from converged.
COARSE_DT = 10.0


class CoarseStepWarning(UserWarning):
    """A time step far coarser than the design's own."""


def _stack(design):
    """Stacked modes of the three members: (m, p, h, q0, v0, members)."""
    upper, sep, lower = members(design)
    m = np.concatenate([np.full(upper.p.size, upper.mass),
                        np.full(sep.p.size, sep.mass),
                        np.full(lower.p.size, lower.mass)])
    p = np.concatenate([upper.p, sep.p, lower.p])
    zeros1, zeros3 = np.zeros(upper.p.size), np.zeros(lower.p.size)
    h = np.stack([np.concatenate([upper.x, -sep.x, zeros3]),
                  np.concatenate([zeros1, sep.lower_x, -lower.x])])
    q0 = np.concatenate([upper.q0, sep.q0, lower.q0])
    return m, p, h, q0, np.zeros_like(q0), (upper, sep, lower)


def _largest_preload(design, sep, lower) -> float:
    # a preload that bends a member by more than its length is no small
    # deflection (1e300 lb gave a lower gap of -1.3e285 in)
    return min(float(design.L2) / system.lower_flexibility(sep),
               float(design.L3) / system.flexibility(lower))


def largest_preload(design) -> float:
    """The largest preload (lb) :func:`~contactsep.chatter.simulate`
    takes for ``design``: the force that bends the separator or the lower
    contact, at its contact point, by its length (27.05 lb for the thesis
    rig's lower contact: 0.70 in/lb at its tip)."""
    _, sep, lower = members(design)
    return _largest_preload(design, sep, lower)


def _system(design, preload, law, static_correction=False
            ) -> runners.System:
    """The stacked system, the lower contact preloaded if asked; with
    ``static_correction`` (Hertz only: ``law`` given) the residual
    flexibilities in series with the contacts."""
    m, p, h, q0, v0, (upper, sep, lower) = _stack(design)
    correct = bool(static_correction) and law is not None
    g0 = np.zeros(2)
    most = _largest_preload(design, sep, lower)
    if preload > most:
        raise ChatterError(f"preload: found {preload!r}, expected at most "
                           f"{most:.6g} lb (it would bend the separator or "
                           f"the lower contact by more than its length)")
    if preload > 0.0:
        depth = 0.0 if law is None else law.depth_at(preload)
        q_sep, q_low, g0 = system.preload_state(sep, lower, preload, depth,
                                                correct)
        n1, n2 = upper.p.size, sep.p.size
        q0 = q0.copy()
        q0[n1:n1 + n2] += q_sep
        q0[n1 + n2:] += q_low
    c = system.series_matrix(upper, sep, lower) if correct \
        else np.zeros((2, 2))
    return runners.System(m=m, p=p, h=h, g0=g0, q0=q0, v0=v0,
                          n_upper=upper.p.size, c=c)


def smallest_dt(n_modes: int, t_end: float = LISTING_TAU_S) -> float:
    """The smallest step (s) a run of ``n_modes`` modes per member over
    ``t_end`` takes: at most MAX_STEPS steps and MAX_WORK steps x modes."""
    return t_end / min(MAX_STEPS, MAX_WORK / (3 * n_modes))


def design_window(design, min_open) -> float:
    """The design's own window (s), refused above MAX_T_END or below
    ``min_open``."""
    m, p, h, q0, v0, parts = _stack(design)
    t_end = numerics.design_window(runners.System(
        m=m, p=p, h=h, g0=np.zeros(2), q0=q0, v0=v0,
        n_upper=parts[0].p.size), parts)
    if t_end > MAX_T_END:
        raise ChatterError(
            f"t_end: the design's window is {t_end:.3g} s (its slowest "
            f"member's first mode), more than {MAX_T_END:g} s: give "
            f"t_end (--t-end)")
    if not min_open <= t_end:
        raise ChatterError(f"min_open: found {min_open!r}, expected 0 "
                           f"to t_end = {t_end:g} s (the design's "
                           f"window)")
    return t_end


def checked_dt(design, dt, dt_source, t_end, t_end_source, design_dt,
               modes, stacklevel=2) -> float:
    """The smallest step the run takes; refuses ``dt`` outside 0 < dt <
    t_end or under it, and warns (:class:`CoarseStepWarning`, at
    ``stacklevel`` above the caller) of one over COARSE_DT times the
    design's step ``design_dt``; ``modes``: the stacked system's."""
    if not (dt > 0.0 and dt < t_end):
        raise ChatterError(f"dt: found {dt!r}, expected 0 < dt < t_end")
    least = smallest_dt(int(design.n_modes), t_end)
    if dt < least:
        if dt_source == "design":
            # the budget, with the numbers, before any work
            n = int(design.n_modes)
            head = f"t_end: found {t_end:g} s at N = {n}" \
                if t_end_source == "given" else \
                f"n_modes: found {n} with the design's window {t_end:.3g} s"
            raise ChatterError(
                f"{head} and the design's step {dt:.3g} s: "
                f"{t_end / dt:.3g} steps x {modes} modes = "
                f"{t_end / dt * modes:.3g}, expected at most "
                f"{MAX_WORK:.0e} steps x modes and {MAX_STEPS:.0e} steps a "
                f"run (shorten t_end, lower n_modes, or give dt >= "
                f"{least:.3g} s)")
        raise ChatterError(f"dt: found {dt!r}, expected at least "
                           f"{least:.3g} s at N = {int(design.n_modes)} (at "
                           f"most {MAX_STEPS:.0e} steps and {MAX_WORK:.0e} "
                           f"steps x modes a run)")
    if dt > COARSE_DT * design_dt:
        warnings.warn(f"dt: {dt:g} s is {dt / design_dt:.3g} times the "
                      f"design's step {design_dt:.3g} s: the answers may be "
                      f"far from converged (docs/chatter.md)",
                      CoarseStepWarning, stacklevel=stacklevel + 1)
    return least
