"""The preload chart (``contactsep study preload``): the smallest
lower-contact preload with no discontinuity event in the window.

For each design (the chart: the thesis rig for d = 0.125 ... 0.75 in and
y_s = 0.25, 0.5, 0.75 in) the search

1. **scans** the grid of preloads 2^(k/4) lb (19 % apart) upward from
   1/16 lb, an octave (four values) at a time, until the four values
   above the highest preload with an event are all closed (no event),
   or those of them up to the row's ceiling (the largest preload the
   simulation takes: it bends the lower contact by its length); if the
   first octave has no event it scans down instead, to 2^-20 lb, then
   tries 0;
2. **bisects** (geometric midpoints) between that highest event and the
   next grid value until they are within 1 %;
3. **checks** every 1 % step up to 25 % above the answer: if one has an
   event, the highest such is the new lower end, the next tested
   preload above it the upper end, and 2-3 repeat (steps above the
   ceiling are not tested).

"Closed" is not monotone in preload (docs/chatter.md, "The preload
chart"): below the highest preload with an event a smaller one may be
closed, and short open windows lie between the scan's values.  The
answer is therefore the smallest tested preload above which every
tested preload stays closed: closed at every 1 % step to 25 % above it
and at the scan's steps to an octave above its last event (or to the
ceiling).  Each step
keeps that true (a closed midpoint becomes the upper end, an open one
the lower end), and the answer is itself closed.

Every scan step, bisection step and check is one batch of simulations
over all the rows, run on worker processes.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from contactsep.chatter import simulate
from contactsep.chatter.circuit import MIN_OPEN
from contactsep.chatter.simulate import DEFAULT_DT, largest_preload
from contactsep.errors import InputError
from contactsep.model import thesis_design
from contactsep.studies.fields import design_lines
from contactsep.studies.pool import (
    map_longest_first,
    stop_pool,
    usable_cores,
    worker_pool,
)
from contactsep.studies.study import Study, refuse_fixed

#: The chart's separators and release heights (in).
THICKNESSES = (0.125, 0.25, 0.35, 0.5, 0.75)
HEIGHTS = (0.25, 0.5, 0.75)
#: The chart's default model and modes per member (Hertz converges in N,
#: docs/chatter.md).
MODELS = ("hertz", "newton")
DEFAULT_MODES = 32
#: The scan's grid: preload k is 2^(k / PER_OCTAVE) lb; the scan starts
#: at FIRST_K (1/16 lb), goes down to LOWEST_K (2^-20 lb, ~1e-6 lb: a
#: preload that small is none) and up to HIGHEST_K (1024 lb), or a
#: row's ceiling below it: an event at the highest grid value tested
#: leaves the row without an answer (NaN).
PER_OCTAVE = 4
FIRST_K = -16
LOWEST_K = -80
HIGHEST_K = 40
#: The bisection stops when the bracket's ends are within this ratio - 1.
TOLERANCE = 0.01
#: The check above an answer: every 1 % step up to 25 % above it.
BAND_STEP = 0.01
BAND_STEPS = 25
#: The fields the chart sets itself.
FIXED = {"h2": "its rows, d = 0.125-0.75 in",
         "ys": "its curves, y_s = 0.25, 0.5, 0.75 in"}


def grid(k: int) -> float:
    """Preload k of the scan's grid (lb)."""
    return 2.0 ** (k / PER_OCTAVE)


@dataclass(frozen=True)
class PreloadSearch:
    """One design's search: the answer and every preload it tested."""

    #: The smallest tested preload (lb) above which every tested preload
    #: has no discontinuity event (NaN: an event up to the grid's top).
    min_preload_lb: float
    #: (preload lb, has an event) of every simulation, by preload.
    tested: tuple
    #: The largest preload the search could test (lb; inf: the grid's
    #: top): the simulation's limit, :func:`largest_preload`.
    ceiling_lb: float = math.inf

    @property
    def closed_below(self) -> tuple:
        """Tested preloads below the answer without an event: where
        "closed" is not monotone in preload."""
        return tuple(p for p, event in self.tested
                     if not event and p < self.min_preload_lb)


