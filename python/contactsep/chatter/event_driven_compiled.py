"""Appendix E, compiled: the rigid-stop solver of ``event_driven.py`` in
Fortran (fortran/chatter/event_driven.f90, module contactsep.chatter._chatter).

The Fortran runs the twin's algorithm (same flow, bound, root finder,
thresholds, Zeno closure, release, ``leaving`` nudge and caps) with two
differences of arithmetic only: the constrained modes come from a cyclic
Jacobi eigensolver instead of ``numpy.linalg.eigh``, and sums are taken in
another order.  One difference of logic, a guard: the root finder's Newton
shortcut tau - f/d is taken only when it is at most twice the safe step.
Without it, at a release from rest (f and f' both at round-off) the
shortcut can jump milliseconds ahead over real contacts; the NumPy twin
keeps the unguarded shortcut (there it only adds impulse-free events,
psi = 0, on the thesis designs; see tests/chatter/test_chatter_event_driven_
compiled.py).

Events come from Fortran; the exact motion between them (``segments``, for
``RigidStopResult.displacement``) is rebuilt here by replaying the events
with the twin's exact flow: free flight to each recorded impact time, the
recorded impulse applied, the contact closed (state projected) where the
Fortran closed it, the resting flow to the recorded release.  The replay
finds nothing itself, so it costs O(events) flows, and its state agrees
with the Fortran's at round-off (the tests check the final state).
"""

from __future__ import annotations

import importlib

import numpy as np

from contactsep.chatter.rigid_stop import ZENO_SPEED, RigidStopResult, _flow
from contactsep.chatter.status import (
    BAD_INPUT,
    IMPACTS_FULL,
    NO_EIGENBASIS,
    RESTS_FULL,
)

#: First size of the event tables; they grow by 4x while a run fills them
#: before t_end (the run is repeated: it is deterministic).
FIRST_TABLE = 1024


def _api():
    return importlib.import_module("contactsep.chatter._chatter").chatter_api


def simulate_rigid_stop_compiled(p, x, mass, q0, v0, e, t_end, *,
                                 stop=0.0, zeno_speed=ZENO_SPEED,
                                 max_impacts=1_000_000, segments=True
                                 ) -> RigidStopResult:
    """``simulate_rigid_stop`` in Fortran; the same arguments and result.

    ``segments=False`` skips the replay (``displacement`` then is
    unavailable).  Raises ValueError for input the Fortran rejects (n < 1,
    p <= 0, mass <= 0, X = 0, e outside [0, 1], t_end or zeno_speed < 0,
    max_impacts < 1, anything non-finite, mismatched lengths).
    """
    if stop != 0.0:
        raise ValueError("the stop is at y = 0 (shift the initial state)")
    p, x = np.asarray(p, float), np.asarray(x, float)
    q0, v0 = np.asarray(q0, float), np.asarray(v0, float)
    if p.ndim != 1 or not p.shape == x.shape == q0.shape == v0.shape:
        raise ValueError(f"p, x, q0, v0 must be 1-D of one length: found "
                         f"{p.shape}, {x.shape}, {q0.shape}, {v0.shape}")
    if p.size < 1:
        raise ValueError("the beam needs at least one mode")
    max_impacts = int(max_impacts)
    if max_impacts < 1:
        raise ValueError(f"max_impacts: found {max_impacts}, expected >= 1")
    table = min(max_impacts, FIRST_TABLE)
    while True:
        (impacts, n_impacts, closure, rests, n_rests, q_end, v_end,
         energies, status) = _api().run_rigid_stop(
            p, x, float(mass), q0, v0, float(e), float(t_end),
            float(zeno_speed), table, table)
        if status in (IMPACTS_FULL, RESTS_FULL) and table < max_impacts:
            table = min(4 * table, max_impacts)
            continue
        break
    if status == BAD_INPUT:
        raise ValueError("run_rigid_stop: bad input (n < 1, p <= 0, "
                         "mass <= 0, X = 0, e outside [0, 1], t_end or "
                         "zeno_speed < 0, or a non-finite value)")
    if status == NO_EIGENBASIS:
        raise ArithmeticError("run_rigid_stop: the Jacobi eigensolver did "
                              "not converge")
    events = impacts[:, :n_impacts].T
    rest_intervals = rests[:, :n_rests].T.copy()
    found = (_replay(p, x, mass, q0, v0, events, closure[:n_impacts],
                     rest_intervals, float(t_end))
             if segments else [])
    return RigidStopResult(
        impact_t=events[:, 0].copy(), impulse=events[:, 1].copy(),
        v_before=events[:, 2].copy(), v_after=events[:, 3].copy(),
        energy_after=events[:, 4].copy(), rest_intervals=rest_intervals,
        initial_energy=float(energies[0]), final_energy=float(energies[1]),
        segments=found, p=p, x=x)


def _replay(p, x, mass, q0, v0, events, closure, rests, t_end) -> list:
    """Segments (t_start, kind, q, v, basis) as the NumPy twin builds
    them, from the recorded events."""
    sx = float(x @ x)
    segments = [(0.0, "free", q0.copy(), v0.copy(), None)]
    basis = None
    k = 0
    for (t, psi, *_), closed in zip(events, closure):
        t0, kind, q, v, b = segments[-1]
        q, v = _flow(kind, q, v, p, b, t - t0)
        v = v + x * psi / mass
        segments.append((t, "free", q.copy(), v.copy(), None))
        if closed == 0:
            continue
        v = v - x * float(v @ x) / sx
        q = q - x * float(q @ x) / sx
        if closed == 2:         # closed and left at once: no rest
            segments.append((t, "free", q.copy(), v.copy(), None))
            continue
        if basis is None:
            basis = constrained_basis(p, x)
        segments.append((t, "rest", q.copy(), v.copy(), basis))
        end = rests[k, 1]
        k += 1
        if end < t_end:
            q, v = _flow("rest", q, v, p, basis, end - t)
            segments.append((end, "free", q.copy(), v.copy(), None))
    return segments


def constrained_basis(p, x):
    """The twin's resting-contact modes: eigh of P K P, the mode most
    aligned with X frozen (omega = 0)."""
    sx = float(x @ x)
    projector = np.eye(p.size) - np.outer(x, x) / sx
    stiff = projector @ np.diag(p**2) @ projector
    omega2, vectors = np.linalg.eigh(0.5 * (stiff + stiff.T))
    omega = np.sqrt(np.clip(omega2, 0.0, None))
    omega[np.argmax(np.abs(vectors.T @ x))] = 0.0
    return vectors, omega


def replayed_end_state(result: RigidStopResult, t_end: float):
    """Modal state (q, v) at t_end from the replayed segments (a check on
    the replay against the Fortran's own final state)."""
    t0, kind, q, v, basis = result.segments[-1]
    return _flow(kind, q, v, result.p, basis, t_end - t0)
