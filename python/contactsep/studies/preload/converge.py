"""The preload chart converged row by row (``contactsep study preload
--converge``; issue 25, docs/preload-family.md "Convergence of the answer").

A row's answer at N modes and step dt is **converged to 2 %** when, at
2N and dt/2, a preload 2 % above it has no discontinuity event and one
within 2 % below it has an event: the threshold at 2N, dt/2 then lies
within 2 % of the answer, unless a window of events lies further above
it at 2N (the check tries 2 % either side only, not the search's fine
band to twice the answer: becu_light's answer held its check at
N = 128 and a whole search there found a window 3.6 % above it,
docs/preload-family.md "The preload command on the family").  The
preload 2 % below is tried first; where it is closed (a closed window
of the rattle, or an answer that moved down), every 0.25 % between it
and the answer.

A row that fails is searched again at 2N, dt/2 (the chart's whole
search, :func:`contactsep.studies.preload.chart.min_preloads`) and its new
answer checked the same way at 4N, dt/4; up to :data:`MAX_MODES`.  A
row is only searched again at an N whose own check fits under
MAX_MODES, so a row that fails its last possible check keeps its
answer, marked not converged.  Convergence in N at a halved step:
the chart's step (5e-8 s) is converged in dt on the thesis rig (the
same answer to 4 digits at 2.5e-8 s), and halving it with N keeps the
check a check of both.  Where a window is long for its N (a design's
own window, ``t_end``), a halved step can exceed the simulation's work
budget; the check then runs at the finest step the budget takes, as
long as that is at most LEAST_REFINEMENT of the last step (still a
check of both), and the checks stop where it is not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contactsep.chatter.stack import smallest_dt
from contactsep.errors import InputError
from contactsep.studies.preload.runs import PreloadRun

#: How close the threshold at 2N, dt/2 must lie to a converged answer.
MARGIN = 0.02
#: The largest N a check runs at (a search runs at most at half of it).
MAX_MODES = 128
#: A check's step where half the last one exceeds the simulation's work
#: budget: the smallest step the budget takes, if at most this fraction of
#: the last step (still a refinement in dt as well as in N).
LEAST_REFINEMENT = 0.75
#: Room left below the budget's smallest step for the window's own
#: dependence on N (the first impact moves by parts per million with N).
WINDOW_ROOM = 1.01
#: Where the preload MARGIN below is closed: the factors between it and
#: the answer (every MARGIN / 8).
BETWEEN = tuple(1.0 - MARGIN * k / 8 for k in range(1, 8))


def largest_check(converge, n_modes: int) -> int | None:
    """The largest N of a check ``converge`` asks for (None: no
    convergence), or an InputError in one line: True (MAX_MODES), False,
    or an integer from 2 ``n_modes`` to 1024."""
    if converge is False or converge is None:
        return None
    if converge is True:
        return max(MAX_MODES, 2 * int(n_modes))
    if isinstance(converge, (bool, np.bool_)) or not isinstance(
            converge, (int, np.integer)) or not (
            2 * int(n_modes) <= converge <= 1024):
        raise InputError(f"converge: found {converge!r}, expected True, "
                         f"False or the largest N of a check (an integer "
                         f"from 2N = {2 * int(n_modes)} to 1024)")
    return int(converge)


def refined_step(n_modes: int, dt: float, t_end: float | None = None
                 ) -> float | None:
    """The step (s) of a check at N = ``n_modes`` after a run at ``dt``:
    dt / 2; where the simulation's work budget over the window ``t_end``
    (s; None: no budget, as on the chart's fixed window) refuses that,
    the smallest step it takes, if at most LEAST_REFINEMENT dt; None
    where not even that is a refinement."""
    half = dt / 2.0
    if t_end is None:
        return half
    least = smallest_dt(int(n_modes), t_end) * WINDOW_ROOM
    if half >= least:
        return half
    return least if least <= LEAST_REFINEMENT * dt else None


def reachable(n_modes: int, dt: float, t_end: float | None,
              max_modes: int) -> int:
    """The largest N, doubling from ``n_modes`` at ``dt`` (the step
    refined with each doubling, :func:`refined_step`), up to
    ``max_modes``, that a check can run at."""
    n, step = int(n_modes), dt
    while 2 * n <= max_modes:
        step = refined_step(2 * n, step, t_end)
        if step is None:
            break
        n *= 2
    return n


@dataclass(frozen=True)
class RowAnswer:
    """One row's answer and its check."""

    #: The answer (lb; NaN: none below the simulation's limit), the N
    #: and the step (s) it was found at.
    min_preload_lb: float
    n_modes: int
    dt_s: float
    #: The N of its last check (0: none) and whether it held.
    check_n_modes: int
    converged: bool
    #: ((N, answer lb), ...) of every search of the row, coarsest first.
    history: tuple
    #: The row's last search again (a PreloadSearch), None if none.
    search: object = None


def window_answer(answer: float, tested) -> float | None:
    """Where ``answer`` holds to MARGIN on the preloads ``tested``
    ((preload lb, has an event) at the finer N and step): of those
    within MARGIN either side of it, one has an event and one above
    the highest such has none (the threshold there lies between them,
    within MARGIN of the answer).  Then the answer restricted to that
    window: the smallest of its tested preloads above its highest event
    (within MARGIN of ``answer`` by construction); None where it does
    not hold.  The one test of a check, the chart's and the preload
    command's."""
    lo = answer * (1.0 - MARGIN) * (1.0 - 1e-12)
    hi = answer * (1.0 + MARGIN) * (1.0 + 1e-12)
    inside = [(p, bool(e)) for p, e in tested if lo <= p <= hi]
    events = [p for p, e in inside if e]
    if not events:
        return None
    above = [p for p, _ in inside if p > max(events)]
    return min(above) if above else None


def brackets_hold(designs, answers, model, settings, sims) -> list[bool]:
    """Whether each answer holds to MARGIN on its design (at the N and
    step the designs and settings carry; :func:`window_answer`) on the
    preloads MARGIN above and below it, and, where the one below is
    closed, every MARGIN / 8 between."""
    tasks = [PreloadRun(design, model, settings, answer * factor)
             for design, answer in zip(designs, answers)
             for factor in (1.0 - MARGIN, 1.0 + MARGIN)]
    found = sims.events(tasks)
    tested = [[(t.preload_lb, e) for t, e in zip(tasks[2 * i:2 * i + 2],
                                                 found[2 * i:2 * i + 2])]
              for i in range(len(designs))]
    closed = [i for i in range(len(designs)) if not found[2 * i]]
    between = [PreloadRun(designs[i], model, settings, answers[i] * f)
               for i in closed for f in BETWEEN]
    for j, (task, event) in enumerate(zip(between, sims.events(between))):
        tested[closed[j // len(BETWEEN)]].append((task.preload_lb, event))
    return [window_answer(a, t) is not None
            for a, t in zip(answers, tested)]


def converge_rows(make_designs, answers, n_modes, dt, model, settings,
                  sims, max_modes=MAX_MODES, *, search_again,
                  t_end=None) -> list[RowAnswer]:
    """Each row's answer checked at twice its N and half its step, and
    searched again there where the check fails (module docstring).
    With ``t_end`` (s, the window) a check whose half step the work
    budget refuses runs at the smallest step it takes where that is
    still a refinement (:func:`refined_step`), and the checks stop where
    none is.

    ``make_designs(n, rows)`` gives the designs of the rows (indices) at
    N = n; ``answers`` the chart's at ``n_modes`` and ``dt``;
    ``settings`` simulate()'s keywords but dt; ``sims`` an open
    :class:`~contactsep.studies.preload.chart.Simulations`; ``search_again``
    the chart's search (:func:`contactsep.studies.preload.chart.min_preloads`,
    given by the caller: this module sits beside it, not under it)."""
    state = [{"answer": float(a), "n": int(n_modes), "dt": float(dt),
              "check": 0, "held": False, "search": None,
              "history": ((int(n_modes), float(a)),)} for a in answers]
    pending = [i for i, a in enumerate(answers) if math.isfinite(a)]
    n, step = int(n_modes), float(dt)
    last = reachable(n, step, t_end, max_modes)
    while pending and 2 * n <= last:
        n, step = 2 * n, refined_step(2 * n, step, t_end)
        finer = {**settings, "dt": step}
        designs = make_designs(n, pending)
        held = brackets_hold(designs, [state[i]["answer"] for i in pending],
                             model, finer, sims)
        failing = []
        for i, design, ok in zip(pending, designs, held):
            state[i]["check"], state[i]["held"] = n, ok
            if not ok:
                failing.append((i, design))
        # search again only where the new answer can itself be checked
        if not failing or 2 * n > last:
            break
        found = search_again([design for _, design in failing], model,
                             finer, simulations=sims)
        pending = []
        for (i, _), result in zip(failing, found):
            row = state[i]
            row["answer"] = float(result.min_preload_lb)
            row["n"], row["dt"], row["search"] = n, step, result
            row["check"], row["held"] = 0, False
            row["history"] += ((n, row["answer"]),)
            if math.isfinite(row["answer"]):
                pending.append(i)
    return [RowAnswer(min_preload_lb=s["answer"], n_modes=s["n"],
                      dt_s=s["dt"], check_n_modes=s["check"],
                      converged=s["held"], history=s["history"],
                      search=s["search"])
            for s in state]


def chart_columns(rows, make_designs, found, n_modes, dt, model, settings,
                  sims, max_modes=MAX_MODES, *, search_again):
    """The chart's converged columns and notes: ``rows`` its (d, y_s),
    ``found`` its searches at ``n_modes`` and ``dt``; returns
    (columns, notes, answers) for :func:`~contactsep.studies.preload.chart.
    preload_chart` (answers: the RowAnswers, whose ``search`` is a
    row's search again)."""
    answers = converge_rows(make_designs, [r.min_preload_lb for r in found],
                            n_modes, dt, model, settings, sims, max_modes,
                            search_again=search_again)
    columns = {
        "n_modes": np.array([a.n_modes for a in answers]),
        "dt_s": np.array([a.dt_s for a in answers]),
        "min_preload_lb": np.array([a.min_preload_lb for a in answers]),
        "check_n_modes": np.array([a.check_n_modes for a in answers]),
        "converged": np.array([int(a.converged) for a in answers])}
    notes = [f"converged: each answer checked at twice its N and half its "
             f"step, no event {MARGIN:.0%} above it and one within "
             f"{MARGIN:.0%} below (converged 1); a row that fails is "
             f"searched again there, up to checks at N = {max_modes}"]
    for (d, ys), a in zip(rows, answers):
        if len(a.history) > 1:
            steps = ", ".join(f"{p:.4g} lb at N = {n}" for n, p in a.history)
            notes.append(f"d = {d:g} in, y_s = {ys:g} in: searched again: "
                         f"{steps}")
        if math.isfinite(a.min_preload_lb) and not a.converged:
            notes.append(f"d = {d:g} in, y_s = {ys:g} in: not converged to "
                         f"{MARGIN:.0%} (its check at N = "
                         f"{a.check_n_modes} failed)")
    return columns, notes, answers
