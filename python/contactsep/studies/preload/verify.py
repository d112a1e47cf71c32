"""The preload command's error estimate (``min_preload_change``): the
answer at N checked at twice the modes and half the step around it, and
searched again there only where that check fails (docs/preload.md,
"The preload command").

The check is the convergence check's (:func:`contactsep.studies.
preload_converge.window_answer`): at 2N, dt/2, every preload of the
fine grid (FINE_RATIO^j lb) within MARGIN (2 %) either side of the
answer, in one batch, four or five runs.  Where one of them has an
event and one above the highest such has none, the threshold at 2N,
dt/2 lies in that window, and the answer at 2N
restricted to it (the smallest of those preloads above their highest
event) is ``verify_min_preload_lb``: ``min_preload_change`` is then
within 2 % by construction, resolved to the fine grid's 0.99 %.  A
window of events further above the answer at 2N is not seen by it, as
the convergence check does not see one (the whole search at 2N looked
to 2 times its answer).  Where the check fails (the threshold moved
more than about 2 %, or the answer is none or 0), the whole search at
2N, dt/2, as before: its answer and change are the whole search's.
"""

from __future__ import annotations

import dataclasses
import math

from contactsep.chatter.stack import largest_preload
from contactsep.studies.preload.converge import MARGIN, window_answer
from contactsep.studies.preload.runs import PreloadRun
from contactsep.studies.preload.scan import PER_OCTAVE, grid
from contactsep.studies.preload.search import (
    TOLERANCE,
    PreloadSearch,
    fine_band,
    fine_grid,
    search,
)


def window_preloads(answer: float) -> list:
    """The fine grid's preloads within MARGIN either side of ``answer``
    lb."""
    return fine_grid(answer * (1.0 - MARGIN), answer * (1.0 + MARGIN))


def expected_runs(verify: bool = True) -> int:
    """About how many simulations one design's search takes (a progress
    bar's first total): the ceiling, three octaves of scan, bisection
    from a grid step to TOLERANCE, the fine band from BAND_LOW and, with
    ``verify``, the check within 2 % at 2N."""
    bisection = math.ceil(math.log2(math.log(grid(1)) /
                                    math.log1p(TOLERANCE)))
    band = len(fine_band(1.0))
    check = len(window_preloads(1.0)) if verify else 0
    return 1 + 3 * PER_OCTAVE + bisection + band + check


def verify_search(has_event, answer: float, ceiling: float,
                  search_whole) -> tuple[PreloadSearch, bool]:
    """(the search at 2N, dt/2, whether it is the local check) for the
    answer ``answer`` lb at N.  ``has_event(preloads)``: whether each
    preload has an event at 2N, dt/2 (one batch); ``ceiling``: the
    largest preload that design takes; ``search_whole(known)``: the whole
    search there, given the runs already made (preload lb -> has an
    event), which it takes instead of running them again."""
    preloads = window_preloads(answer) if (
        math.isfinite(answer) and answer > 0.0) else []
    # a window cut by the ceiling cannot show that 2 % above is closed
    if not preloads or answer * (1.0 + MARGIN) > ceiling:
        return search_whole({}), False
    tested = tuple(zip(preloads, (bool(e) for e in has_event(preloads))))
    local = window_answer(answer, tested)
    if local is None:
        # its runs reported with the whole search's (each run once)
        whole = search_whole(dict(tested))
        runs = dict(tested) | dict(whole.tested)
        return dataclasses.replace(whole, tested=tuple(sorted(
            runs.items()))), False
    return PreloadSearch(min_preload_lb=local, tested=tested,
                         ceiling_lb=ceiling), True


def search_design(design, model, settings, sims, ceiling, start=None,
                  band_below=False, known=None) -> PreloadSearch:
    """``contactsep preload``'s search on one design (the ceiling first;
    the band below only where the scan is not monotone, or
    ``band_below``), simulated on ``sims``; ``known`` (preload lb -> has
    an event): runs already made, answered from there."""
    known = known or {}

    def has_event(tasks):
        missing = [load for _, load in tasks if load not in known]
        found = dict(zip(missing, sims.events(
            [PreloadRun(design, model, settings, load)
             for load in missing])))
        return [known[load] if load in known else found[load]
                for _, load in tasks]

    def speculate(asked, tasks):
        sims.events_ahead([PreloadRun(design, model, settings, load)
                           for _, load in tasks if load not in known],
                          asked)

    found, = search(1, has_event, ceilings=[ceiling],
                    starts=[start if start is not None and
                            math.isfinite(start) else None],
                    band_below=band_below, ceiling_first=True,
                    speculate=speculate)
    return found


def verify_design(finer, model, settings, sims, answer, band_below):
    """(the search at 2N, dt/2 on the design ``finer``, whether it is
    the check 2 % either side of ``answer``): :func:`verify_search`."""
    sims.search = "verify"
    ceiling = largest_preload(finer)
    return verify_search(
        lambda loads: sims.events([PreloadRun(finer, model, settings, load)
                                   for load in loads]),
        answer, ceiling,
        lambda known: search_design(finer, model, settings, sims,
                                    ceiling, start=answer,
                                    band_below=band_below, known=known))