def _next_scan(scan: dict, zero, top_k: int) -> list:
    """The preloads a row's scan still needs (empty: done).  ``scan``
    maps grid index -> has an event; ``zero`` whether 0 lb has one
    (None: not tried); ``top_k`` the highest grid index the row may
    test."""
    events = [k for k, event in scan.items() if event]
    if events:
        top = max(events)
        return [grid(k) for k in range(top + 1, min(top + PER_OCTAVE,
                                                     top_k) + 1)
                if k not in scan]
    low = min(scan)
    if low > LOWEST_K:
        return [grid(k) for k in range(max(LOWEST_K, low - PER_OCTAVE),
                                       low)]
    return [0.0] if zero is None else []


def _bracket(scan: dict, zero) -> tuple:
    """(highest preload with an event, the next tested one above): the
    scan's bracket of the answer; (nan, nan) if it has no closed top."""
    events = [k for k, event in scan.items() if event]
    if events:
        top = max(events)
        if top + 1 not in scan:
            return math.nan, math.nan
        return grid(top), grid(top + 1)
    if zero:
        return 0.0, grid(min(scan))
    return -math.inf, 0.0               # closed even without a preload


def top_index(ceiling: float) -> int:
    """The highest grid index at or below ``ceiling`` lb (and the grid's
    top, HIGHEST_K)."""
    if ceiling >= grid(HIGHEST_K):
        return HIGHEST_K
    k = math.floor(PER_OCTAVE * math.log2(ceiling))
    return k - 1 if grid(k) > ceiling else k


def search(n_rows: int, has_event, tolerance: float = TOLERANCE,
           ceilings=None) -> list[PreloadSearch]:
    """Run the scan, the bisection and the check above the answer for
    ``n_rows`` designs at once (module docstring).

    ``has_event(tasks)`` takes a list of (row, preload lb) and returns,
    in order, whether each has a discontinuity event (one batch).
    ``ceilings``: each row's largest preload to test (lb; default the
    grid's top, 1024 lb): the scan above the last event stops there,
    even short of an octave, and an event at the highest grid value
    below it leaves the row without an answer (NaN).
    """
    limits = list(ceilings) if ceilings else [math.inf] * n_rows
    tops = [top_index(c) for c in limits]
    scans = [{} for _ in range(n_rows)]
    zeros = [None] * n_rows
    tested = [{} for _ in range(n_rows)]

    def run(tasks, on_grid=False):
        for (row, preload), event in zip(tasks, has_event(tasks)):
            tested[row][preload] = bool(event)
            if on_grid and preload == 0.0:
                zeros[row] = bool(event)
            elif on_grid:
                k = round(PER_OCTAVE * math.log2(preload))
                scans[row][k] = bool(event)

    run([(row, grid(k)) for row in range(n_rows)
         for k in range(FIRST_K, FIRST_K + PER_OCTAVE) if k <= tops[row]],
        on_grid=True)
    while True:
        tasks = [(row, p) for row in range(n_rows)
                 for p in _next_scan(scans[row], zeros[row], tops[row])]
        if not tasks:
            break
        run(tasks, on_grid=True)
    brackets = [list(_bracket(scans[row], zeros[row]))
                for row in range(n_rows)]
    checked = [None] * n_rows
    while True:
        _bisect(brackets, tested, has_event, tolerance)
        # the band above each new answer: an event there moves the
        # bracket up to it (every tested preload above stays closed)
        rows = [row for row, (_, hi) in enumerate(brackets)
                if hi > 0.0 and math.isfinite(hi) and checked[row] != hi]
        if not rows:
            break
        run([(row, p) for row in rows for p in _band(brackets[row][1])
             if p not in tested[row] and p <= limits[row]])
        for row in rows:
            checked[row] = hi = brackets[row][1]
            opened = [p for p in _band(hi) if tested[row].get(p)]
            if opened:
                top = max(opened)
                brackets[row] = [top, min(p for p in tested[row]
                                          if p > top)]
    return [PreloadSearch(min_preload_lb=hi,
                          tested=tuple(sorted(tested[row].items())),
                          ceiling_lb=limits[row])
            for row, (_, hi) in enumerate(brackets)]


