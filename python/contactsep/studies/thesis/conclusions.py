"""The thesis's conclusions re-examined for circuit opening
(``contactsep study conclusion3|conclusion5|conclusion6|conclusion7``;
docs/circuit-opening.md, "The thesis's conclusions and circuit opening").

The thesis judges a design by the single-impulse displacement of the
lower contact (eq. 23).  Each study here changes one thing the thesis
recommends, on the thesis rig with y_s = 0.5 in, and sets beside eq.
23's max y3 what the three-beam simulation says about opening:

* ``max_lower_gap_in``, ``circuit_open_s``, ``n_events``: with no
  preload (the lower contact touching the separator, as in the thesis);
* ``min_preload_lb``: the smallest lower-contact preload with no
  discontinuity event in the window (the preload chart's search,
  contactsep.studies.preload.chart) — how hard the design must press its
  lower contact to keep the circuit closed.

Conclusion 3: a smaller coefficient of restitution (Hertz contact with
Flores damping calibrated to e); 5: a thicker separator; 6: a more
massive separator (its density, as in Figure 8: the mass ratio R of eq.
24); 7: the lower contact point moved toward the clamp (x3/L3 from 1.0
to 0.5).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep.chatter import simulate
from contactsep.chatter.simulate import DEFAULT_DT
from contactsep.constants import LISTING_TAU_S
from contactsep.model.fields import column_name, design_lines
from contactsep.studies.preload.chart import (
    DEFAULT_MODES,
    MODELS,
    Simulations,
    limit_notes,
    min_preloads,
)
from contactsep.studies.study import (
    Study,
    StudyRun,
    evaluate_all,
    refuse_fixed,
    thesis_study_design,
)

#: The values each study takes (the thesis rig's first, except e).
RESTITUTIONS = (0.2, 0.375, 0.6, 0.8, 1.0)
THICKNESSES = (0.125, 0.25, 0.35, 0.5, 0.75)
DENSITY_FACTORS = (0.5, 1.0, 2.0, 4.0, 8.0)
CONTACT_RATIOS = (1.0, 0.9, 0.8, 0.7, 0.6, 0.5)

#: study -> (the field it sets, why; the thesis's conclusion in short).
STUDIES = {
    "conclusion3": ("e", "its rows, e = 0.2-1.0",
                    "a smaller coefficient of restitution reduces the "
                    "lower contact's separation"),
    "conclusion5": ("h2", "its rows, d = 0.125-0.75 in",
                    "a thicker separator reduces the lower contact's "
                    "displacement"),
    "conclusion6": ("gamma2", "its rows, 0.5-8 times the rig's density",
                    "the separator should be as massive as feasible"),
    "conclusion7": ("x3", "its rows, x3/L3 = 1.0-0.5",
                    "moving the lower contact point toward the clamp "
                    "reduces its displacement"),
}


@dataclass(frozen=True)
class FreeRun(StudyRun):
    """One simulation of a study's design with no preload, by ``model``,
    ``settings`` further keywords of ``simulate()``."""

    design: object
    model: str
    settings: dict


def _zero_preload(task: FreeRun):
    """One simulation with no preload (runs in a worker)."""
    r = simulate(task.design, model=task.model, samples=1,
                 single_impulse=False, **task.settings)
    return r.max_lower_gap_in, r.circuit_open_s, r.n_events


def _values(name: str, base) -> np.ndarray:
    """The values a study gives its field."""
    if name == "conclusion3":
        return np.array(RESTITUTIONS)
    if name == "conclusion5":
        return np.array(THICKNESSES)
    if name == "conclusion6":
        return float(base.gamma2) * np.array(DENSITY_FACTORS)
    return np.array(CONTACT_RATIOS) * float(base.L3)


def _single_impulse(base, own: str, values, designs):
    """Eq. 23 for the study's designs (y3_max, R), with the members' own
    beam physics (issue 27: ``--separator physical``)."""
    return evaluate_all(base.replace(**{own: values}), "compiled")


def _columns(name: str, values, single, base) -> dict:
    """The parameter's columns, under output names."""
    if name == "conclusion3":
        return {"e": values}
    if name == "conclusion5":
        return {"d_in": values}
    if name == "conclusion6":
        return {"R": single.R, "gamma2_lb_in3": values}
    return {"r": values / float(base.L3), "x3_in": values}


def conclusion(name: str, model: str = "hertz",
               n_modes: int = DEFAULT_MODES, *, dt=None, workers=None,
               progress=None, journal=None, **overrides) -> Study:
    """One of the studies (module docstring): the parameter's columns,
    then y3_max_in (eq. 23 as printed, the thesis's measure, same N),
    max_lower_gap_in, circuit_open_s, n_events (no preload) and
    min_preload_lb; any other design field overridden by keyword;
    ``dt`` the stepper's step (default: the model's); ``progress(k)``
    is called as k more simulations finish (a bar);
    ``journal``: a :class:`~contactsep.runs.journal.RunJournal`
    that keeps every finished simulation and answers those it holds
    (``study NAME --resume``), or None."""
    from contactsep.errors import shown
    from contactsep.studies.preload.search_checks import SearchError, check_search
    if name not in STUDIES:
        raise SearchError(f"name: found {shown(name)}, expected one of "
                          f"{', '.join(STUDIES)}")
    check_search(name, model, MODELS, n_modes, workers, overrides, False)
    own, why, claim = STUDIES[name]
    refuse_fixed(name, overrides, {own: why})
    base = thesis_study_design(n_modes=n_modes, **overrides)
    values = _values(name, base)
    designs = [base.replace(**{own: float(v)}) for v in values]
    single = _single_impulse(base, own, values, designs)
    settings = {"damping": "flores"} if (
        name == "conclusion3" and model == "hertz") else {}
    # the thesis rig's converged step and the listing's window, given
    settings["dt"] = DEFAULT_DT[model] if dt is None else dt
    settings["t_end"] = LISTING_TAU_S
    with Simulations(workers, progress=progress,
                     journal=journal) as sims:
        free = sims.map(_zero_preload, [FreeRun(d, model, settings)
                                        for d in designs])
        found = min_preloads(designs, model, settings, simulations=sims)
    gap, open_s, events = (np.array(v) for v in zip(*free))
    law = {"hertz": "Hertz contact" + (", Flores damping calibrated to e"
                                       if "damping" in settings
                                       else ", elastic"),
           "newton": "Newton's impact law with e"}[model]
    notes = [f"the thesis (conclusion {name[-1]}): {claim}",
             f"y3_max_in: eq. 23 as printed, N = {n_modes}; the rest: the "
             f"three beams, {law}, N = {n_modes}, the adaptive stepper at "
             f"dt {dt or DEFAULT_DT[model]:g} s, window 0-0.06 s from the "
             f"release",
             "max_lower_gap_in, circuit_open_s, n_events: no preload; "
             "min_preload_lb: the smallest tested preload above which no "
             "tested preload has an event (opening >= 1e-05 s), the "
             "preload chart's search",
             f"{sims.runs} simulations",
             *(note for v, result in zip(values, found)
               for note in limit_notes(f"{column_name(own)} = {v:g}",
                                       result)),
             *design_lines(designs[0], per_row=(own,))]
    return Study(name, f"Conclusion {name[-1]} re-examined for circuit "
                 f"opening ({model}, N = {n_modes})", {
                     **_columns(name, values, single, base),
                     "y3_max_in": single.y3_max,
                     "max_lower_gap_in": gap, "circuit_open_s": open_s,
                     "n_events": events.astype(np.int64),
                     "min_preload_lb": np.array(
                         [r.min_preload_lb for r in found])},
                 tuple(notes))
