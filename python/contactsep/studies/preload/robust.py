"""The robust preload (``contactsep preload --tolerance``): the smallest
preload whose probability of a discontinuity event, over a design's
tolerances, is at most a target.

The answer of :func:`contactsep.studies.preload.command.preload` is a
threshold in a phase-sensitive system: a part made to its drawing's
tolerances may open at a preload the nominal design keeps closed.  Here
the tolerances are distributions of design fields, written as a sweep's
``--sample`` (``'d=normal(0.25,0.005)'``, ``'ys=uniform(0.45,0.55)'``;
:func:`contactsep.studies.sweep.axes.parse_sample`), and the samples are
the sweep's own draws (:func:`contactsep.studies.sweep.spec.chunk_inputs`: the
same seed gives the same designs as ``contactsep sweep``).  The same
samples are simulated at every preload tried (common random numbers),
each through :func:`contactsep.studies.sweep.chatter.simulate_design`:
a sample the simulation refuses or cannot finish is counted as failed
and left out of ``p_open``, as in a chatter sweep.

A preload meets the target when the upper end of the 95 % Wilson
interval of p_open = n_open / n (n: the samples that ran) is at most
``p_target`` (:mod:`contactsep.studies.preload.robust_rule`: the point estimate
would call 0 of 20 open "at most 1 %"); below
:func:`~contactsep.studies.preload.robust_rule.samples_needed` samples (381 for
0.01) none can, and no robust search is run.  A preload's samples run in
fixed index blocks, and once the samples still to run cannot change its
decision the rest are not run: the same decision as all of them, so the
same answer.  The answer is the preload search of
:mod:`contactsep.studies.preload.chart` on that test (scan 2^(k/4) lb from the
nominal answer, bisection to 1 %, meeting the target at the scan's steps
to an octave above the last failing preload), its fine band
being every preload of the fine grid (0.99 % steps) from the answer to
ROBUST_BAND_HIGH times it, and the preloads up to twice the answer at
which the nominal design had an event.  Each preload tried costs up to
``samples`` simulations, but the samples' windows need not be the
nominal design's: on becu_light at N = 64 (y_s within 2 %, 30 samples)
4 of 30 samples open at 0.045 lb, 2.4 % above the answer a band of the
nominal design's events alone gave (0.0440 lb, where the nominal design
has no event above 0.0415 lb; docs/chatter.md).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass

import numpy as np

from contactsep.errors import ContactsepWarning, InputError
from contactsep.model import fields as design_fields
from contactsep.studies.sweep.chatter import simulate_design
from contactsep.studies.preload.converge import MARGIN
from contactsep.studies.preload.runs import SampleRun
from contactsep.studies.preload.search import fine_band, search
from contactsep.studies.preload.robust_rule import (
    FIRST_BLOCK,
    block_stops,
    p_open_high,
    samples_needed,
    settled,
)
from contactsep.studies.stats import wilson_interval
from contactsep.studies.sweep.spec import chunk_inputs, make_spec

#: Samples of the tolerances unless asked: enough to show p_open <= 0.05
#: (73 are), not 0.01 (381 are; --samples raises it).
DEFAULT_SAMPLES = 100
#: The largest --samples: each preload tried costs that many runs.
MAX_SAMPLES = 1_000_000
#: The default target: at most 1 % of the parts open.
DEFAULT_P_TARGET = 0.01
#: The robust search tries every preload of the fine grid from its
#: answer to this many times it: windows 1 % wide up to the 1.5 times
#: the answer issue 25 asks of the nominal search (whose band goes on
#: to 2, BAND_HIGH, at one run a preload; here each is ``samples``
#: runs); above, the scan's steps and the nominal design's events.
ROBUST_BAND_HIGH = 1.5
#: The robust band runs from its top down, this many preloads a batch
#: (each ``samples`` runs), and stops at the first batch with a failing
#: preload: the answer is the whole band's (preload_search.search), the
#: preloads below that failure are not tried.
ROBUST_BAND_BATCH = 4
#: Index of n_events and status in simulate_design's row.
_EVENTS, _STATUS = 5, 6


@dataclass(frozen=True)
class RobustPreload:
    """The smallest preload with p_open <= p_target under tolerances."""

    #: (field, distribution, a, b) of each tolerance, as parse_sample.
    tolerances: tuple
    samples: int
    seed: int
    p_target: float
    #: The answer (lb; NaN: none up to the simulation's limit).
    min_preload_lb: float
    #: At the answer: samples that ran, that had an event, that failed.
    n: int
    n_open: int
    n_failed: int
    #: (preload lb, n, n_open, n_failed) of every preload tried, by
    #: preload.
    tested: tuple
    #: The answer's check (:func:`check_robust`): the N it ran at (None:
    #: not checked), whether it held (None: no answer to check), and
    #: (preload lb, n, n_open, n_failed) of each preload it ran.
    check_n_modes: int | None = None
    converged: bool | None = None
    checked: tuple = ()
    #: The fewest samples with which a preload can meet p_target (None:
    #: p_target 0); with fewer no search is run (min_preload_lb NaN).
    samples_needed: int | None = None
    #: Simulations of the samples run (search and check), those the
    #: early stop spared (samples x preloads tried, less those run), and
    #: the seconds they took (wall, on the command's workers).
    simulations: int = 0
    simulations_saved: int = 0
    seconds: float = dataclasses.field(default=0.0, compare=False)

    @property
    def shown(self) -> bool:
        """Whether this sample count can show p_target at all."""
        return self.samples_needed is not None and \
            self.samples >= self.samples_needed

    @property
    def p_open(self) -> float | None:
        """n_open / n at the answer (None without a sample that ran)."""
        return self.n_open / self.n if self.n else None

    @property
    def p_open_ci95(self) -> tuple | None:
        """The 95 % Wilson interval of p_open at the answer."""
        return wilson_interval(self.n_open, self.n) if self.n else None

    @property
    def p_open_ci95_high(self) -> float | None:
        """Its upper end: the number the rule holds to p_target."""
        return p_open_high(self.n_open, self.n) if self.n else None

    def to_json_dict(self) -> dict:
        """JSON-ready: the tolerances by output name, the answer, p_open
        and its interval, and every preload tried."""
        names = ("mean", "sd"), ("low", "high")
        return {
            "tolerances": {
                design_fields.column_name(name): {
                    "distribution": kind,
                    **dict(zip(names[kind == "uniform"], (a, b)))}
                for name, kind, a, b in self.tolerances},
            "samples": self.samples, "seed": self.seed,
            "p_target": self.p_target,
            "min_preload_lb": self.min_preload_lb,
            "n": self.n, "n_open": self.n_open, "n_failed": self.n_failed,
            "p_open": self.p_open,
            "p_open_ci95": list(self.p_open_ci95) if self.n else None,
            "p_open_ci95_high": self.p_open_ci95_high,
            "samples_needed": self.samples_needed,
            "simulations": self.simulations,
            "simulations_saved": self.simulations_saved,
            "tested": [{"preload_lb": p, "n": n, "n_open": k,
                        "n_failed": f} for p, n, k, f in self.tested],
            "check_n_modes": self.check_n_modes,
            "converged": self.converged,
            "checked": [{"preload_lb": p, "n": n, "n_open": k,
                         "n_failed": f} for p, n, k, f in self.checked]}


def parse_tolerances(texts, samples, seed) -> tuple:
    """The tolerances (``'FIELD=normal(MEAN,SD)'`` or
    ``'FIELD=uniform(LO,HI)'``, any numeric design field or min_open)
    and the sweep spec that draws them; errors name --tolerance."""
    if isinstance(samples, bool) or not isinstance(samples, int) or \
            not 1 <= samples <= MAX_SAMPLES:
        raise InputError(f"--samples: found {samples!r}, expected an "
                         f"integer from 1 to {MAX_SAMPLES:,}")
    try:
        spec = make_spec(sample=list(texts), samples=samples, seed=seed,
                         model="hertz")
    except InputError as error:
        raise InputError(str(error).replace("--sample", "--tolerance")
                         ) from None
    for name, _, _, _ in spec.sample:
        if name == "preload":
            raise InputError("--tolerance preload: the preload is what "
                             "the command searches; give the tolerances "
                             "of the design")
    return spec


def check_p_target(p_target) -> float:
    """p_target in (0, 1): the upper end of an interval is never 0."""
    try:
        value = float(p_target)
    except (TypeError, ValueError):
        value = math.nan
    if isinstance(p_target, bool) or not 0.0 < value < 1.0:
        raise InputError(f"--p-target: found {p_target!r}, expected a "
                         f"probability above 0 and below 1 (it is met by "
                         f"p_open's 95 % upper bound, never 0)")
    return value


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value


def _sample_run(task) -> tuple:
    """(n_events, status) of one sample at one preload (in a worker):
    ``task`` a :class:`~contactsep.studies.preload.runs.SampleRun`."""
    fields, model, settings = task.design, task.model, task.sample_settings
    row = simulate_design(fields, model, {
        **settings, "stop_at_event": settings.get("stepper") != "fixed"
        and settings.get("backend") != "numpy"})
    return row[_EVENTS], row[_STATUS]


def tolerance_samples(design, settings: dict, spec) -> list:
    """(fields, settings) of each of ``spec``'s draws of ``design`` (a
    Design; ``settings``: simulate()'s keywords): the samples every
    preload tried runs, the same for a given seed, samples and
    tolerances whatever the design's N."""
    base = {name: getattr(design, name)
            for name in type(design).__dataclass_fields__}
    drawn = chunk_inputs(spec, 0, spec.samples)
    samples = []
    for i in range(spec.samples):
        fields, own = dict(base), dict(settings)
        for name, values in drawn.items():
            target = own if name in design_fields.SETTINGS else fields
            target[name] = _plain(values[i])
        samples.append((fields, own))
    return samples


