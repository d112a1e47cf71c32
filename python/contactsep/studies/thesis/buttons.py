"""The thesis's recommendation 1, the contact button (``contactsep study
buttons``; docs/circuit-opening.md, "The contact button"): "perhaps a contact
button, other than the hemispherical shape, would be advantageous from
an impact standpoint".

On the thesis rig (y_s = 0.5 in, d = 0.25 in) both contacts carry the
same button: a sphere of radius R on a flat (Hertz, k = (4/3) E* sqrt(R),
lb/in^1.5) or a cylinder of radius R across it, as long as its diameter
(a line contact, F = (pi/4) E* L delta, L = 2R: k in lb/in).  For each
shape and radius the study reports, with the elastic law:

* ``circuit_open_s``, ``n_events``: with no preload;
* ``min_preload_lb``: the smallest lower-contact preload with no
  discontinuity event in the window (the preload chart's search,
  contactsep.studies.preload.chart).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep.chatter import simulate
from contactsep.constants import LISTING_TAU_S
from contactsep.model.fields import design_lines
from contactsep.studies.preload.chart import Simulations, limit_notes, min_preloads
from contactsep.studies.study import Study, StudyRun, thesis_study_design

#: The shapes and radii (in) of the study.
SHAPES = ("sphere", "cylinder")
RADII = (0.0625, 0.125, 0.25)
#: Modes per member (a modest N: the study runs about 20 simulations a
#: row) and the window (s, the listing's).
MODES = 8


@dataclass(frozen=True)
class ButtonRun(StudyRun):
    """One simulation of the study's design with no preload, its button
    in ``settings`` (further keywords of ``simulate()``)."""

    design: object
    settings: dict


def _zero_preload(task: ButtonRun):
    """One simulation with no preload (runs in a worker)."""
    r = simulate(task.design, samples=1, single_impulse=False,
                 **task.settings)
    return r.circuit_open_s, r.n_events


def buttons(n_modes: int = MODES, radii=RADII, shapes=SHAPES, *,
            workers=None, progress=None, journal=None) -> Study:
    """Open time and smallest preload against the button's shape and
    radius (module docstring); ``progress(k)`` is called as k more
    simulations finish;
    ``journal``: a :class:`~contactsep.runs.journal.RunJournal`
    that keeps every finished simulation and answers those it holds
    (``study NAME --resume``), or None."""
    for shape in shapes:
        if shape not in SHAPES:
            raise ValueError(f"shapes: found {shape!r}, expected "
                             f"{', '.join(SHAPES)}")
    design = thesis_study_design(n_modes=n_modes)
    rows = [(shape, float(radius)) for shape in shapes for radius in radii]
    settings = [{"button": shape, "button_radius": radius,
                 "t_end": LISTING_TAU_S} for shape, radius in rows]
    with Simulations(workers, progress=progress,
                     journal=journal) as sims:
        free = sims.map(_zero_preload, [ButtonRun(design, s)
                                        for s in settings])
        found = [min_preloads([design], "hertz", s, simulations=sims)[0]
                 for s in settings]
    open_s, events = (np.array(v) for v in zip(*free))
    notes = ["the thesis (recommendation 1): a button other than the "
             "hemispherical shape might be advantageous",
             "sphere: Hertz k = (4/3) E* sqrt(R); cylinder: a line contact "
             "F = (pi/4) E* L delta, L = 2R; E* = E1 / (2 (1 - nu^2)), "
             "nu = 0.33; both contacts the same button",
             f"the three beams, elastic Hertz family, static correction, "
             f"N = {n_modes}, the design's own step, window 0-"
             f"{LISTING_TAU_S:g} s from the release",
             "circuit_open_s, n_events: no preload; min_preload_lb: the "
             "smallest tested preload above which no tested preload has "
             "an event (opening >= 1e-05 s), the preload chart's search",
             f"{sims.runs} simulations",
             *(note for (shape, radius), result in zip(rows, found)
               for note in limit_notes(f"{shape} R = {radius:g} in",
                                       result)),
             *design_lines(design)]
    return Study("buttons", f"Recommendation 1: the contact button's "
                 f"shape and radius (hertz, N = {n_modes})", {
                     "button": np.array([shape for shape, _ in rows]),
                     "button_radius_in": np.array([r for _, r in rows]),
                     "circuit_open_s": open_s,
                     "n_events": events.astype(np.int64),
                     "min_preload_lb": np.array(
                         [r.min_preload_lb for r in found])},
                 tuple(notes))


def draw(axes, study: Study) -> None:
    """Open time (top) and smallest preload (bottom) against the radius,
    one line per shape."""
    c = study.columns
    top, bottom = axes
    for i, shape in enumerate(dict.fromkeys(c["button"])):
        mine = c["button"] == shape
        top.semilogx(c["button_radius_in"][mine], c["circuit_open_s"][mine]
                     * 1e3, "o-", color=f"C{i}", label=shape)
        bottom.semilogx(c["button_radius_in"][mine],
                        c["min_preload_lb"][mine], "s-", color=f"C{i}",
                        label=shape)
    top.set(ylabel="circuit open, no preload (ms)")
    bottom.set(xlabel="button radius R (in)",
               ylabel="smallest preload (lb)")