def _band(answer: float) -> list:
    """The preloads checked above an answer: BAND_STEPS steps of
    BAND_STEP."""
    return [answer * (1.0 + BAND_STEP * j)
            for j in range(1, BAND_STEPS + 1)]


def _bisect(brackets, tested, has_event, tolerance) -> None:
    """Geometric bisection of every bracket (event, closed) until its
    ends are within ``tolerance``, one batch per step for all rows."""
    while True:
        tasks = [(row, math.sqrt(lo * hi))
                 for row, (lo, hi) in enumerate(brackets)
                 if lo > 0.0 and hi > lo * (1.0 + tolerance)]
        if not tasks:
            return
        for (row, preload), event in zip(tasks, has_event(tasks)):
            tested[row][preload] = bool(event)
            brackets[row][0 if event else 1] = preload


def _preload_of(task) -> float:
    """A task's preload (lb; 0 for a task without one): the cost order
    of a batch (pool.map_longest_first)."""
    value = task[3] if isinstance(task, tuple) and len(task) > 3 else 0.0
    return float(value) if isinstance(value, (int, float)) else 0.0


def _simulate_event(task) -> bool:
    """Whether a design has a discontinuity event under a preload (one
    simulation; runs in a worker)."""
    design, model, settings, preload = task
    result = simulate(design, model=model, preload=preload, samples=1,
                      single_impulse=False, **settings)
    return result.n_events > 0


class Simulations:
    """Batches of simulations on worker processes (one pool for the whole
    search; ``workers`` 1 runs them here).  Counts the runs and their
    time for the caller's notes."""

    def __init__(self, workers: int | None = None):
        self.workers = workers or usable_cores()
        self.runs = 0
        self.seconds = 0.0
        self._pool = None

    def __enter__(self) -> "Simulations":
        if self.workers > 1:
            self._pool = worker_pool(self.workers)
        return self

    def __exit__(self, kind, *exc) -> None:
        if self._pool is None:
            return
        # stopped early (Ctrl-C, SIGTERM, a failed run): the runs still
        # going are dropped, so their workers are killed now rather than
        # waited for (a run may take a minute at large N)
        stop_pool(self._pool, finished=kind is None)

    def map(self, function, tasks: list) -> list:
        """function(task) for every task, in order (function and tasks
        picklable: module-level, plain data and Designs)."""
        start = time.perf_counter()
        if self._pool is None:
            out = [function(task) for task in tasks]
        else:
            # the preloaded runs (slower: fixed steps while pressed) first
            out = map_longest_first(self._pool, function, tasks,
                                    cost=_preload_of)
        self.runs += len(tasks)
        self.seconds += time.perf_counter() - start
        return out

    def events(self, tasks: list) -> list:
        """Whether each (design, model, settings, preload) task has a
        discontinuity event."""
        return self.map(_simulate_event, tasks)


def min_preloads(designs, model: str = "hertz", settings=None,
                 workers: int | None = None, simulations=None
                 ) -> list[PreloadSearch]:
    """:func:`search` for single designs: each simulated by ``model``
    with ``settings`` (simulate()'s keywords: dt, damping, min_open,
    ...), the batches on ``workers`` processes (or ``simulations``, an
    open :class:`Simulations`), each design's preloads up to the largest
    the simulation takes (:func:`largest_preload`)."""
    if model not in MODELS:
        raise InputError(f"model: found {model!r}, expected one of "
                         f"{', '.join(MODELS)}")
    settings = dict(settings or {})
    designs = list(designs)

    def has_event(tasks, sims):
        return sims.events([(designs[row], model, settings, preload)
                            for row, preload in tasks])

    ceilings = [largest_preload(design) for design in designs]
    if simulations is not None:
        return search(len(designs),
                      lambda tasks: has_event(tasks, simulations),
                      ceilings=ceilings)
    with Simulations(workers) as sims:
        return search(len(designs), lambda tasks: has_event(tasks, sims),
                      ceilings=ceilings)


