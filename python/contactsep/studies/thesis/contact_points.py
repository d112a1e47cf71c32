"""The thesis's recommendation 3 (``contactsep study contact-points``):
displace the contact points along the separator.  The upper contact
strikes the separator at x2, the lower contact touches it at x2_lower
(Design.x2_lower; docs/circuit-opening.md, "Contact points and
materials"); the study simulates the three beams on a grid of both
positions and reports how the circuit opens.

Every row is one simulation of the thesis rig (y_s = 0.5 in): Hertz
contact (elastic, the static correction), N = :data:`MODES` per member,
the adaptive stepper at dt = :data:`DT` s, window 0-0.06 s from the
release, events = openings of at least 1e-05 s; each position twice,
the lower contact touching the separator with no preload (as in the
thesis) and pressed against it by :data:`PRELOAD` lb (a third of the
rig's smallest preload without events at mid-span, 18 lb: the circuit
then opens for a few ms, and how long tells the positions apart; with
no preload it opens for ~35 ms at every position).  Columns:
``preload_lb``, ``x2_in``, ``x2_lower_in``, ``circuit_open_s`` (total
open time), ``n_events``, ``longest_open_s``, ``max_lower_gap_in`` (the
largest lower gap).

The smallest preload with no event (the preload chart's search) costs
about 130 simulations a design (50 s of one core on the thesis rig at
N = 16); ``min_preload=True`` adds it as ``min_preload_lb`` (Python
only), off by default to keep the study to its 50 simulations.

On the clamped-clamped (symmetric) separator the grid is its own mirror:
(a, b) and (L2 - a, L2 - b) are the same system (tests/chatter/
test_contact_points.py), so the table is symmetric about its centre,
a check of the run.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep.chatter import simulate
from contactsep.constants import LISTING_TAU_S
from contactsep.model.fields import design_lines
from contactsep.studies.preload.chart import Simulations, limit_notes, min_preloads
from contactsep.studies.study import Study, StudyRun, refuse_fixed, thesis_study_design

#: The positions of both contacts on the separator, as x / L2.
RATIOS = (0.2, 0.35, 0.5, 0.65, 0.8)
#: Modes per member and step (the thesis rig's converged Hertz step:
#: docs/convergence.md; N = 32 against 64: the gaps within
#: 0.3 %, the open times without preload 0.05 %, with it 12 %).
MODES = 32
DT = 5e-8
#: The preload (lb) of the second set of rows (module docstring).
PRELOAD = 6.0
#: The fields the study sets itself.
FIXED = {"x2": "its rows, x2/L2 = 0.2-0.8",
         "x2_lower": "its columns, x2_lower/L2 = 0.2-0.8"}


@dataclass(frozen=True)
class OpeningRun(StudyRun):
    """One simulation of the study: ``design`` under ``preload_lb`` (lb),
    ``settings`` further keywords of ``simulate()``; its cost (the
    batch's order, costliest first) its preload."""

    design: object
    preload_lb: float
    settings: dict


def _opening(task: OpeningRun):
    """One simulation (runs in a worker)."""
    r = simulate(task.design, preload=task.preload_lb, samples=1,
                 single_impulse=False, **task.settings)
    return (r.circuit_open_s, r.n_events, r.longest_open_s,
            r.max_lower_gap_in)


def contact_points(*, n_modes: int = MODES, dt: float = DT,
                   ratios=RATIOS, preloads=(0.0, PRELOAD),
                   min_preload: bool = False, workers=None, progress=None,
                   journal=None, **overrides) -> Study:
    """Opening of the circuit against where each contact touches the
    separator (module docstring): one row per preload and (x2, x2_lower)
    of the grid ``ratios`` x ``ratios`` (fractions of L2); any other
    design field overridden by keyword; ``min_preload`` adds the preload
    search's answer (slow); ``progress(k)`` is called as k more
    simulations finish (a bar);
    ``journal``: a :class:`~contactsep.runs.journal.RunJournal`
    that keeps every finished simulation and answers those it holds
    (``study NAME --resume``), or None.

    Returns
    -------
    Study
        Columns preload_lb, x2_in, x2_lower_in, circuit_open_s,
        n_events, longest_open_s, max_lower_gap_in (and min_preload_lb,
        the same for both preloads' rows).
    """
    from contactsep.studies.preload.search_checks import (
        check_modes,
        check_values,
        check_workers,
    )
    check_modes(n_modes)
    check_workers(workers)
    ratios = check_values("ratios", ratios, "fractions of L2")
    preloads = check_values("preloads", preloads, "lb")
    refuse_fixed("contact-points", overrides, FIXED)
    base = thesis_study_design(n_modes=n_modes, **overrides)
    length = float(base.L2)
    pairs = [(a * length, b * length) for a in ratios for b in ratios]
    designs = [base.replace(x2=a, x2_lower=b) for a, b in pairs]
    settings = {"dt": dt, "t_end": LISTING_TAU_S}
    with Simulations(workers, progress=progress,
                     journal=journal) as sims:
        # the preloaded runs first (their cost)
        rows = sims.map(_opening, [OpeningRun(d, p, settings)
                                   for p in preloads for d in designs])
        found = min_preloads(designs, "hertz", settings, simulations=sims) \
            if min_preload else []
    open_s, events, longest, gap = (np.array(v, dtype=float)
                                    for v in zip(*rows))
    count = len(preloads)
    columns = {"preload_lb": np.repeat(preloads, len(pairs)),
               "x2_in": np.tile([a for a, _ in pairs], count),
               "x2_lower_in": np.tile([b for _, b in pairs], count),
               "circuit_open_s": open_s,
               "n_events": events.astype(np.int64),
               "longest_open_s": longest, "max_lower_gap_in": gap}
    if min_preload:
        columns["min_preload_lb"] = np.tile([r.min_preload_lb
                                             for r in found], count)
    notes = ["the thesis (recommendation 3): displace the contact points "
             "along the separator; x2: where the upper contact strikes it, "
             "x2_lower: where the lower contact touches it",
             f"three beams, Hertz contact (elastic, static correction), "
             f"N = {n_modes}, the adaptive stepper at dt {dt:g} s, window "
             f"0-{LISTING_TAU_S:g} s from the release; an event is an "
             f"opening >= 1e-05 s; preload_lb: the lower contact pressed "
             f"against the separator at the start",
             f"{sims.runs} simulations",
             *(note for (a, b), r in zip(pairs, found)
               for note in limit_notes(f"x2 = {a:g} in, x2_lower = {b:g} "
                                       f"in", r)),
             *design_lines(designs[0], per_row=("x2", "x2_lower"))]
    return Study("contact-points", f"Recommendation 3: circuit opening "
                 f"against the contact points on the separator (hertz, "
                 f"N = {n_modes})", columns, tuple(notes))


def draw(axes, study: Study) -> None:
    """Two maps over (x2, x2_lower): the largest lower gap with no
    preload and the total open time at the largest preload (``axes``
    two matplotlib axes)."""
    c = study.columns
    preload = np.asarray(c["preload_lb"])
    panels = ((axes[0], preload == preload.min(), "max_lower_gap_in", 1e3,
               f"max lower gap (0.001 in), {preload.min():g} lb"),
              (axes[1], preload == preload.max(), "circuit_open_s", 1e3,
               f"circuit open (ms), {preload.max():g} lb"))
    for ax, rows, key, scale, label in panels:
        xs = np.unique(c["x2_in"][rows])
        ys = np.unique(c["x2_lower_in"][rows])
        values = np.asarray(c[key][rows], dtype=float).reshape(
            xs.size, ys.size) * scale
        half_x = (xs[1] - xs[0]) / 2 if xs.size > 1 else 0.5
        half_y = (ys[1] - ys[0]) / 2 if ys.size > 1 else 0.5
        image = ax.imshow(values.T, origin="lower", aspect="auto",
                          cmap="viridis", extent=(
                              xs[0] - half_x, xs[-1] + half_x,
                              ys[0] - half_y, ys[-1] + half_y))
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                ax.text(x, y, f"{values[i, j]:.3g}", ha="center",
                        va="center", fontsize=6, color="w")
        ax.figure.colorbar(image, ax=ax, label=label)
        ax.set(ylabel="x2_lower, lower contact (in)")
    axes[1].set(xlabel="x2, where the upper contact strikes (in)")
