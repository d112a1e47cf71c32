"""What Appendix E's two solvers share: the result of a run against a
rigid stop, the exact modal flow between events, and the Zeno threshold.
The NumPy solver (``event_driven.py``) and the compiled one
(``event_driven_compiled.py``) each import this module, not each other's.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

#: Rebound speed (relative to the first impact's) below which impacts are
#: taken to have accumulated into resting contact.
ZENO_SPEED = 1e-4


@dataclass(frozen=True)
class RigidStopResult:
    """Events of a beam against a rigid stop (times from the release)."""

    #: Impact times (s), impulses (lb s, >= 0), contact-point velocities
    #: just before and after (in/s, positive up).
    impact_t: np.ndarray
    impulse: np.ndarray
    v_before: np.ndarray
    v_after: np.ndarray
    #: Energy (in lb) after each impact.
    energy_after: np.ndarray
    #: Resting (closed-contact) intervals, (k, 2) seconds.
    rest_intervals: np.ndarray
    #: Energy at release and at the end of the window (in lb).
    initial_energy: float
    final_energy: float
    #: Segments (t_start, kind, q, v, basis): the exact motion, for sampling.
    segments: list = field(default_factory=list, repr=False)
    p: np.ndarray = field(default=None, repr=False)
    x: np.ndarray = field(default=None, repr=False)

    def displacement(self, t) -> np.ndarray:
        """Contact-point displacement y(t) (in) at times t (s)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty_like(t)
        starts = np.array([s[0] for s in self.segments])
        which = np.searchsorted(starts, t, side="right") - 1
        for k in np.unique(which):
            rows = which == k
            t0, kind, q, v, basis = self.segments[k]
            q_t, _ = _flow(kind, q, v, self.p, basis, t[rows] - t0)
            out[rows] = q_t @ self.x
        return out


def _flow(kind, q, v, p, basis, tau):
    """Exact modal state after tau (scalar or array) in a free or resting
    segment; returns q(tau), v(tau) with a trailing mode axis."""
    tau = np.asarray(tau, dtype=float)[..., None]
    if kind == "free":
        c, s = np.cos(p * tau), np.sin(p * tau)
        return q * c + v / p * s, -q * p * s + v * c
    vectors, omega = basis
    a, b = q @ vectors, v @ vectors
    live = omega > 0.0
    w = np.where(live, omega, 1.0)
    c, s = np.cos(w * tau), np.sin(w * tau)
    qa = np.where(live, a * c + b / w * s, 0.0)
    va = np.where(live, -a * w * s + b * c, 0.0)
    return qa @ vectors.T, va @ vectors.T
