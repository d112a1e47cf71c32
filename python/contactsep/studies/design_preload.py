"""The smallest preload that keeps *this* design's circuit closed
(``contactsep preload``, ``contactsep.preload``; docs/chatter.md, "The
preload command").

:func:`preload` runs the preload search of :mod:`contactsep.studies.preload`
(scan, bisection to 1 %, every 0.99 % step from 0.7 to 2 times the
answer simulated) on one design, then the same search at half the step
and twice the modes (the answer's own error estimate,
``min_preload_change``), and, given tolerances, the robust answer
(:mod:`contactsep.studies.preload_robust`).  Every batch of simulations
runs on the search's worker pool (:class:`~contactsep.studies.preload.
Simulations`).  The simulation's settings (dt, t_end, damping, min_open,
open_threshold, or any other keyword simulate() takes) pass through
unchanged to every run.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from contactsep.chatter import simulate
from contactsep.chatter.simulate import largest_preload
from contactsep.errors import ContactsepWarning, InputError
from contactsep.studies.preload import (
    BAND_HIGH,
    BAND_LOW,
    FINE_RATIO,
    MODELS,
    TOLERANCE,
    Simulations,
    limit_notes,
    min_preloads,
    search,
)
from contactsep.studies.preload_converge import (
    LEAST_REFINEMENT,
    MARGIN,
    MAX_MODES,
    converge_rows,
    largest_check,
    reachable,
)
from contactsep.studies.preload_robust import (
    DEFAULT_P_TARGET,
    DEFAULT_SAMPLES,
    RobustPreload,
    check_p_target,
    parse_tolerances,
    robust_preload,
)

#: simulate()'s keywords the search sets itself.
_OWN = ("preload", "samples", "single_impulse", "model", "design")


def windows(tested, below: float = math.inf, event: bool = True) -> tuple:
    """Runs of consecutive tested preloads (by preload) that all have an
    event (``event``) or all have none, below ``below`` lb: ((first,
    last), ...), each run's ends the tested preloads at its edges (the
    window itself reaches at most to the neighbouring tested preloads)."""
    runs, current = [], None
    for preload, has_event in tested:
        if preload >= below:
            break
        if bool(has_event) == event:
            current = [preload, preload] if current is None else \
                [current[0], preload]
        elif current is not None:
            runs.append(tuple(current))
            current = None
    if current is not None:
        runs.append(tuple(current))
    return tuple(runs)


@dataclass(frozen=True)
class PreloadAnswer:
    """The smallest preload with no discontinuity event for one design
    (:func:`preload`)."""

    #: The design searched, as given.
    design: object
    model: str
    #: simulate()'s keywords given (dt, damping, min_open, ...).
    settings: dict
    #: The step every run used (s; the nominal search's), and N.
    dt_s: float
    n_modes: object
    #: The smallest tested preload (lb) above which every tested preload
    #: has no event (NaN: an event up to the simulation's limit).
    min_preload_lb: float
    #: (answer at half the step and twice the modes - answer) / answer
    #: (None: not verified, or no finite nonzero answer to compare).
    min_preload_change: float | None
    #: The answer at half the step and twice the modes (None: not run).
    verify_min_preload_lb: float | None
    #: (first, last) tested preloads of each run of events (lb).
    event_windows: tuple
    #: (first, last) of each run of closed preloads below the answer.
    closed_windows: tuple
    #: (preload lb, has an event) of every nominal run, by preload.
    tested: tuple
    #: The same for the runs at half the step and twice the modes.
    verify_tested: tuple
    #: The largest preload the simulation takes (lb).
    ceiling_lb: float
    #: The longest opening of the circuit at the answer (s): below
    #: min_open, as the answer has no event; how near it is to one.
    longest_open_at_answer_s: float | None
    #: Simulations run, nominal and verify (the robust ones in robust).
    simulations: int
    #: The robust answer under tolerances (None: none given).
    robust: RobustPreload | None
    notes: tuple
    #: With ``converge``: the answer converged to 2 % (lb), the N and
    #: step (s) it was found at, the N of the check it passed, and
    #: whether it passed one (None: not asked; False: the last check,
    #: at the largest N allowed, failed).  The answer at N when its
    #: change at 2N is within 2 %; else the answer at 2N, checked at 4N
    #: and searched again there if it fails, and so on.
    converged_min_preload_lb: float | None = None
    converged_n_modes: int | None = None
    converged_dt_s: float | None = None
    converged_check_n_modes: int | None = None
    converged: bool | None = None
    #: ((N, answer lb), ...) of every search, coarsest first.
    converge_history: tuple = ()

    def to_json_dict(self) -> dict:
        """JSON-ready (strict through contactsep.output: NaN -> null)."""
        fields = {name: getattr(self.design, name)
                  for name in type(self.design).__dataclass_fields__}
        return {
            "inputs": {"model": self.model, "n_modes": self.n_modes,
                       "dt_s": self.dt_s,
                       "settings": {k: _plain(v)
                                    for k, v in self.settings.items()},
                       "design": {k: _plain(v) for k, v in fields.items()}},
            "min_preload_lb": self.min_preload_lb,
            "min_preload_change": self.min_preload_change,
            "verify_min_preload_lb": self.verify_min_preload_lb,
            "event_windows_lb": [list(w) for w in self.event_windows],
            "closed_windows_lb": [list(w) for w in self.closed_windows],
            "ceiling_lb": self.ceiling_lb,
            "longest_open_at_answer_s": self.longest_open_at_answer_s,
            "simulations": self.simulations,
            "robust": self.robust.to_json_dict() if self.robust else None,
            "converged_min_preload_lb": self.converged_min_preload_lb,
            "converged_n_modes": self.converged_n_modes,
            "converged_dt_s": self.converged_dt_s,
            "converged_check_n_modes": self.converged_check_n_modes,
            "converged": self.converged,
            "converge_history": [{"n_modes": n, "min_preload_lb": p}
                                 for n, p in self.converge_history],
            "tested": [{"preload_lb": p, "event": bool(e)}
                       for p, e in self.tested],
            "verify_tested": [{"preload_lb": p, "event": bool(e)}
                              for p, e in self.verify_tested],
            "notes": list(self.notes)}

    def csv_text(self) -> str:
        """'#' comments (the answer, its change, the windows, the robust
        answer, the notes), then one row per preload tried: search
        (nominal, verify, robust), preload_lb, n (designs run), n_open
        (with an event), n_failed."""
        lines = [f"# contactsep preload: the smallest lower-contact "
                 f"preload with no discontinuity event ({self.model}, "
                 f"N = {self.n_modes}, dt {self.dt_s:g} s)",
                 f"# min_preload_lb = {_g(self.min_preload_lb)}",
                 f"# min_preload_change = {_g(self.min_preload_change)} "
                 f"(at half the step and twice the modes: "
                 f"{_g(self.verify_min_preload_lb)} lb)",
                 *self._converged_lines(),
                 "# event windows (lb): " + spans_text(self.event_windows),
                 "# closed windows below the answer (lb): "
                 + spans_text(self.closed_windows)]
        if self.robust is not None:
            r = self.robust
            ci = r.p_open_ci95
            lines.append(
                f"# robust min_preload_lb = {_g(r.min_preload_lb)}: "
                f"p_open {_g(r.p_open)} (95 % Wilson "
                f"{'-' if ci is None else f'{ci[0]:.4g} to {ci[1]:.4g}'}"
                f"; {r.n_open} of {r.n}, {r.n_failed} failed) <= "
                f"p_target {r.p_target:g}")
        lines += [f"# {note}" for note in self.notes]
        lines.append("search,preload_lb,n,n_open,n_failed")
        for name, tested in (("nominal", self.tested),
                             ("verify", self.verify_tested)):
            lines += [f"{name},{p:.12g},1,{int(bool(e))},0"
                      for p, e in tested]
        if self.robust is not None:
            lines += [f"robust,{p:.12g},{n},{k},{f}"
                      for p, n, k, f in self.robust.tested]
        return "\n".join(lines) + "\n"


    def converged_text(self) -> str | None:
        """The converged answer in words (None: not asked): its N and
        step, its check, every search's answer."""
        if self.converged is None:
            return None
        steps = ", ".join(f"{_g(p)} lb at N = {n}"
                          for n, p in self.converge_history)
        return (f"{_g(self.converged_min_preload_lb)} lb (N = "
                f"{self.converged_n_modes}, dt {_g(self.converged_dt_s)} s;"
                f" {'held' if self.converged else 'NOT held'} at N = "
                f"{self.converged_check_n_modes}; searches: {steps})")

    def _converged_lines(self) -> list:
        text = self.converged_text()
        return [] if text is None else \
            [f"# converged_min_preload_lb = {text}"]


