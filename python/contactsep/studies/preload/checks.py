"""The parts of the design preload search that are not the search
itself (:func:`contactsep.studies.preload.command.preload`): its
arguments checked (``perturbation``, ``converge``), its journal's
manifest, the perturbed and converged answers' fields, and the answer's
event windows and notes.
"""

from __future__ import annotations

import contextlib
import functools
import math

from contactsep.errors import InputError
from contactsep.model.names import shown_text
from contactsep.studies.preload.chart import (
    BAND_HIGH,
    BAND_LOW,
    FINE_RATIO,
    TOLERANCE,
    limit_notes,
    min_preloads,
    search,
)
from contactsep.studies.preload.converge import (
    LEAST_REFINEMENT,
    MARGIN,
    converge_rows,
    largest_check,
    reachable,
)
from contactsep.studies.preload.robust import DEFAULT_P_TARGET
from contactsep.runs.journal import RunJournal

#: The largest ``perturbation``: a probe of the threshold's conditioning,
#: not a tolerance (those are ``tolerance``'s).
MAX_PERTURBATION = 1e-3


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


def doubled_modes(n_modes):
    """Twice the modes of every member (n_modes: one count, or one per
    member)."""
    if isinstance(n_modes, (tuple, list)):
        return type(n_modes)(2 * int(n) for n in n_modes)
    return 2 * int(n_modes)


def relative_change(answer: float, other: float) -> float | None:
    """(other - answer) / answer; None where either is not finite or the
    answer is 0 (and they differ)."""
    if answer == other:
        return 0.0
    if not (math.isfinite(answer) and math.isfinite(other)) or answer == 0:
        return None
    return (other - answer) / answer


def journal_inputs(design, model: str, settings: dict, *, tolerance=(),
                   p_target=DEFAULT_P_TARGET, samples=None, seed=0,
                   verify=True, converge=None, perturbation=None,
                   band_below=False) -> dict:
    """What a search's journal must have been made with to be continued
    (its manifest): :func:`~contactsep.studies.preload.command.preload`'s
    arguments that choose the simulations it asks for."""
    # band_below named only when asked: a journal of the default search
    # keeps the manifest it had before the option
    return dict(design=design, model=model, settings=settings,
                tolerance=list(tolerance), p_target=p_target,
                samples=samples, seed=seed, verify=verify,
                converge=converge, perturbation=perturbation,
                **({"band_below": True} if band_below else {}))


@contextlib.contextmanager
def opened_journal(journal, inputs: dict):
    """The RunJournal ``journal`` names (a path: opened here and closed
    at the end, left in place; a RunJournal: the caller's), or None."""
    if journal is None or isinstance(journal, RunJournal):
        yield journal
        return
    with RunJournal(journal, inputs) as opened:
        yield opened


def check_perturbation(value) -> float | None:
    """``perturbation`` as a float, or an InputError in one line."""
    if value is None:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if isinstance(value, bool) or not 0.0 < number <= MAX_PERTURBATION:
        raise InputError(f"perturbation: found {value!r}, expected a "
                         f"relative change of y_s above 0 and at most "
                         f"{MAX_PERTURBATION:g} (1e-6 is far below any "
                         f"part's tolerance; tolerances themselves: "
                         f"tolerance)")
    return number


def perturbed_searches(design, model, settings, sims, ceiling,
                       perturbation, answer, band_below=False):
    """The searches on y_s (1 + r) and y_s (1 - r) with the nominal's
    settings, in the same batches."""
    designs = [design.replace(ys=design.ys * (1.0 + sign * perturbation))
               for sign in (1.0, -1.0)]
    start = answer if math.isfinite(answer) else None
    sims.search = lambda run: "perturbed_up" if run.design.ys > design.ys \
        else "perturbed_down"
    return search(2, lambda tasks: sims.search_events(
        designs, model, settings, tasks),
        ceilings=[ceiling] * 2, starts=[start] * 2, band_below=band_below,
        ceiling_first=True)


def perturbed_fields(perturbation, perturbed, answer) -> dict:
    """The perturbed_* fields of PreloadAnswer (empty: not asked)."""
    if perturbation is None:
        return {}
    found = tuple(p.min_preload_lb for p in perturbed)
    changes = [relative_change(answer, p) for p in found]
    return dict(perturbation=perturbation, perturbed_min_preload_lb=found,
                min_preload_spread=None if None in changes else
                max(abs(c) for c in changes),
                perturbed_tested=tuple(p.tested for p in perturbed))


def check_converge(converge, verify, n_modes):
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


def converged_fields(design, model, settings, sims, found, verify_found,
                     probe, max_check, band_below=False
                     ) -> tuple[dict, list]:
    """The converged_* fields of the answer (PreloadAnswer) and notes."""
    sims.search = "converge"
    n, dt = int(design.n_modes), probe.dt
    answer, finer = found.min_preload_lb, verify_found.min_preload_lb
    history = ((n, answer), (2 * n, finer))
    change = relative_change(answer, finer)
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
        search_again=functools.partial(min_preloads, band_below=band_below,
                                       ceiling_first=True),
        t_end=probe.t_end_s)
    if row.converged:
        notes.append(f"converged: the answer at N = {row.n_modes} held "
                     f"its check at N = {row.check_n_modes}, which tries "
                     f"the preloads {MARGIN:.0%} either side of it (and "
                     f"between, below) only: a window of events further "
                     f"above it there is not seen "
                     f"(docs/preload-family.md, \"The preload command on "
                     f"the family\"); a whole search at "
                     f"N = {row.check_n_modes} is the stronger test")
    return dict(converged_min_preload_lb=row.min_preload_lb,
                converged_n_modes=row.n_modes, converged_dt_s=row.dt_s,
                converged_check_n_modes=row.check_n_modes,
                converged=row.converged,
                converge_history=((n, answer),) + row.history), notes


def search_notes(found, probe) -> list:
    """The answer's notes on what the search ``found`` saw and missed
    (``probe``: the run at no preload, for its settings)."""
    notes = [
        f"an event: the circuit open (both gaps above "
        f"{shown_text(probe.open_threshold_in, 'in')}) for at least "
        f"{probe.min_open_s:g} s in the window 0-{probe.t_end_s:g} s; "
        f"the answer depends on that min_open (docs/chatter.md)",
        f"search: the ceiling, scan 2^(k/4) lb, bisection to "
        f"{TOLERANCE:.0%}, every {FINE_RATIO - 1:.2%} step from "
        f"{found.band_low:g} to {BAND_HIGH:g} times the answer simulated; "
        f"windows of events narrower than 1 % may lie between two steps "
        f"unseen, and beyond {BAND_HIGH:g} times the answer windows "
        f"narrower than the scan's 19 %",
        f"windows below {found.band_low:g} times the answer are resolved "
        f"to the scan's 19 % steps only" + (
            f" (the scan was monotone; band_below, --band-below: from "
            f"{BAND_LOW:g})" if found.band_low > BAND_LOW else "")]
    notes += limit_notes("the design", found)
    if found.min_preload_lb == 0.0:
        notes.append("closed with no preload at all")
    return notes