def sample_counts(samples, model: str, preloads, simulations) -> list:
    """(n, n_open, n_failed) of ``samples`` (:func:`tolerance_samples`)
    simulated by ``model`` at each of ``preloads`` (lb), all in one
    batch on ``simulations``: the samples that ran, that had a
    discontinuity event, that the simulation refused or could not
    finish."""
    runs = [SampleRun(fields, model, own, preload)
            for preload in preloads for fields, own in samples]
    results = simulations.map(_sample_run, runs)
    counts = []
    for j in range(len(preloads)):
        rows = results[j * len(samples):(j + 1) * len(samples)]
        ok = [events for events, status in rows if status == 0]
        counts.append((len(ok), sum(1 for events in ok if events > 0),
                       len(rows) - len(ok)))
    return counts


def sample_decisions(samples, model: str, preloads, simulations,
                     p_target: float, first_block: int = FIRST_BLOCK
                     ) -> list:
    """(fails, (n, n_open, n_failed)) of each of ``preloads`` (lb): its
    ``samples`` run in the index blocks of robust_rule.block_stops, all
    the preloads' next blocks in one batch, until the samples still to
    run cannot change whether it meets ``p_target`` (robust_rule.settled:
    the decision all of them give); the counts are of the samples run."""
    counts = [[0, 0, 0] for _ in preloads]
    decided = [None] * len(preloads)
    start = 0
    for stop in block_stops(len(samples), first_block):
        live = [j for j, d in enumerate(decided) if d is None]
        if not live:
            break
        for j, (n, k, f) in zip(live, sample_counts(
                samples[start:stop], model, [preloads[j] for j in live],
                simulations)):
            c = counts[j]
            c[0], c[1], c[2] = c[0] + n, c[1] + k, c[2] + f
            decided[j] = settled(c[1], c[0], len(samples) - stop, p_target)
        start = stop
    return [(d, tuple(c)) for d, c in zip(decided, counts)]


