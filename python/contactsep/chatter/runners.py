"""The steppers behind :func:`contactsep.chatter.simulate`: each takes the
stacked modal system and returns one :class:`Run` (samples, each
contact's open intervals, the largest lower gap, the first impact)."""

from __future__ import annotations

import dataclasses
import importlib
import math
import threading
from dataclasses import dataclass, field

import numpy as np

from contactsep import output
from contactsep.chatter import circuit
from contactsep.chatter import status as chatter_status
from contactsep.chatter.contacts import series_energy, series_law_energy
from contactsep.chatter.laws import ContactMemory
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


#: A compiled run of at least this many steps x modes runs in a thread
#: that Ctrl-C and SIGTERM stop (:func:`_stoppable`); a shorter one
#: ends within milliseconds anyway.
STOPPABLE_WORK = 1e6


class StepperError(InputError):
    """A stepper could not finish (the contact LCP had no solution)."""


def _stoppable(work, call):
    """``call()`` (a compiled stepper; it releases the GIL) in a thread
    while this, the main thread, waits: Ctrl-C or SIGTERM (an exception
    raised here by the handler) sets the compiled loops' stop flag
    (chatter_api's request_stop), the stepper returns within a few
    thousand steps with status INTERRUPTED, and the exception goes on.
    A stepper that returns INTERRUPTED of itself is a KeyboardInterrupt.
    Off the main thread (no signal arrives there) or for a short run,
    the call runs here."""
    api = _api()
    if threading.current_thread() is not threading.main_thread():
        return _interrupted_check(call())
    api.clear_stop()        # a stop asked of an earlier run is done
    if work < STOPPABLE_WORK:
        return _interrupted_check(call())
    box = {}

    def target():
        try:
            box["out"] = call()
        except BaseException as error:   # noqa: BLE001 - sent back
            box["error"] = error

    worker = threading.Thread(target=target, name="contactsep-stepper",
                              daemon=True)
    try:
        worker.start()
        while worker.is_alive():
            worker.join(0.1)
            output.check_stops()        # a progress bar's tick
    except BaseException:
        # (a signal inside start() may come before the thread is seen
        # alive: the flag, left set, stops it at its first look)
        api.request_stop()
        if worker.is_alive():
            worker.join()
            api.clear_stop()
        raise
    if "error" in box:
        raise box["error"]
    return _interrupted_check(box["out"])


def _interrupted_check(out):
    if out[-1] == chatter_status.INTERRUPTED:
        raise KeyboardInterrupt
    return out


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
    #: chatter_status: OK, ENERGY_BOUND (the stepper stopped: its
    #: energy passed ENERGY_MARGIN times the start's; the samples not
    #: reached are NaN) or STOPPED_AT_EVENT (as asked, at the end of the
    #: step where its first discontinuity event lasted min_open: the
    #: samples after are NaN, the intervals end there)
    status: int = chatter_status.OK
    #: The Hertz family's energy book: final ``q``, ``v``, the
    #: ``dissipated`` energy and the contacts' ``stored`` one (in lb);
    #: empty for Newton.
    book: dict = field(default_factory=dict)
    #: STOPPED_AT_EVENT: the instant (s) the stepper stopped; NaN: it ran
    #: the whole window.
    stopped_at: float = math.nan
    #: Newton (adaptive): the energy of the final state (in lb), which
    #: the energy check of a run stopped at its event takes (its last
    #: sample may lie far before the stop; the Hertz family's is
    #: ``book["end"]``); NaN where not kept.
    energy_end: float = math.nan


def _energy_bound(system, law=None) -> float:
    """ENERGY_MARGIN times the energy at the start (with the contacts'
    for Hertz): the steppers' hard bound."""
    s = system
    energy0 = 0.5 * np.sum(s.m * (s.v0**2 + (s.p * s.q0)**2))
    if law is not None:
        gap0 = s.h @ s.q0 + s.g0
        if np.any(s.c != 0.0) and law.plastic:
            energy0 += series_law_energy(ContactMemory(law, len(gap0)),
                                         s.c, gap0)
        elif np.any(s.c != 0.0):
            energy0 += series_energy(law.k, s.c, gap0, law.linear)
        else:
            memory = ContactMemory(law, len(gap0))
            for j, gap in enumerate(gap0):
                memory.remember(j, -float(gap))
                energy0 += memory.energy(j, -float(gap))
    return ENERGY_MARGIN * float(energy0)


def _reached(t, g, energy, status):
    """An adaptive run stopped early: its samples not reached (t left
    at 0 after the first) as NaN."""
    if status == chatter_status.OK:
        return t, g, energy
    missed = t <= 0.0
    missed[0] = False
    return (np.where(missed, np.nan, t), np.where(missed, np.nan, g),
            np.where(missed, np.nan, energy))


