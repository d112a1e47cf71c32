"""The steppers behind :func:`contactsep.chatter.simulate`: each takes the
stacked modal system and returns one :class:`Run` (samples, each
contact's open intervals, the largest lower gap, the first impact)."""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field

import numpy as np

from contactsep.chatter import circuit
from contactsep.chatter import status as chatter_status
from contactsep.chatter.contacts import series_energy
from contactsep.errors import InputError

#: First size of the crossing tables; a run that fills one is repeated
#: with 16x the room (the run is deterministic).
FIRST_CROSSINGS = 4096
#: Most crossings a run may record (64 MB of table).
MAX_CROSSINGS = 4096 * 16**3
#: The energy bound the adaptive stepper's cheap test uses, as a multiple
#: of the energy at the start (the splitting's energy error is ~1e-8 of
#: it; Flores damping only removes energy).
ENERGY_MARGIN = 2.0


class StepperError(InputError):
    """A stepper could not finish (the contact LCP had no solution)."""


@dataclass(frozen=True)
class System:
    """Stacked modes of the three members (mass, frequency per mode), the
    contact Jacobian h (2 x n), the gap offsets g0, the initial state,
    and how many leading modes (the upper contact's) move before the
    first impact while the rest stay in static equilibrium; c the static
    correction's series flexibilities (2 x 2, in/lb; zero: the plain
    truncation; the Hertz laws only)."""

    m: np.ndarray
    p: np.ndarray
    h: np.ndarray
    g0: np.ndarray
    q0: np.ndarray
    v0: np.ndarray
    n_upper: int
    c: np.ndarray = field(default_factory=lambda: np.zeros((2, 2)))


@dataclass(frozen=True)
class Run:
    """A stepper's answer on the window [0, t_end]."""

    t: np.ndarray
    gaps: np.ndarray          # (samples, 2)
    energy: np.ndarray
    upper_open: np.ndarray    # (k, 2) intervals
    lower_open: np.ndarray
    max_lower_gap_in: float
    first: tuple              # (time s, impulse lb s); NaN: none
    work: dict


def _api():
    return importlib.import_module("contactsep.chatter._chatter").chatter_api


def _first(first) -> tuple:
    return (float(first[0]), float(first[1])) if first[0] >= 0.0 \
        else (float("nan"), float("nan"))


def _open_from_crossings(crossings, n_cross, g_start, threshold, t_end):
    """Each contact's open intervals from a stepper's crossing table."""
    times, codes = crossings[0, :n_cross], crossings[1, :n_cross]
    spans = []
    for contact in (1, 2):
        mine = np.abs(codes) == contact
        spans.append(circuit.open_intervals(
            g_start[contact - 1] > threshold, times[mine], codes[mine] > 0,
            t_end))
    return spans


def _with_room(call):
    """Run call(room) with growing crossing tables until they suffice."""
    room = FIRST_CROSSINGS
    while True:
        out = call(room)
        if out[-1] != chatter_status.CROSSINGS_FULL:
            return out
        if room >= MAX_CROSSINGS:
            raise StepperError(f"more than {MAX_CROSSINGS:,} crossings of "
                               f"the open threshold: the gaps hover at it "
                               f"(raise open_threshold)")
        room *= 16


def hertz_adaptive(system, law, dt, steps, stride, threshold) -> Run:
    """The compiled adaptive Hertz stepper (fortran/chatter/
    adaptive*.f90): the fixed-step splitting where a contact may
    close, the exact flow elsewhere, crossings on the exact flow."""
    s = system
    samples = steps // stride + 1
    gap0 = s.h @ s.q0 + s.g0
    energy0 = 0.5 * np.sum(s.m * (s.v0**2 + (s.p * s.q0)**2)) + (
        series_energy(law.k, s.c, gap0) if np.any(s.c != 0.0)
        else np.sum(law.energy(gap0)))
    t, g, energy, first, crossings, n_cross, gap_max, counts, _ = \
        _with_room(lambda room: _api().run_hertz_adaptive(
            s.m, s.p, s.h, s.g0, s.c, s.q0, s.v0, law.k, law.chi, dt, steps,
            stride, samples, threshold, s.n_upper,
            ENERGY_MARGIN * energy0, room))
    upper, lower = _open_from_crossings(crossings, n_cross, gap0, threshold,
                                        steps * dt)
    return Run(t=t, gaps=g.T, energy=energy, upper_open=upper,
               lower_open=lower, max_lower_gap_in=float(gap_max[0, 1]),
               first=_first(first), work=_work(counts))