def _not_shown(spec, p_target) -> None:
    needed = samples_needed(p_target)
    warnings.warn(f"the robust answer is not shown at this sample count: "
                  f"needs >= {needed} samples (--samples) for p_open's "
                  f"95 % upper bound to reach p_target {p_target:g}; with "
                  f"{spec.samples} even none open gives "
                  f"{p_open_high(0, spec.samples):.3g}", ContactsepWarning)


def robust_preload(design, model: str, settings: dict, spec, p_target,
                   simulations, start=None, ceiling=math.inf,
                   nominal_events=(), band_batch=ROBUST_BAND_BATCH,
                   first_block=FIRST_BLOCK) -> RobustPreload:
    """The robust answer for ``design`` (a Design) simulated by ``model``
    with ``settings`` (simulate()'s keywords), the tolerances drawn by
    ``spec`` (:func:`parse_tolerances`), the runs on ``simulations``
    (an open :class:`contactsep.studies.preload.chart.Simulations`); the scan
    starts near ``start`` lb (the nominal answer) and stops at
    ``ceiling`` lb.  ``nominal_events``: the preloads (lb) at which the
    nominal design had an event; those above an answer are tried too
    (the scan's 19 % steps would step over a narrow window the nominal
    search found at its 0.99 % steps, and the tolerances smear it), and
    so is every preload of the fine grid from an answer to
    ROBUST_BAND_HIGH times it (a sample's window need not be one of the
    nominal design's); the band from its top down, ``band_batch``
    preloads a batch, to its first failing preload (None: the whole band
    in one batch; the same answer, more preloads tried).  Each preload's
    samples stop once settled (:func:`sample_decisions`, ``first_block``
    the first block).  Fewer samples than the target needs: no search
    (NaN), and a warning."""
    p_target = check_p_target(p_target)
    needed = samples_needed(p_target)
    base = dict(tolerances=spec.sample, samples=spec.samples,
                seed=spec.seed, p_target=p_target, samples_needed=needed)
    if spec.samples < needed:
        _not_shown(spec, p_target)
        return RobustPreload(min_preload_lb=math.nan, n=0, n_open=0,
                             n_failed=0, tested=(), **base)
    samples = tolerance_samples(design, settings, spec)
    counts = {}
    runs, seconds = simulations.runs, simulations.seconds
    simulations.phase = "robust"

    def fails(tasks):
        preloads = [preload for _, preload in tasks]
        out = []
        for preload, (failed, count) in zip(preloads, sample_decisions(
                samples, model, preloads, simulations, p_target,
                first_block)):
            counts[preload] = count
            out.append(failed)
        return out

    events = sorted(set(nominal_events))

    def check(row, answer):
        fine = [p for p in fine_band(answer)
                if answer < p <= ROBUST_BAND_HIGH * answer]
        return sorted(set(fine).union(
            p for p in events if answer < p <= 2.0 * answer))

    found, = search(1, fails, ceilings=[ceiling], starts=[start],
                    band=check, band_batch=band_batch)
    answer = found.min_preload_lb
    n, n_open, n_failed = counts.get(answer, (0, 0, 0))
    ran = simulations.runs - runs
    return RobustPreload(
        min_preload_lb=answer, n=n, n_open=n_open, n_failed=n_failed,
        tested=tuple((p, *counts[p]) for p in sorted(counts)),
        simulations=ran, simulations_saved=len(counts) * spec.samples - ran,
        seconds=simulations.seconds - seconds, **base)