def limit_notes(where: str, result: PreloadSearch) -> list[str]:
    """A note where the simulation's preload limit cut the search short:
    no answer below it, or the answer's closed octave checked only up to
    it (the search's scan, module docstring)."""
    top = max(p for p, _ in result.tested)
    if math.isnan(result.min_preload_lb):
        return [f"no answer at {where}: an event at {top:.4g} lb, and the "
                f"simulation takes at most {result.ceiling_lb:.4g} lb (it "
                f"bends the lower contact or the separator by its length)"]
    if result.ceiling_lb < 2.0 * result.min_preload_lb:
        return [f"{where}: closed checked up to {top:.4g} lb only, the "
                f"simulation's limit being {result.ceiling_lb:.4g} lb"]
    return []


def preload_chart(model: str = "hertz", n_modes: int = DEFAULT_MODES, *,
                  damping: str = "none", dt=None,
                  workers: int | None = None, thicknesses=THICKNESSES,
                  heights=HEIGHTS, **overrides) -> Study:
    """The chart: one row per (d, y_s), columns model, n_modes, d_in,
    ys_in, min_preload_lb; any other design field overridden by keyword;
    ``damping`` the Hertz contact's (none: elastic; flores: calibrated
    to e), ``dt`` the stepper's step (default: the model's)."""
    refuse_fixed("preload", overrides, FIXED)
    if damping != "none" and model != "hertz":
        raise InputError("damping: the Hertz contact's (--model hertz)")
    rows = [(d, ys) for d in thicknesses for ys in heights]
    designs = [thesis_design(d=d, ys=ys, n_modes=n_modes, **overrides)
               for d, ys in rows]
    settings = {"damping": damping} if model == "hertz" else {}
    if dt is not None:
        settings["dt"] = dt
    with Simulations(workers) as sims:
        found = min_preloads(designs, model, settings, simulations=sims)
    step = DEFAULT_DT[model] if dt is None else dt
    law = f", damping {damping}" if model == "hertz" else ""
    notes = [
        f"model {model}{law}, N = {n_modes} modes per member, the "
        f"adaptive stepper at dt {step:g} s, window 0-0.06 s from the "
        f"release; an event: the circuit open (both gaps above 1e-6 in) "
        f"for at least {MIN_OPEN:g} s",
        "min_preload_lb: the smallest tested preload above which every "
        "tested preload has no event; scan 2^(k/4) lb upward from 1/16 "
        "lb until an octave above the last event is closed, bisection "
        f"to {TOLERANCE:.0%}, every {BAND_STEP:.0%} step to "
        f"{BAND_STEP * BAND_STEPS:.0%} above the answer closed",
        f"{sims.runs} simulations",
    ]
    for (d, ys), result in zip(rows, found):
        notes += limit_notes(f"d = {d:g} in, y_s = {ys:g} in", result)
        below = result.closed_below
        if below:
            where = f"{below[0]:.4g} lb" if len(below) == 1 else (
                f"{len(below)} tested preloads from {below[0]:.4g} to "
                f"{below[-1]:.4g} lb")
            notes.append(f"not monotone at d = {d:g} in, y_s = {ys:g} in: "
                         f"no event also at {where}")
    notes += design_lines(designs[0], per_row=("h2", "ys"))
    return Study("preload", "The smallest lower-contact preload with no "
                 "discontinuity event in the window", {
                     "model": np.array([model] * len(rows)),
                     "n_modes": np.full(len(rows), int(n_modes)),
                     "d_in": np.array([d for d, _ in rows]),
                     "ys_in": np.array([ys for _, ys in rows]),
                     "min_preload_lb": np.array(
                         [r.min_preload_lb for r in found])},
                 tuple(notes))
