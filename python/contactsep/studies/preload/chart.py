"""The preload search (``contactsep preload``, :mod:`design_preload`)
and the chart built on it (``contactsep study preload``): the smallest
lower-contact preload with no discontinuity event in the window.

The search itself (scan, bisection to 1 %, the fine check from 0.7 to 2
times the answer) is :func:`contactsep.studies.preload.search.search`;
this module runs it on simulations (:class:`Simulations`,
:func:`min_preloads`) and builds the chart (:func:`preload_chart`; the
chart: the thesis rig for d = 0.125 ... 0.75 in and y_s = 0.25, 0.5,
0.75 in).

Every scan step, bisection step and band is one batch of simulations
over all the rows, run on worker processes.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np

from contactsep.chatter import simulate
from contactsep.chatter.circuit import MIN_OPEN
from contactsep.chatter.numerics import DEFAULT_MODES as CHATTER_DEFAULT_MODES
from contactsep.chatter.simulate import DEFAULT_DT
from contactsep.chatter.stack import largest_preload
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError
from contactsep.model.fields import design_lines
from contactsep.runs.backend import InProcess, backend_for
from contactsep.runs.pool import usable_cores
from contactsep.studies.preload.converge import chart_columns, largest_check
from contactsep.studies.preload.runs import PreloadRun, run_row
from contactsep.studies.preload.runs_ahead import RunsAhead
from contactsep.studies.preload.search import (
    BAND_HIGH,
    BAND_LOW,
    FINE_RATIO,
    TOLERANCE,
    PreloadSearch,
    search,
)
from contactsep.studies.study import Study, refuse_fixed, thesis_study_design

#: The chart's separators and release heights (in).
THICKNESSES = (0.125, 0.25, 0.35, 0.5, 0.75)
HEIGHTS = (0.25, 0.5, 0.75)
#: The chart's default model and modes per member.  One default N for
#: the simulation commands, chatter.numerics.DEFAULT_MODES (64, where
#: every converging quantity of the family is within 1 %): a preload
#: search runs at half of it and checks its answer at it (twice the
#: modes, half the step), so that the answer it calls converged is held
#: at the default N, for 1/3.7 to 1/1.6 of the cost of searching there
#: (docs/numerics.md, "The default N").
MODELS = ("hertz", "newton")
DEFAULT_MODES = CHATTER_DEFAULT_MODES // 2
#: The fields the chart sets itself.
FIXED = {"h2": "its rows, d = 0.125-0.75 in",
         "ys": "its curves, y_s = 0.25, 0.5, 0.75 in"}


def _preload_of(task) -> float:
    """A task's cost, the order of a batch (the backend's ``map``): a
    typed task's own ``cost`` (a
    :class:`~contactsep.studies.preload.runs.PreloadRun`'s preload, lb),
    0 for a task without one (a study's runs with no preload)."""
    return float(getattr(task, "cost", 0.0))


def _simulate_event(task) -> bool:
    """Whether a design has a discontinuity event under a preload (one
    simulation; runs in a worker): ``task`` a
    :class:`~contactsep.studies.preload.runs.PreloadRun`."""
    from contactsep.chatter.simulate import UnconvergedWarning
    from contactsep.chatter.stack import CoarseStepWarning
    design, model, settings = task.design, task.model, task.settings
    preload = task.preload_lb
    with warnings.catch_warnings():
        # one line per run from every worker would bury the answer: the
        # chart says once what step it runs at (preload_chart)
        warnings.simplefilter("ignore", CoarseStepWarning)
        warnings.simplefilter("ignore", UnconvergedWarning)
        result = simulate(design, model=model, preload=preload, samples=1,
                          single_impulse=False,
                          stop_at_event=settings.get("stepper") != "fixed"
                          and settings.get("backend") != "numpy",
                          **settings)
    return result.n_events > 0


class Simulations:
    """Batches of simulations on the backend of ``workers``
    (:func:`contactsep.runs.backend.backend_for`: one pool of worker
    processes for the whole search; 1 runs them here; a
    ``distributed.Client``, which the caller keeps and closes: its
    cluster).  Counts the runs and their time for the caller's notes."""

    def __init__(self, workers=None, progress=None, journal=None):
        from contactsep.runs.dask_run import is_client
        #: The Dask client the batches run on, or None (local).
        self.client = workers if is_client(workers) else None
        self.workers = 1 if self.client else workers or usable_cores()
        #: Called with the number of simulations as some finish, or None;
        #: a ``planned(phase, count)`` method of it, before each batch.
        self.progress = progress
        #: A runs.journal.RunJournal keeping every finished run, or None.
        self.journal = journal
        #: Runs asked for (a journal's answers included: a resumed search
        #: counts as an uninterrupted one), and this process's seconds.
        self.runs = 0
        self.seconds = 0.0
        #: The search the next runs of :meth:`events` belong to (a name,
        #: or a function of the run): each a row (preload_runs).
        self.search = "nominal"
        #: The progress bar's name of the next batches (None: search's).
        self.phase = None
        self.log = []
        #: Runs made ahead for idle workers (capacity set on opening), and
        #: the runs each batch put on the workers (asked and ahead).
        self.ahead, self.batches = RunsAhead(), []
        self._backend = None

    def __enter__(self) -> "Simulations":
        self._backend = backend_for(workers=self.workers,
                                    scheduler=self.client)
        # a journal keeps results for this code only
        self._backend.check_code()
        self.ahead.capacity = self._backend.workers
        return self

    def __exit__(self, kind, *exc) -> None:
        # stopped early (Ctrl-C, SIGTERM, a failed run): the runs still
        # going are killed now, not waited for (a minute each at large N)
        if self._backend is not None:
            self._backend.close(finished=kind is None)

    def map(self, function, tasks: list, cost=None) -> list:
        """function(task) for every task, in order (function and tasks
        picklable: module-level, plain data and Designs); a task the
        journal holds is not run again.  ``cost(task)``: the order the
        tasks are handed out in, costliest first (default: a typed
        task's own cost, the preload; 0 for any other task)."""
        start = time.perf_counter()
        cost = cost or _preload_of
        out, todo = self.ahead.answered(function, tasks)
        batch = [tasks[i] for i in todo]
        extra = self.ahead.take(function, batch)
        batch += [task for _, task in extra]
        planned = getattr(self.progress, "planned", None)
        if planned is not None and batch:
            planned(self.phase or (self.search if isinstance(
                self.search, str) else "perturbed"), len(batch))
        run = self._run if self.journal is None else self._run_journaled
        results = run(function, batch, cost=cost) if batch else []
        for i, result in zip(todo, results):
            out[i] = result
        self.ahead.keep(extra, results[len(todo):])
        self.batches.append(len(batch))
        self.runs += len(tasks)
        self.seconds += time.perf_counter() - start
        return out

    def _run(self, function, tasks: list, finished=None,
             cost=_preload_of) -> list:
        # the preloaded runs first where workers share them (slower:
        # fixed steps while pressed); a Simulations never opened runs
        # them here
        backend = self._backend or InProcess()
        return backend.map(function, tasks, cost=cost, finished=finished,
                           progress=self.progress, kept=self._kept)

    def _kept(self, done: int) -> str:
        """What a lost scheduler's line says of the finished runs."""
        if self.journal is None:
            return (f"{done} simulations of this batch had finished, not "
                    f"kept (keep them with --csv FILE --resume)")
        return (f"the {len(self.journal)} simulations finished before it "
                f"are kept (rerun with --resume to continue)")

    def _run_journaled(self, function, tasks: list, cost) -> list:
        from contactsep.runs.task_keys import task_key
        journal = self.journal
        keys = [task_key(function, task) for task in tasks]
        out, missing = [None] * len(tasks), []
        for i, key in enumerate(keys):
            found, result = journal.lookup(key)
            if found:
                out[i] = result
            else:
                missing.append(i)
        journal.reused += len(tasks) - len(missing)
        if self.progress is not None and len(missing) < len(tasks):
            self.progress(len(tasks) - len(missing))
        results = self._run(
            function, [tasks[i] for i in missing],
            finished=lambda j, result: journal.record(keys[missing[j]],
                                                      result), cost=cost)
        for i, result in zip(missing, results):
            out[i] = result
        return out

    def events(self, tasks: list) -> list:
        """Whether each of ``tasks``
        (:class:`~contactsep.studies.preload.runs.PreloadRun`) has a
        discontinuity event."""
        found = self.map(_simulate_event, tasks)
        self.log += [run_row(self.search, t, e) for t, e in zip(tasks, found)]
        return found

    def events_ahead(self, tasks: list, asked: int) -> None:
        """:meth:`events`' ``tasks`` (most likely first) made beside its
        next batch of ``asked`` runs on idle workers (:mod:`runs_ahead`)."""
        self.ahead.queue(_simulate_event, tasks, asked, self.journal)

    def search_events(self, designs, model: str, settings: dict,
                      tasks) -> list:
        """Whether each run of a search's batch (:func:`search_runs`)
        has a discontinuity event."""
        return self.events(search_runs(designs, model, settings, tasks))


def search_runs(designs, model: str, settings: dict, tasks) -> list:
    """The runs of a batch of :func:`search` (its ``has_event``'s
    ``tasks``): each ``(row, preload)`` as a
    :class:`~contactsep.studies.preload.runs.PreloadRun` of
    ``designs[row]`` simulated by ``model`` with ``settings`` at
    ``preload`` lb."""
    return [PreloadRun(designs[row], model, settings, preload)
            for row, preload in tasks]


def min_preloads(designs, model: str = "hertz", settings=None,
                 workers: int | None = None, simulations=None, *,
                 band_below: bool = True, ceiling_first: bool = False
                 ) -> list[PreloadSearch]:
    """The smallest preload with no discontinuity event, design by design.

    :func:`search` for single designs: each simulated by ``model`` at
    the preloads the search asks for, up to the largest the simulation
    takes (:func:`largest_preload`).

    Parameters
    ----------
    designs : iterable of Design
        Single designs.
    model : {"hertz", "newton"}
        The three-beam model (:func:`contactsep.chatter.simulate`).
    settings : dict, optional
        Further keywords of ``simulate()`` (dt, damping, min_open, ...).
    workers : int or distributed.Client, optional
        Processes for the batches of simulations (1: this process), or
        a Client whose Dask cluster runs them.
    simulations : Simulations, optional
        An open :class:`Simulations` to use instead of ``workers``.
    band_below, ceiling_first : bool
        :func:`search`'s.  The defaults are the chart's and the studies'
        searches as their committed outputs were computed (the band from
        0.7 times every answer, the ceiling where the scan reaches it);
        ``contactsep preload`` runs False, True.

    Returns
    -------
    list of PreloadSearch
        One a design: ``min_preload_lb`` (lb; NaN where an event remains
        up to the simulation's limit), every preload ``tested`` with
        whether it gave an event, and ``ceiling_lb``.

    Examples
    --------
    docs/tutorial.md, step 4 (about 90 s: dozens of simulations).
    """
    if model not in MODELS:
        raise InputError(f"model: found {model!r}, expected one of "
                         f"{', '.join(MODELS)}")
    settings = dict(settings or {})
    from contactsep.studies.preload.search_checks import check_designs, check_workers
    designs = check_designs(designs)
    check_workers(workers)

    def has_event(tasks, sims):
        return sims.events(search_runs(designs, model, settings, tasks))

    ceilings = [largest_preload(design) for design in designs]
    how = dict(ceilings=ceilings, band_below=band_below,
               ceiling_first=ceiling_first)
    if simulations is not None:
        return search(len(designs),
                      lambda tasks: has_event(tasks, simulations), **how)
    with Simulations(workers) as sims:
        return search(len(designs), lambda tasks: has_event(tasks, sims),
                      **how)


def limit_notes(where: str, result: PreloadSearch) -> list[str]:
    """A note where the simulation's preload limit cut the search short:
    no answer below it, or the answer's closed octave checked only up to
    it (the search's scan, module docstring)."""
    from contactsep.model.names import shown_text
    top = shown_text(max(p for p, _ in result.tested), "lb", 4)
    ceiling = shown_text(result.ceiling_lb, "lb", 4)
    if math.isnan(result.min_preload_lb):
        return [f"no answer at {where}: an event at {top}, and the "
                f"simulation takes at most {ceiling} (it "
                f"bends the lower contact or the separator by its length)"]
    if result.ceiling_lb < 2.0 * result.min_preload_lb:
        return [f"{where}: closed checked up to {top} only, the "
                f"simulation's limit being {ceiling}"]
    return []


def preload_chart(model: str = "hertz", n_modes: int = DEFAULT_MODES, *,
                  damping: str = "none", dt=None,
                  workers: int | None = None, thicknesses=THICKNESSES,
                  heights=HEIGHTS, settings=None, progress=None,
                  converge=False, journal=None, **overrides) -> Study:
    """The chart: one row per (d, y_s), columns model, n_modes, d_in,
    ys_in, min_preload_lb; any other design field overridden by keyword;
    ``damping`` the Hertz contact's (none: elastic; flores: calibrated
    to e), ``dt`` the stepper's step (default: the model's);
    ``settings`` simulate()'s other keywords, passed to every run;
    ``progress(k)`` is called as k more simulations finish (a bar);
    ``converge``: each row checked at 2N, dt/2 and searched again where
    it fails, up to checks at N = 128 (or at the N given;
    :mod:`contactsep.studies.preload.converge`);
    ``journal``: a :class:`~contactsep.runs.journal.RunJournal`
    that keeps every finished simulation and answers those it holds
    (``study NAME --resume``), or None."""
    from contactsep.studies.preload import search_checks as checks
    checks.check_search("preload", model, MODELS, n_modes, workers,
                        overrides, True)
    thicknesses = checks.check_values("thicknesses", thicknesses, "in")
    heights = checks.check_values("heights", heights, "in")
    refuse_fixed("preload", overrides, FIXED)
    largest = largest_check(converge, n_modes)
    if damping != "none" and model != "hertz":
        raise InputError("damping: the Hertz contact's (--model hertz)")
    rows = [(d, ys) for d in thicknesses for ys in heights]
    designs = [thesis_study_design(d=d, ys=ys, n_modes=n_modes, **overrides)
               for d, ys in rows]
    extra = dict(settings or {})
    settings = {"damping": damping} if model == "hertz" else {}
    # the thesis rig's converged step and the listing's window, given
    # (not the design's own numerics): the chart is the thesis's
    settings["dt"] = DEFAULT_DT[model] if dt is None else dt
    settings["t_end"] = LISTING_TAU_S
    settings.update(extra)
    step = DEFAULT_DT[model] if dt is None else dt
    columns, converged, again = {}, [], []
    with Simulations(workers, progress=progress,
                     journal=journal) as sims:
        found = min_preloads(designs, model, settings, simulations=sims)
        if largest is not None:
            columns, converged, again = chart_columns(rows, lambda n, idx: [
                thesis_study_design(d=rows[i][0], ys=rows[i][1], n_modes=n,
                              **overrides) for i in idx], found, n_modes,
                step, model, settings, sims, largest,
                search_again=min_preloads)
    law = f", damping {damping}" if model == "hertz" else ""
    if "alpha" in settings:
        law += f" (alpha {settings['alpha']:g} s/in)"
    notes = [
        f"model {model}{law}, N = {n_modes} modes per member, the "
        f"adaptive stepper at dt {step:g} s, window 0-0.06 s from the "
        f"release; an event: the circuit open (both gaps above 1e-6 in) "
        f"for at least {MIN_OPEN:g} s",
        "min_preload_lb: the smallest tested preload above which every "
        "tested preload has no event; scan 2^(k/4) lb upward from 1/16 "
        "lb until an octave above the last event is closed, bisection "
        f"to {TOLERANCE:.0%}, then every {FINE_RATIO - 1:.2%} step from "
        f"{BAND_LOW:g} to {BAND_HIGH:g} times the answer simulated, "
        f"closed above it",
        f"{sims.runs} simulations",
        *converged,
    ]
    for k, ((d, ys), result) in enumerate(zip(rows, found)):
        row = f"d = {d:g} in, y_s = {ys:g} in"
        if again and again[k].search is not None:
            # the answer's own search: the row's last, at its N
            result = again[k].search
            row += f" (N = {again[k].n_modes})"
        notes += limit_notes(row, result)
        below = result.closed_below
        if below:
            where = f"{below[0]:.4g} lb" if len(below) == 1 else (
                f"{len(below)} tested preloads from {below[0]:.4g} to "
                f"{below[-1]:.4g} lb")
            notes.append(f"not monotone at {row}: no event also at "
                         f"{where}")
    notes += design_lines(designs[0], per_row=("h2", "ys"))
    table = {"model": np.array([model] * len(rows)),
             "n_modes": np.full(len(rows), int(n_modes)),
             "d_in": np.array([d for d, _ in rows]),
             "ys_in": np.array([ys for _, ys in rows]),
             "min_preload_lb": np.array([r.min_preload_lb for r in found])}
    table.update(columns)
    return Study("preload", "The smallest lower-contact preload with no "
                 "discontinuity event in the window", table, tuple(notes))