def check_robust(robust: RobustPreload, design, model: str,
                 settings: dict, spec, simulations) -> RobustPreload:
    """``robust`` with its check: the same draws of ``spec`` on
    ``design`` (twice the modes of the search's) with ``settings`` (half
    its step), at the answer and every fine-grid preload within MARGIN
    (2 %) above it, and every one within MARGIN below it.  It held
    (``converged``) when p_open meets p_target at every preload from the
    answer up and fails it at one below where a sample ran: the robust
    answer at 2N then lies within 2 % of it, unless a window of the
    samples' events lies further above it at 2N (the check is local, as
    the nominal answer's: preload_converge).  Each preload's samples stop
    once settled, as the search's.  No answer (NaN, or 0): not
    checked."""
    answer = robust.min_preload_lb
    n_modes = design.n_modes
    if not (math.isfinite(answer) and answer > 0.0):
        return dataclasses.replace(robust, check_n_modes=n_modes)
    near = [p for p in fine_band(answer)
            if answer * (1.0 - MARGIN) <= p <= answer * (1.0 + MARGIN)
            and p != answer]
    preloads = sorted([answer, *near])
    runs, seconds = simulations.runs, simulations.seconds
    simulations.phase = "robust check"
    decisions = sample_decisions(
        tolerance_samples(design, settings, spec), model, preloads,
        simulations, robust.p_target)
    checked = tuple((p, *c) for p, (_, c) in zip(preloads, decisions))
    # above: every preload met the target (which needs samples that
    # ran); below: one that ran failed it (no sample ran: no evidence)
    held = all(not failed for p, (failed, _) in zip(preloads, decisions)
               if p >= answer) and \
        any(failed and c[0] for p, (failed, c) in zip(preloads, decisions)
            if p < answer)
    ran = simulations.runs - runs
    return dataclasses.replace(
        robust, check_n_modes=n_modes, converged=held, checked=checked,
        simulations=robust.simulations + ran,
        simulations_saved=robust.simulations_saved
        + len(preloads) * spec.samples - ran,
        seconds=robust.seconds + simulations.seconds - seconds)
