"""The smallest preload that keeps *this* design's circuit closed
(``contactsep preload``, ``contactsep.preload``; docs/preload.md, "The
preload command").

:func:`preload` runs the preload search of :mod:`contactsep.studies.preload.chart`
(the ceiling first, scan, bisection to 1 %, every 0.99 % step from the
answer to 2 times it simulated, and from 0.7 times it where the scan was
not monotone or ``band_below`` asks) on one design, then its check at
half the step and twice the modes, 2 % either side, searching again
there only where it fails (the answer's own error estimate,
``min_preload_change``: :mod:`contactsep.studies.preload.verify`), and,
given tolerances, the robust answer
(:mod:`contactsep.studies.preload.robust`).  Every batch of simulations
runs on the search's worker pool (:class:`~contactsep.studies.preload.chart.
Simulations`).  The simulation's settings (dt, t_end, damping, min_open,
open_threshold, or any other keyword simulate() takes) pass through
unchanged to every run.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

from contactsep.chatter import simulate
from contactsep.chatter.stack import largest_preload
from contactsep.errors import ContactsepWarning, InputError
from contactsep.studies.preload.chart import (
    FINE_RATIO,
    MODELS,
    Simulations,
    limit_notes,
)
from contactsep.studies.preload.answer import PreloadAnswer
from contactsep.studies.preload.checks import (
    check_converge,
    check_perturbation,
    converged_fields,
    doubled_modes,
    journal_inputs,
    opened_journal,
    perturbed_fields,
    perturbed_searches,
    relative_change,
    search_notes,
    windows,
)
from contactsep.studies.preload.converge import MARGIN, MAX_MODES
from contactsep.studies.preload.robust import (
    DEFAULT_P_TARGET,
    DEFAULT_SAMPLES,
    check_p_target,
    check_robust,
    parse_tolerances,
    robust_preload,
)
from contactsep.studies.preload.estimate import run_seconds, search_estimate
from contactsep.studies.preload.verify import (
    expected_runs,
    search_design,
    verify_design,
)

#: Where the answer moves with N or the step: it may be the threshold's
#: own conditioning (docs/preload-family.md, "How well-posed the answer is").
_HINT = ("; if it is the threshold itself, ill-conditioned, more modes "
         "will not settle it: --perturbation 1e-6 measures that")
#: simulate()'s keywords the search sets itself.
_OWN = ("preload", "samples", "single_impulse", "model", "design")


def _probe(design, model, settings):
    """One run at no preload here: the design and settings checked (an
    InputError in one line, not in a worker), the step simulate() takes,
    and the estimated seconds of a run at that step (:mod:`estimate`)."""
    start = time.perf_counter()
    result = simulate(design, model=model, preload=0.0, samples=1,
                      single_impulse=False, **settings)
    return result, run_seconds(result, time.perf_counter() - start)


def _tell_estimate(progress, run_s, check_run_s, verify, workers) -> None:
    """The search's estimated time on ``workers``, before its first run,
    to a progress that takes it (``progress.estimated``:
    :class:`contactsep.runs.stops.SearchProgress`)."""
    told = getattr(progress, "estimated", None)
    if told is None:
        return
    search_runs = expected_runs(verify=False)
    check_runs = expected_runs() - search_runs if verify else 0
    told(search_estimate(search_runs, run_s, check_runs, check_run_s,
                         workers))


def preload(design, model: str = "hertz", *, tolerance=(),
            p_target: float = DEFAULT_P_TARGET, samples: int | None = None,
            seed: int = 0, verify: bool = True, converge=None,
            perturbation: float | None = None, band_below: bool = False,
            workers: int | None = None, progress=None, journal=None,
            **settings) -> PreloadAnswer:
    """The smallest lower-contact preload (lb) with no discontinuity
    event for ``design`` (a :class:`contactsep.Design`, its own N).

    Parameters
    ----------
    design : Design
        The design; its ``n_modes`` are the modes of the search.
    model : {"hertz", "newton"}
        The contact model of simulate().
    tolerance : sequence of str
        Distributions of design fields, as a sweep's ``--sample``:
        ``'h2=normal(0.25,0.005)'``, ``'ys=uniform(0.45,0.55)'``.  With
        any, the robust answer: the smallest preload whose p_open over
        ``samples`` draws (``seed``) is at most ``p_target``.
    p_target : float
        The largest acceptable p_open (default 0.01).
    samples : int, optional
        Draws of the tolerances (default 100: raise it to resolve a
        p_open of 1 %).
    verify : bool
        Check the answer at half the step and twice the modes for
        ``min_preload_change`` (default True): every 0.99 % step within
        2 % either side of it; where that fails, the whole search there
        (:mod:`contactsep.studies.preload.verify`).
    converge : None, bool or int
        The answer converged to 2 % (``converged_*`` fields): where
        ``min_preload_change`` exceeds 2 %, the answer at 2N is checked
        at 4N and a quarter of the step (or, where the work budget
        refuses that, the finest step it takes if at most 0.75 of the
        last: preload_converge.refined_step; no event 2 % above, one
        within 2 % below).  The default (None) stops there: a few runs
        at 4N, and ``converged`` says whether the check held (where
        ``verify`` is on and every member has the same N; otherwise no
        check).  True also searches again at 4N where the check fails,
        and so on up to checks at N = 128; an integer: up to checks at
        that N (contactsep.studies.preload.converge); False: no check.
        Needs ``verify`` and one N for every member.
    perturbation : float, optional
        A relative change r of y_s (0 < r <= 1e-3; 1e-6 is far below any
        part's tolerance, 1e-9 round-off's scale): the same search, with
        the same settings, on the design with y_s (1 + r) and y_s (1 - r)
        (``perturbed_min_preload_lb``, ``min_preload_spread``; a step
        or window the simulation chooses from the design moves by
        about r with it).  Where
        the spread is far above r the threshold is ill-conditioned, and
        no N or step converges it closer (docs/preload-family.md, "How
        well-posed the answer is").  Two more searches at N.
    band_below : bool
        The fine band from 0.7 times the answer in every search at N
        (default False: from 0.7 only where the scan saw a closed preload
        below its last event; the band below never moves the answer, it
        finds the closed windows below it; with ``tolerance`` the
        nominal search runs it anyway, as the robust search tries the
        nominal design's events).
    workers : int, optional
        Worker processes (default the usable cores; 1: this process).
    progress : callable, optional
        Called with the number of simulations each time some finish.
    journal : str, path or RunJournal, optional
        A directory that keeps every finished simulation (created; a
        journal of the same inputs found there is continued, so a
        search killed at any moment and run again computes only what is
        missing, with the same answer; one of other inputs is refused:
        :class:`contactsep.runs.journal.ResumeError`).  It is left in
        place: remove it once the answer is saved
        (:class:`contactsep.runs.journal.RunJournal`,
        ``contactsep preload --csv F --resume``).
    **settings
        simulate()'s other keywords (dt, t_end, damping, min_open,
        open_threshold, ...), passed to every run.

    Returns
    -------
    PreloadAnswer
    """
    p_target, spec, perturbation = _checked_inputs(
        model, settings, p_target, tolerance, samples, seed, perturbation)
    probe, run_s = _probe(design, model, settings)
    check_run_s = 0.0
    max_check = check_converge(converge, verify, design.n_modes)
    ceiling = largest_preload(design)
    finer = verify_settings = None
    if verify:
        # refused here (the work budget at 2N, dt/2) rather than after
        # the search at N has run
        finer = design.replace(n_modes=doubled_modes(design.n_modes))
        verify_settings = {**settings, "dt": probe.dt / 2}
        check_run_s = _probe(finer, model, verify_settings)[1]
    inputs = journal_inputs(design, model, settings, tolerance=tolerance,
                            p_target=p_target, samples=samples, seed=seed,
                            verify=verify, converge=converge,
                            perturbation=perturbation,
                            band_below=band_below)
    with opened_journal(journal, inputs) as kept, \
            Simulations(workers, progress=progress, journal=kept) as sims:
        _tell_estimate(progress, run_s, check_run_s, verify,
                       sims.ahead.capacity)
        done = _searched(design, model, settings, sims, probe, ceiling,
                         finer, verify_settings, max_check, perturbation,
                         band_below, spec, p_target)
    return _answer(design, model, settings, probe, ceiling, done,
                   perturbation, max_check)


def _checked_inputs(model, settings, p_target, tolerance, samples, seed,
                    perturbation):
    """(p_target, the tolerances' spec or None, perturbation), checked
    before any simulation: each refusal one line."""
    if model not in MODELS:
        raise InputError(f"model: found {model!r}, expected one of "
                         f"{', '.join(MODELS)}")
    own = sorted(set(settings) & set(_OWN))
    if own:
        raise InputError(f"{own[0]}: set by the preload search itself")
    p_target = check_p_target(p_target)
    spec = parse_tolerances(tolerance, DEFAULT_SAMPLES if samples is None
                            else samples, seed) if tolerance else None
    if samples is not None and not tolerance:
        raise InputError("--samples: the draws of --tolerance; give a "
                         "tolerance")
    return p_target, spec, check_perturbation(perturbation)


@dataclass
class _Searched:
    """What :func:`preload`'s searches found, for its answer."""

    found: object
    timing: dict
    notes: list
    verify_found: object = None
    local: bool | None = None
    perturbed: object = None
    converged: dict | None = None
    robust: object = None
    runs: int = 0
    log: tuple = ()


def _searched(design, model, settings, sims, probe, ceiling, finer,
              verify_settings, max_check, perturbation, band_below, spec,
              p_target) -> _Searched:
    """The search at N, its check at 2N and half the step (``finer``,
    ``verify_settings``; None: no check), the perturbed searches, the
    convergence check and the robust answer, on ``sims``."""
    # with tolerances the band below too: the robust search tries the
    # nominal design's events above its own answer
    found = search_design(design, model, settings, sims, ceiling,
                          band_below=band_below or spec is not None)
    # measured for the verdict's estimate of a rerun's time
    done = _Searched(found=found, notes=[],
                     timing={"search": (sims.runs, sims.seconds)})
    answer = found.min_preload_lb
    if finer is not None:
        done.verify_found, done.local = verify_design(
            finer, model, verify_settings, sims, answer, band_below)
    done.timing["verify"] = (sims.runs - done.timing["search"][0],
                             sims.seconds - done.timing["search"][1])
    if perturbation is not None:
        done.perturbed = perturbed_searches(design, model, settings, sims,
                                            ceiling, perturbation, answer,
                                            band_below)
    if max_check is not None:
        done.converged, converge_notes = converged_fields(
            design, model, settings, sims, found, done.verify_found, probe,
            max_check, band_below)
        done.notes += converge_notes
    done.runs = sims.runs
    done.timing["nominal"] = (sims.runs, sims.seconds)
    if spec is not None:
        done.robust = _robust(design, model, settings, spec, p_target,
                              sims, found, ceiling, finer, verify_settings,
                              max_check, done.notes)
    # runs made ahead for idle workers: (made, then asked for)
    done.timing["ahead"] = (sims.ahead.made, sims.ahead.used)
    done.log = tuple(sims.log)
    return done


def _robust(design, model, settings, spec, p_target, sims, nominal,
            ceiling, finer, verify_settings, max_check, notes):
    """The robust answer (and its check at 2N where ``max_check`` asks)
    from the nominal search ``nominal``, its notes appended to
    ``notes``."""
    runs = sims.runs
    answer = nominal.min_preload_lb
    found = robust_preload(
        design, model, settings, spec, p_target, sims,
        start=answer if math.isfinite(answer) else None, ceiling=ceiling,
        nominal_events=[p for p, event in nominal.tested if event])
    notes.append(f"robust answer: {sims.runs - runs} simulations of "
                 f"{spec.samples} samples")
    if max_check is not None:
        runs = sims.runs
        found = check_robust(found, finer, model, verify_settings, spec,
                             sims)
    if found.checked:
        notes.append(f"robust answer's check at N = {found.check_n_modes} "
                     f"and half the step: {sims.runs - runs} simulations; "
                     f"it tries {MARGIN:.0%} either side only, a window of "
                     f"the samples' events further above is not seen")
    return found


def _answer(design, model, settings, probe, ceiling, done: _Searched,
            perturbation, max_check) -> PreloadAnswer:
    """The answer of :func:`preload` from its searches, its warnings
    given."""
    found, verify_found = done.found, done.verify_found
    answer = found.min_preload_lb
    notes = list(done.notes)
    at_answer = None
    if math.isfinite(answer) and answer > 0:
        at_answer = simulate(design, model=model, preload=answer,
                             samples=1, single_impulse=False,
                             **settings).longest_open_s
    notes += search_notes(found, probe)
    verify_answer = None if verify_found is None else \
        verify_found.min_preload_lb
    if done.local:
        notes.append(f"at half the step and twice the modes: checked "
                     f"{MARGIN:.0%} either side of the answer only (every "
                     f"{FINE_RATIO - 1:.2%} step), where it holds: a "
                     f"window of events further above it there is not "
                     f"seen")
    elif verify_found is not None:
        notes += [f"at half the step and twice the modes: {note}" for note
                  in limit_notes("the design", verify_found)]
    change = None if verify_found is None else relative_change(
        answer, verify_answer)
    spread = perturbed_fields(perturbation, done.perturbed, answer)
    _warn(done, answer, verify_answer, change, spread, perturbation,
          max_check)
    return PreloadAnswer(
        design=design, model=model, settings=dict(settings),
        dt_s=probe.dt, n_modes=design.n_modes, min_preload_lb=answer,
        min_preload_change=change, verify_min_preload_lb=verify_answer,
        event_windows=windows(found.tested),
        closed_windows=windows(found.tested, below=answer, event=False),
        tested=found.tested,
        verify_tested=() if verify_found is None else verify_found.tested,
        ceiling_lb=ceiling, longest_open_at_answer_s=at_answer,
        simulations=done.runs, robust=done.robust, notes=tuple(notes),
        timing=done.timing, runs=done.log, **(done.converged or {}),
        **spread)


def _warn(done: _Searched, answer, verify_answer, change, spread,
          perturbation, max_check) -> None:
    """The warnings of an answer that is not converged, whose robust
    answer does not hold at 2N, or whose threshold is ill-conditioned."""
    hint = "" if perturbation is not None else _HINT
    converged, robust = done.converged, done.robust
    # no answer at N nor at 2N (an event up to the ceiling at both): the
    # verdict says so; "not converged" would read as a number to refine
    none_either = not math.isfinite(answer) and not (
        verify_answer is not None and math.isfinite(verify_answer))
    if converged is not None and not converged["converged"] and \
            not none_either:
        checked = converged["converged_check_n_modes"]
        if checked > converged["converged_n_modes"]:
            why = "its check there failed" + (
                f" (converge=True, --converge: search again, up to checks "
                f"at N = {MAX_MODES})" if max_check < MAX_MODES else "")
        else:
            why = (f"no check at N = {2 * checked} fits the simulation's "
                   f"work budget")
        warnings.warn(f"the smallest preload is not converged to "
                      f"{MARGIN:.0%} by N = {checked}: {why}{hint}",
                      ContactsepWarning)
    if robust is not None and robust.converged is False:
        warnings.warn(f"the robust answer does not hold at twice the modes "
                      f"and half the step (N = {robust.check_n_modes}): "
                      f"p_open there is above p_target within "
                      f"{MARGIN:.0%} above it, or not within {MARGIN:.0%} "
                      f"below it; raise n_modes and search again",
                      ContactsepWarning)
    if spread.get("min_preload_spread") is not None and \
            spread["min_preload_spread"] > MARGIN:
        warnings.warn(f"the smallest preload moves by "
                      f"{spread['min_preload_spread']:.1%} when y_s "
                      f"changes by {perturbation:g} of itself: the "
                      f"threshold is ill-conditioned, no N or step "
                      f"converges it closer than that; a design's answer "
                      f"is the robust one (--tolerance)", ContactsepWarning)
    if change is not None and abs(change) > 0.02 and max_check is None:
        warnings.warn(f"the smallest preload moves by {change:+.1%} at half "
                      f"the step and twice the modes: raise n_modes (or "
                      f"lower dt) and search again, or converge it "
                      f"(--converge){hint}", ContactsepWarning)