def _plain(value):
    if hasattr(value, "item"):
        return value.item()
    return list(value) if isinstance(value, tuple) else value


def _g(value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "none"
    return f"{value:.6g}"


def spans_text(spans) -> str:
    """Windows (lb) as text: '0.5; 0.7-0.9' ('none' for none)."""
    return "; ".join(f"{lo:.5g}" if lo == hi else f"{lo:.5g}-{hi:.5g}"
                     for lo, hi in spans) or "none"


def _doubled(n_modes):
    """Twice the modes of every member (n_modes: one count, or one per
    member)."""
    if isinstance(n_modes, (tuple, list)):
        return type(n_modes)(2 * int(n) for n in n_modes)
    return 2 * int(n_modes)


def _probe(design, model, settings):
    """One run at no preload in this process: the design and settings
    checked (an InputError here, in one line, not in a worker), and the
    step simulate() takes for them."""
    return simulate(design, model=model, preload=0.0, samples=1,
                    single_impulse=False, **settings)


def _change(answer: float, other: float) -> float | None:
    if answer == other:
        return 0.0
    if not (math.isfinite(answer) and math.isfinite(other)) or answer == 0:
        return None
    return (other - answer) / answer


def preload(design, model: str = "hertz", *, tolerance=(),
            p_target: float = DEFAULT_P_TARGET, samples: int | None = None,
            seed: int = 0, verify: bool = True, converge=None,
            workers: int | None = None, progress=None,
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
        Search again at half the step and twice the modes for
        ``min_preload_change`` (default True).
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
        that N (contactsep.studies.preload_converge); False: no check.
        Needs ``verify`` and one N for every member.
    workers : int, optional
        Worker processes (default the usable cores; 1: this process).
    progress : callable, optional
        Called with the number of simulations each time some finish.
    **settings
        simulate()'s other keywords (dt, t_end, damping, min_open,
        open_threshold, ...), passed to every run.

    Returns
    -------
    PreloadAnswer
    """
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
    probe = _probe(design, model, settings)
    max_check = _check_converge(converge, verify, design.n_modes)
    ceiling = largest_preload(design)
    notes = []
    if verify:
        # refused here (the work budget at 2N, dt/2) rather than after
        # the search at N has run
        finer = design.replace(n_modes=_doubled(design.n_modes))
        verify_settings = {**settings, "dt": probe.dt / 2}
        _probe(finer, model, verify_settings)
    with Simulations(workers, progress=progress) as sims:
        found = _search(design, model, settings, sims, ceiling)
        answer = found.min_preload_lb
        verify_found = None
        if verify:
            verify_found = _search(finer, model, verify_settings, sims,
                                   largest_preload(finer), start=answer)
        converged = None
        if max_check is not None:
            converged, converge_notes = _converge(
                design, model, settings, sims, found, verify_found, probe,
                max_check)
            notes += converge_notes
        runs = sims.runs
        robust = None
        if spec is not None:
            robust = robust_preload(
                design, model, settings, spec, p_target, sims,
                start=answer if math.isfinite(answer) else None,
                ceiling=ceiling,
                nominal_events=[p for p, event in found.tested if event])
            notes.append(f"robust answer: {sims.runs - runs} "
                         f"simulations of {spec.samples} samples")
    at_answer = None
    if math.isfinite(answer) and answer > 0:
        at_answer = simulate(design, model=model, preload=answer,
                             samples=1, single_impulse=False,
                             **settings).longest_open_s
    notes += _notes(found, probe)
    verify_answer = None if verify_found is None else \
        verify_found.min_preload_lb
    if verify_found is not None:
        notes += [f"at half the step and twice the modes: {note}" for note
                  in limit_notes("the design", verify_found)]
    change = None if verify_found is None else _change(answer,
                                                       verify_answer)
    if converged is not None and not converged["converged"]:
        checked = converged["converged_check_n_modes"]
        if checked > converged["converged_n_modes"]:
            why = "its check there failed" + (
                f" (converge=True, --converge: search again, up to checks "
                f"at N = {MAX_MODES})" if max_check < MAX_MODES else "")
        else:
            why = (f"no check at N = {2 * checked} fits the simulation's "
                   f"work budget")
        warnings.warn(f"the smallest preload is not converged to "
                      f"{MARGIN:.0%} by N = {checked}: {why}",
                      ContactsepWarning)
    if change is not None and abs(change) > 0.02:
        if max_check is None:
            warnings.warn(f"the smallest preload moves by {change:+.1%} "
                          f"at half the step and twice the modes: raise "
                          f"n_modes (or lower dt) and search again, or "
                          f"converge it (--converge)", ContactsepWarning)
    return PreloadAnswer(
        design=design, model=model, settings=dict(settings),
        dt_s=probe.dt, n_modes=design.n_modes, min_preload_lb=answer,
        min_preload_change=change, verify_min_preload_lb=verify_answer,
        event_windows=windows(found.tested),
        closed_windows=windows(found.tested, below=answer, event=False),
        tested=found.tested,
        verify_tested=() if verify_found is None else verify_found.tested,
        ceiling_lb=ceiling, longest_open_at_answer_s=at_answer,
        simulations=runs, robust=robust, notes=tuple(notes),
        **(converged or {}))


def _check_converge(converge, verify, n_modes):
    """The largest N of a convergence check (None: none), or an
    InputError in one line.  The default (``converge`` None): the
    answer at 2N checked once at 4N, where there is one N and verify."""
    if converge is None:
        if not verify or isinstance(n_modes, (tuple, list)):
            return None
        return 4 * int(n_modes)
    if converge is False:
        return None
    if not verify:
        raise InputError("converge: starts from the search at twice the "
                         "modes; it needs verify")
    if isinstance(n_modes, (tuple, list)):
        raise InputError("converge: doubles one N; give the same n_modes "
                         "for every member")
    return largest_check(converge, int(n_modes))


def _converge(design, model, settings, sims, found, verify_found, probe,
              max_check) -> tuple[dict, list]:
    """The converged_* fields of the answer (PreloadAnswer) and notes."""
    n, dt = int(design.n_modes), probe.dt
    answer, finer = found.min_preload_lb, verify_found.min_preload_lb
    history = ((n, answer), (2 * n, finer))
    change = _change(answer, finer)
    if change is not None and abs(change) <= MARGIN:
        return dict(converged_min_preload_lb=answer, converged_n_modes=n,
                    converged_dt_s=dt, converged_check_n_modes=2 * n,
                    converged=True, converge_history=history), []
    last = reachable(2 * n, dt / 2, probe.t_end_s, max_check)
    notes = []
    if last < max_check:
        notes.append(f"converge: checks stop at N = {last}: a run at "
                     f"N = {2 * last} exceeds the simulation's work budget "
                     f"over the {probe.t_end_s:g} s window even at "
                     f"{LEAST_REFINEMENT:g} of the last step")
    if not math.isfinite(finer) or last < 4 * n:
        return dict(converged_min_preload_lb=finer,
                    converged_n_modes=2 * n, converged_dt_s=dt / 2,
                    converged_check_n_modes=2 * n, converged=False,
                    converge_history=history), notes
    row, = converge_rows(
        lambda m, rows: [design.replace(n_modes=m) for _ in rows],
        [finer], 2 * n, dt / 2, model,
        {k: v for k, v in settings.items() if k != "dt"}, sims, last,
        search_again=min_preloads, t_end=probe.t_end_s)
    if row.converged:
        notes.append(f"converged: the answer at N = {row.n_modes} held "
                     f"its check at N = {row.check_n_modes}, which tries "
                     f"the preloads {MARGIN:.0%} either side of it (and "
                     f"between, below) only: a window of events further "
                     f"above it there is not seen (docs/chatter.md, \"The "
                     f"preload command on the family\"); a whole search at "
                     f"N = {row.check_n_modes} is the stronger test")
    return dict(converged_min_preload_lb=row.min_preload_lb,
                converged_n_modes=row.n_modes, converged_dt_s=row.dt_s,
                converged_check_n_modes=row.check_n_modes,
                converged=row.converged,
                converge_history=((n, answer),) + row.history), notes


def _search(design, model, settings, sims, ceiling, start=None):
    found, = search(1, lambda tasks: sims.events(
        [(design, model, settings, load) for _, load in tasks]),
        ceilings=[ceiling],
        starts=[start if start is not None and math.isfinite(start)
                else None])
    return found


def _notes(found, probe) -> list:
    notes = [
        f"an event: the circuit open (both gaps above "
        f"{probe.open_threshold_in:g} in) for at least "
        f"{probe.min_open_s:g} s in the window 0-{probe.t_end_s:g} s; "
        f"the answer depends on that min_open (docs/chatter.md)",
        f"search: scan 2^(k/4) lb, bisection to {TOLERANCE:.0%}, every "
        f"{FINE_RATIO - 1:.2%} step from {BAND_LOW:g} to {BAND_HIGH:g} "
        f"times the answer simulated; windows of events narrower than "
        f"1 % may lie between two steps unseen, and beyond "
        f"{BAND_HIGH:g} times the answer windows narrower than the "
        f"scan's 19 %",
        f"windows below {BAND_LOW:g} times the answer are resolved to the "
        f"scan's 19 % steps only"]
    notes += limit_notes("the design", found)
    if found.min_preload_lb == 0.0:
        notes.append("closed with no preload at all")
    return notes