def newton_adaptive(system, e, dt, steps, stride, threshold) -> Run:
    """The compiled adaptive Newton stepper (fortran/chatter/
    adaptive*.f90): exact flow over half steps, Newton's impulses at the
    midpoints where a contact may close, the exact flow elsewhere."""
    s = system
    samples = steps // stride + 1
    gap0 = s.h @ s.q0 + s.g0
    energy0 = 0.5 * np.sum(s.m * (s.v0**2 + (s.p * s.q0)**2))
    t, g, energy, first, crossings, n_cross, gap_max, counts, status = \
        _with_room(lambda room: _api().run_newton_adaptive(
            s.m, s.p, s.h, s.g0, s.q0, s.v0, e, dt, steps, stride, samples,
            threshold, s.n_upper, ENERGY_MARGIN * energy0, room))
    if status != chatter_status.OK:
        raise StepperError("the contact LCP had no solution")
    upper, lower = _open_from_crossings(crossings, n_cross, gap0, threshold,
                                        steps * dt)
    return Run(t=t, gaps=g.T, energy=energy, upper_open=upper,
               lower_open=lower, max_lower_gap_in=float(gap_max[0, 1]),
               first=_first(first), work=_work(counts))


def _work(counts) -> dict:
    return {"flight_steps": int(counts[0]), "fixed_steps": int(counts[1]),
            "flow_evaluations": int(counts[2])}


def moreau_jean(system, e, dt, theta, steps, stride, threshold) -> Run:
    """The compiled Moreau-Jean stepper (Newton's law), crossings by
    linear interpolation within a step (its positions are linear)."""
    s = system
    samples = steps // stride + 1
    t, g, energy, _, first, crossings, n_cross, gap_max, status = \
        _with_room(lambda room: _api().run_moreau_jean(
            s.m, s.p, s.h, s.g0, s.q0, s.v0, e, dt, theta, steps, stride,
            samples, threshold, room))
    if status != chatter_status.OK:
        raise StepperError("the contact LCP had no solution")
    upper, lower = _open_from_crossings(crossings, n_cross,
                                        s.h @ s.q0 + s.g0, threshold,
                                        steps * dt)
    return Run(t=t, gaps=g.T, energy=energy, upper_open=upper,
               lower_open=lower, max_lower_gap_in=float(gap_max[0, 1]),
               first=_first(first), work={"fixed_steps": steps})


def hertz_fixed(system, law, dt, steps, stride, threshold,
                backend="compiled") -> Run:
    """The fixed-step Hertz splitting (the reference the adaptive stepper
    is tested against; ``backend="numpy"`` its NumPy twin): crossings
    and the largest lower gap from the samples (every ``stride`` steps).
    """
    s = system
    if backend == "numpy":
        from contactsep.chatter import steppers
        t, g, energy, _, first = steppers.hertz(
            s.m, s.p, s.h, s.g0, s.q0, s.v0, law=law, dt=dt, steps=steps,
            stride=stride, c_matrix=s.c)
    else:
        samples = steps // stride + 1
        t, g, energy, _, first = _api().run_hertz(
            s.m, s.p, s.h, s.g0, s.c, s.q0, s.v0, law.k, law.chi, dt, steps,
            stride, samples)
        g = g.T
    return _from_samples(t, g, energy, first, threshold, steps * dt,
                         {"fixed_steps": steps})


def moreau_jean_numpy(system, e, dt, theta, steps, stride,
                      threshold) -> Run:
    """The NumPy twin of Moreau-Jean (tests only); crossings from its
    samples."""
    from contactsep.chatter import steppers
    s = system
    t, g, energy, _, first = steppers.moreau_jean(
        s.m, s.p, s.h, s.g0, s.q0, s.v0, e=e, dt=dt, steps=steps,
        theta=theta, stride=stride)
    return _from_samples(t, g, energy, first, threshold, steps * dt,
                         {"fixed_steps": steps})


def _from_samples(t, g, energy, first, threshold, t_end, work) -> Run:
    return Run(t=t, gaps=g, energy=energy,
               upper_open=circuit.open_from_samples(t, g[:, 0], t_end,
                                                    threshold),
               lower_open=circuit.open_from_samples(t, g[:, 1], t_end,
                                                    threshold),
               max_lower_gap_in=float(g[:, 1].max()), first=_first(first),
               work=work)