def _checked(status, bound=None, energy=None, t=None):
    """The run's status: a stepper's LCP failure is an error; the
    energy past ``bound`` (or not a number) at a sample reached (t >= 0)
    is ENERGY_BOUND whatever the stepper said."""
    if status == chatter_status.LCP_UNSOLVED:
        raise StepperError("the contact LCP had no solution")
    if status not in (chatter_status.OK, chatter_status.ENERGY_BOUND,
                      chatter_status.STOPPED_AT_EVENT):
        raise StepperError(f"the stepper stopped with status {status}")
    if energy is not None:
        reached = energy if t is None else energy[t >= 0.0]
        if not np.all(reached <= bound):
            return chatter_status.ENERGY_BOUND
    return int(status)


def _api():
    return importlib.import_module("contactsep.chatter._chatter").chatter_api


def _first(first) -> tuple:
    return (float(first[0]), float(first[1])) if first[0] >= 0.0 \
        else (float("nan"), float("nan"))


def _stopped_at(crossings, n_cross) -> float:
    """The instant a run stopped at its first event recorded in its
    table (a crossing of code 0; chatter_adaptive_event), else NaN."""
    stops = crossings[0, :n_cross][crossings[1, :n_cross] == 0.0]
    return float(stops[-1]) if len(stops) else math.nan


def _open_from_crossings(crossings, n_cross, g_start, threshold, t_end):
    """Each contact's open intervals from a stepper's crossing table, up
    to t_end or to the stop a run stopped at its event recorded."""
    times, codes = crossings[0, :n_cross], crossings[1, :n_cross]
    stop = _stopped_at(crossings, n_cross)
    t_end = t_end if math.isnan(stop) else stop
    spans = []
    for contact in (1, 2):
        mine = np.abs(codes) == contact
        spans.append(circuit.open_intervals(
            g_start[contact - 1] > threshold, times[mine], codes[mine] > 0,
            t_end))
    return spans


def _with_room(call, work=0.0):
    """Run call(room) with growing crossing tables until they suffice
    (each run stoppable, :func:`_stoppable`)."""
    room = FIRST_CROSSINGS
    while True:
        out = _stoppable(work, lambda: call(room))
        if out[-1] != chatter_status.CROSSINGS_FULL:
            return out
        if room >= MAX_CROSSINGS:
            raise StepperError(f"more than {MAX_CROSSINGS:,} crossings of "
                               f"the open threshold: the gaps hover at it "
                               f"(raise open_threshold)")
        room *= 16


def hertz_adaptive(system, law, dt, steps, stride, threshold,
                   stop_open=-1.0) -> Run:
    """The compiled adaptive Hertz stepper (fortran/chatter/
    adaptive*.f90): the fixed-step splitting where a contact may
    close, the exact flow elsewhere, crossings on the exact flow;
    ``stop_open`` >= 0 stops it once the circuit has been open that
    long (s; its first discontinuity event)."""
    s = system
    samples = steps // stride + 1
    gap0 = s.h @ s.q0 + s.g0
    bound = _energy_bound(s, law)
    (t, g, energy, first, crossings, n_cross, gap_max, counts, q, v, book,
     status) = _with_room(lambda room: _api().run_hertz_adaptive_book(
         s.m, s.p, s.h, s.g0, s.c, s.q0, s.v0, law.k, law.chi,
         law.yield_pressure, law.e_star, law.radius, int(law.linear), dt,
         steps, stride, samples, threshold, s.n_upper, bound, room,
         stop_open=stop_open), steps * s.m.size)
    return _adaptive_run(status, t, g, energy, first, crossings, n_cross,
                         gap_max, counts, gap0, threshold, steps * dt,
                         book=_book(s, q, v, book))


def _adaptive_run(status, t, g, energy, first, crossings, n_cross, gap_max,
                  counts, gap0, threshold, end, **own) -> Run:
    """The Run of an adaptive stepper's outputs: its status checked, its
    samples up to where it stopped, each contact's open intervals from
    its crossings of ``threshold`` (from the gaps ``gap0`` at the
    release to ``end``, s); ``own``: the stepper's own fields of Run."""
    status = _checked(status)
    t, g, energy = _reached(t, g, energy, status)
    upper, lower = _open_from_crossings(crossings, n_cross, gap0, threshold,
                                        end)
    return Run(t=t, gaps=g.T, energy=energy, upper_open=upper,
               lower_open=lower, max_lower_gap_in=float(gap_max[0, 1]),
               first=_first(first), work=_work(counts), status=status,
               stopped_at=_stopped_at(crossings, n_cross), **own)


def _book(system, q, v, book) -> dict:
    """The stepper's energy book, with the energy at the end (in lb)."""
    modal = 0.5 * float(np.sum(system.m * (v**2 + (system.p * q)**2)))
    return {"q": q, "v": v, "dissipated": float(book[0]),
            "stored": float(book[1]), "end": modal + float(book[1])}


def newton_adaptive(system, e, dt, steps, stride, threshold,
                    stop_open=-1.0) -> Run:
    """The compiled adaptive Newton stepper (fortran/chatter/
    adaptive*.f90): exact flow over half steps, Newton's impulses at the
    midpoints where a contact may close, the exact flow elsewhere;
    ``stop_open`` as :func:`hertz_adaptive`'s."""
    s = system
    samples = steps // stride + 1
    gap0 = s.h @ s.q0 + s.g0
    (t, g, energy, first, crossings, n_cross, gap_max, counts, q, v,
     status) = _with_room(lambda room: _api().run_newton_adaptive(
            s.m, s.p, s.h, s.g0, s.q0, s.v0, e, dt, steps, stride, samples,
            threshold, s.n_upper, _energy_bound(s), room,
            stop_open=stop_open), steps * s.m.size)
    return _adaptive_run(
        status, t, g, energy, first, crossings, n_cross, gap_max, counts,
        gap0, threshold, steps * dt,
        energy_end=0.5 * float(np.sum(s.m * (v**2 + (s.p * q)**2))))


def _work(counts) -> dict:
    return {"flight_steps": int(counts[0]), "fixed_steps": int(counts[1]),
            "flow_evaluations": int(counts[2])}


def moreau_jean(system, e, dt, theta, steps, stride, threshold) -> Run:
    """The compiled Moreau-Jean stepper (Newton's law), crossings by
    linear interpolation within a step (its positions are linear)."""
    s = system
    samples = steps // stride + 1
    bound = _energy_bound(s)
    t, g, energy, _, first, crossings, n_cross, gap_max, status = \
        _with_room(lambda room: _api().run_moreau_jean(
            s.m, s.p, s.h, s.g0, s.q0, s.v0, e, dt, theta, steps, stride,
            samples, threshold, room, energy_bound=bound),
            steps * s.m.size)
    status = _checked(status, bound, energy, t)
    upper, lower = _open_from_crossings(crossings, n_cross,
                                        s.h @ s.q0 + s.g0, threshold,
                                        steps * dt)
    return Run(t=t, gaps=g.T, energy=energy, upper_open=upper,
               lower_open=lower, max_lower_gap_in=float(gap_max[0, 1]),
               first=_first(first), work={"fixed_steps": steps},
               status=status)


def hertz_fixed(system, law, dt, steps, stride, threshold,
                backend="compiled") -> Run:
    """The fixed-step Hertz splitting (the reference the adaptive stepper
    is tested against; ``backend="numpy"`` its NumPy twin): crossings
    and the largest lower gap from the samples (every ``stride`` steps).
    """
    s = system
    bound = _energy_bound(s, law)
    status = chatter_status.OK
    if backend == "numpy":
        from contactsep.chatter import steppers
        t, g, energy, _, first, book = steppers.hertz(
            s.m, s.p, s.h, s.g0, s.q0, s.v0, law=law, dt=dt, steps=steps,
            stride=stride, c_matrix=s.c, book=True)
        book = _book(s, book["q"], book["v"], (book["dissipated"],
                                               book["stored"]))
    else:
        samples = steps // stride + 1
        t, g, energy, _, first, q, v, book, status = _stoppable(
            steps * s.m.size, lambda: _api().run_hertz_book(
                s.m, s.p, s.h, s.g0, s.c, s.q0, s.v0, law.k, law.chi,
                law.yield_pressure, law.e_star, law.radius,
                int(law.linear), dt, steps, stride, samples, bound))
        g = g.T
        book = _book(s, q, v, (book[0], book[1]))
    run = _from_samples(t, g, energy, first, threshold, steps * dt,
                        {"fixed_steps": steps},
                        _checked(status, bound, energy, t))
    return dataclasses.replace(run, book=book)


def moreau_jean_numpy(system, e, dt, theta, steps, stride,
                      threshold) -> Run:
    """The NumPy twin of Moreau-Jean (tests only); crossings from its
    samples."""
    from contactsep.chatter import steppers
    s = system
    t, g, energy, _, first = steppers.moreau_jean(
        s.m, s.p, s.h, s.g0, s.q0, s.v0, e=e, dt=dt, steps=steps,
        theta=theta, stride=stride)
    bound = _energy_bound(s)
    return _from_samples(t, g, energy, first, threshold, steps * dt,
                         {"fixed_steps": steps},
                         _checked(chatter_status.OK, bound, energy))


def _from_samples(t, g, energy, first, threshold, t_end, work,
                  status=chatter_status.OK) -> Run:
    if status != chatter_status.OK:
        # the samples the stepper did not reach (t = -1) are no answer
        missed = t < 0.0
        t, g, energy = (np.where(missed, np.nan, t),
                        np.where(missed[:, None], np.nan, g),
                        np.where(missed, np.nan, energy))
        return Run(t=t, gaps=g, energy=energy, upper_open=np.empty((0, 2)),
                   lower_open=np.empty((0, 2)),
                   max_lower_gap_in=math.nan, first=_first(first),
                   work=work, status=status)
    return Run(t=t, gaps=g, energy=energy,
               upper_open=circuit.open_from_samples(t, g[:, 0], t_end,
                                                    threshold),
               lower_open=circuit.open_from_samples(t, g[:, 1], t_end,
                                                    threshold),
               max_lower_gap_in=float(g[:, 1].max()), first=_first(first),
               work=work, status=status)
